/*
 * src/loc/fuzzy_negative.c - negative information of the fuzzy position grid
 * (fl_fuzzy_update_view: landmarks the view should show and no observation
 * explains).
 *
 * Negative information (fl_fuzzy_update_view, after the observations):
 * the frame's view (obs.h) is a ground sector in which every landmark
 * would have been seen.  Without a track, every live cell at least
 * neg_min_q8 high with a narrow heading loses neg_q8 of its height per
 * map landmark its pose puts in the sector that no observation explains
 * (at most neg_max, never below its bias: the other headings keep their
 * possibility); while tracked, the tracked pose is tested and a frame
 * that explains none of its neg_kidnap or more expected landmarks counts
 * as a contradiction.  Cost: live cells x landmarks (integer tests, no
 * root or atan2 unless observations may explain a landmark).
 */
#include "fieldloc/fuzzy.h"
#include "fuzzy_int.h"

#include <string.h>


typedef struct {
    const fl_obs_list_t *obs;    /* the frame's observations (may be NULL) */
    int32_t near_mm, far_mm;     /* the view's range interval */
    fl_angle_t mid;              /* the view's centre bearing */
    int32_t half;                /* its half width (binary angle, < 90 deg) */
    int32_t r_hi;                /* distances d with near + mr(d) <= d <= */
    uint32_t s_lo, s_hi;         /* far - mr(d), mr(d) = margin + neg_range
                                    x d: r_lo^2 <= d^2 <= r_hi^2 */
} negctx_t;

/* Posts, beacons and nets are told apart from line features (seed 004's
 * corner features among them); within each group any kind explains any
 * (vision confuses L, T and X). */
static bool neg_line_kind(fl_landmark_kind_t k)
{
    return k != FL_LM_POST && k != FL_LM_BEACON && k != FL_LM_NET;
}

/* At most this many expected landmarks of one pose are matched against
 * the observations (more are not counted; the maps have at most 25). */
#define NEG_MAX_EXPECTED 32

/* Landmarks of the map that pose (px, py, h) puts inside the view (range
 * margin neg_margin + neg_range x distance, bearing margin neg_bearing +
 * tol) in *expected, and how many of them no observation explains
 * (returned, at most cap; without observations the search stops at cap
 * expected landmarks, *expected then counts only those).  Each
 * observation explains at most one of
 * them, the nearest in bearing within its tolerances (kind group, range
 * within the range margin, bearing within the bearing margin), so that a
 * T seen explains the T a hypothesis put it on, not also the L 9 degrees
 * beside it.  The view tests avoid roots and atan2: the distance by its
 * square against the frame's bounds (negctx_t), the bearing by the
 * landmark vector turned into the view's centre direction (x' > 0 and
 * |y'| cos A <= x' sin A, A = half - margin); root and atan2 only for
 * expected landmarks when there are observations.  Scaling: |dx|, |dy|
 * <= r_hi <= 20000 before squaring, so dx^2 + dy^2 < 2^30; x', y' (Q15)
 * < 2^31 in int64, times a Q15 sine < 2^46.  Stack: NEG_MAX_EXPECTED x
 * 12 B. */
typedef struct {
    int32_t x_mm, y_mm;          /* the pose */
    fl_angle_t h;
    int32_t tol;                 /* its heading uncertainty */
    int cap;
} negpose_t;

