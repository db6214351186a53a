/*
 * src/loc/fuzzy.c - the fuzzy position grid (seed 004, after Buschka, Saffiotti
 * and Wasik): state, resets, priors, the predict step and the estimate.
 * The observation update is in src/loc/fuzzy_update.c, the heading trapezoids
 * in src/loc/fuzzy_trap.c; API, memory and measured numbers in
 * include/fieldloc/fuzzy.h.
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
 *
 * Estimate.  The dominant mode is the global peak, unless the tracked mode
 * (or before tracking, the prior's region: a pose, or the own half, which
 * the game tells) keeps a peak of at least switch_q8 (half prior: 1/8) of
 * it: symmetric modes (SPL 2013's four identical posts) stay in the grid,
 * the prior or the track decides.  Position: 3 mean-shift iterations of the
 * centre of gravity of the contents (cell centre + offset) within
 * mode_radius_mm, weighted by height - peak/2 (near the centre of a
 * symmetric field only cells whose heading agrees with the mode's count,
 * so the mirror mode cannot leak in).  Heading: circular mean of the
 * trapezoid centres weighted by the same weight x (h - b) / h x 16 / (16 +
 * core code), trimmed to 30 degrees around the reference (the tracked
 * heading) when that keeps 1/16 of the weight; otherwise the trimmed mean
 * around the dominant heading cluster (16-bin histogram of the same
 * weights, best 3 adjacent bins), never the mean of two opposite clusters
 * (a heading no cell holds: the single-frame jumps of the frames-mode
 * demo).  Reliability (Q0.16):
 * consistency x compactness min(1, 9 cells / cells >= peak/2) x (1 - mean
 * relative bias of the mode) x uniqueness (1 - the highest cell elsewhere
 * / the peak; the mirror of a symmetric field is not "elsewhere").  The
 * estimate becomes the tracked mode once the reliability reaches
 * track_min_q16; predict moves the track by the odometry.
 *
 * Invariant (fl_fuzzy_check): at least one cell at 255, bias <= height,
 * offsets in [-CELL/2, CELL/2), the estimate on the carpet.
 * Cost: predict O(cells) per sub-step (one sin/cos table read per live
 * cell) + O(cells) per dilation; estimate O(cells) (peak, uniqueness) +
 * O(window); resets O(cells).  Stack < 600 B per call (make stack).
 */
#include "fieldloc/fuzzy.h"
#include "fuzzy_int.h"

#include <string.h>

typedef char fz_cell_is_8_bytes[sizeof(fl_fuzzy_cell_t) == 8 ? 1 : -1];

#define ANGLE_PER_RAD 10430   /* 65536 / (2 pi), rounded */
#define TRIM_ANGLE 5461       /* 30 deg: heading estimate's trimming window */
#define HBIN_BITS 4           /* heading histogram of the estimate: 16 bins */
#define HBINS (1 << HBIN_BITS)
#define HOLD_DEN 16           /* the tracked heading is kept while its
                                 cells carry 1/HOLD_DEN of the weight */

void fl_fuzzy_params_default(fl_fuzzy_params_t *p)
{
    if (p == NULL)
        return;
    memset(p, 0, sizeof *p);
    p->odo_trans_q8 = 64;
    p->odo_turn_mm_per_rad = 60;
    p->odo_rot_q8 = 41;
    p->odo_rot_per_m = 1092;
    p->blur_kappa_min_q8 = 64;
    p->blur_kappa_gain_q8 = 51;
    p->blur_kappa_max_q8 = 230;
    p->blur_step_mm = 100;
    p->head_min_core = 364;
    p->head_min_slope = 728;
    p->wide_core = 8192;
    p->odo_max_mm = 1000;
    p->ring_base_mm = 60;
    p->ring_core_q8 = 15;
    p->ring_slope_mm = 80;
    p->ring_slope_q8 = 46;
    p->ring_track_q8 = 256;
    p->bearing_core = 455;
    p->bearing_slope = 910;
    p->orient_core = 1820;
    p->orient_slope = 2731;
    p->bias_min_q8 = 38;
    p->head_bias_q8 = 64;
    p->max_range_mm = 12000;
    p->min_height_q8 = 2;
    p->mode_radius_mm = 500;
    p->track_radius_mm = 1000;
    p->switch_q8 = 128;
    p->track_min_q16 = 19661;
    p->gate_q8 = 128;
    p->gate_run = 8;
    p->cons_shift = 3;
    p->kidnap_q16 = 29491;
    p->kidnap_rate_q8 = 192;
    p->neg_q8 = 0;
    p->neg_max = 2;
    p->neg_track = 0;
    p->neg_kidnap = 0;
    p->neg_margin_mm = 200;
    p->neg_range_q8 = 26;
    p->neg_bearing = 910;
    p->neg_head_max = 5461;
}

fl_status_t fl_fuzzy_params_check(const fl_fuzzy_params_t *p)
{
    if (p == NULL)
        return FL_ERR_NULL;
    if (p->odo_trans_q8 > 1024 || p->odo_rot_q8 > 1024 ||
        p->blur_step_mm < 10 || p->blur_step_mm > 10000 ||
        p->wide_core > 32768u || p->odo_max_mm < 1 || p->odo_max_mm > 2000 ||
        p->ring_base_mm < 0 || p->ring_base_mm > 5000 ||
        p->ring_slope_mm < 1 || p->ring_slope_mm > 5000 ||
        p->ring_core_q8 > 256 || p->ring_slope_q8 > 256 ||
        p->ring_track_q8 < 1 || p->ring_track_q8 > 256 ||
        p->bearing_core < 0 || p->bearing_slope < 0 ||
        p->orient_core < 0 || p->orient_slope < 1 ||
        p->head_min_core < 0 || p->head_min_slope < 0 ||
        p->blur_kappa_min_q8 > p->blur_kappa_max_q8 ||
        p->max_range_mm < 100 || p->max_range_mm > 30000 ||
        p->mode_radius_mm < FL_FUZZY_CELL_MM || p->mode_radius_mm > 2000 ||
        p->track_radius_mm < FL_FUZZY_CELL_MM || p->track_radius_mm > 5000 ||
        p->track_min_q16 == 0 || p->cons_shift > 8 || p->min_height_q8 < 1 ||
        p->head_bias_outlier > 1 || p->neg_track > 1 || p->neg_max > 8 ||
        p->neg_margin_mm < 0 || p->cross_max_mm < 0 || p->neg_margin_mm > 5000 || p->neg_range_q8 > 256 ||
        p->neg_bearing < 0 || p->neg_head_max < 0)
        return FL_ERR_RANGE;
    return FL_OK;
}

