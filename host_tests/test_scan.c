/*
 * host_tests/test_scan.c - the column scanner: painted frames with known
 * answers (border, lines, posts, contrast, caps), the rendered fixtures
 * (border against the truth files, white and yellow against re-rendered
 * class masks), lighting changes with re-centring, and the real UvA 2013
 * labels.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "io/realdata.h"
#include "world/render.h"
#include "eval/scan_tool.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static fl_color_table_t colors;
static fl_scan_t scan;

static const uint8_t CARPET[3] = {82, 141, 85}, LINE[3] = {254, 253, 250};
static const uint8_t POST[3] = {191, 185, 47}, GREY[3] = {120, 118, 125};

static void colors_default(void)
{
    fl_color_params_t p;
    fl_color_params_default(&p);
    CHECK_EQ(fl_color_init(&colors, &p), FL_OK);
}

static void scan_init(int cs, int rs)
{
    fl_scan_params_t p;
    fl_scan_params_default(&p);
    p.col_step = cs;
    p.row_step = rs;
    CHECK_EQ(fl_scan_init(&scan, &p), FL_OK);
}

static void fill(uint8_t *rgb, int w, int u0, int v0, int u1, int v1, const uint8_t c[3])
{
    int u, v;
    for (v = v0; v < v1; v++)
        for (u = u0; u < u1; u++)
            memcpy(rgb + 3 * ((size_t)v * (size_t)w + (size_t)u), c, 3);
}

/* ---- bad input ------------------------------------------------------------ */

static void test_params(void)
{
    fl_scan_params_t p;
    fl_image_t img;
    uint8_t buf[64 * 48 * 3];
    fl_scan_params_default(&p);
    CHECK_EQ(fl_scan_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_scan_init(&scan, NULL), FL_ERR_NULL);
    p.col_step = 0;
    CHECK_EQ(fl_scan_init(&scan, &p), FL_ERR_RANGE);
    fl_scan_params_default(&p);
    p.row_step = 17;
    CHECK_EQ(fl_scan_init(&scan, &p), FL_ERR_RANGE);
    fl_scan_params_default(&p);
    p.border_run_px = 0;
    CHECK_EQ(fl_scan_init(&scan, &p), FL_ERR_RANGE);
    fl_scan_params_default(&p);
    p.estimate_step_px = -1;
    CHECK_EQ(fl_scan_init(&scan, &p), FL_ERR_RANGE);
    colors_default();
    scan_init(1, 1);
    CHECK_EQ(fl_scan_frame(NULL, &colors, &img, NULL), 0);
    CHECK_EQ(fl_scan_frame(&scan, NULL, &img, NULL), 0);
    CHECK_EQ(scan.status, FL_ERR_NULL);
    CHECK_EQ(scan.width, 0);
    memset(&img, 0x5a, sizeof img);           /* garbage view */
    CHECK_EQ(fl_scan_frame(&scan, &colors, &img, NULL), 0);
    CHECK(scan.status != FL_OK);
    CHECK_EQ(fl_scan_class_at(&scan, 0, 0), FL_CLASS_OTHER);
    CHECK_EQ(fl_scan_mask_word(&scan, 0, 0, FL_CLASS_OTHER), 0);
    /* a grid larger than the capacity */
    memset(buf, 0, sizeof buf);
    fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, 48, 64 * 3);
    img.width = FL_SCAN_MAX_COLS + 2;          /* validate accepts it ... */
    img.stride[0] = 3 * img.width;
    img.height = 16;
    CHECK_EQ(fl_scan_frame(&scan, &colors, &img, NULL), 0);
    CHECK_EQ(scan.status, FL_ERR_SIZE);        /* ... the grid does not fit */
    /* an all-black frame: no border anywhere, nothing classified */
    fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, 48, 64 * 3);
    CHECK_EQ(fl_scan_frame(&scan, &colors, &img, NULL), 0);
    CHECK_EQ(scan.status, FL_OK);
    CHECK_EQ(scan.border_v[10], 48);
    CHECK_EQ(fl_scan_count(&scan, FL_CLASS_OTHER), 64 * 48);
    /* a scanner never set up (zeroed: steps 0) or with a step changed out
     * of range: FL_ERR_RANGE, an empty result, no division by zero */
    memset(&scan, 0, sizeof scan);
    CHECK_EQ(fl_scan_frame(&scan, &colors, &img, NULL), 0);
    CHECK_EQ(scan.status, FL_ERR_RANGE);
    CHECK_EQ(scan.width, 0);
    scan_init(2, 2);
    scan.params.row_step = 17;
    CHECK_EQ(fl_scan_frame(&scan, &colors, &img, NULL), 0);
    CHECK_EQ(scan.status, FL_ERR_RANGE);
    scan_init(2, 2);
    CHECK_EQ(fl_scan_frame(&scan, &colors, &img, NULL), 0);
    CHECK_EQ(scan.status, FL_OK);
}

/* ---- painted frames ----------------------------------------------------------- */

#define PW 128
#define PH 96

/* Background above a wavy border, carpet below, with a green clutter patch
 * of N - 1 rows above the border (shorter than a run) and optionally a
 * green band across the top (a run, above the horizon). */
static int painted_border(int u)
{
    return 40 + (int)lrint(10.0 * sin(u * 0.07));
}

static void paint_border_scene(uint8_t *rgb, int with_object)
{
    int u;
    fill(rgb, PW, 0, 0, PW, PH, GREY);
    for (u = 0; u < PW; u++)
        fill(rgb, PW, u, painted_border(u), u + 1, PH, CARPET);
    fill(rgb, PW, 20, 10, 40, 17, CARPET);     /* 7 rows: shorter than N = 8 */
    if (with_object)
        fill(rgb, PW, 0, 2, PW, 16, CARPET);    /* 14 rows: a run */
}

