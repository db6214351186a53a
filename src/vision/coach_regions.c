/*
 * src/vision/coach_regions.c - connected jersey regions (coach.h, step 4):
 * runs of set bits per row of each jersey mask, joined with the runs of the
 * row above that share a column (4-connectivity) by union-find, and each
 * region's pixel sums for its least-squares line.
 *
 * Bounds: at most FL_COACH_MAX_RUNS runs (the rest of the frame's runs are
 * counted in runs_dropped, not stored: a region may then lose its lower
 * part) and FL_COACH_MAX_REGIONS regions (largest-first selection is not
 * attempted: regions beyond the capacity, in run order, are counted).
 * Scaling: u < 2^12, v < 2^12 (FL_IMAGE_MAX_DIM); a run's sums: sum u <
 * 2^24, sum u^2 < 2^36, sum u v < 2^36; a region's (at most 2^24 pixels):
 * su, sv < 2^36, suu, suv, svv < 2^48, all int64.
 */
#include "coach_int.h"

static uint16_t find_root(fl_coach_run_t *runs, uint16_t i)
{
    while (runs[i].parent != i) {
        runs[i].parent = runs[runs[i].parent].parent;   /* path halving */
        i = runs[i].parent;
    }
    return i;
}

static void join(fl_coach_run_t *runs, uint16_t a, uint16_t b)
{
    uint16_t ra = find_root(runs, a), rb = find_root(runs, b);
    if (ra < rb)
        runs[rb].parent = ra;
    else if (rb < ra)
        runs[ra].parent = rb;
}

/* Append run u0..u1 of row v (team t) and join it with the overlapping
 * runs [*prev0, prev1) of the row above; false when full. */
static bool add_run(fl_coach_t *c, int32_t u0, int32_t u1, int32_t v, int32_t t,
                    uint16_t *prev0, uint16_t prev1)
{
    uint16_t i = c->n_runs, k;
    fl_coach_run_t *r;
    if (c->n_runs >= FL_COACH_MAX_RUNS)
        return false;
    r = &c->runs[i];
    r->u0 = (int16_t)u0;
    r->u1 = (int16_t)u1;
    r->v = (int16_t)v;
    r->parent = i;
    r->region = FL_COACH_NO_REGION;
    r->team = (uint16_t)t;
    while (*prev0 < prev1 && c->runs[*prev0].u1 < u0)
        (*prev0)++;     /* runs above that end left of this one: done */
    for (k = *prev0; k < prev1 && c->runs[k].u0 <= u1; k++)
        join(c->runs, i, k);
    c->n_runs++;
    return true;
}

/* Runs of one mask row (team t); runs beyond the store are counted. */
static void row_runs(fl_coach_t *c, const uint32_t *row, int32_t w, int32_t v, int32_t t,
                     uint16_t prev0, uint16_t prev1, fl_coach_result_t *out)
{
    int32_t u = 0;
    while (u < w) {
        int32_t u0;
        uint32_t x = row[u >> 5] >> (u & 31);
        if (x == 0) {
            u = (u | 31) + 1;      /* rest of this word clear */
            continue;
        }
        if ((x & 1u) == 0) {
            u++;
            continue;
        }
        u0 = u;
        while (u < w && ((row[u >> 5] >> (u & 31)) & 1u))
            u++;
        if (!add_run(c, u0, u - 1, v, t, &prev0, prev1) && out->runs_dropped < 0xFFFFu)
            out->runs_dropped++;
    }
}

static void run_sums(fl_coach_region_t *g, const fl_coach_run_t *r)
{
    int64_t u0 = r->u0, u1 = r->u1, v = r->v, len = u1 - u0 + 1;
    int64_t su = len * (u0 + u1) / 2;
    int64_t suu = (u1 * (u1 + 1) * (2 * u1 + 1) - (u0 - 1) * u0 * (2 * u0 - 1)) / 6;
    g->n += (uint32_t)len;
    g->su += su;
    g->sv += len * v;
    g->suu += suu;
    g->suv += su * v;
    g->svv += len * v * v;
    if (r->u0 < g->u_min)
        g->u_min = r->u0;
    if (r->u1 > g->u_max)
        g->u_max = r->u1;
    if (r->v < g->v_min)
        g->v_min = r->v;
    if (r->v > g->v_max)
        g->v_max = r->v;
}

