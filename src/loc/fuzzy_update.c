/*
 * src/loc/fuzzy_update.c - the observation update of the fuzzy position grid
 * (seed 004, section 3.3 and "Update").
 *
 * Algorithm.  An observation (kind, range r, bearing b, orientation o,
 * confidence) of a landmark that is not unique induces, in each cell, the
 * UNION over the map landmarks L_k of that kind (posts: of the observed
 * side and color when known) of
 *   - a fuzzy ring around L_k: membership 1 within rc of distance r, falling
 *     linearly to 0 at rc + rs (rc, rs grow linearly with r: camera range
 *     errors grow with distance), evaluated where the cell's content is
 *     (centre + sub-cell offset);
 *   - the heading it implies there: direction(cell -> L_k) - b, a
 *     trapezoid of the bearing accuracy plus the angle half a cell
 *     subtends, with a relative bias head_bias (right ring, wrong heading;
 *     with head_bias_outlier at least the outlier bias bP below);
 *   - when the observation has an orientation and the kind one (L, T: mod
 *     360; X, marks: mod 90; centre circle: mod 180), the agreement between
 *     the heading the orientation implies, o_map(L_k) - o (one candidate
 *     per period), and the bearing-implied one: the ring is multiplied by
 *     it, so an oriented crossing gives an arc, not a ring.  At ranges
 *     where the robot may stand on the landmark the bearing says nothing
 *     and the heading is the orientation's;
 *   - a position factor rho = bP + (1 - bP) ring with the outlier bias
 *     bP = 1 - confidence (1 - bias_min): the observation may be false.
 * Per cell the best ring (and its heading) and the best ring with another
 * heading are kept; C x (S1 u S2) = (C x S1) u (C x S2) is computed with
 * the product's outer envelope (fuzzy_trap.c) and the union's; any further
 * hypothesis k is bounded by C x rho_k (the cell's own shape, scaled), so
 * it never widens nor flattens the cell.  Cells outside every ring are
 * multiplied by bP.  Heading cores and slopes are kept at least
 * head_min_core / head_min_slope (widening: still an envelope).  Then, on
 * a symmetric field, the belief is made exactly symmetric (nothing an
 * observation says tells a pose from its mirror; rounding would otherwise
 * let one mode die at random): when it already is on entry (g->sym_exact:
 * after ignorance, after any update, and kept by predict, which copies
 * its first half mirrored onto the second), only the first half of the
 * rows is updated and copied, mirrored, onto the second (half the cost);
 * otherwise (after a pose or penalty reset, painted without the mirror)
 * each cell and its mirror get their union; then the grid is normalized to a peak of 1
 * (heights below min_height become 0; an empty grid becomes ignorance,
 * counted).  No data association: every hypothesis stays in the grid.
 *
 * Robustness (false positives and L/T confusions arrive several times per
 * second in a legged robot's vision).  While a mode is tracked, the
 * observation is first evaluated on the tracked mode's core only: if it
 * leaves none of those cells at least gate_q8 of its height, it
 * contradicts the mode and is deferred (not applied, counted), except
 * every (gate_run + 1)-th of a run.  The fit feeds the consistency
 * (low-passed); consistency collapsing while contradictions arrive at
 * kidnap_rate_q8 per frame or more means a kidnap: reset to ignorance,
 * prior dropped, counted.
 *
 * Cost.  Per observation one region per matching landmark and orientation
 * candidate (bounding box of the ring, or of the arc: the annular sector
 * of directions within the orientation tolerance + 1 degree, where cells
 * outside the sector are skipped by a dot-product test before the atan2;
 * both only skip cells whose agreement is exactly 0); per grid row and
 * region two integer square roots give the one or two cell intervals the
 * ring crosses; only live cells there are evaluated (a squared-distance
 * test against the ring's bounds, then inside the ring one isqrt, one
 * atan2, the agreement, the envelope), on half the rows when the belief
 * is exactly symmetric.  Then passes over the grid: product,
 * symmetry, normalization: O(cells + cells in the rings), bounded by
 * O(cells x landmarks of the kind x orientation candidates).  The gate adds
 * the rows of the tracked window.  Measured by `make bench` (rows
 * fuzzy_*).  Memory: the row accumulator and the region list live
 * in g->scratch; stack < 400 B.
 *
 * Kind confusion (params.confuse_q8, build_regions): an L observation is
 * also a T seen as an L and a T an L seen as a T, their regions scaled by
 * a possibility that rises to 1 at low confidence; without a track those
 * regions only keep a cell possible (r3), never give it a heading.  Seed
 * 004's corner features likewise: a C, T-field or T-net is also either
 * other corner kind at confuse_q8 (the corner stage types by the lines it
 * sees leaving a pair, and a faint stem or an unseen net changes the
 * type; `simulate --field aibo2004 --frames --vision corners`, fuzzy,
 * seeds 1 / 2: position RMSE 374 / 540 mm without, 199 / 131 mm with).
 *
 * Invariant: the grid is valid after every call (never empty, bias <=
 * height); ignored and deferred observations leave the cells untouched.
 */
#include "fieldloc/fuzzy.h"
#include "fuzzy_int.h"

#include <string.h>

#define FZ_HT 32768
/* The sector pre-test and the sector boxes of oriented regions use the
 * orientation tolerance plus this margin (1 deg): far more than the
 * 0.02-degree atan2 error and the Q15 rounding of the unit vectors, so
 * every cell they skip has an orientation agreement of exactly 0 (the
 * results are those of the full evaluation, bit for bit). */
