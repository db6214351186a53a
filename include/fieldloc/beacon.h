/*
 * fieldloc/beacon.h - colored landmarks of the AIBO fields (seed 004's
 * four-legged league): the sky-blue goal's posts and the corner beacons.
 *
 * The column scanner's classes are green, white, yellow and other; a
 * sky-blue goal and the pink bands of a beacon are "other" to it.  This
 * stage looks at the frame again, sparsely, in the part of each column
 * that lies above the field border the scanner found (plus a few pixels
 * below it), and classifies each sample exactly: the pixel's HSV
 * (fl_hsv_from_rgb; YUYV and planar frames through fl_rgb_from_ycbcr, the
 * integer BT.601 of src/base/image.c) against three boxes of the params:
 * sky-blue, pink and a yellow narrower than the color table's.
 *
 * Method.  Per sampled column: vertical runs of one color (a one-sample
 * gap bridged), their top and bottom refined to the pixel.  Runs of the
 * same color that overlap vertically in neighbouring sampled columns are
 * joined into blobs (union-find over a fixed table).  Then:
 *  - sky-blue goal (and yellow with yellow_goals; the post color is the
 *    blob's): a blob at least 3 sampled columns wide whose
 *    bottom meets the field border (border within 1 row step + 3 px under
 *    the bottom and carpet within 3 px under it, in half of its columns:
 *    a sky-blue thing beyond the carpet stands on the wall top, with the
 *    wall's white between it and the carpet) and whose height fits a goal
 *    at the foot's distance (0.5 .. 2.5 times f * post_height / distance).
 *    Each edge that is not the image edge is a post: the outermost column
 *    whose bottom is within 2 px of the lowest bottom of that half, its
 *    edge refined to the pixel along a row 2 px above the bottom, the post
 *    centre half a (predicted) post width inside; not when the border
 *    beside the edge (2, 4, 6 px out) is all more than a row step + 3 px
 *    below the foot (a robot in front cuts the goal).  Left edge =
 *    FL_SIDE_LEFT (goal.h: sides as seen facing the goal).
 *  - beacon: a pink blob stacked on a yellow or sky-blue blob or under one
 *    (the gap between them at most one row step + 2 px + a third of a
 *    band), overlapping by half the narrower width, widths within a factor
 *    2, each band 0.4 .. 2.5 times as tall as wide (the upper band may be
 *    cut by the image top), white under the lower band (the base).  Color
 *    = upper band, color2 = lower band.  A single yellow or sky-blue band
 *    cut by the image top with the white base under it is reported with
 *    color NONE and color2 = that band (it can only be a lower band: the
 *    other color would be visible under it otherwise).
 *    Foot: down the beacon's centre column from the lower band, the first
 *    carpet (green) pixel, accepted 1.2 .. 3.2 band heights under the band
 *    (the white base is two bands tall).  Range from the foot (half a
 *    diameter added along the ray, as goal.c); else from the height of the
 *    two bands (200 mm of a 400 mm beacon): distance = f * 2 band / h_px,
 *    ground range sqrt(distance^2 - (band centre - camera height)^2), with
 *    lower confidence.  With a foot, the band width must be 0.6 .. 1.6
 *    times (+- 2 px) the width a beacon has at the foot's distance.
 *
 * Lifecycle: fl_beacon_params_default, fl_beacon_init (validates), then
 * fl_beacon_find per frame after fl_scan_frame (vision.c calls it when the
 * field has beacons or a sky-blue or pink goal).  Results in
 * fl_beacon_t.found; counters of what did not fit.
 * Cost: one HSV conversion per sample (the columns above their border plus
 * below_border_px, every col_step-th column and row_step-th row), 2
 * row_steps of pixel refinement per run, O(runs) blob joining, O(blobs^2)
 * pairing (<= FL_BEACON_MAX_BLOBS^2 / 2), per result at most a column
 * walk of 4 band heights and a few probes.
 */
#ifndef FIELDLOC_BEACON_H
#define FIELDLOC_BEACON_H

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

/* Capacities FL_BEACON_MAX_RUNS, _BLOBS, _FOUND: config.h.  Runs and blobs
 * beyond a cap are counted (runs_dropped, blobs_dropped) and ignored;
 * results beyond FL_BEACON_MAX_FOUND in found_dropped. */

/*
 * Default boxes (fl_beacon_params_default), measured on the rendered
 * aibo2004 fixtures re-rendered at gain 40..160 % (tools/world/render.c paints
 * sky-blue 80,175,230 and pink 245,90,170; the renderer's mask says which
 * pixels are goal, beacon or background), OpenCV hue units:
 *   sky-blue goal pixels: hue 90..104 (99..102 for 80 %), S p1 134, V p1 53
 *   pink beacon bands:    hue 154..170 (163..165 for 80 %), S p1 98, V p1 57
 *   background (room clutter, robots) with S >= 50 in those hues: sky-blue
 *     couches / bags / books 102..118 (peak 104: a couch is sky-blue as far
 *     as hue goes: geometry, not color, rejects it), red 175..179 and 0..1,
 *     purple shirts ~146, 69 of 567550 background pixels in the pink box.
 *   skyblue  hue 88..108, S 90..255, V 40..255 (goal +- 2 of hue drift; S
 *            and V far below the measured p1: shadow, dark frames)
 *   pink     hue 150..172, S 80..255, V 40..255 (clear of red at 175 and
 *            purple at 146)
 *   yellow   hue 20..38, S 120..255, V 40..255 (beacon yellow bands hue
 *            26..30 and S 188..196 at nominal light, posts 26..32 with S
 *            >= 167 on the UvA images; brown furniture is hue 14..16, S
 *            105..115)
 */
