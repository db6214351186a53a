/*
 * host_tests/test_ukf.c - the fixed-point UKF step (ukf.h) against the
 * double reference (tools/eval/ukf_ref.c): Cholesky and 2x2 inverse to the
 * LSB, ln, predict and update on random poses, covariances (sd 10 mm ..
 * 5 m, 0.5 .. 180 deg) and observations, extreme inputs, draws and the
 * Gaussian density.  The error bounds asserted are the measured ones with
 * a margin (printed as "# ..." lines); a swapped sign or a missing wrap
 * exceeds them by orders of magnitude.
 */
#include "test.h"
#include "fieldloc/ukf.h"
#include "fieldloc/obs.h"
#include "eval/ukf_ref.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void to6(const fl_ukf_cov_t *p, int32_t c[6])
{
    c[0] = p->xx; c[1] = p->xy; c[2] = p->xt; c[3] = p->yy; c[4] = p->yt; c[5] = p->tt;
}

static fl_ukf_cov_t from6(const int32_t c[6])
{
    fl_ukf_cov_t p;
    p.xx = c[0]; p.xy = c[1]; p.xt = c[2]; p.yy = c[3]; p.yt = c[4]; p.tt = c[5];
    return p;
}

static const fl_ukf_limits_t LIM1 = {1, 1};

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* the q-quantile of v[0..n) (sorts v) */
static double quantile(double *v, int n, double q)
{
    int i;
    if (n <= 0)
        return 0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    i = (int)(q * (n - 1) + 0.5);
    return v[i];
}

/* A valid random covariance over the whole range of scales. */
static fl_ukf_cov_t random_cov(ukf_ref_rng_t *r)
{
    for (;;) {
        int32_t c[6];
        fl_ukf_cov_t p;
        ukf_ref_random_cov(r, 10, 5000, 91, 32768, 0.95, c);
        p = from6(c);
        if (fl_ukf_cov_valid(&p, &LIM1))
            return p;
    }
}

/* ---- Cholesky, inverse, ln ------------------------------------------------------- */

static void test_chol_exact(void)
{
    ukf_ref_rng_t r = {12345u};
    int i, worst[6] = {0, 0, 0, 0, 0, 0}, n = t_quick ? 2000 : 20000;
    double rel[6] = {0, 0, 0, 0, 0, 0};
    fl_ukf_chol_t l;
    fl_ukf_cov_t p;
    for (i = 0; i < n; i++) {
        double d[3][3], dl[3][3];
        int32_t c[6], got[6], k;
        p = random_cov(&r);
        to6(&p, c);
        ukf_ref_from6(c, d);
        CHECK_EQ(fl_ukf_chol3(&p, &l), FL_OK);
        CHECK(ukf_ref_chol(d, dl));
        got[0] = l.l11; got[1] = l.l21; got[2] = l.l31; got[3] = l.l22; got[4] = l.l32; got[5] = l.l33;
        {
            double want[6] = {dl[0][0], dl[1][0], dl[2][0], dl[1][1], dl[2][1], dl[2][2]};
            static const int row[6] = {0, 1, 2, 1, 2, 2};
            for (k = 0; k < 6; k++) {
                int e = abs(got[k] - (int32_t)llround(256.0 * want[k]));
                double sd = 256.0 * sqrt(d[row[k]][row[k]]);
                if (e > worst[k])
                    worst[k] = e;
                if ((e - 1) / sd > rel[k])
                    rel[k] = (e - 1) / sd;
            }
        }
    }
    t_info("chol3 vs round(256 L) of double: max LSB l11 %d l21 %d l31 %d l22 %d l32 %d l33 %d",
           worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]);
    t_info("chol3 beyond 1 LSB, relative to the row's sd: l21 %.1e l31 %.1e l22 %.1e l32 %.1e l33 %.1e",
           rel[1], rel[2], rel[3], rel[4], rel[5]);
    /* l11 = round(sqrt(xx) 256) exactly; l21, l22 within 1 LSB; l31, l32, l33
     * (through products of the Q16 intermediates) within 1 LSB + 4e-6 of
     * their row's standard deviation (correlations up to 0.95 between
     * scales 500 times apart; measured 3.1e-6) */
    CHECK_EQ(worst[0], 0);
    CHECK_LE(worst[1], 1);
    CHECK_LE(worst[3], 1);
    for (i = 0; i < 6; i++)
        CHECK_LE(rel[i], 4e-6);
    /* moderate correlations (|rho| <= 0.5): every entry within 1 LSB */
    memset(worst, 0, sizeof worst);
    for (i = 0; i < n; i++) {
        int32_t c[6], got[6], k;
        double d[3][3], dl[3][3];
        do {
            ukf_ref_random_cov(&r, 10, 5000, 91, 32768, 0.5, c);
            p = from6(c);
        } while (!fl_ukf_cov_valid(&p, &LIM1));
        ukf_ref_from6(c, d);
        CHECK_EQ(fl_ukf_chol3(&p, &l), FL_OK);
        CHECK(ukf_ref_chol(d, dl));
        got[0] = l.l11; got[1] = l.l21; got[2] = l.l31; got[3] = l.l22; got[4] = l.l32; got[5] = l.l33;
        {
            double want[6] = {dl[0][0], dl[1][0], dl[2][0], dl[1][1], dl[2][1], dl[2][2]};
            for (k = 0; k < 6; k++) {
                int e = abs(got[k] - (int32_t)llround(256.0 * want[k]));
                if (e > worst[k])
                    worst[k] = e;
            }
        }
    }
    t_info("chol3, |rho| <= 0.5: max LSB l11 %d l21 %d l31 %d l22 %d l32 %d l33 %d",
           worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]);
    for (i = 0; i < 6; i++)
        CHECK_LE(worst[i], 1);
    /* a diagonal matrix: exact */
    p.xx = 100; p.yy = 40000; p.tt = 8281; p.xy = p.xt = p.yt = 0;
    CHECK_EQ(fl_ukf_chol3(&p, &l), FL_OK);
    CHECK_EQ(l.l11, 2560); CHECK_EQ(l.l22, 51200); CHECK_EQ(l.l33, 91 * 256);
    CHECK_EQ(l.l21, 0); CHECK_EQ(l.l31, 0); CHECK_EQ(l.l32, 0);
    /* singular (xy^2 = xx yy): FL_ERR_RANGE and the diagonal's factor */
    p.xy = 2000;
    CHECK_EQ(fl_ukf_chol3(&p, &l), FL_ERR_RANGE);
    CHECK_EQ(l.l11, 2560); CHECK_EQ(l.l22, 51200); CHECK_EQ(l.l33, 91 * 256); CHECK_EQ(l.l21, 0);
    p.xy = 0; p.xx = -5;
    CHECK_EQ(fl_ukf_chol3(&p, &l), FL_ERR_RANGE);
    CHECK_EQ(l.l11, 0);
    CHECK_EQ(fl_ukf_chol3(NULL, &l), FL_ERR_NULL);
    CHECK_EQ(fl_ukf_chol3(&p, NULL), FL_ERR_NULL);
    p.xx = p.yy = p.tt = INT32_MAX; p.xy = p.xt = p.yt = INT32_MIN;
    CHECK_EQ(fl_ukf_chol3(&p, &l), FL_ERR_RANGE);
}

