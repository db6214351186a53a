/*
 * host_tests/test_calib.c - the calibration text (fieldloc/calib.h): a good
 * file, every kind of malformed line with its status and line number, the
 * write -> parse round trip, and the pose it applies; then the
 * detection-driven camera fit (tools/eval/calib_frames.h) on rendered
 * frames with known offsets, and the frames-file errors.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "eval/calib_frames.h"
#include "world/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static fl_status_t parse_str(const char *s, fl_calib_t *c, int32_t *line)
{
    const char *why = NULL;
    fl_status_t st = fl_calib_parse(s, strlen(s), c, line, &why);
    CHECK(why != NULL);
    return st;
}

static void test_good(void)
{
    fl_calib_t c;
    int32_t line = -1;
    const char *txt = "# robot 7, fitted 2026-11-27\n"
                      "\n"
                      "fieldloc-calibration 1   # version\r\n"
                      "camera nao4-bottom-320\n"
                      "  neck_height_mm\t472\n"
                      "pitch_offset_deg -2.5\n"
                      "roll_offset_deg +0.010986"; /* no final LF */
    CHECK_EQ(parse_str(txt, &c, &line), FL_OK);
    CHECK_EQ(line, 0);
    CHECK_EQ(c.has, FL_CALIB_HAS_CAMERA | FL_CALIB_HAS_NECK | FL_CALIB_HAS_PITCH |
                        FL_CALIB_HAS_ROLL);
    CHECK(strcmp(c.camera, "nao4-bottom-320") == 0);
    CHECK_EQ(c.neck_height_mm, 472);
    CHECK_EQ(c.pitch_offset, -455);   /* -2.5 deg * 65536 / 360 = -455.1 */
    CHECK_EQ(c.roll_offset, 2);       /* 0.010986 deg = 1.99997 units */
    /* header only: nothing held */
    CHECK_EQ(parse_str("fieldloc-calibration 1\n", &c, &line), FL_OK);
    CHECK_EQ(c.has, 0u);
    /* boundaries accepted */
    CHECK_EQ(parse_str("fieldloc-calibration 1\nneck_height_mm 50\npitch_offset_deg 45\n"
                       "roll_offset_deg -45.000000000\n",
                       &c, &line),
             FL_OK);
    CHECK_EQ(c.neck_height_mm, 50);
    CHECK_EQ(c.pitch_offset, 8192);
    CHECK_EQ(c.roll_offset, -8192);
    CHECK_EQ(parse_str("fieldloc-calibration 1\npitch_offset_deg .5\nroll_offset_deg 3.\n", &c,
                       &line),
             FL_OK);
    CHECK_EQ(c.pitch_offset, 91);     /* 91.02 */
    CHECK_EQ(c.roll_offset, 546);     /* 546.13 */
}

typedef struct {
    const char *text;
    fl_status_t status;
    int32_t line;
} bad_case_t;