#define SECTOR_MARGIN 182

/* Trapezoid t(delta) in Q16 (65536 = 1), delta = |angle| in [0, 32768]. */
static uint32_t tpos(int32_t delta, int32_t core, int32_t slope)
{
    int32_t L;
    if (delta <= core)
        return 65536u;
    L = core + slope;
    if (delta >= L || slope <= 0)
        return 0;
    return (uint32_t)(((uint32_t)(L - delta) << 16) / (uint32_t)slope);
}

typedef struct {
    int32_t r, rc, rs, rw, rin, rout;
    uint32_t inv_rs;             /* 65535 * 2^16 / rs */
    fl_angle_t bearing;
    int32_t hcore, hslope;       /* heading trapezoid of the observation */
    int32_t ocore, oslope;       /* orientation agreement */
    bool no_bearing_heading;     /* the robot may stand on the landmark */
    int32_t sector_cos_q15;      /* cos(tol + SECTOR_MARGIN), Q15; 0 when
                                    that angle is 90 deg or more (no sector
                                    pre-test) */
    fl_angle_t sector_half;      /* tol + SECTOR_MARGIN (binary angle) */
    uint32_t bias_q16;           /* bP: possibility of an outlier */
    uint8_t bias_q8;
    uint32_t head_bias_q16;      /* relative heading bias of the trapezoid */
} obsp_t;

/* Position factor of a ring value r (Q16): bP + (1 - bP) r, Q16. */
static uint32_t rho(const obsp_t *q, uint32_t r_q16)
{
    return q->bias_q16 + (uint32_t)(((uint64_t)(65536u - q->bias_q16) * r_q16) >> 16);
}

/* Bias of the observation's heading trapezoid at ring value r (Q16):
 * "real, but its heading is not" rho(r) x head_bias; with
 * params.head_bias_outlier the union with "the observation is an outlier"
 * (bP, any pose): max(bP, rho(r) hb), so a pose on the ring with another
 * heading is never less possible than a pose off every ring.  (With rho
 * hb alone, a low-confidence false positive (bP > rho hb) would make the
 * cell's own heading less possible than no ring at all and, the cell's
 * relative bias being about hb too, tie the two plateaus of the product:
 * the envelope would flatten the cell and the next false ring impose its
 * heading, a large single-frame heading error.)
 * Scaling: rho hb < 2^33 in uint64, result <= rho(r). */
static uint32_t rho_head(const fl_fuzzy_t *g, const obsp_t *q, uint32_t r_q16)
{
    uint32_t rh = (uint32_t)(((uint64_t)rho(q, r_q16) * q->head_bias_q16) >> 16);
    return g->params.head_bias_outlier && rh < q->bias_q16 ? q->bias_q16 : rh;
}

static bool post_matches(const fl_landmark_t *lm, const fl_obs_t *o)
{
    if ((lm->kind == FL_LM_POST) && o->side != FL_SIDE_UNKNOWN &&
        lm->side != o->side)
        return false;
    if ((lm->kind == FL_LM_POST || lm->kind == FL_LM_BEACON || lm->kind == FL_LM_NET) &&
        o->color != FL_COLOR_NONE && lm->color != FL_COLOR_NONE &&
        lm->color != o->color)
        return false;
    /* beacons: the lower band too (a full beacon then matches exactly one
     * landmark; a partial one, color unknown, matches by its lower band) */
    if (lm->kind == FL_LM_BEACON && o->color2 != FL_COLOR_NONE &&
        lm->color2 != FL_COLOR_NONE && lm->color2 != o->color2)
        return false;
    return true;
}

static void add_region(fl_fuzzy_t *g, int *n, const fl_fuzzy_region_t *r)
{
    if (*n >= FL_FUZZY_MAX_REGIONS) {
        g->stats.regions_dropped = fz_sat_inc(g->stats.regions_dropped);
        return;
    }
    g->scratch.upd.region[*n] = *r;
    (*n)++;
}

/* Shrink the box [x0, x1] x [y0, y1] (already a valid bound) to the
 * bounding box of the annular sector of the ring around (lx, ly):
 * distances max(rin, 0)..rout, directions phi +- q->sector_half (< 90
 * deg).  Every cell with a non-zero orientation agreement lies in that
 * sector (see SECTOR_MARGIN), so the box stays a valid bound.
 * Scaling and overflow: R <= rout <= 3 x 30000 mm, R x Q15 < 2^32 in
 * int64; each point rounded to the nearest mm, the box widened by 4 mm
 * for the rounding and the table error (R x 2^-15 < 3 mm). */
