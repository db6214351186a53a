/*
 * host_tests/test_camera.c - the fixed-point camera model (src/model/camera.c)
 * against an independent double-precision pinhole model written here from
 * the geometry of camera.h (camera axes and centre built from the head
 * angles, not from the firmware's matrix products).
 *
 * The reference uses the model's integer parameters exactly (focal and
 * principal point in Q4, mount in mm, angles as binary angles converted to
 * radians), so the comparison measures the fixed-point arithmetic only.
 *
 * Sweep (normal run): every catalogue camera x 24 corner poses (extremes of
 * neck height, head pitch, yaw and pitch offset) + 376 random poses; NAO neck
 * 300..600 mm, AIBO 100..200 mm, head pitch -0.6..+0.5 rad, yaw -2..+2 rad,
 * pitch offset +-5 deg.  Per pose: a 21 x 16 pixel grid over the image with
 * random sub-pixel (Q4) jitter, 13 rows just below the fixed-point horizon
 * (1/16 px .. 16 px below it, i.e. ranges up to and beyond 20 m) at 5
 * columns, and 60 random ground points (range 100..8000 mm, bearings
 * across the view) sent ground -> pixel -> ground.
 * Quick run (--quick, qemu): 4 corner poses + 4 random poses per camera,
 * a 6 x 5 grid, the same horizon rows at 2 columns, 12 ground points;
 * polar: 2000 instead of 100000 random points.  Catalogue, invalid-input and
 * extreme-input cases are the same in both modes.
 *
 * Roll (camera.roll_*): the same sweeps with torso pitch and roll (+-10
 * deg) and a roll offset (+-5 deg) added to every pose, the same
 * tolerances; the horizon is checked per column against the reference's
 * sloped line.  camera.roll_zero_is_head_only: without those angles the
 * rotation and centre are the head-only model's integers, bit for bit.
 * camera.extrinsics: fl_camera_init_extrinsics against a ZYX reference,
 * and filled from a head pose's reference kinematics (not hashed: those
 * inputs come from doubles).
 *
 * Every hashed input of the firmware is generated with integers (t_rng,
 * firmware outputs), never from the double reference, so the digests are
 * bit-identical on every target.
 *
 * Tolerances:
 *  - ground point (pixel_to_ground): |fixed - ref| <= 1 mm + 0.1% of the
 *    range whenever the reference range is <= 6 m (the requirement) and
 *    also out to 20 m.
 *  - "no ground point": the fixed point must say false whenever the
 *    reference ray is at/above the horizon, or its ground point is beyond
 *    FL_CAMERA_MAX_RANGE_MM + BAND_MM; it must give a point whenever the
 *    reference is within FL_CAMERA_MAX_RANGE_MM - BAND_MM.  BAND_MM = 21 mm
 *    (1 mm + 0.1% of 20 m): in that band around the max range either answer
 *    is accepted.  No band is needed at the horizon itself: rays that graze
 *    it are far beyond the max range in both models.
 *  - ground_to_pixel: |fixed - 16 ref| <= 1 + f_q4 * (sqrt(3)/32 mm) / D
 *    Q4 (pix_tol_q4), D the camera-to-point distance, for points whose
 *    reference pixel lies within the image grown by half its size: 0.5 LSB
 *    of final rounding (+0.5 margin) plus the camera centre kept in Q4 mm
 *    (each coordinate within 1/32 mm: seen from 300 mm with f = 722 px that
 *    moves the pixel by up to 2.1 LSB; from 1 m by 0.6 LSB).
 *  - round trip ground -> pixel -> ground: |g' - g| <= |ref(pixel) - g| + 1 mm
 *    + 0.1% of range, i.e. the pixel quantization (seen through the
 *    reference) plus the ground tolerance.
 *  - horizon: the firmware row h must be floor(16 * v_ref) exactly, where
 *    v_ref = cy - f tan(total tilt) (pixels with v_q4 > h look down), or
 *    one LSB off when 16 * v_ref is within 1e-3 LSB of an integer; the
 *    same for every column.
 *  - polar: range exact (rounded) for |x|,|y| < 2^26, <= 1 beyond; bearing
 *    within 0.02 deg of atan2; point_from_polar within 1 mm.
 */
#include "test.h"

#include "fieldloc/camera.h"
#include "fieldloc/config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define PI_D 3.14159265358979323846
#define BAND_MM 21.0

/* ground_to_pixel tolerance, Q4 px: 1 LSB (0.5 of final rounding, 0.5 of
 * margin) plus the camera centre's Q4 storage (each coordinate within 1/32
 * mm, |dp| <= sqrt(3)/32 mm) seen from the point's distance. */
static double pix_tol_q4(const fl_camera_model_t *m, double dist_mm)
{
    return 1.0 + m->focal_q4 * (1.7320508 / 32.0) / dist_mm;
}

/* ---- double reference ---------------------------------------------------- */

typedef struct {
    double axis[3][3]; /* axis[0] optical, axis[1] left, axis[2] up: robot frame */
    double p[3];       /* camera centre, mm */
    double f, cx, cy;  /* px */
    double tilt;       /* total downward tilt, rad */
} ref_cam_t;

static double rad_of(int a) { return (double)a * (2.0 * PI_D / 65536.0); }

/* v turned by the torso: first about x (roll: y turns up), then about y
 * (pitch: x turns down), as camera.h describes. */
static void ref_torso(double v[3], double tp, double tr)
{
    double x, y = v[1], z = v[2];
    v[1] = cos(tr) * y - sin(tr) * z;
    v[2] = sin(tr) * y + cos(tr) * z;
    x = v[0];
    z = v[2];
    v[0] = cos(tp) * x + sin(tp) * z;
    v[2] = -sin(tp) * x + cos(tp) * z;
}

static void ref_init(ref_cam_t *rc, const fl_camera_model_t *m, const fl_camera_pose_t *ps)
{
    double psi = rad_of(ps->head_yaw);
    double theta = rad_of(ps->head_pitch) + rad_of(ps->pitch_offset);
    double alpha = theta + rad_of(m->mount_tilt);
    /* head axes: forward (pitched down by theta, then yawed) and up */
    double hf[3], hu[3];
    int i;
    hf[0] = cos(theta) * cos(psi);
    hf[1] = cos(theta) * sin(psi);
    hf[2] = -sin(theta);
    hu[0] = sin(theta) * cos(psi);
    hu[1] = sin(theta) * sin(psi);
    hu[2] = cos(theta);
    /* camera axes: optical axis alpha below horizontal in the yawed plane */
    rc->axis[0][0] = cos(alpha) * cos(psi);
    rc->axis[0][1] = cos(alpha) * sin(psi);
    rc->axis[0][2] = -sin(alpha);
    rc->axis[1][0] = -sin(psi);
    rc->axis[1][1] = cos(psi);
    rc->axis[1][2] = 0.0;
    rc->axis[2][0] = sin(alpha) * cos(psi);
    rc->axis[2][1] = sin(alpha) * sin(psi);
    rc->axis[2][2] = cos(alpha);
    /* roll offset about the optical axis: the left axis turns up */
    {
        double ro = rad_of(ps->roll_offset), l[3], u[3];
        for (i = 0; i < 3; i++) {
            l[i] = cos(ro) * rc->axis[1][i] + sin(ro) * rc->axis[2][i];
            u[i] = -sin(ro) * rc->axis[1][i] + cos(ro) * rc->axis[2][i];
        }
        for (i = 0; i < 3; i++) {
            rc->axis[1][i] = l[i];
            rc->axis[2][i] = u[i];
        }
    }
    for (i = 0; i < 3; i++)
        rc->p[i] = m->mount_x_mm * hf[i] + m->mount_z_mm * hu[i];
    /* the torso turns everything about the head pitch axis */
    for (i = 0; i < 3; i++)
        ref_torso(rc->axis[i], rad_of(ps->torso_pitch), rad_of(ps->torso_roll));
    ref_torso(rc->p, rad_of(ps->torso_pitch), rad_of(ps->torso_roll));
    rc->p[2] += ps->neck_height_mm;
    rc->f = m->focal_q4 / 16.0;
    rc->cx = m->cx_q4 / 16.0;
    rc->cy = m->cy_q4 / 16.0;
    rc->tilt = alpha;
}

/* Horizon row (px) at column u (px): where the ray's vertical part is 0. */
static double ref_horizon_v(const ref_cam_t *rc, double u)
{
    return rc->cy + (rc->f * rc->axis[0][2] - (u - rc->cx) * rc->axis[1][2]) / rc->axis[2][2];
}

enum { REF_HIT, REF_ABOVE, REF_FAR };

/* pixel (px) -> ground (mm); returns REF_* and the range. */
static int ref_pixel_to_ground(const ref_cam_t *rc, double u, double v, double *gx,
                               double *gy, double *range)
{
    double d[3], t;
    int i;
    for (i = 0; i < 3; i++)
        d[i] = rc->f * rc->axis[0][i] - (u - rc->cx) * rc->axis[1][i] - (v - rc->cy) * rc->axis[2][i];
    if (d[2] >= 0.0)
        return REF_ABOVE;
    t = -rc->p[2] / d[2];
    *gx = rc->p[0] + t * d[0];
    *gy = rc->p[1] + t * d[1];
    *range = hypot(*gx, *gy);
    return *range > FL_CAMERA_MAX_RANGE_MM ? REF_FAR : REF_HIT;
}

