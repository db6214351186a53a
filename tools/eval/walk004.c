/*
 * tools/eval/walk004.c - seed 004's walk-through (walk004.h).
 *
 * Per scan frame: render (frames mode) or project the map (features
 * mode), list the frame's observations left to right, fuse the new nets
 * and C's one at a time, measure the belief after each, draw it.  The
 * grid and the corner stage's state are malloc'd once per run.
 */
#include "eval/walk004.h"
#include "eval/detect.h"
#include "eval/picture.h"
#include "io/font.h"
#include "io/ppm.h"
#include "world/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W4_PI 3.14159265358979323846
#define W4_PX 10          /* belief picture: pixels per grid cell */
#define W4_FRAME_SCALE 2  /* camera picture: frame enlarged */

void w4_opts_default(w4_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->x_mm = -1800;
    o->y_mm = -100;
    o->heading_mdeg = 10000;
    o->pitch_mdeg = 0;
    o->yaw_left_mdeg = 60000;
    o->yaw_right_mdeg = -60000;
    o->yaw_step_mdeg = 10000;
    o->seed = 1;
}

/* ---- one run's context -------------------------------------------------- */

typedef struct {
    const w4_opts_t *o;
    FILE *out;
    const fl_field_t *field;
    const fl_camera_model_t *model;
    fl_fuzzy_t *g;
    fl_corners_t *cn;
    det_ctx_t det;
    int det_ready;
    /* the frame being looked at */
    render_scene_t sc;
    render_frame_t fr;
    int have_frame;
    fl_obs_list_t obs;        /* the frame's observations */
    fl_obs_list_t vis_obs;    /* fl_vision_frame's (unused but for posts) */
    /* fused so far (robot frame ground points of the C's) */
    double c_x[W4_MAX_STEPS], c_y[W4_MAX_STEPS];
    int n_c;
    int net_fused[2];         /* yellow, sky-blue */
} w4_ctx_t;

static double w4_deg(fl_angle_t a) { return fl_angle_to_mdeg(a) / 1000.0; }

static const char *w4_kind_name(const fl_obs_t *ob)
{
    switch (ob->kind) {
    case FL_LM_CORNER_C: return "C";
    case FL_LM_CORNER_TFIELD: return "T-field";
    case FL_LM_CORNER_TNET: return "T-net";
    case FL_LM_NET: return ob->color == FL_COLOR_YELLOW ? "net-yellow"
                           : ob->color == FL_COLOR_SKYBLUE ? "net-skyblue" : "net";
    default: return "other";
    }
}

/* The observation's point in the field frame, seen from the true pose. */
static void w4_obs_field(const w4_ctx_t *c, const fl_obs_t *ob, double *fx, double *fy)
{
    double h = c->o->heading_mdeg * W4_PI / 180000.0 + w4_deg(ob->bearing) * W4_PI / 180.0;
    *fx = c->o->x_mm + ob->range_mm * cos(h);
    *fy = c->o->y_mm + ob->range_mm * sin(h);
}

/* Nearest map feature of the observation's kind (and net colour). */
static int w4_map_match_any(const w4_ctx_t *c, const fl_obs_t *ob, int any_kind, double *err)
{
    double fx, fy, best = 1e18;
    int k, bi = -1;
    w4_obs_field(c, ob, &fx, &fy);
    for (k = 0; k < c->field->n_features; k++) {
        const fl_landmark_t *t = &c->field->features[k];
        double d;
        if (!any_kind && (t->kind != ob->kind || (ob->kind == FL_LM_NET && t->color != ob->color)))
            continue;
        d = hypot(t->x_mm - fx, t->y_mm - fy);
        if (d < best) {
            best = d;
            bi = k;
        }
    }
    *err = bi >= 0 ? best : -1;
    return bi;
}

static int w4_map_match(const w4_ctx_t *c, const fl_obs_t *ob, double *err)
{
    return w4_map_match_any(c, ob, 0, err);
}

static const char *w4_lm_name(const fl_landmark_t *t)
{
    fl_obs_t o;
    memset(&o, 0, sizeof o);
    o.kind = t->kind;
    o.color = t->color;
    return w4_kind_name(&o);
}

/* ---- the frame's observations ------------------------------------------- */

static void w4_scene(w4_ctx_t *c, int frame, int32_t yaw_mdeg)
{
    render_scene_default(&c->sc, c->field, c->model);
    c->sc.robot_x_mm = c->o->x_mm;
    c->sc.robot_y_mm = c->o->y_mm;
    c->sc.robot_heading = fl_angle_from_mdeg(c->o->heading_mdeg);
    c->sc.head.head_pitch = fl_angle_from_mdeg(c->o->pitch_mdeg);
    c->sc.head.head_yaw = fl_angle_from_mdeg(yaw_mdeg);
    c->sc.seed = (uint32_t)(c->o->seed * 2654435761u) ^ ((uint32_t)frame * 40503u + 1u);
}

