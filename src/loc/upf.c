/*
 * src/loc/upf.c - the unscented particle filter (upf.h): parameters, init,
 * resets, priors, check.  The resets and priors are the Monte Carlo
 * filter's (mcl_int.h fl_mcl_internal_core_*: the same draws on the
 * samples); each particle's Gaussian then restarts at its sample with the
 * covariance the reset states.
 */
#include "upf_int.h"

#include <string.h>

/* ---- parameters ------------------------------------------------------------ */

/*
 * Defaults (feature-level observations): the Monte Carlo filter's sensor
 * model and augmentation (mcl.c, the same simulator noise), seed 003's 12
 * particles, and, measured on the feature walks of spl2013, uva2013,
 * aibo2004, seeds 1-6 (a random local search over these parameters):
 *  - odometry 5 % per metre (the UKF's process noise: the MCL's 15 %
 *    spreads particles that it needs and this filter does not);
 *  - a kidnap at injection probability 0.4 (12 particles' averages are
 *    noisier than 256's);
 *  - ess_pct 70: resample below 70 % effective size, and whenever the
 *    averages call for injection at 0.15 (with a few particles all
 *    equally wrong after a kidnap the effective size stays high);
 *  - seed_tries 1, inject_tries 1: the Monte Carlo filter's sensor
 *    resetting (feature frames hold one or two observations: the best of
 *    several poses under them is as often a wrong place that fits them);
 *  - init_sd 500 mm and 15 deg: a sensor-reset pose (one feature at a
 *    noisy range and bearing) is that uncertain along its ring;
 *  - floors 5 mm and 0.3 deg: below what the range noise leaves after
 *    many frames, above the covariance's resolution;
 *  - gate 3 nats: a term beyond that at the UKF mean is taken for another
 *    landmark (an L/T confusion, a false positive) and not used by the
 *    UKF, whose update would pull the particle to it (the weight's floor
 *    still counts it);
 *  - prior_mode 1, trans_q8 256: the weight p(z | x) N(x; predicted
 *    Gaussian) / N(x; posterior), the particle's Gaussian as its
 *    transition prior (prior_mode 0, the summed process noise alone,
 *    measured 2x the position error: a particle's correction by the UKF is
 *    then a jump the prior forbids).
 */
void fl_upf_params_default(fl_upf_params_t *p)
{
    if (p == NULL)
        return;
    memset(p, 0, sizeof *p);
    fl_mcl_params_default(&p->mcl);
    p->mcl.n_particles = FL_UPF_MAX_PARTICLES < 12 ? FL_UPF_MAX_PARTICLES : 12;
    p->mcl.odo_trans_pct = 5;
    p->mcl.kidnap_q16 = 26214;
    /* the observed corner kind only: with every corner a candidate, each
     * particle's Kalman update takes the nearest of 16 unoriented points
     * and the filter does not settle (aibo2004 frames, corners alone: 1154
     * mm RMSE with the kind, 1713 mm with any corner) */
    p->mcl.corner_any = 0;
    p->ess_pct = 70;
    p->inject_resample_q16 = 9830;
    p->seed_tries = 1;
    p->inject_tries = 1;
    p->init_sd_mm = 500;
    p->init_sd_mdeg = 15000;
    p->floor_sd_mm = 5;
    p->floor_sd_mdeg = 300;
    p->gate_q8 = 3 * 256;
    p->prior_mode = 1;
    p->trans_q8 = 256;
}

/*
 * Vision: the Monte Carlo filter's vision preset, then (measured on the
 * frames walks of spl2013, uva2013, aibo2004, seeds 1-6, random-generator
 * seeds 1-2, by a random local search over these parameters): ranges sd
 * 3 % + 20 mm (vision's ranges are within 1 %: each particle's UKF takes
 * them at their word), crossings' orientation sd 5 deg, odometry 6 % per
 * metre (the UKF's process noise; the MCL's 15 % spreads particles it
 * needs), kidnap at injection 0.2, injection up to 0.75 and resampling
 * whenever the averages call for it (0.015), the best of 8 sensor-reset
 * poses when seeding from ignorance (a vision frame has several
 * observations) and of 2 when injecting, a fresh sd of 300 mm, the gate
 * at 12 nats (vision's confusions are rarer and the crossings'
 * orientation term catches them).
 */
