/*
 * src/vision/crossings.c - L, T and X crossings and the field marks (seed 000,
 * section 3.7); see crossings.h for the method.
 *
 * Algorithm.
 *   pairs    for i < j over the segments: image angle test (|sin| of the
 *            angle between the directions), intersection X of the two
 *            infinite lines (exact 64-bit solve in Q4), X inside the image,
 *            X within reach of both segments (a long far line: also a
 *            painted gap of up to 6 steps, see cr_bridge_one),
 *            X's position t along each segment, the local directions there
 *            (chord turned by the bulge's slope); arms by extent (t and
 *            len - t against arm_q4), probes in the class map for all four;
 *            ground check from the directions of both lines at X through
 *            the camera; type by arm count; marks by the ground length of
 *            short bars; insertion with merging into a crossing within
 *            merge distance (union of arms).
 *   marks    clusters of points off long segments within the projected
 *            mark size (bucket search from lines.c), isolated out to 2.5
 *            mark sizes, a ring of 16 samples at 1.6 mark sizes that must
 *            be green.
 *   border   per segment (not a circle chord) whose upper end runs up to
 *            the field border: walk the paint past the end, place the T
 *            half a (ground) line width before its stop, find the border
 *            beyond it and check it square to the segment on the ground
 *            (its pixels 3 steps either side projected), probe the
 *            continuation; arms from ground directions projected back.
 *   connect  per segment end where the paint stops: the ground normal
 *            to the nearest image-parallel segment within 1000 mm, a
 *            painted connector (class map or luma) gives an L at the end
 *            and a T at its foot (see cr_connect).
 *   close    per segment end where the paint stops: a parallel line 1 px
 *            to 2 steps across it a box depth away on the ground (a far
 *            goal box's front line end and the goal line): an L at the end
 *            and a T at its foot (see cr_close).
 *   circle   the centre mark and the halfway-line x circle X's of a found
 *            circle, projected back and checked white in the class map.
 *
 * Invariant.  Every stored crossing has 2..4 arms (marks from blobs: 0,
 * until merged), no two stored crossings are closer than the merge
 * distance at the time of insertion, n <= FL_CROSSINGS_MAX.
 *
 * Memory: the caller's fl_crossings_t (about 54 B per crossing, ground
 * arms included).  Stack: a visited bitmap of FL_LINES_MAX_POINTS bits
 * (<= 512 B) and a FL_LINES_NEAR_MAX id list in the mark search (< 900 B
 * in all).
 * Cost: segments^2 / 2 cheap pair tests; per surviving pair 4 probes of at
 * most 64 samples and 3-5 camera projections; per segment at most one
 * border test (3 walks of at most 64 samples, 4-8 projections); marks: one
 * bucket search per cluster and 16 map reads per candidate.
 *
 * Scaling and overflow.  Pixel positions Q4 (|u|, |v| < 2^17 for images up
 * to 4096 px).  Segment direction vectors in Q4 (< 2^17 each); the
 * intersection denominator (cross product) < 2^35, numerator < 2^36, the
 * product with a direction < 2^53: int64.  Unit directions Q15 from the
 * segment angle; projections (Q4 x Q15) < 2^33 in int64, shifted back with
 * rounding.  Angles are binary angles (wrap-around free).  Confidence
 * factors Q8 (256 = 1), multiplied in int32 (< 2^24).  Border T's: ground
 * offsets of at most 300 mm (fl_mul_q15), their pixel differences checked
 * below 2^20 Q4 before fl_hypot / fl_atan2; scale products (Q4 px x mm) in
 * int64; walks and probes capped at 64 px.
 */
#include "fieldloc/crossings.h"

#include <string.h>

#define CR_KAPPA_Q4 (12 * 16) /* probe distance for ground directions */
#define CR_SAME_ARM 4551      /* 25 deg: two arms within this are one */
#define CR_MARK_CLUSTERS_MAX 256 /* mark candidates looked at per frame */
#define CR_MARK_CLUSTERS_CLUTTER 64 /* ... once the line points overflowed */
#define CR_LUMA_PROBES 128    /* probes per frame that may read the luma */
#define CR_APART_MM 500      /* crossings farther apart on the ground never merge */
#define CR_FAR_MM 3000u       /* the ground check's tolerance grows beyond */
#define CR_FAR_TOL_MDEG 15000u /* ... by this much at twice that range */

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

