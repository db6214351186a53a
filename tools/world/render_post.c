/*
 * tools/world/render_post.c - the camera side of the renderer: lighting ramps,
 * motion blur, sensor noise, 8-bit quantization, JPEG-like 8x8 block
 * quantization, conversion to YUYV422 / planar YCbCr, and frame files (PPM
 * and the FLRAW container).  API: render.h.
 *
 * Algorithm.  On the linear-in-sRGB double image of render.c: multiply by
 * gain and the two brightness ramps; average blur_px + 1 bilinear taps along
 * the motion direction; add noise (a luminance part shared by R, G, B plus a
 * smaller per-channel part, sigma noise_x10 / 10 levels, Irwin-Hall
 * approximated normals from the frame seed); round to 8 bits.  JPEG-like:
 * BT.601 YCbCr, 4:2:0 chroma, 8x8 DCT with the JPEG Annex K tables scaled by
 * the strength (quality about 90 / 75 / 50 / 30), round, inverse DCT, back to
 * RGB.  The DCT basis uses the firmware's cosine table (angles (2n+1)k pi/16
 * are exact binary angles), so no libm transcendental is involved.
 * YUYV / planar use exactly the integer BT.601 conversion of src/base/image.c;
 * YUYV chroma is the rounded mean of the pixel pair.
 *
 * Invariant: deterministic from the scene (seed) and the input image.
 * Memory: one extra double image for blur, three double planes for JPEG.
 * Cost: a few passes over the frame; blur O(W H blur_px).
 */
#include "world/render_int.h"
#include "io/ppm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double clamp255(double x) { return x < 0 ? 0 : x > 255 ? 255 : x; }
static uint8_t q8(double x) { return (uint8_t)floor(clamp255(x) + 0.5); }

/* Bilinear sample of channel c at (x, y), clamped to the image. */
static double bilin(const double *img, int W, int H, double x, double y, int c)
{
    double fx, fy;
    int x0, y0, x1, y1;
    if (x < 0) x = 0;
    if (y < 0) y = 0;
    if (x > W - 1) x = W - 1;
    if (y > H - 1) y = H - 1;
    x0 = (int)floor(x);
    y0 = (int)floor(y);
    x1 = x0 + 1 < W ? x0 + 1 : x0;
    y1 = y0 + 1 < H ? y0 + 1 : y0;
    fx = x - x0;
    fy = y - y0;
    return (img[3 * ((size_t)y0 * (size_t)W + (size_t)x0) + (size_t)c] * (1 - fx) +
            img[3 * ((size_t)y0 * (size_t)W + (size_t)x1) + (size_t)c] * fx) * (1 - fy) +
           (img[3 * ((size_t)y1 * (size_t)W + (size_t)x0) + (size_t)c] * (1 - fx) +
            img[3 * ((size_t)y1 * (size_t)W + (size_t)x1) + (size_t)c] * fx) * fy;
}

/* ---- JPEG-like block quantization --------------------------------------------- */

static const int jpeg_qy[64] = {
    16, 11, 10, 16, 24, 40, 51, 61, 12, 12, 14, 19, 26, 58, 60, 55,
    14, 13, 16, 24, 40, 57, 69, 56, 14, 17, 22, 29, 51, 87, 80, 62,
    18, 22, 37, 56, 68, 109, 103, 77, 24, 35, 55, 64, 81, 104, 113, 92,
    49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99};
static const int jpeg_qc[64] = {
    17, 18, 24, 47, 99, 99, 99, 99, 18, 21, 26, 66, 99, 99, 99, 99,
    24, 26, 56, 99, 99, 99, 99, 99, 47, 66, 99, 99, 99, 99, 99, 99,
    99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99,
    99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99};

/* basis[k][n] = a(k) cos((2n+1) k pi / 16) */
static void dct_basis(double basis[8][8])
{
    int k, n;
    for (k = 0; k < 8; k++)
        for (n = 0; n < 8; n++) {
            int32_t a = ((2 * n + 1) * k * 2048) % 65536;
            basis[k][n] = (k == 0 ? 0.35355339059327373 : 0.5) * rcos(fl_angle_wrap(a));
        }
}

