/*
 * src/vision/goal_white.c - white goal posts (the SPL field since 2015):
 * a white upright standing on the carpet in front of the field border;
 * see goal.h (fl_goal_find_white).
 *
 * Algorithm (the rules and their reasons: goal.h).  Per grid column: white
 * just above the border against the carpet below it.  Runs of such
 * columns (split where the border jumps), and within a run each white
 * stretch of a row above it, are candidates.  Per candidate: the foot (the
 * column walked down through a shaded foot), the scanner's border there,
 * the width against the width of a post at the foot's range, the carpet
 * beside it at or above the foot, the climb up the column and, where the
 * white ends, the crossbar beside it (the top and the side).
 *
 * White relative to the field: luma >= carpet + max(40, 2/5 of the
 * headroom 255 - carpet) for the climb (strict), carpet + max(20, 1/5 of
 * it) for candidates and widths (soft: the shaded edges of a round post),
 * chroma |Cb - 128| + |Cr - 128| <= 48 in both.  The carpet luma is
 * measured under the candidate's border, so shade and sunlight move the
 * threshold with the field.
 *
 * Invariant: every stored post passed the foot, width, carpet and height
 * checks;
 * no two stored posts overlap; n <= FL_GOAL_MAX_POSTS.
 * Memory: the caller's fl_posts_t; stack 696 B at the deepest (`make stack`:
 * through the camera's foot projection).
 * Cost: see goal.h (fl_goal_find_white): per grid column 7 pixel reads,
 * then at most WG_MAX_STRETCH candidates, WG_MAX_CAND of them climbed,
 * each bounded by the expected width and height of a post at its foot's
 * range.
 *
 * Scaling and overflow.  Pixels Q4 (< 2^17); ground mm < 2^15; the
 * distance from the camera sqrt(r^2 + h^2) in int64; expected sizes
 * focal_q4 * size / (16 dist) with focal < 2^20, size < 2^12 (int64).
 */
#include "fieldloc/goal.h"

#include <string.h>

/* Candidates climbed (past the foot, width and carpet tests: the walk up
 * the post and the crossbar), and white stretches examined at all (each
 * at most up to those tests: a few runs bounded by the expected width and
 * two camera projections).  Most stretches of a cluttered frame (robots,
 * banners, the hall behind the field) end at the foot test; with one cap
 * for both they used it up before a post further right was reached. */
#define WG_MAX_CAND (8 * FL_GOAL_MAX_POSTS)
#define WG_MAX_STRETCH (4 * WG_MAX_CAND)

/* What every candidate of a frame shares. */
typedef struct {
    fl_posts_t *out;
    const fl_scan_t *s;
    const fl_image_t *img;
    const fl_camera_t *cam;
    int32_t diam, post_h;
    int32_t thr_hi, thr_lo;     /* strict / soft white luma of a candidate */
    int32_t thr_ft;             /* white of a shaded foot */
    int32_t climbed;            /* candidates past the carpet test */
} wg_ctx_t;

/* Luma and chroma distance |Cb - 128| + |Cr - 128| of one pixel (the
 * BT.601 conversion of src/base/image.c).  Luma 0 outside the image. */
