/*
 * tools/cli/cmd_detect.c - `fieldloc detect [--field NAME] [--camera NAME]
 * [--head PITCH_RAD YAW_RAD] [--neck MM] [--picture OUT.ppm] [--stats]
 * [--repeat N] IMAGE`: runs the
 * firmware vision path on one frame and prints one feature per line,
 * tab-separated:
 *     kind  u  v  confidence  range_mm  bearing_deg
 * kind L T X (penalty and centre marks are X) G (post foot) U (post top)
 * C (centre-circle centre, printed when inside the image); u v pixels of the input image (pixel centres at
 * integers, 1 decimal); confidence 0..1 (2 decimals); range_mm integer
 * ground range from the robot origin; bearing_deg 1 decimal, positive =
 * left.  This format is read by external evaluation: keep it stable.
 *
 * IMAGE: binary PPM, or an FLRAW fixture frame (yuyv / planar).  Defaults:
 * field uva2013, camera uva2013 (the UvA 2013 dataset of seed 000); head
 * pitch and yaw 0, except -0.54 rad pitch for camera uva2013 (the
 * dataset's HeadPitch); the neck height and pitch offset are the
 * camera model's defaults (default_neck_height_mm, default_pitch_offset)
 * unless --neck MM gives the neck height.
 * --calib CALIB applies a per-robot calibration (fieldloc/calib.h, written by
 * `fieldloc calibrate --out`; its camera must be --camera's) after the
 * defaults and before --neck; a file that does not parse is refused with
 * "FILE:LINE: reason" (exit status 2).
 * --colors FILE reads the colour classes from a colour file (fieldloc/color.h,
 * `fieldloc colors` writes the defaults): keys it leaves out keep their
 * defaults; a file that does not parse: "fieldloc detect: FILE:LINE:
 * reason", exit status 2.
 * --stats prints the stage counters to stderr; --repeat N runs the path N
 * times (for callgrind: instructions per frame).
 */
#include "eval/detect.h"
#include "eval/calib_frames.h"
#include "io/ppm.h"
#include "cli/registry.h"
#include "world/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int detect_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc detect [--field NAME] [--camera NAME] [--head PITCH_RAD YAW_RAD]\n"
            "                       [--neck MM] [--calib CALIB] [--colors FILE] [--picture OUT.ppm]\n"
            "                       [--stats] [--repeat N] IMAGE.ppm\n"
            "  prints: kind<TAB>u<TAB>v<TAB>confidence<TAB>range_mm<TAB>bearing_deg\n"
            "  kind L T X G (post foot) U (post top) C (circle centre)\n");
    return 2;
}

