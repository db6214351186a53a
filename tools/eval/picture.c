/*
 * tools/eval/picture.c - belief-grid and frame pictures (picture.h).
 *
 * Drawing is plain RGB888 with clipped pixel writes: lines by uniform
 * stepping (one pixel per step of the longer axis), rings by angle
 * stepping.  Cost: one pass over the cells plus a few hundred line pixels
 * per cell tick.
 */
#include "eval/picture.h"
#include "io/font.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PIC_PI 3.14159265358979323846

static void pic_px(host_image_t *im, int u, int v, const uint8_t *c)
{
    if (u < 0 || v < 0 || u >= im->width || v >= im->height)
        return;
    memcpy(im->rgb + 3 * ((size_t)v * (size_t)im->width + (size_t)u), c, 3);
}

static void pic_line(host_image_t *im, double u0, double v0, double u1, double v1,
                     const uint8_t *c, int dotted)
{
    double du = u1 - u0, dv = v1 - v0, n = fmax(fabs(du), fabs(dv));
    int k, steps = (int)ceil(n);
    if (!isfinite(n))
        return;
    if (steps > 16384)
        steps = 16384;
    for (k = 0; k <= steps; k++) {
        double t = steps ? (double)k / steps : 0;
        if (dotted && (k & 2))
            continue;
        pic_px(im, (int)lround(u0 + t * du), (int)lround(v0 + t * dv), c);
    }
}

static void pic_ring(host_image_t *im, double u, double v, double r, const uint8_t *c)
{
    int k, n = (int)(2 * PIC_PI * r) + 8;
    for (k = 0; k < n; k++) {
        double a = 2 * PIC_PI * k / n;
        pic_px(im, (int)lround(u + r * cos(a)), (int)lround(v + r * sin(a)), c);
    }
}

static void pic_square(host_image_t *im, double u, double v, int r, const uint8_t *fill,
                       const uint8_t *edge)
{
    int i, j, cu = (int)lround(u), cv = (int)lround(v);
    for (j = -r; j <= r; j++)
        for (i = -r; i <= r; i++)
            pic_px(im, cu + i, cv + j, (abs(i) == r || abs(j) == r) ? edge : fill);
}

/* Height (0..1) -> color: dark purple, red, orange, pale yellow. */
static void pic_ramp(double h, uint8_t *c)
{
    static const double stop[5][3] = {
        {40, 10, 70}, {130, 20, 110}, {220, 60, 40}, {250, 160, 30}, {255, 250, 170}};
    double x = h < 0 ? 0 : h > 1 ? 4 : h * 4;
    int i = (int)x, k;
    double f;
    if (i > 3)
        i = 3;
    f = x - i;
    for (k = 0; k < 3; k++)
        c[k] = (uint8_t)lround(stop[i][k] + f * (stop[i + 1][k] - stop[i][k]));
}

/* The picture's grid: the localizer's own, or, for a localizer whose
 * belief is a set of samples, the geometry the fuzzy grid would have on
 * the field's carpet (FL_FUZZY_CELL_MM cells, centred like fuzzy.c's), so
 * that both pictures of one field have the same size and scale.  *samples:
 * 1 for the latter.  0 on success. */
static int pic_geometry(const fl_localizer_t *loc, const void *state, const fl_field_t *field,
                        fl_loc_grid_t *g, int *samples)
{
    int32_t hx, hy, nx, ny;
    *samples = 0;
    memset(g, 0, sizeof *g);
    if (loc == NULL || state == NULL)
        return -1;
    if (loc->belief_grid != NULL && loc->belief_grid(state, g))
        return g->nx > 0 && g->ny > 0 ? 0 : -1;
    if (loc->belief_samples == NULL || loc->belief_sample == NULL || field == NULL ||
        loc->belief_samples(state) == 0)
        return -1;
    hx = fl_field_carpet_half_x_mm(field);
    hy = fl_field_carpet_half_y_mm(field);
    if (hx <= 0 || hy <= 0 || hx > 100000 || hy > 100000)
        return -1;
    nx = (2 * hx + FL_FUZZY_CELL_MM - 1) / FL_FUZZY_CELL_MM;
    ny = (2 * hy + FL_FUZZY_CELL_MM - 1) / FL_FUZZY_CELL_MM;
    g->nx = (uint16_t)nx;
    g->ny = (uint16_t)ny;
    g->x0_mm = -((nx * FL_FUZZY_CELL_MM) / 2);
    g->y0_mm = -((ny * FL_FUZZY_CELL_MM) / 2);
    g->cell_mm = FL_FUZZY_CELL_MM;
    *samples = 1;
    return 0;
}

