/*
 * tools/eval/calib_frames.c - camera fit to detected field lines at known
 * poses (model, file format and algorithm: calib_frames.h).
 *
 * Invariant: only the parameters selected in the options change; the
 * residual of a parameter set is computed by the firmware projection with
 * the parameters rounded to its units, so what is printed is what the
 * robot gets from the written calibration.
 */
#include "eval/calib_frames.h"
#include "eval/detect.h"
#include "io/textfile.h"
#include "world/render.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CF_PI 3.14159265358979323846
#define CF_DEG_STEP (16.0 * 360.0 / 65536.0) /* finite-difference step of angles */
#define CF_MM_STEP 4.0

/* ---- frames file -------------------------------------------------------------- */

static const char *cf_parse_line(char *s, const char *dir, cf_frame_t *f, int *is_frame)
{
    static const char *const names[] = {"X_MM", "Y_MM", "HEADING_DEG", "HEAD_YAW_DEG",
                                        "HEAD_PITCH_DEG", "TORSO_PITCH_DEG", "TORSO_ROLL_DEG"};
    static const double lim[] = {20000, 20000, 360, 180, 180, 180, 180};
    static char why[160];
    char *w[10], *save = NULL, *t;
    double v[7] = {0};
    int n = 0, k;
    size_t len;
    for (t = strtok_r(s, " \t\r", &save); t && n < 10; t = strtok_r(NULL, " \t\r", &save))
        w[n++] = t;
    *is_frame = n > 0;
    if (n == 0)
        return NULL;
    if (n != 6 && n != 8)
        return "expected: IMAGE X_MM Y_MM HEADING_DEG HEAD_YAW_DEG HEAD_PITCH_DEG "
               "[TORSO_PITCH_DEG TORSO_ROLL_DEG]";
    for (k = 1; k < n; k++) {
        const char *e = tf_number(w[k], lim[k - 1], &v[k - 1]);
        if (e) {
            snprintf(why, sizeof why, "%s: %s '%.40s' (|value| <= %g)", names[k - 1], e, w[k],
                     lim[k - 1]);
            return why;
        }
    }
    memset(f, 0, sizeof *f);
    len = strlen(w[0]);
    if (w[0][0] != '/' && dir && dir[0]) {
        if (strlen(dir) + 1 + len >= sizeof f->image)
            return "image path too long";
        size_t nd = strlen(dir);
        memcpy(f->image, dir, nd);
        f->image[nd] = '/';
        memcpy(f->image + nd + 1, w[0], len + 1);
    } else {
        if (len >= sizeof f->image)
            return "image path too long";
        memcpy(f->image, w[0], len + 1);
    }
    f->x_mm = v[0];
    f->y_mm = v[1];
    f->heading_deg = v[2];
    f->head_yaw_deg = v[3];
    f->head_pitch_deg = v[4];
    f->torso_pitch_deg = v[5];
    f->torso_roll_deg = v[6];
    return NULL;
}

int cf_frames_parse(const char *text, size_t len, const char *name, const char *dir,
                    cf_frames_t *out, char *err, int err_len)
{
    size_t pos = 0;
    int line = 0, cap = 0;
    char buf[CF_LINE_MAX + 2];
    memset(out, 0, sizeof *out);
    while (pos < len) {
        const char *s = text + pos, *lf = memchr(s, '\n', len - pos);
        size_t n = lf ? (size_t)(lf - s) : len - pos, used;
        const char *why;
        int is_frame = 0;
        cf_frame_t f;
        line++;
        pos += n + 1;
        /* the firmware formats' line rules: length, NUL, comment, CR */
        if (fl_text_line(s, n, CF_LINE_MAX, &used, &why) == FL_OK) {
            memcpy(buf, s, used);
            buf[used] = '\0';
            why = cf_parse_line(buf, dir, &f, &is_frame);
            if (!why && is_frame && out->n >= CF_MAX_FRAMES)
                why = "too many frames";
        }
        if (why) {
            tf_err(err, err_len, "%s:%d: %s", name, line, why);
            cf_frames_free(out);
            return -1;
        }
        if (!is_frame)
            continue;
        if (out->n == cap) {
            cf_frame_t *nf;
            cap = cap ? 2 * cap : 16;
            nf = realloc(out->f, sizeof *nf * (size_t)cap);
            if (!nf) {
                tf_err(err, err_len, "%s: out of memory", name);
                cf_frames_free(out);
                return -1;
            }
            out->f = nf;
        }
        f.line = line;
        out->f[out->n++] = f;
    }
    if (out->n == 0) {
        tf_err(err, err_len, "%s:%d: no frame in the file", name, line);
        return -1;
    }
    return 0;
}

int cf_frames_load(const char *path, cf_frames_t *out, char *err, int err_len)
{
    FILE *fp = fopen(path, "rb");
    char *text, dir[CF_PATH_MAX];
    const char *slash = strrchr(path, '/');
    long sz;
    size_t got;
    int rc;
    memset(out, 0, sizeof *out);
    if (!fp) {
        tf_err(err, err_len, "%s: cannot open", path);
        return -1;
    }
    if (fseek(fp, 0, SEEK_END) != 0 || (sz = ftell(fp)) < 0 || fseek(fp, 0, SEEK_SET) != 0 ||
        sz > 64L * 1024 * 1024) {
        fclose(fp);
        tf_err(err, err_len, "%s: cannot read (or larger than 64 MB)", path);
        return -1;
    }
    text = malloc((size_t)sz + 1);
    if (!text) {
        fclose(fp);
        tf_err(err, err_len, "%s: out of memory", path);
        return -1;
    }
    got = fread(text, 1, (size_t)sz, fp);
    fclose(fp);
    text[got] = '\0';
    dir[0] = '\0';
    if (slash && (size_t)(slash - path) < sizeof dir) {
        memcpy(dir, path, (size_t)(slash - path));
        dir[slash - path] = '\0';
        if (slash == path)
            strcpy(dir, "/");
    }
    rc = cf_frames_parse(text, got, path, dir, out, err, err_len);
    free(text);
    return rc;
}

