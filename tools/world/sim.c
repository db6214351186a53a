/*
 * tools/world/sim.c - walk simulator (API and time line in tools/world/sim.h).
 *
 * Algorithm.  A waypoint follower produces velocity commands (turn toward the
 * waypoint; walk forward when it lies within 60 degrees of ahead, slower the
 * farther off; a little side-stepping), limited by the gait's maximum speeds
 * and accelerations.  The commanded motion of a step is what the legs
 * "walked"; the true motion is that plus occasional slips; the odometry is
 * the walked motion corrupted as a legged robot's is:
 *     odo_dx     = (1 + scale_x)  * dx + N(0, sigma_trans * L)
 *     odo_dy     = (1 + scale_y)  * dy + N(0, sigma_trans * L)
 *     odo_dtheta = (1 + scale_th) * dth + drift_per_m * L
 *                  + N(0, sigma_rot * |dth| + sigma_rot_per_m * L)
 * with L = |(dx, dy)| the step length (mm, metres where "per m").  N() is
 * the Irwin-Hall sum of 12 uniforms minus 6 (variance exactly 1, tails cut
 * at 6 sigma), so no libm transcendental is needed.
 * Head: yaw follows a triangle wave of amplitude A and period T, pitch
 * alternates between two values every half pitch period.
 * Observations: each landmark of the field map, transformed to the robot
 * frame with the (integer) true pose, is seen when its ground point projects
 * (fl_camera_ground_to_pixel, the firmware camera) at least fov_margin_px
 * inside the image, lies within max_range_mm and no other robot of the
 * scenario stands in the way (sim_occluded); then misses, range and
 * bearing noise, L<->T confusion, goal-post sides (known only when both
 * posts of that goal are seen), and false positives at random image pixels
 * (fov_margin_px inside the image, as true landmarks) below the horizon and
 * within max range (random kind among the kinds the field has).
 * White points: a sample of the visible painted-line points
 * (sim_observe_points, SIM_POINTS_PER_FRAME of them, sim.h) with the
 * landmarks' range and bearing noise, from a separate random stream.
 *
 * Invariant.  Everything that reaches an integer output is computed with
 * IEEE + - * / and sqrt from integers and exact decimal parameters, with
 * the polynomial sim_sin/sim_cos/sim_atan2 below, and the PRNG: bit-identical
 * on every IEEE machine (the build uses -std=c99, so no FMA contraction, and
 * SSE2 on i686).  libm is not used.
 *
 * Memory: sim_t and sim_step_t are caller-owned (~4 KB and ~1.3 KB); no heap
 * except render buffers in sim_write_sequence.  Cost per step: one camera
 * init, one projection per landmark (<= 30), a few hundred flops.
 */
#include "world/sim.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define SIM_PI 3.14159265358979323846
#define SIM_TWO_PI 6.28318530717958647692
#define SIM_DEG (SIM_PI / 180.0)

/* ---- deterministic maths ------------------------------------------------- */

/* Round to nearest, ties away from zero (exact: no libm). */
static double sim_round(double x)
{
    long long k;
    /* |x| >= 2^52 is a whole number already (and NaN stays NaN): the
     * conversion below would be undefined beyond the range of long long */
    if (!(x > -4503599627370496.0 && x < 4503599627370496.0))
        return x;
    k = (long long)(x >= 0 ? x + 0.5 : x - 0.5);
    return (double)k;
}

static int32_t sim_iround(double x)
{
    if (x > 2147483647.0)
        return INT32_MAX;
    if (x < -2147483648.0)
        return INT32_MIN;
    return (int32_t)sim_round(x);
}

/* sin and cos: Cody-Waite reduction by pi/2, Taylor polynomials on
 * [-pi/4, pi/4] (truncation error < 1e-17).  Valid for |x| < 1e6. */
static void sim_sincos(double x, double *s, double *c)
{
    static const double pio2_hi = 1.57079632673412561417e+00;
    static const double pio2_lo = 6.07710050650619224932e-11;
    double k = sim_round(x * 0.63661977236758134308);
    double r = (x - k * pio2_hi) - k * pio2_lo;
    double r2 = r * r;
    double sp, cp;
    long long q;
    sp = r * (1.0 + r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 +
         r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800 + r2 * (1.0 / 6227020800.0 +
         r2 * (-1.0 / 1307674368000.0))))))));
    cp = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 *
         (1.0 / 40320 + r2 * (-1.0 / 3628800 + r2 * (1.0 / 479001600.0 +
         r2 * (-1.0 / 87178291200.0 + r2 * (1.0 / 20922789888000.0))))))));
    q = (long long)k;
    switch ((int)(((q % 4) + 4) % 4)) {
    case 0: *s = sp; *c = cp; break;
    case 1: *s = cp; *c = -sp; break;
    case 2: *s = -sp; *c = -cp; break;
    default: *s = -cp; *c = sp; break;
    }
}


/* atan on [-tan(15 deg), tan(15 deg)]: odd series to z^29 (< 1e-18). */
static double sim_atan_small(double z)
{
    double z2 = z * z, p = 0.0;
    int n;
    for (n = 29; n >= 3; n -= 2)
        p = z2 * ((((n - 1) / 2) % 2 ? -1.0 : 1.0) / n + p);
    return z * (1.0 + p);
}

/* atan(t) for t in [0, 1]: atan(t) = pi/6 + atan((t*sqrt3 - 1)/(t + sqrt3))
 * above tan(15 deg). */
static double sim_atan01(double t)
{
    static const double sqrt3 = 1.73205080756887729353;
    if (t > 0.26794919243112270647)
        return SIM_PI / 6 + sim_atan_small((t * sqrt3 - 1.0) / (t + sqrt3));
    return sim_atan_small(t);
}

static double sim_atan2(double y, double x)
{
    double ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, a;
    if (ax == 0 && ay == 0)
        return 0;
    if (ay > ax)
        a = SIM_PI / 2 - sim_atan01(ax / ay);
    else
        a = sim_atan01(ay / ax);
    if (x < 0)
        a = SIM_PI - a;
    return y < 0 ? -a : a;
}

/* Wrap to [-pi, pi). */
static double sim_wrap(double a)
{
    double k = sim_round(a / SIM_TWO_PI);
    a -= k * SIM_TWO_PI;
    if (a >= SIM_PI)
        a -= SIM_TWO_PI;
    if (a < -SIM_PI)
        a += SIM_TWO_PI;
    return a;
}

static fl_angle_t sim_angle(double rad)
{
    return fl_angle_wrap(sim_iround(sim_wrap(rad) * (65536.0 / SIM_TWO_PI)));
}

static double sim_rad(fl_angle_t a) { return (double)a * (SIM_TWO_PI / 65536.0); }

static double sim_abs(double x) { return x < 0 ? -x : x; }
static double sim_clamp(double x, double m) { return x > m ? m : x < -m ? -m : x; }

/* ---- PRNG (xorshift64*) ---------------------------------------------- */

static uint64_t sim_rand64(uint64_t *s)
{
    uint64_t x = *s;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *s = x;
    return x * 2685821657736338717ULL;
}

static double sim_u01(uint64_t *s) /* [0, 1) */
{
    return (double)(sim_rand64(s) >> 11) * (1.0 / 9007199254740992.0);
}

static double sim_uniform(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * sim_u01(s);
}

static double sim_gauss(uint64_t *s) /* Irwin-Hall: mean 0, variance 1 */
{
    double a = 0;
    int i;
    for (i = 0; i < 12; i++)
        a += sim_u01(s);
    return a - 6.0;
}

static uint64_t sim_seed_state(uint64_t seed)
{
    uint64_t s = seed ^ 0x9E3779B97F4A7C15ULL;
    return s == 0 ? 0x2545F4914F6CDD1DULL : s;
}

/* ---- scenarios ----------------------------------------------------------- */

void sim_scenario_defaults(sim_scenario_t *sc, sim_robot_t robot)
{
    memset(sc, 0, sizeof *sc);
    sc->robot = robot;
    sc->seed = 1;
    sc->frame_hz = 30;           /* NAO camera 30 fps; ERS-7 camera 30 fps */
    sc->duration_s = 120;
    sc->arrive_mm = 150;
    sc->yaw_period_s = 6;
    sc->pitch_period_s = 0;
    sc->fov_margin_px = 2;
    sc->penalty_x_mm = 0;
    sc->white_points = 1;
    if (robot == SIM_ROBOT_AIBO) {
        /* ERS-7 (2004): learned trot gaits reached ~290 mm/s (Kohl and
         * Stone, ICRA 2004, on the ERS-210); 250 is a fast game walk. */
        sc->v_forward_mm_s = 250;
        sc->v_backward_mm_s = 150;
        sc->v_side_mm_s = 150;
        sc->turn_deg_s = 90;
        sc->accel_mm_s2 = 500;
        sc->turn_accel_deg_s2 = 180;
        sc->neck_height_mm = 160;   /* as tools/world/render.h's AIBO default */
        sc->head_pitch_rad[0] = 0.15;
        sc->head_pitch_rad[1] = 0.45;
        sc->pitch_period_s = 4;
        sc->yaw_amplitude_rad = 1.4;  /* ERS-7 pan about +-93 deg */
        sc->odo_scale_x = 0.08;
        sc->odo_scale_y = 0.15;
        sc->odo_scale_theta = 0.08;
        sc->odo_drift_deg_per_m = 4;
        sc->odo_sigma_trans = 0.12;
        sc->odo_sigma_rot = 0.10;
        sc->odo_sigma_rot_deg_per_m = 3;
        sc->slip_rate_hz = 0.1;
        sc->slip_max_mm = 80;
        sc->slip_max_deg = 15;
        sc->max_range_mm = 3500;
        sc->range_sigma_pct = 10;
        sc->bearing_sigma_deg = 2;
        sc->orientation_sigma_deg = 6;
        sc->p_miss = 0.25;
        sc->fp_per_frame = 0.2;
        sc->p_confuse = 0.08;
    } else {
        /* NAO v4 with a 2013-era SPL walk: the Aldebaran walk ~100 mm/s,
         * the fastest team walks ~250-300 mm/s; 180 forward, 100 sideways,
         * 45 deg/s turning are typical game values. */
        sc->v_forward_mm_s = 180;
        sc->v_backward_mm_s = 100;
        sc->v_side_mm_s = 100;
        sc->turn_deg_s = 45;
        sc->accel_mm_s2 = 300;
        sc->turn_accel_deg_s2 = 90;
        sc->neck_height_mm = 460;   /* StandInit / walk posture, DESIGN.md */
        sc->head_pitch_rad[0] = 0.25;
        sc->head_pitch_rad[1] = 0.45;
        sc->pitch_period_s = 4;
        sc->yaw_amplitude_rad = 1.5;  /* HeadYaw limit +-2.08 rad */
        sc->odo_scale_x = 0.10;
        sc->odo_scale_y = 0.15;
        sc->odo_scale_theta = -0.07;
        sc->odo_drift_deg_per_m = 3;
        sc->odo_sigma_trans = 0.10;
        sc->odo_sigma_rot = 0.08;
        sc->odo_sigma_rot_deg_per_m = 2;
        sc->slip_rate_hz = 0.05;
        sc->slip_max_mm = 60;
        sc->slip_max_deg = 10;
        sc->max_range_mm = 6000;
        sc->range_sigma_pct = 8;
        sc->bearing_sigma_deg = 1.5;
        sc->orientation_sigma_deg = 5;
        sc->p_miss = 0.2;
        sc->fp_per_frame = 0.15;
        sc->p_confuse = 0.05;
    }
}

