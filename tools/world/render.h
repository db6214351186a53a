/*
 * tools/world/render.h - the synthetic field world: renders camera frames of a
 * field model (include/fieldloc/field.h) seen by a catalogue camera
 * (include/fieldloc/camera.h) from a robot pose, with a per-pixel class mask
 * and the field border per column.  Ground truth (features, file format) is
 * in tools/world/truth.h.  Host only (double, malloc).
 *
 * Geometry: the SAME conventions as camera.h.  Robot frame x forward, y left,
 * z up, origin on the ground below the head pitch axis; the head yaws, then
 * pitches; the camera sits mount_x_mm forward of / mount_z_mm above the pitch
 * axis, tilted mount_tilt down; total downward tilt = mount_tilt +
 * head_pitch + pitch_offset (positive = look down).  Pixel centres at
 * integer (u, v), principal point cx_q4/16, cy_q4/16, focal focal_q4/16.
 * Every angle of a scene is a binary angle (fl_angle_t) and every sin/cos
 * the renderer uses is fl_sin_q30/fl_cos_q30 / 2^30, so the renderer and the
 * firmware projection agree to about 1e-9 and no libm transcendental enters
 * the geometry (deterministic on any IEEE-754 double machine).
 * Field frame: origin at the centre, x toward the +x goal, y left, mm;
 * robot heading counter-clockwise from +x.
 *
 * Determinism: everything random comes from render_scene_t.seed (per frame:
 * noise, JPEG-like blocks) and world_seed (the world: room clutter, carpet
 * texture, shadow patches) through the renderer's own PRNG and integer
 * hashes; rendering the same scene twice gives identical bytes.  The
 * arithmetic is IEEE double + - * / sqrt floor only (no libm
 * transcendentals, one random draw per statement), so other IEEE-754
 * machines give the same bytes too (checked under qemu on i686, mipsel and
 * big-endian mips by the suite `render`).
 *
 * Typical use:
 *     render_scene_t sc;
 *     render_frame_t fr;
 *     render_scene_default(&sc, fl_field_find("spl2013"),
 *                          fl_camera_model_find("nao4-bottom-320"));
 *     sc.robot_x_mm = -2000; sc.head.head_pitch = fl_angle_from_mdeg(10000);
 *     if (render_frame(&sc, &fr) == 0) {
 *         ... fr.view is an fl_image_t over fr.data; fr.mask, fr.border_v ...
 *         render_frame_free(&fr);
 *     }
 */
#ifndef FL_TOOLS_RENDER_H
#define FL_TOOLS_RENDER_H

#include "fieldloc/camera.h"
#include "fieldloc/field.h"
#include "fieldloc/image.h"

#include <stdint.h>
#include <stdio.h>

#define RENDER_MAX_ROBOTS 8

/* Per-pixel class of the surface hit by the ray through the pixel CENTRE
 * (no anti-aliasing in the mask). */
typedef enum {
    RENDER_CLASS_BACKGROUND = 0, /* beyond the carpet: floor, walls, furniture,
                                    people, clutter (incl. its greenish,
                                    yellowish and white decoys) */
    RENDER_CLASS_GREEN = 1,      /* carpet, unpainted */
    RENDER_CLASS_LINE = 2,       /* painted line: boundary, box, halfway,
                                    centre circle, penalty/centre marks */
    RENDER_CLASS_GOAL = 3,       /* goal posts and crossbar (the field's goal
                                    color: yellow, white on spl2020, sky-blue
                                    for one aibo2004 goal) */
    RENDER_CLASS_OBJECT = 4,     /* robots standing on the field */
    RENDER_CLASS_BALL = 5,       /* the ball */
    RENDER_CLASS_BEACON = 6,     /* aibo2004 corner beacons */
    RENDER_CLASS_COUNT = 7
} render_class_t;

/* Jersey colors of the robots. */
typedef enum {
    RENDER_JERSEY_RED = 0,
    RENDER_JERSEY_BLUE = 1
} render_jersey_t;

/* A robot standing on the field (NAO-sized on NAO cameras, AIBO-sized on
 * aibo-ers7): white and grey body parts, colored jersey. */
typedef struct {
    int32_t x_mm, y_mm;      /* field frame, position of the feet centre */
    fl_angle_t heading;      /* facing direction, CCW from +x */
    render_jersey_t jersey;
} render_robot_t;

/*
 * Scene description.  Everything is an integer so that the text form
 * (render_scene_write / render_scene_read) round-trips exactly.  Fill it
 * with render_scene_default, then change what the frame needs.
 */
