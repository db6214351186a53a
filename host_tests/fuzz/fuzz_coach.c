/*
 * libFuzzer harness: the coach's image path (fieldloc/coach.h) on arbitrary
 * frames, homography points, backgrounds and parameters.  Input layout:
 *   [0] format (mod 4: 0 a hand-made view with garbage geometry,
 *       1 RGB888, 2 YUYV422, 3 planar)
 *   [1..2] width, [3..4] height (little end first, taken mod 700: also
 *       beyond the coach's 640 x 480)
 *   [5] stride padding (low 4 bits)
 *   [6] flags: bit 0 store a background (bit 3: of another size),
 *       bit 1 take the parameters from the bytes below (else defaults),
 *       bit 2 the default coach's homography (tools/world/coach_scene.h,
 *       so frames reach the whole path) instead of the points below,
 *       bit 4 a second frame after clearing the background
 *   [7] number of points (mod 10)
 *   [8..43] nine points, 4 bytes each: u = 3 b0 px, v = 2 b1 px,
 *       x = 40 (b2 - 128) mm, y = 30 (b3 - 128) mm
 *   [44..63] parameters (bit 1): radii, region size, thresholds, the
 *       jersey boxes' bounds
 * then pixel bytes (repeated to fill the frame; the background uses them
 * from another offset).  The firmware must return a status, never touch
 * memory outside the views, keep its output bounded and consistent, and
 * keep the state usable.
 */
#include "fieldloc/fieldloc.h"
#include "fieldloc/coach.h"
#include "fieldloc/homography.h"
#include "world/adversarial.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define HDR 64

static fl_coach_t coach;
static int ready, last_custom;

/* the default coach's five points (fixtures/coach/coach.points) */
static const fl_homog_pair_t default_points[5] = {
    {10181, 707, 4500, 3000}, {43, 707, -4500, 3000}, {5112, 707, 0, 3000},
    {5112, 1837, 0, -3000}, {5112, 994, 0, 0}};

static uint8_t *fill(const uint8_t *data, size_t size, size_t bytes, size_t off)
{
    uint8_t *buf = malloc(bytes ? bytes : 1);
    size_t i, n = size > HDR ? size - HDR : 0;
    if (!buf)
        return NULL;
    for (i = 0; i < bytes; i++)
        buf[i] = n ? data[HDR + (i + off) % n] : (uint8_t)(i * 37u);
    return buf;
}

