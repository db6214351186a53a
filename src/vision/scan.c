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
 * Cost (x86-64 host, gcc 12 -O2, callgrind, tools/bench/callgrind.sh, UvA 2013
 *  320x240 frame): full resolution YUYV 629k instructions per frame (8.2
 *  per pixel), RGB 924k (12.0); default 2 x 2 grid YUYV 243k (3.2 per
 *  image pixel), RGB 298k (3.9).  Where the default YUYV frame's
 *  instructions go: the lookups of phase B ~150k (9 per classified cell:
 *  at col_step 2 every sample is the even pixel of its own YUYV pair, so
 *  the chroma lookup is not shared as at full resolution, where a pair
 *  costs 12 = 6 per pixel; an RGB cell costs 11: three byte loads, R - G
 *  and B - G, two bucket loads (the second added from memory), the cell,
 *  the pattern base, the pattern, the accumulate), the row logic of B
 *  (white checks and border refinement included), and the per-column
 *  scalar phases, which do not shrink with the grid (A' extend, bumps, C,
 *  D: exact HSV of ~84 samples).  The scalar walks (extend, border
 *  refinement, white checks, post trace) are specialised per pixel layout
 *  (col_class_k: no layout test per sample, one offset for the three
 *  bytes of RGB and YUYV).  The 5 instructions per pixel of issue 4 are
 *  out of reach for this design: the classification alone is 6.06 per
 *  pixel (YUYV) and 11.12 (RGB) (callgrind on the topnoise frame, every
 *  row classified), and a cheaper one would need a bigger table than the
 *  256 KiB budget (an RGB table indexed by raw R - G and B - G is 522 KB).
 *  Worst case bounded by cells + per-column caps: "topnoise" (12 carpet
 *  rows on top, uniform noise below: every column bordered in row 0, every
 *  cell below classified and checked) full RGB 1.78M, YUYV 1.48M; default
 *  RGB 487k, YUYV 523k.  Uniform noise alone is cheaper (full RGB 607k):
 *  phase A finds no run of N green and leaves the bands unclassified.
 */
#include "fieldloc/scan.h"

#include <string.h>

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

fl_status_t fl_scan_init(fl_scan_t *s, const fl_scan_params_t *p)
{
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
static int32_t col_kind(const frame_t *f)
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

/* Pixel row v upward from the border's first pixel row while the column
 * is green, not above lo (border_found's refinement between grid rows). */
static FL_INLINE int32_t refine_up(const frame_t *f, int32_t u, int32_t v, int32_t lo,
                                   int32_t kind)
{
    col_t col;
    col_init_k(&col, f, u, kind);
    while (v - 1 >= lo && col_class_k(&col, f->ct, v - 1, kind) == FL_CLASS_GREEN)
        v--;
    return v;
}

/* BT.601 luma (RGB888, fl_luma_from_rgb inline: hot in white_keep) or Y
 * of the column's pixel in row v, for kind (see col_class_k). */
static FL_INLINE int32_t col_luma_k(const col_t *c, int32_t v, int32_t kind)
{
    size_t o = (size_t)v * c->sy;
    if (kind == 0) {
        const uint8_t *q = c->y + o;
        return (19595 * q[0] + 38470 * q[1] + 7471 * q[2] + 32768) >> 16;
    }
    return c->y[o];
}

/* R, G, B of the column's pixel in row v. */
static void col_rgb(const col_t *c, int32_t v, uint8_t rgb[3])
{
    size_t vv = (size_t)v;
    if (c->rgb) {
        const uint8_t *q = c->y + vv * c->sy;
        rgb[0] = q[0];
        rgb[1] = q[1];
        rgb[2] = q[2];
        return;
    }
    fl_rgb_from_ycbcr(c->y[vv * c->sy], c->cb[vv * c->scb], c->cr[vv * c->scr], rgb);
}

static FL_INLINE int32_t px_luma_k(const frame_t *f, int32_t u, int32_t v, int32_t kind)
{
    col_t c;
    col_init_k(&c, f, u, kind);
    return col_luma_k(&c, v, kind);
}

/* ---- word classification (phase B) ----------------------------------------------
 * 32 cells -> 64 bits, cell k at bits 63 - 2k, 62 - 2k. */

/* YUYV at full resolution: 16 pixel pairs from q (an even pixel). */
static uint64_t word_yuyv_pairs(const uint8_t *q, const uint16_t *chroma,
                                const uint8_t *pat)
{
    uint64_t acc = 0;
    const uint8_t *r;
#define FL_PAIR(k)                                                              \
    r = pat + chroma[((unsigned)q[4 * (k) + 1] << 8) | q[4 * (k) + 3]];         \
    acc = (acc << 2) + r[q[4 * (k)]];                                           \
    acc = (acc << 2) + r[q[4 * (k) + 2]];
    FL_PAIR(0) FL_PAIR(1) FL_PAIR(2) FL_PAIR(3)
    FL_PAIR(4) FL_PAIR(5) FL_PAIR(6) FL_PAIR(7)
    FL_PAIR(8) FL_PAIR(9) FL_PAIR(10) FL_PAIR(11)
    FL_PAIR(12) FL_PAIR(13) FL_PAIR(14) FL_PAIR(15)
#undef FL_PAIR
    return acc;
}

/* RGB, 32 cells D bytes apart from q.  D is a literal in the common
 * cases so that every address is a constant offset. */
/* Index arithmetic in ptrdiff_t / unsigned so that no result needs a sign
 * extension (tr, tb point at the difference 0 of their tables). */
#define FL_RGB(k)                                                             \
    g_ = q[(k) * D + 1];                                                      \
    acc = (acc << 2) + pat[(ptrdiff_t)rc[(unsigned)tr[(ptrdiff_t)q[(k) * D] - g_] + \
                                         tb[(ptrdiff_t)q[(k) * D + 2] - g_]] + g_];
#define FL_RGB8(k) FL_RGB(k) FL_RGB(k + 1) FL_RGB(k + 2) FL_RGB(k + 3) \
    FL_RGB(k + 4) FL_RGB(k + 5) FL_RGB(k + 6) FL_RGB(k + 7)
#define FL_RGB_WORD(name)                                                     \
    static uint64_t name(const uint8_t *q, size_t d, const fl_color_table_t *ct) \
    {                                                                         \
        const uint32_t *tr = ct->rgb_dr + 255, *tb = ct->rgb_db + 255;       \
        const uint16_t *rc = ct->rgb_chroma;                                  \
        const uint8_t *pat = ct->pattern;                                     \
        ptrdiff_t g_;                                                         \
        uint64_t acc = 0;                                                     \
        (void)d;                                                              \
        FL_RGB8(0) FL_RGB8(8) FL_RGB8(16) FL_RGB8(24)                         \
        return acc;                                                           \
    }
#define D 3
FL_RGB_WORD(word_rgb_1)
#undef D
#define D 6
FL_RGB_WORD(word_rgb_2)
#undef D
#define D d
FL_RGB_WORD(word_rgb)
#undef D

/* YUYV, 32 cells on even pixels D bytes apart from q (D = 2 col_step). */
#define FL_YE(k) acc = (acc << 2) + pat[(size_t)chroma[((unsigned)q[(k) * D + 1] << 8) | \
                                                        q[(k) * D + 3]] + q[(k) * D]];