static int32_t wg_luma(const fl_image_t *img, int32_t u, int32_t v, int32_t *chroma)
{
    const uint8_t *p;
    int32_t y, cb, cr;
    *chroma = 255;
    if (u < 0 || v < 0 || u >= img->width || v >= img->height)
        return 0;
    switch (img->format) {
    case FL_FMT_RGB888: {
        int32_t r, g, b;
        p = img->plane[0] + (size_t)v * (size_t)img->stride[0] + 3u * (size_t)u;
        r = p[0];
        g = p[1];
        b = p[2];
        y = (19595 * r + 38470 * g + 7471 * b + 32768) >> 16;
        cb = ((-11058 * r - 21710 * g + 32768 * b + (128 << 16) + 32768) >> 16) - 128;
        cr = ((32768 * r - 27439 * g - 5329 * b + (128 << 16) + 32768) >> 16) - 128;
        break;
    }
    case FL_FMT_YUYV422:
        p = img->plane[0] + (size_t)v * (size_t)img->stride[0] + 4u * (size_t)(u >> 1);
        y = p[(u & 1) * 2];
        cb = p[1] - 128;
        cr = p[3] - 128;
        break;
    case FL_FMT_YCBCR_PLANAR:
        y = img->plane[0][(size_t)v * (size_t)img->stride[0] + (size_t)u];
        cb = img->plane[1][(size_t)v * (size_t)img->stride[1] + (size_t)u] - 128;
        cr = img->plane[2][(size_t)v * (size_t)img->stride[2] + (size_t)u] - 128;
        break;
    default:
        return 0;
    }
    *chroma = (cb < 0 ? -cb : cb) + (cr < 0 ? -cr : cr);
    return y;
}

/* Luma only (0 outside the image): the cheap test most reads end at. */
static int32_t wg_y(const fl_image_t *img, int32_t u, int32_t v)
{
    const uint8_t *p;
    if (u < 0 || v < 0 || u >= img->width || v >= img->height)
        return 0;
    p = img->plane[0] + (size_t)v * (size_t)img->stride[0];
    switch (img->format) {
    case FL_FMT_RGB888:
        p += 3u * (size_t)u;
        return (19595 * p[0] + 38470 * p[1] + 7471 * p[2] + 32768) >> 16;
    case FL_FMT_YUYV422:
        return p[4u * (size_t)(u >> 1) + (size_t)((u & 1) * 2)];
    case FL_FMT_YCBCR_PLANAR:
        return p[u];
    default:
        return 0;
    }
}

/* White at luma threshold thr (and low chroma): the chroma only for
 * pixels bright enough (most reads end at the luma). */
static bool wg_white(const fl_image_t *img, int32_t u, int32_t v, int32_t thr)
{
    const uint8_t *p;
    int32_t cb, cr;
    if (u < 0 || v < 0 || u >= img->width || v >= img->height)
        return false;
    p = img->plane[0] + (size_t)v * (size_t)img->stride[0];
    switch (img->format) {
    case FL_FMT_RGB888: {
        int32_t r, g, b;
        p += 3u * (size_t)u;
        r = p[0];
        g = p[1];
        b = p[2];
        if (((19595 * r + 38470 * g + 7471 * b + 32768) >> 16) < thr)
            return false;
        cb = ((-11058 * r - 21710 * g + 32768 * b + (128 << 16) + 32768) >> 16) - 128;
        cr = ((32768 * r - 27439 * g - 5329 * b + (128 << 16) + 32768) >> 16) - 128;
        break;
    }
    case FL_FMT_YUYV422:
        p += 4u * (size_t)(u >> 1);
        if (p[(u & 1) * 2] < thr)
            return false;
        cb = p[1] - 128;
        cr = p[3] - 128;
        break;
    case FL_FMT_YCBCR_PLANAR:
        if (p[u] < thr)
            return false;
        cb = img->plane[1][(size_t)v * (size_t)img->stride[1] + (size_t)u] - 128;
        cr = img->plane[2][(size_t)v * (size_t)img->stride[2] + (size_t)u] - 128;
        break;
    default:
        return false;
    }
    return (cb < 0 ? -cb : cb) + (cr < 0 ? -cr : cr) <= 48;
}

/* Strict and soft thresholds over a carpet luma. */
static void wg_thresholds(int32_t carpet, int32_t *hi, int32_t *lo)
{
    int32_t a = (255 - carpet) * 2 / 5, b = (255 - carpet) / 5;
    *hi = carpet + (a > 40 ? a : 40);
    *lo = carpet + (b > 20 ? b : 20);
}

/* Horizontal white run (luma >= thr) through (u, v), at most lim px each
 * way: its width (0 when (u, v) is not white), ends into lohi. */
