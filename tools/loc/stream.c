/*
 * tools/loc/stream.c - localizer input streams (stream.h; format
 * docs/STREAM.md): writer, strict reader, replay.
 *
 * The reader keeps the whole stream in four growing arrays (records,
 * events, calls, observations; about 50 bytes per observation), so a
 * replay can refuse a malformed file before it runs anything.
 */
#include "loc/stream.h"
#include "io/textfile.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- writer ---------------------------------------------------------------- */

static double ls_deg(fl_angle_t a)
{
    return (double)a * (360.0 / 65536.0);
}

void ls_write_header(FILE *f, const sim_scenario_t *sc, int frames, int every, int post_sides,
                     int prior_half)
{
    fprintf(f, "fieldloc-stream %d\n", LS_VERSION);
    fprintf(f, "scenario %s\n", sc->name[0] ? sc->name : "-");
    fprintf(f, "field %s\n", sc->field->name);
    fprintf(f, "camera %s\n", sc->camera->name);
    fprintf(f, "seed %llu\n", (unsigned long long)sc->seed);
    fprintf(f, "mode %s\n", frames ? "frames" : "features");
    fprintf(f, "every %d\n", every);
    fprintf(f, "frame_hz %.9g\n", sc->frame_hz);
    fprintf(f, "period_s %.9g\n", every / sc->frame_hz);
    fprintf(f, "post_sides %d\n", post_sides ? 1 : 0);
    fprintf(f, "prior_half %d\n", prior_half);
    fprintf(f, "penalty_x_mm %ld\n", (long)(int32_t)sc->penalty_x_mm); /* as lr_place */
}

void ls_write_record(FILE *f, long index, uint32_t step, int32_t t_ms, int32_t x_mm,
                     int32_t y_mm, fl_angle_t heading)
{
    fprintf(f, "record %ld %lu %ld %ld %ld %d %.2f\n", index, (unsigned long)step, (long)t_ms,
            (long)x_mm, (long)y_mm, (int)heading, ls_deg(heading));
}

void ls_write_events(FILE *f, unsigned events, uint32_t step, int32_t t_ms, int32_t x_mm,
                     int32_t y_mm, fl_angle_t heading)
{
    if (events & SIM_EV_UNPENALIZED)
        fprintf(f, "unpenalized %lu %ld\n", (unsigned long)step, (long)t_ms);
    if (events & SIM_EV_KIDNAP)
        fprintf(f, "kidnap %lu %ld %ld %ld %d\n", (unsigned long)step, (long)t_ms, (long)x_mm,
                (long)y_mm, (int)heading);
    if (events & SIM_EV_PENALIZED)
        fprintf(f, "penalized %lu %ld %ld %ld %d\n", (unsigned long)step, (long)t_ms,
                (long)x_mm, (long)y_mm, (int)heading);
}

void ls_write_predict(FILE *f, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta)
{
    fprintf(f, "predict %ld %ld %d\n", (long)dx_mm, (long)dy_mm, (int)dtheta);
}

void ls_write_reset_penalty(FILE *f, int32_t x_mm, int32_t pos_unc_mm, fl_angle_t heading_unc)
{
    fprintf(f, "reset_penalty %ld %ld %d\n", (long)x_mm, (long)pos_unc_mm, (int)heading_unc);
}

void ls_write_update(FILE *f, const fl_obs_list_t *obs, const fl_obs_view_t *view)
{
    static const char kc[] = "LTXPCGOBcfnN";
    int i;
    fprintf(f, "update %d %d", (int)obs->n, (int)obs->dropped);
    if (view == NULL)
        fprintf(f, " noview\n");
    else
        fprintf(f, " view %d %d %d %ld %ld\n", view->valid ? 1 : 0, (int)view->bearing_right,
                (int)view->bearing_left, (long)view->near_mm, (long)view->far_mm);
    for (i = 0; i < obs->n && i < FL_OBS_MAX; i++) {
        const fl_obs_t *o = &obs->obs[i];
        fprintf(f, "obs %c %d %d %d %ld %d %d %d %d %ld %ld\n",
                (int)o->kind >= 0 && o->kind < FL_LM_KIND_COUNT ? kc[o->kind] : '?',
                (int)o->color, (int)o->color2, (int)o->side, (long)o->range_mm, (int)o->bearing,
                (int)o->orientation, o->has_orientation ? 1 : 0, (int)o->confidence,
                (long)o->u_q4, (long)o->v_q4);
    }
}