static void test_border_painted(void)
{
    static uint8_t rgb[PW * PH * 3];
    static const fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422, FL_FMT_YCBCR_PLANAR};
    uint32_t h = t_hash_init();
    int f, u, steps;
    colors_default();
    paint_border_scene(rgb, 0);
    for (f = 0; f < 3; f++)
        for (steps = 1; steps <= 2; steps++) {
            scantool_frame_t fr;
            int bad = 0, i;
            CHECK_EQ(scantool_frame_from_rgb(rgb, PW, PH, fmts[f], &fr), 0);
            scan_init(steps, steps);
            CHECK_EQ(fl_scan_frame(&scan, &colors, &fr.view, NULL), PW / steps);
            for (i = 0; i < scan.cols; i++) {
                /* YUYV pixel pairs share chroma: where the pair's two
                 * borders differ, the upper one may hold for both */
                int uu = i * steps, want = painted_border(uu), lo = want;
                if (fmts[f] == FL_FMT_YUYV422 && painted_border(uu ^ 1) < lo)
                    lo = painted_border(uu ^ 1);
                bad += scan.border_v[i] < lo || scan.border_v[i] > want;
            }
            CHECK_EQ(bad, 0);
            /* below the border: green; above: other */
            for (i = 0; i < scan.cols; i++) {
                int jb = (scan.border_v[i] + steps - 1) / steps;
                if (jb > 0)
                    CHECK_EQ(fl_scan_class_at(&scan, i, jb - 1), FL_CLASS_OTHER);
                CHECK_EQ(fl_scan_class_at(&scan, i, jb), FL_CLASS_GREEN);
                CHECK_EQ(fl_scan_class_at(&scan, i, scan.rows - 1), FL_CLASS_GREEN);
                h = t_hash_i32(h, scan.border_v[i]);
            }
            scantool_frame_free(&fr);
        }
    /* a green band across the whole width above the horizon (no neighbour
     * to tell it from the field): without a camera the board pass drops it
     * (a wall-high grey gap lies between it and the carpet that reaches the
     * bottom); ignored with a camera whose horizon lies below it */
    paint_border_scene(rgb, 1);
    {
        fl_image_t img;
        fl_camera_t cam;
        fl_camera_model_t m = *fl_camera_model_find("nao4-top-320");
        fl_camera_pose_t pose = {460, 0, 0, 0, 0, 0, 0};
        int32_t hv;
        fl_image_init_packed(&img, FL_FMT_RGB888, rgb, PW, PH, 3 * PW);
        scan_init(1, 1);
        fl_scan_frame(&scan, &colors, &img, NULL);
        CHECK_EQ(scan.border_v[50], painted_border(50));
        m.width_px = PW;
        m.height_px = PH;
        m.cx_q4 = 16 * (PW - 1) / 2;
        m.cy_q4 = 16 * 30;   /* horizon ~6 rows above: mount tilt 1.2 deg down */
        CHECK_EQ(fl_camera_init(&cam, &m, &pose), FL_OK);
        hv = fl_camera_horizon_v_q4(&cam, 16 * 64);
        t_info("painted camera: horizon row %.2f", hv / 16.0);
        CHECK(hv > 16 * 20 && hv < 16 * 30);
        fl_scan_frame(&scan, &colors, &img, &cam);
        CHECK(scan.start_v > 18 && scan.start_v <= 30);
        for (u = 0; u < PW; u++)
            CHECK_EQ(scan.border_v[u], painted_border(u));
    }
    t_digest("scan.border_painted", h);
}

/* Lines and a post on the carpet: white below the border, the yellow post
 * kept above it, the foot at its base, histograms equal to the map. */
static void test_lines_posts_painted(void)
{
    static uint8_t rgb[PW * PH * 3];
    scantool_frame_t fr;
    uint32_t h = t_hash_init();
    int i, j, f;
    colors_default();
    fill(rgb, PW, 0, 0, PW, PH, GREY);
    fill(rgb, PW, 0, 30, PW, PH, CARPET);
    fill(rgb, PW, 0, 60, PW, 64, LINE);        /* horizontal line, rows 60..63 */
    fill(rgb, PW, 40, 30, 46, PH, LINE);       /* vertical line down to the bottom */
    fill(rgb, PW, 90, 5, 96, 50, POST);        /* post standing at row 49 */
    for (f = 0; f < 2; f++) {
        CHECK_EQ(scantool_frame_from_rgb(rgb, PW, PH, f ? FL_FMT_YUYV422 : FL_FMT_RGB888, &fr), 0);
        scan_init(1, 1);
        fl_scan_frame(&scan, &colors, &fr.view, NULL);
        for (i = 0; i < PW; i++) {
            int want = i >= 90 && i < 96 ? 50 : 30;
            CHECK_EQ(scan.border_v[i], want);   /* the line columns repaired */
        }
        for (i = 0; i < PW; i++)
            for (j = 0; j < PH; j++) {
                int want = FL_CLASS_OTHER;
                if (j >= 30)
                    want = FL_CLASS_GREEN;
                if (j >= 60 && j < 64)
                    want = FL_CLASS_WHITE;
                if (j >= 30 && i >= 40 && i < 46)
                    want = FL_CLASS_WHITE;
                if (i >= 90 && i < 96 && j >= 5 && j < 50)
                    want = FL_CLASS_YELLOW;
                if (fl_scan_class_at(&scan, i, j) != (fl_color_class_t)want) {
                    t_fail_msg(__FILE__, __LINE__, "cell %d %d: %d, want %d", i, j,
                               fl_scan_class_at(&scan, i, j), want);
                    i = PW;
                    break;
                }
            }
        /* one foot per post column at its base, none elsewhere */
        CHECK_EQ(scan.n_feet, 6);
        for (i = 0; i < scan.n_feet; i++) {
            CHECK(scan.feet[i].u >= 90 && scan.feet[i].u < 96);
            CHECK_EQ(scan.feet[i].v, 50);
        }
        /* histograms = the map */
        for (i = 0; i < PW; i++) {
            int n = 0;
            for (j = 0; j < PH; j++)
                n += fl_scan_class_at(&scan, i, j) == FL_CLASS_YELLOW;
            CHECK_EQ(scan.yellow_cols[i], n);
            h = t_hash_i32(h, n);
        }
        for (j = 0; j < PH; j++) {
            int n = 0;
            for (i = 0; i < PW; i++)
                n += fl_scan_class_at(&scan, i, j) == FL_CLASS_YELLOW;
            CHECK_EQ(scan.yellow_rows[j], n);
        }
        CHECK_EQ(fl_scan_count(&scan, FL_CLASS_YELLOW), 6 * 45);
        CHECK_EQ(scan.white_rejected, 0);
        /* mask words agree with the cells */
        for (j = 0; j < PH; j++) {
            uint32_t m = fl_scan_mask_word(&scan, j, 1, FL_CLASS_WHITE);
            for (i = 0; i < 32; i++)
                CHECK_EQ((m >> (31 - i)) & 1, fl_scan_class_at(&scan, 32 + i, j) == FL_CLASS_WHITE);
        }
        scantool_frame_free(&fr);
    }
    t_digest("scan.lines_posts", h);
}

