/*
 * src/loc/loc_mcl.c - the Monte Carlo localizer (mcl.h) behind the
 * localizer interface (localizer.h) as "mcl".  The only interface file
 * that knows fl_mcl_t; it calls the public fl_mcl_* API only.
 */
#include "fieldloc/localizer.h"
#include "fieldloc/mcl.h"
#include "loc_particle.h"

#include <stddef.h>
#include <string.h>

static void mc_params_default(void *params)
{
    if (params != NULL)
        fl_mcl_params_default((fl_mcl_params_t *)params);
}

static void mc_params_preset(void *params, fl_loc_preset_t preset)
{
    fl_mcl_params_t *p = (fl_mcl_params_t *)params;
    if (p == NULL)
        return;
    switch (preset) {
    case FL_LOC_PRESET_VISION:
        fl_mcl_params_vision(p, false);
        break;
    case FL_LOC_PRESET_VISION_LOWRES:
        fl_mcl_params_vision(p, true);
        break;
    case FL_LOC_PRESET_DEFAULT:
    default:
        fl_mcl_params_default(p);
        break;
    }
}

/* Only a NAO vision preset becomes the AIBO's (the parameters a caller
 * holds for feature-level observations stay as they are). */
static void mc_params_adapt(void *params, fl_loc_preset_t preset)
{
    fl_mcl_params_t *p = (fl_mcl_params_t *)params;
    fl_mcl_params_t v;
    if (p == NULL || preset != FL_LOC_PRESET_VISION_LOWRES)
        return;
    fl_mcl_params_vision(&v, false);
    if (p->range_pct == v.range_pct && p->bearing_mdeg == v.bearing_mdeg)
        fl_mcl_params_lowres(p);
}

static fl_status_t mc_params_check(const void *params)
{
    return fl_mcl_params_check((const fl_mcl_params_t *)params);
}

static fl_status_t mc_init(void *state, const fl_field_t *field, const void *params,
                           uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT) {
        fl_mcl_clear((fl_mcl_t *)state);
        return FL_ERR_CONFIG;
    }
    return fl_mcl_init((fl_mcl_t *)state, field, (const fl_mcl_params_t *)params);
}

static void *mc_params_of(void *state)
{
    fl_mcl_t *s = (fl_mcl_t *)state;
    return s == NULL || s->core.field == NULL ? NULL : (void *)&s->params;
}

static void mc_predict(void *state, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    fl_mcl_predict((fl_mcl_t *)state, dx_mm, dy_mm, dtheta);
}

/* The particle filter takes no negative information: the view is unused. */
static uint16_t mc_update(void *state, const fl_obs_list_t *obs, const fl_obs_view_t *view)
{
    (void)view;
    return fl_mcl_update((fl_mcl_t *)state, obs);
}

void fl_loc_internal_from_mcl(const fl_mcl_estimate_t *e, fl_loc_estimate_t *out)
{
    memset(out, 0, sizeof *out);
    out->x_mm = e->x_mm;
    out->y_mm = e->y_mm;
    out->heading = e->heading;
    out->reliability_q16 = e->reliability_q16;
    out->peak_q8 = (uint8_t)(e->share_q16 >> 8);
    out->mode_cells = e->mode_particles;
    out->switched = e->switched;
    out->sd_x_mm = e->sd_x_mm;
    out->sd_y_mm = e->sd_y_mm;
    out->cov_xy_mm2 = e->cov_xy_mm2;
    out->sd_heading = e->sd_heading;
    out->mirror_q16 = e->mirror_q16;
    out->score_q16 = e->score_q16;
    out->since_obs = e->since_obs;
    out->state = !e->tracking || e->ignorance ? FL_LOC_LOST
                 : e->mirror_q16 >= 32768u    ? FL_LOC_AMBIGUOUS
                                              : FL_LOC_TRACKING;
    out->localized = out->state == FL_LOC_TRACKING &&
                     out->reliability_q16 >= FL_LOC_LOCALIZED_Q16;
}

static bool mc_estimate(void *state, fl_loc_estimate_t *out)
{
    fl_mcl_estimate_t e;
    bool ok;
    if (out == NULL)
        return false;
    ok = fl_mcl_estimate((fl_mcl_t *)state, &e);
    fl_loc_internal_from_mcl(&e, out);
    return ok;
}

static void mc_reset_ignorance(void *state)
{
    fl_mcl_reset_ignorance((fl_mcl_t *)state);
}

static void mc_reset_pose(void *state, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                          int32_t pos_unc_mm, fl_angle_t heading_unc)
{
    fl_mcl_reset_pose((fl_mcl_t *)state, x_mm, y_mm, heading, pos_unc_mm, heading_unc);
}

static void mc_reset_penalty(void *state, int32_t x_mm, int32_t pos_unc_mm,
                             fl_angle_t heading_unc)
{
    fl_mcl_reset_penalty((fl_mcl_t *)state, x_mm, pos_unc_mm, heading_unc);
}

static void mc_set_prior_half(void *state, int half)
{
    fl_mcl_set_prior_half((fl_mcl_t *)state, half);
}

static void mc_set_prior_pose(void *state, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                              int32_t radius_mm)
{
    fl_mcl_set_prior_pose((fl_mcl_t *)state, x_mm, y_mm, heading, radius_mm);
}

