/*
 * src/vision/goal.c - yellow goal posts from the scanner's yellow histogram, its
 * yellow->green transitions and image probes above the field border (seed
 * 000, section 3.8); see goal.h.
 *
 * Algorithm.  Per grid column: yellow_cols and 4 probes above the border;
 * runs of post-like columns are candidates.  Per candidate: the yellow
 * column walked down to the foot and up (post rows, crossbar band or
 * clutter), widths by horizontal runs, the shape / height / border checks,
 * ground position from the foot or the width, side from the crossbar band
 * or the order of two posts.
 *
 * Invariant: every stored post passed the shape check and, when its foot
 * is visible, the border check; no two stored posts overlap; n <=
 * FL_GOAL_MAX_POSTS.
 * Memory: the caller's fl_posts_t (about 50 B per post); stack < 400 B.
 * Cost: 4 pixel classifications per grid column + per candidate O(rows)
 * pixel classifications plus a run across every 4th row (at most 4 widths
 * + 8 px) + at most 12 probes.
 *
 * Scaling and overflow.  Pixels Q4 (< 2^17); ground mm (< 2^15 after
 * pixel_to_ground's 20 m limit).  The range along the ray: r = |g| + d/2,
 * the centre g * r / |g| in int64 (< 2^31 * 2^15).  Width fallback and
 * height check: distance from the camera = focal_q4 * size / (16 d) or
 * / width_q4 (focal < 2^20, size < 2^12: int64), ground range
 * sqrt(dist^2 - h^2) with fl_isqrt64.
 */
#include "fieldloc/goal.h"

#include <string.h>

fl_color_class_t fl_goal_pixel_class(const fl_image_t *img,
                                     const fl_color_table_t *colors,
                                     int32_t u, int32_t v)
{
    const uint8_t *p;
    if (!img || !colors || u < 0 || v < 0 || u >= img->width || v >= img->height)
        return FL_CLASS_OTHER;
    switch (img->format) {
    case FL_FMT_RGB888:
        p = img->plane[0] + (size_t)v * (size_t)img->stride[0] + 3u * (size_t)u;
        return fl_color_class_rgb(colors, p[0], p[1], p[2]);
    case FL_FMT_YUYV422:
        p = img->plane[0] + (size_t)v * (size_t)img->stride[0] + 4u * (size_t)(u >> 1);
        return fl_color_class_ycbcr(colors, p[(u & 1) * 2], p[1], p[3]);
    case FL_FMT_YCBCR_PLANAR:
        return fl_color_class_ycbcr(
            colors, img->plane[0][(size_t)v * (size_t)img->stride[0] + (size_t)u],
            img->plane[1][(size_t)v * (size_t)img->stride[1] + (size_t)u],
            img->plane[2][(size_t)v * (size_t)img->stride[2] + (size_t)u]);
    default:
        return FL_CLASS_OTHER;
    }
}


/* Yellow run across grid row j through column i: first and last column. */

static int32_t gl_median3(int32_t a, int32_t b, int32_t c)
{
    if (a > b) { int32_t t = a; a = b; b = t; }
    if (b > c) { int32_t t = b; b = c; c = t; }
    if (a > b) { int32_t t = a; a = b; b = t; }
    return b;
}

/* Yellow pixels of the image at (u_q4 + k * w / 2, v) for k = 3, 5, 7 on
 * one side (dir = +1 right, -1 left). */
static int32_t gl_crossbar(const fl_image_t *img, const fl_color_table_t *ct,
                           int32_t u_q4, int32_t v_px, int32_t w_q4, int32_t dir)
{
    int32_t k, n = 0;
    for (k = 3; k <= 7; k += 2) {
        int32_t u = (u_q4 + dir * k * w_q4 / 2) / 16;
        if (fl_goal_pixel_class(img, ct, u, v_px) == FL_CLASS_YELLOW ||
            fl_goal_pixel_class(img, ct, u, v_px + 1) == FL_CLASS_YELLOW)
            n++;
    }
    return n;
}