void ls_write_end(FILE *f, long records)
{
    fprintf(f, "end %ld\n", records);
}

/* ---- reader ---------------------------------------------------------------- */

#define LS_LINE_MAX 512
#define LS_TOK_MAX 16

void ls_free(ls_stream_t *s)
{
    free(s->rec);
    free(s->ev);
    free(s->op);
    free(s->obs);
    memset(s, 0, sizeof *s);
}

/* Grow an array to hold one more element. */
static int ls_grow(void **p, long *cap, long n, size_t size)
{
    void *g;
    long c;
    if (n < *cap)
        return 0;
    c = *cap ? *cap * 2 : 256;
    g = realloc(*p, (size_t)c * size);
    if (g == NULL)
        return -1;
    *p = g;
    *cap = c;
    return 0;
}

/* An integer token in [lo, hi]. */
static int ls_int(const char *tok, long lo, long hi, long *v)
{
    char *end;
    long x;
    if (tok == NULL || *tok == '\0')
        return -1;
    errno = 0;
    x = strtol(tok, &end, 10);
    if (*end != '\0' || errno != 0 || x < lo || x > hi)
        return -1;
    *v = x;
    return 0;
}

typedef struct {
    ls_stream_t *s;
    int line, in_body, ended;
    long obs_left;                /* observation lines still due */
    unsigned have;                /* header keys seen, bit per key */
    char why[160];
} ls_parser_t;

static const char *const ls_header_keys[] = {"scenario",   "field",    "camera",
                                             "seed",       "mode",     "every",
                                             "frame_hz",   "period_s", "post_sides",
                                             "prior_half", "penalty_x_mm"};
#define LS_N_HEADER ((int)(sizeof ls_header_keys / sizeof ls_header_keys[0]))
/* required: field camera mode every frame_hz prior_half */
#define LS_REQUIRED ((1u << 1) | (1u << 2) | (1u << 4) | (1u << 5) | (1u << 6) | (1u << 9))

static int ls_bad(ls_parser_t *p, const char *fmt, const char *what)
{
    snprintf(p->why, sizeof p->why, fmt, what);
    return -1;
}

static int ls_header_line(ls_parser_t *p, char **tok, int nt)
{
    ls_stream_t *s = p->s;
    long v;
    double d;
    int k;
    for (k = 0; k < LS_N_HEADER; k++)
        if (!strcmp(tok[0], ls_header_keys[k]))
            break;
    if (k == LS_N_HEADER)
        return ls_bad(p, "unknown keyword '%s'", tok[0]);
    if (p->have & (1u << k))
        return ls_bad(p, "'%s' given twice", tok[0]);
    if (nt != 2)
        return ls_bad(p, "'%s' takes one value", tok[0]);
    p->have |= 1u << k;
    switch (k) {
    case 0:
        snprintf(s->scenario, sizeof s->scenario, "%s", tok[1]);
        return 0;
    case 1:
        if ((s->field = fl_field_find(tok[1])) == NULL)
            return ls_bad(p, "unknown field '%s'", tok[1]);
        return 0;
    case 2:
        if ((s->camera = fl_camera_model_find(tok[1])) == NULL)
            return ls_bad(p, "unknown camera '%s'", tok[1]);
        return 0;
    case 3: {
        char *end;
        unsigned long long x;
        errno = 0;
        x = strtoull(tok[1], &end, 10);
        if (*end != '\0' || errno != 0 || tok[1][0] == '-')
            return ls_bad(p, "bad seed '%s'", tok[1]);
        s->seed = (uint64_t)x;
        return 0;
    }
    case 4:
        if (strcmp(tok[1], "features") && strcmp(tok[1], "frames"))
            return ls_bad(p, "mode '%s' is neither features nor frames", tok[1]);
        s->frames = !strcmp(tok[1], "frames");
        return 0;
    case 5:
        if (ls_int(tok[1], 1, 1000, &v))
            return ls_bad(p, "every '%s' is not an integer in 1..1000", tok[1]);
        s->every = (int)v;
        return 0;
    case 6:
    case 7:
        if (tf_number(tok[1], 1e6, &d) != NULL || !(d > 0))
            return ls_bad(p, "'%s' is not a positive number", tok[1]);
        if (k == 6)
            s->frame_hz = d;
        else
            s->period_s = d;
        return 0;
    case 8:
        if (ls_int(tok[1], 0, 1, &v))
            return ls_bad(p, "post_sides '%s' is not 0 or 1", tok[1]);
        s->post_sides = (int)v;
        return 0;
    case 9:
        if (ls_int(tok[1], -1, 1, &v))
            return ls_bad(p, "prior_half '%s' is not -1, 0 or 1", tok[1]);
        s->prior_half = (int)v;
        return 0;
    default:
        if (ls_int(tok[1], -1000000, 1000000, &v))
            return ls_bad(p, "penalty_x_mm '%s' is not an integer in range", tok[1]);
        s->penalty_x_mm = (int32_t)v;
        return 0;
    }
}

