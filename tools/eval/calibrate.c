/*
 * tools/eval/calibrate.c - camera and field-dimension fit to the UvA 2013 hand
 * labels (see calibrate.h for the model).
 *
 * Algorithm: (1) optional grid search over pitch offset (-15..+30 deg,
 * 0.5 deg) and neck height (360..600 mm, 20 mm) minimising the truncated
 * cost sum min(d, gate)^2 with nearest-landmark association; (2) up to 12
 * rounds of: associate every label with the nearest projected landmark of
 * its kind (within the gate), then Levenberg-Marquardt on the associated,
 * non-outlier labels with Huber IRLS weights (central-difference Jacobian);
 * (3) flag labels whose residual exceeds outlier_px and refit without them
 * until the flags stop changing.  Parameter uncertainties: the diagonal of
 * (J^T W J)^-1 scaled by the weighted residual variance.
 * Invariant: only parameters in fit_mask change; everything else in
 * cal_params_t is used as given.
 * Memory: one observation per label (malloc'd), a dense normal matrix of at
 * most CAL_NP^2 doubles on the stack.  Cost: O(labels x CAL_NP^2) per
 * iteration plus one CAL_NP^3 solve.
 */
#include "eval/calibrate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CAL_PI 3.14159265358979323846

static const char *cal_names[CAL_NP] = {
    "neck_mm", "pitch_offset_deg", "focal_px", "cx_px", "cy_px", "yaw_offset_deg",
    "roll_deg", "k1", "half_length_mm", "half_width_mm", "penalty_area_depth_mm",
    "penalty_area_half_width_mm", "penalty_mark_x_mm", "circle_radius_mm", "post_y_mm",
    "post_height_mm"};

const char *cal_param_name(int i) { return (i >= 0 && i < CAL_NP) ? cal_names[i] : "?"; }

double cal_param_display(int i, double v)
{
    if (i == CAL_PITCH || i == CAL_YAW || i == CAL_ROLL)
        return v * (180.0 / CAL_PI);
    return v;
}

void cal_params_init(cal_params_t *p, const fl_camera_model_t *m, const fl_field_t *f)
{
    memset(p, 0, sizeof *p);
    if (m) {
        p->p[CAL_NECK] = m->default_neck_height_mm;
        p->p[CAL_PITCH] = m->default_pitch_offset * (2.0 * CAL_PI / 65536.0);
        p->p[CAL_FOCAL] = m->focal_q4 / 16.0;
        p->p[CAL_CX] = m->cx_q4 / 16.0;
        p->p[CAL_CY] = m->cy_q4 / 16.0;
        p->mount_x_mm = m->mount_x_mm;
        p->mount_z_mm = m->mount_z_mm;
        p->mount_tilt_rad = m->mount_tilt * (2.0 * CAL_PI / 65536.0);
    }
    if (f) {
        p->p[CAL_HALF_L] = f->length_mm / 2.0;
        p->p[CAL_HALF_W] = f->width_mm / 2.0;
        p->p[CAL_PA_DEPTH] = f->penalty_area_depth_mm;
        p->p[CAL_PA_HALFW] = f->penalty_area_width_mm / 2.0;
        p->p[CAL_PM_X] = f->penalty_mark_x_mm;
        p->p[CAL_CIRCLE_R] = f->circle_radius_mm;
        p->p[CAL_POST_Y] = f->goal_width_mm / 2.0;
        p->post_radius_mm = f->post_diameter_mm / 2.0;
        p->p[CAL_POST_H] = f->post_height_mm;
    }
}

/* ---- landmarks as sums of dimensions ---------------------------------- */

/* Express |c| through the dimensions listed in cand (first exact match);
 * fills a[] with sign * coefficients; returns 0 or -1 (no match). */
