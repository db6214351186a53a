/*
 * src/fuzzy_int.h - internals shared by src/fuzzy.c and src/fuzzy_update.c
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

#endif /* FIELDLOC_FUZZY_INT_H */
