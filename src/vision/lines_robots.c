/*
 * src/vision/lines_robots.c - standing objects in the class map: the white
 * of robots (and of a ball, a person's shoe) is no paint on the ground, so
 * it makes no line points.
 *
 * Algorithm.  Every rob_step-th grid column (the vertical scan lines of the
 * point stage) is read from its border down.  A span is a stretch of
 * non-green cells (a single green cell inside is bridged: a gap between
 * the legs, a speck of carpet colour on the robot).  Paint lying on the
 * carpet is white from edge to edge (at most a blurred cell at either
 * end), and along a column it spans the line's projected width (a few
 * times that where the line runs steeply in the image).  A robot stands
 * up: it is taller than a line of the ground at its foot is wide, and its
 * white is broken by dark joints, jersey, shadow.  So a span is an object
 * when
 *   - it has white (at least 2 cells: nothing to reject otherwise) and
 *     dark cells (OTHER or YELLOW) at least 2 and at least 1 in 8 of it,
 *     white being 1 in 8 of it too unless it ends above the image's last
 *     row (mostly dark: the gap between a robot's legs stands on carpet;
 *     the blurred edge of a line running out of the image does not);
 *   - its length is at least 4 cells, and (with a camera) at least 3 times
 *     the projected width of a line seen crosswise (vertical run) and 2
 *     times its width across the row (horizontal run), both at the span's
 *     foot (its bottom row: the nearest ground point under it); without a
 *     camera at least 8 cells.
 * Up to FL_LINES_ROBOT_SPANS spans per column are kept (the longest).  A
 * grid cell lies on an object when a sampled column on either side of it
 * (at most rob_step - 1 columns away) has a span holding its row; inside
 * one (crossings: a line ending at a robot's foot keeps its corner) when
 * the sampled columns on both sides have (or the cell's own column).
 *
 * Cost: every cell of every rob_step-th column below its border read once
 * (a quarter of the map's cells at the default steps), 2 width look-ups
 * per span; a check reads at most 2 x FL_LINES_ROBOT_SPANS spans.
 * Memory: 4 bytes per column and span in fl_lines_t.
 */
#include "lines_int.h"

/* Is the run of non-green cells of grid row j through cell i longer than
 * lim cells?  (Walks at most lim + 1 cells.) */
static bool lr_row_run_over(const fl_scan_t *s, int32_t i, int32_t j, int32_t lim)
{
    const uint64_t *row = s->map[j];
    int32_t a = i, b = i;
    while (b - a < lim && a - 1 >= 0 &&
           ((row[(a - 1) >> 5] >> (62 - 2 * ((a - 1) & 31))) & 3u) != FL_CLASS_GREEN)
        a--;
    while (b - a < lim && b + 1 < s->cols &&
           ((row[(b + 1) >> 5] >> (62 - 2 * ((b + 1) & 31))) & 3u) != FL_CLASS_GREEN)
        b++;
    return b - a + 1 > lim;
}

/* Is span [lo, hi] of column i (n_white white cells, n_dark dark ones
 * not counting its end cells: a line's blurred edges) an object? */
static bool lr_standing(const fl_lines_t *l, const fl_scan_t *s, int32_t i, int32_t lo,
                        int32_t hi, int32_t n_white, int32_t n_dark)
{
    int32_t rs = s->params.row_step, n = hi - lo + 1, len_q4 = n * rs * 16, v = hi * rs;
    int32_t wv, wh, wt, k;
    if (n_white < 2 || n < 4)
        return false;
    wv = fl_lines_width_q4(l, v, true);
    wh = fl_lines_width_q4(l, v, false);
    if (wv <= 0 || wh <= 0) {
        if (n < 8)
            return false;
    } else if (len_q4 < 2 * wv || 2 * len_q4 < 3 * wh) {
        return false;
    }
    /* white broken by joints, jersey, shadow; mostly dark (the gap
     * between a robot's legs) only where it stands on carpet, not along
     * the blurred edge of a line running out of the image */
    if (n_dark >= 2 && n_dark * 10 >= n && (n_white * 8 >= n || hi < s->rows - 1))
        return true;
    if (wv <= 0 || wh <= 0)
        return false;
    /* wider than a line at its rows a quarter and half way down (a steep
     * line is as wide as the projection there; a flat one is not that
     * long; the top row may hold a line the span runs into) */
    for (k = 1; k <= 2; k++) {
        int32_t j = lo + k * (n - 1) / 4;
        wt = fl_lines_width_q4(l, j * rs, false);
        /* more than 3 widths + 2 cells: (3 wt / 16) / col_step + 2 cells */
        if (wt <= 0 || !lr_row_run_over(s, i, j, (3 * wt / 16) / s->params.col_step + 2))
            return false;
    }
    return true;
}

