/*
 * src/vision/scan.c - the column scanner of seed 000 (see include/fieldloc/scan.h
 * for the outputs and their definitions).
 *
 * Algorithm, per frame, over the scan grid (col_step x row_step):
 *  A  candidates: per band of 32 grid columns, from the search start
 *     (horizon - margin with a camera, else row 0), only every ns-th row
 *     (ns = ceil(N / row_step)) is classified (one 32-cell word) until a
 *     cell is green: every run of ns green samples contains one of these
 *     rows, so no run in the band starts earlier than ns - 1 rows before it
 *     (cost ~1/ns of a classification per row above the band's highest
 *     border).
 *  B  bands of 32 grid columns, top-down from the band's earliest possible
 *     run start: first every row of the band is classified once into 32
 *     2-bit codes, written to the map (band_rows: table lookups; YUYV pixel
 *     pairs share one chroma lookup), then the row logic reads the words
 *     back: bit-sliced run counters find the first run of ns green samples
 *     per column (the border; refined to the pixel between grid rows) and
 *     the cells above it are masked (B1, while a column of the band has no
 *     border yet); white run starts (W & ~W_above) get the contrast check
 *     (one per horizontal group), rejected runs are cleared to their end,
 *     yellow->green transitions become feet, yellow cells go to bit-sliced
 *     column counters; once every column has its border (B2) carpet rows
 *     (only green and other, no yellow above) are a tight loop that only
 *     moves the state down.  B also records where each border's first
 *     green run ends (gend), for the bump re-runs.
 *  A' then per column, scalar and short: extend the border up over a thin
 *     line with carpet (or a post) above it; reject green clutter beyond the
 *     carpet (bumps above the border of the flat stretch next to them,
 *     re-searched below the clutter in the class map); repair columns
 *     without a border between columns with one (a line running down the
 *     column).
 *  C  goal posts: yellow right above a border is followed upward into the
 *     map and a foot recorded there.
 *  D  field color: exact HSV of every estimate_step_px-th pixel below the
 *     border; hue mode and mean (see scan.h).
 *  "One pass per column": each column is traversed top-down once; a grid
 *  cell is classified at most once in B, plus a few samples per column in
 *  A, A' (around the border) and C (post pixels).
 * Invariant: map cells above a column's border are OTHER except yellow
 *  kept by C; below it they hold the color class (white only after its
 *  contrast check passed or the per-column check cap was reached).
 * Memory: fl_scan_t only (88 544 bytes at the default capacities);
 *  the stack holds a few words and one 8-entry window.
 * Files: one per phase (scan_band.c A and B, scan_border.c A',
 *  scan_post.c C, scan_field.c D; scan_int.h lists them); this one holds
 *  the public entry points and the per-frame driver.
 * Cost (the numbers: `make bench`, tools/bench/callgrind.sh, instructions
 *  per frame and per pixel on the UvA and rendered frames and on the noise
 *  frames).  Phase B's table lookups dominate: about ten instructions per
 *  classified cell.  A YUYV cell is three byte loads, the chroma lookup,
 *  the pattern lookup and the accumulate; at full resolution a pixel pair
 *  shares its chroma lookup (cheaper per pixel), at col_step 2 every
 *  sample is the even pixel of its own pair and shares nothing.  An RGB
 *  cell costs a few instructions more: three byte loads, R - G and B - G,
 *  two bucket loads (the second added from memory), the cell, the pattern
 *  base, the pattern, the accumulate.  So the cost per image pixel is of
 *  the order of ten over the grid's cell area (col_step x row_step), plus
 *  the row logic of B (white checks and border refinement included) and
 *  the per-column scalar phases, which do not shrink with the grid (A'
 *  extend, bumps, C, D: exact HSV of a few dozen samples).  The scalar
 *  walks (extend, border refinement, white checks, post trace) are
 *  specialised per pixel layout (col_class_k: no layout test per sample,
 *  one offset for the three bytes of RGB and YUYV).  The
 *  classification alone (the word functions; callgrind.sh's classify_only
 *  rows) is the floor of any change outside them; a cheaper one would
 *  need a bigger table than the 256 KiB budget (an RGB table indexed by
 *  raw R - G and B - G is 522 KB).
 *  Worst case bounded by cells + per-column caps: "topnoise" (carpet rows
 *  on top, uniform noise below: every column bordered in row 0, every cell
 *  below classified and checked).  Uniform noise alone is much cheaper:
 *  phase A finds no run of N green and leaves the bands unclassified.
 */
