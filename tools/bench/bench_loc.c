/*
 * tools/bench/bench_loc.c - every localizer of the catalogue
 * (fl_localizer_count / fl_localizer_get) on the same frame, through the
 * localizer interface only: one frame = predict (the step's odometry) +
 * update (a list of 5 observations, no view) + estimate.
 *
 * The frame: the built-in spl2013 walk (feature-level observations, 30 Hz)
 * run for 300 steps (10 s, prior own half, every step predict + update +
 * estimate) with the localizer's default parameters, then the next step's
 * odometry and the next K real observations of the walk (K = 5 here:
 * frames of that walk carry 3-6; false ones left out so that no
 * localizer's gating changes the work).  The state after the 300 steps is
 * saved; every repetition restores it (not timed) and times one frame.
 * States: tracking (as saved) and ignorance (reset_ignorance first, then
 * the same frame).  Vision: the localizer's vision preset
 * (lr_params_frames, as simulate --frames and demo use it) for the walk
 * and the frame, and the frame with a view (50 deg wide, 0.6-4 m deep
 * ahead: what a NAO camera sees; negative information where the
 * localizer has it; the walk itself runs without views).
 *
 * Rows (best of the repetitions, ns per frame): loc_NAME_frame_tracking,
 * loc_NAME_frame_ignorance and loc_NAME_frame_vision (tracking), with the fuzzy grid's row of the same run as
 * the peer (speedup = fuzzy / NAME: above 1, NAME is faster); for a
 * localizer whose belief is a set of samples also loc_NAME_particle_obs,
 * the update's time per particle per observation (update with 5 minus
 * update with 1 observation, over 4 x particles).  A "# loc NAME" line
 * gives state_size, parameters and sample count.
 *
 * Instruction counts: `fieldloc bench --loc-frames NAME --repeat N` runs
 * the same preparation and then N frames through bench_loc_frame, the
 * only function tools/bench/callgrind_loc.sh collects (so the walk before
 * is not counted, per frame = collected / N).
 */
#include "bench/bench.h"
#include "fieldloc/fieldloc.h"
#include "loc/locrun.h"
#include "world/sim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BL_WALK_STEPS 300

typedef struct {
    const fl_localizer_t *loc;
    void *saved, *work;
    int32_t dx, dy;
    fl_angle_t dth;
    fl_obs_list_t obs;
    fl_obs_view_t view;          /* valid only for the vision frame */
    uint16_t samples;
} bl_t;

static void bl_free(bl_t *b)
{
    free(b->saved);
    free(b->work);
    memset(b, 0, sizeof *b);
}

/* The state after the walk and the frame that follows (K observations);
 * params NULL: the localizer's defaults; vision: the frame has a view.
 * 0 on success. */
static int bl_prepare(bl_t *b, const fl_localizer_t *loc, const void *params, int k_obs,
                      int vision)
{
    sim_scenario_t sc;
    sim_t *sim = malloc(sizeof *sim);
    sim_step_t *st = malloc(sizeof *st);
    fl_loc_estimate_t est;
    int k, ok = 0;
    memset(b, 0, sizeof *b);
    b->loc = loc;
    b->saved = malloc(loc->state_size);
    b->work = malloc(loc->state_size);
    if (sim == NULL || st == NULL || b->saved == NULL || b->work == NULL ||
        sim_scenario_builtin(&sc, "spl2013") != 0 || sim_init(sim, &sc) != 0 ||
        fl_loc_init(loc, b->saved, sc.field, params) != FL_OK)
        goto done;
    if (loc->set_prior_half != NULL)
        loc->set_prior_half(b->saved, -1);
    for (k = 0; k < BL_WALK_STEPS && sim_step(sim, st); k++) {
        fl_loc_predict(loc, b->saved, st->odo_dx_mm, st->odo_dy_mm, st->odo_dtheta);
        fl_loc_update(loc, b->saved, &st->obs, NULL);
        fl_loc_estimate(loc, b->saved, &est);
    }
    fl_obs_list_clear(&b->obs);
    k = 0;
    while (b->obs.n < k_obs && sim_step(sim, st)) {
        int i;
        if (k++ == 0) {
            b->dx = st->odo_dx_mm;
            b->dy = st->odo_dy_mm;
            b->dth = st->odo_dtheta;
        }
        for (i = 0; i < st->obs.n && b->obs.n < k_obs; i++)
            if (st->obs_landmark[i] >= 0)
                b->obs.obs[b->obs.n++] = st->obs.obs[i];
    }
    b->view.valid = vision != 0;
    b->view.bearing_right = fl_angle_from_mdeg(-25000);
    b->view.bearing_left = fl_angle_from_mdeg(25000);
    b->view.near_mm = 600;
    b->view.far_mm = 4000;
    b->samples = loc->belief_samples != NULL ? loc->belief_samples(b->saved) : 0;
    ok = b->obs.n == k_obs;
done:
    free(sim);
    free(st);
    if (!ok)
        bl_free(b);
    return ok ? 0 : -1;
}

