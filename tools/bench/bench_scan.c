/*
 * tools/bench/bench_scan.c - `fieldloc bench` section "scan": the column scanner
 * against the OpenCV chain on the same frames, single-threaded both.
 *
 * fieldloc side: fl_scan_frame (tables built beforehand) on the frame in
 *   the named format; output = border per grid column, the 2-bit class map
 *   below the border (+ post yellow above it), yellow histograms, feet,
 *   field color.  "full" = every pixel (step 1 1), "default" = the 2 x 2
 *   grid the later stages use.
 * OpenCV side (cvpeer_chain_run): cvtColor(YUV2RGB_YUYV) for YUYV input,
 *   cvtColor(RGB2HSV), inRange for green, white and yellow (three full
 *   masks, same boxes), first run of N green mask pixels per column.
 * memcpy rows: one memcpy of the frame's bytes (the floor of any pass).
 * Frames: real = UvA 2013 qvga_000001 (320x240) and physar black1_point1
 *   top (640x480, NAO v6, white goals, sunlight); rendered = the fixture
 *   scenes spl2013_goal_both (320) and spl2013_640_goal (640); noise =
 *   uniform random RGB (every pixel its own class: the worst case for
 *   runs, checks and feet; no column has a run of N green pixels, so the
 *   border search ends early and little is classified) and "classnoise"
 *   (random carpet / line / post colors per pixel), and "topnoise":
 *   12 rows of carpet at the top, uniform noise below (every column has
 *   its border in row 0, so every pixel below is classified and checked:
 *   the worst case of the scanner).
 * Times: ns per frame, best of 7 interleaved rounds (1 with --quick; see
 * bench_frame).
 */
#include "eval/scan_tool.h"

#include "io/ppm.h"
#include "io/realdata.h"
#include "bench/bench.h"
#ifdef FL_HAVE_OPENCV
#include "bench/cv_peer.h"
#endif

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static fl_color_table_t bench_colors;
static volatile int32_t bench_sink;

typedef struct {
    char name[32];
    int w, h;
    uint8_t *rgb;        /* malloc'd */
} bench_frame_t;

static int load_real(bench_frame_t *f, const char *name, const char *file)
{
    const char *dir = rd_dir();
    host_image_t im;
    char err[256];
    if (!dir || rd_read_ppm(dir, file, &im, err, sizeof err) != 0)
        return -1;
    snprintf(f->name, sizeof f->name, "%s", name);
    f->w = im.width;
    f->h = im.height;
    f->rgb = im.rgb;
    return 0;
}

static int load_rendered(bench_frame_t *f, const char *name, const char *scene)
{
    render_scene_t sc;
    render_frame_t fr;
    char err[256];
    if (render_scene_load(scene, &sc, err, sizeof err) != 0)
        return -1;
    sc.format = FL_FMT_RGB888;
    if (render_frame(&sc, &fr) != 0)
        return -1;
    snprintf(f->name, sizeof f->name, "%s", name);
    f->w = fr.width;
    f->h = fr.height;
    f->rgb = malloc((size_t)fr.width * (size_t)fr.height * 3);
    if (f->rgb)
        memcpy(f->rgb, fr.rgb, (size_t)fr.width * (size_t)fr.height * 3);
    render_frame_free(&fr);
    return f->rgb ? 0 : -1;
}

static int make_noise(bench_frame_t *f, const char *name, int w, int h, int classes)
{
    static const uint8_t pal[4][3] = {{82, 141, 85}, {254, 253, 250}, {191, 185, 47}, {90, 60, 40}};
    uint64_t s = 0x9E3779B97F4A7C15ULL;
    size_t i, n = (size_t)w * (size_t)h;
    snprintf(f->name, sizeof f->name, "%s", name);
    f->w = w;
    f->h = h;
    f->rgb = malloc(n * 3);
    if (!f->rgb)
        return -1;
    for (i = 0; i < n; i++) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        if (classes == 2 && i < (size_t)w * 12)
            memcpy(f->rgb + 3 * i, pal[0], 3);   /* the carpet strip */
        else if (classes == 1)
            memcpy(f->rgb + 3 * i, pal[s & 3], 3);
        else {
            f->rgb[3 * i] = (uint8_t)s;
            f->rgb[3 * i + 1] = (uint8_t)(s >> 8);
            f->rgb[3 * i + 2] = (uint8_t)(s >> 16);
        }
    }
    return 0;
}

