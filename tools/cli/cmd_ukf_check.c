/*
 * tools/cli/cmd_ukf_check.c - `fieldloc ukf-check [--n N] [--seed S]`: the
 * fixed-point UKF step (ukf.h) against the double reference
 * (tools/eval/ukf_ref.c), step by step, over random filter lives.
 *
 * A life: a robot walks a 10 m field (a 9 x 6 m pitch, 12 map points: the
 * corners, the T and X crossings, the posts); each step it moves by a
 * random odometry (up to 60 mm, 20 mm sideways, 6 deg) with noise, the
 * filter predicts with the process noise of that odometry, then updates
 * with 0 to 3 observations of map points within 8 m (range sd 4-10 % + 10
 * mm, bearing sd 1-4 deg), associated correctly.  Stretches without
 * observations let the covariance grow (the heading up to its cap), a run
 * of observations shrinks it to the floors; kidnaps (the robot moved, the
 * filter not told) give large innovations; a filter far off (2 m, 45 deg)
 * or at random is reset to the true pose with a wide covariance (sd 0.3 to
 * 3 m, 10 to 180 deg).  Each step's input (the fixed-point state before
 * it) also goes through the double step; the errors of the fixed-point
 * result against it are collected for the steps that did not repair
 * (a repair is a floor or a cap the double step does not have; those steps
 * are counted, not compared).  Every covariance is checked with
 * fl_ukf_cov_valid after every step (spd_violations).  cov_rel_err is the
 * largest |P_ij - R_ij| / sqrt(R_ii R_jj) beyond the output's rounding to
 * integers (1/2); cov_rel_err_with_rounding includes it.
 *
 * --fixed-only runs the fixed-point steps alone (for callgrind: the
 * instructions of fl_ukf_predict_odo and fl_ukf_update_obs per call).
 */
#include "fieldloc/ukf.h"
#include "fieldloc/obs.h"
#include "cli/args.h"
#include "cli/registry.h"
#include "eval/ukf_ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const int32_t uc_map[12][2] = {
    {-4500, -3000}, {-4500, 3000}, {4500, -3000}, {4500, 3000}, {0, -3000}, {0, 3000},
    {0, -750},      {0, 750},      {-4500, -800}, {-4500, 800}, {4500, -800}, {4500, 800},
};

typedef struct {
    double *mean, *head, *cov, *nll, *raw;
    long n, cap;
    double nll_worst_at;           /* the reference's nll (Q8) where the nll error is largest */
    double nll_worst;
} uc_errs_t;

static int uc_alloc(uc_errs_t *e, long cap)
{
    e->n = 0;
    e->cap = cap;
    e->nll_worst = e->nll_worst_at = 0;
    e->mean = malloc((size_t)cap * sizeof(double));
    e->head = malloc((size_t)cap * sizeof(double));
    e->cov = malloc((size_t)cap * sizeof(double));
    e->nll = malloc((size_t)cap * sizeof(double));
    e->raw = malloc((size_t)cap * sizeof(double));
    return e->mean && e->head && e->cov && e->nll && e->raw;
}

/* Room for one more (doubling); 0 when out of memory. */
static int uc_room(uc_errs_t *e)
{
    double **v[5];
    int i;
    if (e->n < e->cap)
        return 1;
    v[0] = &e->mean; v[1] = &e->head; v[2] = &e->cov; v[3] = &e->nll; v[4] = &e->raw;
    for (i = 0; i < 5; i++) {
        double *g = realloc(*v[i], (size_t)(2 * e->cap) * sizeof(double));
        if (g == NULL)
            return 0;
        *v[i] = g;
    }
    e->cap *= 2;
    return 1;
}

static void uc_free(uc_errs_t *e)
{
    free(e->mean);
    free(e->head);
    free(e->cov);
    free(e->nll);
    free(e->raw);
}

static int uc_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double uc_q(double *v, long n, double q)
{
    return n > 0 ? v[(long)(q * (double)(n - 1) + 0.5)] : 0.0;
}