/* White decided by contrast: a grey stripe barely brighter than the carpet
 * is a white-box color but not a line; a bright one is. */
static void test_contrast(void)
{
    static uint8_t rgb[PW * PH * 3];
    static const uint8_t dull[3] = {112, 120, 114};   /* S 17, luma ~117 vs carpet 118 */
    fl_image_t img;
    int i;
    colors_default();
    CHECK_EQ(fl_color_class_rgb_exact(&colors, dull[0], dull[1], dull[2]), FL_CLASS_WHITE);
    fill(rgb, PW, 0, 0, PW, PH, GREY);
    fill(rgb, PW, 0, 20, PW, PH, CARPET);
    fill(rgb, PW, 0, 40, 64, 44, dull);
    fill(rgb, PW, 64, 40, PW, 44, LINE);
    fl_image_init_packed(&img, FL_FMT_RGB888, rgb, PW, PH, 3 * PW);
    scan_init(1, 1);
    fl_scan_frame(&scan, &colors, &img, NULL);
    for (i = 0; i < PW; i++) {
        CHECK_EQ(fl_scan_class_at(&scan, i, 41), i < 64 ? FL_CLASS_OTHER : FL_CLASS_WHITE);
        CHECK_EQ(fl_scan_class_at(&scan, i, 43), i < 64 ? FL_CLASS_OTHER : FL_CLASS_WHITE);
    }
    CHECK_EQ(scan.white_rejected, 64);
    /* the same stripe at full contrast setting 0 is kept */
    {
        fl_color_params_t p;
        fl_color_params_default(&p);
        p.white_contrast_pct = 0;
        fl_color_init(&colors, &p);
        fl_scan_frame(&scan, &colors, &img, NULL);
        CHECK_EQ(fl_scan_class_at(&scan, 10, 41), FL_CLASS_WHITE);
        CHECK_EQ(scan.white_rejected, 0);
    }
    /* bright light: carpet of luma ~215 (1.6x, G clipped), a clipped line
     * (255) is only 1.19x as bright but kept; a grey stripe of luma 240
     * (1.12x, not clipped) is still rejected */
    {
        static const uint8_t bright[3] = {150, 250, 155}, grey240[3] = {238, 241, 240};
        static const uint8_t white255[3] = {255, 255, 255};
        colors_default();
        CHECK_EQ(fl_color_class_rgb(&colors, bright[0], bright[1], bright[2]), FL_CLASS_GREEN);
        CHECK_EQ(fl_color_class_rgb(&colors, grey240[0], grey240[1], grey240[2]), FL_CLASS_WHITE);
        fill(rgb, PW, 0, 20, PW, PH, bright);
        fill(rgb, PW, 0, 40, 64, 44, grey240);
        fill(rgb, PW, 64, 40, PW, 44, white255);
        fl_scan_frame(&scan, &colors, &img, NULL);
        for (i = 0; i < PW; i += 7)
            CHECK_EQ(fl_scan_class_at(&scan, i, 42), i < 64 ? FL_CLASS_OTHER : FL_CLASS_WHITE);
        CHECK_EQ(scan.white_rejected, 64);
    }
}

/* Noise: every cap holds and the frame still ends in a valid state. */
static void test_caps_noise(void)
{
    static uint8_t rgb[320 * 240 * 3];
    static const uint8_t *pal[4] = {CARPET, LINE, POST, GREY};
    t_rng_t r;
    fl_scan_params_t p;
    int k, i, fmt;
    uint32_t h = t_hash_init();
    colors_default();
    t_rng_seed(&r, 7);
    for (k = 0; k < 320 * 240; k++)   /* random classes, runs of 1..12 rows */
        memcpy(rgb + 3 * k, pal[t_rng_range(&r, 0, 3)], 3);
    for (i = 0; i < 320; i++)
        fill(rgb, 320, i, 0, i + 1, t_rng_range(&r, 0, 40), CARPET);
    for (fmt = 0; fmt < 2; fmt++) {
        scantool_frame_t fr;
        CHECK_EQ(scantool_frame_from_rgb(rgb, 320, 240, fmt ? FL_FMT_YUYV422 : FL_FMT_RGB888, &fr), 0);
        fl_scan_params_default(&p);
        p.col_step = p.row_step = 1;
        p.border_run_px = 2;
        CHECK_EQ(fl_scan_init(&scan, &p), FL_OK);
        fl_scan_frame(&scan, &colors, &fr.view, NULL);
        CHECK_EQ(scan.status, FL_OK);
        CHECK_LE(scan.n_feet, FL_SCAN_MAX_FEET);
        CHECK(scan.feet_dropped > 0);
        CHECK(scan.checks_skipped > 0);
        for (i = 0; i < 320; i++)
            CHECK_LE(scan.col_checks[i], p.checks_per_column);
        for (i = 0; i < scan.n_feet; i++) {
            CHECK(scan.feet[i].u >= 0 && scan.feet[i].u < 320);
            CHECK(scan.feet[i].v >= 0 && scan.feet[i].v < 240);
            h = t_hash_i32(h, scan.feet[i].u * 1000 + scan.feet[i].v);
        }
        h = t_hash_i32(h, scan.n_border);
        h = t_hash_i32(h, fl_scan_count(&scan, FL_CLASS_WHITE));
        scantool_frame_free(&fr);
    }
    t_digest("scan.noise", h);
}

/* ---- rendered fixtures ------------------------------------------------------------ */

typedef struct {
    scantool_eval_t e;
    int frames;
} acc_t;

