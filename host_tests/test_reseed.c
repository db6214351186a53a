/*
 * host_tests/test_reseed.c - re-seeding a localizer from an observer's
 * report (obs.h fl_obs_report_t, localizer.h fl_loc_reseed, spread_mm), for
 * every localizer of the catalogue: a wrong belief corrected by one report
 * at the truth, tracking afterwards on a feature walk; the spread query
 * wide under ignorance and narrow after convergence; bad reports refused
 * and counted with the state unchanged and valid.
 */
#include "test.h"
#include "fieldloc/localizer.h"
#include "fieldloc/fuzzy.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void good_report(fl_obs_report_t *r, int32_t x, int32_t y)
{
    memset(r, 0, sizeof *r);
    r->x_mm = x;
    r->y_mm = y;
    r->sd_mm = FL_OBS_REPORT_SD_MM;
    r->confidence = 255;
    r->team = 1;
    r->player = 2;
    r->age_ms = 40;
}

static double dist(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    return hypot((double)ax - bx, (double)ay - by);
}

/* One frame of the walk through the interface. */
static void frame(const fl_localizer_t *loc, void *st, const sim_step_t *s, fl_loc_estimate_t *e)
{
    fl_loc_predict(loc, st, s->odo_dx_mm, s->odo_dy_mm, s->odo_dtheta);
    fl_loc_update(loc, st, &s->obs, NULL);
    CHECK(fl_loc_estimate(loc, st, e));
}

/* Converge on the spl2013 feature walk, then a wrong belief 2.5 m away
 * (a told pose with the right heading: a kidnap the filter believes), one
 * report at the truth, and 150 more frames. */
static void test_correct(void)
{
    static sim_t sim;
    static sim_step_t s;
    uint16_t li;
    for (li = 0; li < fl_localizer_count(); li++) {
        const fl_localizer_t *loc = fl_localizer_get(li);
        sim_scenario_t sc;
        void *st = malloc(loc->state_size);
        fl_loc_estimate_t e;
        fl_loc_stats_t ls;
        fl_obs_report_t r;
        uint32_t k, spread0, spread1, spread2, spread3, far = 0, h = t_hash_init();
        char label[64];
        double err, worst = 0, sum = 0;
        int32_t wx, wy;
        CHECK(st != NULL);
        if (st == NULL)
            return;
        CHECK_EQ(sim_scenario_builtin(&sc, "spl2013"), 0);
        CHECK_EQ(sim_init(&sim, &sc), 0);
        CHECK_EQ(fl_loc_init(loc, st, sc.field, NULL), FL_OK);
        spread0 = fl_loc_spread_mm(loc, st);
        CHECK(spread0 > 2500u && spread0 < 5000u);
        CHECK(fl_loc_spread_beyond(loc, st, FL_LOC_RESEED_SPREAD_MM));
        loc->set_prior_half(st, -1);
        for (k = 0; k < 300 && sim_step(&sim, &s); k++)
            frame(loc, st, &s, &e);
        spread1 = fl_loc_spread_mm(loc, st);
        err = dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm);
        t_info("%s converged: err %.0f mm spread %u (ignorance %u)", loc->name, err, spread1,
               spread0);
        CHECK(err < 500);
        CHECK(spread1 < FL_LOC_RESEED_SPREAD_MM);
        CHECK(!fl_loc_spread_beyond(loc, st, FL_LOC_RESEED_SPREAD_MM));
        /* the wrong belief: 2.5 m off, toward the field's centre */
        wx = s.x_mm > 0 ? s.x_mm - 2000 : s.x_mm + 2000;
        wy = s.y_mm > 0 ? s.y_mm - 1500 : s.y_mm + 1500;
        loc->reset_pose(st, wx, wy, s.heading, 200, 1820);
        CHECK(fl_loc_estimate(loc, st, &e));
        CHECK(dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm) > 2000);
        good_report(&r, s.x_mm, s.y_mm);
        CHECK_EQ(fl_loc_reseed(loc, st, &r), FL_OK);
        CHECK(fl_loc_check(loc, st));
        spread2 = fl_loc_spread_mm(loc, st);
        CHECK(fl_loc_estimate(loc, st, &e));
        err = dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm);
        t_info("%s re-seeded: err %.0f mm spread %u", loc->name, err, spread2);
        CHECK(err < 2 * FL_OBS_REPORT_SD_MM);
        CHECK(spread2 < 3u * FL_OBS_REPORT_SD_MM && spread2 > FL_OBS_REPORT_SD_MM / 2u);
        for (k = 0; k < 150 && sim_step(&sim, &s); k++) {
            frame(loc, st, &s, &e);
            h = t_hash_i32(h, e.x_mm);
            h = t_hash_i32(h, e.y_mm);
            h = t_hash_i32(h, e.heading);
            err = dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm);
            sum += err;
            if (err > worst)
                worst = err;
            far += err > FL_LOC_GOOD_MM;
        }
        spread3 = fl_loc_spread_mm(loc, st);
        h = t_hash_i32(h, (int32_t)spread2);
        h = t_hash_i32(h, (int32_t)spread3);
        /* the same on every target (make cross-test compares digests) */
        snprintf(label, sizeof label, "reseed.%s", loc->name);
        t_digest(label, h);
        t_info("%s after %u frames: mean err %.0f mm, worst %.0f, %u beyond %d mm, spread %u",
               loc->name, k, sum / k, worst, far, FL_LOC_GOOD_MM, spread3);
        CHECK_EQ(k, 150u);
        CHECK(sum / k < 300);
        CHECK(far < 15u);
        CHECK(fl_loc_check(loc, st));
        loc->stats(st, &ls);
        CHECK_EQ(ls.reseeds, 1u);
        CHECK_EQ(ls.reseeds_refused, 0u);
        if (loc == &fl_localizer_fuzzy)   /* the belief excluded the foot */
            CHECK_EQ(((const fl_fuzzy_t *)st)->stats.reseed_replaced, 1u);
        free(st);
    }
}

