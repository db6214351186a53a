/*
 * tools/bench/bench_fuzzy.c - the fuzzy position grid (include/fieldloc/fuzzy.h):
 * one predict plus an update with 5 observations on the SPL 2013 grid
 * (104 x 74 cells).
 *
 * States (each repetition starts from a saved copy, the copy is not timed):
 *   tracking   the grid after 10 s of the built-in spl2013 walk (a tracked
 *              mode: most cells impossible, gating on), the next frame's
 *              odometry and the next 5 observations of the walk;
 *   ignorance  total ignorance (every cell possible: the worst case of
 *              the update, no gating), the same odometry and observations.
 * Rows: fuzzy_frame_tracking, fuzzy_frame_ignorance (ns per predict + 5
 * updates), and their parts (predict alone, 5 updates alone).  No peer.
 * fuzzy_negative_ignorance: the negative-information pass of
 * fl_fuzzy_update_view alone (neg_q8 0.39 on cells at least 1/2 high, as
 * tools/loc/locrun.c lr_params_frames; an empty observation list, a
 * view 50 deg wide and 0.6-4 m deep ahead) on the grid that ignorance and
 * the 5 updates leave (many cells with a narrow heading on the arcs);
 * fuzzy_negative_worst: the same on a grid whose every cell has a narrow
 * heading and which is not exactly symmetric (the whole grid is done).
 *
 * Instruction counts (stable, machine independent): run the walk under
 * callgrind collecting only the localizer, e.g.
 *   valgrind --tool=callgrind --toggle-collect=fl_fuzzy_predict \
 *     --toggle-collect=fl_fuzzy_update_one build/fieldloc simulate \
 *     --field spl2013 --localizer fuzzy --seed 1 --steps 300 --quiet
 * and divide the collected instructions by the steps (about 3-4
 * observations per step in that walk).
 */
#include "fieldloc/fieldloc.h"
#include "bench/bench.h"
#include "world/sim.h"

#include <stdio.h>
#include <string.h>

static fl_fuzzy_t bfz_saved, bfz_grid;
static sim_t bfz_sim;
static sim_step_t bfz_step;

typedef struct {
    int32_t dx, dy;
    fl_angle_t dth;
    fl_obs_t obs[5];
    int n;
} bfz_input_t;

/* The grid after `steps` steps of the spl2013 walk, and the next frame's
 * odometry with the next 5 observations.  0 on success. */
static int bfz_prepare(int steps, bfz_input_t *in)
{
    sim_scenario_t sc;
    int k;
    if (sim_scenario_builtin(&sc, "spl2013") != 0 || sim_init(&bfz_sim, &sc) != 0)
        return -1;
    if (fl_fuzzy_init(&bfz_saved, sc.field, NULL) != FL_OK)
        return -1;
    fl_fuzzy_set_prior_half(&bfz_saved, -1);
    for (k = 0; k < steps && sim_step(&bfz_sim, &bfz_step); k++) {
        fl_fuzzy_estimate_t est;
        fl_fuzzy_predict(&bfz_saved, bfz_step.odo_dx_mm, bfz_step.odo_dy_mm, bfz_step.odo_dtheta);
        fl_fuzzy_update(&bfz_saved, &bfz_step.obs);
        fl_fuzzy_estimate(&bfz_saved, &est);
    }
    in->n = 0;
    in->dx = in->dy = 0;
    in->dth = 0;
    while (in->n < 5 && sim_step(&bfz_sim, &bfz_step)) {
        int i;
        if (in->dx == 0 && in->dy == 0) {
            in->dx = bfz_step.odo_dx_mm;
            in->dy = bfz_step.odo_dy_mm;
            in->dth = bfz_step.odo_dtheta;
        }
        for (i = 0; i < bfz_step.obs.n && in->n < 5; i++)
            if (bfz_step.obs_landmark[i] >= 0)     /* real ones: no gating */
                in->obs[in->n++] = bfz_step.obs.obs[i];
    }
    return in->n == 5 ? 0 : -1;
}

/* Best of `reps` timings of predict (+ 5 updates when upd), from the
 * saved state each time. */
