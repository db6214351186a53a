/*
 * host_tests/test_realdata.c - the real-data loader (tools/io/realdata.c) and
 * the UvA 2013 camera calibration (tools/eval/calibrate.c, camera "uva2013" in
 * src/model/camera.c).
 *
 * Always run (synthetic content written to build/):
 *  - CSV parsing of UvA-style and physar-style text: comments, quotes, CRLF,
 *    1-based -> 0-based labels, every malformed-row error path;
 *  - PPM round trip through rd_read_ppm and rd_image_view;
 *  - folder lookup through $FIELDLOC_REALDATA and the skip message;
 *  - pose helpers;
 *  - calibration on synthetic labels: a camera that differs from the
 *    nominal one (neck 470 mm, pitch offset 4 deg, focal 280 px) projects
 *    the uva2013 map through the FIRMWARE projection from 12 poses; the
 *    file poses then get heading errors of up to 3 deg and x/y errors up to
 *    50 mm, labels +-0.5 px of noise; the fit (starting from the nominal
 *    camera) must recover neck within 10 mm, pitch offset within 0.25 deg
 *    and focal within 3 px (measured errors printed as # lines).
 * With ../shared/realdata (t_realdata_dir(); otherwise a "# skipped: ..."
 * line and the cases pass):
 *  - uva2013_annotations.csv: 24 rows, 151 labels, every row re-checked
 *    against an independent sscanf of its raw line; every PPM 320x240;
 *  - physar_poses.csv: 5 rows, their PPMs 640x480;
 *  - the committed camera uva2013 with its default pose and each image's
 *    head angles, through fl_camera_ground_to_pixel, nearest map point of
 *    the label's kind (X/L/T/G): median residual <= 8.5 px with the
 *    file-name poses (measured 8.2, dominated by pose errors) and <= 5.5 px
 *    after a per-image heading-only search (+-10 deg, the camera
 *    untouched; measured 5.0: x/y stay as given, unlike `fieldloc
 *    calibrate`'s pose-corrected 3.3 px);
 *  - cal_fit reproduces the committed values (neck within 2 mm, pitch
 *    offset within 0.05 deg, focal within 0.25 px): the catalogue is not
 *    stale.
 * Quick mode (qemu): identical cases (a fit costs ~0.15 s natively).
 * Digests: the integer firmware projections of the synthetic sweep, and of
 * every real label's nearest map point (real data only).
 */
#include "test.h"

#include "eval/calibrate.h"
#include "eval/colors_opt.h"
#include "eval/detect.h"
#include "fieldloc/fieldloc.h"
#include "io/realdata.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define PI_D 3.14159265358979323846

static const char *tmp_dir(void)
{
    mkdir("build", 0777);
    mkdir("build/test_realdata", 0777);
    return "build/test_realdata";
}

/* ---- CSV parsing ------------------------------------------------------- */

static const char *uva_text =
    "# a comment, with commas\r\n"
    "# another\n"
    "file,in_realdata,set,index,x_cm,y_cm,theta_deg,head_pitch_rad,head_yaw_rad,n_features,"
    "features\r\n"
    "a_000001.ppm,1,qvga,000001,0,0,0,-0.541544,0.001492,3,\"X:162,156 L:36,98 U:91,11\"\r\n"
    "\n"
    "b_000002.ppm,0,triwalk,000002,-300,12.5,33.6,-0.549214,-0.004644,0,\"\"\n"
    "c_000003.ppm,1,qvga,000003,295,-201,-135,-0.5,0.25,2,\"G:1,1  T:320,240\"";

static void t_uva_parse(void)
{
    rd_uva_set_t s;
    char err[200];
    CHECK_EQ(rd_uva_parse(uva_text, &s, err, sizeof err), 0);
    CHECK_EQ(s.n, 3);
    if (s.n != 3)
        return;
    CHECK(strcmp(s.rec[0].file, "a_000001.ppm") == 0);
    CHECK(strcmp(s.rec[0].set, "qvga") == 0);
    CHECK(strcmp(s.rec[0].index, "000001") == 0);
    CHECK_EQ(s.rec[0].in_realdata, 1);
    CHECK_EQ(s.rec[0].n_features, 3);
    CHECK_EQ(s.rec[0].feat[0].type, 'X');
    CHECK(s.rec[0].feat[0].u == 161.0 && s.rec[0].feat[0].v == 155.0);
    CHECK_EQ(s.rec[0].feat[1].type, 'L');
    CHECK(s.rec[0].feat[1].u == 35.0 && s.rec[0].feat[1].v == 97.0);
    CHECK_EQ(s.rec[0].feat[2].type, 'U');
    CHECK(s.rec[0].head_pitch_rad == -0.541544 && s.rec[0].head_yaw_rad == 0.001492);
    CHECK_EQ(s.rec[1].in_realdata, 0);
    CHECK_EQ(s.rec[1].n_features, 0);
    CHECK(s.rec[1].x_cm == -300 && s.rec[1].y_cm == 12.5 && s.rec[1].theta_deg == 33.6);
    CHECK(strcmp(s.rec[1].set, "triwalk") == 0);
    /* last row: no final newline, labels at the image corners */
    CHECK_EQ(s.rec[2].n_features, 2);
    CHECK(s.rec[2].feat[0].type == 'G' && s.rec[2].feat[0].u == 0 && s.rec[2].feat[0].v == 0);
    CHECK(s.rec[2].feat[1].type == 'T' && s.rec[2].feat[1].u == 319 &&
          s.rec[2].feat[1].v == 239);
    CHECK(s.rec[2].y_cm == -201 && s.rec[2].theta_deg == -135 && s.rec[2].head_yaw_rad == 0.25);
    rd_uva_free(&s);
    CHECK(s.rec == NULL && s.n == 0);
}

