/*
 * host_tests/test_stream.c - suite `stream`: localizer input streams
 * (tools/loc/stream.h, docs/STREAM.md), the walk metrics per kidnap
 * (tools/loc/locrun.h lr_metrics_*) and added kidnaps (tools/world/sim.h
 * sim_scenario_set_kidnaps).
 *
 * Checks: a walk exported as a stream and replayed with the same localizer
 * gives byte-identical step lines and summary lines (feature level with
 * two kidnaps and a penalty placement; rendered frames through vision on
 * a short walk, odometry split into several predict calls per record;
 * the same stream again from the observation cache),
 * and the stream holds exactly the calls the localizer got;
 * malformed streams are refused with the line named; a kidnap from which
 * the filter does not recover before a told penalty placement is "never",
 * not the time to the placement; the median and worst over kidnaps; added
 * kidnaps leave the walk identical up to the first of them, keep their
 * times and targets as more are added, stay off penalties and on the
 * carpet.
 */
#include "test.h"
#include "loc/locrun.h"
#include "loc/stream.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#pragma weak render_frame

/* Lines of text starting with "step " or being summary lines (the "#
 * kidnap", "# penalty_recover_s", "# every record" lines and the value
 * lines), concatenated. */
static char *filter_lines(const char *text, int steps)
{
    size_t n = strlen(text);
    char *out = malloc(n + 1), *o = out;
    const char *p = text;
    if (out == NULL)
        return NULL;
    while (*p) {
        const char *e = strchr(p, '\n');
        size_t len = e ? (size_t)(e - p + 1) : strlen(p);
        int keep = steps ? !strncmp(p, "step ", 5) : strncmp(p, "step ", 5) != 0;
        if (keep) {
            memcpy(o, p, len);
            o += len;
        }
        p += len;
    }
    *o = '\0';
    return out;
}

static int count_prefix(const char *text, const char *prefix)
{
    int n = 0;
    size_t k = strlen(prefix);
    const char *p = text;
    while (p && *p) {
        if (!strncmp(p, prefix, k))
            n++;
        p = strchr(p, '\n');
        if (p)
            p++;
    }
    return n;
}

/* predict-call counter behind a localizer (the fuzzy grid), to check the
 * stream against the calls the localizer really got */
static fl_localizer_t counting;
static long n_predict, n_update, n_reset;
static void cnt_predict(void *s, int32_t dx, int32_t dy, fl_angle_t a)
{
    n_predict++;
    fl_localizer_fuzzy.predict(s, dx, dy, a);
}
static uint16_t cnt_update(void *s, const fl_obs_list_t *o, const fl_obs_view_t *v)
{
    n_update++;
    return fl_localizer_fuzzy.update(s, o, v);
}
static void cnt_reset(void *s, int32_t x, int32_t u, fl_angle_t h)
{
    n_reset++;
    fl_localizer_fuzzy.reset_penalty(s, x, u, h);
}

