/*
 * src/vision/corners.c - seed 004's corner detector (corners.h): luma,
 * 3 x 3 binomial smoothing, central-difference gradient, Sojka's
 * gradient-direction variance in integers (doubled angles), non-maximum
 * suppression.  The colour filter, labels and pairing: corners_feat.c.
 *
 * Tables (256 = 1):
 *   cn_wd[i]  exp(-(i / 4)^2 / (2 * 0.75^2)): the weight of a neighbour
 *             whose isoline passes i / 4 px from the candidate (sigma_D
 *             0.75 px, MVTec points_sojka's default); 0 from 2.75 px;
 *   cn_wr[k]  exp(-k / (2 * 2^2)): the weight of a neighbour at squared
 *             distance k (sigma_W 2 px, between a quarter and a half of
 *             the 7 x 7 window as MVTec advises); k <= 32 (window_r 4).
 * Scaling: |g| <= 361 (central difference of 8-bit luma: |gx|, |gy| <=
 * 255); w = |g| * wd * wr >> 8 <= 92416; A = sum w over at most 81
 * neighbours < 7.5e6; the vector sums |sum w c2| < 9.6e8 and their squares
 * in 64 bits; response V * A >> 8 < 7.5e6.
 * Memory: the caller's fl_corners_t; stack < 200 B.
 */
#include "corners_int.h"

#include <string.h>

static const uint8_t cn_wd_tab[12] = { 255, 242, 205, 155, 105, 64, 35, 17, 7, 3, 1, 0 };
static const uint8_t cn_wr_tab[33] = { 255, 226, 199, 176, 155, 137, 121, 107, 94, 83, 73,
                                       65,  57,  50,  44,  39,  35,  31,  27,  24, 21, 19,
                                       17,  15,  13,  11,  10,  9,   8,   7,   6,  5,  5 };

void fl_corners_params_default(fl_corners_params_t *p)
{
    if (!p)
        return;
    memset(p, 0, sizeof *p);
    p->smooth = 1;
    p->min_grad = 12;
    p->window_r = 3;
    p->min_var = 24;
    p->min_app = 4096;
    p->nms_r = 1;
    p->label_r = 2;
    p->label_mm = 40;
    p->min_white = 2;
    p->min_green = 3;
    p->closed_white_pct = 40;
    p->net_r = 30;
    p->net_mm = 450;
    p->min_net = 4;
    p->pair_px = 10;
    p->pair_mm = 75;
    p->min_confidence = 0;
    p->max_range_mm = 4500;
    p->t_first = 0;
    p->min_mid_white = 4;
    p->rel_pct = 60;
    p->label_mode = 3;
    fl_beacon_params_default(&p->net);
}

static bool cn_box_ok(const fl_hsv_box_t *b)
{
    return b->h_lo <= 179 && b->h_hi <= 179 && b->s_lo <= b->s_hi && b->v_lo <= b->v_hi;
}

static bool cn_params_ok(const fl_corners_params_t *p)
{
    return p->smooth >= 0 && p->smooth <= 1 && p->min_grad >= 1 && p->min_grad <= 255 &&
           p->window_r >= 1 && p->window_r <= 4 && p->min_var >= 1 && p->min_var <= 256 &&
           p->min_app >= 0 && p->min_app <= (1 << 24) && p->nms_r >= 1 && p->nms_r <= 8 &&
           p->label_r >= 1 && p->label_r <= 4 && p->label_mm >= 0 && p->label_mm <= 500 && p->min_white >= 0 && p->min_white <= 81 &&
           p->min_green >= 0 && p->min_green <= 81 && p->closed_white_pct >= 1 &&
           p->closed_white_pct <= 100 && p->net_r >= 0 && p->net_r <= 64 && p->net_mm >= 0 &&
           p->net_mm <= 2000 && p->pair_mm >= 0 && p->pair_mm <= 500 && p->min_net >= 1 &&
           p->min_net <= 255 && p->pair_px >= 1 && p->pair_px <= 32 && p->min_confidence >= 0 &&
           p->min_confidence <= 255 && p->max_range_mm >= 0 && p->t_first >= 0 && p->t_first <= 1 && p->min_mid_white >= 0 && p->rel_pct >= 0 && p->rel_pct <= 100 && p->label_mode >= 0 && p->label_mode <= 3 &&
           p->min_mid_white <= 9 && p->max_range_mm <= 20000 && cn_box_ok(&p->net.skyblue) && cn_box_ok(&p->net.yellow) &&
           cn_box_ok(&p->net.pink);
}

