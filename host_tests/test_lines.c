/*
 * host_tests/test_lines.c - line points and segments (lines.h): synthetic
 * point sets (straight lines with noise, L / X shapes, a circle arc, noise,
 * broken lines, capacity), the segment error arithmetic against a double
 * reference, painted frames through the scanner (points at run midpoints,
 * the projected width check, white ratio), bad input, and a digest of the
 * outputs for `make cross-test`.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "eval/scan_tool.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static fl_lines_t L;
static fl_color_table_t colors;
static fl_scan_t scan;

static void lines_default(void)
{
    fl_lines_params_t p;
    fl_lines_params_default(&p);
    CHECK_EQ(fl_lines_init(&L, &p), FL_OK);
}

/* Points along a straight line from (u0, v0) to (u1, v1) every `step` px,
 * jittered by up to +-jit half pixels across. */
static void add_line(double u0, double v0, double u1, double v1, double step,
                     int jit, t_rng_t *r)
{
    double len = hypot(u1 - u0, v1 - v0);
    int k, n = (int)(len / step);
    double nu = -(v1 - v0) / len, nv = (u1 - u0) / len;
    /* as a scanner finds them: a line closer to horizontal crosses the
     * vertical scan lines */
    uint8_t fl = fabs(v1 - v0) < fabs(u1 - u0) ? FL_LINE_POINT_VERTICAL : 0;
    for (k = 0; k <= n; k++) {
        double t = (double)k / (n > 0 ? n : 1);
        double j = jit ? t_rng_range(r, -jit, jit) * 0.5 : 0;
        double u = u0 + t * (u1 - u0) + j * nu, v = v0 + t * (v1 - v0) + j * nv;
        fl_lines_add_point(&L, (int32_t)lround(2 * u), (int32_t)lround(2 * v), 3, fl);
    }
}

/* Distance (px) from (u, v) to the infinite line of segment s. */
static double seg_dist(const fl_segment_t *s, double u, double v)
{
    return abs(fl_segment_distance_q4(s, (int32_t)lround(16 * u), (int32_t)lround(16 * v))) / 16.0;
}

static double seg_len(const fl_segment_t *s) { return s->len_q4 / 16.0; }

static uint32_t digest_lines(uint32_t h)
{
    int32_t i;
    h = t_hash_i32(h, L.n_points);
    h = t_hash_i32(h, L.n_segments);
    for (i = 0; i < L.n_segments; i++) {
        const fl_segment_t *s = &L.segments[i];
        h = t_hash_i32(h, s->u0_q4);
        h = t_hash_i32(h, s->v0_q4);
        h = t_hash_i32(h, s->u1_q4);
        h = t_hash_i32(h, s->v1_q4);
        h = t_hash_i32(h, s->n);
        h = t_hash_i32(h, s->angle);
        h = t_hash_i32(h, (int32_t)s->sse_q2);
        h = t_hash_i32(h, s->bulge_q4);
    }
    for (i = 0; i < L.n_points; i++)
        h = t_hash_i32(h, L.points[i].seg == FL_LINES_NONE ? -1 : L.points[i].seg);
    return h;
}

/* ---- parameters and bad input ------------------------------------------------ */

