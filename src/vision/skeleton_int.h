/*
 * src/vision/skeleton_int.h - private: the working image's flags and the
 * helpers shared by skeleton.c (thinning) and skeleton_cross.c (nodes,
 * crossings, the sample).
 */
#ifndef FL_SKELETON_INT_H
#define FL_SKELETON_INT_H

#include "fieldloc/skeleton.h"

/* Flags of one working pixel (fl_skel_t.px). */
#define SK_WHITE  1u   /* white (mask, then skeleton) */
#define SK_LIST   2u   /* in the contour list */
#define SK_BORDER 4u   /* K3M phase 0 mark of this iteration */
#define SK_SEEN   8u   /* visited by a walk or a flood (cleared after) */
#define SK_NODE   16u  /* a listed node pixel (skeleton_cross.c) */

#define SK_MAGIC 0x736b656cu

/* Neighbourhood weight of working pixel i: bit 0 N, 1 NE, 2 E, 3 SE, 4 S,
 * 5 SW, 6 W, 7 NW (K3M's weights 1, 2, 4, ... 128 clockwise from N), kept
 * in s->wt: a pixel turning white sets its bit in its 8 neighbours'
 * weights, a deletion clears it (fl_skel_erase, skeleton.c). */
static inline uint32_t sk_weight(const fl_skel_t *s, uint32_t i)
{
    return s->wt[i];
}

/* Offsets of the 8 neighbours in weight-bit order, for a row stride ps. */
static inline void sk_offsets(int32_t ps, int32_t off[8])
{
    off[0] = -ps;     off[1] = -ps + 1; off[2] = 1;      off[3] = ps + 1;
    off[4] = ps;      off[5] = ps - 1;  off[6] = -1;     off[7] = -ps - 1;
}

/* Working pixel i becomes background; its neighbours' weights follow. */
void fl_skel_erase(fl_skel_t *s, uint32_t i);

/* Drop the pixels that are no longer white from the contour list and
 * clear their flags; clear the border marks of the others (skeleton.c). */
void fl_skel_compact(fl_skel_t *s);

/* K3M's final phase (A1pix), repeated while it deletes, at most
 * SK_ONE_PIXEL_PASSES passes (skeleton.c). */
#define SK_ONE_PIXEL_PASSES 4
void fl_skel_one_pixel(fl_skel_t *s);

/* Nodes, spur removal, crossings and the sample over the thinned image
 * (skeleton_cross.c). */
void fl_skel_find_crossings(fl_skel_t *s, uint32_t seed);

#endif /* FL_SKELETON_INT_H */
