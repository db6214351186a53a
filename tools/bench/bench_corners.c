/*
 * tools/bench/bench_corners.c - `fieldloc bench` section "corners": seed
 * 004's corner stage (fl_corners_run: luma, smoothing, gradient, Sojka's
 * measure, suppression, labels, pairing, nets) beside the L/T/X path
 * (fl_vision_frame) on the same rendered aibo2004 frames (aibo-ers7
 * 208x160, planar YCbCr as the AIBO's band rows give it, random poses on
 * the field, head 5..25 deg down).  Rows:
 *   vision_aibo_208x160     fl_vision_frame, mean over the frames
 *   corners_208x160         fl_corners_run after it (the nets take its
 *                           beacon stage's posts), mean
 *   corners_worst_208       the slowest frame of fl_corners_run
 * The corner path in frames mode (`simulate --vision corners`) costs both
 * of the first two rows.  No peer.
 */
#include "bench/bench.h"
#include "eval/detect.h"
#include "world/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BC_FRAMES 16

static volatile int32_t bc_sink;

void bench_corners(bench_ctx_t *ctx)
{
    const fl_field_t *field = fl_field_find("aibo2004");
    const fl_camera_model_t *m = fl_camera_model_find("aibo-ers7");
    det_ctx_t det;
    fl_corners_t *cn;
    fl_corners_params_t p;
    static fl_obs_list_t obs;
    double sum_v = 0, sum_c = 0, worst = 0;
    const int reps = ctx->quick ? 5 : 40;
    uint32_t rng = 20040u;
    int n, r, done = 0;
    char desc[160];
    if (!field || !m) {
        printf("corners: field aibo2004 or camera aibo-ers7 not in this build\n");
        return;
    }
    cn = malloc(sizeof *cn);
    fl_corners_params_default(&p);
    if (cn == NULL || fl_corners_init(cn, &p) != FL_OK || det_ctx_init(&det) != 0) {
        free(cn);
        return;
    }
    for (n = 0; n < BC_FRAMES; n++) {
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        double t0, tv, tc;
        render_scene_default(&sc, field, m);
        rng = rng * 1103515245u + 12345u;
        sc.robot_x_mm = (int32_t)((rng >> 8) % 3800) - 1900;
        rng = rng * 1103515245u + 12345u;
        sc.robot_y_mm = (int32_t)((rng >> 8) % 2400) - 1200;
        rng = rng * 1103515245u + 12345u;
        sc.robot_heading = (fl_angle_t)((rng >> 8) & 0xFFFF);
        rng = rng * 1103515245u + 12345u;
        sc.head.head_pitch = fl_angle_from_mdeg(5000 + (int32_t)((rng >> 8) % 20000));
        sc.format = FL_FMT_YCBCR_PLANAR;
        sc.seed = (uint32_t)n + 1;
        if (render_frame(&sc, &fr) != 0)
            continue;
        if (render_scene_camera(&sc, &cam) == FL_OK) {
            bc_sink += fl_vision_frame(det.vis, det.colors, &fr.view, &cam, field, &obs);  /* warm */
            t0 = bench_now_ns();
            for (r = 0; r < reps; r++)
                bc_sink += fl_vision_frame(det.vis, det.colors, &fr.view, &cam, field, &obs);
            tv = (bench_now_ns() - t0) / reps;
            bc_sink += (int32_t)fl_corners_run(cn, &fr.view, det.colors, &cam, &det.vis->beacons);
            t0 = bench_now_ns();
            for (r = 0; r < reps; r++)
                bc_sink += (int32_t)fl_corners_run(cn, &fr.view, det.colors, &cam, &det.vis->beacons);
            tc = (bench_now_ns() - t0) / reps;
            sum_v += tv;
            sum_c += tc;
            if (tc > worst)
                worst = tc;
            done++;
        }
        render_frame_free(&fr);
    }
    if (done > 0) {
        snprintf(desc, sizeof desc, "no peer, %d rendered aibo2004 frames (planar)", done);
        bench_row(ctx, "vision_aibo_208x160", sum_v / done, 0, desc);
        bench_row(ctx, "corners_208x160", sum_c / done, 0, desc);
        bench_row(ctx, "corners_worst_208", worst, 0, desc);
    }
    det_ctx_free(&det);
    free(cn);
}
