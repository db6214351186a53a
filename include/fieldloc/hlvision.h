/*
 * fieldloc/hlvision.h - seed 002's vision path (its section IV) for the
 * humanoid-league field "hl3x2": colour classes from YCbCr boxes, goal
 * posts and striped landmark poles found column by column, and the mask of
 * white pixels surrounded by green, thinned by the skeleton stage
 * (skeleton.h) into line crossings (X, T) and a sample of white points.
 * Everything is projected to the ground with the frame's camera (camera.h,
 * inverse perspective) into the same fl_obs_list_t as every other path.
 *
 *     static fl_hlv_t hv;      fl_hlv_params_default(&p, field);
 *                              fl_hlv_init(&hv, &p);
 *     per frame:  fl_camera_init(&cam, model, &pose);
 *                 n = fl_hlv_frame(&hv, &img, &cam, &obs);
 *
 * Colour classes.  Seed 002 segments with "pre-calibrated ranges for every
 * color" in YCbCr: one box per class.  A box is exact as three per-channel
 * bit tables, class bits = ytab[Y] & cbtab[Cb] & crtab[Cr] (768 bytes, the
 * classic CMVision layout).  Pixels are read as Y, Cb, Cr by image.c's
 * integer BT.601 conversion for every format of image.h.
 *
 * One class grid.  The image is classified once, every mask_step_u
 * columns and mask_step_v rows (grid cell (i, j) is image pixel
 * (i * su + su / 2, j * sv + sv / 2), clamped to the image), row by row.
 *
 * Posts and poles (seed 002 IV.B.1, IV.B.2).  Every grid column is read
 * bottom-up as runs of one class (gaps of up to gap_px
 * unclassified pixels bridged).  The lowest yellow or sky-blue run with a
 * green run right below it (within green_gap_px) starts an object: if the
 * run above it is the other colour and the one above that the first colour
 * again (each at least min_band_px), the column is a pole, YBY or BYB;
 * else a run of at least min_post_px is a post.  Adjoining scanned columns
 * (at most one empty column between) of the same kind, or post columns of
 * a pole's bottom colour beside a pole, whose runs overlap (within
 * foot_tol_px) form one object (at least min_cols columns); its foot is
 * the lowest foot of its columns, at the middle of the columns within a
 * row step of it (foot_u0..foot_u1).  An
 * object whose width does not fit its diameter at the range of its foot
 * (from half to three times, and a column step: src/vision/hlv.c) is dropped.
 * An object touching the image's left or right edge (its first or last
 * grid column) whose foot the edge cuts (the edge column's foot within
 * half the visible width, and two row steps, of the lowest foot) is
 * clipped: it passes every test but the lower width bound, its centre is
 * placed half the width its range gives inside from its inner edge (its
 * visible middle is off by up to half its width), and it is reported with
 * lower confidence (posts 160, poles 180; whole ones 200, 230); a clipped
 * post with its other colour right above its top, between its columns and
 * the edge, is a pole's bottom band left alone in the grid columns by the
 * pole's lean, and dropped.  Other
 * objects touching an edge (only the upper part of a leaning near post
 * reaches it) and objects touching both are dropped.  Two posts
 * of one colour are a goal (the left one in the image is FL_SIDE_LEFT: the
 * left post facing the goal) when their feet on the ground are half to
 * one and a half goal_width_mm apart (else both FL_SIDE_UNKNOWN); one post takes its side from a crossbar of
 * its colour beside its top (bar to the right: the left post; probed 6 to
 * 10 post widths away, a clipped post's width from its range), else
 * FL_SIDE_UNKNOWN.
 *
 * Observations, in this order: posts (FL_LM_POST, color, side, range and
 * bearing of the post's centre from its foot and post_diameter_mm), poles
 * (FL_LM_BEACON, color = top band, color2 = bottom band: YBY is YELLOW /
 * YELLOW, BYB is SKYBLUE / SKYBLUE; range from the foot and
 * pole_diameter_mm), then crossings (FL_LM_X, FL_LM_T, orientation from
 * the arms by obs.h's conventions when the skeleton gives them), and the
 * white points (fl_obs_list_push_point).  Image positions in u_q4 / v_q4.
 *
 * Mask (seed 002 IV.B.3).  The grid below the horizon.  A white sample is
 * in the mask when green lies within surround_px samples on both sides
 * along its row, or on both sides along its column.  The skeleton stage
 * (skeleton.h: K3M thinning, node degrees, crossings merged) gives X and
 * T crossings and a sample of skeleton pixels in mask coordinates; each
 * is mapped to the image and through the camera to the ground.  A
 * crossing's orientation: its arms are mapped to the ground (a point
 * 16 mask px along each), X: the first arm, T: the arm without an opposite
 * (the one farthest from 180 deg to both others), as obs.h states.
 *
 * Work per frame (bounded): (W / su) * (H / sv) pixel reads for the grid,
 * one pass over the columns that hold yellow or sky-blue, at most
 * 2 * surround_px reads per white cell for the mask,
 * the skeleton stage's own bound on that mask, and at most FL_HLV_MAX_RUNS
 * runs per column and FL_HLV_MAX_OBJECTS objects.  No heap, no floats.
 */