void sim_scenario_noise_off(sim_scenario_t *sc)
{
    sc->odo_scale_x = sc->odo_scale_y = sc->odo_scale_theta = 0;
    sc->odo_drift_deg_per_m = 0;
    sc->odo_sigma_trans = sc->odo_sigma_rot = sc->odo_sigma_rot_deg_per_m = 0;
    sc->slip_rate_hz = 0;
    sc->range_sigma_pct = sc->bearing_sigma_deg = sc->orientation_sigma_deg = 0;
    sc->p_miss = sc->fp_per_frame = sc->p_confuse = 0;
}

static void set_err(char *err, int err_len, const char *msg, int line)
{
    if (err && err_len > 0)
        snprintf(err, (size_t)err_len, "line %d: %s", line, msg);
}

/* Parse n doubles from s; returns the count parsed. */
static int parse_doubles(const char *s, double *v, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        char *end;
        errno = 0;
        v[i] = strtod(s, &end);
        if (end == s || errno != 0)
            return i;
        s = end;
    }
    while (*s == ' ' || *s == '\t' || *s == '\r')
        s++;
    return *s == '\0' ? n : -1;
}

static int parse_name(const char *s, char *out)
{
    size_t n = strlen(s);
    const char *sp;
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r'))
        n--;
    sp = strpbrk(s, " \t");
    if (n == 0 || n >= SIM_NAME_LEN || (sp != NULL && sp < s + n))
        return -1;
    /* the whole array: a name given twice leaves no tail of the first, so
     * equal scenarios are equal bytes (the round trip compares them) */
    memset(out, 0, SIM_NAME_LEN);
    memcpy(out, s, n);
    out[n] = '\0';
    return 0;
}

typedef struct { const char *key; int n; size_t off[3]; } sim_key_t;

#define OFF(f) offsetof(sim_scenario_t, f)
static const sim_key_t sim_keys[] = {
    {"frame_hz", 1, {OFF(frame_hz), 0, 0}},
    {"duration_s", 1, {OFF(duration_s), 0, 0}},
    {"start", 3, {OFF(start_x_mm), OFF(start_y_mm), OFF(start_heading_deg)}},
    {"arrive_mm", 1, {OFF(arrive_mm), 0, 0}},
    {"v_forward_mm_s", 1, {OFF(v_forward_mm_s), 0, 0}},
    {"v_backward_mm_s", 1, {OFF(v_backward_mm_s), 0, 0}},
    {"v_side_mm_s", 1, {OFF(v_side_mm_s), 0, 0}},
    {"turn_deg_s", 1, {OFF(turn_deg_s), 0, 0}},
    {"accel_mm_s2", 1, {OFF(accel_mm_s2), 0, 0}},
    {"turn_accel_deg_s2", 1, {OFF(turn_accel_deg_s2), 0, 0}},
    {"head_pitch", 2, {OFF(head_pitch_rad[0]), OFF(head_pitch_rad[1]), 0}},
    {"pitch_period_s", 1, {OFF(pitch_period_s), 0, 0}},
    {"yaw_amplitude_rad", 1, {OFF(yaw_amplitude_rad), 0, 0}},
    {"yaw_period_s", 1, {OFF(yaw_period_s), 0, 0}},
    {"odo_scale", 3, {OFF(odo_scale_x), OFF(odo_scale_y), OFF(odo_scale_theta)}},
    {"odo_drift_deg_per_m", 1, {OFF(odo_drift_deg_per_m), 0, 0}},
    {"odo_sigma_trans", 1, {OFF(odo_sigma_trans), 0, 0}},
    {"odo_sigma_rot", 1, {OFF(odo_sigma_rot), 0, 0}},
    {"odo_sigma_rot_deg_per_m", 1, {OFF(odo_sigma_rot_deg_per_m), 0, 0}},
    {"slip_rate_hz", 1, {OFF(slip_rate_hz), 0, 0}},
    {"slip_max", 2, {OFF(slip_max_mm), OFF(slip_max_deg), 0}},
    {"max_range_mm", 1, {OFF(max_range_mm), 0, 0}},
    {"range_sigma_pct", 1, {OFF(range_sigma_pct), 0, 0}},
    {"bearing_sigma_deg", 1, {OFF(bearing_sigma_deg), 0, 0}},
    {"orientation_sigma_deg", 1, {OFF(orientation_sigma_deg), 0, 0}},
    {"p_miss", 1, {OFF(p_miss), 0, 0}},
    {"fp_per_frame", 1, {OFF(fp_per_frame), 0, 0}},
    {"p_confuse", 1, {OFF(p_confuse), 0, 0}},
    {"penalty_x_mm", 1, {OFF(penalty_x_mm), 0, 0}},
    {"pitch_offset_deg", 1, {OFF(pitch_offset_deg), 0, 0}},
};
#undef OFF

static int sim_scenario_check(const sim_scenario_t *sc, const char **why)
{
    int i;
    *why = NULL;
    if (sc->field == NULL)
        *why = "unknown or missing field";
    else if (sc->camera == NULL)
        *why = "unknown or missing camera";
    else if (!(sc->frame_hz >= 1 && sc->frame_hz <= 1000))
        *why = "frame_hz outside 1..1000";
    else if (!(sc->duration_s >= 0 && sc->duration_s <= 36000))
        *why = "duration_s outside 0..36000";
    else if (sc->n_waypoints < 1)
        *why = "no waypoint";
    else if (!(sc->v_forward_mm_s > 0 && sc->v_forward_mm_s <= 2000 &&
               sc->v_side_mm_s >= 0 && sc->v_side_mm_s <= 2000 &&
               sc->turn_deg_s > 0 && sc->turn_deg_s <= 720 &&
               sc->accel_mm_s2 > 0 && sc->turn_accel_deg_s2 > 0 &&
               sc->arrive_mm > 0))
        *why = "speed, acceleration or arrive_mm out of range";
    else if (!sc->camera_defaults && (sc->neck_height_mm < FL_CAMERA_NECK_MIN_MM ||
                                      sc->neck_height_mm > FL_CAMERA_NECK_MAX_MM))
        *why = "neck_mm out of range";
    else if (!(sim_abs(sc->pitch_offset_deg) <= 45))
        *why = "pitch_offset_deg out of range";
    else if (!(sc->yaw_period_s > 0 && sc->pitch_period_s >= 0 &&
               sim_abs(sc->yaw_amplitude_rad) <= 3 &&
               sim_abs(sc->head_pitch_rad[0]) <= 1.5 &&
               sim_abs(sc->head_pitch_rad[1]) <= 1.5))
        *why = "head parameters out of range";
    else if (!(sim_abs(sc->odo_scale_x) <= 1 && sim_abs(sc->odo_scale_y) <= 1 &&
               sim_abs(sc->odo_scale_theta) <= 1 &&
               sc->odo_sigma_trans >= 0 && sc->odo_sigma_rot >= 0 &&
               sc->odo_sigma_rot_deg_per_m >= 0 && sc->slip_rate_hz >= 0 &&
               sc->slip_rate_hz <= sc->frame_hz && sc->slip_max_mm >= 0 &&
               sc->slip_max_deg >= 0))
        *why = "odometry noise out of range";
    else if (!(sc->max_range_mm > 0 && sc->max_range_mm <= FL_CAMERA_MAX_RANGE_MM &&
               sc->range_sigma_pct >= 0 && sc->range_sigma_pct <= 50 &&
               sc->bearing_sigma_deg >= 0 && sc->orientation_sigma_deg >= 0 &&
               sc->p_miss >= 0 && sc->p_miss <= 1 && sc->p_confuse >= 0 &&
               sc->p_confuse <= 1 && sc->fp_per_frame >= 0 &&
               sc->fp_per_frame <= 4 && sc->fov_margin_px >= 0 &&
               sc->fov_margin_px < 50))
        *why = "observation noise out of range";
    else if (!(sim_abs(sc->start_x_mm) <= 20000 && sim_abs(sc->start_y_mm) <= 20000 &&
               sim_abs(sc->start_heading_deg) <= 360))
        *why = "start outside +-20000 mm or heading outside +-360 deg";
    for (i = 0; *why == NULL && i < sc->n_events; i++)
        if (!(sc->event[i].t_s >= 0 && sc->event[i].duration_s >= 0 &&
              sc->event[i].duration_s <= 3600))
            *why = "event time or duration out of range";
        else if (!(sim_abs(sc->event[i].x_mm) <= 20000 && sim_abs(sc->event[i].y_mm) <= 20000 &&
                   sim_abs(sc->event[i].heading_deg) <= 360))
            *why = "event pose outside +-20000 mm or heading outside +-360 deg";
    for (i = 0; *why == NULL && i < sc->n_others; i++)
        if (!(sim_abs(sc->other[i].x_mm) <= 20000 && sim_abs(sc->other[i].y_mm) <= 20000 &&
              sim_abs(sc->other[i].heading_deg) <= 360))
            *why = "other robot outside +-20000 mm or heading outside +-360 deg";
    for (i = 1; *why == NULL && i < sc->n_events; i++)
        if (sc->event[i].t_s < sc->event[i - 1].t_s)
            *why = "events not in time order";
    return *why == NULL ? 0 : -1;
}