/*
 * fl_fuzzy_params_vision (moved here from tools/loc/locrun.c, where it was
 * measured).  The defaults above were tuned on the simulator's feature-level
 * observations (range noise 8 %, bearing 1.5 deg at 30 Hz).  Through the
 * vision path the rendered frames give ranges within about 1 % and
 * bearings within 0.2 deg (simulate --frames, "# vision" lines), at 10 Hz,
 * with L/T confusions instead: narrower rings (core 3 % of the range
 * instead of 6 %, slope 9 % instead of 18 %) and more heading uncertainty
 * per metre walked (9 deg instead of 6: the walk's drift is 3 deg/m plus
 * 2 deg/m random, now corrected 3x less often).  Measured with simulate
 * --frames (every 3, seeds 1-3, spl2013 / uva2013): position RMSE
 * 102-110 -> 64-72 mm / 58-94 -> 45-52 mm, heading 3.0-4.4 -> 2.4-2.8 deg
 * / 1.7-2.8 -> 1.4-2.3 deg, and the one symmetric flip (uva2013 seed 1,
 * a run of wrong post sides) gone.  On the real UvA spots (localize
 * --uva-spots) heading RMSE 35 -> 6 deg (the centre spot's 90-degree
 * error goes), position about the same (309 -> 329 mm).
 * Vision's false positives (penalty marks at 5 m, confidence about 185,
 * several a second) are real outliers: head_bias_outlier = 1 with
 * head_bias 0 makes an observation's heading trapezoid "the outlier bias
 * bP, or the ring with its heading" (fuzzy_update.c rho_head), so a false
 * ring through the mode no longer flattens the cells' headings (the
 * single-frame 70-80 degree errors at 64 s of the spl2013 walks).
 * simulate --frames (obs-cached), before -> after, position mm / heading
 * deg: spl2013 seeds 1-3 63.7/2.81, 70.2/2.47, 71.8/2.44 -> 54.8/1.42,
 * 61.6/1.36, 59.5/1.32; the demo (seed 2013) 83.0/3.55 -> 67.7/1.89;
 * uva2013 seeds 1-3 45.3/1.40, 52.4/2.27, 46.3/1.50 -> 46.7/1.37,
 * 50.6/1.69, 40.1/1.46; convergence, kidnap recovery (3.3 / 0.2 s) and
 * flips (0) unchanged.  Real UvA spots: heading 6.4 -> 4.9 deg, position
 * 329 -> 339 mm.  (The feature-level simulator's confidences are not
 * outlier odds: with it, the defaults stay.)
 * With the vision of the luma points and connectors (precision 0.88-0.96,
 * more far crossings) spl2013 had fallen to 90.5/78.3/96.2 mm; its error
 * episodes (e.g. 28-31 s of seed 1, 200-370 mm) came with correct
 * observations (posts at 4.5-5.2 m, an L at 4.5 m, ranges 0.2-1.5 % off)
 * whose ring core (60 mm + 3 % of 4.5 m = 200 mm half-width) was flat
 * over the whole error: precise rings while a mode is tracked
 * (ring_track_q8 = 96/256, 0.38; the gate and updates from ignorance keep
 * the wide ones; scaling every ring instead was fragile: false kidnaps
 * followed by mirror flips on 1 seed in 3) give spl2013 seeds 1-3 (and
 * 4-6) 74.3/61.6/61.8 (54.8/75.5/63.4, before 82.5/96.9/89.0) mm, uva2013
 * 53.8/46.1/48.6 -> 42.1/33.4/36.1 mm, 0 flips.  kidnap_rate_q8 128
 * instead of 192 detects the spl2013 kidnap 0.2 s sooner and the frames
 * after it converge better: spl2013 53.4/60.0/56.2 mm (seeds 4-6
 * 51.6/73.2/57.9), kidnap recovery 3.3/3.0/3.2 s, one kidnap detected per
 * walk as before (cons_shift 2 or kidnap_q16 >= 33000 bring false kidnaps
 * and mirror flips).  aibo2004 unchanged (wide rings, fl_fuzzy_params_for_camera).
 * Then (fuzzy.h, fl_fuzzy_update_view): after the spl2013 kidnap the head
 * looks at a touchline and vision sees nothing for 2.2 s; the tracked
 * pose expected 2-4 landmarks in those frames: neg_kidnap 2 counts such
 * frames as contradictions (kidnap detected at 55.8 instead of 57.9 s on
 * seed 3), and neg_q8 0.39 lowers, without a track, the candidate poses
 * of the first T (one per T of the map) that should see something else.
 * The first converged frames after that are less precise (one far T):
 * track_min_q16 0.2 instead of 0.3 starts tracking (precise rings,
 * gate) sooner.  Vision's crossings of confidence <= 160 are of the
 * other kind (L <-> T) 50-74 % of the time (confidence >= 200: 1-9 %;
 * spl2013 seed 1, aibo2004 seed 3): confuse_q8 0.39 rising to 1 at
 * confidence 160.  aibo2004: crossings beyond 2.5 m ignored (fl_fuzzy_params_for_camera).
 * neg_min_q8 1/2 (cells below do not compete for the estimate): the
 * negative pass after ignorance + 5 updates 0.11 -> 0.03 ms (bench),
 * results the same but uva2013 seeds 2/3 33.4/37.3 -> 33.5/35.4 mm.
 * simulate --frames (obs-cached), seeds 1-3, before -> after: spl2013
 * 51.0/58.3/47.0 -> 41.4/44.4/41.1 mm, 1.39/1.50/1.25 -> 1.48/1.42/1.33
 * deg, kidnap recovery 3.3/3.0/3.2 -> 2.7/2.5/2.5 s; aibo2004
 * 60.0/58.1/120.4 -> 58.6/51.0/69.0 mm, 2.71/2.65/2.89 -> 2.78/2.85/2.67
 * deg; uva2013 37.4/35.1/35.3 -> 37.4/33.4/37.3 mm, 1.09/1.46/1.03 ->
 * 1.16/1.09/1.43 deg; one kidnap detected per walk, 0 flips.
 */
