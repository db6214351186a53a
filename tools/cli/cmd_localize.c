/*
 * tools/cli/cmd_localize.c - `fieldloc localize`: the fuzzy grid on a sequence
 * of camera frames with odometry (format: tools/loc/locrun.h), and the UvA 2013
 * standing-spot evaluation on the real frames.
 *
 *   fieldloc localize SEQUENCE.txt [--pictures DIR] [--picture-every N]
 *                     [--param NAME=VALUE]...
 *   fieldloc localize --uva-spots [--pictures DIR] [--write-seq DIR]
 *   fieldloc localize --physar [--localizer NAME] [--repeat N] [--imu angles|accel|off]
 *                     [--colors default|auto|FILE] [--pictures DIR]
 *
 * Per frame, in file order: predict(odometry of the line, split and rounded
 * by lr_predict) ; read the image ; vision (fl_vision_frame, default color
 * tables; camera = the `camera` model at its default neck height and pitch
 * offset with the line's head angles) ; update ; estimate, and print
 *     pose X_MM Y_MM THETA_DEG RELIABILITY STATE sd SDX_MM SDY_MM SDH_DEG mirror M
 * (integers, one decimal in (-180, 180], three decimals in [0, 1]; the
 * confidence of localizer.h: state LOST / AMBIGUOUS / TRACKING, spread,
 * heading spread ("-": none), the mirror pose's weight), one
 * line per frame line, nothing else on stdout.  Localizer parameters:
 * lr_params_frames (tools/loc/locrun.c), changed by --param NAME=VALUE.  Start: total ignorance
 * without a prior; with `prior X Y THETA`: the known pose (reset_pose, 300
 * mm and 20 degrees of uncertainty) which also becomes the prior that
 * decides between symmetric modes (set_prior_pose, 1000 mm).
 *
 * Errors (messages on stderr, naming the file and line):
 *   - a sequence that cannot be read or does not parse (unknown keyword,
 *     wrong field count, bad number, unknown field or camera, no frame...):
 *     nothing is printed on stdout, exit status 2 (usage errors too);
 *   - a frame whose image is missing, unreadable or of the wrong size: the
 *     frame is SKIPPED with a message (its odometry is still applied and
 *     its pose line still printed, so the output keeps one line per frame)
 *     and the exit status is 3 at the end (0 when every frame was used).
 *
 * --calib CALIB (both modes): a per-robot calibration (fieldloc/calib.h,
 * written by `fieldloc calibrate --out`) applied to every frame's camera
 * pose after the model's defaults (fl_calib_apply: neck height, pitch and
 * roll offsets).  A file that does not parse ("FILE:LINE: reason") or is
 * for another camera than the sequence's: exit status 2.
 * --colors default|auto|FILE (both modes): the colour classes
 * (eval/colors_opt.h) of every frame's vision: the 2013 boxes, the field
 * colour estimated on the first frame and tracked frame by frame, or a
 * colour file (one that does not parse: "fieldloc localize: FILE:LINE:
 * reason", exit status 2).  Without it: auto for a white-goal field or
 * real frames outside the UvA 2013 set, else default.
 *
 * --pictures DIR writes DIR/frame_NNNNN.ppm (+ .png): the frame
 * with the detected features and the field model seen from the estimate,
 * next to the belief (the grid's cells, or a particle filter's particles:
 * tools/eval/picture.h); every frame, or every Nth with --picture-every N.
 *
 * --uva-spots: the UvA 2013 qvga frames of the real-data
 * folder (tools/io/realdata.h; skipped with a message when absent) grouped by
 * standing spot (x_cm, y_cm), ordered by heading, each spot run as its own
 * sequence from total ignorance: field uva2013, camera uva2013, odometry =
 * the heading difference to the previous frame (turning in place, no
 * translation).  Prints per frame the estimate and its error, and per spot
 * the final error, position and heading, taken modulo the field's
 * 180-degree symmetry: the labelled pose or its mirror (-x, -y, theta +
 * 180), whichever is closer by position error + 17.5 mm per degree of
 * heading error (1 m per radian), so that at the centre spot, where both
 * positions are the same, the heading decides.  --write-seq DIR also writes each
 * spot as a sequence file DIR/uva_spot_X_Y.txt (absolute image paths), so
 * `fieldloc localize DIR/uva_spot_X_Y.txt` reproduces its pose lines.
 *
 * --physar: the physar black1 points of the real-data folder (NAO v6 top
 * frames, 640x480, field spl2020, OptiTrack truth; tools/loc/physar.h has
 * the method): each frame --repeat N times (default 10) with zero
 * odometry from total ignorance, camera pose from the record's head angles
 * and IMU torso roll/pitch; every localizer of the catalogue side by side
 * (--localizer NAME: that one only; --param needs --localizer).  Prints a
 * "# ..." header, per point one line per localizer
 *     physar LOC POINT truth X Y H est X Y H rel R STATE sym_err MM mm DEG deg
 *            [(mirror)] plain MM mm DEG deg seen N [KINDS] used N map N [KINDS]
 *            goal met|MISSED|n/a
 * and per localizer
 *     physar_summary LOC points N goal_met K of M sym_pos_rmse_mm E
 *            sym_pos_max_mm E sym_heading_rmse_deg D (...)
 * (truth heading: the README's nominal one, approximate; sym = modulo the
 * 180-degree symmetry, the plain errors after them; seen = vision's
 * observations by kind, map = map landmarks in view from the truth pose;
 * goal: sym error <= 300 mm where seen >= 2).  --pictures DIR writes
 * DIR/physar_LOC_POINT.ppm (+ .png): the frame with vision and the model
 * seen from the estimate, beside the belief with the truth.  --imu: the
 * torso roll and pitch of the camera pose: "accel" (default) the tilt of
 * the records' accelerometer, "angles" the records' AngleX / AngleY, "off"
 * none (head angles only).  The accelerometer is the default because
 * AngleY reads about 0.087 rad below it at every one of the five standing
 * points and the frames side with the accelerometer (tools/loc/physar.h;
 * the labels' note on point 2: the circle crossings, the goal width and
 * the far line fit a pitch about 0.095 rad above AngleY's).  Absent folder:
 * one "physar: skipped: ..." line, exit status 0.
 * Without --colors the frames take the policy of eval/colors_opt.h (auto
 * on these frames).
 */
