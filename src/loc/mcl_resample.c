/*
 * src/loc/mcl_resample.c - the Monte Carlo localizer's motion model (seed
 * 000 section 4.3), low-variance resampling (section 4.6, Algorithm 4) and
 * the injection of sensor-reset particles (sections 4.4 and 4.5).
 */
#include "mcl_int.h"

#include <string.h>

/* ---- motion ---------------------------------------------------------------- */

/*
 * Noise sds of one predict call.  Variances grow linearly with the step
 * (a random walk: two calls of half a step add what one call adds), so
 * the filter does not depend on how often the caller predicts:
 *     var_xy = (trans_pct / 100 x 1 m)^2 x step / 1 m
 *     var_h  = (rot_pct / 100 x 1 rad)^2 x |dtheta| / 1 rad
 *              + (rot_mdeg_per_m)^2 x step / 1 m
 * step = |(dx, dy)| in mm, angles in binary units (10430.4 per rad,
 * 0.182 per mdeg).
 */
void fl_mcl_internal_motion_sd(const fl_mcl_params_t *p, int32_t dx, int32_t dy, fl_angle_t dth,
                               int32_t *sd_xy, int32_t *sd_h)
{
    uint64_t step = fl_hypot(dx, dy), turn = (uint64_t)mcl_absang(dth);
    uint64_t vxy = (uint64_t)p->odo_trans_pct * p->odo_trans_pct * step / 10u; /* mm^2 */
    uint64_t s1 = (uint64_t)p->odo_rot_pct * 10430u / 100u;      /* units per rad */
    uint64_t s2 = (uint64_t)p->odo_rot_mdeg_per_m * 2983u / 16384u; /* units per m */
    uint64_t vh = s1 * s1 * turn / 10430u + s2 * s2 * step / 1000u;
    *sd_xy = (int32_t)fl_isqrt64(vxy);
    *sd_h = (int32_t)fl_isqrt64(vh);
    if (*sd_h > 32767)
        *sd_h = 32767;
}

void fl_mcl_predict(fl_mcl_t *s, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    fl_mcl_particle_t *p;
    int32_t sd_xy, sd_h;
    uint16_t i;
    if (!mcl_ready(s))
        return;
    s->stats.predicts = mcl_sat_inc(s->stats.predicts);
    if (s->since_obs < UINT16_MAX)
        s->since_obs++;
    if (dx_mm > s->params.odo_max_mm || dx_mm < -s->params.odo_max_mm ||
        dy_mm > s->params.odo_max_mm || dy_mm < -s->params.odo_max_mm) {
        s->stats.odo_rejected = mcl_sat_inc(s->stats.odo_rejected);
        return;
    }
    if (s->weighted)
        fl_mcl_internal_resample(s);
    fl_mcl_internal_motion_sd(&s->params, dx_mm, dy_mm, dtheta, &sd_xy, &sd_h);
    if (s->jitter_due) {
        /* the resampling's jitter, drawn with the motion noise (one
         * deviate per coordinate instead of two) */
        int32_t jh = (int32_t)(((int64_t)s->params.jitter_mdeg * 65536) / 360000);
        sd_xy = (int32_t)fl_isqrt64((uint64_t)((int64_t)sd_xy * sd_xy +
                                               (int64_t)s->params.jitter_mm * s->params.jitter_mm));
        sd_h = (int32_t)fl_isqrt64((uint64_t)((int64_t)sd_h * sd_h + (int64_t)jh * jh));
        s->jitter_due = false;
    }
    if (dx_mm == 0 && dy_mm == 0 && dtheta == 0 && sd_xy == 0 && sd_h == 0)
        return;
    p = mcl_live(s);
    for (i = 0; i < s->n; i++) {
        int32_t x = p[i].x_mm, y = p[i].y_mm;
        fl_mcl_internal_move(&x, &y, p[i].heading, dx_mm, dy_mm);
        x += mcl_noise(&s->core.rng, sd_xy);
        y += mcl_noise(&s->core.rng, sd_xy);
        fl_mcl_internal_clamp(&s->core, &x, &y);
        p[i].x_mm = (int16_t)x;
        p[i].y_mm = (int16_t)y;
        p[i].heading = fl_angle_add(p[i].heading,
                                    fl_angle_wrap((int32_t)dtheta + mcl_noise(&s->core.rng, sd_h)));
    }
    /* the tracked mode follows the odometry: the estimate's cluster is
     * gathered within 90 deg of its heading, so a turn in place of more
     * than that between two estimates would otherwise leave the cluster
     * behind (a NAO turning 135 deg between two frames) */
    fl_mcl_internal_track_move(&s->core, dx_mm, dy_mm, dtheta);
}

