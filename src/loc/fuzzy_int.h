/*
 * src/loc/fuzzy_int.h - internals shared by src/loc/fuzzy.c and src/loc/fuzzy_update.c
 * (not installed; not part of the API).
 */
#ifndef FIELDLOC_FUZZY_INT_H
#define FIELDLOC_FUZZY_INT_H

#include "fieldloc/fuzzy.h"

#define FZ_CELL FL_FUZZY_CELL_MM
#define FZ_HALF (FL_FUZZY_CELL_MM / 2)

/* Rescale so that the highest cell is 255 (max_q8 = current highest, from
 * the caller's pass); zero cells below params.min_height_q8; an empty grid
 * (max 0) becomes total ignorance (counted in stats.empty_resets). */
void fl_fuzzy_internal_normalize(fl_fuzzy_t *g, uint32_t max_q8);
/* Recompute row_lo / row_hi from the cells (one pass). */
void fl_fuzzy_internal_rows(fl_fuzzy_t *g);
/* Symmetric field: every cell i of the first half (row-major order) is
 * copied, mirrored, onto its mirror cell n-1-i (fuzzy_update.c). */
void fl_fuzzy_internal_mirror_copy(fl_fuzzy_t *g);
/* Total ignorance without counting an explicit reset; clears the track. */
void fl_fuzzy_internal_ignorance(fl_fuzzy_t *g);

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

#endif /* FIELDLOC_FUZZY_INT_H */
