/*
 * host_tests/test_homography.c - the fixed-point normalised DLT
 * (src/model/homography.c) against a double DLT written here, against
 * synthetic points of a known homography, and against the project's camera
 * model (camera.h) for a coach camera beside the touchline.
 *
 * The double reference: Hartley normalisation (centroid, mean distance
 * exactly sqrt(2)), the same h33 = 1 equations, an 8 x 8 solve for four
 * pairs and the normal equations for more, Gaussian elimination with
 * partial pivoting, then H = Tf^-1 Hn Ti.  Both fits see the same integer
 * inputs, so the comparison measures the fixed-point arithmetic (and the
 * power-of-two normalisation) only.
 *
 * Tolerances (measured maxima in the comments of each test):
 *  - random views of a 9 x 6 m field from a 640 x 480 camera beside it
 *    (300 views, 60 quick; 4..17 pairs of random field points in the
 *    image; four-point sets with a corner angle below asin(0.1) skipped):
 *    |fixed - double| <= 0.1 mm (fl_homog_image_to_field_q4; measured
 *    0.049 mm, of which 1/32 mm is the Q4 output's rounding) at every
 *    pixel of a 40 px grid whose double image lies on the carpet; field
 *    -> image within 2/16 px (measured 0.049 px).
 *  - a known homography: an affine map with integer coefficients is
 *    recovered exactly (1/16 mm bound, measured 0); a projective one
 *    from 17 field points rounded to mm to within 1.5 mm over the image
 *    (measured 0.31 mm); four pairs reproduce themselves within 1/8 mm.
 *  - the camera model (test_camera_truth): 11 of the 17 points in view,
 *    725 ground points on a 250 mm grid: image -> field within 1 mm +
 *    0.2% of the range (measured: 0.36 of that; at most 3.2 mm within
 *    5 m), field -> image within 1 px (measured 0.20 px).  The truth is
 *    the camera model's own pixel_to_ground of the same Q4 pixel, so the
 *    error is the fit's (the 17 points' pixels rounded to 1/16 px) plus
 *    the camera model's fixed-point error (camera.h: 1 mm + 0.1%).  Four
 *    of the points (far corners, penalty marks): within 2 x that bound
 *    (measured 2.2 mm over the view).  With uniform pixel noise on the 11
 *    pixels (20 draws): +-0.5 px, worst within 5 m 75 mm; +-1 px, 211 mm
 *    (bounds 160 and 320 mm: a regression check, not a target).
 */
#include "test.h"
#include "fieldloc/homography.h"
#include "fieldloc/camera.h"
#include "fieldloc/field.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- double reference ------------------------------------------------------ */

typedef struct { double h[9]; } dh_t;

static void d_norm(const double (*p)[2], int n, double T[9])
{
    double cx = 0, cy = 0, md = 0, s;
    int i;
    for (i = 0; i < n; i++) { cx += p[i][0]; cy += p[i][1]; }
    cx /= n; cy /= n;
    for (i = 0; i < n; i++) md += hypot(p[i][0] - cx, p[i][1] - cy);
    md /= n;
    s = sqrt(2.0) / md;
    T[0] = s; T[1] = 0; T[2] = -s * cx;
    T[3] = 0; T[4] = s; T[5] = -s * cy;
    T[6] = 0; T[7] = 0; T[8] = 1;
}

static void d_apply(const double H[9], double x, double y, double *X, double *Y, double *W)
{
    double w = H[6] * x + H[7] * y + H[8];
    *X = (H[0] * x + H[1] * y + H[2]) / w;
    *Y = (H[3] * x + H[4] * y + H[5]) / w;
    if (W) *W = w;
}

static void d_mul3(const double A[9], const double B[9], double C[9])
{
    int r, c, k;
    for (r = 0; r < 3; r++)
        for (c = 0; c < 3; c++) {
            C[3 * r + c] = 0;
            for (k = 0; k < 3; k++) C[3 * r + c] += A[3 * r + k] * B[3 * k + c];
        }
}

