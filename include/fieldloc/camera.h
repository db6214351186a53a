/*
 * fieldloc/camera.h - pinhole camera model in fixed point: pixel -> ground
 * point (robot frame, mm) -> range and bearing, and back.
 *
 * Frames.  Image: u right, v down, pixel centres at integer coordinates, the
 * top-left pixel centre at (0, 0); sub-pixel positions are Q4 (1/16 px).
 * Robot (ground) frame: origin on the ground directly below the head pitch
 * axis, x forward, y left, z up, millimetres.  Camera frame: x along the
 * optical axis, y to the image's left, z to the image's top.
 *
 * Angles are right-handed rotations about those axes (the NAOqi
 * convention): a positive rotation about z turns x towards y (yaw, left
 * positive), about y turns x down (pitch, down positive, like HeadPitch),
 * about x turns y up (roll: the left side rises, i.e. leaning to the
 * right; the image content then turns counter-clockwise, and the horizon
 * rises towards the image's right edge).  A NAO's inertial unit reports its
 * torso's AngleX / AngleY in this convention: AngleX is torso_roll
 * (positive = leaning right), AngleY is torso_pitch (positive = leaning
 * forward).
 *
 * Two ways to place a camera:
 *  - fl_camera_init_extrinsics: the camera's own position and orientation
 *    in the robot frame (fl_camera_extrinsics_t), e.g. from a robot's
 *    forward kinematics: R = Rz(yaw) * Ry(pitch) * Rx(roll) maps camera
 *    axes to robot axes (ZYX Euler angles of the camera frame).
 *  - fl_camera_init: a head pose (fl_camera_pose_t), through this chain:
 *    the torso tilts about the head pitch axis by Ry(torso_pitch) *
 *    Rx(torso_roll); in the torso the head yaws (head_yaw) about the neck
 *    and pitches (head_pitch + pitch_offset) about its y axis; the camera
 *    sits mount_x_mm forward of and mount_z_mm above the pitch axis, looks
 *    mount_tilt below the head's horizontal and is rolled by roll_offset
 *    about its optical axis.  Without torso angles and roll offset the
 *    total downward tilt of the optical axis is mount_tilt + head_pitch +
 *    pitch_offset.  The pivot is the head pitch axis, not the feet: the
 *    robot frame's origin is defined under that axis and neck_height_mm is
 *    its measured height, so a torso tilt turns the camera about a fixed
 *    point and leaves both definitions intact (a lean about the feet only
 *    moves that point, which the caller's neck height and odometry already
 *    describe).
 *
 * Lens distortion is not modelled (NAO and AIBO cameras are near pinhole at
 * these resolutions).
 *
 * Your own camera.  Fill an fl_camera_model_t from your intrinsics (no
 * catalogue entry needed; the name is only for messages):
 *     focal_q4 = round(16 * fx), fx in px (square pixels); from a field of
 *                view: fx = (W / 2) / tan(HFOV / 2)
 *     cx_q4, cy_q4 = 16 * principal point in the pixel-centre convention
 *                above (the image centre is (W - 1) / 2, (H - 1) / 2)
 *     mount_x_mm, mount_z_mm, mount_tilt = the camera relative to the head
 *                pitch axis (all 0 when you use fl_camera_init_extrinsics)
 *     default_neck_height_mm, default_pitch_offset = your usual stance
 * e.g. a 640x480 camera with a 60 deg horizontal field of view, principal
 * point at the centre, placed by kinematics:
 *     fl_camera_model_t m = {"mycam", 640, 480, 8868, 5112, 3832,
 *                            0, 0, 0, 450, 0};
 *     fl_camera_extrinsics_t e = {20, 0, 480, 0, fl_angle_from_mdeg(25000),
 *                                 fl_angle_from_mdeg(-2000)};
 *     fl_camera_init_extrinsics(&cam, &m, &e);
 * (320 / tan 30 deg = 554.26 px -> 8868.)
 */