#ifndef FIELDLOC_HLVISION_H
#define FIELDLOC_HLVISION_H

#include "fieldloc/camera.h"
#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/field.h"
#include "fieldloc/image.h"
#include "fieldloc/obs.h"
#include "fieldloc/skeleton.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Class bits (a pixel may have several when boxes overlap). */
#define FL_HLV_YELLOW 1u
#define FL_HLV_BLUE 2u
#define FL_HLV_GREEN 4u
#define FL_HLV_WHITE 8u

/* Box index in fl_hlv_params_t.box. */
enum { FL_HLV_BOX_YELLOW = 0, FL_HLV_BOX_BLUE = 1, FL_HLV_BOX_GREEN = 2,
       FL_HLV_BOX_WHITE = 3, FL_HLV_N_BOXES = 4 };

/* An inclusive YCbCr box; min > max on a channel: the class is empty. */
typedef struct {
    uint8_t y_min, y_max, cb_min, cb_max, cr_min, cr_max;
} fl_hlv_box_t;

typedef struct {
    fl_hlv_box_t box[FL_HLV_N_BOXES];
    int32_t gap_px;         /* unclassified pixels bridged in a run, 0..32 */
    int32_t green_gap_px;   /* foot: green within this below, 0..32 */
    int32_t min_green_px;   /* the green run below a foot, 1..64 */
    int32_t min_post_px;    /* a post's run upwards, 2..480 */
    int32_t min_band_px;    /* each band of a pole, 1..160 */
    int32_t min_cols;       /* scanned columns per object, 1..64 */
    int32_t foot_tol_px;    /* feet of adjoining columns, 0..480 */
    int32_t mask_step_u;    /* image columns per grid (mask) column, 1..16;
                               0 (default): width / 160 rounded up */
    int32_t mask_step_v;    /* image rows per grid (mask) row, 1..16;
                               0 (default): height / 240 rounded up */
    int32_t surround_px;    /* green within this many mask px, 1..32 */
    int32_t post_diameter_mm;  /* 10..1000 */
    int32_t pole_diameter_mm;  /* 10..1000 */
    int32_t goal_width_mm;     /* 100..5000: two posts of one colour are a
                                  goal (sides from their order) only when
                                  their feet are 1/2..3/2 of this apart */
    int32_t max_range_mm;   /* farther observations are dropped, 100..FL_OBS_MAX_RANGE_MM */
    int32_t crossings;      /* 1: mask and skeleton stage; 0: posts and poles only */
    fl_skel_params_t skel;  /* the skeleton stage's (skeleton.h) */
} fl_hlv_params_t;

/* A post or pole in the image. */
typedef enum {
    FL_HLV_POST_YELLOW = 1, FL_HLV_POST_BLUE = 2, FL_HLV_POLE_YBY = 3, FL_HLV_POLE_BYB = 4
} fl_hlv_kind_t;

typedef struct {
    fl_hlv_kind_t kind;
    int32_t u0, u1;          /* first and last grid column, image px */
    int32_t foot_v;          /* lowest foot (bottom of the coloured run) */
    int32_t top_v;           /* highest top of the object's runs */
    int32_t band_v[2];       /* poles: the two band boundaries (median
                                column's, lower then upper); posts: -1 */
    int32_t foot_u0, foot_u1; /* the columns whose feet are within a row
                                step of the lowest: the foot lies between */
    fl_side_t side;          /* posts */
    int32_t clip;            /* -1: its foot cut by the image's left edge
                                (it has the first grid column), +1: by
                                its right edge (the last), 0: whole */
    int32_t edge_foot_v[2];  /* the feet of its first and last columns */
    uint16_t cols;           /* grid columns */
} fl_hlv_object_t;

