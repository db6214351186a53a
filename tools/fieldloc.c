/*
 * tools/fieldloc.c - the host command-line tool (never linked into firmware).
 *
 *   fieldloc fields                      list the field models and landmarks
 *   fieldloc cameras                     list the camera models
 *   fieldloc project --camera NAME [--neck MM] [--head PITCH_RAD YAW_RAD] U V
 *                                        pixel -> ground point, range, bearing
 *   fieldloc bench [--out FILE.tsv]      micro-benchmarks against libm
 */
#include "fieldloc/fieldloc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *kind_name[FL_LM_KIND_COUNT] = {
    "L", "T", "X", "penalty-mark", "centre-mark", "post", "centre-circle", "beacon"};

static fl_angle_t angle_from_rad(double rad)
{
    return fl_angle_from_urad((int32_t)lround(rad * 1e6));
}

static double angle_to_deg(fl_angle_t a) { return a * (360.0 / 65536.0); }

static int cmd_fields(void)
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

static int cmd_cameras(void)
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

static int cmd_project(int argc, char **argv)
{
    const char *cam_name = "nao4-bottom-320";
    fl_camera_pose_t pose = {450, 0, 0, 0};
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
            pose.neck_height_mm = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--head") && i + 2 < argc) {
            pose.head_pitch = angle_from_rad(atof(argv[++i]));
            pose.head_yaw = angle_from_rad(atof(argv[++i]));
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
        fprintf(stderr, "usage: fieldloc project [--camera NAME] [--neck MM] [--head PITCH_RAD YAW_RAD] U V\n");
        return 2;
    }
    m = fl_camera_model_find(cam_name);
    if (!m) {
        fprintf(stderr, "project: unknown camera %s (see: fieldloc cameras)\n", cam_name);
        return 2;
    }
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

/* ---- bench ---- */

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

static volatile int64_t sink_i;
static volatile double sink_d;

#define BENCH_N 2000000

static double bench_sin_fl(void)
{
    int64_t acc = 0;
    uint32_t i;
    double t0 = now_ns();
    for (i = 0; i < BENCH_N; i++)
        acc += fl_sin_q15((fl_angle_t)(int16_t)(uint16_t)(i * 40503u));
    sink_i = acc;
    return (now_ns() - t0) / BENCH_N;
}

static double bench_sin_libm(void)
{
    double acc = 0;
    uint32_t i;
    double t0 = now_ns();
    for (i = 0; i < BENCH_N; i++)
        acc += sin((double)(uint16_t)(i * 40503u) * (M_PI / 32768.0));
    sink_d = acc;
    return (now_ns() - t0) / BENCH_N;
}

static double bench_atan2_fl(void)
{
    int64_t acc = 0;
    uint32_t i, s = 12345;
    double t0 = now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += fl_atan2((int32_t)(s >> 8) - (1 << 23), (int32_t)(s & 0xffff) - 32768);
    }
    sink_i = acc;
    return (now_ns() - t0) / BENCH_N;
}

static double bench_atan2_libm(void)
{
    double acc = 0;
    uint32_t i, s = 12345;
    double t0 = now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += atan2((double)((int32_t)(s >> 8) - (1 << 23)), (double)((int32_t)(s & 0xffff) - 32768));
    }
    sink_d = acc;
    return (now_ns() - t0) / BENCH_N;
}

static double bench_isqrt_fl(void)
{
    int64_t acc = 0;
    uint32_t i, s = 777;
    double t0 = now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += fl_isqrt32(s);
    }
    sink_i = acc;
    return (now_ns() - t0) / BENCH_N;
}

static double bench_isqrt_libm(void)
{
    int64_t acc = 0;
    uint32_t i, s = 777;
    double t0 = now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += (uint32_t)sqrt((double)s);
    }
    sink_i = acc;
    return (now_ns() - t0) / BENCH_N;
}

