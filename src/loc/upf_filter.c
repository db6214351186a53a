/*
 * src/loc/upf_filter.c - the unscented particle filter's predict, update
 * and resampling (van der Merwe, Doucet, de Freitas and Wan, "The
 * Unscented Particle Filter", NIPS 2000, section 4: per particle a UKF
 * step as the proposal, a sample from it, the weight likelihood x
 * transition prior / proposal, selection).
 *
 * From the Monte Carlo filter (mcl_int.h): the motion model's noise (as
 * the process noise Q), the odometry's motion of a pose, the track's
 * motion, the sensor model per observation and per pose (association,
 * range/bearing Gaussians, the outlier floor: p(z | x) is the MCL's), the
 * reset observations, augmented MCL's averages and injection, low-variance
 * resampling.
 */
#include "upf_int.h"

#include <string.h>

/* Observations used per frame at most (as the Monte Carlo filter). */
#define UPF_OBS_PER_FRAME 16

/* ---- predict ------------------------------------------------------------------ */

static int32_t add_sat(int32_t a, int64_t b, int32_t cap)
{
    int64_t v = (int64_t)a + b;
    return v > cap ? cap : (int32_t)v;
}

/* The particles restart at their samples (after an update's draw). */
static void restart_drawn(fl_upf_t *s)
{
    uint16_t i;
    if (!s->drawn)
        return;
    s->drawn = false;
    for (i = 0; i < s->n; i++)
        fl_upf_internal_restart(s, i, NULL);
}

void fl_upf_predict(fl_upf_t *s, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    fl_ukf_limits_t lim;
    fl_ukf_cov_t q;
    fl_ukf_odo_t odo;
    int32_t sd_xy, sd_h;
    uint16_t i;
    if (!upf_ready(s))
        return;
    s->stats.predicts = upf_sat_inc(s->stats.predicts);
    if (s->since_obs < UINT16_MAX)
        s->since_obs++;
    if (dx_mm > s->params.mcl.odo_max_mm || dx_mm < -s->params.mcl.odo_max_mm ||
        dy_mm > s->params.mcl.odo_max_mm || dy_mm < -s->params.mcl.odo_max_mm ||
        dx_mm > FL_OBS_MAX_RANGE_MM || dx_mm < -FL_OBS_MAX_RANGE_MM ||
        dy_mm > FL_OBS_MAX_RANGE_MM || dy_mm < -FL_OBS_MAX_RANGE_MM) {
        s->stats.odo_rejected = upf_sat_inc(s->stats.odo_rejected);
        return;
    }
    restart_drawn(s);
    fl_mcl_internal_motion_sd(&s->params.mcl, dx_mm, dy_mm, dtheta, &sd_xy, &sd_h);
    memset(&q, 0, sizeof q);
    q.xx = (int32_t)((int64_t)sd_xy * sd_xy);
    q.yy = q.xx;
    q.tt = (int32_t)((int64_t)sd_h * sd_h);
    s->q_acc.xx = add_sat(s->q_acc.xx, q.xx, FL_UKF_VAR_MM2_MAX);
    s->q_acc.yy = add_sat(s->q_acc.yy, q.yy, FL_UKF_VAR_MM2_MAX);
    s->q_acc.tt = add_sat(s->q_acc.tt, q.tt, FL_UKF_VAR_ANG2_MAX);
    if (dx_mm == 0 && dy_mm == 0 && dtheta == 0 && sd_xy == 0 && sd_h == 0)
        return;
    fl_upf_limits(s, &lim);
    odo.dx_mm = dx_mm;
    odo.dy_mm = dy_mm;
    odo.dtheta = dtheta;
    for (i = 0; i < s->n; i++) {
        fl_mcl_particle_t *p = &s->part[i];
        int32_t x = p->x_mm, y = p->y_mm;
        (void)fl_ukf_predict_odo(&s->g[i].mean, &s->g[i].cov, &odo, &q, &lim, &s->stats.repairs);
        fl_mcl_internal_move(&x, &y, p->heading, dx_mm, dy_mm);
        fl_mcl_internal_clamp(&s->core, &x, &y);
        p->x_mm = (int16_t)x;
        p->y_mm = (int16_t)y;
        p->heading = fl_angle_add(p->heading, dtheta);
        fl_mcl_internal_clamp(&s->core, &s->g[i].mean.x_mm, &s->g[i].mean.y_mm);
    }
    fl_mcl_internal_track_move(&s->core, dx_mm, dy_mm, dtheta);
}

