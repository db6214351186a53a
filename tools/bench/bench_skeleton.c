/*
 * tools/bench/bench_skeleton.c - `fieldloc bench` section "skeleton": the
 * skeleton stage (fl_skel_run: pinholes, K3M thinning, spurs, nodes,
 * crossings, the white-point sample) on 320x240 masks, against OpenCV's
 * cv::ximgproc::thinning (Zhang-Suen, opencv_contrib; thinning only, no
 * nodes: the peer does less) when that module is installed
 * (tools/bench/bench_skeleton_cv.cpp).
 * Rows (ns per mask, best of 5 means of BENCH_SK_N runs, 1 with --quick):
 *   skeleton         the field-like view of tools/world/line_mask.c (a
 *                    touch line, the halfway line, the centre circle, a
 *                    penalty-area T and corner; about 4600 white pixels)
 *   skeleton_ragged  the same view with ragged edges (40 % of the edge
 *                    pixels flipped)
 *   skeleton_thick   the view drawn at twice the line width
 *   skeleton_blob    all 76800 pixels white (the iteration cap: 32)
 *   skeleton_noise   each pixel white with probability 1/2 (the contour
 *                    list overflows: FL_SKEL_MAX_CONTOUR)
 */
#include "bench/bench.h"
#include "world/line_mask.h"
#include "fieldloc/skeleton.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef FL_HAVE_OPENCV
double bskcv_thin_ns(const uint8_t *mask, int w, int h, int n);
#endif

#define BENCH_SK_W 320
#define BENCH_SK_H 240
#define BENCH_SK_N 200

static volatile int32_t bsk_sink;

static double bsk_time(fl_skel_t *s, const uint8_t *mask, int n)
{
    fl_skel_mask_t m = {mask, BENCH_SK_W, BENCH_SK_H, BENCH_SK_W};
    double t0 = bench_now_ns();
    int k;
    for (k = 0; k < n; k++) {
        (void)fl_skel_run(s, &m, (uint32_t)k);
        bsk_sink += s->n_crossings;
    }
    return (bench_now_ns() - t0) / n;
}

/* The masks of the rows, by index; returns the name. */
static const char *bsk_mask(int i, uint8_t *m)
{
    const int w = BENCH_SK_W, h = BENCH_SK_H;
    uint32_t r = 12345;
    int k;
    memset(m, 0, (size_t)w * (size_t)h);
    switch (i) {
    case 0:
        lm_field_view(m, w, h, w);
        return "skeleton";
    case 1:
        lm_field_view(m, w, h, w);
        lm_ragged(m, w, h, w, 7, 40);
        return "skeleton_ragged";
    case 2:
        lm_segment(m, w, h, w, -10, 70, 330, 60, 3.2, 3.2);
        lm_segment(m, w, h, w, 150, 65.6, 175, 250, 3.2, 8.0);
        lm_ellipse(m, w, h, w, 165, 170, 90, 45, 5.2);
        lm_segment(m, w, h, w, 20, 68.5, 10, 110, 3.6, 4.8);
        lm_segment(m, w, h, w, 10, 110, 60, 112, 4.8, 4.8);
        return "skeleton_thick";
    case 3:
        memset(m, 1, (size_t)w * (size_t)h);
        return "skeleton_blob";
    default:
        for (k = 0; k < w * h; k++) {
            r ^= r << 13;
            r ^= r >> 17;
            r ^= r << 5;
            m[k] = (uint8_t)(r >> 31);
        }
        return "skeleton_noise";
    }
}

void bench_skeleton(bench_ctx_t *ctx)
{
    fl_skel_t *s = malloc(sizeof *s);
    uint8_t *m = malloc((size_t)BENCH_SK_W * BENCH_SK_H);
    fl_skel_params_t p;
    int i, k, reps = ctx->quick ? 1 : 5, n = ctx->quick ? 20 : BENCH_SK_N;
    if (!s || !m) {
        free(s);
        free(m);
        return;
    }
    fl_skel_params_default(&p);
    (void)fl_skel_init(s, &p);
    for (i = 0; i < 5; i++) {
        const char *name = bsk_mask(i, m);
        double a = 1e30, peer = -1;
        char desc[160];
        int nn = i >= 3 ? n / 10 + 1 : n;
        for (k = 0; k < reps; k++) {
            double t = bsk_time(s, m, nn);
            if (t < a)
                a = t;
        }
#ifdef FL_HAVE_OPENCV
        for (k = 0; k < reps; k++) {
            double t = bskcv_thin_ns(m, BENCH_SK_W, BENCH_SK_H, nn);
            if (t > 0 && (peer < 0 || t < peer))
                peer = t;
        }
#endif
        snprintf(desc, sizeof desc, "%s; %d white px, skeleton %d, %d iterations, %d crossings%s%s",
                 peer > 0 ? "cv::ximgproc::thinning (Zhang-Suen; thinning only)"
                          : "no peer (opencv_contrib ximgproc not built)",
                 (int)s->n_white, (int)s->n_skeleton, (int)s->iterations, (int)s->n_crossings,
                 s->iter_capped ? ", iteration cap" : "",
                 s->contour_dropped ? ", contour list full" : "");
        bench_row(ctx, name, a, peer, desc);
    }
    free(s);
    free(m);
}