static int32_t wg_hrun(const wg_ctx_t *c, int32_t u, int32_t v, int32_t lim, int32_t thr,
                       int32_t lohi[2])
{
    int32_t a = u, b = u, k;
    if (!wg_white(c->img, u, v, thr))
        return 0;
    for (k = 0; k < lim && wg_white(c->img, a - 1, v, thr); k++)
        a--;
    for (k = 0; k < lim && wg_white(c->img, b + 1, v, thr); k++)
        b++;
    lohi[0] = a;
    lohi[1] = b;
    return b - a + 1;
}

/* Distance from the camera (mm) to a ground point at range r at height
 * z_mm; 0 without a camera. */
static int64_t wg_dist(const fl_camera_t *cam, int32_t r, int32_t z_mm)
{
    int64_t hz = cam->pos_q4[2] / 16 - z_mm;
    return (int64_t)fl_isqrt64((uint64_t)((int64_t)r * r + hz * hz));
}

/* Step of wg_candidate: the climb up column u from the post's bottom row
 * pb, from the probe row vb above its shaded foot (strict white: a
 * robot's grey knee is not; gaps of 2 rows bridged), at most 1.6 expected
 * heights h_exp.  Into res: [0] the highest white row reached, [1] 1 when
 * the white ended below that limit (0: it went on, strict or, for 2 widths
 * above, soft on 2 rows of 3), [2] narrow rows (no
 * wider than 1.6 widths) and [3] measured rows (every 2nd) in the lower
 * 40 % of h_exp. */
static void wg_climb(const wg_ctx_t *c, int32_t u, int32_t pb, int32_t vb, int32_t w,
                     int32_t h_exp, int32_t res[4])
{
    int32_t v, gap = 0, lim = 2 * w + 4, vmin = pb - h_exp * 8 / 5;
    res[0] = pb;
    res[1] = 0;
    res[2] = 0;
    res[3] = 0;
    if (vmin < 0)
        vmin = 0;
    for (v = (vb < pb ? vb : pb - 1); v >= vmin; v--) {
        int32_t ab[2], rw;
        if (!wg_white(c->img, u, v, c->thr_hi) && !wg_white(c->img, u + 1, v, c->thr_hi) &&
            !wg_white(c->img, u - 1, v, c->thr_hi)) {
            if (++gap > 2) {
                res[1] = 1;
                break;
            }
            continue;
        }
        gap = 0;
        res[0] = v;
        if (((pb - v) & 1) != 0 || (pb - v) * 5 > h_exp * 2)
            continue;
        rw = wg_hrun(c, u, v, lim, c->thr_hi, ab);
        if (rw > 0 && rw * 10 <= w * 16 + 20)
            res[2]++;
        res[3]++;
    }
    if (res[1]) {
        /* a shaded stretch of the post (soft white on most rows of the
         * next 2 widths) has not ended it; a robot's jersey has */
        int32_t n = 0, m = 0;
        for (v = res[0] - 1; v >= 0 && v >= res[0] - 2 * w - 4; v--, m++)
            if (wg_white(c->img, u, v, c->thr_lo))
                n++;
        if (m > 0 && n * 3 >= m * 2)
            res[1] = 0;
    }
}

/* Step of wg_candidate: the crossbar at the top row vt: at 1.5, 2.5 and
 * 3.5 widths beside the post, soft white at vt and not one width above it
 * (a bar, not a white background).  Returns 3 for a bar on one side with
 * no white on the other: the post's side (FL_SIDE_LEFT: the bar to the
 * right, the left post facing the goal); 0 for white on both sides or a
 * white background (no answer); -1: no bar (a robot's head or shoulders
 * reach 2 widths). */
