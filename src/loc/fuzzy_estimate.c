/*
 * src/loc/fuzzy_estimate.c - the estimate of the fuzzy position grid
 * (dominant mode, position, heading, reliability, tracking).
 *
 *
 * Estimate.  The dominant mode is the global peak, unless the tracked mode
 * (or before tracking, the prior's region: a pose, or the own half, which
 * the game tells) keeps a peak of at least switch_q8 (half prior: 1/8) of
 * it: symmetric modes (SPL 2013's four identical posts) stay in the grid,
 * the prior or the track decides.  Position: 3 mean-shift iterations of the
 * centre of gravity of the contents (cell centre + offset) within
 * mode_radius_mm, weighted by height - peak/2 (near the centre of a
 * symmetric field only cells whose heading agrees with the mode's count,
 * so the mirror mode cannot leak in).  Heading: circular mean of the
 * trapezoid centres weighted by the same weight x (h - b) / h x 16 / (16 +
 * core code), trimmed to 30 degrees around the reference (the tracked
 * heading) when that keeps 1/16 of the weight; otherwise the trimmed mean
 * around the dominant heading cluster (16-bin histogram of the same
 * weights, best 3 adjacent bins), never the mean of two opposite clusters
 * (a heading no cell holds: the estimate would jump to it for single
 * frames).  Reliability (Q0.16):
 * consistency x compactness min(1, 9 cells / cells >= peak/2) x (1 - mean
 * relative bias of the mode) x uniqueness (1 - the highest cell elsewhere
 * / the peak; the mirror of a symmetric field is not "elsewhere").  The
 * estimate becomes the tracked mode once the reliability reaches
 * track_min_q16; predict moves the track by the odometry.
 * Confidence (step 7, read by nothing above): the spread of the possibility
 * mass around the estimate, the heading spread of the mode, the mirror
 * pose's possibility when the half is not decided, and the reliability
 * calibrated to the contract of localizer.h (fz_calibrate); a flat grid
 * reports the centre of the prior's region, not the first cell scanned.
 * Cost: O(cells) (peak, uniqueness) + O(window) per mean-shift
 * iteration.
 */
#include "fieldloc/fuzzy.h"
#include "fuzzy_int.h"

#include <string.h>

#define TRIM_ANGLE 5461       /* 30 deg: heading estimate's trimming window */
#define HBIN_BITS 4           /* heading histogram of the estimate: 16 bins */
#define HBINS (1 << HBIN_BITS)
#define HOLD_DEN 16           /* the tracked heading is kept while its
                                 cells carry 1/HOLD_DEN of the weight */


static bool heading_agrees(const fl_fuzzy_cell_t *c, fl_angle_t h)
{
    int32_t d = fl_angle_sub(c->centre, h);
    return c->core >= FL_FUZZY_WFULL || (d <= FL_ANGLE_90 && d >= -FL_ANGLE_90);
}

typedef struct {
    int kind;                 /* 0 none, 1 half, 2 pose */
    int half;
    int32_t x, y, r;
    fl_angle_t h;
    bool check_heading;       /* the mirror mode may fall in the region */
} ref_t;

/* On a symmetric field the mirror (-x, -y, h + 180) of a pose within r of
 * (x, y) can itself lie within r of it only near the centre: only there
 * must a region tell the two apart by heading (a single cell whose heading
 * an outlier replaced must not make the region miss its mode). */
static bool mirror_near(const fl_fuzzy_t *g, int32_t x, int32_t y, int32_t r)
{
    return g->field->symmetric && fz_iabs(x) <= 2 * r && fz_iabs(y) <= 2 * r;
}