int sim_scenario_parse(sim_scenario_t *sc, const char *text, char *err,
                       int err_len)
{
    const char *p = text;
    int line = 0, seen_key = 0;
    const char *why;
    if (sc == NULL || text == NULL) {
        set_err(err, err_len, "NULL argument", 0);
        return -1;
    }
    sim_scenario_defaults(sc, SIM_ROBOT_NAO);
    while (*p) {
        char buf[512], key[64];
        const char *rest;
        size_t n = strcspn(p, "\n"), k;
        line++;
        if (n >= sizeof buf) {
            set_err(err, err_len, "line too long", line);
            return -1;
        }
        memcpy(buf, p, n);
        buf[n] = '\0';
        p += n + (p[n] == '\n');
        if (strchr(buf, '#'))
            *strchr(buf, '#') = '\0';
        rest = buf;
        while (*rest == ' ' || *rest == '\t')
            rest++;
        k = strcspn(rest, " \t\r");
        if (k == 0)
            continue;
        if (k >= sizeof key) {
            set_err(err, err_len, "key too long", line);
            return -1;
        }
        memcpy(key, rest, k);
        key[k] = '\0';
        rest += k;
        while (*rest == ' ' || *rest == '\t')
            rest++;
        if (strcmp(key, "robot") == 0) {
            char nm[SIM_NAME_LEN];
            if (seen_key) {
                set_err(err, err_len, "'robot' must be the first key", line);
                return -1;
            }
            if (parse_name(rest, nm) != 0 ||
                (strcmp(nm, "nao") != 0 && strcmp(nm, "aibo") != 0)) {
                set_err(err, err_len, "robot must be nao or aibo", line);
                return -1;
            }
            sim_scenario_defaults(sc, strcmp(nm, "aibo") == 0 ? SIM_ROBOT_AIBO
                                                              : SIM_ROBOT_NAO);
        } else if (strcmp(key, "name") == 0 || strcmp(key, "field") == 0 ||
                   strcmp(key, "camera") == 0) {
            char *dst = key[0] == 'n' ? sc->name
                        : key[0] == 'f' ? sc->field_name : sc->camera_name;
            if (parse_name(rest, dst) != 0) {
                set_err(err, err_len, "bad name", line);
                return -1;
            }
        } else if (strcmp(key, "seed") == 0 || strcmp(key, "neck_mm") == 0 ||
                   strcmp(key, "fov_margin_px") == 0 ||
                   strcmp(key, "camera_defaults") == 0) {
            char *end;
            unsigned long long v;
            errno = 0;
            v = strtoull(rest, &end, 10);
            while (*end == ' ' || *end == '\t' || *end == '\r')
                end++;
            if (end == rest || *end || errno || rest[0] == '-' ||
                (key[0] != 's' && v > 100000)) {
                set_err(err, err_len, "bad integer", line);
                return -1;
            }
            if (key[0] == 's')
                sc->seed = (uint64_t)v;
            else if (key[0] == 'c')
                sc->camera_defaults = v != 0;
            else if (key[0] == 'n')
                sc->neck_height_mm = (int32_t)v;
            else
                sc->fov_margin_px = (int32_t)v;
        } else if (strcmp(key, "face_deg") == 0 || strcmp(key, "route_once") == 0) {
            double v[1];
            if (parse_doubles(rest, v, 1) != 1 || !(v[0] >= -360 && v[0] <= 360)) {
                set_err(err, err_len, key[0] == 'f' ? "face_deg DEG (-360..360)"
                                                    : "route_once 0|1", line);
                return -1;
            }
            if (key[0] == 'f') {
                sc->hold_heading = 1;
                sc->face_deg = v[0];
            } else
                sc->route_once = v[0] != 0;
        } else if (strcmp(key, "waypoint") == 0) {
            double v[2];
            if (sc->n_waypoints >= SIM_MAX_WAYPOINTS || parse_doubles(rest, v, 2) != 2) {
                set_err(err, err_len, "waypoint X_MM Y_MM (at most 64)", line);
                return -1;
            }
            sc->waypoint[sc->n_waypoints].x_mm = v[0];
            sc->waypoint[sc->n_waypoints].y_mm = v[1];
            sc->n_waypoints++;
        } else if (strcmp(key, "other") == 0) {
            double v[3];
            char jersey[SIM_NAME_LEN];
            const char *q = rest;
            int j, ok = sc->n_others < SIM_MAX_OTHERS;
            sim_other_t *o;
            for (j = 0; ok && j < 3; j++) {
                char *end;
                errno = 0;
                v[j] = strtod(q, &end);
                ok = end != q && errno == 0 && (*end == ' ' || *end == '\t');
                q = end;
            }
            while (ok && (*q == ' ' || *q == '\t'))
                q++;
            if (!ok || parse_name(q, jersey) != 0 ||
                (strcmp(jersey, "red") != 0 && strcmp(jersey, "blue") != 0)) {
                set_err(err, err_len, "other X_MM Y_MM DEG red|blue (at most 8)", line);
                return -1;
            }
            o = &sc->other[sc->n_others++];
            o->x_mm = v[0];
            o->y_mm = v[1];
            o->heading_deg = v[2];
            o->jersey = strcmp(jersey, "blue") == 0 ? RENDER_JERSEY_BLUE : RENDER_JERSEY_RED;
        } else if (strcmp(key, "kidnap") == 0 || strcmp(key, "penalty") == 0) {
            double v[4];
            int want = key[0] == 'k' ? 4 : 2;
            sim_event_t *e;
            if (sc->n_events >= SIM_MAX_EVENTS || parse_doubles(rest, v, want) != want) {
                set_err(err, err_len, key[0] == 'k' ? "kidnap T_S X_MM Y_MM DEG"
                                                    : "penalty T_S DURATION_S", line);
                return -1;
            }
            e = &sc->event[sc->n_events++];
            memset(e, 0, sizeof *e);
            e->t_s = v[0];
            if (key[0] == 'k') {
                e->kind = SIM_EVENT_KIDNAP;
                e->x_mm = v[1];
                e->y_mm = v[2];
                e->heading_deg = v[3];
            } else {
                e->kind = SIM_EVENT_PENALTY;
                e->duration_s = v[1];
            }
        } else {
            size_t i;
            for (i = 0; i < sizeof sim_keys / sizeof sim_keys[0]; i++)
                if (strcmp(key, sim_keys[i].key) == 0)
                    break;
            if (i == sizeof sim_keys / sizeof sim_keys[0]) {
                set_err(err, err_len, "unknown key", line);
                return -1;
            } else {
                double v[3];
                int j;
                if (parse_doubles(rest, v, sim_keys[i].n) != sim_keys[i].n) {
                    set_err(err, err_len, "wrong number of values", line);
                    return -1;
                }
                for (j = 0; j < sim_keys[i].n; j++)
                    memcpy((char *)sc + sim_keys[i].off[j], &v[j], sizeof(double));
            }
        }
        seen_key = 1;
    }
    sc->field = fl_field_find(sc->field_name);
    sc->camera = fl_camera_model_find(sc->camera_name);
    if (sim_scenario_check(sc, &why) != 0) {
        set_err(err, err_len, why, line);
        return -1;
    }
    return 0;
}

int sim_scenario_load(sim_scenario_t *sc, const char *path, char *err,
                      int err_len)
{
    FILE *f;
    char *buf;
    long n;
    int r;
    if (path == NULL || (f = fopen(path, "rb")) == NULL) {
        set_err(err, err_len, "cannot open scenario file", 0);
        return -1;
    }
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    if (n < 0 || n > 1000000 || (buf = malloc((size_t)n + 1)) == NULL) {
        fclose(f);
        set_err(err, err_len, "scenario file too large", 0);
        return -1;
    }
    if (fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        fclose(f);
        set_err(err, err_len, "read error", 0);
        return -1;
    }
    fclose(f);
    buf[n] = '\0';
    r = sim_scenario_parse(sc, buf, err, err_len);
    free(buf);
    return r;
}

int sim_scenario_write(FILE *f, const sim_scenario_t *sc)
{
    size_t i;
    int j;
    if (f == NULL || sc == NULL)
        return -1;
    fprintf(f, "robot %s\n", sc->robot == SIM_ROBOT_AIBO ? "aibo" : "nao");
    if (sc->name[0])
        fprintf(f, "name %s\n", sc->name);
    fprintf(f, "field %s\ncamera %s\nseed %llu\nneck_mm %ld\nfov_margin_px %ld\n"
               "camera_defaults %d\n",
            sc->field_name, sc->camera_name, (unsigned long long)sc->seed,
            (long)sc->neck_height_mm, (long)sc->fov_margin_px, sc->camera_defaults);
    for (i = 0; i < sizeof sim_keys / sizeof sim_keys[0]; i++) {
        fprintf(f, "%s", sim_keys[i].key);
        for (j = 0; j < sim_keys[i].n; j++) {
            double v;
            memcpy(&v, (const char *)sc + sim_keys[i].off[j], sizeof v);
            fprintf(f, " %.17g", v);
        }
        fputc('\n', f);
    }
    if (sc->hold_heading)
        fprintf(f, "face_deg %.17g\n", sc->face_deg);
    if (sc->route_once)
        fprintf(f, "route_once 1\n");
    for (j = 0; j < sc->n_waypoints; j++)
        fprintf(f, "waypoint %.17g %.17g\n", sc->waypoint[j].x_mm, sc->waypoint[j].y_mm);
    for (j = 0; j < sc->n_events; j++) {
        const sim_event_t *e = &sc->event[j];
        if (e->kind == SIM_EVENT_KIDNAP)
            fprintf(f, "kidnap %.17g %.17g %.17g %.17g\n", e->t_s, e->x_mm,
                    e->y_mm, e->heading_deg);
        else
            fprintf(f, "penalty %.17g %.17g\n", e->t_s, e->duration_s);
    }
    for (j = 0; j < sc->n_others; j++)
        fprintf(f, "other %.17g %.17g %.17g %s\n", sc->other[j].x_mm, sc->other[j].y_mm,
                sc->other[j].heading_deg,
                sc->other[j].jersey == RENDER_JERSEY_BLUE ? "blue" : "red");
    return ferror(f) ? -1 : 0;
}

/* ---- built-in scenarios (the committed fixtures/walks/NAME.walk) --------- */

static const char sim_text_spl2013[] =
    "# SPL 2013 field, NAO v4 top camera: a lap of the whole field.\n"
    "# Format: fixtures/walks/README.md.  Keys not given keep the defaults of\n"
    "# the robot (tools/world/sim.c, sim_scenario_defaults).\n"
    "robot nao\n"
    "name spl2013\n"
    "field spl2013\n"
    "camera nao4-top-320\n"
    "seed 2013\n"
    "frame_hz 30\n"
    "duration_s 130\n"
    "neck_mm 460\n"
    "head_pitch 0.25 0.45         # rad, + = down; alternates every 2 s\n"
    "pitch_period_s 4\n"
    "yaw_amplitude_rad 1.5\n"
    "yaw_period_s 6\n"
    "v_forward_mm_s 180\n"
    "v_side_mm_s 100\n"
    "turn_deg_s 45\n"
    "odo_scale 0.10 0.15 -0.07     # x, y, theta: odometry = true * (1 + s)\n"
    "odo_drift_deg_per_m 3\n"
    "odo_sigma_trans 0.10\n"
    "odo_sigma_rot 0.08\n"
    "odo_sigma_rot_deg_per_m 2\n"
    "slip_rate_hz 0.05\n"
    "slip_max 60 10\n"
    "max_range_mm 6000\n"
    "range_sigma_pct 8\n"
    "bearing_sigma_deg 1.5\n"
    "orientation_sigma_deg 5\n"
    "p_miss 0.2\n"
    "fp_per_frame 0.15\n"
    "p_confuse 0.05\n"
    "penalty_x_mm -1000\n"
    "start -3500 -2000 45\n"
    "waypoint -1500 0\n"
    "waypoint 0 1800\n"
    "waypoint 2500 1800\n"
    "waypoint 3500 0\n"
    "waypoint 2500 -2000\n"
    "waypoint 0 -1500\n"
    "waypoint -3000 -1800\n"
    "waypoint -3500 1500\n"
    "kidnap 55 2500 -1000 180\n"
    "penalty 95 8\n";