fl_status_t fl_crossings_init(fl_crossings_t *c, const fl_crossings_params_t *p)
{
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

static int32_t cr_abs(int32_t a) { return a < 0 ? -a : a; }
static int64_t cr_abs64(int64_t a) { return a < 0 ? -a : a; }

/* |a - b| folded to [0, 180 deg] as a non-negative int32 (0..32768). */
static int32_t cr_adiff(fl_angle_t a, fl_angle_t b)
{
    return cr_abs(fl_angle_sub(a, b));
}

/* An image ray: from (xu, xv) (Q4) along the unit vector (cu, cv) (Q15).
 * (Helpers take it by pointer: at most six arguments, so no frame needs
 * stack-passed arguments.) */
typedef struct {
    int32_t xu, xv, cu, cv;
    int32_t r0, len;          /* probe: from r0 to r0 + len along it, Q4 */
    fl_point_t gx;            /* ground point of the start */
    int32_t white;            /* out: probe white ratio */
    fl_angle_t dir;           /* out: ground direction */
} cr_ray_t;

/* Ground direction (robot frame) of an image ray into r->dir.  r->gx:
 * ground point of its start.  False when neither this direction nor the
 * opposite one reaches the ground.  (The results are written into the
 * struct: gcc then keeps it a pointer instead of splitting it into more
 * than six scalar arguments.) */
static bool cr_ground_dir(const fl_camera_t *cam, cr_ray_t *r)
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
static void cr_orient(fl_crossing_t *x, const fl_angle_t *garm, bool ground)
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
static bool cr_type(fl_crossing_t *x)
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

/* Crossing plus its ground arms, while building. */
typedef struct {
    fl_crossing_t x;
    fl_angle_t garm[4];
    bool ground;
} cr_item_t;

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
static void cr_add(fl_crossings_t *c, fl_angle_t (*garm_store)[4],
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
            (void)cr_type(e);
        if (it->x.confidence > e->confidence) {
            e->u_q4 = it->x.u_q4;
            e->v_q4 = it->x.v_q4;
            e->ground = it->x.ground;
            e->range_mm = it->x.range_mm;
            e->bearing = it->x.bearing;
            e->confidence = it->x.confidence;
        }
        if (e->kind != FL_LM_PENALTY_MARK || e->n_arms >= 2)
            cr_orient(e, garm_store[k], it->ground);
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
static void cr_probe(fl_crossings_t *c, const fl_lines_t *l, const fl_scan_t *scan,
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
static fl_angle_t cr_local_angle(const fl_segment_t *s, int32_t t)
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
static int32_t cr_ground_len(const fl_camera_t *cam, const fl_segment_t *s)
{
    fl_point_t a, b;
    if (!cam || !fl_camera_pixel_to_ground(cam, s->u0_q4, s->v0_q4, &a) ||
        !fl_camera_pixel_to_ground(cam, s->u1_q4, s->v1_q4, &b))
        return -1;
    return (int32_t)fl_hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
}

/* Line width (Q4 px) at row v for the thresholds; step when unknown. */
static int32_t cr_width_q4(const fl_lines_t *l, int32_t v_q4)
{
    int32_t w = fl_lines_width_q4(l, v_q4 / 16, false);
    int32_t wv = fl_lines_width_q4(l, v_q4 / 16, true);
    if (wv > w)
        w = wv;
    return w;
}

/* Does a segment end within a line step of the image edge? */
static bool cr_cut(const fl_lines_t *l, const fl_segment_t *s)
{
    int32_t e = 16 * l->step_px, um = 16 * (l->width - 1) - e, vm = 16 * (l->height - 1) - e;
    return s->u0_q4 < e || s->v0_q4 < e || s->u0_q4 > um || s->v0_q4 > vm || s->u1_q4 < e ||
           s->v1_q4 < e || s->u1_q4 > um || s->v1_q4 > vm;
}

static int32_t cr_class_px(const fl_scan_t *s, int32_t u_q4, int32_t v_q4);

/* Is most of the straight path between two pixels (Q4) neither carpet
 * nor paint in the class map (a robot, a post in front of the line)?  At
 * most 64 samples, 1 px apart; false when no sample lies in the image. */
static bool cr_hidden(const fl_scan_t *s, int32_t u0, int32_t v0, int32_t u1, int32_t v1)
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

/* What every pair test of a frame shares. */
typedef struct {
    fl_crossings_t *c;
    const fl_lines_t *l;
    const fl_scan_t *scan;
    const fl_camera_t *cam;
    const fl_field_t *field;
    int32_t sin_min_q15, sin_tol_q15;
} cr_ctx_t;

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
static bool cr_end_ray(const cr_ctx_t *ctx, fl_angle_t ain, int32_t w, bool beside, cr_ray_t *r)
{
    if (!cr_follow_paint(ctx, ain, 16 * ctx->l->step_px + w / 2, beside, &r->xu, &r->xv))
        return false;
    r->cu = fl_cos_q15(ain);
    r->cv = fl_sin_q15(ain);
    if (!fl_camera_pixel_to_ground(ctx->cam, r->xu, r->xv, &r->gx) || !cr_ground_dir(ctx->cam, r))
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

static void cr_pair(const cr_ctx_t *ctx, int32_t ia, int32_t ib)
{
    fl_crossings_t *c = ctx->c;
    fl_angle_t (*garm_store)[4] = c->garm;
    const fl_lines_t *l = ctx->l;
    const fl_scan_t *scan = ctx->scan;
    const fl_camera_t *cam = ctx->cam;
    const fl_field_t *field = ctx->field;
    int32_t sin_min_q15 = ctx->sin_min_q15, sin_tol_q15 = ctx->sin_tol_q15;
    const fl_segment_t *A = &l->segments[ia], *B = &l->segments[ib];
    const fl_crossings_params_t *pp = &c->params;
    int64_t ax = (int64_t)A->u1_q4 - A->u0_q4, ay = (int64_t)A->v1_q4 - A->v0_q4;
    int64_t bx = (int64_t)B->u1_q4 - B->u0_q4, by = (int64_t)B->v1_q4 - B->v0_q4;
    int64_t den, num;
    int32_t xu, xv, ca, sa, cb, sb, ta, tb, w, arm, arm_a, arm_b, reach, sinab, k;
    int32_t step_q4 = 16 * l->step_px, conf, f;
    bool pres[4], geo[4];
    int32_t dirc[4], dirs[4], conflicts = 0, cntA, cntB;
    cr_item_t it;
    fl_point_t gx;
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
        fl_angle_t la = cr_local_angle(A, ta), lb = cr_local_angle(B, tb);
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
            (ta < -reach && !cr_hidden(scan, A->u0_q4, A->v0_q4, xu, xv)) ||
            (ta > A->len_q4 + reach && !cr_hidden(scan, A->u1_q4, A->v1_q4, xu, xv)) ||
            (tb < -reach && !cr_hidden(scan, B->u0_q4, B->v0_q4, xu, xv)) ||
            (tb > B->len_q4 + reach && !cr_hidden(scan, B->u1_q4, B->v1_q4, xu, xv)))
            return;
    }
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
            cr_probe(c, l, scan, &ray);
            pr = ray.white;
            if (pr >= pp->probe_white_pct && !geo[k])
                pres[k] = true;
            else if (pr >= 0 && pr < pp->probe_green_pct && geo[k])
                conflicts++;
        }
    }
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
        fl_angle_t ga, gb;
        int32_t between;
        cr_ray_t ra, rb;
        ra.xu = rb.xu = xu;
        ra.xv = rb.xv = xv;
        ra.cu = ca;
        ra.cv = sa;
        rb.cu = cb;
        rb.cv = sb;
        if (!fl_camera_pixel_to_ground(cam, xu, xv, &gx)) {
            c->rejected_ground++;
            return;
        }
        ra.gx = rb.gx = gx;
        if (!cr_ground_dir(cam, &ra) || !cr_ground_dir(cam, &rb)) {
            c->rejected_ground++;
            return;
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
                return;
            }
        }
        ground = true;
        it.ground = true;
        it.x.ground = gx;
        fl_polar_from_point(gx, &it.x.range_mm, &it.x.bearing);
        k = 0;
        if (pres[0]) it.garm[k++] = ga;
        if (pres[1]) it.garm[k++] = fl_angle_add(ga, FL_ANGLE_180);
        if (pres[2]) it.garm[k++] = gb;
        if (pres[3]) it.garm[k++] = fl_angle_add(gb, FL_ANGLE_180);
        /* confidence factor of squareness, Q8: 256 at 90 deg, 128 at tol */
        conf = 256 - (int32_t)(((int64_t)f * 128) / (sin_tol_q15 > 0 ? sin_tol_q15 : 1));
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
    if (!cr_type(&it.x)) {
        c->rejected_arms++;
        return;
    }
    /* a short bar crossing a line is a mark: centre mark (on a line) or
     * penalty mark (two short bars) */
    if (it.x.kind == FL_LM_X && cam && field && field->mark_size_mm > 0) {
        int32_t la = cr_ground_len(cam, A), lb = cr_ground_len(cam, B);
        int32_t lim = 5 * field->mark_size_mm / 2;
        /* (a bar cut off by the image edge is no short bar) */
        bool sa_ = la >= 0 && la <= lim && !cr_cut(l, A), sb_ = lb >= 0 && lb <= lim && !cr_cut(l, B);
        if (sa_ && sb_)
            it.x.kind = FL_LM_PENALTY_MARK;
        else if (sa_ || sb_)
            it.x.kind = FL_LM_CENTRE_MARK;
    }
    if (it.x.confidence < pp->min_confidence)
        return;
    cr_orient(&it.x, it.garm, ground);
    {
        int32_t merge = 3 * w > 4 * step_q4 ? 3 * w : 4 * step_q4;
        cr_add(c, garm_store, &it, merge, l);
    }
}

