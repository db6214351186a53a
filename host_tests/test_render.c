/*
 * host_tests/test_render.c - suite `render`: the synthetic world of
 * tools/world/render.h and tools/world/truth.h against the firmware camera model, its
 * own invariants, and the committed fixtures in fixtures/frames/ (run from
 * the repository root).
 *
 * Cases and tolerances:
 *  - camera agreement: every visible (not occluded) crossing, mark, circle
 *    point and post foot of every committed truth file, and of random scenes
 *    rendered here, has its truth pixel (rounded to Q4) sent through
 *    fl_camera_pixel_to_ground with the scene's pose; the ground point must
 *    be within 3 mm + 1% of the range of the truth robot-frame point.  The
 *    other way, fl_camera_ground_to_pixel of the truth point (rounded to
 *    mm) must agree with the renderer's projection of that point to 1.5 Q4
 *    LSB + f * (sqrt(3)/32 mm) / distance (test_camera.c's bound + 0.5).
 *  - line pixels: every LINE pixel centre of a few frames, through the
 *    firmware, lands within 3 mm + 0.5% of range of the paint (distance to
 *    the paint computed here from field.h, independently of the renderer);
 *    every GREEN pixel centre at least that far outside it.
 *  - border: per column, rows above border_v are not GREEN/LINE, rows in
 *    [border_v, border_end_v) are carpet or an object standing on it, rows
 *    below are not GREEN/LINE; border_visible_v is the first GREEN/LINE row;
 *    the firmware ground point of (u, border_v) is on the carpet and that of
 *    (u, border_v - 1) is not (same tolerance).
 *  - features in the mask: crossings nearer than 3 m sit on a LINE pixel;
 *    3 px above a post foot nearer than 4 m is GOAL.
 *  - determinism: two renders byte-identical (digest printed); the
 *    committed fixtures are what `make fixtures` writes: a few are
 *    re-rendered from their .scene and compared byte for byte (frame and
 *    truth text), every .scene equals the fixture table, the index lists
 *    every fixture and the set is under 20 MB.
 *  - round trips: scene and truth text write -> read -> write identical.
 *  - formats: YUYV / planar bytes are the integer BT.601 of the RGB frame.
 *  - colors: mean carpet and line color of a nominal frame within 12% of
 *    the UvA measurement in tools/world/render.c.
 * Quick mode (--quick, qemu, about 20x slower): 2 fixtures re-rendered
 * instead of 5, 1 random scene instead of 8, line/border checks on 1 frame
 * (208x160) instead of 4, features in the mask on 2 fixtures instead of 14,
 * formats on a 208x160 frame, and no second-seed and no frame-less border
 * comparison.
 */
#include "test.h"

#include "fieldloc/camera.h"
#include "fieldloc/field.h"
#include "fieldloc/image.h"
#include "world/render.h"
#include "world/render_cache.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#define FIX_DIR "fixtures/frames"

/* ---- helpers --------------------------------------------------------------- */

static uint32_t hash_frame(const render_frame_t *fr)
{
    uint32_t h = t_hash_init();
    int u;
    h = t_hash_bytes(h, fr->data, fr->size);
    h = t_hash_bytes(h, fr->mask, (size_t)fr->width * (size_t)fr->height);
    for (u = 0; u < fr->width; u++) {
        h = t_hash_i32(h, fr->border_v[u]);
        h = t_hash_i32(h, fr->border_end_v[u]);
        h = t_hash_i32(h, fr->border_visible_v[u]);
    }
    return h;
}

/* A busy scene: robots, ball, blur, JPEG, noise, YUYV. */
static void busy_scene(render_scene_t *sc)
{
    render_scene_default(sc, fl_field_find("spl2013"), fl_camera_model_find("nao4-top-320"));
    sc->format = FL_FMT_YUYV422;
    sc->robot_x_mm = 1500;
    sc->robot_y_mm = 300;
    sc->head.head_pitch = fl_angle_from_mdeg(3000);
    sc->seed = 7;
    sc->world_seed = 3;
    sc->n_robots = 2;
    sc->robots[0].x_mm = 4200;
    sc->robots[0].heading = FL_ANGLE_180;
    sc->robots[0].jersey = RENDER_JERSEY_BLUE;
    sc->robots[1].x_mm = 2200; /* between the camera and the penalty mark */
    sc->robots[1].y_mm = 125;
    sc->ball = 1;
    sc->ball_x_mm = 3300;
    sc->ball_y_mm = 200;
    sc->blur_px = 3;
    sc->jpeg = 2;
}

/* Distance (mm, negative inside) from a field point to the paint, written
 * here from field.h alone (boundary, box and halfway lines as rectangles
 * of the line width with square ends extended by half a width, the circle
 * as an annulus, marks as crosses). */
static double rect_sd(double x, double y, double x0, double y0, double x1, double y1, double hw)
{
    double lo_x = (x0 < x1 ? x0 : x1) - hw, hi_x = (x0 > x1 ? x0 : x1) + hw;
    double lo_y = (y0 < y1 ? y0 : y1) - hw, hi_y = (y0 > y1 ? y0 : y1) + hw;
    double dx = x < lo_x ? lo_x - x : x > hi_x ? x - hi_x : -(x - lo_x < hi_x - x ? x - lo_x : hi_x - x);
    double dy = y < lo_y ? lo_y - y : y > hi_y ? y - hi_y : -(y - lo_y < hi_y - y ? y - lo_y : hi_y - y);
    if (dx > 0 && dy > 0)
        return sqrt(dx * dx + dy * dy);
    return dx > dy ? dx : dy;
}

