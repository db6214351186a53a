/*
 * fieldloc/fuzzy.h - the fuzzy position grid localizer (seed 004:
 * Herrero-Perez, Martinez-Barbera and Saffiotti, after Buschka, Saffiotti
 * and Wasik, IROS 2000).
 *
 * The belief is a 2D grid over the carpet (field frame, FL_FUZZY_CELL_MM
 * cells) with ONE heading trapezoid per cell: "the robot is in this cell
 * with possibility mu(theta) for heading theta", where
 *     mu(theta) = bias + (height - bias) * t(|theta - centre|)
 *     t(d) = 1 for d <= core, (core + slope - d) / slope below core + slope,
 *            0 beyond (d: wrapped angular distance, 0..180 deg).
 * Total ignorance is height 1, bias 1 everywhere.  Possibilities are not
 * probabilities: the grid is normalized so that its highest cell has
 * height 1 (union = max, intersection = product).
 *
 * Lifecycle:
 *     fl_fuzzy_t *g = <caller-owned, static storage: ~63 KiB for SPL>;
 *     fl_fuzzy_init(g, fl_field_find("spl2013"), NULL);   -> ignorance
 *     fl_fuzzy_set_prior_half(g, -1);      (kick-off: own half, x < 0)
 *     every frame: fl_fuzzy_predict(g, odo_dx_mm, odo_dy_mm, odo_dtheta);
 *                  fl_fuzzy_update(g, &obs_list);
 *                  fl_fuzzy_estimate(g, &est);
 *     penalty placement: fl_fuzzy_reset_penalty(g, x_mm, ...);
 * Per-frame calls never fail: bad input is ignored and counted in g->stats,
 * and the grid is always valid (fl_fuzzy_check): never empty (an update
 * that would zero every cell resets to ignorance and is counted), every
 * cell bias <= height, estimate on the carpet.
 *
 * Callers may read every field; they may change `params` between calls
 * (fl_fuzzy_params_check tells whether the values are in range; out-of-range
 * values are clamped where used) and nothing else.
 *
 * Memory (defaults, SPL 2013 grid 104 x 74 = 7,696 cells):
 *     cells    8 B x 7,696          = 61,568 B (layout: fl_fuzzy_cell_t)
 *     scratch  the larger of predict's row ring buffer (3 rows x 104 x
 *              8 B = 2,496 B) and the update's row accumulator with its
 *              region list (104 x 10 B + 48 x 36 B = 2,768 B): 2,768 B
 *     live column range per row    2 x 74 B =    148 B
 *     the rest (params, prior, track, counters)   252 B on x86-64
 *     sizeof(fl_fuzzy_t) = 64,736 B on x86-64, < 64 KiB (printed by the
 *     fuzzy suite).
 *     No heap; stack at most about 1 KB per call (make stack).
 * Cost: predict O(cells) per sub-step and per dilation; an observation
 * update O(live cells in the rings of the matching landmarks) plus a few
 * passes over the grid, on half the grid on a symmetric field (SPL 2013;
 * fuzzy_update.c).  Worst case: total ignorance (every cell possible), for
 * a fraction of a second after a reset; with a tracked mode most cells are
 * 0 and the cost falls several-fold.  The negative information pass of
 * fl_fuzzy_update_view (only without a track) scales with the live cells
 * at least neg_min_q8 high with a narrow heading x the map's landmarks;
 * its worst case is every cell at the peak with a narrow heading.
 * Measured by `make bench` (rows fuzzy_*, fuzzy_negative_*).
 */
#ifndef FIELDLOC_FUZZY_H
#define FIELDLOC_FUZZY_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Trapezoid widths in a cell are 8-bit codes in units of FL_FUZZY_AUNIT
 * binary angles (128 = 0.703 deg); code FL_FUZZY_WFULL means "180 degrees or
 * more" (a core of FL_FUZZY_WFULL covers every heading). */
#define FL_FUZZY_AUNIT 128
#define FL_FUZZY_WFULL 255
/* Widths in the expanded form (fl_fuzzy_trap_t): binary angle units,
 * 0..FL_FUZZY_HALF_TURN; a core of FL_FUZZY_HALF_TURN covers every heading. */
