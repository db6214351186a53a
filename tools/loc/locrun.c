/*
 * tools/loc/locrun.c - vision-to-grid glue and the sequence parser (locrun.h).
 *
 * Algorithm: lr_predict rounds the (double) odometry to mm and binary
 * angles with error diffusion (the remainder of each call is added to the
 * next), so a long run of small motions integrates without bias; a
 * component beyond the localizer's odo_max_mm is split into equal parts.
 * lr_frame builds the camera for the frame's pose, runs fl_vision_frame and
 * feeds the observation list and the view to the localizer's update
 * (localizer.h; the tools hold only the interface).
 * Memory: the localizer's state (fuzzy: about 64 KiB) and the vision context (color tables,
 * vision workspace) are malloc'd once per lr_t; a parsed sequence holds
 * one lr_seq_frame_t (about 1 KiB) per frame.
 */
#include "loc/locrun.h"
#include "loc/stream.h"
#include "eval/picture.h"
#include "io/textfile.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define LR_PI 3.14159265358979323846

/* ---- engine ---------------------------------------------------------------- */

int lr_init(lr_t *r, const fl_localizer_t *loc, const fl_field_t *field,
            const fl_camera_model_t *model, const void *params, char *err, int err_len)
{
    memset(r, 0, sizeof *r);
    if (loc == NULL)
        loc = fl_localizer_find("fuzzy");
    if (field == NULL || model == NULL || loc == NULL) {
        if (err)
            snprintf(err, (size_t)err_len, "no field, camera or localizer");
        return -1;
    }
    r->field = field;
    r->model = model;
    r->loc = loc;
    r->state = malloc(loc->state_size);
    r->params = malloc(loc->params_size);
    r->hlv = hld_field_wants(field) ? hld_new(field) : NULL;
    if (r->state == NULL || r->params == NULL || det_ctx_init(&r->det) != 0 ||
        (hld_field_wants(field) && r->hlv == NULL)) {
        if (err)
            snprintf(err, (size_t)err_len, "out of memory (vision context or localizer)");
        lr_free(r);
        return -1;
    }
    if (params != NULL) {
        /* the camera-dependent part of the vision parameters (fuzzy:
         * fl_fuzzy_params_lowres: wide rings and crossings up to 2.5 m
         * for the AIBO); a no-op for other parameters */
        memcpy(r->params, params, loc->params_size);
        loc->params_adapt(r->params, fl_loc_preset_for_width(model->width_px));
    } else {
        loc->params_default(r->params);
    }
    if (fl_loc_init(loc, r->state, field, params != NULL ? r->params : NULL) != FL_OK) {
        if (err)
            snprintf(err, (size_t)err_len, "cannot size the %s localizer for field %s (or bad params)",
                     loc->name, field->name);
        lr_free(r);
        return -1;
    }
    fl_obs_list_clear(&r->obs);
    return 0;
}

void lr_free(lr_t *r)
{
    if (r == NULL)
        return;
    free(r->state);
    r->state = NULL;
    free(r->params);
    r->params = NULL;
    free(r->hlv);
    r->hlv = NULL;
    free(r->corners);
    r->corners = NULL;
    if (r->det.colors != NULL || r->det.vis != NULL)
        det_ctx_free(&r->det);
}

int lr_set_vision(lr_t *r, int vision)
{
    fl_corners_params_t p;
    if (r == NULL || (vision != SIM_VISION_LTX && vision != SIM_VISION_CORNERS &&
                      vision != SIM_VISION_BOTH))
        return -1;
    r->vision = vision;
    if (vision == SIM_VISION_LTX)
        return 0;
    if (r->corners == NULL && (r->corners = malloc(sizeof *r->corners)) == NULL)
        return -1;
    fl_corners_params_default(&p);
    return fl_corners_init(r->corners, &p) == FL_OK ? 0 : -1;
}

/* The largest |dx| or |dy| the localizer takes in one predict call:
 * its odo_max_mm parameter when it has one (fuzzy), else 1000. */
static double lr_odo_max(const lr_t *r)
{
    int32_t v = 0;
    void *p = r->loc->params_of(r->state);
    if (p == NULL || fl_localizer_param_get(r->loc, p, "odo_max_mm", &v) != FL_OK || v <= 0)
        return 1000.0;
    return (double)v;
}

/* Every localizer call of the engine goes through these (the stream). */
static void lr_call_predict(lr_t *r, int32_t dx, int32_t dy, fl_angle_t dth)
{
    if (r->stream != NULL)
        ls_write_predict(r->stream, dx, dy, dth);
    r->loc->predict(r->state, dx, dy, dth);
}

static uint16_t lr_call_update(lr_t *r, const fl_obs_list_t *obs, const fl_obs_view_t *view)
{
    if (r->stream != NULL)
        ls_write_update(r->stream, obs, view);
    return r->loc->update(r->state, obs, view);
}

void lr_predict(lr_t *r, double dx_mm, double dy_mm, double dtheta_rad)
{
    double x = dx_mm + r->carry_x, y = dy_mm + r->carry_y;
    double a = dtheta_rad * (32768.0 / LR_PI) + r->carry_a;
    double rx, ry, ra, lim = lr_odo_max(r), m;
    int parts, k;
    if (!isfinite(x) || !isfinite(y) || !isfinite(a))
        return;
    rx = floor(x + 0.5);
    ry = floor(y + 0.5);
    ra = floor(a + 0.5);
    r->carry_x = x - rx;
    r->carry_y = y - ry;
    r->carry_a = a - ra;
    ra = fmod(ra, 65536.0);
    if (fabs(rx) > 2e6 || fabs(ry) > 2e6) {
        /* absurd: one call, which the grid rejects and counts */
        lr_call_predict(r, rx > 0 ? 2000000 : -2000000, 0, 0);
        return;
    }
    m = fabs(rx) > fabs(ry) ? fabs(rx) : fabs(ry);
    parts = m > lim ? (int)ceil(m / lim) : 1;
    if (parts == 1) {
        lr_call_predict(r, (int32_t)rx, (int32_t)ry, fl_angle_wrap((int32_t)ra));
        return;
    }
    {
        /* equal parts along the straight line, the turn in the last part */
        int32_t done_x = 0, done_y = 0;
        for (k = 1; k <= parts; k++) {
            int32_t tx = (int32_t)floor(rx * k / parts + 0.5);
            int32_t ty = (int32_t)floor(ry * k / parts + 0.5);
            lr_call_predict(r, tx - done_x, ty - done_y,
                            k == parts ? fl_angle_wrap((int32_t)ra) : 0);
            done_x = tx;
            done_y = ty;
        }
    }
}

void lr_camera_pose(const fl_camera_model_t *m, double head_pitch_rad,
                    double head_yaw_rad, fl_camera_pose_t *pose)
{
    memset(pose, 0, sizeof *pose);
    pose->neck_height_mm = m ? m->default_neck_height_mm : 450;
    pose->pitch_offset = m ? m->default_pitch_offset : 0;
    pose->head_pitch = fl_angle_from_urad((int32_t)lround(head_pitch_rad * 1e6));
    pose->head_yaw = fl_angle_from_urad((int32_t)lround(head_yaw_rad * 1e6));
}

/* Glue-side choices about what vision reports (see lr_t). */
static void lr_filter(lr_t *r)
{
    int i;
    if (r->ignore_post_sides)
        for (i = 0; i < r->obs.n; i++)
            if (r->obs.obs[i].kind == FL_LM_POST)
                r->obs.obs[i].side = FL_SIDE_UNKNOWN;
}