static double bench_project_fl(void)
{
    fl_camera_t cam;
    fl_camera_pose_t pose = {450, 0, 0, 0};
    int64_t acc = 0;
    uint32_t i;
    double t0;
    fl_camera_init(&cam, fl_camera_model_find("nao4-bottom-320"), &pose);
    t0 = now_ns();
    for (i = 0; i < BENCH_N; i++) {
        fl_point_t g;
        if (fl_camera_pixel_to_ground(&cam, (int32_t)(i % 320) * 16, (int32_t)((i / 320) % 240) * 16, &g))
            acc += g.x_mm + g.y_mm;
    }
    sink_i = acc;
    return (now_ns() - t0) / BENCH_N;
}

/* The same projection in double: the peer a host programmer would write. */
static double bench_project_double(void)
{
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    double f = m->focal_q4 / 16.0, cx = m->cx_q4 / 16.0, cy = m->cy_q4 / 16.0;
    double tilt = m->mount_tilt * (M_PI / 32768.0), h = 450 + m->mount_z_mm;
    double st = sin(tilt), ct = cos(tilt), acc = 0;
    uint32_t i;
    double t0 = now_ns();
    for (i = 0; i < BENCH_N; i++) {
        double u = (double)(i % 320), v = (double)((i / 320) % 240);
        double dx = f, dy = cx - u, dz = cy - v;
        double wx = ct * dx + st * dz, wz = -st * dx + ct * dz;
        if (wz < 0) {
            double t = h / -wz;
            acc += m->mount_x_mm + t * wx + t * dy;
        }
    }
    sink_d = acc;
    return (now_ns() - t0) / BENCH_N;
}

static int cmd_bench(int argc, char **argv)
{
    const char *out = "build/bench.tsv";
    struct { const char *name; double (*fl)(void); double (*peer)(void); const char *peer_name; } b[] = {
        {"sin_q15", bench_sin_fl, bench_sin_libm, "libm sin (double)"},
        {"atan2", bench_atan2_fl, bench_atan2_libm, "libm atan2 (double)"},
        {"isqrt32", bench_isqrt_fl, bench_isqrt_libm, "(uint32_t)sqrt((double)x)"},
        {"pixel_to_ground", bench_project_fl, bench_project_double, "double pinhole projection"},
    };
    FILE *f;
    size_t i;
    int k;
    for (k = 0; k < argc; k++)
        if (!strcmp(argv[k], "--out") && k + 1 < argc)
            out = argv[++k];
    f = fopen(out, "w");
    if (!f) {
        perror(out);
        return 1;
    }
    fprintf(f, "name\tfieldloc_ns\tpeer_ns\tspeedup\n");
    printf("%-16s %12s %12s %8s  peer\n", "name", "fieldloc_ns", "peer_ns", "speedup");
    for (i = 0; i < sizeof b / sizeof b[0]; i++) {
        double a = 1e30, p = 1e30;
        for (k = 0; k < 5; k++) {   /* best of 5 */
            double x = b[i].fl(), y = b[i].peer();
            if (x < a) a = x;
            if (y < p) p = y;
        }
        fprintf(f, "%s\t%.2f\t%.2f\t%.2f\n", b[i].name, a, p, p / a);
        printf("%-16s %12.2f %12.2f %8.2f  %s\n", b[i].name, a, p, p / a, b[i].peer_name);
    }
    fclose(f);
    printf("wrote %s (ns per call, best of 5 runs of %d calls)\n", out, BENCH_N);
    return 0;
}

static void usage(void)
{
    fprintf(stderr,
            "usage: fieldloc COMMAND ...\n"
            "  fields                  list the field models\n"
            "  cameras                 list the camera models\n"
            "  project [--camera NAME] [--neck MM] [--head PITCH_RAD YAW_RAD] U V\n"
            "                          pixel (u right, v down) -> ground point, range, bearing\n"
            "  bench [--out FILE]      micro-benchmarks (ns per call) against libm\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage();
        return 2;
    }
    if (!strcmp(argv[1], "fields"))
        return cmd_fields();
    if (!strcmp(argv[1], "cameras"))
        return cmd_cameras();
    if (!strcmp(argv[1], "project"))
        return cmd_project(argc - 2, argv + 2);
    if (!strcmp(argv[1], "bench"))
        return cmd_bench(argc - 2, argv + 2);
    usage();
    return 2;
}