/* One frame on the work state: what callgrind_loc.sh collects.  Not
 * static, never inlined: callgrind finds it by name. */
__attribute__((noinline)) void bench_loc_frame(const fl_localizer_t *loc, void *state,
                                               int32_t dx, int32_t dy, fl_angle_t dth,
                                               const fl_obs_list_t *obs,
                                               const fl_obs_view_t *view, int pred_est)
{
    fl_loc_estimate_t est;
    if (pred_est)
        fl_loc_predict(loc, state, dx, dy, dth);
    fl_loc_update(loc, state, obs, view->valid ? view : NULL);
    if (pred_est)
        fl_loc_estimate(loc, state, &est);
}

/* Best of reps: restore, (reset to ignorance,) time one frame with the
 * first n observations (whole frame, or the update alone). */
static double bl_time(const bl_t *b, int reps, int ignorance, int n_obs, int whole)
{
    double best = 1e30;
    fl_obs_list_t obs = b->obs;
    int r;
    obs.n = (uint8_t)n_obs;
    for (r = 0; r < reps; r++) {
        double t0, t;
        memcpy(b->work, b->saved, b->loc->state_size);
        if (ignorance && b->loc->reset_ignorance != NULL)
            b->loc->reset_ignorance(b->work);
        t0 = bench_now_ns();
        bench_loc_frame(b->loc, b->work, b->dx, b->dy, b->dth, &obs, &b->view, whole);
        t = bench_now_ns() - t0;
        if (t < best)
            best = t;
    }
    return best;
}

