/*
 * host_tests/loc_walk.c - see loc_walk.h.
 */
#include "loc_walk.h"
#include "test.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void *t_loc_walk(const char *loc_name, const char *walk, int32_t seed, uint32_t steps,
                 bool (*valid)(const void *state), t_loc_walk_t *out)
{
    return t_loc_walk_vision(loc_name, walk, seed, steps, SIM_VISION_LTX, valid, out, NULL);
}

void *t_loc_walk_vision(const char *loc_name, const char *walk, int32_t seed, uint32_t steps,
                        int vision, bool (*valid)(const void *state), t_loc_walk_t *out,
                        uint32_t *kinds_seen)
{
    char path[256], err[256];
    static sim_scenario_t sc;
    static sim_t sim;
    static sim_step_t st;
    const fl_localizer_t *loc = fl_localizer_find(loc_name);
    void *pp, *s;
    double se = 0;
    memset(out, 0, sizeof *out);
    out->hash = t_hash_init();
    if (loc == NULL) {
        t_fail_msg(__FILE__, __LINE__, "no localizer %s", loc_name);
        return NULL;
    }
    pp = malloc(loc->params_size);
    s = malloc(loc->state_size);
    if (pp == NULL || s == NULL) {
        free(pp);
        free(s);
        t_fail_msg(__FILE__, __LINE__, "out of memory");
        return NULL;
    }
    snprintf(path, sizeof path, "fixtures/walks/%s.walk", walk);
    loc->params_default(pp);
    fl_localizer_param_set(loc, pp, "seed", seed);
    if (sim_scenario_load(&sc, path, err, sizeof err) != 0 || sim_init(&sim, &sc) != 0 ||
        fl_loc_init(loc, s, sc.field, pp) != FL_OK) {
        t_fail_msg(__FILE__, __LINE__, "%s: %s", path, err);
        free(pp);
        free(s);
        return NULL;
    }
    free(pp);
    sim.sc.white_points = loc->reads_points;   /* costly; only relmap reads them */
    sim.sc.vision = vision;
    loc->set_prior_half(s, sc.start_x_mm < 0 ? -1 : 1);
    while (out->steps < steps && sim_step(&sim, &st)) {
        fl_loc_estimate_t e;
        fl_loc_predict(loc, s, st.odo_dx_mm, st.odo_dy_mm, st.odo_dtheta);
        if (st.events & SIM_EV_PENALIZED)
            loc->reset_penalty(s, (int32_t)sc.penalty_x_mm, 300, 2730);
        out->obs_used += fl_loc_update(loc, s, &st.obs, NULL);
        if (kinds_seen != NULL) {
            uint16_t k;
            for (k = 0; k < st.obs.n; k++)
                if ((int)st.obs.obs[k].kind >= 0 && st.obs.obs[k].kind < FL_LM_KIND_COUNT)
                    kinds_seen[st.obs.obs[k].kind]++;
        }
        CHECK(fl_loc_estimate(loc, s, &e));
        out->hash = t_hash_i32(out->hash, e.x_mm);
        out->hash = t_hash_i32(out->hash, e.y_mm);
        out->hash = t_hash_i32(out->hash, e.heading);
        if (st.t_ms >= 5000) {
            double dx = e.x_mm - st.x_mm, dy = e.y_mm - st.y_mm;
            se += dx * dx + dy * dy;
        }
        if (valid != NULL && (out->steps & 63u) == 0u)
            CHECK(fl_loc_check(loc, s) && valid(s));
        out->steps++;
    }
    CHECK(fl_loc_check(loc, s));
    if (valid != NULL)
        CHECK(valid(s));
    out->rmse_mm = sqrt(se / (out->steps > 150 ? out->steps - 150 : 1));
    return s;
}