void cf_frames_free(cf_frames_t *fr)
{
    free(fr->f);
    fr->f = NULL;
    fr->n = 0;
}

/* ---- model ------------------------------------------------------------------------ */

void cf_options_default(cf_options_t *o)
{
    o->fit_neck = o->fit_pitch = o->fit_roll = 1;
    o->gate_px = 6.0;
    o->huber_px = 1.0;
    o->grid = 1;
    o->fit_heading = 0;
    o->sigma_heading_deg = 5.0;
    o->sigma_xy_mm = 100.0;
}

static fl_angle_t cf_angle(double deg)
{
    double md = deg * 1000.0;
    if (md > 2e9)
        md = 2e9;
    if (md < -2e9)
        md = -2e9;
    return fl_angle_from_mdeg((int32_t)lround(md));
}

void cf_pose(const cf_frame_t *f, const cf_params_t *p, fl_camera_pose_t *pose)
{
    memset(pose, 0, sizeof *pose);
    pose->neck_height_mm = (int32_t)lround(p->neck_mm);
    pose->head_pitch = cf_angle(f->head_pitch_deg);
    pose->head_yaw = cf_angle(f->head_yaw_deg);
    pose->pitch_offset = cf_angle(p->pitch_offset_deg);
    pose->roll_offset = cf_angle(p->roll_offset_deg);
    pose->torso_pitch = cf_angle(f->torso_pitch_deg);
    pose->torso_roll = cf_angle(f->torso_roll_deg);
}

typedef struct {
    int32_t *uv;      /* u_q4, v_q4 pairs */
    int n;
    int used;         /* frame read and detected */
} cf_fpts_t;

typedef struct {
    const cf_frames_t *fr;
    const fl_field_t *field;
    const fl_camera_model_t *m;
    cf_fpts_t *pts;
    int n_total;      /* points over all frames */
    double gate, huber;
    double *corr;     /* per-frame pose correction (heading deg, x mm, y mm;
                         fit_heading), NULL: the poses as given */
} cf_prob_t;

/* Distance (mm) of a field point to the nearest painted line. */
static double cf_line_dist(const fl_field_t *f, double x, double y)
{
    double best = fabs(hypot(x, y) - f->circle_radius_mm);
    uint16_t i;
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *l = &f->lines[i];
        double ax = l->x0_mm, ay = l->y0_mm, dx = l->x1_mm - ax, dy = l->y1_mm - ay;
        double L2 = dx * dx + dy * dy, t = L2 > 0 ? ((x - ax) * dx + (y - ay) * dy) / L2 : 0;
        double d;
        if (t < 0)
            t = 0;
        if (t > 1)
            t = 1;
        d = hypot(x - ax - t * dx, y - ay - t * dy);
        if (d < best)
            best = d;
    }
    return best;
}

/* Residuals of frame k's points for p and heading correction dth (deg)
 * into r (the frame's n entries; invalid points get -1).  Returns the
 * number of valid points. */
static int cf_frame_res(const cf_prob_t *pb, int k, const cf_params_t *p, const double *corr,
                        double *r)
{
    static const double zero[3] = {0, 0, 0};
    const cf_frame_t *fr = &pb->fr->f[k];
    const cf_fpts_t *pt = &pb->pts[k];
    fl_camera_pose_t pose;
    fl_camera_t cam;
    double f = pb->m->focal_q4 / 16.0;
    const double *cr = corr ? corr : zero;
    double th = (fr->heading_deg + cr[0]) * CF_PI / 180.0, c = cos(th), s = sin(th), h;
    int i, ok, valid = 0;
    cf_pose(fr, p, &pose);
    ok = pt->used && fl_camera_init(&cam, pb->m, &pose) == FL_OK;
    h = cam.pos_q4[2] / 16.0;
    for (i = 0; i < pt->n; i++) {
        fl_point_t g;
        double fx, fy, d;
        r[i] = -1;
        if (!ok || !fl_camera_pixel_to_ground(&cam, pt->uv[2 * i], pt->uv[2 * i + 1], &g))
            continue;
        fx = fr->x_mm + cr[1] + c * g.x_mm - s * g.y_mm;
        fy = fr->y_mm + cr[2] + s * g.x_mm + c * g.y_mm;
        d = cf_line_dist(pb->field, fx, fy);
        r[i] = d * f / sqrt((double)g.x_mm * g.x_mm + (double)g.y_mm * g.y_mm + h * h);
        valid++;
    }
    return valid;
}

/* Residuals of every point for p into r (n_total entries). */
static int cf_residuals(const cf_prob_t *pb, const cf_params_t *p, double *r)
{
    int k, n = 0, valid = 0;
    for (k = 0; k < pb->fr->n; k++) {
        valid += cf_frame_res(pb, k, p, pb->corr ? pb->corr + 3 * k : NULL, r + n);
        n += pb->pts[k].n;
    }
    return valid;
}

