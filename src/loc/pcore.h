/*
 * src/loc/pcore.h - the particle core (mcl.h fl_mcl_core_t) and the
 * functions of the Monte Carlo filter's files that take it (src/loc/mcl.c,
 * mcl_update.c, mcl_resample.c, mcl_estimate.c), shared by the Monte Carlo
 * filter (mcl_int.h) and the unscented particle filter (upf_int.h).  Not a
 * public header.
 */
#ifndef FIELDLOC_PCORE_H
#define FIELDLOC_PCORE_H

#include "fieldloc/mcl.h"

/* mcl.c */
/* Index the field's landmarks, the carpet box (carpet + margin), the
 * random generator from seed; the prior none.  FL_ERR_SIZE, FL_ERR_RANGE
 * as fl_mcl_init (c then zeroed, field NULL). */
fl_status_t fl_mcl_internal_core_init(fl_mcl_core_t *c, const fl_field_t *field,
                                      int32_t margin_mm, int32_t seed);
bool fl_mcl_internal_allowed(const fl_mcl_core_t *c, int32_t x, int32_t y, fl_angle_t h);
void fl_mcl_internal_uniform(fl_mcl_core_t *c, fl_mcl_particle_t *p);
void fl_mcl_internal_clamp(const fl_mcl_core_t *c, int32_t *x, int32_t *y);
void fl_mcl_internal_drop_prior(fl_mcl_core_t *c);

/* A pose with its uncertainty, to draw particles around (passed by
 * pointer: six arguments at most, so no call pushes arguments on the stack
 * and every frame stays static for `make stack`). */
typedef struct {
    int32_t x, y, pos_unc;
    fl_angle_t h, heading_unc;
} fl_mcl_paint_t;

static inline void mcl_paint(fl_mcl_paint_t *c, int32_t x, int32_t y, fl_angle_t h,
                             int32_t pos_unc, fl_angle_t heading_unc)
{
    c->x = x;
    c->y = y;
    c->h = h;
    c->pos_unc = pos_unc;
    c->heading_unc = heading_unc;
}

/* Resets and priors on n particles p of a core (the caller resets its own
 * weights, averages and counters): uniform over the allowed region;
 * around a pose (sd pos_unc / 2, heading_unc / 2; the pose tracked); at
 * the penalty spots x (the placement's half as the prior unless x = 0);
 * a prior half or pose (pose->pos_unc the radius), which draws the
 * particles again from its region under ignorance and, on a symmetric
 * field, mirrors those outside the own half. */
void fl_mcl_internal_core_ignorance(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n);
void fl_mcl_internal_core_pose(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                               const fl_mcl_paint_t *pose);
void fl_mcl_internal_core_penalty(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                  const fl_mcl_paint_t *pose);
void fl_mcl_internal_core_prior_half(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                     bool ignorance, int half);
void fl_mcl_internal_core_prior_pose(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                     bool ignorance, const fl_mcl_paint_t *pose);
void fl_mcl_internal_core_clear_prior(fl_mcl_core_t *c);
/* A re-seed from an observer's report (obs.h; seed 003 section 3.4): the
 * paint it draws from: the foot with the report's sd, the estimate's
 * heading with sd max(pi/8, the estimate's heading sd) (pose->pos_unc and
 * heading_unc are twice the sds: core_pose draws with half of them).
 * False when the estimate tells no heading (ignorance, or a heading sd of
 * 90 deg or more): the draw then takes any heading. */
bool fl_mcl_internal_reseed_paint(const fl_obs_report_t *r, const fl_mcl_estimate_t *e,
                                  fl_mcl_paint_t *pose);
/* core_pose with that paint (the foot tracked); with !heading_known the
 * headings evenly spaced over the turn from a random start instead (n
 * headings 360/n deg apart) and no mode tracked. */
void fl_mcl_internal_core_reseed(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                 const fl_mcl_paint_t *pose, bool heading_known);
/* The belief's spread (localizer.h spread_mm): sqrt of the weighted
 * variance of x plus y of n points about their weighted mean, each point
 * with its own further variance var[i] (mm^2; NULL: none); while a mode is
 * tracked on a symmetric field, each point counted at the nearer of itself
 * and its mirror to the track (the mirror is the half's question, not the
 * spread's).  Equal weights when they sum to 0. */
uint32_t fl_mcl_internal_spread(const fl_mcl_core_t *c, const fl_mcl_particle_t *p, uint16_t n,
                                const uint32_t *var);
/* The core's tables and the particles within the box. */
bool fl_mcl_internal_core_check(const fl_mcl_core_t *c, const fl_mcl_particle_t *p, uint16_t n);

/* mcl_update.c */
uint32_t fl_mcl_internal_exp_q16(uint32_t nll_q8);

/* The sensor model, per observation (fl_mcl_internal_prepare: usable?
 * and its constants) and per pose (fl_mcl_internal_obs_nll: the Gaussian
 * part q in Q8 nats, the associated landmark in at->best), and the outlier
 * floor: fl_mcl_internal_mixture(tab, q) = -ln((1 - eps) e^-q + eps) from
 * a table that fl_mcl_internal_mixture_table fills (FL_MCL_MIX_N
 * entries).  The unscented particle filter's p(z | x) is this one. */