void fl_fuzzy_params_vision(fl_fuzzy_params_t *p, const fl_camera_model_t *model)
{
    if (p == NULL)
        return;
    fl_fuzzy_params_default(p);
    p->ring_core_q8 = 8;
    p->ring_slope_q8 = 23;
    p->odo_rot_per_m = 1638;
    p->head_bias_q8 = 0;
    p->head_bias_outlier = 1;
    p->ring_track_q8 = FL_FUZZY_RING_TRACK_VISION;
    p->kidnap_rate_q8 = 128;
    p->neg_q8 = 100;
    p->neg_min_q8 = 128;
    p->neg_kidnap = 2;
    p->track_min_q16 = 13107;
    p->confuse_q8 = 100;
    p->confuse_conf = 160;
    fl_fuzzy_params_for_camera(p, model);
}

/* The AIBO's 208 x 160 camera measures ranges 1-3 % off (the NAO cameras
 * 0.3-0.4 % in the spl2013/uva2013 walks) and loses accuracy with the
 * precise tracking rings (aibo2004 seeds 1-3: 122/54/163 mm -> 165/97/164
 * at 96): it keeps the wide rings.  Its crossings beyond 2.5 m are 5-15 %
 * short and often of the wrong kind (aibo2004 seed 3, --frames: rms range
 * error 114 mm at 2-2.5 m, 576 mm at 3.5-4 m): ignored. */
void fl_fuzzy_params_for_camera(fl_fuzzy_params_t *p, const fl_camera_model_t *model)
{
    if (p == NULL || model == NULL || model->width_px >= 320 ||
        p->ring_track_q8 != FL_FUZZY_RING_TRACK_VISION)
        return;
    p->ring_track_q8 = 256;
    if (p->cross_max_mm == 0)
        p->cross_max_mm = 2500;
}


static bool ready(const fl_fuzzy_t *g)
{
    return g != NULL && g->field != NULL && g->nx > 0 && g->ny > 0;
}

static int32_t clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

static int32_t centre_x(const fl_fuzzy_t *g, int ix)
{
    return g->x0_mm + ix * FZ_CELL + FZ_HALF;
}

static int32_t centre_y(const fl_fuzzy_t *g, int iy)
{
    return g->y0_mm + iy * FZ_CELL + FZ_HALF;
}

void fl_fuzzy_internal_rows(fl_fuzzy_t *g)
{
    int ix, iy;
    for (iy = 0; iy < g->ny; iy++) {
        const fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * g->nx];
        int lo = -1, hi = -1;
        for (ix = 0; ix < g->nx; ix++)
            if (row[ix].height != 0) {
                if (lo < 0)
                    lo = ix;
                hi = ix;
            }
        if (lo < 0) {                 /* none: lo 1 > hi 0 */
            lo = 1;
            hi = 0;
        }
        g->row_lo[iy] = (uint8_t)lo;
        g->row_hi[iy] = (uint8_t)hi;
    }
}

void fl_fuzzy_internal_ignorance(fl_fuzzy_t *g)
{
    size_t i, n = (size_t)g->nx * g->ny;
    fl_fuzzy_cell_t c;
    c.centre = 0;
    c.core = FL_FUZZY_WFULL;
    c.slope = 0;
    c.height = 255;
    c.bias = 255;
    c.off_x_mm = 0;
    c.off_y_mm = 0;
    for (i = 0; i < n; i++)
        g->cell[i] = c;
    for (i = 0; i < g->ny; i++) {
        g->row_lo[i] = 0;
        g->row_hi[i] = (uint8_t)(g->nx - 1);
    }
    g->blur_acc_mm = 0;
    g->widen_acc = 0;
    g->consistency_q16 = 65535;
    g->contra_run = 0;
    g->contra_rate_q8 = 0;
    g->track_valid = false;
    g->sym_exact = g->field->symmetric;
}

fl_status_t fl_fuzzy_init(fl_fuzzy_t *g, const fl_field_t *field,
                          const fl_fuzzy_params_t *params)
{
    fl_fuzzy_params_t p;
    int32_t hx, hy, nx, ny;
    if (g == NULL)
        return FL_ERR_NULL;
    g->field = NULL;
    g->nx = g->ny = 0;
    if (field == NULL)
        return FL_ERR_NULL;
    if (params != NULL)
        p = *params;
    else
        fl_fuzzy_params_default(&p);
    if (fl_fuzzy_params_check(&p) != FL_OK)
        return FL_ERR_RANGE;
    hx = fl_field_carpet_half_x_mm(field);
    hy = fl_field_carpet_half_y_mm(field);
    if (hx <= 0 || hy <= 0 || hx > 10 * (FL_FUZZY_MAX_NX * FZ_CELL) ||
        hy > 10 * (FL_FUZZY_MAX_NY * FZ_CELL))
        return FL_ERR_SIZE;
    nx = (2 * hx + FZ_CELL - 1) / FZ_CELL;
    ny = (2 * hy + FZ_CELL - 1) / FZ_CELL;
    if (nx > FL_FUZZY_MAX_NX || ny > FL_FUZZY_MAX_NY)
        return FL_ERR_SIZE;
    memset(g, 0, sizeof *g);
    g->params = p;
    g->nx = (uint16_t)nx;
    g->ny = (uint16_t)ny;
    g->x0_mm = -((nx * FZ_CELL) / 2);
    g->y0_mm = -((ny * FZ_CELL) / 2);
    g->half_x_mm = hx;
    g->half_y_mm = hy;
    g->prior.kind = FL_FUZZY_PRIOR_NONE;
    g->field = field;
    fl_fuzzy_internal_ignorance(g);
    return FL_OK;
}