/* From total ignorance the report gives the position; the heading is
 * unknown (any heading), and observations then find it.  At three places
 * of the walk (on a symmetric field: the mirror must not win).  The
 * unscented filter's 12 particles, 30 deg apart, do not always find it
 * (a particle that converges on a wrong heading is far from the foot a few
 * frames later): at least 2 of the 3; the others every time. */
static void test_from_ignorance(void)
{
    static sim_t sim;
    static sim_step_t s;
    uint16_t li;
    int start, good[8] = {0};
    for (li = 0; li < fl_localizer_count() && li < 8; li++)
        for (start = 0; start < 3; start++) {
            const fl_localizer_t *loc = fl_localizer_get(li);
            sim_scenario_t sc;
            void *st = malloc(loc->state_size);
            fl_loc_estimate_t e;
            fl_obs_report_t r;
            uint32_t k;
            uint16_t i, n;
            double err;
            CHECK(st != NULL);
            if (st == NULL)
                return;
            CHECK_EQ(sim_scenario_builtin(&sc, "spl2013"), 0);
            CHECK_EQ(sim_init(&sim, &sc), 0);
            CHECK_EQ(fl_loc_init(loc, st, sc.field, NULL), FL_OK);
            for (k = 0; k <= (uint32_t)start * 200u; k++)
                CHECK(sim_step(&sim, &s));
            good_report(&r, s.x_mm, s.y_mm);
            CHECK_EQ(fl_loc_reseed(loc, st, &r), FL_OK);
            CHECK(fl_loc_check(loc, st));
            CHECK(fl_loc_spread_mm(loc, st) < 3u * FL_OBS_REPORT_SD_MM);
            /* every sample within 4.5 sd (the sampler's tail) of the foot */
            n = loc->belief_samples(st);
            for (i = 0; i < n; i++) {
                fl_loc_sample_t p;
                CHECK(loc->belief_sample(st, i, &p));
                CHECK(dist(p.x_mm, p.y_mm, s.x_mm, s.y_mm) < 4.5 * 1.42 * FL_OBS_REPORT_SD_MM);
            }
            for (k = 0; k < 150 && sim_step(&sim, &s); k++)
                frame(loc, st, &s, &e);
            err = dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm);
            t_info("%s from ignorance at step %d, 150 frames later: err %.0f mm, heading err %d",
                   loc->name, start * 200, err, (int)fl_angle_sub(e.heading, s.heading));
            good[li] += err < FL_LOC_GOOD_MM;
            CHECK(fl_loc_check(loc, st));
            free(st);
        }
    for (li = 0; li < fl_localizer_count() && li < 8; li++)
        CHECK(good[li] >= (fl_localizer_get(li) == &fl_localizer_upf ? 2 : 3));
}

