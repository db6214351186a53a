/*
 * host_tests/test_mcl.c - the Monte Carlo localizer (mcl.h): the Gaussian
 * sampler's moments, unbiased low-variance resampling, the injection rate
 * of augmented MCL, the association, the carpet box, hostile input, the
 * configuration fingerprint, seed determinism, and a simulated walk.
 */
#include "test.h"
#include "loc_walk.h"
#include "fieldloc/fieldloc.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Mean, variance and 4th moment of 400k deviates against 0, 1, 3 (4 sd of
 * the sample moments: sqrt(1/N), sqrt(2/N), sqrt(96/N)). */
static void test_gauss_moments(void)
{
    uint32_t rng = 12345u;
    const double n = 400000;
    double s1 = 0, s2 = 0, s4 = 0, m, v, k;
    int32_t zmax = 0;
    long i;
    for (i = 0; i < n; i++) {
        int32_t z = fl_mcl_gauss_q12(&rng);
        double d = z / 4096.0;
        if (abs(z) > zmax)
            zmax = abs(z);
        s1 += d;
        s2 += d * d;
        s4 += d * d * d * d;
    }
    m = s1 / n;
    v = s2 / n;
    k = s4 / n;
    t_info("gauss: mean %+.5f var %.5f m4 %.4f max |z| %.3f (%ld draws)", m, v, k,
           zmax / 4096.0, (long)n);
    CHECK(fabs(m) < 4 * sqrt(1.0 / n));
    CHECK(fabs(v - 1) < 4 * sqrt(2.0 / n));
    CHECK(fabs(k - 3) < 4 * sqrt(96.0 / n));
    CHECK(zmax > 4 * 4096 && zmax < 4.6 * 4096);
    /* xorshift32 never reaches 0 */
    rng = 0u;
    CHECK(fl_mcl_rand(&rng) != 0u && rng != 0u);
}

/* Each particle is drawn floor or ceil of n w_i / W times per call, and
 * over many calls the counts follow the weights within binomial bounds. */
static void test_resample_unbiased(void)
{
    enum { NI = 24, NO = 31, T = 4000 };
    fl_mcl_particle_t p[NI];
    uint16_t out[NO];
    long cnt[NI];
    uint64_t W = 0;
    uint32_t rng = 99u;
    int i, t, bad_spread = 0, bad_mean = 0;
    memset(p, 0, sizeof p);
    memset(cnt, 0, sizeof cnt);
    for (i = 0; i < NI; i++) {
        p[i].weight = (uint16_t)(i % 5 == 0 ? 0 : (i * 2731) % 65536);
        W += p[i].weight;
    }
    p[7].weight = 65535;
    W = 0;
    for (i = 0; i < NI; i++)
        W += p[i].weight;
    for (t = 0; t < T; t++) {
        int c[NI];
        memset(c, 0, sizeof c);
        CHECK(fl_mcl_lowvar_pick(p, NI, out, NO, &rng) || t > 0);
        for (i = 0; i < NO; i++)
            c[out[i]]++;
        for (i = 0; i < NI; i++) {
            double e = (double)NO * p[i].weight / (double)W;
            if (c[i] < floor(e) - 1e-9 || c[i] > ceil(e) + 1e-9)
                bad_spread++;
            cnt[i] += c[i];
        }
    }
    for (i = 0; i < NI; i++) {
        double pi = (double)p[i].weight / (double)W, e = (double)T * NO * pi;
        double sd = sqrt((double)T * NO * pi * (1 - pi));
        if (fabs((double)cnt[i] - e) > 4 * sd + 1)
            bad_mean++;
        if (p[i].weight == 0)
            CHECK_EQ(cnt[i], 0);
    }
    CHECK_EQ(bad_spread, 0);
    CHECK_EQ(bad_mean, 0);
    /* zero total weight: refused */
    memset(p, 0, sizeof p);
    CHECK(!fl_mcl_lowvar_pick(p, NI, out, NO, &rng));
}

