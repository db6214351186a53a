/*
 * src/base/image.c - image views: validation and single-pixel access.
 *
 * A view never owns pixels.  Validation guarantees for a view that passed:
 * 1 <= width, height <= FL_IMAGE_MAX_DIM; every plane pointer non-NULL;
 * every stride >= one row of its plane and stride * height <= INT32_MAX, so
 * that v * stride + byte offset never overflows an int32 for in-range u, v.
 *
 * Color conversion is BT.601 full range (JPEG/JFIF), integer Q16:
 *   Y  = ( 19595 R + 38470 G +  7471 B + 2^15) >> 16
 *   Cb = (-11058 R - 21710 G + 32768 B + 128*2^16 + 2^15) >> 16
 *   Cr = ( 32768 R - 27439 G -  5329 B + 128*2^16 + 2^15) >> 16
 *   R = Y + 1.402 Cr', G = Y - 0.344136 Cb' - 0.714136 Cr', B = Y + 1.772 Cb'
 * (Cb' = Cb - 128), coefficients rounded to Q16, results rounded to
 * nearest and clamped to [0, 255].  Per-pixel cost: a handful of multiplies;
 * the scanner uses its own row loops and lookup tables, these accessors are
 * for tests, tools and sparse probes.
 */
#include "fieldloc/image.h"
#include "fieldloc/fixed.h"

#include <string.h>

static void image_clear(fl_image_t *img)
{
    memset(img, 0, sizeof *img);
}

/* Bytes per row of plane p for a validated format, or 0. */
static int32_t row_bytes(fl_pixel_format_t format, int32_t width, int p)
{
    switch (format) {
    case FL_FMT_RGB888: return p == 0 ? 3 * width : 0;
    case FL_FMT_YUYV422: return p == 0 ? 2 * width : 0;
    case FL_FMT_YCBCR_PLANAR: return width;
    }
    return 0;
}

static int plane_count(fl_pixel_format_t format)
{
    return format == FL_FMT_YCBCR_PLANAR ? 3 : 1;
}

fl_status_t fl_image_validate(const fl_image_t *img)
{
    int p, np;
    if (img == NULL)
        return FL_ERR_NULL;
    if (img->format != FL_FMT_RGB888 && img->format != FL_FMT_YUYV422 &&
        img->format != FL_FMT_YCBCR_PLANAR)
        return FL_ERR_FORMAT;
    if (img->width < 1 || img->height < 1 || img->width > FL_IMAGE_MAX_DIM ||
        img->height > FL_IMAGE_MAX_DIM)
        return FL_ERR_SIZE;
    if (img->format == FL_FMT_YUYV422 && (img->width & 1) != 0)
        return FL_ERR_FORMAT;
    np = plane_count(img->format);
    for (p = 0; p < np; p++) {
        if (img->plane[p] == NULL)
            return FL_ERR_NULL;
        if (img->stride[p] < row_bytes(img->format, img->width, p))
            return FL_ERR_STRIDE;
        if (img->stride[p] > INT32_MAX / img->height)
            return FL_ERR_STRIDE;
    }
    return FL_OK;
}

fl_status_t fl_image_init_packed(fl_image_t *img, fl_pixel_format_t format,
                                 const uint8_t *data, int32_t width,
                                 int32_t height, int32_t stride)
{
    fl_status_t s;
    if (img == NULL)
        return FL_ERR_NULL;
    image_clear(img);
    if (format == FL_FMT_YCBCR_PLANAR)
        return FL_ERR_FORMAT;
    img->width = width;
    img->height = height;
    img->format = format;
    img->plane[0] = data;
    img->stride[0] = stride;
    s = fl_image_validate(img);
    if (s != FL_OK)
        image_clear(img);
    return s;
}