static void test_inv2_exact(void)
{
    ukf_ref_rng_t r = {777u};
    int i, n = 0;
    int64_t ia, ib, ic, det;
    for (i = 0; i < 20000; i++) {
        int64_t a = (int64_t)(ukf_ref_unif(&r) * INT32_MAX) + 1;
        int64_t c = (int64_t)(ukf_ref_unif(&r) * INT32_MAX) + 1;
        int64_t b = (int64_t)((2 * ukf_ref_unif(&r) - 1) * sqrt((double)a * (double)c));
        if (i % 4 == 0) {           /* small entries too */
            a >>= 20; c >>= 20; b >>= 20;
            a++; c++;
        }
        if (fl_ukf_inv2(a, b, c, &ia, &ib, &ic, &det)) {
            n++;
            /* [a b; b c] [ia ib; ib ic] = det I, exactly */
            CHECK(a * ia + b * ib == det && a * ib + b * ic == 0 && b * ia + c * ib == 0 &&
                  b * ib + c * ic == det && det == a * c - b * b && det > 0);
        } else {
            CHECK(a * c - b * b <= 0);
            CHECK(ia == 0 && ib == 0 && ic == 0 && det == 0);
        }
    }
    t_info("inv2: %d of 20000 random symmetric matrices inverted (det > 0), all exact", n);
    CHECK(n > 19000);
    CHECK(!fl_ukf_inv2(1, 1, 1, &ia, &ib, &ic, &det));            /* det 0 */
    CHECK(fl_ukf_inv2(-4, 0, -4, &ia, &ib, &ic, &det) && det == 16);  /* exact for any det > 0 */
    CHECK(fl_ukf_inv2(INT32_MAX, INT32_MAX - 1, INT32_MAX, &ia, &ib, &ic, &det));
    CHECK_EQ(det, (int64_t)INT32_MAX * INT32_MAX - (int64_t)(INT32_MAX - 1) * (INT32_MAX - 1));
    CHECK(!fl_ukf_inv2((int64_t)INT32_MAX + 1, 0, 1, &ia, &ib, &ic, &det));
    CHECK(det == 0 && ia == 0);
    CHECK(!fl_ukf_inv2(INT64_MIN, INT64_MIN, INT64_MAX, NULL, NULL, NULL, NULL));
    CHECK(fl_ukf_inv2(3, -1, 2, NULL, NULL, NULL, &det) && det == 5);
}

static void test_ln(void)
{
    uint64_t x;
    int worst = 0, i;
    ukf_ref_rng_t r = {99u};
    CHECK_EQ(fl_ukf_ln_q8(0), 0);
    CHECK_EQ(fl_ukf_ln_q8(1), 0);
    for (x = 1; x < 70000; x += 1 + x / 64) {
        int e = abs(fl_ukf_ln_q8(x) - (int)lround(256.0 * log((double)x)));
        if (e > worst)
            worst = e;
    }
    for (i = 0; i < 20000; i++) {
        uint64_t v = ((uint64_t)(ukf_ref_unif(&r) * 4294967296.0) << 32 |
                      (uint64_t)(ukf_ref_unif(&r) * 4294967296.0)) >> (i % 64);
        int e;
        if (v == 0)
            continue;
        e = abs(fl_ukf_ln_q8(v) - (int)lround(256.0 * log((double)v)));
        if (e > worst)
            worst = e;
    }
    t_info("ln_q8: max %d LSB from round(256 ln x)", worst);
    CHECK_LE(worst, 1);
    CHECK_EQ(fl_ukf_ln_q8(UINT64_MAX), (int32_t)lround(256.0 * 64 * log(2.0)));
}

/* ---- repair --------------------------------------------------------------------- */

