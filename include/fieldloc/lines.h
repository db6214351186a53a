/*
 * fieldloc/lines.h - line points and line segments (seed 000, section 3.6).
 *
 * Line points.  The scanner's class map (scan.h) is read along a grid of
 * horizontal and vertical scan lines, step_px apart.  Every run of white
 * cells with a non-white cell on both sides (black-white-black in the
 * binary line image) and green within two cells on at least one side (paint
 * lies on carpet) gives one point: the run's midpoint.  Its width is
 * checked against the width a painted line of the field's line_width_mm has
 * at that row through the camera model: at least min_width_pct of it and at
 * most max_width_pct (oblique lines cross a scan line over a longer run;
 * robots, goals and clutter are wider still).
 *
 * Luma points.  Far away a line is a pixel or two across: blurred into
 * the carpet, its color is no longer white and the class map misses it,
 * or it lies a few pixels above the field border.  With the frame's image,
 * the same scan lines are read in the image's luma over the band of rows
 * where the projected width is at most luma_width_px (vertical scan lines
 * from a few pixels above their border): a ridge brighter than the pixels
 * d = 1 + 1.5 w (2..6 px) to either side by luma_contrast_pct of the
 * brighter one (and 8 levels), at most d - 1 px wide at half its height,
 * with carpet-colored flanks (Cb, Cr below grey), neither yellow nor
 * orange itself, going on in the pixel line beside the scan line (a line,
 * not a speck of noise), where the class map has no white within a cell,
 * gives a point flagged FL_LINE_POINT_LUMA (at most 8 ridges per scan line
 * and FL_LINES_MAX_POINTS / 8 per frame, counted in luma_capped).  The paths
 * that the segment stage checks for white (growth, the segment itself,
 * merge gaps) fall back to the luma where the class map falls short in
 * the band: the share of samples on a luma ridge across the path (at most
 * 32 samples, 256 such checks per frame, counted in ridge_checks).
 * Segments with luma points carry FL_SEG_LUMA.
 *
 * Standing objects.  White that stands up from the carpet (robots, the
 * ball, a person's shoes) is no paint.  Before the point scan every
 * vertical scan line's stretches of non-green cells below its border
 * (one green cell bridged) are tested: a stretch with at least 2 white
 * cells, at least 4 cells long and (with a camera) at least 3 times as
 * long as a line's projected width across it (2 times its width along the
 * row) at the stretch's bottom, is an object when its white is broken by
 * dark cells (OTHER or YELLOW, at least 2 and 1 in 8: joints, jersey,
 * shadow) or when, at its top row, its non-green run is wider than 3
 * projected line widths there plus 2 cells (a steep line is as wide as
 * the projection; a flat one is not that long).  No camera: 8 cells and
 * the dark rule only.  Up to FL_LINES_ROBOT_SPANS stretches (the longest)
 * per scan line are kept; a cell is on an object when a scan line on
 * either side of it (less than a line step away) has a stretch holding
 * its row.  Runs and luma ridges there give no point (counted in
 * robot_rejected); the crossing stage drops crossings inside one (the
 * scan lines on both sides hold the row: a line ending at a robot's foot
 * keeps its corner).
 *
 * Segments (seed 000, Algorithm 1).  Points are taken as seeds in order.
 * A segment grows from its tail, then from its head, to the best of the
 * nearest (at most FL_LINES_CANDIDATES) unassigned points within gap_px
 * ahead of that end (never a point of the same scan line: two runs of one
 * scan line have non-white between them), connected only when the cells
 * between them are white (white_pct); it stops when the summed squared
 * distance of its points to the line through its two end points exceeds
 * err_base_q2 + n * err_point_q2 (seed 000, equation 1; the per-point term
 * keeps a long straight line from being cut by quantization noise, while a
 * circle arc is cut into chords), scaled down to half where the projected
 * line is under 2 px wide (points of a thin line lie within a pixel; the
 * full allowance lets growth jump to a parallel line 2-3 px away).  Points
 * more than 2 px (plus a quarter of the line width; under 2 px wide: 1 px
 * plus half of it) off the grown segment's least-squares line are given
 * back (a point where another line joins).  A segment is kept with
 * min_points points, min_len_px length and a white straight path between
 * its ends.  It is merged into an earlier one when they extend each other:
 * nearly parallel, the shorter one's ends within 3 px of the longer's line,
 * the gap between their nearest ends white, and the summed squared error
 * of all their points to their least-squares line below the threshold
 * (here the least-squares line: the line through two jittered end points
 * would reject straight pieces).  Finally each segment is refitted by total
 * least squares (direction from the second moments, end points = its
 * extreme points projected on the fitted line) and its bulge (sagitta) is
 * fitted from its points' offsets.
 *
 * Work is bounded: at most FL_LINES_MAX_POINTS points (the point scan
 * stops at the scan line where the first one beyond was dropped),
 * neighbours found through a bucket grid (only the 3 x 3 buckets around an
 * end are searched, at most 96 points looked at), at most
 * FL_LINES_CANDIDATES white checks per growth step, each of at most gap_px
 * samples, 2 x FL_LINES_MAX_POINTS checks per frame (then growth stops,
 * counted in checks_capped), and FL_LINES_MAX_SEGMENTS segments
 * (merging compares a new segment with each stored one once, and the
 * stored ones pairwise once more).
 *
 * Lifecycle: fl_lines_params_default(&p); fl_lines_init(&l, &p) once;
 * per frame fl_lines_find_points(&l, &scan, &image, camera, line_width_mm)
 * then fl_lines_find_segments(&l, &scan); the image's pixels are read until the
 * frame's last fl_lines_find_segments / fl_lines_paint_pct / fl_crossings_find
 * (the view is kept in l).  Tests may instead fill points[] / n_points
 * with fl_lines_reset + fl_lines_add_point and call fl_lines_find_segments with a
 * NULL scan (no white checks).  Callers read everything before the
 * "private" mark.
 *
 * Coordinates: pixels of the input image (not grid cells), u right, v down,
 * pixel centres at integers.  Points are Q1 (half pixels: a run midpoint is
 * exact), segment ends Q4.
 */