static void t_uva_errors(void)
{
    static const char *hdr =
        "file,in_realdata,set,index,x_cm,y_cm,theta_deg,head_pitch_rad,head_yaw_rad,"
        "n_features,features\n";
    static const char *bad_rows[] = {
        "a.ppm,1,qvga,1,0,0,0,-0.5,0,2,\"X:1,2\"\n",          /* count mismatch */
        "a.ppm,1,qvga,1,0,zero,0,-0.5,0,1,\"X:1,2\"\n",       /* bad number */
        "a.ppm,1,qvga,1,0,0,0,-0.5,0,1,\"Q:1,2\"\n",          /* bad type */
        "a.ppm,1,qvga,1,0,0,0,-0.5,0,1,\"X:1;2\"\n",          /* bad pair */
        "a.ppm,1,qvga,1,0,0,0,-0.5,0,1,X:1,2\n",              /* unquoted: 12 fields */
        "a.ppm,1,qvga,1,0,0,0,-0.5,0,1,\"X:1,2\n",            /* open quote */
        ",1,qvga,1,0,0,0,-0.5,0,0,\"\"\n",                    /* empty name */
        "a.ppm,1,qvga,1,0,0,0,-0.5,0\n",                      /* too few fields */
    };
    char text[1024], err[200];
    rd_uva_set_t s;
    size_t i;
    for (i = 0; i < sizeof bad_rows / sizeof bad_rows[0]; i++) {
        snprintf(text, sizeof text, "%s%s", hdr, bad_rows[i]);
        err[0] = '\0';
        CHECK_EQ(rd_uva_parse(text, &s, err, sizeof err), -1);
        CHECK(s.rec == NULL && s.n == 0);
        CHECK(strstr(err, "line 2") != NULL);
    }
    /* missing column, empty text, NULLs */
    CHECK_EQ(rd_uva_parse("file,set\na,b\n", &s, err, sizeof err), -1);
    CHECK(strstr(err, "in_realdata") != NULL);
    CHECK_EQ(rd_uva_parse("# only a comment\n", &s, err, sizeof err), -1);
    CHECK_EQ(rd_uva_parse(NULL, &s, NULL, 0), -1);
    CHECK_EQ(rd_uva_parse(hdr, NULL, NULL, 0), -1);
    /* header only: zero records, success */
    CHECK_EQ(rd_uva_parse(hdr, &s, err, sizeof err), 0);
    CHECK_EQ(s.n, 0);
    rd_uva_free(&s);
    rd_uva_free(NULL);
}

static void t_uva_load_file(void)
{
    char path[256], err[200];
    FILE *f;
    rd_uva_set_t s;
    const char *text =
        "file,in_realdata,set,index,x_cm,y_cm,theta_deg,head_pitch_rad,head_yaw_rad,n_features,"
        "features\n"
        "x.ppm,1,straightwalk,000009,-120,0,0,-0.546146,0.003026,2,\"X:23,156 G:110,80\"\n";
    snprintf(path, sizeof path, "%s/uva.csv", tmp_dir());
    f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f)
        return;
    fputs(text, f);
    fclose(f);
    CHECK_EQ(rd_uva_load(path, &s, err, sizeof err), 0);
    CHECK_EQ(s.n, 1);
    if (s.n == 1) {
        CHECK_EQ(s.rec[0].n_features, 2);
        CHECK(s.rec[0].feat[1].type == 'G' && s.rec[0].feat[1].u == 109 &&
              s.rec[0].feat[1].v == 79);
    }
    rd_uva_free(&s);
    CHECK_EQ(rd_uva_load("build/test_realdata/no_such.csv", &s, err, sizeof err), -1);
    CHECK(strstr(err, "no_such.csv") != NULL);
}

static void t_physar_parse(void)
{
    const char *text =
        "# comment, with, commas\n"
        "image_top,image_bottom,point,nominal_x_cm,nominal_y_cm,nominal_heading_deg,ot_frame,"
        "ot_field_x_cm,ot_field_y_cm,ot_height_m,ot_rotX,ot_rotY,ot_rotZ,head_pitch_rad,"
        "head_yaw_rad,imu_anglex_rad,imu_angley_rad\n"
        "t1.ppm,,p1,130,120,-135,1152,129.6,121.7,0.460,-8.1,-6.1,-5.5,0.1257,0.0552,-0.0186,"
        "-0.0627\n"
        "t2.ppm,b2.ppm,p2,270,0,-180,1680,279.1,-0.3,0.472,-23.3,-43.7,-28.6,0.0306,0.0521,"
        "-0.0004,-0.1615\n";
    rd_physar_set_t s;
    char err[200];
    CHECK_EQ(rd_physar_parse(text, &s, err, sizeof err), 0);
    CHECK_EQ(s.n, 2);
    if (s.n == 2) {
        CHECK(strcmp(s.rec[0].image_top, "t1.ppm") == 0 && s.rec[0].image_bottom[0] == '\0');
        CHECK(strcmp(s.rec[1].image_bottom, "b2.ppm") == 0);
        CHECK(strcmp(s.rec[0].point, "p1") == 0);
        CHECK_EQ(s.rec[0].ot_frame, 1152);
        CHECK(s.rec[0].ot_field_x_cm == 129.6 && s.rec[0].ot_field_y_cm == 121.7);
        CHECK(s.rec[1].nominal_heading_deg == -180 && s.rec[1].ot_height_m == 0.472);
        CHECK(s.rec[1].ot_rot_deg[2] == -28.6 && s.rec[1].imu_angley_rad == -0.1615);
        CHECK(s.rec[0].head_pitch_rad == 0.1257 && s.rec[0].head_yaw_rad == 0.0552);
    }
    rd_physar_free(&s);
    CHECK_EQ(rd_physar_parse("image_top,point\nx,y\n", &s, err, sizeof err), -1);
    CHECK(strstr(err, "image_bottom") != NULL);
}

/* ---- PPM, folder, poses ----------------------------------------------------- */

static void t_ppm(void)
{
    uint8_t rgb[6 * 4 * 3];
    host_image_t img;
    fl_image_t view;
    char path[256], err[200];
    uint8_t px[3];
    int i;
    for (i = 0; i < (int)sizeof rgb; i++)
        rgb[i] = (uint8_t)(i * 7 + 3);
    snprintf(path, sizeof path, "%s/tiny.ppm", tmp_dir());
    CHECK_EQ(ppm_write(path, rgb, 6, 4), 0);
    CHECK_EQ(rd_read_ppm(tmp_dir(), "tiny.ppm", &img, err, sizeof err), 0);
    CHECK(img.rgb != NULL && img.width == 6 && img.height == 4);
    if (!img.rgb)
        return;
    CHECK(memcmp(img.rgb, rgb, sizeof rgb) == 0);
    CHECK_EQ(rd_image_view(&img, &view), FL_OK);
    CHECK(fl_image_get_rgb(&view, 5, 3, px));
    CHECK(memcmp(px, &rgb[(3 * 6 + 5) * 3], 3) == 0);
    CHECK(!fl_image_get_rgb(&view, 6, 3, px));
    host_image_free(&img);
    CHECK_EQ(rd_read_ppm(tmp_dir(), "missing.ppm", &img, err, sizeof err), -1);
    CHECK(img.rgb == NULL);
    CHECK(rd_image_view(NULL, &view) != FL_OK);
}

static void t_dir(void)
{
    const char *saved = getenv("FIELDLOC_REALDATA");
    char keep[1024] = "";
    char path[16];
    int had = saved != NULL;
    if (had)
        snprintf(keep, sizeof keep, "%s", saved);
    setenv("FIELDLOC_REALDATA", "build/test_realdata/does_not_exist", 1);
    CHECK(rd_dir() == NULL);
    tmp_dir();
    setenv("FIELDLOC_REALDATA", "build/test_realdata", 1);
    CHECK(rd_dir() != NULL && strcmp(rd_dir(), "build/test_realdata") == 0);
    if (had)
        setenv("FIELDLOC_REALDATA", keep, 1);
    else
        unsetenv("FIELDLOC_REALDATA");
    CHECK(strncmp(rd_skip_message(), "skipped: ../shared/realdata not found", 37) == 0);
    if (t_realdata_dir())
        CHECK(rd_dir() != NULL);
    CHECK_EQ(rd_path(path, sizeof path, "abc", "def.ppm"), 0);
    CHECK(strcmp(path, "abc/def.ppm") == 0);
    CHECK_EQ(rd_path(path, sizeof path, "abcdefgh", "def.ppm"), -1);
}

