/*
 * src/vision/lines.c - line points and line segments (seed 000, section 3.6 and
 * Algorithm 1); see lines.h for the method.
 *
 * Algorithm.
 *   points   every m-th grid row of the scanner's class map is read 32
 *            cells at a time (white masks), every m-th grid column cell by
 *            cell from its border down; each white run closed by non-white
 *            cells, with green beside it and a width that passes the
 *            projected-width check (a per-row table from the camera,
 *            FL_LINES_WTAB knots, interpolated) becomes a point (Q1).
 *   luma     with the image: the same scan lines in the band of rows where
 *            the projected width is at most luma_width_px, read in luma
 *            (one pass per scan line into lum_buf); ridge runs with
 *            carpet flanks and no class-map white nearby become points
 *            flagged FL_LINE_POINT_LUMA.  White checks that fall short in
 *            the band are retried as luma ridge checks across the path
 *            (a second line close beside on one flank tolerated:
 *            LN_RIDGE_NEAR).
 *   buckets  points are counting-sorted into square buckets of 2^bshift
 *            px >= gap_px, so the neighbours of a point within gap_px lie in
 *            the 3 x 3 buckets around it.
 *   growth   seed = first point not yet tried; grow the tail, then the
 *            head: candidates = unassigned points of other scan lines
 *            within gap_px, ahead of the end (positive projection on the
 *            segment direction) and within gap/2 of its line, ranked by
 *            distance + 3 x offset; the best FL_LINES_CANDIDATES are tried
 *            in order, each needs white_pct white cells on the way and must
 *            keep the error of equation 1 (line through the ends) within
 *            the threshold; then the outliers of the least-squares line are
 *            pruned and the end-to-end white check decides.
 *   merge    a kept segment is merged into the first stored segment that it
 *            extends (angle within ~6 deg or 3 px over the shorter piece,
 *            the shorter piece's ends within 3 px of the longer's line, gap
 *            <= merge_gap_px and white when longer than gap_px, summed
 *            squared error to the least-squares line within the
 *            threshold); a last pass merges stored pairs the same way (a
 *            line cut by an occluder).
 *   refit    total least squares from the second moments: direction
 *            1/2 atan2(2 Cuv, Cuu - Cvv), end points = extreme points
 *            projected on the fitted line; bulge = parabola fit of the
 *            points' offsets (ln_curvature).
 *
 * Invariant.  Every point belongs to at most one segment; point.seg is the
 * index of a stored segment or FL_LINES_NONE.  A stored segment has at
 * least min_points points (<= FL_LINES_SEG_MAX_POINTS) and its moments are
 * the exact sums over its points.
 *
 * Memory: the caller's fl_lines_t (see config.h; ~34 KB at the defaults,
 * the per-segment point list, the luma tables and scratch included: 3
 * bytes per image row).  Stack < 700 bytes.
 * Cost: points O(grid cells / m); luma points O(band rows x width / m):
 * every pixel of every m-th column in the band and of every m-th row of
 * the band read once (about 15 instructions per pixel from RGB, 5 from
 * YUYV or planar), plus at most 8 ridge tests per scan line; ridge checks
 * at most 256 x 33 samples of 5 pixels per frame (64 and a growth budget
 * of FL_LINES_MAX_POINTS / 2 checks once the points overflowed; stopping once the
 * threshold is out of reach); growth O(points x (3 x 3 bucket
 * occupancy + FL_LINES_CANDIDATES x gap samples)); merging O(segments^2)
 * cheap tests plus at most one white check per candidate pair; refit and
 * bulge O(points + segments).
 *
 * Scaling and overflow (segment error).  Point coordinates relative to the
 * segment's anchor (its seed), in half pixels shifted right by LN_MSHIFT
 * (0 for images up to 2048 px, 1 above), so |x|, |y| <= 2^12.  Moments over
 * n <= 1023 points: |sx| <= 2^22, sxx <= 2^34.  Growth (equation 1): the
 * error of the line through ends P, Q with normal (a, b) = (P_v - Q_v,
 * Q_u - P_u), |a|, |b| <= 2^13 after re-anchoring, c = a P_u + b P_v
 * (|c| <= 2^26):
 *     E (a^2 + b^2) = a^2 sxx + 2ab sxy + b^2 syy - 2c (a sx + b sy) + n c^2
 * each term below 2^61, the sum (exact, int64) below 2^63; compared with
 * threshold (a^2 + b^2) without a division.  Merging: the least-squares
 * error from the n-scaled central moments (< 2^45), see ln_sse_fit.
 */
#include "fieldloc/lines.h"

#include <string.h>

#if FL_IMAGE_MAX_DIM > 2048
#define LN_MSHIFT 1
#else
#define LN_MSHIFT 0
#endif

#define LN_SEEDED 0x80u   /* internal point flag: already used as a seed */

/* Per frame: white checks of the growth (real frames use about 1.5 per
 * point, random class noise 8) and points looked at per candidate search
 * (real frames: under 40 in the 3 x 3 buckets). */
#define LN_CHECK_BUDGET (2 * FL_LINES_MAX_POINTS)
#define LN_SEARCH_MAX 96
/* Clutter: a frame whose line points overflowed FL_LINES_MAX_POINTS (every
 * rendered fixture and UvA frame has at most a third of them; class noise
 * fills the table) gets a quarter of the growth's white checks and of the
 * ridge checks: a field frame never gets there, and the worst frame's
 * cost is mostly failed checks. */
#define LN_CLUTTER_BUDGET (FL_LINES_MAX_POINTS / 2)
#define LN_CLUTTER_RIDGE_BUDGET (LN_RIDGE_BUDGET / 4)

/* ---- small helpers --------------------------------------------------------- */