#define FL_YE8(k) FL_YE(k) FL_YE(k + 1) FL_YE(k + 2) FL_YE(k + 3) \
    FL_YE(k + 4) FL_YE(k + 5) FL_YE(k + 6) FL_YE(k + 7)
#define FL_YE_WORD(name)                                                      \
    static uint64_t name(const uint8_t *q, size_t d, const uint16_t *chroma,  \
                         const uint8_t *pat)                                  \
    {                                                                         \
        uint64_t acc = 0;                                                     \
        (void)d;                                                              \
        FL_YE8(0) FL_YE8(8) FL_YE8(16) FL_YE8(24)                             \
        return acc;                                                           \
    }
#define D 4
FL_YE_WORD(word_yuyv_2)
#undef D
#define D d
FL_YE_WORD(word_yuyv_even)
#undef D

/* Any format and step, n cells (1..32) of pixel row v from cell i0. */
static uint64_t word_generic(const frame_t *f, int32_t v, int32_t i0, int32_t n)
{
    const fl_color_table_t *ct = f->ct;
    uint64_t acc = 0;
    int32_t k;
    for (k = 0; k < n; k++) {
        col_t c;
        col_init(&c, f, (i0 + k) * f->cs);
        acc = (acc << 2) + (uint64_t)col_class(&c, ct, v);
    }
    return acc << (2 * (32 - n));
}

/* Row j of band w (n cells; row points at pixel row j * rs of plane 0)
 * through the word function of its kind: the candidate rows of phase A
 * and the rarer kinds of band_rows (six arguments: all in registers). */
static uint64_t band_word(const frame_t *f, int32_t kind, const uint8_t *row,
                          int32_t j, int32_t w, int32_t n)
{
    const fl_color_table_t *ct = f->ct;
    size_t cs = (size_t)f->cs, u0 = (size_t)w * 32 * cs;
    /* the common kinds first: a predicted compare is cheaper than the
     * jump table */
    if (kind == 4)
        return word_yuyv_2(row + 2 * u0, 4, ct->chroma, ct->pattern);
    if (kind == 1)
        return word_yuyv_pairs(row + 2 * u0, ct->chroma, ct->pattern);
    switch (kind) {
    case 2: return word_yuyv_even(row + 2 * u0, 2 * cs, ct->chroma, ct->pattern);
    case 3: return word_rgb(row + 3 * u0, 3 * cs, ct);
    case 5: return word_rgb_1(row + 3 * u0, 3, ct);
    case 6: return word_rgb_2(row + 3 * u0, 6, ct);
    default: return word_generic(f, j * f->rs, 32 * w, n);
    }
}

/* ---- bit helpers ----------------------------------------------------------------- */

/* Index of the lowest set bit of x != 0 (de Bruijn). */
static int32_t lowest_bit(uint64_t x)
{
    static const uint8_t tab[64] = {
        0, 1, 2, 53, 3, 7, 54, 27, 4, 38, 41, 8, 34, 55, 48, 28,
        62, 5, 39, 46, 44, 42, 22, 9, 24, 35, 59, 56, 49, 18, 29, 11,
        63, 52, 6, 26, 37, 40, 33, 47, 61, 45, 43, 21, 23, 58, 17, 10,
        51, 25, 36, 32, 60, 20, 57, 16, 50, 31, 19, 15, 30, 14, 13, 12};
    return tab[((x & (~x + 1)) * 0x022FDD63CC95386DULL) >> 58];
}

static int32_t popcount64(uint64_t x)
{
    x = x - ((x >> 1) & EVEN);
    x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
    x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
    return (int32_t)((x * 0x0101010101010101ULL) >> 56);
}

/* Low bit of cell k (0..31) in a word. */
static uint64_t cell_bit(int32_t k)
{
    return 1ULL << (62 - 2 * k);
}

static int32_t map_class(const fl_scan_t *s, int32_t i, int32_t j)
{
    return (int32_t)((s->map[j][i >> 5] >> (62 - 2 * (i & 31))) & 3);
}

/* ---- phase B helpers ------------------------------------------------------------------ */

static void add_foot(fl_scan_t *s, int32_t i, int32_t u, int32_t v)
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

#define WHITE_CLIP 250

/* Contrast check of a white run starting at cell (i, j), k = i % 32 in its
 * word; g1, g2: green of the two rows above in this word (words left of it
 * and this word are final in the map for row j).  True: keep. */
static FL_INLINE bool white_keep_k(fl_scan_t *s, const frame_t *f, int32_t i, int32_t j,
                                   uint64_t g1, uint64_t g2, int32_t kind)
{
    int32_t k = i & 31;
    int32_t v = j * f->rs, lw, lg = -1, d;
    col_t col;
    if (s->col_checks[i] >= s->params.checks_per_column) {
        s->checks_skipped++;
        return true;
    }
    s->col_checks[i]++;
    col_init_k(&col, f, i * f->cs, kind);
    /* brightest pixel from this sample to the next: a thin line sampled
     * on its blurred edge still shows its core */
    lw = col_luma_k(&col, v, kind);
    for (d = 1; d <= f->rs && v + d < s->height && lw < WHITE_CLIP; d++) {
        int32_t l2 = col_luma_k(&col, v + d, kind);
        if (l2 > lw)
            lw = l2;
    }
    if (lw >= WHITE_CLIP)
        return true;  /* clipped (then the loop stopped at once): passes
                       * whatever the green (see below) */
    /* the darkest green of the three samples above: the one right above a
     * line is often its blurred edge, brighter than the carpet */
    if (g1 & cell_bit(k))
        lg = col_luma_k(&col, v - f->rs, kind);
    if (g2 & cell_bit(k)) {
        int32_t l2 = col_luma_k(&col, v - 2 * f->rs, kind);
        lg = lg < 0 || l2 < lg ? l2 : lg;
    }
    if (lg >= 0 && v - 3 * f->rs >= 0 &&
        col_class_k(&col, f->ct, v - 3 * f->rs, kind) == FL_CLASS_GREEN) {
        int32_t l3 = col_luma_k(&col, v - 3 * f->rs, kind);
        lg = l3 < lg ? l3 : lg;
    }
    for (d = 1; d <= 2 && lg < 0; d++) {
        if (i - d >= 0 && map_class(s, i - d, j) == FL_CLASS_GREEN)
            lg = px_luma_k(f, (i - d) * f->cs, v, kind);
        else if (i + d < s->cols && ((i + d) >> 5) == (i >> 5) &&
                 map_class(s, i + d, j) == FL_CLASS_GREEN)
            lg = px_luma_k(f, (i + d) * f->cs, v, kind);
    }
    if (lg < 0) {
        if (s->field.n <= 0)
            return true;
        lg = s->field.luma;   /* the previous frame's field */
    }
    /* Scaling: luma <= 255, products <= 255 * 300.  A clipped white
     * (luma >= WHITE_CLIP) passes: over carpet brighter than ~200 the
     * contrast asked for lies beyond what the sensor can show. */
    return lw * 100 >= lg * (100 + (int32_t)f->ct->params.white_contrast_pct);
}

