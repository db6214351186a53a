/*
 * fieldloc/crossings.h - L, T and X line crossings and the penalty and
 * centre marks (seed 000, section 3.7).
 *
 * Pairs.  Every pair of segments (lines.h) at least min_angle apart in the
 * image whose (infinite) lines meet inside the image (or at most 2 line
 * steps outside it: a corner at the image edge; its pixel is then clamped
 * into the image, its ground position is the true meeting point's) is a
 * candidate.  For
 * each segment the meeting point X is placed along it: an arm leaves X
 * where the segment goes on past X by at least arm_px (half of it where
 * the segment ends within a line step of the image border: the arm is cut
 * off there); X may lie beyond a
 * segment's end by at most reach_px (segments stop short of a crossing,
 * where white runs merge).  Seed 000's rules follow: near both ends -> L,
 * inside one and near an end of the other -> T, inside both -> X.  The
 * direction of a line at X is its chord's, turned by the slope its bulge
 * gives there (an arc of the centre circle meets the halfway line along
 * its tangent, not its chord).
 *
 * Checks.  Ground: both lines projected through the camera must meet at
 * 90 degrees within ground_tol (every crossing of a field is square; the
 * chords of the centre circle are not).  Image: each of the 4 arm
 * directions is probed in the class map beyond the other line's paint (a
 * cheap white-ratio test along a short ray); an arm the segment did not
 * reach but the probe finds white is added (a line broken at the
 * crossing), an arm the segment claims but the probe finds green lowers
 * the confidence.  Far lines too thin for the class map: a probe below
 * the lines' white_pct reads the luma (fl_lines_paint_pct; at most 128
 * such probes per frame, counted in luma_probes).  The arm count gives the type (2 L, 3 T, 4 X).
 * Crossings closer than the merge distance (3 line widths or 4 steps) are
 * merged by the union of their arms: two opposite T's become an X, an L
 * and its continuation a T.  Two crossings of one straight segment with
 * two others (a goal box side with the goal line and the front line), and
 * a mark and a crossing of lines, merge only within half that distance;
 * crossings 500 mm apart on the ground never merge.
 *
 * Border T's.  Far away the boundary lines are a pixel or less tall: their
 * paint blends into the carpet or lies above the field border found by the
 * scanner, so a line running up to one (the halfway line, a goal-area side
 * line) pairs with nothing.  A segment at least 3 line steps long whose
 * upper end runs up (at least 10 degrees from horizontal) toward the
 * border gives a T when: its paint, followed past that end (at most the
 * reach), stops, the crossing being half a line width (on the ground)
 * before that; the field border lies within 1000 mm (ground) beyond it
 * with only field colors between and runs square to the segment on the
 * ground (ground_tol); the segment's continuation past the crossing is not
 * white (probe_green_pct); and no crossing from a pair is already within
 * the merge distance.  Arms: the segment and the boundary line both ways;
 * confidence as a pair's length factor times 160/256 (counted in
 * border_t).  Field corners seen this way are called T as well.
 *
 * Short connectors.  Far away the sides of the goal box (and other short
 * lines between two parallel ones) are a few pixels long: no segment, so
 * their corners pair with nothing.  At an end of a segment where its paint
 * stops, the line's ground normal is followed to the nearest segment
 * parallel to it in the image, 2 line steps to 1000 mm (at most 8 steps)
 * away; when that connector is paint (fl_lines_paint_pct, the luma for
 * thin lines) and the strip beside it beyond the corner is not, the end
 * is an L and the connector's foot a T (an L where the parallel segment
 * ends), square on the ground by construction, confidence as a border T
 * (counted in connectors).  No crossing is added within merge distance of
 * one found before.
 *
 * Marks.  The penalty and centre marks (a 100 mm cross) are too small to
 * make long segments.  Points off long segments are clustered within 0.75
 * of the projected mark size; a cluster of at least 2 points with no other
 * point out to 2.5 mark sizes (but those of a long line passing by, twice
 * the inner half-axis away), whose ring of 16 class-map samples at 1.6
 * mark sizes is green (13 of 16, no white), is a penalty mark (a cluster
 * with luma points needs 2 class-map points or 3 points in all).  An X of a
 * short bar (<= 2.5 mark sizes on the ground) across a long line is a
 * centre mark, of two short bars a penalty mark.  Both count as X (as the
 * UvA 2013 labels do); their kind says which.  A found centre circle with
 * its halfway line gives the centre mark and the two halfway-line x circle
 * X's where the class map is white (fl_crossings_add_circle).
 *
 * Orientation (robot frame, obs.h conventions): L bisector of its arms, T
 * the stem direction, X and marks the direction of one arm (mod 90 deg);
 * marks found as blobs have none.
 *
 * Lifecycle: fl_crossings_params_default, fl_crossings_init once; per
 * frame fl_crossings_find after fl_lines_find_segments (and after the circle stage,
 * which flags its chords: chord pairs are skipped), then
 * fl_crossings_add_circle.  Work: O(segments^2) pair tests (at most
 * FL_LINES_MAX_SEGMENTS^2 / 2), each surviving pair 4 probes of at most 64
 * samples and 3-5 camera projections; border T's one test per segment (a
 * walk, a border search and a probe of at most 64 samples each, 4-8 camera
 * projections); connectors per segment end 2-6 camera projections, a pass
 * over the segments and probes within the frame's 128 luma probes; marks
 * O(points) with bounded bucket searches.
 */
