/*
 * tools/bench/bench_vision.c - `fieldloc bench` section "vision": the whole
 * per-frame vision path (fl_vision_frame: scanner, line points, segments,
 * circle, crossings and marks, posts, observations) against the OpenCV
 * chain of tools/bench/bench_vision_cv.cpp (HSV + inRange + HoughLinesP) on the
 * same frames, both single-threaded.
 *
 * Frames: every rendered fixture of fixtures/frames/index.txt in its own
 * format (RGB888, YUYV422 or planar; the peer gets the YUYV bytes and
 * converts them itself, and an RGB copy of planar frames), the UvA 2013
 * labelled frames and the modern 640x480 real frames when
 * ../shared/realdata is there (physar top frames with their records' head
 * angles and IMU; HTWK 2015, the NaoTH referee frame and the scarrix upper
 * frames with the head level: field spl2020, camera nao6-top-640), and
 * noise frames at
 * 320x240 and 640x480: uniform random RGB ("noise") and random carpet /
 * line / post / clutter colors per pixel ("classnoise"), the worst cases
 * for runs, line points and segment growth.
 * Rows (ns per frame, best of 5 runs per frame, 1 with --quick):
 *   vision_fix_<W>x<H>     mean over the fixtures of that size
 *   vision_uva_320x240     mean over the real UvA frames
 *   vision_physar_640x480, vision_htwk_640x480, vision_naoth_640x480,
 *   vision_scarrix_640x480 mean over the modern real frames of each source
 *   vision_noise_<W>       uniform noise, vision_classnoise_<W> class noise
 *   vision_worst           worst frame of all of the above (peer: its
 *                          worst frame, named in the description)
 * Instruction counts: run callgrind on the CLI, counting only inside
 * fl_vision_frame (as tools/bench/callgrind_vision.sh does):
 *   valgrind --tool=callgrind --toggle-collect=fl_vision_frame \
 *     build/fieldloc detect --field spl2013 --camera nao4-top-640 \
 *     --repeat 10 fixtures/frames/spl2013_640_goal.ppm
 *   (Ir / 10 = instructions per 640x480 frame).
 * Without ../shared/realdata the real-frame rows are left out and the
 * section says so.
 */
#include "eval/detect.h"
#include "io/ppm.h"
#include "io/realdata.h"
#include "bench/bench.h"
#include "world/render.h"
#include "world/truth.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef FL_HAVE_OPENCV
void *bvcv_new(void);
void bvcv_free(void *s);
int bvcv_run(void *state, const uint8_t *data, int yuyv, int w, int h,
             const uint8_t boxes[3][6]);
#endif

static volatile int32_t bv_sink;

typedef struct {
    char name[64];
    int w, h;
    fl_image_t view;          /* the frame in its format (over data) */
    uint8_t *data;            /* malloc'd frame bytes */
    uint8_t *rgb;             /* RGB copy for the peer (NULL: use data) */
    int yuyv;                 /* peer input is YUYV */
    fl_camera_t cam;
    const fl_field_t *field;
} bv_frame_t;

typedef struct {
    double fl_sum, cv_sum;
    int n;
} bv_acc_t;

static double bv_worst_fl, bv_worst_cv;
static char bv_worst_fl_name[64], bv_worst_cv_name[64];

static void bv_free(bv_frame_t *f)
{
    free(f->data);
    free(f->rgb);
    f->data = f->rgb = NULL;
}

static int bv_load_fixture(bv_frame_t *f, const char *dir, const char *name,
                           const char *file, const char *fieldn, const char *camn)
{
    char path[1024], err[256];
    render_frame_t fr;
    static truth_t tr;
    const fl_camera_model_t *m = fl_camera_model_find(camn);
    memset(f, 0, sizeof *f);
    f->field = fl_field_find(fieldn);
    snprintf(path, sizeof path, "%s/frames/%s.truth", dir, name);
    if (!m || !f->field || truth_load(path, &tr, err, sizeof err) != 0)
        return -1;
    snprintf(path, sizeof path, "%s/frames/%s", dir, file);
    if (render_read_frame(path, &fr, err, sizeof err) != 0)
        return -1;
    if (fl_camera_init(&f->cam, m, &tr.head) != FL_OK) {
        render_frame_free(&fr);
        return -1;
    }
    snprintf(f->name, sizeof f->name, "%.60s", name);
    f->w = fr.width;
    f->h = fr.height;
    f->data = malloc(fr.size);
    if (!f->data) {
        render_frame_free(&fr);
        return -1;
    }
    memcpy(f->data, fr.data, fr.size);
    f->view = fr.view;
    /* re-point the view at our copy */
    {
        ptrdiff_t k;
        for (k = 0; k < 3; k++)
            if (fr.view.plane[k])
                f->view.plane[k] = f->data + (fr.view.plane[k] - fr.data);
    }
    f->yuyv = fr.format == FL_FMT_YUYV422;
    if (fr.format == FL_FMT_YCBCR_PLANAR)
        f->rgb = det_rgb_copy(&f->view);
    render_frame_free(&fr);
    return 0;
}