int lr_frame(lr_t *r, const fl_image_t *img, const fl_camera_pose_t *pose)
{
    fl_obs_list_clear(&r->obs);
    r->obs_used = 0;
    if (img == NULL || pose == NULL || img->width != r->model->width_px ||
        img->height != r->model->height_px)
        return -1;
    if (fl_camera_init(&r->cam, r->model, pose) != FL_OK)
        return -1;
    if (r->hlv != NULL) {
        /* seed 002's field: its own vision path (colour boxes, no colour
         * file) */
        (void)fl_hlv_frame(r->hlv, img, &r->cam, &r->obs);
        r->frames++;
        lr_filter(r);
        fl_vision_view(&r->cam, &r->view);
        r->obs_used = lr_call_update(r, &r->obs, &r->view);
        return r->obs_used;
    }
    if (r->colors != NULL && !r->colors_ready) {
        /* start-up: --colors auto estimates the carpet of this frame */
        if (colors_opt_setup(r->colors, r->det.colors, r->field, img, &r->cam, NULL) < 0)
            return -1;
        r->colors_ready = 1;
    }
    fl_vision_frame(r->det.vis, r->det.colors, img, &r->cam, r->field, &r->obs);
    if (r->vision != SIM_VISION_LTX && r->corners != NULL) {
        /* seed 004's corner path: nets from this frame's posts */
        if (r->vision == SIM_VISION_CORNERS)
            fl_obs_list_clear(&r->obs);
        if (fl_corners_run(r->corners, img, r->det.colors, &r->cam, &r->det.vis->beacons) == FL_OK)
            (void)fl_corners_obs(r->corners, &r->obs);
    }
    if (r->colors != NULL)
        (void)colors_opt_track(r->det.colors, &r->det.vis->scan);
    r->frames++;
    lr_filter(r);
    fl_vision_view(&r->cam, &r->view);
    r->obs_used = lr_call_update(r, &r->obs, &r->view);
    return r->obs_used;
}

int lr_frame_obs(lr_t *r, const fl_camera_pose_t *pose, const fl_obs_list_t *obs)
{
    fl_obs_list_clear(&r->obs);
    r->obs_used = 0;
    if (pose == NULL || obs == NULL || fl_camera_init(&r->cam, r->model, pose) != FL_OK)
        return -1;
    r->obs = *obs;
    r->frames++;
    lr_filter(r);
    fl_vision_view(&r->cam, &r->view);
    r->obs_used = lr_call_update(r, &r->obs, &r->view);
    return r->obs_used;
}

void lr_estimate(lr_t *r, fl_loc_estimate_t *est)
{
    r->loc->estimate(r->state, est);
}

void lr_odo_add(lr_odo_t *o, double dx_mm, double dy_mm, double dtheta_rad)
{
    double c = cos(o->a), s = sin(o->a);
    o->x += dx_mm * c - dy_mm * s;
    o->y += dx_mm * s + dy_mm * c;
    o->a += dtheta_rad;
}

static double lr_wrap_deg(double d)
{
    d = fmod(d, 360.0);
    if (d >= 180.0)
        d -= 360.0;
    if (d < -180.0)
        d += 360.0;
    return d;
}

void lr_pose_error(double ex, double ey, double eh_deg, double tx, double ty,
                   double th_deg, double *pos_mm, double *head_deg,
                   double *mirror_pos_mm, double *mirror_head_deg)
{
    if (pos_mm)
        *pos_mm = hypot(ex - tx, ey - ty);
    if (head_deg)
        *head_deg = fabs(lr_wrap_deg(eh_deg - th_deg));
    if (mirror_pos_mm)
        *mirror_pos_mm = hypot(ex + tx, ey + ty);
    if (mirror_head_deg)
        *mirror_head_deg = fabs(lr_wrap_deg(eh_deg - th_deg - 180.0));
}

int lr_mkdirs(const char *path)
{
    char buf[LR_PATH_MAX];
    struct stat sb;
    size_t i, n;
    if (path == NULL || (n = strlen(path)) == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, path, n + 1);
    for (i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (stat(buf, &sb) != 0)
                mkdir(buf, 0777);
            buf[i] = c;
        }
    }
    return stat(path, &sb) == 0 && S_ISDIR(sb.st_mode) ? 0 : -1;
}

const char *lr_state_name(fl_loc_state_t s)
{
    return s == FL_LOC_TRACKING ? "TRACKING" : s == FL_LOC_AMBIGUOUS ? "AMBIGUOUS" : "LOST";
}

void lr_print_conf(FILE *f, const fl_loc_estimate_t *e)
{
    fprintf(f, " %s sd %u %u ", lr_state_name(e->state), (unsigned)e->sd_x_mm,
            (unsigned)e->sd_y_mm);
    if (e->sd_heading >= 32767)
        fprintf(f, "-");
    else
        fprintf(f, "%.1f", e->sd_heading * (360.0 / 65536.0));
    fprintf(f, " mirror %.2f", e->mirror_q16 / 65536.0);
}

double lr_deg(fl_angle_t a)
{
    return (double)a * (180.0 / 32768.0);
}

/* ---- sequence files ------------------------------------------------------- */

static int lr_fail(char *err, int err_len, int line, const char *fmt, ...)
{
    va_list ap;
    char msg[512];
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (err != NULL && err_len > 0) {
        if (line > 0)
            snprintf(err, (size_t)err_len, "line %d: %s", line, msg);
        else
            snprintf(err, (size_t)err_len, "%s", msg);
    }
    return -1;
}

/* A finite number filling the whole token, |v| <= lim. */
static int lr_num(const char *tok, double lim, double *v)
{
    return tf_number(tok, lim, v) ? -1 : 0;
}

#define LR_MAX_TOK 12