#define FL_FUZZY_HALF_TURN 32768
/* Possibilities: Q0.8 in cells (255 = 1), Q16 with 65536 = 1 in the
 * expanded trapezoid and in fl_fuzzy_trap_eval. */
#define FL_FUZZY_ONE_Q16 65536u

/*
 * One cell, 8 bytes, no padding (static assert in fuzzy.c).
 *   centre     trapezoid centre, heading of the robot (binary angle, field)
 *   core       core half-width code (x FL_FUZZY_AUNIT; FL_FUZZY_WFULL = all)
 *   slope      slope width code (same units; FL_FUZZY_WFULL = >= 180 deg)
 *   height     possibility at the core, Q0.8 (0 = impossible cell)
 *   bias       possibility of any heading, Q0.8, bias <= height
 *   off_x_mm, off_y_mm  where in the cell the content is, relative to the
 *              cell centre, mm, in [-CELL/2, CELL/2): the contents move by
 *              odometry with sub-cell precision (predict) and rings and
 *              headings are evaluated there (update).
 */
typedef struct {
    fl_angle_t centre;
    uint8_t core;
    uint8_t slope;
    uint8_t height;
    uint8_t bias;
    int8_t off_x_mm;
    int8_t off_y_mm;
} fl_fuzzy_cell_t;

/* A heading trapezoid in expanded form, for the trapezoid algebra below.
 * core, slope: binary angle units in [0, FL_FUZZY_HALF_TURN] (values outside
 * are clamped by the functions); height_q16, bias_q16 in [0, 65536], bias <=
 * height (a larger bias is treated as equal to the height). */
typedef struct {
    fl_angle_t centre;
    int32_t core;
    int32_t slope;
    uint32_t height_q16;
    uint32_t bias_q16;
} fl_fuzzy_trap_t;

/*
 * Tunable parameters (fl_fuzzy_params_default gives the values used by the
 * simulations in the report; units in the names, Q0.8 fractions "_q8" with
 * 256 = 1, angles binary).
 */
