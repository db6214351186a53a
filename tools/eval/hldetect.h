/*
 * tools/eval/hldetect.h - host helpers around seed 002's vision path
 * (include/fieldloc/hlvision.h) for `fieldloc detect` on hl3x2 frames, the
 * benchmark and the tests: a malloc'd state, the feature list the CLI
 * prints (tools/eval/detect.h det_feature_t; kinds G post foot, P pole
 * foot, X, T crossings) and the detection picture.  Host only.
 */
#ifndef FL_TOOLS_HLDETECT_H
#define FL_TOOLS_HLDETECT_H

#include "fieldloc/fieldloc.h"
#include "eval/detect.h"

/* True when a field is seed 002's (the tools pick the hl path for it). */
int hld_field_wants(const fl_field_t *field);

/* A state with the defaults for field (malloc'd; NULL when out of memory
 * or refused).  Free with free(). */
fl_hlv_t *hld_new(const fl_field_t *field);

/* One frame; the features (at most max) from the observations.  obs must
 * not be NULL.  Returns the number of features. */
int hld_run(fl_hlv_t *hv, const fl_image_t *img, const fl_camera_t *cam, fl_obs_list_t *obs,
            det_feature_t *out, int max);

/* Draw the last frame's stages over an RGB copy: the mask (light blue),
 * the skeleton (red), crossings, white points (black dots: projected back
 * to the image), posts (green box at the foot, the column range) and
 * poles (a box per band in the top band's colour). */
void hld_draw(const fl_hlv_t *hv, const fl_obs_list_t *obs, uint8_t *rgb, int width, int height,
              const fl_camera_t *cam);

#endif
