/*
 * src/loc/ukf.c - the fixed-point UKF step of one particle (ukf.h): the
 * Cholesky factor, the symmetric-positive-definite repair, the Gaussian
 * density and draws, ln.  Predict and update: ukf_step.c.
 *
 * Sigma points (n = 3, 2n + 1 = 7): the scaled unscented transform of
 * Julier ("The scaled unscented transformation", ACC 2002) with the
 * parameters of van der Merwe et al. (NIPS 2000, and Wan and van der Merwe,
 * "The unscented Kalman filter for nonlinear estimation", 2000) set to
 * alpha = 1, beta = 2, kappa = 0: lambda = alpha^2 (n + kappa) - n = 0,
 * points m and m +- sqrt(3) L_j (L_j the columns of the Cholesky factor),
 * mean weights W0 = 0, Wi = 1/6, covariance weights W0 = 2 (beta = 2 is
 * the optimum for a Gaussian prior), Wi = 1/6.  kappa = 0 is Julier and
 * Uhlmann's n + kappa = 3 rule for n = 3 (it matches the fourth moment of a
 * Gaussian), and with alpha = 1 every weight is a non-negative integer over
 * 6: the sample covariances are sums of outer products with non-negative
 * weights, positive semi-definite before rounding, and the sums are exact
 * in int64 (one rounded division by 6 at the end).  The state deviations
 * of the points sum to zero exactly (pairs +-), so the cross-covariance
 * needs no state mean.
 *
 * Precision: the factor L in Q8 of the state's units (round to nearest:
 * l11 = round(sqrt(xx 2^16)), the others by rounded divisions); sigma
 * deviations in Q8 (mm / 256, angle unit / 256), their products and the
 * sample covariances in Q16 (int64); bearings by atan2 refined to Q8 units
 * (ukf_step.c); the innovation covariance's factor, the gain's factor U and
 * the whitened innovation in Q12 / Q16.  Means are rounded to the state's
 * integer mm and angle units; covariances to integer units.
 *
 * Symmetric positive definite, by construction and by repair: a covariance
 * is stored as its six distinct entries (symmetric by construction); the
 * update subtracts U U^T (K S K^T in factored form, U = Pxz L_S^-T) entry
 * by entry from the same products (symmetric); every written covariance
 * goes through fl_ukf_cov_repair, whose steps are each counted in
 * fl_ukf_repairs_t: (1) the diagonal clamped to [floor, cap] (floors,
 * caps); (2) each covariance clamped to the Cauchy-Schwarz bound
 * sqrt(P_ii P_jj) of its variances (caps); (3) a modified Cholesky (Gill,
 * Murray and Wright, Practical Optimization, 1981, 4.4.2.2): a pivot (the
 * conditional variance of y given x, of the heading given x and y) below
 * its floor raises its diagonal entry by the deficit, which leaves every
 * other pivot and correlation as it was; when that would pass a cap, the
 * matrix is replaced by its diagonal (not_pd).  A valid covariance
 * (fl_ukf_cov_valid) therefore factors with every pivot at least its
 * floor: positive definite with a margin that rounding cannot erase.
 */
#include "ukf_int.h"

#include "fieldloc/mcl.h"

#include <string.h>

/* ln(1 + k/32) in Q24, k = 0..32 (Python's math.log). */
static const uint32_t ukf_ln1p_q24[33] = {
    0u, 516263u, 1017112u, 1503443u, 1976071u, 2435750u, 2883169u, 3318965u,
    3743728u, 4158001u, 4562291u, 4957067u, 5342767u, 5719799u, 6088544u, 6449358u,
    6802576u, 7148510u, 7487455u, 7819688u, 8145469u, 8465045u, 8778647u, 9086495u,
    9388795u, 9685745u, 9977530u, 10264327u, 10546303u, 10823619u, 11096425u,
    11364866u, 11629080u,
};

/* Covariances beyond 2^30 break Cauchy-Schwarz within the caps. */
#define UKF_C_LIM   ((int64_t)1 << 30)

/* ln x = k ln 2 + ln(1 + f), x = 2^k (1 + f); ln(1 + f) by linear
 * interpolation between 33 knots (chord error <= (1/32)^2 / 8 = 1.2e-4
 * nats, below the tables' rounding to Q8). */