static void sector_box(fl_fuzzy_region_t *rg, fl_angle_t phi, const obsp_t *q)
{
    int32_t lx = rg->lx_mm, ly = rg->ly_mm;
    int32_t *x0 = &rg->x0_mm, *x1 = &rg->x1_mm, *y0 = &rg->y0_mm, *y1 = &rg->y1_mm;
    int32_t rad[2], ax0 = INT32_MAX, ax1 = INT32_MIN, ay0 = INT32_MAX, ay1 = INT32_MIN;
    fl_angle_t ang[2];
    int i, j, k;
    rad[0] = q->rin > 0 ? q->rin : 0;
    rad[1] = q->rout;
    ang[0] = fl_angle_wrap((int32_t)phi - q->sector_half);
    ang[1] = fl_angle_wrap((int32_t)phi + q->sector_half);
    for (i = 0; i < 2; i++)
        for (j = 0; j < 2; j++) {
            int32_t px = lx + (int32_t)(((int64_t)rad[i] * fl_cos_q15(ang[j]) + 16384) >> 15);
            int32_t py = ly + (int32_t)(((int64_t)rad[i] * fl_sin_q15(ang[j]) + 16384) >> 15);
            ax0 = px < ax0 ? px : ax0;
            ax1 = px > ax1 ? px : ax1;
            ay0 = py < ay0 ? py : ay0;
            ay1 = py > ay1 ? py : ay1;
        }
    /* the outer arc's extreme points along the axes inside the sector */
    for (k = 0; k < 4; k++) {
        fl_angle_t a = fl_angle_wrap(k * 16384);
        int32_t dd = fz_iabs(fl_angle_sub(a, phi));
        if (dd > q->sector_half)
            continue;
        if (k == 0)
            ax1 = lx + q->rout > ax1 ? lx + q->rout : ax1;
        else if (k == 1)
            ay1 = ly + q->rout > ay1 ? ly + q->rout : ay1;
        else if (k == 2)
            ax0 = lx - q->rout < ax0 ? lx - q->rout : ax0;
        else
            ay0 = ly - q->rout < ay0 ? ly - q->rout : ay0;
    }
    if (ax0 - 4 > *x0)
        *x0 = ax0 - 4;
    if (ax1 + 4 < *x1)
        *x1 = ax1 + 4;
    if (ay0 - 4 > *y0)
        *y0 = ay0 - 4;
    if (ay1 + 4 < *y1)
        *y1 = ay1 + 4;
}

/* Regions of one map landmark for observation o: with an orientation, one
 * per orientation candidate om + j x period (the arcs), else the ring;
 * ring values scaled by scale_q16 (65535 = 1).  Scaling and overflow:
 * r + rw <= 3 * 30000; arc half size 2 (r + rw) sin(tol / 2) from a Q15
 * sine in 64 bit. */
typedef struct {
    bool oriented;
    fl_angle_t om;               /* the landmark's orientation (map) */
    fl_angle_t orientation;      /* the observation's */
    int32_t period;              /* of the orientation (65536: one candidate) */
    uint16_t scale_q16;
    int n;                       /* regions so far (in and out: the callee
                                    writes *sp, so gcc passes the pointer,
                                    not its fields on the stack) */
} regspec_t;

static void landmark_regions(fl_fuzzy_t *g, const fl_landmark_t *lm, const obsp_t *q,
                             regspec_t *sp)
{
    int *n = &sp->n;
    bool oriented = sp->oriented;
    fl_angle_t om = sp->om, orientation = sp->orientation;
    int32_t period = sp->period;
    uint16_t scale_q16 = sp->scale_q16;
    int32_t bx0 = lm->x_mm - q->rout - FZ_CELL, bx1 = lm->x_mm + q->rout + FZ_CELL;
    int32_t by0 = lm->y_mm - q->rout - FZ_CELL, by1 = lm->y_mm + q->rout + FZ_CELL;
    if (oriented) {
        fl_angle_t base = fl_angle_sub(om, orientation);
        int32_t j, nj = 65536 / period;
        int32_t tol = q->ocore + q->oslope;
        int32_t arc;
        if (tol > FZ_HT)
            tol = FZ_HT;
        arc = (int32_t)(((int64_t)2 * (q->r + q->rw) * fl_sin_q15(fl_angle_wrap(tol / 2)) + 32767) >> 15);
        arc += q->rw + FZ_CELL;
        for (j = 0; j < nj; j++) {
            fl_angle_t ho = fl_angle_wrap(base + j * period);
            /* direction landmark -> robot = heading + bearing + 180 */
            fl_angle_t phi = fl_angle_wrap((int32_t)ho + q->bearing + 32768);
            int32_t px = lm->x_mm + (int32_t)(((int64_t)q->r * fl_cos_q15(phi) + 16384) >> 15);
            int32_t py = lm->y_mm + (int32_t)(((int64_t)q->r * fl_sin_q15(phi) + 16384) >> 15);
            int32_t x0 = px - arc > bx0 ? px - arc : bx0;
            int32_t x1 = px + arc < bx1 ? px + arc : bx1;
            int32_t y0 = py - arc > by0 ? py - arc : by0;
            int32_t y1 = py + arc < by1 ? py + arc : by1;
            bool sector = !q->no_bearing_heading && q->sector_cos_q15 > 0;
            fl_fuzzy_region_t r;
            r.lx_mm = lm->x_mm;
            r.ly_mm = lm->y_mm;
            r.x0_mm = x0;
            r.x1_mm = x1;
            r.y0_mm = y0;
            r.y1_mm = y1;
            if (q->no_bearing_heading) {   /* no arc: the whole disc */
                r.x0_mm = bx0;
                r.x1_mm = bx1;
                r.y0_mm = by0;
                r.y1_mm = by1;
            } else if (sector) {
                sector_box(&r, phi, q);
            }
            if (r.x0_mm <= r.x1_mm && r.y0_mm <= r.y1_mm) {
                r.head_o = ho;
                r.ux_q15 = fl_cos_q15(phi);
                r.uy_q15 = fl_sin_q15(phi);
                r.oriented = true;
                r.sector = sector;
                r.scale_q16 = scale_q16;
                add_region(g, n, &r);
            }
        }
    } else {
        fl_fuzzy_region_t r;
        r.lx_mm = lm->x_mm;
        r.ly_mm = lm->y_mm;
        r.x0_mm = bx0;
        r.x1_mm = bx1;
        r.y0_mm = by0;
        r.y1_mm = by1;
        r.head_o = 0;
        r.ux_q15 = 0;
        r.uy_q15 = 0;
        r.oriented = false;
        r.sector = false;
        r.scale_q16 = scale_q16;
        add_region(g, n, &r);
    }
}