static void t_pose(void)
{
    rd_uva_record_t r;
    int32_t x, y;
    fl_angle_t h;
    double rx, ry;
    fl_camera_pose_t cp;
    const fl_camera_model_t *m = fl_camera_model_find("uva2013");
    memset(&r, 0, sizeof r);
    r.x_cm = -86;
    r.y_cm = 143.4;
    r.theta_deg = 33.6;
    r.head_pitch_rad = -0.549214;
    r.head_yaw_rad = 0.001492;
    rd_uva_pose(&r, &x, &y, &h);
    CHECK_EQ(x, -860);
    CHECK_EQ(y, 1434);
    CHECK_EQ(h, 6117); /* 33.6 / 360 * 65536 = 6116.7 */
    r.theta_deg = -135;
    rd_uva_pose(&r, NULL, NULL, &h);
    CHECK_EQ(h, -24576);
    r.theta_deg = 180;
    rd_uva_pose(&r, NULL, NULL, &h);
    CHECK_EQ(h, -32768);
    /* field -> robot: robot at (-860, 1434) facing +y (90 deg) */
    r.theta_deg = 90;
    rd_uva_field_to_robot(&r, -860, 2434, &rx, &ry);
    CHECK(fabs(rx - 1000) < 1e-9 && fabs(ry) < 1e-9);
    rd_uva_field_to_robot(&r, -1860, 1434, &rx, &ry);
    CHECK(fabs(rx) < 1e-9 && fabs(ry - 1000) < 1e-9);
    CHECK(m != NULL);
    if (!m)
        return;
    rd_uva_camera_pose(&r, m, &cp);
    CHECK_EQ(cp.neck_height_mm, m->default_neck_height_mm);
    CHECK_EQ(cp.pitch_offset, m->default_pitch_offset);
    CHECK_EQ(cp.head_pitch, -5729); /* -0.549214 rad = -5728.51 */
    CHECK_EQ(cp.head_yaw, 16);      /* 0.001492 rad = 15.6 */
}

/* ---- calibration on synthetic labels ------------------------------------------ */

static char lm_type(fl_landmark_kind_t k)
{
    switch (k) {
    case FL_LM_L: return 'L';
    case FL_LM_T: return 'T';
    case FL_LM_X: case FL_LM_PENALTY_MARK: case FL_LM_CENTRE_MARK: return 'X';
    case FL_LM_POST: return 'G';
    default: return 0;
    }
}

/* Firmware projection of every X/L/T/G map point of f seen by camera model
 * m (pose: neck, pitch offset; head angles of rec) from the robot pose
 * (x_mm, y_mm, th_rad); labels into rec (0-based px, Q4 / 16 + noise).
 * Posts: the point of the post surface toward the robot.  Returns the
 * number of labels; *h accumulates the integer projections. */
static int synth_labels(const fl_field_t *f, const fl_camera_model_t *m, int32_t neck,
                        fl_angle_t poff, double x_mm, double y_mm, double th,
                        rd_uva_record_t *rec, t_rng_t *rng, uint32_t *h)
{
    fl_camera_pose_t pose;
    fl_camera_t cam;
    uint16_t i;
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = neck;
    pose.head_pitch = fl_angle_from_urad((int32_t)lround(rec->head_pitch_rad * 1e6));
    pose.head_yaw = fl_angle_from_urad((int32_t)lround(rec->head_yaw_rad * 1e6));
    pose.pitch_offset = poff;
    rec->n_features = 0;
    if (fl_camera_init(&cam, m, &pose) != FL_OK)
        return 0;
    for (i = 0; i < f->n_landmarks && rec->n_features < RD_MAX_FEATURES; i++) {
        const fl_landmark_t *l = &f->landmarks[i];
        char t = lm_type(l->kind);
        double dx = l->x_mm - x_mm, dy = l->y_mm - y_mm;
        double rx = cos(th) * dx + sin(th) * dy, ry = -sin(th) * dx + cos(th) * dy;
        fl_point_t g;
        int32_t uq, vq;
        if (!t)
            continue;
        if (t == 'G') {
            double d = hypot(rx, ry);
            rx -= rx / d * f->post_diameter_mm / 2.0;
            ry -= ry / d * f->post_diameter_mm / 2.0;
        }
        g.x_mm = (int32_t)lround(rx);
        g.y_mm = (int32_t)lround(ry);
        if (!fl_camera_ground_to_pixel(&cam, g, &uq, &vq))
            continue;
        *h = t_hash_i32(*h, uq);
        *h = t_hash_i32(*h, vq);
        if (uq < 0 || vq < 0 || uq > 16 * 319 || vq > 16 * 239)
            continue;
        rec->feat[rec->n_features].type = t;
        rec->feat[rec->n_features].u = uq / 16.0 + t_rng_range(rng, -8, 8) / 16.0;
        rec->feat[rec->n_features].v = vq / 16.0 + t_rng_range(rng, -8, 8) / 16.0;
        rec->n_features++;
    }
    return rec->n_features;
}