static void test_params(void)
{
    fl_lines_params_t p;
    fl_lines_params_default(&p);
    CHECK_EQ(fl_lines_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_lines_init(&L, NULL), FL_ERR_NULL);
    p.step_px = 65;
    CHECK_EQ(fl_lines_init(&L, &p), FL_ERR_RANGE);
    fl_lines_params_default(&p);
    p.white_pct = 101;
    CHECK_EQ(fl_lines_init(&L, &p), FL_ERR_RANGE);
    fl_lines_params_default(&p);
    p.min_points = 1;
    CHECK_EQ(fl_lines_init(&L, &p), FL_ERR_RANGE);
    fl_lines_params_default(&p);
    p.max_width_pct = 99;
    CHECK_EQ(fl_lines_init(&L, &p), FL_ERR_RANGE);
    lines_default();
    /* per-frame calls never fail */
    CHECK_EQ(fl_lines_find_points(NULL, &scan, NULL, NULL, 50), 0);
    CHECK_EQ(fl_lines_find_points(&L, NULL, NULL, NULL, 50), 0);
    CHECK_EQ(fl_lines_find_segments(NULL, NULL), 0);
    CHECK(!fl_lines_reset(&L, 0, 10));
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 0);
    CHECK(!fl_lines_add_point(&L, 2, 2, 1, 0)); /* no frame */
    CHECK(fl_lines_reset(&L, 100, 80));
    CHECK(!fl_lines_add_point(&L, -1, 2, 1, 0));
    CHECK(!fl_lines_add_point(&L, 2 * 100, 2, 1, 0));
    CHECK(fl_lines_add_point(&L, 2 * 99, 2 * 79, 1, 0));
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 0);     /* one point: no segment */
    CHECK_EQ(fl_lines_white_pct(NULL, 0, 0, 100, 100), 100);
    CHECK_EQ(fl_lines_width_q4(&L, 10, false), 0); /* no camera */
    CHECK_EQ(fl_lines_points_near(NULL, 0, 0, 5, 5, NULL), 0);
}

/* ---- synthetic point sets ---------------------------------------------------- */

static void test_straight(void)
{
    t_rng_t r;
    uint32_t h = t_hash_init();
    int a;
    t_rng_seed(&r, 11);
    /* lines at 0..180 degrees, 5 px point spacing, +-1 px jitter */
    for (a = 0; a < 180; a += 7) {
        double c = cos(a * M_PI / 180), s = sin(a * M_PI / 180);
        double u0 = 160 - 100 * c, v0 = 120 - 100 * s, u1 = 160 + 100 * c, v1 = 120 + 100 * s;
        const fl_segment_t *sg;
        double da;
        lines_default();
        CHECK(fl_lines_reset(&L, 320, 240));
        add_line(u0, v0, u1, v1, 5, 2, &r);
        CHECK_EQ(fl_lines_find_segments(&L, NULL), 1);
        if (L.n_segments != 1)
            continue;
        sg = &L.segments[0];
        CHECK_LE(fabs(seg_len(sg) - 200), 3.0);
        CHECK_LE(seg_dist(sg, 160, 120), 0.75);
        CHECK_LE(seg_dist(sg, u0, v0), 1.0);
        CHECK_LE(seg_dist(sg, u1, v1), 1.0);
        /* end 0 has the smaller u; angle in [-90, 90) */
        CHECK(sg->u0_q4 <= sg->u1_q4);
        da = fmod(sg->angle * 180.0 / 32768 - a + 720, 180);
        if (da > 90)
            da -= 180;
        CHECK_LE(fabs(da), 1.0);
        CHECK_LE(abs(sg->bulge_q4), 16);       /* straight: under 1 px */
        h = digest_lines(h);
    }
    t_digest("lines.straight", h);
}

static void test_l_and_x(void)
{
    t_rng_t r;
    uint32_t h = t_hash_init();
    int i;
    t_rng_seed(&r, 12);
    /* X: two lines crossing at (160, 120) */
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    add_line(60, 60, 260, 180, 5, 1, &r);
    add_line(60, 180, 260, 60, 5, 1, &r);
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 2);
    for (i = 0; i < L.n_segments; i++) {
        CHECK_LE(seg_dist(&L.segments[i], 160, 120), 1.0);
        CHECK(seg_len(&L.segments[i]) > 200);
    }
    h = digest_lines(h);
    /* L: corner at (100, 200) */
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    add_line(100, 200, 300, 200, 5, 1, &r);
    add_line(100, 200, 100, 20, 5, 1, &r);
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 2);
    for (i = 0; i < L.n_segments; i++)
        CHECK_LE(seg_dist(&L.segments[i], 100, 200), 1.0);
    h = digest_lines(h);
    t_digest("lines.l_and_x", h);
}