/* Regions of an observation: one per matching landmark and orientation
 * candidate; with params.confuse_q8, an L observation is also a T seen
 * as an L (the L of the stem and one bar arm: bisector = stem +- 45 deg)
 * and a T observation an L seen as a T (a third arm found along one of
 * the L's arms, the stem being the other: stem = either arm), those
 * regions scaled by confuse_q8. */
static int build_regions(fl_fuzzy_t *g, const fl_obs_t *o, const obsp_t *q)
{
    const fl_field_t *f = g->field;
    uint16_t i, nk = fl_field_count_kind(f, o->kind);
    uint8_t cq = g->params.confuse_q8;
    regspec_t sp;
    sp.n = 0;
    for (i = 0; i < nk; i++) {
        const fl_landmark_t *lm = fl_field_nth_kind(f, o->kind, i);
        fl_angle_t om = 0;
        int32_t period;
        bool oriented;
        if (lm == NULL || !post_matches(lm, o))
            continue;
        /* per landmark: seed 004's T-fields are Ts and Xs */
        period = fl_landmark_orientation_period(lm);
        oriented = o->has_orientation && period > 0 && fl_landmark_orientation(lm, &om);
        sp.oriented = oriented;
        sp.om = om;
        sp.orientation = o->orientation;
        sp.period = period;
        sp.scale_q16 = 65535u;
        landmark_regions(g, lm, q, &sp);
    }
    if (cq > 0 && (o->kind == FL_LM_L || o->kind == FL_LM_T)) {
        fl_landmark_kind_t other = o->kind == FL_LM_L ? FL_LM_T : FL_LM_L;
        uint32_t cc = g->params.confuse_conf, s8 = cq;
        uint16_t scale;
        /* vision's low-confidence crossings are often of the other kind:
         * the possibility rises to 1 at confidence confuse_conf */
        if (cc > 0 && cc < 255u && o->confidence < 255u)
            s8 = o->confidence <= cc ? 255u
                                     : cq + ((255u - cq) * (255u - o->confidence)) / (255u - cc);
        scale = (uint16_t)(s8 * 257u);              /* <= 65535 */
        nk = fl_field_count_kind(f, other);
        for (i = 0; i < nk; i++) {
            const fl_landmark_t *lm = fl_field_nth_kind(f, other, i);
            fl_angle_t om;
            int k;
            if (lm == NULL)
                continue;
            sp.oriented = o->has_orientation;
            sp.om = 0;
            sp.orientation = o->orientation;
            sp.period = 65536;
            sp.scale_q16 = scale;
            if (!o->has_orientation) {
                landmark_regions(g, lm, q, &sp);
            } else if (other == FL_LM_L && lm->n_arms == 2) {
                for (k = 0; k < 2; k++) {
                    sp.om = lm->arm[k];
                    landmark_regions(g, lm, q, &sp);
                }
            } else if (other == FL_LM_T && fl_landmark_orientation(lm, &om)) {
                for (k = -1; k <= 1; k += 2) {
                    sp.om = fl_angle_wrap((int32_t)om + k * 8192);
                    landmark_regions(g, lm, q, &sp);
                }
            }
        }
    }
    if (cq > 0 && (o->kind == FL_LM_CORNER_C || o->kind == FL_LM_CORNER_TFIELD ||
                   o->kind == FL_LM_CORNER_TNET)) {
        /* seed 004's corner features: a C is often a T seen with one arm
         * too few, a T-field a T-net whose net was not seen, and the
         * other way round; each of the two other kinds' points at
         * confuse_q8 (no orientation: the corner path measures none) */
        static const fl_landmark_kind_t ck[3] = { FL_LM_CORNER_C, FL_LM_CORNER_TFIELD,
                                                  FL_LM_CORNER_TNET };
        int k;
        for (k = 0; k < 3; k++) {
            if (ck[k] == o->kind)
                continue;
            nk = fl_field_count_kind(f, ck[k]);
            for (i = 0; i < nk; i++) {
                const fl_landmark_t *lm = fl_field_nth_kind(f, ck[k], i);
                if (lm == NULL)
                    continue;
                sp.oriented = false;
                sp.om = 0;
                sp.orientation = 0;
                sp.period = 65536;
                sp.scale_q16 = (uint16_t)(cq * 257u);
                landmark_regions(g, lm, q, &sp);
            }
        }
    }
    return sp.n;
}

/* Offer region reg's ring to the live cells ix0..ix1 of row iy.
 * Scaling and overflow: content positions and landmarks within 20 m of
 * each other (config.h), so dx^2 + dy^2 < 2^30 in uint32; ring value Q16
 * from (rw - delta) * inv_rs < rs * inv_rs <= 65535 * 2^16. */
