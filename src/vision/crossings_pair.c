/*
 * src/vision/crossings_pair.c - crossings of two segments (L, T, X)
 * (crossings_int.h for the algorithm, scaling and cost model).
 */
#include "crossings_int.h"

#include <string.h>

#define CR_BRIDGE_FLOOR 25
#define CR_BRIDGE_STEPS 6
static bool cr_bridge_one(const cr_ctx_t *ctx, const fl_segment_t *S, int32_t t, int32_t reach,
                          int32_t xu, int32_t xv)
{
    fl_crossings_t *c = ctx->c;
    int32_t step_q4 = 16 * ctx->l->step_px, eu, ev;
    if (t >= -reach && t <= S->len_q4 + reach)
        return true;
    if (ctx->l->step_px < 3 || !(S->flags & FL_SEG_LUMA) || S->len_q4 < 6 * step_q4 ||
        t < -CR_BRIDGE_STEPS * step_q4 ||
        t > S->len_q4 + CR_BRIDGE_STEPS * step_q4 || c->luma_probes >= CR_LUMA_PROBES)
        return false;
    eu = t < 0 ? S->u0_q4 : S->u1_q4;
    ev = t < 0 ? S->v0_q4 : S->v1_q4;
    c->luma_probes++;
    return 2 * fl_lines_paint_pct(ctx->l, ctx->scan, eu, ev, xu, xv) >=
           ctx->l->params.white_pct + CR_BRIDGE_FLOOR;
}

/* Both segments pass the reach test, one at least by a painted bridge
 * (not with a fixed reach_px). */
static bool cr_bridged(const cr_ctx_t *ctx, int32_t ia, int32_t ta, int32_t reach, int32_t xu,
                       int32_t xv, int32_t ib, int32_t tb)
{
    if (!ctx->scan || ctx->c->params.reach_px > 0)
        return false;
    return cr_bridge_one(ctx, &ctx->l->segments[ia], ta, reach, xu, xv) &&
           cr_bridge_one(ctx, &ctx->l->segments[ib], tb, reach, xu, xv);
}

/* What the steps of fl_cr_pair share: X (Q4), the unit directions (Q15)
 * of A and B there and sin of their angle, X's position along each, the
 * line width and arm lengths (Q4); out: the arms present and their image
 * directions. */
typedef struct {
    int32_t xu, xv, ca, sa, cb, sb, sinab, ta, tb, w, arm, arm_a, arm_b;
    bool pres[4];
    int32_t dirc[4], dirs[4];
} cr_pair_geo_t;

/* Step 2 of fl_cr_pair: the four arms at X (0 = A forward, 1 = A backward,
 * 2 = B forward, 3 = B backward): present by geometry (segment beyond X)
 * or by a white probe; returns the arms contradicted by a green probe. */
