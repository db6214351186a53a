/*
 * fieldloc/mcl.h - augmented Monte Carlo localization in fixed point
 * (seed 000 section 4: Fox et al.'s particle filter with Thrun et al.'s
 * augmentation, sensor resetting after Lenser and Veloso, low-variance
 * resampling with seed 000's average-weight step).
 *
 * The belief is a set of n weighted particles (x_mm, y_mm, heading) on the
 * carpet.  Per frame (localizer.h order):
 *     predict   each particle moves by the odometry, rotated by its own
 *               heading, plus independent Gaussian noise in x, y and
 *               rotation whose variance grows with the step (so that
 *               splitting a motion into more calls adds the same noise);
 *     update    each observation is placed in the field from the particle
 *               and associated with the nearest map landmark of its kind
 *               (and colour, side); the per-observation likelihood is the
 *               product of zero-mean Gaussians of the range difference and
 *               the bearing difference (optionally of the association
 *               certainty and the crossing orientation), mixed with a
 *               uniform outlier term; integer negative log-likelihoods
 *               (Q8 nats: 256 = 1 nat) summed over the observations, then
 *               per-frame renormalised to uint16 weights (heaviest 65535);
 *               w_slow / w_fast follow the mean geometric-mean likelihood;
 *     resample  (at the next predict or update, so that the estimate sees
 *               the weights) low-variance resampling, each new particle
 *               injected with probability max(0, 1 - w_fast / w_slow)
 *               from one observed feature (sensor resetting), uniformly
 *               over the allowed region when nothing was observed;
 *     estimate  the weighted mean of the dominant cluster (coarse bins,
 *               then a local weighted mean; never the mean of two mirror
 *               modes), its spread, the mirror's weight, a calibrated
 *               reliability.
 * No libm, no heap, no floating point; the random generator (xorshift32)
 * is in the state, seeded from params.seed at init: the same seed, inputs
 * and build give the same particles on every target.
 *
 * Memory (FL_MCL_MAX_PARTICLES = 256): particles 8 B each, double-buffered
 * (16 B per particle = 4,096 B), per-particle update scratch 8 B (the
 * negative log-likelihood and the heading's cos and sin: 2,048 B),
 * landmark tables 264 B, the rest (params, prior, track, averages, the
 * frame's reset observations, counters) about 300 B: sizeof(fl_mcl_t) is
 * 6,688 B on x86-64 (printed by the mcl suite), below 24 B per particle
 * + 1 KiB.  Stack below 1 KiB per call.
 * Cost: predict O(n); update O(n x observations x landmarks of the kind);
 * resample O(n); estimate O(n) (a few passes).  Measured by callgrind.
 */
#ifndef FIELDLOC_MCL_H
#define FIELDLOC_MCL_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Map landmarks the filter indexes (every catalogue field has at most 33);
 * init refuses a field with more (FL_ERR_SIZE). */
#define FL_MCL_MAX_LANDMARKS 64
/* Observations of one frame kept for sensor resetting (the first ones of
 * the frame that were applied). */
#define FL_MCL_RESET_OBS 6

/*
 * Parameters (fl_mcl_params_default; sources beside each default in
 * src/loc/mcl.c).  Units in the names: _mm millimetres, _pct percent,
 * _mdeg millidegrees, _q16 Q0.16 fractions (65536 = 1), _q8 Q0.8.
 */
