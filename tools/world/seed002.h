/*
 * tools/world/seed002.h - seed 002's table I (its appendix B) in the project's
 * field frame, and the frame readings that were tested to get there.
 *
 * Seed 002 gives three poses of its figure 2 "considering the bottom left
 * corner of the field as origin", angles anticlockwise, on a field of
 * 3 m x 2 m, yet pose 2(a) has y = 2.15 m (measured) and 2.22 m
 * (estimated).  Each reading below maps its (X, Y, angle) to the field
 * frame of hl3x2 (origin at the centre, x toward the sky-blue goal, y left,
 * mm, degrees anticlockwise); s002_visible says which landmarks the
 * acyut-640 camera (its default stance, head 20 deg down, yaw 0) sees at a
 * pose, by the renderer's truth (tools/world/truth.h).  The chosen reading
 * and why: tools/world/seed002.c (file top) and docs/DESIGN.md 15i.
 * Host only.
 */
#ifndef FL_TOOLS_SEED002_H
#define FL_TOOLS_SEED002_H

#include "world/render.h"

#include <stdio.h>

typedef enum {
    S002_LINE_CORNER = 0,   /* origin at the lines' corner (-1500, -1000) */
    S002_CARPET_CORNER = 1, /* origin at the carpet's corner: lines offset
                               by hl3x2's border (350) */
    S002_CARPET_700 = 2,    /* origin at a carpet corner 700 mm beyond the
                               lines (the unscaled KidSize border) */
    S002_Y_DOWN = 3,        /* origin at the lines' top-left corner, y
                               measured downward (angles then clockwise in
                               the field frame) */
    S002_SWAPPED = 4,       /* the field drawn upright: X across the 2 m
                               width, Y along the 3 m length */
    S002_LINE_CORNER_2A = 5,/* the line corner, with 2(a)'s y values (2.15,
                               2.22 m: beyond the 2 m width) read as 1.15
                               and 1.22 m, a slipped leading digit; only
                               s002_to_field_pose applies it (to 2(a)) */
    S002_READING_COUNT = 6
} s002_reading_t;

/* The reading the project uses (seed002.c explains the choice). */
#define S002_CHOSEN S002_LINE_CORNER_2A

/* One pose of table I in seed 002's own numbers (mm, deg). */
typedef struct {
    const char *fig;                    /* "2(a)", "2(b)", "2(c)" */
    int32_t meas_x_mm, meas_y_mm;       /* measured (the true pose) */
    int32_t meas_deg;
    int32_t est_x_mm, est_y_mm;         /* seed 002's estimate */
    int32_t est_deg;
    const char *seen;                   /* what its text says is visible */
} s002_paper_pose_t;

/* A table I pose in the project's field frame under S002_CHOSEN, with
 * seed 002's own errors (its estimate minus the measured pose). */
typedef struct {
    const char *fig;
    int32_t x_mm, y_mm;                 /* measured pose, field frame */
    int32_t heading_deg;                /* -180..179 */
    int32_t est_x_mm, est_y_mm;         /* seed 002's estimate, field frame */
    int32_t est_heading_deg;
    int32_t paper_pos_err_mm;           /* |estimate - measured|, rounded */
    int32_t paper_heading_err_deg;      /* |estimate - measured| */
} s002_table1_t;

#define S002_TABLE1_N 3
extern const s002_paper_pose_t s002_paper[S002_TABLE1_N];
/* S002_TABLE1_N poses under S002_CHOSEN (the same numbers as
 * s002_to_field_pose gives; host_tests/test_seed002.c checks it). */
extern const s002_table1_t s002_table1[S002_TABLE1_N];

const char *s002_reading_name(s002_reading_t r);

/* Paper (X, Y, deg) -> field frame (x, y mm rounded, heading deg in
 * -180..179).  0 on success, -1 for an unknown reading or NULL output. */
int s002_to_field(s002_reading_t r, int32_t X_mm, int32_t Y_mm, int32_t deg,
                  int32_t *x_mm, int32_t *y_mm, int32_t *heading_deg);

/* As s002_to_field for table I pose fig_index (0..2) of s002_paper,
 * measured (est = 0) or estimated (est = 1): the reading's per-pose
 * rules included (S002_LINE_CORNER_2A). */
int s002_to_field_pose(s002_reading_t r, int fig_index, int est, int32_t *x_mm,
                       int32_t *y_mm, int32_t *heading_deg);

/* The scene of a table I pose: hl3x2, acyut-640 in its default stance
 * (render_scene_default), robot at the pose, no room around the carpet. */
void s002_scene(render_scene_t *sc, int32_t x_mm, int32_t y_mm, int32_t heading_deg);

/* What the camera sees at a pose (not occluded truth features): counts of
 * crossings (L, T, X), goal posts (feet or tops, counted once per post),
 * landmark poles, and marks; names (e.g. "T(0,1000) pole(YBY) post(-x,L)")
 * into buf.  0 on success. */
/* A crossing seed 002's vision can report: a T or an X (its skeleton
 * marks nodes of degree 3 and 4; an L is no node) whose arms lie in the
 * frame.  The skeleton (skeleton.h) wants every arm to reach arm_px (6)
 * mask pixels beyond the node and rejects a cluster clipped by the mask
 * edge; at acyut-640's mask grid of 4 x 2 pixels that is 24 columns and
 * 12 rows of the image. */
#define S002_EDGE_U_PX 24
#define S002_EDGE_V_PX 12

typedef struct {
    int crossings, posts, poles, marks;
    int tx;                             /* T and X crossings whose arms the
                                           skeleton can follow (S002_EDGE_*
                                           inside the frame) */
    int pole_landmark;                  /* index of the last pole seen, -1 */
} s002_seen_t;
int s002_visible(const render_scene_t *sc, s002_seen_t *seen, char *buf, int buf_len);

/* Does what a pose sees agree with seed 002's text?  2(a): exactly one
 * pole, at least one crossing, no post; 2(b): both posts of one goal;
 * 2(c): at least three landmarks (posts, poles, crossings, marks). */
int s002_agrees(int fig_index, const s002_seen_t *seen);

/* Print every reading: each pose in the field frame, what it sees, and
 * whether that agrees with the text; returns the number of poses (of
 * S002_TABLE1_N) that agree under reading r in agree[r]. */
void s002_report(FILE *f, int agree[S002_READING_COUNT]);

#endif /* FL_TOOLS_SEED002_H */
