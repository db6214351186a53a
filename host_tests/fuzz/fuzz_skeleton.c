/*
 * libFuzzer harness: arbitrary bytes as a binary mask of arbitrary size
 * (valid or not) through the skeleton stage (skeleton.h).  Input layout:
 * 10 header bytes
 *   [0..1] width, [2..3] height (little end first, taken mod the cap + 8,
 *   so oversize masks are tried too), [4] stride padding (bit 7: stride
 *   one less than the width, the refusal path), [5] params (bits 0-1
 *   spur_px 0/2/4/8, bits 2-3 merge_px 1/3/6/12, bits 4-5 arm_px
 *   2/5/8/16, bit 6 report_l, bit 7 max_iterations 3 instead of 32),
 *   [6..9] seed,
 * then the pixels, one bit each (bit 0 of a byte first), the bytes
 * repeated to fill the mask.  Checks: a valid mask gives FL_OK, an
 * invalid one its status; counts within their caps; the skeleton inside
 * the mask's white pixels and filled pinholes; every sampled point a
 * skeleton pixel; every crossing inside the mask with 2..4 arms in ascending order.
 */
#include "fieldloc/skeleton.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static fl_skel_t sk;
static uint8_t mask[(FL_SKEL_MAX_WIDTH + 8) * (FL_SKEL_MAX_HEIGHT + 8) + 160];

static int at(int32_t x, int32_t y, int32_t w, int32_t h, int32_t stride)
{
    return x >= 0 && y >= 0 && x < w && y < h && mask[y * stride + x] != 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const int32_t spur[4] = {0, 2, 4, 8}, merge[4] = {1, 3, 6, 12}, arm[4] = {2, 5, 8, 16};
    fl_skel_params_t p;
    fl_skel_mask_t m;
    int32_t w, h, stride, x, y, i;
    size_t n_px, k;
    int bad;
    fl_status_t st;
    if (size < 11)
        return 0;
    w = (data[0] | (data[1] << 8)) % (FL_SKEL_MAX_WIDTH + 8);
    h = (data[2] | (data[3] << 8)) % (FL_SKEL_MAX_HEIGHT + 8);
    stride = (data[4] & 128) ? w - 1 : w + (data[4] & 127);
    fl_skel_params_default(&p);
    p.spur_px = spur[data[5] & 3];
    p.merge_px = merge[(data[5] >> 2) & 3];
    p.arm_px = arm[(data[5] >> 4) & 3];
    p.report_l = (data[5] >> 6) & 1;
    p.max_iterations = (data[5] & 128) ? 3 : 32;
    if (fl_skel_init(&sk, &p) != FL_OK)
        abort();
    if (stride < 1)
        stride = 1;
    n_px = (size_t)stride * (size_t)(h > 0 ? h : 1);
    if (n_px > sizeof mask)
        n_px = sizeof mask;
    for (k = 0; k < n_px; k++) {
        size_t bit = k % ((size - 10) * 8);
        mask[k] = (uint8_t)((data[10 + bit / 8] >> (bit % 8)) & 1);
    }
    m.data = mask;
    m.width = w;
    m.height = h;
    m.stride = stride;
    bad = w < 1 || h < 1 || w > FL_SKEL_MAX_WIDTH || h > FL_SKEL_MAX_HEIGHT || stride < w ||
          (size_t)stride * (size_t)h > sizeof mask;
    if ((size_t)stride * (size_t)h > sizeof mask && !(w < 1 || h < 1 || w > FL_SKEL_MAX_WIDTH ||
                                                      h > FL_SKEL_MAX_HEIGHT || stride < w))
        return 0;   /* the harness's buffer, not a case */
    st = fl_skel_run(&sk, &m, (uint32_t)(data[6] | data[7] << 8 | data[8] << 16 | (uint32_t)data[9] << 24));
    if (bad) {
        if (st == FL_OK || sk.n_crossings != 0 || sk.n_points != 0)
            abort();
        return 0;
    }
    if (st != FL_OK)
        abort();
    if (sk.n_crossings < 0 || sk.n_crossings > FL_SKEL_MAX_CROSSINGS || sk.n_points < 0 ||
        sk.n_points > p.n_points || sk.n_nodes > FL_SKEL_MAX_NODES ||
        sk.n_skeleton > FL_SKEL_MAX_CONTOUR || sk.iterations > p.max_iterations)
        abort();
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++)
            if (fl_skel_pixel(&sk, x, y) && !at(x, y, w, h, stride) &&
                at(x - 1, y, w, h, stride) + at(x + 1, y, w, h, stride) +
                        at(x, y - 1, w, h, stride) + at(x, y + 1, w, h, stride) < 3)
                abort();
    for (i = 0; i < sk.n_points; i++)
        if (!fl_skel_pixel(&sk, sk.point[i].x, sk.point[i].y))
            abort();
    for (i = 0; i < sk.n_crossings; i++) {
        const fl_skel_crossing_t *c = &sk.crossing[i];
        int a;
        if (c->x_q4 < -16 || c->y_q4 < -16 || c->x_q4 > w * 16 || c->y_q4 > h * 16 ||
            c->kind < 2 || c->kind > 4 || (c->kind == FL_SKEL_L && !p.report_l))
            abort();
        for (a = 1; a < c->kind; a++)
            if (c->arm[a - 1] > c->arm[a])
                abort();
    }
    return 0;
}
