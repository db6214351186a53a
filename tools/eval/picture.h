/*
 * tools/eval/picture.h - pictures of the localizer: the belief grid (cells
 * shaded by height, heading ticks, field lines, truth and estimate marked,
 * the frame's observations seen from the estimate) and camera frames with
 * the detected features (tools/eval/detect.h det_draw) and the field model
 * projected from the estimated pose.  Host only (malloc, double).
 *
 * Belief picture geometry: px_per_cell pixels per grid cell (clamped to
 * 2..32), so the picture is nx * px_per_cell wide and ny * px_per_cell high
 * (SPL 2013 at 8 px: 832 x 592); +x to the right, +y up (image rows go
 * down), the grid's corner (x0, y0) at the bottom left.
 * Colors: cells of height 0 dark green (carpet); height h > 0 on a ramp
 * from dark purple (small) through red and orange to pale yellow (1);
 * heading ticks (black, from the cell centre along the trapezoid centre,
 * length ~0.45 cell) on cells of height >= 1/4 whose core half-width is
 * below 45 degrees; field lines white; truth: cyan ring with a heading
 * line; estimate: magenta ring with a heading line (longer when more
 * reliable); observations: small white/black squares at the estimate
 * pose + (range, bearing).
 */
#ifndef FL_TOOLS_PICTURE_H
#define FL_TOOLS_PICTURE_H

#include "eval/detect.h"
#include "fieldloc/fieldloc.h"
#include "io/ppm.h"

#include <stdint.h>

typedef struct {
    double x_mm, y_mm, heading_deg;
} pic_pose_t;

/* Pixels per cell used when 0 is given. */
#define PIC_DEFAULT_PX_PER_CELL 8

/* Size of the belief picture of a localizer's state (localizer.h; its
 * belief_grid) (0 on success). */
int pic_belief_size(const fl_localizer_t *loc, const void *state, int px_per_cell,
                    int *width, int *height);

/* Draw the belief into a new image (out->rgb malloc'd; free with
 * host_image_free); field: the state's field (lines drawn).  truth, est,
 * obs may be NULL.  0 on success, -1 on a
 * NULL/uninitialized state, a localizer without belief_grid or out of
 * memory. */
int pic_belief(const fl_localizer_t *loc, const void *state, const fl_field_t *field,
               int px_per_cell,
               const pic_pose_t *truth, const fl_loc_estimate_t *est,
               const fl_obs_list_t *obs, host_image_t *out);

/* The frame with the last vision run of det drawn over it (det_draw) and,
 * when pose is not NULL, the field lines and circle projected from that
 * pose (dotted, yellow): what the localizer believes the camera sees.
 * scale 1..4 enlarges the frame (nearest neighbour) before drawing the
 * projection.  0 on success. */
int pic_frame(const det_ctx_t *det, const fl_image_t *img, const fl_camera_t *cam,
              const fl_field_t *field, const pic_pose_t *pose, int scale,
              host_image_t *out);

/* a and b side by side (top aligned, gap px of dark grey between). */
int pic_side_by_side(const host_image_t *a, const host_image_t *b, int gap,
                     host_image_t *out);

/* Write base.ppm, and base.png when png is 1 and the tools were built with
 * OpenCV.  Returns 0 when the PPM was written; *png_written (may be NULL)
 * tells about the PNG. */
int pic_save(const host_image_t *img, const char *base, int png, int *png_written);

#endif
