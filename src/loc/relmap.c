/*
 * src/loc/relmap.c - seed 002's particle grid (relmap.h): parameters,
 * init, resets and priors, re-seeding from a report, and odometry.
 *
 * Odometry on a fixed grid: each particle moves along its own heading, so
 * the belief is shifted particle by particle (a forward splat of each
 * particle's belief onto the four particles around where it lands,
 * bilinear) and every heading turns by the step's rotation.  A splat
 * after every 10 mm step would blur the belief by a cell every few steps;
 * the motion is therefore collected in the robot frame (turned with the
 * robot) until it reaches half a cell, then shifted at once.  The splat's
 * spreading is the process noise (about a third of a cell per shift).
 */
#include "fieldloc/relmap.h"

#include <string.h>

void fl_relmap_params_default(fl_relmap_params_t *p)
{
    if (p == NULL)
        return;
    memset(p, 0, sizeof *p);
    p->sigma_base_mm = 200;
    p->sigma_pct = 15;
    p->z2_cap_q8 = 6 * 256;
    p->cand_q16 = 32768;
    p->max_cand = 32;
    p->err_cap_mm = 1500;
    p->tie_mm = 60;
    p->white_tol_mm = 40;
    p->heading_gate_deg = 30;
    /* 24 in the exponent once tracking: at 8, frames of two landmarks of
     * repeated kinds (crossings, two posts of a colour) flipped tracked
     * headings by up to 180 deg at full reliability (aibo2004 and hl3x2
     * feature walks); a third of it while tracking starts, so that an
     * early wrong heading is not locked in (src/loc/relmap_update.c) */
    p->jump_q8 = 6144;
    p->frame_cap_q8 = 384;
    p->spread_q16 = 16384;
    p->floor_q16 = 1;
    p->kidnap_q16 = 1500;
    p->kidnap_frames = 30;
    p->max_range_mm = 12000;
    p->odo_max_mm = 1000;
}

/*
 * Observations from a camera (a vision path, FL_LOC_PRESET_VISION) give
 * ranges far better than the feature-level defaults assume: on rendered
 * hl3x2 frames seed 002's path measures post and pole ranges within about
 * 1 % (`fieldloc eval-relmap --verbose`).  Eq. 1's sigma is then 100 mm
 * (about a cell diagonal on hl3x2, 68 x 75 mm cells: a particle stands up
 * to half that from the robot) plus 8 % of the range (MCL's vision preset
 * takes 6 %).  Eq. 2's miss is capped at 500 mm, about half the spacing
 * of two landmarks of one kind (posts 800 mm, T crossings 1100 mm apart on
 * hl3x2): a superimposed landmark farther than that from every map
 * landmark of its kind is no match (a false crossing, e.g. the centre
 * mark's node on the halfway line); with the feature-level 1500 mm one
 * such landmark outweighed two posts at the mirrored pose (host test
 * relmap.vision_preset).
 *
 * The feature-level defaults stay 200 mm + 15 % and 1500 mm.  The same
 * 100 mm + 10 % and 500 mm improved the simulator's feature walks on
 * average (`fieldloc simulate --localizer relmap --features`, hl3x2,
 * spl2013, uva2013, aibo2004, spl2020, seeds 1-2: position RMSE 704 ->
 * 325 mm), but on spl2013's walk from the own-half prior the 500 mm cap
 * alone let the grid settle on the mirrored half (host tests
 * reseed.correct, report.apply): on a field whose landmarks are all
 * mirrored, a cheap miss makes the mirror as good as the truth.
 */
void fl_relmap_params_vision(fl_relmap_params_t *p)
{
    if (p == NULL)
        return;
    fl_relmap_params_default(p);
    p->sigma_base_mm = 100;
    p->sigma_pct = 8;
    p->err_cap_mm = 500;
}

fl_status_t fl_relmap_params_check(const fl_relmap_params_t *p)
{
    if (p == NULL)
        return FL_ERR_NULL;
    if (p->sigma_base_mm < 10 || p->sigma_pct > 100 || p->z2_cap_q8 == 0 || p->cand_q16 == 0 ||
        p->max_cand < 1 || p->max_cand > FL_RELMAP_MAX_CAND || p->err_cap_mm < 10 ||
        p->heading_gate_deg > 180u || p->floor_q16 > 32768u || p->kidnap_frames == 0 || p->frame_cap_q8 == 0 ||
        p->max_range_mm < 100 || p->max_range_mm > FL_OBS_MAX_RANGE_MM || p->odo_max_mm < 1)
        return FL_ERR_RANGE;
    return FL_OK;
}

