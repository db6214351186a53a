/*
 * tools/bench/bench_fixed.c - fixed-point core and camera projection against the
 * obvious double-precision code (ns per call, best of 5 x BENCH_N calls).
 */
#include "fieldloc/fieldloc.h"
#include "bench/bench.h"

#include <math.h>


static volatile int64_t sink_i;
static volatile double sink_d;

#define BENCH_N 2000000

static double bench_sin_fl(void)
{
    int64_t acc = 0;
    uint32_t i;
    double t0 = bench_now_ns();
    for (i = 0; i < BENCH_N; i++)
        acc += fl_sin_q15((fl_angle_t)(int16_t)(uint16_t)(i * 40503u));
    sink_i = acc;
    return (bench_now_ns() - t0) / BENCH_N;
}

static double bench_sin_libm(void)
{
    double acc = 0;
    uint32_t i;
    double t0 = bench_now_ns();
    for (i = 0; i < BENCH_N; i++)
        acc += sin((double)(uint16_t)(i * 40503u) * (M_PI / 32768.0));
    sink_d = acc;
    return (bench_now_ns() - t0) / BENCH_N;
}

static double bench_atan2_fl(void)
{
    int64_t acc = 0;
    uint32_t i, s = 12345;
    double t0 = bench_now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += fl_atan2((int32_t)(s >> 8) - (1 << 23), (int32_t)(s & 0xffff) - 32768);
    }
    sink_i = acc;
    return (bench_now_ns() - t0) / BENCH_N;
}

static double bench_atan2_libm(void)
{
    double acc = 0;
    uint32_t i, s = 12345;
    double t0 = bench_now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += atan2((double)((int32_t)(s >> 8) - (1 << 23)), (double)((int32_t)(s & 0xffff) - 32768));
    }
    sink_d = acc;
    return (bench_now_ns() - t0) / BENCH_N;
}

static double bench_isqrt_fl(void)
{
    int64_t acc = 0;
    uint32_t i, s = 777;
    double t0 = bench_now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += fl_isqrt32(s);
    }
    sink_i = acc;
    return (bench_now_ns() - t0) / BENCH_N;
}

static double bench_isqrt_libm(void)
{
    int64_t acc = 0;
    uint32_t i, s = 777;
    double t0 = bench_now_ns();
    for (i = 0; i < BENCH_N; i++) {
        s = s * 1664525u + 1013904223u;
        acc += (uint32_t)sqrt((double)s);
    }
    sink_i = acc;
    return (bench_now_ns() - t0) / BENCH_N;
}

static double bench_project_fl(void)
{
    fl_camera_t cam;
    fl_camera_pose_t pose = {450, 0, 0, 0, 0, 0, 0};
    int64_t acc = 0;
    uint32_t i;
    double t0;
    fl_camera_init(&cam, fl_camera_model_find("nao4-bottom-320"), &pose);
    t0 = bench_now_ns();
    for (i = 0; i < BENCH_N; i++) {
        fl_point_t g;
        if (fl_camera_pixel_to_ground(&cam, (int32_t)(i % 320) * 16, (int32_t)((i / 320) % 240) * 16, &g))
            acc += g.x_mm + g.y_mm;
    }
    sink_i = acc;
    return (bench_now_ns() - t0) / BENCH_N;
}

/* The same projection in double: the peer a host programmer would write. */
static double bench_project_double(void)
{
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    double f = m->focal_q4 / 16.0, cx = m->cx_q4 / 16.0, cy = m->cy_q4 / 16.0;
    double tilt = m->mount_tilt * (M_PI / 32768.0), h = 450 + m->mount_z_mm;
    double st = sin(tilt), ct = cos(tilt), acc = 0;
    uint32_t i;
    double t0 = bench_now_ns();
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
    return (bench_now_ns() - t0) / BENCH_N;
}

void bench_fixed(bench_ctx_t *ctx)
{
    struct { const char *name; double (*fl)(void); double (*peer)(void); const char *peer_name; } b[] = {
        {"sin_q15", bench_sin_fl, bench_sin_libm, "libm sin (double)"},
        {"atan2", bench_atan2_fl, bench_atan2_libm, "libm atan2 (double)"},
        {"isqrt32", bench_isqrt_fl, bench_isqrt_libm, "(uint32_t)sqrt((double)x)"},
        {"pixel_to_ground", bench_project_fl, bench_project_double, "double pinhole projection, no yaw"},
    };
    size_t i;
    int k, reps = ctx->quick ? 1 : 5;
    for (i = 0; i < sizeof b / sizeof b[0]; i++) {
        double a = 1e30, p = 1e30;
        for (k = 0; k < reps; k++) {   /* best of reps */
            double x = b[i].fl(), y = b[i].peer();
            if (x < a) a = x;
            if (y < p) p = y;
        }
        bench_row(ctx, b[i].name, a, p, b[i].peer_name);
    }
}
