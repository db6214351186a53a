/*
 * fieldloc/common.h - status codes and small types shared by every stage.
 *
 * Conventions (see docs/DESIGN.md, "Frames, units and fixed-point formats"):
 *   image    origin top-left, u right, v down, pixels
 *   robot    x forward, y left, millimetres
 *   field    origin at the centre, x toward the opponent goal, y left, mm,
 *            heading counter-clockwise
 *   angles   16-bit binary angles, 65536 per turn (fl_angle_t, fixed.h)
 *
 * Init functions validate and return an fl_status_t; per-frame functions
 * return counts and never fail (bad input gives an empty result).
 */
#ifndef FIELDLOC_COMMON_H
#define FIELDLOC_COMMON_H

#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    FL_OK = 0,
    FL_ERR_NULL = -1,      /* a required pointer was NULL */
    FL_ERR_SIZE = -2,      /* zero, negative or too large width/height */
    FL_ERR_STRIDE = -3,    /* stride smaller than one row of the format */
    FL_ERR_FORMAT = -4,    /* unknown pixel format, or a format constraint
                              (e.g. odd width for YUYV422) violated */
    FL_ERR_RANGE = -5,     /* a parameter outside its documented range */
    FL_ERR_NOT_FOUND = -6  /* a name not present in a catalogue */
} fl_status_t;

/* A point or vector in a metric frame (robot or field), millimetres. */
typedef struct {
    int32_t x_mm;
    int32_t y_mm;
} fl_point_t;

/* Human-readable name of a status code (static string, never NULL). */
const char *fl_status_str(fl_status_t s);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_COMMON_H */
