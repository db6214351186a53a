/*
 * src/vision/crossings.c - crossings: parameters, the shared ray, probe and
 * arm helpers, the driver fl_crossings_find and the circle crossings
 * (crossings_int.h for the algorithm, scaling and cost model).
 */
#include "crossings_int.h"

#include <string.h>


void fl_crossings_params_default(fl_crossings_params_t *p)
{
    if (!p)
        return;
    p->min_angle_mdeg = 10000;
    p->ground_tol_mdeg = 25000;
    p->arm_px = 0;
    p->reach_px = 0;
    p->probe_white_pct = 55;
    p->probe_green_pct = 25;
    p->min_confidence = 60;
    p->marks = 1;
}

fl_status_t fl_crossings_init_cfg(fl_crossings_t *c, const fl_crossings_params_t *p,
                                  uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *c has another layout: no write is safe */
    if (!c || !p)
        return FL_ERR_NULL;
    memset(c, 0, sizeof *c);
    fl_crossings_params_default(&c->params);
    if (p->min_angle_mdeg < 1000 || p->min_angle_mdeg > 60000 ||
        p->ground_tol_mdeg < 1000 || p->ground_tol_mdeg > 45000 ||
        p->arm_px < 0 || p->arm_px > 255 || p->reach_px < 0 ||
        p->reach_px > 255 || p->probe_white_pct < 0 ||
        p->probe_white_pct > 100 || p->probe_green_pct < 0 ||
        p->probe_green_pct > p->probe_white_pct || p->min_confidence < 0 ||
        p->min_confidence > 255 || p->marks < 0 || p->marks > 1)
        return FL_ERR_RANGE;
    c->params = *p;
    return FL_OK;
}


/* Ground direction (robot frame) of an image ray into r->dir.  r->gx:
 * ground point of its start.  False when neither this direction nor the
 * opposite one reaches the ground.  (The results are written into the
 * struct: gcc then keeps it a pointer instead of splitting it into more
 * than six scalar arguments.) */
bool fl_cr_ground_dir(const fl_camera_t *cam, cr_ray_t *r)
{
    fl_point_t g, gx = r->gx;
    fl_angle_t *dir = &r->dir;
    int32_t xu = r->xu, xv = r->xv, cu = r->cu, cv = r->cv;
    int32_t du = fl_rshift_round((int64_t)cu * CR_KAPPA_Q4, 15);
    int32_t dv = fl_rshift_round((int64_t)cv * CR_KAPPA_Q4, 15);
    if (fl_camera_pixel_to_ground(cam, xu + du, xv + dv, &g) &&
        (g.x_mm != gx.x_mm || g.y_mm != gx.y_mm)) {
        *dir = fl_atan2(g.y_mm - gx.y_mm, g.x_mm - gx.x_mm);
        return true;
    }
    if (fl_camera_pixel_to_ground(cam, xu - du, xv - dv, &g) &&
        (g.x_mm != gx.x_mm || g.y_mm != gx.y_mm)) {
        *dir = fl_angle_add(fl_atan2(g.y_mm - gx.y_mm, g.x_mm - gx.x_mm),
                            FL_ANGLE_180);
        return true;
    }
    return false;
}

/* Orientation of a crossing from its ground arms (obs.h conventions). */
void fl_cr_orient(fl_crossing_t *x, const fl_angle_t *garm, bool ground)
{
    int32_t i, j;
    x->has_orientation = false;
    x->orientation = 0;
    if (!ground || x->n_arms < 2)
        return;
    if (x->n_arms == 2) {
        int32_t d = fl_angle_sub(garm[1], garm[0]);
        x->orientation = fl_angle_add(garm[0], fl_angle_wrap(d / 2));
        x->has_orientation = true;
    } else if (x->n_arms == 3) {
        for (i = 0; i < 3; i++) {
            bool opposite = false;
            for (j = 0; j < 3; j++)
                if (j != i && cr_adiff(garm[i], garm[j]) > 32768 - CR_SAME_ARM)
                    opposite = true;
            if (!opposite) {
                x->orientation = garm[i];
                x->has_orientation = true;
                return;
            }
        }
    } else {
        x->orientation = garm[0];
        x->has_orientation = true;
    }
}

