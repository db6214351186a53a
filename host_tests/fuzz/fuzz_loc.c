/*
 * libFuzzer harness: arbitrary odometry, observation lists, views, resets
 * and priors through every localizer of the catalogue, by the localizer
 * interface (localizer.h) only, so each new localizer is fuzzed by being
 * listed.  Input: byte 0 = localizer (low 3 bits, modulo the catalogue)
 * and field (next 2 bits); byte 1 = preset (modulo 3) and the random seed
 * for a localizer with a "seed" parameter; then records of 16 bytes:
 *   [0] op: 0 predict (raw int32 odometry up to the extremes), 1 update
 *           with up to 8 observations built from the record (kinds outside
 *           the enum, ranges 0 .. 2^31, any bearing/orientation/colour/side),
 *           2 estimate, 3 reset ignorance, 4 reset pose, 5 penalty
 *           placement, 6 prior half, 7 prior pose, 8 clear prior,
 *           9 update with one observation repeated FL_OBS_MAX times and a
 *           view, 10 samples and possibility, 11 empty update, or (byte 1
 *           bit 7) a re-seed from a report built from the record (any
 *           position, sd, confidence, age) and the spread query
 * After every operation the localizer's check must hold; every estimate
 * must lie on the carpet with its spread and state in range; every sample
 * must lie within the carpet plus a 1 m margin; a re-seed is accepted or
 * refused with a report's status, and the spread is finite.
 */
#include "fieldloc/fieldloc.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static union { int64_t align; uint8_t b[256 * 1024]; } state;
static union { int64_t align; uint8_t b[4096]; } params;
static fl_obs_list_t list;