#include "loc/locrun.h"
#include "loc/physar.h"
#include "eval/calib_frames.h"
#include "cli/args.h"
#include "eval/picture.h"
#include "io/ppm.h"
#include "io/realdata.h"
#include "cli/registry.h"
#include "world/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define LZ_PI 3.14159265358979323846

static int lz_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc localize SEQUENCE.txt [--pictures DIR] [--picture-every N]\n"
            "       fieldloc localize --uva-spots [--pictures DIR] [--write-seq DIR]\n"
            "       fieldloc localize --physar [--localizer NAME] [--repeat N]\n"
            "                                  [--imu accel|angles|off] [--pictures DIR]\n"
            "       (both: [--param NAME=VALUE]... localizer parameters,\n"
            "        [--calib CALIB] per-robot calibration from `fieldloc calibrate --out`,\n"
            "        [--colors default|auto|FILE] colour classes: the 2013 boxes, from the\n"
            "        frames (tracked), or a file from `fieldloc colors|calibrate-colors`)\n"
            "  SEQUENCE.txt: 'field NAME', 'camera NAME', optional 'prior X_MM Y_MM THETA_DEG',\n"
            "  then per frame 'frame IMAGE.ppm odo DX_MM DY_MM DTHETA_DEG head PITCH_RAD YAW_RAD'\n"
            "  prints per frame: pose X_MM Y_MM THETA_DEG RELIABILITY STATE sd X Y DEG mirror M\n"
            "  --picture-every 1..1000000; --physar: --repeat 1..1000 frames per point (10)\n");
    return 2;
}

