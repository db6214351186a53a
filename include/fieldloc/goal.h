/*
 * fieldloc/goal.h - goal posts (seed 000, section 3.8): foot, top, width,
 * side and ground distance; yellow posts (fl_goal_find, below) and white
 * posts (fl_goal_find_white, further below).
 *
 * Method.  The scanner (scan.h) counts yellow cells per grid column
 * (yellow_cols, the post's run above the border included when it touches
 * the border) and lists yellow->green transitions (feet).  Because a post
 * stands on the goal line, a line between the yellow and the carpet can
 * keep the scanner from following it up; so the image is also probed (by
 * the color table) at 2, 6, 12 and 20 px above each grid column's border.
 * A candidate is a run of columns with yellow at two probes or
 * yellow_cols >= min_cells (gaps of two columns bridged).  In the image:
 * its yellow column is followed down to the foot and up through the post
 * rows (no wider than 1.6 widths) into a crossbar band (wider rows, at
 * most two widths thick: the top is the band's top) or clutter (thicker:
 * top unknown); the width is the median of three horizontal runs at 10,
 * 25 and 40 % of the post's height.  It is a post when the height is at
 * least 2.5 widths and half of what the camera predicts for a post of the
 * field's height at the foot's distance (small yellow things are not
 * posts), and its foot lies below the field border: carpet (or a line)
 * right under the foot and the border of the columns beside the post
 * above the foot (a yellow object beyond the carpet stands above the
 * border).  The scanner's lowest transition near the foot refines it.  The
 * side comes from the crossbar band: the image is probed beside the top at
 * 1.5, 2.5 and 3.5 widths; crossbar to the right = the left post as seen
 * facing the goal, to the left = the right post.  With two posts and no
 * crossbar seen, the left one in the image is the left.
 *
 * Distance.  The foot pixel is projected through the camera (the visible
 * foot is the front of the post: half a diameter is added along the ray,
 * and the reported foot pixel is the base centre projected back).  When
 * the foot is not visible (below the image) the range comes from the
 * width: f * diameter / width, a fallback flagged in the result.
 *
 * Lifecycle: fl_goal_find per frame after fl_scan_frame; no init (the
 * result struct is overwritten).  Cost: 4 pixel classifications per grid
 * column, then per candidate one column walk (every 4th row measured
 * across, at most 2 widths each way) and a few probes.
 */
#ifndef FIELDLOC_GOAL_H
#define FIELDLOC_GOAL_H

#include "fieldloc/camera.h"
#include "fieldloc/color.h"
#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/field.h"
#include "fieldloc/fixed.h"
#include "fieldloc/image.h"
#include "fieldloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int32_t foot_u_q4, foot_v_q4; /* base centre, Q4 px (estimated from the
                                     width when !foot_visible) */
    int32_t top_u_q4, top_v_q4;   /* top of the yellow run, Q4 px */
    int32_t width_q4;             /* post width at the foot, Q4 px */
    bool foot_visible;            /* foot seen on the field */
    bool top_visible;             /* top inside the image */
    bool range_from_width;        /* range by the width fallback */
    fl_side_t side;               /* from the crossbar (or the pair) */
    fl_point_t ground;            /* post centre, robot frame, mm */
    int32_t range_mm;
    fl_angle_t bearing;
    uint8_t confidence;           /* Q0.8 */
} fl_post_t;

typedef struct {
    int32_t n;
    fl_post_t post[FL_GOAL_MAX_POSTS];
    int32_t dropped;              /* posts beyond FL_GOAL_MAX_POSTS (white:
                                     and candidates beyond the cap) */
    int32_t candidates;           /* column runs examined */
    int32_t rejected_border;      /* foot above the field border */
    int32_t rejected_shape;       /* not a vertical bar */
} fl_posts_t;

/* Find the posts of a scanned frame.  img and colors (the table the scan
 * used) are needed (NULL: no posts); camera may be NULL: no ground position
 * (range 0) and no height check; field gives the post diameter and height
 * (NULL: 100 and 800 mm).  Returns n. */
int32_t fl_goal_find(fl_posts_t *out, const fl_scan_t *scan,
                     const fl_image_t *img, const fl_color_table_t *colors,
                     const fl_camera_t *camera, const fl_field_t *field);