static const char sim_text_uva2013[] =
    "# UvA 2013 lab field, the UvA NAO v4 bottom camera as calibrated from the\n"
    "# dataset's labels (camera uva2013: its fitted neck height and pitch\n"
    "# offset), with the dataset's head pitch (-0.54 rad: looking up, so the\n"
    "# bottom camera sees the field ahead).\n"
    "robot nao\n"
    "name uva2013\n"
    "field uva2013\n"
    "camera uva2013\n"
    "camera_defaults 1\n"
    "seed 42\n"
    "frame_hz 30\n"
    "duration_s 125\n"
    "head_pitch -0.54 -0.54\n"
    "pitch_period_s 0\n"
    "yaw_amplitude_rad 1.2\n"
    "yaw_period_s 5\n"
    "v_forward_mm_s 150\n"
    "v_side_mm_s 80\n"
    "turn_deg_s 40\n"
    "odo_scale 0.08 0.12 -0.06\n"
    "odo_drift_deg_per_m 3\n"
    "odo_sigma_trans 0.10\n"
    "odo_sigma_rot 0.08\n"
    "odo_sigma_rot_deg_per_m 2\n"
    "slip_rate_hz 0.05\n"
    "slip_max 60 10\n"
    "max_range_mm 4500\n"
    "range_sigma_pct 8\n"
    "bearing_sigma_deg 1.5\n"
    "orientation_sigma_deg 5\n"
    "p_miss 0.2\n"
    "fp_per_frame 0.15\n"
    "p_confuse 0.05\n"
    "penalty_x_mm -600\n"
    "start -2200 -1200 30\n"
    "waypoint -800 300\n"
    "waypoint 1000 1300\n"
    "waypoint 2200 0\n"
    "waypoint 1000 -1300\n"
    "waypoint -800 -300\n"
    "waypoint -2200 1300\n"
    "kidnap 50 1500 1000 -90\n"
    "penalty 85 8\n";

static const char sim_text_aibo2004[] =
    "# AIBO 2004 four-legged league field, ERS-7 camera (208 x 160).\n"
    "robot aibo\n"
    "name aibo2004\n"
    "field aibo2004\n"
    "camera aibo-ers7\n"
    "seed 2004\n"
    "frame_hz 30\n"
    "duration_s 125\n"
    "neck_mm 160\n"
    "head_pitch 0.15 0.45\n"
    "pitch_period_s 4\n"
    "yaw_amplitude_rad 1.4\n"
    "yaw_period_s 4\n"
    "v_forward_mm_s 250\n"
    "v_side_mm_s 150\n"
    "turn_deg_s 90\n"
    "accel_mm_s2 500\n"
    "turn_accel_deg_s2 180\n"
    "odo_scale 0.08 0.15 0.08\n"
    "odo_drift_deg_per_m 4\n"
    "odo_sigma_trans 0.12\n"
    "odo_sigma_rot 0.10\n"
    "odo_sigma_rot_deg_per_m 3\n"
    "slip_rate_hz 0.1\n"
    "slip_max 80 15\n"
    "max_range_mm 3500\n"
    "range_sigma_pct 10\n"
    "bearing_sigma_deg 2\n"
    "orientation_sigma_deg 6\n"
    "p_miss 0.25\n"
    "fp_per_frame 0.2\n"
    "p_confuse 0.08\n"
    "penalty_x_mm 0\n"
    "start -1500 -800 0\n"
    "waypoint 0 -300\n"
    "waypoint 1500 800\n"
    "waypoint 1700 -900\n"
    "waypoint 0 400\n"
    "waypoint -1600 900\n"
    "waypoint -1700 -900\n"
    "kidnap 45 1200 -600 135\n"
    "penalty 80 6\n";

/* The spl2013 walk (same route, speeds, noise, kidnap and penalty, so the
 * numbers compare) on today's field: white goals, the larger penalty area
 * with a goal area, a NAO v6 top camera at 640 x 480 (the resolution the
 * vision path's per-frame budget is stated for), and six other robots
 * standing where the walk sees them (two teammates and the own keeper in
 * blue, three opponents in red), at least 0.6 m from where the walk goes
 * with seeds 1-6 (its own kidnap, or two: --kidnaps 2; the penalty on
 * either touchline). */
static const char sim_text_spl2020[] =
    "# SPL field since 2020 (white goals, penalty and goal areas), NAO v6 top\n"
    "# camera at 640 x 480: the spl2013 lap with other robots on the field.\n"
    "robot nao\n"
    "name spl2020\n"
    "field spl2020\n"
    "camera nao6-top-640\n"
    "seed 2020\n"
    "frame_hz 30\n"
    "duration_s 130\n"
    "neck_mm 460\n"
    "head_pitch 0.25 0.45\n"
    "pitch_period_s 4\n"
    "yaw_amplitude_rad 1.5\n"
    "yaw_period_s 6\n"
    "v_forward_mm_s 180\n"
    "v_side_mm_s 100\n"
    "turn_deg_s 45\n"
    "odo_scale 0.10 0.15 -0.07\n"
    "odo_drift_deg_per_m 3\n"
    "odo_sigma_trans 0.10\n"
    "odo_sigma_rot 0.08\n"
    "odo_sigma_rot_deg_per_m 2\n"
    "slip_rate_hz 0.05\n"
    "slip_max 60 10\n"
    "max_range_mm 6000\n"
    "range_sigma_pct 8\n"
    "bearing_sigma_deg 1.5\n"
    "orientation_sigma_deg 5\n"
    "p_miss 0.2\n"
    "fp_per_frame 0.15\n"
    "p_confuse 0.05\n"
    "penalty_x_mm -1000\n"
    "start -3500 -2000 45\n"
    "waypoint -1500 0\n"
    "waypoint 0 1800\n"
    "waypoint 2500 1800\n"
    "waypoint 3500 0\n"
    "waypoint 2500 -2000\n"
    "waypoint 0 -1500\n"
    "waypoint -3000 -1800\n"
    "waypoint -3500 1500\n"
    "kidnap 55 2500 -1000 180\n"
    "penalty 95 8\n"
    "# other robots: X_MM Y_MM HEADING_DEG jersey\n"
    "other -4200 0 0 blue          # own keeper\n"
    "other -3000 -2750 45 blue\n"
    "other -1700 1750 -30 blue\n"
    "other 4200 300 180 red        # their keeper\n"
    "other -250 -250 180 red       # in the centre circle\n"
    "other 3250 -2300 135 red\n";

/* Seed 002's setup: the scaled humanoid field hl3x2 with AcYut's head
 * camera (acyut-640, its default neck height 420 mm), at seed 002's frame
 * rate (about 20 fps, section VI).  The gait keeps the NAO defaults'
 * noise ("robot nao" is the humanoid body and walk model); speeds are a
 * kid-size humanoid's of that time (about 120 mm/s forward).  The head
 * pitch alternates 0.30 / 0.45 rad so the near ground and the poles are
 * both seen; the lap passes both poles, both goals and the circle. */
static const char sim_text_hl3x2[] =
    "# Seed 002's scaled humanoid field (3 m x 2 m, yellow and sky-blue goals,\n"
    "# YBY / BYB landmark poles), AcYut head camera at 640 x 480, 20 fps.\n"
    "robot nao\n"
    "name hl3x2\n"
    "field hl3x2\n"
    "camera acyut-640\n"
    "seed 2012\n"
    "frame_hz 20\n"
    "duration_s 120\n"
    "neck_mm 420\n"
    "head_pitch 0.30 0.45\n"
    "pitch_period_s 4\n"
    "yaw_amplitude_rad 1.2\n"
    "yaw_period_s 5\n"
    "v_forward_mm_s 120\n"
    "v_backward_mm_s 60\n"
    "v_side_mm_s 60\n"
    "turn_deg_s 40\n"
    "odo_scale 0.10 0.15 -0.07\n"
    "odo_drift_deg_per_m 3\n"
    "odo_sigma_trans 0.10\n"
    "odo_sigma_rot 0.08\n"
    "odo_sigma_rot_deg_per_m 2\n"
    "slip_rate_hz 0.05\n"
    "slip_max 40 10\n"
    "max_range_mm 3600\n"
    "range_sigma_pct 8\n"
    "bearing_sigma_deg 1.5\n"
    "orientation_sigma_deg 5\n"
    "p_miss 0.2\n"
    "fp_per_frame 0.15\n"
    "p_confuse 0.05\n"
    "penalty_x_mm -400\n"
    "start -1200 -700 30\n"
    "waypoint -400 200\n"
    "waypoint 600 700\n"
    "waypoint 1200 0\n"
    "waypoint 600 -700\n"
    "waypoint -400 -200\n"
    "waypoint -1200 700\n"
    "kidnap 50 900 500 -90\n"
    "penalty 85 6\n";

const char *const sim_builtin_names[SIM_BUILTIN_COUNT] = {"spl2013", "uva2013", "aibo2004",
                                                          "spl2020", "hl3x2"};

const char *sim_builtin_text(const char *name)
{
    if (name == NULL)
        return NULL;
    if (strcmp(name, "spl2013") == 0)
        return sim_text_spl2013;
    if (strcmp(name, "uva2013") == 0)
        return sim_text_uva2013;
    if (strcmp(name, "aibo2004") == 0)
        return sim_text_aibo2004;
    if (strcmp(name, "spl2020") == 0)
        return sim_text_spl2020;
    if (strcmp(name, "hl3x2") == 0)
        return sim_text_hl3x2;
    return NULL;
}

int sim_scenario_builtin(sim_scenario_t *sc, const char *name)
{
    const char *t = sim_builtin_text(name);
    if (t == NULL || sc == NULL)
        return -1;
    return sim_scenario_parse(sc, t, NULL, 0);
}

/* ---- the walk ------------------------------------------------------------ */

int sim_init(sim_t *sim, const sim_scenario_t *sc)
{
    const char *why;
    if (sim == NULL)
        return -1;
    memset(sim, 0, sizeof *sim);
    if (sc == NULL || sim_scenario_check(sc, &why) != 0)
        return -1;
    sim->sc = *sc;
    sim->rng = sim_seed_state(sc->seed);
    sim->n_steps = (uint32_t)(sc->duration_s * sc->frame_hz) + 1u;
    sim->x = sc->start_x_mm;
    sim->y = sc->start_y_mm;
    sim->h = sim_wrap(sc->start_heading_deg * SIM_DEG);
    sim->penalty_until_s = -1;
    return 0;
}