static fl_obs_t obs_of(fl_landmark_kind_t kind, int32_t range, int32_t bearing_deg)
{
    fl_obs_t o;
    memset(&o, 0, sizeof o);
    o.kind = kind;
    o.range_mm = range;
    o.bearing = fl_angle_from_mdeg(bearing_deg * 1000);
    o.confidence = 255;
    o.u_q4 = o.v_q4 = -1;
    return o;
}

/* The injection probability is 1 - w_fast / w_slow (alpha_slow 0, alpha
 * fast 1: w_fast = the frame's w_avg), and the injected count follows it. */
static void test_injection_rate(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_mcl_t *s = malloc(sizeof *s);
    fl_mcl_params_t pp;
    fl_obs_list_t ol;
    fl_obs_t o = obs_of(FL_LM_POST, 3000, 10);
    long inj = 0, expect = 0, var = 0;
    int k;
    if (s == NULL)
        return;
    fl_mcl_params_default(&pp);
    pp.alpha_slow_q16 = 0;
    pp.alpha_fast_q16 = 65535;
    pp.inject_max_q16 = 65535;
    pp.kidnap_q16 = 65535;
    pp.inject_min_q16 = 0;
    CHECK_EQ(fl_mcl_init(s, f, &pp), FL_OK);
    fl_obs_list_clear(&ol);
    fl_obs_list_push(&ol, &o);
    for (k = 0; k < 40; k++) {
        uint32_t before, ws, wf, pq;
        s->aug.w_slow_q24 = 1u << 24;     /* as if every observation fitted */
        s->aug.w_fast_q24 = 1u << 24;
        CHECK_EQ(fl_mcl_update(s, &ol), 1);
        ws = s->aug.w_slow_q24;
        wf = s->aug.w_fast_q24;
        pq = wf < ws ? 65536u - (uint32_t)(((uint64_t)wf << 16) / ws) : 0u;
        CHECK_EQ(s->aug.inject_q16, pq > 65535u ? 65535u : pq);
        before = s->stats.injected;
        fl_mcl_predict(s, 0, 0, 0);             /* resamples */
        inj += (long)(s->stats.injected - before);
        expect += (long)s->n * s->aug.inject_q16 / 65536;
        var += (long)(s->n * (s->aug.inject_q16 / 65536.0) * (1 - s->aug.inject_q16 / 65536.0));
    }
    t_info("injected %ld, expected %ld (sd %.1f)", inj, expect, sqrt((double)var));
    CHECK(expect > 100);
    CHECK(fabs((double)(inj - expect)) <= 4 * sqrt((double)var) + 40);
    /* w_fast at or above w_slow: no injection */
    s->aug.w_slow_q24 = 1u;
    s->aug.w_fast_q24 = 1u;
    pp.alpha_fast_q16 = 0;
    s->params = pp;
    CHECK_EQ(fl_mcl_update(s, &ol), 1);
    CHECK_EQ(s->aug.inject_q16, 0);
    free(s);
}

/* The nearest landmark of the kind, by brute force; colour and side filter. */
static void test_association(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_mcl_t *s = malloc(sizeof *s);
    t_rng_t r;
    int k, trial, wrong = 0;
    if (s == NULL)
        return;
    CHECK_EQ(fl_mcl_init(s, f, NULL), FL_OK);
    t_rng_seed(&r, 7);
    for (trial = 0; trial < 2000; trial++) {
        int32_t x = t_rng_range(&r, -6000, 6000), y = t_rng_range(&r, -4500, 4500);
        fl_obs_t o;
        uint32_t d1, d2, best = UINT32_MAX;
        int got, want = -1;
        uint16_t i;
        k = trial % FL_LM_KIND_COUNT;
        o = obs_of((fl_landmark_kind_t)k, 1000, 0);
        for (i = 0; i < f->n_landmarks; i++) {
            uint32_t dx, dy;
            if ((int)f->landmarks[i].kind != k)
                continue;
            dx = (uint32_t)abs(f->landmarks[i].x_mm - x);
            dy = (uint32_t)abs(f->landmarks[i].y_mm - y);
            if (dx * dx + dy * dy < best) {
                best = dx * dx + dy * dy;
                want = i;
            }
        }
        got = fl_mcl_associate(s, &o, x, y, &d1, &d2);
        if (got != want || (want >= 0 && d1 != best) || (want >= 0 && d2 < d1))
            wrong++;
    }
    CHECK_EQ(wrong, 0);
    /* a post with a side matches only posts of that side */
    for (trial = 0; trial < 200; trial++) {
        fl_obs_t o = obs_of(FL_LM_POST, 1000, 0);
        int got;
        o.side = trial & 1 ? FL_SIDE_LEFT : FL_SIDE_RIGHT;
        got = fl_mcl_associate(s, &o, t_rng_range(&r, -5000, 5000), t_rng_range(&r, -3000, 3000),
                               NULL, NULL);
        CHECK(got >= 0 && f->landmarks[got].side == o.side);
    }
    free(s);
}