static void eval_cells(fl_fuzzy_t *g, const fl_fuzzy_region_t *reg,
                       const obsp_t *q, int iy, int ix0, int ix1)
{
    fl_fuzzy_acc_t *acc = g->scratch.upd.acc;
    const fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * g->nx];
    int32_t ddy0 = reg->ly_mm - (g->y0_mm + iy * FZ_CELL + FZ_HALF);
    int32_t ddx0 = reg->lx_mm - (g->x0_mm + FZ_HALF);
    /* d = floor(sqrt(s)) is outside the ring (|d - r| >= rw) iff s >= rout^2
     * or s < (rin + 1)^2 (rin >= 0): tested before the root (exact) */
    uint32_t s_out = (uint32_t)q->rout * (uint32_t)q->rout;
    uint32_t s_in = q->rin >= 0 ? (uint32_t)(q->rin + 1) * (uint32_t)(q->rin + 1) : 0u;
    int ix;
    if (q->rout >= 65536)
        s_out = UINT32_MAX;
    for (ix = ix0; ix <= ix1; ix++) {
        const fl_fuzzy_cell_t *c = &row[ix];
        int32_t ddx, ddy, d, delta;
        uint32_t m, s2;
        fl_angle_t head;
        fl_fuzzy_acc_t *a;
        if (c->height == 0)
            continue;
        ddx = ddx0 - ix * FZ_CELL - c->off_x_mm;
        ddy = ddy0 - c->off_y_mm;
        s2 = (uint32_t)(ddx * ddx) + (uint32_t)(ddy * ddy);
        if (s2 >= s_out || s2 < s_in)
            continue;
        d = (int32_t)fl_isqrt32(s2);
        delta = fz_iabs(d - q->r);
        if (delta >= q->rw)
            continue;
        m = delta <= q->rc ? 65535u : ((uint32_t)(q->rw - delta) * q->inv_rs) >> 16;
        if (q->no_bearing_heading) {
            head = reg->oriented ? reg->head_o : 0;
        } else if (reg->sector &&
                   -ddx * (int32_t)reg->ux_q15 - ddy * (int32_t)reg->uy_q15 < d * q->sector_cos_q15) {
            continue;                 /* outside the sector: agreement 0 */
        } else {
            head = fz_asub(fl_atan2(ddy, ddx), q->bearing);
            if (reg->oriented) {
                uint32_t agree = tpos(fz_iabs(fz_asub(head, reg->head_o)), q->ocore, q->oslope);
                m = (uint32_t)(((uint64_t)m * agree) >> 16);
            }
        }
        if (reg->scale_q16 < 65535u) {
            m = (m * reg->scale_q16) >> 16;
            if (!g->track_valid) {
                /* the other kind (confuse_q8) without a track: never a
                 * heading hypothesis of its own, only "a pose here stays
                 * this possible" (r3: the cell's own shape scaled): from
                 * ignorance the union of its heading with the observed
                 * kind's would widen and move the cells' headings */
                if (m > acc[ix].r3_q16)
                    acc[ix].r3_q16 = (uint16_t)m;
                continue;
            }
        }
        if (m == 0)
            continue;
        a = &acc[ix];
        if (a->r1_q16 == 0) {
            a->r1_q16 = (uint16_t)m;
            a->head1 = head;
        } else if (fz_iabs(fz_asub(head, a->head1)) <= q->hcore) {
            if (m > a->r1_q16) {      /* the same heading: no competitor */
                a->r1_q16 = (uint16_t)m;
                a->head1 = head;
            }
        } else if (a->r2_q16 != 0 && fz_iabs(fz_asub(head, a->head2)) <= q->hcore) {
            if (m > a->r2_q16) {
                a->r2_q16 = (uint16_t)m;
                a->head2 = head;
            }
            if (a->r2_q16 > a->r1_q16) {
                uint16_t tr = a->r1_q16;
                fl_angle_t th = a->head1;
                a->r1_q16 = a->r2_q16;
                a->head1 = a->head2;
                a->r2_q16 = tr;
                a->head2 = th;
            }
        } else if (m > a->r1_q16) {
            if (a->r2_q16 > a->r3_q16)
                a->r3_q16 = a->r2_q16;
            a->r2_q16 = a->r1_q16;
            a->head2 = a->head1;
            a->r1_q16 = (uint16_t)m;
            a->head1 = head;
        } else if (m > a->r2_q16) {
            if (a->r2_q16 > a->r3_q16)
                a->r3_q16 = a->r2_q16;
            a->r2_q16 = (uint16_t)m;
            a->head2 = head;
        } else if (m > a->r3_q16) {
            a->r3_q16 = (uint16_t)m;
        }
    }
}

/* Cells of row iy whose centre lies in [xa, xb] (mm), clamped to the grid. */
static void visit_interval(fl_fuzzy_t *g, const fl_fuzzy_region_t *reg,
                           const obsp_t *q, int iy, int32_t xa, int32_t xb)
{
    int32_t i0, i1;
    if (xa > xb)
        return;
    i0 = fl_floor_div(xa - g->x0_mm - FZ_HALF + FZ_CELL - 1, FZ_CELL);
    i1 = fl_floor_div(xb - g->x0_mm - FZ_HALF, FZ_CELL);
    if (i0 < g->row_lo[iy])            /* only where the row has live cells */
        i0 = g->row_lo[iy];
    if (i1 > g->row_hi[iy])
        i1 = g->row_hi[iy];
    if (i0 <= i1)
        eval_cells(g, reg, q, iy, (int)i0, (int)i1);
}

