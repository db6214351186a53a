/*
 * src/vision/crossings_close.c - close parallel lines (the corners of a far goal box)
 * (crossings_int.h for the algorithm, scaling and cost model).
 */
#include "crossings_int.h"

#include <string.h>

/* Close parallel lines: the corners of a far goal box (or penalty area).
 * Far away the box side projects to a stub of a few px between the goal
 * line and the box front line, which lie 2-8 px apart: too close for
 * fl_cr_connect (its connector would be under 2 steps and run along the
 * lines) and for the pairs (the stub is rarely a segment).  Per end E of
 * a long segment S (6 steps), no crossing within merge distance, E moved
 * out along S while the paint goes on (up to a step, as in fl_cr_connect):
 * beyond E carpet in the class map and no paint (the near-flank ridge
 * ratio, fl_lines_paint_beside_pct, below probe_green_pct).  The farther
 * line: the nearest segment P (6 steps), parallel in the image
 * (CR_CONN_PAR_SIN), 1 px to 2 steps across from E, E within
 * CR_CLOSE_REACH steps of its extent; the ground distance D from E to P's
 * ground line a box depth of the field (goal area or penalty area) within
 * CR_CLOSE_TOL_PCT, the foot F of E on it farther from the robot than E.
 * Without such a P, cr_close_model: F a box depth from E along S's ground
 * normal, painted along S one way at least.  Then E is an L (S inward,
 * toward F) and F a T (the farther line both ways, toward E) unless a
 * crossing is within merge distance of F or (model) F is painted one way
 * only (a faint goal line in the goal's shadow, a post beside F); the two
 * never merge with each other;
 * confidence CR_CLOSE_CONF (a connector's is 160).  Cost per end: a pass
 * over the segments, at most 5 camera projections and 16 luma probes
 * (counted against CR_LUMA_PROBES).
 * Scaling: ground points in mm (|x|, |y| < 2^16, checked): cross and dot
 * products < 2^34 in int64, the foot's offset (product < 2^51) divided by
 * the squared length (< 2^34). */
#define CR_CLOSE_TOL_PCT 40
#define CR_CLOSE_CONF 128
#define CR_CLOSE_REACH 8
/* fl_cr_close without a segment for the farther line: F = E's ground point
 * moved by a box depth along S's ground normal away from the robot
 * (r: E's ray, r->gx its ground point; gin: S's ground direction into S;
 * sa: S's image angle), 1 px to 2 steps from E in the image; F must be
 * paint along S for 1.5 steps one way (fl_lines_paint_beside_pct; a half
 * hidden by a post counts as its other half), both ways for a T; F moved
 * across by up to 1 px to the best paint.  Into ft: F (ground, Q4 pixel)
 * and whether it is a T. */
typedef struct {
    fl_point_t g;  /* ground point */
    int32_t u, v;  /* pixel, Q4 */
    bool t_ok;     /* paint both ways: a T (else only one way: an L at E) */
} cr_foot_t;

