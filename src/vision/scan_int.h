/*
 * src/vision/scan_int.h - internals shared by the column scanner's files
 * (not installed; not part of the API):
 *   scan.c         public entry points, parameters, the per-frame driver,
 *                  accessors of the class map
 *   scan_band.c    phases A and B, the hot part: word classification, the
 *                  candidate rows, the per-band row logic (one translation
 *                  unit so that the per-pixel and per-row code inlines)
 *   scan_border.c  phase A': extend borders over lines, reject green
 *                  clutter bumps, repair columns without a border
 *   scan_post.c    phase C: goal posts traced up from the border
 *   scan_field.c   phase D: field color estimate
 * The per-pixel helpers below are static inline so that every file that
 * walks a column gets them inlined (and specialised on a constant pixel
 * layout where the caller passes one).
 */
#ifndef FIELDLOC_SCAN_INT_H
#define FIELDLOC_SCAN_INT_H

#include "fieldloc/scan.h"

#define EVEN 0x5555555555555555ULL
#define ODD 0xAAAAAAAAAAAAAAAAULL

/* Kept out of its caller (gcc's inlining limits are then spent on the
 * caller's hot loops); no effect on results. */
#if defined(__GNUC__)
#define FL_NOINLINE __attribute__((noinline))
#else
#define FL_NOINLINE
#endif

/* Inlined where a constant argument (a pixel layout) lets a whole walk be
 * specialised; no effect on results. */
#if defined(__GNUC__)
#define FL_INLINE inline __attribute__((always_inline))
#else
#define FL_INLINE inline
#endif

/* ---- pixel access ------------------------------------------------------------ */

typedef struct {
    const fl_color_table_t *ct;
    fl_pixel_format_t fmt;
    const uint8_t *p0, *p1, *p2;
    size_t st0, st1, st2;
    int32_t cs, rs;
    /* col_init's layout, per format: pixel u's Y (R) at py + ky u, its
     * chroma at pcb / pcr + kc (u >> csh); rows scb / scr apart */
    const uint8_t *py, *pcb, *pcr;
    size_t ky, kc, scb, scr;
    int32_t csh;
} frame_t;

/* One image column as three byte pointers (Y, Cb, Cr of pixel (u, 0); for
 * RGB888 y points at R) and the bytes from one pixel row to the next. */
typedef struct {
    const uint8_t *y, *cb, *cr;
    size_t sy, scb, scr;
    bool rgb;
} col_t;

static inline void col_init(col_t *c, const frame_t *f, int32_t u)
{
    size_t uu = (size_t)u, ch = uu >> f->csh;
    c->rgb = f->fmt == FL_FMT_RGB888;
    c->sy = f->st0;
    c->scb = f->scb;
    c->scr = f->scr;
    c->y = f->py + f->ky * uu;
    c->cb = f->pcb + f->kc * ch;
    c->cr = f->pcr + f->kc * ch;
}

/* Class of one pixel by the tables of color.h: RGB888 at q (R, G, B), or
 * Y, Cb, Cr. */
static FL_INLINE int32_t px_class_rgb(const fl_color_table_t *ct, const uint8_t *q)
{
    unsigned g = q[1];
    return ct->pattern[(unsigned)ct->rgb_chroma[(unsigned)ct->rgb_dr[q[0] + 255u - g] +
                                                ct->rgb_db[q[2] + 255u - g]] + g];
}

static FL_INLINE int32_t px_class_ycc(const fl_color_table_t *ct, unsigned y, unsigned cb,
                                      unsigned cr)
{
    return ct->pattern[(size_t)ct->chroma[(cb << 8) | cr] + y];
}

/* Pixel layout of a frame for col_class_k: 0 RGB, 1 YUYV (one stride for
 * the three bytes), 2 planar (a stride per plane). */
static inline int32_t col_kind(const frame_t *f)
{
    return f->fmt == FL_FMT_RGB888 ? 0 : (f->fmt == FL_FMT_YUYV422 ? 1 : 2);
}

/* col_class for a walk specialised on kind (a constant where inlined):
 * no test of the layout per sample, one offset for the packed ones. */
static FL_INLINE int32_t col_class_k(const col_t *c, const fl_color_table_t *ct,
                                     int32_t v, int32_t kind)
{
    size_t o = (size_t)v * c->sy;
    if (kind == 0)
        return px_class_rgb(ct, c->y + o);
    if (kind == 1)
        return px_class_ycc(ct, c->y[o], c->cb[o], c->cr[o]);
    return px_class_ycc(ct, c->y[o], c->cb[(size_t)v * c->scb], c->cr[(size_t)v * c->scr]);
}