/* Ideal observations: the map features in the frame. */
static void w4_ideal(w4_ctx_t *c, fl_obs_list_t *out)
{
    int k;
    fl_obs_list_clear(out);
    for (k = 0; k < c->field->n_features; k++) {
        const fl_landmark_t *t = &c->field->features[k];
        double u, v, rx, ry, r;
        fl_obs_t ob;
        if (!render_project_field(&c->sc, t->x_mm, t->y_mm, 0, &u, &v, NULL) || u < 8 ||
            v < 8 || u > c->model->width_px - 9 || v > c->model->height_px - 9)
            continue;
        render_field_to_robot(&c->sc, t->x_mm, t->y_mm, &rx, &ry);
        r = hypot(rx, ry);
        if (r > (t->kind == FL_LM_NET ? FL_OBS_MAX_RANGE_MM : W4_CORNER_RANGE_MM))
            continue;
        memset(&ob, 0, sizeof ob);
        ob.kind = t->kind;
        ob.color = t->kind == FL_LM_NET ? t->color : FL_COLOR_NONE;
        ob.range_mm = (int32_t)lround(r);
        ob.bearing = fl_angle_from_mdeg((int32_t)lround(atan2(ry, rx) * 180000.0 / W4_PI));
        ob.confidence = 255;
        ob.u_q4 = (int32_t)lround(u * 16);
        ob.v_q4 = (int32_t)lround(v * 16);
        if (out->n < FL_OBS_MAX)
            out->obs[out->n++] = ob;
    }
}

/* Frames mode: the map's C's in this frame (w4_ideal) against the corner
 * stage's observations: each is reported as a C, as another kind, or not
 * at all (the nearest observation within 150 mm + 10 % of its range,
 * robot frame: eval-detect's tolerance). */
static void w4_truth_score(w4_ctx_t *c, w4_result_t *res)
{
    static fl_obs_list_t truth;
    int i, j;
    w4_ideal(c, &truth);
    for (i = 0; i < truth.n; i++) {
        const fl_obs_t *t = &truth.obs[i];
        double ta = w4_deg(t->bearing) * W4_PI / 180, tx = t->range_mm * cos(ta),
               ty = t->range_mm * sin(ta), best = 150 + 0.1 * t->range_mm;
        int bj = -1;
        if (t->kind != FL_LM_CORNER_C)
            continue;
        res->truth_c_views++;
        for (j = 0; j < c->obs.n; j++) {
            const fl_obs_t *d = &c->obs.obs[j];
            double da = w4_deg(d->bearing) * W4_PI / 180;
            double e = hypot(d->range_mm * cos(da) - tx, d->range_mm * sin(da) - ty);
            if (d->kind != FL_LM_NET && e <= best) {
                best = e;
                bj = j;
            }
        }
        if (bj < 0)
            res->truth_c_missed++;
        else if (c->obs.obs[bj].kind == FL_LM_CORNER_C)
            res->truth_c_as_c++;
        else
            res->truth_c_as_other[c->obs.obs[bj].kind == FL_LM_CORNER_TNET]++;
    }
}

/* Rendered frame through the vision path and the corner stage.  0, -1. */
static int w4_vision(w4_ctx_t *c)
{
    fl_camera_t cam;
    static det_feature_t feat[DET_MAX_FEATURES];
    fl_obs_list_clear(&c->obs);
    if (render_frame(&c->sc, &c->fr) != 0)
        return -1;
    c->have_frame = 1;
    if (render_scene_camera(&c->sc, &cam) != FL_OK)
        return -1;
    (void)det_run(&c->det, &c->fr.view, &cam, c->field, &c->vis_obs, feat, DET_MAX_FEATURES);
    if (fl_corners_run(c->cn, &c->fr.view, c->det.colors, &cam, &c->det.vis->beacons) != FL_OK)
        return -1;
    (void)fl_corners_obs(c->cn, &c->obs);
    return 0;
}

/* Left to right: bearing descending (insertion sort, a handful). */
static void w4_sort(fl_obs_list_t *l)
{
    int i, j;
    for (i = 1; i < l->n; i++) {
        fl_obs_t t = l->obs[i];
        for (j = i; j > 0 && fl_angle_to_mdeg(l->obs[j - 1].bearing) < fl_angle_to_mdeg(t.bearing); j--)
            l->obs[j] = l->obs[j - 1];
        l->obs[j] = t;
    }
}

/* Is the observation new (to be fused)?  Counts what it is. */
static int w4_is_new(w4_ctx_t *c, const fl_obs_t *ob, w4_result_t *res)
{
    if (ob->kind == FL_LM_NET) {
        int i = ob->color == FL_COLOR_YELLOW ? 0 : ob->color == FL_COLOR_SKYBLUE ? 1 : -1;
        return i >= 0 && !c->net_fused[i];
    }
    if (ob->kind == FL_LM_CORNER_C) {
        double a = w4_deg(ob->bearing) * W4_PI / 180, x = ob->range_mm * cos(a),
               y = ob->range_mm * sin(a);
        int k;
        res->seen_c++;
        for (k = 0; k < c->n_c; k++)
            if (hypot(x - c->c_x[k], y - c->c_y[k]) <= W4_SAME_C_MM)
                return 0;
        return 1;
    }
    if (ob->kind == FL_LM_CORNER_TFIELD || ob->kind == FL_LM_CORNER_TNET)
        res->seen_other++;
    return 0;
}