typedef struct {
    const fl_field_t *field;            /* from fl_field_find */
    const fl_camera_model_t *camera;    /* from fl_camera_model_find; its
                                           size is the frame size */
    fl_pixel_format_t format;           /* output format of render_frame */

    /* robot pose, field frame */
    int32_t robot_x_mm, robot_y_mm;
    fl_angle_t robot_heading;           /* CCW from +x */
    /* camera pose (as the firmware gets it: fl_camera_pose_t) */
    fl_camera_pose_t head;              /* neck_height_mm, head_pitch (+ down),
                                           head_yaw (+ left), pitch_offset */

    uint32_t seed;                      /* per-frame randomness: sensor
                                           noise, JPEG-like blocks */
    uint32_t world_seed;                /* the room around the field (clutter
                                           layout), carpet texture and the
                                           shadow patches: keep it fixed over
                                           the frames of one walk */

    /* objects */
    int n_robots;                       /* 0..RENDER_MAX_ROBOTS */
    render_robot_t robots[RENDER_MAX_ROBOTS];
    int ball;                           /* 1: draw the ball at ball_x/y */
    int32_t ball_x_mm, ball_y_mm;       /* field frame */
    int background;                     /* 1: cluttered room beyond the carpet
                                           (default); 0: plain grey walls */
    int32_t clear_sides;                /* bit mask of room sides left without
                                           floor clutter and wall decoration
                                           (an observer's line of sight to the
                                           field): 1 the +x end, 2 the -x
                                           end, 4 the +y side, 8 the -y side;
                                           the other sides keep exactly the
                                           clutter they have with 0 (default) */

    /* photometry (integer units, see each) */
    int32_t gain_pct;           /* overall brightness, 100 = nominal */
    int32_t grad_x_pct;         /* brightness change from the left to the
                                   right edge, percent (vignette-free ramp) */
    int32_t grad_y_pct;         /* same, top to bottom */
    int32_t shadows;            /* 1: robots cast soft shadows and a few
                                   random soft shadow patches darken the
                                   carpet; 0: none */
    int32_t noise_x10;          /* sensor noise sigma, tenths of a level
                                   (per channel of Y/Cb/Cr) */
    int32_t jpeg;               /* JPEG-like 8x8 block quantization strength
                                   0 (off) .. 4 */
    int32_t blur_px;            /* motion blur length, pixels (0 = none) */
    fl_angle_t blur_dir;        /* motion direction in the image (0 = along
                                   +u, 16384 = along +v) */
    int32_t supersample;        /* n x n samples per pixel on edges, 1..4
                                   (default 3) */
} render_scene_t;

/* Default scene: no robots, no ball, cluttered background, nominal light,
 * shadows 1, noise_x10 15, jpeg 0, blur 0, supersample 3, format RGB888,
 * robot at the field centre facing +x, head: the camera's default stance
 * (camera->default_neck_height_mm and default_pitch_offset; 450 mm / 160 mm
 * for NAO / AIBO when the model has none), pitch 0 (humanoid head cameras
 * "acyut-*": RENDER_HUMANOID_HEAD_PITCH), yaw 0, seed 1,
 * world_seed 1.  NULL field or camera are allowed
 * here (render_frame rejects them). */
#define RENDER_HUMANOID_HEAD_PITCH 3641   /* 20 deg down, binary angle */
void render_scene_default(render_scene_t *sc, const fl_field_t *field,
                          const fl_camera_model_t *camera);

/* The camera a field's frames are rendered with when none is named: the
 * humanoid head camera "acyut-640" on seed 002's "hl3x2", NULL (the
 * caller's own default) for every other field. */
const char *render_field_camera(const fl_field_t *field);

/* The firmware camera for the scene's camera and head pose (what a
 * detector would use).  Returns fl_camera_init's status. */
fl_status_t render_scene_camera(const render_scene_t *sc, fl_camera_t *cam);

/* Scene text form: "key value..." lines (documented in fixtures/README.md),
 * '#' comments.  write returns 0 on success; read returns 0 and fills *sc
 * (starting from render_scene_default of the named field and camera), or -1
 * with a message in err (may be NULL). */
int render_scene_write(FILE *f, const render_scene_t *sc);
int render_scene_read(FILE *f, render_scene_t *sc, char *err, int err_len);
int render_scene_save(const char *path, const render_scene_t *sc);
int render_scene_load(const char *path, render_scene_t *sc, char *err, int err_len);

/* A rendered frame.  All buffers malloc'd by render_frame, released by
 * render_frame_free. */
