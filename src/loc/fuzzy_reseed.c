/*
 * src/loc/fuzzy_reseed.c - the fuzzy grid's re-seeding from an observer's
 * report (fuzzy.h fl_fuzzy_reseed: an intersection with a disc around the
 * foot, seed 003 section 3.4's re-sprinkling for a possibility grid) and
 * the belief's spread (fl_fuzzy_spread_mm).
 */
#include "fuzzy_int.h"

#include <string.h>

/* pi/8 (seed 003's heading sd) and 90 deg, binary angles. */
#define RESEED_SD_H 4096
#define RESEED_SD_H_MAX FL_ANGLE_90

/* The disc's possibility at distance d from the foot, Q8: 1 within sd (the
 * report's error is that large at least a third of the time), falling
 * linearly to 0 at 3 sd (beyond, the foot is out of the question). */
static uint32_t disc_q8(uint32_t d, int32_t sd)
{
    uint32_t s = (uint32_t)sd;
    if (d <= s)
        return 255u;
    if (d >= 3u * s)
        return 0u;
    return (uint32_t)(((uint64_t)(3u * s - d) * 255u + s) / (2u * s));
}

/* Where cell (ix, iy)'s content is, and its distance to (x, y). */
static uint32_t cell_dist(const fl_fuzzy_t *g, int ix, int iy, int32_t x, int32_t y)
{
    const fl_fuzzy_cell_t *c = &g->cell[(size_t)iy * g->nx + (size_t)ix];
    return fl_hypot(x - (fz_centre_x(g, ix) + c->off_x_mm), y - (fz_centre_y(g, iy) + c->off_y_mm));
}

/* Every cell times the disc (product, rounded up as the updates round:
 * never rules out what the disc allows); returns the new peak. */
static uint32_t intersect_disc(fl_fuzzy_t *g, const fl_obs_report_t *r)
{
    int ix, iy;
    uint32_t peak = 0;
    for (iy = 0; iy < g->ny; iy++)
        for (ix = 0; ix < g->nx; ix++) {
            fl_fuzzy_cell_t *c = &g->cell[(size_t)iy * g->nx + (size_t)ix];
            uint32_t v;
            if (c->height == 0)
                continue;
            v = disc_q8(cell_dist(g, ix, iy, r->x_mm, r->y_mm), r->sd_mm);
            if (v == 0u) {
                memset(c, 0, sizeof *c);
                continue;
            }
            c->height = fz_mul8_ceil(c->height, v);
            c->bias = fz_mul8_ceil(c->bias, v);
            if (c->height > peak)
                peak = c->height;
        }
    return peak;
}

/* The disc alone, heading trapezoid t, the content at the foot where the
 * foot's cell is; returns the peak. */
static uint32_t paint_disc(fl_fuzzy_t *g, const fl_obs_report_t *r, fl_fuzzy_trap_t *t)
{
    int ix0, ix1, iy0, iy1, ix, iy;
    uint32_t peak = 0;
    memset(g->cell, 0, sizeof(fl_fuzzy_cell_t) * (size_t)g->nx * g->ny);
    fz_window(g, r->x_mm, r->y_mm, 3 * r->sd_mm, &ix0, &ix1, &iy0, &iy1);
    for (iy = iy0; iy <= iy1; iy++)
        for (ix = ix0; ix <= ix1; ix++) {
            fl_fuzzy_cell_t *c = &g->cell[(size_t)iy * g->nx + (size_t)ix];
            int32_t ox = fz_clamp32(r->x_mm - fz_centre_x(g, ix), -FZ_HALF, FZ_HALF - 1);
            int32_t oy = fz_clamp32(r->y_mm - fz_centre_y(g, iy), -FZ_HALF, FZ_HALF - 1);
            uint32_t v;
            c->off_x_mm = (int8_t)ox;
            c->off_y_mm = (int8_t)oy;
            v = disc_q8(cell_dist(g, ix, iy, r->x_mm, r->y_mm), r->sd_mm);
            if (v == 0u) {
                memset(c, 0, sizeof *c);
                continue;
            }
            t->height_q16 = v * 257u;
            fl_fuzzy_trap_to_cell(t, c);
            c->off_x_mm = (int8_t)ox;
            c->off_y_mm = (int8_t)oy;
            if (c->height > peak)
                peak = c->height;
        }
    return peak;
}

