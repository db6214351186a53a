/*
 * src/loc/ukf_step.c - the UKF's predict and update (ukf.h; sigma-point
 * parameters and the repairs: ukf.c).
 *
 * Both start the same way: the mean clamped onto the box, the covariance
 * repaired (counted), its Cholesky factor (Q16), the six sigma deviations
 * +-sqrt(3) L_j in Q12 of the state's units (the seventh point is the mean
 * itself).  Every sigma-space quantity is Q12 (mm / 4096, angle unit /
 * 4096), their products and sample covariances Q24 (int64; the sums stay
 * below 2^62 for any covariance within the caps and any odometry within
 * +-FL_OBS_MAX_RANGE_MM).
 *
 * Predict: each point moved by the odometry at its own heading, the
 * heading's table cos/sin at the integer unit corrected to first order in
 * the Q12 fraction (error below 5e-9); the points' deviations from the
 * central point's motion give the mean shift and the covariance (one
 * rounded division by 6), plus the process noise.  Heading deviations are
 * not changed by the motion, so their mean stays 0.
 *
 * Update: each point's range (rounded square root) and bearing (fl_atan2
 * refined by rotating the vector back by its result, atan t = t for the
 * remaining |t| < 1e-4 rad, minus the point's heading), both Q12;
 * deviations from the central point's, bearings wrapped to +-180 deg about
 * it; the predicted measurement is the central point's plus the mean
 * deviation.  S = sum W (z - zhat)(z - zhat)^T + R, Pxz = sum W dx (z -
 * zhat)^T.  S is normalised, S' = D S D with D = diag(2^-u, 2^-v) putting
 * its diagonal in [2^28, 2^30), so its determinant is exact in int64
 * (as fl_ukf_inv2's); its Cholesky factor L' = [a 0; b c] in Q15 (relative
 * error ~2^-30 whatever the scale of S).  The gain is applied in factored
 * form: U = Pxz D L'^-T (Q15 of the state's units), w = L'^-1 D nu (the
 * whitened innovation, Q16): K nu = U w, K S K^T = U U^T, so the
 * covariance update P - U U^T is symmetric entry by entry; the negative
 * log-likelihood is |w|^2 / 2 + ln(a c) + the scales.
 *
 * Precision: the posterior covariance loses what the update cancels: its
 * error is ~1e-7 of the prior's (the Q12 sigma deviations), so an
 * observation 100 times sharper than the prior (variances 10^4 apart)
 * leaves ~1e-3 of the posterior (measured: host_tests/test_ukf.c, fieldloc
 * ukf-check).
 */
#include "ukf_int.h"

#include "fieldloc/obs.h"

#include <string.h>

#define UKF_SQRT3_Q20 1816187      /* round(sqrt(3) 2^20) */
#define UKF_2PI_Q16   411775       /* round(2 pi 2^16) */
#define UKF_RAD_Q12   42722830     /* round(2^28 / (2 pi)): Q12 units per radian */
#define UKF_U_LIM     ((int64_t)5 << 28)    /* |U| (Q15): beyond any sd within the caps */
#define UKF_W_LIM     ((int64_t)1 << 30)    /* |w| (Q16): 16384 sd */

/* Deviations of sigma points 1..6 from the mean, Q12: +sqrt(3) L_j for
 * j = 0, 1, 2, then the same negated. */
typedef struct {
    int32_t d[6][3];
} ukf_sigma_t;

static const uint8_t ukf_pair[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};

static void ukf_cov_set(fl_ukf_cov_t *p, const int64_t v[6])
{
    p->xx = fl_sat32(v[0]);
    p->xy = fl_sat32(v[1]);
    p->xt = fl_sat32(v[2]);
    p->yy = fl_sat32(v[3]);
    p->yt = fl_sat32(v[4]);
    p->tt = fl_sat32(v[5]);
}

static void ukf_cov_get(const fl_ukf_cov_t *p, int64_t v[6])
{
    v[0] = p->xx;
    v[1] = p->xy;
    v[2] = p->xt;
    v[3] = p->yy;
    v[4] = p->yt;
    v[5] = p->tt;
}