static void test_arc(void)
{
    int k, i, n_long = 0;
    /* a circle of radius 100 px, points every 3 degrees on 150 degrees */
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    for (k = 0; k <= 50; k++) {
        double a = (15 + 3 * k) * M_PI / 180;
        fl_lines_add_point(&L, (int32_t)lround(2 * (160 + 100 * cos(a))),
                           (int32_t)lround(2 * (20 + 100 * sin(a))), 3,
                           fabs(cos(a)) < 0.7 ? FL_LINE_POINT_VERTICAL : 0);
    }
    CHECK(fl_lines_find_segments(&L, NULL) >= 3); /* chords, not one line */
    for (i = 0; i < L.n_segments; i++) {
        const fl_segment_t *s = &L.segments[i];
        double mu = (s->u0_q4 + s->u1_q4) / 32.0, mv = (s->v0_q4 + s->v1_q4) / 32.0;
        /* a chord: ends on the circle, middle inside it */
        CHECK_LE(fabs(hypot(s->u0_q4 / 16.0 - 160, s->v0_q4 / 16.0 - 20) - 100), 2.5);
        CHECK_LE(fabs(hypot(s->u1_q4 / 16.0 - 160, s->v1_q4 / 16.0 - 20) - 100), 2.5);
        CHECK(hypot(mu - 160, mv - 20) < 100);
        if (seg_len(s) > 30)
            n_long++;
        /* it bulges away from the centre: positive along (-sin, cos) means
         * toward larger v for a chord running along +u */
        if (seg_len(s) > 30) {
            double nu = -sin(s->angle * M_PI / 32768), nv = cos(s->angle * M_PI / 32768);
            double side = (160 - mu) * nu + (20 - mv) * nv;  /* centre side */
            CHECK(side * s->bulge_q4 < 0);
        }
    }
    CHECK(n_long >= 2);
    t_digest("lines.arc", digest_lines(t_hash_init()));
}

static void test_noise_and_gaps(void)
{
    t_rng_t r;
    int k;
    t_rng_seed(&r, 13);
    /* scattered points 25+ px apart: nothing to connect */
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    for (k = 0; k < 60; k++)
        fl_lines_add_point(&L, 2 * (25 * (k % 12) + 10), 2 * (28 * (k / 12) + 5 + (k % 3)),
                           2, (uint8_t)(k & 1));
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 0);
    for (k = 0; k < L.n_points; k++)
        CHECK_EQ(L.points[k].seg, FL_LINES_NONE);
    /* one line broken by a 20 px gap: two pieces merged back */
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    add_line(20, 100, 140, 110, 5, 1, &r);
    add_line(160, 111.7, 300, 123.3, 5, 1, &r);
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 1);
    CHECK(L.merges >= 1);
    CHECK(L.n_segments == 1 && seg_len(&L.segments[0]) > 270);
    /* the same with a 60 px gap (beyond 6 steps): two segments */
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    add_line(20, 100, 120, 108.3, 5, 1, &r);
    add_line(180, 113.3, 300, 123.3, 5, 1, &r);
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 2);
    /* parallel lines 6 px apart stay apart */
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    add_line(20, 100, 300, 100, 5, 0, &r);
    add_line(20, 112, 300, 112, 5, 0, &r);
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 2);
}