static int bv_make_noise(bv_frame_t *f, const char *name, int w, int h, int classes)
{
    static const uint8_t pal[5][3] = {
        {82, 141, 85}, {254, 253, 250}, {191, 185, 47}, {90, 60, 40}, {60, 110, 62}};
    uint64_t s = 0x9E3779B97F4A7C15ULL;
    size_t i, n = (size_t)w * (size_t)h;
    const char *camn = w == 640 ? "nao4-top-640" : "nao4-top-320";
    fl_camera_pose_t pose = {450, 0, 0, 0, 0, 0, 0};
    memset(f, 0, sizeof *f);
    snprintf(f->name, sizeof f->name, "%s", name);
    f->w = w;
    f->h = h;
    f->field = fl_field_find("spl2013");
    f->data = malloc(n * 3);
    if (!f->data)
        return -1;
    for (i = 0; i < n; i++) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        if (classes)
            memcpy(f->data + 3 * i, pal[(s & 0xff) % 5], 3);
        else {
            f->data[3 * i] = (uint8_t)s;
            f->data[3 * i + 1] = (uint8_t)(s >> 8);
            f->data[3 * i + 2] = (uint8_t)(s >> 16);
        }
    }
    /* looking down a little: most of the frame is below the horizon */
    pose.head_pitch = fl_angle_from_mdeg(15000);
    fl_camera_init(&f->cam, fl_camera_model_find(camn), &pose);
    return fl_image_init_packed(&f->view, FL_FMT_RGB888, f->data, w, h, 3 * w) == FL_OK ? 0 : -1;
}

/* `fieldloc bench --noise-frames DIR`: write the four noise frames as
 * DIR/<row name>.ppm for callgrind (tools/bench/callgrind_vision.sh); their pose is
 * `detect --camera nao4-top-<W> --neck 450 --head 0.261799 0`. */
int bench_vision_write_noise(const char *dir)
{
    static const char *names[4] = {"vision_noise_320", "vision_classnoise_320",
                                   "vision_noise_640", "vision_classnoise_640"};
    char path[1024];
    int k, rc = 0;
    for (k = 0; k < 4 && rc == 0; k++) {
        bv_frame_t f;
        int w = k < 2 ? 320 : 640;
        if (bv_make_noise(&f, names[k], w, w * 3 / 4, k & 1) != 0)
            rc = 1;
        snprintf(path, sizeof path, "%s/%s.ppm", dir, names[k]);
        if (rc == 0 && ppm_write(path, f.data, f.w, f.h) != 0)
            rc = 1;
        bv_free(&f);
    }
    return rc;
}

/* Time one frame on both sides; accumulate. */
static void bv_time(bench_ctx_t *ctx, det_ctx_t *dc, void *cv, const bv_frame_t *f,
                    bv_acc_t *acc)
{
    int reps = ctx->quick ? 1 : 5, r;
    double best = 1e300, best_cv = 0;
    fl_obs_list_t obs;
    for (r = 0; r < reps; r++) {
        double t0 = bench_now_ns();
        bv_sink += fl_vision_frame(dc->vis, dc->colors, &f->view, &f->cam, f->field, &obs);
        t0 = bench_now_ns() - t0;
        if (t0 < best)
            best = t0;
    }
#ifdef FL_HAVE_OPENCV
    {
        uint8_t boxes[3][6];
        const fl_hsv_box_t *b[3];
        int k;
        b[0] = &dc->colors->green;
        b[1] = &dc->colors->white;
        b[2] = &dc->colors->yellow;
        for (k = 0; k < 3; k++) {
            boxes[k][0] = b[k]->h_lo;
            boxes[k][1] = b[k]->h_hi;
            boxes[k][2] = b[k]->s_lo;
            boxes[k][3] = b[k]->s_hi;
            boxes[k][4] = b[k]->v_lo;
            boxes[k][5] = b[k]->v_hi;
        }
        best_cv = 1e300;
        for (r = 0; r < reps; r++) {
            double t0 = bench_now_ns();
            bv_sink += bvcv_run(cv, f->rgb ? f->rgb : f->data, f->rgb ? 0 : f->yuyv, f->w,
                                f->h, (const uint8_t(*)[6])boxes);
            t0 = bench_now_ns() - t0;
            if (t0 < best_cv)
                best_cv = t0;
        }
    }
#else
    (void)cv;
#endif
    acc->fl_sum += best;
    acc->cv_sum += best_cv;
    acc->n++;
    if (best > bv_worst_fl) {
        bv_worst_fl = best;
        snprintf(bv_worst_fl_name, sizeof bv_worst_fl_name, "%s", f->name);
    }
    if (best_cv > bv_worst_cv) {
        bv_worst_cv = best_cv;
        snprintf(bv_worst_cv_name, sizeof bv_worst_cv_name, "%s", f->name);
    }
}

