/*
 * host_tests/test_coach_scene.c - the coach's scene (tools/world/coach_scene.h):
 * its pose and head pitch (the far touchline just inside the image), a clear
 * line of sight over the room side behind it, the points it sees of seed
 * 003's 17 and the homography fitted from them (exact and with +-0.5 px
 * pixel noise) against the renderer's own ground truth, and the points
 * file reader and writer.
 */
#include "test.h"
#include "world/coach_scene.h"
#include "fieldloc/homography.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const fl_field_t *spl2016(void) { return fl_field_find("spl2016"); }

/* pixel of a field point on the ground, or 0 when behind the camera */
static int px(const render_scene_t *sc, double x, double y, double *u, double *v)
{
    return render_project_field(sc, x, y, 0.0, u, v, NULL);
}

static void test_pose(void)
{
    render_scene_t sc;
    double u, v, ul, vl, ur, vr, margin;
    const fl_field_t *f = spl2016();
    CHECK(f != NULL);
    coach_scene_default(&sc, f);
    CHECK(sc.camera && sc.camera->width_px == 640 && sc.camera->height_px == 480);
    CHECK_EQ(sc.robot_y_mm, -6000);
    CHECK_EQ(sc.head.neck_height_mm, sc.camera->default_neck_height_mm);
    /* far touchline, corner to corner: inside with COACH_EDGE_MARGIN_PX */
    CHECK(px(&sc, -4500, 3000, &ul, &vl) && px(&sc, 4500, 3000, &ur, &vr));
    CHECK(px(&sc, 0, 3000, &u, &v));
    margin = fmin(fmin(ul, 639 - ur), v);
    t_info("# coach pitch %.1f deg: far corners at u %.2f / %.2f, far touchline at v %.2f, near at v %.2f",
           COACH_HEAD_PITCH_MDEG / 1000.0, ul, ur, v, (px(&sc, 0, -3000, &u, &vl), vl));
    CHECK(margin >= COACH_EDGE_MARGIN_PX);
    CHECK(ul < ur); /* the +x end on the right: facing +y */
    /* "just": one degree more and a far corner leaves the margin */
    sc.head.head_pitch = fl_angle_from_mdeg(COACH_HEAD_PITCH_MDEG + 1000);
    CHECK(px(&sc, -4500, 3000, &ul, &vl) && px(&sc, 4500, 3000, &ur, &vr));
    CHECK(fmin(ul, 639 - ur) < COACH_EDGE_MARGIN_PX);
}

/* The room side behind the coach is clear: below the carpet (the floor
 * between the coach and the field) the coach's view is the same as with no
 * room clutter at all, while the plain room puts clutter there (world seed
 * 1); and clearing a side leaves the other sides' clutter as it was (a
 * player's view of the +y side is unchanged). */
static void test_clear_view(void)
{
    render_scene_t sc, plain, bare;
    render_frame_t a, b, c;
    int u, v, diff_clear = 0, diff_plain = 0;
    if (t_quick) /* five full renders: too slow under qemu */
        return;
    coach_scene_default(&sc, spl2016());
    sc.supersample = 1;
    sc.noise_x10 = 0;
    plain = sc;
    plain.clear_sides = 0;
    bare = sc;
    bare.background = 0;
    CHECK(render_frame(&sc, &a) == 0);
    CHECK(render_frame(&plain, &b) == 0);
    CHECK(render_frame(&bare, &c) == 0);
    for (u = 0; u < a.width; u++)
        for (v = c.border_end_v[u]; v < a.height; v++) {
            size_t i = 3 * ((size_t)v * (size_t)a.width + (size_t)u);
            diff_clear += memcmp(a.rgb + i, c.rgb + i, 3) != 0;
            diff_plain += memcmp(b.rgb + i, c.rgb + i, 3) != 0;
        }
    t_info("# coach view, floor rows in front of the carpet: %d / %d pixels differ from a room "
           "without clutter (cleared / plain room)", diff_clear, diff_plain);
    CHECK_EQ(diff_clear, 0);
    CHECK(diff_plain > 1000);
    render_frame_free(&a);
    render_frame_free(&b);
    render_frame_free(&c);
    /* a player at the centre facing the +y side */
    render_scene_default(&sc, spl2016(), fl_camera_model_find("nao6-top-640"));
    sc.robot_heading = fl_angle_from_mdeg(90000);
    sc.supersample = 1;
    plain = sc;
    sc.clear_sides = COACH_CLEAR_SIDES;
    CHECK(render_frame(&sc, &a) == 0);
    CHECK(render_frame(&plain, &b) == 0);
    CHECK(a.size == b.size && memcmp(a.data, b.data, a.size) == 0);
    render_frame_free(&a);
    render_frame_free(&b);
}