static void check_result(const fl_coach_result_t *r, fl_status_t st, const fl_field_t *field)
{
    fl_obs_report_t rep[FL_COACH_MAX_FEET];
    size_t k, n;
    if (r->n_feet > FL_COACH_MAX_FEET || (st != FL_OK && r->n_feet != 0))
        abort();
    for (k = 0; k < r->n_feet; k++) {
        const fl_coach_foot_t *f = &r->feet[k];
        if (f->team != FL_COLOR_RED && f->team != FL_COLOR_BLUE)
            abort();
        if (f->x_mm > FL_HOMOG_MAX_MM || f->x_mm < -FL_HOMOG_MAX_MM ||
            f->y_mm > FL_HOMOG_MAX_MM || f->y_mm < -FL_HOMOG_MAX_MM)
            abort();
    }
    n = fl_coach_reports(r, 0, rep, FL_COACH_MAX_FEET);
    if (n != r->n_feet)
        abort();
    for (k = 0; k < n; k++)
        if (fl_obs_report_check(&rep[k], field) != FL_OK)
            abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fl_coach_params_t p;
    fl_coach_result_t res;
    fl_homog_pair_t pts[9];
    fl_homog_t h;
    fl_image_t img, bg;
    fl_status_t st;
    int32_t w, h_px, pad, bw, bh;
    int fmt, npts, k;
    uint8_t flags, *buf, *bgbuf = NULL;
    size_t bytes;
    const fl_field_t *field = fl_field_find("spl2016");
    if (size < HDR)
        return 0;
    fmt = data[0] & 3;
    w = (data[1] | (data[2] << 8)) % 700;
    h_px = (data[3] | (data[4] << 8)) % 700;
    pad = data[5] & 15;
    flags = data[6];
    npts = data[7] % 10;
    fl_coach_params_default(&p);
    if (flags & 2) {
        const uint8_t *q = data + 44;
        p.open_radius = q[0] % 6;
        p.close_radius = q[1] % 10;
        p.min_region_px = (uint16_t)(q[2] | (q[3] << 8));
        p.bg_diff = q[4];
        p.otsu_lo = q[5];
        p.otsu_hi = q[6];
        p.field_pct = q[7];
        p.field_a_max = q[8];
        p.gap_rows = q[9] % 12;
        p.max_band_px = q[10];
        p.foot_offset_mm = (int16_t)(q[11] | (q[12] << 8));
        p.red.h_lo = q[13];
        p.red.s_lo = q[14];
        p.blue.h_hi = q[15];
        p.blue.v_lo = q[16];
    }
    /* init builds the colour tables (the slow part of a run): once with
     * the defaults, again only for parameters from the input; otherwise the
     * state of the previous run carries over (its background cleared), which
     * also checks that any run leaves it usable */
    if (!ready || (flags & 2) || last_custom) {
        st = fl_coach_init(&coach, &p);
        if ((st == FL_OK) != (fl_coach_params_check(&p, NULL) == FL_OK))
            abort();
        if (st != FL_OK) {
            fl_coach_params_default(&p);
            if (fl_coach_init(&coach, &p) != FL_OK)
                abort();
        }
        ready = 1;
        last_custom = (flags & 2) != 0;
    } else {
        fl_coach_clear_background(&coach);
    }
    for (k = 0; k < 9; k++) {
        const uint8_t *q = data + 8 + 4 * k;
        pts[k].u_q4 = 48 * q[0];
        pts[k].v_q4 = 32 * q[1];
        pts[k].x_mm = 40 * (q[2] - 128);
        pts[k].y_mm = 30 * (q[3] - 128);
    }
    if (flags & 4)
        st = fl_homog_fit(&h, default_points, 5) == FL_HOMOG_OK ? FL_OK : FL_ERR_RANGE;
    else
        st = fl_homog_fit(&h, pts, (size_t)npts) == FL_HOMOG_OK ? FL_OK : FL_ERR_RANGE;
    /* an unfitted homography must be refused too */
    (void)fl_coach_set_homography(&coach, &h, field);

    bytes = (size_t)(3 * w + pad + 1) * (size_t)(h_px + 1) * 3 + 16;
    buf = fill(data, size, bytes, 0);
    if (!buf)
        return 0;
    if (flags & 1) {
        bw = (flags & 8) ? (w + 2) % 700 : w;
        bh = h_px;
        bgbuf = fill(data, size, (size_t)(3 * bw + pad + 1) * (size_t)(bh + 1) * 3 + 16, 7);
        if (bgbuf) {
            adv_fuzz_view(&bg, fmt, bgbuf, bw, bh, pad, data[5]);
            (void)fl_coach_set_background(&coach, &bg);
        }
    }
    adv_fuzz_view(&img, fmt, buf, w, h_px, pad, data[5]);
    memset(&res, 0xA5, sizeof res);
    st = fl_coach_frame(&coach, &img, &res);
    check_result(&res, st, field);
    if (flags & 16) {
        fl_coach_clear_background(&coach);
        memset(&res, 0x5A, sizeof res);
        st = fl_coach_frame(&coach, &img, &res);
        check_result(&res, st, field);
    }
    /* NULLs: statuses, not crashes */
    if (fl_coach_frame(&coach, NULL, &res) == FL_OK || fl_coach_frame(NULL, &img, &res) == FL_OK)
        abort();
    free(buf);
    free(bgbuf);
    return 0;
}
