/*
 * tools/io/realdata.h - host-only loader for the shared real-image folder
 * (../shared/realdata relative to the repository root): its PPM frames, the
 * UvA 2013 hand labels (uva2013_annotations.csv) and the physar 2024 poses
 * (physar_poses.csv).  Read /work/shared/realdata/SOURCES.md for what the
 * files are.  The images and labels may NOT be copied into the repository:
 * every tool reads them from the folder at run time and, when the folder is
 * absent, says so with rd_skip_message() and carries on (a skip is not a
 * failure).
 *
 * Locating the folder (rd_dir): $FIELDLOC_REALDATA when set and non-empty
 * (used as given: NULL when it is not a directory), else the first existing
 * directory of
 *     ../shared/realdata            (cwd = repository root: make test, CLI)
 *     ../../shared/realdata         (cwd = build/ or tools/)
 *     <P>/../shared/realdata for P = the 1st..3rd parent folder of the
 *                                   executable's folder (build/fieldloc
 *                                   or build/x/run_tests run from anywhere;
 *                                   Linux /proc/self/exe)
 * The result is a static string valid until the next rd_dir() call.
 *
 * UvA 2013 labels (rd_uva_*): one record per data row of
 * uva2013_annotations.csv ('#' comment lines and the header skipped).  The
 * pose comes from the original file name: x_cm, y_cm in the field frame
 * (origin at the centre, +x toward the goal seen at theta 0, y left),
 * theta_deg counter-clockwise; head_pitch_rad / head_yaw_rad are NAOqi
 * sensor angles (HeadPitch < 0 = head up, the same sign as
 * fl_camera_pose_t.head_pitch).  Features "TYPE:u,v" are 1-based MATLAB
 * ginput pixels in the 320x240 frame; the loader stores them 0-based
 * (u - 1, v - 1: the pixel-centre convention of camera.h).  Types:
 *     X  X crossing (also centre mark, penalty marks, halfway line x circle)
 *     L  L corner     T  T junction
 *     G  goal-post foot    U  goal-post top
 * The shared copy has 24 data rows (16 qvga, 4 straightwalk, 4 triwalk;
 * all in_realdata = 1) with 151 labels (X 26, L 43, T 34, G 32, U 16).
 *
 * physar 2024 poses (rd_physar_*): one record per row of physar_poses.csv,
 * NAO v6 at 640x480; field x/y in cm from OptiTrack (ot_field_*), the
 * README's nominal point and heading (heading approximate, see SOURCES.md),
 * head joint angles and IMU angles in rad.
 *
 * Modern frames (rd_modern_*): the project's own hand labels of the
 * non-UvA frames of the folder (physar, HTWK, NaoTH, dbloisi, scarrix), kept
 * in the repository as tools/eval/realdata_modern.csv (the images stay in
 * ../shared/realdata).  The UvA columns plus `camera` (a camera model name
 * of fl_camera_model_find: it fixes the resolution).  Differences to the
 * UvA file: features are 0-based pixel centres in the image's own
 * resolution (stored as written); the extra type B:u,v is the field border
 * (v = topmost carpet row of column u); the pose columns x_cm, y_cm,
 * theta_deg are all blank (no pose) or all numbers; head_pitch_rad and
 * head_yaw_rad likewise (blank: not known).  Checked: the camera exists,
 * every feature lies inside its image, n_features matches.  The file's
 * own comment lines give the labelling conventions.
 * Locating it (rd_modern_csv): $FIELDLOC_MODERN_CSV when set and non-empty,
 * else the first existing file of tools/eval/realdata_modern.csv,
 * ../tools/eval/realdata_modern.csv and <P>/tools/eval/realdata_modern.csv
 * for P = the 1st..3rd parent folder of the executable's folder.
 *
 * Errors: loaders return 0 on success and -1 with a one-line message in
 * err (may be NULL) otherwise; a malformed row is an error naming the line
 * (the files are small and curated: better loud than half-loaded).
 * Memory: rd_*_load mallocs the record array; free with rd_*_free.
 * Cost: linear in the file size.
 */