typedef struct {
    /* motion model (predict) */
    uint16_t odo_trans_q8;       /* position uncertainty per mm walked (0.25) */
    uint16_t odo_turn_mm_per_rad;/* position uncertainty per radian turned (60) */
    uint16_t odo_rot_q8;         /* heading uncertainty per |dtheta| (0.16) */
    uint16_t odo_rot_per_m;      /* heading uncertainty per metre walked,
                                    binary angle (6 deg = 1092) */
    uint8_t blur_kappa_min_q8;   /* every predict dilates the grid (3x3 max,
                                    neighbour factor kappa) with kappa =
                                    min + gain x this call's position
                                    uncertainty (mm), at most max: keeps
                                    the neighbours of a mode alive so that
                                    observations can move it (0.25) */
    uint8_t blur_kappa_gain_q8;  /* per mm (0.2) */
    uint8_t blur_kappa_max_q8;   /* (0.9) */
    uint16_t blur_step_mm;       /* plus one crisp dilation (kappa 1) per
                                    this much accumulated position
                                    uncertainty: the support grows with
                                    the motion (100) */
    uint16_t wide_core;          /* cells whose core half-width is at least
                                    this (binary angle, 45 deg) do not move:
                                    their direction is unknown, the blur
                                    covers them */
    int32_t odo_max_mm;          /* |dx| or |dy| above this in one call is
                                    absurd: rejected and counted (1000;
                                    range 1..2000, which bounds predict to
                                    59 sub-steps) */
    /* observation model (update) */
    int32_t ring_base_mm;        /* radial core half-width at range 0 (60) */
    uint16_t ring_core_q8;       /* + this fraction of the range (0.06) */
    int32_t ring_slope_mm;       /* radial slope width at range 0 (80) */
    uint16_t ring_slope_q8;      /* + this fraction of the range (0.18) */
    uint16_t ring_track_q8;      /* while a mode is tracked the update uses
                                    the four ring widths above scaled by
                                    this (1 = 256, the default; 1..256):
                                    precise rings for tracking; wide ones
                                    from ignorance and for the gate, so
                                    deferral and kidnap detection do not
                                    change (fl_fuzzy_params_vision) */
    fl_angle_t bearing_core;     /* heading core half-width (2.5 deg) */
    fl_angle_t bearing_slope;    /* heading slope width (5 deg) */
    fl_angle_t head_min_core;    /* a cell's heading core and slope never
                                    shrink below these by intersection:
                                    observations are not independent
                                    (2 deg, 4 deg) */
    fl_angle_t head_min_slope;
    fl_angle_t orient_core;      /* orientation agreement core (10 deg) */
    fl_angle_t orient_slope;     /* orientation agreement slope (15 deg) */
    uint8_t bias_min_q8;         /* observation bias at confidence 255 (0.15):
                                    the possibility that it is an outlier
                                    (the robot anywhere, any heading) */
    uint8_t head_bias_q8;        /* relative bias of an observation's
                                    heading trapezoid (0.25): right ring,
                                    heading unreliable */
    uint8_t head_bias_outlier;   /* 1: that bias is at least the outlier
                                    bias bP (a pose on the ring with another
                                    heading is never less possible than one
                                    off every ring: a false positive can
                                    no longer flatten a cell's heading);
                                    0: head_bias alone (the default; 1 with
                                    head_bias 0 for the vision path,
                                    fl_fuzzy_params_vision) */
    uint8_t confuse_q8;          /* kind confusion (0 = none, the
                                    default): an L observation is also a T
                                    and a T an L, and each of seed 004's
                                    corner features (C, T-field, T-net) is
                                    also either of the other two, with
                                    this possibility (fuzzy_update.c
                                    build_regions) */
    uint8_t confuse_conf;        /* ... rising linearly to 1 at this
                                    confidence and below (0 = constant):
                                    vision's low-confidence crossings are
                                    often of the other kind */
    int32_t max_range_mm;        /* observations farther are ignored (12000) */
    int32_t cross_max_mm;        /* crossings and marks (L, T, X, penalty
                                    and centre marks) farther are ignored
                                    (0 = max_range_mm, the default): a
                                    low-resolution camera measures them
                                    badly far away (fl_fuzzy_params_lowres) */
    /* normalization */
    uint8_t min_height_q8;       /* heights below this after normalization
                                    are zero (2/255) */
    /* estimate, prior, kidnap */
    int32_t mode_radius_mm;      /* centre of gravity window (500) */
    int32_t track_radius_mm;     /* tracked mode's neighbourhood (1000) */
    uint8_t switch_q8;           /* keep the tracked (or pose prior) mode
                                    while its peak >= this x the global
                                    peak (0.5; a half prior: 1/8) */
    uint16_t track_min_q16;      /* reliability that starts tracking (0.3) */
    uint8_t gate_q8;             /* while tracking, an observation that
                                    leaves no cell of the tracked mode at
                                    least this fraction of its height is
                                    deferred (0.5; 0 disables) */
    uint8_t gate_run;            /* ... but not more than this many in a
                                    row (8) */
    uint8_t cons_shift;          /* consistency low-pass: 2^-shift (3) */
    uint16_t kidnap_q16;         /* tracked, consistency below this and
                                    contradictions at kidnap_rate_q8 per
                                    predict call or more: kidnap (0.45) */
    uint16_t kidnap_rate_q8;     /* (0.75) */
    /* negative information (fl_fuzzy_update_view) */
    uint8_t neg_q8;              /* a cell's core loses this fraction of its
                                    height per landmark its pose puts in
                                    the frame's view that no observation
                                    explains (0 = off, the default; the
                                    vision path: fl_fuzzy_params_vision) */
    uint8_t neg_max;             /* at most this many such landmarks count
                                    per cell and frame (2) */
    uint8_t neg_track;           /* 1: also while a mode is tracked; 0: only
                                    without a track (the default), when
                                    the belief has several modes */
    uint8_t neg_kidnap;          /* while tracked: a frame in which the
                                    tracked pose expects at least this many
                                    landmarks (2; 0 = off) and none is
                                    explained counts as a contradiction */
    int32_t neg_margin_mm;       /* position margin: a landmark counts when
                                    it is this far (plus neg_range_q8 of its
                                    distance) inside the view's range
                                    interval (200) */
    uint16_t neg_range_q8;       /* (0.1); an observation explains it
                                    within the same margin of its range */
    fl_angle_t neg_bearing;      /* bearing margin (5 deg) inside the view's
                                    sides, plus the cell's heading core and
                                    slope; an observation explains it
                                    within the same margin of its bearing */
    fl_angle_t neg_head_max;     /* cells whose heading core + slope is
                                    wider than this are skipped (30 deg) */
    uint8_t neg_min_q8;          /* ... and cells lower than this (0: none;
                                    they do not compete for the estimate) */
} fl_fuzzy_params_t;