/* Numbers of a line: tok[from ..] into v[] with the ranges lo[], hi[]. */
static int ls_ints(ls_parser_t *p, char **tok, int from, int n, const long *lo, const long *hi,
                   long *v)
{
    int i;
    for (i = 0; i < n; i++)
        if (ls_int(tok[from + i], lo[i], hi[i], &v[i]))
            return ls_bad(p, "'%s' is not an integer in its range", tok[from + i]);
    return 0;
}

#define LS_A_MIN (-32768L)
#define LS_A_MAX 32767L
#define LS_I_MIN ((long)INT32_MIN)
#define LS_I_MAX ((long)INT32_MAX)

static int ls_body_line(ls_parser_t *p, char **tok, int nt)
{
    ls_stream_t *s = p->s;
    ls_record_t *r = s->n_rec > 0 ? &s->rec[s->n_rec - 1] : NULL;
    long v[12];
    if (!strcmp(tok[0], "record")) {
        static const long lo[6] = {0, 0, LS_I_MIN, LS_I_MIN, LS_I_MIN, LS_A_MIN};
        static const long hi[6] = {LONG_MAX, LONG_MAX, LS_I_MAX, LS_I_MAX, LS_I_MAX, LS_A_MAX};
        double d;
        if (nt != 7 && nt != 8)
            return ls_bad(p, "%srecord K STEP T_MS X_MM Y_MM HEADING [DEG]", "");
        if (ls_ints(p, tok, 1, 6, lo, hi, v))
            return -1;
        if (nt == 8 && tf_number(tok[7], 1e3, &d) != NULL)
            return ls_bad(p, "heading degrees '%s' is not a number", tok[7]);
        if (v[0] != s->n_rec)
            return ls_bad(p, "record index %s out of sequence", tok[1]);
        if (r != NULL && (uint32_t)v[1] <= r->step)
            return ls_bad(p, "record step %s not after the previous record's", tok[2]);
        if (ls_grow((void **)&s->rec, &s->cap_rec, s->n_rec, sizeof *s->rec))
            return ls_bad(p, "%sout of memory", "");
        r = &s->rec[s->n_rec++];
        memset(r, 0, sizeof *r);
        r->step = (uint32_t)v[1];
        r->t_ms = (int32_t)v[2];
        r->x_mm = (int32_t)v[3];
        r->y_mm = (int32_t)v[4];
        r->heading = (fl_angle_t)v[5];
        r->ev0 = (uint32_t)s->n_ev;
        r->op0 = (uint32_t)s->n_op;
        r->line = p->line;
        return 0;
    }
    if (!strcmp(tok[0], "end")) {
        if (nt != 2 || ls_int(tok[1], 0, LONG_MAX, &v[0]) || v[0] != s->n_rec)
            return ls_bad(p, "%send line does not give the number of records", "");
        p->ended = 1;
        return 0;
    }
    if (r == NULL)
        return ls_bad(p, "'%s' before the first record", tok[0]);
    if (!strcmp(tok[0], "kidnap") || !strcmp(tok[0], "penalized") ||
        !strcmp(tok[0], "unpenalized")) {
        static const long lo[5] = {0, LS_I_MIN, LS_I_MIN, LS_I_MIN, LS_A_MIN};
        static const long hi[5] = {LONG_MAX, LS_I_MAX, LS_I_MAX, LS_I_MAX, LS_A_MAX};
        int un = !strcmp(tok[0], "unpenalized");
        ls_event_t *e;
        if (nt != (un ? 3 : 6))
            return ls_bad(p, "'%s' has the wrong number of values", tok[0]);
        if (r->n_op > 0)
            return ls_bad(p, "event '%s' after a call of its record", tok[0]);
        if (ls_ints(p, tok, 1, un ? 2 : 5, lo, hi, v))
            return -1;
        if ((uint32_t)v[0] > r->step)
            return ls_bad(p, "event step %s after its record's", tok[1]);
        if (ls_grow((void **)&s->ev, &s->cap_ev, s->n_ev, sizeof *s->ev))
            return ls_bad(p, "%sout of memory", "");
        e = &s->ev[s->n_ev++];
        memset(e, 0, sizeof *e);
        e->bits = un ? SIM_EV_UNPENALIZED
                     : !strcmp(tok[0], "kidnap") ? SIM_EV_KIDNAP : SIM_EV_PENALIZED;
        e->step = (uint32_t)v[0];
        e->t_ms = (int32_t)v[1];
        if (!un) {
            e->x_mm = (int32_t)v[2];
            e->y_mm = (int32_t)v[3];
            e->heading = (fl_angle_t)v[4];
        }
        r->n_ev++;
        return 0;
    }
    if (!strcmp(tok[0], "predict") || !strcmp(tok[0], "reset_penalty")) {
        static const long lo[3] = {LS_I_MIN, LS_I_MIN, LS_A_MIN};
        static const long hi[3] = {LS_I_MAX, LS_I_MAX, LS_A_MAX};
        ls_op_t *op;
        if (nt != 4)
            return ls_bad(p, "'%s' takes three integers", tok[0]);
        if (ls_ints(p, tok, 1, 3, lo, hi, v))
            return -1;
        if (ls_grow((void **)&s->op, &s->cap_op, s->n_op, sizeof *s->op))
            return ls_bad(p, "%sout of memory", "");
        op = &s->op[s->n_op++];
        memset(op, 0, sizeof *op);
        op->kind = tok[0][0] == 'p' ? LS_OP_PREDICT : LS_OP_RESET_PENALTY;
        op->a = (int32_t)v[0];
        op->b = (int32_t)v[1];
        op->angle = (fl_angle_t)v[2];
        r->n_op++;
        return 0;
    }
    if (!strcmp(tok[0], "update")) {
        static const long lo[7] = {0, 0, 0, LS_A_MIN, LS_A_MIN, LS_I_MIN, LS_I_MIN};
        static const long hi[7] = {FL_OBS_MAX, 65535, 1, LS_A_MAX, LS_A_MAX, LS_I_MAX, LS_I_MAX};
        ls_op_t *op;
        int view;
        if (nt < 4 || (strcmp(tok[3], "noview") && strcmp(tok[3], "view")))
            return ls_bad(p, "%supdate N DROPPED noview | view VALID RIGHT LEFT NEAR FAR", "");
        view = !strcmp(tok[3], "view");
        if (nt != (view ? 9 : 4))
            return ls_bad(p, "%supdate has the wrong number of values", "");
        if (ls_ints(p, tok, 1, 2, lo, hi, v) || (view && ls_ints(p, tok, 4, 5, lo + 2, hi + 2, v + 2)))
            return -1;
        if (ls_grow((void **)&s->op, &s->cap_op, s->n_op, sizeof *s->op))
            return ls_bad(p, "%sout of memory", "");
        op = &s->op[s->n_op++];
        memset(op, 0, sizeof *op);
        op->kind = LS_OP_UPDATE;
        op->n_obs = (uint16_t)v[0];
        op->dropped = (uint16_t)v[1];
        op->obs0 = (uint32_t)s->n_obs;
        op->has_view = view;
        if (view) {
            op->view.valid = v[2] != 0;
            op->view.bearing_right = (fl_angle_t)v[3];
            op->view.bearing_left = (fl_angle_t)v[4];
            op->view.near_mm = (int32_t)v[5];
            op->view.far_mm = (int32_t)v[6];
        }
        p->obs_left = v[0];
        r->n_op++;
        return 0;
    }
    return ls_bad(p, "unknown keyword '%s'", tok[0]);
}

