/*
 * src/loc/relmap_estimate.c - what seed 002's grid reports (relmap.h):
 * the estimate in localizer.h's form, its spread, the mirror's weight,
 * the calibrated reliability, a pose's possibility and the particles.
 *
 * The estimate is the peak particle, refined by the belief-weighted mean
 * of its 3 x 3 neighbours that share its heading (within 45 deg) and by
 * the motion not yet shifted.  The mode is every particle within
 * FL_LOC_GOOD_MM of it; particles at the belief floor (a recovery reserve,
 * not a belief) count in neither the mode nor the spread.
 */
#include "fieldloc/relmap.h"

#include <string.h>

#define RM_MODE_MM FL_LOC_GOOD_MM

static int peak_cell(const fl_relmap_t *s)
{
    int c, best = 0;
    for (c = 1; c < FL_RELMAP_N; c++)
        if (s->bel[c] > s->bel[best])
            best = c;
    return best;
}

static uint32_t reserve(const fl_relmap_t *s)
{
    return (uint32_t)s->params.floor_q16 * 4u;
}

/* The peak's pose, refined. */
static void peak_pose(const fl_relmap_t *s, int pk, int32_t *x, int32_t *y)
{
    int ix = pk % FL_RELMAP_NX, iy = pk / FL_RELMAP_NX, dx, dy;
    int64_t sx = 0, sy = 0, sw = 0;
    int32_t cs = fl_cos_q15(s->head[pk]), sn = fl_sin_q15(s->head[pk]);
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++) {
            int jx = ix + dx, jy = iy + dy, j;
            int32_t cx, cy;
            fl_angle_t d;
            if (jx < 0 || jx >= FL_RELMAP_NX || jy < 0 || jy >= FL_RELMAP_NY)
                continue;
            j = jy * FL_RELMAP_NX + jx;
            d = fl_angle_sub(s->head[j], s->head[pk]);
            if (d > FL_ANGLE_45 || d < -FL_ANGLE_45 || s->bel[j] <= reserve(s))
                continue;
            fl_relmap_cell_pos(s, jx, jy, &cx, &cy);
            sx += (int64_t)cx * s->bel[j];
            sy += (int64_t)cy * s->bel[j];
            sw += s->bel[j];
        }
    if (sw == 0) {
        fl_relmap_cell_pos(s, ix, iy, x, y);
    } else {
        *x = (int32_t)(sx / sw);
        *y = (int32_t)(sy / sw);
    }
    *x += (int32_t)((((int64_t)s->pend_x_mm * cs - (int64_t)s->pend_y_mm * sn) >> 15) / 16);
    *y += (int32_t)((((int64_t)s->pend_x_mm * sn + (int64_t)s->pend_y_mm * cs) >> 15) / 16);
}

/* Under ignorance: the prior region's centre and uniform spread. */
static void ignorant(const fl_relmap_t *s, fl_loc_estimate_t *out)
{
    int32_t hx = s->hx, hy = s->hy;
    /* a uniform's sd: width / sqrt(12) = half width * 0.57735 */
    out->sd_x_mm = (uint16_t)((hx * 37837LL) >> 16);
    out->sd_y_mm = (uint16_t)((hy * 37837LL) >> 16);
    if (s->prior_pose) {
        out->x_mm = s->prior_x_mm;
        out->y_mm = s->prior_y_mm;
        out->sd_x_mm = out->sd_y_mm = (uint16_t)(s->prior_r_mm / 2 > 65535 ? 65535 : s->prior_r_mm / 2);
    } else if (s->prior_half != 0) {
        out->x_mm = s->prior_half * (hx / 2);
        out->sd_x_mm = (uint16_t)((hx * 18919LL) >> 16);
    }
    out->sd_heading = 32767;
    out->state = FL_LOC_LOST;
}

/*
 * The reliability from the grid's own measures: the mode's share of the
 * belief, the frames since an observation, and the mirror.  The table was
 * set by hand and checked on training walks (`fieldloc reliability
 * --localizer relmap --seeds 2,3,4,5 --frame-seeds 0`: of the estimates
 * at reliability >= r, at least r were good, 98 % at 0.9 and more; its
 * top kept below that); held-out seed 1 is checked by
 * host_tests/test_confidence.c.
 */