/* Simulate (stream and step lines to memory), replay, compare. */
static void roundtrip(const char *field, int frames, long steps, int kidnaps, int want_kidnaps,
                      int want_placement)
{
    static sim_scenario_t sc;
    lr_walk_opts_t o;
    lr_walk_result_t res, res2;
    char *sim_out = NULL, *rep_out = NULL, *stream = NULL, err[256], cache[128];
    size_t n1 = 0, n2 = 0, n3 = 0;
    FILE *fs, *fo, *fr, *in;
    ls_stream_t s;
    void *params;
    counting = fl_localizer_fuzzy;
    counting.predict = cnt_predict;
    counting.update = cnt_update;
    counting.reset_penalty = cnt_reset;
    n_predict = n_update = n_reset = 0;

    CHECK_EQ(sim_scenario_builtin(&sc, field), 0);
    sc.seed = 5;
    if (!frames) {
        /* a short walk with its own kidnap at 12 s and a placement at 20 s */
        CHECK(sc.n_events == 2 && sc.event[0].kind == SIM_EVENT_KIDNAP);
        sc.event[0].t_s = 12;
        sc.event[1].t_s = 20;
        sc.event[1].duration_s = 4;
        sc.duration_s = 30;
    }
    if (kidnaps >= 0)
        CHECK_EQ(sim_scenario_set_kidnaps(&sc, kidnaps), 0);
    params = lr_params_new(&counting);
    if (params == NULL)
        return;
    if (frames) {
        lr_params_frames(&counting, params);
        /* small enough that a record's odometry is split into several
         * predict calls: the stream must hold each */
        CHECK_EQ(lr_param_set(&counting, params, "odo_max_mm=6"), 0);
    }
    fs = open_memstream(&stream, &n1);
    fo = open_memstream(&sim_out, &n2);
    memset(&o, 0, sizeof o);
    o.frames = frames;
    o.every = 3;
    o.max_steps = steps;
    o.threads = 2;
    o.loc = &counting;
    o.params = params;
    o.steps = fo;
    o.stream = fs;
    if (frames) {
        snprintf(cache, sizeof cache, "/tmp/fieldloc_test_stream_%ld.obs", (long)getpid());
        remove(cache);
        o.obs_cache = cache;
    }
    CHECK_EQ(lr_walk_run(&sc, &o, &res, err, sizeof err), 0);
    lr_walk_print_summary(fo, &res);
    fclose(fs);
    fclose(fo);
    if (frames) {
        /* the observation cache's path writes the same stream */
        char *again = NULL;
        size_t n4 = 0;
        lr_walk_result_t res3;
        o.steps = NULL;
        o.stream = open_memstream(&again, &n4);
        CHECK_EQ(lr_walk_run(&sc, &o, &res3, err, sizeof err), 0);
        fclose(o.stream);
        CHECK(again != NULL && strcmp(again, stream) == 0);
        CHECK_EQ(res3.render_s, 0.0);   /* nothing rendered the second time */
        n_predict /= 2;                 /* the counts of one run */
        n_update /= 2;
        n_reset /= 2;
        free(again);
        remove(cache);
    }

    /* the stream holds exactly the calls made */
    CHECK_EQ(count_prefix(stream, "predict "), n_predict);
    CHECK_EQ(count_prefix(stream, "update "), n_update);
    CHECK_EQ(count_prefix(stream, "reset_penalty "), n_reset);
    CHECK_EQ(count_prefix(stream, "record "), res.records);
    if (frames)
        CHECK(n_predict > res.records);
    CHECK(n_update > 0);
    CHECK_EQ(n_reset > 0, want_placement);
    CHECK_EQ(count_prefix(stream, "kidnap "), want_kidnaps);
    CHECK_EQ(res.n_kidnaps, want_kidnaps);

    in = fmemopen(stream, strlen(stream), "r");
    CHECK(in != NULL);
    if (in == NULL)
        return;
    CHECK_EQ(ls_read(in, "mem", &s, err, sizeof err), 0);
    fclose(in);
    CHECK_EQ(s.frames, frames);
    CHECK_EQ(s.n_rec, res.records);
    fr = open_memstream(&rep_out, &n3);
    CHECK_EQ(ls_replay(&s, &fl_localizer_fuzzy, params, fr, 0, &res2, err, sizeof err), 0);
    lr_walk_print_summary(fr, &res2);
    fclose(fr);
    {
        char *a = filter_lines(sim_out, 1), *b = filter_lines(rep_out, 1);
        char *c = filter_lines(sim_out, 0), *d = filter_lines(rep_out, 0);
        CHECK(a && b && c && d);
        if (a && b && c && d) {
            CHECK(strlen(a) > 0);
            CHECK(strcmp(a, b) == 0);
            CHECK(strcmp(c, d) == 0);
            CHECK(strstr(c, "kidnap_recover_s ") != NULL);
        }
        free(a);
        free(b);
        free(c);
        free(d);
    }
    CHECK_EQ(res2.n_kidnaps, res.n_kidnaps);
    t_info("stream %s %s: %ld records, %zu bytes, %ld predict calls, %d kidnaps", field,
           frames ? "frames" : "features", res.records, strlen(stream), n_predict,
           res.n_kidnaps);
    ls_free(&s);
    free(params);
    free(stream);
    free(sim_out);
    free(rep_out);
}

