/*
 * host_tests/loc_walk.h - a short feature-level walk through one catalogue
 * localizer (the localizer.h interface), shared by the particle filters'
 * suites: own-half prior, penalties told, the estimate hashed every step.
 */
#ifndef FIELDLOC_TEST_LOC_WALK_H
#define FIELDLOC_TEST_LOC_WALK_H

#include "fieldloc/localizer.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    uint32_t steps;              /* steps run */
    uint32_t obs_used;           /* observations the localizer applied */
    uint32_t hash;               /* of every estimate's x, y, heading */
    double rmse_mm;              /* position error after the first 5 s */
} t_loc_walk_t;

/* Walks fixtures/walks/WALK.walk for at most `steps` steps with parameter
 * "seed" = seed; `valid` (may be NULL) is checked with fl_loc_check every
 * 64 steps and at the end.  Returns the state (the caller frees it), NULL
 * after a failure (recorded). */
void *t_loc_walk(const char *loc_name, const char *walk, int32_t seed, uint32_t steps,
                 bool (*valid)(const void *state), t_loc_walk_t *out);
/* The same with the simulator's vision set (tools/world/sim.h
 * sim_scenario_t.vision: SIM_VISION_LTX as t_loc_walk, _CORNERS seed
 * 004's corner features, _BOTH); kinds_seen (may be NULL; FL_LM_KIND_COUNT
 * entries) counts the observations given to the localizer by kind. */
void *t_loc_walk_vision(const char *loc_name, const char *walk, int32_t seed, uint32_t steps,
                        int vision, bool (*valid)(const void *state), t_loc_walk_t *out,
                        uint32_t *kinds_seen);

#endif