static int pic_scale(int px_per_cell)
{
    int s = px_per_cell <= 0 ? PIC_DEFAULT_PX_PER_CELL : px_per_cell;
    return s < 2 ? 2 : s > 32 ? 32 : s;
}

int pic_belief_size_on(const fl_localizer_t *loc, const void *state, const fl_field_t *field,
                       int px_per_cell, int *width, int *height)
{
    int s = pic_scale(px_per_cell), samples;
    fl_loc_grid_t g;
    if (pic_geometry(loc, state, field, &g, &samples) != 0)
        return -1;
    if (width)
        *width = g.nx * s;
    if (height)
        *height = g.ny * s;
    return 0;
}

int pic_belief_size(const fl_localizer_t *loc, const void *state, int px_per_cell,
                    int *width, int *height)
{
    return pic_belief_size_on(loc, state, NULL, px_per_cell, width, height);
}

unsigned pic_belief_legend(const fl_localizer_t *loc, const void *state)
{
    fl_loc_grid_t g;
    if (loc == NULL || state == NULL || (loc->belief_grid != NULL && loc->belief_grid(state, &g)))
        return PIC_LEGEND_BELIEF;
    return loc->belief_samples != NULL && loc->belief_sample != NULL &&
                   loc->belief_samples(state) > 0
               ? PIC_LEGEND_PARTICLES
               : PIC_LEGEND_BELIEF;
}

typedef struct {
    double x0, y0, s, h;   /* grid corner (mm), px per mm, picture height */
} pic_map_t;

static void pic_to_px(const pic_map_t *m, double x, double y, double *u, double *v)
{
    *u = (x - m->x0) * m->s - 0.5;
    *v = m->h - (y - m->y0) * m->s - 0.5;
}

static const uint8_t pic_carpet[3] = {18, 62, 28}, pic_white[3] = {235, 235, 235},
                     pic_black[3] = {0, 0, 0};

/* Field lines, centre circle, posts/beacons and marks. */
static void pic_draw_field(host_image_t *out, const pic_map_t *m, const fl_field_t *f, int s)
{
    int i;
    for (i = 0; i < f->n_lines; i++) {
        double a, b, c2, d;
        pic_to_px(m, f->lines[i].x0_mm, f->lines[i].y0_mm, &a, &b);
        pic_to_px(m, f->lines[i].x1_mm, f->lines[i].y1_mm, &c2, &d);
        pic_line(out, a, b, c2, d, pic_white, 0);
    }
    if (f->circle_radius_mm > 0) {
        double cu, cv;
        pic_to_px(m, 0, 0, &cu, &cv);
        pic_ring(out, cu, cv, f->circle_radius_mm * m->s, pic_white);
    }
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *lm = &f->landmarks[i];
        double a, b;
        if (lm->kind != FL_LM_POST && lm->kind != FL_LM_BEACON && lm->kind != FL_LM_PENALTY_MARK &&
            lm->kind != FL_LM_CENTRE_MARK)
            continue;
        pic_to_px(m, lm->x_mm, lm->y_mm, &a, &b);
        if (lm->kind == FL_LM_POST || lm->kind == FL_LM_BEACON) {
            static const uint8_t yellow[3] = {255, 220, 0}, sky[3] = {80, 180, 255},
                                 pink[3] = {255, 120, 200};
            const uint8_t *pc = lm->color == FL_COLOR_SKYBLUE ? sky
                              : lm->color == FL_COLOR_YELLOW ? yellow
                              : lm->color == FL_COLOR_WHITE ? pic_white : pink;
            pic_square(out, a, b, s / 3 > 1 ? s / 3 : 1, pc, pic_black);
        } else {
            pic_line(out, a - 2, b, a + 2, b, pic_white, 0);
            pic_line(out, a, b - 2, a, b + 2, pic_white, 0);
        }
    }
}