static void test_repair(void)
{
    fl_ukf_limits_t lim = {25, 100};
    fl_ukf_repairs_t rep = {0, 0, 0};
    fl_ukf_cov_t p = {10000, 500, 200, 20000, -300, 4000}, q;
    q = p;
    CHECK(fl_ukf_cov_valid(&p, &lim));
    CHECK(fl_ukf_cov_repair(&p, &lim, &rep));                 /* valid: untouched */
    CHECK(!memcmp(&p, &q, sizeof p));
    CHECK(rep.floors == 0 && rep.caps == 0 && rep.not_pd == 0);
    /* a diagonal below its floor */
    p.xx = 3;
    p.xy = p.xt = 0;
    CHECK(!fl_ukf_cov_valid(&p, &lim));
    CHECK(!fl_ukf_cov_repair(&p, &lim, &rep));
    CHECK_EQ(rep.floors, 1);
    CHECK_EQ(p.xx, 25);
    CHECK(fl_ukf_cov_valid(&p, &lim));
    /* beyond the caps */
    p.yy = INT32_MAX;
    p.tt = INT32_MAX;
    CHECK(!fl_ukf_cov_repair(&p, &lim, &rep));
    CHECK_EQ(rep.caps, 2);
    CHECK(p.yy == FL_UKF_VAR_MM2_MAX && p.tt == FL_UKF_VAR_ANG2_MAX);
    CHECK(fl_ukf_cov_valid(&p, &lim));
    /* a covariance beyond Cauchy-Schwarz, then singular: clamped, pivot raised */
    p.xx = 10000; p.yy = 10000; p.tt = 10000; p.xy = 20000; p.xt = 0; p.yt = 0;
    memset(&rep, 0, sizeof rep);
    CHECK(!fl_ukf_cov_repair(&p, &lim, &rep));
    CHECK_EQ(rep.caps, 1);
    CHECK_EQ(rep.not_pd, 1);
    CHECK_EQ(p.xy, 10000);
    CHECK_EQ(p.yy, 10025);                                    /* y given x: the floor */
    CHECK(fl_ukf_cov_valid(&p, &lim));
    /* heading given x and y below its floor: tt raised by the deficit */
    p.xx = 10000; p.xy = 0; p.yy = 10000; p.xt = 9000; p.yt = 4000; p.tt = 9750;
    memset(&rep, 0, sizeof rep);
    CHECK(!fl_ukf_cov_valid(&p, &lim));
    CHECK(!fl_ukf_cov_repair(&p, &lim, &rep));
    CHECK_EQ(rep.not_pd, 1);
    CHECK_EQ(p.tt, 9800);                                     /* 9000^2/1e4 + 4000^2/1e4 + 100 */
    CHECK(p.xt == 9000 && p.yt == 4000);
    CHECK(fl_ukf_cov_valid(&p, &lim));
    /* at the caps and singular: the diagonal alone */
    p.xx = FL_UKF_VAR_MM2_MAX; p.yy = FL_UKF_VAR_MM2_MAX; p.xy = FL_UKF_VAR_MM2_MAX;
    p.xt = p.yt = 0; p.tt = 100;
    memset(&rep, 0, sizeof rep);
    CHECK(!fl_ukf_cov_repair(&p, &lim, &rep));
    CHECK_EQ(rep.not_pd, 1);
    CHECK(p.xy == 0 && p.xt == 0 && p.yt == 0 && p.yy == FL_UKF_VAR_MM2_MAX);
    CHECK(fl_ukf_cov_valid(&p, &lim));
    /* garbage in every entry, many times: valid afterwards */
    {
        ukf_ref_rng_t r = {4242u};
        int i, bad = 0;
        for (i = 0; i < 20000; i++) {
            int32_t c[6], k;
            for (k = 0; k < 6; k++)
                c[k] = (int32_t)(uint32_t)(ukf_ref_unif(&r) * 4294967296.0) >> (i % 31);
            p = from6(c);
            fl_ukf_cov_repair(&p, &lim, &rep);
            bad += !fl_ukf_cov_valid(&p, &lim);
        }
        CHECK_EQ(bad, 0);
    }
    CHECK(!fl_ukf_cov_repair(NULL, &lim, &rep));
    CHECK(!fl_ukf_cov_valid(NULL, &lim));
    /* NULL limits: floors of 1 */
    p.xx = 0; p.yy = 1; p.tt = 1; p.xy = p.xt = p.yt = 0;
    CHECK(!fl_ukf_cov_valid(&p, NULL));
    CHECK(!fl_ukf_cov_repair(&p, NULL, NULL));
    CHECK(fl_ukf_cov_valid(&p, NULL) && p.xx == 1);
}

/* ---- predict and update against the double reference ----------------------------- */

typedef struct {
    fl_ukf_pose_t m;
    fl_ukf_cov_t p;
} ukf_case_t;

static ukf_case_t random_state(ukf_ref_rng_t *r)
{
    ukf_case_t c;
    c.m.x_mm = (int32_t)lround((2 * ukf_ref_unif(r) - 1) * 5000);
    c.m.y_mm = (int32_t)lround((2 * ukf_ref_unif(r) - 1) * 3500);
    c.m.heading = (fl_angle_t)(int32_t)lround(ukf_ref_unif(r) * 65535 - 32768);
    c.p = random_cov(r);
    return c;
}

static void ref_of(const ukf_case_t *c, ukf_ref_pose_t *m, double p[3][3])
{
    int32_t v[6];
    m->x = c->m.x_mm;
    m->y = c->m.y_mm;
    m->t = c->m.heading;
    to6(&c->p, v);
    ukf_ref_from6(v, p);
}

typedef struct {
    double *mean, *head, *cov, *nll;
    int n, skipped;
} ukf_errs_t;