typedef struct {
    int32_t seed;                /* random generator seed, used at init;
                                    0..INT32_MAX */
    uint16_t n_particles;        /* particles in use, 1..FL_MCL_MAX_PARTICLES
                                    (a change takes effect at the next
                                    resampling) */
    /* motion model: variance of x and y (each) and of the rotation per
     * predict call, growing with the step */
    uint16_t odo_trans_pct;      /* sd of x and y over a 1 m step, % of 1 m:
                                    sd = sqrt(pct^2/1e4 * step_mm * 1000) */
    uint16_t odo_rot_pct;        /* sd of the rotation over a 1 rad turn,
                                    % of 1 rad (same square-root law) */
    uint16_t odo_rot_mdeg_per_m; /* further sd of the rotation over 1 m
                                    walked (square-root law), mdeg */
    int32_t odo_max_mm;          /* a call with |dx| or |dy| beyond this is
                                    rejected and counted */
    uint16_t jitter_mm;          /* sd of x and y added to each resampled
                                    particle (keeps duplicates apart) */
    uint16_t jitter_mdeg;        /* sd of the heading added likewise */
    int32_t margin_mm;           /* particles stay within the carpet plus
                                    this margin */
    /* sensor model */
    uint16_t range_pct;          /* sd of the range, % of the range */
    uint16_t range_base_mm;      /* ... plus this (near observations) */
    uint16_t bearing_mdeg;       /* sd of the bearing */
    uint16_t orient_mdeg;        /* sd of a crossing's orientation; 0: the
                                    orientation is not used */
    uint16_t assoc_q8;           /* sd of the association certainty term
                                    (Q8: 256 = 1; the term is d1/d2, the
                                    nearest over the second-nearest
                                    landmark's distance); 0: not used */
    uint16_t outlier_q16;        /* weight of the uniform term of each
                                    observation's likelihood (the floor) */
    uint8_t corner_any;          /* 1 (mcl's default): a C, T-field or
                                    T-net observation (seed 004's corner
                                    features) is associated with the
                                    nearest corner feature of any of the
                                    three kinds: the image stage's typing
                                    errors cost nothing, the positions
                                    still count; 0 (upf's default): the
                                    observed kind only */
    int32_t max_range_mm;        /* observations farther are ignored */
    int32_t cross_max_mm;        /* L/T/X crossings farther are ignored
                                    (0: no limit) */
    /* augmented MCL */
    uint16_t alpha_slow_q16;     /* long-term average's rate */
    uint16_t alpha_fast_q16;     /* short-term average's rate */
    uint16_t inject_max_q16;     /* cap on the injection probability */
    uint16_t inject_min_q16;     /* injection probability at least this
                                    while observations arrive (sensor
                                    resetting: a pose that the averages
                                    cannot tell from the current one, e.g.
                                    the mirror on a field whose goals
                                    differ only in colour, is still
                                    challenged) */
    uint16_t kidnap_q16;         /* an injection probability at or above
                                    this means a kidnap: prior and track
                                    dropped, counted */
    /* estimate */
    int32_t cluster_mm;          /* radius of the dominant cluster */
    uint8_t switch_q8;           /* the tracked cluster is kept while its
                                    weight is at least this share of the
                                    heaviest cluster's */
} fl_mcl_params_t;

/* One particle: 8 bytes. */
typedef struct {
    int16_t x_mm, y_mm;          /* field frame (the box keeps them within
                                    +-32767) */
    fl_angle_t heading;
    uint16_t weight;             /* this frame's weight, heaviest 65535 */
} fl_mcl_particle_t;

/* One observation kept for sensor resetting. */
typedef struct {
    uint8_t kind, color, side, pad;
    int32_t range_mm;
    fl_angle_t bearing;
} fl_mcl_reset_obs_t;

typedef enum {
    FL_MCL_PRIOR_NONE = 0,
    FL_MCL_PRIOR_HALF = 1,       /* the robot is in half sign(half) * x > 0 */
    FL_MCL_PRIOR_POSE = 2        /* within radius_mm of a pose, heading
                                    within 90 deg of it */
} fl_mcl_prior_kind_t;

typedef struct {
    uint32_t predicts, updates, obs_used, obs_ignored, odo_rejected;
    uint32_t injected, kidnaps, mode_switches, resets;
    uint32_t reseeds, reseeds_refused;   /* fl_mcl_reseed applied / refused */
} fl_mcl_stats_t;

/* The particle core: what the Monte Carlo filter and the unscented
 * particle filter (upf.h) share, with the functions of src/loc/mcl*.c that
 * take it: the map's landmark index and fl_mcl_core_associate, the carpet
 * box, the prior and its allowed region, the tracked mode, the frame's
 * sensor-reset observations and the random generator. */