uint32_t sim_step_count(const sim_t *sim)
{
    return sim == NULL ? 0 : sim->n_steps;
}

int sim_set_others(sim_t *sim, const sim_other_t *other, int n)
{
    if (sim == NULL || n < 0 || n > SIM_MAX_OTHERS || (n > 0 && other == NULL))
        return -1;
    if (n > 0)
        memcpy(sim->sc.other, other, (size_t)n * sizeof *other);
    sim->sc.n_others = n;
    return 0;
}

int sim_set_route(sim_t *sim, const sim_waypoint_t *wp, int n)
{
    if (sim == NULL || wp == NULL || n < 1 || n > SIM_MAX_WAYPOINTS)
        return -1;
    memcpy(sim->sc.waypoint, wp, (size_t)n * sizeof *wp);
    sim->sc.n_waypoints = n;
    sim->wp = 0;
    sim->arrived = 0;
    return 0;
}

int sim_arrived(const sim_t *sim)
{
    return sim != NULL && sim->arrived;
}

/* Head angles at time t (triangle-wave yaw, two-level pitch). */
static void sim_head(const sim_scenario_t *sc, double t, double *pitch,
                     double *yaw)
{
    double p = t / sc->yaw_period_s, tri;
    p -= (double)(long long)p;   /* t >= 0: truncation is floor */
    tri = p < 0.25 ? 4 * p : p < 0.75 ? 2 - 4 * p : 4 * p - 4;
    *yaw = sc->yaw_amplitude_rad * tri;
    *pitch = sc->head_pitch_rad[0];
    if (sc->pitch_period_s > 0) {
        double q = t / sc->pitch_period_s;
        q -= (double)(long long)q;
        if (q >= 0.5)
            *pitch = sc->head_pitch_rad[1];
    }
}

/* Emit an integer delta with error diffusion. */
static int32_t sim_emit(double v, double *carry)
{
    double want = v + *carry;
    int32_t r = sim_iround(want);
    *carry = want - (double)r;
    return r;
}

static fl_angle_t sim_emit_angle(double rad, double *carry)
{
    return fl_angle_wrap(sim_emit(rad * (65536.0 / SIM_TWO_PI), carry));
}

/* Boxes enclosing a standing robot's body, its own frame (x forward, y
 * left, z up; mm): lo x, y, z then hi x, y, z.  They enclose render.c's
 * build_robot parts: NAO feet and legs, torso with the arms, the head;
 * AIBO legs, body, head. */
static const double sim_body_nao[3][6] = {
    {-60, -95, 0, 100, 95, 290},
    {-65, -148, 290, 65, 148, 565},
    {-72, -72, 565, 85, 72, 717}};
static const double sim_body_aibo[3][6] = {
    {-117, -77, 0, 117, 77, 140},
    {-130, -73, 130, 130, 73, 250},
    {95, -55, 230, 220, 55, 340}};

/* Does p + t d, t in [0, 1], meet the box b (slab test)? */
static int sim_segment_box(const double p[3], const double d[3], const double b[6])
{
    double t0 = 0, t1 = 1;
    int k;
    for (k = 0; k < 3; k++) {
        if (d[k] == 0) {
            if (p[k] < b[k] || p[k] > b[k + 3])
                return 0;
        } else {
            double ta = (b[k] - p[k]) / d[k], tb = (b[k + 3] - p[k]) / d[k];
            if (ta > tb) {
                double x = ta;
                ta = tb;
                tb = x;
            }
            if (ta > t0)
                t0 = ta;
            if (tb < t1)
                t1 = tb;
            if (t0 > t1)
                return 0;
        }
    }
    return 1;
}

/* The per-frame part of sim_occluded: the camera in the field frame and
 * each other robot's rounded pose and heading's sine and cosine (the same
 * arithmetic as computing them per test, so results are unchanged). */
typedef struct {
    const double (*body)[6];
    double c[3];
    int n;
    double ox[SIM_MAX_OTHERS], oy[SIM_MAX_OTHERS], os[SIM_MAX_OTHERS], oc[SIM_MAX_OTHERS];
} sim_occ_t;

static void sim_occ_prepare(sim_occ_t *o, const sim_scenario_t *sc, const fl_camera_t *cam,
                            int32_t x_mm, int32_t y_mm, fl_angle_t heading)
{
    double sh, ch, cxr, cyr;
    int i;
    o->n = 0;
    if (sc == NULL || cam == NULL || sc->n_others == 0)
        return;
    /* the renderer's rule: AIBO bodies on an aibo field or camera */
    o->body = strncmp(sc->field_name, "aibo", 4) == 0 ||
                      (sc->camera != NULL && strncmp(sc->camera->name, "aibo", 4) == 0)
                  ? sim_body_aibo : sim_body_nao;
    sim_sincos(sim_rad(heading), &sh, &ch);
    cxr = cam->pos_q4[0] / 16.0;
    cyr = cam->pos_q4[1] / 16.0;
    o->c[0] = x_mm + cxr * ch - cyr * sh;
    o->c[1] = y_mm + cxr * sh + cyr * ch;
    o->c[2] = cam->pos_q4[2] / 16.0;
    o->n = sc->n_others < SIM_MAX_OTHERS ? sc->n_others : SIM_MAX_OTHERS;
    for (i = 0; i < o->n; i++) {
        /* the segment in that robot's frame (its rounded pose, as rendered) */
        o->ox[i] = sim_iround(sc->other[i].x_mm);
        o->oy[i] = sim_iround(sc->other[i].y_mm);
        sim_sincos(sim_rad(sim_angle(sc->other[i].heading_deg * SIM_DEG)), &o->os[i], &o->oc[i]);
    }
}

static int sim_occ_test(const sim_occ_t *o, double fx, double fy, double fz)
{
    int i, j;
    for (i = 0; i < o->n; i++) {
        double ox = o->ox[i], oy = o->oy[i], os = o->os[i], oc = o->oc[i], p[3], q[3], d[3];
        p[0] = (o->c[0] - ox) * oc + (o->c[1] - oy) * os;
        p[1] = -(o->c[0] - ox) * os + (o->c[1] - oy) * oc;
        p[2] = o->c[2];
        q[0] = (fx - ox) * oc + (fy - oy) * os;
        q[1] = -(fx - ox) * os + (fy - oy) * oc;
        q[2] = fz;
        for (j = 0; j < 3; j++)
            d[j] = q[j] - p[j];
        for (j = 0; j < 3; j++)
            if (sim_segment_box(p, d, o->body[j]))
                return 1;
    }
    return 0;
}

int sim_occluded(const sim_scenario_t *sc, const fl_camera_t *cam, int32_t x_mm,
                 int32_t y_mm, fl_angle_t heading, double fx, double fy, double fz)
{
    sim_occ_t o;
    sim_occ_prepare(&o, sc, cam, x_mm, y_mm, heading);
    return sim_occ_test(&o, fx, fy, fz);
}

/* A kind the field has among those the vision mode observes (landmark
 * kinds for ltx, seed 004's feature kinds for corners, both for both). */
static fl_landmark_kind_t sim_kind_present(const fl_field_t *f, int vision, uint64_t *rng)
{
    fl_landmark_kind_t kinds[FL_LM_KIND_COUNT];
    int n = 0, k;
    for (k = 0; k < FL_LM_KIND_COUNT; k++) {
        int feat = fl_landmark_kind_is_feature((fl_landmark_kind_t)k);
        if ((feat && vision == SIM_VISION_LTX) || (!feat && vision == SIM_VISION_CORNERS))
            continue;
        if (fl_field_count_kind(f, (fl_landmark_kind_t)k) > 0)
            kinds[n++] = (fl_landmark_kind_t)k;
    }
    if (n == 0)
        return FL_LM_L;
    k = (int)(sim_u01(rng) * n);
    return kinds[k < n ? k : n - 1];
}

/* ---- painted-line points (feature mode's "white points") ------------------ */

/* Is the ground point (rx, ry) (robot frame, mm) one the camera sees:
 * inside the image by fov_margin_px, within max range, not behind another
 * robot?  (fx, fy): the same point in the field frame. */
static int sim_point_visible(const sim_scenario_t *sc, const fl_camera_t *cam,
                             const sim_occ_t *occ, double rx, double ry, double fx, double fy)
{
    fl_point_t gp;
    int32_t u, v, m = 16 * sc->fov_margin_px;
    if (rx * rx + ry * ry > sc->max_range_mm * sc->max_range_mm)
        return 0;
    gp.x_mm = sim_iround(rx);
    gp.y_mm = sim_iround(ry);
    if (!fl_camera_ground_to_pixel(cam, gp, &u, &v) || u < m || v < m ||
        u > 16 * (cam->model.width_px - 1) - m || v > 16 * (cam->model.height_px - 1) - m)
        return 0;
    return !sim_occ_test(occ, fx, fy, 0);
}

/* Is every point of line l (NULL: the centre circle of radius r_mm) farther
 * than far mm from (x_mm, y_mm)? */
static int sim_beyond(const fl_field_line_t *l, int32_t r_mm, int32_t x_mm, int32_t y_mm,
                      double far)
{
    double px = x_mm, py = y_mm, d;
    if (l == NULL) {
        d = fabs(sqrt(px * px + py * py) - r_mm);
    } else {
        double ax = l->x0_mm, ay = l->y0_mm, bx = l->x1_mm - ax, by = l->y1_mm - ay;
        double len2 = bx * bx + by * by, t = 0, ex, ey;
        if (len2 > 0)
            t = ((px - ax) * bx + (py - ay) * by) / len2;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        ex = px - (ax + t * bx);
        ey = py - (ay + t * by);
        d = sqrt(ex * ex + ey * ey);
    }
    return d > far;
}

/* Reservoir sample (Algorithm R) of the visible painted-line points: the
 * lines and the centre circle walked every SIM_POINT_STEP_MM, each point
 * moved across the paint by a uniform offset within the line width; then
 * range and bearing noise as the landmarks' (range_sigma_pct,
 * bearing_sigma_deg).  Its own random stream, seeded from *rng without
 * advancing it, so the landmark observations (and every trace) are the
 * same with or without points. */
