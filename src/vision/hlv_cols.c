/*
 * src/vision/hlv_cols.c - goal posts and striped landmark poles (seed 002
 * IV.B.1 and IV.B.2), column by column.
 *
 * A grid column (hlvision.h) is read bottom-up as runs of one colour (yellow, sky-blue,
 * green, white; anything else ends a run unless the gap is at most
 * gap_px).  The lowest yellow or sky-blue run with a green run of at least
 * min_green_px right below (within green_gap_px), or a white run at most
 * 1/8 of its length right below and such a green run below that (a post
 * on the goal line), is a foot.  Going upwards from it, the
 * seed's pole test: the column "continues to a yellow-blue and further a
 * blue-yellow boundary" (for YBY; BYB alike), each band at least
 * min_band_px; a column whose run above the first band is the other colour
 * but has no third band is neither (a post in front of a pole, a partly
 * seen pole: not identified, so not reported).  Else the first band alone,
 * at least min_post_px high, is a post.
 *
 * Adjoining grid columns of one kind whose feet differ by at most
 * foot_tol_px form an object; objects of fewer than min_cols columns are
 * dropped (single-column noise).
 */
#include "hlv_int.h"

#include <string.h>

typedef struct {
    uint8_t cls;            /* FL_HLV_YELLOW, BLUE or GREEN */
    int32_t lo, hi;         /* lowest and highest row of the run (lo >= hi) */
} hlv_run_t;

typedef struct {
    int32_t kind;           /* 0 none, else fl_hlv_kind_t */
    int32_t foot, top;
    int32_t band_lo, band_hi;
} hlv_col_t;

/* The single colour of class bits c that a run may have (0: none). */
static uint8_t run_class(uint8_t c)
{
    if (c & FL_HLV_YELLOW)
        return FL_HLV_YELLOW;
    if (c & FL_HLV_BLUE)
        return FL_HLV_BLUE;
    if (c & FL_HLV_GREEN)
        return FL_HLV_GREEN;
    if (c & FL_HLV_WHITE)
        return FL_HLV_WHITE;
    return 0;
}

/* Runs of grid column i from the bottom up (rows as image rows); returns
 * their count. */
static int32_t column_runs(fl_hlv_t *s, int32_t i, int32_t height, hlv_run_t *runs)
{
    const int32_t step = s->step_v, gap = s->params.gap_px;
    int32_t n = 0, j, last_v = -1;
    uint8_t cur = 0;
    for (j = s->mask_h - 1; j >= 0; j--) {
        const uint8_t c = run_class(s->cls[j * s->mask_w + i]);
        const int32_t v = j * step + step / 2 < height ? j * step + step / 2 : height - 1;
        if (c == 0)
            continue;
        if (c == cur && last_v - v <= gap + step) {
            runs[n - 1].hi = v;
        } else {
            if (n == FL_HLV_MAX_RUNS) {
                s->runs_dropped++;
                break;
            }
            runs[n].cls = c;
            runs[n].lo = v;
            runs[n].hi = v;
            n++;
            cur = c;
        }
        last_v = v;
    }
    return n;
}

static int32_t run_len(const hlv_run_t *r, int32_t step)
{
    return r->lo - r->hi + step;
}

/* Adjacent: run b starts within gap_px + step above run a's end. */
static bool adjacent(const hlv_run_t *a, const hlv_run_t *b, int32_t gap, int32_t step)
{
    return a->hi - b->lo <= gap + step;
}