int64_t fl_ukf_internal_ln_q16(uint64_t x)
{
    unsigned k;
    uint64_t y;
    uint32_t j, t;
    int64_t v;
    if (x == 0u)
        return 0;
    k = ukf_topbit(x);
    y = x << (63u - k);                       /* top bit at 63 */
    j = (uint32_t)(y >> 58) & 31u;
    t = (uint32_t)(y >> 26);                  /* the next 32 bits */
    v = (int64_t)k * UKF_LN2_Q24 + ukf_ln1p_q24[j] +
        (int64_t)(((uint64_t)(ukf_ln1p_q24[j + 1] - ukf_ln1p_q24[j]) * t) >> 32);
    return ukf_rsr(v, 8);
}

int32_t fl_ukf_ln_q8(uint64_t x)
{
    return (int32_t)ukf_rsr(fl_ukf_internal_ln_q16(x), 8);
}

/* ---- the factor ------------------------------------------------------------ */

static bool ukf_in(int64_t v, int64_t lo, int64_t hi)
{
    return v >= lo && v <= hi;
}

/* n / d in Q32, rounded, for d in [1, 2^31) and n / d < lim <= 2^30.5;
 * false beyond lim. */
static bool ukf_ratio_q32(uint64_t n, uint64_t d, uint64_t lim, int64_t *out)
{
    uint64_t q = n / d, r = n % d;
    if (q >= lim)
        return false;
    *out = (int64_t)((q << 32) + ((r << 32) + d / 2u) / d);
    return true;
}

/* n / d in Q16 for n in Q32 and d in Q(16 + k) (the pivot's root with k
 * more bits); false when beyond 2^31. */
static bool ukf_div_hi(int64_t n, int64_t d, unsigned k, int64_t *out)
{
    uint64_t un = ukf_abs64(n), ud = (uint64_t)d, q = un / ud, r = un % ud;
    if (q >= ((uint64_t)1 << (31 - k)))
        return false;
    *out = ukf_signed((q << k) + ((r << k) + ud / 2u) / ud, n < 0);
    return true;
}

/* sqrt(v) with k more bits (k <= 15, v 4^k < 2^62 kept near 2^60): the
 * root in Q(16 + k) for v in Q32, and k. */
static int64_t ukf_sqrt_hi(int64_t v, unsigned *k)
{
    unsigned n = ukf_topbit((uint64_t)v);
    *k = n >= 60u ? 0u : (61u - n) / 2u > 15u ? 15u : (61u - n) / 2u;
    return ukf_sqrt_round(v * ((int64_t)1 << (2u * *k)));
}

/* Entries in Q16, pivots in Q32.  The pivots come from exact integer
 * quantities: l21^2 = xy^2 / xx and l31^2 = xt^2 / xx (numerators exact in
 * int64, the divisions rounded in Q32), l32 = (yt xx - xt xy) / xx / l22;
 * the entries below the diagonal are divisions by the diagonal's roots
 * taken with up to 15 more bits: each entry is within about 1/2 LSB of
 * Q16 whatever the correlations.  Every product stays below 2^63 by the
 * bounds checked on the way (a matrix within the caps passes them unless
 * it is not positive definite). */
void fl_ukf_internal_factor(const fl_ukf_cov_t *p, ukf_fac_t *f)
{
    int64_t t, n, h;
    unsigned k;
    memset(f, 0, sizeof *f);
    f->piv[0] = f->piv[1] = f->piv[2] = UKF_PIVOT_BAD;
    f->fail = 1;
    if (!ukf_in(p->xx, 1, FL_UKF_VAR_MM2_MAX))
        return;
    f->piv[0] = (int64_t)p->xx * UKF_P32;
    h = ukf_sqrt_hi(f->piv[0], &k);
    f->l11 = k ? ukf_rsr(h, k) : h;
    f->fail = 2;
    if (!ukf_in(p->xy, -UKF_C_LIM, UKF_C_LIM) || !ukf_in(p->yy, 1, FL_UKF_VAR_MM2_MAX) ||
        !ukf_ratio_q32(ukf_abs64(p->xy) * ukf_abs64(p->xy), (uint64_t)p->xx,
                       (uint64_t)p->yy + 1u, &t) ||
        !ukf_div_hi((int64_t)p->xy * UKF_P32, h, k, &f->l21))
        return;
    f->piv[1] = (int64_t)p->yy * UKF_P32 - t;
    f->fail = 3;
    if (f->piv[1] <= 0) {
        f->fail = 2;
        return;
    }
    if (!ukf_in(p->xt, -UKF_C_LIM, UKF_C_LIM) || !ukf_in(p->yt, -UKF_C_LIM, UKF_C_LIM) ||
        !ukf_in(p->tt, 1, FL_UKF_VAR_ANG2_MAX) ||
        !ukf_ratio_q32(ukf_abs64(p->xt) * ukf_abs64(p->xt), (uint64_t)p->xx,
                       (uint64_t)p->tt + 1u, &t) ||
        !ukf_div_hi((int64_t)p->xt * UKF_P32, h, k, &f->l31))
        return;
    n = (int64_t)p->yt * p->xx - (int64_t)p->xt * p->xy;            /* |n| < 2^61 */
    if (!ukf_ratio_q32(ukf_abs64(n), (uint64_t)p->xx, (uint64_t)3 << 29, &n))
        return;
    if (p->yt * (int64_t)p->xx < (int64_t)p->xt * p->xy)
        n = -n;
    h = ukf_sqrt_hi(f->piv[1], &k);
    f->l22 = k ? ukf_rsr(h, k) : h;
    if (!ukf_div_hi(n, h, k, &f->l32))
        return;
    f->piv[2] = (int64_t)p->tt * UKF_P32 - t - f->l32 * f->l32;
    if (f->piv[2] <= 0)
        return;
    f->l33 = ukf_sqrt_round(f->piv[2]);
    f->fail = 0;
}