/* A real frame of the folder with this camera pose (RGB888). */
static int bv_load_real(bv_frame_t *f, const char *dir, const char *file, const char *name,
                        const char *fieldn, const char *camn, const fl_camera_pose_t *pose)
{
    host_image_t img;
    char err[256];
    const fl_camera_model_t *m = fl_camera_model_find(camn);
    memset(f, 0, sizeof *f);
    f->field = fl_field_find(fieldn);
    if (!m || !f->field || rd_read_ppm(dir, file, &img, err, sizeof err) != 0)
        return -1;
    snprintf(f->name, sizeof f->name, "%.60s", name);
    f->w = img.width;
    f->h = img.height;
    f->data = img.rgb;
    if (rd_image_view(&img, &f->view) != FL_OK || fl_camera_init(&f->cam, m, pose) != FL_OK) {
        bv_free(f);
        return -1;
    }
    return 0;
}

/* The modern 640x480 real frames: physar (its records' poses), HTWK,
 * NaoTH and scarrix (head level: their poses are not recorded). */
static void bv_modern(bench_ctx_t *ctx, det_ctx_t *dc, void *cv, const char *dir,
                      bv_acc_t *acc)
{
    static const char *const other[][2] = {
        {"htwk_49806", "NaoHTWK_HTWKVision_ChinaTest2015GAB03B_AnyBallTest3_00049806_U.ppm"},
        {"htwk_51659", "NaoHTWK_HTWKVision_ChinaTest2015GAB03B_AnyBallTest3_00051659_U.ppm"},
        {"naoth_referee", "BerlinUnited_NaoTH-Deeplearning_referee_pose_test_image.ppm"},
        {"scarrix_9500", "scarrix_Detect_Foot_danu_fallen_robot_9500_upper.ppm"},
        {"scarrix_2002", "scarrix_Detect_Foot_danu_gaolie_shots_on_goal_2002_upper.ppm"},
        {"scarrix_3141", "scarrix_Detect_Foot_danu_moving_ball_across_vision_3141_upper.ppm"}};
    const fl_camera_model_t *m = fl_camera_model_find("nao6-top-640");
    rd_physar_set_t set;
    char path[1024], err[256];
    bv_frame_t f;
    fl_camera_pose_t pose;
    size_t k;
    if (m == NULL)
        return;
    if (rd_path(path, sizeof path, dir, RD_PHYSAR_CSV) == 0 &&
        rd_physar_load(path, &set, err, sizeof err) == 0) {
        for (k = 0; k < (size_t)set.n; k++) {
            char name[64];
            if (!set.rec[k].image_top[0])
                continue;
            snprintf(name, sizeof name, "physar_%.40s", set.rec[k].point);
            rd_physar_camera_pose(&set.rec[k], m, &pose);
            if (bv_load_real(&f, dir, set.rec[k].image_top, name, "spl2020", m->name, &pose) == 0)
                bv_time(ctx, dc, cv, &f, &acc[0]);
            bv_free(&f);
        }
        rd_physar_free(&set);
    }
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    for (k = 0; k < sizeof other / sizeof other[0]; k++) {
        /* accumulators: 1 HTWK, 2 NaoTH, 3 scarrix */
        int a = k < 2 ? 1 : k == 2 ? 2 : 3;
        if (bv_load_real(&f, dir, other[k][1], other[k][0], "spl2020", m->name, &pose) == 0)
            bv_time(ctx, dc, cv, &f, &acc[a]);
        bv_free(&f);
    }
}

static void bv_row(bench_ctx_t *ctx, const char *name, const bv_acc_t *a, const char *what)
{
    char desc[160];
    if (a->n <= 0)
        return;
#ifdef FL_HAVE_OPENCV
    snprintf(desc, sizeof desc, "OpenCV HSV+inRange+HoughLinesP, %d %s", a->n, what);
    bench_row(ctx, name, a->fl_sum / a->n, a->cv_sum / a->n, desc);
#else
    snprintf(desc, sizeof desc, "no OpenCV peer in this build, %d %s", a->n, what);
    bench_row(ctx, name, a->fl_sum / a->n, 0, desc);
#endif
}