#ifndef FIELDLOC_LINES_H
#define FIELDLOC_LINES_H

#include "fieldloc/camera.h"
#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/image.h"
#include "fieldloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FL_LINES_NONE 0xffffu   /* point not in a segment */
#define FL_LINES_CANDIDATES 5   /* nearest points tried per growth step */
#define FL_LINES_SEG_MAX_POINTS 1023 /* points per segment (overflow bound) */
#define FL_LINES_ROBOT_SPANS 2  /* standing-object spans kept per column */

/* Point flags. */
#define FL_LINE_POINT_VERTICAL 1u /* found on a vertical scan line (column) */
#define FL_LINE_POINT_LUMA 2u     /* a luma ridge of the image (thin far line
                                     the class map misses), not a white run */

typedef struct {
    int16_t u_q1, v_q1;   /* run midpoint, half pixels */
    uint8_t width_px;     /* white run length in pixels (saturated at 255) */
    uint8_t flags;        /* FL_LINE_POINT_* */
    uint16_t seg;         /* segment index, FL_LINES_NONE if none */
} fl_line_point_t;

/* Segment flags. */
#define FL_SEG_MERGED 1u  /* built from more than one grown piece */
#define FL_SEG_CIRCLE 2u  /* a chord of the centre circle (circle.h) */
#define FL_SEG_LUMA 4u    /* at least one of its points is a luma point */

typedef struct {
    /* fitted end points, Q4 pixels; (u0, v0) is the end with the smaller
     * u (smaller v when vertical) */
    int32_t u0_q4, v0_q4, u1_q4, v1_q4;
    int32_t len_q4;       /* |end1 - end0|, Q4 pixels */
    fl_angle_t angle;     /* image direction end0 -> end1, atan2(dv, du) */
    uint16_t n;           /* points */
    uint8_t flags;        /* FL_SEG_* */
    uint8_t reserved;
    uint32_t sse_q2;      /* summed squared distance of its points to the
                             fitted line, quarter pixels squared (Q2) */
    int32_t bulge_q4;     /* sagitta of its points, Q4 px: offset of the
                             middle against the ends, from a parabola fit
                             of the offsets, signed along the normal
                             (-sin angle, cos angle); ~0 when straight */
    /* ---- private: growth state ---- */
    int16_t au, av;       /* anchor (Q1, halved above 2048 px) */
    int16_t e0u, e0v, e1u, e1v; /* extreme points, Q1 */
    uint16_t n_luma;      /* luma points among its points */
    int64_t sx, sy, sxx, syy, sxy; /* moments about the anchor */
} fl_segment_t;

typedef struct {
    int32_t step_px;          /* scan line spacing, px; 0 = auto
                                 (max(2, width / 80)); else 1..64 */
    int32_t gap_px;           /* largest distance between neighbouring
                                 points of one segment, px; 0 = auto
                                 (3 * step); else 2..255 */
    int32_t min_points;       /* points of a kept segment, 2..255 */
    int32_t min_len_px;       /* length of a kept segment, px; 0 = auto
                                 (2 * step); else 1..4096 */
    int32_t err_base_q2;      /* summed squared error allowance, (px/2)^2 */
    int32_t err_point_q2;     /* ... plus this per point; both 0..65535 */
    int32_t white_pct;        /* white cells needed between connected
                                 points, 0..100 */
    int32_t merge_gap_px;     /* largest gap bridged by merging, px; 0 =
                                 auto (6 * step); else 1..4096 */
    int32_t max_width_pct;    /* horizontal runs up to this % of the
                                 projected line width (oblique lines),
                                 100..2000 */
    int32_t min_width_pct;    /* runs at least this % of the projected
                                 width (thinner: noise), 0..100 */
    int32_t luma_contrast_pct; /* luma points: ridge at least this % of
                                 its brighter flank above it (and 8 grey
                                 levels), 1..100; 0 = no luma points */
    int32_t luma_width_px;    /* luma points only where the projected
                                 line width is at most this, 1..16 px */
} fl_lines_params_t;