/* Type from the arm count (marks keep their kind). */
bool fl_cr_type(fl_crossing_t *x)
{
    if (x->kind == FL_LM_PENALTY_MARK || x->kind == FL_LM_CENTRE_MARK)
        return true;
    if (x->n_arms == 2)
        x->kind = FL_LM_L;
    else if (x->n_arms == 3)
        x->kind = FL_LM_T;
    else if (x->n_arms == 4)
        x->kind = FL_LM_X;
    else
        return false;
    return true;
}

/* Do two crossings of straight segments (no circle chord) share one? */
static bool cr_shared(const fl_lines_t *l, const fl_crossing_t *e, const fl_crossing_t *x)
{
    int16_t s[4];
    int32_t k;
    s[0] = e->seg_a;
    s[1] = e->seg_b;
    s[2] = x->seg_a;
    s[3] = x->seg_b;
    for (k = 0; k < 4; k++)
        if (s[k] < 0 || s[k] >= l->n_segments || (l->segments[s[k]].flags & FL_SEG_CIRCLE))
            return false;
    return s[0] == s[2] || s[0] == s[3] || s[1] == s[2] || s[1] == s[3];
}

/* Two crossings that share a segment and lie within CR_PIECE_MM of each
 * other on the ground are one crossing seen through two pieces of a broken
 * line (the distinct crossings of one segment, a goal box's side with the
 * goal line and the front line, are 600 mm apart or more).  Only on line
 * steps of 3 px or more (the AIBO's 2 px steps are left as they were). */
#define CR_PIECE_MM 250
static bool cr_pieces(const fl_lines_t *l, const fl_crossing_t *e, const cr_item_t *it)
{
    int64_t gx, gy;
    if (l->step_px < 3 || !it->ground || e->range_mm <= 0)
        return false;
    gx = (int64_t)e->ground.x_mm - it->x.ground.x_mm;
    gy = (int64_t)e->ground.y_mm - it->x.ground.y_mm;
    return gx * gx + gy * gy <= (int64_t)CR_PIECE_MM * CR_PIECE_MM;
}

/* Insert with merging.  Ground arms of stored crossings are kept in
 * garm_store (parallel to c->c). */
void fl_cr_add(fl_crossings_t *c, fl_angle_t (*garm_store)[4],
                   const cr_item_t *it, int32_t merge_q4,
                   const fl_lines_t *l)
{
    int32_t k, a, b;
    for (k = 0; k < c->n; k++) {
        fl_crossing_t *e = &c->c[k];
        int64_t du = (int64_t)e->u_q4 - it->x.u_q4, dv = (int64_t)e->v_q4 - it->x.v_q4;
        bool emark = e->kind == FL_LM_PENALTY_MARK || e->kind == FL_LM_CENTRE_MARK;
        bool imark = it->x.kind == FL_LM_PENALTY_MARK || it->x.kind == FL_LM_CENTRE_MARK;
        int64_t m = merge_q4;
        /* two crossings of one segment with two others (a goal box's side
         * with the goal line and the front line) are distinct unless they
         * nearly coincide (two pieces of one line broken at the segment) */
        /* ... and so are a mark and a crossing of lines (a penalty mark
         * is far from every line crossing) */
        if ((cr_shared(l, e, &it->x) && !cr_pieces(l, e, it)) || emark != imark)
            m = merge_q4 / 2;
        if (du * du + dv * dv > m * m)
            continue;
        /* two features CR_APART_MM apart on the ground are two (a far
         * penalty mark a few px above the centre mark, the corners of a
         * far goal box; the nearest distinct features of a field are
         * 600 mm apart) */
        if (it->ground && e->range_mm > 0) {
            int64_t gx = (int64_t)e->ground.x_mm - it->x.ground.x_mm;
            int64_t gy = (int64_t)e->ground.y_mm - it->x.ground.y_mm;
            if (gx * gx + gy * gy > (int64_t)CR_APART_MM * CR_APART_MM)
                continue;
        }
        /* union of the arms */
        for (a = 0; a < it->x.n_arms; a++) {
            bool have = false;
            for (b = 0; b < e->n_arms; b++)
                if (cr_adiff(e->arm[b], it->x.arm[a]) < CR_SAME_ARM)
                    have = true;
            if (!have && e->n_arms < 4) {
                e->arm[e->n_arms] = it->x.arm[a];
                garm_store[k][e->n_arms] = it->garm[a];
                e->n_arms++;
            }
        }
        if (imark && !emark)
            e->kind = it->x.kind;
        else if (!emark)
            (void)fl_cr_type(e);
        if (it->x.confidence > e->confidence) {
            e->u_q4 = it->x.u_q4;
            e->v_q4 = it->x.v_q4;
            e->ground = it->x.ground;
            e->range_mm = it->x.range_mm;
            e->bearing = it->x.bearing;
            e->confidence = it->x.confidence;
        }
        if (e->kind != FL_LM_PENALTY_MARK || e->n_arms >= 2)
            fl_cr_orient(e, garm_store[k], it->ground);
        c->merged++;
        return;
    }
    if (c->n >= FL_CROSSINGS_MAX) {
        c->dropped++;
        return;
    }
    c->c[c->n] = it->x;
    for (a = 0; a < 4; a++)
        garm_store[c->n][a] = it->garm[a];
    c->n++;
}

