/*
 * src/vision/crossings_connect.c - corners of a short connector (two parallel far lines)
 * (crossings_int.h for the algorithm, scaling and cost model).
 */
#include "crossings_int.h"

#include <string.h>

/* ---- corners of a short connector (two parallel far lines) ------------------- */

/* Longest connector on the ground (the goal box is 600 mm deep). */
#define CR_CONN_MM 1000

/* What the steps of fl_cr_connect share: E (Q4), the connector's unit
 * direction (Q15) and its length range (Q4); out: t of F along it and F's
 * position along P; then F (Q4 pixel, ground), S's ground direction into
 * S, the confidence and the arm length. */
typedef struct {
    int32_t eu, ev, lim, tmin, bt, btp, fu, fv, conf, arm;
    int64_t cu, cv;
    fl_point_t gf;
    fl_angle_t gin;
} cr_conn_t;

/* Step 2 of fl_cr_connect: the nearest segment P parallel to S (not S
 * itself, no circle chord) whose line the ray E + t (cu, cv) meets at t in
 * [tmin, lim], inside P's extent (within a width w); its index (-1 when
 * none), t into q->bt and F's position along P into q->btp. */
static int32_t cr_conn_nearest(const cr_ctx_t *ctx, int32_t is, int32_t w, cr_conn_t *q)
{
    const fl_lines_t *l = ctx->l;
    const fl_segment_t *S = &l->segments[is];
    int32_t eu = q->eu, ev = q->ev, lim = q->lim, tmin = q->tmin, best = -1, bt = 0, btp = 0;
    int32_t j, fu, fv;
    int64_t cu = q->cu, cv = q->cv;
    for (j = 0; j < l->n_segments; j++) {
        const fl_segment_t *P = &l->segments[j];
        int64_t px = (int64_t)P->u1_q4 - P->u0_q4, py = (int64_t)P->v1_q4 - P->v0_q4;
        int64_t den, num;
        int32_t t, tp;
        if (j == is || (P->flags & FL_SEG_CIRCLE) || P->len_q4 <= 0 ||
            cr_abs(fl_sin_q15(fl_angle_sub(P->angle, S->angle))) > CR_CONN_PAR_SIN)
            continue;
        /* E + t (cu, cv) on P's line: t = cross(P0 - E, p) / cross(c, p) */
        den = (cu * py - cv * px) >> 15;
        num = ((int64_t)P->u0_q4 - eu) * py - ((int64_t)P->v0_q4 - ev) * px;
        if (den < 0) {
            den = -den;
            num = -num;
        }
        /* t in [0, lim] before the division (its int32 range) */
        if (den == 0 || num < 0 || num > (int64_t)lim * den)
            continue;
        t = (int32_t)fl_div_round(num, den);
        if (t < tmin || t > lim || (best >= 0 && t >= bt))
            continue;
        fu = eu + fl_rshift_round(cu * t, 15);
        fv = ev + fl_rshift_round(cv * t, 15);
        tp = (int32_t)fl_div_round(((int64_t)fu - P->u0_q4) * px + ((int64_t)fv - P->v0_q4) * py,
                                   P->len_q4);
        if (tp < -w || tp > P->len_q4 + w)
            continue;
        best = j;
        bt = t;
        btp = tp;
    }
    q->bt = bt;
    q->btp = btp;
    return best;
}

/* Step 3 of fl_cr_connect: the T (or L where P ends) at the connector's
 * foot F on P, unless a crossing (of a pair) is already within merge
 * distance of F; r: the connector's ray from E. */
static void cr_conn_foot(const cr_ctx_t *ctx, int32_t is, int32_t best, const cr_conn_t *q,
                         const cr_ray_t *r)
{
    fl_crossings_t *c = ctx->c;
    const fl_lines_t *l = ctx->l;
    const fl_segment_t *S = &l->segments[is];
    int32_t step_q4 = 16 * l->step_px, fu = q->fu, fv = q->fv, btp = q->btp, bt = q->bt, j;
    fl_angle_t gin = q->gin;
    cr_item_t it;
    const fl_segment_t *P = &l->segments[best];
    fl_angle_t gp = fl_cos_q15(fl_angle_sub(P->angle, S->angle)) >= 0
                        ? gin : fl_angle_add(gin, FL_ANGLE_180);
    int32_t wf = cr_width_q4(l, fv), mf;
    bool near = false;
    mf = 3 * wf > 4 * step_q4 ? 3 * wf : 4 * step_q4;
    for (j = 0; j < c->n; j++) {
        int64_t a = (int64_t)c->c[j].u_q4 - fu, b = (int64_t)c->c[j].v_q4 - fv;
        if (a * a + b * b <= (int64_t)mf * mf)
            near = true;
    }
    memset(&it, 0, sizeof it);
    it.x.seg_a = (int16_t)best;
    it.x.seg_b = (int16_t)is;
    it.x.u_q4 = fu;
    it.x.v_q4 = fv;
    it.x.ground = q->gf;
    fl_polar_from_point(q->gf, &it.x.range_mm, &it.x.bearing);
    it.ground = true;
    it.x.arm[0] = fl_atan2(-r->cv, -r->cu);
    it.garm[0] = fl_angle_add(r->dir, FL_ANGLE_180);
    it.x.n_arms = 1;
    if (P->len_q4 - btp >= q->arm) {
        it.x.arm[it.x.n_arms] = P->angle;
        it.garm[it.x.n_arms++] = gp;
    }
    if (btp >= q->arm) {
        it.x.arm[it.x.n_arms] = fl_angle_add(P->angle, FL_ANGLE_180);
        it.garm[it.x.n_arms++] = fl_angle_add(gp, FL_ANGLE_180);
    }
    it.x.confidence = (uint8_t)q->conf;
    if (!near && fl_cr_type(&it.x)) {
        fl_cr_orient(&it.x, it.garm, true);
        c->connectors++;
        fl_cr_add(c, c->garm, &it, mf < bt / 2 ? mf : bt / 2, l);
    }
}

