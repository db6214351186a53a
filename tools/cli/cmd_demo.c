/*
 * tools/cli/cmd_demo.c - `fieldloc demo`: the main job end to end on the
 * bundled walk.  A NAO walks the SPL 2013 field (fixtures/walks/spl2013.walk:
 * 130 s, head scanning, a kidnap at 55 s, a penalty at 95 s); every 3rd frame
 * (10 Hz) is rendered at the true pose, run through the firmware vision path
 * and fed to the localizer (--localizer, default the fuzzy position grid), exactly as `fieldloc simulate
 * --frames` (tools/loc/locrun.c lr_walk_run; same metrics and summary lines).
 *
 *   fieldloc demo [--walk FILE.walk | --field NAME] [--seed N] [--every N]
 *                 [--seconds S] [--out DIR] [--picture-every-s S] [--no-png]
 *                 [--localizer NAME] [--param NAME=VALUE]...
 *                 [--compare NAME [--compare-param NAME=VALUE]...]
 *
 * Defaults: the built-in spl2013 walk (the text of
 * fixtures/walks/spl2013.walk), its own seed, --every 3, the whole walk,
 * --out build/demo, a picture every 10 s of walk time.  --field NAME takes
 * another built-in walk: uva2013, aibo2004, or spl2020 (today's field:
 * white goals, NAO v6 top camera at 640 x 480, other robots in view).
 *
 * Prints a progress line every 5 s of walk time (estimate, truth, error,
 * reliability, observations, wall time), the events (kidnap, penalty), the
 * summary lines of `simulate` and the final error.  Writes to DIR:
 *   demo_tNNN.ppm (.png)  frame with the detected features and the field
 *                         model seen from the estimate (yellow dots), next
 *                         to the belief grid (cells shaded by height,
 *                         heading ticks, truth cyan, estimate magenta,
 *                         the frame's observations as white squares), or
 *                         a particle filter's particles (picture.h) with
 *                         a 4 x magnified view around the estimate
 *   demo_kidnap.ppm       1 s after the kidnap; demo_final.ppm at the end
 *   belief_final.ppm, frame_final.ppm   the two halves of the last picture
 *   compare_NAME.ppm      with --compare B: for every belief picture above
 *                         (demo_tNNN, demo_kidnap, demo_final), the belief
 *                         of the --localizer (left) and of B (right) at the
 *                         same record, side by side.  B runs after the walk
 *                         on the same observations (the walk's vision
 *                         output cached in DIR/compare_obs.cache, removed
 *                         afterwards) with its vision parameters and
 *                         --compare-param; its summary lines follow the
 *                         first's after a "# compare: B" line
 *   steps.txt             the per-record lines of `simulate`
 *   summary.txt           the summary lines
 * PNG next to every PPM (unless --no-png).
 */
#include "loc/locrun.h"
#include "cli/args.h"
#include "eval/picture.h"
#include "io/ppm.h"
#include "cli/registry.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* A belief picture kept for --compare: its record, name and caption. */
typedef struct {
    long record;
    char name[64];
    char caption[512];
    host_image_t belief;
    unsigned sets;
} demo_keep_t;

typedef struct {
    const char *out;
    int png;
    int compare;                 /* keep the belief pictures */
    demo_keep_t *keep;
    int n_keep, cap_keep;
    double picture_every_s, next_picture_s, next_progress_s;
    double t_kidnap, wall0;
    int kidnap_pictured;
    int pictures, pngs;
    FILE *steps;
    long records;
} demo_t;

static double demo_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void demo_save(demo_t *d, const host_image_t *img, const char *name)
{
    char base[1100];
    int png = 0;
    snprintf(base, sizeof base, "%s/%s", d->out, name);
    if (pic_save(img, base, d->png, &png) == 0) {
        d->pictures++;
        d->pngs += png;
    } else {
        fprintf(stderr, "demo: cannot write %s.ppm\n", base);
    }
}

/* The belief picture of the record; for a sample localizer with its
 * magnified view around the estimate (pic_belief_zoom: 4 x, as tall as the
 * picture) on the right, since a tracked cluster is a few pixels wide at
 * the field's scale.  0 on success. */
