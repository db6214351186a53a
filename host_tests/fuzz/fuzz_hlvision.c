/*
 * libFuzzer harness: seed 002's vision path (hlvision.h) on arbitrary
 * bytes as a frame of arbitrary geometry and format (valid or not), with
 * params perturbed by the input.  Input layout: 12 header bytes
 *   [0] format (mod 4: 0 a hand-made view, 1 RGB888, 2 YUYV422, 3 planar)
 *   [1..2] width, [3..4] height (little end first, taken mod 700)
 *   [5] stride padding, [6] camera index (bit 7 set: the catalogue model
 *   as it is, usually of another size than the frame: the refusal path;
 *   clear: that model rescaled to the frame), [7..8] head pitch, [9]
 *   min_cols, [10] grid steps, [11] surround, gap, crossings
 * then pixel bytes (repeated to fill the frame).  The stage must return
 * without touching memory outside the view, keep its output bounded and
 * every observation well formed.
 */
#include "fieldloc/fieldloc.h"
#include "world/adversarial.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static fl_hlv_t hv;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fl_image_t img;
    fl_camera_t cam;
    fl_camera_pose_t pose;
    fl_obs_list_t obs;
    fl_hlv_params_t p;
    const fl_camera_model_t *m;
    fl_camera_model_t model;
    int32_t w, h, pad, n, i;
    size_t bytes;
    uint8_t *buf;
    if (size < 12)
        return 0;
    fl_hlv_params_default(&p, fl_field_find("hl3x2"));
    p.min_cols = 1 + (data[9] & 7);
    p.mask_step_u = 1 + (data[10] & 15);
    p.mask_step_v = 1 + ((data[10] >> 4) & 15);
    p.surround_px = 1 + (data[11] & 31);
    p.gap_px = (data[11] >> 5) * 4;
    p.crossings = (data[11] >> 4) & 1;
    if (fl_hlv_init(&hv, &p) != FL_OK)
        abort();
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
    if (fl_camera_init(&cam, m, &pose) != FL_OK)
        memset(&cam, 0, sizeof cam);   /* a camera that projects nothing */
    bytes = (size_t)(3 * w + pad + 1) * (size_t)(h + 1) * 3 + 16;
    buf = malloc(bytes);
    if (!buf)
        return 0;
    for (i = 0; (size_t)i < bytes; i++)
        buf[i] = size > 12 ? data[12 + (size_t)i % (size - 12)] : 0;
    switch (data[0] & 3) {
    case 1:
        (void)fl_image_init_packed(&img, FL_FMT_RGB888, buf, w, h, 3 * w + pad);
        break;
    case 2:
        (void)fl_image_init_packed(&img, FL_FMT_YUYV422, buf, w, h, 2 * w + pad);
        break;
    case 3: {
        size_t plane = (size_t)(w + pad) * (size_t)h;
        (void)fl_image_init_planar(&img, buf, w + pad, buf + plane, w + pad, buf + 2 * plane,
                                   w + pad, w, h);
        break;
    }
    default:   /* a hand-made view: garbage geometry */
        memset(&img, 0, sizeof img);
        img.width = w;
        img.height = h;
        img.format = (fl_pixel_format_t)(data[5] % 5);
        img.plane[0] = buf;
        img.stride[0] = pad;
        break;
    }
    n = fl_hlv_frame(&hv, &img, &cam, &obs);
    if (n < 0 || n > FL_OBS_MAX || obs.n != (uint16_t)n || obs.n_points > FL_OBS_MAX_POINTS)
        abort();
    if (hv.status != FL_OK && (n != 0 || obs.n_points != 0))
        abort();
    if (hv.n_objects > FL_HLV_MAX_OBJECTS || hv.mask_w > FL_SKEL_MAX_WIDTH ||
        hv.mask_h > FL_SKEL_MAX_HEIGHT)
        abort();
    for (i = 0; i < n; i++) {
        const fl_obs_t *o = &obs.obs[i];
        if (o->range_mm < 0 || o->range_mm > FL_OBS_MAX_RANGE_MM)
            abort();
        if (o->kind != FL_LM_POST && o->kind != FL_LM_BEACON && o->kind != FL_LM_X &&
            o->kind != FL_LM_T)
            abort();
        if (o->kind == FL_LM_BEACON && o->color != o->color2)
            abort();
    }
    for (i = 0; i < obs.n_points; i++)
        if (obs.points[i].x_mm < -FL_OBS_MAX_RANGE_MM || obs.points[i].x_mm > FL_OBS_MAX_RANGE_MM)
            abort();
    free(buf);
    return 0;
}
