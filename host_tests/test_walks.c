/*
 * host_tests/test_walks.c - determinism of the localizer over the committed
 * walk fixtures: each walk of fixtures/walks/ is replayed at the
 * feature level (simulator observations and odometry -> fuzzy grid, penalty
 * placements told as the rules do), and the integer estimate of every step
 * is hashed; so is every other localizer of the catalogue, through the
 * localizer interface (lines "LOCALIZER:WALK").  The hash is compared with fixtures/golden/walks.txt and, by
 * `make cross-test`, across x86-64, i686, mipsel and mips.  Quick mode (qemu)
 * replays the first 300 steps of each walk and prints its own digest.
 * `FIELDLOC_WRITE_GOLDEN=1 build/run_tests -k walks` (make golden) rewrites
 * the golden file.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N_WALKS 4
static const char *walk_names[N_WALKS] = {"spl2013", "uva2013", "aibo2004", "spl2020"};

static uint32_t replay(const char *name, uint32_t max_steps, uint32_t *steps, double *err_mm)
{
    char path[256], err[256];
    sim_scenario_t sc;
    static sim_t sim;
    static sim_step_t st;
    fl_fuzzy_t *g = malloc(sizeof *g);
    uint32_t h = t_hash_init(), n = 0;
    double se = 0;
    *steps = 0;
    *err_mm = 0;
    if (!g)
        return 0;
    snprintf(path, sizeof path, "fixtures/walks/%s.walk", name);
    if (sim_scenario_load(&sc, path, err, sizeof err) != 0 || sim_init(&sim, &sc) != 0 ||
        fl_fuzzy_init(g, sc.field, NULL) != FL_OK) {
        t_fail_msg(__FILE__, __LINE__, "%s: %s", path, err);
        free(g);
        return 0;
    }
    while (n < max_steps && sim_step(&sim, &st)) {
        fl_fuzzy_estimate_t e;
        fl_fuzzy_predict(g, st.odo_dx_mm, st.odo_dy_mm, st.odo_dtheta);
        if (st.events & SIM_EV_PENALIZED)
            fl_fuzzy_reset_penalty(g, (int32_t)sc.penalty_x_mm, 200, 2048);
        fl_fuzzy_update(g, &st.obs);
        CHECK(fl_fuzzy_estimate(g, &e));
        CHECK(fl_fuzzy_check(g));
        h = t_hash_i32(h, e.x_mm);
        h = t_hash_i32(h, e.y_mm);
        h = t_hash_i32(h, e.heading);
        h = t_hash_i32(h, e.reliability_q16);
        {
            double dx = e.x_mm - st.x_mm, dy = e.y_mm - st.y_mm, d2 = dx * dx + dy * dy;
            if (sc.field->symmetric) {   /* modulo the 180-degree symmetry */
                double mx = e.x_mm + st.x_mm, my = e.y_mm + st.y_mm;
                if (mx * mx + my * my < d2)
                    d2 = mx * mx + my * my;
            }
            se += d2;
        }
        n++;
    }
    *steps = n;
    *err_mm = n ? sqrt(se / n) : 0;
    free(g);
    return h;
}

/* The same replay through the localizer interface, for the catalogue's
 * other localizers (the fuzzy grid is traced above through its own API):
 * defaults, random seed 1 where the localizer has one, the own-half prior
 * of kick-off, penalty placements told. */