static bool cr_close_model(const cr_ctx_t *ctx, const cr_ray_t *r, fl_angle_t gin,
                           fl_angle_t sa, cr_foot_t *ft)
{
    const fl_lines_t *l = ctx->l;
    fl_crossings_t *c = ctx->c;
    const fl_field_t *field = ctx->field;
    int32_t step_q4 = 16 * l->step_px, k, side, j;
    int32_t cu = fl_cos_q15(sa), cv = fl_sin_q15(sa);
    int32_t hu = fl_rshift_round((int64_t)cu * (3 * step_q4 / 2), 15);
    int32_t hv = fl_rshift_round((int64_t)cv * (3 * step_q4 / 2), 15);
    int64_t rE = (int64_t)r->gx.x_mm * r->gx.x_mm + (int64_t)r->gx.y_mm * r->gx.y_mm;
    for (k = 0; k < 2; k++) {
        int32_t depth = k ? field->penalty_area_depth_mm : field->goal_area_depth_mm;
        if (depth <= 0 || depth > 4000)
            continue;
        for (side = -1; side <= 1; side += 2) {
            fl_angle_t n = fl_angle_add(gin, (fl_angle_t)(side * FL_ANGLE_90));
            fl_point_t g;
            int32_t u, v, du, dv, dd, nu, nv, bp = -1, bu = 0, bv = 0, bmax = -1;
            g.x_mm = r->gx.x_mm + fl_rshift_round((int64_t)depth * fl_cos_q15(n), 15);
            g.y_mm = r->gx.y_mm + fl_rshift_round((int64_t)depth * fl_sin_q15(n), 15);
            if ((int64_t)g.x_mm * g.x_mm + (int64_t)g.y_mm * g.y_mm <= rE)
                continue;
            if (!fl_camera_ground_to_pixel(ctx->cam, g, &u, &v))
                continue;
            du = u - r->xu;
            dv = v - r->xv;
            if (cr_abs(du) > 4 * step_q4 || cr_abs(dv) > 4 * step_q4)
                continue;
            dd = (int32_t)fl_hypot(du, dv);
            if (dd < 16 || dd > 2 * step_q4)
                continue;
            if (u - hu - 16 < 0 || v - hv - 16 < 0 || u + hu + 16 > 16 * (l->width - 1) ||
                v + hv + 16 > 16 * (l->height - 1) || u - hu + 16 > 16 * (l->width - 1) ||
                v - hv + 16 > 16 * (l->height - 1) || u + hu - 16 < 0 || v + hv - 16 < 0)
                continue;
            /* across S by -1, 0, +1 px: the best paint both ways */
            nu = fl_rshift_round((int64_t)-cv * 16, 15);
            nv = fl_rshift_round((int64_t)cu * 16, 15);
            for (j = -1; j <= 1; j++) {
                int32_t pu = u + j * nu, pv = v + j * nv, p1, p2;
                if (c->luma_probes + 2 > CR_LUMA_PROBES)
                    return false;
                c->luma_probes += 2;
                p1 = fl_lines_paint_beside_pct(l, ctx->scan, pu, pv, pu + hu, pv + hv);
                p2 = fl_lines_paint_beside_pct(l, ctx->scan, pu, pv, pu - hu, pv - hv);
                /* one half may be hidden (a post's foot on the line) */
                if (p1 >= l->params.white_pct && p2 < p1 &&
                    fl_cr_hidden(ctx->scan, pu, pv, pu - hu, pv - hv))
                    p2 = p1;
                if (p2 >= l->params.white_pct && p1 < p2 &&
                    fl_cr_hidden(ctx->scan, pu, pv, pu + hu, pv + hv))
                    p1 = p2;
                if (p2 < p1) {
                    int32_t t = p1;
                    p1 = p2;
                    p2 = t;
                }
                /* p1 the weaker half, p2 the stronger */
                if (p1 > bp || (p1 == bp && p2 > bmax)) {
                    bp = p1;
                    bmax = p2;
                    bu = pu;
                    bv = pv;
                }
            }
            if (bmax < l->params.white_pct)
                continue;
            if (!fl_camera_pixel_to_ground(ctx->cam, bu, bv, &ft->g))
                continue;
            ft->u = bu;
            ft->v = bv;
            ft->t_ok = bp >= l->params.white_pct;
            return true;
        }
    }
    return false;
}

/* Step 1 of fl_cr_close: the nearest image-parallel segment (6 steps) 1 px
 * to 2 steps across E = (eu, ev), E within CR_CLOSE_REACH steps of its
 * extent; -1 when none. */
static int32_t cr_close_nearest(const cr_ctx_t *ctx, int32_t is, int32_t eu, int32_t ev)
{
    const fl_lines_t *l = ctx->l;
    const fl_segment_t *S = &l->segments[is];
    int32_t step_q4 = 16 * l->step_px, j, best = -1, bd = 0;
    for (j = 0; j < l->n_segments; j++) {
        const fl_segment_t *P = &l->segments[j];
        int64_t px = (int64_t)P->u1_q4 - P->u0_q4, py = (int64_t)P->v1_q4 - P->v0_q4, t;
        int32_t d;
        if (j == is || (P->flags & FL_SEG_CIRCLE) || P->len_q4 < 6 * step_q4 ||
            cr_abs(fl_sin_q15(fl_angle_sub(P->angle, S->angle))) > CR_CONN_PAR_SIN)
            continue;
        /* distance of E from P's line; E's position along P */
        d = (int32_t)(cr_abs64(((int64_t)eu - P->u0_q4) * py - ((int64_t)ev - P->v0_q4) * px) /
                      P->len_q4);
        t = (((int64_t)eu - P->u0_q4) * px + ((int64_t)ev - P->v0_q4) * py) / P->len_q4;
        if (d < 16 || d > 2 * step_q4 || t < -CR_CLOSE_REACH * step_q4 ||
            t > P->len_q4 + CR_CLOSE_REACH * step_q4)
            continue;
        if (best < 0 || d < bd) {
            best = j;
            bd = d;
        }
    }
    return best;
}

/* Step 3 of fl_cr_close with a farther segment P: F, the foot of E (r:
 * E's ray, r->gx its ground point) on P's ground line, whose distance
 * from E must be a box depth (depth[2]) within CR_CLOSE_TOL_PCT, farther
 * from the robot than E and inside the image; into ft (ground, Q4 pixel)
 * and gp (P's ground direction).  False when there is no such F. */