static bool in_ref(const fl_fuzzy_t *g, const ref_t *ref, int ix, int iy,
                   const fl_fuzzy_cell_t *c, uint32_t *d2)
{
    int32_t cx = fz_centre_x(g, ix) + c->off_x_mm, cy = fz_centre_y(g, iy) + c->off_y_mm;
    *d2 = 0;
    if (ref->kind == 1)
        return ref->half < 0 ? cx < 0 : cx > 0;
    if (ref->kind == 2) {
        int32_t ddx = cx - ref->x, ddy = cy - ref->y;
        if (fz_iabs(ddx) > ref->r || fz_iabs(ddy) > ref->r)
            return false;
        *d2 = (uint32_t)(ddx * ddx) + (uint32_t)(ddy * ddy);
        return *d2 <= (uint32_t)ref->r * (uint32_t)ref->r &&
               (!ref->check_heading || heading_agrees(c, ref->h));
    }
    return false;
}

/* Reference heading of a mode found without a track: circular mean of the
 * trapezoid centres within mode_radius of (px, py), weighted by height x
 * heading information (h - b), so that one cell with a stray heading does
 * not decide.  fallback when no cell has heading information. */
static fl_angle_t window_heading(const fl_fuzzy_t *g, int32_t px, int32_t py,
                                 fl_angle_t fallback)
{
    int32_t R = fz_clamp32(g->params.mode_radius_mm, FZ_CELL, 2000);
    int ix0, ix1, iy0, iy1, ix, iy;
    int64_t sc = 0, ss = 0;
    fz_window(g, px, py, R, &ix0, &ix1, &iy0, &iy1);
    for (iy = iy0; iy <= iy1; iy++)
        for (ix = ix0; ix <= ix1; ix++) {
            const fl_fuzzy_cell_t *c = &g->cell[iy * g->nx + ix];
            int32_t w;
            if (c->height <= c->bias || c->core >= FL_FUZZY_WFULL)
                continue;
            w = (int32_t)c->height * (int32_t)(c->height - c->bias);
            sc += (int64_t)w * fl_cos_q15(c->centre);
            ss += (int64_t)w * fl_sin_q15(c->centre);
        }
    while (sc > (1 << 30) || sc < -(1 << 30) || ss > (1 << 30) || ss < -(1 << 30)) {
        sc /= 2;
        ss /= 2;
    }
    return sc == 0 && ss == 0 ? fallback : fl_atan2((int32_t)ss, (int32_t)sc);
}

/* Uniqueness (Q16): 1 - c / peak, c = the highest cell farther than two
 * mode radii from the estimate (and, on a symmetric field, from its
 * mirror, which is the same hypothesis); 0 when another place is as
 * possible.  Keeps an ambiguous belief (two penalty spots that look alike)
 * from being tracked (and gated) before an observation decides. */
static uint32_t uniqueness(const fl_fuzzy_t *g, int32_t px, int32_t py, uint32_t peak)
{
    int32_t R2 = 2 * fz_clamp32(g->params.mode_radius_mm, FZ_CELL, 2000);
    uint32_t c = 0;
    int ix, iy;
    if (peak == 0)
        return 0;
    for (iy = 0; iy < g->ny; iy++) {
        int32_t cy = fz_centre_y(g, iy);
        const fl_fuzzy_cell_t *row = &g->cell[iy * g->nx];
        bool near_y = fz_iabs(cy - py) <= R2;
        bool near_my = g->field->symmetric && fz_iabs(cy + py) <= R2;
        for (ix = 0; ix < g->nx; ix++) {
            int32_t cx;
            if (row[ix].height <= c)
                continue;
            cx = fz_centre_x(g, ix);
            if ((near_y && fz_iabs(cx - px) <= R2) || (near_my && fz_iabs(cx + px) <= R2))
                continue;
            c = row[ix].height;
        }
    }
    return c >= peak ? 0u : 65536u - (c * 65536u) / peak;
}

/* The estimate's mode window: cells within R of (px, py), height at least
 * hp / 2, heading agreeing with rh when chk (the mirror may be inside). */
typedef struct {
    int ix0, ix1, iy0, iy1;
    int32_t px, py, R;
    uint32_t hp;
    bool chk;
    fl_angle_t rh;
} win_t;