/* white_keep_k per pixel layout. */
static bool white_keep(fl_scan_t *s, const frame_t *f, int32_t i, int32_t j,
                       uint64_t g1, uint64_t g2)
{
    if (f->fmt == FL_FMT_YUYV422)
        return white_keep_k(s, f, i, j, g1, g2, 1);
    if (f->fmt == FL_FMT_RGB888)
        return white_keep_k(s, f, i, j, g1, g2, 0);
    return white_keep_k(s, f, i, j, g1, g2, 2);
}

static void count_yellow(uint64_t *planes, uint64_t x)
{
    int32_t p;
    for (p = 0; p < FL_SCAN_COUNT_BITS && x != 0; p++) {
        uint64_t t = planes[p] & x;
        planes[p] ^= x;
        x = t;
    }
}

/* A column's run of ns green samples completed at grid row j: its border. */
static void border_found(fl_scan_t *s, const frame_t *f, int32_t i, int32_t j,
                         int32_t ns)
{
    int32_t st = j - ns + 1, v = st * f->rs, lo;
    lo = (st - 1) * f->rs + 1;
    if (lo < s->start_v)
        lo = s->start_v;
    if (f->rs > 1) {   /* refine between grid rows */
        if (f->fmt == FL_FMT_YUYV422)
            v = refine_up(f, i * f->cs, v, lo, 1);
        else if (f->fmt == FL_FMT_RGB888)
            v = refine_up(f, i * f->cs, v, lo, 0);
        else
            v = refine_up(f, i * f->cs, v, lo, 2);
    }
    s->border_v[i] = (int16_t)v;
    s->first_row[i] = (int16_t)st;
    s->gend_row[i] = (int16_t)st;
    s->n_border++;
}

/* Green in the top grid row within 32 px of column i (left or right): a
 * white stretch from the border up to the top of an all-ground image is a
 * line cut by the top when carpet shows beside it there; the floor beyond a
 * field whose far edge is in view is white-ish (S ~ 30) across the width. */
static bool green_near_top(const fl_scan_t *s, const frame_t *f, int32_t i)
{
    int32_t reach = 32 / f->cs > 1 ? 32 / f->cs : 1, d;
    for (d = 1; d <= reach; d++) {
        col_t col;
        if (i - d >= 0) {
            col_init(&col, f, (i - d) * f->cs);
            if (col_class(&col, f->ct, 0) == FL_CLASS_GREEN)
                return true;
        }
        if (i + d < s->cols) {
            col_init(&col, f, (i + d) * f->cs);
            if (col_class(&col, f->ct, 0) == FL_CLASS_GREEN)
                return true;
        }
    }
    return false;
}

/* The first of the samples j0 + ns - 1, j0 + 2 ns - 1, ... of column i
 * that is green (rows when none): what first_row holds for a column
 * without a border until the loop over the columns after phase B reaches
 * it (extend_border reads it for columns to the right). */
static int32_t column_candidate(const fl_scan_t *s, const frame_t *f, int32_t i,
                                int32_t j0, int32_t ns)
{
    int32_t j;
    col_t col;
    col_init(&col, f, i * f->cs);
    for (j = j0 + ns - 1; j < s->rows; j += ns)
        if (col_class(&col, f->ct, j * f->rs) == FL_CLASS_GREEN)
            return j;
    return s->rows;
}

/* Above the border.  Far away the carpet beyond the boundary line is a
 * strip thinner than N: the first run of N is then below the line.  From
 * the border up: a white stretch of at most 2 N px (a line) with green
 * right above it moves the border to the top of that green (twice at most:
 * two lines); with yellow above it (a post standing on the line) to the top
 * of the white.  Yellow right above the border (or above the line, or with
 * one other sample between) marks the column for the post trace (phase C).
 * The cells passed are classified into the map (they were masked).  lo:
 * the first searched grid row; max_white: 2 N px in grid rows (both
 * computed once per frame). */
static FL_INLINE void extend_border(fl_scan_t *s, const frame_t *f, int32_t i,
                                    int32_t ns, int32_t lo, int32_t max_white,
                                    int32_t kind)
{
    const fl_color_table_t *ct = f->ct;
    int32_t rs = f->rs, jb = s->first_row[i], k, j;
    uint64_t shift = (uint64_t)(62 - 2 * (i & 31));
    col_t col;
    col_init_k(&col, f, i * f->cs, kind);
    for (k = 0; k < 2; k++) {
        int32_t jw = jb - 1, jg, c = -1, jstop = jb - max_white > lo ? jb - max_white : lo;
        uint64_t *mp;
        /* c keeps the class of the sample that ended the walk (-1: the
         * walk ended on a bound), so it is not classified twice */
        while (jw >= jstop) {
            c = col_class_k(&col, ct, jw * rs, kind);
            if (c != FL_CLASS_WHITE)
                break;
            c = -1;
            jw--;
        }
        if (c < 0) {   /* (else jw >= jstop: inside both bounds) */
            if (jw < lo && lo == 0 && s->below_horizon && jw < jb - 1 &&
                green_near_top(s, f, i)) {
                /* a line cut by the top of an image that is all ground
                 * (the walk found every sample above the border white) */
                for (j = 0; j < jb; j++)
                    s->map[j][i >> 5] |= (uint64_t)FL_CLASS_WHITE << shift;
                s->first_row[i] = 0;
                s->border_v[i] = 0;
                return;
            }
            if (jw < 0 || jb - jw > max_white)
                return;
            c = col_class_k(&col, ct, jw * rs, kind);
        }
        /* one other sample (the blurred edge) may sit under a post */
        if (c == FL_CLASS_OTHER && jw > 0 &&
            col_class_k(&col, ct, (jw - 1) * rs, kind) == FL_CLASS_YELLOW)
            c = FL_CLASS_YELLOW;
        if (c == FL_CLASS_YELLOW) {
            if (jw == jb - 1) {
                s->post_top[i >> 5] |= 1ULL << shift;
                return;
            }
            /* a post standing on a line (thin: not a floor strip beyond
             * the carpet under a yellow box): the line is field */
            int32_t q, wmin = s->rows;
            for (q = i - 2 * ns; q <= i + 2 * ns; q++) {
                int32_t fq;
                if (q < 0 || q >= s->cols || q == i)
                    continue;
                fq = s->first_row[q];
                if (q > i && s->border_v[q] >= s->height)
                    fq = column_candidate(s, f, q, lo, ns);
                if (fq < wmin)
                    wmin = fq;
            }
            /* ... and inside the field: its line lies below the carpet
             * edge of the columns around it */
            if (jw < lo || 2 * (jb - 1 - jw) > ns || jw + 1 <= wmin)
                return;
            s->post_top[i >> 5] |= 1ULL << shift;
            jg = jw + 1;
        } else if (c == FL_CLASS_GREEN && jw < jb - 1 && jw >= lo) {
            jg = jw;
            while (jg - 1 >= lo && col_class_k(&col, ct, (jg - 1) * rs, kind) == FL_CLASS_GREEN)
                jg--;
        } else {
            return;
        }
        /* the walks classified these samples: green up to jw, white
         * below it */
        mp = &s->map[jg][i >> 5];
        for (j = jg; j <= jw; j++, mp += FL_SCAN_WORDS)
            *mp |= (uint64_t)FL_CLASS_GREEN << shift;
        for (; j < jb; j++, mp += FL_SCAN_WORDS)
            *mp |= (uint64_t)FL_CLASS_WHITE << shift;
        jb = jg;
        s->first_row[i] = (int16_t)jb;
        s->border_v[i] = (int16_t)(jb * rs);
        if (c == FL_CLASS_YELLOW)
            return;
    }
}