static bool cr_close_on_p(const cr_ctx_t *ctx, const fl_segment_t *P, const cr_ray_t *r,
                          const int32_t *depth, cr_foot_t *ft, fl_angle_t *gp)
{
    const fl_lines_t *l = ctx->l;
    const fl_camera_t *cam = ctx->cam;
    int64_t gx, gy, dx, dy, len2, dot, cr, rE;
    fl_point_t gA, gB;
    int32_t k;
    int32_t D, ok = 0;
    if (!fl_camera_pixel_to_ground(cam, P->u0_q4, P->v0_q4, &gA) ||
        !fl_camera_pixel_to_ground(cam, P->u1_q4, P->v1_q4, &gB))
        return false;
    if (cr_abs(gA.x_mm) > 65535 || cr_abs(gA.y_mm) > 65535 || cr_abs(gB.x_mm) > 65535 ||
        cr_abs(gB.y_mm) > 65535 || cr_abs(r->gx.x_mm) > 65535 || cr_abs(r->gx.y_mm) > 65535)
        return false;
    dx = (int64_t)gB.x_mm - gA.x_mm;
    dy = (int64_t)gB.y_mm - gA.y_mm;
    len2 = dx * dx + dy * dy;
    if (len2 <= 0)
        return false;
    gx = (int64_t)r->gx.x_mm - gA.x_mm;
    gy = (int64_t)r->gx.y_mm - gA.y_mm;
    cr = gx * dy - gy * dx;
    dot = gx * dx + gy * dy;
    D = (int32_t)(cr_abs64(cr) / (int64_t)fl_hypot((int32_t)dx, (int32_t)dy));
    for (k = 0; k < 2; k++)
        if (depth[k] > 0 && 100 * cr_abs(D - depth[k]) <= CR_CLOSE_TOL_PCT * depth[k])
            ok = 1;
    if (!ok)
        return false;
    ft->g.x_mm = gA.x_mm + (int32_t)fl_div_round(dx * dot, len2);
    ft->g.y_mm = gA.y_mm + (int32_t)fl_div_round(dy * dot, len2);
    rE = (int64_t)r->gx.x_mm * r->gx.x_mm + (int64_t)r->gx.y_mm * r->gx.y_mm;
    if ((int64_t)ft->g.x_mm * ft->g.x_mm + (int64_t)ft->g.y_mm * ft->g.y_mm <= rE)
        return false;
    if (!fl_camera_ground_to_pixel(cam, ft->g, &ft->u, &ft->v))
        return false;
    if (ft->u < 0 || ft->v < 0 || ft->u > 16 * (l->width - 1) || ft->v > 16 * (l->height - 1))
        return false;
    *gp = fl_atan2((int32_t)dy, (int32_t)dx);
    return true;
}