static void errs_alloc(ukf_errs_t *e, int n)
{
    e->mean = calloc((size_t)n, sizeof(double));
    e->head = calloc((size_t)n, sizeof(double));
    e->cov = calloc((size_t)n, sizeof(double));
    e->nll = calloc((size_t)n, sizeof(double));
    e->n = e->skipped = 0;
}

static void errs_free(ukf_errs_t *e)
{
    free(e->mean); free(e->head); free(e->cov); free(e->nll);
}

static void errs_add(ukf_errs_t *e, const ukf_case_t *got, const ukf_ref_pose_t *rm,
                     double rp[3][3], double nll_err)
{
    ukf_ref_err_t x;
    int32_t v[6];
    to6(&got->p, v);
    ukf_ref_compare(rm, rp, got->m.x_mm, got->m.y_mm, got->m.heading, v, &x);
    e->mean[e->n] = x.mean_mm;
    e->head[e->n] = x.heading_deg;
    e->cov[e->n] = x.cov_rel;
    e->nll[e->n] = nll_err;
    e->n++;
}

/* An observation of a random map point from a pose drawn near the mean. */
typedef struct {
    int32_t lx, ly, range, sd_r;
    fl_angle_t bearing, sd_b;
} ukf_obs_t;

static ukf_obs_t random_obs(ukf_ref_rng_t *r, const ukf_case_t *c)
{
    ukf_obs_t o;
    double l[3][3], p[3][3], g[3], tx, ty, tt, rr, b;
    int32_t v[6];
    int k;
    to6(&c->p, v);
    ukf_ref_from6(v, p);
    ukf_ref_chol(p, l);
    for (k = 0; k < 3; k++) {
        g[k] = ukf_ref_gauss(r);
        g[k] = g[k] > 2 ? 2 : g[k] < -2 ? -2 : g[k];
    }
    tx = c->m.x_mm + l[0][0] * g[0];
    ty = c->m.y_mm + l[1][0] * g[0] + l[1][1] * g[1];
    tt = c->m.heading + l[2][0] * g[0] + l[2][1] * g[1] + l[2][2] * g[2];
    o.lx = (int32_t)lround((2 * ukf_ref_unif(r) - 1) * 5200);
    o.ly = (int32_t)lround((2 * ukf_ref_unif(r) - 1) * 3700);
    rr = hypot(o.lx - tx, o.ly - ty);
    o.sd_r = (int32_t)lround(10 + 290 * ukf_ref_unif(r) + 0.05 * rr);
    o.sd_b = (fl_angle_t)lround((0.5 + 7.5 * ukf_ref_unif(r)) * 65536 / 360);
    rr += o.sd_r * ukf_ref_gauss(r);
    o.range = (int32_t)lround(rr < 0 ? 0 : rr > FL_OBS_MAX_RANGE_MM ? FL_OBS_MAX_RANGE_MM : rr);
    b = atan2(o.ly - ty, o.lx - tx) * 32768 / M_PI - tt + o.sd_b * ukf_ref_gauss(r);
    o.bearing = (fl_angle_t)lround(ukf_ref_wrap(b) >= 32767.5 ? -32768 : ukf_ref_wrap(b));
    return o;
}

static void report(const char *what, ukf_errs_t *e, double *p99)
{
    double m50 = quantile(e->mean, e->n, 0.5), m99 = quantile(e->mean, e->n, 0.99);
    double h50 = quantile(e->head, e->n, 0.5), h99 = quantile(e->head, e->n, 0.99);
    double c50 = quantile(e->cov, e->n, 0.5), c99 = quantile(e->cov, e->n, 0.99);
    double n99 = quantile(e->nll, e->n, 0.99);
    t_info("%s vs double (%d cases, %d skipped: repaired): mean p50 %.3f p99 %.3f max %.3f mm; "
           "heading p50 %.4f p99 %.4f max %.4f deg; cov rel p50 %.2e p99 %.2e max %.2e; "
           "nll p99 %.2f max %.2f Q8",
           what, e->n, e->skipped, m50, m99, e->mean[e->n - 1], h50, h99, e->head[e->n - 1],
           c50, c99, e->cov[e->n - 1], n99, e->nll[e->n - 1]);
    p99[0] = m99; p99[1] = e->mean[e->n - 1];
    p99[2] = h99; p99[3] = e->head[e->n - 1];
    p99[4] = c99; p99[5] = e->cov[e->n - 1];
    p99[6] = n99; p99[7] = e->nll[e->n - 1];
}

