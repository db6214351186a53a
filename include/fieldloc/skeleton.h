/*
 * fieldloc/skeleton.h - line crossings from a binary mask of painted
 * lines: thinning to one pixel, node degrees, crossings merged, and a
 * sample of skeleton pixels (seed 002 section IV.B.3).  Pure image space:
 * every position is in mask pixel coordinates (x right, y down, the
 * centre of pixel (x, y) at (x, y)); mapping to the image and the ground
 * is the caller's.
 *
 * Thinning: K3M (K. Saeed, M. Tabedzki, M. Rybnik, M. Adamski, "K3M: a
 * universal algorithm for image skeletonization and a review of thinning
 * techniques", Int. J. Appl. Math. Comput. Sci. 20(2):317-335, 2010),
 * which seed 002 cites, rather than Hilditch's algorithm, which its text
 * names: K3M is defined by lookup tables of the 8-neighbourhood weight,
 * so each test is one table read; its phases 1..5 peel a border pixel
 * only when its white neighbours form one circular run of 3..7 pixels
 * (such a pixel is simple: removing it keeps every 8-connected white
 * component and opens no hole), and its final phase thins the remaining
 * two-pixel-thick diagonal staircases to one pixel, where Hilditch's
 * parallel conditions either leave them two thick or, in the common
 * simplified form, erase a 2x2 square entirely.  src/vision/skeleton.c
 * states the tables and where this implementation departs from the paper.
 *
 * Degree of a skeleton pixel: the crossing number of Rutovitz, the
 * number of 0 -> 1 transitions going once around its 8 neighbours (N, NE,
 * E, ... NW), i.e. the number of circular runs of white neighbours.  The
 * plain count of white neighbours over-counts on staircases and next to a
 * junction (a branch that touches a pixel with an edge and a corner
 * neighbour counts twice).  The number of 8-connected groups of white
 * neighbours under-counts at junctions: the centre of a one-pixel plus,
 * whose four edge neighbours touch each other diagonally, gets 1 instead
 * of 4.  Degree 1: an end; 2: a line; 3 and more: a node.
 * Several adjacent pixels of one junction may be nodes: they are merged,
 * and a crossing's arm count comes from its branches, not from a degree.
 *
 * Pinholes: a background pixel with 3 or 4 white edge neighbours (a hole
 * of one or two pixels, a one-pixel notch) is taken as white: such noise
 * in a line would put a loop, and so nodes, into its skeleton.
 *
 * Crossings: end branches of at most spur_px pixels that end at a node
 * (ragged mask edges) are removed first; the remaining node pixels
 * within merge_px of each other (Chebyshev, chained), or linked by a
 * skeleton path inside their grown box (an acute X thins to two T nodes
 * several pixels apart), are one cluster; its arms are the distinct
 * skeleton branches, flooded from the cluster inside the box of its node
 * pixels grown by arm_px, that cross that box's border (so an arm is at
 * least arm_px long), each followed up to arm_px further for its
 * direction: 4 arms X, 3 T, 2 at an angle L (only with report_l; a
 * straight pair is a line, not reported), more than 4 rejected; an arm
 * that reaches the mask edge inside the box rejects the cluster (an X
 * with an arm outside the mask is no T).  Position: X, the intersection
 * of the lines through opposite arms; T, the node centroid projected on
 * the line of the straightest arm pair; L, the node centroid.
 *
 * Lifecycle: fl_skel_params_default, fl_skel_init (validates), then
 * fl_skel_run per frame; results in the state until the next run.
 *
 * Bounded work: copying the mask into the padded working image is
 * O(width x height) once (8-byte words of background skipped); every
 * thinning pass visits only the contour list (the white pixels that may
 * still change: those next to the background, plus those a deletion
 * exposes), at most FL_SKEL_MAX_CONTOUR entries, 6 phases per iteration
 * (K3M's phases 0..5), at most max_iterations iterations, then at most 16
 * passes of the final phases; neighbourhood weights are kept per pixel (8
 * updates per change); node and degree passes are O(skeleton pixels);
 * spur walks at most spur_px steps per end; clustering O(nodes^2)
 * (<= FL_SKEL_MAX_NODES^2 / 2); joining at most 4 passes of one flood per
 * cluster, O(nodes) per node pixel a flood meets; each crossing a flood
 * of its box and 4 walks of arm_px; the sample O(n_points).  Measured
 * (callgrind, 320 x 240): a field-like view of 4600 white pixels 1.8 M
 * instructions; all white 12.5 M (the iteration cap); uniform noise, half
 * white, 17.5 M (the contour list full, 256 nodes).  No heap, no floating
 * point.
 */