static int cal_express(const fl_field_t *f, int32_t c, int is_x, fl_landmark_kind_t kind,
                       signed char *a)
{
    int32_t ac = c < 0 ? -c : c;
    signed char s = (signed char)(c < 0 ? -1 : 1);
    memset(a, 0, CAL_NP);
    if (ac == 0)
        return 0;
    if (is_x) {
        if (2 * ac == f->length_mm) {
            a[CAL_HALF_L] = s;
            return 0;
        }
        if (f->penalty_area_depth_mm > 0 && 2 * (ac + f->penalty_area_depth_mm) == f->length_mm) {
            a[CAL_HALF_L] = s;
            a[CAL_PA_DEPTH] = (signed char)-s;
            return 0;
        }
        if ((kind == FL_LM_PENALTY_MARK) && ac == f->penalty_mark_x_mm) {
            a[CAL_PM_X] = s;
            return 0;
        }
        return -1;
    }
    if (2 * ac == f->width_mm) {
        a[CAL_HALF_W] = s;
        return 0;
    }
    if (kind == FL_LM_POST && 2 * ac == f->goal_width_mm) {
        a[CAL_POST_Y] = s;
        return 0;
    }
    if (kind == FL_LM_X && ac == f->circle_radius_mm) {
        a[CAL_CIRCLE_R] = s;
        return 0;
    }
    if (f->penalty_area_width_mm > 0 && 2 * ac == f->penalty_area_width_mm) {
        a[CAL_PA_HALFW] = s;
        return 0;
    }
    return -1;
}

int cal_problem_init(cal_problem_t *pb, const rd_uva_set_t *set, const fl_field_t *f)
{
    uint16_t i;
    int r, k, n = 0;

    memset(pb, 0, sizeof *pb);
    if (!set || !f)
        return -1;
    pb->set = set;
    pb->field = f;
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *l = &f->landmarks[i];
        cal_landmark_t *c;
        char type;
        switch (l->kind) {
        case FL_LM_L: type = 'L'; break;
        case FL_LM_T: type = 'T'; break;
        case FL_LM_X: case FL_LM_PENALTY_MARK: case FL_LM_CENTRE_MARK: type = 'X'; break;
        case FL_LM_POST: type = 'G'; break;
        default: continue;
        }
        if (pb->n_lm >= (int)(sizeof pb->lm / sizeof pb->lm[0]))
            return -1;
        c = &pb->lm[pb->n_lm];
        c->type = type;
        c->kind = l->kind;
        if (cal_express(f, l->x_mm, 1, l->kind, c->ax) != 0 ||
            cal_express(f, l->y_mm, 0, l->kind, c->ay) != 0)
            return -1; /* e.g. posts behind the goal line: not this model */
        pb->n_lm++;
    }
    for (r = 0; r < set->n; r++)
        n += set->rec[r].n_features;
    pb->obs = calloc((size_t)(n ? n : 1), sizeof *pb->obs);
    if (!pb->obs)
        return -1;
    for (r = 0; r < set->n; r++)
        for (k = 0; k < set->rec[r].n_features; k++) {
            cal_obs_t *o = &pb->obs[pb->n_obs++];
            o->rec = r;
            o->feat = k;
            o->type = set->rec[r].feat[k].type;
            o->u = set->rec[r].feat[k].u;
            o->v = set->rec[r].feat[k].v;
            o->lm = -1;
        }
    return 0;
}

void cal_problem_free(cal_problem_t *pb)
{
    if (!pb)
        return;
    free(pb->obs);
    pb->obs = NULL;
    pb->n_obs = 0;
}

/* ---- projection --------------------------------------------------------- */

