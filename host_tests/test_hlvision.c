/*
 * host_tests/test_hlvision.c - seed 002's vision path (hlvision.h): the
 * colour boxes, posts and poles on images built here (planar YCbCr, pixel
 * values chosen inside / outside the default boxes), the mask, bad input.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/render.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define HW 640
#define HH 480

/* Colours inside the default boxes (Y, Cb, Cr). */
static const uint8_t c_green[3] = {117, 110, 103};
static const uint8_t c_yellow[3] = {190, 50, 150};
static const uint8_t c_blue[3] = {150, 170, 75};
static const uint8_t c_white[3] = {235, 128, 128};
static const uint8_t c_grey[3] = {90, 128, 128};   /* none of the classes */

typedef struct {
    uint8_t p[3][HW * HH];
    fl_image_t img;
} t_frame_t;

static t_frame_t *frame_new(const uint8_t bg[3])
{
    t_frame_t *f = malloc(sizeof *f);
    int k;
    for (k = 0; k < 3; k++)
        memset(f->p[k], bg[k], sizeof f->p[k]);
    fl_image_init_planar(&f->img, f->p[0], HW, f->p[1], HW, f->p[2], HW, HW, HH);
    return f;
}

/* Rows v0..v1 (inclusive), columns u0..u1 (clipped to the image). */
static void paint(t_frame_t *f, int u0, int u1, int v0, int v1, const uint8_t c[3])
{
    int u, v, k;
    u0 = u0 < 0 ? 0 : u0;
    u1 = u1 > HW - 1 ? HW - 1 : u1;
    for (v = v0; v <= v1; v++)
        for (u = u0; u <= u1; u++)
            for (k = 0; k < 3; k++)
                f->p[k][v * HW + u] = c[k];
}

/* A small humanoid's head camera: 60 deg field of view, 450 mm up, looking
 * 20 deg down (horizon near row 80). */
static void t_camera(fl_camera_t *cam)
{
    static const fl_camera_model_t m = {"hum-640", HW, HH, 8868, 5112, 3832, 0, 0, 0, 450, 0};
    fl_camera_extrinsics_t e;
    memset(&e, 0, sizeof e);
    e.z_mm = 450;
    e.pitch = fl_angle_from_mdeg(20000);
    CHECK_EQ(fl_camera_init_extrinsics(cam, &m, &e), FL_OK);
}

static fl_hlv_t hv;

static void t_init(void)
{
    fl_hlv_params_t p;
    fl_hlv_params_default(&p, NULL);
    CHECK_EQ(fl_hlv_init(&hv, &p), FL_OK);
}

