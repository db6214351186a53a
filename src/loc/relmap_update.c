/*
 * src/loc/relmap_update.c - one frame of seed 002's localizer (relmap.h):
 * equation 1 on every particle, the relative map (equations 2-4) on the
 * particles over the threshold, ties broken by white points, the belief
 * updated and normalised to its peak.
 *
 * The belief after a frame: particle p's prior belief times its eq.-1
 * likelihood L1 (the posterior "probability function" of seed 002's MCL,
 * normalised here to its peak, so that the threshold is a share of the
 * best particle's), then, for the particles over the threshold, times the
 * relative map's fit L2 = exp(-err / (2 sigma^2)) at their heading (the
 * error of eq. 2 measured against the same sigma as eq. 1); the others
 * times half the worst candidate's L2 (they were not examined and cannot
 * be better than the worst that was).
 */
#include "fieldloc/relmap.h"

#include <string.h>

#define RM_TRACK_FLOOR 4u   /* a particle at most this many floors is untracked */
#define RM_JUMP_RAMP 60u    /* frames over which a heading jump's cost grows
                               from a third of jump_q8 to all of it */

/* Eq. 1 for every particle: tmp_head holds L1 (Q16, bits of a uint16),
 * tmp_bel the posterior bel * L1; the maxima returned. */
static void eq1(fl_relmap_t *s, const fl_relmap_frame_t *f, uint32_t *max_post, uint32_t *max_l1)
{
    const fl_relmap_params_t *p = &s->params;
    uint32_t inv[FL_RELMAP_MAX_OBS];
    int64_t r2[FL_RELMAP_MAX_OBS];
    uint32_t min_sum = UINT32_MAX;
    int ix, iy, c;
    uint16_t i;
    *max_post = 0;
    *max_l1 = 0;
    for (i = 0; i < f->n; i++) {
        int32_t r = f->lm[i].range_mm > 50 ? f->lm[i].range_mm : 50;
        int64_t sig = (int64_t)p->sigma_base_mm + (int64_t)r * p->sigma_pct / 100;
        /* z = (d^2 - r^2) / (2 r sigma) ~ (d - r) / sigma near d = r */
        inv[i] = (uint32_t)(((int64_t)1 << 32) / (2 * (int64_t)r * (sig > 0 ? sig : 1)));
        r2[i] = (int64_t)f->lm[i].range_mm * f->lm[i].range_mm;
    }
    /* pass 1: each particle's exponent (Q8, saturated) in tmp_bel */
    for (iy = 0; iy < FL_RELMAP_NY; iy++)
        for (ix = 0; ix < FL_RELMAP_NX; ix++) {
            int32_t x, y;
            uint32_t sum = 0;
            fl_relmap_cell_pos(s, ix, iy, &x, &y);
            for (i = 0; i < f->n; i++) {
                const fl_relmap_lm_t *lm = &f->lm[i];
                int64_t best = INT64_MAX, z;
                uint32_t z2;
                uint8_t k;
                for (k = 0; k < lm->n_cand; k++) {
                    const fl_landmark_t *m = fl_field_all_at(s->field, lm->cand[k]);
                    int64_t dx = (int64_t)m->x_mm - x, dy = (int64_t)m->y_mm - y;
                    int64_t dd = dx * dx + dy * dy - r2[i];
                    if (dd < 0)
                        dd = -dd;
                    if (dd < best)
                        best = dd;
                }
                z = (best * inv[i]) >> 24;   /* Q8, >= 0 */
                z2 = z >= 65536 ? UINT32_MAX : (uint32_t)((z * z) >> 9);
                sum += z2 < p->z2_cap_q8 ? z2 : p->z2_cap_q8;
            }
            sum = sum < 65535u ? sum : 65535u;
            s->tmp_bel[iy * FL_RELMAP_NX + ix] = (uint16_t)sum;
            if (sum < min_sum)
                min_sum = sum;
        }
    /* pass 2: L1 normalised to the best particle's (the exponent less the
     * smallest), into tmp_head; the posterior into tmp_bel */
    for (c = 0; c < FL_RELMAP_N; c++) {
        uint32_t x = s->tmp_bel[c] - min_sum, l1, post;
        l1 = fl_relmap_exp_q16(x < p->frame_cap_q8 ? x : p->frame_cap_q8);
        if (l1 > 65535u)
            l1 = 65535u;
        post = ((uint32_t)s->bel[c] * l1 + 32768u) >> 16;
        s->tmp_head[c] = (int16_t)(uint16_t)l1;
        s->tmp_bel[c] = (uint16_t)post;
        if (post > *max_post)
            *max_post = post;
        if (l1 > *max_l1)
            *max_l1 = l1;
    }
}

