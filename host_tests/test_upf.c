/*
 * host_tests/test_upf.c - the unscented particle filter (upf.h): state
 * size and parameters, a foreign configuration refused, convergence on a
 * feature walk (seed determinism), hostile input, covariances valid after
 * many random updates, the repair counters, the in-place resampling, a
 * stated pose kept through frames that inform nothing.
 */
#include "test.h"
#include "loc_walk.h"
#include "fieldloc/fieldloc.h"
#include "fieldloc/upf.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* Every particle's covariance valid under the state's floors. */
static bool all_valid(const fl_upf_t *s)
{
    fl_ukf_limits_t lim;
    uint16_t i;
    fl_upf_limits(s, &lim);
    for (i = 0; i < s->n; i++)
        if (!fl_ukf_cov_valid(&s->g[i].cov, &lim))
            return false;
    return true;
}

static void test_params_config(void)
{
    const fl_localizer_t *loc = fl_localizer_find("upf");
    const fl_field_t *f = fl_field_find("spl2013");
    fl_upf_params_t pp;
    fl_loc_sample_t smp;
    void *st;
    int32_t v = 0;
    CHECK(loc != NULL);
    if (loc == NULL)
        return;
    t_info("sizeof(fl_upf_t) %u B (%u particles, capacity %u)", (unsigned)sizeof(fl_upf_t),
           12u, (unsigned)FL_UPF_MAX_PARTICLES);
    /* 1.2 KiB at 12 particles; 56 B per further particle */
    CHECK(sizeof(fl_upf_t) <= 1228u + 56u * (FL_UPF_MAX_PARTICLES > 12 ? FL_UPF_MAX_PARTICLES - 12 : 0));
    CHECK_EQ(loc->state_size, sizeof(fl_upf_t));
    st = malloc(loc->state_size);
    if (st == NULL)
        return;
    loc->params_default(&pp);
    CHECK_EQ(loc->params_check(&pp), FL_OK);
    CHECK_EQ(fl_localizer_param_get(loc, &pp, "n_particles", &v), FL_OK);
    CHECK_EQ(v, FL_UPF_MAX_PARTICLES < 12 ? FL_UPF_MAX_PARTICLES : 12);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "n_particles", 0), FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "n_particles", FL_UPF_MAX_PARTICLES + 1),
             FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "seed", 7), FL_OK);
    CHECK_EQ(pp.mcl.seed, 7);
    CHECK_EQ(fl_localizer_param_set(loc, &pp, "range_pct", 5), FL_OK);
    CHECK_EQ(pp.mcl.range_pct, 5);
    pp.floor_sd_mm = pp.init_sd_mm;             /* floor at the fresh sd */
    CHECK_EQ(loc->params_check(&pp), FL_OK);
    pp.floor_sd_mm = (uint16_t)(pp.init_sd_mm + 1);
    CHECK_EQ(loc->params_check(&pp), FL_ERR_RANGE);
    CHECK_EQ(fl_loc_init(loc, st, f, &pp), FL_ERR_RANGE);
    loc->params_preset(&pp, FL_LOC_PRESET_VISION);
    CHECK_EQ(loc->params_check(&pp), FL_OK);
    loc->params_adapt(&pp, FL_LOC_PRESET_VISION_LOWRES);
    {
        fl_upf_params_t lr;
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
    /* samples with their spread (the pictures' ellipses) */
    loc->params_default(&pp);
    CHECK_EQ(fl_loc_init(loc, st, f, NULL), FL_OK);
    CHECK_EQ(loc->belief_samples(st), 12);
    CHECK(loc->belief_sample(st, 11, &smp));
    CHECK_EQ(smp.sd_x_mm, pp.init_sd_mm);
    CHECK(smp.sd_heading > 2000);
    CHECK(!loc->belief_sample(st, 12, &smp));
    free(st);
}

static bool all_valid_v(const void *s)
{
    return all_valid((const fl_upf_t *)s);
}

