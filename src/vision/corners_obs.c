/*
 * src/vision/corners_obs.c - seed 004's corner features as observations
 * (corners.h fl_corners_obs): the seam to the localizers is obs.h alone,
 * as for the L/T/X path (no localizer header here).
 */
#include "corners_int.h"

#include <string.h>

int32_t fl_corners_obs(const fl_corners_t *c, fl_obs_list_t *out)
{
    int32_t i, n = 0;
    if (c == NULL || out == NULL || c->magic != CN_MAGIC || c->width == 0)
        return 0;
    for (i = 0; i < c->n_features && i < FL_CORNERS_MAX_FEATURES; i++) {
        const fl_cfeat_t *f = &c->feature[i];
        fl_obs_t o;
        if (!f->has_ground || f->range_mm <= 0 || f->range_mm > FL_OBS_MAX_RANGE_MM ||
            f->confidence == 0)
            continue;
        memset(&o, 0, sizeof o);
        switch (f->type) {
        case FL_CFEAT_C:
            o.kind = FL_LM_CORNER_C;
            break;
        case FL_CFEAT_T_FIELD:
            o.kind = FL_LM_CORNER_TFIELD;
            break;
        case FL_CFEAT_T_NET:
            o.kind = FL_LM_CORNER_TNET;
            break;
        case FL_CFEAT_NET_YELLOW:
            o.kind = FL_LM_NET;
            o.color = FL_COLOR_YELLOW;
            break;
        case FL_CFEAT_NET_SKYBLUE:
            o.kind = FL_LM_NET;
            o.color = FL_COLOR_SKYBLUE;
            break;
        default:
            continue;
        }
        o.side = FL_SIDE_UNKNOWN;
        o.range_mm = f->range_mm;
        o.bearing = f->bearing;
        o.has_orientation = false;
        o.orientation = 0;
        o.confidence = f->confidence;
        o.u_q4 = f->u_q4;
        o.v_q4 = f->v_q4;
        o.color2 = FL_COLOR_NONE;
        if (fl_obs_list_push(out, &o))
            n++;
    }
    return n;
}
