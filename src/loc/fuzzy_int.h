/*
 * src/loc/fuzzy_int.h - internals shared by the files of the fuzzy position
 * grid, src/loc/fuzzy*.c (not installed; not part of the API).  Small
 * helpers of the per-cell loops are static inline here, so that every hot
 * loop is compiled with its helpers in one translation unit.
 */
#ifndef FIELDLOC_FUZZY_INT_H
#define FIELDLOC_FUZZY_INT_H

#include "fieldloc/fuzzy.h"

#define FZ_CELL FL_FUZZY_CELL_MM
#define FZ_HALF (FL_FUZZY_CELL_MM / 2)
#define FZ_HT 32768           /* half a turn, binary angle */

/* Rescale so that the highest cell is 255 (max_q8 = current highest, from
 * the caller's pass); zero cells below params.min_height_q8; an empty grid
 * (max 0) becomes total ignorance (counted in stats.empty_resets). */
void fl_fuzzy_internal_normalize(fl_fuzzy_t *g, uint32_t max_q8);
/* Recompute row_lo / row_hi from the cells (one pass). */
void fl_fuzzy_internal_rows(fl_fuzzy_t *g);
/* Symmetric field: every cell i of the first half (row-major order) is
 * copied, mirrored, onto its mirror cell n-1-i. */
void fl_fuzzy_internal_mirror_copy(fl_fuzzy_t *g);
/* Symmetric field: each cell and its mirror get their union. */
void fl_fuzzy_internal_symmetrize(fl_fuzzy_t *g);
/* Total ignorance without counting an explicit reset; clears the track. */
void fl_fuzzy_internal_ignorance(fl_fuzzy_t *g);

static inline bool fz_ready(const fl_fuzzy_t *g)
{
    return g != NULL && g->field != NULL && g->nx > 0 && g->ny > 0;
}

static inline int32_t fz_iabs(int32_t v)
{
    return v < 0 ? -v : v;   /* callers: |v| <= 2^20 */
}

static inline int32_t fz_clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* Field coordinates of the centre of column ix / row iy. */
static inline int32_t fz_centre_x(const fl_fuzzy_t *g, int ix)
{
    return g->x0_mm + ix * FZ_CELL + FZ_HALF;
}

static inline int32_t fz_centre_y(const fl_fuzzy_t *g, int iy)
{
    return g->y0_mm + iy * FZ_CELL + FZ_HALF;
}

/* fl_angle_wrap / fl_angle_sub of fixed.c, inlined for the per-cell loops
 * (same arithmetic, same results). */
static inline fl_angle_t fz_wrap16(int32_t a)
{
    uint32_t u = (uint32_t)a & 0xFFFFu;
    return (fl_angle_t)(u >= 0x8000u ? (int32_t)u - 65536 : (int32_t)u);
}

static inline fl_angle_t fz_asub(fl_angle_t a, fl_angle_t b)
{
    return fz_wrap16((int32_t)a - (int32_t)b);
}

static inline uint32_t fz_sat_inc(uint32_t v)
{
    return v < UINT32_MAX ? v + 1u : v;
}

/* Q0.8 product, rounded up: ceil(a * b / 255). */
static inline uint8_t fz_mul8_ceil(uint32_t a, uint32_t b)
{
    return (uint8_t)((a * b + 254u) / 255u);
}

/* Cells of the square window of half-side r_mm around field point (x, y),
 * clipped to the grid: columns ix0..ix1, rows iy0..iy1 (floor division, so
 * no double-width cell at the grid origin). */
static inline void fz_window(const fl_fuzzy_t *g, int32_t x_mm, int32_t y_mm, int32_t r_mm,
                             int *ix0, int *ix1, int *iy0, int *iy1)
{
    *ix0 = fl_floor_div(x_mm - r_mm - g->x0_mm, FZ_CELL);
    *ix1 = fl_floor_div(x_mm + r_mm - g->x0_mm, FZ_CELL);
    *iy0 = fl_floor_div(y_mm - r_mm - g->y0_mm, FZ_CELL);
    *iy1 = fl_floor_div(y_mm + r_mm - g->y0_mm, FZ_CELL);
    if (*ix0 < 0)
        *ix0 = 0;
    if (*iy0 < 0)
        *iy0 = 0;
    if (*ix1 > g->nx - 1)
        *ix1 = g->nx - 1;
    if (*iy1 > g->ny - 1)
        *iy1 = g->ny - 1;
}

/* Consistency: low-pass of how well observations fit (Q8 fit in, Q16
 * state): while tracking, the fit on the tracked mode (mode_fit), else the
 * peak the observation left before normalization.  Collapsing while a mode
 * is tracked, with contradictions arriving at kidnap_rate_q8 or more per
 * frame (predict call, low-passed over about 8 frames: false positives, a
 * fraction per frame while the robot sees nothing real, must not do it;
 * real observations after a kidnap come several per frame), means the
 * robot is not where the belief says (kidnap): reset to ignorance and drop
 * the prior, counted. */
static inline void fz_update_consistency(fl_fuzzy_t *g, uint32_t fit_q8)
{
    const fl_fuzzy_params_t *p = &g->params;
    int32_t cons = (int32_t)g->consistency_q16;
    cons += ((int32_t)(fit_q8 * 257u) - cons) >> (p->cons_shift > 8 ? 8 : p->cons_shift);
    g->consistency_q16 = (uint16_t)fz_clamp32(cons, 0, 65535);
}

static inline bool fz_kidnapped(fl_fuzzy_t *g)
{
    if (g->track_valid && g->consistency_q16 < g->params.kidnap_q16 &&
        g->contra_rate_q8 >= g->params.kidnap_rate_q8) {
        /* lost: the belief and the prior no longer hold */
        g->stats.kidnaps = fz_sat_inc(g->stats.kidnaps);
        fl_fuzzy_internal_ignorance(g);
        g->prior.kind = FL_FUZZY_PRIOR_NONE;
        g->half_known = false;
        return true;
    }
    return false;
}

static inline uint32_t fz_grid_max(const fl_fuzzy_t *g)
{
    size_t i, n = (size_t)g->nx * g->ny;
    uint32_t m = 0;
    for (i = 0; i < n; i++)
        if (g->cell[i].height > m)
            m = g->cell[i].height;
    return m;
}

#endif /* FIELDLOC_FUZZY_INT_H */