/* Far away the sides of the goal box are a few pixels long: too short for
 * a segment, so its corners (an L where the front line ends, a T where the
 * side meets the goal line) pair with nothing.  At an end E of a segment S
 * (moved out along S while its paint goes on, at most a step) whose paint
 * stops there, the ground normal of S (both ways; not within 12 degrees
 * of S in the image) is followed to the nearest segment P parallel to S in
 * the image (12 degrees) whose line it meets between 2 line steps and
 * CR_CONN_MM (at most 8 steps), inside P's extent.  The connector E-F must
 * be paint (fl_lines_paint_pct >= white_pct, F moved along P by up to a
 * step to the best paint: the ground normal is a few degrees off far
 * away) and the half of the strip beside it beyond the corner nearer E
 * must not be (a robot or a blob is wide).  Then F is a T (P both ways
 * where it goes on past F by an arm, the connector back toward E; an L
 * when P ends there) unless a crossing is already within merge distance of
 * it, and E an L (S inward, the connector), square on the ground by
 * construction; confidence as a border T's.  Each end costs at most 2
 * camera projections per normal, one pass over the segments, and 8-16
 * paint probes (counted against CR_LUMA_PROBES).
 * Scaling: image directions Q15, positions Q4 (< 2^17): the ray-line
 * solve's cross products < 2^50 in int64, t checked within [0, lim]
 * (< 2^11 Q4) before the division. */
