/*
 * fieldloc/upf.h - the unscented particle filter localizer (seed 003
 * section 2: van der Merwe, Doucet, de Freitas and Wan, "The Unscented
 * Particle Filter", NIPS 2000), in fixed point, on the Monte Carlo
 * filter's particle core (mcl.h fl_mcl_core_t).
 *
 * Each of a few particles (12 by default, seed 003's player) carries a
 * sampled pose, a weight, and a Gaussian: a UKF mean and its 3x3
 * covariance (ukf.h: mm^2, mm x binary angle, binary angle^2).  Per frame
 * (localizer.h order):
 *     predict   each particle's Gaussian through the odometry motion model
 *               by the unscented transform (fl_ukf_predict) with the
 *               process noise Q of the Monte Carlo filter's motion model
 *               (variance growing with the step); the sampled pose moved by
 *               the odometry alone (the transition prior's mean), Q summed
 *               since the last update (its covariance);
 *     update    per particle, each observation associated at the UKF mean
 *               as the Monte Carlo filter associates it, then a UKF
 *               measurement update (fl_ukf_update), sequentially; the new
 *               pose sampled from the posterior N(mean, P) (the proposal,
 *               fl_ukf_sample); its weight the Monte Carlo filter's
 *               likelihood p(z | x) at the sample (range/bearing Gaussians
 *               with the outlier floor) x the transition prior / the
 *               proposal (fl_ukf_gauss_nll_q8), as Q8 negative
 *               log-likelihoods accumulated since the last resampling;
 *               the UKF mean restarts at the sample (the particle is
 *               the sample with its covariance) at the next predict or
 *               update: until then it is the posterior mean, which the
 *               estimate uses (the sample's draw is noise to it);
 *     resample  (at the next update) low variance, when the
 *               effective sample size falls below ess_pct of the
 *               particles; with augmented MCL's injection (sensor
 *               resetting from the frame's observations, the best of
 *               seed_tries poses, fresh covariance init_sd_mm /
 *               init_sd_mdeg) as the Monte Carlo filter;
 *     estimate  the Monte Carlo filter's dominant cluster of the
 *               posterior means with the samples' weights; the spread
 *               that of the cluster's mixture (weighted particle
 *               covariances + the spread of the means); the
 *               mirror's weight; its own calibrated reliability.
 * Every covariance repair of the UKF steps is counted (stats.repairs).
 *
 * Memory (FL_UPF_MAX_PARTICLES = 12): per particle 8 B sample + 12 B mean
 * + 24 B covariance + 4 B log-weight (48 B); the core (landmark index,
 * reset observations, prior, track) 408 B; params 84 B, averages,
 * counters, the summed process noise: sizeof(fl_upf_t) is 1,192 B on
 * x86-64, within 1.2 KiB (printed and asserted by the upf suite).  Stack
 * below 2.4 KiB per call (make stack).  Cost (callgrind, `fieldloc bench
 * --loc-frames upf`, 12 particles, 5 observations): about 0.46 M
 * instructions per frame, 6.1 k per particle per observation (the UKF
 * measurement update, 4.9 k, is most of it).  No heap, no floating point.
 */
#ifndef FIELDLOC_UPF_H
#define FIELDLOC_UPF_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"
#include "fieldloc/mcl.h"
#include "fieldloc/ukf.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Parameters (fl_upf_params_default; sources in src/loc/upf.c).  mcl: the
 * Monte Carlo filter's (seed, n_particles 1..FL_UPF_MAX_PARTICLES, the
 * motion model as the process noise, the sensor model, augmentation,
 * estimate; jitter unused); then the unscented filter's own.
 */
typedef struct {
    fl_mcl_params_t mcl;
    uint16_t ess_pct;            /* resample when the effective sample size
                                    is below this % of the particles */
    uint16_t inject_resample_q16;/* ... or when the injection probability is
                                    at least this (65535: never) */
    uint16_t seed_tries;         /* under ignorance a particle is the best of
                                    this many sensor-reset poses (1..64) */
    uint16_t inject_tries;       /* ... an injected one while tracking */
    uint16_t init_sd_mm;         /* an injected or drawn particle's sd of x
                                    and y */
    uint16_t init_sd_mdeg;       /* ... of the heading (at most 60 deg) */
    uint16_t floor_sd_mm;        /* covariance floor: sd of x and y */
    uint16_t floor_sd_mdeg;      /* ... of the heading */
    uint16_t gate_q8;            /* an observation whose likelihood term at
                                    the UKF mean exceeds this (Q8 nats) is
                                    not used by the UKF update (an outlier
                                    for that particle; the weight's floor
                                    still counts it) */
    uint8_t prior_mode;          /* transition prior's covariance: 0 the
                                    summed process noise Q (van der Merwe
                                    et al.); 1 the particle's predicted
                                    covariance (its Gaussian as the prior) */
    uint16_t trans_q8;           /* weight of the transition prior / the
                                    proposal term (256 = 1, the method;
                                    0..256) */
} fl_upf_params_t;

