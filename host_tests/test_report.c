/*
 * host_tests/test_report.c - observer reports (report.h): the coach's
 * assignment against brute force and against greedy nearest; the player's
 * pick and its refusals; the per-frame step on every localizer (a spread
 * belief re-seeded near the report, a converged one and a refused report
 * leaving the state byte for byte as it was); the message's round trip,
 * its refusals and its bytes (a digest compared across targets).
 */
#include "test.h"
#include "fieldloc/report.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- helpers ------------------------------------------------------------ */

static uint32_t rng_state;

static uint32_t rnd(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return rng_state >> 8;
}

/* uniform in [0, 1) */
static double urand(void)
{
    return (double)(rnd() & 0xFFFFFFu) / 16777216.0;
}

static double gauss(void)
{
    double a = urand(), b = urand();
    return sqrt(-2.0 * log(a + 1e-12)) * cos(2.0 * 3.14159265358979 * b);
}

static fl_obs_report_t rep(int32_t x, int32_t y, uint8_t team, uint8_t player)
{
    fl_obs_report_t r;
    memset(&r, 0, sizeof r);
    r.x_mm = x;
    r.y_mm = y;
    r.sd_mm = FL_OBS_REPORT_SD_MM;
    r.confidence = 200;
    r.team = team;
    r.player = player;
    r.age_ms = 40;
    return r;
}

static fl_report_claim_t claim(int32_t x, int32_t y, uint32_t spread, uint8_t team, uint8_t player)
{
    fl_report_claim_t c;
    memset(&c, 0, sizeof c);
    c.x_mm = x;
    c.y_mm = y;
    c.spread_mm = spread;
    c.team = team;
    c.player = player;
    return c;
}

/* ---- brute force reference ------------------------------------------------ */

/* Every one-to-one partial matching of nr reports to nc claims (claims
 * sorted by number), the least by (sum of costs with the gate for an
 * unmatched report, then the sequence of ranks). */
typedef struct {
    uint64_t cost[FL_REPORT_MAX][FL_REPORT_MAX_PLAYERS];
    uint32_t gate;
    size_t nr, nc;
    int cur[FL_REPORT_MAX], best[FL_REPORT_MAX];
    uint64_t best_cost;
    bool used[FL_REPORT_MAX_PLAYERS];
} brute_t;

static bool ranks_less(const int *a, const int *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (a[i] != b[i])
            return a[i] < b[i];
    return false;
}

static void brute(brute_t *b, size_t i, uint64_t sum)
{
    size_t j;
    if (i == b->nr) {
        if (sum < b->best_cost || (sum == b->best_cost && ranks_less(b->cur, b->best, b->nr))) {
            b->best_cost = sum;
            memcpy(b->best, b->cur, sizeof b->cur);
        }
        return;
    }
    for (j = 0; j < b->nc; j++) {
        if (b->used[j] || b->cost[i][j] > b->gate)
            continue;
        b->used[j] = true;
        b->cur[i] = (int)j;
        brute(b, i + 1, sum + b->cost[i][j]);
        b->used[j] = false;
    }
    b->cur[i] = (int)b->nc;   /* unmatched ranks after every claim */
    brute(b, i + 1, sum + b->gate);
}

/* Random small cases, one team (and distractors of the other team): the
 * assignment's total equals brute force's least and its matching is the
 * one the stated tie rule picks.  Positions on a coarse grid so that ties
 * happen. */
