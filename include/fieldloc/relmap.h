/*
 * fieldloc/relmap.h - seed 002's localizer: a fixed grid of position
 * particles weighted by observed against expected landmark distances (its
 * equation 1), the relative map of the observed landmarks superimposed at
 * every heading in 1 degree steps on the particles over a threshold (its
 * equations 2-4), ties between equally good poses broken by white line
 * points, odometry moving the belief between frames.  Behind localizer.h
 * as "relmap" (src/loc/loc_relmap.c); tools reach it only through there.
 *
 * The grid: FL_RELMAP_NX x FL_RELMAP_NY particles (config.h; seed 002's
 * 54 x 36) at the centres of equal cells over the carpet (lines plus
 * border: a robot stands outside the lines too), each with a belief
 * (Q0.16, the peak 65535 after every update) and its own heading.  The
 * grid is 8 bytes a particle (belief, heading, and the copy odometry
 * shifts into): 15,552 bytes at 54 x 36; sizeof(fl_relmap_t) adds some
 * hundred bytes.
 *
 * Equation 1 changed: seed 002 writes exp(-|s_e - s_o| / (2 sigma^2)),
 * which divides a distance by a variance (units 1/mm, and sigma then only
 * scales the exponent's steepness).  Here the term is the Gaussian of the
 * difference, exp(-(s_e - s_o)^2 / (2 sigma^2)), with sigma = sigma_base_mm
 * + sigma_pct % of the observed range (a monocular range's error grows
 * with the range), each term capped at exp(-z2_cap) so that one false
 * landmark cannot empty the grid.
 *
 * Which landmarks are told apart: beacons (poles) by (color, color2);
 * posts by colour and by side when known; crossings, marks and the circle
 * only by kind.  An observation that matches one map landmark is
 * "identified"; otherwise eq. 1 takes the best match of its set (the
 * expected distance closest to the observed), and eq. 2 the nearest
 * landmark of the set to the superimposed one.
 *
 * Per-frame calls never fail: bad input (NULL, an observation with a range
 * above max_range_mm or negative, an empty list, absurd odometry) is
 * ignored and counted; the state stays valid (fl_relmap_check).
 */
#ifndef FIELDLOC_RELMAP_H
#define FIELDLOC_RELMAP_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"
#include "fieldloc/localizer.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FL_RELMAP_N (FL_RELMAP_NX * FL_RELMAP_NY)

typedef struct {
    uint16_t sigma_base_mm;   /* eq. 1 sigma = base + pct % of range */
    uint16_t sigma_pct;
    uint16_t z2_cap_q8;       /* cap of one term's (d/sigma)^2 / 2, Q8 */
    uint16_t cand_q16;        /* threshold: particles whose weight after
                                 eq. 1 reaches this share of the best
                                 particle's get a relative map */
    uint16_t max_cand;        /* at most this many (<= FL_RELMAP_MAX_CAND) */
    uint16_t err_cap_mm;      /* eq. 2: one landmark's miss counts at most
                                 this far (a false landmark stays bounded) */
    uint16_t tie_mm;          /* eq. 4 ties: d_p within n_obs * tie_mm^2 */
    uint16_t white_tol_mm;    /* a white point matches within this of a
                                 painted line's centre line (half the line
                                 width is added) */
    uint16_t heading_gate_deg; /* a particle keeps its tracked heading when
                                   the relative map's is within this */
    uint16_t jump_q8;         /* a particle whose heading jumps: this much
                                 added to its exponent (Q8), a third of
                                 it on the first frames of tracking,
                                 all of it after RM_JUMP_RAMP frames */
    uint16_t frame_cap_q8;    /* one frame lowers a particle against the
                                 best by at most exp(-cap) per factor (eq.
                                 1, the map): the grid's discretisation and
                                 correlated errors make single frames
                                 overconfident; it also bounds how much one
                                 false frame can move the belief */
    uint16_t floor_q16;       /* belief floor after an update (recovery) */
    uint16_t spread_q16;      /* process noise: after each odometry shift a
                                 particle has at least this share of its
                                 strongest neighbour's belief */
    uint16_t kidnap_q16;      /* mean eq.-1 fit below this, kidnap_frames
                                 frames in a row: back to ignorance */
    uint16_t kidnap_frames;
    int32_t max_range_mm;     /* observations beyond are ignored */
    int32_t odo_max_mm;       /* odometry steps beyond are rejected */
} fl_relmap_params_t;