static void test_boxes(void)
{
    fl_hlv_params_t p;
    t_init();
    CHECK_EQ(fl_hlv_class(&hv, c_green[0], c_green[1], c_green[2]), FL_HLV_GREEN);
    CHECK_EQ(fl_hlv_class(&hv, c_yellow[0], c_yellow[1], c_yellow[2]), FL_HLV_YELLOW);
    CHECK_EQ(fl_hlv_class(&hv, c_blue[0], c_blue[1], c_blue[2]), FL_HLV_BLUE);
    CHECK_EQ(fl_hlv_class(&hv, c_white[0], c_white[1], c_white[2]), FL_HLV_WHITE);
    CHECK_EQ(fl_hlv_class(&hv, c_grey[0], c_grey[1], c_grey[2]), 0);
    /* the tables are exact for boxes: every edge in, one past it out */
    fl_hlv_params_default(&p, NULL);
    memset(p.box, 0, sizeof p.box);
    p.box[FL_HLV_BOX_WHITE] = (fl_hlv_box_t){10, 20, 30, 40, 50, 60};
    p.box[FL_HLV_BOX_YELLOW] = (fl_hlv_box_t){1, 0, 0, 255, 0, 255};   /* empty */
    p.box[FL_HLV_BOX_BLUE] = (fl_hlv_box_t){1, 0, 0, 255, 0, 255};
    p.box[FL_HLV_BOX_GREEN] = (fl_hlv_box_t){1, 0, 0, 255, 0, 255};
    CHECK_EQ(fl_hlv_init(&hv, &p), FL_OK);
    {
        int y, cb, cr, bad = 0;
        for (y = 0; y < 256; y += 1)
            for (cb = 25; cb <= 45; cb++)
                for (cr = 45; cr <= 65; cr++) {
                    const int want = y >= 10 && y <= 20 && cb >= 30 && cb <= 40 && cr >= 50 &&
                                     cr <= 60;
                    if (fl_hlv_class(&hv, (uint8_t)y, (uint8_t)cb, (uint8_t)cr) !=
                        (want ? FL_HLV_WHITE : 0))
                        bad++;
                }
        CHECK_EQ(bad, 0);
    }
    /* params: ranges refused */
    fl_hlv_params_default(&p, NULL);
    p.mask_step_u = 17;
    CHECK_EQ(fl_hlv_init(&hv, &p), FL_ERR_RANGE);
    fl_hlv_params_default(&p, NULL);
    p.max_range_mm = FL_OBS_MAX_RANGE_MM + 1;
    CHECK_EQ(fl_hlv_params_check(&p), FL_ERR_RANGE);
    CHECK_EQ(fl_hlv_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_hlv_init(&hv, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_hlv_init_cfg(&hv, &p, FL_CONFIG_FINGERPRINT ^ 1u), FL_ERR_CONFIG);
}

/* Range and bearing of the centre of a round object of diameter diam
 * whose foot is at the lower edge of image row v, column u. */
static void t_foot_polar(const fl_camera_t *cam, int u, int v, int32_t diam, int32_t *r,
                         fl_angle_t *b)
{
    fl_point_t g;
    int32_t uq = u * 16, vq = v * 16 + 8;
    CHECK(fl_camera_foot_to_centre(cam, &uq, &vq, diam, &g));
    fl_polar_from_point(g, r, b);
}

/* The ground under image row v (foot at its lower edge), column u. */
static int32_t t_range(const fl_camera_t *cam, int u, int v, int32_t diam)
{
    int32_t r;
    fl_angle_t b;
    t_foot_polar(cam, u, v, diam, &r, &b);
    return r;
}

/* Columns of an object of diameter diam centred at column uc with its
 * foot at row v: the width the camera gives it at that range. */
static void t_cols(const fl_camera_t *cam, int uc, int v, int32_t diam, int *u0, int *u1)
{
    const int32_t r = t_range(cam, uc, v, diam);
    const int w = (int)(cam->model.focal_q4 / 16 * diam / (r > 1 ? r : 1));
    *u0 = uc - w / 2;
    *u1 = *u0 + w - 1;
}

/* A post (single colour) or a pole (bands c0, c1, c0 from the foot up). */
static void paint_object(t_frame_t *f, const fl_camera_t *cam, int uc, int foot, int top, int32_t diam,
                         const uint8_t *c0, const uint8_t *c1)
{
    int u0, u1;
    t_cols(cam, uc, foot, diam, &u0, &u1);
    if (!c1) {
        paint(f, u0, u1, top, foot, c0);
    } else {
        const int band = (foot - top + 1) / 3;
        paint(f, u0, u1, foot - band + 1, foot, c0);
        paint(f, u0, u1, foot - 2 * band + 1, foot - band, c1);
        paint(f, u0, u1, top, foot - 2 * band, c0);
    }
}

static const fl_obs_t *find_obs(const fl_obs_list_t *o, fl_landmark_kind_t kind, fl_color_t c)
{
    int i;
    for (i = 0; i < o->n; i++)
        if (o->obs[i].kind == kind && o->obs[i].color == c)
            return &o->obs[i];
    return NULL;
}

/* The observation of kind and colour c, which must be there, at the range
 * of the object of diameter 100 mm painted with its foot at (u, v) within
 * 2 % + 10 mm; NULL when it is missing. */
static const fl_obs_t *check_found(const fl_obs_list_t *obs, const fl_camera_t *cam,
                                   fl_landmark_kind_t kind, fl_color_t c, int u, int v)
{
    const fl_obs_t *o = find_obs(obs, kind, c);
    int32_t r;
    CHECK(o != NULL);
    if (o) {
        r = t_range(cam, u, v, 100);
        CHECK_LE(abs(o->range_mm - r), r / 50 + 10);
    }
    return o;
}

/* Green from row 200 down; a yellow post, a YBY pole, a BYB pole, a
 * single-colour sky-blue column and a two-colour column (YB, no third
 * band) standing on it. */
static void test_posts_poles(void)
{
    t_frame_t *f = frame_new(c_grey);
    fl_camera_t cam;
    fl_obs_list_t obs;
    const fl_obs_t *o;
    int32_t n;
    t_init();
    t_camera(&cam);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint_object(f, &cam, 310, 350, 150, 100, c_yellow, NULL);        /* yellow post */
    paint_object(f, &cam, 108, 360, 180, 100, c_yellow, c_blue);      /* YBY pole */
    paint_object(f, &cam, 508, 290, 170, 100, c_blue, c_yellow);      /* BYB pole */
    n = fl_hlv_frame(&hv, &f->img, &cam, &obs);
    CHECK_EQ(hv.status, FL_OK);
    CHECK_EQ(n, 3);
    CHECK_EQ(hv.n_objects, 3);
    o = check_found(&obs, &cam, FL_LM_POST, FL_COLOR_YELLOW, 310, 350);
    if (o) {
        CHECK_EQ(o->side, FL_SIDE_UNKNOWN);
        CHECK_LE(abs(o->u_q4 / 16 - 310), 4);
    }
    o = check_found(&obs, &cam, FL_LM_BEACON, FL_COLOR_YELLOW, 108, 360);
    if (o) {
        CHECK_EQ(o->color2, FL_COLOR_YELLOW);
        CHECK(o->bearing > 0);   /* left of the image centre */
    }
    o = check_found(&obs, &cam, FL_LM_BEACON, FL_COLOR_SKYBLUE, 508, 290);
    if (o) {
        CHECK_EQ(o->color2, FL_COLOR_SKYBLUE);
        CHECK(o->bearing < 0);
    }
    /* a single-colour column is never a pole, a two-band column nothing */
    paint(f, 0, HW - 1, 0, 199, c_grey);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint_object(f, &cam, 108, 360, 150, 100, c_blue, NULL);          /* tall blue: a post */
    {   /* Y then B: neither */
        int u0, u1;
        t_cols(&cam, 408, 300, 100, &u0, &u1);
        paint(f, u0, u1, 200, 300, c_yellow);
        paint(f, u0, u1, 120, 199, c_blue);
    }
    n = fl_hlv_frame(&hv, &f->img, &cam, &obs);
    CHECK_EQ(n, 1);
    CHECK(find_obs(&obs, FL_LM_POST, FL_COLOR_SKYBLUE) != NULL);
    CHECK(find_obs(&obs, FL_LM_BEACON, FL_COLOR_SKYBLUE) == NULL);
    CHECK(find_obs(&obs, FL_LM_BEACON, FL_COLOR_YELLOW) == NULL);
    /* a column without green below is no post */
    paint(f, 0, HW - 1, 0, HH - 1, c_grey);
    paint_object(f, &cam, 310, 350, 150, 100, c_yellow, NULL);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
    /* a yellow box three times too wide for a post at its range */
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    {
        int u0, u1;
        t_cols(&cam, 310, 300, 100, &u0, &u1);
        paint(f, 310 - 3 * (u1 - u0), 310 + 3 * (u1 - u0), 220, 300, c_yellow);
    }
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
    CHECK(hv.objects_rejected > 0);
    free(f);
}

/* Two yellow posts: left and right by their order; one post with a bar
 * to its right: the left post. */
static void test_goal_sides(void)
{
    t_frame_t *f = frame_new(c_grey);
    fl_camera_t cam;
    fl_obs_list_t obs;
    fl_hlv_params_t p;
    const fl_field_t *field = fl_field_find("hl3x2");
    int k, foot_u[2], foot_v[2];
    CHECK(field != NULL);
    if (!field) {
        free(f);
        return;
    }
    fl_hlv_params_default(&p, field);   /* posts 50 mm, goal 800 mm wide */
    CHECK_EQ(fl_hlv_init(&hv, &p), FL_OK);
    t_camera(&cam);
    for (k = 0; k < 2; k++) {   /* the feet of a goal 1200 mm ahead */
        fl_point_t g;
        int32_t uq, vq;
        g.x_mm = 1200;
        g.y_mm = k ? -400 : 400;
        CHECK(fl_camera_ground_to_pixel(&cam, g, &uq, &vq));
        foot_u[k] = uq / 16;
        foot_v[k] = vq / 16;
    }
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint_object(f, &cam, foot_u[0], foot_v[0], 90, 50, c_yellow, NULL);
    paint_object(f, &cam, foot_u[1], foot_v[1], 90, 50, c_yellow, NULL);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 2);
    CHECK_EQ(obs.obs[0].side, FL_SIDE_LEFT);
    CHECK_EQ(obs.obs[1].side, FL_SIDE_RIGHT);
    CHECK(obs.obs[0].bearing > obs.obs[1].bearing);
    /* one post with its bar to the right: the left post */
    paint(f, foot_u[1] - 40, foot_u[1] + 40, 90, 199, c_grey);
    paint(f, foot_u[1] - 40, foot_u[1] + 40, 200, HH - 1, c_green);
    paint(f, foot_u[0], HW - 1, 90, 97, c_yellow);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 1);
    CHECK_EQ(obs.obs[0].side, FL_SIDE_LEFT);
    /* two posts too close for a goal: no sides */
    paint(f, 0, HW - 1, 0, 199, c_grey);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint_object(f, &cam, foot_u[0], foot_v[0], 90, 50, c_yellow, NULL);
    paint_object(f, &cam, foot_u[0] + 60, foot_v[0], 90, 50, c_yellow, NULL);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 2);
    CHECK_EQ(obs.obs[0].side, FL_SIDE_UNKNOWN);
    CHECK_EQ(obs.obs[1].side, FL_SIDE_UNKNOWN);
    free(f);
}