void fl_upf_params_vision(fl_upf_params_t *p, bool lowres)
{
    uint16_t n;
    if (p == NULL)
        return;
    fl_upf_params_default(p);
    n = p->mcl.n_particles;
    fl_mcl_params_vision(&p->mcl, false);
    p->mcl.n_particles = n;
    p->mcl.corner_any = 0;   /* as in fl_upf_params_default */
    p->mcl.range_pct = 3;
    p->mcl.range_base_mm = 20;
    p->mcl.orient_mdeg = 5000;
    p->mcl.odo_trans_pct = 6;
    p->mcl.kidnap_q16 = 13107;
    p->mcl.inject_max_q16 = 49152;
    p->inject_resample_q16 = 1000;
    p->seed_tries = 8;
    p->inject_tries = 2;
    p->init_sd_mm = 300;
    p->gate_q8 = 12 * 256;
    if (lowres)
        fl_upf_params_lowres(p);
}

/* The AIBO's camera: far crossings short and often of the wrong kind (the
 * Monte Carlo filter's limit); its ranges measured as good for the UPF as
 * the NAO's. */
void fl_upf_params_lowres(fl_upf_params_t *p)
{
    if (p != NULL && p->mcl.cross_max_mm == 0)
        p->mcl.cross_max_mm = 2500;
}

fl_status_t fl_upf_params_check(const fl_upf_params_t *p)
{
    fl_mcl_params_t m;
    fl_status_t st;
    if (p == NULL)
        return FL_ERR_NULL;
    m = p->mcl;
    if (m.n_particles < 1 || m.n_particles > FL_UPF_MAX_PARTICLES)
        return FL_ERR_RANGE;
    m.n_particles = 1;
    st = fl_mcl_params_check(&m);
    if (st != FL_OK)
        return st;
    if (p->ess_pct > 100 || p->seed_tries < 1 || p->seed_tries > 64 ||
        p->inject_tries < 1 || p->inject_tries > 64 || p->init_sd_mm < 1 || p->init_sd_mm > 10000 ||
        p->init_sd_mdeg < 10 || p->init_sd_mdeg > 60000 || p->floor_sd_mm < 1 ||
        p->floor_sd_mm > 1000 || p->floor_sd_mdeg < 10 || p->floor_sd_mdeg > 30000 ||
        p->floor_sd_mm > p->init_sd_mm || p->floor_sd_mdeg > p->init_sd_mdeg ||
        p->gate_q8 < 256 || p->prior_mode > 1 || p->trans_q8 > 256)
        return FL_ERR_RANGE;
    return FL_OK;
}

/* ---- covariances ----------------------------------------------------------- */

void fl_upf_limits(const fl_upf_t *s, fl_ukf_limits_t *lim)
{
    int32_t fh;
    if (lim == NULL)
        return;
    lim->var_min_mm2 = 1;
    lim->var_min_ang2 = 1;
    if (s == NULL)
        return;
    fh = upf_mdeg(s->params.floor_sd_mdeg);
    lim->var_min_mm2 = (int32_t)s->params.floor_sd_mm * s->params.floor_sd_mm;
    lim->var_min_ang2 = fh * fh;
}

/* A diagonal covariance of sds sd_mm (x, y) and sd_h (binary angle),
 * within the caps and at least the floors. */
void fl_upf_internal_diag(const fl_upf_t *s, int32_t sd_mm, int32_t sd_h, fl_ukf_cov_t *p)
{
    fl_ukf_limits_t lim;
    int64_t v = (int64_t)sd_mm * sd_mm, vh = (int64_t)sd_h * sd_h;
    fl_upf_limits(s, &lim);
    memset(p, 0, sizeof *p);
    p->xx = v > FL_UKF_VAR_MM2_MAX ? FL_UKF_VAR_MM2_MAX : v < lim.var_min_mm2 ? lim.var_min_mm2 : (int32_t)v;
    p->yy = p->xx;
    p->tt = vh > FL_UKF_VAR_ANG2_MAX ? FL_UKF_VAR_ANG2_MAX
            : vh < lim.var_min_ang2  ? lim.var_min_ang2
                                     : (int32_t)vh;
}

/* Particle i's Gaussian restarts at its sample with covariance p. */
void fl_upf_internal_restart(fl_upf_t *s, uint16_t i, const fl_ukf_cov_t *p)
{
    s->g[i].mean.x_mm = s->part[i].x_mm;
    s->g[i].mean.y_mm = s->part[i].y_mm;
    s->g[i].mean.heading = s->part[i].heading;
    if (p != NULL)
        s->g[i].cov = *p;
}

