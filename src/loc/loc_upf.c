/*
 * src/loc/loc_upf.c - the unscented particle filter (upf.h) behind the
 * localizer interface (localizer.h) as "upf".  The only interface file
 * that knows fl_upf_t; it calls the public fl_upf_* API and the particle
 * adapters' shared pieces (loc_particle.h, in loc_mcl.c).
 */
#include "fieldloc/localizer.h"
#include "fieldloc/upf.h"
#include "loc_particle.h"

#include <stddef.h>
#include <string.h>

static void up_params_default(void *params)
{
    if (params != NULL)
        fl_upf_params_default((fl_upf_params_t *)params);
}

static void up_params_preset(void *params, fl_loc_preset_t preset)
{
    fl_upf_params_t *p = (fl_upf_params_t *)params;
    if (p == NULL)
        return;
    if (preset == FL_LOC_PRESET_VISION || preset == FL_LOC_PRESET_VISION_LOWRES)
        fl_upf_params_vision(p, preset == FL_LOC_PRESET_VISION_LOWRES);
    else
        fl_upf_params_default(p);
}

/* Only a NAO vision preset becomes the AIBO's (as the Monte Carlo
 * filter's adapter decides it). */
static void up_params_adapt(void *params, fl_loc_preset_t preset)
{
    fl_upf_params_t *p = (fl_upf_params_t *)params;
    fl_upf_params_t v;
    if (p == NULL || preset != FL_LOC_PRESET_VISION_LOWRES)
        return;
    fl_upf_params_vision(&v, false);
    if (p->mcl.range_pct == v.mcl.range_pct && p->mcl.bearing_mdeg == v.mcl.bearing_mdeg)
        fl_upf_params_lowres(p);
}

static fl_status_t up_params_check(const void *params)
{
    return fl_upf_params_check((const fl_upf_params_t *)params);
}

static fl_status_t up_init(void *state, const fl_field_t *field, const void *params,
                           uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT) {
        fl_upf_clear((fl_upf_t *)state);
        return FL_ERR_CONFIG;
    }
    return fl_upf_init((fl_upf_t *)state, field, (const fl_upf_params_t *)params);
}

static void *up_params_of(void *state)
{
    fl_upf_t *s = (fl_upf_t *)state;
    return s == NULL || s->core.field == NULL ? NULL : (void *)&s->params;
}

static void up_predict(void *state, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    fl_upf_predict((fl_upf_t *)state, dx_mm, dy_mm, dtheta);
}

/* No negative information: the view is unused. */
static uint16_t up_update(void *state, const fl_obs_list_t *obs, const fl_obs_view_t *view)
{
    (void)view;
    return fl_upf_update((fl_upf_t *)state, obs);
}

static bool up_estimate(void *state, fl_loc_estimate_t *out)
{
    fl_mcl_estimate_t e;
    bool ok;
    if (out == NULL)
        return false;
    ok = fl_upf_estimate((fl_upf_t *)state, &e);
    fl_loc_internal_from_mcl(&e, out);
    return ok;
}

static void up_reset_ignorance(void *state)
{
    fl_upf_reset_ignorance((fl_upf_t *)state);
}

static void up_reset_pose(void *state, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                          int32_t pos_unc_mm, fl_angle_t heading_unc)
{
    fl_upf_reset_pose((fl_upf_t *)state, x_mm, y_mm, heading, pos_unc_mm, heading_unc);
}

static void up_reset_penalty(void *state, int32_t x_mm, int32_t pos_unc_mm,
                             fl_angle_t heading_unc)
{
    fl_upf_reset_penalty((fl_upf_t *)state, x_mm, pos_unc_mm, heading_unc);
}

static void up_set_prior_half(void *state, int half)
{
    fl_upf_set_prior_half((fl_upf_t *)state, half);
}

static void up_set_prior_pose(void *state, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                              int32_t radius_mm)
{
    fl_upf_set_prior_pose((fl_upf_t *)state, x_mm, y_mm, heading, radius_mm);
}

static void up_clear_prior(void *state)
{
    fl_upf_clear_prior((fl_upf_t *)state);
}

static bool up_check(const void *state)
{
    return fl_upf_check((const fl_upf_t *)state);
}

static uint32_t up_possibility_q16(const void *state, int32_t x_mm, int32_t y_mm,
                                   fl_angle_t heading)
{
    return fl_upf_possibility_q16((const fl_upf_t *)state, x_mm, y_mm, heading);
}

