/*
 * fieldloc/corners.h - seed 004's corner features (section 2,
 * "Perception"): corners of the white field lines found by a brightness-
 * gradient corner detector, kept when the colour says field line,
 * labelled open / closed / net-closed from the colours in a small window,
 * and paired into the features seed 004 localizes with: C (an open
 * corner near a closed corner: the convex outer and the concave inner
 * corner of an L of a thick line), T-field (two closed corners: the two
 * concave corners of a T) and T-net (a closed corner near a net-closed
 * corner: the box line meeting the goal line next to the net), together
 * with the nets (goal-coloured regions).  Pure image work plus the
 * ground projection of each feature; which map point a feature is stays
 * the localizer's question (seed 004 section 3.3: ambiguity).
 *
 * Detector.  E. Sojka, "A new and efficient algorithm for detecting the
 * corners in digital images", DAGM 2002 (seed 004's reference [9]): a
 * corner is where two straight brightness edges meet; the measure at a
 * candidate Q is the variance of the gradient direction over the
 * neighbours X of Q, each weighted by its gradient size |g(X)| and by how
 * likely X lies on one of the two edges that form a corner at Q, which
 * Sojka estimates from the distance between Q and the edge line through X
 * (the isoline through X, perpendicular to g(X)): a Gaussian of that
 * distance (sigma_D; MVTec's points_sojka default 0.75 px) times a
 * Gaussian of |X - Q| (sigma_W, a quarter to half of the window).  Here,
 * in integers, on one frame of up to FL_CORNERS_MAX_WIDTH x _HEIGHT:
 *  1. luma of every pixel (fl_image_ycbcr_at: any fl_image_t format),
 *     smoothed by the 3 x 3 binomial (1 2 1)^T (1 2 1) / 16 (seed 004
 *     fig. 1: without smoothing the detector fires on pixelated straight
 *     lines and on the carpet's noise; params.smooth 0 skips it);
 *  2. gradient by central differences of the smoothed luma (|g| up to
 *     361), its unit normal n = g / |g| and its doubled-angle unit vector
 *     (cos 2phi, sin 2phi) = ((gx^2 - gy^2), 2 gx gy) / |g|^2, both Q7;
 *  3. every pixel with |g| >= min_grad is a candidate Q (Sojka also
 *     evaluates only edge pixels); over the (2 window_r + 1)^2 window
 *     (default 7 x 7) each neighbour X with |g| >= min_grad gets weight
 *        w = |g(X)| * G_D(|n(X) . (X - Q)|) * G_W(|X - Q|^2) / 256
 *     with G_D a table in quarter pixels (sigma_D 0.75 px) and G_W a table
 *     of the squared distance (sigma_W 2 px), both scaled to 256;
 *  4. the variance of the direction is the circular variance of the
 *     doubled angles V = 1 - |sum w (cos 2phi, sin 2phi)| / sum w (Q8:
 *     0 straight, 256 for two equally strong edges at 90 degrees; for two
 *     equal edges at an angle a, V = 1 - |cos a|); the apparentness is
 *     A = sum w (Sojka: the number of relevant points and their
 *     gradients); a corner needs V >= min_var and A >= min_app, and its
 *     response is V * A / 256.
 * Simplified from Sojka, with the reasons (bounded integer work on a
 * 208 x 160 frame, thin lines):
 *  - doubled angles (orientation, not direction): the two sides of a
 *    white line one or two pixels wide have opposite gradients at 1-2 px
 *    from each other, and Sojka's direction variance would call every
 *    thin straight line a corner; doubling maps both sides to one
 *    orientation, so a straight thin line has V ~ 0 while two edges at a
 *    right angle keep V = 1.  The price: a corner's two edges only count
 *    as different when they are not parallel (a line's end cap still is a
 *    corner);
 *  - no per-candidate search for the corner's brightness (Sojka's
 *    probability also asks that X be on the brightness level of the
 *    corner) and no sub-pixel refinement: the isoline distance alone
 *    selects the two edges; position = the response's local maximum;
 *  - the weights are tables, not exp(); the circular variance needs one
 *    64-bit integer square root per candidate, no angle at all.
 * Thresholds (defaults, rendered AIBO frames: carpet luma ~ 100, lines ~
 * 200 over 1-3 px, noise sigma 1.5 levels): min_grad 12 (a smoothed line
 * edge gives 40..120, the smoothed noise < 6); min_var 24 (two equal edges
 * at 25 degrees: the AIBO camera, 150..250 mm above the carpet, sees the
 * field's right angles at 20..160 degrees; 40 lost the obtuse outer
 * corners of near L's, host test corners.rendered: recall 0.19 at 40,
 * 0.25 at 24); min_app 4096 (about 4 pixels of gradient 16 on the
 * candidate's isolines).  With a camera, corners without a ground point
 * within max_range_mm are dropped (room clutter above the horizon).
 *
 * Non-maximum suppression: a candidate is a corner when its response is
 * the largest in the (2 nms_r + 1)^2 square around it (ties: the first in
 * raster order).  Default nms_r 1: on a thin line the outer and inner
 * corner of an L are 2-3 px apart and both are needed (the pair is the
 * feature).  A weak second maximum beside a strong corner can survive
 * it; the pairing order (strongest pairs first) leaves it unpaired.
 *
 * Colour filter and labels, in the (2 label_r + 1)^2 window around the
 * corner pixel (default 5 x 5; with a camera, radius label_mm = 40 mm
 * at the corner's range when that is more: 9 x 9 within about 2.2 m on
 * the AIBO): white and carpet counted by the caller's colour table
 * (color.h: FL_CLASS_WHITE and FL_CLASS_GREEN, the scanner's classes); a
 * corner with fewer than min_white white or min_green carpet
 * pixels does not come from a field line and is dropped (seed 004: "the
 * detected corners are filtered depending on whether they come from a
 * white line segment").  Then
 *   closed  white >= closed_white_pct % of the window ("many white");
 *   open    otherwise (carpet the larger part, white above min_white);
 *   net-closed  closed, and at least min_net net pixels (the goals'
 *           yellow or sky-blue by beacon.h's boxes, fl_beacon_pixel_color)
 *           among about 20 x 10 samples of the rows above the corner within
 *           net_r pixels, or with a camera net_mm at the corner's range
 *           (4..64 px): the net stands behind the goal line, so above the
 *           corner in the image, and at the AIBO's ranges it is 20..40 px
 *           beside the T; seed 004's "small window" could not see it.
 *           With a camera the net must also stand at the corner: the
 *           lowest net pixel found (the foot of the goal's wall or post)
 *           has its ground point within net_mm of the corner's; else the
 *           samples count 0.  Without that test the far goal seen above
 *           a T-field or an X of the centre circle made 23 of eval-detect's
 *           117 detections T-nets.
 * For a line t px wide, the 5 x 5 window of the outer corner of an L
 * holds about 2 * 2t white pixels and that of the inner corner 2 * 2t +
 * t^2 (+ the corner's own square): 40 % separates them for t >= 2 px; at
 * t = 1 px (lines beyond ~ 2.5 m) both are open and no C forms.
 *
 * Those absolute labels fail on the AIBO's views: its camera sees the
 * 25 mm lines 1..10 px wide (thin across the view, wide along it), so a
 * fixed window calls both corners of a thin L open and both of a thick
 * one closed.  label_mode 1 types a pair relative to itself (rel_pct
 * 60): the convex corner of an L has about half the white of its
 * concave partner (2 t r - t^2 against 2 t r + t^2 for a line t px wide
 * in a window of radius r), the two concave corners of a T about the
 * same; but a thin and a thick line also meet at a T seen at a slant,
 * and it typed about half the T-fields and the centre circle's X's as C.
 * The default, label_mode 3 (with a camera), types a pair by its shape
 * on the ground: 24 probes on a circle of 60 mm around the pair's
 * midpoint (and, when that shows at most 2, of 100 mm), projected into
 * the image; the white runs around it are the lines leaving the joint: a T-net when either corner saw the net at it
 * and at least 1 arm shows (the goal line along the net's foot is thin
 * or leaves the image); else 2 arms (not in line) a C, 3 or more a
 * T-field, 2 arms in line (150..210 degrees apart: two corners of one
 * straight line) or fewer than 2 no feature (corners_feat.c
 * cn_shape_arms: the numbers; eval-detect against label_mode 1:
 * precision 0.56 -> 0.80, recall 0.44 -> 0.43).
 * Without a camera label_mode 3 is label_mode 1.  label_mode 0 (or
 * rel_pct 0) gives seed 004's rule on the labels above; label_mode 2
 * types pairs by Sojka's convex / concave corner instead
 * (fl_corner_t.convex: the weighted gradient sum and the edge pixels'
 * centroid on the same side of Q: convex), which measured worse on the
 * rendered frames (docs/DESIGN.md 14c).
 *
 * Pairing: two corners closer than their pair distance (pair_px, or with
 * a camera pair_mm at the first corner's range when more, at most 64 px)
 * whose midpoint has at least min_mid_white white pixels in its 3 x 3
 * square (an L's joint, a T's stem end: two corners of different lines
 * have carpet between them) are paired greedily, the pair with the
 * strongest weaker response first (t_first: all T pairs before the C
 * pairs), each corner in one feature at most:
 *   rel_pct 0:  open + closed -> C, closed + closed -> T-field, closed +
 *               net-closed (or two net-closed) -> T-net;
 *   rel_pct > 0: C when one corner has less than rel_pct % of the other's
 *               white pixels (it is relabelled open, the other closed),
 *               else T-net when either saw the net (both relabelled
 *               net-closed / closed by their net samples), else T-field;
 *   label_mode 3 with a camera: C, T-field or T-net by the arms (above),
 *               relabelled as for rel_pct > 0.
 * Position: the midpoint of the two corners (Q4 px); with a camera, range
 * and bearing of that pixel's ground point (fl_camera_pixel_to_ground);
 * none (range 0) when it has no ground point.  Confidence Q0.8: the
 * smaller of the two corners' V, halved when the pair is more than half
 * its pair distance apart.
 *
 * Nets: not found again here.  fl_beacon_find (beacon.h) already finds
 * the AIBO goals' posts (sky-blue, and yellow with yellow_goals); the
 * caller passes its result and each goal colour with at least one post
 * of a known range becomes one net feature at the mean of its posts'
 * ground points (both posts: the mouth's centre; one: that post), image
 * position the mean of their feet, confidence the largest.  NULL: no
 * nets.
 *
 * Lifecycle: fl_corners_params_default, fl_corners_init (validates), then
 * fl_corners_run per frame; results in the state until the next run.
 *
 * Bounded work: luma, smoothing and gradient O(width x height) (one
 * integer square root and four divisions per edge pixel); the measure at
 * most FL_CORNERS_MAX_CAND candidates (more are counted, not evaluated) x
 * (2 window_r + 1)^2 neighbours; suppression (2 nms_r + 1)^2 per evaluated
 * candidate; per kept corner (at most FL_CORNERS_MAX_CORNERS, more
 * counted) one label window and at most 33 x 17 net samples (HSV
 * each) and one column of net pixels and two ground projections for
 * the net's foot; pairing at most corners / 2 rounds of O(corners^2)
 * pairs, each within its pair distance with one 3 x 3 colour probe and
 * (label_mode 3) 2 + 48 projections and 48 colour probes.  No heap, no
 * floating point.
 */
