/*
 * fieldloc/circle.h - the centre circle, fitted on the ground (seed 000,
 * section 3.9 detects it as an image ellipse; here its line points are
 * projected through the camera and fitted with the field's known radius).
 *
 * Method.  The line segments (lines.h) of a circle are chords: the growth
 * stops on the summed error where the arc bends.  Centre candidates come
 * from (a) each short segment (ground length <= 2.1 R) whose points bulge
 * to one side of its chord: the circle through its two ends and its apex
 * (chord middle moved by 1.5 x the mean bulge, the sagitta of a parabola)
 * projected to the ground, and (b) each pair of such segments meeting end
 * to end at 4..70 degrees in the image: the circle through the far ends
 * and the joint.  A candidate is kept when its radius is within 30 % of R.
 * Straight segments longer than R (the halfway line through the circle)
 * are no chords.  Candidates are clustered (the largest point-weighted
 * group within max(150 mm, range / 10)); the cluster needs two segments,
 * or one chord of at least R.  Chord candidates not in the cluster with
 * both ends on its annulus join.  The centre is refined by fixed-radius
 * Gauss-Newton over the ground points of the member segments (c <- mean
 * of p - R (p - c) / |p - c|, up to 12 rounds), members whose points stay
 * off the circle by more than max(60 mm, range / 12) on average are
 * dropped and the fit repeated; it is accepted with at least 12 points,
 * spanning at least 67.5 degrees of the circle, and an RMS distance from
 * it below max(60 mm, range / 30).  Member segments are flagged
 * FL_SEG_CIRCLE (the crossing stage skips chord pairs).
 *
 * Orientation: the direction (mod 180 deg) of the longest segment whose
 * ground line passes within max(150 mm, range / 10) of the centre and that
 * is longer than R on the ground: the halfway line.
 *
 * Lifecycle: fl_circle_find per frame after fl_lines_find_segments and before
 * fl_crossings_find.  Cost: O(points) for the bulges, O(segments^2) for
 * the pairs, O(candidates^2) clustering, 4 x (fit points) refinement, about
 * 3 camera projections per segment plus one per fit point.
 */
#ifndef FIELDLOC_CIRCLE_H
#define FIELDLOC_CIRCLE_H

#include "fieldloc/camera.h"
#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/field.h"
#include "fieldloc/fixed.h"
#include "fieldloc/lines.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int32_t x_mm, y_mm;     /* candidate centre, robot frame */
    int16_t seg_a, seg_b;   /* segments it came from (seg_b -1: single) */
    int32_t weight;         /* points behind it */
} fl_circle_cand_t;

typedef struct {
    bool found;
    fl_point_t centre;      /* robot frame, mm */
    int32_t range_mm;
    fl_angle_t bearing;
    int32_t u_q4, v_q4;     /* centre pixel (may lie outside the image) */
    bool has_pixel;
    fl_angle_t orientation; /* halfway line direction, robot frame, mod 180 */
    bool has_orientation;
    uint8_t confidence;     /* Q0.8 */
    int32_t n_points;       /* points in the fit */
    int32_t n_segments;     /* chords flagged */
    int32_t rms_mm;         /* RMS distance of the fit points from the circle */
    /* counters of the last frame */
    int32_t n_cand;
    int32_t cand_dropped;   /* beyond FL_CIRCLE_MAX_CHORDS */
    /* ---- private scratch ---- */
    fl_circle_cand_t cand[FL_CIRCLE_MAX_CHORDS];
    fl_point_t pts[FL_CIRCLE_MAX_POINTS];
    int16_t pts_seg[FL_CIRCLE_MAX_POINTS];
    fl_point_t seg_g0[FL_LINES_MAX_SEGMENTS], seg_g1[FL_LINES_MAX_SEGMENTS];
    int32_t seg_bulge[FL_LINES_MAX_SEGMENTS]; /* summed signed distance, Q1 */
    int32_t seg_cnt[FL_LINES_MAX_SEGMENTS];
    uint8_t seg_state[FL_LINES_MAX_SEGMENTS];
} fl_circle_t;

/* Find the centre circle.  lines: its segments get FL_SEG_CIRCLE when they
 * are chords of the found circle.  NULL camera or field, or a field
 * without a circle: not found.  Returns 1 when found, else 0. */
int32_t fl_circle_find(fl_circle_t *c, fl_lines_t *lines,
                       const fl_camera_t *camera, const fl_field_t *field);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_CIRCLE_H */