static double paint_sd(const fl_field_t *f, double x, double y)
{
    double best = 1e9, hw = 0.5 * f->line_width_mm, s;
    int i;
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *l = &f->lines[i];
        s = rect_sd(x, y, l->x0_mm, l->y0_mm, l->x1_mm, l->y1_mm, hw);
        if (s < best)
            best = s;
    }
    if (f->circle_radius_mm > 0) {
        s = fabs(sqrt(x * x + y * y) - f->circle_radius_mm) - hw;
        if (s < best)
            best = s;
    }
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *lm = &f->landmarks[i];
        double m = 0.5 * f->mark_size_mm;
        if ((lm->kind != FL_LM_PENALTY_MARK && lm->kind != FL_LM_CENTRE_MARK) || m <= 0)
            continue;
        s = rect_sd(x, y, lm->x_mm - m + hw, lm->y_mm, lm->x_mm + m - hw, lm->y_mm, hw);
        if (s < best)
            best = s;
        s = rect_sd(x, y, lm->x_mm, lm->y_mm - m + hw, lm->x_mm, lm->y_mm + m - hw, hw);
        if (s < best)
            best = s;
    }
    return best;
}

static double carpet_sd(const fl_field_t *f, double x, double y)
{
    double a = fabs(x) - fl_field_carpet_half_x_mm(f), b = fabs(y) - fl_field_carpet_half_y_mm(f);
    return a > b ? a : b;
}

/* Firmware ground point of pixel (u, v) in the field frame; 0 if none. */
static int fw_ground(const render_scene_t *sc, const fl_camera_t *cam, int u, int v, double *fx,
                     double *fy, double *range)
{
    fl_point_t g;
    if (!fl_camera_pixel_to_ground(cam, u * 16, v * 16, &g))
        return 0;
    render_robot_to_field(sc, g.x_mm, g.y_mm, fx, fy);
    *range = sqrt((double)g.x_mm * g.x_mm + (double)g.y_mm * g.y_mm);
    return 1;
}

static int is_ground_kind(truth_kind_t k)
{
    return k == TRUTH_L || k == TRUTH_T || k == TRUTH_X || k == TRUTH_PENALTY_MARK ||
           k == TRUTH_CENTRE_MARK || k == TRUTH_CIRCLE_CENTRE || k == TRUTH_CIRCLE_ARC ||
           k == TRUTH_POST_FOOT || k == TRUTH_BEACON;
}

/* Check every visible ground feature of a truth against the firmware:
 * pixel -> ground within 3 mm + 1% of range; ground -> pixel (of the truth
 * point rounded to whole mm) within the firmware's documented precision
 * (test_camera.c: 1 Q4 LSB + f * (sqrt(3)/32 mm) / distance) plus 0.5 LSB
 * of the renderer's own projection of that rounded point. */
static int check_truth_vs_camera(const truth_t *t, double *max_err, double *max_rel, double *max_px)
{
    const fl_camera_model_t *m = fl_camera_model_find(t->camera);
    render_scene_t sc;
    fl_camera_t cam;
    int i, n = 0;
    CHECK(m != NULL);
    if (!m)
        return 0;
    render_scene_default(&sc, fl_field_find(t->field), m);
    sc.robot_x_mm = t->robot_x_mm;
    sc.robot_y_mm = t->robot_y_mm;
    sc.robot_heading = t->robot_heading;
    sc.head = t->head;
    CHECK_EQ(fl_camera_init(&cam, m, &t->head), FL_OK);
    for (i = 0; i < t->n; i++) {
        const truth_feature_t *f = &t->f[i];
        fl_point_t g, q;
        int32_t uq, vq;
        double e, ep, fx, fy, ur, vr, dist;
        if (f->occluded || !is_ground_kind(f->kind))
            continue;
        if (!fl_camera_pixel_to_ground(&cam, (int32_t)lround(f->u * 16), (int32_t)lround(f->v * 16), &g)) {
            /* only acceptable beyond the firmware's range limit */
            CHECK(f->range_mm > FL_CAMERA_MAX_RANGE_MM - 500);
            continue;
        }
        e = hypot(g.x_mm - f->robot_x_mm, g.y_mm - f->robot_y_mm);
        if (e > 3.0 + 0.01 * f->range_mm)
            t_fail_msg(__FILE__, __LINE__, "%s %s landmark %d: ground error %.1f mm at range %.0f",
                       t->camera, truth_kind_name(f->kind), f->landmark, e, f->range_mm);
        if (e > *max_err)
            *max_err = e;
        if (e / f->range_mm > *max_rel)
            *max_rel = e / f->range_mm;
        q.x_mm = (int32_t)lround(f->robot_x_mm);
        q.y_mm = (int32_t)lround(f->robot_y_mm);
        render_robot_to_field(&sc, q.x_mm, q.y_mm, &fx, &fy);
        if (!render_project_field(&sc, fx, fy, 0, &ur, &vr, &dist) ||
            !fl_camera_ground_to_pixel(&cam, q, &uq, &vq)) {
            CHECK(0);
            continue;
        }
        ep = hypot(uq / 16.0 - ur, vq / 16.0 - vr);
        CHECK_LE(ep, (1.5 + m->focal_q4 * (1.7320508 / 32.0) / dist) / 16.0);
        if (ep > *max_px)
            *max_px = ep;
        n++;
    }
    return n;
}

/* ---- cases ------------------------------------------------------------------------ */

/* The frame cache (tools/world/render_cache.c) off for one test and back
 * on: this test checks the renderer itself, on every target. */
static char *cache_off(void)
{
    const char *c = getenv("FIELDLOC_RENDER_CACHE");
    char *saved = c ? strdup(c) : NULL;
    unsetenv("FIELDLOC_RENDER_CACHE");
    return saved;
}

static void cache_restore(char *saved)
{
    if (saved) {
        setenv("FIELDLOC_RENDER_CACHE", saved, 1);
        free(saved);
    }
}

static int frames_equal(const render_frame_t *a, const render_frame_t *b)
{
    size_t npx = (size_t)a->width * (size_t)a->height;
    return a->width == b->width && a->height == b->height && a->format == b->format &&
           a->size == b->size && memcmp(a->data, b->data, a->size) == 0 &&
           memcmp(a->rgb, b->rgb, npx * 3) == 0 && memcmp(a->mask, b->mask, npx) == 0 &&
           memcmp(a->border_v, b->border_v, (size_t)a->width * sizeof(int16_t)) == 0 &&
           memcmp(a->border_end_v, b->border_end_v, (size_t)a->width * sizeof(int16_t)) == 0 &&
           memcmp(a->border_visible_v, b->border_visible_v, (size_t)a->width * sizeof(int16_t)) == 0 &&
           fl_image_validate(&b->view) == FL_OK && b->view.width == a->width;
}

