/*
 * tools/cli/cmd_calibrate.c - camera calibration.
 *
 * `fieldloc calibrate --field F --camera C --frames FILE [--out CALIB]
 * [--no-roll] [--fit-heading]`: per-robot calibration from the user's own frames taken at
 * known poses (format of FILE and the fit: tools/eval/calib_frames.h; in
 * short one line per frame "IMAGE X_MM Y_MM HEADING_DEG HEAD_YAW_DEG
 * HEAD_PITCH_DEG [TORSO_PITCH_DEG TORSO_ROLL_DEG]", '#' comments, paths
 * relative to FILE).  Fits the neck height, pitch offset and roll offset
 * (not with --no-roll) to the detected field lines, prints per frame and
 * in total the residuals with the camera's default pose and with the
 * fitted one, and writes CALIB (fieldloc/calib.h format) for `detect
 * --calib`, `localize --calib` and fl_calib_parse on the robot.
 * --fit-heading also refits each frame's heading and x/y (priors 5 deg,
 * 100 mm) for robots put down by hand.  A malformed FILE is refused with
 * its line (exit status 2); an unreadable image skips its frame with a
 * message.
 *
 * `fieldloc calibrate [--dir DIR] [--verbose] [--out CALIB]`: fit
 * the UvA 2013 camera (calibrate.h) to ../shared/realdata's hand labels
 * and print the fitted values, the residuals per kind and per image, the
 * alternatives tried (top vs bottom mounting, extra parameters, with and
 * without per-image pose corrections), the field dimension check, the
 * leave-one-image-out residuals and the check of the committed catalogue
 * camera "uva2013" through the firmware projection; then the same frames
 * as a frame list through the detection-driven fit of --frames (from the
 * nominal NAO v4 pose, with --fit-heading: the file-name poses are off)
 * for comparison ([10]).  --out writes the hand-label fit
 * [4] as a calibration of camera uva2013.
 * Says "skipped: ..." and exits 0 when the folder is absent.
 */
#include "eval/calibrate.h"
#include "eval/calib_frames.h"
#include "fieldloc/fieldloc.h"
#include "cli/args.h"
#include "cli/registry.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CAL_DEG (180.0 / 3.14159265358979323846)
#define HP_TYPICAL (-0.545) /* typical HeadPitch of the set, rad */
/* The camera fit: neck, pitch offset, focal, and the post height as a
 * nuisance (the U labels sit lower than DESIGN.md's 800 mm). */
#define FIT_CAM (CAL_FIT_BASE | CAL_BIT(CAL_POST_H))

static void print_kinds(const cal_problem_t *pb, const char *indent)
{
    static const char *kinds[] = {"X", "L", "T", "G", "U", "XLT", "XLTGU"};
    size_t k;
    for (k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        double med, mx, med_all, mx_all;
        int n = cal_residual_stats(pb, kinds[k], 1, -1, &med, &mx);
        int na = cal_residual_stats(pb, kinds[k], 0, -1, &med_all, &mx_all);
        printf("%s%-6s inliers %3d: median %5.2f max %5.2f px | all matched %3d: median %5.2f "
               "max %5.2f px\n",
               indent, kinds[k], n, med, mx, na, med_all, mx_all);
    }
}

static void print_params(const cal_params_t *p, const cal_result_t *r, unsigned mask)
{
    int i;
    for (i = 0; i < CAL_NP; i++)
        if (mask & CAL_BIT(i))
            printf("    %-28s %10.3f +- %.3f\n", cal_param_name(i),
                   cal_param_display(i, p->p[i]), cal_param_display(i, r->sigma[i]));
    printf("    labels used %d, outliers %d (> 8 px), unmatched %d; rms %.2f px\n", r->n_used,
           r->n_outliers, r->n_unmatched, r->rms_px);
}

static double tilt_deg(const cal_params_t *p)
{
    return (p->mount_tilt_rad + HP_TYPICAL + p->p[CAL_PITCH]) * CAL_DEG;
}

static double cam_height(const cal_params_t *p)
{
    double th = HP_TYPICAL + p->p[CAL_PITCH];
    return p->p[CAL_NECK] - p->mount_x_mm * sin(th) + p->mount_z_mm * cos(th);
}