/* Heading weight of a cell of the window (w = height - peak/2 > 0) x how
 * much heading information the cell has: (h - b) / h x 16 / (16 + core
 * code) (core 11 deg: 1/2); 0 for a cell without heading information.
 * Scaling: w <= 255, product <= 255 x 255 x 16 < 2^21, result <= 255. */
static int32_t heading_weight(const fl_fuzzy_cell_t *c, int32_t w)
{
    if (c->core >= FL_FUZZY_WFULL || c->height <= c->bias)
        return 0;
    return (w * (int32_t)(c->height - c->bias) * 16) /
           ((int32_t)c->height * (16 + (int32_t)c->core));
}

static bool in_window(const fl_fuzzy_t *g, const win_t *wn, int ix, int iy,
                      const fl_fuzzy_cell_t *c)
{
    int32_t ddx = fz_centre_x(g, ix) - wn->px, ddy = fz_centre_y(g, iy) - wn->py;
    return c->height * 2u >= wn->hp && ddx * ddx + ddy * ddy <= wn->R * wn->R &&
           (!wn->chk || heading_agrees(c, wn->rh));
}

/* Circular sums (cos, sin, Q15 x weight) of the window's trapezoid centres
 * within TRIM_ANGLE of h.  Scaling: weight <= 255, window <= 41 x 41
 * cells: |sums| < 2^15 x 255 x 1681 < 2^39 (int64). */
static void trimmed_sums(const fl_fuzzy_t *g, const win_t *wn, fl_angle_t h,
                         int64_t *scos, int64_t *ssin)
{
    int ix, iy;
    *scos = *ssin = 0;
    for (iy = wn->iy0; iy <= wn->iy1; iy++)
        for (ix = wn->ix0; ix <= wn->ix1; ix++) {
            const fl_fuzzy_cell_t *c = &g->cell[iy * g->nx + ix];
            int32_t wh, dh;
            if (!in_window(g, wn, ix, iy, c))
                continue;
            wh = heading_weight(c, (int32_t)c->height - (int32_t)(wn->hp / 2u));
            dh = fl_angle_sub(c->centre, h);
            if (wh <= 0 || dh > TRIM_ANGLE || dh < -TRIM_ANGLE)
                continue;
            *scos += (int64_t)wh * fl_cos_q15(c->centre);
            *ssin += (int64_t)wh * fl_sin_q15(c->centre);
        }
}

/* Step 1: the reference region: the tracked mode, else the prior's (a
 * pose, or the own half); kind 0 when there is none. */
static void mode_reference(const fl_fuzzy_t *g, ref_t *ref)
{
    memset(ref, 0, sizeof *ref);
    if (g->track_valid) {
        ref->kind = 2;
        ref->x = g->track_x_mm;
        ref->y = g->track_y_mm;
        ref->h = g->track_heading;
        ref->r = fz_clamp32(g->params.track_radius_mm, FZ_CELL, 5000);
        ref->check_heading = mirror_near(g, ref->x, ref->y, ref->r);
    } else if (g->prior.kind == FL_FUZZY_PRIOR_POSE) {
        ref->kind = 2;
        ref->x = g->prior.x_mm;
        ref->y = g->prior.y_mm;
        ref->h = g->prior.heading;
        ref->r = g->prior.radius_mm;
        ref->check_heading = true;
    } else if (g->prior.kind == FL_FUZZY_PRIOR_HALF) {
        ref->kind = 1;
        ref->half = g->prior.half;
    }
}

/* Step 2: the dominant mode's cell: the global peak, unless the reference
 * region's peak (ties: the nearest to the reference) is at least
 * switch_q8 of it (half prior: 1/8).  -1 for an empty grid; *switched when
 * a tracked mode is given up. */
