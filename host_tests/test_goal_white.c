/*
 * host_tests/test_goal_white.c - white goal posts (goal.h,
 * fl_goal_find_white) through fl_vision_frame on the rendered spl2020
 * fixtures:
 *   - the goals: every post foot of the truth found within 4 px, the left
 *     post LEFT and the right one RIGHT, observations of kind post and
 *     colour white;
 *   - no post from robots (alone in front of the border, or around the
 *     circle with the ball: only the far goal's posts there) nor from a
 *     near line seen end-on;
 *   - a drawn single post: the crossbar to one side gives its side; a
 *     drawn upright with no crossbar running to the image's top is none;
 *   - bad input: NULL camera or scan, no posts.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/render.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    fl_color_table_t colors;
    fl_vision_t vis;
    fl_obs_list_t obs;
    truth_t tr;
    fl_camera_t cam;
} gw_state_t;

static gw_state_t *G;

/* Run the vision path on fixture `name` (file extension ext); 0 or -1. */
static int gw_run(const char *name, const char *ext)
{
    char path[256], err[256];
    fl_color_params_t cp;
    fl_vision_params_t vp;
    render_frame_t fr;
    const fl_camera_model_t *m;
    if (!G)
        G = calloc(1, sizeof *G);
    if (!G)
        return -1;
    fl_color_params_default(&cp);
    fl_vision_params_default(&vp);
    if (fl_color_init(&G->colors, &cp) != FL_OK || fl_vision_init(&G->vis, &vp) != FL_OK)
        return -1;
    snprintf(path, sizeof path, "fixtures/frames/%s.truth", name);
    if (truth_load(path, &G->tr, err, sizeof err) != 0)
        return -1;
    snprintf(path, sizeof path, "fixtures/frames/%s.%s", name, ext);
    if (render_read_frame(path, &fr, err, sizeof err) != 0)
        return -1;
    m = fl_camera_model_find("nao6-top-320");
    if (!m || fl_camera_init(&G->cam, m, &G->tr.head) != FL_OK) {
        render_frame_free(&fr);
        return -1;
    }
    fl_vision_frame(&G->vis, &G->colors, &fr.view, &G->cam, fl_field_find("spl2020"), &G->obs);
    render_frame_free(&fr);
    return 0;
}

static void test_goals(void)
{
    static const char *names[] = {"spl2020_goal_both", "spl2020_goal_robots", "spl2020_goal_far"};
    static const char *exts[] = {"ppm", "ppm", "raw"};
    int s, i, k;
    for (s = 0; s < 3; s++) {
        int feet = 0, white_obs = 0;
        CHECK(gw_run(names[s], exts[s]) == 0);
        if (!G)
            return;
        CHECK(G->vis.posts.n == 2);
        for (i = 0; i < G->tr.n; i++) {
            const truth_feature_t *f = &G->tr.f[i];
            if (f->kind != TRUTH_POST_FOOT)
                continue;
            feet++;
            for (k = 0; k < G->vis.posts.n; k++) {
                const fl_post_t *p = &G->vis.posts.post[k];
                if (fabs(p->foot_u_q4 / 16.0 - f->u) <= 4.0 && fabs(p->foot_v_q4 / 16.0 - f->v) <= 4.0)
                    break;
            }
            CHECK(k < G->vis.posts.n);
            if (k < G->vis.posts.n)
                /* truth side 1 = left (y > 0), 2 = right, as fl_side_t */
                CHECK((int)G->vis.posts.post[k].side == (int)f->side);
        }
        CHECK(feet == 2);
        for (i = 0; i < G->obs.n; i++)
            if (G->obs.obs[i].kind == FL_LM_POST) {
                CHECK(G->obs.obs[i].color == FL_COLOR_WHITE);
                white_obs++;
            }
        CHECK(white_obs == 2);
    }
}

/* Every post found lies within 4 px of a true foot. */
static int gw_all_true(void)
{
    int i, k;
    for (k = 0; k < G->vis.posts.n; k++) {
        const fl_post_t *p = &G->vis.posts.post[k];
        for (i = 0; i < G->tr.n; i++) {
            const truth_feature_t *f = &G->tr.f[i];
            if (f->kind == TRUTH_POST_FOOT && fabs(p->foot_u_q4 / 16.0 - f->u) <= 4.0 &&
                fabs(p->foot_v_q4 / 16.0 - f->v) <= 4.0)
                break;
        }
        if (i == G->tr.n)
            return 0;
    }
    return 1;
}

