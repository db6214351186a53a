/*
 * src/vision/hlv.c - seed 002's vision path (hlvision.h): params, colour
 * tables, the per-frame driver and the projection of its findings to the
 * ground (seed 002's inverse perspective, its ref. [6]: fl_camera's
 * pixel-to-ground ray, camera.h).
 *
 * Default boxes.  Seed 002 calibrates its YCbCr ranges by hand ("pre-
 * calibrated ranges for every color").  Ours were measured on 30 rendered
 * hl3x2 frames (tools/world renderer, acyut-640, random poses on the
 * field, head 15..35 deg down, world seeds 1..3, noise on): per class the
 * 1 % / 50 % / 99 % quantiles of Y, Cb, Cr over the renderer's truth-mask
 * pixels of that class with the same class 2 px around them (goal pixels
 * split into yellow and sky-blue by Cb < 128):
 *   yellow  Y 112/152/180  Cb 54/66/82     Cr 137/141/143   (59055 px)
 *   blue    Y 86/107/139   Cb 152/159/168  Cr 81/91/99      (120431 px)
 *   green   Y 79/110/129   Cb 108/111/116  Cr 100/105/111   (5.5 M px)
 *   white   Y 184/243/255  Cb 125/127/128  Cr 127/129/130   (148340 px)
 * Boxes: chroma 1 % - 8 .. 99 % + 8, luma 1 % - 24 .. 99 % + 24 (light
 * changes luma most), white from 160 (below it the green box's top, 153,
 * stays apart).  The boxes do not overlap.
 *
 * Default grid (mask_step_u, mask_step_v 0: auto, the image's width over
 * 160 and its height over 240, rounded up: 4 x 2 on 640x480, 2 x 1 on
 * 320x240, the same angles per cell; a 160 x 240 grid).  On a
 * camera looking down from a small humanoid's head, a painted line w wide
 * at ground range d is about f * w / d pixels wide when it runs away from
 * the camera and f * h * w / d^2 pixels tall when it runs across the view
 * (h the camera's height), so lines are much thinner vertically than
 * horizontally.  On hl3x2 (w = 25 mm) with acyut-640 (f = 554 px,
 * h = 460 mm): at 1.5 m a line is 9 px wide and 2.8 px tall, at 2.5 m
 * 5.5 px and 1.0 px; at 0.6 m 23 px and 18 px.  A grid 4 px wide keeps a
 * line running away at least one sample wide to 2.5 m, 2 px tall keeps
 * the cross lines to about 2 m (thinner ones break up), and the near
 * lines are at most 6 x 9 cells, so the thinning runs few passes and
 * surround_px 12 covers half of the widest.  Measured on the 48 rendered
 * frames of host_tests/test_hlvision.c (hlvision.rendered): 4 x 2 finds
 * 23/26 crossings up to 1.5 m and 12/17 at 1.5..2.5 m, every kind right,
 * orientation within 21 deg; 4 x 4 (half the cells) 20/26 and 1/17;
 * 2 x 2 (twice the cells) 20/26 and 15/17 but 7 of 35 kinds wrong (the
 * near lines are twice as many cells thick: spurs become arms) and 17
 * split or spurious posts; 2 x 4 19/26, 4/17, 3 false crossings.  The
 * whole frame costs 4.0 M instructions at 4 x 2 (callgrind, one rendered
 * YUYV frame: grid 1.1 M, mask 0.7 M, objects 0.2 M, skeleton 1.6 M).
 */
#include "hlv_int.h"
#include "fieldloc/fixed.h"

#include <string.h>

static const fl_hlv_box_t hlv_default_box[FL_HLV_N_BOXES] = {
    {88, 204, 46, 90, 129, 151},     /* yellow */
    {62, 163, 144, 176, 73, 107},    /* sky-blue */
    {55, 153, 100, 124, 92, 119},    /* green */
    {160, 255, 117, 136, 119, 138},  /* white */
};