static int ls_obs_line(ls_parser_t *p, char **tok, int nt)
{
    static const char kc[] = "LTXPCGOBcfnN";
    static const long lo[10] = {0, 0, 0, 0, LS_A_MIN, LS_A_MIN, 0, 0, LS_I_MIN, LS_I_MIN};
    static const long hi[10] = {4, 4, 2, LS_I_MAX, LS_A_MAX, LS_A_MAX, 1, 255, LS_I_MAX, LS_I_MAX};
    ls_stream_t *s = p->s;
    const char *k;
    fl_obs_t *o;
    long v[10];
    if (strcmp(tok[0], "obs"))
        return ls_bad(p, "'%s' where an obs line is due", tok[0]);
    if (nt != 12)
        return ls_bad(p, "%sobs KIND COLOR COLOR2 SIDE RANGE BEARING ORIENTATION HAS_ORIENTATION "
                         "CONFIDENCE U_Q4 V_Q4", "");
    if (strlen(tok[1]) != 1 || (k = strchr(kc, tok[1][0])) == NULL)
        return ls_bad(p, "unknown observation kind '%s' (L T X P C G O B c f n N)", tok[1]);
    if (ls_ints(p, tok, 2, 10, lo, hi, v))
        return -1;
    if (ls_grow((void **)&s->obs, &s->cap_obs, s->n_obs, sizeof *s->obs))
        return ls_bad(p, "%sout of memory", "");
    o = &s->obs[s->n_obs++];
    memset(o, 0, sizeof *o);
    o->kind = (fl_landmark_kind_t)(k - kc);
    o->color = (fl_color_t)v[0];
    o->color2 = (fl_color_t)v[1];
    o->side = (fl_side_t)v[2];
    o->range_mm = (int32_t)v[3];
    o->bearing = (fl_angle_t)v[4];
    o->orientation = (fl_angle_t)v[5];
    o->has_orientation = v[6] != 0;
    o->confidence = (uint8_t)v[7];
    o->u_q4 = (int32_t)v[8];
    o->v_q4 = (int32_t)v[9];
    p->obs_left--;
    return 0;
}

