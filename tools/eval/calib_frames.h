/*
 * tools/eval/calib_frames.h - per-robot camera calibration from the user's
 * own frames taken at known poses (`fieldloc calibrate --frames FILE`):
 * fits the neck height, the pitch offset and the roll offset of a
 * catalogue camera to the field lines the firmware vision path detects.
 * Host only (double, malloc).
 *
 * Frames file (text, one frame per line; '#' starts a comment, blank lines
 * are skipped; words separated by spaces or tabs):
 *     IMAGE X_MM Y_MM HEADING_DEG HEAD_YAW_DEG HEAD_PITCH_DEG [TORSO_PITCH_DEG TORSO_ROLL_DEG]
 *   IMAGE     PPM (or FLRAW) frame of the camera's size; a relative path is
 *             relative to the folder of the frames file; no spaces
 *   X_MM Y_MM HEADING_DEG  robot pose, field frame (origin at the centre,
 *             x toward the +x goal, y left; heading CCW from +x)
 *   HEAD_YAW_DEG HEAD_PITCH_DEG  head joint angles in degrees, NAOqi signs
 *             (yaw positive = left, pitch positive = looking down)
 *   TORSO_PITCH_DEG TORSO_ROLL_DEG  optional torso angles from the IMU
 *             (fl_camera_pose_t.torso_pitch / torso_roll; 0 when absent)
 * Numbers are decimal (strtod), finite, |x|, |y| <= 20000 mm, |heading|
 * <= 360, head and torso angles within +-180 deg.  At most CF_MAX_FRAMES
 * frames, lines up to CF_LINE_MAX bytes.  Any other line is an error
 * "FILE:LINE: reason" (the whole file is refused).
 *
 * Residual.  Each frame is run through the vision path (fl_vision_frame)
 * with the start camera; its line points (white-run midpoints that belong
 * to a line segment) are the observations.  For parameters q, a point's
 * pixel is taken to the ground by the FIRMWARE projection
 * (fl_camera_pixel_to_ground with the pose q gives, so the fit uses exactly
 * the geometry the robot will), then to the field frame with the known
 * pose; the residual is its distance to the nearest painted line of the
 * field model (straight lines and the centre circle), converted to an
 * image-plane size by f / (distance from the camera): about pixels, so
 * near and far points weigh alike.  Points with a residual above gate_px
 * (robots, goals, background, wrong detections) are left out (trimmed,
 * re-decided at every step); the rest enter a Huber loss (huber_px).
 *
 * Fit: a grid over pitch offset (+-10 deg around the start, 0.5 deg) and
 * neck height (+-120 mm, 10 mm) with the truncated cost sum min(r, gate)^2,
 * then Levenberg-Marquardt (central differences of 16 binary-angle units
 * and 4 mm) on the fitted parameters; then the frames are detected again
 * with the fitted camera and the fit repeated from there (the detection's
 * width checks and horizon depend on the camera).  Uncertainty: the
 * diagonal of (J^T W J)^-1 scaled by the weighted residual variance.
 * Parameters move in the firmware's units (1 mm, 1/65536 turn).
 *
 * Pose errors (fit_heading): a robot put down by hand faces a few degrees
 * off and stands some centimetres off, which moves every point of its
 * frame and would bias the camera.  With fit_heading each frame also gets
 * a heading and x/y correction, nuisance parameters with Gaussian priors
 * (sigma_heading_deg, sigma_xy_mm; each as one pseudo-point of 1 px per
 * sigma).  They start from a +-10 deg heading grid and a per-frame LM
 * for the grid's camera, then everything is fitted jointly by LM (the
 * normal matrix is block-arrow shaped; each step eliminates the frames'
 * 3x3 blocks by the Schur complement; the camera's sigma comes from it,
 * so it accounts for the freedom of the poses); "before" residuals use
 * the poses as given.
 *
 * Memory: the frames array and the points of every frame (malloc'd).
 * Cost: 2 detections per frame; the grid evaluates every point about 900
 * times (a second or so for a few thousand points).
 */
#ifndef FL_TOOLS_CALIB_FRAMES_H
#define FL_TOOLS_CALIB_FRAMES_H

#include "fieldloc/fieldloc.h"
#include "io/realdata.h"

#include <stddef.h>