static void up_stats(const void *state, fl_loc_stats_t *out)
{
    const fl_upf_t *s = (const fl_upf_t *)state;
    if (!fl_loc_internal_stats_zero(state, out))
        return;
    FL_LOC_STATS_COMMON(out, &s->stats);
}

static uint16_t up_belief_samples(const void *state)
{
    const fl_upf_t *s = (const fl_upf_t *)state;
    return s == NULL || s->core.field == NULL ? 0 : s->n;
}

static uint16_t sd16(int32_t var, uint32_t cap)
{
    uint32_t r = fl_isqrt64((uint64_t)(var > 0 ? var : 0));
    return (uint16_t)(r > cap ? cap : r);
}

/* The sample with its Gaussian's spread (the pictures draw its ellipse). */
static bool up_belief_sample(const void *state, uint16_t i, fl_loc_sample_t *out)
{
    const fl_upf_t *s = (const fl_upf_t *)state;
    const fl_ukf_cov_t *c;
    if (out == NULL)
        return false;
    memset(out, 0, sizeof *out);
    if (s == NULL || s->core.field == NULL || i >= s->n)
        return false;
    fl_loc_internal_sample(&s->core, s->params.mcl.cluster_mm, &s->part[i], out);
    c = &s->g[i].cov;
    out->sd_x_mm = sd16(c->xx, 65535u);
    out->sd_y_mm = sd16(c->yy, 65535u);
    out->cov_xy_mm2 = c->xy;
    out->sd_heading = (fl_angle_t)sd16(c->tt, 32767u);
    return true;
}

#define OFF(f) ((uint16_t)offsetof(fl_upf_params_t, f))
#define U8(f)  { #f, OFF(f), 1, false, 0, 255 }
#define U16(f) { #f, OFF(f), 2, false, 0, 65535 }
#define S32(f) { #f, OFF(f), 4, true, INT32_MIN, INT32_MAX }
/* The Monte Carlo filter's parameters under their own names. */
#define M16(f) { #f, OFF(mcl.f), 2, false, 0, 65535 }
#define M32(f) { #f, OFF(mcl.f), 4, true, INT32_MIN, INT32_MAX }

static const fl_loc_param_t up_param[] = {
    { "seed", OFF(mcl.seed), 4, true, 0, INT32_MAX },
    { "n_particles", OFF(mcl.n_particles), 2, false, 1, FL_UPF_MAX_PARTICLES },
    M16(odo_trans_pct), M16(odo_rot_pct), M16(odo_rot_mdeg_per_m), M32(odo_max_mm),
    M32(margin_mm), M16(range_pct), M16(range_base_mm), M16(bearing_mdeg), M16(orient_mdeg),
    M16(assoc_q8), M16(outlier_q16), { "corner_any", OFF(mcl.corner_any), 1, false, 0, 1 },
    M32(max_range_mm), M32(cross_max_mm), M16(alpha_slow_q16),
    M16(alpha_fast_q16), M16(inject_max_q16), M16(inject_min_q16), M16(kidnap_q16),
    M32(cluster_mm), { "switch_q8", OFF(mcl.switch_q8), 1, false, 0, 255 },
    U16(ess_pct), U16(inject_resample_q16), U16(seed_tries), U16(inject_tries), U16(init_sd_mm), U16(init_sd_mdeg), U16(floor_sd_mm), U16(floor_sd_mdeg),
    U16(gate_q8), U8(prior_mode), { "trans_q8", OFF(trans_q8), 2, false, 0, 256 },
};

static fl_status_t up_reseed(void *state, const fl_obs_report_t *r)
{
    return fl_upf_reseed((fl_upf_t *)state, r);
}

static uint32_t up_spread_mm(const void *state)
{
    return fl_upf_spread_mm((const fl_upf_t *)state);
}

const fl_localizer_t fl_localizer_upf = {
    "upf",
    "unscented particle filter (seed 003): few particles, a UKF each",
    sizeof(fl_upf_t),
    sizeof(fl_upf_params_t),
    up_param,
    (uint16_t)(sizeof up_param / sizeof up_param[0]),
    up_params_default,
    up_params_preset,
    up_params_adapt,
    up_params_check,
    up_init,
    up_params_of,
    up_predict,
    up_update,
    up_estimate,
    up_reset_ignorance,
    up_reset_pose,
    up_reset_penalty,
    up_set_prior_half,
    up_set_prior_pose,
    up_clear_prior,
    up_check,
    up_possibility_q16,
    up_stats,
    fl_loc_internal_no_grid,
    fl_loc_internal_no_cell,
    up_belief_samples,
    up_belief_sample,
    up_reseed,
    up_spread_mm,
    false,   /* reads_points */
};