/* Every particle restarts with one covariance; the weights equal. */
static void restart_all(fl_upf_t *s, const fl_ukf_cov_t *p, bool search)
{
    uint16_t i;
    for (i = 0; i < s->n; i++) {
        fl_upf_internal_restart(s, i, p);
        s->search[i] = search;
        s->lw[i] = 0;
        s->part[i].weight = 65535u;
    }
}

/* ---- init ------------------------------------------------------------------ */

void fl_upf_clear(fl_upf_t *s)
{
    if (s != NULL)
        memset(s, 0, sizeof *s);
}

/* Fresh particles: the averages start again from the next update. */
static void fresh(fl_upf_t *s)
{
    s->n = s->params.mcl.n_particles;
    if (s->n < 1 || s->n > FL_UPF_MAX_PARTICLES)
        s->n = FL_UPF_MAX_PARTICLES;
    s->resample_due = false;
    memset(&s->aug, 0, sizeof s->aug);
    s->core.n_reset = 0;
    s->est_density = 0;
    fl_upf_internal_diag(s, 0, 0, &s->q_acc);
}

fl_status_t fl_upf_init(fl_upf_t *s, const fl_field_t *field, const fl_upf_params_t *params)
{
    fl_upf_params_t p;
    fl_status_t st;
    if (s == NULL)
        return FL_ERR_NULL;
    fl_upf_clear(s);
    if (field == NULL || field->landmarks == NULL)
        return FL_ERR_NULL;
    if (params != NULL)
        p = *params;
    else
        fl_upf_params_default(&p);
    st = fl_upf_params_check(&p);
    if (st != FL_OK)
        return st;
    st = fl_mcl_internal_core_init(&s->core, field, p.mcl.margin_mm, p.mcl.seed);
    if (st != FL_OK)
        return st;
    s->params = p;
    fl_upf_reset_ignorance(s);
    s->stats.resets = 0;
    return FL_OK;
}

/* ---- resets ---------------------------------------------------------------- */

void fl_upf_internal_fresh_cov(const fl_upf_t *s, fl_ukf_cov_t *p)
{
    fl_upf_internal_diag(s, s->params.init_sd_mm, upf_mdeg(s->params.init_sd_mdeg), p);
}

void fl_upf_reset_ignorance(fl_upf_t *s)
{
    fl_ukf_cov_t p;
    if (!upf_ready(s))
        return;
    fresh(s);
    fl_mcl_internal_core_ignorance(&s->core, s->part, s->n);
    fl_upf_internal_fresh_cov(s, &p);
    restart_all(s, &p, true);
    s->ignorance = true;
    s->stats.resets = upf_sat_inc(s->stats.resets);
}

/* The covariance of a reset around a pose: the particles' draw's.  A
 * stated pose is tracked from the start (search false); a reset that only
 * guesses among places or headings searches. */
static void reset_cov(fl_upf_t *s, const fl_mcl_paint_t *c, bool search)
{
    fl_ukf_cov_t p;
    int32_t sd = c->pos_unc < 2 ? 1 : c->pos_unc > 20000 ? 10000 : c->pos_unc / 2;
    int32_t sh = c->heading_unc < 0 ? -(int32_t)c->heading_unc : c->heading_unc;
    fl_upf_internal_diag(s, sd, sh / 2, &p);
    restart_all(s, &p, search);
}

void fl_upf_reset_pose(fl_upf_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                       int32_t pos_unc_mm, fl_angle_t heading_unc)
{
    fl_mcl_paint_t c;
    if (!upf_ready(s))
        return;
    fresh(s);
    mcl_paint(&c, x_mm, y_mm, heading, pos_unc_mm, heading_unc);
    fl_mcl_internal_core_pose(&s->core, s->part, s->n, &c);
    reset_cov(s, &c, false);
    s->ignorance = false;
    s->stats.resets = upf_sat_inc(s->stats.resets);
}

void fl_upf_reset_penalty(fl_upf_t *s, int32_t x_mm, int32_t pos_unc_mm,
                          fl_angle_t heading_unc)
{
    fl_mcl_paint_t c;
    if (!upf_ready(s))
        return;
    fresh(s);
    mcl_paint(&c, x_mm, 0, 0, pos_unc_mm, heading_unc);
    s->ignorance = false;
    fl_mcl_internal_core_penalty(&s->core, s->part, s->n, &c);
    reset_cov(s, &c, true);
    s->stats.resets = upf_sat_inc(s->stats.resets);
}

