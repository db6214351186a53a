/*
 * fieldloc/image.h - image views.  A view describes pixels owned by the
 * caller (the camera driver's buffer); fieldloc never copies or frees them.
 *
 * Pixel (u, v) of a packed format lives at plane[0][v * stride[0] + ...]:
 *   FL_FMT_RGB888   3 bytes per pixel R, G, B; stride[0] >= 3 * width
 *   FL_FMT_YUYV422  2 bytes per pixel, pairs Y0 U Y1 V (NAO's native camera
 *                   format); width must be even; stride[0] >= 2 * width
 *   FL_FMT_YCBCR_PLANAR  three planes Y, Cb, Cr, 1 byte per sample, full
 *                   resolution, each plane with its own stride >= width.
 *                   AIBO's band-per-row layout (Y, U, V rows interleaved)
 *                   is this with plane[1] = plane[0] + width, etc. and all
 *                   strides = 6 * width (or as the driver delivers).
 * Sizes: 1 <= width, height <= FL_IMAGE_MAX_DIM (config.h).
 */
#ifndef FIELDLOC_IMAGE_H
#define FIELDLOC_IMAGE_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    FL_FMT_RGB888 = 1,
    FL_FMT_YUYV422 = 2,
    FL_FMT_YCBCR_PLANAR = 3
} fl_pixel_format_t;

typedef struct {
    int32_t width;                 /* pixels */
    int32_t height;                /* pixels */
    fl_pixel_format_t format;
    const uint8_t *plane[3];       /* packed formats use plane[0] only */
    int32_t stride[3];             /* bytes from one row to the next */
} fl_image_t;

/* Fill *img as a view of a packed buffer (RGB888 or YUYV422) and validate
 * it.  On error *img is set to an empty view (width = height = 0). */
fl_status_t fl_image_init_packed(fl_image_t *img, fl_pixel_format_t format,
                                 const uint8_t *data, int32_t width,
                                 int32_t height, int32_t stride);

/* Fill *img as a view of three planes Y, Cb, Cr and validate it. */
fl_status_t fl_image_init_planar(fl_image_t *img, const uint8_t *y,
                                 int32_t y_stride, const uint8_t *cb,
                                 int32_t cb_stride, const uint8_t *cr,
                                 int32_t cr_stride, int32_t width,
                                 int32_t height);

/* Validate a view filled by hand.  FL_OK or the first problem found. */
fl_status_t fl_image_validate(const fl_image_t *img);

/* Read one pixel as Y, Cb, Cr (BT.601 full-range integer conversion from
 * RGB888; YUYV shares chroma between the pixel pair).  For tests and tools;
 * the scanner reads rows directly.  (u, v) must be inside a valid view;
 * outside it the output is 0, 128, 128 and false is returned. */
bool fl_image_get_ycbcr(const fl_image_t *img, int32_t u, int32_t v,
                        uint8_t ycbcr[3]);

/* The same without checks, for per-pixel loops of a stage: img must have
 * passed fl_image_validate and (u, v) must lie inside it (nothing is
 * checked; anything else reads out of bounds). */
void fl_image_ycbcr_at(const fl_image_t *img, int32_t u, int32_t v, uint8_t ycbcr[3]);

/* Read one pixel as R, G, B (integer BT.601 full-range from Y, Cb, Cr,
 * rounded and clamped).  Outside the view: 0, 0, 0 and false. */
bool fl_image_get_rgb(const fl_image_t *img, int32_t u, int32_t v,
                      uint8_t rgb[3]);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_IMAGE_H */
