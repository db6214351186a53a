/*
 * src/vision/skeleton.c - K3M thinning of a binary mask (skeleton.h).
 *
 * K3M (Saeed, Tabedzki, Rybnik, Adamski, AMCS 20(2):317-335, 2010).  The
 * weight of a pixel is the sum of its white neighbours' weights
 *      128   1   2
 *       64   .   4
 *       32  16   8
 * and every test is membership of the weight in a lookup array.  The
 * paper lists the arrays; they are, by construction (and so written here,
 * checked against that construction by host_tests/test_skeleton.c):
 *   A0     the white neighbours form one circular run of 2..7 pixels
 *          (phase 0: border pixels; 48 weights);
 *   A1..A4 one circular run of 3..(i + 2) pixels (8, 16, 24, 32 weights);
 *   A5     A4 and the runs of 7 whose missing neighbour is an edge one
 *          (weights 191, 239, 251, 254; 36 weights);
 *   A1pix  the final one-pixel phase: the paper lists the same 48
 *          weights as A0.  Four of them are runs of 7 whose missing
 *          neighbour is a corner (127, 223, 247, 253): such a pixel's only
 *          background neighbour touches it by a corner, so deleting it
 *          opens a hole in the line (a loop in the skeleton); phases 1..5
 *          never delete them (A5 leaves them out) and neither does this
 *          implementation's A1pix (44 weights).
 * One iteration: phase 0 marks the border pixels (weight in A0); phases
 * 1..5 each visit the marked pixels in order and delete, at once, those
 * whose current weight is in Ai; then the marks are cleared.  Iterate
 * until an iteration deletes nothing; then delete, in order, every pixel
 * whose weight is in A1pix.  The paper makes one such pass; a pixel it
 * keeps early in the order may become deletable when a later one goes (a
 * 2x2 block at a junction), so here the pass repeats while it deletes, at
 * most SK_ONE_PIXEL_PASSES times, and once more after the spurs are
 * removed (skeleton_cross.c).  Phases are sequential (a deletion changes
 * the weights the same phase sees next), so the result depends on the
 * visiting order: here the contour list's, which is the raster order of
 * the first contour followed by pixels in the order deletions expose them
 * (deterministic).
 *
 * The contour list replaces the paper's raster passes: it holds the white
 * pixels that touch the background (only they can be border pixels) and
 * gains the white neighbours of every deleted pixel; deleted pixels leave
 * it when an iteration ends.  So a pass costs the contour, not the frame,
 * and at the end the list is the skeleton.
 *
 * One more departure.  K3M keeps the corner pixel of every 4-connected
 * step (weight 88: W, S and SE white), so its lines at shallow angles
 * are 4-connected staircases and about a third of their pixels could go
 * without breaking anything.  A last pass (repeated while it deletes, at
 * most SK_ONE_PIXEL_PASSES times) deletes, in list order, the pixels
 * whose white neighbours form one 8-connected group (two edge neighbours
 * around a corner touch) with an edge neighbour background, and are 3 or
 * more, or exactly two edge neighbours at a right angle (the inner corner
 * of a step): simple points that are not ends (an end has one white
 * neighbour, or two that touch each other along the ring).  The result is
 * an 8-connected skeleton none of whose pixels but the ends can be
 * removed without splitting a neighbourhood or opening a hole.
 *
 * Table byte k3m[w]: bit 0 A0, bits 1..5 A1..A5, bit 6 A1pix, bit 7 the
 * last pass.
 * Memory: the caller's fl_skel_t; stack < 200 B.
 */
#include "skeleton_int.h"

#include <string.h>