/* ---- update ------------------------------------------------------------------- */

/* The frame's per-particle work areas (on the stack of fl_upf_update). */
typedef struct {
    fl_upf_gauss_t prior[FL_UPF_MAX_PARTICLES];  /* predicted Gaussians */
    int32_t ratio[FL_UPF_MAX_PARTICLES];         /* transition - proposal */
    uint32_t nll[FL_UPF_MAX_PARTICLES];          /* p(z | sample), Q8 */
    uint16_t tab[FL_MCL_MIX_N];                  /* outlier floor */
    bool informed[FL_UPF_MAX_PARTICLES];         /* a UKF update applied */
    fl_ukf_limits_t lim;
} upf_frame_t;


/* ---- resampling -------------------------------------------------------------- */

static void at_pose(fl_mcl_at_t *at, int32_t x, int32_t y, fl_angle_t h)
{
    at->x = x;
    at->y = y;
    at->h = h;
    at->c = fl_cos_q15(h);
    at->s = fl_sin_q15(h);
    at->best = -1;
}

/* The frame's observations' negative log-likelihood at a pose (the
 * Monte Carlo filter's sensor model with the outlier floor). */
static uint32_t pose_nll(fl_upf_t *s, const fl_obs_list_t *obs, const upf_frame_t *f,
                         const fl_mcl_particle_t *p)
{
    fl_mcl_obs_c_t c;
    fl_mcl_at_t at;
    uint32_t sum = 0;
    uint16_t i, used = 0, nmax = obs->n < FL_OBS_MAX ? obs->n : FL_OBS_MAX;
    at_pose(&at, p->x_mm, p->y_mm, p->heading);
    for (i = 0; i < nmax && used < UPF_OBS_PER_FRAME; i++)
        if (fl_mcl_internal_prepare(&s->core, &s->params.mcl, &obs->obs[i], &c)) {
            sum += fl_mcl_internal_mixture(f->tab, fl_mcl_internal_obs_nll(&s->core,
                                                                           &s->params.mcl, &c,
                                                                           &at));
            used++;
        }
    return sum;
}

/* An injected pose: the best of seed_tries (under ignorance) or
 * inject_tries sensor-reset poses under the frame's observations (a few
 * particles cannot afford the sensor resetting's misses: a random landmark
 * of the kind, a random point on its ring). */
static void candidate(fl_upf_t *s, const fl_obs_list_t *obs, const upf_frame_t *f,
                      fl_mcl_particle_t *out)
{
    fl_mcl_particle_t c;
    uint32_t best = UINT32_MAX;
    uint16_t k, tries = s->ignorance ? s->params.seed_tries : s->params.inject_tries;
    for (k = 0; k < tries; k++) {
        uint32_t q;
        (void)fl_mcl_internal_core_inject(&s->core, &s->params.mcl, &c);
        q = pose_nll(s, obs, f, &c);
        if (q < best) {
            best = q;
            *out = c;
        }
    }
    if (best == UINT32_MAX)
        (void)fl_mcl_internal_core_inject(&s->core, &s->params.mcl, out);
    out->weight = 65535u;
}

/* Low-variance selection in place (the picks are sorted: a picked
 * particle keeps its slot, its further copies go to the slots of the
 * particles not picked), then augmented MCL's injection per slot with a
 * fresh covariance; the weights equal again. */