/* The observations seen from the estimate, the truth and the estimate. */
static void pic_draw_marks(host_image_t *out, const pic_map_t *m, int s, const pic_pose_t *truth,
                           const fl_loc_estimate_t *est, const fl_obs_list_t *obs)
{
    static const uint8_t cyan[3] = {0, 230, 255}, magenta[3] = {255, 40, 255};
    int i;
    if (obs != NULL && est != NULL) {
        double eh = est->heading * (PIC_PI / 32768.0);
        for (i = 0; i < obs->n; i++) {
            const fl_obs_t *o = &obs->obs[i];
            double b = eh + o->bearing * (PIC_PI / 32768.0), a, c2;
            pic_to_px(m, est->x_mm + o->range_mm * cos(b), est->y_mm + o->range_mm * sin(b), &a,
                      &c2);
            pic_square(out, a, c2, s >= 6 ? 3 : 2, pic_white, pic_black);
        }
    }
    if (truth != NULL) {
        double a, b, h = truth->heading_deg * (PIC_PI / 180.0);
        pic_to_px(m, truth->x_mm, truth->y_mm, &a, &b);
        pic_ring(out, a, b, 1.6 * s, cyan);
        pic_ring(out, a, b, 1.6 * s + 1, cyan);
        pic_line(out, a, b, a + 3.5 * s * cos(h), b - 3.5 * s * sin(h), cyan, 0);
    }
    if (est != NULL) {
        double a, b, h = est->heading * (PIC_PI / 32768.0);
        double L = (2.0 + 2.5 * est->reliability_q16 / 65536.0) * s;
        pic_to_px(m, est->x_mm, est->y_mm, &a, &b);
        pic_ring(out, a, b, 1.1 * s, magenta);
        pic_ring(out, a, b, 1.1 * s + 1, magenta);
        pic_line(out, a, b, a + L * cos(h), b - L * sin(h), magenta, 0);
        pic_line(out, a + 1, b, a + 1 + L * cos(h), b - L * sin(h), magenta, 0);
    }
}

/* Color of a sample of relative weight w (0..1): in the estimate's cluster
 * the grid's ramp from its second stop up (never darker than dark
 * magenta, so a light particle still shows on the carpet), elsewhere a
 * ramp of blues. */
void pic_particle_color(double w, int in_mode, uint8_t *c)
{
    static const double lo[3] = {50, 70, 115}, hi[3] = {150, 195, 255};
    int k;
    w = w < 0 ? 0 : w > 1 ? 1 : w;
    if (in_mode) {
        pic_ramp(0.25 + 0.75 * w, c);
        return;
    }
    for (k = 0; k < 3; k++)
        c[k] = (uint8_t)lround(lo[k] + w * (hi[k] - lo[k]));
}

static int pic_sample_cmp(const void *pa, const void *pb)
{
    const fl_loc_sample_t *a = pa, *b = pb;
    if (a->in_mode != b->in_mode)
        return a->in_mode ? 1 : -1;
    return (a->weight_q16 > b->weight_q16) - (a->weight_q16 < b->weight_q16);
}

/* The 2-sd ellipse of a position covariance (sd_x, sd_y, cov_xy) at
 * (x, y), from its Cholesky factor (l11, 0; l21, l22); dotted: every
 * other segment. */
static void pic_ellipse2(host_image_t *out, const pic_map_t *m, int32_t x, int32_t y,
                         double sd_x, double sd_y, double cov_xy, const uint8_t *col,
                         int dotted)
{
    double l11 = sd_x, l21 = cov_xy / l11, r = sd_y * sd_y - l21 * l21, l22 = r > 0 ? sqrt(r) : 0;
    int j, steps = 96;
    for (j = 0; j < steps; j++) {
        double t = 2 * PIC_PI * j / steps, c = 2 * cos(t), d = 2 * sin(t), u0, v0, u1, v1;
        double t1 = 2 * PIC_PI * (j + 1) / steps, c1 = 2 * cos(t1), d1 = 2 * sin(t1);
        if (dotted && (j & 1))
            continue;
        pic_to_px(m, x + l11 * c, y + l21 * c + l22 * d, &u0, &v0);
        pic_to_px(m, x + l11 * c1, y + l21 * c1 + l22 * d1, &u1, &v1);
        pic_line(out, u0, v0, u1, v1, col, 0);
    }
}

/* Samples as dots with a heading tick, the lighter first (the cluster's
 * and the heavy ones stay on top), then the cluster's spread: the
 * estimate's 2-sd ellipse (from sd_x, sd_y and cov_xy) dotted; a sample
 * with a spread of its own (upf) is drawn with its 2-sd ellipse. */
