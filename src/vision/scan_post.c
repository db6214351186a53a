/*
 * src/vision/scan_post.c - phase C of the column scanner (see scan.c for
 * the algorithm, include/fieldloc/scan.h for the outputs): goal posts.
 * Yellow right above a border (phase A' and the repair set the
 * column's post_top bit) is followed upward into the class map and a foot
 * recorded at the border.  Each marked column is read once, from the
 * border up, one pixel layout per walk.
 */
#include "scan_int.h"

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
 * the border when it is a post.  kind: the frame's pixel layout
 * (col_kind; a constant where inlined, so that neither the two samples
 * above the border nor the walk test the layout per sample). */
static FL_INLINE void trace_post(fl_scan_t *s, const frame_t *f, int32_t i, int32_t kind)
{
    const fl_color_table_t *ct = f->ct;
    int32_t jb = s->first_row[i], jj, n;
    bool yellow = false;
    col_t col;
    if (jb >= s->rows)
        return;
    col_init_k(&col, f, i * f->cs, kind);
    for (jj = jb - 1; jj >= 0 && jj >= jb - 2; jj--)
        if (col_class_k(&col, ct, jj * f->rs, kind) == FL_CLASS_YELLOW) {
            yellow = true;
            break;
        }
    if (!yellow)
        return;
    n = trace_walk(s, ct, &col, i, jb, kind);
    s->yellow_cols[i] = (uint16_t)(s->yellow_cols[i] + n);
    if (n >= 2)   /* a post, not a yellowish speck at the carpet edge */
        add_foot(s, i, i * f->cs, s->border_v[i]);
}

/* trace_post for the columns with a post_top bit, left to right (the
 * highest bit of each word first), for one pixel layout. */
static FL_INLINE void trace_all(fl_scan_t *s, const frame_t *f, int32_t kind)
{
    int32_t w;
    for (w = 0; w < s->words; w++) {
        uint64_t x = s->post_top[w];
        while (x != 0) {
            int32_t b = highest_bit(x);
            x &= ~(1ULL << b);
            trace_post(s, f, 32 * w + 31 - (b >> 1), kind);
        }
    }
}

/* A post is tall: one loop per pixel layout (the branch on it out of the
 * walks; YUYV and RGB step one offset for all three bytes). */
void fl_scan_internal_trace_posts(fl_scan_t *s, const frame_t *f)
{
    int32_t kind = col_kind(f);
    if (kind == 1)
        trace_all(s, f, 1);
    else if (kind == 0)
        trace_all(s, f, 0);
    else
        trace_all(s, f, 2);
}
