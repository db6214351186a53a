/*
 * src/vision/scan_band.c - phases A and B of the column scanner (see
 * scan.c for the algorithm, include/fieldloc/scan.h for the outputs): the
 * candidate rows of each band of 32 grid columns, the band's rows
 * classified into the class map (one 32-cell word per row), and the row
 * logic that reads the words back (bit-sliced run counters for the border,
 * white contrast checks, feet, yellow counts).
 *
 * Everything on the per-pixel and per-row path lives in this one
 * translation unit: the word functions, the row logic and the scalar walks
 * they call (border refinement, white checks) are inlined or specialised
 * per pixel layout here; a call across files would lose that.
 */
#include "scan_int.h"

#include <string.h>

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

static FL_INLINE int32_t px_luma_k(const frame_t *f, int32_t u, int32_t v, int32_t kind)
{
    col_t c;
    col_init_k(&c, f, u, kind);
    return col_luma_k(&c, v, kind);
}

/* ---- word classification (phase B) ----------------------------------------------
 * 32 cells -> 64 bits, cell k at bits 63 - 2k, 62 - 2k.  Only the word_*
 * functions classify rows (plus word_generic's per-cell lookups): the
 * classify_only rows of tools/bench/callgrind.sh collect the functions
 * named word_*, so the name prefix is part of that measurement. */

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

/* ---- phase B helpers ------------------------------------------------------------------ */

/* Low bit of cell k (0..31) in a word. */
static uint64_t cell_bit(int32_t k)
{
    return 1ULL << (62 - 2 * k);
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
 * rows) skips the test (every row with a green cell is taken). */
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

/* Phase B's state carried from one row of a band to the next: green (g1,
 * g2) and yellow (y1, y2, y3) cells of the rows above, the white cells of
 * the row above (wprev) and those of them rejected (wrej).  A local of
 * fl_scan_internal_band; the functions that take it are inlined, so it
 * lives in registers. */
typedef struct {
    uint64_t g1, g2, y1, y2, y3, wprev, wrej;
} row_state_t;

/* The rest of a phase B row once c, lo, hi hold only the cells below the
 * border (shared by both loops of fl_scan_internal_band): carpet rows
 * (only green and other, no yellow in the two rows above) take the fast
 * path; else white run starts get their contrast check, yellow->green
 * transitions become feet and yellow cells are counted.  The row's map
 * word *mp is written in both cases; the caller goes on with the next row
 * either way, so there is nothing to return. */
static FL_INLINE void row_tail(fl_scan_t *s, const frame_t *f, int32_t w, int32_t j,
                               uint64_t *mp, uint64_t c, uint64_t lo, uint64_t hi,
                               row_state_t *st, uint64_t *ycount)
{
    uint64_t g, wh, y, starts, rej, cand;
    if ((hi | st->y1 | st->y2) == 0) {
        /* only green and other (the carpet below the border): no white
         * run, no yellow, no foot; the row's state moves down (y1, y2 are
         * 0 already) */
        *mp = c;
        st->g2 = st->g1;
        st->g1 = lo;
        st->y3 = 0;
        st->wprev = 0;
        st->wrej = 0;
        return;
    }
    g = lo & ~hi;
    wh = hi & ~lo;
    y = lo & hi;
    *mp = c;
    rej = st->wrej & wh;
    starts = wh & ~st->wprev;
    if (starts != 0) {
        int32_t last = -4;
        bool keep = true;
        while (starts != 0) {   /* right to left; one check per group */
            int32_t b = lowest_bit(starts), k = 31 - (b >> 1);
            starts &= starts - 1;
            if (b != last + 2)
                keep = white_keep(s, f, 32 * w + k, j, st->g1, st->g2);
            last = b;
            if (!keep) {
                rej |= 1ULL << b;
                s->white_rejected++;
            }
        }
    }
    if (rej != 0)
        *mp = c & ~(rej | (rej << 1));
    st->wrej = rej;
    st->wprev = wh;
    /* two yellow samples right above, or above one non-green sample */
    cand = g & ~st->g1 & ((st->y1 & st->y2) | (st->y2 & st->y3));
    while (cand != 0) {
        int32_t b = lowest_bit(cand), k = 31 - (b >> 1);
        cand &= cand - 1;
        add_foot(s, 32 * w + k, (32 * w + k) * f->cs, j * f->rs);
    }
    if (y != 0) {
        count_yellow(ycount, y);
        s->yellow_rows[j] = (uint16_t)(s->yellow_rows[j] + popcount64(y));
    }
    st->g2 = st->g1;
    st->g1 = g;
    st->y3 = st->y2;
    st->y2 = st->y1;
    st->y1 = y;
}