/* false when singular */
static int d_solve(double m[8][9], double x[8])
{
    int i, r, c;
    for (i = 0; i < 8; i++) {
        int p = i;
        for (r = i + 1; r < 8; r++) if (fabs(m[r][i]) > fabs(m[p][i])) p = r;
        if (fabs(m[p][i]) < 1e-12) return 0;
        for (c = 0; c < 9; c++) { double t = m[i][c]; m[i][c] = m[p][c]; m[p][c] = t; }
        for (r = i + 1; r < 8; r++) {
            double f = m[r][i] / m[i][i];
            for (c = i; c < 9; c++) m[r][c] -= f * m[i][c];
        }
    }
    for (i = 7; i >= 0; i--) {
        double s = m[i][8];
        for (c = i + 1; c < 8; c++) s -= m[i][c] * x[c];
        x[i] = s / m[i][i];
    }
    return 1;
}

/* image (px) -> field (mm) */
static int d_fit(const fl_homog_pair_t *p, int n, dh_t *out)
{
    double img[FL_HOMOG_MAX_POINTS][2], fld[FL_HOMOG_MAX_POINTS][2];
    double Ti[9], Tf[9], Tfi[9], Hn[9], tmp[9], m[8][9], x[8], rows[2][9];
    int i, a, b, k;
    for (i = 0; i < n; i++) {
        img[i][0] = p[i].u_q4 / 16.0; img[i][1] = p[i].v_q4 / 16.0;
        fld[i][0] = p[i].x_mm; fld[i][1] = p[i].y_mm;
    }
    d_norm((const double (*)[2])img, n, Ti);
    d_norm((const double (*)[2])fld, n, Tf);
    memset(m, 0, sizeof m);
    for (i = 0; i < n; i++) {
        double xx = Ti[0] * img[i][0] + Ti[2], yy = Ti[4] * img[i][1] + Ti[5];
        double XX = Tf[0] * fld[i][0] + Tf[2], YY = Tf[4] * fld[i][1] + Tf[5];
        double r0[9] = {xx, yy, 1, 0, 0, 0, -xx * XX, -yy * XX, XX};
        double r1[9] = {0, 0, 0, xx, yy, 1, -xx * YY, -yy * YY, YY};
        memcpy(rows[0], r0, sizeof r0);
        memcpy(rows[1], r1, sizeof r1);
        if (n == 4) {
            memcpy(m[2 * i], r0, sizeof r0);
            memcpy(m[2 * i + 1], r1, sizeof r1);
            continue;
        }
        for (k = 0; k < 2; k++)
            for (a = 0; a < 8; a++)
                for (b = 0; b < 9; b++) m[a][b] += rows[k][a] * rows[k][b];
    }
    if (!d_solve(m, x)) return 0;
    for (i = 0; i < 8; i++) Hn[i] = x[i];
    Hn[8] = 1;
    memset(Tfi, 0, sizeof Tfi);
    Tfi[0] = 1 / Tf[0]; Tfi[2] = -Tf[2] / Tf[0];
    Tfi[4] = 1 / Tf[4]; Tfi[5] = -Tf[5] / Tf[4]; Tfi[8] = 1;
    d_mul3(Hn, Ti, tmp);
    d_mul3(Tfi, tmp, out->h);
    return 1;
}

static void d_inverse(const double a[9], double c[9])
{
    c[0] = a[4] * a[8] - a[5] * a[7]; c[1] = a[2] * a[7] - a[1] * a[8];
    c[2] = a[1] * a[5] - a[2] * a[4]; c[3] = a[5] * a[6] - a[3] * a[8];
    c[4] = a[0] * a[8] - a[2] * a[6]; c[5] = a[2] * a[3] - a[0] * a[5];
    c[6] = a[3] * a[7] - a[4] * a[6]; c[7] = a[1] * a[6] - a[0] * a[7];
    c[8] = a[0] * a[4] - a[1] * a[3];
}

/* ---- a double pinhole coach camera ----------------------------------------- */

typedef struct {
    double cx, cy, cz;   /* field frame, mm */
    double yaw, pitch;   /* heading of the optical axis, tilt down (rad) */
    double f, u0, v0;    /* px */
} dcam_t;

/* field point -> pixel; false behind the camera */
static int dcam_project(const dcam_t *c, double X, double Y, double *u, double *v)
{
    double dx = X - c->cx, dy = Y - c->cy, dz = -c->cz;
    double cyw = cos(c->yaw), syw = sin(c->yaw), cp = cos(c->pitch), sp = sin(c->pitch);
    double fx = cyw * dx + syw * dy, ly = -syw * dx + cyw * dy;   /* level frame */
    double fwd = cp * fx - sp * dz, up = sp * fx + cp * dz;
    if (fwd <= 1) return 0;
    *u = c->u0 - c->f * ly / fwd;
    *v = c->v0 - c->f * up / fwd;
    return 1;
}