static void test_replay_features(void)
{
    /* uva2013, 30 s: kidnaps at 6 s (added) and 12 s, penalty placement
     * at 20 s */
    roundtrip("uva2013", 0, -1, 2, 2, 1);
}

static void test_replay_frames(void)
{
    if (render_frame == NULL) {
        t_info("stream.replay_frames: renderer not linked, skipped");
        return;
    }
    /* aibo2004 (low-resolution camera: params_adapt), rendered, 5 records */
    roundtrip("aibo2004", 1, 15, -1, 0, 0);
}

/* ---- malformed streams ----------------------------------------------------- */

#define HDR "fieldloc-stream 1\nfield spl2013\ncamera nao4-top-320\nmode features\n" \
            "every 1\nframe_hz 30\nprior_half -1\n"
#define REC0 "record 0 0 0 -3500 -2000 8192 45.00\npredict 0 0 0\n"

static void expect_bad(const char *text, int line, const char *why)
{
    char err[256], want[64];
    ls_stream_t s;
    FILE *in = fmemopen((void *)text, strlen(text), "r");
    if (in == NULL) {
        CHECK(0);
        return;
    }
    snprintf(want, sizeof want, "t: line %d: ", line);
    if (ls_read(in, "t", &s, err, sizeof err) == 0) {
        t_fail_msg(__FILE__, __LINE__, "accepted: %s", text);
        ls_free(&s);
    } else if (strncmp(err, want, strlen(want)) != 0 || strstr(err, why) == NULL) {
        t_fail_msg(__FILE__, __LINE__, "message \"%s\", want \"%s...%s\"", err, want, why);
    } else {
        CHECK(1);
    }
    CHECK_EQ(s.n_rec, 0);
    fclose(in);
}