fl_status_t fl_corners_init_cfg(fl_corners_t *c, const fl_corners_params_t *p, uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *c has another layout: no write is safe */
    if (!c || !p)
        return FL_ERR_NULL;
    memset(c, 0, sizeof *c);
    fl_corners_params_default(&c->params);
    if (!cn_params_ok(p))
        return FL_ERR_RANGE;
    c->params = *p;
    c->magic = CN_MAGIC;
    return FL_OK;
}

static void cn_clear_results(fl_corners_t *c)
{
    c->width = 0;
    c->height = 0;
    c->n_corners = 0;
    c->n_features = 0;
    c->n_edge = 0;
    c->n_cand = 0;
    c->n_maxima = 0;
    c->rejected_color = 0;
    c->rejected_ground = 0;
    c->cand_dropped = 0;
    c->corners_dropped = 0;
    c->features_dropped = 0;
}

/* Luma of every pixel, then (smooth) the 3 x 3 binomial with the border
 * pixels replicated, into c->sm. */
static void cn_luma(fl_corners_t *c, const fl_image_t *img)
{
    const int32_t w = img->width, h = img->height;
    int32_t x, y;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            uint8_t ycc[3];
            fl_image_ycbcr_at(img, x, y, ycc);
            c->luma[y * w + x] = ycc[0];
        }
    if (!c->params.smooth) {
        memcpy(c->sm, c->luma, (size_t)w * (size_t)h);
        return;
    }
    for (y = 0; y < h; y++) {
        const uint8_t *r0 = c->luma + (y > 0 ? y - 1 : 0) * w;
        const uint8_t *r1 = c->luma + y * w;
        const uint8_t *r2 = c->luma + (y < h - 1 ? y + 1 : y) * w;
        for (x = 0; x < w; x++) {
            const int32_t xl = x > 0 ? x - 1 : 0, xr = x < w - 1 ? x + 1 : x;
            const int32_t s = (r0[xl] + 2 * r0[x] + r0[xr]) + 2 * (r1[xl] + 2 * r1[x] + r1[xr]) +
                              (r2[xl] + 2 * r2[x] + r2[xr]);
            c->sm[y * w + x] = (uint8_t)((s + 8) >> 4);
        }
    }
}

/* Gradient size, unit normal and doubled-angle vector (Q7) of every
 * pixel; 0 on the image border and below min_grad.  Returns the number of
 * edge pixels. */
static int32_t cn_gradient(fl_corners_t *c)
{
    const int32_t w = c->width, h = c->height;
    int32_t x, y, n = 0;
    const size_t np = (size_t)w * (size_t)h;
    memset(c->mag, 0, np * sizeof c->mag[0]);
    memset(c->nx, 0, np);
    memset(c->ny, 0, np);
    memset(c->c2, 0, np);
    memset(c->s2, 0, np);
    for (y = 1; y < h - 1; y++)
        for (x = 1; x < w - 1; x++) {
            const int32_t i = y * w + x;
            const int32_t gx = (int32_t)c->sm[i + 1] - (int32_t)c->sm[i - 1];
            const int32_t gy = (int32_t)c->sm[i + w] - (int32_t)c->sm[i - w];
            const int32_t m2 = gx * gx + gy * gy;
            const int32_t m = (int32_t)fl_isqrt32((uint32_t)m2);
            if (m < c->params.min_grad || m == 0)
                continue;
            c->mag[i] = (uint16_t)m;
            c->nx[i] = (int8_t)(gx * 127 / m);
            c->ny[i] = (int8_t)(gy * 127 / m);
            c->c2[i] = (int8_t)((gx * gx - gy * gy) * 127 / m2);
            c->s2[i] = (int8_t)(2 * gx * gy * 127 / m2);
            n++;
        }
    return n;
}