static void resample(fl_upf_t *s, const fl_obs_list_t *obs, upf_frame_t *f)
{
    uint16_t idx[FL_UPF_MAX_PARTICLES];
    uint8_t cnt[FL_UPF_MAX_PARTICLES];
    uint16_t n_out = s->params.mcl.n_particles, m, j = 0;
    fl_ukf_cov_t fc;
    s->resample_due = false;
    if (n_out < 1 || n_out > FL_UPF_MAX_PARTICLES)
        n_out = s->n;
    if (!fl_mcl_lowvar_pick(s->part, s->n, idx, n_out, &s->core.rng))
        return;
    s->stats.resamples = upf_sat_inc(s->stats.resamples);
    memset(cnt, 0, sizeof cnt);
    for (m = 0; m < n_out; m++)
        cnt[idx[m]]++;
    for (m = 0; m < n_out; m++) {
        uint16_t i = idx[m];
        if (i < n_out && cnt[i] > 0u && (m == 0 || idx[m - 1] != i))
            continue;               /* the first copy stays in its slot */
        /* a further copy (or one whose slot is beyond n_out): the next
         * slot whose particle was not picked */
        while (j < n_out && j < s->n && cnt[j] > 0u)
            j++;
        if (j >= n_out)
            break;
        s->part[j] = s->part[i];
        s->g[j] = s->g[i];
        s->search[j] = s->search[i];
        j++;
    }
    s->n = n_out;
    fl_upf_internal_fresh_cov(s, &fc);
    for (m = 0; m < s->n; m++) {
        s->lw[m] = 0;
        s->part[m].weight = 65535u;
        if (s->aug.inject_q16 != 0u && (fl_mcl_rand(&s->core.rng) >> 16) < s->aug.inject_q16) {
            s->stats.injected = upf_sat_inc(s->stats.injected);
            candidate(s, obs, f, &s->part[m]);
            fl_upf_internal_restart(s, m, &fc);
            s->search[m] = true;
        }
    }
}

/* One observation's UKF update of every particle, associated at its mean
 * as the Monte Carlo filter associates (gated: far from every landmark of
 * its kind, the observation is not this particle's). */
static void ukf_obs(fl_upf_t *s, const fl_mcl_obs_c_t *c, upf_frame_t *f)
{
    const fl_obs_t *o = c->o;
    int32_t r = o->range_mm > 1 ? o->range_mm : 1;
    int32_t sd_b = (int32_t)(((int64_t)c->sd_a * 10430) / r);
    fl_ukf_obs_t u;
    uint16_t i;
    if (sd_b > 16384)
        sd_b = 16384;
    if (sd_b < 1)
        sd_b = 1;
    u.range_mm = o->range_mm;
    u.bearing = o->bearing;
    u.sd_range_mm = c->sd_r;
    u.sd_bearing = (fl_angle_t)sd_b;
    for (i = 0; i < s->n; i++) {
        fl_upf_gauss_t *g = &s->g[i];
        const fl_landmark_t *lm;
        fl_mcl_at_t at;
        uint32_t q;
        at_pose(&at, g->mean.x_mm, g->mean.y_mm, g->mean.heading);
        q = fl_mcl_internal_obs_nll(&s->core, &s->params.mcl, c, &at);
        if (q > s->params.gate_q8 || at.best < 0) {
            s->stats.gated = upf_sat_inc(s->stats.gated);
            continue;
        }
        lm = fl_field_all_at(s->core.field, (uint16_t)at.best);
        u.lx_mm = lm->x_mm;
        u.ly_mm = lm->y_mm;
        if (fl_ukf_update_obs(&g->mean, &g->cov, &u, &f->lim, &s->stats.repairs, NULL) == FL_OK) {
            s->stats.ukf_updates = upf_sat_inc(s->stats.ukf_updates);
            f->informed[i] = true;
        }
    }
}

/* Each particle's new pose from its posterior, and the transition prior /
 * proposal part of its weight.  A particle whose UKF took no observation
 * this frame (every one gated) has no information to propose from: its
 * posterior is its predicted Gaussian, whose covariance still holds the
 * uncertainty of earlier frames.  Drawing from it and restarting there
 * with that covariance would add it again at every frame, a random walk
 * that no observation bounds (frames of false positives alone walk the
 * particles off their pose); a tracked particle draws from the transition
 * prior instead, the process noise since the last update (the bootstrap
 * proposal: the weight is the likelihood alone).  Only particles that
 * descend from a stated pose (a known start, a re-seed with its heading)
 * are tracked so; a particle that descends from a guess (search: ignorance,
 * a sensor reset, a penalty, a re-seed without heading) keeps drawing from
 * its Gaussian, a walk that is its search along the ring it was put on
 * (the built-in walks and re-seeds from ignorance need it). */