/* What decides between symmetric modes until a mode is tracked.  A
 * detected kidnap drops it (the robot no longer knows its half). */
typedef enum {
    FL_FUZZY_PRIOR_NONE = 0,
    FL_FUZZY_PRIOR_HALF = 1,     /* the robot is in half sign(half) * x > 0 */
    FL_FUZZY_PRIOR_POSE = 2      /* near a pose (within radius_mm, heading
                                    within 90 deg) */
} fl_fuzzy_prior_kind_t;

typedef struct {
    fl_fuzzy_prior_kind_t kind;
    int8_t half;                 /* HALF: -1 own half (x < 0), +1 */
    int32_t x_mm, y_mm;          /* POSE */
    fl_angle_t heading;
    int32_t radius_mm;
} fl_fuzzy_prior_t;

/* Everything that went wrong or happened, counted (saturating). */
typedef struct {
    uint32_t predicts, updates;  /* calls */
    uint32_t obs_used;           /* observations applied */
    uint32_t obs_gated;          /* deferred: contradicted the tracked mode */
    uint32_t obs_ignored;        /* NULL, confidence 0, unknown kind, range
                                    < 0 or > max_range, kind not on the map */
    uint32_t odo_rejected;       /* absurd odometry (ignored) */
    uint32_t regions_dropped;    /* regions beyond FL_FUZZY_MAX_REGIONS */
    uint32_t empty_resets;       /* grid emptied -> reset to ignorance */
    uint32_t kidnaps;            /* collapsing consistency -> ignorance */
    uint32_t mode_switches;      /* estimate left the tracked mode */
    uint32_t resets;             /* explicit resets (any kind) */
    uint32_t reseeds;            /* fl_fuzzy_reseed applied */
    uint32_t reseed_replaced;    /* ... of which the disc replaced an
                                    empty intersection */
    uint32_t reseeds_refused;    /* ... refused (bad report) */
} fl_fuzzy_stats_t;

/* One estimate. */
typedef struct {
    int32_t x_mm, y_mm;          /* field frame, always on the carpet */
    fl_angle_t heading;
    uint16_t reliability_q16;    /* Q0.16 in [0, 65535] ~ [0, 1]: consistency
                                    x compactness x (1 - bias); see fuzzy_estimate.c */
    uint8_t peak_q8;             /* height of the chosen mode's peak */
    uint16_t mode_cells;         /* cells of the mode with height >= peak/2 */
    bool switched;               /* the estimate left the tracked mode */
    /* confidence (fuzzy_estimate.c; localizer.h gives the contract) */
    bool ignorance;              /* the grid holds no information (flat):
                                    the pose is the centre of the prior's
                                    region (the field's centre without one) */
    bool tracking;               /* a mode is tracked (after this call) */
    bool half_known;             /* the game told the half (prior, placement,
                                    pose reset) and no kidnap since */
    uint16_t sd_x_mm, sd_y_mm;   /* spread of the possibility mass around
                                    the estimate (cells at least half the
                                    peak, the mirror's side excluded) */
    int32_t cov_xy_mm2;          /* its covariance */
    fl_angle_t sd_heading;       /* heading spread of the mode (binary
                                    angle; 32767: no heading information) */
    uint16_t mirror_q16;         /* possibility of the 180-degree mirror
                                    pose relative to the estimate's, given
                                    the half (0 when half_known or the
                                    field is not symmetric) */
    uint16_t since_obs;          /* predict calls since an observation was
                                    last applied (saturating) */
    uint16_t calibrated_q16;     /* reliability_q16 and the rest mapped to
                                    the probability that the pose is within
                                    500 mm and 20 deg of the truth
                                    (fuzzy_estimate.c, fitted on simulated
                                    walks) */
} fl_fuzzy_estimate_t;

