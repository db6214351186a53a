/*
 * libFuzzer harness: arbitrary bytes as a frame of arbitrary geometry and
 * format (valid or not) through the color tables, the column scanner and
 * the whole vision path.  Input layout: 12 header bytes
 *   [0] format (mod 4: 0 invalid, 1 RGB888, 2 YUYV422, 3 planar)
 *   [1..2] width, [3..4] height (little end first, taken mod 700)
 *   [5] stride padding, [6] camera index (bits 0-6; bit 7 set: the
 *   catalogue model as it is, usually of another size than the frame:
 *   the refusal path; clear: that model rescaled to the frame,
 *   adv_camera_model), [7..8] head pitch, [9..10] yaw, [11] field index
 * then pixel bytes (repeated to fill the frame).  The firmware must return
 * without touching memory outside the view and keep its output bounded.
 */
#include "fieldloc/fieldloc.h"
#include "world/adversarial.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static fl_color_table_t colors;
static fl_vision_t vis;
static int ready;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fl_image_t img;
    fl_camera_t cam;
    fl_camera_pose_t pose;
    fl_obs_list_t obs;
    const fl_camera_model_t *m;
    fl_camera_model_t model;
    const fl_field_t *field;
    int32_t w, h, pad, n, i;
    size_t bytes;
    uint8_t *buf;
    if (!ready) {
        fl_color_params_t cp;
        fl_vision_params_t vp;
        fl_color_params_default(&cp);
        fl_vision_params_default(&vp);
        if (fl_color_init(&colors, &cp) != FL_OK || fl_vision_init(&vis, &vp) != FL_OK)
            abort();
        ready = 1;
    }
    if (size < 12)
        return 0;
    w = (data[1] | (data[2] << 8)) % 700;
    h = (data[3] | (data[4] << 8)) % 700;
    pad = data[5] & 15;
    m = fl_camera_model_at((size_t)(data[6] & 127) % fl_camera_model_count());
    if (!(data[6] & 128)) {
        adv_camera_model(m, w, h, &model);
        m = &model;
    }
    field = fl_field_at((size_t)data[11] % fl_field_count());
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    pose.head_pitch = (fl_angle_t)(int16_t)(data[7] | (data[8] << 8));
    pose.head_yaw = (fl_angle_t)(int16_t)(data[9] | (data[10] << 8));
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
    n = fl_vision_frame(&vis, &colors, &img, &cam, field, &obs);
    if (n < 0 || n > FL_OBS_MAX || obs.n != (uint16_t)n)
        abort();
    for (i = 0; i < n; i++)
        if (obs.obs[i].range_mm < 0 || (int)obs.obs[i].kind >= FL_LM_KIND_COUNT)
            abort();
    free(buf);
    return 0;
}