/* ground (mm) -> pixel (px); 0 when behind the camera.  *side = c_x / |c|,
 * *dist = |c| (camera to point, mm). */
static int ref_ground_to_pixel(const ref_cam_t *rc, double gx, double gy, double *u, double *v,
                               double *side, double *dist)
{
    double w[3], c[3];
    int i;
    w[0] = gx - rc->p[0];
    w[1] = gy - rc->p[1];
    w[2] = -rc->p[2];
    for (i = 0; i < 3; i++)
        c[i] = rc->axis[i][0] * w[0] + rc->axis[i][1] * w[1] + rc->axis[i][2] * w[2];
    *dist = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    *side = c[0] / *dist;
    if (c[0] <= 0.0)
        return 0;
    *u = rc->cx - rc->f * c[1] / c[0];
    *v = rc->cy - rc->f * c[2] / c[0];
    return 1;
}

/* ---- poses ----------------------------------------------------------------- */

#define PITCH_MIN (-6259) /* -0.6 rad */
#define PITCH_MAX 5216    /* +0.5 rad */
#define YAW_MAX 20861     /* 2 rad */
#define OFFSET_MAX 910    /* 5 deg */

#define TORSO_MAX 1820      /* 10 deg: a walking NAO rolls a few degrees */
#define ROLL_OFFSET_MAX 910 /* 5 deg */

static int is_aibo(const fl_camera_model_t *m) { return strncmp(m->name, "aibo", 4) == 0; }

/* Set by the camera.roll_* tests: make_pose adds torso pitch and roll and a
 * roll offset (extra random draws only then, so the sweeps without roll
 * are unchanged). */
static int g_roll_mode;

/* Pose k of a sweep: k < 24 corners, then random. */
static fl_camera_pose_t make_pose(const fl_camera_model_t *m, int k, t_rng_t *rng)
{
    fl_camera_pose_t ps;
    int32_t nlo = is_aibo(m) ? 100 : 300, nhi = is_aibo(m) ? 200 : 600;
    memset(&ps, 0, sizeof ps);
    if (k < 24) {
        ps.neck_height_mm = (k & 1) ? nhi : nlo;
        ps.head_pitch = (fl_angle_t)((k & 2) ? PITCH_MAX : PITCH_MIN);
        ps.pitch_offset = (fl_angle_t)((k & 4) ? OFFSET_MAX : -OFFSET_MAX);
        ps.head_yaw = (fl_angle_t)((k / 8 - 1) * YAW_MAX);
    } else {
        ps.neck_height_mm = t_rng_range(rng, nlo, nhi);
        ps.head_pitch = (fl_angle_t)t_rng_range(rng, PITCH_MIN, PITCH_MAX);
        ps.pitch_offset = (fl_angle_t)t_rng_range(rng, -OFFSET_MAX, OFFSET_MAX);
        ps.head_yaw = (fl_angle_t)t_rng_range(rng, -YAW_MAX, YAW_MAX);
    }
    if (g_roll_mode) {
        if (k < 24) {
            ps.torso_pitch = (fl_angle_t)((k & 1) ? TORSO_MAX : -TORSO_MAX);
            ps.torso_roll = (fl_angle_t)((k & 2) ? TORSO_MAX : -TORSO_MAX);
            ps.roll_offset = (fl_angle_t)((k & 4) ? -ROLL_OFFSET_MAX : ROLL_OFFSET_MAX);
        } else {
            ps.torso_pitch = (fl_angle_t)t_rng_range(rng, -TORSO_MAX, TORSO_MAX);
            ps.torso_roll = (fl_angle_t)t_rng_range(rng, -TORSO_MAX, TORSO_MAX);
            ps.roll_offset = (fl_angle_t)t_rng_range(rng, -ROLL_OFFSET_MAX, ROLL_OFFSET_MAX);
        }
    }
    return ps;
}

static int n_poses(void) { return t_quick ? 8 : 400; }
static int pose_index(int i) { return t_quick ? (i < 4 ? i * 7 : 20 + i) : i; }

/* ---- statistics -------------------------------------------------------------- */

typedef struct {
    long n_near, n_far, n_above, n_beyond, n_band;
    double max_err_near, max_rel_near; /* <= 6 m: mm, % of range */
    double max_err_far, max_rel_far;   /* 6..20 m */
    double max_frac;                   /* error / (1 mm + 0.1% range), any range */
} gstat_t;

/* Compare one firmware pixel_to_ground against the reference. */
static void check_p2g(const fl_camera_t *cam, const ref_cam_t *rc, int32_t u_q4, int32_t v_q4,
                      gstat_t *st, uint32_t *h)
{
    fl_point_t g = {12345, -12345};
    double rx = 0, ry = 0, rr = 0, err;
    int ok = fl_camera_pixel_to_ground(cam, u_q4, v_q4, &g);
    int ref = ref_pixel_to_ground(rc, u_q4 / 16.0, v_q4 / 16.0, &rx, &ry, &rr);
    *h = t_hash_i32(*h, ok);
    if (ok) {
        *h = t_hash_i32(*h, g.x_mm);
        *h = t_hash_i32(*h, g.y_mm);
    }
    if (ref == REF_ABOVE) {
        st->n_above++;
        if (ok)
            t_fail_msg(__FILE__, __LINE__, "%s u=%ld v=%ld: ground point above the horizon",
                       cam->model.name, (long)u_q4, (long)v_q4);
        return;
    }
    if (fabs(rr - FL_CAMERA_MAX_RANGE_MM) <= BAND_MM) {
        st->n_band++;
        if (!ok)
            return;
    } else if (ref == REF_FAR) {
        st->n_beyond++;
        if (ok)
            t_fail_msg(__FILE__, __LINE__, "%s u=%ld v=%ld: point at %.0f mm beyond max range",
                       cam->model.name, (long)u_q4, (long)v_q4, rr);
        return;
    } else if (!ok) {
        t_fail_msg(__FILE__, __LINE__, "%s u=%ld v=%ld: no ground point, reference %.1f mm",
                   cam->model.name, (long)u_q4, (long)v_q4, rr);
        return;
    }
    err = hypot(g.x_mm - rx, g.y_mm - ry);
    if (err / (1.0 + 0.001 * rr) > st->max_frac)
        st->max_frac = err / (1.0 + 0.001 * rr);
    if (rr <= 6000.0) {
        st->n_near++;
        if (err > st->max_err_near)
            st->max_err_near = err;
        if (rr >= 1000.0 && 100.0 * err / rr > st->max_rel_near)
            st->max_rel_near = 100.0 * err / rr;
    } else {
        st->n_far++;
        if (err > st->max_err_far)
            st->max_err_far = err;
        if (100.0 * err / rr > st->max_rel_far)
            st->max_rel_far = 100.0 * err / rr;
    }
    if (!(err <= 1.0 + 0.001 * rr))
        t_fail_msg(__FILE__, __LINE__, "%s u=%ld v=%ld: ground error %.2f mm at range %.0f mm",
                   cam->model.name, (long)u_q4, (long)v_q4, err, rr);
}

/* ---- cases ------------------------------------------------------------------- */