void fl_cr_connect(const cr_ctx_t *ctx, int32_t is, bool end1)
{
    fl_crossings_t *c = ctx->c;
    const fl_lines_t *l = ctx->l;
    const fl_segment_t *S = &l->segments[is];
    const fl_camera_t *cam = ctx->cam;
    int32_t step_q4 = 16 * l->step_px, eu, ev, w, merge, k, j, lim, f, conf, arm;
    fl_angle_t ain, gin;
    cr_ray_t r;
    eu = end1 ? S->u1_q4 : S->u0_q4;
    ev = end1 ? S->v1_q4 : S->v0_q4;
    ain = end1 ? fl_angle_add(S->angle, FL_ANGLE_180) : S->angle;
    w = cr_width_q4(l, ev);
    if (w <= 0 || S->len_q4 < 2 * step_q4)
        return;
    if (eu < 2 * w || ev < 2 * w || eu > 16 * (l->width - 1) - 2 * w ||
        ev > 16 * (l->height - 1) - 2 * w)
        return;
    merge = 3 * w > 4 * step_q4 ? 3 * w : 4 * step_q4;
    for (k = 0; k < c->n; k++) {
        int64_t a = (int64_t)c->c[k].u_q4 - eu, b = (int64_t)c->c[k].v_q4 - ev;
        if (a * a + b * b <= (int64_t)merge * merge)
            return;
    }
    /* the segment's extreme points stop up to a step short of the paint;
     * S's paint stops at E */
    r.xu = eu;
    r.xv = ev;
    if (!fl_cr_end_ray(ctx, ain, w, false, &r))
        return;
    eu = r.xu;
    ev = r.xv;
    gin = r.dir;
    r.len = 2 * step_q4 > 2 * w ? 2 * step_q4 : 2 * w;
    fl_cr_probe(c, l, ctx->scan, &r);
    if (r.white < 0 || r.white >= c->params.probe_green_pct)
        return;
    arm = 2 * step_q4 > 2 * w ? 2 * step_q4 : 2 * w;
    for (k = 0; k < 2; k++) {
        int32_t plen, best, fu, fv, ou, ov, tmin;
        int64_t cu, cv;
        cr_item_t it;
        fl_point_t gf;
        cr_conn_t q;
        r.xu = eu;
        r.xv = ev;
        r.dir = fl_angle_add(gin, (fl_angle_t)(k ? -FL_ANGLE_90 : FL_ANGLE_90));
        plen = fl_cr_image_dir(cam, &r);
        if (plen <= 0)
            continue;
        lim = (int32_t)((int64_t)plen * CR_CONN_MM / CR_SCALE_MM);
        if (lim > 8 * step_q4)
            lim = 8 * step_q4;
        /* far away the ground normal of a line near the horizon projects
         * almost along it: no corner to tell from a break */
        if (cr_abs(fl_sin_q15(fl_angle_sub(fl_atan2(r.cv, r.cu), S->angle))) <= CR_CONN_PAR_SIN)
            continue;
        cu = r.cu;
        cv = r.cv;
        /* the nearest parallel segment the normal meets, 2 steps (and a
         * line width) away at least: closer lines blur into one another */
        tmin = 2 * step_q4 > w ? 2 * step_q4 : w;
        q.eu = eu;
        q.ev = ev;
        q.cu = cu;
        q.cv = cv;
        q.lim = lim;
        q.tmin = tmin;
        best = cr_conn_nearest(ctx, is, w, &q);
        if (best < 0)
            continue;
        fu = eu + fl_rshift_round(cu * q.bt, 15);
        fv = ev + fl_rshift_round(cv * q.bt, 15);
        /* the connector is paint (its foot F moved along P by up to a step
         * to where the paint is best: the camera's ground normal is off by
         * a few degrees far away), the strip beyond the corner is not */
        {
            const fl_segment_t *P = &l->segments[best];
            int32_t pc = fl_cos_q15(P->angle), ps = fl_sin_q15(P->angle), bp = -1, bj = 0;
            for (j = -2; j <= 2; j++) {
                int32_t gu = fu + fl_rshift_round((int64_t)pc * j * step_q4 / 2, 15);
                int32_t gv = fv + fl_rshift_round((int64_t)ps * j * step_q4 / 2, 15);
                int32_t pp;
                if (c->luma_probes >= CR_LUMA_PROBES)
                    return;
                c->luma_probes++;
                pp = fl_lines_paint_pct(l, ctx->scan, eu, ev, gu, gv);
                if (pp > bp || (pp == bp && cr_abs(j) < cr_abs(bj))) {
                    bp = pp;
                    bj = j;
                }
            }
            if (bp < l->params.white_pct)
                continue;
            fu += fl_rshift_round((int64_t)pc * bj * step_q4 / 2, 15);
            fv += fl_rshift_round((int64_t)ps * bj * step_q4 / 2, 15);
            q.btp += bj * step_q4 / 2;
            if (bj != 0) {
                /* the connector's own direction */
                int32_t a = fl_atan2(fv - ev, fu - eu);
                r.cu = fl_cos_q15((fl_angle_t)a);
                r.cv = fl_sin_q15((fl_angle_t)a);
            }
        }
        ou = fl_rshift_round((int64_t)-fl_cos_q15(ain) * (2 * w + 32), 15);
        ov = fl_rshift_round((int64_t)-fl_sin_q15(ain) * (2 * w + 32), 15);
        c->luma_probes++;
        /* (its half at E: the other half nears P, a ridge across a shallow
         * connector) */
        if (fl_lines_paint_pct(l, ctx->scan, eu + ou, ev + ov, (eu + fu) / 2 + ou,
                               (ev + fv) / 2 + ov) >= c->params.probe_green_pct)
            continue;
        if (!fl_camera_pixel_to_ground(cam, fu, fv, &gf))
            continue;
        f = S->len_q4 >= 4 * step_q4 ? 256 : 77 + (int32_t)((int64_t)179 * S->len_q4 / (4 * step_q4));
        conf = 160 * f / 256;
        if (conf < c->params.min_confidence)
            return;
        q.fu = fu;
        q.fv = fv;
        q.gf = gf;
        q.gin = gin;
        q.conf = conf;
        q.arm = arm;
        cr_conn_foot(ctx, is, best, &q, &r);
        /* L at E */
        memset(&it, 0, sizeof it);
        it.x.seg_a = (int16_t)is;
        it.x.seg_b = (int16_t)best;
        it.x.u_q4 = eu;
        it.x.v_q4 = ev;
        it.x.ground = r.gx;
        fl_polar_from_point(r.gx, &it.x.range_mm, &it.x.bearing);
        it.ground = true;
        it.x.arm[0] = ain;
        it.garm[0] = gin;
        it.x.arm[1] = fl_atan2(r.cv, r.cu);
        it.garm[1] = r.dir;
        it.x.n_arms = 2;
        it.x.confidence = (uint8_t)conf;
        if (fl_cr_type(&it.x)) {
            fl_cr_orient(&it.x, it.garm, true);
            c->connectors++;
            fl_cr_add(c, c->garm, &it, merge < q.bt / 2 ? merge : q.bt / 2, l);
        }
        return;
    }
}
