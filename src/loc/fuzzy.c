/*
 * src/loc/fuzzy.c - the fuzzy position grid (seed 004, after Buschka, Saffiotti
 * and Wasik): parameters, init, normalization, symmetry, resets, priors,
 * check and inspection.  The other files of the grid, sharing the private
 * header fuzzy_int.h: fuzzy_predict.c (motion model, dilation),
 * fuzzy_update.c (observation update), fuzzy_negative.c (negative
 * information, fl_fuzzy_update_view), fuzzy_estimate.c (estimate,
 * tracking), fuzzy_trap.c (heading trapezoids).  API and memory in
 * include/fieldloc/fuzzy.h.
 *
 * Invariant (fl_fuzzy_check): at least one cell at 255, bias <= height,
 * offsets in [-CELL/2, CELL/2), the estimate on the carpet.
 * Cost: init, resets, normalization, symmetry, check O(cells); the rest
 * O(1).  Stack < 600 B per call (make stack).
 */
#include "fieldloc/fuzzy.h"
#include "fuzzy_int.h"

#include <string.h>

typedef char fz_cell_is_8_bytes[sizeof(fl_fuzzy_cell_t) == 8 ? 1 : -1];

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
 * fl_fuzzy_params_vision: the defaults above suit the simulator's
 * feature-level observations (noisy ranges and bearings, many per second);
 * observations through the vision path are more precise but fewer, with
 * L/T confusions and false positives instead.  What each change trades:
 *  - ring_core_q8 / ring_slope_q8 halved: precise ranges give narrow rings
 *    (too narrow: a range error puts the mode outside its ring);
 *  - odo_rot_per_m up: heading uncertainty must cover the walk's drift
 *    between the rarer corrections (too much: headings flatten);
 *  - head_bias 0 with head_bias_outlier 1: an observation's heading
 *    trapezoid is "the outlier bias, or the ring with its heading"
 *    (fuzzy_update.c rho_head), so a false ring through the mode does not
 *    flatten the cells' headings;
 *  - ring_track_q8 (precise rings while tracking; the gate and updates
 *    from ignorance keep the wide ones): precision while tracked against
 *    robustness to a wrong track (scaling every ring instead brings false
 *    kidnaps and mirror flips);
 *  - kidnap_rate_q8 lower: a kidnap is detected sooner, against false
 *    kidnaps (with cons_shift or kidnap_q16 too aggressive, mirror flips);
 *  - neg_kidnap / neg_q8 (fl_fuzzy_update_view): frames in which the
 *    tracked pose expects landmarks and sees none count as contradictions;
 *    without a track, poses that should see something else are lowered;
 *  - neg_min_q8: cells below it do not compete for the estimate, so the
 *    negative pass skips them (cost against a marginal accuracy change);
 *  - track_min_q16 lower: tracking (precise rings, gate) starts sooner
 *    after convergence, against tracking a less certain mode;
 *  - confuse_q8 / confuse_conf: low-confidence crossings of vision are
 *    often of the other kind (L <-> T); their regions keep such poses
 *    possible.
 * Measured with `build/fieldloc simulate --field F --localizer fuzzy
 * --seed N --frames` (position and heading error, kidnap recovery, mirror
 * flips per field and seed) and `build/fieldloc localize` on the real
 * sequences; cost with `make bench` (rows fuzzy_*).
 */
void fl_fuzzy_params_vision(fl_fuzzy_params_t *p, bool lowres)
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
    if (lowres)
        fl_fuzzy_params_lowres(p);
}

/* Low-resolution cameras (the AIBO's 208 x 160) measure ranges several
 * times less precisely than the NAO's: they keep the wide rings while
 * tracking (precise rings lose the mode), and their far crossings are
 * short and often of the wrong kind: ignored beyond cross_max_mm.
 * Measured with `build/fieldloc simulate --field aibo2004 --localizer
 * fuzzy --seed N --frames`. */
void fl_fuzzy_params_lowres(fl_fuzzy_params_t *p)
{
    if (p == NULL || p->ring_track_q8 != FL_FUZZY_RING_TRACK_VISION)
        return;
    p->ring_track_q8 = 256;
    if (p->cross_max_mm == 0)
        p->cross_max_mm = 2500;
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
    g->half_known = g->prior.kind != FL_FUZZY_PRIOR_NONE;
    g->since_obs = 0;
}