static double rnd(t_rng_t *r, double lo, double hi)
{
    return lo + (hi - lo) * (t_rng_u32(r) / 4294967296.0);
}

/* a random coach view of the 9 x 6 m field and n in-image pairs of random
 * field points; 0 when too few landed in the image */
static int random_view(t_rng_t *r, dcam_t *c, fl_homog_pair_t *p, int n)
{
    int k = 0, tries = 0;
    c->cx = rnd(r, -2000, 2000);
    c->cy = -3000 - rnd(r, 500, 1500);
    c->cz = rnd(r, 450, 560);
    c->yaw = 1.5708 + rnd(r, -0.3, 0.3);
    c->pitch = rnd(r, 0.15, 0.35);
    c->f = rnd(r, 260, 400);
    c->u0 = 319.5; c->v0 = 239.5;
    while (k < n && tries < 2000) {
        double X = rnd(r, -4500, 4500), Y = rnd(r, -3000, 3000), u, v;
        int i, dup = 0;
        tries++;
        if (!dcam_project(c, X, Y, &u, &v) || u < 0 || u > 639 || v < 0 || v > 479) continue;
        p[k].x_mm = (int32_t)lround(X); p[k].y_mm = (int32_t)lround(Y);
        p[k].u_q4 = (int32_t)lround(u * 16); p[k].v_q4 = (int32_t)lround(v * 16);
        for (i = 0; i < k; i++)
            if (abs(p[i].u_q4 - p[k].u_q4) < 160 && abs(p[i].v_q4 - p[k].v_q4) < 160) dup = 1;
        if (!dup) k++;
    }
    return k == n;
}

/* smallest |sin| of the angle at a corner of any triangle of the image points */
static double min_sin(const fl_homog_pair_t *p, int n)
{
    double best = 1;
    int i, j, k;
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            for (k = j + 1; k < n; k++) {
                double ax = p[j].u_q4 - p[i].u_q4, ay = p[j].v_q4 - p[i].v_q4;
                double bx = p[k].u_q4 - p[i].u_q4, by = p[k].v_q4 - p[i].v_q4;
                double s;
                if (i == j || i == k) continue;
                s = fabs(ax * by - ay * bx) / (hypot(ax, ay) * hypot(bx, by));
                if (s < best) best = s;
            }
    return best;
}

static void test_against_double(void)
{
    t_rng_t r;
    int sets = t_quick ? 60 : 300, done = 0, tries = 0;
    double worst_mm = 0, worst_px = 0;
    t_rng_seed(&r, 19003);
    while (done < sets && tries < 20 * sets) {
        fl_homog_pair_t p[FL_HOMOG_MAX_POINTS];
        fl_homog_t h;
        dh_t d;
        dcam_t c;
        double inv[9];
        int n = 4 + (int)(t_rng_u32(&r) % (FL_HOMOG_MAX_POINTS - 3)), gu, gv;
        fl_homog_status_t st;
        tries++;
        if (!random_view(&r, &c, p, n) || min_sin(p, n) < (n == 4 ? 0.1 : 0.0)) continue;
        if (!d_fit(p, n, &d)) continue;
        st = fl_homog_fit(&h, p, (size_t)n);
        CHECK_EQ(st, FL_HOMOG_OK);
        if (st != FL_HOMOG_OK) continue;
        done++;
        d_inverse(d.h, inv);
        for (gu = 0; gu <= 640; gu += 40)
            for (gv = 0; gv <= 480; gv += 40) {
                int32_t u = gu * 16 - (gu == 640 ? 16 : 0), v = gv * 16 - (gv == 480 ? 16 : 0);
                double X, Y, W, U, V, WW;
                fl_point_t q;
                int32_t fu, fv, fx, fy;
                d_apply(d.h, u / 16.0, v / 16.0, &X, &Y, &W);
                if (W <= 0 || fabs(X) > 5200 || fabs(Y) > 3700) continue;
                CHECK_EQ(fl_homog_image_to_field_q4(&h, u, v, &fx, &fy), FL_HOMOG_OK);
                worst_mm = fmax(worst_mm, hypot(fx / 16.0 - X, fy / 16.0 - Y));
                q.x_mm = (int32_t)lround(X); q.y_mm = (int32_t)lround(Y);
                d_apply(inv, q.x_mm, q.y_mm, &U, &V, &WW);
                CHECK_EQ(fl_homog_field_to_image(&h, q, &fu, &fv), FL_HOMOG_OK);
                worst_px = fmax(worst_px, hypot(fu / 16.0 - U, fv / 16.0 - V));
            }
    }
    CHECK_EQ(done, sets);
    t_info("homography vs double DLT: %d views, 4..%d pairs: max %.3f mm (image -> field), "
           "%.4f px (field -> image)", done, FL_HOMOG_MAX_POINTS, worst_mm, worst_px);
    CHECK_LE(worst_mm, 0.1);
    CHECK_LE(worst_px, 2.0 / 16);
}