static void test_catalogue(void)
{
    static const struct {
        const char *prefix;
        double hfov_deg;
    } hfov[] = {{"nao3-", 47.8}, {"nao4-", 60.9}, {"nao6-", 56.3}, {"aibo-ers7", 56.9},
                {"acyut-", 60.0}};
    static const char *const required[] = {
        "nao3-top-320", "nao3-top-640", "nao3-bottom-320", "nao3-bottom-640",
        "nao4-top-320", "nao4-top-640", "nao4-bottom-320", "nao4-bottom-640",
        "nao6-top-320", "nao6-top-640", "nao6-bottom-320", "nao6-bottom-640",
        "nao6-top-1280", "nao6-bottom-1280", "aibo-ers7", "acyut-640"};
    size_t i, j, n = fl_camera_model_count();
    const fl_camera_model_t *m;
    fl_camera_pose_t ps = {450, 0, 0, 0, 0, 0, 0};
    fl_camera_t cam;

    CHECK(n >= sizeof required / sizeof required[0]);
    CHECK(fl_camera_model_at(n) == NULL);
    CHECK(fl_camera_model_at((size_t)-1) == NULL);
    CHECK(fl_camera_model_find(NULL) == NULL);
    CHECK(fl_camera_model_find("") == NULL);
    CHECK(fl_camera_model_find("nao4-bottom-32") == NULL);
    CHECK(fl_camera_model_find("nao4-bottom-3200") == NULL);
    CHECK(fl_camera_model_find("nao5-top-320") == NULL);
    for (i = 0; i < sizeof required / sizeof required[0]; i++) {
        m = fl_camera_model_find(required[i]);
        CHECK(m != NULL);
        if (m)
            CHECK(strcmp(m->name, required[i]) == 0);
    }
    for (i = 0; i < n; i++) {
        m = fl_camera_model_at(i);
        CHECK(m != NULL);
        if (!m || !m->name) {
            CHECK(0);
            continue;
        }
        CHECK(fl_camera_model_find(m->name) == m);
        for (j = 0; j < i; j++)
            CHECK(strcmp(fl_camera_model_at(j)->name, m->name) != 0);
        ps.neck_height_mm = is_aibo(m) ? 150 : 450;
        CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
        CHECK_EQ(m->cx_q4, 8 * (m->width_px - 1));
        CHECK_EQ(m->cy_q4, 8 * (m->height_px - 1));
        for (j = 0; j < sizeof hfov / sizeof hfov[0]; j++) {
            if (strncmp(m->name, hfov[j].prefix, strlen(hfov[j].prefix)) == 0) {
                double f = 16.0 * (m->width_px / 2.0) / tan(hfov[j].hfov_deg * PI_D / 360.0);
                CHECK_LE(fabs(m->focal_q4 - f), 0.5);
                break;
            }
        }
        /* every model has a known HFOV, except calibrated ones (below) */
        CHECK(j < sizeof hfov / sizeof hfov[0] || strcmp(m->name, "uva2013") == 0);
        /* default pose (added with uva2013): a valid neck height, a small
         * pitch offset, and it initialises with a level head */
        CHECK(m->default_neck_height_mm >= FL_CAMERA_NECK_MIN_MM &&
              m->default_neck_height_mm <= FL_CAMERA_NECK_MAX_MM);
        CHECK(m->default_pitch_offset > -2731 && m->default_pitch_offset < 2731); /* 15 deg */
        {
            fl_camera_pose_t dp;
            memset(&dp, 0, sizeof dp);
            dp.neck_height_mm = m->default_neck_height_mm;
            dp.head_pitch = 0;
            dp.head_yaw = 0;
            dp.pitch_offset = m->default_pitch_offset;
            CHECK_EQ(fl_camera_init(&cam, m, &dp), FL_OK);
        }
        if (strncmp(m->name, "nao", 3) == 0)
            CHECK(m->default_neck_height_mm > 400 && m->default_neck_height_mm < 480);
        if (is_aibo(m))
            CHECK(m->default_neck_height_mm >= 100 && m->default_neck_height_mm <= 200);
        if (strstr(m->name, "-320")) {
            CHECK_EQ(m->width_px, 320);
            CHECK_EQ(m->height_px, 240);
        } else if (strstr(m->name, "-640")) {
            CHECK_EQ(m->width_px, 640);
            CHECK_EQ(m->height_px, 480);
        } else if (strstr(m->name, "-1280")) {
            CHECK_EQ(m->width_px, 1280);
            CHECK_EQ(m->height_px, 960);
        }
        if (strstr(m->name, "-bottom-"))
            CHECK(m->mount_tilt > 7000 && m->mount_tilt < 7400); /* about 39-40.5 deg */
        if (strstr(m->name, "-top-"))
            CHECK(m->mount_tilt >= 0 && m->mount_tilt < 400); /* 0 .. 2.2 deg */
    }
    m = fl_camera_model_find("nao4-bottom-320");
    if (m) { /* DESIGN.md: 50.71 mm forward, 17.74 up, 39.7 deg, about 272 px */
        CHECK_EQ(m->mount_x_mm, 51);
        CHECK_EQ(m->mount_z_mm, 18);
        CHECK_EQ(m->mount_tilt, 7227);
        CHECK(m->focal_q4 > 271 * 16 && m->focal_q4 < 273 * 16);
    }
    m = fl_camera_model_find("aibo-ers7");
    if (m) {
        CHECK_EQ(m->width_px, 208);
        CHECK_EQ(m->height_px, 160);
    }
    /* acyut-640 (seed 002's humanoid, inferred numbers: camera.c): a
     * kid-size head height and a level mount looking down by head pitch */
    m = fl_camera_model_find("acyut-640");
    if (m) {
        CHECK(m->default_neck_height_mm >= 300 && m->default_neck_height_mm <= 600);
        CHECK_EQ(m->mount_tilt, 0);
        CHECK(m->mount_z_mm > 0 && m->mount_x_mm > 0);
    }
    /* uva2013: the NAO v4 bottom camera of the UvA 2013 set, calibrated
     * from its hand labels (test_realdata checks it against them): the
     * nao4-bottom-320 geometry with a fitted focal length within 3% of the
     * data sheet's, and a StandInit-like default pose (neck 430..470 mm,
     * pitch offset 0..10 deg) */
    m = fl_camera_model_find("uva2013");
    CHECK(m != NULL);
    {
        const fl_camera_model_t *b = fl_camera_model_find("nao4-bottom-320");
        if (m && b) {
            CHECK(m->width_px == 320 && m->height_px == 240);
            CHECK(m->mount_x_mm == b->mount_x_mm && m->mount_z_mm == b->mount_z_mm &&
                  m->mount_tilt == b->mount_tilt);
            CHECK_LE(fabs(m->focal_q4 - (double)b->focal_q4), 0.03 * b->focal_q4);
            CHECK(m->default_neck_height_mm >= 430 && m->default_neck_height_mm <= 470);
            CHECK(m->default_pitch_offset > 0 && m->default_pitch_offset < 1820);
        }
    }
}

/* Asserts that cam projects nothing. */
static void check_projects_nothing(const fl_camera_t *cam)
{
    int32_t u, v, uu = 7, vv = 7;
    fl_point_t g;
    int any = 0;
    for (v = -16 * 100; v <= 16 * 1400; v += 16 * 25 + 3)
        for (u = -16 * 100; u <= 16 * 1400; u += 16 * 25 + 5)
            any |= fl_camera_pixel_to_ground(cam, u, v, &g);
    CHECK(!any);
    for (v = -3000; v <= 3000; v += 250)
        for (u = -3000; u <= 3000; u += 250) {
            g.x_mm = u;
            g.y_mm = v;
            any |= fl_camera_ground_to_pixel(cam, g, &uu, &vv);
        }
    CHECK(!any);
    CHECK_EQ(uu, 7);
    CHECK_EQ(vv, 7);
    CHECK_EQ(fl_camera_horizon_v_q4(cam, 0), INT32_MAX);
    CHECK_EQ(fl_camera_horizon_v_q4(cam, 16 * 100), INT32_MAX);
}

/* Init cam validly, then with (m, ps): expect status st and, on error, a camera
 * that projects nothing. */
static void expect_init(const fl_camera_model_t *m, const fl_camera_pose_t *ps, fl_status_t st)
{
    fl_camera_t cam;
    fl_camera_pose_t good = {450, 0, 0, 0, 0, 0, 0};
    CHECK_EQ(fl_camera_init(&cam, fl_camera_model_find("nao4-bottom-320"), &good), FL_OK);
    CHECK_EQ(fl_camera_init(&cam, m, ps), st);
    if (st != FL_OK)
        check_projects_nothing(&cam);
}

static void test_invalid(void)
{
    const fl_camera_model_t *base = fl_camera_model_find("nao4-bottom-320");
    fl_camera_model_t m;
    fl_camera_pose_t ps = {450, 0, 0, 0, 0, 0, 0}, p2;
    fl_camera_t cam;
    fl_point_t g = {1000, 0};
    int32_t u, v;

    CHECK(base != NULL);
    if (!base)
        return;
    CHECK_EQ(fl_camera_init(NULL, base, &ps), FL_ERR_NULL);
    expect_init(NULL, &ps, FL_ERR_NULL);
    expect_init(base, NULL, FL_ERR_NULL);
    expect_init(base, &ps, FL_OK);

    m = *base; m.width_px = 0; expect_init(&m, &ps, FL_ERR_SIZE);
    m = *base; m.width_px = -320; expect_init(&m, &ps, FL_ERR_SIZE);
    m = *base; m.height_px = 0; expect_init(&m, &ps, FL_ERR_SIZE);
    m = *base; m.height_px = -1; expect_init(&m, &ps, FL_ERR_SIZE);
    m = *base; m.width_px = FL_IMAGE_MAX_DIM + 1; expect_init(&m, &ps, FL_ERR_SIZE);
    m = *base; m.height_px = FL_IMAGE_MAX_DIM + 1; expect_init(&m, &ps, FL_ERR_SIZE);
    m = *base; m.width_px = FL_IMAGE_MAX_DIM; m.height_px = FL_IMAGE_MAX_DIM;
    expect_init(&m, &ps, FL_OK);
    m = *base; m.focal_q4 = 0; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.focal_q4 = -4355; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.focal_q4 = INT32_MIN; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.focal_q4 = FL_CAMERA_MAX_FOCAL_Q4 + 1; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.focal_q4 = FL_CAMERA_MAX_FOCAL_Q4; expect_init(&m, &ps, FL_OK);
    m = *base; m.focal_q4 = 1; expect_init(&m, &ps, FL_OK);
    m = *base; m.cx_q4 = -1; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.cy_q4 = 16 * 240 + 1; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.mount_x_mm = FL_CAMERA_MAX_MOUNT_MM + 1; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.mount_z_mm = -FL_CAMERA_MAX_MOUNT_MM - 1; expect_init(&m, &ps, FL_ERR_RANGE);
    m = *base; m.mount_z_mm = INT32_MIN; expect_init(&m, &ps, FL_ERR_RANGE);

    p2 = ps; p2.neck_height_mm = 49; expect_init(base, &p2, FL_ERR_RANGE);
    p2 = ps; p2.neck_height_mm = 2001; expect_init(base, &p2, FL_ERR_RANGE);
    p2 = ps; p2.neck_height_mm = 0; expect_init(base, &p2, FL_ERR_RANGE);
    p2 = ps; p2.neck_height_mm = INT32_MIN; expect_init(base, &p2, FL_ERR_RANGE);
    p2 = ps; p2.neck_height_mm = 50; expect_init(base, &p2, FL_OK);
    p2 = ps; p2.neck_height_mm = 2000; expect_init(base, &p2, FL_OK);
    /* total tilt (39.7 deg mount + pitch + offset) must stay within +-90 deg */
    p2 = ps; p2.head_pitch = (fl_angle_t)(FL_ANGLE_90 - base->mount_tilt);
    expect_init(base, &p2, FL_OK);
    p2.head_pitch++; expect_init(base, &p2, FL_ERR_RANGE);
    p2 = ps; p2.head_pitch = (fl_angle_t)(-FL_ANGLE_90 - base->mount_tilt);
    expect_init(base, &p2, FL_OK);
    p2.pitch_offset = -1; expect_init(base, &p2, FL_ERR_RANGE);
    p2 = ps; p2.head_pitch = 30000; p2.pitch_offset = 30000; /* wraps to -70 deg total */
    expect_init(base, &p2, FL_OK);

    /* NULL outputs and NULL camera never crash */
    CHECK_EQ(fl_camera_init(&cam, base, &ps), FL_OK);
    CHECK(!fl_camera_pixel_to_ground(&cam, 2552, 1912, NULL));
    CHECK(!fl_camera_pixel_to_ground(NULL, 2552, 1912, &g));
    CHECK(!fl_camera_ground_to_pixel(&cam, g, NULL, &v));
    CHECK(!fl_camera_ground_to_pixel(&cam, g, &u, NULL));
    CHECK(!fl_camera_ground_to_pixel(NULL, g, &u, &v));
    CHECK_EQ(fl_camera_horizon_v_q4(NULL, 0), INT32_MAX);
    fl_polar_from_point(g, NULL, NULL);
}