#ifndef FIELDLOC_CAMERA_H
#define FIELDLOC_CAMERA_H

#include "fieldloc/common.h"
#include "fieldloc/fixed.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Intrinsics and mounting of one camera at one resolution (catalogue data). */
typedef struct {
    const char *name;      /* e.g. "nao4-bottom-320" */
    int32_t width_px;
    int32_t height_px;
    int32_t focal_q4;      /* focal length, 1/16 px (square pixels) */
    int32_t cx_q4;         /* principal point u, 1/16 px */
    int32_t cy_q4;         /* principal point v, 1/16 px */
    int32_t mount_x_mm;    /* camera forward of the head pitch axis */
    int32_t mount_z_mm;    /* camera above the head pitch axis */
    fl_angle_t mount_tilt; /* optical axis below the head horizontal */
    /* added: the default pose of this camera for callers that have no
     * better value (the CLI's --camera NAME alone, rd_uva_camera_pose):
     * the head pitch axis above the ground in the robot's usual stance
     * (NAO StandInit, AIBO standing) and the extra downward tilt.  For a
     * calibrated model ("uva2013") they are the fitted values; for the
     * others nominal values (src/model/camera.c).  Not read by fl_camera_init. */
    int32_t default_neck_height_mm; /* FL_CAMERA_NECK_MIN_MM..MAX_MM */
    fl_angle_t default_pitch_offset; /* positive = tilted further down */
} fl_camera_model_t;

/* Where the head is (per frame, from joint sensors and the inertial unit).
 * Zero torso angles and roll offset give the head-only model. */
typedef struct {
    int32_t neck_height_mm;  /* head pitch axis above the ground, 50..2000 */
    fl_angle_t head_pitch;   /* NAOqi HeadPitch, positive = look down */
    fl_angle_t head_yaw;     /* NAOqi HeadYaw, positive = look left */
    fl_angle_t pitch_offset; /* extra downward tilt: torso lean, calibration */
    fl_angle_t roll_offset;  /* calibration: extra roll of the camera, same sign as torso_roll */
    fl_angle_t torso_pitch; /* IMU: torso pitch, positive = leaning forward */
    fl_angle_t torso_roll; /* IMU: torso roll */
} fl_camera_pose_t;

/* The camera itself in the robot frame (per frame, e.g. from forward
 * kinematics): the optical centre and the ZYX Euler angles of the camera
 * frame, R = Rz(yaw) * Ry(pitch) * Rx(roll) (see the top of this file). */
typedef struct {
    int32_t x_mm;     /* optical centre, robot frame; |x|, |y| <= FL_CAMERA_MAX_XY_MM */
    int32_t y_mm;
    int32_t z_mm;     /* height above the ground, 1..FL_CAMERA_MAX_Z_MM */
    fl_angle_t yaw;   /* heading of the optical axis, positive = left */
    fl_angle_t pitch; /* optical axis below the horizontal, -90..+90 deg */
    fl_angle_t roll;  /* about the optical axis, positive = left side up
                       * (image content turns counter-clockwise);
                       * |roll| <= FL_CAMERA_MAX_ROLL */
} fl_camera_extrinsics_t;

/* Largest range reported by pixel_to_ground, mm; farther points (rays that
 * graze the horizon) count as "no ground point". */
#define FL_CAMERA_MAX_RANGE_MM 20000

/* A camera ready to project: model, pose and derived quantities.  Fields
 * after `pose` are private.  For a camera from fl_camera_init_extrinsics,
 * pose holds neck_height_mm = z_mm, head_yaw = yaw, head_pitch = pitch,
 * roll_offset = roll and zeros (vision reads head_yaw as the view's
 * heading). */
typedef struct {
    fl_camera_model_t model;
    fl_camera_pose_t pose;
    int32_t rot_q30[3][3];   /* camera (x optical, y left, z up) -> robot */
    int32_t pos_q4[3];       /* camera centre in the robot frame, 1/16 mm */
} fl_camera_t;

