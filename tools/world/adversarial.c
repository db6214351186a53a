/* tools/world/adversarial.c - hostile frames (see adversarial.h). */
#include "world/adversarial.h"

#include <stdlib.h>
#include <string.h>

static uint32_t adv_rand(uint64_t *s)   /* xorshift64* */
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (uint32_t)((*s * 2685821657736338717ull) >> 32);
}

static const char *const adv_names[ADV_COUNT] = {"all_green", "all_white", "all_yellow", "black",
                                           "saturated", "noise", "checker_8px", "checker_1px",
                                           "stripes"};

static void adv_rgb(adv_kind_t k, int u, int v, uint64_t *rng, uint8_t px[3])
{
    static const uint8_t green[3] = {82, 141, 85}, white[3] = {250, 250, 248},
                         yellow[3] = {191, 185, 47};
    const uint8_t *c = green;
    switch (k) {
    case ADV_GREEN: c = green; break;
    case ADV_WHITE: c = white; break;
    case ADV_YELLOW: c = yellow; break;
    case ADV_BLACK: px[0] = px[1] = px[2] = 0; return;
    case ADV_SATURATED: px[0] = px[1] = px[2] = 255; return;
    case ADV_NOISE: {
        uint32_t r = adv_rand(rng);
        px[0] = (uint8_t)r; px[1] = (uint8_t)(r >> 8); px[2] = (uint8_t)(r >> 16);
        return;
    }
    case ADV_CHECKER_LINE: c = ((u / 8 + v / 8) & 1) ? white : green; break;
    case ADV_CHECKER_PIXEL: c = ((u + v) & 1) ? white : green; break;
    case ADV_STRIPES: c = (v % 6 < 2 || u % 7 < 2) ? (u % 3 ? white : yellow) : green; break;
    default: break;
    }
    memcpy(px, c, 3);
}

/* RGB -> the integer BT.601 of src/base/image.c, via a 1x1 view. */
static void to_ycc(const uint8_t rgb[3], uint8_t ycc[3])
{
    fl_image_t one;
    fl_image_init_packed(&one, FL_FMT_RGB888, rgb, 1, 1, 3);
    fl_image_get_ycbcr(&one, 0, 0, ycc);
}

const char *adv_name(adv_kind_t k)
{
    return (int)k >= 0 && k < ADV_COUNT ? adv_names[k] : "?";
}

/* Build a frame of kind k, size w x h, format f, row padding pad; returns
 * the malloc'd buffer (freed by the caller) and fills the view. */
uint8_t *adv_frame(adv_kind_t k, int w, int hgt, fl_pixel_format_t f, int pad,
                          fl_image_t *img, fl_status_t *st)
{
    uint64_t rng;
    int u, v, bpp = f == FL_FMT_RGB888 ? 3 : f == FL_FMT_YUYV422 ? 2 : 1;
    /* YUYV rows hold whole pixel pairs, also for the (rejected) odd widths */
    int stride = (f == FL_FMT_YUYV422 ? 4 * ((w + 1) / 2) : bpp * w) + pad;
    size_t plane = (size_t)stride * (size_t)hgt + 1;
    uint8_t *buf = calloc(f == FL_FMT_YCBCR_PLANAR ? 3 * plane : plane, 1), px[3], ycc[3];
    if (!buf)
        return NULL;
    rng = 0x9e3779b97f4a7c15ull ^ (1234u + (uint64_t)k);
    for (v = 0; v < hgt; v++)
        for (u = 0; u < w; u++) {
            adv_rgb(k, u, v, &rng, px);
            if (f == FL_FMT_RGB888) {
                memcpy(buf + (size_t)v * (size_t)stride + 3 * (size_t)u, px, 3);
                continue;
            }
            to_ycc(px, ycc);
            if (f == FL_FMT_YUYV422) {
                uint8_t *q = buf + (size_t)v * (size_t)stride + 4 * (size_t)(u / 2);
                q[(u & 1) * 2] = ycc[0];
                if (!(u & 1)) { q[1] = ycc[1]; q[3] = ycc[2]; }
            } else {
                buf[(size_t)v * (size_t)stride + (size_t)u] = ycc[0];
                buf[plane + (size_t)v * (size_t)stride + (size_t)u] = ycc[1];
                buf[2 * plane + (size_t)v * (size_t)stride + (size_t)u] = ycc[2];
            }
        }
    if (f == FL_FMT_YCBCR_PLANAR)
        *st = fl_image_init_planar(img, buf, stride, buf + plane, stride, buf + 2 * plane, stride, w, hgt);
    else
        *st = fl_image_init_packed(img, f, buf, w, hgt, stride);
    return buf;
}


