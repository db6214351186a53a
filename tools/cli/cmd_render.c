/*
 * tools/cli/cmd_render.c - `fieldloc render`: render one frame of the synthetic
 * world (tools/world/render.h) with its ground truth (tools/world/truth.h).
 */
#include "world/render.h"
#include "world/truth.h"
#include "cli/args.h"
#include "eval/picture.h"
#include "io/ppm.h"
#include "cli/registry.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void render_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc render [--field F] [--camera C] [--pose X_MM Y_MM THETA_DEG]\n"
            "         [--head PITCH_RAD YAW_RAD] [--neck MM] [--seed N] [--format rgb|yuyv|planar]\n"
            "         --out OUT.ppm [--truth OUT.txt]\n"
            "  more:  --scene IN.scene (start from a scene file; later options override)\n"
            "         --save-scene OUT.scene  --world-seed N  --pitch-offset RAD\n"
            "         --robot X_MM Y_MM THETA_DEG red|blue (repeatable)  --ball X_MM Y_MM\n"
            "         --gain PCT  --grad X_PCT Y_PCT  --no-shadows  --noise SIGMA_X10  --jpeg 0..4\n"
            "         --blur PX DIR_DEG  --supersample 1..4  --no-background\n"
            "         --mask OUT.ppm (class mask picture)  --rgb OUT.ppm (RGB picture of any format)\n"
            "  Defaults: spl2013, nao4-bottom-320 (on hl3x2: acyut-640, head 20 deg down),\n"
            "  robot at the centre facing +x, level head,\n"
            "  the camera's default neck height and pitch offset (fieldloc cameras).\n"
            "  Head pitch: NAOqi, positive looks down.\n"
            "  --out writes PPM for rgb, else the FLRAW container (fixtures/README.md).\n"
            "  Ranges: positions within the field's carpet + 1000 mm, angles -360..360 deg,\n"
            "  --head within the NAO head joints (HeadPitch -0.6720..0.5149 rad, HeadYaw\n"
            "  -2.0857..2.0857 rad; other cameras: their tilt limit), --neck 50..2000 mm,\n"
            "  --pitch-offset -0.7854..0.7854 rad, seeds 0..4294967295, --gain 0..400,\n"
            "  --grad -200..200 each, --noise 0..1000, --blur 0..64 px.\n");
}

static fl_angle_t ang_rad(double rad) { return fl_angle_from_urad((int32_t)lround(rad * 1e6)); }
static fl_angle_t ang_deg(double deg) { return fl_angle_from_mdeg((int32_t)lround(deg * 1e3)); }

/* X_MM Y_MM THETA_DEG at argv[0..2] on field f; 0 on success. */
static int render_pose_args(const char *opt, char **argv, const fl_field_t *f, int32_t *x,
                            int32_t *y, fl_angle_t *theta)
{
    double dx, dy, dt;
    char name[32];
    snprintf(name, sizeof name, "%s X", opt);
    if (arg_field_mm("render", name, argv[0], f, 'x', &dx) != 0)
        return -1;
    snprintf(name, sizeof name, "%s Y", opt);
    if (arg_field_mm("render", name, argv[1], f, 'y', &dy) != 0)
        return -1;
    if (theta != NULL) {
        snprintf(name, sizeof name, "%s THETA", opt);
        if (arg_double("render", name, argv[2], -360, 360, "deg", &dt) != 0)
            return -1;
        *theta = ang_deg(dt);
    }
    *x = (int32_t)lround(dx);
    *y = (int32_t)lround(dy);
    return 0;
}

/* Picture of the class mask: one color per class, the field border as a
 * red dot per column; the legend strip below (picture.h PIC_LEGEND_MASK,
 * same colors). */
static int write_mask_picture(const char *path, const render_frame_t *fr)
{
    static const uint8_t pal[RENDER_CLASS_COUNT][3] = {
        {40, 40, 40}, {30, 140, 50}, {255, 255, 255}, {240, 220, 0}, {60, 90, 230}, {255, 120, 0}, {230, 60, 200}};
    size_t npx = (size_t)fr->width * (size_t)fr->height, p;
    uint8_t *img = (uint8_t *)malloc(npx * 3);
    int u, r;
    if (!img)
        return -1;
    for (p = 0; p < npx; p++)
        memcpy(img + 3 * p, pal[fr->mask[p] < RENDER_CLASS_COUNT ? fr->mask[p] : 0], 3);
    for (u = 0; u < fr->width; u++) {
        int v = fr->border_v[u];
        if (v < fr->height) {
            uint8_t *q = img + 3 * ((size_t)v * (size_t)fr->width + (size_t)u);
            q[0] = 255;
            q[1] = 0;
            q[2] = 0;
        }
    }
    {
        host_image_t pic, out;
        pic.width = fr->width;
        pic.height = fr->height;
        pic.rgb = img;
        r = pic_add_legend(&pic, PIC_LEGEND_MASK, "render: pixel classes of the frame",
                           &out);
        free(img);
        if (r != 0)
            return -1;
        r = ppm_write(path, out.rgb, out.width, out.height);
        host_image_free(&out);
    }
    return r;
}

