/*
 * tools/eval/eval_relmap.c - seed 002's evaluation (eval_relmap.h): table I
 * and random poses on hl3x2, rendered, through seed 002's vision path and a
 * catalogue localizer from ignorance.
 */
#include "eval/eval_relmap.h"

#include "fieldloc/camera.h"
#include "fieldloc/hlvision.h"
#include "fieldloc/localizer.h"
#include "fieldloc/relmap.h"
#include "fieldloc/vision.h"
#include "world/render.h"
#include "world/seed002.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define ER_WRONG_SIDE_MM 500.0
#define ER_TIE_RIGHT_MM 300.0
#define ER_TIE_RIGHT_DEG 20.0
#define ER_DRAWS_PER_POSE 50

typedef struct {
    const er_opts_t *o;
    const fl_field_t *field;
    const fl_localizer_t *loc;
    void *state, *params;
    fl_hlv_t *hlv;
    fl_obs_list_t obs;
    double time_sum_ms, time_max_ms;
    long frames, ties, ties_right;
} er_ctx_t;

typedef struct {
    double pos_mm, head_deg;
    int wrong_side;
    fl_loc_estimate_t est;
    char seen[160];           /* the last frame's observations, short */
    int white_n;              /* relmap: white points of the last frame; */
    int white_true, white_est;   /* ... on lines at the true pose and at
                                    the estimate; -1: not relmap */
    int n_tied;               /* relmap: the last frame's tie set */
} er_score_t;

static uint64_t er_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform integer in [lo, hi]. */
static int32_t er_uniform(uint64_t *s, int32_t lo, int32_t hi)
{
    return lo + (int32_t)(er_next(s) % (uint64_t)(hi - lo + 1));
}

static double er_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static double er_angle_deg(fl_angle_t a)
{
    return (double)a * 360.0 / 65536.0;
}

static double er_wrap_deg(double d)
{
    while (d > 180.0)
        d -= 360.0;
    while (d <= -180.0)
        d += 360.0;
    return d;
}

static int er_ctx_init(er_ctx_t *c, const er_opts_t *o)
{
    fl_hlv_params_t hp;
    memset(c, 0, sizeof *c);
    c->o = o;
    c->field = fl_field_find("hl3x2");
    c->loc = fl_localizer_find(o->localizer);
    if (c->field == NULL || c->loc == NULL) {
        fprintf(stderr, "eval-relmap: no field hl3x2 or no localizer \"%s\"\n", o->localizer);
        return -1;
    }
    c->state = malloc(c->loc->state_size);
    c->params = malloc(c->loc->params_size);
    c->hlv = malloc(sizeof *c->hlv);
    if (c->state == NULL || c->params == NULL || c->hlv == NULL) {
        fprintf(stderr, "eval-relmap: out of memory\n");
        return -1;
    }
    fl_hlv_params_default(&hp, c->field);
    if (fl_hlv_init(c->hlv, &hp) != FL_OK) {
        fprintf(stderr, "eval-relmap: seed 002's vision path refused its defaults\n");
        return -1;
    }
    return 0;
}

static void er_ctx_free(er_ctx_t *c)
{
    free(c->state);
    free(c->params);
    free(c->hlv);
}

/* The localizer from ignorance, seeded per pose so that every pose is
 * reproducible alone. */
static int er_loc_reset(er_ctx_t *c, uint32_t pose_seed)
{
    int i;
    c->loc->params_preset(c->params, FL_LOC_PRESET_VISION);   /* vision in the loop */
    c->loc->params_adapt(c->params, fl_loc_preset_for_width(640));
    if (fl_localizer_param_find(c->loc, "seed") != NULL)
        (void)fl_localizer_param_set(c->loc, c->params, "seed", (int32_t)(pose_seed & 0x7fffffff));
    for (i = 0; i < c->o->n_param; i++)
        if (fl_localizer_param_set(c->loc, c->params, c->o->param_name[i], c->o->param_value[i]) !=
                FL_OK ||
            c->loc->params_check(c->params) != FL_OK) {
            fprintf(stderr, "eval-relmap: bad --param %s=%ld (not a parameter of %s, or out of range)\n",
                    c->o->param_name[i], (long)c->o->param_value[i], c->loc->name);
            return -1;
        }
    if (fl_loc_init(c->loc, c->state, c->field, c->params) != FL_OK) {
        fprintf(stderr, "eval-relmap: %s refused hl3x2\n", c->loc->name);
        return -1;
    }
    return 0;
}