/* The common start: mean on the box, covariance repaired, sigma points. */
static void ukf_prepare(fl_ukf_pose_t *m, fl_ukf_cov_t *p, const fl_ukf_limits_t *lim,
                        fl_ukf_repairs_t *rep, ukf_sigma_t *s)
{
    ukf_fac_t f;
    int64_t col[3][3];
    int j, k;
    m->x_mm = ukf_box(m->x_mm);
    m->y_mm = ukf_box(m->y_mm);
    fl_ukf_internal_repair(p, lim, rep, &f);  /* a repaired matrix factors */
    col[0][0] = f.l11; col[0][1] = f.l21; col[0][2] = f.l31;
    col[1][0] = 0;     col[1][1] = f.l22; col[1][2] = f.l32;
    col[2][0] = 0;     col[2][1] = 0;     col[2][2] = f.l33;
    for (j = 0; j < 3; j++)
        for (k = 0; k < 3; k++) {
            /* Q16 x Q20 -> Q12; |L| <= 2^31 */
            int32_t v = (int32_t)ukf_rsr(col[j][k] * UKF_SQRT3_Q20, 24);
            s->d[j][k] = v;
            s->d[j + 3][k] = -v;
        }
}

/* cos and sin (Q30) of a Q12 angle: the tables at the integer unit, first
 * order in the fraction f < 1 unit (9.6e-5 rad; the neglected f^2 / 2 is
 * 5e-9). */
static void ukf_cossin(int64_t a_q12, int64_t *c, int64_t *s)
{
    int64_t ip = ukf_asr(a_q12, 12), fr = a_q12 - ip * 4096;
    fl_angle_t a = fl_angle_wrap((int32_t)ip);
    int64_t c0 = fl_cos_q30(a), s0 = fl_sin_q30(a);
    *c = c0 - ukf_rsr(s0 * fr * UKF_2PI_Q16, 44);
    *s = s0 + ukf_rsr(c0 * fr * UKF_2PI_Q16, 44);
}

fl_status_t fl_ukf_predict(fl_ukf_pose_t *m, fl_ukf_cov_t *p, int32_t dx_mm,
                           int32_t dy_mm, fl_angle_t dtheta, const fl_ukf_cov_t *q,
                           const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep)
{
    fl_ukf_odo_t o;
    o.dx_mm = dx_mm;
    o.dy_mm = dy_mm;
    o.dtheta = dtheta;
    return fl_ukf_predict_odo(m, p, &o, q, lim, rep);
}

fl_status_t fl_ukf_predict_odo(fl_ukf_pose_t *m, fl_ukf_cov_t *p, const fl_ukf_odo_t *odo,
                               const fl_ukf_cov_t *q, const fl_ukf_limits_t *lim,
                               fl_ukf_repairs_t *rep)
{
    ukf_sigma_t s;
    int64_t dev[6][3], acc[6], qv[6], c0, s0, mx, my, h_q12, mu[3] = {0, 0, 0}, cd[3], sd[3];
    int64_t dx_mm, dy_mm;
    int i, k;
    if (m == NULL || p == NULL || odo == NULL)
        return FL_ERR_NULL;
    dx_mm = odo->dx_mm;
    dy_mm = odo->dy_mm;
    ukf_prepare(m, p, lim, rep, &s);
    if (dx_mm > FL_OBS_MAX_RANGE_MM || dx_mm < -FL_OBS_MAX_RANGE_MM ||
        dy_mm > FL_OBS_MAX_RANGE_MM || dy_mm < -FL_OBS_MAX_RANGE_MM)
        return FL_ERR_RANGE;
    h_q12 = (int64_t)m->heading * 4096;
    ukf_cossin(h_q12, &c0, &s0);
    for (i = 0; i < 3; i++)
        ukf_cossin(s.d[i][2], &cd[i], &sd[i]);
    for (i = 0; i < 6; i++) {
        /* cos and sin of h +- d from those of d (the +- pairs share them) */
        int64_t c = cd[i % 3], sn = i < 3 ? sd[i] : -sd[i - 3], ci, si;
        ci = ukf_rsr(c0 * c - s0 * sn, 30) - c0;
        si = ukf_rsr(s0 * c + c0 * sn, 30) - s0;
        /* Q30 mm -> Q12 mm */
        dev[i][0] = s.d[i][0] + ukf_rsr(dx_mm * ci - dy_mm * si, 18);
        dev[i][1] = s.d[i][1] + ukf_rsr(dx_mm * si + dy_mm * ci, 18);
        dev[i][2] = s.d[i][2];
        mu[0] += dev[i][0];
        mu[1] += dev[i][1];
    }
    mu[0] = ukf_div(mu[0], 6);
    mu[1] = ukf_div(mu[1], 6);              /* mu[2] = 0: the +- pairs cancel */
    for (k = 0; k < 6; k++) {
        int a = ukf_pair[k][0], b = ukf_pair[k][1];
        int64_t sum = 12 * mu[a] * mu[b];   /* W0 = 2 on the central point, x 6 */
        for (i = 0; i < 6; i++)
            sum += (dev[i][a] - mu[a]) * (dev[i][b] - mu[b]);
        acc[k] = ukf_div(sum, (int64_t)6 << 24);
    }
    if (q != NULL) {
        ukf_cov_get(q, qv);
        for (k = 0; k < 6; k++)
            acc[k] += qv[k];
    }
    ukf_cov_set(p, acc);
    mx = ukf_rsr(dx_mm * c0 - dy_mm * s0, 18) + mu[0];
    my = ukf_rsr(dx_mm * s0 + dy_mm * c0, 18) + mu[1];
    m->x_mm = ukf_box((int64_t)m->x_mm + ukf_rsr(mx, 12));
    m->y_mm = ukf_box((int64_t)m->y_mm + ukf_rsr(my, 12));
    m->heading = fl_angle_add(m->heading, odo->dtheta);
    fl_ukf_cov_repair(p, lim, rep);
    return FL_OK;
}

