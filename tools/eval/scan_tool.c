/*
 * tools/eval/scan_tool.c - the host helpers of scan_tool.h around the column
 * scanner: frame format conversion, the picture, scoring against a rendered
 * frame's truth, hue shifts.  Shared by `fieldloc scan`, the scanner
 * benchmark and the tests.
 */
#include "eval/scan_tool.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int scantool_frame_from_rgb(const uint8_t *rgb, int w, int h,
                            fl_pixel_format_t format, scantool_frame_t *out)
{
    fl_image_t src;
    size_t n = (size_t)w * (size_t)h, sw = (size_t)w;
    int u, v;
    memset(out, 0, sizeof *out);
    if (fl_image_init_packed(&src, FL_FMT_RGB888, rgb, w, h, 3 * w) != FL_OK)
        return -1;
    if (format == FL_FMT_YUYV422 && (w & 1))
        return -1;
    out->width = w;
    out->height = h;
    out->format = format;
    out->size = format == FL_FMT_RGB888 ? 3 * n : format == FL_FMT_YUYV422 ? 2 * n : 3 * n;
    out->data = malloc(out->size);
    if (!out->data)
        return -1;
    if (format == FL_FMT_RGB888) {
        memcpy(out->data, rgb, out->size);
        fl_image_init_packed(&out->view, format, out->data, w, h, 3 * w);
        return 0;
    }
    for (v = 0; v < h; v++) {
        for (u = 0; u < w; u++) {
            uint8_t ycc[3];
            fl_image_get_ycbcr(&src, u, v, ycc);
            if (format == FL_FMT_YUYV422) {
                uint8_t *p = out->data + (size_t)v * 2 * sw + 4 * (size_t)(u >> 1);
                if ((u & 1) == 0) {
                    uint8_t y2[3];
                    fl_image_get_ycbcr(&src, u + 1, v, y2);
                    p[0] = ycc[0];
                    p[1] = (uint8_t)((ycc[1] + y2[1] + 1) >> 1);
                    p[3] = (uint8_t)((ycc[2] + y2[2] + 1) >> 1);
                } else {
                    p[2] = ycc[0];
                }
            } else {
                size_t i = (size_t)v * sw + (size_t)u;
                out->data[i] = ycc[0];
                out->data[n + i] = ycc[1];
                out->data[2 * n + i] = ycc[2];
            }
        }
    }
    if (format == FL_FMT_YUYV422)
        fl_image_init_packed(&out->view, format, out->data, w, h, 2 * w);
    else
        fl_image_init_planar(&out->view, out->data, w, out->data + n, w,
                             out->data + 2 * n, w, w, h);
    return 0;
}

void scantool_frame_free(scantool_frame_t *f)
{
    if (f) {
        free(f->data);
        memset(f, 0, sizeof *f);
    }
}

static void put(uint8_t *out, int w, int h, int u, int v, int r, int g, int b)
{
    if (u < 0 || v < 0 || u >= w || v >= h)
        return;
    size_t i = 3 * ((size_t)v * (size_t)w + (size_t)u);
    out[i] = (uint8_t)r;
    out[i + 1] = (uint8_t)g;
    out[i + 2] = (uint8_t)b;
}

void scantool_picture(const fl_scan_t *s, const uint8_t *rgb, int w, int h,
                      uint8_t *out)
{
    int cs = s->params.col_step, rs = s->params.row_step, u, v, i, j, k;
    memcpy(out, rgb, (size_t)w * (size_t)h * 3);
    if (s->width != w || s->height != h)
        return;
    /* dim above the border (per pixel column: the border of its cell) */
    for (u = 0; u < w; u++) {
        int b = s->border_v[u / cs];
        for (v = 0; v < h && v < b; v++)
            for (k = 0; k < 3; k++) {
                size_t o = 3 * ((size_t)v * (size_t)w + (size_t)u) + (size_t)k;
                out[o] = (uint8_t)(out[o] * 2 / 5);
            }
    }
    for (j = 0; j < s->rows; j++)
        for (i = 0; i < s->cols; i++) {
            fl_color_class_t c = fl_scan_class_at(s, i, j);
            int du, dv;
            if (c != FL_CLASS_WHITE && c != FL_CLASS_YELLOW)
                continue;
            for (dv = 0; dv < rs; dv++)
                for (du = 0; du < cs; du++)
                    put(out, w, h, i * cs + du, j * rs + dv, 255, 255,
                        c == FL_CLASS_WHITE ? 255 : 0);
        }
    for (i = 0; i < s->cols; i++)
        if (s->border_v[i] < h)
            for (u = i * cs; u < (i + 1) * cs; u++)
                put(out, w, h, u, s->border_v[i], 255, 0, 0);
    for (k = 0; k < s->n_feet; k++)
        for (i = -3; i <= 3; i++) {
            put(out, w, h, s->feet[k].u + i, s->feet[k].v, 0, 255, 255);
            put(out, w, h, s->feet[k].u, s->feet[k].v + i, 0, 255, 255);
        }
}