static void test_assign_vs_brute(void)
{
    const fl_field_t *field = fl_field_find("spl2013");
    int trial, ties = 0, gated = 0;
    rng_state = 12345u;
    for (trial = 0; trial < 3000; trial++) {
        fl_obs_report_t r[FL_REPORT_MAX];
        fl_report_claim_t c[2 * FL_REPORT_MAX_PLAYERS];
        fl_report_stats_t st;
        static brute_t b;
        size_t nr = 1 + rnd() % 6, nc = 1 + rnd() % 5, nother = rnd() % 3, i, j, k;
        uint32_t gate = trial % 3 == 0 ? 0 : 256u * (1u + rnd() % 20u);
        int coarse = trial % 2;
        uint64_t total = 0;
        memset(&st, 0, sizeof st);
        for (i = 0; i < nr + nother; i++) {
            int32_t x = coarse ? (int32_t)(rnd() % 5) * 500 - 1000 : (int32_t)(rnd() % 6000) - 3000;
            int32_t y = coarse ? (int32_t)(rnd() % 3) * 500 - 500 : (int32_t)(rnd() % 4000) - 2000;
            r[i] = rep(x, y, i < nr ? FL_COLOR_RED : FL_COLOR_BLUE, (uint8_t)(rnd() % 4));
        }
        /* claim numbers: a random distinct subset of 1..9, in random order */
        for (j = 0; j < nc; j++) {
            uint8_t num;
            bool dup;
            do {
                num = (uint8_t)(1 + rnd() % 9);
                dup = false;
                for (k = 0; k < j; k++)
                    dup = dup || c[k].player == num;
            } while (dup);
            {   /* one draw per statement: argument order is unspecified */
                int32_t x = coarse ? (int32_t)(rnd() % 5) * 500 - 1000 : (int32_t)(rnd() % 6000) - 3000;
                int32_t y = coarse ? (int32_t)(rnd() % 3) * 500 - 500 : (int32_t)(rnd() % 4000) - 2000;
                uint32_t sp = coarse ? 400u : 100u + rnd() % 2000u;
                c[j] = claim(x, y, sp, FL_COLOR_RED, num);
            }
        }
        CHECK_EQ(fl_report_assign(r, nr + nother, c, nc, field, gate, &st), FL_OK);
        /* the reference, claims in number order */
        memset(&b, 0, sizeof b);
        b.gate = gate ? gate : FL_REPORT_GATE_Q8;
        b.nr = nr;
        b.nc = nc;
        b.best_cost = UINT64_MAX;
        {
            size_t order[FL_REPORT_MAX_PLAYERS];
            for (j = 0; j < nc; j++)
                order[j] = j;
            for (j = 1; j < nc; j++)
                for (k = j; k > 0 && c[order[k - 1]].player > c[order[k]].player; k--) {
                    size_t t = order[k];
                    order[k] = order[k - 1];
                    order[k - 1] = t;
                }
            for (i = 0; i < nr; i++)
                for (j = 0; j < nc; j++)
                    b.cost[i][j] = fl_report_pair_cost_q8(&r[i], &c[order[j]]);
            brute(&b, 0, 0);
            for (i = 0; i < nr; i++) {
                uint8_t want = b.best[i] < (int)nc ? c[order[b.best[i]]].player : 0;
                if (r[i].player != want) {
                    t_fail_msg(__FILE__, __LINE__, "trial %d report %u: player %u, brute force %u",
                               trial, (unsigned)i, r[i].player, want);
                    break;
                }
                if (want) {
                    total += b.cost[i][b.best[i]];
                    CHECK(b.cost[i][b.best[i]] <= b.gate);
                } else {
                    total += b.gate;
                    gated++;
                }
            }
            CHECK_EQ(total, b.best_cost);
            /* a tie: another matching with the same total exists */
            for (i = 0; i + 1 < nr; i++)
                for (k = i + 1; k < nr; k++)
                    if (b.best[i] < (int)nc && b.best[k] < (int)nc &&
                        b.cost[i][b.best[k]] + b.cost[k][b.best[i]] ==
                            b.cost[i][b.best[i]] + b.cost[k][b.best[k]])
                        ties++;
        }
        for (i = nr; i < nr + nother; i++)
            CHECK_EQ(r[i].player, 0);   /* the other team has no claims */
        CHECK_EQ(st.assigned + st.unassigned, (uint32_t)(nr + nother));
    }
    t_info("assign vs brute force: 3000 cases, %d swaps of equal cost, %d reports gated", ties,
           gated);
    CHECK(ties > 100);
    CHECK(gated > 100);
}

/* Two players whose estimates are both shifted toward +x: greedy nearest
 * (each report to its nearest estimate, or the nearest pair first) gives
 * B's report to A; the global assignment gives each its own. */
static void test_assign_swapped(void)
{
    const fl_field_t *field = fl_field_find("spl2013");
    fl_obs_report_t r[2];
    fl_report_claim_t c[2];
    fl_report_stats_t st;
    memset(&st, 0, sizeof st);
    r[0] = rep(0, 0, FL_COLOR_RED, 0);       /* A's foot */
    r[1] = rep(1000, 0, FL_COLOR_RED, 0);    /* B's foot */
    c[0] = claim(600, 0, 400, FL_COLOR_RED, 1);    /* A thinks 600 mm off */
    c[1] = claim(1700, 0, 400, FL_COLOR_RED, 2);   /* B thinks 700 mm off */
    /* greedy: B's report is nearer A's estimate (400) than A's is (600) */
    CHECK(fl_report_pair_cost_q8(&r[1], &c[0]) < fl_report_pair_cost_q8(&r[0], &c[0]));
    CHECK(fl_report_pair_cost_q8(&r[1], &c[0]) < fl_report_pair_cost_q8(&r[1], &c[1]));
    CHECK_EQ(fl_report_assign(r, 2, c, 2, field, 0, &st), FL_OK);
    CHECK_EQ(r[0].player, 1);
    CHECK_EQ(r[1].player, 2);
    CHECK_EQ(st.assigned, 2u);
    /* numbers the caller left in are overwritten; with A's claim alone,
     * B's report (the cheaper one) is A's: the coach cannot know better */
    r[0].player = r[1].player = 7;
    CHECK_EQ(fl_report_assign(r, 2, &c[0], 1, field, 0, &st), FL_OK);
    CHECK_EQ(r[0].player, 0);
    CHECK_EQ(r[1].player, 1);
    /* the claims listed the other way round: the same matching */
    {
        fl_report_claim_t cc[2];
        cc[0] = c[1];
        cc[1] = c[0];
        CHECK_EQ(fl_report_assign(r, 2, cc, 2, field, 0, &st), FL_OK);
        CHECK_EQ(r[0].player, 1);
        CHECK_EQ(r[1].player, 2);
    }
}