static int32_t cr_pair_arms(const cr_ctx_t *ctx, const fl_segment_t *A, const fl_segment_t *B,
                            cr_pair_geo_t *g)
{
    fl_crossings_t *c = ctx->c;
    const fl_lines_t *l = ctx->l;
    const fl_scan_t *scan = ctx->scan;
    const fl_crossings_params_t *pp = &c->params;
    int32_t xu = g->xu, xv = g->xv, ca = g->ca, sa = g->sa, cb = g->cb, sb = g->sb;
    int32_t sinab = g->sinab, ta = g->ta, tb = g->tb, w = g->w, arm = g->arm;
    int32_t arm_a = g->arm_a, arm_b = g->arm_b, step_q4 = 16 * l->step_px, k, conflicts = 0;
    bool *pres = g->pres, geo[4];
    int32_t *dirc = g->dirc, *dirs = g->dirs;

    /* an arm of A must reach past B's paint, which covers B's width across
     * B over |sin| of A (and vice versa): below arm where the other line
     * crosses the image's rows or columns on its thin side (a horizontal
     * far line is thinner across than a line running away is), never
     * below 2 steps */
    if (pp->arm_px <= 0) {
        int32_t wh = fl_lines_width_q4(l, xv / 16, false), wv = fl_lines_width_q4(l, xv / 16, true);
        int32_t wa = (int32_t)(((int64_t)wv * cr_abs(ca) + (int64_t)wh * cr_abs(sa)) >> 15);
        int32_t wb = (int32_t)(((int64_t)wv * cr_abs(cb) + (int64_t)wh * cr_abs(sb)) >> 15);
        int32_t ea = (int32_t)((int64_t)2 * wa * 32768 / cr_abs(sinab));
        int32_t eb = (int32_t)((int64_t)2 * wb * 32768 / cr_abs(sinab));
        arm_a = eb < arm ? (eb > 2 * step_q4 ? eb : 2 * step_q4) : arm;
        arm_b = ea < arm ? (ea > 2 * step_q4 ? ea : 2 * step_q4) : arm;
    }
    /* arms: 0 = A forward, 1 = A backward, 2 = B forward, 3 = B backward */
    geo[0] = A->len_q4 - ta >= arm_a;
    geo[1] = ta >= arm_a;
    geo[2] = B->len_q4 - tb >= arm_b;
    geo[3] = tb >= arm_b;
    /* an arm cut off by the image edge: half an arm (at most 2 steps) of
     * segment up to an end within a step of the border (not in images
     * under 8 arms across: there every segment is near an edge) */
    if (16 * l->width >= 8 * arm && 16 * l->height >= 8 * arm) {
        int32_t eh = step_q4, umax = 16 * (l->width - 1) - eh, vmax = 16 * (l->height - 1) - eh;
        int32_t ha = arm_a / 2 < 2 * step_q4 ? arm_a / 2 : 2 * step_q4;
        int32_t hb = arm_b / 2 < 2 * step_q4 ? arm_b / 2 : 2 * step_q4;
#define CR_AT_EDGE(u, v) ((u) < eh || (v) < eh || (u) > umax || (v) > vmax)
        if (!geo[0] && A->len_q4 - ta >= ha && CR_AT_EDGE(A->u1_q4, A->v1_q4))
            geo[0] = true;
        if (!geo[1] && ta >= ha && CR_AT_EDGE(A->u0_q4, A->v0_q4))
            geo[1] = true;
        if (!geo[2] && B->len_q4 - tb >= hb && CR_AT_EDGE(B->u1_q4, B->v1_q4))
            geo[2] = true;
        if (!geo[3] && tb >= hb && CR_AT_EDGE(B->u0_q4, B->v0_q4))
            geo[3] = true;
#undef CR_AT_EDGE
    }
    dirc[0] = ca; dirs[0] = sa;
    dirc[1] = -ca; dirs[1] = -sa;
    dirc[2] = cb; dirs[2] = sb;
    dirc[3] = -cb; dirs[3] = -sb;
    for (k = 0; k < 4; k++) {
        pres[k] = geo[k];
        if (scan) {
            /* start beyond the other line's paint: w / |sin| + w / 2 */
            int32_t r0 = (int32_t)((int64_t)w * 32768 / cr_abs(sinab)) + w / 2 + 16;
            int32_t len = 3 * step_q4 > 2 * w ? 3 * step_q4 : 2 * w;
            int32_t pr;
            if (r0 > 6 * w + 48)
                r0 = 6 * w + 48;
            if (len > 16 * 64)
                len = 16 * 64;
            cr_ray_t ray;
            ray.xu = xu;
            ray.xv = xv;
            ray.cu = dirc[k];
            ray.cv = dirs[k];
            ray.r0 = r0;
            ray.len = len;
            fl_cr_probe(c, l, scan, &ray);
            pr = ray.white;
            if (pr >= pp->probe_white_pct && !geo[k])
                pres[k] = true;
            else if (pr >= 0 && pr < pp->probe_green_pct && geo[k])
                conflicts++;
        }
    }
    return conflicts;
}

/* Step 3 of fl_cr_pair (with a camera): X on the ground, the two lines'
 * ground directions square within the tolerance (growing beyond
 * CR_FAR_MM); fills the item's ground point and ground arms.  Returns the
 * squareness confidence factor (Q8), -1 when rejected. */
