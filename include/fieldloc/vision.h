/*
 * fieldloc/vision.h - the whole per-frame vision path in one call (seed
 * 000's pipeline, DESIGN.md "Data flow"): image -> column scanner ->
 * line points -> segments -> centre circle -> crossings and marks -> goal
 * posts -> observations.
 *
 *     static fl_color_table_t colors;  fl_color_init(&colors, &cp);
 *     static fl_vision_t vis;          fl_vision_params_default(&vp);
 *                                      fl_vision_init(&vis, &vp);
 *     per frame:  fl_camera_init(&cam, model, &pose);
 *                 n = fl_vision_frame(&vis, &colors, &img, &cam, field, &obs);
 *
 * Every buffer lives in the caller's fl_vision_t (the scanner's class map
 * is most of it: see sizeof, printed by the features suite); every stage
 * is bounded by the caps of config.h and counts what did not fit.  The
 * stage results stay readable after the call (vis.lines, vis.circle,
 * vis.crossings, vis.posts, vis.scan) for pictures and evaluation.
 *
 * Observations (obs.h), in this order: posts (kind FL_LM_POST, side,
 * color = the field's goal color, range from the foot or the width),
 * the centre circle (FL_LM_CENTRE_CIRCLE, orientation = halfway line),
 * then crossings and marks by falling confidence (FL_LM_L, T, X,
 * PENALTY_MARK, CENTRE_MARK).  Image positions are kept in u_q4 / v_q4.
 * Then, on fields with beacons or a sky-blue or pink goal (fl_vision_
 * wants_beacons), the colored landmarks of beacon.h: sky-blue and yellow
 * posts (FL_LM_POST, color SKYBLUE / YELLOW, side LEFT/RIGHT; a post
 * fl_goal_find already reported is not repeated) and beacons
 * (FL_LM_BEACON, color = upper band, color2 = lower band), in the order
 * found.  Other fields never run that stage, so their outputs do not
 * depend on it.  Those below min_confidence are left out.
 */
#ifndef FIELDLOC_VISION_H
#define FIELDLOC_VISION_H

#include "fieldloc/beacon.h"
#include "fieldloc/camera.h"
#include "fieldloc/circle.h"
#include "fieldloc/color.h"
#include "fieldloc/common.h"
#include "fieldloc/crossings.h"
#include "fieldloc/field.h"
#include "fieldloc/goal.h"
#include "fieldloc/image.h"
#include "fieldloc/lines.h"
#include "fieldloc/obs.h"
#include "fieldloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    fl_scan_params_t scan;        /* col_step / row_step 0 = auto: 1 up to
                                     320 px wide, else width / 320 (rounded
                                     up); border_run_px 4 (the scanner's
                                     default 8 puts the far lines, with
                                     only a 1-3 px strip of carpet between
                                     them, above the border) */
    fl_lines_params_t lines;
    fl_crossings_params_t crossings;
    int32_t min_confidence;       /* observations below are dropped, 0..255 */
    int32_t posts;                /* 1: goal posts */
    int32_t circle;               /* 1: centre circle */
    int32_t beacons;              /* added: 1: colored landmarks (beacon.h)
                                     on fields that have them; 0: never */
    fl_beacon_params_t beacon;    /* added: their params */
} fl_vision_params_t;

typedef struct {
    fl_vision_params_t params;
    fl_scan_t scan;
    fl_lines_t lines;
    fl_circle_t circle;
    fl_crossings_t crossings;
    fl_posts_t posts;
    fl_beacon_t beacons;          /* added: n = 0 unless the stage ran */
    /* counters */
    uint32_t frames;              /* frames processed */
    uint32_t obs_dropped;         /* observations beyond FL_OBS_MAX, summed */
    fl_status_t status;           /* of the last frame (FL_OK or why empty) */
    /* private */
    fl_scan_params_t scan_active; /* scan params in effect */
} fl_vision_t;

/* Defaults of every stage, automatic grid, border run 4 px, confidence 40,
 * posts, circle and beacons on. */
void fl_vision_params_default(fl_vision_params_t *p);

/* True when the field has something for the beacon stage: beacons
 * (beacon_height_mm > 0 or an FL_LM_BEACON landmark) or a goal colored
 * sky-blue or pink.  NULL: false. */
bool fl_vision_wants_beacons(const fl_field_t *field);

/* Validate every stage's params and clear.  FL_ERR_NULL, FL_ERR_RANGE.
 * FL_ERR_CONFIG
 * (common.h: the caller's config.h differs from the library's): nothing
 * written. */
fl_status_t fl_vision_init_cfg(fl_vision_t *v, const fl_vision_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_vision_init(fl_vision_t *v, const fl_vision_params_t *p)
{
    return fl_vision_init_cfg(v, p, FL_CONFIG_FINGERPRINT);
}

/* One frame.  colors: the tables (not changed); camera: this frame's pose
 * (NULL: no ground geometry, hence no observations but the image-level
 * stages run); field: geometry (line width, radius, post size).  Fills out
 * (cleared first) and returns out->n; 0 with v->status set on bad input,
 * and then nothing is processed (frames not counted, stage results
 * empty) and the next valid frame works as usual:
 *   FL_ERR_NULL      v's other pointers but camera
 *   FL_ERR_SIZE, FL_ERR_STRIDE, FL_ERR_FORMAT   fl_image_validate (every
 *                    format of image.h is read by every stage)
 *   FL_ERR_CAMERA    a camera whose fl_camera_init failed (zeroed model)
 *   FL_ERR_MISMATCH  img->width x height is not the camera model's
 *                    width_px x height_px (a frame and a model of another
 *                    resolution: scale the frame or pick the model). */
int32_t fl_vision_frame(fl_vision_t *v, const fl_color_table_t *colors,
                        const fl_image_t *img, const fl_camera_t *camera,
                        const fl_field_t *field, fl_obs_list_t *out);

/* ---- the frame's view, for negative information (obs.h fl_obs_view_t;
 * src/vision/vision_view.c) ---- */

/* The view of a camera (camera.h, initialized with the frame's pose): the
 * image shrunk by margin_px on every side (and below the horizon by as
 * much) projected onto the ground, reduced to the sector inside it
 * (samples along each edge: near = the farthest of the bottom edge, far =
 * the nearest of the top edge but at most max_range_mm, bearings the
 * innermost of the side edges; the footprint is convex, so the sector
 * lies inside it up to the curvature of the side edges, which the margin
 * covers).  valid false when the camera is NULL, the shrunk image has no
 * ground, or the sector is empty.  Integer only (camera.c projections). */
void fl_vision_view_from_camera(const fl_camera_t *cam, int32_t margin_px,
                                int32_t max_range_mm, fl_obs_view_t *view);

/* The view that goes with fl_fuzzy_params_vision (fuzzy.h): the image
 * shrunk by 1/16 of its width, up to 4 m for cameras at least 320 px wide
 * and 2.5 m for narrower ones (vision finds 72-99 % of the landmarks of
 * each kind that project that far inside the image, simulate --frames
 * "# vision" lines).  valid false for a NULL camera. */
void fl_vision_view(const fl_camera_t *cam, fl_obs_view_t *view);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_VISION_H */