typedef struct {
    fl_lines_params_t params;
    /* ---- results ---- */
    int32_t n_points;
    fl_line_point_t points[FL_LINES_MAX_POINTS];
    int32_t n_segments;
    fl_segment_t segments[FL_LINES_MAX_SEGMENTS];
    int32_t width, height;    /* image of the last frame, px */
    int32_t step_px, gap_px;  /* effective values of the last frame */
    int32_t line_width_mm;    /* as given to fl_lines_find_points (0: none) */
    /* counters of the last frame */
    int32_t points_dropped;   /* beyond FL_LINES_MAX_POINTS (> 0: the
                                 table overflowed; fl_lines_find_points
                                 stops at the scan line of the first, so
                                 its count and runs_rejected, luma_points,
                                 luma_capped are those seen until then) */
    int32_t runs_rejected;    /* white runs failing the width check */
    int32_t segments_dropped; /* beyond FL_LINES_MAX_SEGMENTS */
    int32_t merges;           /* pieces merged into earlier segments */
    int32_t white_checks;     /* white-ratio checks made by the growth */
    int32_t checks_capped;    /* growth steps stopped by the per-frame
                                 budget of 2 x FL_LINES_MAX_POINTS checks,
                                 FL_LINES_MAX_POINTS / 2 once points were
                                 dropped (clutter) */
    int32_t luma_points;      /* points found as luma ridges */
    int32_t luma_capped;      /* scan lines cut by the per-line cap, plus
                                 ridges beyond the per-frame cap */
    int32_t ridge_checks;     /* paths checked in the luma (after the class
                                 map fell short) */
    int32_t robot_rejected;   /* runs and ridges on a standing object (a
                                 robot, a ball, a leg): no points */
    int32_t robot_spans;      /* standing-object spans found in the
                                 sampled columns */
    /* ---- private ---- */
    fl_image_t img;           /* view of this frame's pixels (width 0:
                                 none); valid while the caller's frame is */
    int32_t lum_vend, lum_hend; /* last rows of the luma band, vertical and
                                 horizontal scan lines (-1: none) */
    int32_t lum_above;        /* luma scan starts this far above the border */
    int32_t thr_q8;           /* error threshold scale of the current test */
    uint8_t lum_dv[FL_IMAGE_MAX_DIM]; /* flank distance per row, columns */
    uint8_t lum_dh[FL_IMAGE_MAX_DIM]; /* ... rows */
    uint8_t lum_buf[FL_IMAGE_MAX_DIM]; /* one scan line's lumas */
    int32_t bshift, bcols, brows;   /* bucket size 2^bshift px, grid */
    uint16_t bstart[FL_LINES_MAX_BUCKETS + 1];
    uint16_t border[FL_LINES_MAX_POINTS];  /* point ids sorted by bucket */
    /* standing objects: up to FL_LINES_ROBOT_SPANS spans of grid rows
     * [lo, hi] per sampled column (every rob_step-th from rob_step / 2);
     * lo > hi: none */
    int32_t rob_step;
    int16_t rob_lo[FL_SCAN_MAX_COLS][FL_LINES_ROBOT_SPANS];
    int16_t rob_hi[FL_SCAN_MAX_COLS][FL_LINES_ROBOT_SPANS];
    int16_t wtab_h_q4[FL_LINES_WTAB];      /* projected widths by row band */
    int16_t wtab_v_q4[FL_LINES_WTAB];
    int32_t wtab_shift;
    uint16_t grow_ids[FL_LINES_SEG_MAX_POINTS]; /* segment being grown */
    uint16_t remap[FL_LINES_MAX_SEGMENTS];      /* merge pass */
    int64_t curv[FL_LINES_MAX_SEGMENTS][5];     /* bulge fit sums */
} fl_lines_t;

/* Defaults: step auto, gap auto, 3 points, length auto, error 16 + 4 per
 * point (Q2: 4 px^2 + 1 px^2 per point), white 70 %, merge gap auto, width
 * 400 % .. 25 %, luma contrast 12 % where the line is at most 3 px wide. */
void fl_lines_params_default(fl_lines_params_t *p);

/* Validate params (FL_ERR_RANGE) and clear.  FL_ERR_NULL.  FL_ERR_CONFIG
 * (common.h: the caller's config.h differs from the library's): nothing
 * written. */
