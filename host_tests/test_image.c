/* host_tests/test_image.c - image views: validation and pixel access. */
#include "test.h"
#include "fieldloc/image.h"

#include <math.h>
#include <string.h>

static uint8_t buf[64 * 48 * 6];

static void test_validation(void)
{
    fl_image_t img;
    /* good views of every format */
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, 48, 192), FL_OK);
    CHECK_EQ(img.width, 64);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_YUYV422, buf, 64, 48, 128), FL_OK);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 1, 1, 3), FL_OK);
    CHECK_EQ(fl_image_init_planar(&img, buf, 64, buf + 4096, 70, buf + 9000, 64, 64, 48), FL_OK);
    /* stride larger than the width is fine */
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 10, 10, 400), FL_OK);

    /* NULLs */
    CHECK_EQ(fl_image_init_packed(NULL, FL_FMT_RGB888, buf, 64, 48, 192), FL_ERR_NULL);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, NULL, 64, 48, 192), FL_ERR_NULL);
    CHECK_EQ(img.width, 0);
    CHECK(img.plane[0] == NULL);
    CHECK_EQ(fl_image_init_planar(&img, buf, 64, NULL, 64, buf, 64, 64, 48), FL_ERR_NULL);
    CHECK_EQ(fl_image_validate(NULL), FL_ERR_NULL);
    /* sizes */
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 0, 48, 192), FL_ERR_SIZE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, 0, 192), FL_ERR_SIZE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, -5, 48, 192), FL_ERR_SIZE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, FL_IMAGE_MAX_DIM + 1, 2, 3 * (FL_IMAGE_MAX_DIM + 1)), FL_ERR_SIZE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, INT32_MAX, 192), FL_ERR_SIZE);
    /* strides */
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, 48, 191), FL_ERR_STRIDE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, 48, -192), FL_ERR_STRIDE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_YUYV422, buf, 64, 48, 127), FL_ERR_STRIDE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, buf, 64, 48, INT32_MAX), FL_ERR_STRIDE);
    CHECK_EQ(fl_image_init_planar(&img, buf, 64, buf, 63, buf, 64, 64, 48), FL_ERR_STRIDE);
    /* formats */
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_YUYV422, buf, 63, 48, 128), FL_ERR_FORMAT);
    CHECK_EQ(fl_image_init_packed(&img, (fl_pixel_format_t)99, buf, 64, 48, 192), FL_ERR_FORMAT);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_YCBCR_PLANAR, buf, 64, 48, 192), FL_ERR_FORMAT);
    /* a hand-filled view with garbage is rejected, and reading it is safe */
    memset(&img, 0x5a, sizeof img);
    CHECK(fl_image_validate(&img) != FL_OK);
    {
        uint8_t px[3] = {1, 2, 3};
        CHECK(!fl_image_get_rgb(&img, 0, 0, px));
        CHECK_EQ(px[0], 0);
    }
}

/* double reference of BT.601 full range */
static void ref_ycbcr(int r, int g, int b, double out[3])
{
    out[0] = 0.299 * r + 0.587 * g + 0.114 * b;
    out[1] = 128.0 - 0.168736 * r - 0.331264 * g + 0.5 * b;
    out[2] = 128.0 + 0.5 * r - 0.418688 * g - 0.081312 * b;
}

static void test_rgb_to_ycbcr(void)
{
    /* every 4th level of every channel (262144 colors; every color would
     * take 16.7M calls through the accessor) */
    static uint8_t px[3];
    fl_image_t img;
    int r, g, b, k, step = t_quick ? 17 : 4;
    double worst = 0, ref[3];
    uint32_t h = t_hash_init();
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, px, 1, 1, 3), FL_OK);
    for (r = 0; r < 256; r += step)
        for (g = 0; g < 256; g += step)
            for (b = 0; b < 256; b += step) {
                uint8_t y[3];
                px[0] = (uint8_t)r; px[1] = (uint8_t)g; px[2] = (uint8_t)b;
                CHECK(fl_image_get_ycbcr(&img, 0, 0, y));
                ref_ycbcr(r, g, b, ref);
                for (k = 0; k < 3; k++) {
                    double e = fabs(y[k] - fmin(255.0, fmax(0.0, ref[k])));
                    if (e > worst) worst = e;
                    h = t_hash_i32(h, y[k]);
                }
            }
    t_info("max |Y/Cb/Cr - BT.601 double| = %.3f LSB", worst);
    CHECK_LE(worst, 0.51);   /* rounded to nearest */
    /* neutral greys map to neutral chroma exactly */
    for (k = 0; k < 256; k++) {
        uint8_t y[3];
        px[0] = px[1] = px[2] = (uint8_t)k;
        fl_image_get_ycbcr(&img, 0, 0, y);
        CHECK_EQ(y[0], k);
        CHECK_EQ(y[1], 128);
        CHECK_EQ(y[2], 128);
    }
    t_digest("image.rgb_to_ycbcr", h);
}