#ifndef FIELDLOC_CORNERS_H
#define FIELDLOC_CORNERS_H

#include <stdbool.h>
#include <stdint.h>

#include "fieldloc/beacon.h"
#include "fieldloc/camera.h"
#include "fieldloc/color.h"
#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/image.h"
#include "fieldloc/obs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Capacities FL_CORNERS_MAX_WIDTH, _HEIGHT, _CAND, _CORNERS, _FEATURES:
 * config.h.  What does not fit is counted (see fl_corners_t). */

typedef struct {
    int32_t smooth;           /* 1 (default): 3 x 3 binomial before the
                                 gradient; 0: the raw luma */
    int32_t min_grad;         /* edge pixel: |g| >= this, 1..255; 12 */
    int32_t window_r;         /* measure window radius, 1..4; 3 (7 x 7) */
    int32_t min_var;          /* doubled-angle circular variance, Q8,
                                 1..256; 24 */
    int32_t min_app;          /* apparentness sum w (|g| * 256 units),
                                 0..2^24; 4096 */
    int32_t nms_r;            /* suppression radius, 1..8; 1 */
    int32_t label_r;          /* label window radius, 1..4; 2 (5 x 5) */
    int32_t label_mm;         /* with a camera: radius this at the
                                 corner's range when more than label_r
                                 (at most 4), 0..500, 0 = off; 40 (1.6
                                 line widths: the window then sees the
                                 line's joint, not only its edge; host
                                 test corners.rendered: recall 0.25 off,
                                 0.28 at 25, 0.30 at 40 and 60) */
    int32_t min_white;        /* colour filter, pixels of the window; 2 */
    int32_t min_green;        /* 3 */
    int32_t closed_white_pct; /* closed when white >= this % of the
                                 window, 1..100; 40 */
    int32_t net_r;            /* net search above the corner, px, 0..64
                                 (0: no net-closed label); 30 */
    int32_t net_mm;           /* with a camera: the net search spans this
                                 at the corner's ground range instead
                                 (4..64 px), 0..2000, 0 = net_r always;
                                 450 (the box line is 200 mm from the post,
                                 the goal 600 mm wide); also the largest
                                 ground distance of the net's foot from
                                 the corner */
    int32_t min_net;          /* net samples for net-closed, 1..255; 4 */
    int32_t pair_px;          /* largest distance of a pair, 1..32; 10 */
    int32_t pair_mm;          /* with a camera: pair distance this at the
                                 corner's range when more than pair_px (up
                                 to 64 px), 0..500, 0 = off; 75 (3 line
                                 widths: an L seen at a slant puts its
                                 inner and outer corner 1.5..2.5 line
                                 widths apart) */
    int32_t min_mid_white;    /* a pair needs this many white pixels in
                                 the 3 x 3 square at its midpoint (an L's
                                 joint, a T's stem end), 0..9; 4 */
    int32_t label_mode;       /* how a pair is typed: 0 seed 004's labels;
                                 1 white counts relative to each other
                                 (rel_pct); 2 Sojka's convex / concave
                                 (fl_corner_t.convex); 3 the lines
                                 leaving the pair on the ground (with a
                                 camera; else as 1); default 3 */
    int32_t rel_pct;          /* 0: a pair's type from its labels; 1..100:
                                 from the two corners' white counts
                                 relative to each other (see file top);
                                 60 */
    int32_t t_first;          /* 1: T pairs are made before C pairs, each
                                 in the pairing order; 0 (default): one
                                 order over all */
    int32_t min_confidence;   /* features below are not reported, 0..255;
                                 0 */
    int32_t max_range_mm;     /* with a camera: corners without a ground
                                 point or farther than this are dropped
                                 (field lines lie on the ground; room
                                 clutter above the horizon does not),
                                 0..20000, 0 = off; 4500 */
    fl_beacon_params_t net;   /* the net colours: its skyblue and yellow
                                 boxes (fl_beacon_params_default) */
} fl_corners_params_t;