void bench_vision(bench_ctx_t *ctx)
{
    det_ctx_t dc;
    void *cv = NULL;
    char line[1024];
    FILE *idx;
    bv_acc_t a320 = {0, 0, 0}, a640 = {0, 0, 0}, aaibo = {0, 0, 0}, auva = {0, 0, 0};
    bv_acc_t amod[4] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    bv_frame_t f;
    int k;
    if (det_ctx_init(&dc) != 0)
        return;
#ifdef FL_HAVE_OPENCV
    cv = bvcv_new();
#endif
    bv_worst_fl = bv_worst_cv = 0;
    bv_worst_fl_name[0] = bv_worst_cv_name[0] = '\0';
    idx = fopen("fixtures/frames/index.txt", "r");
    while (idx && fgets(line, sizeof line, idx)) {
        char name[256], file[256], fmt[32], fieldn[64], camn[64];
        if (line[0] == '#' ||
            sscanf(line, "%255s %255s %31s %63s %63s", name, file, fmt, fieldn, camn) != 5)
            continue;
        if (bv_load_fixture(&f, "fixtures", name, file, fieldn, camn) != 0)
            continue;
        bv_time(ctx, &dc, cv, &f, f.w == 640 ? &a640 : f.w == 320 ? &a320 : &aaibo);
        bv_free(&f);
    }
    if (idx)
        fclose(idx);
    else
        printf("vision: fixtures/frames/index.txt not found (run from the repository)\n");
    {
        const char *dir = rd_dir();
        rd_uva_set_t set;
        char path[1024], err[256];
        if (dir && rd_path(path, sizeof path, dir, RD_UVA_CSV) == 0 &&
            rd_uva_load(path, &set, err, sizeof err) == 0) {
            const fl_camera_model_t *m = fl_camera_model_find("uva2013");
            for (k = 0; k < set.n; k++) {
                host_image_t img;
                fl_camera_pose_t pose;
                memset(&f, 0, sizeof f);
                if (rd_read_ppm(dir, set.rec[k].file, &img, err, sizeof err) != 0)
                    continue;
                snprintf(f.name, sizeof f.name, "uva_%s_%s", set.rec[k].set, set.rec[k].index);
                f.w = img.width;
                f.h = img.height;
                f.data = img.rgb;
                f.field = fl_field_find("uva2013");
                rd_uva_camera_pose(&set.rec[k], m, &pose);
                if (rd_image_view(&img, &f.view) == FL_OK &&
                    fl_camera_init(&f.cam, m, &pose) == FL_OK)
                    bv_time(ctx, &dc, cv, &f, &auva);
                bv_free(&f);
            }
            rd_uva_free(&set);
        } else {
            printf("vision: UvA frames %s\n", rd_skip_message());
        }
        if (dir)
            bv_modern(ctx, &dc, cv, dir, amod);
        else
            printf("vision: modern 640x480 real frames %s\n", rd_skip_message());
    }
    bv_row(ctx, "vision_fix_320x240", &a320, "rendered fixtures");
    bv_row(ctx, "vision_fix_640x480", &a640, "rendered fixtures");
    bv_row(ctx, "vision_fix_208x160", &aaibo, "rendered AIBO fixtures");
    bv_row(ctx, "vision_uva_320x240", &auva, "real UvA 2013 frames");
    bv_row(ctx, "vision_physar_640x480", &amod[0], "real physar 2024 top frames (record poses)");
    bv_row(ctx, "vision_htwk_640x480", &amod[1], "real HTWK 2015 upper frames (head level)");
    bv_row(ctx, "vision_naoth_640x480", &amod[2], "real NaoTH referee frame (head level)");
    bv_row(ctx, "vision_scarrix_640x480", &amod[3], "real scarrix upper frames (head level)");
    for (k = 0; k < 4; k++) {
        static const char *names[4] = {"vision_noise_320", "vision_classnoise_320",
                                       "vision_noise_640", "vision_classnoise_640"};
        bv_acc_t an = {0, 0, 0};
        int w = k < 2 ? 320 : 640;
        if (bv_make_noise(&f, names[k], w, w * 3 / 4, k & 1) == 0) {
            bv_time(ctx, &dc, cv, &f, &an);
            bv_row(ctx, names[k], &an, "noise frame");
        }
        bv_free(&f);
    }
    {
        char desc[200];
        snprintf(desc, sizeof desc, "worst frame: fieldloc %s, peer %s", bv_worst_fl_name,
                 bv_worst_cv_name);
        bench_row(ctx, "vision_worst", bv_worst_fl, bv_worst_cv, desc);
    }
#ifdef FL_HAVE_OPENCV
    bvcv_free(cv);
#endif
    det_ctx_free(&dc);
}
