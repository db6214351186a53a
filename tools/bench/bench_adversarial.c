/*
 * tools/bench/bench_adversarial.c - time of the whole vision path (scanner to
 * observations) on the hostile frames of tools/world/adversarial.h at 320x240 and
 * 640x480 in every format: the per-frame worst case the caps allow.  One
 * row per kind and size (the slowest of the three formats), best of 5 runs
 * of each frame; the last row is the worst of all.
 */
#include "world/adversarial.h"
#include "fieldloc/fieldloc.h"
#include "bench/bench.h"

#include <stdio.h>
#include <stdlib.h>

void bench_adversarial(bench_ctx_t *ctx)
{
    static const int sizes[2][2] = {{320, 240}, {640, 480}};
    static const fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422, FL_FMT_YCBCR_PLANAR};
    static const char *const cams[2] = {"nao4-bottom-320", "nao4-top-640"};
    fl_color_table_t *colors = malloc(sizeof *colors);
    fl_vision_t *vis = malloc(sizeof *vis);
    fl_color_params_t cp;
    fl_vision_params_t vp;
    fl_obs_list_t obs;
    double worst = 0;
    char worst_name[96] = "";
    int k, si, fi, rep, reps = ctx->quick ? 2 : 5;
    if (!colors || !vis)
        goto out;
    fl_color_params_default(&cp);
    fl_vision_params_default(&vp);
    if (fl_color_init(colors, &cp) != FL_OK || fl_vision_init(vis, &vp) != FL_OK)
        goto out;
    for (si = 0; si < 2; si++) {
        const fl_camera_model_t *m = fl_camera_model_find(cams[si]);
        fl_camera_pose_t pose = {m->default_neck_height_mm, 0, 0, m->default_pitch_offset, 0, 0, 0};
        fl_camera_t cam;
        fl_camera_init(&cam, m, &pose);
        for (k = 0; k < ADV_COUNT; k++) {
            double slowest = 0;
            for (fi = 0; fi < 3; fi++) {
                fl_image_t img;
                fl_status_t st;
                double best = 1e30;
                uint8_t *buf = adv_frame((adv_kind_t)k, sizes[si][0], sizes[si][1], fmts[fi], 8, &img, &st);
                if (!buf)
                    continue;
                for (rep = 0; rep < reps; rep++) {
                    double t0 = bench_now_ns(), dt;
                    fl_vision_frame(vis, colors, &img, &cam, fl_field_find("spl2013"), &obs);
                    dt = bench_now_ns() - t0;
                    if (dt < best)
                        best = dt;
                }
                if (best > slowest)
                    slowest = best;
                if (best > worst) {
                    worst = best;
                    snprintf(worst_name, sizeof worst_name, "%s %dx%d format %d", adv_name((adv_kind_t)k),
                             sizes[si][0], sizes[si][1], (int)fmts[fi]);
                }
                free(buf);
            }
            {
                char name[64];
                snprintf(name, sizeof name, "adv_%s_%d", adv_name((adv_kind_t)k), sizes[si][0]);
                bench_row(ctx, name, slowest, 0, "vision path, slowest of RGB/YUYV/planar (no peer)");
            }
        }
    }
    {
        char desc[160];
        snprintf(desc, sizeof desc, "worst hostile frame: %s (no peer)", worst_name);
        bench_row(ctx, "adv_worst", worst, 0, desc);
    }
out:
    free(colors);
    free(vis);
}