/* Quantize the 8x8 blocks of a plane (w x h, row stride w) in place. */
static void jpeg_plane(double *pl, int w, int h, const int *qt, double scale, double basis[8][8])
{
    int bx, by, i, j, k, l;
    for (by = 0; by < h; by += 8) {
        for (bx = 0; bx < w; bx += 8) {
            double blk[8][8], tmp[8][8], co[8][8];
            for (j = 0; j < 8; j++)
                for (i = 0; i < 8; i++) {
                    int x = bx + i < w ? bx + i : w - 1, y = by + j < h ? by + j : h - 1;
                    blk[j][i] = pl[(size_t)y * (size_t)w + (size_t)x] - 128.0;
                }
            /* forward: co = B blk B^T */
            for (j = 0; j < 8; j++)
                for (k = 0; k < 8; k++) {
                    double s = 0;
                    for (i = 0; i < 8; i++)
                        s += basis[k][i] * blk[j][i];
                    tmp[j][k] = s;
                }
            for (l = 0; l < 8; l++)
                for (k = 0; k < 8; k++) {
                    double s = 0, q;
                    for (j = 0; j < 8; j++)
                        s += basis[l][j] * tmp[j][k];
                    q = floor(qt[l * 8 + k] * scale + 0.5);
                    if (q < 1)
                        q = 1;
                    co[l][k] = floor(s / q + 0.5) * q;
                }
            /* inverse: blk = B^T co B */
            for (l = 0; l < 8; l++)
                for (i = 0; i < 8; i++) {
                    double s = 0;
                    for (k = 0; k < 8; k++)
                        s += co[l][k] * basis[k][i];
                    tmp[l][i] = s;
                }
            for (j = 0; j < 8; j++)
                for (i = 0; i < 8; i++) {
                    double s = 0;
                    if (bx + i >= w || by + j >= h)
                        continue;
                    for (l = 0; l < 8; l++)
                        s += basis[l][j] * tmp[l][i];
                    pl[(size_t)(by + j) * (size_t)w + (size_t)(bx + i)] = s + 128.0;
                }
        }
    }
}

static void jpeg_like(int strength, int W, int H, uint8_t *rgb8)
{
    static const double scales[5] = {0, 0.2, 0.5, 1.0, 1.67};
    double basis[8][8], scale;
    int cw = (W + 1) / 2, ch = (H + 1) / 2, u, v;
    size_t npx = (size_t)W * (size_t)H;
    double *Y = (double *)malloc(npx * sizeof *Y);
    double *Cb = (double *)malloc((size_t)cw * (size_t)ch * sizeof *Cb);
    double *Cr = (double *)malloc((size_t)cw * (size_t)ch * sizeof *Cr);
    if (!Y || !Cb || !Cr) {
        free(Y);
        free(Cb);
        free(Cr);
        return;
    }
    if (strength > 4)
        strength = 4;
    scale = scales[strength];
    dct_basis(basis);
    for (v = 0; v < H; v++)
        for (u = 0; u < W; u++) {
            const uint8_t *p = rgb8 + 3 * ((size_t)v * (size_t)W + (size_t)u);
            Y[(size_t)v * (size_t)W + (size_t)u] = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
        }
    for (v = 0; v < ch; v++)
        for (u = 0; u < cw; u++) {
            double sb = 0, sr = 0;
            int n = 0, i, j;
            for (j = 0; j < 2; j++)
                for (i = 0; i < 2; i++) {
                    int x = 2 * u + i, y = 2 * v + j;
                    const uint8_t *p;
                    if (x >= W || y >= H)
                        continue;
                    p = rgb8 + 3 * ((size_t)y * (size_t)W + (size_t)x);
                    sb += 128.0 - 0.168736 * p[0] - 0.331264 * p[1] + 0.5 * p[2];
                    sr += 128.0 + 0.5 * p[0] - 0.418688 * p[1] - 0.081312 * p[2];
                    n++;
                }
            Cb[(size_t)v * (size_t)cw + (size_t)u] = sb / n;
            Cr[(size_t)v * (size_t)cw + (size_t)u] = sr / n;
        }
    jpeg_plane(Y, W, H, jpeg_qy, scale, basis);
    jpeg_plane(Cb, cw, ch, jpeg_qc, scale, basis);
    jpeg_plane(Cr, cw, ch, jpeg_qc, scale, basis);
    for (v = 0; v < H; v++)
        for (u = 0; u < W; u++) {
            size_t ci = (size_t)(v / 2) * (size_t)cw + (size_t)(u / 2);
            double y = Y[(size_t)v * (size_t)W + (size_t)u], cb = Cb[ci] - 128.0, cr = Cr[ci] - 128.0;
            uint8_t *p = rgb8 + 3 * ((size_t)v * (size_t)W + (size_t)u);
            p[0] = q8(y + 1.402 * cr);
            p[1] = q8(y - 0.344136 * cb - 0.714136 * cr);
            p[2] = q8(y + 1.772 * cb);
        }
    free(Y);
    free(Cb);
    free(Cr);
}

/* ---- the pipeline -------------------------------------------------------------------- */