/* Claims and reports the assignment refuses, and its argument checks. */
static void test_assign_refusals(void)
{
    const fl_field_t *field = fl_field_find("spl2013");
    fl_obs_report_t r[FL_REPORT_MAX + 1];
    fl_report_claim_t c[2 * FL_REPORT_MAX_PLAYERS + 1];
    fl_report_stats_t st;
    size_t i;
    memset(&st, 0, sizeof st);
    r[0] = rep(0, 0, FL_COLOR_RED, 0);
    r[1] = rep(1000, 0, FL_COLOR_RED, 0);
    r[1].age_ms = FL_OBS_REPORT_MAX_AGE_MS + 1;     /* stale */
    r[2] = rep(99999, 0, FL_COLOR_RED, 0);          /* off the carpet */
    r[3] = rep(-2000, 0, FL_COLOR_RED, 0);          /* far from every claim */
    c[0] = claim(100, 0, 300, FL_COLOR_RED, 3);
    c[1] = claim(900, 0, 300, FL_COLOR_RED, 3);      /* number twice */
    c[2] = claim(900, 0, 300, FL_COLOR_RED, 0);      /* no number */
    c[3] = claim(900, 0, 300, FL_COLOR_RED, FL_REPORT_PLAYER_MAX + 1);
    CHECK_EQ(fl_report_assign(r, 4, c, 4, field, 0, &st), FL_OK);
    CHECK_EQ(r[0].player, 3);
    CHECK_EQ(r[1].player, 0);
    CHECK_EQ(r[2].player, 0);
    CHECK_EQ(r[3].player, 0);
    CHECK_EQ(st.stale, 1u);
    CHECK_EQ(st.off_carpet, 1u);
    CHECK_EQ(st.claims_refused, 3u);
    CHECK_EQ(st.assigned, 1u);
    CHECK_EQ(st.unassigned, 1u);
    /* more claims of a team than FL_REPORT_MAX_PLAYERS: the extra ones */
    for (i = 0; i <= FL_REPORT_MAX_PLAYERS; i++)
        c[i] = claim((int32_t)i * 100, 0, 300, FL_COLOR_BLUE, (uint8_t)(i + 1));
    memset(&st, 0, sizeof st);
    CHECK_EQ(fl_report_assign(r, 1, c, FL_REPORT_MAX_PLAYERS + 1, field, 0, &st), FL_OK);
    CHECK_EQ(st.claims_refused, 1u);
    CHECK_EQ(fl_report_assign(r, 1, c, 2 * FL_REPORT_MAX_PLAYERS + 1, field, 0, &st),
             FL_ERR_SIZE);
    for (i = 0; i <= FL_REPORT_MAX; i++)
        r[i] = rep(0, 0, FL_COLOR_RED, 0);
    CHECK_EQ(fl_report_assign(r, FL_REPORT_MAX + 1, c, 1, field, 0, &st), FL_ERR_SIZE);
    CHECK_EQ(fl_report_assign(NULL, 1, c, 1, field, 0, &st), FL_ERR_NULL);
    CHECK_EQ(fl_report_assign(r, 1, NULL, 1, field, 0, &st), FL_ERR_NULL);
    CHECK_EQ(fl_report_assign(r, 1, c, 1, NULL, 0, &st), FL_ERR_NULL);
    CHECK_EQ(fl_report_assign(r, 1, c, 1, field, FL_REPORT_GATE_MAX_Q8 + 1, NULL), FL_ERR_RANGE);
    CHECK_EQ(fl_report_assign(NULL, 0, NULL, 0, field, 0, NULL), FL_OK);
    CHECK_EQ(st.bad_calls, 5u);
    /* every report of the largest frame at once (the worst case's work) */
    for (i = 0; i < FL_REPORT_MAX; i++)
        r[i] = rep((int32_t)i * 300 - 1500, 0, FL_COLOR_RED, 0);
    for (i = 0; i < FL_REPORT_MAX_PLAYERS; i++)
        c[i] = claim((int32_t)i * 300 - 1400, 0, 300, FL_COLOR_RED, (uint8_t)(i + 1));
    memset(&st, 0, sizeof st);
    CHECK_EQ(fl_report_assign(r, FL_REPORT_MAX, c, FL_REPORT_MAX_PLAYERS, field, 0, &st), FL_OK);
    CHECK_EQ(st.assigned, (uint32_t)FL_REPORT_MAX_PLAYERS);
    for (i = 0; i < FL_REPORT_MAX_PLAYERS; i++)   /* each to the one 100 mm from it */
        CHECK_EQ(r[i].player, (uint8_t)(i + 1));
}

/* ---- the player's pick ---------------------------------------------------- */

static fl_report_self_t self(uint8_t team, uint8_t player, uint32_t now)
{
    fl_report_self_t me;
    memset(&me, 0, sizeof me);
    me.team = team;
    me.player = player;
    me.now_ms = now;
    me.field = fl_field_find("spl2013");
    return me;
}