/* Yellow pixel through the tables. */
static bool gl_yellow(const fl_image_t *img, const fl_color_table_t *ct,
                      int32_t u, int32_t v)
{
    return fl_goal_pixel_class(img, ct, u, v) == FL_CLASS_YELLOW;
}

/* Horizontal yellow run of the image through (u, v): first and last
 * column; 0 when (u, v) is not yellow.  At most `lim` px each way. */
static int32_t gl_img_hrun_lim(const fl_image_t *img, const fl_color_table_t *ct,
                               int32_t u, int32_t v, int32_t lohi[2], int32_t lim)
{
    int32_t a = u, b = u, k;
    if (!gl_yellow(img, ct, u, v))
        return 0;
    for (k = 0; k < lim && gl_yellow(img, ct, a - 1, v); k++)
        a--;
    for (k = 0; k < lim && gl_yellow(img, ct, b + 1, v); k++)
        b++;
    lohi[0] = a;
    lohi[1] = b;
    return b - a + 1;
}

static int32_t gl_img_hrun(const fl_image_t *img, const fl_color_table_t *ct,
                           int32_t u, int32_t v, int32_t *lo, int32_t *hi)
{
    int32_t lh[2], n = gl_img_hrun_lim(img, ct, u, v, lh, 256);
    if (n > 0) {
        *lo = lh[0];
        *hi = lh[1];
    }
    return n;
}

/* What every candidate of a frame shares. */
typedef struct {
    fl_posts_t *out;
    const fl_scan_t *s;
    const fl_image_t *img;
    const fl_color_table_t *ct;
    const fl_camera_t *cam;
    int32_t diam, post_h;
} gl_ctx_t;

/* Is a post already found within its width plus half (px) of column u_c? */
static bool gl_found(const fl_posts_t *out, int32_t u_c, int32_t half)
{
    int32_t k;
    for (k = 0; k < out->n; k++) {
        int32_t d = out->post[k].foot_u_q4 / 16 - u_c;
        if (d < 0)
            d = -d;
        if (d <= out->post[k].width_q4 / 16 + half)
            return true;
    }
    return false;
}

/* Step of gl_candidate: up from the foot row foot_v in column u_c: post
 * rows (no wider than 1.6 widths w_px) then a crossbar band or clutter
 * (wider rows).  Into tpw: the top post row, the top row (-1: unknown)
 * and the rows of the band. */
static void gl_climb(const fl_image_t *img, const fl_color_table_t *ct, int32_t u_c,
                     int32_t foot_v, int32_t w_px, int32_t *tpw)
{
    int32_t top_post, top, wide, gap, v;
    top_post = foot_v;
    top = -1;
    wide = 0;
    gap = 0;
    for (v = foot_v - 1; v >= 0; v--) {
        int32_t ab[2], w;
        if (!gl_yellow(img, ct, u_c, v)) {
            if (++gap > 1)
                break;
            continue;
        }
        gap = 0;
        /* the width every 4th row (and every row in a band); only "wider
         * than 1.6 widths" matters, so the run is cut there */
        if ((v & 3) != 0 && wide == 0) {
            top_post = v;
            continue;
        }
        w = gl_img_hrun_lim(img, ct, u_c, v, ab, 2 * w_px + 4);
        if (w * 10 <= w_px * 16 + 20) {
            if (wide > 0)
                break;          /* post again above a band: clutter */
            top_post = v;
        } else {
            wide++;
            top = v;
            if (wide > 2 * w_px + 2)
                break;          /* too thick for a crossbar */
        }
    }
    if (wide > 2 * w_px + 2)
        top = -1;               /* clutter above: top unknown */
    else if (wide == 0)
        top = top_post;
    tpw[0] = top_post;
    tpw[1] = top;
    tpw[2] = wide;
}

/* Step of gl_candidate: the post's range and bearing (from the foot, else
 * from the width) and its confidence; false when its yellow is too short
 * for the height the camera predicts from the foot distance. */