static void test_predict_vs_double(void)
{
    ukf_ref_rng_t r = {2024u};
    ukf_errs_t e;
    int i, n = 3000;
    double s[8];
    errs_alloc(&e, n);
    for (i = 0; i < n; i++) {
        ukf_case_t c = random_state(&r);
        ukf_ref_pose_t rm;
        double rp[3][3], q[3][3];
        fl_ukf_cov_t fq;
        fl_ukf_repairs_t rep = {0, 0, 0};
        int32_t dx = (int32_t)lround((2 * ukf_ref_unif(&r) - 1) * (i % 10 == 0 ? 20000 : 400));
        int32_t dy = (int32_t)lround((2 * ukf_ref_unif(&r) - 1) * (i % 10 == 0 ? 20000 : 200));
        fl_angle_t dth = (fl_angle_t)lround((2 * ukf_ref_unif(&r) - 1) * 6000);
        int32_t qv[6];
        qv[0] = (int32_t)(25 + 0.01 * dx * dx); qv[3] = (int32_t)(25 + 0.01 * dy * dy);
        qv[1] = qv[2] = qv[4] = 0;
        qv[5] = (int32_t)(100 + 0.01 * dth * dth);
        fq = from6(qv);
        ukf_ref_from6(qv, q);
        ref_of(&c, &rm, rp);
        if (i & 1) {                  /* the struct form, the same step */
            fl_ukf_odo_t od;
            od.dx_mm = dx;
            od.dy_mm = dy;
            od.dtheta = dth;
            CHECK_EQ(fl_ukf_predict_odo(&c.m, &c.p, &od, &fq, &LIM1, &rep), FL_OK);
        } else {
            CHECK_EQ(fl_ukf_predict(&c.m, &c.p, dx, dy, dth, &fq, &LIM1, &rep), FL_OK);
        }
        CHECK(ukf_ref_predict(&rm, rp, dx, dy, dth, q));
        CHECK(fl_ukf_cov_valid(&c.p, &LIM1));
        if (rep.floors || rep.caps || rep.not_pd)
            e.skipped++;
        else
            errs_add(&e, &c, &rm, rp, 0);
    }
    report("predict", &e, s);
    CHECK(e.skipped <= n / 50);       /* the heading variance at its cap plus the noise */
    /* the mean rounded to the integer mm (<= 0.71); the heading moves by
     * dtheta exactly; covariance: measured p99 9e-7, max 3.1e-6 */
    CHECK_LE(s[1], 0.75);
    CHECK_LE(s[3], 0.003);
    CHECK_LE(s[4], 1e-5);
    CHECK_LE(s[5], 2e-5);
    errs_free(&e);
}

static void test_update_vs_double(void)
{
    ukf_ref_rng_t r = {31337u};
    ukf_errs_t e;
    int i, n = 4000;
    double s[8];
    errs_alloc(&e, n);
    for (i = 0; i < n; i++) {
        ukf_case_t c = random_state(&r);
        ukf_obs_t o = random_obs(&r, &c);
        ukf_ref_pose_t rm;
        double rp[3][3], rnll;
        fl_ukf_repairs_t rep = {0, 0, 0};
        uint32_t nll = 0;
        ref_of(&c, &rm, rp);
        if (i & 1) {                  /* the struct form, the same step */
            fl_ukf_obs_t ob;
            ob.lx_mm = o.lx;
            ob.ly_mm = o.ly;
            ob.range_mm = o.range;
            ob.bearing = o.bearing;
            ob.sd_range_mm = o.sd_r;
            ob.sd_bearing = o.sd_b;
            CHECK_EQ(fl_ukf_update_obs(&c.m, &c.p, &ob, &LIM1, &rep, &nll), FL_OK);
        } else {
            CHECK_EQ(fl_ukf_update(&c.m, &c.p, o.lx, o.ly, o.range, o.bearing, o.sd_r, o.sd_b,
                                   &LIM1, &rep, &nll), FL_OK);
        }
        CHECK(ukf_ref_update(&rm, rp, o.lx, o.ly, o.range, o.bearing, o.sd_r, o.sd_b, &rnll));
        CHECK(fl_ukf_cov_valid(&c.p, &LIM1));
        if (rep.floors || rep.caps || rep.not_pd)
            e.skipped++;
        else
            errs_add(&e, &c, &rm, rp, fabs(nll - (rnll < 0 ? 0 : rnll)));
    }
    report("update", &e, s);
    CHECK(e.skipped <= n / 100);
    /* measured: mean max 0.70 mm (the rounding to integer mm), heading p99
     * 0.0028 max 0.0035 deg (rounding to the unit, 0.0055 deg), covariance
     * p99 1.3e-4 max 3.5e-3 (the prior's 1e-7 left by the cancellation of
     * sharp observations), nll p99 0.51 max 0.54 Q8 (the output's rounding) */
    CHECK_LE(s[1], 0.75);
    CHECK_LE(s[2], 0.005);
    CHECK_LE(s[3], 0.01);
    CHECK_LE(s[4], 5e-4);
    CHECK_LE(s[5], 1e-2);
    CHECK_LE(s[6], 1.0);
    CHECK_LE(s[7], 2.0);
    errs_free(&e);
}

/* ---- bit-identical outputs (inputs from integers only: the same on every
 * target, so `make cross-test` compares the digests) ---------------------- */