void fl_relmap_clear(fl_relmap_t *s)
{
    if (s != NULL)
        memset(s, 0, sizeof *s);
}

void fl_relmap_cell_pos(const fl_relmap_t *s, int ix, int iy, int32_t *x_mm, int32_t *y_mm)
{
    *x_mm = -s->hx + (int32_t)(((int64_t)(2 * ix + 1) * s->cell_x_q8) >> 9);
    *y_mm = -s->hy + (int32_t)(((int64_t)(2 * iy + 1) * s->cell_y_q8) >> 9);
}

int32_t fl_relmap_cell_at(const fl_relmap_t *s, int32_t x_mm, int32_t y_mm)
{
    int64_t ix, iy;
    if (s == NULL || s->field == NULL || x_mm < -s->hx || x_mm > s->hx || y_mm < -s->hy ||
        y_mm > s->hy)
        return -1;
    ix = (((int64_t)x_mm + s->hx) << 8) / s->cell_x_q8;
    iy = (((int64_t)y_mm + s->hy) << 8) / s->cell_y_q8;
    if (ix >= FL_RELMAP_NX)
        ix = FL_RELMAP_NX - 1;
    if (iy >= FL_RELMAP_NY)
        iy = FL_RELMAP_NY - 1;
    return (int32_t)(iy * FL_RELMAP_NX + ix);
}

/* Whether a particle lies in the prior's region. */
static bool in_prior(const fl_relmap_t *s, int32_t x, int32_t y)
{
    if (s->prior_half != 0 && (s->prior_half < 0 ? x > 0 : x < 0))
        return false;
    if (s->prior_pose) {
        int64_t dx = (int64_t)x - s->prior_x_mm, dy = (int64_t)y - s->prior_y_mm;
        /* at least the particle holding the centre: half a cell's diagonal */
        int64_t r = s->prior_r_mm + ((s->cell_x_q8 + s->cell_y_q8) >> 9);
        return dx * dx + dy * dy <= r * r;
    }
    return true;
}

/* Uniform over the prior's region (every particle without a prior).  A
 * region that holds no cell (the entry points keep one prior at a time, so
 * none should) gives the whole carpet: the belief is never empty. */
static void uniform(fl_relmap_t *s)
{
    int ix, iy;
    uint32_t inside = 0;
    for (iy = 0; iy < FL_RELMAP_NY; iy++)
        for (ix = 0; ix < FL_RELMAP_NX; ix++) {
            int32_t x, y;
            bool in;
            fl_relmap_cell_pos(s, ix, iy, &x, &y);
            in = in_prior(s, x, y);
            inside += in;
            s->bel[iy * FL_RELMAP_NX + ix] = in ? 65535u : 0u;
            s->head[iy * FL_RELMAP_NX + ix] = 0;
        }
    if (inside == 0)
        for (ix = 0; ix < FL_RELMAP_N; ix++)
            s->bel[ix] = 65535u;
    s->ignorance = true;
    s->heading_known = false;
    s->half_known = s->prior_half != 0 || s->prior_pose;
    s->have_last = false;
    s->pend_x_mm = s->pend_y_mm = 0;
    s->best.valid = false;
    s->bad_frames = 0;
    s->track_frames = 0;
}

fl_status_t fl_relmap_init(fl_relmap_t *s, const fl_field_t *field,
                           const fl_relmap_params_t *params)
{
    fl_relmap_params_t p;
    if (s == NULL)
        return FL_ERR_NULL;
    fl_relmap_clear(s);
    if (field == NULL)
        return FL_ERR_NULL;
    if (params != NULL)
        p = *params;
    else
        fl_relmap_params_default(&p);
    if (fl_relmap_params_check(&p) != FL_OK)
        return FL_ERR_RANGE;
    if (fl_field_carpet_half_x_mm(field) > 10000 || fl_field_carpet_half_y_mm(field) > 10000 ||
        fl_field_carpet_half_x_mm(field) < 100 || fl_field_carpet_half_y_mm(field) < 100)
        return FL_ERR_RANGE;
    s->params = p;
    s->field = field;
    s->hx = fl_field_carpet_half_x_mm(field);
    s->hy = fl_field_carpet_half_y_mm(field);
    s->cell_x_q8 = (int32_t)(((int64_t)2 * s->hx << 8) / FL_RELMAP_NX);
    s->cell_y_q8 = (int32_t)(((int64_t)2 * s->hy << 8) / FL_RELMAP_NY);
    uniform(s);
    return FL_OK;
}

