/*
 * src/loc/report_int.h - what the coach's assignment and the player's pick
 * share (report.h): the normalised squared distance of a report from an
 * estimate, so that both gate alike.
 */
#ifndef FIELDLOC_REPORT_INT_H
#define FIELDLOC_REPORT_INT_H

#include "fieldloc/report.h"

/* Saturating counter increment, and REPORT_COUNT(stats, member): increment a
 * counter of a stats block the caller may have left NULL. */
static inline uint32_t fl_report_sat_inc(uint32_t v)
{
    return v < UINT32_MAX ? v + 1u : v;
}

#define REPORT_COUNT(st, f)                            \
    do {                                               \
        if ((st) != NULL)                              \
            (st)->f = fl_report_sat_inc((st)->f);      \
    } while (0)

/* An estimate's spread is clamped to this in the cost (a lost player's
 * spread on an SPL carpet is about 3,000 mm; UINT32_MAX, uninitialized,
 * must not make every distance free). */
#define FL_REPORT_SPREAD_CAP_MM 8000

/* Squared distance, each axis clamped to +-2^24 mm (so no product
 * overflows whatever the caller passes). */
int64_t fl_report_internal_dist2(int32_t ax, int32_t ay, int32_t bx, int32_t by);

/* 256 x d2 / (spread^2 / 2 + sd^2), rounded, saturating at UINT32_MAX. */
uint32_t fl_report_internal_cost_q8(int64_t d2, uint32_t spread_mm, int32_t sd_mm);

#endif /* FIELDLOC_REPORT_INT_H */