static const uint8_t sk_k3m[256] = {
    0x00, 0x00, 0x00, 0x41, 0x00, 0x80, 0x41, 0xff, 0x00, 0x00, 0x00, 0x00, 0x41, 0x80, 0xff, 0xfd,
    0x00, 0x00, 0x00, 0x00, 0x80, 0x80, 0x80, 0x80, 0x41, 0x00, 0x00, 0x00, 0xff, 0x80, 0xfd, 0xf9,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x41, 0x00, 0x00, 0x00, 0x80, 0x80, 0x80, 0x80, 0xff, 0x00, 0x00, 0x00, 0xfd, 0x80, 0xf9, 0xf1,
    0x00, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0x80,
    0x80, 0x80, 0x00, 0x80, 0x80, 0x00, 0x80, 0x00, 0x80, 0x80, 0x00, 0x80, 0x80, 0x00, 0x80, 0x00,
    0x41, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0x80,
    0xff, 0x80, 0x00, 0x80, 0x80, 0x00, 0x80, 0x00, 0xfd, 0x80, 0x00, 0x80, 0xf9, 0x00, 0xf1, 0x01,
    0x00, 0x41, 0x00, 0xff, 0x00, 0x80, 0x00, 0xfd, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0xf9,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0xf1,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0xe1,
    0x41, 0xff, 0x00, 0xfd, 0x00, 0x80, 0x00, 0xf9, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0xf1,
    0x80, 0x80, 0x00, 0x80, 0x80, 0x00, 0x80, 0x00, 0x80, 0x80, 0x00, 0x80, 0x80, 0x00, 0x80, 0x01,
    0xff, 0xfd, 0x00, 0xf9, 0x00, 0x80, 0x00, 0xf1, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0xe1,
    0xfd, 0xf9, 0x00, 0xf1, 0x80, 0x00, 0x80, 0x01, 0xf9, 0xf1, 0x00, 0xe1, 0xf1, 0x01, 0xe1, 0x00,
};

/* Circular runs of white neighbours (Rutovitz crossing number) by weight. */
static const uint8_t sk_runs[256] = {
    0, 1, 1, 1, 1, 2, 1, 1, 1, 2, 2, 2, 1, 2, 1, 1, 1, 2, 2, 2, 2, 3, 2, 2, 1, 2, 2, 2, 1, 2, 1, 1,
    1, 2, 2, 2, 2, 3, 2, 2, 2, 3, 3, 3, 2, 3, 2, 2, 1, 2, 2, 2, 2, 3, 2, 2, 1, 2, 2, 2, 1, 2, 1, 1,
    1, 2, 2, 2, 2, 3, 2, 2, 2, 3, 3, 3, 2, 3, 2, 2, 2, 3, 3, 3, 3, 4, 3, 3, 2, 3, 3, 3, 2, 3, 2, 2,
    1, 2, 2, 2, 2, 3, 2, 2, 2, 3, 3, 3, 2, 3, 2, 2, 1, 2, 2, 2, 2, 3, 2, 2, 1, 2, 2, 2, 1, 2, 1, 1,
    1, 1, 2, 1, 2, 2, 2, 1, 2, 2, 3, 2, 2, 2, 2, 1, 2, 2, 3, 2, 3, 3, 3, 2, 2, 2, 3, 2, 2, 2, 2, 1,
    2, 2, 3, 2, 3, 3, 3, 2, 3, 3, 4, 3, 3, 3, 3, 2, 2, 2, 3, 2, 3, 3, 3, 2, 2, 2, 3, 2, 2, 2, 2, 1,
    1, 1, 2, 1, 2, 2, 2, 1, 2, 2, 3, 2, 2, 2, 2, 1, 2, 2, 3, 2, 3, 3, 3, 2, 2, 2, 3, 2, 2, 2, 2, 1,
    1, 1, 2, 1, 2, 2, 2, 1, 2, 2, 3, 2, 2, 2, 2, 1, 1, 1, 2, 1, 2, 2, 2, 1, 1, 1, 2, 1, 1, 1, 1, 0,
};

int fl_skel_degree(uint8_t w)
{
    return sk_runs[w];
}

/* The K3M table byte of weight w (for the tests: bit 0 A0, bits 1..5
 * A1..A5, bit 6 A1pix). */
int fl_skel_k3m_table(uint8_t w)
{
    return sk_k3m[w];
}

