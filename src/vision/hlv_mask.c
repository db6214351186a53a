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
 * Three passes, each O(mask pixels): classify (top-down, recording the
 * distance to the last green above in mask[]), then bottom-up per row:
 * the distance to the next green below per column (below[]), and the row's
 * left and right distances (two sweeps over the row).
 */
#include "hlv_int.h"

#include <string.h>

#define HLV_FAR 255

void fl_hlv_int_mask(fl_hlv_t *s, const fl_image_t *img, int32_t j0)
{
    const int32_t mw = s->mask_w, mh = s->mask_h;
    const int32_t su = s->params.mask_step_u, sv = s->params.mask_step_v;
    const int32_t r = s->params.surround_px;
    int32_t i, j;
    if (j0 < 0)
        j0 = 0;
    if (j0 > mh)
        j0 = mh;
    memset(s->cls, 0, (size_t)(mw * j0));
    memset(s->mask, 0, (size_t)(mw * j0));
    memset(s->below, HLV_FAR, sizeof s->below);
    /* classify; mask[] = samples up to the last green above (capped) */
    for (j = j0; j < mh; j++) {
        const int32_t v = j * sv + sv / 2 < img->height ? j * sv + sv / 2 : img->height - 1;
        uint8_t *c = s->cls + j * mw, *m = s->mask + j * mw;
        for (i = 0; i < mw; i++) {
            const int32_t u = i * su + su / 2 < img->width ? i * su + su / 2 : img->width - 1;
            c[i] = hlv_pixel_class(s, img, u, v);
            if (c[i] & FL_HLV_GREEN)
                m[i] = 0;
            else if (j == j0)
                m[i] = HLV_FAR;
            else
                m[i] = (uint8_t)(m[i - mw] == HLV_FAR ? HLV_FAR : m[i - mw] + 1);
        }
    }
    /* bottom-up: below[i] is the distance to the next green below row j */
    for (j = mh - 1; j >= j0; j--) {
        uint8_t *c = s->cls + j * mw, *m = s->mask + j * mw;
        int32_t last = -HLV_FAR;   /* column of the last green to the left */
        uint8_t left_ok[FL_SKEL_MAX_WIDTH];
        for (i = 0; i < mw; i++) {
            if (c[i] & FL_HLV_GREEN)
                last = i;
            left_ok[i] = (uint8_t)(i - last <= r);
        }
        last = mw + HLV_FAR;
        for (i = mw - 1; i >= 0; i--) {
            const uint8_t up = m[i], down = s->below[i];
            uint8_t keep = 0;
            if (c[i] & FL_HLV_GREEN)
                last = i;
            if ((c[i] & FL_HLV_WHITE) && !(c[i] & FL_HLV_GREEN))
                keep = (uint8_t)((left_ok[i] && last - i <= r) || (up <= r && down <= r));
            m[i] = keep;
            s->below[i] = (uint8_t)((c[i] & FL_HLV_GREEN) ? 1
                                    : (down == HLV_FAR ? HLV_FAR : down + 1));
        }
    }
}