static void test_pixel_to_ground(void)
{
    size_t mi;
    int k, i, j, nu = t_quick ? 6 : 21, nv = t_quick ? 5 : 16, ncol = t_quick ? 2 : 5;
    static const int rows[] = {1, 2, 4, 8, 16, 24, 32, 48, 64, 96, 128, 192, 256};
    gstat_t st;
    uint32_t h = t_hash_init();
    t_rng_t rng;

    memset(&st, 0, sizeof st);
    t_rng_seed(&rng, 0xca3e7a01u);
    for (mi = 0; mi < fl_camera_model_count(); mi++) {
        const fl_camera_model_t *m = fl_camera_model_at(mi);
        for (k = 0; k < n_poses(); k++) {
            fl_camera_pose_t ps = make_pose(m, pose_index(k), &rng);
            fl_camera_t cam;
            ref_cam_t rc;
            int32_t hz;
            CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
            ref_init(&rc, m, &ps);
            for (j = 0; j < nv; j++)
                for (i = 0; i < nu; i++) {
                    int32_t u = (int32_t)(16 * (m->width_px - 1) * i / (nu - 1));
                    int32_t v = (int32_t)(16 * (m->height_px - 1) * j / (nv - 1));
                    if (i > 0 && i < nu - 1)
                        u += t_rng_range(&rng, -8, 7);
                    if (j > 0 && j < nv - 1)
                        v += t_rng_range(&rng, -8, 7);
                    check_p2g(&cam, &rc, u, v, &st, &h);
                }
            /* rows just below the horizon: far ground points, max range */
            hz = fl_camera_horizon_v_q4(&cam, 0);
            h = t_hash_i32(h, hz);
            if (hz > INT32_MIN && hz < 16 * m->height_px)
                for (i = 0; i < ncol; i++) {
                    int32_t u = t_rng_range(&rng, 0, 16 * (m->width_px - 1));
                    int32_t hu = fl_camera_horizon_v_q4(&cam, u); /* = hz without roll */
                    if (hu == INT32_MIN || hu == INT32_MAX)
                        continue;
                    for (j = 0; j < (int)(sizeof rows / sizeof rows[0]); j++)
                        check_p2g(&cam, &rc, u, hu + rows[j], &st, &h);
                }
        }
    }
    t_info("ground <= 6 m: %ld points, max error %.3f mm, max %.4f%% of range (ranges >= 1 m)",
           st.n_near, st.max_err_near, st.max_rel_near);
    t_info("ground 6..20 m: %ld points, max error %.3f mm, max %.4f%% of range", st.n_far,
           st.max_err_far, st.max_rel_far);
    t_info("max error / (1 mm + 0.1%% of range) = %.3f (<= 1 required)", st.max_frac);
    t_info("no ground point (fixed agrees with reference): %ld above the horizon, %ld beyond "
           "max range; %ld in the +-%.0f mm band at max range",
           st.n_above, st.n_beyond, st.n_band, BAND_MM);
    CHECK(st.n_near > 0 && st.n_far > 0 && st.n_above > 0 && st.n_beyond > 0);
    t_digest(g_roll_mode ? "camera.roll_pixel_to_ground" : "camera.pixel_to_ground", h);
}

static void test_ground_to_pixel(void)
{
    size_t mi;
    int k, i, npts = t_quick ? 12 : 60;
    uint32_t h = t_hash_init();
    t_rng_t rng;
    double max_pix = 0, max_pix_far = 0, max_pix_frac = 0, max_rt = 0, max_rt_excess = 0;
    long n_pix = 0, n_rt = 0, n_behind = 0;

    t_rng_seed(&rng, 0x6a0d2b1bu);
    for (mi = 0; mi < fl_camera_model_count(); mi++) {
        const fl_camera_model_t *m = fl_camera_model_at(mi);
        for (k = 0; k < n_poses(); k++) {
            fl_camera_pose_t ps = make_pose(m, pose_index(k), &rng);
            fl_camera_t cam;
            ref_cam_t rc;
            CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
            ref_init(&rc, m, &ps);
            for (i = 0; i < npts; i++) {
                /* bearing around the head yaw (+-40 deg, a few behind), range 100..8000 */
                int32_t r = t_rng_range(&rng, 100, 8000);
                int32_t b = ps.head_yaw + t_rng_range(&rng, -7300, 7300);
                fl_point_t g, g2;
                int32_t u = 0, v = 0;
                double ru, rv, side, dist, rx, ry, rr, e, tol;
                int ok, rok, ok2;
                if (i % 10 == 9)
                    b += 32768; /* behind */
                g = fl_point_from_polar(r, fl_angle_wrap(b));
                ok = fl_camera_ground_to_pixel(&cam, g, &u, &v);
                h = t_hash_i32(h, ok);
                if (ok) {
                    h = t_hash_i32(h, u);
                    h = t_hash_i32(h, v);
                }
                rok = ref_ground_to_pixel(&rc, g.x_mm, g.y_mm, &ru, &rv, &side, &dist);
                if (!rok) {
                    n_behind++;
                    if (side < -1e-6)
                        CHECK(!ok);
                    continue;
                }
                if (fabs(ru - rc.cx) > 1.0 * m->width_px || fabs(rv - rc.cy) > 1.0 * m->height_px)
                    continue; /* far outside the image: only no-crash is required */
                CHECK(ok);
                if (!ok)
                    continue;
                n_pix++;
                e = fabs(u - 16.0 * ru);
                if (fabs(v - 16.0 * rv) > e)
                    e = fabs(v - 16.0 * rv);
                if (e > max_pix)
                    max_pix = e;
                if (dist >= 1000.0 && e > max_pix_far)
                    max_pix_far = e;
                tol = pix_tol_q4(m, dist);
                if (e / tol > max_pix_frac)
                    max_pix_frac = e / tol;
                if (!(e <= tol))
                    t_fail_msg(__FILE__, __LINE__, "%s (%ld, %ld): pixel error %.2f Q4 > %.2f",
                               m->name, (long)g.x_mm, (long)g.y_mm, e, tol);
                /* round trip: pixel back to the ground */
                ok2 = fl_camera_pixel_to_ground(&cam, u, v, &g2);
                h = t_hash_i32(h, ok2);
                if (ok2) {
                    h = t_hash_i32(h, g2.x_mm);
                    h = t_hash_i32(h, g2.y_mm);
                }
                if (ref_pixel_to_ground(&rc, u / 16.0, v / 16.0, &rx, &ry, &rr) != REF_HIT ||
                    rr > 6000.0)
                    continue;
                CHECK(ok2);
                if (!ok2)
                    continue;
                n_rt++;
                {
                    double qerr = hypot(rx - g.x_mm, ry - g.y_mm); /* pixel quantization */
                    double rt = hypot(g2.x_mm - g.x_mm, g2.y_mm - g.y_mm);
                    double excess = rt - qerr;
                    if (rt > max_rt)
                        max_rt = rt;
                    if (excess > max_rt_excess)
                        max_rt_excess = excess;
                    if (!(rt <= qerr + 1.0 + 0.001 * r))
                        t_fail_msg(__FILE__, __LINE__, "%s round trip (%ld, %ld): %.2f mm (quant %.2f)",
                                   m->name, (long)g.x_mm, (long)g.y_mm, rt, qerr);
                }
            }
        }
    }
    t_info("ground_to_pixel: %ld points in view, max pixel error %.3f Q4 (%.4f px), %.3f Q4 for "
           "points >= 1 m from the camera, max error / tolerance %.3f; %ld behind",
           n_pix, max_pix, max_pix / 16.0, max_pix_far, max_pix_frac, n_behind);
    t_info("round trip ground->pixel->ground <= 6 m: %ld points, max %.2f mm, max %.3f mm beyond "
           "the Q4 pixel quantization", n_rt, max_rt, max_rt_excess);
    CHECK(n_pix > 0 && n_rt > 0 && n_behind > 0);
    t_digest(g_roll_mode ? "camera.roll_ground_to_pixel" : "camera.ground_to_pixel", h);
}