static void t_calibrate_synthetic(void)
{
    /* poses like the dataset's (cm, deg) */
    static const double poses[][3] = {
        {0, 0, 0},      {0, 60, 180},    {0, 201, -45},  {295, 201, 180},
        {235, 111, 180}, {115, 0, 0},    {-280, 0, 0},   {-120, 0, 0},
        {-300, 0, 33.6}, {66, 156, -33.6}, {0, 201, -135}, {115, 0, -135}};
    const int np = (int)(sizeof poses / sizeof poses[0]);
    const fl_field_t *f = fl_field_find("uva2013");
    const fl_camera_model_t *nominal = fl_camera_model_find("nao4-bottom-320");
    fl_camera_model_t truth;
    rd_uva_set_t set;
    cal_problem_t pb;
    cal_options_t o;
    cal_params_t p;
    cal_result_t res;
    t_rng_t rng;
    uint32_t h = t_hash_init();
    int i, n = 0;
    const fl_angle_t poff = 728; /* 4.0 deg */
    double e_neck, e_pitch, e_f;

    CHECK(f != NULL && nominal != NULL);
    if (!f || !nominal)
        return;
    truth = *nominal;
    truth.focal_q4 = 280 * 16;
    t_rng_seed(&rng, 2013);
    set.n = np;
    set.rec = calloc((size_t)np, sizeof *set.rec);
    CHECK(set.rec != NULL);
    if (!set.rec)
        return;
    for (i = 0; i < np; i++) {
        rd_uva_record_t *r = &set.rec[i];
        double th = poses[i][2] * PI_D / 180.0;
        snprintf(r->file, sizeof r->file, "synthetic_%02d.ppm", i);
        snprintf(r->set, sizeof r->set, "synthetic");
        snprintf(r->index, sizeof r->index, "%06d", i);
        r->head_pitch_rad = -0.545 + t_rng_range(&rng, -50, 50) * 1e-4;
        r->head_yaw_rad = t_rng_range(&rng, -100, 100) * 1e-4;
        n += synth_labels(f, &truth, 470, poff, poses[i][0] * 10, poses[i][1] * 10, th, r,
                          &rng, &h);
        /* the "file pose" is off: heading up to 3 deg, x/y up to 50 mm */
        r->x_cm = poses[i][0] + t_rng_range(&rng, -50, 50) / 10.0;
        r->y_cm = poses[i][1] + t_rng_range(&rng, -50, 50) / 10.0;
        r->theta_deg = poses[i][2] + t_rng_range(&rng, -30, 30) / 10.0;
    }
    t_digest("realdata.synthetic_projections", h);
    t_info("synthetic calibration: %d images, %d labels", np, n);
    CHECK(n >= 60);
    CHECK_EQ(cal_problem_init(&pb, &set, f), 0);
    cal_options_default(&o);
    o.fit_mask = CAL_FIT_BASE;
    o.pose_mask = CAL_FIT_POSE_HEADING | CAL_FIT_POSE_XY;
    cal_params_init(&p, nominal, f); /* start: 445 mm, 0 deg, 272.2 px */
    CHECK_EQ(cal_fit(&pb, &o, &p, &res), 0);
    e_neck = p.p[CAL_NECK] - 470.0;
    e_pitch = (p.p[CAL_PITCH] - poff * 2 * PI_D / 65536.0) * 180.0 / PI_D;
    e_f = p.p[CAL_FOCAL] - 280.0;
    t_info("synthetic fit: neck %+.2f mm, pitch offset %+.3f deg, focal %+.2f px off; "
           "sigma %.1f mm %.3f deg %.2f px; %d used, %d outliers, rms %.2f px",
           e_neck, e_pitch, e_f, res.sigma[CAL_NECK], res.sigma[CAL_PITCH] * 180 / PI_D,
           res.sigma[CAL_FOCAL], res.n_used, res.n_outliers, res.rms_px);
    CHECK_LE(fabs(e_neck), 10.0);
    CHECK_LE(fabs(e_pitch), 0.25);
    CHECK_LE(fabs(e_f), 3.0);
    CHECK_LE(res.n_outliers + res.n_unmatched, n / 20);
    /* without pose corrections the heading errors must hurt (else the
     * synthetic poses are not off at all and the case proves nothing) */
    o.pose_mask = 0;
    cal_params_init(&p, nominal, f);
    CHECK_EQ(cal_fit(&pb, &o, &p, &res), 0);
    t_info("synthetic fit on the perturbed poses without pose corrections: rms %.2f px, %d "
           "outliers",
           res.rms_px, res.n_outliers);
    CHECK(res.rms_px > 1.5 || res.n_outliers > 0);
    cal_problem_free(&pb);
    free(set.rec);
}

/* ---- real data ------------------------------------------------------------------- */

static int skip_if_absent(void)
{
    if (t_realdata_dir())
        return 0;
    t_info("%s", rd_skip_message());
    return 1;
}

static void t_real_uva(void)
{
    const char *dir;
    char path[1024], err[200], *text = NULL;
    rd_uva_set_t s;
    int i, k, total = 0, counts[5] = {0};
    FILE *f;
    long len;
    if (skip_if_absent())
        return;
    dir = t_realdata_dir();
    CHECK_EQ(rd_path(path, sizeof path, dir, RD_UVA_CSV), 0);
    CHECK_EQ(rd_uva_load(path, &s, err, sizeof err), 0);
    t_info("%s: %d rows", path, s.n);
    CHECK_EQ(s.n, 24);
    /* independent re-read of the raw lines */
    f = fopen(path, "rb");
    CHECK(f != NULL);
    if (f) {
        fseek(f, 0, SEEK_END);
        len = ftell(f);
        fseek(f, 0, SEEK_SET);
        text = calloc((size_t)len + 1, 1);
        if (text && fread(text, 1, (size_t)len, f) != (size_t)len) {
            free(text);
            text = NULL;
        }
        fclose(f);
    }
    CHECK(text != NULL);
    for (i = 0; i < s.n && text; i++) {
        const rd_uva_record_t *r = &s.rec[i];
        const char *line = strstr(text, r->file), *q;
        double x, y, th, hp, hy;
        int nf, colons = 0, u1, v1;
        char t1;
        host_image_t img;
        CHECK(line != NULL);
        if (!line)
            continue;
        q = line;
        for (k = 0; k < 4; k++) /* skip file, in_realdata, set, index */
            q = strchr(q, ',') + 1;
        CHECK_EQ(sscanf(q, "%lf,%lf,%lf,%lf,%lf,%d", &x, &y, &th, &hp, &hy, &nf), 6);
        CHECK(x == r->x_cm && y == r->y_cm && th == r->theta_deg);
        CHECK(hp == r->head_pitch_rad && hy == r->head_yaw_rad);
        CHECK_EQ(nf, r->n_features);
        q = strchr(q, '"');
        CHECK(q != NULL);
        if (!q)
            continue;
        for (k = 1; q[k] && q[k] != '"'; k++)
            colons += q[k] == ':';
        CHECK_EQ(colons, r->n_features);
        if (r->n_features > 0) {
            CHECK_EQ(sscanf(q + 1, "%c:%d,%d", &t1, &u1, &v1), 3);
            CHECK(t1 == r->feat[0].type && u1 - 1 == r->feat[0].u && v1 - 1 == r->feat[0].v);
        }
        for (k = 0; k < r->n_features; k++) {
            counts[strchr("XLTGU", r->feat[k].type) - "XLTGU"]++;
            CHECK(r->feat[k].u >= -1 && r->feat[k].u <= 320 && r->feat[k].v >= -1 &&
                  r->feat[k].v <= 240);
        }
        total += r->n_features;
        CHECK_EQ(r->in_realdata, 1);
        CHECK(r->theta_deg >= -180 && r->theta_deg <= 180 && fabs(r->x_cm) <= 350 &&
              fabs(r->y_cm) <= 250);
        CHECK(r->head_pitch_rad > -0.6 && r->head_pitch_rad < -0.5);
        CHECK_EQ(rd_read_ppm(dir, r->file, &img, err, sizeof err), 0);
        CHECK(img.width == 320 && img.height == 240);
        host_image_free(&img);
    }
    t_info("labels: %d (X %d, L %d, T %d, G %d, U %d)", total, counts[0], counts[1], counts[2],
           counts[3], counts[4]);
    CHECK_EQ(total, 151);
    free(text);
    rd_uva_free(&s);
}