/* Sojka's measure at (x, y) (an edge pixel window_r inside the image):
 * *var_q8 = V, *app = A. */
static void cn_measure_at(const fl_corners_t *c, int32_t x, int32_t y, int32_t *var_q8, int32_t *app,
                          int32_t *convex)
{
    const int32_t w = c->width, r = c->params.window_r;
    int64_t sx = 0, sy = 0, a = 0, gx = 0, gy = 0, px = 0, py = 0;
    int32_t dx, dy;
    for (dy = -r; dy <= r; dy++)
        for (dx = -r; dx <= r; dx++) {
            const int32_t i = (y + dy) * w + (x + dx);
            int32_t d, wt;
            if (c->mag[i] == 0)
                continue;
            d = (int32_t)c->nx[i] * dx + (int32_t)c->ny[i] * dy;   /* Q7 px */
            if (d < 0)
                d = -d;
            d = (d + 16) >> 5;                                       /* 1/4 px */
            if (d >= 11)
                continue;
            wt = ((int32_t)c->mag[i] * cn_wd_tab[d] * cn_wr_tab[dx * dx + dy * dy]) >> 8;
            a += wt;
            sx += (int64_t)wt * c->c2[i];
            sy += (int64_t)wt * c->s2[i];
            gx += (int64_t)wt * c->nx[i];
            gy += (int64_t)wt * c->ny[i];
            px += (int64_t)wt * dx;
            py += (int64_t)wt * dy;
        }
    *app = (int32_t)a;
    if (convex) {
        /* Sojka's convex / concave: the gradients (dark to bright) point
         * into the bright sector; the edge pixels' centroid lies along
         * the bisector of the sector the edges leave Q in.  Same side:
         * the bright region is convex at Q. */
        const int64_t g = gx / 128, p = px, gq = gy / 128, pq = py;
        const int64_t dot = g * p + gq * pq;
        *convex = dot > 0 ? 1 : dot < 0 ? -1 : 0;
    }
    if (a <= 0) {
        *var_q8 = 0;
        return;
    }
    {
        const uint64_t len = fl_isqrt64((uint64_t)(sx * sx) + (uint64_t)(sy * sy));
        int64_t v = 256 - (int64_t)((len * 256u) / ((uint64_t)a * 127u));
        *var_q8 = (int32_t)(v < 0 ? 0 : v > 256 ? 256 : v);
    }
}

bool fl_corners_measure(const fl_corners_t *c, int32_t x, int32_t y, int32_t *var_q8, int32_t *app)
{
    int32_t r;
    if (var_q8)
        *var_q8 = 0;
    if (app)
        *app = 0;
    if (!c || !var_q8 || !app || c->magic != CN_MAGIC || c->width == 0)
        return false;
    r = c->params.window_r;
    if (x < r || y < r || x >= c->width - r || y >= c->height - r || c->mag[y * c->width + x] == 0)
        return false;
    cn_measure_at(c, x, y, var_q8, app, NULL);
    return true;
}