/* Hostile input: the state stays valid, particles stay in the box. */
static void test_hostile(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_mcl_t *s = malloc(sizeof *s);
    fl_mcl_params_t pp;
    fl_mcl_estimate_t e;
    fl_obs_list_t ol;
    int k, i;
    bool in_box = true;
    if (s == NULL)
        return;
    /* NULL everywhere */
    fl_mcl_predict(NULL, 1, 2, 3);
    CHECK_EQ(fl_mcl_update(NULL, NULL), 0);
    CHECK(!fl_mcl_estimate(NULL, &e));
    CHECK(!fl_mcl_check(NULL));
    CHECK_EQ(fl_mcl_init(NULL, f, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_mcl_init(s, NULL, NULL), FL_ERR_NULL);
    CHECK(!fl_mcl_check(s));
    fl_mcl_params_default(&pp);
    pp.odo_max_mm = 100000;
    CHECK_EQ(fl_mcl_init(s, f, &pp), FL_OK);
    CHECK_EQ(fl_mcl_update(s, NULL), 0);
    fl_mcl_set_prior_half(s, -1);
    for (k = 0; k < 40; k++) {
        fl_obs_t o;
        fl_obs_list_clear(&ol);
        /* 0 mm, 100 m, a bad kind, then one kind over and over */
        o = obs_of(FL_LM_T, 0, 0);
        fl_obs_list_push(&ol, &o);
        o = obs_of(FL_LM_L, 100000, 30);
        fl_obs_list_push(&ol, &o);
        o = obs_of((fl_landmark_kind_t)99, 1000, 30);
        fl_obs_list_push(&ol, &o);
        while (ol.n < FL_OBS_MAX) {
            o = obs_of(FL_LM_X, 1500 + 37 * ol.n, (int32_t)ol.n * 7 - 100);
            fl_obs_list_push(&ol, &o);
        }
        fl_mcl_predict(s, k & 1 ? 90000 : -90000, k & 2 ? 90000 : -70000,
                       (fl_angle_t)(k * 9001));
        fl_mcl_predict(s, INT32_MAX, INT32_MIN, -32768);
        fl_mcl_update(s, &ol);
        CHECK(fl_mcl_estimate(s, &e));
        CHECK(fl_mcl_check(s));
        for (i = 0; i < s->n; i++) {
            const fl_mcl_particle_t *p = &s->buf[s->cur][i];
            if (abs(p->x_mm) > s->core.half_x_mm + pp.margin_mm ||
                abs(p->y_mm) > s->core.half_y_mm + pp.margin_mm)
                in_box = false;
        }
        CHECK(abs(e.x_mm) <= s->core.half_x_mm && abs(e.y_mm) <= s->core.half_y_mm);
    }
    CHECK(in_box);
    CHECK(s->stats.odo_rejected > 0);
    /* three minutes of empty lists at 30 Hz */
    fl_obs_list_clear(&ol);
    for (k = 0; k < 5400; k++) {
        fl_mcl_predict(s, 10, 0, 50);
        fl_mcl_update(s, &ol);
    }
    CHECK(fl_mcl_estimate(s, &e));
    CHECK(fl_mcl_check(s));
    CHECK_EQ(e.since_obs, 5400);
    /* a corrupted state is detected */
    s->buf[s->cur][3].x_mm = 32000;
    CHECK(!fl_mcl_check(s));
    free(s);
}

/* Parameters: ranges, names the tools rely on, the foreign configuration. */
static void test_params_config(void)
{
    const fl_localizer_t *loc = fl_localizer_find("mcl");
    const fl_field_t *f = fl_field_find("uva2013");
    fl_mcl_params_t pp;
    void *st;
    int32_t v = 0;
    CHECK(loc != NULL);
    if (loc == NULL)
        return;
    st = malloc(loc->state_size);
    if (st == NULL)
        return;
    t_info("sizeof(fl_mcl_t) %u B (%u particles)", (unsigned)sizeof(fl_mcl_t),
           (unsigned)FL_MCL_MAX_PARTICLES);
    CHECK(sizeof(fl_mcl_t) <= 24u * FL_MCL_MAX_PARTICLES + 1024u);
    loc->params_default(&pp);
    CHECK_EQ(loc->params_check(&pp), FL_OK);
    CHECK_EQ(fl_localizer_param_get(loc, &pp, "n_particles", &v), FL_OK);
    CHECK_EQ(v, 256);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "n_particles", 0), FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "n_particles", FL_MCL_MAX_PARTICLES + 1),
             FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "seed", -1), FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "seed", INT32_MAX), FL_OK);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "n_particles", 64), FL_OK);
    CHECK_EQ(pp.n_particles, 64);
    CHECK_EQ(loc->params_check(&pp), FL_OK);
    pp.alpha_slow_q16 = 7000;                  /* slow above fast */
    CHECK_EQ(loc->params_check(&pp), FL_ERR_RANGE);
    CHECK_EQ(fl_loc_init(loc, st, f, &pp), FL_ERR_RANGE);
    loc->params_preset(&pp, FL_LOC_PRESET_VISION);
    CHECK_EQ(loc->params_check(&pp), FL_OK);
    loc->params_adapt(&pp, FL_LOC_PRESET_VISION_LOWRES);
    {
        fl_mcl_params_t lr;
        loc->params_preset(&lr, FL_LOC_PRESET_VISION_LOWRES);
        CHECK(memcmp(&lr, &pp, sizeof pp) == 0);
    }
    /* a foreign configuration: refused, the state left empty */
    CHECK_EQ(fl_loc_init(loc, st, f, NULL), FL_OK);
    CHECK(fl_loc_check(loc, st));
    CHECK_EQ(loc->init(st, f, NULL, FL_CONFIG_FINGERPRINT ^ 1u), FL_ERR_CONFIG);
    CHECK(!fl_loc_check(loc, st));
    CHECK(loc->params_of(st) == NULL);
    CHECK_EQ(loc->belief_samples(st), 0);
    /* samples: n of them, on the carpet */
    CHECK_EQ(fl_loc_init(loc, st, f, NULL), FL_OK);
    CHECK_EQ(loc->belief_samples(st), 256);
    {
        fl_loc_sample_t smp;
        fl_loc_grid_t g;
        CHECK(loc->belief_sample(st, 255, &smp));
        CHECK(!loc->belief_sample(st, 256, &smp));
        CHECK(!loc->belief_grid(st, &g));
    }
    free(st);
}