static void t_real_physar(void)
{
    const char *dir;
    char path[1024], err[200];
    rd_physar_set_t s;
    int i, n_bottom = 0;
    if (skip_if_absent())
        return;
    dir = t_realdata_dir();
    CHECK_EQ(rd_path(path, sizeof path, dir, RD_PHYSAR_CSV), 0);
    CHECK_EQ(rd_physar_load(path, &s, err, sizeof err), 0);
    CHECK_EQ(s.n, 5);
    for (i = 0; i < s.n; i++) {
        host_image_t img;
        CHECK_EQ(rd_read_ppm(dir, s.rec[i].image_top, &img, err, sizeof err), 0);
        CHECK(img.width == 640 && img.height == 480);
        host_image_free(&img);
        if (s.rec[i].image_bottom[0]) {
            n_bottom++;
            CHECK_EQ(rd_read_ppm(dir, s.rec[i].image_bottom, &img, err, sizeof err), 0);
            host_image_free(&img);
        }
        /* OptiTrack within 15 cm of the nominal point */
        CHECK_LE(hypot(s.rec[i].ot_field_x_cm - s.rec[i].nominal_x_cm,
                       s.rec[i].ot_field_y_cm - s.rec[i].nominal_y_cm), 15.0);
        CHECK(s.rec[i].ot_height_m > 0.4 && s.rec[i].ot_height_m < 0.5);
    }
    CHECK_EQ(n_bottom, 1);
    rd_physar_free(&s);
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Nearest-map-point residual of label ft (firmware projection) for the
 * robot pose (x_mm, y_mm, th) and camera cam; -1 when none projects. */
static double fw_residual(const fl_field_t *f, const fl_camera_t *cam, double x_mm,
                          double y_mm, double th, const rd_feature_t *ft, int32_t best_q4[2])
{
    double best = -1;
    uint16_t i;
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *l = &f->landmarks[i];
        double dx = l->x_mm - x_mm, dy = l->y_mm - y_mm, rx, ry, d;
        fl_point_t g;
        int32_t uq, vq;
        if (lm_type(l->kind) != ft->type)
            continue;
        rx = cos(th) * dx + sin(th) * dy;
        ry = -sin(th) * dx + cos(th) * dy;
        if (ft->type == 'G') {
            d = hypot(rx, ry);
            rx -= rx / d * f->post_diameter_mm / 2.0;
            ry -= ry / d * f->post_diameter_mm / 2.0;
        }
        g.x_mm = (int32_t)lround(rx);
        g.y_mm = (int32_t)lround(ry);
        if (!fl_camera_ground_to_pixel(cam, g, &uq, &vq))
            continue;
        d = hypot(uq / 16.0 - ft->u, vq / 16.0 - ft->v);
        if (best < 0 || d < best) {
            best = d;
            if (best_q4) {
                best_q4[0] = uq;
                best_q4[1] = vq;
            }
        }
    }
    return best;
}

static void t_real_camera(void)
{
    const char *dir;
    char path[1024], err[200];
    rd_uva_set_t s;
    const fl_field_t *f = fl_field_find("uva2013");
    const fl_camera_model_t *m = fl_camera_model_find("uva2013");
    double file_e[256], fix_e[256], med_file, med_fix;
    int n_file = 0, n_fix = 0, i, k;
    uint32_t h = t_hash_init();
    if (skip_if_absent())
        return;
    CHECK(f != NULL && m != NULL);
    if (!f || !m)
        return;
    dir = t_realdata_dir();
    CHECK_EQ(rd_path(path, sizeof path, dir, RD_UVA_CSV), 0);
    CHECK_EQ(rd_uva_load(path, &s, err, sizeof err), 0);
    for (i = 0; i < s.n; i++) {
        const rd_uva_record_t *r = &s.rec[i];
        fl_camera_pose_t pose;
        fl_camera_t cam;
        double th0 = r->theta_deg * PI_D / 180.0, best_c = 1e300, best_dth = 0, dth;
        rd_uva_camera_pose(r, m, &pose);
        CHECK_EQ(fl_camera_init(&cam, m, &pose), FL_OK);
        for (k = 0; k < r->n_features; k++) {
            int32_t q[2] = {0, 0};
            double e;
            if (r->feat[k].type == 'U')
                continue;
            e = fw_residual(f, &cam, r->x_cm * 10, r->y_cm * 10, th0, &r->feat[k], q);
            h = t_hash_i32(h, q[0]);
            h = t_hash_i32(h, q[1]);
            if (e >= 0 && n_file < 256)
                file_e[n_file++] = e;
        }
        /* per-image heading search, camera untouched: cost truncated at 20 px */
        for (dth = -10.0; dth <= 10.0001; dth += 0.1) {
            double c = 0;
            for (k = 0; k < r->n_features; k++) {
                double e;
                if (r->feat[k].type == 'U')
                    continue;
                e = fw_residual(f, &cam, r->x_cm * 10, r->y_cm * 10, th0 + dth * PI_D / 180.0,
                                &r->feat[k], NULL);
                c += (e < 0 || e > 20) ? 400.0 : e * e;
            }
            if (c < best_c) {
                best_c = c;
                best_dth = dth;
            }
        }
        for (k = 0; k < r->n_features; k++) {
            double e;
            if (r->feat[k].type == 'U')
                continue;
            e = fw_residual(f, &cam, r->x_cm * 10, r->y_cm * 10, th0 + best_dth * PI_D / 180.0,
                            &r->feat[k], NULL);
            if (e >= 0 && n_fix < 256)
                fix_e[n_fix++] = e;
        }
    }
    t_digest("realdata.uva2013_label_projections", h);
    qsort(file_e, (size_t)n_file, sizeof(double), cmp_d);
    qsort(fix_e, (size_t)n_fix, sizeof(double), cmp_d);
    CHECK(n_file >= 130 && n_fix >= 130);
    if (n_file < 2 || n_fix < 2) {
        rd_uva_free(&s);
        return;
    }
    med_file = file_e[n_file / 2];
    med_fix = fix_e[n_fix / 2];
    t_info("uva2013 camera, X/L/T/G labels, file poses: %d, median %.2f px, 90%% %.2f, max %.2f",
           n_file, med_file, file_e[n_file * 9 / 10], file_e[n_file - 1]);
    t_info("uva2013 camera, per-image heading search: %d, median %.2f px, 90%% %.2f, max %.2f",
           n_fix, med_fix, fix_e[n_fix * 9 / 10], fix_e[n_fix - 1]);
    CHECK_LE(med_file, 8.5);
    CHECK_LE(med_fix, 5.5);
    rd_uva_free(&s);
}

