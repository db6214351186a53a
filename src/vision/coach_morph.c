/*
 * src/vision/coach_morph.c - binary opening and closing of the coach's
 * bit-packed jersey masks (coach.h, step 3), word-parallel: 32 pixels per
 * uint32 (bit u & 31 of word u >> 5 is pixel u of the row; bits at and
 * beyond the width are kept clear).
 *
 * A (2r+1) x (2r+1) square is r passes of the 3 x 3 square, and a square
 * is a row of three times a column of three, so each erosion or dilation
 * is r horizontal and r vertical radius-1 passes:
 *   horizontal  x & (x >> 1 | next << 31) & (x << 1 | prev >> 31)  (or |
 *               for dilation), carrying the neighbouring words' end bits
 *   vertical    row & row above & row below (|), from a copy in tmp
 * Outside the image counts as set for erosion and clear for dilation
 * (OpenCV's default border for morphology), so a region touching the image
 * edge is not eaten from it.  With that border, r radius-1 passes equal one
 * radius-r pass inside the rectangle (every pixel of the big window is
 * reached through pixels of the image, which is convex).  The host test
 * coach.morph_reference checks both against a naive per-pixel version.
 * Cost: r * (2 * words * h) word operations per pass (plus a copy).
 */
#include "coach_int.h"

#include <string.h>

/* The valid bits of a row's last word. */
static uint32_t last_mask(int32_t w)
{
    int32_t k = w & 31;
    return k == 0 ? 0xFFFFFFFFu : ((1u << k) - 1u);
}

static void h_pass(uint32_t *m, int32_t words, int32_t w, int32_t h, bool erode)
{
    uint32_t edge = erode ? 0xFFFFFFFFu : 0u, lm = last_mask(w);
    int32_t v, i;
    for (v = 0; v < h; v++) {
        uint32_t *row = m + (size_t)v * (size_t)words;
        uint32_t prev = edge, x;
        if (erode)
            row[words - 1] |= ~lm;     /* beyond the width: outside, set */
        for (i = 0; i < words; i++) {
            uint32_t next = i + 1 < words ? row[i + 1] : edge;
            uint32_t right, left;
            x = row[i];
            right = (x >> 1) | (next << 31);
            left = (x << 1) | (prev >> 31);
            prev = x;
            row[i] = erode ? (x & right & left) : (x | right | left);
        }
        row[words - 1] &= lm;
    }
}

static void v_pass(uint32_t *m, uint32_t *tmp, int32_t words, int32_t h, bool erode)
{
    size_t n = (size_t)words * (size_t)h;
    int32_t v, i;
    memcpy(tmp, m, n * sizeof(uint32_t));
    for (v = 0; v < h; v++) {
        uint32_t *row = m + (size_t)v * (size_t)words;
        const uint32_t *up = v > 0 ? tmp + (size_t)(v - 1) * (size_t)words : NULL;
        const uint32_t *dn = v + 1 < h ? tmp + (size_t)(v + 1) * (size_t)words : NULL;
        for (i = 0; i < words; i++) {
            uint32_t x = row[i];
            if (erode) {
                if (up != NULL)
                    x &= up[i];
                if (dn != NULL)
                    x &= dn[i];
            } else {
                if (up != NULL)
                    x |= up[i];
                if (dn != NULL)
                    x |= dn[i];
            }
            row[i] = x;
        }
    }
}

static void morph(uint32_t *m, uint32_t *tmp, int32_t w, int32_t h, int32_t r, bool erode)
{
    int32_t words = fl_coach_words(w), k;
    for (k = 0; k < r; k++)
        h_pass(m, words, w, h, erode);
    for (k = 0; k < r; k++)
        v_pass(m, tmp, words, h, erode);
}

void fl_coach_open(uint32_t *mask, uint32_t *tmp, int32_t w, int32_t h, int32_t r)
{
    if (mask == NULL || tmp == NULL || w < 1 || h < 1 || r < 1)
        return;
    morph(mask, tmp, w, h, r, true);
    morph(mask, tmp, w, h, r, false);
}

void fl_coach_close(uint32_t *mask, uint32_t *tmp, int32_t w, int32_t h, int32_t r)
{
    if (mask == NULL || tmp == NULL || w < 1 || h < 1 || r < 1)
        return;
    morph(mask, tmp, w, h, r, false);
    morph(mask, tmp, w, h, r, true);
}