/* The mask: a white band across green is in it; white on grey is not. */
static void test_mask(void)
{
    t_frame_t *f = frame_new(c_grey);
    fl_camera_t cam;
    fl_obs_list_t obs;
    int i, j, in_line = 0, out_line = 0, on_grey = 0;
    t_init();
    t_camera(&cam);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint(f, 0, HW - 1, 300, 309, c_white);     /* a line across the view */
    paint(f, 100, 300, 120, 160, c_white);      /* white above the field */
    fl_hlv_frame(&hv, &f->img, &cam, &obs);
    CHECK_EQ(hv.status, FL_OK);
    CHECK_EQ(hv.mask_w, HW / 4);
    CHECK_EQ(hv.mask_h, HH / 2);
    for (j = 0; j < hv.mask_h; j++)
        for (i = 0; i < hv.mask_w; i++) {
            const int v = j * 2 + 1;
            const uint8_t m = hv.mask[j * hv.mask_w + i];
            CHECK(m <= 1);
            if (v >= 300 && v <= 309)
                in_line += m;
            else if (v >= 120 && v <= 160)
                on_grey += m;
            else
                out_line += m;
        }
    CHECK_EQ(in_line, 5 * HW / 4);
    CHECK_EQ(out_line, 0);
    CHECK_EQ(on_grey, 0);
    {
        int32_t u, v;
        fl_hlv_mask_to_image(&hv, 10 * 16, 20 * 16, &u, &v);
        CHECK_EQ(u, 10 * 64 + 32);
        CHECK_EQ(v, 20 * 32 + 16);
    }
    free(f);
}