/* ---- update ----------------------------------------------------------------------- */

typedef struct {
    int32_t e[6][2];          /* points 1..6: range, bearing minus the central point's, Q12 */
    int64_t r0, b0;           /* the central point's range and bearing, Q12 */
    int64_t mu[2];            /* mean deviation, Q12 */
    int64_t s[3];             /* S: rr, rb, bb, Q24 */
    int64_t pxz[3][2];        /* Pxz, Q24 */
    int u, v;                 /* D = diag(2^-u, 2^-v) */
    int64_t a, b, c;          /* L' = [a 0; b c], Q15 */
    int64_t uu[3][2];         /* U, Q15 */
    int64_t w[2];             /* w, Q16 */
} ukf_upd_t;

/* atan2(y, x) in Q12 units (0 for the zero vector): the vector normalised
 * to [2^29, 2^30), fl_atan2's angle, the residual by rotating back. */
static int64_t ukf_atan2_q12(int64_t y, int64_t x)
{
    uint64_t mx = ukf_abs64(x) > ukf_abs64(y) ? ukf_abs64(x) : ukf_abs64(y);
    unsigned n;
    fl_angle_t a;
    int64_t c, s, xr, yr;
    if (mx == 0u)
        return 0;
    n = ukf_topbit(mx);
    if (n < 29u) {
        x *= (int64_t)1 << (29u - n);
        y *= (int64_t)1 << (29u - n);
    } else if (n > 29u) {
        x = ukf_asr(x, n - 29u);
        y = ukf_asr(y, n - 29u);
    }
    a = fl_atan2((int32_t)y, (int32_t)x);
    c = fl_cos_q30(a);
    s = fl_sin_q30(a);
    xr = ukf_asr(x * c + y * s, 24);          /* > 2^34 */
    yr = ukf_asr(y * c - x * s, 24);          /* |yr| < 2^24 */
    return (int64_t)a * 4096 + ukf_div(yr * UKF_RAD_Q12, xr);
}

/* sqrt(x^2 + y^2), rounded (|x|, |y| < 2^62). */
static int64_t ukf_hypot64(int64_t x, int64_t y)
{
    uint64_t mx = ukf_abs64(x) > ukf_abs64(y) ? ukf_abs64(x) : ukf_abs64(y);
    unsigned k = mx >= ((uint64_t)1 << 30) ? ukf_topbit(mx) - 29u : 0u;
    if (k == 0u)
        return ukf_sqrt_round(x * x + y * y);
    x = ukf_rsr(x, k);
    y = ukf_rsr(y, k);
    return ukf_sqrt_round(x * x + y * y) * ((int64_t)1 << k);
}