void fl_hlv_params_default(fl_hlv_params_t *p, const fl_field_t *field)
{
    if (p == NULL)
        return;
    memset(p, 0, sizeof *p);
    memcpy(p->box, hlv_default_box, sizeof p->box);
    p->gap_px = 4;
    p->green_gap_px = 6;
    p->min_green_px = 4;
    p->min_post_px = 16;
    p->min_band_px = 4;
    p->min_cols = 2;
    p->foot_tol_px = 12;
    p->mask_step_u = 0;   /* auto: 4 x 2 at 640x480 */
    p->mask_step_v = 0;
    p->surround_px = 12;
    p->post_diameter_mm = 100;
    p->pole_diameter_mm = 100;
    p->goal_width_mm = 1500;
    p->max_range_mm = 6000;
    p->crossings = 1;
    fl_skel_params_default(&p->skel);
    if (field != NULL) {
        if (field->post_diameter_mm >= 10 && field->post_diameter_mm <= 1000)
            p->post_diameter_mm = field->post_diameter_mm;
        if (field->goal_width_mm >= 100 && field->goal_width_mm <= 5000)
            p->goal_width_mm = field->goal_width_mm;
        if (field->beacon_diameter_mm >= 10 && field->beacon_diameter_mm <= 1000)
            p->pole_diameter_mm = field->beacon_diameter_mm;
    }
}

static bool in(int32_t v, int32_t lo, int32_t hi)
{
    return v >= lo && v <= hi;
}

fl_status_t fl_hlv_params_check(const fl_hlv_params_t *p)
{
    if (p == NULL)
        return FL_ERR_NULL;
    if (!in(p->gap_px, 0, 32) ||
        !in(p->green_gap_px, 0, 32) || !in(p->min_green_px, 1, 64) ||
        !in(p->min_post_px, 2, 480) || !in(p->min_band_px, 1, 160) || !in(p->min_cols, 1, 64) ||
        !in(p->foot_tol_px, 0, 480) || !in(p->mask_step_u, 0, 16) || !in(p->mask_step_v, 0, 16) ||
        !in(p->surround_px, 1, 32) || !in(p->post_diameter_mm, 10, 1000) ||
        !in(p->pole_diameter_mm, 10, 1000) || !in(p->goal_width_mm, 100, 5000) || !in(p->max_range_mm, 100, FL_OBS_MAX_RANGE_MM) ||
        !in(p->crossings, 0, 1))
        return FL_ERR_RANGE;
    return FL_OK;
}

fl_status_t fl_hlv_init_cfg(fl_hlv_t *s, const fl_hlv_params_t *p, uint32_t caller_cfg)
{
    fl_status_t st;
    int32_t b, x;
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *s has another layout: no write is safe */
    if (s == NULL)
        return FL_ERR_NULL;
    memset(s, 0, sizeof *s);
    st = fl_hlv_params_check(p);
    if (st != FL_OK) {
        s->status = st;
        return st;
    }
    st = fl_skel_init(&s->skel, &p->skel);
    if (st != FL_OK) {
        s->status = st;
        return st;
    }
    s->params = *p;
    for (b = 0; b < FL_HLV_N_BOXES; b++) {
        const fl_hlv_box_t *k = &p->box[b];
        const uint8_t bit = (uint8_t)(1u << b);
        for (x = 0; x < 256; x++) {
            if (in(x, k->y_min, k->y_max))
                s->ytab[x] |= bit;
            if (in(x, k->cb_min, k->cb_max))
                s->cbtab[x] |= bit;
            if (in(x, k->cr_min, k->cr_max))
                s->crtab[x] |= bit;
        }
    }
    return FL_OK;
}

void fl_hlv_mask_to_image(const fl_hlv_t *s, int32_t mx_q4, int32_t my_q4, int32_t *u_q4,
                          int32_t *v_q4)
{
    const int32_t su = s && s->step_u > 0 ? s->step_u : 1, sv = s && s->step_v > 0 ? s->step_v : 1;
    if (u_q4)
        *u_q4 = mx_q4 * su + (su / 2) * 16;
    if (v_q4)
        *v_q4 = my_q4 * sv + (sv / 2) * 16;
}

/* The width in pixels (Q4) an object of diameter d shows at ground range
 * range_mm: f * d / range (the ground range: a little more than the true
 * one for near objects, where the camera's height adds to the distance). */
static int64_t expect_width_q4(const fl_camera_t *cam, int32_t d, int32_t range_mm)
{
    return (int64_t)cam->model.focal_q4 * d / (range_mm < 1 ? 1 : range_mm);   /* < 2^20 * 1000 */
}

/* Does the object's width in the image fit its diameter at that range?
 * Measured (u1 - u0 + su) px, each end known to a grid step su.  Kept
 * within [expected / 2 - su, 3 * expected + 2 * su]: shading may eat the
 * dark side of a cylinder and a near post at the image's side leans (its
 * columns span more than its diameter), but a yellow box beside the
 * field, whose foot seems to stand on the carpet far away, is many times
 * too wide.  A clipped object (cut: its foot cut by the image's side)
 * shows only part of its width: the upper bound alone. */
