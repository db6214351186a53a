/*
 * src/vision/circle.c - the centre circle from curved line segments, fitted on
 * the ground with the field's radius (see circle.h for the method).
 *
 * Algorithm.
 *   1. ground ends of every segment; state: chord candidate (ground
 *      length 0.15 R .. 2.1 R) or long line (>= R).
 *   2. one pass over the points: summed signed distance of each chord
 *      candidate's points from the chord through its extreme points.
 *   3. centre candidates: single bulging segments (3-point circle through
 *      its ends and its ground apex) and end-to-end pairs (far ends and
 *      joint); kept when the radius is within 30 % of R.
 *   4. point-weighted clustering, then fixed-radius Gauss-Newton over the
 *      projected points of the member segments (subsampled to
 *      FL_CIRCLE_MAX_POINTS), one round of dropping members off the
 *      circle, RMS and arc-coverage acceptance, flags, orientation from
 *      the halfway line.
 *
 * Invariant: found implies rms_mm within the acceptance bound, n_points >=
 * 12, an arc of at least 67.5 degrees and at least one flagged chord.
 * Memory: the caller's fl_circle_t (scratch inside it); stack < 200 B.
 * Cost: O(points + segments^2 + candidates^2 + 24 x fit points), at most
 * 3 projections per segment and two per fit point.
 *
 * Scaling and overflow.  Ground points are mm with |x|, |y| <= 20000
 * (< 2^15, pixel_to_ground's range limit).  3-point circle, coordinates
 * relative to the first point (< 2^16): squared norms < 2^33, products
 * with a coordinate < 2^49, D < 2^34: int64.  Gauss-Newton sums over <=
 * 4096 points of values < 2^17: int64.  Bulge sums: |cross| / len < 2^14
 * (Q1) per point, < 2^26 per segment: int32.
 */
#include "fieldloc/circle.h"

#include <string.h>

#define CI_OK 1u      /* ground ends known */
#define CI_CHORD 2u   /* short enough to be a chord */
#define CI_LONG 4u    /* at least R long on the ground */
#define CI_MEMBER 8u  /* in the fit */

static int32_t ci_abs(int32_t a) { return a < 0 ? -a : a; }

/* Circle through three ground points: centre and radius.  False when
 * (nearly) collinear. */
static bool ci_circle3(fl_point_t a, fl_point_t b, fl_point_t c,
                       fl_point_t *centre, int32_t *r)
{
    int64_t bx = (int64_t)b.x_mm - a.x_mm, by = (int64_t)b.y_mm - a.y_mm;
    int64_t cx = (int64_t)c.x_mm - a.x_mm, cy = (int64_t)c.y_mm - a.y_mm;
    int64_t d = 2 * (bx * cy - by * cx), b2 = bx * bx + by * by,
            c2 = cx * cx + cy * cy, ux, uy;
    if (d == 0)
        return false;
    ux = (cy * b2 - by * c2) / d;
    uy = (bx * c2 - cx * b2) / d;
    if (ux > 40000 || ux < -40000 || uy > 40000 || uy < -40000)
        return false;
    centre->x_mm = a.x_mm + (int32_t)ux;
    centre->y_mm = a.y_mm + (int32_t)uy;
    *r = (int32_t)fl_hypot((int32_t)ux, (int32_t)uy);
    return true;
}

static void ci_add(fl_circle_t *c, fl_point_t ctr, int32_t sa, int32_t sb,
                   int32_t w)
{
    fl_circle_cand_t *k;
    if (c->n_cand >= FL_CIRCLE_MAX_CHORDS) {
        c->cand_dropped++;
        return;
    }
    k = &c->cand[c->n_cand++];
    k->x_mm = ctr.x_mm;
    k->y_mm = ctr.y_mm;
    k->seg_a = (int16_t)sa;
    k->seg_b = (int16_t)sb;
    k->weight = w;
}

