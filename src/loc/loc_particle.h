/*
 * src/loc/loc_particle.h - what the particle localizers' adapters share
 * (defined in loc_mcl.c, used by loc_upf.c): the estimate in the
 * interface's form and a sample from a particle; with what every adapter
 * shares (loc_adapter.h).  Not a public header.
 */
#ifndef FIELDLOC_LOC_PARTICLE_H
#define FIELDLOC_LOC_PARTICLE_H

#include "fieldloc/localizer.h"
#include "fieldloc/mcl.h"
#include "loc_adapter.h"

/* localizer.h's estimate from the Monte Carlo filter's form (state from
 * tracking, ignorance and the mirror; localized from the reliability). */
void fl_loc_internal_from_mcl(const fl_mcl_estimate_t *e, fl_loc_estimate_t *out);
/* A sample's fields from a particle; in_mode when the core tracks a mode
 * and the particle is within cluster_mm of it and 90 deg of its heading. */
void fl_loc_internal_sample(const fl_mcl_core_t *c, int32_t cluster_mm,
                            const fl_mcl_particle_t *p, fl_loc_sample_t *out);

#endif /* FIELDLOC_LOC_PARTICLE_H */