/* Catalogue: NAO v3/v4/v6 top and bottom at 320x240 and 640x480 (NAO v6
 * also at 1280x960: "nao6-top-1280", "nao6-bottom-1280"), the AIBO
 * ERS-7 camera at 208x160, plus calibrated models.
 * Names: "nao3-top-320", "nao4-bottom-640", "aibo-ers7", ...,
 * "uva2013" (the UvA 2013 dataset's NAO v4 bottom camera at 320x240,
 * calibrated from the hand labels by `fieldloc calibrate`; use it with its
 * default pose and each frame's head angles). */
const fl_camera_model_t *fl_camera_model_find(const char *name);
size_t fl_camera_model_count(void);
const fl_camera_model_t *fl_camera_model_at(size_t i);  /* NULL if out of range */

/* Validate model and pose and precompute the projection.  On error the
 * camera is left in a valid state that projects nothing (fl_vision_frame
 * refuses it: FL_ERR_CAMERA).  FL_ERR_CONFIG (common.h: the caller's
 * headers differ from the library's): nothing written. */
fl_status_t fl_camera_init_cfg(fl_camera_t *cam, const fl_camera_model_t *model,
                               const fl_camera_pose_t *pose, uint32_t caller_cfg);
static inline fl_status_t fl_camera_init(fl_camera_t *cam, const fl_camera_model_t *model,
                                         const fl_camera_pose_t *pose)
{
    return fl_camera_init_cfg(cam, model, pose, FL_CONFIG_FINGERPRINT);
}

/* The same from the camera's own position and orientation; the model's
 * mount fields are not used (the extrinsics already include the mount). */
fl_status_t fl_camera_init_extrinsics_cfg(fl_camera_t *cam, const fl_camera_model_t *model,
                                          const fl_camera_extrinsics_t *ext, uint32_t caller_cfg);
static inline fl_status_t fl_camera_init_extrinsics(fl_camera_t *cam,
                                                    const fl_camera_model_t *model,
                                                    const fl_camera_extrinsics_t *ext)
{
    return fl_camera_init_extrinsics_cfg(cam, model, ext, FL_CONFIG_FINGERPRINT);
}

/* Pixel (Q4) -> ground point in the robot frame (mm).  False when the ray
 * does not hit the ground in front of the camera within
 * FL_CAMERA_MAX_RANGE_MM (at or above the horizon). */
bool fl_camera_pixel_to_ground(const fl_camera_t *cam, int32_t u_q4,
                               int32_t v_q4, fl_point_t *ground);

/* Ground point (robot frame, mm) -> pixel (Q4).  False when the point is
 * behind the camera; a true result may still lie outside the image. */
bool fl_camera_ground_to_pixel(const fl_camera_t *cam, fl_point_t ground,
                               int32_t *u_q4, int32_t *v_q4);

/* Foot pixel (Q4) of a round upright object (a post, a beacon) of
 * diameter diameter_mm -> its centre on the ground: the foot's ground
 * point moved diameter_mm / 2 further along the ray, and the pixel moved
 * to that centre's projection (left as it was when that fails).  False
 * (nothing written) without a ground point.  Scaling: ground points are
 * within FL_CAMERA_MAX_RANGE_MM, so coordinate * (range + d / 2) fits
 * int64; the division rounds to nearest. */
bool fl_camera_foot_to_centre(const fl_camera_t *cam, int32_t *u_q4, int32_t *v_q4,
                              int32_t diameter_mm, fl_point_t *centre);

/* Row (v, Q4) of the horizon at column u_q4: pixels with v below (greater
 * than) this can see the ground.  Returns INT32_MIN when the whole column
 * is below the horizon and INT32_MAX when none of it can be.  With roll the
 * row differs per column (a straight line). */
int32_t fl_camera_horizon_v_q4(const fl_camera_t *cam, int32_t u_q4);

/* Topmost (smallest) horizon row over the columns u0_q4..u1_q4: the min of
 * the two ends.  Start a scan below it to miss no ground in those columns;
 * without roll it equals fl_camera_horizon_v_q4 at any column. */
