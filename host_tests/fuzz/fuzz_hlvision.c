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
 * then pixel bytes (repeated to fill the frame; adv_fuzz_frame reads
 * [0..8] and the pixels).  The stage must return
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
    fl_obs_list_t obs;
    fl_hlv_params_t p;
    int32_t n, i;
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
    buf = adv_fuzz_frame(data, size, 12, 0, &img, &cam);
    if (!buf)
        return 0;
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