/* Camera centre (robot frame, mm) and axes for record r. */
static void cal_camera(const cal_params_t *p, const rd_uva_record_t *r, double pos[3],
                       double ax[3][3])
{
    double th = r->head_pitch_rad + p->p[CAL_PITCH];
    double psi = r->head_yaw_rad + p->p[CAL_YAW];
    double al = p->mount_tilt_rad + th, ro = p->p[CAL_ROLL];
    double cps = cos(psi), sps = sin(psi), ca = cos(al), sa = sin(al);
    double cr = cos(ro), sr = sin(ro);
    double xh = p->mount_x_mm * cos(th) + p->mount_z_mm * sin(th);
    double zh = -p->mount_x_mm * sin(th) + p->mount_z_mm * cos(th);
    /* Ry(al) columns: x' = (ca, 0, -sa), y' = (0, 1, 0), z' = (sa, 0, ca);
     * then Rx(roll): y'' = cr y' + sr z', z'' = -sr y' + cr z'; then Rz. */
    double loc[3][3];
    int i;
    pos[0] = xh * cps;
    pos[1] = xh * sps;
    pos[2] = p->p[CAL_NECK] + zh;
    loc[0][0] = ca; loc[0][1] = 0; loc[0][2] = -sa;
    loc[1][0] = sr * sa; loc[1][1] = cr; loc[1][2] = sr * ca;
    loc[2][0] = cr * sa; loc[2][1] = -sr; loc[2][2] = cr * ca;
    for (i = 0; i < 3; i++) {
        ax[i][0] = cps * loc[i][0] - sps * loc[i][1];
        ax[i][1] = sps * loc[i][0] + cps * loc[i][1];
        ax[i][2] = loc[i][2];
    }
}

static int cal_to_pixel(const cal_params_t *p, const double pos[3], double ax[3][3],
                        double x, double y, double z, double *u, double *v)
{
    double w[3] = {x - pos[0], y - pos[1], z - pos[2]};
    double c[3];
    int i;
    double du, dv, f = p->p[CAL_FOCAL], k;
    for (i = 0; i < 3; i++)
        c[i] = ax[i][0] * w[0] + ax[i][1] * w[1] + ax[i][2] * w[2];
    if (c[0] <= 1.0)
        return -1;
    du = -f * c[1] / c[0];
    dv = -f * c[2] / c[0];
    k = 1.0 + p->p[CAL_K1] * (du * du + dv * dv) / (f * f);
    *u = p->p[CAL_CX] + du * k;
    *v = p->p[CAL_CY] + dv * k;
    return 0;
}

int cal_project_robot(const cal_params_t *p, const rd_uva_record_t *r, double x, double y,
                      double z, double *u, double *v)
{
    double pos[3], ax[3][3];
    cal_camera(p, r, pos, ax);
    return cal_to_pixel(p, pos, ax, x, y, z, u, v);
}

int cal_project(const cal_problem_t *pb, const cal_params_t *p, int rec, int lm, int top,
                double *u, double *v)
{
    const cal_landmark_t *l;
    const rd_uva_record_t *r;
    double fx = 0, fy = 0, rx, ry, z = 0, pos[3], ax[3][3], th, c, s, dx, dy;
    const double *pc;
    int k;
    if (lm < 0 || lm >= pb->n_lm || rec < 0 || rec >= pb->set->n || rec >= CAL_MAX_REC)
        return -1;
    l = &pb->lm[lm];
    r = &pb->set->rec[rec];
    pc = p->pose[rec];
    for (k = 0; k < CAL_NP; k++) {
        fx += l->ax[k] * p->p[k];
        fy += l->ay[k] * p->p[k];
    }
    /* field -> robot with the corrected pose */
    th = r->theta_deg * (CAL_PI / 180.0) + pc[CAL_POSE_TH];
    c = cos(th);
    s = sin(th);
    dx = fx - (r->x_cm * 10.0 + pc[CAL_POSE_X]);
    dy = fy - (r->y_cm * 10.0 + pc[CAL_POSE_Y]);
    rx = c * dx + s * dy;
    ry = -s * dx + c * dy;
    cal_camera(p, r, pos, ax);
    if (l->type == 'G') {
        /* the post's surface point nearest the camera */
        double ex = pos[0] - rx, ey = pos[1] - ry, d = sqrt(ex * ex + ey * ey);
        if (d > p->post_radius_mm) {
            rx += ex / d * p->post_radius_mm;
            ry += ey / d * p->post_radius_mm;
        }
        if (top)
            z = p->p[CAL_POST_H];
    }
    return cal_to_pixel(p, pos, ax, rx, ry, z, u, v);
}

