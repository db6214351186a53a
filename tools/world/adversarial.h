/*
 * tools/world/adversarial.h - hostile frames for the robustness tests and the
 * worst-case timing: all green, all white, all yellow, black,
 * saturated, random noise, checkerboards of line-width and single-pixel
 * squares, stripes; any size, any format, any row padding.
 */
#ifndef FL_TOOLS_ADVERSARIAL_H
#define FL_TOOLS_ADVERSARIAL_H

#include "fieldloc/camera.h"
#include "fieldloc/image.h"

typedef enum { ADV_GREEN, ADV_WHITE, ADV_YELLOW, ADV_BLACK, ADV_SATURATED, ADV_NOISE,
               ADV_CHECKER_LINE, ADV_CHECKER_PIXEL, ADV_STRIPES, ADV_COUNT } adv_kind_t;

const char *adv_name(adv_kind_t k);

/* Build a frame of kind k, w x h, format f, rows padded by pad bytes
 * (stride > width); returns the malloc'd buffer (free it) and fills the
 * view and the status of its validation (odd YUYV widths are rejected). */
uint8_t *adv_frame(adv_kind_t k, int w, int h, fl_pixel_format_t f, int pad,
                   fl_image_t *img, fl_status_t *st);

/* A camera model for a frame of w x h: base as a sensor scaled by the
 * larger of w / width_px and h / height_px and cropped to w x h (focal
 * length scaled by that ratio, at least 1/16 px; the principal point at
 * the same relative place), name kept.  fl_vision_frame refuses a frame
 * whose size is not its camera model's, so frames of any size need their
 * own model.  w or h below 1: base unchanged. */
void adv_camera_model(const fl_camera_model_t *base, int w, int h, fl_camera_model_t *out);

/* The vision fuzz harnesses' frame from their input's first 9 bytes
 *   [0] format (mod 4: 0 a hand-made view of garbage geometry, 1 RGB888,
 *   2 YUYV422, 3 planar), [1..2] width, [3..4] height (little end first,
 *   taken mod 700), [5] stride padding, [6] camera index (bits 0-6; bit 7
 *   set: the catalogue model as it is, usually of another size than the
 *   frame: the refusal path; clear: that model rescaled to the frame,
 *   adv_camera_model), [7..8] head pitch
 * and the bytes after the header_len header bytes as pixels, repeated to
 * fill the frame (none: zeros); size >= header_len >= 9.  The head yaw is
 * head_yaw; *cam is zeroed (a camera that projects nothing) when the
 * camera refuses the model or the pose.  Returns the malloc'd buffer
 * behind *img (free it), NULL when out of memory. */
/* The fuzz harnesses' view of buf (at least (3 w + pad + 1) (h + 1) 3
 * bytes): fmt 1 RGB888 (stride 3 w + pad), 2 YUYV422 (2 w + pad), 3
 * planar (three planes of stride w + pad), else a hand-made view of
 * garbage geometry (format garbage % 5, stride pad).  The packed and
 * planar views are whatever fl_image_init_* makes of the sizes (a refused
 * one stays refused). */
void adv_fuzz_view(fl_image_t *img, int fmt, uint8_t *buf, int32_t w, int32_t h, int32_t pad,
                   uint8_t garbage);

uint8_t *adv_fuzz_frame(const uint8_t *data, size_t size, size_t header_len, fl_angle_t head_yaw,
                        fl_image_t *img, fl_camera_t *cam);

#endif
