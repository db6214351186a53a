/*
 * fieldloc/ukf.h - the unscented Kalman filter step of one particle of the
 * unscented particle filter (upf.h), in fixed point: a pose mean and its
 * 3x3 covariance, predicted through the odometry motion model and updated
 * by one range/bearing observation of a known map point (Julier and
 * Uhlmann's unscented transform as van der Merwe et al., "The Unscented
 * Particle Filter", NIPS 2000, use it per particle).  Building blocks,
 * public so that the tests can hold them against a double reference.
 *
 * Units (the state's fixed-point format):
 *   mean   x_mm, y_mm: int32 millimetres; heading: binary angle
 *          (fl_angle_t, 65536 = one turn, wraps).
 *   cov    six int32 of the symmetric 3x3 matrix over (x, y, heading):
 *          xx, yy in mm^2; xy in mm^2; xt, yt in mm x angle unit; tt in
 *          angle unit^2 (angle unit = 1/65536 turn).  Headroom: variances
 *          are capped at FL_UKF_VAR_MM2_MAX (sd 20 m: a 10 m field twice
 *          over) and FL_UKF_VAR_ANG2_MAX (sd 180 deg: any heading), so
 *          every product of two standard deviations fits int32; covariance
 *          terms are kept within the Cauchy-Schwarz bound of their
 *          variances.  Intermediate products are int64.
 * Every function is total: NULL or out-of-range input gives a status (or
 * false) and leaves its outputs valid (a mean within +-FL_UKF_POS_MAX_MM
 * and a symmetric positive definite covariance).  No heap, no floating
 * point.  Algorithms, parameters and precision: src/loc/ukf.c.
 */
#ifndef FIELDLOC_UKF_H
#define FIELDLOC_UKF_H

#include "fieldloc/common.h"
#include "fieldloc/fixed.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FL_UKF_VAR_MM2_MAX  400000000     /* (20,000 mm)^2 */
#define FL_UKF_VAR_ANG2_MAX 1073741824    /* (32,768 units = 180 deg)^2 */
/* The box of the mean and of the map points (x and y within +-1 km: any
 * carpet with room to spare); a mean beyond it is clamped onto it. */
#define FL_UKF_POS_MAX_MM   1000000
/* Range standard deviations above this are taken as this. */
#define FL_UKF_SD_RANGE_MAX_MM 65535

typedef struct {
    int32_t x_mm, y_mm;
    fl_angle_t heading;
} fl_ukf_pose_t;

typedef struct {
    int32_t xx, xy, xt, yy, yt, tt;
} fl_ukf_cov_t;

/* Lower-triangular Cholesky factor L (P = L L^T), in Q8 of the state's
 * units: l11 (mm), l21 (mm), l31 (angle unit), l22 (mm), l32, l33 (angle
 * unit), each x 256. */
typedef struct {
    int32_t l11, l21, l31, l22, l32, l33;
} fl_ukf_chol_t;

/* Floors on the diagonal and caps, used by every step that writes a
 * covariance (a step that had to apply one counts a repair).  The floors
 * also bound the conditional variances (the Cholesky pivots: y given x,
 * heading given x and y), so a valid covariance is positive definite with
 * a margin.  Values outside [1, cap] are taken as the nearest of them; a
 * NULL limits pointer means floors of 1. */
typedef struct {
    int32_t var_min_mm2;         /* floor of xx and yy (> 0) */
    int32_t var_min_ang2;        /* floor of tt (> 0) */
} fl_ukf_limits_t;

/* What a step had to repair to keep the covariance symmetric positive
 * definite (counted by the caller; never silent). */
typedef struct {
    uint32_t floors;             /* a diagonal raised to its floor */
    uint32_t caps;               /* a variance or covariance clamped */
    uint32_t not_pd;             /* a Cholesky pivot fell below its floor:
                                    the diagonal entry was raised by the
                                    deficit (modified Cholesky), or, when
                                    that would pass a cap, the matrix was
                                    replaced by its diagonal */
} fl_ukf_repairs_t;

/* Cholesky factor of an SPD matrix (each entry within 1 LSB of the exact
 * factor rounded).  FL_ERR_RANGE when p is not positive definite at the
 * factor's resolution or an entry is beyond the caps (l is then the factor
 * of p's diagonal, its negative entries taken as 0); FL_ERR_NULL for
 * NULL. */
fl_status_t fl_ukf_chol3(const fl_ukf_cov_t *p, fl_ukf_chol_t *l);

/* Inverse of a symmetric 2x2 matrix [a b; b c] (int64 entries), scaled:
 * inv = [ia ib; ib ic] / det with det = a c - b^2 returned through *det.
 * false when det <= 0 or an entry is beyond +-INT32_MAX (det would not
 * fit; outputs zeroed, NULL outputs allowed then).  Exact: no rounding. */
bool fl_ukf_inv2(int64_t a, int64_t b, int64_t c, int64_t *ia, int64_t *ib,
                 int64_t *ic, int64_t *det);

