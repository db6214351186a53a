/*
 * tools/loc/physar.c - the physar black1 evaluation (physar.h).
 *
 * Algorithm: per point, a fresh localizer (lr_init: total ignorance), then
 * `repeat` times lr_predict(0) + lr_frame on the same image and camera
 * pose; the estimate after the last frame is scored against the OptiTrack
 * truth and its 180-degree mirror.  The map landmarks in view are the
 * field's landmarks transformed into the robot frame at the truth pose and
 * projected with the frame's camera (fl_camera_ground_to_pixel).
 * Memory: one lr_t (localizer state, vision context) and one image at a
 * time.  Cost: repeat x (vision + update) per point.
 */
#include "loc/physar.h"
#include "eval/picture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PH_PI 3.14159265358979323846
#define PH_EDGE_PX 4

static const char ph_kind_letter[FL_LM_KIND_COUNT] = {'L', 'T', 'X', 'P', 'M', 'G', 'C',
                                                          'B', 'c', 'f', 'n', 'N'};

void ph_kinds(const int *count, char *buf, size_t n)
{
    size_t o = 0;
    int k;
    if (n == 0)
        return;
    buf[0] = '\0';
    for (k = 0; k < FL_LM_KIND_COUNT; k++) {
        int w;
        if (count[k] <= 0)
            continue;
        w = snprintf(buf + o, n - o, "%s%c%d", o ? " " : "", ph_kind_letter[k], count[k]);
        if (w < 0 || (size_t)w >= n - o)
            break;
        o += (size_t)w;
    }
    if (o == 0)
        snprintf(buf, n, "-");
}

static double ph_wrap_deg(double d)
{
    d = fmod(d, 360.0);
    if (d > 180.0)
        d -= 360.0;
    if (d <= -180.0)
        d += 360.0;
    return d;
}

/* Map landmarks that project at least PH_EDGE_PX inside the image from
 * the truth pose (robot at x, y with heading h_deg). */
static void ph_map_in_view(const fl_field_t *f, const fl_camera_t *cam, double x, double y,
                           double h_deg, ph_point_t *p)
{
    double h = h_deg * (PH_PI / 180.0), c = cos(h), s = sin(h);
    int32_t w = cam->model.width_px, ht = cam->model.height_px;
    uint16_t i;
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *lm = &f->landmarks[i];
        double dx = lm->x_mm - x, dy = lm->y_mm - y;
        fl_point_t g;
        int32_t uq, vq;
        if ((int)lm->kind < 0 || lm->kind >= FL_LM_KIND_COUNT)
            continue;
        g.x_mm = (int32_t)lround(c * dx + s * dy);
        g.y_mm = (int32_t)lround(-s * dx + c * dy);
        if (!fl_camera_ground_to_pixel(cam, g, &uq, &vq))
            continue;
        if (uq < 16 * PH_EDGE_PX || uq > 16 * (w - 1 - PH_EDGE_PX) || vq < 16 * PH_EDGE_PX ||
            vq > 16 * (ht - 1 - PH_EDGE_PX))
            continue;
        p->map[lm->kind]++;
        p->n_map++;
    }
}

/* The picture of a point: the frame with vision and the field model seen
 * from the estimate, beside the belief with the truth. */
static void ph_picture(const ph_opts_t *o, lr_t *lr, const fl_image_t *view,
                       const ph_point_t *p)
{
    host_image_t belief, frame, both;
    pic_pose_t ep, tp;
    char base[1200], info[256], caption[600];
    ep.x_mm = p->est.x_mm;
    ep.y_mm = p->est.y_mm;
    ep.heading_deg = p->est_heading_deg;
    tp.x_mm = p->mirror ? -p->truth_x_mm : p->truth_x_mm;
    tp.y_mm = p->mirror ? -p->truth_y_mm : p->truth_y_mm;
    tp.heading_deg = ph_wrap_deg(p->truth_heading_deg + (p->mirror ? 180.0 : 0.0));
    if (lr_mkdirs(o->pictures) != 0 ||
        pic_belief(lr->loc, lr->state, lr->field, 0, &tp, &p->est, &lr->obs, &belief) != 0)
        return;
    snprintf(base, sizeof base, "%s/physar_%s_%s", o->pictures, lr->loc->name, p->point);
    pic_belief_caption(info, sizeof info, -1, o->repeat, &p->est, p->sym_pos_err_mm,
                       p->sym_head_err_deg);
    snprintf(caption, sizeof caption,
             "%s (%s, %d frames; truth: OptiTrack, nominal heading; errors modulo symmetry)  %s",
             p->point, lr->loc->name, o->repeat, info);
    if (pic_frame(&lr->det, view, &lr->cam, lr->field, &ep, 1, &frame) == 0) {
        if (pic_side_by_side(&frame, &belief, 8, &both) == 0) {
            if (pic_legend_inplace(&both, PIC_LEGEND_DETECT | PIC_LEGEND_MODEL |
                                              PIC_LEGEND_TRUTH |
                                              pic_belief_legend(lr->loc, lr->state),
                                   caption) == 0)
                pic_save(&both, base, 1, NULL);
            host_image_free(&both);
        }
        host_image_free(&frame);
    }
    host_image_free(&belief);
}

