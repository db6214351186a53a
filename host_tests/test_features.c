/*
 * host_tests/test_features.c - crossings, marks, goal posts, the centre
 * circle and the one-call vision path (crossings.h, goal.h, circle.h,
 * vision.h):
 *   - crossings from synthetic point sets: L / T / X by arm geometry, two
 *     opposite T's merged into an X, the 10-degree and in-image rules;
 *   - the ground check and orientation with a camera: ground lines
 *     projected into the image (a square corner passes with the right
 *     bisector, a 60-degree one fails);
 *   - the circle fitted on the ground from projected arc points, with its
 *     orientation from the halfway line;
 *   - a painted goal post (foot, width, side from the crossbar) and a
 *     yellow object beyond the field border (rejected);
 *   - bad input and noise frames through fl_vision_frame (bounded, caps
 *     counted), memory sizes;
 *   - goldens: every fixture's integer outputs against fixtures/golden/
 *     (rewrite with FIELDLOC_WRITE_GOLDEN=1 build/run_tests -k features);
 *   - the fixture and UvA 2013 evaluation (tools/cli/cmd_eval_detect.c) with
 *     the measured levels as regression floors and the targets
 *     printed as gaps.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "eval/detect.h"
#include "world/render.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static fl_lines_t L;
static fl_crossings_t X;
static fl_circle_t C;
static fl_posts_t P;

static void lines_default(int w, int h)
{
    fl_lines_params_t p;
    fl_lines_params_default(&p);
    CHECK_EQ(fl_lines_init(&L, &p), FL_OK);
    CHECK(fl_lines_reset(&L, w, h));
}

static void crossings_default(void)
{
    fl_crossings_params_t p;
    fl_crossings_params_default(&p);
    CHECK_EQ(fl_crossings_init(&X, &p), FL_OK);
}

static void add_line(double u0, double v0, double u1, double v1, double step)
{
    double len = hypot(u1 - u0, v1 - v0);
    int k, n = (int)(len / step);
    /* as a scanner finds them (see test_lines.c) */
    uint8_t fl = fabs(v1 - v0) < fabs(u1 - u0) ? FL_LINE_POINT_VERTICAL : 0;
    for (k = 0; k <= n; k++) {
        double t = (double)k / (n > 0 ? n : 1);
        fl_lines_add_point(&L, (int32_t)lround(2 * (u0 + t * (u1 - u0))),
                           (int32_t)lround(2 * (v0 + t * (v1 - v0))), 3, fl);
    }
}

static uint32_t digest_crossings(uint32_t h)
{
    int32_t i;
    h = t_hash_i32(h, X.n);
    for (i = 0; i < X.n; i++) {
        h = t_hash_i32(h, X.c[i].kind);
        h = t_hash_i32(h, X.c[i].u_q4);
        h = t_hash_i32(h, X.c[i].v_q4);
        h = t_hash_i32(h, X.c[i].confidence);
        h = t_hash_i32(h, X.c[i].range_mm);
        h = t_hash_i32(h, X.c[i].orientation);
    }
    return h;
}

/* ---- crossings on synthetic points ---------------------------------------------- */

static void test_params(void)
{
    fl_crossings_params_t p;
    fl_crossings_params_default(&p);
    CHECK_EQ(fl_crossings_init(NULL, &p), FL_ERR_NULL);
    p.min_angle_mdeg = 500;
    CHECK_EQ(fl_crossings_init(&X, &p), FL_ERR_RANGE);
    fl_crossings_params_default(&p);
    p.probe_green_pct = p.probe_white_pct + 1;
    CHECK_EQ(fl_crossings_init(&X, &p), FL_ERR_RANGE);
    crossings_default();
    CHECK_EQ(fl_crossings_find(&X, NULL, NULL, NULL, NULL), 0);
    CHECK_EQ(fl_crossings_find(NULL, &L, NULL, NULL, NULL), 0);
    CHECK_EQ(fl_circle_find(NULL, &L, NULL, NULL), 0);
    CHECK_EQ(fl_circle_find(&C, &L, NULL, NULL), 0);
    CHECK(!C.found);
    CHECK_EQ(fl_goal_find(NULL, NULL, NULL, NULL, NULL, NULL), 0);
    CHECK_EQ(fl_goal_find(&P, NULL, NULL, NULL, NULL, NULL), 0);
    CHECK_EQ(P.n, 0);
}

/* Find the crossing nearest to (u, v); NULL when none within 3 px. */
static const fl_crossing_t *near(double u, double v)
{
    int32_t i;
    for (i = 0; i < X.n; i++)
        if (hypot(X.c[i].u_q4 / 16.0 - u, X.c[i].v_q4 / 16.0 - v) <= 3.0)
            return &X.c[i];
    return NULL;
}