#ifndef FL_TOOLS_REALDATA_H
#define FL_TOOLS_REALDATA_H

#include "fieldloc/camera.h"
#include "fieldloc/image.h"
#include "io/ppm.h"

#include <stddef.h>
#include <stdio.h>

#define RD_UVA_CSV "uva2013_annotations.csv"
#define RD_PHYSAR_CSV "physar_poses.csv"
#define RD_NAME_MAX 160     /* longest file name stored (longer: error) */
#define RD_MAX_FEATURES 48  /* features per UvA row (more: error) */
#define RD_MODERN_CSV "realdata_modern.csv"   /* in tools/eval/ of the repository */
#define RD_MODERN_MAX_FEATURES 64             /* features per modern row (more: error) */

/* ---- the folder ---------------------------------------------------------- */

/* Path of the real-data folder, or NULL when absent (see above). */
const char *rd_dir(void);

/* The one skip message every tool and test prints when rd_dir() is NULL:
 * "skipped: ../shared/realdata not found (set FIELDLOC_REALDATA to its
 * path)".  Static string. */
const char *rd_skip_message(void);

/* dir + "/" + file into buf.  0 on success, -1 when it does not fit. */
int rd_path(char *buf, size_t buf_len, const char *dir, const char *file);

/* Read the PPM `file` of folder `dir` (ppm_read).  0 on success. */
int rd_read_ppm(const char *dir, const char *file, host_image_t *img,
                char *err, int err_len);

/* An FL_FMT_RGB888 view of a host image (no copy).  FL_OK or the status of
 * fl_image_init_packed. */
fl_status_t rd_image_view(const host_image_t *img, fl_image_t *view);

/* ---- UvA 2013 labels ----------------------------------------------------- */

typedef struct {
    char type;      /* 'X', 'L', 'T', 'G' or 'U'; modern rows also 'B' */
    double u, v;    /* pixel, 0-based (UvA: label - 1, 320x240 frame) */
} rd_feature_t;

typedef struct {
    char file[RD_NAME_MAX];  /* PPM file name in the folder */
    int in_realdata;         /* 1 when the PPM is in this folder */
    char set[32];            /* "qvga", "straightwalk", "triwalk" */
    char index[16];          /* image number as in the file, "000001" */
    double x_cm, y_cm;       /* robot position, field frame, cm */
    double theta_deg;        /* robot heading, CCW from +x, degrees */
    double head_pitch_rad;   /* NAOqi HeadPitch (negative = head up) */
    double head_yaw_rad;     /* NAOqi HeadYaw (positive = left) */
    int n_features;          /* = the n_features column (checked) */
    rd_feature_t feat[RD_MAX_FEATURES];
} rd_uva_record_t;

typedef struct {
    rd_uva_record_t *rec;    /* malloc'd, n entries */
    int n;
} rd_uva_set_t;

/* Parse the CSV text (NUL-terminated) / the file at path.  The feature
 * count of each row must equal its n_features column. */
int rd_uva_parse(const char *text, rd_uva_set_t *out, char *err, int err_len);
int rd_uva_load(const char *path, rd_uva_set_t *out, char *err, int err_len);
void rd_uva_free(rd_uva_set_t *set);

/* Robot pose of a record in fieldloc units: x_mm, y_mm (rounded) and the
 * heading as a binary angle (rounded).  Any pointer may be NULL. */
void rd_uva_pose(const rd_uva_record_t *r, int32_t *x_mm, int32_t *y_mm,
                 fl_angle_t *heading);

/* Camera pose of a record for a camera model: the record's head angles
 * (rounded to binary angles), the model's default neck height and pitch
 * offset (fl_camera_model_t.default_neck_height_mm / default_pitch_offset;
 * for camera "uva2013" these are the calibrated values). */