int lr_seq_parse(const char *text, const char *base_dir, lr_seq_t *out,
                 char *err, int err_len)
{
    const char *p = text;
    int line = 0;
    memset(out, 0, sizeof *out);
    if (text == NULL)
        return lr_fail(err, err_len, 0, "no text");
    while (*p != '\0') {
        char buf[2 * LR_PATH_MAX], *tok[LR_MAX_TOK], *q;
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        int nt = 0;
        line++;
        if (len >= sizeof buf) {
            lr_seq_free(out);
            return lr_fail(err, err_len, line, "line too long");
        }
        memcpy(buf, p, len);
        buf[len] = '\0';
        p += len + (eol ? 1 : 0);
        q = strchr(buf, '#');
        if (q != NULL)
            *q = '\0';
        for (q = buf; *q != '\0';) {
            while (*q != '\0' && isspace((unsigned char)*q))
                *q++ = '\0';
            if (*q == '\0')
                break;
            if (nt == LR_MAX_TOK) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line, "too many fields");
            }
            tok[nt++] = q;
            while (*q != '\0' && !isspace((unsigned char)*q))
                q++;
        }
        if (nt == 0)
            continue;
        if (!strcmp(tok[0], "field") || !strcmp(tok[0], "camera")) {
            int is_field = tok[0][0] == 'f';
            if (nt != 2) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line, "expected '%s NAME'", tok[0]);
            }
            if (out->n > 0) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line, "'%s' after the first frame", tok[0]);
            }
            if (is_field ? out->field != NULL : out->camera != NULL) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line, "'%s' given twice", tok[0]);
            }
            if (is_field) {
                out->field = fl_field_find(tok[1]);
                if (out->field == NULL) {
                    lr_seq_free(out);
                    return lr_fail(err, err_len, line,
                                   "unknown field '%s' (see: fieldloc fields)", tok[1]);
                }
            } else {
                out->camera = fl_camera_model_find(tok[1]);
                if (out->camera == NULL) {
                    lr_seq_free(out);
                    return lr_fail(err, err_len, line,
                                   "unknown camera '%s' (see: fieldloc cameras)", tok[1]);
                }
            }
        } else if (!strcmp(tok[0], "prior")) {
            if (nt != 4 || lr_num(tok[1], 20000, &out->prior_x_mm) ||
                lr_num(tok[2], 20000, &out->prior_y_mm) ||
                lr_num(tok[3], 3600, &out->prior_theta_deg)) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line,
                               "expected 'prior X_MM Y_MM THETA_DEG' (|x|, |y| <= 20000)");
            }
            if (out->n > 0 || out->has_prior) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line,
                               "'prior' must come once, before the first frame");
            }
            out->has_prior = 1;
        } else if (!strcmp(tok[0], "frame")) {
            lr_seq_frame_t *f;
            if (nt != 9 || strcmp(tok[2], "odo") != 0 || strcmp(tok[6], "head") != 0) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line,
                               "expected 'frame IMAGE odo DX_MM DY_MM DTHETA_DEG head "
                               "PITCH_RAD YAW_RAD'");
            }
            if (out->field == NULL || out->camera == NULL) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line,
                               "frame before the 'field' and 'camera' lines");
            }
            if (out->n == out->cap) {
                int cap = out->cap ? 2 * out->cap : 64;
                lr_seq_frame_t *nf = realloc(out->frame, (size_t)cap * sizeof *nf);
                if (nf == NULL) {
                    lr_seq_free(out);
                    return lr_fail(err, err_len, line, "out of memory");
                }
                out->frame = nf;
                out->cap = cap;
            }
            f = &out->frame[out->n];
            memset(f, 0, sizeof *f);
            f->line = line;
            if (lr_num(tok[3], 20000, &f->odo_dx_mm) || lr_num(tok[4], 20000, &f->odo_dy_mm) ||
                lr_num(tok[5], 3600, &f->odo_dtheta_deg)) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line,
                               "bad odometry (numbers, |dx|, |dy| <= 20000 mm, |dtheta| <= "
                               "3600 deg)");
            }
            if (lr_num(tok[7], 3.2, &f->head_pitch_rad) || lr_num(tok[8], 3.2, &f->head_yaw_rad)) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line, "bad head angles (radians, |a| <= 3.2)");
            }
            if (tok[1][0] == '/' || base_dir == NULL || base_dir[0] == '\0') {
                if (strlen(tok[1]) >= LR_PATH_MAX) {
                    lr_seq_free(out);
                    return lr_fail(err, err_len, line, "image path too long");
                }
                strcpy(f->image, tok[1]);
            } else if (snprintf(f->image, LR_PATH_MAX, "%s/%s", base_dir, tok[1]) >=
                       LR_PATH_MAX) {
                lr_seq_free(out);
                return lr_fail(err, err_len, line, "image path too long");
            }
            out->n++;
        } else {
            lr_seq_free(out);
            return lr_fail(err, err_len, line,
                           "unknown keyword '%s' (field, camera, prior, frame)", tok[0]);
        }
    }
    if (out->field == NULL || out->camera == NULL) {
        lr_seq_free(out);
        return lr_fail(err, err_len, 0, "missing 'field NAME' or 'camera NAME' line");
    }
    if (out->n == 0) {
        lr_seq_free(out);
        return lr_fail(err, err_len, 0, "no 'frame' line");
    }
    return 0;
}

int lr_seq_load(const char *path, lr_seq_t *out, char *err, int err_len)
{
    FILE *f;
    char *text, dir[LR_PATH_MAX];
    const char *slash;
    long size;
    int rc;
    memset(out, 0, sizeof *out);
    f = fopen(path, "rb");
    if (f == NULL)
        return lr_fail(err, err_len, 0, "cannot open: %s", strerror(errno));
    if (fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 || size > (64L << 20) ||
        fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return lr_fail(err, err_len, 0, "cannot read (or larger than 64 MiB)");
    }
    text = malloc((size_t)size + 1);
    if (text == NULL || fread(text, 1, (size_t)size, f) != (size_t)size) {
        free(text);
        fclose(f);
        return lr_fail(err, err_len, 0, "cannot read");
    }
    fclose(f);
    text[size] = '\0';
    if (memchr(text, '\0', (size_t)size) != NULL) {
        free(text);
        return lr_fail(err, err_len, 0, "binary file (NUL byte), not a sequence");
    }
    slash = strrchr(path, '/');
    if (slash == NULL)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    rc = lr_seq_parse(text, dir, out, err, err_len);
    free(text);
    return rc;
}

void lr_seq_free(lr_seq_t *s)
{
    if (s == NULL)
        return;
    free(s->frame);
    memset(s, 0, sizeof *s);
}

/* ---- running a sequence --------------------------------------------------- */

static void lr_seq_picture(const lr_seq_opts_t *o, lr_t *lr, const render_frame_t *fr, int have_frame,
                       const fl_loc_estimate_t *est, int k)
{
    host_image_t belief, frame, both;
    pic_pose_t ep;
    char base[1100], info[256], caption[1400];
    ep.x_mm = est->x_mm;
    ep.y_mm = est->y_mm;
    ep.heading_deg = lr_deg(est->heading);
    if (pic_belief(lr->loc, lr->state, lr->field, 0, NULL, est, have_frame ? &lr->obs : NULL, &belief) != 0)
        return;
    snprintf(base, sizeof base, "%s/%s%05d", o->pictures,
             o->picture_prefix ? o->picture_prefix : "frame_", k);
    /* legend strip: the sequence frame, the estimate and its reliability
     * (a sequence has no truth, so no error) */
    pic_belief_caption(info, sizeof info, -1, k, est, -1, 0);
    snprintf(caption, sizeof caption, "%s  %s", o->name ? o->name : "", info);
    if (have_frame && pic_frame(&lr->det, &fr->view, &lr->cam, lr->field, &ep, 2, &frame) == 0) {
        if (pic_side_by_side(&frame, &belief, 8, &both) == 0) {
            if (pic_legend_inplace(&both, PIC_LEGEND_DETECT | PIC_LEGEND_MODEL |
                                   pic_belief_legend(lr->loc, lr->state), caption) == 0)
                pic_save(&both, base, 1, NULL);
            host_image_free(&both);
        }
        host_image_free(&frame);
    } else if (pic_legend_inplace(&belief, pic_belief_legend(lr->loc, lr->state), caption) == 0) {
        pic_save(&belief, base, 1, NULL);
    }
    host_image_free(&belief);
}

