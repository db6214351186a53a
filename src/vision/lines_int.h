/*
 * src/vision/lines_int.h - line stage internals shared by lines.c,
 * lines_points.c and lines_segments.c (seed 000, section 3.6 and Algorithm 1);
 * see lines.h for the method.
 *
 * Algorithm.
 *   points   every m-th grid row of the scanner's class map is read 32
 *            cells at a time (white masks), every m-th grid column cell by
 *            cell from its border down; each white run closed by non-white
 *            cells, with green beside it and a width that passes the
 *            projected-width check (a per-row table from the camera,
 *            FL_LINES_WTAB knots, interpolated) becomes a point (Q1).
 *   luma     with the image: the same scan lines in the band of rows where
 *            the projected width is at most luma_width_px, read in luma
 *            (one pass per scan line into lum_buf); ridge runs with
 *            carpet flanks and no class-map white nearby become points
 *            flagged FL_LINE_POINT_LUMA.  White checks that fall short in
 *            the band are retried as luma ridge checks across the path
 *            (a second line close beside on one flank tolerated:
 *            LN_RIDGE_NEAR).
 *   buckets  points are counting-sorted into square buckets of 2^bshift
 *            px >= gap_px, so the neighbours of a point within gap_px lie in
 *            the 3 x 3 buckets around it.
 *   growth   seed = first point not yet tried; grow the tail, then the
 *            head: candidates = unassigned points of other scan lines
 *            within gap_px, ahead of the end (positive projection on the
 *            segment direction) and within gap/2 of its line, ranked by
 *            distance + 3 x offset; the best FL_LINES_CANDIDATES are tried
 *            in order, each needs white_pct white cells on the way and must
 *            keep the error of equation 1 (line through the ends) within
 *            the threshold; then the outliers of the least-squares line are
 *            pruned and the end-to-end white check decides.
 *   merge    a kept segment is merged into the first stored segment that it
 *            extends (angle within ~6 deg or 3 px over the shorter piece,
 *            the shorter piece's ends within 3 px of the longer's line, gap
 *            <= merge_gap_px and white when longer than gap_px, summed
 *            squared error to the least-squares line within the
 *            threshold); a last pass merges stored pairs the same way (a
 *            line cut by an occluder).
 *   refit    total least squares from the second moments: direction
 *            1/2 atan2(2 Cuv, Cuu - Cvv), end points = extreme points
 *            projected on the fitted line; bulge = parabola fit of the
 *            points' offsets (ln_curvature).
 *
 * Invariant.  Every point belongs to at most one segment; point.seg is the
 * index of a stored segment or FL_LINES_NONE.  A stored segment has at
 * least min_points points (<= FL_LINES_SEG_MAX_POINTS) and its moments are
 * the exact sums over its points.
 *
 * Memory: the caller's fl_lines_t (see config.h; ~34 KB at the defaults,
 * the per-segment point list, the luma tables and scratch included: 3
 * bytes per image row).  Stack < 700 bytes.
 * Cost: points O(grid cells / m); luma points O(band rows x width / m):
 * every pixel of every m-th column in the band and of every m-th row of
 * the band read once (about 15 instructions per pixel from RGB, 5 from
 * YUYV or planar), plus at most 8 ridge tests per scan line; ridge checks
 * at most 256 x 33 samples of 5 pixels per frame (64 and a growth budget
 * of FL_LINES_MAX_POINTS / 2 checks once the points overflowed; stopping once the
 * threshold is out of reach); growth O(points x (3 x 3 bucket
 * occupancy + FL_LINES_CANDIDATES x gap samples)); merging O(segments^2)
 * cheap tests plus at most one white check per candidate pair; refit and
 * bulge O(points + segments).
 *
 * Scaling and overflow (segment error).  Point coordinates relative to the
 * segment's anchor (its seed), in half pixels shifted right by LN_MSHIFT
 * (0 for images up to 2048 px, 1 above), so |x|, |y| <= 2^12.  Moments over
 * n <= 1023 points: |sx| <= 2^22, sxx <= 2^34.  Growth (equation 1): the
 * error of the line through ends P, Q with normal (a, b) = (P_v - Q_v,
 * Q_u - P_u), |a|, |b| <= 2^13 after re-anchoring, c = a P_u + b P_v
 * (|c| <= 2^26):
 *     E (a^2 + b^2) = a^2 sxx + 2ab sxy + b^2 syy - 2c (a sx + b sy) + n c^2
 * each term below 2^61, the sum (exact, int64) below 2^63; compared with
 * threshold (a^2 + b^2) without a division.  Merging: the least-squares
 * error from the n-scaled central moments (< 2^45), see ln_sse_fit.
 */
#ifndef FL_VISION_LINES_INT_H
#define FL_VISION_LINES_INT_H

#include "fieldloc/lines.h"

#if FL_IMAGE_MAX_DIM > 2048
#define LN_MSHIFT 1
#else
#define LN_MSHIFT 0
#endif

#define LN_SEEDED 0x80u   /* internal point flag: already used as a seed */

/* Per frame: white checks of the growth (real frames use about 1.5 per
 * point, random class noise 8) and points looked at per candidate search
 * (real frames: under 40 in the 3 x 3 buckets). */