static int32_t ci_tol(fl_point_t p)
{
    int32_t r = (int32_t)fl_hypot(p.x_mm, p.y_mm) / 10;
    return r > 150 ? r : 150;
}

/* Steps 1-2 of fl_circle_find: ground ends and states of the segments,
 * the bulge of each chord candidate; long straight chords are lines. */
static void ci_ground(fl_circle_t *c, fl_lines_t *lines, const fl_camera_t *camera, int32_t R)
{
    int32_t i, k, nseg = lines->n_segments;

    /* 1. ground ends and states */
    for (i = 0; i < nseg; i++) {
        fl_segment_t *s = &lines->segments[i];
        int32_t len;
        c->seg_state[i] = 0;
        c->seg_bulge[i] = 0;
        s->flags &= (uint8_t)~FL_SEG_CIRCLE;
        if (!fl_camera_pixel_to_ground(camera, s->u0_q4, s->v0_q4, &c->seg_g0[i]) ||
            !fl_camera_pixel_to_ground(camera, s->u1_q4, s->v1_q4, &c->seg_g1[i]))
            continue;
        c->seg_state[i] = CI_OK;
        len = (int32_t)fl_hypot(c->seg_g1[i].x_mm - c->seg_g0[i].x_mm,
                                c->seg_g1[i].y_mm - c->seg_g0[i].y_mm);
        if (len >= R)
            c->seg_state[i] |= CI_LONG;
        if (len * 100 >= 15 * R && len * 10 <= 21 * R)
            c->seg_state[i] |= CI_CHORD;
    }

    /* 2. bulge of each chord candidate from its extreme-point chord */
    for (k = 0; k < lines->n_points; k++) {
        const fl_line_point_t *p = &lines->points[k];
        const fl_segment_t *s;
        int32_t du, dv, len;
        if (p->seg == FL_LINES_NONE || !(c->seg_state[p->seg] & CI_CHORD))
            continue;
        s = &lines->segments[p->seg];
        du = s->e1u - s->e0u;
        dv = s->e1v - s->e0v;
        len = (int32_t)fl_hypot(du, dv);
        if (len > 0)
            c->seg_bulge[p->seg] += (du * (p->v_q1 - s->e0v) - dv * (p->u_q1 - s->e0u)) / len;
    }

    /* a chord longer than R bulges by at least 0.13 R: straight ones are
     * lines (the halfway line through the circle) */
    for (i = 0; i < nseg; i++) {
        const fl_segment_t *s = &lines->segments[i];
        if ((c->seg_state[i] & CI_CHORD) && (c->seg_state[i] & CI_LONG) && s->n > 0 &&
            ci_abs(3 * c->seg_bulge[i] / (2 * s->n)) < 2)
            c->seg_state[i] &= (uint8_t)~CI_CHORD;
    }
}

/* Step 3a of fl_circle_find: a circle through each single bulging chord. */
static void ci_singles(fl_circle_t *c, const fl_lines_t *lines, const fl_camera_t *camera,
                       int32_t R)
{
    int32_t i, nseg = lines->n_segments;

    /* 3a. single bulging segments */
    for (i = 0; i < nseg; i++) {
        const fl_segment_t *s = &lines->segments[i];
        int32_t du = s->e1u - s->e0u, dv = s->e1v - s->e0v, len, b, au, av, r;
        fl_point_t gm, cc;
        if (!(c->seg_state[i] & CI_CHORD) || s->n < 4)
            continue;
        len = (int32_t)fl_hypot(du, dv);
        if (len <= 0)
            continue;
        b = 3 * c->seg_bulge[i] / (2 * s->n); /* sagitta, Q1 */
        if (ci_abs(b) < 2)
            continue;
        au = (s->e0u + s->e1u) * 4 - (int32_t)((int64_t)dv * b * 8 / len);
        av = (s->e0v + s->e1v) * 4 + (int32_t)((int64_t)du * b * 8 / len);
        if (!fl_camera_pixel_to_ground(camera, au, av, &gm))
            continue;
        if (!ci_circle3(c->seg_g0[i], gm, c->seg_g1[i], &cc, &r))
            continue;
        if (ci_abs(r - R) * 10 <= 3 * R)
            ci_add(c, cc, i, -1, s->n);
    }
}