typedef struct {
    const fl_field_t *field;     /* NULL: not initialized */
    uint32_t rng;                /* xorshift32 state, never 0 */
    bool half_known;             /* the game told the half (prior, reset) */
    bool track_valid;
    uint8_t lm_index[FL_MCL_MAX_LANDMARKS];   /* landmark ids by kind */
    uint8_t kind_start[FL_LM_KIND_COUNT + 1]; /* kind k: lm_index[start[k]
                                                 .. start[k+1]) */
    fl_angle_t lm_orient[FL_MCL_MAX_LANDMARKS]; /* by field index
                                                   (fl_field_all_at) */
    uint8_t lm_orient_mod[FL_MCL_MAX_LANDMARKS];/* 0: none; 1: mod 360,
                                                   2: mod 180, 4: mod 90 */
    int32_t half_x_mm, half_y_mm;        /* carpet */
    int32_t box_x_mm, box_y_mm;          /* carpet plus margin */
    fl_mcl_prior_kind_t prior;
    int8_t prior_half;
    int32_t prior_x_mm, prior_y_mm, prior_radius_mm;
    fl_angle_t prior_heading;
    int32_t track_x_mm, track_y_mm;
    fl_angle_t track_heading;
    uint16_t n_reset;                    /* reset observations kept */
    fl_mcl_reset_obs_t reset_obs[FL_MCL_RESET_OBS];
} fl_mcl_core_t;

/* Augmented MCL's likelihood averages (shared with upf.h). */
typedef struct {
    uint32_t w_slow_q24, w_fast_q24;     /* averages of the likelihood */
    uint16_t inject_q16;                 /* injection probability at the
                                            next resampling */
} fl_mcl_aug_t;

typedef struct {
    fl_mcl_core_t core;          /* core.field NULL: not initialized */
    fl_mcl_params_t params;
    uint16_t n;                  /* particles in buf[cur] */
    uint8_t cur;                 /* the live buffer */
    bool weighted;               /* weights of an update not yet resampled */
    bool ignorance;              /* no observation applied since the last
                                    reset to ignorance */
    bool jitter_due;             /* resampled since the last motion: the
                                    next predict adds the jitter */
    fl_mcl_particle_t buf[2][FL_MCL_MAX_PARTICLES];
    uint32_t nll[FL_MCL_MAX_PARTICLES];  /* update scratch, Q8 nats */
    int16_t trig[FL_MCL_MAX_PARTICLES][2];  /* update scratch: cos, sin of
                                               each particle's heading */
    fl_mcl_aug_t aug;
    uint16_t since_obs;
    uint32_t est_density;                /* kernel density at the last
                                            estimate (possibility's peak) */
    fl_mcl_stats_t stats;
} fl_mcl_t;

/* The estimate (localizer.h fl_loc_estimate_t is filled from it). */
typedef struct {
    int32_t x_mm, y_mm;
    fl_angle_t heading;
    uint16_t reliability_q16;    /* calibrated (localizer.h contract) */
    uint16_t score_q16;          /* raw: cluster share x compactness */
    uint16_t share_q16;          /* cluster weight / total weight */
    uint16_t mode_particles;
    bool switched, tracking, ignorance;
    uint16_t sd_x_mm, sd_y_mm;
    int32_t cov_xy_mm2;
    fl_angle_t sd_heading;
    uint16_t mirror_q16;
    uint16_t since_obs;
} fl_mcl_estimate_t;

void fl_mcl_params_default(fl_mcl_params_t *p);
/* Observations from fl_vision_frame (NAO camera, lowres false; AIBO
 * lowres true). */
void fl_mcl_params_vision(fl_mcl_params_t *p, bool lowres);
/* The camera-dependent part of the vision preset (AIBO). */
void fl_mcl_params_lowres(fl_mcl_params_t *p);
fl_status_t fl_mcl_params_check(const fl_mcl_params_t *p);

/* params NULL: defaults.  FL_ERR_NULL (no field: the state is left
 * empty), FL_ERR_RANGE (bad params, or a carpet beyond +-30 m),
 * FL_ERR_SIZE (a field with more than FL_MCL_MAX_LANDMARKS landmarks).
 * Starts in total ignorance (particles uniform over the carpet). */