#define CF_PATH_MAX 1024
#define CF_LINE_MAX 2048
#define CF_MAX_FRAMES 4096

typedef struct {
    char image[CF_PATH_MAX];  /* path as used (folder of the file prepended) */
    int line;                 /* line of the frames file */
    double x_mm, y_mm, heading_deg;
    double head_yaw_deg, head_pitch_deg;
    double torso_pitch_deg, torso_roll_deg;
} cf_frame_t;

typedef struct {
    cf_frame_t *f;            /* malloc'd */
    int n;
} cf_frames_t;

/* Parse frames text (NUL-terminated, len bytes; a NUL inside is an error)
 * named `name` in messages; relative images get `dir` + "/" prepended
 * (dir NULL or "": as given).  0, or -1 with "NAME:LINE: reason" in err. */
int cf_frames_parse(const char *text, size_t len, const char *name, const char *dir,
                    cf_frames_t *out, char *err, int err_len);
/* Read and parse the file at path (images relative to its folder). */
int cf_frames_load(const char *path, cf_frames_t *out, char *err, int err_len);
void cf_frames_free(cf_frames_t *fr);

/* Camera parameters being fitted. */
typedef struct {
    double neck_mm;
    double pitch_offset_deg;
    double roll_offset_deg;
} cf_params_t;

typedef struct {
    int fit_neck, fit_pitch, fit_roll;  /* which parameters move (default all) */
    double gate_px;                     /* default 6 */
    double huber_px;                    /* default 1 */
    int grid;                           /* 1: start with the grid (default) */
    int fit_heading;                    /* 1: per-frame pose corrections
                                           (default 0: the poses are exact) */
    double sigma_heading_deg;           /* their priors: heading (default 5) */
    double sigma_xy_mm;                 /* and position (default 100) */
} cf_options_t;

void cf_options_default(cf_options_t *o);

/* Per-frame result of one parameter set. */
typedef struct {
    int n_points;       /* line points detected */
    int n_in;           /* within the gate */
    double median_px;   /* of the inliers' residuals */
    double rms_px;
} cf_stats_t;

typedef struct {
    cf_params_t start, fit;
    double sigma[3];          /* neck mm, pitch deg, roll deg (0 if not fitted) */
    cf_stats_t *before;       /* per frame (malloc'd, n entries): start params */
    cf_stats_t *after;        /* per frame: fitted params */
    cf_stats_t before_all, after_all;
    int n_frames, n_skipped;  /* frames used; frames not read / wrong size */
    int iterations;
    double *corr;             /* per frame heading deg, x mm, y mm (3 per
                                 frame), with fit_heading (else NULL) */
} cf_result_t;

/* Fit (start values in *p: usually the model's defaults, roll 0) to the
 * frames.  Frames whose image cannot be read or has the wrong size are
 * reported in err_frame (a message per frame through the callback when
 * not NULL) and skipped.  0 on success, -1 with a message in err when no
 * usable frame, too few points, or out of memory. */
typedef void (*cf_warn_fn)(const char *msg, void *user);
int cf_fit(const cf_frames_t *fr, const fl_field_t *field, const fl_camera_model_t *m,
           const cf_options_t *o, cf_params_t *p, cf_result_t *res, cf_warn_fn warn,
           void *user, char *err, int err_len);
void cf_result_free(cf_result_t *res);

/* The UvA 2013 hand-label records as a frame list (images in dir; records
 * whose PPM is not in the folder left out): pose from the file name, head
 * angles converted to degrees, no torso angles.  0, or -1 out of memory. */
int cf_frames_from_uva(const rd_uva_set_t *set, const char *dir, cf_frames_t *out);

/* Read a calibration file (fieldloc/calib.h format) with fl_calib_parse.
 * 0, or -1 with "PATH:LINE: reason" (or "PATH: reason") in err. */
int cf_calib_load(const char *path, fl_calib_t *c, char *err, int err_len);
/* Write c to path (fl_calib_format) with a leading comment line (may be
 * NULL).  0, or -1 with a message. */
int cf_calib_save(const char *path, const fl_calib_t *c, const char *comment, char *err,
                  int err_len);

/* The firmware camera pose of frame f with parameters p (neck rounded to
 * mm, angles to binary angles). */
void cf_pose(const cf_frame_t *f, const cf_params_t *p, fl_camera_pose_t *pose);

#endif
