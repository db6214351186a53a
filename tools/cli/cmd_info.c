/* tools/cli/cmd_info.c - `fieldloc fields`, `cameras`, `project`. */
#include "fieldloc/fieldloc.h"
#include "cli/args.h"
#include "cli/registry.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *kind_name[FL_LM_KIND_COUNT] = {
    "L", "T", "X", "penalty-mark", "centre-mark", "post", "centre-circle", "beacon",
    "C-corner", "T-field", "T-net", "net"};

static int list_fields(void);

/* The listing commands take no option: --help says so, anything else is an
 * error (status 2). */
static int no_options(const char *cmd, const char *arg)
{
    if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
        fprintf(stderr, "usage: fieldloc %s (no options)\n", cmd);
        return 0;
    }
    return arg_unknown(cmd, arg, NULL);
}
static int list_cameras(void);

static fl_angle_t angle_from_rad(double rad)
{
    return fl_angle_from_urad((int32_t)lround(rad * 1e6));
}

static double angle_to_deg(fl_angle_t a) { return a * (360.0 / 65536.0); }

int cmd_fields(int argc, char **argv)
{
    if (argc > 0)
        return no_options("fields", argv[0]);
    return list_fields();
}

static int list_fields(void)
{
    size_t i;
    for (i = 0; i < fl_field_count(); i++) {
        const fl_field_t *f = fl_field_at(i);
        int k;
        printf("%-9s lines %d x %d mm, carpet %d x %d mm, %u landmarks:", f->name,
               (int)f->length_mm, (int)f->width_mm, 2 * (int)fl_field_carpet_half_x_mm(f),
               2 * (int)fl_field_carpet_half_y_mm(f), (unsigned)f->n_landmarks);
        for (k = 0; k < FL_LM_KIND_COUNT; k++) {
            unsigned n = fl_field_count_kind(f, (fl_landmark_kind_t)k);
            if (fl_landmark_kind_is_feature((fl_landmark_kind_t)k))
                continue;
            if (n)
                printf(" %u %s", n, kind_name[k]);
        }
        if (f->features != NULL && f->n_features > 0) {
            /* seed 004's corner features, a list of their own (field.h) */
            printf("; %u seed-004 features:", (unsigned)f->n_features);
            for (k = 0; k < FL_LM_KIND_COUNT; k++) {
                unsigned n = fl_field_count_kind(f, (fl_landmark_kind_t)k);
                if (fl_landmark_kind_is_feature((fl_landmark_kind_t)k) && n)
                    printf(" %u %s", n, kind_name[k]);
            }
        }
        printf("%s\n", f->symmetric ? " (180-degree symmetric)" : "");
    }
    return 0;
}

int cmd_cameras(int argc, char **argv)
{
    if (argc > 0)
        return no_options("cameras", argv[0]);
    return list_cameras();
}

static int list_cameras(void)
{
    size_t i;
    printf("%-18s %9s %9s %8s %8s %8s %8s\n", "name", "size", "focal_px", "cx_px", "cy_px",
           "mount_mm", "tilt_deg");
    for (i = 0; i < fl_camera_model_count(); i++) {
        const fl_camera_model_t *m = fl_camera_model_at(i);
        char size[32];
        snprintf(size, sizeof size, "%dx%d", (int)m->width_px, (int)m->height_px);
        printf("%-18s %9s %9.2f %8.2f %8.2f %3d,%-4d %8.2f\n", m->name, size, m->focal_q4 / 16.0,
               m->cx_q4 / 16.0, m->cy_q4 / 16.0, (int)m->mount_x_mm, (int)m->mount_z_mm,
               angle_to_deg(m->mount_tilt));
    }
    return 0;
}

static int project_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc project [--camera NAME] [--neck MM] [--head PITCH_RAD YAW_RAD]\n"
            "                        [--tilt TORSO_PITCH_RAD TORSO_ROLL_RAD ROLL_OFFSET_RAD] U V\n"
            "  (neck height and pitch offset default to the camera model's calibrated pose;\n"
            "  --tilt: the IMU's AngleY, AngleX and a calibration roll, camera.h's signs,\n"
            "  each -0.7854..0.7854 rad)\n"
            "  --neck 50..2000 mm; --head within the NAO head joints (HeadPitch\n"
            "  -0.6720..0.5149 rad, HeadYaw -2.0857..2.0857 rad; non-NAO camera: its\n"
            "  tilt limit); U V a pixel of the image (-0.5..width-0.5, -0.5..height-0.5)\n");
    return 2;
}