/* With roll: the horizon of several columns against the reference line,
 * the topmost row over the image, and no ground point at or above it. */
static void check_horizon_line(const fl_camera_t *cam, const ref_cam_t *rc, t_rng_t *rng,
                               uint32_t *h, double *max_err)
{
    const fl_camera_model_t *m = &cam->model;
    int32_t w16 = 16 * (m->width_px - 1), top, lo = INT32_MAX;
    fl_point_t g;
    int c, k;
    for (c = 0; c < 8; c++) {
        int32_t u = c == 0 ? 0 : c == 1 ? w16 : t_rng_range(rng, -16 * 1000, 16 * 2000);
        int32_t hz = fl_camera_horizon_v_q4(cam, u);
        double vref = 16.0 * ref_horizon_v(rc, u / 16.0);
        *h = t_hash_i32(*h, hz);
        CHECK(hz != INT32_MIN && hz != INT32_MAX);
        if (fabs(hz - floor(vref)) > *max_err)
            *max_err = fabs(hz - floor(vref));
        if (fabs(vref - floor(vref + 0.5)) > 1e-3)
            CHECK_EQ(hz, (long long)floor(vref)); /* exact */
        else
            CHECK_LE(fabs(hz - floor(vref)), 1.0);
        if (u >= 0 && u <= w16) {
            lo = hz < lo ? hz : lo;
            for (k = 0; k < 4; k++)
                CHECK(!fl_camera_pixel_to_ground(cam, u, hz - k * 37, &g));
        }
    }
    top = fl_camera_horizon_top_v_q4(cam, 0, w16);
    CHECK_LE(top, lo); /* no column of the image has its horizon above it */
    CHECK(top == fl_camera_horizon_v_q4(cam, 0) || top == fl_camera_horizon_v_q4(cam, w16));
}

static void test_horizon(void)
{
    size_t mi;
    int k, c;
    uint32_t h = t_hash_init();
    t_rng_t rng;
    double max_err = 0;
    long n = 0;

    t_rng_seed(&rng, 0x401120u);
    for (mi = 0; mi < fl_camera_model_count(); mi++) {
        const fl_camera_model_t *m = fl_camera_model_at(mi);
        for (k = 0; k < n_poses(); k++) {
            fl_camera_pose_t ps = make_pose(m, pose_index(k), &rng);
            fl_camera_t cam;
            ref_cam_t rc;
            int32_t hz, hz0;
            double vref;
            fl_point_t g;
            if (fl_camera_init(&cam, m, &ps) != FL_OK)
                t_fail_msg(__FILE__, __LINE__, "%s pose %d (%d %d %d %d %d %d %d): init failed", m->name, k,
                           (int)ps.neck_height_mm, ps.head_pitch, ps.head_yaw, ps.pitch_offset,
                           ps.roll_offset, ps.torso_pitch, ps.torso_roll);
            ref_init(&rc, m, &ps);
            hz0 = fl_camera_horizon_v_q4(&cam, 0);
            h = t_hash_i32(h, hz0);
            if (g_roll_mode) {
                check_horizon_line(&cam, &rc, &rng, &h, &max_err);
                n++;
                continue;
            }
            for (c = 0; c < 4; c++) {
                hz = fl_camera_horizon_v_q4(&cam, t_rng_range(&rng, -16 * 1000, 16 * 2000));
                CHECK_EQ(hz, hz0);
            }
            vref = 16.0 * (rc.cy - rc.f * tan(rc.tilt));
            n++;
            if (fabs(hz0 - floor(vref)) > max_err)
                max_err = fabs(hz0 - floor(vref));
            if (fabs(vref - floor(vref + 0.5)) > 1e-3)
                CHECK_EQ(hz0, (long long)floor(vref)); /* exact */
            else
                CHECK_LE(fabs(hz0 - floor(vref)), 1.0); /* within 1e-3 LSB of an integer */
            /* nothing at or above the horizon row has a ground point */
            for (c = 0; c < 8; c++) {
                int32_t u = t_rng_range(&rng, 0, 16 * (m->width_px - 1));
                CHECK(!fl_camera_pixel_to_ground(&cam, u, hz0 - c * 37, &g));
            }
        }
    }
    /* looking straight down / up: the whole column or none of it */
    {
        const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-640");
        fl_camera_pose_t ps = {450, 0, 0, 0, 0, 0, 0};
        fl_camera_t cam;
        fl_point_t g;
        int32_t u = 0, v = 0;
        if (m) {
            ps.head_pitch = (fl_angle_t)(FL_ANGLE_90 - m->mount_tilt);
            CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
            CHECK_EQ(fl_camera_horizon_v_q4(&cam, m->cx_q4), INT32_MIN);
            /* the image centre sees the ground right below the camera */
            CHECK(fl_camera_pixel_to_ground(&cam, m->cx_q4, m->cy_q4, &g));
            CHECK_LE(fabs(16.0 * g.x_mm - cam.pos_q4[0]), 16.0);
            CHECK_LE(fabs(16.0 * g.y_mm - cam.pos_q4[1]), 16.0);
            CHECK(fl_camera_pixel_to_ground(&cam, 0, 0, &g));
            CHECK(fl_camera_ground_to_pixel(&cam, g, &u, &v));
            CHECK_LE(abs(u) + abs(v), 16 * 4);
            ps.head_pitch = (fl_angle_t)(-FL_ANGLE_90 - m->mount_tilt);
            CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
            CHECK_EQ(fl_camera_horizon_v_q4(&cam, m->cx_q4), INT32_MAX);
            CHECK(!fl_camera_pixel_to_ground(&cam, m->cx_q4, 16 * 479, &g));
        }
    }
    t_info("horizon: %ld poses, max |h - floor(16 v_ref)| = %.0f Q4", n, max_err);
    t_digest(g_roll_mode ? "camera.roll_horizon" : "camera.horizon", h);
}

/* Odd and far inputs: no crash, documented false results, no overflow. */
static void test_extremes(void)
{
    static const int32_t big[] = {INT32_MIN, INT32_MIN + 1, -FL_CAMERA_MAX_GROUND_MM - 1,
                                  -FL_CAMERA_MAX_GROUND_MM, -20001, -1, 0, 1, 20001,
                                  FL_CAMERA_MAX_GROUND_MM, FL_CAMERA_MAX_GROUND_MM + 1,
                                  INT32_MAX - 1, INT32_MAX};
    size_t mi, i, j;
    uint32_t h = t_hash_init();
    for (mi = 0; mi < fl_camera_model_count(); mi++) {
        const fl_camera_model_t *m = fl_camera_model_at(mi);
        fl_camera_pose_t ps = {450, 0, 0, 0, 0, 0, 0};
        fl_camera_t cam;
        ref_cam_t rc;
        int32_t u, v;
        fl_point_t g;
        if (is_aibo(m))
            ps.neck_height_mm = 150;
        CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
        ref_init(&rc, m, &ps);
        for (i = 0; i < sizeof big / sizeof big[0]; i++)
            for (j = 0; j < sizeof big / sizeof big[0]; j++) {
                int ok = fl_camera_pixel_to_ground(&cam, big[i], big[j], &g);
                h = t_hash_i32(h, ok);
                if (ok) {
                    h = t_hash_i32(h, g.x_mm);
                    h = t_hash_i32(h, g.y_mm);
                    CHECK(fl_hypot(g.x_mm, g.y_mm) <= FL_CAMERA_MAX_RANGE_MM);
                }
                g.x_mm = big[i];
                g.y_mm = big[j];
                ok = fl_camera_ground_to_pixel(&cam, g, &u, &v);
                h = t_hash_i32(h, ok);
                if (ok) {
                    double ru, rv, side, dist;
                    h = t_hash_i32(h, u);
                    h = t_hash_i32(h, v);
                    CHECK(labs((long)u - m->cx_q4) <= FL_CAMERA_MAX_OFFSET_Q4);
                    CHECK(labs((long)v - m->cy_q4) <= FL_CAMERA_MAX_OFFSET_Q4);
                    CHECK(ref_ground_to_pixel(&rc, g.x_mm, g.y_mm, &ru, &rv, &side, &dist));
                    CHECK_LE(fabs(u - 16.0 * ru), pix_tol_q4(m, dist) + 1e-7 * fabs(16.0 * ru));
                    CHECK_LE(fabs(v - 16.0 * rv), pix_tol_q4(m, dist) + 1e-7 * fabs(16.0 * rv));
                }
                if (llabs((long long)big[i]) > FL_CAMERA_MAX_GROUND_MM ||
                    llabs((long long)big[j]) > FL_CAMERA_MAX_GROUND_MM)
                    CHECK(!ok);
            }
        /* 10 km straight ahead projects onto the horizon row (within 2 LSB) */
        g.x_mm = FL_CAMERA_MAX_GROUND_MM;
        g.y_mm = 0;
        CHECK(fl_camera_ground_to_pixel(&cam, g, &u, &v));
        CHECK_LE(labs((long)v - fl_camera_horizon_v_q4(&cam, u)), 2);
        CHECK(!fl_camera_pixel_to_ground(&cam, u, v, &g)); /* beyond max range */
        /* the pixel offset limit */
        CHECK(!fl_camera_pixel_to_ground(&cam, m->cx_q4, m->cy_q4 + FL_CAMERA_MAX_OFFSET_Q4 + 1, &g));
        CHECK(fl_camera_pixel_to_ground(&cam, m->cx_q4, m->cy_q4 + FL_CAMERA_MAX_OFFSET_Q4, &g));
        CHECK_EQ(fl_camera_horizon_v_q4(&cam, m->cx_q4 + FL_CAMERA_MAX_OFFSET_Q4 + 1), INT32_MAX);
    }
    t_digest("camera.extremes", h);
}