static void test_types(void)
{
    const fl_crossing_t *c;
    uint32_t h = t_hash_init();
    /* L at (100, 150): arms right and up */
    lines_default(320, 240);
    add_line(100, 150, 250, 150, 4);
    add_line(100, 150, 100, 30, 4);
    fl_lines_find_segments(&L, NULL);
    crossings_default();
    fl_crossings_find(&X, &L, NULL, NULL, NULL);
    CHECK_EQ(X.n, 1);
    c = near(100, 150);
    CHECK(c && c->kind == FL_LM_L && c->n_arms == 2);
    h = digest_crossings(h);
    /* T at (160, 60): bar along v = 60, stem down */
    lines_default(320, 240);
    add_line(40, 60, 280, 60, 4);
    add_line(160, 62, 160, 220, 4);
    fl_lines_find_segments(&L, NULL);
    fl_crossings_find(&X, &L, NULL, NULL, NULL);
    CHECK_EQ(X.n, 1);
    c = near(160, 60);
    CHECK(c && c->kind == FL_LM_T && c->n_arms == 3);
    h = digest_crossings(h);
    /* X at (160, 120) */
    lines_default(320, 240);
    add_line(40, 40, 280, 200, 4);
    add_line(40, 200, 280, 40, 4);
    fl_lines_find_segments(&L, NULL);
    fl_crossings_find(&X, &L, NULL, NULL, NULL);
    CHECK_EQ(X.n, 1);
    c = near(160, 120);
    CHECK(c && c->kind == FL_LM_X && c->n_arms == 4);
    h = digest_crossings(h);
    /* two opposite T's (a crossing line cut at the bar and not merged
     * back: merging off) -> one X */
    {
        fl_lines_params_t p;
        fl_lines_params_default(&p);
        p.merge_gap_px = 1;
        CHECK_EQ(fl_lines_init(&L, &p), FL_OK);
        CHECK(fl_lines_reset(&L, 320, 240));
    }
    add_line(40, 120, 280, 120, 4);
    add_line(160, 20, 160, 110, 4);
    add_line(160, 130, 160, 230, 4);
    CHECK_EQ(fl_lines_find_segments(&L, NULL), 3);
    fl_crossings_find(&X, &L, NULL, NULL, NULL);
    CHECK_EQ(X.n, 1);
    CHECK(X.merged >= 1);
    c = near(160, 120);
    CHECK(c && c->kind == FL_LM_X && c->n_arms == 4);
    h = digest_crossings(h);
    /* nearly parallel (8 deg): no crossing; meeting outside the image: none */
    lines_default(320, 240);
    add_line(20, 100, 150, 100, 4);
    add_line(150, 100, 300, 121, 4);
    fl_lines_find_segments(&L, NULL);
    fl_crossings_find(&X, &L, NULL, NULL, NULL);
    CHECK_EQ(X.n, 0);
    lines_default(320, 240);
    add_line(20, 20, 20, 200, 4);
    add_line(60, 20, 300, 26, 4);
    fl_lines_find_segments(&L, NULL);
    fl_crossings_find(&X, &L, NULL, NULL, NULL);
    CHECK_EQ(X.n, 0); /* they would meet left of (20, ...) but end 40 px away */
    t_digest("features.types", h);
}

/* ---- with a camera: ground lines projected ---------------------------------------- */

static fl_camera_t cam;

static void camera_down(const char *model, double pitch_deg)
{
    fl_camera_pose_t pose = {450, 0, 0, 0, 0, 0, 0};
    pose.head_pitch = fl_angle_from_mdeg((int32_t)lround(pitch_deg * 1000));
    CHECK_EQ(fl_camera_init(&cam, fl_camera_model_find(model), &pose), FL_OK);
}

/* Points of the ground segment (robot frame, mm) every 20 mm, projected. */
static void add_ground_line(double x0, double y0, double x1, double y1)
{
    double len = hypot(x1 - x0, y1 - y0);
    int k, n = (int)(len / 20);
    int32_t pu = 0, pv = 0;
    for (k = 0; k <= n; k++) {
        double t = (double)k / n;
        fl_point_t g;
        int32_t u, v;
        g.x_mm = (int32_t)lround(x0 + t * (x1 - x0));
        g.y_mm = (int32_t)lround(y0 + t * (y1 - y0));
        if (fl_camera_ground_to_pixel(&cam, g, &u, &v) && u >= 0 && v >= 0 &&
            u < 16 * 319 && v < 16 * 239) {
            if (k == 0) {
                pu = u;
                pv = v;
            }
            fl_lines_add_point(&L, (u + 4) / 8, (v + 4) / 8, 3,
                               abs(v - pv) < abs(u - pu) ? FL_LINE_POINT_VERTICAL : 0);
        }
    }
}

static void test_ground_check(void)
{
    const fl_crossing_t *c;
    fl_point_t corner = {1500, 200};
    int32_t u, v;
    double o;
    camera_down("nao4-top-320", 20);
    CHECK(fl_camera_ground_to_pixel(&cam, corner, &u, &v));
    /* square corner, arms toward +x... no: toward the robot (-x) and left (+y) */
    lines_default(320, 240);
    add_ground_line(1500, 200, 900, 200);
    add_ground_line(1500, 200, 1500, 900);
    fl_lines_find_segments(&L, NULL);
    crossings_default();
    fl_crossings_find(&X, &L, NULL, &cam, NULL);
    CHECK_EQ(X.n, 1);
    c = near(u / 16.0, v / 16.0);
    CHECK(c != NULL);
    if (c) {
        CHECK_EQ(c->kind, FL_LM_L);
        CHECK(c->has_orientation);
        /* bisector of 180 deg (-x) and 90 deg (+y): 135 deg */
        o = c->orientation * 180.0 / 32768;
        CHECK_LE(fabs(o - 135), 3.0);
        CHECK_LE(abs(c->range_mm - 1513), 40);
        t_info("square corner: orientation %.2f deg (135), range %d mm (1513)", o,
               (int)c->range_mm);
    }
    /* 60-degree corner: fails the ground check */
    lines_default(320, 240);
    add_ground_line(1500, 200, 900, 200);
    add_ground_line(1500, 200, 1850, 806);
    fl_lines_find_segments(&L, NULL);
    fl_crossings_find(&X, &L, NULL, &cam, NULL);
    CHECK_EQ(X.n, 0);
    CHECK(X.rejected_ground >= 1);
    /* without the camera the same pair is an L */
    fl_crossings_find(&X, &L, NULL, NULL, NULL);
    CHECK_EQ(X.n, 1);
    t_digest("features.ground", digest_crossings(t_hash_init()));
}