static void mc_clear_prior(void *state)
{
    fl_mcl_clear_prior((fl_mcl_t *)state);
}

static bool mc_check(const void *state)
{
    return fl_mcl_check((const fl_mcl_t *)state);
}

static uint32_t mc_possibility_q16(const void *state, int32_t x_mm, int32_t y_mm,
                                   fl_angle_t heading)
{
    return fl_mcl_possibility_q16((const fl_mcl_t *)state, x_mm, y_mm, heading);
}

static void mc_stats(const void *state, fl_loc_stats_t *out)
{
    const fl_mcl_t *s = (const fl_mcl_t *)state;
    if (!fl_loc_internal_stats_zero(state, out))
        return;
    FL_LOC_STATS_COMMON(out, &s->stats);
}

/* Particles are not a grid (loc_adapter.h; relmap's grid shows its
 * particles too). */
bool fl_loc_internal_no_grid(const void *state, fl_loc_grid_t *out)
{
    (void)state;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    return false;
}

bool fl_loc_internal_no_cell(const void *state, int ix, int iy, fl_loc_cell_t *out)
{
    (void)state;
    (void)ix;
    (void)iy;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    return false;
}

static uint16_t mc_belief_samples(const void *state)
{
    const fl_mcl_t *s = (const fl_mcl_t *)state;
    return s == NULL || s->core.field == NULL ? 0 : s->n;
}

/* Weight relative to the heaviest particle (the update normalises the
 * heaviest to 65535); in the mode: within cluster_mm of the tracked
 * estimate and heading within 90 deg of it.  A point: no spread. */
void fl_loc_internal_sample(const fl_mcl_core_t *c, int32_t cluster_mm,
                            const fl_mcl_particle_t *p, fl_loc_sample_t *out)
{
    out->x_mm = p->x_mm;
    out->y_mm = p->y_mm;
    out->heading = p->heading;
    out->weight_q16 = p->weight;
    if (c->track_valid) {
        int32_t dx = p->x_mm - c->track_x_mm, dy = p->y_mm - c->track_y_mm;
        int32_t dh = fl_angle_sub(p->heading, c->track_heading);
        int64_t r = cluster_mm;
        out->in_mode = (int64_t)dx * dx + (int64_t)dy * dy <= r * r && dh <= FL_ANGLE_90 &&
                       dh >= -FL_ANGLE_90;
    }
}

static bool mc_belief_sample(const void *state, uint16_t i, fl_loc_sample_t *out)
{
    const fl_mcl_t *s = (const fl_mcl_t *)state;
    if (out == NULL)
        return false;
    memset(out, 0, sizeof *out);
    if (s == NULL || s->core.field == NULL || i >= s->n)
        return false;
    fl_loc_internal_sample(&s->core, s->params.cluster_mm, &s->buf[s->cur & 1u][i], out);
    return true;
}

#define OFF(f) ((uint16_t)offsetof(fl_mcl_params_t, f))
#define U8(f)  { #f, OFF(f), 1, false, 0, 255 }
#define U16(f) { #f, OFF(f), 2, false, 0, 65535 }
#define S32(f) { #f, OFF(f), 4, true, INT32_MIN, INT32_MAX }

static const fl_loc_param_t mc_param[] = {
    { "seed", OFF(seed), 4, true, 0, INT32_MAX },
    { "n_particles", OFF(n_particles), 2, false, 1, FL_MCL_MAX_PARTICLES },
    U16(odo_trans_pct), U16(odo_rot_pct), U16(odo_rot_mdeg_per_m), S32(odo_max_mm),
    U16(jitter_mm), U16(jitter_mdeg), S32(margin_mm), U16(range_pct), U16(range_base_mm),
    U16(bearing_mdeg), U16(orient_mdeg), U16(assoc_q8), U16(outlier_q16), U8(corner_any), S32(max_range_mm),
    S32(cross_max_mm), U16(alpha_slow_q16), U16(alpha_fast_q16), U16(inject_max_q16), U16(inject_min_q16),
    U16(kidnap_q16), S32(cluster_mm), U8(switch_q8),
};

static fl_status_t mc_reseed(void *state, const fl_obs_report_t *r)
{
    return fl_mcl_reseed((fl_mcl_t *)state, r);
}

static uint32_t mc_spread_mm(const void *state)
{
    return fl_mcl_spread_mm((const fl_mcl_t *)state);
}

const fl_localizer_t fl_localizer_mcl = {
    "mcl",
    "augmented Monte Carlo localization (seed 000): particles, sensor resetting",
    sizeof(fl_mcl_t),
    sizeof(fl_mcl_params_t),
    mc_param,
    (uint16_t)(sizeof mc_param / sizeof mc_param[0]),
    mc_params_default,
    mc_params_preset,
    mc_params_adapt,
    mc_params_check,
    mc_init,
    mc_params_of,
    mc_predict,
    mc_update,
    mc_estimate,
    mc_reset_ignorance,
    mc_reset_pose,
    mc_reset_penalty,
    mc_set_prior_half,
    mc_set_prior_pose,
    mc_clear_prior,
    mc_check,
    mc_possibility_q16,
    mc_stats,
    fl_loc_internal_no_grid,
    fl_loc_internal_no_cell,
    mc_belief_samples,
    mc_belief_sample,
    mc_reseed,
    mc_spread_mm,
    false,   /* reads_points */
};