static int ls_line(ls_parser_t *p, char *line)
{
    char *tok[LS_TOK_MAX + 1], *c = strchr(line, '#');
    int nt = 0;
    if (c != NULL)
        *c = '\0';
    for (c = strtok(line, " \t\r\n"); c != NULL; c = strtok(NULL, " \t\r\n")) {
        if (nt == LS_TOK_MAX)
            return ls_bad(p, "%stoo many values", "");
        tok[nt++] = c;
    }
    if (nt == 0)
        return 0;
    if (p->ended)
        return ls_bad(p, "'%s' after the end line", tok[0]);
    if (p->obs_left > 0)
        return ls_obs_line(p, tok, nt);
    if (!strcmp(tok[0], "obs"))
        return ls_bad(p, "%sobs line outside an update (or more than its N)", "");
    if (!p->in_body && strcmp(tok[0], "record") && strcmp(tok[0], "end")) {
        static const char *const body[] = {"predict", "update", "reset_penalty", "kidnap",
                                           "penalized", "unpenalized"};
        size_t k;
        for (k = 0; k < sizeof body / sizeof body[0]; k++)
            if (!strcmp(tok[0], body[k]))
                return ls_bad(p, "'%s' before the first record", tok[0]);
        return ls_header_line(p, tok, nt);
    }
    if (!p->in_body) {
        if ((p->have & LS_REQUIRED) != LS_REQUIRED)
            return ls_bad(p, "%sheader incomplete (field, camera, mode, every, frame_hz and "
                             "prior_half are required)", "");
        p->in_body = 1;
    }
    return ls_body_line(p, tok, nt);
}

int ls_read(FILE *f, const char *name, ls_stream_t *s, char *err, int err_len)
{
    ls_parser_t p;
    char line[LS_LINE_MAX + 2];
    memset(s, 0, sizeof *s);
    memset(&p, 0, sizeof p);
    p.s = s;
    s->version = LS_VERSION;
    s->every = 1;
    s->post_sides = 1;
    while (fgets(line, sizeof line, f) != NULL) {
        size_t len = strlen(line);
        p.line++;
        if (len > LS_LINE_MAX && line[len - 1] != '\n') {
            snprintf(p.why, sizeof p.why, "line longer than %d characters", LS_LINE_MAX);
            goto fail;
        }
        if (p.line == 1) {
            int ver = 0;
            char tail;
            if (sscanf(line, "fieldloc-stream %d %c", &ver, &tail) != 1) {
                snprintf(p.why, sizeof p.why, "not a fieldloc stream (first line "
                                              "\"fieldloc-stream %d\")", LS_VERSION);
                goto fail;
            }
            if (ver != LS_VERSION) {
                snprintf(p.why, sizeof p.why, "stream version %d (this reader: %d)", ver,
                         LS_VERSION);
                goto fail;
            }
            continue;
        }
        if (ls_line(&p, line) != 0)
            goto fail;
    }
    if (ferror(f)) {
        tf_err(err, err_len, "%s: read error", name);
        ls_free(s);
        return -1;
    }
    if (p.line == 0 || p.obs_left > 0 || !p.ended) {
        p.line++;
        snprintf(p.why, sizeof p.why, "%s",
                 p.line == 1 ? "empty file"
                 : p.obs_left > 0 ? "the file ends inside an update's observations"
                                  : "the file ends without its end line (truncated?)");
        goto fail;
    }
    return 0;
fail:
    tf_err(err, err_len, "%s: line %d: %s", name, p.line, p.why);
    ls_free(s);
    return -1;
}