static int32_t wg_bar(const wg_ctx_t *c, int32_t u, int32_t vt, int32_t w, fl_side_t *side)
{
    int32_t k, d, n[2] = {0, 0}, bar[2] = {0, 0};
    *side = FL_SIDE_UNKNOWN;
    for (d = 0; d < 2; d++)
        for (k = 3; k <= 7; k += 2) {
            int32_t uu = u + (d ? k : -k) * w / 2;
            if (!wg_white(c->img, uu, vt, c->thr_lo))
                continue;
            n[d]++;
            if (!wg_white(c->img, uu, vt - w - 2, c->thr_lo))
                bar[d]++;
        }
    if (n[1] == 3 && bar[1] >= 2 && n[0] <= 1)
        *side = FL_SIDE_LEFT;
    else if (n[0] == 3 && bar[0] >= 2 && n[1] <= 1)
        *side = FL_SIDE_RIGHT;
    if (*side != FL_SIDE_UNKNOWN)
        return 3;
    return (n[0] >= 2 && n[1] >= 2) || n[0] - bar[0] >= 2 || n[1] - bar[1] >= 2 ? 0 : -1;
}

/* Step of wg_candidate: a post carries the crossbar at its top, so soft
 * white wider than 2.5 widths (the bar, or a white wall behind it) shows
 * somewhere 0.6-1.6 expected heights h_exp above its bottom row pb; an
 * upright that stays as narrow as the post there (at least 4 of the
 * measured rows, every 2nd, white) is a door or window frame.  Asked only
 * where that band lies in the image up to 1.2 h_exp (a near post's bar
 * may be above the image).  True: such a frame. */
static bool wg_frame(const wg_ctx_t *c, int32_t u, int32_t pb, int32_t w, int32_t h_exp)
{
    int32_t v, ab[2], n = 0;
    if (pb - h_exp * 12 / 10 < 0)
        return false;
    for (v = pb - h_exp * 6 / 10; v >= pb - h_exp * 16 / 10 && v >= 0; v -= 2) {
        int32_t rw = wg_hrun(c, u, v, 4 * w + 8, c->thr_lo, ab);
        if (rw * 2 > w * 5)
            return false;
        if (rw > 0)
            n++;
    }
    return n >= 4;
}

/* Step of wg_candidate: the lowest row of the post above the goal line
 * beside its foot (which joins its lowest rows).  From the white's lowest
 * row foot_v up to vb: rows wider than 1.6 w0 + 2 (w0: the post's width
 * at vb) are the line (counted into *nline).  Returns that row (vb when
 * no row is narrow). */
static int32_t wg_bottom(const wg_ctx_t *c, int32_t u, int32_t foot_v, int32_t vb,
                         int32_t w0, int32_t *nline)
{
    int32_t v, ab[2], lim = (w0 * 16 + 20) / 10 + 1;  /* enough to tell "wider" */
    *nline = 0;
    for (v = foot_v; v > vb; v--) {
        int32_t rw = wg_hrun(c, u, v, lim, c->thr_lo, ab);
        if (rw > 0 && rw * 10 <= w0 * 16 + 20)
            return v;
        if (rw > 0)
            (*nline)++;
    }
    return vb;
}

/* Step of wg_candidate: ground point and range of the foot pixel (the
 * front of the post: the centre is half a diameter further along the ray);
 * sets p->foot_* and p->ground.  False without a ground point. */
static bool wg_ground(const wg_ctx_t *c, fl_post_t *p, int32_t u_q4, int32_t v_px)
{
    p->foot_u_q4 = u_q4;
    p->foot_v_q4 = v_px * 16 + 8;
    if (!fl_camera_foot_to_centre(c->cam, &p->foot_u_q4, &p->foot_v_q4, c->diam, &p->ground))
        return false;
    fl_polar_from_point(p->ground, &p->range_mm, &p->bearing);
    return p->range_mm > 0;
}

/* Step of wg_candidate: the post stands on the field: the border of the
 * columns 1 width + 2 cells beside it lies at or above its bottom row pb
 * (on the SPL field it lies well above: the post hides the carpet strip
 * behind it; a lab with a narrow border has the feet on the carpet's
 * edge).  A white thing beyond the carpet stands above that border. */
