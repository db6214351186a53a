/*
 * tools/loc/physar.h - the physar black1 evaluation (`fieldloc localize
 * --physar`, host_tests localize.physar, docs/RESULTS.md): each point of
 * ../shared/realdata/physar_poses.csv is one real NAO v6 top frame
 * (640x480, camera nao6-top-640, field spl2020: 9 x 6 m, white goals)
 * repeated `repeat` times with zero odometry through one localizer, from
 * total ignorance; the last estimate is compared with the OptiTrack
 * position.  Host only.
 *
 * Per point:
 *   - camera pose: rd_physar_camera_pose (the record's head joint angles
 *     and the inertial unit's AngleX / AngleY as torso roll / pitch, the
 *     model's neck height and pitch offset); or the torso tilt from the
 *     record's accelerometer, or none (ph_imu_t).  On these five records
 *     AngleY is 0.086-0.089 rad below the accelerometer's pitch (a bias of
 *     the angle filter, the same at every point); the accelerometer's tilt
 *     fits the frames (on point 2 the far field edge sits where a 4 deg
 *     backward lean puts it, AngleY's 9 deg would put it at the horizon);
 *   - truth: OptiTrack x, y (field frame, mm) and the README's NOMINAL
 *     heading, which is approximate (SOURCES.md: the OptiTrack rotation
 *     could not be reconciled with it), so heading errors are approximate;
 *     at black1_point5 it is wrong: the frame shows the centre circle
 *     straight ahead and the far goal about 17 deg to the left, which from
 *     (-2096, 901) means a heading near -20 deg, not the nominal 135;
 *   - errors modulo the field's 180-degree point symmetry: position error =
 *     the smaller of the distances to the truth and to its mirror (-x, -y);
 *     the heading error is taken against the same choice (the truth's
 *     heading, or the mirror's, heading + 180), since the heading is the
 *     less certain half of the truth; the plain errors are kept as well;
 *   - features in view: vision's observations of the frame by kind (what
 *     the localizer is given), and, for information, the map landmarks
 *     that project at least 4 px inside the image from the truth pose
 *     with the nominal heading (wrong wherever the nominal heading is);
 *   - the goal: position error (modulo symmetry) <= PH_GOAL_MM wherever
 *     two or more features are in view (vision's count); a point with
 *     fewer features does not count.
 *
 * Vision runs on every repeat (as on the robot: any per-frame state of the
 * vision path, such as colour tracking, sees the frame again).
 * Cost: repeat x (vision on 640x480 + one localizer update) per point.
 */
#ifndef FL_TOOLS_PHYSAR_H
#define FL_TOOLS_PHYSAR_H

#include "io/realdata.h"
#include "loc/locrun.h"

#include <stdio.h>

#define PH_MAX_POINTS 16
#define PH_GOAL_MM 300.0
#define PH_FIELD "spl2020"
#define PH_CAMERA "nao6-top-640"
#define PH_REPEAT_DEFAULT 10

/* The torso angles of the camera pose. */
typedef enum {
    PH_IMU_ANGLES = 0,  /* the records' AngleX / AngleY (physar_poses.csv) */
    PH_IMU_ACCEL = 1,   /* tilt from the records' accelerometer (the
                           *_record.csv next to the frame): pitch =
                           atan2(accx, -accz), roll = atan2(-accy, -accz)
                           (NAOqi reports gravity: accz = -g upright) */
    PH_IMU_OFF = 2      /* 0: head angles only */
} ph_imu_t;

typedef struct {
    int repeat;                         /* frames per point, >= 1 */
    const void *params;                 /* the localizer's parameters; NULL:
                                           its vision preset (lr_params_frames) */
    const colors_opt_t *colors;         /* --colors (eval/colors_opt.h),
                                           resolved per point by its policy
                                           (auto on these frames when unset);
                                           NULL: as unset */
    const char *pictures;               /* folder for one picture per point
                                           (last frame), or NULL */
    ph_imu_t imu;                       /* where torso roll / pitch come from */
} ph_opts_t;

typedef struct {
    char point[32];                     /* "black1_point1" */
    char image[RD_NAME_MAX];
    double truth_x_mm, truth_y_mm;      /* OptiTrack */
    double truth_heading_deg;           /* nominal (approximate) */
    int ok;                             /* the frame was read and used */
    fl_loc_estimate_t est;              /* after the last repeat */
    double est_heading_deg;             /* (-180, 180] */
    double pos_err_mm, head_err_deg;    /* against the truth itself */
    double sym_pos_err_mm, sym_head_err_deg;  /* modulo symmetry */
    int mirror;                         /* 1: the mirror of the truth is closer */
    int seen[FL_LM_KIND_COUNT], n_seen; /* vision's observations (last frame) */
    int map[FL_LM_KIND_COUNT], n_map;   /* map landmarks in view (truth pose) */
    int used;                           /* observations applied (last frame) */
    double torso_roll_rad, torso_pitch_rad;  /* used in the camera pose */
    int goal_applies, goal_met;
} ph_point_t;

typedef struct {
    const char *localizer;              /* its name */
    ph_point_t pt[PH_MAX_POINTS];
    int n;
    int n_goal, n_met;                  /* points the goal applies to, met */
    double sym_rmse_mm, sym_max_mm;     /* over the points with a frame */
    double head_rmse_deg;               /* modulo symmetry, vs nominal */
} ph_result_t;

/* Run every point through loc (NULL: "fuzzy").  Returns 0 on success, 1
 * when the real-data folder is absent (rd_skip_message(); res->n = 0), -1
 * with a message in err on an unreadable CSV, an unknown field/camera or
 * a localizer that cannot be set up.  A point whose frame cannot be read
 * has ok = 0 and a message on stderr (it is not a run failure). */
int ph_run(const fl_localizer_t *loc, const ph_opts_t *o, ph_result_t *res, char *err,
           int err_len);

/* Kind letters of a count array ("L1 T2 X1 C1"; "-" when none), into buf. */
void ph_kinds(const int *count, char *buf, size_t n);

/* The table header, one line per point and the summary line (formats at
 * the top of tools/cli/cmd_localize.c). */
void ph_print_header(FILE *f, const ph_opts_t *o);
void ph_print_point(FILE *f, const ph_result_t *r, const ph_point_t *p);
void ph_print_summary(FILE *f, const ph_result_t *r);

#endif