int ls_load(const char *path, ls_stream_t *s, char *err, int err_len)
{
    FILE *f = fopen(path, "r");
    int rc;
    if (f == NULL) {
        memset(s, 0, sizeof *s);
        tf_err(err, err_len, "%s: cannot open", path);
        return -1;
    }
    rc = ls_read(f, path, s, err, err_len);
    fclose(f);
    return rc;
}

/* ---- replay ---------------------------------------------------------------- */

int ls_replay(const ls_stream_t *s, const fl_localizer_t *loc, const void *params, FILE *steps,
              int print_obs, lr_walk_result_t *res, char *err, int err_len)
{
    lr_t lr;
    lr_metrics_t met;
    fl_loc_estimate_t est;
    long i;
    memset(res, 0, sizeof *res);
    if (lr_init(&lr, loc, s->field, s->camera, params, err, err_len) != 0)
        return -1;
    if (lr_metrics_init(&met, s->field->symmetric) != 0) {
        lr_free(&lr);
        tf_err(err, err_len, "out of memory");
        return -1;
    }
    if (s->prior_half != 0)
        lr.loc->set_prior_half(lr.state, s->prior_half);
    res->dt_s = s->frame_hz > 0 ? s->every / s->frame_hz : 0;
    for (i = 0; i < s->n_rec; i++) {
        const ls_record_t *r = &s->rec[i];
        double t = r->t_ms / 1000.0, pe = 0, he = 0;
        uint32_t k;
        for (k = 0; k < r->n_ev; k++)
            lr_metrics_event(&met, s->ev[r->ev0 + k].bits, s->ev[r->ev0 + k].t_ms / 1000.0);
        fl_obs_list_clear(&lr.obs);
        for (k = 0; k < r->n_op; k++) {
            const ls_op_t *op = &s->op[r->op0 + k];
            if (op->kind == LS_OP_PREDICT) {
                lr.loc->predict(lr.state, op->a, op->b, op->angle);
            } else if (op->kind == LS_OP_RESET_PENALTY) {
                lr.loc->reset_penalty(lr.state, op->a, op->b, op->angle);
            } else {
                fl_obs_list_clear(&lr.obs);
                memcpy(lr.obs.obs, &s->obs[op->obs0], op->n_obs * sizeof lr.obs.obs[0]);
                lr.obs.n = op->n_obs;
                lr.obs.dropped = op->dropped;
                lr.view = op->view;
                lr.obs_used =
                    lr.loc->update(lr.state, &lr.obs, op->has_view ? &lr.view : NULL);
            }
        }
        lr.loc->estimate(lr.state, &est);
        if (lr_metrics_record(&met, t, &est, r->x_mm, r->y_mm, r->heading, &pe, &he) < 0) {
            lr_metrics_free(&met);
            lr_free(&lr);
            tf_err(err, err_len, "out of memory");
            return -1;
        }
        if (steps != NULL) {
            lr_print_step(steps, r->step, t, &est, r->x_mm, r->y_mm, r->heading, pe, he);
            if (print_obs)
                lr_print_obs(steps, &lr.obs);
        }
    }
    lr_metrics_finish(&met, res);
    res->steps = s->n_rec > 0 ? (long)s->rec[s->n_rec - 1].step + 1 : 0;
    lr.loc->stats(lr.state, &res->stats);
    lr_metrics_free(&met);
    lr_free(&lr);
    return 0;
}
