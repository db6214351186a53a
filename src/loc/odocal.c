/*
 * src/loc/odocal.c - odometry scale calibration from an observer's track
 * (fieldloc/odocal.h).
 *
 * Integer bounds: the pair sums work in cm; a pair is used only when its
 * distances are below ODOCAL_MAX_PAIR_CM (20 m), so a squared distance is
 * below 4e6 cm^2, a product of two below 1.6e13 and the sum over at most
 * 64 x 63 / 2 pairs below 3.3e16 (int64 holds 9.2e18).
 */
#include "fieldloc/odocal.h"

#include <string.h>

#define ODOCAL_MAX_PAIR_CM 2000
#define ODOCAL_MAX_STEP_MM 1000
#define ODOCAL_MAX_POS_MM 100000

fl_status_t fl_odocal_init(fl_odocal_t *c)
{
    if (c == NULL)
        return FL_ERR_NULL;
    memset(c, 0, sizeof *c);
    c->gain_q16[0] = c->gain_q16[1] = FL_ODOCAL_ONE_Q16;
    return FL_OK;
}

fl_status_t fl_odocal_odometry(fl_odocal_t *c, int32_t dx_mm, int32_t dy_mm,
                               fl_angle_t dtheta)
{
    int64_t co, si;
    if (c == NULL)
        return FL_ERR_NULL;
    if (dx_mm < -ODOCAL_MAX_STEP_MM || dx_mm > ODOCAL_MAX_STEP_MM ||
        dy_mm < -ODOCAL_MAX_STEP_MM || dy_mm > ODOCAL_MAX_STEP_MM)
        return FL_ERR_RANGE;
    co = fl_cos_q15(c->heading);
    si = fl_sin_q15(c->heading);
    c->px_x_q15 += (int64_t)dx_mm * co;
    c->px_y_q15 += (int64_t)dx_mm * si;
    c->py_x_q15 -= (int64_t)dy_mm * si;
    c->py_y_q15 += (int64_t)dy_mm * co;
    c->heading = fl_angle_add(c->heading, dtheta);
    return FL_OK;
}

/* A Q15 sum in mm, saturated to +-ODOCAL_MAX_POS_MM (a longer walk is not
 * a calibration walk; the pair gate drops it). */
static int32_t odocal_mm(int64_t q15)
{
    int64_t lim = (int64_t)ODOCAL_MAX_POS_MM << 15;
    if (q15 > lim)
        q15 = lim;
    if (q15 < -lim)
        q15 = -lim;
    return fl_rshift_round(q15, 15);
}

fl_status_t fl_odocal_fix(fl_odocal_t *c, int32_t x_mm, int32_t y_mm)
{
    fl_odocal_fix_t *f;
    if (c == NULL)
        return FL_ERR_NULL;
    if (x_mm < -ODOCAL_MAX_POS_MM || x_mm > ODOCAL_MAX_POS_MM || y_mm < -ODOCAL_MAX_POS_MM ||
        y_mm > ODOCAL_MAX_POS_MM)
        return FL_ERR_RANGE;
    if (c->n_fixes >= FL_ODOCAL_MAX_FIXES) {
        if (c->fixes_refused < UINT32_MAX)
            c->fixes_refused++;
        return FL_ERR_SIZE;
    }
    f = &c->fix[c->n_fixes++];
    f->px_x_mm = odocal_mm(c->px_x_q15);
    f->px_y_mm = odocal_mm(c->px_y_q15);
    f->py_x_mm = odocal_mm(c->py_x_q15);
    f->py_y_mm = odocal_mm(c->py_y_q15);
    f->rx_mm = x_mm;
    f->ry_mm = y_mm;
    return FL_OK;
}

/* Sums of one axis over the gated pairs: num += (D^2 - O^2) * A^2 and
 * den += A^4 in cm, where A is the axis' odometry motion, O the other
 * axis' (at unit gain) and D the reported distance. */
typedef struct {
    int64_t num, den;
    uint32_t used, gated;
} odocal_sums_t;