static void test_capacity(void)
{
    t_rng_t r;
    int k;
    t_rng_seed(&r, 14);
    lines_default();
    CHECK(fl_lines_reset(&L, 640, 480));
    for (k = 0; k < FL_LINES_MAX_POINTS + 100; k++)
        fl_lines_add_point(&L, t_rng_range(&r, 0, 2 * 639), t_rng_range(&r, 0, 2 * 479), 2, 0);
    CHECK_EQ(L.n_points, FL_LINES_MAX_POINTS);
    CHECK_EQ(L.points_dropped, 100);
    fl_lines_find_segments(&L, NULL);
    CHECK(L.n_segments <= FL_LINES_MAX_SEGMENTS);
    for (k = 0; k < L.n_points; k++)
        CHECK(L.points[k].seg == FL_LINES_NONE || L.points[k].seg < L.n_segments);
    /* many short lines: the segment table fills and counts */
    lines_default();
    CHECK(fl_lines_reset(&L, 640, 480));
    for (k = 0; k < 160; k++) {
        double u = 10 + 40 * (k % 16), v = 10 + 45 * (k / 16);
        add_line(u, v, u + 20, v + 20, 5, 0, &r);
    }
    fl_lines_find_segments(&L, NULL);
    CHECK_EQ(L.n_segments, FL_LINES_MAX_SEGMENTS);
    CHECK(L.segments_dropped > 0);
    t_digest("lines.capacity", digest_lines(t_hash_init()));
}

/* ---- the segment error arithmetic -------------------------------------------- */

/* The summed squared error that decides growth (seed 000, eq. 1) equals the
 * double computation: checked through growth decisions on lines whose
 * error crosses the threshold at a known point.  A line bent by 3 px at
 * its middle: the growth stops near the bend (or the prune removes the
 * bent half). */
static void test_error_stop(void)
{
    int k, i;
    lines_default();
    CHECK(fl_lines_reset(&L, 320, 240));
    /* 30 points straight, then 30 points turning by 25 degrees */
    for (k = 0; k <= 30; k++)
        fl_lines_add_point(&L, 2 * (10 + 5 * k), 2 * 120, 3, FL_LINE_POINT_VERTICAL);
    for (k = 1; k <= 30; k++)
        fl_lines_add_point(&L, (int32_t)lround(2 * (160 + 5 * k * cos(0.436))),
                           (int32_t)lround(2 * (120 + 5 * k * sin(0.436))), 3,
                           FL_LINE_POINT_VERTICAL);
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 2);
    for (i = 0; i < L.n_segments; i++)
        CHECK_LE(L.segments[i].sse_q2 / (double)L.segments[i].n, 4.0); /* < 1 px^2 mean */
    /* the bend point is near an end of both */
    for (i = 0; i < L.n_segments; i++) {
        const fl_segment_t *s = &L.segments[i];
        double d0 = hypot(s->u0_q4 / 16.0 - 160, s->v0_q4 / 16.0 - 120);
        double d1 = hypot(s->u1_q4 / 16.0 - 160, s->v1_q4 / 16.0 - 120);
        CHECK_LE(d0 < d1 ? d0 : d1, 12.0);
    }
}

/* ---- painted frames through the scanner --------------------------------------- */

static const uint8_t CARPET[3] = {82, 141, 85}, PAINT[3] = {254, 253, 250};

static void paint_rect(uint8_t *rgb, int w, int h, double u0, double v0, double u1,
                       double v1, double width, const uint8_t c[3])
{
    int u, v;
    double len = hypot(u1 - u0, v1 - v0);
    for (v = 0; v < h; v++)
        for (u = 0; u < w; u++) {
            double t = ((u - u0) * (u1 - u0) + (v - v0) * (v1 - v0)) / (len * len);
            double d = fabs((u - u0) * (v1 - v0) - (v - v0) * (u1 - u0)) / len;
            if (t >= 0 && t <= 1 && d <= width / 2)
                memcpy(rgb + 3 * ((size_t)v * (size_t)w + (size_t)u), c, 3);
        }
}

static void scan_painted(uint8_t *rgb, int w, int h, const fl_camera_t *cam)
{
    fl_color_params_t cp;
    fl_scan_params_t sp;
    fl_image_t img;
    fl_color_params_default(&cp);
    CHECK_EQ(fl_color_init(&colors, &cp), FL_OK);
    fl_scan_params_default(&sp);
    sp.col_step = sp.row_step = 1;
    CHECK_EQ(fl_scan_init(&scan, &sp), FL_OK);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, rgb, w, h, 3 * w), FL_OK);
    CHECK(fl_scan_frame(&scan, &colors, &img, cam) > 0);
}

