/*
 * tools/eval/scan_tool.h - host helpers around the column scanner (scan.h),
 * shared by `fieldloc scan` (tools/cli/cmd_scan.c), the benchmark
 * (tools/bench/bench_scan.c) and the tests (host_tests/test_scan.c): frame format
 * conversion, the picture, and scoring against a rendered frame's truth.
 */
#ifndef FL_TOOLS_SCAN_TOOL_H
#define FL_TOOLS_SCAN_TOOL_H

#include "fieldloc/fieldloc.h"
#include "world/render.h"

#include <stddef.h>

/* A frame in any pixel format, converted from RGB888 (malloc'd). */
typedef struct {
    int width, height;
    fl_pixel_format_t format;
    uint8_t *data;          /* packed rows (planar: Y, Cb, Cr planes) */
    size_t size;
    fl_image_t view;
} scantool_frame_t;

/* RGB888 (w x h, packed) -> format with the BT.601 integer conversion of
 * src/base/image.c; YUYV pairs take the rounded mean of the two pixels' Cb and
 * Cr.  0 on success (-1: bad size, odd width for YUYV, no memory). */
int scantool_frame_from_rgb(const uint8_t *rgb, int w, int h,
                            fl_pixel_format_t format, scantool_frame_t *out);
void scantool_frame_free(scantool_frame_t *f);

/* Picture of a scan over its frame (out: w*h*3): the frame dimmed to 40 %
 * above the border, white cells painted white, yellow cells yellow (cells
 * of a coarse grid fill their col_step x row_step block), green cells
 * kept, the border red, feet cyan. */
void scantool_picture(const fl_scan_t *s, const uint8_t *rgb, int w, int h,
                      uint8_t *out);

/* Score a scan of a rendered frame (accumulates into *e; zero it first).
 * Border: every grid column whose truth border_visible_v < height; error =
 * detected - truth (a missing border counts height - truth).  Pixels: grid
 * cells at or below the truth carpet edge border_v, robots and ball
 * excluded (a color class cannot tell a white robot from a line); truth
 * white = LINE, truth yellow = GOAL. */
typedef struct {
    long border_cols;
    long border_within3;
    double border_abs_sum;
    int border_max_abs;
    long white_tp, white_fp, white_fn;
    long yellow_tp, yellow_fp, yellow_fn;
} scantool_eval_t;
void scantool_evaluate(const fl_scan_t *s, const render_frame_t *fr,
                       scantool_eval_t *e);
double scantool_precision(long tp, long fp);   /* 1 when tp + fp = 0 */
double scantool_recall(long tp, long fn);      /* 1 when tp + fn = 0 */

/* Frame-level hue rotation of an RGB buffer by dh OpenCV hue units (2
 * degrees each), keeping S and V (for the lighting tests). */
void scantool_hue_shift(uint8_t *rgb, size_t n_pixels, int dh);

#endif