/* Relmap's frame result: a tie, and whether its pick is right. */
static void er_tie(er_ctx_t *c, int32_t x, int32_t y, int32_t heading_deg)
{
    const fl_relmap_t *s = (const fl_relmap_t *)c->state;
    double d, h;
    if (strcmp(c->loc->name, "relmap") != 0 || !s->best.valid || s->best.n_tied <= 1)
        return;
    c->ties++;
    d = hypot((double)s->best.x_mm - x, (double)s->best.y_mm - y);
    h = fabs(er_wrap_deg(er_angle_deg(s->best.heading) - heading_deg));
    if (d <= ER_TIE_RIGHT_MM && h <= ER_TIE_RIGHT_DEG)
        c->ties_right++;
}

/* The observations as kind letters (P pole, G post; lower case: the
 * localizer ignores it, confidence 0) with their ranges in cm. */
static void er_obs_names(const fl_obs_list_t *obs, char *buf, size_t len)
{
    static const char kinds[FL_LM_KIND_COUNT + 1] = "LTXMmGCPcfnN";
    size_t n = 0;
    uint16_t i;
    buf[0] = '\0';
    for (i = 0; i < obs->n && i < FL_OBS_MAX && n + 12 < len; i++) {
        const fl_obs_t *o = &obs->obs[i];
        char k = (int)o->kind >= 0 && o->kind < FL_LM_KIND_COUNT ? kinds[o->kind] : '?';
        if (o->confidence == 0)
            k = (char)(k | 0x20);
        n += (size_t)snprintf(buf + n, len - n, "%s%c%d", n ? " " : "", k, (int)(o->range_mm / 10));
    }
}

/* One pose: frames rendered, seen and localized; the score. */
static int er_pose(er_ctx_t *c, int32_t x, int32_t y, int32_t heading_deg, uint32_t pose_seed,
                   er_score_t *sc_out)
{
    render_scene_t sc;
    int f;
    double mx, my;
    if (er_loc_reset(c, pose_seed) != 0)
        return -1;
    s002_scene(&sc, x, y, heading_deg);
    sc.world_seed = pose_seed;
    for (f = 0; f < c->o->frames; f++) {
        render_frame_t fr;
        fl_camera_t cam;
        fl_obs_view_t view;
        double t0, dt;
        sc.seed = pose_seed * 31u + (uint32_t)f;
        if (render_frame(&sc, &fr) != 0 || render_scene_camera(&sc, &cam) != FL_OK) {
            fprintf(stderr, "eval-relmap: cannot render the pose (%d, %d, %d deg)\n", (int)x,
                    (int)y, (int)heading_deg);
            return -1;
        }
        fl_vision_view(&cam, &view);
        t0 = er_now_ms();
        (void)fl_hlv_frame(c->hlv, &fr.view, &cam, &c->obs);
        (void)fl_loc_update(c->loc, c->state, &c->obs, &view);
        dt = er_now_ms() - t0;
        render_frame_free(&fr);
        c->time_sum_ms += dt;
        if (dt > c->time_max_ms)
            c->time_max_ms = dt;
        c->frames++;
        er_tie(c, x, y, heading_deg);
    }
    memset(sc_out, 0, sizeof *sc_out);
    er_obs_names(&c->obs, sc_out->seen, sizeof sc_out->seen);
    if (!fl_loc_estimate(c->loc, c->state, &sc_out->est))
        return -1;
    sc_out->white_true = sc_out->white_est = -1;
    if (strcmp(c->loc->name, "relmap") == 0) {
        const fl_relmap_t *s = (const fl_relmap_t *)c->state;
        sc_out->white_n = c->obs.n_points < FL_RELMAP_MAX_WHITE ? c->obs.n_points : FL_RELMAP_MAX_WHITE;
        sc_out->white_true = fl_relmap_white_hits(c->field, &c->obs, x, y,
                                                  fl_angle_from_mdeg(heading_deg * 1000),
                                                  s->params.white_tol_mm);
        sc_out->white_est = fl_relmap_white_hits(c->field, &c->obs, sc_out->est.x_mm, sc_out->est.y_mm,
                                                 sc_out->est.heading, s->params.white_tol_mm);
        sc_out->n_tied = s->best.valid ? s->best.n_tied : 0;
    }
    sc_out->pos_mm = hypot((double)sc_out->est.x_mm - x, (double)sc_out->est.y_mm - y);
    sc_out->head_deg = fabs(er_wrap_deg(er_angle_deg(sc_out->est.heading) - heading_deg));
    mx = -(double)x;
    my = -(double)y;
    sc_out->wrong_side = sc_out->pos_mm > ER_WRONG_SIDE_MM &&
                         hypot((double)sc_out->est.x_mm - mx, (double)sc_out->est.y_mm - my) <
                             sc_out->pos_mm;
    return 0;
}