static void test_circle(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    double cx = 2300, cy = -300, R = f->circle_radius_mm, err;
    int k;
    camera_down("nao4-top-320", 18);
    lines_default(320, 240);
    /* the circle every 3 deg and the halfway line through its centre */
    for (k = 0; k < 120; k++) {
        double a = k * 3 * M_PI / 180;
        fl_point_t g;
        int32_t u, v;
        g.x_mm = (int32_t)lround(cx + R * cos(a));
        g.y_mm = (int32_t)lround(cy + R * sin(a));
        if (fl_camera_ground_to_pixel(&cam, g, &u, &v) && u >= 0 && v >= 0 &&
            u < 16 * 319 && v < 16 * 239)
            fl_lines_add_point(&L, (u + 4) / 8, (v + 4) / 8, 3, (uint8_t)(k & 1));
    }
    add_ground_line(cx - 40, cy - 1400, cx + 40, cy + 1400);
    fl_lines_find_segments(&L, NULL);
    CHECK_EQ(fl_circle_find(&C, &L, &cam, f), 1);
    CHECK(C.found);
    if (!C.found)
        return;
    err = hypot(C.centre.x_mm - cx, C.centre.y_mm - cy);
    t_info("circle centre error %.1f mm at %.0f mm (rms %d mm, %d points, %d chords)", err,
           hypot(cx, cy), (int)C.rms_mm, (int)C.n_points, (int)C.n_segments);
    CHECK_LE(err, 60);
    CHECK(C.has_orientation);
    if (C.has_orientation) {
        double o = C.orientation * 180.0 / 32768, want = atan2(2800, 80) * 180 / M_PI;
        CHECK_LE(fabs(o - want), 3.0);
    }
    /* its chords are flagged: the crossing stage makes no L/T from them */
    crossings_default();
    fl_crossings_find(&X, &L, NULL, &cam, f);
    for (k = 0; k < X.n; k++)
        CHECK(X.c[k].kind != FL_LM_L);
    /* a field without a circle, or no camera: nothing */
    CHECK_EQ(fl_circle_find(&C, &L, NULL, f), 0);
    t_digest("features.circle", t_hash_i32(t_hash_i32(t_hash_init(), C.centre.x_mm), C.centre.y_mm));
}

/* ---- goal posts on painted frames ------------------------------------------------ */

static const uint8_t CARPET[3] = {82, 141, 85}, POST[3] = {191, 185, 47},
                     WALL[3] = {150, 140, 150};

static void fill(uint8_t *rgb, int w, int u0, int v0, int u1, int v1, const uint8_t c[3])
{
    int u, v;
    for (v = v0 < 0 ? 0 : v0; v < v1; v++)
        for (u = u0 < 0 ? 0 : u0; u < u1 && u < w; u++)
            memcpy(rgb + 3 * ((size_t)v * (size_t)w + (size_t)u), c, 3);
}

static void test_goal_painted(void)
{
    enum { W = 320, H = 240 };
    static fl_color_table_t colors;
    static fl_scan_t scan;
    uint8_t *rgb = malloc((size_t)W * H * 3);
    const fl_field_t *f = fl_field_find("spl2013");
    fl_color_params_t cp;
    fl_scan_params_t sp;
    fl_image_t img;
    fl_point_t g;
    int32_t foot_v = 150, hpx, wpx, range;
    double d;
    camera_down("nao4-top-320", 8);
    /* the post's size at the foot's distance */
    CHECK(fl_camera_pixel_to_ground(&cam, 100 * 16, foot_v * 16, &g));
    range = (int32_t)fl_hypot(g.x_mm, g.y_mm);
    d = hypot(range, 500 - 400);
    hpx = (int32_t)lround(cam.model.focal_q4 / 16.0 * 800 / d);
    wpx = (int32_t)lround(cam.model.focal_q4 / 16.0 * 100 / d);
    fill(rgb, W, 0, 0, W, H, WALL);
    fill(rgb, W, 0, foot_v - 10, W, H, CARPET);               /* border at 140 */
    fill(rgb, W, 100 - wpx / 2, foot_v - hpx, 100 + wpx - wpx / 2, foot_v, POST);
    fill(rgb, W, 100 - wpx / 2, foot_v - hpx, 250, foot_v - hpx + wpx, POST); /* crossbar */
    /* a yellow box beyond the border: stands on the wall, no field below */
    fill(rgb, W, 280, 60, 290, 120, POST);
    fl_color_params_default(&cp);
    CHECK_EQ(fl_color_init(&colors, &cp), FL_OK);
    fl_scan_params_default(&sp);
    sp.col_step = sp.row_step = 1;
    sp.border_run_px = 4;
    CHECK_EQ(fl_scan_init(&scan, &sp), FL_OK);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, rgb, W, H, 3 * W), FL_OK);
    CHECK(fl_scan_frame(&scan, &colors, &img, &cam) > 0);
    CHECK_EQ(fl_goal_find(&P, &scan, &img, &colors, &cam, f), 1);
    if (P.n == 1) {
        const fl_post_t *p = &P.post[0];
        CHECK(p->foot_visible);
        CHECK_LE(fabs(p->foot_u_q4 / 16.0 - 100), 2.0);
        CHECK_LE(fabs(p->foot_v_q4 / 16.0 - foot_v), 4.0);
        CHECK_LE(fabs(p->width_q4 / 16.0 - wpx), 1.5);
        CHECK_EQ(p->side, FL_SIDE_LEFT);          /* crossbar to the right */
        CHECK(p->top_visible);
        CHECK(!p->range_from_width);
        /* ground range: the foot (front of the post) plus the radius */
        CHECK_LE(abs(p->range_mm - (range + 50)), range / 25);
        t_info("painted post: range %d mm (foot %d + 50), width %.1f px (%d)", (int)p->range_mm,
               (int)range, p->width_q4 / 16.0, (int)wpx);
    }
    /* the same without the field under the post: nothing */
    fill(rgb, W, 0, 0, W, H, WALL);
    fill(rgb, W, 100 - wpx / 2, foot_v - hpx, 100 + wpx - wpx / 2, foot_v, POST);
    fill(rgb, W, 0, 200, W, H, CARPET);
    fl_scan_frame(&scan, &colors, &img, &cam);
    CHECK_EQ(fl_goal_find(&P, &scan, &img, &colors, &cam, f), 0);
    free(rgb);
}

/* ---- the vision path ------------------------------------------------------------- */

