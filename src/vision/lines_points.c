/*
 * src/vision/lines_points.c - line points: class-map runs, luma ridges and
 * the paint and ridge checks of paths (the hot loops; lines.c has the
 * parameters, reset and bucket grid; lines_int.h for the algorithm, scaling
 * and cost model; lines.h for the method).
 */
#include "lines_int.h"


/* ---- class map access ------------------------------------------------------ */

static int32_t ln_cell(const fl_scan_t *s, int32_t i, int32_t j)
{
    uint64_t w;
    if (i < 0 || j < 0 || i >= s->cols || j >= s->rows)
        return FL_CLASS_OTHER;
    w = s->map[j][i >> 5];
    return (int32_t)((w >> (62 - 2 * (i & 31))) & 3u);
}

int32_t fl_lines_white_pct(const fl_scan_t *scan, int32_t u0_q4,
                           int32_t v0_q4, int32_t u1_q4, int32_t v1_q4)
{
    return fl_lines_int_white_pct(scan, u0_q4, v0_q4, u1_q4, v1_q4, 4096);
}

/* As fl_lines_white_pct with at most max_samples samples (evenly spread:
 * long paths are subsampled); strict: no neighbour tolerance (lines at
 * least two cells wide). */
int32_t fl_lines_int_white_pct(const fl_scan_t *scan, int32_t u0_q4, int32_t v0_q4,
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
    if (fl_lines_int_run_on_robot(l, s, i0, i1, j)) {
        l->robot_rejected++;
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
    if (fl_lines_int_on_robot(l, s, i, (j0 + j1) / 2, false)) {
        l->robot_rejected++;
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
    if (fl_lines_int_on_robot(l, s, u / cs, v / rs, false)) {
        l->robot_rejected++;
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

int32_t fl_lines_int_ridge_pct(const fl_lines_t *l, int32_t u0, int32_t v0, int32_t u1,
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


int32_t fl_lines_int_paint_pct(fl_lines_t *l, const fl_scan_t *scan, int32_t u0, int32_t v0,
                            int32_t u1, int32_t v1)
{
    int32_t p = fl_lines_int_white_pct(scan, u0, v0, u1, v1, 4096 | LN_NEED(l->params.white_pct)), r;
    if (!scan || !ln_luma_path(l, p, v0, v1) || l->ridge_checks >= ln_ridge_budget(l))
        return p;
    l->ridge_checks++;
    r = fl_lines_int_ridge_pct(l, u0, v0, u1, v1, l->params.white_pct | LN_RIDGE_NEAR);
    return r > p ? r : p;
}

int32_t fl_lines_paint_pct(const fl_lines_t *l, const fl_scan_t *scan, int32_t u0_q4,
                           int32_t v0_q4, int32_t u1_q4, int32_t v1_q4)
{
    int32_t p = fl_lines_white_pct(scan, u0_q4, v0_q4, u1_q4, v1_q4), r;
    if (!l || !scan || !ln_luma_path(l, p, v0_q4, v1_q4))
        return p;
    r = fl_lines_int_ridge_pct(l, u0_q4, v0_q4, u1_q4, v1_q4, 0);
    return r > p ? r : p;
}

int32_t fl_lines_paint_beside_pct(const fl_lines_t *l, const fl_scan_t *scan, int32_t u0_q4,
                                  int32_t v0_q4, int32_t u1_q4, int32_t v1_q4)
{
    int32_t p = fl_lines_white_pct(scan, u0_q4, v0_q4, u1_q4, v1_q4), r;
    if (!l || !scan || !ln_luma_path(l, p, v0_q4, v1_q4))
        return p;
    r = fl_lines_int_ridge_pct(l, u0_q4, v0_q4, u1_q4, v1_q4, LN_RIDGE_NEAR);
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
    /* standing objects first: both scan directions skip their cells */
    fl_lines_int_robots(l, scan, mc);

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