/* The angle (Q12 units) of v relative to the unit direction (c, s) (Q30),
 * by the series atan t = t - t^3/3 + ... + t^9/9 (truncation below 1.1e-11
 * rad for |t| <= 1/8): false when v is 0, behind, or more than atan(1/8)
 * = 7.1 deg off (the caller then takes the full atan2). */
static bool ukf_rel_angle(int64_t vx, int64_t vy, int64_t c, int64_t s, int64_t *out)
{
    uint64_t mx = ukf_abs64(vx) > ukf_abs64(vy) ? ukf_abs64(vx) : ukf_abs64(vy);
    unsigned n;
    int64_t xr, yr, t, t2, p;
    if (mx == 0u)
        return false;
    n = ukf_topbit(mx);
    if (n > 29u) {
        vx = ukf_asr(vx, n - 29u);
        vy = ukf_asr(vy, n - 29u);
    } else if (n < 29u) {
        vx *= (int64_t)1 << (29u - n);
        vy *= (int64_t)1 << (29u - n);
    }
    xr = ukf_asr(vx * c + vy * s, 30);        /* |v| in [2^29, 2^30.5) */
    yr = ukf_asr(vy * c - vx * s, 30);
    if (xr <= 0 || ukf_abs64(yr) * 8u > (uint64_t)xr)
        return false;
    t = ukf_div(yr * ((int64_t)1 << 30), xr);   /* Q30, |t| <= 2^27 */
    t2 = ukf_rsr(t * t, 30);
    p = 119304647;                                /* 1/9, then 1/7, 1/5, 1/3, 1 in Q30 */
    p = 153391689 - ukf_rsr(t2 * p, 30);
    p = 214748365 - ukf_rsr(t2 * p, 30);
    p = 357913941 - ukf_rsr(t2 * p, 30);
    p = ((int64_t)1 << 30) - ukf_rsr(t2 * p, 30);
    *out = ukf_rsr(ukf_rsr(t * p, 30) * UKF_RAD_Q12, 30);
    return true;
}

/* The points through the measurement function; deviations and their mean.
 * Ranges by a rounded square root each; bearing deviations relative to
 * the central point's direction by the series (both angles through the
 * same rotation, so its error cancels), else by the full atan2. */
static void ukf_points(const fl_ukf_pose_t *m, const ukf_sigma_t *s, int32_t lx, int32_t ly,
                       ukf_upd_t *u)
{
    int64_t sum[2] = {0, 0}, vx0, vy0, a0, c, sn, res0 = 0, h = (int64_t)m->heading * 4096;
    bool series;
    int i;
    vx0 = ((int64_t)lx - m->x_mm) * 4096;
    vy0 = ((int64_t)ly - m->y_mm) * 4096;
    u->r0 = ukf_hypot64(vx0, vy0);
    a0 = ukf_atan2_q12(vy0, vx0);
    u->b0 = a0 - h;
    ukf_cossin(a0, &c, &sn);
    series = ukf_rel_angle(vx0, vy0, c, sn, &res0);
    for (i = 0; i < 6; i++) {
        int64_t vx = vx0 - s->d[i][0], vy = vy0 - s->d[i][1], res;
        u->e[i][0] = (int32_t)(ukf_hypot64(vx, vy) - u->r0);   /* |.| <= |d| < 2^28 */
        if (series && ukf_rel_angle(vx, vy, c, sn, &res))
            u->e[i][1] = ukf_wrap_q12(res - res0 - s->d[i][2]);
        else
            u->e[i][1] = ukf_wrap_q12(ukf_atan2_q12(vy, vx) - (h + s->d[i][2]) - u->b0);
        sum[0] += u->e[i][0];
        sum[1] += u->e[i][1];
    }
    u->mu[0] = ukf_div(sum[0], 6);
    u->mu[1] = ukf_div(sum[1], 6);
}

/* x 2^k (k may be negative: rounded), |x 2^k| clamped below 2^61. */
static int64_t ukf_scale(int64_t x, int k)
{
    int64_t lim;
    if (k <= 0)
        return k == 0 ? x : ukf_rsr(x, (unsigned)-k);
    lim = ((int64_t)1 << 61) >> k;
    return ukf_clamp64(x, -lim, lim) * ((int64_t)1 << k);
}