static double cf_grid_cost(const cf_prob_t *pb, const double *r)
{
    double s = 0, g = pb->gate;
    int i;
    for (i = 0; i < pb->n_total; i++)
        s += (r[i] < 0 || r[i] > g) ? g * g : r[i] * r[i];
    return s;
}

/* Huber cost over the active set (act[i] != 0); invalid points cost the
 * gate (a step that loses points is not free). */
static double cf_cost(const cf_prob_t *pb, const double *r, const unsigned char *act)
{
    double s = 0, h = pb->huber, g = pb->gate;
    int i;
    for (i = 0; i < pb->n_total; i++) {
        double e;
        if (!act[i])
            continue;
        e = r[i] < 0 ? g : r[i];
        s += e <= h ? e * e : 2 * h * e - h * h;
    }
    return s;
}

static double *cf_par(cf_params_t *p, int j)
{
    return j == 0 ? &p->neck_mm : j == 1 ? &p->pitch_offset_deg : &p->roll_offset_deg;
}

/* Solve the n x n system A x = b (n <= 3) by Gaussian elimination with
 * partial pivoting; A and b are destroyed.  0, or -1 when singular. */
static int cf_solve(int n, double A[3][3], double b[3], double x[3])
{
    int i, j, k;
    for (i = 0; i < n; i++) {
        int piv = i;
        for (k = i + 1; k < n; k++)
            if (fabs(A[k][i]) > fabs(A[piv][i]))
                piv = k;
        if (fabs(A[piv][i]) < 1e-300)
            return -1;
        if (piv != i) {
            double t;
            for (j = 0; j < n; j++) {
                t = A[i][j];
                A[i][j] = A[piv][j];
                A[piv][j] = t;
            }
            t = b[i];
            b[i] = b[piv];
            b[piv] = t;
        }
        for (k = i + 1; k < n; k++) {
            double m = A[k][i] / A[i][i];
            for (j = i; j < n; j++)
                A[k][j] -= m * A[i][j];
            b[k] -= m * b[i];
        }
    }
    for (i = n - 1; i >= 0; i--) {
        double s = b[i];
        for (j = i + 1; j < n; j++)
            s -= A[i][j] * x[j];
        x[i] = s / A[i][i];
    }
    return 0;
}

typedef struct {
    double *r, *rp, *J[3];
    double *K[3];           /* Jacobian columns of the pose corrections */
    unsigned char *act;
} cf_work_t;

/* Column j of the Jacobian at p into w->J[j], by central differences
 * (w->rp is scratch); a point that misses the image on either side gets 0. */
static void cf_jacobian_column(const cf_prob_t *pb, const cf_params_t *p, const int *id,
                               int j, cf_work_t *w)
{
    cf_params_t q = *p;
    double step = id[j] == 0 ? CF_MM_STEP : CF_DEG_STEP;
    int i;
    *cf_par(&q, id[j]) += step;
    cf_residuals(pb, &q, w->J[j]);
    q = *p;
    *cf_par(&q, id[j]) -= step;
    cf_residuals(pb, &q, w->rp);
    for (i = 0; i < pb->n_total; i++)
        w->J[j][i] = (w->J[j][i] < 0 || w->rp[i] < 0) ? 0 : (w->J[j][i] - w->rp[i]) / (2 * step);
}

/* Normal equations of the active points at p (residuals in w->r). */
static int cf_normal(const cf_prob_t *pb, const cf_params_t *p, const int *id, int np,
                     cf_work_t *w, double A[3][3], double g[3], double *wssr, int *used)
{
    int j, k, i;
    for (j = 0; j < np; j++)
        cf_jacobian_column(pb, p, id, j, w);
    memset(A, 0, sizeof(double) * 9);
    memset(g, 0, sizeof(double) * 3);
    *wssr = 0;
    *used = 0;
    for (i = 0; i < pb->n_total; i++) {
        double e = w->r[i], wt;
        if (!w->act[i] || e < 0)
            continue;
        wt = e <= pb->huber ? 1.0 : pb->huber / e;
        for (j = 0; j < np; j++) {
            for (k = 0; k < np; k++)
                A[j][k] += wt * w->J[j][i] * w->J[k][i];
            g[j] += wt * w->J[j][i] * e;
        }
        *wssr += wt * e * e;
        (*used)++;
    }
    return *used > np ? 0 : -1;
}

static void cf_activate(const cf_prob_t *pb, cf_work_t *w)
{
    int i;
    for (i = 0; i < pb->n_total; i++)
        w->act[i] = w->r[i] >= 0 && w->r[i] <= pb->gate;
}

/* The parameters the options fit, as cf_par indices in id[]; their count. */
static int cf_selected(const cf_options_t *o, int id[3])
{
    int np = 0;
    if (o->fit_neck)
        id[np++] = 0;
    if (o->fit_pitch)
        id[np++] = 1;
    if (o->fit_roll)
        id[np++] = 2;
    return np;
}