fl_status_t fl_mcl_init(fl_mcl_t *s, const fl_field_t *field,
                        const fl_mcl_params_t *params);
/* The empty state that init leaves after an error. */
void fl_mcl_clear(fl_mcl_t *s);

void fl_mcl_predict(fl_mcl_t *s, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta);
/* The number of observations applied. */
uint16_t fl_mcl_update(fl_mcl_t *s, const fl_obs_list_t *obs);
bool fl_mcl_estimate(fl_mcl_t *s, fl_mcl_estimate_t *out);

/* Resets and priors, as the fuzzy grid has them (fuzzy.h). */
void fl_mcl_reset_ignorance(fl_mcl_t *s);
void fl_mcl_reset_pose(fl_mcl_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                       int32_t pos_unc_mm, fl_angle_t heading_unc);
void fl_mcl_reset_penalty(fl_mcl_t *s, int32_t x_mm, int32_t pos_unc_mm,
                          fl_angle_t heading_unc);
void fl_mcl_set_prior_half(fl_mcl_t *s, int half);
void fl_mcl_set_prior_pose(fl_mcl_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                           int32_t radius_mm);
void fl_mcl_clear_prior(fl_mcl_t *s);

/* Re-seeding from an observer's report (obs.h; seed 003 section 3.4):
 * every particle drawn again from N(foot, report sd) in position and
 * N(the current estimate's heading, max(pi/8, its heading sd)) in heading
 * (when the estimate tells none: n headings evenly spaced over the turn
 * from a random start, no mode tracked), weights equal, the foot
 * tracked, as fl_mcl_reset_pose does with that uncertainty (the prior
 * kept).  FL_OK; FL_ERR_STATE (uninitialized); fl_obs_report_check's
 * refusals (counted in stats.reseeds_refused, the state unchanged). */
fl_status_t fl_mcl_reseed(fl_mcl_t *s, const fl_obs_report_t *r);
/* How far the particles have spread (localizer.h spread_mm), mm;
 * UINT32_MAX when uninitialized. */
uint32_t fl_mcl_spread_mm(const fl_mcl_t *s);

bool fl_mcl_check(const fl_mcl_t *s);
uint32_t fl_mcl_possibility_q16(const fl_mcl_t *s, int32_t x_mm, int32_t y_mm,
                                fl_angle_t heading);

/* ---- building blocks (exposed for the tests) ---------------------------- */

/* xorshift32 (Marsaglia 2003): the next 32 random bits. */
uint32_t fl_mcl_rand(uint32_t *rng);
/* A standard normal deviate in Q12 (4096 = 1 sd): the inverse normal CDF
 * by table with linear interpolation, from 17 random bits (|z| <= 4.48). */
int32_t fl_mcl_gauss_q12(uint32_t *rng);
/* Low-variance resampling (seed 000 Algorithm 4 with the average weight as
 * the step, exactly in integers): out[m] = the index i whose cumulative
 * weight interval [C_i, C_i + w_i) holds r + m * W / n_out, W the total
 * weight, r in [0, W / n_out).  Returns false for W = 0. */
bool fl_mcl_lowvar_pick(const fl_mcl_particle_t *p, uint16_t n_in, uint16_t *out,
                        uint16_t n_out, uint32_t *rng);
/* The nearest map landmark of the observation's kind (and colour and side
 * when the observation has them) to the field point (fx, fy): its field
 * index (fl_field_all_at: landmarks, then seed 004's features), -1 when
 * none matches; *d1 / *d2 the squared distances to it and
 * to the second nearest (UINT32_MAX when none). */
int fl_mcl_associate(const fl_mcl_t *s, const fl_obs_t *o, int32_t fx, int32_t fy,
                     uint32_t *d1, uint32_t *d2);
/* The same on a particle core (the unscented particle filter's). */
int fl_mcl_core_associate(const fl_mcl_core_t *c, const fl_obs_t *o, int32_t fx, int32_t fy,
                          uint32_t *d1, uint32_t *d2);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_MCL_H */