static void test_bad_input(void)
{
    t_frame_t *f = frame_new(c_grey);
    fl_camera_t cam, bad;
    fl_obs_list_t obs;
    fl_image_t img;
    static fl_hlv_t zero;
    t_init();
    t_camera(&cam);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint_object(f, &cam, 310, 350, 150, 100, c_yellow, NULL);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 1);
    CHECK_EQ(fl_hlv_frame(&hv, NULL, &cam, &obs), 0);
    CHECK_EQ(hv.status, FL_ERR_NULL);
    CHECK_EQ(obs.n, 0);
    CHECK_EQ(hv.n_objects, 0);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, NULL, &obs), 0);
    CHECK_EQ(hv.status, FL_ERR_NULL);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, NULL), 0);
    CHECK_EQ(hv.status, FL_ERR_NULL);
    CHECK_EQ(fl_hlv_frame(NULL, &f->img, &cam, &obs), 0);
    CHECK_EQ(obs.n, 0);
    /* uninitialized state */
    CHECK_EQ(fl_hlv_frame(&zero, &f->img, &cam, &obs), 0);
    CHECK_EQ(zero.status, FL_ERR_STATE);
    /* a frame of another size than the camera's */
    fl_image_init_planar(&img, f->p[0], HW, f->p[1], HW, f->p[2], HW, 320, 240);
    CHECK_EQ(fl_hlv_frame(&hv, &img, &cam, &obs), 0);
    CHECK_EQ(hv.status, FL_ERR_MISMATCH);
    /* a broken view */
    img = f->img;
    img.stride[1] = 10;
    CHECK_EQ(fl_hlv_frame(&hv, &img, &cam, &obs), 0);
    CHECK_EQ(hv.status, FL_ERR_STRIDE);
    /* a camera that failed init */
    memset(&bad, 0, sizeof bad);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &bad, &obs), 0);
    CHECK_EQ(hv.status, FL_ERR_CAMERA);
    /* a frame with no field: fine, nothing found */
    paint(f, 0, HW - 1, 0, HH - 1, c_grey);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
    CHECK_EQ(hv.status, FL_OK);
    CHECK_EQ(obs.n_points, 0);
    /* and the next valid frame works */
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint_object(f, &cam, 310, 350, 150, 100, c_yellow, NULL);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 1);
    free(f);
}

/* Bearing (deg) of the centre of a round object of diameter diam whose
 * foot is at row v below column u (Q0). */
static double t_bearing(const fl_camera_t *cam, int u, int v, int32_t diam)
{
    int32_t r;
    fl_angle_t b;
    t_foot_polar(cam, u, v, diam, &r, &b);
    return fl_angle_to_mdeg(b) / 1000.0;
}

/* Posts and poles whose foot the image's left or right edge cuts: found,
 * the range as for whole posts (r / 50 + 10), the bearing within 0.3 deg
 * (3 px on this camera: the inner edge known to half a grid step, the
 * width from the range); the middle of the visible part would be more
 * than 0.8 deg off.  Lower confidence.  Nothing new where there is no post:
 * a clipped column without green below, a clipped box too wide for its
 * range, a clipped pole without its third band, a pole's bottom band
 * alone in the grid columns with its middle band beside them at the edge,
 * a post whose upper part only reaches the side. */
static void test_clipped(void)
{
    t_frame_t *f = frame_new(c_grey);
    fl_camera_t cam;
    fl_obs_list_t obs;
    const fl_obs_t *o;
    int side, u0, u1;
    t_init();
    t_camera(&cam);
    for (side = 0; side < 2; side++) {
        /* a 100 mm post about 1 m away, 56 px wide, its centre 6 px
         * inside the left (right) edge: 34 px of it in the frame */
        const int foot = 330, uc = side ? HW - 1 - 6 : 6;
        const int32_t r = t_range(&cam, uc, foot, 100);
        const double b = t_bearing(&cam, uc, foot, 100);
        int vis0, vis1;
        t_cols(&cam, uc, foot, 100, &u0, &u1);
        vis0 = u0 < 0 ? 0 : u0;
        vis1 = u1 > HW - 1 ? HW - 1 : u1;
        CHECK(u1 - u0 >= 40 && (side ? u1 > HW - 1 : u0 < 0));   /* the setup: cut */
        CHECK(fabs(t_bearing(&cam, (vis0 + vis1) / 2, foot, 100) - b) > 0.8);
        paint(f, 0, HW - 1, 0, 199, c_grey);
        paint(f, 0, HW - 1, 200, HH - 1, c_green);
        paint_object(f, &cam, uc, foot, 20, 100, c_yellow, NULL);
        CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 1);
        CHECK_EQ(hv.n_objects, 1);
        CHECK_EQ(hv.objects[0].clip, side ? 1 : -1);
        o = find_obs(&obs, FL_LM_POST, FL_COLOR_YELLOW);
        CHECK(o != NULL);
        if (o) {
            const double e = fabs(fl_angle_to_mdeg(o->bearing) / 1000.0 - b);
            t_info("clipped post %s: range %d (want %d), bearing error %.2f deg", side ? "right" : "left",
                   (int)o->range_mm, (int)r, e);
            CHECK_LE(abs(o->range_mm - r), r / 50 + 10);
            CHECK(e <= 0.3);
            CHECK_EQ(o->confidence, 160);
            CHECK_EQ(o->side, FL_SIDE_UNKNOWN);
        }
        /* a YBY pole cut alike: a pole, with its band order */
        paint(f, 0, HW - 1, 0, 199, c_grey);
        paint(f, 0, HW - 1, 200, HH - 1, c_green);
        paint_object(f, &cam, uc, foot, 150, 100, c_yellow, c_blue);
        CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 1);
        o = find_obs(&obs, FL_LM_BEACON, FL_COLOR_YELLOW);
        CHECK(o != NULL);
        if (o) {
            CHECK_LE(abs(o->range_mm - r), r / 50 + 10);
            CHECK(fabs(fl_angle_to_mdeg(o->bearing) / 1000.0 - b) <= 0.3);
            CHECK_EQ(o->confidence, 180);
        }
        /* the same two bands without the third: nothing */
        paint(f, 0, HW - 1, 0, 199, c_grey);
        paint(f, 0, HW - 1, 200, HH - 1, c_green);
        paint(f, u0, u1, 250, foot, c_yellow);
        paint(f, u0, u1, 170, 249, c_blue);
        CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
        /* the post without green below: nothing */
        paint(f, 0, HW - 1, 0, HH - 1, c_grey);
        paint_object(f, &cam, uc, foot, 20, 100, c_yellow, NULL);
        CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
        /* a yellow box at the side, four post widths in the frame: too
         * wide for a post at its range */
        paint(f, 0, HW - 1, 200, HH - 1, c_green);
        paint(f, 0, HW - 1, 0, 199, c_grey);
        paint(f, side ? HW - 4 * (u1 - u0) : 0, side ? HW - 1 : 4 * (u1 - u0), 20, foot, c_yellow);
        hv.objects_rejected = 0;
        CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
        CHECK_EQ(hv.objects_rejected, 1);
        /* a BYB pole leaning out of the frame: its bottom band alone in
         * the grid columns (u 2, 6, 10; 630, 634, 638), its yellow band
         * above it only in the pixel columns the grid does not read, at
         * the edge (u 0..1; 639) */
        paint(f, 0, HW - 1, 0, 199, c_grey);
        paint(f, 0, HW - 1, 200, HH - 1, c_green);
        paint(f, side ? HW - 12 : 0, side ? HW - 1 : 11, foot - 40, foot, c_blue);
        paint(f, side ? HW - 1 : 0, side ? HW - 1 : 1, foot - 70, foot - 41, c_yellow);
        hv.objects_rejected = 0;
        CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
        CHECK_EQ(hv.objects_rejected, 1);
        /* a post whose foot is whole, 30 px inside, and whose upper part
         * alone reaches the side (a leaning near post): not clipped, and
         * touching the side, dropped */
        paint(f, 0, HW - 1, 0, 199, c_grey);
        paint(f, 0, HW - 1, 200, HH - 1, c_green);
        paint_object(f, &cam, side ? HW - 1 - 58 : 58, foot, 120, 100, c_yellow, NULL);
        paint(f, side ? HW - 40 : 0, side ? HW - 1 : 39, 120, 230, c_yellow);
        CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
    }
    free(f);
}