/* LM from p; returns the iterations, -1 on failure.  sigma[3] out. */
static int cf_lm(const cf_prob_t *pb, const cf_options_t *o, cf_params_t *p, cf_work_t *w,
                 double sigma[3])
{
    int id[3], np, it, j, used = 0;
    double lambda = 1e-3, A[3][3], g[3], wssr;
    np = cf_selected(o, id);
    sigma[0] = sigma[1] = sigma[2] = 0;
    if (np == 0)
        return 0;
    for (it = 0; it < 60; it++) {
        double cost;
        int improved = 0;
        cf_residuals(pb, p, w->r);
        cf_activate(pb, w);
        cost = cf_cost(pb, w->r, w->act);
        if (cf_normal(pb, p, id, np, w, A, g, &wssr, &used) != 0)
            return -1;
        while (lambda < 1e10) {
            double B[3][3], b[3], dx[3];
            cf_params_t q = *p;
            int k;
            for (j = 0; j < np; j++) {
                for (k = 0; k < np; k++)
                    B[j][k] = A[j][k];
                B[j][j] += lambda * (A[j][j] > 0 ? A[j][j] : 1.0);
                b[j] = -g[j];
            }
            if (cf_solve(np, B, b, dx) == 0) {
                double nc;
                for (j = 0; j < np; j++)
                    *cf_par(&q, id[j]) += dx[j];
                cf_residuals(pb, &q, w->rp);
                nc = cf_cost(pb, w->rp, w->act);
                if (nc < cost) {
                    improved = (cost - nc) > 1e-9 * cost ? 1 : 2;
                    *p = q;
                    lambda = lambda > 1e-9 ? lambda * 0.3 : lambda;
                    break;
                }
            }
            lambda *= 10;
        }
        if (improved != 1)
            break;
    }
    /* uncertainty at the solution */
    cf_residuals(pb, p, w->r);
    cf_activate(pb, w);
    if (cf_normal(pb, p, id, np, w, A, g, &wssr, &used) == 0) {
        double s2 = wssr / (used - np);
        for (j = 0; j < np; j++) {
            double Ai[3][3], e[3] = {0, 0, 0}, x[3];
            memcpy(Ai, A, sizeof Ai);
            e[j] = 1;
            if (cf_solve(np, Ai, e, x) == 0 && x[j] > 0)
                sigma[id[j]] = sqrt(x[j] * s2);
        }
    }
    return it;
}

/* Joint Levenberg-Marquardt over the camera parameters and every frame's
 * pose correction (fit_heading).  The normal matrix is block-arrow shaped
 * (a camera block, a 3x3 block per frame, and camera x frame blocks), so
 * each step eliminates the frames (Schur complement) and solves for the
 * camera first.  Returns the iterations, -1 on failure; sigma[3] out (of
 * the camera parameters, from the Schur complement). */
