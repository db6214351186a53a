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

bool fl_landmark_orientation(const fl_landmark_t *lm, fl_angle_t *orientation)
{
    int i, j;
    if (lm == NULL || orientation == NULL)
        return false;
    switch (lm->kind) {
    case FL_LM_L:
        if (lm->n_arms != 2)
            return false;
        *orientation = bisector(lm->arm[0], lm->arm[1]);
        return true;
    case FL_LM_T:
        if (lm->n_arms != 3)
            return false;
        /* the stem is the arm with no arm about 180 degrees from it */
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

/* Samples along each edge of the shrunk image (fl_obs_view_from_camera). */
#define VIEW_SAMPLES 5

/* Scaling: pixel coordinates Q4 < 2^20 (config caps the image size), the
 * sample interpolation (u1 - u0) * i < 2^23; ranges and bearings from
 * fl_polar_from_point.  Bearings are taken relative to the head yaw so
 * that min / max never straddle the +-180 degree wrap. */
void fl_obs_view_from_camera(const fl_camera_t *cam, int32_t margin_px,
                             int32_t max_range_mm, fl_obs_view_t *view)
{
    int32_t w, h, m, u0, u1, v0, v1, hz, near = 0, far, i;
    int32_t bl = INT32_MAX, br = INT32_MIN;
    fl_angle_t yaw;
    if (view == NULL)
        return;
    memset(view, 0, sizeof *view);
    if (cam == NULL || max_range_mm <= 0)
        return;
    w = cam->model.width_px;
    h = cam->model.height_px;
    if (w < 8 || h < 8 || margin_px < 0 || margin_px > (w < h ? w : h) / 4)
        return;
    m = margin_px * 16;
    u0 = m;
    u1 = (w - 1) * 16 - m;
    v0 = m;
    v1 = (h - 1) * 16 - m;
    hz = fl_camera_horizon_v_q4(cam, (u0 + u1) / 2);
    if (hz == INT32_MAX)
        return;
    if (hz != INT32_MIN && hz + m > v0)
        v0 = hz + m;
    if (v0 >= v1)
        return;
    yaw = cam->pose.head_yaw;
    far = max_range_mm;
    for (i = 0; i < VIEW_SAMPLES; i++) {
        int32_t u = u0 + ((u1 - u0) * i) / (VIEW_SAMPLES - 1);
        int32_t v = v0 + ((v1 - v0) * i) / (VIEW_SAMPLES - 1);
        fl_point_t gp;
        int32_t r, rb;
        fl_angle_t b;
        if (!fl_camera_pixel_to_ground(cam, u, v1, &gp))
            return;                    /* the bottom edge must see ground */
        fl_polar_from_point(gp, &r, &b);
        near = r > near ? r : near;
        if (fl_camera_pixel_to_ground(cam, u, v0, &gp)) {
            fl_polar_from_point(gp, &r, &b);
            far = r < far ? r : far;
        }
        if (fl_camera_pixel_to_ground(cam, u0, v, &gp)) {
            fl_polar_from_point(gp, &r, &b);
            rb = fl_angle_sub(b, yaw);
            bl = rb < bl ? rb : bl;
        }
        if (fl_camera_pixel_to_ground(cam, u1, v, &gp)) {
            fl_polar_from_point(gp, &r, &b);
            rb = fl_angle_sub(b, yaw);
            br = rb > br ? rb : br;
        }
    }
    if (bl == INT32_MAX || br == INT32_MIN || bl <= br || near >= far)
        return;
    view->valid = true;
    view->bearing_left = fl_angle_add(yaw, (fl_angle_t)bl);
    view->bearing_right = fl_angle_add(yaw, (fl_angle_t)br);
    view->near_mm = near;
    view->far_mm = far;
}

void fl_obs_view_vision(const fl_camera_t *cam, fl_obs_view_t *view)
{
    int32_t w;
    if (cam == NULL) {
        fl_obs_view_from_camera(NULL, 0, 0, view);
        return;
    }
    w = cam->model.width_px;
    fl_obs_view_from_camera(cam, w / 16, w >= 320 ? 4000 : 2500, view);
}