static int file_exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return 0;
    fclose(f);
    return 1;
}

/* FIELDLOC_RENDER_CACHE: a stored frame comes back byte for byte; a
 * truncated file or another scene's file under this scene's name is not
 * used (the frame is rendered afresh). */
static void test_cache(void)
{
    char dir[] = "/tmp/fl_render_cache_XXXXXX", path[1200], other[1200], cmd[2500];
    char *saved = cache_off();
    render_scene_t sc, sc2;
    render_frame_t fresh, a, b, c;
    FILE *f;
    long len;
    busy_scene(&sc);
    sc.format = FL_FMT_YUYV422;
    sc2 = sc;
    sc2.seed++;
    CHECK_EQ(render_frame(&sc, &fresh), 0);      /* cache off */
    if (mkdtemp(dir) == NULL) {
        CHECK(0);
        render_frame_free(&fresh);
        cache_restore(saved);
        return;
    }
    setenv("FIELDLOC_RENDER_CACHE", dir, 1);
    CHECK_EQ(render_cache_file(&sc, path, sizeof path), 0);
    CHECK_EQ(render_cache_file(&sc2, other, sizeof other), 0);
    CHECK(strcmp(path, other) != 0);
    CHECK(!file_exists(path));
    CHECK_EQ(render_frame(&sc, &a), 0);          /* renders and stores */
    CHECK(file_exists(path));
    CHECK(frames_equal(&fresh, &a));
    CHECK_EQ(render_frame(&sc, &b), 0);          /* loads */
    CHECK(frames_equal(&fresh, &b));
    CHECK(b.data != NULL && b.data != b.rgb);    /* YUYV: its own buffer */
    render_frame_free(&b);
    /* the frame really comes from the file: one byte changed there (the
     * high byte of the last border_visible_v) shows in the loaded frame */
    f = fopen(path, "rb+");
    CHECK(f != NULL);
    if (f) {
        CHECK(fseek(f, -1, SEEK_END) == 0);
        fputc(0x40, f);
        fclose(f);
        CHECK_EQ(render_frame(&sc, &b), 0);
        CHECK_EQ(b.border_visible_v[b.width - 1], (int16_t)(0x4000 | (fresh.border_visible_v[b.width - 1] & 0xff)));
        render_frame_free(&b);
        CHECK(remove(path) == 0);
        CHECK_EQ(render_frame(&sc, &b), 0);   /* rendered and stored again */
        CHECK(frames_equal(&fresh, &b));
        render_frame_free(&b);
    }
    /* truncated: refused, rendered again and stored whole */
    f = fopen(path, "rb+");
    CHECK(f != NULL);
    if (f) {
        fseek(f, 0, SEEK_END);
        len = ftell(f);
        fclose(f);
        CHECK(truncate(path, len - 1) == 0);
        CHECK_EQ(render_frame(&sc, &b), 0);
        CHECK(frames_equal(&fresh, &b));
        render_frame_free(&b);
        f = fopen(path, "rb");
        CHECK(f != NULL);
        if (f) {
            fseek(f, 0, SEEK_END);
            CHECK_EQ(ftell(f), len);
            fclose(f);
        }
    }
    /* scene 1's file under scene 2's name: scene 2 is rendered */
    CHECK_EQ(render_frame(&sc2, &c), 0);
    render_frame_free(&c);
    CHECK(file_exists(other));
    CHECK(other[0] != '\0');
    snprintf(cmd, sizeof cmd, "cp '%s' '%s'", path, other);
    CHECK(system(cmd) == 0);
    CHECK_EQ(render_frame(&sc2, &c), 0);
    CHECK(!frames_equal(&fresh, &c));
    CHECK(c.size == fresh.size && memcmp(c.data, fresh.data, c.size) != 0);
    render_frame_free(&c);
    render_frame_free(&a);
    render_frame_free(&fresh);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    unsetenv("FIELDLOC_RENDER_CACHE");
    cache_restore(saved);
}

static void test_determinism(void)
{
    render_scene_t sc;
    render_frame_t a, b;
    char *saved = cache_off();
    busy_scene(&sc);
    CHECK_EQ(render_frame(&sc, &a), 0);
    CHECK_EQ(render_frame(&sc, &b), 0);
    CHECK_EQ(a.size, b.size);
    CHECK(a.size == b.size && memcmp(a.data, b.data, a.size) == 0);
    CHECK(memcmp(a.mask, b.mask, (size_t)a.width * (size_t)a.height) == 0);
    CHECK(memcmp(a.rgb, b.rgb, (size_t)a.width * (size_t)a.height * 3) == 0);
    t_digest("render.busy_scene", hash_frame(&a));
    /* another seed changes the noise */
    sc.seed++;
    render_frame_free(&b);
    if (!t_quick) {
        CHECK_EQ(render_frame(&sc, &b), 0);
        CHECK(memcmp(a.data, b.data, a.size) != 0);
    }
    render_frame_free(&a);
    render_frame_free(&b);
    cache_restore(saved);
}