/* ---- marks ------------------------------------------------------------------ */

static int32_t cr_class_px(const fl_scan_t *s, int32_t u_q4, int32_t v_q4)
{
    int32_t i, j;
    uint64_t w;
    if (u_q4 < 0 || v_q4 < 0)
        return FL_CLASS_OTHER;
    i = (u_q4 / 16 + s->params.col_step / 2) / s->params.col_step;
    j = (v_q4 / 16 + s->params.row_step / 2) / s->params.row_step;
    if (i >= s->cols || j >= s->rows)
        return FL_CLASS_OTHER;
    w = s->map[j][i >> 5];
    return (int32_t)((w >> (62 - 2 * (i & 31))) & 3u);
}

/* cos / sin of k * 22.5 deg, Q8 */
static const int16_t cr_ring_c[16] = {256, 237, 181, 98, 0, -98, -181, -237,
                                      -256, -237, -181, -98, 0, 98, 181, 237};

/* A census of the line points around a mark candidate: in: the centre
 * (cu, cv), the inner ellipse half-axes (iu, iv), the outer box (ou, ov),
 * all Q1, and the length (Q4) above which a segment is "long"; out: the
 * points inside the inner ellipse (summed into su, sv, counted in n_in,
 * long_in of them on long segments) and those outside it but within the
 * outer ellipse (n_out). */
typedef struct {
    int32_t cu, cv, iu, iv, ou, ov, long_q4;
    int32_t su, sv, n_in, n_out, long_in, luma_in;
} cr_census_t;