void adv_camera_model(const fl_camera_model_t *base, int w, int h, fl_camera_model_t *out)
{
    int64_t num, den;
    *out = *base;
    if (w < 1 || h < 1 || base->width_px < 1 || base->height_px < 1)
        return;
    /* ratio num / den = max(w / W, h / H) */
    if ((int64_t)w * base->height_px >= (int64_t)h * base->width_px) {
        num = w;
        den = base->width_px;
    } else {
        num = h;
        den = base->height_px;
    }
    out->width_px = w;
    out->height_px = h;
    out->focal_q4 = (int32_t)(base->focal_q4 * num / den);
    if (out->focal_q4 < 1)
        out->focal_q4 = 1;
    out->cx_q4 = (int32_t)((int64_t)base->cx_q4 * w / base->width_px);
    out->cy_q4 = (int32_t)((int64_t)base->cy_q4 * h / base->height_px);
}

uint8_t *adv_fuzz_frame(const uint8_t *data, size_t size, size_t header_len, fl_angle_t head_yaw,
                        fl_image_t *img, fl_camera_t *cam)
{
    const fl_camera_model_t *m;
    fl_camera_model_t model;
    fl_camera_pose_t pose;
    int32_t w, h, pad;
    size_t bytes, i;
    uint8_t *buf;
    w = (data[1] | (data[2] << 8)) % 700;
    h = (data[3] | (data[4] << 8)) % 700;
    pad = data[5] & 15;
    m = fl_camera_model_at((size_t)(data[6] & 127) % fl_camera_model_count());
    if (!(data[6] & 128)) {
        adv_camera_model(m, w, h, &model);
        m = &model;
    }
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    pose.head_pitch = (fl_angle_t)(int16_t)(data[7] | (data[8] << 8));
    pose.head_yaw = head_yaw;
    if (fl_camera_init(cam, m, &pose) != FL_OK)
        memset(cam, 0, sizeof *cam);   /* a camera that projects nothing */
    bytes = (size_t)(3 * w + pad + 1) * (size_t)(h + 1) * 3 + 16;
    buf = malloc(bytes);
    if (!buf)
        return NULL;
    for (i = 0; i < bytes; i++)
        buf[i] = size > header_len ? data[header_len + i % (size - header_len)] : 0;
    adv_fuzz_view(img, data[0] & 3, buf, w, h, pad, data[5]);
    return buf;
}

void adv_fuzz_view(fl_image_t *img, int fmt, uint8_t *buf, int32_t w, int32_t h, int32_t pad,
                   uint8_t garbage)
{
    switch (fmt) {
    case 1:
        (void)fl_image_init_packed(img, FL_FMT_RGB888, buf, w, h, 3 * w + pad);
        break;
    case 2:
        (void)fl_image_init_packed(img, FL_FMT_YUYV422, buf, w, h, 2 * w + pad);
        break;
    case 3: {
        size_t plane = (size_t)(w + pad) * (size_t)h;
        (void)fl_image_init_planar(img, buf, w + pad, buf + plane, w + pad, buf + 2 * plane,
                                   w + pad, w, h);
        break;
    }
    default:   /* a hand-made view: garbage geometry */
        memset(img, 0, sizeof *img);
        img->width = w;
        img->height = h;
        img->format = (fl_pixel_format_t)(garbage % 5);
        img->plane[0] = buf;
        img->stride[0] = pad;
        break;
    }
}
