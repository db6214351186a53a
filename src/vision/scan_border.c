/*
 * src/vision/scan_border.c - phase A' of the column scanner (see scan.c for
 * the algorithm, include/fieldloc/scan.h for the outputs): per column,
 * scalar and short, after phase B found the borders: extend a border up
 * over a thin line with carpet (or a post) above it; reject green clutter
 * beyond the carpet (bumps above the border of the flat stretch next to
 * them, re-searched below the clutter in the class map); repair columns
 * without a border between columns with one (a line running down the
 * column).  Per column, not per pixel: a few samples around each border.
 */
#include "scan_int.h"

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

void fl_scan_internal_extend_borders(fl_scan_t *s, const frame_t *f, int32_t ns,
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

/* reject_bumps left to right, then right to left, so that bumps at
 * either image edge are entered. */
void fl_scan_internal_reject_bumps(fl_scan_t *s, const frame_t *f, int32_t ns)
{
    reject_bumps(s, f, ns, 1);
    reject_bumps(s, f, ns, -1);
}

/* Columns without a border between columns with one: a field line running
 * down the column has no green.  Between the neighbours' border row and the
 * bottom, the lowest stretch of field colors (green or white, at most one
 * other sample in ten, no yellow) becomes the field; its top is the border
 * and its cells are classified into the map (white unchecked).  Only such
 * columns are read again, bottom-up, once. */
void fl_scan_internal_repair_borders(fl_scan_t *s, const frame_t *f)
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