static void cr_mark_census(const fl_lines_t *l, cr_census_t *k, uint32_t *vis)
{
    uint16_t ids[FL_LINES_NEAR_MAX];
    int32_t n, j, cu = k->cu, cv = k->cv;
    int64_t iu = k->iu, iv = k->iv, ou = k->ou, ov = k->ov;
    k->su = k->sv = k->n_in = k->n_out = k->long_in = k->luma_in = 0;
    n = fl_lines_points_near(l, cu, cv, k->ou / 2 + 1, k->ov / 2 + 1, ids);
    if (n > FL_LINES_NEAR_MAX) {
        k->n_out = n;
        return;
    }
    for (j = 0; j < n; j++) {
        const fl_line_point_t *q = &l->points[ids[j]];
        int64_t du = q->u_q1 - cu, dv = q->v_q1 - cv;
        /* inside the inner ellipse: du^2 / iu^2 + dv^2 / iv^2 <= 1 */
        if (du * du * iv * iv + dv * dv * iu * iu <= iu * iu * iv * iv) {
            k->n_in++;
            if (q->flags & FL_LINE_POINT_LUMA)
                k->luma_in++;
            k->su += q->u_q1;
            k->sv += q->v_q1;
            if (q->seg != FL_LINES_NONE && l->segments[q->seg].len_q4 > k->long_q4)
                k->long_in++;
            if (vis)
                vis[ids[j] >> 5] |= 1u << (ids[j] & 31);
        } else if (du * du * ov * ov + dv * dv * ou * ou <= ou * ou * ov * ov) {
            /* a point of a long line passing by, its line farther than
             * twice the inner ellipse across it, is no clutter */
            if (q->seg != FL_LINES_NONE && l->segments[q->seg].len_q4 > k->long_q4) {
                const fl_segment_t *s = &l->segments[q->seg];
                int32_t d = fl_segment_distance_q4(s, 8 * cu, 8 * cv);
                int32_t m = (int32_t)((16 * (iu * cr_abs(fl_sin_q15(s->angle)) +
                                             iv * cr_abs(fl_cos_q15(s->angle)))) >> 15);
                if (d > m || d < -m)
                    continue;
            }
            k->n_out++;
        }
    }
}

static void cr_marks(fl_crossings_t *c, fl_angle_t (*garm_store)[4],
                     const fl_lines_t *l, const fl_scan_t *scan,
                     const fl_camera_t *cam, const fl_field_t *field)
{
    uint32_t vis[(FL_LINES_MAX_POINTS + 31) / 32];
    int32_t k, lw = l->line_width_mm, step_q4 = 16 * l->step_px, clusters = 0;
    int32_t max_clusters = l->points_dropped > 0 ? CR_MARK_CLUSTERS_CLUTTER
                                                 : CR_MARK_CLUSTERS_MAX;
    if (!scan || !field || field->mark_size_mm <= 0 || lw <= 0 || !cam)
        return;
    memset(vis, 0, sizeof vis);
    for (k = 0; k < l->n_points; k++) {
        const fl_line_point_t *p = &l->points[k];
        int32_t wh, wv, mh, mv, iu, iv, ou, ov, n_in, cu, cv, green = 0, white = 0, outside = 0,
            conf, ru, rv, j, long_q4;
        cr_census_t cc;
        cr_item_t it;
        fl_point_t g;
        if (vis[k >> 5] & (1u << (k & 31)))
            continue;
        vis[k >> 5] |= 1u << (k & 31);
        if (++clusters > max_clusters) {
            c->marks_capped++;
            return;
        }
        wh = fl_lines_width_q4(l, p->v_q1 / 2, false);
        wv = fl_lines_width_q4(l, p->v_q1 / 2, true);
        if (wh <= 0 || wv <= 0)
            continue;
        mh = field->mark_size_mm * wh / lw;  /* mark size, Q4 px */
        mv = field->mark_size_mm * wv / lw;
        /* a mark under 2.5 px tall is a speck, as are the corners of far
         * lines too faint for the class map: not looked for */
        if (mv < 0)
            continue;
        long_q4 = 2 * mh + step_q4;
        if (p->seg != FL_LINES_NONE && l->segments[p->seg].len_q4 > long_q4)
            continue;
        /* inner ellipse 0.75 mark (>= 2 px), outer 2.5 marks (>= 7 / 5 px), Q1 */
        iu = mh * 3 / 32 > 4 ? mh * 3 / 32 : 4;
        iv = mv * 3 / 32 > 4 ? mv * 3 / 32 : 4;
        ou = mh * 5 / 16 > 14 ? mh * 5 / 16 : 14;
        ov = mv * 5 / 16 > 10 ? mv * 5 / 16 : 10;
        cc.cu = p->u_q1;
        cc.cv = p->v_q1;
        cc.iu = iu;
        cc.iv = iv;
        cc.ou = ou;
        cc.ov = ov;
        cc.long_q4 = long_q4;
        cr_mark_census(l, &cc, NULL);
        if (cc.n_in < 2 || cc.long_in > 0)
            continue;
        cc.cu = cc.su / cc.n_in;
        cc.cv = cc.sv / cc.n_in;
        cr_mark_census(l, &cc, vis);
        /* luma points (noise ridges of a dark frame, the bright rims of
         * carpet seams) count only beside 2 class-map points, or in a
         * cluster of 3 (a far mark: one white run and its blurred ends),
         * or beside one class-map point where the mark is at most 2 line
         * steps across (2 scan columns cross it at most) */
        if (cc.n_in < 2 || cc.long_in > 0 || cc.n_out > 0 ||
            (cc.luma_in > 0 && cc.n_in < 3 &&
             cc.n_in - cc.luma_in < (mh <= 2 * step_q4 ? 1 : 2)))
            continue;
        n_in = cc.n_in;
        cu = cc.su * 8 / n_in; /* Q4 */
        cv = cc.sv * 8 / n_in;
        /* ring of 16 samples at 1.6 mark sizes (at least 4 / 3 px) */
        ru = mh * 16 / 10;
        rv = mv * 16 / 10;
        if (ru < 64)
            ru = 64;
        if (rv < 48)
            rv = 48;
        /* samples outside the image (a mark near its edge) are not
         * counted: 13 of 16 green means 13/16 of those inside, at least 8: a mark
         * cut by the image edge has half its ring */
        for (j = 0; j < 16; j++) {
            int32_t su = cu + ru * cr_ring_c[j] / 256, sv = cv + rv * cr_ring_c[(j + 4) & 15] / 256;
            int32_t cls;
            if (su < 0 || sv < 0 || su > 16 * (l->width - 1) || sv > 16 * (l->height - 1)) {
                outside++;
                continue;
            }
            cls = cr_class_px(scan, su, sv);
            if (cls == FL_CLASS_GREEN)
                green++;
            else if (cls == FL_CLASS_WHITE)
                white++;
        }
        if (outside > 8 || 16 * green < 13 * (16 - outside) || white > 0)
            continue;
        green += outside;
        if (!fl_camera_pixel_to_ground(cam, cu, cv, &g))
            continue;
        memset(&it, 0, sizeof it);
        it.x.kind = FL_LM_PENALTY_MARK;
        it.x.u_q4 = cu;
        it.x.v_q4 = cv;
        it.x.ground = g;
        fl_polar_from_point(g, &it.x.range_mm, &it.x.bearing);
        it.x.seg_a = it.x.seg_b = -1;
        it.ground = true;
        conf = 110 + 25 * (n_in < 5 ? n_in : 5) - 10 * (16 - green);
        it.x.confidence = (uint8_t)(conf > 255 ? 255 : conf < 0 ? 0 : conf);
        if (it.x.confidence < c->params.min_confidence)
            continue;
        {
            int32_t merge = 2 * mh > 4 * step_q4 ? 2 * mh : 4 * step_q4;
            cr_add(c, garm_store, &it, merge, l);
        }
    }
}