/* The best cells by value (tmp_bel, or L1 in tmp_head) at or over thr,
 * at most k, appended to cand (not twice).  Values are binned by 1/64;
 * when the last bin taken holds more cells than there are places left,
 * they are taken evenly spread over it (a ring of equally good particles
 * is sampled around the ring, not at its first cells in memory). */
static uint16_t select_top(const fl_relmap_t *s, bool by_l1, uint32_t thr, uint16_t k,
                           uint16_t *cand, uint16_t n)
{
    uint16_t hist[64], above = 0, left, seen = 0, j;
    uint16_t n0 = n;
    int c, b, cut = 0;
    if (thr == 0)
        thr = 1;
    memset(hist, 0, sizeof hist);
    for (c = 0; c < FL_RELMAP_N; c++) {
        uint32_t v = by_l1 ? (uint16_t)s->tmp_head[c] : s->tmp_bel[c];
        if (v >= thr && hist[v >> 10] < 65535u)
            hist[v >> 10]++;
    }
    for (b = 63; b >= 0; b--) {
        cut = b;
        if (above + hist[b] > k)
            break;
        above = (uint16_t)(above + hist[b]);
    }
    left = (uint16_t)(k - above);   /* places for the cut bin (b >= 0) */
    for (c = 0; c < FL_RELMAP_N && n - n0 < k; c++) {
        uint32_t v = by_l1 ? (uint16_t)s->tmp_head[c] : s->tmp_bel[c];
        bool dup = false, take;
        if (v < thr || (int)(v >> 10) < cut)
            continue;
        if (b >= 0 && (int)(v >> 10) == cut) {
            /* the seen-th of hist[cut] cells: taken when it starts a new
             * share of `left` */
            take = (uint32_t)(seen + 1u) * left / hist[cut] > (uint32_t)seen * left / hist[cut];
            seen++;
            if (!take)
                continue;
        }
        for (j = 0; j < n0 && !dup; j++)
            dup = cand[j] == c;
        if (!dup)
            cand[n++] = (uint16_t)c;
    }
    return n;
}

typedef struct {
    uint16_t cell;
    int16_t head;
    uint32_t err;
    uint32_t x;        /* the map's exponent (Q8) */
    uint32_t wf;       /* white points' factor (Q16) */
} rm_cand_t;

/* The map's exponent err / (2 sigma^2) (Q8) with sigma^2 the mean of the
 * landmarks' eq.-1 variances. */
static uint32_t fit_x(const fl_relmap_t *s, const fl_relmap_frame_t *f, uint32_t err)
{
    uint64_t s2 = 0;
    uint16_t i;
    for (i = 0; i < f->n; i++) {
        uint64_t sig = s->params.sigma_base_mm + (uint64_t)f->lm[i].range_mm * s->params.sigma_pct / 100u;
        s2 += sig * sig;
    }
    if (s2 == 0)
        return 0;
    /* x_q8 = err * n * 256 / (2 * s2) */
    s2 = ((uint64_t)err * f->n * 128u) / s2;
    return s2 > 65535u ? 65535u : (uint32_t)s2;
}