static void test_no_false_posts(void)
{
    /* a robot alone in front of the border and a near line end-on: no
     * post in view; robots around the circle with the ball: the far
     * goal's posts (6.3 m) at most */
    static const char *names[] = {"spl2020_robot_border", "spl2020_line_end_on",
                                  "spl2020_robots_ball"};
    static const char *exts[] = {"ppm", "ppm", "raw"};
    int s;
    for (s = 0; s < 3; s++) {
        CHECK(gw_run(names[s], exts[s]) == 0);
        if (!G)
            return;
        if (s < 2)
            CHECK(G->vis.posts.n == 0);
        CHECK(gw_all_true());
    }
}

/* A drawn post: a grey room above row 100, carpet below, one white post
 * 100 mm wide and 800 mm tall at 2.5 m ahead (sizes through the camera)
 * with a crossbar to one side (dir +1 right, -1 left) and dark above it;
 * dir 0: no crossbar, the upright runs to the image's top (a door frame).
 * Returns the side found for the single post, or -1. */
static int gw_drawn(int dir)
{
    static uint8_t rgb[320 * 240 * 3];
    const fl_camera_model_t *m = fl_camera_model_find("nao6-top-320");
    fl_camera_pose_t pose;
    fl_point_t g = {2500, 0};
    fl_image_t img;
    int32_t fu, fv, u, v, w, h, k;
    if (!m || !G)
        return -1;
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    pose.head_pitch = fl_angle_from_urad(100000);
    if (fl_camera_init(&G->cam, m, &pose) != FL_OK ||
        !fl_camera_ground_to_pixel(&G->cam, g, &fu, &fv))
        return -1;
    fu /= 16;
    fv /= 16;
    /* about f d / r: a width of 100 mm and a height of 800 mm at 2.5 m */
    w = G->cam.model.focal_q4 * 100 / (16 * 2500);
    h = G->cam.model.focal_q4 * 800 / (16 * 2500);
    for (v = 0; v < 240; v++)
        for (u = 0; u < 320; u++) {
            uint8_t *p = rgb + 3 * (v * 320 + u);
            bool post = u >= fu - w / 2 && u < fu - w / 2 + w && v <= fv && (v > fv - h || dir == 0);
            bool bar = dir != 0 && v <= fv - h + w && v > fv - h &&
                       (dir > 0 ? u >= fu && u < fu + 6 * w : u <= fu && u > fu - 6 * w);
            if (post || bar)
                p[0] = p[1] = p[2] = 235;
            else if (v > fv - 12)
                p[0] = 60, p[1] = 140, p[2] = 60;     /* carpet: 12 px strip behind */
            else
                p[0] = p[1] = p[2] = 70;              /* dark room */
        }
    fl_image_init_packed(&img, FL_FMT_RGB888, rgb, 320, 240, 320 * 3);
    fl_vision_frame(&G->vis, &G->colors, &img, &G->cam, fl_field_find("spl2020"), &G->obs);
    k = G->vis.posts.n;
    if (k != 1)
        return -1;
    return (int)G->vis.posts.post[0].side;
}

/* The crossbar decides the side of a single post: bar to the right, the
 * left post (facing the goal); to the left, the right post. */
static void test_crossbar_side(void)
{
    CHECK(gw_run("spl2020_goal_both", "ppm") == 0);   /* tables and vision */
    if (!G)
        return;
    CHECK_EQ(gw_drawn(1), (int)FL_SIDE_LEFT);
    CHECK(G->vis.posts.n == 1 && G->vis.posts.post[0].top_visible);
    CHECK_EQ(gw_drawn(-1), (int)FL_SIDE_RIGHT);
}

/* A white upright as wide as a post at its foot's range but with no
 * crossbar, running on far above a post's height (a door or window frame
 * standing on the carpet's edge) is no post. */
static void test_door_frame(void)
{
    CHECK(gw_run("spl2020_goal_both", "ppm") == 0);
    if (!G)
        return;
    CHECK_EQ(gw_drawn(0), -1);
    CHECK_EQ(G->vis.posts.n, 0);
    CHECK(G->vis.posts.candidates > 0);     /* it was examined */
}

static void test_bad_input(void)
{
    fl_posts_t out;
    CHECK(gw_run("spl2020_goal_both", "ppm") == 0);
    if (!G)
        return;
    CHECK(fl_goal_find_white(&out, &G->vis.scan, NULL, &G->cam, NULL) == 0);
    CHECK(fl_goal_find_white(&out, NULL, NULL, &G->cam, NULL) == 0);
    CHECK(fl_goal_find_white(NULL, &G->vis.scan, NULL, NULL, NULL) == 0);
}

void suite_goal_white(void)
{
    t_run("goal_white.goals", test_goals);
    t_run("goal_white.no_false_posts", test_no_false_posts);
    t_run("goal_white.crossbar_side", test_crossbar_side);
    t_run("goal_white.door_frame", test_door_frame);
    t_run("goal_white.bad_input", test_bad_input);
    free(G);
    G = NULL;
}