static void report(const char *what, const acc_t *a, int pixels)
{
    const scantool_eval_t *e = &a->e;
    if (pixels)
        t_info("%s: %d frames, border within 3 px %.2f%% of %ld columns, mean |err| %.3f px, max %d; "
               "white P %.4f R %.4f, yellow P %.4f R %.4f", what, a->frames,
               100.0 * (double)e->border_within3 / (double)(e->border_cols ? e->border_cols : 1),
               e->border_cols, e->border_abs_sum / (double)(e->border_cols ? e->border_cols : 1),
               e->border_max_abs, scantool_precision(e->white_tp, e->white_fp),
               scantool_recall(e->white_tp, e->white_fn), scantool_precision(e->yellow_tp, e->yellow_fp),
               scantool_recall(e->yellow_tp, e->yellow_fn));
    else
        t_info("%s: %d frames, border within 3 px %.2f%% of %ld columns, mean |err| %.3f px, max %d",
               what, a->frames,
               100.0 * (double)e->border_within3 / (double)(e->border_cols ? e->border_cols : 1),
               e->border_cols, e->border_abs_sum / (double)(e->border_cols ? e->border_cols : 1),
               e->border_max_abs);
}

/* Accuracy targets of the scanner.  Quick mode (qemu) scores a few frames
 * only: there the numbers are reported and the digests compared, the
 * targets are checked on the full sets. */
static void check_border(const acc_t *a)
{
    if (t_quick)
        return;
    CHECK(a->e.border_cols > 0);
    CHECK_LE(0.98, (double)a->e.border_within3 / (double)a->e.border_cols);
    CHECK_LE(a->e.border_abs_sum / (double)a->e.border_cols, 1.0);
}

static void check_pixels(const acc_t *a)
{
    const scantool_eval_t *e = &a->e;
    if (t_quick)
        return;
    CHECK(e->white_tp > 1000);
    CHECK(e->yellow_tp > 100);
    CHECK_LE(0.95, scantool_precision(e->white_tp, e->white_fp));
    CHECK_LE(0.95, scantool_recall(e->white_tp, e->white_fn));
    CHECK_LE(0.95, scantool_precision(e->yellow_tp, e->yellow_fp));
    CHECK_LE(0.95, scantool_recall(e->yellow_tp, e->yellow_fn));
}

/* Fixtures with yellow goals and the green carpet (spl2013, uva2013). */
static int fixture_names(char names[][64], int max)
{
    FILE *f = fopen("fixtures/frames/index.txt", "r");
    char line[512];
    int n = 0;
    if (!f)
        return 0;
    while (fgets(line, sizeof line, f) && n < max) {
        char name[64], file[64], fmt[16], field[32];
        if (line[0] == '#' || sscanf(line, "%63s %63s %15s %31s", name, file, fmt, field) != 4)
            continue;
        if (strcmp(field, "spl2013") && strcmp(field, "uva2013"))
            continue;
        snprintf(names[n++], 64, "%s", name);
    }
    fclose(f);
    return n;
}

/* Scan a fixture frame as stored (its own format), both grids; a truth
 * (for the border) always, a re-rendered class mask when `pixels`. */
static void scan_fixture(const char *name, int pixels, acc_t *full, acc_t *grid,
                         uint32_t *h)
{
    char path[256], err[256];
    render_scene_t sc;
    render_frame_t fr;
    static truth_t truth;
    int k, u;
    snprintf(path, sizeof path, "fixtures/frames/%s.scene", name);
    if (render_scene_load(path, &sc, err, sizeof err) != 0) {
        t_fail_msg(__FILE__, __LINE__, "%s", err);
        return;
    }
    if (pixels) {
        if (render_frame(&sc, &fr) != 0) {
            t_fail_msg(__FILE__, __LINE__, "render %s", name);
            return;
        }
    } else {
        snprintf(path, sizeof path, "fixtures/frames/%s.%s", name,
                 sc.format == FL_FMT_RGB888 ? "ppm" : "raw");
        if (render_read_frame(path, &fr, err, sizeof err) != 0) {
            t_fail_msg(__FILE__, __LINE__, "%s", err);
            return;
        }
        snprintf(path, sizeof path, "fixtures/frames/%s.truth", name);
        if (truth_load(path, &truth, err, sizeof err) != 0) {
            t_fail_msg(__FILE__, __LINE__, "%s", err);
            render_frame_free(&fr);
            return;
        }
        fr.border_v = truth.border_v;
        fr.border_visible_v = truth.border_visible_v;
    }
    for (k = 0; k < 2; k++) {
        fl_camera_t cam;
        acc_t *a = k ? grid : full;
        scan_init(k ? 2 : 1, k ? 2 : 1);
        CHECK_EQ(render_scene_camera(&sc, &cam), FL_OK);
        fl_scan_frame(&scan, &colors, &fr.view, &cam);
        if (pixels) {
            scantool_evaluate(&scan, &fr, &a->e);
        } else {   /* border only: no mask */
            scantool_eval_t e;
            memset(&e, 0, sizeof e);
            for (u = 0; u < scan.cols; u++) {
                int tb = fr.border_visible_v[u * scan.params.col_step], err2;
                if (tb >= fr.height)
                    continue;
                err2 = abs(scan.border_v[u] - tb);
                a->e.border_cols++;
                a->e.border_within3 += err2 <= 3;
                a->e.border_abs_sum += err2;
                if (err2 > a->e.border_max_abs)
                    a->e.border_max_abs = err2;
            }
        }
        a->frames++;
        for (u = 0; u < scan.cols; u++)
            *h = t_hash_i32(*h, scan.border_v[u]);
        *h = t_hash_i32(*h, fl_scan_count(&scan, FL_CLASS_WHITE));
        *h = t_hash_i32(*h, fl_scan_count(&scan, FL_CLASS_YELLOW));
    }
    if (!pixels) {
        fr.border_v = fr.border_visible_v = NULL;  /* owned by truth */
    }
    render_frame_free(&fr);
}

