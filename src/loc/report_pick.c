/*
 * src/loc/report_pick.c - the player's side of an observer's reports
 * (report.h): which report of a frame is its own, the refusals (another
 * team, stale, off the carpet, two that disagree, ambiguous, beyond the
 * gate, a jump no walking robot makes), and the per-frame step that
 * re-seeds a spread belief from the accepted one.  Nothing here writes the
 * localizer's state except fl_loc_reseed.
 */
#include "report_int.h"

#include <string.h>

#define TRACKER_MAGIC 0x46525054u   /* "FRPT" */
/* Beyond this, any report is within reach of the last one (a minute). */
#define JUMP_DT_CAP_MS 60000


#define COUNT(t, f) ((t)->stats.f = fl_report_sat_inc((t)->stats.f))

const char *fl_report_result_str(fl_report_result_t r)
{
    switch (r) {
    case FL_REPORT_RESEEDED: return "reseeded";
    case FL_REPORT_NOT_NEEDED: return "not_needed";
    case FL_REPORT_NONE: return "none";
    case FL_REPORT_AMBIGUOUS: return "ambiguous";
    case FL_REPORT_CONFLICT: return "conflict";
    case FL_REPORT_JUMP: return "jump";
    case FL_REPORT_STALE: return "stale";
    case FL_REPORT_OFF_CARPET: return "off_carpet";
    case FL_REPORT_GATED: return "gated";
    case FL_REPORT_BAD_CALL: return "bad_call";
    case FL_REPORT_REFUSED: return "refused";
    default: return "unknown";
    }
}

void fl_report_tracker_init(fl_report_tracker_t *t)
{
    if (t == NULL)
        return;
    memset(t, 0, sizeof *t);
    t->magic = TRACKER_MAGIC;
}

static int64_t dist2(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    return fl_report_internal_dist2(ax, ay, bx, by);
}

/* Step 1 of fl_report_pick for one report: whether it may be the player's
 * (its team, checked, its number or none); a refusal is remembered in
 * *why (the first one) and counted. */
static bool candidate(const fl_obs_report_t *r, const fl_report_self_t *me,
                      fl_report_tracker_t *t, fl_report_result_t *why)
{
    fl_status_t s;
    if (r->team != me->team) {
        COUNT(t, other_team);
        return false;
    }
    if (r->player != 0 && r->player != me->player)
        return false;   /* another player's, by the coach's numbering */
    s = fl_obs_report_check(r, me->field);
    if (s == FL_OK)
        return true;
    if (s == FL_ERR_STALE) {
        COUNT(t, stale);
        if (*why == FL_REPORT_NONE)
            *why = FL_REPORT_STALE;
    } else {
        COUNT(t, off_carpet);
        if (*why == FL_REPORT_NONE)
            *why = FL_REPORT_OFF_CARPET;
    }
    return false;
}

/* Step 2: the reports carrying the player's number (ok[], numbered). */
static fl_report_result_t pick_numbered(const fl_obs_report_t *reports, size_t n,
                                        const bool *ok, fl_report_tracker_t *t, size_t *best)
{
    const int64_t lim = (int64_t)FL_REPORT_CONFLICT_MM * FL_REPORT_CONFLICT_MM;
    size_t i, k;
    *best = n;
    for (i = 0; i < n; i++) {
        if (!ok[i] || reports[i].player == 0)
            continue;
        for (k = i + 1; k < n; k++) {
            if (ok[k] && reports[k].player != 0 &&
                dist2(reports[i].x_mm, reports[i].y_mm, reports[k].x_mm, reports[k].y_mm) > lim) {
                COUNT(t, conflict);
                return FL_REPORT_CONFLICT;
            }
        }
        if (*best == n || reports[i].sd_mm < reports[*best].sd_mm)
            *best = i;
    }
    return FL_REPORT_NOT_NEEDED;
}

/* The gate's test for a report at squared distance d2 from an estimate of
 * the given spread (the coach's pair cost, report.h). */
static bool beyond_gate(int64_t d2, uint32_t spread_mm, int32_t sd_mm)
{
    return fl_report_internal_cost_q8(d2, spread_mm, sd_mm) > FL_REPORT_GATE_Q8;
}

/* Step 3: the unnumbered reports of the team (ok[], player 0). */
static fl_report_result_t pick_nearest(const fl_obs_report_t *reports, size_t n,
                                       const bool *ok, int32_t ex, int32_t ey,
                                       uint32_t spread_mm, fl_report_tracker_t *t, size_t *best)
{
    size_t i, second = n;
    int64_t d1 = 0, d2 = 0;
    uint32_t r1, r2, margin;
    *best = n;
    for (i = 0; i < n; i++) {
        int64_t d;
        if (!ok[i] || reports[i].player != 0)
            continue;
        d = dist2(reports[i].x_mm, reports[i].y_mm, ex, ey);
        if (*best == n || d < d1) {
            second = *best;
            d2 = d1;
            *best = i;
            d1 = d;
        } else if (second == n || d < d2) {
            second = i;
            d2 = d;
        }
    }
    if (*best == n)
        return FL_REPORT_NONE;
    if (beyond_gate(d1, spread_mm, reports[*best].sd_mm)) {
        COUNT(t, gated);
        return FL_REPORT_GATED;
    }
    if (second < n && !beyond_gate(d2, spread_mm, reports[second].sd_mm)) {
        r1 = fl_isqrt64((uint64_t)d1);
        r2 = fl_isqrt64((uint64_t)d2);
        margin = r1 / 2u > (uint32_t)FL_REPORT_AMBIG_MM ? r1 / 2u : (uint32_t)FL_REPORT_AMBIG_MM;
        if (r2 - r1 < margin) {
            COUNT(t, ambiguous);
            return FL_REPORT_AMBIGUOUS;
        }
    }
    return FL_REPORT_NOT_NEEDED;
}

