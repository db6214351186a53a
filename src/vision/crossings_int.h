/*
 * src/vision/crossings_int.h - crossing stage internals shared by crossings.c
 * and the detectors crossings_{pair,marks,border,connect,close}.c; see crossings.h.
 *
 * Algorithm.
 *   pairs    for i < j over the segments: image angle test (|sin| of the
 *            angle between the directions), intersection X of the two
 *            infinite lines (exact 64-bit solve in Q4), X inside the image,
 *            X within reach of both segments (a long far line: also a
 *            painted gap of up to 6 steps, see cr_bridge_one),
 *            X's position t along each segment, the local directions there
 *            (chord turned by the bulge's slope); arms by extent (t and
 *            len - t against arm_q4), probes in the class map for all four;
 *            ground check from the directions of both lines at X through
 *            the camera; type by arm count; marks by the ground length of
 *            short bars; insertion with merging into a crossing within
 *            merge distance (union of arms).
 *   marks    clusters of points off long segments within the projected
 *            mark size (bucket search from lines.c), isolated out to 2.5
 *            mark sizes, a ring of 16 samples at 1.6 mark sizes that must
 *            be green, and (white-goal fields) inside that ring at most
 *            1 dark (OTHER or YELLOW) class-map cell in 16 (a white spot
 *            on a robot or a ball passes the sparse ring; bare carpet has
 *            no dark).
 *   border   per segment (not a circle chord) whose upper end runs up to
 *            the field border: walk the paint past the end, place the T
 *            half a (ground) line width before its stop, find the border
 *            beyond it and check it square to the segment on the ground
 *            (its pixels 3 steps either side projected), probe the
 *            continuation; arms from ground directions projected back.
 *   connect  per segment end where the paint stops: the ground normal
 *            to the nearest image-parallel segment within 1000 mm, a
 *            painted connector (class map or luma) gives an L at the end
 *            and a T at its foot (see fl_cr_connect).
 *   close    per segment end where the paint stops: a parallel line 1 px
 *            to 2 steps across it a box depth away on the ground (a far
 *            goal box's front line end and the goal line): an L at the end
 *            and a T at its foot (see fl_cr_close).
 *   circle   the centre mark and the halfway-line x circle X's of a found
 *            circle, projected back and checked white in the class map.
 *   objects  (before circle) crossings on a standing object or above the
 *            carpet removed; on white-goal fields also those with more
 *            than 1 in 10 dark class-map cells of the carpet within 3 line
 *            widths (a robot's body, a goal's foot).
 *
 * Invariant.  Every stored crossing has 2..4 arms (marks from blobs: 0,
 * until merged), no two stored crossings are closer than the merge
 * distance at the time of insertion, n <= FL_CROSSINGS_MAX.
 *
 * Memory: the caller's fl_crossings_t (about 54 B per crossing, ground
 * arms included).  Stack: a visited bitmap of FL_LINES_MAX_POINTS bits
 * (<= 512 B) and a FL_LINES_NEAR_MAX id list in the mark search (< 900 B
 * in all).
 * Cost: segments^2 / 2 cheap pair tests; per surviving pair 4 probes of at
 * most 64 samples and 3-5 camera projections; per segment at most one
 * border test (3 walks of at most 64 samples, 4-8 projections); marks: one
 * bucket search per cluster, 16 map reads per candidate and at most
 * 17 x 17 more per candidate that passed its ring.
 *
 * Scaling and overflow.  Pixel positions Q4 (|u|, |v| < 2^17 for images up
 * to 4096 px).  Segment direction vectors in Q4 (< 2^17 each); the
 * intersection denominator (cross product) < 2^35, numerator < 2^36, the
 * product with a direction < 2^53: int64.  Unit directions Q15 from the
 * segment angle; projections (Q4 x Q15) < 2^33 in int64, shifted back with
 * rounding.  Angles are binary angles (wrap-around free).  Confidence
 * factors Q8 (256 = 1), multiplied in int32 (< 2^24).  Border T's: ground
 * offsets of at most 300 mm (fl_mul_q15), their pixel differences checked
 * below 2^20 Q4 before fl_hypot / fl_atan2; scale products (Q4 px x mm) in
 * int64; walks and probes capped at 64 px.
 */
#ifndef FL_VISION_CROSSINGS_INT_H
#define FL_VISION_CROSSINGS_INT_H

#include "fieldloc/crossings.h"

#define CR_KAPPA_Q4 (12 * 16) /* probe distance for ground directions */
#define CR_SAME_ARM 4551      /* 25 deg: two arms within this are one */
#define CR_MARK_CLUSTERS_MAX 256 /* mark candidates looked at per frame */
#define CR_MARK_CLUSTERS_CLUTTER 64 /* ... once the line points overflowed */
#define CR_LUMA_PROBES 128    /* probes per frame that may read the luma */
#define CR_APART_MM 500      /* crossings farther apart on the ground never merge */
#define CR_FAR_MM 3000u       /* the ground check's tolerance grows beyond */
#define CR_FAR_TOL_MDEG 15000u /* ... by this much at twice that range */

/* Ground length (mm) over which image scales are measured along a ground
 * direction. */
#define CR_SCALE_MM 300
/* Parallel in the image: |sin| of the angle between the two lines at most
 * sin 12 deg (Q15). */
#define CR_CONN_PAR_SIN 6813