static void test_pick(void)
{
    fl_report_tracker_t t;
    fl_report_self_t me = self(FL_COLOR_RED, 2, 10000);
    fl_obs_report_t r[4];
    size_t idx = 99;
    fl_report_tracker_init(&t);
    /* wrong team ignored; the own team's only report taken */
    r[0] = rep(0, 0, FL_COLOR_BLUE, 0);
    r[1] = rep(2000, 1000, FL_COLOR_RED, 0);
    CHECK_EQ(fl_report_pick(r, 2, &me, 1800, 900, 600, &t, &idx), FL_REPORT_NOT_NEEDED);
    CHECK_EQ(idx, 1u);
    CHECK_EQ(t.stats.other_team, 1u);
    /* only the other team: none */
    CHECK_EQ(fl_report_pick(r, 1, &me, 0, 0, 600, &t, &idx), FL_REPORT_NONE);
    /* ambiguous: two unnumbered reports of the team, 700 and 900 mm away */
    r[0] = rep(2700, 1000, FL_COLOR_RED, 0);
    r[1] = rep(2000, 1900, FL_COLOR_RED, 0);
    me.now_ms += 100;
    CHECK_EQ(fl_report_pick(r, 2, &me, 2000, 1000, 1500, &t, &idx), FL_REPORT_AMBIGUOUS);
    CHECK_EQ(t.stats.ambiguous, 1u);
    /* the same two, one clearly nearer (200 vs 900 mm): taken */
    r[0] = rep(2100, 1170, FL_COLOR_RED, 0);
    CHECK_EQ(fl_report_pick(r, 2, &me, 2000, 1000, 1500, &t, &idx), FL_REPORT_NOT_NEEDED);
    CHECK_EQ(idx, 0u);
    /* numbered: the one with its number, however far the estimate */
    r[0] = rep(2150, 1200, FL_COLOR_RED, 1);
    r[1] = rep(2200, 1200, FL_COLOR_RED, 2);
    me.now_ms += 100;
    CHECK_EQ(fl_report_pick(r, 2, &me, -3000, -2000, 200, &t, &idx), FL_REPORT_NOT_NEEDED);
    CHECK_EQ(idx, 1u);
    /* two with its number that disagree: conflict */
    r[0] = rep(2200 + FL_REPORT_CONFLICT_MM + 50, 1200, FL_COLOR_RED, 2);
    me.now_ms += 100;
    CHECK_EQ(fl_report_pick(r, 2, &me, 2200, 1200, 200, &t, &idx), FL_REPORT_CONFLICT);
    CHECK_EQ(t.stats.conflict, 1u);
    /* two with its number that agree: the one with the smaller sd */
    r[0] = rep(2250, 1200, FL_COLOR_RED, 2);
    r[0].sd_mm = 80;
    CHECK_EQ(fl_report_pick(r, 2, &me, 2200, 1200, 200, &t, &idx), FL_REPORT_NOT_NEEDED);
    CHECK_EQ(idx, 0u);
    /* numbered for others only: none (not its) */
    r[0].player = 3;
    r[1].player = 4;
    CHECK_EQ(fl_report_pick(r, 2, &me, 2200, 1200, 200, &t, &idx), FL_REPORT_NONE);
    /* stale / off the carpet, when nothing else could be its */
    r[0] = rep(2200, 1200, FL_COLOR_RED, 0);
    r[0].age_ms = FL_OBS_REPORT_MAX_AGE_MS + 1;
    CHECK_EQ(fl_report_pick(r, 1, &me, 2200, 1200, 200, &t, &idx), FL_REPORT_STALE);
    r[0] = rep(20000, 1200, FL_COLOR_RED, 2);
    CHECK_EQ(fl_report_pick(r, 1, &me, 2200, 1200, 200, &t, &idx), FL_REPORT_OFF_CARPET);
    CHECK_EQ(t.stats.stale, 1u);
    CHECK_EQ(t.stats.off_carpet, 1u);
    /* gated: the team's only report 3 m from a converged estimate */
    r[0] = rep(-800, 1200, FL_COLOR_RED, 0);
    CHECK_EQ(fl_report_pick(r, 1, &me, 2200, 1200, 200, &t, &idx), FL_REPORT_GATED);
    CHECK_EQ(t.stats.gated, 1u);
    /* jump: 2.5 m from the last accepted report (2250, 1200) 100 ms later */
    me.now_ms += 100;
    r[0] = rep(-250, 1200, FL_COLOR_RED, 2);
    CHECK_EQ(fl_report_pick(r, 1, &me, 2200, 1200, 3000, &t, &idx), FL_REPORT_JUMP);
    CHECK_EQ(t.stats.jump, 1u);
    /* ... reachable 6 s later (3 m at the walking limit) */
    me.now_ms += 6000;
    CHECK_EQ(fl_report_pick(r, 1, &me, 2200, 1200, 3000, &t, &idx), FL_REPORT_NOT_NEEDED);
    CHECK_EQ(t.last_x_mm, -250);
    /* the tracker re-initialized (a manual placement): no jump test */
    fl_report_tracker_init(&t);
    r[0] = rep(3000, -2000, FL_COLOR_RED, 2);
    CHECK_EQ(fl_report_pick(r, 1, &me, 0, 0, 3000, &t, &idx), FL_REPORT_NOT_NEEDED);
    /* bad calls */
    CHECK_EQ(fl_report_pick(r, 1, NULL, 0, 0, 3000, &t, &idx), FL_REPORT_BAD_CALL);
    CHECK_EQ(fl_report_pick(NULL, 1, &me, 0, 0, 3000, &t, &idx), FL_REPORT_BAD_CALL);
    CHECK_EQ(fl_report_pick(r, FL_REPORT_MAX + 1, &me, 0, 0, 3000, &t, &idx), FL_REPORT_BAD_CALL);
    CHECK_EQ(fl_report_pick(r, 1, &me, 0, 0, 3000, NULL, &idx), FL_REPORT_BAD_CALL);
    {
        fl_report_tracker_t raw;
        memset(&raw, 0, sizeof raw);
        CHECK_EQ(fl_report_pick(r, 1, &me, 0, 0, 3000, &raw, &idx), FL_REPORT_BAD_CALL);
    }
    CHECK_EQ(t.stats.bad_calls, 3u);
    CHECK(strcmp(fl_report_result_str(FL_REPORT_AMBIGUOUS), "ambiguous") == 0);
    CHECK(strcmp(fl_report_result_str((fl_report_result_t)99), "unknown") == 0);
}

