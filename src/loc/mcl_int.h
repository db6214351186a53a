/*
 * src/loc/mcl_int.h - internals shared by the Monte Carlo localizer's files
 * (mcl.c: parameters, init, resets, sampling; mcl_update.c: the sensor
 * model and the likelihood averages; mcl_resample.c: motion and
 * resampling; mcl_estimate.c: the estimate).  Not a public header.
 */
#ifndef FIELDLOC_MCL_INT_H
#define FIELDLOC_MCL_INT_H

#include "fieldloc/mcl.h"
#include "pcore.h"

/* Largest negative log-likelihood of one term, Q8 nats (16 nats: beyond
 * it every likelihood is at the outlier floor). */
#define MCL_NLL_MAX (16 * 256)

static inline int32_t mcl_clamp(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* floor(v / 2^n) without shifting a negative value (bit-identical on
 * every target: no result depends on how a compiler shifts signed values). */
static inline int32_t mcl_asr(int64_t v, unsigned n)
{
    return v >= 0 ? (int32_t)(v >> n)
                  : -(int32_t)((uint64_t)((-v) + (((int64_t)1 << n) - 1)) >> n);
}

static inline bool mcl_ready(const fl_mcl_t *s)
{
    return s != NULL && s->core.field != NULL;
}

static inline uint32_t mcl_sat_inc(uint32_t v)
{
    return v == UINT32_MAX ? v : v + 1u;
}

static inline fl_mcl_particle_t *mcl_live(fl_mcl_t *s)
{
    return s->buf[s->cur & 1u];
}

static inline const fl_mcl_particle_t *mcl_live_c(const fl_mcl_t *s)
{
    return s->buf[s->cur & 1u];
}

/* Uniform in [0, n) (n >= 1): the high word of a 32 x 32 bit product. */
static inline uint32_t mcl_below(uint32_t *rng, uint32_t n)
{
    return (uint32_t)(((uint64_t)fl_mcl_rand(rng) * n) >> 32);
}

/* sd x a standard deviate, rounded (sd any non-negative int32 below 2^19). */
static inline int32_t mcl_noise(uint32_t *rng, int32_t sd)
{
    if (sd <= 0)
        return 0;
    return mcl_asr((int64_t)fl_mcl_gauss_q12(rng) * sd + 2048, 12);
}

/* |a| of a binary angle difference, 0..32768. */
static inline int32_t mcl_absang(fl_angle_t a)
{
    return a < 0 ? -(int32_t)a : (int32_t)a;
}

/* mcl_resample.c: the MCL's own resampling and counted injection */
void fl_mcl_internal_resample(fl_mcl_t *s);
/* One injected particle: sensor-reset from a kept observation, else
 * uniform over the allowed region (counted). */
void fl_mcl_internal_inject(fl_mcl_t *s, fl_mcl_particle_t *out);

/* the MCL's live buffer as a particle set (mcl_estimate.c) */
static inline void mcl_set_of(fl_mcl_t *s, fl_mcl_set_t *set)
{
    set->core = &s->core;
    set->params = &s->params;
    set->p = mcl_live_c(s);
    set->n = s->n;
}

#endif /* FIELDLOC_MCL_INT_H */