void bench_loc(bench_ctx_t *ctx)
{
    int reps = ctx->quick ? 20 : 300, i, n = (int)fl_localizer_count();
    double ref_track = 0, ref_ign = 0, ref_vis = 0;
    /* the fuzzy grid first: the reference of the other rows */
    for (i = -1; i < n; i++) {
        const fl_localizer_t *loc = i < 0 ? fl_localizer_find("fuzzy") : fl_localizer_get((uint16_t)i);
        char name[96], desc[128];
        double tt, ti;
        bl_t b;
        int is_ref = i < 0;
        if (loc == NULL || (!is_ref && strcmp(loc->name, "fuzzy") == 0))
            continue;
        if (bl_prepare(&b, loc, NULL, 5, 0) != 0) {
            printf("# loc %s: could not prepare the spl2013 walk state, skipped\n", loc->name);
            continue;
        }
        printf("# loc %s: state_size %lu B, params %lu B, %u samples; frame: odometry %d %d mm, "
               "%d observations\n",
               loc->name, (unsigned long)loc->state_size, (unsigned long)loc->params_size,
               (unsigned)b.samples, (int)b.dx, (int)b.dy, (int)b.obs.n);
        tt = bl_time(&b, reps, 0, b.obs.n, 1);
        ti = bl_time(&b, reps, 1, b.obs.n, 1);
        snprintf(desc, sizeof desc, "%s: predict + update (5 obs) + estimate, tracking",
                 is_ref ? "reference" : "peer: fuzzy");
        snprintf(name, sizeof name, "loc_%s_frame_tracking", loc->name);
        bench_row(ctx, name, tt, is_ref ? 0 : ref_track, desc);
        snprintf(desc, sizeof desc, "%s: the same frame from total ignorance",
                 is_ref ? "reference" : "peer: fuzzy");
        snprintf(name, sizeof name, "loc_%s_frame_ignorance", loc->name);
        bench_row(ctx, name, ti, is_ref ? 0 : ref_ign, desc);
        if (is_ref) {
            ref_track = tt;
            ref_ign = ti;
        }
        {
            void *vp = lr_params_new(loc);
            bl_t bv;
            if (vp != NULL) {
                lr_params_frames(loc, vp);
                if (bl_prepare(&bv, loc, vp, 5, 1) == 0) {
                    double tv = bl_time(&bv, reps, 0, bv.obs.n, 1);
                    snprintf(desc, sizeof desc, "%s: the frame with the vision preset and a view",
                             is_ref ? "reference" : "peer: fuzzy");
                    snprintf(name, sizeof name, "loc_%s_frame_vision", loc->name);
                    bench_row(ctx, name, tv, is_ref ? 0 : ref_vis, desc);
                    if (is_ref)
                        ref_vis = tv;
                    bl_free(&bv);
                }
                free(vp);
            }
        }
        if (b.samples > 0) {
            double t5 = bl_time(&b, reps, 0, 5, 0), t1 = bl_time(&b, reps, 0, 1, 0);
            snprintf(name, sizeof name, "loc_%s_particle_obs", loc->name);
            snprintf(desc, sizeof desc, "update per particle per observation ((5 obs - 1 obs) / 4 / %u)",
                     (unsigned)b.samples);
            bench_row(ctx, name, (t5 - t1) / (4.0 * b.samples), 0, desc);
        }
        bl_free(&b);
    }
}

int bench_loc_list(void)
{
    uint16_t i;
    for (i = 0; i < fl_localizer_count(); i++)
        printf("%s\n", fl_localizer_get(i)->name);
    return 0;
}

int bench_loc_repeat(const char *name, const char *const *param, int n_param, long repeat,
                     int k_obs, int vision)
{
    char err[256];
    const fl_localizer_t *loc = lr_localizer(name, err, (int)sizeof err);
    void *params;
    bl_t b;
    long r;
    int k;
    if (loc == NULL) {
        fprintf(stderr, "bench: %s\n", err);
        return 2;
    }
    if ((params = lr_params_new(loc)) == NULL)
        return 1;
    if (vision)
        lr_params_frames(loc, params);
    for (k = 0; k < n_param; k++)
        if (lr_param_set(loc, params, param[k]) != 0) {
            fprintf(stderr, "bench: bad --param '%s' for localizer %s\n", param[k], loc->name);
            free(params);
            return 2;
        }
    if (bl_prepare(&b, loc, params, k_obs, vision) != 0) {
        fprintf(stderr, "bench: could not prepare the walk state for %s\n", loc->name);
        free(params);
        return 1;
    }
    for (r = 0; r < repeat; r++) {
        memcpy(b.work, b.saved, loc->state_size);
        bench_loc_frame(loc, b.work, b.dx, b.dy, b.dth, &b.obs, &b.view, 1);
    }
    printf("loc %s state_size %lu samples %u obs %d frames %ld%s\n", loc->name,
           (unsigned long)loc->state_size, (unsigned)b.samples, (int)b.obs.n, repeat,
           vision ? " vision" : "");
    bl_free(&b);
    free(params);
    return 0;
}