typedef struct {
    const fl_obs_t *o;
    int32_t ox, oy;              /* robot-frame vector, mm */
    int32_t cb, sb;              /* its direction, Q15 */
    int32_t sd_r, sd_a;          /* along and across sds, mm */
    uint64_t k_r, k_a;           /* 128 * 2^32 / sd^2 */
    uint8_t cand[FL_MCL_MAX_LANDMARKS];  /* candidate landmarks (field ids) */
    int16_t cx[FL_MCL_MAX_LANDMARKS], cy[FL_MCL_MAX_LANDMARKS];  /* their
                                                                    positions */
    uint8_t n_cand;
} fl_mcl_obs_c_t;

/* The pose an observation is weighed at: position, cos and sin (Q15) of
 * the heading, the heading; best: out, the associated landmark. */
typedef struct {
    int32_t x, y, c, s;
    fl_angle_t h;
    int best;
} fl_mcl_at_t;

#define FL_MCL_MIX_N 65
bool fl_mcl_internal_prepare(const fl_mcl_core_t *pc, const fl_mcl_params_t *p,
                             const fl_obs_t *o, fl_mcl_obs_c_t *c);
uint32_t fl_mcl_internal_obs_nll(const fl_mcl_core_t *pc, const fl_mcl_params_t *p,
                                 const fl_mcl_obs_c_t *c, fl_mcl_at_t *at);
void fl_mcl_internal_mixture_table(uint16_t eps_q16, uint16_t *tab);
uint32_t fl_mcl_internal_mixture(const uint16_t *tab, uint32_t q);
/* w_avg of the frame's negative log-likelihoods nll[0..n) of `used`
 * observations, the averages and the injection probability; true when
 * that probability calls a kidnap (the prior dropped; the caller counts). */
bool fl_mcl_internal_augment(fl_mcl_core_t *c, const fl_mcl_params_t *p, fl_mcl_aug_t *s,
                             const uint32_t *nll, uint16_t n, uint16_t used);
/* Keep an applied observation for sensor resetting (the first
 * FL_MCL_RESET_OBS of a frame; the caller sets n_reset 0 first). */
void fl_mcl_internal_keep_reset_obs(fl_mcl_core_t *c, const fl_obs_t *o);

/* mcl_resample.c */
/* The motion model's noise sds of one predict call (see there). */
void fl_mcl_internal_motion_sd(const fl_mcl_params_t *p, int32_t dx, int32_t dy, fl_angle_t dth,
                               int32_t *sd_xy, int32_t *sd_h);
/* (x, y) moved by the robot-frame odometry (dx, dy) at heading h (rounded). */
void fl_mcl_internal_move(int32_t *x, int32_t *y, fl_angle_t h, int32_t dx_mm, int32_t dy_mm);
/* The tracked mode follows the odometry. */
void fl_mcl_internal_track_move(fl_mcl_core_t *k, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta);
/* The same on a particle core with the sensor model's parameters p (not
 * counted): true when the pose came from an observation. */
bool fl_mcl_internal_core_inject(fl_mcl_core_t *c, const fl_mcl_params_t *p,
                                 fl_mcl_particle_t *out);

/* mcl_estimate.c: the estimate of a set of weighted particles (the MCL's
 * live buffer, or the unscented particle filter's samples). */
typedef struct {
    fl_mcl_core_t *core;
    const fl_mcl_params_t *params;   /* cluster_mm, switch_q8 */
    const fl_mcl_particle_t *p;
    uint16_t n;
} fl_mcl_set_t;


/* Under total ignorance: the centre of the prior's region, its spread; no
 * mode tracked. */
void fl_mcl_internal_ignorance_pose(fl_mcl_core_t *c, uint16_t since_obs, fl_mcl_estimate_t *out);
/* Steps 1-5 of the estimate (mcl_estimate.c): pose, spread, share, score,
 * mirror, tracking; the track follows, a switch drops the prior (counted
 * by the caller).  out zeroed by the caller; since_obs and the
 * reliability are the caller's. */
bool fl_mcl_internal_cluster(const fl_mcl_set_t *s, fl_mcl_estimate_t *out);
/* Piecewise-linear calibration of the raw score through n knots (raw
 * score, reliability), then the not-tracking and mirror factors.  The
 * tables are arrays in the struct (one pointer argument: the call stays
 * within six arguments however the compiler splits it). */
#define FL_MCL_CAL_MAX 16
typedef struct {
    int n;
    uint16_t raw[FL_MCL_CAL_MAX], rel[FL_MCL_CAL_MAX];
} fl_mcl_cal_t;
uint16_t fl_mcl_internal_calibrate(const fl_mcl_estimate_t *e, const fl_mcl_cal_t *cal);
uint64_t fl_mcl_internal_density(const fl_mcl_set_t *s, int32_t x, int32_t y, fl_angle_t h);
uint32_t fl_mcl_internal_possibility(const fl_mcl_set_t *s, bool ignorance, uint32_t est_density,
                                     int32_t x_mm, int32_t y_mm, fl_angle_t heading);

#endif /* FIELDLOC_PCORE_H */