/* Seed 002's vision with its defaults on hl3x2 and the acyut-640 camera
 * (allocated; the caller frees it), or NULL after a failed check. */
static fl_hlv_t *hl3x2_vision(const fl_field_t **field, const fl_camera_model_t **m)
{
    fl_hlv_t *st = malloc(sizeof *st);
    fl_hlv_params_t p;
    *field = fl_field_find("hl3x2");
    *m = fl_camera_model_find("acyut-640");
    CHECK(*field != NULL && *m != NULL && st != NULL);
    if (*field == NULL || *m == NULL || st == NULL) {
        free(st);
        return NULL;
    }
    fl_hlv_params_default(&p, *field);
    CHECK_EQ(fl_hlv_init(st, &p), FL_OK);
    return st;
}

/* Rendered hl3x2 frames (acyut-640, head 20 deg down, the room behind
 * the carpet) where a yellow goal post's foot is cut by the image's left
 * edge (robot at (12, 660) facing 159 deg: half the post's 18 px in the
 * frame; at 158 deg a single grid column, too few) and, mirrored, by its right
 * edge: found, the range within 10 % and the bearing within 1 deg of the
 * truth (the rendered posts' bounds of hlvision.rendered are 10 % and 2
 * deg); the post seen by the renderer is cut indeed (its axis's foot
 * less than half its width from the edge). */
static void test_clipped_rendered(void)
{
    const fl_field_t *field;
    const fl_camera_model_t *m;
    fl_hlv_t *st = hl3x2_vision(&field, &m);
    int side;
    if (st == NULL)
        return;
    for (side = 0; side < 2; side++) {
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        fl_obs_list_t obs;
        const fl_obs_t *o;
        double u, v, rx, ry;
        int k, lm = -1;
        render_scene_default(&sc, field, m);
        sc.robot_x_mm = 12;
        sc.robot_y_mm = side ? -660 : 660;
        sc.robot_heading = fl_angle_from_mdeg(side ? -159000 : 159000);
        if (render_frame(&sc, &fr) != 0 || render_scene_camera(&sc, &cam) != FL_OK) {
            CHECK(0);
            continue;
        }
        for (k = 0; k < field->n_landmarks; k++)   /* the yellow post at (-1512, +-400) */
            if (field->landmarks[k].kind == FL_LM_POST && field->landmarks[k].color == FL_COLOR_YELLOW &&
                (field->landmarks[k].y_mm > 0) == (side == 0))
                lm = k;
        CHECK(lm >= 0);
        if (lm < 0) {
            render_frame_free(&fr);
            continue;
        }
        CHECK(render_project_field(&sc, field->landmarks[lm].x_mm, field->landmarks[lm].y_mm, 0, &u, &v, NULL));
        CHECK(side ? u > HW - 1 - 4 : u < 4);   /* the setup: the axis's foot at the edge */
        fl_hlv_frame(st, &fr.view, &cam, &obs);
        CHECK_EQ(st->status, FL_OK);
        o = find_obs(&obs, FL_LM_POST, FL_COLOR_YELLOW);
        CHECK(o != NULL);
        if (o) {
            double range, brg, eb;
            render_field_to_robot(&sc, field->landmarks[lm].x_mm, field->landmarks[lm].y_mm, &rx, &ry);
            range = sqrt(rx * rx + ry * ry);
            brg = atan2(ry, rx) * 180 / M_PI;
            eb = fabs(fl_angle_to_mdeg(o->bearing) / 1000.0 - brg);
            t_info("rendered clipped post %s (foot u %.1f): range %d (truth %.0f), bearing %.2f (truth %.2f)",
                   side ? "right" : "left", u, (int)o->range_mm, range, fl_angle_to_mdeg(o->bearing) / 1000.0,
                   brg);
            CHECK(fabs(o->range_mm - range) <= 0.10 * range);
            CHECK(eb <= 1.0);
            CHECK_EQ(o->confidence, 160);
        }
        /* and nothing else but the crossings */
        for (k = 0; k < obs.n; k++)
            CHECK(obs.obs[k].kind == FL_LM_X || obs.obs[k].kind == FL_LM_T || &obs.obs[k] == o);
        render_frame_free(&fr);
    }
    free(st);
}

