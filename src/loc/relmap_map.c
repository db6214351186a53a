/*
 * src/loc/relmap_map.c - seed 002's relative landmark map (relmap.h): the
 * frame's landmarks prepared with the map landmarks each may be, the error
 * of its equation 2 at a pose, the best heading of equation 3 found
 * exactly without trying all 360, the white points counted on the painted
 * lines, and the exp table of equation 1.
 */
#include "fieldloc/relmap.h"

#include <string.h>

/* 2^(-k/32), Q16, k = 0..31. */
static const uint16_t exp2_frac[32] = {
    65535, 64132, 62757, 61413, 60097, 58809, 57549, 56316, 55109, 53928, 52773,
    51642, 50535, 49452, 48393, 47356, 46341, 45348, 44376, 43425, 42495, 41584,
    40693, 39821, 38968, 38133, 37316, 36516, 35734, 34968, 34219, 33486};

uint32_t fl_relmap_exp_q16(uint32_t x_q8)
{
    /* e^-x = 2^(-x log2 e); log2 e = 369.33 / 256 */
    uint32_t y = (uint32_t)(((uint64_t)x_q8 * 369u + 128u) >> 8);   /* Q8 of base 2 */
    uint32_t ip = y >> 8;
    if (ip >= 17u)
        return 0;
    return (uint32_t)exp2_frac[(y & 255u) >> 3] >> ip;
}

static bool compatible(const fl_landmark_t *m, const fl_obs_t *o)
{
    if (m->kind != o->kind)
        return false;
    if (o->kind == FL_LM_NET) {
        if (o->color != FL_COLOR_NONE && m->color != o->color)
            return false;
    } else if (o->kind == FL_LM_POST) {
        if (o->color != FL_COLOR_NONE && m->color != o->color)
            return false;
        if (o->side != FL_SIDE_UNKNOWN && m->side != o->side)
            return false;
    } else if (o->kind == FL_LM_BEACON) {
        if (o->color != FL_COLOR_NONE && m->color != o->color)
            return false;
        if (o->color2 != FL_COLOR_NONE && m->color2 != o->color2)
            return false;
    }
    return true;
}

/* Whether an observation can be used: a known kind, some confidence, a
 * range the camera can give. */
static bool usable(const fl_obs_t *o, int32_t max_range)
{
    return (int)o->kind >= 0 && o->kind < FL_LM_KIND_COUNT && o->confidence > 0 &&
           o->range_mm >= 0 && o->range_mm <= max_range && o->range_mm <= FL_OBS_MAX_RANGE_MM;
}

uint16_t fl_relmap_frame(const fl_relmap_t *s, const fl_obs_list_t *obs, fl_relmap_frame_t *f)
{
    const fl_field_t *field;
    uint16_t i, n, j, k;
    int32_t cap;
    if (f == NULL)
        return 0;
    memset(f, 0, sizeof *f);
    if (s == NULL || s->field == NULL || obs == NULL)
        return 0;
    field = s->field;
    cap = s->params.err_cap_mm;
    f->cap_mm2 = (uint32_t)(cap * cap);
    n = obs->n < FL_OBS_MAX ? obs->n : FL_OBS_MAX;
    for (i = 0; i < n; i++) {
        const fl_obs_t *o = &obs->obs[i];
        fl_relmap_lm_t lm;
        if (!usable(o, s->params.max_range_mm))
            continue;
        memset(&lm, 0, sizeof lm);
        /* candidates by fl_field_all_at id: landmarks, then seed 004's
         * features (at most 255 ids: the maps have under 50) */
        for (j = 0; j < fl_field_n_all(field) && j < 256u && lm.n_cand < 16u; j++)
            if (compatible(fl_field_all_at(field, j), o))
                lm.cand[lm.n_cand++] = (uint8_t)j;
        if (lm.n_cand == 0)
            continue;
        lm.range_mm = o->range_mm;
        lm.ox = (int32_t)(((int64_t)o->range_mm * fl_cos_q15(o->bearing)) >> 15);
        lm.oy = (int32_t)(((int64_t)o->range_mm * fl_sin_q15(o->bearing)) >> 15);
        /* keep the nearest FL_RELMAP_MAX_OBS, sorted by range (insertion) */
        if (f->n == FL_RELMAP_MAX_OBS && f->lm[f->n - 1].range_mm <= lm.range_mm)
            continue;
        k = f->n < FL_RELMAP_MAX_OBS ? f->n : (uint16_t)(FL_RELMAP_MAX_OBS - 1);
        while (k > 0 && f->lm[k - 1].range_mm > lm.range_mm) {
            f->lm[k] = f->lm[k - 1];
            k--;
        }
        f->lm[k] = lm;
        if (f->n < FL_RELMAP_MAX_OBS)
            f->n++;
    }
    return f->n;
}