/* ---- the per-frame step on every localizer -------------------------------- */

static double dist(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    return hypot((double)ax - bx, (double)ay - by);
}

static void test_apply(void)
{
    static sim_t sim;
    static sim_step_t s;
    uint16_t li;
    for (li = 0; li < fl_localizer_count(); li++) {
        const fl_localizer_t *loc = fl_localizer_get(li);
        sim_scenario_t sc;
        void *st = malloc(loc->state_size), *copy = malloc(loc->state_size);
        fl_loc_estimate_t e;
        fl_report_tracker_t t;
        fl_report_self_t me;
        fl_obs_report_t r[3];
        uint32_t k;
        CHECK(st != NULL && copy != NULL);
        if (st == NULL || copy == NULL)
            return;
        CHECK_EQ(sim_scenario_builtin(&sc, "spl2013"), 0);
        CHECK_EQ(sim_init(&sim, &sc), 0);
        CHECK_EQ(fl_loc_init(loc, st, sc.field, NULL), FL_OK);
        fl_report_tracker_init(&t);
        me = self(FL_COLOR_BLUE, 3, 1000);
        me.field = sc.field;
        me.est = &e;
        /* converge on the walk; the belief is narrow */
        loc->set_prior_half(st, -1);
        for (k = 0; k < 300 && sim_step(&sim, &s); k++) {
            fl_loc_predict(loc, st, s.odo_dx_mm, s.odo_dy_mm, s.odo_dtheta);
            fl_loc_update(loc, st, &s.obs, NULL);
        }
        CHECK(fl_loc_estimate(loc, st, &e));
        CHECK(dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm) < 500);
        memcpy(copy, st, loc->state_size);
        /* converged: a good report of its own is accepted and not needed */
        r[0] = rep(s.x_mm + 60, s.y_mm - 40, FL_COLOR_BLUE, 0);
        r[1] = rep(-s.x_mm, -s.y_mm, FL_COLOR_RED, 0);
        CHECK_EQ(fl_report_apply(loc, st, r, 2, &me, 0, &t), FL_REPORT_NOT_NEEDED);
        CHECK(memcmp(copy, st, loc->state_size) == 0);
        /* refused reports leave the state as it was, byte for byte */
        me.now_ms += 100;
        r[0] = rep(s.x_mm, s.y_mm, FL_COLOR_BLUE, 3);
        r[1] = rep(s.x_mm + 900, s.y_mm, FL_COLOR_BLUE, 3);
        CHECK_EQ(fl_report_apply(loc, st, r, 2, &me, 1, &t), FL_REPORT_CONFLICT);
        r[0].age_ms = 5000;
        CHECK_EQ(fl_report_apply(loc, st, r, 1, &me, 1, &t), FL_REPORT_STALE);
        r[0] = rep(s.x_mm > 0 ? s.x_mm - 2000 : s.x_mm + 2000, s.y_mm, FL_COLOR_BLUE, 3);  /* 2 m in 100 ms */
        CHECK_EQ(fl_report_apply(loc, st, r, 1, &me, 1, &t), FL_REPORT_JUMP);
        CHECK_EQ(fl_report_apply(loc, st, r, 0, &me, 1, &t), FL_REPORT_NONE);
        CHECK(memcmp(copy, st, loc->state_size) == 0);
        CHECK_EQ(t.stats.frames, 5u);
        CHECK_EQ(t.stats.not_needed, 1u);
        CHECK_EQ(t.stats.none, 1u);
        CHECK_EQ(t.stats.reseeded, 0u);
        /* spread: a wrong belief 2.5 m off widened to ignorance */
        loc->reset_ignorance(st);
        CHECK(fl_loc_estimate(loc, st, &e));
        CHECK(fl_loc_spread_beyond(loc, st, FL_LOC_RESEED_SPREAD_MM));
        me.now_ms += 400;
        r[0] = rep(s.x_mm, s.y_mm, FL_COLOR_BLUE, 3);
        r[1] = rep(0, 0, FL_COLOR_RED, 1);
        r[2] = rep(-s.x_mm, s.y_mm, FL_COLOR_BLUE, 1);
        CHECK_EQ(fl_report_apply(loc, st, r, 3, &me, 0, &t), FL_REPORT_RESEEDED);
        CHECK(fl_loc_check(loc, st));
        CHECK(fl_loc_estimate(loc, st, &e));
        t_info("%s re-seeded by apply: estimate %.0f mm from the report, spread %u", loc->name,
               dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm), fl_loc_spread_mm(loc, st));
        CHECK(dist(e.x_mm, e.y_mm, s.x_mm, s.y_mm) < 2 * FL_OBS_REPORT_SD_MM);
        CHECK(!fl_loc_spread_beyond(loc, st, FL_LOC_RESEED_SPREAD_MM));
        CHECK_EQ(t.stats.reseeded, 1u);
        /* bad calls: no estimate, uninitialized state */
        me.est = NULL;
        CHECK_EQ(fl_report_apply(loc, st, r, 1, &me, 0, &t), FL_REPORT_BAD_CALL);
        me.est = &e;
        memset(copy, 0, loc->state_size);
        CHECK_EQ(fl_report_apply(loc, copy, r, 1, &me, 0, &t), FL_REPORT_BAD_CALL);
        CHECK_EQ(fl_report_apply(NULL, st, r, 1, &me, 0, &t), FL_REPORT_BAD_CALL);
        CHECK_EQ(t.stats.bad_calls, 3u);
        free(st);
        free(copy);
    }
}

