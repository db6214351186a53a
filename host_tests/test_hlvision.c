/*
 * host_tests/test_hlvision.c - seed 002's vision path (hlvision.h): the
 * colour boxes, posts and poles on images built here (planar YCbCr, pixel
 * values chosen inside / outside the default boxes), the mask, bad input.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"

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

/* Rows v0..v1 (inclusive), columns u0..u1. */
static void paint(t_frame_t *f, int u0, int u1, int v0, int v1, const uint8_t c[3])
{
    int u, v, k;
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
    p.col_step = 0;
    CHECK_EQ(fl_hlv_init(&hv, &p), FL_ERR_RANGE);
    fl_hlv_params_default(&p, NULL);
    p.max_range_mm = FL_OBS_MAX_RANGE_MM + 1;
    CHECK_EQ(fl_hlv_params_check(&p), FL_ERR_RANGE);
    CHECK_EQ(fl_hlv_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_hlv_init(&hv, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_hlv_init_cfg(&hv, &p, FL_CONFIG_FINGERPRINT ^ 1u), FL_ERR_CONFIG);
}

/* The ground under image row v (foot at its lower edge), column u. */
static int32_t t_range(const fl_camera_t *cam, int u, int v, int32_t diam)
{
    fl_point_t g;
    int32_t uq = u * 16, vq = v * 16 + 8, r;
    fl_angle_t b;
    CHECK(fl_camera_foot_to_centre(cam, &uq, &vq, diam, &g));
    fl_polar_from_point(g, &r, &b);
    return r;
}

static const fl_obs_t *find_obs(const fl_obs_list_t *o, fl_landmark_kind_t kind, fl_color_t c)
{
    int i;
    for (i = 0; i < o->n; i++)
        if (o->obs[i].kind == kind && o->obs[i].color == c)
            return &o->obs[i];
    return NULL;
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
    int32_t n, r;
    t_init();
    t_camera(&cam);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint(f, 300, 319, 150, 350, c_yellow);                /* yellow post */
    paint(f, 100, 115, 300, 360, c_yellow);                /* YBY pole */
    paint(f, 100, 115, 240, 299, c_blue);
    paint(f, 100, 115, 180, 239, c_yellow);
    paint(f, 500, 515, 250, 290, c_blue);                  /* BYB pole */
    paint(f, 500, 515, 210, 249, c_yellow);
    paint(f, 500, 515, 170, 209, c_blue);
    n = fl_hlv_frame(&hv, &f->img, &cam, &obs);
    CHECK_EQ(hv.status, FL_OK);
    CHECK_EQ(n, 3);
    CHECK_EQ(hv.n_objects, 3);
    o = find_obs(&obs, FL_LM_POST, FL_COLOR_YELLOW);
    CHECK(o != NULL);
    if (o) {
        r = t_range(&cam, 310, 350, 100);
        CHECK_LE(abs(o->range_mm - r), r / 50 + 10);
        CHECK_EQ(o->side, FL_SIDE_UNKNOWN);
        CHECK_LE(abs(o->u_q4 / 16 - 310), 4);
    }
    o = find_obs(&obs, FL_LM_BEACON, FL_COLOR_YELLOW);
    CHECK(o != NULL);
    if (o) {
        CHECK_EQ(o->color2, FL_COLOR_YELLOW);
        r = t_range(&cam, 108, 360, 100);
        CHECK_LE(abs(o->range_mm - r), r / 50 + 10);
        CHECK(o->bearing > 0);   /* left of the image centre */
    }
    o = find_obs(&obs, FL_LM_BEACON, FL_COLOR_SKYBLUE);
    CHECK(o != NULL);
    if (o) {
        CHECK_EQ(o->color2, FL_COLOR_SKYBLUE);
        r = t_range(&cam, 508, 290, 100);
        CHECK_LE(abs(o->range_mm - r), r / 50 + 10);
        CHECK(o->bearing < 0);
    }
    /* a single-colour column is never a pole, a two-band column nothing */
    paint(f, 0, HW - 1, 0, 199, c_grey);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint(f, 100, 115, 150, 360, c_blue);                  /* tall blue: a post */
    paint(f, 400, 415, 200, 300, c_yellow);                /* Y then B: neither */
    paint(f, 400, 415, 120, 199, c_blue);
    n = fl_hlv_frame(&hv, &f->img, &cam, &obs);
    CHECK_EQ(n, 1);
    CHECK(find_obs(&obs, FL_LM_POST, FL_COLOR_SKYBLUE) != NULL);
    CHECK(find_obs(&obs, FL_LM_BEACON, FL_COLOR_SKYBLUE) == NULL);
    CHECK(find_obs(&obs, FL_LM_BEACON, FL_COLOR_YELLOW) == NULL);
    /* a column without green below is no post */
    paint(f, 0, HW - 1, 0, HH - 1, c_grey);
    paint(f, 300, 319, 150, 350, c_yellow);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 0);
    free(f);
}

/* Two yellow posts: left and right by their order; one post with a bar
 * to its right: the left post. */
static void test_goal_sides(void)
{
    t_frame_t *f = frame_new(c_grey);
    fl_camera_t cam;
    fl_obs_list_t obs;
    t_init();
    t_camera(&cam);
    paint(f, 0, HW - 1, 200, HH - 1, c_green);
    paint(f, 200, 215, 120, 330, c_yellow);
    paint(f, 450, 465, 120, 330, c_yellow);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 2);
    CHECK_EQ(obs.obs[0].side, FL_SIDE_LEFT);
    CHECK_EQ(obs.obs[1].side, FL_SIDE_RIGHT);
    CHECK(obs.obs[0].bearing > obs.obs[1].bearing);
    paint(f, 450, 465, 120, 330, c_grey);
    paint(f, 450, 465, 200, 330, c_green);
    paint(f, 216, 400, 120, 130, c_yellow);   /* the crossbar to the right */
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 1);
    CHECK_EQ(obs.obs[0].side, FL_SIDE_LEFT);
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
    paint(f, 300, 319, 150, 350, c_yellow);
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
    paint(f, 300, 319, 150, 350, c_yellow);
    CHECK_EQ(fl_hlv_frame(&hv, &f->img, &cam, &obs), 1);
    free(f);
}

void suite_hlvision(void)
{
    t_run("hlvision.boxes", test_boxes);
    t_run("hlvision.posts_poles", test_posts_poles);
    t_run("hlvision.goal_sides", test_goal_sides);
    t_run("hlvision.mask", test_mask);
    t_run("hlvision.bad_input", test_bad_input);
}