static int demo_belief(const lr_walk_step_t *ws, const pic_pose_t *truth, host_image_t *out)
{
    host_image_t belief, zoom;
    if (pic_belief(ws->lr->loc, ws->lr->state, ws->lr->field, 0, truth, ws->est, &ws->lr->obs,
                   &belief) != 0)
        return -1;
    if (pic_belief_legend(ws->lr->loc, ws->lr->state) != PIC_LEGEND_PARTICLES ||
        pic_belief_zoom(ws->lr->loc, ws->lr->state, ws->lr->field, ws->est->x_mm, ws->est->y_mm,
                        0, belief.height, truth, ws->est, &ws->lr->obs, &zoom) != 0) {
        *out = belief;
        return 0;
    }
    if (pic_side_by_side(&belief, &zoom, 4, out) != 0)
        *out = belief;
    else
        host_image_free(&belief);
    host_image_free(&zoom);
    return 0;
}

/* A copy of a belief picture for --compare (none when out of memory). */
static void demo_keep(demo_t *d, long record, const char *name, const char *caption,
                      const host_image_t *belief, unsigned sets)
{
    demo_keep_t *k;
    size_t bytes = (size_t)belief->width * (size_t)belief->height * 3;
    if (d->n_keep == d->cap_keep) {
        int cap = d->cap_keep ? 2 * d->cap_keep : 16;
        demo_keep_t *nk = realloc(d->keep, (size_t)cap * sizeof *nk);
        if (nk == NULL)
            return;
        d->keep = nk;
        d->cap_keep = cap;
    }
    k = &d->keep[d->n_keep];
    k->belief = host_image_new(belief->width, belief->height, 0, 0, 0);
    if (k->belief.rgb == NULL)
        return;
    memcpy(k->belief.rgb, belief->rgb, bytes);
    k->record = record;
    k->sets = sets;
    snprintf(k->name, sizeof k->name, "%s", name);
    snprintf(k->caption, sizeof k->caption, "%s", caption);
    d->n_keep++;
}

/* Frame | belief picture of one record; halves optionally kept.  Each
 * picture carries its legend strip: walk time and frame (record) number,
 * the estimate with its reliability, and the error to the truth as the
 * metrics count it (modulo the symmetry while the half is unknown). */
static void demo_picture(demo_t *d, const lr_walk_step_t *ws, const char *name, int halves)
{
    host_image_t belief, frame, both;
    pic_pose_t truth, ep;
    char caption[512];
    const unsigned frame_sets = PIC_LEGEND_DETECT | PIC_LEGEND_MODEL,
                   belief_sets = pic_belief_legend(ws->lr->loc, ws->lr->state) | PIC_LEGEND_TRUTH;
    truth.x_mm = ws->st->true_x_mm;
    truth.y_mm = ws->st->true_y_mm;
    truth.heading_deg = ws->st->true_heading_rad * (180.0 / 3.14159265358979323846);
    ep.x_mm = ws->est->x_mm;
    ep.y_mm = ws->est->y_mm;
    ep.heading_deg = lr_deg(ws->est->heading);
    if (demo_belief(ws, &truth, &belief) != 0)
        return;
    pic_belief_caption(caption, sizeof caption, ws->t_s, ws->record, ws->est, ws->pos_err_mm,
                       ws->head_err_deg);
    if (d->compare)
        demo_keep(d, ws->record, name, caption, &belief, belief_sets & ~PIC_LEGEND_TRUTH);
    if (ws->frame != NULL &&
        pic_frame(&ws->lr->det, &ws->frame->view, &ws->lr->cam, ws->lr->field, &ep, 2, &frame) ==
            0) {
        if (pic_side_by_side(&frame, &belief, 8, &both) == 0) {
            if (pic_legend_inplace(&both, frame_sets | belief_sets, caption) == 0)
                demo_save(d, &both, name);
            host_image_free(&both);
        }
        if (halves && pic_legend_inplace(&frame, frame_sets, caption) == 0)
            demo_save(d, &frame, "frame_final");
        host_image_free(&frame);
        if (halves && pic_legend_inplace(&belief, belief_sets, caption) == 0)
            demo_save(d, &belief, "belief_final");
    } else if (pic_legend_inplace(&belief, belief_sets, caption) == 0) {
        demo_save(d, &belief, name);
        if (halves)
            demo_save(d, &belief, "belief_final");
    }
    host_image_free(&belief);
}