void post_process(const render_scene_t *sc, int W, int H, double *img, uint8_t *rgb8)
{
    int u, v, c;
    size_t npx = (size_t)W * (size_t)H, p;
    double gain = sc->gain_pct / 100.0;
    rnd_t r;

    /* lighting ramps */
    for (v = 0; v < H; v++) {
        double gy = 1.0 + (sc->grad_y_pct / 100.0) * ((H > 1 ? (double)v / (H - 1) : 0.5) - 0.5);
        for (u = 0; u < W; u++) {
            double gx = 1.0 + (sc->grad_x_pct / 100.0) * ((W > 1 ? (double)u / (W - 1) : 0.5) - 0.5);
            double k = gain * gx * gy;
            if (k < 0)
                k = 0;
            p = (size_t)v * (size_t)W + (size_t)u;
            for (c = 0; c < 3; c++)
                img[3 * p + (size_t)c] *= k;
        }
    }
    /* motion blur */
    if (sc->blur_px > 0) {
        int L = sc->blur_px > 64 ? 64 : (int)sc->blur_px, k;
        double dx = rcos(sc->blur_dir), dy = rsin(sc->blur_dir);
        double *tmp = (double *)malloc(npx * 3 * sizeof *tmp);
        if (tmp) {
            for (v = 0; v < H; v++)
                for (u = 0; u < W; u++) {
                    double acc[3] = {0, 0, 0};
                    for (k = 0; k <= L; k++) {
                        double o = k - 0.5 * L;
                        for (c = 0; c < 3; c++)
                            acc[c] += bilin(img, W, H, u + o * dx, v + o * dy, c);
                    }
                    p = (size_t)v * (size_t)W + (size_t)u;
                    for (c = 0; c < 3; c++)
                        tmp[3 * p + (size_t)c] = acc[c] / (L + 1);
                }
            memcpy(img, tmp, npx * 3 * sizeof *tmp);
            free(tmp);
        }
    }
    /* sensor noise and quantization */
    rnd_seed(&r, ((uint64_t)sc->seed << 20) ^ 0x5EED0F1E1D10CULL);
    for (p = 0; p < npx; p++) {
        if (sc->noise_x10 > 0) {
            double s = sc->noise_x10 / 10.0, l = 0.85 * s * rnd_gauss(&r);
            for (c = 0; c < 3; c++)
                img[3 * p + (size_t)c] += l + 0.5 * s * rnd_gauss(&r);
        }
        for (c = 0; c < 3; c++)
            rgb8[3 * p + (size_t)c] = q8(img[3 * p + (size_t)c]);
    }
    if (sc->jpeg > 0)
        jpeg_like((int)sc->jpeg, W, H, rgb8);
}

/* BT.601 full range, the integers of src/base/image.c. */
static void ycc(const uint8_t *p, int32_t out[3])
{
    int32_t r = p[0], g = p[1], b = p[2];
    out[0] = (19595 * r + 38470 * g + 7471 * b + 32768) >> 16;
    out[1] = (-11058 * r - 21710 * g + 32768 * b + (128 << 16) + 32768) >> 16;
    out[2] = (32768 * r - 27439 * g - 5329 * b + (128 << 16) + 32768) >> 16;
    if (out[1] > 255) out[1] = 255;
    if (out[2] > 255) out[2] = 255;
}

void post_convert(fl_pixel_format_t fmt, int W, int H, const uint8_t *rgb8, uint8_t *out)
{
    size_t npx = (size_t)W * (size_t)H, p;
    int32_t a[3], b[3];
    if (fmt == FL_FMT_YUYV422) {
        for (p = 0; p + 1 < npx; p += 2) {
            ycc(rgb8 + 3 * p, a);
            ycc(rgb8 + 3 * (p + 1), b);
            out[2 * p + 0] = (uint8_t)a[0];
            out[2 * p + 1] = (uint8_t)((a[1] + b[1] + 1) >> 1);
            out[2 * p + 2] = (uint8_t)b[0];
            out[2 * p + 3] = (uint8_t)((a[2] + b[2] + 1) >> 1);
        }
    } else if (fmt == FL_FMT_YCBCR_PLANAR) {
        for (p = 0; p < npx; p++) {
            ycc(rgb8 + 3 * p, a);
            out[p] = (uint8_t)a[0];
            out[npx + p] = (uint8_t)a[1];
            out[2 * npx + p] = (uint8_t)a[2];
        }
    } else {
        memcpy(out, rgb8, npx * 3);
    }
}

/* ---- names ----------------------------------------------------------------------------- */

const char *render_format_name(fl_pixel_format_t f)
{
    switch (f) {
    case FL_FMT_RGB888: return "rgb";
    case FL_FMT_YUYV422: return "yuyv";
    case FL_FMT_YCBCR_PLANAR: return "planar";
    default: return "?";
    }
}

