/*
 * src/vision/hlv_int.h - private parts of seed 002's vision path
 * (hlvision.h): the column scan for posts and poles (hlv_cols.c), the
 * white-surrounded-by-green mask (hlv_mask.c), the driver (hlv.c).
 */
#ifndef FIELDLOC_HLV_INT_H
#define FIELDLOC_HLV_INT_H

#include "fieldloc/hlvision.h"

/* Class bits of image pixel (u, v) inside a validated view. */
static inline uint8_t hlv_pixel_class(const fl_hlv_t *s, const fl_image_t *img, int32_t u,
                                      int32_t v)
{
    uint8_t p[3];
    fl_image_ycbcr_at(img, u, v, p);
    return fl_hlv_class(s, p[0], p[1], p[2]);
}

/* The class grid of the frame into s->cls (s->mask_w, mask_h set). */
void fl_hlv_int_classify(fl_hlv_t *s, const fl_image_t *img);

/* Posts and poles of the frame from the class grid into s->objects
 * (cleared first); sides of posts from their pairing or a crossbar (a few
 * pixel probes; a lone clipped post's is left UNKNOWN).  v_start: the
 * first image row that can see the ground, so feet above it are not
 * looked for.  Work: one pass over the grid. */
void fl_hlv_int_objects(fl_hlv_t *s, const fl_image_t *img, int32_t v_start);

/* The side of a lone post o from a crossbar of its colour beside its
 * top, probed 6, 8 and 10 times width_px beside it (its columns' width,
 * or for a clipped post the width its range gives); UNKNOWN when its top
 * is in the first grid row (maybe cut).  At most 12 pixel reads. */
fl_side_t fl_hlv_int_bar_side(const fl_hlv_t *s, const fl_image_t *img, const fl_hlv_object_t *o,
                              int32_t width_px);

/* The mask of white cells surrounded by green into s->mask from the
 * class grid, from grid row j0 down (above it: 0).  Work: two passes
 * over the grid. */
void fl_hlv_int_mask(fl_hlv_t *s, int32_t j0);

#endif /* FIELDLOC_HLV_INT_H */