static int pic_draw_samples(host_image_t *out, const pic_map_t *m, int s,
                            const fl_localizer_t *loc, const void *state,
                            const fl_loc_estimate_t *est)
{
    static const uint8_t lime[3] = {150, 255, 60};
    uint16_t n = loc->belief_samples(state), i, k = 0;
    fl_loc_sample_t *sp = malloc((size_t)n * sizeof *sp);
    if (sp == NULL)
        return -1;
    for (i = 0; i < n; i++)
        if (loc->belief_sample(state, i, &sp[k]))
            k++;
    qsort(sp, k, sizeof *sp, pic_sample_cmp);
    for (i = 0; i < k; i++) {
        /* 0.9 cell at the field's scale; shorter (in mm) when magnified,
         * or a cluster's ticks hide each other */
        double a, b, h = sp[i].heading * (PIC_PI / 32768.0),
                  L = s <= PIC_DEFAULT_PX_PER_CELL ? 0.9 * s
                                                   : 0.9 * PIC_DEFAULT_PX_PER_CELL +
                                                         0.15 * (s - PIC_DEFAULT_PX_PER_CELL);
        uint8_t col[3];
        pic_particle_color(sp[i].weight_q16 / 65535.0, sp[i].in_mode, col);
        pic_to_px(m, sp[i].x_mm, sp[i].y_mm, &a, &b);
        pic_line(out, a, b, a + L * cos(h), b - L * sin(h), col, 0);
        pic_square(out, a, b, s >= 24 ? 2 : s >= 6 ? 1 : 0, col, col);
        /* a sample that carries a Gaussian (upf): its 2-sd ellipse */
        if (sp[i].sd_x_mm > 0 && sp[i].sd_y_mm > 0)
            pic_ellipse2(out, m, sp[i].x_mm, sp[i].y_mm, sp[i].sd_x_mm, sp[i].sd_y_mm,
                         sp[i].cov_xy_mm2, col, 0);
    }
    free(sp);
    if (est != NULL && est->state != FL_LOC_LOST && est->sd_x_mm > 0 && est->sd_y_mm > 0) {
        pic_ellipse2(out, m, est->x_mm, est->y_mm, est->sd_x_mm, est->sd_y_mm,
                     est->cov_xy_mm2, lime, 1);
    }
    return 0;
}

int pic_belief(const fl_localizer_t *loc, const void *state, const fl_field_t *f, int px_per_cell,
               const pic_pose_t *truth, const fl_loc_estimate_t *est,
               const fl_obs_list_t *obs, host_image_t *out)
{
    int W, H, s, ix, iy, u, v, samples;
    pic_map_t m;
    fl_loc_grid_t gr;
    const fl_loc_grid_t *g = &gr;
    memset(out, 0, sizeof *out);
    if (f == NULL || pic_geometry(loc, state, f, &gr, &samples) != 0 ||
        (!samples && loc->belief_cell == NULL))
        return -1;
    s = pic_scale(px_per_cell);
    W = g->nx * s;
    H = g->ny * s;
    *out = host_image_new(W, H, pic_carpet[0], pic_carpet[1], pic_carpet[2]);
    if (out->rgb == NULL)
        return -1;
    m.x0 = g->x0_mm;
    m.y0 = g->y0_mm;
    m.s = (double)s / g->cell_mm;
    m.h = H;
    if (samples) {
        pic_draw_field(out, &m, f, s);
        if (pic_draw_samples(out, &m, s, loc, state, est) != 0) {
            host_image_free(out);
            return -1;
        }
        pic_draw_marks(out, &m, s, truth, est, obs);
        return 0;
    }
    /* cells */
    for (iy = 0; iy < g->ny; iy++) {
        for (ix = 0; ix < g->nx; ix++) {
            fl_loc_cell_t cl;
            const fl_loc_cell_t *c = &cl;
            uint8_t col[3];
            int v0 = (g->ny - 1 - iy) * s, u0 = ix * s;
            if (!loc->belief_cell(state, ix, iy, &cl) || c->height_q8 == 0)
                continue;
            pic_ramp(c->height_q8 / 255.0, col);
            for (v = 0; v < s; v++)
                for (u = 0; u < s; u++)
                    pic_px(out, u0 + u, v0 + v, col);
        }
    }
    pic_draw_field(out, &m, f, s);
    /* heading ticks */
    for (iy = 0; iy < g->ny; iy++) {
        for (ix = 0; ix < g->nx; ix++) {
            fl_loc_cell_t cl;
            const fl_loc_cell_t *c = &cl;
            double cu = ix * s + (s - 1) / 2.0, cv = (g->ny - 1 - iy) * s + (s - 1) / 2.0;
            double a, L = 0.45 * s;
            if (!loc->belief_cell(state, ix, iy, &cl) || c->height_q8 < 64 || c->spread >= 8192)
                continue;
            a = c->heading * (PIC_PI / 32768.0);
            pic_line(out, cu, cv, cu + L * cos(a), cv - L * sin(a), pic_black, 0);
        }
    }
    pic_draw_marks(out, &m, s, truth, est, obs);
    return 0;
}