/* an affine map with integer coefficients: recovered exactly (to the
 * 1/16 mm of the Q4 output); a projective one from rounded field points:
 * within 1.5 mm */
static void test_known(void)
{
    /* X = 3 (u/16) + 2 (v/16) - 1000, Y = -(u/16) + 4 (v/16) - 500, pixels on a 16 px grid */
    static const int pix[17][2] = {{0, 0}, {640, 0}, {0, 480}, {640, 480}, {320, 240},
                                   {160, 96}, {480, 400}, {96, 320}, {560, 160}, {256, 32},
                                   {32, 448}, {608, 336}, {400, 80}, {208, 384}, {352, 304},
                                   {512, 464}, {128, 176}};
    static const double Hp[9] = {12.0, 3.0, -3500.0, 0.5, 20.0, -1200.0, 0.0002, 0.004, 1.0};
    fl_homog_pair_t p[17];
    fl_homog_t h;
    fl_homog_error_t e;
    int n, i, u, v;
    double worst_aff = 0, worst_proj = 0;
    for (n = 4; n <= 17; n += 13) {
        for (i = 0; i < n; i++) {
            p[i].u_q4 = pix[i][0] * 16; p[i].v_q4 = pix[i][1] * 16;
            p[i].x_mm = 3 * pix[i][0] + 2 * pix[i][1] - 1000;
            p[i].y_mm = -pix[i][0] + 4 * pix[i][1] - 500;
        }
        CHECK_EQ(fl_homog_fit(&h, p, (size_t)n), FL_HOMOG_OK);
        CHECK_EQ(fl_homog_error(&h, p, (size_t)n, &e), FL_HOMOG_OK);
        CHECK_EQ(e.n_used, (uint32_t)n);
        CHECK_LE(e.max_mm_q4, 1);
        CHECK_LE(e.max_px_q4, 1);
        for (u = 0; u < 640; u += 37)
            for (v = 0; v < 480; v += 29) {
                int32_t x, y;
                CHECK_EQ(fl_homog_image_to_field_q4(&h, u * 16, v * 16, &x, &y), FL_HOMOG_OK);
                worst_aff = fmax(worst_aff, hypot(x / 16.0 - (3 * u + 2 * v - 1000),
                                                  y / 16.0 - (-u + 4 * v - 500)));
            }
        for (i = 0; i < n; i++) {
            double X, Y;
            d_apply(Hp, pix[i][0], pix[i][1], &X, &Y, NULL);
            p[i].x_mm = (int32_t)lround(X); p[i].y_mm = (int32_t)lround(Y);
        }
        CHECK_EQ(fl_homog_fit(&h, p, (size_t)n), FL_HOMOG_OK);
        CHECK_EQ(fl_homog_error(&h, p, (size_t)n, &e), FL_HOMOG_OK);
        if (n == 4)
            CHECK_LE(e.max_mm_q4, 2);   /* four pairs: an exact fit */
        for (u = 0; u < 640; u += 37)
            for (v = 0; v < 480; v += 29) {
                int32_t x, y;
                double X, Y;
                d_apply(Hp, u, v, &X, &Y, NULL);
                CHECK_EQ(fl_homog_image_to_field_q4(&h, u * 16, v * 16, &x, &y), FL_HOMOG_OK);
                if (n == 17)
                    worst_proj = fmax(worst_proj, hypot(x / 16.0 - X, y / 16.0 - Y));
            }
    }
    t_info("homography known maps: affine %.4f mm, projective (17 rounded pairs) %.3f mm",
           worst_aff, worst_proj);
    CHECK_LE(worst_aff, 1.0 / 16);
    CHECK_LE(worst_proj, 1.5);
}

/* ---- the camera model's truth ------------------------------------------------ */