/* Bad reports and an uninitialized state: refused, counted, the state as it
 * was (same estimate, possibility and spread) and valid. */
static void test_refused(void)
{
    uint16_t li;
    const fl_field_t *field = fl_field_find("spl2013");
    int32_t hx = fl_field_carpet_half_x_mm(field), hy = fl_field_carpet_half_y_mm(field);
    for (li = 0; li < fl_localizer_count(); li++) {
        const fl_localizer_t *loc = fl_localizer_get(li);
        void *st = malloc(loc->state_size);
        fl_loc_estimate_t e0, e1;
        fl_loc_stats_t ls;
        fl_obs_report_t r;
        uint32_t sp0, p0;
        int j, refused = 0;
        CHECK(st != NULL);
        if (st == NULL)
            return;
        memset(st, 0, loc->state_size);
        good_report(&r, 0, 0);
        CHECK_EQ(fl_loc_reseed(loc, st, &r), FL_ERR_STATE);
        CHECK_EQ(fl_loc_spread_mm(loc, st), UINT32_MAX);
        CHECK(!fl_loc_spread_beyond(loc, st, 0));
        CHECK_EQ(fl_loc_reseed(NULL, st, &r), FL_ERR_NULL);
        CHECK_EQ(fl_loc_reseed(loc, NULL, &r), FL_ERR_NULL);
        CHECK_EQ(fl_loc_reseed(loc, st, NULL), FL_ERR_NULL);
        CHECK_EQ(fl_loc_init(loc, st, field, NULL), FL_OK);
        loc->reset_pose(st, 1200, -800, 3000, 300, 2000);
        CHECK(fl_loc_estimate(loc, st, &e0));
        CHECK(fl_loc_estimate(loc, st, &e0));
        sp0 = fl_loc_spread_mm(loc, st);
        p0 = loc->possibility_q16(st, 1200, -800, 3000);
        for (j = 0; j < 10; j++) {
            fl_status_t want = FL_ERR_RANGE;
            good_report(&r, 1000, 500);
            switch (j) {
            case 0: r.sd_mm = 0; break;
            case 1: r.sd_mm = -125; break;
            case 2: r.sd_mm = FL_OBS_REPORT_SD_MAX_MM + 1; break;
            case 3: r.x_mm = hx + 1; break;
            case 4: r.y_mm = -hy - 1; break;
            case 5: r.x_mm = INT32_MIN; r.y_mm = INT32_MAX; break;
            case 6: r.confidence = 0; break;
            case 7: r.age_ms = -1; break;
            case 8: r.age_ms = FL_OBS_REPORT_MAX_AGE_MS + 1; want = FL_ERR_STALE; break;
            default: r.sd_mm = INT32_MAX; break;
            }
            CHECK_EQ(fl_loc_reseed(loc, st, &r), want);
            refused++;
        }
        CHECK(fl_loc_check(loc, st));
        CHECK(fl_loc_estimate(loc, st, &e1));
        CHECK(memcmp(&e0, &e1, sizeof e0) == 0);
        CHECK_EQ(fl_loc_spread_mm(loc, st), sp0);
        CHECK_EQ(loc->possibility_q16(st, 1200, -800, 3000), p0);
        loc->stats(st, &ls);
        CHECK_EQ(ls.reseeds_refused, (uint32_t)refused);
        CHECK_EQ(ls.reseeds, 0u);
        /* the limits themselves are accepted */
        good_report(&r, hx, -hy);
        r.age_ms = FL_OBS_REPORT_MAX_AGE_MS;
        r.sd_mm = FL_OBS_REPORT_SD_MIN_MM;
        CHECK_EQ(fl_loc_reseed(loc, st, &r), FL_OK);
        CHECK(fl_loc_check(loc, st));
        good_report(&r, -hx, hy);
        r.sd_mm = FL_OBS_REPORT_SD_MAX_MM;
        CHECK_EQ(fl_loc_reseed(loc, st, &r), FL_OK);
        CHECK(fl_loc_check(loc, st));
        loc->stats(st, &ls);
        CHECK_EQ(ls.reseeds, 2u);
        free(st);
    }
    CHECK(strcmp(fl_status_str(FL_ERR_STALE), fl_status_str(FL_ERR_RANGE)) != 0);
    CHECK(strcmp(fl_status_str(FL_ERR_STATE), "unknown status") != 0);
}