/* extend_border for every column with a border (the others get first_row
 * = rows), one loop per pixel layout. */
static FL_INLINE void extend_all(fl_scan_t *s, const frame_t *f, int32_t ns, int32_t lo,
                                 int32_t max_white, int32_t kind)
{
    int32_t i;
    for (i = 0; i < s->cols; i++) {
        if (s->border_v[i] >= s->height)
            s->first_row[i] = (int16_t)s->rows;   /* no run found */
        else
            extend_border(s, f, i, ns, lo, max_white, kind);
    }
}

static FL_NOINLINE void extend_borders(fl_scan_t *s, const frame_t *f, int32_t ns,
                                       int32_t lo, int32_t max_white)
{
    int32_t kind = col_kind(f);
    if (kind == 1)
        extend_all(s, f, ns, lo, max_white, 1);
    else if (kind == 0)
        extend_all(s, f, ns, lo, max_white, 0);
    else
        extend_all(s, f, ns, lo, max_white, 2);
}

/* Word function of band w: 0 generic, 1 YUYV pairs, 2 YUYV even pixels,
 * 3 RGB, 4 YUYV col_step 2, 5 RGB col_step 1, 6 RGB col_step 2. */
static int32_t band_kind(const frame_t *f, int32_t n)
{
    size_t cs = (size_t)f->cs;
    if (n == 32 && f->fmt == FL_FMT_YUYV422)
        return cs == 1 ? 1 : (cs == 2 ? 4 : ((cs & 1) == 0 ? 2 : 0));
    if (n == 32 && f->fmt == FL_FMT_RGB888)
        return cs == 1 ? 5 : (cs == 2 ? 6 : 3);
    return 0;
}

/* Green cells of a classified word (class 1: low bit set, high bit clear),
 * on the EVEN bits. */
#define GREEN_OF(c) ((c) & ~((c) >> 1) & EVEN)

/* Longest run looked for around a phase A row: up to this many rows above
 * it are kept on the stack (8 bytes each); a longer run (N above 16 grid
 * rows) skips the test (every row with a green cell is taken, as before). */
#define RUN_PROBE_MAX 16

/* Phase A for band w: the first of the rows j0 + ns - 1, j0 + 2 ns - 1,
 * ... through which some column of the band is green on ns consecutive
 * rows (rows: none).  Every run of ns green samples below j0 contains one
 * of these rows, and only such a row has a run through it, so no run in
 * the band starts before that row - (ns - 1): the band's first row is
 * max(j0, that).  The test classifies the rows next to the sampled row
 * only while some column is still green (up[k]: the columns green on rows
 * j - k .. j; down: on j .. j + k), so on carpet it stops after ns - 1 rows
 * above and on a frame without carpet (noise, the sky, a robot held up)
 * after one or two, and the rest of the band is never classified.  The
 * rows it classified, cls[0] .. cls[1] around the returned row, are
 * left in the map as classified (band_rows skips them). */
static FL_NOINLINE int32_t band_start(fl_scan_t *s, const frame_t *f,
                                      int32_t w, int32_t j0, int32_t ns,
                                      int32_t cls[2])
{
    int32_t n = s->cols - 32 * w > 32 ? 32 : s->cols - 32 * w;
    int32_t kind = band_kind(f, n), j, rows = s->rows;
    size_t step = (size_t)f->rs * f->st0;
    uint64_t up[RUN_PROBE_MAX];
    for (j = j0 + ns - 1; j < rows; j += ns) {
        uint64_t c = band_word(f, kind, f->p0 + (size_t)j * step, j, w, n);
        int32_t ku, k, hi = j;
        bool run = false;
        up[0] = GREEN_OF(c);
        if (up[0] == 0)
            continue;
        s->map[j][w] = c;
        if (ns > RUN_PROBE_MAX || ns == 1) {
            cls[0] = cls[1] = j;
            return j;
        }
        /* up: rows j - 1 .. j - (ns - 1), not above j0 */
        for (ku = 1; ku < ns && j - ku >= j0; ku++) {
            c = band_word(f, kind, f->p0 + (size_t)(j - ku) * step, j - ku, w, n);
            s->map[j - ku][w] = c;
            up[ku] = up[ku - 1] & GREEN_OF(c);
            if (up[ku] == 0) {
                ku++;
                break;
            }
        }
        /* up[0 .. ku - 1] classified (later entries are 0) */
        if (ku == ns && up[ns - 1] != 0) {
            run = true;
        } else {
            uint64_t d = up[0];
            for (k = 1; k < ns && j + k < rows; k++) {
                c = band_word(f, kind, f->p0 + (size_t)(j + k) * step, j + k, w, n);
                s->map[j + k][w] = c;
                hi = j + k;
                d &= GREEN_OF(c);
                if (d == 0)
                    break;
                /* a run j - (ns - 1 - k) .. j + k */
                if (ns - 1 - k < ku && (up[ns - 1 - k] & d) != 0) {
                    run = true;
                    break;
                }
            }
        }
        if (run) {
            cls[0] = j - ku + 1;
            cls[1] = hi;
            return j;
        }
    }
    cls[0] = cls[1] = rows;
    return rows;
}

/* Rows j .. jend - 1 of band w classified into the map, unmasked (phase
 * B then reads them back; the common kinds first: a predicted compare is
 * cheaper than the jump table). */
static FL_NOINLINE void band_rows(fl_scan_t *s, const frame_t *f, int32_t j,
                                  int32_t jend, int32_t w)
{
    const fl_color_table_t *ct = f->ct;
    int32_t n = s->cols - 32 * w > 32 ? 32 : s->cols - 32 * w, kind = band_kind(f, n);
    size_t step = (size_t)f->rs * f->st0, u0 = (size_t)w * 32 * (size_t)f->cs;
    const uint8_t *row;
    uint64_t *mp, *end;
    if (j >= jend)
        return;
    row = f->p0 + (size_t)j * step;
    mp = &s->map[j][w];
    end = mp + (size_t)(jend - j) * FL_SCAN_WORDS;
    if (kind == 4) {
        for (; mp < end; mp += FL_SCAN_WORDS, row += step)
            *mp = word_yuyv_2(row + 2 * u0, 4, ct->chroma, ct->pattern);
    } else if (kind == 1) {
        for (; mp < end; mp += FL_SCAN_WORDS, row += step)
            *mp = word_yuyv_pairs(row + 2 * u0, ct->chroma, ct->pattern);
    } else if (kind == 5) {
        for (; mp < end; mp += FL_SCAN_WORDS, row += step)
            *mp = word_rgb_1(row + 3 * u0, 3, ct);
    } else if (kind == 6) {
        for (; mp < end; mp += FL_SCAN_WORDS, row += step)
            *mp = word_rgb_2(row + 3 * u0, 6, ct);
    } else {
        for (; mp < end; mp += FL_SCAN_WORDS, row += step, j++)
            *mp = band_word(f, kind, row, j, w, n);
    }
}


