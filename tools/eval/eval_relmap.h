/*
 * tools/eval/eval_relmap.h - seed 002's evaluation (`fieldloc eval-relmap`):
 * its table I poses and random poses on the hl3x2 field, each rendered
 * (acyut-640 in its default stance), seen by seed 002's vision path
 * (hlvision.h) and localized from total ignorance by a catalogue localizer
 * (relmap by default) over a few frames of the robot standing still.
 *
 * Per pose: `frames` frames, each rendered with its own sensor noise, each
 * through fl_hlv_frame and fl_loc_update (the view of fl_vision_view);
 * the estimate after the last frame is scored against the rendered pose:
 * position error (mm) and heading error (deg).
 *   - table I: the three poses of tools/world/seed002.h (S002_CHOSEN), with
 *     seed 002's own errors beside ours;
 *   - random poses: uniform over the field inside the lines, heading
 *     uniform, kept when the renderer's truth shows at least two landmarks
 *     the vision path can report (T and X crossings with their arms in
 *     the frame, goal posts, poles: s002_visible; an L corner is no
 *     landmark of seed 002's, whose skeleton marks nodes of degree 3 and
 *     4 only), until `poses` are kept (at most 50 draws per pose).
 * Wrong side: the estimate is more than 500 mm from the true position and
 * nearer the true position turned 180 degrees about the field's centre.
 * Ties (relmap only, its fl_relmap_best_t): frames whose eq. 4 minimum was
 * shared by more than one particle; resolved right when the frame's best
 * pose after the white-point tie break is within 300 mm and 20 degrees of
 * the truth.
 * Time: vision plus the localizer's update per frame (CLOCK_MONOTONIC),
 * mean over every frame of the run; rendering is not counted.
 * Host only (malloc, double).
 */
#ifndef FL_TOOLS_EVAL_RELMAP_H
#define FL_TOOLS_EVAL_RELMAP_H

#include <stdint.h>
#include <stdio.h>

typedef struct {
    uint32_t seed;            /* random poses and render noise */
    int poses;                /* random poses kept (>= 0) */
    int frames;               /* frames per pose (>= 1) */
    const char *localizer;    /* catalogue name */
    int verbose;              /* one line per random pose */
    char param_name[16][48];  /* localizer parameters set by name */
    int32_t param_value[16];
    int n_param;
} er_opts_t;

typedef struct {
    double table1_max_pos_mm, table1_max_head_deg;
    double median_pos_mm, median_head_deg;
    double wrong_side_pct;
    double frame_ms;          /* mean vision + update per frame */
    double frame_ms_max;
    int kept, drawn;          /* random poses kept / drawn */
    long ties, ties_right;    /* relmap only */
    long frames_run;
} er_result_t;

/* Runs the evaluation, printing '#' lines and the per-pose tables to out;
 * 0 on success, -1 on bad options or a failure (message on stderr). */
int er_run(const er_opts_t *o, FILE *out, er_result_t *res);

/* The summary lines (external evaluation reads them). */
void er_print_summary(FILE *out, const er_result_t *res);

#endif /* FL_TOOLS_EVAL_RELMAP_H */