void scantool_evaluate(const fl_scan_t *s, const render_frame_t *fr,
                       scantool_eval_t *e)
{
    int i, j, cs = s->params.col_step, rs = s->params.row_step;
    if (s->width != fr->width || s->height != fr->height)
        return;
    for (i = 0; i < s->cols; i++) {
        int u = i * cs, tb = fr->border_visible_v[u], err;
        if (tb < fr->height) {
            err = abs(s->border_v[i] - tb);
            e->border_cols++;
            e->border_within3 += err <= 3;
            e->border_abs_sum += err;
            if (err > e->border_max_abs)
                e->border_max_abs = err;
        }
        for (j = 0; j < s->rows; j++) {
            int v = j * rs, m = fr->mask[(size_t)v * (size_t)fr->width + (size_t)u];
            fl_color_class_t c;
            if (v < fr->border_v[u] || m == RENDER_CLASS_OBJECT || m == RENDER_CLASS_BALL)
                continue;
            c = fl_scan_class_at(s, i, j);
            if (c == FL_CLASS_WHITE)
                m == RENDER_CLASS_LINE ? e->white_tp++ : e->white_fp++;
            else if (m == RENDER_CLASS_LINE)
                e->white_fn++;
            if (c == FL_CLASS_YELLOW)
                m == RENDER_CLASS_GOAL ? e->yellow_tp++ : e->yellow_fp++;
            else if (m == RENDER_CLASS_GOAL)
                e->yellow_fn++;
        }
    }
}

double scantool_precision(long tp, long fp)
{
    return tp + fp > 0 ? (double)tp / (double)(tp + fp) : 1.0;
}

double scantool_recall(long tp, long fn)
{
    return tp + fn > 0 ? (double)tp / (double)(tp + fn) : 1.0;
}

void scantool_hue_shift(uint8_t *rgb, size_t n_pixels, int dh)
{
    size_t i;
    for (i = 0; i < n_pixels; i++) {
        double r = rgb[3 * i], g = rgb[3 * i + 1], b = rgb[3 * i + 2];
        double mx = fmax(r, fmax(g, b)), mn = fmin(r, fmin(g, b)), d = mx - mn;
        double h, c[3], hh, x;
        int sector;
        if (d <= 0)
            continue;
        if (mx == r)
            h = 60.0 * (g - b) / d;
        else if (mx == g)
            h = 120.0 + 60.0 * (b - r) / d;
        else
            h = 240.0 + 60.0 * (r - g) / d;
        h += 2.0 * dh;
        h = fmod(h, 360.0);
        if (h < 0)
            h += 360.0;
        hh = h / 60.0;
        sector = (int)hh;
        x = d * (1.0 - fabs(fmod(hh, 2.0) - 1.0));
        switch (sector % 6) {
        case 0: c[0] = d; c[1] = x; c[2] = 0; break;
        case 1: c[0] = x; c[1] = d; c[2] = 0; break;
        case 2: c[0] = 0; c[1] = d; c[2] = x; break;
        case 3: c[0] = 0; c[1] = x; c[2] = d; break;
        case 4: c[0] = x; c[1] = 0; c[2] = d; break;
        default: c[0] = d; c[1] = 0; c[2] = x; break;
        }
        rgb[3 * i] = (uint8_t)lrint(c[0] + mn);
        rgb[3 * i + 1] = (uint8_t)lrint(c[1] + mn);
        rgb[3 * i + 2] = (uint8_t)lrint(c[2] + mn);
    }
}