/* Step 3b of fl_circle_find: a circle through two chords meeting end to end. */
static void ci_pairs(fl_circle_t *c, const fl_lines_t *lines, int32_t R)
{
    int32_t i, j, nseg = lines->n_segments;

    /* 3b. end-to-end pairs */
    for (i = 0; i < nseg; i++) {
        const fl_segment_t *a = &lines->segments[i];
        if (!(c->seg_state[i] & CI_CHORD))
            continue;
        for (j = i + 1; j < nseg; j++) {
            const fl_segment_t *b = &lines->segments[j];
            int32_t ea[2][2], eb[2][2], bi = 0, bj = 0, r, x, y, dang;
            int64_t bestd = -1, lim = 16 * 2 * lines->gap_px;
            fl_point_t ga[2], gb[2], jn, cc;
            if (!(c->seg_state[j] & CI_CHORD))
                continue;
            dang = ci_abs(fl_angle_sub(a->angle, b->angle));
            if (dang > 16384)
                dang = 32768 - dang;
            if (dang < 728 || dang > 12743) /* 4 .. 70 deg */
                continue;
            ea[0][0] = a->u0_q4; ea[0][1] = a->v0_q4;
            ea[1][0] = a->u1_q4; ea[1][1] = a->v1_q4;
            eb[0][0] = b->u0_q4; eb[0][1] = b->v0_q4;
            eb[1][0] = b->u1_q4; eb[1][1] = b->v1_q4;
            ga[0] = c->seg_g0[i]; ga[1] = c->seg_g1[i];
            gb[0] = c->seg_g0[j]; gb[1] = c->seg_g1[j];
            for (x = 0; x < 2; x++)
                for (y = 0; y < 2; y++) {
                    int64_t du = ea[x][0] - eb[y][0], dv = ea[x][1] - eb[y][1];
                    int64_t d = du * du + dv * dv;
                    if (bestd < 0 || d < bestd) {
                        bestd = d;
                        bi = x;
                        bj = y;
                    }
                }
            if (bestd > lim * lim)
                continue;
            jn.x_mm = (ga[bi].x_mm + gb[bj].x_mm) / 2;
            jn.y_mm = (ga[bi].y_mm + gb[bj].y_mm) / 2;
            if (!ci_circle3(ga[1 - bi], jn, gb[1 - bj], &cc, &r))
                continue;
            if (ci_abs(r - R) * 4 <= R)
                ci_add(c, cc, i, j, a->n + b->n);
        }
    }
}

/* Step 4 of fl_circle_find: the heaviest cluster of candidate centres
 * (its members marked, the unvoted arcs on its annulus too) into ctr, the
 * cluster tolerance into tolp; false without two distinct members (or
 * one long one). */
