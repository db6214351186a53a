/*
 * src/loc/report_assign.c - the coach's numbering of its reports: per team,
 * a minimum-cost one-to-one matching of reports to the players' own
 * estimates (report.h fl_report_assign), by the Hungarian method with
 * potentials on integer costs (Kuhn 1955, Munkres 1957; the shortest
 * augmenting path form in which each row is added by a Dijkstra-like scan
 * over the columns, as in Jonker and Volgenant 1987).
 *
 * Rows are the team's reports in the caller's order, columns its claims
 * sorted by number and then one "unmatched" column per report (cost: the
 * gate).  A pair beyond the gate costs more than any sum of gates, so the
 * optimum never uses it.  Ties are broken by a perturbation below one Q8
 * unit of cost: each cost is shifted left by TIE_BITS and report i taking
 * the column of rank k (a claim's index in number order; the unmatched
 * columns rank after every claim) adds k x B^(n-1-i), B =
 * FL_REPORT_MAX_PLAYERS + 1: the sum of those terms is a base-B number
 * whose digits are the ranks, so among matchings of equal Q8 cost the
 * least is the lexicographically least sequence of ranks.
 */
#include "report_int.h"

#include <string.h>

#define TIE_BITS 39
#define TIE_BASE ((int64_t)FL_REPORT_MAX_PLAYERS + 1)
#define COLS (FL_REPORT_MAX_PLAYERS + FL_REPORT_MAX)
#define INF64 INT64_MAX

/* B^FL_REPORT_MAX < 2^TIE_BITS, so that the ranks never outweigh a Q8
 * unit: 9^12 = 2.8e11 < 2^39 = 5.5e11 at the largest configuration. */
typedef char fl_report_tie_fits[(FL_REPORT_MAX_PLAYERS + 1 <= 9 && FL_REPORT_MAX <= 12) ? 1 : -1];

int64_t fl_report_internal_dist2(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    const int64_t cap = (int64_t)1 << 24;
    int64_t dx = (int64_t)ax - bx, dy = (int64_t)ay - by;
    dx = dx > cap ? cap : dx < -cap ? -cap : dx;
    dy = dy > cap ? cap : dy < -cap ? -cap : dy;
    return dx * dx + dy * dy;
}

uint32_t fl_report_internal_cost_q8(int64_t d2, uint32_t spread_mm, int32_t sd_mm)
{
    int64_t var, q;
    uint32_t sp = spread_mm;
    if (sp < FL_OBS_REPORT_SD_MIN_MM)
        sp = FL_OBS_REPORT_SD_MIN_MM;
    if (sp > FL_REPORT_SPREAD_CAP_MM)
        sp = FL_REPORT_SPREAD_CAP_MM;
    var = (int64_t)sp * sp / 2;
    if (sd_mm > 0 && sd_mm <= 1000000)
        var += (int64_t)sd_mm * sd_mm;
    if (var < 1)
        var = 1;
    if (d2 < 0)
        d2 = 0;
    q = (d2 * 256 + var / 2) / var;   /* d2 <= 2^49: no overflow */
    return q > (int64_t)UINT32_MAX ? UINT32_MAX : (uint32_t)q;
}

uint32_t fl_report_pair_cost_q8(const fl_obs_report_t *r, const fl_report_claim_t *c)
{
    if (r == NULL || c == NULL)
        return UINT32_MAX;
    return fl_report_internal_cost_q8(fl_report_internal_dist2(r->x_mm, r->y_mm, c->x_mm, c->y_mm),
                                      c->spread_mm, r->sd_mm);
}

/* The matching of n rows to m columns (n <= m) that minimizes the sum of
 * cost(i, j); col_of[i] gets row i's column.  cost[i][j] as given; the
 * work is at most n x (n + 1) x m column visits. */
typedef struct {
    int64_t a[FL_REPORT_MAX][COLS];
    size_t n, m;
} hung_t;