static void test_bad_input(void)
{
    render_scene_t sc;
    render_frame_t fr;
    fl_camera_model_t odd;
    char err[128];
    FILE *f;
    CHECK_EQ(render_frame(NULL, &fr), -1);
    CHECK_EQ(render_frame(&sc, NULL), -1);
    render_scene_default(&sc, NULL, fl_camera_model_find("nao4-top-320"));
    CHECK_EQ(render_frame(&sc, &fr), -1);
    CHECK(fr.data == NULL && fr.mask == NULL);
    render_scene_default(&sc, fl_field_find("spl2013"), fl_camera_model_find("nao4-top-320"));
    sc.head.head_pitch = fl_angle_from_mdeg(120000); /* looks past vertical */
    CHECK_EQ(render_frame(&sc, &fr), -1);
    sc.head.head_pitch = 0;
    sc.head.neck_height_mm = 10;
    CHECK_EQ(render_frame(&sc, &fr), -1);
    sc.head.neck_height_mm = 450;
    sc.n_robots = RENDER_MAX_ROBOTS + 1;
    CHECK_EQ(render_frame(&sc, &fr), -1);
    sc.n_robots = 0;
    odd = *fl_camera_model_find("nao4-top-320");
    odd.width_px = 31;
    odd.height_px = 24;
    odd.cx_q4 = 8 * 30;
    odd.cy_q4 = 8 * 23;
    sc.camera = &odd;
    sc.format = FL_FMT_YUYV422;
    CHECK_EQ(render_frame(&sc, &fr), -1);
    sc.format = FL_FMT_RGB888;
    CHECK_EQ(render_frame(&sc, &fr), 0); /* odd width is fine in RGB */
    CHECK_EQ(fr.width, 31);
    render_frame_free(&fr);
    /* scene text errors */
    f = tmpfile();
    CHECK(f != NULL);
    if (f) {
        fputs("fieldloc-scene 1\nfield spl2013\ncamera nao4-top-320\nbogus 1\n", f);
        rewind(f);
        CHECK_EQ(render_scene_read(f, &sc, err, sizeof err), -1);
        CHECK(strstr(err, "line 4") != NULL);
        fclose(f);
    }
    f = tmpfile();
    if (f) {
        fputs("fieldloc-scene 1\nfield nowhere\n", f);
        rewind(f);
        CHECK_EQ(render_scene_read(f, &sc, err, sizeof err), -1);
        fclose(f);
    }
    CHECK_EQ(render_read_frame("fixtures/frames/does-not-exist.ppm", &fr, err, sizeof err), -1);
}

static void test_scene_roundtrip(void)
{
    render_scene_t a, b;
    char t1[4096] = {0}, t2[4096] = {0};
    FILE *f = tmpfile(), *g = tmpfile();
    CHECK(f && g);
    if (!f || !g)
        return;
    busy_scene(&a);
    a.head.pitch_offset = -77;
    a.head.head_yaw = 1234;
    a.grad_x_pct = -30;
    a.blur_dir = 5461;
    CHECK_EQ(render_scene_write(f, &a), 0);
    rewind(f);
    CHECK_EQ(render_scene_read(f, &b, NULL, 0), 0);
    CHECK(b.field == a.field && b.camera == a.camera && b.format == a.format);
    CHECK_EQ(b.robot_x_mm, a.robot_x_mm);
    CHECK_EQ(b.head.head_pitch, a.head.head_pitch);
    CHECK_EQ(b.head.head_yaw, a.head.head_yaw);
    CHECK_EQ(b.head.pitch_offset, a.head.pitch_offset);
    CHECK_EQ(b.n_robots, a.n_robots);
    CHECK_EQ(b.robots[0].heading, a.robots[0].heading);
    CHECK_EQ(b.robots[0].jersey, a.robots[0].jersey);
    CHECK_EQ(b.ball_y_mm, a.ball_y_mm);
    CHECK_EQ(b.grad_x_pct, a.grad_x_pct);
    CHECK_EQ(b.blur_dir, a.blur_dir);
    CHECK_EQ(b.jpeg, a.jpeg);
    CHECK_EQ(b.seed, a.seed);
    CHECK_EQ(b.world_seed, a.world_seed);
    CHECK_EQ(render_scene_write(g, &b), 0);
    rewind(f);
    rewind(g);
    CHECK(fread(t1, 1, sizeof t1 - 1, f) > 0);
    CHECK(fread(t2, 1, sizeof t2 - 1, g) > 0);
    CHECK(strcmp(t1, t2) == 0);
    fclose(f);
    fclose(g);
}

static void test_truth_roundtrip(void)
{
    render_scene_t sc;
    render_frame_t fr;
    truth_t *a = (truth_t *)malloc(sizeof *a), *b = (truth_t *)malloc(sizeof *b);
    FILE *f = tmpfile(), *g = tmpfile();
    static char t1[200000], t2[200000];
    size_t n1, n2;
    int i, u;
    CHECK(a && b && f && g);
    if (!a || !b || !f || !g)
        return;
    busy_scene(&sc);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK_EQ(truth_compute(&sc, &fr, a), 0);
    CHECK(a->n > 5);
    CHECK_EQ(truth_write(f, a), 0);
    rewind(f);
    CHECK_EQ(truth_read(f, b, NULL, 0), 0);
    CHECK(strcmp(a->field, b->field) == 0 && strcmp(a->camera, b->camera) == 0);
    CHECK_EQ(b->width, a->width);
    CHECK_EQ(b->robot_heading, a->robot_heading);
    CHECK_EQ(b->head.head_pitch, a->head.head_pitch);
    CHECK_LE(fabs(b->horizon_v - a->horizon_v), 0.0005);
    CHECK_LE(fabs(b->cam_z_mm - a->cam_z_mm), 0.0005);
    for (u = 0; u < a->width; u++) {
        if (a->border_v[u] != b->border_v[u] || a->border_end_v[u] != b->border_end_v[u] ||
            a->border_visible_v[u] != b->border_visible_v[u]) {
            CHECK(0);
            break;
        }
    }
    CHECK_EQ(b->n, a->n);
    for (i = 0; i < a->n && i < b->n; i++) {
        const truth_feature_t *x = &a->f[i], *y = &b->f[i];
        CHECK(x->kind == y->kind && x->landmark == y->landmark && x->index == y->index &&
              x->side == y->side && x->goal == y->goal && x->occluded == y->occluded);
        CHECK(fabs(x->u - y->u) <= 0.0005 && fabs(x->v - y->v) <= 0.0005 &&
              fabs(x->robot_x_mm - y->robot_x_mm) <= 0.0005 && fabs(x->field_y_mm - y->field_y_mm) <= 0.0005 &&
              fabs(x->z_mm - y->z_mm) <= 0.0005 && fabs(x->range_mm - y->range_mm) <= 0.0005);
    }
    CHECK_EQ(truth_write(g, b), 0);
    rewind(f);
    rewind(g);
    n1 = fread(t1, 1, sizeof t1 - 1, f);
    n2 = fread(t2, 1, sizeof t2 - 1, g);
    CHECK(n1 > 0 && n1 == n2 && memcmp(t1, t2, n1) == 0);
    /* the border without a frame (ray-cast in truth_compute) is the same */
    if (!t_quick) {
        CHECK_EQ(truth_compute(&sc, NULL, b), 0);
        CHECK(memcmp(a->border_v, b->border_v, (size_t)a->width * sizeof(int16_t)) == 0);
        CHECK(memcmp(a->border_visible_v, b->border_visible_v, (size_t)a->width * sizeof(int16_t)) == 0);
    }
    /* the robots hide something in this scene */
    for (i = 0, u = 0; i < a->n; i++)
        u += a->f[i].occluded;
    CHECK(u > 0);
    render_frame_free(&fr);
    fclose(f);
    fclose(g);
    free(a);
    free(b);
}

