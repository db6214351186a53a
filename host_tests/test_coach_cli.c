/*
 * host_tests/test_coach_cli.c - `fieldloc coach`'s path (tools/eval/coach_view.h
 * coach_cli_run, what cmd_coach.c calls after parsing its options) on the
 * committed coach fixtures (fixtures/coach/): the homography it prints
 * against the firmware's mapping, the feet of the two robots against the
 * scene's truth, the picture; and bad input, each refused with its exit
 * status and a message that says what is wrong: a missing image, points
 * file or background, a bad points line, too few or degenerate points, an
 * unknown field, a background of another size, a frame without a field.
 */
#include "test.h"
#include "eval/coach_view.h"
#include "io/ppm.h"
#include "world/coach_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define FX "fixtures/coach/"

static char t_out[1 << 14];

/* run with the options; stdout in t_out, the error in err */
static int run(const coach_cli_opts_t *o, char *err, int n)
{
    FILE *f = tmpfile();
    size_t got = 0;
    int rc;
    t_out[0] = 0;
    if (!f)
        return -1;
    rc = coach_cli_run(o, f, err, n);
    rewind(f);
    got = fread(t_out, 1, sizeof t_out - 1, f);
    t_out[got] = 0;
    fclose(f);
    return rc;
}

static void base_opts(coach_cli_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->image = FX "coach_two.ppm";
    o->points = FX "coach.points";
    o->background = FX "coach_empty.ppm";
}

static void test_matrix(void)
{
    fl_homog_pair_t p[COACH_POINTS_MAX];
    fl_homog_t h;
    double m[9], worst = 0;
    char err[300];
    int n = 0, u, v;
    CHECK_EQ(coach_points_load(FX "coach.points", fl_field_find("spl2016"), p, NULL,
                               COACH_POINTS_MAX, &n, err, sizeof err), 0);
    CHECK_EQ(n, 5);
    CHECK_EQ(fl_homog_fit(&h, p, (size_t)n), FL_HOMOG_OK);
    CHECK_EQ(coach_homog_matrix(&h, m), 0);
    CHECK_LE(fabs(m[8] - 1.0), 1e-12);
    for (v = 40; v < 480; v += 40)
        for (u = 0; u < 640; u += 64) {
            int32_t x, y;
            double w = m[6] * u + m[7] * v + m[8];
            if (fl_homog_image_to_field_q4(&h, u * 16, v * 16, &x, &y) != FL_HOMOG_OK)
                continue;
            worst = fmax(worst, hypot((m[0] * u + m[1] * v + m[2]) / w - x / 16.0,
                                      (m[3] * u + m[4] * v + m[5]) / w - y / 16.0));
        }
    t_info("# coach matrix against fl_homog_image_to_field_q4: worst %.4f mm", worst);
    CHECK_LE(worst, 0.1);
    memset(&h, 0, sizeof h);
    CHECK_EQ(coach_homog_matrix(&h, m), -1);
}

/* the feet printed: "foot TEAM X Y CONF U V SD" */
static int parse_feet(double xy[][2], char team[][8], int cap)
{
    const char *p = t_out;
    int n = 0;
    while ((p = strstr(p, "\nfoot ")) != NULL && n < cap) {
        if (sscanf(p, "\nfoot %7s %lf %lf", team[n], &xy[n][0], &xy[n][1]) == 3)
            n++;
        p++;
    }
    return n;
}