static void t_real_refit(void)
{
    const char *dir;
    char path[1024], err[200];
    rd_uva_set_t s;
    cal_problem_t pb;
    cal_options_t o;
    cal_params_t p;
    cal_result_t res;
    const fl_field_t *f = fl_field_find("uva2013");
    const fl_camera_model_t *bottom = fl_camera_model_find("nao4-bottom-320");
    const fl_camera_model_t *m = fl_camera_model_find("uva2013");
    double pitch_deg, committed_pitch_deg;
    if (skip_if_absent())
        return;
    CHECK(f && bottom && m);
    if (!f || !bottom || !m)
        return;
    dir = t_realdata_dir();
    CHECK_EQ(rd_path(path, sizeof path, dir, RD_UVA_CSV), 0);
    CHECK_EQ(rd_uva_load(path, &s, err, sizeof err), 0);
    CHECK_EQ(cal_problem_init(&pb, &s, f), 0);
    cal_options_default(&o);
    o.fit_mask = CAL_FIT_BASE | CAL_BIT(CAL_POST_H); /* = `fieldloc calibrate` [4] */
    o.pose_mask = CAL_FIT_POSE_HEADING | CAL_FIT_POSE_XY;
    cal_params_init(&p, bottom, f);
    CHECK_EQ(cal_fit(&pb, &o, &p, &res), 0);
    pitch_deg = p.p[CAL_PITCH] * 180.0 / PI_D;
    committed_pitch_deg = m->default_pitch_offset * 360.0 / 65536.0;
    t_info("refit: neck %.2f mm (committed %d), pitch offset %.3f deg (%.3f), focal %.2f px "
           "(%.2f); %d used, %d outliers, rms %.2f px",
           p.p[CAL_NECK], (int)m->default_neck_height_mm, pitch_deg, committed_pitch_deg,
           p.p[CAL_FOCAL], m->focal_q4 / 16.0, res.n_used, res.n_outliers, res.rms_px);
    CHECK_LE(fabs(p.p[CAL_NECK] - m->default_neck_height_mm), 2.0);
    CHECK_LE(fabs(pitch_deg - committed_pitch_deg), 0.05);
    CHECK_LE(fabs(p.p[CAL_FOCAL] - m->focal_q4 / 16.0), 0.25);
    /* the committed model keeps the mount and principal point it was fitted with */
    CHECK(m->mount_x_mm == bottom->mount_x_mm && m->mount_z_mm == bottom->mount_z_mm &&
          m->mount_tilt == bottom->mount_tilt && m->cx_q4 == bottom->cx_q4 &&
          m->cy_q4 == bottom->cy_q4);
    cal_problem_free(&pb);
    rd_uva_free(&s);
}

/* ---- modern frames (tools/eval/realdata_modern.csv) -------------------- */

static const char *modern_hdr =
    "file,in_realdata,set,index,x_cm,y_cm,theta_deg,head_pitch_rad,head_yaw_rad,n_features,"
    "features,camera\n";

static void t_modern_parse(void)
{
    static const char *text =
        "# conventions\n"
        "file,in_realdata,set,index,x_cm,y_cm,theta_deg,head_pitch_rad,head_yaw_rad,n_features,"
        "features,camera\r\n"
        "p.ppm,1,physar,p1,129.6,121.7,-135,0.1257,0.0552,3,\"X:0,0 G:639,479 B:10,150\","
        "nao6-top-640\r\n"
        "h.ppm,1,htwk,h1,,,,0.28,0,1,\"B:20,51\",nao4-top-640\n"
        "n.ppm,0,naoth,n2,,,,,,0,\"\",nao6-bottom-320";
    rd_modern_set_t s;
    char err[200];
    CHECK_EQ(rd_modern_parse(text, &s, err, sizeof err), 0);
    CHECK_EQ(s.n, 3);
    if (s.n != 3)
        return;
    CHECK(s.rec[0].has_pose && s.rec[0].has_head);
    CHECK(s.rec[0].x_cm == 129.6 && s.rec[0].y_cm == 121.7 && s.rec[0].theta_deg == -135);
    CHECK(s.rec[0].head_pitch_rad == 0.1257 && s.rec[0].head_yaw_rad == 0.0552);
    CHECK(strcmp(s.rec[0].camera, "nao6-top-640") == 0);
    /* 0-based pixels kept as written (no UvA -1) */
    CHECK(s.rec[0].feat[0].type == 'X' && s.rec[0].feat[0].u == 0 && s.rec[0].feat[0].v == 0);
    CHECK(s.rec[0].feat[1].type == 'G' && s.rec[0].feat[1].u == 639 &&
          s.rec[0].feat[1].v == 479);
    CHECK(s.rec[0].feat[2].type == 'B' && s.rec[0].feat[2].u == 10);
    CHECK_EQ(rd_modern_count(&s.rec[0], 'B'), 1);
    CHECK_EQ(rd_modern_count(&s.rec[0], 0), 3);
    CHECK(!s.rec[1].has_pose && s.rec[1].has_head && s.rec[1].x_cm == 0);
    CHECK(s.rec[1].head_pitch_rad == 0.28);
    CHECK(!s.rec[2].has_pose && !s.rec[2].has_head && s.rec[2].in_realdata == 0);
    CHECK_EQ(s.rec[2].n_features, 0);
    CHECK(strcmp(s.rec[2].camera, "nao6-bottom-320") == 0);
    rd_modern_free(&s);
    CHECK(s.rec == NULL && s.n == 0);
    rd_modern_free(NULL);
    CHECK_EQ(rd_modern_count(NULL, 'X'), 0);
}

