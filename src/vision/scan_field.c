/*
 * src/vision/scan_field.c - phase D of the column scanner (see scan.c for
 * the algorithm, include/fieldloc/scan.h for the outputs): the field color
 * of this frame, from the exact HSV of every estimate_step_px-th pixel
 * below the border (in u and v): hue mode and mean around it, mean S, V
 * and luma, for fl_color_adapt (color.h).  A few dozen samples per frame
 * at the default step, each one an RGB -> HSV conversion.
 */
#include "scan_int.h"

#include <string.h>

/* R, G, B of the column's pixel at byte offsets oy (Y, or R of RGB888),
 * ocb, ocr from the column's first row. */
static void col_rgb(const col_t *c, size_t oy, size_t ocb, size_t ocr, uint8_t rgb[3])
{
    if (c->rgb) {
        const uint8_t *q = c->y + oy;
        rgb[0] = q[0];
        rgb[1] = q[1];
        rgb[2] = q[2];
        return;
    }
    fl_rgb_from_ycbcr(c->y[oy], c->cb[ocb], c->cr[ocr], rgb);
}

static int32_t hue_wrap(int32_t h)
{
    if (h < 0)
        return h + 180;
    return h >= 180 ? h - 180 : h;
}

void fl_scan_internal_estimate_field(fl_scan_t *s, const frame_t *f)
{
    const fl_hsv_box_t *gb = &f->ct->green;
    int32_t est = s->params.estimate_step_px;
    int32_t ecs, ers, i, j, h, n = 0, best = -1, mode = 0, acc, wsum, sum;
    int32_t span = gb->h_hi >= gb->h_lo ? gb->h_hi - gb->h_lo : gb->h_hi + 180 - gb->h_lo;
    int32_t centre = hue_wrap(gb->h_lo + span / 2);
    int32_t smin = gb->s_lo / 2;
    uint32_t ss = 0, sv = 0, sl = 0;
    memset(&s->field, 0, sizeof s->field);
    if (est <= 0)
        return;
    ecs = est / f->cs > 0 ? est / f->cs : 1;
    ers = est / f->rs > 0 ? est / f->rs : 1;
    memset(s->hue_hist, 0, sizeof s->hue_hist);
    for (i = 0; i < s->cols; i += ecs) {
        int32_t jf = s->first_row[i];
        size_t vv, dv, oy, ocb, ocr;
        col_t col;
        col_init(&col, f, i * f->cs);
        j = (jf + ers - 1) / ers * ers;
        /* the sample's byte offsets, stepped from sample to sample */
        vv = (size_t)j * (size_t)f->rs;
        dv = (size_t)ers * (size_t)f->rs;
        oy = vv * col.sy;
        ocb = vv * col.scb;
        ocr = vv * col.scr;
        for (; j < s->rows; j += ers, oy += dv * col.sy, ocb += dv * col.scb,
             ocr += dv * col.scr) {
            uint8_t rgb[3];
            fl_hsv_t hsv;
            int32_t dh;
            col_rgb(&col, oy, ocb, ocr, rgb);
            hsv = fl_hsv_from_rgb(rgb[0], rgb[1], rgb[2]);
            dh = hsv.h - centre;
            dh = dh > 90 ? dh - 180 : (dh < -90 ? dh + 180 : dh);
            if (hsv.s < smin || dh > 30 || dh < -30)
                continue;
            s->hue_hist[hsv.h]++;
            ss += hsv.s;
            sv += hsv.v;
            /* fl_luma_from_rgb, inline */
            sl += (uint32_t)(19595 * rgb[0] + 38470 * rgb[1] + 7471 * rgb[2] + 32768) >> 16;
            n++;
        }
    }
    if (n == 0)
        return;
    /* mode of the histogram smoothed over 5 bins (sliding sum) */
    sum = s->hue_hist[178] + s->hue_hist[179] + s->hue_hist[0] + s->hue_hist[1] +
          s->hue_hist[2];
    /* three stretches so that only the ends wrap (h - 2 below 0, h + 3
     * past 179) */
    for (h = 0; h < 2; h++) {
        if (sum > best) {
            best = sum;
            mode = h;
        }
        sum += s->hue_hist[h + 3] - s->hue_hist[h + 178];
    }
    for (; h < 177; h++) {
        if (sum > best) {
            best = sum;
            mode = h;
        }
        sum += s->hue_hist[h + 3] - s->hue_hist[h - 2];
    }
    for (; h < 180; h++) {
        if (sum > best) {
            best = sum;
            mode = h;
        }
        sum += s->hue_hist[h - 177] - s->hue_hist[h - 2];
    }
    acc = 0;
    wsum = 0;
    for (h = -8; h <= 8; h++) {
        acc += h * s->hue_hist[hue_wrap(mode + h)];
        wsum += s->hue_hist[hue_wrap(mode + h)];
    }
    /* Scaling: |acc| <= 8 * n; rounded division to nearest */
    if (wsum > 0)
        mode += (acc >= 0 ? acc + wsum / 2 : acc - wsum / 2) / wsum;
    s->field.n = n;
    s->field.hue = (uint8_t)hue_wrap(mode);
    s->field.sat = (uint8_t)(ss / (uint32_t)n);
    s->field.val = (uint8_t)(sv / (uint32_t)n);
    s->field.luma = (uint8_t)(sl / (uint32_t)n);
}
