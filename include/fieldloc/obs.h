/*
 * fieldloc/obs.h - observations: the one seam between vision and
 * localization.  A localizer never sees pixels; it sees a list of these.
 *
 * Every observation is in the robot frame (x forward, y left, origin on the
 * ground below the head), measured at the time of the frame.
 */
#ifndef FIELDLOC_OBS_H
#define FIELDLOC_OBS_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/field.h"

#ifdef __cplusplus
extern "C" {
#endif

/* No observation is farther than this (mm): the camera's largest ground
 * range (camera.h FL_CAMERA_MAX_RANGE_MM, equal by a compile-time check in
 * src/vision/vision_view.c).  A localizer may treat a larger range as bad
 * input. */
#define FL_OBS_MAX_RANGE_MM 20000

/* Orientation conventions (robot frame, binary angle), when has_orientation:
 *   L   direction of the bisector of the two arms (pointing between them)
 *   T   direction of the stem (the arm with no opposite arm)
 *   X, penalty mark, centre mark   direction of any arm (meaningful mod 90 deg)
 *   centre circle   direction of the halfway line through it (mod 180 deg)
 *   post, beacon    no orientation
 * The same conventions give a map landmark's orientation from its arms
 * (fl_landmark_orientation). */
typedef struct {
    fl_landmark_kind_t kind;   /* FL_LM_L ... FL_LM_BEACON */
    fl_side_t side;            /* posts: left/right when the crossbar says so */
    fl_color_t color;        /* posts and beacons; FL_COLOR_NONE if unknown */
    int32_t range_mm;          /* ground distance from the robot origin, >= 0 */
    fl_angle_t bearing;        /* 0 ahead, positive left */
    fl_angle_t orientation;    /* see above; 0 when !has_orientation */
    bool has_orientation;
    uint8_t confidence;        /* Q0.8: 255 = certain, 0 = ignore */
    int32_t u_q4, v_q4;        /* image position it came from (Q4 px), for
                                  pictures and evaluation; -1 if none */
    fl_color_t color2;       /* added: beacons: the lower color band
                                  (color is the upper band, as
                                  fl_landmark_t.color / color2); a beacon
                                  whose upper band was not seen has color
                                  FL_COLOR_NONE and color2 set.
                                  FL_COLOR_NONE (0, what memset gives)
                                  for every other kind and when unknown */
} fl_obs_t;

/* Capacity of one frame's observation list: FL_OBS_MAX, config.h. */
typedef struct {
    fl_obs_t obs[FL_OBS_MAX];
    uint16_t n;          /* valid entries */
    uint16_t dropped;    /* observations that did not fit (counted, not stored) */
} fl_obs_list_t;

/* What a frame could have seen: the part of the ground (robot frame) in
 * which every landmark projects well inside the image, as a sector:
 * bearing in [bearing_right, bearing_left] (left - right in (0, 180) deg)
 * and range in [near_mm, far_mm].  A localizer uses it for negative
 * information: a landmark that a pose hypothesis puts inside the sector
 * and that no observation of the frame explains makes that hypothesis
 * less possible (fuzzy.h, fl_fuzzy_update_view).  valid false: unknown
 * (no negative information).  A camera's view: vision.h,
 * fl_vision_view_from_camera and fl_vision_view. */
typedef struct {
    bool valid;
    fl_angle_t bearing_right, bearing_left;
    int32_t near_mm, far_mm;
} fl_obs_view_t;

void fl_obs_list_clear(fl_obs_list_t *list);

/* Append; when full, count it in `dropped` and return false. */
bool fl_obs_list_push(fl_obs_list_t *list, const fl_obs_t *obs);

/* Orientation of a map landmark by the conventions above (field frame);
 * false for kinds without one. */
bool fl_landmark_orientation(const fl_landmark_t *lm, fl_angle_t *orientation);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_OBS_H */