fl_pixel_format_t render_format_from_name(const char *name)
{
    if (!name)
        return (fl_pixel_format_t)0;
    if (!strcmp(name, "rgb"))
        return FL_FMT_RGB888;
    if (!strcmp(name, "yuyv"))
        return FL_FMT_YUYV422;
    if (!strcmp(name, "planar"))
        return FL_FMT_YCBCR_PLANAR;
    return (fl_pixel_format_t)0;
}

const char *render_class_name(render_class_t c)
{
    static const char *names[RENDER_CLASS_COUNT] = {"background", "green", "line", "goal",
                                                    "object", "ball", "beacon"};
    return (int)c >= 0 && c < RENDER_CLASS_COUNT ? names[c] : "?";
}

/* ---- frame files ------------------------------------------------------------------------- */

int render_write_frame(const char *path, const render_frame_t *fr)
{
    FILE *f;
    int ok;
    if (!path || !fr || !fr->data)
        return -1;
    if (fr->format == FL_FMT_RGB888)
        return ppm_write(path, fr->data, fr->width, fr->height);
    f = fopen(path, "wb");
    if (!f)
        return -1;
    ok = fprintf(f, "FLRAW %s %d %d\n", render_format_name(fr->format), fr->width, fr->height) > 0;
    ok = ok && fwrite(fr->data, 1, fr->size, f) == fr->size;
    ok = (fclose(f) == 0) && ok;
    return ok ? 0 : -1;
}

int render_read_frame(const char *path, render_frame_t *fr, char *err, int err_len)
{
    FILE *f;
    char magic[8] = {0}, fmt[16] = {0};
    int w = 0, h = 0;
    size_t npx;
    fl_status_t st;
    if (!fr)
        return -1;
    memset(fr, 0, sizeof *fr);
    f = path ? fopen(path, "rb") : NULL;
    if (!f) {
        if (err) snprintf(err, (size_t)err_len, "%s: cannot open", path ? path : "(null)");
        return -1;
    }
    if (fread(magic, 1, 2, f) != 2) {
        fclose(f);
        if (err) snprintf(err, (size_t)err_len, "%s: empty", path);
        return -1;
    }
    if (magic[0] == 'P' && magic[1] == '6') {
        host_image_t im;
        fclose(f);
        if (ppm_read(path, &im, err, err_len) != 0)
            return -1;
        fr->width = im.width;
        fr->height = im.height;
        fr->format = FL_FMT_RGB888;
        fr->data = im.rgb;
        fr->size = (size_t)im.width * (size_t)im.height * 3;
        st = fl_image_init_packed(&fr->view, FL_FMT_RGB888, fr->data, im.width, im.height, 3 * im.width);
        if (st != FL_OK) {
            if (err) snprintf(err, (size_t)err_len, "%s: %s", path, fl_status_str(st));
            render_frame_free(fr);
            return -1;
        }
        return 0;
    }
    if (fscanf(f, "%3s %15s %d %d", magic + 2, fmt, &w, &h) != 4 || strcmp(magic, "FLRAW") != 0 ||
        fgetc(f) != '\n' || w <= 0 || h <= 0 || w > FL_IMAGE_MAX_DIM || h > FL_IMAGE_MAX_DIM ||
        !render_format_from_name(fmt) || render_format_from_name(fmt) == FL_FMT_RGB888) {
        fclose(f);
        if (err) snprintf(err, (size_t)err_len, "%s: not a PPM or FLRAW file", path);
        return -1;
    }
    fr->width = w;
    fr->height = h;
    fr->format = render_format_from_name(fmt);
    npx = (size_t)w * (size_t)h;
    fr->size = fr->format == FL_FMT_YUYV422 ? 2 * npx : 3 * npx;
    fr->data = (uint8_t *)malloc(fr->size);
    if (!fr->data || fread(fr->data, 1, fr->size, f) != fr->size) {
        fclose(f);
        render_frame_free(fr);
        if (err) snprintf(err, (size_t)err_len, "%s: short file", path);
        return -1;
    }
    fclose(f);
    if (fr->format == FL_FMT_YUYV422)
        st = fl_image_init_packed(&fr->view, FL_FMT_YUYV422, fr->data, w, h, 2 * w);
    else
        st = fl_image_init_planar(&fr->view, fr->data, w, fr->data + npx, w, fr->data + 2 * npx, w, w, h);
    if (st != FL_OK) {
        if (err) snprintf(err, (size_t)err_len, "%s: %s", path, fl_status_str(st));
        render_frame_free(fr);
        return -1;
    }
    return 0;
}