static void test_polar(void)
{
    t_rng_t rng;
    int i, n = t_quick ? 2000 : 100000;
    uint32_t h = t_hash_init();
    double max_b = 0, max_p = 0;
    fl_point_t p;
    int32_t r;
    fl_angle_t b;

    t_rng_seed(&rng, 0x901a4u);
    for (i = 0; i < n; i++) {
        int32_t lim = (i & 3) == 0 ? INT32_MAX : (i & 3) == 1 ? (1 << 25) : 20000;
        double e, rb;
        p.x_mm = t_rng_range(&rng, (i & 3) == 0 ? INT32_MIN : -lim, lim);
        p.y_mm = t_rng_range(&rng, (i & 3) == 0 ? INT32_MIN : -lim, lim);
        fl_polar_from_point(p, &r, &b);
        h = t_hash_i32(h, r);
        h = t_hash_i32(h, b);
        {
            long double exact = sqrtl((long double)p.x_mm * p.x_mm + (long double)p.y_mm * p.y_mm);
            long double want = exact > (long double)INT32_MAX ? (long double)INT32_MAX : floorl(exact + 0.5L);
            if (lim <= (1 << 25))
                CHECK_EQ(r, (long long)want);
            else
                CHECK_LE(fabs((double)(r - want)), 1.0);
        }
        rb = atan2((double)p.y_mm, (double)p.x_mm) * 180.0 / PI_D;
        e = fabs(fl_angle_to_mdeg(b) / 1000.0 - rb);
        if (e > 180.0)
            e = 360.0 - e;
        if (p.x_mm == 0 && p.y_mm == 0)
            e = fabs((double)b);
        if (e > max_b)
            max_b = e;
        CHECK_LE(e, 0.02);
        /* back to a point */
        r = t_rng_range(&rng, -1000000, 1000000);
        b = (fl_angle_t)t_rng_range(&rng, -32768, 32767);
        p = fl_point_from_polar(r, b);
        h = t_hash_i32(h, p.x_mm);
        h = t_hash_i32(h, p.y_mm);
        e = fabs(p.x_mm - r * cos(rad_of(b)));
        if (fabs(p.y_mm - r * sin(rad_of(b))) > e)
            e = fabs(p.y_mm - r * sin(rad_of(b)));
        if (e > max_p)
            max_p = e;
        CHECK_LE(e, 1.0);
    }
    p.x_mm = 0;
    p.y_mm = 0;
    fl_polar_from_point(p, &r, &b);
    CHECK_EQ(r, 0);
    CHECK_EQ(b, 0);
    p.x_mm = 0;
    p.y_mm = 1000;
    fl_polar_from_point(p, &r, &b);
    CHECK_EQ(r, 1000);
    CHECK_EQ(b, FL_ANGLE_90);
    p.x_mm = INT32_MIN;
    p.y_mm = INT32_MIN;
    fl_polar_from_point(p, &r, &b);
    CHECK_EQ(r, INT32_MAX);
    p = fl_point_from_polar(3000, FL_ANGLE_180);
    CHECK_EQ(p.x_mm, -3000);
    CHECK_EQ(p.y_mm, 0);
    t_info("polar: max bearing error %.4f deg, point_from_polar max error %.3f mm", max_b, max_p);
    t_digest("camera.polar", h);
}

/* A round object's foot pixel -> its centre: d / 2 further along the
 * ray on the ground, the pixel moved onto the centre (further away: up the
 * image); nothing written without a ground point or a camera. */
static void test_foot_to_centre(void)
{
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    fl_camera_pose_t ps;
    fl_camera_t cam;
    fl_point_t g, c = {7, 7};
    int32_t u = 160 * 16, v = 200 * 16, u0, v0;
    uint32_t rg, rcen;
    memset(&ps, 0, sizeof ps);
    ps.neck_height_mm = m->default_neck_height_mm;
    ps.pitch_offset = m->default_pitch_offset;
    ps.head_pitch = 0;
    ps.head_yaw = fl_angle_from_mdeg(20000);
    CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
    CHECK(fl_camera_pixel_to_ground(&cam, u, v, &g));
    u0 = u;
    v0 = v;
    CHECK(fl_camera_foot_to_centre(&cam, &u, &v, 100, &c));
    rg = fl_hypot(g.x_mm, g.y_mm);
    rcen = fl_hypot(c.x_mm, c.y_mm);
    CHECK_LE((int64_t)rg + 49, (int64_t)rcen);   /* 50 mm further, +-1 of rounding */
    CHECK_LE((int64_t)rcen, (int64_t)rg + 51);
    CHECK(v < v0);                               /* further: higher in the image */
    CHECK_LE(abs(u - u0), 16 * 8);
    /* above the horizon and without a camera: false, nothing written */
    u = u0;
    v = -400 * 16;   /* far above the bottom camera's horizon */
    c.x_mm = c.y_mm = 7;
    CHECK(!fl_camera_foot_to_centre(&cam, &u, &v, 100, &c));
    CHECK(!fl_camera_foot_to_centre(NULL, &u, &v, 100, &c));
    CHECK(u == u0 && v == -400 * 16 && c.x_mm == 7 && c.y_mm == 7);
}

/* ---- roll, torso, extrinsics ------------------------------------------------ */

/* The sweeps above with torso pitch / roll (+-10 deg) and a roll offset
 * (+-5 deg) on every pose, against the same reference and tolerances. */
static void test_roll_pixel_to_ground(void)
{
    g_roll_mode = 1;
    test_pixel_to_ground();
    g_roll_mode = 0;
}

static void test_roll_ground_to_pixel(void)
{
    g_roll_mode = 1;
    test_ground_to_pixel();
    g_roll_mode = 0;
}

static void test_roll_horizon(void)
{
    g_roll_mode = 1;
    test_horizon();
    g_roll_mode = 0;
}

/* Zero torso angles and roll offset: the rotation and the centre are the
 * integers of the head-only model (its formulas written out here), bit for
 * bit, for every catalogue camera and random head poses. */
static void test_roll_zero_is_head_only(void)
{
    size_t mi;
    int k, i, j;
    long n = 0;
    t_rng_t rng;
    t_rng_seed(&rng, 0x2e70u);
    for (mi = 0; mi < fl_camera_model_count(); mi++) {
        const fl_camera_model_t *m = fl_camera_model_at(mi);
        for (k = 0; k < (t_quick ? 20 : 300); k++) {
            fl_camera_pose_t ps = make_pose(m, k, &rng);
            fl_camera_t cam;
            fl_angle_t alpha = fl_angle_wrap((int32_t)m->mount_tilt + ps.head_pitch + ps.pitch_offset);
            fl_angle_t theta = fl_angle_wrap((int32_t)ps.head_pitch + ps.pitch_offset);
            int32_t sa = fl_sin_q30(alpha), ca = fl_cos_q30(alpha);
            int32_t sy = fl_sin_q30(ps.head_yaw), cy = fl_cos_q30(ps.head_yaw);
            int32_t st = fl_sin_q30(theta), ct = fl_cos_q30(theta);
            int32_t r[3][3], p[3], xh;
            int same = 1;
            r[0][0] = fl_mul_q30(cy, ca); r[0][1] = -sy; r[0][2] = fl_mul_q30(cy, sa);
            r[1][0] = fl_mul_q30(sy, ca); r[1][1] = cy;  r[1][2] = fl_mul_q30(sy, sa);
            r[2][0] = -sa;                r[2][1] = 0;   r[2][2] = ca;
            xh = fl_rshift_round((int64_t)m->mount_x_mm * ct + (int64_t)m->mount_z_mm * st, 14);
            p[0] = fl_rshift_round((int64_t)xh * cy, 42);
            p[1] = fl_rshift_round((int64_t)xh * sy, 42);
            p[2] = ps.neck_height_mm * 16 +
                   fl_rshift_round(-(int64_t)m->mount_x_mm * st + (int64_t)m->mount_z_mm * ct, 26);
            CHECK_EQ(fl_camera_init(&cam, m, &ps), FL_OK);
            for (i = 0; i < 3; i++) {
                same &= cam.pos_q4[i] == p[i];
                for (j = 0; j < 3; j++)
                    same &= cam.rot_q30[i][j] == r[i][j];
            }
            if (!same)
                t_fail_msg(__FILE__, __LINE__, "%s pose %d: not the head-only integers", m->name, k);
            n++;
        }
    }
    t_info("%ld poses without torso angles or roll offset: rotation and centre bit-identical to "
           "the head-only model", n);
}