static void test_malformed(void)
{
    static const bad_case_t cases[] = {
        {"", FL_ERR_FORMAT, 0},                                          /* empty */
        {"# only a comment\n\n", FL_ERR_FORMAT, 0},
        {"camera nao4-bottom-320\n", FL_ERR_FORMAT, 1},                  /* missing header */
        {"\nfieldloc-calibration 2\n", FL_ERR_RANGE, 2},                 /* version */
        {"fieldloc-calibration one\n", FL_ERR_FORMAT, 1},
        {"fieldloc-calibration 1\nfocal_px 272\n", FL_ERR_NOT_FOUND, 2}, /* unknown key */
        {"fieldloc-calibration 1\nneck_height_mm 47x\n", FL_ERR_FORMAT, 2}, /* non-number */
        {"fieldloc-calibration 1\nneck_height_mm 472.5\n", FL_ERR_FORMAT, 2},
        {"fieldloc-calibration 1\npitch_offset_deg -\n", FL_ERR_FORMAT, 2},
        {"fieldloc-calibration 1\npitch_offset_deg 1e3\n", FL_ERR_FORMAT, 2},
        {"fieldloc-calibration 1\npitch_offset_deg 0.1234567891\n", FL_ERR_FORMAT, 2},
        {"fieldloc-calibration 1\n\nroll_offset_deg 1..2\n", FL_ERR_FORMAT, 3},
        {"fieldloc-calibration 1\nneck_height_mm 49\n", FL_ERR_RANGE, 2}, /* out of range */
        {"fieldloc-calibration 1\nneck_height_mm 2001\n", FL_ERR_RANGE, 2},
        {"fieldloc-calibration 1\nneck_height_mm 99999999999999999999999\n", FL_ERR_RANGE, 2},
        {"fieldloc-calibration 1\npitch_offset_deg 45.000001\n", FL_ERR_RANGE, 2},
        {"fieldloc-calibration 1\nroll_offset_deg -90\n", FL_ERR_RANGE, 2},
        {"fieldloc-calibration 1\nneck_height_mm\n", FL_ERR_FORMAT, 2},  /* missing value */
        {"fieldloc-calibration 1\nneck_height_mm 470 471\n", FL_ERR_FORMAT, 2}, /* extra */
        {"fieldloc-calibration 1\nneck_height_mm 470\nneck_height_mm 471\n", FL_ERR_FORMAT, 3},
        {"fieldloc-calibration 1\nfieldloc-calibration 1\n", FL_ERR_FORMAT, 2},
        {"fieldloc-calibration 1\ncamera nao4/bottom\n", FL_ERR_FORMAT, 2},
        {"fieldloc-calibration 1\ncamera abcdefghijklmnopqrstuvwxyz0123456\n", FL_ERR_FORMAT, 2},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fl_calib_t c;
        int32_t line = -1;
        fl_status_t st = parse_str(cases[i].text, &c, &line);
        if (st != cases[i].status || line != cases[i].line)
            t_fail_msg(__FILE__, __LINE__, "case %u: status %d line %d, want %d line %d",
                       (unsigned)i, (int)st, (int)line, (int)cases[i].status,
                       (int)cases[i].line);
        CHECK_EQ(c.has, 0u); /* out cleared on error */
    }
}