/* ---- UvA 2013 standing spots ------------------------------------------------ */

typedef struct {
    double x_cm, y_cm;
    int idx[32];
    int n;
} lz_spot_t;

static int lz_uva_spots(const char *pictures, const char *write_seq,
                        const fl_localizer_t *loc, const void *params, const fl_calib_t *calib,
                        const colors_opt_t *colors)
{
    const char *dir = rd_dir();
    char path[1200], err[256];
    rd_uva_set_t set;
    lz_spot_t spot[64];
    int nspot = 0, i, j, s, total = 0;
    double se_p = 0, se_h = 0;
    int n_err = 0;
    const fl_field_t *field = fl_field_find("uva2013");
    const fl_camera_model_t *cam = fl_camera_model_find("uva2013");
    if (calib != NULL && (calib->has & FL_CALIB_HAS_CAMERA) && strcmp(calib->camera, "uva2013")) {
        fprintf(stderr, "localize: the calibration is for camera %s, --uva-spots uses uva2013\n",
                calib->camera);
        return 2;
    }
    if (dir == NULL) {
        printf("uva-spots: %s\n", rd_skip_message());
        return 0;
    }
    if (rd_path(path, sizeof path, dir, RD_UVA_CSV) != 0 ||
        rd_uva_load(path, &set, err, (int)sizeof err) != 0) {
        fprintf(stderr, "localize: %s: %s\n", RD_UVA_CSV, err);
        return 1;
    }
    for (i = 0; i < set.n; i++) {
        const rd_uva_record_t *r = &set.rec[i];
        if (strcmp(r->set, "qvga") != 0 || !r->in_realdata)
            continue;
        for (s = 0; s < nspot; s++)
            if (spot[s].x_cm == r->x_cm && spot[s].y_cm == r->y_cm)
                break;
        if (s == nspot) {
            if (nspot == 64)
                continue;
            spot[s].x_cm = r->x_cm;
            spot[s].y_cm = r->y_cm;
            spot[s].n = 0;
            nspot++;
        }
        if (spot[s].n < 32)
            spot[s].idx[spot[s].n++] = i;
        total++;
    }
    printf("# uva-spots: %d qvga frames in %s at %d standing spots; field uva2013, camera "
           "uva2013;\n# per spot: frames ordered by heading, odometry = heading difference "
           "(turn in place), start in total ignorance; errors modulo the 180-degree symmetry\n",
           total, dir, nspot);
    if (pictures != NULL)
        mkdir(pictures, 0777);
    if (write_seq != NULL)
        mkdir(write_seq, 0777);
    for (s = 0; s < nspot; s++) {
        lz_spot_t *sp = &spot[s];
        lr_seq_t seq;
        lr_frame_result_t res[32];
        lr_seq_opts_t o;
        char name[64], prefix[64];
        int rc;
        /* order by heading (insertion sort) */
        for (i = 1; i < sp->n; i++)
            for (j = i; j > 0 && set.rec[sp->idx[j]].theta_deg < set.rec[sp->idx[j - 1]].theta_deg;
                 j--) {
                int t = sp->idx[j];
                sp->idx[j] = sp->idx[j - 1];
                sp->idx[j - 1] = t;
            }
        memset(&seq, 0, sizeof seq);
        seq.field = field;
        seq.camera = cam;
        seq.frame = calloc((size_t)sp->n, sizeof *seq.frame);
        if (seq.frame == NULL)
            break;
        seq.n = seq.cap = sp->n;
        for (i = 0; i < sp->n; i++) {
            const rd_uva_record_t *r = &set.rec[sp->idx[i]];
            lr_seq_frame_t *f = &seq.frame[i];
            if (rd_path(f->image, sizeof f->image, dir, r->file) != 0)
                f->image[0] = '\0';
            f->line = i + 1;
            f->odo_dtheta_deg = i == 0 ? 0.0 : r->theta_deg - set.rec[sp->idx[i - 1]].theta_deg;
            f->head_pitch_rad = r->head_pitch_rad;
            f->head_yaw_rad = r->head_yaw_rad;
        }
        snprintf(name, sizeof name, "uva_spot_%.0f_%.0f", sp->x_cm, sp->y_cm);
        if (write_seq != NULL) {
            FILE *wf;
            snprintf(path, sizeof path, "%s/%s.txt", write_seq, name);
            wf = fopen(path, "w");
            if (wf != NULL) {
                char abs[LR_PATH_MAX];
                fprintf(wf, "# UvA 2013 qvga frames at (%.0f, %.0f) cm, ordered by heading\n"
                            "field uva2013\ncamera uva2013\n",
                        sp->x_cm, sp->y_cm);
                for (i = 0; i < sp->n; i++) {
                    const char *img = seq.frame[i].image;
                    if (img[0] != '/' && realpath(img, abs) != NULL)
                        img = abs;
                    fprintf(wf, "frame %s odo 0 0 %.3f head %.6f %.6f\n", img,
                            seq.frame[i].odo_dtheta_deg, seq.frame[i].head_pitch_rad,
                            seq.frame[i].head_yaw_rad);
                }
                fclose(wf);
            }
        }
        memset(&o, 0, sizeof o);
        o.name = name;
        o.pictures = pictures;
        snprintf(prefix, sizeof prefix, "%.60s_", name);
        o.picture_prefix = prefix;
        o.picture_every = 1;
        o.loc = loc;
        o.params = params;
        o.calib = calib;
        o.colors = colors;
        rc = lr_seq_run(&seq, &o, res);
        if (rc < 0) {
            free(seq.frame);
            break;
        }
        for (i = 0; i < sp->n; i++) {
            const rd_uva_record_t *r = &set.rec[sp->idx[i]];
            const fl_loc_estimate_t *e = &res[i].est;
            double pe, he, mpe, mhe, ex = e->x_mm, ey = e->y_mm, eh = lr_deg(e->heading);
            int mir;
            lr_pose_error(ex, ey, eh, r->x_cm * 10, r->y_cm * 10, r->theta_deg, &pe, &he, &mpe,
                          &mhe);
            mir = mpe + 17.5 * mhe < pe + 17.5 * he;   /* the mirror is closer */
            printf("spot %.0f %.0f frame %d %s theta %.0f obs %d used %d est %d %d %.1f rel %.3f "
                   "%s err %.0f mm %.1f deg%s\n",
                   sp->x_cm, sp->y_cm, i + 1, r->index, r->theta_deg, res[i].obs,
                   res[i].used < 0 ? 0 : res[i].used, (int)e->x_mm, (int)e->y_mm, eh,
                   e->reliability_q16 / 65536.0, lr_state_name(e->state), mir ? mpe : pe,
                   mir ? mhe : he,
                   mir ? " (mirror)" : "");
            if (i == sp->n - 1) {
                double fp = mir ? mpe : pe, fh = mir ? mhe : he;
                printf("spot_result %.0f %.0f frames %d pos_err_mm %.0f heading_err_deg %.1f "
                       "reliability %.3f\n",
                       sp->x_cm, sp->y_cm, sp->n, fp, fh, e->reliability_q16 / 65536.0);
                se_p += fp * fp;
                se_h += fh * fh;
                n_err++;
            }
        }
        free(seq.frame);
    }
    if (n_err > 0)
        printf("uva_spots %d pos_rmse_mm %.0f heading_rmse_deg %.1f (final estimate per spot, "
               "modulo symmetry)\n",
               n_err, sqrt(se_p / n_err), sqrt(se_h / n_err));
    rd_uva_free(&set);
    return 0;
}