static bool wg_notch(const wg_ctx_t *c, int32_t u, int32_t pb, int32_t w)
{
    const fl_scan_t *s = c->s;
    int32_t k, ok = 0, seen = 0, cs = s->params.col_step;
    for (k = -1; k <= 1; k += 2) {
        int32_t uu = u + k * (w + 2 * cs + 2), ic = uu / cs;
        if (uu < 0 || ic >= s->cols || s->border_v[ic] >= s->height)
            continue;
        seen++;
        if (s->border_v[ic] <= pb + 2 + 2 * s->params.row_step)
            ok++;
    }
    return seen > 0 && ok == seen;
}

/* Step of wg_candidate: the post's width: of the soft white runs (at
 * most lim px each way) on rows pb - 1, pb - 3, pb - 5 and at 10, 20 and
 * 30 % of the expected height h_exp above pb, the one nearest the
 * expected width w_exp (a goal's ground frame, a net or a banner beside a
 * post widen some rows, never all); its ends into lohi; 0 when none. */
static int32_t wg_width(const wg_ctx_t *c, int32_t u, int32_t pb, int32_t lim, int32_t w_exp,
                        int32_t h_exp, int32_t lohi[2])
{
    int32_t k, best = 0, bd = 0;
    for (k = 0; k < 6; k++) {
        int32_t lh[2], d, r = k < 3 ? pb - 1 - 2 * k : pb - h_exp * (k - 2) / 10;
        int32_t rw = wg_hrun(c, u, r, lim, c->thr_lo, lh);
        if (rw <= 0)
            continue;
        d = rw > w_exp ? rw - w_exp : w_exp - rw;
        if (best == 0 || d < bd) {
            best = rw;
            bd = d;
            lohi[0] = lh[0];
            lohi[1] = lh[1];
        }
    }
    return best;
}

/* Step of wg_candidate: the chroma of the carpet below the border of
 * column u (the darkest of the rows 2, 5 and 9 px down, as wg_column). */
static int32_t wg_carpet_chroma(const wg_ctx_t *c, int32_t u)
{
    const fl_scan_t *s = c->s;
    int32_t b = s->border_v[u / s->params.col_step], k, best = 256, chroma = 0;
    for (k = 2; k <= 9; k += k < 5 ? 3 : 4) {
        int32_t ch, y = b + k < s->height ? wg_luma(c->img, u, b + k, &ch) : 256;
        if (y < best) {
            best = y;
            chroma = ch;
        }
    }
    return chroma;
}

/* Step of wg_candidate: the lowest row of the post in column u below vb
 * (1-px gaps bridged; at most 6 px below the column's border): white at
 * the foot's threshold, or grey (a shaded foot: brighter than the carpet
 * with less than half its chroma). */
static int32_t wg_foot(const wg_ctx_t *c, int32_t u, int32_t vb, int32_t carpet)
{
    int32_t v, gap = 0, foot_v = vb, k = wg_carpet_chroma(c, u);
    /* the foot lies at most 4 px below the border of its column (checked
     * by the caller): the walk ends past that */
    int32_t vmax = c->s->border_v[u / c->s->params.col_step] + 6;
    if (vmax > c->img->height)
        vmax = c->img->height;
    for (v = vb + 1; v < vmax; v++) {
        int32_t ch, y = wg_luma(c->img, u, v, &ch);
        if ((y >= c->thr_ft && ch <= 48) || (y >= carpet + 8 && ch * 2 < k)) {
            foot_v = v;
            gap = 0;
        } else if (++gap > 1) {
            break;
        }
    }
    return foot_v;
}

/* One candidate: white just above the border in image columns u0..u1
 * (px); vb a row of it, carpet luma `carpet`. */