/* ns per call of fn, best of reps batches of n calls */
#define BENCH_TIME(result, reps, n, stmt)                                         \
    do {                                                                          \
        int r_, k_;                                                               \
        double best_ = 1e300;                                                     \
        for (r_ = 0; r_ < (reps); r_++) {                                         \
            double t0_ = bench_now_ns();                                          \
            for (k_ = 0; k_ < (n); k_++) {                                        \
                stmt;                                                             \
            }                                                                     \
            t0_ = (bench_now_ns() - t0_) / (n);                                   \
            if (t0_ < best_)                                                      \
                best_ = t0_;                                                      \
        }                                                                         \
        (result) = best_;                                                         \
    } while (0)

#ifdef FL_HAVE_OPENCV
static void boxes_of(const fl_color_table_t *t, uint8_t boxes[3][6])
{
    const fl_hsv_box_t *b[3];
    int k;
    b[0] = &t->green;
    b[1] = &t->white;
    b[2] = &t->yellow;
    for (k = 0; k < 3; k++) {
        boxes[k][0] = b[k]->h_lo;
        boxes[k][1] = b[k]->h_hi;
        boxes[k][2] = b[k]->s_lo;
        boxes[k][3] = b[k]->s_hi;
        boxes[k][4] = b[k]->v_lo;
        boxes[k][5] = b[k]->v_hi;
    }
}
#endif

/* One batch of n calls of stmt, ns per call; best kept in *best. */
#define BENCH_BATCH(best, n, stmt)                                                \
    do {                                                                          \
        int k_;                                                                   \
        double t0_ = bench_now_ns();                                              \
        for (k_ = 0; k_ < (n); k_++) {                                            \
            stmt;                                                                 \
        }                                                                         \
        t0_ = (bench_now_ns() - t0_) / (n);                                       \
        if (t0_ < (best))                                                         \
            (best) = t0_;                                                         \
    } while (0)

/* The batches of both sides are interleaved: each round times the OpenCV
 * chain and fieldloc (both formats, both modes) and the memcpy once, and
 * each keeps its best round.  A slow stretch of the machine (another
 * process, a clock change) then hits both sides of a ratio alike instead
 * of one of them (timing one side's batches first makes the ratio drift
 * with the machine's load). */
static void bench_frame(bench_ctx_t *ctx, const bench_frame_t *f, int noise)
{
    int reps = ctx->quick ? 1 : 7;
    int n = f->w * f->h <= 320 * 240 ? 200 : 60;
    int fmt_i, mode, r;
    static const fl_pixel_format_t fmts[2] = {FL_FMT_YUYV422, FL_FMT_RGB888};
    static fl_scan_t scanners[2];   /* full, default (host tool: static is fine) */
    double peer[2] = {0, 0}, t[2][2], t_copy[2];
    scantool_frame_t fr[2];
    uint8_t *copy[2] = {NULL, NULL};
    int have[2] = {0, 0};
    char name[400], desc[400];
#ifdef FL_HAVE_OPENCV
    cvpeer_chain_t *chain = cvpeer_chain_new();
    int16_t *border = malloc(sizeof(int16_t) * (size_t)f->w);
    uint8_t boxes[3][6];
    boxes_of(&bench_colors, boxes);
    peer[0] = peer[1] = 1e300;
#endif
    if (ctx->quick)
        n /= 10;
    for (mode = 0; mode < 2; mode++) {
        fl_scan_params_t sp;
        fl_scan_params_default(&sp);
        if (mode == 0)
            sp.col_step = sp.row_step = 1;
        fl_scan_init(&scanners[mode], &sp);
    }
    for (fmt_i = 0; fmt_i < 2; fmt_i++) {
        have[fmt_i] = scantool_frame_from_rgb(f->rgb, f->w, f->h, fmts[fmt_i], &fr[fmt_i]) == 0;
        if (have[fmt_i])
            copy[fmt_i] = malloc(fr[fmt_i].size);
        t[fmt_i][0] = t[fmt_i][1] = t_copy[fmt_i] = 1e300;
    }
    for (r = 0; r < reps; r++) {
        for (fmt_i = 0; fmt_i < 2; fmt_i++) {
            if (!have[fmt_i])
                continue;
#ifdef FL_HAVE_OPENCV
            if (chain && border)
                BENCH_BATCH(peer[fmt_i], n,
                            cvpeer_chain_run(chain, fmt_i == 0 ? fr[0].data : f->rgb, fmt_i == 0,
                                             f->w, f->h, (const uint8_t(*)[6])boxes, 8, border));
#endif
            for (mode = 0; mode < 2; mode++)
                BENCH_BATCH(t[fmt_i][mode], n,
                            bench_sink += fl_scan_frame(&scanners[mode], &bench_colors,
                                                        &fr[fmt_i].view, NULL));
            if (copy[fmt_i])
                BENCH_BATCH(t_copy[fmt_i], n,
                            memcpy(copy[fmt_i], fr[fmt_i].data, fr[fmt_i].size);
                            bench_sink += copy[fmt_i][fr[fmt_i].size / 2]);
        }
    }
#ifdef FL_HAVE_OPENCV
    for (fmt_i = 0; fmt_i < 2; fmt_i++)
        if (peer[fmt_i] >= 1e300)
            peer[fmt_i] = 0;
    free(border);
    cvpeer_chain_free(chain);
#endif
    for (fmt_i = 0; fmt_i < 2; fmt_i++) {
        if (!have[fmt_i])
            continue;
        for (mode = 0; mode < 2; mode++) {
            snprintf(name, sizeof name, "scan_%s_%s_%s", mode == 0 ? "full" : "default",
                     render_format_name(fmts[fmt_i]), f->name);
            snprintf(desc, sizeof desc, "OpenCV %s-> HSV, 3x inRange, first green run/column%s",
                     fmts[fmt_i] == FL_FMT_YUYV422 ? "YUYV->RGB " : "RGB ",
                     noise ? " (noise: worst case)" : "");
            bench_row(ctx, name, t[fmt_i][mode], peer[fmt_i], desc);
        }
        if (copy[fmt_i]) {
            snprintf(name, sizeof name, "memcpy_%s_%s", render_format_name(fmts[fmt_i]), f->name);
            snprintf(desc, sizeof desc, "memcpy of the %zu-byte frame (no peer)", fr[fmt_i].size);
            bench_row(ctx, name, t_copy[fmt_i], 0, desc);
            free(copy[fmt_i]);
        }
        scantool_frame_free(&fr[fmt_i]);
    }
}