static int mode_cell(const fl_fuzzy_t *g, const ref_t *ref, bool *switched)
{
    int nx = g->nx, ny = g->ny, ix, iy, gi = -1, li = -1, ci;
    uint32_t hg = 0, hl = 0, dl = UINT32_MAX;
    for (iy = 0; iy < ny; iy++) {
        for (ix = 0; ix < nx; ix++) {
            int i = iy * nx + ix;
            const fl_fuzzy_cell_t *c = &g->cell[i];
            uint32_t d2;
            if (c->height == 0)
                continue;
            if (c->height > hg) {
                hg = c->height;
                gi = i;
            }
            if (ref->kind != 0 && in_ref(g, ref, ix, iy, c, &d2) &&
                (c->height > hl || (c->height == hl && d2 < dl))) {
                hl = c->height;
                dl = d2;
                li = i;
            }
        }
    }
    if (gi < 0)                         /* impossible for a valid grid */
        return -1;
    /* the tracked mode (or a pose prior) is kept while its peak is at least
     * switch_q8 of the global one; the half prior (kick-off, penalty
     * placement: told by the game) while it is at least 1/8 of it */
    ci = (li >= 0 && hl * 256u >= hg * (ref->kind == 1 ? 32u : g->params.switch_q8)) ? li : gi;
    *switched = g->track_valid && ci != li;
    return ci;
}

/* The sums of one mean-shift iteration over the mode window. */
typedef struct {
    int64_t sw, sb;                  /* weight, weighted relative bias */
    int64_t scos, ssin, swh;         /* heading: all cells */
    int64_t swcore2;                 /* heading: sum wh x core^2 (binary
                                        angle^2 / 2^8) */
    int64_t tcos, tsin, twh;         /* heading: within TRIM_ANGLE of rh */
    int32_t bin[HBINS];              /* heading histogram */
    uint32_t nmode;                  /* cells in the window */
} msum_t;

/* Highest cell of the window (within R of its centre; heading agreeing
 * when the mirror may be inside). */
static uint32_t window_peak(const fl_fuzzy_t *g, const win_t *wn)
{
    int ix, iy;
    uint32_t hp = 0;
    for (iy = wn->iy0; iy <= wn->iy1; iy++)
        for (ix = wn->ix0; ix <= wn->ix1; ix++) {
            const fl_fuzzy_cell_t *c = &g->cell[iy * g->nx + ix];
            int32_t ddx = fz_centre_x(g, ix) - wn->px, ddy = fz_centre_y(g, iy) - wn->py;
            if (c->height > hp && ddx * ddx + ddy * ddy <= wn->R * wn->R &&
                (!wn->chk || heading_agrees(c, wn->rh)))
                hp = c->height;
        }
    return hp;
}

/* Step 3: 3 mean-shift iterations from (*px, *py): centre of gravity of
 * the contents of the window, weighted by height - peak/2; *wn and *s are
 * the last iteration's window and sums. */