static void test_vision_bad_input(void)
{
    det_ctx_t dc;
    fl_obs_list_t obs;
    fl_image_t img;
    fl_vision_params_t p;
    uint8_t px[3 * 64 * 48];
    CHECK_EQ(det_ctx_init(&dc), 0);
    fl_vision_params_default(&p);
    p.min_confidence = 300;
    CHECK_EQ(fl_vision_init(dc.vis, &p), FL_ERR_RANGE);
    fl_vision_params_default(&p);
    CHECK_EQ(fl_vision_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_vision_init(dc.vis, &p), FL_OK);
    CHECK_EQ(fl_vision_frame(NULL, dc.colors, &img, NULL, NULL, &obs), 0);
    CHECK_EQ(fl_vision_frame(dc.vis, dc.colors, NULL, NULL, fl_field_find("spl2013"), &obs), 0);
    CHECK_EQ(obs.n, 0);
    CHECK_EQ(dc.vis->status, FL_ERR_NULL);
    memset(&img, 0x33, sizeof img);
    CHECK_EQ(fl_vision_frame(dc.vis, dc.colors, &img, NULL, fl_field_find("spl2013"), &obs), 0);
    CHECK(dc.vis->status != FL_OK);
    /* a frame with no field at all: empty, valid */
    memset(px, 90, sizeof px);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, px, 64, 48, 64 * 3), FL_OK);
    CHECK_EQ(fl_vision_frame(dc.vis, dc.colors, &img, NULL, fl_field_find("spl2013"), &obs), 0);
    CHECK_EQ(dc.vis->status, FL_OK);
    CHECK_EQ(dc.vis->lines.n_segments, 0);
    t_info("sizeof fl_vision_t %lu B (scan %lu, lines %lu, circle %lu, crossings %lu, posts %lu)",
           (unsigned long)sizeof(fl_vision_t), (unsigned long)sizeof(fl_scan_t),
           (unsigned long)sizeof(fl_lines_t), (unsigned long)sizeof(fl_circle_t),
           (unsigned long)sizeof(fl_crossings_t), (unsigned long)sizeof(fl_posts_t));
    det_ctx_free(&dc);
}

/* The frame must be the camera model's size and the camera initialized:
 * else nothing is processed, the observations are empty, the status says
 * why, and the next matching frame gives what a fresh state gives. */
static uint32_t vision_obs_hash(const fl_obs_list_t *obs)
{
    uint32_t h = t_hash_i32(t_hash_init(), obs->n);
    int i;
    for (i = 0; i < obs->n; i++) {
        h = t_hash_i32(h, (int32_t)obs->obs[i].kind);
        h = t_hash_i32(h, obs->obs[i].range_mm);
        h = t_hash_i32(h, obs->obs[i].bearing);
    }
    return h;
}

static void vision_expect_refused(det_ctx_t *dc, const fl_image_t *img, const fl_camera_t *camera,
                                  const fl_field_t *field, fl_status_t want)
{
    fl_obs_list_t obs;
    uint32_t frames = dc->vis->frames;
    memset(&obs, 0x5a, sizeof obs);
    CHECK_EQ(fl_vision_frame(dc->vis, dc->colors, img, camera, field, &obs), 0);
    CHECK_EQ(obs.n, 0);
    CHECK_EQ(obs.dropped, 0);
    CHECK_EQ(dc->vis->status, want);
    CHECK_EQ(dc->vis->frames, frames);   /* not counted: not processed */
    CHECK_EQ(dc->vis->lines.n_points + dc->vis->lines.n_segments + dc->vis->crossings.n +
             dc->vis->posts.n + dc->vis->beacons.n, 0);
    CHECK(!dc->vis->circle.found);
}

static void test_vision_camera_mismatch(void)
{
    det_ctx_t dc, fresh;
    render_scene_t sc;
    render_frame_t fr;
    fl_camera_t cam320, cam640, bad;
    fl_camera_pose_t pose;
    fl_obs_list_t obs;
    fl_image_t big;
    uint8_t *px = calloc(640 * 480, 3);
    char err[256];
    uint32_t want;
    int32_t n;
    FILE *f = fopen("fixtures/frames/spl2013_t_near.scene", "r");
    CHECK(f != NULL && px != NULL);
    if (!f || !px) {
        if (f) fclose(f);
        free(px);
        return;
    }
    CHECK_EQ(render_scene_read(f, &sc, err, sizeof err), 0);
    fclose(f);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK_EQ(fr.width, 320);
    CHECK_EQ(det_ctx_init(&dc), 0);
    CHECK_EQ(det_ctx_init(&fresh), 0);
    CHECK_EQ(fl_camera_init(&cam320, sc.camera, &sc.head), FL_OK);
    n = fl_vision_frame(fresh.vis, fresh.colors, &fr.view, &cam320, sc.field, &obs);
    CHECK_EQ(n, obs.n);
    want = vision_obs_hash(&obs);
    CHECK(obs.n > 0);   /* the fixture shows a T: a refusal is not "nothing seen" */

    /* the case that used to pass: a 640x480 frame with a 320x240 model */
    CHECK_EQ(fl_image_init_packed(&big, FL_FMT_RGB888, px, 640, 480, 640 * 3), FL_OK);
    vision_expect_refused(&dc, &big, &cam320, sc.field, FL_ERR_MISMATCH);
    /* the 320x240 frame with a 640x480 model of the same camera */
    pose = sc.head;
    CHECK_EQ(fl_camera_init(&cam640, fl_camera_model_find("nao4-bottom-640"), &pose), FL_OK);
    vision_expect_refused(&dc, &fr.view, &cam640, sc.field, FL_ERR_MISMATCH);
    /* a camera whose init failed (neck height out of range: zeroed) */
    pose.neck_height_mm = 1;
    CHECK_EQ(fl_camera_init(&bad, sc.camera, &pose), FL_ERR_RANGE);
    vision_expect_refused(&dc, &fr.view, &bad, sc.field, FL_ERR_CAMERA);
    /* a width that matches but a height that does not (a cropped view) */
    {
        fl_image_t crop = fr.view;
        crop.height = fr.view.height - 2;
        vision_expect_refused(&dc, &crop, &cam320, sc.field, FL_ERR_MISMATCH);
    }
    /* every status names its cause */
    CHECK(strstr(fl_status_str(FL_ERR_MISMATCH), "camera model") != NULL);
    CHECK(strstr(fl_status_str(FL_ERR_CAMERA), "fl_camera_init") != NULL);
    CHECK(strcmp(fl_status_str(FL_ERR_MISMATCH), fl_status_str(FL_ERR_CAMERA)) != 0);

    /* the state is usable: the matching frame gives what a fresh state gives */
    n = fl_vision_frame(dc.vis, dc.colors, &fr.view, &cam320, sc.field, &obs);
    CHECK_EQ(n, obs.n);
    CHECK_EQ(dc.vis->status, FL_OK);
    CHECK_EQ(dc.vis->frames, 1);
    CHECK_EQ(vision_obs_hash(&obs), want);
    /* no camera at all is still accepted (image-level stages only) */
    CHECK_EQ(fl_vision_frame(dc.vis, dc.colors, &big, NULL, sc.field, &obs), 0);
    CHECK_EQ(dc.vis->status, FL_OK);
    det_ctx_free(&dc);
    det_ctx_free(&fresh);
    render_frame_free(&fr);
    free(px);
}

