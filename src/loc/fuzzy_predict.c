/*
 * src/loc/fuzzy_predict.c - the predict step of the fuzzy position grid
 * (motion model, translation, dilation).
 *
 * Predict.  Odometry (dx, dy, dtheta), robot frame, is split into
 * sub-steps of at most CELL/2 - 2 mm.  In each sub-step every live cell's
 * contents move by the step rotated by the cell's own heading (trapezoid
 * centre): the sub-cell offset absorbs the motion and the contents hop to
 * a neighbour cell when the offset leaves [-CELL/2, CELL/2).  Cells whose
 * heading core is at least params.wide_core do not move (direction
 * unknown; the blur covers them).  Contents landing on the same cell are
 * merged by fuzzy union (outer envelope), contents leaving the grid are
 * lost.  The last sub-step also turns every trapezoid by dtheta and widens
 * its core by the accumulated heading uncertainty (odo_rot_q8 |dtheta| +
 * odo_rot_per_m x distance, remainder carried).  Then the grid is dilated
 * (3x3 separable max, neighbour factor kappa): every call with kappa
 * growing with this call's position uncertainty (keeps the neighbours of
 * a mode possible so that observations can move it), plus one crisp
 * dilation (kappa 1) per params.blur_step_mm of accumulated uncertainty
 * (the support grows with the motion).  An exactly symmetric belief (symmetric
 * field, g->sym_exact) is kept exactly symmetric: the first half of the
 * cells, mirrored, replaces the second (the two differ by rounding only:
 * offsets clamped differently at the cell border, ties of the rotation),
 * so that the update may work on half the grid.
 * No aliasing: the translation scatters input row r into output rows
 * r-1..r+1 held in a ring of 3 row buffers (scratch.ring); output row r-1 is
 * written back after input row r is read, so no input row is overwritten
 * before it is consumed.  Memory: 3 x FL_FUZZY_MAX_NX x 8 B = 2,496 B for
 * the SPL grid, instead of a 61,568 B double buffer.  The dilation uses two
 * of those rows (the originals of the previous and the current row).
 * Cost: O(cells) per sub-step (one sin/cos table read per live cell) +
 * O(cells) per dilation.
 */
#include "fieldloc/fuzzy.h"
#include "fuzzy_int.h"

#include <string.h>

#define ANGLE_PER_RAD 10430   /* 65536 / (2 pi), rounded */

/* Merge src into the output slot dst (fuzzy union; offsets of the higher). */
static void merge_cell(fl_fuzzy_cell_t *dst, const fl_fuzzy_cell_t *src)
{
    fl_fuzzy_trap_t a, b, u;
    int8_t ox, oy;
    if (dst->height == 0) {
        *dst = *src;
        return;
    }
    if (src->height <= dst->bias)
        return;
    if (dst->height <= src->bias) {
        *dst = *src;
        return;
    }
    ox = src->height > dst->height ? src->off_x_mm : dst->off_x_mm;
    oy = src->height > dst->height ? src->off_y_mm : dst->off_y_mm;
    fl_fuzzy_trap_from_cell(dst, &a);
    fl_fuzzy_trap_from_cell(src, &b);
    fl_fuzzy_trap_union(&a, &b, &u);
    fl_fuzzy_trap_to_cell(&u, dst);
    dst->off_x_mm = ox;
    dst->off_y_mm = oy;
}

/* One sub-step: move by (dx, dy) (|(dx, dy)| < CELL/2), then turn and
 * widen.  Returns the highest height written back.
 * Scaling and overflow: |dx|, |dy| < 128; dx * cos_q15 < 2^22; offsets
 * + motion in [-CELL, CELL). */