/* ---- T at the field border (one segment) ----------------------------------- */

/* Ground length (mm) over which image scales are measured along a ground
 * direction. */
#define CR_SCALE_MM 300
/* A line ending at most this far (ground, mm) before the field border ends
 * at the boundary line (the field's border strip is 700 mm). */
#define CR_BORDER_MM 1000
/* The segment must run up toward the border: |sin| of its image angle from
 * horizontal at least sin 10 deg (Q15; flatter ones run along the border,
 * like the boundary line itself). */
#define CR_BORDER_MIN_SIN 5690

/* Image direction of the ground direction r->dir from the ground point
 * r->gx (pixel r->xu, r->xv): unit vector into r->cu, r->cv (Q15); returns
 * the pixel length (Q4) of CR_SCALE_MM on the ground that way (from a
 * third of it, times 3, when the far point is beyond the horizon), 0 when
 * it does not project.  Scaling: ground offsets fl_mul_q15(mm, Q15) in
 * int32; the direction from fl_atan2 of Q4 pixel differences (checked
 * below 2^20). */
static int32_t cr_image_dir(const fl_camera_t *cam, cr_ray_t *r)
{
    int32_t k, u, v, du, dv, len;
    for (k = 1; k <= 3; k += 2) {
        fl_point_t q;
        fl_angle_t a;
        int32_t mm = CR_SCALE_MM / k;
        q.x_mm = r->gx.x_mm + fl_mul_q15(mm, fl_cos_q15(r->dir));
        q.y_mm = r->gx.y_mm + fl_mul_q15(mm, fl_sin_q15(r->dir));
        if (!fl_camera_ground_to_pixel(cam, q, &u, &v))
            continue;
        du = u - r->xu;
        dv = v - r->xv;
        if (cr_abs(du) > (1 << 20) || cr_abs(dv) > (1 << 20))
            return 0;
        len = (int32_t)fl_hypot(du, dv);
        if (len < 8)
            return 0;
        a = fl_atan2(dv, du);
        r->cu = fl_cos_q15(a);
        r->cv = fl_sin_q15(a);
        return len * k;
    }
    return 0;
}

/* Distance (Q4) from the ray's start to the last white sample of its
 * paint, walking 1 px steps up to r->len (thin-line tolerant: white at the
 * sample or one pixel either side across; one non-white sample is
 * bridged); -1 when still white at the end (the line goes on). */
static int32_t cr_walk(const fl_scan_t *s, const cr_ray_t *r)
{
    int32_t t, last = 0, miss = 0;
    int32_t au = fl_rshift_round((int64_t)-r->cv * 16, 15);
    int32_t av = fl_rshift_round((int64_t)r->cu * 16, 15);
    for (t = 16; t <= r->len; t += 16) {
        int32_t u = r->xu + fl_rshift_round((int64_t)r->cu * t, 15);
        int32_t v = r->xv + fl_rshift_round((int64_t)r->cv * t, 15);
        if (cr_class_px(s, u, v) == FL_CLASS_WHITE ||
            cr_class_px(s, u + au, v + av) == FL_CLASS_WHITE ||
            cr_class_px(s, u - au, v - av) == FL_CLASS_WHITE) {
            last = t;
            miss = 0;
        } else if (++miss >= 2) {
            return last;
        }
    }
    return miss > 0 ? last : -1;
}

/* Is the field border within max_q4 (at most 64 px) of the ray's start
 * along it, with nothing but field colors on the way, and does the border
 * there run square (within ground_tol) to the ground direction g?  The
 * border's ground direction: its pixels 3 line steps either side of the
 * column where the ray meets it, projected to the ground. */
