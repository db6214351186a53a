/*
 * libFuzzer harness: seed 004's corner stage (corners.h) on arbitrary
 * bytes as a frame of arbitrary geometry and format (valid or not), with
 * params perturbed by the input.  Input layout: 12 header bytes
 *   [0..8] adv_fuzz_frame's (format, width, height, stride padding, camera,
 *   head pitch: world/adversarial.h), [9] min_grad, [10] window and
 *   suppression radii, [11] bit 0: the nets from the full vision path's
 *   beacons on aibo2004 (else none), bit 1: no camera, bits 2-3 label
 *   mode, bits 4-7 pair_px
 * then pixel bytes (repeated to fill the frame).  The stage must return
 * without touching memory outside the view, keep every count within its
 * capacity, leave the results empty on an error, and give well-formed
 * corners and features.
 */
#include "fieldloc/fieldloc.h"
#include "world/adversarial.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static fl_color_table_t colors;
static fl_vision_t vis;
static fl_corners_t cs;
static int ready;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fl_image_t img;
    fl_camera_t cam;
    fl_obs_list_t obs;
    fl_corners_params_t p;
    fl_status_t st;
    const fl_beacon_t *beacons = NULL;
    int32_t i;
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
    fl_corners_params_default(&p);
    p.min_grad = 1 + data[9] % 255;
    p.window_r = 1 + (data[10] & 3);
    p.nms_r = 1 + ((data[10] >> 2) & 7);
    p.label_mode = (data[11] >> 2) % 3;
    p.pair_px = 1 + (data[11] >> 4);
    if (fl_corners_init(&cs, &p) != FL_OK)
        abort();
    buf = adv_fuzz_frame(data, size, 12, 0, &img, &cam);
    if (!buf)
        return 0;
    if (data[11] & 1) {
        (void)fl_vision_frame(&vis, &colors, &img, &cam, fl_field_find("aibo2004"), &obs);
        beacons = &vis.beacons;
    }
    st = fl_corners_run(&cs, &img, &colors, (data[11] & 2) ? NULL : &cam, beacons);
    if (cs.n_corners < 0 || cs.n_corners > FL_CORNERS_MAX_CORNERS || cs.n_features < 0 ||
        cs.n_features > FL_CORNERS_MAX_FEATURES)
        abort();
    if (st != FL_OK && (cs.n_corners != 0 || cs.n_features != 0))
        abort();
    for (i = 0; i < cs.n_corners; i++) {
        const fl_corner_t *k = &cs.corner[i];
        if (k->x < 0 || k->y < 0 || k->x >= img.width || k->y >= img.height ||
            k->label < FL_CORNER_OPEN || k->label > FL_CORNER_NET_CLOSED)
            abort();
    }
    for (i = 0; i < cs.n_features; i++) {
        const fl_cfeat_t *f = &cs.feature[i];
        if (f->type < FL_CFEAT_C || f->type > FL_CFEAT_NET_SKYBLUE)
            abort();
        if (f->has_ground && (f->range_mm < 0 || f->range_mm > 4 * FL_OBS_MAX_RANGE_MM))
            abort();
        if (f->type <= FL_CFEAT_T_NET &&
            (f->a < 0 || f->a >= cs.n_corners || f->b < 0 || f->b >= cs.n_corners ||
             f->u_q4 < 0 || f->v_q4 < 0 || f->u_q4 >= 16 * img.width || f->v_q4 >= 16 * img.height))
            abort();
    }
    free(buf);
    return 0;
}