static int run_fit(cal_problem_t *pb, const fl_camera_model_t *m, unsigned mask,
                   unsigned pose_mask, cal_params_t *p, cal_result_t *r, int exclude)
{
    cal_options_t o;
    cal_options_default(&o);
    o.fit_mask = mask;
    o.pose_mask = pose_mask;
    o.exclude_rec = exclude;
    cal_params_init(p, m, pb->field);
    return cal_fit(pb, &o, p, r);
}

/* Residuals with the poses as given (corrections zeroed). */
static void file_pose_residuals(cal_problem_t *pb, const cal_params_t *p)
{
    cal_params_t q = *p;
    memset(q.pose, 0, sizeof q.pose);
    cal_evaluate(pb, &q, 40.0, 8.0);
}

static void lm_pos(const cal_problem_t *pb, const cal_params_t *p, int lm, double *x, double *y)
{
    int k;
    *x = *y = 0;
    for (k = 0; k < CAL_NP; k++) {
        *x += pb->lm[lm].ax[k] * p->p[k];
        *y += pb->lm[lm].ay[k] * p->p[k];
    }
}

static void print_outliers(const cal_problem_t *pb, const cal_params_t *p)
{
    int i, any = 0;
    for (i = 0; i < pb->n_obs; i++) {
        const cal_obs_t *o = &pb->obs[i];
        const rd_uva_record_t *r = &pb->set->rec[o->rec];
        double x, y;
        if (o->lm >= 0 && !o->outlier)
            continue;
        any = 1;
        if (o->lm < 0) {
            printf("    %s_%s %c label (%g, %g) 1-based: no %s landmark within 40 px\n", r->set,
                   r->index, o->type, o->u + 1, o->v + 1, o->type == 'U' ? "post" : "such");
            continue;
        }
        lm_pos(pb, p, o->lm, &x, &y);
        printf("    %s_%s %c label (%g, %g) 1-based: %.1f px (du %+.1f, dv %+.1f) from "
               "(%.0f, %.0f) mm%s\n",
               r->set, r->index, o->type, o->u + 1, o->v + 1, hypot(o->du, o->dv), o->du, o->dv,
               x, y, o->type == 'U' ? " top" : "");
    }
    if (!any)
        printf("    none\n");
}

/* Firmware check of a catalogue model: nearest-landmark residuals through
 * fl_camera_ground_to_pixel with the model's default pose and the file-name
 * robot poses (U labels not checked: fl_camera projects ground points). */
static void firmware_check(const rd_uva_set_t *set, const fl_field_t *f,
                           const fl_camera_model_t *m)
{
    static const char *groups[] = {"X", "L", "T", "G", "XLT", "XLTG"};
    double *e[6];
    int n[6] = {0}, r, k, g;
    for (g = 0; g < 6; g++)
        e[g] = malloc(sizeof(double) * 512);
    for (r = 0; r < set->n; r++) {
        const rd_uva_record_t *rec = &set->rec[r];
        fl_camera_pose_t pose;
        fl_camera_t cam;
        rd_uva_camera_pose(rec, m, &pose);
        if (fl_camera_init(&cam, m, &pose) != FL_OK)
            continue;
        for (k = 0; k < rec->n_features; k++) {
            const rd_feature_t *ft = &rec->feat[k];
            double best = 1e300;
            uint16_t i;
            if (ft->type == 'U')
                continue;
            for (i = 0; i < f->n_landmarks; i++) {
                const fl_landmark_t *l = &f->landmarks[i];
                char t = l->kind == FL_LM_L ? 'L' : l->kind == FL_LM_T ? 'T'
                       : (l->kind == FL_LM_X || l->kind == FL_LM_PENALTY_MARK ||
                          l->kind == FL_LM_CENTRE_MARK) ? 'X'
                       : l->kind == FL_LM_POST ? 'G' : 0;
                double gx, gy, d;
                fl_point_t gp;
                int32_t uq, vq;
                if (t != ft->type)
                    continue;
                rd_uva_field_to_robot(rec, l->x_mm, l->y_mm, &gx, &gy);
                if (t == 'G') { /* post surface nearest the camera (near enough) */
                    d = hypot(gx, gy);
                    if (d > f->post_diameter_mm / 2.0) {
                        gx -= gx / d * f->post_diameter_mm / 2.0;
                        gy -= gy / d * f->post_diameter_mm / 2.0;
                    }
                }
                gp.x_mm = (int32_t)lround(gx);
                gp.y_mm = (int32_t)lround(gy);
                if (!fl_camera_ground_to_pixel(&cam, gp, &uq, &vq))
                    continue;
                d = hypot(uq / 16.0 - ft->u, vq / 16.0 - ft->v);
                if (d < best)
                    best = d;
            }
            if (best > 1e299)
                continue;
            for (g = 0; g < 6; g++)
                if (strchr(groups[g], ft->type) && n[g] < 512)
                    e[g][n[g]++] = best;
        }
    }
    for (g = 0; g < 6; g++) {
        int i, j;
        for (i = 1; i < n[g]; i++) /* insertion sort */
            for (j = i; j > 0 && e[g][j - 1] > e[g][j]; j--) {
                double t = e[g][j];
                e[g][j] = e[g][j - 1];
                e[g][j - 1] = t;
            }
        if (n[g])
            printf("    %-5s %3d labels: median %5.2f px  max %6.2f px\n", groups[g], n[g],
                   n[g] % 2 ? e[g][n[g] / 2] : 0.5 * (e[g][n[g] / 2 - 1] + e[g][n[g] / 2]),
                   e[g][n[g] - 1]);
        free(e[g]);
    }
}