static bool ci_cluster(fl_circle_t *c, const fl_lines_t *lines, int32_t R, fl_point_t *ctr,
                       int32_t *tolp)
{
    int32_t i, j, t, tol, best = -1, best_w = 0, nseg = lines->n_segments;
    int64_t sx, sy;

    /* 4. clustering */
    for (i = 0; i < c->n_cand; i++) {
        fl_point_t pi;
        int32_t w = 0;
        pi.x_mm = c->cand[i].x_mm;
        pi.y_mm = c->cand[i].y_mm;
        t = ci_tol(pi);
        for (j = 0; j < c->n_cand; j++)
            if (ci_abs(c->cand[j].x_mm - pi.x_mm) <= t &&
                ci_abs(c->cand[j].y_mm - pi.y_mm) <= t)
                w += c->cand[j].weight;
        if (w > best_w) {
            best_w = w;
            best = i;
        }
    }
    ctr->x_mm = c->cand[best].x_mm;
    ctr->y_mm = c->cand[best].y_mm;
    tol = ci_tol(*ctr);
    *tolp = tol;
    sx = sy = 0;
    {
        int64_t wsum = 0;
        int32_t distinct = 0, single_long = 0;
        for (j = 0; j < c->n_cand; j++) {
            const fl_circle_cand_t *k2 = &c->cand[j];
            if (ci_abs(k2->x_mm - ctr->x_mm) > tol || ci_abs(k2->y_mm - ctr->y_mm) > tol)
                continue;
            sx += (int64_t)k2->x_mm * k2->weight;
            sy += (int64_t)k2->y_mm * k2->weight;
            wsum += k2->weight;
            if (!(c->seg_state[k2->seg_a] & CI_MEMBER)) {
                c->seg_state[k2->seg_a] |= CI_MEMBER;
                distinct++;
            }
            if (k2->seg_b >= 0 && !(c->seg_state[k2->seg_b] & CI_MEMBER)) {
                c->seg_state[k2->seg_b] |= CI_MEMBER;
                distinct++;
            }
            if (k2->seg_b < 0 && (c->seg_state[k2->seg_a] & CI_LONG))
                single_long = 1;
        }
        if (wsum <= 0 || (distinct < 2 && !single_long))
            return false;
        ctr->x_mm = (int32_t)(sx / wsum);
        ctr->y_mm = (int32_t)(sy / wsum);
    }
    /* unvoted arcs: chord candidates with both ends on the annulus */
    for (i = 0; i < nseg; i++) {
        int32_t d0, d1;
        if (!(c->seg_state[i] & CI_CHORD) || (c->seg_state[i] & CI_MEMBER))
            continue;
        d0 = (int32_t)fl_hypot(c->seg_g0[i].x_mm - ctr->x_mm, c->seg_g0[i].y_mm - ctr->y_mm);
        d1 = (int32_t)fl_hypot(c->seg_g1[i].x_mm - ctr->x_mm, c->seg_g1[i].y_mm - ctr->y_mm);
        if (ci_abs(d0 - R) <= tol / 2 && ci_abs(d1 - R) <= tol / 2)
            c->seg_state[i] |= CI_MEMBER;
    }
    return true;
}

/* Step 5 of fl_circle_find: fixed-radius Gauss-Newton fit of ctr over the
 * member points (into c->pts); members whose points stay off the circle
 * are dropped and the fit repeated.  Returns the points fitted, 0 when
 * too few or the centre moved more than 2 tol. */