static double bfz_time(const bfz_input_t *in, int reps, int pred, int upd)
{
    double best = 1e30;
    int r, i;
    for (r = 0; r < reps; r++) {
        double t0, t;
        memcpy(&bfz_grid, &bfz_saved, sizeof bfz_grid);
        t0 = bench_now_ns();
        if (pred)
            fl_fuzzy_predict(&bfz_grid, in->dx, in->dy, in->dth);
        if (upd)
            for (i = 0; i < in->n; i++)
                fl_fuzzy_update_one(&bfz_grid, &in->obs[i]);
        t = bench_now_ns() - t0;
        if (t < best)
            best = t;
    }
    return best;
}

void bench_fuzzy(bench_ctx_t *ctx)
{
    static bfz_input_t in;
    int reps = ctx->quick ? 20 : 400, live = 0, i;
    if (bfz_prepare(300, &in) != 0) {
        printf("fuzzy: could not prepare the spl2013 walk state, skipped\n");
        return;
    }
    for (i = 0; i < bfz_saved.nx * bfz_saved.ny; i++)
        live += bfz_saved.cell[i].height != 0;
    printf("# fuzzy: SPL grid %d x %d cells, sizeof(fl_fuzzy_t) %lu B; tracking state %d live "
           "cells, odometry %d %d mm\n", bfz_saved.nx, bfz_saved.ny,
           (unsigned long)sizeof(fl_fuzzy_t), live, (int)in.dx, (int)in.dy);
    bench_row(ctx, "fuzzy_frame_tracking", bfz_time(&in, reps, 1, 1), 0,
              "predict + 5 updates, tracked mode (goal 500000)");
    bench_row(ctx, "fuzzy_predict_tracking", bfz_time(&in, reps, 1, 0), 0, "predict alone");
    bench_row(ctx, "fuzzy_update5_tracking", bfz_time(&in, reps, 0, 1), 0, "5 updates alone");
    fl_fuzzy_reset_ignorance(&bfz_saved);
    bench_row(ctx, "fuzzy_frame_ignorance", bfz_time(&in, reps, 1, 1), 0,
              "predict + 5 updates from total ignorance (worst case)");
    bench_row(ctx, "fuzzy_predict_ignorance", bfz_time(&in, reps, 1, 0), 0, "predict alone");
    bench_row(ctx, "fuzzy_update5_ignorance", bfz_time(&in, reps, 0, 1), 0, "5 updates alone");
    {
        static fl_obs_list_t empty;
        fl_obs_view_t v;
        double best = 1e30;
        int r, pass;
        fl_obs_list_clear(&empty);
        v.valid = true;
        v.bearing_right = fl_angle_from_mdeg(-25000);
        v.bearing_left = fl_angle_from_mdeg(25000);
        v.near_mm = 600;
        v.far_mm = 4000;
        bfz_saved.params.neg_q8 = 100;        /* as lr_params_frames */
        bfz_saved.params.neg_min_q8 = 128;
        for (i = 0; i < in.n; i++)
            fl_fuzzy_update_one(&bfz_saved, &in.obs[i]);
        for (pass = 0; pass < 2; pass++) {
            if (pass == 1) {
                for (i = 0; i < bfz_saved.nx * bfz_saved.ny; i++) {
                    fl_fuzzy_cell_t *c = &bfz_saved.cell[i];
                    c->height = 255;
                    c->bias = 0;
                    c->core = 3;
                    c->slope = 6;
                    c->centre = (fl_angle_t)(i * 2731);
                }
                for (i = 0; i < bfz_saved.ny; i++) {
                    bfz_saved.row_lo[i] = 0;
                    bfz_saved.row_hi[i] = (uint8_t)(bfz_saved.nx - 1);
                }
                bfz_saved.sym_exact = false;
            }
            best = 1e30;
            for (r = 0; r < reps; r++) {
                double t0, t;
                memcpy(&bfz_grid, &bfz_saved, sizeof bfz_grid);
                t0 = bench_now_ns();
                fl_fuzzy_update_view(&bfz_grid, &empty, &v);
                t = bench_now_ns() - t0;
                if (t < best)
                    best = t;
            }
            bench_row(ctx, pass == 0 ? "fuzzy_negative_ignorance" : "fuzzy_negative_worst", best, 0,
                      pass == 0 ? "negative information pass after ignorance + 5 updates"
                                : "negative information pass, every cell narrow");
        }
    }
}