/* Random class noise: bounded output, caps counted, nothing square. */
static void test_vision_noise(void)
{
    static const uint8_t pal[5][3] = {
        {82, 141, 85}, {254, 253, 250}, {191, 185, 47}, {90, 60, 40}, {60, 110, 62}};
    det_ctx_t dc;
    fl_obs_list_t obs;
    fl_image_t img;
    t_rng_t r;
    int sz, k, n_cross = 0;
    CHECK_EQ(det_ctx_init(&dc), 0);
    t_rng_seed(&r, 77);
    for (sz = 0; sz < 2; sz++) {
        int w = sz ? 640 : 320, h = w * 3 / 4;
        uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
        camera_down(sz ? "nao4-top-640" : "nao4-top-320", 15);
        for (k = 0; k < w * h; k++)
            memcpy(rgb + 3 * k, pal[t_rng_range(&r, 0, 4)], 3);
        CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, rgb, w, h, 3 * w), FL_OK);
        fl_vision_frame(dc.vis, dc.colors, &img, &cam, fl_field_find("spl2013"), &obs);
        CHECK(obs.n <= FL_OBS_MAX);
        CHECK(dc.vis->lines.n_points <= FL_LINES_MAX_POINTS);
        CHECK(dc.vis->lines.n_points == FL_LINES_MAX_POINTS || dc.vis->lines.points_dropped == 0);
        /* class noise overflows the points: the clutter budgets apply
         * (growth checks FL_LINES_MAX_POINTS / 2, ridge checks 64, marks
         * 64 clusters) */
        CHECK(dc.vis->lines.points_dropped > 0);
        CHECK_LE(dc.vis->lines.white_checks, FL_LINES_MAX_POINTS / 2);
        CHECK(dc.vis->lines.checks_capped > 0);
        CHECK_LE(dc.vis->lines.ridge_checks, 64);
        n_cross += dc.vis->crossings.n;
        t_info("noise %dx%d: points %d (+%d dropped), white checks %d, segments %d, "
               "crossings %d, posts %d, circle %d",
               w, h, (int)dc.vis->lines.n_points, (int)dc.vis->lines.points_dropped,
               (int)dc.vis->lines.white_checks,
               (int)dc.vis->lines.n_segments, (int)dc.vis->crossings.n, (int)dc.vis->posts.n,
               (int)dc.vis->circle.found);
        free(rgb);
    }
    CHECK_LE(n_cross, 2);
    det_ctx_free(&dc);
}

/* ---- goldens --------------------------------------------------------------------- */

/* The integer outputs of one frame, one item per line. */
static int golden_text(const fl_vision_t *v, char *buf, size_t cap)
{
    size_t n = 0;
    int32_t i;
#define GOUT(...)                                                                 \
    do {                                                                          \
        int w_ = snprintf(buf + n, cap > n ? cap - n : 0, __VA_ARGS__);           \
        if (w_ > 0)                                                               \
            n += (size_t)w_;                                                      \
    } while (0)
    GOUT("points %d segments %d\n", (int)v->lines.n_points, (int)v->lines.n_segments);
    for (i = 0; i < v->crossings.n; i++) {
        const fl_crossing_t *x = &v->crossings.c[i];
        GOUT("crossing %d %d %d %d %d %d %d %d\n", (int)x->kind, (int)x->u_q4, (int)x->v_q4,
             (int)x->confidence, (int)x->range_mm, (int)x->bearing,
             x->has_orientation ? (int)x->orientation : 99999, (int)x->n_arms);
    }
    for (i = 0; i < v->posts.n; i++) {
        const fl_post_t *p = &v->posts.post[i];
        GOUT("post %d %d %d %d %d %d %d %d %d %d %d %d\n", (int)p->foot_u_q4, (int)p->foot_v_q4,
             (int)p->top_u_q4, (int)p->top_v_q4, (int)p->width_q4, (int)p->foot_visible,
             (int)p->top_visible, (int)p->side, (int)p->range_mm, (int)p->bearing,
             (int)p->range_from_width, (int)p->confidence);
    }
    if (v->circle.found)
        GOUT("circle %d %d %d %d %d %d\n", (int)v->circle.centre.x_mm,
             (int)v->circle.centre.y_mm, v->circle.has_pixel ? (int)v->circle.u_q4 : -1,
             v->circle.has_pixel ? (int)v->circle.v_q4 : -1,
             v->circle.has_orientation ? (int)v->circle.orientation : 99999,
             (int)v->circle.confidence);
#undef GOUT
    return n < cap ? 0 : -1;
}