static void sim_observe_points(const sim_scenario_t *sc, const fl_camera_t *cam,
                               const sim_occ_t *occ, int32_t x_mm, int32_t y_mm,
                               fl_angle_t heading, const uint64_t *rng, sim_step_t *out)
{
    const fl_field_t *f = sc->field;
    double pick[SIM_POINTS_PER_FRAME > 0 ? SIM_POINTS_PER_FRAME : 1][2], sh, ch, lw = f->line_width_mm;
    uint64_t prng = *rng ^ 0x5bd1e9955bd1e995ULL;
    long seen = 0;
    int i, k, n_circle = 0;
    /* a line (or the circle) whose every point is beyond max range by more
     * than the paint's width is skipped whole: its offsets are still drawn,
     * so the stream, and every result, is the same as testing each point */
    double far = sc->max_range_mm + lw + 1.0;
    sim_sincos(sim_rad(heading), &sh, &ch);
    if (f->circle_radius_mm > 0)
        n_circle = (int)(SIM_TWO_PI * f->circle_radius_mm / SIM_POINT_STEP_MM);
    for (i = 0; i < f->n_lines + (n_circle > 0); i++) {
        const fl_field_line_t *l = i < f->n_lines ? &f->lines[i] : NULL;
        double len = l ? sqrt((double)(l->x1_mm - l->x0_mm) * (l->x1_mm - l->x0_mm) +
                              (double)(l->y1_mm - l->y0_mm) * (l->y1_mm - l->y0_mm))
                       : 0;
        int n = l ? (int)(len / SIM_POINT_STEP_MM) + 1 : n_circle;
        if (sim_beyond(l, f->circle_radius_mm, x_mm, y_mm, far)) {
            for (k = 0; k < n; k++)
                (void)sim_u01(&prng);
            continue;
        }
        for (k = 0; k < n; k++) {
            double fx, fy, across = (sim_u01(&prng) - 0.5) * lw, dx, dy, rx, ry;
            if (l) {
                double t = n > 1 ? (double)k / (n - 1) : 0.5;
                double nx = len > 0 ? -(l->y1_mm - l->y0_mm) / len : 0;
                double ny = len > 0 ? (l->x1_mm - l->x0_mm) / len : 0;
                fx = l->x0_mm + t * (l->x1_mm - l->x0_mm) + across * nx;
                fy = l->y0_mm + t * (l->y1_mm - l->y0_mm) + across * ny;
            } else {
                double a = SIM_TWO_PI * k / n, sa, ca;
                sim_sincos(a, &sa, &ca);
                fx = (f->circle_radius_mm + across) * ca;
                fy = (f->circle_radius_mm + across) * sa;
            }
            dx = fx - x_mm;
            dy = fy - y_mm;
            rx = dx * ch + dy * sh;
            ry = -dx * sh + dy * ch;
            if (!sim_point_visible(sc, cam, occ, rx, ry, fx, fy))
                continue;
            if (seen < SIM_POINTS_PER_FRAME) {
                pick[seen][0] = rx;
                pick[seen][1] = ry;
            } else {
                long j = (long)(sim_u01(&prng) * (double)(seen + 1));
                if (j < SIM_POINTS_PER_FRAME) {
                    pick[j][0] = rx;
                    pick[j][1] = ry;
                }
            }
            seen++;
        }
    }
    for (k = 0; k < SIM_POINTS_PER_FRAME && k < seen; k++) {
        double g_r = sim_gauss(&prng), g_b = sim_gauss(&prng), s, c;
        double r = sqrt(pick[k][0] * pick[k][0] + pick[k][1] * pick[k][1]);
        double b = sim_atan2(pick[k][1], pick[k][0]) + g_b * sc->bearing_sigma_deg * SIM_DEG;
        r *= 1.0 + g_r * sc->range_sigma_pct / 100.0;
        sim_sincos(b, &s, &c);
        (void)fl_obs_list_push_point(&out->obs, sim_iround(r * c), sim_iround(r * s));
    }
}

void sim_observe(const sim_scenario_t *sc, const fl_camera_t *cam,
                 int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                 uint64_t *rng, sim_step_t *out)
{
    const fl_field_t *f;
    double hr = sim_rad(heading), ch, sh;
    int i, n_fp = 0, trials;
    int seen_goal[2] = {0, 0};
    int32_t umin, umax, vmin, vmax;
    sim_occ_t occ;
    if (sc == NULL || cam == NULL || rng == NULL || out == NULL)
        return;
    fl_obs_list_clear(&out->obs);
    f = sc->field;
    if (f == NULL)
        return;
    sim_sincos(hr, &sh, &ch);
    umin = 16 * sc->fov_margin_px;
    vmin = umin;
    umax = 16 * (cam->model.width_px - 1 - sc->fov_margin_px);
    vmax = 16 * (cam->model.height_px - 1 - sc->fov_margin_px);
    sim_occ_prepare(&occ, sc, cam, x_mm, y_mm, heading);
    if (sc->white_points)
        sim_observe_points(sc, cam, &occ, x_mm, y_mm, heading, rng, out);

    /* ids of fl_field_all_at: the landmarks (ltx, both), then seed 004's
     * features (corners, both) */
    for (i = sc->vision == SIM_VISION_CORNERS ? f->n_landmarks : 0;
         i < (sc->vision == SIM_VISION_LTX ? f->n_landmarks : fl_field_n_all(f)); i++) {
        const fl_landmark_t *lm = fl_field_all_at(f, (uint16_t)i);
        double dx = (double)lm->x_mm - x_mm, dy = (double)lm->y_mm - y_mm;
        double rx = dx * ch + dy * sh, ry = -dx * sh + dy * ch;
        double range = sqrt(dx * dx + dy * dy), bearing;
        fl_point_t gp;
        int32_t u, v;
        fl_obs_t o;
        fl_angle_t ori;
        gp.x_mm = sim_iround(rx);
        gp.y_mm = sim_iround(ry);
        if (range > sc->max_range_mm ||
            !fl_camera_ground_to_pixel(cam, gp, &u, &v) ||
            u < umin || u > umax || v < vmin || v > vmax ||
            sim_occ_test(&occ, lm->x_mm, lm->y_mm, 0))
            continue;
        /* every random draw below happens for every visible landmark, so
         * the stream does not depend on the outcome of earlier draws */
        {
            double g_r = sim_gauss(rng), g_b = sim_gauss(rng), g_o = sim_gauss(rng);
            double u_miss = sim_u01(rng), u_conf = sim_u01(rng);
            double u_c = sim_u01(rng);
            if (u_miss < sc->p_miss)
                continue;
            memset(&o, 0, sizeof o);
            o.kind = lm->kind;
            if (u_conf < sc->p_confuse && (lm->kind == FL_LM_L || lm->kind == FL_LM_T))
                o.kind = lm->kind == FL_LM_L ? FL_LM_T : FL_LM_L;
            range *= 1.0 + g_r * sc->range_sigma_pct / 100.0;
            o.range_mm = range < 0 ? 0 : sim_iround(range);
            bearing = sim_atan2(dy, dx) - hr + g_b * sc->bearing_sigma_deg * SIM_DEG;
            o.bearing = sim_angle(bearing);
            if (fl_landmark_orientation(lm, &ori)) {
                o.has_orientation = true;
                o.orientation = sim_angle(sim_rad(ori) - hr +
                                          g_o * sc->orientation_sigma_deg * SIM_DEG);
            }
            o.side = FL_SIDE_UNKNOWN;
            o.color = lm->color;
            o.color2 = lm->color2;   /* beacons: lower band, as the vision stage reports it */
            o.confidence = (uint8_t)(160 + (int)(u_c * 96));
            o.u_q4 = u;
            o.v_q4 = v;
            if (lm->kind == FL_LM_POST && lm->goal != 0)
                seen_goal[lm->goal > 0]++;
            if (out->obs.n < FL_OBS_MAX) {
                out->obs_landmark[out->obs.n] = (int16_t)i;
                out->obs_confused[out->obs.n] = (uint8_t)(o.kind != lm->kind);
            }
            fl_obs_list_push(&out->obs, &o);
        }
    }
    /* goal-post sides: known only when both posts of that goal are seen */
    for (i = 0; i < out->obs.n; i++) {
        const fl_landmark_t *lm = fl_field_all_at(f, (uint16_t)out->obs_landmark[i]);
        if (lm->kind == FL_LM_POST && lm->goal != 0 && seen_goal[lm->goal > 0] >= 2)
            out->obs.obs[i].side = lm->side;
    }
    /* false positives: binomial(8, fp/8) of them, at random pixels below
     * the horizon within max range */
    for (trials = 0; trials < 8; trials++)
        if (sim_u01(rng) < sc->fp_per_frame / 8.0)
            n_fp++;
    for (i = 0; i < n_fp; i++) {
        int tries;
        for (tries = 0; tries < 8; tries++) {
            int32_t u = umin + (int32_t)(sim_u01(rng) * (double)(umax - umin + 1));
            int32_t v = vmin + (int32_t)(sim_u01(rng) * (double)(vmax - vmin + 1));
            fl_landmark_kind_t kind = sim_kind_present(f, sc->vision, rng);
            double u_c = sim_u01(rng), u_o = sim_u01(rng);
            fl_point_t gp;
            fl_obs_t o;
            if (!fl_camera_pixel_to_ground(cam, u, v, &gp))
                continue;
            if (sqrt((double)gp.x_mm * gp.x_mm + (double)gp.y_mm * gp.y_mm) >
                sc->max_range_mm)
                continue;
            memset(&o, 0, sizeof o);
            o.kind = kind;
            o.range_mm = sim_iround(sqrt((double)gp.x_mm * gp.x_mm +
                                         (double)gp.y_mm * gp.y_mm));
            o.bearing = sim_angle(sim_atan2(gp.y_mm, gp.x_mm));
            o.has_orientation = kind != FL_LM_POST && kind != FL_LM_BEACON && kind != FL_LM_NET;
            o.orientation = o.has_orientation ? sim_angle((u_o - 0.5) * SIM_TWO_PI) : 0;
            o.side = FL_SIDE_UNKNOWN;
            o.color = kind == FL_LM_POST || kind == FL_LM_NET ? f->goal_color[u_o < 0.5 ? 0 : 1]
                       : kind == FL_LM_BEACON ? FL_COLOR_PINK : FL_COLOR_NONE;
            o.confidence = (uint8_t)(160 + (int)(u_c * 96));
            o.u_q4 = u;
            o.v_q4 = v;
            if (out->obs.n < FL_OBS_MAX) {
                out->obs_landmark[out->obs.n] = -1;
                out->obs_confused[out->obs.n] = 0;
            }
            fl_obs_list_push(&out->obs, &o);
            break;
        }
    }
}