static void w4_mark_fused(w4_ctx_t *c, const fl_obs_t *ob)
{
    if (ob->kind == FL_LM_NET) {
        c->net_fused[ob->color == FL_COLOR_YELLOW ? 0 : 1] = 1;
    } else if (c->n_c < W4_MAX_STEPS) {
        double a = w4_deg(ob->bearing) * W4_PI / 180;
        c->c_x[c->n_c] = ob->range_mm * cos(a);
        c->c_y[c->n_c] = ob->range_mm * sin(a);
        c->n_c++;
    }
}

/* ---- the belief's numbers ------------------------------------------------ */

static void w4_measure(const w4_ctx_t *c, w4_step_t *s)
{
    const fl_fuzzy_t *g = c->g;
    const w4_opts_t *o = c->o;
    const fl_landmark_t *net = NULL;
    fl_fuzzy_estimate_t est;
    int ix, iy, k, top = 0, half = 0;
    double dh;
    for (k = 0; k < c->field->n_features; k++)
        if (c->field->features[k].kind == FL_LM_NET &&
            c->field->features[k].color == FL_COLOR_YELLOW)
            net = &c->field->features[k];
    fl_fuzzy_estimate(c->g, &est);
    s->est_x_mm = est.x_mm;
    s->est_y_mm = est.y_mm;
    s->est_heading_deg = w4_deg(est.heading);
    s->est_ignorance = est.ignorance;
    s->err_mm = hypot(est.x_mm - o->x_mm, est.y_mm - o->y_mm);
    dh = fl_angle_to_mdeg(fl_angle_sub(est.heading, fl_angle_from_mdeg(o->heading_mdeg))) /
         1000.0;
    s->err_deg = fabs(dh);
    s->reliability = est.reliability_q16 / 65535.0;
    s->p_true = fl_fuzzy_possibility_q16(g, o->x_mm, o->y_mm,
                                         fl_angle_from_mdeg(o->heading_mdeg)) / 65536.0;
    s->net_r_min_mm = 1e9;
    s->net_r_max_mm = 0;
    for (iy = 0; iy < g->ny; iy++)
        for (ix = 0; ix < g->nx; ix++) {
            const fl_fuzzy_cell_t *cl = &g->cell[iy * g->nx + ix];
            int32_t cx, cy;
            if (cl->height >= W4_TOP_Q8)
                top++;
            if (cl->height < 128)
                continue;
            half++;
            if (net != NULL && fl_fuzzy_cell_centre(g, ix, iy, &cx, &cy)) {
                double d = hypot(cx - net->x_mm, cy - net->y_mm);
                if (d < s->net_r_min_mm)
                    s->net_r_min_mm = d;
                if (d > s->net_r_max_mm)
                    s->net_r_max_mm = d;
            }
        }
    if (half == 0)
        s->net_r_min_mm = 0;
    s->top_area_m2 = top * (FL_FUZZY_CELL_MM / 1000.0) * (FL_FUZZY_CELL_MM / 1000.0);
    s->half_area_m2 = half * (FL_FUZZY_CELL_MM / 1000.0) * (FL_FUZZY_CELL_MM / 1000.0);
    s->net_r_true_mm = net != NULL ? hypot(o->x_mm - net->x_mm, o->y_mm - net->y_mm) : 0;
}

/* ---- pictures ------------------------------------------------------------- */

static void w4_px(host_image_t *im, int u, int v, const uint8_t *col)
{
    if (u < 0 || v < 0 || u >= im->width || v >= im->height)
        return;
    memcpy(im->rgb + 3 * ((size_t)v * (size_t)im->width + (size_t)u), col, 3);
}

static void w4_line(host_image_t *im, double u0, double v0, double u1, double v1,
                    const uint8_t *col, int thick)
{
    double du = u1 - u0, dv = v1 - v0, n = fmax(fabs(du), fabs(dv));
    int k, steps = (int)ceil(n), i, j;
    if (!isfinite(n) || steps > 16384)
        return;
    for (k = 0; k <= steps; k++) {
        double t = steps ? (double)k / steps : 0;
        int u = (int)lround(u0 + t * du), v = (int)lround(v0 + t * dv);
        for (j = 0; j < thick; j++)
            for (i = 0; i < thick; i++)
                w4_px(im, u + i - thick / 2, v + j - thick / 2, col);
    }
}