static void mean_shift(const fl_fuzzy_t *g, int32_t *px, int32_t *py, fl_angle_t rh,
                       win_t *wn, msum_t *s)
{
    int32_t R = fz_clamp32(g->params.mode_radius_mm, FZ_CELL, 2000);
    bool chk = mirror_near(g, *px, *py, R);
    int ix, iy, it;
    memset(wn, 0, sizeof *wn);
    memset(s, 0, sizeof *s);
    for (it = 0; it < 3; it++) {
        int64_t sx = 0, sy = 0;
        fz_window(g, *px, *py, R, &wn->ix0, &wn->ix1, &wn->iy0, &wn->iy1);
        wn->px = *px;
        wn->py = *py;
        wn->R = R;
        wn->chk = chk;
        wn->rh = rh;
        wn->hp = window_peak(g, wn);
        memset(s, 0, sizeof *s);
        for (iy = wn->iy0; iy <= wn->iy1; iy++)
            for (ix = wn->ix0; ix <= wn->ix1; ix++) {
                const fl_fuzzy_cell_t *c = &g->cell[iy * g->nx + ix];
                int32_t cx = fz_centre_x(g, ix), cy = fz_centre_y(g, iy);
                int32_t w, wh;
                if (!in_window(g, wn, ix, iy, c))
                    continue;
                s->nmode++;
                w = (int32_t)c->height - (int32_t)(wn->hp / 2u);
                if (w <= 0)
                    continue;
                s->sw += w;
                sx += (int64_t)w * (cx + c->off_x_mm);
                sy += (int64_t)w * (cy + c->off_y_mm);
                s->sb += (int64_t)w * ((c->bias * 255u) / c->height);
                wh = heading_weight(c, w);
                if (wh > 0) {
                    int32_t dh = fl_angle_sub(c->centre, rh);
                    s->scos += (int64_t)wh * fl_cos_q15(c->centre);
                    s->ssin += (int64_t)wh * fl_sin_q15(c->centre);
                    s->swh += wh;
                    s->swcore2 += (int64_t)wh *
                                  (((int64_t)c->core * FL_FUZZY_AUNIT *
                                    c->core * FL_FUZZY_AUNIT) >> 8);
                    s->bin[(uint16_t)c->centre >> (16 - HBIN_BITS)] += wh;
                    if (dh <= TRIM_ANGLE && dh >= -TRIM_ANGLE) {
                        s->tcos += (int64_t)wh * fl_cos_q15(c->centre);
                        s->tsin += (int64_t)wh * fl_sin_q15(c->centre);
                        s->twh += wh;
                    }
                }
            }
        if (s->sw == 0)
            break;
        *px = (int32_t)(sx / s->sw);
        *py = (int32_t)(sy / s->sw);
    }
}

/* Step 4: the heading: trimmed mean around the reference rh, else around
 * the dominant heading cluster; rh when no cell has heading information. */
static fl_angle_t mode_heading(const fl_fuzzy_t *g, const win_t *wn, const msum_t *s,
                               fl_angle_t rh)
{
    int64_t scos = s->scos, ssin = s->ssin;
    if (HOLD_DEN * s->twh >= s->swh && (s->tcos != 0 || s->tsin != 0)) {
        /* trimmed mean: cells within TRIM_ANGLE of the reference (the
         * tracked heading) carry at least 1/HOLD_DEN of the weight; cells
         * whose heading an outlier replaced do not pull the estimate */
        scos = s->tcos;
        ssin = s->tsin;
    } else if (s->swh > 0) {
        /* otherwise the dominant heading cluster: the 3 adjacent bins
         * (67.5 deg) with the most weight, then the trimmed mean around
         * the middle bin's centre.  Never the mean of two opposite
         * clusters (a heading that no cell holds). */
        int k, kb = 0;
        int32_t best = -1;
        for (k = 0; k < HBINS; k++) {
            int32_t v = s->bin[(k + HBINS - 1) % HBINS] + s->bin[k] + s->bin[(k + 1) % HBINS];
            if (v > best) {
                best = v;
                kb = k;
            }
        }
        trimmed_sums(g, wn, (fl_angle_t)(int32_t)((kb << (16 - HBIN_BITS)) +
                                                  (1 << (15 - HBIN_BITS)) - 65536 * (kb >= HBINS / 2)),
                     &scos, &ssin);
    }
    if (scos == 0 && ssin == 0)
        return rh;
    /* reduce to 31 bits keeping the ratio (window up to 41 x 41 cells) */
    while (scos > (1 << 30) || scos < -(1 << 30) || ssin > (1 << 30) || ssin < -(1 << 30)) {
        scos /= 2;
        ssin /= 2;
    }
    return fl_atan2((int32_t)ssin, (int32_t)scos);
}

/* Step 5: reliability, Q16: consistency x compactness x (1 - bias) x
 * uniqueness. */
static uint32_t reliability(const fl_fuzzy_t *g, const msum_t *s, int32_t px, int32_t py,
                            uint32_t hp)
{
    uint32_t rel, area, one_minus_b;
    area = s->nmode <= 9 ? 65536u : (9u * 65536u) / s->nmode;
    one_minus_b = s->sw > 0 ? (uint32_t)(65536 - (s->sb * 65536) / (s->sw * 255)) : 0;
    if (one_minus_b > 65536u)
        one_minus_b = 0;
    rel = (uint32_t)(((uint64_t)g->consistency_q16 * area) >> 16);
    rel = (uint32_t)(((uint64_t)rel * one_minus_b) >> 16);
    rel = (uint32_t)(((uint64_t)rel * uniqueness(g, px, py, hp)) >> 16);
    return rel > 65535u ? 65535u : rel;
}