/* ---- the message ------------------------------------------------------------ */

static void sample_msg(fl_report_msg_t *m)
{
    memset(m, 0, sizeof *m);
    m->frame_ms = 0x89ABCDEFu;
    m->n = 3;
    m->report[0] = rep(-4500, 3000, FL_COLOR_RED, 1);
    m->report[1] = rep(1234, -2999, FL_COLOR_BLUE, 0);
    m->report[1].sd_mm = FL_OBS_REPORT_SD_MAX_MM;
    m->report[1].age_ms = 65535;
    m->report[2] = rep(INT16_MIN, INT16_MAX, FL_COLOR_BLUE, FL_REPORT_PLAYER_MAX);
    m->report[2].confidence = 0;
    m->report[2].sd_mm = FL_OBS_REPORT_SD_MIN_MM;
    m->report[2].age_ms = 0;
}

/* Rewrite the checksum after a deliberate change (a well-formed message
 * with a bad field). */
static void reseal(uint8_t *b)
{
    uint32_t c = fl_report_crc32(b, FL_REPORT_MSG_BYTES - 4);
    b[FL_REPORT_MSG_BYTES - 4] = (uint8_t)c;
    b[FL_REPORT_MSG_BYTES - 3] = (uint8_t)(c >> 8);
    b[FL_REPORT_MSG_BYTES - 2] = (uint8_t)(c >> 16);
    b[FL_REPORT_MSG_BYTES - 1] = (uint8_t)(c >> 24);
}