/* Paint ratio of a probe ray between r0 and r0 + len (Q4) from its start,
 * into r->white: -1 when less than half of it lies inside the image.  The
 * class map's white ratio; below the lines' white_pct, while the frame's
 * budget of CR_LUMA_PROBES lasts, fl_lines_paint_pct (a far line too thin
 * for the class map: its luma ridge). */
void fl_cr_probe(fl_crossings_t *c, const fl_lines_t *l, const fl_scan_t *scan,
                     cr_ray_t *r)
{
    int32_t w_px = l->width, h_px = l->height;
    int32_t xu = r->xu, xv = r->xv, cu = r->cu, cv = r->cv, r0 = r->r0, len = r->len;
    int32_t u0 = xu + fl_rshift_round((int64_t)cu * r0, 15);
    int32_t v0 = xv + fl_rshift_round((int64_t)cv * r0, 15);
    int32_t u1 = xu + fl_rshift_round((int64_t)cu * (r0 + len), 15);
    int32_t v1 = xv + fl_rshift_round((int64_t)cv * (r0 + len), 15);
    int32_t um = (u0 + u1) / 2, vm = (v0 + v1) / 2;
    int32_t maxu = 16 * (w_px - 1), maxv = 16 * (h_px - 1);
    r->white = -1;
    if (u0 < 0 || v0 < 0 || u0 > maxu || v0 > maxv)
        return;
    if (um < 0 || vm < 0 || um > maxu || vm > maxv)
        return;
    if (u1 < 0 || v1 < 0 || u1 > maxu || v1 > maxv) {
        u1 = um;
        v1 = vm;
    }
    r->white = fl_lines_white_pct(scan, u0, v0, u1, v1);
    if (r->white < l->params.white_pct && c->luma_probes < CR_LUMA_PROBES) {
        c->luma_probes++;
        r->white = fl_lines_paint_pct(l, scan, u0, v0, u1, v1);
    }
}

/* Direction of a segment at distance t (Q4) from its end 0: the chord
 * angle plus atan of the slope of a parabolic arc with the segment's
 * bulge, 4 b (L - 2t) / L^2 (t clamped to the segment, at most 45 deg).
 * Scaling: numerator and denominator in int64 (< 2^36), shifted together
 * below 2^30 for fl_atan2. */
fl_angle_t fl_cr_local_angle(const fl_segment_t *s, int32_t t)
{
    int64_t L = s->len_q4, num, den, tt = t;
    int32_t d;
    /* straight lines bulge by point noise only: below 1.5 px, no turn */
    if (L <= 0 || (s->bulge_q4 < 24 && s->bulge_q4 > -24))
        return s->angle;
    if (tt < 0)
        tt = 0;
    if (tt > L)
        tt = L;
    num = 4 * (int64_t)s->bulge_q4 * (L - 2 * tt);
    den = L * L;
    while (num >= (1LL << 30) || num <= -(1LL << 30) || den >= (1LL << 30)) {
        num >>= 1;
        den >>= 1;
    }
    if (den <= 0)
        return s->angle;
    d = fl_atan2((int32_t)num, (int32_t)den);
    if (d > 8192)
        d = 8192;
    if (d < -8192)
        d = -8192;
    return fl_angle_add(s->angle, (fl_angle_t)d);
}

/* Ground length (mm) of a segment, or -1 when an end has no ground point. */
int32_t fl_cr_ground_len(const fl_camera_t *cam, const fl_segment_t *s)
{
    fl_point_t a, b;
    if (!cam || !fl_camera_pixel_to_ground(cam, s->u0_q4, s->v0_q4, &a) ||
        !fl_camera_pixel_to_ground(cam, s->u1_q4, s->v1_q4, &b))
        return -1;
    return (int32_t)fl_hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
}