/* The fuzzy grid's intersection: a report that the belief allows keeps
 * the belief where the disc allows it (headings kept), nothing beyond 3 sd
 * of the foot, and replaces nothing. */
static void test_fuzzy_intersection(void)
{
    fl_fuzzy_t *g = malloc(sizeof *g);
    fl_fuzzy_estimate_t e;
    fl_obs_report_t r;
    CHECK(g != NULL);
    if (g == NULL)
        return;
    CHECK_EQ(fl_fuzzy_init(g, fl_field_find("spl2013"), NULL), FL_OK);
    fl_fuzzy_reset_pose(g, 1000, 500, 0, 500, 1820);
    CHECK(fl_fuzzy_possibility_q16(g, 750, 150, 0) > 0u);
    CHECK(fl_fuzzy_possibility_q16(g, 1300, 500, 0) > 0u);
    good_report(&r, 1100, 500);
    CHECK_EQ(fl_fuzzy_reseed(g, &r), FL_OK);
    CHECK(fl_fuzzy_check(g));
    CHECK_EQ(g->stats.reseeds, 1u);
    CHECK_EQ(g->stats.reseed_replaced, 0u);
    /* its cell's content about 425 mm from the foot: beyond 3 sd */
    CHECK_EQ(fl_fuzzy_possibility_q16(g, 750, 150, 0), 0u);
    /* 200 mm from the foot and 300 from the told pose: both allow it */
    CHECK(fl_fuzzy_possibility_q16(g, 1300, 500, 0) > 0u);
    /* headings kept: the told heading's opposite is still impossible */
    CHECK_EQ(fl_fuzzy_possibility_q16(g, 1100, 500, FL_ANGLE_180), 0u);
    CHECK(fl_fuzzy_estimate(g, &e));
    t_info("fuzzy intersection: est (%d, %d) heading %d spread %u", (int)e.x_mm, (int)e.y_mm,
           (int)e.heading, fl_fuzzy_spread_mm(g));
    CHECK(dist(e.x_mm, e.y_mm, 1100, 500) < FL_OBS_REPORT_SD_MM);
    CHECK(abs((int)e.heading) < 910);
    CHECK(fl_fuzzy_spread_mm(g) < 2u * FL_OBS_REPORT_SD_MM);
    free(g);
}

void suite_reseed(void)
{
    t_run("reseed.correct", test_correct);
    t_run("reseed.from_ignorance", test_from_ignorance);
    t_run("reseed.refused", test_refused);
    t_run("reseed.fuzzy_intersection", test_fuzzy_intersection);
}