#ifndef FIELDLOC_SKELETON_H
#define FIELDLOC_SKELETON_H

#include <stdbool.h>
#include <stdint.h>

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Capacities FL_SKEL_MAX_WIDTH, _HEIGHT, _CONTOUR, _NODES, _CROSSINGS,
 * _POINTS: config.h.  What does not fit is counted (see fl_skel_t). */

/* The input: one byte per pixel, nonzero = white (a painted line pixel),
 * row y at data + y * stride.  1..FL_SKEL_MAX_WIDTH x 1..FL_SKEL_MAX_HEIGHT,
 * stride >= width. */
typedef struct {
    const uint8_t *data;
    int32_t width;
    int32_t height;
    int32_t stride;
} fl_skel_mask_t;

typedef struct {
    int32_t max_iterations; /* K3M iterations (each peels about one pixel
                               off every side), 1..255; default 32: lines
                               up to about 64 px thick thin completely */
    int32_t spur_px;        /* end branches of at most this many pixels
                               that end at a node are removed, 0..32;
                               default 3 */
    int32_t merge_px;       /* node pixels this close (Chebyshev, chained)
                               are one crossing, 1..32; default 4 */
    int32_t arm_px;         /* an arm must reach this far beyond the node
                               box, 2..32; default 6 (for masks whose
                               lines are a few pixels wide; about twice
                               the widest line) */
    int32_t n_points;       /* skeleton pixels sampled per run,
                               0..FL_SKEL_MAX_POINTS; default all */
    int32_t report_l;       /* 1: report two-arm corners (FL_SKEL_L) too;
                               0 (default): X and T only */
} fl_skel_params_t;

typedef enum {
    FL_SKEL_NONE = 0,
    FL_SKEL_L = 2,          /* two arms at an angle (a corner) */
    FL_SKEL_T = 3,          /* three arms */
    FL_SKEL_X = 4           /* four arms */
} fl_skel_kind_t;

typedef struct {
    uint8_t kind;           /* fl_skel_kind_t; its value is the arm count */
    uint8_t n_nodes;        /* node pixels merged (saturating) */
    uint8_t confidence;     /* Q0.8: how straight the arms continue
                               through the crossing (X: both opposite
                               pairs, T: the straightest pair, L: how far
                               from straight the corner is) */
    int32_t x_q4, y_q4;     /* position, mask coordinates, Q4 px */
    fl_angle_t arm[4];      /* arm directions in the mask, fl_atan2(dy,
                               dx) with y down (so clockwise on screen),
                               ascending; the first `kind` are set, the
                               rest 0 */
} fl_skel_crossing_t;

typedef struct {
    int16_t x, y;           /* a skeleton pixel, mask coordinates */
} fl_skel_point_t;