/* Scratch of one call (not state: contents are dead between calls). */
typedef struct {
    int32_t lx_mm, ly_mm;        /* map landmark */
    int32_t x0_mm, x1_mm, y0_mm, y1_mm;  /* bounding box of the cells to visit */
    fl_angle_t head_o;           /* heading implied by the orientation */
    int16_t ux_q15, uy_q15;      /* oriented: unit vector landmark -> the
                                    arc's centre (cos, sin Q15) */
    uint16_t scale_q16;          /* ring values x this (65535 = 1: the
                                    observed kind; confuse_q8: the other) */
    bool oriented;
    bool sector;                 /* oriented with a narrow sector: cells
                                    whose direction from the landmark is
                                    outside it are skipped before atan2 */
} fl_fuzzy_region_t;

typedef struct {
    uint16_t r1_q16;             /* best ring value in this cell (Q16, 65535 = 1) */
    uint16_t r2_q16;             /* best with another heading */
    uint16_t r3_q16;             /* anything else (folded into the bias) */
    fl_angle_t head1, head2;     /* headings implied by the first two */
} fl_fuzzy_acc_t;

typedef union {
    fl_fuzzy_cell_t ring[3][FL_FUZZY_MAX_NX];      /* predict, dilation */
    struct {
        fl_fuzzy_acc_t acc[FL_FUZZY_MAX_NX];
        fl_fuzzy_region_t region[FL_FUZZY_MAX_REGIONS];
    } upd;                                         /* update */
} fl_fuzzy_scratch_t;

typedef struct {
    const fl_field_t *field;
    fl_fuzzy_params_t params;
    uint16_t nx, ny;             /* cells in use (row-major, stride nx) */
    int32_t x0_mm, y0_mm;        /* field position of the grid's corner
                                    (-x, -y); cell (ix, iy) centre is
                                    x0 + ix*CELL + CELL/2 */
    int32_t half_x_mm, half_y_mm;/* carpet half extents */
    int32_t blur_acc_mm;         /* motion uncertainty not yet dilated */
    int32_t widen_acc;           /* heading widening not yet applied
                                    (binary angle units < FL_FUZZY_AUNIT) */
    uint16_t consistency_q16;    /* low-passed peak before normalization */
    uint8_t contra_run;          /* observations contradicting the tracked
                                    mode in a row */
    uint16_t contra_rate_q8;     /* contradictions per predict call, Q8,
                                    low-passed over about 8 calls */
    fl_fuzzy_prior_t prior;
    bool track_valid;            /* a mode is tracked (converged) */
    bool sym_exact;              /* symmetric field: every cell is exactly
                                    the mirror of its mirror cell (after
                                    ignorance, an update, and predicts
                                    since; not after a pose or penalty
                                    reset until the next update) */
    int32_t track_x_mm, track_y_mm;
    fl_angle_t track_heading;
    bool half_known;             /* the half was told (prior, placement,
                                    pose reset) and no kidnap since */
    uint16_t since_obs;          /* predict calls since an observation was
                                    last applied (saturating) */
    fl_fuzzy_stats_t stats;
    uint8_t row_lo[FL_FUZZY_MAX_NY];  /* live cells of row iy lie in columns */
    uint8_t row_hi[FL_FUZZY_MAX_NY];  /* row_lo..row_hi (lo > hi: none); a
                                         superset, refreshed by every
                                         normalization and predict */
    fl_fuzzy_cell_t cell[FL_FUZZY_MAX_NX * FL_FUZZY_MAX_NY];
    fl_fuzzy_scratch_t scratch;
} fl_fuzzy_t;