/* One landmark's term at the superimposed position (qx, qy). */
static uint32_t term(const fl_field_t *field, const fl_relmap_lm_t *lm, int32_t qx, int32_t qy,
                     uint32_t cap)
{
    uint32_t best = cap;
    uint8_t c;
    for (c = 0; c < lm->n_cand; c++) {
        const fl_landmark_t *m = fl_field_all_at(field, lm->cand[c]);
        int64_t dx = (int64_t)m->x_mm - qx, dy = (int64_t)m->y_mm - qy;
        int64_t d2 = dx * dx + dy * dy;
        if (d2 < (int64_t)best)
            best = (uint32_t)d2;
    }
    return best;
}

static fl_angle_t deg_angle(int32_t deg)
{
    return fl_angle_from_mdeg(deg * 1000);
}

uint32_t fl_relmap_error(const fl_field_t *field, const fl_relmap_frame_t *f, int32_t x_mm,
                         int32_t y_mm, int32_t deg)
{
    fl_angle_t a = deg_angle(deg);
    int32_t c = fl_cos_q15(a), sn = fl_sin_q15(a);
    uint32_t sum = 0;
    uint16_t i;
    if (field == NULL || f == NULL)
        return UINT32_MAX;
    for (i = 0; i < f->n; i++) {
        const fl_relmap_lm_t *lm = &f->lm[i];
        int32_t qx = x_mm + (int32_t)(((int64_t)lm->ox * c - (int64_t)lm->oy * sn) >> 15);
        int32_t qy = y_mm + (int32_t)(((int64_t)lm->ox * sn + (int64_t)lm->oy * c) >> 15);
        sum += term(field, lm, qx, qy, f->cap_mm2);
    }
    return sum;
}

/*
 * A lower bound of the error over the headings [deg0, deg0 + 9]: at the
 * block's middle heading each superimposed landmark is at q; over the block
 * it stays on an arc within r * 4.5 deg (plus the Q15 rounding, 2 mm) of
 * q, so its distance to any map landmark is at least the one at q less
 * that.
 */
static uint32_t block_bound(const fl_field_t *field, const fl_relmap_frame_t *f, int32_t x_mm,
                            int32_t y_mm, int32_t deg0)
{
    /* the block's middle heading deg0 + 4.5: half a degree off the grid */
    fl_angle_t a = fl_angle_from_mdeg(deg0 * 1000 + 4500);
    int32_t c = fl_cos_q15(a), sn = fl_sin_q15(a);
    uint32_t sum = 0;
    uint16_t i;
    for (i = 0; i < f->n; i++) {
        const fl_relmap_lm_t *lm = &f->lm[i];
        int32_t qx = x_mm + (int32_t)(((int64_t)lm->ox * c - (int64_t)lm->oy * sn) >> 15);
        int32_t qy = y_mm + (int32_t)(((int64_t)lm->ox * sn + (int64_t)lm->oy * c) >> 15);
        uint32_t d2 = term(field, lm, qx, qy, UINT32_MAX);
        /* the arc: r * 4.5 deg = r * 0.0785 < r * 81 / 1024 */
        int32_t slack = (int32_t)(((int64_t)lm->range_mm * 81 + 1023) >> 10) +
                        lm->range_mm / 4096 + 4;
        int32_t d = (int32_t)fl_isqrt64(d2) - slack;   /* isqrt rounds down */
        uint32_t t = d > 0 ? (uint32_t)((int64_t)d * d) : 0u;
        sum += t < f->cap_mm2 ? t : f->cap_mm2;
    }
    return sum;
}

