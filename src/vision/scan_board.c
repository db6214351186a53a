/*
 * src/vision/scan_board.c - phase A'' of the column scanner (see scan.c,
 * include/fieldloc/scan.h): without a horizon to start the border search
 * from (no camera, or the horizon above the image), a green board or wall
 * above the field is the first green run of its columns.  The carpet is
 * the green region connected to the image bottom; a green region above it
 * separated by a stretch that is no paint (a wall, the floor beyond the
 * carpet, a goal's net) is not the field.
 *
 * Per column, from the bottom up (class map cells, classified below the
 * border by phase B): the lower region (field colors: green and white, at
 * most one other cell in ten and no max(2, ns / 2) in a row, no white
 * stretch of rows / 8 (a wall; a line crosswise is shorter), at least half
 * green; its top is its topmost green cell), above it a gap of at least
 * max(ns, rows / 32) cells, at least a third of them other or yellow or
 * at least rows / 8 long (a painted line is white and
 * narrower: the boundary line with the strip of carpet beyond it keeps
 * its border; a white-grey wall is long), green runs shorter than ns
 * inside it, above that a run of ns green cells (the board).  A column
 * qualifies when all this holds; a stretch of adjacent columns that
 * qualify (or have nothing above their lower region; at most 2 failing
 * ones in a row inside) with at least cols / 4 qualifying (a board or wall is wide; a robot standing
 * on the carpet between far and near carpet is narrow) gets its borders
 * moved to the top of the lower region, the cells above it become
 * background (their yellow counted out, their feet removed).
 *
 * Cost: per column the cells from its border to the bottom read once from
 * the map (2 bits each), only in frames searched from row 0; the moved
 * columns' cells cleared once.
 */
#include "scan_int.h"

/* The top row of column i's lower region when the column qualifies; -2
 * when nothing lies above the lower region (no border, or the border is
 * its top already: neutral); else -1.  Bottom-up: the lower region (as the border repair reads a column),
 * then the gap up to the next run of ns green cells. */
static int32_t board_gap(const fl_scan_t *s, int32_t i, int32_t ns, int32_t min_gap)
{
    int32_t j, n = 0, nf = 0, n_green = 0, best = -1, run = 0, n_dark = 0, gap, n_off = 0;
    int32_t top = s->first_row[i], max_off = ns / 2 > 2 ? ns / 2 : 2, n_white = 0;
    if (top >= s->rows)
        return -2;
    for (j = s->rows - 1; j >= top; j--) {
        int32_t c = map_class(s, i, j);
        n++;
        if (c == FL_CLASS_WHITE && 8 * ++n_white >= s->rows)
            break;   /* a long white stretch: a wall, not paint */
        if (c == FL_CLASS_GREEN || c == FL_CLASS_WHITE) {
            nf++;
            n_off = 0;
            if (c == FL_CLASS_GREEN) {
                n_green++;
                n_white = 0;
                best = j;   /* the region's top is carpet */
            }
        } else if (nf * 10 < n * 9 || ++n_off >= max_off || (n_white = 0) != 0) {
            break;   /* too much else, or a stretch of it (a wall's foot) */
        }
    }
    if (best == top)
        return -2;
    if (best < top || 2 * n_green < s->rows - best)
        return -1;
    /* the gap above it: up to a run of ns green cells */
    for (j = best - 1; j >= top; j--) {
        int32_t c = map_class(s, i, j);
        if (c == FL_CLASS_GREEN) {
            if (++run >= ns)
                break;
            continue;
        }
        run = 0;
        if (c != FL_CLASS_WHITE)
            n_dark++;
    }
    if (j < top)
        return -2;   /* no green region above: nothing to reject */
    gap = best - (j + ns);
    if (gap < min_gap || (3 * n_dark < gap && 8 * gap < s->rows))
        return -1;
    return best;
}

/* Move column i's border down to grid row js. */
static void board_move(fl_scan_t *s, const frame_t *f, int32_t i, int32_t js)
{
    int32_t j, k, v = js * f->rs;
    uint64_t keep = ~(3ULL << (62 - 2 * (i & 31)));
    for (j = s->first_row[i]; j < js; j++) {
        if (map_class(s, i, j) == FL_CLASS_YELLOW) {
            s->yellow_cols[i]--;
            s->yellow_rows[j]--;
        }
        s->map[j][i >> 5] &= keep;
    }
    for (k = 0; k < s->n_feet; k++)
        if (s->feet[k].u == i * f->cs && s->feet[k].v < v) {
            s->feet[k] = s->feet[--s->n_feet];
            s->col_feet[i]--;
            k--;
        }
    s->first_row[i] = (int16_t)js;
    s->border_v[i] = (int16_t)v;
    s->post_top[i >> 5] &= ~(1ULL << (62 - 2 * (i & 31)));
}

void fl_scan_internal_reject_boards(fl_scan_t *s, const frame_t *f, int32_t ns)
{
    int32_t min_gap = s->rows / 32 > ns ? s->rows / 32 : ns, min_cols = s->cols / 4;
    int32_t i, start = -1, n_q = 0, n_fail = 0;
    if (min_cols < 2)
        min_cols = 2;
    /* gend_row is free scratch after the bump pass: the lower region's
     * top per column (-1: the column does not qualify, -2: neutral) */
    for (i = 0; i <= s->cols; i++) {
        int32_t js = i < s->cols ? board_gap(s, i, ns, min_gap) : -1;
        if (i < s->cols)
            s->gend_row[i] = (int16_t)js;
        if (js != -1 || (start >= 0 && i < s->cols && ++n_fail < 3)) {
            if (js != -1)
                n_fail = 0;
            if (start < 0) {
                start = i;
                n_q = 0;
            }
            n_q += js >= 0;
            continue;
        }
        /* the end of a stretch (3 failing columns in a row, or the edge) */
        if (start >= 0 && n_q >= min_cols) {
            int32_t k;
            for (k = start; k < i; k++)
                if (s->gend_row[k] >= 0)
                    board_move(s, f, k, s->gend_row[k]);
        }
        start = -1;
        n_fail = 0;
    }
}