static int neg_count(const fl_fuzzy_t *g, const negctx_t *x, const negpose_t *ps, int *expected)
{
    int32_t px = ps->x_mm, py = ps->y_mm, tol = ps->tol;
    fl_angle_t h = ps->h;
    int cap = ps->cap;
    const fl_field_t *f = g->field;
    const fl_fuzzy_params_t *p = &g->params;
    int32_t bt = fz_clamp32(p->neg_bearing, 0, FZ_HT) + tol;
    int64_t c, sn, ca, sa;
    fl_angle_t dir;
    struct {
        int32_t d, mr;
        fl_angle_t b;
        bool line, explained;
    } ex[NEG_MAX_EXPECTED];
    uint16_t i, k, nobs = 0;
    int n = 0, e = 0, j;
    *expected = 0;
    if (x->obs != NULL)
        nobs = x->obs->n > FL_OBS_MAX ? (uint16_t)FL_OBS_MAX : x->obs->n;
    if (bt >= x->half || x->s_lo > x->s_hi)
        return 0;                      /* nothing lies surely inside */
    dir = fl_angle_add(h, x->mid);     /* the view's centre, field frame */
    c = fl_cos_q15(dir);
    sn = fl_sin_q15(dir);
    ca = fl_cos_q15((fl_angle_t)(x->half - bt));
    sa = fl_sin_q15((fl_angle_t)(x->half - bt));
    for (i = 0; i < f->n_landmarks && e < NEG_MAX_EXPECTED && (nobs > 0 || e < cap); i++) {
        const fl_landmark_t *lm = &f->landmarks[i];
        int32_t dx = lm->x_mm - px, dy = lm->y_mm - py;
        int64_t xr, yr;
        uint32_t s2;
        if (fz_iabs(dx) > x->r_hi || fz_iabs(dy) > x->r_hi)
            continue;
        s2 = (uint32_t)(dx * dx) + (uint32_t)(dy * dy);
        if (s2 < x->s_lo || s2 > x->s_hi)
            continue;
        xr = dx * c + dy * sn;
        yr = dy * c - dx * sn;
        if (xr <= 0 || (yr < 0 ? -yr : yr) * ca > xr * sa)
            continue;
        ex[e].explained = false;
        if (nobs > 0) {
            ex[e].d = (int32_t)fl_isqrt32(s2);
            ex[e].mr = fz_clamp32(p->neg_margin_mm, 0, 5000) +
                       (int32_t)(((uint32_t)ex[e].d *
                                  (p->neg_range_q8 > 256 ? 256u : p->neg_range_q8)) >> 8);
            ex[e].b = fz_asub(fl_atan2(dy, dx), h);
            ex[e].line = neg_line_kind(lm->kind);
        }
        e++;
    }
    for (k = 0; k < nobs; k++) {
        const fl_obs_t *o = &x->obs->obs[k];
        int32_t best = bt + 1;
        int jb = -1;
        if (o->confidence == 0 || (unsigned)o->kind >= (unsigned)FL_LM_KIND_COUNT ||
            o->range_mm < 0 || o->range_mm > 2 * FL_OBS_MAX_RANGE_MM)
            continue;
        for (j = 0; j < e; j++) {
            int32_t db = fz_iabs(fz_asub(o->bearing, ex[j].b));
            if (ex[j].line == neg_line_kind(o->kind) && db < best &&
                fz_iabs(o->range_mm - ex[j].d) <= ex[j].mr) {
                best = db;
                jb = j;
            }
        }
        if (jb >= 0)
            ex[jb].explained = true;
    }
    for (j = 0; j < e && n < cap; j++)
        n += !ex[j].explained;
    *expected = e;
    return n;
}

/* Every live cell with a known heading: height x (1 - neg_q8)^n, at least
 * the bias (n unexplained landmarks, at most neg_max); then normalized.
 * On an exactly symmetric belief the first half of the rows is done and
 * mirrored (the map is symmetric, so the mirror pose expects the mirrored
 * landmarks).  Cost: live cells with a narrow heading x landmarks within
 * the view's range (one isqrt and one atan2 each) x observations. */