static void uc_print(const char *pre, uc_errs_t *e, int with_nll)
{
    qsort(e->mean, (size_t)e->n, sizeof(double), uc_cmp);
    qsort(e->head, (size_t)e->n, sizeof(double), uc_cmp);
    qsort(e->cov, (size_t)e->n, sizeof(double), uc_cmp);
    qsort(e->nll, (size_t)e->n, sizeof(double), uc_cmp);
    qsort(e->raw, (size_t)e->n, sizeof(double), uc_cmp);
    printf("%smean_err_mm_p50/p99/max %.3f %.3f %.3f\n", pre, uc_q(e->mean, e->n, 0.5),
           uc_q(e->mean, e->n, 0.99), uc_q(e->mean, e->n, 1));
    printf("%sheading_err_deg_p50/p99/max %.4f %.4f %.4f\n", pre, uc_q(e->head, e->n, 0.5),
           uc_q(e->head, e->n, 0.99), uc_q(e->head, e->n, 1));
    printf("%scov_rel_err_p50/p99/max %.2e %.2e %.2e\n", pre, uc_q(e->cov, e->n, 0.5),
           uc_q(e->cov, e->n, 0.99), uc_q(e->cov, e->n, 1));
    printf("%scov_rel_err_with_rounding_p50/p99/max %.2e %.2e %.2e\n", pre,
           uc_q(e->raw, e->n, 0.5), uc_q(e->raw, e->n, 0.99), uc_q(e->raw, e->n, 1));
    if (with_nll)
        printf("%snll_err_q8_p99/max %.2f %.2f (the largest at nll %.0f Q8)\n", pre,
               uc_q(e->nll, e->n, 0.99), uc_q(e->nll, e->n, 1), e->nll_worst_at);
}

static void uc_to6(const fl_ukf_cov_t *p, int32_t c[6])
{
    c[0] = p->xx; c[1] = p->xy; c[2] = p->xt; c[3] = p->yy; c[4] = p->yt; c[5] = p->tt;
}

typedef struct {
    ukf_ref_rng_t rng;
    fl_ukf_limits_t lim;
    fl_ukf_repairs_t rep;          /* all repairs */
    long updates, predicts, violations, skipped_u, skipped_p;
    int fixed_only;
    uc_errs_t eu, ep;
    /* the life */
    double tx, ty, tt;             /* true pose: mm, mm, units */
    fl_ukf_pose_t m;
    fl_ukf_cov_t p;
    int quiet_steps;               /* steps left without observations */
} uc_t;

static bool uc_repaired(const fl_ukf_repairs_t *a, const fl_ukf_repairs_t *b)
{
    return a->floors != b->floors || a->caps != b->caps || a->not_pd != b->not_pd;
}

static void uc_reset(uc_t *s)
{
    double sd = 300 * pow(10, ukf_ref_unif(&s->rng)), sdt = 1820 * pow(18, ukf_ref_unif(&s->rng));
    double h;
    s->m.x_mm = (int32_t)lround(s->tx + sd * ukf_ref_gauss(&s->rng));
    s->m.y_mm = (int32_t)lround(s->ty + sd * ukf_ref_gauss(&s->rng));
    h = ukf_ref_wrap(s->tt + 0.5 * sdt * ukf_ref_gauss(&s->rng));
    s->m.heading = (fl_angle_t)(h >= 32767.5 ? -32768 : lround(h));
    memset(&s->p, 0, sizeof s->p);
    s->p.xx = s->p.yy = (int32_t)lround(sd * sd);
    s->p.tt = (int32_t)fmin(sdt * sdt, FL_UKF_VAR_ANG2_MAX);
}

