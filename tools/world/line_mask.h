/*
 * tools/world/line_mask.h - binary masks of painted lines for the skeleton
 * stage's tests, fuzz harness and benchmark (skeleton.h): thick segments
 * (capsules), ragged edges, and a field-like view (a perspective line
 * pattern with a crossing, T's and a centre circle).  Host only (double).
 * A mask is one byte per pixel, 1 white, 0 background.
 */
#ifndef FL_TOOLS_LINE_MASK_H
#define FL_TOOLS_LINE_MASK_H

#include <stdint.h>

/* Paint the segment (x0, y0)-(x1, y1) with half width hw0 at its start and
 * hw1 at its end (pixels whose centre lies within the interpolated half
 * width of the segment). */
void lm_segment(uint8_t *m, int w, int h, int stride, double x0, double y0,
                double x1, double y1, double hw0, double hw1);

/* Paint an ellipse outline (centre, radii, half width of the band). */
void lm_ellipse(uint8_t *m, int w, int h, int stride, double cx, double cy,
                double rx, double ry, double hw);

/* Raggedness: every background pixel 4-adjacent to white becomes white,
 * and every white pixel 4-adjacent to background becomes background, each
 * with probability pct / 100 (seeded, deterministic). */
void lm_ragged(uint8_t *m, int w, int h, int stride, uint32_t seed, int pct);

/* A field-like view at w x h: the lines of a field half seen from a
 * standing robot (a touch line, the halfway line meeting it in a T, the
 * centre circle crossed by the halfway line, a penalty-area T and corner),
 * half widths shrinking toward the horizon.  Returns the white pixels. */
int lm_field_view(uint8_t *m, int w, int h, int stride);

#endif /* FL_TOOLS_LINE_MASK_H */