/* B2's fast path at row j (*mpp: its map word, c: its cells, only green
 * and other, no yellow in the two rows above): this row and the carpet
 * rows that follow are in the map already, final as classified; the
 * state moves down past them, and the columns of ing (found, still in the
 * border's green run) that meet other in them get their gend.  Returns the
 * first row after the carpet, *mpp its map word. */
static FL_INLINE int32_t carpet_rows(fl_scan_t *s, int32_t w, int32_t j, uint64_t c,
                                     uint64_t **mpp, row_state_t *st, uint64_t *ing)
{
    uint64_t *mp = *mpp, *mq = mp, acc = c;
    const uint64_t *mlast = &s->map[s->rows - 1][w];
    int32_t j1 = j;
    /* the row count from the pointer afterwards: one instruction less per
     * carpet row */
    do {
        acc &= c;
        mq += FL_SCAN_WORDS;
    } while (mq <= mlast && ((c = *mq) & ODD) == 0);
    j += (int32_t)((mq - mp) / FL_SCAN_WORDS);
    /* green of the last two rows (g1 when only one) */
    st->g2 = j - j1 >= 2 ? mq[-2 * FL_SCAN_WORDS] & EVEN : st->g1;
    st->g1 = mq[-FL_SCAN_WORDS] & EVEN;
    if ((*ing & ~acc) != 0) {
        /* columns that met other in these rows: find where */
        uint64_t leave = *ing & ~acc;
        *ing &= acc;
        for (; leave != 0; mp += FL_SCAN_WORDS, j1++) {
            if ((leave & ~*mp) != 0) {
                gend_record(s, w, j1, leave & ~*mp);
                leave &= *mp;
            }
        }
    }
    *mpp = mq;
    st->y3 = 0;
    st->wprev = 0;
    st->wrej = 0;
    return j;
}

/* The band's bit-sliced yellow counts (ycount) added to yellow_cols. */
static void yellow_to_cols(fl_scan_t *s, int32_t w, const uint64_t *ycount)
{
    int32_t p;
    for (p = 0; p < FL_SCAN_COUNT_BITS; p++) {
        uint64_t x = ycount[p];
        while (x != 0) {
            int32_t b = lowest_bit(x);
            x &= x - 1;
            s->yellow_cols[32 * w + 31 - (b >> 1)] =
                (uint16_t)(s->yellow_cols[32 * w + 31 - (b >> 1)] + (1 << p));
        }
    }
}

/* Band w (32 grid columns): rows from j_lo down, each row classified once
 * (32 cells, all rows first, into the map: band_rows), then per row the run
 * detector for columns still without a border and the bit logic on the
 * cells below the border, each row's map word rewritten masked.  State
 * lives in locals.  Two loops: B1 while some column of the band has no
 * border yet (run counters, cells masked to the found columns), B2 once
 * all have one (no counters, no masking: the cells beyond a partial band's
 * last column are 0 from word_generic; carpet rows, the common case, only
 * move the state down: their map word is final as classified). */
FL_NOINLINE void fl_scan_internal_band(fl_scan_t *s, const frame_t *f, int32_t w,
                                       int32_t j0, int32_t ns)
{
    /* jm: phase A's row (rows cls[0] .. cls[1] are in the map already);
     * rows when no run: nothing to scan (six arguments: all in registers) */
    int32_t cls[2], jm = band_start(s, f, w, j0, ns, cls);
    int32_t j_lo = jm >= s->rows ? s->rows : (jm - ns + 1 > j0 ? jm - ns + 1 : j0), nplanes;
    int32_t n = s->cols - 32 * w, rows = s->rows, j, p;
    row_state_t st = {0, 0, 0, 0, 0, 0, 0};
    uint64_t found = 0;
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
        uint64_t c = *mp, lo, hi;
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
        row_tail(s, f, w, j, mp, c, lo, hi, &st, ycount);
    }
    /* B2: every column has its border: no counters, no masking (a partial
     * band's cells beyond its last column are 0 from word_generic) */
    while (j < rows) {
        uint64_t c = *mp, lo, hi;
        if ((c & ODD) == 0 && (st.y1 | st.y2) == 0) {
            /* carpet rows (only green and other, no yellow in the two rows
             * above): the map holds them already; the state moves down */
            j = carpet_rows(s, w, j, c, &mp, &st, &ing);
            continue;
        }
        lo = c & EVEN;
        hi = (c >> 1) & EVEN;
        if ((ing & ~(lo & ~hi)) != 0) {
            gend_record(s, w, j, ing & ~(lo & ~hi));
            ing &= lo & ~hi;
        }
        row_tail(s, f, w, j, mp, c, lo, hi, &st, ycount);
        j++;
        mp += FL_SCAN_WORDS;
    }
    s->gend_none[w] = ing;   /* green down to the last row */
    yellow_to_cols(s, w, ycount);   /* bit-sliced counts -> columns */
}