static bool cr_border_near(const cr_ctx_t *ctx, const cr_ray_t *r, int32_t max_q4,
                           fl_angle_t g)
{
    const fl_scan_t *s = ctx->scan;
    int32_t cs = s->params.col_step, t, i = -1, k, i0, i1;
    fl_point_t a, b;
    if (max_q4 > 16 * 64)
        max_q4 = 16 * 64;
    for (t = 0; t <= max_q4; t += 16) {
        int32_t u = r->xu + fl_rshift_round((int64_t)r->cu * t, 15);
        int32_t v = r->xv + fl_rshift_round((int64_t)r->cv * t, 15);
        if (u < 0 || v < 0 || u >= 16 * s->width)
            return false;
        k = (u / 16 + cs / 2) / cs;
        if (k >= s->cols)
            k = s->cols - 1;
        if (v / 16 < s->border_v[k]) {
            i = k;
            break;
        }
        if (cr_class_px(s, u, v) == FL_CLASS_OTHER)
            return false; /* something in between (a robot, a ball) */
    }
    if (i < 0)
        return false;
    k = 3 * ctx->l->step_px / cs;
    if (k < 1)
        k = 1;
    i0 = i - k < 0 ? 0 : i - k;
    i1 = i + k >= s->cols ? s->cols - 1 : i + k;
    if (i1 - i0 < k || s->border_v[i0] >= s->height || s->border_v[i1] >= s->height ||
        !fl_camera_pixel_to_ground(ctx->cam, 16 * i0 * cs, 16 * s->border_v[i0], &a) ||
        !fl_camera_pixel_to_ground(ctx->cam, 16 * i1 * cs, 16 * s->border_v[i1], &b) ||
        (a.x_mm == b.x_mm && a.y_mm == b.y_mm))
        return false;
    return cr_abs(fl_cos_q15(fl_angle_sub(fl_atan2(b.y_mm - a.y_mm, b.x_mm - a.x_mm), g))) <=
           ctx->sin_tol_q15;
}

/* A T at the upper end of a single segment that runs up to the field
 * border: far away the boundary line there is a pixel or less tall (its
 * paint blends into the carpet, or the border search puts it above the
 * border), so no segment pairs with this one.  The paint is followed past
 * the segment's end to where it stops (at most reach); the crossing is
 * half a line width (on the ground) before that; it is kept when the
 * border is within CR_BORDER_MM beyond it, running square to the segment on
 * the ground, with only field colors between, and the segment's
 * continuation past the crossing is not white.  Arms: the segment and the
 * boundary line both ways (square on the ground). */
static void cr_border_t(const cr_ctx_t *ctx, int32_t is)
{
    fl_crossings_t *c = ctx->c;
    const fl_lines_t *l = ctx->l;
    const fl_segment_t *S = &l->segments[is];
    const fl_camera_t *cam = ctx->cam;
    int32_t step_q4 = 16 * l->step_px, lw = l->line_width_mm, w, reach, t, k, plen, wd;
    int32_t merge, lim, f, conf, eu, ev, du, dv;
    fl_angle_t out = S->angle, gin;
    cr_ray_t r;
    cr_item_t it;

    /* long enough for its direction to be followed (3 line steps), its
     * upper end running up toward the border */
    if (S->len_q4 < 3 * step_q4)
        return;
    if (fl_sin_q15(out) > 0)
        out = fl_angle_add(out, FL_ANGLE_180);
    du = fl_cos_q15(out);
    dv = fl_sin_q15(out);
    if (dv > -CR_BORDER_MIN_SIN)
        return;
    eu = S->v0_q4 < S->v1_q4 ? S->u0_q4 : S->u1_q4;
    ev = S->v0_q4 < S->v1_q4 ? S->v0_q4 : S->v1_q4;
    w = cr_width_q4(l, ev);
    if (w <= 0 || lw <= 0)
        return;
    /* the segment's ground direction (inward) and the scale along it */
    r.xu = eu;
    r.xv = ev;
    r.cu = -du;
    r.cv = -dv;
    if (!fl_camera_pixel_to_ground(cam, eu, ev, &r.gx) || !cr_ground_dir(cam, &r))
        return;
    gin = r.dir;
    r.dir = fl_angle_add(gin, FL_ANGLE_180);
    plen = cr_image_dir(cam, &r);
    if (plen <= 0)
        return;
    wd = (int32_t)((int64_t)plen * lw / CR_SCALE_MM); /* boundary paint, Q4 */
    /* follow the paint past the end */
    reach = 3 * step_q4 > 3 * w ? 3 * step_q4 : 3 * w;
    if (reach > 16 * 64)
        reach = 16 * 64;
    r.cu = du;
    r.cv = dv;
    r.len = reach;
    t = cr_walk(ctx->scan, &r);
    if (t < 0)
        return;
    t -= wd / 2;
    if (t < 0)
        t = 0;
    r.xu = eu + fl_rshift_round((int64_t)du * t, 15);
    r.xv = ev + fl_rshift_round((int64_t)dv * t, 15);
    if (r.xu < 0 || r.xv < 0 || r.xu > 16 * (l->width - 1) || r.xv > 16 * (l->height - 1))
        return;
    /* a crossing found by a pair is better */
    merge = 3 * w > 4 * step_q4 ? 3 * w : 4 * step_q4;
    for (k = 0; k < c->n; k++) {
        int64_t a = (int64_t)c->c[k].u_q4 - r.xu, b = (int64_t)c->c[k].v_q4 - r.xv;
        if (a * a + b * b <= (int64_t)merge * merge)
            return;
    }
    if (!fl_camera_pixel_to_ground(cam, r.xu, r.xv, &r.gx) ||
        !cr_border_near(ctx, &r, (int32_t)((int64_t)plen * CR_BORDER_MM / CR_SCALE_MM), gin))
        return;
    /* the segment does not go on past the boundary line */
    lim = 3 * step_q4 > 2 * w ? 3 * step_q4 : 2 * w;
    r.r0 = wd + 16;
    r.len = plen / 2 < lim ? plen / 2 : lim;
    if (r.len < 48)
        r.len = 48;
    cr_probe(c, l, ctx->scan, &r);
    if (r.white >= c->params.probe_green_pct)
        return;
    memset(&it, 0, sizeof it);
    it.x.seg_a = (int16_t)is;
    it.x.seg_b = -1;
    it.x.u_q4 = r.xu;
    it.x.v_q4 = r.xv;
    it.x.ground = r.gx;
    fl_polar_from_point(r.gx, &it.x.range_mm, &it.x.bearing);
    it.ground = true;
    it.x.arm[0] = fl_angle_add(out, FL_ANGLE_180);
    it.garm[0] = gin;
    it.x.n_arms = 1;
    for (k = 0; k < 2; k++) {
        r.dir = fl_angle_add(gin, (fl_angle_t)(k ? -FL_ANGLE_90 : FL_ANGLE_90));
        if (cr_image_dir(cam, &r) <= 0)
            return;
        it.x.arm[it.x.n_arms] = fl_atan2(r.cv, r.cu);
        it.garm[it.x.n_arms] = r.dir;
        it.x.n_arms++;
    }
    if (!cr_type(&it.x))
        return;
    /* one segment and an unseen line: below a pair's confidence, short
     * segments less */
    f = S->len_q4 >= 4 * step_q4 ? 256 : 77 + (int32_t)((int64_t)179 * S->len_q4 / (4 * step_q4));
    conf = 160 * f / 256;
    it.x.confidence = (uint8_t)conf;
    if (it.x.confidence < c->params.min_confidence)
        return;
    cr_orient(&it.x, it.garm, true);
    c->border_t++;
    cr_add(c, c->garm, &it, merge, l);
}