/* Eq. 3 at one candidate, with the tracked heading kept when the map
 * allows it (a particle that keeps following its odometry is not flipped
 * by a frame whose landmarks fit another heading as well). */
static void search(fl_relmap_t *s, const fl_relmap_frame_t *f, rm_cand_t *k, uint32_t floor_bel)
{
    const fl_relmap_params_t *p = &s->params;
    int ix = k->cell % FL_RELMAP_NX, iy = k->cell / FL_RELMAP_NX;
    int32_t x, y, deg = 0;
    uint32_t e, x2;
    fl_angle_t own = s->head[k->cell], best;
    fl_relmap_cell_pos(s, ix, iy, &x, &y);
    e = fl_relmap_best_heading(s->field, f, x, y, &deg);
    best = fl_angle_from_mdeg(deg * 1000);
    x2 = fit_x(s, f, e);
    k->err = e;
    k->head = best;
    k->x = x2;
    k->wf = 65535u;
    s->stats.searches++;
    /* a tracked particle may change its heading only on a frame of two
     * landmarks or more: one landmark of a repeated kind fits several
     * headings equally (one per map landmark of its kind), and one false
     * landmark would flip it */
    if (s->heading_known && s->bel[k->cell] > floor_bel * RM_TRACK_FLOOR) {
        fl_angle_t d = fl_angle_sub(best, own);
        int32_t dm = fl_angle_to_mdeg(d);
        if (dm < 0)
            dm = -dm;
        if (dm <= (int32_t)p->heading_gate_deg * 1000) {
            k->head = fl_angle_add(own, (fl_angle_t)(d / 4));
        } else {
            /* keep the own heading at its error, or jump at a cost */
            int32_t od = fl_angle_to_mdeg(own);
            int32_t odeg = ((od + (od < 0 ? -500 : 500)) / 1000 + 360) % 360;
            uint32_t eo = fl_relmap_error(s->field, f, x, y, odeg);
            uint32_t t = s->track_frames < RM_JUMP_RAMP ? s->track_frames : RM_JUMP_RAMP;
            uint32_t jump = p->jump_q8 / 3u + (p->jump_q8 - p->jump_q8 / 3u) * t / RM_JUMP_RAMP;
            uint32_t xo = fit_x(s, f, eo), xj = x2 + jump;
            if (xo <= xj || f->n < 2) {
                k->head = own;
                k->x = xo;
                k->err = eo;
            } else {
                k->x = xj;
            }
        }
    }
}

/* Eq. 4 and the white points: the tie set's members get weight
 * (hits + 1) / (most hits + 1); the frame's best pose recorded. */
static void ties(fl_relmap_t *s, const fl_relmap_frame_t *f, const fl_obs_list_t *obs,
                 rm_cand_t *k, uint16_t n)
{
    uint32_t d = UINT32_MAX, slack = (uint32_t)f->n * s->params.tie_mm * s->params.tie_mm;
    uint16_t i, hits[FL_RELMAP_MAX_CAND], most = 0, nt = 0, win = 0, plain = 0;
    for (i = 0; i < n; i++)
        if (k[i].err < d) {
            d = k[i].err;
            plain = i;
        }
    win = plain;
    for (i = 0; i < n; i++) {
        int32_t x, y;
        hits[i] = 0;
        if (k[i].err > d + slack)
            continue;
        nt++;
        fl_relmap_cell_pos(s, k[i].cell % FL_RELMAP_NX, k[i].cell / FL_RELMAP_NX, &x, &y);
        hits[i] = fl_relmap_white_hits(s->field, obs, x, y, k[i].head, s->params.white_tol_mm);
        if (hits[i] > most || (hits[i] == most && k[i].err < k[win].err)) {
            most = hits[i];
            win = i;
        }
    }
    if (nt > 1 && most > 0) {
        for (i = 0; i < n; i++)
            if (k[i].err <= d + slack)
                k[i].wf = (uint32_t)((65535u * (hits[i] + 1u)) / (most + 1u));
        s->stats.ties++;
        if (win != plain)
            s->stats.ties_changed++;
    }
    s->best.valid = true;
    fl_relmap_cell_pos(s, k[win].cell % FL_RELMAP_NX, k[win].cell / FL_RELMAP_NX, &s->best.x_mm,
                       &s->best.y_mm);
    s->best.heading = k[win].head;
    s->best.err_mm2 = k[win].err;
    s->best.n_tied = nt;
    s->best.white_hits = most;
}