static void test_limits(void)
{
    char buf[FL_CALIB_TEXT_MAX + 64];
    fl_calib_t c;
    int32_t line = -1;
    const char *why = NULL;
    size_t n;
    /* overlong line (line 3), even inside a comment */
    n = (size_t)snprintf(buf, sizeof buf, "fieldloc-calibration 1\n\n#");
    memset(buf + n, 'x', FL_CALIB_LINE_MAX);
    strcpy(buf + n + FL_CALIB_LINE_MAX, "\nneck_height_mm 470\n");
    CHECK_EQ(parse_str(buf, &c, &line), FL_ERR_SIZE);
    CHECK_EQ(line, 3);
    /* exactly FL_CALIB_LINE_MAX bytes is fine ('#' and LINE_MAX - 1 x) */
    memset(buf + n, 'x', FL_CALIB_LINE_MAX - 1);
    strcpy(buf + n + FL_CALIB_LINE_MAX - 1, "\nneck_height_mm 470\n");
    CHECK_EQ(parse_str(buf, &c, &line), FL_OK);
    CHECK_EQ(c.neck_height_mm, 470);
    /* embedded NUL on line 2 */
    memcpy(buf, "fieldloc-calibration 1\nneck_height_mm 4\0" "70\n", 43);
    CHECK_EQ(fl_calib_parse(buf, 43, &c, &line, &why), FL_ERR_FORMAT);
    CHECK_EQ(line, 2);
    CHECK(strstr(why, "NUL") != NULL);
    /* the length bounds the parse: a NUL after len is never read */
    CHECK_EQ(fl_calib_parse(buf, 39, &c, &line, &why), FL_ERR_RANGE); /* "... 4" */
    CHECK_EQ(line, 2);
    /* whole text too long */
    memset(buf, '\n', sizeof buf);
    memcpy(buf, "fieldloc-calibration 1\n", 23);
    CHECK_EQ(fl_calib_parse(buf, FL_CALIB_TEXT_MAX, &c, &line, &why), FL_OK);
    CHECK_EQ(fl_calib_parse(buf, FL_CALIB_TEXT_MAX + 1, &c, &line, &why), FL_ERR_SIZE);
    CHECK_EQ(line, 0);
    /* NULL arguments */
    CHECK_EQ(fl_calib_parse(NULL, 5, &c, &line, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_calib_parse(buf, 5, NULL, NULL, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_calib_parse(NULL, 0, &c, NULL, NULL), FL_ERR_FORMAT);
    CHECK_EQ(fl_calib_apply(NULL, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_calib_format(NULL, buf, sizeof buf), 0u);
}

static void test_round_trip(void)
{
    char buf[FL_CALIB_TEXT_MAX];
    fl_calib_t c, d;
    int32_t a, line;
    size_t n;
    memset(&c, 0, sizeof c);
    c.has = FL_CALIB_HAS_CAMERA | FL_CALIB_HAS_NECK | FL_CALIB_HAS_PITCH | FL_CALIB_HAS_ROLL;
    strcpy(c.camera, "uva2013");
    c.neck_height_mm = 2000;
    /* every representable offset parses back to itself */
    for (a = -8192; a <= 8192; a++) {
        c.pitch_offset = (fl_angle_t)a;
        c.roll_offset = (fl_angle_t)-a;
        n = fl_calib_format(&c, buf, sizeof buf);
        if (n == 0 || n != strlen(buf) || fl_calib_parse(buf, n, &d, &line, NULL) != FL_OK ||
            memcmp(&c, &d, sizeof c) != 0) {
            t_fail_msg(__FILE__, __LINE__, "round trip of %d: '%s'", (int)a, buf);
            break;
        }
    }
    c.pitch_offset = -455;
    c.roll_offset = 0;
    n = fl_calib_format(&c, buf, sizeof buf);
    CHECK(strcmp(buf, "fieldloc-calibration 1\ncamera uva2013\nneck_height_mm 2000\n"
                      "pitch_offset_deg -2.499390\nroll_offset_deg 0.000000\n") == 0);
    /* too small a buffer, invalid values */
    CHECK_EQ(fl_calib_format(&c, buf, n), 0u);
    CHECK_EQ(buf[0], '\0');
    CHECK_EQ(fl_calib_format(&c, buf, n + 1), n);
    c.neck_height_mm = 10;
    CHECK_EQ(fl_calib_format(&c, buf, sizeof buf), 0u);
    c.neck_height_mm = 450;
    c.roll_offset = 8193;
    CHECK_EQ(fl_calib_format(&c, buf, sizeof buf), 0u);
    c.roll_offset = 0;
    memset(c.camera, 'a', sizeof c.camera); /* no NUL */
    CHECK_EQ(fl_calib_format(&c, buf, sizeof buf), 0u);
    /* only what is held is written */
    c.has = FL_CALIB_HAS_PITCH;
    CHECK(fl_calib_format(&c, buf, sizeof buf) > 0);
    CHECK(strcmp(buf, "fieldloc-calibration 1\npitch_offset_deg -2.499390\n") == 0);
}

static void test_apply(void)
{
    fl_calib_t c;
    fl_camera_pose_t pose;
    const char *txt = "fieldloc-calibration 1\nneck_height_mm 480\nroll_offset_deg 1\n";
    CHECK_EQ(parse_str(txt, &c, NULL), FL_OK);
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = 450;
    pose.head_pitch = 100;
    pose.head_yaw = -50;
    pose.pitch_offset = 33;
    CHECK_EQ(fl_calib_apply(&c, &pose), FL_OK);
    CHECK_EQ(pose.neck_height_mm, 480);
    CHECK_EQ(pose.pitch_offset, 33);    /* not held: unchanged */
    CHECK_EQ(pose.roll_offset, 182);    /* 1 deg = 182.04 units */
    CHECK_EQ(pose.head_pitch, 100);
    CHECK_EQ(pose.head_yaw, -50);
}

/* ---- the detection-driven fit ------------------------------------------------------ */

/* Frames rendered with a camera whose neck height, pitch offset and roll
 * differ from the model's defaults by known amounts. */
typedef struct {
    int32_t x, y, heading_deg, yaw_deg, pitch_deg;
} shot_t;

static const shot_t shots[] = {
    {-2500, 0, 0, 0, 18},      {-1500, 1500, -30, 10, 20}, {0, -1500, 90, -20, 16},
    {2000, 1000, 0, 0, 20},    {2500, -1500, 45, 15, 22},  {-3000, -2000, 150, 0, 18},
    {1000, 0, 180, -10, 16},   {-500, 2500, -90, 25, 20},  {3200, 2200, -30, -30, 24},
    {-1200, -800, -120, 0, 22},
};

/* Write the frames and a frames file (relative image paths) into dir;
 * neck / pitch / roll are the true offsets from the model defaults. */
static int render_set(const char *dir, const fl_field_t *field, const fl_camera_model_t *m,
                      int32_t dneck, double dpitch_deg, double roll_deg, int torso_deg,
                      int pose_err, char *list, size_t list_len)
{
    FILE *fp;
    size_t i;
    snprintf(list, list_len, "%s/frames.txt", dir);
    fp = fopen(list, "w");
    if (!fp)
        return -1;
    fprintf(fp, "# rendered: neck %+d mm, pitch offset %+.2f deg, roll %+.2f deg\n", (int)dneck,
            dpitch_deg, roll_deg);
    for (i = 0; i < sizeof shots / sizeof shots[0]; i++) {
        render_scene_t sc;
        render_frame_t fr;
        char path[600];
        render_scene_default(&sc, field, m);
        sc.robot_x_mm = shots[i].x;
        sc.robot_y_mm = shots[i].y;
        sc.robot_heading = fl_angle_from_mdeg(shots[i].heading_deg * 1000);
        sc.head.head_yaw = fl_angle_from_mdeg(shots[i].yaw_deg * 1000);
        sc.head.head_pitch = fl_angle_from_mdeg(shots[i].pitch_deg * 1000);
        sc.head.neck_height_mm += dneck;
        sc.head.pitch_offset = (fl_angle_t)(sc.head.pitch_offset +
                                            fl_angle_from_mdeg((int32_t)lround(dpitch_deg * 1000)));
        sc.head.roll_offset = fl_angle_from_mdeg((int32_t)lround(roll_deg * 1000));
        /* torso lean (IMU), alternating in sign from frame to frame */
        sc.head.torso_pitch = fl_angle_from_mdeg((int32_t)(i % 2 ? torso_deg : -torso_deg) * 1000);
        sc.head.torso_roll = fl_angle_from_mdeg((int32_t)(i % 3 ? -torso_deg : torso_deg) * 1000);
        sc.seed = (uint32_t)(i + 11);
        snprintf(path, sizeof path, "%s/f%02d.ppm", dir, (int)i);
        if (render_frame(&sc, &fr) != 0) {
            fclose(fp);
            return -1;
        }
        if (render_write_frame(path, &fr) != 0) {
            render_frame_free(&fr);
            fclose(fp);
            return -1;
        }
        render_frame_free(&fr);
        /* the file's head angles: NAOqi degrees as the robot reports them */
        /* pose_err: the file's pose off by up to pose_err mm and pose_err / 20
         * deg, as when a robot is put down by hand */
        fprintf(fp, "f%02d.ppm %d %d %g %d %d", (int)i,
                (int)shots[i].x + (int)(i % 3 == 0 ? pose_err : -pose_err / 2),
                (int)shots[i].y + (int)(i % 2 == 0 ? -pose_err : pose_err / 3),
                shots[i].heading_deg + (i % 2 == 0 ? 1.0 : -0.7) * pose_err / 20.0,
                (int)shots[i].yaw_deg, (int)shots[i].pitch_deg);
        if (torso_deg != 0)
            fprintf(fp, " %d %d", i % 2 ? torso_deg : -torso_deg, i % 3 ? -torso_deg : torso_deg);
        fprintf(fp, "\n");
    }
    return fclose(fp) == 0 ? 0 : -1;
}

static void rm_set(const char *dir)
{
    size_t i;
    char path[600];
    for (i = 0; i < sizeof shots / sizeof shots[0]; i++) {
        snprintf(path, sizeof path, "%s/f%02d.ppm", dir, (int)i);
        remove(path);
    }
    snprintf(path, sizeof path, "%s/frames.txt", dir);
    remove(path);
    rmdir(dir);
}

/* Render a set with the given true offsets (from the defaults of
 * nao4-top-320 on spl2013), fit from the defaults, check the recovery.
 * Tolerances 10 mm and 0.3 deg: what a robot needs (0.3 deg is 1.4 px at
 * the 272 px focal length, 10 mm of neck about 2 % of every range), and
 * some 30 times the fitted 1-sigma on these frames (the log line prints
 * both), so a wrong model or a biased residual fails while the detector's
 * noise does not. */
static void fit_case(int32_t dneck, double dpitch, double roll, int torso_deg, int pose_err)
{
    const fl_field_t *field = fl_field_find("spl2013");
    const fl_camera_model_t *m = fl_camera_model_find("nao4-top-320");
    char dir[] = "/tmp/fl_calib_XXXXXX", list[700], err[512];
    cf_frames_t fr;
    cf_options_t o;
    cf_params_t p, truth;
    cf_result_t res;
    CHECK(field != NULL && m != NULL);
    if (!field || !m || !mkdtemp(dir)) {
        CHECK(0);
        return;
    }
    if (render_set(dir, field, m, dneck, dpitch, roll, torso_deg, pose_err, list, sizeof list) !=
        0) {
        CHECK(0);
        rm_set(dir);
        return;
    }
    CHECK_EQ(cf_frames_load(list, &fr, err, sizeof err), 0);
    CHECK_EQ(fr.n, (int)(sizeof shots / sizeof shots[0]));
    truth.neck_mm = m->default_neck_height_mm + dneck;
    truth.pitch_offset_deg = m->default_pitch_offset * 360.0 / 65536.0 + dpitch;
    truth.roll_offset_deg = roll;
    p.neck_mm = m->default_neck_height_mm;
    p.pitch_offset_deg = m->default_pitch_offset * 360.0 / 65536.0;
    p.roll_offset_deg = 0;
    cf_options_default(&o);
    o.fit_heading = pose_err != 0;
    if (cf_fit(&fr, field, m, &o, &p, &res, NULL, NULL, err, sizeof err) != 0) {
        t_fail_msg(__FILE__, __LINE__, "fit failed: %s", err);
    } else {
        t_info("torso +-%d deg, pose errors %d mm; true neck %.0f pitch %.3f roll %.3f; fitted %.1f +- %.1f mm, "
               "%.3f +- %.3f deg, %.3f +- %.3f deg; %d points, in %d -> %d, median %.2f -> "
               "%.2f px",
               torso_deg, pose_err, truth.neck_mm, truth.pitch_offset_deg, truth.roll_offset_deg,
               p.neck_mm, res.sigma[0], p.pitch_offset_deg, res.sigma[1], p.roll_offset_deg,
               res.sigma[2], res.after_all.n_points, res.before_all.n_in, res.after_all.n_in,
               res.before_all.median_px, res.after_all.median_px);
        CHECK_EQ(res.n_frames, fr.n);
        CHECK(fabs(p.neck_mm - truth.neck_mm) <= 10.0);
        CHECK(fabs(p.pitch_offset_deg - truth.pitch_offset_deg) <= 0.3);
        CHECK(fabs(p.roll_offset_deg - truth.roll_offset_deg) <= 0.3);
        CHECK(res.after_all.n_in > res.before_all.n_in);
        CHECK(res.after_all.median_px < 1.0);
        cf_result_free(&res);
    }
    cf_frames_free(&fr);
    rm_set(dir);
}

static void test_fit_recovers(void) { fit_case(35, 2.5, 1.5, 0, 0); }

/* The other signs, with the IMU's torso angles in the frames file (the
 * fit must not absorb them into the offsets). */
static void test_fit_recovers_torso(void) { fit_case(-40, -3.0, -2.0, 3, 0); }

/* Poses in the file off by up to 60 mm and 3 deg, refitted per frame
 * (fit_heading): the camera must still come out. */
static void test_fit_pose_errors(void) { fit_case(25, 1.5, -1.0, 0, 60); }

static void test_frames_errors(void)
{
    static const struct {
        const char *text;
        int line;
        const char *why;
    } cases[] = {
        {"a.ppm 0 0 0 0 20\n\nb.ppm 0 0 0 0\n", 3, "expected: IMAGE"},
        {"# c\na.ppm 0 0 0 0 20 1\n", 2, "expected: IMAGE"},
        {"a.ppm 0 0 0 0 20 1 2 3\n", 1, "expected: IMAGE"},
        {"a.ppm 0 0 0 0 20\nb.ppm 0 1e9 0 0 20\n", 2, "Y_MM: out of range"},
        {"a.ppm 0 0 0 0 20x\n", 1, "HEAD_PITCH_DEG: not a number"},
        {"a.ppm 0 0 nan 0 20\n", 1, "HEADING_DEG: out of range"},
        {"a.ppm 0 0 0 0 20 0 inf\n", 1, "TORSO_ROLL_DEG: out of range"},
        {"# nothing\n\n", 2, "no frame"},
    };
    size_t i;
    char err[512];
    cf_frames_t fr;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char want[64];
        int rc = cf_frames_parse(cases[i].text, strlen(cases[i].text), "F.txt", "d", &fr, err,
                                 sizeof err);
        snprintf(want, sizeof want, "F.txt:%d: %s", cases[i].line, cases[i].why);
        if (rc != -1 || strncmp(err, want, strlen(want)) != 0)
            t_fail_msg(__FILE__, __LINE__, "case %u: rc %d '%s', want '%s...'", (unsigned)i, rc,
                       err, want);
        CHECK(fr.n == 0 && fr.f == NULL);
    }
    /* embedded NUL, overlong line */
    {
        char buf[CF_LINE_MAX + 64];
        memcpy(buf, "a.ppm 0 0 0 0 20\nb.ppm\0 0 0 0 0 20\n", 36);
        CHECK_EQ(cf_frames_parse(buf, 36, "F.txt", NULL, &fr, err, sizeof err), -1);
        CHECK(strcmp(err, "F.txt:2: NUL byte") == 0);
        memset(buf, ' ', sizeof buf);
        memcpy(buf, "a.ppm 0 0 0 0 20\n", 17);
        CHECK_EQ(cf_frames_parse(buf, sizeof buf, "F.txt", NULL, &fr, err, sizeof err), -1);
        CHECK(strcmp(err, "F.txt:2: line too long") == 0);
    }
    /* a good one: relative paths get the folder, absolute ones not */
    {
        const char *good = "a.ppm -1.5 2 +3 4 5 # c\n/x/b.ppm 0 0 0 0 20 -1 2.5";
        CHECK_EQ(cf_frames_parse(good, strlen(good), "F.txt", "dir", &fr, err, sizeof err), 0);
    }
    CHECK_EQ(fr.n, 2);
    if (fr.n == 2) {
        CHECK(strcmp(fr.f[0].image, "dir/a.ppm") == 0);
        CHECK(strcmp(fr.f[1].image, "/x/b.ppm") == 0);
        CHECK(fr.f[0].x_mm == -1.5 && fr.f[0].heading_deg == 3 && fr.f[0].head_yaw_deg == 4 &&
              fr.f[0].head_pitch_deg == 5 && fr.f[0].torso_pitch_deg == 0);
        CHECK(fr.f[1].torso_pitch_deg == -1 && fr.f[1].torso_roll_deg == 2.5);
        CHECK_EQ(fr.f[1].line, 2);
    }
    cf_frames_free(&fr);
    /* CRLF line ends (a list written on Windows): the same frames */
    {
        const char *crlf = "a.ppm -1.5 2 +3 4 5\r\n# c\r\nb.ppm 0 0 0 0 20 -1 2.5\r\n";
        CHECK_EQ(cf_frames_parse(crlf, strlen(crlf), "F.txt", NULL, &fr, err, sizeof err), 0);
        CHECK_EQ(fr.n, 2);
        if (fr.n == 2)
            CHECK(fr.f[0].head_pitch_deg == 5 && fr.f[1].torso_roll_deg == 2.5 &&
                  fr.f[1].line == 3 && strcmp(fr.f[1].image, "b.ppm") == 0);
        cf_frames_free(&fr);
    }
    /* a missing file */
    CHECK_EQ(cf_frames_load("/nonexistent/frames.txt", &fr, err, sizeof err), -1);
    CHECK(strstr(err, "/nonexistent/frames.txt") != NULL);
}

void suite_calib(void)
{
    t_run("calib.good", test_good);
    t_run("calib.malformed", test_malformed);
    t_run("calib.limits", test_limits);
    t_run("calib.round_trip", test_round_trip);
    t_run("calib.apply", test_apply);
    t_run("calib.frames_errors", test_frames_errors);
    t_run("calib.fit_recovers", test_fit_recovers);
    t_run("calib.fit_recovers_torso", test_fit_recovers_torso);
    t_run("calib.fit_pose_errors", test_fit_pose_errors);
}
