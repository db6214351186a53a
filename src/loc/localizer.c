/*
 * src/loc/localizer.c - the localizer catalogue (localizer.h), parameters
 * by name, and the checked wrappers.  Each localizer's adapter (loc_*.c)
 * defines one `const fl_localizer_t`; add it to `catalogue` below.
 */
#include "fieldloc/localizer.h"

#include <string.h>

static const fl_localizer_t *const catalogue[] = {
    &fl_localizer_fuzzy,
    &fl_localizer_mcl,
    &fl_localizer_upf,
    &fl_localizer_relmap,
};
#define N_LOC ((uint16_t)(sizeof catalogue / sizeof catalogue[0]))

static bool name_equal(const char *a, const char *b)
{
    while (*a != '\0' && *a == *b) {
        a++;
        b++;
    }
    return *a == *b;
}

const fl_localizer_t *fl_localizer_find(const char *name)
{
    uint16_t i;
    if (name == NULL)
        return NULL;
    for (i = 0; i < N_LOC; i++)
        if (name_equal(catalogue[i]->name, name))
            return catalogue[i];
    return NULL;
}

uint16_t fl_localizer_count(void)
{
    return N_LOC;
}

const fl_localizer_t *fl_localizer_get(uint16_t i)
{
    return i < N_LOC ? catalogue[i] : NULL;
}

fl_loc_preset_t fl_loc_preset_for_width(int32_t width_px)
{
    return width_px > 0 && width_px < 320 ? FL_LOC_PRESET_VISION_LOWRES
                                          : FL_LOC_PRESET_VISION;
}

/* ---- parameters by name ---- */

const fl_loc_param_t *fl_localizer_param_find(const fl_localizer_t *loc,
                                              const char *name)
{
    uint16_t i;
    if (loc == NULL || name == NULL || loc->param == NULL)
        return NULL;
    for (i = 0; i < loc->n_param; i++)
        if (name_equal(loc->param[i].name, name))
            return &loc->param[i];
    return NULL;
}

fl_status_t fl_localizer_param_set(const fl_localizer_t *loc, void *params,
                                   const char *name, int32_t value)
{
    const fl_loc_param_t *d;
    uint8_t *p = (uint8_t *)params;
    if (loc == NULL || params == NULL || name == NULL)
        return FL_ERR_NULL;
    d = fl_localizer_param_find(loc, name);
    if (d == NULL)
        return FL_ERR_NOT_FOUND;
    if (value < d->min || value > d->max ||
        (size_t)d->offset + d->size > loc->params_size)
        return FL_ERR_RANGE;
    if (d->size == 1) {
        uint8_t v = (uint8_t)(value & 0xff);
        memcpy(p + d->offset, &v, 1);
    } else if (d->size == 2) {
        uint16_t v = (uint16_t)(value & 0xffff);
        memcpy(p + d->offset, &v, 2);
    } else if (d->size == 4) {
        uint32_t v = (uint32_t)value;
        memcpy(p + d->offset, &v, 4);
    } else {
        return FL_ERR_SIZE;
    }
    return FL_OK;
}

fl_status_t fl_localizer_param_get(const fl_localizer_t *loc,
                                   const void *params, const char *name,
                                   int32_t *value)
{
    const fl_loc_param_t *d;
    const uint8_t *p = (const uint8_t *)params;
    if (loc == NULL || params == NULL || name == NULL || value == NULL)
        return FL_ERR_NULL;
    d = fl_localizer_param_find(loc, name);
    if (d == NULL)
        return FL_ERR_NOT_FOUND;
    if ((size_t)d->offset + d->size > loc->params_size)
        return FL_ERR_RANGE;
    if (d->size == 1) {
        uint8_t v;
        memcpy(&v, p + d->offset, 1);
        *value = d->is_signed ? (int32_t)(int8_t)v : (int32_t)v;
    } else if (d->size == 2) {
        uint16_t v;
        memcpy(&v, p + d->offset, 2);
        *value = d->is_signed ? (int32_t)(int16_t)v : (int32_t)v;
    } else if (d->size == 4) {
        int32_t v;
        memcpy(&v, p + d->offset, 4);
        *value = v;
    } else {
        return FL_ERR_SIZE;
    }
    return FL_OK;
}

/* ---- checked wrappers ---- */

fl_status_t fl_loc_init_cfg(const fl_localizer_t *loc, void *state,
                            const fl_field_t *field, const void *params,
                            uint32_t caller_cfg)
{
    if (loc == NULL || state == NULL || loc->init == NULL)
        return FL_ERR_NULL;
    return loc->init(state, field, params, caller_cfg);
}

void fl_loc_predict(const fl_localizer_t *loc, void *state, int32_t dx_mm,
                    int32_t dy_mm, fl_angle_t dtheta)
{
    if (loc != NULL && state != NULL && loc->predict != NULL)
        loc->predict(state, dx_mm, dy_mm, dtheta);
}

uint16_t fl_loc_update(const fl_localizer_t *loc, void *state,
                       const fl_obs_list_t *obs, const fl_obs_view_t *view)
{
    if (loc == NULL || state == NULL || loc->update == NULL)
        return 0;
    return loc->update(state, obs, view);
}

bool fl_loc_estimate(const fl_localizer_t *loc, void *state,
                     fl_loc_estimate_t *out)
{
    if (loc == NULL || state == NULL || loc->estimate == NULL) {
        if (out != NULL)
            memset(out, 0, sizeof *out);
        return false;
    }
    return loc->estimate(state, out);
}

bool fl_loc_check(const fl_localizer_t *loc, const void *state)
{
    if (loc == NULL || state == NULL || loc->check == NULL)
        return false;
    return loc->check(state);
}

fl_status_t fl_loc_reseed(const fl_localizer_t *loc, void *state, const fl_obs_report_t *r)
{
    if (loc == NULL || state == NULL || r == NULL || loc->reseed == NULL)
        return FL_ERR_NULL;
    return loc->reseed(state, r);
}

uint32_t fl_loc_spread_mm(const fl_localizer_t *loc, const void *state)
{
    if (loc == NULL || state == NULL || loc->spread_mm == NULL)
        return UINT32_MAX;
    return loc->spread_mm(state);
}

bool fl_loc_spread_beyond(const fl_localizer_t *loc, const void *state, uint32_t threshold_mm)
{
    uint32_t s = fl_loc_spread_mm(loc, state);
    return s != UINT32_MAX && s > threshold_mm;
}