static int32_t cr_pair_ground(const cr_ctx_t *ctx, const cr_pair_geo_t *g, cr_item_t *it)
{
    fl_crossings_t *c = ctx->c;
    const fl_camera_t *cam = ctx->cam;
    int32_t sin_tol_q15 = ctx->sin_tol_q15, xu = g->xu, xv = g->xv, f, k;
    const bool *pres = g->pres;
    fl_point_t gx;
    fl_angle_t ga, gb;
    int32_t between;
    cr_ray_t ra, rb;
    ra.xu = rb.xu = xu;
    ra.xv = rb.xv = xv;
    ra.cu = g->ca;
    ra.cv = g->sa;
    rb.cu = g->cb;
    rb.cv = g->sb;
    if (!fl_camera_pixel_to_ground(cam, xu, xv, &gx)) {
        c->rejected_ground++;
        return -1;
    }
    ra.gx = rb.gx = gx;
    if (!fl_cr_ground_dir(cam, &ra) || !fl_cr_ground_dir(cam, &rb)) {
        c->rejected_ground++;
        return -1;
    }
    ga = ra.dir;
    gb = rb.dir;
    between = cr_adiff(ga, gb);            /* 0..180 deg */
    if (between > 16384)
        between = 32768 - between;         /* 0..90 deg */
    /* deviation from square: sin(90 - between) = cos(between) */
    f = fl_cos_q15((fl_angle_t)between);
    if (f > sin_tol_q15) {
        /* beyond CR_FAR_MM the ground angles depend on the camera
         * pitch (1 degree moves a point 5 m away by about 1 m): the
         * tolerance grows linearly by CR_FAR_TOL_MDEG up to twice
         * that range (u32 range clamped first: products < 2^26) */
        uint32_t rg = fl_hypot(gx.x_mm, gx.y_mm);
        int32_t tm = c->params.ground_tol_mdeg;
        if (rg > CR_FAR_MM)
            tm += (int32_t)((rg > 2 * CR_FAR_MM ? CR_FAR_MM : rg - CR_FAR_MM) *
                            CR_FAR_TOL_MDEG / CR_FAR_MM);
        if (tm > 45000)
            tm = 45000;
        if (f > fl_sin_q15(fl_angle_from_mdeg(tm))) {
            c->rejected_ground++;
            return -1;
        }
    }
    it->ground = true;
    it->x.ground = gx;
    fl_polar_from_point(gx, &it->x.range_mm, &it->x.bearing);
    k = 0;
    if (pres[0]) it->garm[k++] = ga;
    if (pres[1]) it->garm[k++] = fl_angle_add(ga, FL_ANGLE_180);
    if (pres[2]) it->garm[k++] = gb;
    if (pres[3]) it->garm[k++] = fl_angle_add(gb, FL_ANGLE_180);
    /* confidence factor of squareness, Q8: 256 at 90 deg, 128 at tol */
    return 256 - (int32_t)(((int64_t)f * 128) / (sin_tol_q15 > 0 ? sin_tol_q15 : 1));
}

/* Step 4 of fl_cr_pair: a short bar crossing a line is a mark: centre mark
 * (on a line) or penalty mark (two short bars). */
static void cr_pair_mark(const cr_ctx_t *ctx, const fl_segment_t *A, const fl_segment_t *B,
                         fl_crossing_t *x)
{
    const fl_camera_t *cam = ctx->cam;
    const fl_lines_t *l = ctx->l;
    int32_t la = fl_cr_ground_len(cam, A), lb = fl_cr_ground_len(cam, B);
    int32_t lim = 5 * ctx->field->mark_size_mm / 2;
    /* (a bar cut off by the image edge is no short bar) */
    bool sa_ = la >= 0 && la <= lim && !cr_cut(l, A), sb_ = lb >= 0 && lb <= lim && !cr_cut(l, B);
    if (sa_ && sb_)
        x->kind = FL_LM_PENALTY_MARK;
    else if (sa_ || sb_)
        x->kind = FL_LM_CENTRE_MARK;
}