static void test_painted(void)
{
    enum { W = 320, H = 240 };
    uint8_t *rgb = malloc((size_t)W * H * 3);
    int k, i, found_h = 0, found_d = 0;
    for (k = 0; k < W * H; k++)
        memcpy(rgb + 3 * k, CARPET, 3);
    paint_rect(rgb, W, H, 20, 60, 300, 60, 5, PAINT);       /* horizontal */
    paint_rect(rgb, W, H, 40, 220, 280, 100, 4, PAINT);     /* diagonal */
    scan_painted(rgb, W, H, NULL);
    lines_default();
    CHECK(fl_lines_find_points(&L, &scan, NULL, NULL, 0) > 20);
    /* every point is a run midpoint: on one of the painted lines (no
     * camera: no width check, rows along a line give points too) */
    for (i = 0; i < L.n_points; i++) {
        double u = L.points[i].u_q1 / 2.0, v = L.points[i].v_q1 / 2.0;
        double dh = fabs(v - 60), dd = fabs((u - 40) * (100 - 220) - (v - 220) * (280 - 40)) /
                                       hypot(240, 120);
        /* within half the paint width (a row scanned along the 5 px line
         * lies up to 2 px off its centre) */
        CHECK_LE(dh < dd ? dh : dd, 2.5);
    }
    fl_lines_find_segments(&L, &scan);
    for (i = 0; i < L.n_segments; i++) {
        const fl_segment_t *s = &L.segments[i];
        if (fabs(s->angle * 180.0 / 32768) < 2 && seg_len(s) > 250)
            found_h++;
        if (fabs(s->angle * 180.0 / 32768 + 26.57) < 2 && seg_len(s) > 230)
            found_d++;
    }
    CHECK_EQ(found_h, 1);
    CHECK_EQ(found_d, 1);
    /* white ratio: along the painted line 100 %, across carpet 0 % */
    CHECK_EQ(fl_lines_white_pct(&scan, 16 * 30, 16 * 60, 16 * 290, 16 * 60), 100);
    CHECK_EQ(fl_lines_white_pct(&scan, 16 * 30, 16 * 150, 16 * 100, 16 * 150), 0);
    CHECK(fl_lines_white_pct(&scan, 16 * 30, 16 * 60, 16 * 290, 16 * 150) < 40);
    free(rgb);
}

/* The projected width check: with a camera, a white band much wider than a
 * painted line of the field at that row gives no points; a line of the
 * right width does. */
static void test_width_check(void)
{
    enum { W = 320, H = 240 };
    uint8_t *rgb = malloc((size_t)W * H * 3);
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    fl_camera_pose_t pose = {450, 0, 0, 0, 0, 0, 0};
    fl_camera_t cam;
    int k, i, in_wide = 0, in_line = 0;
    int32_t wq4;
    CHECK_EQ(fl_camera_init(&cam, m, &pose), FL_OK);
    for (k = 0; k < W * H; k++)
        memcpy(rgb + 3 * k, CARPET, 3);
    scan_painted(rgb, W, H, &cam);
    lines_default();
    fl_lines_find_points(&L, &scan, NULL, &cam, 50);
    wq4 = fl_lines_width_q4(&L, 200, false);
    /* a 50 mm line across row 200 at ~ 0.6 m is ~ 20 px wide horizontally */
    CHECK(wq4 > 16 * 10 && wq4 < 16 * 40);
    CHECK(fl_lines_width_q4(&L, 200, true) < wq4); /* foreshortened */
    /* vertical band: a line (wq4 wide) at u 80, a robot leg 6 times wider at u 220 */
    for (k = 0; k < W * H; k++)
        memcpy(rgb + 3 * k, CARPET, 3);
    paint_rect(rgb, W, H, 80, 150, 80, 239, wq4 / 16.0, PAINT);
    paint_rect(rgb, W, H, 220, 150, 220, 239, 6 * wq4 / 16.0, PAINT);
    scan_painted(rgb, W, H, &cam);
    lines_default();
    fl_lines_find_points(&L, &scan, NULL, &cam, 50);
    for (i = 0; i < L.n_points; i++) {
        if (L.points[i].flags & FL_LINE_POINT_VERTICAL)
            continue;
        if (abs(L.points[i].u_q1 / 2 - 80) < 3)
            in_line++;
        if (abs(L.points[i].u_q1 / 2 - 220) < 3)
            in_wide++;
    }
    CHECK(in_line >= 10);
    CHECK_EQ(in_wide, 0);
    CHECK(L.runs_rejected >= 10);
    /* without a camera both are points */
    fl_lines_find_points(&L, &scan, NULL, NULL, 50);
    in_wide = 0;
    for (i = 0; i < L.n_points; i++)
        if (!(L.points[i].flags & FL_LINE_POINT_VERTICAL) && abs(L.points[i].u_q1 / 2 - 220) < 3)
            in_wide++;
    CHECK(in_wide >= 10);
    free(rgb);
}