/* ---- association ---------------------------------------------------------- */

static int cal_type_match(char label, char lm_type)
{
    if (label == 'U')
        return lm_type == 'G';
    return label == lm_type;
}

/* Nearest landmark of the label's kind; returns lm or -1, distance in *d. */
static int cal_nearest(const cal_problem_t *pb, const cal_params_t *p, const cal_obs_t *o,
                       double *d)
{
    int best = -1, i;
    double bd = 1e300;
    for (i = 0; i < pb->n_lm; i++) {
        double u, v, e;
        if (!cal_type_match(o->type, pb->lm[i].type))
            continue;
        if (cal_project(pb, p, o->rec, i, o->type == 'U', &u, &v) != 0)
            continue;
        e = hypot(u - o->u, v - o->v);
        if (e < bd) {
            bd = e;
            best = i;
        }
    }
    *d = bd;
    return best;
}

static int cal_residual(const cal_problem_t *pb, const cal_params_t *p, const cal_obs_t *o,
                        double *du, double *dv)
{
    double u, v;
    if (cal_project(pb, p, o->rec, o->lm, o->type == 'U', &u, &v) != 0)
        return -1;
    *du = u - o->u;
    *dv = v - o->v;
    return 0;
}

int cal_evaluate(cal_problem_t *pb, const cal_params_t *p, double gate_px, double outlier_px)
{
    int i, n = 0;
    for (i = 0; i < pb->n_obs; i++) {
        cal_obs_t *o = &pb->obs[i];
        double d;
        o->lm = cal_nearest(pb, p, o, &d);
        if (o->lm >= 0 && d > gate_px)
            o->lm = -1;
        o->outlier = 0;
        o->du = o->dv = 0;
        if (o->lm >= 0 && cal_residual(pb, p, o, &o->du, &o->dv) == 0) {
            o->outlier = hypot(o->du, o->dv) > outlier_px;
            n++;
        } else {
            o->lm = -1;
        }
    }
    return n;
}

/* ---- fit ------------------------------------------------------------------------ */

void cal_options_default(cal_options_t *o)
{
    o->fit_mask = CAL_FIT_BASE;
    o->gate_px = 40.0;
    o->huber_px = 3.0;
    o->outlier_px = 8.0;
    o->exclude_rec = -1;
    o->grid_init = 1;
    o->pose_mask = 0;
    o->sigma_heading_deg = 5.0;
    o->sigma_xy_mm = 100.0;
    o->label_sigma_px = 2.0;
}

/* Parameter ids: 0..CAL_NP-1 global, CAL_NP + 3 rec + comp per image. */
static double *cal_par(cal_params_t *p, int id)
{
    return id < CAL_NP ? &p->p[id] : &p->pose[(id - CAL_NP) / 3][(id - CAL_NP) % 3];
}

/* Solve A x = b (n x n, symmetric positive definite, row-major) by
 * Cholesky; the diagonal of A^-1 into inv_diag when not NULL.  0, or -1
 * when singular or out of memory. */
