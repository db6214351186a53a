/*
 * src/vision/beacon.c - sky-blue goal posts and corner beacons of the AIBO fields
 * from a sparse exact-HSV sampling above the field border (beacon.h).
 *
 * Algorithm.  (1) Per sampled column, top to the border + margin: each
 * sample's color by the HSV boxes; vertical runs of one color (one
 * missing sample bridged), ends refined to the pixel; runs overlapping a
 * run of the same color in the previous sampled column join its blob
 * (union-find).  (2) Blob boxes from the runs.  (3) Sky-blue (and
 * yellow) blobs that stand on the carpet: two posts from their edges.
 * (4) Pink blobs stacked
 * with a yellow or sky-blue blob and a white base: beacons; then single
 * lower bands cut by the image top.  (5) Foot, range and bearing per
 * result through the camera model.
 *
 * Invariant: n <= FL_BEACON_MAX_FOUND, n_runs <= FL_BEACON_MAX_RUNS,
 * n_blobs <= FL_BEACON_MAX_BLOBS; every run's blob index is a root (or
 * 255: none); a blob is used by at most one result.
 * Memory: the caller's fl_beacon_t (about 4 KB); stack < 300 B.
 * Cost: see beacon.h (samples <= (width / col_step) * (height / row_step
 * + 1); at most 16 runs per column).
 *
 * Scaling and overflow.  Pixels < 2^12 (FL_IMAGE_MAX_DIM), Q4 < 2^16.
 * Ground points from fl_camera_pixel_to_ground are within 20 m (< 2^15
 * mm); the centre along the ray g * (r + d/2) / r in int64.  Sizes:
 * focal_q4 < 2^21 times a size <= 2^12 mm in int64, divided by a pixel
 * size (Q4, > 0); distances squared in int64 (< 2^62), roots by
 * fl_isqrt64; ranges clamped to FL_CAMERA_MAX_RANGE_MM.  Counts saturate
 * (samples at 65535).  No division by a value that can be 0 (checked).
 */
#include "fieldloc/beacon.h"
#include "fieldloc/goal.h"

#include <string.h>

#define BC_NONE_BLOB 255u
#define BC_RUNS_PER_COLUMN 16

static int32_t bc_min(int32_t a, int32_t b) { return a < b ? a : b; }
static int32_t bc_max(int32_t a, int32_t b) { return a > b ? a : b; }

void fl_beacon_params_default(fl_beacon_params_t *p)
{
    static const fl_hsv_box_t sky = {88, 108, 90, 255, 40, 255};
    static const fl_hsv_box_t pink = {150, 172, 80, 255, 40, 255};
    static const fl_hsv_box_t yellow = {20, 38, 120, 255, 40, 255};
    if (!p)
        return;
    p->skyblue = sky;
    p->pink = pink;
    p->yellow = yellow;
    p->col_step = 0;
    p->row_step = 0;
    p->below_border_px = 4;
    p->min_confidence = 40;
    p->yellow_goals = 1;
}

static bool bc_box_ok(const fl_hsv_box_t *b)
{
    return b->h_lo <= 179 && b->h_hi <= 179 && b->s_lo <= b->s_hi &&
           b->v_lo <= b->v_hi;
}

fl_status_t fl_beacon_init_cfg(fl_beacon_t *b, const fl_beacon_params_t *p, uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *b has another layout: no write is safe */
    if (!b || !p)
        return FL_ERR_NULL;
    memset(b, 0, sizeof *b);
    fl_beacon_params_default(&b->params);
    if (!bc_box_ok(&p->skyblue) || !bc_box_ok(&p->pink) || !bc_box_ok(&p->yellow) ||
        p->col_step < 0 ||
        p->col_step > 16 || p->row_step < 0 || p->row_step > 16 ||
        p->below_border_px < 0 || p->below_border_px > 64 ||
        p->min_confidence < 0 || p->min_confidence > 255 ||
        p->yellow_goals < 0 || p->yellow_goals > 1)
        return FL_ERR_RANGE;
    b->params = *p;
    return FL_OK;
}

/* ---- pixels ---------------------------------------------------------------- */