int cmd_render(int argc, char **argv)
{
    render_scene_t sc;
    render_frame_t fr;
    const char *field = NULL, *camera = NULL, *out = NULL, *truth_path = NULL, *scene_in = NULL;
    const char *scene_out = NULL, *mask_out = NULL, *rgb_out = NULL;
    int i;
    char err[256];

    /* first pass: the scene file, field and camera decide the defaults */
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            render_usage();
            return 0;
        }
        if (!strcmp(argv[i], "--scene") && i + 1 < argc)
            scene_in = argv[++i];
        else if (!strcmp(argv[i], "--field") && i + 1 < argc)
            field = argv[++i];
        else if (!strcmp(argv[i], "--camera") && i + 1 < argc)
            camera = argv[++i];
    }
    if (scene_in) {
        if (render_scene_load(scene_in, &sc, err, sizeof err) != 0) {
            fprintf(stderr, "render: %s\n", err);
            return 1;
        }
        if (field) sc.field = fl_field_find(field);
        if (camera) sc.camera = fl_camera_model_find(camera);
    } else {
        const fl_field_t *ff = fl_field_find(field ? field : "spl2013");
        const char *dc = render_field_camera(ff);
        render_scene_default(&sc, ff,
                             fl_camera_model_find(camera ? camera : dc ? dc : "nao4-bottom-320"));
    }
    if (!sc.field) {
        fprintf(stderr, "render: unknown field %s (see: fieldloc fields)\n", field);
        return 2;
    }
    if (!sc.camera) {
        fprintf(stderr, "render: unknown camera %s (see: fieldloc cameras)\n", camera);
        return 2;
    }
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        int left = argc - i - 1;
        double d, d2;
        if ((!strcmp(a, "--scene") || !strcmp(a, "--field") || !strcmp(a, "--camera")) && left >= 1)
            i++;
        else if (!strcmp(a, "--pose") && left >= 3) {
            if (render_pose_args("--pose", argv + i + 1, sc.field, &sc.robot_x_mm,
                                 &sc.robot_y_mm, &sc.robot_heading) != 0)
                return 2;
            i += 3;
        } else if (!strcmp(a, "--head") && left >= 2) {
            if (arg_head("render", "--head", sc.camera, argv[i + 1], argv[i + 2], &d, &d2) != 0)
                return 2;
            sc.head.head_pitch = ang_rad(d);
            sc.head.head_yaw = ang_rad(d2);
            i += 2;
        } else if (!strcmp(a, "--neck") && left >= 1) {
            if (arg_int32("render", "--neck", argv[++i], FL_CAMERA_NECK_MIN_MM,
                          FL_CAMERA_NECK_MAX_MM, "mm", &sc.head.neck_height_mm) != 0)
                return 2;
        } else if (!strcmp(a, "--pitch-offset") && left >= 1) {
            /* the simulator's bound too (sim.c: |pitch_offset_deg| <= 45) */
            if (arg_double("render", "--pitch-offset", argv[++i], -0.7854, 0.7854, "rad", &d))
                return 2;
            sc.head.pitch_offset = ang_rad(d);
        } else if (!strcmp(a, "--seed") && left >= 1) {
            if (arg_u32("render", "--seed", argv[++i], &sc.seed) != 0)
                return 2;
        } else if (!strcmp(a, "--world-seed") && left >= 1) {
            if (arg_u32("render", "--world-seed", argv[++i], &sc.world_seed) != 0)
                return 2;
        } else if (!strcmp(a, "--format") && left >= 1) {
            sc.format = render_format_from_name(argv[++i]);
            if (!sc.format) {
                fprintf(stderr, "render: --format rgb|yuyv|planar\n");
                return 2;
            }
        } else if (!strcmp(a, "--out") && left >= 1)
            out = argv[++i];
        else if (!strcmp(a, "--truth") && left >= 1)
            truth_path = argv[++i];
        else if (!strcmp(a, "--save-scene") && left >= 1)
            scene_out = argv[++i];
        else if (!strcmp(a, "--mask") && left >= 1)
            mask_out = argv[++i];
        else if (!strcmp(a, "--rgb") && left >= 1)
            rgb_out = argv[++i];
        else if (!strcmp(a, "--robot") && left >= 4) {
            render_robot_t *rb;
            if (sc.n_robots >= RENDER_MAX_ROBOTS) {
                fprintf(stderr, "render: at most %d robots\n", RENDER_MAX_ROBOTS);
                return 2;
            }
            rb = &sc.robots[sc.n_robots++];
            if (render_pose_args("--robot", argv + i + 1, sc.field, &rb->x_mm, &rb->y_mm,
                                 &rb->heading) != 0)
                return 2;
            if (strcmp(argv[i + 4], "red") != 0 && strcmp(argv[i + 4], "blue") != 0) {
                fprintf(stderr, "fieldloc render: --robot: jersey \"%s\" is not red or blue\n",
                        argv[i + 4]);
                return 2;
            }
            rb->jersey = strcmp(argv[i + 4], "blue") ? RENDER_JERSEY_RED : RENDER_JERSEY_BLUE;
            i += 4;
        } else if (!strcmp(a, "--ball") && left >= 2) {
            sc.ball = 1;
            if (render_pose_args("--ball", argv + i + 1, sc.field, &sc.ball_x_mm, &sc.ball_y_mm,
                                 NULL) != 0)
                return 2;
            i += 2;
        } else if (!strcmp(a, "--gain") && left >= 1) {
            if (arg_int32("render", "--gain", argv[++i], 0, 400, "%", &sc.gain_pct) != 0)
                return 2;
        } else if (!strcmp(a, "--grad") && left >= 2) {
            /* beyond 200 % the ramp makes one edge negative */
            if (arg_int32("render", "--grad X", argv[i + 1], -200, 200, "%", &sc.grad_x_pct) ||
                arg_int32("render", "--grad Y", argv[i + 2], -200, 200, "%", &sc.grad_y_pct))
                return 2;
            i += 2;
        } else if (!strcmp(a, "--no-shadows"))
            sc.shadows = 0;
        else if (!strcmp(a, "--no-background"))
            sc.background = 0;
        else if (!strcmp(a, "--noise") && left >= 1) {
            if (arg_int32("render", "--noise", argv[++i], 0, 1000, "tenths of a level",
                          &sc.noise_x10) != 0)
                return 2;
        } else if (!strcmp(a, "--jpeg") && left >= 1) {
            if (arg_int32("render", "--jpeg", argv[++i], 0, 4, NULL, &sc.jpeg) != 0)
                return 2;
        } else if (!strcmp(a, "--blur") && left >= 2) {
            /* render_post.c caps the length at 64 px */
            if (arg_int32("render", "--blur PX", argv[i + 1], 0, 64, "px", &sc.blur_px) ||
                arg_double("render", "--blur DIR", argv[i + 2], -360, 360, "deg", &d))
                return 2;
            sc.blur_dir = ang_deg(d);
            i += 2;
        } else if (!strcmp(a, "--supersample") && left >= 1) {
            if (arg_int32("render", "--supersample", argv[++i], 1, 4, NULL, &sc.supersample))
                return 2;
        } else
            return arg_unknown("render", a,
                               "--scene=1 --field=1 --camera=1 --pose=3 --head=2 --neck=1 "
                               "--pitch-offset=1 --seed=1 --world-seed=1 --format=1 --out=1 "
                               "--truth=1 --save-scene=1 --mask=1 --rgb=1 --robot=4 --ball=2 "
                               "--gain=1 --grad=2 --noise=1 --jpeg=1 --blur=2 --supersample=1");
    }
    if (!out) {
        render_usage();
        return 2;
    }
    if (render_frame(&sc, &fr) != 0) {
        fprintf(stderr, "render: cannot render this scene (camera pose out of range, or odd width for yuyv)\n");
        return 1;
    }
    if (render_write_frame(out, &fr) != 0) {
        fprintf(stderr, "render: cannot write %s\n", out);
        render_frame_free(&fr);
        return 1;
    }
    if (truth_path) {
        truth_t *t = (truth_t *)malloc(sizeof *t);
        if (!t || truth_compute(&sc, &fr, t) != 0 || truth_save(truth_path, t) != 0) {
            fprintf(stderr, "render: cannot write %s\n", truth_path);
            free(t);
            render_frame_free(&fr);
            return 1;
        }
        free(t);
    }
    if (scene_out && render_scene_save(scene_out, &sc) != 0)
        fprintf(stderr, "render: cannot write %s\n", scene_out);
    if (mask_out && write_mask_picture(mask_out, &fr) != 0)
        fprintf(stderr, "render: cannot write %s\n", mask_out);
    if (rgb_out && ppm_write(rgb_out, fr.rgb, fr.width, fr.height) != 0)
        fprintf(stderr, "render: cannot write %s\n", rgb_out);
    render_frame_free(&fr);
    return 0;
}