typedef enum {
    FL_CORNER_OPEN = 1,       /* convex: carpet around, a little white */
    FL_CORNER_CLOSED = 2,     /* concave: white around, some carpet */
    FL_CORNER_NET_CLOSED = 3  /* closed with the net's colour above */
} fl_corner_label_t;

typedef enum {
    FL_CFEAT_C = 1,           /* open + closed: an L */
    FL_CFEAT_T_FIELD = 2,     /* closed + closed: a T */
    FL_CFEAT_T_NET = 3,       /* closed + net-closed: a T at the net */
    FL_CFEAT_NET_YELLOW = 4,  /* the yellow goal (from beacon.h's posts) */
    FL_CFEAT_NET_SKYBLUE = 5  /* the sky-blue goal */
} fl_cfeat_type_t;

typedef struct {
    int16_t x, y;             /* pixel */
    uint8_t label;            /* fl_corner_label_t */
    uint8_t var;              /* V, Q8 (saturated at 255) */
    uint8_t n_white, n_green; /* label window counts */
    uint8_t n_area;           /* label window pixels inside the image */
    uint8_t n_net;            /* net samples */
    uint8_t paired;           /* 1: used by a feature */
    uint8_t pair_lim;         /* pair distance at its range, px */
    int8_t convex;            /* 1: the bright side is convex at the
                                 corner (Sojka's convex corner), -1
                                 concave, 0 undecided */
    uint32_t response;        /* V * A / 256 */
} fl_corner_t;