int pic_belief_zoom(const fl_localizer_t *loc, const void *state, const fl_field_t *f,
                    int32_t cx_mm, int32_t cy_mm, int px_per_cell, int size_px,
                    const pic_pose_t *truth, const fl_loc_estimate_t *est,
                    const fl_obs_list_t *obs, host_image_t *out)
{
    static const uint8_t frame_col[3] = {150, 150, 150};
    int s, samples, i;
    pic_map_t m;
    fl_loc_grid_t g;
    char label[32];
    memset(out, 0, sizeof *out);
    if (f == NULL || pic_geometry(loc, state, f, &g, &samples) != 0 || !samples ||
        size_px < 32 || size_px > 4096)
        return -1;
    s = px_per_cell <= 0 ? 4 * PIC_DEFAULT_PX_PER_CELL : px_per_cell < 2 ? 2 : px_per_cell > 128 ? 128 : px_per_cell;
    *out = host_image_new(size_px, size_px, pic_carpet[0], pic_carpet[1], pic_carpet[2]);
    if (out->rgb == NULL)
        return -1;
    m.s = (double)s / g.cell_mm;
    m.x0 = cx_mm - size_px / 2.0 / m.s;
    m.y0 = cy_mm - size_px / 2.0 / m.s;
    m.h = size_px;
    pic_draw_field(out, &m, f, s);
    if (pic_draw_samples(out, &m, s, loc, state, est) != 0) {
        host_image_free(out);
        return -1;
    }
    pic_draw_marks(out, &m, s, truth, est, obs);
    for (i = 0; i < size_px; i++) {
        pic_px(out, i, 0, frame_col);
        pic_px(out, i, size_px - 1, frame_col);
        pic_px(out, 0, i, frame_col);
        pic_px(out, size_px - 1, i, frame_col);
    }
    snprintf(label, sizeof label, "x%g: %.1f m wide", (double)s / PIC_DEFAULT_PX_PER_CELL,
             size_px / m.s / 1000.0);
    font_draw(out, 4, 4, label, frame_col, 1);
    return 0;
}

/* Field point -> pixel of the camera at a robot pose (false when behind). */
static int pic_project(const fl_camera_t *cam, const pic_pose_t *p, double fx, double fy,
                       double *u, double *v)
{
    double h = p->heading_deg * (PIC_PI / 180.0), dx = fx - p->x_mm, dy = fy - p->y_mm;
    fl_point_t gp;
    int32_t uq, vq;
    gp.x_mm = (int32_t)lround(dx * cos(h) + dy * sin(h));
    gp.y_mm = (int32_t)lround(-dx * sin(h) + dy * cos(h));
    if (gp.x_mm < 50 || !fl_camera_ground_to_pixel(cam, gp, &uq, &vq))
        return 0;
    *u = uq / 16.0;
    *v = vq / 16.0;
    return 1;
}

static void pic_project_polyline(host_image_t *im, const fl_camera_t *cam, const pic_pose_t *p,
                                 const double *xs, const double *ys, int n, int scale,
                                 const uint8_t *col)
{
    int k, prev = 0;
    double pu = 0, pv = 0;
    for (k = 0; k < n; k++) {
        double u, v;
        if (pic_project(cam, p, xs[k], ys[k], &u, &v) && fabs(u) < 4000 && fabs(v) < 4000) {
            u = (u + 0.5) * scale - 0.5;
            v = (v + 0.5) * scale - 0.5;
            if (prev)
                pic_line(im, pu, pv, u, v, col, 1);
            pu = u;
            pv = v;
            prev = 1;
        } else {
            prev = 0;
        }
    }
}