static int cal_cholesky_solve(int n, const double *A, const double *b, double *x,
                              double *inv_diag)
{
    double *L = calloc((size_t)n * (size_t)n + 2 * (size_t)n + 1, sizeof(double));
    double *y, *z;
    int i, j, k, col;
    if (!L)
        return -1;
    y = L + (size_t)n * (size_t)n;
    z = y + n;
    for (i = 0; i < n; i++)
        for (j = 0; j <= i; j++) {
            double s = A[i * n + j];
            for (k = 0; k < j; k++)
                s -= L[i * n + k] * L[j * n + k];
            if (i == j) {
                if (!(s > 1e-300)) {
                    free(L);
                    return -1;
                }
                L[i * n + i] = sqrt(s);
            } else {
                L[i * n + j] = s / L[j * n + j];
            }
        }
    for (col = (b && x) ? -1 : 0; col < (inv_diag ? n : 0); col++) {
        /* col -1: solve for b; col >= 0: unit vector, keep element col */
        for (i = 0; i < n; i++) {
            double s = col < 0 ? b[i] : (double)(i == col);
            for (k = 0; k < i; k++)
                s -= L[i * n + k] * y[k];
            y[i] = s / L[i * n + i];
        }
        for (i = n - 1; i >= 0; i--) {
            double s = y[i];
            for (k = i + 1; k < n; k++)
                s -= L[k * n + i] * z[k];
            z[i] = s / L[i * n + i];
        }
        if (col < 0)
            memcpy(x, z, sizeof(double) * (size_t)n);
        else
            inv_diag[col] = z[col];
    }
    free(L);
    return 0;
}

static int cal_active(const cal_options_t *o, const cal_obs_t *ob)
{
    return ob->lm >= 0 && !ob->outlier && ob->rec != o->exclude_rec;
}

/* Prior of a pose parameter: pseudo-residual = value * scale. */
static double cal_prior_scale(const cal_options_t *o, int comp)
{
    if (comp == CAL_POSE_TH)
        return o->label_sigma_px / (o->sigma_heading_deg * (CAL_PI / 180.0));
    return o->label_sigma_px / o->sigma_xy_mm;
}

/* The parameter list of a fit. */
typedef struct {
    int id[CAL_NP + 3 * CAL_MAX_REC];
    int pos_of[CAL_NP + 3 * CAL_MAX_REC]; /* id -> position, -1 if not fitted */
    int n;
} cal_plist_t;

static void cal_plist(const cal_problem_t *pb, const cal_options_t *o, cal_plist_t *pl)
{
    int k, r, c, i;
    int has[CAL_MAX_REC];
    memset(has, 0, sizeof has);
    for (i = 0; i < pb->n_obs; i++)
        if (pb->obs[i].rec < CAL_MAX_REC && pb->obs[i].rec != o->exclude_rec)
            has[pb->obs[i].rec] = 1;
    pl->n = 0;
    for (k = 0; k < CAL_NP + 3 * CAL_MAX_REC; k++)
        pl->pos_of[k] = -1;
    for (k = 0; k < CAL_NP; k++)
        if (o->fit_mask & CAL_BIT(k)) {
            pl->pos_of[k] = pl->n;
            pl->id[pl->n++] = k;
        }
    for (r = 0; r < pb->set->n && r < CAL_MAX_REC; r++) {
        if (!has[r])
            continue;
        for (c = 0; c < 3; c++) {
            int want = c == CAL_POSE_TH ? (o->pose_mask & CAL_FIT_POSE_HEADING) != 0
                                        : (o->pose_mask & CAL_FIT_POSE_XY) != 0;
            if (want) {
                int id = CAL_NP + 3 * r + c;
                pl->pos_of[id] = pl->n;
                pl->id[pl->n++] = id;
            }
        }
    }
}

/* Cost with fixed association: Huber loss of the labels plus the priors. */
static double cal_cost(const cal_problem_t *pb, const cal_options_t *o, const cal_plist_t *pl,
                       const cal_params_t *p)
{
    double s = 0;
    int i;
    for (i = 0; i < pb->n_obs; i++) {
        const cal_obs_t *ob = &pb->obs[i];
        double du, dv, e, h = o->huber_px;
        if (!cal_active(o, ob))
            continue;
        if (cal_residual(pb, p, ob, &du, &dv) != 0)
            return 1e300;
        e = hypot(du, dv);
        s += e <= h ? e * e : 2 * h * e - h * h; /* Huber loss */
    }
    for (i = 0; i < pl->n; i++)
        if (pl->id[i] >= CAL_NP) {
            int comp = (pl->id[i] - CAL_NP) % 3;
            double v = *cal_par((cal_params_t *)p, pl->id[i]) * cal_prior_scale(o, comp);
            s += v * v;
        }
    return s;
}