/* Spread of the possibility mass around the estimate (px, py): second
 * moments about it of the cell contents at least half the peak, weighted
 * by height - 127 (like the mean shift), over the whole grid except, on a
 * symmetric field, the cells nearer the mirror pose (the mirror is its own
 * hypothesis, mirror_q16).  Also tells whether the grid is flat (every
 * cell height 1 with bias 1: no information at all).  Scaling: |d| <
 * 2^15 mm, d^2 < 2^30, x weight 128 < 2^37, x 2^14 cells < 2^51 (int64).
 * Cost: O(cells). */
static bool spread(const fl_fuzzy_t *g, int32_t px, int32_t py, fl_fuzzy_estimate_t *out)
{
    int64_t sw = 0, sxx = 0, syy = 0, sxy = 0;
    bool flat = true;
    int ix, iy;
    for (iy = 0; iy < g->ny; iy++) {
        const fl_fuzzy_cell_t *row = &g->cell[iy * g->nx];
        for (ix = 0; ix < g->nx; ix++) {
            const fl_fuzzy_cell_t *c = &row[ix];
            int32_t cx, cy, dx, dy, w;
            if (c->height != 255 || c->bias != 255)
                flat = false;
            if (c->height < 128)
                continue;
            cx = fz_centre_x(g, ix) + c->off_x_mm;
            cy = fz_centre_y(g, iy) + c->off_y_mm;
            dx = cx - px;
            dy = cy - py;
            if (g->field->symmetric &&
                (int64_t)(cx + px) * (cx + px) + (int64_t)(cy + py) * (cy + py) <
                    (int64_t)dx * dx + (int64_t)dy * dy)
                continue;
            w = (int32_t)c->height - 127;
            sw += w;
            sxx += (int64_t)w * dx * dx;
            syy += (int64_t)w * dy * dy;
            sxy += (int64_t)w * dx * dy;
        }
    }
    if (sw > 0) {
        uint32_t vx = (uint32_t)(sxx / sw), vy = (uint32_t)(syy / sw);
        out->sd_x_mm = (uint16_t)fl_isqrt32(vx);
        out->sd_y_mm = (uint16_t)fl_isqrt32(vy);
        out->cov_xy_mm2 = (int32_t)(sxy / sw);
    }
    return flat;
}

/* Heading spread of the mode window: the circular spread of the trapezoid
 * centres, sqrt(2 (1 - R)) rad (R: mean resultant length; the small-angle
 * form of the circular standard deviation), combined with the mean core
 * half-width as a uniform spread (core^2 / 3).  32767 without heading
 * information. */
static fl_angle_t heading_spread(const msum_t *s)
{
    int64_t sc = s->scos, ss = s->ssin, sw = s->swh;
    uint32_t r_q16, v_q16, sd_q16;
    int64_t var;
    if (sw <= 0)
        return (fl_angle_t)32767;
    while (sc > (1 << 30) || sc < -(1 << 30) || ss > (1 << 30) || ss < -(1 << 30)) {
        sc /= 2;
        ss /= 2;
        sw /= 2;
    }
    if (sw <= 0)
        return (fl_angle_t)32767;
    r_q16 = (uint32_t)(((uint64_t)fl_hypot((int32_t)sc, (int32_t)ss) * 2u) / (uint64_t)sw);
    v_q16 = r_q16 >= 65536u ? 0u : 2u * (65536u - r_q16);       /* rad^2, Q16 */
    sd_q16 = fl_isqrt64((uint64_t)v_q16 << 16);                  /* rad, Q16 */
    /* rad -> binary angle: x 65536 / 2 pi = 10430.4 */
    var = (int64_t)(((uint64_t)sd_q16 * 10430u) >> 16);
    var = var * var + ((s->swcore2 / s->swh) << 8) / 3;
    var = (int64_t)fl_isqrt64((uint64_t)var);
    return (fl_angle_t)(var > 32767 ? 32767 : var);
}

