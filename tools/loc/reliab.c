/*
 * tools/loc/reliab.c - reliability diagram and calibration contract
 * (reliab.h).
 */
#include "loc/reliab.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    rb_set_t *set;
    int mode, field;
    long seed;
    int fail;
} rb_ctx_t;

static void rb_hook(void *user, const lr_walk_step_t *ws)
{
    rb_ctx_t *c = user;
    rb_set_t *s = c->set;
    rb_rec_t *r;
    double pe, he, mpe, mhe;
    if (s->n == s->cap) {
        long cap = s->cap ? 2 * s->cap : 4096;
        rb_rec_t *nr = realloc(s->rec, (size_t)cap * sizeof *nr);
        if (nr == NULL) {
            c->fail = 1;
            return;
        }
        s->rec = nr;
        s->cap = cap;
    }
    r = &s->rec[s->n++];
    memset(r, 0, sizeof *r);
    r->mode = (uint8_t)c->mode;
    r->field = (uint8_t)c->field;
    r->seed = (uint16_t)c->seed;
    r->est = *ws->est;
    lr_pose_error(ws->est->x_mm, ws->est->y_mm, lr_deg(ws->est->heading), ws->st->true_x_mm,
                  ws->st->true_y_mm, ws->st->true_heading_rad * (180.0 / 3.14159265358979323846),
                  &pe, &he, &mpe, &mhe);
    r->pos_err_mm = pe;
    r->head_err_deg = he;
    r->good = pe < FL_LOC_GOOD_MM && he < FL_LOC_GOOD_DEG;
}

int rb_walk(rb_set_t *set, const fl_localizer_t *loc, const char *field, int field_index,
            long seed, int frames, const char *obs_cache, long max_steps, char *err,
            int err_len)
{
    static sim_scenario_t sc;
    lr_walk_opts_t o;
    lr_walk_result_t res;
    rb_ctx_t c;
    void *params;
    int rc;
    if (sim_scenario_builtin(&sc, field) != 0) {
        snprintf(err, (size_t)err_len, "no built-in walk for field '%s'", field);
        return -1;
    }
    sc.seed = (uint64_t)seed;
    params = lr_params_new(loc);
    if (params == NULL) {
        snprintf(err, (size_t)err_len, "out of memory");
        return -1;
    }
    if (frames)
        lr_params_frames(loc, params);
    memset(&o, 0, sizeof o);
    memset(&c, 0, sizeof c);
    c.set = set;
    c.mode = frames;
    c.field = field_index;
    c.seed = seed;
    o.frames = frames;
    o.every = 3;
    o.max_steps = max_steps;
    o.loc = loc;
    o.params = params;
    o.obs_cache = obs_cache;
    o.hook = rb_hook;
    o.user = &c;
    rc = lr_walk_run(&sc, &o, &res, err, err_len);
    free(params);
    if (rc == 0 && c.fail) {
        snprintf(err, (size_t)err_len, "out of memory");
        rc = -1;
    }
    return rc;
}

void rb_free(rb_set_t *set)
{
    free(set->rec);
    memset(set, 0, sizeof *set);
}

/* Records of mode, counted per reported value (65536 values). */
static long rb_hist(const rb_set_t *set, int mode, long *n, long *good)
{
    long i, tot = 0;
    memset(n, 0, 65536 * sizeof *n);
    memset(good, 0, 65536 * sizeof *good);
    for (i = 0; i < set->n; i++) {
        const rb_rec_t *r = &set->rec[i];
        if (mode >= 0 && r->mode != mode)
            continue;
        n[r->est.reliability_q16]++;
        good[r->est.reliability_q16] += r->good;
        tot++;
    }
    return tot;
}