static bool width_fits(const fl_hlv_t *s, const fl_hlv_object_t *o, int64_t expect_q4, bool cut)
{
    const int32_t step = s->step_u, width = o->u1 - o->u0 + step;
    return (int64_t)width * 16 <= 3 * expect_q4 + 32 * step &&
           (cut || (int64_t)width * 16 >= expect_q4 / 2 - 16 * step);
}

/* Two posts of one colour whose feet are not about a goal width apart
 * are not a goal: their sides (from the image order) are withdrawn. */
static void check_pairs(const fl_hlv_t *s, fl_obs_list_t *out)
{
    int32_t i, j;
    for (i = 0; i < out->n; i++)
        for (j = i + 1; j < out->n; j++) {
            fl_obs_t *a = &out->obs[i], *b = &out->obs[j];
            fl_point_t pa, pb;
            int64_t dx, dy, d2, w = s->params.goal_width_mm;
            if (a->kind != FL_LM_POST || b->kind != FL_LM_POST || a->color != b->color)
                continue;
            pa = fl_point_from_polar(a->range_mm, a->bearing);
            pb = fl_point_from_polar(b->range_mm, b->bearing);
            dx = pa.x_mm - pb.x_mm;
            dy = pa.y_mm - pb.y_mm;
            d2 = dx * dx + dy * dy;
            if (4 * d2 < w * w || 4 * d2 > 9 * w * w)
                a->side = b->side = FL_SIDE_UNKNOWN;
        }
}

/* The only object of its kind in the frame? */
static bool lone_kind(const fl_hlv_t *s, const fl_hlv_object_t *o)
{
    int32_t i, n = 0;
    for (i = 0; i < s->n_objects; i++)
        n += s->objects[i].kind == o->kind;
    return n == 1;
}

/* A post or pole as an observation: the foot pixel (the lower edge of the
 * lowest coloured sample, between the object's outer columns) to the
 * centre of its base on the ground.
 *
 * A clipped object (o->clip: its foot cut by the image's left or right
 * edge, hlv_cols.c) has only part of its width in the frame, so the
 * middle of its visible columns lies inside the true centre by up to half
 * its width (a 50 mm post on acyut-640: 14 px, 1.4 deg of bearing, at
 * 1 m; 2.9 deg at 0.5 m).  Its inner edge is whole (a post leans
 * outwards towards the image's sides, so the inner edge of its columns is
 * its foot's), so the centre is placed half the width its range gives
 * (expect_width_q4) inside from that edge, and the foot projected again
 * from there.  That beats the visible middle for any cut and needs no
 * second look at the image.  The confidence is lowered still (posts 200
 * -> 160, poles 230 -> 180): the range comes from the lowest visible foot,
 * which is not the base's lowest point when the cut lies short of the
 * axis (the range a little long), the centre rests on that range, and the
 * lower-bound width test, which catches a partial coloured blob, cannot
 * apply.  A lone clipped post takes its side from a crossbar probed at the
 * width its range gives (its visible width may be far less and probe into
 * a goal's top frame). */
static void push_object(fl_hlv_t *s, const fl_image_t *img, const fl_hlv_object_t *o,
                        const fl_camera_t *cam, fl_obs_list_t *out)
{
    const bool pole = o->kind == FL_HLV_POLE_YBY || o->kind == FL_HLV_POLE_BYB;
    const int32_t d = pole ? s->params.pole_diameter_mm : s->params.post_diameter_mm;
    fl_obs_t ob;
    fl_point_t c;
    int32_t u_q4 = (o->foot_u0 + o->foot_u1) * 8, v_q4 = o->foot_v * 16 + 8;
    int64_t expect_q4;
    fl_side_t side = o->side;
    const bool cut = o->clip != 0;
    memset(&ob, 0, sizeof ob);
    if (!fl_camera_foot_to_centre(cam, &u_q4, &v_q4, d, &c))
        return;
    fl_polar_from_point(c, &ob.range_mm, &ob.bearing);
    expect_q4 = expect_width_q4(cam, d, ob.range_mm);
    if (cut) {
        /* the inner edge's last (first) coloured pixel lies within a
         * grid step of the last (first) column: its middle, then half
         * the width to the centre */
        const int32_t half_step_q4 = s->step_u * 8;
        const int32_t half_q4 = (int32_t)(expect_q4 / 2);
        u_q4 = o->clip < 0 ? o->u1 * 16 + half_step_q4 - half_q4 : o->u0 * 16 - half_step_q4 + half_q4;
        v_q4 = o->foot_v * 16 + 8;
        if (!fl_camera_foot_to_centre(cam, &u_q4, &v_q4, d, &c))
            return;
        fl_polar_from_point(c, &ob.range_mm, &ob.bearing);
        expect_q4 = expect_width_q4(cam, d, ob.range_mm);
    }
    if (ob.range_mm > s->params.max_range_mm)
        return;
    if (!width_fits(s, o, expect_q4, cut)) {
        s->objects_rejected++;
        return;
    }
    ob.u_q4 = u_q4;
    ob.v_q4 = v_q4;
    if (pole) {
        ob.kind = FL_LM_BEACON;
        ob.color = o->kind == FL_HLV_POLE_YBY ? FL_COLOR_YELLOW : FL_COLOR_SKYBLUE;
        ob.color2 = ob.color;
        ob.confidence = cut ? 180 : 230;
    } else {
        if (cut && side == FL_SIDE_UNKNOWN && lone_kind(s, o))
            side = fl_hlv_int_bar_side(s, img, o, (int32_t)((expect_q4 + 8) / 16));
        ob.kind = FL_LM_POST;
        ob.color = o->kind == FL_HLV_POST_YELLOW ? FL_COLOR_YELLOW : FL_COLOR_SKYBLUE;
        ob.side = side;
        ob.confidence = cut ? 160 : 200;
    }
    if (!fl_obs_list_push(out, &ob))
        s->obs_dropped++;
}