static void w4_ring(host_image_t *im, double u, double v, double r, const uint8_t *col)
{
    int k, n = (int)(2 * W4_PI * r) + 8;
    for (k = 0; k < n; k++) {
        double a = 2 * W4_PI * k / n;
        w4_px(im, (int)lround(u + r * cos(a)), (int)lround(v + r * sin(a)), col);
    }
}

static void w4_box(host_image_t *im, double u, double v, int r, const uint8_t *col)
{
    w4_line(im, u - r, v - r, u + r, v - r, col, 1);
    w4_line(im, u - r, v + r, u + r, v + r, col, 1);
    w4_line(im, u - r, v - r, u - r, v + r, col, 1);
    w4_line(im, u + r, v - r, u + r, v + r, col, 1);
}

/* Filled triangle pointing along heading h (radians, picture: +x right, +y
 * up), size r px: seed 004's estimate mark. */
static void w4_triangle(host_image_t *im, double u, double v, double h, double r,
                        const uint8_t *fill, const uint8_t *edge)
{
    double ax = u + r * cos(h), ay = v - r * sin(h);
    double bx = u + 0.7 * r * cos(h + 2.4), by = v - 0.7 * r * sin(h + 2.4);
    double cx = u + 0.7 * r * cos(h - 2.4), cy = v - 0.7 * r * sin(h - 2.4);
    int x0 = (int)floor(fmin(ax, fmin(bx, cx))), x1 = (int)ceil(fmax(ax, fmax(bx, cx)));
    int y0 = (int)floor(fmin(ay, fmin(by, cy))), y1 = (int)ceil(fmax(ay, fmax(by, cy)));
    int x, y;
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++) {
            double d1 = (bx - ax) * (y - ay) - (by - ay) * (x - ax);
            double d2 = (cx - bx) * (y - by) - (cy - by) * (x - bx);
            double d3 = (ax - cx) * (y - cy) - (ay - cy) * (x - cx);
            if ((d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0))
                w4_px(im, x, y, fill);
        }
    w4_line(im, ax, ay, bx, by, edge, 1);
    w4_line(im, bx, by, cx, cy, edge, 1);
    w4_line(im, cx, cy, ax, ay, edge, 1);
}

/* Field mm -> belief picture pixel. */
static void w4_map_px(const fl_fuzzy_t *g, double x, double y, double *u, double *v)
{
    *u = (x - g->x0_mm) * W4_PX / FL_FUZZY_CELL_MM;
    *v = g->ny * W4_PX - (y - g->y0_mm) * W4_PX / FL_FUZZY_CELL_MM;
}

static int w4_save(host_image_t *im, const char *caption, const char *path)
{
    if (pic_legend_inplace(im, 0, caption) != 0)
        return -1;
    return png_write(path, im->rgb, im->width, im->height);
}

/* The grid as seed 004's figure 7: white = impossible, black = fully
 * possible; field lines light green, the yellow and sky-blue nets as
 * bars, the truth a blue ring with its heading, the estimate a filled red
 * triangle; the fused observation (when not NULL) as its ring from the
 * true pose is not drawn (the belief shows it). */
static int w4_belief_picture(const w4_ctx_t *c, const w4_step_t *s, const char *caption,
                             const char *path)
{
    static const uint8_t line_c[3] = {90, 190, 90}, truth_c[3] = {0, 110, 255},
                         est_c[3] = {230, 20, 20}, edge_c[3] = {255, 255, 255},
                         yel[3] = {235, 200, 0}, sky[3] = {60, 190, 255};
    const fl_fuzzy_t *g = c->g;
    host_image_t im = host_image_new(g->nx * W4_PX, g->ny * W4_PX, 255, 255, 255);
    int ix, iy, i, j, k;
    double u, v, u1, v1, h;
    if (im.rgb == NULL)
        return -1;
    for (iy = 0; iy < g->ny; iy++)
        for (ix = 0; ix < g->nx; ix++) {
            const fl_fuzzy_cell_t *cl = &g->cell[iy * g->nx + ix];
            uint8_t grey = (uint8_t)(255 - cl->height);
            uint8_t col[3];
            col[0] = col[1] = col[2] = grey;
            for (j = 0; j < W4_PX; j++)
                for (i = 0; i < W4_PX; i++)
                    w4_px(&im, ix * W4_PX + i, (g->ny - 1 - iy) * W4_PX + j, col);
        }
    for (k = 0; k < c->field->n_lines; k++) {
        const fl_field_line_t *l = &c->field->lines[k];
        w4_map_px(g, l->x0_mm, l->y0_mm, &u, &v);
        w4_map_px(g, l->x1_mm, l->y1_mm, &u1, &v1);
        w4_line(&im, u, v, u1, v1, line_c, 1);
    }
    w4_map_px(g, 0, 0, &u, &v);
    w4_ring(&im, u, v, c->field->circle_radius_mm * (double)W4_PX / FL_FUZZY_CELL_MM, line_c);
    for (k = 0; k < 2; k++) {
        double gx = (k ? 1 : -1) * c->field->length_mm / 2.0, gw = c->field->goal_width_mm / 2.0;
        const uint8_t *col = c->field->goal_color[k] == FL_COLOR_YELLOW ? yel : sky;
        w4_map_px(g, gx + (k ? 40 : -40), -gw, &u, &v);
        w4_map_px(g, gx + (k ? 40 : -40), gw, &u1, &v1);
        w4_line(&im, u, v, u1, v1, col, 4);
    }
    /* truth: ring and heading line */
    w4_map_px(g, c->o->x_mm, c->o->y_mm, &u, &v);
    h = c->o->heading_mdeg * W4_PI / 180000.0;
    w4_ring(&im, u, v, 7, truth_c);
    w4_ring(&im, u, v, 8, truth_c);
    w4_line(&im, u, v, u + 18 * cos(h), v - 18 * sin(h), truth_c, 2);
    if (s != NULL && !s->est_ignorance) {
        w4_map_px(g, s->est_x_mm, s->est_y_mm, &u, &v);
        w4_triangle(&im, u, v, s->est_heading_deg * W4_PI / 180, 12, est_c, edge_c);
    }
    k = w4_save(&im, caption, path);
    host_image_free(&im);
    return k;
}