static void test_wire(void)
{
    fl_report_msg_t m, d;
    fl_report_stats_t st;
    uint8_t b[FL_REPORT_MSG_BYTES + 8], c[FL_REPORT_MSG_BYTES + 8];
    size_t i, bit, undetected = 0;
    memset(&st, 0, sizeof st);
    CHECK_EQ(fl_report_crc32((const uint8_t *)"123456789", 9), 0xCBF43926u);
    sample_msg(&m);
    CHECK_EQ(fl_report_encode(&m, b, sizeof b), FL_OK);
    t_digest("report.wire", t_hash_bytes(t_hash_init(), b, FL_REPORT_MSG_BYTES));
    /* the bytes themselves: little-endian, byte by byte */
    CHECK(b[0] == 'F' && b[1] == 'R' && b[2] == FL_REPORT_WIRE_VERSION && b[3] == 3);
    CHECK(b[4] == 0xEF && b[5] == 0xCD && b[6] == 0xAB && b[7] == 0x89);
    CHECK(b[8] == (uint8_t)(-4500 & 0xFF) && b[9] == (uint8_t)((-4500 >> 8) & 0xFF));
    CHECK_EQ(fl_report_decode(b, FL_REPORT_MSG_BYTES, &d, &st), FL_OK);
    CHECK_EQ(d.frame_ms, m.frame_ms);
    CHECK_EQ(d.n, 3);
    CHECK(memcmp(&d, &m, sizeof m) == 0);
    /* every single-bit error is detected */
    for (i = 0; i < FL_REPORT_MSG_BYTES; i++)
        for (bit = 0; bit < 8; bit++) {
            memcpy(c, b, FL_REPORT_MSG_BYTES);
            c[i] ^= (uint8_t)(1u << bit);
            if (fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st) == FL_OK)
                undetected++;
            else if (d.n != 0)
                undetected++;
        }
    CHECK_EQ(undetected, 0u);
    CHECK_EQ(st.msg_corrupt, (uint32_t)FL_REPORT_MSG_BYTES * 8u);
    /* truncated and padded */
    for (i = 0; i < FL_REPORT_MSG_BYTES + 8; i++)
        if (i != FL_REPORT_MSG_BYTES)
            CHECK_EQ(fl_report_decode(b, i, &d, &st), FL_ERR_SIZE);
    CHECK_EQ(st.msg_truncated, (uint32_t)FL_REPORT_MSG_BYTES + 7u);
    /* well-sealed but wrong: version, count, a used slot, an unused slot */
    memcpy(c, b, FL_REPORT_MSG_BYTES);
    c[2] = FL_REPORT_WIRE_VERSION + 1;
    reseal(c);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_FORMAT);
    CHECK_EQ(st.msg_version, 1u);
    memcpy(c, b, FL_REPORT_MSG_BYTES);
    c[3] = FL_REPORT_MAX + 1;
    reseal(c);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_RANGE);
    memcpy(c, b, FL_REPORT_MSG_BYTES);
    c[8 + 4] = 0;   /* sd 0 */
    c[8 + 5] = 0;
    reseal(c);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_RANGE);
    CHECK_EQ(d.n, 0);
    memcpy(c, b, FL_REPORT_MSG_BYTES);
    c[8 + 7] = FL_COLOR_BLUE + 1;   /* team */
    reseal(c);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_RANGE);
    memcpy(c, b, FL_REPORT_MSG_BYTES);
    c[8 + 9] = 1;   /* reserved */
    reseal(c);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_RANGE);
    if (FL_REPORT_MAX > 3) {
        memcpy(c, b, FL_REPORT_MSG_BYTES);
        c[8 + 12 * 3 + 5] = 1;   /* an unused slot */
        reseal(c);
        CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_RANGE);
        CHECK_EQ(st.msg_range, 5u);
    }
    /* bad magic, even sealed */
    memcpy(c, b, FL_REPORT_MSG_BYTES);
    c[0] = 'G';
    reseal(c);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_FORMAT);
    /* encode refuses what it cannot carry, writing nothing */
    memset(c, 0xAA, sizeof c);
    m.report[1].x_mm = 40000;
    CHECK_EQ(fl_report_encode(&m, c, sizeof c), FL_ERR_RANGE);
    CHECK_EQ(c[0], 0xAA);
    sample_msg(&m);
    m.report[0].age_ms = -1;
    CHECK_EQ(fl_report_encode(&m, c, sizeof c), FL_ERR_RANGE);
    sample_msg(&m);
    m.report[0].player = FL_REPORT_PLAYER_MAX + 1;
    CHECK_EQ(fl_report_encode(&m, c, sizeof c), FL_ERR_RANGE);
    sample_msg(&m);
    m.n = FL_REPORT_MAX + 1;
    CHECK_EQ(fl_report_encode(&m, c, sizeof c), FL_ERR_RANGE);
    sample_msg(&m);
    CHECK_EQ(fl_report_encode(&m, c, FL_REPORT_MSG_BYTES - 1), FL_ERR_SIZE);
    CHECK_EQ(fl_report_encode(NULL, c, sizeof c), FL_ERR_NULL);
    CHECK_EQ(fl_report_decode(NULL, FL_REPORT_MSG_BYTES, &d, &st), FL_ERR_NULL);
    /* a full and an empty message round trip */
    memset(&m, 0, sizeof m);
    CHECK_EQ(fl_report_encode(&m, c, sizeof c), FL_OK);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, NULL), FL_OK);
    CHECK_EQ(d.n, 0);
    m.n = FL_REPORT_MAX;
    for (i = 0; i < FL_REPORT_MAX; i++)
        m.report[i] = rep((int32_t)i * 700 - 4000, (int32_t)i * -500 + 2500, FL_COLOR_RED,
                          (uint8_t)i);
    CHECK_EQ(fl_report_encode(&m, c, sizeof c), FL_OK);
    CHECK_EQ(fl_report_decode(c, FL_REPORT_MSG_BYTES, &d, NULL), FL_OK);
    CHECK(memcmp(&d, &m, sizeof m) == 0);
    t_digest("report.wire_full", t_hash_bytes(t_hash_init(), c, FL_REPORT_MSG_BYTES));
}

/* ---- wrong assignments on random scenes ------------------------------------- */

typedef struct {
    long players, wrong, unassigned, refused;
} tally_t;

/* Scenes of 2-5 players of one team (and as many opponents, whose reports
 * the team's rules must ignore) on the spl2016 carpet's field, at least
 * 400 mm apart; each player's estimate off its truth by 200-1500 mm in a
 * random direction, its spread its error times a factor in [0.7, 1.4]
 * (spread_known) or 800 mm for all; the coach's foot off by N(0, 125 mm)
 * per axis.  Counts, per player: greedy nearest (the report of its team
 * nearest its estimate, no refusal), the player-side pick (nearest with
 * the ambiguity and gate refusals), greedy by pairs (the coach taking the
 * cheapest free pair first, the same cost) and the coach's global
 * assignment. */
