/*
 * tools/bench/bench_coach.c - `fieldloc bench` section "coach": the
 * firmware's coach frame (fl_coach_frame, fieldloc/coach.h: jersey classes,
 * a* channel and its Otsu threshold, background difference, word-parallel
 * opening and closing, regions, a line per region, the feet through the
 * homography) against the OpenCV chain of seed 003
 * (tools/bench/bench_coach_cv.cpp: warpPerspective to a top view, inRange,
 * morphologyEx, connected components, fitLine, Lab a* + Otsu, absdiff) on
 * the same frames, both single-threaded.
 *
 * Frames (640 x 480, nao6-top-640, the default coach of
 * tools/world/coach_scene.h on spl2016): fixtures/coach/coach_two.ppm (two
 * robots) with coach_empty.ppm as the background and the homography from
 * coach.points (rendered with coach_fixture_scene when the files are
 * missing), and a class-noise frame: every pixel at random carpet, line,
 * red or blue jersey, with the same background (many small regions and
 * runs: the worst case for the region stage).  The peer's top view covers
 * the carpet at COACH_TOP_MM_PER_PX (20 mm per pixel: 521 x 371).
 * The same chain in image space is a second peer (rows ending _img):
 * the firmware's order of work (search the frame, map only the feet) in
 * OpenCV.  Seed 003's top view does not suit a coach camera at a standing
 * NAO's height: a jersey 0.3-0.45 m above the carpet, seen from 0.51 m,
 * maps 2.5-9 times as far as the robot's feet, mostly beyond the carpet,
 * so that peer finds few or no jerseys in the top view ("peer N" in the
 * row); its cost is still the chain's cost, dominated by the full-view
 * operations.
 * Rows (ns per frame, best of 7 runs, 2 with --quick):
 *   coach_frame_640x480        the frame with two robots
 *   coach_frame_640x480_img    the same, image-space peer
 *   coach_noise_640x480        the class-noise frame (and _img)
 *   coach_homog_fit_4pt        fl_homog_fit of 4 pairs (peer:
 *                              getPerspectiveTransform)
 *   coach_homog_fit_5pt        fl_homog_fit of the 5 pairs the coach sees
 *                              (no peer row: findHomography is in calib3d,
 *                              which the build does not link)
 * Instruction count: tools/bench/callgrind_coach.sh (fl_coach_frame only).
 */
#include "bench/bench.h"
#include "eval/coach_view.h"
#include "fieldloc/coach.h"
#include "io/ppm.h"
#include "world/coach_scene.h"
#include "world/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef FL_HAVE_OPENCV
void *bccv_new(const double img_to_top[9], int top_w, int top_h, const uint8_t *bg_rgb, int w,
               int h, const uint8_t red[6], const uint8_t blue[6], int open_r, int close_r,
               int min_area, int bg_diff, int image_space);
void bccv_free(void *s);
int bccv_run(void *state, const uint8_t *rgb, int w, int h, double *feet, int cap);
double bccv_perspective_4pt(const float *src, const float *dst);
#endif

static volatile int32_t bc_sink;

/* frame i of the coach fixtures: from fixtures/coach/, else rendered */
static int bc_load(int which, host_image_t *img)
{
    static const char *const files[2] = {"fixtures/coach/coach_empty.ppm",
                                         "fixtures/coach/coach_two.ppm"};
    render_scene_t sc;
    render_frame_t fr;
    char err[256];
    if (ppm_read(files[which], img, err, sizeof err) == 0)
        return 0;
    if (coach_fixture_scene(which, &sc) != 0 || render_frame(&sc, &fr) != 0)
        return -1;
    img->width = fr.width;
    img->height = fr.height;
    img->rgb = (uint8_t *)malloc(fr.size);
    if (img->rgb)
        memcpy(img->rgb, fr.rgb, fr.size);
    render_frame_free(&fr);
    return img->rgb ? 0 : -1;
}

static void bc_classnoise(const host_image_t *like, host_image_t *out)
{
    static const uint8_t pal[4][3] = {{82, 141, 85}, {254, 253, 250}, {205, 40, 45}, {40, 70, 190}};
    uint64_t s = 0x9E3779B97F4A7C15ULL;
    size_t i, n = (size_t)like->width * (size_t)like->height;
    *out = host_image_new(like->width, like->height, 0, 0, 0);
    for (i = 0; out->rgb && i < n; i++) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        /* half carpet, so the frame still has a field */
        memcpy(out->rgb + 3 * i, pal[(s & 7) < 4 ? 0 : (s & 7) - 4], 3);
    }
}