static double cal_step(int id)
{
    if (id >= CAL_NP)
        return ((id - CAL_NP) % 3 == CAL_POSE_TH) ? 1e-6 : 1e-3;
    switch (id) {
    case CAL_PITCH: case CAL_YAW: case CAL_ROLL: return 1e-6;
    case CAL_K1: return 1e-5;
    default: return 1e-3; /* px, mm */
    }
}

/* Normal equations at p: A (n x n), g (n), weighted SSR; with Huber
 * weights.  Returns the number of labels used, -1 on failure. */
static int cal_normal(const cal_problem_t *pb, const cal_options_t *o, const cal_plist_t *pl,
                      const cal_params_t *p, double *A, double *g, double *ssr, double *wssr)
{
    int n = pl->n, i, j, k, used = 0;
    int rel[CAL_NP + 3];
    double J[2][CAL_NP + 3];
    memset(A, 0, sizeof(double) * (size_t)n * (size_t)n);
    memset(g, 0, sizeof(double) * (size_t)n);
    *ssr = *wssr = 0;
    for (i = 0; i < pb->n_obs; i++) {
        const cal_obs_t *ob = &pb->obs[i];
        double du, dv, e, w;
        int nr = 0;
        if (!cal_active(o, ob))
            continue;
        if (cal_residual(pb, p, ob, &du, &dv) != 0)
            return -1;
        e = hypot(du, dv);
        w = e <= o->huber_px ? 1.0 : o->huber_px / e;
        /* parameters this label depends on: the globals and its image's pose */
        for (k = 0; k < CAL_NP; k++)
            if (pl->pos_of[k] >= 0)
                rel[nr++] = k;
        for (k = 0; k < 3; k++)
            if (ob->rec < CAL_MAX_REC && pl->pos_of[CAL_NP + 3 * ob->rec + k] >= 0)
                rel[nr++] = CAL_NP + 3 * ob->rec + k;
        for (j = 0; j < nr; j++) {
            cal_params_t q = *p;
            double h = cal_step(rel[j]), u1, v1, u2, v2, *x = cal_par(&q, rel[j]), x0 = *x;
            *x = x0 + h;
            if (cal_residual(pb, &q, ob, &u1, &v1) != 0)
                return -1;
            *x = x0 - h;
            if (cal_residual(pb, &q, ob, &u2, &v2) != 0)
                return -1;
            J[0][j] = (u1 - u2) / (2 * h);
            J[1][j] = (v1 - v2) / (2 * h);
        }
        for (j = 0; j < nr; j++) {
            int a = pl->pos_of[rel[j]];
            for (k = 0; k < nr; k++)
                A[a * n + pl->pos_of[rel[k]]] += w * (J[0][j] * J[0][k] + J[1][j] * J[1][k]);
            g[a] += w * (J[0][j] * du + J[1][j] * dv);
        }
        *ssr += e * e;
        *wssr += w * e * e;
        used++;
    }
    for (j = 0; j < n; j++)
        if (pl->id[j] >= CAL_NP) {
            double sc = cal_prior_scale(o, (pl->id[j] - CAL_NP) % 3);
            A[j * n + j] += sc * sc;
            g[j] += sc * sc * *cal_par((cal_params_t *)p, pl->id[j]);
        }
    return used;
}