/* A T at the field border from one segment (crossings.h, "Border"): in
 * spl2013_circle_side the halfway line runs up to the far side line, which
 * is too thin there for the class map; without the luma points (lines.h)
 * it gives no segment, and the T must be found at the truth (within 8 px)
 * as a border T; with the border search disabled (no camera for the
 * crossing stage) it is not.  With the luma points the far side line is a
 * segment and the T comes from the pair. */
static void test_border_t(void)
{
    static truth_t tr;
    render_frame_t fr;
    fl_camera_t fc;
    fl_obs_list_t obs;
    det_ctx_t dc;
    fl_vision_params_t vp;
    char err[256];
    int32_t i, found = 0, k, pair = 0;
    const fl_field_t *field = fl_field_find("spl2013");
    if (truth_load("fixtures/frames/spl2013_circle_side.truth", &tr, err, sizeof err) != 0 ||
        render_read_frame("fixtures/frames/spl2013_circle_side.raw", &fr, err, sizeof err) != 0) {
        t_info("skipped: fixture spl2013_circle_side not found (run from the repository root)");
        return;
    }
    CHECK_EQ(fl_camera_init(&fc, fl_camera_model_find("nao4-top-320"), &tr.head), FL_OK);
    /* default parameters: the T from a pair of segments, one of luma points */
    CHECK_EQ(det_ctx_init(&dc), 0);
    fl_vision_frame(dc.vis, dc.colors, &fr.view, &fc, field, &obs);
    for (k = 0; k < tr.n; k++) {
        if (tr.f[k].kind != TRUTH_T || tr.f[k].occluded || tr.f[k].range_mm > 6000)
            continue;
        for (i = 0; i < dc.vis->crossings.n; i++) {
            const fl_crossing_t *x = &dc.vis->crossings.c[i];
            if (x->kind == FL_LM_T && x->seg_a >= 0 && x->seg_b >= 0 &&
                hypot(x->u_q4 / 16.0 - tr.f[k].u, x->v_q4 / 16.0 - tr.f[k].v) <= 8.0 &&
                ((dc.vis->lines.segments[x->seg_a].flags |
                  dc.vis->lines.segments[x->seg_b].flags) & FL_SEG_LUMA))
                pair++;
        }
    }
    CHECK_EQ(pair, 1);
    det_ctx_free(&dc);
    /* no luma points: the border T */
    fl_vision_params_default(&vp);
    vp.lines.luma_contrast_pct = 0;
    CHECK_EQ(det_ctx_init_params(&dc, &vp), 0);
    fl_vision_frame(dc.vis, dc.colors, &fr.view, &fc, field, &obs);
    render_frame_free(&fr);
    CHECK_EQ(dc.vis->lines.luma_points, 0);
    CHECK(dc.vis->crossings.border_t >= 1);
    for (k = 0; k < tr.n; k++) {
        if (tr.f[k].kind != TRUTH_T || tr.f[k].occluded || tr.f[k].range_mm > 6000)
            continue;
        for (i = 0; i < dc.vis->crossings.n; i++) {
            const fl_crossing_t *x = &dc.vis->crossings.c[i];
            if (x->kind == FL_LM_T && x->seg_b < 0 &&
                hypot(x->u_q4 / 16.0 - tr.f[k].u, x->v_q4 / 16.0 - tr.f[k].v) <= 8.0) {
                found++;
                CHECK(x->n_arms == 3 && x->has_orientation);
                CHECK(x->range_mm > 3000 && fabs(x->range_mm - tr.f[k].range_mm) <
                                                0.05 * tr.f[k].range_mm);
            }
        }
    }
    CHECK_EQ(found, 1);
    /* the same segments without a camera: no border T */
    fl_crossings_find(&dc.vis->crossings, &dc.vis->lines, &dc.vis->scan, NULL, field);
    CHECK_EQ(dc.vis->crossings.border_t, 0);
    det_ctx_free(&dc);
}

/* Corners of a short connector (crossings.h, "Short connectors").  In
 * spl2013_t_far the side of the goal box 4 m away runs a few px from the
 * goal line down to the end of the box's front line, too short for a
 * segment: the L at that end (truth within 8 px) must come from the
 * connector, with 2 arms, an orientation and a range within 5 %, and the T
 * where the side meets the goal line is found (by a pair or the
 * connector).  In spl2020_penalty_area the goal area's side is 10 px long:
 * a 3-point segment whose pairs give the L (the connector before crossings
 * of one segment merged only within half the distance); the same L and T
 * checks, from a pair or the connector. */
static void connector_case(const char *name, const char *field_name, const char *camera,
                           double u_lo, double u_hi, int from_connector)
{
    static truth_t tr;
    render_frame_t fr;
    fl_camera_t fc;
    fl_obs_list_t obs;
    det_ctx_t dc;
    char err[256], path[256], raw[256];
    int32_t i, k, l_found = 0, t_found = 0;
    const fl_field_t *field = fl_field_find(field_name);
    snprintf(path, sizeof path, "fixtures/frames/%s.truth", name);
    snprintf(raw, sizeof raw, "fixtures/frames/%s.raw", name);
    if (truth_load(path, &tr, err, sizeof err) != 0 ||
        render_read_frame(raw, &fr, err, sizeof err) != 0) {
        t_info("skipped: fixture %s not found (run from the repository root)", name);
        return;
    }
    CHECK_EQ(fl_camera_init(&fc, fl_camera_model_find(camera), &tr.head), FL_OK);
    CHECK_EQ(det_ctx_init(&dc), 0);
    fl_vision_frame(dc.vis, dc.colors, &fr.view, &fc, field, &obs);
    render_frame_free(&fr);
    if (from_connector)
        CHECK(dc.vis->crossings.connectors >= 1);
    for (k = 0; k < tr.n; k++) {
        const truth_feature_t *f = &tr.f[k];
        if (f->occluded || f->range_mm > 6000 || f->u < u_lo || f->u > u_hi)
            continue;
        for (i = 0; i < dc.vis->crossings.n; i++) {
            const fl_crossing_t *x = &dc.vis->crossings.c[i];
            if (hypot(x->u_q4 / 16.0 - f->u, x->v_q4 / 16.0 - f->v) > 8.0)
                continue;
            /* a connector's confidence is at most 160 (a border T's) */
            if (f->kind == TRUTH_L && x->kind == FL_LM_L && x->seg_b >= 0 &&
                (!from_connector || x->confidence <= 160)) {
                l_found++;
                CHECK(x->n_arms == 2 && x->has_orientation);
                CHECK(fabs(x->range_mm - f->range_mm) < 0.05 * f->range_mm);
            }
            if (f->kind == TRUTH_T && (x->kind == FL_LM_T || x->kind == FL_LM_X))
                t_found++;
        }
    }
    t_info("%s: L %d, T %d found (connectors %d)", name, (int)l_found, (int)t_found,
           (int)dc.vis->crossings.connectors);
    CHECK_EQ(l_found, 1);
    CHECK_EQ(t_found, 1);
    det_ctx_free(&dc);
}

