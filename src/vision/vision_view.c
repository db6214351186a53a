/*
 * src/vision/vision_view.c - what a frame could have seen (vision.h,
 * fl_vision_view_from_camera, fl_vision_view): the camera's footprint on
 * the ground reduced to a sector (fl_obs_view_t, obs.h) for a localizer's
 * negative information.  Moved from src/loc/obs.c: it needs the camera,
 * which localization does not.
 */
#include "fieldloc/vision.h"

#include <string.h>

/* obs.h promises no observation beyond the camera's ground range. */
typedef char fl_vv_obs_range_is_camera_range[FL_OBS_MAX_RANGE_MM == FL_CAMERA_MAX_RANGE_MM ? 1 : -1];

/* Samples along each edge of the shrunk image (fl_vision_view_from_camera). */
#define VIEW_SAMPLES 5

/* Scaling: pixel coordinates Q4 < 2^20 (config caps the image size), the
 * sample interpolation (u1 - u0) * i < 2^23; ranges and bearings from
 * fl_polar_from_point.  Bearings are taken relative to the head yaw so
 * that min / max never straddle the +-180 degree wrap. */
void fl_vision_view_from_camera(const fl_camera_t *cam, int32_t margin_px,
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
    /* the lowest horizon row over u0..u1 (one row without roll; with roll
     * the line's lower end), so that the whole top edge sees ground */
    hz = fl_camera_horizon_v_q4(cam, u0);
    i = fl_camera_horizon_v_q4(cam, u1);
    if (hz == INT32_MAX || i == INT32_MAX)
        return;
    hz = i > hz ? i : hz;
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

void fl_vision_view(const fl_camera_t *cam, fl_obs_view_t *view)
{
    int32_t w;
    if (cam == NULL) {
        fl_vision_view_from_camera(NULL, 0, 0, view);
        return;
    }
    w = cam->model.width_px;
    fl_vision_view_from_camera(cam, w / 16, w >= 320 ? 4000 : 2500, view);
}
