/* tools/cli/cmd_info.c - `fieldloc fields`, `cameras`, `project`. */
#include "fieldloc/fieldloc.h"
#include "cli/registry.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *kind_name[FL_LM_KIND_COUNT] = {
    "L", "T", "X", "penalty-mark", "centre-mark", "post", "centre-circle", "beacon"};

static int list_fields(void);
static int list_cameras(void);

static fl_angle_t angle_from_rad(double rad)
{
    return fl_angle_from_urad((int32_t)lround(rad * 1e6));
}

static double angle_to_deg(fl_angle_t a) { return a * (360.0 / 65536.0); }

int cmd_fields(int argc, char **argv)
{
    (void)argc; (void)argv;
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
            if (n)
                printf(" %u %s", n, kind_name[k]);
        }
        printf("%s\n", f->symmetric ? " (180-degree symmetric)" : "");
    }
    return 0;
}

int cmd_cameras(int argc, char **argv)
{
    (void)argc; (void)argv;
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

int cmd_project(int argc, char **argv)
{
    const char *cam_name = "nao4-bottom-320";
    fl_camera_pose_t pose = {0, 0, 0, 0, 0, 0, 0};
    int32_t neck_mm = -1;
    fl_camera_t cam;
    const fl_camera_model_t *m;
    double u = -1, v = -1;
    int i, npos = 0;
    fl_status_t s;
    fl_point_t g;
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--camera") && i + 1 < argc)
            cam_name = argv[++i];
        else if (!strcmp(argv[i], "--neck") && i + 1 < argc)
            neck_mm = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--head") && i + 2 < argc) {
            pose.head_pitch = angle_from_rad(atof(argv[++i]));
            pose.head_yaw = angle_from_rad(atof(argv[++i]));
        } else if (!strcmp(argv[i], "--tilt") && i + 3 < argc) {
            pose.torso_pitch = angle_from_rad(atof(argv[++i]));
            pose.torso_roll = angle_from_rad(atof(argv[++i]));
            pose.roll_offset = angle_from_rad(atof(argv[++i]));
        } else if (npos == 0) {
            u = atof(argv[i]);
            npos++;
        } else if (npos == 1) {
            v = atof(argv[i]);
            npos++;
        } else {
            fprintf(stderr, "project: unexpected argument %s\n", argv[i]);
            return 2;
        }
    }
    if (npos != 2) {
        fprintf(stderr, "usage: fieldloc project [--camera NAME] [--neck MM] [--head PITCH_RAD YAW_RAD]\n"
                        "                        [--tilt TORSO_PITCH_RAD TORSO_ROLL_RAD ROLL_OFFSET_RAD] U V\n"
                        "  (neck height and pitch offset default to the camera model's calibrated pose;\n"
                        "  --tilt: the IMU's AngleY, AngleX and a calibration roll, camera.h's signs)\n");
        return 2;
    }
    m = fl_camera_model_find(cam_name);
    if (!m) {
        fprintf(stderr, "project: unknown camera %s (see: fieldloc cameras)\n", cam_name);
        return 2;
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


/* `fieldloc sizes`: what one full instance costs (all caller-owned). */
int cmd_sizes(int argc, char **argv)
{
    /* the localizer's state through the interface (localizer.h) */
    const fl_localizer_t *loc = fl_localizer_find("fuzzy");
    char loc_type[64];
    struct { const char *name; size_t size; const char *what; } t[] = {
        {"fl_color_table_t", sizeof(fl_color_table_t), "colour class tables (built once, read-only per frame)"},
        {"fl_vision_t", sizeof(fl_vision_t), "whole vision path: scanner, lines, circle, crossings, posts, beacons"},
        {"  fl_scan_t", sizeof(fl_scan_t), "column scanner (class map, histograms, feet)"},
        {"  fl_lines_t", sizeof(fl_lines_t), "line points and segments"},
        {"  fl_circle_t", sizeof(fl_circle_t), "centre circle"},
        {"  fl_crossings_t", sizeof(fl_crossings_t), "L/T/X crossings and marks"},
        {"  fl_posts_t", sizeof(fl_posts_t), "goal posts"},
        {"  fl_beacon_t", sizeof(fl_beacon_t), "coloured goals and beacons (AIBO fields)"},
        {loc_type, loc->state_size, "fuzzy position grid (SPL 2013 capacity)"},
        {"fl_camera_t", sizeof(fl_camera_t), "camera model with its pose"},
        {"fl_obs_list_t", sizeof(fl_obs_list_t), "one frame's observations"},
        {"fl_image_t", sizeof(fl_image_t), "image view"},
    };
    size_t i, total = sizeof(fl_color_table_t) + sizeof(fl_vision_t) + loc->state_size +
                      sizeof(fl_camera_t) + sizeof(fl_obs_list_t) + sizeof(fl_image_t);
    (void)argc;
    (void)argv;
    snprintf(loc_type, sizeof loc_type, "fl_%s_t", loc->name);
    for (i = 0; i < sizeof t / sizeof t[0]; i++)
        printf("%-18s %8lu B  %s\n", t[i].name, (unsigned long)t[i].size, t[i].what);
    printf("%-18s %8lu B  one full instance (colour tables + vision + grid + camera + obs + view)\n",
           "total", (unsigned long)total);
    return 0;
}