fl_status_t fl_fuzzy_init_cfg(fl_fuzzy_t *g, const fl_field_t *field,
                              const fl_fuzzy_params_t *params, uint32_t caller_cfg)
{
    fl_fuzzy_params_t p;
    int32_t hx, hy, nx, ny;
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *g has another layout: no write is safe */
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

/* ---- symmetry -------------------------------------------------------------- */

/* Symmetric field (fl_field_t.symmetric): nothing an observation says can
 * tell a pose from its 180-degree mirror (-x, -y, h + 180), so the belief
 * is made exactly symmetric (each cell and its mirror get their union):
 * without this, rounding lets the two modes' ratio drift as a random walk
 * until one dies.  The prior or the tracked mode picks one (estimate).
 * Mirror of cell (ix, iy) is (nx-1-ix, ny-1-iy) (the grid is centred);
 * offsets negate (clamped into [-CELL/2, CELL/2)).  (The centre cell of a
 * grid with odd nx and ny maps onto itself and is left alone.) */
static int8_t mirror_off(int8_t o)
{
    return (int8_t)(o <= -FZ_HALF ? FZ_HALF - 1 : -o);
}

static void mirror_cell(const fl_fuzzy_cell_t *c, fl_fuzzy_cell_t *m)
{
    m->centre = fz_wrap16((int32_t)c->centre + FL_ANGLE_180);
    m->height = c->height;
    m->bias = c->bias;
    m->core = c->core;
    m->slope = c->slope;
    m->off_x_mm = mirror_off(c->off_x_mm);
    m->off_y_mm = mirror_off(c->off_y_mm);
}

static void sym_merge(fl_fuzzy_cell_t *dst, const fl_fuzzy_cell_t *src)
{
    fl_fuzzy_trap_t a, b, u;
    int8_t ox = dst->off_x_mm, oy = dst->off_y_mm;
    if (src->height == 0)
        return;
    if (dst->height == 0 || (src->height == dst->height && src->bias == dst->bias &&
                             src->centre == dst->centre && src->core == dst->core &&
                             src->slope == dst->slope)) {
        *dst = *src;
        return;
    }
    if (src->height > dst->height) {
        ox = src->off_x_mm;
        oy = src->off_y_mm;
    }
    fl_fuzzy_trap_from_cell(dst, &a);
    fl_fuzzy_trap_from_cell(src, &b);
    fl_fuzzy_trap_union(&a, &b, &u);
    fl_fuzzy_trap_to_cell(&u, dst);
    dst->off_x_mm = ox;
    dst->off_y_mm = oy;
}

/* Cell i starts a row that is dead (empty row range) together with its
 * mirror row: the mirror passes below skip such row pairs whole. */
static bool rows_dead_at(const fl_fuzzy_t *g, size_t i)
{
    size_t iy = i / g->nx, my = (size_t)g->ny - 1 - iy;
    return i % g->nx == 0 && g->row_lo[iy] > g->row_hi[iy] && g->row_lo[my] > g->row_hi[my];
}

void fl_fuzzy_internal_symmetrize(fl_fuzzy_t *g)
{
    size_t n = (size_t)g->nx * g->ny, i;
    for (i = 0; i < n / 2; i++) {
        fl_fuzzy_cell_t *a = &g->cell[i], *b = &g->cell[n - 1 - i];
        if (rows_dead_at(g, i)) {
            i += (size_t)g->nx - 1;    /* both rows dead: skip the row */
            continue;
        }
        if (a->height == 0 && b->height == 0)
            continue;
        if (b->height != 0) {
            if (a->height == 0 ||
                (b->height == a->height && b->bias == a->bias && b->core == a->core &&
                 b->slope == a->slope && fz_wrap16((int32_t)b->centre + FL_ANGLE_180) == a->centre)) {
                mirror_cell(b, a);     /* sym_merge's copy case, in place */
            } else {
                fl_fuzzy_cell_t mb;
                mirror_cell(b, &mb);
                sym_merge(a, &mb);
            }
        }
        mirror_cell(a, b);
    }
}

void fl_fuzzy_internal_mirror_copy(fl_fuzzy_t *g)
{
    size_t n = (size_t)g->nx * g->ny, i;
    for (i = 0; i < n / 2; i++) {
        fl_fuzzy_cell_t *a = &g->cell[i], *b = &g->cell[n - 1 - i];
        if (rows_dead_at(g, i)) {
            i += (size_t)g->nx - 1;    /* both rows dead: skip the row */
            continue;
        }
        if (a->height == 0) {
            if (b->height != 0)
                memset(b, 0, sizeof *b);
            continue;
        }
        mirror_cell(a, b);
    }
}

/* ---- resets --------------------------------------------------------------- */

void fl_fuzzy_reset_ignorance(fl_fuzzy_t *g)
{
    if (!fz_ready(g))
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
    x = fz_clamp32(x, -g->half_x_mm, g->half_x_mm);
    y = fz_clamp32(y, -g->half_y_mm, g->half_y_mm);
    unc = fz_clamp32(unc, FZ_CELL, 4 * FL_FUZZY_MAX_NX * FZ_CELL);
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
            int32_t cx = fz_centre_x(g, ix), cy = fz_centre_y(g, iy);
            int32_t ox = fz_clamp32(x - cx, -FZ_HALF, FZ_HALF - 1);
            int32_t oy = fz_clamp32(y - cy, -FZ_HALF, FZ_HALF - 1);
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

void fl_fuzzy_reset_pose(fl_fuzzy_t *g, int32_t x_mm, int32_t y_mm,
                         fl_angle_t heading, int32_t pos_unc_mm,
                         fl_angle_t heading_unc)
{
    if (!fz_ready(g))
        return;
    g->stats.resets = fz_sat_inc(g->stats.resets);
    clear_cells(g);
    paint_pose(g, x_mm, y_mm, heading, pos_unc_mm, heading_unc);
    fl_fuzzy_internal_normalize(g, fz_grid_max(g));
    /* the pose is known: track it (on a symmetric field the update makes
     * the mirror equally possible; the track keeps the estimate here) */
    g->track_valid = true;
    g->half_known = true;
    g->track_x_mm = fz_clamp32(x_mm, -g->half_x_mm, g->half_x_mm);
    g->track_y_mm = fz_clamp32(y_mm, -g->half_y_mm, g->half_y_mm);
    g->track_heading = heading;
}

void fl_fuzzy_reset_penalty(fl_fuzzy_t *g, int32_t x_mm, int32_t pos_unc_mm,
                            fl_angle_t heading_unc)
{
    int32_t hw;
    if (!fz_ready(g))
        return;
    g->stats.resets = fz_sat_inc(g->stats.resets);
    hw = g->field->width_mm / 2;
    clear_cells(g);
    paint_pose(g, x_mm, hw, (fl_angle_t)-FL_ANGLE_90, pos_unc_mm, heading_unc);
    paint_pose(g, x_mm, -hw, (fl_angle_t)FL_ANGLE_90, pos_unc_mm, heading_unc);
    fl_fuzzy_internal_normalize(g, fz_grid_max(g));
    /* the placement tells the half (unless the spots are on the halfway
     * line, where they are each other's mirror) */
    if (x_mm != 0)
        fl_fuzzy_set_prior_half(g, x_mm < 0 ? -1 : 1);
    g->half_known = g->prior.kind != FL_FUZZY_PRIOR_NONE;
}

/* ---- priors --------------------------------------------------------------- */

void fl_fuzzy_set_prior_half(fl_fuzzy_t *g, int half)
{
    if (g == NULL)
        return;
    g->prior.kind = half == 0 ? FL_FUZZY_PRIOR_NONE : FL_FUZZY_PRIOR_HALF;
    g->prior.half = (int8_t)(half < 0 ? -1 : 1);
    /* no half: a tracked mode still carries the half it was told */
    g->half_known = half != 0 || (g->half_known && g->track_valid);
}

void fl_fuzzy_set_prior_pose(fl_fuzzy_t *g, int32_t x_mm, int32_t y_mm,
                             fl_angle_t heading, int32_t radius_mm)
{
    if (g == NULL)
        return;
    g->prior.kind = FL_FUZZY_PRIOR_POSE;
    g->prior.x_mm = fz_clamp32(x_mm, -100000, 100000);
    g->prior.y_mm = fz_clamp32(y_mm, -100000, 100000);
    g->prior.heading = heading;
    g->prior.radius_mm = fz_clamp32(radius_mm, FZ_CELL, 20000);
    g->half_known = true;
}

void fl_fuzzy_clear_prior(fl_fuzzy_t *g)
{
    if (g == NULL)
        return;
    g->prior.kind = FL_FUZZY_PRIOR_NONE;
    g->half_known = g->half_known && g->track_valid;
}

/* ---- inspection ----------------------------------------------------------- */

bool fl_fuzzy_cell_centre(const fl_fuzzy_t *g, int ix, int iy, int32_t *x_mm,
                          int32_t *y_mm)
{
    if (!fz_ready(g) || ix < 0 || iy < 0 || ix >= g->nx || iy >= g->ny)
        return false;
    if (x_mm != NULL)
        *x_mm = fz_centre_x(g, ix);
    if (y_mm != NULL)
        *y_mm = fz_centre_y(g, iy);
    return true;
}

uint32_t fl_fuzzy_possibility_q16(const fl_fuzzy_t *g, int32_t x_mm,
                                  int32_t y_mm, fl_angle_t heading)
{
    int32_t ix, iy;
    fl_fuzzy_trap_t t;
    if (!fz_ready(g) || x_mm < g->x0_mm || y_mm < g->y0_mm)
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
    if (!fz_ready(g) || g->nx > FL_FUZZY_MAX_NX || g->ny > FL_FUZZY_MAX_NY)
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
