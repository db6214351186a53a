/*
 * host_tests/test_robots.c - standing objects are not lines (lines.h,
 * "Standing objects"): robots and the ball make no line points and no
 * crossings.
 *
 *   - rendered scenes with robots standing on and near lines (the fixture
 *     spl2020_robots_ball and scenes made here): the render's class mask
 *     is the truth; no crossing on a robot or ball pixel, at most 4 % of
 *     the line points there (the scan lines pass beside a ball's black
 *     patches; a run of a line ending at a robot's foot has its midpoint on
 *     the paint, the mask's silhouette is supersampled), and the lines' own
 *     crossings still found;
 *   - real frames with robots (scarrix, ../shared/realdata; skipped when
 *     absent) with colour boxes set for their carpets and the robots' boxes
 *     as seen by eye: no crossing inside a box;
 *   - without a camera, a green board above a wall stays out of the field
 *     (scan.h, the board pass); the far carpet above a robot and the
 *     strip of carpet beyond a far boundary line stay in.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "eval/detect.h"
#include "io/ppm.h"
#include "io/realdata.h"
#include "world/render.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *name;
    const char *field, *camera;
    int32_t x, y, heading_mdeg, pitch_urad;
    int n;                       /* robots */
    render_robot_t r[4];
    int ball;
    int32_t bx, by;
    int min_crossings;           /* crossings of lines found (off objects) */
} rob_scene_t;

static int on_object(const render_frame_t *fr, int u, int v)
{
    int c;
    if (u < 0 || v < 0 || u >= fr->width || v >= fr->height)
        return 0;
    c = fr->mask[v * fr->width + u];
    return c == RENDER_CLASS_OBJECT || c == RENDER_CLASS_BALL;
}

/* Render a scene, run the vision path; counts of points and crossings on
 * object pixels. */
static int run_scene(const rob_scene_t *t, det_ctx_t *dc)
{
    render_scene_t sc;
    render_frame_t fr;
    fl_camera_t cam;
    fl_obs_list_t obs;
    int i, pts_on = 0, x_on = 0, x_off = 0, obj_px = 0;
    render_scene_default(&sc, fl_field_find(t->field), fl_camera_model_find(t->camera));
    sc.robot_x_mm = t->x;
    sc.robot_y_mm = t->y;
    sc.robot_heading = fl_angle_from_mdeg(t->heading_mdeg);
    sc.head.head_pitch = fl_angle_from_urad(t->pitch_urad);
    sc.n_robots = t->n;
    for (i = 0; i < t->n; i++)
        sc.robots[i] = t->r[i];
    sc.ball = t->ball;
    sc.ball_x_mm = t->bx;
    sc.ball_y_mm = t->by;
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK_EQ(render_scene_camera(&sc, &cam), FL_OK);
    fl_vision_frame(dc->vis, dc->colors, &fr.view, &cam, sc.field, &obs);
    for (i = 0; i < fr.width * fr.height; i++)
        obj_px += fr.mask[i] == RENDER_CLASS_OBJECT;
    for (i = 0; i < dc->vis->lines.n_points; i++) {
        const fl_line_point_t *p = &dc->vis->lines.points[i];
        pts_on += on_object(&fr, (p->u_q1 + 1) / 2, (p->v_q1 + 1) / 2);
    }
    for (i = 0; i < dc->vis->crossings.n; i++) {
        const fl_crossing_t *x = &dc->vis->crossings.c[i];
        if (on_object(&fr, (x->u_q4 + 8) >> 4, (x->v_q4 + 8) >> 4)) {
            x_on++;
            t_info("%s: crossing kind %d at (%.1f, %.1f) on an object", t->name, (int)x->kind,
                   x->u_q4 / 16.0, x->v_q4 / 16.0);
        }
        else
            x_off++;
    }
    t_info("%s: %d robot px, points %d (%d on objects, %d rejected there), crossings %d on "
           "objects, %d off (%d dropped on objects)",
           t->name, obj_px, (int)dc->vis->lines.n_points, pts_on,
           (int)dc->vis->lines.robot_rejected, x_on, x_off,
           (int)dc->vis->crossings.robot_rejected);
    CHECK(obj_px > 500);   /* the robots are in view */
    CHECK_EQ(x_on, 0);
    CHECK_LE(pts_on * 100, 4 * dc->vis->lines.n_points);
    CHECK(x_off >= t->min_crossings);
    render_frame_free(&fr);
    return (int)dc->vis->lines.robot_rejected;
}

