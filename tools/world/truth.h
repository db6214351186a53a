/*
 * tools/world/truth.h - exact ground truth of a rendered frame (tools/world/render.h):
 * camera pose, field border per column, and every visible feature (L/T/X
 * crossings, penalty and centre marks, goal-post feet and tops, centre
 * circle centre and arc points, beacons, ball) with its pixel, its ground
 * position in the robot and field frames and the map landmark it is.
 * Host only.  File format: fixtures/README.md ("Truth files") and below.
 *
 * Which features are listed: every map landmark (and arc point, ball) whose
 * projected pixel lies inside the image (-0.5 <= u < width - 0.5, same for
 * v), in front of the camera and on the ground side of the horizon (post
 * tops may be above it).  Features hidden behind an object (robot, post,
 * ball; tested along the ray from the camera to the point) are listed with
 * occluded = 1: evaluation should neither require nor penalize them.
 *
 * Pixels are doubles in the pixel-centre convention of camera.h (the
 * top-left pixel centre is (0, 0)); multiply by 16 for the firmware's Q4.
 */
#ifndef FL_TOOLS_TRUTH_H
#define FL_TOOLS_TRUTH_H

#include "world/render.h"

#include <stdio.h>

#define TRUTH_MAX_FEATURES 256
#define TRUTH_MAX_WIDTH FL_IMAGE_MAX_DIM
/* Centre-circle arc points are sampled every 360/TRUTH_ARC_POINTS degrees
 * (starting at +x of the field frame); the visible ones are listed. */
#define TRUTH_ARC_POINTS 24

typedef enum {
    TRUTH_L = 0,            /* FL_LM_L */
    TRUTH_T = 1,            /* FL_LM_T */
    TRUTH_X = 2,            /* FL_LM_X */
    TRUTH_PENALTY_MARK = 3, /* FL_LM_PENALTY_MARK (centre of the cross) */
    TRUTH_CENTRE_MARK = 4,  /* FL_LM_CENTRE_MARK */
    TRUTH_POST_FOOT = 5,    /* FL_LM_POST: centre of the post base, z = 0 */
    TRUTH_POST_TOP = 6,     /* FL_LM_POST: centre of the post top,
                               z = post_height_mm (ground x/y = the foot's) */
    TRUTH_CIRCLE_CENTRE = 7,/* FL_LM_CENTRE_CIRCLE */
    TRUTH_CIRCLE_ARC = 8,   /* a point on the centre circle's line centre
                               (landmark = -1, arc index in `index`) */
    TRUTH_BEACON = 9,       /* FL_LM_BEACON: foot centre of the beacon */
    TRUTH_BALL = 10,        /* ball centre on the ground (landmark = -1) */
    TRUTH_KIND_COUNT = 11
} truth_kind_t;

typedef struct {
    truth_kind_t kind;
    int landmark;           /* index into field->landmarks, -1 if none */
    int index;              /* arc points: 0..TRUTH_ARC_POINTS-1; else 0 */
    double u, v;            /* pixel of the point (pixel-centre convention) */
    double robot_x_mm, robot_y_mm;  /* ground point, robot frame */
    double field_x_mm, field_y_mm;  /* ground point, field frame */
    double z_mm;            /* height of the pictured point (post tops) */
    double range_mm;        /* ground distance from the robot origin */
    fl_side_t side;         /* posts: FL_SIDE_LEFT / RIGHT (facing the goal) */
    int goal;               /* posts: +1 goal at +x, -1 at -x; else 0 */
    int occluded;           /* 1: hidden behind an object (see file top) */
} truth_feature_t;

typedef struct {
    char field[32];         /* field name */
    char camera[32];        /* camera model name */
    int width, height;
    int32_t robot_x_mm, robot_y_mm;   /* robot pose, field frame */
    fl_angle_t robot_heading;
    fl_camera_pose_t head;            /* as given to fl_camera_init */
    double cam_x_mm, cam_y_mm, cam_z_mm; /* camera centre, robot frame */
    double horizon_v;       /* row of the horizon (pixels with v > it see
                               the ground); may lie outside the image */
    /* Per column, as render_frame_t (see render.h): geometric carpet edge
     * (objects ignored), end of the carpet, first visible GREEN/LINE row;
     * height when none. */
    int16_t border_v[TRUTH_MAX_WIDTH];
    int16_t border_end_v[TRUTH_MAX_WIDTH];
    int16_t border_visible_v[TRUTH_MAX_WIDTH];
    int n;                  /* features */
    int dropped;            /* features beyond TRUTH_MAX_FEATURES */
    truth_feature_t f[TRUTH_MAX_FEATURES];
} truth_t;

/* Compute the truth of a scene.  frame (may be NULL) supplies the border
 * arrays from a render_frame of the same scene; when NULL they are computed
 * here by ray casting (same values).  0 on success, -1 on bad input. */
int truth_compute(const render_scene_t *sc, const render_frame_t *frame,
                  truth_t *t);

/* Text form (one item per line, '#' comments; see fixtures/README.md):
 *   fieldloc-truth 1
 *   field NAME
 *   camera NAME WIDTH HEIGHT
 *   robot X_MM Y_MM HEADING_BINANG
 *   head NECK_MM PITCH_BINANG YAW_BINANG PITCH_OFFSET_BINANG
 *   tilt TORSO_PITCH TORSO_ROLL ROLL_OFFSET  (binary angles; only when not all 0)
 *   camera_centre X Y Z            (robot frame, mm)
 *   horizon V                      (at the principal point's column)
 *   border V0 V1 ... V(width-1)
 *   border_end V0 ...
 *   border_visible V0 ...
 *   feature KIND LANDMARK INDEX U V RX RY FX FY Z RANGE SIDE GOAL OCCLUDED
 * KIND is truth_kind_name(); SIDE is 0/1/2 (fl_side_t); doubles with 3
 * decimals.  write returns 0 on success; read returns 0 or -1 with a message
 * in err (may be NULL). */
int truth_write(FILE *f, const truth_t *t);
int truth_read(FILE *f, truth_t *t, char *err, int err_len);
int truth_save(const char *path, const truth_t *t);
int truth_load(const char *path, truth_t *t, char *err, int err_len);

const char *truth_kind_name(truth_kind_t k);  /* "L", "T", ..., "?" */
int truth_kind_from_name(const char *name);   /* -1 if unknown */
/* Map landmark kind of a truth kind (posts: FL_LM_POST; arc points and ball:
 * FL_LM_KIND_COUNT). */
fl_landmark_kind_t truth_landmark_kind(truth_kind_t k);

#endif /* FL_TOOLS_TRUTH_H */