/* A short feature walk from the own-half prior through the interface. */
static double walk(const char *name, int32_t seed, uint32_t steps, uint32_t *hash)
{
    t_loc_walk_t w;
    fl_upf_t *s = (fl_upf_t *)t_loc_walk("upf", name, seed, steps, all_valid_v, &w);
    if (s == NULL)
        return 1e9;
    CHECK(w.obs_used > w.steps);
    t_info("%s seed %d: %u UKF updates, %u resamplings, %u injected, repairs floors %u caps %u "
           "not_pd %u", name, (int)seed, (unsigned)s->stats.ukf_updates,
           (unsigned)s->stats.resamples, (unsigned)s->stats.injected,
           (unsigned)s->stats.repairs.floors, (unsigned)s->stats.repairs.caps,
           (unsigned)s->stats.repairs.not_pd);
    CHECK(s->stats.ukf_updates > w.steps);
    free(s);
    *hash = w.hash;
    return w.rmse_mm;
}

static void test_walk(void)
{
    uint32_t h1, h2, h3;
    double e1 = walk("spl2013", 5, 900, &h1), e2 = walk("spl2013", 5, 900, &h2);
    double e3 = walk("spl2013", 6, 900, &h3);
    t_info("spl2013 walk, 30 s, 12 particles: rmse after 5 s %.1f mm (seed 5), %.1f mm (seed 6)",
           e1, e3);
    CHECK_EQ(h1, h2);
    CHECK(e1 == e2);
    CHECK(h1 != h3);
    CHECK(e1 < 150 && e3 < 150);
}

/* Hostile odometry and observations: statuses and counters, never a
 * corrupt state. */
static void test_hostile(void)
{
    const fl_field_t *f = fl_field_find("uva2013");
    fl_upf_t *s = malloc(sizeof *s);
    fl_mcl_estimate_t e;
    fl_obs_list_t ol;
    static const int32_t odo[] = {INT32_MIN, -1000000, -20001, 999, 20000, INT32_MAX};
    static const int32_t ranges[] = {INT32_MIN, -1, 0, 1, 19999, 20000, 20001, INT32_MAX};
    unsigned i, j;
    if (s == NULL)
        return;
    CHECK_EQ(fl_upf_init(s, NULL, NULL), FL_ERR_NULL);
    CHECK(!fl_upf_check(s));
    fl_upf_predict(s, 10, 0, 0);                 /* uninitialized: no-ops */
    CHECK_EQ(fl_upf_update(s, NULL), 0);
    CHECK(!fl_upf_estimate(s, &e));
    CHECK_EQ(fl_upf_init(s, f, NULL), FL_OK);
    CHECK(fl_upf_check(s) && all_valid(s));
    for (i = 0; i < sizeof odo / sizeof odo[0]; i++)
        for (j = 0; j < sizeof odo / sizeof odo[0]; j++) {
            fl_upf_predict(s, odo[i], odo[j], (fl_angle_t)(i * 9000u + j * 77u));
            CHECK(fl_upf_check(s));
        }
    CHECK(s->stats.odo_rejected > 0);
    memset(&ol, 0, sizeof ol);
    for (i = 0; i < sizeof ranges / sizeof ranges[0]; i++) {
        ol.n = 3;
        ol.obs[0] = obs_of(FL_LM_POST, ranges[i], (int32_t)i * 40);
        ol.obs[1] = obs_of((fl_landmark_kind_t)(i * 3u), ranges[i], -170);
        ol.obs[2] = obs_of(FL_LM_L, 1500, 10);
        ol.obs[1].kind = (fl_landmark_kind_t)(i % 2u ? 99 : -3);
        (void)fl_upf_update(s, &ol);
        CHECK(fl_upf_check(s) && all_valid(s));
        CHECK(fl_upf_estimate(s, &e));
        CHECK(e.x_mm >= -s->core.half_x_mm && e.x_mm <= s->core.half_x_mm);
    }
    ol.n = (uint16_t)65535u;                     /* beyond the list's capacity */
    (void)fl_upf_update(s, &ol);
    CHECK(fl_upf_check(s));
    fl_upf_reset_pose(s, 1000000, -1000000, 0, -5, (fl_angle_t)-32768);
    CHECK(fl_upf_check(s) && all_valid(s));
    fl_upf_reset_penalty(s, -100000, INT32_MAX, 32767);
    CHECK(fl_upf_check(s) && all_valid(s));
    fl_upf_set_prior_pose(s, INT32_MAX, INT32_MIN, 5, INT32_MAX);
    fl_upf_reset_ignorance(s);
    CHECK(fl_upf_check(s) && all_valid(s));
    free(s);
}