typedef struct {
    fl_coach_t *c;
    void *cv[2];   /* OpenCV chains: [0] seed 003's top view, [1] image space */
    int reps;
} bc_ctx_t;

#ifdef FL_HAVE_OPENCV
static const char *const bc_peer_desc[2] = {
    "OpenCV seed 003 chain: warpPerspective to the top view, inRange, morphologyEx, components, "
    "fitLine, Lab a* Otsu, absdiff",
    "OpenCV, same chain on the frame (no warp), feet by perspectiveTransform"};
#endif

static void bc_time_frame(bench_ctx_t *ctx, bc_ctx_t *b, const char *row, const host_image_t *img)
{
    fl_image_t view;
    static fl_coach_result_t res;
    double best = 1e300, best_cv = 0;
    int r, feet = -1;
    char desc[200];
    if (fl_image_init_packed(&view, FL_FMT_RGB888, img->rgb, img->width, img->height,
                             3 * img->width) != FL_OK)
        return;
    for (r = 0; r < b->reps; r++) {
        double t0 = bench_now_ns();
        bc_sink += (int32_t)fl_coach_frame(b->c, &view, &res);
        t0 = bench_now_ns() - t0;
        if (t0 < best)
            best = t0;
    }
    feet = res.n_feet;
#ifdef FL_HAVE_OPENCV
    {
        int k, any = 0;
        for (k = 0; k < 2; k++) {
            double f2[2 * 16];
            int n = 0;
            char name[80];
            if (!b->cv[k])
                continue;
            best_cv = 1e300;
            for (r = 0; r < b->reps; r++) {
                double t0 = bench_now_ns();
                n = bccv_run(b->cv[k], img->rgb, img->width, img->height, f2, 16);
                t0 = bench_now_ns() - t0;
                if (t0 < best_cv)
                    best_cv = t0;
            }
            snprintf(desc, sizeof desc, "feet %d / peer %d; %s", feet, n, bc_peer_desc[k]);
            snprintf(name, sizeof name, "%s%s", row, k ? "_img" : "");
            bench_row(ctx, name, best, best_cv, desc);
            any = 1;
        }
        if (any)
            return;
    }
#endif
    (void)best_cv;
    snprintf(desc, sizeof desc, "feet %d; no OpenCV peer in this build", feet);
    bench_row(ctx, row, best, 0, desc);
}

static void bc_time_fit(bench_ctx_t *ctx, const fl_homog_pair_t *p, int n, int reps)
{
    fl_homog_t h;
    double best = 1e300, best_cv = 0;
    int r, k, it = 200;
    char row[64];
    snprintf(row, sizeof row, "coach_homog_fit_%dpt", n);
    for (r = 0; r < reps; r++) {
        double t0 = bench_now_ns();
        for (k = 0; k < it; k++)
            bc_sink += (int32_t)fl_homog_fit(&h, p, (size_t)n);
        t0 = (bench_now_ns() - t0) / it;
        if (t0 < best)
            best = t0;
    }
#ifdef FL_HAVE_OPENCV
    if (n == 4) {
        float src[8], dst[8];
        for (k = 0; k < 4; k++) {
            src[2 * k] = (float)(p[k].u_q4 / 16.0);
            src[2 * k + 1] = (float)(p[k].v_q4 / 16.0);
            dst[2 * k] = (float)p[k].x_mm;
            dst[2 * k + 1] = (float)p[k].y_mm;
        }
        best_cv = 1e300;
        for (r = 0; r < reps; r++) {
            double t0 = bench_now_ns(), sink = 0;
            for (k = 0; k < it; k++)
                sink += bccv_perspective_4pt(src, dst);
            t0 = (bench_now_ns() - t0) / it;
            bc_sink += (int32_t)(sink != 0);
            if (t0 < best_cv)
                best_cv = t0;
        }
        bench_row(ctx, row, best, best_cv, "OpenCV getPerspectiveTransform (double, 4 points)");
        return;
    }
#endif
    (void)best_cv;
    bench_row(ctx, row, best, 0, n == 4 ? "no OpenCV peer in this build"
                                        : "normal equations; peer findHomography needs calib3d");
}