/* Scaling and overflow: gain = 255 * 2^16 / max (max in 1..254) < 2^24;
 * h * gain < 2^32; rounded to nearest, saturated to 255.  Also refreshes
 * the live column range of every row. */
void fl_fuzzy_internal_normalize(fl_fuzzy_t *g, uint32_t max_q8)
{
    int ix, iy;
    uint32_t gain, minh = g->params.min_height_q8;
    if (max_q8 == 0) {
        g->stats.empty_resets = fz_sat_inc(g->stats.empty_resets);
        fl_fuzzy_internal_ignorance(g);
        return;
    }
    gain = max_q8 >= 255 ? 65536u : (255u << 16) / max_q8;
    if (gain == 65536u) {
        /* peak already 1 (the usual case after an update: some cell kept
         * its full support): heights and biases are unchanged, only the
         * floor and the live ranges (same results as the general loop) */
        for (iy = 0; iy < g->ny; iy++) {
            fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * g->nx];
            int lo = -1, hi = -1;
            for (ix = 0; ix < g->nx; ix++) {
                fl_fuzzy_cell_t *c = &row[ix];
                if (c->height == 0)
                    continue;
                if (c->height < minh) {
                    c->height = 0;
                    c->bias = 0;
                    continue;
                }
                if (lo < 0)
                    lo = ix;
                hi = ix;
            }
            g->row_lo[iy] = (uint8_t)(lo < 0 ? 1 : lo);
            g->row_hi[iy] = (uint8_t)(lo < 0 ? 0 : hi);
        }
        return;
    }
    for (iy = 0; iy < g->ny; iy++) {
        fl_fuzzy_cell_t *row = &g->cell[(size_t)iy * g->nx];
        int lo = -1, hi = -1;
        for (ix = 0; ix < g->nx; ix++) {
            fl_fuzzy_cell_t *c = &row[ix];
            uint32_t h, b;
            if (c->height == 0)
                continue;
            h = (c->height * gain + 32768u) >> 16;
            if (h > 255)
                h = 255;
            if (h < minh) {
                c->height = 0;
                c->bias = 0;
                continue;
            }
            b = (c->bias * gain + 32768u) >> 16;
            if (b > h)
                b = h;
            c->height = (uint8_t)h;
            c->bias = (uint8_t)b;
            if (lo < 0)
                lo = ix;
            hi = ix;
        }
        if (lo < 0) {
            lo = 1;
            hi = 0;
        }
        g->row_lo[iy] = (uint8_t)lo;
        g->row_hi[iy] = (uint8_t)hi;
    }
}

/* ---- resets --------------------------------------------------------------- */

void fl_fuzzy_reset_ignorance(fl_fuzzy_t *g)
{
    if (!ready(g))
        return;
    g->stats.resets = fz_sat_inc(g->stats.resets);
    fl_fuzzy_internal_ignorance(g);
}

static void clear_cells(fl_fuzzy_t *g)
{
    memset(g->cell, 0, sizeof(fl_fuzzy_cell_t) * (size_t)g->nx * g->ny);
    g->blur_acc_mm = 0;
    g->widen_acc = 0;
    g->consistency_q16 = 65535;
    g->contra_run = 0;
    g->contra_rate_q8 = 0;
    g->track_valid = false;
    g->sym_exact = false;        /* a pose is painted without its mirror */
}

/* Union of the cone "at (x, y) within unc, heading trapezoid" into the grid.
 * Scaling and overflow: distances <= 2^17 (clamped pose, 20 m grid),
 * height 255 - 128 d / unc in [127, 255]. */
static void paint_pose(fl_fuzzy_t *g, int32_t x, int32_t y, fl_angle_t heading,
                       int32_t unc, fl_angle_t hunc)
{
    int ix0, ix1, iy0, iy1, ix, iy;
    fl_fuzzy_trap_t t;
    int32_t hu = hunc < 0 ? -(int32_t)hunc : hunc;
    x = clamp32(x, -g->half_x_mm, g->half_x_mm);
    y = clamp32(y, -g->half_y_mm, g->half_y_mm);
    unc = clamp32(unc, FZ_CELL, 4 * FL_FUZZY_MAX_NX * FZ_CELL);
    t.centre = heading;
    t.core = hu;
    t.slope = hu;
    t.bias_q16 = 0;
    ix0 = fl_floor_div(x - unc - g->x0_mm, FZ_CELL);
    ix1 = fl_floor_div(x + unc - g->x0_mm, FZ_CELL);
    iy0 = fl_floor_div(y - unc - g->y0_mm, FZ_CELL);
    iy1 = fl_floor_div(y + unc - g->y0_mm, FZ_CELL);
    if (ix0 < 0)
        ix0 = 0;
    if (iy0 < 0)
        iy0 = 0;
    if (ix1 > g->nx - 1)
        ix1 = g->nx - 1;
    if (iy1 > g->ny - 1)
        iy1 = g->ny - 1;
    for (iy = iy0; iy <= iy1; iy++) {
        for (ix = ix0; ix <= ix1; ix++) {
            int32_t cx = centre_x(g, ix), cy = centre_y(g, iy);
            int32_t ox = clamp32(x - cx, -FZ_HALF, FZ_HALF - 1);
            int32_t oy = clamp32(y - cy, -FZ_HALF, FZ_HALF - 1);
            uint32_t d = fl_hypot(x - (cx + ox), y - (cy + oy));
            fl_fuzzy_cell_t *c = &g->cell[(size_t)iy * g->nx + (size_t)ix];
            fl_fuzzy_cell_t nc;
            if (d > (uint32_t)unc)
                continue;
            t.height_q16 = 65536u - (uint32_t)(((uint64_t)d << 15) / (uint32_t)unc);
            nc.off_x_mm = (int8_t)ox;
            nc.off_y_mm = (int8_t)oy;
            if (c->height != 0) {
                fl_fuzzy_trap_t old, u;
                fl_fuzzy_trap_from_cell(c, &old);
                fl_fuzzy_trap_union(&old, &t, &u);
                if (c->height > (uint8_t)((t.height_q16 * 255u) >> 16)) {
                    nc.off_x_mm = c->off_x_mm;
                    nc.off_y_mm = c->off_y_mm;
                }
                fl_fuzzy_trap_to_cell(&u, &nc);
            } else {
                fl_fuzzy_trap_to_cell(&t, &nc);
            }
            *c = nc;
        }
    }
}