static void draw(fl_upf_t *s, upf_frame_t *f)
{
    uint16_t i;
    for (i = 0; i < s->n; i++) {
        fl_upf_gauss_t *g = &s->g[i];
        fl_mcl_particle_t *p = &s->part[i];
        fl_ukf_pose_t xs, prev;
        const fl_ukf_cov_t *pc = &s->q_acc;
        int64_t d = 0;
        fl_mcl_internal_clamp(&s->core, &g->mean.x_mm, &g->mean.y_mm);
        if (!f->informed[i] && !s->search[i]) {
            xs = g->mean;
            if (s->q_acc.xx > 0 && s->q_acc.tt > 0)
                (void)fl_ukf_sample(&g->mean, &s->q_acc, &s->core.rng, &xs);
            fl_mcl_internal_clamp(&s->core, &xs.x_mm, &xs.y_mm);
        } else {
            if (!fl_ukf_sample(&g->mean, &g->cov, &s->core.rng, &xs))
                s->stats.sample_fail = upf_sat_inc(s->stats.sample_fail);
            fl_mcl_internal_clamp(&s->core, &xs.x_mm, &xs.y_mm);
            prev.x_mm = p->x_mm;
            prev.y_mm = p->y_mm;
            prev.heading = p->heading;
            if (s->params.prior_mode == 1) {
                prev = f->prior[i].mean;
                pc = &f->prior[i].cov;
            }
            d = (int64_t)fl_ukf_gauss_nll_q8(&prev, pc, &xs) -
                (int64_t)fl_ukf_gauss_nll_q8(&g->mean, &g->cov, &xs);
            d = (d * s->params.trans_q8) / 256;
        }
        f->ratio[i] = (int32_t)(d > (int64_t)UPF_LW_MAX ? UPF_LW_MAX
                                : d < -(int64_t)UPF_LW_MAX ? -(int32_t)UPF_LW_MAX
                                                           : d);
        p->x_mm = (int16_t)xs.x_mm;
        p->y_mm = (int16_t)xs.y_mm;
        p->heading = xs.heading;
    }
    s->drawn = true;
}

/* p(z | sample): the Monte Carlo filter's likelihood of one observation
 * added to every particle's sum. */
static void weigh_obs(fl_upf_t *s, const fl_mcl_obs_c_t *c, upf_frame_t *f)
{
    uint16_t i;
    for (i = 0; i < s->n; i++) {
        fl_mcl_at_t at;
        at_pose(&at, s->part[i].x_mm, s->part[i].y_mm, s->part[i].heading);
        f->nll[i] += fl_mcl_internal_mixture(f->tab, fl_mcl_internal_obs_nll(&s->core,
                                                                             &s->params.mcl, c,
                                                                             &at));
    }
}

/* The weights: accumulated since the last resampling, the lightest at 0;
 * the effective sample size decides the next resampling. */
static void normalise(fl_upf_t *s, const upf_frame_t *f)
{
    int64_t tot[FL_UPF_MAX_PARTICLES], lo = INT64_MAX;
    uint64_t sw = 0, sww = 0;
    uint16_t i;
    for (i = 0; i < s->n; i++) {
        tot[i] = (int64_t)s->lw[i] + f->nll[i] + f->ratio[i];
        if (tot[i] < lo)
            lo = tot[i];
    }
    for (i = 0; i < s->n; i++) {
        int64_t v = tot[i] - lo;
        uint32_t w;
        s->lw[i] = v > (int64_t)UPF_LW_MAX ? UPF_LW_MAX : (uint32_t)v;
        w = fl_mcl_internal_exp_q16(s->lw[i]);
        s->part[i].weight = (uint16_t)(w > 65535u ? 65535u : w);
        sw += s->part[i].weight;
        sww += (uint64_t)s->part[i].weight * s->part[i].weight;
    }
    /* N_eff = (sum w)^2 / sum w^2 < ess_pct % of n */
    s->resample_due = sww > 0u && sw * sw * 100u < sww * s->params.ess_pct * s->n;
}