/* The coach: a robot standing ROBOT_Y_MM beside the touchline at the
 * halfway line, facing across the field (+y), camera CAM_Z_MM above the
 * ground (a standing NAO's head) pitched PITCH_MDEG down.  The lens: a
 * 640 x 480 image with a 100 degree horizontal field of view (a NAO's own
 * 56 degree lens sees only the centre mark and the far T from there). */
#define ROBOT_Y_MM (-3700)
#define CAM_Z_MM 510
#define PITCH_MDEG 17000

static void robot_from_field(int32_t X, int32_t Y, fl_point_t *g)
{
    g->x_mm = Y - ROBOT_Y_MM;   /* robot at (0, ROBOT_Y_MM), heading +90 deg */
    g->y_mm = -X;
}

static void field_from_robot(fl_point_t g, int32_t *X, int32_t *Y)
{
    *X = -g.y_mm;
    *Y = g.x_mm + ROBOT_Y_MM;
}

static void coach_camera(fl_camera_t *cam)
{
    static const fl_camera_model_t m = {"coach-wide-640", 640, 480, 4296, 5112, 3832,
                                        0, 0, 0, 450, 0};
    fl_camera_extrinsics_t e;
    memset(&e, 0, sizeof e);
    e.z_mm = CAM_Z_MM;
    e.pitch = fl_angle_from_mdeg(PITCH_MDEG);
    CHECK_EQ(fl_camera_init_extrinsics(cam, &m, &e), FL_OK);
}

typedef struct {
    int cnt;
    double near_mm, all_mm, rel, px;   /* maxima; rel: error / (1 mm + 0.2% of range) */
} truth_t;

/* h against the camera model at the ground points of a 250 mm grid over the
 * field that the camera sees */
static void truth_error(const fl_homog_t *h, const fl_camera_t *cam, truth_t *t)
{
    int32_t X, Y;
    memset(t, 0, sizeof *t);
    for (X = -4500; X <= 4500; X += 250)
        for (Y = -3000; Y <= 3000; Y += 250) {
            fl_point_t g, cg, hf, q;
            int32_t u, v, hu, hv, cx, cy;
            double d, range;
            robot_from_field(X, Y, &g);
            if (!fl_camera_ground_to_pixel(cam, g, &u, &v) || u < 0 || u > 639 * 16 ||
                v < 0 || v > 479 * 16 || !fl_camera_pixel_to_ground(cam, u, v, &cg))
                continue;
            field_from_robot(cg, &cx, &cy);
            CHECK_EQ(fl_homog_image_to_field(h, u, v, &hf), FL_HOMOG_OK);
            d = hypot(hf.x_mm - cx, hf.y_mm - cy);
            range = hypot(g.x_mm, g.y_mm);
            t->rel = fmax(t->rel, d / (1 + 0.002 * range));
            t->all_mm = fmax(t->all_mm, d);
            if (range <= 5000)
                t->near_mm = fmax(t->near_mm, d);
            q.x_mm = X;
            q.y_mm = Y;
            CHECK_EQ(fl_homog_field_to_image(h, q, &hu, &hv), FL_HOMOG_OK);
            t->px = fmax(t->px, hypot(hu - u, hv - v) / 16.0);
            t->cnt++;
        }
}

/* the named field points the coach sees, as pairs; noise_q4 > 0 moves each
 * pixel by a uniform -noise..+noise (Q4) per axis */
static size_t coach_pairs(const fl_camera_t *cam, fl_homog_pair_t *p, t_rng_t *r,
                          int32_t noise_q4)
{
    fl_homog_field_point_t fp[FL_HOMOG_FIELD_POINTS];
    size_t nf, i, n = 0;
    nf = fl_homog_field_points(fl_field_find("spl2020"), fp, FL_HOMOG_FIELD_POINTS);
    CHECK_EQ(nf, 17);
    for (i = 0; i < nf; i++) {
        fl_point_t g;
        int32_t u, v;
        robot_from_field(fp[i].x_mm, fp[i].y_mm, &g);
        if (!fl_camera_ground_to_pixel(cam, g, &u, &v) || u < 0 || u > 639 * 16 ||
            v < 0 || v > 479 * 16)
            continue;
        if (noise_q4 > 0) {
            u += t_rng_range(r, -noise_q4, noise_q4);
            v += t_rng_range(r, -noise_q4, noise_q4);
        }
        p[n].u_q4 = u; p[n].v_q4 = v;
        p[n].x_mm = fp[i].x_mm; p[n].y_mm = fp[i].y_mm;
        n++;
    }
    return n;
}