typedef struct {
    uint32_t predicts, updates, obs_used, obs_ignored, odo_rejected;
    uint32_t kidnaps, resets, reseeds, reseeds_refused, empty_resets;
    uint32_t mode_switches;   /* the peak moved farther than a frame's
                                 motion can explain */
    uint32_t searches;        /* relative maps built (particles x frames) */
    uint32_t ties;            /* frames whose best pose was tied */
    uint32_t ties_changed;    /* ... where the white points chose another
                                 pose than the smallest error alone */
} fl_relmap_stats_t;

/* The frame's best pose (eq. 4 after the tie break). */
typedef struct {
    bool valid;
    int32_t x_mm, y_mm;
    fl_angle_t heading;
    uint32_t err_mm2;         /* d of eq. 4 */
    uint16_t n_tied;          /* size of the tie set T (1: unique) */
    uint16_t white_hits;      /* m_max */
} fl_relmap_best_t;

typedef struct {
    const fl_field_t *field;
    fl_relmap_params_t params;
    int32_t hx, hy;                     /* carpet half extents, mm */
    int32_t cell_x_q8, cell_y_q8;       /* cell size, Q8 mm */
    uint16_t bel[FL_RELMAP_N];          /* Q0.16, peak 65535 */
    int16_t head[FL_RELMAP_N];          /* binary angle */
    uint16_t tmp_bel[FL_RELMAP_N];      /* odometry shift target */
    int16_t tmp_head[FL_RELMAP_N];
    int32_t pend_x_mm, pend_y_mm;       /* odometry not yet shifted (robot
                                           frame, Q4 mm) */
    bool ignorance;                     /* nothing observed since a reset */
    bool heading_known;                 /* headings are tracked */
    int8_t prior_half;                  /* 0 none, -1 own half x < 0, +1 */
    bool prior_pose;
    bool half_known;                    /* a symmetric field's half has been
                                           told (prior, placement, told
                                           pose, report) and no mode switch
                                           since */
    bool have_last;
    int32_t last_x_mm, last_y_mm;       /* the peak after the last update */
    int32_t prior_x_mm, prior_y_mm, prior_r_mm;
    uint16_t since_obs;
    uint16_t bad_frames;                /* consecutive poor fits */
    uint16_t track_frames;              /* frames with landmarks since the
                                           grid started tracking (from
                                           ignorance or a mode switch; a
                                           told pose counts as long
                                           tracked): a heading jump's
                                           cost ramps up over them */
    uint16_t fit_q16;                   /* last frame's mean eq.-1 fit */
    fl_relmap_best_t best;
    fl_relmap_stats_t stats;
} fl_relmap_t;

/* Defaults for feature-level observations: eq. 1's sigma 200 mm + 15 % of
 * the range, eq. 2's miss capped at 1500 mm. */
void fl_relmap_params_default(fl_relmap_params_t *p);
/* For observations from a camera image (FL_LOC_PRESET_VISION): sigma
 * 100 mm + 8 % of the range, the miss capped at 500 mm (src/loc/relmap.c
 * says why, and why the defaults stay). */
void fl_relmap_params_vision(fl_relmap_params_t *p);
fl_status_t fl_relmap_params_check(const fl_relmap_params_t *p);

/* params NULL: defaults.  FL_ERR_NULL, FL_ERR_RANGE (params, or a field
 * larger than 20 m a side); on error the state is empty (check false). */
fl_status_t fl_relmap_init(fl_relmap_t *s, const fl_field_t *field,
                           const fl_relmap_params_t *params);
void fl_relmap_clear(fl_relmap_t *s);
bool fl_relmap_check(const fl_relmap_t *s);

void fl_relmap_predict(fl_relmap_t *s, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta);
/* The number of observations applied. */
uint16_t fl_relmap_update(fl_relmap_t *s, const fl_obs_list_t *obs);

