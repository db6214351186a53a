/*
 * src/vision/corners_int.h - private to corners*.c: the steps of
 * fl_corners_run (corners.h) split over the detector (corners.c) and the
 * colour, label and pairing part (corners_feat.c).
 */
#ifndef FIELDLOC_CORNERS_INT_H
#define FIELDLOC_CORNERS_INT_H

#include "fieldloc/corners.h"

#define CN_MAGIC 0x434e5231u   /* "CNR1" */

/* Colour filter and label of one suppressed maximum k (x, y, var,
 * response set): fills k's counts and label; false when it does not come
 * from a white line (the corner is dropped). */
bool fl_corners_int_color_label(const fl_corners_t *c, const fl_image_t *img, const fl_color_table_t *colors,
                    const fl_camera_t *camera, fl_corner_t *k);

/* Pairing of c->corner[0..n_corners) into features, then the nets from
 * beacons (may be NULL); camera may be NULL. */
void fl_corners_int_pair(fl_corners_t *c, const fl_image_t *img, const fl_color_table_t *colors,
             const fl_camera_t *camera, const fl_beacon_t *beacons);

#endif /* FIELDLOC_CORNERS_INT_H */