int lr_seq_run(const lr_seq_t *seq, const lr_seq_opts_t *o, lr_frame_result_t *res)
{
    lr_t lr;
    colors_opt_t colors;
    char err[256];
    int k, skipped = 0;
    const char *name = o->name != NULL ? o->name : "sequence";
    if (lr_init(&lr, o->loc, seq->field, seq->camera, o->params, err, (int)sizeof err) != 0) {
        fprintf(stderr, "localize: %s\n", err);
        return -1;
    }
    if (o->colors != NULL) {
        colors = *o->colors;
        colors_opt_resolve(&colors, seq->field, seq->n > 0 ? seq->frame[0].image : NULL);
        lr.colors = &colors;
    }
    if (seq->has_prior) {
        int32_t x = (int32_t)lround(seq->prior_x_mm), y = (int32_t)lround(seq->prior_y_mm);
        fl_angle_t h = fl_angle_from_mdeg((int32_t)lround(fmod(seq->prior_theta_deg, 360.0) * 1000));
        lr.loc->set_prior_pose(lr.state, x, y, h, 1000);
        lr.loc->reset_pose(lr.state, x, y, h, 300, fl_angle_from_mdeg(20000));
    }
    for (k = 0; k < seq->n; k++) {
        const lr_seq_frame_t *f = &seq->frame[k];
        render_frame_t fr;
        fl_camera_pose_t pose;
        fl_loc_estimate_t est;
        int have = 0, used = -1;
        lr_predict(&lr, f->odo_dx_mm, f->odo_dy_mm, f->odo_dtheta_deg * (LR_PI / 180.0));
        if (render_read_frame(f->image, &fr, err, (int)sizeof err) != 0) {
            if (!o->quiet)
                fprintf(stderr, "localize: %s line %d: %s; frame skipped (odometry only)\n",
                        name, f->line, err);
        } else {
            have = 1;
            lr_camera_pose(seq->camera, f->head_pitch_rad, f->head_yaw_rad, &pose);
            if (o->calib != NULL)
                fl_calib_apply(o->calib, &pose);
            used = lr_frame(&lr, &fr.view, &pose);
            if (used < 0 && !o->quiet)
                fprintf(stderr,
                        "localize: %s line %d: %s: image %dx%d does not fit camera %s (%dx%d) "
                        "or bad head pose; frame skipped (odometry only)\n",
                        name, f->line, f->image, fr.width, fr.height, seq->camera->name,
                        (int)seq->camera->width_px, (int)seq->camera->height_px);
        }
        if (used < 0)
            skipped++;
        lr_estimate(&lr, &est);
        if (o->out != NULL) {
            double h = lr_deg(est.heading);
            if (h <= -180.0)
                h += 360.0;
            fprintf(o->out, "pose %d %d %.1f %.3f", (int)est.x_mm, (int)est.y_mm, h,
                    est.reliability_q16 / 65536.0);
            lr_print_conf(o->out, &est);
            fputc('\n', o->out);
        }
        if (res != NULL) {
            res[k].est = est;
            res[k].obs = used >= 0 ? lr.obs.n : 0;
            res[k].used = used;
            res[k].ok = used >= 0;
        }
        if (o->pictures != NULL && (k % (o->picture_every > 0 ? o->picture_every : 1) == 0 || k == seq->n - 1))
            lr_seq_picture(o, &lr, &fr, used >= 0, &est, k);
        if (have)
            render_frame_free(&fr);
    }
    lr_free(&lr);
    return skipped;
}

/* ---- simulated walks ------------------------------------------------------- */

#include <pthread.h>
#include <time.h>
#include <unistd.h>

#define LR_GOOD_MM 300.0
#define LR_GOOD_DEG 15.0
#define LR_HOLD_S 1.0

typedef struct lr_rec {
    double t, pos_err, head_err;
    int good, flip, excluded;
} lr_rec_t;

static double lr_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* First index i >= from such that every record in [t_i, t_i + hold] is
 * good (and at least hold seconds of run remain); -1 if none. */
static long lr_first_hold(const lr_rec_t *r, long n, long from, double hold)
{
    long i = from;
    while (i < n) {
        long j = i;
        if (!r[i].good) {
            i++;
            continue;
        }
        while (j < n && r[j].good && r[j].t < r[i].t + hold)
            j++;
        if (j < n && r[j].t >= r[i].t + hold)
            return i;
        if (j >= n)
            return -1;
        i = j + 1;
    }
    return -1;
}

static int lr_kind_group(fl_landmark_kind_t k)
{
    if (k == FL_LM_POST)
        return 1;
    if (k == FL_LM_CENTRE_CIRCLE)
        return 2;
    if (k == FL_LM_BEACON)
        return 3;
    if (k == FL_LM_NET)
        return 4;
    if (fl_landmark_kind_is_feature(k))
        return 5; /* seed 004's C, T-field, T-net */
    return 0; /* crossings and marks */
}

/* Match one frame's vision observations to the map at the true pose. */
static void lr_vdiag_frame(lr_vdiag_t *d, const sim_scenario_t *sc, const fl_camera_t *cam,
                           const sim_step_t *st, const fl_obs_list_t *obs)
{
    const fl_field_t *f = sc->field;
    double h = st->true_heading_rad, ch = cos(h), sh = sin(h);
    /* the map points: the landmarks, and with a corner vision path
     * (frames --vision corners|both) seed 004's features after them */
    const int n_map = sc->vision == SIM_VISION_LTX ? f->n_landmarks : fl_field_n_all(f);
    int found[256] = {0};
    int i, j;
    for (i = 0; i < obs->n; i++) {
        const fl_obs_t *o = &obs->obs[i];
        double b = lr_deg(o->bearing) * (LR_PI / 180.0);
        double ox = o->range_mm * cos(b), oy = o->range_mm * sin(b);
        double tol = o->range_mm * 0.2 > 250 ? o->range_mm * 0.2 : 250;
        double best = 1e30;
        int bj = -1;
        lr_vdiag_t *dk;
        if ((int)o->kind < 0 || o->kind >= FL_LM_KIND_COUNT)
            continue;
        dk = &d[o->kind];
        dk->n_obs++;
        for (j = 0; j < n_map && j < 256; j++) {
            const fl_landmark_t *lm = fl_field_all_at(f, (uint16_t)j);
            double dx = lm->x_mm - st->true_x_mm, dy = lm->y_mm - st->true_y_mm;
            double rx = dx * ch + dy * sh, ry = -dx * sh + dy * ch, e;
            if (lr_kind_group(lm->kind) != lr_kind_group(o->kind))
                continue;
            e = hypot(rx - ox, ry - oy);
            if (e < best) {
                best = e;
                bj = j;
            }
        }
        if (bj < 0 || best > tol) {
            dk->false_pos++;
            continue;
        }
        {
            const fl_landmark_t *lm = fl_field_all_at(f, (uint16_t)bj);
            double dx = lm->x_mm - st->true_x_mm, dy = lm->y_mm - st->true_y_mm;
            double rx = dx * ch + dy * sh, ry = -dx * sh + dy * ch;
            double tr = hypot(rx, ry), tb = atan2(ry, rx) * (180.0 / LR_PI), db;
            dk->matched++;
            if (lm->kind != o->kind)
                dk->wrong_kind++;
            if (o->kind == FL_LM_POST && o->side != FL_SIDE_UNKNOWN) {
                dk->side_known++;
                if (o->side != lm->side)
                    dk->side_wrong++;
            }
            if (tr > 1)
                dk->sum_abs_range_pct += fabs(o->range_mm - tr) / tr * 100.0;
            db = fmod(lr_deg(o->bearing) - tb + 540.0, 360.0) - 180.0;
            dk->sum_abs_bearing_deg += fabs(db);
            found[bj] = 1;
        }
    }
    for (j = 0; j < n_map && j < 256; j++) {
        const fl_landmark_t *lm = fl_field_all_at(f, (uint16_t)j);
        double dx = lm->x_mm - st->true_x_mm, dy = lm->y_mm - st->true_y_mm;
        double rx = dx * ch + dy * sh, ry = -dx * sh + dy * ch;
        fl_point_t gp;
        int32_t u, v;
        gp.x_mm = (int32_t)lround(rx);
        gp.y_mm = (int32_t)lround(ry);
        if (hypot(rx, ry) > sc->max_range_mm || !fl_camera_ground_to_pixel(cam, gp, &u, &v) ||
            u < 64 || v < 64 || u > 16 * (cam->model.width_px - 5) ||
            v > 16 * (cam->model.height_px - 5) ||
            sim_occluded(sc, cam, st->x_mm, st->y_mm, st->heading, lm->x_mm, lm->y_mm, 0))
            continue;
        d[lm->kind].truth_visible++;
        if (found[j])
            d[lm->kind].truth_found++;
    }
}

