/*
 * tools/eval/calibrate.h - fit a NAO camera (neck height, pitch offset, focal
 * length, optionally principal point, yaw offset, roll, radial distortion)
 * and the field dimensions to hand-labelled features of the UvA 2013
 * images (realdata.h), host-only, double precision.
 *
 * Model (the geometry of fieldloc/camera.h, extended by a yaw offset, a
 * roll and one radial distortion term, all 0 in the firmware model):
 *   robot pose (x, y, theta) from the file name; a map point (field frame,
 *   mm, z up) goes to the robot frame; the camera centre is
 *   (0, 0, neck) + Rz(yaw) Ry(pitch) (mount_x, 0, mount_z) with
 *   pitch = head_pitch + pitch_offset, yaw = head_yaw + yaw_offset; the axes
 *   are Rz(yaw) Ry(mount_tilt + pitch) Rx(roll) (x optical, y left, z up);
 *   u = cx - f c_y / c_x, v = cy - f c_z / c_x, then
 *   (u, v) = c + (u - c)(1 + k1 r^2), r = |(u, v) - c| / f.
 * Post feet (G) and tops (U, at post_height_mm) are the point of the post's
 * surface nearest the camera (centre moved by the post radius toward the
 * camera): that is where a foot is clicked.
 *
 * Field dimensions are parameters too: every map landmark coordinate is a
 * signed sum of the dimensions (half length, half width, penalty area depth
 * and half width, penalty mark x, circle radius, post y) recognised from
 * the fl_field_t, so a fit can move e.g. the penalty marks; the post
 * height (for U labels) is a parameter too.
 *
 * Per-image pose corrections: the file-name poses were set by hand (the
 * walk sets even by the plan), and the labels show heading errors of several
 * degrees per image (a constant horizontal shift of all labels of an
 * image).  Optionally each image gets a heading and x/y correction, fitted
 * as nuisance parameters with a Gaussian prior (pseudo-residual
 * label_sigma_px * correction / sigma), so the camera parameters are not
 * biased by pose errors; residuals are then reported both with the
 * corrected and with the file-name poses.
 *
 * Association: each label is matched to the nearest projected map landmark
 * of its kind (X: X crossing, penalty mark or centre mark; L; T; G and U:
 * posts) under the current parameters, within a gate; the fit alternates
 * association and Levenberg-Marquardt (numeric Jacobian, Huber-weighted
 * IRLS), then flags outliers (residual > outlier_px) and refits without
 * them.  Initial values come from a grid search over pitch offset and neck
 * height with a truncated cost (the nominal DESIGN.md pitch is ~7 deg off).
 *
 * Memory: the problem's observation array and the normal matrices
 * (malloc'd).  Cost: a fit of the 24 images (151 labels, up to 15 + 72
 * parameters) takes well under a second.
 */
#ifndef FL_TOOLS_CALIBRATE_H
#define FL_TOOLS_CALIBRATE_H

#include "fieldloc/camera.h"
#include "fieldloc/field.h"
#include "io/realdata.h"

/* Parameter indices.  Angles in rad, lengths in mm, pixels 0-based. */
enum {
    CAL_NECK = 0,      /* head pitch axis above the ground, mm */
    CAL_PITCH,         /* pitch offset, rad, positive = further down */
    CAL_FOCAL,         /* focal length, px */
    CAL_CX, CAL_CY,    /* principal point, px (pixel-centre convention) */
    CAL_YAW,           /* yaw offset, rad, positive = left */
    CAL_ROLL,          /* roll about the optical axis, rad */
    CAL_K1,            /* radial distortion coefficient */
    CAL_HALF_L,        /* goal line x, mm */
    CAL_HALF_W,        /* touchline y, mm */
    CAL_PA_DEPTH,      /* penalty area depth, mm */
    CAL_PA_HALFW,      /* penalty area half width, mm */
    CAL_PM_X,          /* penalty mark x, mm */
    CAL_CIRCLE_R,      /* centre circle radius, mm */
    CAL_POST_Y,        /* post centre y (half the goal width), mm */
    CAL_POST_H,        /* post height (where U labels are), mm */
    CAL_NP
};
#define CAL_BIT(i) (1u << (i))
#define CAL_FIT_BASE (CAL_BIT(CAL_NECK) | CAL_BIT(CAL_PITCH) | CAL_BIT(CAL_FOCAL))
#define CAL_FIT_DIMS                                                              \
    (CAL_BIT(CAL_HALF_L) | CAL_BIT(CAL_HALF_W) | CAL_BIT(CAL_PA_DEPTH) |          \
     CAL_BIT(CAL_PA_HALFW) | CAL_BIT(CAL_PM_X) | CAL_BIT(CAL_CIRCLE_R) | CAL_BIT(CAL_POST_Y) |  \
     CAL_BIT(CAL_POST_H))

/* Short name of a parameter ("neck_mm", "pitch_offset_deg", ...). */
const char *cal_param_name(int i);
/* Value as printed: angles in degrees, others unchanged. */
double cal_param_display(int i, double v);