static uint16_t reliability(const fl_relmap_t *s, uint32_t share_q16, uint16_t mirror_q16)
{
    static const uint16_t by_share[8] = {0, 0, 6554, 19661, 32768, 45875, 55705, 60293};
    uint32_t r = by_share[share_q16 >> 13];
    if (s->since_obs > 30)
        r = r * 30u / s->since_obs;
    if (mirror_q16 >= 32768u)
        r = r < 32767u ? r : 32767u;
    else
        r = (uint32_t)((uint64_t)r * (65536u - mirror_q16 / 2u) >> 16);
    return (uint16_t)(r > 65535u ? 65535u : r);
}

/* The mode's moments about (x, y): share of the belief, sd, heading sd. */
static uint32_t mode_moments(const fl_relmap_t *s, int pk, int32_t x, int32_t y,
                             fl_loc_estimate_t *out)
{
    int c;
    uint64_t tot = 0, w = 0;
    int64_t sxx = 0, syy = 0, sxy = 0, shh = 0;
    uint16_t cells = 0;
    for (c = 0; c < FL_RELMAP_N; c++) {
        int32_t cx, cy;
        int64_t dx, dy;
        uint32_t b = s->bel[c];
        fl_angle_t dh;
        if (b <= reserve(s))
            continue;
        tot += b;
        fl_relmap_cell_pos(s, c % FL_RELMAP_NX, c / FL_RELMAP_NX, &cx, &cy);
        dx = (int64_t)cx - x;
        dy = (int64_t)cy - y;
        if (dx * dx + dy * dy > (int64_t)RM_MODE_MM * RM_MODE_MM)
            continue;
        dh = fl_angle_sub(s->head[c], s->head[pk]);
        w += b;
        cells++;
        sxx += dx * dx * b;
        syy += dy * dy * b;
        sxy += dx * dy * b;
        shh += (int64_t)dh * dh * b;
    }
    if (w == 0)
        return 0;
    out->sd_x_mm = (uint16_t)fl_isqrt64((uint64_t)(sxx / (int64_t)w));
    out->sd_y_mm = (uint16_t)fl_isqrt64((uint64_t)(syy / (int64_t)w));
    out->cov_xy_mm2 = (int32_t)(sxy / (int64_t)w);
    out->sd_heading = s->heading_known ? (fl_angle_t)fl_isqrt64((uint64_t)(shh / (int64_t)w)) : 32767;
    out->mode_cells = cells;
    return (uint32_t)((w * 65535u) / (tot > 0 ? tot : 1u));
}

bool fl_relmap_estimate(const fl_relmap_t *s, fl_loc_estimate_t *out)
{
    int pk, m, dx, dy;
    uint32_t share, mir = 0;
    if (out == NULL)
        return false;
    memset(out, 0, sizeof *out);
    if (s == NULL || s->field == NULL)
        return false;
    out->since_obs = s->since_obs;
    if (s->ignorance) {
        ignorant(s, out);
        return true;
    }
    pk = peak_cell(s);
    peak_pose(s, pk, &out->x_mm, &out->y_mm);
    out->heading = s->head[pk];
    out->peak_q8 = (uint8_t)(s->bel[pk] >> 8);
    share = mode_moments(s, pk, out->x_mm, out->y_mm, out);
    if (s->field->symmetric) {
        m = FL_RELMAP_N - 1 - pk;
        for (dy = -1; dy <= 1; dy++)
            for (dx = -1; dx <= 1; dx++) {
                int jx = m % FL_RELMAP_NX + dx, jy = m / FL_RELMAP_NX + dy;
                if (jx >= 0 && jx < FL_RELMAP_NX && jy >= 0 && jy < FL_RELMAP_NY &&
                    s->bel[jy * FL_RELMAP_NX + jx] > mir)
                    mir = s->bel[jy * FL_RELMAP_NX + jx];
            }
        mir = mir <= reserve(s) ? 0 : (mir * 65535u) / (s->bel[pk] > 0 ? s->bel[pk] : 1u);
        out->mirror_q16 = (uint16_t)(mir > 65535u ? 65535u : mir);
        if (!s->half_known)
            out->mirror_q16 = 65535u;   /* nothing told the half */
    }
    out->score_q16 = (uint16_t)(share > 65535u ? 65535u : share);
    out->reliability_q16 = reliability(s, share, out->mirror_q16);
    out->state = out->mirror_q16 >= 32768u ? FL_LOC_AMBIGUOUS : FL_LOC_TRACKING;
    out->localized = out->state == FL_LOC_TRACKING && out->reliability_q16 >= FL_LOC_LOCALIZED_Q16;
    return true;
}