static void test_fixture(void)
{
    coach_cli_opts_t o;
    render_scene_t sc;
    char err[600] = "", team[8][8], path[256];
    double xy[8][2], err_a = -1, err_b = -1;
    host_image_t pic;
    int rc, n, i;
    struct stat st;
    base_opts(&o);
    snprintf(path, sizeof path, "build/test_coach_cli_%d.ppm", (int)getpid());
    o.out = path;
    rc = run(&o, err, sizeof err);
    CHECK_EQ(rc, 0);
    if (rc != 0)
        t_info("# coach: %s", err);
    CHECK(strstr(t_out, "homography_status ok\n") != NULL);
    CHECK(strstr(t_out, "homography_image_to_field ") != NULL);
    CHECK(strstr(t_out, "reprojection_rms_px ") != NULL);
    CHECK(strstr(t_out, "coach_status ok\n") != NULL);
    n = parse_feet(xy, team, 8);
    coach_fixture_scene(1, &sc);
    /* every foot near the robot of its jersey; each robot found */
    for (i = 0; i < n; i++) {
        int r = !strcmp(team[i], "red") ? 0 : !strcmp(team[i], "blue") ? 1 : -1;
        double d;
        CHECK(r >= 0);
        if (r < 0)
            continue;
        d = hypot(xy[i][0] - sc.robots[r].x_mm, xy[i][1] - sc.robots[r].y_mm);
        t_info("# coach fixture: foot %s (%.0f, %.0f), %.0f mm from robot %c", team[i], xy[i][0],
               xy[i][1], d, r ? 'B' : 'A');
        /* a gross bound that catches a wrong map or team: the accuracy
         * targets are the coach path's own tests */
        CHECK_LE(d, r ? 500.0 : 300.0);
        if (r == 0 && (err_a < 0 || d < err_a)) err_a = d;
        if (r == 1 && (err_b < 0 || d < err_b)) err_b = d;
    }
    t_info("# coach fixture: %d feet for 2 robots; nearest to red A (4.6 m) %.0f mm, to blue B (8 m) "
           "%.0f mm", n, err_a, err_b);
    CHECK(err_a >= 0 && err_b >= 0);
    CHECK_EQ(n, 2); /* one foot per robot */
    /* the picture: the frame beside the top view, legend below */
    CHECK(stat(path, &st) == 0);
    if (ppm_read(path, &pic, err, sizeof err) == 0) {
        CHECK_EQ(pic.width, 640 + 8 + 521);
        CHECK(pic.height > 480);
        host_image_free(&pic);
    } else {
        t_fail_msg(__FILE__, __LINE__, "picture %s: %s", path, err);
    }
    remove(path);
    /* PNG by the name */
    snprintf(path, sizeof path, "build/test_coach_cli_%d.png", (int)getpid());
    o.out = path;
    CHECK_EQ(run(&o, err, sizeof err), 0);
    {
        size_t len = 0;
        char *b = t_read_file(path, &len);
        CHECK(b != NULL && len > 8 && memcmp(b, "\x89PNG", 4) == 0);
        free(b);
    }
    remove(path);
    /* without the background: the a* channel alone, still both robots */
    o.out = NULL;
    o.background = NULL;
    CHECK_EQ(run(&o, err, sizeof err), 0);
    CHECK(strstr(t_out, "background no\n") != NULL);
}

/* The same view as a robot's camera gives it (YUYV422 in the FLRAW
 * container), background too: the firmware reads that format itself. */
static void test_yuyv(void)
{
    coach_cli_opts_t o;
    render_scene_t sc;
    render_frame_t fr;
    char err[600] = "", a[256], b[256], team[8][8];
    double xy[8][2];
    int k, n;
    if (t_quick) /* two full renders */
        return;
    snprintf(a, sizeof a, "build/test_coach_cli_%d_two.raw", (int)getpid());
    snprintf(b, sizeof b, "build/test_coach_cli_%d_empty.raw", (int)getpid());
    for (k = 0; k < 2; k++) {
        coach_fixture_scene(1 - k, &sc);
        sc.format = FL_FMT_YUYV422;
        sc.supersample = 1;
        CHECK(render_frame(&sc, &fr) == 0);
        CHECK(render_write_frame(k ? b : a, &fr) == 0);
        render_frame_free(&fr);
    }
    base_opts(&o);
    o.image = a;
    o.background = b;
    CHECK_EQ(run(&o, err, sizeof err), 0);
    n = parse_feet(xy, team, 8);
    coach_fixture_scene(1, &sc);
    CHECK_EQ(n, 2);
    for (k = 0; k < n; k++) {
        int r = !strcmp(team[k], "blue");
        double d = hypot(xy[k][0] - sc.robots[r].x_mm, xy[k][1] - sc.robots[r].y_mm);
        t_info("# coach yuyv: foot %s %.0f mm from its robot", team[k], d);
        CHECK_LE(d, r ? 500.0 : 300.0);
    }
    remove(a);
    remove(b);
}

static int write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fputs(text, f);
    return fclose(f);
}

/* rc and the start of the error */
static void expect(const coach_cli_opts_t *o, int want_rc, const char *want_err, int line)
{
    char err[600] = "";
    int rc = run(o, err, sizeof err);
    if (rc != want_rc || !strstr(err, want_err))
        t_fail_msg(__FILE__, line, "status %d \"%s\" (want %d, \"...%s...\")", rc, err, want_rc,
                   want_err);
    else
        CHECK(1);
}