/* Velocity command toward the current waypoint, with acceleration limits. */
static void sim_control(sim_t *s, double dt)
{
    const sim_scenario_t *sc = &s->sc;
    double tx, ty, dx, dy, rx, ry, dist, b, ch, sh;
    double want_v, want_s, want_w, dv, dw;
    int guard;
    for (guard = 0; guard < sc->n_waypoints && !s->arrived; guard++) {
        tx = sc->waypoint[s->wp].x_mm;
        ty = sc->waypoint[s->wp].y_mm;
        dx = tx - s->x;
        dy = ty - s->y;
        if (sqrt(dx * dx + dy * dy) > sc->arrive_mm)
            break;
        if (sc->route_once && s->wp == sc->n_waypoints - 1)
            s->arrived = 1;
        else
            s->wp = (s->wp + 1) % sc->n_waypoints;
    }
    tx = sc->waypoint[s->wp].x_mm;
    ty = sc->waypoint[s->wp].y_mm;
    dx = tx - s->x;
    dy = ty - s->y;
    sim_sincos(s->h, &sh, &ch);
    rx = dx * ch + dy * sh;
    ry = -dx * sh + dy * ch;
    dist = sqrt(rx * rx + ry * ry);
    b = sim_atan2(ry, rx);
    want_w = sim_clamp(2.0 * b, sc->turn_deg_s * SIM_DEG);
    if (s->arrived) {
        /* stand at the end of the route, facing as it is */
        want_v = want_s = want_w = 0;
    } else if (sc->hold_heading) {
        /* keep facing face_deg; walk toward the waypoint with the gait's
         * forward and sideways speeds (same proportional gain as the side
         * step below, so the robot slows down on arrival) */
        want_w = sim_clamp(2.0 * sim_wrap(sc->face_deg * SIM_DEG - s->h),
                           sc->turn_deg_s * SIM_DEG);
        want_v = rx >= 0 ? sim_clamp(0.5 * rx, sc->v_forward_mm_s)
                         : sim_clamp(0.5 * rx, sc->v_backward_mm_s);
        want_s = sim_clamp(0.5 * ry, sc->v_side_mm_s);
    } else if (sim_abs(b) < 60 * SIM_DEG) {
        want_v = sc->v_forward_mm_s * (1.0 - sim_abs(b) / (60 * SIM_DEG));
        want_s = sim_clamp(0.5 * ry, sc->v_side_mm_s);
    } else {
        want_v = 0;
        want_s = 0;
    }
    (void)dist;
    dv = sc->accel_mm_s2 * dt;
    dw = sc->turn_accel_deg_s2 * SIM_DEG * dt;
    s->vx += sim_clamp(want_v - s->vx, dv);
    s->vy += sim_clamp(want_s - s->vy, dv);
    s->vh += sim_clamp(want_w - s->vh, dw);
}

static void sim_move(double *x, double *y, double *h, double dx, double dy,
                     double dth)
{
    double s, c;
    sim_sincos(*h, &s, &c);
    *x += dx * c - dy * s;
    *y += dx * s + dy * c;
    *h = sim_wrap(*h + dth);
}

int sim_step(sim_t *s, sim_step_t *out)
{
    const sim_scenario_t *sc;
    double dt, t, pitch, yaw;
    double wx = 0, wy = 0, wth = 0, tx = 0, ty = 0, tth = 0;
    double ox = 0, oy = 0, oth = 0;
    if (s == NULL || out == NULL || s->k >= s->n_steps)
        return 0;
    sc = &s->sc;
    memset(out, 0, sizeof *out);
    dt = 1.0 / sc->frame_hz;
    t = (double)s->k / sc->frame_hz;
    out->index = s->k;
    out->t_ms = sim_iround(t * 1000.0);

    if (s->k > 0) {
        /* end of a penalty: walking resumes with this step */
        if (s->penalty_until_s >= 0 && t > s->penalty_until_s + 0.5 * dt) {
            out->events |= SIM_EV_UNPENALIZED;
            s->penalty_until_s = -1;
        }
        /* 1. motion */
        if (s->penalty_until_s < 0) {
            sim_control(s, dt);
            wx = s->vx * dt;
            wy = s->vy * dt;
            wth = s->vh * dt;
        }
        {
            double L = sqrt(wx * wx + wy * wy);
            double g1 = sim_gauss(&s->rng), g2 = sim_gauss(&s->rng);
            double g3 = sim_gauss(&s->rng), u_slip = sim_u01(&s->rng);
            double s1 = sim_uniform(&s->rng, -1, 1), s2 = sim_uniform(&s->rng, -1, 1);
            double s3 = sim_uniform(&s->rng, -1, 1);
            tx = wx;
            ty = wy;
            tth = wth;
            /* slips only while walking (above 10% of full speed) */
            if (L > 0.1 * sc->v_forward_mm_s * dt &&
                u_slip < sc->slip_rate_hz * dt) {
                tx += s1 * sc->slip_max_mm;
                ty += s2 * sc->slip_max_mm;
                tth += s3 * sc->slip_max_deg * SIM_DEG;
                out->events |= SIM_EV_SLIP;
            }
            ox = wx * (1 + sc->odo_scale_x) + g1 * sc->odo_sigma_trans * L;
            oy = wy * (1 + sc->odo_scale_y) + g2 * sc->odo_sigma_trans * L;
            oth = wth * (1 + sc->odo_scale_theta) +
                  sc->odo_drift_deg_per_m * SIM_DEG * L / 1000.0 +
                  g3 * (sc->odo_sigma_rot * sim_abs(wth) +
                        sc->odo_sigma_rot_deg_per_m * SIM_DEG * L / 1000.0);
        }
        sim_move(&s->x, &s->y, &s->h, tx, ty, tth);

    }
    /* 2. events */
    while (s->next_event < sc->n_events &&
           sc->event[s->next_event].t_s <= t + 0.5 * dt) {
        const sim_event_t *e = &sc->event[s->next_event++];
        if (e->kind == SIM_EVENT_KIDNAP) {
            s->x = e->x_mm;
            s->y = e->y_mm;
            s->h = sim_wrap(e->heading_deg * SIM_DEG);
            out->events |= SIM_EV_KIDNAP;
        } else {
            double side = sim_u01(&s->rng) < 0.5 ? 1.0 : -1.0;
            s->x = sc->penalty_x_mm;
            s->y = side * (double)sc->field->width_mm / 2.0;
            s->h = side > 0 ? -SIM_PI / 2 : SIM_PI / 2;
            s->penalty_until_s = t + e->duration_s;
            out->events |= SIM_EV_PENALIZED;
            out->events &= ~SIM_EV_UNPENALIZED;
        }
        s->vx = s->vy = s->vh = 0;
    }
    out->penalized = s->penalty_until_s >= 0;

    /* outputs: pose, motion, odometry */
    out->true_x_mm = s->x;
    out->true_y_mm = s->y;
    out->true_heading_rad = s->h;
    out->x_mm = sim_iround(s->x);
    out->y_mm = sim_iround(s->y);
    out->heading = sim_angle(s->h);
    out->true_dx = tx;
    out->true_dy = ty;
    out->true_dtheta_rad = tth;
    out->true_dx_mm = sim_emit(tx, &s->carry[0]);
    out->true_dy_mm = sim_emit(ty, &s->carry[1]);
    out->true_dtheta = sim_emit_angle(tth, &s->carry[2]);
    out->odo_dx = ox;
    out->odo_dy = oy;
    out->odo_dtheta_rad = oth;
    out->odo_dx_mm = sim_emit(ox, &s->carry[3]);
    out->odo_dy_mm = sim_emit(oy, &s->carry[4]);
    out->odo_dtheta = sim_emit_angle(oth, &s->carry[5]);

    /* 3. head and observations */
    sim_head(sc, t, &pitch, &yaw);
    out->head.neck_height_mm = sc->camera_defaults ? sc->camera->default_neck_height_mm
                                                   : sc->neck_height_mm;
    out->head.head_pitch = sim_angle(pitch);
    out->head.head_yaw = sim_angle(yaw);
    out->head.pitch_offset = sc->camera_defaults ? sc->camera->default_pitch_offset
                                                 : sim_angle(sc->pitch_offset_deg * SIM_DEG);
    out->head_pitch_rad = sim_rad(out->head.head_pitch);
    out->head_yaw_rad = sim_rad(out->head.head_yaw);
    if (fl_camera_init(&s->cam, sc->camera, &out->head) == FL_OK)
        sim_observe(sc, &s->cam, out->x_mm, out->y_mm, out->heading, &s->rng, out);
    else
        fl_obs_list_clear(&out->obs);
    s->k++;
    return 1;
}

/* ---- trace ---------------------------------------------------------------- */

static char sim_kind_char(fl_landmark_kind_t k)
{
    static const char c[FL_LM_KIND_COUNT + 1] = "LTXPCGOBcfnN";
    return (int)k >= 0 && k < FL_LM_KIND_COUNT ? c[k] : '?';
}

static char sim_color_char(fl_color_t c)
{
    static const char s[] = "-wysp";
    return (int)c >= 0 && (int)c < 5 ? s[c] : '?';
}

int sim_write_trace(FILE *f, const sim_scenario_t *sc)
{
    sim_t *s;
    sim_step_t st;
    int i;
    if (f == NULL || sc == NULL)
        return -1;
    s = malloc(sizeof *s);
    if (s == NULL || sim_init(s, sc) != 0) {
        free(s);
        return -1;
    }
    fprintf(f, "# fieldloc walk trace v1: generated by tools/world/sim.c from %s.walk"
               " (format: fixtures/walks/README.md)\n",
            sc->name[0] ? sc->name : "scenario");
    fprintf(f, "walk %s field %s camera %s steps %lu seed %llu\n",
            sc->name[0] ? sc->name : "-", sc->field_name, sc->camera_name,
            (unsigned long)s->n_steps, (unsigned long long)sc->seed);
    fprintf(f, "# s K T_MS  X Y H  TDX TDY TDH  ODX ODY ODH  PITCH YAW  EVENTS NOBS"
               "   (mm, binary angles 65536/turn)\n");
    fprintf(f, "# o KIND RANGE BEARING ORIENT|- SIDE COLOUR CONF U_Q4 V_Q4 LANDMARK|-1"
               " [c=confused]\n");
    while (sim_step(s, &st)) {
        fprintf(f, "s %lu %ld %ld %ld %d %ld %ld %d %ld %ld %d %d %d %u %u\n",
                (unsigned long)st.index, (long)st.t_ms, (long)st.x_mm,
                (long)st.y_mm, st.heading, (long)st.true_dx_mm,
                (long)st.true_dy_mm, st.true_dtheta, (long)st.odo_dx_mm,
                (long)st.odo_dy_mm, st.odo_dtheta, st.head.head_pitch,
                st.head.head_yaw, st.events, (unsigned)st.obs.n);
        for (i = 0; i < st.obs.n; i++) {
            const fl_obs_t *o = &st.obs.obs[i];
            char ori[16];
            if (o->has_orientation)
                snprintf(ori, sizeof ori, "%d", o->orientation);
            else
                snprintf(ori, sizeof ori, "-");
            fprintf(f, "o %c %ld %d %s %c %c %u %ld %ld %d%s\n",
                    sim_kind_char(o->kind), (long)o->range_mm, o->bearing, ori,
                    "ulr"[o->side <= FL_SIDE_RIGHT ? o->side : 0],
                    sim_color_char(o->color), (unsigned)o->confidence,
                    (long)o->u_q4, (long)o->v_q4, st.obs_landmark[i],
                    st.obs_confused[i] ? " c" : "");
        }
    }
    free(s);
    return ferror(f) ? -1 : 0;
}

