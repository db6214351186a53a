/*
 * src/loc/obs.c - observation lists (fixed capacity, overflow counted) and the
 * orientation convention shared by detectors and localizers.
 */
#include "fieldloc/obs.h"

#include <string.h>

void fl_obs_list_clear(fl_obs_list_t *list)
{
    if (list == NULL)
        return;
    list->n = 0;
    list->dropped = 0;
    list->n_points = 0;
    list->points_dropped = 0;
}

bool fl_obs_list_push_point(fl_obs_list_t *list, int32_t x_mm, int32_t y_mm)
{
    if (list == NULL || x_mm < -FL_OBS_MAX_RANGE_MM || x_mm > FL_OBS_MAX_RANGE_MM ||
        y_mm < -FL_OBS_MAX_RANGE_MM || y_mm > FL_OBS_MAX_RANGE_MM)
        return false;
#if FL_OBS_MAX_POINTS > 0
    if (list->n_points < FL_OBS_MAX_POINTS) {
        list->points[list->n_points].x_mm = x_mm;
        list->points[list->n_points].y_mm = y_mm;
        list->n_points++;
        return true;
    }
#endif
    if (list->points_dropped < UINT16_MAX)
        list->points_dropped++;
    return false;
}

bool fl_obs_list_push(fl_obs_list_t *list, const fl_obs_t *obs)
{
    if (list == NULL || obs == NULL)
        return false;
    if (list->n >= FL_OBS_MAX) {
        if (list->dropped < UINT16_MAX)
            list->dropped++;
        return false;
    }
    list->obs[list->n++] = *obs;
    return true;
}

/* Mean direction of two arms a, b (the bisector of the smaller angle). */
static fl_angle_t bisector(fl_angle_t a, fl_angle_t b)
{
    int32_t d = fl_angle_sub(b, a);      /* (-32768, 32767] after wrap */
    return fl_angle_add(a, fl_angle_wrap(d / 2));
}

/* Stem of a T: the arm with no arm about 180 degrees from it. */
static bool t_stem(const fl_landmark_t *lm, fl_angle_t *orientation)
{
    int i, j;
    if (lm->n_arms != 3)
        return false;
    for (i = 0; i < 3; i++) {
        bool opposite = false;
        for (j = 0; j < 3; j++) {
            int32_t d = fl_angle_sub(lm->arm[j], lm->arm[i]);
            if (j != i && (d > 32768 - 2048 || d < -32768 + 2048))
                opposite = true;
        }
        if (!opposite) {
            *orientation = lm->arm[i];
            return true;
        }
    }
    return false;
}

bool fl_landmark_orientation(const fl_landmark_t *lm, fl_angle_t *orientation)
{
    if (lm == NULL || orientation == NULL)
        return false;
    switch (lm->kind) {
    case FL_LM_L:
    case FL_LM_CORNER_C:
        if (lm->n_arms != 2)
            return false;
        *orientation = bisector(lm->arm[0], lm->arm[1]);
        return true;
    case FL_LM_T:
    case FL_LM_CORNER_TNET:
        return t_stem(lm, orientation);
    case FL_LM_CORNER_TFIELD:
        /* a T's stem, or an X's arm (mod 90 deg: fl_landmark_orientation_period) */
        if (lm->n_arms == 4) {
            *orientation = lm->arm[0];
            return true;
        }
        return t_stem(lm, orientation);
    case FL_LM_X:
    case FL_LM_PENALTY_MARK:
    case FL_LM_CENTRE_MARK:
        if (lm->n_arms < 1)
            return false;
        *orientation = lm->arm[0];
        return true;
    case FL_LM_CENTRE_CIRCLE:
        *orientation = FL_ANGLE_90;   /* the halfway line runs along y */
        return true;
    default:
        return false;
    }
}

int32_t fl_landmark_orientation_period(const fl_landmark_t *lm)
{
    if (lm == NULL)
        return 0;
    switch (lm->kind) {
    case FL_LM_L:
    case FL_LM_T:
    case FL_LM_CORNER_C:
    case FL_LM_CORNER_TNET:
        return 65536;
    case FL_LM_CORNER_TFIELD:
        return lm->n_arms == 4 ? 16384 : 65536;
    case FL_LM_X:
    case FL_LM_PENALTY_MARK:
    case FL_LM_CENTRE_MARK:
        return 16384;
    case FL_LM_CENTRE_CIRCLE:
        return 32768;
    default:
        return 0;
    }
}

fl_status_t fl_obs_report_check(const fl_obs_report_t *r, const fl_field_t *field)
{
    int32_t hx, hy;
    if (r == NULL)
        return FL_ERR_NULL;
    if (field == NULL)
        return FL_ERR_RANGE;
    hx = fl_field_carpet_half_x_mm(field);
    hy = fl_field_carpet_half_y_mm(field);
    if (r->sd_mm < FL_OBS_REPORT_SD_MIN_MM || r->sd_mm > FL_OBS_REPORT_SD_MAX_MM ||
        r->confidence == 0 || r->age_ms < 0 || r->x_mm < -hx || r->x_mm > hx ||
        r->y_mm < -hy || r->y_mm > hy)
        return FL_ERR_RANGE;
    if (r->age_ms > FL_OBS_REPORT_MAX_AGE_MS)
        return FL_ERR_STALE;
    return FL_OK;
}