static bool gl_range(const gl_ctx_t *ctx, fl_post_t *p, int32_t u_c, int32_t foot_v,
                     int32_t top_post, int32_t height_px)
{
    fl_posts_t *out = ctx->out;
    const fl_camera_t *cam = ctx->cam;
    int32_t diam = ctx->diam, post_h = ctx->post_h;
    /* a post is post_height tall: its yellow must reach half the height
     * the camera predicts from the foot distance (f h / d), or the image
     * top (small yellow things on the field are not posts) */
    if (cam && p->foot_visible && p->range_mm > 0) {
        int64_t hz = cam->pos_q4[2] / 16 - post_h / 2;
        int64_t d = (int64_t)fl_isqrt64((uint64_t)((int64_t)p->range_mm * p->range_mm + hz * hz));
        int64_t expect = d > 0 ? (int64_t)cam->model.focal_q4 * post_h / (16 * d) : 0;
        if (top_post > 1 && (int64_t)height_px * 2 < expect) {
            out->rejected_shape++;
            return false;
        }
    }
    if (cam && (!p->foot_visible || p->range_mm == 0)) {
        /* width fallback: distance from the camera f d / w */
        int64_t dist = (int64_t)cam->model.focal_q4 * diam / p->width_q4;
        int64_t hz = cam->pos_q4[2] / 16, r;
        fl_angle_t b = fl_angle_add(
            fl_atan2(cam->model.cx_q4 - u_c * 8, cam->model.focal_q4),
            cam->pose.head_yaw);
        r = dist > hz ? (int64_t)fl_isqrt64((uint64_t)(dist * dist - hz * hz)) : 0;
        if (r > FL_CAMERA_MAX_RANGE_MM)
            r = FL_CAMERA_MAX_RANGE_MM;
        p->range_mm = (int32_t)r;
        p->bearing = b;
        p->ground = fl_point_from_polar(p->range_mm, b);
        p->range_from_width = true;
        p->foot_u_q4 = u_c * 8;
        p->foot_v_q4 = foot_v * 16 + 8;
        p->confidence = 120;
    }
    if (p->foot_visible && cam && p->range_mm > 0) {
        /* agreement of the width with the foot distance */
        int64_t dist = (int64_t)cam->model.focal_q4 * diam / p->width_q4;
        int64_t hz = cam->pos_q4[2] / 16;
        int64_t r2 = (int64_t)p->range_mm * p->range_mm + hz * hz;
        int64_t d2 = dist * dist;
        if (d2 * 4 < r2 || d2 > r2 * 4)
            p->confidence = 130;
    }
    return true;
}

/* One candidate: the image columns u0..u1 (px) look like a post just above
 * the field border.  vb: a row inside it (px). */