/* ---- rendered hl3x2 frames ---------------------------------------------- */

typedef struct {
    int truth[2], found[2], wrong_kind, extra, sided, wrong_side;  /* [0] posts, [1] poles */
    double rng_sum[2], rng_max[2], brg_max[2];  /* relative range, deg */
    /* crossings: [0] up to 1.5 m, [1] 1.5..2.5 m */
    int cr_truth[2], cr_found[2], cr_kind_ok, cr_false, cr_orient_n;
    double cr_err_sum, cr_err_max, cr_orient_max;   /* ground mm, deg */
} t_score_t;

/* Degrees of a binary angle difference wrapped to (-180, 180], mod m deg. */
static double t_angle_err(fl_angle_t a, fl_angle_t b, double mod)
{
    double d = fl_angle_to_mdeg(fl_angle_sub(a, b)) / 1000.0;
    d = fmod(fabs(d), mod);
    return d > mod / 2 ? mod - d : d;
}

/* Crossings (X, T) against the truth: a truth X or T, not occluded, at
 * least 16 px inside the image and within 2.5 m, must be matched by a
 * detection of its kind within 150 mm + 10 % of its range on the ground;
 * every X / T detection must lie that close to some crossing or mark of
 * the truth (else false). */
static void score_crossings(const render_scene_t *sc, const fl_obs_list_t *obs, t_score_t *s)
{
    static truth_t t;
    int k, i;
    if (truth_compute(sc, NULL, &t) != 0) {
        CHECK(0);
        return;
    }
    for (k = 0; k < t.n; k++) {
        const truth_feature_t *f = &t.f[k];
        int best = -1, bin;
        double bd = 1e9;
        if ((f->kind != TRUTH_X && f->kind != TRUTH_T) || f->occluded || f->u < 16 || f->v < 16 ||
            f->u > HW - 17 || f->v > HH - 17 || f->range_mm > 2500)
            continue;
        bin = f->range_mm > 1500;
        s->cr_truth[bin]++;
        for (i = 0; i < obs->n; i++) {
            const fl_obs_t *o = &obs->obs[i];
            fl_point_t p;
            double d;
            if (o->kind != FL_LM_X && o->kind != FL_LM_T)
                continue;
            p = fl_point_from_polar(o->range_mm, o->bearing);
            d = hypot(p.x_mm - f->robot_x_mm, p.y_mm - f->robot_y_mm);
            if (d < bd) {
                bd = d;
                best = i;
            }
        }
        if (best < 0 || bd > 150 + 0.1 * f->range_mm)
            continue;
        s->cr_found[bin]++;
        s->cr_err_sum += bd;
        if (bd > s->cr_err_max)
            s->cr_err_max = bd;
        if ((obs->obs[best].kind == FL_LM_X) == (f->kind == TRUTH_X))
            s->cr_kind_ok++;
        if (obs->obs[best].has_orientation && f->landmark >= 0) {
            fl_angle_t o;
            if (fl_landmark_orientation(&sc->field->landmarks[f->landmark], &o)) {
                const fl_angle_t want = fl_angle_sub(o, sc->robot_heading);
                const double e = t_angle_err(obs->obs[best].orientation, want,
                                             f->kind == TRUTH_X ? 90.0 : 360.0);
                s->cr_orient_n++;
                if (e > s->cr_orient_max)
                    s->cr_orient_max = e;
            }
        }
    }
    for (i = 0; i < obs->n; i++) {
        const fl_obs_t *o = &obs->obs[i];
        fl_point_t p;
        int near = 0;
        if (o->kind != FL_LM_X && o->kind != FL_LM_T)
            continue;
        p = fl_point_from_polar(o->range_mm, o->bearing);
        for (k = 0; k < t.n; k++) {
            const truth_feature_t *f = &t.f[k];
            if (f->kind > TRUTH_CENTRE_MARK && f->kind != TRUTH_CIRCLE_ARC)
                continue;
            if (hypot(p.x_mm - f->robot_x_mm, p.y_mm - f->robot_y_mm) <= 150 + 0.1 * f->range_mm)
                near = 1;
        }
        s->cr_false += !near;
    }
}