static void classify_column(const fl_hlv_t *s, const hlv_run_t *runs, int32_t n, hlv_col_t *out)
{
    const fl_hlv_params_t *p = &s->params;
    int32_t k;
    memset(out, 0, sizeof *out);
    for (k = 1; k < n; k++) {
        const hlv_run_t *a = &runs[k], *g = &runs[k - 1];
        uint8_t other;
        if (a->cls != FL_HLV_YELLOW && a->cls != FL_HLV_BLUE)
            continue;
        if (!adjacent(g, a, p->green_gap_px, s->step_v))
            continue;
        /* a painted line right below and green below that: a post on
         * the goal line */
        if (g->cls == FL_HLV_WHITE) {
            /* a line under a post is far thinner than the post is tall
             * (on hl3x2 25 mm lines seen from 460 mm up against 450 mm
             * posts: under 1/10 at any range over 0.3 m); a longer white
             * run is a floor or a wall between an object and the carpet */
            if (k < 2 || !adjacent(&runs[k - 2], g, p->green_gap_px, s->step_v) ||
                8 * run_len(g, s->step_v) > run_len(a, s->step_v))
                continue;
            g = &runs[k - 2];
        }
        if (g->cls != FL_HLV_GREEN || run_len(g, s->step_v) < p->min_green_px)
            continue;
        other = a->cls == FL_HLV_YELLOW ? FL_HLV_BLUE : FL_HLV_YELLOW;
        out->foot = a->lo;
        if (k + 1 < n && runs[k + 1].cls == other && adjacent(a, &runs[k + 1], p->gap_px, s->step_v)) {
            const hlv_run_t *b = &runs[k + 1], *c = k + 2 < n ? &runs[k + 2] : NULL;
            if (c && c->cls == a->cls && adjacent(b, c, p->gap_px, s->step_v) &&
                run_len(a, s->step_v) >= p->min_band_px && run_len(b, s->step_v) >= p->min_band_px &&
                run_len(c, s->step_v) >= p->min_band_px) {
                out->kind = a->cls == FL_HLV_YELLOW ? FL_HLV_POLE_YBY : FL_HLV_POLE_BYB;
                out->top = c->hi;
                out->band_lo = a->hi;
                out->band_hi = b->hi;
            }
            return;   /* two colours without a third band: not identified */
        }
        if (run_len(a, s->step_v) >= p->min_post_px) {
            out->kind = a->cls == FL_HLV_YELLOW ? FL_HLV_POST_YELLOW : FL_HLV_POST_BLUE;
            out->top = a->hi;
            out->band_lo = out->band_hi = -1;
        }
        return;
    }
}

/* A post's other colour right above the top of clipped post o (rows
 * top_v - 1 up to gap_px + 2 row steps above it), anywhere from its inner
 * column to the cut edge, every pixel (2 hits): a pole's band.  The camera
 * looks down, so upright objects lean outwards towards the image's sides:
 * a pole cut by the side can leave its bottom band alone in the grid
 * columns, its upper bands between the last grid column and the edge
 * (hl3x2: a 100 mm band on green, 2 post widths tall, as tall as a post
 * cut near its inner edge, whose upper part leans out of the frame).
 * classify_column refuses a column with the other colour above its run;
 * this is that test for the pixels the grid does not read.  A pole whose
 * upper bands all lean beyond the edge stays a post.  At most
 * (gap_px + 2 step_v) x (u1 - u0 + step_u) pixel reads. */
static bool band_above(const fl_hlv_t *s, const fl_image_t *img, const fl_hlv_object_t *o, bool left)
{
    const uint8_t other = o->kind == FL_HLV_POST_YELLOW ? FL_HLV_BLUE : FL_HLV_YELLOW;
    const int32_t u_lo = left ? 0 : o->u0, u_hi = left ? o->u1 : img->width - 1;
    int32_t v, u, hits = 0;
    for (v = o->top_v - 1; v >= 0 && v >= o->top_v - s->params.gap_px - 2 * s->step_v; v--)
        for (u = u_lo; u <= u_hi; u++)
            if ((hlv_pixel_class(s, img, u, v) & other) && ++hits >= 2)
                return true;
    return false;
}

/* Keep an object of at least min_cols columns.  One that touches the
 * image's left or right edge (its first or last grid column) is kept when
 * the edge cuts its foot, marked clipped (o->clip), and hlv.c places its
 * centre from its inner edge and the width its range gives (its visible
 * columns' middle is off by up to half its width).  The foot is cut when
 * the edge column's foot lies within half the visible width (and two row
 * steps) of the lowest foot: a base's outline rises from its lowest point
 * by at most its half width (the ellipse's minor semi-axis), less the
 * farther the cut lies from the axis, so that bound holds whether the
 * axis is inside or outside the frame.  Else only the upper part of the
 * object reaches the side (a near post leans outwards towards the image's
 * sides), its edge column's foot far above the lowest, and the object is
 * dropped: its foot may be whole, but its columns need not span it (the
 * foot's outer columns may hold runs shorter than min_post_px), so
 * neither its edges nor its foot's middle place it well.  One touching
 * both edges is no post or pole. */