/* Columns (bits of leave) of band w whose first green run below the
 * border ends at grid row j: s->gend (what rerun_column's first walk
 * would find). */
static void gend_record(fl_scan_t *s, int32_t w, int32_t j, uint64_t leave)
{
    do {
        int32_t b = lowest_bit(leave);
        leave &= leave - 1;
        s->gend[32 * w + 31 - (b >> 1)] = (int16_t)j;
    } while (leave != 0);
}

/* The rest of a phase B row once c, lo, hi hold only the cells below the
 * border (shared by both loops of scan_band): carpet rows (only green and
 * other, no yellow in the two rows above) take the fast path; else white
 * run starts get their contrast check, yellow->green transitions become
 * feet and yellow cells are counted. */
#define FL_ROW_TAIL                                                           \
    if ((hi | y1 | y2) == 0) {                                                \
        /* only green and other (the carpet below the border): no white      \
         * run, no yellow, no foot; the row's state moves down (y1, y2 are   \
         * 0 already) */                                                      \
        *mp = c;                                                              \
        g2 = g1;                                                              \
        g1 = lo;                                                              \
        y3 = 0;                                                               \
        wprev = 0;                                                            \
        wrej = 0;                                                             \
        continue;                                                             \
    }                                                                         \
    g = lo & ~hi;                                                             \
    wh = hi & ~lo;                                                            \
    y = lo & hi;                                                              \
    *mp = c;                                                                  \
    rej = wrej & wh;                                                          \
    starts = wh & ~wprev;                                                     \
    if (starts != 0) {                                                        \
        int32_t last = -4;                                                    \
        bool keep = true;                                                     \
        while (starts != 0) {   /* right to left; one check per group */      \
            int32_t b = lowest_bit(starts), k = 31 - (b >> 1);                \
            starts &= starts - 1;                                             \
            if (b != last + 2)                                                \
                keep = white_keep(s, f, 32 * w + k, j, g1, g2);               \
            last = b;                                                         \
            if (!keep) {                                                      \
                rej |= 1ULL << b;                                             \
                s->white_rejected++;                                          \
            }                                                                 \
        }                                                                     \
    }                                                                         \
    if (rej != 0)                                                             \
        *mp = c & ~(rej | (rej << 1));                                        \
    wrej = rej;                                                               \
    wprev = wh;                                                               \
    /* two yellow samples right above, or above one non-green sample */      \
    cand = g & ~g1 & ((y1 & y2) | (y2 & y3));                                 \
    while (cand != 0) {                                                       \
        int32_t b = lowest_bit(cand), k = 31 - (b >> 1);                      \
        cand &= cand - 1;                                                     \
        add_foot(s, 32 * w + k, (32 * w + k) * f->cs, j * f->rs);             \
    }                                                                         \
    if (y != 0) {                                                             \
        count_yellow(ycount, y);                                              \
        s->yellow_rows[j] = (uint16_t)(s->yellow_rows[j] + popcount64(y));    \
    }                                                                         \
    g2 = g1;                                                                  \
    g1 = g;                                                                   \
    y3 = y2;                                                                  \
    y2 = y1;                                                                  \
    y1 = y;

/* Band w (32 grid columns): rows from j_lo down, each row classified once
 * (32 cells, all rows first, into the map: band_rows), then per row the run
 * detector for columns still without a border and the bit logic on the
 * cells below the border, each row's map word rewritten masked.  State
 * lives in locals.  Two loops: B1 while some column of the band has no
 * border yet (run counters, cells masked to the found columns), B2 once
 * all have one (no counters, no masking: the cells beyond a partial band's
 * last column are 0 from word_generic; carpet rows, the common case, only
 * move the state down: their map word is final as classified). */