static void gl_candidate(const gl_ctx_t *ctx, int32_t u0, int32_t u1, int32_t vb)
{
    fl_posts_t *out = ctx->out;
    const fl_scan_t *s = ctx->s;
    const fl_image_t *img = ctx->img;
    const fl_color_table_t *ct = ctx->ct;
    const fl_camera_t *cam = ctx->cam;
    int32_t diam = ctx->diam;
    int32_t cs = s->params.col_step, H = s->height, k, v, gap, foot_v,
            top_post, top, lo, hi, wl[3], w_px, u_c, height_px, wide, ic,
            jfoot, j, tpw[3];
    fl_post_t p;
    out->candidates++;
    /* a yellow pixel of the candidate at row vb, nearest to its middle */
    u_c = (u0 + u1) / 2;
    /* a post already found here (a column run split in two) */
    if (gl_found(out, u_c, (u1 - u0) / 2 + 2))
        return;
    for (k = 0; k <= (u1 - u0) / 2 + 1; k++) {
        if (gl_yellow(img, ct, u_c + k, vb)) {
            u_c += k;
            break;
        }
        if (gl_yellow(img, ct, u_c - k, vb)) {
            u_c -= k;
            break;
        }
    }
    if (!gl_yellow(img, ct, u_c, vb))
        return;
    if (gl_img_hrun(img, ct, u_c, vb, &lo, &hi) > 0)
        u_c = (lo + hi) / 2;
    /* down to the foot (1-px gaps bridged) */
    foot_v = vb;
    gap = 0;
    for (v = vb + 1; v < H; v++) {
        if (gl_yellow(img, ct, u_c, v)) {
            foot_v = v;
            gap = 0;
        } else if (++gap > 1) {
            break;
        }
    }
    /* the post's width above the foot: median of three rows (the lowest
     * rows blend with the line under the post) */
    for (k = 0; k < 3; k++) {
        int32_t a = u_c, b = u_c;
        wl[k] = gl_img_hrun(img, ct, u_c, foot_v - 2 - 2 * k, &a, &b);
    }
    w_px = gl_median3(wl[0], wl[1], wl[2]);
    if (w_px <= 0)
        w_px = gl_img_hrun(img, ct, u_c, vb, &lo, &hi);
    if (w_px <= 0)
        return;
    lo = u_c;
    hi = u_c;
    (void)gl_img_hrun(img, ct, u_c, foot_v - 2, &lo, &hi);
    /* up: post rows then a crossbar band or clutter */
    gl_climb(img, ct, u_c, foot_v, w_px, tpw);
    top_post = tpw[0];
    top = tpw[1];
    wide = tpw[2];
    height_px = foot_v - top_post + 1;
    /* width: median of the runs at 10, 25 and 40 % of the post rows */
    for (k = 0; k < 3; k++) {
        static const int32_t frac[3] = {10, 25, 40};
        int32_t a = u_c, b = u_c;
        wl[k] = gl_img_hrun(img, ct, u_c, foot_v - height_px * frac[k] / 100, &a, &b);
    }
    w_px = gl_median3(wl[0], wl[1], wl[2]);
    if (w_px <= 0 || height_px * 10 < w_px * 25) {
        out->rejected_shape++;
        return;
    }
    memset(&p, 0, sizeof p);
    p.width_q4 = w_px * 16;
    /* foot seen: field (green or white) right below it, and the field
     * border beside the post at or above the foot */
    p.foot_visible = foot_v < H - 2;
    if (p.foot_visible) {
        int32_t field_px = 0, ok = 0, seen = 0, off = 2 * w_px + 2 * cs;
        for (k = 2; k <= 4; k++) {
            fl_color_class_t c = fl_goal_pixel_class(img, ct, u_c, foot_v + k);
            if (c == FL_CLASS_GREEN || c == FL_CLASS_WHITE)
                field_px++;
        }
        for (k = -1; k <= 1; k += 2) {
            int32_t uu = u_c + k * off;
            ic = uu / cs;
            if (uu < 0 || ic >= s->cols)
                continue;
            seen++;
            if (s->border_v[ic] <= foot_v + 2 + 2 * s->params.row_step)
                ok++;
        }
        if (field_px == 0 || (seen > 0 && ok == 0)) {
            out->rejected_border++;
            return;
        }
    }
    /* the scanner's lowest yellow->green transition in these columns
     * refines the foot row */
    jfoot = -1;
    for (j = 0; j < s->n_feet; j++) {
        int32_t fu = s->feet[j].u;
        if (fu >= lo - cs && fu <= hi + cs && s->feet[j].v >= foot_v - 2 &&
            s->feet[j].v <= foot_v + 3 && s->feet[j].v > jfoot)
            jfoot = s->feet[j].v;
    }
    u_c = lo + hi;          /* Q1 */
    p.top_visible = top > 0;
    p.top_u_q4 = u_c * 8;
    p.top_v_q4 = top >= 0 ? top * 16 - 8 : 0;
    p.confidence = 200;
    if (p.foot_visible) {
        p.foot_u_q4 = u_c * 8;
        p.foot_v_q4 = foot_v * 16 + 8;
        if (jfoot >= 0 && jfoot - 1 > foot_v)
            p.foot_v_q4 = (jfoot - 1) * 16 + 8;
        if (fl_camera_foot_to_centre(cam, &p.foot_u_q4, &p.foot_v_q4, diam, &p.ground))
            fl_polar_from_point(p.ground, &p.range_mm, &p.bearing);
    }
    if (!gl_range(ctx, &p, u_c, foot_v, top_post, height_px))
        return;
    /* side from the crossbar */
    p.side = FL_SIDE_UNKNOWN;
    if (p.top_visible && wide > 0) {
        int32_t vv = top + (wide + 1) / 2;
        int32_t r = gl_crossbar(img, ct, u_c * 8, vv, p.width_q4, 1);
        int32_t l = gl_crossbar(img, ct, u_c * 8, vv, p.width_q4, -1);
        if (r >= 2 && l == 0)
            p.side = FL_SIDE_LEFT;
        else if (l >= 2 && r == 0)
            p.side = FL_SIDE_RIGHT;
    }
    /* the same post twice (a split column run) */
    for (k = 0; k < out->n; k++) {
        int32_t d = out->post[k].foot_u_q4 - p.foot_u_q4;
        if (d < 0)
            d = -d;
        if (d < p.width_q4 + out->post[k].width_q4)
            return;
    }
    if (out->n >= FL_GOAL_MAX_POSTS) {
        out->dropped++;
        return;
    }
    out->post[out->n++] = p;
}