static int32_t ci_fit(fl_circle_t *c, const fl_lines_t *lines, const fl_camera_t *camera,
                      int32_t R, fl_point_t *ctr, int32_t tol)
{
    int32_t i, j, k, n = 0, stride, it, cnt_pts, nseg = lines->n_segments;
    int64_t sx, sy;

    /* 5. fit: fixed-radius Gauss-Newton over the member points; members
     * whose points stay off the circle are dropped and the fit repeated */
    {
        fl_point_t start = *ctr;
        int32_t round, lim = (int32_t)fl_hypot(ctr->x_mm, ctr->y_mm) / 12;
        if (lim < 60)
            lim = 60;
        for (round = 0; round < 2; round++) {
            int32_t kept = 0;
            cnt_pts = 0;
            for (k = 0; k < lines->n_points; k++) {
                uint16_t sg = lines->points[k].seg;
                if (sg != FL_LINES_NONE && (c->seg_state[sg] & CI_MEMBER))
                    cnt_pts++;
            }
            stride = (cnt_pts + FL_CIRCLE_MAX_POINTS - 1) / FL_CIRCLE_MAX_POINTS;
            if (stride < 1)
                stride = 1;
            n = 0;
            j = 0;
            for (k = 0; k < lines->n_points && n < FL_CIRCLE_MAX_POINTS; k++) {
                const fl_line_point_t *p = &lines->points[k];
                if (p->seg == FL_LINES_NONE || !(c->seg_state[p->seg] & CI_MEMBER))
                    continue;
                if (j++ % stride)
                    continue;
                if (fl_camera_pixel_to_ground(camera, p->u_q1 * 8, p->v_q1 * 8, &c->pts[n])) {
                    c->pts_seg[n] = (int16_t)p->seg;
                    n++;
                }
            }
            if (n < 6)
                return 0;
            for (it = 0; it < 12; it++) {
                fl_point_t prev = *ctr;
                sx = sy = 0;
                for (k = 0; k < n; k++) {
                    int32_t dx = c->pts[k].x_mm - ctr->x_mm, dy = c->pts[k].y_mm - ctr->y_mm;
                    int32_t d = (int32_t)fl_hypot(dx, dy);
                    if (d <= 0) {
                        sx += ctr->x_mm;
                        sy += ctr->y_mm;
                        continue;
                    }
                    sx += c->pts[k].x_mm - (int64_t)dx * R / d;
                    sy += c->pts[k].y_mm - (int64_t)dy * R / d;
                }
                ctr->x_mm = (int32_t)(sx / n);
                ctr->y_mm = (int32_t)(sy / n);
                if (ci_abs(ctr->x_mm - prev.x_mm) + ci_abs(ctr->y_mm - prev.y_mm) <= 1)
                    break;
            }
            if (round == 1)
                break;
            /* mean |residual| per member segment (seg_bulge reused) */
            for (i = 0; i < nseg; i++) {
                c->seg_bulge[i] = 0;
                c->seg_cnt[i] = 0;
            }
            for (k = 0; k < n; k++) {
                int32_t d = (int32_t)fl_hypot(c->pts[k].x_mm - ctr->x_mm,
                                              c->pts[k].y_mm - ctr->y_mm) - R;
                c->seg_bulge[c->pts_seg[k]] += ci_abs(d) > 30000 ? 30000 : ci_abs(d);
                c->seg_cnt[c->pts_seg[k]]++;
            }
            for (i = 0; i < nseg; i++)
                if ((c->seg_state[i] & CI_MEMBER) && c->seg_cnt[i] > 0) {
                    if (c->seg_bulge[i] > lim * c->seg_cnt[i])
                        c->seg_state[i] &= (uint8_t)~CI_MEMBER;
                    else
                        kept++;
                }
            if (kept < 1)
                return 0;
        }
        if (ci_abs(ctr->x_mm - start.x_mm) > 2 * tol || ci_abs(ctr->y_mm - start.y_mm) > 2 * tol)
            return 0;
    }
    return n;
}

/* Orientation of a found circle: the longest line through the centre. */
static void ci_orient(fl_circle_t *c, const fl_lines_t *lines, fl_point_t ctr)
{
    int32_t i, tol, nseg = lines->n_segments;

    /* orientation: the longest line through the centre */
    {
        int32_t best_len = 0;
        tol = ci_tol(ctr);
        for (i = 0; i < nseg; i++) {
            int64_t dx, dy, len, cr;
            if (!(c->seg_state[i] & CI_LONG) || (c->seg_state[i] & CI_MEMBER))
                continue;
            dx = (int64_t)c->seg_g1[i].x_mm - c->seg_g0[i].x_mm;
            dy = (int64_t)c->seg_g1[i].y_mm - c->seg_g0[i].y_mm;
            len = fl_hypot((int32_t)dx, (int32_t)dy);
            cr = dx * ((int64_t)ctr.y_mm - c->seg_g0[i].y_mm) -
                 dy * ((int64_t)ctr.x_mm - c->seg_g0[i].x_mm);
            if (cr < 0)
                cr = -cr;
            if (len > 0 && cr <= (int64_t)tol * len && len > best_len) {
                fl_angle_t o = fl_atan2((int32_t)dy, (int32_t)dx);
                if (o >= 16384 || o < -16384)
                    o = fl_angle_add(o, FL_ANGLE_180);
                best_len = (int32_t)len;
                c->orientation = o;
                c->has_orientation = true;
            }
        }
    }
}