/* Mask point (Q4) to the ground; false when it is not on the ground. */
static bool mask_to_ground(const fl_hlv_t *s, const fl_camera_t *cam, int32_t x_q4, int32_t y_q4,
                           fl_point_t *g)
{
    int32_t u_q4, v_q4;
    fl_hlv_mask_to_image(s, x_q4, y_q4, &u_q4, &v_q4);
    return fl_camera_pixel_to_ground(cam, u_q4, v_q4, g);
}

/* Ground direction of each arm: the crossing and a point 16 mask px along
 * the arm, both on the ground.  False when one is not. */
static bool arms_on_ground(const fl_hlv_t *s, const fl_camera_t *cam, const fl_skel_crossing_t *c,
                           fl_point_t at, fl_angle_t *dir)
{
    int32_t k;
    for (k = 0; k < c->kind; k++) {
        fl_point_t e;
        const int32_t ex = c->x_q4 + fl_rshift_round((int64_t)fl_cos_q15(c->arm[k]) * 256, 15);
        const int32_t ey = c->y_q4 + fl_rshift_round((int64_t)fl_sin_q15(c->arm[k]) * 256, 15);
        if (!mask_to_ground(s, cam, ex, ey, &e))
            return false;
        dir[k] = fl_atan2(e.y_mm - at.y_mm, e.x_mm - at.x_mm);
    }
    return true;
}

static int32_t abs_angle(fl_angle_t a)
{
    return a < 0 ? -(int32_t)a : (int32_t)a;
}

/* T: the stem is the arm whose best partner is farthest from opposite. */
static fl_angle_t t_stem(const fl_angle_t *dir)
{
    int32_t k, best = 0, best_dev = -1;
    for (k = 0; k < 3; k++) {
        int32_t j, dev = INT32_MAX;
        for (j = 0; j < 3; j++)
            if (j != k) {
                const int32_t d = abs_angle(fl_angle_sub(fl_angle_sub(dir[j], dir[k]), FL_ANGLE_180));
                if (d < dev)
                    dev = d;
            }
        if (dev > best_dev) {
            best_dev = dev;
            best = k;
        }
    }
    return dir[best];
}

/* The skeleton's crossings (X, T) and white points into the list. */
static void push_skeleton(fl_hlv_t *s, const fl_camera_t *cam, fl_obs_list_t *out)
{
    int32_t i;
    for (i = 0; i < s->skel.n_crossings; i++) {
        const fl_skel_crossing_t *c = &s->skel.crossing[i];
        fl_angle_t dir[4];
        fl_point_t g;
        fl_obs_t ob;
        if ((c->kind != FL_SKEL_X && c->kind != FL_SKEL_T) ||
            !mask_to_ground(s, cam, c->x_q4, c->y_q4, &g))
            continue;
        memset(&ob, 0, sizeof ob);
        fl_polar_from_point(g, &ob.range_mm, &ob.bearing);
        if (ob.range_mm > s->params.max_range_mm)
            continue;
        ob.kind = c->kind == FL_SKEL_X ? FL_LM_X : FL_LM_T;
        ob.confidence = c->confidence;
        fl_hlv_mask_to_image(s, c->x_q4, c->y_q4, &ob.u_q4, &ob.v_q4);
        if (arms_on_ground(s, cam, c, g, dir)) {
            ob.has_orientation = true;
            ob.orientation = c->kind == FL_SKEL_X ? dir[0] : t_stem(dir);
        }
        if (!fl_obs_list_push(out, &ob))
            s->obs_dropped++;
    }
    for (i = 0; i < s->skel.n_points; i++) {
        fl_point_t g;
        if (mask_to_ground(s, cam, (int32_t)s->skel.point[i].x * 16, (int32_t)s->skel.point[i].y * 16,
                           &g) &&
            g.x_mm * (int64_t)g.x_mm + g.y_mm * (int64_t)g.y_mm <=
                (int64_t)s->params.max_range_mm * s->params.max_range_mm &&
            !fl_obs_list_push_point(out, g.x_mm, g.y_mm))
            s->points_dropped++;
    }
}

