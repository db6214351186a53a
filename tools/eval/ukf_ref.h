/*
 * tools/eval/ukf_ref.h - the UKF step of src/loc/ukf*.c in double precision,
 * written from the equations (not from the fixed-point code), for the tests
 * (host_tests/test_ukf.c) and `fieldloc ukf-check`.  Same parameters
 * (alpha = 1, beta = 2, kappa = 0: points m and m +- sqrt(3) L_j, mean
 * weights 0 and 1/6, covariance weights 2 and 1/6), no floors or caps.
 *
 * Units: positions mm; angles in binary-angle units (65536 per turn) but
 * real-valued; covariances in mm^2, mm x unit, unit^2.  Bearings of the
 * sigma points are wrapped to (-32768, 32768] about the central point's;
 * the predicted bearing is the central one plus the mean wrapped deviation;
 * the innovation's bearing is wrapped.
 */
#ifndef FL_TOOLS_UKF_REF_H
#define FL_TOOLS_UKF_REF_H

#include <stdint.h>

typedef struct {
    double x, y, t;
} ukf_ref_pose_t;

/* l = the lower Cholesky factor of p; 0 when p is not positive definite. */
int ukf_ref_chol(double p[3][3], double l[3][3]);

/* In place; q may be NULL.  0 when p does not factor. */
int ukf_ref_predict(ukf_ref_pose_t *m, double p[3][3], double dx, double dy, double dth,
                    double q[3][3]);

/* In place; *nll_q8: (nu' S^-1 nu + ln det S) / 2 in Q8 nats.  0 when p
 * does not factor. */
int ukf_ref_update(ukf_ref_pose_t *m, double p[3][3], double lx, double ly, double range,
                   double bearing, double sd_r, double sd_b, double *nll_q8);

/* a wrapped to (-32768, 32768]. */
double ukf_ref_wrap(double a);

/* The six distinct entries (xx, xy, xt, yy, yt, tt) <-> the full matrix. */
void ukf_ref_from6(const int32_t c[6], double p[3][3]);

/* Errors of a fixed-point result against the reference: the mean's
 * distance (mm), its heading difference (deg), and the covariance's largest
 * relative error beyond the rounding of the output to integers,
 * max(0, |P_ij - R_ij| - 1/2) / sqrt(R_ii R_jj). */
typedef struct {
    double mean_mm, heading_deg, cov_rel;
    double cov_rel_raw;          /* the same with the rounding included */
} ukf_ref_err_t;
void ukf_ref_compare(const ukf_ref_pose_t *ref, double rp[3][3], int32_t x_mm,
                     int32_t y_mm, int32_t heading, const int32_t c[6], ukf_ref_err_t *e);

/* A deterministic generator (xorshift64*) and the random inputs. */
typedef struct {
    uint64_t s;
} ukf_ref_rng_t;
double ukf_ref_unif(ukf_ref_rng_t *r);               /* [0, 1) */
double ukf_ref_gauss(ukf_ref_rng_t *r);              /* N(0, 1) */
/* A random SPD covariance (six entries, rounded): standard deviations
 * log-uniform in [sd_lo_mm, sd_hi_mm] (x, y) and [sd_lo_t, sd_hi_t] units
 * (heading), correlations from a random unit-row factor (any in (-1, 1),
 * bounded by rho_max in magnitude). */
void ukf_ref_random_cov(ukf_ref_rng_t *r, double sd_lo_mm, double sd_hi_mm, double sd_lo_t,
                        double sd_hi_t, double rho_max, int32_t c[6]);

#endif