/* ---- corners of a short connector (two parallel far lines) ------------------- */

/* Longest connector on the ground (the goal box is 600 mm deep). */
#define CR_CONN_MM 1000
/* Parallel in the image: |sin| of the angle between the two lines at most
 * sin 12 deg (Q15). */
#define CR_CONN_PAR_SIN 6813

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
static void cr_connect(const cr_ctx_t *ctx, int32_t is, bool end1)
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
    if (!cr_end_ray(ctx, ain, w, false, &r))
        return;
    eu = r.xu;
    ev = r.xv;
    gin = r.dir;
    r.len = 2 * step_q4 > 2 * w ? 2 * step_q4 : 2 * w;
    cr_probe(c, l, ctx->scan, &r);
    if (r.white < 0 || r.white >= c->params.probe_green_pct)
        return;
    arm = 2 * step_q4 > 2 * w ? 2 * step_q4 : 2 * w;
    for (k = 0; k < 2; k++) {
        int32_t plen, best = -1, bt = 0, btp = 0, fu, fv, ou, ov, tmin;
        int64_t cu, cv;
        cr_item_t it;
        fl_point_t gf;
        r.xu = eu;
        r.xv = ev;
        r.dir = fl_angle_add(gin, (fl_angle_t)(k ? -FL_ANGLE_90 : FL_ANGLE_90));
        plen = cr_image_dir(cam, &r);
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
        if (best < 0)
            continue;
        fu = eu + fl_rshift_round(cu * bt, 15);
        fv = ev + fl_rshift_round(cv * bt, 15);
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
            btp += bj * step_q4 / 2;
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
        /* T (or L) at F first: not where a pair already found a crossing */
        {
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
            it.x.ground = gf;
            fl_polar_from_point(gf, &it.x.range_mm, &it.x.bearing);
            it.ground = true;
            it.x.arm[0] = fl_atan2(-r.cv, -r.cu);
            it.garm[0] = fl_angle_add(r.dir, FL_ANGLE_180);
            it.x.n_arms = 1;
            if (P->len_q4 - btp >= arm) {
                it.x.arm[it.x.n_arms] = P->angle;
                it.garm[it.x.n_arms++] = gp;
            }
            if (btp >= arm) {
                it.x.arm[it.x.n_arms] = fl_angle_add(P->angle, FL_ANGLE_180);
                it.garm[it.x.n_arms++] = fl_angle_add(gp, FL_ANGLE_180);
            }
            it.x.confidence = (uint8_t)conf;
            if (!near && cr_type(&it.x)) {
                cr_orient(&it.x, it.garm, true);
                c->connectors++;
                cr_add(c, c->garm, &it, mf < bt / 2 ? mf : bt / 2, l);
            }
        }
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
        if (cr_type(&it.x)) {
            cr_orient(&it.x, it.garm, true);
            c->connectors++;
            cr_add(c, c->garm, &it, merge < bt / 2 ? merge : bt / 2, l);
        }
        return;
    }
}