/* Score one frame: every post and pole of the field whose foot projects
 * at least 8 px inside the image, with its whole height below the top and
 * not occluded, must be found (same kind and colour, bearing within 3 deg);
 * every observation must match a landmark of its kind and colour. */
static void score_frame(const render_scene_t *sc, const fl_camera_t *cam, const fl_obs_list_t *obs,
                        t_score_t *s)
{
    const fl_field_t *f = sc->field;
    int k, i, used[FL_OBS_MAX];
    memset(used, 0, sizeof used);
    for (k = 0; k < f->n_landmarks; k++) {
        const fl_landmark_t *lm = &f->landmarks[k];
        const int pole = lm->kind == FL_LM_BEACON, h = pole ? f->beacon_height_mm : f->post_height_mm;
        double u, v, ut, vt, rx, ry, range, brg;
        int best = -1;
        if (lm->kind != FL_LM_POST && !pole)
            continue;
        if (!render_project_field(sc, lm->x_mm, lm->y_mm, 0, &u, &v, NULL) ||
            !render_project_field(sc, lm->x_mm, lm->y_mm, pole ? h : 60, &ut, &vt, NULL))
            continue;
        if (u < 24 || u > HW - 25 || v < 8 || v > HH - 9 || vt < 2)
            continue;
        if (render_occluded(sc, lm->x_mm, lm->y_mm, 30, 60, k) ||
            render_occluded(sc, lm->x_mm, lm->y_mm, h / 2, 60, k))
            continue;
        render_field_to_robot(sc, lm->x_mm, lm->y_mm, &rx, &ry);
        range = sqrt(rx * rx + ry * ry);
        brg = atan2(ry, rx) * 180 / M_PI;
        s->truth[pole]++;
        if (getenv("HLV_VERBOSE"))
            t_info("  truth lm %d kind %d at %.1f %.1f range %.0f bearing %.2f", k, (int)lm->kind, u, v,
                   range, brg);
        for (i = 0; i < obs->n; i++) {
            const fl_obs_t *o = &obs->obs[i];
            const double ob = fl_angle_to_mdeg(o->bearing) / 1000.0;
            if (o->kind == lm->kind && o->color == lm->color && fabs(ob - brg) < 3.0 &&
                (best < 0 || fabs(ob - brg) < fabs(fl_angle_to_mdeg(obs->obs[best].bearing) / 1000.0 - brg)))
                best = i;
        }
        if (best < 0 && getenv("HLV_VERBOSE"))
            t_info("  MISSED lm %d", k);
        if (best >= 0) {
            const fl_obs_t *o = &obs->obs[best];
            const double er = fabs(o->range_mm - range) / range;
            const double eb = fabs(fl_angle_to_mdeg(o->bearing) / 1000.0 - brg);
            used[best] = 1;
            if (getenv("HLV_VERBOSE"))
                t_info("  truth lm %d: range %.0f bearing %.2f, found %d range err %.1f%% brg err %.2f side %d/%d",
                       k, range, brg, best, 100 * er, eb, (int)o->side, (int)lm->side);
            s->found[pole]++;
            s->rng_sum[pole] += er;
            if (er > s->rng_max[pole])
                s->rng_max[pole] = er;
            if (eb > s->brg_max[pole])
                s->brg_max[pole] = eb;
            if (pole && o->color2 != lm->color2)
                s->wrong_kind++;
            if (!pole && o->side != FL_SIDE_UNKNOWN) {
                s->sided++;
                s->wrong_side += o->side != lm->side;
            }
        }
    }
    (void)cam;
    for (i = 0; i < obs->n; i++) {
        const fl_obs_t *o = &obs->obs[i];
        int match = 0;
        if (used[i] || (o->kind != FL_LM_POST && o->kind != FL_LM_BEACON))
            continue;
        for (k = 0; k < f->n_landmarks; k++)
            if (f->landmarks[k].kind == o->kind && f->landmarks[k].color == o->color) {
                double rx, ry;
                render_field_to_robot(sc, f->landmarks[k].x_mm, f->landmarks[k].y_mm, &rx, &ry);
                if (fabs(fl_angle_to_mdeg(o->bearing) / 1000.0 - atan2(ry, rx) * 180 / M_PI) < 5.0)
                    match = 1;
            }
        if (match)
            s->extra += 0;   /* a landmark seen but not required (partly visible) */
        else if (o->kind == FL_LM_BEACON)
            s->wrong_kind++;   /* a pole where no pole of that colour is */
        else
            s->extra++;
    }
}

/* Random poses on the hl3x2 field, the head looking 15..35 deg down and
 * up to 40 deg to the side; detections against the field's landmarks. */