static int cf_lm_joint(cf_prob_t *pb, const cf_options_t *o, const double *psig, cf_params_t *p,
                       cf_work_t *w, double sigma[3])
{
    static const double cstep[3] = {0.05, 5.0, 5.0};
    int id[3], np, it, j, m, i, k, nf = pb->fr->n, used = 0, ret = -1;
    double lambda = 1e-3, wssr = 0, Acc[3][3], gc[3];
    /* per frame: Akk 9, gk 3, Ack 9 (np x 3; 3 rows kept), y 3 */
    double *blk = malloc(sizeof(double) * 24 * (size_t)(nf + 1));
    double *nc = malloc(sizeof(double) * 3 * (size_t)(nf + 1));
    if (!blk || !nc)
        goto out;
    np = cf_selected(o, id);
    sigma[0] = sigma[1] = sigma[2] = 0;
    for (it = 0; it < 100; it++) {
        double cost = 0;
        int improved = 0, off;
        cf_residuals(pb, p, w->r);
        cf_activate(pb, w);
        /* camera columns */
        for (j = 0; j < np; j++)
            cf_jacobian_column(pb, p, id, j, w);
        /* correction columns, frame by frame */
        for (k = 0, off = 0; k < nf; off += pb->pts[k].n, k++)
            for (j = 0; j < 3; j++) {
                double c[3];
                memcpy(c, pb->corr + 3 * k, sizeof c);
                c[j] += cstep[j];
                cf_frame_res(pb, k, p, c, w->K[j] + off);
                c[j] -= 2 * cstep[j];
                cf_frame_res(pb, k, p, c, w->rp + off);
                for (i = off; i < off + pb->pts[k].n; i++)
                    w->K[j][i] = (w->K[j][i] < 0 || w->rp[i] < 0) ? 0
                                 : (w->K[j][i] - w->rp[i]) / (2 * cstep[j]);
            }
        memset(Acc, 0, sizeof Acc);
        memset(gc, 0, sizeof gc);
        memset(blk, 0, sizeof(double) * 24 * (size_t)nf);
        wssr = 0;
        used = 0;
        for (k = 0, off = 0; k < nf; off += pb->pts[k].n, k++) {
            double *Akk = blk + 24 * k, *gk = Akk + 9, *Ack = Akk + 12;
            for (j = 0; j < 3; j++) {
                double ps = 1.0 / (psig[j] * psig[j]), cj = pb->corr[3 * k + j];
                Akk[4 * j] += ps;
                gk[j] += ps * cj;
                cost += ps * cj * cj;
            }
            for (i = off; i < off + pb->pts[k].n; i++) {
                double e = w->r[i], wt;
                if (!w->act[i] || e < 0)
                    continue;
                wt = e <= pb->huber ? 1.0 : pb->huber / e;
                cost += e <= pb->huber ? e * e : 2 * pb->huber * e - pb->huber * pb->huber;
                for (j = 0; j < 3; j++) {
                    for (m = 0; m < 3; m++) {
                        Akk[3 * j + m] += wt * w->K[j][i] * w->K[m][i];
                        if (j < np)
                            Ack[3 * j + m] += wt * w->J[j][i] * w->K[m][i];
                        if (j < np && m < np)
                            Acc[j][m] += wt * w->J[j][i] * w->J[m][i];
                    }
                    gk[j] += wt * w->K[j][i] * e;
                    if (j < np)
                        gc[j] += wt * w->J[j][i] * e;
                }
                wssr += wt * e * e;
                used++;
            }
        }
        if (used <= np + 3)
            goto out;
        while (lambda < 1e10) {
            double S[3][3], rhs[3], dc[3] = {0, 0, 0}, newcost;
            cf_params_t q = *p;
            int ok = 1;
            for (j = 0; j < np; j++) {
                for (m = 0; m < np; m++)
                    S[j][m] = Acc[j][m];
                S[j][j] += lambda * (Acc[j][j] > 0 ? Acc[j][j] : 1.0);
                rhs[j] = -gc[j];
            }
            /* eliminate the frames: S -= Ack Akk^-1 Akc, rhs -= Ack Akk^-1 (-gk) */
            for (k = 0; k < nf && ok; k++) {
                double *Akk = blk + 24 * k, *gk = Akk + 9, *Ack = Akk + 12;
                double D[3][3], X[3][3], b[3], y[3];
                for (j = 0; j < 3; j++)
                    for (m = 0; m < 3; m++)
                        D[j][m] = Akk[3 * j + m] + (j == m ? lambda * Akk[4 * j] : 0);
                /* X = D^-1 Akc (columns j: Ack row j), y = D^-1 (-gk) */
                for (j = 0; j < np && ok; j++) {
                    double Dc[3][3], col[3];
                    memcpy(Dc, D, sizeof Dc);
                    for (m = 0; m < 3; m++)
                        col[m] = Ack[3 * j + m];
                    ok = cf_solve(3, Dc, col, X[j]) == 0;
                }
                if (!ok)
                    break;
                {
                    double Dc[3][3];
                    memcpy(Dc, D, sizeof Dc);
                    for (m = 0; m < 3; m++)
                        b[m] = -gk[m];
                    ok = cf_solve(3, Dc, b, y) == 0;
                }
                for (j = 0; j < np && ok; j++) {
                    for (m = 0; m < np; m++)
                        S[j][m] -= Ack[3 * j + 0] * X[m][0] + Ack[3 * j + 1] * X[m][1] +
                                   Ack[3 * j + 2] * X[m][2];
                    rhs[j] -= Ack[3 * j + 0] * y[0] + Ack[3 * j + 1] * y[1] + Ack[3 * j + 2] * y[2];
                }
                memcpy(blk + 24 * k + 21, y, sizeof y); /* for the back-substitution */
            }
            if (ok && np > 0)
                ok = cf_solve(np, S, rhs, dc) == 0;
            if (ok) {
                /* back-substitute: dk = y - D^-1 Akc dc */
                for (k = 0; k < nf && ok; k++) {
                    double *Akk = blk + 24 * k, *Ack = Akk + 12, *y = Akk + 21;
                    double D[3][3], b[3], dk[3];
                    for (j = 0; j < 3; j++)
                        for (m = 0; m < 3; m++)
                            D[j][m] = Akk[3 * j + m] + (j == m ? lambda * Akk[4 * j] : 0);
                    for (m = 0; m < 3; m++) {
                        b[m] = 0;
                        for (j = 0; j < np; j++)
                            b[m] += Ack[3 * j + m] * dc[j];
                    }
                    ok = cf_solve(3, D, b, dk) == 0;
                    for (m = 0; m < 3; m++)
                        nc[3 * k + m] = pb->corr[3 * k + m] + y[m] - dk[m];
                }
            }
            if (ok) {
                double *old = pb->corr;
                for (j = 0; j < np; j++)
                    *cf_par(&q, id[j]) += dc[j];
                pb->corr = nc;
                cf_residuals(pb, &q, w->rp);
                pb->corr = old;
                newcost = 0;
                for (k = 0; k < nf; k++)
                    for (j = 0; j < 3; j++)
                        newcost += (nc[3 * k + j] / psig[j]) * (nc[3 * k + j] / psig[j]);
                for (i = 0; i < pb->n_total; i++) {
                    double e;
                    if (!w->act[i])
                        continue;
                    e = w->rp[i] < 0 ? pb->gate : w->rp[i];
                    newcost += e <= pb->huber ? e * e : 2 * pb->huber * e - pb->huber * pb->huber;
                }
                if (newcost < cost) {
                    improved = (cost - newcost) > 1e-9 * cost ? 1 : 2;
                    *p = q;
                    memcpy(pb->corr, nc, sizeof(double) * 3 * (size_t)nf);
                    lambda = lambda > 1e-9 ? lambda * 0.3 : lambda;
                    break;
                }
            }
            lambda *= 10;
        }
        if (improved != 1)
            break;
    }
    /* camera uncertainty: the inverse of the Schur complement (lambda 0)
     * of the last normal equations, scaled by the residual variance */
    if (np > 0) {
        double S[3][3], s2 = wssr / (used - np);
        for (j = 0; j < np; j++)
            for (m = 0; m < np; m++)
                S[j][m] = Acc[j][m];
        for (k = 0; k < nf; k++) {
            double *Akk = blk + 24 * k, *Ack = Akk + 12;
            for (j = 0; j < np; j++) {
                double D[3][3], col[3], x[3];
                memcpy(D, Akk, sizeof D);
                memcpy(col, Ack + 3 * j, sizeof col);
                if (cf_solve(3, D, col, x) != 0)
                    continue;
                for (m = 0; m < np; m++)
                    S[m][j] -= Ack[3 * m] * x[0] + Ack[3 * m + 1] * x[1] + Ack[3 * m + 2] * x[2];
            }
        }
        for (j = 0; j < np; j++) {
            double Si[3][3], e[3] = {0, 0, 0}, x[3];
            memcpy(Si, S, sizeof Si);
            e[j] = 1;
            if (cf_solve(np, Si, e, x) == 0 && x[j] > 0)
                sigma[id[j]] = sqrt(x[j] * s2);
        }
    }
    ret = it;
out:
    free(blk);
    free(nc);
    return ret;
}