/* Response of every candidate (0 elsewhere). */
static void cn_responses(fl_corners_t *c)
{
    const int32_t w = c->width, h = c->height, r = c->params.window_r;
    int32_t x, y;
    memset(c->resp, 0, (size_t)w * (size_t)h * sizeof c->resp[0]);
    for (y = r; y < h - r; y++)
        for (x = r; x < w - r; x++) {
            int32_t v, a;
            if (c->mag[y * w + x] == 0)
                continue;
            if (c->n_cand >= FL_CORNERS_MAX_CAND) {
                c->cand_dropped++;
                continue;
            }
            c->n_cand++;
            cn_measure_at(c, x, y, &v, &a, NULL);
            if (v >= c->params.min_var && a >= c->params.min_app)
                c->resp[y * w + x] = (uint32_t)(((int64_t)v * a) >> 8) + 1u;
        }
}

/* (x, y) holds the largest response of its (2 nms_r + 1)^2 square (ties:
 * the first in raster order wins). */
static bool cn_is_max(const fl_corners_t *c, int32_t x, int32_t y)
{
    const int32_t w = c->width, h = c->height, r = c->params.nms_r;
    const uint32_t me = c->resp[y * w + x];
    int32_t dx, dy;
    for (dy = -r; dy <= r; dy++) {
        const int32_t yy = y + dy;
        if (yy < 0 || yy >= h)
            continue;
        for (dx = -r; dx <= r; dx++) {
            const int32_t xx = x + dx;
            uint32_t o;
            if (xx < 0 || xx >= w || (dx == 0 && dy == 0))
                continue;
            o = c->resp[yy * w + xx];
            if (o > me || (o == me && (dy < 0 || (dy == 0 && dx < 0))))
                return false;
        }
    }
    return true;
}

fl_status_t fl_corners_run(fl_corners_t *c, const fl_image_t *img, const fl_color_table_t *colors,
                           const fl_camera_t *camera, const fl_beacon_t *beacons)
{
    fl_status_t st;
    int32_t x, y;
    if (!c)
        return FL_ERR_NULL;
    if (c->magic != CN_MAGIC)
        return FL_ERR_STATE;
    cn_clear_results(c);
    if (!img || !colors)
        return FL_ERR_NULL;
    st = fl_image_validate(img);
    if (st != FL_OK)
        return st;
    if (img->width < 8 || img->height < 8 || img->width > FL_CORNERS_MAX_WIDTH ||
        img->height > FL_CORNERS_MAX_HEIGHT)
        return FL_ERR_SIZE;
    if (camera && (camera->model.width_px != img->width || camera->model.height_px != img->height))
        return FL_ERR_MISMATCH;
    c->width = img->width;
    c->height = img->height;
    cn_luma(c, img);
    c->n_edge = cn_gradient(c);
    cn_responses(c);
    for (y = 0; y < c->height; y++)
        for (x = 0; x < c->width; x++) {
            fl_corner_t k;
            int32_t v, a, cv;
            if (c->resp[y * c->width + x] == 0 || !cn_is_max(c, x, y))
                continue;
            c->n_maxima++;
            memset(&k, 0, sizeof k);
            k.x = (int16_t)x;
            k.y = (int16_t)y;
            cn_measure_at(c, x, y, &v, &a, &cv);
            k.convex = (int8_t)cv;
            k.var = (uint8_t)(v > 255 ? 255 : v);
            k.response = c->resp[y * c->width + x];
            if (camera && c->params.max_range_mm > 0) {
                fl_point_t g;
                if (!fl_camera_pixel_to_ground(camera, x * 16, y * 16, &g) ||
                    fl_hypot(g.x_mm, g.y_mm) > (uint32_t)c->params.max_range_mm) {
                    c->rejected_ground++;
                    continue;
                }
            }
            if (!fl_corners_int_color_label(c, img, colors, camera, &k)) {
                c->rejected_color++;
                continue;
            }
            if (c->n_corners >= FL_CORNERS_MAX_CORNERS) {
                c->corners_dropped++;
                continue;
            }
            c->corner[c->n_corners++] = k;
        }
    fl_corners_int_pair(c, img, colors, camera, beacons);
    return FL_OK;
}