/* Is most of the straight path between two pixels (Q4) neither carpet
 * nor paint in the class map (a robot, a post in front of the line)?  At
 * most 64 samples, 1 px apart; false when no sample lies in the image. */
bool fl_cr_hidden(const fl_scan_t *s, int32_t u0, int32_t v0, int32_t u1, int32_t v1)
{
    int32_t du = u1 - u0, dv = v1 - v0, len = (int32_t)fl_hypot(du, dv), n, k, in = 0, hid = 0;
    n = len / 16;
    if (n > 63)
        n = 63;
    if (n < 1)
        return false;
    for (k = 0; k <= n; k++) {
        int32_t u = u0 + (int32_t)((int64_t)du * k / n), v = v0 + (int32_t)((int64_t)dv * k / n);
        int32_t c;
        if (u < 0 || v < 0 || u >= 16 * s->width || v >= 16 * s->height)
            continue;
        in++;
        c = cr_class_px(s, u, v);
        if (c == FL_CLASS_OTHER || c == FL_CLASS_YELLOW)
            hid++;
    }
    return in > 0 && 2 * hid >= in;
}

/* Move (*eu, *ev) (Q4) out along the direction opposite to binary angle
 * ain, 1 px at a time for less than limit (Q4), while the 2 px ahead are
 * paint (fl_lines_paint_pct, or fl_lines_paint_beside_pct when beside: a
 * second line may stand on one flank).  One luma probe per px; false when
 * the frame's CR_LUMA_PROBES ran out (the point is then left as it was). */
static bool cr_follow_paint(const cr_ctx_t *ctx, fl_angle_t ain, int32_t limit, bool beside,
                            int32_t *eu, int32_t *ev)
{
    fl_crossings_t *c = ctx->c;
    int32_t du = -fl_cos_q15(ain), dv = -fl_sin_q15(ain), t;
    for (t = 0; t < limit; t += 16) {
        int32_t au = *eu + fl_rshift_round((int64_t)du * t, 15);
        int32_t av = *ev + fl_rshift_round((int64_t)dv * t, 15);
        int32_t bu = *eu + fl_rshift_round((int64_t)du * (t + 32), 15);
        int32_t bv = *ev + fl_rshift_round((int64_t)dv * (t + 32), 15);
        if (c->luma_probes >= CR_LUMA_PROBES)
            return false;
        c->luma_probes++;
        if ((beside ? fl_lines_paint_beside_pct(ctx->l, ctx->scan, au, av, bu, bv)
                    : fl_lines_paint_pct(ctx->l, ctx->scan, au, av, bu, bv)) < 50)
            break;
    }
    *eu += fl_rshift_round((int64_t)du * t, 15);
    *ev += fl_rshift_round((int64_t)dv * t, 15);
    return true;
}

/* The probe ray back into a segment from its end: r->xu, r->xv (Q4) in,
 * the segment's end; moved out along the paint (cr_follow_paint, limit a
 * step plus half the paint width w, Q4); r->gx its ground point, r->dir
 * the ground direction of binary angle ain there, r->cu, r->cv pointing
 * back along the segment (against ain), r->r0 half the paint plus 1 px.
 * false when the luma probes ran out or the end has no ground point. */
bool fl_cr_end_ray(const cr_ctx_t *ctx, fl_angle_t ain, int32_t w, bool beside, cr_ray_t *r)
{
    if (!cr_follow_paint(ctx, ain, 16 * ctx->l->step_px + w / 2, beside, &r->xu, &r->xv))
        return false;
    r->cu = fl_cos_q15(ain);
    r->cv = fl_sin_q15(ain);
    if (!fl_camera_pixel_to_ground(ctx->cam, r->xu, r->xv, &r->gx) || !fl_cr_ground_dir(ctx->cam, r))
        return false;
    r->cu = -r->cu;
    r->cv = -r->cv;
    r->r0 = w / 2 + 16;
    return true;
}