/* ---- lifecycle ---------------------------------------------------------- */

void fl_fuzzy_params_default(fl_fuzzy_params_t *p);
/* FL_OK, FL_ERR_NULL or FL_ERR_RANGE (a value outside its documented use). */
fl_status_t fl_fuzzy_params_check(const fl_fuzzy_params_t *p);

/* The parameters for observations from fl_vision_frame (vision.h), with
 * the frame's view given to fl_fuzzy_update_view (vision.h,
 * fl_vision_view): the defaults above suit noisy feature-level
 * observations; vision's are more precise but fewer, with L/T confusions
 * and far false marks instead.  Changes (what each trades in
 * src/loc/fuzzy.c; measured by `build/fieldloc simulate ... --frames`):
 * narrower rings (core 3 % and slope 9 % of the range), precise rings
 * while tracked (ring_track_q8 FL_FUZZY_RING_TRACK_VISION), 9 deg heading
 * uncertainty per metre walked, outlier heading bias, kidnap rate 0.5,
 * negative information (neg_q8 0.39 on cells at least half the peak,
 * neg_kidnap 2), tracking from reliability 0.2, L/T confusion (0.39 rising
 * to 1 at confidence 160).  lowres: a camera narrower than 320 px (the
 * AIBO's; localizer.h fl_loc_preset_for_width decides from the width):
 * fl_fuzzy_params_lowres then keeps the wide rings and ignores crossings
 * beyond 2.5 m. */
#define FL_FUZZY_RING_TRACK_VISION 96
void fl_fuzzy_params_vision(fl_fuzzy_params_t *p, bool lowres);

/* The low-resolution part of fl_fuzzy_params_vision, applied only while
 * ring_track_q8 still has its vision value (an explicit other value is the
 * caller's choice): ring_track_q8 256 (a narrow camera's ranges are less
 * precise: precise rings cost accuracy) and, when cross_max_mm is 0, 2500
 * (its far crossings read short).  No-op for NULL. */
void fl_fuzzy_params_lowres(fl_fuzzy_params_t *p);

/* Sizes the grid to the field's carpet (ceil(2 * half / CELL) cells each way,
 * centred) and resets to total ignorance with no prior.  params NULL gives
 * the defaults.  FL_ERR_NULL, FL_ERR_SIZE (carpet larger than the compiled
 * capacity), FL_ERR_RANGE (params out of range); on error *g is unusable
 * (g->field is NULL and every other call is a no-op).  FL_ERR_CONFIG
 * (common.h: the caller's config.h differs from the library's): nothing
 * written. */
fl_status_t fl_fuzzy_init_cfg(fl_fuzzy_t *g, const fl_field_t *field,
                              const fl_fuzzy_params_t *params, uint32_t caller_cfg);
static inline fl_status_t fl_fuzzy_init(fl_fuzzy_t *g, const fl_field_t *field,
                                        const fl_fuzzy_params_t *params)
{
    return fl_fuzzy_init_cfg(g, field, params, FL_CONFIG_FINGERPRINT);
}

/* ---- resets (each clears the tracked mode; see each for the prior) ----- */

/* Total ignorance: every cell height 1, bias 1, any heading.  The prior
 * is kept. */
void fl_fuzzy_reset_ignorance(fl_fuzzy_t *g);
/* A known pose: cells within pos_unc_mm (at least one cell) of (x, y)
 * possible with height falling linearly from 1 at the pose to 1/2 at
 * pos_unc_mm, heading trapezoid (heading, core heading_unc, slope
 * heading_unc), bias 0; every other cell impossible.  A pose off the carpet
 * is clamped onto it.  The pose becomes the tracked mode (on a symmetric
 * field the next update makes its mirror equally possible; the track keeps
 * the estimate on this one).  The prior is kept. */