#include "scan_int.h"

#include <string.h>

void fl_scan_params_default(fl_scan_params_t *p)
{
    if (p == NULL)
        return;
    p->col_step = 2;
    p->row_step = 2;
    p->border_run_px = 8;
    p->horizon_margin_px = 2;
    p->feet_per_column = 4;
    p->checks_per_column = 32;
    p->estimate_step_px = 24;
}

static bool params_ok(const fl_scan_params_t *p)
{
    return p->col_step >= 1 && p->col_step <= 16 && p->row_step >= 1 &&
           p->row_step <= 16 && p->border_run_px >= 1 && p->border_run_px <= 255 &&
           p->horizon_margin_px >= 0 && p->horizon_margin_px <= 255 &&
           p->feet_per_column >= 0 && p->feet_per_column <= 255 &&
           p->checks_per_column >= 0 && p->checks_per_column <= 255 &&
           p->estimate_step_px >= 0 && p->estimate_step_px <= 255;
}

fl_status_t fl_scan_init_cfg(fl_scan_t *s, const fl_scan_params_t *p, uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *s has another layout: no write is safe */
    if (s == NULL || p == NULL)
        return FL_ERR_NULL;
    memset(s, 0, sizeof *s);
    s->status = FL_ERR_SIZE;   /* no frame yet */
    if (!params_ok(p)) {
        fl_scan_params_default(&s->params);
        return FL_ERR_RANGE;
    }
    s->params = *p;
    return FL_OK;
}

/* ---- the frame ---------------------------------------------------------------------------- */

static void empty_result(fl_scan_t *s, fl_status_t st)
{
    s->status = st;
    s->width = s->height = s->cols = s->rows = s->words = 0;
    s->start_v = 0;
    s->n_border = 0;
    s->n_feet = 0;
    s->feet_dropped = s->checks_skipped = s->white_rejected = 0;
}

int32_t fl_scan_frame(fl_scan_t *s, const fl_color_table_t *colors,
                      const fl_image_t *img, const fl_camera_t *camera)
{
    frame_t f;
    fl_status_t st;
    int32_t cols, rows, w, j0, ns, max_white;
    if (s == NULL)
        return 0;
    if (colors == NULL || img == NULL) {
        empty_result(s, FL_ERR_NULL);
        return 0;
    }
    if (!params_ok(&s->params)) {
        /* never set up by fl_scan_init (a zeroed struct), or params
         * changed out of range since: no division by a zero step */
        empty_result(s, FL_ERR_RANGE);
        return 0;
    }
    st = fl_image_validate(img);
    if (st != FL_OK) {
        empty_result(s, st);
        return 0;
    }
    cols = (img->width + s->params.col_step - 1) / s->params.col_step;
    rows = (img->height + s->params.row_step - 1) / s->params.row_step;
    if (cols > FL_SCAN_MAX_COLS || rows > FL_SCAN_MAX_ROWS) {
        empty_result(s, FL_ERR_SIZE);
        return 0;
    }
    f.ct = colors;
    f.fmt = img->format;
    f.p0 = img->plane[0];
    f.p1 = img->plane[1];
    f.p2 = img->plane[2];
    f.st0 = (size_t)img->stride[0];
    f.st1 = (size_t)img->stride[1];
    f.st2 = (size_t)img->stride[2];
    f.cs = s->params.col_step;
    /* col_init's layout (see frame_t) */
    f.py = f.p0;
    f.scb = f.scr = f.st0;
    if (f.fmt == FL_FMT_RGB888) {
        f.pcb = f.pcr = f.p0;
        f.ky = f.kc = 3;
        f.csh = 0;
    } else if (f.fmt == FL_FMT_YUYV422) {
        f.pcb = f.p0 + 1;   /* the pixel pair's chroma */
        f.pcr = f.p0 + 3;
        f.ky = 2;
        f.kc = 4;
        f.csh = 1;
    } else {
        f.pcb = f.p1;
        f.pcr = f.p2;
        f.scb = f.st1;
        f.scr = f.st2;
        f.ky = f.kc = 1;
        f.csh = 0;
    }
    f.rs = s->params.row_step;

    empty_result(s, FL_OK);
    s->width = img->width;
    s->height = img->height;
    s->cols = cols;
    s->rows = rows;
    s->words = (cols + 31) / 32;
    s->start_v = 0;
    s->below_horizon = false;
    if (camera != NULL) {
        /* the topmost horizon row over the width (the same row everywhere
         * without roll), so that no column's ground is cut off; the whole
         * image sees ground when the lowest one is above it */
        int32_t h0 = fl_camera_horizon_v_q4(camera, 0);
        int32_t h1 = fl_camera_horizon_v_q4(camera, (img->width - 1) * 16);
        int32_t hv = h0 < h1 ? h0 : h1, hlow = h0 < h1 ? h1 : h0;
        if (hv == INT32_MAX)
            s->start_v = img->height;
        else if (hlow == INT32_MIN || hlow < -16)
            s->below_horizon = true;
        if (hv != INT32_MAX && hv != INT32_MIN) {
            int32_t v = (hv >> 4) + 1 - s->params.horizon_margin_px;
            s->start_v = v < 0 ? 0 : (v > img->height ? img->height : v);
        }
    }
    j0 = (s->start_v + f.rs - 1) / f.rs;

    /* A */
    ns = (s->params.border_run_px + f.rs - 1) / f.rs;
    max_white = (2 * s->params.border_run_px + f.rs - 1) / f.rs;
    /* B */
    memset(s->col_feet, 0, (size_t)cols);
    memset(s->col_checks, 0, (size_t)cols);
    memset(s->yellow_cols, 0, (size_t)cols * sizeof s->yellow_cols[0]);
    memset(s->yellow_rows, 0, (size_t)rows * sizeof s->yellow_rows[0]);
    memset(s->post_top, 0, sizeof s->post_top);
    for (w = 0; w < cols; w++) {
        s->first_row[w] = (int16_t)rows;
        s->border_v[w] = (int16_t)s->height;
    }
    for (w = 0; w < s->words; w++)
        fl_scan_internal_band(s, &f, w, j0, ns);
    fl_scan_internal_extend_borders(s, &f, ns, j0, max_white);
    fl_scan_internal_reject_bumps(s, &f, ns);
    if (j0 == 0 && !s->below_horizon)   /* no horizon: a board may be first */
        fl_scan_internal_reject_boards(s, &f, ns);
    if (s->n_border < cols)   /* else no column to repair */
        fl_scan_internal_repair_borders(s, &f);
    /* C */
    fl_scan_internal_trace_posts(s, &f);
    /* D */
    fl_scan_internal_estimate_field(s, &f);
    return s->n_border;
}