static uint32_t translate(fl_fuzzy_t *g, int32_t dx, int32_t dy,
                          fl_angle_t turn, uint32_t widen)
{
    fl_fuzzy_cell_t (*ring)[FL_FUZZY_MAX_NX] = g->scratch.ring;
    int nx = g->nx, ny = g->ny, r, ix;
    size_t rowbytes = sizeof(fl_fuzzy_cell_t) * (size_t)nx;
    bool moving = dx != 0 || dy != 0;
    uint32_t wide = g->params.wide_core;
    uint32_t maxh = 0;
    memset(ring[0], 0, rowbytes);
    memset(ring[1], 0, rowbytes);
    for (r = 0; r < ny; r++) {
        const fl_fuzzy_cell_t *row = &g->cell[(size_t)r * (size_t)nx];
        if (r + 1 < ny)
            memset(ring[(r + 1) % 3], 0, rowbytes);
        for (ix = 0; ix < nx; ix++) {
            fl_fuzzy_cell_t c = row[ix];
            int sx = 0, sy = 0, dr, dc;
            if (c.height == 0)
                continue;
            if (moving && (uint32_t)c.core * FL_FUZZY_AUNIT < wide) {
                int32_t cs = fl_cos_q15(c.centre), sn = fl_sin_q15(c.centre);
                int32_t mx = (dx * cs - dy * sn + 16384) >> 15;
                int32_t my = (dx * sn + dy * cs + 16384) >> 15;
                int32_t px = c.off_x_mm + mx, py = c.off_y_mm + my;
                sx = px >= FZ_HALF ? 1 : px < -FZ_HALF ? -1 : 0;
                sy = py >= FZ_HALF ? 1 : py < -FZ_HALF ? -1 : 0;
                px = fz_clamp32(px - sx * FZ_CELL, -FZ_HALF, FZ_HALF - 1);
                py = fz_clamp32(py - sy * FZ_CELL, -FZ_HALF, FZ_HALF - 1);
                c.off_x_mm = (int8_t)px;
                c.off_y_mm = (int8_t)py;
            }
            if (turn != 0)
                c.centre = fl_angle_add(c.centre, turn);
            if (widen != 0 && c.core < FL_FUZZY_WFULL) {
                uint32_t w = c.core + widen;
                c.core = (uint8_t)(w > FL_FUZZY_WFULL ? FL_FUZZY_WFULL : w);
            }
            dr = r + sy;
            dc = ix + sx;
            if (dr < 0 || dr >= ny || dc < 0 || dc >= nx)
                continue;                       /* left the grid */
            merge_cell(&ring[(dr + 3) % 3][dc], &c);
        }
        if (r >= 1) {
            const fl_fuzzy_cell_t *o = ring[(r - 1) % 3];
            memcpy(&g->cell[(size_t)(r - 1) * (size_t)nx], o, rowbytes);
            for (ix = 0; ix < nx; ix++)
                if (o[ix].height > maxh)
                    maxh = o[ix].height;
        }
    }
    {
        const fl_fuzzy_cell_t *o = ring[(ny - 1) % 3];
        memcpy(&g->cell[(size_t)(ny - 1) * (size_t)nx], o, rowbytes);
        for (ix = 0; ix < nx; ix++)
            if (o[ix].height > maxh)
                maxh = o[ix].height;
    }
    return maxh;
}

/* Neighbour n (already a copy) offered to cell *c with factor kappa (Q8,
 * 256 = crisp): "the robot may be one cell further".  The higher of c and
 * kappa x n wins (its trapezoid and its offset: the content moved by one
 * cell keeps its place within the cell); the bias is the higher of the
 * two.  Not the envelope of the union: neighbours of a mode
 * with slightly different headings would widen and drag every trapezoid of
 * the mode at every step (the update's intersection is the exact outer
 * envelope; this is the motion model). */
static void offer(fl_fuzzy_cell_t *c, const fl_fuzzy_cell_t *n, uint32_t kappa)
{
    uint32_t h = (n->height * kappa) >> 8, b = (n->bias * kappa) >> 8;
    if (h > c->height) {
        uint8_t ob = c->bias;
        *c = *n;                      /* offset kept: the content one
                                         cell further, same place in it */
        c->height = (uint8_t)h;
        c->bias = (uint8_t)(b > ob ? b : ob);
    } else if (b > c->bias) {
        c->bias = (uint8_t)b;
    }
}

/* Separable 3x3 fuzzy dilation: horizontal then vertical max of kappa x
 * neighbour (diagonals get kappa^2).  The heading trapezoid follows the
 * winning height. */
static void dilate(fl_fuzzy_t *g, uint32_t kappa)
{
    int nx = g->nx, ny = g->ny, ix, iy;
    size_t rowbytes = sizeof(fl_fuzzy_cell_t) * (size_t)nx;
    fl_fuzzy_cell_t *prev_orig = g->scratch.ring[0];
    fl_fuzzy_cell_t *cur_orig = g->scratch.ring[1];
    for (iy = 0; iy < ny; iy++) {
        fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * (size_t)nx];
        fl_fuzzy_cell_t prev = row[0];
        for (ix = 0; ix < nx; ix++) {
            fl_fuzzy_cell_t cur = row[ix];
            fl_fuzzy_cell_t out = cur;
            if (ix > 0 && prev.height != 0)
                offer(&out, &prev, kappa);
            if (ix + 1 < nx && row[ix + 1].height != 0) {
                fl_fuzzy_cell_t right = row[ix + 1];
                offer(&out, &right, kappa);
            }
            row[ix] = out;
            prev = cur;
        }
    }
    for (iy = 0; iy < ny; iy++) {
        fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * (size_t)nx];
        const fl_fuzzy_cell_t *below = iy + 1 < ny ? row + nx : NULL;
        fl_fuzzy_cell_t *t;
        memcpy(cur_orig, row, rowbytes);
        for (ix = 0; ix < nx; ix++) {
            if (iy > 0 && prev_orig[ix].height != 0)
                offer(&row[ix], &prev_orig[ix], kappa);
            if (below != NULL && below[ix].height != 0) {
                fl_fuzzy_cell_t b = below[ix];
                offer(&row[ix], &b, kappa);
            }
        }
        t = prev_orig;
        prev_orig = cur_orig;
        cur_orig = t;
    }
}

/* Scaling and overflow: |dx|, |dy| <= odo_max_mm <= 2000, so dist < 2829
 * and at most 59 sub-steps; every product fits 32 bits (dist * 1024 <
 * 2^22, |dtheta| * 65535 < 2^32 unsigned) except dist * odo_rot_per_m
 * (64 bit). */