static void lr_record(lr_rec_t *r, double t, int sym, int half_known, double ex, double ey,
                      double eh, double tx, double ty, double th)
{
    double pe, he, mpe, mhe;
    lr_pose_error(ex, ey, eh, tx, ty, th, &pe, &he, &mpe, &mhe);
    r->t = t;
    if (sym && !half_known && mpe < pe) {
        r->pos_err = mpe;
        r->head_err = mhe;
    } else {
        r->pos_err = pe;
        r->head_err = he;
    }
    r->flip = sym && half_known && mpe < 500.0 && mhe < 30.0 && pe > 1000.0;
    r->good = r->pos_err < LR_GOOD_MM && r->head_err < LR_GOOD_DEG;
    r->excluded = 0;
}

/* ---- metrics ------------------------------------------------------------------ */

int lr_metrics_init(lr_metrics_t *m, int symmetric)
{
    memset(m, 0, sizeof *m);
    m->sym = symmetric;
    m->half_known = 1;
    m->i_penalty = -1;
    m->cap = 1024;
    m->rec = malloc((size_t)m->cap * sizeof *m->rec);
    return m->rec != NULL ? 0 : -1;
}

void lr_metrics_free(lr_metrics_t *m)
{
    free(m->rec);
    m->rec = NULL;
    m->n = m->cap = 0;
}

/* The open kidnap windows close at record m->n (the next one). */
static void lr_metrics_close(lr_metrics_t *m, lr_kidnap_end_t why, double t_s)
{
    int k;
    for (k = 0; k < m->n_kid; k++) {
        if (m->kid_end[k] >= 0)
            continue;
        m->kid_end[k] = m->n;
        m->kid_why[k] = why;
        m->kid_end_t[k] = t_s;
    }
}

void lr_metrics_event(lr_metrics_t *m, unsigned events, double t_s)
{
    if (events & SIM_EV_KIDNAP) {
        lr_metrics_close(m, LR_KIDNAP_NEXT, t_s);
        if (m->n_kid < LR_MAX_KIDNAPS) {
            m->kid_rec[m->n_kid] = m->n;
            m->kid_t[m->n_kid] = t_s;
            m->kid_end[m->n_kid] = -1;
            m->n_kid++;
        }
        m->half_known = 0;
    }
    if (events & SIM_EV_PENALIZED) {
        /* told: from here on the robot's belief is the reset's, not its own */
        lr_metrics_close(m, LR_KIDNAP_TOLD, t_s);
        if (m->i_penalty < 0)
            m->i_penalty = m->n;
        m->half_known = 1;
    }
}

long lr_metrics_record(lr_metrics_t *m, double t_s, const fl_loc_estimate_t *est,
                       int32_t truth_x_mm, int32_t truth_y_mm, fl_angle_t truth_heading,
                       double *pos_err_mm, double *head_err_deg)
{
    lr_rec_t *r;
    if (m->n == m->cap) {
        lr_rec_t *g = realloc(m->rec, (size_t)m->cap * 2 * sizeof *g);
        if (g == NULL)
            return -1;
        m->rec = g;
        m->cap *= 2;
    }
    r = &m->rec[m->n];
    lr_record(r, t_s, m->sym, m->half_known, est->x_mm, est->y_mm, lr_deg(est->heading),
              truth_x_mm, truth_y_mm, lr_deg(truth_heading));
    m->last_pos_err = r->pos_err;
    m->last_head_err = r->head_err;
    if (pos_err_mm != NULL)
        *pos_err_mm = r->pos_err;
    if (head_err_deg != NULL)
        *head_err_deg = r->head_err;
    return m->n++;
}

static int lr_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

void lr_metrics_finish(lr_metrics_t *m, lr_walk_result_t *res)
{
    lr_rec_t *rec = m->rec;
    long n = m->n, i, ic = lr_first_hold(rec, n, 0, LR_HOLD_S);
    double se_p = 0, se_h = 0, se_pa = 0, se_ha = 0, sorted[LR_MAX_KIDNAPS];
    long used_all = 0;
    int k;
    res->records = n;
    res->used = 0;
    res->flips = 0;
    res->final_pos_err_mm = m->last_pos_err;
    res->final_head_err_deg = m->last_head_err;
    res->converge_s = ic >= 0 ? rec[ic].t : INFINITY;
    /* each kidnap: recovered by itself before its window closes (the
     * next told reset, the next kidnap, the end), the whole 1 s hold
     * inside the window; the window is excluded from the RMSE */
    res->n_kidnaps = 0;
    for (k = 0; k < m->n_kid; k++) {
        long from = m->kid_rec[k], end = m->kid_end[k] >= 0 ? m->kid_end[k] : n, ik;
        lr_kidnap_t *kd;
        if (from >= n)
            continue; /* after the last record */
        if (end > n)
            end = n;
        kd = &res->kidnap[res->n_kidnaps++];
        kd->t_s = m->kid_t[k];
        ik = lr_first_hold(rec, end, from, LR_HOLD_S);
        kd->recover_s = ik >= 0 ? rec[ik].t - m->kid_t[k] : INFINITY;
        kd->end = ik >= 0 ? LR_KIDNAP_RECOVERED : m->kid_end[k] >= 0 ? m->kid_why[k]
                                                                    : LR_KIDNAP_END;
        kd->end_s = ik >= 0 ? rec[ik].t : m->kid_end[k] >= 0 ? m->kid_end_t[k] : rec[n - 1].t;
        for (i = from; i < (ik >= 0 ? ik : end); i++)
            rec[i].excluded = 1;
    }
    res->kidnap_recover_s = NAN;
    res->kidnap_recover_worst_s = NAN;
    if (res->n_kidnaps > 0) {
        int nk = res->n_kidnaps;
        for (k = 0; k < nk; k++)
            sorted[k] = res->kidnap[k].recover_s;
        qsort(sorted, (size_t)nk, sizeof sorted[0], lr_cmp_double);
        res->kidnap_recover_s =
            nk % 2 ? sorted[nk / 2] : 0.5 * (sorted[nk / 2 - 1] + sorted[nk / 2]);
        res->kidnap_recover_worst_s = sorted[nk - 1];
    }
    res->penalty_recover_s = NAN;
    if (m->i_penalty >= 0 && m->i_penalty < n) {
        long ip = lr_first_hold(rec, n, m->i_penalty, LR_HOLD_S);
        res->penalty_recover_s = ip >= 0 ? rec[ip].t - rec[m->i_penalty].t : INFINITY;
        for (i = m->i_penalty; i < n && (ip < 0 || i < ip); i++)
            rec[i].excluded = 1;
    }
    for (i = 0; i < n; i++) {
        if (rec[i].flip && (i == 0 || !rec[i - 1].flip))
            res->flips++;
        if (ic < 0 || i < ic)
            continue;
        se_pa += rec[i].pos_err * rec[i].pos_err;
        se_ha += rec[i].head_err * rec[i].head_err;
        used_all++;
        if (rec[i].excluded)
            continue;
        se_p += rec[i].pos_err * rec[i].pos_err;
        se_h += rec[i].head_err * rec[i].head_err;
        res->used++;
    }
    res->pos_rmse_mm = res->used > 0 ? sqrt(se_p / (double)res->used) : NAN;
    res->heading_rmse_deg = res->used > 0 ? sqrt(se_h / (double)res->used) : NAN;
    res->pos_rmse_all_mm = used_all > 0 ? sqrt(se_pa / (double)used_all) : NAN;
    res->heading_rmse_all_deg = used_all > 0 ? sqrt(se_ha / (double)used_all) : NAN;
}