/* One segment's side of the reach test: t (Q4) along it within reach of
 * its extent, or, for a long luma segment (a far thin line, 6 steps), up
 * to CR_BRIDGE_STEPS steps beyond an end when the gap from that end to X
 * is paint (fl_lines_paint_pct at least halfway between white_pct and
 * CR_BRIDGE_FLOOR: the goal line and the box front line of a far goal
 * box lie a few px apart, each stands on the other's ridge flank, the
 * segment growth stops short of the corner and the ridge ratio of the gap
 * is low too).  One luma probe (CR_LUMA_PROBES).  Not on a 2 px line-step
 * grid (the AIBO's 208x160 frames, as LN_RIDGE_NEAR in lines.c): there it
 * found no fixture crossing and moved the localizer's heading on simulate
 * aibo2004 seed 6 from 2.96 to 3.02 degrees. */
/* Dark cells (OTHER or YELLOW in the class map) in the ellipse of
 * half-axes (ru, rv) around (cu, cv), all Q4: d->n samples inside the image
 * (d->carpet: and not above the field border of their column), d->dark of them
 * dark.  A grid of at most 17 x 17 samples, no finer than
 * the class map's cells.  Half-axes capped at 1024 px: the ellipse test's
 * products stay below 2^57. */
void fl_cr_dark(const fl_scan_t *s, int32_t cu, int32_t cv, int32_t ru, int32_t rv,
                cr_dark_t *d)
{
    int32_t du = 16 * s->params.col_step, dv = 16 * s->params.row_step, a, b;
    int64_t ru2, rv2;
    ru = ru > 16 * 1024 ? 16 * 1024 : ru;
    rv = rv > 16 * 1024 ? 16 * 1024 : rv;
    ru2 = (int64_t)ru * ru;
    rv2 = (int64_t)rv * rv;
    if (du < ru / 8)
        du = ru / 8;
    if (dv < rv / 8)
        dv = rv / 8;
    d->n = d->dark = 0;
    for (b = -(rv / dv) * dv; b <= rv; b += dv)
        for (a = -(ru / du) * du; a <= ru; a += du) {
            int32_t u = cu + a, v = cv + b, c;
            if ((int64_t)a * a * rv2 + (int64_t)b * b * ru2 > ru2 * rv2 || u < 0 || v < 0 ||
                u > 16 * (s->width - 1) || v > 16 * (s->height - 1))
                continue;
            if (d->carpet) {
                int32_t i = (u >> 4) / s->params.col_step;
                if (i >= s->cols || (v >> 4) < s->border_v[i])
                    continue;
            }
            c = cr_class_px(s, u, v);
            d->n++;
            if (c == FL_CLASS_OTHER || c == FL_CLASS_YELLOW)
                d->dark++;
        }
}

/* Above the field border of its column and of the columns 4 cells to one
 * side by more than 8 cells and 4 line widths: the vertex is not on the
 * carpet (an object in front of the border makes a dip there, as wide as
 * the object: two lines meeting behind a robot's leg).  A single column's
 * border (a line running down it) is not a dip. */
static bool cr_above_border(const fl_lines_t *lines, const fl_scan_t *scan, int32_t u, int32_t v)
{
    int32_t i, w, lim, d;
    if (!scan || scan->width != lines->width || u < 0 || v < 0 || u >= scan->width ||
        v >= scan->height || scan->params.col_step < 1)
        return false;
    i = u / scan->params.col_step;
    w = fl_lines_width_q4(lines, v, true);
    lim = v + 8 * scan->params.row_step + (w + 8) / 16 * 4;
    if (scan->border_v[i] >= scan->height || scan->border_v[i] <= lim)
        return false;
    for (d = -4; d <= 4; d += 8)
        if (i + d >= 0 && i + d < scan->cols && scan->border_v[i + d] > lim &&
            scan->border_v[i + d] < scan->height)
            return true;
    return false;
}

/* Among dark cells: more than 1 in 10 (at least 2) of the class-map cells
 * within 3 line widths of a crossing of lines (an ellipse of 3 projected
 * widths across and 3 along the rows, about 150 mm on the ground) are
 * OTHER or YELLOW.  Painted lines cross on bare carpet; where two edges
 * of a robot's body, a goal's foot against its net or a cable on the floor
 * beyond the border meet, the dark is close by.  Marks have their own
 * test (crossings_marks.c). */