/* mean and max of image -> field error over the carpet (a 20 px grid),
 * truth from the renderer's ray */
static void fit_error(const render_scene_t *sc, const fl_homog_t *h, double *mean, double *mx,
                      double *mean5, double *max5)
{
    int u, v, n = 0, n5 = 0;
    double s = 0, s5 = 0;
    *mx = *max5 = 0;
    for (v = 0; v < 480; v += 20)
        for (u = 0; u < 640; u += 20) {
            double g[2], d;
            int32_t x, y;
            render_class_t c = render_classify_pixel(sc, u, v, g);
            if (c != RENDER_CLASS_GREEN && c != RENDER_CLASS_LINE)
                continue;
            if (fabs(g[0]) > 4500 || fabs(g[1]) > 3000)
                continue;
            if (fl_homog_image_to_field_q4(h, u * 16, v * 16, &x, &y) != FL_HOMOG_OK) {
                d = 1e9;
            } else {
                d = hypot(x / 16.0 - g[0], y / 16.0 - g[1]);
            }
            s += d;
            n++;
            if (*mx < d) *mx = d;
            if (hypot(g[0] - COACH_X_MM, g[1] - COACH_Y_MM) <= 5000) {
                s5 += d;
                n5++;
                if (*max5 < d) *max5 = d;
            }
        }
    *mean = n ? s / n : 1e9;
    *mean5 = n5 ? s5 / n5 : 0;
}

static void test_points(void)
{
    render_scene_t sc;
    fl_homog_pair_t p[FL_HOMOG_FIELD_POINTS];
    const char *nm[FL_HOMOG_FIELD_POINTS];
    fl_homog_t h;
    fl_homog_error_t e;
    char list[512] = "";
    int n, i, s;
    double mean, mx, mean5, max5, worst_noisy = 0, worst_noisy5 = 0, sum_noisy = 0, sum_rms = 0;
    uint32_t worst_rms = 0;
    coach_scene_default(&sc, spl2016());
    n = coach_scene_points(&sc, 0, 0, p, nm, FL_HOMOG_FIELD_POINTS);
    for (i = 0; i < n; i++) {
        strcat(list, " ");
        strcat(list, nm[i]);
    }
    t_info("# default coach sees %d of the 17 points:%s", n, list);
    /* far corners, both halfway T's, centre mark */
    CHECK_EQ(n, 5);
    CHECK(n >= FL_HOMOG_MIN_POINTS);
    CHECK_EQ(fl_homog_fit(&h, p, (size_t)n), FL_HOMOG_OK);
    CHECK_EQ(fl_homog_error(&h, p, (size_t)n, &e), FL_HOMOG_OK);
    fit_error(&sc, &h, &mean, &mx, &mean5, &max5);
    t_info("# exact points: reprojection rms %.3f px, %.2f mm; carpet grid error mean %.1f max %.1f mm "
           "(within 5 m of the coach: mean %.1f max %.1f mm)",
           e.rms_px_q4 / 16.0, e.rms_mm_q4 / 16.0, mean, mx, mean5, max5);
    /* exact points up to the Q4 rounding: sub-pixel and a few mm */
    CHECK_LE(e.rms_px_q4, 4);
    CHECK_LE(mx, 40.0);
    for (s = 1; s <= 20; s++) {
        n = coach_scene_points(&sc, 0.5, (uint32_t)s, p, NULL, FL_HOMOG_FIELD_POINTS);
        CHECK_EQ(n, 5);
        CHECK_EQ(fl_homog_fit(&h, p, (size_t)n), FL_HOMOG_OK);
        fit_error(&sc, &h, &mean, &mx, &mean5, &max5);
        CHECK_EQ(fl_homog_error(&h, p, (size_t)n, &e), FL_HOMOG_OK);
        sum_rms += e.rms_px_q4 / 16.0;
        if (worst_rms < e.rms_px_q4) worst_rms = e.rms_px_q4;
        sum_noisy += mean;
        if (worst_noisy < mx) worst_noisy = mx;
        if (worst_noisy5 < max5) worst_noisy5 = max5;
    }
    t_info("# +-0.5 px points (20 draws): reprojection rms mean %.3f px, worst %.3f px; carpet grid "
           "error mean %.1f mm, worst %.1f mm (worst within 5 m of the coach %.1f mm)",
           sum_rms / 20, worst_rms / 16.0, sum_noisy / 20, worst_noisy, worst_noisy5);
    /* five points, eight unknowns: two residual degrees of freedom (the
     * far corners' pixels are the lever); measured worst 1.44 px */
    CHECK_LE(worst_rms, 32);
    CHECK_LE(worst_noisy5, 150.0);
    /* noise is deterministic */
    {
        fl_homog_pair_t q[FL_HOMOG_FIELD_POINTS];
        CHECK_EQ(coach_scene_points(&sc, 0.5, 20, q, NULL, FL_HOMOG_FIELD_POINTS), n);
        CHECK(memcmp(p, q, sizeof q[0] * (size_t)n) == 0);
    }
    /* a robot just in front of the centre mark hides it and the far T
     * behind it (both on the coach's line of sight along x = 0) */
    sc.n_robots = 1;
    sc.robots[0].x_mm = 0;
    sc.robots[0].y_mm = -150;
    sc.robots[0].jersey = RENDER_JERSEY_RED;
    n = coach_scene_points(&sc, 0, 0, p, nm, FL_HOMOG_FIELD_POINTS);
    CHECK_EQ(n, 3);
    for (i = 0; i < n; i++)
        CHECK(strcmp(nm[i], "centre_mark") != 0 && strcmp(nm[i], "halfway_left") != 0);
    CHECK_EQ(coach_scene_points(NULL, 0, 0, p, nm, 5), -1);
}