static void t_modern_errors(void)
{
    static const struct {
        const char *row, *why;
    } bad[] = {
        {"a.ppm,1,s,i,,,,,,2,\"X:1,2\",nao6-top-640\n", "n_features"},
        {"a.ppm,1,s,i,1,,3,,,0,\"\",nao6-top-640\n", "all blank or all numbers"},
        {"a.ppm,1,s,i,,,,0.1,,0,\"\",nao6-top-640\n", "all blank or all numbers"},
        {"a.ppm,1,s,i,1,x,3,,,0,\"\",nao6-top-640\n", "bad number"},
        {"a.ppm,1,s,i,,,,9,0,0,\"\",nao6-top-640\n", "out of range"},
        {"a.ppm,1,s,i,,,,,,1,\"Q:1,2\",nao6-top-640\n", "feature list"},
        {"a.ppm,1,s,i,,,,,,1,\"X:1,2\",nao9-top\n", "unknown camera"},
        {"a.ppm,1,s,i,,,,,,1,\"X:640,2\",nao6-top-640\n", "outside"},
        {"a.ppm,1,s,i,,,,,,1,\"B:10,-3\",nao6-top-640\n", "outside"},
        {"a.ppm,1,s,i,,,,,,1,\"X:400,300\",nao6-bottom-320\n", "outside"},
        {"a.ppm,2,s,i,,,,,,0,\"\",nao6-top-640\n", "in_realdata"},
        {",1,s,i,,,,,,0,\"\",nao6-top-640\n", "name"},
        {"a.ppm,1,,i,,,,,,0,\"\",nao6-top-640\n", "name"},
        {"a.ppm,1,s,i,,,,,,0,\"\"\n", "fields"},
    };
    char text[1024], err[200];
    rd_modern_set_t s;
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(text, sizeof text, "%s%s", modern_hdr, bad[i].row);
        err[0] = '\0';
        CHECK_EQ(rd_modern_parse(text, &s, err, sizeof err), -1);
        CHECK(s.rec == NULL && s.n == 0);
        if (!strstr(err, "line 2") || !strstr(err, bad[i].why))
            t_info("row %d: error '%s' (expected line 2, '%s')", (int)i, err, bad[i].why);
        CHECK(strstr(err, "line 2") != NULL);
        CHECK(strstr(err, bad[i].why) != NULL);
    }
    /* the same file twice: line 3 */
    snprintf(text, sizeof text, "%sa.ppm,1,s,i,,,,,,0,\"\",nao6-top-640\n"
                                "a.ppm,1,s,j,,,,,,0,\"\",nao6-top-640\n", modern_hdr);
    CHECK_EQ(rd_modern_parse(text, &s, err, sizeof err), -1);
    CHECK(strstr(err, "line 3") != NULL && strstr(err, "twice") != NULL);
    /* the UvA header lacks camera */
    CHECK_EQ(rd_modern_parse("file,in_realdata,set,index,x_cm,y_cm,theta_deg,head_pitch_rad,"
                             "head_yaw_rad,n_features,features\n", &s, err, sizeof err), -1);
    CHECK(strstr(err, "camera") != NULL);
    CHECK_EQ(rd_modern_parse(NULL, &s, NULL, 0), -1);
    CHECK_EQ(rd_modern_parse(modern_hdr, NULL, NULL, 0), -1);
    CHECK_EQ(rd_modern_parse(modern_hdr, &s, err, sizeof err), 0);
    CHECK_EQ(s.n, 0);
    rd_modern_free(&s);
}

/* Label counts of tools/eval/realdata_modern.csv as labelled, per type:
 * X, L, T, G, U, B (19 frames, 178 labels: X 26, L 2, T 1, G 15, U 16,
 * B 118).  The file is in the repository: always checked; the images only
 * with ../shared/realdata. */
static void t_modern_file(void)
{
    static const char types[] = "XLTGUB";
    static const struct {
        const char *index;
        int n[6];
    } expect[] = {
        {"black1_point1_top", {3, 0, 0, 1, 1, 9}},
        {"black1_point2_top", {2, 0, 0, 2, 2, 7}},
        {"black1_point2_bottom", {0, 0, 0, 0, 0, 0}},
        {"black1_point3_top", {2, 0, 0, 2, 2, 8}},
        {"black1_point4_top", {2, 0, 0, 1, 1, 8}},
        {"black1_point5_top", {2, 0, 0, 2, 2, 7}},
        {"00049806_U", {1, 0, 0, 0, 0, 8}},
        {"00051659_U", {3, 0, 0, 2, 2, 7}},
        {"referee_pose_test_image", {3, 0, 0, 2, 2, 8}},
        {"rc19_outdoor5_bottom_18795", {0, 0, 0, 0, 0, 0}},
        {"danu_fallen_robot_9500_upper", {1, 0, 0, 0, 0, 9}},
        {"danu_gaolie_shots_on_goal_2002_upper", {2, 0, 0, 2, 2, 6}},
        {"danu_moving_ball_across_vision_3141_upper", {3, 0, 0, 0, 0, 6}},
        {"eobr313", {0, 1, 0, 1, 2, 8}},
        {"oisin_ball_robot0476", {2, 0, 1, 0, 0, 8}},
        {"oisin_demo_ball0485", {0, 1, 0, 0, 0, 0}},
        {"lower_942458", {0, 0, 0, 0, 0, 0}},
        {"log_31527", {0, 0, 0, 0, 0, 10}},
        {"log_40230", {0, 0, 0, 0, 0, 9}},
    };
    const char *csv = rd_modern_csv(), *dir = t_realdata_dir();
    char err[200];
    rd_modern_set_t s;
    size_t e;
    int i, k, physar = 0;
    CHECK(csv != NULL);
    if (!csv)
        return;
    CHECK_EQ(rd_modern_load(csv, &s, err, sizeof err), 0);
    t_info("%s: %d rows", csv, s.n);
    CHECK_EQ(s.n, (int)(sizeof expect / sizeof expect[0]));
    for (e = 0; e < sizeof expect / sizeof expect[0]; e++) {
        const rd_modern_record_t *r = NULL;
        for (i = 0; i < s.n; i++)
            if (strcmp(s.rec[i].index, expect[e].index) == 0)
                r = &s.rec[i];
        CHECK(r != NULL);
        if (!r)
            continue;
        for (k = 0; k < 6; k++)
            CHECK_EQ(rd_modern_count(r, types[k]), expect[e].n[k]);
    }
    for (i = 0; i < s.n; i++) {
        const rd_modern_record_t *r = &s.rec[i];
        const fl_camera_model_t *m = fl_camera_model_find(r->camera);
        CHECK(m != NULL && r->in_realdata == 1);
        /* physar rows carry the OptiTrack pose and head angles; the others none */
        if (strcmp(r->set, "physar") == 0) {
            physar++;
            CHECK(r->has_pose && r->has_head);
        } else {
            CHECK(!r->has_pose);
        }
        if (dir && m) {
            host_image_t img;
            CHECK_EQ(rd_read_ppm(dir, r->file, &img, err, sizeof err), 0);
            CHECK(img.rgb && (int32_t)img.width == m->width_px &&
                  (int32_t)img.height == m->height_px);
            host_image_free(&img);
        }
    }
    CHECK_EQ(physar, 6);
    if (!dir)
        t_info("%s (images not checked)", rd_skip_message());
    rd_modern_free(&s);
}

static void modern_floor(const char *what, double got, double floor)
{
    CHECK_LE(floor, got);
    t_info("modern %s %.3f (floor %.2f)", what, got, floor);
}

static double ratio_d(int a, int b) { return b > 0 ? (double)a / b : 0.0; }

/* eval-detect's modern block with today's vision (default colours, 19
 * frames): the floors sit just under what it measures (crossings
 * precision 0.167, recall 0.276; field border 0.339 of the 118 labelled
 * columns within 3 px); no white post is found yet, so the feet have no
 * floor.  Targets: crossings 0.85 / 0.7, feet 0.9 / 0.8, border 0.95. */