int pic_frame(const det_ctx_t *det, const fl_image_t *img, const fl_camera_t *cam,
              const fl_field_t *field, const pic_pose_t *pose, int scale,
              host_image_t *out)
{
    static const uint8_t yellow[3] = {255, 235, 0};
    uint8_t *rgb;
    int W, H, u, v, i;
    memset(out, 0, sizeof *out);
    if (det == NULL || img == NULL || cam == NULL || field == NULL)
        return -1;
    if (scale < 1)
        scale = 1;
    if (scale > 4)
        scale = 4;
    rgb = det_rgb_copy(img);
    if (rgb == NULL)
        return -1;
    W = img->width;
    H = img->height;
    det_draw(det, rgb, W, H, cam, field);
    *out = host_image_new(W * scale, H * scale, 0, 0, 0);
    if (out->rgb == NULL) {
        free(rgb);
        return -1;
    }
    for (v = 0; v < H * scale; v++)
        for (u = 0; u < W * scale; u++)
            memcpy(out->rgb + 3 * ((size_t)v * (size_t)(W * scale) + (size_t)u),
                   rgb + 3 * ((size_t)(v / scale) * (size_t)W + (size_t)(u / scale)), 3);
    free(rgb);
    if (pose != NULL) {
        /* the model seen from the pose: lines sampled every 50 mm */
        for (i = 0; i < field->n_lines; i++) {
            const fl_field_line_t *l = &field->lines[i];
            double len = hypot(l->x1_mm - l->x0_mm, l->y1_mm - l->y0_mm);
            int n = (int)(len / 50) + 2, k;
            double *xs = malloc((size_t)n * 2 * sizeof *xs);
            if (xs == NULL)
                continue;
            for (k = 0; k < n; k++) {
                xs[k] = l->x0_mm + (l->x1_mm - l->x0_mm) * (double)k / (n - 1);
                xs[n + k] = l->y0_mm + (l->y1_mm - l->y0_mm) * (double)k / (n - 1);
            }
            pic_project_polyline(out, cam, pose, xs, xs + n, n, scale, yellow);
            free(xs);
        }
        if (field->circle_radius_mm > 0) {
            double xs[97], ys[97];
            int k;
            for (k = 0; k <= 96; k++) {
                xs[k] = field->circle_radius_mm * cos(2 * PIC_PI * k / 96);
                ys[k] = field->circle_radius_mm * sin(2 * PIC_PI * k / 96);
            }
            pic_project_polyline(out, cam, pose, xs, ys, 97, scale, yellow);
        }
    }
    return 0;
}

int pic_side_by_side(const host_image_t *a, const host_image_t *b, int gap,
                     host_image_t *out)
{
    int W, H, v;
    memset(out, 0, sizeof *out);
    if (a == NULL || b == NULL || a->rgb == NULL || b->rgb == NULL || gap < 0)
        return -1;
    W = a->width + gap + b->width;
    H = a->height > b->height ? a->height : b->height;
    *out = host_image_new(W, H, 40, 40, 40);
    if (out->rgb == NULL)
        return -1;
    for (v = 0; v < a->height; v++)
        memcpy(out->rgb + 3 * (size_t)v * (size_t)W, a->rgb + 3 * (size_t)v * (size_t)a->width,
               3 * (size_t)a->width);
    for (v = 0; v < b->height; v++)
        memcpy(out->rgb + 3 * ((size_t)v * (size_t)W + (size_t)(a->width + gap)),
               b->rgb + 3 * (size_t)v * (size_t)b->width, 3 * (size_t)b->width);
    return 0;
}

int pic_save(const host_image_t *img, const char *base, int png, int *png_written)
{
    char path[1100];
    int rc;
    if (png_written)
        *png_written = 0;
    if (img == NULL || img->rgb == NULL || base == NULL ||
        snprintf(path, sizeof path, "%s.ppm", base) >= (int)sizeof path)
        return -1;
    rc = ppm_write(path, img->rgb, img->width, img->height);
    if (png) {
        snprintf(path, sizeof path, "%s.png", base);
        if (png_write(path, img->rgb, img->width, img->height) == 0 && png_written)
            *png_written = 1;
    }
    return rc == 0 ? 0 : -1;
}