int cmd_project(int argc, char **argv)
{
    const char *cam_name = "nao4-bottom-320";
    fl_camera_pose_t pose = {0, 0, 0, 0, 0, 0, 0};
    int32_t neck_mm = -1;
    fl_camera_t cam;
    const fl_camera_model_t *m;
    double u = -1, v = -1, pitch = 0, yaw = 0;
    const char *uv_text[2] = {NULL, NULL}, *head_text[2] = {NULL, NULL};
    int i, npos = 0;
    fl_status_t s;
    fl_point_t g;
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--camera") && i + 1 < argc)
            cam_name = argv[++i];
        else if (!strcmp(argv[i], "--neck") && i + 1 < argc) {
            if (arg_int32("project", "--neck", argv[++i], FL_CAMERA_NECK_MIN_MM,
                          FL_CAMERA_NECK_MAX_MM, "mm", &neck_mm) != 0)
                return 2;
        } else if (!strcmp(argv[i], "--head") && i + 2 < argc) {
            head_text[0] = argv[++i];   /* range checked once the camera is known */
            head_text[1] = argv[++i];
            if (arg_double("project", "--head pitch", head_text[0], -1e9, 1e9, NULL, &pitch) ||
                arg_double("project", "--head yaw", head_text[1], -1e9, 1e9, NULL, &yaw))
                return 2;
        } else if (!strcmp(argv[i], "--tilt") && i + 3 < argc) {
            /* the IMU's AngleY and AngleX and a calibration roll (camera.h's
             * signs), each within the camera model's limit */
            double t[3];
            int k;
            for (k = 0; k < 3; k++) {
                static const char *const what[3] = {"--tilt torso pitch", "--tilt torso roll",
                                                    "--tilt roll offset"};
                if (arg_double("project", what[k], argv[++i], -0.7854, 0.7854, "rad", &t[k]) != 0)
                    return 2;
            }
            pose.torso_pitch = angle_from_rad(t[0]);
            pose.torso_roll = angle_from_rad(t[1]);
            pose.roll_offset = angle_from_rad(t[2]);
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            project_usage();
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1] != '.' &&
                   !(argv[i][1] >= '0' && argv[i][1] <= '9'))
            return arg_unknown("project", argv[i], "--camera=1 --neck=1 --head=2 --tilt=3");
        else if (npos < 2)
            uv_text[npos++] = argv[i];
        else
            return arg_unknown("project", argv[i], NULL);
    }
    if (npos != 2)
        return project_usage();
    m = fl_camera_model_find(cam_name);
    if (!m) {
        fprintf(stderr, "project: unknown camera %s (see: fieldloc cameras)\n", cam_name);
        return 2;
    }
    /* a pixel of the image (pixel centres at integers) */
    if (arg_double("project", "U", uv_text[0], -0.5, m->width_px - 0.5, "px", &u) != 0 ||
        arg_double("project", "V", uv_text[1], -0.5, m->height_px - 0.5, "px", &v) != 0)
        return 2;
    if (head_text[0] != NULL) {
        if (arg_head("project", "--head", m, head_text[0], head_text[1], &pitch, &yaw) != 0)
            return 2;
        pose.head_pitch = angle_from_rad(pitch);
        pose.head_yaw = angle_from_rad(yaw);
    }
    /* the model's default pose (calibrated for uva2013) unless overridden */
    pose.neck_height_mm = neck_mm >= 0 ? neck_mm : m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    s = fl_camera_init(&cam, m, &pose);
    if (s != FL_OK) {
        fprintf(stderr, "project: %s\n", fl_status_str(s));
        return 1;
    }
    if (!fl_camera_pixel_to_ground(&cam, (int32_t)lround(u * 16), (int32_t)lround(v * 16), &g)) {
        printf("no ground point (at or above the horizon, or beyond %d mm)\n", FL_CAMERA_MAX_RANGE_MM);
        return 0;
    }
    {
        int32_t r;
        fl_angle_t b;
        fl_polar_from_point(g, &r, &b);
        printf("ground x_mm %d y_mm %d range_mm %d bearing_deg %.2f\n", (int)g.x_mm, (int)g.y_mm,
               (int)r, angle_to_deg(b));
    }
    return 0;
}