static int er_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double er_median(double *v, int n)
{
    if (n <= 0)
        return 0.0;
    qsort(v, (size_t)n, sizeof *v, er_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static int er_table1(er_ctx_t *c, FILE *out, er_result_t *res)
{
    int i;
    fprintf(out, "# table I (seed 002 appendix B, reading %s; %d frames per pose, %s)\n",
            s002_reading_name(S002_CHOSEN), c->o->frames, c->loc->name);
    fprintf(out, "# fig   true pose (mm, deg)      estimate (mm, deg)       err mm  err deg"
                 "   seed 002: err mm  err deg\n");
    for (i = 0; i < S002_TABLE1_N; i++) {
        const s002_table1_t *t = &s002_table1[i];
        er_score_t s;
        if (er_pose(c, t->x_mm, t->y_mm, t->heading_deg, c->o->seed * 1000u + (uint32_t)i, &s) != 0)
            return -1;
        fprintf(out, "# %-5s (%5d, %5d, %4d)   (%5d, %5d, %6.1f)   %6.0f  %7.1f   %16d  %7d\n",
                t->fig, (int)t->x_mm, (int)t->y_mm, (int)t->heading_deg, (int)s.est.x_mm,
                (int)s.est.y_mm, er_wrap_deg(er_angle_deg(s.est.heading)), s.pos_mm, s.head_deg,
                (int)t->paper_pos_err_mm, (int)t->paper_heading_err_deg);
        if (s.pos_mm > res->table1_max_pos_mm)
            res->table1_max_pos_mm = s.pos_mm;
        if (s.head_deg > res->table1_max_head_deg)
            res->table1_max_head_deg = s.head_deg;
    }
    return 0;
}

static int er_random(er_ctx_t *c, FILE *out, er_result_t *res)
{
    uint64_t rng = 0x5eed002ull ^ ((uint64_t)c->o->seed << 20);
    double *pos = malloc(sizeof(double) * (size_t)(c->o->poses + 1));
    double *head = malloc(sizeof(double) * (size_t)(c->o->poses + 1));
    int wrong = 0, kept = 0, drawn = 0, rc = 0;
    int32_t hx = c->field->length_mm / 2, hy = c->field->width_mm / 2;
    if (pos == NULL || head == NULL) {
        free(pos);
        free(head);
        return -1;
    }
    while (kept < c->o->poses && drawn < ER_DRAWS_PER_POSE * c->o->poses) {
        int32_t x = er_uniform(&rng, -hx, hx), y = er_uniform(&rng, -hy, hy);
        int32_t deg = er_uniform(&rng, -180, 179);
        render_scene_t sc;
        s002_seen_t seen;
        er_score_t s;
        char names[256];
        drawn++;
        s002_scene(&sc, x, y, deg);
        if (s002_visible(&sc, &seen, names, (int)sizeof names) != 0 ||
            seen.tx + seen.posts + seen.poles < 2)
            continue;
        if (er_pose(c, x, y, deg, c->o->seed * 100003u + (uint32_t)drawn, &s) != 0) {
            rc = -1;
            break;
        }
        pos[kept] = s.pos_mm;
        head[kept] = s.head_deg;
        wrong += s.wrong_side;
        if (c->o->verbose)
            fprintf(out, "# pose %3d (%5d, %5d, %4d) sees %-48s found %-24s est (%5d, %5d) err %6.0f mm %5.1f deg%s",
                    kept, (int)x, (int)y, (int)deg, names, s.seen, (int)s.est.x_mm, (int)s.est.y_mm,
                    s.pos_mm, s.head_deg, s.wrong_side ? " WRONG SIDE" : "");
        if (c->o->verbose && s.white_true >= 0)
            fprintf(out, "; white points on lines %d of %d at the pose, %d at the estimate; tied %d",
                    s.white_true, s.white_n, s.white_est, s.n_tied);
        if (c->o->verbose)
            fputc('\n', out);
        kept++;
    }
    res->kept = kept;
    res->drawn = drawn;
    res->median_pos_mm = er_median(pos, kept);
    res->median_head_deg = er_median(head, kept);
    res->wrong_side_pct = kept > 0 ? 100.0 * wrong / kept : 0.0;
    free(pos);
    free(head);
    return rc;
}

int er_run(const er_opts_t *o, FILE *out, er_result_t *res)
{
    er_ctx_t c;
    int rc;
    memset(res, 0, sizeof *res);
    if (o == NULL || o->frames < 1 || o->poses < 0 || o->localizer == NULL)
        return -1;
    if (er_ctx_init(&c, o) != 0) {
        er_ctx_free(&c);
        return -1;
    }
    rc = er_table1(&c, out, res);
    if (rc == 0)
        rc = er_random(&c, out, res);
    res->frames_run = c.frames;
    res->frame_ms = c.frames > 0 ? c.time_sum_ms / (double)c.frames : 0.0;
    res->frame_ms_max = c.time_max_ms;
    res->ties = c.ties;
    res->ties_right = c.ties_right;
    fprintf(out, "# random poses: %d kept of %d drawn (at least two landmarks in view: T or X "
                 "crossings with their arms in the frame, posts, poles); "
                 "wrong side: estimate > %.0f mm off and nearer the pose turned about the centre\n",
            res->kept, res->drawn, ER_WRONG_SIDE_MM);
    if (strcmp(c.loc->name, "relmap") == 0)
        fprintf(out, "# ties (eq. 4 minimum shared): %ld frames, resolved right (within %.0f mm, "
                     "%.0f deg) %ld (%.1f %%)\n",
                res->ties, ER_TIE_RIGHT_MM, ER_TIE_RIGHT_DEG, res->ties_right,
                res->ties > 0 ? 100.0 * (double)res->ties_right / (double)res->ties : 0.0);
    fprintf(out, "# time: vision + update %.3f ms per frame (mean of %ld), worst %.3f ms\n",
            res->frame_ms, res->frames_run, res->frame_ms_max);
    er_ctx_free(&c);
    return rc;
}

void er_print_summary(FILE *out, const er_result_t *res)
{
    fprintf(out, "table1_max_pos_err_mm %.0f\n", res->table1_max_pos_mm);
    fprintf(out, "table1_max_heading_err_deg %.1f\n", res->table1_max_head_deg);
    fprintf(out, "median_pos_err_mm %.0f\n", res->median_pos_mm);
    fprintf(out, "median_heading_err_deg %.1f\n", res->median_head_deg);
    fprintf(out, "wrong_side_pct %.1f\n", res->wrong_side_pct);
    fprintf(out, "frame_ms %.3f\n", res->frame_ms);
}