static void test_bad_input(void)
{
    coach_cli_opts_t o;
    char pts[256], img[256];
    render_scene_t sc;
    render_frame_t fr;
    snprintf(pts, sizeof pts, "build/test_coach_cli_%d.points", (int)getpid());
    snprintf(img, sizeof img, "build/test_coach_cli_%d_nofield.ppm", (int)getpid());

    base_opts(&o);
    o.image = "build/no_such_frame.ppm";
    expect(&o, 2, "image build/no_such_frame.ppm", __LINE__);
    base_opts(&o);
    o.points = "build/no_such.points";
    expect(&o, 2, "build/no_such.points: cannot open", __LINE__);
    base_opts(&o);
    o.background = "build/no_such_empty.ppm";
    expect(&o, 2, "background build/no_such_empty.ppm", __LINE__);
    base_opts(&o);
    o.field = "spl1999";
    expect(&o, 2, "unknown field \"spl1999\"", __LINE__);

    /* a bad line names its number */
    base_opts(&o);
    o.points = pts;
    CHECK_EQ(write_file(pts, "# two good, one bad\ncentre_mark 319.5 62.125\n"
                             "halfway_right 319.5 114.8125\ncentre_mark 12\n"), 0);
    expect(&o, 2, "points line 4: expected", __LINE__);
    CHECK_EQ(write_file(pts, "penalty_spot 1 2\n"), 0);
    expect(&o, 2, "points line 1: unknown point name 'penalty_spot'", __LINE__);
    /* too few */
    CHECK_EQ(write_file(pts, "corner_pos_left 636.3125 44.1875\ncorner_neg_left 2.6875 44.1875\n"
                             "halfway_right 319.5 114.8125\n"), 0);
    expect(&o, 2, "3 points give no homography: too few points (needs at least 4)", __LINE__);
    CHECK(strstr(t_out, "homography_status too few points") != NULL);
    /* four with three collinear (the far touchline's three and the
     * centre mark) and four all on the halfway line */
    CHECK_EQ(write_file(pts, "corner_pos_left 636.3125 44.1875\ncorner_neg_left 2.6875 44.1875\n"
                             "halfway_left 319.5 44.1875\ncentre_mark 319.5 62.125\n"), 0);
    expect(&o, 2, "4 points give no homography: degenerate points", __LINE__);
    CHECK_EQ(write_file(pts, "319.5 44.1875 0 3000\n319.5 62.125 0 0\n319.5 114.8125 0 -3000\n"
                             "319.5 80 0 -1500\n"), 0);
    expect(&o, 2, "degenerate points", __LINE__);
    /* the same point four times */
    CHECK_EQ(write_file(pts, "centre_mark 319.5 62.125\ncentre_mark 319.5 62.125\n"
                             "centre_mark 319.5 62.125\ncentre_mark 319.5 62.125\n"), 0);
    expect(&o, 2, "degenerate points", __LINE__);
    remove(pts);

    /* a background of another size */
    base_opts(&o);
    o.background = "fixtures/frames/spl2013_l_near.ppm";
    expect(&o, 2, "is 320 x 240, the image 640 x 480", __LINE__);

    /* a frame without a field: the coach turned to face the room (a full
     * render: not under qemu) */
    if (t_quick)
        return;
    coach_fixture_scene(0, &sc);
    sc.robot_heading = fl_angle_from_mdeg(-90000);
    sc.clear_sides = 0;
    sc.supersample = 1;
    CHECK(render_frame(&sc, &fr) == 0);
    CHECK(ppm_write(img, fr.rgb, fr.width, fr.height) == 0);
    render_frame_free(&fr);
    base_opts(&o);
    o.image = img;
    o.background = NULL;
    expect(&o, 1, "the coach path refuses the frame", __LINE__);
    expect(&o, 1, "no field in the frame", __LINE__);
    CHECK(strstr(t_out, "coach_status ") != NULL);
    remove(img);
}

void suite_coach_cli(void)
{
    t_run("coach_cli.matrix", test_matrix);
    t_run("coach_cli.fixture", test_fixture);
    t_run("coach_cli.yuyv", test_yuyv);
    t_run("coach_cli.bad_input", test_bad_input);
}