/* ---- --frames: the user's own frames ------------------------------------------- */

static int cal_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc calibrate --field NAME --camera NAME --frames FILE [--out CALIB]\n"
            "                          [--no-roll] [--fit-heading]\n"
            "       fieldloc calibrate [--dir REALDATA_DIR] [--verbose] [--out CALIB]  (UvA 2013)\n"
            "  FILE: one frame per line, '#' comments, image paths relative to FILE:\n"
            "    IMAGE X_MM Y_MM HEADING_DEG HEAD_YAW_DEG HEAD_PITCH_DEG [TORSO_PITCH_DEG "
            "TORSO_ROLL_DEG]\n"
            "  (robot pose in the field frame; NAOqi head angles in degrees, pitch > 0 = down;\n"
            "  optional IMU torso angles).  Fits neck height, pitch offset and roll offset to\n"
            "  the detected field lines; CALIB (for detect/localize --calib, fl_calib_parse):\n"
            "    fieldloc-calibration 1 / camera NAME / neck_height_mm N / pitch_offset_deg D /\n"
            "    roll_offset_deg D\n"
            "  --no-roll: roll offset stays 0; --fit-heading: each frame's heading and x/y are\n"
            "  refitted too (priors 5 deg, 100 mm) for poses set by hand\n");
    return 2;
}

static void cal_warn(const char *msg, void *user)
{
    fprintf(stderr, "calibrate: %s: %s\n", (const char *)user, msg);
}

static void cal_print_params(const char *what, const cf_params_t *p, const double *sigma)
{
    if (sigma)
        printf("%s: neck_height_mm %.1f +- %.1f, pitch_offset_deg %.3f +- %.3f, "
               "roll_offset_deg %.3f +- %.3f\n",
               what, p->neck_mm, sigma[0], p->pitch_offset_deg, sigma[1], p->roll_offset_deg,
               sigma[2]);
    else
        printf("%s: neck_height_mm %.1f, pitch_offset_deg %.3f, roll_offset_deg %.3f\n", what,
               p->neck_mm, p->pitch_offset_deg, p->roll_offset_deg);
}

/* Fit, print before/after per frame and in total.  0 or -1. */
static int cal_frames_run(const cf_frames_t *fr, const char *name, const fl_field_t *field,
                          const fl_camera_model_t *m, const cf_options_t *o, cf_params_t *p,
                          int per_frame)
{
    cf_result_t res;
    char err[512];
    int k;
    cal_print_params("start", p, NULL);
    if (cf_fit(fr, field, m, o, p, &res, cal_warn, (void *)name, err, sizeof err) != 0) {
        fprintf(stderr, "calibrate: %s: %s\n", name, err);
        return -1;
    }
    printf("residual = distance of a detected line point, projected to the field at the known\n"
           "pose, to the nearest field line, in image px (mm * f / distance); 'in' = within %.0f "
           "px\n",
           o->gate_px);
    if (per_frame) {
        printf("%5s %-28s %6s | %5s %6s %6s | %5s %6s %6s%s\n", "line", "image", "points",
               "in", "median", "rms", "in", "median", "rms", res.corr ? "   dth_deg  dx_mm  dy_mm" : "");
        printf("%5s %-28s %6s | %-19s | %-19s\n", "", "", "", "  start", "  fitted");
        for (k = 0; k < fr->n; k++) {
            const char *img = strrchr(fr->f[k].image, '/');
            const cf_stats_t *b = &res.before[k], *a = &res.after[k];
            img = img ? img + 1 : fr->f[k].image;
            printf("%5d %-28.28s %6d | %5d %6.2f %6.2f | %5d %6.2f %6.2f", fr->f[k].line, img,
                   a->n_points, b->n_in, b->median_px, b->rms_px, a->n_in, a->median_px,
                   a->rms_px);
            if (res.corr)
                printf(" %+9.2f %+6.0f %+6.0f", res.corr[3 * k], res.corr[3 * k + 1],
                       res.corr[3 * k + 2]);
            printf("\n");
        }
    }
    printf("total: %d frames (%d skipped), %d line points; start: %d in, median %.2f px, rms "
           "%.2f px; fitted: %d in, median %.2f px, rms %.2f px\n",
           res.n_frames, res.n_skipped, res.after_all.n_points, res.before_all.n_in,
           res.before_all.median_px, res.before_all.rms_px, res.after_all.n_in,
           res.after_all.median_px, res.after_all.rms_px);
    cal_print_params("fitted", &res.fit, res.sigma);
    cf_result_free(&res);
    return 0;
}

