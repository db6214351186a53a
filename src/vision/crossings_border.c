/*
 * src/vision/crossings_border.c - T at the field border (one segment)
 * (crossings_int.h for the algorithm, scaling and cost model).
 */
#include "crossings_int.h"

#include <string.h>

/* ---- T at the field border (one segment) ----------------------------------- */

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
int32_t fl_cr_image_dir(const fl_camera_t *cam, cr_ray_t *r)
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
void fl_cr_border_t(const cr_ctx_t *ctx, int32_t is)
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
    if (!fl_camera_pixel_to_ground(cam, eu, ev, &r.gx) || !fl_cr_ground_dir(cam, &r))
        return;
    gin = r.dir;
    r.dir = fl_angle_add(gin, FL_ANGLE_180);
    plen = fl_cr_image_dir(cam, &r);
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
    fl_cr_probe(c, l, ctx->scan, &r);
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
        if (fl_cr_image_dir(cam, &r) <= 0)
            return;
        it.x.arm[it.x.n_arms] = fl_atan2(r.cv, r.cu);
        it.garm[it.x.n_arms] = r.dir;
        it.x.n_arms++;
    }
    if (!fl_cr_type(&it.x))
        return;
    /* one segment and an unseen line: below a pair's confidence, short
     * segments less */
    f = S->len_q4 >= 4 * step_q4 ? 256 : 77 + (int32_t)((int64_t)179 * S->len_q4 / (4 * step_q4));
    conf = 160 * f / 256;
    it.x.confidence = (uint8_t)conf;
    if (it.x.confidence < c->params.min_confidence)
        return;
    fl_cr_orient(&it.x, it.garm, true);
    c->border_t++;
    fl_cr_add(c, c->garm, &it, merge, l);
}