void lr_print_step(FILE *f, uint32_t step, double t_s, const fl_loc_estimate_t *est,
                   int32_t truth_x_mm, int32_t truth_y_mm, fl_angle_t truth_heading,
                   double pos_err_mm, double head_err_deg)
{
    fprintf(f, "step %ld %.3f est %d %d %.1f %.3f truth %d %d %.1f err %.0f %.1f", (long)step,
            t_s, (int)est->x_mm, (int)est->y_mm, lr_deg(est->heading),
            est->reliability_q16 / 65536.0, (int)truth_x_mm, (int)truth_y_mm,
            lr_deg(truth_heading), pos_err_mm, head_err_deg);
    lr_print_conf(f, est);
    fputc('\n', f);
}

void lr_print_obs(FILE *f, const fl_obs_list_t *ol)
{
    static const char kc[] = "LTXPCGOBcfnN";
    int q;
    for (q = 0; q < ol->n; q++) {
        const fl_obs_t *ob = &ol->obs[q];
        fprintf(f, "#  obs %c range %d bearing %.1f orient %s%.1f side %d conf %d\n",
                (int)ob->kind < FL_LM_KIND_COUNT ? kc[ob->kind] : '?', (int)ob->range_mm,
                lr_deg(ob->bearing), ob->has_orientation ? "" : "-", lr_deg(ob->orientation),
                (int)ob->side, (int)ob->confidence);
    }
}

/* ---- the walk ------------------------------------------------------------------ */

/* The told and untold events of one simulator step (slips left out). */
typedef struct {
    unsigned bits;
    uint32_t step;
    int32_t t_ms, x_mm, y_mm;
    fl_angle_t heading;
} lr_ev_t;

/* every SIM_EVENT of a scenario and every end of a penalty: the most a
 * record can collect */
#define LR_EV_MAX (2 * SIM_MAX_EVENTS + 2)
#define LR_EV_BITS (SIM_EV_KIDNAP | SIM_EV_PENALIZED | SIM_EV_UNPENALIZED)

typedef struct {
    lr_ev_t ev[LR_EV_MAX];
    int n;
} lr_evlist_t;

static void lr_ev_add(lr_evlist_t *l, const sim_step_t *st)
{
    lr_ev_t *e;
    if ((st->events & LR_EV_BITS) == 0 || l->n >= LR_EV_MAX)
        return;
    e = &l->ev[l->n++];
    e->bits = st->events & LR_EV_BITS;
    e->step = st->index;
    e->t_ms = st->t_ms;
    e->x_mm = st->x_mm;
    e->y_mm = st->y_mm;
    e->heading = st->heading;
}

/* One record of a batch (frames mode: a vision step). */
typedef struct {
    sim_step_t st;
    double ax, ay, aa;            /* odometry since the previous vision step
                                     (after the placement, if any) */
    int placed;                   /* penalty placement since then */
    unsigned events;              /* events of the steps since then */
    lr_evlist_t ev;               /* the same, one entry per step */
    render_scene_t scene;
    render_frame_t fr;
    int rc;
} lr_job_t;

typedef struct {
    lr_job_t *job;
    int n, tid, nthreads;
} lr_worker_t;

static void *lr_render_worker(void *arg)
{
    lr_worker_t *w = arg;
    int j;
    for (j = w->tid; j < w->n; j += w->nthreads)
        w->job[j].rc = render_frame(&w->job[j].scene, &w->job[j].fr);
    return NULL;
}

#define LR_BATCH 16

/* Render a batch with up to nthreads threads (the caller is one of them). */
static void lr_render_batch(lr_job_t *job, int n, int nthreads)
{
    pthread_t th[LR_MAX_THREADS];
    lr_worker_t w[LR_MAX_THREADS];
    int started[LR_MAX_THREADS] = {0};
    int t;
    if (nthreads > n)
        nthreads = n;
    if (nthreads < 1)
        nthreads = 1;
    for (t = 0; t < nthreads; t++) {
        w[t].job = job;
        w[t].n = n;
        w[t].tid = t;
        w[t].nthreads = nthreads;
    }
    for (t = 1; t < nthreads; t++)
        started[t] = pthread_create(&th[t], NULL, lr_render_worker, &w[t]) == 0;
    lr_render_worker(&w[0]);
    for (t = 1; t < nthreads; t++) {
        if (started[t])
            pthread_join(th[t], NULL);
        else
            lr_render_worker(&w[t]); /* no thread: do its share here */
    }
}

int lr_threads_default(void)
{
    const char *e = getenv("FIELDLOC_THREADS");
    long n = e != NULL && *e != '\0' ? strtol(e, NULL, 10) : sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1)
        n = 1;
    if (n > LR_MAX_THREADS)
        n = LR_MAX_THREADS;
    return (int)n;
}

/* The placement the rules tell: one of the two touchline spots at
 * penalty_x_mm, 300 mm and about 15 degrees of uncertainty. */
static void lr_place(lr_t *lr, const sim_scenario_t *sc)
{
    if (lr->stream != NULL)
        ls_write_reset_penalty(lr->stream, (int32_t)sc->penalty_x_mm, 300, 2730);
    lr->loc->reset_penalty(lr->state, (int32_t)sc->penalty_x_mm, 300, 2730);
}

/* The observation cache (frames mode, lr_walk_opts_t.obs_cache): returns
 * the open file, *reading 1 when it holds this walk's observations. */
static FILE *lr_cache_open(const sim_scenario_t *sc, const char *path, int every, int *reading)
{
    char want[128], have[128];
    FILE *cache;
    *reading = 0;
    /* the vision path is part of the key (ltx: the header as before, so
     * its caches stay valid; corners / both: a word more) */
    snprintf(want, sizeof want, "fieldloc-obs-cache 1 %s %s %llu %d %u %d%s\n", sc->name,
             sc->field->name, (unsigned long long)sc->seed, every,
             (unsigned)sizeof(fl_obs_list_t), (int)(sc->duration_s * 1000),
             sc->vision == SIM_VISION_CORNERS ? " corners"
             : sc->vision == SIM_VISION_BOTH  ? " both"
                                              : "");
    cache = fopen(path, "rb");
    if (cache != NULL && fgets(have, sizeof have, cache) != NULL && !strcmp(have, want)) {
        *reading = 1;
        return cache;
    }
    if (cache != NULL)
        fclose(cache);
    cache = fopen(path, "wb");
    if (cache != NULL)
        fputs(want, cache);
    return cache;
}