static int cal_write(const char *out, const char *camera, const cf_params_t *p, int roll,
                     const char *comment)
{
    fl_calib_t c;
    char err[512];
    memset(&c, 0, sizeof c);
    c.has = FL_CALIB_HAS_CAMERA | FL_CALIB_HAS_NECK | FL_CALIB_HAS_PITCH |
            (roll ? FL_CALIB_HAS_ROLL : 0u);
    snprintf(c.camera, sizeof c.camera, "%s", camera);
    c.neck_height_mm = (int32_t)lround(p->neck_mm);
    c.pitch_offset = fl_angle_from_mdeg((int32_t)lround(p->pitch_offset_deg * 1000.0));
    c.roll_offset = fl_angle_from_mdeg((int32_t)lround(p->roll_offset_deg * 1000.0));
    if (cf_calib_save(out, &c, comment, err, sizeof err) != 0) {
        fprintf(stderr, "calibrate: %s\n", err);
        return 1;
    }
    printf("wrote %s\n", out);
    return 0;
}

static int cal_frames_cmd(const char *frames, const char *field_name, const char *cam_name,
                          const char *out, int roll, int heading)
{
    const fl_field_t *field = field_name ? fl_field_find(field_name) : NULL;
    const fl_camera_model_t *m = cam_name ? fl_camera_model_find(cam_name) : NULL;
    cf_frames_t fr;
    cf_options_t o;
    cf_params_t p;
    char err[CF_PATH_MAX + 256], comment[256];
    int rc;
    if (!field_name || !cam_name)
        return cal_usage();
    if (!field) {
        fprintf(stderr, "calibrate: unknown field %s (see: fieldloc fields)\n", field_name);
        return 2;
    }
    if (!m) {
        fprintf(stderr, "calibrate: unknown camera %s (see: fieldloc cameras)\n", cam_name);
        return 2;
    }
    if (cf_frames_load(frames, &fr, err, sizeof err) != 0) {
        fprintf(stderr, "calibrate: %s\n", err);
        return 2;
    }
    printf("calibrate: %s: %d frames, field %s, camera %s\n", frames, fr.n, field->name,
           m->name);
    cf_options_default(&o);
    o.fit_roll = roll;
    o.fit_heading = heading;
    p.neck_mm = m->default_neck_height_mm;
    p.pitch_offset_deg = m->default_pitch_offset * 360.0 / 65536.0;
    p.roll_offset_deg = 0;
    rc = cal_frames_run(&fr, frames, field, m, &o, &p, 1) != 0 ? 1 : 0;
    if (rc == 0 && out) {
        snprintf(comment, sizeof comment, "fieldloc calibrate: %d frames of %.150s", fr.n,
                 frames);
        rc = cal_write(out, m->name, &p, roll, comment);
    }
    cf_frames_free(&fr);
    return rc;
}

