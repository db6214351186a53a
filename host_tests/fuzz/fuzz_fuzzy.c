/*
 * libFuzzer harness: arbitrary odometry and observation lists through the
 * fuzzy position grid.  Input: byte 0 = field, then records of 16 bytes:
 *   [0] op: 0 predict, 1 update one, 2 estimate, 3 reset ignorance,
 *           4 reset pose, 5 penalty placement, 6 prior half, 7 one
 *           observation with a view (fl_fuzzy_update_view: bearings,
 *           near and far from the record)
 * Byte 0 bit 7: the vision path's additions on (negative information,
 * L/T confusion, far-crossing cut-off).
 *   [1..15] raw values (odometry up to INT32 extremes, observation kind,
 *           range 0 .. 2^31, bearing, orientation, confidence, side).
 * After every operation the grid must satisfy fl_fuzzy_check and every
 * estimate must lie on the carpet with reliability in [0, 1].
 */
#include "fieldloc/fieldloc.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static fl_fuzzy_t grid;
static fl_fuzzy_params_t params;

static int32_t rd32(const uint8_t *p)
{
    return (int32_t)((uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
                     ((uint32_t)p[3] << 24));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const fl_field_t *field;
    size_t k;
    if (size < 1)
        return 0;
    field = fl_field_at((size_t)(data[0] & 0x7f) % fl_field_count());
    fl_fuzzy_params_default(&params);
    if (data[0] & 0x80) {
        params.neg_q8 = 100;
        params.neg_min_q8 = 128;
        params.neg_kidnap = 2;
        params.confuse_q8 = 100;
        params.confuse_conf = 160;
        params.cross_max_mm = 2500;
    }
    if (fl_fuzzy_init(&grid, field, &params) != FL_OK)
        abort();
    for (k = 1; k + 16 <= size; k += 16) {
        const uint8_t *r = data + k;
        fl_obs_t o;
        fl_fuzzy_estimate_t e;
        switch (r[0] % 8) {
        case 0:
            fl_fuzzy_predict(&grid, rd32(r + 1), rd32(r + 5), (fl_angle_t)(int16_t)(r[9] | (r[10] << 8)));
            break;
        case 1:
            memset(&o, 0, sizeof o);
            o.kind = (fl_landmark_kind_t)(r[1] % (FL_LM_KIND_COUNT + 2));
            o.side = (fl_side_t)(r[2] % 4);
            o.color = (fl_color_t)(r[3] % 6);
            o.range_mm = rd32(r + 4);
            o.bearing = (fl_angle_t)(int16_t)(r[8] | (r[9] << 8));
            o.orientation = (fl_angle_t)(int16_t)(r[10] | (r[11] << 8));
            o.has_orientation = (r[12] & 1) != 0;
            o.confidence = r[13];
            o.u_q4 = o.v_q4 = -1;
            (void)fl_fuzzy_update_one(&grid, &o);
            break;
        case 2:
            if (!fl_fuzzy_estimate(&grid, &e))
                abort();
            if (e.x_mm < -fl_field_carpet_half_x_mm(field) || e.x_mm > fl_field_carpet_half_x_mm(field) ||
                e.y_mm < -fl_field_carpet_half_y_mm(field) || e.y_mm > fl_field_carpet_half_y_mm(field))
                abort();
            break;
        case 3:
            fl_fuzzy_reset_ignorance(&grid);
            break;
        case 4:
            fl_fuzzy_reset_pose(&grid, rd32(r + 1), rd32(r + 5), (fl_angle_t)(int16_t)(r[9] | (r[10] << 8)),
                                rd32(r + 11) & 0xfffff, (fl_angle_t)(r[15] << 6));
            break;
        case 5:
            fl_fuzzy_reset_penalty(&grid, rd32(r + 1), rd32(r + 5) & 0xfffff, (fl_angle_t)(r[9] << 6));
            break;
        case 6:
            fl_fuzzy_set_prior_half(&grid, (int)(r[1] % 3) - 1);
            break;
        default: {
            fl_obs_list_t list;
            fl_obs_view_t v;
            memset(&o, 0, sizeof o);
            o.kind = (fl_landmark_kind_t)(r[1] % (FL_LM_KIND_COUNT + 2));
            o.range_mm = (int32_t)(r[2] | (r[3] << 8)) * 4;
            o.bearing = (fl_angle_t)(int16_t)(r[4] | (r[5] << 8));
            o.orientation = (fl_angle_t)(int16_t)(r[6] | (r[7] << 8));
            o.has_orientation = (r[8] & 1) != 0;
            o.confidence = r[9];
            o.u_q4 = o.v_q4 = -1;
            fl_obs_list_clear(&list);
            if (r[8] & 2)
                fl_obs_list_push(&list, &o);
            v.valid = (r[8] & 4) != 0;
            v.bearing_right = (fl_angle_t)(int16_t)(r[10] << 8);
            v.bearing_left = (fl_angle_t)(int16_t)(r[11] << 8);
            v.near_mm = (int32_t)(r[12] | (r[13] << 8)) - 1000;
            v.far_mm = (int32_t)(r[14] | (r[15] << 8)) - 1000;
            (void)fl_fuzzy_update_view(&grid, &list, &v);
            break;
        }
        }
        if (!fl_fuzzy_check(&grid))
            abort();
    }
    return 0;
}