/* The new belief; false when nothing is left (every particle at 0).
 * L2 is taken relative to the best candidate's (as L1 to the best
 * particle's): a frame whose landmarks no particle explains well (a false
 * landmark) lowers every particle alike instead of emptying the grid. */
static bool apply(fl_relmap_t *s, rm_cand_t *k, uint16_t n)
{
    uint32_t minl2 = 65535u, xmin = UINT32_MAX, xmax = 0, fl = s->params.floor_q16;
    uint32_t cap = s->params.frame_cap_q8;
    uint64_t mx = 0;
    uint16_t i;
    int c;
    for (i = 0; i < n; i++) {
        if (k[i].x < xmin)
            xmin = k[i].x;
        if (k[i].x > xmax)
            xmax = k[i].x;
    }
    for (i = 0; i < n; i++) {
        uint32_t x = k[i].x - xmin;
        k[i].x = (uint32_t)(((uint64_t)fl_relmap_exp_q16(x < cap ? x : cap) * k[i].wf) >> 16);
    }
    if (n > 0)
        minl2 = fl_relmap_exp_q16(xmax - xmin < cap ? xmax - xmin : cap);
    minl2 /= 2u;
    for (c = 0; c < FL_RELMAP_N; c++) {
        uint64_t v = (uint64_t)s->tmp_bel[c] * minl2;
        if (v > mx)
            mx = v;
    }
    for (i = 0; i < n; i++) {
        uint64_t v = (uint64_t)s->tmp_bel[k[i].cell] * k[i].x;
        if (v > mx)
            mx = v;
    }
    if (mx == 0)
        return false;
    for (c = 0; c < FL_RELMAP_N; c++) {
        uint32_t v = (uint32_t)(((uint64_t)s->tmp_bel[c] * minl2 * 65535u + mx / 2u) / mx);
        s->bel[c] = (uint16_t)(v > fl ? v : fl);
    }
    for (i = 0; i < n; i++) {
        uint16_t c2 = k[i].cell;
        uint32_t v = (uint32_t)(((uint64_t)s->tmp_bel[c2] * k[i].x * 65535u + mx / 2u) / mx);
        s->bel[c2] = (uint16_t)(v > fl ? (v > 65535u ? 65535u : v) : fl);
        s->head[c2] = k[i].head;
    }
    return true;
}

/* The fit of the frame at the believed pose: L1 around the peak particle
 * before the frame (the best of its 3 x 3 neighbourhood). */
static uint32_t peak_fit(const fl_relmap_t *s)
{
    int c, best = 0, ix, iy, dx, dy;
    uint32_t fit = 0;
    for (c = 1; c < FL_RELMAP_N; c++)
        if (s->bel[c] > s->bel[best])
            best = c;
    ix = best % FL_RELMAP_NX;
    iy = best / FL_RELMAP_NX;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++) {
            int jx = ix + dx, jy = iy + dy;
            if (jx >= 0 && jx < FL_RELMAP_NX && jy >= 0 && jy < FL_RELMAP_NY) {
                uint32_t v = (uint16_t)s->tmp_head[jy * FL_RELMAP_NX + jx];
                if (v > fit)
                    fit = v;
            }
        }
    return fit;
}