static void test_rendered(void)
{
    const fl_field_t *field;
    const fl_camera_model_t *m;
    const int frames = t_quick ? 12 : 48;
    t_score_t s;
    t_rng_t rng;
    fl_hlv_t *st = hl3x2_vision(&field, &m);
    const int verbose = getenv("HLV_VERBOSE") != NULL;
    int n;
    if (st == NULL)
        return;
    memset(&s, 0, sizeof s);
    t_rng_seed(&rng, 2002);
    for (n = 0; n < frames; n++) {
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        fl_obs_list_t obs;
        render_scene_default(&sc, field, m);
        sc.robot_x_mm = (int32_t)(t_rng_u32(&rng) % 2800) - 1400;
        sc.robot_y_mm = (int32_t)(t_rng_u32(&rng) % 1800) - 900;
        sc.robot_heading = (fl_angle_t)(t_rng_u32(&rng) & 0xFFFF);
        sc.head.head_pitch = fl_angle_from_mdeg(15000 + (int32_t)(t_rng_u32(&rng) % 20000));
        sc.head.head_yaw = fl_angle_from_mdeg((int32_t)(t_rng_u32(&rng) % 80000) - 40000);
        sc.seed = (uint32_t)n + 1;
        sc.format = (n % 3) == 0 ? FL_FMT_YUYV422 : (n % 3) == 1 ? FL_FMT_RGB888 : FL_FMT_YCBCR_PLANAR;
        if (render_frame(&sc, &fr) != 0 || render_scene_camera(&sc, &cam) != FL_OK) {
            CHECK(0);
            continue;
        }
        fl_hlv_frame(st, &fr.view, &cam, &obs);
        CHECK_EQ(st->status, FL_OK);
        score_frame(&sc, &cam, &obs, &s);
        score_crossings(&sc, &obs, &s);
        if (verbose) {
            int i;
            char path[64];
            t_info("frame %d: pose %d %d %d head %d %d: %d obs", n, (int)sc.robot_x_mm,
                   (int)sc.robot_y_mm, (int)fl_angle_to_mdeg(sc.robot_heading) / 1000,
                   (int)fl_angle_to_mdeg(sc.head.head_pitch), (int)fl_angle_to_mdeg(sc.head.head_yaw),
                   (int)obs.n);
            for (i = 0; i < obs.n; i++)
                t_info("  kind %d color %d/%d side %d range %d bearing %.2f at %.1f %.1f", (int)obs.obs[i].kind,
                       (int)obs.obs[i].color, (int)obs.obs[i].color2, (int)obs.obs[i].side,
                       (int)obs.obs[i].range_mm, fl_angle_to_mdeg(obs.obs[i].bearing) / 1000.0,
                       obs.obs[i].u_q4 / 16.0, obs.obs[i].v_q4 / 16.0);
            snprintf(path, sizeof path, "/tmp/hp/r%02d.ppm", n);
            render_write_frame(path, &fr);
        }
        render_frame_free(&fr);
    }
    t_info("hlvision rendered %d frames: posts %d/%d (range err mean %.1f%% max %.1f%%, bearing "
           "max %.2f deg), poles %d/%d (range err mean %.1f%% max %.1f%%, bearing max %.2f deg), "
           "wrong kind %d, extra %d, sides %d (wrong %d)",
           frames, s.found[0], s.truth[0], s.found[0] ? 100 * s.rng_sum[0] / s.found[0] : 0,
           100 * s.rng_max[0], s.brg_max[0], s.found[1], s.truth[1],
           s.found[1] ? 100 * s.rng_sum[1] / s.found[1] : 0, 100 * s.rng_max[1], s.brg_max[1],
           s.wrong_kind, s.extra, s.sided, s.wrong_side);
    t_info("crossings: found %d/%d up to 1.5 m, %d/%d at 1.5..2.5 m, kind right %d, "
           "ground error mean %.0f mm max %.0f mm, orientation (%d) max %.1f deg, false %d",
           s.cr_found[0], s.cr_truth[0], s.cr_found[1], s.cr_truth[1], s.cr_kind_ok,
           s.cr_found[0] + s.cr_found[1] ? s.cr_err_sum / (s.cr_found[0] + s.cr_found[1]) : 0,
           s.cr_err_max, s.cr_orient_n, s.cr_orient_max, s.cr_false);
    CHECK(s.cr_truth[0] >= frames / 4);
    CHECK_LE(s.cr_truth[0] - s.cr_found[0], s.cr_truth[0] / 5);   /* >= 80 % up to 1.5 m */
    CHECK_LE(s.cr_truth[1] - s.cr_found[1], s.cr_truth[1] / 2);   /* >= 50 % to 2.5 m */
    CHECK_EQ(s.cr_kind_ok, s.cr_found[0] + s.cr_found[1]);       /* X never for T */
    CHECK_LE(s.cr_err_max, 60);
    CHECK_LE(s.cr_orient_max, 30);
    CHECK_LE(s.cr_false, frames / 16);
    CHECK(s.truth[0] >= frames / 4);
    CHECK(s.truth[1] >= frames / 8);
    CHECK_LE(s.truth[0] - s.found[0], s.truth[0] / 10);   /* >= 90 % of the posts */
    CHECK_LE(s.truth[1] - s.found[1], s.truth[1] / 10);   /* and of the poles */
    CHECK_EQ(s.wrong_kind, 0);                            /* YBY never for BYB */
    CHECK_EQ(s.wrong_side, 0);
    CHECK(s.sided >= s.found[0] / 3);
    CHECK_LE(s.extra, 1 + frames / 8);   /* partly seen posts the truth does not require */
    CHECK_LE(s.rng_max[0], 0.10);
    CHECK_LE(s.rng_max[1], 0.10);
    CHECK_LE(s.brg_max[0], 2.0);
    CHECK_LE(s.brg_max[1], 2.0);
    free(st);
}

void suite_hlvision(void)
{
    t_run("hlvision.boxes", test_boxes);
    t_run("hlvision.posts_poles", test_posts_poles);
    t_run("hlvision.goal_sides", test_goal_sides);
    t_run("hlvision.mask", test_mask);
    t_run("hlvision.bad_input", test_bad_input);
    t_run("hlvision.clipped", test_clipped);
    t_run("hlvision.clipped_rendered", test_clipped_rendered);
    t_run("hlvision.rendered", test_rendered);
}