typedef struct {
    int width, height;
    fl_pixel_format_t format;
    /* Pixels in `format`: RGB888 width*height*3 bytes, YUYV422 width*height*2,
     * planar YCbCr three full-resolution planes Y, Cb, Cr of width*height
     * bytes each, one after the other.  Rows are packed (stride = width *
     * bytes per pixel). */
    uint8_t *data;
    size_t size;             /* bytes in data */
    fl_image_t view;         /* a valid fl_image_t view of data */
    /* The same frame as RGB888 (width*height*3): identical to data for
     * RGB888; for YUYV/planar it is the frame before conversion (for
     * pictures). */
    uint8_t *rgb;
    uint8_t *mask;           /* width*height render_class_t values */
    /* Field border per column u: the first row v (0..height-1) whose
     * pixel-centre ray hits the carpet (the ground within the carpet
     * rectangle |x| <= length/2 + border, |y| <= width/2 + border), with
     * objects (robots, posts, ball) ignored; `height` when the column shows
     * no carpet.  Rows from border_v[u] down to border_end_v[u] - 1 are
     * carpet (except where an object stands in front). */
    int16_t *border_v;
    int16_t *border_end_v;   /* one past the last carpet row (height when
                                the carpet reaches the bottom of the image) */
    /* First row whose mask is GREEN or LINE (what a perfect scanner would
     * call the border with occluders in front); height if none. */
    int16_t *border_visible_v;
} render_frame_t;

/* Render the scene.  0 on success; -1 on bad input (NULL, unknown field or
 * camera, invalid head pose, odd width with YUYV), with *out zeroed. */
int render_frame(const render_scene_t *sc, render_frame_t *out);
void render_frame_free(render_frame_t *fr);

/* Class of the surface at the ray through pixel (u, v) (double pixel
 * coordinates, pixel-centre convention): what the mask holds at integer
 * (u, v).  Also gives the ground/field point hit when the class is GREEN or
 * LINE (field frame, mm) when field_xy is not NULL.  For tests. */
render_class_t render_classify_pixel(const render_scene_t *sc, double u,
                                     double v, double field_xy[2]);

/* Projection of a 3D point (field frame, mm, z up) to a pixel (double,
 * pixel-centre convention) with the renderer's geometry; 0 when behind the
 * camera.  range_mm (may be NULL) receives the distance from the camera. */
int render_project_field(const render_scene_t *sc, double fx, double fy,
                         double fz, double *u, double *v, double *range_mm);

/* Field frame <-> robot frame (mm) for the scene's robot pose. */
void render_field_to_robot(const render_scene_t *sc, double fx, double fy,
                           double *rx, double *ry);
void render_robot_to_field(const render_scene_t *sc, double rx, double ry,
                           double *fx, double *fy);

/* Is the straight segment from the camera to the field point (fx, fy, fz)
 * blocked by an object (robot, post, crossbar, ball, beacon) nearer than
 * the point itself, minus tolerance_mm?  exclude_landmark >= 0 ignores that
 * landmark's post or beacon (used for a post's own foot). */
int render_occluded(const render_scene_t *sc, double fx, double fy, double fz,
                    double tolerance_mm, int exclude_landmark);

/* Frame files.  RGB888 -> binary PPM (P6).  YUYV422 and planar -> the raw
 * container: one text line "FLRAW <yuyv|planar> <width> <height>\n"
 * followed by the bytes of render_frame_t.data.  0 on success. */
int render_write_frame(const char *path, const render_frame_t *fr);
/* Read either kind back (PPM or FLRAW); fills width, height, format, data,
 * size and view (other buffers NULL).  0 on success, -1 with err. */
int render_read_frame(const char *path, render_frame_t *fr, char *err,
                      int err_len);

/* Names: "rgb", "yuyv", "planar" <-> fl_pixel_format_t (0 if unknown). */
const char *render_format_name(fl_pixel_format_t f);
fl_pixel_format_t render_format_from_name(const char *name);
const char *render_class_name(render_class_t c);

/* The committed fixture set (tools/world/fixtures.c; written by `make fixtures`): the
 * i-th fixture's scene, name (file stem under fixtures/frames/) and a short
 * description.  0 on success, -1 when i is out of range. */
int render_fixture_count(void);
int render_fixture_get(int i, render_scene_t *sc, const char **name,
                       const char **description);

/* Default colors (sRGB 0..255), measured from the UvA 2013 images; see
 * tools/world/render.c for the measurement. */
extern const uint8_t render_color_carpet[3];
extern const uint8_t render_color_line[3];
extern const uint8_t render_color_goal_yellow[3];

#endif /* FL_TOOLS_RENDER_H */