#define MODERN_CROSS_P 0.15
#define MODERN_CROSS_R 0.28
#define MODERN_FOOT_P 0.30
#define MODERN_FOOT_R 0.20
#define MODERN_BORDER 0.50
static void t_modern_eval(void)
{
    const char *dir = t_realdata_dir(), *csv = rd_modern_csv();
    det_ctx_t dc;
    evd_stats_t s;
    evd_border_t b;
    colors_opt_t co;
    int n;
    if (skip_if_absent())
        return;
    if (t_quick) {
        t_info("skipped in quick mode");
        return;
    }
    CHECK(csv != NULL);
    CHECK_EQ(det_ctx_init(&dc), 0);
    /* the colour policy of `fieldloc eval-detect` without --colors: each
     * frame's own carpet (auto), as a user gets it */
    memset(&co, 0, sizeof co);
    dc.colors_each = &co;
    evd_stats_clear(&s);
    evd_border_clear(&b);
    n = evd_modern(&dc, dir, csv, 0, &s, &b);
    det_ctx_free(&dc);
    CHECK_EQ(n, 19);
    /* floors a little below what the merged vision measures (the issue's
     * targets, far above: crossings 0.85 / 0.7, feet 0.9 / 0.8, border
     * 0.95; docs/RESULTS.md has the numbers) */
    modern_floor("crossings precision", ratio_d(s.cross_tp, s.cross_tp + s.cross_fp), MODERN_CROSS_P);
    modern_floor("crossings recall", ratio_d(s.cross_tp, s.cross_tp + s.cross_fn), MODERN_CROSS_R);
    modern_floor("post feet precision", ratio_d(s.foot_tp, s.foot_tp + s.foot_fp), MODERN_FOOT_P);
    modern_floor("post feet recall", ratio_d(s.foot_tp, s.foot_tp + s.foot_fn), MODERN_FOOT_R);
    modern_floor("field border within 3 px", ratio_d(b.within, b.n), MODERN_BORDER);
    t_info("modern border mean %.1f px, worst %.1f px", b.n ? b.sum / b.n : 0.0, b.worst);
}

/* Marks and crossings on robots in the modern real frames (auto colours,
 * as eval-detect): a white spot on a robot (its arm, its leg) passes a
 * mark's sparse ring of green samples, and two edges of a robot's body
 * meet like lines; the dark cells close by (joints, jersey, the ball's
 * patches) reject both.  The robots' boxes are those of robots.realdata;
 * for marks on oisin_demo from below the robot's head (the white top of
 * its head at (572, 84) still passes: few dark cells in its ring).  Over
 * the 19 frames the crossings keep their 8 hits while 11 of the 55 false
 * ones (marks and crossings on robots, balls and clutter) are gone. */
static void t_modern_marks(void)
{
    static const struct {
        const char *index;
        int u0, v0, u1, v1, mark_v0;
    } box[] = {
        {"oisin_demo_ball0485", 465, 65, 639, 335, 150},
        {"oisin_ball_robot0476", 505, 0, 639, 300, 0},
    };
    const char *dir = t_realdata_dir(), *csv = rd_modern_csv();
    const fl_field_t *field = fl_field_find("spl2020");
    colors_opt_t opt;
    det_ctx_t dc;
    evd_stats_t s;
    evd_border_t b;
    rd_modern_set_t set;
    char err[256];
    size_t k;
    int i, j, n, seen = 0;
    if (skip_if_absent())
        return;
    CHECK(csv != NULL && field != NULL);
    if (!csv || !field)
        return;
    memset(&opt, 0, sizeof opt);   /* unset: auto colours on these frames */
    CHECK_EQ(det_ctx_init(&dc), 0);
    dc.colors_each = &opt;
    CHECK_EQ(rd_modern_load(csv, &set, err, sizeof err), 0);
    for (k = 0; k < sizeof box / sizeof box[0]; k++)
        for (i = 0; i < set.n; i++) {
            const rd_modern_record_t *r = &set.rec[i];
            const fl_camera_model_t *m = fl_camera_model_find(r->camera);
            det_feature_t feat[DET_MAX_FEATURES];
            fl_camera_pose_t pose;
            fl_camera_t cam;
            host_image_t img;
            fl_image_t view;
            int on = 0, marks = 0, crossings = 0;
            if (strcmp(r->index, box[k].index) != 0 || !m)
                continue;
            CHECK_EQ(rd_read_ppm(dir, r->file, &img, err, sizeof err), 0);
            CHECK_EQ(rd_image_view(&img, &view), FL_OK);
            rd_modern_camera_pose(r, m, &pose);
            CHECK_EQ(fl_camera_init(&cam, m, &pose), FL_OK);
            n = det_run(&dc, &view, &cam, field, NULL, feat, DET_MAX_FEATURES);
            for (j = 0; j < n; j++) {
                bool mark = feat[j].lm == FL_LM_PENALTY_MARK;
                bool line = feat[j].lm == FL_LM_L || feat[j].lm == FL_LM_T || feat[j].lm == FL_LM_X;
                if (!mark && !line)
                    continue;
                marks += mark;
                crossings += line;
                if (feat[j].u >= box[k].u0 && feat[j].u <= box[k].u1 &&
                    feat[j].v >= (mark ? box[k].mark_v0 : box[k].v0) && feat[j].v <= box[k].v1)
                    on++;
            }
            t_info("%s: %d features, %d penalty marks, %d crossings of lines, %d on the robot",
                   r->index, n, marks, crossings, on);
            CHECK_EQ(on, 0);
            seen++;
            host_image_free(&img);
        }
    rd_modern_free(&set);
    CHECK_EQ(seen, 2);
    if (t_quick) {
        det_ctx_free(&dc);
        return;
    }
    evd_stats_clear(&s);
    evd_border_clear(&b);
    CHECK_EQ(evd_modern(&dc, dir, csv, 0, &s, &b), 19);
    det_ctx_free(&dc);
    t_info("modern crossings tp %d fp %d fn %d", s.cross_tp, s.cross_fp, s.cross_fn);
    CHECK_LE(8, s.cross_tp);
    CHECK_LE(s.cross_fp, 44);
}

void suite_realdata(void)
{
    t_run("realdata.uva_parse", t_uva_parse);
    t_run("realdata.uva_errors", t_uva_errors);
    t_run("realdata.uva_load_file", t_uva_load_file);
    t_run("realdata.physar_parse", t_physar_parse);
    t_run("realdata.ppm", t_ppm);
    t_run("realdata.dir", t_dir);
    t_run("realdata.pose", t_pose);
    t_run("realdata.calibrate_synthetic", t_calibrate_synthetic);
    t_run("realdata.real_uva", t_real_uva);
    t_run("realdata.real_physar", t_real_physar);
    t_run("realdata.real_camera", t_real_camera);
    t_run("realdata.real_refit", t_real_refit);
    t_run("realdata.modern_parse", t_modern_parse);
    t_run("realdata.modern_errors", t_modern_errors);
    t_run("realdata.modern_file", t_modern_file);
    t_run("realdata.modern_eval", t_modern_eval);
    t_run("realdata.modern_marks", t_modern_marks);
}