int cmd_detect(int argc, char **argv)
{
    const char *field_name = "uva2013", *cam_name = "uva2013", *path = NULL,
               *picture = NULL, *calib_path = NULL, *colors_path = NULL;
    fl_calib_t calib;
    fl_color_params_t colors;
    double pitch = 0, yaw = 0;
    int i, n, stats = 0, rc = 0, repeat = 1, head_given = 0, neck = 0;
    const fl_field_t *field;
    const fl_camera_model_t *m;
    fl_camera_t cam;
    render_frame_t fr;
    char err[256];
    det_ctx_t ctx;
    det_feature_t feat[DET_MAX_FEATURES];
    fl_obs_list_t obs;

    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--field") && i + 1 < argc)
            field_name = argv[++i];
        else if (!strcmp(argv[i], "--camera") && i + 1 < argc)
            cam_name = argv[++i];
        else if (!strcmp(argv[i], "--head") && i + 2 < argc) {
            pitch = atof(argv[++i]);
            yaw = atof(argv[++i]);
            head_given = 1;
        } else if (!strcmp(argv[i], "--calib") && i + 1 < argc)
            calib_path = argv[++i];
        else if (!strcmp(argv[i], "--colors") && i + 1 < argc)
            colors_path = argv[++i];
        else if (!strcmp(argv[i], "--picture") && i + 1 < argc)
            picture = argv[++i];
        else if (!strcmp(argv[i], "--stats"))
            stats = 1;
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
            repeat = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--neck") && i + 1 < argc)
            neck = atoi(argv[++i]);
        else if (argv[i][0] == '-' && argv[i][1] != '\0')
            return detect_usage();
        else if (!path)
            path = argv[i];
        else
            return detect_usage();
    }
    if (!path)
        return detect_usage();
    field = fl_field_find(field_name);
    if (!field) {
        fprintf(stderr, "detect: unknown field %s (see: fieldloc fields)\n", field_name);
        return 2;
    }
    m = fl_camera_model_find(cam_name);
    if (!m) {
        fprintf(stderr, "detect: unknown camera %s (see: fieldloc cameras)\n", cam_name);
        return 2;
    }
    if (calib_path) {
        if (cf_calib_load(calib_path, &calib, err, sizeof err) != 0) {
            fprintf(stderr, "detect: %s\n", err);
            return 2;
        }
        if ((calib.has & FL_CALIB_HAS_CAMERA) && strcmp(calib.camera, m->name) != 0) {
            fprintf(stderr, "detect: %s is for camera %s, not %s\n", calib_path, calib.camera,
                    m->name);
            return 2;
        }
    }
    if (colors_path && det_colors_load(colors_path, &colors, err, sizeof err) != 0) {
        fprintf(stderr, "fieldloc detect: %s\n", err);
        return 2;
    }
    if (render_read_frame(path, &fr, err, sizeof err) != 0) {
        fprintf(stderr, "detect: %s: %s\n", path, err);
        return 1;
    }
    if (fr.width != m->width_px || fr.height != m->height_px) {
        fprintf(stderr, "detect: image %dx%d does not match camera %s (%dx%d)\n", fr.width,
                fr.height, m->name, (int)m->width_px, (int)m->height_px);
        render_frame_free(&fr);
        return 2;
    }
    if (!head_given && !strcmp(m->name, "uva2013"))
        pitch = -0.54;  /* the dataset's HeadPitch (see realdata/SOURCES.md) */
    if (det_camera(&cam, m, pitch, yaw) != FL_OK) {
        fprintf(stderr, "detect: invalid head pose\n");
        render_frame_free(&fr);
        return 2;
    }
    if (calib_path) {
        fl_camera_pose_t pose = cam.pose;
        if (fl_calib_apply(&calib, &pose) != FL_OK || fl_camera_init(&cam, m, &pose) != FL_OK) {
            fprintf(stderr, "detect: invalid head pose with %s\n", calib_path);
            render_frame_free(&fr);
            return 2;
        }
    }
    if (neck > 0) {  /* --neck MM: another neck height than the model's default */
        fl_camera_pose_t pose = cam.pose;
        pose.neck_height_mm = neck;
        if (fl_camera_init(&cam, m, &pose) == FL_OK)
            neck = 0;
    }
    if (neck > 0) {
        fprintf(stderr, "detect: invalid head pose\n");
        render_frame_free(&fr);
        return 2;
    }
    if (det_ctx_init(&ctx) != 0) {
        fprintf(stderr, "detect: out of memory\n");
        render_frame_free(&fr);
        return 1;
    }
    if (colors_path && det_ctx_set_colors(&ctx, &colors) != 0) {  /* parsed: valid */
        fprintf(stderr, "fieldloc detect: %s: colour classes refused\n", colors_path);
        det_ctx_free(&ctx);
        render_frame_free(&fr);
        return 2;
    }
    /* --repeat N: run the path N times (callgrind: instructions per frame) */
    for (i = 1; i < repeat; i++)
        fl_vision_frame(ctx.vis, ctx.colors, &fr.view, &cam, field, &obs);
    n = det_run(&ctx, &fr.view, &cam, field, &obs, feat, DET_MAX_FEATURES);
    for (i = 0; i < n; i++)
        printf("%c\t%.1f\t%.1f\t%.2f\t%d\t%.1f\n", feat[i].kind, feat[i].u, feat[i].v,
               feat[i].confidence, (int)feat[i].range_mm, feat[i].bearing_deg);
    if (stats) {
        const fl_vision_t *v = ctx.vis;
        fprintf(stderr,
                "# points %d (dropped %d, width-rejected %d) segments %d (merges %d, white checks %d) "
                "crossings %d (pairs %d, ground-rejected %d, arm-rejected %d, merged %d) "
                "posts %d (candidates %d) circle %s (cand %d, rms %d mm) obs %d\n",
                (int)v->lines.n_points, (int)v->lines.points_dropped,
                (int)v->lines.runs_rejected, (int)v->lines.n_segments, (int)v->lines.merges,
                (int)v->lines.white_checks,
                (int)v->crossings.n, (int)v->crossings.pairs, (int)v->crossings.rejected_ground,
                (int)v->crossings.rejected_arms, (int)v->crossings.merged, (int)v->posts.n,
                (int)v->posts.candidates, v->circle.found ? "found" : "no",
                (int)v->circle.n_cand, (int)v->circle.rms_mm, (int)obs.n);
    }
    if (picture) {
        uint8_t *rgb = det_rgb_copy(&fr.view);
        if (!rgb) {
            rc = 1;
        } else {
            size_t len = strlen(picture);
            det_draw(&ctx, rgb, fr.width, fr.height, &cam, field);
            if (len > 4 && !strcmp(picture + len - 4, ".png")) {
                if (png_write(picture, rgb, fr.width, fr.height) != 0) {
                    fprintf(stderr, "detect: cannot write %s (PNG needs OpenCV)\n", picture);
                    rc = 1;
                }
            } else if (ppm_write(picture, rgb, fr.width, fr.height) != 0) {
                fprintf(stderr, "detect: cannot write %s\n", picture);
                rc = 1;
            }
            free(rgb);
        }
    }
    det_ctx_free(&ctx);
    render_frame_free(&fr);
    return rc;
}