static bool cr_among_dark(const fl_lines_t *lines, const fl_scan_t *scan, const fl_crossing_t *x)
{
    int32_t wh, wv;
    cr_dark_t d;
    if (!scan || x->kind == FL_LM_PENALTY_MARK || x->kind == FL_LM_CENTRE_MARK)
        return false;
    wh = fl_lines_width_q4(lines, (x->v_q4 + 8) >> 4, false);
    wv = fl_lines_width_q4(lines, (x->v_q4 + 8) >> 4, true);
    if (wh <= 0 || wv <= 0)
        return false;
    d.carpet = true;
    fl_cr_dark(scan, x->u_q4, x->v_q4, 3 * wh, 3 * wv, &d);
    return d.dark >= 2 && 10 * d.dark > d.n;
}

/* Crossings on a standing object (a robot's legs and arms) or above the
 * carpet are no field feature: removed, order kept.  On white-goal fields
 * (today's SPL, colours from the frame) also those among dark cells
 * (cr_among_dark); the coloured-goal fields keep their outputs
 * bit-identical (their walks' stored observations are compared as they
 * are, and a yellow goal's foot is dark by class there). */
static void cr_drop_objects(fl_crossings_t *c, const fl_lines_t *lines, const fl_scan_t *scan,
                            const fl_field_t *field)
{
    int32_t i, n = 0;
    bool white_goals = field && field->goal_color[0] == FL_COLOR_WHITE;
    for (i = 0; i < c->n; i++) {
        int32_t u = (c->c[i].u_q4 + 8) >> 4, v = (c->c[i].v_q4 + 8) >> 4;
        if (fl_lines_on_object(lines, scan, u, v) || cr_above_border(lines, scan, u, v) ||
            (white_goals && cr_among_dark(lines, scan, &c->c[i]))) {
            c->robot_rejected++;
            continue;
        }
        if (n != i) {
            c->c[n] = c->c[i];
            memcpy(c->garm[n], c->garm[i], sizeof c->garm[n]);
        }
        n++;
    }
    c->n = n;
}

int32_t fl_crossings_find(fl_crossings_t *c, const fl_lines_t *lines,
                          const fl_scan_t *scan, const fl_camera_t *camera,
                          const fl_field_t *field)
{
    fl_angle_t (*garm)[4];
    int32_t i, j, sin_min, sin_tol;
    cr_ctx_t ctx;
    if (!c)
        return 0;
    c->n = 0;
    c->dropped = 0;
    c->pairs = 0;
    c->rejected_ground = 0;
    c->rejected_arms = 0;
    c->merged = 0;
    c->marks_capped = 0;
    c->border_t = 0;
    c->luma_probes = 0;
    c->connectors = 0;
    c->robot_rejected = 0;
    if (!lines || lines->width <= 0)
        return 0;
    if (scan && (scan->width != lines->width || scan->height != lines->height))
        scan = NULL;
    sin_min = fl_sin_q15(fl_angle_from_mdeg(c->params.min_angle_mdeg));
    sin_tol = fl_sin_q15(fl_angle_from_mdeg(c->params.ground_tol_mdeg));
    garm = c->garm;
    memset(c->garm, 0, sizeof c->garm);
    if (c->params.marks)
        fl_cr_marks(c, garm, lines, scan, camera, field);
    ctx.c = c;
    ctx.l = lines;
    ctx.scan = scan;
    ctx.cam = camera;
    ctx.field = field;
    ctx.sin_min_q15 = sin_min;
    ctx.sin_tol_q15 = sin_tol;
    for (i = 0; i < lines->n_segments; i++)
        for (j = i + 1; j < lines->n_segments; j++) {
            if ((lines->segments[i].flags & FL_SEG_CIRCLE) &&
                (lines->segments[j].flags & FL_SEG_CIRCLE))
                continue;
            fl_cr_pair(&ctx, i, j);
        }
    if (scan && camera)
        for (i = 0; i < lines->n_segments; i++)
            if (!(lines->segments[i].flags & FL_SEG_CIRCLE))
                fl_cr_border_t(&ctx, i);
    if (scan && camera)
        for (i = 0; i < lines->n_segments; i++)
            if (!(lines->segments[i].flags & FL_SEG_CIRCLE)) {
                fl_cr_connect(&ctx, i, false);
                fl_cr_connect(&ctx, i, true);
            }
    if (scan && camera)
        for (i = 0; i < lines->n_segments; i++)
            if (!(lines->segments[i].flags & FL_SEG_CIRCLE)) {
                fl_cr_close(&ctx, i, false);
                fl_cr_close(&ctx, i, true);
            }
    cr_drop_objects(c, lines, scan, field);
    return c->n;
}