/* The torso tilt from the accelerometer of the point's record.csv (the
 * frame's name with _top.ppm replaced by _record.csv; its last row). */
static int ph_accel_tilt(const char *dir, const rd_physar_record_t *r, double *roll,
                         double *pitch, char *err, int err_len)
{
    char name[RD_NAME_MAX + 16], path[1400], line[2][1024], *tok;
    const char *suffix = "_top.ppm";
    size_t n = strlen(r->image_top), ls = strlen(suffix);
    int col[3] = {-1, -1, -1}, k, c, have = 0;
    double acc[3] = {0, 0, 0};
    FILE *f;
    if (n <= ls || strcmp(r->image_top + n - ls, suffix) != 0) {
        snprintf(err, (size_t)err_len, "%s: no record file name", r->image_top);
        return -1;
    }
    snprintf(name, sizeof name, "%.*s_record.csv", (int)(n - ls), r->image_top);
    if (rd_path(path, sizeof path, dir, name) != 0 || (f = fopen(path, "r")) == NULL) {
        snprintf(err, (size_t)err_len, "%s: cannot read", name);
        return -1;
    }
    /* header, then data rows: keep the last one */
    if (fgets(line[0], sizeof line[0], f) == NULL) {
        fclose(f);
        snprintf(err, (size_t)err_len, "%s: empty", name);
        return -1;
    }
    for (c = 0, tok = strtok(line[0], ",\r\n"); tok != NULL; tok = strtok(NULL, ",\r\n"), c++)
        for (k = 0; k < 3; k++)
            if (!strcmp(tok, k == 0 ? "accelx" : k == 1 ? "accely" : "accelz"))
                col[k] = c;
    while (fgets(line[1], sizeof line[1], f) != NULL) {
        int got = 0;
        for (c = 0, tok = strtok(line[1], ",\r\n"); tok != NULL;
             tok = strtok(NULL, ",\r\n"), c++)
            for (k = 0; k < 3; k++)
                if (c == col[k]) {
                    char *end;
                    acc[k] = strtod(tok, &end);
                    got += end != tok && *end == '\0' && isfinite(acc[k]);
                }
        have = got == 3;
    }
    fclose(f);
    if (!have || acc[2] > -5.0) {
        snprintf(err, (size_t)err_len, "%s: no accelx, accely, accelz row of an upright robot",
                 name);
        return -1;
    }
    *pitch = atan2(acc[0], -acc[2]);
    *roll = atan2(-acc[1], -acc[2]);
    return 0;
}