/* ---- physar black1 points --------------------------------------------------- */

static int lz_physar(const char *pictures, const fl_localizer_t *only, const void *params,
                     int repeat, ph_imu_t imu, const colors_opt_t *colors)
{
    ph_opts_t o;
    ph_result_t *res;
    char err[512];
    int n_loc = 0, i, k, rc;
    memset(&o, 0, sizeof o);
    o.repeat = repeat;
    o.colors = colors;
    o.pictures = pictures;
    o.params = params;
    o.imu = imu;
    if (rd_dir() == NULL) {
        printf("physar: %s\n", rd_skip_message());
        return 0;
    }
    res = calloc(fl_localizer_count() + 1u, sizeof *res);
    if (res == NULL) {
        fprintf(stderr, "localize: out of memory\n");
        return 1;
    }
    for (i = 0; i < (int)fl_localizer_count(); i++) {
        const fl_localizer_t *loc = fl_localizer_get((uint16_t)i);
        if (only != NULL && loc != only)
            continue;
        rc = ph_run(loc, &o, &res[n_loc], err, (int)sizeof err);
        if (rc != 0) {
            fprintf(stderr, "localize: physar (%s): %s\n", loc->name,
                    rc > 0 ? rd_skip_message() : err);
            free(res);
            return 1;
        }
        n_loc++;
    }
    ph_print_header(stdout, &o);
    for (k = 0; n_loc > 0 && k < res[0].n; k++)
        for (i = 0; i < n_loc; i++)
            if (k < res[i].n)
                ph_print_point(stdout, &res[i], &res[i].pt[k]);
    for (i = 0; i < n_loc; i++)
        ph_print_summary(stdout, &res[i]);
    free(res);
    return 0;
}

