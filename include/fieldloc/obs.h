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
 *   seed 004's features (field.h): C as L; T-net as T; T-field as the T
 *   (stem) or X (any arm, mod 90 deg) it is; net no orientation
 * The same conventions give a map landmark's orientation from its arms
 * (fl_landmark_orientation). */
typedef struct {
    fl_landmark_kind_t kind;   /* FL_LM_L ... FL_LM_NET */
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

/* A point on a painted line, on the ground, robot frame (mm). */
typedef struct {
    int32_t x_mm, y_mm;
} fl_obs_point_t;

/* Capacity of one frame's observation list: FL_OBS_MAX, config.h.
 * Besides the landmarks, a list may carry a sample of points on the white
 * lines the frame showed (FL_OBS_MAX_POINTS of them, config.h): seed 002's
 * "white points", which tell apart poses the landmarks leave tied.  A
 * vision path that finds none leaves n_points 0, and a localizer that has
 * no use for them ignores them. */
typedef struct {
    fl_obs_t obs[FL_OBS_MAX];
    uint16_t n;          /* valid entries */
    uint16_t dropped;    /* observations that did not fit (counted, not stored) */
#if FL_OBS_MAX_POINTS > 0
    fl_obs_point_t points[FL_OBS_MAX_POINTS];
#endif
    uint16_t n_points;        /* valid entries of points */
    uint16_t points_dropped;  /* points that did not fit (counted) */
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

/*
 * A report of the robot's own position from an external observer (seed
 * 003's coach: a camera beside the field that finds each player's foot).
 * It lives here, at the seam, rather than in localizer.h: the coach's image
 * path is a vision-layer producer of reports and never includes a localizer
 * header; the localizers consume them (localizer.h fl_loc_reseed), as they
 * consume observations, and never see the pixels behind them.
 *
 *   x_mm, y_mm   the foot in the field frame (mm)
 *   sd_mm        the position's standard deviation (mm): the spread a
 *                re-seed draws with.  FL_OBS_REPORT_SD_MM is seed 003's
 *                sigma = 1/alpha with alpha = 8: its field coordinates are
 *                metres (1/8 mm would be far below a pixel of the coach's
 *                top view, and 1/8 m = 125 mm is the size of its measured
 *                foot errors, 80-199 mm), so sigma = 125 mm.
 *   confidence   Q0.8 (255 = certain, 0 = ignore), as an observation's
 *   team, player the observer's identification (jersey colour as
 *                fl_color_t, player number; 0 = unknown): which report is
 *                whose is decided by the caller before re-seeding
 *   age_ms       how long ago the coach's frame was taken
 *
 * fl_obs_report_check refuses: FL_ERR_NULL (NULL), FL_ERR_RANGE (sd outside
 * [FL_OBS_REPORT_SD_MIN_MM, FL_OBS_REPORT_SD_MAX_MM], confidence 0, a
 * negative age, a foot off the carpet (field plus border, field.h), no
 * field), FL_ERR_STALE (age above FL_OBS_REPORT_MAX_AGE_MS).
 */
#define FL_OBS_REPORT_SD_MM 125
/* Below a pixel of a 640 px coach view of a 9 m field at 5 m: absurd. */
#define FL_OBS_REPORT_SD_MIN_MM 10
/* Beyond a third of an SPL field's width: tells nothing a re-seed could use. */
#define FL_OBS_REPORT_SD_MAX_MM 2000
/* A robot walking 250 mm/s moves about one FL_OBS_REPORT_SD_MM in 500 ms. */
#define FL_OBS_REPORT_MAX_AGE_MS 500

typedef struct {
    int32_t x_mm, y_mm;
    int32_t sd_mm;
    uint8_t confidence;
    uint8_t team;
    uint8_t player;
    int32_t age_ms;
} fl_obs_report_t;

fl_status_t fl_obs_report_check(const fl_obs_report_t *r, const fl_field_t *field);

/* Empties the list: landmarks and points. */
void fl_obs_list_clear(fl_obs_list_t *list);

/* Append; when full, count it in `dropped` and return false. */
bool fl_obs_list_push(fl_obs_list_t *list, const fl_obs_t *obs);

/* Append a line point (robot frame, mm); when full, count it in
 * points_dropped and return false.  A point farther than
 * FL_OBS_MAX_RANGE_MM on either axis is refused (false, not counted). */
bool fl_obs_list_push_point(fl_obs_list_t *list, int32_t x_mm, int32_t y_mm);

/* Orientation of a map landmark by the conventions above (field frame);
 * false for kinds without one. */
bool fl_landmark_orientation(const fl_landmark_t *lm, fl_angle_t *orientation);
/* The period of that orientation (binary angle: 65536 one direction, 32768
 * mod 180, 16384 mod 90); 0 when the landmark has none (NULL too). */
int32_t fl_landmark_orientation_period(const fl_landmark_t *lm);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_OBS_H */