/* The frame (figure 6): enlarged, the corner stage's corners (open white,
 * closed black, net-closed yellow squares), its features (C magenta,
 * T-field orange, T-net cyan: a line between the two corners and the
 * letter), nets (a box at the posts' mean foot), the fused observation
 * circled in red.  Features mode: the frame rendered for the picture
 * only, the ideal observations as boxes. */
static int w4_frame_picture(w4_ctx_t *c, const fl_obs_t *fused, const char *caption,
                            const char *path)
{
    static const uint8_t white[3] = {255, 255, 255}, black[3] = {0, 0, 0},
                         yel[3] = {255, 230, 0}, mag[3] = {255, 0, 255}, ora[3] = {255, 150, 0},
                         cya[3] = {0, 230, 230}, red[3] = {255, 30, 30};
    const int S = W4_FRAME_SCALE;
    host_image_t im;
    int u, v, i;
    if (!c->have_frame) {
        if (render_frame(&c->sc, &c->fr) != 0)
            return -1;
        c->have_frame = 1;
    }
    im = host_image_new(c->fr.width * S, c->fr.height * S, 0, 0, 0);
    if (im.rgb == NULL)
        return -1;
    for (v = 0; v < im.height; v++)
        for (u = 0; u < im.width; u++)
            memcpy(im.rgb + 3 * ((size_t)v * (size_t)im.width + (size_t)u),
                   c->fr.rgb + 3 * ((size_t)(v / S) * (size_t)c->fr.width + (size_t)(u / S)), 3);
    if (!c->o->features) {
        const fl_corners_t *cn = c->cn;
        for (i = 0; i < cn->n_corners; i++) {
            const fl_corner_t *k = &cn->corner[i];
            const uint8_t *col = k->label == FL_CORNER_OPEN ? white
                                 : k->label == FL_CORNER_CLOSED ? black : yel;
            w4_box(&im, k->x * S + S / 2, k->y * S + S / 2, 2, col);
        }
        for (i = 0; i < cn->n_features; i++) {
            const fl_cfeat_t *f = &cn->feature[i];
            const uint8_t *col = f->type == FL_CFEAT_C ? mag
                                 : f->type == FL_CFEAT_T_FIELD ? ora
                                 : f->type == FL_CFEAT_T_NET ? cya : yel;
            double fu = f->u_q4 * S / 16.0 + S / 2.0, fv = f->v_q4 * S / 16.0 + S / 2.0;
            const char *lab = f->type == FL_CFEAT_C ? "C"
                              : f->type == FL_CFEAT_T_FIELD ? "T"
                              : f->type == FL_CFEAT_T_NET ? "TN"
                              : f->type == FL_CFEAT_NET_YELLOW ? "NET Y" : "NET B";
            if (f->a >= 0 && f->b >= 0)
                w4_line(&im, cn->corner[f->a].x * S + S / 2.0, cn->corner[f->a].y * S + S / 2.0,
                        cn->corner[f->b].x * S + S / 2.0, cn->corner[f->b].y * S + S / 2.0, col, 1);
            else
                w4_box(&im, fu, fv, 6, col);
            {
                int lu = (int)fu + 6, lv = (int)fv - 12;
                if (lu + font_text_width(lab, 1) >= im.width)
                    lu = (int)fu - 6 - font_text_width(lab, 1);
                font_draw(&im, lu, lv < 0 ? 0 : lv, lab, col, 1);
            }
        }
    } else {
        for (i = 0; i < c->obs.n; i++) {
            const fl_obs_t *ob = &c->obs.obs[i];
            w4_box(&im, ob->u_q4 * S / 16.0 + S / 2.0, ob->v_q4 * S / 16.0 + S / 2.0, 4,
                   ob->kind == FL_LM_CORNER_C ? mag : ob->kind == FL_LM_NET ? yel : ora);
        }
    }
    if (fused != NULL && fused->u_q4 >= 0) {
        double fu = fused->u_q4 * S / 16.0 + S / 2.0, fv = fused->v_q4 * S / 16.0 + S / 2.0;
        w4_ring(&im, fu, fv, 11, red);
        w4_ring(&im, fu, fv, 12, red);
    }
    i = w4_save(&im, caption, path);
    host_image_free(&im);
    return i;
}