/* Random poses, odometry and observations: every covariance stays valid
 * (repairs counted); a covariance broken by hand is repaired and counted. */
static void test_cov_random(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_upf_t *s = malloc(sizeof *s);
    fl_obs_list_t ol;
    uint32_t rng = 4242u, k, before;
    bool ok = true;
    static const fl_landmark_kind_t kinds[] = {FL_LM_POST, FL_LM_L, FL_LM_T, FL_LM_X,
                                               FL_LM_CENTRE_CIRCLE};
    if (s == NULL)
        return;
    CHECK_EQ(fl_upf_init(s, f, NULL), FL_OK);
    for (k = 0; k < 2000u; k++) {
        uint32_t r = fl_mcl_rand(&rng), m;
        fl_upf_predict(s, (int32_t)(r % 301u) - 150, (int32_t)((r >> 9) % 201u) - 100,
                       (fl_angle_t)(int32_t)((int32_t)((r >> 17) % 4001u) - 2000));
        memset(&ol, 0, sizeof ol);
        ol.n = (uint16_t)(fl_mcl_rand(&rng) % 5u);
        for (m = 0; m < ol.n; m++) {
            uint32_t q = fl_mcl_rand(&rng);
            ol.obs[m] = obs_of(kinds[q % 5u], 100 + (int32_t)((q >> 3) % 9000u),
                               (int32_t)((q >> 16) % 181u) - 90);
        }
        (void)fl_upf_update(s, &ol);
        if (k % 500u == 499u)
            fl_upf_reset_ignorance(s);
        ok = ok && fl_upf_check(s) && all_valid(s);
    }
    CHECK(ok);
    t_info("2000 random frames x 12 particles: %u UKF updates, repairs floors %u caps %u "
           "not_pd %u, sample failures %u", (unsigned)s->stats.ukf_updates,
           (unsigned)s->stats.repairs.floors, (unsigned)s->stats.repairs.caps,
           (unsigned)s->stats.repairs.not_pd, (unsigned)s->stats.sample_fail);
    CHECK(s->stats.ukf_updates > 1000u);
    /* a covariance beyond Cauchy-Schwarz: the next predict repairs it */
    before = s->stats.repairs.floors + s->stats.repairs.caps + s->stats.repairs.not_pd;
    s->g[0].cov.xy = s->g[0].cov.xx;
    s->g[0].cov.yy = 1;
    CHECK(!fl_upf_check(s));
    fl_upf_predict(s, 10, 0, 0);
    CHECK(fl_upf_check(s) && all_valid(s));
    CHECK(s->stats.repairs.floors + s->stats.repairs.caps + s->stats.repairs.not_pd > before);
    free(s);
}

/* In-place selection: after a resampling the particles are copies of the
 * heavy ones only (the light ones gone), each Gaussian with its pose. */