fl_status_t fl_upf_reseed(fl_upf_t *s, const fl_obs_report_t *r)
{
    fl_mcl_estimate_t e;
    fl_mcl_paint_t c;
    fl_status_t st;
    bool known;
    if (!upf_ready(s))
        return FL_ERR_STATE;
    st = fl_obs_report_check(r, s->core.field);
    if (st != FL_OK) {
        s->stats.reseeds_refused = upf_sat_inc(s->stats.reseeds_refused);
        return st;
    }
    (void)fl_upf_estimate(s, &e);        /* the previous heading */
    known = fl_mcl_internal_reseed_paint(r, &e, &c);
    fresh(s);
    fl_mcl_internal_core_reseed(&s->core, s->part, s->n, &c, known);
    if (!known)   /* headings 360/n apart: each covers half the gap (sd) */
        c.heading_unc = (fl_angle_t)(s->n < 3 ? 32767 : 65536 / s->n);
    reset_cov(s, &c, !known);
    s->drawn = false;
    s->ignorance = false;
    s->stats.reseeds = upf_sat_inc(s->stats.reseeds);
    return FL_OK;
}

/* The mixture: each particle's mean with its weight and the trace of its
 * position covariance. */
uint32_t fl_upf_spread_mm(const fl_upf_t *s)
{
    fl_mcl_particle_t m[FL_UPF_MAX_PARTICLES];
    uint32_t var[FL_UPF_MAX_PARTICLES];
    uint16_t i;
    if (!upf_ready(s) || s->n > FL_UPF_MAX_PARTICLES)
        return UINT32_MAX;
    for (i = 0; i < s->n; i++) {
        m[i] = s->part[i];
        m[i].x_mm = (int16_t)s->g[i].mean.x_mm;
        m[i].y_mm = (int16_t)s->g[i].mean.y_mm;
        var[i] = (uint32_t)s->g[i].cov.xx + (uint32_t)s->g[i].cov.yy;
    }
    return fl_mcl_internal_spread(&s->core, m, s->n, var);
}

/* ---- priors ---------------------------------------------------------------- */

/* After a prior moved samples (drawn again under ignorance, or mirrored):
 * those Gaussians follow (a mirror negates the position-heading terms). */
static void follow_samples(fl_upf_t *s)
{
    fl_ukf_cov_t fc;
    uint16_t i;
    fl_upf_internal_fresh_cov(s, &fc);
    for (i = 0; i < s->n; i++) {
        fl_upf_gauss_t *g = &s->g[i];
        if (g->mean.x_mm == s->part[i].x_mm && g->mean.y_mm == s->part[i].y_mm &&
            g->mean.heading == s->part[i].heading)
            continue;
        if (s->ignorance) {
            fl_upf_internal_restart(s, i, &fc);
            s->search[i] = true;
            continue;
        }
        fl_upf_internal_restart(s, i, NULL);
        g->cov.xt = -g->cov.xt;
        g->cov.yt = -g->cov.yt;
    }
}

void fl_upf_set_prior_half(fl_upf_t *s, int half)
{
    if (!upf_ready(s))
        return;
    fl_mcl_internal_core_prior_half(&s->core, s->part, s->n, s->ignorance, half);
    follow_samples(s);
}

void fl_upf_set_prior_pose(fl_upf_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                           int32_t radius_mm)
{
    fl_mcl_paint_t c;
    if (!upf_ready(s))
        return;
    mcl_paint(&c, x_mm, y_mm, heading, radius_mm, 0);
    fl_mcl_internal_core_prior_pose(&s->core, s->part, s->n, s->ignorance, &c);
    follow_samples(s);
}

void fl_upf_clear_prior(fl_upf_t *s)
{
    if (!upf_ready(s))
        return;
    fl_mcl_internal_core_clear_prior(&s->core);
}

/* ---- check ------------------------------------------------------------------- */

bool fl_upf_check(const fl_upf_t *s)
{
    fl_ukf_limits_t lim;
    uint16_t i;
    if (!upf_ready(s) || s->n < 1 || s->n > FL_UPF_MAX_PARTICLES ||
        !fl_mcl_internal_core_check(&s->core, s->part, s->n))
        return false;
    fl_upf_limits(s, &lim);
    for (i = 0; i < s->n; i++) {
        const fl_upf_gauss_t *g = &s->g[i];
        if (!fl_ukf_cov_valid(&g->cov, &lim) || s->lw[i] > UPF_LW_MAX ||
            g->mean.x_mm < -s->core.box_x_mm || g->mean.x_mm > s->core.box_x_mm ||
            g->mean.y_mm < -s->core.box_y_mm || g->mean.y_mm > s->core.box_y_mm)
            return false;
    }
    return true;
}