/* The mirror hypothesis: on a symmetric field whose half nothing told,
 * the possibility of (-x, -y, h + 180) relative to the estimate's (Q16,
 * 65535 = as possible); 0 otherwise. */
static uint16_t mirror_ratio(const fl_fuzzy_t *g, int32_t px, int32_t py, fl_angle_t h)
{
    uint32_t pe, pm;
    if (!g->field->symmetric || g->half_known)
        return 0;
    pe = fl_fuzzy_possibility_q16(g, px, py, h);
    pm = fl_fuzzy_possibility_q16(g, -px, -py, fl_angle_add(h, FL_ANGLE_180));
    if (pm >= pe)
        return pm > 0 ? 65535u : 0u;
    return (uint16_t)(((uint64_t)pm * 65535u) / pe);
}

/* No information (a flat grid): the pose is the centre of the region the
 * prior allows (own half, a pose's disc, else the field), heading the
 * prior's (else 0); spread: a uniform distribution over that region
 * (sd = extent / sqrt(12)), no heading information. */
static void ignorance_pose(const fl_fuzzy_t *g, fl_fuzzy_estimate_t *out)
{
    int32_t hx = g->half_x_mm, hy = g->half_y_mm;
    out->ignorance = true;
    out->x_mm = 0;
    out->y_mm = 0;
    out->heading = 0;
    out->sd_x_mm = (uint16_t)((2 * hx * 1000) / 3464);
    out->sd_y_mm = (uint16_t)((2 * hy * 1000) / 3464);
    out->cov_xy_mm2 = 0;
    out->sd_heading = (fl_angle_t)32767;
    if (g->prior.kind == FL_FUZZY_PRIOR_HALF) {
        out->x_mm = g->prior.half * (hx / 2);
        out->sd_x_mm = (uint16_t)((hx * 1000) / 3464);
    } else if (g->prior.kind == FL_FUZZY_PRIOR_POSE) {
        int32_t r = fz_clamp32(g->prior.radius_mm, FZ_CELL, hx);
        out->x_mm = fz_clamp32(g->prior.x_mm, -hx, hx);
        out->y_mm = fz_clamp32(g->prior.y_mm, -hy, hy);
        out->heading = g->prior.heading;
        out->sd_x_mm = (uint16_t)(r / 2);
        out->sd_y_mm = (uint16_t)(r / 2);
    }
}

/* Calibration of the reliability (localizer.h: of the estimates reported
 * with reliability >= r, at least the share r is within 500 mm and 20 deg
 * of the truth).  Raw score: the grid's reliability x 16 / (16 + predict
 * calls since an observation was applied) (a belief that has only been
 * moved by odometry for a while is worth less than its shape says).  The
 * map raw -> reliability is piecewise linear through the knots below,
 * fitted by tools/build/fit_reliability.py on the records of tracked,
 * half-decided estimates of the training walks
 *     build/fieldloc reliability --seeds 11,12,...,40
 *         --frame-seeds 11,12,13 --obs-cache-dir DIR --dump train.tsv
 * (share of good records per raw interval, made monotone, lowered by two
 * standard errors, the smaller of feature mode and frames mode, capped at
 * 0.97; each knot at its interval's upper end so that the interpolation
 * never exceeds the interval's share).  The held-out walks (seeds 1-3)
 * are `fieldloc reliability`'s default.  Then: on a symmetric field whose
 * half is not decided, x 1 / (1 + mirror) (the pose or its mirror, the
 * grid cannot tell: measured 0.50 good); without a tracked mode x
 * FZ_CAL_LOST / 256; no information at all: 0. */