static void test_fixtures_border(void)
{
    static char names[128][64];
    int n = fixture_names(names, 128), k;
    acc_t full, grid;
    uint32_t h = t_hash_init();
    if (n == 0) {
        t_info("scan.fixtures_border: skipped, fixtures/frames/index.txt not found");
        return;
    }
    colors_default();
    memset(&full, 0, sizeof full);
    memset(&grid, 0, sizeof grid);
    for (k = 0; k < n; k += t_quick ? 8 : 1)
        scan_fixture(names[k], 0, &full, &grid, &h);
    report("fixtures (spl2013, uva2013), full resolution", &full, 0);
    report("fixtures (spl2013, uva2013), 2x2 grid", &grid, 0);
    check_border(&full);
    check_border(&grid);
    t_digest("scan.fixtures_border", h);
}

static void test_fixtures_pixels(void)
{
    static char names[128][64];
    int n = fixture_names(names, 128), k, step;
    acc_t full, grid;
    uint32_t h = t_hash_init();
    if (n == 0) {
        t_info("scan.fixtures_pixels: skipped, fixtures/frames/index.txt not found");
        return;
    }
    colors_default();
    memset(&full, 0, sizeof full);
    memset(&grid, 0, sizeof grid);
    /* re-rendering costs ~50 ms a frame: every 3rd fixture normally, all
     * with --exhaustive, every 12th under --quick */
    step = t_exhaustive ? 1 : (t_quick ? 12 : 3);
    for (k = 0; k < n; k += step)
        scan_fixture(names[k], 1, &full, &grid, &h);
    report("fixtures re-rendered, full resolution", &full, 1);
    report("fixtures re-rendered, 2x2 grid", &grid, 1);
    /* the border is checked on every fixture in scan.fixtures_border */
    check_pixels(&full);
    check_pixels(&grid);
    t_digest("scan.fixtures_pixels", h);
}

/* ---- lighting ------------------------------------------------------------------------ */

/* Render scenes at gains 50..160 % and hue shifts of -8..+8 (applied to the
 * rendered RGB: the renderer has no hue control), scan, re-centre with
 * fl_color_adapt, scan again; accuracy after adaptation. */
static void test_lighting(void)
{
    static const char *scenes[] = {"spl2013_goal_both", "uva2013_qvga_000001", "spl2013_x_far"};
    static const int gains[] = {50, 70, 100, 130, 160};
    static const int shifts[] = {-8, 0, 8};
    static const char *gain_names[] = {"  after re-centring, gain 50 %", "  after re-centring, gain 70 %",
                                       "  after re-centring, gain 100 %", "  after re-centring, gain 130 %",
                                       "  after re-centring, gain 160 %"};
    acc_t before, after, per_gain[5];
    int s, g, d, ns = t_quick ? 1 : 3, ng = t_quick ? 2 : 5;
    uint32_t h = t_hash_init();
    char path[256], err[256];
    memset(&before, 0, sizeof before);
    memset(&after, 0, sizeof after);
    memset(per_gain, 0, sizeof per_gain);
    for (s = 0; s < ns; s++) {
        render_scene_t sc;
        snprintf(path, sizeof path, "fixtures/frames/%s.scene", scenes[s]);
        if (render_scene_load(path, &sc, err, sizeof err) != 0) {
            t_info("scan.lighting: skipped, %s", err);
            return;
        }
        sc.format = FL_FMT_RGB888;
        for (g = 0; g < ng; g++) {
            render_frame_t fr;
            fl_camera_t cam;
            sc.gain_pct = gains[t_quick ? 4 * g : g];
            if (render_frame(&sc, &fr) != 0) {
                t_fail_msg(__FILE__, __LINE__, "render");
                return;
            }
            render_scene_camera(&sc, &cam);
            for (d = 0; d < 3; d++) {
                scantool_frame_t yuyv;
                uint8_t *rgb = malloc((size_t)fr.width * (size_t)fr.height * 3);
                fl_image_t view;
                memcpy(rgb, fr.rgb, (size_t)fr.width * (size_t)fr.height * 3);
                scantool_hue_shift(rgb, (size_t)fr.width * (size_t)fr.height, shifts[d]);
                fl_image_init_packed(&view, FL_FMT_RGB888, rgb, fr.width, fr.height, 3 * fr.width);
                scantool_frame_from_rgb(rgb, fr.width, fr.height, FL_FMT_YUYV422, &yuyv);
                colors_default();
                scan_init(1, 1);
                scan.field.n = 0;
                fl_scan_frame(&scan, &colors, (d & 1) ? &yuyv.view : &view, &cam);
                scantool_evaluate(&scan, &fr, &before.e);
                before.frames++;
                /* re-centre (at most twice: the estimate of a shifted frame
                 * comes from the part of the carpet the old box found) */
                if (fl_color_adapt(&colors, &scan.field) == 1) {
                    fl_scan_frame(&scan, &colors, (d & 1) ? &yuyv.view : &view, &cam);
                    if (fl_color_adapt(&colors, &scan.field) == 1)
                        fl_scan_frame(&scan, &colors, (d & 1) ? &yuyv.view : &view, &cam);
                }
                scantool_evaluate(&scan, &fr, &after.e);
                scantool_evaluate(&scan, &fr, &per_gain[g].e);
                after.frames++;
                per_gain[g].frames++;
                h = t_hash_i32(h, colors.hue_shift);
                h = t_hash_i32(h, scan.n_border);
                scantool_frame_free(&yuyv);
                free(rgb);
            }
            render_frame_free(&fr);
        }
    }
    for (g = 0; g < ng; g++)
        report(gain_names[g], &per_gain[g], 1);
    report("lighting gain 50..160 %, hue -8/0/+8, before re-centring", &before, 1);
    report("lighting gain 50..160 %, hue -8/0/+8, after re-centring", &after, 1);
    check_border(&after);
    /* The target: white precision and recall >= 0.95 under every
     * lighting.  At gain 160 % the lines clip and their blurred edges clip
     * to near-white; the per-frame white level (fl_color_white_cap) and the
     * exact RGB path at the white/green boundary hold precision there.
     * White s_hi is a trade between precision and recall (color.h): the
     * default 48 meets the precision target and misses the recall target
     * slightly, so recall has a floor just under 0.95 set by that trade
     * (0.955, checked below).  What is lost is thin far lines
     * (spl2013_x_far) and YUYV's shared chroma at vertical line edges. */
    if (!t_quick) {
        const scantool_eval_t *e = &after.e;
        double wp = scantool_precision(e->white_tp, e->white_fp);
        CHECK(e->white_tp > 1000);
        CHECK(e->yellow_tp > 100);
        CHECK_LE(0.95, wp);                                   /* the target */
        CHECK_LE(0.94, scantool_precision(per_gain[4].e.white_tp, per_gain[4].e.white_fp));
        CHECK_LE(0.955, scantool_recall(e->white_tp, e->white_fn));  /* floor */
        CHECK_LE(0.95, scantool_recall(e->white_tp, e->white_fn));
        CHECK_LE(0.95, scantool_precision(e->yellow_tp, e->yellow_fp));
        CHECK_LE(0.95, scantool_recall(e->yellow_tp, e->yellow_fn));
        if (wp < 0.95)
            t_info("TARGET NOT MET: white precision under lighting %.3f < 0.95 (short by %.3f)",
                   wp, 0.95 - wp);
    }
    t_digest("scan.lighting", h);
}