fl_status_t fl_lines_init_cfg(fl_lines_t *l, const fl_lines_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_lines_init(fl_lines_t *l, const fl_lines_params_t *p)
{
    return fl_lines_init_cfg(l, p, FL_CONFIG_FINGERPRINT);
}

/* Find the line points of a scanned frame.  img: the scanned frame (same
 * size as the scan) or NULL (no luma points).  camera may be NULL (no
 * width check, no luma points); line_width_mm <= 0 also disables both.
 * Returns n_points (0 for a NULL or empty scan). */
int32_t fl_lines_find_points(fl_lines_t *l, const fl_scan_t *scan,
                             const fl_image_t *img, const fl_camera_t *camera,
                             int32_t line_width_mm);

/* Start a point list by hand (tests): clears points and segments and sets
 * the image size used by the bucket grid.  Returns false on a bad size. */
bool fl_lines_reset(fl_lines_t *l, int32_t width, int32_t height);
/* Append a point (Q1 pixels inside the image); false when full or outside
 * (full: counted in points_dropped). */
bool fl_lines_add_point(fl_lines_t *l, int32_t u_q1, int32_t v_q1,
                        int32_t width_px, uint8_t flags);

/* Grow and merge segments from points[] (seed 000, Algorithm 1).  scan may
 * be NULL: every connection then counts as white.  Returns n_segments. */
int32_t fl_lines_find_segments(fl_lines_t *l, const fl_scan_t *scan);

/* Percentage (0..100) of white grid cells on the straight path between two
 * pixels (Q4), thin-line tolerant (a cell counts as white when it or a
 * neighbour across the path is).  Samples every grid cell along the
 * longer axis, at most 4096.  100 for a NULL scan; 0 when the path leaves
 * the grid entirely. */
int32_t fl_lines_white_pct(const fl_scan_t *scan, int32_t u0_q4,
                           int32_t v0_q4, int32_t u1_q4, int32_t v1_q4);

/* Paint on the straight path between two pixels (Q4), 0..100: the class
 * map's white ratio (fl_lines_white_pct); where that is below white_pct
 * and the path's middle row lies in the luma band of the last frame
 * (projected width at most luma_width_px, with its image), the share of
 * 1 px samples (at most 64) on a luma ridge across the path when higher.
 * Reads the frame's pixels: call before the caller releases them.  l NULL:
 * fl_lines_white_pct. */
int32_t fl_lines_paint_pct(const fl_lines_t *l, const fl_scan_t *scan,
                           int32_t u0_q4, int32_t v0_q4, int32_t u1_q4,
                           int32_t v1_q4);

/* fl_lines_paint_pct for a line with a second one close beside it (a far
 * goal box: goal line and box front line a few px apart): a luma sample
 * whose one flank is bright also counts when that side is dark 2 px
 * beside the ridge's peak and the other flank is dark. */
int32_t fl_lines_paint_beside_pct(const fl_lines_t *l, const fl_scan_t *scan,
                                  int32_t u0_q4, int32_t v0_q4, int32_t u1_q4,
                                  int32_t v1_q4);

/* Projected width (Q4 px) of a painted line at pixel row v_px, as used by
 * the width check: across the row (horizontal run of a line pointing away
 * from the camera) or along the column (vertical: a line seen crosswise).
 * 0 when unknown (no camera, row above the horizon, or no frame). */
int32_t fl_lines_width_q4(const fl_lines_t *l, int32_t v_px, bool vertical);

/* Ids of the points in the box |du| <= ru_px, |dv| <= rv_px around
 * (u_q1, v_q1): at most FL_LINES_NEAR_MAX stored in ids (which must hold
 * that many; may be NULL), all counted in the return value.  Valid after
 * fl_lines_find_segments.  Cost: the buckets the box covers.  FL_LINES_NEAR_MAX:
 * config.h. */
int32_t fl_lines_points_near(const fl_lines_t *l, int32_t u_q1, int32_t v_q1,
                             int32_t ru_px, int32_t rv_px, uint16_t *ids);

/* Is pixel (u_px, v_px) inside a standing object (a robot, a ball: white
 * that is no paint, see "Standing objects" above) of the last
 * fl_lines_find_points with this scan: the scan lines on both sides of it
 * (or its own) have a stretch holding its row?  false outside the image
 * or with no scan. */
bool fl_lines_on_object(const fl_lines_t *l, const fl_scan_t *scan, int32_t u_px,
                        int32_t v_px);

/* Distance in Q4 pixels from a point (Q4) to the infinite line of a
 * segment, signed (positive to the left of end0 -> end1 in image axes,
 * i.e. toward smaller v for a segment pointing +u). */
int32_t fl_segment_distance_q4(const fl_segment_t *s, int32_t u_q4,
                               int32_t v_q4);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_LINES_H */