/* The coach's distance from the touchline: at each, the pitch chosen by the
 * same rule (the largest whole degree with both far corners
 * COACH_EDGE_MARGIN_PX inside; the far touchline itself must be in view),
 * the points seen and whether they fit.  Seed 003's coach needs the far
 * corners: nearer than about 2.5 m only the three collinear points of the
 * halfway line remain. */
static void test_distance(void)
{
    static const int beyond_mm[] = {1000, 2000, 2500, 3000, 3500, 4000};
    int i;
    for (i = 0; i < (int)(sizeof beyond_mm / sizeof beyond_mm[0]); i++) {
        render_scene_t sc;
        fl_homog_pair_t p[FL_HOMOG_FIELD_POINTS];
        fl_homog_t h;
        double ul, ur, vl, vr, vt;
        int deg, best = -1000, n = 0;
        fl_homog_status_t st = FL_HOMOG_TOO_FEW;
        coach_scene_default(&sc, spl2016());
        sc.robot_y_mm = -3000 - beyond_mm[i];
        for (deg = 0; deg <= 29; deg++) {
            sc.head.head_pitch = fl_angle_from_mdeg(deg * 1000);
            if (px(&sc, -4500, 3000, &ul, &vl) && px(&sc, 4500, 3000, &ur, &vr) &&
                px(&sc, 0, 3000, &vt, &vt) && vt >= COACH_EDGE_MARGIN_PX &&
                fmin(ul, 639 - ur) >= COACH_EDGE_MARGIN_PX)
                best = deg;
        }
        if (best >= 0) {
            sc.head.head_pitch = fl_angle_from_mdeg(best * 1000);
            n = coach_scene_points(&sc, 0, 0, p, NULL, FL_HOMOG_FIELD_POINTS);
            st = fl_homog_fit(&h, p, (size_t)(n > 0 ? n : 0));
        } else {
            /* the far corners never fit: pitch down to 20 deg for the points */
            sc.head.head_pitch = fl_angle_from_mdeg(COACH_HEAD_PITCH_MDEG);
            n = coach_scene_points(&sc, 0, 0, p, NULL, FL_HOMOG_FIELD_POINTS);
            st = fl_homog_fit(&h, p, (size_t)(n > 0 ? n : 0));
        }
        t_info("# coach %d mm beyond the touchline: pitch %s%d deg, %d points, fit %s",
               beyond_mm[i], best >= 0 ? "" : "(no pitch keeps the far corners) ",
               best >= 0 ? best : COACH_HEAD_PITCH_MDEG / 1000, n, fl_homog_status_str(st));
        if (beyond_mm[i] <= 2000)
            CHECK(st != FL_HOMOG_OK);
        if (beyond_mm[i] >= 3000)
            CHECK(best >= 0 && n >= 5 && st == FL_HOMOG_OK);
        if (beyond_mm[i] == 3000)
            CHECK_EQ(best * 1000, COACH_HEAD_PITCH_MDEG);
    }
}