/* ---- the real UvA 2013 frames ----------------------------------------------------------- */

/* Every labelled crossing (X, L, T) and post foot (G) of the UvA 2013
 * frames (labels +-2 px): below the detected border (crossings: v >= border
 * of their column - 2; feet: a post occludes the carpet behind it, so the
 * border of its own column is the foot itself or just below it, and the
 * foot is compared with the highest border within 8 columns, the carpet
 * edge next to the post), and on white (crossings: a white cell within
 * 2 px) or yellow (feet: a yellow cell within 3 px above, or a foot
 * candidate within 4 px).  The counts are reported; the spec sets no
 * threshold on real data: the checks (80 %) only catch regressions. */
static void test_realdata(void)
{
    const char *dir = rd_dir();
    char path[4096], err[256];
    rd_uva_set_t set;
    const fl_camera_model_t *m = fl_camera_model_find("uva2013");
    int k, nframes = 0, nx = 0, nx_below = 0, nx_white = 0, ng = 0, ng_below = 0;
    int ng_own = 0, ng_yellow = 0;
    if (!dir) {
        t_info("scan.realdata %s", rd_skip_message());
        return;
    }
    colors_default();
    scan_init(1, 1);
    CHECK(m != NULL);
    CHECK_EQ(rd_path(path, sizeof path, dir, RD_UVA_CSV), 0);
    if (rd_uva_load(path, &set, err, sizeof err) != 0) {
        t_fail_msg(__FILE__, __LINE__, "%s", err);
        return;
    }
    for (k = 0; k < set.n; k++) {
        const rd_uva_record_t *r = &set.rec[k];
        host_image_t im;
        fl_image_t view;
        fl_camera_pose_t pose;
        fl_camera_t cam;
        int f;
        if (rd_read_ppm(dir, r->file, &im, err, sizeof err) != 0)
            continue;
        nframes++;
        rd_image_view(&im, &view);
        rd_uva_camera_pose(r, m, &pose);
        CHECK_EQ(fl_camera_init(&cam, m, &pose), FL_OK);
        fl_scan_frame(&scan, &colors, &view, &cam);
        for (f = 0; f < r->n_features; f++) {
            const rd_feature_t *a = &r->feat[f];
            int u = (int)lrint(a->u), v = (int)lrint(a->v), du, dv, hit = 0, i;
            if (u < 0 || u >= im.width || v < 0 || v >= im.height)
                continue;
            if (a->type == 'X' || a->type == 'L' || a->type == 'T') {
                for (dv = -2; dv <= 2; dv++)
                    for (du = -2; du <= 2; du++)
                        hit |= fl_scan_class_at(&scan, u + du, v + dv) == FL_CLASS_WHITE;
                nx++;
                nx_below += v >= scan.border_v[u] - 2;
                nx_white += hit;
                if (v < scan.border_v[u] - 2 || !hit)
                    t_info("  %c at (%d, %d) of %s: border %d, white %d", a->type, u, v,
                           r->file + 30, scan.border_v[u], hit);
            } else if (a->type == 'G') {
                int edge = im.height;   /* the carpet edge: the highest border */
                for (i = u - 8; i <= u + 8; i++)
                    if (i >= 0 && i < im.width && scan.border_v[i] < edge)
                        edge = scan.border_v[i];
                for (dv = -3; dv <= 0; dv++)
                    for (du = -2; du <= 2; du++)
                        hit |= fl_scan_class_at(&scan, u + du, v + dv) == FL_CLASS_YELLOW;
                for (i = 0; i < scan.n_feet; i++)
                    hit |= abs(scan.feet[i].u - u) <= 4 && abs(scan.feet[i].v - v) <= 4;
                ng++;
                ng_own += v >= scan.border_v[u] - 2;
                ng_below += v >= edge - 2;
                ng_yellow += hit;
                if (!hit) t_info("  G at (%d, %d) of %s: border %d, no yellow", u, v, r->file + 30, scan.border_v[u]);
            }
        }
        host_image_free(&im);
    }
    rd_uva_free(&set);
    t_info("UvA 2013 (%d frames): crossings %d: below the border %d, on white %d; "
           "post feet %d: below the border next to the post %d (of their own column %d), "
           "on yellow %d", nframes, nx, nx_below, nx_white, ng, ng_below, ng_own, ng_yellow);
    CHECK(nx > 80 && ng > 20);
    CHECK_LE(0.8 * nx, nx_below);
    CHECK_LE(0.8 * nx, nx_white);
    CHECK_LE(0.8 * ng, ng_below);
    CHECK_LE(0.8 * ng, ng_yellow);
}

/* ---- golden scanner outputs -------------------------------------------------------
 * Every output of fl_scan_frame (border, the whole class map, yellow
 * histograms, feet, field-color estimate, counters) over every fixture
 * frame in all three pixel formats (RGB888, YUYV, planar YCbCr, converted
 * from the stored frame with the BT.601 integers of src/base/image.c), on
 * several grids (full resolution, the default 2x2, 3x1, 1x3, 4x4), with
 * the fixture's camera and without one, with capped and uncapped
 * per-column work, and with the default and a re-centred color table.
 * One line per fixture in fixtures/golden/scan.txt: NAME 0xRGB 0xYUYV
 * 0xPLANAR (FNV-1a of integers, identical on every architecture).  The
 * vision goldens see the default grid only; this one pins the full
 * resolution paths the speed work changes.  Rewritten by
 * FIELDLOC_WRITE_GOLDEN=1 build/run_tests -k scan.outputs_golden (make
 * golden). */
