/*
 * tools/bench/bench_hlvision.c - `fieldloc bench` section "hlvision": seed
 * 002's whole vision frame (fl_hlv_frame: colour classes, posts and poles,
 * the mask, the skeleton, the projection) at 640x480 on rendered hl3x2
 * frames (acyut-640, YUYV as a camera delivers it, random poses on the
 * field, head 15..35 deg down).  Rows:
 *   hlvision_640x480        the whole frame, mean over the frames
 *   hlvision_objects_640    posts and poles only (crossings off)
 *   hlvision_worst_640      the slowest frame of the whole path
 * No peer.
 */
#include "bench/bench.h"
#include "eval/hldetect.h"
#include "world/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BH_FRAMES 16

static volatile int32_t bh_sink;

/* ns per frame of hv on the frame (the mean of reps runs). */
static double bh_time(fl_hlv_t *hv, const render_frame_t *fr, const fl_camera_t *cam, int reps)
{
    fl_obs_list_t obs;
    double t0;
    int r;
    bh_sink += fl_hlv_frame(hv, &fr->view, cam, &obs);   /* warm */
    t0 = bench_now_ns();
    for (r = 0; r < reps; r++)
        bh_sink += fl_hlv_frame(hv, &fr->view, cam, &obs);
    return (bench_now_ns() - t0) / reps;
}

void bench_hlvision(bench_ctx_t *ctx)
{
    const fl_field_t *field = fl_field_find("hl3x2");
    const fl_camera_model_t *m = fl_camera_model_find("acyut-640");
    fl_hlv_t *all, *objects;
    fl_hlv_params_t p;
    double sum_all = 0, sum_obj = 0, worst = 0;
    const int reps = ctx->quick ? 5 : 40;
    uint32_t rng = 20020u;
    int n, done = 0;
    char desc[160];
    if (!field || !m) {
        printf("hlvision: field hl3x2 or camera acyut-640 not in this build\n");
        return;
    }
    all = hld_new(field);
    objects = malloc(sizeof *objects);
    fl_hlv_params_default(&p, field);
    p.crossings = 0;
    if (!all || !objects || fl_hlv_init(objects, &p) != FL_OK) {
        free(all);
        free(objects);
        return;
    }
    for (n = 0; n < BH_FRAMES; n++) {
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        double t;
        render_scene_default(&sc, field, m);
        rng = rng * 1103515245u + 12345u;
        sc.robot_x_mm = (int32_t)((rng >> 8) % 2800) - 1400;
        rng = rng * 1103515245u + 12345u;
        sc.robot_y_mm = (int32_t)((rng >> 8) % 1800) - 900;
        rng = rng * 1103515245u + 12345u;
        sc.robot_heading = (fl_angle_t)((rng >> 8) & 0xFFFF);
        rng = rng * 1103515245u + 12345u;
        sc.head.head_pitch = fl_angle_from_mdeg(15000 + (int32_t)((rng >> 8) % 20000));
        sc.format = FL_FMT_YUYV422;
        sc.seed = (uint32_t)n + 1;
        if (render_frame(&sc, &fr) != 0)
            continue;
        if (render_scene_camera(&sc, &cam) == FL_OK) {
            t = bh_time(all, &fr, &cam, reps);
            sum_all += t;
            if (t > worst)
                worst = t;
            sum_obj += bh_time(objects, &fr, &cam, reps);
            done++;
        }
        render_frame_free(&fr);
    }
    if (done > 0) {
        snprintf(desc, sizeof desc, "no peer, %d rendered hl3x2 frames (YUYV)", done);
        bench_row(ctx, "hlvision_640x480", sum_all / done, 0, desc);
        bench_row(ctx, "hlvision_objects_640", sum_obj / done, 0, desc);
        bench_row(ctx, "hlvision_worst_640", worst, 0, desc);
    }
    free(all);
    free(objects);
}