/* ---- the walk -------------------------------------------------------------- */

static void w4_print_step(FILE *out, const w4_step_t *s, int n)
{
    if (out == NULL)
        return;
    fprintf(out,
            "%d %-11s %5d %7.1f %5d %6.0f %5d %5d %6.1f %6.0f %6.1f %5.2f %6.2f %6.2f %5.2f\n", n,
            w4_kind_name(&s->obs), s->frame, s->yaw_mdeg / 1000.0, (int)s->obs.range_mm,
            w4_deg(s->obs.bearing), (int)s->est_x_mm, (int)s->est_y_mm, s->est_heading_deg,
            s->err_mm, s->err_deg, s->reliability, s->top_area_m2, s->half_area_m2, s->p_true);
}

static int w4_fuse(w4_ctx_t *c, w4_result_t *res, const fl_obs_t *ob, int frame,
                   int32_t yaw_mdeg)
{
    w4_step_t *s = &res->step[res->n_steps];
    char cap[512], path[600];
    memset(s, 0, sizeof *s);
    s->obs = *ob;
    s->frame = frame;
    s->yaw_mdeg = yaw_mdeg;
    s->map_index = w4_map_match(c, ob, &s->map_err_mm);
    if (!fl_fuzzy_update_one(c->g, ob)) {
        if (c->out)
            fprintf(c->out, "# frame %d: the grid ignored a %s observation\n", frame,
                    w4_kind_name(ob));
        return 0;
    }
    w4_mark_fused(c, ob);
    if (ob->kind == FL_LM_NET)
        res->nets++;
    else
        res->cs++;
    w4_measure(c, s);
    res->n_steps++;
    w4_print_step(c->out, s, res->n_steps);
    if (c->out && s->map_index >= 0) {
        const fl_landmark_t *t = &c->field->features[s->map_index];
        double e_any;
        int any = w4_map_match_any(c, ob, 1, &e_any);
        fprintf(c->out, "#   seen from the truth: %.0f mm from the map's nearest %s (%d, %d)",
                s->map_err_mm, w4_kind_name(ob), (int)t->x_mm, (int)t->y_mm);
        if (any >= 0 && any != s->map_index)
            fprintf(c->out, ", %.0f mm from its nearest feature, a %s (%d, %d)", e_any,
                    w4_lm_name(&c->field->features[any]), (int)c->field->features[any].x_mm,
                    (int)c->field->features[any].y_mm);
        fprintf(c->out, "; the cells >= 1/2 lie %.0f..%.0f mm from the yellow net (the truth "
                "%.0f mm)\n", s->net_r_min_mm, s->net_r_max_mm, s->net_r_true_mm);
    }
    if (c->o->out_dir != NULL) {
        snprintf(cap, sizeof cap,
                 "seed 004 walk, step %d: %s at %d mm, %.1f deg (frame %d, head yaw %.0f deg)\n"
                 "estimate (%d, %d) %.0f deg: error %.0f mm %.1f deg, reliability %.2f, "
                 "possibility at the truth %.2f\n"
                 "darker = more possible; blue ring: truth; red triangle: estimate",
                 res->n_steps, w4_kind_name(ob), (int)ob->range_mm, w4_deg(ob->bearing), frame,
                 yaw_mdeg / 1000.0, (int)s->est_x_mm, (int)s->est_y_mm, s->est_heading_deg,
                 s->err_mm, s->err_deg, s->reliability, s->p_true);
        snprintf(path, sizeof path, "%s/walk004_step%d_belief.png", c->o->out_dir, res->n_steps);
        if (w4_belief_picture(c, s, cap, path) == 0)
            snprintf(s->picture[0], sizeof s->picture[0], "%s", path);
        snprintf(cap, sizeof cap,
                 "frame %d, head yaw %.0f deg: %s\n"
                 "corners: open white, closed black, net-closed yellow; features: C magenta, "
                 "T orange, T-net cyan; red ring: fused",
                 frame, yaw_mdeg / 1000.0,
                 c->o->features ? "ideal observations (boxes, colours as features below)"
                                : "the corner stage's detections");
        snprintf(path, sizeof path, "%s/walk004_step%d_frame.png", c->o->out_dir, res->n_steps);
        if (w4_frame_picture(c, ob, cap, path) == 0)
            snprintf(s->picture[1], sizeof s->picture[1], "%s", path);
        if (c->out)
            fprintf(c->out, "#   pictures %s %s\n", s->picture[0], s->picture[1]);
    }
    return 1;
}