fl_status_t fl_ukf_chol3(const fl_ukf_cov_t *p, fl_ukf_chol_t *l)
{
    ukf_fac_t f;
    if (l != NULL)
        memset(l, 0, sizeof *l);
    if (p == NULL || l == NULL)
        return FL_ERR_NULL;
    fl_ukf_internal_factor(p, &f);
    if (f.fail == 0) {
        l->l11 = (int32_t)ukf_sqrt_round((int64_t)p->xx * 65536);   /* not rounded twice */
        l->l21 = (int32_t)ukf_rsr(f.l21, 8);
        l->l31 = (int32_t)ukf_rsr(f.l31, 8);
        l->l22 = (int32_t)ukf_rsr(f.l22, 8);
        l->l32 = (int32_t)ukf_rsr(f.l32, 8);
        l->l33 = (int32_t)ukf_rsr(f.l33, 8);
        return FL_OK;
    }
    l->l11 = (int32_t)ukf_sqrt_round(p->xx > 0 ? (int64_t)p->xx * 65536 : 0);
    l->l22 = (int32_t)ukf_sqrt_round(p->yy > 0 ? (int64_t)p->yy * 65536 : 0);
    l->l33 = (int32_t)ukf_sqrt_round(p->tt > 0 ? (int64_t)p->tt * 65536 : 0);
    return FL_ERR_RANGE;
}

bool fl_ukf_inv2(int64_t a, int64_t b, int64_t c, int64_t *ia, int64_t *ib,
                 int64_t *ic, int64_t *det)
{
    int64_t d = 0;
    bool ok = a >= -INT32_MAX && a <= INT32_MAX && b >= -INT32_MAX && b <= INT32_MAX &&
              c >= -INT32_MAX && c <= INT32_MAX;
    if (ok) {
        d = a * c - b * b;          /* |a c|, b^2 < 2^62 */
        ok = d > 0;
    }
    if (ia != NULL)
        *ia = ok ? c : 0;
    if (ib != NULL)
        *ib = ok ? -b : 0;
    if (ic != NULL)
        *ic = ok ? a : 0;
    if (det != NULL)
        *det = ok ? d : 0;
    return ok;
}

/* ---- validity and repair ---------------------------------------------------- */

static int32_t ukf_clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

void fl_ukf_internal_limits(const fl_ukf_limits_t *lim, fl_ukf_limits_t *out)
{
    out->var_min_mm2 = lim ? ukf_clamp32(lim->var_min_mm2, 1, FL_UKF_VAR_MM2_MAX) : 1;
    out->var_min_ang2 = lim ? ukf_clamp32(lim->var_min_ang2, 1, FL_UKF_VAR_ANG2_MAX) : 1;
}

static uint32_t ukf_inc(uint32_t v)
{
    return v == UINT32_MAX ? v : v + 1u;
}

static void ukf_fix_diag(int32_t *v, int32_t lo, int32_t hi, fl_ukf_repairs_t *r)
{
    if (*v < lo) {
        *v = lo;
        r->floors = ukf_inc(r->floors);
    } else if (*v > hi) {
        *v = hi;
        r->caps = ukf_inc(r->caps);
    }
}

/* |c| <= sqrt(a b) (a, b >= 1 and below 2^31). */
static void ukf_fix_cs(int32_t *c, int32_t a, int32_t b, fl_ukf_repairs_t *r)
{
    int32_t bound = (int32_t)fl_isqrt64((uint64_t)a * (uint64_t)b);
    if (*c > bound || *c < -bound) {
        *c = *c > 0 ? bound : -bound;
        r->caps = ukf_inc(r->caps);
    }
}