uint32_t fl_relmap_spread_mm(const fl_relmap_t *s)
{
    fl_loc_estimate_t e;
    int c;
    uint64_t w = 0;
    int64_t sx = 0, sy = 0, sxx = 0, syy = 0;
    bool fold;
    if (s == NULL || s->field == NULL)
        return UINT32_MAX;
    fl_relmap_estimate(s, &e);
    fold = s->field->symmetric && !s->ignorance;
    for (c = 0; c < FL_RELMAP_N; c++) {
        int32_t x, y;
        uint32_t b = s->bel[c];
        if (b <= reserve(s) && !s->ignorance)
            continue;
        fl_relmap_cell_pos(s, c % FL_RELMAP_NX, c / FL_RELMAP_NX, &x, &y);
        if (fold) {
            int64_t d1 = ((int64_t)x - e.x_mm) * (x - e.x_mm) + ((int64_t)y - e.y_mm) * (y - e.y_mm);
            int64_t d2 = ((int64_t)x + e.x_mm) * (x + e.x_mm) + ((int64_t)y + e.y_mm) * (y + e.y_mm);
            if (d2 < d1) {
                x = -x;
                y = -y;
            }
        }
        w += b;
        sx += (int64_t)x * b;
        sy += (int64_t)y * b;
        sxx += (int64_t)x * x * b;
        syy += (int64_t)y * y * b;
    }
    if (w == 0)
        return UINT32_MAX;
    {
        int64_t mx = sx / (int64_t)w, my = sy / (int64_t)w;
        int64_t v = sxx / (int64_t)w - mx * mx + syy / (int64_t)w - my * my;
        return fl_isqrt64((uint64_t)(v > 0 ? v : 0));
    }
}

uint32_t fl_relmap_possibility_q16(const fl_relmap_t *s, int32_t x_mm, int32_t y_mm,
                                   fl_angle_t heading)
{
    int32_t c;
    uint32_t v, pk;
    fl_angle_t d;
    if (s == NULL || s->field == NULL)
        return 0;
    c = fl_relmap_cell_at(s, x_mm, y_mm);
    if (c < 0)
        return 0;
    pk = s->bel[peak_cell(s)];
    v = pk > 0 ? (uint32_t)(((uint64_t)s->bel[c] << 16) / pk) : 0u;
    d = fl_angle_sub(heading, s->head[c]);
    if (s->heading_known && !s->ignorance && (d > FL_ANGLE_45 || d < -FL_ANGLE_45))
        v /= 16u;
    return v;
}

uint16_t fl_relmap_samples(const fl_relmap_t *s)
{
    int c;
    uint16_t n = 0;
    if (s == NULL || s->field == NULL)
        return 0;
    for (c = 0; c < FL_RELMAP_N; c++)
        n = (uint16_t)(n + (s->bel[c] > 0));
    return n;
}

bool fl_relmap_sample(const fl_relmap_t *s, uint16_t i, fl_loc_sample_t *out)
{
    fl_loc_estimate_t e;
    int c;
    uint16_t k = 0;
    if (out == NULL)
        return false;
    memset(out, 0, sizeof *out);
    if (s == NULL || s->field == NULL)
        return false;
    for (c = 0; c < FL_RELMAP_N; c++) {
        int64_t dx, dy;
        fl_angle_t d;
        if (s->bel[c] == 0 || k++ != i)
            continue;
        fl_relmap_estimate(s, &e);
        fl_relmap_cell_pos(s, c % FL_RELMAP_NX, c / FL_RELMAP_NX, &out->x_mm, &out->y_mm);
        out->heading = s->head[c];
        out->weight_q16 = (uint16_t)(((uint32_t)s->bel[c] * 65535u) /
                                     (s->bel[peak_cell(s)] > 0 ? s->bel[peak_cell(s)] : 1u));
        dx = (int64_t)out->x_mm - e.x_mm;
        dy = (int64_t)out->y_mm - e.y_mm;
        d = fl_angle_sub(out->heading, e.heading);
        out->in_mode = !s->ignorance && dx * dx + dy * dy <= (int64_t)RM_MODE_MM * RM_MODE_MM &&
                       d <= FL_ANGLE_90 && d >= -FL_ANGLE_90;
        return true;
    }
    return false;
}