/* Scaling and overflow: q->rout <= 3 * 30000 mm so rout^2 < 2^33: the
 * squares are taken in uint64 and the roots with fl_isqrt64. */
static void visit_row(fl_fuzzy_t *g, const fl_fuzzy_region_t *reg,
                      const obsp_t *q, int iy)
{
    const int32_t m = (3 * FZ_CELL) / 4;   /* content may sit off-centre */
    int32_t cy = g->y0_mm + iy * FZ_CELL + FZ_HALF;
    int32_t ady, dyo, dyi, xo, xi, bx0, bx1;
    if (cy + m < reg->y0_mm || cy - m > reg->y1_mm)
        return;
    ady = fz_iabs(cy - reg->ly_mm);
    if (ady > q->rout + m)
        return;
    dyo = ady > m ? ady - m : 0;
    xo = (int32_t)fl_isqrt64((uint64_t)q->rout * (uint64_t)q->rout -
                             (uint64_t)dyo * (uint64_t)dyo) + m;
    dyi = ady + m;
    xi = -1;
    if (q->rin > dyi)
        xi = (int32_t)fl_isqrt64((uint64_t)q->rin * (uint64_t)q->rin -
                                 (uint64_t)dyi * (uint64_t)dyi) - m;
    bx0 = reg->x0_mm - m;
    bx1 = reg->x1_mm + m;
    if (xi <= 0) {
        int32_t a = reg->lx_mm - xo, b = reg->lx_mm + xo;
        visit_interval(g, reg, q, iy, a > bx0 ? a : bx0, b < bx1 ? b : bx1);
    } else {
        int32_t a = reg->lx_mm - xo, b = reg->lx_mm - xi;
        visit_interval(g, reg, q, iy, a > bx0 ? a : bx0, b < bx1 ? b : bx1);
        a = reg->lx_mm + xi;
        b = reg->lx_mm + xo;
        visit_interval(g, reg, q, iy, a > bx0 ? a : bx0, b < bx1 ? b : bx1);
    }
}

/* Scaling and overflow: range <= max_range_mm <= 30000; rc, rs = base +
 * r * q8 / 256 <= 5000 + 30000, times the ring scale tq in [1, 256]
 * (Q8, 256 = 1) < 2^24 in uint32, rounded back by 8; confidence Q0.8 -> bias Q0.8 -> Q16. */
static void obs_params(const fl_fuzzy_t *g, const fl_obs_t *o, obsp_t *q, uint32_t tq)
{
    const fl_fuzzy_params_t *p = &g->params;
    int32_t dmin, cell_ang;
    uint32_t conf = o->confidence, bmin = p->bias_min_q8;
    q->r = o->range_mm;
    q->rc = fz_clamp32(p->ring_base_mm, 0, 5000) +
            (int32_t)(((uint32_t)q->r * (p->ring_core_q8 > 256 ? 256u : p->ring_core_q8)) >> 8);
    q->rs = fz_clamp32(p->ring_slope_mm, 1, 5000) +
            (int32_t)(((uint32_t)q->r * (p->ring_slope_q8 > 256 ? 256u : p->ring_slope_q8)) >> 8);
    /* tracked: precise rings (rounded, the slope at least 1 mm) */
    q->rc = (int32_t)(((uint32_t)q->rc * tq + 128u) >> 8);
    q->rs = (int32_t)(((uint32_t)q->rs * tq + 128u) >> 8);
    if (q->rs < 1)
        q->rs = 1;
    q->rw = q->rc + q->rs;
    q->rin = q->r - q->rw;
    q->rout = q->r + q->rw;
    q->inv_rs = (uint32_t)((65535ull << 16) / (uint32_t)q->rs);
    q->bearing = o->bearing;
    dmin = q->rin > FZ_CELL ? q->rin : FZ_CELL;
    cell_ang = fl_atan2(FZ_HALF, dmin);
    q->hcore = fz_clamp32((int32_t)p->bearing_core + cell_ang, 0, FZ_HT);
    q->hslope = fz_clamp32((int32_t)p->bearing_slope + cell_ang, 0, FZ_HT);
    q->ocore = fz_clamp32(p->orient_core, 0, FZ_HT);
    q->oslope = fz_clamp32(p->orient_slope, 1, FZ_HT);
    q->no_bearing_heading = q->rin < FZ_CELL;
    {
        int32_t tol = q->ocore + q->oslope + SECTOR_MARGIN;
        q->sector_half = (fl_angle_t)(tol < 16384 ? tol : 16384);
        q->sector_cos_q15 = tol < 16384 ? fl_cos_q15(q->sector_half) : 0;
    }
    q->bias_q8 = (uint8_t)(255u - (conf * (255u - bmin)) / 255u);
    q->bias_q16 = (uint32_t)q->bias_q8 * 257u + (uint32_t)(q->bias_q8 >> 7);
    q->head_bias_q16 = (uint32_t)p->head_bias_q8 * 257u + (uint32_t)(p->head_bias_q8 >> 7);
}

/* The observation applied to one live cell c (acc: what the rings said
 * there), result in *out (may be c).  Cells outside every ring: product
 * with the outlier bias bP (same shape).  Ring cells: product with the
 * observation's trapezoid, outer envelope (fuzzy_trap.c), per heading
 * hypothesis, then the heading floors (widening only: still an envelope). */
typedef struct {
    const fl_fuzzy_t *g;
    const obsp_t *q;
    bool any_oriented;
} prodctx_t;