void fl_skel_params_default(fl_skel_params_t *p)
{
    if (!p)
        return;
    p->max_iterations = 32;
    p->spur_px = 3;
    p->merge_px = 6;
    p->arm_px = 6;
    p->n_points = FL_SKEL_MAX_POINTS;
    p->report_l = 0;
}

fl_status_t fl_skel_init_cfg(fl_skel_t *s, const fl_skel_params_t *p, uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *s has another layout: no write is safe */
    if (!s || !p)
        return FL_ERR_NULL;
    memset(s, 0, sizeof *s);
    fl_skel_params_default(&s->params);
    if (p->max_iterations < 1 || p->max_iterations > 255 ||
        p->spur_px < 0 || p->spur_px > 32 || p->merge_px < 1 || p->merge_px > 32 ||
        p->arm_px < 2 || p->arm_px > 32 || p->n_points < 0 ||
        p->n_points > FL_SKEL_MAX_POINTS || p->report_l < 0 || p->report_l > 1)
        return FL_ERR_RANGE;
    s->params = *p;
    s->magic = SK_MAGIC;
    return FL_OK;
}

static void sk_clear_results(fl_skel_t *s)
{
    s->n_crossings = 0;
    s->n_points = 0;
    s->n_white = 0;
    s->filled = 0;
    s->n_skeleton = 0;
    s->n_nodes = 0;
    s->iterations = 0;
    s->spurs = 0;
    s->contour_dropped = 0;
    s->iter_capped = 0;
    s->nodes_dropped = 0;
    s->crossings_dropped = 0;
    s->rejected = 0;
    s->n_contour = 0;
}

/* Append working pixel i to the contour list (flagged), or count it. */
static void sk_push(fl_skel_t *s, uint32_t i)
{
    if (s->n_contour < FL_SKEL_MAX_CONTOUR) {
        s->contour[s->n_contour++] = i;
        s->px[i] |= SK_LIST;
    } else {
        s->contour_dropped++;
    }
}

/* Mask pixel (x, y), 0 outside. */
static int sk_in(const fl_skel_mask_t *m, int32_t x, int32_t y)
{
    if (x < 0 || y < 0 || x >= m->width || y >= m->height)
        return 0;
    return m->data[(size_t)y * (size_t)m->stride + (size_t)x] != 0;
}

/* Add / remove pixel i's bit in its neighbours' weights: it is the S
 * neighbour (16) of the pixel above it, and so on. */
static inline void sk_weights_set(uint8_t *w, uint32_t i, uint32_t ps)
{
    w[i - ps] |= 16u;        w[i - ps + 1] |= 32u;
    w[i + 1] |= 64u;         w[i + ps + 1] |= 128u;
    w[i + ps] |= 1u;         w[i + ps - 1] |= 2u;
    w[i - 1] |= 4u;          w[i - ps - 1] |= 8u;
}

static inline void sk_weights_clear(uint8_t *w, uint32_t i, uint32_t ps)
{
    w[i - ps] &= (uint8_t)~16u;     w[i - ps + 1] &= (uint8_t)~32u;
    w[i + 1] &= (uint8_t)~64u;      w[i + ps + 1] &= (uint8_t)~128u;
    w[i + ps] &= (uint8_t)~1u;      w[i + ps - 1] &= (uint8_t)~2u;
    w[i - 1] &= (uint8_t)~4u;       w[i - ps - 1] &= (uint8_t)~8u;
}

void fl_skel_erase(fl_skel_t *s, uint32_t i)
{
    s->px[i] = (uint8_t)(s->px[i] & ~(SK_WHITE | SK_BORDER | SK_SEEN));
    sk_weights_clear(s->wt, i, (uint32_t)s->pstride);
}

/* Working pixel i becomes white and joins the list (raster order). */
static void sk_set_white(fl_skel_t *s, uint32_t i, int *overflow)
{
    s->px[i] = (uint8_t)SK_WHITE;
    sk_weights_set(s->wt, i, (uint32_t)s->pstride);
    s->n_white++;
    if (s->n_contour < FL_SKEL_MAX_CONTOUR) {
        s->contour[s->n_contour++] = i;
        s->px[i] |= SK_LIST;
    } else {
        *overflow = 1;
    }
}