/* Keep span [lo, hi] of column i (k spans stored so far): the longest. */
static int32_t lr_keep(fl_lines_t *l, int32_t i, int32_t k, int32_t lo, int32_t hi)
{
    int32_t m, short_k = 0;
    l->robot_spans++;
    if (k < FL_LINES_ROBOT_SPANS) {
        l->rob_lo[i][k] = (int16_t)lo;
        l->rob_hi[i][k] = (int16_t)hi;
        return k + 1;
    }
    for (m = 1; m < FL_LINES_ROBOT_SPANS; m++)
        if (l->rob_hi[i][m] - l->rob_lo[i][m] < l->rob_hi[i][short_k] - l->rob_lo[i][short_k])
            short_k = m;
    if (hi - lo > l->rob_hi[i][short_k] - l->rob_lo[i][short_k]) {
        l->rob_lo[i][short_k] = (int16_t)lo;
        l->rob_hi[i][short_k] = (int16_t)hi;
    }
    return k;
}

/* The spans of one sampled column i. */
static void lr_column(fl_lines_t *l, const fl_scan_t *s, int32_t i)
{
    int32_t rs = s->params.row_step, j, j0, lo = -1, last = -1, nw = 0, nd = 0, gap = 0, k = 0;
    int32_t c_lo = 0, c_last = 0;
    int32_t word = i >> 5, shift = 62 - 2 * (i & 31);
    const uint64_t *q;
    for (j = 0; j < FL_LINES_ROBOT_SPANS; j++) {
        l->rob_lo[i][j] = 1;
        l->rob_hi[i][j] = 0;
    }
    if (s->border_v[i] >= s->height)
        return;
    j0 = (s->border_v[i] + rs - 1) / rs;
    q = &s->map[j0 < s->rows ? j0 : 0][word];
    for (j = j0; j <= s->rows; j++, q += FL_SCAN_WORDS) {
        int32_t c = j < s->rows ? (int32_t)((*q >> shift) & 3u) : FL_CLASS_GREEN;
        if (c != FL_CLASS_GREEN) {
            if (lo < 0) {
                lo = j;
                nw = nd = 0;
                c_lo = c;
            }
            if (c == FL_CLASS_WHITE)
                nw++;
            else
                nd++;
            last = j;
            c_last = c;
            gap = 0;
            continue;
        }
        if (lo < 0 || (++gap <= 1 && j < s->rows))
            continue;
        /* two green cells (or the bottom): the span ends at last; the end
         * cells' dark is a blurred edge */
        nd -= (c_lo != FL_CLASS_WHITE) + (last > lo && c_last != FL_CLASS_WHITE);
        if (nw >= 2 && last - lo >= 3 && lr_standing(l, s, i, lo, last, nw, nd))
            k = lr_keep(l, i, k, lo, last);
        lo = -1;
        gap = 0;
    }
}

void fl_lines_int_robots(fl_lines_t *l, const fl_scan_t *s, int32_t step)
{
    int32_t i;
    l->rob_step = step;
    for (i = step / 2; i < s->cols; i += step)
        lr_column(l, s, i);
}

/* Does sampled column i have a span holding row j? */
static bool lr_in(const fl_lines_t *l, int32_t i, int32_t j)
{
    int32_t k;
    for (k = 0; k < FL_LINES_ROBOT_SPANS; k++)
        if (j >= l->rob_lo[i][k] && j <= l->rob_hi[i][k])
            return true;
    return false;
}

bool fl_lines_int_on_robot(const fl_lines_t *l, const fl_scan_t *s, int32_t i, int32_t j,
                           bool inside)
{
    int32_t m = l->rob_step, i0, a, b;
    bool in_a, in_b;
    if (l->robot_spans == 0 || m < 1 || i < 0 || i >= s->cols)
        return false;
    i0 = m / 2;
    if (i0 >= s->cols)
        return false;
    if (i < i0)
        return lr_in(l, i0, j);
    a = i0 + (i - i0) / m * m;
    /* a scan line itself: its neighbours on both sides */
    b = a == i ? a + m : a + m;
    if (a == i)
        return lr_in(l, a, j);
    in_a = a >= 0 && lr_in(l, a, j);
    in_b = b < s->cols && lr_in(l, b, j);
    return inside ? in_a && in_b : in_a || in_b;
}

/* Is any scan line among grid columns i0..i1 on an object at row j? */
bool fl_lines_int_run_on_robot(const fl_lines_t *l, const fl_scan_t *s, int32_t i0, int32_t i1,
                               int32_t j)
{
    int32_t m = l->rob_step, i;
    if (l->robot_spans == 0 || m < 1)
        return false;
    if (fl_lines_int_on_robot(l, s, i0, j, false) || fl_lines_int_on_robot(l, s, i1, j, false))
        return true;
    for (i = m / 2 + ((i0 - m / 2 + m - 1) / m) * m; i <= i1 && i < s->cols; i += m)
        if (i >= 0 && lr_in(l, i, j))
            return true;
    return false;
}

bool fl_lines_on_object(const fl_lines_t *l, const fl_scan_t *scan, int32_t u_px,
                        int32_t v_px)
{
    int32_t cs, rs;
    if (!l || !scan || scan->width <= 0 || l->width != scan->width || u_px < 0 ||
        v_px < 0 || u_px >= scan->width || v_px >= scan->height)
        return false;
    cs = scan->params.col_step;
    rs = scan->params.row_step;
    if (cs < 1 || rs < 1)
        return false;
    return fl_lines_int_on_robot(l, scan, (u_px + cs / 2) / cs, (v_px + rs / 2) / rs, true);
}