static FL_NOINLINE void scan_band(fl_scan_t *s, const frame_t *f, int32_t w,
                                  int32_t j0, int32_t ns)
{
    /* jm: phase A's row (rows cls[0] .. cls[1] are in the map already);
     * rows when no run: nothing to scan (six arguments: all in registers) */
    int32_t cls[2], jm = band_start(s, f, w, j0, ns, cls);
    int32_t j_lo = jm >= s->rows ? s->rows : (jm - ns + 1 > j0 ? jm - ns + 1 : j0), nplanes;
    int32_t n = s->cols - 32 * w, rows = s->rows, j, p;
    uint64_t found = 0, g1 = 0, g2 = 0, y1 = 0, y2 = 0, y3 = 0, wprev = 0, wrej = 0;
    uint64_t ing = 0;   /* found, still in the border's green run */
    uint64_t cnt[8] = {0, 0, 0, 0, 0, 0, 0, 0}, m[8], all;
    uint64_t c0 = 0, c1 = 0, c2 = 0, c3 = 0, m0, m1, m2, m3;
    uint64_t *ycount = s->ycount[w], *mp;
    if (n > 32)
        n = 32;
    all = n == 32 ? EVEN : EVEN & ~((1ULL << (64 - 2 * n)) - 1);
    for (p = 0; p < 8; p++)
        m[p] = (ns >> p) & 1 ? 0 : ~0ULL;
    m0 = m[0];
    m1 = m[1];
    m2 = m[2];
    m3 = m[3];
    memset(ycount, 0, sizeof s->ycount[w]);
    for (j = 0; j < j_lo && j < rows; j++)
        s->map[j][w] = 0;
    mp = &s->map[0][w] + (size_t)j_lo * FL_SCAN_WORDS;
    j = j_lo;
    for (nplanes = 1; (1 << nplanes) <= ns; nplanes++)
        ;
    band_rows(s, f, j_lo, cls[0], w);
    band_rows(s, f, cls[1] + 1, rows, w);
    /* B1: until every column of the band has its border */
    for (; j < rows && found != all; j++, mp += FL_SCAN_WORDS) {
        uint64_t c = *mp, lo, hi, g, wh, y, starts, rej, cand;
        /* bit-sliced run counters: +1 where green, 0 elsewhere */
        uint64_t gr, x, eq;
        lo = c & EVEN;
        hi = (c >> 1) & EVEN;
        gr = lo & ~hi;
        x = gr & ~found;
        /* A counter never exceeds ns (a column that reaches ns is found
         * and leaves the count), so it equals ns exactly when it has
         * every bit of ns set: eq = x & the planes of ns's set bits
         * (m[p] all ones for the others). */
        if (nplanes <= 4) {   /* the common ns 1..15: in registers */
            uint64_t t = c0 & x, t2;
            c0 = ~c0 & x;
            t2 = c1 & t;
            c1 = (c1 ^ t) & x;
            t = c2 & t2;
            c2 = (c2 ^ t2) & x;
            c3 = (c3 ^ t) & x;
            eq = x & (c0 | m0) & (c1 | m1) & (c2 | m2) & (c3 | m3);
        } else {
            for (p = 0; p < nplanes; p++) {
                uint64_t t = cnt[p] & x;
                cnt[p] ^= x;
                x = t;
            }
            x = gr & ~found;
            eq = x;
            for (p = 0; p < nplanes; p++) {
                cnt[p] &= x;
                eq &= cnt[p] | m[p];
            }
        }
        if (eq != 0) {
            uint64_t e = eq;
            int32_t jj;
            found |= eq;
            ing |= eq;
            for (jj = j - ns + 1; jj < j; jj++)  /* the run was masked: green */
                s->map[jj][w] |= eq;
            while (e != 0) {
                int32_t b = lowest_bit(e);
                e &= e - 1;
                border_found(s, f, 32 * w + 31 - (b >> 1), j, ns);
            }
        } else if (found == 0) {
            /* no border in the band yet: the row is all masked and the
             * state (g, y, w of the rows above) is still all 0 */
            *mp = 0;
            continue;
        }
        if ((ing & ~gr) != 0) {   /* (ing is within found) */
            gend_record(s, w, j, ing & ~gr);
            ing &= gr;
        }
        c &= found | (found << 1);
        lo &= found;
        hi &= found;
        FL_ROW_TAIL
    }
    /* B2: every column has its border: no counters, no masking (a partial
     * band's cells beyond its last column are 0 from word_generic) */
    while (j < rows) {
        uint64_t c = *mp, lo, hi, g, wh, y, starts, rej, cand;
        if ((c & ODD) == 0 && (y1 | y2) == 0) {
            /* carpet rows (only green and other, no yellow in the two rows
             * above): the map holds them already; the state moves down */
            uint64_t *mq = mp, acc = c;
            const uint64_t *mlast = &s->map[rows - 1][w];
            int32_t j1 = j;
            /* the row count from the pointer afterwards: one instruction
             * less per carpet row */
            do {
                acc &= c;
                mq += FL_SCAN_WORDS;
            } while (mq <= mlast && ((c = *mq) & ODD) == 0);
            j += (int32_t)((mq - mp) / FL_SCAN_WORDS);
            /* green of the last two rows (g1 when only one) */
            g2 = j - j1 >= 2 ? mq[-2 * FL_SCAN_WORDS] & EVEN : g1;
            g1 = mq[-FL_SCAN_WORDS] & EVEN;
            if ((ing & ~acc) != 0) {
                /* columns that met other in these rows: find where */
                uint64_t leave = ing & ~acc;
                ing &= acc;
                for (; leave != 0; mp += FL_SCAN_WORDS, j1++) {
                    if ((leave & ~*mp) != 0) {
                        gend_record(s, w, j1, leave & ~*mp);
                        leave &= *mp;
                    }
                }
            }
            mp = mq;
            y3 = 0;
            wprev = 0;
            wrej = 0;
            continue;
        }
        lo = c & EVEN;
        hi = (c >> 1) & EVEN;
        if ((ing & ~(lo & ~hi)) != 0) {
            gend_record(s, w, j, ing & ~(lo & ~hi));
            ing &= lo & ~hi;
        }
        do {
            FL_ROW_TAIL
        } while (0);
        j++;
        mp += FL_SCAN_WORDS;
    }
    s->gend_none[w] = ing;   /* green down to the last row */
    for (p = 0; p < FL_SCAN_COUNT_BITS; p++) {   /* bit-sliced counts -> columns */
        uint64_t x = ycount[p];
        while (x != 0) {
            int32_t b = lowest_bit(x);
            x &= x - 1;
            s->yellow_cols[32 * w + 31 - (b >> 1)] =
                (uint16_t)(s->yellow_cols[32 * w + 31 - (b >> 1)] + (1 << p));
        }
    }
}
#undef FL_ROW_TAIL

/* Green clutter beyond the carpet (a couch, a bin, a shirt in carpet
 * green) stands up from the floor: its columns form a bump above the
 * border of the columns next to it.  Entering a bump is a step up of at
 * least t = max(2, ns / 2) rows; the bump goes on while the border stays t
 * rows above the level extrapolated from the 8 bordered columns before the
 * step.  In each of its columns the search goes on below the clutter in the
 * class map (classified below the old border): past the clutter's green, a
 * gap that looks like floor (an other cell, or at least ns white cells),
 * then the next run of ns green cells is the border if it starts within
 * [level - t, level + ns] (the clutter's green must end ns above the
 * level, the gap be at least ns samples).  Cells between the two borders return to
 * background (their yellow and feet removed).  Done left to right, then
 * right to left, so that bumps at either image edge are entered.  Robots
 * and posts in front of the carpet make dips and are left alone. */
static bool rerun_column(fl_scan_t *s, const frame_t *f, int32_t i, int32_t ns,
                         int32_t t, int32_t level)
{
    int32_t j = s->first_row[i], run = 0, st = -1, jj, k, v, lo, n_gap = 0, lim;
    int32_t wi = i >> 5, sh = 62 - 2 * (i & 31);
    uint64_t cell, green;
    if (s->first_row[i] == s->gend_row[i]) {
        /* phase B saw where this border's green run ends (the cells from
         * its border down are as phase B left them): the walk below would
         * stop there */
        if (s->gend_none[wi] & (1ULL << sh))
            return false;   /* green to the bottom */
        j = s->gend[i];
        if (j > level - ns)
            return false;
    } else {
        lim = level - ns < s->rows - 1 ? level - ns : s->rows - 1;
        while (j <= lim && ((s->map[j][wi] >> sh) & 3) == FL_CLASS_GREEN)
            j++;
        if (j > level - ns)
            return false;   /* the green (nearly) reaches the level: carpet */
    }
    /* a run completing below row level + 2 ns - 1 would start below
     * level + ns and be refused: the walk stops there */
    lim = level + 2 * ns - 1 < s->rows - 1 ? level + 2 * ns - 1 : s->rows - 1;
    cell = 3ULL << sh;
    green = (uint64_t)FL_CLASS_GREEN << sh;
    if (j <= lim) {
        const uint64_t *q = &s->map[j][wi];
        for (; j <= lim; j++, q += FL_SCAN_WORDS) {
            if ((*q & cell) == green) {
                if (++run >= ns) {
                    st = j - ns + 1;
                    break;
                }
            } else {
                run = 0;
                n_gap++;   /* other, white or yellow */
            }
        }
    }
    /* ... after a gap of at least ns other or white samples */
    if (st < 0 || st < level - t || st > level + ns || n_gap < ns)
        return false;
    for (jj = s->first_row[i]; jj < st; jj++) {
        if (map_class(s, i, jj) == FL_CLASS_YELLOW) {
            s->yellow_cols[i]--;
            s->yellow_rows[jj]--;
        }
        s->map[jj][i >> 5] &= ~(3ULL << (62 - 2 * (i & 31)));
    }
    v = st * f->rs;
    for (k = 0; k < s->n_feet; k++)   /* feet inside the clutter */
        if (s->feet[k].u == i * f->cs && s->feet[k].v < v) {
            s->feet[k] = s->feet[--s->n_feet];
            s->col_feet[i]--;
            k--;
        }
    lo = (st - 1) * f->rs + 1;
    if (f->rs > 1) {
        col_t col;
        col_init(&col, f, i * f->cs);
        while (v - 1 >= lo && col_class(&col, f->ct, v - 1) == FL_CLASS_GREEN)
            v--;
    }
    s->first_row[i] = (int16_t)st;
    s->border_v[i] = (int16_t)v;
    return true;
}