static void test_camera_truth(void)
{
    fl_homog_pair_t p[FL_HOMOG_FIELD_POINTS], p4[4];
    fl_camera_t cam;
    fl_homog_t h;
    fl_homog_error_t e;
    truth_t t;
    t_rng_t r;
    size_t n, i, k = 0;
    double noisy_near = 0, noisy_all = 0;
    int run, noise;
    coach_camera(&cam);
    t_rng_seed(&r, 3);
    n = coach_pairs(&cam, p, &r, 0);
    t_info("coach camera: %u of the 17 field points in view", (unsigned)n);
    CHECK(n >= 10);
    CHECK_EQ(fl_homog_fit(&h, p, n), FL_HOMOG_OK);
    CHECK_EQ(fl_homog_error(&h, p, n, &e), FL_HOMOG_OK);
    t_info("coach camera fit: reprojection rms %.2f mm max %.2f mm, rms %.3f px max %.3f px",
           e.rms_mm_q4 / 16.0, e.max_mm_q4 / 16.0, e.rms_px_q4 / 16.0, e.max_px_q4 / 16.0);
    CHECK_LE(e.max_px_q4, 16);
    truth_error(&h, &cam, &t);
    t_info("coach camera vs camera model (%u pairs): %d ground points, within 5 m max %.1f mm, "
           "all max %.1f mm, max error / (1 mm + 0.2%% of range) %.2f, field -> image max "
           "%.2f px", (unsigned)n, t.cnt, t.near_mm, t.all_mm, t.rel, t.px);
    CHECK(t.cnt > 300);
    CHECK_LE(t.rel, 1.0);
    CHECK_LE(t.px, 1.0);
    /* four of them: the far corners and the penalty marks, an exact fit */
    for (i = 0; i < n && k < 4; i++)
        if ((p[i].y_mm == 3000 && (p[i].x_mm == 4500 || p[i].x_mm == -4500)) ||
            (p[i].y_mm == 0 && p[i].x_mm != 0))
            p4[k++] = p[i];
    CHECK_EQ(k, 4);
    CHECK_EQ(fl_homog_fit(&h, p4, 4), FL_HOMOG_OK);
    truth_error(&h, &cam, &t);
    t_info("coach camera vs camera model (4 pairs): within 5 m max %.1f mm, all max %.1f mm, "
           "field -> image max %.2f px", t.near_mm, t.all_mm, t.px);
    CHECK_LE(t.rel, 2.0);
    CHECK_LE(t.px, 1.0);
    /* the pixels as vision finds them: +-0.5 and +-1 px uniform noise on
     * every one, 20 draws each (a regression bound: the far points' depth
     * moves about 0.5 m per pixel, which the fit inherits) */
    for (noise = 8; noise <= 16; noise += 8) {
        double mean_near = 0;
        noisy_near = noisy_all = 0;
        for (run = 0; run < 20; run++) {
            n = coach_pairs(&cam, p, &r, noise);
            CHECK_EQ(fl_homog_fit(&h, p, n), FL_HOMOG_OK);
            truth_error(&h, &cam, &t);
            noisy_near = fmax(noisy_near, t.near_mm);
            noisy_all = fmax(noisy_all, t.all_mm);
            mean_near += t.near_mm / 20;
        }
        t_info("coach camera, +-%.1f px noise on the %u pixels, 20 draws: within 5 m worst "
               "%.1f mm (mean of the draws' worst %.1f mm), whole view worst %.1f mm",
               noise / 16.0, (unsigned)n, noisy_near, mean_near, noisy_all);
        CHECK_LE(noisy_near, noise * 20.0);
    }
}

/* ---- bad input ------------------------------------------------------------- */

static void set4(fl_homog_pair_t *p, const int32_t uv[4][2], const int32_t xy[4][2])
{
    int i;
    for (i = 0; i < 4; i++) {
        p[i].u_q4 = uv[i][0]; p[i].v_q4 = uv[i][1];
        p[i].x_mm = xy[i][0]; p[i].y_mm = xy[i][1];
    }
}