static void scenes(int n_scenes, bool spread_known, tally_t *greedy, tally_t *pairs,
                   tally_t *pick, tally_t *global)
{
    const fl_field_t *field = fl_field_find("spl2013");
    int sc;
    for (sc = 0; sc < n_scenes; sc++) {
        int np = 2 + (int)(rnd() % 4), i, j, n = 0;
        int32_t tx[10], ty[10];
        fl_obs_report_t r[FL_REPORT_MAX];
        int owner[FL_REPORT_MAX];
        fl_report_claim_t c[5];
        fl_report_stats_t st;
        /* truths of both teams, 400 mm apart */
        for (i = 0; i < 2 * np; i++) {
            bool close;
            do {
                tx[i] = (int32_t)(urand() * 8400) - 4200;
                ty[i] = (int32_t)(urand() * 5400) - 2700;
                close = false;
                for (j = 0; j < i; j++)
                    close = close || dist(tx[i], ty[i], tx[j], ty[j]) < 400;
            } while (close);
        }
        for (i = 0; i < 2 * np; i++) {
            uint8_t team = i < np ? FL_COLOR_RED : FL_COLOR_BLUE;
            int32_t ex = (int32_t)lround(gauss() * 125);
            int32_t ey = (int32_t)lround(gauss() * 125);
            r[n] = rep(tx[i] + ex, ty[i] + ey, team, 0);
            owner[n++] = i < np ? i + 1 : 0;
        }
        /* shuffle the coach's order */
        for (i = n - 1; i > 0; i--) {
            int k = (int)(rnd() % (uint32_t)(i + 1)), to;
            fl_obs_report_t tr = r[i];
            r[i] = r[k];
            r[k] = tr;
            to = owner[i];
            owner[i] = owner[k];
            owner[k] = to;
        }
        for (i = 0; i < np; i++) {
            double e = 200 + urand() * 1300, a = urand() * 6.283185307;
            c[i] = claim(tx[i] + (int32_t)lround(e * cos(a)), ty[i] + (int32_t)lround(e * sin(a)),
                         spread_known ? (uint32_t)lround(e * (0.7 + 0.7 * urand())) : 800u,
                         FL_COLOR_RED, (uint8_t)(i + 1));
        }
        for (i = 0; i < np; i++) {   /* the player's side */
            fl_report_tracker_t t;
            fl_report_self_t me = self(FL_COLOR_RED, 0, 1000);
            fl_report_result_t res;
            size_t idx = 99;
            int best = -1;
            double bd = 1e18;
            for (j = 0; j < n; j++) {
                double d = dist(r[j].x_mm, r[j].y_mm, c[i].x_mm, c[i].y_mm);
                if (r[j].team == FL_COLOR_RED && d < bd) {
                    bd = d;
                    best = j;
                }
            }
            greedy->players++;
            greedy->wrong += owner[best] != i + 1;
            fl_report_tracker_init(&t);
            res = fl_report_pick(r, (size_t)n, &me, c[i].x_mm, c[i].y_mm, c[i].spread_mm, &t, &idx);
            pick->players++;
            if (res == FL_REPORT_NOT_NEEDED)
                pick->wrong += owner[idx] != i + 1;
            else
                pick->refused++;
        }
        {   /* greedy by pairs: the cheapest free (report, claim) pair first */
            bool rused[FL_REPORT_MAX] = {false}, cused[5] = {false};
            int step;
            for (step = 0; step < np; step++) {
                int bi = -1, bj = -1;
                uint32_t bc = UINT32_MAX;
                for (j = 0; j < n; j++)
                    for (i = 0; i < np; i++) {
                        uint32_t cost = fl_report_pair_cost_q8(&r[j], &c[i]);
                        if (!rused[j] && !cused[i] && r[j].team == FL_COLOR_RED && cost < bc) {
                            bc = cost;
                            bi = i;
                            bj = j;
                        }
                    }
                if (bi < 0)
                    break;
                rused[bj] = cused[bi] = true;
                pairs->players++;
                pairs->wrong += owner[bj] != bi + 1;
            }
        }
        memset(&st, 0, sizeof st);
        CHECK_EQ(fl_report_assign(r, (size_t)n, c, (size_t)np, field, 0, &st), FL_OK);
        for (i = 0; i < np; i++) {   /* player i + 1: the report numbered for it */
            int got = -1;
            for (j = 0; j < n; j++)
                if (r[j].player == i + 1)
                    got = j;
            global->players++;
            if (got < 0)
                global->unassigned++;
            else
                global->wrong += owner[got] != i + 1;
        }
    }
}

static double pct(long a, long b)
{
    return b > 0 ? 100.0 * (double)a / (double)b : 0.0;
}

static void test_wrong_rates(void)
{
    int mode;
    rng_state = 2024u;
    for (mode = 0; mode < 2; mode++) {
        tally_t g = {0, 0, 0, 0}, q = {0, 0, 0, 0}, p = {0, 0, 0, 0}, a = {0, 0, 0, 0};
        int n = t_quick ? 2000 : 10000;
        scenes(n, mode == 0, &g, &q, &p, &a);
        t_info("wrong assignments over %d scenes (2-5 players a team, estimate errors "
               "0.2-1.5 m, spread %s):",
               n, mode == 0 ? "0.7-1.4 x error" : "800 mm for all");
        t_info("  greedy nearest %.2f%% wrong; greedy pairs %.2f%%; player pick %.2f%% wrong, "
               "%.2f%% refused; global assignment %.2f%% wrong, %.2f%% unassigned",
               pct(g.wrong, g.players), pct(q.wrong, q.players), pct(p.wrong, p.players),
               pct(p.refused, p.players), pct(a.wrong, a.players), pct(a.unassigned, a.players));
        CHECK(g.players > 0 && a.players == g.players);
        /* the global assignment: fewer wrong than either greedy */
        CHECK(a.wrong * 3 < g.wrong * 2);
        CHECK(a.wrong < q.wrong);
        /* the pick's refusals trade wrong ones for none */
        CHECK(p.wrong < g.wrong);
    }
}

void suite_report(void)
{
    t_run("report.assign_vs_brute", test_assign_vs_brute);
    t_run("report.assign_swapped", test_assign_swapped);
    t_run("report.assign_refusals", test_assign_refusals);
    t_run("report.pick", test_pick);
    t_run("report.apply", test_apply);
    t_run("report.wire", test_wire);
    t_run("report.wrong_rates", test_wrong_rates);
}