#define SCAN_GOLDEN "fixtures/golden/scan.txt"

static uint32_t hash_scan_outputs(uint32_t h, const fl_scan_t *s)
{
    int32_t i, j, w;
    h = t_hash_i32(h, (int32_t)s->status);
    h = t_hash_i32(h, s->width);
    h = t_hash_i32(h, s->height);
    h = t_hash_i32(h, s->cols);
    h = t_hash_i32(h, s->rows);
    h = t_hash_i32(h, s->words);
    h = t_hash_i32(h, s->start_v);
    h = t_hash_i32(h, s->below_horizon);
    h = t_hash_i32(h, s->n_border);
    for (i = 0; i < s->cols; i++) {
        h = t_hash_i32(h, s->border_v[i]);
        h = t_hash_i32(h, s->yellow_cols[i]);
    }
    for (j = 0; j < s->rows; j++) {
        h = t_hash_i32(h, s->yellow_rows[j]);
        for (w = 0; w < s->words; w++) {
            h = t_hash_i32(h, (int32_t)(uint32_t)(s->map[j][w] >> 32));
            h = t_hash_i32(h, (int32_t)(uint32_t)s->map[j][w]);
        }
    }
    h = t_hash_i32(h, s->n_feet);
    for (i = 0; i < s->n_feet; i++) {
        h = t_hash_i32(h, s->feet[i].u);
        h = t_hash_i32(h, s->feet[i].v);
    }
    h = t_hash_i32(h, s->field.n);
    h = t_hash_i32(h, s->field.hue);
    h = t_hash_i32(h, s->field.sat);
    h = t_hash_i32(h, s->field.val);
    h = t_hash_i32(h, s->field.luma);
    h = t_hash_i32(h, s->feet_dropped);
    h = t_hash_i32(h, s->checks_skipped);
    return t_hash_i32(h, s->white_rejected);
}

/* The hash of one frame in one format over every configuration. */
static uint32_t scan_configs(const fl_image_t *img, const fl_camera_t *cam,
                             const fl_color_table_t *adapted)
{
    static const int grids[][2] = {{1, 1}, {2, 2}, {3, 1}, {1, 3}, {4, 4}};
    uint32_t h = t_hash_init();
    size_t g;
    int k;
    for (g = 0; g < sizeof grids / sizeof grids[0]; g++)
        for (k = 0; k < 5; k++) {
            fl_scan_params_t p;
            const fl_color_table_t *ct = k == 4 ? adapted : &colors;
            fl_scan_params_default(&p);
            p.col_step = grids[g][0];
            p.row_step = grids[g][1];
            if (k == 2) {   /* short runs, tight caps */
                p.border_run_px = 3;
                p.feet_per_column = 1;
                p.checks_per_column = 2;
                p.estimate_step_px = 7;
            } else if (k == 3) {   /* long runs, no field-color samples */
                p.border_run_px = 24;
                p.horizon_margin_px = 0;
                p.estimate_step_px = 0;
            }
            CHECK_EQ(fl_scan_init(&scan, &p), FL_OK);
            fl_scan_frame(&scan, ct, img, k == 1 ? NULL : cam);
            h = hash_scan_outputs(h, &scan);
        }
    return h;
}

/* The golden line of one frame: its scanner outputs over every
 * configuration (scan_configs) in each of the three formats. */
static void golden_line(const uint8_t *rgb, int w, int h, const fl_camera_t *cam,
                        const fl_color_table_t *adapted, const char *name, char *got,
                        size_t size, uint32_t *all)
{
    static const fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422, FL_FMT_YCBCR_PLANAR};
    uint32_t fh[3];
    int f;
    for (f = 0; f < 3; f++) {
        scantool_frame_t conv;
        fh[f] = 0;
        if (scantool_frame_from_rgb(rgb, w, h, fmts[f], &conv) != 0) {
            t_fail_msg(__FILE__, __LINE__, "%s: format %d", name, f);
            continue;
        }
        fh[f] = scan_configs(&conv.view, cam, adapted);
        *all = t_hash_i32(*all, (int32_t)fh[f]);
        scantool_frame_free(&conv);
    }
    snprintf(got, size, "%s 0x%08lx 0x%08lx 0x%08lx", name, (unsigned long)fh[0],
             (unsigned long)fh[1], (unsigned long)fh[2]);
}

static void test_outputs_golden(void)
{
    static fl_color_table_t adapted;
    t_golden_lines_t gold;
    FILE *idx = fopen("fixtures/frames/index.txt", "r");
    char line[512], got[256];
    uint32_t all = t_hash_init();
    int k = 0;
    if (!idx) {
        t_info("scan.outputs_golden: skipped, fixtures/frames/index.txt not found");
        return;
    }
    colors_default();
    t_golden_lines_begin(&gold, SCAN_GOLDEN,
                         "# every output of fl_scan_frame over every fixture frame, 5 grids x 5 "
                         "configurations\n# (host_tests/test_scan.c, test_outputs_golden): NAME "
                         "0xRGB888 0xYUYV 0xPLANAR\n",
                         "scan.outputs_golden");
    while (fgets(line, sizeof line, idx)) {
        char name[64], file[64], fmt[16], field[32], path[256], err[256];
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        uint8_t *rgb;
        int n, u, v;
        if (line[0] == '#' || sscanf(line, "%63s %63s %15s %31s", name, file, fmt, field) != 4)
            continue;
        if (t_quick && k++ % 8 != 0)
            continue;
        snprintf(path, sizeof path, "fixtures/frames/%s.scene", name);
        if (render_scene_load(path, &sc, err, sizeof err) != 0 ||
            render_scene_camera(&sc, &cam) != FL_OK) {
            t_fail_msg(__FILE__, __LINE__, "%s: %s", name, err);
            continue;
        }
        snprintf(path, sizeof path, "fixtures/frames/%s", file);
        if (render_read_frame(path, &fr, err, sizeof err) != 0) {
            t_fail_msg(__FILE__, __LINE__, "%s", err);
            continue;
        }
        n = fr.width * fr.height;
        rgb = malloc((size_t)n * 3);
        CHECK(rgb != NULL);
        if (!rgb) {
            render_frame_free(&fr);
            continue;
        }
        for (v = 0; v < fr.height; v++)
            for (u = 0; u < fr.width; u++)
                fl_image_get_rgb(&fr.view, u, v, rgb + 3 * ((size_t)v * (size_t)fr.width + (size_t)u));
        /* the re-centred table: the field color the default scan estimated */
        scan_init(2, 2);
        fl_scan_frame(&scan, &colors, &fr.view, &cam);
        adapted = colors;
        fl_color_adapt(&adapted, &scan.field);
        golden_line(rgb, fr.width, fr.height, &cam, &adapted, name, got, sizeof got, &all);
        t_golden_lines_check(&gold, name, got);
        free(rgb);
        render_frame_free(&fr);
    }
    fclose(idx);
    CHECK(gold.n > 0);
    if (!gold.out)
        t_info("scanner outputs of %d fixture frames x 3 formats x 25 configurations: %d of %d "
               "identical to %s", gold.n, gold.same, gold.n, SCAN_GOLDEN);
    t_golden_lines_end(&gold);
    t_digest("scan.outputs_golden", all);
}