int32_t fl_camera_horizon_top_v_q4(const fl_camera_t *cam, int32_t u0_q4, int32_t u1_q4);

/* Robot-frame point -> range (mm, rounded) and bearing (binary angle,
 * 0 = straight ahead, positive = left), and back. */
void fl_polar_from_point(fl_point_t p, int32_t *range_mm, fl_angle_t *bearing);
fl_point_t fl_point_from_polar(int32_t range_mm, fl_angle_t bearing);

/* ---- limits (see src/model/camera.c) -----------------------------------------
 * Validated by fl_camera_init (FL_ERR_RANGE beyond them) or enforced by the
 * projection calls (false beyond them), so that every 64-bit intermediate
 * stays in range; see "Scaling and overflow" in src/model/camera.c. */

/* Neck height range accepted by fl_camera_init, mm. */
#define FL_CAMERA_NECK_MIN_MM 50
#define FL_CAMERA_NECK_MAX_MM 2000
/* Largest focal length accepted by fl_camera_init, 1/16 px (65536 px). */
#define FL_CAMERA_MAX_FOCAL_Q4 (1L << 20)
/* Largest |mount_x_mm| and |mount_z_mm| accepted by fl_camera_init. */
#define FL_CAMERA_MAX_MOUNT_MM 1000
/* Largest |roll| of fl_camera_extrinsics_t, and of torso_pitch, torso_roll
 * and roll_offset each (45 deg); FL_ERR_RANGE beyond it: a robot leaning
 * that far is falling, and its frames are not worth localizing on. */
#define FL_CAMERA_MAX_ROLL FL_ANGLE_45
/* fl_camera_init_extrinsics: |x_mm|, |y_mm| <= FL_CAMERA_MAX_XY_MM, z_mm in
 * [1, FL_CAMERA_MAX_Z_MM] (Q4 positions below 2^15 and 2^16). */
#define FL_CAMERA_MAX_XY_MM 2000
#define FL_CAMERA_MAX_Z_MM 4000
/* fl_camera_init also requires the total downward tilt of the head part,
 * mount_tilt + head_pitch + pitch_offset (wrapped to a turn), to lie in
 * [-90, +90] deg, and both inits require the finished camera to be upright:
 * optical axis within 90 deg of the horizontal and roll within 90 deg (a
 * torso lean can push a steep head past them; the image is never upside
 * down, so the sky is always at the top and the horizon convention below
 * holds), and the principal point to lie in [0, 16*width_px] x
 * [0, 16*height_px] (Q4). */

/* Pixels farther than this from the principal point (|u_q4 - cx_q4| or
 * |v_q4 - cy_q4|, 1/16 px; i.e. 2^24 px) have no ground point, and
 * fl_camera_ground_to_pixel returns false for points that would project
 * farther out (nearly 90 degrees off the optical axis). */
#define FL_CAMERA_MAX_OFFSET_Q4 (1L << 28)
/* fl_camera_ground_to_pixel returns false for ground points with
 * |x_mm| or |y_mm| above this (10 km). */
#define FL_CAMERA_MAX_GROUND_MM 10000000L

/* fl_camera_horizon_v_q4 gives the exact row (the same integer test as
 * pixel_to_ground's ray test) even when it lies outside the image, e.g. a
 * negative row when the whole image is below the horizon: callers compare
 * v_q4 > row.  INT32_MIN / INT32_MAX are returned when no accepted pixel
 * row (|v_q4 - cy_q4| <= FL_CAMERA_MAX_OFFSET_Q4) is above / below the
 * horizon (optical axis vertical, or the horizon more than 2^24 px away),
 * for columns beyond FL_CAMERA_MAX_OFFSET_Q4, and for a camera that failed
 * init (INT32_MAX).  Without roll the row is the same for every column;
 * with roll it is a straight line over the columns. */

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_CAMERA_H */