static void wg_candidate(wg_ctx_t *c, int32_t u0, int32_t u1, int32_t vb, int32_t carpet)
{
    fl_posts_t *out = c->out;
    const fl_camera_t *cam = c->cam;
    int32_t u, k, foot_v, pb, nline, ab[2], w, lim, h_exp, w_exp, cl[4], top;
    int64_t dist;
    fl_side_t side;
    fl_post_t p;
    out->candidates++;
    wg_thresholds(carpet, &c->thr_hi, &c->thr_lo);
    u = (u0 + u1) / 2;
    for (k = 0; k <= (u1 - u0) / 2 + 1; k++) {
        if (wg_white(c->img, u + k, vb, c->thr_lo)) { u += k; break; }
        if (wg_white(c->img, u - k, vb, c->thr_lo)) { u -= k; break; }
    }
    lim = u1 - u0 + 8;
    w = wg_hrun(c, u, vb, lim, c->thr_lo, ab);
    if (w == 0)
        return;
    u = (ab[0] + ab[1]) / 2;
    c->thr_ft = carpet + ((255 - carpet) / 8 > 16 ? (255 - carpet) / 8 : 16);
    foot_v = wg_foot(c, u, vb, carpet);
    if (foot_v >= c->img->height - 2)
        return;                 /* foot not seen */
    /* the scanner's border of the foot's column is the foot (or the far
     * edge of a goal line under it, about half a width lower) */
    k = c->s->border_v[u / c->s->params.col_step];
    if (foot_v < k - 4 - w / 2 || foot_v > k + 4) {
        out->rejected_border++;
        return;
    }
    /* the widest a post can be at the foot's range (runs are cut there:
     * a white wall costs no more than a post) */
    memset(&p, 0, sizeof p);
    if (!wg_ground(c, &p, u * 16 + 8, foot_v))
        return;
    dist = wg_dist(cam, p.range_mm, 0);
    w_exp = dist > 0 ? (int32_t)((int64_t)cam->model.focal_q4 * c->diam / (16 * dist)) : 0;
    lim = (w_exp * 17 + 20) / 10 + 2;
    dist = wg_dist(cam, p.range_mm, c->post_h / 2);
    h_exp = dist > 0 ? (int32_t)((int64_t)cam->model.focal_q4 * c->post_h / (16 * dist)) : 0;
    /* the width above the foot */
    pb = wg_bottom(c, u, foot_v, vb, w < lim ? w : lim, &nline);
    w = wg_width(c, u, pb, lim, w_exp, h_exp, ab);
    if (w <= 0)
        return;
    if (u != (ab[0] + ab[1]) / 2) {
        /* the first column was off centre (a shaded stripe of a round
         * post cuts a run): the foot again from the middle */
        u = (ab[0] + ab[1]) / 2;
        foot_v = wg_foot(c, u, vb, carpet);
    }
    memset(&p, 0, sizeof p);
    /* the lowest row in the column is the foot; but where a goal line
     * shows under the post (every row below its lowest narrow row pb is
     * wide: a dark, shaded foot is not), the post meets the field at the
     * line's far edge */
    k = nline >= 2 && nline >= foot_v - pb ? pb + 1 : foot_v;
    if (!wg_ground(c, &p, (ab[0] + ab[1]) * 8 + 8, k))
        return;
    /* the width a post of the field's diameter has at this range */
    dist = wg_dist(cam, p.range_mm, 0);
    w_exp = dist > 0 ? (int32_t)((int64_t)cam->model.focal_q4 * c->diam / (16 * dist)) : 0;
    if (w * 2 + 4 < w_exp || w * 10 > w_exp * 17 + 20) {
        out->rejected_shape++;
        return;
    }
    if (!wg_notch(c, u, pb, w)) {
        out->rejected_border++;
        return;
    }
    c->climbed++;
    /* the height a post has here */
    dist = wg_dist(cam, p.range_mm, c->post_h / 2);
    h_exp = dist > 0 ? (int32_t)((int64_t)cam->model.focal_q4 * c->post_h / (16 * dist)) : 0;
    wg_climb(c, u, pb, vb, w, h_exp, cl);
    /* where the white ends inside the image at a post's height (0.4-1.4
     * of it: the foot's range errs with the body's tilt), a crossbar: it
     * gives the top and the side, and a white end without one is a robot
     * (head, shoulders) or clutter; white on both sides (a white
     * background) asks for 0.85 of the height (a robot is 0.72 of a
     * post).  Where the white goes on or leaves the image, 0.7 of the
     * height suffices. */
    side = FL_SIDE_UNKNOWN;
    top = -1;
    k = pb - cl[0];
    if (cl[1] && cl[0] > 1 && k * 10 >= h_exp * 4 && k * 10 <= h_exp * 14) {
        int32_t bar = wg_bar(c, u, cl[0] + (w + 1) / 2, w, &side);
        if (bar < 0 || (bar == 0 && k * 10 < h_exp * 8)) {
            out->rejected_shape++;
            return;
        }
        if (bar > 0)
            top = cl[0];
    } else if (cl[0] > 1 && k * 10 < h_exp * 7) {
        out->rejected_shape++;
        return;
    }
    if (cl[2] * 4 < cl[3]) {      /* the lower part as narrow as the foot */
        out->rejected_shape++;
        return;
    }
    if (wg_frame(c, u, pb, w, h_exp)) {
        out->rejected_shape++;
        return;
    }
    p.width_q4 = w * 16;
    p.foot_visible = true;
    p.top_visible = top > 0;
    p.top_u_q4 = u * 16 + 8;
    p.top_v_q4 = top > 0 ? top * 16 : 0;
    p.confidence = 200;
    p.side = side;
    for (k = 0; k < out->n; k++) {
        int32_t d = out->post[k].foot_u_q4 - p.foot_u_q4;
        if ((d < 0 ? -d : d) < p.width_q4 + out->post[k].width_q4)
            return;
    }
    if (out->n >= FL_GOAL_MAX_POSTS) {
        out->dropped++;
        return;
    }
    out->post[out->n++] = p;
}