/* Raises *v by the deficit of pivot piv (Q32) below floor; false when it
 * cannot (the pivot not computable, or the cap would be passed). */
static bool ukf_raise(int32_t *v, int64_t piv, int32_t floor, int32_t cap)
{
    int64_t need, d;
    if (piv <= UKF_PIVOT_BAD)
        return false;
    need = ((int64_t)floor * UKF_P32) - piv;                 /* < 2^63 */
    d = (int64_t)(((uint64_t)need + 0xffffffffu) >> 32);
    if ((int64_t)*v + d > cap)
        return false;
    *v = (int32_t)((int64_t)*v + d);
    return true;
}

/* Step (3) of the repair: the pivots up to their floors (modified
 * Cholesky), else the diagonal alone.  Diagonal and Cauchy-Schwarz already
 * repaired. */
static void ukf_fix_pivots(fl_ukf_cov_t *p, const fl_ukf_limits_t *lm, fl_ukf_repairs_t *r)
{
    ukf_fac_t f;
    bool ok = true, touched = false;
    fl_ukf_internal_factor(p, &f);
    if (f.fail == 2 || f.piv[1] < (int64_t)lm->var_min_mm2 * UKF_P32) {
        touched = true;
        ok = ukf_raise(&p->yy, f.piv[1], lm->var_min_mm2, FL_UKF_VAR_MM2_MAX);
        if (ok)
            fl_ukf_internal_factor(p, &f);
    }
    if (ok && (f.fail != 0 || f.piv[2] < (int64_t)lm->var_min_ang2 * UKF_P32)) {
        touched = true;
        ok = ukf_raise(&p->tt, f.piv[2], lm->var_min_ang2, FL_UKF_VAR_ANG2_MAX);
    }
    if (!ok)
        p->xy = p->xt = p->yt = 0;
    if (touched)
        r->not_pd = ukf_inc(r->not_pd);
}

static void ukf_add_repairs(fl_ukf_repairs_t *to, const fl_ukf_repairs_t *r)
{
    to->floors = to->floors > UINT32_MAX - r->floors ? UINT32_MAX : to->floors + r->floors;
    to->caps = to->caps > UINT32_MAX - r->caps ? UINT32_MAX : to->caps + r->caps;
    to->not_pd = to->not_pd > UINT32_MAX - r->not_pd ? UINT32_MAX : to->not_pd + r->not_pd;
}

static bool ukf_fac_valid(const fl_ukf_cov_t *p, const fl_ukf_limits_t *lm, ukf_fac_t *f)
{
    if (p->xx < lm->var_min_mm2 || p->xx > FL_UKF_VAR_MM2_MAX || p->yy < lm->var_min_mm2 ||
        p->yy > FL_UKF_VAR_MM2_MAX || p->tt < lm->var_min_ang2 || p->tt > FL_UKF_VAR_ANG2_MAX) {
        f->fail = 1;
        return false;
    }
    fl_ukf_internal_factor(p, f);
    return f->fail == 0 && f->piv[1] >= (int64_t)lm->var_min_mm2 * UKF_P32 &&
           f->piv[2] >= (int64_t)lm->var_min_ang2 * UKF_P32;
}

bool fl_ukf_internal_repair(fl_ukf_cov_t *p, const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep,
                            ukf_fac_t *f)
{
    fl_ukf_limits_t lm;
    fl_ukf_repairs_t r = {0u, 0u, 0u};
    fl_ukf_internal_limits(lim, &lm);
    if (ukf_fac_valid(p, &lm, f))
        return true;                          /* the common case: one factorisation */
    ukf_fix_diag(&p->xx, lm.var_min_mm2, FL_UKF_VAR_MM2_MAX, &r);
    ukf_fix_diag(&p->yy, lm.var_min_mm2, FL_UKF_VAR_MM2_MAX, &r);
    ukf_fix_diag(&p->tt, lm.var_min_ang2, FL_UKF_VAR_ANG2_MAX, &r);
    ukf_fix_cs(&p->xy, p->xx, p->yy, &r);
    ukf_fix_cs(&p->xt, p->xx, p->tt, &r);
    ukf_fix_cs(&p->yt, p->yy, p->tt, &r);
    ukf_fix_pivots(p, &lm, &r);
    fl_ukf_internal_factor(p, f);
    if (rep != NULL)
        ukf_add_repairs(rep, &r);
    return r.floors == 0u && r.caps == 0u && r.not_pd == 0u;
}