/* The UvA frames through the --frames fit, from the nominal NAO v4 pose. */
static void cal_uva_frames(const rd_uva_set_t *set, const char *dir, const cal_params_t *label)
{
    const fl_field_t *field = fl_field_find("uva2013");
    const fl_camera_model_t *m = fl_camera_model_find("uva2013");
    const fl_camera_model_t *nominal = fl_camera_model_find("nao4-bottom-320");
    cf_frames_t fr;
    cf_options_t o;
    cf_params_t p;
    printf("\n[10] The same frames through the detection-driven fit of --frames (camera uva2013's "
           "focal,\n     start: the nominal nao4-bottom-320 neck and pitch offset, roll 0; "
           "detected line points, no labels):\n");
    if (!field || !m || !nominal || cf_frames_from_uva(set, dir, &fr) != 0) {
        printf("    not available\n");
        return;
    }
    cf_options_default(&o);
    o.fit_heading = 1; /* the file-name poses are off by several degrees ([8]) */
    p.neck_mm = nominal->default_neck_height_mm;
    p.pitch_offset_deg = nominal->default_pitch_offset * 360.0 / 65536.0;
    p.roll_offset_deg = 0;
    if (cal_frames_run(&fr, "uva2013 frames", field, m, &o, &p, 0) == 0) {
        cf_result_t res;
        char err[256];
        printf("    hand-label fit [4] for comparison: neck_height_mm %.1f, pitch_offset_deg "
               "%.3f (roll not fitted)\n",
               label->p[CAL_NECK], label->p[CAL_PITCH] * CAL_DEG);
        /* the label camera on the same residual: only the poses refitted */
        o.fit_neck = o.fit_pitch = o.fit_roll = 0;
        o.grid = 0;
        p.neck_mm = label->p[CAL_NECK];
        p.pitch_offset_deg = label->p[CAL_PITCH] * CAL_DEG;
        p.roll_offset_deg = 0;
        if (cf_fit(&fr, field, m, &o, &p, &res, NULL, NULL, err, sizeof err) == 0) {
            printf("    that camera on this residual (poses refitted): %d in, median %.2f px, "
                   "rms %.2f px\n",
                   res.after_all.n_in, res.after_all.median_px, res.after_all.rms_px);
            cf_result_free(&res);
        }
    }
    cf_frames_free(&fr);
}