/* Candidate test of grid column i: white (soft: the foot of a post is
 * often shaded) at 2 of the rows 3, 6, 10 and 16 px above its border
 * against the carpet 2, 5 or 9 px below (the darkest).  Returns the carpet luma (the second
 * lowest white probe row, above a line beside the foot, into *vb), or -1. */
static int32_t wg_column(const wg_ctx_t *c, int32_t i, int32_t *vb)
{
    static const int32_t probe[4] = {3, 6, 10, 16};
    const fl_scan_t *s = c->s;
    int32_t b = s->border_v[i], u = i * s->params.col_step, carpet, hi, lo, k, n = 0;
    if (b < 4 || b + 2 >= s->height)
        return -1;
    /* the darkest of 3 rows below the border: a goal line under a post's
     * foot is no carpet */
    carpet = wg_y(c->img, u, b + 2);
    for (k = 5; k <= 9; k += 4) {
        int32_t y = b + k < s->height ? wg_y(c->img, u, b + k) : 255;
        if (y < carpet)
            carpet = y;
    }
    wg_thresholds(carpet, &hi, &lo);
    *vb = -1;
    for (k = 0; k < 4 && b - probe[k] >= 0; k++)
        if (wg_white(c->img, u, b - probe[k], lo) && ++n == 2)
            *vb = b - probe[k];
    return n >= 2 ? carpet : -1;
}

/* A run of candidate grid columns start..last: each white stretch of a
 * row just above its probe row vb (two posts, or a post and the goal's
 * rear frame, may share a run) examined while under the cap, the rest
 * counted. */
