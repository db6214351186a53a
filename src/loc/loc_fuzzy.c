/*
 * src/loc/loc_fuzzy.c - the fuzzy position grid (fuzzy.h) behind the
 * localizer interface (localizer.h) as "fuzzy".  The only interface file
 * that knows fl_fuzzy_t; it calls the public fl_fuzzy_* API only.
 */
#include "fieldloc/localizer.h"
#include "fieldloc/fuzzy.h"
#include "loc_adapter.h"

#include <stddef.h>
#include <string.h>

static void fz_params_default(void *params)
{
    if (params != NULL)
        fl_fuzzy_params_default((fl_fuzzy_params_t *)params);
}

static void fz_params_preset(void *params, fl_loc_preset_t preset)
{
    fl_fuzzy_params_t *p = (fl_fuzzy_params_t *)params;
    if (p == NULL)
        return;
    switch (preset) {
    case FL_LOC_PRESET_VISION:
        fl_fuzzy_params_vision(p, false);
        break;
    case FL_LOC_PRESET_VISION_LOWRES:
        fl_fuzzy_params_vision(p, true);
        break;
    case FL_LOC_PRESET_DEFAULT:
    default:
        fl_fuzzy_params_default(p);
        break;
    }
}

static void fz_params_adapt(void *params, fl_loc_preset_t preset)
{
    if (params == NULL || preset != FL_LOC_PRESET_VISION_LOWRES)
        return;
    fl_fuzzy_params_lowres((fl_fuzzy_params_t *)params);
}

static fl_status_t fz_params_check(const void *params)
{
    return fl_fuzzy_params_check((const fl_fuzzy_params_t *)params);
}

static fl_status_t fz_init(void *state, const fl_field_t *field, const void *params,
                           uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT) {
        /* the state is state_size bytes, the library's layout: left empty
         * the way fl_fuzzy_init leaves it without a field */
        (void)fl_fuzzy_init((fl_fuzzy_t *)state, NULL, NULL);
        return FL_ERR_CONFIG;
    }
    return fl_fuzzy_init((fl_fuzzy_t *)state, field, (const fl_fuzzy_params_t *)params);
}

static void *fz_params_of(void *state)
{
    fl_fuzzy_t *g = (fl_fuzzy_t *)state;
    return g == NULL || g->field == NULL ? NULL : (void *)&g->params;
}

static void fz_predict(void *state, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    fl_fuzzy_predict((fl_fuzzy_t *)state, dx_mm, dy_mm, dtheta);
}

static uint16_t fz_update(void *state, const fl_obs_list_t *obs, const fl_obs_view_t *view)
{
    return fl_fuzzy_update_view((fl_fuzzy_t *)state, obs, view);
}

static bool fz_estimate(void *state, fl_loc_estimate_t *out)
{
    fl_fuzzy_estimate_t e;
    bool ok;
    if (out == NULL)
        return false;
    ok = fl_fuzzy_estimate((fl_fuzzy_t *)state, &e);
    memset(out, 0, sizeof *out);
    out->x_mm = e.x_mm;
    out->y_mm = e.y_mm;
    out->heading = e.heading;
    out->peak_q8 = e.peak_q8;
    out->mode_cells = e.mode_cells;
    out->switched = e.switched;
    out->reliability_q16 = e.calibrated_q16;
    out->score_q16 = e.reliability_q16;
    out->sd_x_mm = e.sd_x_mm;
    out->sd_y_mm = e.sd_y_mm;
    out->cov_xy_mm2 = e.cov_xy_mm2;
    out->sd_heading = e.sd_heading;
    out->mirror_q16 = e.mirror_q16;
    out->since_obs = e.since_obs;
    out->state = !e.tracking || e.ignorance ? FL_LOC_LOST
                 : e.mirror_q16 >= 32768u   ? FL_LOC_AMBIGUOUS
                                            : FL_LOC_TRACKING;
    out->localized = out->state == FL_LOC_TRACKING &&
                     out->reliability_q16 >= FL_LOC_LOCALIZED_Q16;
    return ok;
}

static void fz_reset_ignorance(void *state)
{
    fl_fuzzy_reset_ignorance((fl_fuzzy_t *)state);
}

static void fz_reset_pose(void *state, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                          int32_t pos_unc_mm, fl_angle_t heading_unc)
{
    fl_fuzzy_reset_pose((fl_fuzzy_t *)state, x_mm, y_mm, heading, pos_unc_mm, heading_unc);
}

static void fz_reset_penalty(void *state, int32_t x_mm, int32_t pos_unc_mm,
                             fl_angle_t heading_unc)
{
    fl_fuzzy_reset_penalty((fl_fuzzy_t *)state, x_mm, pos_unc_mm, heading_unc);
}

static void fz_set_prior_half(void *state, int half)
{
    fl_fuzzy_set_prior_half((fl_fuzzy_t *)state, half);
}

static void fz_set_prior_pose(void *state, int32_t x_mm, int32_t y_mm,
                              fl_angle_t heading, int32_t radius_mm)
{
    fl_fuzzy_set_prior_pose((fl_fuzzy_t *)state, x_mm, y_mm, heading, radius_mm);
}

static void fz_clear_prior(void *state)
{
    fl_fuzzy_clear_prior((fl_fuzzy_t *)state);
}

static bool fz_check(const void *state)
{
    return fl_fuzzy_check((const fl_fuzzy_t *)state);
}

