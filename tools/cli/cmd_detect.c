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
 * dataset's HeadPitch) and 20 deg down for the acyut cameras (the rendered
 * hl3x2 frames' stance; field hl3x2 defaults to camera acyut-640); the neck height and pitch offset are the
 * camera model's defaults (default_neck_height_mm, default_pitch_offset)
 * unless --neck MM gives the neck height.
 * --calib CALIB applies a per-robot calibration (fieldloc/calib.h, written by
 * `fieldloc calibrate --out`; its camera must be --camera's) after the
 * defaults and before --neck; a file that does not parse is refused with
 * "FILE:LINE: reason" (exit status 2).
 * --colors default|auto|FILE: the colour classes (eval/colors_opt.h: the 2013
 * boxes, the field colour from this frame, or a colour file whose keys
 * override the defaults; a file that does not parse: "fieldloc detect:
 * FILE:LINE: reason", exit status 2).  Without it: auto on fields with
 * white goals and on real frames that are not the UvA 2013 set, else
 * default.  With --stats the carpet estimate and the boxes are printed.
 * --stats prints the stage counters to stderr; --repeat N runs the path N
 * times (for callgrind: instructions per frame).
 * --picture OUT.ppm|.png draws the stages over the frame (det_draw) with a
 * legend strip below it; --show border,classes adds the scanner's field
 * border (and first searched row) and its class map (green / white /
 * yellow / other per grid cell), to see why a feature was or was not found.
 * Numbers are checked (tools/cli/args.h): --head within the NAO head joints
 * (the camera's limit for a non-NAO camera), --neck 50..2000 mm, --repeat
 * 1..1000000; a bad value or option exits with status 2.
 * --vision default|hl picks the vision path: seed 000's (vision.h) or seed
 * 002's (hlvision.h: posts, striped poles, the skeleton's crossings); by
 * default hl on field hl3x2, else default.  The hl path prints kinds G
 * (post foot), P (pole foot), X and T; --stats gives its counters and its
 * picture shows the mask, the skeleton, posts and poles (hldetect.h).
 * --imu ANGLEX ANGLEY gives the torso roll and pitch (rad, a NAO inertial
 * unit's AngleX / AngleY: fieldloc/camera.h), applied after --calib and
 * --neck; |angle| <= 45 deg (0.7854 rad).
 */
#include "cli/args.h"
#include "eval/colors_opt.h"
#include "eval/detect.h"
#include "eval/hldetect.h"
#include "eval/calib_frames.h"
#include "eval/picture.h"
#include "io/ppm.h"
#include "cli/registry.h"
#include "world/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int detect_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc detect [--field NAME] [--camera NAME] [--head PITCH_RAD YAW_RAD]\n"
            "                       [--neck MM] [--calib CALIB] [--colors default|auto|FILE]\n"
            "                       [--picture OUT.ppm]\n"
            "                       [--show border,classes] [--stats] [--repeat N] IMAGE.ppm\n"
            "  --head: NAO HeadPitch -0.6720..0.5149 rad, HeadYaw -2.0857..2.0857 rad\n"
            "  --neck 50..2000 mm, --repeat 1..1000000\n"
            "  --imu ANGLEX ANGLEY: torso roll and pitch, rad (NAO AngleX / AngleY)\n"
            "  --vision default|hl: seed 000's path or seed 002's (default: hl on hl3x2)\n"
            "  --calib: a calibration file from `fieldloc calibrate --out`\n"
            "  --colors: default (2013 boxes), auto (from the frame) or a colour file\n"
            "            (`fieldloc colors`, `fieldloc calibrate-colors`)\n"
            "  prints: kind<TAB>u<TAB>v<TAB>confidence<TAB>range_mm<TAB>bearing_deg\n"
            "  kind L T X G (post foot) U (post top) C (circle centre)\n");
    return 2;
}

/* --show LIST: comma-separated border, classes. */
static int detect_show(const char *list, int *border, int *classes)
{
    char buf[128], *tok, *save = NULL;
    snprintf(buf, sizeof buf, "%s", list);
    for (tok = strtok_r(buf, ",", &save); tok != NULL; tok = strtok_r(NULL, ",", &save)) {
        if (!strcmp(tok, "border"))
            *border = 1;
        else if (!strcmp(tok, "classes"))
            *classes = 1;
        else {
            fprintf(stderr, "fieldloc detect: --show: unknown layer \"%s\" (border, classes)\n",
                    tok);
            return -1;
        }
    }
    return 0;
}

/* The detection picture: the frame, the scanner layers asked for, the
 * stages (det_draw) on top, and the legend strip below. */
static int detect_picture(const det_ctx_t *ctx, const render_frame_t *fr, const fl_camera_t *cam,
                          const fl_field_t *field, const fl_camera_model_t *m, const char *path,
                          int n_features, int show_border, int show_classes, const char *picture)
{
    host_image_t img, out;
    char caption[512];
    const char *base = strrchr(path, '/');
    size_t len = strlen(picture);
    int rc = 0;
    unsigned sets = PIC_LEGEND_DETECT;
    img.width = fr->width;
    img.height = fr->height;
    img.rgb = det_rgb_copy(&fr->view);
    if (!img.rgb)
        return 1;
    pic_scan_overlay(&ctx->vis->scan, img.rgb, fr->width, fr->height, show_classes, show_border);
    det_draw(ctx, img.rgb, fr->width, fr->height, cam, field);
    if (show_classes)
        sets |= PIC_LEGEND_CLASSES;
    if (show_border)
        sets |= PIC_LEGEND_BORDER;
    snprintf(caption, sizeof caption, "%s: %d features (field %s, camera %s)",
             base ? base + 1 : path, n_features, field->name, m->name);
    if (pic_add_legend(&img, sets, caption, &out) != 0) {
        free(img.rgb);
        return 1;
    }
    free(img.rgb);
    if (len > 4 && !strcmp(picture + len - 4, ".png")) {
        if (png_write(picture, out.rgb, out.width, out.height) != 0) {
            fprintf(stderr, "detect: cannot write %s\n", picture);
            rc = 1;
        }
    } else if (ppm_write(picture, out.rgb, out.width, out.height) != 0) {
        fprintf(stderr, "detect: cannot write %s\n", picture);
        rc = 1;
    }
    host_image_free(&out);
    return rc;
}

/* Write a picture with its legend strip, .png or .ppm by the name. */
static int detect_write(host_image_t *img, unsigned sets, const char *caption, const char *picture)
{
    host_image_t out;
    size_t len = strlen(picture);
    int rc = 0;
    if (pic_add_legend(img, sets, caption, &out) != 0)
        return 1;
    if (len > 4 && !strcmp(picture + len - 4, ".png") ? png_write(picture, out.rgb, out.width, out.height) != 0
                                                      : ppm_write(picture, out.rgb, out.width, out.height) != 0) {
        fprintf(stderr, "detect: cannot write %s\n", picture);
        rc = 1;
    }
    host_image_free(&out);
    return rc;
}

/* Seed 002's path (hlvision.h) on one frame: features, stats, picture. */
static int detect_hl(const render_frame_t *fr, const fl_camera_t *cam, const fl_field_t *field,
                     const fl_camera_model_t *m, const char *path, int repeat, int stats,
                     const char *picture)
{
    det_feature_t feat[DET_MAX_FEATURES];
    fl_obs_list_t obs;
    fl_hlv_t *hv = hld_new(field);
    int i, n, rc = 0;
    if (!hv) {
        fprintf(stderr, "detect: out of memory\n");
        return 1;
    }
    for (i = 1; i < repeat; i++)
        fl_hlv_frame(hv, &fr->view, cam, &obs);
    n = hld_run(hv, &fr->view, cam, &obs, feat, DET_MAX_FEATURES);
    for (i = 0; i < n; i++)
        printf("%c\t%.1f\t%.1f\t%.2f\t%d\t%.1f\n", feat[i].kind, feat[i].u, feat[i].v,
               feat[i].confidence, (int)feat[i].range_mm, feat[i].bearing_deg);
    if (stats)
        fprintf(stderr,
                "# hl status %s objects %d (dropped %u, runs dropped %u) mask %dx%d obs %d "
                "(dropped %u) points %d (dropped %u)\n",
                fl_status_str(hv->status), (int)hv->n_objects, (unsigned)hv->objects_dropped,
                (unsigned)hv->runs_dropped, (int)hv->mask_w, (int)hv->mask_h, (int)obs.n,
                (unsigned)obs.dropped, (int)obs.n_points, (unsigned)obs.points_dropped);
    if (picture) {
        host_image_t img;
        char caption[512];
        const char *base = strrchr(path, '/');
        img.width = fr->width;
        img.height = fr->height;
        img.rgb = det_rgb_copy(&fr->view);
        if (!img.rgb) {
            free(hv);
            return 1;
        }
        hld_draw(hv, &obs, img.rgb, fr->width, fr->height, cam);
        snprintf(caption, sizeof caption, "%s: %d features, %d white points (field %s, camera %s, seed 002 path)",
                 base ? base + 1 : path, n, (int)obs.n_points, field->name, m->name);
        rc = detect_write(&img, PIC_LEGEND_HLV, caption, picture);
        free(img.rgb);
    }
    free(hv);
    return rc;
}

int cmd_detect(int argc, char **argv)
{
    int cam_given = 0;
    const char *field_name = "uva2013", *cam_name = "uva2013", *path = NULL,
               *picture = NULL, *calib_path = NULL;
    fl_calib_t calib;
    colors_opt_t colors;
    fl_color_estimate_t est;
    double pitch = 0, yaw = 0;
    const char *head_text[2] = {NULL, NULL};
    int i, n, stats = 0, rc = 0, repeat = 1, head_given = 0, show_border = 0, show_classes = 0;
    int32_t neck = 0;
    double imu[2] = {0, 0};
    int imu_given = 0, hl = -1;
    const fl_field_t *field;
    const fl_camera_model_t *m;
    fl_camera_t cam;
    render_frame_t fr;
    char err[256];
    det_ctx_t ctx;
    det_feature_t feat[DET_MAX_FEATURES];
    fl_obs_list_t obs;

    memset(&colors, 0, sizeof colors);
    memset(&est, 0, sizeof est);
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--field") && i + 1 < argc)
            field_name = argv[++i];
        else if (!strcmp(argv[i], "--camera") && i + 1 < argc) {
            cam_name = argv[++i];
            cam_given = 1;
        }
        else if (!strcmp(argv[i], "--head") && i + 2 < argc) {
            /* numbers now, their range once the camera is known */
            head_text[0] = argv[++i];
            head_text[1] = argv[++i];
            if (arg_double("detect", "--head pitch", head_text[0], -1e9, 1e9, NULL, &pitch) ||
                arg_double("detect", "--head yaw", head_text[1], -1e9, 1e9, NULL, &yaw))
                return 2;
            head_given = 1;
        } else if (!strcmp(argv[i], "--imu") && i + 2 < argc) {
            if (arg_double("detect", "--imu anglex", argv[i + 1], -0.7854, 0.7854, "rad",
                           &imu[0]) ||
                arg_double("detect", "--imu angley", argv[i + 2], -0.7854, 0.7854, "rad",
                           &imu[1]))
                return 2;
            i += 2;
            imu_given = 1;
        } else if (!strcmp(argv[i], "--calib") && i + 1 < argc)
            calib_path = argv[++i];
        else if (!strcmp(argv[i], "--colors") && i + 1 < argc) {
            if (colors_opt_parse("detect", argv[++i], &colors) != 0)
                return 2;
        }
        else if (!strcmp(argv[i], "--picture") && i + 1 < argc)
            picture = argv[++i];
        else if (!strcmp(argv[i], "--stats"))
            stats = 1;
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc) {
            if (arg_int("detect", "--repeat", argv[++i], 1, 1000000, NULL, &repeat) != 0)
                return 2;
        } else if (!strcmp(argv[i], "--neck") && i + 1 < argc) {
            if (arg_int32("detect", "--neck", argv[++i], FL_CAMERA_NECK_MIN_MM,
                          FL_CAMERA_NECK_MAX_MM, "mm", &neck) != 0)
                return 2;
        } else if (!strcmp(argv[i], "--vision") && i + 1 < argc) {
            i++;
            if (!strcmp(argv[i], "hl"))
                hl = 1;
            else if (!strcmp(argv[i], "default"))
                hl = 0;
            else {
                fprintf(stderr, "fieldloc detect: --vision: unknown path \"%s\" (default, hl)\n",
                        argv[i]);
                return 2;
            }
        } else if (!strcmp(argv[i], "--show") && i + 1 < argc) {
            if (detect_show(argv[++i], &show_border, &show_classes) != 0)
                return 2;
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            detect_usage();
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0')
            return arg_unknown("detect", argv[i],
                               "--field=1 --camera=1 --head=2 --picture=1 --repeat=1 --neck=1 "
                               "--show=1 --calib=1 --colors=1 --imu=2 --vision=1");
        else if (!path)
            path = argv[i];
        else
            return arg_unknown("detect", argv[i], NULL);
    }
    if (!path)
        return detect_usage();
    field = fl_field_find(field_name);
    if (!field) {
        fprintf(stderr, "detect: unknown field %s (see: fieldloc fields)\n", field_name);
        return 2;
    }
    if (!cam_given && render_field_camera(field) != NULL)
        cam_name = render_field_camera(field);   /* hl3x2: its humanoid camera */
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
    if (head_given && arg_head("detect", "--head", m, head_text[0], head_text[1], &pitch, &yaw) != 0) {
        render_frame_free(&fr);
        return 2;
    }
    if (!head_given && !strcmp(m->name, "uva2013"))
        pitch = -0.54;  /* the dataset's HeadPitch (see realdata/SOURCES.md) */
    if (!head_given && !strncmp(m->name, "acyut-", 6))
        pitch = RENDER_HUMANOID_HEAD_PITCH * (2.0 * M_PI / 65536.0);  /* rendered hl3x2 frames */
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
    if (imu_given) {  /* --imu: torso roll and pitch from the inertial unit */
        fl_camera_pose_t pose = cam.pose;
        pose.torso_roll = fl_angle_from_urad((int32_t)lround(imu[0] * 1e6));
        pose.torso_pitch = fl_angle_from_urad((int32_t)lround(imu[1] * 1e6));
        if (fl_camera_init(&cam, m, &pose) != FL_OK) {
            fprintf(stderr, "detect: invalid head pose with --imu\n");
            render_frame_free(&fr);
            return 2;
        }
    }
    if (hl < 0)
        hl = hld_field_wants(field);
    if (hl) {
        rc = detect_hl(&fr, &cam, field, m, path, repeat, stats, picture);
        render_frame_free(&fr);
        return rc;
    }
    if (det_ctx_init(&ctx) != 0) {
        fprintf(stderr, "detect: out of memory\n");
        render_frame_free(&fr);
        return 1;
    }
    colors_opt_resolve(&colors, field, path);
    if (colors_opt_setup(&colors, ctx.colors, field, &fr.view, &cam, &est) < 0) {
        fprintf(stderr, "fieldloc detect: colour classes refused\n");
        det_ctx_free(&ctx);
        render_frame_free(&fr);
        return 2;
    }
    if (stats)
        colors_print_stats(stderr, &colors, ctx.colors, &est);
    /* --repeat N: run the path N times (callgrind: instructions per frame),
     * tracking the field colour after each */
    for (i = 1; i < repeat; i++) {
        fl_vision_frame(ctx.vis, ctx.colors, &fr.view, &cam, field, &obs);
        colors_opt_track(ctx.colors, &ctx.vis->scan);
    }
    n = det_run(&ctx, &fr.view, &cam, field, &obs, feat, DET_MAX_FEATURES);
    for (i = 0; i < n; i++)
        printf("%c\t%.1f\t%.1f\t%.2f\t%d\t%.1f\n", feat[i].kind, feat[i].u, feat[i].v,
               feat[i].confidence, (int)feat[i].range_mm, feat[i].bearing_deg);
    if (stats) {
        const fl_vision_t *v = ctx.vis;
        fprintf(stderr,
                "# points %d (dropped %d, width-rejected %d, robot-rejected %d) segments %d (merges %d, white checks %d) "
                "crossings %d (pairs %d, ground-rejected %d, arm-rejected %d, robot-rejected %d, merged %d) "
                "posts %d (candidates %d) circle %s (cand %d, rms %d mm) obs %d\n",
                (int)v->lines.n_points, (int)v->lines.points_dropped,
                (int)v->lines.runs_rejected, (int)v->lines.robot_rejected, (int)v->lines.n_segments, (int)v->lines.merges,
                (int)v->lines.white_checks,
                (int)v->crossings.n, (int)v->crossings.pairs, (int)v->crossings.rejected_ground,
                (int)v->crossings.rejected_arms, (int)v->crossings.robot_rejected,
                (int)v->crossings.merged, (int)v->posts.n,
                (int)v->posts.candidates, v->circle.found ? "found" : "no",
                (int)v->circle.n_cand, (int)v->circle.rms_mm, (int)obs.n);
    }
    if (picture)
        rc = detect_picture(&ctx, &fr, &cam, field, m, path, n, show_border, show_classes,
                            picture);
    det_ctx_free(&ctx);
    render_frame_free(&fr);
    return rc;
}
