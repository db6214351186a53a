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
 *
 * A localizer whose belief is a set of samples (belief_samples > 0, no
 * belief_grid) gets the same picture geometry (the grid the fuzzy
 * localizer would have on that field's carpet: same size and scale) with,
 * on the carpet, every sample as a dot with a heading tick (0.9 cell
 * long; pic_belief_zoom: a little longer in pixels, shorter in mm) shaded by its relative weight: in the estimate's cluster (in_mode)
 * on the grid's ramp from dark magenta (light) to pale yellow (heaviest),
 * the others in blues (dark: light, pale: heavy); drawn lightest first;
 * then the cluster's spread, the estimate's 2-sd ellipse (lime, dotted),
 * and the same lines, observations, truth and estimate.
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

/* The same for any localizer: a sample localizer's picture needs the
 * field (its carpet gives the geometry).  pic_belief_size refuses it. */
int pic_belief_size_on(const fl_localizer_t *loc, const void *state, const fl_field_t *field,
                       int px_per_cell, int *width, int *height);

/* The legend set of the belief picture of this state: PIC_LEGEND_PARTICLES
 * for a sample localizer, PIC_LEGEND_BELIEF otherwise. */
unsigned pic_belief_legend(const fl_localizer_t *loc, const void *state);

/* Color of a sample of relative weight w (0..1), in the estimate's
 * cluster or not (the legend's swatches use it). */
void pic_particle_color(double w, int in_mode, uint8_t *c);

/* Draw the belief into a new image (out->rgb malloc'd; free with
 * host_image_free); field: the state's field (lines drawn).  truth, est,
 * obs may be NULL.  0 on success, -1 on a
 * NULL/uninitialized state, a localizer with neither a grid nor samples,
 * or out of memory. */
int pic_belief(const fl_localizer_t *loc, const void *state, const fl_field_t *field,
               int px_per_cell,
               const pic_pose_t *truth, const fl_loc_estimate_t *est,
               const fl_obs_list_t *obs, host_image_t *out);

/* A sample localizer's belief magnified: a size_px square centred on
 * (cx, cy) at px_per_cell pixels per 100 mm cell (0: 4 x the default, 32;
 * clamped to 2..128), drawn as pic_belief draws it (particles, cluster,
 * lines, truth, estimate, observations) with a grey frame and its scale
 * written in the top left corner.  0 on success; -1 for a grid localizer
 * (its picture shows the cells already), no samples, size_px outside
 * 32..4096 or out of memory. */
int pic_belief_zoom(const fl_localizer_t *loc, const void *state, const fl_field_t *field,
                    int32_t cx_mm, int32_t cy_mm, int px_per_cell, int size_px,
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

/* ---- legends ------------------------------------------------------------------
 * Every picture the CLI writes carries a legend in a strip added BELOW the
 * image (never over data): optional caption lines (time, error,
 * reliability...), then one swatch + text per mark, wrapped to the width.
 * The text uses the built-in 5 x 7 font (tools/io/font.h), light grey on
 * PIC_LEGEND_BG.  An item two sets share (same mark, color and text) is
 * shown once.  The sets name the marks of each drawing function: */
#define PIC_LEGEND_DETECT  0x01u  /* det_draw: points, segments, crossings, posts, circle */
#define PIC_LEGEND_MODEL   0x02u  /* pic_frame: the field model seen from the estimate */
#define PIC_LEGEND_BELIEF  0x04u  /* pic_belief: shading, ticks, truth, estimate, obs */
#define PIC_LEGEND_CLASSES 0x08u  /* pic_scan_overlay classes: the scanner's class map */
#define PIC_LEGEND_BORDER  0x10u  /* pic_scan_overlay border: border and search start */
#define PIC_LEGEND_SCAN    0x20u  /* scantool_picture */
#define PIC_LEGEND_EVAL    0x40u  /* eval-detect: truth rings */
#define PIC_LEGEND_MASK    0x80u  /* render --mask: the renderer's pixel classes */
#define PIC_LEGEND_TRUTH   0x100u /* pic_belief with a truth pose: its ring */
#define PIC_LEGEND_PARTICLES 0x200u /* pic_belief of samples (instead of _BELIEF):
                                       carpet, particles, cluster, lines, estimate,
                                       obs */
#define PIC_LEGEND_HLV     0x400u /* hld_draw: seed 002's mask, skeleton, posts, poles */

/* Strip background; the caption and labels are drawn in PIC_LEGEND_FG. */
#define PIC_LEGEND_BG 24
#define PIC_LEGEND_FG 230

/* Legend strip height for an image of this width (same layout as
 * pic_add_legend). */
int pic_legend_height(int width, unsigned sets, const char *caption);

/* out = img with the legend strip of sets below it; caption (may be NULL;
 * '\n' separates lines, long lines wrap at spaces) first.  0 on success. */
int pic_add_legend(const host_image_t *img, unsigned sets, const char *caption,
                   host_image_t *out);

/* The same, replacing *img (freed) by the picture with its legend. */
int pic_legend_inplace(host_image_t *img, unsigned sets, const char *caption);

/* Caption of a belief picture: time (t_s < 0: unknown) and frame number
 * (frame < 0: unknown), the estimate with its reliability, and, when
 * err_mm >= 0, the position and heading error to the truth. */
void pic_belief_caption(char *buf, size_t n, double t_s, long frame,
                        const fl_loc_estimate_t *est, double err_mm, double err_deg);

/* Draw the scanner's result over an RGB image of its frame: with classes,
 * every grid cell tinted by its class (green, white, yellow; other dimmed);
 * with border, the field border per grid column (red line) and, when the
 * search started below row 0, the first searched row (dotted white). */
void pic_scan_overlay(const fl_scan_t *s, uint8_t *rgb, int w, int h, int classes,
                      int border);

/* Write base.ppm, and base.png when png is 1 (tools/io/png.c).  Returns 0
 * when the PPM was written; *png_written (may be NULL) tells about the PNG. */
int pic_save(const host_image_t *img, const char *base, int png, int *png_written);

#endif
