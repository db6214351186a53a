/*
 * src/vision/hlv_mask.c - seed 002's "white pixels surrounded by green"
 * (its IV.B.3) at the mask's subsampled resolution.
 *
 * A white sample is kept when green lies within surround_px samples on
 * both sides along its row, or on both sides along its column.  Either
 * direction alone would lose part of the lines: a line running across the
 * view is bounded by green above and below only, one running away from the
 * camera by green left and right only; a crossing's centre has green on
 * neither side along one direction but on the diagonal-free other (or
 * within surround_px of both arms), which is why surround_px must cover
 * half the widest line in samples (hlv.c, the defaults).
 *
 * The classes come from the grid (fl_hlv_int_classify, one pixel read
 * per cell, row by row so that the reads stay in the cache lines of a few
 * image rows).  One pass over the grid keeps, per row and per column, the
 * cells since the last green to the left and above; a white cell with
 * green within surround_px to the left (above) looks for green to the
 * right (below), at most surround_px cells and usually a handful (a walk
 * stops at the first green): at most 2 surround_px reads per white cell.
 */
#include "hlv_int.h"

#include <string.h>

/* Grid row j: image row j * sv + sv / 2, clamped; the same for columns. */
static int32_t grid_px(int32_t i, int32_t step, int32_t size)
{
    const int32_t p = i * step + step / 2;
    return p < size ? p : size - 1;
}

/* One grid row's classes (and each column's OR of them).  The packed
 * formats are read in place (the same bytes fl_image_ycbcr_at reads); RGB
 * goes through image.c's integer conversion. */
static void classify_row(fl_hlv_t *s, const fl_image_t *img, int32_t v, uint8_t *c)
{
    const int32_t mw = s->mask_w, su = s->step_u, w1 = img->width - 1;
    int32_t i, u;
    if (img->format == FL_FMT_YUYV422) {
        const uint8_t *row = img->plane[0] + v * img->stride[0];
        for (i = 0, u = su / 2; i < mw; i++, u += su) {
            const uint8_t *px = row + 4 * ((u < w1 ? u : w1) >> 1);
            c[i] = fl_hlv_class(s, px[((u < w1 ? u : w1) & 1) * 2], px[1], px[3]);
        }
    } else if (img->format == FL_FMT_YCBCR_PLANAR) {
        const uint8_t *y = img->plane[0] + v * img->stride[0];
        const uint8_t *cb = img->plane[1] + v * img->stride[1];
        const uint8_t *cr = img->plane[2] + v * img->stride[2];
        for (i = 0, u = su / 2; i < mw; i++, u += su) {
            const int32_t x = u < w1 ? u : w1;
            c[i] = fl_hlv_class(s, y[x], cb[x], cr[x]);
        }
    } else {
        for (i = 0, u = su / 2; i < mw; i++, u += su)
            c[i] = hlv_pixel_class(s, img, u < w1 ? u : w1, v);
    }
    for (i = 0; i < mw; i++)
        s->colbits[i] |= c[i];
}

void fl_hlv_int_classify(fl_hlv_t *s, const fl_image_t *img)
{
    int32_t j;
    memset(s->colbits, 0, sizeof s->colbits);
    for (j = 0; j < s->mask_h; j++)
        classify_row(s, img, grid_px(j, s->step_v, img->height), s->cls + j * s->mask_w);
}

/* Green within r cells of (i, j) going by (di, dj), inside the grid. */
static bool green_within(const fl_hlv_t *s, int32_t i, int32_t j, int32_t di, int32_t dj, int32_t r,
                         int32_t j0)
{
    int32_t k;
    for (k = 1; k <= r; k++) {
        const int32_t x = i + k * di, y = j + k * dj;
        if (x < 0 || x >= s->mask_w || y < j0 || y >= s->mask_h)
            return false;
        if (s->cls[y * s->mask_w + x] & FL_HLV_GREEN)
            return true;
    }
    return false;
}

void fl_hlv_int_mask(fl_hlv_t *s, int32_t j0)
{
    const int32_t mw = s->mask_w, mh = s->mask_h, r = s->params.surround_px;
    int32_t i, j;
    if (j0 < 0)
        j0 = 0;
    if (j0 > mh)
        j0 = mh;
    memset(s->mask, 0, (size_t)(mw * mh));
    memset(s->up, 255, sizeof s->up);
    for (j = j0; j < mh; j++) {
        const uint8_t *c = s->cls + j * mw;
        uint8_t *m = s->mask + j * mw;
        int32_t left = 255;   /* cells since the last green in this row */
        for (i = 0; i < mw; i++) {
            if (c[i] & FL_HLV_GREEN) {
                left = 0;
                s->up[i] = 0;
                continue;
            }
            left = left < 255 ? left + 1 : 255;
            s->up[i] = (uint8_t)(s->up[i] < 255 ? s->up[i] + 1 : 255);
            if (c[i] & FL_HLV_WHITE)
                m[i] = (uint8_t)((left <= r && green_within(s, i, j, 1, 0, r, j0)) ||
                                 (s->up[i] <= r && green_within(s, i, j, 0, 1, r, j0)));
        }
    }
}