void fl_relmap_reset_ignorance(fl_relmap_t *s);
void fl_relmap_reset_pose(fl_relmap_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                          int32_t pos_unc_mm);
void fl_relmap_reset_penalty(fl_relmap_t *s, int32_t x_mm, int32_t pos_unc_mm);
void fl_relmap_set_prior_half(fl_relmap_t *s, int half);
/* One prior at a time: each of these replaces the other.  The pose's centre
 * is clamped to the carpet, the radius to 0 .. 20000 mm. */
void fl_relmap_set_prior_pose(fl_relmap_t *s, int32_t x_mm, int32_t y_mm, int32_t radius_mm);
void fl_relmap_clear_prior(fl_relmap_t *s);
/* FL_OK, FL_ERR_STATE, FL_ERR_NULL / RANGE / STALE (obs.h checks). */
fl_status_t fl_relmap_reseed(fl_relmap_t *s, const fl_obs_report_t *r);

/* localizer.h's estimate (its contract; reliability calibrated), the
 * spread (localizer.h spread_mm), a pose's possibility (Q16, the peak
 * particle 65536), the particles with belief above 0 and the i-th. */
bool fl_relmap_estimate(const fl_relmap_t *s, fl_loc_estimate_t *out);
uint32_t fl_relmap_spread_mm(const fl_relmap_t *s);
uint32_t fl_relmap_possibility_q16(const fl_relmap_t *s, int32_t x_mm, int32_t y_mm,
                                   fl_angle_t heading);
uint16_t fl_relmap_samples(const fl_relmap_t *s);
bool fl_relmap_sample(const fl_relmap_t *s, uint16_t i, fl_loc_sample_t *out);

/* Particle (ix, iy)'s position. */
void fl_relmap_cell_pos(const fl_relmap_t *s, int ix, int iy, int32_t *x_mm, int32_t *y_mm);
/* The cell holding (x, y), -1 off the carpet. */
int32_t fl_relmap_cell_at(const fl_relmap_t *s, int32_t x_mm, int32_t y_mm);

/* ---- the relative map, exposed for tests ---------------------------------
 * A frame's landmarks prepared for eq. 2: robot-frame positions and, for
 * each, the map landmarks it may be (one when identified). */
typedef struct {
    int32_t ox, oy;                     /* robot frame, mm */
    int32_t range_mm;
    uint8_t n_cand;
    uint8_t cand[16];                   /* fl_field_all_at ids (landmarks, then features) */
} fl_relmap_lm_t;

typedef struct {
    fl_relmap_lm_t lm[FL_RELMAP_MAX_OBS];
    uint16_t n;
    uint32_t cap_mm2;
} fl_relmap_frame_t;

/* Fill f from obs (the nearest FL_RELMAP_MAX_OBS usable landmarks). */
uint16_t fl_relmap_frame(const fl_relmap_t *s, const fl_obs_list_t *obs, fl_relmap_frame_t *f);
/* Eq. 2 at a pose (heading in whole degrees, 0..359): sum over the
 * landmarks of min(cap, squared distance to the nearest candidate). */
uint32_t fl_relmap_error(const fl_field_t *field, const fl_relmap_frame_t *f, int32_t x_mm,
                         int32_t y_mm, int32_t deg);
/* Eq. 3: the best whole-degree heading at (x, y) and its error, the same
 * as the minimum of fl_relmap_error over the 360 headings (the smallest
 * degree among equals) but with a bound that skips most of them. */
uint32_t fl_relmap_best_heading(const fl_field_t *field, const fl_relmap_frame_t *f,
                                int32_t x_mm, int32_t y_mm, int32_t *deg);
/* White points of obs (at most FL_RELMAP_MAX_WHITE, evenly spread over
 * the list) on the field's painted lines or centre circle at a pose. */
uint16_t fl_relmap_white_hits(const fl_field_t *field, const fl_obs_list_t *obs, int32_t x_mm,
                              int32_t y_mm, fl_angle_t heading, int32_t tol_mm);
/* exp(-x) for x in Q8, Q16 (65536 = 1). */
uint32_t fl_relmap_exp_q16(uint32_t x_q8);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_RELMAP_H */