#ifndef FIELDLOC_CROSSINGS_H
#define FIELDLOC_CROSSINGS_H

#include "fieldloc/camera.h"
#include "fieldloc/circle.h"
#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/field.h"
#include "fieldloc/fixed.h"
#include "fieldloc/lines.h"
#include "fieldloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    fl_landmark_kind_t kind;  /* FL_LM_L, FL_LM_T, FL_LM_X,
                                 FL_LM_PENALTY_MARK or FL_LM_CENTRE_MARK */
    int32_t u_q4, v_q4;       /* image position, Q4 px */
    fl_point_t ground;        /* robot frame, mm */
    int32_t range_mm;
    fl_angle_t bearing;
    fl_angle_t orientation;   /* robot frame, obs.h conventions */
    bool has_orientation;
    uint8_t confidence;       /* Q0.8 */
    uint8_t n_arms;           /* 2 L, 3 T, 4 X and marks */
    fl_angle_t arm[4];        /* image directions of the arms, atan2(dv, du) */
    int16_t seg_a, seg_b;     /* segments it came from (-1: none) */
} fl_crossing_t;

typedef struct {
    int32_t min_angle_mdeg;   /* image angle between the two segments,
                                 millidegrees, 1000..60000 (seed: 10 deg) */
    int32_t ground_tol_mdeg;  /* allowed deviation from 90 deg on the
                                 ground, 1000..45000 */
    int32_t arm_px;           /* segment extent past X that makes an arm,
                                 px; 0 = auto (max(2 step, 2 line width),
                                 lowered to twice the other line's paint
                                 along the segment: its width across
                                 itself over |sin|, at least 2 steps) */
    int32_t reach_px;         /* largest gap between X and a segment end,
                                 px; 0 = auto (max(3 step, 3 line width),
                                 at least 5 steps when both segments are
                                 6 steps long, 7 steps where the gap is
                                 mostly neither carpet nor paint: a robot
                                 or post hides the corner's first steps) */
    int32_t probe_white_pct;  /* probe: arm present at >= this % white */
    int32_t probe_green_pct;  /* probe: arm absent at < this % white */
    int32_t min_confidence;   /* crossings below are dropped, 0..255 */
    int32_t marks;            /* 1: look for penalty/centre marks */
} fl_crossings_params_t;

typedef struct {
    fl_crossings_params_t params;
    int32_t n;
    fl_crossing_t c[FL_CROSSINGS_MAX];
    /* counters of the last frame */
    int32_t dropped;          /* beyond FL_CROSSINGS_MAX */
    int32_t pairs;            /* segment pairs tested */
    int32_t rejected_ground;  /* failed the 90 degree ground check */
    int32_t rejected_arms;    /* arm set that is no crossing */
    int32_t merged;           /* crossings merged into others */
    int32_t marks_capped;     /* mark search stopped after 256 clusters
                                 (64 once the line points overflowed) */
    int32_t border_t;         /* T's of one segment at the field border */
    int32_t luma_probes;      /* arm probes that fell back to the luma
                                 (at most 128 per frame) */
    int32_t connectors;       /* crossings of short connectors (L + T) */
    int32_t robot_rejected;   /* crossings on a standing object (lines.h:
                                 a robot's white is no paint) */
    /* ---- private ---- */
    fl_angle_t garm[FL_CROSSINGS_MAX][4]; /* ground arms (robot frame) */
} fl_crossings_t;

/* Defaults: 10 deg, 25 deg, auto, auto, 55 %, 25 %, confidence 60,
 * marks on. */
void fl_crossings_params_default(fl_crossings_params_t *p);

/* Validate params (FL_ERR_RANGE) and clear.  FL_ERR_NULL.  FL_ERR_CONFIG
 * (common.h: the caller's config.h differs from the library's): nothing
 * written. */
fl_status_t fl_crossings_init_cfg(fl_crossings_t *c, const fl_crossings_params_t *p,
                                  uint32_t caller_cfg);
static inline fl_status_t fl_crossings_init(fl_crossings_t *c, const fl_crossings_params_t *p)
{
    return fl_crossings_init_cfg(c, p, FL_CONFIG_FINGERPRINT);
}

/* Find the crossings of a frame's segments.  scan may be NULL (no image
 * probes, no marks), camera may be NULL (no ground check, no ground
 * position: range 0), field may be NULL (no marks; line width from the
 * lines stage).  Returns n. */
int32_t fl_crossings_find(fl_crossings_t *c, const fl_lines_t *lines,
                          const fl_scan_t *scan, const fl_camera_t *camera,
                          const fl_field_t *field);

/* Crossings implied by a found centre circle whose halfway line was seen
 * (circle->has_orientation; else the longest segment through its centre;
 * else, a halfway line too faint for segments, the one of 16 ground
 * directions through the centre that is paint from 1.15 to 1.5 radii out
 * on both sides): the two X where the halfway line crosses the circle and
 * the centre mark.  Each is added (merged with a crossing
 * already there, which then becomes an X) only when its pixel is inside
 * the image and the class map is white within one cell of it; confidence
 * 3/4 of the circle's.  Call after fl_crossings_find.  Returns the number
 * added or merged. */
int32_t fl_crossings_add_circle(fl_crossings_t *c, const fl_circle_t *circle,
                                const fl_lines_t *lines, const fl_scan_t *scan,
                                const fl_camera_t *camera,
                                const fl_field_t *field);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_CROSSINGS_H */