void fl_mcl_internal_track_move(fl_mcl_core_t *k, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    int32_t x, y;
    if (!k->track_valid)
        return;
    x = k->track_x_mm;
    y = k->track_y_mm;
    fl_mcl_internal_move(&x, &y, k->track_heading, dx_mm, dy_mm);
    k->track_x_mm = mcl_clamp(x, -k->half_x_mm, k->half_x_mm);
    k->track_y_mm = mcl_clamp(y, -k->half_y_mm, k->half_y_mm);
    k->track_heading = fl_angle_add(k->track_heading, dtheta);
}

void fl_mcl_internal_move(int32_t *x, int32_t *y, fl_angle_t h, int32_t dx_mm, int32_t dy_mm)
{
    int32_t c = fl_cos_q15(h), sn = fl_sin_q15(h);
    *x += mcl_asr((int64_t)dx_mm * c - (int64_t)dy_mm * sn + 16384, 15);
    *y += mcl_asr((int64_t)dx_mm * sn + (int64_t)dy_mm * c + 16384, 15);
}

/* ---- resampling ------------------------------------------------------------- */

bool fl_mcl_lowvar_pick(const fl_mcl_particle_t *p, uint16_t n_in, uint16_t *out,
                        uint16_t n_out, uint32_t *rng)
{
    uint64_t total = 0, c, target;
    uint32_t r;
    uint16_t i, m;
    if (p == NULL || out == NULL || rng == NULL || n_in == 0 || n_out == 0)
        return false;
    for (i = 0; i < n_in; i++)
        total += p[i].weight;
    if (total == 0u)
        return false;
    /* pointer m at (r + m W) / n_out with r uniform in [0, W): the step is
     * the average weight W / n_out (seed 000), compared exactly by scaling
     * the cumulative weights by n_out */
    r = (uint32_t)(((uint64_t)fl_mcl_rand(rng) * total) >> 32);
    i = 0;
    c = (uint64_t)p[0].weight * n_out;
    for (m = 0; m < n_out; m++) {
        target = r + (uint64_t)m * total;
        while (c <= target && i + 1 < n_in) {
            i++;
            c += (uint64_t)p[i].weight * n_out;
        }
        out[m] = i;
    }
    return true;
}

/* A pose from one observed feature (sensor resetting): a random landmark
 * of its kind (colour, side) at the noisy range, from a random direction,
 * the heading from the noisy bearing.  false when none fits the allowed
 * region (after mirroring on a symmetric field) in a few tries. */