void bench_scan(bench_ctx_t *ctx)
{
    bench_frame_t fr[7];
    int nf = 0, k, reps = ctx->quick ? 1 : 5;
    fl_color_params_t cp;
    double t;
    fl_color_params_default(&cp);
    fl_color_init(&bench_colors, &cp);
#ifdef FL_HAVE_OPENCV
    cvpeer_set_threads(1);
#endif
    memset(fr, 0, sizeof fr);
    if (load_real(&fr[nf], "real320", "IntelligentRoboticsLab_Datasets_qvga_000001.ppm") == 0)
        nf++;
    if (load_real(&fr[nf], "real640", "physar_landmark_based_slam_dataset_black1_point1_top.ppm") == 0)
        nf++;
    if (nf == 0)
        printf("# scan bench: real frames %s\n", rd_skip_message());
    if (load_rendered(&fr[nf], "rend320", "fixtures/frames/spl2013_goal_both.scene") == 0)
        nf++;
    if (load_rendered(&fr[nf], "rend640", "fixtures/frames/spl2013_640_goal.scene") == 0)
        nf++;
    if (make_noise(&fr[nf], "noise320", 320, 240, 0) == 0)
        nf++;
    if (make_noise(&fr[nf], "classnoise320", 320, 240, 1) == 0)
        nf++;
    if (make_noise(&fr[nf], "topnoise320", 320, 240, 2) == 0)
        nf++;
    for (k = 0; k < nf; k++)
        bench_frame(ctx, &fr[k], strstr(fr[k].name, "noise") != NULL);
    /* table build (what fl_color_adapt costs when the light moved) */
    BENCH_TIME(t, reps, ctx->quick ? 2 : 20, fl_color_init(&bench_colors, &cp));
    bench_row(ctx, "color_tables_build", t, 0, "fl_color_init: YCbCr + RGB tables (no peer)");
    for (k = 0; k < nf; k++)
        free(fr[k].rgb);
}

/* `fieldloc bench --noise-frames DIR` also writes the scanner's worst
 * case, scan_topnoise_320.ppm (see the file top). */
int bench_scan_write_noise(const char *dir)
{
    bench_frame_t f;
    char path[1024];
    int rc;
    if (make_noise(&f, "topnoise320", 320, 240, 2) != 0)
        return 1;
    snprintf(path, sizeof path, "%s/scan_topnoise_320.ppm", dir);
    rc = ppm_write(path, f.rgb, f.w, f.h) != 0;
    free(f.rgb);
    return rc;
}