int sim_write_walk_fixtures(const char *out_dir)
{
    int i;
    if (out_dir == NULL)
        return -1;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        const char *name = sim_builtin_names[i];
        const char *text = sim_builtin_text(name);
        char path[1024], err[128];
        sim_scenario_t sc;
        FILE *f;
        int bad;
        snprintf(path, sizeof path, "%s/%s.walk", out_dir, name);
        if ((f = fopen(path, "wb")) == NULL) {
            fprintf(stderr, "sim: cannot write %s\n", path);
            return -1;
        }
        bad = fputs(text, f) < 0;
        bad |= fclose(f) != 0;
        if (bad)
            return -1;
        /* the trace is generated from the file just written */
        if (sim_scenario_load(&sc, path, err, (int)sizeof err) != 0) {
            fprintf(stderr, "sim: %s: %s\n", path, err);
            return -1;
        }
        snprintf(path, sizeof path, "%s/%s.trace", out_dir, name);
        if ((f = fopen(path, "wb")) == NULL) {
            fprintf(stderr, "sim: cannot write %s\n", path);
            return -1;
        }
        bad = sim_write_trace(f, &sc) != 0;
        bad |= fclose(f) != 0;
        if (bad)
            return -1;
    }
    return SIM_BUILTIN_COUNT;
}

/* ---- mode (b): rendered frames -------------------------------------------- */

/* Weak references: the simulator links (and mode (a) works) even in a build
 * without tools/world/render.c; mode (b) then fails with -1. */
#pragma weak render_scene_default
#pragma weak render_frame
#pragma weak render_write_frame
#pragma weak render_frame_free

void sim_render_scene(const sim_scenario_t *sc, const sim_step_t *st,
                      render_scene_t *scene)
{
    int i;
    if (sc == NULL || st == NULL || scene == NULL || render_scene_default == NULL)
        return;
    render_scene_default(scene, sc->field, sc->camera);
    scene->robot_x_mm = st->x_mm;
    scene->robot_y_mm = st->y_mm;
    scene->robot_heading = st->heading;
    scene->head = st->head;
    scene->seed = (uint32_t)(sc->seed * 2654435761u) ^ (st->index * 40503u + 1u);
    for (i = 0; i < sc->n_others && i < RENDER_MAX_ROBOTS; i++) {
        scene->robots[i].x_mm = sim_iround(sc->other[i].x_mm);
        scene->robots[i].y_mm = sim_iround(sc->other[i].y_mm);
        scene->robots[i].heading = sim_angle(sc->other[i].heading_deg * SIM_DEG);
        scene->robots[i].jersey = sc->other[i].jersey;
    }
    scene->n_robots = i;
}

static void sim_print_fixed(FILE *f, double v, int decimals)
{
    /* deterministic decimal: round to 10^-decimals, print as integer parts */
    double scale = decimals == 3 ? 1000.0 : decimals == 6 ? 1000000.0 : 10.0;
    long long k = (long long)sim_round(v * scale), a = k < 0 ? -k : k;
    fprintf(f, "%s%lld.%0*lld", k < 0 ? "-" : "", a / (long long)scale, decimals,
            a % (long long)scale);
}

int sim_write_sequence(const sim_scenario_t *sc, const char *seq_path,
                       const char *image_prefix, int every, int max_frames,
                       int with_prior)
{
    sim_t *s;
    sim_step_t st;
    FILE *f;
    char dir[1024], path[1200];
    const char *slash;
    double ax = 0, ay = 0, ah = 0;     /* odometry since the last frame */
    double cx = 0, cy = 0, ca = 0;     /* rounding carries (mm, deg) */
    int frames = 0, status = 0;
    if (sc == NULL || seq_path == NULL || image_prefix == NULL || every < 1 ||
        render_scene_default == NULL || render_frame == NULL ||
        render_write_frame == NULL || render_frame_free == NULL)
        return -1;
    slash = strrchr(seq_path, '/');
    if (slash == NULL)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - seq_path), seq_path);
    /* create the image folder when the prefix names one */
    slash = strrchr(image_prefix, '/');
    if (slash != NULL) {
        snprintf(path, sizeof path, "%s/%.*s", dir, (int)(slash - image_prefix),
                 image_prefix);
        mkdir(path, 0777);
    }
    s = malloc(sizeof *s);
    if (s == NULL || sim_init(s, sc) != 0 || (f = fopen(seq_path, "w")) == NULL) {
        free(s);
        return -1;
    }
    fprintf(f, "field %s\ncamera %s\n", sc->field_name, sc->camera_name);
    if (with_prior) {
        fprintf(f, "prior ");
        sim_print_fixed(f, sc->start_x_mm, 1);
        fputc(' ', f);
        sim_print_fixed(f, sc->start_y_mm, 1);
        fputc(' ', f);
        sim_print_fixed(f, sc->start_heading_deg, 3);
        fputc('\n', f);
    }
    while (sim_step(s, &st)) {
        render_scene_t scene;
        render_frame_t fr;
        double a, b;
        /* compose this step's odometry onto the accumulated motion */
        a = st.odo_dx;
        b = st.odo_dy;
        {
            double sn, cs;
            sim_sincos(ah, &sn, &cs);
            ax += a * cs - b * sn;
            ay += a * sn + b * cs;
            ah += st.odo_dtheta_rad;
        }
        if (st.index % (uint32_t)every != 0)
            continue;
        if (max_frames > 0 && frames >= max_frames)
            break;
        sim_render_scene(sc, &st, &scene);
        /* what `localize` will assume (lr_camera_pose): the camera's defaults */
        scene.head.neck_height_mm = sc->camera->default_neck_height_mm;
        scene.head.pitch_offset = sc->camera->default_pitch_offset;
        snprintf(path, sizeof path, "%s/%s%05lu.ppm", dir, image_prefix,
                 (unsigned long)st.index);
        if (render_frame(&scene, &fr) != 0) {
            status = -1;
            break;
        }
        if (render_write_frame(path, &fr) != 0)
            status = -1;
        render_frame_free(&fr);
        if (status != 0)
            break;
        {
            double ox = ax + cx, oy = ay + cy;
            double rx = sim_round(ox * 10) / 10, ry = sim_round(oy * 10) / 10;
            double oa = ah / SIM_DEG + ca, ra = sim_round(oa * 1000) / 1000;
            cx = ox - rx;
            cy = oy - ry;
            ca = oa - ra;
            fprintf(f, "frame %s%05lu.ppm odo ", image_prefix, (unsigned long)st.index);
            sim_print_fixed(f, ox, 1);
            fputc(' ', f);
            sim_print_fixed(f, oy, 1);
            fputc(' ', f);
            sim_print_fixed(f, oa, 3);
            fprintf(f, " head ");
            sim_print_fixed(f, st.head_pitch_rad, 6);
            fputc(' ', f);
            sim_print_fixed(f, st.head_yaw_rad, 6);
            fputc('\n', f);
        }
        ax = ay = ah = 0;
        frames++;
    }
    if (fclose(f) != 0)
        status = -1;
    free(s);
    return status;
}

/* ---- kidnaps added to a scenario ------------------------------------------- */

/* Distance (s) from t to the nearest busy time: the start, the end, a
 * kidnap, a penalty (from its start to its end). */
static double sim_kidnap_room(const sim_scenario_t *sc, double t)
{
    double d = t < sc->duration_s - t ? t : sc->duration_s - t, e;
    int j;
    for (j = 0; j < sc->n_events; j++) {
        const sim_event_t *ev = &sc->event[j];
        double end = ev->kind == SIM_EVENT_PENALTY ? ev->t_s + ev->duration_s : ev->t_s;
        e = t < ev->t_s ? ev->t_s - t : t > end ? t - end : 0;
        if (e < d)
            d = e;
    }
    return d;
}

int sim_scenario_set_kidnaps(sim_scenario_t *sc, int n)
{
    uint64_t rng;
    int own = 0, j, k, add;
    size_t len;
    if (sc == NULL || sc->field == NULL || n < 0)
        return -1;
    for (j = 0; j < sc->n_events; j++)
        own += sc->event[j].kind == SIM_EVENT_KIDNAP;
    if (n == own)
        return 0;
    if (n > own && sc->n_events + (n - own) > SIM_MAX_EVENTS)
        return -1;
    if (n < own) {
        /* keep the first n kidnaps (time order) and every penalty */
        int kept = 0, m = 0;
        for (j = 0; j < sc->n_events; j++) {
            if (sc->event[j].kind == SIM_EVENT_KIDNAP && kept++ >= n)
                continue;
            sc->event[m++] = sc->event[j];
        }
        sc->n_events = m;
    }
    /* the targets' own stream: the walk's PRNG is not touched, so the walk
     * is identical up to the first added kidnap */
    rng = sim_seed_state(sc->seed * 0x9E3779B97F4A7C15ULL + 0x6B69646E61707321ULL);
    for (add = own; add < n; add++) {
        double best_t = -1, best = -1, t, hx, hy;
        sim_event_t e;
        /* the time farthest from every busy time, on a 0.1 s grid (the
         * first of equals): added one by one, so kidnap k is the same for
         * every n >= k */
        for (k = 1; k * 0.1 < sc->duration_s; k++) {
            double r;
            t = k * 0.1;
            r = sim_kidnap_room(sc, t);
            if (r > best + 1e-9) {
                best = r;
                best_t = t;
            }
        }
        if (best < 2.0)
            return -1; /* no room left: kidnaps closer than 2 s */
        memset(&e, 0, sizeof e);
        e.kind = SIM_EVENT_KIDNAP;
        e.t_s = best_t;
        hx = sc->field->length_mm / 2.0 + sc->field->border_mm / 2.0;
        hy = sc->field->width_mm / 2.0 + sc->field->border_mm / 2.0;
        /* not onto another robot: drawn again (a walk without other robots
         * draws once, so its kidnaps do not depend on this) */
        for (j = 0; j < 16; j++) {
            int near = 0, o;
            e.x_mm = sim_round(sim_uniform(&rng, -hx, hx));
            e.y_mm = sim_round(sim_uniform(&rng, -hy, hy));
            e.heading_deg = sim_round(sim_uniform(&rng, -180.0, 180.0));
            for (o = 0; o < sc->n_others; o++) {
                double dx = e.x_mm - sc->other[o].x_mm, dy = e.y_mm - sc->other[o].y_mm;
                near |= dx * dx + dy * dy < 500.0 * 500.0;
            }
            if (!near)
                break;
        }
        for (j = sc->n_events; j > 0 && sc->event[j - 1].t_s > e.t_s; j--)
            sc->event[j] = sc->event[j - 1];
        sc->event[j] = e;
        sc->n_events++;
    }
    /* another walk: its name says so (observation caches are keyed on it) */
    len = strlen(sc->name);
    if (len > SIM_NAME_LEN - 6)
        len = SIM_NAME_LEN - 6;
    snprintf(sc->name + len, SIM_NAME_LEN - len, "+k%d", n);
    return 0;
}