#define FZ_CAL_KNOTS 15
#define FZ_CAL_LOST 128u
static const uint16_t fz_cal_raw[FZ_CAL_KNOTS] = {
    0, 1021, 1641, 2247, 2912, 3538, 4727, 5968, 8496, 11011, 13350, 18288, 22605, 30452, 65535};
static const uint16_t fz_cal_rel[FZ_CAL_KNOTS] = {
    0, 12700, 29276, 51978, 56046, 59224, 59224, 59769, 60901, 61840, 63251, 63568, 63568, 63568, 63568};

static uint16_t fz_calibrate(const fl_fuzzy_estimate_t *e)
{
    uint32_t raw, rel;
    int k;
    if (e->ignorance)
        return 0;
    raw = ((uint32_t)e->reliability_q16 * 16u) / (16u + (uint32_t)e->since_obs);
    for (k = 1; k < FZ_CAL_KNOTS - 1 && raw > fz_cal_raw[k]; k++)
        ;
    rel = fz_cal_rel[k - 1];
    if (raw > fz_cal_raw[k - 1])
        rel += (uint32_t)(((uint64_t)(fz_cal_rel[k] - fz_cal_rel[k - 1]) *
                           (raw - fz_cal_raw[k - 1])) / (uint32_t)(fz_cal_raw[k] - fz_cal_raw[k - 1]));
    if (rel > fz_cal_rel[k])
        rel = fz_cal_rel[k];
    if (!e->tracking)
        rel = (rel * FZ_CAL_LOST) >> 8;
    rel = (uint32_t)(((uint64_t)rel * 65536u) / (65536u + e->mirror_q16));
    return (uint16_t)(rel > 65535u ? 65535u : rel);
}

bool fl_fuzzy_estimate(fl_fuzzy_t *g, fl_fuzzy_estimate_t *out)
{
    int ci;
    int32_t px, py;
    fl_angle_t rh, heading;
    ref_t ref;
    win_t wn;
    msum_t s;
    uint32_t rel;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    if (!fz_ready(g) || out == NULL)
        return false;
    mode_reference(g, &ref);
    ci = mode_cell(g, &ref, &out->switched);
    if (ci < 0)
        return false;
    px = fz_centre_x(g, ci % g->nx) + g->cell[ci].off_x_mm;
    py = fz_centre_y(g, ci / g->nx) + g->cell[ci].off_y_mm;
    rh = g->track_valid && !out->switched ? g->track_heading
                                          : window_heading(g, px, py, g->cell[ci].centre);
    mean_shift(g, &px, &py, rh, &wn, &s);
    heading = mode_heading(g, &wn, &s, rh);
    px = fz_clamp32(px, -g->half_x_mm, g->half_x_mm);
    py = fz_clamp32(py, -g->half_y_mm, g->half_y_mm);
    rel = reliability(g, &s, px, py, wn.hp);
    /* step 6: the output, and the track */
    out->x_mm = px;
    out->y_mm = py;
    out->heading = heading;
    out->reliability_q16 = (uint16_t)rel;
    out->peak_q8 = (uint8_t)wn.hp;
    out->mode_cells = (uint16_t)(s.nmode > 65535u ? 65535u : s.nmode);
    if (out->switched)
        g->stats.mode_switches = fz_sat_inc(g->stats.mode_switches);
    if (g->track_valid || rel >= g->params.track_min_q16) {
        g->track_valid = true;
        g->track_x_mm = px;
        g->track_y_mm = py;
        g->track_heading = heading;
    }
    /* step 7: the confidence */
    out->tracking = g->track_valid;
    out->half_known = g->half_known || !g->field->symmetric;
    out->since_obs = g->since_obs;
    out->sd_heading = heading_spread(&s);
    if (spread(g, px, py, out)) {
        ignorance_pose(g, out);
    } else {
        out->mirror_q16 = mirror_ratio(g, px, py, heading);
    }
    out->calibrated_q16 = fz_calibrate(out);
    return true;
}