/* Most records a problem can hold (per-image pose corrections). */
#define CAL_MAX_REC 64
/* Per-image pose correction components (field frame). */
enum { CAL_POSE_TH = 0, CAL_POSE_X = 1, CAL_POSE_Y = 2 };
#define CAL_FIT_POSE_HEADING 1u
#define CAL_FIT_POSE_XY 2u

typedef struct {
    double p[CAL_NP];
    /* per-image correction of the file-name pose: heading (rad, CCW), x and
     * y (mm, field frame); all 0 = the poses as given */
    double pose[CAL_MAX_REC][3];
    double mount_x_mm, mount_z_mm, mount_tilt_rad; /* fixed: the mounting */
    double post_radius_mm;                         /* fixed: from the field */
} cal_params_t;

/* Parameters from a catalogue camera (focal, principal point, mount, its
 * default neck height and pitch offset) and a field (dimensions, posts). */
void cal_params_init(cal_params_t *p, const fl_camera_model_t *m, const fl_field_t *f);

/* A map point: coordinates as signed sums of the dimension parameters. */
typedef struct {
    char type;               /* 'X', 'L', 'T' or 'G' (post; U uses it too) */
    fl_landmark_kind_t kind;
    signed char ax[CAL_NP];  /* x = sum ax[k] p[k] (k: dimension indices) */
    signed char ay[CAL_NP];
} cal_landmark_t;

typedef struct {
    int rec, feat;       /* record and feature index in the set */
    char type;           /* label type */
    double u, v;         /* label, 0-based px */
    int lm;              /* matched landmark, -1 when none within the gate */
    int outlier;         /* 1 when flagged by the last fit */
    double du, dv;       /* projected - label, px, at the last fit */
} cal_obs_t;

typedef struct {
    const rd_uva_set_t *set;
    const fl_field_t *field;
    cal_landmark_t lm[64];
    int n_lm;
    cal_obs_t *obs;
    int n_obs;
} cal_problem_t;

/* Build the problem: one observation per label of every record.  0 on
 * success; -1 when a landmark of the field is not recognised as a sum of
 * its dimensions or on allocation failure. */
int cal_problem_init(cal_problem_t *pb, const rd_uva_set_t *set, const fl_field_t *f);
void cal_problem_free(cal_problem_t *pb);

/* Project landmark lm of the problem for record index rec (its file-name
 * pose corrected by p->pose[rec]); `top` selects the post top (U) instead
 * of the foot.  0 when in front of the camera. */
int cal_project(const cal_problem_t *pb, const cal_params_t *p, int rec, int lm, int top,
                double *u, double *v);
/* Project a robot-frame point (mm, z up) for record r's head angles. */
int cal_project_robot(const cal_params_t *p, const rd_uva_record_t *r, double x, double y,
                      double z, double *u, double *v);

typedef struct {
    unsigned fit_mask;   /* CAL_BIT()s of the parameters to fit */
    double gate_px;      /* association gate (default 40) */
    double huber_px;     /* Huber threshold of the IRLS weights (default 3) */
    double outlier_px;   /* residual above which a label is an outlier (8) */
    int exclude_rec;     /* record left out (leave-one-out), -1 for none */
    int grid_init;       /* 1: start with the pitch / neck grid search */
    unsigned pose_mask;  /* CAL_FIT_POSE_*: per-image pose corrections fitted
                            as nuisance parameters (default 0) */
    double sigma_heading_deg; /* their priors: heading (default 5 deg), */
    double sigma_xy_mm;       /* position (default 100 mm), */
    double label_sigma_px;    /* against a label noise of 2 px */
} cal_options_t;

void cal_options_default(cal_options_t *o);

typedef struct {
    double sigma[CAL_NP];  /* 1-sigma uncertainty of the fitted parameters */
    int n_used;            /* labels in the final fit (inliers, matched) */
    int n_outliers;        /* matched but residual > outlier_px */
    int n_unmatched;       /* no landmark of the kind within the gate */
    double rms_px;         /* RMS of the inlier residuals (2D distance) */
    int iterations;
} cal_result_t;

/* Fit p (in: start values, out: fitted) to the problem; observations get
 * their association, residual and outlier flag.  0 on success, -1 when
 * fewer labels than parameters were matched or the system is singular. */
int cal_fit(cal_problem_t *pb, const cal_options_t *o, cal_params_t *p, cal_result_t *res);

/* Re-associate and compute residuals of every observation for p (no fit;
 * outliers flagged by outlier_px; poses corrected by p->pose, zero them
 * for the file-name poses).  Returns the number matched. */
int cal_evaluate(cal_problem_t *pb, const cal_params_t *p, double gate_px, double outlier_px);

/* Median and max of the 2D residual of the matched observations whose type
 * is in `types` (e.g. "XLT", "G"); inliers only when inliers_only.  The
 * count is returned (0: median and max set to 0). */
int cal_residual_stats(const cal_problem_t *pb, const char *types, int inliers_only,
                       int rec, double *median, double *max);

#endif