/* --verbose, frames mode: the corner stage's features with their two
 * corners (label, white / window pixels, net samples): why a pair got its
 * type. */
static void w4_print_corners(FILE *out, const fl_corners_t *cn)
{
    static const char *const type[6] = {"?", "C", "T-field", "T-net", "net-yellow", "net-skyblue"};
    static const char *const label[4] = {"?", "open", "closed", "net-closed"};
    int i, k;
    for (i = 0; i < cn->n_features; i++) {
        const fl_cfeat_t *f = &cn->feature[i];
        fprintf(out, "#   %s at (%.1f, %.1f) px, %d mm", type[f->type < 6 ? f->type : 0],
                f->u_q4 / 16.0, f->v_q4 / 16.0, (int)f->range_mm);
        for (k = 0; k < 2; k++) {
            int j = k ? f->b : f->a;
            if (j < 0 || j >= cn->n_corners)
                continue;
            fprintf(out, "; corner (%d, %d) %s white %d/%d net %d", cn->corner[j].x,
                    cn->corner[j].y, label[cn->corner[j].label < 4 ? cn->corner[j].label : 0],
                    cn->corner[j].n_white, cn->corner[j].n_area, cn->corner[j].n_net);
        }
        fprintf(out, "\n");
    }
}

static int w4_setup(w4_ctx_t *c, const w4_opts_t *o, FILE *out)
{
    fl_fuzzy_params_t fp;
    fl_corners_params_t cp;
    memset(c, 0, sizeof *c);
    c->o = o;
    c->out = out;
    c->field = fl_field_find("aibo2004");
    c->model = fl_camera_model_find("aibo-ers7");
    if (c->field == NULL || c->model == NULL || o->yaw_step_mdeg <= 0) {
        fprintf(stderr,
                "fieldloc walk004: no aibo2004 field or aibo-ers7 camera, or a bad scan step\n");
        return -1;
    }
    c->g = malloc(sizeof *c->g);
    c->cn = malloc(sizeof *c->cn);
    if (c->g == NULL || c->cn == NULL || det_ctx_init(&c->det) != 0) {
        fprintf(stderr, "fieldloc walk004: out of memory\n");
        return -1;
    }
    c->det_ready = 1;
    fl_fuzzy_params_vision(&fp, true);
    fl_corners_params_default(&cp);
    if (fl_fuzzy_init(c->g, c->field, &fp) != FL_OK || fl_corners_init(c->cn, &cp) != FL_OK) {
        fprintf(stderr, "fieldloc walk004: cannot set up the grid or the corner stage\n");
        return -1;
    }
    return 0;
}

static void w4_free(w4_ctx_t *c)
{
    if (c->have_frame)
        render_frame_free(&c->fr);
    c->have_frame = 0;
    if (c->det_ready)
        det_ctx_free(&c->det);
    free(c->g);
    free(c->cn);
}