bool fl_relmap_check(const fl_relmap_t *s)
{
    int c;
    if (s == NULL || s->field == NULL || s->hx <= 0 || s->hy <= 0 || s->cell_x_q8 <= 0 ||
        s->cell_y_q8 <= 0 || fl_relmap_params_check(&s->params) != FL_OK)
        return false;
    for (c = 0; c < FL_RELMAP_N; c++)
        if (s->bel[c] > 0)
            return true;
    return false;   /* an empty belief never happens */
}

void fl_relmap_reset_ignorance(fl_relmap_t *s)
{
    if (s == NULL || s->field == NULL)
        return;
    uniform(s);
    s->stats.resets++;
}

/* Paint a Gaussian (sd) blob at (x, y) with heading h, cut at 4 sd, into
 * the belief (max with what is there). */
static void blob(fl_relmap_t *s, int32_t x0, int32_t y0, fl_angle_t h, int32_t sd)
{
    int ix, iy;
    int64_t s2, cut2;
    int32_t cmin = (s->cell_x_q8 < s->cell_y_q8 ? s->cell_x_q8 : s->cell_y_q8) >> 8;
    if (sd < 10)
        sd = 10;
    s2 = (int64_t)sd * sd;
    cut2 = 16 * s2;
    for (iy = 0; iy < FL_RELMAP_NY; iy++)
        for (ix = 0; ix < FL_RELMAP_NX; ix++) {
            int c = iy * FL_RELMAP_NX + ix;
            int32_t x, y;
            int64_t d2;
            uint32_t v;
            fl_relmap_cell_pos(s, ix, iy, &x, &y);
            d2 = ((int64_t)x - x0) * (x - x0) + ((int64_t)y - y0) * (y - y0);
            /* the particle holding the point always gets it */
            if (d2 > cut2 && d2 > (int64_t)cmin * cmin / 2)
                continue;
            v = fl_relmap_exp_q16((uint32_t)((d2 * 128) / s2));
            if (d2 <= (int64_t)cmin * cmin / 2 && v < 32768u)
                v = 32768u;
            if (v > 65535u)
                v = 65535u;
            if (v > s->bel[c]) {
                s->bel[c] = (uint16_t)v;
                s->head[c] = h;
            }
        }
    /* the particle holding the point (the nearest, off the carpet) */
    x0 = x0 < -s->hx ? -s->hx : x0 > s->hx ? s->hx : x0;
    y0 = y0 < -s->hy ? -s->hy : y0 > s->hy ? s->hy : y0;
    ix = (int)fl_relmap_cell_at(s, x0, y0);
    if (ix >= 0 && s->bel[ix] < 65535u) {
        s->bel[ix] = 65535u;
        s->head[ix] = h;
    }
}

static void told(fl_relmap_t *s)
{
    memset(s->bel, 0, sizeof s->bel);
    s->ignorance = false;
    s->half_known = true;
    s->have_last = false;
    s->heading_known = true;
    s->pend_x_mm = s->pend_y_mm = 0;
    s->best.valid = false;
    s->bad_frames = 0;
    s->track_frames = UINT16_MAX;   /* the heading was told */
    s->stats.resets++;
}

void fl_relmap_reset_pose(fl_relmap_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                          int32_t pos_unc_mm)
{
    if (s == NULL || s->field == NULL)
        return;
    told(s);
    blob(s, x_mm, y_mm, heading, pos_unc_mm);
}

void fl_relmap_reset_penalty(fl_relmap_t *s, int32_t x_mm, int32_t pos_unc_mm)
{
    int32_t hw;
    if (s == NULL || s->field == NULL)
        return;
    hw = s->field->width_mm / 2;
    told(s);
    blob(s, x_mm, hw, (fl_angle_t)-FL_ANGLE_90, pos_unc_mm);
    blob(s, x_mm, -hw, (fl_angle_t)FL_ANGLE_90, pos_unc_mm);
    if (x_mm != 0) {
        s->prior_half = (int8_t)(x_mm < 0 ? -1 : 1);
        s->prior_pose = false;   /* one prior at a time (set_prior_half) */
    } else
        s->half_known = false;   /* the halfway spots are each other's mirror */
}