static void cf_grid(const cf_prob_t *pb, const cf_options_t *o, cf_params_t *p, double *r)
{
    cf_params_t best = *p, q = *p;
    double bc = 1e300, dp, dn;
    for (dp = -10; dp <= 10.0001; dp += 0.5)
        for (dn = -120; dn <= 120.0001; dn += 10) {
            double c;
            if ((!o->fit_pitch && dp != 0) || (!o->fit_neck && dn != 0))
                continue;
            q.pitch_offset_deg = p->pitch_offset_deg + dp;
            q.neck_mm = p->neck_mm + dn;
            if (q.neck_mm < FL_CAMERA_NECK_MIN_MM)
                continue;
            cf_residuals(pb, &q, r);
            c = cf_grid_cost(pb, r);
            if (c < bc) {
                bc = c;
                best = q;
            }
        }
    *p = best;
}

/* Frame k's cost at pose correction c: Huber over the points marked in
 * act (or truncated at the gate when act is NULL), plus the priors
 * (c_j / sigma_j)^2 (one pseudo-point of 1 px per sigma each). */
static double cf_frame_cost(const cf_prob_t *pb, int k, const cf_params_t *p, const double *c,
                            const double *sigma, const unsigned char *act, double *r)
{
    int i, j, n = pb->pts[k].n;
    double s = 0, g = pb->gate, h = pb->huber;
    for (j = 0; j < 3; j++)
        s += (c[j] / sigma[j]) * (c[j] / sigma[j]);
    cf_frame_res(pb, k, p, c, r);
    for (i = 0; i < n; i++) {
        double e = r[i] < 0 ? g : r[i];
        if (!act)
            s += e > g ? g * g : e * e;
        else if (act[i])
            s += e <= h ? e * e : 2 * h * e - h * h;
    }
    return s;
}

/* Per-frame pose corrections for fixed camera parameters: on the first
 * call a grid of +-10 deg (0.25 deg) over the heading on the truncated
 * cost, then Levenberg-Marquardt over heading, x and y with the points
 * within the gate (Huber, numeric Jacobian).  r, rp, J (3 columns) and
 * act: scratch of the largest frame's size. */
static void cf_poses(const cf_prob_t *pb, const cf_params_t *p, const double *sigma, int grid,
                     double *r, double *rp, double *J[3], unsigned char *act)
{
    static const double step[3] = {0.05, 5.0, 5.0};
    int k, i, j, m, it;
    for (k = 0; k < pb->fr->n; k++) {
        double *c = pb->corr + 3 * k, lambda = 1e-3, cost;
        int n = pb->pts[k].n;
        if (!pb->pts[k].used || n == 0)
            continue;
        if (grid) {
            double bc = 1e300, d, t[3] = {0, 0, 0};
            for (d = -10; d <= 10.0001; d += 0.25) {
                double cc;
                t[0] = d;
                cc = cf_frame_cost(pb, k, p, t, sigma, NULL, r);
                if (cc < bc) {
                    bc = cc;
                    c[0] = d;
                }
            }
            c[1] = c[2] = 0;
        }
        for (it = 0; it < 30; it++) {
            double A[3][3], g[3];
            int improved = 0;
            cf_frame_res(pb, k, p, c, r);
            for (i = 0; i < n; i++)
                act[i] = r[i] >= 0 && r[i] <= pb->gate;
            cost = cf_frame_cost(pb, k, p, c, sigma, act, rp);
            for (j = 0; j < 3; j++) {
                double q[3];
                memcpy(q, c, sizeof q);
                q[j] += step[j];
                cf_frame_res(pb, k, p, q, J[j]);
                q[j] -= 2 * step[j];
                cf_frame_res(pb, k, p, q, rp);
                for (i = 0; i < n; i++)
                    J[j][i] = (J[j][i] < 0 || rp[i] < 0) ? 0 : (J[j][i] - rp[i]) / (2 * step[j]);
            }
            for (j = 0; j < 3; j++) {
                double ps = 1.0 / (sigma[j] * sigma[j]);
                for (m = 0; m < 3; m++)
                    A[j][m] = j == m ? ps : 0;
                g[j] = ps * c[j];
            }
            for (i = 0; i < n; i++) {
                double wt;
                if (!act[i])
                    continue;
                wt = r[i] <= pb->huber ? 1.0 : pb->huber / r[i];
                for (j = 0; j < 3; j++) {
                    for (m = 0; m < 3; m++)
                        A[j][m] += wt * J[j][i] * J[m][i];
                    g[j] += wt * J[j][i] * r[i];
                }
            }
            while (lambda < 1e10) {
                double B[3][3], b[3], dx[3], q[3], nc;
                for (j = 0; j < 3; j++) {
                    for (m = 0; m < 3; m++)
                        B[j][m] = A[j][m];
                    B[j][j] += lambda * A[j][j];
                    b[j] = -g[j];
                }
                if (cf_solve(3, B, b, dx) == 0) {
                    for (j = 0; j < 3; j++)
                        q[j] = c[j] + dx[j];
                    nc = cf_frame_cost(pb, k, p, q, sigma, act, rp);
                    if (nc < cost) {
                        improved = (cost - nc) > 1e-9 * cost ? 1 : 2;
                        memcpy(c, q, sizeof q);
                        lambda = lambda > 1e-9 ? lambda * 0.3 : lambda;
                        break;
                    }
                }
                lambda *= 10;
            }
            if (improved != 1)
                break;
        }
    }
}