static int32_t ln_abs(int32_t a) { return a < 0 ? -a : a; }
static int64_t ln_abs64(int64_t a) { return a < 0 ? -a : a; }
static int32_t ln_clamp(int32_t x, int32_t lo, int32_t hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

void fl_lines_params_default(fl_lines_params_t *p)
{
    if (!p)
        return;
    p->step_px = 0;
    p->gap_px = 0;
    p->min_points = 3;
    p->min_len_px = 0;
    p->err_base_q2 = 16;
    p->err_point_q2 = 4;
    p->white_pct = 70;
    p->merge_gap_px = 0;
    p->max_width_pct = 400;
    p->min_width_pct = 25;
    p->luma_contrast_pct = 12;
    p->luma_width_px = 3;
}

static bool ln_params_ok(const fl_lines_params_t *p)
{
    return p->step_px >= 0 && p->step_px <= 64 &&
           (p->gap_px == 0 || (p->gap_px >= 2 && p->gap_px <= 255)) &&
           p->min_points >= 2 && p->min_points <= 255 &&
           p->min_len_px >= 0 && p->min_len_px <= 4096 &&
           p->err_base_q2 >= 0 && p->err_base_q2 <= 65535 &&
           p->err_point_q2 >= 0 && p->err_point_q2 <= 65535 &&
           p->white_pct >= 0 && p->white_pct <= 100 &&
           p->merge_gap_px >= 0 && p->merge_gap_px <= 4096 &&
           p->max_width_pct >= 100 && p->max_width_pct <= 2000 &&
           p->min_width_pct >= 0 && p->min_width_pct <= 100 &&
           p->luma_contrast_pct >= 0 && p->luma_contrast_pct <= 100 &&
           p->luma_width_px >= 1 && p->luma_width_px <= 16;
}

fl_status_t fl_lines_init(fl_lines_t *l, const fl_lines_params_t *p)
{
    if (!l || !p)
        return FL_ERR_NULL;
    memset(l, 0, sizeof *l);
    fl_lines_params_default(&l->params);
    if (!ln_params_ok(p))
        return FL_ERR_RANGE;
    l->params = *p;
    return FL_OK;
}

/* Effective step / gap for an image width. */
static void ln_effective(fl_lines_t *l, int32_t width)
{
    int32_t step = l->params.step_px;
    if (step <= 0) {
        step = width / 80;
        if (step < 2)
            step = 2;
    }
    l->step_px = step;
    l->gap_px = l->params.gap_px > 0 ? l->params.gap_px : 3 * step;
    if (l->gap_px > 255)
        l->gap_px = 255;
}

bool fl_lines_reset(fl_lines_t *l, int32_t width, int32_t height)
{
    if (!l)
        return false;
    l->n_points = 0;
    l->n_segments = 0;
    l->points_dropped = 0;
    l->runs_rejected = 0;
    l->segments_dropped = 0;
    l->merges = 0;
    l->white_checks = 0;
    l->checks_capped = 0;
    l->luma_points = 0;
    l->luma_capped = 0;
    l->ridge_checks = 0;
    l->img.width = l->img.height = 0;
    l->lum_vend = l->lum_hend = -1;
    l->line_width_mm = 0;
    l->bcols = l->brows = 0;
    if (width < 1 || height < 1 || width > FL_IMAGE_MAX_DIM ||
        height > FL_IMAGE_MAX_DIM) {
        l->width = l->height = 0;
        return false;
    }
    l->width = width;
    l->height = height;
    ln_effective(l, width);
    return true;
}

bool fl_lines_add_point(fl_lines_t *l, int32_t u_q1, int32_t v_q1,
                        int32_t width_px, uint8_t flags)
{
    fl_line_point_t *pt;
    if (!l || l->width <= 0)
        return false;
    if (u_q1 < 0 || v_q1 < 0 || u_q1 > 2 * (l->width - 1) ||
        v_q1 > 2 * (l->height - 1))
        return false;
    if (l->n_points >= FL_LINES_MAX_POINTS) {
        l->points_dropped++;
        return false;
    }
    pt = &l->points[l->n_points++];
    pt->u_q1 = (int16_t)u_q1;
    pt->v_q1 = (int16_t)v_q1;
    pt->width_px = (uint8_t)(width_px < 0 ? 0 : width_px > 255 ? 255 : width_px);
    pt->flags = (uint8_t)(flags & (FL_LINE_POINT_VERTICAL | FL_LINE_POINT_LUMA));
    pt->seg = FL_LINES_NONE;
    return true;
}

/* ---- class map access ------------------------------------------------------ */

static int32_t ln_cell(const fl_scan_t *s, int32_t i, int32_t j)
{
    uint64_t w;
    if (i < 0 || j < 0 || i >= s->cols || j >= s->rows)
        return FL_CLASS_OTHER;
    w = s->map[j][i >> 5];
    return (int32_t)((w >> (62 - 2 * (i & 31))) & 3u);
}

/* mode: the largest number of samples (1..4096), plus LN_STRICT for no
 * neighbour tolerance, plus LN_NEED(p) for callers that only compare the
 * result with p (1..100): the walk stops once p is out of reach and the
 * ratio so far (below p) is returned (six arguments: no stack-passed
 * ones). */
#define LN_STRICT 0x10000
#define LN_NEED(p) ((int32_t)(p) << 20)
static int32_t ln_white_pct(const fl_scan_t *scan, int32_t u0_q4, int32_t v0_q4,
                            int32_t u1_q4, int32_t v1_q4, int32_t mode);

int32_t fl_lines_white_pct(const fl_scan_t *scan, int32_t u0_q4,
                           int32_t v0_q4, int32_t u1_q4, int32_t v1_q4)
{
    return ln_white_pct(scan, u0_q4, v0_q4, u1_q4, v1_q4, 4096);
}

/* As fl_lines_white_pct with at most max_samples samples (evenly spread:
 * long paths are subsampled); strict: no neighbour tolerance (lines at
 * least two cells wide). */
static int32_t ln_white_pct(const fl_scan_t *scan, int32_t u0_q4, int32_t v0_q4,
                            int32_t u1_q4, int32_t v1_q4, int32_t mode)
{
    int32_t max_samples = mode & 0xffff;
    bool strict = (mode & LN_STRICT) != 0;
    int32_t need = (mode >> 20) & 127;
    int32_t cs, rs, gu0, gv0, gu1, gv1, du, dv, n, k, white = 0, inside = 0;
    int32_t su, sv, pu, pv;
    bool horiz;
    if (!scan)
        return 100;
    if (scan->width <= 0 || scan->cols <= 0)
        return 0;
    cs = scan->params.col_step;
    rs = scan->params.row_step;
    if (cs < 1 || rs < 1)
        return 0;
    /* grid coordinates, Q4 cells (inputs clamped to a sane range first) */
    u0_q4 = ln_clamp(u0_q4, -(1 << 17), 1 << 17);
    u1_q4 = ln_clamp(u1_q4, -(1 << 17), 1 << 17);
    v0_q4 = ln_clamp(v0_q4, -(1 << 17), 1 << 17);
    v1_q4 = ln_clamp(v1_q4, -(1 << 17), 1 << 17);
    gu0 = u0_q4 / cs;
    gu1 = u1_q4 / cs;
    gv0 = v0_q4 / rs;
    gv1 = v1_q4 / rs;
    du = gu1 - gu0;
    dv = gv1 - gv0;
    horiz = ln_abs(du) >= ln_abs(dv);
    n = (horiz ? ln_abs(du) : ln_abs(dv)) / 16;
    if (n > max_samples - 1)
        n = max_samples - 1;
    /* n + 1 samples from end 0 to end 1 in Q16 cell units */
    pu = gu0 * 4096;
    pv = gv0 * 4096;
    su = n > 0 ? du * 4096 / n : 0;
    sv = n > 0 ? dv * 4096 / n : 0;
    for (k = 0; k <= n; k++) {
        int32_t i = (pu + 32768) >> 16, j = (pv + 32768) >> 16;
        if (i >= 0 && j >= 0 && i < scan->cols && j < scan->rows) {
            inside++;
            if (ln_cell(scan, i, j) == FL_CLASS_WHITE)
                white++;
            else if (strict)
                ;
            else if (horiz ? (ln_cell(scan, i, j - 1) == FL_CLASS_WHITE ||
                              ln_cell(scan, i, j + 1) == FL_CLASS_WHITE)
                           : (ln_cell(scan, i - 1, j) == FL_CLASS_WHITE ||
                              ln_cell(scan, i + 1, j) == FL_CLASS_WHITE))
                white++;
        }
        /* early rejection: even all-white samples from here on stay below
         * need (the result is then below need, as the full walk's) */
        if (need > 0 && (white + n - k) * 100 < need * (n + 1))
            break;
        pu += su;
        pv += sv;
    }
    if (inside == 0)
        return 0;
    return white * 100 / (n + 1);
}

/* ---- projected line width per row ------------------------------------------ */

/* Knot k of the width table is row min(k << shift, height - 1).  Widths in
 * Q4 px of a line of lw mm: horizontal = lw * 128 / |g(cx + 8 px) - g(cx)|,
 * vertical = lw * 64 / |g(v + 4 px) - g(v)|; 0 where the row has no ground
 * point (unknown: only the cell bounds apply).  Saturated to int16. */
static void ln_width_table(fl_lines_t *l, const fl_camera_t *cam, int32_t lw)
{
    int32_t shift = 2, k, nk;
    while (((l->height - 1) >> shift) + 2 > FL_LINES_WTAB)
        shift++;
    l->wtab_shift = shift;
    nk = ((l->height - 1) >> shift) + 2;
    for (k = 0; k < nk; k++) {
        int32_t v = k << shift, wh = 0, wv = 0;
        fl_point_t g0, g1, g2;
        if (v > l->height - 1)
            v = l->height - 1;
        if (cam && lw > 0 &&
            fl_camera_pixel_to_ground(cam, cam->model.cx_q4, v * 16, &g0)) {
            if (fl_camera_pixel_to_ground(cam, cam->model.cx_q4 + 128, v * 16, &g1)) {
                uint32_t d = fl_hypot(g1.x_mm - g0.x_mm, g1.y_mm - g0.y_mm);
                wh = d > 0 ? (int32_t)((int64_t)lw * 128 / (int64_t)d) : 32767;
            }
            if (fl_camera_pixel_to_ground(cam, cam->model.cx_q4, v * 16 + 64, &g2)) {
                uint32_t d = fl_hypot(g2.x_mm - g0.x_mm, g2.y_mm - g0.y_mm);
                wv = d > 0 ? (int32_t)((int64_t)lw * 64 / (int64_t)d) : 32767;
            }
        }
        l->wtab_h_q4[k] = (int16_t)(wh > 32767 ? 32767 : wh);
        l->wtab_v_q4[k] = (int16_t)(wv > 32767 ? 32767 : wv);
    }
}

/* Interpolated projected width at pixel row v (Q4 px); 0 = unknown. */
static int32_t ln_width_at(const fl_lines_t *l, const int16_t *tab, int32_t v)
{
    int32_t k = v >> l->wtab_shift, f = v - (k << l->wtab_shift);
    int32_t a = tab[k], b = tab[k + 1];
    if (a == 0 || b == 0)
        return 0;
    return a + (((b - a) * f) >> l->wtab_shift);
}

int32_t fl_lines_width_q4(const fl_lines_t *l, int32_t v_px, bool vertical)
{
    if (!l || l->width <= 0 || l->line_width_mm <= 0 || v_px < 0 ||
        v_px >= l->height)
        return 0;
    return ln_width_at(l, vertical ? l->wtab_v_q4 : l->wtab_h_q4, v_px);
}

/* Does a white run of width_px (grid quantum q px) pass the check against
 * the projected width w_q4 (0 = unknown)? */
static bool ln_width_ok(const fl_lines_t *l, int32_t width_px, int32_t q,
                        int32_t w_q4)
{
    int32_t hi, lo;
    if (w_q4 <= 0)
        return true;
    hi = w_q4 * l->params.max_width_pct / 100 + 32 * q;
    lo = w_q4 * l->params.min_width_pct / 100 - 16 * q;
    return width_px * 16 <= hi && width_px * 16 >= lo;
}

/* ---- point extraction ------------------------------------------------------ */

static void ln_push(fl_lines_t *l, int32_t u_q1, int32_t v_q1, int32_t w,
                    uint8_t flags)
{
    fl_line_point_t *pt;
    if (l->n_points >= FL_LINES_MAX_POINTS) {
        l->points_dropped++;
        return;
    }
    pt = &l->points[l->n_points++];
    pt->u_q1 = (int16_t)u_q1;
    pt->v_q1 = (int16_t)v_q1;
    pt->width_px = (uint8_t)(w > 255 ? 255 : w);
    pt->flags = flags;
    pt->seg = FL_LINES_NONE;
}

/* A horizontal white run of cells i0..i1 on grid row j; w_q4: the row's
 * projected width (ln_width_at, once per row).  The width check comes
 * first: it is the cheaper one (and the one noise runs fail). */
static void ln_hrun(fl_lines_t *l, const fl_scan_t *s, int32_t i0, int32_t i1,
                    int32_t j, int32_t w_q4)
{
    int32_t cs = s->params.col_step, rs = s->params.row_step;
    int32_t w = (i1 - i0 + 1) * cs;
    if (i0 <= 0 || i1 >= s->cols - 1)
        return; /* not closed by a non-white cell on both sides */
    /* the width, then paint lies on carpet: green within two cells on one
     * side at least */
    if (!ln_width_ok(l, w, cs, w_q4) ||
        (ln_cell(s, i0 - 1, j) != FL_CLASS_GREEN && ln_cell(s, i0 - 2, j) != FL_CLASS_GREEN &&
         ln_cell(s, i1 + 1, j) != FL_CLASS_GREEN && ln_cell(s, i1 + 2, j) != FL_CLASS_GREEN)) {
        l->runs_rejected++;
        return;
    }
    ln_push(l, (i0 + i1) * cs, 2 * j * rs, w, 0);
}

/* A vertical white run of cells j0..j1 on grid column i. */
static void ln_vrun(fl_lines_t *l, const fl_scan_t *s, int32_t i, int32_t j0,
                    int32_t j1)
{
    int32_t cs = s->params.col_step, rs = s->params.row_step;
    int32_t w = (j1 - j0 + 1) * rs;
    if (j0 <= 0 || j1 >= s->rows - 1)
        return;
    /* width first (cheaper); green within two cells above (or the border
     * right above) or below */
    if (!ln_width_ok(l, w, rs, ln_width_at(l, l->wtab_v_q4, (j0 + j1) * rs / 2)) ||
        (ln_cell(s, i, j0 - 1) != FL_CLASS_GREEN && ln_cell(s, i, j0 - 2) != FL_CLASS_GREEN &&
         (j0 - 2) * rs >= s->border_v[i] &&
         ln_cell(s, i, j1 + 1) != FL_CLASS_GREEN && ln_cell(s, i, j1 + 2) != FL_CLASS_GREEN)) {
        l->runs_rejected++;
        return;
    }
    ln_push(l, 2 * i * cs, (j0 + j1) * rs, w, FL_LINE_POINT_VERTICAL);
}

/* ---- luma points ------------------------------------------------------------ */

/* Far away a painted line is a pixel or less across: blurred into the
 * carpet its color is no longer white (the class map calls it green or
 * other), yet its luma still stands out.  Along the same scan lines, in the
 * band of rows where the projected width is at most luma_width_px, a luma
 * ridge is a short run of pixels each brighter than both pixels d away (d
 * from the projected width across the scan line: 1 + 1.5 w, 2..6 px) by
 * luma_contrast_pct of the brighter one (at least 8 levels), whose width at
 * half its height is below d, with carpet-colored flanks (Cb, Cr below
 * grey: green dominates), a peak that is not yellow (its Cb not 16 below
 * the flanks') nor orange (Cr at most grey + 12), and that goes on in one
 * of the two pixel lines beside the scan line (ln_ridge_goes_on).  Ridges where the class map
 * already has white (within a cell) are left to the class-map points. */

#define LN_LUMA_PER_LINE 8   /* ridges looked at per scan line */
#define LN_LUMA_MAX (FL_LINES_MAX_POINTS / 8) /* luma points per frame */
#define LN_LUMA_DMAX 6       /* largest flank distance, px */
#define LN_RIDGE_SAMPLES 32  /* samples of a path's ridge check */
#define LN_RIDGE_BUDGET 256  /* ridge checks of the segment stage per frame */
/* Flag in ln_ridge_pct's need: a line close beside.  Only with line steps
 * of 3 px or more (images from 240 px wide): on the AIBO's 208x160 frames
 * (2 px steps) it changed the far goal-line and box segments so that the
 * localizer's heading drifted on simulate seeds 4-6 (2.6-3.0 -> 7.7-11.9
 * degrees RMSE; seeds 1-3 unaffected); why was not found. */
#define LN_RIDGE_NEAR 0x1000

/* The frame's budgets (see LN_CLUTTER_BUDGET). */
static int32_t ln_check_budget(const fl_lines_t *l)
{
    return l->points_dropped > 0 ? LN_CLUTTER_BUDGET : LN_CHECK_BUDGET;
}

static int32_t ln_ridge_budget(const fl_lines_t *l)
{
    return l->points_dropped > 0 ? LN_CLUTTER_RIDGE_BUDGET : LN_RIDGE_BUDGET;
}

/* Offset of pixel (u, v) in plane 0 and the bytes per step along u. */
static inline int32_t ln_px_off(const fl_image_t *im, int32_t u, int32_t v)
{
    int32_t bpp = im->format == FL_FMT_RGB888 ? 3 : im->format == FL_FMT_YUYV422 ? 2 : 1;
    return v * im->stride[0] + bpp * u;
}

/* Luma of a pixel inside a validated view: BT.601 from RGB (the integer
 * formula of image.c: Q16 weights summing to 2^16, products < 2^24), the
 * Y byte of the other formats. */
static inline int32_t ln_luma(const fl_image_t *im, int32_t u, int32_t v)
{
    const uint8_t *p = im->plane[0] + ln_px_off(im, u, v);
    if (im->format == FL_FMT_RGB888)
        return (19595 * p[0] + 38470 * p[1] + 7471 * p[2] + 32768) >> 16;
    return p[0];
}

/* Luma of a pixel, -1 outside the view. */
static inline int32_t ln_luma_at(const fl_image_t *im, int32_t u, int32_t v)
{
    if (u < 0 || v < 0 || u >= im->width || v >= im->height)
        return -1;
    return ln_luma(im, u, v);
}

/* Cb, Cr of a pixel inside a validated view (RGB: image.c's Q16 formula,
 * all terms non-negative after the offset, so >> is a plain floor). */
static void ln_chroma(const fl_image_t *im, int32_t u, int32_t v, int32_t *cb, int32_t *cr)
{
    const uint8_t *p;
    switch (im->format) {
    case FL_FMT_RGB888:
        p = im->plane[0] + ln_px_off(im, u, v);
        *cb = (-11058 * p[0] - 21710 * p[1] + 32768 * p[2] + (128 << 16) + 32768) >> 16;
        *cr = (32768 * p[0] - 27439 * p[1] - 5329 * p[2] + (128 << 16) + 32768) >> 16;
        break;
    case FL_FMT_YUYV422:
        p = im->plane[0] + v * im->stride[0] + 4 * (u >> 1);
        *cb = p[1];
        *cr = p[3];
        break;
    default:
        *cb = im->plane[1][v * im->stride[1] + u];
        *cr = im->plane[2][v * im->stride[2] + u];
        break;
    }
    if (*cb > 255)
        *cb = 255;
    if (*cr > 255)
        *cr = 255;
}

/* n lumas of a scan line into lum_buf[0..n-1]: pixel k at byte offset
 * off + k * step of plane 0 (every pixel inside the view; at most five
 * arguments however gcc splits l). */
static void ln_luma_fill(fl_lines_t *l, int32_t off, int32_t step, int32_t n)
{
    const uint8_t *p = l->img.plane[0];
    uint8_t *buf = l->lum_buf;
    int32_t k;
    if (l->img.format == FL_FMT_RGB888) {
        for (k = 0; k < n; k++, off += step)
            buf[k] = (uint8_t)((19595 * p[off] + 38470 * p[off + 1] + 7471 * p[off + 2] + 32768) >> 16);
    } else {
        for (k = 0; k < n; k++, off += step)
            buf[k] = p[off];
    }
}

/* Carpet color: green dominates (Cb and Cr below grey, together at least
 * 8 below). */
static bool ln_greenish(int32_t cb, int32_t cr)
{
    return cb < 128 && cr < 128 && cb + cr <= 248;
}

/* Does a ridge of luma pk stand out of the brighter flank f?  Scaling:
 * lumas 0..255, pct <= 100: products < 2^15 in int32. */
static bool ln_ridge(const fl_lines_t *l, int32_t pk, int32_t f)
{
    int32_t c = pk - f;
    return c >= 8 && c * 100 >= f * l->params.luma_contrast_pct;
}

/* One scan line's lumas are in lum_buf, position x (u on a row, v on a
 * column) at lum_buf[x - x0]; the run r0..r1 (positions) passed the ridge
 * test with flank distance d.  Check it and add its point.  The scan line
 * is column i (vertical) or row v = j * rs; pos = its fixed coordinate. */
typedef struct {
    int32_t x0, x1;       /* positions held in lum_buf */
    int32_t pos;          /* u of a column, v of a row (px) */
    int32_t cell;         /* grid column i / grid row j of the scan line */
    bool vertical;
} ln_sline_t;

/* Does the ridge at position k of a scan line go on in a parallel pixel
 * line beside it (offset -1 or +1 across the scan line; at k - 1, k or
 * k + 1 along it, flanks d away)?  A line does (it is at most 45 degrees
 * off the scan line's normal); most noise specks do not. */
static bool ln_ridge_goes_on(const fl_lines_t *l, const ln_sline_t *sl, int32_t k, int32_t d)
{
    const fl_image_t *im = &l->img;
    int32_t side, j;
    for (side = -1; side <= 1; side += 2) {
        bool found = false;
        for (j = -1; j <= 1 && !found; j++) {
            int32_t x = k + j, a, f1, f2;
            if (sl->vertical) {
                a = ln_luma_at(im, sl->pos + side, x);
                f1 = ln_luma_at(im, sl->pos + side, x - d);
                f2 = ln_luma_at(im, sl->pos + side, x + d);
            } else {
                a = ln_luma_at(im, x, sl->pos + side);
                f1 = ln_luma_at(im, x - d, sl->pos + side);
                f2 = ln_luma_at(im, x + d, sl->pos + side);
            }
            if (a >= 0 && f1 >= 0 && f2 >= 0 && ln_ridge(l, a, f1 > f2 ? f1 : f2))
                found = true;
        }
        if (found)
            return true;
    }
    return false;
}

static void ln_luma_run(fl_lines_t *l, const fl_scan_t *s, const ln_sline_t *sl,
                        int32_t r0, int32_t r1, int32_t d)
{
    const uint8_t *y = l->lum_buf;   /* position x at y[x - o] */
    const int32_t o = sl->x0;
    const fl_image_t *im = &l->img;
    int32_t k, pk, f, mid, e0, e1, x, cs = s->params.col_step, rs = s->params.row_step;
    int32_t cb1, cr1, cb2, cr2, cbk, crk, u, v;
    /* peak of the run and its flanks */
    k = r0;
    for (x = r0 + 1; x <= r1; x++)
        if (y[x - o] > y[k - o])
            k = x;
    if (k - d < sl->x0 || k + d > sl->x1)
        return;
    pk = y[k - o];
    f = y[k - d - o] > y[k + d - o] ? y[k - d - o] : y[k + d - o];
    /* width at half height */
    mid = (pk + f + 1) / 2;
    e0 = k;
    while (e0 - 1 > k - d && y[e0 - 1 - o] >= mid)
        e0--;
    e1 = k;
    while (e1 + 1 < k + d && y[e1 + 1 - o] >= mid)
        e1++;
    if (e1 - e0 + 1 > d - 1 && e1 - e0 + 1 > 1) {
        l->runs_rejected++;
        return;
    }
    /* left to the class map where it has white within a cell */
    if (sl->vertical) {
        for (x = e0 / rs - 1; x <= e1 / rs + 1; x++)
            if (ln_cell(s, sl->cell, x) == FL_CLASS_WHITE)
                return;
    } else {
        for (x = e0 / cs - 1; x <= e1 / cs + 1; x++)
            if (ln_cell(s, x, sl->cell) == FL_CLASS_WHITE)
                return;
    }
    /* carpet on both sides, neither yellow nor orange paint */
    u = sl->vertical ? sl->pos : k;
    v = sl->vertical ? k : sl->pos;
    ln_chroma(im, sl->vertical ? u : k - d, sl->vertical ? k - d : v, &cb1, &cr1);
    ln_chroma(im, sl->vertical ? u : k + d, sl->vertical ? k + d : v, &cb2, &cr2);
    ln_chroma(im, u, v, &cbk, &crk);
    if (!ln_greenish(cb1, cr1) || !ln_greenish(cb2, cr2) ||
        cbk + 16 < (cb1 < cb2 ? cb1 : cb2) || crk > 140 ||
        !ln_ridge_goes_on(l, sl, k, d)) { /* (last: a line, not a speck) */
        l->runs_rejected++;
        return;
    }
    if (l->luma_points >= LN_LUMA_MAX) {
        l->luma_capped++;
        return;
    }
    l->luma_points++;
    if (sl->vertical)
        ln_push(l, 2 * sl->pos, e0 + e1, e1 - e0 + 1,
                FL_LINE_POINT_VERTICAL | FL_LINE_POINT_LUMA);
    else
        ln_push(l, e0 + e1, 2 * sl->pos, e1 - e0 + 1, FL_LINE_POINT_LUMA);
}

/* Ridge runs of one scan line (lumas in lum_buf) between positions lo and
 * hi; dtab: flank distance per row (columns: by position; rows: dtab[0]
 * for the whole line); border: for a row, candidates only where the row
 * lies at most lum_above above the column's border. */
static void ln_luma_scan(fl_lines_t *l, const fl_scan_t *s, const ln_sline_t *sl,
                         int32_t lo, int32_t hi, const uint8_t *dtab)
{
    const uint8_t *y = l->lum_buf;   /* position x at y[x - o] */
    const int32_t o = sl->x0;
    int32_t x, start = -1, dr = 0, runs = 0, cs = s->params.col_step;
    for (x = lo; x <= hi + 1; x++) {
        bool on = false;
        int32_t d = sl->vertical ? dtab[x] : dtab[0];
        if (x <= hi && x - d >= sl->x0 && x + d <= sl->x1 &&
            (sl->vertical || sl->pos >= s->border_v[x / cs] - l->lum_above)) {
            int32_t f = y[x - d - o] > y[x + d - o] ? y[x - d - o] : y[x + d - o];
            on = ln_ridge(l, y[x - o], f);
        }
        if (on && start < 0) {
            start = x;
            dr = d;
        } else if (!on && start >= 0) {
            if (++runs > LN_LUMA_PER_LINE) {
                l->luma_capped++;
                return;
            }
            if (x - start <= dr)
                ln_luma_run(l, s, sl, start, x - 1, dr);
            start = -1;
        }
    }
}

/* Band and flank distances from the width table: rows (from the top)
 * whose projected width is known and at most luma_width_px. */
static void ln_luma_band(fl_lines_t *l)
{
    int32_t v, lim = 16 * l->params.luma_width_px;
    l->lum_vend = l->lum_hend = -1;
    l->lum_above = 2 + l->height / 120;
    for (v = 0; v < l->height; v++) {
        int32_t wv = ln_width_at(l, l->wtab_v_q4, v), wh = ln_width_at(l, l->wtab_h_q4, v);
        int32_t dv = 1 + (3 * wv + 31) / 32, dh = 1 + (3 * wh + 31) / 32;
        if (wv > 0 && wv <= lim)
            l->lum_vend = v;
        if (wh > 0 && wh <= lim)
            l->lum_hend = v;
        l->lum_dv[v] = (uint8_t)(dv < 2 ? 2 : dv > LN_LUMA_DMAX ? LN_LUMA_DMAX : dv);
        l->lum_dh[v] = (uint8_t)(dh < 2 ? 2 : dh > LN_LUMA_DMAX ? LN_LUMA_DMAX : dh);
    }
}

/* The luma points of a frame: every m-th column from lum_above above its
 * border to the band's end, every m-th row of the band. */
static void ln_luma_points(fl_lines_t *l, const fl_scan_t *s, int32_t mc, int32_t mr)
{
    int32_t cs = s->params.col_step, rs = s->params.row_step, i, j, top = l->height;
    ln_sline_t sl;
    ln_luma_band(l);
    for (i = mc / 2; i < s->cols && l->points_dropped == 0; i += mc) {
        int32_t bv = s->border_v[i], lo;
        if (bv >= l->height)
            continue;
        lo = bv - l->lum_above;
        if (lo < 0)
            lo = 0;
        if (lo < top)
            top = lo;
        if (lo > l->lum_vend)
            continue;
        sl.vertical = true;
        sl.cell = i;
        sl.pos = i * cs;
        sl.x0 = lo - LN_LUMA_DMAX < 0 ? 0 : lo - LN_LUMA_DMAX;
        sl.x1 = l->lum_vend + LN_LUMA_DMAX >= l->height ? l->height - 1
                                                        : l->lum_vend + LN_LUMA_DMAX;
        ln_luma_fill(l, ln_px_off(&l->img, sl.pos, sl.x0), l->img.stride[0], sl.x1 - sl.x0 + 1);
        ln_luma_scan(l, s, &sl, lo, l->lum_vend, l->lum_dv);
    }
    for (j = mr / 2; j < s->rows && l->points_dropped == 0; j += mr) {
        int32_t v = j * rs;
        if (v < top || v > l->lum_hend)
            continue;
        sl.vertical = false;
        sl.cell = j;
        sl.pos = v;
        sl.x0 = 0;
        sl.x1 = l->width - 1;
        ln_luma_fill(l, ln_px_off(&l->img, 0, v), ln_px_off(&l->img, 1, 0), l->width);
        ln_luma_scan(l, s, &sl, 0, l->width - 1, &l->lum_dh[v]);
    }
}

/* Percentage of 1 px samples (at most LN_RIDGE_SAMPLES, spread evenly) of the straight path between two
 * pixels (Q4) that lie on a luma ridge across the path: the brightest of
 * the sample and its two neighbours across stands out (ln_ridge) of the
 * brighter of the two pixels d + 1 away across (d from the projected width
 * across the path at its middle row).  0 outside the image or without
 * luma.  Stops early once `need` percent is out of reach (then the result
 * is some value below need).  need | LN_RIDGE_NEAR: a sample whose one
 * flank is bright (a second line close beside) also passes when the pixel
 * 1 or 2 px beside the peak on that side is dark and the other flank is
 * (at most 2 more pixel reads per failing sample).  Scaling: Q4 positions < 2^17, the unit normal in Q8, products
 * < 2^26 in int32. */
static int32_t ln_ridge_pct(const fl_lines_t *l, int32_t u0, int32_t v0, int32_t u1,
                            int32_t v1, int32_t need)
{
    const fl_image_t *im = &l->img;
    int32_t du = u1 - u0, dv = v1 - v0, len, n, k, pass = 0, nu, nv, wv, wh, w, d, vm;
    int32_t ou, ov, fu, fv, ru, rv, so, sf;
    /* (not on a 2 px line-step grid: see LN_RIDGE_NEAR) */
    bool near = (need & LN_RIDGE_NEAR) != 0 && l->step_px >= 3;
    need &= ~LN_RIDGE_NEAR;
    if (im->width <= 0 || l->params.luma_contrast_pct <= 0)
        return 0;
    len = (int32_t)fl_hypot(du, dv);
    if (len < 16)
        return 0;
    n = len / 16;
    if (n > LN_RIDGE_SAMPLES - 1)
        n = LN_RIDGE_SAMPLES - 1;
    nu = -dv * 256 / len;
    nv = du * 256 / len;
    vm = ((v0 + v1) / 2 + 8) >> 4;
    if (vm < 0 || vm >= l->height)
        return 0;
    wv = ln_width_at(l, l->wtab_v_q4, vm);
    wh = ln_width_at(l, l->wtab_h_q4, vm);
    w = (int32_t)(((int64_t)wv * ln_abs(du) + (int64_t)wh * ln_abs(dv)) / len);
    d = 2 + (3 * w + 31) / 32;
    if (d > LN_LUMA_DMAX + 1)
        d = LN_LUMA_DMAX + 1;
    ou = (nu + 128) >> 8;
    ov = (nv + 128) >> 8;
    fu = (d * nu + 128) >> 8;
    fv = (d * nv + 128) >> 8;
    /* the five pixels of a sample: p, p +- (ou, ov), p +- (fu, fv); where
     * all lie inside, read at byte offsets from p (ln_luma's formula) */
    ru = ln_abs(ou) > ln_abs(fu) ? ln_abs(ou) : ln_abs(fu);
    rv = ln_abs(ov) > ln_abs(fv) ? ln_abs(ov) : ln_abs(fv);
    so = ln_px_off(im, ou, ov);
    sf = ln_px_off(im, fu, fv);
    for (k = 0; k <= n; k++) {
        int32_t pu = (u0 + du * k / n + 8) >> 4, pv = (v0 + dv * k / n + 8) >> 4;
        int32_t a, b, c, f1, f2;
        if (pu - ru >= 0 && pv - rv >= 0 && pu + ru < im->width && pv + rv < im->height) {
            const uint8_t *q = im->plane[0] + ln_px_off(im, pu, pv);
            if (im->format == FL_FMT_RGB888) {
#define LN_Q_LUMA(o) ((19595 * q[(o)] + 38470 * q[(o) + 1] + 7471 * q[(o) + 2] + 32768) >> 16)
                a = LN_Q_LUMA(0);
                b = LN_Q_LUMA(so);
                c = LN_Q_LUMA(-so);
                f1 = LN_Q_LUMA(sf);
                f2 = LN_Q_LUMA(-sf);
#undef LN_Q_LUMA
            } else {
                a = q[0];
                b = q[so];
                c = q[-so];
                f1 = q[sf];
                f2 = q[-sf];
            }
        } else {
            a = ln_luma_at(im, pu, pv);
            b = ln_luma_at(im, pu + ou, pv + ov);
            c = ln_luma_at(im, pu - ou, pv - ov);
            f1 = ln_luma_at(im, pu + fu, pv + fv);
            f2 = ln_luma_at(im, pu - fu, pv - fv);
        }
        {
            int32_t o = 0; /* the peak's offset across: -1, 0, +1 */
            if (b > a) {
                a = b;
                o = 1;
            }
            if (c > a) {
                a = c;
                o = -1;
            }
            if (f1 >= 0 && f2 >= 0 && a >= 0 && ln_ridge(l, a, f1 > f2 ? f1 : f2)) {
                pass++;
                continue;
            }
            /* near: a second line close beside this one (a far goal box:
             * goal line and box front line 2-4 px apart) lies on one
             * flank; that side counts as dark when 1 or 2 px beside the
             * peak is, the other flank must be dark at d */
            if (near && d >= 3 && f1 >= 0 && f2 >= 0 && a >= 0 &&
                ln_ridge(l, a, f1 < f2 ? f1 : f2)) {
                int32_t side = f1 > f2 ? 1 : -1;
                int32_t g = ln_luma_at(im, pu + (((o + 2 * side) * nu + 128) >> 8),
                                       pv + (((o + 2 * side) * nv + 128) >> 8));
                int32_t g1 = ln_luma_at(im, pu + (((o + side) * nu + 128) >> 8),
                                        pv + (((o + side) * nv + 128) >> 8));
                if (g1 >= 0 && g1 < g)
                    g = g1;
                if (g >= 0 && ln_ridge(l, a, g)) {
                    pass++;
                    continue;
                }
            }
        }
        if ((pass + n - k) * 100 < need * (n + 1))
            break; /* need is out of reach: the ratio so far is below it */
    }
    return pass * 100 / (n + 1);
}

/* Does a path whose class-map white ratio is p fall back to the luma:
 * below white_pct, with an image, its middle row (Q4 ends) in the band? */
static bool ln_luma_path(const fl_lines_t *l, int32_t p, int32_t v0, int32_t v1)
{
    int32_t bend = l->lum_vend > l->lum_hend ? l->lum_vend : l->lum_hend;
    return p < l->params.white_pct && l->img.width > 0 && bend >= 0 &&
           (v0 + v1) / 32 <= bend;
}

/* Paint on the path, for a comparison with params.white_pct: the class
 * map's white ratio (thin-line tolerant, the walk stopping once white_pct
 * is out of reach, see ln_white_pct); where ln_luma_path, the luma ridge
 * ratio when higher (counted in ridge_checks).  Six arguments: a seventh
 * goes on the stack, a dynamic frame that make stack rejects. */
static int32_t ln_paint_pct(fl_lines_t *l, const fl_scan_t *scan, int32_t u0, int32_t v0,
                            int32_t u1, int32_t v1)
{
    int32_t p = ln_white_pct(scan, u0, v0, u1, v1, 4096 | LN_NEED(l->params.white_pct)), r;
    if (!scan || !ln_luma_path(l, p, v0, v1) || l->ridge_checks >= ln_ridge_budget(l))
        return p;
    l->ridge_checks++;
    r = ln_ridge_pct(l, u0, v0, u1, v1, l->params.white_pct | LN_RIDGE_NEAR);
    return r > p ? r : p;
}

int32_t fl_lines_paint_pct(const fl_lines_t *l, const fl_scan_t *scan, int32_t u0_q4,
                           int32_t v0_q4, int32_t u1_q4, int32_t v1_q4)
{
    int32_t p = fl_lines_white_pct(scan, u0_q4, v0_q4, u1_q4, v1_q4), r;
    if (!l || !scan || !ln_luma_path(l, p, v0_q4, v1_q4))
        return p;
    r = ln_ridge_pct(l, u0_q4, v0_q4, u1_q4, v1_q4, 0);
    return r > p ? r : p;
}

int32_t fl_lines_paint_beside_pct(const fl_lines_t *l, const fl_scan_t *scan, int32_t u0_q4,
                                  int32_t v0_q4, int32_t u1_q4, int32_t v1_q4)
{
    int32_t p = fl_lines_white_pct(scan, u0_q4, v0_q4, u1_q4, v1_q4), r;
    if (!l || !scan || !ln_luma_path(l, p, v0_q4, v1_q4))
        return p;
    r = ln_ridge_pct(l, u0_q4, v0_q4, u1_q4, v1_q4, LN_RIDGE_NEAR);
    return r > p ? r : p;
}

int32_t fl_lines_find_points(fl_lines_t *l, const fl_scan_t *scan,
                             const fl_image_t *img, const fl_camera_t *camera,
                             int32_t line_width_mm)
{
    int32_t cs, rs, mr, mc, i, j, w;
    if (!l)
        return 0;
    if (!scan || scan->width <= 0 || scan->cols <= 0 || scan->rows <= 0 ||
        !fl_lines_reset(l, scan->width, scan->height))
        return 0;
    cs = scan->params.col_step;
    rs = scan->params.row_step;
    if (cs < 1 || rs < 1)
        return 0;
    l->line_width_mm = camera && line_width_mm > 0 ? line_width_mm : 0;
    ln_width_table(l, camera, l->line_width_mm);
    mr = l->step_px / rs;
    mc = l->step_px / cs;
    if (mr < 1)
        mr = 1;
    if (mc < 1)
        mc = 1;

    /* horizontal scan lines: 32 cells per mask word.  Once a point was
     * dropped (the table is full) no later scan line can add one: the
     * scan stops there (points_dropped counts only what was seen so far) */
    for (j = mr / 2; j < scan->rows && l->points_dropped == 0; j += mr) {
        int32_t start = -1, wq4 = ln_width_at(l, l->wtab_h_q4, j * rs);
        for (w = 0; w < scan->words; w++) {
            uint32_t m = fl_scan_mask_word(scan, j, w, FL_CLASS_WHITE);
            int32_t b;
            if (m == 0u) {
                if (start >= 0) {
                    ln_hrun(l, scan, start, 32 * w - 1, j, wq4);
                    start = -1;
                }
                continue;
            }
            if (m == 0xffffffffu) {
                if (start < 0)
                    start = 32 * w;
                continue;
            }
            for (b = 0; b < 32; b++) {
                bool on = (m >> (31 - b)) & 1u;
                int32_t c = 32 * w + b;
                if (on && start < 0)
                    start = c;
                else if (!on && start >= 0) {
                    ln_hrun(l, scan, start, c - 1, j, wq4);
                    start = -1;
                }
            }
        }
        /* a run reaching the last cell is not closed: dropped */
    }

    /* vertical scan lines: from the border down */
    for (i = mc / 2; i < scan->cols && l->points_dropped == 0; i += mc) {
        int32_t start = -1, j0, bv = scan->border_v[i];
        const uint64_t *col;
        int32_t shift = 62 - 2 * (i & 31), word = i >> 5;
        if (bv >= scan->height)
            continue;
        j0 = (bv + rs - 1) / rs;
        if (j0 > 0)
            j0--; /* include the cell above the border (the run's top side) */
        for (j = j0; j < scan->rows; j++) {
            bool on;
            col = scan->map[j];
            on = ((col[word] >> shift) & 3u) == (uint64_t)FL_CLASS_WHITE;
            if (on && start < 0)
                start = j;
            else if (!on && start >= 0) {
                ln_vrun(l, scan, i, start, j - 1);
                start = -1;
            }
        }
    }
    /* thin far lines from the image's luma (needs the projected widths) */
    if (img && l->line_width_mm > 0 && l->params.luma_contrast_pct > 0 &&
        fl_image_validate(img) == FL_OK && img->width == scan->width &&
        img->height == scan->height) {
        l->img = *img;
        if (l->points_dropped == 0)
            ln_luma_points(l, scan, mc, mr);
        else
            ln_luma_band(l); /* the band of the ridge checks */
    }
    return l->n_points;
}

/* ---- bucket grid ----------------------------------------------------------- */

static void ln_buckets(fl_lines_t *l)
{
    int32_t shift = 2, nb, k;
    while ((1 << shift) < l->gap_px)
        shift++;
    for (;;) {
        l->bcols = ((l->width - 1) >> shift) + 1;
        l->brows = ((l->height - 1) >> shift) + 1;
        if (l->bcols * l->brows <= FL_LINES_MAX_BUCKETS)
            break;
        shift++;
    }
    l->bshift = shift;
    nb = l->bcols * l->brows;
    memset(l->bstart, 0, (size_t)(nb + 1) * sizeof l->bstart[0]);
    for (k = 0; k < l->n_points; k++) {
        const fl_line_point_t *p = &l->points[k];
        int32_t b = ((p->v_q1 >> 1) >> shift) * l->bcols + ((p->u_q1 >> 1) >> shift);
        l->bstart[b + 1]++;
    }
    for (k = 0; k < nb; k++)
        l->bstart[k + 1] = (uint16_t)(l->bstart[k + 1] + l->bstart[k]);
    /* stable fill; bstart[b] is advanced and restored below */
    for (k = 0; k < l->n_points; k++) {
        const fl_line_point_t *p = &l->points[k];
        int32_t b = ((p->v_q1 >> 1) >> shift) * l->bcols + ((p->u_q1 >> 1) >> shift);
        l->border[l->bstart[b]++] = (uint16_t)k;
    }
    for (k = nb; k > 0; k--)
        l->bstart[k] = l->bstart[k - 1];
    l->bstart[0] = 0;
}

int32_t fl_lines_points_near(const fl_lines_t *l, int32_t u_q1, int32_t v_q1,
                             int32_t ru_px, int32_t rv_px, uint16_t *ids)
{
    int32_t b0u, b1u, b0v, b1v, x, y, n = 0, ru, rv;
    if (!l || l->width <= 0 || l->bcols <= 0 || ru_px < 0 || rv_px < 0)
        return 0;
    if (u_q1 < 0 || v_q1 < 0 || u_q1 > 2 * (l->width - 1) || v_q1 > 2 * (l->height - 1))
        return 0;
    if (ru_px > l->width)
        ru_px = l->width;
    if (rv_px > l->height)
        rv_px = l->height;
    ru = 2 * ru_px;
    rv = 2 * rv_px;
    b0u = ((u_q1 - ru) < 0 ? 0 : (u_q1 - ru) >> 1) >> l->bshift;
    b1u = ((u_q1 + ru) >> 1) >> l->bshift;
    b0v = ((v_q1 - rv) < 0 ? 0 : (v_q1 - rv) >> 1) >> l->bshift;
    b1v = ((v_q1 + rv) >> 1) >> l->bshift;
    if (b1u >= l->bcols)
        b1u = l->bcols - 1;
    if (b1v >= l->brows)
        b1v = l->brows - 1;
    for (y = b0v; y <= b1v; y++) {
        for (x = b0u; x <= b1u; x++) {
            int32_t b = y * l->bcols + x, k;
            for (k = l->bstart[b]; k < l->bstart[b + 1]; k++) {
                const fl_line_point_t *p = &l->points[l->border[k]];
                int32_t du = p->u_q1 - u_q1, dv = p->v_q1 - v_q1;
                if (du > ru || du < -ru || dv > rv || dv < -rv)
                    continue;
                if (ids && n < FL_LINES_NEAR_MAX)
                    ids[n] = l->border[k];
                n++;
            }
        }
    }
    return n;
}

/* ---- segment error ------------------------------------------------------- */

typedef struct {
    int32_t n;
    int64_t sx, sy, sxx, syy, sxy;
} ln_mom_t;

/* Summed squared distance of the points (moments m) to their least-squares
 * line: the smaller eigenvalue of the scatter matrix,
 *     E = ((A + B) - sqrt((A - B)^2 + 4 C^2)) / (2 n)
 * with the n-scaled central moments A = n sxx - sx^2, B = n syy - sy^2,
 * C = n sxy - sx sy (exact int64: < 2^45).  A, B, C are shifted right
 * together by sh until below 2^30 so that the squares fit; the result is
 * then within 2^sh / n of the exact value (0.13 (px/2)^2 for a 500-point
 * line across a 640 px frame).  Units: (Q1 >> LN_MSHIFT)^2. */
static int64_t ln_sse_fit(const ln_mom_t *m)
{
    int64_t n = m->n, A, B, C, r;
    uint64_t q;
    int32_t sh = 0;
    if (n < 3)
        return 0;
    A = n * m->sxx - m->sx * m->sx;
    B = n * m->syy - m->sy * m->sy;
    C = n * m->sxy - m->sx * m->sy;
    while (A >= (1LL << 30) || B >= (1LL << 30) || ln_abs64(C) >= (1LL << 30)) {
        A >>= 1;
        B >>= 1;
        C >>= 1;
        sh++;
    }
    q = (uint64_t)((A - B) * (A - B)) + (uint64_t)(4 * C * C);
    r = (A + B) - (int64_t)fl_isqrt64(q);
    if (r < 0)
        r = 0;
    return (r << sh) / (2 * n);
}

/* Threshold (in the moment units: Q1 >> LN_MSHIFT, squared) for n points,
 * scaled by l->thr_q8 (Q8, 128..256: see ln_thin_q8); the unscaled sum
 * < 2^27, times 256 < 2^35 in int64, floored. */
static int64_t ln_thr(const fl_lines_t *l, int32_t n)
{
    int64_t t = (int64_t)l->params.err_base_q2 + (int64_t)n * l->params.err_point_q2;
    return ((t * l->thr_q8) >> 8) >> (2 * LN_MSHIFT);
}

/* Error scale for lines at pixel row v (Q8): the projected width (the
 * smaller of across and along, Q4) over 2 px, within 1/2..1; 1 when
 * unknown.  A far line a pixel wide gives points within half a pixel: the
 * allowance made for the run quantization of wide lines would let its
 * growth jump to a parallel line 2-3 px away. */
static int32_t ln_thin_q8(const fl_lines_t *l, int32_t v)
{
    int32_t wh = fl_lines_width_q4(l, v, false), wv = fl_lines_width_q4(l, v, true);
    int32_t w = wh < wv ? wh : wv;
    if (w <= 0 || w >= 32)
        return 256;
    return w < 16 ? 128 : w * 8;
}

/* Merging: is the summed squared error of the points to their
 * least-squares line within the threshold? */
static bool ln_err_ok(const fl_lines_t *l, const ln_mom_t *m)
{
    return ln_sse_fit(m) <= ln_thr(l, m->n);
}

/* Summed squared distance of the points (moments m about the origin) to
 * the line through P and Q (same coordinates), times |Q - P|^2; and that
 * squared length in *len2.  See "Scaling and overflow" at the top. */
static int64_t ln_err_scaled(const ln_mom_t *m, int32_t pu, int32_t pv,
                             int32_t qu, int32_t qv, int64_t *len2)
{
    int64_t a = (int64_t)pv - qv, b = (int64_t)qu - pu;
    int64_t c = a * pu + b * pv;
    int64_t e = a * a * m->sxx + 2 * a * b * m->sxy + b * b * m->syy -
                2 * c * (a * m->sx + b * m->sy) + (int64_t)m->n * c * c;
    *len2 = a * a + b * b;
    return e < 0 ? 0 : e;
}

/* Growth (seed 000, equation 1): is the summed squared distance of the
 * points to the line through the end points P and Q within the threshold? */
static bool ln_err_ends_ok(const fl_lines_t *l, const ln_mom_t *m, int32_t pu,
                           int32_t pv, int32_t qu, int32_t qv)
{
    int64_t len2, e = ln_err_scaled(m, pu, pv, qu, qv, &len2);
    if (len2 == 0)
        return true;
    return e <= ln_thr(l, m->n) * len2;
}

static void ln_mom_of(const fl_segment_t *s, ln_mom_t *m)
{
    m->n = s->n;
    m->sx = s->sx;
    m->sy = s->sy;
    m->sxx = s->sxx;
    m->syy = s->syy;
    m->sxy = s->sxy;
}

static void ln_mom_add(ln_mom_t *m, int32_t x, int32_t y)
{
    m->n++;
    m->sx += x;
    m->sy += y;
    m->sxx += (int64_t)x * x;
    m->syy += (int64_t)y * y;
    m->sxy += (int64_t)x * y;
}

/* Moments m (about origin o) re-expressed about origin o + d. */
static void ln_mom_shift(ln_mom_t *m, int32_t du, int32_t dv)
{
    /* sum (x - du)^2 = sxx - 2 du sx + n du^2, etc. */
    int64_t n = m->n;
    m->sxx += -2 * (int64_t)du * m->sx + n * du * du;
    m->syy += -2 * (int64_t)dv * m->sy + n * dv * dv;
    m->sxy += -(int64_t)dv * m->sx - (int64_t)du * m->sy + n * du * dv;
    m->sx -= n * du;
    m->sy -= n * dv;
}

/* Q1 point -> moment units relative to anchor (au, av). */
static int32_t ln_mu(int32_t q1, int32_t a) { return (q1 >> LN_MSHIFT) - a; }

/* ---- growth ---------------------------------------------------------------- */

/* Segment under construction (its point ids live in l->grow_ids). */
typedef struct {
    fl_segment_t s;
    int32_t n_ids;
    uint16_t *ids;
    int32_t end0, end1;   /* point ids of the two ends */
} ln_grow_t;

typedef struct {
    int32_t id;
    int32_t cost;
} ln_cand_t;

/* Up to FL_LINES_CANDIDATES candidates for extending end E (Q1) of a
 * segment whose other end is O (O == E for a single point), best first.
 * Returns the count. */
static int32_t ln_candidates(const fl_lines_t *l, const ln_grow_t *g, bool tail,
                             ln_cand_t *out)
{
    const fl_segment_t *s = &g->s;
    int32_t eu = tail ? s->e1u : s->e0u, ev = tail ? s->e1v : s->e0v;
    int32_t ou = tail ? s->e0u : s->e1u, ov = tail ? s->e0v : s->e1v;
    uint8_t ef = l->points[tail ? g->end1 : g->end0].flags;
    int32_t n = 0, bu, bv, x, y, gap2 = 2 * l->gap_px, looked = 0;
    int64_t du = (int64_t)eu - ou, dv = (int64_t)ev - ov;
    int64_t dlen = (int64_t)fl_hypot((int32_t)du, (int32_t)dv);
    bu = (eu >> 1) >> l->bshift;
    bv = (ev >> 1) >> l->bshift;
    for (y = bv - 1; y <= bv + 1; y++) {
        if (y < 0 || y >= l->brows)
            continue;
        for (x = bu - 1; x <= bu + 1; x++) {
            int32_t b, k;
            if (x < 0 || x >= l->bcols)
                continue;
            b = y * l->bcols + x;
            for (k = l->bstart[b]; k < l->bstart[b + 1]; k++) {
                int32_t id = l->border[k], cu, cv, d2, cost, j;
                if (++looked > LN_SEARCH_MAX)
                    return n;
                const fl_line_point_t *p = &l->points[id];
                if (p->seg != FL_LINES_NONE)
                    continue;
                /* two runs of one scan line are apart by construction
                 * (non-white between them): never neighbours on a line */
                if ((p->flags & FL_LINE_POINT_VERTICAL) == (ef & FL_LINE_POINT_VERTICAL) &&
                    ((ef & FL_LINE_POINT_VERTICAL) ? p->u_q1 == eu : p->v_q1 == ev))
                    continue;
                cu = p->u_q1 - eu;
                cv = p->v_q1 - ev;
                d2 = cu * cu + cv * cv;
                if (d2 == 0 || d2 > gap2 * gap2)
                    continue;
                if (dlen > 0) {
                    int64_t along = cu * du + cv * dv;
                    int64_t off = ln_abs64(cu * dv - cv * du);
                    if (along <= 0)
                        continue;
                    /* offset from the line, Q1; at most gap / 2 */
                    if (off * 2 > (int64_t)gap2 * dlen)
                        continue;
                    cost = (int32_t)fl_isqrt32((uint32_t)d2) + (int32_t)(3 * off / dlen);
                } else {
                    cost = (int32_t)fl_isqrt32((uint32_t)d2);
                }
                /* insert into the sorted short list */
                if (n == FL_LINES_CANDIDATES && cost >= out[n - 1].cost)
                    continue;
                j = n < FL_LINES_CANDIDATES ? n++ : n - 1;
                while (j > 0 && out[j - 1].cost > cost) {
                    out[j] = out[j - 1];
                    j--;
                }
                out[j].id = id;
                out[j].cost = cost;
            }
        }
    }
    return n;
}


static void ln_seg_add(fl_lines_t *l, ln_grow_t *g, int32_t id, int32_t sid,
                       bool at_tail)
{
    fl_line_point_t *p = &l->points[id];
    fl_segment_t *s = &g->s;
    ln_mom_t m;
    ln_mom_of(s, &m);
    ln_mom_add(&m, ln_mu(p->u_q1, s->au), ln_mu(p->v_q1, s->av));
    s->n = (uint16_t)m.n;
    s->sx = m.sx;
    s->sy = m.sy;
    s->sxx = m.sxx;
    s->syy = m.syy;
    s->sxy = m.sxy;
    if (at_tail) {
        s->e1u = p->u_q1;
        s->e1v = p->v_q1;
        g->end1 = id;
    } else {
        s->e0u = p->u_q1;
        s->e0v = p->v_q1;
        g->end0 = id;
    }
    if (p->flags & FL_LINE_POINT_LUMA)
        s->n_luma++;
    p->seg = (uint16_t)sid;
    g->ids[g->n_ids++] = (uint16_t)id;
}

/* Grow one end (tail: e1, else e0) as far as it goes. */
static void ln_grow_end(fl_lines_t *l, const fl_scan_t *scan, ln_grow_t *g,
                        int32_t sid, bool tail)
{
    fl_segment_t *s = &g->s;
    if (scan && l->white_checks >= ln_check_budget(l))
        return;
    while (g->n_ids < FL_LINES_SEG_MAX_POINTS) {
        ln_cand_t c[FL_LINES_CANDIDATES];
        int32_t eu = tail ? s->e1u : s->e0u, ev = tail ? s->e1v : s->e0v;
        int32_t nc = ln_candidates(l, g, tail, c), k;
        bool added = false;
        for (k = 0; k < nc && !added; k++) {
            const fl_line_point_t *p = &l->points[c[k].id];
            ln_mom_t m;
            int32_t pu, pv, qu, qv;
            if (scan) {
                /* per-frame budget: noise cannot blow up the time */
                if (l->white_checks >= ln_check_budget(l)) {
                    l->checks_capped++;
                    return;
                }
                l->white_checks++;
                if (ln_paint_pct(l, scan, eu * 8, ev * 8, p->u_q1 * 8, p->v_q1 * 8) <
                    l->params.white_pct)
                    continue;
            }
            ln_mom_of(s, &m);
            ln_mom_add(&m, ln_mu(p->u_q1, s->au), ln_mu(p->v_q1, s->av));
            pu = ln_mu(tail ? s->e0u : p->u_q1, s->au);
            pv = ln_mu(tail ? s->e0v : p->v_q1, s->av);
            qu = ln_mu(tail ? p->u_q1 : s->e1u, s->au);
            qv = ln_mu(tail ? p->v_q1 : s->e1v, s->av);
            if (!ln_err_ends_ok(l, &m, pu, pv, qu, qv))
                continue;
            ln_seg_add(l, g, c[k].id, sid, tail);
            added = true;
        }
        if (!added)
            return;
    }
}

/* ---- merging --------------------------------------------------------------- */

static int64_t ln_d2(int32_t au, int32_t av, int32_t bu, int32_t bv)
{
    int64_t du = (int64_t)au - bu, dv = (int64_t)av - bv;
    return du * du + dv * dv;
}

/* |signed distance| * |Q - P| of point X from line P-Q (Q1 units). */
static int64_t ln_off_scaled(int32_t pu, int32_t pv, int32_t qu, int32_t qv,
                             int32_t xu, int32_t xv)
{
    return ln_abs64(((int64_t)qu - pu) * ((int64_t)xv - pv) -
                    ((int64_t)qv - pv) * ((int64_t)xu - pu));
}

/* Try to merge segment b into a (both with extreme points and moments).
 * On success a holds the union (moments about a's anchor) and true is
 * returned. */
static bool ln_try_merge(fl_lines_t *l, const fl_scan_t *scan, fl_segment_t *a,
                         const fl_segment_t *b)
{
    int64_t la, lb, cross, dot, tol, best, d;
    int32_t au = a->e1u - a->e0u, av = a->e1v - a->e0v;
    int32_t bu = b->e1u - b->e0u, bv = b->e1v - b->e0v;
    int32_t pts[4][2], i, j, bi = 0, bj = 1, gi = 0, gj = 0;
    int32_t merge_gap = l->params.merge_gap_px > 0 ? l->params.merge_gap_px
                                                   : 6 * l->step_px;
    ln_mom_t m, mb;
    if ((int32_t)a->n + b->n > FL_LINES_SEG_MAX_POINTS)
        return false;
    la = fl_hypot(au, av);
    lb = fl_hypot(bu, bv);
    if (la == 0 || lb == 0)
        return false;
    /* nearly parallel: |sin| <= 0.105 (6 deg), or what 3 px of end jitter
     * allows over the shorter piece */
    cross = ln_abs64((int64_t)au * bv - (int64_t)av * bu);
    dot = (int64_t)au * bu + (int64_t)av * bv;
    if (dot <= 0)
        dot = -dot;
    tol = 6; /* 3 px, Q1 */
    if (cross * 1000 > 105 * la * lb && cross * (la < lb ? la : lb) > 2 * tol * la * lb)
        return false;
    /* collinear: the shorter piece's ends within 3 px of the longer's line
     * (the short one's own direction is too noisy to extrapolate) */
    if (la >= lb) {
        if (ln_off_scaled(a->e0u, a->e0v, a->e1u, a->e1v, b->e0u, b->e0v) > tol * la ||
            ln_off_scaled(a->e0u, a->e0v, a->e1u, a->e1v, b->e1u, b->e1v) > tol * la)
            return false;
    } else {
        if (ln_off_scaled(b->e0u, b->e0v, b->e1u, b->e1v, a->e0u, a->e0v) > tol * lb ||
            ln_off_scaled(b->e0u, b->e0v, b->e1u, b->e1v, a->e1u, a->e1v) > tol * lb)
            return false;
    }
    pts[0][0] = a->e0u; pts[0][1] = a->e0v;
    pts[1][0] = a->e1u; pts[1][1] = a->e1v;
    pts[2][0] = b->e0u; pts[2][1] = b->e0v;
    pts[3][0] = b->e1u; pts[3][1] = b->e1v;
    /* nearest a-end / b-end pair: the gap */
    best = -1;
    for (i = 0; i < 2; i++)
        for (j = 2; j < 4; j++) {
            d = ln_d2(pts[i][0], pts[i][1], pts[j][0], pts[j][1]);
            if (best < 0 || d < best) {
                best = d;
                gi = i;
                gj = j;
            }
        }
    if (best > (int64_t)4 * merge_gap * merge_gap)
        return false;
    if (scan && best > (int64_t)4 * l->gap_px * l->gap_px) {
        l->white_checks++;
        if (ln_paint_pct(l, scan, pts[gi][0] * 8, pts[gi][1] * 8, pts[gj][0] * 8,
                         pts[gj][1] * 8) < l->params.white_pct)
            return false;
    }
    /* farthest pair of the four ends: the merged extremes */
    best = -1;
    for (i = 0; i < 4; i++)
        for (j = i + 1; j < 4; j++) {
            d = ln_d2(pts[i][0], pts[i][1], pts[j][0], pts[j][1]);
            if (d > best) {
                best = d;
                bi = i;
                bj = j;
            }
        }
    {
        int32_t ta = ln_thin_q8(l, (a->e0v + a->e1v) / 4);
        int32_t tb = ln_thin_q8(l, (b->e0v + b->e1v) / 4);
        l->thr_q8 = ta > tb ? ta : tb;
    }
    ln_mom_of(a, &m);
    ln_mom_of(b, &mb);
    ln_mom_shift(&mb, a->au - b->au, a->av - b->av);
    m.n += mb.n;
    m.sx += mb.sx;
    m.sy += mb.sy;
    m.sxx += mb.sxx;
    m.syy += mb.syy;
    m.sxy += mb.sxy;
    if (!ln_err_ok(l, &m))
        return false;
    a->n = (uint16_t)m.n;
    a->n_luma = (uint16_t)(a->n_luma + b->n_luma);
    a->sx = m.sx;
    a->sy = m.sy;
    a->sxx = m.sxx;
    a->syy = m.syy;
    a->sxy = m.sxy;
    a->e0u = (int16_t)pts[bi][0];
    a->e0v = (int16_t)pts[bi][1];
    a->e1u = (int16_t)pts[bj][0];
    a->e1v = (int16_t)pts[bj][1];
    a->flags |= FL_SEG_MERGED;
    return true;
}

/* ---- refit ------------------------------------------------------------------ */

/* Principal direction of a segment's point moments: the centred second
 * moments times n (A, B, C; out), and half the angle of (A - B, 2C),
 * scaled below 2^30 for atan2, as (cos, sin) in Q15.  n > 0. */
static void ln_principal_dir(const fl_segment_t *s, int64_t *pA, int64_t *pB, int64_t *pC,
                             int32_t *c, int32_t *sn)
{
    int64_t n = s->n;
    int64_t A = n * s->sxx - s->sx * s->sx;
    int64_t B = n * s->syy - s->sy * s->sy;
    int64_t C = n * s->sxy - s->sx * s->sy;
    int64_t x2 = A - B, y2 = 2 * C;
    fl_angle_t th;
    *pA = A;
    *pB = B;
    *pC = C;
    while (ln_abs64(x2) >= (1LL << 30) || ln_abs64(y2) >= (1LL << 30)) {
        x2 >>= 1;
        y2 >>= 1;
    }
    th = (fl_angle_t)(fl_atan2((int32_t)y2, (int32_t)x2) / 2);
    *c = fl_cos_q15(th);
    *sn = fl_sin_q15(th);
}

/* Total least squares: direction from the n-scaled central moments, end
 * points = extreme points projected on the line through the centroid.
 * Scaling: A = n sxx - sx^2 etc. exact in int64 (< 2^45); for atan2 they
 * are shifted right together until |2C|, |A - B| < 2^30 (the ratio is what
 * counts).  The direction (cos, sin) is Q15; projections are computed in
 * Q4 pixels with 64-bit products. */
static void ln_refit(fl_segment_t *s)
{
    int64_t n = s->n, A, B, C;
    int32_t cu_q4, cv_q4, c, sn, t0, t1, u0, v0, u1, v1;
    if (n <= 0)
        return;
    ln_principal_dir(s, &A, &B, &C, &c, &sn);
    /* centroid, Q4 px */
    cu_q4 = (int32_t)fl_div_round((s->sx + n * s->au) * 8 * (1 << LN_MSHIFT), n);
    cv_q4 = (int32_t)fl_div_round((s->sy + n * s->av) * 8 * (1 << LN_MSHIFT), n);
    u0 = s->e0u * 8;
    v0 = s->e0v * 8;
    u1 = s->e1u * 8;
    v1 = s->e1v * 8;
    if (n == 1 || (A == 0 && B == 0)) {
        s->u0_q4 = u0;
        s->v0_q4 = v0;
        s->u1_q4 = u1;
        s->v1_q4 = v1;
    } else {
        t0 = fl_rshift_round((int64_t)(u0 - cu_q4) * c + (int64_t)(v0 - cv_q4) * sn, 15);
        t1 = fl_rshift_round((int64_t)(u1 - cu_q4) * c + (int64_t)(v1 - cv_q4) * sn, 15);
        s->u0_q4 = cu_q4 + fl_rshift_round((int64_t)t0 * c, 15);
        s->v0_q4 = cv_q4 + fl_rshift_round((int64_t)t0 * sn, 15);
        s->u1_q4 = cu_q4 + fl_rshift_round((int64_t)t1 * c, 15);
        s->v1_q4 = cv_q4 + fl_rshift_round((int64_t)t1 * sn, 15);
    }
    /* order: end 0 has the smaller u (smaller v when vertical) */
    if (s->u1_q4 < s->u0_q4 || (s->u1_q4 == s->u0_q4 && s->v1_q4 < s->v0_q4)) {
        int32_t tu = s->u0_q4, tv = s->v0_q4;
        int16_t eu = s->e0u, ev = s->e0v;
        s->u0_q4 = s->u1_q4;
        s->v0_q4 = s->v1_q4;
        s->u1_q4 = tu;
        s->v1_q4 = tv;
        s->e0u = s->e1u;
        s->e0v = s->e1v;
        s->e1u = eu;
        s->e1v = ev;
    }
    s->len_q4 = (int32_t)fl_hypot(s->u1_q4 - s->u0_q4, s->v1_q4 - s->v0_q4);
    s->angle = fl_atan2(s->v1_q4 - s->v0_q4, s->u1_q4 - s->u0_q4);
    /* smallest eigenvalue of the scatter (SSE to the fitted line):
     * n lambda = ((A + B) - sqrt((A - B)^2 + 4 C^2)) / 2, A, B, C shifted
     * together below 2^31 */
    {
        int64_t a = A, b = B, cc = C, r;
        int32_t sh = 0;
        uint64_t q;
        while (a >= (1LL << 30) || b >= (1LL << 30) || ln_abs64(cc) >= (1LL << 30)) {
            a >>= 1;
            b >>= 1;
            cc >>= 1;
            sh++;
        }
        q = (uint64_t)((a - b) * (a - b)) + (uint64_t)(4 * cc * cc);
        r = (a + b) - (int64_t)fl_isqrt64(q);
        if (r < 0)
            r = 0;
        r = (r << sh) / 2 / n; /* Q1 >> LN_MSHIFT, squared */
        r <<= 2 * LN_MSHIFT;   /* Q1 squared = Q2 */
        s->sse_q2 = r > (int64_t)UINT32_MAX ? UINT32_MAX : (uint32_t)r;
    }
}

/* Bulge of every segment: least-squares fit of the points' offsets from
 * the fitted line, d = alpha + beta t^2, t in [-1, 1] from the middle of
 * the segment to its ends; the sagitta (middle against ends) is -beta.
 * Robust to jitter of the end points, unlike the chord through them.
 * Scaling: offsets D in Q4 (|D| < 2^16), T = t in Q15, T2 = T^2 >> 15
 * (<= 2^16 after clamping |t| <= 1.4); sums over n <= 1023 points: sum D
 * T2 < 2^42, n sum T2^2 < 2^52, products of sums < 2^59: int64.  beta_q4
 * = (n sum D T2 - sum T2 sum D) * 2^15 / (n sum T2^2 - (sum T2)^2), the
 * denominator shifted right by 15 instead. */
static void ln_curvature(fl_lines_t *l)
{
    int32_t i, k;
    for (i = 0; i < l->n_segments; i++)
        memset(l->curv[i], 0, sizeof l->curv[i]);
    for (k = 0; k < l->n_points; k++) {
        const fl_line_point_t *p = &l->points[k];
        const fl_segment_t *s;
        int64_t du, dv, half, T, D, T2;
        int32_t c, sn;
        if (p->seg == FL_LINES_NONE)
            continue;
        s = &l->segments[p->seg];
        half = s->len_q4 / 2;
        if (half <= 0)
            continue;
        c = fl_cos_q15(s->angle);
        sn = fl_sin_q15(s->angle);
        du = (int64_t)p->u_q1 * 8 - (s->u0_q4 + s->u1_q4) / 2;
        dv = (int64_t)p->v_q1 * 8 - (s->v0_q4 + s->v1_q4) / 2;
        T = (du * c + dv * sn) / half;           /* Q15 */
        if (T > 45875)
            T = 45875;
        if (T < -45875)
            T = -45875;
        D = (dv * c - du * sn) >> 15;            /* Q4, along (-sin, cos) */
        T2 = (T * T) >> 15;
        l->curv[p->seg][0]++;
        l->curv[p->seg][1] += T2;
        l->curv[p->seg][2] += T2 * T2;
        l->curv[p->seg][3] += D;
        l->curv[p->seg][4] += D * T2;
    }
    for (i = 0; i < l->n_segments; i++) {
        const int64_t *a = l->curv[i];
        int64_t num = a[0] * a[4] - a[1] * a[3];
        int64_t den = (a[0] * a[2] - a[1] * a[1]) >> 15;
        l->segments[i].bulge_q4 = a[0] >= 3 && den > 0 ? -fl_div_round(num, den) : 0;
    }
}

int32_t fl_segment_distance_q4(const fl_segment_t *s, int32_t u_q4, int32_t v_q4)
{
    int64_t du, dv;
    if (!s || s->len_q4 <= 0)
        return 0;
    du = (int64_t)s->u1_q4 - s->u0_q4;
    dv = (int64_t)s->v1_q4 - s->v0_q4;
    /* cross(d, p - e0) / |d|: positive toward smaller v for d along +u */
    return (int32_t)fl_div_round(dv * ((int64_t)u_q4 - s->u0_q4) -
                                     du * ((int64_t)v_q4 - s->v0_q4),
                                 s->len_q4);
}

/* ---- outlier pruning ----------------------------------------------------- */

/* Drop the points of a grown segment that lie off its least-squares line
 * by more than 2 px plus a quarter of the projected line width (a point
 * where another line joins, taken because it was nearest), then rebuild
 * its moments and extreme points from the rest.  The dropped points go
 * back to the pool.  Scaling: as ln_refit (direction Q15, offsets Q1 * Q15
 * in int64). */
static void ln_prune(fl_lines_t *l, ln_grow_t *g)
{
    fl_segment_t *s = &g->s;
    int64_t n = s->n, A, B, C, cu, cv;
    int32_t c, sn, k, kept = 0, tol, wq4, n_luma = 0;
    int64_t tmin = 0, tmax = 0;
    ln_mom_t m;
    if (n < 3)
        return;
    ln_principal_dir(s, &A, &B, &C, &c, &sn);
    /* centroid in Q1 (moment units are Q1 >> LN_MSHIFT about the anchor) */
    /* multiplications, not shifts: the sums and anchors may be negative */
    cu = (s->sx * (1 << LN_MSHIFT) + n * ((int64_t)s->au * (1 << LN_MSHIFT))) / n;
    cv = (s->sy * (1 << LN_MSHIFT) + n * ((int64_t)s->av * (1 << LN_MSHIFT))) / n;
    wq4 = fl_lines_width_q4(l, (int32_t)(cv / 2), false);
    k = fl_lines_width_q4(l, (int32_t)(cv / 2), true);
    if (k > 0 && (wq4 <= 0 || k < wq4))
        wq4 = k;
    /* Q1: 2 px + width / 4; lines under 2 px wide: 1 px + width / 2 */
    tol = wq4 <= 0 ? 4 : wq4 >= 32 ? 4 + wq4 / 32 : 2 + wq4 / 16;
    memset(&m, 0, sizeof m);
    for (k = 0; k < g->n_ids; k++) {
        fl_line_point_t *p = &l->points[g->ids[k]];
        int64_t du = p->u_q1 - cu, dv = p->v_q1 - cv;
        int64_t off = ln_abs64(du * sn - dv * c); /* Q1 * Q15 */
        int64_t t = du * c + dv * sn;
        if (off > (int64_t)tol << 15) {
            p->seg = FL_LINES_NONE;
            continue;
        }
        g->ids[kept++] = g->ids[k];
        if (p->flags & FL_LINE_POINT_LUMA)
            n_luma++;
        ln_mom_add(&m, ln_mu(p->u_q1, s->au), ln_mu(p->v_q1, s->av));
        if (m.n == 1 || t < tmin) {
            tmin = t;
            s->e0u = p->u_q1;
            s->e0v = p->v_q1;
        }
        if (m.n == 1 || t > tmax) {
            tmax = t;
            s->e1u = p->u_q1;
            s->e1v = p->v_q1;
        }
    }
    g->n_ids = kept;
    s->n_luma = (uint16_t)n_luma;
    s->n = (uint16_t)m.n;
    s->sx = m.sx;
    s->sy = m.sy;
    s->sxx = m.sxx;
    s->syy = m.syy;
    s->sxy = m.sxy;
}

/* Is the projected line width at the middle of s at least two grid cells
 * across (so a straight path along it stays on white)? */
static bool ln_thick(const fl_lines_t *l, const fl_scan_t *scan, const fl_segment_t *s)
{
    int32_t v = (s->e0v + s->e1v) / 4, wh, wv, w;
    wh = fl_lines_width_q4(l, v, false);
    wv = fl_lines_width_q4(l, v, true);
    w = wh < wv ? wh : wv;
    return w >= 32 * (scan->params.col_step > scan->params.row_step
                          ? scan->params.col_step : scan->params.row_step);
}

/* The end-to-end check of a grown segment: the straight path between its
 * extreme points is white (white_pct, thin-line tolerant; strictly for
 * lines two cells wide) and, even for thin lines, at least 40 % strictly
 * white: random class noise is white on a fifth of the cells and passes
 * the tolerant test half the time, never the strict one.  At most 64
 * samples. */
static bool ln_segment_white(fl_lines_t *l, const fl_scan_t *scan, const fl_segment_t *s)
{
    bool thick = ln_thick(l, scan, s);
    int32_t strict = ln_white_pct(scan, s->e0u * 8, s->e0v * 8, s->e1u * 8, s->e1v * 8,
                                  64 | LN_STRICT);
    if (thick ? strict >= l->params.white_pct
              : strict >= 40 && ln_white_pct(scan, s->e0u * 8, s->e0v * 8, s->e1u * 8,
                                             s->e1v * 8, 64) >= l->params.white_pct)
        return true;
    /* a thin far line found in the luma: the path is a luma ridge */
    if (s->n_luma == 0 || !ln_luma_path(l, strict, s->e0v * 8, s->e1v * 8) ||
        l->ridge_checks >= ln_ridge_budget(l))
        return false;
    l->ridge_checks++;
    return ln_ridge_pct(l, s->e0u * 8, s->e0v * 8, s->e1u * 8, s->e1v * 8,
                        l->params.white_pct | LN_RIDGE_NEAR) >= l->params.white_pct;
}

/* ---- build ------------------------------------------------------------------ */

int32_t fl_lines_find_segments(fl_lines_t *l, const fl_scan_t *scan)
{
    ln_grow_t g;
    int32_t k, i, j, min_len, min_len2;
    uint16_t *remap;
    if (!l || l->width <= 0)
        return 0;
    remap = l->remap;
    g.ids = l->grow_ids;
    l->n_segments = 0;
    for (k = 0; k < l->n_points; k++) {
        l->points[k].seg = FL_LINES_NONE;
        l->points[k].flags &= (uint8_t)~LN_SEEDED;
    }
    if (l->n_points == 0)
        return 0;
    ln_buckets(l);
    min_len = l->params.min_len_px > 0 ? l->params.min_len_px : 2 * l->step_px;
    min_len2 = 4 * min_len * min_len; /* Q1 squared */

    for (k = 0; k < l->n_points; k++) {
        fl_line_point_t *p = &l->points[k];
        int32_t sid = l->n_segments;
        bool stored = false;
        if (p->seg != FL_LINES_NONE || (p->flags & LN_SEEDED))
            continue;
        p->flags |= LN_SEEDED;
        /* budget spent: no seed grows past its own point (ln_grow_end),
         * which is never a segment (min_points >= 2); the rest are only
         * marked as seeds */
        if (scan && l->white_checks >= ln_check_budget(l)) {
            l->checks_capped++; /* (this seed's growth is stopped too) */
            for (i = k + 1; i < l->n_points; i++)
                if (l->points[i].seg == FL_LINES_NONE)
                    l->points[i].flags |= LN_SEEDED;
            break;
        }
        if (sid >= FL_LINES_MAX_SEGMENTS) {
            l->segments_dropped++;
            continue;
        }
        memset(&g.s, 0, sizeof g.s);
        g.n_ids = 0;
        l->thr_q8 = ln_thin_q8(l, p->v_q1 / 2);
        g.s.au = (int16_t)(p->u_q1 >> LN_MSHIFT);
        g.s.av = (int16_t)(p->v_q1 >> LN_MSHIFT);
        g.s.e0u = g.s.e1u = p->u_q1;
        g.s.e0v = g.s.e1v = p->v_q1;
        g.end0 = g.end1 = k;
        ln_seg_add(l, &g, k, sid, true);
        ln_grow_end(l, scan, &g, sid, true);
        ln_grow_end(l, scan, &g, sid, false);
        ln_prune(l, &g);
        if (g.s.n >= l->params.min_points &&
            ln_d2(g.s.e0u, g.s.e0v, g.s.e1u, g.s.e1v) >= min_len2 &&
            (!scan || ln_segment_white(l, scan, &g.s))) {
            /* storeLine: merge into a stored segment it extends */
            for (i = 0; i < l->n_segments && !stored; i++) {
                if (ln_try_merge(l, scan, &l->segments[i], &g.s)) {
                    for (j = 0; j < g.n_ids; j++)
                        l->points[g.ids[j]].seg = (uint16_t)i;
                    l->merges++;
                    stored = true;
                }
            }
            if (!stored) {
                l->segments[sid] = g.s;
                l->n_segments++;
                stored = true;
            }
        }
        if (!stored)
            for (j = 0; j < g.n_ids; j++)
                l->points[g.ids[j]].seg = FL_LINES_NONE;
    }

    /* last pass: stored pairs that extend each other (occluded lines) */
    for (i = 0; i < l->n_segments; i++)
        remap[i] = (uint16_t)i;
    for (i = 0; i < l->n_segments; i++) {
        if (remap[i] != i)
            continue;
        for (j = i + 1; j < l->n_segments; j++) {
            if (remap[j] != j)
                continue;
            if (ln_try_merge(l, scan, &l->segments[i], &l->segments[j])) {
                remap[j] = (uint16_t)i;
                l->merges++;
            }
        }
    }
    /* compact */
    j = 0;
    for (i = 0; i < l->n_segments; i++) {
        if (remap[i] == i) {
            if (j != i)
                l->segments[j] = l->segments[i];
            remap[i] = (uint16_t)j;
            j++;
        } else {
            remap[i] = remap[remap[i]];
        }
    }
    for (k = 0; k < l->n_points; k++)
        if (l->points[k].seg != FL_LINES_NONE)
            l->points[k].seg = remap[l->points[k].seg];
    l->n_segments = j;
    for (i = 0; i < l->n_segments; i++) {
        ln_refit(&l->segments[i]);
        if (l->segments[i].n_luma > 0)
            l->segments[i].flags |= FL_SEG_LUMA;
    }
    ln_curvature(l);
    return l->n_segments;
}