void fl_cr_pair(const cr_ctx_t *ctx, int32_t ia, int32_t ib)
{
    fl_crossings_t *c = ctx->c;
    fl_angle_t (*garm_store)[4] = c->garm;
    const fl_lines_t *l = ctx->l;
    const fl_scan_t *scan = ctx->scan;
    const fl_camera_t *cam = ctx->cam;
    const fl_field_t *field = ctx->field;
    int32_t sin_min_q15 = ctx->sin_min_q15;
    const fl_segment_t *A = &l->segments[ia], *B = &l->segments[ib];
    const fl_crossings_params_t *pp = &c->params;
    int64_t ax = (int64_t)A->u1_q4 - A->u0_q4, ay = (int64_t)A->v1_q4 - A->v0_q4;
    int64_t bx = (int64_t)B->u1_q4 - B->u0_q4, by = (int64_t)B->v1_q4 - B->v0_q4;
    int64_t den, num;
    int32_t xu, xv, ca, sa, cb, sb, ta, tb, w, arm, arm_a, arm_b, reach, sinab, k;
    int32_t step_q4 = 16 * l->step_px, conf, f;
    const bool *pres;
    const int32_t *dirc, *dirs;
    int32_t conflicts, cntA, cntB;
    cr_item_t it;
    cr_pair_geo_t pg;
    bool ground = false;

    den = ax * by - ay * bx;
    if (den == 0)
        return;
    /* two segments under 3 steps each: neither direction is known well
     * enough (a few points of clutter at the image edge) */
    if (A->len_q4 < 3 * 16 * l->step_px && B->len_q4 < 3 * 16 * l->step_px)
        return;
    ca = fl_cos_q15(A->angle);
    sa = fl_sin_q15(A->angle);
    cb = fl_cos_q15(B->angle);
    sb = fl_sin_q15(B->angle);
    sinab = fl_sin_q15(fl_angle_sub(B->angle, A->angle));
    if (cr_abs(sinab) < sin_min_q15)
        return;
    c->pairs++;
    num = ((int64_t)B->u0_q4 - A->u0_q4) * by - ((int64_t)B->v0_q4 - A->v0_q4) * bx;
    xu = A->u0_q4 + fl_div_round(ax * num, den);
    xv = A->v0_q4 + fl_div_round(ay * num, den);
    /* X may lie up to 2 steps outside the image: a corner at the image
     * edge whose lines come in from it (its arms point inward) */
    if (xu < -2 * step_q4 || xv < -2 * step_q4 || xu > 16 * (l->width - 1) + 2 * step_q4 ||
        xv > 16 * (l->height - 1) + 2 * step_q4)
        return;
    ta = fl_rshift_round(((int64_t)xu - A->u0_q4) * ca + ((int64_t)xv - A->v0_q4) * sa, 15);
    tb = fl_rshift_round(((int64_t)xu - B->u0_q4) * cb + ((int64_t)xv - B->v0_q4) * sb, 15);
    /* the lines' directions at X: the chord's, turned by the slope of the
     * segment's bulge there (a circle arc meets a line along its tangent) */
    {
        fl_angle_t la = fl_cr_local_angle(A, ta), lb = fl_cr_local_angle(B, tb);
        ca = fl_cos_q15(la);
        sa = fl_sin_q15(la);
        cb = fl_cos_q15(lb);
        sb = fl_sin_q15(lb);
        sinab = fl_sin_q15(fl_angle_sub(lb, la));
        if (cr_abs(sinab) < sin_min_q15)
            return;
    }
    w = cr_width_q4(l, xv);
    arm = pp->arm_px > 0 ? 16 * pp->arm_px : 2 * step_q4 > 2 * w ? 2 * step_q4 : 2 * w;
    arm_a = arm_b = arm;
    reach = pp->reach_px > 0 ? 16 * pp->reach_px : 3 * step_q4 > 3 * w ? 3 * step_q4 : 3 * w;
    /* two long segments (6 steps each) may stop up to 5 steps short of
     * their intersection: where lines meet at a shallow image angle (a far
     * corner) one of them takes the other's points near the corner */
    if (pp->reach_px <= 0 && A->len_q4 >= 6 * step_q4 && B->len_q4 >= 6 * step_q4 &&
        reach < 5 * step_q4)
        reach = 5 * step_q4;
    if ((ta < -reach || ta > A->len_q4 + reach || tb < -reach || tb > B->len_q4 + reach) &&
        !cr_bridged(ctx, ia, ta, reach, xu, xv, ib, tb)) {
        /* ... 7 steps where the gap is hidden (a robot or a post on the
         * line before the corner: no field color in most of it) */
        int32_t far = 7 * step_q4;
        if (!scan || pp->reach_px > 0 || A->len_q4 < 6 * step_q4 || B->len_q4 < 6 * step_q4 ||
            ta < -far || ta > A->len_q4 + far || tb < -far || tb > B->len_q4 + far ||
            (ta < -reach && !fl_cr_hidden(scan, A->u0_q4, A->v0_q4, xu, xv)) ||
            (ta > A->len_q4 + reach && !fl_cr_hidden(scan, A->u1_q4, A->v1_q4, xu, xv)) ||
            (tb < -reach && !fl_cr_hidden(scan, B->u0_q4, B->v0_q4, xu, xv)) ||
            (tb > B->len_q4 + reach && !fl_cr_hidden(scan, B->u1_q4, B->v1_q4, xu, xv)))
            return;
    }
    pg.xu = xu;
    pg.xv = xv;
    pg.ca = ca;
    pg.sa = sa;
    pg.cb = cb;
    pg.sb = sb;
    pg.sinab = sinab;
    pg.ta = ta;
    pg.tb = tb;
    pg.w = w;
    pg.arm = arm;
    pg.arm_a = arm_a;
    pg.arm_b = arm_b;
    conflicts = cr_pair_arms(ctx, A, B, &pg);
    pres = pg.pres;
    dirc = pg.dirc;
    dirs = pg.dirs;
    cntA = (int32_t)pres[0] + (int32_t)pres[1];
    cntB = (int32_t)pres[2] + (int32_t)pres[3];
    if (cntA == 0 || cntB == 0) {
        c->rejected_arms++;
        return;
    }
    memset(&it, 0, sizeof it);
    it.x.seg_a = (int16_t)ia;
    it.x.seg_b = (int16_t)ib;
    /* the image position inside the image (ground from the true X) */
    it.x.u_q4 = xu < 0 ? 0 : xu > 16 * (l->width - 1) ? 16 * (l->width - 1) : xu;
    it.x.v_q4 = xv < 0 ? 0 : xv > 16 * (l->height - 1) ? 16 * (l->height - 1) : xv;
    for (k = 0; k < 4; k++)
        if (pres[k])
            it.x.arm[it.x.n_arms++] = fl_atan2(dirs[k], dirc[k]);

    /* ground check and ground arms */
    if (cam) {
        conf = cr_pair_ground(ctx, &pg, &it);
        if (conf < 0)
            return;
        ground = true;
    } else {
        conf = 256;
    }
    /* short segments and contradicted arms lower the confidence */
    {
        int32_t m = A->len_q4 < B->len_q4 ? A->len_q4 : B->len_q4;
        int32_t ref = 4 * step_q4;
        f = m >= ref ? 256 : 77 + (int32_t)((int64_t)179 * m / ref);
        conf = conf * f / 256;
        for (k = 0; k < conflicts; k++)
            conf = conf * 154 / 256;
    }
    conf = conf * 255 / 256;
    it.x.confidence = (uint8_t)(conf < 0 ? 0 : conf > 255 ? 255 : conf);
    if (!fl_cr_type(&it.x)) {
        c->rejected_arms++;
        return;
    }
    if (it.x.kind == FL_LM_X && cam && field && field->mark_size_mm > 0)
        cr_pair_mark(ctx, A, B, &it.x);
    if (it.x.confidence < pp->min_confidence)
        return;
    fl_cr_orient(&it.x, it.garm, ground);
    {
        int32_t merge = 3 * w > 4 * step_q4 ? 3 * w : 4 * step_q4;
        fl_cr_add(c, garm_store, &it, merge, l);
    }
}