static void test_yuyv_and_planar(void)
{
    /* a 6x3 YUYV frame with stride padding: pixel pairs share chroma */
    static uint8_t yuyv[3 * 16];
    static uint8_t yp[3 * 8], cbp[3 * 9], crp[3 * 7];
    fl_image_t a, p;
    int u, v, worst = 0;
    uint32_t h = t_hash_init();
    for (v = 0; v < 3; v++)
        for (u = 0; u < 6; u += 2) {
            uint8_t *q = yuyv + v * 16 + 2 * u;
            q[0] = (uint8_t)(20 * u + v);       /* Y0 */
            q[1] = (uint8_t)(100 + u);          /* U  */
            q[2] = (uint8_t)(20 * u + 10 + v);  /* Y1 */
            q[3] = (uint8_t)(150 - u);          /* V  */
            for (int k = 0; k < 2; k++) {
                yp[v * 8 + u + k] = q[k * 2];
                cbp[v * 9 + u + k] = q[1];
                crp[v * 7 + u + k] = q[3];
            }
        }
    CHECK_EQ(fl_image_init_packed(&a, FL_FMT_YUYV422, yuyv, 6, 3, 16), FL_OK);
    CHECK_EQ(fl_image_init_planar(&p, yp, 8, cbp, 9, crp, 7, 6, 3), FL_OK);
    for (v = 0; v < 3; v++)
        for (u = 0; u < 6; u++) {
            uint8_t x[3], y[3], rgb[3];
            CHECK(fl_image_get_ycbcr(&a, u, v, x));
            CHECK(fl_image_get_ycbcr(&p, u, v, y));
            CHECK(memcmp(x, y, 3) == 0);
            CHECK_EQ(x[0], 20 * (u & ~1) + 10 * (u & 1) + v);
            CHECK_EQ(x[1], 100 + (u & ~1));
            CHECK(fl_image_get_rgb(&a, u, v, rgb));
            {
                double r = x[0] + 1.402 * (x[2] - 128);
                double g = x[0] - 0.344136 * (x[1] - 128) - 0.714136 * (x[2] - 128);
                double b = x[0] + 1.772 * (x[1] - 128);
                double ref[3] = {r, g, b};
                for (int k = 0; k < 3; k++) {
                    double c = fmin(255, fmax(0, ref[k]));
                    int e = (int)fabs(rgb[k] - floor(c + 0.5));
                    if (e > worst) worst = e;
                    h = t_hash_i32(h, rgb[k]);
                }
            }
        }
    CHECK_LE(worst, 1);
    /* outside the view */
    {
        uint8_t x[3];
        CHECK(!fl_image_get_ycbcr(&a, 6, 0, x));
        CHECK(!fl_image_get_ycbcr(&a, -1, 0, x));
        CHECK(!fl_image_get_ycbcr(&a, 0, 3, x));
        CHECK_EQ(x[1], 128);
        CHECK(!fl_image_get_ycbcr(&a, 0, 0, NULL));
    }
    t_digest("image.yuyv_planar", h);
}

/* AIBO's band-per-row layout: each image row holds a Y band, then U, then V
 * (and three more bands the driver fills); planes alias one buffer. */
static void test_aibo_bands(void)
{
    enum { W = 8, H = 4 };
    static uint8_t raw[H * 6 * W];
    fl_image_t img;
    int u, v;
    for (v = 0; v < H; v++)
        for (u = 0; u < W; u++) {
            raw[v * 6 * W + u] = (uint8_t)(v * 10 + u);          /* Y */
            raw[v * 6 * W + W + u] = (uint8_t)(200 - u);         /* Cb (driver's U) */
            raw[v * 6 * W + 2 * W + u] = (uint8_t)(50 + v);      /* Cr */
        }
    CHECK_EQ(fl_image_init_planar(&img, raw, 6 * W, raw + W, 6 * W, raw + 2 * W, 6 * W, W, H), FL_OK);
    for (v = 0; v < H; v++)
        for (u = 0; u < W; u++) {
            uint8_t x[3];
            CHECK(fl_image_get_ycbcr(&img, u, v, x));
            CHECK_EQ(x[0], v * 10 + u);
            CHECK_EQ(x[1], 200 - u);
            CHECK_EQ(x[2], 50 + v);
        }
}

void suite_image(void)
{
    t_run("image.validation", test_validation);
    t_run("image.rgb_to_ycbcr", test_rgb_to_ycbcr);
    t_run("image.yuyv_and_planar", test_yuyv_and_planar);
    t_run("image.aibo_bands", test_aibo_bands);
}