/* White within one cell of a pixel (Q4). */
static bool cr_white_near(const fl_scan_t *s, int32_t u_q4, int32_t v_q4)
{
    int32_t du = 16 * s->params.col_step, dv = 16 * s->params.row_step;
    return cr_class_px(s, u_q4, v_q4) == FL_CLASS_WHITE ||
           cr_class_px(s, u_q4 + du, v_q4) == FL_CLASS_WHITE ||
           cr_class_px(s, u_q4 - du, v_q4) == FL_CLASS_WHITE ||
           cr_class_px(s, u_q4, v_q4 + dv) == FL_CLASS_WHITE ||
           cr_class_px(s, u_q4, v_q4 - dv) == FL_CLASS_WHITE;
}

/* Halfway-line direction for a circle found without one: the longest
 * segment (not a chord of the circle) at least a third of the radius long
 * on the ground whose ground line passes within max(150 mm, range / 10) of
 * the circle's centre (the circle stage asks for a full radius, which a
 * halfway line broken by the centre mark or cut by the image edge misses).
 * Direction folded to [-90, 90) deg like the circle's.  Scaling: ground
 * coordinates |mm| < 2^17, the cross product < 2^35 in int64 against
 * tolerance x length < 2^35. */
static bool cr_circle_axis(const fl_circle_t *circle, const fl_lines_t *lines,
                           const fl_camera_t *camera, int32_t R, fl_angle_t *out)
{
    int32_t i, best_len = 0, tol;
    tol = (int32_t)fl_hypot(circle->centre.x_mm, circle->centre.y_mm) / 10;
    if (tol < 150)
        tol = 150;
    for (i = 0; i < lines->n_segments && i < FL_LINES_MAX_SEGMENTS; i++) {
        const fl_segment_t *s = &lines->segments[i];
        fl_point_t a, b;
        int64_t dx, dy, cr;
        int32_t len;
        if ((s->flags & FL_SEG_CIRCLE) ||
            !fl_camera_pixel_to_ground(camera, s->u0_q4, s->v0_q4, &a) ||
            !fl_camera_pixel_to_ground(camera, s->u1_q4, s->v1_q4, &b))
            continue;
        dx = (int64_t)b.x_mm - a.x_mm;
        dy = (int64_t)b.y_mm - a.y_mm;
        if (dx < -(1 << 17) || dx > (1 << 17) || dy < -(1 << 17) || dy > (1 << 17))
            continue;
        len = (int32_t)fl_hypot((int32_t)dx, (int32_t)dy);
        if (3 * len < R || len <= best_len)
            continue;
        cr = dx * ((int64_t)circle->centre.y_mm - a.y_mm) -
             dy * ((int64_t)circle->centre.x_mm - a.x_mm);
        if (cr < 0)
            cr = -cr;
        if (cr <= (int64_t)tol * len) {
            fl_angle_t o = fl_atan2((int32_t)dy, (int32_t)dx);
            if (o >= 16384 || o < -16384)
                o = fl_angle_add(o, FL_ANGLE_180);
            *out = o;
            best_len = len;
        }
    }
    return best_len > 0;
}

/* Halfway-line direction for a circle found with no segment through its
 * centre (a blurred or faint halfway line): of 16 ground directions
 * through the centre, the one whose line is paint (fl_lines_paint_pct at
 * least the lines' white_pct) from 1.15 to 1.5 radii out on both sides,
 * the best of the two sides' paint; false when none (or a side leaves the
 * image).  Cost: 64 projections and at most 32 paint probes, only for
 * such a circle. */
