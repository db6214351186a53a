/*
 * src/vision/lines_segments.c - line segments: growth, merging, refit, outlier
 * pruning and the build (lines_int.h for the algorithm, scaling and cost
 * model; lines.h for the method).
 */
#include "lines_int.h"

#include <string.h>


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
                if (fl_lines_int_paint_pct(l, scan, eu * 8, ev * 8, p->u_q1 * 8, p->v_q1 * 8) <
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
        if (fl_lines_int_paint_pct(l, scan, pts[gi][0] * 8, pts[gi][1] * 8, pts[gj][0] * 8,
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
    int32_t strict = fl_lines_int_white_pct(scan, s->e0u * 8, s->e0v * 8, s->e1u * 8, s->e1v * 8,
                                  64 | LN_STRICT);
    if (thick ? strict >= l->params.white_pct
              : strict >= 40 && fl_lines_int_white_pct(scan, s->e0u * 8, s->e0v * 8, s->e1u * 8,
                                             s->e1v * 8, 64) >= l->params.white_pct)
        return true;
    /* a thin far line found in the luma: the path is a luma ridge */
    if (s->n_luma == 0 || !ln_luma_path(l, strict, s->e0v * 8, s->e1v * 8) ||
        l->ridge_checks >= ln_ridge_budget(l))
        return false;
    l->ridge_checks++;
    return fl_lines_int_ridge_pct(l, s->e0u * 8, s->e0v * 8, s->e1u * 8, s->e1v * 8,
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
    fl_lines_int_buckets(l);
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