void fl_relmap_set_prior_half(fl_relmap_t *s, int half)
{
    int c;
    if (s == NULL || s->field == NULL)
        return;
    /* one prior at a time, the latest (as mcl and fuzzy): a half and a pose
     * disc on the other half would leave no cell (libFuzzer) */
    s->prior_half = (int8_t)(half < 0 ? -1 : half > 0 ? 1 : 0);
    s->prior_pose = false;
    if (s->prior_half != 0)
        s->half_known = true;
    if (s->ignorance) {
        uniform(s);
        return;
    }
    if (!s->field->symmetric || s->prior_half == 0)
        return;
    /* the other half's particles to their mirror (the same observations) */
    for (c = 0; c < FL_RELMAP_N; c++) {
        int ix = c % FL_RELMAP_NX, m = FL_RELMAP_N - 1 - c;
        int32_t x, y;
        fl_relmap_cell_pos(s, ix, c / FL_RELMAP_NX, &x, &y);
        if (s->prior_half < 0 ? x > 0 : x < 0) {
            if (s->bel[c] > s->bel[m]) {
                s->bel[m] = s->bel[c];
                s->head[m] = fl_angle_add(s->head[c], (fl_angle_t)FL_ANGLE_180);
            }
            s->bel[c] = s->params.floor_q16;
        }
    }
}

void fl_relmap_set_prior_pose(fl_relmap_t *s, int32_t x_mm, int32_t y_mm, int32_t radius_mm)
{
    if (s == NULL || s->field == NULL)
        return;
    /* The centre is clamped to the carpet, so the region always holds the
     * cell under it (a centre off the carpet would leave no cell, an empty
     * belief) and in_prior's squares stay within int64. */
    s->prior_pose = true;
    s->prior_half = 0;   /* replaces a half prior (see set_prior_half) */
    s->prior_x_mm = x_mm < -s->hx ? -s->hx : x_mm > s->hx ? s->hx : x_mm;
    s->prior_y_mm = y_mm < -s->hy ? -s->hy : y_mm > s->hy ? s->hy : y_mm;
    s->prior_r_mm = radius_mm < 0 ? 0 : radius_mm > 20000 ? 20000 : radius_mm;
    if (s->ignorance)
        uniform(s);
}

void fl_relmap_clear_prior(fl_relmap_t *s)
{
    if (s == NULL || s->field == NULL)
        return;
    s->prior_half = 0;
    s->prior_pose = false;
    if (s->ignorance)
        uniform(s);
}

fl_status_t fl_relmap_reseed(fl_relmap_t *s, const fl_obs_report_t *r)
{
    fl_status_t st;
    fl_angle_t h = 0;
    bool known;
    int c, best = 0;
    if (s == NULL)
        return FL_ERR_NULL;
    if (s->field == NULL)
        return FL_ERR_STATE;
    st = fl_obs_report_check(r, s->field);
    if (st != FL_OK) {
        s->stats.reseeds_refused++;
        return st;
    }
    known = !s->ignorance && s->heading_known;
    for (c = 1; c < FL_RELMAP_N; c++)
        if (s->bel[c] > s->bel[best])
            best = c;
    h = s->head[best];
    told(s);
    s->stats.resets--;
    s->heading_known = known;
    blob(s, r->x_mm, r->y_mm, h, r->sd_mm);
    s->stats.reseeds++;
    return FL_OK;
}

/* Process noise: each particle at least spread_q16 of its strongest
 * neighbour's belief (and that neighbour's heading when it takes it), so
 * that the particles around a mode stay candidates for the relative map
 * as the robot moves and slips. */
static void dilate(fl_relmap_t *s)
{
    int ix, iy, dx, dy;
    memcpy(s->tmp_bel, s->bel, sizeof s->bel);
    memcpy(s->tmp_head, s->head, sizeof s->head);
    for (iy = 0; iy < FL_RELMAP_NY; iy++)
        for (ix = 0; ix < FL_RELMAP_NX; ix++) {
            int c = iy * FL_RELMAP_NX + ix;
            for (dy = -1; dy <= 1; dy++)
                for (dx = -1; dx <= 1; dx++) {
                    int jx = ix + dx, jy = iy + dy, j;
                    uint32_t v;
                    if (jx < 0 || jx >= FL_RELMAP_NX || jy < 0 || jy >= FL_RELMAP_NY)
                        continue;
                    j = jy * FL_RELMAP_NX + jx;
                    v = ((uint32_t)s->tmp_bel[j] * s->params.spread_q16) >> 16;
                    if (v > s->bel[c]) {
                        s->bel[c] = (uint16_t)v;
                        s->head[c] = s->tmp_head[j];
                    }
                }
        }
}

/* The collected motion shifted: every particle's belief splat onto the
 * four particles around its own displacement. */