static void close_object(fl_hlv_t *s, fl_hlv_object_t *o, const fl_image_t *img)
{
    const int32_t step = s->step_u;
    const bool left = o->u0 - step < 0, right = o->u1 + step >= img->width;
    if (o->cols < s->params.min_cols || (left && right))
        return;
    if (left || right) {
        const int32_t rise = o->foot_v - o->edge_foot_v[left ? 0 : 1];
        if (2 * rise > o->u1 - o->u0 + step + 4 * s->step_v)
            return;
        if (o->kind <= FL_HLV_POST_BLUE && band_above(s, img, o, left)) {
            s->objects_rejected++;
            return;
        }
    }
    if (s->n_objects == FL_HLV_MAX_OBJECTS) {
        s->objects_dropped++;
        return;
    }
    o->clip = left ? -1 : right ? 1 : 0;
    s->objects[s->n_objects++] = *o;
}

/* A crossbar of colour cls beside the top of post o: -1 left, +1 right, 0
 * none or both.  Probes at 6, 8 and 10 post widths (w px) beside the top (on
 * hl3x2: 300..500 mm, inside the 800 mm goal but beyond its 250 mm deep
 * top frame, which a post seen from the side shows on the other side),
 * at the top row and 2 rows below it; at least 4 of the 6 on one side
 * and none on the other. */
static int32_t crossbar_side(const fl_hlv_t *s, const fl_image_t *img, const fl_hlv_object_t *o,
                             uint8_t cls, int32_t w)
{
    int32_t side, k, dv, hits[2] = {0, 0};
    if (o->top_v <= 0)
        return 0;   /* the top is not in the image */
    for (side = 0; side < 2; side++)
        for (k = 6; k <= 10; k += 2)
            for (dv = 0; dv <= 2; dv += 2) {
                const int32_t u = side ? o->u1 + k * w : o->u0 - k * w, v = o->top_v + dv;
                if (u >= 0 && u < img->width && v < img->height &&
                    (hlv_pixel_class(s, img, u, v) & cls))
                    hits[side]++;
            }
    if (hits[1] >= 4 && hits[0] == 0)
        return 1;
    if (hits[0] >= 4 && hits[1] == 0)
        return -1;
    return 0;
}

fl_side_t fl_hlv_int_bar_side(const fl_hlv_t *s, const fl_image_t *img, const fl_hlv_object_t *o,
                              int32_t width_px)
{
    int32_t bar;
    /* a top in the first grid row may be cut by the image's top: no bar
     * is looked for (crossbar_side's own test, top_v <= 0, never holds on
     * a grid whose rows are sampled at step_v / 2 and below; whole posts
     * keep it as it was) */
    if (o->top_v < s->step_v)
        return FL_SIDE_UNKNOWN;
    bar = crossbar_side(s, img, o, o->kind == FL_HLV_POST_YELLOW ? FL_HLV_YELLOW : FL_HLV_BLUE,
                        width_px > 0 ? width_px : 1);
    return bar > 0 ? FL_SIDE_LEFT : bar < 0 ? FL_SIDE_RIGHT : FL_SIDE_UNKNOWN;
}

/* Sides: two posts of one colour by their order; one post by its bar. */
static void post_sides(fl_hlv_t *s, const fl_image_t *img)
{
    int32_t kind, i;
    for (kind = FL_HLV_POST_YELLOW; kind <= FL_HLV_POST_BLUE; kind++) {
        int32_t idx[2] = {-1, -1}, count = 0;
        for (i = 0; i < s->n_objects; i++)
            if ((int32_t)s->objects[i].kind == kind) {
                if (count < 2)
                    idx[count] = i;
                count++;
            }
        if (count == 2) {
            s->objects[idx[0]].side = FL_SIDE_LEFT;   /* objects are in column order */
            s->objects[idx[1]].side = FL_SIDE_RIGHT;
        } else if (count == 1 && s->objects[idx[0]].clip != 0) {
            /* clipped: its visible width is not its width, which sets
             * how far the bar is probed for; hlv.c probes with the
             * width its range gives */
            s->objects[idx[0]].side = FL_SIDE_UNKNOWN;
        } else if (count == 1) {
            const fl_hlv_object_t *o = &s->objects[idx[0]];
            const int32_t bar = crossbar_side(s, img, o, kind == FL_HLV_POST_YELLOW ? FL_HLV_YELLOW : FL_HLV_BLUE,
                                              o->u1 - o->u0 + s->step_u);
            s->objects[idx[0]].side = bar > 0 ? FL_SIDE_LEFT : bar < 0 ? FL_SIDE_RIGHT : FL_SIDE_UNKNOWN;
        }
    }
}