/* One point: repeat x (vision + update), then the scores. */
static int ph_point(const fl_localizer_t *loc, const ph_opts_t *o, const char *dir,
                    const rd_physar_record_t *r, const fl_field_t *field,
                    const fl_camera_model_t *m, ph_point_t *p, char *err, int err_len)
{
    lr_t lr;
    colors_opt_t colors;
    char ipath[1400];
    host_image_t img;
    fl_image_t view;
    fl_camera_pose_t pose;
    char ierr[256];
    double pe, he, mpe, mhe;
    int k, used = -1;
    memset(p, 0, sizeof *p);
    snprintf(p->point, sizeof p->point, "%s", r->point);
    snprintf(p->image, sizeof p->image, "%s", r->image_top);
    p->truth_x_mm = r->ot_field_x_cm * 10.0;
    p->truth_y_mm = r->ot_field_y_cm * 10.0;
    p->truth_heading_deg = ph_wrap_deg(r->nominal_heading_deg);
    if (lr_init(&lr, loc, field, m, o->params, err, err_len) != 0)
        return -1;
    /* the colour classes: set up from the first frame (auto) and tracked
     * after every one by lr_frame */
    memset(&colors, 0, sizeof colors);
    if (o->colors != NULL)
        colors = *o->colors;
    if (rd_path(ipath, sizeof ipath, dir, r->image_top) != 0)
        ipath[0] = '\0';
    colors_opt_resolve(&colors, field, ipath);
    lr.colors = &colors;
    rd_physar_camera_pose(r, m, &pose);
    p->torso_roll_rad = r->imu_anglex_rad;
    p->torso_pitch_rad = r->imu_angley_rad;
    if (o->imu == PH_IMU_OFF) {
        pose.torso_roll = pose.torso_pitch = 0;
        p->torso_roll_rad = p->torso_pitch_rad = 0;
    } else if (o->imu == PH_IMU_ACCEL) {
        if (ph_accel_tilt(dir, r, &p->torso_roll_rad, &p->torso_pitch_rad, err, err_len) != 0) {
            lr_free(&lr);
            return -1;
        }
        pose.torso_roll = fl_angle_from_urad((int32_t)lround(p->torso_roll_rad * 1e6));
        pose.torso_pitch = fl_angle_from_urad((int32_t)lround(p->torso_pitch_rad * 1e6));
    }
    if (rd_read_ppm(dir, r->image_top, &img, ierr, (int)sizeof ierr) != 0) {
        fprintf(stderr, "physar: %s: %s (point skipped)\n", r->image_top, ierr);
        img.rgb = NULL;
    } else if (rd_image_view(&img, &view) == FL_OK) {
        for (k = 0; k < o->repeat; k++) {
            lr_predict(&lr, 0, 0, 0);
            used = lr_frame(&lr, &view, &pose);
            if (used < 0)
                break;
        }
        if (used < 0)
            fprintf(stderr, "physar: %s: image %dx%d does not fit camera %s or bad pose "
                            "(point skipped)\n",
                    r->image_top, img.width, img.height, m->name);
    }
    p->ok = used >= 0;
    lr_estimate(&lr, &p->est);
    p->est_heading_deg = ph_wrap_deg(lr_deg(p->est.heading));
    lr_pose_error(p->est.x_mm, p->est.y_mm, p->est_heading_deg, p->truth_x_mm, p->truth_y_mm,
                  p->truth_heading_deg, &pe, &he, &mpe, &mhe);
    p->pos_err_mm = pe;
    p->head_err_deg = he;
    p->mirror = mpe < pe;
    p->sym_pos_err_mm = p->mirror ? mpe : pe;
    p->sym_head_err_deg = p->mirror ? mhe : he;
    if (p->ok) {
        p->used = used;
        for (k = 0; k < lr.obs.n; k++)
            if ((int)lr.obs.obs[k].kind >= 0 && lr.obs.obs[k].kind < FL_LM_KIND_COUNT) {
                p->seen[lr.obs.obs[k].kind]++;
                p->n_seen++;
            }
        ph_map_in_view(field, &lr.cam, p->truth_x_mm, p->truth_y_mm, p->truth_heading_deg, p);
        p->goal_applies = p->n_seen >= 2;
        p->goal_met = p->goal_applies && p->sym_pos_err_mm <= PH_GOAL_MM;
        if (o->pictures != NULL)
            ph_picture(o, &lr, &view, p);
    }
    host_image_free(&img);
    lr_free(&lr);
    return 0;
}

