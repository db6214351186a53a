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
 * then pixel bytes (repeated to fill the frame; adv_fuzz_frame reads
 * [0..8] and the pixels).  The firmware must return
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
    fl_obs_list_t obs;
    const fl_field_t *field;
    int32_t n, i;
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
    field = fl_field_at((size_t)data[11] % fl_field_count());
    buf = adv_fuzz_frame(data, size, 12, (fl_angle_t)(int16_t)(data[9] | (data[10] << 8)), &img,
                         &cam);
    if (!buf)
        return 0;
    n = fl_vision_frame(&vis, &colors, &img, &cam, field, &obs);
    if (n < 0 || n > FL_OBS_MAX || obs.n != (uint16_t)n)
        abort();
    for (i = 0; i < n; i++)
        if (obs.obs[i].range_mm < 0 || (int)obs.obs[i].kind >= FL_LM_KIND_COUNT)
            abort();
    free(buf);
    return 0;
}