static void test_points_file(void)
{
    render_scene_t sc;
    fl_homog_pair_t p[8], q[8];
    const char *nm[8], *nq[8];
    char err[200];
    int n, m, i;
    FILE *f = tmpfile();
    coach_scene_default(&sc, spl2016());
    n = coach_scene_points(&sc, 0.5, 3, p, nm, 8);
    CHECK_EQ(n, 5);
    nm[1] = NULL; /* one written as U V X Y */
    CHECK(f != NULL);
    if (!f) return;
    CHECK_EQ(coach_points_write(f, p, nm, n), 0);
    rewind(f);
    CHECK_EQ(coach_points_read(f, spl2016(), q, nq, 8, &m, err, sizeof err), 0);
    CHECK_EQ(m, n);
    CHECK(memcmp(p, q, sizeof p[0] * (size_t)n) == 0);
    for (i = 0; i < n; i++)
        CHECK(nm[i] ? (nq[i] && !strcmp(nm[i], nq[i])) : nq[i] == NULL);
    fclose(f);
    {
        static const struct { const char *text; const char *err; } bad[] = {
            {"centre_mark 1 2\nbogus 3 4\n", "points line 2: unknown point name"},
            {"# c\n\n1 2 3\n", "points line 3: expected"},
            {"centre_mark x 2\n", "points line 1: expected NAME U V"},
            {"1 2 3.5 4\n", "points line 1: expected U V X_MM Y_MM"},
            {"1e9 2 3 4\n", "points line 1: expected U V"},
            {"nan 2 3 4\n", "points line 1: expected U V"},
        };
        for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); i++) {
            FILE *g = tmpfile();
            if (!g) continue;
            fputs(bad[i].text, g);
            rewind(g);
            err[0] = 0;
            CHECK_EQ(coach_points_read(g, spl2016(), q, nq, 8, &m, err, sizeof err), -1);
            if (strncmp(err, bad[i].err, strlen(bad[i].err)) != 0)
                t_fail_msg(__FILE__, __LINE__, "case %d: '%s'", i, err);
            fclose(g);
        }
    }
    CHECK_EQ(coach_points_load("/nonexistent/points.txt", spl2016(), q, nq, 8, &m, err, sizeof err), -1);
    CHECK(strstr(err, "cannot open") != NULL);
}

/* The committed fixtures/coach/ are what coach_write_fixtures writes now
 * (byte for byte: `make fixtures` leaves them unchanged). */
static void test_fixtures(void)
{
    static const char *const files[] = {"coach_empty.ppm", "coach_empty.scene", "coach_two.ppm",
                                        "coach_two.scene", "coach.points"};
    char dir[] = "build/coach_fixtures_XXXXXX", a[1200], b[1200];
    int i;
    if (t_quick) /* two full renders: too slow under qemu */
        return;
    if (!mkdtemp(dir)) {
        t_fail_msg(__FILE__, __LINE__, "mkdtemp %s", dir);
        return;
    }
    CHECK_EQ(coach_write_fixtures(dir), 0);
    for (i = 0; i < (int)(sizeof files / sizeof files[0]); i++) {
        size_t na = 0, nb = 0;
        char *x, *y;
        snprintf(a, sizeof a, "%s/%s", dir, files[i]);
        snprintf(b, sizeof b, "fixtures/coach/%s", files[i]);
        x = t_read_file(a, &na);
        y = t_read_file(b, &nb);
        if (!x || !y || na != nb || memcmp(x, y, na) != 0)
            t_fail_msg(__FILE__, __LINE__, "%s differs from a fresh render (make fixtures)", b);
        else
            CHECK(1);
        free(x);
        free(y);
        remove(a);
    }
    remove(dir);
}

void suite_coach_scene(void)
{
    t_run("coach_scene.pose", test_pose);
    t_run("coach_scene.clear_view", test_clear_view);
    t_run("coach_scene.points", test_points);
    t_run("coach_scene.distance", test_distance);
    t_run("coach_scene.points_file", test_points_file);
    t_run("coach_scene.fixtures", test_fixtures);
}