uint32_t fl_relmap_best_heading(const fl_field_t *field, const fl_relmap_frame_t *f,
                                int32_t x_mm, int32_t y_mm, int32_t *deg)
{
    uint32_t lb[36], best = UINT32_MAX;
    uint8_t order[36];
    int32_t b, j, k, best_deg = 0;
    if (deg != NULL)
        *deg = 0;
    if (field == NULL || f == NULL || f->n == 0)
        return 0;
    for (b = 0; b < 36; b++) {
        lb[b] = block_bound(field, f, x_mm, y_mm, b * 10);
        /* insertion by bound, blocks in order among equals */
        for (k = b; k > 0 && lb[order[k - 1]] > lb[b]; k--)
            order[k] = order[k - 1];
        order[k] = (uint8_t)b;
    }
    for (k = 0; k < 36; k++) {
        b = order[k];
        if (lb[b] > best)
            break;   /* every later block is bounded above the best */
        for (j = b * 10; j < b * 10 + 10; j++) {
            uint32_t e = fl_relmap_error(field, f, x_mm, y_mm, j);
            if (e < best || (e == best && j < best_deg)) {
                best = e;
                best_deg = j;
            }
        }
    }
    if (deg != NULL)
        *deg = best_deg;
    return best;
}

/* Squared distance of (px, py) to the segment a-b. */
static int64_t seg_d2(int32_t px, int32_t py, const fl_field_line_t *l)
{
    int64_t vx = (int64_t)l->x1_mm - l->x0_mm, vy = (int64_t)l->y1_mm - l->y0_mm;
    int64_t wx = (int64_t)px - l->x0_mm, wy = (int64_t)py - l->y0_mm;
    int64_t vv = vx * vx + vy * vy, t = wx * vx + wy * vy, dx, dy;
    if (vv == 0 || t <= 0)
        return wx * wx + wy * wy;
    if (t >= vv) {
        dx = (int64_t)px - l->x1_mm;
        dy = (int64_t)py - l->y1_mm;
        return dx * dx + dy * dy;
    }
    /* |w x v|^2 / |v|^2 (|w x v| < 2^31 on any carpet: no overflow) */
    dx = wx * vy - wy * vx;
    return dx * dx / vv;
}

uint16_t fl_relmap_white_hits(const fl_field_t *field, const fl_obs_list_t *obs, int32_t x_mm,
                              int32_t y_mm, fl_angle_t heading, int32_t tol_mm)
{
    uint16_t hits = 0, n, used, i, j, step;
    int32_t c, sn, tol;
    int64_t tol2;
    if (field == NULL || obs == NULL)
        return 0;
    n = obs->n_points < FL_OBS_MAX_POINTS ? obs->n_points : (uint16_t)FL_OBS_MAX_POINTS;
    if (n == 0 || FL_RELMAP_MAX_WHITE == 0)
        return 0;
    c = fl_cos_q15(heading);
    sn = fl_sin_q15(heading);
    tol = tol_mm + field->line_width_mm / 2;
    tol2 = (int64_t)tol * tol;
    step = (uint16_t)((n + FL_RELMAP_MAX_WHITE - 1) / FL_RELMAP_MAX_WHITE);
    for (i = 0, used = 0; i < n && used < FL_RELMAP_MAX_WHITE; i += step, used++) {
#if FL_OBS_MAX_POINTS > 0
        const fl_obs_point_t *p = &obs->points[i];
        int32_t qx = x_mm + (int32_t)(((int64_t)p->x_mm * c - (int64_t)p->y_mm * sn) >> 15);
        int32_t qy = y_mm + (int32_t)(((int64_t)p->x_mm * sn + (int64_t)p->y_mm * c) >> 15);
        bool hit = false;
        for (j = 0; j < field->n_lines && !hit; j++)
            hit = seg_d2(qx, qy, &field->lines[j]) <= tol2;
        if (!hit && field->circle_radius_mm > 0) {
            int32_t d = (int32_t)fl_hypot(qx, qy) - field->circle_radius_mm;
            hit = d <= tol && d >= -tol;
        }
        hits += hit;
#else
        (void)j;
#endif
    }
    return hits;
}