/* Random poses on the four fields: crossings through the firmware. */
static void test_camera_agreement_random(void)
{
    static const char *fields[] = {"spl2013", "uva2013", "spl2020", "aibo2004"};
    static const char *cams[] = {"nao4-top-320", "nao4-bottom-320", "nao6-top-640", "aibo-ers7"};
    t_rng_t r;
    int k, n = 0, scenes = t_quick ? 1 : 8;
    double max_err = 0, max_rel = 0, max_px = 0;
    truth_t *t = (truth_t *)malloc(sizeof *t);
    CHECK(t != NULL);
    if (!t)
        return;
    t_rng_seed(&r, 42);
    for (k = 0; k < scenes; k++) {
        render_scene_t sc;
        const fl_field_t *f = fl_field_find(fields[k % 4]);
        render_scene_default(&sc, f, fl_camera_model_find(cams[k % 4]));
        sc.robot_x_mm = t_rng_range(&r, -f->length_mm / 2, f->length_mm / 2);
        sc.robot_y_mm = t_rng_range(&r, -f->width_mm / 2, f->width_mm / 2);
        sc.robot_heading = (fl_angle_t)t_rng_range(&r, -32768, 32767);
        sc.head.head_pitch = (fl_angle_t)t_rng_range(&r, -3000, 3500);
        sc.head.head_yaw = (fl_angle_t)t_rng_range(&r, -12000, 12000);
        sc.head.pitch_offset = (fl_angle_t)t_rng_range(&r, -300, 300);
        sc.head.neck_height_mm += t_rng_range(&r, -30, 30);
        CHECK_EQ(truth_compute(&sc, NULL, t), 0);
        n += check_truth_vs_camera(t, &max_err, &max_rel, &max_px);
    }
    t_info("random scenes: %d ground features, max ground error %.2f mm (%.3f%% of range), "
           "max pixel error %.3f px", n, max_err, 100 * max_rel, max_px);
    free(t);
}

/* The committed truth files against the firmware. */
static void test_camera_agreement_fixtures(void)
{
    int i, n = 0, files = 0;
    double max_err = 0, max_rel = 0, max_px = 0;
    truth_t *t = (truth_t *)malloc(sizeof *t);
    CHECK(t != NULL);
    if (!t)
        return;
    for (i = 0; i < render_fixture_count(); i++) {
        render_scene_t sc;
        const char *name;
        char path[512], err[256];
        CHECK_EQ(render_fixture_get(i, &sc, &name, NULL), 0);
        snprintf(path, sizeof path, FIX_DIR "/%s.truth", name);
        if (truth_load(path, t, err, sizeof err) != 0) {
            t_fail_msg(__FILE__, __LINE__, "%s", err);
            continue;
        }
        files++;
        n += check_truth_vs_camera(t, &max_err, &max_rel, &max_px);
    }
    CHECK_EQ(files, render_fixture_count());
    t_info("fixtures: %d truth files, %d ground features, max ground error %.2f mm (%.3f%% of range), "
           "max pixel error %.3f px", files, n, max_err, 100 * max_rel, max_px);
    free(t);
}

/* Scenes for the per-pixel checks: fixture names. */
static const char *pixel_scenes[] = {"aibo2004_robots_ball", "spl2013_robots_occlude",
                                     "uva2013_qvga_000001", "spl2013_640_circle"};

static void test_line_pixels(void)
{
    int k, n_line = 0, n_green = 0, nsc = t_quick ? 1 : 4;
    double worst_line = -1e9, worst_green = 1e9;
    for (k = 0; k < nsc; k++) {
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        int i, u, v;
        const char *name = NULL;
        for (i = 0; i < render_fixture_count(); i++) {
            CHECK_EQ(render_fixture_get(i, &sc, &name, NULL), 0);
            if (!strcmp(name, pixel_scenes[k]))
                break;
        }
        CHECK(i < render_fixture_count());
        CHECK_EQ(render_frame(&sc, &fr), 0);
        CHECK_EQ(render_scene_camera(&sc, &cam), FL_OK);
        for (v = 0; v < fr.height; v++)
            for (u = 0; u < fr.width; u++) {
                int cls = fr.mask[(size_t)v * (size_t)fr.width + (size_t)u];
                double fx, fy, range, sd, tol;
                if (cls != RENDER_CLASS_LINE && cls != RENDER_CLASS_GREEN)
                    continue;
                if (!fw_ground(&sc, &cam, u, v, &fx, &fy, &range))
                    continue;
                tol = 3.0 + 0.005 * range;
                sd = paint_sd(sc.field, fx, fy);
                if (cls == RENDER_CLASS_LINE) {
                    n_line++;
                    if (sd - tol > worst_line)
                        worst_line = sd - tol;
                    if (sd > tol)
                        t_fail_msg(__FILE__, __LINE__, "%s: LINE pixel (%d,%d) %.1f mm off the paint",
                                   name, u, v, sd);
                } else {
                    n_green++;
                    if (sd + tol < worst_green)
                        worst_green = sd + tol;
                    if (sd < -tol)
                        t_fail_msg(__FILE__, __LINE__, "%s: GREEN pixel (%d,%d) %.1f mm inside the paint",
                                   name, u, v, -sd);
                }
            }
        render_frame_free(&fr);
    }
    CHECK(n_line > (t_quick ? 100 : 1000));
    t_info("line pixels %d (worst margin %.2f mm), green pixels %d (worst margin %.2f mm)", n_line,
           -worst_line, n_green, worst_green);
}