/* One mask row into the working image.  Words of 8 background bytes whose
 * outer neighbours are background too are skipped: a pinhole has a white
 * left or right neighbour (3 of its 4 edge neighbours are white). */
static void sk_load_row(fl_skel_t *s, const fl_skel_mask_t *m, int32_t y, int *overflow)
{
    const uint8_t *row = m->data + (size_t)y * (size_t)m->stride;
    const uint32_t base = (uint32_t)(y + 1) * (uint32_t)s->pstride + 1u;
    int32_t x = 0;
    while (x < m->width) {
        if (x + 8 <= m->width) {
            uint64_t w8;
            memcpy(&w8, row + x, 8);
            if (w8 == 0 && (x == 0 || !row[x - 1]) && (x + 8 >= m->width || !row[x + 8])) {
                x += 8;
                continue;
            }
        }
        if (row[x]) {
            sk_set_white(s, base + (uint32_t)x, overflow);
        } else if ((x > 0 && row[x - 1]) || (x + 1 < m->width && row[x + 1])) {
            int n = sk_in(m, x - 1, y) + sk_in(m, x + 1, y) + sk_in(m, x, y - 1) +
                    sk_in(m, x, y + 1);
            if (n >= 3) {
                sk_set_white(s, base + (uint32_t)x, overflow);
                s->filled++;
            }
        }
        x++;
    }
}

/* Copy the mask into the bordered working image, filling pinholes: a
 * background pixel with 3 or 4 white edge neighbours in the mask (holes of
 * one or two pixels, one-pixel notches) becomes white.  Such noise would
 * put a loop, and so nodes, into the skeleton; the white pixels next to
 * it are already 8-connected, so no components merge.  Every white pixel
 * is listed as it is copied; then those inside (all 8 neighbours white)
 * leave the list, so it starts as the contour, in raster order.  When the
 * list was full, a raster pass lists the contour pixels that fit (the
 * others are counted). */
static void sk_load(fl_skel_t *s, const fl_skel_mask_t *m)
{
    const uint32_t ps = (uint32_t)m->width + 2u;
    int32_t y, r, w = 0;
    int overflow = 0;
    s->pstride = (int32_t)ps;
    memset(s->px, 0, ps * ((uint32_t)m->height + 2u));
    memset(s->wt, 0, ps * ((uint32_t)m->height + 2u));
    for (y = 0; y < m->height; y++)
        sk_load_row(s, m, y, &overflow);
    for (r = 0; r < s->n_contour; r++) {
        uint32_t i = s->contour[r];
        if (sk_weight(s, i) != 255u)
            s->contour[w++] = i;
        else
            s->px[i] = (uint8_t)SK_WHITE;
    }
    s->n_contour = w;
    if (overflow) {
        for (y = 1; y <= m->height; y++) {
            uint32_t i = (uint32_t)y * ps + 1u, end = i + (uint32_t)m->width;
            for (; i < end; i++)
                if ((s->px[i] & (SK_WHITE | SK_LIST)) == SK_WHITE && sk_weight(s, i) != 255u)
                    sk_push(s, i);
        }
    }
}

/* Delete working pixel i; its white neighbours not yet listed join the
 * list (they may now touch the background). */
static void sk_delete(fl_skel_t *s, uint32_t i, const int32_t off[8])
{
    uint32_t nb = s->wt[i];
    int k;
    s->px[i] = (uint8_t)(s->px[i] & ~(SK_WHITE | SK_BORDER));
    sk_weights_clear(s->wt, i, (uint32_t)s->pstride);
    for (k = 0; nb != 0; k++, nb >>= 1) {   /* the white neighbours */
        uint32_t j;
        if (!(nb & 1u))
            continue;
        j = (uint32_t)((int32_t)i + off[k]);
        if (!(s->px[j] & SK_LIST))
            sk_push(s, j);
    }
}