static void test_rendered(void)
{
    static const rob_scene_t scenes[] = {
        /* the fixture: circle, two robots, the ball */
        {"spl2020_robots_ball", "spl2020", "nao6-top-320", -1800, -400, 10000, 250000, 2,
         {{-600, 300, -32768, RENDER_JERSEY_BLUE}, {-300, -700, 8000, RENDER_JERSEY_RED}},
         1, -1000, -250, 2},
        /* robots standing on the halfway line and on the circle */
        {"robots_on_halfway", "spl2020", "nao6-top-320", -1800, -400, 0, 250000, 3,
         {{0, -300, -32768, RENDER_JERSEY_RED}, {0, 700, 16384, RENDER_JERSEY_BLUE},
          {-750, 100, 0, RENDER_JERSEY_BLUE}},
         0, 0, 0, 1},
        /* robots on the penalty area's front and side lines */
        {"robots_on_penalty_area", "spl2020", "nao6-top-320", 1500, 1200, 0, 250000, 2,
         {{2850, 600, -32768, RENDER_JERSEY_RED}, {3600, 2000, 16384, RENDER_JERSEY_BLUE}},
         0, 0, 0, 1},
        /* 2013 field, close robot on a goal-box line */
        {"robots_on_box_2013", "spl2013", "nao4-top-320", 2300, -300, 0, 300000, 2,
         {{3900, -600, -32768, RENDER_JERSEY_BLUE}, {4200, 1100, 0, RENDER_JERSEY_RED}},
         0, 0, 0, 1},
    };
    det_ctx_t dc;
    size_t k;
    int rejected = 0;
    CHECK_EQ(det_ctx_init(&dc), 0);
    for (k = 0; k < sizeof scenes / sizeof scenes[0]; k++)
        rejected += run_scene(&scenes[k], &dc);
    /* most of a robot standing in front of the border is above it (no
     * class map there); the points of what stands below it were rejected */
    CHECK(rejected > 0);
    det_ctx_free(&dc);
}

/* ---- real frames ---------------------------------------------------------- */

typedef struct {
    int u0, v0, u1, v1;
} rob_box_t;

typedef struct {
    const char *file;
    fl_hsv_box_t green, white, yellow;
    int n;
    rob_box_t box[3];
} rob_real_t;

static void test_realdata(void)
{
    /* carpets: danu_fallen hue ~42 (yellowish green: yellow moved off it),
     * danu_moving hue ~85, oisin_ball the default, oisin_demo dark (hue
     * 60-70, S ~60, V ~80); robots' boxes by eye, pixels */
    static const rob_real_t frames[] = {
        {"scarrix_Detect_Foot_danu_fallen_robot_9500_upper.ppm",
         {33, 56, 50, 255, 25, 255}, {0, 179, 0, 40, 60, 255}, {10, 22, 120, 255, 50, 255},
         2, {{380, 10, 500, 305}, {495, 10, 635, 275}}},
        {"scarrix_Detect_Foot_danu_moving_ball_across_vision_3141_upper.ppm",
         {68, 100, 40, 255, 25, 255}, {0, 179, 0, 39, 60, 255}, {15, 40, 90, 255, 50, 255},
         2, {{55, 40, 215, 300}, {435, 15, 585, 405}}},
        {"scarrix_Detect_Foot_oisin_ball_robot0476.ppm",
         {46, 78, 49, 255, 25, 255}, {0, 179, 0, 48, 60, 255}, {15, 40, 90, 255, 50, 255},
         2, {{505, 0, 639, 300}, {105, 35, 175, 130}}},
        {"scarrix_Detect_Foot_oisin_demo_ball0485.ppm",
         {48, 82, 30, 255, 20, 255}, {0, 179, 0, 29, 60, 255}, {15, 40, 90, 255, 50, 255},
         3, {{465, 65, 639, 335}, {262, 45, 326, 137}, {195, 333, 270, 405}}},
    };
    const char *dir = rd_dir();
    det_ctx_t dc;
    size_t k;
    int total_rejected = 0;
    if (!dir) {
        t_info("robots.realdata %s", rd_skip_message());
        return;
    }
    CHECK_EQ(det_ctx_init(&dc), 0);
    for (k = 0; k < sizeof frames / sizeof frames[0]; k++) {
        const rob_real_t *f = &frames[k];
        char path[1024], err[256];
        host_image_t im;
        fl_color_params_t cp;
        fl_camera_t cam;
        fl_obs_list_t obs;
        fl_image_t view;
        int i, b, on = 0;
        if (rd_path(path, sizeof path, dir, f->file) != 0 ||
            ppm_read(path, &im, err, sizeof err) != 0) {
            t_info("robots.realdata: %s missing", f->file);
            continue;
        }
        fl_color_params_default(&cp);
        cp.green = f->green;
        cp.white = f->white;
        cp.yellow = f->yellow;
        CHECK_EQ(det_ctx_set_colors(&dc, &cp), 0);
        /* upper camera looking down about 0.32 rad (the horizon near the
         * robots' heads) */
        CHECK_EQ(det_camera(&cam, fl_camera_model_find("nao6-top-640"), 0.32, 0.0), FL_OK);
        CHECK_EQ(fl_image_init_packed(&view, FL_FMT_RGB888, im.rgb, im.width, im.height,
                                      3 * im.width), FL_OK);
        fl_vision_frame(dc.vis, dc.colors, &view, &cam, fl_field_find("spl2020"), &obs);
        for (i = 0; i < dc.vis->crossings.n; i++) {
            double u = dc.vis->crossings.c[i].u_q4 / 16.0, v = dc.vis->crossings.c[i].v_q4 / 16.0;
            for (b = 0; b < f->n; b++)
                if (u >= f->box[b].u0 && u <= f->box[b].u1 && v >= f->box[b].v0 &&
                    v <= f->box[b].v1)
                    on++;
        }
        total_rejected += dc.vis->lines.robot_rejected;
        t_info("%s: points %d (robot-rejected %d), crossings %d (%d on robots, robot-rejected %d)",
               f->file, (int)dc.vis->lines.n_points, (int)dc.vis->lines.robot_rejected,
               (int)dc.vis->crossings.n, on, (int)dc.vis->crossings.robot_rejected);
        CHECK_EQ(on, 0);
        host_image_free(&im);
    }
    CHECK(total_rejected > 0);
    det_ctx_free(&dc);
}