static uint32_t replay_loc(const fl_localizer_t *loc, const char *name, uint32_t max_steps,
                           uint32_t *steps, double *err_mm)
{
    char path[256], err[256];
    sim_scenario_t sc;
    static sim_t sim;
    static sim_step_t st;
    void *state = malloc(loc->state_size), *params = malloc(loc->params_size);
    uint32_t h = t_hash_init(), n = 0;
    double se = 0;
    *steps = 0;
    *err_mm = 0;
    if (!state || !params) {
        free(state);
        free(params);
        return 0;
    }
    loc->params_default(params);
    if (fl_localizer_param_find(loc, "seed") != NULL)
        CHECK_EQ(fl_localizer_param_set(loc, params, "seed", 1), FL_OK);
    snprintf(path, sizeof path, "fixtures/walks/%s.walk", name);
    if (sim_scenario_load(&sc, path, err, sizeof err) != 0 || sim_init(&sim, &sc) != 0 ||
        fl_loc_init(loc, state, sc.field, params) != FL_OK) {
        t_fail_msg(__FILE__, __LINE__, "%s (%s): %s", path, loc->name, err);
        free(state);
        free(params);
        return 0;
    }
    sim.sc.white_points = loc->reads_points;   /* costly; only relmap reads them */
    loc->set_prior_half(state, sc.start_x_mm < 0 ? -1 : 1);
    while (n < max_steps && sim_step(&sim, &st)) {
        fl_loc_estimate_t e;
        loc->predict(state, st.odo_dx_mm, st.odo_dy_mm, st.odo_dtheta);
        if (st.events & SIM_EV_PENALIZED)
            loc->reset_penalty(state, (int32_t)sc.penalty_x_mm, 300, 2730);
        loc->update(state, &st.obs, NULL);
        CHECK(loc->estimate(state, &e));
        CHECK(loc->check(state));
        h = t_hash_i32(h, e.x_mm);
        h = t_hash_i32(h, e.y_mm);
        h = t_hash_i32(h, e.heading);
        h = t_hash_i32(h, e.reliability_q16);
        {
            double dx = e.x_mm - st.x_mm, dy = e.y_mm - st.y_mm, d2 = dx * dx + dy * dy;
            if (sc.field->symmetric) {   /* after the kidnap nothing tells the half */
                double mx = e.x_mm + st.x_mm, my = e.y_mm + st.y_mm;
                if (mx * mx + my * my < d2)
                    d2 = mx * mx + my * my;
            }
            se += d2;
        }
        n++;
    }
    *steps = n;
    *err_mm = n ? sqrt(se / n) : 0;
    free(state);
    free(params);
    return h;
}

/* golden: lines "NAME STEPS 0xHASH" */
static int golden_lookup(const char *name, uint32_t *steps, uint32_t *hash)
{
    FILE *f = fopen("fixtures/golden/walks.txt", "r");
    char line[256], n[64];
    unsigned long st, hs;
    int found = 0;
    if (!f)
        return 0;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "%63s %lu %lx", n, &st, &hs) == 3 && !strcmp(n, name)) {
            *steps = (uint32_t)st;
            *hash = (uint32_t)hs;
            found = 1;
        }
    fclose(f);
    return found;
}

static void test_walk_traces(void)
{
    const char *write = getenv("FIELDLOC_WRITE_GOLDEN");
    FILE *out = NULL;
    int i;
    if (write && *write && !t_quick) {
        out = fopen("fixtures/golden/walks.txt", "w");
        CHECK(out != NULL);
        if (out)
            fprintf(out, "# localizer trace digests of fixtures/walks (host_tests/test_walks.c)\n");
    }
    for (i = 0; i < N_WALKS * (int)fl_localizer_count(); i++) {
        const fl_localizer_t *loc = fl_localizer_get((uint16_t)(i / N_WALKS));
        uint32_t steps, h, gs = 0, gh = 0;
        double rms;
        char label[96], name[64];
        /* the fuzzy grid's lines keep their names; the others' are
         * "LOCALIZER:WALK" */
        if (i < N_WALKS) {
            CHECK(loc == &fl_localizer_fuzzy);
            snprintf(name, sizeof name, "%s", walk_names[i]);
            h = replay(walk_names[i], t_quick ? 300u : 1000000u, &steps, &rms);
        } else {
            snprintf(name, sizeof name, "%s:%s", loc->name, walk_names[i % N_WALKS]);
            h = replay_loc(loc, walk_names[i % N_WALKS], t_quick ? 300u : 1000000u, &steps, &rms);
        }
        CHECK(steps > 0);
        snprintf(label, sizeof label, "walks.%s.%s", name, t_quick ? "quick" : "full");
        t_digest(label, h);
        t_info("%s: %u steps, position rms error %.0f mm (feature level, whole walk incl. kidnap, modulo symmetry)",
               name, (unsigned)steps, rms);
        if (t_quick)
            continue;
        if (out) {
            fprintf(out, "%s %u 0x%08lx\n", name, (unsigned)steps, (unsigned long)h);
            continue;
        }
        CHECK(golden_lookup(name, &gs, &gh));
        CHECK_EQ(steps, gs);
        CHECK_EQ(h, gh);
    }
    if (out)
        fclose(out);
}

void suite_walks(void)
{
    t_run("walks.localizer_traces", test_walk_traces);
}