static void cell_product(const prodctx_t *x, const fl_fuzzy_acc_t *a,
                         const fl_fuzzy_cell_t *c, fl_fuzzy_cell_t *out)
{
    const fl_fuzzy_t *g = x->g;
    const obsp_t *q = x->q;
    bool any_oriented = x->any_oriented;
    fl_fuzzy_trap_t ct, st, et;
    int8_t ox = c->off_x_mm, oy = c->off_y_mm;
    int32_t hmin_core = fz_clamp32(g->params.head_min_core, 0, FZ_HT);
    int32_t hmin_slope = fz_clamp32(g->params.head_min_slope, 0, FZ_HT);
    if (a->r1_q16 == 0) {
        /* off every ring: x bP; only the other kind's ring (confuse_q8):
         * x rho(r3) >= bP, the cell's shape kept */
        uint32_t f8 = q->bias_q8;
        if (a->r3_q16 != 0)
            f8 = (rho(q, a->r3_q16) * 255u + 65535u) >> 16;
        *out = *c;
        out->height = fz_mul8_ceil(c->height, f8);
        out->bias = fz_mul8_ceil(c->bias, f8);
        return;
    }
    fl_fuzzy_trap_from_cell(c, &ct);
    st.centre = a->head1;
    if (q->no_bearing_heading) {
        st.core = any_oriented ? q->ocore : FZ_HT;
        st.slope = any_oriented ? q->oslope : 0;
    } else {
        st.core = q->hcore;
        st.slope = q->hslope;
    }
    /* position factor rho = bP + (1 - bP) r (outlier bias bP), heading
     * trapezoid with relative bias head_bias */
    st.height_q16 = rho(q, a->r1_q16);
    st.bias_q16 = rho_head(g, q, a->r1_q16);
    fl_fuzzy_trap_isect(&ct, &st, &et);
    if (a->r2_q16 != 0) {
        /* a second heading: C x (S1 u S2) = (C x S1) u (C x S2) */
        fl_fuzzy_trap_t s2 = st, e2, e1 = et;
        s2.centre = a->head2;
        s2.height_q16 = rho(q, a->r2_q16);
        s2.bias_q16 = rho_head(g, q, a->r2_q16);
        fl_fuzzy_trap_isect(&ct, &s2, &e2);
        fl_fuzzy_trap_union(&e1, &e2, &et);
    }
    if (a->r3_q16 != 0) {
        /* any further heading k: C x Sk <= C x rho(rk) (C's own shape
         * scaled), so the rest never widens nor flattens the cell */
        fl_fuzzy_trap_t e3 = ct, e1 = et;
        uint32_t r3 = rho(q, a->r3_q16);
        e3.height_q16 = (uint32_t)(((uint64_t)ct.height_q16 * r3 + 65535u) >> 16);
        e3.bias_q16 = (uint32_t)(((uint64_t)ct.bias_q16 * r3 + 65535u) >> 16);
        fl_fuzzy_trap_union(&e1, &e3, &et);
    }
    if (et.core < hmin_core) {                    /* widening: still >= */
        et.slope = et.slope + et.core > hmin_core ? et.slope + et.core - hmin_core : 0;
        et.core = hmin_core;
    }
    if (et.slope < hmin_slope)
        et.slope = hmin_slope;
    fl_fuzzy_trap_to_cell(&et, out);
    out->off_x_mm = ox;
    out->off_y_mm = oy;
}

/* Gating (robustness to false positives and confusions, which arrive at
 * several per second): while a mode is tracked, the observation is first
 * evaluated on the core of the tracked mode only (cells within mode_radius
 * of the tracked position with at least 3/4 of the highest height there):
 * its fit is the largest fraction of its height such a cell keeps (Q8).
 * Without a track the fit is 255.  Cost: the rows of that window only. */
static uint32_t mode_fit(fl_fuzzy_t *g, const obsp_t *q, int nreg, bool any_oriented)
{
    const fl_fuzzy_params_t *p = &g->params;
    int32_t R = fz_clamp32(p->mode_radius_mm, FZ_CELL, 2000);
    int ix0, ix1, iy0, iy1, ix, iy, ir;
    uint32_t best = 0, top = 0;
    prodctx_t x;
    if (!g->track_valid)
        return 255;
    x.g = g;
    x.q = q;
    x.any_oriented = any_oriented;
    fz_window(g, g->track_x_mm, g->track_y_mm, R, &ix0, &ix1, &iy0, &iy1);
    for (iy = iy0; iy <= iy1; iy++)
        for (ix = ix0; ix <= ix1; ix++)
            if (g->cell[(size_t)iy * g->nx + (size_t)ix].height > top)
                top = g->cell[(size_t)iy * g->nx + (size_t)ix].height;
    if (top == 0)
        return 0;
    for (iy = iy0; iy <= iy1; iy++) {
        fl_fuzzy_acc_t *acc = g->scratch.upd.acc;
        const fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * g->nx];
        memset(acc, 0, sizeof(fl_fuzzy_acc_t) * (size_t)g->nx);
        for (ir = 0; ir < nreg; ir++)
            visit_row(g, &g->scratch.upd.region[ir], q, iy);
        for (ix = ix0; ix <= ix1; ix++) {
            fl_fuzzy_cell_t e;
            uint32_t r;
            if (row[ix].height == 0 || 4u * row[ix].height < 3u * top)
                continue;                 /* only the mode's core */
            cell_product(&x, &acc[ix], &row[ix], &e);
            r = ((uint32_t)e.height * 255u) / row[ix].height;
            if (r > best)
                best = r;
        }
    }
    return best > 255u ? 255u : best;
}