/* Frames with sparse green, where the first green sample of a column is
 * seldom the start of a run: phase A must not skip a run (and its test
 * classifies rows around the sampled one only while some column is still
 * green).  Pixel classes at random with carpet at p %, the rest line, post,
 * grey or a uniform random color; then 60 vertical carpet stretches of
 * 1..24 rows; p = 0 is the bench's worst case (uniform noise).  Their
 * outputs over 3 formats x 25 configurations are pinned in SPARSE_GOLDEN
 * (written by the scanner before the run test in phase A). */
#define SPARSE_GOLDEN "fixtures/golden/scan_sparse.txt"

static void sparse_frame(uint8_t *rgb, int w, int h, int pct, uint32_t seed)
{
    static const uint8_t *pal[3] = {LINE, POST, GREY};
    t_rng_t r;
    int k, i;
    t_rng_seed(&r, seed);
    for (k = 0; k < w * h; k++) {
        uint8_t *q = rgb + 3 * k;
        if (pct == 0 || t_rng_range(&r, 0, 99) >= pct) {
            if (pct == 0 || t_rng_range(&r, 0, 3) == 3) {
                uint32_t x = t_rng_u32(&r);
                q[0] = (uint8_t)x;
                q[1] = (uint8_t)(x >> 8);
                q[2] = (uint8_t)(x >> 16);
            } else {
                memcpy(q, pal[t_rng_range(&r, 0, 2)], 3);
            }
        } else {
            memcpy(q, CARPET, 3);
        }
    }
    for (i = 0; i < (pct == 0 ? 0 : 60); i++) {
        int u = t_rng_range(&r, 0, w - 1), v = t_rng_range(&r, 0, h - 1);
        int len = t_rng_range(&r, 1, 24);
        fill(rgb, w, u, v, u + 1, v + len < h ? v + len : h, CARPET);
    }
}

static void test_sparse_golden(void)
{
    static const int pcts[] = {0, 5, 15, 30, 50, 70};
    static uint8_t rgb[320 * 240 * 3];
    static fl_color_table_t adapted;
    t_golden_lines_t gold;
    uint32_t all = t_hash_init();
    int pi, seed;
    fl_camera_t cam;
    render_scene_t sc;
    char err[256];
    colors_default();
    /* a level top camera: the horizon inside the image (j0 > 0; the
     * configuration without a camera starts at row 0) */
    if (render_scene_load("fixtures/frames/spl2013_goal_both.scene", &sc, err, sizeof err) != 0 ||
        render_scene_camera(&sc, &cam) != FL_OK) {
        t_info("scan.sparse_golden: skipped, %s", err);
        return;
    }
    t_golden_lines_begin(&gold, SPARSE_GOLDEN,
                         "# every output of fl_scan_frame on frames with sparse green, 5 grids x 5 "
                         "configurations\n# (host_tests/test_scan.c, test_sparse_golden): NAME "
                         "0xRGB888 0xYUYV 0xPLANAR\n",
                         "scan.sparse_golden");
    for (pi = 0; pi < (int)(sizeof pcts / sizeof pcts[0]); pi++)
        for (seed = 1; seed <= 2; seed++) {
            char name[64], got[256];
            fl_image_t img;
            if (t_quick && seed == 2)
                continue;
            sparse_frame(rgb, 320, 240, pcts[pi], (uint32_t)(100 * pcts[pi] + seed));
            /* the re-centred table, as test_outputs_golden (no camera) */
            fl_image_init_packed(&img, FL_FMT_RGB888, rgb, 320, 240, 320 * 3);
            scan_init(2, 2);
            fl_scan_frame(&scan, &colors, &img, NULL);
            adapted = colors;
            fl_color_adapt(&adapted, &scan.field);
            snprintf(name, sizeof name, "sparse_p%02d_s%d", pcts[pi], seed);
            golden_line(rgb, 320, 240, &cam, &adapted, name, got, sizeof got, &all);
            t_golden_lines_check(&gold, name, got);
        }
    if (!gold.out)
        t_info("scanner outputs of %d sparse-green frames x 3 formats x 25 configurations: %d of "
               "%d identical to %s", gold.n, gold.same, gold.n, SPARSE_GOLDEN);
    t_golden_lines_end(&gold);
    t_digest("scan.sparse_golden", all);
}

void suite_scan(void)
{
    t_run("scan.params", test_params);
    t_run("scan.border_painted", test_border_painted);
    t_run("scan.lines_posts_painted", test_lines_posts_painted);
    t_run("scan.contrast", test_contrast);
    t_run("scan.caps_noise", test_caps_noise);
    t_run("scan.fixtures_border", test_fixtures_border);
    t_run("scan.fixtures_pixels", test_fixtures_pixels);
    t_run("scan.lighting", test_lighting);
    t_run("scan.realdata", test_realdata);
    t_run("scan.outputs_golden", test_outputs_golden);
    t_run("scan.sparse_golden", test_sparse_golden);
}