static void wg_flush(wg_ctx_t *c, int32_t start, int32_t last, int32_t vb, int32_t carpet)
{
    const fl_scan_t *s = c->s;
    int32_t cs = s->params.col_step, u, u1 = last * cs + cs - 1, a = -1, hi, lo, vs;
    if (vb < 0)
        vb = s->border_v[(start + last) / 2] - 3;
    if (vb < 0)
        return;
    wg_thresholds(carpet, &hi, &lo);
    if (u1 >= c->img->width)
        u1 = c->img->width - 1;
    /* the stretches 8 px above the probe row: clear of a goal's ground
     * frame joining its posts */
    vs = vb >= 8 ? vb - 8 : vb;
    for (u = start * cs; u <= u1 + 1; u++) {
        bool wh = u <= u1 && wg_white(c->img, u, vs, lo);
        if (wh && a < 0)
            a = u;
        if (wh || a < 0)
            continue;
        if (c->out->candidates >= WG_MAX_STRETCH || c->climbed >= WG_MAX_CAND) {
            c->out->dropped++;
            return;
        }
        if ((u - a) * 6 <= c->img->width)
            wg_candidate(c, a, u - 1, vs, carpet);
        else
            c->out->rejected_shape++;   /* a white wall or floor: too wide */
        a = -1;
    }
}

int32_t fl_goal_find_white(fl_posts_t *out, const fl_scan_t *scan,
                           const fl_image_t *img, const fl_camera_t *camera,
                           const fl_field_t *field)
{
    int32_t i, start = -1, last = -1, csum = 0, cn = 0, vb, run_vb = -1;
    wg_ctx_t ctx;
    if (!out)
        return 0;
    memset(out, 0, sizeof *out);
    if (!scan || scan->width <= 0 || scan->cols <= 0 || !img || !camera ||
        img->width != scan->width || img->height != scan->height ||
        camera->model.focal_q4 <= 0)
        return 0;
    memset(&ctx, 0, sizeof ctx);
    ctx.out = out;
    ctx.s = scan;
    ctx.img = img;
    ctx.cam = camera;
    ctx.diam = field && field->post_diameter_mm > 0 ? field->post_diameter_mm : 100;
    ctx.post_h = field && field->post_height_mm > 0 ? field->post_height_mm : 800;
    for (i = 0; i <= scan->cols; i++) {
        int32_t carpet = i < scan->cols ? wg_column(&ctx, i, &vb) : -1;
        /* a post's columns share its foot row: a jump of the border ends
         * a run (a post in front of a bright floor band) */
        if (carpet >= 0 && start >= 0 &&
            (scan->border_v[i] - scan->border_v[last] > 3 ||
             scan->border_v[last] - scan->border_v[i] > 3)) {
            wg_flush(&ctx, start, last, run_vb, csum / cn);
            start = -1;
        }
        if (carpet >= 0) {
            if (start < 0) {
                start = i;
                csum = cn = 0;
                run_vb = -1;
            }
            if (vb > run_vb)
                run_vb = vb;
            last = i;
            csum += carpet;
            cn++;
        } else if (start >= 0 && (i - last > 1 || i == scan->cols)) {
            wg_flush(&ctx, start, last, run_vb, csum / cn);
            start = -1;
        }
    }
    /* two posts, sides unknown: order in the image */
    if (out->n == 2) {
        fl_post_t *a = &out->post[0], *b = &out->post[1];
        if (a->side == FL_SIDE_UNKNOWN && b->side == FL_SIDE_UNKNOWN) {
            a->side = FL_SIDE_LEFT;
            b->side = FL_SIDE_RIGHT;
        } else if (a->side == FL_SIDE_UNKNOWN) {
            a->side = b->side == FL_SIDE_RIGHT ? FL_SIDE_LEFT : FL_SIDE_UNKNOWN;
        } else if (b->side == FL_SIDE_UNKNOWN) {
            b->side = a->side == FL_SIDE_LEFT ? FL_SIDE_RIGHT : FL_SIDE_UNKNOWN;
        }
    }
    return out->n;
}