static void hungarian(const hung_t *h, size_t *col_of)
{
    int64_t u[FL_REPORT_MAX + 1], v[COLS + 1], minv[COLS + 1];
    size_t p[COLS + 1], way[COLS + 1];
    bool used[COLS + 1];
    size_t i, j;
    for (i = 0; i <= h->n; i++)
        u[i] = 0;
    for (j = 0; j <= h->m; j++) {
        v[j] = 0;
        p[j] = 0;
        way[j] = 0;
    }
    for (i = 1; i <= h->n; i++) {
        size_t j0 = 0;
        p[0] = i;
        for (j = 0; j <= h->m; j++) {
            minv[j] = INF64;
            used[j] = false;
        }
        do {   /* at most i + 1 passes: each one uses a new column */
            size_t i0 = p[j0], j1 = 0;
            int64_t delta = INF64;
            used[j0] = true;
            for (j = 1; j <= h->m; j++) {
                if (!used[j]) {
                    int64_t cur = h->a[i0 - 1][j - 1] - u[i0] - v[j];
                    if (cur < minv[j]) {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if (minv[j] < delta) {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for (j = 0; j <= h->m; j++) {
                if (used[j]) {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
        } while (p[j0] != 0);
        do {
            size_t j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0 != 0);
    }
    for (j = 1; j <= h->m; j++)
        if (p[j] != 0)
            col_of[p[j] - 1] = j - 1;
}

/* The claims fl_report_assign uses: valid numbers, at most
 * FL_REPORT_MAX_PLAYERS per team, no team and number twice; flags in ok[]. */
static void usable_claims(const fl_report_claim_t *claims, size_t n_claims, bool *ok,
                          fl_report_stats_t *st)
{
    size_t i, k;
    for (i = 0; i < n_claims; i++) {
        size_t same_team = 0;
        bool good = claims[i].player >= 1 && claims[i].player <= FL_REPORT_PLAYER_MAX;
        for (k = 0; k < i && good; k++) {
            if (!ok[k] || claims[k].team != claims[i].team)
                continue;
            same_team++;
            if (claims[k].player == claims[i].player)
                good = false;
        }
        if (same_team >= FL_REPORT_MAX_PLAYERS)
            good = false;
        ok[i] = good;
        if (!good)
            REPORT_COUNT(st, claims_refused);
    }
}

/* Match the valid reports of one team to its claims (indices into the
 * caller's arrays) and write the numbers. */
static void assign_team(fl_obs_report_t *reports, const size_t *ri, size_t nr,
                        const fl_report_claim_t *claims, const size_t *ci, size_t nc,
                        uint32_t gate_q8, fl_report_stats_t *st)
{
    const int64_t gated = ((int64_t)FL_REPORT_GATE_MAX_Q8 + 1) << TIE_BITS;
    hung_t h;
    size_t col_of[FL_REPORT_MAX];
    int64_t w = 1;
    size_t i, j;
    h.n = nr;
    h.m = nc + nr;
    for (i = nr; i-- > 0;) {   /* w = B^(nr - 1 - i) */
        for (j = 0; j < h.m; j++) {
            int64_t rank = (int64_t)(j < nc ? j : nc);
            int64_t base;
            if (j < nc) {
                uint32_t c = fl_report_pair_cost_q8(&reports[ri[i]], &claims[ci[j]]);
                base = c > gate_q8 ? gated : (int64_t)c << TIE_BITS;
            } else {
                base = (int64_t)gate_q8 << TIE_BITS;
            }
            h.a[i][j] = base + rank * w;
        }
        col_of[i] = h.m;
        w *= TIE_BASE;
    }
    if (nr > 0)
        hungarian(&h, col_of);
    for (i = 0; i < nr; i++) {
        if (col_of[i] < nc) {
            reports[ri[i]].player = claims[ci[col_of[i]]].player;
            REPORT_COUNT(st, assigned);
        } else {
            REPORT_COUNT(st, unassigned);
        }
    }
}

/* Indices of the usable claims of `team`, sorted by number (insertion). */
static size_t team_claims(const fl_report_claim_t *claims, size_t n_claims, const bool *ok,
                          uint8_t team, size_t *ci)
{
    size_t i, n = 0;
    for (i = 0; i < n_claims; i++) {
        size_t k;
        if (!ok[i] || claims[i].team != team)
            continue;
        for (k = n; k > 0 && claims[ci[k - 1]].player > claims[i].player; k--)
            ci[k] = ci[k - 1];
        ci[k] = i;
        n++;
    }
    return n;
}

fl_status_t fl_report_assign(fl_obs_report_t *reports, size_t n_reports,
                             const fl_report_claim_t *claims, size_t n_claims,
                             const fl_field_t *field, uint32_t gate_q8,
                             fl_report_stats_t *st)
{
    bool ok[2 * FL_REPORT_MAX_PLAYERS], valid[FL_REPORT_MAX], done[FL_REPORT_MAX];
    size_t ci[FL_REPORT_MAX_PLAYERS], ri[FL_REPORT_MAX];
    size_t i, k;
    if ((n_reports > 0 && (reports == NULL || field == NULL)) ||
        (n_claims > 0 && claims == NULL)) {
        REPORT_COUNT(st, bad_calls);
        return FL_ERR_NULL;
    }
    if (n_reports > FL_REPORT_MAX || n_claims > 2 * FL_REPORT_MAX_PLAYERS) {
        REPORT_COUNT(st, bad_calls);
        return FL_ERR_SIZE;
    }
    if (gate_q8 > FL_REPORT_GATE_MAX_Q8) {
        REPORT_COUNT(st, bad_calls);
        return FL_ERR_RANGE;
    }
    if (gate_q8 == 0)
        gate_q8 = FL_REPORT_GATE_Q8;
    usable_claims(claims, n_claims, ok, st);
    for (i = 0; i < n_reports; i++) {
        fl_status_t s = fl_obs_report_check(&reports[i], field);
        reports[i].player = 0;
        valid[i] = s == FL_OK;
        done[i] = false;
        if (s == FL_ERR_STALE)
            REPORT_COUNT(st, stale);
        else if (s != FL_OK)
            REPORT_COUNT(st, off_carpet);
    }
    /* one matching per team that has valid reports; teams in report order */
    for (i = 0; i < n_reports; i++) {
        size_t nr = 0, nc;
        uint8_t team = reports[i].team;
        if (!valid[i] || done[i])
            continue;
        for (k = i; k < n_reports; k++) {
            if (valid[k] && !done[k] && reports[k].team == team) {
                ri[nr++] = k;
                done[k] = true;
            }
        }
        nc = team_claims(claims, n_claims, ok, team, ci);
        assign_team(reports, ri, nr, claims, ci, nc, gate_q8, st);
    }
    return FL_OK;
}