static void shift(fl_relmap_t *s)
{
    int c, mx = 0;
    memset(s->tmp_bel, 0, sizeof s->tmp_bel);
    memset(s->tmp_head, 0, sizeof s->tmp_head);
    for (c = 0; c < FL_RELMAP_N; c++) {
        int32_t cs = fl_cos_q15(s->head[c]), sn = fl_sin_q15(s->head[c]), tx, ty, k;
        int64_t wx_q4, wy_q4;
        if (s->bel[c] == 0)
            continue;
        wx_q4 = ((int64_t)s->pend_x_mm * cs - (int64_t)s->pend_y_mm * sn) >> 15;
        wy_q4 = ((int64_t)s->pend_x_mm * sn + (int64_t)s->pend_y_mm * cs) >> 15;
        /* landing point in Q8 cells (Q4 mm * 4096 / Q8 mm; a multiply, as a left shift of a
         * negative value is undefined) */
        tx = (c % FL_RELMAP_NX) * 256 + (int32_t)((wx_q4 * 4096) / s->cell_x_q8);
        ty = (c / FL_RELMAP_NX) * 256 + (int32_t)((wy_q4 * 4096) / s->cell_y_q8);
        tx = tx < 0 ? 0 : tx > (FL_RELMAP_NX - 1) * 256 ? (FL_RELMAP_NX - 1) * 256 : tx;
        ty = ty < 0 ? 0 : ty > (FL_RELMAP_NY - 1) * 256 ? (FL_RELMAP_NY - 1) * 256 : ty;
        for (k = 0; k < 4; k++) {
            int jx = (tx >> 8) + (k & 1), jy = (ty >> 8) + (k >> 1);
            uint32_t wx = (k & 1) ? (uint32_t)(tx & 255) : 256u - (uint32_t)(tx & 255);
            uint32_t wy = (k >> 1) ? (uint32_t)(ty & 255) : 256u - (uint32_t)(ty & 255);
            uint32_t v = ((uint32_t)s->bel[c] * wx * wy + 32768u) >> 16, t;
            int j;
            if (v == 0 || jx >= FL_RELMAP_NX || jy >= FL_RELMAP_NY)
                continue;
            j = jy * FL_RELMAP_NX + jx;
            if (v > s->tmp_bel[j])
                s->tmp_head[j] = s->head[c];
            t = s->tmp_bel[j] + v;
            s->tmp_bel[j] = (uint16_t)(t > 65535u ? 65535u : t);
        }
    }
    for (c = 0; c < FL_RELMAP_N; c++)
        if (s->tmp_bel[c] > mx)
            mx = s->tmp_bel[c];
    for (c = 0; c < FL_RELMAP_N; c++) {
        uint32_t v = mx > 0 ? (uint32_t)(((uint64_t)s->tmp_bel[c] * 65535u + (uint32_t)mx / 2u) /
                                         (uint32_t)mx)
                            : 65535u;
        if (!s->ignorance && v < s->params.floor_q16 && s->bel[c] > 0)
            v = s->params.floor_q16;
        s->bel[c] = (uint16_t)v;
        s->head[c] = s->tmp_head[c];
    }
    s->pend_x_mm = s->pend_y_mm = 0;
    dilate(s);
}

void fl_relmap_predict(fl_relmap_t *s, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    int32_t c, sn, px, py, half;
    int i;
    if (s == NULL || s->field == NULL)
        return;
    s->stats.predicts++;
    if (dx_mm > s->params.odo_max_mm || dx_mm < -s->params.odo_max_mm ||
        dy_mm > s->params.odo_max_mm || dy_mm < -s->params.odo_max_mm) {
        s->stats.odo_rejected++;
        return;
    }
    if (s->since_obs < 65535u)
        s->since_obs++;
    if (s->ignorance)
        return;   /* odometry alone tells nothing */
    for (i = 0; i < FL_RELMAP_N; i++)
        s->head[i] = fl_angle_add(s->head[i], dtheta);
    /* P' = R(-dtheta) (P + d), Q4 mm in the new robot frame */
    c = fl_cos_q15(dtheta);
    sn = fl_sin_q15(dtheta);
    px = s->pend_x_mm + dx_mm * 16;
    py = s->pend_y_mm + dy_mm * 16;
    s->pend_x_mm = (int32_t)(((int64_t)px * c + (int64_t)py * sn) >> 15);
    s->pend_y_mm = (int32_t)((-(int64_t)px * sn + (int64_t)py * c) >> 15);
    half = (s->cell_x_q8 < s->cell_y_q8 ? s->cell_x_q8 : s->cell_y_q8) >> 5;   /* Q4 half cell */
    if ((int64_t)s->pend_x_mm * s->pend_x_mm + (int64_t)s->pend_y_mm * s->pend_y_mm >=
        (int64_t)half * half)
        shift(s);
}