/* ---- a green board above the field ----------------------------------------- */

static void paint(uint8_t *rgb, int w, int v0, int v1, uint8_t r, uint8_t g, uint8_t b)
{
    int u, v;
    for (v = v0; v < v1; v++)
        for (u = 0; u < w; u++) {
            uint8_t *p = rgb + 3 * (v * w + u);
            /* a little texture so that no run is perfectly flat */
            int d = ((u * 7 + v * 13) % 5) - 2;
            p[0] = (uint8_t)(r + d);
            p[1] = (uint8_t)(g + d);
            p[2] = (uint8_t)(b + d);
        }
}

/* Columns (of cols) whose border lies within tol px of v. */
static int border_near(const fl_scan_t *s, int v, int tol)
{
    int i, n = 0;
    for (i = 0; i < s->cols; i++)
        n += abs(s->border_v[i] - v) <= tol;
    return n;
}

/* No camera: the border search starts at row 0.  A board in carpet green
 * (the hardest case: its colour is the carpet's) above a grey wall with a
 * dark skirting, the carpet below with a line across: the border stays on
 * the carpet.  A far field whose boundary line has a thin strip of carpet
 * beyond it keeps its border on the strip (a white gap is a line). */
static void test_board(void)
{
    enum { W = 320, H = 240 };
    static uint8_t rgb[W * H * 3];
    static fl_color_table_t colors;
    static fl_scan_t scan;
    fl_color_params_t cp;
    fl_scan_params_t sp;
    fl_image_t img;
    int n;
    fl_color_params_default(&cp);
    CHECK_EQ(fl_color_init(&colors, &cp), FL_OK);
    fl_scan_params_default(&sp);
    CHECK_EQ(fl_scan_init(&scan, &sp), FL_OK);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, rgb, W, H, 3 * W), FL_OK);
    paint(rgb, W, 0, 60, 170, 170, 165);       /* wall */
    paint(rgb, W, 60, 110, 60, 140, 60);       /* the board, carpet green */
    paint(rgb, W, 110, 130, 175, 172, 168);    /* wall */
    paint(rgb, W, 130, 140, 50, 45, 40);       /* dark skirting */
    paint(rgb, W, 140, H, 60, 140, 60);        /* carpet */
    paint(rgb, W, 190, 196, 235, 235, 235);    /* a line */
    CHECK(fl_scan_frame(&scan, &colors, &img, NULL) > 0);
    n = border_near(&scan, 140, 3);
    t_info("board: border within 3 px of the carpet in %d of %d columns", n, (int)scan.cols);
    CHECK(n * 100 >= 95 * scan.cols);
    CHECK_EQ(fl_scan_class_at(&scan, 10, 80 / sp.row_step), FL_CLASS_OTHER);
    /* carpet from row 60 with a robot (an eighth of the width, grey and
     * dark) standing on it: far carpet above it, near carpet below it; the
     * border stays on the far carpet (a robot is no wall) */
    paint(rgb, W, 0, 60, 170, 170, 165);
    paint(rgb, W, 60, H, 60, 140, 60);
    {
        int v, u;
        for (v = 90; v < 170; v++)
            for (u = 100; u < 100 + W / 8; u++) {
                uint8_t c = (uint8_t)(v % 20 < 14 ? 220 : 50);
                rgb[3 * (v * W + u)] = rgb[3 * (v * W + u) + 1] = rgb[3 * (v * W + u) + 2] = c;
            }
    }
    CHECK(fl_scan_frame(&scan, &colors, &img, NULL) > 0);
    CHECK_EQ(scan.border_v[(100 + W / 16) / sp.col_step], 60);
    CHECK_EQ(border_near(&scan, 60, 2), scan.cols);
    /* far field: wall, a 4 px strip of carpet, the boundary line (2 px),
     * the field */
    paint(rgb, W, 0, 100, 170, 170, 165);
    paint(rgb, W, 100, 104, 60, 140, 60);
    paint(rgb, W, 104, 106, 235, 235, 235);
    paint(rgb, W, 106, H, 60, 140, 60);
    CHECK(fl_scan_frame(&scan, &colors, &img, NULL) > 0);
    n = border_near(&scan, 100, 2);
    t_info("far field: border on the strip beyond the boundary line in %d of %d columns", n,
           (int)scan.cols);
    CHECK(n * 100 >= 95 * scan.cols);
}

void suite_robots(void)
{
    t_run("robots.board_border", test_board);
    t_run("robots.rendered", test_rendered);
    t_run("robots.realdata", test_realdata);
}