static inline int32_t cr_abs(int32_t a) { return a < 0 ? -a : a; }
static inline int64_t cr_abs64(int64_t a) { return a < 0 ? -a : a; }

/* |a - b| folded to [0, 180 deg] as a non-negative int32 (0..32768). */
static inline int32_t cr_adiff(fl_angle_t a, fl_angle_t b)
{
    return cr_abs(fl_angle_sub(a, b));
}

/* Class (FL_CLASS_*) of the class-map cell nearest pixel (u, v) (Q4); other
 * outside the map. */
static inline int32_t cr_class_px(const fl_scan_t *s, int32_t u_q4, int32_t v_q4)
{
    int32_t i, j;
    uint64_t w;
    if (u_q4 < 0 || v_q4 < 0)
        return FL_CLASS_OTHER;
    i = (u_q4 / 16 + s->params.col_step / 2) / s->params.col_step;
    j = (v_q4 / 16 + s->params.row_step / 2) / s->params.row_step;
    if (i >= s->cols || j >= s->rows)
        return FL_CLASS_OTHER;
    w = s->map[j][i >> 5];
    return (int32_t)((w >> (62 - 2 * (i & 31))) & 3u);
}

/* Line width (Q4 px) at row v for the thresholds; step when unknown. */
static inline int32_t cr_width_q4(const fl_lines_t *l, int32_t v_q4)
{
    int32_t w = fl_lines_width_q4(l, v_q4 / 16, false);
    int32_t wv = fl_lines_width_q4(l, v_q4 / 16, true);
    if (wv > w)
        w = wv;
    return w;
}

/* Does a segment end within a line step of the image edge? */
static inline bool cr_cut(const fl_lines_t *l, const fl_segment_t *s)
{
    int32_t e = 16 * l->step_px, um = 16 * (l->width - 1) - e, vm = 16 * (l->height - 1) - e;
    return s->u0_q4 < e || s->v0_q4 < e || s->u0_q4 > um || s->v0_q4 > vm || s->u1_q4 < e ||
           s->v1_q4 < e || s->u1_q4 > um || s->v1_q4 > vm;
}


/* An image ray: from (xu, xv) (Q4) along the unit vector (cu, cv) (Q15).
 * (Helpers take it by pointer: at most six arguments, so no frame needs
 * stack-passed arguments.) */
typedef struct {
    int32_t xu, xv, cu, cv;
    int32_t r0, len;          /* probe: from r0 to r0 + len along it, Q4 */
    fl_point_t gx;            /* ground point of the start */
    int32_t white;            /* out: probe white ratio */
    fl_angle_t dir;           /* out: ground direction */
} cr_ray_t;

/* Crossing plus its ground arms, while building. */
typedef struct {
    fl_crossing_t x;
    fl_angle_t garm[4];
    bool ground;
} cr_item_t;

/* What every pair test of a frame shares. */
typedef struct {
    fl_crossings_t *c;
    const fl_lines_t *l;
    const fl_scan_t *scan;
    const fl_camera_t *cam;
    const fl_field_t *field;
    int32_t sin_min_q15, sin_tol_q15;
} cr_ctx_t;

/* Shared helpers (crossings.c) and the detectors (crossings_*.c); each is
 * described at its definition. */
bool fl_cr_ground_dir(const fl_camera_t *cam, cr_ray_t *r);
void fl_cr_orient(fl_crossing_t *x, const fl_angle_t *garm, bool ground);
bool fl_cr_type(fl_crossing_t *x);
/* fl_cr_dark's count: carpet (in) limits it to cells below the field
 * border; n samples, dark of them OTHER or YELLOW (out).  A struct keeps
 * the call at six arguments: a seventh is passed on the stack, a frame
 * `make stack` cannot bound statically. */
typedef struct {
    bool carpet;
    int32_t n, dark;
} cr_dark_t;
void fl_cr_dark(const fl_scan_t *s, int32_t cu, int32_t cv, int32_t ru, int32_t rv,
                cr_dark_t *d);
void fl_cr_add(fl_crossings_t *c, fl_angle_t (*garm_store)[4],
                   const cr_item_t *it, int32_t merge_q4,
                   const fl_lines_t *l);
void fl_cr_probe(fl_crossings_t *c, const fl_lines_t *l, const fl_scan_t *scan,
                     cr_ray_t *r);
fl_angle_t fl_cr_local_angle(const fl_segment_t *s, int32_t t);
int32_t fl_cr_ground_len(const fl_camera_t *cam, const fl_segment_t *s);
bool fl_cr_hidden(const fl_scan_t *s, int32_t u0, int32_t v0, int32_t u1, int32_t v1);
bool fl_cr_end_ray(const cr_ctx_t *ctx, fl_angle_t ain, int32_t w, bool beside, cr_ray_t *r);
int32_t fl_cr_image_dir(const fl_camera_t *cam, cr_ray_t *r);
void fl_cr_pair(const cr_ctx_t *ctx, int32_t ia, int32_t ib);
void fl_cr_marks(fl_crossings_t *c, fl_angle_t (*garm_store)[4],
                     const fl_lines_t *l, const fl_scan_t *scan,
                     const fl_camera_t *cam, const fl_field_t *field);
void fl_cr_border_t(const cr_ctx_t *ctx, int32_t is);
void fl_cr_connect(const cr_ctx_t *ctx, int32_t is, bool end1);
void fl_cr_close(const cr_ctx_t *ctx, int32_t is, bool end1);

#endif