static void neg_apply(fl_fuzzy_t *g, const negctx_t *x)
{
    const fl_fuzzy_params_t *p = &g->params;
    int32_t hmax = fz_clamp32(p->neg_head_max, 0, FZ_HT);
    uint32_t keep = 256u - p->neg_q8, maxh = 0;
    int iy, ix, ny_upd = g->sym_exact ? (g->ny + 1) / 2 : g->ny;
    int cap = p->neg_max;
    for (iy = 0; iy < ny_upd; iy++) {
        fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * g->nx];
        int32_t cy = g->y0_mm + iy * FZ_CELL + FZ_HALF;
        for (ix = g->row_lo[iy]; ix <= g->row_hi[iy]; ix++) {
            fl_fuzzy_cell_t *c = &row[ix];
            int32_t tol;
            int e, n, k;
            uint32_t hh;
            if (c->height == 0)
                continue;
            /* the heading is within the core, or not far into the slope */
            tol = (int32_t)(c->core >= FL_FUZZY_WFULL || c->slope >= FL_FUZZY_WFULL
                                ? FZ_HT : ((int32_t)c->core + (int32_t)c->slope / 2) * FL_FUZZY_AUNIT);
            if (c->height > c->bias && c->height >= p->neg_min_q8 && tol <= hmax && cap > 0) {
                negpose_t ps;
                ps.x_mm = g->x0_mm + ix * FZ_CELL + FZ_HALF + c->off_x_mm;
                ps.y_mm = cy + c->off_y_mm;
                ps.h = c->centre;
                ps.tol = tol;
                ps.cap = cap;
                n = neg_count(g, x, &ps, &e);
                hh = c->height;
                for (k = 0; k < n; k++)
                    hh = (hh * keep) >> 8;
                c->height = (uint8_t)(hh > c->bias ? hh : c->bias);
            }
            if (c->height > maxh)
                maxh = c->height;
        }
    }
    if (g->sym_exact)
        fl_fuzzy_internal_mirror_copy(g);
    fl_fuzzy_internal_normalize(g, maxh);
}

uint16_t fl_fuzzy_update_view(fl_fuzzy_t *g, const fl_obs_list_t *obs,
                              const fl_obs_view_t *view)
{
    const fl_fuzzy_params_t *p;
    uint16_t used = fl_fuzzy_update(g, obs);
    negctx_t x;
    int32_t width;
    if (!fz_ready(g) || view == NULL || !view->valid)
        return used;
    p = &g->params;
    width = fl_angle_sub(view->bearing_left, view->bearing_right);
    if (width <= 0 || view->near_mm < 0 || view->far_mm <= view->near_mm ||
        view->far_mm > FL_OBS_MAX_RANGE_MM)
        return used;                   /* not a view: ignored */
    x.obs = obs;
    x.near_mm = view->near_mm;
    x.far_mm = view->far_mm;
    x.half = width / 2;
    x.mid = fl_angle_add(view->bearing_right, (fl_angle_t)x.half);
    {
        /* d >= near + m + rq d  <=>  d >= (near + m) / (1 - rq);
         * d <= far - m - rq d   <=>  d <= (far - m) / (1 + rq) (Q8) */
        uint32_t rq = p->neg_range_q8 > 255 ? 255u : p->neg_range_q8;
        int32_t m = fz_clamp32(p->neg_margin_mm, 0, 5000);
        int32_t lo = (int32_t)((((uint32_t)(view->near_mm + m) << 8) + (255u - rq)) / (256u - rq));
        int32_t hi = view->far_mm - m < 0
                         ? -1 : (int32_t)(((uint32_t)(view->far_mm - m) << 8) / (256u + rq));
        if (lo > 30000)                /* (rq near 1): nothing; no wrap */
            lo = 30000;
        x.r_hi = hi;
        x.s_lo = (uint32_t)lo * (uint32_t)lo;
        x.s_hi = hi < 0 ? 0u : (uint32_t)hi * (uint32_t)hi;
        if (hi < lo) {
            x.s_lo = 1u;
            x.s_hi = 0u;
        }
    }
    if (g->track_valid && p->neg_kidnap > 0) {
        int e = 0, n;
        negpose_t ps;
        ps.x_mm = g->track_x_mm;
        ps.y_mm = g->track_y_mm;
        ps.h = g->track_heading;
        ps.tol = 0;
        ps.cap = 255;
        n = neg_count(g, &x, &ps, &e);
        if (e >= p->neg_kidnap && n == e) {
            /* the tracked pose should see landmarks and the frame shows
             * none of them: a contradiction, as a deferred observation */
            fz_update_consistency(g, 0);
            if (g->contra_run < UINT8_MAX)
                g->contra_run++;
            if (g->contra_rate_q8 < UINT16_MAX - 32u)
                g->contra_rate_q8 = (uint16_t)(g->contra_rate_q8 + 32u);
            (void)fz_kidnapped(g);
        }
    }
    if (p->neg_q8 > 0 && (!g->track_valid || p->neg_track))
        neg_apply(g, &x);
    return used;
}