static void test_malformed(void)
{
    char err[256];
    ls_stream_t s;
    const char *good = HDR REC0 "update 1 0 noview\nobs L 0 0 0 1200 -300 5000 1 200 -1 -1\n"
                                "record 1 1 33 -3500 -2000 8192\nkidnap 1 33 0 0 0\n"
                                "predict 3 0 -7\nupdate 0 0 view 1 -3000 3000 300 2000\nend 2\n";
    FILE *in = fmemopen((void *)good, strlen(good), "r");
    CHECK(in != NULL);
    if (in != NULL) {
        CHECK_EQ(ls_read(in, "t", &s, err, sizeof err), 0);
        fclose(in);
        CHECK_EQ(s.n_rec, 2);
        CHECK_EQ(s.n_op, 4);
        CHECK_EQ(s.n_obs, 1);
        CHECK_EQ(s.n_ev, 1);
        CHECK_EQ(s.obs[0].kind, FL_LM_L);
        CHECK_EQ(s.obs[0].bearing, -300);
        CHECK_EQ(s.op[3].view.far_mm, 2000);
        CHECK_EQ(s.op[2].angle, -7);
        CHECK_EQ(s.ev[0].bits, SIM_EV_KIDNAP);
        ls_free(&s);
    }
    expect_bad("fieldloc-stream 2\n", 1, "version 2");
    expect_bad("hello\n", 1, "not a fieldloc stream");
    expect_bad("", 1, "empty");
    expect_bad(HDR "colour 3\n", 8, "unknown keyword 'colour'");
    expect_bad("fieldloc-stream 1\nfield spl2013\n" REC0, 3, "header incomplete");
    expect_bad(HDR "field spl2013\n", 8, "twice");
    expect_bad(HDR "field nowhere\n" REC0, 8, "twice");
    expect_bad("fieldloc-stream 1\nfield nowhere\n", 2, "unknown field");
    expect_bad(HDR "every 0\n", 8, "every");
    expect_bad(HDR REC0 "predict 1 2\n", 10, "three integers");
    expect_bad(HDR REC0 "predict 1 2 40000\n", 10, "'40000' is not an integer");
    expect_bad(HDR REC0 "predict 1.5 2 3\n", 10, "'1.5'");
    expect_bad(HDR "record 1 0 0 0 0 0\n", 8, "out of sequence");
    expect_bad(HDR REC0 "record 1 0 0 0 0 0\n", 10, "not after");
    expect_bad(HDR "predict 0 0 0\n", 8, "before the first record");
    expect_bad(HDR REC0 "obs L 0 0 0 1 2 3 1 200 -1 -1\n", 10, "outside an update");
    expect_bad(HDR REC0 "update 1 0 noview\nobs Q 0 0 0 1 2 3 1 200 -1 -1\n", 11, "kind 'Q'");
    expect_bad(HDR REC0 "update 1 0 noview\nobs L 0 0 0 1 2 3 1 256 -1 -1\n", 11, "'256'");
    expect_bad(HDR REC0 "update 2 0 noview\nobs L 0 0 0 1 2 3 1 200 -1 -1\npredict 0 0 0\n", 12,
               "where an obs line is due");
    expect_bad(HDR REC0 "update 1 0 noview\n", 11, "inside an update");
    expect_bad(HDR REC0 "update 99 0 noview\n", 10, "'99'");
    expect_bad(HDR REC0 "update 0 0 view 1 2\n", 10, "wrong number");
    expect_bad(HDR REC0 "update 0 0 sideways\n", 10, "noview | view");
    expect_bad(HDR REC0 "kidnap 0 0 1 2 3\n", 10, "after a call");
    expect_bad(HDR "record 0 5 0 0 0 0\nkidnap 6 0 1 2 3\n", 9, "after its record");
    expect_bad(HDR REC0, 10, "without its end line");
    expect_bad(HDR REC0 "end 3\n", 10, "number of records");
    expect_bad(HDR REC0 "end 1\npredict 0 0 0\n", 11, "after the end line");
}

/* ---- metrics per kidnap ---------------------------------------------------- */

/* 10 Hz records, truth fixed at (1000, 500, 0); the estimate right except
 * in the given windows [bad_from, bad_to) (seconds) where it is 2 m off. */
static void feed(lr_metrics_t *m, double t0, double t1, const double *bad, int n_bad)
{
    fl_loc_estimate_t e;
    double t;
    int k;
    for (t = t0; t < t1 - 1e-9; t += 0.1) {
        int wrong = 0;
        for (k = 0; k < n_bad; k++)
            wrong |= t >= bad[2 * k] - 1e-9 && t < bad[2 * k + 1] - 1e-9;
        memset(&e, 0, sizeof e);
        e.x_mm = wrong ? 3000 : 1000;
        e.y_mm = 500;
        CHECK(lr_metrics_record(m, t, &e, 1000, 500, 0, NULL, NULL) >= 0);
    }
}