/* Kinds that may be one object: equal, or a post column of a pole's
 * bottom colour (the pole's edge columns, or columns whose upper bands
 * were lost to shading or the image's top).  0: no; else the kind of the
 * union (a pole wins). */
static int32_t join_kind(int32_t a, int32_t b)
{
    if (a == b)
        return a;
    if ((a == FL_HLV_POST_YELLOW && b == FL_HLV_POLE_YBY) || (a == FL_HLV_POST_BLUE && b == FL_HLV_POLE_BYB))
        return b;
    if ((b == FL_HLV_POST_YELLOW && a == FL_HLV_POLE_YBY) || (b == FL_HLV_POST_BLUE && a == FL_HLV_POLE_BYB))
        return a;
    return 0;
}

/* Add scanned column u (of kind col->kind, joinable) to the object. */
static void add_column(fl_hlv_object_t *o, const hlv_col_t *col, int32_t u, int32_t row_step)
{
    const bool pole = col->kind >= FL_HLV_POLE_YBY;
    if (o->cols == 0) {
        memset(o, 0, sizeof *o);
        o->kind = (fl_hlv_kind_t)col->kind;
        o->u0 = u;
        o->foot_v = col->foot;
        o->top_v = col->top;
        o->band_v[0] = col->band_lo;
        o->band_v[1] = col->band_hi;
        o->foot_u0 = o->foot_u1 = u;
        o->edge_foot_v[0] = col->foot;
    }
    o->edge_foot_v[1] = col->foot;
    o->kind = (fl_hlv_kind_t)join_kind((int32_t)o->kind, col->kind);
    o->u1 = u;
    /* a cylinder's lowest foot is below its axis: the columns within a
     * row step of the lowest foot give the foot's column */
    if (col->foot > o->foot_v + row_step) {
        o->foot_v = col->foot;
        o->foot_u0 = o->foot_u1 = u;
    } else if (col->foot >= o->foot_v - row_step) {
        if (col->foot > o->foot_v)
            o->foot_v = col->foot;
        o->foot_u1 = u;
    }
    if (pole && (o->band_v[0] < 0 || col->foot >= o->foot_v - row_step)) {
        o->band_v[0] = col->band_lo;
        o->band_v[1] = col->band_hi;
    }
    if (col->top < o->top_v)
        o->top_v = col->top;
    o->cols++;
}

void fl_hlv_int_objects(fl_hlv_t *s, const fl_image_t *img, int32_t v_start)
{
    const int32_t step = s->step_u;
    hlv_run_t runs[FL_HLV_MAX_RUNS];
    fl_hlv_object_t cur;
    hlv_col_t last;
    int32_t i, last_u = -1;
    s->n_objects = 0;
    memset(&cur, 0, sizeof cur);
    memset(&last, 0, sizeof last);
    if (v_start < 0)
        v_start = 0;
    for (i = 0; i < s->mask_w; i++) {
        hlv_col_t col;
        /* tops may be above the horizon: the whole column; a column
         * without yellow or sky-blue has nothing to find */
        const int32_t n = (s->colbits[i] & (FL_HLV_YELLOW | FL_HLV_BLUE)) ? column_runs(s, i, img->height, runs) : 0;
        const int32_t u = i * step + step / 2 < img->width ? i * step + step / 2 : img->width - 1;
        classify_column(s, runs, n, &col);
        if (col.kind != 0 && col.foot < v_start)
            col.kind = 0;   /* a foot above the horizon is no foot */
        /* the same object: a joinable kind, at most one empty scanned
         * column between, and its run overlapping the previous column's
         * (within foot_tol_px): a near post leans in the image, so its
         * feet differ from column to column by more than any fixed
         * tolerance */
        if (cur.cols > 0 && col.kind != 0 &&
            (join_kind(col.kind, (int32_t)cur.kind) == 0 || last_u < u - 2 * step ||
             col.top > last.foot + s->params.foot_tol_px ||
             last.top > col.foot + s->params.foot_tol_px)) {
            close_object(s, &cur, img);
            cur.cols = 0;
        }
        if (cur.cols > 0 && col.kind == 0 && last_u < u - step) {
            close_object(s, &cur, img);
            cur.cols = 0;
        }
        if (col.kind == 0)
            continue;
        add_column(&cur, &col, u, s->step_v);
        last_u = u;
        last = col;
    }
    if (cur.cols > 0)
        close_object(s, &cur, img);
    post_sides(s, img);
}