/* White posts (fields whose goals are white, spl2020): a white upright
 * standing on the field.  Candidates: grid columns white (soft, below) at
 * 2 of the rows 3, 6, 10, 16 px above the border against the carpet below
 * it (the darkest of 3 rows 2-9 px down: not a goal line); runs of them,
 * ended where the border jumps by more than 3 px (a post's columns share
 * its foot row: on the SPL field the post hides the carpet strip behind
 * it, so the scanner's border there is its foot); each white stretch of a
 * row 8 px above a run's probe row (two posts, or a post and the goal's
 * rear frame, may share a run) is a candidate.  Its foot: the lowest row
 * of its middle column that is white or grey (a shaded foot: brighter
 * than the carpet, under half its chroma); where a goal line shows under
 * the post (every row below its lowest narrow row is wide), the line's
 * far edge.  A candidate is a post when
 *  - its foot is within 4 px of its column's border (up to half a width
 *    more above it: a goal line under the foot) and the border of the
 *    columns beside it lies at or above the foot (a white thing beyond
 *    the carpet stands above the border);
 *  - its width fits diameter * f / distance at the foot's range (0.5x - 2
 *    px .. 1.7x + 2): of the runs on 3 rows above the foot and at 10, 20
 *    and 30 % of a post's height, the one nearest that (a goal's ground
 *    frame, a net or a banner widen some rows, never all);
 *  - the lower 40 % of the height the camera predicts for a post at that
 *    range is as narrow on 1 row of 4, and its white climbs (strict; soft
 *    over a shaded stretch) either out of the image or on past 1.6 of that
 *    height (0.7 of it needed), or ends at 0.4-1.4 of it under a crossbar
 *    (the foot's range errs with the body's tilt) or at 0.8 of it with
 *    white on both sides (a white background).  A white end with no bar
 *    beside it is a robot (jersey, head: 0.72 of a post) or clutter; the
 *    ball and lines are flat;
 *  - somewhere 0.6-1.6 of that height above its bottom a row is wider
 *    than 2.5 widths (the crossbar, or a white wall behind it): an upright
 *    as narrow as a post all the way up is a door or window frame (asked
 *    where 1.2 of the height lies in the image).
 * White is relative to the carpet under the candidate: luma >= carpet +
 * max(40, (255 - carpet) * 2 / 5) (strict) or + max(20, 1/5 of that)
 * (soft: candidates, widths), chroma |Cb - 128| + |Cr - 128| <= 48.
 * Crossbar: at 1.5, 2.5 and 3.5 widths beside the end's row (+ half a
 * width), soft white there and not one width above it, on one side only
 * (a robot's shoulders reach 2 widths).  It gives the top (the end) and
 * the side: to the right, the left post facing the goal.  Else the top is
 * unknown and two posts take their sides from their order in the image.
 * Needs the camera (NULL: no posts).
 * Cost: 7 pixel reads per grid column (luma only, the chroma of bright
 * ones), then at most 32 * FL_GOAL_MAX_POSTS white stretches (the rest
 * counted in dropped; stretches wider than 1/6 of the image are rejected
 * unexamined), each: a run across it, two foot walks (at most to 6 px
 * below the border), runs cut at 1.7 expected widths + 2 px each way on
 * the rows from the foot to the probe row and on 6 rows; of those, at
 * most 8 * FL_GOAL_MAX_POSTS that pass the foot, width and carpet tests
 * (then the rest are dropped) also: a climb (at most 1.6 post heights + 2
 * widths, a run of at most 2 widths + 4 px each way on every 2nd row of
 * its lower 40 %) and 12 probes.  Measured
 * (callgrind): 0.34 M instructions on a 320x240 frame with a goal, 0.03-
 * 0.2 M on the noise frames of `make bench`, 0.5-0.9 M on real 640x480
 * frames.  Returns n. */
int32_t fl_goal_find_white(fl_posts_t *out, const fl_scan_t *scan,
                           const fl_image_t *img, const fl_camera_t *camera,
                           const fl_field_t *field);

/* Color class of one image pixel through the tables (RGB888: the RGB
 * table; YUYV/planar: the YCbCr table).  OTHER outside the image. */
fl_color_class_t fl_goal_pixel_class(const fl_image_t *img,
                                     const fl_color_table_t *colors,
                                     int32_t u, int32_t v);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_GOAL_H */