static void demo_hook(void *user, const lr_walk_step_t *ws)
{
    demo_t *d = user;
    const fl_loc_estimate_t *e = ws->est;
    char name[64];
    d->records++;
    if (ws->events & SIM_EV_KIDNAP) {
        d->t_kidnap = ws->t_s;
        printf("  t %6.1f s  KIDNAP: the robot is carried to (%d, %d) and nobody tells the "
               "localizer\n",
               ws->t_s, (int)ws->st->x_mm, (int)ws->st->y_mm);
    }
    if (ws->events & SIM_EV_PENALIZED)
        printf("  t %6.1f s  PENALTY: placed on a touchline spot; the localizer is reset to "
               "both spots of its half\n",
               ws->t_s);
    if (ws->t_s + 1e-9 >= d->next_progress_s) {
        printf("  t %6.1f s  est %6d %6d %6.1f  rel %.2f %-9s  truth %6d %6d %6.1f  err %5.0f mm "
               "%5.1f deg  obs %2d  (%.0f s)\n",
               ws->t_s, (int)e->x_mm, (int)e->y_mm, lr_deg(e->heading),
               e->reliability_q16 / 65536.0, lr_state_name(e->state), (int)ws->st->x_mm,
               (int)ws->st->y_mm,
               lr_deg(ws->st->heading), ws->pos_err_mm, ws->head_err_deg, (int)ws->lr->obs.n,
               demo_now() - d->wall0);
        fflush(stdout);
        d->next_progress_s += 5.0;
    }
    if (d->picture_every_s > 0 && ws->t_s + 1e-9 >= d->next_picture_s) {
        snprintf(name, sizeof name, "demo_t%03d", (int)lround(ws->t_s));
        demo_picture(d, ws, name, 0);
        d->next_picture_s += d->picture_every_s;
    }
    if (d->t_kidnap >= 0 && !d->kidnap_pictured && ws->t_s >= d->t_kidnap + 1.0) {
        demo_picture(d, ws, "demo_kidnap", 0);
        d->kidnap_pictured = 1;
    }
}

/* The last record gets its own picture: re-run is not possible after the
 * walk, so the hook keeps the newest record's picture pending and the
 * final one is written from a second, minimal hook pass below. */
typedef struct {
    demo_t *d;
    long last;
} demo_final_t;

static void demo_final_hook(void *user, const lr_walk_step_t *ws)
{
    demo_final_t *f = user;
    demo_hook(f->d, ws);
    if (ws->record == f->last)
        demo_picture(f->d, ws, "demo_final", 1);
}

/* --compare: the second localizer's pass over the cached observations. */
typedef struct {
    demo_t *d;
    const char *name_a;
} demo_cmp_t;

/* One caption line: the localizer's name, then the caption's lines joined. */
static void demo_cmp_line(char *buf, size_t n, const char *who, const char *caption)
{
    size_t k;
    snprintf(buf, n, "%s: %s", who, caption);
    for (k = 0; buf[k] != '\0'; k++)
        if (buf[k] == '\n')
            buf[k] = ' ';
}

