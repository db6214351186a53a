/*
 * src/vision/coach_int.h - shared between the coach's files (coach.h):
 * coach.c (parameters, state, the frame's order of steps, reports),
 * coach_pixels.c (pixel access, a*, the class and background pass, Otsu),
 * coach_morph.c (bit-mask opening and closing), coach_regions.c (runs,
 * union-find, region sums), coach_foot.c (line, foot, sub-pixel row,
 * field point) and coach_tables.c (generated tables).
 */
#ifndef FIELDLOC_COACH_INT_H
#define FIELDLOC_COACH_INT_H

#include "fieldloc/coach.h"

/* Generated (tools/build/gen_coach_tables.py): sRGB -> linear, Q15, and
 * CIE f(t) at t = k / 1024 (k = 0..1025), Q15. */
extern const int32_t fl_coach_lin_q15[256];
extern const int32_t fl_coach_f_q15[1026];

/* Words per row of a mask of width w. */
static inline int32_t fl_coach_words(int32_t w) { return (w + 31) >> 5; }

/* R, G, B of pixel (u, v) of a validated view, (u, v) inside it. */
void fl_coach_int_rgb(const fl_image_t *img, int32_t u, int32_t v, uint8_t rgb[3]);
/* Row v of a validated view as packed R, G, B (w pixels). */
void fl_coach_int_row(const fl_image_t *img, int32_t v, uint8_t *rgb);

/* The frame pass: jersey masks, a* histogram, moved mask (when a
 * background is stored); img validated, of the state's size.  */
void fl_coach_int_pixels(fl_coach_t *c, const fl_image_t *img);
/* Store the background of a validated view (Y and a*). */
void fl_coach_int_store_background(fl_coach_t *c, const fl_image_t *img);

/* Runs and regions of the jersey masks (c->n_runs, c->n_regions). */
void fl_coach_int_regions(fl_coach_t *c, int32_t w, int32_t h, fl_coach_result_t *out);

/* The feet of the regions into out (largest jersey first). */
void fl_coach_int_feet(fl_coach_t *c, const fl_image_t *img, fl_coach_result_t *out);

#endif /* FIELDLOC_COACH_INT_H */