/* Luma points (lines.h): far away a line is a pixel tall and its color a
 * blend of paint and carpet that the class map does not call white.  A
 * frame with such a faint 1 px line across the far band, a 1 px yellow
 * line (a far goal's crossbar color) and a bright 1 px line on a grey
 * background above the field: in every pixel format the faint line gives
 * luma points (on the vertical scan lines, at its row) that make one
 * segment, the yellow and grey ones none; without the image, or with
 * luma_contrast_pct 0, there are no luma points. */
static void test_luma(void)
{
    enum { W = 320, H = 240 };
    /* FAINT: HSV S 55, above white's 49: not white in the class map */
    static const uint8_t FAINT[3] = {146, 186, 146}, YEL[3] = {186, 176, 60},
                         BACK[3] = {96, 92, 90}, BRIGHT[3] = {220, 220, 220};
    const fl_camera_model_t *m = fl_camera_model_find("nao4-top-320");
    fl_camera_pose_t pose = {450, 0, 0, 0, 0, 0, 0};
    fl_camera_t cam;
    fl_lines_params_t lp;
    uint8_t *rgb = malloc((size_t)W * H * 3);
    int k, i, f, vline = -1, vhor = -1, white = 0;
    fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422, FL_FMT_YCBCR_PLANAR};
    CHECK_EQ(fl_camera_init(&cam, m, &pose), FL_OK);
    /* the far band: rows whose projected line is 1 px tall or less */
    for (k = 0; k < W * H; k++)
        memcpy(rgb + 3 * k, CARPET, 3);
    scan_painted(rgb, W, H, &cam);
    lines_default();
    fl_lines_find_points(&L, &scan, NULL, &cam, 50);
    for (k = H - 1; k >= 0; k--) {
        int32_t w = fl_lines_width_q4(&L, k, true);
        if (w > 0 && w <= 16 && vline < 0)
            vline = k;
        if (w > 0)
            vhor = k;
    }
    CHECK(vline > 0 && vhor >= 0);
    if (vline <= 0 || vhor < 0) {
        free(rgb);
        return;
    }
    vline -= 2;
    /* background above the horizon (+3 px), a bright line on it */
    for (k = 0; k < W * (vhor + 3); k++)
        memcpy(rgb + 3 * k, BACK, 3);
    paint_rect(rgb, W, H, 0, vhor + 1, W - 1, vhor + 1, 1, BRIGHT);
    paint_rect(rgb, W, H, 20, vline, 300, vline, 1, FAINT);
    paint_rect(rgb, W, H, 20, vline + 6, 300, vline + 6, 1, YEL);
    for (f = 0; f < 3; f++) {
        scantool_frame_t fr;
        int on = 0, off = 0, seg = 0;
        CHECK_EQ(scantool_frame_from_rgb(rgb, W, H, fmts[f], &fr), 0);
        {
            fl_color_params_t cp;
            fl_scan_params_t sp;
            fl_color_params_default(&cp);
            CHECK_EQ(fl_color_init(&colors, &cp), FL_OK);
            fl_scan_params_default(&sp);
            CHECK_EQ(fl_scan_init(&scan, &sp), FL_OK);
            CHECK(fl_scan_frame(&scan, &colors, &fr.view, &cam) > 0);
        }
        /* the premise: the class map has no white on the faint line */
        for (i = 0; i < scan.cols; i++)
            if (fl_scan_class_at(&scan, i, vline / scan.params.row_step) == FL_CLASS_WHITE)
                white++;
        CHECK_EQ(white, 0);
        lines_default();
        fl_lines_find_points(&L, &scan, &fr.view, &cam, 50);
        for (i = 0; i < L.n_points; i++) {
            const fl_line_point_t *p = &L.points[i];
            if (!(p->flags & FL_LINE_POINT_LUMA))
                continue;
            if ((p->flags & FL_LINE_POINT_VERTICAL) && abs(p->v_q1 - 2 * vline) <= 1)
                on++;
            else
                off++;
        }
        CHECK_EQ(L.luma_points, on + off);
        CHECK(on >= 50);
        CHECK_EQ(off, 0);
        fl_lines_find_segments(&L, &scan);
        for (i = 0; i < L.n_segments; i++) {
            const fl_segment_t *s = &L.segments[i];
            if ((s->flags & FL_SEG_LUMA) && fabs(s->v0_q4 / 16.0 - vline) < 1 &&
                fabs(s->v1_q4 / 16.0 - vline) < 1 && seg_len(s) > 250)
                seg++;
        }
        CHECK_EQ(seg, 1);
        /* the luma ridge on the path along the line, none across the carpet */
        CHECK(fl_lines_paint_pct(&L, &scan, 16 * 40, 16 * vline, 16 * 280, 16 * vline) >= 90);
        CHECK_EQ(fl_lines_paint_pct(&L, &scan, 16 * 40, 16 * (vline + 3), 16 * 280,
                                    16 * (vline + 3)), 0);
        CHECK_EQ(fl_lines_white_pct(&scan, 16 * 40, 16 * vline, 16 * 280, 16 * vline), 0);
        /* no image, or luma off: no luma points */
        fl_lines_find_points(&L, &scan, NULL, &cam, 50);
        CHECK_EQ(L.luma_points, 0);
        fl_lines_params_default(&lp);
        lp.luma_contrast_pct = 0;
        CHECK_EQ(fl_lines_init(&L, &lp), FL_OK);
        fl_lines_find_points(&L, &scan, &fr.view, &cam, 50);
        CHECK_EQ(L.luma_points, 0);
        t_info("luma %s: %d points on the faint line, %d ridge checks", f == 0 ? "rgb" : f == 1 ? "yuyv" : "planar", on, L.ridge_checks);
        scantool_frame_free(&fr);
    }
    /* bad parameters */
    fl_lines_params_default(&lp);
    lp.luma_contrast_pct = 101;
    CHECK_EQ(fl_lines_init(&L, &lp), FL_ERR_RANGE);
    fl_lines_params_default(&lp);
    lp.luma_width_px = 0;
    CHECK_EQ(fl_lines_init(&L, &lp), FL_ERR_RANGE);
    free(rgb);
}

void suite_lines(void)
{
    t_run("lines.params", test_params);
    t_run("lines.straight", test_straight);
    t_run("lines.l_and_x", test_l_and_x);
    t_run("lines.arc", test_arc);
    t_run("lines.noise_gaps", test_noise_and_gaps);
    t_run("lines.capacity", test_capacity);
    t_run("lines.error_stop", test_error_stop);
    t_run("lines.painted", test_painted);
    t_run("lines.width_check", test_width_check);
    t_run("lines.luma", test_luma);
}