static void test_connector(void)
{
    connector_case("spl2013_t_far", "spl2013", "nao4-top-320", 140, 170, 1);
    connector_case("spl2020_penalty_area", "spl2020", "nao6-top-320", 150, 200, 0);
}

/* A circle found without its halfway line (the circle stage wants a full
 * radius of line through the centre; spl2013_penalty_far's halfway line is
 * broken by the centre mark): the crossings stage takes the longest
 * segment through the centre instead and reports the centre mark and the
 * circle's X on the halfway line. */
static void test_circle_axis(void)
{
    static truth_t tr;
    render_frame_t fr;
    fl_camera_t fc;
    fl_obs_list_t obs;
    det_ctx_t dc;
    char err[256];
    int32_t i, k, found = 0, want = 0;
    const fl_field_t *field = fl_field_find("spl2013");
    if (truth_load("fixtures/frames/spl2013_penalty_far.truth", &tr, err, sizeof err) != 0 ||
        render_read_frame("fixtures/frames/spl2013_penalty_far.raw", &fr, err, sizeof err) != 0) {
        t_info("skipped: fixture spl2013_penalty_far not found (run from the repository root)");
        return;
    }
    CHECK_EQ(fl_camera_init(&fc, fl_camera_model_find("nao4-top-320"), &tr.head), FL_OK);
    CHECK_EQ(det_ctx_init(&dc), 0);
    fl_vision_frame(dc.vis, dc.colors, &fr.view, &fc, field, &obs);
    render_frame_free(&fr);
    CHECK(dc.vis->circle.found);
    CHECK(!dc.vis->circle.has_orientation);
    for (k = 0; k < tr.n; k++) {
        const truth_feature_t *f = &tr.f[k];
        if (f->occluded || f->range_mm > 3000 ||
            (f->kind != TRUTH_X && f->kind != TRUTH_CENTRE_MARK))
            continue;
        want++;
        for (i = 0; i < dc.vis->crossings.n; i++) {
            const fl_crossing_t *x = &dc.vis->crossings.c[i];
            if (hypot(x->u_q4 / 16.0 - f->u, x->v_q4 / 16.0 - f->v) <= 8.0 &&
                (x->kind == FL_LM_X || x->kind == FL_LM_CENTRE_MARK)) {
                found++;
                CHECK(fabs(x->range_mm - f->range_mm) < 0.05 * f->range_mm);
                break;
            }
        }
    }
    t_info("circle without halfway line: %d of %d X's / centre marks under 3 m found",
           (int)found, (int)want);
    CHECK(want >= 2);
    CHECK_EQ(found, want);
    det_ctx_free(&dc);
}

static void test_goldens(void)
{
    const char *write = getenv("FIELDLOC_WRITE_GOLDEN");
    int rewrite = write && write[0] && write[0] != '0';
    FILE *idx = fopen("fixtures/frames/index.txt", "r");
    char line[1024];
    det_ctx_t dc;
    int frames = 0, same = 0, missing = 0, written = 0;
    uint32_t h = t_hash_init();
    if (!idx) {
        t_info("skipped: fixtures/frames/index.txt not found (run from the repository root)");
        return;
    }
    CHECK_EQ(det_ctx_init(&dc), 0);
    if (rewrite)
        mkdir("fixtures/golden", 0755);
    while (fgets(line, sizeof line, idx)) {
        char name[256], file[256], fmt[32], fieldn[64], camn[64], path[1024], err[256];
        static char got[16384], want[16384];
        static truth_t tr;
        render_frame_t fr;
        fl_camera_t c;
        fl_obs_list_t obs;
        FILE *g;
        size_t nw;
        if (line[0] == '#' ||
            sscanf(line, "%255s %255s %31s %63s %63s", name, file, fmt, fieldn, camn) != 5)
            continue;
        snprintf(path, sizeof path, "fixtures/frames/%s.truth", name);
        if (truth_load(path, &tr, err, sizeof err) != 0)
            continue;
        snprintf(path, sizeof path, "fixtures/frames/%s", file);
        if (render_read_frame(path, &fr, err, sizeof err) != 0)
            continue;
        if (fl_camera_init(&c, fl_camera_model_find(camn), &tr.head) != FL_OK) {
            render_frame_free(&fr);
            continue;
        }
        fl_vision_frame(dc.vis, dc.colors, &fr.view, &c, fl_field_find(fieldn), &obs);
        render_frame_free(&fr);
        CHECK_EQ(golden_text(dc.vis, got, sizeof got), 0);
        h = t_hash_bytes(h, got, strlen(got));
        frames++;
        snprintf(path, sizeof path, "fixtures/golden/%s.txt", name);
        if (rewrite) {
            g = fopen(path, "w");
            CHECK(g != NULL);
            if (g) {
                fprintf(g, "# fl_vision_frame outputs for fixtures/frames/%s (default parameters)\n%s",
                        file, got);
                fclose(g);
                written++;
            }
            continue;
        }
        g = fopen(path, "r");
        if (!g) {
            missing++;
            continue;
        }
        nw = fread(want, 1, sizeof want - 1, g);
        fclose(g);
        want[nw] = '\0';
        {
            char *body = strchr(want, '\n');  /* skip the comment line */
            body = body ? body + 1 : want;
            if (strcmp(body, got) == 0)
                same++;
            else
                t_fail_msg(__FILE__, __LINE__, "golden %s differs (rewrite with "
                           "FIELDLOC_WRITE_GOLDEN=1 build/run_tests -k features)", name);
        }
    }
    fclose(idx);
    det_ctx_free(&dc);
    CHECK(frames > 0);
    CHECK_EQ(missing, 0);
    if (rewrite)
        t_info("wrote %d goldens to fixtures/golden/", written);
    else
        t_info("goldens: %d of %d frames identical", same, frames);
    t_digest("features.goldens", h);
}