static void test_digest(void)
{
    t_rng_t r;
    fl_ukf_limits_t lim = {25, 1296};
    fl_ukf_repairs_t rep = {0, 0, 0};
    uint32_t h = t_hash_init(), nll;
    int i;
    t_rng_seed(&r, 77);
    for (i = 0; i < 400; i++) {
        int32_t l11 = t_rng_range(&r, 10, 5000), l21 = t_rng_range(&r, -3000, 3000);
        int32_t l22 = t_rng_range(&r, 10, 4000), l31 = t_rng_range(&r, -15000, 15000);
        int32_t l32 = t_rng_range(&r, -15000, 15000), l33 = t_rng_range(&r, 30, 15000);
        fl_ukf_cov_t p;
        fl_ukf_pose_t m;
        int k;
        p.xx = l11 * l11;
        p.xy = l11 * l21;
        p.xt = l11 * l31;
        p.yy = l21 * l21 + l22 * l22;
        p.yt = l21 * l31 + l22 * l32;
        p.tt = l31 * l31 + l32 * l32 + l33 * l33;
        m.x_mm = t_rng_range(&r, -5000, 5000);
        m.y_mm = t_rng_range(&r, -3500, 3500);
        m.heading = (fl_angle_t)t_rng_range(&r, -32768, 32767);
        for (k = 0; k < 8; k++) {
            int32_t a[6], j;
            /* drawn in order first (argument evaluation order is unspecified) */
            for (j = 0; j < 6; j++)
                a[j] = t_rng_range(&r, k % 2 == 0 ? -2000 : -5200, k % 2 == 0 ? 2000 : 5200);
            if (k % 2 == 0) {
                fl_ukf_cov_t q = {400, 0, 0, 400, 0, 2000};
                fl_ukf_predict(&m, &p, a[0] / 8 + 125, a[1] / 20, (fl_angle_t)a[2], &q, &lim, &rep);
            } else {
                fl_ukf_update(&m, &p, a[0], a[1] * 37 / 52, (a[2] + 5200) * 9 / 10,
                              (fl_angle_t)(a[3] * 6), 10 + (a[4] + 5200) / 12,
                              (fl_angle_t)(90 + (a[5] + 5200) / 12), &lim, &rep, &nll);
                h = t_hash_i32(h, (int32_t)nll);
            }
            h = t_hash_i32(h, m.x_mm);
            h = t_hash_i32(h, m.y_mm);
            h = t_hash_i32(h, m.heading);
            h = t_hash_i32(h, p.xx);
            h = t_hash_i32(h, p.xy);
            h = t_hash_i32(h, p.xt);
            h = t_hash_i32(h, p.yy);
            h = t_hash_i32(h, p.yt);
            h = t_hash_i32(h, p.tt);
            CHECK(fl_ukf_cov_valid(&p, &lim));
        }
        h = t_hash_i32(h, (int32_t)fl_ukf_gauss_nll_q8(&m, &p, &m));
    }
    h = t_hash_i32(h, (int32_t)rep.floors);
    h = t_hash_i32(h, (int32_t)rep.caps);
    h = t_hash_i32(h, (int32_t)rep.not_pd);
    t_digest("ukf.steps", h);
}

/* ---- extreme inputs ------------------------------------------------------------------ */

static bool in_box(const fl_ukf_pose_t *m)
{
    return m->x_mm >= -FL_UKF_POS_MAX_MM && m->x_mm <= FL_UKF_POS_MAX_MM &&
           m->y_mm >= -FL_UKF_POS_MAX_MM && m->y_mm <= FL_UKF_POS_MAX_MM;
}