static void demo_cmp_hook(void *user, const lr_walk_step_t *ws)
{
    demo_cmp_t *c = user;
    demo_t *d = c->d;
    int i;
    for (i = 0; i < d->n_keep; i++) {
        demo_keep_t *k = &d->keep[i];
        host_image_t belief, both;
        pic_pose_t truth;
        char cap_b[512], la[600], lb[600], caption[1300], name[96];
        if (k->record != ws->record)
            continue;
        truth.x_mm = ws->st->true_x_mm;
        truth.y_mm = ws->st->true_y_mm;
        truth.heading_deg = ws->st->true_heading_rad * (180.0 / 3.14159265358979323846);
        if (demo_belief(ws, &truth, &belief) != 0)
            continue;
        pic_belief_caption(cap_b, sizeof cap_b, ws->t_s, ws->record, ws->est, ws->pos_err_mm,
                           ws->head_err_deg);
        demo_cmp_line(la, sizeof la, c->name_a, k->caption);
        demo_cmp_line(lb, sizeof lb, ws->lr->loc->name, cap_b);
        snprintf(caption, sizeof caption, "left %s\nright %s", la, lb);
        if (pic_side_by_side(&k->belief, &belief, 8, &both) == 0) {
            if (pic_legend_inplace(&both,
                                   k->sets | pic_belief_legend(ws->lr->loc, ws->lr->state) |
                                       PIC_LEGEND_TRUTH,
                                   caption) == 0) {
                snprintf(name, sizeof name, "compare_%s", k->name);
                demo_save(d, &both, name);
            }
            host_image_free(&both);
        }
        host_image_free(&belief);
    }
}

/* Run localizer b over the walk's cached observations; 0 on success. */
static int demo_compare(demo_t *d, const sim_scenario_t *sc, const lr_walk_opts_t *first,
                        const char *name_a, const fl_localizer_t *b, const char *const *param,
                        int n_param)
{
    lr_walk_opts_t o = *first;
    lr_walk_result_t res;
    demo_cmp_t c;
    char err[256];
    void *params = lr_params_new(b);
    int k, rc;
    if (params == NULL)
        return -1;
    lr_params_frames(b, params);
    for (k = 0; k < n_param; k++)
        if (lr_param_set(b, params, param[k]) != 0) {
            fprintf(stderr, "demo: bad --compare-param '%s' (a parameter of localizer %s)\n",
                    param[k], b->name);
            free(params);
            return -1;
        }
    c.d = d;
    c.name_a = name_a;
    o.loc = b;
    o.params = params;
    o.steps = NULL;
    o.hook = demo_cmp_hook;
    o.user = &c;
    rc = lr_walk_run(sc, &o, &res, err, (int)sizeof err);
    free(params);
    if (rc != 0) {
        fprintf(stderr, "demo: --compare %s: %s\n", b->name, err);
        return -1;
    }
    printf("# compare: %s on the same observations\n", b->name);
    lr_walk_print_summary(stdout, &res);
    printf("final error %.0f mm %.1f deg\n", res.final_pos_err_mm, res.final_head_err_deg);
    return 0;
}

static int demo_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc demo [--walk FILE.walk | --field NAME] [--seed N] [--every N]\n"
            "                     [--seconds S] [--out DIR] [--picture-every-s S] [--no-png]\n"
            "                     [--localizer NAME (default fuzzy)] [--param NAME=VALUE]...\n"
            "                     [--compare NAME [--compare-param NAME=VALUE]...]\n"
            "                     [--colors default|auto|FILE]\n"
            "  --seed 0..2147483647, --every 1..1000, --seconds 0..86400 (0: the whole walk),\n"
            "  --picture-every-s 0..86400 (0: none)\n");
    return 2;
}