/* One LM run with fixed association.  Returns iterations or -1. */
static int cal_lm(cal_problem_t *pb, const cal_options_t *o, cal_params_t *p,
                  double sigma[CAL_NP], double *rms, int *n_used)
{
    cal_plist_t *pl = malloc(sizeof *pl);
    double *A, *B, *g, *mg, *dx, *inv, ssr, wssr, lambda = 1e-3, cost;
    int n, it, j, k, used, n_glob = 0, ret = -1;

    if (!pl)
        return -1;
    cal_plist(pb, o, pl);
    n = pl->n;
    A = malloc(sizeof(double) * ((size_t)n * (size_t)n * 2 + 4 * (size_t)n + 4));
    if (!A) {
        free(pl);
        return -1;
    }
    B = A + (size_t)n * (size_t)n;
    g = B + (size_t)n * (size_t)n;
    mg = g + n;
    dx = mg + n;
    inv = dx + n;
    for (j = 0; j < n; j++)
        n_glob += pl->id[j] < CAL_NP;
    cost = cal_cost(pb, o, pl, p);
    for (it = 0; it < 100; it++) {
        int improved = 0;
        used = cal_normal(pb, o, pl, p, A, g, &ssr, &wssr);
        if (used < 0 || 2 * used < n_glob + 1)
            goto out;
        while (lambda < 1e12) {
            cal_params_t q = *p;
            double nc;
            for (j = 0; j < n; j++) {
                for (k = 0; k < n; k++)
                    B[j * n + k] = A[j * n + k];
                B[j * n + j] += lambda * (A[j * n + j] > 0 ? A[j * n + j] : 1.0);
                mg[j] = -g[j];
            }
            if (cal_cholesky_solve(n, B, mg, dx, NULL) != 0) {
                lambda *= 10;
                continue;
            }
            for (j = 0; j < n; j++)
                *cal_par(&q, pl->id[j]) += dx[j];
            nc = cal_cost(pb, o, pl, &q);
            if (nc < cost) {
                double rel = (cost - nc) / (cost + 1e-12);
                *p = q;
                cost = nc;
                if (lambda > 1e-9)
                    lambda *= 0.3;
                improved = rel < 1e-12 ? 2 : 1;
                break;
            }
            lambda *= 10;
        }
        if (improved != 1)
            break;
    }
    /* uncertainty and RMS at the solution */
    used = cal_normal(pb, o, pl, p, A, g, &ssr, &wssr);
    if (used < 0)
        goto out;
    for (k = 0; k < CAL_NP; k++)
        sigma[k] = 0;
    if (cal_cholesky_solve(n, A, NULL, NULL, inv) == 0 && 2 * used > n_glob) {
        /* residual variance per coordinate; the pose parameters are
         * balanced by their priors, so only the globals use up degrees of
         * freedom here (an approximation) */
        double s2 = wssr / (2.0 * used - n_glob);
        for (j = 0; j < n; j++)
            if (pl->id[j] < CAL_NP)
                sigma[pl->id[j]] = sqrt(inv[j] * s2);
    }
    *rms = used ? sqrt(ssr / used) : 0;
    *n_used = used;
    ret = it;
out:
    free(A);
    free(pl);
    return ret;
}

/* Truncated cost with nearest association, for the grid search. */
static double cal_grid_cost(const cal_problem_t *pb, const cal_options_t *o,
                            const cal_params_t *p)
{
    double s = 0, g2 = o->gate_px * o->gate_px;
    int i;
    for (i = 0; i < pb->n_obs; i++) {
        const cal_obs_t *ob = &pb->obs[i];
        double d;
        if (ob->rec == o->exclude_rec)
            continue;
        if (cal_nearest(pb, p, ob, &d) < 0 || d * d > g2)
            s += g2;
        else
            s += d * d;
    }
    return s;
}