int cmd_calibrate(int argc, char **argv)
{
    const unsigned POSE = CAL_FIT_POSE_HEADING | CAL_FIT_POSE_XY;
    const char *dir = NULL;
    char path[4096], err[256];
    rd_uva_set_t set;
    cal_problem_t pb;
    const fl_field_t *field = fl_field_find("uva2013");
    const fl_camera_model_t *bottom = fl_camera_model_find("nao4-bottom-320");
    const fl_camera_model_t *top = fl_camera_model_find("nao4-top-320");
    const fl_camera_model_t *committed = fl_camera_model_find("uva2013");
    cal_params_t p, best;
    cal_result_t r;
    int i, verbose = 0, n_per[5] = {0}, roll = 1, heading = 0;
    const char *frames = NULL, *field_name = NULL, *cam_name = NULL, *out = NULL;

    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--dir") && i + 1 < argc)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--verbose"))
            verbose = 1;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = argv[++i];
        else if (!strcmp(argv[i], "--field") && i + 1 < argc)
            field_name = argv[++i];
        else if (!strcmp(argv[i], "--camera") && i + 1 < argc)
            cam_name = argv[++i];
        else if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--no-roll"))
            roll = 0;
        else if (!strcmp(argv[i], "--fit-heading"))
            heading = 1;
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            cal_usage();
            return 0;
        } else
            return arg_unknown("calibrate", argv[i],
                               "--dir=1 --frames=1 --field=1 --camera=1 --out=1");
    }
    if (frames) {
        if (dir || verbose)
            return cal_usage();
        return cal_frames_cmd(frames, field_name, cam_name, out, roll, heading);
    }
    if (field_name || cam_name || !roll || heading)
        return cal_usage();
    if (!dir)
        dir = rd_dir();
    if (!dir) {
        printf("calibrate: %s\n", rd_skip_message());
        return 0;
    }
    if (!field || !bottom || !top) {
        fprintf(stderr, "calibrate: field uva2013 or NAO v4 cameras missing from the catalogue\n");
        return 1;
    }
    if (rd_path(path, sizeof path, dir, RD_UVA_CSV) != 0 ||
        rd_uva_load(path, &set, err, sizeof err) != 0) {
        fprintf(stderr, "calibrate: %s\n", err);
        return 1;
    }
    if (set.n > CAL_MAX_REC || cal_problem_init(&pb, &set, field) != 0) {
        fprintf(stderr, "calibrate: cannot build the problem\n");
        rd_uva_free(&set);
        return 1;
    }
    for (i = 0; i < pb.n_obs; i++)
        n_per[strchr("XLTGU", pb.obs[i].type) - "XLTGU"]++;
    printf("UvA 2013 labels: %s: %d images, %d labels (X %d, L %d, T %d, G %d, U %d); "
           "field uva2013 (%d map points)\n",
           path, set.n, pb.n_obs, n_per[0], n_per[1], n_per[2], n_per[3], n_per[4], pb.n_lm);
    printf("Residual = |projection of the nearest map point of the label's kind - label|, px;\n"
           "inliers <= 8 px.  'pose-corrected': each image's heading and x/y refitted\n"
           "(prior 5 deg, 100 mm); 'file poses': the poses of the file names.\n");

    /* nominal values (DESIGN.md) */
    cal_params_init(&p, bottom, field);
    cal_evaluate(&pb, &p, 40.0, 8.0);
    printf("\n[1] Nominal nao4-bottom-320 (f %.1f px, neck %.0f mm, pitch offset 0), file poses, "
           "no fit:\n",
           p.p[CAL_FOCAL], p.p[CAL_NECK]);
    print_kinds(&pb, "    ");

    printf("\n[2] Fit neck, pitch offset, focal, post height on the file poses (bottom mounting):\n");
    if (run_fit(&pb, bottom, FIT_CAM, 0, &p, &r, -1) == 0) {
        print_params(&p, &r, FIT_CAM);
        print_kinds(&pb, "    ");
    } else
        printf("    fit failed\n");

    printf("\n[3] TOP camera mounting (58.7 fwd / 63.6 up, 1.2 deg), pose-corrected fit:\n");
    if (run_fit(&pb, top, FIT_CAM, POSE, &p, &r, -1) == 0) {
        print_params(&p, &r, FIT_CAM);
        print_kinds(&pb, "    ");
        printf("    optical axis %.1f deg below horizontal at HeadPitch %.3f, camera %.0f mm "
               "high\n",
               tilt_deg(&p), HP_TYPICAL, cam_height(&p));
    } else
        printf("    fit failed\n");

    printf("\n[4] BOTTOM camera mounting (50.7 fwd / 17.7 up, 39.7 deg), pose-corrected fit "
           "(the committed model):\n");
    if (run_fit(&pb, bottom, FIT_CAM, POSE, &p, &r, -1) != 0) {
        printf("    fit failed\n");
        cal_problem_free(&pb);
        rd_uva_free(&set);
        return 1;
    }
    best = p;
    print_params(&p, &r, FIT_CAM);
    print_kinds(&pb, "    ");
    printf("    optical axis %.1f deg below horizontal at HeadPitch %.3f, camera %.0f mm high\n",
           tilt_deg(&p), HP_TYPICAL, cam_height(&p));
    printf("    outliers (pose-corrected):\n");
    print_outliers(&pb, &p);
    printf("  same camera, file poses:\n");
    file_pose_residuals(&pb, &best);
    print_kinds(&pb, "    ");

    /* prior sensitivity */
    {
        static const double sig[][2] = {{2.5, 50}, {10, 200}, {5, 30}};
        size_t k;
        printf("\n  prior sensitivity of [4] (heading sigma deg, x/y sigma mm):\n");
        for (k = 0; k < sizeof sig / sizeof sig[0]; k++) {
            cal_options_t o;
            double med, mx;
            cal_options_default(&o);
            o.fit_mask = FIT_CAM;
            o.pose_mask = POSE;
            o.sigma_heading_deg = sig[k][0];
            o.sigma_xy_mm = sig[k][1];
            cal_params_init(&p, bottom, field);
            if (cal_fit(&pb, &o, &p, &r) != 0) {
                printf("    %4.1f deg %3.0f mm: fit failed\n", sig[k][0], sig[k][1]);
                continue;
            }
            cal_residual_stats(&pb, "XLTGU", 1, -1, &med, &mx);
            printf("    %4.1f deg %3.0f mm: neck %.1f mm, pitch offset %.2f deg, focal %.1f px; "
                   "inliers %d, median %.2f px\n",
                   sig[k][0], sig[k][1], p.p[CAL_NECK], p.p[CAL_PITCH] * CAL_DEG,
                   p.p[CAL_FOCAL], r.n_used, med);
        }
    }

    /* extra parameters */
    {
        static const struct {
            const char *what;
            unsigned mask;
        } ext[] = {
            {"+ principal point", FIT_CAM | CAL_BIT(CAL_CX) | CAL_BIT(CAL_CY)},
            {"+ roll", FIT_CAM | CAL_BIT(CAL_ROLL)},
            {"+ radial k1", FIT_CAM | CAL_BIT(CAL_K1)},
            {"+ yaw offset (file poses; with pose corrections it is their mean)",
             FIT_CAM | CAL_BIT(CAL_YAW)},
        };
        size_t e;
        printf("\n[5] Extra parameters (bottom mounting, pose-corrected unless noted):\n");
        for (e = 0; e < sizeof ext / sizeof ext[0]; e++) {
            double med, mx;
            unsigned pm = (ext[e].mask & CAL_BIT(CAL_YAW)) ? 0u : POSE;
            printf("  %s:\n", ext[e].what);
            if (run_fit(&pb, bottom, ext[e].mask, pm, &p, &r, -1) != 0) {
                printf("    fit failed\n");
                continue;
            }
            print_params(&p, &r, ext[e].mask);
            cal_residual_stats(&pb, "XLTGU", 1, -1, &med, &mx);
            printf("    all kinds, inliers: median %.2f px, max %.2f px\n", med, mx);
            if (verbose)
                print_kinds(&pb, "    ");
        }
    }

    /* field dimensions */
    {
        static const struct {
            const char *what;
            unsigned mask;
        } dv[] = {
            {"focal fixed at the NAO v4 data sheet's 272.2 px (breaks the f / lateral-scale "
             "degeneracy)",
             CAL_BIT(CAL_NECK) | CAL_BIT(CAL_PITCH) | CAL_FIT_DIMS},
            {"focal free (f, neck and the lateral dimensions are nearly degenerate: u ~ f y / x, "
             "v ~ f h / x)",
             CAL_FIT_BASE | CAL_FIT_DIMS},
        };
        size_t k;
        cal_params_t nom;
        cal_params_init(&nom, bottom, field);
        printf("\n[6] Field dimensions, fitted with the camera, pose-corrected (DESIGN.md "
               "values in brackets):\n");
        for (k = 0; k < sizeof dv / sizeof dv[0]; k++) {
            double med, mx;
            printf("  %s:\n", dv[k].what);
            if (run_fit(&pb, bottom, dv[k].mask, POSE, &p, &r, -1) != 0) {
                printf("    fit failed\n");
                continue;
            }
            for (i = 0; i < CAL_NP; i++) {
                if (!(dv[k].mask & CAL_BIT(i)))
                    continue;
                printf("    %-28s %9.1f +- %5.1f", cal_param_name(i),
                       cal_param_display(i, p.p[i]), cal_param_display(i, r.sigma[i]));
                if (i >= CAL_HALF_L)
                    printf("  [%.0f]  %+.1f%%", nom.p[i], 100.0 * (p.p[i] / nom.p[i] - 1.0));
                printf("\n");
            }
            cal_residual_stats(&pb, "XLTGU", 1, -1, &med, &mx);
            printf("    labels used %d, outliers %d, rms %.2f px; inliers median %.2f max %.2f "
                   "px\n",
                   r.n_used, r.n_outliers, r.rms_px, med, mx);
        }
    }

    /* leave one image out */
    {
        double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
        printf("\n[7] Leave-one-image-out: camera fitted (pose-corrected) without the image; "
               "that image's labels with its file pose, and with only its heading/x/y refitted:\n");
        printf("    %-19s %-15s %3s %15s %15s\n", "image", "pose cm,deg", "n", "file med/max",
               "refit med/max");
        for (i = 0; i < set.n; i++) {
            double m1, x1, m2, x2;
            int n;
            char pose[48], name[48];
            cal_options_t o;
            cal_result_t rr;
            if (set.rec[i].n_features == 0)
                continue;
            if (run_fit(&pb, bottom, FIT_CAM, POSE, &p, &r, i) != 0) {
                printf("    %s_%s: fit failed\n", set.rec[i].set, set.rec[i].index);
                continue;
            }
            lo[0] = fmin(lo[0], p.p[CAL_NECK]);
            hi[0] = fmax(hi[0], p.p[CAL_NECK]);
            lo[1] = fmin(lo[1], p.p[CAL_PITCH] * CAL_DEG);
            hi[1] = fmax(hi[1], p.p[CAL_PITCH] * CAL_DEG);
            lo[2] = fmin(lo[2], p.p[CAL_FOCAL]);
            hi[2] = fmax(hi[2], p.p[CAL_FOCAL]);
            file_pose_residuals(&pb, &p);
            n = cal_residual_stats(&pb, "XLTGU", 0, i, &m1, &x1);
            /* the held-out pose only: camera fixed */
            cal_options_default(&o);
            o.fit_mask = 0;
            o.pose_mask = POSE;
            o.grid_init = 0;
            memset(p.pose, 0, sizeof p.pose);
            if (cal_fit(&pb, &o, &p, &rr) == 0)
                cal_residual_stats(&pb, "XLTGU", 0, i, &m2, &x2);
            else
                m2 = x2 = -1;
            snprintf(pose, sizeof pose, "%g,%g,%g", set.rec[i].x_cm, set.rec[i].y_cm,
                     set.rec[i].theta_deg);
            snprintf(name, sizeof name, "%s_%s", set.rec[i].set, set.rec[i].index);
            printf("    %-19s %-15s %3d %7.2f %7.2f %7.2f %7.2f\n", name, pose, n, m1, x1, m2,
                   x2);
        }
        printf("    range of the leave-one-out fits: neck %.1f..%.1f mm, pitch offset "
               "%.2f..%.2f deg, focal %.1f..%.1f px\n",
               lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
    }

    /* per image, committed fit */
    p = best;
    printf("\n[8] Per image, fit [4]: pose correction and residuals (pose-corrected | file "
           "poses), matched labels incl. outliers:\n");
    printf("    %-19s %3s %8s %7s %7s | %13s | %13s\n", "image", "n", "dth_deg", "dx_cm",
           "dy_cm", "med/max", "file med/max");
    {
        double fm[CAL_MAX_REC], fx[CAL_MAX_REC];
        file_pose_residuals(&pb, &best);
        for (i = 0; i < set.n && i < CAL_MAX_REC; i++)
            cal_residual_stats(&pb, "XLTGU", 0, i, &fm[i], &fx[i]);
        cal_evaluate(&pb, &best, 40.0, 8.0);
        for (i = 0; i < set.n && i < CAL_MAX_REC; i++) {
            double med, mx;
            char name[48];
            int n = cal_residual_stats(&pb, "XLTGU", 0, i, &med, &mx);
            snprintf(name, sizeof name, "%s_%s", set.rec[i].set, set.rec[i].index);
            printf("    %-19s %3d %8.2f %7.1f %7.1f | %6.2f %6.2f | %6.2f %6.2f\n", name, n,
                   best.pose[i][CAL_POSE_TH] * CAL_DEG, best.pose[i][CAL_POSE_X] / 10,
                   best.pose[i][CAL_POSE_Y] / 10, med, mx, fm[i], fx[i]);
        }
    }

    printf("\n[9] Committed catalogue camera uva2013 through the firmware projection "
           "(fl_camera_ground_to_pixel,\n    its default pose, each image's head angles, file "
           "poses; nearest map point; U not checked):\n");
    if (committed) {
        printf("    model: f %.2f px, c (%.2f, %.2f) px, mount %d/%d mm tilt %.2f deg, neck %d mm, "
               "pitch offset %.2f deg\n",
               committed->focal_q4 / 16.0, committed->cx_q4 / 16.0, committed->cy_q4 / 16.0,
               (int)committed->mount_x_mm, (int)committed->mount_z_mm,
               committed->mount_tilt * 360.0 / 65536.0, (int)committed->default_neck_height_mm,
               committed->default_pitch_offset * 360.0 / 65536.0);
        printf("    fit [4] for comparison: f %.2f px, neck %.1f mm, pitch offset %.2f deg\n",
               best.p[CAL_FOCAL], best.p[CAL_NECK], best.p[CAL_PITCH] * CAL_DEG);
        firmware_check(&set, field, committed);
    } else
        printf("    not in the catalogue\n");

    cal_uva_frames(&set, dir, &best);
    i = 0;
    if (out) {
        cf_params_t cp;
        cp.neck_mm = best.p[CAL_NECK];
        cp.pitch_offset_deg = best.p[CAL_PITCH] * CAL_DEG;
        cp.roll_offset_deg = 0;
        i = cal_write(out, "uva2013", &cp, 0,
                      "fieldloc calibrate: UvA 2013 hand labels, fit [4] (bottom mounting, "
                      "pose-corrected)");
    }
    cal_problem_free(&pb);
    rd_uva_free(&set);
    return i;
}
