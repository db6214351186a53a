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
 *
 * Configuration check.  Every public init (fl_camera_init, fl_color_init,
 * fl_scan_init, fl_lines_init, fl_crossings_init, fl_beacon_init,
 * fl_vision_init, fl_fuzzy_init, fl_loc_init and a localizer's init
 * pointer) is a static inline wrapper that passes the caller's
 * FL_CONFIG_FINGERPRINT (config.h, as the caller's compiler saw it) to the
 * library's fl_*_init_cfg; a fingerprint other than the library's gives
 * FL_ERR_CONFIG and writes nothing to the caller's object (its layout is
 * not the library's, so no write into it would be safe; fl_loc_init is the
 * exception: the localizer's state has the library's size, and is left
 * empty as after any other init error).  Call the wrappers; the _cfg
 * functions are for the wrappers only.
 */
#ifndef FIELDLOC_COMMON_H
#define FIELDLOC_COMMON_H

#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>

#include "fieldloc/config.h"

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
    FL_ERR_NOT_FOUND = -6, /* a name not present in a catalogue */
    FL_ERR_CONFIG = -7,    /* the caller was compiled with other config.h
                              values (or headers of another layout
                              version) than the library: FL_CONFIG_
                              FINGERPRINT differs */
    FL_ERR_MISMATCH = -8,  /* a frame whose size differs from the camera
                              model's width_px x height_px */
    FL_ERR_CAMERA = -9,    /* a camera that is not initialized (its
                              fl_camera_init failed or never ran) */
    FL_ERR_STALE = -10,    /* a report older than its limit (obs.h) */
    FL_ERR_STATE = -11     /* a localizer state that is not initialized
                              (its init failed or never ran) */
} fl_status_t;

/* A point or vector in a metric frame (robot or field), millimetres. */
typedef struct {
    int32_t x_mm;
    int32_t y_mm;
} fl_point_t;

/* Human-readable name of a status code (static string, never NULL). */
const char *fl_status_str(fl_status_t s);

/* The library's own FL_CONFIG_FINGERPRINT and FL_VERSION_STRING (config.h)
 * as it was compiled: a caller may compare them with its own. */
uint32_t fl_config_fingerprint(void);
const char *fl_version(void);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_COMMON_H */