int w4_run(const w4_opts_t *o, FILE *out, w4_result_t *res)
{
    w4_ctx_t c;
    int frame, n_frames, i, rc = 0;
    int32_t yaw;
    memset(res, 0, sizeof *res);
    if (w4_setup(&c, o, out) != 0) {
        w4_free(&c);
        return -1;
    }
    n_frames = 1 + (o->yaw_left_mdeg - o->yaw_right_mdeg) / o->yaw_step_mdeg + 1;
    if (n_frames > W4_MAX_FRAMES)
        n_frames = W4_MAX_FRAMES;
    if (out) {
        fprintf(out, "# walk004: seed 004 section 5 on aibo2004, camera aibo-ers7, %s\n",
                o->features ? "ideal observations of the map features in view (--features)"
                            : "rendered frames through the corner stage (nets from the posts)");
        fprintf(out, "# true pose (%d, %d) %.1f deg: own (sky-blue) goal box x -2100..-1450, "
                "y -500..500, facing the yellow net at (2100, 0)\n",
                (int)o->x_mm, (int)o->y_mm, o->heading_mdeg / 1000.0);
        fprintf(out, "# scan: head straight ahead, then yaw %.0f to %.0f deg in %.0f deg steps, "
                "pitch %.0f deg; G0 = 1 everywhere (fuzzy grid %dx%d cells of %d mm, vision "
                "params, lowres)\n",
                o->yaw_left_mdeg / 1000.0, o->yaw_right_mdeg / 1000.0, o->yaw_step_mdeg / 1000.0,
                o->pitch_mdeg / 1000.0, c.g->nx, c.g->ny, FL_FUZZY_CELL_MM);
        fprintf(out, "# fused: a net of a new colour, a C more than %d mm from the C's fused "
                "before; stops after a net and two C's\n", W4_SAME_C_MM);
        fprintf(out, "# step kind frame yaw_deg range_mm bearing_deg est_x est_y est_h_deg "
                "err_mm err_deg reliab top_m2 half_m2 p_true\n");
    }
    {
        w4_step_t s0;
        memset(&s0, 0, sizeof s0);
        w4_measure(&c, &s0);
        res->ignorance_area_m2 = s0.top_area_m2;
        if (out)
            fprintf(out, "0 ignorance       -       -     -      -  %5d %5d %6.1f %6.0f %6.1f %5.2f "
                    "%6.2f %6.2f %5.2f\n",
                    (int)s0.est_x_mm, (int)s0.est_y_mm, s0.est_heading_deg, s0.err_mm,
                    s0.err_deg, s0.reliability, s0.top_area_m2, s0.half_area_m2, s0.p_true);
        if (o->out_dir != NULL) {
            char path[600];
            snprintf(path, sizeof path, "%s/walk004_step0_belief.png", o->out_dir);
            if (w4_belief_picture(&c, &s0, "seed 004 walk, step 0: total ignorance (G0 = 1 "
                                  "everywhere)\nblue ring: truth", path) == 0)
                snprintf(res->ignorance_picture, sizeof res->ignorance_picture, "%s", path);
        }
    }
    for (frame = 0; frame < n_frames && (!res->complete || o->whole_scan); frame++) {
        yaw = frame == 0 ? 0 : o->yaw_left_mdeg - (frame - 1) * o->yaw_step_mdeg;
        w4_scene(&c, frame, yaw);
        if (c.have_frame)
            render_frame_free(&c.fr);
        c.have_frame = 0;
        if (o->features) {
            w4_ideal(&c, &c.obs);
        } else if (w4_vision(&c) != 0) {
            fprintf(stderr, "fieldloc walk004: frame %d: rendering or vision failed\n", frame);
            rc = -1;
            break;
        } else {
            w4_truth_score(&c, res);
        }
        res->frames++;
        w4_sort(&c.obs);
        if (out && o->verbose) {
            fprintf(out, "# frame %d yaw %.0f: %d observations", frame, yaw / 1000.0, c.obs.n);
            for (i = 0; i < c.obs.n; i++) {
                double err;
                int m = w4_map_match(&c, &c.obs.obs[i], &err);
                fprintf(out, "; %s %d mm %.1f deg (map %d, %.0f mm off)",
                        w4_kind_name(&c.obs.obs[i]), (int)c.obs.obs[i].range_mm,
                        w4_deg(c.obs.obs[i].bearing), m, err);
            }
            fprintf(out, "\n");
            if (!o->features)
                w4_print_corners(out, c.cn);
        }
        if (o->verbose && o->out_dir != NULL) {
            char path[600], cap[128];
            snprintf(path, sizeof path, "%s/walk004_frame%02d.png", o->out_dir, frame);
            snprintf(cap, sizeof cap, "frame %d, head yaw %.0f deg", frame, yaw / 1000.0);
            (void)w4_frame_picture(&c, NULL, cap, path);
        }
        for (i = 0; i < c.obs.n; i++) {
            const fl_obs_t *ob = &c.obs.obs[i];
            /* counted always; fused while the walk is not complete */
            if (!w4_is_new(&c, ob, res) || res->complete || res->n_steps >= W4_MAX_STEPS)
                continue;
            (void)w4_fuse(&c, res, ob, frame, yaw);
            res->complete = res->nets >= 1 && res->cs >= 2;
        }
    }
    if (out) {
        fprintf(out, "# %d frames looked at; fused %d net(s) and %d C(s)%s; %d C observations "
                "in these frames, %d T-field/T-net observations (not fused)\n",
                res->frames, res->nets, res->cs,
                res->complete ? "" : " (the scan ended before a net and two C's)", res->seen_c,
                res->seen_other);
        if (!o->features)
            fprintf(out, "# the map's C's in view %d times (C x frame, within %d mm): the corner "
                    "stage reported %d as a C, %d as a T-field, %d as a T-net, missed %d\n",
                    res->truth_c_views, W4_CORNER_RANGE_MM, res->truth_c_as_c,
                    res->truth_c_as_other[0], res->truth_c_as_other[1], res->truth_c_missed);
        if (res->ignorance_picture[0])
            fprintf(out, "# pictures in %s: walk004_step0_belief.png (ignorance), "
                    "walk004_stepN_belief.png and walk004_stepN_frame.png per step\n", o->out_dir);
    }
    w4_free(&c);
    return rc;
}

void w4_print_summary(FILE *out, const w4_opts_t *o, const w4_result_t *res)
{
    const w4_step_t *s = res->n_steps > 0 ? &res->step[res->n_steps - 1] : NULL;
    (void)o;
    fprintf(out, "walk004_error_mm %.0f\n", s ? s->err_mm : -1.0);
    fprintf(out, "walk004_heading_err_deg %.1f\n", s ? s->err_deg : -1.0);
    fprintf(out, "walk004_observations %d\n", res->n_steps);
    fprintf(out, "walk004_reliability %.2f\n", s ? s->reliability : 0.0);
    fprintf(out, "walk004_p_true %.2f\n", s ? s->p_true : 1.0);
}