int cal_fit(cal_problem_t *pb, const cal_options_t *o, cal_params_t *p, cal_result_t *res)
{
    int round, i, total_it = 0, changed, n_used = 0;
    double rms = 0, sigma[CAL_NP];
    int *prev = malloc(sizeof(int) * 2 * (size_t)(pb->n_obs + 1));

    memset(res, 0, sizeof *res);
    if (!prev || pb->set->n > CAL_MAX_REC) {
        free(prev);
        return -1;
    }
    if (o->grid_init) {
        cal_params_t best = *p, q = *p;
        double bc = 1e300, pitch, neck;
        for (pitch = -15; pitch <= 30.0001; pitch += 0.5)
            for (neck = 360; neck <= 600; neck += 20) {
                double c;
                q.p[CAL_PITCH] = pitch * CAL_PI / 180.0;
                q.p[CAL_NECK] = neck;
                c = cal_grid_cost(pb, o, &q);
                if (c < bc) {
                    bc = c;
                    best = q;
                }
            }
        if (o->fit_mask & CAL_BIT(CAL_PITCH))
            p->p[CAL_PITCH] = best.p[CAL_PITCH];
        if (o->fit_mask & CAL_BIT(CAL_NECK))
            p->p[CAL_NECK] = best.p[CAL_NECK];
    }
    for (i = 0; i < pb->n_obs; i++)
        pb->obs[i].outlier = 0;
    /* association rounds: associate, fit the inliers, flag outliers */
    for (round = 0; round < 20; round++) {
        int it;
        for (i = 0; i < pb->n_obs; i++) {
            cal_obs_t *ob = &pb->obs[i];
            double d;
            prev[2 * i] = ob->lm;
            prev[2 * i + 1] = ob->outlier;
            ob->lm = cal_nearest(pb, p, ob, &d);
            if (ob->lm >= 0 && d > o->gate_px)
                ob->lm = -1;
        }
        it = cal_lm(pb, o, p, sigma, &rms, &n_used);
        if (it < 0) {
            free(prev);
            return -1;
        }
        total_it += it;
        changed = 0;
        for (i = 0; i < pb->n_obs; i++) {
            cal_obs_t *ob = &pb->obs[i];
            ob->du = ob->dv = 0;
            if (ob->lm >= 0 && cal_residual(pb, p, ob, &ob->du, &ob->dv) == 0)
                ob->outlier = hypot(ob->du, ob->dv) > o->outlier_px;
            else
                ob->lm = -1;
            if (prev[2 * i] != ob->lm || prev[2 * i + 1] != ob->outlier)
                changed = 1;
        }
        if (!changed && round > 0)
            break;
    }
    free(prev);
    for (i = 0; i < CAL_NP; i++)
        res->sigma[i] = sigma[i];
    res->rms_px = rms;
    res->n_used = n_used;
    res->iterations = total_it;
    for (i = 0; i < pb->n_obs; i++) {
        const cal_obs_t *ob = &pb->obs[i];
        if (ob->rec == o->exclude_rec)
            continue;
        if (ob->lm < 0)
            res->n_unmatched++;
        else if (ob->outlier)
            res->n_outliers++;
    }
    return 0;
}

/* ---- statistics ------------------------------------------------------------------ */

static int cal_cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int cal_residual_stats(const cal_problem_t *pb, const char *types, int inliers_only, int rec,
                       double *median, double *max)
{
    double *e = malloc(sizeof(double) * (size_t)(pb->n_obs + 1));
    int i, n = 0;
    if (median)
        *median = 0;
    if (max)
        *max = 0;
    if (!e)
        return 0;
    for (i = 0; i < pb->n_obs; i++) {
        const cal_obs_t *o = &pb->obs[i];
        if (o->lm < 0 || (inliers_only && o->outlier) || !strchr(types, o->type))
            continue;
        if (rec >= 0 && o->rec != rec)
            continue;
        e[n++] = hypot(o->du, o->dv);
    }
    if (n) {
        qsort(e, (size_t)n, sizeof *e, cal_cmp_d);
        if (median)
            *median = n % 2 ? e[n / 2] : 0.5 * (e[n / 2 - 1] + e[n / 2]);
        if (max)
            *max = e[n - 1];
    }
    free(e);
    return n;
}