int ph_run(const fl_localizer_t *loc, const ph_opts_t *o, ph_result_t *res, char *err,
           int err_len)
{
    const char *dir = rd_dir();
    const fl_field_t *field = fl_field_find(PH_FIELD);
    const fl_camera_model_t *m = fl_camera_model_find(PH_CAMERA);
    char path[1200];
    rd_physar_set_t set;
    double sp = 0, sh = 0;
    int i, n_ok = 0, rc = 0;
    void *preset = NULL;
    ph_opts_t oo;
    memset(res, 0, sizeof *res);
    if (loc == NULL)
        loc = fl_localizer_find("fuzzy");
    if (loc == NULL || field == NULL || m == NULL || o == NULL || o->repeat < 1) {
        snprintf(err, (size_t)err_len, "no localizer, field %s or camera %s, or repeat < 1",
                 PH_FIELD, PH_CAMERA);
        return -1;
    }
    res->localizer = loc->name;
    if (dir == NULL)
        return 1;
    oo = *o;
    if (oo.params == NULL) {
        /* the vision preset, as `localize` uses it */
        if ((preset = lr_params_new(loc)) == NULL) {
            snprintf(err, (size_t)err_len, "out of memory");
            return -1;
        }
        lr_params_frames(loc, preset);
        oo.params = preset;
    }
    o = &oo;
    if (rd_path(path, sizeof path, dir, RD_PHYSAR_CSV) != 0 ||
        rd_physar_load(path, &set, err, err_len) != 0) {
        free(preset);
        return -1;
    }
    for (i = 0; i < set.n && res->n < PH_MAX_POINTS; i++) {
        ph_point_t *p = &res->pt[res->n];
        if (set.rec[i].image_top[0] == '\0')
            continue;
        if (ph_point(loc, o, dir, &set.rec[i], field, m, p, err, err_len) != 0) {
            rc = -1;
            break;
        }
        res->n++;
        if (!p->ok)
            continue;
        n_ok++;
        sp += p->sym_pos_err_mm * p->sym_pos_err_mm;
        sh += p->sym_head_err_deg * p->sym_head_err_deg;
        if (p->sym_pos_err_mm > res->sym_max_mm)
            res->sym_max_mm = p->sym_pos_err_mm;
        res->n_goal += p->goal_applies;
        res->n_met += p->goal_met;
    }
    res->sym_rmse_mm = n_ok > 0 ? sqrt(sp / n_ok) : NAN;
    res->head_rmse_deg = n_ok > 0 ? sqrt(sh / n_ok) : NAN;
    rd_physar_free(&set);
    free(preset);
    return rc;
}

void ph_print_header(FILE *f, const ph_opts_t *o)
{
    fprintf(f,
            "# physar black1 points: field %s, camera %s, each top frame %d times with zero "
            "odometry from total ignorance;\n"
            "# the record's head angles %s; truth = OptiTrack x, y and "
            "the README's nominal heading\n"
            "# (APPROXIMATE: heading errors are approximate); errors modulo the 180-degree "
            "symmetry (sym), plain errors\n"
            "# after them; seen = vision's observations by kind (L T X P=penalty mark "
            "M=centre mark G=post C=circle),\n"
            "# map = landmarks in view from the truth pose with the nominal heading; goal: "
            "sym error <= %.0f mm where seen >= 2\n",
            PH_FIELD, PH_CAMERA, o->repeat,
            o->imu == PH_IMU_OFF     ? "only (--imu off: torso roll/pitch 0)"
            : o->imu == PH_IMU_ACCEL ? "and torso roll/pitch from the accelerometer (--imu accel)"
                                     : "and IMU AngleX/AngleY as torso roll/pitch (--imu angles)",
            PH_GOAL_MM);
}

void ph_print_point(FILE *f, const ph_result_t *r, const ph_point_t *p)
{
    char seen[64], map[64];
    if (!p->ok) {
        fprintf(f, "physar %-6s %s truth %.0f %.0f %.0f NO FRAME\n", r->localizer, p->point,
                p->truth_x_mm, p->truth_y_mm, p->truth_heading_deg);
        return;
    }
    ph_kinds(p->seen, seen, sizeof seen);
    ph_kinds(p->map, map, sizeof map);
    fprintf(f,
            "physar %-6s %s truth %.0f %.0f %.0f est %d %d %.1f rel %.3f %s sym_err %.0f mm "
            "%.1f deg%s plain %.0f mm %.1f deg seen %d [%s] used %d map %d [%s] torso %.3f %.3f "
            "goal %s\n",
            r->localizer, p->point, p->truth_x_mm, p->truth_y_mm, p->truth_heading_deg,
            (int)p->est.x_mm, (int)p->est.y_mm, p->est_heading_deg,
            p->est.reliability_q16 / 65536.0, lr_state_name(p->est.state), p->sym_pos_err_mm,
            p->sym_head_err_deg, p->mirror ? " (mirror)" : "", p->pos_err_mm, p->head_err_deg,
            p->n_seen, seen, p->used, p->n_map, map, p->torso_roll_rad, p->torso_pitch_rad,
            !p->goal_applies ? "n/a" : p->goal_met ? "met" : "MISSED");
}

void ph_print_summary(FILE *f, const ph_result_t *r)
{
    fprintf(f,
            "physar_summary %-6s points %d goal_met %d of %d sym_pos_rmse_mm %.0f "
            "sym_pos_max_mm %.0f sym_heading_rmse_deg %.1f (heading vs nominal, approximate)\n",
            r->localizer, r->n, r->n_met, r->n_goal, r->sym_rmse_mm, r->sym_max_mm,
            r->head_rmse_deg);
}