static uint32_t grid_max(const fl_fuzzy_t *g)
{
    size_t i, n = (size_t)g->nx * g->ny;
    uint32_t m = 0;
    for (i = 0; i < n; i++)
        if (g->cell[i].height > m)
            m = g->cell[i].height;
    return m;
}

void fl_fuzzy_reset_pose(fl_fuzzy_t *g, int32_t x_mm, int32_t y_mm,
                         fl_angle_t heading, int32_t pos_unc_mm,
                         fl_angle_t heading_unc)
{
    if (!ready(g))
        return;
    g->stats.resets = fz_sat_inc(g->stats.resets);
    clear_cells(g);
    paint_pose(g, x_mm, y_mm, heading, pos_unc_mm, heading_unc);
    fl_fuzzy_internal_normalize(g, grid_max(g));
    /* the pose is known: track it (on a symmetric field the update makes
     * the mirror equally possible; the track keeps the estimate here) */
    g->track_valid = true;
    g->track_x_mm = clamp32(x_mm, -g->half_x_mm, g->half_x_mm);
    g->track_y_mm = clamp32(y_mm, -g->half_y_mm, g->half_y_mm);
    g->track_heading = heading;
}

void fl_fuzzy_reset_penalty(fl_fuzzy_t *g, int32_t x_mm, int32_t pos_unc_mm,
                            fl_angle_t heading_unc)
{
    int32_t hw;
    if (!ready(g))
        return;
    g->stats.resets = fz_sat_inc(g->stats.resets);
    hw = g->field->width_mm / 2;
    clear_cells(g);
    paint_pose(g, x_mm, hw, (fl_angle_t)-FL_ANGLE_90, pos_unc_mm, heading_unc);
    paint_pose(g, x_mm, -hw, (fl_angle_t)FL_ANGLE_90, pos_unc_mm, heading_unc);
    fl_fuzzy_internal_normalize(g, grid_max(g));
    /* the placement tells the half (unless the spots are on the halfway
     * line, where they are each other's mirror) */
    if (x_mm != 0)
        fl_fuzzy_set_prior_half(g, x_mm < 0 ? -1 : 1);
}

/* ---- priors --------------------------------------------------------------- */

void fl_fuzzy_set_prior_half(fl_fuzzy_t *g, int half)
{
    if (g == NULL)
        return;
    g->prior.kind = half == 0 ? FL_FUZZY_PRIOR_NONE : FL_FUZZY_PRIOR_HALF;
    g->prior.half = (int8_t)(half < 0 ? -1 : 1);
}

void fl_fuzzy_set_prior_pose(fl_fuzzy_t *g, int32_t x_mm, int32_t y_mm,
                             fl_angle_t heading, int32_t radius_mm)
{
    if (g == NULL)
        return;
    g->prior.kind = FL_FUZZY_PRIOR_POSE;
    g->prior.x_mm = clamp32(x_mm, -100000, 100000);
    g->prior.y_mm = clamp32(y_mm, -100000, 100000);
    g->prior.heading = heading;
    g->prior.radius_mm = clamp32(radius_mm, FZ_CELL, 20000);
}

void fl_fuzzy_clear_prior(fl_fuzzy_t *g)
{
    if (g == NULL)
        return;
    g->prior.kind = FL_FUZZY_PRIOR_NONE;
}

/* ---- predict -------------------------------------------------------------- */

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
                px = clamp32(px - sx * FZ_CELL, -FZ_HALF, FZ_HALF - 1);
                py = clamp32(py - sy * FZ_CELL, -FZ_HALF, FZ_HALF - 1);
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

static int32_t iabs(int32_t v)
{
    return v < 0 ? -v : v;   /* callers: |v| <= 2^17 */
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
    if (!ready(g))
        return;
    p = &g->params;
    g->stats.predicts = fz_sat_inc(g->stats.predicts);
    g->contra_rate_q8 = (uint16_t)(g->contra_rate_q8 - (g->contra_rate_q8 >> 3));
    maxodo = clamp32(p->odo_max_mm, 1, 2000);
    if (dx_mm < -maxodo || dx_mm > maxodo || dy_mm < -maxodo || dy_mm > maxodo) {
        g->stats.odo_rejected = fz_sat_inc(g->stats.odo_rejected);
        return;
    }
    dist = (int32_t)fl_hypot(dx_mm, dy_mm);
    adth = iabs(dtheta);
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
        maxh = grid_max(g);
    }
    if (maxh < 255)
        fl_fuzzy_internal_normalize(g, grid_max(g));
    else
        fl_fuzzy_internal_rows(g);
    /* the tracked mode follows the odometry */
    if (g->track_valid) {
        int32_t cs = fl_cos_q15(g->track_heading), sn = fl_sin_q15(g->track_heading);
        g->track_x_mm += (int32_t)(((int64_t)dx_mm * cs - (int64_t)dy_mm * sn + 16384) >> 15);
        g->track_y_mm += (int32_t)(((int64_t)dx_mm * sn + (int64_t)dy_mm * cs + 16384) >> 15);
        g->track_x_mm = clamp32(g->track_x_mm, -g->half_x_mm, g->half_x_mm);
        g->track_y_mm = clamp32(g->track_y_mm, -g->half_y_mm, g->half_y_mm);
        g->track_heading = fl_angle_add(g->track_heading, dtheta);
    }
}

/* ---- estimate ------------------------------------------------------------- */

static bool heading_agrees(const fl_fuzzy_cell_t *c, fl_angle_t h)
{
    int32_t d = fl_angle_sub(c->centre, h);
    return c->core >= FL_FUZZY_WFULL || (d <= FL_ANGLE_90 && d >= -FL_ANGLE_90);
}

