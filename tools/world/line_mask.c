/*
 * tools/world/line_mask.c - binary masks of painted lines (line_mask.h).
 */
#include "world/line_mask.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void lm_segment(uint8_t *m, int w, int h, int stride, double x0, double y0,
                double x1, double y1, double hw0, double hw1)
{
    double dx = x1 - x0, dy = y1 - y0, l2 = dx * dx + dy * dy;
    double hwm = hw0 > hw1 ? hw0 : hw1;
    int xa = (int)floor((x0 < x1 ? x0 : x1) - hwm - 1), xb = (int)ceil((x0 > x1 ? x0 : x1) + hwm + 1);
    int ya = (int)floor((y0 < y1 ? y0 : y1) - hwm - 1), yb = (int)ceil((y0 > y1 ? y0 : y1) + hwm + 1);
    int x, y;
    if (xa < 0) xa = 0;
    if (ya < 0) ya = 0;
    if (xb > w - 1) xb = w - 1;
    if (yb > h - 1) yb = h - 1;
    for (y = ya; y <= yb; y++)
        for (x = xa; x <= xb; x++) {
            double t = l2 > 0 ? ((x - x0) * dx + (y - y0) * dy) / l2 : 0, ex, ey, hw;
            if (t < 0) t = 0;
            if (t > 1) t = 1;
            ex = x0 + t * dx - x;
            ey = y0 + t * dy - y;
            hw = hw0 + t * (hw1 - hw0);
            if (ex * ex + ey * ey <= hw * hw)
                m[(size_t)y * (size_t)stride + (size_t)x] = 1;
        }
}

void lm_ellipse(uint8_t *m, int w, int h, int stride, double cx, double cy,
                double rx, double ry, double hw)
{
    int k, n = 256;
    for (k = 0; k < n; k++) {
        double a0 = 2 * M_PI * k / n, a1 = 2 * M_PI * (k + 1) / n;
        lm_segment(m, w, h, stride, cx + rx * cos(a0), cy + ry * sin(a0),
                   cx + rx * cos(a1), cy + ry * sin(a1), hw, hw);
    }
}

static uint32_t lm_rand(uint32_t *r)
{
    *r ^= *r << 13;
    *r ^= *r >> 17;
    *r ^= *r << 5;
    return *r;
}

void lm_ragged(uint8_t *m, int w, int h, int stride, uint32_t seed, int pct)
{
    uint32_t r = seed * 2654435761u + 12345u;
    uint8_t *copy = malloc((size_t)stride * (size_t)h);
    int x, y;
    if (!copy)
        return;
    memcpy(copy, m, (size_t)stride * (size_t)h);
    if (r == 0)
        r = 1;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            uint8_t v = copy[(size_t)y * (size_t)stride + (size_t)x];
            int edge = 0;
            if (x > 0 && copy[(size_t)y * (size_t)stride + (size_t)x - 1] != v) edge = 1;
            if (x < w - 1 && copy[(size_t)y * (size_t)stride + (size_t)x + 1] != v) edge = 1;
            if (y > 0 && copy[(size_t)(y - 1) * (size_t)stride + (size_t)x] != v) edge = 1;
            if (y < h - 1 && copy[(size_t)(y + 1) * (size_t)stride + (size_t)x] != v) edge = 1;
            if (edge && (int)(lm_rand(&r) % 100u) < pct)
                m[(size_t)y * (size_t)stride + (size_t)x] = v ? 0 : 1;
        }
    free(copy);
}

int lm_field_view(uint8_t *m, int w, int h, int stride)
{
    double sx = w / 320.0, sy = h / 240.0;
    int x, y, n = 0;
    for (y = 0; y < h; y++)
        memset(m + (size_t)y * (size_t)stride, 0, (size_t)w);
    /* touch line across the view, far (thin) */
    lm_segment(m, w, h, stride, -10 * sx, 70 * sy, 330 * sx, 60 * sy, 1.6 * sx, 1.6 * sx);
    /* halfway line from the touch line (T) down toward the robot, widening */
    lm_segment(m, w, h, stride, 150 * sx, 65.6 * sy, 175 * sx, 250 * sy, 1.6 * sx, 4.0 * sx);
    /* centre circle seen in perspective, crossed by the halfway line */
    lm_ellipse(m, w, h, stride, 165 * sx, 170 * sy, 90 * sx, 45 * sy, 2.6 * sx);
    /* a penalty-area corner and its T on the left */
    lm_segment(m, w, h, stride, 20 * sx, 68.5 * sy, 10 * sx, 110 * sy, 1.8 * sx, 2.4 * sx);
    lm_segment(m, w, h, stride, 10 * sx, 110 * sy, 60 * sx, 112 * sy, 2.4 * sx, 2.4 * sx);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++)
            n += m[(size_t)y * (size_t)stride + (size_t)x] != 0;
    return n;
}