int32_t fl_circle_find(fl_circle_t *c, fl_lines_t *lines,
                       const fl_camera_t *camera, const fl_field_t *field)
{
    int32_t R, i, k, n, tol;
    int32_t nseg;
    int64_t se;
    fl_point_t ctr;
    if (!c)
        return 0;
    c->found = false;
    c->has_pixel = false;
    c->has_orientation = false;
    c->orientation = 0;
    c->confidence = 0;
    c->n_points = c->n_segments = c->rms_mm = 0;
    c->range_mm = 0;
    c->bearing = 0;
    c->n_cand = c->cand_dropped = 0;
    if (!lines || !camera || !field || field->circle_radius_mm <= 0 ||
        lines->width <= 0)
        return 0;
    R = field->circle_radius_mm;
    nseg = lines->n_segments;

    ci_ground(c, lines, camera, R);

    ci_singles(c, lines, camera, R);

    ci_pairs(c, lines, R);
    if (c->n_cand == 0)
        return 0;

    if (!ci_cluster(c, lines, R, &ctr, &tol))
        return 0;

    n = ci_fit(c, lines, camera, R, &ctr, tol);
    if (n == 0)
        return 0;
    se = 0;
    for (k = 0; k < n; k++) {
        int32_t d = (int32_t)fl_hypot(c->pts[k].x_mm - ctr.x_mm, c->pts[k].y_mm - ctr.y_mm) - R;
        se += (int64_t)d * d;
    }
    c->rms_mm = (int32_t)fl_isqrt64((uint64_t)(se / n));
    /* arc coverage: 32 bins of 11.25 deg around the centre; the points
     * must span at least 60 deg (a short straight piece fits any circle) */
    {
        uint32_t bins = 0;
        int32_t b, run = 0, gap = 0;
        for (k = 0; k < n; k++) {
            fl_angle_t a = fl_atan2(c->pts[k].y_mm - ctr.y_mm, c->pts[k].x_mm - ctr.x_mm);
            bins |= 1u << (((uint32_t)(uint16_t)a) >> 11);
        }
        for (b = 0; b < 64; b++) {  /* twice round: circular gaps */
            if (bins & (1u << (b & 31))) {
                run = 0;
            } else if (++run > gap) {
                gap = run;
            }
        }
        if (gap > 32)
            gap = 32;
        if (32 - gap < 6) /* 6 bins: 67.5 deg */
            return 0;
    }
    if (n < 12)
        return 0;
    {
        int32_t lim = (int32_t)fl_hypot(ctr.x_mm, ctr.y_mm) / 30;
        int32_t conf;
        if (lim < 60)
            lim = 60;
        if (c->rms_mm > lim)
            return 0;
        conf = 255 * (n < 24 ? n : 24) / 24;
        conf = conf * (2 * lim - c->rms_mm) / (2 * lim);
        c->confidence = (uint8_t)(conf < 40 ? 40 : conf > 255 ? 255 : conf);
    }
    c->found = true;
    c->centre = ctr;
    c->n_points = n;
    fl_polar_from_point(ctr, &c->range_mm, &c->bearing);
    c->has_pixel = fl_camera_ground_to_pixel(camera, ctr, &c->u_q4, &c->v_q4);
    for (i = 0; i < nseg; i++)
        if (c->seg_state[i] & CI_MEMBER) {
            lines->segments[i].flags |= FL_SEG_CIRCLE;
            c->n_segments++;
        }

    ci_orient(c, lines, ctr);
    return 1;
}
