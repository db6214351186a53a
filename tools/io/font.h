/*
 * tools/io/font.h - a built-in 5 x 7 pixel font (printable ASCII) for the
 * legends and captions of the tools' pictures.  No external dependency.
 * Glyphs are 5 x 7 above the baseline plus one descender row (g j p q y),
 * so FONT_H is 8.  Each character cell is FONT_ADVANCE x FONT_LINE pixels
 * at scale 1 (the glyph in its top-left corner, blank column and rows
 * around it).
 */
#ifndef FL_TOOLS_FONT_H
#define FL_TOOLS_FONT_H

#include "io/ppm.h"

#include <stdint.h>

#define FONT_W 5
#define FONT_H 8
#define FONT_ADVANCE 6
#define FONT_LINE 10

/* Row r (0 = top) of the glyph of c: bit 4 = leftmost pixel.  Characters
 * outside 32..126 draw as '?'. */
uint8_t font_row(char c, int r);
/* Width in pixels of s drawn at scale (1..8), without the trailing blank
 * column. */
int font_text_width(const char *s, int scale);
/* Draw s with its top-left corner at (x, y) in color rgb (pixels outside
 * the image are clipped).  Returns the x after the text. */
int font_draw(host_image_t *im, int x, int y, const char *s, const uint8_t *rgb, int scale);

#endif