typedef struct {
    fl_ukf_pose_t mean;
    fl_ukf_cov_t cov;
} fl_upf_gauss_t;

typedef struct {
    uint32_t predicts, updates, obs_used, obs_ignored, odo_rejected;
    uint32_t injected, kidnaps, mode_switches, resets;
    uint32_t reseeds, reseeds_refused;   /* fl_upf_reseed applied / refused */
    uint32_t resamples;          /* resamplings (effective size too low) */
    uint32_t ukf_updates;        /* UKF measurement updates applied */
    uint32_t gated;              /* (particle, observation) pairs gated */
    uint32_t sample_fail;        /* a posterior that did not factor (the
                                    sample is the mean; also counted in
                                    repairs.not_pd by the repair) */
    fl_ukf_repairs_t repairs;    /* every covariance repair */
} fl_upf_stats_t;

typedef struct {
    fl_mcl_core_t core;          /* core.field NULL: not initialized */
    fl_upf_params_t params;
    uint16_t n;
    bool resample_due;           /* effective size low: resample at the next
                                    predict or update */
    bool ignorance;
    bool drawn;                  /* the means are this update's posterior
                                    means (the estimate's); the next predict
                                    or update restarts them at the samples */
    uint16_t since_obs;
    fl_mcl_particle_t part[FL_UPF_MAX_PARTICLES];  /* samples and weights */
    fl_upf_gauss_t g[FL_UPF_MAX_PARTICLES];        /* UKF means, covariances */
    bool search[FL_UPF_MAX_PARTICLES];  /* descends from a guess (ignorance,
                                           a sensor reset, a penalty or a
                                           re-seed without heading), not
                                           from a stated pose: in a frame
                                           that informs its UKF nothing it
                                           still draws from its Gaussian (a
                                           local search); a tracked one from
                                           the process noise */
    uint32_t lw[FL_UPF_MAX_PARTICLES];  /* accumulated negative log-weights,
                                           Q8 nats above the lightest */
    fl_ukf_cov_t q_acc;          /* process noise since the last update */
    fl_mcl_aug_t aug;
    uint32_t est_density;
    fl_upf_stats_t stats;
} fl_upf_t;

void fl_upf_params_default(fl_upf_params_t *p);
void fl_upf_params_vision(fl_upf_params_t *p, bool lowres);
void fl_upf_params_lowres(fl_upf_params_t *p);
fl_status_t fl_upf_params_check(const fl_upf_params_t *p);

/* As fl_mcl_init (FL_ERR_NULL, FL_ERR_RANGE, FL_ERR_SIZE); total ignorance. */
fl_status_t fl_upf_init(fl_upf_t *s, const fl_field_t *field, const fl_upf_params_t *params);
void fl_upf_clear(fl_upf_t *s);

void fl_upf_predict(fl_upf_t *s, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta);
uint16_t fl_upf_update(fl_upf_t *s, const fl_obs_list_t *obs);
/* The estimate in the Monte Carlo filter's form (sd from the mixture). */
bool fl_upf_estimate(fl_upf_t *s, fl_mcl_estimate_t *out);

void fl_upf_reset_ignorance(fl_upf_t *s);
void fl_upf_reset_pose(fl_upf_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                       int32_t pos_unc_mm, fl_angle_t heading_unc);
void fl_upf_reset_penalty(fl_upf_t *s, int32_t x_mm, int32_t pos_unc_mm,
                          fl_angle_t heading_unc);
void fl_upf_set_prior_half(fl_upf_t *s, int half);
void fl_upf_set_prior_pose(fl_upf_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                           int32_t radius_mm);
void fl_upf_clear_prior(fl_upf_t *s);

/* Re-seeding, as fl_mcl_reseed; each particle's Gaussian restarts at its
 * draw with the draw's covariance (diagonal: the report's sd, the heading
 * sd drawn with; with headings evenly spaced, half their spacing). */
fl_status_t fl_upf_reseed(fl_upf_t *s, const fl_obs_report_t *r);
/* The mixture's spread (its particles' means and covariances, weighted),
 * as fl_mcl_spread_mm. */
uint32_t fl_upf_spread_mm(const fl_upf_t *s);

/* The core, every sample within the box, every covariance valid
 * (fl_ukf_cov_valid with the params' floors), the log-weights bounded. */
bool fl_upf_check(const fl_upf_t *s);
uint32_t fl_upf_possibility_q16(const fl_upf_t *s, int32_t x_mm, int32_t y_mm,
                                fl_angle_t heading);
/* The floors the UKF steps keep (from the params). */
void fl_upf_limits(const fl_upf_t *s, fl_ukf_limits_t *lim);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_UPF_H */