/* Priors and resets: the particles go where the game says. */
/* A turn in place larger than 90 deg between two estimates (the UvA
 * spots: frames 135 deg apart, odometry the turn): the estimate turns with
 * the particles, it does not stay with the heading it tracked before. */
static void test_turn_in_place(void)
{
    const fl_field_t *f = fl_field_find("uva2013");
    fl_mcl_t *s = malloc(sizeof *s);
    fl_mcl_estimate_t e;
    fl_angle_t turn = fl_angle_from_mdeg(135000);
    if (s == NULL)
        return;
    CHECK_EQ(fl_mcl_init(s, f, NULL), FL_OK);
    fl_mcl_reset_pose(s, 1000, 500, 0, 100, fl_angle_from_mdeg(5000));
    CHECK(fl_mcl_estimate(s, &e));
    CHECK(e.tracking);
    CHECK_LE(abs(e.heading), fl_angle_from_mdeg(3000));
    fl_mcl_predict(s, 0, 0, turn);
    CHECK(fl_mcl_estimate(s, &e));
    CHECK_LE(abs(fl_angle_sub(e.heading, turn)), fl_angle_from_mdeg(8000));
    CHECK_LE(abs(e.x_mm - 1000) + abs(e.y_mm - 500), 300);
    free(s);
}