static void test_border(void)
{
    int k, nsc = t_quick ? 1 : 4, cols = 0;
    for (k = 0; k < nsc; k++) {
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        int i, u, v;
        const char *name = NULL;
        for (i = 0; i < render_fixture_count(); i++) {
            CHECK_EQ(render_fixture_get(i, &sc, &name, NULL), 0);
            if (!strcmp(name, pixel_scenes[k]))
                break;
        }
        CHECK_EQ(render_frame(&sc, &fr), 0);
        CHECK_EQ(render_scene_camera(&sc, &cam), FL_OK);
        for (u = 0; u < fr.width; u++) {
            int b = fr.border_v[u], e = fr.border_end_v[u], vis = fr.height, bad = 0;
            double fx, fy, range;
            CHECK(b >= 0 && b <= fr.height && e >= b && e <= fr.height);
            for (v = 0; v < fr.height; v++) {
                int cls = fr.mask[(size_t)v * (size_t)fr.width + (size_t)u];
                int carpet = cls == RENDER_CLASS_GREEN || cls == RENDER_CLASS_LINE;
                if (carpet && vis == fr.height)
                    vis = v;
                if (v < b || v >= e)
                    bad |= carpet;
                else
                    bad |= cls == RENDER_CLASS_BACKGROUND;
            }
            CHECK(!bad);
            CHECK_EQ(fr.border_visible_v[u], vis);
            if (b < fr.height) {
                double tol;
                CHECK(fw_ground(&sc, &cam, u, b, &fx, &fy, &range));
                tol = 3.0 + 0.005 * range;
                CHECK_LE(carpet_sd(sc.field, fx, fy), tol);
                if (b > 0 && fw_ground(&sc, &cam, u, b - 1, &fx, &fy, &range))
                    CHECK(carpet_sd(sc.field, fx, fy) >= -(3.0 + 0.005 * range));
                cols++;
            }
        }
        render_frame_free(&fr);
    }
    CHECK(cols > (t_quick ? 100 : 300));
}

static void test_features_in_mask(void)
{
    int i, j, n_line = 0, n_goal = 0;
    truth_t *t = (truth_t *)malloc(sizeof *t);
    CHECK(t != NULL);
    if (!t)
        return;
    for (i = t_quick ? 21 : 0; i < render_fixture_count(); i += t_quick ? 40 : 5) {
        render_scene_t sc;
        render_frame_t fr;
        CHECK_EQ(render_fixture_get(i, &sc, NULL, NULL), 0);
        sc.noise_x10 = 0;
        CHECK_EQ(render_frame(&sc, &fr), 0);
        CHECK_EQ(truth_compute(&sc, &fr, t), 0);
        /* hl3x2's 25 mm lines, seen at 320 x 240 from a 460 mm high camera,
         * are less than one pixel row thick beyond about 1.8 m (rows per
         * mm of range ~ f h / r^2: 25 * 277 * 460 / r^2 < 1), so a
         * crossing's rounded pixel may show the carpet there */
        double line_limit = strcmp(sc.field->name, "hl3x2") == 0 ? 1500 : 3000;
        for (j = 0; j < t->n; j++) {
            const truth_feature_t *f = &t->f[j];
            int u = (int)lround(f->u), v = (int)lround(f->v);
            if (f->occluded || u < 0 || v < 0 || u >= fr.width || v >= fr.height)
                continue;
            if ((f->kind == TRUTH_L || f->kind == TRUTH_T || f->kind == TRUTH_X ||
                 f->kind == TRUTH_PENALTY_MARK) && f->range_mm < line_limit) {
                CHECK_EQ(fr.mask[(size_t)v * (size_t)fr.width + (size_t)u], RENDER_CLASS_LINE);
                n_line++;
            }
            if (f->kind == TRUTH_POST_FOOT && f->range_mm < 4000 && v >= 3) {
                CHECK_EQ(fr.mask[(size_t)(v - 3) * (size_t)fr.width + (size_t)u], RENDER_CLASS_GOAL);
                n_goal++;
            }
        }
        render_frame_free(&fr);
    }
    CHECK(n_line > (t_quick ? 3 : 10));
    CHECK(n_goal > (t_quick ? 1 : 5));
    t_info("%d crossings on LINE pixels, %d post feet under GOAL pixels", n_line, n_goal);
    free(t);
}