/* `fieldloc sizes`: what one full instance costs (all caller-owned): the
 * vision path's structs, then every localizer of the catalogue (its state
 * through the interface, localizer.h), then an instance with the largest
 * localizer. */
int cmd_sizes(int argc, char **argv)
{
    struct { const char *name; size_t size; const char *what; } t[] = {
        {"fl_color_table_t", sizeof(fl_color_table_t), "colour class tables (built once, read-only per frame)"},
        {"fl_vision_t", sizeof(fl_vision_t), "whole vision path: scanner, lines, circle, crossings, posts, beacons"},
        {"  fl_scan_t", sizeof(fl_scan_t), "column scanner (class map, histograms, feet)"},
        {"  fl_lines_t", sizeof(fl_lines_t), "line points and segments"},
        {"  fl_circle_t", sizeof(fl_circle_t), "centre circle"},
        {"  fl_crossings_t", sizeof(fl_crossings_t), "L/T/X crossings and marks"},
        {"  fl_posts_t", sizeof(fl_posts_t), "goal posts"},
        {"  fl_beacon_t", sizeof(fl_beacon_t), "coloured goals and beacons (AIBO fields)"},
        {"fl_camera_t", sizeof(fl_camera_t), "camera model with its pose"},
        {"fl_obs_list_t", sizeof(fl_obs_list_t), "one frame's observations"},
        {"fl_image_t", sizeof(fl_image_t), "image view"},
    };
    size_t i, largest = 0, total = sizeof(fl_color_table_t) + sizeof(fl_vision_t) +
                                   sizeof(fl_camera_t) + sizeof(fl_obs_list_t) + sizeof(fl_image_t);
    uint16_t k;
    if (argc > 0)
        return no_options("sizes", argv[0]);
    for (i = 0; i < sizeof t / sizeof t[0]; i++)
        printf("%-18s %8lu B  %s\n", t[i].name, (unsigned long)t[i].size, t[i].what);
    for (k = 0; k < fl_localizer_count(); k++) {
        const fl_localizer_t *loc = fl_localizer_get(k);
        char loc_type[64];
        snprintf(loc_type, sizeof loc_type, "fl_%s_t", loc->name);
        printf("%-18s %8lu B  localizer \"%s\": %s\n", loc_type, (unsigned long)loc->state_size,
               loc->name, loc->summary);
        if (loc->state_size > largest)
            largest = loc->state_size;
    }
    printf("%-18s %8lu B  one full instance (colour tables + vision + camera + obs + view + the "
           "largest localizer)\n", "total", (unsigned long)(total + largest));
    /* the coach camera's structs: a coach robot holds fl_coach_t instead of
     * (or beside) an instance; a player adds a tracker and a message */
    printf("%-18s %8lu B  the coach's image path at %dx%d (stored empty-field frame, masks, tables)\n",
           "fl_coach_t", (unsigned long)sizeof(fl_coach_t), FL_COACH_MAX_WIDTH, FL_COACH_MAX_HEIGHT);
    /* the other vision paths: seed 002's (instead of fl_vision_t on its
     * field) and seed 004's corner stage (beside it on the AIBO field) */
    printf("%-18s %8lu B  seed 002's vision path (hlvision.h: posts, poles, skeleton crossings)\n",
           "fl_hlv_t", (unsigned long)sizeof(fl_hlv_t));
    printf("%-18s %8lu B  seed 004's corner stage at %dx%d (corners.h: smoothed luma, gradients, "
           "responses)\n", "fl_corners_t", (unsigned long)sizeof(fl_corners_t),
           FL_CORNERS_MAX_WIDTH, FL_CORNERS_MAX_HEIGHT);
    printf("%-18s %8lu B  a player's memory of the coach's reports (report.h)\n",
           "fl_report_tracker_t", (unsigned long)sizeof(fl_report_tracker_t));
    printf("%-18s %8lu B  one decoded report message (%d bytes on the wire)\n", "fl_report_msg_t",
           (unsigned long)sizeof(fl_report_msg_t), (int)FL_REPORT_MSG_BYTES);
    return 0;
}