void fl_fuzzy_predict(fl_fuzzy_t *g, int32_t dx_mm, int32_t dy_mm,
                      fl_angle_t dtheta)
{
    const fl_fuzzy_params_t *p;
    int32_t dist, n, k, step, adth, maxodo;
    uint32_t widen, maxh = 255;
    int dil;
    if (!fz_ready(g))
        return;
    p = &g->params;
    g->stats.predicts = fz_sat_inc(g->stats.predicts);
    if (g->since_obs < UINT16_MAX)
        g->since_obs++;
    g->contra_rate_q8 = (uint16_t)(g->contra_rate_q8 - (g->contra_rate_q8 >> 3));
    maxodo = fz_clamp32(p->odo_max_mm, 1, 2000);
    if (dx_mm < -maxodo || dx_mm > maxodo || dy_mm < -maxodo || dy_mm > maxodo) {
        g->stats.odo_rejected = fz_sat_inc(g->stats.odo_rejected);
        return;
    }
    dist = (int32_t)fl_hypot(dx_mm, dy_mm);
    adth = fz_iabs(dtheta);
    /* heading widening, in AUNIT steps, remainder kept */
    g->widen_acc += (int32_t)(((uint32_t)adth * p->odo_rot_q8) >> 8) +
                    (int32_t)(((uint64_t)(uint32_t)dist * p->odo_rot_per_m) / 1000u);
    widen = (uint32_t)(g->widen_acc / FL_FUZZY_AUNIT);
    g->widen_acc -= (int32_t)widen * FL_FUZZY_AUNIT;
    if (widen > FL_FUZZY_WFULL)
        widen = FL_FUZZY_WFULL;
    /* translation in sub-steps of at most CELL/2 - 2 mm (rounding margin) */
    step = FZ_HALF - 2;
    n = dist == 0 ? 0 : (dist + step - 1) / step;
    for (k = 0; k < n; k++) {
        int32_t sx = (int32_t)(((int64_t)dx_mm * (k + 1)) / n - ((int64_t)dx_mm * k) / n);
        int32_t sy = (int32_t)(((int64_t)dy_mm * (k + 1)) / n - ((int64_t)dy_mm * k) / n);
        bool last = k == n - 1;
        maxh = translate(g, sx, sy, last ? dtheta : 0, last ? widen : 0);
    }
    if (n == 0 && (dtheta != 0 || widen != 0))
        maxh = translate(g, 0, 0, dtheta, widen);
    /* position blur: this call's uncertainty u (Q4 mm) sets the fuzzy
     * dilation's kappa; the accumulated uncertainty adds crisp dilations */
    {
        uint32_t u_q4 = (((uint32_t)dist * p->odo_trans_q8) >> 4) +
                        (((uint32_t)adth * p->odo_turn_mm_per_rad) / (ANGLE_PER_RAD / 16));
        uint32_t kappa = p->blur_kappa_min_q8 + ((u_q4 * p->blur_kappa_gain_q8) >> 4);
        if (kappa > p->blur_kappa_max_q8)
            kappa = p->blur_kappa_max_q8;
        g->blur_acc_mm += (int32_t)(u_q4 >> 4);
        for (dil = 0; dil < 4 && g->blur_acc_mm >= (int32_t)p->blur_step_mm; dil++) {
            dilate(g, 256u);
            g->blur_acc_mm -= (int32_t)p->blur_step_mm;
        }
        if (g->blur_acc_mm > (int32_t)p->blur_step_mm)
            g->blur_acc_mm = (int32_t)p->blur_step_mm;
        if (kappa > 0)
            dilate(g, kappa);
    }
    /* an exactly symmetric belief stays exactly symmetric: the motion of
     * a cell and of its mirror differ by rounding only (offsets clamped
     * differently at the cell border, ties of the Q15 rotation), so the
     * first half, mirrored, is the second (the update then needs only
     * half the grid) */
    if (g->sym_exact) {
        fl_fuzzy_internal_mirror_copy(g);
        maxh = fz_grid_max(g);
    }
    if (maxh < 255)
        fl_fuzzy_internal_normalize(g, fz_grid_max(g));
    else
        fl_fuzzy_internal_rows(g);
    /* the tracked mode follows the odometry */
    if (g->track_valid) {
        int32_t cs = fl_cos_q15(g->track_heading), sn = fl_sin_q15(g->track_heading);
        g->track_x_mm += (int32_t)(((int64_t)dx_mm * cs - (int64_t)dy_mm * sn + 16384) >> 15);
        g->track_y_mm += (int32_t)(((int64_t)dx_mm * sn + (int64_t)dy_mm * cs + 16384) >> 15);
        g->track_x_mm = fz_clamp32(g->track_x_mm, -g->half_x_mm, g->half_x_mm);
        g->track_y_mm = fz_clamp32(g->track_y_mm, -g->half_y_mm, g->half_y_mm);
        g->track_heading = fl_angle_add(g->track_heading, dtheta);
    }
}