static void test_kidnap_metrics(void)
{
    lr_metrics_t m;
    lr_walk_result_t r;
    /* asymmetric field: a wrong pose stays wrong (no modulo symmetry) */
    {
        /* kidnap at 10 s, never right by itself, told at 20 s (placement),
         * right from then on: "never", not 10 s */
        static const double bad[2] = {10, 20};
        CHECK_EQ(lr_metrics_init(&m, 0), 0);
        feed(&m, 0, 10, bad, 1);
        lr_metrics_event(&m, SIM_EV_KIDNAP, 10.0);
        feed(&m, 10, 20, bad, 1);
        lr_metrics_event(&m, SIM_EV_PENALIZED, 20.0);
        feed(&m, 20, 30, bad, 1);
        memset(&r, 0, sizeof r);
        lr_metrics_finish(&m, &r);
        CHECK_EQ(r.n_kidnaps, 1);
        CHECK(isinf(r.kidnap[0].recover_s));
        CHECK_EQ(r.kidnap[0].end, LR_KIDNAP_TOLD);
        CHECK(fabs(r.kidnap[0].end_s - 20.0) < 1e-9);
        CHECK(isinf(r.kidnap_recover_s));
        CHECK(isinf(r.kidnap_recover_worst_s));
        CHECK(fabs(r.penalty_recover_s) < 1e-9);
        /* the excluded window ends at the placement: 0-10 s and 20-30 s
         * count (the last 1 s hold is not needed for the RMSE) */
        CHECK_EQ(r.used, 200);
        CHECK(fabs(r.pos_rmse_mm) < 1e-9);
        lr_metrics_free(&m);
    }
    {
        /* three kidnaps: recovered after 1.5 s and 0.5 s, and one that is
         * still wrong when the next kidnap comes; plus the run's end */
        static const double bad[6] = {10, 11.5, 20, 30, 30, 30.5};
        char *txt = NULL;
        size_t len = 0;
        FILE *f;
        CHECK_EQ(lr_metrics_init(&m, 0), 0);
        feed(&m, 0, 10, bad, 3);
        lr_metrics_event(&m, SIM_EV_KIDNAP, 10.0);
        feed(&m, 10, 20, bad, 3);
        lr_metrics_event(&m, SIM_EV_KIDNAP, 20.0);
        feed(&m, 20, 30, bad, 3);
        lr_metrics_event(&m, SIM_EV_KIDNAP, 30.0);
        feed(&m, 30, 40, bad, 3);
        memset(&r, 0, sizeof r);
        lr_metrics_finish(&m, &r);
        CHECK_EQ(r.n_kidnaps, 3);
        CHECK(fabs(r.kidnap[0].recover_s - 1.5) < 1e-6);
        CHECK(isinf(r.kidnap[1].recover_s));
        CHECK_EQ(r.kidnap[1].end, LR_KIDNAP_NEXT);
        CHECK(fabs(r.kidnap[2].recover_s - 0.5) < 1e-6);
        CHECK(fabs(r.kidnap_recover_s - 1.5) < 1e-6);   /* median of 0.5 1.5 inf */
        CHECK(isinf(r.kidnap_recover_worst_s));
        f = open_memstream(&txt, &len);
        lr_walk_print_summary(f, &r);
        fclose(f);
        CHECK(strstr(txt, "# kidnap 1 at 10.00 recovered after 1.50 s\n") != NULL);
        CHECK(strstr(txt, "# kidnap 2 at 20.00 never recovered before the next kidnap at "
                          "30.00\n") != NULL);
        CHECK(strstr(txt, "# kidnap_recover_worst_s inf\n") != NULL);
        CHECK(strstr(txt, "\nkidnap_recover_s 1.50\n") != NULL);
        free(txt);
        lr_metrics_free(&m);
    }
    {
        /* two kidnaps: the median is the mean of the two */
        static const double bad[4] = {10, 11, 20, 23};
        CHECK_EQ(lr_metrics_init(&m, 0), 0);
        feed(&m, 0, 10, bad, 2);
        lr_metrics_event(&m, SIM_EV_KIDNAP, 10.0);
        feed(&m, 10, 20, bad, 2);
        lr_metrics_event(&m, SIM_EV_KIDNAP, 20.0);
        feed(&m, 20, 30, bad, 2);
        memset(&r, 0, sizeof r);
        lr_metrics_finish(&m, &r);
        CHECK(fabs(r.kidnap_recover_s - 2.0) < 1e-6);
        CHECK(fabs(r.kidnap_recover_worst_s - 3.0) < 1e-6);
        lr_metrics_free(&m);
    }
}

/* ---- added kidnaps ----------------------------------------------------------- */