/* Level at column x of the line through window points (x0, y0), (x1, y1).
 * Scaling: |dy| <= 4096, |x - x0| <= 4096: products < 2^24. */
static int32_t level_at(int32_t x0, int32_t y0, int32_t x1, int32_t y1, int32_t x)
{
    return x1 == x0 || y1 == y0 ? y1 : y0 + (y1 - y0) * (x - x0) / (x1 - x0);
}

#define BUMP_WIN 8

/* The window wx (BUMP_WIN bordered columns, oldest at wh) is flat: every
 * border within t of the band between its end values (a line, or a gentle
 * curve; a dip breaks it). */
static bool window_flat(const int16_t *b, const int32_t *wx, int32_t wh, int32_t t)
{
    int32_t first = b[wx[wh]], last = b[wx[(wh + BUMP_WIN - 1) % BUMP_WIN]], k;
    int32_t lo_b = (first < last ? first : last) - t, hi_b = (first < last ? last : first) + t;
    for (k = 0; k < BUMP_WIN; k++)
        if (b[wx[k]] < lo_b || b[wx[k]] > hi_b)
            return false;
    return true;
}

/* The level of a flat window is only needed where a column steps up from
 * it, so the flatness is checked lazily there (same result as checking it
 * at every column: the window does not change in between). */
static void reject_bumps(fl_scan_t *s, const frame_t *f, int32_t ns, int32_t dir)
{
    const int16_t *b = s->first_row;
    int32_t t = ns / 2 > 2 ? ns / 2 : 2, rows = s->rows, cols = s->cols;
    int32_t wx[BUMP_WIN], wn = 0, wh = 0, i;
    for (i = dir > 0 ? 0 : cols - 1; i >= 0 && i < cols; i += dir) {
        int32_t last, r;
        if (b[i] >= rows)
            continue;
        if (wn == BUMP_WIN) {
            int32_t x0 = wx[wh], x1 = wx[(wh + BUMP_WIN - 1) % BUMP_WIN];
            int32_t y0 = b[x0], y1 = b[x1];
            if (b[i] < level_at(x0, y0, x1, y1, i) - t && window_flat(b, wx, wh, t)) {
                /* a bump: up to where the border comes back to the level
                 * (at most cols / 2 columns on, inside the image: r_end) */
                int32_t r_end = dir > 0 ? (i + cols / 2 < cols ? i + cols / 2 : cols)
                                        : (i - cols / 2 > -1 ? i - cols / 2 : -1);
                last = i;
                for (r = i; r != r_end; r += dir) {
                    int32_t lv;
                    if (b[r] >= rows)
                        continue;
                    lv = level_at(x0, y0, x1, y1, r);
                    if (b[r] >= lv - t)
                        break;
                    last = r;
                    /* changes column r only: the columns still to test
                     * keep the borders they had when the bump began */
                    (void)rerun_column(s, f, r, ns, t, lv);
                }
                i = last;
                continue;
            }
        }
        /* the window of the last BUMP_WIN bordered columns; post feet
         * (yellow right above) never make a level */
        if (s->post_top[i >> 5] & (1ULL << (62 - 2 * (i & 31)))) {
            wn = 0;
            continue;
        }
        wx[wh] = i;
        wh = (wh + 1) % BUMP_WIN;
        if (wn < BUMP_WIN)
            wn++;
    }
}

/* Columns without a border between columns with one: a field line running
 * down the column has no green.  Between the neighbours' border row and the
 * bottom, the lowest stretch of field colors (green or white, at most one
 * other sample in ten, no yellow) becomes the field; its top is the border
 * and its cells are classified into the map (white unchecked).  Only such
 * columns are read again, bottom-up, once. */
static void repair_borders(fl_scan_t *s, const frame_t *f)
{
    const fl_color_table_t *ct = f->ct;
    int32_t reach = 16 / f->cs > 2 ? 16 / f->cs : 2;
    /* l: the nearest column left of i with a border (repaired ones
     * included), r: the nearest right of i (not yet visited: as found) */
    int32_t i, l = -1, r = 0;
    for (i = 0; i < s->cols; i++) {
        int32_t ref = -1, j, n = 0, nf = 0, best = -1;
        col_t col;
        if (s->border_v[i] < s->height) {
            l = i;
            continue;
        }
        while (r < s->cols && (r <= i || s->border_v[r] >= s->height))
            r++;
        if (l >= 0 && l >= i - reach)
            ref = s->first_row[l];
        if (r < s->cols && r <= i + reach && s->first_row[r] > ref)
            ref = s->first_row[r];
        if (ref < 0)
            continue;
        col_init(&col, f, i * f->cs);
        for (j = s->rows - 1; j >= ref; j--) {
            int32_t c = col_class(&col, ct, j * f->rs);
            if (c == FL_CLASS_YELLOW)
                break;
            n++;
            if (c == FL_CLASS_GREEN || c == FL_CLASS_WHITE) {
                nf++;
                best = j;
            } else if (nf * 10 < n * 9) {
                break;
            }
        }
        if (best < 0 || n - nf > (n + 9) / 10)
            continue;
        s->border_v[i] = (int16_t)(best * f->rs);
        s->first_row[i] = (int16_t)best;
        s->n_border++;
        l = i;
        s->post_top[i >> 5] |= 1ULL << (62 - 2 * (i & 31));   /* let C look */
        for (j = best; j < s->rows; j++) {
            uint64_t c = (uint64_t)col_class(&col, ct, j * f->rs);
            s->map[j][i >> 5] |= c << (62 - 2 * (i & 31));
            if (c == FL_CLASS_YELLOW) {
                s->yellow_cols[i]++;
                s->yellow_rows[j]++;
            }
        }
    }
}

/* ---- phase C: posts above the border ---------------------------------------------------- */

/* Index of the highest set bit of x != 0 (binary search). */
static int32_t highest_bit(uint64_t x)
{
    int32_t n = 0;
    if (x >> 32) {
        x >>= 32;
        n += 32;
    }
    if (x >> 16) {
        x >>= 16;
        n += 16;
    }
    if (x >> 8) {
        x >>= 8;
        n += 8;
    }
    if (x >> 4) {
        x >>= 4;
        n += 4;
    }
    if (x >> 2) {
        x >>= 2;
        n += 2;
    }
    return x >> 1 ? n + 1 : n;
}

/* The yellow of column i from grid row jb - 1 up (a gap of one sample
 * bridged) into the map and yellow_rows; returns the cells kept.  kind
 * (a constant where inlined): 0 RGB, 1 one stride for the three bytes
 * (YUYV), 2 a stride per plane. */
