/*
 * src/loc/loc_adapter.h - what every localizer's adapter (loc_*.c) may
 * share: the counters its filter keeps under localizer.h's names, and the
 * empty grid of a belief that is not one (defined in loc_mcl.c).  Knows
 * no filter's types.  Not a public header.
 */
#ifndef FIELDLOC_LOC_ADAPTER_H
#define FIELDLOC_LOC_ADAPTER_H

#include "fieldloc/localizer.h"

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

/* The start of every adapter's stats: *out zeroed (a localizer's missing
 * counters read 0); true when there is a state to copy from. */
static inline bool fl_loc_internal_stats_zero(const void *state, fl_loc_stats_t *out)
{
    if (out == NULL)
        return false;
    memset(out, 0, sizeof *out);
    return state != NULL;
}

/* The counters every filter keeps under the same names (fl_mcl_stats_t,
 * fl_upf_stats_t, fl_fuzzy_stats_t, fl_relmap_stats_t: src points to one)
 * into *out; the adapter copies those only its filter keeps. */
#define FL_LOC_STATS_COMMON(out, src)                       \
    do {                                                    \
        (out)->predicts = (src)->predicts;                  \
        (out)->updates = (src)->updates;                    \
        (out)->obs_used = (src)->obs_used;                  \
        (out)->obs_ignored = (src)->obs_ignored;            \
        (out)->odo_rejected = (src)->odo_rejected;          \
        (out)->kidnaps = (src)->kidnaps;                    \
        (out)->mode_switches = (src)->mode_switches;        \
        (out)->resets = (src)->resets;                      \
        (out)->reseeds = (src)->reseeds;                    \
        (out)->reseeds_refused = (src)->reseeds_refused;    \
    } while (0)

/* A belief that is not a grid (particles): false, *out zeroed. */
bool fl_loc_internal_no_grid(const void *state, fl_loc_grid_t *out);
bool fl_loc_internal_no_cell(const void *state, int ix, int iy, fl_loc_cell_t *out);

#endif /* FIELDLOC_LOC_ADAPTER_H */