static void test_formats(void)
{
    render_scene_t sc;
    render_frame_t rgb, yuyv, planar;
    fl_image_t rv;
    int u, v, bad = 0;
    if (t_quick)
        render_scene_default(&sc, fl_field_find("aibo2004"), fl_camera_model_find("aibo-ers7"));
    else
        render_scene_default(&sc, fl_field_find("uva2013"), fl_camera_model_find("nao4-bottom-320"));
    sc.head.head_pitch = fl_angle_from_urad(t_quick ? 0 : -541544);
    CHECK_EQ(render_frame(&sc, &rgb), 0);
    sc.format = FL_FMT_YUYV422;
    CHECK_EQ(render_frame(&sc, &yuyv), 0);
    sc.format = FL_FMT_YCBCR_PLANAR;
    CHECK_EQ(render_frame(&sc, &planar), 0);
    CHECK(memcmp(rgb.data, yuyv.rgb, rgb.size) == 0 && memcmp(rgb.data, planar.rgb, rgb.size) == 0);
    CHECK_EQ(fl_image_init_packed(&rv, FL_FMT_RGB888, rgb.data, rgb.width, rgb.height, 3 * rgb.width), FL_OK);
    for (v = 0; v < rgb.height; v++)
        for (u = 0; u < rgb.width; u += 2) {
            uint8_t a[3], b[3], py[3], pp[3];
            fl_image_get_ycbcr(&rv, u, v, a);
            fl_image_get_ycbcr(&rv, u + 1, v, b);
            fl_image_get_ycbcr(&yuyv.view, u, v, py);
            fl_image_get_ycbcr(&planar.view, u, v, pp);
            bad |= py[0] != a[0] || py[1] != (a[1] + b[1] + 1) / 2 || py[2] != (a[2] + b[2] + 1) / 2;
            bad |= pp[0] != a[0] || pp[1] != a[1] || pp[2] != a[2];
        }
    CHECK(!bad);
    render_frame_free(&rgb);
    render_frame_free(&yuyv);
    render_frame_free(&planar);
}

static void test_colors(void)
{
    render_scene_t sc;
    render_frame_t fr;
    double sum[2][3] = {{0, 0, 0}, {0, 0, 0}};
    int n[2] = {0, 0}, u, v, c;
    render_scene_default(&sc, fl_field_find("uva2013"), fl_camera_model_find("nao4-bottom-320"));
    sc.robot_x_mm = -1200;
    sc.head.head_pitch = fl_angle_from_urad(-300000);
    sc.shadows = 0;
    CHECK_EQ(render_frame(&sc, &fr), 0);
    for (v = 2; v < fr.height - 2; v++)
        for (u = 2; u < fr.width - 2; u++) {
            size_t p = (size_t)v * (size_t)fr.width + (size_t)u;
            int cls = fr.mask[p], k, same = 1;
            if (cls != RENDER_CLASS_GREEN && cls != RENDER_CLASS_LINE)
                continue;
            for (k = -2; k <= 2; k++) /* away from edges */
                same &= fr.mask[p + (size_t)k] == cls && fr.mask[p + (size_t)(k * fr.width)] == cls;
            if (!same)
                continue;
            k = cls == RENDER_CLASS_LINE;
            for (c = 0; c < 3; c++)
                sum[k][c] += fr.rgb[3 * p + (size_t)c];
            n[k]++;
        }
    CHECK(n[0] > 1000 && n[1] > 50);
    for (c = 0; c < 3 && n[0] && n[1]; c++) {
        CHECK_LE(fabs(sum[0][c] / n[0] - render_color_carpet[c]), 0.12 * render_color_carpet[c]);
        CHECK_LE(fabs(sum[1][c] / n[1] - render_color_line[c]), 0.12 * render_color_line[c]);
    }
    if (n[0] && n[1])
        t_info("mean carpet %.0f %.0f %.0f (measured 82 141 85), line %.0f %.0f %.0f (254 253 250)",
               sum[0][0] / n[0], sum[0][1] / n[0], sum[0][2] / n[0], sum[1][0] / n[1], sum[1][1] / n[1],
               sum[1][2] / n[1]);
    render_frame_free(&fr);
}

/* hl3x2's landmark poles: three equal bands, YBY at +y and BYB at -y, no
 * white base.  The pole's pixels in the centre column (mask class BEACON)
 * are split into thirds; the middle of each third must show its band's
 * color (yellow: red and green well above blue; sky-blue: blue above red),
 * and the lowest pole pixel the bottom band's. */
static int is_yellowish(const uint8_t *c) { return c[0] > c[2] + 60 && c[1] > c[2] + 60; }
static int is_bluish(const uint8_t *c) { return c[2] > c[0] + 60; }