/* R, G, B of pixel (u, v) of a validated view, (u, v) inside it. */
static void bc_rgb(const fl_image_t *img, int32_t u, int32_t v, uint8_t rgb[3])
{
    const uint8_t *p;
    switch (img->format) {
    case FL_FMT_RGB888:
        p = img->plane[0] + (size_t)v * (size_t)img->stride[0] + 3u * (size_t)u;
        rgb[0] = p[0];
        rgb[1] = p[1];
        rgb[2] = p[2];
        return;
    case FL_FMT_YUYV422:
        p = img->plane[0] + (size_t)v * (size_t)img->stride[0] + 4u * (size_t)(u >> 1);
        fl_rgb_from_ycbcr(p[(u & 1) * 2], p[1], p[3], rgb);
        return;
    case FL_FMT_YCBCR_PLANAR:
        fl_rgb_from_ycbcr(img->plane[0][(size_t)v * (size_t)img->stride[0] + (size_t)u],
                          img->plane[1][(size_t)v * (size_t)img->stride[1] + (size_t)u],
                          img->plane[2][(size_t)v * (size_t)img->stride[2] + (size_t)u],
                          rgb);
        return;
    default:
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
}

static bool bc_in_box(const fl_hsv_box_t *b, fl_hsv_t x)
{
    return fl_hsv_box_has_hue(b, x.h) && x.s >= b->s_lo && x.s <= b->s_hi &&
           x.v >= b->v_lo && x.v <= b->v_hi;
}

/* What one frame's search shares. */
typedef struct {
    fl_beacon_t *b;
    const fl_scan_t *s;
    const fl_image_t *img;
    const fl_color_table_t *ct;
    const fl_camera_t *cam;
    int32_t W, H, cs, rs;
    int32_t post_d, post_h, beacon_d, beacon_h;
} bc_ctx_t;

static fl_color_t bc_classify(const fl_beacon_params_t *p, const fl_hsv_box_t *yellow,
                               fl_hsv_t x)
{
    if (bc_in_box(yellow, x))
        return FL_COLOR_YELLOW;
    if (bc_in_box(&p->skyblue, x))
        return FL_COLOR_SKYBLUE;
    if (bc_in_box(&p->pink, x))
        return FL_COLOR_PINK;
    return FL_COLOR_NONE;
}

static fl_hsv_t bc_hsv(const bc_ctx_t *c, int32_t u, int32_t v)
{
    uint8_t rgb[3];
    bc_rgb(c->img, u, v, rgb);
    return fl_hsv_from_rgb(rgb[0], rgb[1], rgb[2]);
}

/* Color of R, G, B by the boxes of p (yellow: p->yellow).  Most samples
 * above the border are walls and other grey things: a color whose
 * saturation is surely below every box's s_lo or whose value is below
 * every v_lo is NONE without the HSV conversion, with the same result:
 * fl_hsv_from_rgb rounds S = 255 (max - min) / max to the nearest through
 * a reciprocal table (error < 0.04), so 255 (max - min) < (s_lo - 1) max
 * gives S < s_lo (checked for all 2^24 colors and every s_lo; the beacon
 * suite compares with the plain HSV classification).  Scaling: 255 * 255
 * < 2^16. */
static fl_color_t bc_color_rgb(const fl_beacon_params_t *p, const uint8_t rgb[3])
{
    int32_t mx, mn, s_min, v_min;
    s_min = bc_min(bc_min(p->skyblue.s_lo, p->pink.s_lo), p->yellow.s_lo);
    v_min = bc_min(bc_min(p->skyblue.v_lo, p->pink.v_lo), p->yellow.v_lo);
    mx = rgb[0] > rgb[1] ? rgb[0] : rgb[1];
    mn = rgb[0] < rgb[1] ? rgb[0] : rgb[1];
    if (rgb[2] > mx) mx = rgb[2];
    if (rgb[2] < mn) mn = rgb[2];
    if (mx < v_min || 255 * (mx - mn) < (s_min - 1) * mx)
        return FL_COLOR_NONE;
    return bc_classify(p, &p->yellow, fl_hsv_from_rgb(rgb[0], rgb[1], rgb[2]));
}

/* Color of pixel (u, v); NONE outside the image. */
static fl_color_t bc_color(const bc_ctx_t *c, int32_t u, int32_t v)
{
    uint8_t rgb[3];
    if (u < 0 || v < 0 || u >= c->W || v >= c->H)
        return FL_COLOR_NONE;
    bc_rgb(c->img, u, v, rgb);
    return bc_color_rgb(&c->b->params, rgb);
}

/* The white of a beacon base (or the wall behind it): unsaturated, not
 * dark.  S <= 80, V >= 60 (the base at 40 % light has V ~ 95). */
static bool bc_whitish(const bc_ctx_t *c, int32_t u, int32_t v)
{
    fl_hsv_t x;
    if (u < 0 || v < 0 || u >= c->W || v >= c->H)
        return false;
    x = bc_hsv(c, u, v);
    return x.s <= 80 && x.v >= 60;
}

static bool bc_green(const bc_ctx_t *c, int32_t u, int32_t v)
{
    return fl_goal_pixel_class(c->img, c->ct, u, v) == FL_CLASS_GREEN;
}

fl_color_t fl_beacon_pixel_color(const fl_beacon_params_t *p,
                                   const fl_image_t *img, int32_t u, int32_t v)
{
    uint8_t rgb[3];
    if (!p || !img || fl_image_validate(img) != FL_OK || u < 0 ||
        v < 0 || u >= img->width || v >= img->height)
        return FL_COLOR_NONE;
    bc_rgb(img, u, v, rgb);
    return bc_color_rgb(p, rgb);
}

/* ---- runs and blobs ---------------------------------------------------------- */

static uint8_t bc_find(fl_beacon_t *b, uint8_t k)
{
    int32_t guard = 0;
    while (b->parent[k] != k && guard++ < FL_BEACON_MAX_BLOBS) {
        b->parent[k] = b->parent[b->parent[k]];
        k = b->parent[k];
    }
    return k;
}

/* Field border of image column u (px): the scanner's nearest grid column;
 * the image height when none. */
static int32_t bc_border(const bc_ctx_t *c, int32_t u)
{
    int32_t i = u / c->s->params.col_step;
    if (i >= c->s->cols)
        i = c->s->cols - 1;
    if (i < 0)
        return c->H;
    return c->s->border_v[i];
}

/* Store the run [v0, v1] of color col in column u (ends refined to the
 * pixel) and join it to the blobs of the previous column's runs
 * prev0 .. prev1 - 1. */
static void bc_add_run(const bc_ctx_t *c, int32_t u, int32_t v0, int32_t v1,
                       fl_color_t col, int32_t prev0, int32_t prev1)
{
    fl_beacon_t *b = c->b;
    fl_beacon_run_t *r;
    int32_t k, j;
    uint8_t blob = BC_NONE_BLOB;
    if (b->n_runs >= FL_BEACON_MAX_RUNS) {
        b->runs_dropped++;
        return;
    }
    for (k = 1; k < c->rs && v0 - 1 >= 0 && bc_color(c, u, v0 - 1) == col; k++)
        v0--;
    for (k = 1; k < c->rs && v1 + 1 < c->H && bc_color(c, u, v1 + 1) == col; k++)
        v1++;
    r = &b->run[b->n_runs];
    r->u = (int16_t)u;
    r->v0 = (int16_t)v0;
    r->v1 = (int16_t)v1;
    r->color = (uint8_t)col;
    for (j = prev0; j < prev1; j++) {
        const fl_beacon_run_t *q = &b->run[j];
        uint8_t rq;
        if (q->color != (uint8_t)col || q->blob == BC_NONE_BLOB ||
            q->v0 > v1 + 1 || v0 > q->v1 + 1)
            continue;
        rq = bc_find(b, q->blob);
        if (blob == BC_NONE_BLOB)
            blob = rq;
        else if (rq != blob)
            b->parent[rq] = blob;
    }
    if (blob == BC_NONE_BLOB) {
        if (b->n_blobs >= FL_BEACON_MAX_BLOBS) {
            b->blobs_dropped++;
        } else {
            blob = (uint8_t)b->n_blobs++;
            b->parent[blob] = blob;
            b->blob[blob].color = (uint8_t)col;
        }
    }
    r->blob = blob;
    b->n_runs++;
}

/* One sampled column: runs from row 0 to the border + margin. */
static void bc_column(const bc_ctx_t *c, int32_t u, int32_t prev0, int32_t prev1)
{
    fl_beacon_t *b = c->b;
    int32_t border = bc_border(c, u), v_end, v, v0 = 0, vl = 0, gap = 0, nrun = 0;
    fl_color_t cur = FL_COLOR_NONE;
    v_end = border >= c->H ? c->H - 1 : border + b->params.below_border_px;
    if (v_end > c->H - 1)
        v_end = c->H - 1;
    for (v = 0; v <= v_end + c->rs; v += c->rs) {
        fl_color_t col = FL_COLOR_NONE;
        if (v <= v_end) {
            col = bc_color(c, u, v);
            b->samples++;
        }
        if (cur != FL_COLOR_NONE && col == cur) {
            vl = v;
            gap = 0;
            continue;
        }
        if (cur != FL_COLOR_NONE && col == FL_COLOR_NONE && gap == 0 && v <= v_end) {
            gap = 1;    /* one sample bridged */
            continue;
        }
        if (cur != FL_COLOR_NONE) {
            if (nrun < BC_RUNS_PER_COLUMN)
                bc_add_run(c, u, v0, vl, cur, prev0, prev1);
            else
                b->runs_dropped++;
            nrun++;
        }
        cur = col;
        v0 = vl = v;
        gap = 0;
    }
}

/* Blob boxes from the runs; every run's blob index becomes its root. */
static void bc_blob_boxes(fl_beacon_t *b)
{
    int32_t i;
    for (i = 0; i < b->n_blobs; i++) {
        fl_beacon_blob_t *bl = &b->blob[i];
        bl->u0 = bl->v0 = INT16_MAX;
        bl->u1 = bl->v1 = -1;
        bl->samples = 0;
        bl->used = 0;
    }
    for (i = 0; i < b->n_runs; i++) {
        fl_beacon_run_t *r = &b->run[i];
        fl_beacon_blob_t *bl;
        uint32_t ns;
        if (r->blob == BC_NONE_BLOB)
            continue;
        r->blob = bc_find(b, r->blob);
        bl = &b->blob[r->blob];
        if (r->u < bl->u0) bl->u0 = r->u;
        if (r->u > bl->u1) bl->u1 = r->u;
        if (r->v0 < bl->v0) bl->v0 = r->v0;
        if (r->v1 > bl->v1) bl->v1 = r->v1;
        ns = (uint32_t)bl->samples + (uint32_t)(r->v1 - r->v0) / (uint32_t)b->row_step + 1u;
        bl->samples = (uint16_t)(ns > 65535u ? 65535u : ns);
    }
}

static bool bc_is_root(const fl_beacon_t *b, int32_t k)
{
    return b->parent[k] == (uint8_t)k && b->blob[k].u1 >= 0;
}

/* Lowest run of blob k in the column of run i (i must belong to k): true
 * when no later run of the same column belongs to k. */
static bool bc_lowest_in_column(const fl_beacon_t *b, int32_t i)
{
    int32_t j;
    for (j = i + 1; j < b->n_runs && b->run[j].u == b->run[i].u; j++)
        if (b->run[j].blob == b->run[i].blob)
            return false;
    return true;
}

/* ---- geometry ---------------------------------------------------------------- */

/* Distance from the camera (mm) to a ground point at height z_mm above it:
 * sqrt(range^2 + (camera height - z)^2), >= 1. */
static int64_t bc_dist3(const bc_ctx_t *c, int32_t range_mm, int32_t z_mm)
{
    int64_t hz = (int64_t)c->cam->pos_q4[2] / 16 - z_mm;
    uint64_t d2 = (uint64_t)((int64_t)range_mm * range_mm + hz * hz);
    int64_t d = (int64_t)fl_isqrt64(d2);
    return d > 0 ? d : 1;
}

static void bc_push(fl_beacon_t *b, const fl_beacon_found_t *f)
{
    if (f->confidence < b->params.min_confidence)
        return;
    if (b->n >= FL_BEACON_MAX_FOUND) {
        b->found_dropped++;
        return;
    }
    b->found[b->n++] = *f;
}

/* ---- sky-blue goal --------------------------------------------------------------- */

/* One post at the left (dir = -1) or right (+1) edge of goal blob k. */
static void bc_post(const bc_ctx_t *c, int32_t k, int32_t dir, int32_t top_v)
{
    const fl_beacon_t *b = c->b;
    const fl_beacon_blob_t *bl = &b->blob[k];
    int32_t mid = (bl->u0 + bl->u1) / 2, i, mb = -1, ue = -1, bot = -1, vr, step,
            u_e, w_q4 = 0;
    fl_beacon_found_t f;
    /* lowest bottom of this half, then the outermost column within 2 px */
    for (i = 0; i < b->n_runs; i++) {
        const fl_beacon_run_t *r = &b->run[i];
        if (r->blob != (uint8_t)k || (dir < 0 ? r->u > mid : r->u < mid) ||
            !bc_lowest_in_column(b, i))
            continue;
        if (r->v1 > mb)
            mb = r->v1;
    }
    for (i = 0; i < b->n_runs; i++) {
        const fl_beacon_run_t *r = &b->run[i];
        if (r->blob != (uint8_t)k || (dir < 0 ? r->u > mid : r->u < mid) ||
            !bc_lowest_in_column(b, i) || r->v1 < mb - 2)
            continue;
        if (ue < 0 || (dir < 0 ? r->u < ue : r->u > ue)) {
            ue = r->u;
            bot = r->v1;
        }
    }
    if (ue < 0)
        return;
    /* the edge to the pixel, along a row just above the bottom */
    vr = bot - 2 >= top_v ? bot - 2 : bot;
    u_e = ue;
    for (step = 1; step < c->cs + 1 && bc_color(c, u_e + dir, vr) == (fl_color_t)bl->color;
         step++)
        u_e += dir;
    if (u_e + dir < 0 || u_e + dir >= c->W)
        return;     /* cut by the image edge: the post may be outside */
    /* beside a post the carpet ends at the wall, behind the foot: the
     * border there is at or above the foot.  Much lower: an object (a
     * robot) stands in front and its edge is not the post's. */
    {
        int32_t k2, seen = 0, ok = 0;
        for (k2 = 1; k2 <= 3; k2++) {
            int32_t uu = u_e + dir * 2 * k2;
            if (uu < 0 || uu >= c->W)
                continue;
            seen++;
            if (bc_border(c, uu) <= bot + c->rs + 3)
                ok++;
        }
        if (seen > 0 && ok == 0) {
            c->b->rejected_goal++;
            return;
        }
    }
    memset(&f, 0, sizeof f);
    f.kind = FL_LM_POST;
    f.color = (fl_color_t)bl->color;
    f.color2 = FL_COLOR_NONE;
    f.side = dir < 0 ? FL_SIDE_LEFT : FL_SIDE_RIGHT;
    f.top_v_q4 = top_v * 16;
    f.foot_visible = true;
    f.confidence = 190;
    f.u_q4 = u_e * 16;
    f.v_q4 = bot * 16 + 8;
    if (c->cam) {
        fl_point_t g;
        /* predicted post width at the edge's ground distance */
        if (fl_camera_pixel_to_ground(c->cam, f.u_q4, f.v_q4, &g)) {
            int32_t rg = (int32_t)fl_hypot(g.x_mm, g.y_mm);
            int64_t d3 = bc_dist3(c, rg, 0);
            int64_t w = (int64_t)c->cam->model.focal_q4 * c->post_d / d3;
            w_q4 = (int32_t)(w > 16 * 256 ? 16 * 256 : w);
        }
        f.width_q4 = w_q4;
        f.u_q4 -= dir * (w_q4 / 2);
        if (!fl_camera_foot_to_centre(c->cam, &f.u_q4, &f.v_q4, c->post_d, &f.ground))
            return;
        fl_polar_from_point(f.ground, &f.range_mm, &f.bearing);
    }
    bc_push(c->b, &f);
}

/* Goal-colored blob k: a goal standing on the carpet?  Then its posts. */
static void bc_goal(const bc_ctx_t *c, int32_t k)
{
    fl_beacon_t *b = c->b;
    fl_beacon_blob_t *bl = &b->blob[k];
    int32_t i, ncol = 0, meet = 0, h;
    if ((bl->u1 - bl->u0) / c->cs + 1 < 3 || bl->samples < 6)
        return;
    for (i = 0; i < b->n_runs; i++) {
        const fl_beacon_run_t *r = &b->run[i];
        int32_t bd, d, j;
        if (r->blob != (uint8_t)k || !bc_lowest_in_column(b, i))
            continue;
        ncol++;
        bd = bc_border(c, r->u);
        d = bd - r->v1;
        if (bd >= c->H || d < -2 || d > c->rs + 3)
            continue;
        for (j = 1; j <= 3; j++)
            if (bc_green(c, r->u, r->v1 + j))
                break;
        if (j <= 3)
            meet++;
    }
    if (ncol == 0 || meet * 2 < ncol) {
        b->rejected_goal++;
        return;
    }
    /* height against a goal at the foot's distance */
    h = bl->v1 - bl->v0 + 1;
    if (c->cam) {
        fl_point_t g;
        int32_t um = (bl->u0 + bl->u1) / 2;
        if (fl_camera_pixel_to_ground(c->cam, um * 16, bl->v1 * 16 + 8, &g)) {
            int32_t rg = (int32_t)fl_hypot(g.x_mm, g.y_mm);
            int64_t d3 = bc_dist3(c, rg, c->post_h / 2);
            int64_t expect = (int64_t)c->cam->model.focal_q4 * c->post_h / (16 * d3);
            if ((int64_t)h * 2 < expect ||
                (bl->v0 > c->rs && (int64_t)h * 2 > expect * 5 + 4)) {
                b->rejected_goal++;
                return;
            }
        }
    }
    bl->used = 1;
    bc_post(c, k, -1, bl->v0);
    bc_post(c, k, 1, bl->v0);
}

/* ---- beacons --------------------------------------------------------------------- */

/* Foot of a beacon under its lower band (bottom row lo_v1, band height hb
 * px) in column u: the last row before the carpet, or -1 when the carpet
 * is not 1.2 .. 3.2 band heights under the band. */
static int32_t bc_beacon_foot(const bc_ctx_t *c, int32_t u, int32_t lo_v1, int32_t hb)
{
    int32_t v, lim = lo_v1 + 4 * hb + 2;
    if (lim > c->H - 1)
        lim = c->H - 1;
    for (v = lo_v1 + 1; v <= lim; v++) {
        if (bc_green(c, u, v)) {
            int32_t d = v - 1 - lo_v1;
            if (d * 10 >= hb * 12 && d * 10 <= hb * 32)
                return v - 1;
            return -1;
        }
    }
    return -1;
}

/* A beacon with the given bands (up may be NULL: cut off), band height hb
 * (px) and width w (px) around column u_c. */
static void bc_beacon_emit(const bc_ctx_t *c, const fl_beacon_blob_t *up,
                           const fl_beacon_blob_t *lo, int32_t u_c, int32_t hb,
                           int32_t w)
{
    fl_beacon_found_t f;
    int32_t foot;
    memset(&f, 0, sizeof f);
    f.kind = FL_LM_BEACON;
    f.color = up ? (fl_color_t)up->color : FL_COLOR_NONE;
    f.color2 = (fl_color_t)lo->color;
    f.side = FL_SIDE_UNKNOWN;
    f.top_v_q4 = (up ? up->v0 : lo->v0) * 16;
    f.width_q4 = w * 16;
    foot = bc_beacon_foot(c, u_c, lo->v1, hb);
    f.u_q4 = u_c * 16;
    if (foot >= 0) {
        f.foot_visible = true;
        f.v_q4 = foot * 16 + 8;
        f.confidence = up ? 200 : 150;
        if (c->cam) {
            int64_t d3, expect;
            if (!fl_camera_foot_to_centre(c->cam, &f.u_q4, &f.v_q4, c->beacon_d, &f.ground))
                return;
            fl_polar_from_point(f.ground, &f.range_mm, &f.bearing);
            /* the width a beacon has at that distance (f d / dist, Q4):
             * 0.6 .. 1.6 times, 2 px of sampling slack */
            d3 = bc_dist3(c, f.range_mm, c->beacon_h * 3 / 4);
            expect = (int64_t)c->cam->model.focal_q4 * c->beacon_d / d3;
            if ((int64_t)w * 16 * 10 + 32 * 10 < expect * 6 ||
                (int64_t)w * 16 * 10 > expect * 16 + 32 * 10) {
                c->b->rejected_beacon++;
                return;
            }
        }
    } else {
        /* from the size: the two bands are half the beacon's height */
        int32_t hpx = lo->v1 - (up ? up->v0 : 0) + 1;
        f.v_q4 = lo->v1 * 16 + 8;
        if (!up || up->v0 <= 0 || hpx <= 0)
            return;     /* neither the foot nor the whole size */
        f.confidence = 120;
        if (c->cam) {
            int64_t dist = (int64_t)c->cam->model.focal_q4 * (c->beacon_h / 2) /
                           ((int64_t)hpx * 16);
            int64_t hz = (int64_t)c->cam->pos_q4[2] / 16 - c->beacon_h * 3 / 4, r;
            r = dist > hz && dist > -hz
                    ? (int64_t)fl_isqrt64((uint64_t)(dist * dist - hz * hz)) : 0;
            if (r > FL_CAMERA_MAX_RANGE_MM)
                r = FL_CAMERA_MAX_RANGE_MM;
            f.range_mm = (int32_t)r;
            f.bearing = fl_angle_add(fl_atan2(c->cam->model.cx_q4 - f.u_q4,
                                              c->cam->model.focal_q4),
                                     c->cam->pose.head_yaw);
            f.ground = fl_point_from_polar(f.range_mm, f.bearing);
        }
    }
    bc_push(c->b, &f);
}


/* Bands up over lo: stacked, similar width, band-shaped, white under lo?
 * Returns the horizontal overlap (px) when they pass, else 0. */
static int32_t bc_pair_ok(const bc_ctx_t *c, const fl_beacon_blob_t *up,
                          const fl_beacon_blob_t *lo)
{
    int32_t cs = c->cs, rs = c->rs;
    int32_t wu = up->u1 - up->u0 + cs, wl = lo->u1 - lo->u0 + cs;
    int32_t ov = bc_min(up->u1, lo->u1) - bc_max(up->u0, lo->u0) + cs;
    int32_t hu = up->v1 - up->v0 + 1, hl = lo->v1 - lo->v0 + 1;
    int32_t gap = lo->v0 - up->v1 - 1, uc, k, white = 0, probes = 0;
    if (ov * 2 < bc_min(wu, wl) || wu > 2 * wl + cs || wl > 2 * wu + cs)
        return 0;
    if (gap < -2 || gap > rs + 2 + hl / 3)
        return 0;
    /* band shape: 0.4 .. 2.5 times as tall as wide (sampling slack) */
    if (hl * 5 + 5 * rs < 2 * wl || hl * 2 > 5 * wl + 4 * rs)
        return 0;
    if (up->v0 > rs) {
        if (hu * 5 + 5 * rs < 2 * wu || hu * 2 > 5 * wu + 4 * rs)
            return 0;
        if (hu * 2 + 2 * rs < hl || hl * 2 + 2 * rs < hu)
            return 0;
    } else if (hu > 2 * hl + 2 * rs) {
        return 0;
    }
    /* the white base: probes at 1/2 and 1 band under the lower band (a
     * base below the image passes) */
    uc = (bc_max(up->u0, lo->u0) + bc_min(up->u1, lo->u1)) / 2;
    for (k = 1; k <= 2; k++) {
        int32_t v = lo->v1 + k * hl / 2 + 1;
        if (v >= c->H)
            continue;
        probes++;
        if (bc_whitish(c, uc, v))
            white++;
    }
    if (probes > 0 && white == 0)
        return 0;
    return ov;
}

static void bc_beacons(const bc_ctx_t *c)
{
    fl_beacon_t *b = c->b;
    int32_t i, j;
    for (i = 0; i < b->n_blobs; i++) {
        fl_beacon_blob_t *p = &b->blob[i];
        int32_t best = -1, best_ov = 0, best_up = 0;
        if (!bc_is_root(b, i) || p->used || p->color != FL_COLOR_PINK || p->samples < 2)
            continue;
        for (j = 0; j < b->n_blobs; j++) {
            fl_beacon_blob_t *q = &b->blob[j];
            int32_t ov, pu;
            if (j == i || !bc_is_root(b, j) || q->used || q->samples < 2 ||
                (q->color != FL_COLOR_YELLOW && q->color != FL_COLOR_SKYBLUE))
                continue;
            for (pu = 0; pu <= 1; pu++) {
                ov = pu ? bc_pair_ok(c, p, q) : bc_pair_ok(c, q, p);
                if (ov > best_ov) {
                    best_ov = ov;
                    best = j;
                    best_up = pu;
                }
            }
        }
        if (best < 0) {
            continue;
        } else {
            fl_beacon_blob_t *q = &b->blob[best];
            const fl_beacon_blob_t *up = best_up ? p : q, *lo = best_up ? q : p;
            int32_t u_c;
            int32_t hb = lo->v1 - lo->v0 + 1;
            int32_t a = bc_min(up->u0, lo->u0), z = bc_max(up->u1, lo->u1), e;
            /* the width and centre to the pixel along the lower band's middle */
            int32_t vm = (lo->v0 + lo->v1) / 2;
            for (e = 1; e < c->cs && bc_color(c, a - 1, vm) == (fl_color_t)lo->color; e++)
                a--;
            for (e = 1; e < c->cs && bc_color(c, z + 1, vm) == (fl_color_t)lo->color; e++)
                z++;
            u_c = (a + z) / 2;
            p->used = q->used = 1;
            bc_beacon_emit(c, up, lo, u_c, hb, z - a + 1);
        }
    }
    /* a lower band alone, cut by the image top, on a white base */
    for (i = 0; i < b->n_blobs; i++) {
        fl_beacon_blob_t *q = &b->blob[i];
        int32_t w, uc, k, white = 0, foot;
        if (!bc_is_root(b, i) || q->used || q->v0 > c->rs ||
            (q->color != FL_COLOR_YELLOW && q->color != FL_COLOR_SKYBLUE))
            continue;
        w = q->u1 - q->u0 + c->cs;
        if ((q->u1 - q->u0) / c->cs + 1 < 2 || q->v1 - q->v0 + 1 > 3 * w)
            continue;
        uc = (q->u0 + q->u1) / 2;
        for (k = 1; k <= 4; k++)
            if (bc_whitish(c, uc, q->v1 + 1 + k * w / 2))
                white++;
        /* the band is as tall as wide: the base 2 widths */
        foot = bc_beacon_foot(c, uc, q->v1, w);
        if (white < 3 || foot < 0) {
            b->rejected_beacon++;
            continue;
        }
        q->used = 1;
        bc_beacon_emit(c, NULL, q, uc, w, w);
    }
}

/* ---- the frame ------------------------------------------------------------------- */

int32_t fl_beacon_find(fl_beacon_t *b, const fl_scan_t *scan,
                       const fl_image_t *img, const fl_color_table_t *colors,
                       const fl_camera_t *camera, const fl_field_t *field)
{
    bc_ctx_t c;
    int32_t u, i, prev0 = 0, prev1 = 0;
    bool yellow_goal;
    if (!b)
        return 0;
    b->n = b->n_runs = b->n_blobs = 0;
    b->samples = b->runs_dropped = b->blobs_dropped = b->found_dropped = 0;
    b->rejected_goal = b->rejected_beacon = 0;
    if (!scan || scan->width <= 0 || scan->cols <= 0 || !img || !colors ||
        fl_image_validate(img) != FL_OK || img->width != scan->width ||
        img->height != scan->height || scan->params.col_step <= 0)
        return 0;
    memset(&c, 0, sizeof c);
    c.b = b;
    c.s = scan;
    c.img = img;
    c.ct = colors;
    c.cam = camera;
    c.W = img->width;
    c.H = img->height;
    c.cs = b->params.col_step > 0 ? b->params.col_step
                                  : (c.W <= 208 ? 2 : (c.W + 103) / 104);
    c.rs = b->params.row_step > 0 ? b->params.row_step
                                  : (c.H <= 160 ? 2 : (c.H + 79) / 80);
    if (c.cs > 16)
        c.cs = 16;
    if (c.rs > 16)
        c.rs = 16;
    b->col_step = c.cs;
    b->row_step = c.rs;
    c.post_d = field && field->post_diameter_mm > 0 ? field->post_diameter_mm : 50;
    c.post_h = field && field->post_height_mm > 0 ? field->post_height_mm : 300;
    c.beacon_d = field && field->beacon_diameter_mm > 0 ? field->beacon_diameter_mm : 100;
    c.beacon_h = field && field->beacon_height_mm > 0 ? field->beacon_height_mm : 400;
    if (c.post_d > 4096) c.post_d = 4096;
    if (c.post_h > 4096) c.post_h = 4096;
    if (c.beacon_d > 4096) c.beacon_d = 4096;
    if (c.beacon_h > 4096) c.beacon_h = 4096;
    for (u = 0; u < c.W; u += c.cs) {
        int32_t start = b->n_runs;
        bc_column(&c, u, prev0, prev1);
        prev0 = start;
        prev1 = b->n_runs;
    }
    bc_blob_boxes(b);
    yellow_goal = b->params.yellow_goals &&
                  (!field || field->goal_color[0] == FL_COLOR_YELLOW ||
                   field->goal_color[1] == FL_COLOR_YELLOW);
    for (i = 0; i < b->n_blobs; i++)
        if (bc_is_root(b, i) && (b->blob[i].color == FL_COLOR_SKYBLUE ||
                                 (yellow_goal && b->blob[i].color == FL_COLOR_YELLOW)))
            bc_goal(&c, i);
    bc_beacons(&c);
    return b->n;
}