int32_t fl_goal_find(fl_posts_t *out, const fl_scan_t *scan,
                     const fl_image_t *img, const fl_color_table_t *colors,
                     const fl_camera_t *camera, const fl_field_t *field)
{
    static const int32_t probe_px[4] = {2, 6, 12, 20};
    int32_t i, start = -1, last = -1, min_cells, diam, cs, post_h, run_vb = -1;
    gl_ctx_t ctx;
    if (!out)
        return 0;
    memset(out, 0, sizeof *out);
    if (!scan || scan->width <= 0 || scan->cols <= 0 || !img || !colors ||
        img->width != scan->width || img->height != scan->height)
        return 0;
    cs = scan->params.col_step;
    diam = field && field->post_diameter_mm > 0 ? field->post_diameter_mm : 100;
    post_h = field && field->post_height_mm > 0 ? field->post_height_mm : 800;
    ctx.out = out;
    ctx.s = scan;
    ctx.img = img;
    ctx.ct = colors;
    ctx.cam = camera;
    ctx.diam = diam;
    ctx.post_h = post_h;
    min_cells = 8 / scan->params.row_step;
    if (min_cells < 3)
        min_cells = 3;
    /* post-like columns: yellow in the map's histogram, or yellow in the
     * image at 2 of 4 rows just above the column's border (a goal line
     * under the foot keeps the scanner from following the post up) */
    for (i = 0; i <= scan->cols; i++) {
        bool on = false;
        int32_t k, n = 0, vb = -1;
        if (i < scan->cols && scan->border_v[i] < scan->height) {
            for (k = 0; k < 4; k++) {
                int32_t v = scan->border_v[i] - probe_px[k];
                if (v >= 0 && gl_yellow(img, colors, i * cs, v)) {
                    n++;
                    if (v > vb)
                        vb = v;
                }
            }
            on = n >= 2 || scan->yellow_cols[i] >= min_cells;
        }
        if (on) {
            if (start < 0) {
                start = i;
                run_vb = -1;
            }
            last = i;
            if (vb > run_vb)
                run_vb = vb;
        } else if (start >= 0 && (i - last > 2 || i == scan->cols)) {
            /* probe row: the lowest yellow probe of the run, else just
             * above the border of its middle column */
            int32_t v = run_vb >= 0 ? run_vb : scan->border_v[(start + last) / 2] - 4;
            if (v < 0)
                v = 0;
            gl_candidate(&ctx, start * cs, last * cs, v);
            start = -1;
        }
    }
    /* two posts, sides unknown: order in the image */
    if (out->n == 2) {
        fl_post_t *a = &out->post[0], *b = &out->post[1];
        if (a->side == FL_SIDE_UNKNOWN && b->side == FL_SIDE_UNKNOWN) {
            a->side = FL_SIDE_LEFT;  /* candidates run left to right */
            b->side = FL_SIDE_RIGHT;
        } else if (a->side == FL_SIDE_UNKNOWN) {
            a->side = b->side == FL_SIDE_RIGHT ? FL_SIDE_LEFT : FL_SIDE_UNKNOWN;
        } else if (b->side == FL_SIDE_UNKNOWN) {
            b->side = a->side == FL_SIDE_LEFT ? FL_SIDE_RIGHT : FL_SIDE_UNKNOWN;
        }
    }
    return out->n;
}