int lr_walk_run(const sim_scenario_t *sc, const lr_walk_opts_t *o,
                lr_walk_result_t *res, char *err, int err_len)
{
    sim_t *sim;
    sim_step_t *st;
    lr_t lr;
    lr_metrics_t met;
    lr_job_t *job = NULL;
    lr_odo_t acc = {0, 0, 0};
    lr_evlist_t pend;
    int every = o->every < 1 ? 1 : o->every, placed = 0, done = 0, prior_half;
    unsigned events = 0;
    int nthreads = o->threads > 0 ? o->threads : lr_threads_default();
    FILE *cache = NULL;
    int cache_read = 0;
    fl_loc_estimate_t est;

    memset(res, 0, sizeof *res);
    pend.n = 0;
    sim = malloc(sizeof *sim);
    st = malloc(sizeof *st);
    job = calloc(o->frames ? LR_BATCH : 1, sizeof *job);
    if (sim == NULL || st == NULL || job == NULL) {
        free(sim);
        free(st);
        free(job);
        return lr_fail(err, err_len, 0, "out of memory");
    }
    if (sim_init(sim, sc) != 0) {
        free(sim);
        free(st);
        free(job);
        return lr_fail(err, err_len, 0, "invalid scenario");
    }
    if (lr_init(&lr, o->loc, sc->field, sc->camera, o->params, err, err_len) != 0) {
        free(sim);
        free(st);
        free(job);
        return -1;
    }
    if (o->frames && lr_set_vision(&lr, sc->vision) != 0) {
        if (err)
            snprintf(err, (size_t)err_len, "out of memory (corner stage)");
        lr_free(&lr);
        free(sim);
        free(st);
        free(job);
        return -1;
    }
    /* feature mode's white points only for a localizer that reads them
     * (frames mode: the vision path makes its own) */
    if (!lr.loc->reads_points || o->frames)
        sim->sc.white_points = 0;
    lr.colors = o->colors;
    if (lr_metrics_init(&met, sc->field->symmetric) != 0) {
        lr_free(&lr);
        free(sim);
        free(st);
        free(job);
        return lr_fail(err, err_len, 0, "out of memory");
    }
    prior_half = sc->start_x_mm < 0 ? -1 : 1;
    lr.loc->set_prior_half(lr.state, prior_half);
    lr.ignore_post_sides = o->ignore_post_sides;
    lr.stream = o->stream;
    if (o->stream != NULL)
        ls_write_header(o->stream, sc, o->frames, o->frames ? every : 1, !o->ignore_post_sides,
                        prior_half);
    res->dt_s = (o->frames ? every : 1) / sc->frame_hz;
    if (o->frames && o->obs_cache != NULL)
        cache = lr_cache_open(sc, o->obs_cache, every, &cache_read);
    while (!done) {
        int nb = 0, b;
        double t0;
        /* 1. advance the simulator: one step (features) or up to a batch of
         *    vision steps (frames) */
        while (!done) {
            if ((o->max_steps >= 0 && res->steps >= o->max_steps) || !sim_step(sim, st)) {
                done = 1;
                break;
            }
            res->steps++;
            lr_ev_add(&pend, st);
            if (!o->frames) {
                job[0].ev = pend;
                pend.n = 0;
                nb = 1;
                break;
            }
            lr_odo_add(&acc, st->odo_dx, st->odo_dy, st->odo_dtheta_rad);
            events |= st->events;
            if (st->events & SIM_EV_PENALIZED) {
                /* the placement replaces the belief: motion before it is moot */
                acc.x = acc.y = acc.a = 0;
                placed = 1;
            }
            if (st->index % (uint32_t)every != 0)
                continue;
            job[nb].st = *st;
            job[nb].ax = acc.x;
            job[nb].ay = acc.y;
            job[nb].aa = acc.a;
            job[nb].placed = placed;
            job[nb].events = events;
            job[nb].ev = pend;
            pend.n = 0;
            events = 0;
            sim_render_scene(sc, st, &job[nb].scene);
            acc.x = acc.y = acc.a = 0;
            placed = 0;
            if (++nb == LR_BATCH)
                break;
        }
        if (o->frames && nb > 0 && !cache_read) {
            t0 = lr_now_s();
            lr_render_batch(job, nb, nthreads);
            res->render_s += lr_now_s() - t0;
        }
        /* 2. localize each record of the batch in order */
        for (b = 0; b < nb; b++) {
            const sim_step_t *sp = o->frames ? &job[b].st : st;
            double t = sp->t_ms / 1000.0, pe = 0, he = 0;
            lr_walk_step_t ws;
            long n = met.n;
            int q;
            if (o->frames && job[b].rc != 0) {
                unsigned long idx = (unsigned long)sp->index;
                for (; b < nb; b++)
                    render_frame_free(&job[b].fr);
                lr_metrics_free(&met);
                lr_free(&lr);
                free(sim);
                free(st);
                free(job);
                if (cache != NULL)
                    fclose(cache);
                return lr_fail(err, err_len, 0, "render failed at step %lu", idx);
            }
            for (q = 0; q < job[b].ev.n; q++)
                lr_metrics_event(&met, job[b].ev.ev[q].bits, job[b].ev.ev[q].t_ms / 1000.0);
            if (o->stream != NULL) {
                ls_write_record(o->stream, n, sp->index, sp->t_ms, sp->x_mm, sp->y_mm,
                                sp->heading);
                for (q = 0; q < job[b].ev.n; q++) {
                    const lr_ev_t *e = &job[b].ev.ev[q];
                    ls_write_events(o->stream, e->bits, e->step, e->t_ms, e->x_mm, e->y_mm,
                                    e->heading);
                }
            }
            if (!o->frames) {
                /* feature mode: predict, placement, update every step */
                lr_call_predict(&lr, sp->odo_dx_mm, sp->odo_dy_mm, sp->odo_dtheta);
                if (sp->events & SIM_EV_PENALIZED)
                    lr_place(&lr, sc);
                lr_call_update(&lr, &sp->obs, NULL);
            } else {
                if (job[b].placed)
                    lr_place(&lr, sc);
                t0 = lr_now_s();
                lr_predict(&lr, job[b].ax, job[b].ay, job[b].aa);
                if (cache_read) {
                    uint32_t idx = 0;
                    fl_obs_list_t cached;
                    if (fread(&idx, sizeof idx, 1, cache) != 1 ||
                        fread(&cached, sizeof cached, 1, cache) != 1 || idx != sp->index) {
                        fl_obs_list_clear(&cached);
                        if (cache_read == 1)
                            fprintf(stderr, "simulate: observation cache %s ends or differs at "
                                            "step %lu: no observations from there on\n",
                                    o->obs_cache, (unsigned long)sp->index);
                        cache_read = 2;
                    }
                    lr_frame_obs(&lr, &sp->head, &cached);
                } else {
                    lr_frame(&lr, &job[b].fr.view, &sp->head);
                    if (cache != NULL) {
                        uint32_t idx = sp->index;
                        fwrite(&idx, sizeof idx, 1, cache);
                        fwrite(&lr.obs, sizeof lr.obs, 1, cache);
                    }
                }
                res->vision_grid_s += lr_now_s() - t0;
                lr_vdiag_frame(res->vdiag, sc, &lr.cam, sp, &lr.obs);
            }
            lr.loc->estimate(lr.state, &est);
            if (lr_metrics_record(&met, t, &est, sp->x_mm, sp->y_mm, sp->heading, &pe, &he) <
                0) {
                for (; b < nb; b++)
                    if (o->frames && !cache_read)
                        render_frame_free(&job[b].fr);
                lr_metrics_free(&met);
                lr_free(&lr);
                free(sim);
                free(st);
                free(job);
                if (cache != NULL)
                    fclose(cache);
                return lr_fail(err, err_len, 0, "out of memory");
            }
            if (o->steps != NULL) {
                lr_print_step(o->steps, sp->index, t, &est, sp->x_mm, sp->y_mm, sp->heading, pe,
                              he);
                if (o->print_obs)
                    lr_print_obs(o->steps, o->frames ? &lr.obs : &sp->obs);
            }
            if (o->hook != NULL) {
                ws.sc = sc;
                ws.st = sp;
                ws.lr = &lr;
                ws.est = &est;
                ws.frame = o->frames && !cache_read ? &job[b].fr : NULL;
                ws.record = n;
                ws.t_s = t;
                ws.pos_err_mm = pe;
                ws.head_err_deg = he;
                ws.half_known = met.half_known;
                ws.events = o->frames ? job[b].events : sp->events;
                o->hook(o->user, &ws);
            }
            if (o->frames && !cache_read)
                render_frame_free(&job[b].fr);
        }
    }
    lr_metrics_finish(&met, res);
    if (o->stream != NULL)
        ls_write_end(o->stream, res->records);
    lr.loc->stats(lr.state, &res->stats);
    if (cache != NULL)
        fclose(cache);
    lr_metrics_free(&met);
    lr_free(&lr);
    free(sim);
    free(st);
    free(job);
    return 0;
}