double rb_contract(const rb_set_t *set, int mode, double *worst_r, long *count)
{
    long *n = malloc(65536 * sizeof *n), *good = malloc(65536 * sizeof *good);
    long cn = 0, cg = 0;
    double worst = 1.0;
    int v;
    *worst_r = 0;
    *count = 0;
    if (n == NULL || good == NULL) {
        free(n);
        free(good);
        return -1.0;
    }
    *count = rb_hist(set, mode, n, good);
    /* share(rel >= r) for r between two reported values equals the one at
     * the upper value, which is >= r: checking at every reported value
     * checks every r */
    for (v = 65535; v > 0; v--) {
        double m;
        cn += n[v];
        cg += good[v];
        if (n[v] == 0)
            continue;
        m = (double)cg / (double)cn - v / 65536.0;
        if (m < worst) {
            worst = m;
            *worst_r = v / 65536.0;
        }
    }
    free(n);
    free(good);
    return worst;
}

int rb_print(FILE *f, const rb_set_t *set, int mode, const char *title)
{
    long bn[10] = {0}, bg[10] = {0}, tot = 0, i, count;
    double worst, wr;
    int b, k;
    for (i = 0; i < set->n; i++) {
        const rb_rec_t *r = &set->rec[i];
        if (mode >= 0 && r->mode != mode)
            continue;
        b = r->est.reliability_q16 * 10 / 65536;
        bn[b]++;
        bg[b] += r->good;
        tot++;
    }
    fprintf(f, "reliability diagram: %s (%ld records; good = within %d mm and %d deg of the "
               "truth)\n", title, tot, FL_LOC_GOOD_MM, FL_LOC_GOOD_DEG);
    fprintf(f, "  reported   records  good share |   r  records>=r  share>=r  check\n");
    for (b = 0; b < 10; b++) {
        long cn = 0, cg = 0;
        double r = b / 10.0;
        char sh[16], csh[16];
        for (k = b; k < 10; k++) {
            cn += bn[k];
            cg += bg[k];
        }
        snprintf(sh, sizeof sh, bn[b] ? "%.3f" : "-", bn[b] ? (double)bg[b] / (double)bn[b] : 0.0);
        snprintf(csh, sizeof csh, cn ? "%.3f" : "-", cn ? (double)cg / (double)cn : 0.0);
        fprintf(f, "  %.1f-%.1f  %8ld  %10s | %.1f  %10ld  %8s  %s\n", r, (b + 1) / 10.0, bn[b],
                sh, r, cn, csh,
                cn == 0 ? "ok (none)" : (double)cg / (double)cn >= r ? "ok" : "FAIL");
    }
    worst = rb_contract(set, mode, &wr, &count);
    fprintf(f, "  worst over every reported r: share(reliability >= %.4f) - %.4f = %+.4f: %s\n",
            wr, wr, worst, worst >= 0 ? "contract met" : "CONTRACT FAILS");
    return worst >= 0 ? 0 : 1;
}

void rb_dump(FILE *f, const rb_set_t *set, const char *const *field_names)
{
    long i;
    fprintf(f, "mode\tfield\tseed\trel\tscore\tpeak\tcells\tstate\tsdx\tsdy\tcov\tsdh\tmirror\t"
               "since\tswitched\tpos_err\thead_err\tgood\n");
    for (i = 0; i < set->n; i++) {
        const rb_rec_t *r = &set->rec[i];
        const fl_loc_estimate_t *e = &r->est;
        fprintf(f, "%d\t%s\t%u\t%u\t%u\t%u\t%u\t%d\t%u\t%u\t%ld\t%d\t%u\t%u\t%d\t%.0f\t%.1f\t%d\n",
                r->mode, field_names[r->field], r->seed, e->reliability_q16, e->score_q16,
                e->peak_q8, e->mode_cells, (int)e->state, e->sd_x_mm, e->sd_y_mm,
                (long)e->cov_xy_mm2, (int)e->sd_heading, e->mirror_q16, e->since_obs,
                (int)e->switched, r->pos_err_mm, r->head_err_deg, r->good);
    }
}