static void test_degenerate(void)
{
    static const int32_t uv[4][2] = {{800, 6000}, {9000, 6100}, {7000, 2000}, {2500, 2100}};
    static const int32_t xy[4][2] = {{-1500, -2000}, {1500, -2000}, {1500, 2000}, {-1500, 2000}};
    static const int32_t uv_col[4][2] = {{800, 6000}, {4800, 4000}, {8800, 2000}, {2500, 2100}};
    static const int32_t xy_col[4][2] = {{-1500, -2000}, {0, -2000}, {1500, -2000}, {-1500, 2000}};
    fl_homog_pair_t p[FL_HOMOG_MAX_POINTS + 1];
    fl_homog_t h;
    fl_homog_error_t e;
    fl_point_t q;
    int32_t u, v;
    int i;
    set4(p, uv, xy);
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_OK);
    CHECK_EQ(fl_homog_fit(NULL, p, 4), FL_HOMOG_ERR_NULL);
    CHECK_EQ(fl_homog_fit(&h, NULL, 4), FL_HOMOG_ERR_NULL);
    CHECK_EQ(fl_homog_fit(&h, p, 3), FL_HOMOG_TOO_FEW);
    CHECK_EQ(fl_homog_fit(&h, p, 0), FL_HOMOG_TOO_FEW);
    /* a failed fit leaves h not fitted */
    CHECK_EQ(fl_homog_image_to_field(&h, 100, 100, &q), FL_HOMOG_NOT_FITTED);
    CHECK_EQ(fl_homog_field_to_image(&h, q, &u, &v), FL_HOMOG_NOT_FITTED);
    CHECK_EQ(fl_homog_error(&h, p, 4, &e), FL_HOMOG_NOT_FITTED);
    for (i = 4; i <= FL_HOMOG_MAX_POINTS; i++) p[i] = p[i % 4];
    CHECK_EQ(fl_homog_fit(&h, p, FL_HOMOG_MAX_POINTS + 1), FL_HOMOG_RANGE);
    CHECK_EQ(fl_homog_fit(&h, p, 5), FL_HOMOG_DEGENERATE);   /* a duplicate */
    /* three of four collinear in the image, then in the field */
    set4(p, uv_col, xy);
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_DEGENERATE);
    set4(p, uv, xy_col);
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_DEGENERATE);
    /* nearly collinear (0.03 degree off) is still degenerate */
    set4(p, uv_col, xy);
    p[1].v_q4 += 2;
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_DEGENERATE);
    /* all of many collinear */
    for (i = 0; i < 9; i++) {
        p[i].u_q4 = 100 + 700 * i; p[i].v_q4 = 7000 - 500 * i;
        p[i].x_mm = -4000 + 1000 * i; p[i].y_mm = 300 * i;
    }
    CHECK_EQ(fl_homog_fit(&h, p, 9), FL_HOMOG_DEGENERATE);
    /* four collinear of five: the system is singular */
    set4(p, uv, xy);
    for (i = 0; i < 4; i++) {
        p[i].u_q4 = 1000 + 1500 * i; p[i].v_q4 = 6000 - 700 * i;
        p[i].x_mm = -3000 + 2000 * i; p[i].y_mm = -2000;
    }
    p[4].u_q4 = 3000; p[4].v_q4 = 2000; p[4].x_mm = 0; p[4].y_mm = 2500;
    CHECK_EQ(fl_homog_fit(&h, p, 5), FL_HOMOG_DEGENERATE);
    /* out of range coordinates */
    set4(p, uv, xy);
    p[2].u_q4 = FL_HOMOG_MAX_Q4 + 1;
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_RANGE);
    set4(p, uv, xy);
    p[3].y_mm = INT32_MIN;
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_RANGE);
    /* a convex quadrilateral onto a crossed one (two adjacent corners
     * swapped): the exact map puts the horizon line through it, so its
     * corners lie on both sides; two opposite corners swapped is a mirror
     * image, which a homography maps fine */
    set4(p, uv, xy);
    p[0].x_mm = 1500;
    p[1].x_mm = -1500;
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_DEGENERATE);
    set4(p, uv, xy);
    p[0].x_mm = 1500; p[0].y_mm = 2000;
    p[2].x_mm = -1500; p[2].y_mm = -2000;
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_OK);
    /* mapping: the horizon and beyond, out of range, NULL */
    set4(p, uv, xy);
    CHECK_EQ(fl_homog_fit(&h, p, 4), FL_HOMOG_OK);
    CHECK_EQ(fl_homog_image_to_field(&h, 4800, -200000, &q), FL_HOMOG_HORIZON);
    CHECK_EQ(fl_homog_image_to_field(&h, 4800, FL_HOMOG_MAX_Q4 + 1, &q), FL_HOMOG_RANGE);
    CHECK_EQ(fl_homog_image_to_field(&h, 4800, 4000, NULL), FL_HOMOG_ERR_NULL);
    CHECK_EQ(fl_homog_image_to_field(NULL, 4800, 4000, &q), FL_HOMOG_ERR_NULL);
    q.x_mm = 0; q.y_mm = 900000;   /* far ahead: just below the horizon line */
    CHECK_EQ(fl_homog_field_to_image(&h, q, &u, &v), FL_HOMOG_OK);
    q.y_mm = -900000;              /* behind the camera */
    CHECK_EQ(fl_homog_field_to_image(&h, q, &u, &v), FL_HOMOG_HORIZON);
    CHECK_EQ(fl_homog_field_to_image(&h, q, NULL, &v), FL_HOMOG_ERR_NULL);
    CHECK_EQ(fl_homog_error(&h, NULL, 4, &e), FL_HOMOG_ERR_NULL);
    CHECK(strcmp(fl_homog_status_str(FL_HOMOG_DEGENERATE), "degenerate points") == 0);
    CHECK(fl_homog_status_str((fl_homog_status_t)99) != NULL);
}