typedef struct {
    fl_hlv_params_t params;
    uint8_t ytab[256], cbtab[256], crtab[256];
    /* the grid: class bits (every row), and the mask (0/1) of the
     * skeleton stage (rows above the horizon 0) */
    int32_t step_u, step_v;   /* the grid steps of the last frame */
    int32_t mask_w, mask_h;
    uint8_t cls[FL_SKEL_MAX_WIDTH * FL_SKEL_MAX_HEIGHT];
    uint8_t mask[FL_SKEL_MAX_WIDTH * FL_SKEL_MAX_HEIGHT];
    uint8_t colbits[FL_SKEL_MAX_WIDTH]; /* per grid column: OR of its classes */
    uint8_t up[FL_SKEL_MAX_WIDTH];      /* per grid column: cells since green */
    fl_skel_t skel;                     /* the skeleton of the mask */
    fl_hlv_object_t objects[FL_HLV_MAX_OBJECTS];
    uint16_t n_objects;
    /* counters (summed over frames) */
    uint32_t frames;
    uint32_t runs_dropped;      /* runs beyond FL_HLV_MAX_RUNS in a column */
    uint32_t objects_dropped;   /* objects beyond FL_HLV_MAX_OBJECTS */
    uint32_t objects_rejected;  /* objects too wide or narrow for their range,
                                   clipped posts under a pole's band */
    uint32_t obs_dropped;       /* observations beyond FL_OBS_MAX */
    uint32_t points_dropped;    /* white points beyond FL_OBS_MAX_POINTS */
    fl_status_t status;         /* of the last frame (FL_OK or why empty) */
} fl_hlv_t;

/* Defaults (boxes measured on rendered hl3x2 frames, see src/vision/
 * hlv.c); post and pole diameters from field when it is not NULL
 * (post_diameter_mm, beacon_diameter_mm) else 100 mm. */
void fl_hlv_params_default(fl_hlv_params_t *p, const fl_field_t *field);

/* FL_OK or FL_ERR_NULL / FL_ERR_RANGE (a parameter outside its range, a
 * box with a channel min above max is allowed: empty class). */
fl_status_t fl_hlv_params_check(const fl_hlv_params_t *p);

/* Validate, build the tables, clear.  FL_ERR_CONFIG: nothing written. */
fl_status_t fl_hlv_init_cfg(fl_hlv_t *s, const fl_hlv_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_hlv_init(fl_hlv_t *s, const fl_hlv_params_t *p)
{
    return fl_hlv_init_cfg(s, p, FL_CONFIG_FINGERPRINT);
}

/* Class bits of one YCbCr triple (the tables of an initialized state). */
static inline uint8_t fl_hlv_class(const fl_hlv_t *s, uint8_t y, uint8_t cb, uint8_t cr)
{
    return (uint8_t)(s->ytab[y] & s->cbtab[cb] & s->crtab[cr]);
}

/* One frame: fills out (cleared first) and returns out->n.  0 with
 * s->status set, nothing processed and out empty, on bad input:
 *   FL_ERR_NULL       s, img, cam or out NULL (out NULL: nothing written)
 *   FL_ERR_STATE      s not initialized by fl_hlv_init
 *   FL_ERR_SIZE, FL_ERR_STRIDE, FL_ERR_FORMAT   fl_image_validate, or a
 *                     mask larger than FL_SKEL_MAX_WIDTH x FL_SKEL_MAX_HEIGHT
 *   FL_ERR_CAMERA     a camera whose init failed
 *   FL_ERR_MISMATCH   image size other than the camera model's.
 * The stage results (objects, mask, skel) stay readable after the call. */
int32_t fl_hlv_frame(fl_hlv_t *s, const fl_image_t *img, const fl_camera_t *cam,
                     fl_obs_list_t *out);

/* Mask pixel (Q4) -> image pixel (Q4) of the last frame's grid steps. */
void fl_hlv_mask_to_image(const fl_hlv_t *s, int32_t mx_q4, int32_t my_q4, int32_t *u_q4,
                          int32_t *v_q4);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_HLVISION_H */