/* First image row that can see the ground (0..height). */
static int32_t ground_row(const fl_camera_t *cam, int32_t width, int32_t height)
{
    const int32_t hz = fl_camera_horizon_top_v_q4(cam, 0, (width - 1) * 16);
    if (hz == INT32_MIN || hz < 0)
        return 0;
    if (hz == INT32_MAX || hz >= height * 16)
        return height;
    return hz / 16 + 1;
}

/* The grid step: the param, or (0) the size over cells rounded up. */
static int32_t grid_step(int32_t param, int32_t size, int32_t cells)
{
    return param > 0 ? param : (size + cells - 1) / cells;
}

static fl_status_t frame_check(const fl_hlv_t *s, const fl_image_t *img, const fl_camera_t *cam)
{
    fl_status_t st;
    if (img == NULL || cam == NULL)
        return FL_ERR_NULL;
    if (fl_hlv_params_check(&s->params) != FL_OK || s->skel.magic == 0)
        return FL_ERR_STATE;
    st = fl_image_validate(img);
    if (st != FL_OK)
        return st;
    if (cam->model.width_px <= 0 || cam->model.focal_q4 <= 0)
        return FL_ERR_CAMERA;
    if (cam->model.width_px != img->width || cam->model.height_px != img->height)
        return FL_ERR_MISMATCH;
    if ((img->width + grid_step(s->params.mask_step_u, img->width, 160) - 1) /
                grid_step(s->params.mask_step_u, img->width, 160) > FL_SKEL_MAX_WIDTH ||
        (img->height + grid_step(s->params.mask_step_v, img->height, 240) - 1) /
                grid_step(s->params.mask_step_v, img->height, 240) > FL_SKEL_MAX_HEIGHT)
        return FL_ERR_SIZE;
    return FL_OK;
}

int32_t fl_hlv_frame(fl_hlv_t *s, const fl_image_t *img, const fl_camera_t *cam,
                     fl_obs_list_t *out)
{
    int32_t v0, i;
    if (out != NULL)
        fl_obs_list_clear(out);
    if (s == NULL)
        return 0;
    s->n_objects = 0;
    s->status = out == NULL ? FL_ERR_NULL : frame_check(s, img, cam);
    if (s->status != FL_OK) {
        s->mask_w = s->mask_h = 0;
        return 0;
    }
    s->frames++;
    v0 = ground_row(cam, img->width, img->height);
    s->step_u = grid_step(s->params.mask_step_u, img->width, 160);
    s->step_v = grid_step(s->params.mask_step_v, img->height, 240);
    s->mask_w = (img->width + s->step_u - 1) / s->step_u;
    s->mask_h = (img->height + s->step_v - 1) / s->step_v;
    fl_hlv_int_classify(s, img);
    fl_hlv_int_objects(s, img, v0);
    for (i = 0; i < s->n_objects; i++)
        if (s->objects[i].kind <= FL_HLV_POST_BLUE)
            push_object(s, img, &s->objects[i], cam, out);
    check_pairs(s, out);
    for (i = 0; i < s->n_objects; i++)
        if (s->objects[i].kind >= FL_HLV_POLE_YBY)
            push_object(s, img, &s->objects[i], cam, out);
    if (s->params.crossings) {
        fl_skel_mask_t m;
        fl_hlv_int_mask(s, (v0 + s->step_v - 1) / s->step_v);
        m.data = s->mask;
        m.width = s->mask_w;
        m.height = s->mask_h;
        m.stride = s->mask_w;
        if (fl_skel_run(&s->skel, &m, s->frames) == FL_OK)
            push_skeleton(s, cam, out);
    } else {
        s->mask_w = s->mask_h = 0;
    }
    return out->n;
}
