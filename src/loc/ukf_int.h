/*
 * src/loc/ukf_int.h - internals shared by the UKF step's files (ukf.c: the
 * factor, repairs, densities and draws; ukf_step.c: predict and update).
 * Not a public header.  Every shift of a signed value goes through the
 * helpers below (magnitude and sign apart), so no result depends on how a
 * compiler shifts negative numbers.
 */
#ifndef FIELDLOC_UKF_INT_H
#define FIELDLOC_UKF_INT_H

#include "fieldloc/ukf.h"

/* The Cholesky factor in Q16 of the state's units, with its pivots before
 * the square roots (Q32 of the squared units): the conditional variances
 * of x, of y given x, of the heading given x and y.  fail: 0, or the first
 * pivot (1..3) that is not positive, or whose row has an entry beyond the
 * caps (pivots from a failed one on that could not be computed are
 * UKF_PIVOT_BAD). */
typedef struct {
    int64_t l11, l21, l31, l22, l32, l33;
    int64_t piv[3];
    int fail;
} ukf_fac_t;

#define UKF_PIVOT_BAD (-((int64_t)1 << 62))
#define UKF_P32 ((int64_t)1 << 32)
#define UKF_LN2_Q24 11629080              /* round(ln 2 2^24) */

static inline uint64_t ukf_abs64(int64_t v)
{
    return v >= 0 ? (uint64_t)v : (uint64_t)0 - (uint64_t)v;
}

static inline int64_t ukf_signed(uint64_t mag, bool neg)
{
    return neg ? -(int64_t)mag : (int64_t)mag;     /* mag < 2^63 */
}

/* v / 2^n rounded to nearest, ties away from zero (n in 1..62, |v| < 2^63). */
static inline int64_t ukf_rsr(int64_t v, unsigned n)
{
    return ukf_signed((ukf_abs64(v) + ((uint64_t)1 << (n - 1))) >> n, v < 0);
}

/* floor(v / 2^n) (n in 1..62). */
static inline int64_t ukf_asr(int64_t v, unsigned n)
{
    return v >= 0 ? (int64_t)((uint64_t)v >> n)
                  : -(int64_t)((ukf_abs64(v) + (((uint64_t)1 << n) - 1)) >> n);
}

/* n / d rounded to nearest, ties away from zero, for d > 0 (|n| < 2^63). */
static inline int64_t ukf_div(int64_t n, int64_t d)
{
    uint64_t ud = (uint64_t)d;
    return ukf_signed((ukf_abs64(n) + ud / 2u) / ud, n < 0);
}

/* Index of the top set bit of x (x >= 1), by halving. */
static inline unsigned ukf_topbit(uint64_t x)
{
    unsigned k = 0;
    if (x >> 32) { x >>= 32; k += 32; }
    if (x >> 16) { x >>= 16; k += 16; }
    if (x >> 8) { x >>= 8; k += 8; }
    if (x >> 4) { x >>= 4; k += 4; }
    if (x >> 2) { x >>= 2; k += 2; }
    if (x >> 1) k += 1;
    return k;
}

static inline int64_t ukf_clamp64(int64_t v, int64_t lo, int64_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* round(sqrt(v)) for any v (0 for v <= 0): s = floor(sqrt v), plus one
 * when v > s^2 + s (sqrt v >= s + 1/2 for integers). */
static inline int64_t ukf_sqrt_round(int64_t v)
{
    uint64_t s;
    if (v <= 0)
        return 0;
    s = fl_isqrt64((uint64_t)v);
    return (int64_t)((uint64_t)v - s * s > s ? s + 1u : s);
}

/* v modulo 2^28 (a turn in Q12 angle units) in [-2^27, 2^27). */
static inline int32_t ukf_wrap_q12(int64_t v)
{
    uint32_t u = (uint32_t)((uint64_t)v & 0xfffffffu);
    return u >= 0x8000000u ? (int32_t)u - 0x10000000 : (int32_t)u;
}

static inline int32_t ukf_box(int64_t v)
{
    return (int32_t)ukf_clamp64(v, -FL_UKF_POS_MAX_MM, FL_UKF_POS_MAX_MM);
}

/* ukf.c */
void fl_ukf_internal_factor(const fl_ukf_cov_t *p, ukf_fac_t *f);
/* fl_ukf_cov_repair, leaving in *f the factor of the repaired matrix (one
 * factorisation when p was valid). */
bool fl_ukf_internal_repair(fl_ukf_cov_t *p, const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep,
                            ukf_fac_t *f);
/* ln(x) in Q16 (x >= 1; 0 for 0). */
int64_t fl_ukf_internal_ln_q16(uint64_t x);
/* The effective floors (lim clamped into [1, cap]; NULL: 1). */
void fl_ukf_internal_limits(const fl_ukf_limits_t *lim, fl_ukf_limits_t *out);

#endif /* FIELDLOC_UKF_INT_H */