static inline int32_t trace_walk(fl_scan_t *s, const fl_color_table_t *ct,
                                 const col_t *col, int32_t i, int32_t jb, int32_t kind)
{
    uint64_t *mp = &s->map[jb - 1][i >> 5], cell = 3ULL << (62 - 2 * (i & 31));
    size_t rs = (size_t)s->params.row_step, vv = (size_t)(jb - 1) * rs;
    size_t oy = vv * col->sy, ocb = vv * col->scb, ocr = vv * col->scr;
    size_t dy = rs * col->sy, dcb = rs * col->scb, dcr = rs * col->scr;
    int32_t jj, n = 0, gap = 0;
    for (jj = jb - 1; jj >= 0; jj--, mp -= FL_SCAN_WORDS, oy -= dy) {
        int32_t c;
        if (kind == 0) {
            c = px_class_rgb(ct, col->y + oy);
        } else if (kind == 1) {
            c = px_class_ycc(ct, col->y[oy], col->cb[oy], col->cr[oy]);
        } else {
            c = px_class_ycc(ct, col->y[oy], col->cb[ocb], col->cr[ocr]);
            ocb -= dcb;
            ocr -= dcr;
        }
        if (c == FL_CLASS_YELLOW) {
            *mp |= cell;
            s->yellow_rows[jj]++;
            n++;
            gap = 0;
        } else if (++gap > 1) {
            break;
        }
    }
    return n;
}

/* Column i with its post_top bit set (phase B or the repair saw yellow
 * right above the border): follow the yellow up, keep it, and a foot at
 * the border when it is a post. */
static void trace_post(fl_scan_t *s, const frame_t *f, int32_t i)
{
    const fl_color_table_t *ct = f->ct;
    int32_t jb = s->first_row[i], jj, n;
    bool yellow = false;
    col_t col;
    if (jb >= s->rows)
        return;
    col_init(&col, f, i * f->cs);
    for (jj = jb - 1; jj >= 0 && jj >= jb - 2; jj--)
        if (col_class(&col, ct, jj * f->rs) == FL_CLASS_YELLOW) {
            yellow = true;
            break;
        }
    if (!yellow)
        return;
    /* a post is tall: one walk per pixel layout (the branch on it out of
     * the loop; YUYV and RGB step one offset for all three bytes) */
    if (col.rgb)
        n = trace_walk(s, ct, &col, i, jb, 0);
    else if (col.scb == col.sy && col.scr == col.sy)
        n = trace_walk(s, ct, &col, i, jb, 1);
    else
        n = trace_walk(s, ct, &col, i, jb, 2);
    s->yellow_cols[i] = (uint16_t)(s->yellow_cols[i] + n);
    if (n >= 2)   /* a post, not a yellowish speck at the carpet edge */
        add_foot(s, i, i * f->cs, s->border_v[i]);
}

/* The columns with a post_top bit, left to right (the highest bit of
 * each word first). */
static void trace_posts(fl_scan_t *s, const frame_t *f)
{
    int32_t w;
    for (w = 0; w < s->words; w++) {
        uint64_t x = s->post_top[w];
        while (x != 0) {
            int32_t b = highest_bit(x);
            x &= ~(1ULL << b);
            trace_post(s, f, 32 * w + 31 - (b >> 1));
        }
    }
}

/* ---- phase D: field color --------------------------------------------------------------- */

static int32_t hue_wrap(int32_t h)
{
    if (h < 0)
        return h + 180;
    return h >= 180 ? h - 180 : h;
}

static void estimate_field(fl_scan_t *s, const frame_t *f)
{
    const fl_hsv_box_t *gb = &f->ct->green;
    int32_t est = s->params.estimate_step_px;
    int32_t ecs, ers, i, j, h, n = 0, best = -1, mode = 0, acc, wsum, sum;
    int32_t span = gb->h_hi >= gb->h_lo ? gb->h_hi - gb->h_lo : gb->h_hi + 180 - gb->h_lo;
    int32_t centre = hue_wrap(gb->h_lo + span / 2);
    int32_t smin = gb->s_lo / 2;
    uint32_t ss = 0, sv = 0, sl = 0;
    memset(&s->field, 0, sizeof s->field);
    if (est <= 0)
        return;
    ecs = est / f->cs > 0 ? est / f->cs : 1;
    ers = est / f->rs > 0 ? est / f->rs : 1;
    memset(s->hue_hist, 0, sizeof s->hue_hist);
    for (i = 0; i < s->cols; i += ecs) {
        int32_t jf = s->first_row[i];
        col_t col;
        col_init(&col, f, i * f->cs);
        for (j = (jf + ers - 1) / ers * ers; j < s->rows; j += ers) {
            uint8_t rgb[3];
            fl_hsv_t hsv;
            int32_t dh;
            col_rgb(&col, j * f->rs, rgb);
            hsv = fl_hsv_from_rgb(rgb[0], rgb[1], rgb[2]);
            dh = hsv.h - centre;
            dh = dh > 90 ? dh - 180 : (dh < -90 ? dh + 180 : dh);
            if (hsv.s < smin || dh > 30 || dh < -30)
                continue;
            s->hue_hist[hsv.h]++;
            ss += hsv.s;
            sv += hsv.v;
            /* fl_luma_from_rgb, inline */
            sl += (uint32_t)(19595 * rgb[0] + 38470 * rgb[1] + 7471 * rgb[2] + 32768) >> 16;
            n++;
        }
    }
    if (n == 0)
        return;
    /* mode of the histogram smoothed over 5 bins (sliding sum) */
    sum = s->hue_hist[178] + s->hue_hist[179] + s->hue_hist[0] + s->hue_hist[1] +
          s->hue_hist[2];
    /* three stretches so that only the ends wrap (h - 2 below 0, h + 3
     * past 179) */
    for (h = 0; h < 2; h++) {
        if (sum > best) {
            best = sum;
            mode = h;
        }
        sum += s->hue_hist[h + 3] - s->hue_hist[h + 178];
    }
    for (; h < 177; h++) {
        if (sum > best) {
            best = sum;
            mode = h;
        }
        sum += s->hue_hist[h + 3] - s->hue_hist[h - 2];
    }
    for (; h < 180; h++) {
        if (sum > best) {
            best = sum;
            mode = h;
        }
        sum += s->hue_hist[h - 177] - s->hue_hist[h - 2];
    }
    acc = 0;
    wsum = 0;
    for (h = -8; h <= 8; h++) {
        acc += h * s->hue_hist[hue_wrap(mode + h)];
        wsum += s->hue_hist[hue_wrap(mode + h)];
    }
    /* Scaling: |acc| <= 8 * n; rounded division to nearest */
    if (wsum > 0)
        mode += (acc >= 0 ? acc + wsum / 2 : acc - wsum / 2) / wsum;
    s->field.n = n;
    s->field.hue = (uint8_t)hue_wrap(mode);
    s->field.sat = (uint8_t)(ss / (uint32_t)n);
    s->field.val = (uint8_t)(sv / (uint32_t)n);
    s->field.luma = (uint8_t)(sl / (uint32_t)n);
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
        int32_t hv = fl_camera_horizon_v_q4(camera, (img->width - 1) * 8);
        if (hv == INT32_MAX)
            s->start_v = img->height;
        else if (hv == INT32_MIN || hv < -16)
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
        scan_band(s, &f, w, j0, ns);
    extend_borders(s, &f, ns, j0, max_white);
    reject_bumps(s, &f, ns, 1);
    reject_bumps(s, &f, ns, -1);
    if (s->n_border < cols)   /* else no column to repair */
        repair_borders(s, &f);
    /* C */
    trace_posts(s, &f);
    /* D */
    estimate_field(s, &f);
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