void fl_fuzzy_reset_pose(fl_fuzzy_t *g, int32_t x_mm, int32_t y_mm,
                         fl_angle_t heading, int32_t pos_unc_mm,
                         fl_angle_t heading_unc);
/* Penalty placement: the union of the two touchline spots (x_mm, +-width/2)
 * facing into the field (heading -90 deg at +y, +90 deg at -y), each with
 * pos_unc_mm and heading_unc.  x_mm != 0 tells the half: it becomes the
 * prior (on a symmetric field the spots of the other half look the same). */
void fl_fuzzy_reset_penalty(fl_fuzzy_t *g, int32_t x_mm, int32_t pos_unc_mm,
                            fl_angle_t heading_unc);

/* ---- priors (decide between modes until one is tracked) ----------------- */

void fl_fuzzy_set_prior_half(fl_fuzzy_t *g, int half);   /* -1 own, +1 */
void fl_fuzzy_set_prior_pose(fl_fuzzy_t *g, int32_t x_mm, int32_t y_mm,
                             fl_angle_t heading, int32_t radius_mm);
void fl_fuzzy_clear_prior(fl_fuzzy_t *g);

/* Re-seeding from an observer's report (obs.h; seed 003 section 3.4's
 * re-sprinkling, for a possibility grid): the product intersection (the
 * grid's fuzzy AND) of every cell with a disc around the foot, possibility
 * 1 within the report's sd and falling linearly to 0 at 3 sd (evaluated
 * where the cell's content is), each cell's heading trapezoid kept; then
 * normalized.  An empty intersection (its peak below min_height_q8, the
 * normalization's floor: the belief excluded the foot) is replaced by the
 * disc alone, with the current estimate's heading (core max(pi/8, its
 * heading sd), slope twice that; any heading when the estimate tells
 * none), counted in stats.reseed_replaced.  The foot becomes the tracked
 * mode (with the estimate's heading) and the half known, the consistency fresh,
 * as fl_fuzzy_reset_pose; the prior kept.  FL_OK; FL_ERR_STATE
 * (uninitialized); fl_obs_report_check's refusals (counted in
 * stats.reseeds_refused, the grid unchanged). */
fl_status_t fl_fuzzy_reseed(fl_fuzzy_t *g, const fl_obs_report_t *r);
/* How far the belief has spread (localizer.h spread_mm): sqrt of the
 * variance of x plus y of the possibility mass (each live cell weighted by
 * its height, at its content's position); while a mode is tracked on a
 * symmetric field each cell counted at the nearer of itself and its mirror
 * to the track.  UINT32_MAX when uninitialized. */
uint32_t fl_fuzzy_spread_mm(const fl_fuzzy_t *g);

/* ---- per frame ---------------------------------------------------------- */

/* Odometry since the last call, robot frame at the start of the motion
 * (x forward, y left, mm; dtheta CCW), composed as
 *     x += dx cos(h) - dy sin(h); y += dx sin(h) + dy cos(h); h += dtheta
 * (translation along the heading before the turn).  Each cell's contents
 * move by the displacement rotated by the cell's own heading, then headings
 * turn, trapezoids widen and the grid is dilated by the motion uncertainty.
 * |dx| or |dy| > params.odo_max_mm: ignored, counted (odo_rejected). */
void fl_fuzzy_predict(fl_fuzzy_t *g, int32_t dx_mm, int32_t dy_mm,
                      fl_angle_t dtheta);

/* One observation: product intersection of every cell with the union of
 * fuzzy rings around every map landmark of the observation's kind (posts:
 * of its side and color when known), then normalization.  Returns true if
 * it was applied (false: ignored and counted). */