static void test_extremes(void)
{
    fl_ukf_limits_t lim = {25, 30};
    fl_ukf_repairs_t rep = {0, 0, 0};
    fl_ukf_pose_t m = {1000, -500, 0}, m0;
    fl_ukf_cov_t p = {10000, 0, 0, 10000, 0, 3000}, p0;
    uint32_t nll = 0, off = 0;
    ukf_ref_rng_t r = {555u};
    int i, bad = 0;
    /* NULLs */
    CHECK_EQ(fl_ukf_predict(NULL, &p, 0, 0, 0, NULL, &lim, &rep), FL_ERR_NULL);
    CHECK_EQ(fl_ukf_predict(&m, NULL, 0, 0, 0, NULL, &lim, &rep), FL_ERR_NULL);
    CHECK_EQ(fl_ukf_update(NULL, &p, 0, 0, 100, 0, 10, 100, &lim, &rep, &nll), FL_ERR_NULL);
    CHECK_EQ(nll, UINT32_MAX);
    CHECK_EQ(fl_ukf_update(&m, NULL, 0, 0, 100, 0, 10, 100, &lim, &rep, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_ukf_update_obs(&m, &p, NULL, &lim, &rep, &nll), FL_ERR_NULL);
    CHECK_EQ(fl_ukf_predict_odo(&m, &p, NULL, NULL, &lim, &rep), FL_ERR_NULL);
    CHECK_EQ(fl_ukf_predict(&m, &p, 100, 0, 0, NULL, NULL, NULL), FL_OK);
    CHECK_EQ(fl_ukf_update(&m, &p, 3000, 0, 2000, 0, 50, 300, NULL, NULL, NULL), FL_OK);
    CHECK(fl_ukf_cov_valid(&p, NULL));
    CHECK_EQ(fl_ukf_gauss_nll_q8(NULL, &p, &m), UINT32_MAX);
    CHECK(!fl_ukf_sample(&m, NULL, NULL, &m0));
    CHECK(!fl_ukf_sample(&m, &p, NULL, NULL));
    /* out-of-range arguments: statuses, nothing moved */
    m.x_mm = 1000; m.y_mm = -500; m.heading = 0;
    p.xx = 10000; p.xy = 0; p.xt = 0; p.yy = 10000; p.yt = 0; p.tt = 3000;
    m0 = m; p0 = p;
    CHECK_EQ(fl_ukf_predict(&m, &p, FL_OBS_MAX_RANGE_MM + 1, 0, 0, NULL, &lim, &rep), FL_ERR_RANGE);
    CHECK_EQ(fl_ukf_predict(&m, &p, 0, INT32_MIN, 0, NULL, &lim, &rep), FL_ERR_RANGE);
    CHECK_EQ(fl_ukf_update(&m, &p, 0, 0, -1, 0, 10, 100, &lim, &rep, &nll), FL_ERR_RANGE);
    CHECK_EQ(nll, UINT32_MAX);
    CHECK_EQ(fl_ukf_update(&m, &p, 0, 0, FL_OBS_MAX_RANGE_MM + 1, 0, 10, 100, &lim, &rep, &nll),
             FL_ERR_RANGE);
    CHECK_EQ(fl_ukf_update(&m, &p, 0, 0, 100, 0, 0, 100, &lim, &rep, &nll), FL_ERR_RANGE);
    CHECK_EQ(fl_ukf_update(&m, &p, 0, 0, 100, 0, 10, 0, &lim, &rep, &nll), FL_ERR_RANGE);
    CHECK_EQ(fl_ukf_update(&m, &p, 0, 0, 100, 0, 10, -5, &lim, &rep, &nll), FL_ERR_RANGE);
    CHECK_EQ(fl_ukf_update(&m, &p, INT32_MAX, 0, 100, 0, 10, 100, &lim, &rep, &nll), FL_ERR_RANGE);
    /* field by field: the pose struct has padding after the heading,
     * which memcmp would read uninitialised */
    CHECK(m.x_mm == m0.x_mm && m.y_mm == m0.y_mm && m.heading == m0.heading);
    CHECK(!memcmp(&p, &p0, sizeof p));
    CHECK(rep.floors == 0 && rep.caps == 0 && rep.not_pd == 0);
    /* ranges 0 and the largest; the map point on the mean */
    CHECK_EQ(fl_ukf_update(&m, &p, 1000, -500, 0, 0, 10, 100, &lim, &rep, &nll), FL_OK);
    CHECK(fl_ukf_cov_valid(&p, &lim));
    CHECK_EQ(fl_ukf_update(&m, &p, -15000, 10000, FL_OBS_MAX_RANGE_MM, 0, 10, 100, &lim, &rep,
                           &nll), FL_OK);
    CHECK(fl_ukf_cov_valid(&p, &lim));
    /* bearings at +-180 deg: the map point straight behind; both ends of the
     * binary angle are the same direction, the innovation is 0, the mean
     * stays (a missing wrap would throw it by a turn's worth of gain; the
     * predicted range is above 3000 by the points' spread, hence x moves a
     * few mm towards the point) */
    for (i = 0; i < 3; i++) {
        fl_ukf_pose_t mm = {0, 0, 0};
        fl_ukf_cov_t pp = {40000, 0, 0, 40000, 0, 300000};
        fl_angle_t b = i == 0 ? (fl_angle_t)32767 : i == 1 ? (fl_angle_t)-32768 : (fl_angle_t)16384;
        CHECK_EQ(fl_ukf_update(&mm, &pp, -3000, 0, 3000, b, 30, 200, &lim, &rep, &nll), FL_OK);
        CHECK(fl_ukf_cov_valid(&pp, &lim));
        if (i < 2) {
            CHECK(mm.x_mm <= 0 && mm.x_mm >= -8 && abs(mm.y_mm) <= 1 && abs(mm.heading) <= 2);
            off = nll;
        } else {
            CHECK(nll > off + 256 * 5);          /* 90 deg off: far less likely */
        }
    }
    /* heading near +-180 deg, map point ahead */
    {
        fl_ukf_pose_t mm = {0, 0, (fl_angle_t)-32768};
        fl_ukf_cov_t pp = {40000, 0, 0, 40000, 0, 300000};
        CHECK_EQ(fl_ukf_update(&mm, &pp, -3000, 10, 3000, 0, 30, 200, &lim, &rep, &nll), FL_OK);
        CHECK(abs(mm.x_mm) <= 8 && abs(mm.y_mm) <= 15);
        CHECK(mm.heading <= -32768 + 40 || mm.heading >= 32767 - 40);
    }
    /* the caps themselves: tt = 2^30 puts its pivot at 2^62 (Q32) */
    {
        fl_ukf_cov_t pc = {FL_UKF_VAR_MM2_MAX, 0, 0, FL_UKF_VAR_MM2_MAX, 0, FL_UKF_VAR_ANG2_MAX};
        fl_ukf_limits_t lc = {FL_UKF_VAR_MM2_MAX, FL_UKF_VAR_ANG2_MAX};
        fl_ukf_chol_t lq;
        CHECK(fl_ukf_cov_valid(&pc, &lc));
        CHECK_EQ(fl_ukf_chol3(&pc, &lq), FL_OK);
        CHECK(lq.l11 == 20000 * 256 && lq.l22 == 20000 * 256 && lq.l33 == 32768 * 256);
        m.x_mm = 0; m.y_mm = 0; m.heading = 0;
        CHECK_EQ(fl_ukf_predict(&m, &pc, 20000, -20000, 100, &pc, &lc, &rep), FL_OK);
        CHECK(fl_ukf_cov_valid(&pc, &lc));
        CHECK_EQ(fl_ukf_update(&m, &pc, 1000, 1000, 20000, -32768, 65535, 32767, &lc, &rep, &nll),
                 FL_OK);
        CHECK(fl_ukf_cov_valid(&pc, &lc));
    }
    /* zero, negative, huge, INT32 extremes everywhere: valid outputs */
    for (i = 0; i < (t_quick ? 3000 : 20000); i++) {
        int32_t v[16], k;
        fl_ukf_cov_t q;
        fl_angle_t b, sdb;
        for (k = 0; k < 16; k++) {
            uint32_t u = (uint32_t)(ukf_ref_unif(&r) * 4294967296.0);
            int kind = (int)(ukf_ref_unif(&r) * 6);
            v[k] = kind == 0 ? INT32_MIN : kind == 1 ? INT32_MAX : kind == 2 ? 0 :
                   kind == 3 ? (int32_t)(u % 40001u) - 20000 : (int32_t)u;
        }
        m.x_mm = v[0]; m.y_mm = v[1]; m.heading = (fl_angle_t)(v[2] % 32768);
        p.xx = v[3]; p.xy = v[4]; p.xt = v[5]; p.yy = v[6]; p.yt = v[7]; p.tt = v[8];
        q.xx = v[9]; q.xy = v[10]; q.xt = v[11]; q.yy = v[12]; q.yt = v[13]; q.tt = v[14];
        b = (fl_angle_t)(v[15] % 32768);
        sdb = (fl_angle_t)((v[15] / 65536) % 32768);
        if (i & 1)
            fl_ukf_predict(&m, &p, v[9] % 20001, v[10] % 20001, b, &q, &lim, &rep);
        else
            fl_ukf_update(&m, &p, v[9] % 1000001, v[10] % 1000001, v[11] % 20001, b,
                          v[12] % 100000, sdb, &lim, &rep, &nll);
        bad += !fl_ukf_cov_valid(&p, &lim) || !in_box(&m);
    }
    CHECK_EQ(bad, 0);
}

/* ---- draws and the density -------------------------------------------------------------- */

static void test_sample(void)
{
    fl_ukf_pose_t m = {1200, -800, 32000}, x;
    fl_ukf_cov_t p = {90000, 30000, 20000, 40000, -8000, 250000};
    double sum[3] = {0, 0, 0}, sq[3][3] = {{0}}, want[3][3];
    uint32_t rng = 7u, h = t_hash_init();
    int i, a, b, n = 40000;
    int32_t v[6];
    for (i = 0; i < n; i++) {
        double d[3];
        CHECK(fl_ukf_sample(&m, &p, &rng, &x));
        d[0] = x.x_mm - m.x_mm;
        d[1] = x.y_mm - m.y_mm;
        d[2] = (fl_angle_t)(x.heading - m.heading);
        h = t_hash_i32(h, x.x_mm);
        h = t_hash_i32(h, x.heading);
        for (a = 0; a < 3; a++) {
            sum[a] += d[a];
            for (b = 0; b < 3; b++)
                sq[a][b] += d[a] * d[b];
        }
    }
    t_digest("ukf.sample", h);
    to6(&p, v);
    ukf_ref_from6(v, want);
    for (a = 0; a < 3; a++) {
        CHECK_LE(fabs(sum[a] / n), 4 * sqrt(want[a][a] / n));
        for (b = 0; b < 3; b++)
            CHECK_LE(fabs(sq[a][b] / n - want[a][b]), 0.04 * sqrt(want[a][a] * want[b][b]));
    }
    p.xx = -1;
    CHECK(!fl_ukf_sample(&m, &p, &rng, &x));
    CHECK(x.x_mm == m.x_mm && x.heading == m.heading);
}

static void test_gauss_nll(void)
{
    ukf_ref_rng_t r = {8080u};
    int i, worst = 0;
    fl_ukf_cov_t p;
    fl_ukf_pose_t m = {0, 0, 0}, x;
    for (i = 0; i < 5000; i++) {
        double d[3][3], l[3][3], z[3], dv[3], want;
        int32_t v[6], k;
        ukf_case_t c = random_state(&r);
        c.m.heading = (fl_angle_t)(c.m.heading / 2);
        to6(&c.p, v);
        ukf_ref_from6(v, d);
        ukf_ref_chol(d, l);
        for (k = 0; k < 3; k++)
            z[k] = 3 * ukf_ref_gauss(&r);
        x.x_mm = c.m.x_mm + (int32_t)lround(l[0][0] * z[0]);
        x.y_mm = c.m.y_mm + (int32_t)lround(l[1][0] * z[0] + l[1][1] * z[1]);
        x.heading = (fl_angle_t)(c.m.heading + (int32_t)lround(fmod(l[2][0] * z[0] + l[2][1] * z[1] +
                                                                    l[2][2] * z[2], 16000)));
        dv[0] = x.x_mm - c.m.x_mm;
        dv[1] = x.y_mm - c.m.y_mm;
        dv[2] = ukf_ref_wrap(x.heading - c.m.heading);
        /* forward substitution in double */
        z[0] = dv[0] / l[0][0];
        z[1] = (dv[1] - l[1][0] * z[0]) / l[1][1];
        z[2] = (dv[2] - l[2][0] * z[0] - l[2][1] * z[1]) / l[2][2];
        want = 256 * (0.5 * (z[0] * z[0] + z[1] * z[1] + z[2] * z[2]) +
                      log(l[0][0] * l[1][1] * l[2][2]));
        k = abs((int)fl_ukf_gauss_nll_q8(&c.m, &c.p, &x) - (int)lround(want));
        if (k > worst)
            worst = k;
    }
    t_info("gauss_nll_q8: max %d LSB from the double value rounded", worst);
    CHECK_LE(worst, 2);
    p.xx = 100; p.yy = 100; p.tt = 100; p.xy = p.xt = p.yt = 0;
    x = m;
    CHECK_EQ(fl_ukf_gauss_nll_q8(&m, &p, &x), (uint32_t)lround(256 * 3 * log(10.0)));
    x.x_mm = INT32_MAX;
    m.x_mm = INT32_MIN;
    CHECK_EQ(fl_ukf_gauss_nll_q8(&m, &p, &x), UINT32_MAX);
    p.xy = 100;
    CHECK_EQ(fl_ukf_gauss_nll_q8(&m, &p, &x), UINT32_MAX);          /* singular */
}

void suite_ukf(void)
{
    t_run("ukf.chol_exact", test_chol_exact);
    t_run("ukf.inv2_exact", test_inv2_exact);
    t_run("ukf.ln", test_ln);
    t_run("ukf.repair", test_repair);
    t_run("ukf.predict_vs_double", test_predict_vs_double);
    t_run("ukf.update_vs_double", test_update_vs_double);
    t_run("ukf.digest", test_digest);
    t_run("ukf.extremes", test_extremes);
    t_run("ukf.sample", test_sample);
    t_run("ukf.gauss_nll", test_gauss_nll);
}