typedef struct {
    int kind;                 /* 0 none, 1 half, 2 pose */
    int half;
    int32_t x, y, r;
    fl_angle_t h;
    bool check_heading;       /* the mirror mode may fall in the region */
} ref_t;

/* On a symmetric field the mirror (-x, -y, h + 180) of a pose within r of
 * (x, y) can itself lie within r of it only near the centre: only there
 * must a region tell the two apart by heading (a single cell whose heading
 * an outlier replaced must not make the region miss its mode). */
static bool mirror_near(const fl_fuzzy_t *g, int32_t x, int32_t y, int32_t r)
{
    return g->field->symmetric && iabs(x) <= 2 * r && iabs(y) <= 2 * r;
}

static bool in_ref(const fl_fuzzy_t *g, const ref_t *ref, int ix, int iy,
                   const fl_fuzzy_cell_t *c, uint32_t *d2)
{
    int32_t cx = centre_x(g, ix) + c->off_x_mm, cy = centre_y(g, iy) + c->off_y_mm;
    *d2 = 0;
    if (ref->kind == 1)
        return ref->half < 0 ? cx < 0 : cx > 0;
    if (ref->kind == 2) {
        int32_t ddx = cx - ref->x, ddy = cy - ref->y;
        if (iabs(ddx) > ref->r || iabs(ddy) > ref->r)
            return false;
        *d2 = (uint32_t)(ddx * ddx) + (uint32_t)(ddy * ddy);
        return *d2 <= (uint32_t)ref->r * (uint32_t)ref->r &&
               (!ref->check_heading || heading_agrees(c, ref->h));
    }
    return false;
}

/* Reference heading of a mode found without a track: circular mean of the
 * trapezoid centres within mode_radius of (px, py), weighted by height x
 * heading information (h - b), so that one cell with a stray heading does
 * not decide.  fallback when no cell has heading information. */
static fl_angle_t window_heading(const fl_fuzzy_t *g, int32_t px, int32_t py,
                                 fl_angle_t fallback)
{
    int32_t R = clamp32(g->params.mode_radius_mm, FZ_CELL, 2000);
    int ix0, ix1, iy0, iy1, ix, iy;
    int64_t sc = 0, ss = 0;
    fz_window(g, px, py, R, &ix0, &ix1, &iy0, &iy1);
    for (iy = iy0; iy <= iy1; iy++)
        for (ix = ix0; ix <= ix1; ix++) {
            const fl_fuzzy_cell_t *c = &g->cell[iy * g->nx + ix];
            int32_t w;
            if (c->height <= c->bias || c->core >= FL_FUZZY_WFULL)
                continue;
            w = (int32_t)c->height * (int32_t)(c->height - c->bias);
            sc += (int64_t)w * fl_cos_q15(c->centre);
            ss += (int64_t)w * fl_sin_q15(c->centre);
        }
    while (sc > (1 << 30) || sc < -(1 << 30) || ss > (1 << 30) || ss < -(1 << 30)) {
        sc /= 2;
        ss /= 2;
    }
    return sc == 0 && ss == 0 ? fallback : fl_atan2((int32_t)ss, (int32_t)sc);
}

/* Uniqueness (Q16): 1 - c / peak, c = the highest cell farther than two
 * mode radii from the estimate (and, on a symmetric field, from its
 * mirror, which is the same hypothesis); 0 when another place is as
 * possible.  Keeps an ambiguous belief (two penalty spots that look alike)
 * from being tracked (and gated) before an observation decides. */
static uint32_t uniqueness(const fl_fuzzy_t *g, int32_t px, int32_t py, uint32_t peak)
{
    int32_t R2 = 2 * clamp32(g->params.mode_radius_mm, FZ_CELL, 2000);
    uint32_t c = 0;
    int ix, iy;
    if (peak == 0)
        return 0;
    for (iy = 0; iy < g->ny; iy++) {
        int32_t cy = centre_y(g, iy);
        const fl_fuzzy_cell_t *row = &g->cell[iy * g->nx];
        bool near_y = iabs(cy - py) <= R2;
        bool near_my = g->field->symmetric && iabs(cy + py) <= R2;
        for (ix = 0; ix < g->nx; ix++) {
            int32_t cx;
            if (row[ix].height <= c)
                continue;
            cx = centre_x(g, ix);
            if ((near_y && iabs(cx - px) <= R2) || (near_my && iabs(cx + px) <= R2))
                continue;
            c = row[ix].height;
        }
    }
    return c >= peak ? 0u : 65536u - (c * 65536u) / peak;
}

/* The estimate's mode window: cells within R of (px, py), height at least
 * hp / 2, heading agreeing with rh when chk (the mirror may be inside). */
typedef struct {
    int ix0, ix1, iy0, iy1;
    int32_t px, py, R;
    uint32_t hp;
    bool chk;
    fl_angle_t rh;
} win_t;

/* Heading weight of a cell of the window (w = height - peak/2 > 0) x how
 * much heading information the cell has: (h - b) / h x 16 / (16 + core
 * code) (core 11 deg: 1/2); 0 for a cell without heading information.
 * Scaling: w <= 255, product <= 255 x 255 x 16 < 2^21, result <= 255. */
static int32_t heading_weight(const fl_fuzzy_cell_t *c, int32_t w)
{
    if (c->core >= FL_FUZZY_WFULL || c->height <= c->bias)
        return 0;
    return (w * (int32_t)(c->height - c->bias) * 16) /
           ((int32_t)c->height * (16 + (int32_t)c->core));
}

static bool in_window(const fl_fuzzy_t *g, const win_t *wn, int ix, int iy,
                      const fl_fuzzy_cell_t *c)
{
    int32_t ddx = centre_x(g, ix) - wn->px, ddy = centre_y(g, iy) - wn->py;
    return c->height * 2u >= wn->hp && ddx * ddx + ddy * ddy <= wn->R * wn->R &&
           (!wn->chk || heading_agrees(c, wn->rh));
}