static void expect_init_ext(const fl_camera_model_t *m, const fl_camera_extrinsics_t *e,
                            fl_status_t st)
{
    fl_camera_t cam;
    fl_camera_pose_t good = {450, 0, 0, 0, 0, 0, 0};
    CHECK_EQ(fl_camera_init(&cam, fl_camera_model_find("nao4-bottom-320"), &good), FL_OK);
    CHECK_EQ(fl_camera_init_extrinsics(&cam, m, e), st);
    if (st != FL_OK)
        check_projects_nothing(&cam);
}

static void test_roll_invalid(void)
{
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    fl_camera_pose_t ps = {450, 0, 0, 0, 0, 0, 0}, p2;
    fl_camera_extrinsics_t e = {0, 0, 480, 0, 5000, 0}, e2;
    fl_camera_model_t bad;
    fl_camera_t cam;
    CHECK(m != NULL);
    if (!m)
        return;
    /* each new angle: |a| <= 45 deg */
    p2 = ps; p2.torso_roll = FL_CAMERA_MAX_ROLL; expect_init(m, &p2, FL_OK);
    p2.torso_roll = -FL_CAMERA_MAX_ROLL; expect_init(m, &p2, FL_OK);
    p2 = ps; p2.torso_roll = FL_CAMERA_MAX_ROLL + 1; expect_init(m, &p2, FL_ERR_RANGE);
    p2 = ps; p2.torso_roll = INT16_MIN; expect_init(m, &p2, FL_ERR_RANGE);
    p2 = ps; p2.torso_pitch = -FL_CAMERA_MAX_ROLL - 1; expect_init(m, &p2, FL_ERR_RANGE);
    p2 = ps; p2.roll_offset = FL_CAMERA_MAX_ROLL + 1; expect_init(m, &p2, FL_ERR_RANGE);
    p2 = ps; p2.roll_offset = -FL_CAMERA_MAX_ROLL; expect_init(m, &p2, FL_OK);
    /* the finished camera must be upright: a level camera rolled by 45 + 45
     * deg is on its side */
    p2 = ps; p2.head_pitch = (fl_angle_t)-m->mount_tilt;
    p2.roll_offset = FL_CAMERA_MAX_ROLL; p2.torso_roll = FL_CAMERA_MAX_ROLL;
    expect_init(m, &p2, FL_ERR_RANGE);
    p2.torso_roll = fl_angle_from_mdeg(44000); expect_init(m, &p2, FL_OK);
    /* optical axis pushed past the vertical by the torso */
    p2 = ps; p2.head_pitch = (fl_angle_t)(FL_ANGLE_90 - m->mount_tilt - 100);
    p2.torso_pitch = 200; expect_init(m, &p2, FL_ERR_RANGE);
    p2.torso_pitch = 50; expect_init(m, &p2, FL_OK);
    /* extrinsics */
    CHECK_EQ(fl_camera_init_extrinsics(NULL, m, &e), FL_ERR_NULL);
    expect_init_ext(m, NULL, FL_ERR_NULL);
    expect_init_ext(NULL, &e, FL_ERR_NULL);
    expect_init_ext(m, &e, FL_OK);
    bad = *m; bad.width_px = 0; expect_init_ext(&bad, &e, FL_ERR_SIZE);
    bad = *m; bad.focal_q4 = 0; expect_init_ext(&bad, &e, FL_ERR_RANGE);
    e2 = e; e2.roll = FL_CAMERA_MAX_ROLL; expect_init_ext(m, &e2, FL_OK);
    e2 = e; e2.roll = -FL_CAMERA_MAX_ROLL; expect_init_ext(m, &e2, FL_OK);
    e2 = e; e2.roll = FL_CAMERA_MAX_ROLL + 1; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.roll = INT16_MIN; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.pitch = FL_ANGLE_90; expect_init_ext(m, &e2, FL_OK);
    e2 = e; e2.pitch = FL_ANGLE_90 + 1; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.pitch = -FL_ANGLE_90 - 1; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.z_mm = 0; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.z_mm = FL_CAMERA_MAX_Z_MM; expect_init_ext(m, &e2, FL_OK);
    e2 = e; e2.z_mm = FL_CAMERA_MAX_Z_MM + 1; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.x_mm = FL_CAMERA_MAX_XY_MM + 1; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.y_mm = -FL_CAMERA_MAX_XY_MM - 1; expect_init_ext(m, &e2, FL_ERR_RANGE);
    e2 = e; e2.y_mm = INT32_MIN; expect_init_ext(m, &e2, FL_ERR_RANGE);
    /* extremes still project without overflow: far corner, steep roll */
    e2.x_mm = -FL_CAMERA_MAX_XY_MM; e2.y_mm = FL_CAMERA_MAX_XY_MM; e2.z_mm = FL_CAMERA_MAX_Z_MM;
    e2.yaw = 12345; e2.pitch = 200; e2.roll = FL_CAMERA_MAX_ROLL;
    CHECK_EQ(fl_camera_init_extrinsics(&cam, m, &e2), FL_OK);
    {
        fl_point_t g;
        int32_t u, v, i;
        static const int32_t ex[] = {INT32_MIN, -FL_CAMERA_MAX_OFFSET_Q4, 0, 1912,
                                     FL_CAMERA_MAX_OFFSET_Q4, INT32_MAX};
        for (i = 0; i < 36; i++) {
            (void)fl_camera_pixel_to_ground(&cam, ex[i % 6], ex[i / 6], &g);
            (void)fl_camera_horizon_v_q4(&cam, ex[i % 6]);
        }
        g.x_mm = FL_CAMERA_MAX_GROUND_MM;
        g.y_mm = -FL_CAMERA_MAX_GROUND_MM;
        (void)fl_camera_ground_to_pixel(&cam, g, &u, &v);
        CHECK(fl_camera_pixel_to_ground(&cam, 2552, 3800, &g));
    }
}

/* The sign conventions of camera.h, on the nao4 top camera looking ahead. */
static void test_roll_signs(void)
{
    const fl_camera_model_t *m = fl_camera_model_find("nao4-top-640");
    fl_camera_pose_t ps = {450, 0, 0, 0, 0, 0, 0};
    fl_camera_t c0, c1;
    fl_point_t g0, g1;
    int32_t w16;
    CHECK(m != NULL);
    if (!m)
        return;
    w16 = 16 * (m->width_px - 1);
    ps.head_pitch = fl_angle_from_mdeg(15000);
    CHECK_EQ(fl_camera_init(&c0, m, &ps), FL_OK);
    /* leaning right (NAO AngleX > 0): the horizon rises towards the right
     * edge, the camera moves to the right (y < 0) */
    ps.torso_roll = fl_angle_from_mdeg(5000);
    CHECK_EQ(fl_camera_init(&c1, m, &ps), FL_OK);
    CHECK_EQ(fl_camera_horizon_v_q4(&c0, 0), fl_camera_horizon_v_q4(&c0, w16));
    CHECK_LE(fl_camera_horizon_v_q4(&c1, w16) + 16 * 40 + 1, fl_camera_horizon_v_q4(&c1, 0));
    CHECK_LE(c1.pos_q4[1] + 1, -16 * 3);
    /* roll offset of the same sign turns the image the same way */
    ps.torso_roll = 0;
    ps.roll_offset = fl_angle_from_mdeg(5000);
    CHECK_EQ(fl_camera_init(&c1, m, &ps), FL_OK);
    CHECK_LE(fl_camera_horizon_v_q4(&c1, w16) + 16 * 40 + 1, fl_camera_horizon_v_q4(&c1, 0));
    CHECK_EQ(c1.pos_q4[1], c0.pos_q4[1]); /* about the optical axis: no shift */
    /* leaning forward: the image centre sees the ground nearer */
    ps.roll_offset = 0;
    ps.torso_pitch = fl_angle_from_mdeg(5000);
    CHECK_EQ(fl_camera_init(&c1, m, &ps), FL_OK);
    CHECK(fl_camera_pixel_to_ground(&c0, m->cx_q4, m->cy_q4, &g0));
    CHECK(fl_camera_pixel_to_ground(&c1, m->cx_q4, m->cy_q4, &g1));
    CHECK_LE(g1.x_mm + 100 + 1, g0.x_mm);
}