static void uc_predict(uc_t *s)
{
    fl_ukf_odo_t o;
    fl_ukf_cov_t q;
    fl_ukf_repairs_t before = s->rep;
    ukf_ref_pose_t rm;
    double rp[3][3], rq[3][3], c, sn, nx, ny, nt;
    int32_t v[6];
    o.dx_mm = (int32_t)lround(60 * ukf_ref_unif(&s->rng) - 10);
    o.dy_mm = (int32_t)lround(40 * ukf_ref_unif(&s->rng) - 20);
    o.dtheta = (fl_angle_t)lround((2 * ukf_ref_unif(&s->rng) - 1) * 1092);
    memset(&q, 0, sizeof q);
    q.xx = 4 + (int32_t)lround(0.01 * o.dx_mm * o.dx_mm + 0.0025 * o.dy_mm * o.dy_mm);
    q.yy = 4 + (int32_t)lround(0.01 * o.dy_mm * o.dy_mm + 0.0025 * o.dx_mm * o.dx_mm);
    q.tt = 400 + (int32_t)lround(0.01 * o.dtheta * o.dtheta);
    /* the robot: odometry plus noise of q's size */
    c = cos(s->tt * M_PI / 32768);
    sn = sin(s->tt * M_PI / 32768);
    nx = o.dx_mm + sqrt(q.xx) * ukf_ref_gauss(&s->rng);
    ny = o.dy_mm + sqrt(q.yy) * ukf_ref_gauss(&s->rng);
    nt = o.dtheta + sqrt(q.tt) * ukf_ref_gauss(&s->rng);
    s->tx = fmax(-5000, fmin(5000, s->tx + c * nx - sn * ny));
    s->ty = fmax(-3500, fmin(3500, s->ty + sn * nx + c * ny));
    s->tt = ukf_ref_wrap(s->tt + nt);
    rm.x = s->m.x_mm;
    rm.y = s->m.y_mm;
    rm.t = s->m.heading;
    uc_to6(&s->p, v);
    ukf_ref_from6(v, rp);
    uc_to6(&q, v);
    ukf_ref_from6(v, rq);
    fl_ukf_predict_odo(&s->m, &s->p, &o, &q, &s->lim, &s->rep);
    s->predicts++;
    s->violations += !fl_ukf_cov_valid(&s->p, &s->lim);
    if (s->fixed_only)
        return;
    if (uc_repaired(&before, &s->rep)) {
        s->skipped_p++;
        return;
    }
    if (ukf_ref_predict(&rm, rp, o.dx_mm, o.dy_mm, o.dtheta, rq) && uc_room(&s->ep)) {
        ukf_ref_err_t e;
        uc_to6(&s->p, v);
        ukf_ref_compare(&rm, rp, s->m.x_mm, s->m.y_mm, s->m.heading, v, &e);
        s->ep.mean[s->ep.n] = e.mean_mm;
        s->ep.head[s->ep.n] = e.heading_deg;
        s->ep.cov[s->ep.n] = e.cov_rel;
        s->ep.raw[s->ep.n] = e.cov_rel_raw;
        s->ep.nll[s->ep.n++] = 0;
    }
}

static void uc_update(uc_t *s, int k)
{
    fl_ukf_obs_t o;
    fl_ukf_repairs_t before = s->rep;
    ukf_ref_pose_t rm;
    double rp[3][3], r, b, rnll = 0;
    int32_t v[6];
    uint32_t nll;
    o.lx_mm = uc_map[k][0];
    o.ly_mm = uc_map[k][1];
    r = hypot(o.lx_mm - s->tx, o.ly_mm - s->ty);
    o.sd_range_mm = (int32_t)lround(10 + (0.04 + 0.06 * ukf_ref_unif(&s->rng)) * r);
    o.sd_bearing = (fl_angle_t)lround((1 + 3 * ukf_ref_unif(&s->rng)) * 65536 / 360);
    r += o.sd_range_mm * ukf_ref_gauss(&s->rng);
    o.range_mm = (int32_t)lround(fmax(0, fmin(FL_OBS_MAX_RANGE_MM, r)));
    b = ukf_ref_wrap(atan2(o.ly_mm - s->ty, o.lx_mm - s->tx) * 32768 / M_PI - s->tt +
                     o.sd_bearing * ukf_ref_gauss(&s->rng));
    o.bearing = (fl_angle_t)(b >= 32767.5 ? -32768 : lround(b));
    rm.x = s->m.x_mm;
    rm.y = s->m.y_mm;
    rm.t = s->m.heading;
    uc_to6(&s->p, v);
    ukf_ref_from6(v, rp);
    fl_ukf_update_obs(&s->m, &s->p, &o, &s->lim, &s->rep, &nll);
    s->updates++;
    s->violations += !fl_ukf_cov_valid(&s->p, &s->lim);
    if (s->fixed_only)
        return;
    if (uc_repaired(&before, &s->rep)) {
        s->skipped_u++;
        return;
    }
    if (ukf_ref_update(&rm, rp, o.lx_mm, o.ly_mm, o.range_mm, o.bearing, o.sd_range_mm,
                       o.sd_bearing, &rnll) && uc_room(&s->eu)) {
        ukf_ref_err_t e;
        uc_to6(&s->p, v);
        ukf_ref_compare(&rm, rp, s->m.x_mm, s->m.y_mm, s->m.heading, v, &e);
        s->eu.mean[s->eu.n] = e.mean_mm;
        s->eu.head[s->eu.n] = e.heading_deg;
        s->eu.cov[s->eu.n] = e.cov_rel;
        s->eu.raw[s->eu.n] = e.cov_rel_raw;
        s->eu.nll[s->eu.n] = fabs((double)nll - (rnll < 0 ? 0 : rnll));
        if (s->eu.nll[s->eu.n] > s->eu.nll_worst) {
            s->eu.nll_worst = s->eu.nll[s->eu.n];
            s->eu.nll_worst_at = rnll;
        }
        s->eu.n++;
    }
}