/* The shift u with x 2^-2u in [2^28, 2^30) (x >= 1). */
static int ukf_norm_shift(int64_t x)
{
    /* floor((top bit - 28) / 2): the scaled top bit is 28 or 29 */
    return (int)((ukf_topbit((uint64_t)x) + 36u) / 2u) - 32;
}

/* S, Pxz, and the factor of the normalised S. */
static void ukf_innovation_cov(const ukf_sigma_t *s, ukf_upd_t *u, int64_t r_rr, int64_t r_bb)
{
    static const uint8_t pr[3][2] = {{0, 0}, {0, 1}, {1, 1}};
    int64_t srr, srb, sbb, det, lim;
    int i, j, k;
    for (k = 0; k < 3; k++) {
        int a = pr[k][0], b = pr[k][1];
        int64_t sum = 12 * u->mu[a] * u->mu[b];
        for (i = 0; i < 6; i++)
            sum += (u->e[i][a] - u->mu[a]) * (u->e[i][b] - u->mu[b]);
        u->s[k] = ukf_div(sum, 6);
    }
    u->s[0] += r_rr * ((int64_t)1 << 24);
    u->s[2] += r_bb * ((int64_t)1 << 24);
    for (j = 0; j < 3; j++)
        for (k = 0; k < 2; k++) {
            int64_t sum = 0;
            for (i = 0; i < 3; i++)
                sum += (int64_t)s->d[i][j] * (u->e[i][k] - u->e[i + 3][k]);
            u->pxz[j][k] = ukf_div(sum, 6);
        }
    u->u = ukf_norm_shift(u->s[0]);
    u->v = ukf_norm_shift(u->s[2]);
    srr = ukf_scale(u->s[0], -2 * u->u);
    sbb = ukf_scale(u->s[2], -2 * u->v);
    lim = (int64_t)fl_isqrt64((uint64_t)(srr * sbb));
    srb = ukf_clamp64(ukf_scale(u->s[1], -(u->u + u->v)), -lim, lim);
    det = srr * sbb - srb * srb;              /* exact, < 2^60 (fl_ukf_inv2's det) */
    if (det < 1)
        det = 1;                              /* singular at 2^-30: S's floor */
    u->a = ukf_sqrt_round(srr << 30);         /* [2^29, 2^30) */
    u->b = ukf_div(srb * ((int64_t)1 << 30), u->a);
    /* c^2 = det / srr in Q30, in two steps (det < 2^60) */
    u->c = ukf_sqrt_round((det / srr) * ((int64_t)1 << 30) + ukf_div((det % srr) << 30, srr));
    if (u->c < 1)
        u->c = 1;
}

/* U, w, and the negative log-likelihood (Q16) for the innovation nu (Q12). */
static int64_t ukf_gain(ukf_upd_t *u, int64_t nu_r, int64_t nu_b)
{
    int j;
    uint64_t sq;
    for (j = 0; j < 3; j++) {
        int64_t u1 = ukf_div(ukf_scale(u->pxz[j][0], 18 - u->u), u->a);
        int64_t u2;
        u1 = ukf_clamp64(u1, -UKF_U_LIM, UKF_U_LIM);
        u2 = ukf_div(ukf_scale(u->pxz[j][1], 18 - u->v) - u1 * u->b, u->c);
        u->uu[j][0] = u1;
        u->uu[j][1] = ukf_clamp64(u2, -UKF_U_LIM, UKF_U_LIM);
    }
    u->w[0] = ukf_clamp64(ukf_div(ukf_scale(nu_r, 31 - u->u), u->a), -UKF_W_LIM, UKF_W_LIM);
    u->w[1] = ukf_clamp64(ukf_div(ukf_scale(nu_b, 31 - u->v) - u->b * u->w[0], u->c),
                          -UKF_W_LIM, UKF_W_LIM);
    sq = ukf_abs64(u->w[0]) * ukf_abs64(u->w[0]) + ukf_abs64(u->w[1]) * ukf_abs64(u->w[1]);
    /* |w|^2 / 2 (Q32 -> Q16) + ln a + ln c: a, c in Q15 of sqrt(S') (2^27 off
     * Q12 units) scaled back by 2^u, 2^v */
    return (int64_t)(sq >> 17) + fl_ukf_internal_ln_q16((uint64_t)u->a) +
           fl_ukf_internal_ln_q16((uint64_t)u->c) -
           ukf_rsr((int64_t)(54 - u->u - u->v) * UKF_LN2_Q24, 8);
}

