/*
 * src/loc/upf_int.h - internals shared by the unscented particle filter's
 * files (upf.c: parameters, init, resets, priors, check; upf_filter.c:
 * predict, update, resampling; upf_estimate.c: the estimate).  It uses
 * the Monte Carlo filter's particle core (pcore.h).  Not a public header.
 */
#ifndef FIELDLOC_UPF_INT_H
#define FIELDLOC_UPF_INT_H

#include "fieldloc/upf.h"
#include "pcore.h"

/* Largest accumulated negative log-weight, Q8 nats (64 nats: e^-64 is
 * nothing next to the heaviest particle). */
#define UPF_LW_MAX (64u * 256u)

static inline bool upf_ready(const fl_upf_t *s)
{
    return s != NULL && s->core.field != NULL;
}

static inline uint32_t upf_sat_inc(uint32_t v)
{
    return v == UINT32_MAX ? v : v + 1u;
}

/* Millidegrees as a binary angle magnitude (65536 per turn). */
static inline int32_t upf_mdeg(uint32_t mdeg)
{
    return (int32_t)(((int64_t)mdeg * 65536) / 360000);
}

void fl_upf_internal_diag(const fl_upf_t *s, int32_t sd_mm, int32_t sd_h, fl_ukf_cov_t *p);
void fl_upf_internal_fresh_cov(const fl_upf_t *s, fl_ukf_cov_t *p);
void fl_upf_internal_restart(fl_upf_t *s, uint16_t i, const fl_ukf_cov_t *p);

#endif /* FIELDLOC_UPF_INT_H */