static void test_added_kidnaps(void)
{
    static sim_scenario_t a, b, c;
    static sim_t sa, sb;
    static sim_step_t xa, xb;
    int j, k, nk = 0;
    double first_added = -1, hx, hy;
    CHECK_EQ(sim_scenario_builtin(&a, "spl2013"), 0);
    b = a;
    CHECK_EQ(sim_scenario_set_kidnaps(&b, 1), 0);   /* its own count: unchanged */
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    CHECK_EQ(sim_scenario_set_kidnaps(&b, 0), 0);
    for (j = 0; j < b.n_events; j++)
        CHECK(b.event[j].kind != SIM_EVENT_KIDNAP);
    CHECK(strcmp(b.name, "spl2013+k0") == 0);
    CHECK_EQ(sim_scenario_set_kidnaps(&b, SIM_MAX_EVENTS + 1), -1);

    b = a;
    c = a;
    CHECK_EQ(sim_scenario_set_kidnaps(&b, 4), 0);
    CHECK_EQ(sim_scenario_set_kidnaps(&c, 6), 0);
    hx = a.field->length_mm / 2.0 + a.field->border_mm;
    hy = a.field->width_mm / 2.0 + a.field->border_mm;
    for (j = 0; j < b.n_events; j++) {
        const sim_event_t *e = &b.event[j];
        int in_c = 0;
        if (j > 0)
            CHECK(e->t_s >= b.event[j - 1].t_s);
        if (e->kind != SIM_EVENT_KIDNAP)
            continue;
        nk++;
        CHECK(fabs(e->x_mm) <= hx && fabs(e->y_mm) <= hy);
        for (k = 0; k < b.n_events; k++) {
            const sim_event_t *o = &b.event[k];
            if (k == j)
                continue;
            if (o->kind == SIM_EVENT_PENALTY)
                CHECK(e->t_s <= o->t_s - 2.0 || e->t_s >= o->t_s + o->duration_s + 2.0);
            else
                CHECK(fabs(e->t_s - o->t_s) >= 2.0);
        }
        /* the same kidnap (time and target) with more kidnaps added */
        for (k = 0; k < c.n_events; k++)
            in_c |= c.event[k].kind == SIM_EVENT_KIDNAP && c.event[k].t_s == e->t_s &&
                    c.event[k].x_mm == e->x_mm && c.event[k].y_mm == e->y_mm &&
                    c.event[k].heading_deg == e->heading_deg;
        CHECK(in_c);
        if (e->t_s != a.event[0].t_s && (first_added < 0 || e->t_s < first_added))
            first_added = e->t_s;
    }
    CHECK_EQ(nk, 4);
    CHECK(first_added > 5.0);
    /* the walk is the same up to the first added kidnap */
    CHECK_EQ(sim_init(&sa, &a), 0);
    CHECK_EQ(sim_init(&sb, &b), 0);
    for (k = 0; sim_step(&sa, &xa) && sim_step(&sb, &xb); k++) {
        if (xb.events & SIM_EV_KIDNAP) {
            CHECK(fabs(xb.t_ms / 1000.0 - first_added) < 0.05);
            break;
        }
        if (xa.x_mm != xb.x_mm || xa.odo_dx_mm != xb.odo_dx_mm || xa.obs.n != xb.obs.n ||
            (xa.obs.n > 0 && xa.obs.obs[0].range_mm != xb.obs.obs[0].range_mm)) {
            t_fail_msg(__FILE__, __LINE__, "walks differ at step %d", k);
            break;
        }
    }
    CHECK(k > 100);
}

void suite_stream(void)
{
    t_run("stream.replay_features", test_replay_features);
    t_run("stream.replay_frames", test_replay_frames);
    t_run("stream.malformed", test_malformed);
    t_run("stream.kidnap_metrics", test_kidnap_metrics);
    t_run("stream.added_kidnaps", test_added_kidnaps);
}