typedef struct {
    uint8_t type;             /* fl_cfeat_type_t */
    uint8_t confidence;       /* Q0.8 */
    int16_t a, b;             /* corner indices (-1 for nets) */
    int32_t u_q4, v_q4;       /* image position, Q4 px */
    bool has_ground;          /* range and bearing valid */
    fl_point_t ground;        /* robot frame, mm */
    int32_t range_mm;         /* 0 when no ground point */
    fl_angle_t bearing;
} fl_cfeat_t;

typedef struct {
    fl_corners_params_t params;
    int32_t width, height;    /* of the last run's image */
    /* ---- results of the last fl_corners_run ---- */
    int32_t n_corners;        /* kept (colour filter passed), labelled */
    fl_corner_t corner[FL_CORNERS_MAX_CORNERS];
    int32_t n_features;
    fl_cfeat_t feature[FL_CORNERS_MAX_FEATURES];
    /* statistics and counters of this frame */
    int32_t n_edge;           /* pixels with |g| >= min_grad */
    int32_t n_cand;           /* candidates evaluated */
    int32_t n_maxima;         /* corners after suppression */
    int32_t rejected_color;   /* maxima failing the colour filter */
    int32_t rejected_ground;  /* maxima without a ground point within
                                 max_range_mm (only with a camera) */
    int32_t cand_dropped;     /* edge pixels beyond FL_CORNERS_MAX_CAND */
    int32_t corners_dropped;  /* kept corners beyond FL_CORNERS_MAX_CORNERS */
    int32_t features_dropped; /* features beyond FL_CORNERS_MAX_FEATURES */
    /* private: working planes (smoothed luma, gradient size, unit normal
     * and doubled-angle vector Q7, response) */
    uint32_t magic;           /* set by a successful init */
    uint8_t luma[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
    uint8_t sm[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
    uint16_t mag[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
    int8_t nx[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
    int8_t ny[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
    int8_t c2[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
    int8_t s2[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
    uint32_t resp[FL_CORNERS_MAX_WIDTH * FL_CORNERS_MAX_HEIGHT];
} fl_corners_t;

/* The defaults listed above; net = fl_beacon_params_default. */
void fl_corners_params_default(fl_corners_params_t *p);

/* Validate (FL_ERR_RANGE: a parameter outside its range, or a net box
 * that fl_beacon_init refuses) and clear.  FL_ERR_NULL.  FL_ERR_CONFIG
 * (common.h: the caller's config.h differs from the library's): nothing
 * written. */
fl_status_t fl_corners_init_cfg(fl_corners_t *c, const fl_corners_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_corners_init(fl_corners_t *c, const fl_corners_params_t *p)
{
    return fl_corners_init_cfg(c, p, FL_CONFIG_FINGERPRINT);
}

/* Detect, filter, label and pair the corners of one frame; nets from
 * beacons (fl_beacon_find's result for this frame, or NULL).  colors: the
 * frame's colour table (white and carpet).  camera may be NULL (image
 * positions only).  FL_ERR_NULL (c, img, colors), FL_ERR_STATE (c not
 * initialized), fl_image_validate's status (FL_ERR_SIZE, _STRIDE,
 * _FORMAT), FL_ERR_SIZE (larger than FL_CORNERS_MAX_WIDTH x _HEIGHT, or
 * smaller than 8 x 8), FL_ERR_MISMATCH (a camera of another size): the
 * results are empty (when c is usable). */
fl_status_t fl_corners_run(fl_corners_t *c, const fl_image_t *img, const fl_color_table_t *colors,
                           const fl_camera_t *camera, const fl_beacon_t *beacons);

/* The measure at one pixel of the last run (for tests and tools): V
 * (Q8) and A; false (outputs 0) outside the image, at the border, for a
 * pixel below min_grad, or without a run. */
bool fl_corners_measure(const fl_corners_t *c, int32_t x, int32_t y, int32_t *var_q8, int32_t *app);

/* The last run's features as observations for a localizer (obs.h),
 * appended to out (not cleared: the L/T/X path's list may come first):
 * C -> FL_LM_CORNER_C, T-field -> FL_LM_CORNER_TFIELD, T-net ->
 * FL_LM_CORNER_TNET, the nets -> FL_LM_NET with color FL_COLOR_YELLOW /
 * FL_COLOR_SKYBLUE.  Range and bearing of the feature's ground point,
 * u_q4 / v_q4 its image position, confidence the feature's; no
 * orientation (the stage measures none), side unknown.  A feature without
 * a ground point, farther than FL_OBS_MAX_RANGE_MM or of confidence 0 is
 * not reported; one that does not fit is counted in out->dropped.
 * Returns the number appended; 0 for NULL, an uninitialized state or no
 * run. */
int32_t fl_corners_obs(const fl_corners_t *c, fl_obs_list_t *out);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_CORNERS_H */