/* Symmetric-positive-definite repair in place: caps, the Cauchy-Schwarz
 * bound, the diagonal floors, and the diagonal alone when the matrix does
 * not factor.  Returns true when nothing had to change. */
bool fl_ukf_cov_repair(fl_ukf_cov_t *p, const fl_ukf_limits_t *lim,
                       fl_ukf_repairs_t *rep);
/* true when p is within the caps and floors and factors with every pivot
 * (conditional variance) at least its floor: SPD with a margin. */
bool fl_ukf_cov_valid(const fl_ukf_cov_t *p, const fl_ukf_limits_t *lim);

/* Predict: the sigma points of (m, p) moved by the odometry (dx_mm, dy_mm
 * in the robot frame at each sigma point's heading, then dtheta), their
 * mean and covariance, plus the process noise q (field frame).  FL_OK, or
 * FL_ERR_RANGE for odometry beyond +-FL_OBS_MAX_RANGE_MM (nothing moved),
 * FL_ERR_NULL for a NULL m or p.  q (no noise), lim (floors 1) and rep
 * (repairs not counted) may be NULL.  An input mean beyond the box or an
 * input covariance that is not valid is clamped / repaired first (the
 * repairs counted), whatever the status. */
fl_status_t fl_ukf_predict(fl_ukf_pose_t *m, fl_ukf_cov_t *p, int32_t dx_mm,
                           int32_t dy_mm, fl_angle_t dtheta, const fl_ukf_cov_t *q,
                           const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep);

/* Update by one observation of the map point (lx_mm, ly_mm) at range_mm and
 * bearing (robot frame) with standard deviations sd_range_mm and
 * sd_bearing: the sigma points through the range/bearing function, the
 * predicted measurement (bearing averaged about the central point's,
 * differences wrapped), innovation covariance S (2x2), cross-covariance,
 * gain, mean and covariance update.  *nll_q8 (may be NULL): the
 * innovation's negative log-likelihood under N(0, S), Q8 nats (256 = 1
 * nat), 1/2 ln det S included (S in mm^2 and angle unit^2; constants
 * common to every particle dropped), saturated.  FL_OK; FL_ERR_RANGE for a
 * range outside [0, FL_OBS_MAX_RANGE_MM], a non-positive sd or a map point
 * beyond the box (nothing updated, *nll_q8 = UINT32_MAX); FL_ERR_NULL for a
 * NULL m or p.  lim and rep may be NULL (as for fl_ukf_predict); the input
 * is clamped and repaired first the same way. */
fl_status_t fl_ukf_update(fl_ukf_pose_t *m, fl_ukf_cov_t *p, int32_t lx_mm,
                          int32_t ly_mm, int32_t range_mm, fl_angle_t bearing,
                          int32_t sd_range_mm, fl_angle_t sd_bearing,
                          const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep,
                          uint32_t *nll_q8);

/* The same two steps with their inputs in a struct: six arguments, so a
 * caller's frame stays static (a call with more arguments than registers
 * puts them on the caller's stack, which `make stack` cannot bound on
 * every target).  fl_ukf_predict and fl_ukf_update call these. */
typedef struct {
    int32_t dx_mm, dy_mm;        /* robot frame */
    fl_angle_t dtheta;
} fl_ukf_odo_t;

typedef struct {
    int32_t lx_mm, ly_mm;        /* the map point */
    int32_t range_mm;
    fl_angle_t bearing;          /* robot frame */
    fl_angle_t sd_bearing;
    int32_t sd_range_mm;
} fl_ukf_obs_t;

fl_status_t fl_ukf_predict_odo(fl_ukf_pose_t *m, fl_ukf_cov_t *p, const fl_ukf_odo_t *odo,
                               const fl_ukf_cov_t *q, const fl_ukf_limits_t *lim,
                               fl_ukf_repairs_t *rep);
fl_status_t fl_ukf_update_obs(fl_ukf_pose_t *m, fl_ukf_cov_t *p, const fl_ukf_obs_t *obs,
                              const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep,
                              uint32_t *nll_q8);

/* Negative log density of x under N(m, p), Q8 nats, 1/2 ln det p included
 * (same convention as fl_ukf_update), heading difference wrapped;
 * saturated; UINT32_MAX for NULL or a p that does not factor. */
uint32_t fl_ukf_gauss_nll_q8(const fl_ukf_pose_t *m, const fl_ukf_cov_t *p,
                             const fl_ukf_pose_t *x);

/* A draw from N(m, p) (fl_mcl_gauss_q12 deviates through the Cholesky
 * factor, from *rng), the position clamped onto the box.  false (out = m,
 * clamped) when p does not factor or rng is NULL. */
bool fl_ukf_sample(const fl_ukf_pose_t *m, const fl_ukf_cov_t *p, uint32_t *rng,
                   fl_ukf_pose_t *out);

/* ln(x) in Q8 for x >= 1 (x = 0: 0), within 1 LSB: for the log
 * determinants. */
int32_t fl_ukf_ln_q8(uint64_t x);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_UKF_H */