bool fl_fuzzy_update_one(fl_fuzzy_t *g, const fl_obs_t *obs);
/* Every observation of a frame in turn; returns how many were applied. */
uint16_t fl_fuzzy_update(fl_fuzzy_t *g, const fl_obs_list_t *obs);
/* fl_fuzzy_update, then negative information from the frame's view
 * (obs.h; NULL or !valid: none): for every live cell whose heading is known
 * to within neg_head_max, every map landmark that the pose (the cell's
 * content position, its trapezoid centre) puts inside the view (with the
 * margins above, widened by the cell's heading core and slope) and that
 * no observation of the list explains (an observation of a compatible
 * kind near the expected range and bearing: posts and beacons explain
 * posts and beacons, any line feature explains any line feature, as kind
 * confusions happen; each observation explains at most one landmark, the
 * nearest in bearing) lowers the cell's height by neg_q8, at most neg_max
 * times: height' = max(height x (1 - neg_q8)^n, bias), i.e. the headings
 * of the core lose possibility, the others keep the bias.  Applied while
 * no mode is tracked (or always with neg_track); then normalized.  While
 * tracked, with neg_kidnap, the tracked pose is tested the same way
 * (heading known exactly): neg_kidnap or more expected landmarks and none
 * explained counts as a contradiction (consistency and kidnap detection,
 * fuzzy_negative.c).  neg_q8 = 0 and neg_kidnap = 0: exactly
 * fl_fuzzy_update.  Returns how many observations were applied. */
uint16_t fl_fuzzy_update_view(fl_fuzzy_t *g, const fl_obs_list_t *obs,
                              const fl_obs_view_t *view);

/* The estimate: centre of gravity of the dominant mode (the tracked mode or
 * the prior's while its peak is at least switch_q8 x the global peak),
 * heading = weighted circular mean of the trapezoid centres, reliability;
 * then the confidence (spread, mirror, the calibrated reliability of
 * localizer.h).  A flat grid (no information) gives the centre of the
 * prior's region instead of a mode.  Updates the tracked mode.  false (and
 * *out zeroed) only for NULL or an uninitialized grid. */
bool fl_fuzzy_estimate(fl_fuzzy_t *g, fl_fuzzy_estimate_t *out);

/* ---- inspection --------------------------------------------------------- */

/* Field position of a cell's centre (false if outside the grid). */
bool fl_fuzzy_cell_centre(const fl_fuzzy_t *g, int ix, int iy,
                          int32_t *x_mm, int32_t *y_mm);
/* Possibility of pose (x, y, heading): the cell containing (x, y) evaluated
 * at heading, Q16 (65536 = 1); 0 off the grid. */
uint32_t fl_fuzzy_possibility_q16(const fl_fuzzy_t *g, int32_t x_mm,
                                  int32_t y_mm, fl_angle_t heading);
/* Invariants: initialized, at least one cell at height 255, every bias <=
 * height, codes and offsets in range.  Used by the tests. */
bool fl_fuzzy_check(const fl_fuzzy_t *g);

/* ---- trapezoid algebra (exported for tests and pictures) --------------- */

/* mu(theta) in Q16 (65536 = 1), rounded down. */
uint32_t fl_fuzzy_trap_eval(const fl_fuzzy_trap_t *t, fl_angle_t theta);
/* Outer trapezoidal envelope of the product mu_a(theta) * mu_b(theta):
 * out >= a * b for every heading (never rules out a possibility), see
 * fuzzy_trap.c for the construction and how much it widens. */
void fl_fuzzy_trap_isect(const fl_fuzzy_trap_t *a, const fl_fuzzy_trap_t *b,
                         fl_fuzzy_trap_t *out);
/* Outer trapezoidal envelope of the union max(mu_a, mu_b). */
void fl_fuzzy_trap_union(const fl_fuzzy_trap_t *a, const fl_fuzzy_trap_t *b,
                         fl_fuzzy_trap_t *out);
/* Cell <-> expanded form.  fl_fuzzy_trap_to_cell rounds outward (widths,
 * height and bias up), so the cell's trapezoid >= the expanded one; the
 * offsets of *c are left unchanged. */
void fl_fuzzy_trap_from_cell(const fl_fuzzy_cell_t *c, fl_fuzzy_trap_t *t);
void fl_fuzzy_trap_to_cell(const fl_fuzzy_trap_t *t, fl_fuzzy_cell_t *c);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_FUZZY_H */