/* One step of the life: the robot moves, perhaps kidnapped or reset, then
 * observes. */
static void uc_step(uc_t *s)
{
    int n_obs, i;
    double u = ukf_ref_unif(&s->rng);
    if (u < 0.002) {               /* kidnapped */
        s->tx = (2 * ukf_ref_unif(&s->rng) - 1) * 4500;
        s->ty = (2 * ukf_ref_unif(&s->rng) - 1) * 3000;
        s->tt = (2 * ukf_ref_unif(&s->rng) - 1) * 32768;
    } else if (u < 0.004 ||
               hypot(s->m.x_mm - s->tx, s->m.y_mm - s->ty) > 2000 ||
               fabs(ukf_ref_wrap(s->m.heading - s->tt)) > 8192) {
        uc_reset(s);
    }
    uc_predict(s);
    if (s->quiet_steps > 0) {
        s->quiet_steps--;
        return;
    }
    if (ukf_ref_unif(&s->rng) < 0.01)
        s->quiet_steps = (int)(300 * ukf_ref_unif(&s->rng));
    n_obs = (int)(4 * ukf_ref_unif(&s->rng));
    for (i = 0; i < n_obs; i++) {
        int k = (int)(12 * ukf_ref_unif(&s->rng));
        if (hypot(uc_map[k][0] - s->tx, uc_map[k][1] - s->ty) < 8000)
            uc_update(s, k);
    }
}

static int uc_usage(void)
{
    fprintf(stderr, "usage: fieldloc ukf-check [--n UPDATES] [--seed S] [--fixed-only]\n"
                    "  the fixed-point UKF step against the double reference over random\n"
                    "  filter lives on a 10 m field (default 1000000 updates, seed 1)\n");
    return 0;
}

int cmd_ukf_check(int argc, char **argv)
{
    uc_t *s;
    long n = 1000000;
    uint32_t seed = 1;
    int i, fixed_only = 0;
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return uc_usage();
        if (!strcmp(argv[i], "--n") && i + 1 < argc) {
            if (arg_long("ukf-check", "--n", argv[++i], 1, 100000000L, NULL, &n))
                return 2;
        } else if (!strcmp(argv[i], "--seed") && i + 1 < argc) {
            if (arg_u32("ukf-check", "--seed", argv[++i], &seed))
                return 2;
        } else if (!strcmp(argv[i], "--fixed-only")) {
            fixed_only = 1;
        } else {
            return arg_unknown("ukf-check", argv[i], NULL);
        }
    }
    s = calloc(1, sizeof *s);
    if (s == NULL || (!fixed_only && (!uc_alloc(&s->eu, n) || !uc_alloc(&s->ep, 2 * n + 64)))) {
        fprintf(stderr, "fieldloc ukf-check: out of memory\n");
        return 1;
    }
    s->fixed_only = fixed_only;
    s->rng.s = 0x9e3779b97f4a7c15ull ^ ((uint64_t)seed * 0x100000001b3ull);
    s->lim.var_min_mm2 = 25;           /* 5 mm */
    s->lim.var_min_ang2 = 1296;        /* 36 units = 0.2 deg */
    s->tx = 0;
    s->ty = 0;
    s->tt = 0;
    uc_reset(s);
    while (s->updates < n)
        uc_step(s);
    printf("updates %ld\n", s->updates);
    printf("predicts %ld\n", s->predicts);
    printf("repairs_floors %lu\n", (unsigned long)s->rep.floors);
    printf("repairs_caps %lu\n", (unsigned long)s->rep.caps);
    printf("repairs_not_pd %lu\n", (unsigned long)s->rep.not_pd);
    printf("spd_violations %ld\n", s->violations);
    if (!fixed_only) {
        printf("compared_updates %ld (%ld repaired, not compared)\n", s->eu.n, s->skipped_u);
        uc_print("", &s->eu, 1);
        printf("compared_predicts %ld (%ld repaired, not compared)\n", s->ep.n, s->skipped_p);
        uc_print("predict_", &s->ep, 0);
        uc_free(&s->eu);
        uc_free(&s->ep);
    }
    free(s);
    return 0;
}