void rd_uva_camera_pose(const rd_uva_record_t *r, const fl_camera_model_t *m,
                        fl_camera_pose_t *pose);

/* Field frame point (mm) -> robot frame (mm, double) for a record's pose. */
void rd_uva_field_to_robot(const rd_uva_record_t *r, double fx_mm, double fy_mm,
                           double *rx_mm, double *ry_mm);

/* ---- physar 2024 poses --------------------------------------------------- */

typedef struct {
    char image_top[RD_NAME_MAX];     /* PPM of the top camera ("" if none) */
    char image_bottom[RD_NAME_MAX];  /* PPM of the bottom camera ("" if none) */
    char point[32];                  /* "black1_point1" */
    double nominal_x_cm, nominal_y_cm, nominal_heading_deg; /* README, approx */
    int ot_frame;                    /* OptiTrack frame number */
    double ot_field_x_cm, ot_field_y_cm;  /* OptiTrack, field frame, cm */
    double ot_height_m;              /* head marker height */
    double ot_rot_deg[3];            /* raw OptiTrack Euler X, Y, Z (see SOURCES.md) */
    double head_pitch_rad, head_yaw_rad;  /* NAO v6 joint sensors */
    double imu_anglex_rad, imu_angley_rad;
} rd_physar_record_t;

typedef struct {
    rd_physar_record_t *rec;
    int n;
} rd_physar_set_t;

int rd_physar_parse(const char *text, rd_physar_set_t *out, char *err, int err_len);
int rd_physar_load(const char *path, rd_physar_set_t *out, char *err, int err_len);
void rd_physar_free(rd_physar_set_t *set);

/* ---- modern frames (hand labels in the repository) ---------------------- */

typedef struct {
    char file[RD_NAME_MAX];  /* PPM file name in the real-data folder */
    int in_realdata;         /* 1 when the PPM is in that folder */
    char set[32];            /* source: "physar", "htwk", "naoth", "dbloisi", "scarrix" */
    char index[64];          /* short id, unique within the set */
    int has_pose;            /* 1: x_cm, y_cm, theta_deg given (else 0s) */
    double x_cm, y_cm, theta_deg;
    int has_head;            /* 1: head_pitch_rad, head_yaw_rad given (else 0s) */
    double head_pitch_rad, head_yaw_rad;   /* NAOqi signs (pitch > 0 = down) */
    char camera[32];         /* camera model name (fl_camera_model_find) */
    int n_features;
    rd_feature_t feat[RD_MODERN_MAX_FEATURES];   /* 0-based pixel centres */
} rd_modern_record_t;

typedef struct {
    rd_modern_record_t *rec;  /* malloc'd, n entries */
    int n;
} rd_modern_set_t;

/* Path of tools/eval/realdata_modern.csv (see above), or NULL.  Static
 * string valid until the next call. */
const char *rd_modern_csv(void);

int rd_modern_parse(const char *text, rd_modern_set_t *out, char *err, int err_len);
int rd_modern_load(const char *path, rd_modern_set_t *out, char *err, int err_len);
void rd_modern_free(rd_modern_set_t *set);

/* Labels of one type in a record (type 0: all). */
int rd_modern_count(const rd_modern_record_t *r, char type);

/* Camera pose of a modern record: its head angles (0 when not known), the
 * model's default neck height and pitch offset. */
void rd_modern_camera_pose(const rd_modern_record_t *r, const fl_camera_model_t *m,
                           fl_camera_pose_t *pose);

/* Camera pose of a physar record: the model's default neck height and pitch
 * offset, the record's head joint angles and its torso angles from the
 * inertial unit (imu_anglex = torso_roll, imu_angley = torso_pitch: the
 * NAOqi AngleX / AngleY convention of fieldloc/camera.h), all rounded to
 * binary angles. */
void rd_physar_camera_pose(const rd_physar_record_t *r, const fl_camera_model_t *m,
                           fl_camera_pose_t *pose);

#endif