static void test_priors(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_mcl_t *s = malloc(sizeof *s);
    int i, own = 0, left = 0;
    if (s == NULL)
        return;
    CHECK_EQ(fl_mcl_init(s, f, NULL), FL_OK);
    fl_mcl_set_prior_half(s, -1);
    for (i = 0; i < s->n; i++)
        own += s->buf[s->cur][i].x_mm <= 0;
    CHECK_EQ(own, s->n);
    fl_mcl_reset_penalty(s, -1500, 200, 1024);
    for (i = 0; i < s->n; i++) {
        const fl_mcl_particle_t *p = &s->buf[s->cur][i];
        bool l = p->y_mm > 0;
        left += l;
        CHECK(abs(abs(p->y_mm) - f->width_mm / 2) < 600 && abs(p->x_mm + 1500) < 600);
        CHECK(abs(fl_angle_sub(p->heading, (fl_angle_t)(l ? -16384 : 16384))) < 3000);
    }
    CHECK(left > s->n / 3 && left < 2 * s->n / 3);
    CHECK(s->core.half_known && s->core.prior == FL_MCL_PRIOR_HALF && s->core.prior_half == -1);
    fl_mcl_set_prior_pose(s, 1000, 500, 0, 300);
    fl_mcl_reset_ignorance(s);
    for (i = 0; i < s->n; i++) {
        const fl_mcl_particle_t *p = &s->buf[s->cur][i];
        int32_t dx = p->x_mm - 1000, dy = p->y_mm - 500;
        CHECK(dx * dx + dy * dy <= 300 * 300 && abs(p->heading) <= 16384);
    }
    free(s);
}

/* One short feature-level walk: same seed same particles, other seeds
 * others; the filter converges from the own-half prior. */
static double walk(const char *name, int32_t seed, uint32_t steps, uint32_t *hash)
{
    t_loc_walk_t w;
    void *s = t_loc_walk("mcl", name, seed, steps, NULL, &w);
    if (s == NULL)
        return 1e9;
    CHECK(w.obs_used > w.steps);
    free(s);
    *hash = w.hash;
    return w.rmse_mm;
}

static void test_walk_seeds(void)
{
    uint32_t h1, h2, h3;
    double e1 = walk("spl2013", 5, 900, &h1), e2 = walk("spl2013", 5, 900, &h2);
    double e3 = walk("spl2013", 6, 900, &h3);
    double e4;
    uint32_t h4;
    t_info("spl2013 walk, 30 s: rmse after 5 s %.1f mm (seed 5), %.1f mm (seed 6)", e1, e3);
    CHECK_EQ(h1, h2);
    CHECK(e1 == e2);
    CHECK(h1 != h3);
    CHECK(e1 < 150 && e3 < 150);
    e4 = walk("aibo2004", 1, 900, &h4);
    t_info("aibo2004 walk, 30 s: rmse after 5 s %.1f mm", e4);
    CHECK(e4 < 200);
}

void suite_mcl(void)
{
    t_run("mcl.gauss_moments", test_gauss_moments);
    t_run("mcl.resample_unbiased", test_resample_unbiased);
    t_run("mcl.injection_rate", test_injection_rate);
    t_run("mcl.association", test_association);
    t_run("mcl.hostile", test_hostile);
    t_run("mcl.params_config", test_params_config);
    t_run("mcl.priors", test_priors);
    t_run("mcl.turn_in_place", test_turn_in_place);
    t_run("mcl.walk_seeds", test_walk_seeds);
}