/* random garbage never crashes and a fit that succeeds maps its own points */
static void test_random_input(void)
{
    t_rng_t r;
    int k, ok = 0, runs = t_quick ? 300 : 2000;
    t_rng_seed(&r, 77);
    for (k = 0; k < runs; k++) {
        fl_homog_pair_t p[FL_HOMOG_MAX_POINTS];
        fl_homog_t h;
        fl_homog_error_t e;
        int n = (int)(t_rng_u32(&r) % (FL_HOMOG_MAX_POINTS + 1)), i;
        int32_t span = (int32_t)1 << (t_rng_u32(&r) % 21);
        for (i = 0; i < n; i++) {
            p[i].u_q4 = t_rng_range(&r, -span, span);
            p[i].v_q4 = t_rng_range(&r, -span, span);
            p[i].x_mm = t_rng_range(&r, -span, span);
            p[i].y_mm = t_rng_range(&r, -span, span);
        }
        if (fl_homog_fit(&h, p, (size_t)n) == FL_HOMOG_OK) {
            ok++;
            CHECK_EQ(fl_homog_error(&h, p, (size_t)n, &e), FL_HOMOG_OK);
            CHECK_EQ(e.n_failed, 0);
        }
    }
    t_info("homography random input: %d of %d fits accepted", ok, runs);
}

static void test_field_points(void)
{
    fl_homog_field_point_t fp[FL_HOMOG_FIELD_POINTS];
    const fl_field_t *f = fl_field_find("spl2013");
    size_t n = fl_homog_field_points(f, fp, FL_HOMOG_FIELD_POINTS), i;
    CHECK_EQ(n, 17);
    CHECK(strcmp(fp[0].name, "corner_pos_left") == 0 && fp[0].x_mm == 4500 && fp[0].y_mm == 3000);
    /* spl2013: penalty area 600 x 2200 (the 2016 rules') */
    CHECK(strcmp(fp[6].name, "penalty_pos_front_left") == 0);
    CHECK_EQ(fp[6].x_mm, 3900);
    CHECK_EQ(fp[6].y_mm, 1100);
    CHECK(strcmp(fp[12].name, "penalty_mark_pos") == 0 && fp[12].x_mm == 2700);
    CHECK(strcmp(fp[16].name, "centre_mark") == 0 && fp[16].x_mm == 0 && fp[16].y_mm == 0);
    for (i = 0; i < n; i++) {
        size_t j;
        for (j = i + 1; j < n; j++)
            CHECK(fp[i].x_mm != fp[j].x_mm || fp[i].y_mm != fp[j].y_mm);
    }
    CHECK_EQ(fl_homog_field_points(f, fp, 5), 5);
    CHECK_EQ(fl_homog_field_points(NULL, fp, 17), 0);
    CHECK_EQ(fl_homog_field_points(f, NULL, 17), 0);
}

void suite_homography(void)
{
    t_run("homography.field_points", test_field_points);
    t_run("homography.known", test_known);
    t_run("homography.against_double", test_against_double);
    t_run("homography.camera_truth", test_camera_truth);
    t_run("homography.degenerate", test_degenerate);
    t_run("homography.random_input", test_random_input);
}