typedef struct {
    fl_hsv_box_t skyblue;
    fl_hsv_box_t pink;
    fl_hsv_box_t yellow;      /* beacon bands (not the color table's
                                 yellow: its hue 15..40, S >= 90 takes in
                                 brown furniture, hue 15 S 110) */
    int32_t col_step;         /* px between sampled columns, 0 = auto
                                 (2 up to 208 px wide, then width / 104
                                 rounded up), else 1..16 */
    int32_t row_step;         /* px between sampled rows, 0 = auto (as
                                 col_step with the height / 80), 1..16 */
    int32_t below_border_px;  /* rows sampled under the border, 0..64 */
    int32_t min_confidence;   /* results below are not reported, 0..255 */
    int32_t yellow_goals;     /* 1: yellow goals too, by the same blob
                                 method, when the field has a yellow goal
                                 (the AIBO goal is a box with side and back
                                 panels, which goal.c's post-and-crossbar
                                 model rejects); 0: sky-blue only */
} fl_beacon_params_t;

/* One vertical run of a color in a sampled column. */
typedef struct {
    int16_t u;                /* column, px */
    int16_t v0, v1;           /* first and last row of the color, px */
    uint8_t color;           /* fl_color_t: YELLOW, SKYBLUE, PINK */
    uint8_t blob;             /* blob index (after joining) */
} fl_beacon_run_t;

/* A blob: joined runs of one color. */
typedef struct {
    int16_t u0, u1;           /* first and last sampled column, px */
    int16_t v0, v1;           /* highest top, lowest bottom, px */
    uint16_t samples;         /* samples of the color (saturating) */
    uint8_t color;           /* fl_color_t */
    uint8_t used;             /* private: taken by a result */
} fl_beacon_blob_t;

/* One result: a beacon or a post of a sky-blue goal. */
typedef struct {
    fl_landmark_kind_t kind;  /* FL_LM_BEACON or FL_LM_POST */
    fl_color_t color;       /* beacon: upper band (NONE when cut off);
                                 post: the goal's color (SKYBLUE, YELLOW) */
    fl_color_t color2;      /* beacon: lower band; post: NONE */
    fl_side_t side;           /* posts: LEFT / RIGHT; beacons: UNKNOWN */
    int32_t u_q4, v_q4;       /* foot: base centre (Q4 px); for a beacon
                                 without a foot, the lower band's bottom */
    int32_t top_v_q4;         /* beacon: top of the upper band; post: top
                                 of the goal blob (Q4 px) */
    int32_t width_q4;         /* beacon: band width; post: predicted post
                                 width (Q4 px) */
    bool foot_visible;        /* range from the foot (else from the size) */
    fl_point_t ground;        /* landmark centre, robot frame, mm */
    int32_t range_mm;         /* 0 when no camera */
    fl_angle_t bearing;
    uint8_t confidence;       /* Q0.8 */
} fl_beacon_found_t;

typedef struct {
    fl_beacon_params_t params;
    /* ---- results of the last fl_beacon_find ---- */
    int32_t n;                                    /* results */
    fl_beacon_found_t found[FL_BEACON_MAX_FOUND];
    int32_t col_step, row_step;                   /* grid in effect */
    int32_t samples;                              /* pixels classified */
    int32_t n_runs;
    fl_beacon_run_t run[FL_BEACON_MAX_RUNS];
    int32_t n_blobs;
    fl_beacon_blob_t blob[FL_BEACON_MAX_BLOBS];
    /* counters of this frame */
    int32_t runs_dropped;      /* runs beyond FL_BEACON_MAX_RUNS */
    int32_t blobs_dropped;     /* runs that found no blob slot */
    int32_t found_dropped;     /* results beyond FL_BEACON_MAX_FOUND */
    int32_t rejected_goal;     /* goal-colored blobs failing the goal checks */
    int32_t rejected_beacon;   /* stacked band pairs failing the checks */
    /* private: union-find parents of the blobs while joining */
    uint8_t parent[FL_BEACON_MAX_BLOBS];
} fl_beacon_t;

/* The boxes above, automatic grid, 4 px under the border, confidence 40,
 * yellow goals on. */
void fl_beacon_params_default(fl_beacon_params_t *p);

/* Validate (FL_ERR_RANGE: hue > 179, lo > hi for S or V, a step, the
 * margin or the confidence out of range) and clear.  FL_ERR_NULL.
 * FL_ERR_CONFIG
 * (common.h: the caller's config.h differs from the library's): nothing
 * written. */
fl_status_t fl_beacon_init_cfg(fl_beacon_t *b, const fl_beacon_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_beacon_init(fl_beacon_t *b, const fl_beacon_params_t *p)
{
    return fl_beacon_init_cfg(b, p, FL_CONFIG_FINGERPRINT);
}

/* Find beacons and sky-blue goal posts in a scanned frame.  scan: the
 * frame's fl_scan_frame result (its border); colors: the table the scan
 * used (yellow box, carpet class); camera may be NULL (image positions
 * only, range 0); field: beacon and post sizes (NULL or 0: 100 x 400 mm
 * beacons, 50 x 300 mm posts).  Returns n; 0 on bad input (NULL, an image
 * of another size than the scan). */
int32_t fl_beacon_find(fl_beacon_t *b, const fl_scan_t *scan,
                       const fl_image_t *img, const fl_color_table_t *colors,
                       const fl_camera_t *camera, const fl_field_t *field);

/* Color of one pixel by the boxes of p: FL_COLOR_YELLOW, SKYBLUE, PINK
 * or NONE (also outside the image, an invalid view, or NULL). */
fl_color_t fl_beacon_pixel_color(const fl_beacon_params_t *p,
                                   const fl_image_t *img, int32_t u, int32_t v);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_BEACON_H */