int cmd_demo(int argc, char **argv)
{
    static sim_scenario_t sc;
    const char *walk = NULL, *field = "spl2013", *out = "build/demo";
    long seed = -1, every = 3;
    double seconds = 0, pic_s = 10;
    int png = 1, k;
    char err[256], path[1100];
    lr_walk_opts_t o;
    lr_walk_result_t res;
    colors_opt_t colors;
    const char *localizer = NULL, *param[64], *compare = NULL, *cparam[64];
    int n_param = 0, n_cparam = 0;
    const fl_localizer_t *loc_b = NULL;
    char cache[1100];
    const fl_localizer_t *loc;
    void *params;
    demo_t d;
    demo_final_t fin;
    sim_t *probe;
    FILE *f;
    memset(&colors, 0, sizeof colors);
    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--walk") && k + 1 < argc)
            walk = argv[++k];
        else if (!strcmp(argv[k], "--colors") && k + 1 < argc) {
            /* colour classes (eval/colors_opt.h): auto estimated on the
             * first frame and tracked on every one */
            if (colors_opt_parse("demo", argv[++k], &colors) != 0)
                return 2;
        }
        else if (!strcmp(argv[k], "--field") && k + 1 < argc)
            field = argv[++k];
        else if (!strcmp(argv[k], "--seed") && k + 1 < argc) {
            if (arg_long("demo", "--seed", argv[++k], 0, 2147483647L, NULL, &seed) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--every") && k + 1 < argc) {
            if (arg_long("demo", "--every", argv[++k], 1, 1000, NULL, &every) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--seconds") && k + 1 < argc) {
            if (arg_double("demo", "--seconds", argv[++k], 0, 86400, "s", &seconds) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--out") && k + 1 < argc)
            out = argv[++k];
        else if (!strcmp(argv[k], "--picture-every-s") && k + 1 < argc) {
            if (arg_double("demo", "--picture-every-s", argv[++k], 0, 86400, "s", &pic_s) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--no-png"))
            png = 0;
        else if (!strcmp(argv[k], "--localizer") && k + 1 < argc)
            localizer = argv[++k];
        else if (!strcmp(argv[k], "--param") && k + 1 < argc) {
            if (n_param == 64) {
                fprintf(stderr, "demo: at most 64 --param\n");
                return 2;
            }
            param[n_param++] = argv[++k];
        } else if (!strcmp(argv[k], "--compare") && k + 1 < argc)
            compare = argv[++k];
        else if (!strcmp(argv[k], "--compare-param") && k + 1 < argc) {
            if (n_cparam == 64) {
                fprintf(stderr, "demo: at most 64 --compare-param\n");
                return 2;
            }
            cparam[n_cparam++] = argv[++k];
        }
        else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            demo_usage();
            return 0;
        } else
            return arg_unknown("demo", argv[k],
                               "--walk=1 --field=1 --seed=1 --every=1 --seconds=1 --out=1 "
                               "--picture-every-s=1 --localizer=1 --param=1 --compare=1 "
                               "--compare-param=1 --colors=1");
    }
    if (every < 1 || every > 1000 || seconds < 0 || pic_s < 0)
        return demo_usage();
    if ((loc = lr_localizer(localizer, err, (int)sizeof err)) == NULL) {
        fprintf(stderr, "demo: %s\n", err);
        return 2;
    }
    if (compare != NULL && (loc_b = lr_localizer(compare, err, (int)sizeof err)) == NULL) {
        fprintf(stderr, "demo: --compare: %s\n", err);
        return 2;
    }
    if (walk != NULL) {
        if (sim_scenario_load(&sc, walk, err, (int)sizeof err) != 0) {
            fprintf(stderr, "demo: %s: %s\n", walk, err);
            return 1;
        }
    } else if (sim_scenario_builtin(&sc, field) != 0) {
        fprintf(stderr, "demo: no built-in walk for field '%s' (spl2013, uva2013, aibo2004, spl2020)\n",
                field);
        return 2;
    }
    if (seed >= 0)
        sc.seed = (uint64_t)seed;
    if (lr_mkdirs(out) != 0) {
        fprintf(stderr, "demo: cannot create %s\n", out);
        return 1;
    }
    memset(&d, 0, sizeof d);
    d.out = out;
    d.png = png;
    d.picture_every_s = pic_s;
    d.t_kidnap = -1;
    d.wall0 = demo_now();
    d.compare = loc_b != NULL;
    snprintf(path, sizeof path, "%s/steps.txt", out);
    d.steps = fopen(path, "w");
    memset(&o, 0, sizeof o);
    o.frames = 1;
    o.every = (int)every;
    /* the localizer's vision parameters; freed at exit */
    if ((params = lr_params_new(loc)) == NULL) {
        fprintf(stderr, "demo: out of memory\n");
        return 1;
    }
    lr_params_frames(loc, params);
    for (k = 0; k < n_param; k++)
        if (lr_param_set(loc, params, param[k]) != 0) {
            fprintf(stderr, "demo: bad --param '%s' (NAME=INTEGER, a parameter of localizer %s, "
                            "in range)\n", param[k], loc->name);
            free(params);
            if (d.steps)
                fclose(d.steps);
            return 2;
        }
    o.loc = loc;
    o.params = params;
    colors_opt_resolve(&colors, sc.field, NULL);
    o.colors = &colors;
    o.max_steps = seconds > 0 ? (long)floor(seconds * sc.frame_hz) + 1 : -1;
    o.steps = d.steps;
    fin.d = &d;
    /* index of the last record: vision steps 0, every, 2 every, ... */
    probe = malloc(sizeof *probe);
    if (probe == NULL || sim_init(probe, &sc) != 0) {
        free(probe);
        free(params);
        fprintf(stderr, "demo: invalid scenario\n");
        return 1;
    }
    {
        long steps = (long)sim_step_count(probe);
        if (o.max_steps >= 0 && o.max_steps < steps)
            steps = o.max_steps;
        fin.last = (steps - 1) / every;
    }
    free(probe);
    o.hook = demo_final_hook;
    o.user = &fin;
    if (loc_b != NULL) {
        /* the first pass writes what vision saw; a stale cache must not be
         * read instead of rendering (the frame pictures need the frames) */
        snprintf(cache, sizeof cache, "%s/compare_obs.cache", out);
        remove(cache);
        o.obs_cache = cache;
    }
    printf("fieldloc demo: walk %s on field %s, camera %s, seed %llu, %.0f s at %.0f Hz%s\n",
           sc.name, sc.field->name, sc.camera->name, (unsigned long long)sc.seed,
           o.max_steps >= 0 ? (double)(o.max_steps - 1) / sc.frame_hz : sc.duration_s,
           sc.frame_hz, walk ? "" : " (fixtures/walks/NAME.walk)");
    printf("  every %ld%s step (%.1f Hz): render the frame at the true pose -> fl_vision_frame "
           "-> %s (odometry accumulated between);\n  start in total ignorance, prior "
           "own half; rendering on %d thread(s); pictures in %s\n",
           every, every == 1 ? "st" : every == 2 ? "nd" : every == 3 ? "rd" : "th",
           sc.frame_hz / (double)every,
           strcmp(loc->name, "fuzzy") != 0 ? loc->name : "fuzzy grid", lr_threads_default(), out);
    fflush(stdout);
    if (lr_walk_run(&sc, &o, &res, err, (int)sizeof err) != 0) {
        fprintf(stderr, "demo: %s\n", err);
        if (d.steps)
            fclose(d.steps);
        free(params);
        return 1;
    }
    free(params);
    if (d.steps)
        fclose(d.steps);
    o.steps = NULL;
    printf("  %ld frames in %.1f s (rendering %.1f s, vision + localizer %.2f ms per frame)\n",
           res.records, demo_now() - d.wall0, res.render_s,
           res.records ? 1000.0 * res.vision_grid_s / (double)res.records : 0.0);
    printf("# localizer: %u kidnaps detected, %u mode switches, %u obs used, %u deferred, "
           "%u empty resets\n",
           res.stats.kidnaps, res.stats.mode_switches, res.stats.obs_used, res.stats.obs_gated,
           res.stats.empty_resets);
    lr_walk_print_vdiag(stdout, &res);
    lr_walk_print_summary(stdout, &res);
    printf("final error %.0f mm %.1f deg\n", res.final_pos_err_mm, res.final_head_err_deg);
    snprintf(path, sizeof path, "%s/summary.txt", out);
    f = fopen(path, "w");
    if (f != NULL) {
        lr_walk_print_summary(f, &res);
        fprintf(f, "final error %.0f mm %.1f deg\n", res.final_pos_err_mm,
                res.final_head_err_deg);
        fclose(f);
    }
    k = 0;
    if (loc_b != NULL) {
        int i;
        k = demo_compare(&d, &sc, &o, loc->name, loc_b, cparam, n_cparam);
        remove(cache);
        for (i = 0; i < d.n_keep; i++)
            host_image_free(&d.keep[i].belief);
        free(d.keep);
    }
    printf("pictures: %d PPM%s in %s (demo_final, demo_kidnap, demo_tNNN, belief_final, "
           "frame_final%s), steps.txt, summary.txt\n",
           d.pictures, d.pngs ? " + PNG" : (png ? " (PNG not written)" : ""), out,
           loc_b != NULL ? ", compare_*" : "");
    return k == 0 ? 0 : 1;
}