static void test_hl3x2_poles(void)
{
    int side;
    for (side = 0; side < 2; side++) {
        render_scene_t sc;
        render_frame_t fr;
        int v, top = -1, bot = -1, u = 320, k;
        render_scene_default(&sc, fl_field_find("hl3x2"), fl_camera_model_find("acyut-640"));
        sc.robot_heading = side ? fl_angle_from_mdeg(-90000) : fl_angle_from_mdeg(90000);
        sc.shadows = 0;
        sc.background = 0;
        sc.supersample = 1;   /* the bands are 40+ rows tall: no edge detail needed */
        CHECK_EQ(sc.head.head_pitch, RENDER_HUMANOID_HEAD_PITCH);
        CHECK_EQ(render_frame(&sc, &fr), 0);
        for (v = 0; v < fr.height; v++)
            if (fr.mask[(size_t)v * (size_t)fr.width + (size_t)u] == RENDER_CLASS_BEACON) {
                if (top < 0)
                    top = v;
                bot = v;
            }
        CHECK(top >= 0 && bot - top > 60);   /* 300 mm at 1.2 m: about 130 px */
        if (top >= 0 && bot - top > 60) {
            for (k = 0; k < 3; k++) {
                int vm = top + (2 * k + 1) * (bot - top) / 6;
                const uint8_t *c = fr.rgb + 3 * ((size_t)vm * (size_t)fr.width + (size_t)u);
                int want_yellow = (k == 1) == (side == 1);
                CHECK(want_yellow ? is_yellowish(c) : is_bluish(c));
            }
            /* no white base: the lowest pole pixels are the bottom band */
            CHECK(side ? is_bluish(fr.rgb + 3 * ((size_t)(bot - 2) * (size_t)fr.width + (size_t)u))
                       : is_yellowish(fr.rgb + 3 * ((size_t)(bot - 2) * (size_t)fr.width + (size_t)u)));
        }
        render_frame_free(&fr);
    }
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* Table, index and sizes of the committed set. */
static void test_fixture_set(void)
{
    int i, listed = 0, missing = 0;
    long total = 0;
    char line[512];
    FILE *idx = fopen(FIX_DIR "/index.txt", "r");
    CHECK(idx != NULL);
    if (!idx)
        return;
    while (fgets(line, sizeof line, idx)) {
        char name[128], file[160], path[512];
        long s;
        if (line[0] == '#' || sscanf(line, "%127s %159s", name, file) != 2)
            continue;
        listed++;
        snprintf(path, sizeof path, FIX_DIR "/%s", file);
        s = file_size(path);
        missing += s < 0;
        total += s > 0 ? s : 0;
        snprintf(path, sizeof path, FIX_DIR "/%s.truth", name);
        s = file_size(path);
        missing += s < 0;
        total += s > 0 ? s : 0;
        snprintf(path, sizeof path, FIX_DIR "/%s.scene", name);
        s = file_size(path);
        missing += s < 0;
        total += s > 0 ? s : 0;
    }
    fclose(idx);
    CHECK_EQ(listed, render_fixture_count());
    CHECK(listed >= 60);
    CHECK_EQ(missing, 0);
    CHECK_LE(total, 20L * 1000 * 1000);
    t_info("fixture set: %d frames, %.1f MB (frames + truth + scene)", listed, (double)total / 1e6);
    /* README lists every fixture */
    {
        size_t len = 0;
        char *readme = t_read_file("fixtures/README.md", &len);
        CHECK(readme != NULL);
        for (i = 0; readme && i < render_fixture_count(); i++) {
            render_scene_t sc;
            const char *name;
            char needle[160];
            CHECK_EQ(render_fixture_get(i, &sc, &name, NULL), 0);
            snprintf(needle, sizeof needle, "| %s |", name);
            if (!strstr(readme, needle))
                t_fail_msg(__FILE__, __LINE__, "fixtures/README.md does not list %s", name);
        }
        free(readme);
    }
    /* every committed scene equals the table */
    for (i = 0; i < render_fixture_count(); i++) {
        render_scene_t sc;
        const char *name;
        char path[512], *committed;
        static char mine[8192];
        size_t len = 0, n;
        FILE *f = tmpfile();
        CHECK_EQ(render_fixture_get(i, &sc, &name, NULL), 0);
        snprintf(path, sizeof path, FIX_DIR "/%s.scene", name);
        committed = t_read_file(path, &len);
        CHECK(committed != NULL && f != NULL);
        if (committed && f) {
            CHECK_EQ(render_scene_write(f, &sc), 0);
            rewind(f);
            n = fread(mine, 1, sizeof mine, f);
            if (n != len || memcmp(mine, committed, n) != 0)
                t_fail_msg(__FILE__, __LINE__, "%s differs from the fixture table (run make fixtures)", path);
        }
        free(committed);
        if (f)
            fclose(f);
    }
}

/* A few fixtures re-rendered from their committed .scene: identical bytes. */
static void test_fixtures_rerender(void)
{
    static const char *names[] = {"aibo2004_dark", "spl2013_robots_goal", "uva2013_qvga_000001",
                                  "spl2013_jpeg_noise", "spl2013_blur_diag"};
    int k, n = t_quick ? 2 : 5;
    truth_t *t = (truth_t *)malloc(sizeof *t);
    CHECK(t != NULL);
    if (!t)
        return;
    for (k = 0; k < n; k++) {
        render_scene_t sc;
        render_frame_t fr, committed;
        char path[512], err[256], *text;
        size_t len = 0;
        FILE *f;
        snprintf(path, sizeof path, FIX_DIR "/%s.scene", names[k]);
        if (render_scene_load(path, &sc, err, sizeof err) != 0) {
            t_fail_msg(__FILE__, __LINE__, "%s", err);
            continue;
        }
        CHECK_EQ(render_frame(&sc, &fr), 0);
        snprintf(path, sizeof path, FIX_DIR "/%s.%s", names[k], sc.format == FL_FMT_RGB888 ? "ppm" : "raw");
        if (render_read_frame(path, &committed, err, sizeof err) != 0) {
            t_fail_msg(__FILE__, __LINE__, "%s", err);
            render_frame_free(&fr);
            continue;
        }
        CHECK_EQ(committed.format, fr.format);
        CHECK(committed.size == fr.size && memcmp(committed.data, fr.data, fr.size) == 0);
        t_digest(names[k], hash_frame(&fr));
        /* the truth text too */
        CHECK_EQ(truth_compute(&sc, &fr, t), 0);
        snprintf(path, sizeof path, FIX_DIR "/%s.truth", names[k]);
        text = t_read_file(path, &len);
        f = tmpfile();
        CHECK(text != NULL && f != NULL);
        if (text && f) {
            char *mine = (char *)malloc(len + 2);
            size_t got;
            CHECK_EQ(truth_write(f, t), 0);
            rewind(f);
            got = mine ? fread(mine, 1, len + 1, f) : 0;
            CHECK(got == len && memcmp(mine, text, len) == 0);
            free(mine);
        }
        free(text);
        if (f)
            fclose(f);
        render_frame_free(&committed);
        render_frame_free(&fr);
    }
    free(t);
}

void suite_render(void)
{
    t_run("render.determinism", test_determinism);
    t_run("render.cache", test_cache);
    t_run("render.bad_input", test_bad_input);
    t_run("render.scene_roundtrip", test_scene_roundtrip);
    t_run("render.truth_roundtrip", test_truth_roundtrip);
    t_run("render.camera_agreement_random", test_camera_agreement_random);
    t_run("render.camera_agreement_fixtures", test_camera_agreement_fixtures);
    t_run("render.line_pixels", test_line_pixels);
    t_run("render.border", test_border);
    t_run("render.features_in_mask", test_features_in_mask);
    t_run("render.formats", test_formats);
    t_run("render.colours", test_colors);
    t_run("render.hl3x2_poles", test_hl3x2_poles);
    t_run("render.fixture_set", test_fixture_set);
    t_run("render.fixtures_rerender", test_fixtures_rerender);
}