int cmd_localize(int argc, char **argv)
{
    const char *seq_path = NULL, *pictures = NULL, *write_seq = NULL;
    int uva = 0, physar = 0, imu = PH_IMU_ACCEL, imu_given = 0, repeat = PH_REPEAT_DEFAULT, repeat_given = 0, every = 1, k, rc;
    lr_seq_t seq;
    lr_seq_opts_t o;
    char err[512];
    const char *localizer = NULL, *param[64], *calib_path = NULL;
    fl_calib_t calib;
    colors_opt_t colors;
    int n_param = 0;
    const fl_localizer_t *loc;
    void *params;
    memset(&colors, 0, sizeof colors);   /* COLORS_UNSET: the policy decides */
    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--pictures") && k + 1 < argc)
            pictures = argv[++k];
        else if (!strcmp(argv[k], "--picture-every") && k + 1 < argc) {
            if (arg_int("localize", "--picture-every", argv[++k], 1, 1000000, NULL, &every) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--write-seq") && k + 1 < argc)
            write_seq = argv[++k];
        else if (!strcmp(argv[k], "--uva-spots"))
            uva = 1;
        else if (!strcmp(argv[k], "--physar"))
            physar = 1;
        else if (!strcmp(argv[k], "--imu") && k + 1 < argc) {
            const char *v = argv[++k];
            imu_given = 1;
            if (!strcmp(v, "angles"))
                imu = PH_IMU_ANGLES;
            else if (!strcmp(v, "accel"))
                imu = PH_IMU_ACCEL;
            else if (!strcmp(v, "off"))
                imu = PH_IMU_OFF;
            else {
                fprintf(stderr, "fieldloc localize: --imu: \"%s\" is not angles, accel or off\n",
                        v);
                return 2;
            }
        }
        else if (!strcmp(argv[k], "--repeat") && k + 1 < argc) {
            if (arg_int("localize", "--repeat", argv[++k], 1, 1000, NULL, &repeat) != 0)
                return 2;
            repeat_given = 1;
        }
        else if (!strcmp(argv[k], "--calib") && k + 1 < argc)
            calib_path = argv[++k];
        else if (!strcmp(argv[k], "--colors") && k + 1 < argc) {
            if (colors_opt_parse("localize", argv[++k], &colors) != 0)
                return 2;
        }
        else if (!strcmp(argv[k], "--localizer") && k + 1 < argc)
            localizer = argv[++k];
        else if (!strcmp(argv[k], "--param") && k + 1 < argc) {
            if (n_param < 64)
                param[n_param++] = argv[++k];
        }
        else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            lz_usage();
            return 0;
        } else if (argv[k][0] == '-' && argv[k][1] != '\0')
            return arg_unknown("localize", argv[k],
                               "--pictures=1 --picture-every=1 --write-seq=1 --localizer=1 "
                               "--param=1 --calib=1 --colors=1 --repeat=1 --imu=1");
        else if (seq_path == NULL)
            seq_path = argv[k];
        else
            return arg_unknown("localize", argv[k], NULL);
    }
    if (calib_path != NULL && cf_calib_load(calib_path, &calib, err, (int)sizeof err) != 0) {
        fprintf(stderr, "localize: %s\n", err);
        return 2;
    }
    if (uva + physar > 1 || ((repeat_given || imu_given) && !physar) ||
        (physar && (seq_path != NULL || write_seq != NULL || calib_path != NULL ||
                    (n_param > 0 && localizer == NULL))))
        return lz_usage();
    if ((loc = lr_localizer(localizer, err, (int)sizeof err)) == NULL) {
        fprintf(stderr, "localize: %s\n", err);
        return 2;
    }
    if ((params = lr_params_new(loc)) == NULL) {
        fprintf(stderr, "localize: out of memory\n");
        return 1;
    }
    lr_params_frames(loc, params);
    for (k = 0; k < n_param; k++) {
        if (lr_param_set(loc, params, param[k]) != 0) {
            fprintf(stderr, "localize: bad --param '%s' (NAME=INTEGER, a parameter of "
                            "localizer %s, in range)\n", param[k], loc->name);
            free(params);
            return 2;
        }
    }
    if (physar) {
        rc = lz_physar(pictures, localizer != NULL ? loc : NULL, localizer != NULL ? params : NULL,
                       repeat, (ph_imu_t)imu, &colors);
        free(params);
        return rc;
    }
    if (uva) {
        rc = seq_path != NULL ? lz_usage() : lz_uva_spots(pictures, write_seq, loc, params,
                                                           calib_path ? &calib : NULL,
                                                           &colors);
        free(params);
        return rc;
    }
    if (seq_path == NULL || write_seq != NULL) {
        free(params);
        return lz_usage();
    }
    if (lr_seq_load(seq_path, &seq, err, (int)sizeof err) != 0) {
        fprintf(stderr, "localize: %s: %s\n", seq_path, err);
        free(params);
        return 2;
    }
    if (calib_path != NULL && (calib.has & FL_CALIB_HAS_CAMERA) &&
        strcmp(calib.camera, seq.camera->name) != 0) {
        fprintf(stderr, "localize: %s is for camera %s, the sequence uses %s\n", calib_path,
                calib.camera, seq.camera->name);
        lr_seq_free(&seq);
        free(params);
        return 2;
    }
    if (pictures != NULL)
        mkdir(pictures, 0777);
    memset(&o, 0, sizeof o);
    o.calib = calib_path != NULL ? &calib : NULL;
    o.colors = &colors;
    o.out = stdout;
    o.name = seq_path;
    o.pictures = pictures;
    o.picture_prefix = "frame_";
    o.picture_every = every;
    o.loc = loc;
    o.params = params;
    rc = lr_seq_run(&seq, &o, NULL);
    free(params);
    k = seq.n;
    lr_seq_free(&seq);
    if (rc < 0)
        return 1;
    if (rc > 0) {
        fprintf(stderr, "localize: %d of %d frames skipped (no usable image)\n", rc, k);
        return 3;
    }
    return 0;
}