/* Circular sums (cos, sin, Q15 x weight) of the window's trapezoid centres
 * within TRIM_ANGLE of h.  Scaling: weight <= 255, window <= 41 x 41
 * cells: |sums| < 2^15 x 255 x 1681 < 2^39 (int64). */
static void trimmed_sums(const fl_fuzzy_t *g, const win_t *wn, fl_angle_t h,
                         int64_t *scos, int64_t *ssin)
{
    int ix, iy;
    *scos = *ssin = 0;
    for (iy = wn->iy0; iy <= wn->iy1; iy++)
        for (ix = wn->ix0; ix <= wn->ix1; ix++) {
            const fl_fuzzy_cell_t *c = &g->cell[iy * g->nx + ix];
            int32_t wh, dh;
            if (!in_window(g, wn, ix, iy, c))
                continue;
            wh = heading_weight(c, (int32_t)c->height - (int32_t)(wn->hp / 2u));
            dh = fl_angle_sub(c->centre, h);
            if (wh <= 0 || dh > TRIM_ANGLE || dh < -TRIM_ANGLE)
                continue;
            *scos += (int64_t)wh * fl_cos_q15(c->centre);
            *ssin += (int64_t)wh * fl_sin_q15(c->centre);
        }
}

bool fl_fuzzy_estimate(fl_fuzzy_t *g, fl_fuzzy_estimate_t *out)
{
    const fl_fuzzy_params_t *p;
    int nx, ny, ix, iy, it, gi = -1, li = -1, ci;
    uint32_t hg = 0, hl = 0, dl = UINT32_MAX, hp = 0, nmode = 0;
    int32_t px, py, R;
    fl_angle_t rh, heading;
    int64_t sw = 0, sb = 0;
    int64_t scos = 0, ssin = 0, tcos = 0, tsin = 0, swh = 0, twh = 0;
    ref_t ref;
    win_t wn;
    int32_t bin[HBINS];
    bool chk;
    uint32_t rel, area, one_minus_b;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    if (!ready(g) || out == NULL)
        return false;
    p = &g->params;
    nx = g->nx;
    ny = g->ny;
    memset(&ref, 0, sizeof ref);
    if (g->track_valid) {
        ref.kind = 2;
        ref.x = g->track_x_mm;
        ref.y = g->track_y_mm;
        ref.h = g->track_heading;
        ref.r = clamp32(p->track_radius_mm, FZ_CELL, 5000);
        ref.check_heading = mirror_near(g, ref.x, ref.y, ref.r);
    } else if (g->prior.kind == FL_FUZZY_PRIOR_POSE) {
        ref.kind = 2;
        ref.x = g->prior.x_mm;
        ref.y = g->prior.y_mm;
        ref.h = g->prior.heading;
        ref.r = g->prior.radius_mm;
        ref.check_heading = true;
    } else if (g->prior.kind == FL_FUZZY_PRIOR_HALF) {
        ref.kind = 1;
        ref.half = g->prior.half;
    }
    for (iy = 0; iy < ny; iy++) {
        for (ix = 0; ix < nx; ix++) {
            int i = iy * nx + ix;
            const fl_fuzzy_cell_t *c = &g->cell[i];
            uint32_t d2;
            if (c->height == 0)
                continue;
            if (c->height > hg) {
                hg = c->height;
                gi = i;
            }
            if (ref.kind != 0 && in_ref(g, &ref, ix, iy, c, &d2) &&
                (c->height > hl || (c->height == hl && d2 < dl))) {
                hl = c->height;
                dl = d2;
                li = i;
            }
        }
    }
    if (gi < 0)                         /* impossible for a valid grid */
        return false;
    /* the tracked mode (or a pose prior) is kept while its peak is at least
     * switch_q8 of the global one; the half prior (kick-off, penalty
     * placement: told by the game) while it is at least 1/8 of it */
    ci = (li >= 0 && hl * 256u >= hg * (ref.kind == 1 ? 32u : p->switch_q8)) ? li : gi;
    out->switched = g->track_valid && ci != li;
    px = centre_x(g, ci % nx) + g->cell[ci].off_x_mm;
    py = centre_y(g, ci / nx) + g->cell[ci].off_y_mm;
    rh = g->track_valid && !out->switched ? g->track_heading
                                          : window_heading(g, px, py, g->cell[ci].centre);
    R = clamp32(p->mode_radius_mm, FZ_CELL, 2000);
    chk = mirror_near(g, px, py, R);
    memset(&wn, 0, sizeof wn);
    for (it = 0; it < 3; it++) {
        int64_t sx = 0, sy = 0;
        fz_window(g, px, py, R, &wn.ix0, &wn.ix1, &wn.iy0, &wn.iy1);
        wn.px = px;
        wn.py = py;
        wn.R = R;
        wn.chk = chk;
        wn.rh = rh;
        hp = 0;
        for (iy = wn.iy0; iy <= wn.iy1; iy++)
            for (ix = wn.ix0; ix <= wn.ix1; ix++) {
                const fl_fuzzy_cell_t *c = &g->cell[iy * nx + ix];
                int32_t ddx = centre_x(g, ix) - px, ddy = centre_y(g, iy) - py;
                if (c->height > hp && ddx * ddx + ddy * ddy <= R * R &&
                    (!chk || heading_agrees(c, rh)))
                    hp = c->height;
            }
        wn.hp = hp;
        sw = sb = scos = ssin = tcos = tsin = swh = twh = 0;
        memset(bin, 0, sizeof bin);
        nmode = 0;
        for (iy = wn.iy0; iy <= wn.iy1; iy++)
            for (ix = wn.ix0; ix <= wn.ix1; ix++) {
                const fl_fuzzy_cell_t *c = &g->cell[iy * nx + ix];
                int32_t cx = centre_x(g, ix), cy = centre_y(g, iy);
                int32_t w, wh;
                if (!in_window(g, &wn, ix, iy, c))
                    continue;
                nmode++;
                w = (int32_t)c->height - (int32_t)(hp / 2u);
                if (w <= 0)
                    continue;
                sw += w;
                sx += (int64_t)w * (cx + c->off_x_mm);
                sy += (int64_t)w * (cy + c->off_y_mm);
                sb += (int64_t)w * ((c->bias * 255u) / c->height);
                wh = heading_weight(c, w);
                if (wh > 0) {
                    int32_t dh = fl_angle_sub(c->centre, rh);
                    scos += (int64_t)wh * fl_cos_q15(c->centre);
                    ssin += (int64_t)wh * fl_sin_q15(c->centre);
                    swh += wh;
                    bin[(uint16_t)c->centre >> (16 - HBIN_BITS)] += wh;
                    if (dh <= TRIM_ANGLE && dh >= -TRIM_ANGLE) {
                        tcos += (int64_t)wh * fl_cos_q15(c->centre);
                        tsin += (int64_t)wh * fl_sin_q15(c->centre);
                        twh += wh;
                    }
                }
            }
        if (sw == 0)
            break;
        px = (int32_t)(sx / sw);
        py = (int32_t)(sy / sw);
    }
    if (HOLD_DEN * twh >= swh && (tcos != 0 || tsin != 0)) {
        /* trimmed mean: cells within TRIM_ANGLE of the reference (the
         * tracked heading) carry at least 1/HOLD_DEN of the weight; cells
         * whose heading an outlier replaced do not pull the estimate */
        scos = tcos;
        ssin = tsin;
    } else if (swh > 0) {
        /* otherwise the dominant heading cluster: the 3 adjacent bins
         * (67.5 deg) with the most weight, then the trimmed mean around
         * the middle bin's centre.  Never the mean of two opposite
         * clusters (a heading that no cell holds). */
        int k, kb = 0;
        int32_t best = -1;
        for (k = 0; k < HBINS; k++) {
            int32_t v = bin[(k + HBINS - 1) % HBINS] + bin[k] + bin[(k + 1) % HBINS];
            if (v > best) {
                best = v;
                kb = k;
            }
        }
        trimmed_sums(g, &wn, (fl_angle_t)(int32_t)((kb << (16 - HBIN_BITS)) +
                                                   (1 << (15 - HBIN_BITS)) - 65536 * (kb >= HBINS / 2)),
                     &scos, &ssin);
    }
    if (scos != 0 || ssin != 0) {
        /* reduce to 31 bits keeping the ratio (window up to 41 x 41 cells) */
        while (scos > (1 << 30) || scos < -(1 << 30) || ssin > (1 << 30) || ssin < -(1 << 30)) {
            scos /= 2;
            ssin /= 2;
        }
        heading = fl_atan2((int32_t)ssin, (int32_t)scos);
    } else {
        heading = rh;
    }
    px = clamp32(px, -g->half_x_mm, g->half_x_mm);
    py = clamp32(py, -g->half_y_mm, g->half_y_mm);
    /* reliability: consistency x compactness x (1 - bias), Q16 */
    area = nmode <= 9 ? 65536u : (9u * 65536u) / nmode;
    one_minus_b = sw > 0 ? (uint32_t)(65536 - (sb * 65536) / (sw * 255)) : 0;
    if (one_minus_b > 65536u)
        one_minus_b = 0;
    rel = (uint32_t)(((uint64_t)g->consistency_q16 * area) >> 16);
    rel = (uint32_t)(((uint64_t)rel * one_minus_b) >> 16);
    rel = (uint32_t)(((uint64_t)rel * uniqueness(g, px, py, hp)) >> 16);
    if (rel > 65535u)
        rel = 65535u;
    out->x_mm = px;
    out->y_mm = py;
    out->heading = heading;
    out->reliability_q16 = (uint16_t)rel;
    out->peak_q8 = (uint8_t)hp;
    out->mode_cells = (uint16_t)(nmode > 65535u ? 65535u : nmode);
    if (out->switched)
        g->stats.mode_switches = fz_sat_inc(g->stats.mode_switches);
    if (g->track_valid || rel >= p->track_min_q16) {
        g->track_valid = true;
        g->track_x_mm = px;
        g->track_y_mm = py;
        g->track_heading = heading;
    }
    return true;
}