static int cf_cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void cf_stats(const double *r, int n, double gate, cf_stats_t *s, double *tmp)
{
    int i, m = 0;
    double ss = 0;
    memset(s, 0, sizeof *s);
    s->n_points = n;
    for (i = 0; i < n; i++)
        if (r[i] >= 0 && r[i] <= gate) {
            tmp[m++] = r[i];
            ss += r[i] * r[i];
        }
    s->n_in = m;
    if (m) {
        qsort(tmp, (size_t)m, sizeof *tmp, cf_cmp_d);
        s->median_px = m % 2 ? tmp[m / 2] : 0.5 * (tmp[m / 2 - 1] + tmp[m / 2]);
        s->rms_px = sqrt(ss / m);
    }
}

/* Detect every frame with parameters p; fills pb->pts (replacing). */
static int cf_detect(cf_prob_t *pb, const cf_params_t *p, det_ctx_t *ctx, cf_warn_fn warn,
                     void *user, int *n_skipped)
{
    int k, i;
    det_feature_t feat[DET_MAX_FEATURES];
    pb->n_total = 0;
    *n_skipped = 0;
    for (k = 0; k < pb->fr->n; k++) {
        const cf_frame_t *f = &pb->fr->f[k];
        cf_fpts_t *pt = &pb->pts[k];
        render_frame_t img;
        fl_camera_pose_t pose;
        fl_camera_t cam;
        char e[256], msg[CF_PATH_MAX + 300];
        const fl_lines_t *ln = &ctx->vis->lines;
        free(pt->uv);
        pt->uv = NULL;
        pt->n = pt->used = 0;
        if (render_read_frame(f->image, &img, e, sizeof e) != 0) {
            snprintf(msg, sizeof msg, "line %d: %s (frame skipped)", f->line, e);
            if (warn)
                warn(msg, user);
            (*n_skipped)++;
            continue;
        }
        cf_pose(f, p, &pose);
        if (img.width != pb->m->width_px || img.height != pb->m->height_px ||
            fl_camera_init(&cam, pb->m, &pose) != FL_OK) {
            snprintf(msg, sizeof msg, "line %d: %s: %dx%d image or head pose does not fit "
                     "camera %s (frame skipped)", f->line, f->image, img.width, img.height,
                     pb->m->name);
            if (warn)
                warn(msg, user);
            render_frame_free(&img);
            (*n_skipped)++;
            continue;
        }
        det_run(ctx, &img.view, &cam, pb->field, NULL, feat, DET_MAX_FEATURES);
        render_frame_free(&img);
        pt->uv = malloc(sizeof(int32_t) * 2 * (size_t)(ln->n_points + 1));
        if (!pt->uv)
            return -1;
        for (i = 0; i < ln->n_points; i++) {
            if (ln->points[i].seg == FL_LINES_NONE)
                continue;
            pt->uv[2 * pt->n] = (int32_t)ln->points[i].u_q1 * 8;
            pt->uv[2 * pt->n + 1] = (int32_t)ln->points[i].v_q1 * 8;
            pt->n++;
        }
        pt->used = 1;
        pb->n_total += pt->n;
    }
    return 0;
}

void cf_result_free(cf_result_t *res)
{
    free(res->before);
    free(res->after);
    free(res->corr);
    res->before = res->after = NULL;
    res->corr = NULL;
}