/* A mode switch: the peak moved farther than a frame's motion (at most a
 * cell) and the grid's diffusion explain.  The new mode grew from the
 * floor, where on a symmetric field its mirror was as possible: the half
 * is no longer known. */
static void note_switch(fl_relmap_t *s)
{
    int c, pk = 0;
    int32_t x, y;
    int64_t dx, dy;
    for (c = 1; c < FL_RELMAP_N; c++)
        if (s->bel[c] > s->bel[pk])
            pk = c;
    fl_relmap_cell_pos(s, pk % FL_RELMAP_NX, pk / FL_RELMAP_NX, &x, &y);
    dx = (int64_t)x - s->last_x_mm;
    dy = (int64_t)y - s->last_y_mm;
    if (s->have_last && dx * dx + dy * dy > (int64_t)1000 * 1000) {
        s->stats.mode_switches++;
        s->track_frames = 0;
        if (s->field->symmetric)
            s->half_known = false;
    }
    s->have_last = true;
    s->last_x_mm = x;
    s->last_y_mm = y;
}

uint16_t fl_relmap_update(fl_relmap_t *s, const fl_obs_list_t *obs)
{
    static const fl_relmap_frame_t empty;   /* const: no mutable state */
    fl_relmap_frame_t f = empty;
    rm_cand_t k[FL_RELMAP_MAX_CAND];
    uint16_t cand[FL_RELMAP_MAX_CAND], n = 0, i, kmax, nin;
    uint32_t max_post, max_l1, thr_post, thr_l1, fit;
    if (s == NULL || s->field == NULL)
        return 0;
    s->stats.updates++;
    if (obs == NULL)
        return 0;
    nin = obs->n < FL_OBS_MAX ? obs->n : FL_OBS_MAX;
    fl_relmap_frame(s, obs, &f);
    s->stats.obs_ignored += (uint32_t)(nin - f.n);
    if (f.n == 0)
        return 0;
    s->best.valid = false;
    eq1(s, &f, &max_post, &max_l1);
    fit = s->ignorance ? 65535u : peak_fit(s);
    s->fit_q16 = (uint16_t)(fit > 65535u ? 65535u : fit);
    kmax = s->params.max_cand < FL_RELMAP_MAX_CAND ? s->params.max_cand : FL_RELMAP_MAX_CAND;
    thr_post = (uint32_t)(((uint64_t)max_post * s->params.cand_q16) >> 16);
    thr_l1 = (uint32_t)(((uint64_t)max_l1 * s->params.cand_q16) >> 16);
    /* three quarters of the relative maps for the belief's best, a
     * quarter for the frame's own best (a particle the belief had given
     * up: recovery after a kidnap) */
    n = select_top(s, false, thr_post, (uint16_t)(kmax - kmax / 4u), cand, 0);
    n = select_top(s, true, thr_l1, (uint16_t)(kmax - n), cand, n);
    for (i = 0; i < n; i++) {
        k[i].cell = cand[i];
        search(s, &f, &k[i], s->params.floor_q16);
    }
    if (n > 0)
        ties(s, &f, obs, k, n);
    if (!apply(s, k, n)) {
        fl_relmap_reset_ignorance(s);
        s->stats.empty_resets++;
        return 0;
    }
    s->ignorance = false;
    s->heading_known = true;
    s->since_obs = 0;
    if (s->track_frames < UINT16_MAX)
        s->track_frames++;
    note_switch(s);
    s->stats.obs_used += f.n;
    if (s->fit_q16 < s->params.kidnap_q16) {
        if (++s->bad_frames >= s->params.kidnap_frames) {
            /* the believed pose has not explained the landmarks for a
             * while: start again, and the half told before no longer
             * holds */
            s->prior_half = 0;
            s->prior_pose = false;
            fl_relmap_reset_ignorance(s);
            s->stats.resets--;
            s->stats.kidnaps++;
        }
    } else {
        s->bad_frames = 0;
    }
    return f.n;
}
