/*
 * src/loc/loc_relmap.c - seed 002's particle grid with the relative
 * landmark map (relmap.h) behind the localizer interface (localizer.h) as
 * "relmap".  Deterministic: no random generator, so no "seed" parameter.
 * Presets: the defaults for feature-level observations, a tighter eq. 1
 * sigma and eq. 2 cap for a camera (fl_relmap_params_vision), the
 * defaults again for a low-resolution camera.
 */
#include "fieldloc/localizer.h"
#include "fieldloc/relmap.h"
#include "loc_adapter.h"

#include <stddef.h>
#include <string.h>

static void rm_params_default(void *params)
{
    if (params != NULL)
        fl_relmap_params_default((fl_relmap_params_t *)params);
}

static void rm_params_preset(void *params, fl_loc_preset_t preset)
{
    if (params == NULL)
        return;
    if (preset == FL_LOC_PRESET_VISION)
        fl_relmap_params_vision((fl_relmap_params_t *)params);
    else
        fl_relmap_params_default((fl_relmap_params_t *)params);
}

/* A low-resolution camera (AIBO, 208 px) measures ranges several times
 * less precisely: parameters still at the vision preset's values take the
 * feature-level ones (unmeasured with relmap; the looser choice). */
static void rm_params_adapt(void *params, fl_loc_preset_t preset)
{
    fl_relmap_params_t *p = (fl_relmap_params_t *)params, v, d;
    if (p == NULL || preset != FL_LOC_PRESET_VISION_LOWRES)
        return;
    fl_relmap_params_vision(&v);
    fl_relmap_params_default(&d);
    if (p->sigma_base_mm == v.sigma_base_mm && p->sigma_pct == v.sigma_pct &&
        p->err_cap_mm == v.err_cap_mm) {
        p->sigma_base_mm = d.sigma_base_mm;
        p->sigma_pct = d.sigma_pct;
        p->err_cap_mm = d.err_cap_mm;
    }
}

static fl_status_t rm_params_check(const void *params)
{
    return fl_relmap_params_check((const fl_relmap_params_t *)params);
}

static fl_status_t rm_init(void *state, const fl_field_t *field, const void *params,
                           uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT) {
        fl_relmap_clear((fl_relmap_t *)state);
        return FL_ERR_CONFIG;
    }
    return fl_relmap_init((fl_relmap_t *)state, field, (const fl_relmap_params_t *)params);
}

static void *rm_params_of(void *state)
{
    fl_relmap_t *s = (fl_relmap_t *)state;
    return s == NULL || s->field == NULL ? NULL : (void *)&s->params;
}

static void rm_predict(void *state, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    fl_relmap_predict((fl_relmap_t *)state, dx_mm, dy_mm, dtheta);
}

/* No negative information: the view is unused. */
static uint16_t rm_update(void *state, const fl_obs_list_t *obs, const fl_obs_view_t *view)
{
    (void)view;
    return fl_relmap_update((fl_relmap_t *)state, obs);
}

static bool rm_estimate(void *state, fl_loc_estimate_t *out)
{
    return fl_relmap_estimate((const fl_relmap_t *)state, out);
}

static void rm_reset_ignorance(void *state)
{
    fl_relmap_reset_ignorance((fl_relmap_t *)state);
}

/* One heading per particle: the heading uncertainty is not represented
 * (observations correct the heading through the relative map). */
static void rm_reset_pose(void *state, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                          int32_t pos_unc_mm, fl_angle_t heading_unc)
{
    (void)heading_unc;
    fl_relmap_reset_pose((fl_relmap_t *)state, x_mm, y_mm, heading, pos_unc_mm);
}

static void rm_reset_penalty(void *state, int32_t x_mm, int32_t pos_unc_mm,
                             fl_angle_t heading_unc)
{
    (void)heading_unc;
    fl_relmap_reset_penalty((fl_relmap_t *)state, x_mm, pos_unc_mm);
}