/* ---- accessors ------------------------------------------------------------------------------- */

fl_color_class_t fl_scan_class_at(const fl_scan_t *s, int32_t i, int32_t j)
{
    if (s == NULL || i < 0 || j < 0 || i >= s->cols || j >= s->rows)
        return FL_CLASS_OTHER;
    return (fl_color_class_t)map_class(s, i, j);
}

/* Spread bits (cells at even positions) of class c in a map word, cells
 * beyond the grid excluded. */
static uint64_t select_class(const fl_scan_t *s, int32_t j, int32_t w,
                             fl_color_class_t c)
{
    uint64_t x = s->map[j][w], lo = x & EVEN, hi = (x >> 1) & EVEN, sel;
    int32_t n = s->cols - 32 * w;
    switch (c) {
    case FL_CLASS_GREEN: sel = lo & ~hi; break;
    case FL_CLASS_WHITE: sel = hi & ~lo; break;
    case FL_CLASS_YELLOW: sel = lo & hi; break;
    default: sel = ~(lo | hi) & EVEN; break;
    }
    if (n < 32)
        sel &= ~((1ULL << (64 - 2 * n)) - 1);
    return sel;
}

uint32_t fl_scan_mask_word(const fl_scan_t *s, int32_t j, int32_t w,
                           fl_color_class_t c)
{
    uint64_t x;
    if (s == NULL || j < 0 || j >= s->rows || w < 0 || w >= s->words)
        return 0;
    x = select_class(s, j, w, c);
    x = (x | (x >> 1)) & 0x3333333333333333ULL;
    x = (x | (x >> 2)) & 0x0F0F0F0F0F0F0F0FULL;
    x = (x | (x >> 4)) & 0x00FF00FF00FF00FFULL;
    x = (x | (x >> 8)) & 0x0000FFFF0000FFFFULL;
    x = (x | (x >> 16)) & 0x00000000FFFFFFFFULL;
    return (uint32_t)x;
}

int32_t fl_scan_count(const fl_scan_t *s, fl_color_class_t c)
{
    int32_t j, w, n = 0;
    if (s == NULL)
        return 0;
    for (j = 0; j < s->rows; j++)
        for (w = 0; w < s->words; w++)
            n += popcount64(select_class(s, j, w, c));
    return n;
}
