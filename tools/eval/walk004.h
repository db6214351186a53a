/*
 * tools/eval/walk004.h - seed 004's walk-through (its section 5, figures
 * 6 and 7; `fieldloc walk004`): the AIBO in its own goal area, more or
 * less facing the opponent (yellow) net, starts from total ignorance
 * (the fuzzy grid G0 = 1 everywhere) and scans its head left to right;
 * every new feature is fused into the grid as soon as it is perceived,
 * one observation at a time: the net, then two C corners.  After each
 * fused observation the walk records the belief (estimate, error to the
 * truth, reliability, the top region's area, the possibility of the true
 * pose, how the belief lies around the yellow net) and, with an output
 * folder, draws it as seed 004's figure 7 does (the x-y projection of the
 * grid, darker = more possible) next to the camera frame with the corner
 * detections (figure 6).
 *
 * The pose (w4_opts_default; --pose): x -1800, y -100, heading 10 deg.
 * aibo2004's own goal is the sky-blue one at -x and its goal-keeper box
 * spans x -2100..-1450, y -500..500 (src/model/field.c); -1800 is the
 * middle of the box's depth, y -100 and 10 deg make "more or less facing
 * the yellow net" (it is 8 deg right of the robot's heading) and keep the
 * pose off the field's y mirror axis, so that the C's to the left and to
 * the right are not mirror images of each other.
 *
 * The scan: the head straight ahead first (where it rests when the robot
 * is put down: this frame shows the yellow net, seed 004's first
 * observation), then from yaw_left to yaw_right in yaw_step steps at a
 * fixed pitch (0: the AIBO camera 145 mm above the carpet then sees the
 * ground from 0.35 m to the horizon, the goal-box corners 0.6 m away and
 * the net 3.9 m away in the same frames).
 *
 * Observations.  Frames mode (the default): each frame is rendered at the
 * true pose (tools/world/render.h, the renderer's defaults, RGB, seed
 * mixed with the frame index) and goes through fl_vision_frame (the goal
 * posts the nets come from) and the corner stage (fl_corners_run,
 * fl_corners_obs: seed 004's C, T-field, T-net and the nets).  Features
 * mode: the map's features (fl_field_t.features) whose ground point is in
 * the frame (8 px margin) and within W4_CORNER_RANGE_MM (corners) or
 * FL_OBS_MAX_RANGE_MM (nets), with their exact range and bearing from the
 * true pose, confidence 255.  Either way a frame's observations are
 * taken left to right (bearing descending: the scan's direction) and
 * fused when new: a net of a colour not fused yet, or a C whose ground
 * point (robot frame: the robot stands still) is more than
 * W4_SAME_C_MM from every C fused before.  T-field and T-net
 * observations are counted, not fused (the walk-through fuses nets and
 * C's).  The walk stops once a net and two C's are fused, or at the end of
 * the scan (the steps then say what was not seen).
 *
 * The localizer: fl_fuzzy_init on aibo2004 with fl_fuzzy_params_vision
 * for a low-resolution camera (the parameters `simulate --frames` gives
 * the AIBO), fl_fuzzy_update_one per observation, fl_fuzzy_estimate after
 * each.  Which map feature an observation is matters not to the grid (seed
 * 004 section 3.3: a C is the union of a ring around every C); the report
 * names the nearest map feature of its kind seen from the true pose, so
 * that a false detection shows.
 *
 * Host only (malloc, double).
 */
#ifndef FL_TOOLS_WALK004_H
#define FL_TOOLS_WALK004_H

#include "fieldloc/fieldloc.h"

#include <stdint.h>
#include <stdio.h>

#define W4_MAX_STEPS 8
#define W4_MAX_FRAMES 64
#define W4_CORNER_RANGE_MM 3000  /* the corner stage's reach (eval-detect's 3 m) */
#define W4_SAME_C_MM 300         /* two C's nearer than this are one */
#define W4_TOP_Q8 230            /* the top region: cells at least 0.9 of the peak */

typedef struct {
    int features;             /* 1: ideal observations of the map features */
    const char *out_dir;      /* pictures (PNG) here; NULL: none */
    int verbose;              /* '#' lines per frame: its observations and
                                 (frames mode) the corner stage's pairs
                                 with their corners' labels and counts;
                                 with out_dir also walk004_frameNN.png */
    int32_t x_mm, y_mm;       /* true pose, field frame */
    int32_t heading_mdeg;
    int32_t pitch_mdeg;       /* head pitch during the scan (+ down) */
    int32_t yaw_left_mdeg;    /* the scan: straight ahead, then yaw_left */
    int32_t yaw_right_mdeg;   /* ... to yaw_right */
    int32_t yaw_step_mdeg;    /* > 0 */
    uint32_t seed;            /* render noise */
    int whole_scan;           /* 1: look at every frame of the scan (the
                                 fusion still stops after a net and two
                                 C's; later frames are only counted) */
} w4_opts_t;

typedef struct {
    fl_obs_t obs;             /* as fused */
    int frame;                /* scan frame it was seen in (0 = straight ahead) */
    int32_t yaw_mdeg;         /* head yaw of that frame */
    int map_index;            /* nearest map feature of its kind (index into
                                 field->features; -1: none) */
    double map_err_mm;        /* distance of the observation's field point
                                 (from the true pose) to that feature */
    int32_t est_x_mm, est_y_mm; /* the grid's estimate after the fusion */
    double est_heading_deg;
    int est_ignorance;        /* the grid was flat (no estimate) */
    double err_mm, err_deg;   /* estimate - truth */
    double reliability;       /* reliability_q16 / 65535 */
    double top_area_m2;       /* cells >= W4_TOP_Q8 (0.9 of the peak) */
    double half_area_m2;      /* cells >= half the peak */
    double p_true;            /* possibility of the true pose, 0..1 */
    double net_r_min_mm;      /* distances from the yellow net's centre of */
    double net_r_max_mm;      /* the cells >= half the peak */
    double net_r_true_mm;     /* ... and of the true position */
    char picture[2][640];     /* belief, frame ("" when not written) */
} w4_step_t;

typedef struct {
    int n_steps;
    w4_step_t step[W4_MAX_STEPS];
    int frames;               /* scan frames looked at */
    int nets, cs;             /* fused */
    int seen_other;           /* T-field / T-net observations (not fused) */
    int seen_c;               /* C observations, every frame */
    int complete;             /* a net and two C's were fused */
    /* frames mode: the map's C's in the frames looked at (C x frame),
     * each reported by the corner stage as a C, as a T-field ([0]) or
     * T-net ([1]), or missed */
    int truth_c_views, truth_c_as_c, truth_c_as_other[2], truth_c_missed;
    double ignorance_area_m2; /* the grid's area (G0: all of it is top) */
    char ignorance_picture[640];
} w4_result_t;

void w4_opts_default(w4_opts_t *o);

/* Runs the walk, printing '#' comment lines and one table row per fused
 * observation to out (may be NULL: quiet).  0 on success, -1 on a
 * failure (message on stderr). */
int w4_run(const w4_opts_t *o, FILE *out, w4_result_t *res);

/* walk004_error_mm, walk004_heading_err_deg, walk004_observations,
 * walk004_reliability, walk004_p_true (the last step; without a step the
 * ignorance estimate). */
void w4_print_summary(FILE *out, const w4_opts_t *o, const w4_result_t *res);

#endif /* FL_TOOLS_WALK004_H */