fl_status_t fl_image_init_planar(fl_image_t *img, const uint8_t *y,
                                 int32_t y_stride, const uint8_t *cb,
                                 int32_t cb_stride, const uint8_t *cr,
                                 int32_t cr_stride, int32_t width,
                                 int32_t height)
{
    fl_status_t s;
    if (img == NULL)
        return FL_ERR_NULL;
    image_clear(img);
    img->width = width;
    img->height = height;
    img->format = FL_FMT_YCBCR_PLANAR;
    img->plane[0] = y;
    img->plane[1] = cb;
    img->plane[2] = cr;
    img->stride[0] = y_stride;
    img->stride[1] = cb_stride;
    img->stride[2] = cr_stride;
    s = fl_image_validate(img);
    if (s != FL_OK)
        image_clear(img);
    return s;
}

static bool inside(const fl_image_t *img, int32_t u, int32_t v)
{
    return fl_image_validate(img) == FL_OK && u >= 0 && v >= 0 &&
           u < img->width && v < img->height;
}

/* Scaling: R, G, B in [0, 255]; products < 2^24, sums < 2^25 plus the
 * 128*2^16 offset, all non-negative for Cb/Cr (the negative terms add to at
 * most 255 * 32768 = 128*2^16 - 2^15), so >> is a plain floor. */
static void rgb_to_ycbcr(const uint8_t *rgb, uint8_t out[3])
{
    int32_t r = rgb[0], g = rgb[1], b = rgb[2];
    out[0] = fl_satu8((19595 * r + 38470 * g + 7471 * b + 32768) >> 16);
    out[1] = fl_satu8((-11058 * r - 21710 * g + 32768 * b + (128 << 16) + 32768) >> 16);
    out[2] = fl_satu8((32768 * r - 27439 * g - 5329 * b + (128 << 16) + 32768) >> 16);
}

/* Scaling: Y in [0, 255], Cb', Cr' in [-128, 127]; Q16 products fit in
 * 2^24; the sum is rounded by adding 2^15 and flooring (>> of a negative
 * int is arithmetic on every supported compiler), then clamped. */
static void ycbcr_to_rgb(int32_t y, int32_t cb, int32_t cr, uint8_t out[3])
{
    int32_t y16 = y * 65536 + 32768, cbp = cb - 128, crp = cr - 128;
    out[0] = fl_satu8((y16 + 91881 * crp) >> 16);
    out[1] = fl_satu8((y16 - 22554 * cbp - 46802 * crp) >> 16);
    out[2] = fl_satu8((y16 + 116130 * cbp) >> 16);
}

bool fl_image_get_ycbcr(const fl_image_t *img, int32_t u, int32_t v,
                        uint8_t ycbcr[3])
{
    if (ycbcr == NULL)
        return false;
    if (!inside(img, u, v)) {
        ycbcr[0] = 0;
        ycbcr[1] = 128;
        ycbcr[2] = 128;
        return false;
    }
    fl_image_ycbcr_at(img, u, v, ycbcr);
    return true;
}

void fl_image_ycbcr_at(const fl_image_t *img, int32_t u, int32_t v, uint8_t ycbcr[3])
{
    const uint8_t *px;
    switch (img->format) {
    case FL_FMT_RGB888:
        rgb_to_ycbcr(img->plane[0] + v * img->stride[0] + 3 * u, ycbcr);
        break;
    case FL_FMT_YUYV422:
        px = img->plane[0] + v * img->stride[0] + 4 * (u >> 1);
        ycbcr[0] = px[(u & 1) * 2];
        ycbcr[1] = px[1];
        ycbcr[2] = px[3];
        break;
    case FL_FMT_YCBCR_PLANAR:
        ycbcr[0] = img->plane[0][v * img->stride[0] + u];
        ycbcr[1] = img->plane[1][v * img->stride[1] + u];
        ycbcr[2] = img->plane[2][v * img->stride[2] + u];
        break;
    }
}

bool fl_image_get_rgb(const fl_image_t *img, int32_t u, int32_t v,
                      uint8_t rgb[3])
{
    uint8_t ycc[3];
    if (rgb == NULL)
        return false;
    if (!inside(img, u, v)) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return false;
    }
    if (img->format == FL_FMT_RGB888) {
        memcpy(rgb, img->plane[0] + v * img->stride[0] + 3 * u, 3);
        return true;
    }
    (void)fl_image_get_ycbcr(img, u, v, ycc);
    ycbcr_to_rgb(ycc[0], ycc[1], ycc[2], rgb);
    return true;
}