/* Class of the column's pixel in row v (any layout). */
static inline int32_t col_class(const col_t *c, const fl_color_table_t *ct, int32_t v)
{
    size_t vv = (size_t)v;
    if (c->rgb)
        return px_class_rgb(ct, c->y + vv * c->sy);
    return px_class_ycc(ct, c->y[vv * c->sy], c->cb[vv * c->scb], c->cr[vv * c->scr]);
}

/* col_init for col_class_k of the same kind (the packed layouts need only
 * y, cb, cr and one stride). */
static FL_INLINE void col_init_k(col_t *c, const frame_t *f, int32_t u, int32_t kind)
{
    size_t uu = (size_t)u;
    if (kind == 0) {
        c->y = c->cb = c->cr = f->p0 + 3 * uu;
        c->sy = c->scb = c->scr = f->st0;
        c->rgb = true;
    } else if (kind == 1) {
        c->y = f->p0 + 2 * uu;
        c->cb = f->p0 + 1 + 4 * (uu >> 1);
        c->cr = c->cb + 2;
        c->sy = c->scb = c->scr = f->st0;
        c->rgb = false;
    } else {
        col_init(c, f, u);
    }
}

/* ---- bit helpers ----------------------------------------------------------------- */

/* Index of the lowest set bit of x != 0 (de Bruijn). */
static inline int32_t lowest_bit(uint64_t x)
{
    static const uint8_t tab[64] = {
        0, 1, 2, 53, 3, 7, 54, 27, 4, 38, 41, 8, 34, 55, 48, 28,
        62, 5, 39, 46, 44, 42, 22, 9, 24, 35, 59, 56, 49, 18, 29, 11,
        63, 52, 6, 26, 37, 40, 33, 47, 61, 45, 43, 21, 23, 58, 17, 10,
        51, 25, 36, 32, 60, 20, 57, 16, 50, 31, 19, 15, 30, 14, 13, 12};
    return tab[((x & (~x + 1)) * 0x022FDD63CC95386DULL) >> 58];
}

static inline int32_t popcount64(uint64_t x)
{
    x = x - ((x >> 1) & EVEN);
    x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
    x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
    return (int32_t)((x * 0x0101010101010101ULL) >> 56);
}

static inline int32_t map_class(const fl_scan_t *s, int32_t i, int32_t j)
{
    return (int32_t)((s->map[j][i >> 5] >> (62 - 2 * (i & 31))) & 3);
}

/* A yellow->green transition at grid column i, pixel (u, v), within the
 * per-column and total caps (phase B and the post trace). */
static inline void add_foot(fl_scan_t *s, int32_t i, int32_t u, int32_t v)
{
    if (s->col_feet[i] >= s->params.feet_per_column || s->n_feet >= FL_SCAN_MAX_FEET) {
        s->feet_dropped++;
        return;
    }
    s->col_feet[i]++;
    s->feet[s->n_feet].u = (int16_t)u;
    s->feet[s->n_feet].v = (int16_t)v;
    s->n_feet++;
}

/* ---- the phases, one per file (called in this order by fl_scan_frame) ---- */

/* Phases A and B for band w (32 grid columns) from grid row j0 (scan_band.c):
 * border candidates, the class map of the band, borders, white checks,
 * feet, yellow counts. */
void fl_scan_internal_band(fl_scan_t *s, const frame_t *f, int32_t w, int32_t j0,
                           int32_t ns);
/* Phase A' (scan_border.c): every border extended up over a thin line with
 * carpet or a post above it (lo: first searched grid row; max_white: 2 N px
 * in grid rows); columns without a border get first_row = rows. */
void fl_scan_internal_extend_borders(fl_scan_t *s, const frame_t *f, int32_t ns,
                                     int32_t lo, int32_t max_white);
/* Phase A' (scan_border.c): green clutter bumps above the flat border
 * rejected (left to right, then right to left). */
void fl_scan_internal_reject_bumps(fl_scan_t *s, const frame_t *f, int32_t ns);
/* Phase A' (scan_border.c): columns without a border between columns
 * with one get the top of their lowest stretch of field colors. */
void fl_scan_internal_repair_borders(fl_scan_t *s, const frame_t *f);
/* scan_board.c: without a horizon, green regions above a wall or gap over
 * the carpet connected to the bottom are not the field. */
void fl_scan_internal_reject_boards(fl_scan_t *s, const frame_t *f, int32_t ns);
/* Phase C (scan_post.c): yellow above the border of the post_top columns
 * into the map, and a foot at the border of each post. */
void fl_scan_internal_trace_posts(fl_scan_t *s, const frame_t *f);
/* Phase D (scan_field.c): s->field from samples below the border. */
void fl_scan_internal_estimate_field(fl_scan_t *s, const frame_t *f);

#endif /* FIELDLOC_SCAN_INT_H */