#define LN_CHECK_BUDGET (2 * FL_LINES_MAX_POINTS)
#define LN_SEARCH_MAX 96
/* Clutter: a frame whose line points overflowed FL_LINES_MAX_POINTS (every
 * rendered fixture and UvA frame has at most a third of them; class noise
 * fills the table) gets a quarter of the growth's white checks and of the
 * ridge checks: a field frame never gets there, and the worst frame's
 * cost is mostly failed checks. */
#define LN_CLUTTER_BUDGET (FL_LINES_MAX_POINTS / 2)
#define LN_CLUTTER_RIDGE_BUDGET (LN_RIDGE_BUDGET / 4)

#define LN_RIDGE_BUDGET 256  /* ridge checks of the segment stage per frame */
/* Flag in fl_lines_int_ridge_pct's need: a line close beside.  Only with line steps
 * of 3 px or more (images from 240 px wide): with the 2 px steps of the
 * AIBO's 208x160 frames it moves the far goal-line and box segments enough
 * to bias the localizer's heading. */
#define LN_RIDGE_NEAR 0x1000

/* ---- small helpers --------------------------------------------------------- */

static inline int32_t ln_abs(int32_t a) { return a < 0 ? -a : a; }
static inline int64_t ln_abs64(int64_t a) { return a < 0 ? -a : a; }
static inline int32_t ln_clamp(int32_t x, int32_t lo, int32_t hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

/* The frame's budgets (see LN_CLUTTER_BUDGET). */
static inline int32_t ln_check_budget(const fl_lines_t *l)
{
    return l->points_dropped > 0 ? LN_CLUTTER_BUDGET : LN_CHECK_BUDGET;
}

static inline int32_t ln_ridge_budget(const fl_lines_t *l)
{
    return l->points_dropped > 0 ? LN_CLUTTER_RIDGE_BUDGET : LN_RIDGE_BUDGET;
}


/* mode: the largest number of samples (1..4096), plus LN_STRICT for no
 * neighbour tolerance, plus LN_NEED(p) for callers that only compare the
 * result with p (1..100): the walk stops once p is out of reach and the
 * ratio so far (below p) is returned (six arguments: no stack-passed
 * ones). */
#define LN_STRICT 0x10000
#define LN_NEED(p) ((int32_t)(p) << 20)
int32_t fl_lines_int_white_pct(const fl_scan_t *scan, int32_t u0_q4, int32_t v0_q4,
                     int32_t u1_q4, int32_t v1_q4, int32_t mode);

/* Percentage of 1 px samples (at most LN_RIDGE_SAMPLES, spread evenly) of the straight path between two
 * pixels (Q4) that lie on a luma ridge across the path: the brightest of
 * the sample and its two neighbours across stands out (ln_ridge) of the
 * brighter of the two pixels d + 1 away across (d from the projected width
 * across the path at its middle row).  0 outside the image or without
 * luma.  Stops early once `need` percent is out of reach (then the result
 * is some value below need).  need | LN_RIDGE_NEAR: a sample whose one
 * flank is bright (a second line close beside) also passes when the pixel
 * 1 or 2 px beside the peak on that side is dark and the other flank is
 * (at most 2 more pixel reads per failing sample).  Scaling: Q4 positions < 2^17, the unit normal in Q8, products
 * < 2^26 in int32. */
int32_t fl_lines_int_ridge_pct(const fl_lines_t *l, int32_t u0, int32_t v0, int32_t u1,
                    int32_t v1, int32_t need);

/* Does a path whose class-map white ratio is p fall back to the luma:
 * below white_pct, with an image, its middle row (Q4 ends) in the band? */
static inline bool ln_luma_path(const fl_lines_t *l, int32_t p, int32_t v0, int32_t v1)
{
    int32_t bend = l->lum_vend > l->lum_hend ? l->lum_vend : l->lum_hend;
    return p < l->params.white_pct && l->img.width > 0 && bend >= 0 &&
           (v0 + v1) / 32 <= bend;
}

/* Paint on the path, for a comparison with params.white_pct: the class
 * map's white ratio (thin-line tolerant, the walk stopping once white_pct
 * is out of reach, see fl_lines_int_white_pct); where ln_luma_path, the luma ridge
 * ratio when higher (counted in ridge_checks).  Six arguments: a seventh
 * goes on the stack, a dynamic frame that make stack rejects. */
int32_t fl_lines_int_paint_pct(fl_lines_t *l, const fl_scan_t *scan, int32_t u0, int32_t v0,
                    int32_t u1, int32_t v1);

/* Bucket grid of the points (fl_lines_find_points builds it, fl_lines_points_near
 * and the segment growth read it). */
void fl_lines_int_buckets(fl_lines_t *l);

/* Standing objects (lines_robots.c): find the spans of every step-th grid
 * column (after the width table is made); is grid cell (i, j) on one? */
void fl_lines_int_robots(fl_lines_t *l, const fl_scan_t *s, int32_t step);
bool fl_lines_int_on_robot(const fl_lines_t *l, const fl_scan_t *s, int32_t i, int32_t j,
                           bool inside);
/* ... any cell of row j from column i0 to i1 (a horizontal run)? */
bool fl_lines_int_run_on_robot(const fl_lines_t *l, const fl_scan_t *s, int32_t i0, int32_t i1,
                               int32_t j);

#endif