fl_status_t fl_ukf_update(fl_ukf_pose_t *m, fl_ukf_cov_t *p, int32_t lx_mm,
                          int32_t ly_mm, int32_t range_mm, fl_angle_t bearing,
                          int32_t sd_range_mm, fl_angle_t sd_bearing,
                          const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep,
                          uint32_t *nll_q8)
{
    fl_ukf_obs_t o;
    o.lx_mm = lx_mm;
    o.ly_mm = ly_mm;
    o.range_mm = range_mm;
    o.bearing = bearing;
    o.sd_range_mm = sd_range_mm;
    o.sd_bearing = sd_bearing;
    return fl_ukf_update_obs(m, p, &o, lim, rep, nll_q8);
}

fl_status_t fl_ukf_update_obs(fl_ukf_pose_t *m, fl_ukf_cov_t *p, const fl_ukf_obs_t *o,
                              const fl_ukf_limits_t *lim, fl_ukf_repairs_t *rep,
                              uint32_t *nll_q8)
{
    ukf_sigma_t s;
    ukf_upd_t u;
    int64_t pv[6], nll;
    int32_t sd_r;
    int k;
    if (nll_q8 != NULL)
        *nll_q8 = UINT32_MAX;
    if (m == NULL || p == NULL || o == NULL)
        return FL_ERR_NULL;
    ukf_prepare(m, p, lim, rep, &s);
    if (o->range_mm < 0 || o->range_mm > FL_OBS_MAX_RANGE_MM || o->sd_range_mm <= 0 ||
        o->sd_bearing <= 0 || o->lx_mm > FL_UKF_POS_MAX_MM || o->lx_mm < -FL_UKF_POS_MAX_MM ||
        o->ly_mm > FL_UKF_POS_MAX_MM || o->ly_mm < -FL_UKF_POS_MAX_MM)
        return FL_ERR_RANGE;
    sd_r = o->sd_range_mm > FL_UKF_SD_RANGE_MAX_MM ? FL_UKF_SD_RANGE_MAX_MM : o->sd_range_mm;
    memset(&u, 0, sizeof u);
    ukf_points(m, &s, o->lx_mm, o->ly_mm, &u);
    ukf_innovation_cov(&s, &u, (int64_t)sd_r * sd_r, (int64_t)o->sd_bearing * o->sd_bearing);
    nll = ukf_gain(&u, (int64_t)o->range_mm * 4096 - (u.r0 + u.mu[0]),
                   ukf_wrap_q12((int64_t)o->bearing * 4096 - (u.b0 + u.mu[1])));
    nll = ukf_rsr(nll, 8);
    if (nll_q8 != NULL)
        *nll_q8 = nll <= 0 ? 0u : nll >= (int64_t)UINT32_MAX ? UINT32_MAX : (uint32_t)nll;
    /* mean: K nu = U w (Q15 x Q16 = Q31); covariance: P - U U^T (Q30) */
    m->x_mm = ukf_box((int64_t)m->x_mm + ukf_rsr(u.uu[0][0] * u.w[0] + u.uu[0][1] * u.w[1], 31));
    m->y_mm = ukf_box((int64_t)m->y_mm + ukf_rsr(u.uu[1][0] * u.w[0] + u.uu[1][1] * u.w[1], 31));
    m->heading = fl_angle_wrap((int32_t)((int64_t)m->heading +
                                         ukf_rsr(u.uu[2][0] * u.w[0] + u.uu[2][1] * u.w[1], 31)));
    ukf_cov_get(p, pv);
    for (k = 0; k < 6; k++) {
        int a = ukf_pair[k][0], b = ukf_pair[k][1];
        pv[k] -= ukf_rsr(u.uu[a][0] * u.uu[b][0] + u.uu[a][1] * u.uu[b][1], 30);
    }
    ukf_cov_set(p, pv);
    fl_ukf_cov_repair(p, lim, rep);
    return FL_OK;
}