void bench_coach(bench_ctx_t *ctx)
{
    host_image_t empty = {0, 0, NULL}, two = {0, 0, NULL}, noise = {0, 0, NULL};
    fl_homog_pair_t pairs[COACH_POINTS_MAX];
    const fl_field_t *f = fl_field_find("spl2016");
    fl_coach_params_t cp;
    fl_homog_t h;
    fl_image_t bgv;
    bc_ctx_t b;
    char err[300];
    int n = 0;
    memset(&b, 0, sizeof b);
    b.reps = ctx->quick ? 2 : 7;
    if (bc_load(0, &empty) != 0 || bc_load(1, &two) != 0) {
        printf("coach: frames not available, section skipped\n");
        goto done;
    }
    if (coach_points_load("fixtures/coach/coach.points", f, pairs, NULL, COACH_POINTS_MAX, &n,
                          err, sizeof err) != 0) {
        render_scene_t sc;
        coach_fixture_scene(0, &sc);
        n = coach_scene_points(&sc, 0.0, 0, pairs, NULL, COACH_POINTS_MAX);
    }
    b.c = (fl_coach_t *)malloc(sizeof *b.c);
    fl_coach_params_default(&cp);
    if (!b.c || n < 4 || fl_homog_fit(&h, pairs, (size_t)n) != FL_HOMOG_OK ||
        fl_coach_init(b.c, &cp) != FL_OK || fl_coach_set_homography(b.c, &h, f) != FL_OK ||
        fl_image_init_packed(&bgv, FL_FMT_RGB888, empty.rgb, empty.width, empty.height,
                             3 * empty.width) != FL_OK ||
        fl_coach_set_background(b.c, &bgv) != FL_OK) {
        printf("coach: set-up failed, section skipped\n");
        goto done;
    }
#ifdef FL_HAVE_OPENCV
    {
        double m[9], t[9], s = COACH_TOP_MM_PER_PX, hx = fl_field_carpet_half_x_mm(f),
                           hy = fl_field_carpet_half_y_mm(f);
        uint8_t red[6], blue[6];
        int i, j, k;
        /* top-view pixel = T * field: u = (x + hx) / s, v = (hy - y) / s */
        const double T[9] = {1 / s, 0, hx / s, 0, -1 / s, hy / s, 0, 0, 1};
        coach_homog_matrix(&h, m);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) {
                t[3 * i + j] = 0;
                for (k = 0; k < 3; k++)
                    t[3 * i + j] += T[3 * i + k] * m[3 * k + j];
            }
        memcpy(red, &cp.red, 6);
        memcpy(blue, &cp.blue, 6);
        for (k = 0; k < 2; k++)
            b.cv[k] = bccv_new(t, (int)(2 * hx / s) + 1, (int)(2 * hy / s) + 1, empty.rgb,
                               empty.width, empty.height, red, blue, cp.open_radius,
                               cp.close_radius, cp.min_region_px, cp.bg_diff, k);
    }
#endif
    bc_time_frame(ctx, &b, "coach_frame_640x480", &two);
    bc_classnoise(&two, &noise);
    if (noise.rgb)
        bc_time_frame(ctx, &b, "coach_noise_640x480", &noise);
    {
        /* four of the five with no three collinear: leave out the far T
         * (on the far touchline between the two far corners) */
        fl_homog_pair_t four[4];
        int i, m = 0;
        for (i = 0; i < n && m < 4; i++)
            if (!(pairs[i].x_mm == 0 && pairs[i].y_mm > 0))
                four[m++] = pairs[i];
        if (m == 4)
            bc_time_fit(ctx, four, 4, b.reps);
    }
    bc_time_fit(ctx, pairs, n, b.reps);
done:
#ifdef FL_HAVE_OPENCV
    if (b.cv[0])
        bccv_free(b.cv[0]);
    if (b.cv[1])
        bccv_free(b.cv[1]);
#endif
    free(b.c);
    host_image_free(&empty);
    host_image_free(&two);
    host_image_free(&noise);
}