void fl_cr_close(const cr_ctx_t *ctx, int32_t is, bool end1)
{
    fl_crossings_t *c = ctx->c;
    const fl_lines_t *l = ctx->l;
    const fl_segment_t *S = &l->segments[is];
    const fl_field_t *field = ctx->field;
    int32_t step_q4 = 16 * l->step_px, eu, ev, w, merge, k, j, best, conf;
    int32_t fu, fv, depth[2];
    fl_angle_t ain, gin, gp;
    fl_point_t gF;
    cr_foot_t ft;
    cr_ray_t r;
    cr_item_t it;
    bool near = false, t_ok = true;
    if (!field || S->len_q4 < 6 * step_q4)
        return;
    depth[0] = field->goal_area_depth_mm;
    depth[1] = field->penalty_area_depth_mm;
    if (depth[0] <= 0 && depth[1] <= 0)
        return;
    eu = end1 ? S->u1_q4 : S->u0_q4;
    ev = end1 ? S->v1_q4 : S->v0_q4;
    ain = end1 ? fl_angle_add(S->angle, FL_ANGLE_180) : S->angle;
    w = cr_width_q4(l, ev);
    if (w <= 0 || eu < 2 * step_q4 || ev < 2 * step_q4 ||
        eu > 16 * (l->width - 1) - 2 * step_q4 || ev > 16 * (l->height - 1) - 2 * step_q4)
        return;
    merge = 3 * w > 4 * step_q4 ? 3 * w : 4 * step_q4;
    for (k = 0; k < c->n; k++) {
        int64_t a = (int64_t)c->c[k].u_q4 - eu, b = (int64_t)c->c[k].v_q4 - ev;
        if (a * a + b * b <= (int64_t)merge * merge)
            return;
    }
    best = cr_close_nearest(ctx, is, eu, ev);
    /* the segment's extreme point stops up to a step short of the paint;
     * S's paint stops at E */
    r.xu = eu;
    r.xv = ev;
    if (!fl_cr_end_ray(ctx, ain, w, true, &r))
        return;
    eu = r.xu;
    ev = r.xv;
    gin = r.dir;
    r.len = 2 * step_q4;
    /* ... because it ends there: carpet beyond E, not a robot or a post,
     * and no ridge there either (a far line beside: near flanks) */
    {
        int32_t bu = eu + fl_rshift_round((int64_t)r.cu * (r.r0 + r.len), 15);
        int32_t bv = ev + fl_rshift_round((int64_t)r.cv * (r.r0 + r.len), 15);
        int32_t au = eu + fl_rshift_round((int64_t)r.cu * r.r0, 15);
        int32_t av = ev + fl_rshift_round((int64_t)r.cv * r.r0, 15);
        if (cr_class_px(ctx->scan, bu, bv) != FL_CLASS_GREEN ||
            cr_class_px(ctx->scan, (eu + bu) / 2, (ev + bv) / 2) != FL_CLASS_GREEN ||
            c->luma_probes >= CR_LUMA_PROBES)
            return;
        c->luma_probes++;
        if (fl_lines_paint_beside_pct(l, ctx->scan, au, av, bu, bv) >= c->params.probe_green_pct)
            return;
    }
    if (best < 0) {
        if (!cr_close_model(ctx, &r, gin, S->angle, &ft))
            return;
        gF = ft.g;
        fu = ft.u;
        fv = ft.v;
        t_ok = ft.t_ok;
        /* gin is S's ground direction from E inward */
        gp = end1 ? fl_angle_add(gin, FL_ANGLE_180) : gin;
    } else {
        /* P on the ground: E's distance D from its line, farther away */
        if (!cr_close_on_p(ctx, &l->segments[best], &r, depth, &ft, &gp))
            return;
        gF = ft.g;
        fu = ft.u;
        fv = ft.v;
    }
    conf = CR_CLOSE_CONF;
    if (conf < c->params.min_confidence)
        return;
    /* T at F, unless a crossing is there already; the two never merge */
    {
        int32_t mef = (int32_t)fl_hypot(fu - eu, fv - ev) / 2;
        fl_angle_t toE = fl_atan2(ev - fv, eu - fu);
        fl_angle_t pa = best >= 0 ? l->segments[best].angle : S->angle;
        if (mef > merge)
            mef = merge;
        for (j = 0; j < c->n; j++) {
            int64_t a = (int64_t)c->c[j].u_q4 - fu, b = (int64_t)c->c[j].v_q4 - fv;
            if (a * a + b * b <= (int64_t)merge * merge)
                near = true;
        }
        memset(&it, 0, sizeof it);
        it.x.seg_a = (int16_t)(best >= 0 ? best : is);
        it.x.seg_b = (int16_t)is;
        it.x.u_q4 = fu;
        it.x.v_q4 = fv;
        it.x.ground = gF;
        fl_polar_from_point(gF, &it.x.range_mm, &it.x.bearing);
        it.ground = true;
        it.x.arm[0] = toE;
        it.garm[0] = fl_atan2(r.gx.y_mm - gF.y_mm, r.gx.x_mm - gF.x_mm);
        it.x.arm[1] = pa;
        it.x.arm[2] = fl_angle_add(pa, FL_ANGLE_180);
        /* (pa and gp point alike: from the line's end 0 toward its end 1) */
        it.garm[1] = gp;
        it.garm[2] = fl_angle_add(gp, FL_ANGLE_180);
        it.x.n_arms = 3;
        it.x.confidence = (uint8_t)conf;
        if (!near && t_ok && fl_cr_type(&it.x)) {
            fl_cr_orient(&it.x, it.garm, true);
            c->connectors++;
            fl_cr_add(c, c->garm, &it, mef, l);
        }
        /* L at E */
        memset(&it, 0, sizeof it);
        it.x.seg_a = (int16_t)is;
        it.x.seg_b = (int16_t)(best >= 0 ? best : is);
        it.x.u_q4 = eu;
        it.x.v_q4 = ev;
        it.x.ground = r.gx;
        fl_polar_from_point(r.gx, &it.x.range_mm, &it.x.bearing);
        it.ground = true;
        it.x.arm[0] = ain;
        it.garm[0] = gin;
        it.x.arm[1] = fl_angle_add(toE, FL_ANGLE_180);
        it.garm[1] = fl_atan2(gF.y_mm - r.gx.y_mm, gF.x_mm - r.gx.x_mm);
        it.x.n_arms = 2;
        it.x.confidence = (uint8_t)conf;
        if (fl_cr_type(&it.x)) {
            fl_cr_orient(&it.x, it.garm, true);
            c->connectors++;
            fl_cr_add(c, c->garm, &it, mef, l);
        }
    }
}
