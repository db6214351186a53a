/*
 * src/vision/lines_luma.c - luma line points (ridges beyond the class map's
 * reach) and the luma ridge check of a path (lines_int.h for the algorithm,
 * scaling and cost model; lines.h for the method).
 */
#include "lines_int.h"

#include <string.h>

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
void fl_lines_int_luma_band(fl_lines_t *l)
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
void fl_lines_int_luma_points(fl_lines_t *l, const fl_scan_t *s, int32_t mc, int32_t mr)
{
    int32_t cs = s->params.col_step, rs = s->params.row_step, i, j, top = l->height;
    ln_sline_t sl;
    fl_lines_int_luma_band(l);
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
