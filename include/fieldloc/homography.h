/*
 * fieldloc/homography.h - the plane-to-plane map between an image and the
 * field (seed 003, section 3.1: an observer camera beside the field maps
 * its perspective view to a top view), fitted in fixed point from point
 * correspondences and applied both ways.
 *
 * Fit: the normalised direct linear transform (Hartley & Zisserman,
 * "Multiple View Geometry", 2nd ed., sections 4.1 and 4.4).  Each point set
 * is moved to its centroid and scaled by a power of two so that its mean
 * distance from the centroid lies in [1, 2), i.e. within a factor sqrt(2)
 * of Hartley's sqrt(2); a power of two keeps the normalisation and its
 * inverse exact.  With h33 = 1 each pair gives two linear equations in the
 * other eight entries: four pairs give an 8 x 8 system solved exactly,
 * more pairs the least-squares solution of the normal equations (8 x 8).
 * Fixing h33 = 1 is safe after the normalisation: h33 is the homogeneous
 * scale w at the image centroid, w is affine in the pixel, and w has one
 * sign at every point in front of the camera, so w(centroid), a mean of
 * the points' w, is bounded away from zero by the nearest-to-farthest
 * depth ratio of the points (about 10 for a coach beside the field), not
 * by the pixel units.  The 8 x 8 solve (Gaussian elimination with partial
 * pivoting) runs on integer mantissas with a power-of-two exponent per
 * number (30-bit mantissas, no floating point); the result is kept as nine
 * int32 entries with one shared scale.
 *
 * Units: pixels in Q4 (1/16 px, as fl_obs_t's u_q4 / v_q4 and camera.h),
 * field points in mm (field frame of field.h).  Memory: the caller's
 * fl_homog_t (80 bytes); no heap.  Cost: O(n) to build the system and a
 * fixed 8 x 8 elimination; each mapping is a few 64-bit products and one
 * division.
 */
#ifndef FIELDLOC_HOMOGRAPHY_H
#define FIELDLOC_HOMOGRAPHY_H

#include "fieldloc/common.h"
#include "fieldloc/field.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    FL_HOMOG_OK = 0,
    FL_HOMOG_ERR_NULL = -1,     /* a required pointer was NULL */
    FL_HOMOG_TOO_FEW = -2,      /* fewer than FL_HOMOG_MIN_POINTS pairs */
    FL_HOMOG_DEGENERATE = -3,   /* duplicate points, three of four collinear,
                                   all collinear, a singular system, or
                                   fitted points on both sides of the
                                   horizon */
    FL_HOMOG_RANGE = -4,        /* more than FL_HOMOG_MAX_POINTS pairs, a
                                   coordinate beyond FL_HOMOG_MAX_Q4 /
                                   FL_HOMOG_MAX_MM, or a mapped point beyond
                                   them */
    FL_HOMOG_HORIZON = -5,      /* the point maps to or beyond the horizon
                                   line (w <= 0): no point on the other plane */
    FL_HOMOG_NOT_FITTED = -6    /* the fl_homog_t holds no valid fit */
} fl_homog_status_t;

#define FL_HOMOG_MIN_POINTS 4
/* |u_q4|, |v_q4| of an accepted pixel (65536 px) and |x_mm|, |y_mm| of an
 * accepted field point (about 1 km): the 64-bit intermediates stay in range. */
#define FL_HOMOG_MAX_Q4 (1L << 20)
#define FL_HOMOG_MAX_MM (1L << 20)

/* One correspondence: an image pixel and the field point it shows. */
typedef struct {
    int32_t u_q4, v_q4;
    int32_t x_mm, y_mm;
} fl_homog_pair_t;

/* A fitted homography.  Private fields: the image and field centroids,
 * the normalising shifts (normalised = (p - centroid) / 2^shift), and the
 * normalised maps image -> field (h) and field -> image (hinv), row major,
 * largest |entry| in [2^29, 2^30], w at the centroid positive. */
typedef struct {
    int32_t valid;
    int32_t img_c_q4[2];
    int32_t fld_c_mm[2];
    int32_t img_shift, fld_shift;
    int32_t h[9];
    int32_t hinv[9];
} fl_homog_t;

/* Reprojection error of a fit over its pairs: image -> field against the
 * field point (mm, Q4 = 1/16 mm) and field -> image against the pixel
 * (Q4 px).  n_used counts the pairs that mapped (a pair that does not map
 * is counted in n_failed and left out of the error). */
typedef struct {
    uint32_t rms_mm_q4, max_mm_q4;
    uint32_t rms_px_q4, max_px_q4;
    uint32_t n_used, n_failed;
} fl_homog_error_t;

/* Fit from n pairs (FL_HOMOG_MIN_POINTS..FL_HOMOG_MAX_POINTS).  On any
 * status but FL_HOMOG_OK, *h is left not fitted (every mapping refuses it
 * with FL_HOMOG_NOT_FITTED). */
fl_homog_status_t fl_homog_fit(fl_homog_t *h, const fl_homog_pair_t *pairs, size_t n);

/* Image pixel (Q4) -> field point (mm, rounded). */
fl_homog_status_t fl_homog_image_to_field(const fl_homog_t *h, int32_t u_q4, int32_t v_q4,
                                          fl_point_t *field);
/* The same in 1/16 mm (for error measures). */
fl_homog_status_t fl_homog_image_to_field_q4(const fl_homog_t *h, int32_t u_q4, int32_t v_q4,
                                             int32_t *x_mm_q4, int32_t *y_mm_q4);
/* Field point (mm) -> image pixel (Q4); FL_HOMOG_HORIZON for a point behind
 * the camera's horizon line on the field. */
fl_homog_status_t fl_homog_field_to_image(const fl_homog_t *h, fl_point_t field,
                                          int32_t *u_q4, int32_t *v_q4);

/* Reprojection error of h over n pairs (RMS and max, both directions). */
fl_homog_status_t fl_homog_error(const fl_homog_t *h, const fl_homog_pair_t *pairs, size_t n,
                                 fl_homog_error_t *err);

/* The 17 field points seed 003 names, from a field model: four field
 * corners, eight penalty-area corners, two penalty marks, the two
 * halfway-line / touchline T's and the centre mark (a field without a
 * penalty area or penalty marks gives fewer).  Writes at most cap points
 * and returns how many it wrote (0 for a NULL argument). */
#define FL_HOMOG_FIELD_POINTS 17
typedef struct {
    const char *name;   /* e.g. "corner_pos_left": x > 0 end, y > 0 side */
    int32_t x_mm, y_mm;
} fl_homog_field_point_t;
size_t fl_homog_field_points(const fl_field_t *f, fl_homog_field_point_t *out, size_t cap);

/* Name of a status (static string, never NULL). */
const char *fl_homog_status_str(fl_homog_status_t s);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_HOMOGRAPHY_H */