/* Under ignorance every particle is injected from the observations. */
static void seed_from_obs(fl_upf_t *s, const fl_obs_list_t *obs, const upf_frame_t *f)
{
    fl_ukf_cov_t fc;
    uint16_t i;
    fl_upf_internal_fresh_cov(s, &fc);
    for (i = 0; i < s->n; i++) {
        s->stats.injected = upf_sat_inc(s->stats.injected);
        candidate(s, obs, f, &s->part[i]);
        fl_upf_internal_restart(s, i, &fc);
        s->search[i] = true;
        s->lw[i] = 0;
    }
}

/* The usable observations (the first ones, kept for sensor resetting). */
static uint16_t count_obs(fl_upf_t *s, const fl_obs_list_t *obs, uint16_t nmax,
                          fl_mcl_obs_c_t *c)
{
    uint16_t i, used = 0;
    for (i = 0; i < nmax && used < UPF_OBS_PER_FRAME; i++)
        if (fl_mcl_internal_prepare(&s->core, &s->params.mcl, &obs->obs[i], c)) {
            if (used == 0)
                s->core.n_reset = 0;
            fl_mcl_internal_keep_reset_obs(&s->core, c->o);
            used++;
        }
    return used;
}

uint16_t fl_upf_update(fl_upf_t *s, const fl_obs_list_t *obs)
{
    fl_mcl_obs_c_t c;
    upf_frame_t f;
    uint16_t i, used, nmax;
    if (!upf_ready(s))
        return 0;
    s->stats.updates = upf_sat_inc(s->stats.updates);
    if (obs == NULL)
        return 0;
    nmax = obs->n < FL_OBS_MAX ? obs->n : FL_OBS_MAX;
    used = count_obs(s, obs, nmax, &c);
    s->stats.obs_ignored += (uint32_t)(nmax - used);
    if (used == 0)
        return 0;
    restart_drawn(s);
    memset(&f, 0, sizeof f);
    fl_upf_limits(s, &f.lim);
    fl_mcl_internal_mixture_table(s->params.mcl.outlier_q16, f.tab);
    if (s->resample_due)
        resample(s, obs, &f);
    if (s->ignorance)
        seed_from_obs(s, obs, &f);
    memcpy(f.prior, s->g, sizeof(s->g[0]) * s->n);
    /* the proposals: UKF updates, observation after observation */
    for (i = 0, used = 0; i < nmax && used < UPF_OBS_PER_FRAME; i++)
        if (fl_mcl_internal_prepare(&s->core, &s->params.mcl, &obs->obs[i], &c)) {
            ukf_obs(s, &c, &f);
            used++;
        }
    draw(s, &f);
    /* the likelihoods at the samples */
    for (i = 0, used = 0; i < nmax && used < UPF_OBS_PER_FRAME; i++)
        if (fl_mcl_internal_prepare(&s->core, &s->params.mcl, &obs->obs[i], &c)) {
            weigh_obs(s, &c, &f);
            used++;
        }
    normalise(s, &f);
    if (fl_mcl_internal_augment(&s->core, &s->params.mcl, &s->aug, f.nll, s->n, used))
        s->stats.kidnaps = upf_sat_inc(s->stats.kidnaps);
    /* injection happens at a resampling: with a few particles all equally
     * wrong after a kidnap the effective size stays high, so the averages'
     * call for injection resamples too */
    if (s->aug.inject_q16 >= s->params.inject_resample_q16)
        s->resample_due = true;
    fl_upf_internal_diag(s, 0, 0, &s->q_acc);
    s->ignorance = false;
    s->since_obs = 0;
    s->stats.obs_used += used;
    return used;
}