/* Step 4: farther from the last accepted report than a walk reaches. */
static bool jumped(const fl_obs_report_t *r, uint32_t seen_ms, const fl_report_tracker_t *t)
{
    int64_t dt, reach;
    if (!t->have_last)
        return false;
    dt = (int64_t)(int32_t)(seen_ms - t->last_ms);
    if (dt < 0)
        dt = -dt;
    if (dt > JUMP_DT_CAP_MS)
        dt = JUMP_DT_CAP_MS;
    reach = dt * FL_REPORT_MAX_SPEED_MM_S / 1000 +
            (int64_t)FL_REPORT_JUMP_SDS * ((int64_t)t->last_sd_mm + r->sd_mm);
    return dist2(r->x_mm, r->y_mm, t->last_x_mm, t->last_y_mm) > reach * reach;
}

/* fl_report_pick's inputs in one block (a call with more arguments than
 * registers pushes them: a dynamic frame for the stack report). */
typedef struct {
    const fl_obs_report_t *reports;
    size_t n;
    const fl_report_self_t *me;
    int32_t est_x_mm, est_y_mm;
    uint32_t est_spread_mm;
} pick_in_t;

static fl_report_result_t pick(const pick_in_t *in, fl_report_tracker_t *t, size_t *index)
{
    bool ok[FL_REPORT_MAX], numbered = false;
    fl_report_result_t why = FL_REPORT_NONE, res;
    const fl_obs_report_t *reports = in->reports, *r;
    const fl_report_self_t *me = in->me;
    size_t i, n = in->n, best = n;
    uint32_t seen_ms;
    if (t == NULL || t->magic != TRACKER_MAGIC)
        return FL_REPORT_BAD_CALL;
    if (me == NULL || me->field == NULL || (n > 0 && reports == NULL) || n > FL_REPORT_MAX) {
        COUNT(t, bad_calls);
        return FL_REPORT_BAD_CALL;
    }
    for (i = 0; i < n; i++) {
        ok[i] = candidate(&reports[i], me, t, &why);
        numbered = numbered || (ok[i] && me->player != 0 && reports[i].player == me->player);
    }
    if (numbered)
        res = pick_numbered(reports, n, ok, t, &best);
    else
        res = pick_nearest(reports, n, ok, in->est_x_mm, in->est_y_mm, in->est_spread_mm, t,
                           &best);
    if (res == FL_REPORT_NONE)
        return why;
    if (res != FL_REPORT_NOT_NEEDED)
        return res;
    r = &reports[best];
    seen_ms = me->now_ms - (uint32_t)r->age_ms;
    if (jumped(r, seen_ms, t)) {
        COUNT(t, jump);
        return FL_REPORT_JUMP;
    }
    t->have_last = true;
    t->last_x_mm = r->x_mm;
    t->last_y_mm = r->y_mm;
    t->last_sd_mm = r->sd_mm;
    t->last_ms = seen_ms;
    if (index != NULL)
        *index = best;
    return FL_REPORT_NOT_NEEDED;
}

fl_report_result_t fl_report_pick(const fl_obs_report_t *reports, size_t n,
                                  const fl_report_self_t *me, int32_t est_x_mm,
                                  int32_t est_y_mm, uint32_t est_spread_mm,
                                  fl_report_tracker_t *t, size_t *index)
{
    pick_in_t in;
    in.reports = reports;
    in.n = n;
    in.me = me;
    in.est_x_mm = est_x_mm;
    in.est_y_mm = est_y_mm;
    in.est_spread_mm = est_spread_mm;
    return pick(&in, t, index);
}

fl_report_result_t fl_report_apply(const fl_localizer_t *loc, void *state,
                                   const fl_obs_report_t *reports, size_t n,
                                   const fl_report_self_t *me,
                                   uint32_t spread_threshold_mm,
                                   fl_report_tracker_t *t)
{
    fl_report_result_t res;
    size_t idx = 0;
    uint32_t spread;
    if (t == NULL || t->magic != TRACKER_MAGIC)
        return FL_REPORT_BAD_CALL;
    COUNT(t, frames);
    spread = fl_loc_spread_mm(loc, state);
    if (loc == NULL || state == NULL || me == NULL || me->est == NULL || spread == UINT32_MAX) {
        COUNT(t, bad_calls);
        return FL_REPORT_BAD_CALL;
    }
    {
        pick_in_t in;
        in.reports = reports;
        in.n = n;
        in.me = me;
        in.est_x_mm = me->est->x_mm;
        in.est_y_mm = me->est->y_mm;
        in.est_spread_mm = spread;
        res = pick(&in, t, &idx);
    }
    if (res == FL_REPORT_NONE)
        COUNT(t, none);
    if (res != FL_REPORT_NOT_NEEDED)
        return res;
    if (spread_threshold_mm == 0)
        spread_threshold_mm = FL_LOC_RESEED_SPREAD_MM;
    if (!fl_loc_spread_beyond(loc, state, spread_threshold_mm)) {
        COUNT(t, not_needed);
        return FL_REPORT_NOT_NEEDED;
    }
    if (fl_loc_reseed(loc, state, &reports[idx]) != FL_OK)
        return FL_REPORT_REFUSED;
    COUNT(t, reseeded);
    return FL_REPORT_RESEEDED;
}