void fl_skel_compact(fl_skel_t *s)
{
    int32_t r, w = 0;
    for (r = 0; r < s->n_contour; r++) {
        uint32_t i = s->contour[r];
        if (s->px[i] & SK_WHITE) {
            s->px[i] = (uint8_t)(s->px[i] & ~SK_BORDER);
            s->contour[w++] = i;
        } else {
            s->px[i] = 0;
        }
    }
    s->n_contour = w;
}

/* One K3M iteration (phases 0..5); returns the pixels deleted. */
static int32_t sk_iteration(fl_skel_t *s, const int32_t off[8])
{
    int32_t r, n = s->n_contour, deleted = 0;
    int phase;
    for (r = 0; r < n; r++) {
        uint32_t i = s->contour[r];
        if ((s->px[i] & SK_WHITE) && (sk_k3m[sk_weight(s, i)] & 1u))
            s->px[i] |= SK_BORDER;
    }
    for (phase = 1; phase <= 5; phase++) {
        for (r = 0; r < n; r++) {
            uint32_t i = s->contour[r];
            if ((s->px[i] & SK_BORDER) &&
                (sk_k3m[sk_weight(s, i)] & (1u << phase))) {
                sk_delete(s, i, off);
                deleted++;
            }
        }
    }
    fl_skel_compact(s);
    return deleted;
}

/* One pass over the list deleting, in order, the pixels whose weight has
 * a table bit of `bit` (0x40: phase 6, A1pix; 0x80: the last pass).
 * Returns the pixels deleted. */
static int32_t sk_pass(fl_skel_t *s, const int32_t off[8], uint32_t bit)
{
    int32_t r, n = s->n_contour, deleted = 0;
    for (r = 0; r < n; r++) {
        uint32_t i = s->contour[r];
        if ((s->px[i] & SK_WHITE) && (sk_k3m[sk_weight(s, i)] & bit)) {
            sk_delete(s, i, off);
            deleted++;
        }
    }
    fl_skel_compact(s);
    return deleted;
}

void fl_skel_one_pixel(fl_skel_t *s)
{
    int32_t off[8], pass;
    sk_offsets(s->pstride, off);
    for (pass = 0; pass < SK_ONE_PIXEL_PASSES; pass++)
        if (sk_pass(s, off, 0x40u) == 0)
            break;
    for (pass = 0; pass < SK_ONE_PIXEL_PASSES; pass++)
        if (sk_pass(s, off, 0x80u) == 0)
            break;
}

fl_status_t fl_skel_run(fl_skel_t *s, const fl_skel_mask_t *mask, uint32_t seed)
{
    int32_t off[8];
    if (!s)
        return FL_ERR_NULL;
    if (s->magic != SK_MAGIC)
        return FL_ERR_STATE;
    sk_clear_results(s);
    s->width = 0;
    s->height = 0;
    if (!mask || !mask->data)
        return FL_ERR_NULL;
    if (mask->width < 1 || mask->width > FL_SKEL_MAX_WIDTH ||
        mask->height < 1 || mask->height > FL_SKEL_MAX_HEIGHT)
        return FL_ERR_SIZE;
    if (mask->stride < mask->width)
        return FL_ERR_STRIDE;
    s->width = mask->width;
    s->height = mask->height;
    sk_load(s, mask);
    sk_offsets(s->pstride, off);
    while (s->iterations < s->params.max_iterations) {
        s->iterations++;
        if (sk_iteration(s, off) == 0)
            break;
        if (s->iterations == s->params.max_iterations)
            s->iter_capped = 1;
    }
    fl_skel_one_pixel(s);
    fl_skel_find_crossings(s, seed);
    return FL_OK;
}

int fl_skel_pixel(const fl_skel_t *s, int32_t x, int32_t y)
{
    if (!s || x < 0 || y < 0 || x >= s->width || y >= s->height)
        return 0;
    return (s->px[(uint32_t)(y + 1) * (uint32_t)s->pstride + (uint32_t)x + 1u] & SK_WHITE) ? 1 : 0;
}