/* ---- evaluation floors ------------------------------------------------------------ */

static double ratio(int a, int b) { return b > 0 ? (double)a / b : 0.0; }

/* Floor: fail below the measured level (measured with the scanner and
 * color defaults of this commit, minus about 0.02: those stages are still
 * being tuned); print the gap to the target (targets below the
 * measured level are not asserted: a failing test would block everyone). */
static void floor_target(const char *what, double got, double floor, double target)
{
    CHECK_LE(floor, got);
    if (got < target)
        t_info("%s %.3f: below the target %.2f by %.3f (floor %.2f)", what, got, target,
               target - got, floor);
    else
        t_info("%s %.3f: meets the target %.2f", what, got, target);
}

static void test_eval_fixtures(void)
{
    det_ctx_t dc;
    evd_stats_t s;
    int n, k;
    double worst3 = 0;
    if (t_quick) {
        t_info("skipped in quick mode (covered by the goldens)");
        return;
    }
    CHECK_EQ(det_ctx_init(&dc), 0);
    evd_stats_clear(&s);
    n = evd_fixtures(&dc, "fixtures", 6000, 0, &s, NULL);
    det_ctx_free(&dc);
    if (n < 0) {
        t_info("skipped: fixtures/frames/index.txt not found");
        return;
    }
    CHECK(n >= 60);
    /* 0.966 / 0.760 before the far-corner, edge and mark changes of
     * crossings.c; 0.968 / 0.804 before the far goal-box corners (painted
     * bridges, near-flank ridges, cr_close) and far marks; 0.962 / 0.902
     * before the merging of one crossing through two pieces of a broken
     * line (cr_pieces); 0.967 / 0.902 now */
    floor_target("rendered crossings precision (<= 6 m)",
                 ratio(s.cross_tp, s.cross_tp + s.cross_fp), 0.965, 0.95);
    floor_target("rendered crossings recall (<= 6 m)",
                 ratio(s.cross_tp, s.cross_tp + s.cross_fn), 0.90, 0.90);
    for (k = 0; k < 3; k++)   /* bins 0-1, 1-2, 2-3 m */
        if (s.rng_n[k] > 0 && s.rng_max[k] > worst3)
            worst3 = s.rng_max[k];
    CHECK_LE(worst3, 0.05);
    t_info("rendered range error under 3 m: max %.2f %% (target 5 %%)", 100 * worst3);
    floor_target("rendered post feet precision", ratio(s.foot_tp, s.foot_tp + s.foot_fp), 0.96,
                 0.90);
    floor_target("rendered post feet recall", ratio(s.foot_tp, s.foot_tp + s.foot_fn), 0.82, 0.90);
}

static void test_eval_realdata(void)
{
    const char *dir = t_realdata_dir();
    det_ctx_t dc;
    evd_stats_t s;
    int n;
    if (!dir) {
        t_info("skipped: ../shared/realdata not found (set FIELDLOC_REALDATA to its path)");
        return;
    }
    if (t_quick) {
        t_info("skipped in quick mode");
        return;
    }
    CHECK_EQ(det_ctx_init(&dc), 0);
    evd_stats_clear(&s);
    n = evd_uva(&dc, dir, 0, &s);
    det_ctx_free(&dc);
    CHECK(n >= 20);
    /* precision 0.919 at recall 0.553 before the luma line points; 0.880
     * at recall 0.641 with them (white s_hi 48, color.h); 0.919 at 0.767
     * after the far ground tolerance, edge corners, arm widths, merging,
     * far and edge marks and hidden gaps of crossings.c; 0.921 at 0.796
     * after the far goal-box corners */
    floor_target("UvA crossings precision", ratio(s.cross_tp, s.cross_tp + s.cross_fp), 0.92,
                 0.85);
    floor_target("UvA crossings recall", ratio(s.cross_tp, s.cross_tp + s.cross_fn), 0.79, 0.75);
    floor_target("UvA post feet precision", ratio(s.foot_tp, s.foot_tp + s.foot_fp), 0.96, 0.90);
    floor_target("UvA post feet recall", ratio(s.foot_tp, s.foot_tp + s.foot_fn), 0.90, 0.90);
    t_info("UvA type accuracy %.3f over %d matched crossings", ratio(s.type_ok, s.cross_tp),
           s.cross_tp);
}

void suite_features(void)
{
    t_run("features.params", test_params);
    t_run("features.types", test_types);
    t_run("features.ground_check", test_ground_check);
    t_run("features.circle", test_circle);
    t_run("features.goal_painted", test_goal_painted);
    t_run("features.vision_bad_input", test_vision_bad_input);
    t_run("features.vision_camera_mismatch", test_vision_camera_mismatch);
    t_run("features.vision_noise", test_vision_noise);
    t_run("features.border_t", test_border_t);
    t_run("features.connector", test_connector);
    t_run("features.circle_axis", test_circle_axis);
    t_run("features.goldens", test_goldens);
    t_run("features.eval_fixtures", test_eval_fixtures);
    t_run("features.eval_realdata", test_eval_realdata);
}