static void lr_print_val(FILE *f, const char *name, double v, int decimals)
{
    if (isnan(v))
        fprintf(f, "%s nan\n", name);
    else if (isinf(v))
        fprintf(f, "%s inf\n", name);
    else
        fprintf(f, "%s %.*f\n", name, decimals, v);
}

void lr_walk_print_stats(FILE *f, const lr_walk_result_t *res)
{
    fprintf(f, "# localizer: %u kidnaps detected, %u empty resets, %u mode switches, "
               "%u obs used, %u deferred (contradicting the tracked mode), %u ignored, "
               "%u odometry rejected\n",
            res->stats.kidnaps, res->stats.empty_resets, res->stats.mode_switches,
            res->stats.obs_used, res->stats.obs_gated, res->stats.obs_ignored,
            res->stats.odo_rejected);
}

void lr_walk_print_summary(FILE *f, const lr_walk_result_t *res)
{
    static const char *const why[] = {"", "before the penalty placement at",
                                      "before the next kidnap at", "before the run ended at"};
    int k;
    for (k = 0; k < res->n_kidnaps; k++) {
        const lr_kidnap_t *kd = &res->kidnap[k];
        if (kd->end == LR_KIDNAP_RECOVERED)
            fprintf(f, "# kidnap %d at %.2f recovered after %.2f s\n", k + 1, kd->t_s,
                    kd->recover_s);
        else
            fprintf(f, "# kidnap %d at %.2f never recovered %s %.2f\n", k + 1, kd->t_s,
                    why[kd->end], kd->end_s);
    }
    if (res->n_kidnaps > 0) {
        fprintf(f, "# ");
        lr_print_val(f, "kidnap_recover_worst_s", res->kidnap_recover_worst_s, 2);
    }
    fprintf(f, "# penalty_recover_s %.2f (its window is excluded like the kidnap's)\n",
            res->penalty_recover_s);
    fprintf(f, "# every record after convergence, nothing excluded: pos_rmse_mm %.1f "
               "heading_rmse_deg %.2f\n",
            res->pos_rmse_all_mm, res->heading_rmse_all_deg);
    lr_print_val(f, "pos_rmse_mm", res->pos_rmse_mm, 1);
    lr_print_val(f, "heading_rmse_deg", res->heading_rmse_deg, 2);
    lr_print_val(f, "converge_s", res->converge_s, 2);
    lr_print_val(f, "kidnap_recover_s", res->kidnap_recover_s, 2);
    fprintf(f, "flips %ld\n", res->flips);
}

void lr_walk_print_vdiag(FILE *f, const lr_walk_result_t *res)
{
    static const char *const names[FL_LM_KIND_COUNT] = {
        "L", "T", "X", "penalty_mark", "centre_mark", "post", "circle", "beacon",
        "corner_c", "corner_tfield", "corner_tnet", "net"};
    int k;
    fprintf(f, "# vision vs map at the true pose (per kind): obs matched wrong_kind false | "
               "visible found | mean |range err| %% mean |bearing err| deg\n");
    for (k = 0; k < FL_LM_KIND_COUNT; k++) {
        const lr_vdiag_t *d = &res->vdiag[k];
        if (d->n_obs == 0 && d->truth_visible == 0)
            continue;
        fprintf(f, "# vision %-12s %6u %6u %5u %6u | %6u %6u (%.0f%%) | %5.1f %5.2f\n", names[k],
                d->n_obs, d->matched, d->wrong_kind, d->false_pos, d->truth_visible,
                d->truth_found,
                d->truth_visible ? 100.0 * d->truth_found / d->truth_visible : 0.0,
                d->matched ? d->sum_abs_range_pct / d->matched : 0.0,
                d->matched ? d->sum_abs_bearing_deg / d->matched : 0.0);
        if (d->side_known > 0)
            fprintf(f, "# vision %-12s side given %u, wrong %u (%.0f%%)\n", names[k],
                    d->side_known, d->side_wrong, 100.0 * d->side_wrong / d->side_known);
    }
}

/* ---- parameters by name ------------------------------------------------------ */

/* The localizer's vision preset for a NAO camera (fuzzy: fl_fuzzy_params_vision,
 * src/loc/fuzzy.c, where its measurements are); lr_init applies params_adapt
 * for the actual camera. */
void lr_params_frames(const fl_localizer_t *loc, void *p)
{
    loc->params_preset(p, FL_LOC_PRESET_VISION);
}

const fl_localizer_t *lr_localizer(const char *name, char *err, int err_len)
{
    const fl_localizer_t *loc = fl_localizer_find(name != NULL ? name : "fuzzy");
    uint16_t i;
    size_t n;
    if (loc != NULL)
        return loc;
    if (err != NULL && err_len > 0) {
        snprintf(err, (size_t)err_len, "unknown localizer '%s' (known:", name);
        for (i = 0; i < fl_localizer_count(); i++) {
            n = strlen(err);
            snprintf(err + n, (size_t)err_len - n, " %s", fl_localizer_get(i)->name);
        }
        n = strlen(err);
        snprintf(err + n, (size_t)err_len - n, ")");
    }
    return NULL;
}

void *lr_params_new(const fl_localizer_t *loc)
{
    void *p = loc != NULL ? malloc(loc->params_size) : NULL;
    if (p != NULL)
        loc->params_default(p);
    return p;
}

int lr_param_set(const fl_localizer_t *loc, void *p, const char *assign)
{
    const char *eq = assign ? strchr(assign, '=') : NULL;
    char name[128], *end;
    long v;
    size_t n;
    if (loc == NULL || p == NULL || eq == NULL)
        return -1;
    n = (size_t)(eq - assign);
    if (n >= sizeof name)
        return -1;
    memcpy(name, assign, n);
    name[n] = '\0';
    errno = 0;
    v = strtol(eq + 1, &end, 10);
    if (*end != '\0' || eq[1] == '\0' || errno != 0 || v < INT32_MIN || v > INT32_MAX)
        return -1;
    if (fl_localizer_param_set(loc, p, name, (int32_t)v) != FL_OK)
        return -1;
    return loc->params_check(p) == FL_OK ? 0 : -1;
}

int lr_param_diff(const fl_localizer_t *loc, const void *p, const void *ref)
{
    uint16_t i;
    int n = 0;
    for (i = 0; i < loc->n_param; i++) {
        int32_t a = 0, b = 0;
        fl_localizer_param_get(loc, p, loc->param[i].name, &a);
        fl_localizer_param_get(loc, ref, loc->param[i].name, &b);
        n += a != b;
    }
    return n;
}

void lr_param_print(FILE *f, const fl_localizer_t *loc, const void *p, const void *ref)
{
    uint16_t i;
    for (i = 0; i < loc->n_param; i++) {
        int32_t a = 0, b = 0;
        const char *nm = loc->param[i].name;
        fl_localizer_param_get(loc, p, nm, &a);
        if (ref != NULL)
            fl_localizer_param_get(loc, ref, nm, &b);
        if (ref == NULL || a != b)
            fprintf(f, " %s=%ld", nm, (long)a);
    }
}