static bool cr_circle_probe_axis(const fl_circle_t *circle, const fl_lines_t *lines,
                                 const fl_scan_t *scan, const fl_camera_t *camera, int32_t R,
                                 fl_angle_t *out)
{
    int32_t d, side, best = -1;
    for (d = 0; d < 16; d++) {
        fl_angle_t g = (fl_angle_t)(d * 2048);
        int32_t co = fl_cos_q15(g), so = fl_sin_q15(g), worst = 100;
        for (side = -1; side <= 1 && worst >= 0; side += 2) {
            fl_point_t a, b;
            int32_t ua, va, ub, vb, p;
            a.x_mm = circle->centre.x_mm + side * fl_mul_q15(R * 115 / 100, co);
            a.y_mm = circle->centre.y_mm + side * fl_mul_q15(R * 115 / 100, so);
            b.x_mm = circle->centre.x_mm + side * fl_mul_q15(R * 3 / 2, co);
            b.y_mm = circle->centre.y_mm + side * fl_mul_q15(R * 3 / 2, so);
            if (!fl_camera_ground_to_pixel(camera, a, &ua, &va) ||
                !fl_camera_ground_to_pixel(camera, b, &ub, &vb) || ua < 0 || va < 0 || ub < 0 ||
                vb < 0 || ua > 16 * (lines->width - 1) || ub > 16 * (lines->width - 1) ||
                va > 16 * (lines->height - 1) || vb > 16 * (lines->height - 1)) {
                worst = -1;
                break;
            }
            p = fl_lines_paint_pct(lines, scan, ua, va, ub, vb);
            if (p < worst)
                worst = p;
        }
        if (worst >= lines->params.white_pct && worst > best) {
            best = worst;
            *out = g;
        }
    }
    return best >= 0;
}

int32_t fl_crossings_add_circle(fl_crossings_t *c, const fl_circle_t *circle,
                                const fl_lines_t *lines, const fl_scan_t *scan,
                                const fl_camera_t *camera,
                                const fl_field_t *field)
{
    int32_t k, a, added = 0, R, step_q4;
    fl_angle_t ori;
    if (!c || !circle || !lines || !scan || !camera || !field || !circle->found ||
        field->circle_radius_mm <= 0 || lines->width <= 0 ||
        scan->width != lines->width || scan->height != lines->height)
        return 0;
    R = field->circle_radius_mm;
    ori = circle->orientation;
    if (!circle->has_orientation && !cr_circle_axis(circle, lines, camera, R, &ori) &&
        !cr_circle_probe_axis(circle, lines, scan, camera, R, &ori))
        return 0;
    step_q4 = 16 * lines->step_px;
    for (k = -1; k <= 1; k++) {
        cr_item_t it;
        fl_point_t p;
        int32_t u, v, w, merge;
        int16_t co = fl_cos_q15(ori), so = fl_sin_q15(ori);
        p.x_mm = circle->centre.x_mm + k * fl_mul_q15(R, co);
        p.y_mm = circle->centre.y_mm + k * fl_mul_q15(R, so);
        if (!fl_camera_ground_to_pixel(camera, p, &u, &v) || u < 0 || v < 0 ||
            u > 16 * (lines->width - 1) || v > 16 * (lines->height - 1) ||
            !cr_white_near(scan, u, v))
            continue;
        if (fl_lines_on_object(lines, scan, (u + 8) >> 4, (v + 8) >> 4)) {
            c->robot_rejected++;   /* the circle's line hidden by a robot */
            continue;
        }
        memset(&it, 0, sizeof it);
        it.x.kind = k == 0 ? FL_LM_CENTRE_MARK : FL_LM_X;
        it.x.u_q4 = u;
        it.x.v_q4 = v;
        it.x.ground = p;
        fl_polar_from_point(p, &it.x.range_mm, &it.x.bearing);
        it.x.seg_a = it.x.seg_b = -1;
        it.ground = true;
        for (a = 0; a < 4; a++) {
            fl_angle_t g = fl_angle_add(ori, (fl_angle_t)(a == 0 ? 0 : a == 1 ? 16384 : a == 2 ? -32768 : -16384));
            fl_point_t q;
            int32_t u2, v2;
            q.x_mm = p.x_mm + fl_mul_q15(100, fl_cos_q15(g));
            q.y_mm = p.y_mm + fl_mul_q15(100, fl_sin_q15(g));
            it.garm[it.x.n_arms] = g;
            if (fl_camera_ground_to_pixel(camera, q, &u2, &v2) && (u2 != u || v2 != v))
                it.x.arm[it.x.n_arms++] = fl_atan2(v2 - v, u2 - u);
        }
        it.x.confidence = (uint8_t)(circle->confidence * 3 / 4);
        fl_cr_orient(&it.x, it.garm, true);
        if (it.x.confidence < c->params.min_confidence)
            continue;
        w = cr_width_q4(lines, v);
        merge = 3 * w > 4 * step_q4 ? 3 * w : 4 * step_q4;
        fl_cr_add(c, c->garm, &it, merge, lines);
        added++;
    }
    return added;
}