fl_status_t fl_fuzzy_reseed(fl_fuzzy_t *g, const fl_obs_report_t *r)
{
    fl_fuzzy_estimate_t e;
    fl_fuzzy_trap_t t;
    fl_status_t st;
    uint32_t peak;
    int32_t sh;
    bool known;
    if (!fz_ready(g))
        return FL_ERR_STATE;
    st = fl_obs_report_check(r, g->field);
    if (st != FL_OK) {
        g->stats.reseeds_refused = fz_sat_inc(g->stats.reseeds_refused);
        return st;
    }
    (void)fl_fuzzy_estimate(g, &e);      /* the previous heading */
    sh = fz_iabs(e.sd_heading);
    known = !e.ignorance && sh < RESEED_SD_H_MAX;
    peak = intersect_disc(g, r);
    if (peak < g->params.min_height_q8 || peak == 0u) {
        /* the belief excluded the foot: the report wins */
        t.centre = e.heading;
        t.core = known ? (sh < RESEED_SD_H ? RESEED_SD_H : sh) : FL_FUZZY_HALF_TURN;
        t.slope = known ? 2 * t.core : 0;
        t.bias_q16 = 0;
        peak = paint_disc(g, r, &t);
        g->stats.reseed_replaced = fz_sat_inc(g->stats.reseed_replaced);
    }
    fl_fuzzy_internal_normalize(g, peak);
    /* as a pose reset: the foot tracked, the half known, the consistency
     * fresh; the disc has no mirror.  The foot is tracked even when the
     * heading is unknown: on a symmetric field the next update makes the
     * mirror as possible, and only the track's position keeps the estimate
     * at the foot (the estimate takes the cells' dominant heading when
     * they disagree with the track's) */
    g->blur_acc_mm = 0;
    g->consistency_q16 = 65535;
    g->contra_run = 0;
    g->contra_rate_q8 = 0;
    g->sym_exact = false;
    g->half_known = true;
    g->track_valid = true;
    g->track_x_mm = fz_clamp32(r->x_mm, -g->half_x_mm, g->half_x_mm);
    g->track_y_mm = fz_clamp32(r->y_mm, -g->half_y_mm, g->half_y_mm);
    g->track_heading = e.heading;
    g->stats.reseeds = fz_sat_inc(g->stats.reseeds);
    return FL_OK;
}

/* Cell (ix, iy)'s content position, folded onto the track's side of the
 * mirror when fold. */
static void spread_pos(const fl_fuzzy_t *g, int ix, int iy, bool fold, int64_t *x, int64_t *y)
{
    const fl_fuzzy_cell_t *c = &g->cell[(size_t)iy * g->nx + (size_t)ix];
    int64_t px = fz_centre_x(g, ix) + c->off_x_mm, py = fz_centre_y(g, iy) + c->off_y_mm;
    if (fold) {
        int64_t dx = px - g->track_x_mm, dy = py - g->track_y_mm;
        int64_t ex = -px - g->track_x_mm, ey = -py - g->track_y_mm;
        if (ex * ex + ey * ey < dx * dx + dy * dy) {
            px = -px;
            py = -py;
        }
    }
    *x = px;
    *y = py;
}

/* Scaling: positions below 2^15, heights below 2^8, at most 2^16 cells:
 * sums of w x below 2^39, of w dx^2 below 2^56. */
uint32_t fl_fuzzy_spread_mm(const fl_fuzzy_t *g)
{
    int ix, iy;
    uint64_t w = 0, sq = 0;
    int64_t sx = 0, sy = 0, mx, my, x, y;
    bool fold;
    if (!fz_ready(g))
        return UINT32_MAX;
    fold = g->track_valid && g->field->symmetric;
    for (iy = 0; iy < g->ny; iy++)
        for (ix = 0; ix < g->nx; ix++) {
            uint32_t h = g->cell[(size_t)iy * g->nx + (size_t)ix].height;
            if (h == 0u)
                continue;
            spread_pos(g, ix, iy, fold, &x, &y);
            w += h;
            sx += (int64_t)h * x;
            sy += (int64_t)h * y;
        }
    if (w == 0u)
        return 0;
    mx = sx / (int64_t)w;
    my = sy / (int64_t)w;
    for (iy = 0; iy < g->ny; iy++)
        for (ix = 0; ix < g->nx; ix++) {
            uint32_t h = g->cell[(size_t)iy * g->nx + (size_t)ix].height;
            if (h == 0u)
                continue;
            spread_pos(g, ix, iy, fold, &x, &y);
            x -= mx;
            y -= my;
            sq += (uint64_t)h * (uint64_t)(x * x + y * y);
        }
    return fl_isqrt64(sq / w);
}