static void rm_set_prior_half(void *state, int half)
{
    fl_relmap_set_prior_half((fl_relmap_t *)state, half);
}

/* The prior's heading is not used: a particle holds the heading its
 * observations give. */
static void rm_set_prior_pose(void *state, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                              int32_t radius_mm)
{
    (void)heading;
    fl_relmap_set_prior_pose((fl_relmap_t *)state, x_mm, y_mm, radius_mm);
}

static void rm_clear_prior(void *state)
{
    fl_relmap_clear_prior((fl_relmap_t *)state);
}

static bool rm_check(const void *state)
{
    return fl_relmap_check((const fl_relmap_t *)state);
}

static uint32_t rm_possibility_q16(const void *state, int32_t x_mm, int32_t y_mm,
                                   fl_angle_t heading)
{
    return fl_relmap_possibility_q16((const fl_relmap_t *)state, x_mm, y_mm, heading);
}

static void rm_stats(const void *state, fl_loc_stats_t *out)
{
    const fl_relmap_t *s = (const fl_relmap_t *)state;
    if (!fl_loc_internal_stats_zero(state, out))
        return;
    FL_LOC_STATS_COMMON(out, &s->stats);
    out->empty_resets = s->stats.empty_resets;
}

static uint16_t rm_belief_samples(const void *state)
{
    return fl_relmap_samples((const fl_relmap_t *)state);
}

static bool rm_belief_sample(const void *state, uint16_t i, fl_loc_sample_t *out)
{
    return fl_relmap_sample((const fl_relmap_t *)state, i, out);
}

static fl_status_t rm_reseed(void *state, const fl_obs_report_t *r)
{
    return fl_relmap_reseed((fl_relmap_t *)state, r);
}

static uint32_t rm_spread_mm(const void *state)
{
    return fl_relmap_spread_mm((const fl_relmap_t *)state);
}

#define OFF(f) ((uint16_t)offsetof(fl_relmap_params_t, f))
#define U16(f) { #f, OFF(f), 2, false, 0, 65535 }
#define S32(f) { #f, OFF(f), 4, true, INT32_MIN, INT32_MAX }

static const fl_loc_param_t rm_param[] = {
    U16(sigma_base_mm), U16(sigma_pct), U16(z2_cap_q8), U16(cand_q16),
    { "max_cand", OFF(max_cand), 2, false, 1, FL_RELMAP_MAX_CAND },
    U16(err_cap_mm), U16(tie_mm), U16(white_tol_mm), U16(heading_gate_deg), U16(jump_q8), U16(frame_cap_q8),
    U16(floor_q16), U16(spread_q16), U16(kidnap_q16), U16(kidnap_frames), S32(max_range_mm), S32(odo_max_mm),
};

const fl_localizer_t fl_localizer_relmap = {
    "relmap",
    "position grid + relative landmark map (seed 002): eq. 1 distances, best heading, white-point ties",
    sizeof(fl_relmap_t),
    sizeof(fl_relmap_params_t),
    rm_param,
    (uint16_t)(sizeof rm_param / sizeof rm_param[0]),
    rm_params_default,
    rm_params_preset,
    rm_params_adapt,
    rm_params_check,
    rm_init,
    rm_params_of,
    rm_predict,
    rm_update,
    rm_estimate,
    rm_reset_ignorance,
    rm_reset_pose,
    rm_reset_penalty,
    rm_set_prior_half,
    rm_set_prior_pose,
    rm_clear_prior,
    rm_check,
    rm_possibility_q16,
    rm_stats,
    /* the grid's cells are not square on every field (the same count on
     * any carpet): the belief is shown as its particles instead */
    fl_loc_internal_no_grid,
    fl_loc_internal_no_cell,
    rm_belief_samples,
    rm_belief_sample,
    rm_reseed,
    rm_spread_mm,
    true,   /* reads_points */
};