static int32_t rd32(const uint8_t *p)
{
    return (int32_t)((uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
                     ((uint32_t)p[3] << 24));
}

static fl_angle_t rd16(const uint8_t *p)
{
    return (fl_angle_t)(int16_t)(uint16_t)(p[0] | (p[1] << 8));
}

static void obs_from(const uint8_t *r, fl_obs_t *o)
{
    memset(o, 0, sizeof *o);
    o->kind = (fl_landmark_kind_t)(r[0] % (FL_LM_KIND_COUNT + 2));
    o->side = (fl_side_t)(r[1] % 4);
    o->color = (fl_color_t)(r[1] / 4 % 6);
    o->color2 = (fl_color_t)(r[1] / 32 % 6);
    o->range_mm = (r[2] & 0x80) ? rd32(r + 2) : (int32_t)(r[2] | (r[3] << 8)) * 2;
    o->bearing = rd16(r + 4);
    o->orientation = rd16(r + 6);
    o->has_orientation = (r[0] & 0x40) != 0;
    o->confidence = r[3];
    o->u_q4 = o->v_q4 = -1;
}

static void check_estimate(const fl_localizer_t *loc, const fl_field_t *f)
{
    fl_loc_estimate_t e;
    int32_t hx = fl_field_carpet_half_x_mm(f), hy = fl_field_carpet_half_y_mm(f);
    if (!loc->estimate(state.b, &e))
        abort();
    if (e.x_mm < -hx || e.x_mm > hx || e.y_mm < -hy || e.y_mm > hy)
        abort();
    if (e.state != FL_LOC_LOST && e.state != FL_LOC_AMBIGUOUS && e.state != FL_LOC_TRACKING)
        abort();
    if (e.localized != (e.state == FL_LOC_TRACKING && e.reliability_q16 >= FL_LOC_LOCALIZED_Q16))
        abort();
    if (e.sd_heading < 0)
        abort();
}

static void check_samples(const fl_localizer_t *loc, const fl_field_t *f)
{
    int32_t hx = fl_field_carpet_half_x_mm(f) + 1000, hy = fl_field_carpet_half_y_mm(f) + 1000;
    uint16_t n = loc->belief_samples(state.b), i;
    fl_loc_sample_t s;
    for (i = 0; i < n; i++) {
        if (!loc->belief_sample(state.b, i, &s))
            abort();
        if (s.x_mm < -hx || s.x_mm > hx || s.y_mm < -hy || s.y_mm > hy)
            abort();
    }
    if (loc->belief_sample(state.b, n, &s))
        abort();
}

static void reseed_from(const fl_localizer_t *loc, const uint8_t *r)
{
    fl_obs_report_t rep;
    fl_status_t st;
    uint32_t sp;
    memset(&rep, 0, sizeof rep);
    rep.x_mm = (r[2] & 0x80) ? rd32(r + 2) : rd16(r + 2);
    rep.y_mm = (r[6] & 0x80) ? rd32(r + 6) : rd16(r + 6);
    rep.sd_mm = rd16(r + 10);
    rep.confidence = r[12];
    rep.age_ms = rd16(r + 13);
    rep.team = r[15];
    st = fl_loc_reseed(loc, state.b, &rep);
    if (st != FL_OK && st != FL_ERR_RANGE && st != FL_ERR_STALE)
        abort();
    sp = fl_loc_spread_mm(loc, state.b);
    if (sp > 100000u)
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const fl_localizer_t *loc;
    const fl_field_t *field;
    fl_obs_view_t view;
    size_t k;
    int i;
    if (size < 2)
        return 0;
    loc = fl_localizer_get((uint16_t)((data[0] & 7) % fl_localizer_count()));
    field = fl_field_at((size_t)((data[0] >> 3) & 3) % fl_field_count());
    if (loc == NULL || field == NULL || loc->state_size > sizeof state.b ||
        loc->params_size > sizeof params.b)
        abort();
    loc->params_preset(params.b, (fl_loc_preset_t)(data[1] % 3));
    if (fl_localizer_param_find(loc, "seed") != NULL &&
        fl_localizer_param_set(loc, params.b, "seed", data[1]) != FL_OK)
        abort();
    {
        fl_status_t st = fl_loc_init(loc, state.b, field, params.b);
        if (st != FL_OK) {
            fprintf(stderr, "init %s %s preset %d: %d\n", loc->name, field->name, data[1] % 3, (int)st);
            abort();
        }
    }
    for (k = 2; k + 16 <= size; k += 16) {
        const uint8_t *r = data + k;
        fl_obs_t o;
        switch (r[0] % 12) {
        case 0:
            loc->predict(state.b, rd32(r + 1), rd32(r + 5), rd16(r + 9));
            break;
        case 1:
            fl_obs_list_clear(&list);
            for (i = 0; i < (r[1] & 7) + 1 && i <= 6; i++) {
                obs_from(r + 2 + i, &o);   /* overlapping 8-byte windows */
                fl_obs_list_push(&list, &o);
            }
            (void)loc->update(state.b, &list, NULL);
            break;
        case 2:
            check_estimate(loc, field);
            break;
        case 3:
            loc->reset_ignorance(state.b);
            break;
        case 4:
            loc->reset_pose(state.b, rd32(r + 1), rd32(r + 5), rd16(r + 9),
                            rd32(r + 11) & 0xfffff, (fl_angle_t)(r[15] << 6));
            break;
        case 5:
            loc->reset_penalty(state.b, rd32(r + 1), rd32(r + 5) & 0xfffff, (fl_angle_t)(r[9] << 6));
            break;
        case 6:
            loc->set_prior_half(state.b, (int)(r[1] % 3) - 1);
            break;
        case 7:
            loc->set_prior_pose(state.b, rd32(r + 1), rd32(r + 5), rd16(r + 9), rd32(r + 11));
            break;
        case 8:
            loc->clear_prior(state.b);
            break;
        case 9:
            obs_from(r + 1, &o);
            fl_obs_list_clear(&list);
            for (i = 0; i < FL_OBS_MAX + 2; i++)
                fl_obs_list_push(&list, &o);
            view.valid = (r[9] & 1) != 0;
            view.bearing_right = (fl_angle_t)(int16_t)(r[10] << 8);
            view.bearing_left = (fl_angle_t)(int16_t)(r[11] << 8);
            view.near_mm = (int32_t)(r[12] | (r[13] << 8)) - 1000;
            view.far_mm = (int32_t)(r[14] | (r[15] << 8)) - 1000;
            (void)loc->update(state.b, &list, &view);
            break;
        case 10:
            check_samples(loc, field);
            (void)loc->possibility_q16(state.b, rd32(r + 1), rd32(r + 5), rd16(r + 9));
            break;
        default:
            if (r[1] & 0x80) {
                reseed_from(loc, r);
                break;
            }
            fl_obs_list_clear(&list);
            (void)loc->update(state.b, &list, NULL);
            break;
        }
        if (!loc->check(state.b))
            abort();
    }
    return 0;
}