/* Each root run opens a region (in run order); every run adds its sums. */
static void gather(fl_coach_t *c, fl_coach_result_t *out)
{
    uint16_t i;
    c->n_regions = 0;
    for (i = 0; i < c->n_runs; i++) {
        fl_coach_run_t *r = &c->runs[i];
        uint16_t root = find_root(c->runs, i);
        if (root == i) {
            fl_coach_region_t *g;
            if (c->n_regions >= FL_COACH_MAX_REGIONS) {
                if (out->regions_dropped < 0xFFFFu)
                    out->regions_dropped++;
                continue;
            }
            r->region = c->n_regions++;
            g = &c->regions[r->region];
            g->su = g->sv = g->suu = g->suv = g->svv = 0;
            g->n = 0;
            g->u_min = g->v_min = INT16_MAX;
            g->u_max = g->v_max = -1;
            g->team = (uint8_t)r->team;
        } else {
            r->region = c->runs[root].region;
        }
        if (r->region != FL_COACH_NO_REGION)
            run_sums(&c->regions[r->region], r);
    }
}

/* Boxes of a and b, each grown by m pixels, overlap. */
static bool near_boxes(const fl_coach_region_t *a, const fl_coach_region_t *b, int32_t m)
{
    return a->u_min - m <= b->u_max && b->u_min - m <= a->u_max && a->v_min - m <= b->v_max &&
           b->v_min - m <= a->v_max;
}

/* Parts of one jersey: an arm or a leg of the robot in front of its
 * jersey splits it, and each part alone would give a line along one side
 * of the body.  Regions of one team whose boxes come within the smaller
 * one's height (an arm seen from the side hides up to ~80 mm of a 115 mm
 * high jersey's width) are joined into the larger; the joined one is left
 * with n = 0.
 * Two robots of one team whose jerseys overlap in the image become one
 * (the front one's feet are found).  At most FL_COACH_MAX_REGIONS^2 / 2
 * box tests, repeated while a join happens (at most REGIONS - 1 times). */
static void join_parts(fl_coach_t *c)
{
    bool again = true;
    while (again) {
        uint16_t i, j;
        again = false;
        for (i = 0; i < c->n_regions; i++)
            for (j = (uint16_t)(i + 1); j < c->n_regions; j++) {
                fl_coach_region_t *a = &c->regions[i], *b = &c->regions[j], *big, *sm;
                int32_t ha, hb, m;
                if (a->n == 0 || b->n == 0 || a->team != b->team)
                    continue;
                ha = a->v_max - a->v_min + 1;
                hb = b->v_max - b->v_min + 1;
                m = ha < hb ? ha : hb;
                if (!near_boxes(a, b, m < 2 ? 2 : m))
                    continue;
                big = a->n >= b->n ? a : b;
                sm = big == a ? b : a;
                big->n += sm->n;
                big->su += sm->su;
                big->sv += sm->sv;
                big->suu += sm->suu;
                big->suv += sm->suv;
                big->svv += sm->svv;
                big->u_min = sm->u_min < big->u_min ? sm->u_min : big->u_min;
                big->u_max = sm->u_max > big->u_max ? sm->u_max : big->u_max;
                big->v_min = sm->v_min < big->v_min ? sm->v_min : big->v_min;
                big->v_max = sm->v_max > big->v_max ? sm->v_max : big->v_max;
                sm->n = 0;
                again = true;
            }
    }
}

void fl_coach_int_regions(fl_coach_t *c, int32_t w, int32_t h, fl_coach_result_t *out)
{
    int32_t t, v, words = fl_coach_words(w);
    c->n_runs = 0;
    for (t = 0; t < 2; t++) {
        uint16_t prev0 = c->n_runs, prev1 = c->n_runs;
        for (v = 0; v < h; v++) {
            uint16_t start = c->n_runs;
            row_runs(c, c->mask[t] + (size_t)v * (size_t)words, w, v, t, prev0, prev1, out);
            prev0 = start;
            prev1 = c->n_runs;
        }
    }
    gather(c, out);
    join_parts(c);
}