/* ---- inspection ----------------------------------------------------------- */

bool fl_fuzzy_cell_centre(const fl_fuzzy_t *g, int ix, int iy, int32_t *x_mm,
                          int32_t *y_mm)
{
    if (!ready(g) || ix < 0 || iy < 0 || ix >= g->nx || iy >= g->ny)
        return false;
    if (x_mm != NULL)
        *x_mm = centre_x(g, ix);
    if (y_mm != NULL)
        *y_mm = centre_y(g, iy);
    return true;
}

uint32_t fl_fuzzy_possibility_q16(const fl_fuzzy_t *g, int32_t x_mm,
                                  int32_t y_mm, fl_angle_t heading)
{
    int32_t ix, iy;
    fl_fuzzy_trap_t t;
    if (!ready(g) || x_mm < g->x0_mm || y_mm < g->y0_mm)
        return 0;
    ix = fl_floor_div(x_mm - g->x0_mm, FZ_CELL);
    iy = fl_floor_div(y_mm - g->y0_mm, FZ_CELL);
    if (ix >= g->nx || iy >= g->ny)
        return 0;
    fl_fuzzy_trap_from_cell(&g->cell[iy * g->nx + ix], &t);
    return fl_fuzzy_trap_eval(&t, heading);
}

bool fl_fuzzy_check(const fl_fuzzy_t *g)
{
    size_t i, n;
    bool top = false;
    if (!ready(g) || g->nx > FL_FUZZY_MAX_NX || g->ny > FL_FUZZY_MAX_NY)
        return false;
    n = (size_t)g->nx * g->ny;
    for (i = 0; i < n; i++) {
        const fl_fuzzy_cell_t *c = &g->cell[i];
        if (c->bias > c->height)
            return false;
        if (c->off_x_mm < -FZ_HALF || c->off_x_mm >= FZ_HALF ||
            c->off_y_mm < -FZ_HALF || c->off_y_mm >= FZ_HALF)
            return false;
        if (c->height == 255)
            top = true;
    }
    return top;
}