bool fl_fuzzy_update_one(fl_fuzzy_t *g, const fl_obs_t *o)
{
    const fl_fuzzy_params_t *p;
    obsp_t q;
    int nreg, ir, iy, ix, nx, ny_upd;
    uint32_t maxh = 0, fit;
    bool any_oriented = false;
    prodctx_t x;
    if (!fz_ready(g))
        return false;
    p = &g->params;
    g->stats.updates = fz_sat_inc(g->stats.updates);
    if (o == NULL || o->confidence == 0 || (unsigned)o->kind >= (unsigned)FL_LM_KIND_COUNT ||
        o->range_mm < 0 || o->range_mm > fz_clamp32(p->max_range_mm, 100, 30000) ||
        (p->cross_max_mm > 0 && o->range_mm > p->cross_max_mm && o->kind != FL_LM_POST &&
         o->kind != FL_LM_BEACON && o->kind != FL_LM_CENTRE_CIRCLE && o->kind != FL_LM_NET) ||
        fl_field_count_kind(g->field, o->kind) == 0) {
        g->stats.obs_ignored = fz_sat_inc(g->stats.obs_ignored);
        return false;
    }
    obs_params(g, o, &q, 256u);       /* the wide rings: regions and gate */
    nreg = build_regions(g, o, &q);
    if (nreg == 0) {
        g->stats.obs_ignored = fz_sat_inc(g->stats.obs_ignored);
        return false;
    }
    for (ir = 0; ir < nreg; ir++)
        any_oriented = any_oriented || g->scratch.upd.region[ir].oriented;
    x.g = g;
    x.q = &q;
    x.any_oriented = any_oriented;
    nx = g->nx;
    /* gating: an observation that contradicts the tracked mode (fit below
     * gate_q8) is deferred, except every (gate_run + 1)-th of a run of
     * contradictions: persistent contradiction is how a kidnap shows */
    fit = mode_fit(g, &q, nreg, any_oriented);
    if (g->track_valid) {
        fz_update_consistency(g, fit);
        if (fit < p->gate_q8) {
            if (g->contra_run < UINT8_MAX)
                g->contra_run++;
            if (g->contra_rate_q8 < UINT16_MAX - 32u)
                g->contra_rate_q8 = (uint16_t)(g->contra_rate_q8 + 32u);
            if (fz_kidnapped(g))
                return false;
            if (g->contra_run % ((uint32_t)p->gate_run + 1u) != 0) {
                g->stats.obs_gated = fz_sat_inc(g->stats.obs_gated);
                return false;
            }
        } else {
            g->contra_run = 0;
        }
    }
    /* tracked: the update itself uses the precise rings (ring_track_q8;
     * the regions of the wide rings contain them, the gate above keeps
     * the wide rings so that deferral and kidnap detection do not depend
     * on it) */
    if (g->track_valid && p->ring_track_q8 < 256)
        obs_params(g, o, &q, (uint32_t)fz_clamp32(p->ring_track_q8, 1, 256));
    /* an exactly symmetric belief on a symmetric field: the first half of
     * the rows (and the middle row of an odd grid) is updated, the rest is
     * its mirror (symmetrize below would make it so anyway) */
    ny_upd = g->sym_exact ? (g->ny + 1) / 2 : g->ny;
    for (iy = 0; iy < ny_upd; iy++) {
        fl_fuzzy_acc_t *acc = g->scratch.upd.acc;
        fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * (size_t)nx];
        int lo = g->row_lo[iy], hi = g->row_hi[iy];
        if (lo > hi)
            continue;                  /* no live cell in this row */
        memset(&acc[lo], 0, sizeof(fl_fuzzy_acc_t) * (size_t)(hi - lo + 1));
        for (ir = 0; ir < nreg; ir++)
            visit_row(g, &g->scratch.upd.region[ir], &q, iy);
        for (ix = lo; ix <= hi; ix++) {
            fl_fuzzy_cell_t *c = &row[ix];
            if (c->height == 0)
                continue;
            cell_product(&x, &acc[ix], c, c);
            if (c->height > maxh)
                maxh = c->height;
        }
    }
    if (g->sym_exact) {
        fl_fuzzy_internal_mirror_copy(g);
    } else if (g->field->symmetric) {
        fl_fuzzy_internal_symmetrize(g);
        g->sym_exact = true;
    }
    g->stats.obs_used = fz_sat_inc(g->stats.obs_used);
    g->since_obs = 0;
    if (!g->track_valid)
        fz_update_consistency(g, maxh);
    fl_fuzzy_internal_normalize(g, maxh);
    return true;
}

uint16_t fl_fuzzy_update(fl_fuzzy_t *g, const fl_obs_list_t *obs)
{
    uint16_t i, n, used = 0;
    if (!fz_ready(g))
        return 0;
    if (obs == NULL) {
        g->stats.obs_ignored = fz_sat_inc(g->stats.obs_ignored);
        return 0;
    }
    n = obs->n > FL_OBS_MAX ? (uint16_t)FL_OBS_MAX : obs->n;
    for (i = 0; i < n; i++)
        if (fl_fuzzy_update_one(g, &obs->obs[i]))
            used++;
    return used;
}
