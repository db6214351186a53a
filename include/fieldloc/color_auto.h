/*
 * fieldloc/color_auto.h - the field colour from the frame: the colour
 * classes of color.h found from an image at start-up, with no hand-set
 * boxes, and tracked per frame from the scanner's field estimate.
 *
 * Start-up (fl_color_estimate, fl_color_auto_params).  The carpet is the
 * dominant saturated hue of the ground part of the image: every pixel of a
 * grid of at most 128 x 96 (step width/64, height/48) below the horizon
 * (with a camera; without one, the lower half).  Pass 1: hue histogram of
 * the samples with S >= 40 and V >= 24, mode over 5 bins among the hues
 * 30..100 (60..200 degrees: any green carpet; the 2013 UvA carpet at ~60,
 * the physar one 37..53, scarrix and HTWK frames 75..89; a yellow post or
 * an orange ball filling the view is not taken), spread = 3/2 of the
 * 10th / 90th percentile's distance from the mode, of the samples within
 * +-30 of it (the 3rd / 97th percentile of a normal spread; a weak second
 * population, a bluish wall below the horizon, moves it little).  Pass 2: S and V
 * histograms of the samples inside that spread with S >= 16 (sunlit
 * carpet is paler: its S falls, V rises; shadows keep hue and S, lower V).
 * From that, fl_color_auto_params derives (green_sat_ref, field_hue and
 * field_val record the carpet they were made for):
 *   green   hue spread +- auto_margin, at least 12 and at most 30 units on
 *           each side of the mode (with auto_yellow, not below 3 units
 *           above the yellow box: the posts are not carpet); S from half the carpet's median S
 *           (24..49: lines are far paler than the carpet, sunlit carpet
 *           keeps most of its S) to 255; V from auto_shadow_pct % of V p2
 *           (hard shadows, the shade at a post's foot; at least 8) to 255
 *           (sunlit patches)
 *   white   any hue, S below green's S_LO (the boxes meet), V from half
 *           the carpet's V p2 (30..160: lines at half the light; the 2013
 *           box has 60 for a carpet p1 of 57); the scanner's
 *           white_contrast_pct does the rest
 *   yellow  auto_yellow 1: the given box with its hue kept 2 units clear
 *           of green (so no carpet pixel, sunlit or not, is yellow);
 *           auto_yellow 0 (white goals): no yellow class at all
 * Cost: two passes over <= 12288 samples, one HSV conversion each (once,
 * at start-up), plus fl_color_init.
 *
 * Per frame (fl_color_track, after fl_vision_frame or fl_scan_frame, from
 * fl_scan_t.field).  With params.field_auto 1 the table tracks the carpet
 * (hue in 1/16 units, S, V): each frame moves it halfway to the
 * measurement, at most FL_COLOR_TRACK_HUE_Q4 / _SAT / _VAL per frame (a
 * reflection or a robot filling the view cannot swing it), and
 * measurements more than 30 hue units away are ignored.  The effective
 * boxes are the params' boxes shifted by (tracked hue - field_hue), green
 * and white V_LO scaled by tracked V / field_val (1/2..2x), green S_LO by
 * tracked S / green_sat_ref (1/2..1x, white S_HI follows); the tables are
 * rebuilt only when the shift moved by >= 2 hue units, green S_LO by >= 6
 * or green or white V_LO by >= 8 from what they were built for
 * (hysteresis), and at most once per FL_COLOR_TRACK_GAP (8) frames.  The
 * scanner samples the carpet below the border only, so
 * the tracker follows a carpet that drifts within the box from frame to
 * frame; a jump out of it (another venue) needs a new start-up estimate.
 * No ceiling on the hue (fl_color_adapt's adapt_max_hue does not apply).
 * Cost bound per frame: ~300 instructions without a rebuild; a rebuild
 * (the table build of fl_color_init) is 7.2 M instructions (callgrind,
 * x86-64 -O2; 1.5 times the vision path on a 640x480 frame), at most one
 * per 8 frames: <= 0.9 M per frame over any 8 frames.  The start-up
 * estimate is 0.8 M on a 640x480 frame (DESIGN.md "Field colour from the
 * frame").
 * Without field_auto fl_color_track does nothing (returns 0).
 */
#ifndef FIELDLOC_COLOR_AUTO_H
#define FIELDLOC_COLOR_AUTO_H

#include "fieldloc/camera.h"
#include "fieldloc/color.h"
#include "fieldloc/common.h"
#include "fieldloc/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Per-frame rate limits of fl_color_track. */
#define FL_COLOR_TRACK_HUE_Q4 16  /* 1 hue unit */
#define FL_COLOR_TRACK_SAT 4
#define FL_COLOR_TRACK_VAL 6
/* At most one table rebuild per this many tracked frames. */
#define FL_COLOR_TRACK_GAP 8

/* A start-up estimate of the carpet (fl_color_estimate). */
typedef struct {
    int32_t n_sat;      /* samples in the hue histogram (pass 1) */
    int32_t n;          /* carpet samples (pass 2); 0: no estimate */
    uint8_t hue;        /* mode, 0..179 */
    uint8_t hue_lo;     /* spread: 10th / 90th percentile x 3/2 (may wrap) */
    uint8_t hue_hi;
    uint8_t s_p5, s_med;
    uint8_t v_p2, v_med, v_p98;
    /* scratch of the two passes */
    uint16_t hist_h[180];
    uint16_t hist_s[256];
    uint16_t hist_v[256];
} fl_color_estimate_t;

/* Estimate the carpet of img (any format of image.h).  cam NULL: the
 * lower half of the image; else the pixels below the horizon (cam's model
 * the size of img).  FL_OK (e->n > 0), FL_ERR_NOT_FOUND (fewer than 32
 * saturated or carpet samples: e->n 0), FL_ERR_NULL, or the image's
 * fl_image_validate status. */
fl_status_t fl_color_estimate(const fl_image_t *img, const fl_camera_t *cam,
                              fl_color_estimate_t *e);

/* Boxes from an estimate (rules at the top), over *p: auto_margin,
 * auto_shadow_pct, auto_yellow, the yellow box and the white numbers are
 * read from *p; green, white, yellow, green_sat_ref, field_hue, field_val
 * are written and field_auto set to 1.  FL_OK (p valid for fl_color_init),
 * FL_ERR_NULL, FL_ERR_NOT_FOUND (e->n 0: *p unchanged), FL_ERR_RANGE (*p
 * breaks a rule of fl_color_params_check: unchanged). */
fl_status_t fl_color_auto_params(const fl_color_estimate_t *e, fl_color_params_t *p);

/* One frame of tracking (rules at the top): 1 when the tables were
 * rebuilt, 0 when not (no field_auto, field->n < 16, or nothing moved
 * enough), FL_ERR_NULL. */
int fl_color_track(fl_color_table_t *t, const fl_field_color_t *field);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_COLOR_AUTO_H */