/* ZYX reference of camera.h: R = Rz(yaw) Ry(pitch) Rx(roll); axis i = column i. */
static void ref_init_ext(ref_cam_t *rc, const fl_camera_model_t *m, const fl_camera_extrinsics_t *e)
{
    double y = rad_of(e->yaw), p = rad_of(e->pitch), r = rad_of(e->roll);
    double cy = cos(y), sy = sin(y), cp = cos(p), sp = sin(p), cr = cos(r), sr = sin(r);
    double R[3][3];
    int i;
    R[0][0] = cy * cp; R[0][1] = cy * sp * sr - sy * cr; R[0][2] = cy * sp * cr + sy * sr;
    R[1][0] = sy * cp; R[1][1] = sy * sp * sr + cy * cr; R[1][2] = sy * sp * cr - cy * sr;
    R[2][0] = -sp;     R[2][1] = cp * sr;                R[2][2] = cp * cr;
    for (i = 0; i < 3; i++) {
        rc->axis[i][0] = R[0][i];
        rc->axis[i][1] = R[1][i];
        rc->axis[i][2] = R[2][i];
    }
    rc->p[0] = e->x_mm;
    rc->p[1] = e->y_mm;
    rc->p[2] = e->z_mm;
    rc->f = m->focal_q4 / 16.0;
    rc->cx = m->cx_q4 / 16.0;
    rc->cy = m->cy_q4 / 16.0;
    rc->tilt = p;
}

/* fl_camera_init_extrinsics against the ZYX reference (random positions,
 * yaw, pitch -20..80 deg, roll +-45 deg), and filled from a head pose's
 * reference kinematics (centre rounded to mm, angles from the reference
 * axes): it must see the ground where the pose camera does. */
static void test_extrinsics(void)
{
    size_t mi;
    int k, i, j, nu = t_quick ? 5 : 11, nv = t_quick ? 4 : 9;
    gstat_t st;
    uint32_t h = t_hash_init();
    t_rng_t rng;
    double max_pose = 0, max_hz = 0;
    long n_pose = 0;

    memset(&st, 0, sizeof st);
    t_rng_seed(&rng, 0xe7e7u);
    for (mi = 0; mi < fl_camera_model_count(); mi++) {
        const fl_camera_model_t *m = fl_camera_model_at(mi);
        for (k = 0; k < (t_quick ? 4 : 60); k++) {
            fl_camera_extrinsics_t e;
            fl_camera_t cam;
            ref_cam_t rc;
            e.x_mm = t_rng_range(&rng, -300, 300);
            e.y_mm = t_rng_range(&rng, -300, 300);
            e.z_mm = t_rng_range(&rng, 100, 1000);
            e.yaw = (fl_angle_t)t_rng_range(&rng, -32768, 32767);
            e.pitch = (fl_angle_t)t_rng_range(&rng, -3641, 14563);
            e.roll = (fl_angle_t)t_rng_range(&rng, -FL_CAMERA_MAX_ROLL, FL_CAMERA_MAX_ROLL);
            CHECK_EQ(fl_camera_init_extrinsics(&cam, m, &e), FL_OK);
            ref_init_ext(&rc, m, &e);
            for (j = 0; j < nv; j++)
                for (i = 0; i < nu; i++) {
                    int32_t u = (int32_t)(16 * (m->width_px - 1) * i / (nu - 1));
                    int32_t v = (int32_t)(16 * (m->height_px - 1) * j / (nv - 1));
                    check_p2g(&cam, &rc, u, v, &st, &h);
                }
            for (i = 0; i < 3; i++) {
                int32_t u = t_rng_range(&rng, 0, 16 * (m->width_px - 1));
                int32_t hz = fl_camera_horizon_v_q4(&cam, u);
                double vref = 16.0 * ref_horizon_v(&rc, u / 16.0);
                h = t_hash_i32(h, hz);
                if (hz == INT32_MIN || hz == INT32_MAX)
                    continue;
                if (fabs(hz - floor(vref)) > max_hz)
                    max_hz = fabs(hz - floor(vref));
                CHECK_LE(fabs(hz - floor(vref)), 1.0);
            }
        }
        /* from a head pose with torso and roll, through the reference */
        g_roll_mode = 1;
        for (k = 0; k < (t_quick ? 4 : 40); k++) {
            fl_camera_pose_t ps = make_pose(m, 24 + k, &rng);
            fl_camera_extrinsics_t e;
            fl_camera_t cp, ce;
            ref_cam_t rc;
            ref_init(&rc, m, &ps);
            e.x_mm = (int32_t)lround(rc.p[0]);
            e.y_mm = (int32_t)lround(rc.p[1]);
            e.z_mm = (int32_t)lround(rc.p[2]);
            /* ZYX angles of the reference axes (optical axis = column 0) */
            e.yaw = fl_angle_from_urad((int32_t)lround(1e6 * atan2(rc.axis[0][1], rc.axis[0][0])));
            e.pitch = fl_angle_from_urad((int32_t)lround(1e6 * asin(-rc.axis[0][2])));
            e.roll = fl_angle_from_urad((int32_t)lround(1e6 * atan2(rc.axis[1][2], rc.axis[2][2])));
            CHECK_EQ(fl_camera_init(&cp, m, &ps), FL_OK);
            CHECK_EQ(fl_camera_init_extrinsics(&ce, m, &e), FL_OK);
            for (i = 0; i < 9; i++) {
                int32_t u = (int32_t)(16 * (m->width_px - 1) * (i % 3) / 2);
                int32_t v = (int32_t)(16 * (m->height_px - 1) * (2 + i / 3) / 4);
                fl_point_t g1, g2;
                double r, d, tol;
                if (!fl_camera_pixel_to_ground(&cp, u, v, &g1) ||
                    !fl_camera_pixel_to_ground(&ce, u, v, &g2))
                    continue;
                r = hypot(g1.x_mm, g1.y_mm);
                if (r > 6000)
                    continue;
                /* both cameras' own tolerance against the reference (1 mm
                 * + 0.1% of range each), the centre rounded to mm (0.9 mm)
                 * and 3 angles to binary units (each within 4.8e-5 rad),
                 * which moves a ground point by up to 1.5e-4 * D^2 / z (D
                 * camera-to-point distance, z camera height) */
                d = hypot(g1.x_mm - g2.x_mm, g1.y_mm - g2.y_mm);
                tol = 3.0 + 0.002 * r + 1.5e-4 * (r * r + rc.p[2] * rc.p[2]) / rc.p[2];
                n_pose++;
                if (d / tol > max_pose)
                    max_pose = d / tol;
                if (!(d <= tol))
                    t_fail_msg(__FILE__, __LINE__, "%s pose %d: extrinsics camera %.1f mm off at %.0f mm",
                               m->name, k, d, r);
            }
        }
        g_roll_mode = 0;
    }
    t_info("extrinsics: %ld ground points <= 6 m, max error %.3f mm, max / (1 mm + 0.1%%) %.3f; "
           "horizon max |h - floor(16 v_ref)| %.0f Q4", st.n_near, st.max_err_near, st.max_frac, max_hz);
    t_info("extrinsics filled from head poses (torso, roll): %ld points, max |diff| / tolerance "
           "%.3f", n_pose, max_pose);
    CHECK(st.n_near > 0 && st.n_above > 0 && n_pose > 0);
    t_digest("camera.extrinsics", h);
}

/* The own-model example of camera.h, as written there. */
static void test_own_model_example(void)
{
    fl_camera_t cam;
    fl_camera_model_t m = {"mycam", 640, 480, 8868, 5112, 3832, 0, 0, 0, 450, 0};
    fl_camera_extrinsics_t e = {20, 0, 480, 0, fl_angle_from_mdeg(25000), fl_angle_from_mdeg(-2000)};
    fl_point_t g;
    CHECK_LE(fabs(m.focal_q4 - 16.0 * 320.0 / tan(30.0 * PI_D / 180.0)), 0.5);
    CHECK_EQ(fl_camera_init_extrinsics(&cam, &m, &e), FL_OK);
    /* the image centre looks 25 deg down from 480 mm: 1029 mm ahead */
    CHECK(fl_camera_pixel_to_ground(&cam, m.cx_q4, m.cy_q4, &g));
    CHECK_LE(fabs(g.x_mm - (20 + 480.0 / tan(25.0 * PI_D / 180.0))), 2.0);
    CHECK_LE(abs(g.y_mm), 1);
    /* rolled 2 deg to the right (left side down): the horizon falls towards the right */
    CHECK_LE(fl_camera_horizon_v_q4(&cam, 0) + 16 * 10, fl_camera_horizon_v_q4(&cam, 16 * 639));
}

void suite_camera(void)
{
    t_run("camera.catalogue", test_catalogue);
    t_run("camera.invalid", test_invalid);
    t_run("camera.pixel_to_ground", test_pixel_to_ground);
    t_run("camera.ground_to_pixel", test_ground_to_pixel);
    t_run("camera.horizon", test_horizon);
    t_run("camera.roll_pixel_to_ground", test_roll_pixel_to_ground);
    t_run("camera.roll_ground_to_pixel", test_roll_ground_to_pixel);
    t_run("camera.roll_horizon", test_roll_horizon);
    t_run("camera.roll_zero_is_head_only", test_roll_zero_is_head_only);
    t_run("camera.roll_invalid", test_roll_invalid);
    t_run("camera.roll_signs", test_roll_signs);
    t_run("camera.extrinsics", test_extrinsics);
    t_run("camera.own_model_example", test_own_model_example);
    t_run("camera.extremes", test_extremes);
    t_run("camera.polar", test_polar);
    t_run("camera.foot_to_centre", test_foot_to_centre);
}