typedef struct {
    fl_skel_params_t params;
    int32_t width, height;  /* of the last run's mask */
    /* ---- results of the last fl_skel_run ---- */
    int32_t n_crossings;
    fl_skel_crossing_t crossing[FL_SKEL_MAX_CROSSINGS];
    int32_t n_points;
    fl_skel_point_t point[FL_SKEL_MAX_POINTS];
    /* statistics */
    int32_t n_white;        /* white pixels of the mask, pinholes filled */
    int32_t filled;         /* pinholes filled (background pixels with 3
                               or 4 white edge neighbours) */
    int32_t n_skeleton;     /* skeleton pixels after spur removal */
    int32_t n_nodes;        /* node pixels (degree >= 3) kept */
    int32_t iterations;     /* K3M iterations run */
    int32_t spurs;          /* end branches removed */
    /* counters of what did not fit or was not reported */
    int32_t contour_dropped;   /* pixels the contour list had no room for
                                  (they are never thinned) */
    int32_t iter_capped;       /* 1: thinning stopped at max_iterations
                                  before it converged */
    int32_t nodes_dropped;     /* node pixels beyond FL_SKEL_MAX_NODES */
    int32_t crossings_dropped; /* crossings beyond FL_SKEL_MAX_CROSSINGS */
    int32_t rejected;          /* clusters with more than 4 arms, or 2
                                  straight, or 2 with report_l off */
    /* private: working image, (width + 2) x (height + 2) with a border of
     * background, one flag byte per pixel, and each pixel's neighbourhood
     * weight kept up to date as pixels turn white or are deleted; the
     * contour list (indices into px); node pixels and their union-find
     * parents */
    uint32_t magic;         /* set by a successful init */
    int32_t pstride;
    int32_t n_contour;
    uint8_t px[(FL_SKEL_MAX_WIDTH + 2) * (FL_SKEL_MAX_HEIGHT + 2)];
    uint8_t wt[(FL_SKEL_MAX_WIDTH + 2) * (FL_SKEL_MAX_HEIGHT + 2)];
    uint32_t contour[FL_SKEL_MAX_CONTOUR];
    uint32_t node[FL_SKEL_MAX_NODES];
    uint16_t parent[FL_SKEL_MAX_NODES];
} fl_skel_t;

/* max_iterations 32, spur_px 3, merge_px 4, arm_px 6, n_points
 * FL_SKEL_MAX_POINTS, report_l 0. */
void fl_skel_params_default(fl_skel_params_t *p);

/* Validate (FL_ERR_RANGE: a parameter outside its range) and clear.
 * FL_ERR_NULL.  FL_ERR_CONFIG (common.h: the caller's config.h differs
 * from the library's): nothing written. */
fl_status_t fl_skel_init_cfg(fl_skel_t *s, const fl_skel_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_skel_init(fl_skel_t *s, const fl_skel_params_t *p)
{
    return fl_skel_init_cfg(s, p, FL_CONFIG_FINGERPRINT);
}

/* Thin the mask, find the crossings, sample n_points skeleton pixels
 * (a deterministic function of the mask, the params and seed, e.g. a frame
 * counter).  FL_ERR_NULL (s, mask or mask->data), FL_ERR_SIZE (width or
 * height below 1 or above the caps), FL_ERR_STRIDE (stride < width),
 * FL_ERR_STATE (s not initialized): results empty (when s is usable). */
fl_status_t fl_skel_run(fl_skel_t *s, const fl_skel_mask_t *mask, uint32_t seed);

/* 1 when (x, y) is a pixel of the last run's skeleton, else 0 (outside
 * the mask, NULL). */
int fl_skel_pixel(const fl_skel_t *s, int32_t x, int32_t y);

/* Degree of a pixel from its neighbourhood weight w (bit 0 N, 1 NE, 2 E,
 * 3 SE, 4 S, 5 SW, 6 W, 7 NW set when that neighbour is white): the
 * number of circular runs of white neighbours, 0..4 (0 for none and for
 * all eight). */
int fl_skel_degree(uint8_t w);

/* K3M's lookup arrays as one byte per weight w: bit 0 set when w is in
 * A0, bits 1..5 in A1..A5, bit 6 in A1pix, bit 7 in the last pass's
 * (skeleton.c; for the tests). */
int fl_skel_k3m_table(uint8_t w);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_SKELETON_H */