static void test_resample_in_place(void)
{
    const fl_field_t *f = fl_field_find("uva2013");
    fl_upf_t *s = malloc(sizeof *s);
    fl_obs_list_t ol;
    fl_ukf_cov_t c0;
    uint16_t i;
    int copies_a = 0, copies_b = 0;
    if (s == NULL)
        return;
    CHECK_EQ(fl_upf_init(s, f, NULL), FL_OK);
    fl_upf_reset_pose(s, 0, 0, 0, 2, 10);
    c0 = s->g[0].cov;                            /* at the floors */
    s->aug.inject_q16 = 0;
    for (i = 0; i < s->n; i++) {
        s->part[i].weight = 0;
        s->part[i].x_mm = 0;
        s->g[i].mean.x_mm = 0;
        s->g[i].cov = c0;
    }
    s->part[3].weight = 65535u;                  /* a: 2/3 */
    s->part[3].x_mm = -2000;
    s->g[3].mean.x_mm = -2000;
    s->g[3].cov.xx = 30;
    s->part[9].weight = 32768u;                  /* b: 1/3 */
    s->part[9].x_mm = 2000;
    s->g[9].mean.x_mm = 2000;
    s->g[9].cov.xx = 31;
    s->resample_due = true;
    memset(&ol, 0, sizeof ol);
    ol.n = 1;
    ol.obs[0] = obs_of(FL_LM_POST, 19000, 10);   /* gated: far from every post */
    CHECK_EQ(fl_upf_update(s, &ol), 1);
    for (i = 0; i < s->n; i++) {
        copies_a += s->part[i].x_mm < -1900 && s->g[i].cov.xx == 30;
        copies_b += s->part[i].x_mm > 1900 && s->g[i].cov.xx == 31;
    }
    CHECK_EQ(copies_a, 8);
    CHECK_EQ(copies_b, 4);
    CHECK_EQ(s->stats.resamples, 1u);
    CHECK(fl_upf_check(s));
    free(s);
}

/* A stated pose (a known start) and then frames whose only observation
 * every particle gates (a false positive, as a robot facing out of the
 * field sees for minutes): nothing informs the UKFs, so the particles
 * follow the odometry with its noise and no more (drawing from the
 * stated covariance at every frame would walk them off by sqrt(frames)
 * times it: about 120 deg of heading after 300 frames). */
static void test_stated_pose_gated(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_upf_t *s = malloc(sizeof *s);
    fl_mcl_estimate_t e;
    fl_obs_list_t ol;
    uint16_t i, k;
    int32_t worst_mm = 0, worst_mdeg = 0;
    if (s == NULL)
        return;
    CHECK_EQ(fl_upf_init(s, f, NULL), FL_OK);
    fl_upf_reset_pose(s, -3000, -2500, fl_angle_from_mdeg(-90000), 100,
                      fl_angle_from_mdeg(10000));
    memset(&ol, 0, sizeof ol);
    ol.n = 1;
    ol.obs[0] = obs_of(FL_LM_POST, 19000, 10);   /* gated: far from every post */
    for (k = 0; k < 300; k++) {
        fl_upf_predict(s, 0, 3, 0);               /* a side step: +x here */
        CHECK_EQ(fl_upf_update(s, &ol), 1);
    }
    CHECK_EQ(s->stats.ukf_updates, 0u);
    CHECK(fl_upf_check(s) && all_valid(s));
    for (i = 0; i < s->n; i++) {
        int32_t dx = s->part[i].x_mm - (-2100), dy = s->part[i].y_mm - (-2500);
        int32_t dh = fl_angle_sub(s->part[i].heading, fl_angle_from_mdeg(-90000));
        int32_t d = (int32_t)sqrt((double)dx * dx + (double)dy * dy);
        int32_t mdeg = (int32_t)((int64_t)(dh < 0 ? -dh : dh) * 180000 / 32768);
        worst_mm = d > worst_mm ? d : worst_mm;
        worst_mdeg = mdeg > worst_mdeg ? mdeg : worst_mdeg;
    }
    t_info("after 300 gated frames: worst particle %d mm, %d mdeg from the odometry's pose",
           (int)worst_mm, (int)worst_mdeg);
    CHECK(worst_mm < 600);
    CHECK(worst_mdeg < 40000);
    CHECK(fl_upf_estimate(s, &e));
    CHECK(abs(e.x_mm - (-2100)) < 300 && abs(e.y_mm - (-2500)) < 300);
    free(s);
}

void suite_upf(void)
{
    t_run("upf.params_config", test_params_config);
    t_run("upf.walk", test_walk);
    t_run("upf.hostile", test_hostile);
    t_run("upf.cov_random", test_cov_random);
    t_run("upf.resample_in_place", test_resample_in_place);
    t_run("upf.stated_pose_gated", test_stated_pose_gated);
}