int cf_fit(const cf_frames_t *fr, const fl_field_t *field, const fl_camera_model_t *m,
           const cf_options_t *o, cf_params_t *p, cf_result_t *res, cf_warn_fn warn,
           void *user, char *err, int err_len)
{
    cf_prob_t pb;
    cf_work_t w;
    det_ctx_t ctx;
    int k, pass, rc = -1, n;
    memset(res, 0, sizeof *res);
    memset(&w, 0, sizeof w);
    memset(&pb, 0, sizeof pb);
    res->start = *p;
    pb.fr = fr;
    pb.field = field;
    pb.m = m;
    pb.gate = o->gate_px;
    pb.huber = o->huber_px;
    pb.pts = calloc((size_t)fr->n + 1, sizeof *pb.pts);
    res->before = calloc((size_t)fr->n + 1, sizeof *res->before);
    res->after = calloc((size_t)fr->n + 1, sizeof *res->after);
    if (!pb.pts || !res->before || !res->after || det_ctx_init(&ctx) != 0) {
        tf_err(err, err_len, "out of memory");
        free(pb.pts);
        cf_result_free(res);
        return -1;
    }
    if (o->fit_heading) {
        pb.corr = calloc(3 * (size_t)fr->n + 1, sizeof *pb.corr);
        res->corr = calloc(3 * (size_t)fr->n + 1, sizeof *res->corr);
        if (!pb.corr || !res->corr) {
            tf_err(err, err_len, "out of memory");
            goto out;
        }
    }
    for (pass = 0; pass < 2; pass++) {
        if (cf_detect(&pb, p, &ctx, pass == 0 ? warn : NULL, user, &res->n_skipped) != 0) {
            tf_err(err, err_len, "out of memory");
            goto out;
        }
        free(w.r);
        w.r = malloc(sizeof(double) * 8 * (size_t)(pb.n_total + 1) + (size_t)pb.n_total + 1);
        if (!w.r) {
            tf_err(err, err_len, "out of memory");
            goto out;
        }
        w.rp = w.r + pb.n_total + 1;
        for (k = 0; k < 3; k++) {
            w.J[k] = w.rp + (size_t)(k + 1) * (size_t)(pb.n_total + 1);
            w.K[k] = w.rp + (size_t)(k + 4) * (size_t)(pb.n_total + 1);
        }
        w.act = (unsigned char *)(w.K[2] + pb.n_total + 1);
        if (pb.n_total < 20) {
            tf_err(err, err_len, "only %d line points detected in %d usable frames (need 20)",
                   pb.n_total, fr->n - res->n_skipped);
            goto out;
        }
        if (pass == 0 && o->grid)
            cf_grid(&pb, o, p, w.r);
        /* with pose corrections: start them for the grid's camera frame by
         * frame, then fit everything jointly */
        if (o->fit_heading) {
            double sig[3];
            sig[0] = o->sigma_heading_deg;
            sig[1] = sig[2] = o->sigma_xy_mm;
            if (pass == 0)
                cf_poses(&pb, p, sig, 1, w.r, w.rp, w.J, w.act);
            n = cf_lm_joint(&pb, o, sig, p, &w, res->sigma);
        } else
            n = cf_lm(&pb, o, p, &w, res->sigma);
        if (n < 0) {
            tf_err(err, err_len, "too few line points near the field lines (fit failed)");
            goto out;
        }
        res->iterations += n;
    }
    if (pb.corr)
        memcpy(res->corr, pb.corr, sizeof *pb.corr * 3 * (size_t)fr->n);
    res->fit = *p;
    res->n_frames = fr->n - res->n_skipped;
    /* before / after on the final points, per frame and in total */
    for (pass = 0; pass < 2; pass++) {
        const cf_params_t *q = pass == 0 ? &res->start : &res->fit;
        cf_stats_t *st = pass == 0 ? res->before : res->after;
        int off = 0;
        double *corr = pb.corr;
        if (pass == 0)
            pb.corr = NULL; /* before: the poses as given */
        cf_residuals(&pb, q, w.r);
        pb.corr = corr;
        for (k = 0; k < fr->n; k++) {
            cf_stats(w.r + off, pb.pts[k].n, pb.gate, &st[k], w.rp);
            off += pb.pts[k].n;
        }
        cf_stats(w.r, pb.n_total, pb.gate, pass == 0 ? &res->before_all : &res->after_all, w.rp);
    }
    rc = 0;
out:
    for (k = 0; k < fr->n; k++)
        free(pb.pts[k].uv);
    free(pb.pts);
    free(pb.corr);
    free(w.r);
    det_ctx_free(&ctx);
    if (rc != 0)
        cf_result_free(res);
    return rc;
}

/* ---- UvA set, calibration files ------------------------------------------------ */

int cf_frames_from_uva(const rd_uva_set_t *set, const char *dir, cf_frames_t *out)
{
    int i;
    memset(out, 0, sizeof *out);
    out->f = calloc((size_t)set->n + 1, sizeof *out->f);
    if (!out->f)
        return -1;
    for (i = 0; i < set->n; i++) {
        const rd_uva_record_t *r = &set->rec[i];
        cf_frame_t *f = &out->f[out->n];
        if (!r->in_realdata || rd_path(f->image, sizeof f->image, dir, r->file) != 0)
            continue;
        f->line = i + 1;
        f->x_mm = r->x_cm * 10.0;
        f->y_mm = r->y_cm * 10.0;
        f->heading_deg = r->theta_deg;
        f->head_yaw_deg = r->head_yaw_rad * 180.0 / CF_PI;
        f->head_pitch_deg = r->head_pitch_rad * 180.0 / CF_PI;
        out->n++;
    }
    return 0;
}

int cf_calib_load(const char *path, fl_calib_t *c, char *err, int err_len)
{
    char text[FL_CALIB_TEXT_MAX + 1];
    size_t n;
    int32_t line = 0;
    const char *why = "";
    memset(c, 0, sizeof *c);
    if (tf_read(path, text, sizeof text, &n, err, err_len) != 0)
        return -1;
    if (fl_calib_parse(text, n, c, &line, &why) == FL_OK)
        return 0;
    tf_parse_err(err, err_len, path, line, why);
    return -1;
}

int cf_calib_save(const char *path, const fl_calib_t *c, const char *comment, char *err,
                  int err_len)
{
    char text[FL_CALIB_TEXT_MAX];
    size_t n = fl_calib_format(c, text, sizeof text);
    FILE *fp;
    if (n == 0) {
        tf_err(err, err_len, "%s: calibration out of range, not written", path);
        return -1;
    }
    fp = fopen(path, "w");
    if (!fp) {
        tf_err(err, err_len, "%s: cannot write", path);
        return -1;
    }
    if (comment)
        fprintf(fp, "# %s\n", comment);
    fwrite(text, 1, n, fp);
    if (fclose(fp) != 0) {
        tf_err(err, err_len, "%s: write error", path);
        return -1;
    }
    return 0;
}