static void odocal_pair(odocal_sums_t *s, uint32_t a_mm, uint32_t o_mm, uint32_t d_mm)
{
    int64_t a, o, d;
    if (a_mm < FL_ODOCAL_MIN_BASELINE_MM || (uint64_t)o_mm * 4u > a_mm)
        return;
    /* the pair's own gain D / A within the bounds, distances below 20 m */
    if ((uint64_t)d_mm * FL_ODOCAL_ONE_Q16 < (uint64_t)a_mm * FL_ODOCAL_GAIN_MIN_Q16 ||
        (uint64_t)d_mm * FL_ODOCAL_ONE_Q16 > (uint64_t)a_mm * FL_ODOCAL_GAIN_MAX_Q16 ||
        a_mm >= ODOCAL_MAX_PAIR_CM * 10u || d_mm >= ODOCAL_MAX_PAIR_CM * 10u) {
        s->gated++;
        return;
    }
    a = ((int64_t)a_mm + 5) / 10;
    o = ((int64_t)o_mm + 5) / 10;
    d = ((int64_t)d_mm + 5) / 10;
    s->num += (d * d - o * o) * (a * a);
    s->den += (a * a) * (a * a);
    s->used++;
}

/* gain = sqrt(num / den) in Q16, bounded; 1 with too few pairs. */
static int32_t odocal_gain(odocal_sums_t s)
{
    int64_t v;
    uint32_t g;
    if (s.used < FL_ODOCAL_MIN_PAIRS || s.den <= 0)
        return FL_ODOCAL_ONE_Q16;
    while (s.den > ((int64_t)1 << 40)) {
        s.den /= 2;
        s.num /= 2;
    }
    if (s.num <= 0 || s.den == 0)
        return FL_ODOCAL_GAIN_MIN_Q16;
    v = s.num * FL_ODOCAL_ONE_Q16 / s.den; /* gain^2, Q16; num < 2^57 */
    if (v > ((int64_t)2 << 16))
        return FL_ODOCAL_GAIN_MAX_Q16;
    g = fl_isqrt64((uint64_t)v << 16);
    if (g < FL_ODOCAL_GAIN_MIN_Q16)
        return FL_ODOCAL_GAIN_MIN_Q16;
    if (g > FL_ODOCAL_GAIN_MAX_Q16)
        return FL_ODOCAL_GAIN_MAX_Q16;
    return (int32_t)g;
}

fl_status_t fl_odocal_solve(fl_odocal_t *c)
{
    odocal_sums_t sx, sy;
    uint32_t i, j;
    if (c == NULL)
        return FL_ERR_NULL;
    memset(&sx, 0, sizeof sx);
    memset(&sy, 0, sizeof sy);
    for (i = 0; i < c->n_fixes && i < FL_ODOCAL_MAX_FIXES; i++)
        for (j = i + 1; j < c->n_fixes && j < FL_ODOCAL_MAX_FIXES; j++) {
            const fl_odocal_fix_t *p = &c->fix[i], *q = &c->fix[j];
            uint32_t ax = fl_hypot(q->px_x_mm - p->px_x_mm, q->px_y_mm - p->px_y_mm);
            uint32_t ay = fl_hypot(q->py_x_mm - p->py_x_mm, q->py_y_mm - p->py_y_mm);
            uint32_t d = fl_hypot(q->rx_mm - p->rx_mm, q->ry_mm - p->ry_mm);
            odocal_pair(&sx, ax, ay, d);
            odocal_pair(&sy, ay, ax, d);
        }
    c->gain_q16[0] = odocal_gain(sx);
    c->gain_q16[1] = odocal_gain(sy);
    c->pairs[0] = sx.used;
    c->pairs[1] = sy.used;
    c->pairs_gated[0] = sx.gated;
    c->pairs_gated[1] = sy.gated;
    return FL_OK;
}

static int32_t odocal_scale(int32_t d, int32_t gain, int64_t *carry)
{
    int64_t v = (int64_t)d * gain + *carry;
    int64_t q = (v + FL_ODOCAL_ONE_Q16 / 2) / FL_ODOCAL_ONE_Q16;
    /* division truncates toward zero: make it a floor of v / 2^16 + 1/2 */
    if (q * FL_ODOCAL_ONE_Q16 > v + FL_ODOCAL_ONE_Q16 / 2)
        q--;
    *carry = v - q * FL_ODOCAL_ONE_Q16;
    return fl_sat32(q);
}

fl_status_t fl_odocal_apply(fl_odocal_t *c, int32_t *dx_mm, int32_t *dy_mm)
{
    if (c == NULL || dx_mm == NULL || dy_mm == NULL)
        return FL_ERR_NULL;
    *dx_mm = odocal_scale(*dx_mm, c->gain_q16[0], &c->carry[0]);
    *dy_mm = odocal_scale(*dy_mm, c->gain_q16[1], &c->carry[1]);
    return FL_OK;
}