static uint32_t fz_possibility_q16(const void *state, int32_t x_mm, int32_t y_mm,
                                   fl_angle_t heading)
{
    return fl_fuzzy_possibility_q16((const fl_fuzzy_t *)state, x_mm, y_mm, heading);
}

static void fz_stats(const void *state, fl_loc_stats_t *out)
{
    const fl_fuzzy_t *g = (const fl_fuzzy_t *)state;
    if (!fl_loc_internal_stats_zero(state, out))
        return;
    FL_LOC_STATS_COMMON(out, &g->stats);
    out->obs_gated = g->stats.obs_gated;
    out->empty_resets = g->stats.empty_resets;
}

static bool fz_belief_grid(const void *state, fl_loc_grid_t *out)
{
    const fl_fuzzy_t *g = (const fl_fuzzy_t *)state;
    if (out == NULL)
        return false;
    memset(out, 0, sizeof *out);
    if (g == NULL || g->field == NULL || g->nx == 0 || g->ny == 0)
        return false;
    out->nx = g->nx;
    out->ny = g->ny;
    out->x0_mm = g->x0_mm;
    out->y0_mm = g->y0_mm;
    out->cell_mm = FL_FUZZY_CELL_MM;
    return true;
}

static bool fz_belief_cell(const void *state, int ix, int iy, fl_loc_cell_t *out)
{
    const fl_fuzzy_t *g = (const fl_fuzzy_t *)state;
    const fl_fuzzy_cell_t *c;
    if (out == NULL)
        return false;
    memset(out, 0, sizeof *out);
    if (g == NULL || g->field == NULL || ix < 0 || iy < 0 || ix >= g->nx || iy >= g->ny)
        return false;
    c = &g->cell[iy * g->nx + ix];
    out->height_q8 = c->height;
    out->heading = c->centre;
    out->spread = c->core >= FL_FUZZY_WFULL ? FL_FUZZY_HALF_TURN
                                            : (int32_t)c->core * FL_FUZZY_AUNIT;
    return true;
}

/* The grid is not a set of samples. */
static uint16_t fz_belief_samples(const void *state)
{
    (void)state;
    return 0;
}

static bool fz_belief_sample(const void *state, uint16_t i, fl_loc_sample_t *out)
{
    (void)state;
    (void)i;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    return false;
}

/* Parameter table: every field of fl_fuzzy_params_t, in declaration order,
 * with the range of its type (fl_fuzzy_params_check decides the rest). */
#define OFF(f) ((uint16_t)offsetof(fl_fuzzy_params_t, f))
#define U8(f)  { #f, OFF(f), 1, false, 0, 255 }
#define U16(f) { #f, OFF(f), 2, false, 0, 65535 }
#define S16(f) { #f, OFF(f), 2, true, -32768, 32767 }
#define S32(f) { #f, OFF(f), 4, true, INT32_MIN, INT32_MAX }

static const fl_loc_param_t fz_param[] = {
    U16(odo_trans_q8), U16(odo_turn_mm_per_rad), U16(odo_rot_q8), U16(odo_rot_per_m),
    U8(blur_kappa_min_q8), U8(blur_kappa_gain_q8), U8(blur_kappa_max_q8), U16(blur_step_mm),
    U16(wide_core), S32(odo_max_mm), S32(ring_base_mm), U16(ring_core_q8), S32(ring_slope_mm),
    U16(ring_slope_q8), U16(ring_track_q8), S16(bearing_core), S16(bearing_slope),
    S16(head_min_core), S16(head_min_slope), S16(orient_core), S16(orient_slope),
    U8(bias_min_q8), U8(head_bias_q8), U8(head_bias_outlier), U8(confuse_q8), U8(confuse_conf),
    S32(max_range_mm), S32(cross_max_mm), U8(min_height_q8), S32(mode_radius_mm),
    S32(track_radius_mm), U8(switch_q8), U16(track_min_q16), U8(gate_q8), U8(gate_run),
    U8(cons_shift), U16(kidnap_q16), U16(kidnap_rate_q8), U8(neg_q8), U8(neg_max), U8(neg_track),
    U8(neg_kidnap), S32(neg_margin_mm), U16(neg_range_q8), S16(neg_bearing), S16(neg_head_max),
    U8(neg_min_q8),
};

static fl_status_t fz_reseed(void *state, const fl_obs_report_t *r)
{
    return fl_fuzzy_reseed((fl_fuzzy_t *)state, r);
}

static uint32_t fz_spread_mm(const void *state)
{
    return fl_fuzzy_spread_mm((const fl_fuzzy_t *)state);
}

const fl_localizer_t fl_localizer_fuzzy = {
    "fuzzy",
    "fuzzy position grid (seed 004): heading trapezoid per 100 mm cell",
    sizeof(fl_fuzzy_t),
    sizeof(fl_fuzzy_params_t),
    fz_param,
    (uint16_t)(sizeof fz_param / sizeof fz_param[0]),
    fz_params_default,
    fz_params_preset,
    fz_params_adapt,
    fz_params_check,
    fz_init,
    fz_params_of,
    fz_predict,
    fz_update,
    fz_estimate,
    fz_reset_ignorance,
    fz_reset_pose,
    fz_reset_penalty,
    fz_set_prior_half,
    fz_set_prior_pose,
    fz_clear_prior,
    fz_check,
    fz_possibility_q16,
    fz_stats,
    fz_belief_grid,
    fz_belief_cell,
    fz_belief_samples,
    fz_belief_sample,
    fz_reseed,
    fz_spread_mm,
    false,   /* reads_points */
};