bool fl_ukf_cov_repair(fl_ukf_cov_t *p, const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep)
{
    ukf_fac_t f;
    if (p == NULL)
        return false;
    return fl_ukf_internal_repair(p, lim, rep, &f);
}

bool fl_ukf_cov_valid(const fl_ukf_cov_t *p, const fl_ukf_limits_t *lim)
{
    fl_ukf_limits_t lm;
    ukf_fac_t f;
    if (p == NULL)
        return false;
    fl_ukf_internal_limits(lim, &lm);
    return ukf_fac_valid(p, &lm, &f);
}

/* ---- density and draws -------------------------------------------------------- */

#define UKF_Z_LIM ((int64_t)1 << 30)    /* 16384 sd in Q16: beyond, saturated */
#define UKF_D_LIM ((int64_t)1 << 30)    /* a difference beyond it saturates too */

uint32_t fl_ukf_gauss_nll_q8(const fl_ukf_pose_t *m, const fl_ukf_cov_t *p,
                             const fl_ukf_pose_t *x)
{
    ukf_fac_t f;
    int64_t z1, z2, z3, v, d1, d2;
    uint64_t sq;
    if (m == NULL || p == NULL || x == NULL)
        return UINT32_MAX;
    fl_ukf_internal_factor(p, &f);
    if (f.fail != 0)
        return UINT32_MAX;
    d1 = ukf_clamp64((int64_t)x->x_mm - m->x_mm, -UKF_D_LIM, UKF_D_LIM);
    d2 = ukf_clamp64((int64_t)x->y_mm - m->y_mm, -UKF_D_LIM, UKF_D_LIM);
    /* L z = d by forward substitution (L Q16): z in Q16 standard deviations */
    z1 = ukf_clamp64(ukf_div(d1 * UKF_P32, f.l11), -UKF_Z_LIM, UKF_Z_LIM);
    z2 = ukf_clamp64(ukf_div(d2 * UKF_P32 - f.l21 * z1, f.l22), -UKF_Z_LIM, UKF_Z_LIM);
    z3 = ukf_div((int64_t)fl_angle_sub(x->heading, m->heading) * UKF_P32 -
                 f.l31 * z1 - f.l32 * z2, f.l33);
    z3 = ukf_clamp64(z3, -UKF_Z_LIM, UKF_Z_LIM);
    sq = ukf_abs64(z1) * ukf_abs64(z1) + ukf_abs64(z2) * ukf_abs64(z2) +
         ukf_abs64(z3) * ukf_abs64(z3);                        /* Q32, < 2^62 */
    /* |z|^2 / 2 + ln det L (L in Q16: 3 x 16 ln 2 off), Q16 */
    v = (int64_t)(sq >> 17) + fl_ukf_internal_ln_q16((uint64_t)f.l11) +
        fl_ukf_internal_ln_q16((uint64_t)f.l22) + fl_ukf_internal_ln_q16((uint64_t)f.l33) -
        ukf_rsr((int64_t)48 * UKF_LN2_Q24, 8);
    v = ukf_rsr(v, 8);
    return v <= 0 ? 0u : v >= (int64_t)UINT32_MAX ? UINT32_MAX : (uint32_t)v;
}

bool fl_ukf_sample(const fl_ukf_pose_t *m, const fl_ukf_cov_t *p, uint32_t *rng,
                   fl_ukf_pose_t *out)
{
    ukf_fac_t f;
    int64_t g1, g2, g3;
    if (out == NULL)
        return false;
    if (m == NULL) {
        memset(out, 0, sizeof *out);
        return false;
    }
    out->x_mm = ukf_box(m->x_mm);
    out->y_mm = ukf_box(m->y_mm);
    out->heading = m->heading;
    if (p == NULL || rng == NULL)
        return false;
    fl_ukf_internal_factor(p, &f);
    if (f.fail != 0)
        return false;
    g1 = fl_mcl_gauss_q12(rng);
    g2 = fl_mcl_gauss_q12(rng);
    g3 = fl_mcl_gauss_q12(rng);
    /* L (Q16) g (Q12): Q28 */
    out->x_mm = ukf_box((int64_t)out->x_mm + ukf_rsr(f.l11 * g1, 28));
    out->y_mm = ukf_box((int64_t)out->y_mm + ukf_rsr(f.l21 * g1 + f.l22 * g2, 28));
    out->heading = fl_angle_wrap((int32_t)((int64_t)out->heading +
                                           ukf_rsr(f.l31 * g1 + f.l32 * g2 + f.l33 * g3, 28)));
    return true;
}