static bool sensor_reset(fl_mcl_core_t *c, const fl_mcl_params_t *p, fl_mcl_particle_t *out)
{
    const fl_mcl_reset_obs_t *ro = &c->reset_obs[mcl_below(&c->rng, c->n_reset)];
    const fl_mcl_reset_obs_t *r2 = &c->reset_obs[mcl_below(&c->rng, c->n_reset)];
    int k, a, tries;
    /* of two random observations the one of the rarer kind (fewer map
     * landmarks: fewer rings, a likelier hit) */
    if (c->kind_start[r2->kind + 1] - c->kind_start[r2->kind] <
        c->kind_start[ro->kind + 1] - c->kind_start[ro->kind])
        ro = r2;
    k = ro->kind;
    for (tries = 0; tries < 3; tries++) {
        uint32_t nk = (uint32_t)(c->kind_start[k + 1] - c->kind_start[k]);
        const fl_landmark_t *lm;
        int32_t r, x, y;
        fl_angle_t phi, h;
        if (nk == 0u)
            return false;
        a = c->kind_start[k] + (int)mcl_below(&c->rng, nk);
        lm = fl_field_all_at(c->field, c->lm_index[a]);
        if ((ro->side != FL_SIDE_UNKNOWN && lm->side != FL_SIDE_UNKNOWN && lm->side != ro->side) ||
            (ro->color != FL_COLOR_NONE && lm->color != FL_COLOR_NONE && lm->color != ro->color) ||
            (ro->pad != FL_COLOR_NONE && lm->color2 != FL_COLOR_NONE && lm->color2 != ro->pad))
            continue;
        r = ro->range_mm + mcl_noise(&c->rng, p->range_base_mm +
                                                  (int32_t)((int64_t)ro->range_mm * p->range_pct / 100));
        if (r < 0)
            r = 0;
        phi = (fl_angle_t)(int32_t)(fl_mcl_rand(&c->rng) >> 16);
        x = lm->x_mm + mcl_asr((int64_t)r * fl_cos_q15(phi), 15);
        y = lm->y_mm + mcl_asr((int64_t)r * fl_sin_q15(phi), 15);
        /* the landmark is at bearing b from heading h: phi + 180 = h + b */
        h = fl_angle_sub(fl_angle_add(phi, FL_ANGLE_180), ro->bearing);
        h = fl_angle_add(h, fl_angle_wrap(mcl_noise(&c->rng, (int32_t)((int64_t)p->bearing_mdeg *
                                                                         65536 / 360000))));
        if (!fl_mcl_internal_allowed(c, x, y, h) && c->field->symmetric) {
            x = -x;
            y = -y;
            h = fl_angle_add(h, FL_ANGLE_180);
        }
        if (!fl_mcl_internal_allowed(c, x, y, h))
            continue;
        out->x_mm = (int16_t)x;
        out->y_mm = (int16_t)y;
        out->heading = h;
        out->weight = 65535u;
        return true;
    }
    return false;
}

bool fl_mcl_internal_core_inject(fl_mcl_core_t *c, const fl_mcl_params_t *p,
                                 fl_mcl_particle_t *out)
{
    if (c->n_reset > 0 && sensor_reset(c, p, out))
        return true;
    fl_mcl_internal_uniform(c, out);
    return false;
}

void fl_mcl_internal_inject(fl_mcl_t *s, fl_mcl_particle_t *out)
{
    s->stats.injected = mcl_sat_inc(s->stats.injected);
    (void)fl_mcl_internal_core_inject(&s->core, &s->params, out);
}

void fl_mcl_internal_resample(fl_mcl_t *s)
{
    uint16_t idx[FL_MCL_MAX_PARTICLES];
    const fl_mcl_particle_t *src = mcl_live_c(s);
    fl_mcl_particle_t *dst = s->buf[(s->cur & 1u) ^ 1u];
    uint16_t n_out = s->params.n_particles, m;
    s->weighted = false;
    if (n_out < 1 || n_out > FL_MCL_MAX_PARTICLES)
        n_out = s->n;
    if (!fl_mcl_lowvar_pick(src, s->n, idx, n_out, &s->core.rng))
        return;
    for (m = 0; m < n_out; m++) {
        fl_mcl_particle_t *d = &dst[m];
        if (s->aug.inject_q16 != 0u && (fl_mcl_rand(&s->core.rng) >> 16) < s->aug.inject_q16) {
            fl_mcl_internal_inject(s, d);
            continue;
        }
        *d = src[idx[m]];
        d->weight = 65535u;
    }
    s->jitter_due = true;
    s->cur = (uint8_t)((s->cur & 1u) ^ 1u);
    s->n = n_out;
}