/* Close parallel lines: the corners of a far goal box (or penalty area).
 * Far away the box side projects to a stub of a few px between the goal
 * line and the box front line, which lie 2-8 px apart: too close for
 * cr_connect (its connector would be under 2 steps and run along the
 * lines) and for the pairs (the stub is rarely a segment).  Per end E of
 * a long segment S (6 steps), no crossing within merge distance, E moved
 * out along S while the paint goes on (up to a step, as in cr_connect):
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
/* cr_close without a segment for the farther line: F = E's ground point
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
                    cr_hidden(ctx->scan, pu, pv, pu - hu, pv - hv))
                    p2 = p1;
                if (p2 >= l->params.white_pct && p1 < p2 &&
                    cr_hidden(ctx->scan, pu, pv, pu + hu, pv + hv))
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

static void cr_close(const cr_ctx_t *ctx, int32_t is, bool end1)
{
    fl_crossings_t *c = ctx->c;
    const fl_lines_t *l = ctx->l;
    const fl_segment_t *S = &l->segments[is];
    const fl_camera_t *cam = ctx->cam;
    const fl_field_t *field = ctx->field;
    int32_t step_q4 = 16 * l->step_px, eu, ev, w, merge, k, j, best = -1, bd = 0, conf;
    int32_t fu, fv, depth[2];
    int64_t gx, gy, dx, dy, len2, dot, cr, rE;
    fl_angle_t ain, gin, gp;
    fl_point_t gA, gB, gF;
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
    /* the nearest image-parallel segment 1 px to 2 steps across E */
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
    /* the segment's extreme point stops up to a step short of the paint;
     * S's paint stops at E */
    r.xu = eu;
    r.xv = ev;
    if (!cr_end_ray(ctx, ain, w, true, &r))
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
        cr_foot_t ft;
        if (!cr_close_model(ctx, &r, gin, S->angle, &ft))
            return;
        gF = ft.g;
        fu = ft.u;
        fv = ft.v;
        t_ok = ft.t_ok;
        /* gin is S's ground direction from E inward */
        gp = end1 ? fl_angle_add(gin, FL_ANGLE_180) : gin;
    } else
    /* P on the ground: E's distance D from its line, farther away */
    {
        const fl_segment_t *P = &l->segments[best];
        int32_t D, ok = 0;
        if (!fl_camera_pixel_to_ground(cam, P->u0_q4, P->v0_q4, &gA) ||
            !fl_camera_pixel_to_ground(cam, P->u1_q4, P->v1_q4, &gB))
            return;
        if (cr_abs(gA.x_mm) > 65535 || cr_abs(gA.y_mm) > 65535 || cr_abs(gB.x_mm) > 65535 ||
            cr_abs(gB.y_mm) > 65535 || cr_abs(r.gx.x_mm) > 65535 || cr_abs(r.gx.y_mm) > 65535)
            return;
        dx = (int64_t)gB.x_mm - gA.x_mm;
        dy = (int64_t)gB.y_mm - gA.y_mm;
        len2 = dx * dx + dy * dy;
        if (len2 <= 0)
            return;
        gx = (int64_t)r.gx.x_mm - gA.x_mm;
        gy = (int64_t)r.gx.y_mm - gA.y_mm;
        cr = gx * dy - gy * dx;
        dot = gx * dx + gy * dy;
        D = (int32_t)(cr_abs64(cr) / (int64_t)fl_hypot((int32_t)dx, (int32_t)dy));
        for (k = 0; k < 2; k++)
            if (depth[k] > 0 && 100 * cr_abs(D - depth[k]) <= CR_CLOSE_TOL_PCT * depth[k])
                ok = 1;
        if (!ok)
            return;
        gF.x_mm = gA.x_mm + (int32_t)fl_div_round(dx * dot, len2);
        gF.y_mm = gA.y_mm + (int32_t)fl_div_round(dy * dot, len2);
        rE = (int64_t)r.gx.x_mm * r.gx.x_mm + (int64_t)r.gx.y_mm * r.gx.y_mm;
        if ((int64_t)gF.x_mm * gF.x_mm + (int64_t)gF.y_mm * gF.y_mm <= rE)
            return;
        if (!fl_camera_ground_to_pixel(cam, gF, &fu, &fv))
            return;
        if (fu < 0 || fv < 0 || fu > 16 * (l->width - 1) || fv > 16 * (l->height - 1))
            return;
        gp = fl_atan2((int32_t)dy, (int32_t)dx);
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
        if (!near && t_ok && cr_type(&it.x)) {
            cr_orient(&it.x, it.garm, true);
            c->connectors++;
            cr_add(c, c->garm, &it, mef, l);
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
        if (cr_type(&it.x)) {
            cr_orient(&it.x, it.garm, true);
            c->connectors++;
            cr_add(c, c->garm, &it, mef, l);
        }
    }
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
    if (!lines || lines->width <= 0)
        return 0;
    if (scan && (scan->width != lines->width || scan->height != lines->height))
        scan = NULL;
    sin_min = fl_sin_q15(fl_angle_from_mdeg(c->params.min_angle_mdeg));
    sin_tol = fl_sin_q15(fl_angle_from_mdeg(c->params.ground_tol_mdeg));
    garm = c->garm;
    memset(c->garm, 0, sizeof c->garm);
    if (c->params.marks)
        cr_marks(c, garm, lines, scan, camera, field);
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
            cr_pair(&ctx, i, j);
        }
    if (scan && camera)
        for (i = 0; i < lines->n_segments; i++)
            if (!(lines->segments[i].flags & FL_SEG_CIRCLE))
                cr_border_t(&ctx, i);
    if (scan && camera)
        for (i = 0; i < lines->n_segments; i++)
            if (!(lines->segments[i].flags & FL_SEG_CIRCLE)) {
                cr_connect(&ctx, i, false);
                cr_connect(&ctx, i, true);
            }
    if (scan && camera)
        for (i = 0; i < lines->n_segments; i++)
            if (!(lines->segments[i].flags & FL_SEG_CIRCLE)) {
                cr_close(&ctx, i, false);
                cr_close(&ctx, i, true);
            }
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
        cr_orient(&it.x, it.garm, true);
        if (it.x.confidence < c->params.min_confidence)
            continue;
        w = cr_width_q4(lines, v);
        merge = 3 * w > 4 * step_q4 ? 3 * w : 4 * step_q4;
        cr_add(c, c->garm, &it, merge, lines);
        added++;
    }
    return added;
}
