/*
 * fieldloc/calib.h - a per-robot camera calibration as text, parsed and
 * written without files, heap or floating point (the firmware gets the text
 * from wherever it keeps it; `fieldloc calibrate --out` writes it).
 *
 * Format (one item per line, ASCII):
 *     fieldloc-calibration 1        header, the first item (version 1)
 *     camera NAME                   catalogue camera it was fitted for
 *     neck_height_mm N              head pitch axis above the ground, mm,
 *                                   integer FL_CAMERA_NECK_MIN_MM..MAX_MM
 *     pitch_offset_deg D            extra downward tilt, decimal degrees
 *     roll_offset_deg D             roll about the optical axis, decimal
 *                                   degrees (fl_camera_pose_t.roll_offset:
 *                                   positive = the camera's left side up,
 *                                   the image content turned counter-
 *                                   clockwise, camera.h)
 * D: optional sign, digits, optional '.' and up to 9 decimals; |D| <=
 * FL_CALIB_MAX_OFFSET_DEG; rounded to the nearest binary angle.  Every key
 * but the header is optional and may appear at most once; '#' starts a
 * comment (whole line or after an item); blank lines, spaces, tabs and a
 * CR before the LF are ignored.  Lines are at most FL_CALIB_LINE_MAX bytes
 * (without the LF), the text at most FL_CALIB_TEXT_MAX bytes.
 *
 * Errors (fl_calib_parse's status; *err_line = 1-based line, 0 when the
 * text as a whole is at fault):
 *     FL_ERR_NULL       text (with len > 0) or out NULL
 *     FL_ERR_SIZE       text longer than FL_CALIB_TEXT_MAX (line 0), or a
 *                       line longer than FL_CALIB_LINE_MAX
 *     FL_ERR_FORMAT     no header first (line of the first item; 0 for a
 *                       text without items), a bad number or name, a
 *                       missing or extra word, a repeated key, a NUL byte
 *     FL_ERR_NOT_FOUND  unknown key
 *     FL_ERR_RANGE      header version other than 1, a value out of range
 * *why (when why is not NULL) gets a static one-line reason ("unknown
 * key", "not a number", ...); out is all zero on any error.
 *
 * Memory: the caller's fl_calib_t.  Cost: one pass over the text.
 */
#ifndef FIELDLOC_CALIB_H
#define FIELDLOC_CALIB_H

#include "fieldloc/common.h"
#include "fieldloc/fixed.h"
#include "fieldloc/camera.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FL_CALIB_LINE_MAX 128      /* bytes per line, without the LF */
#define FL_CALIB_TEXT_MAX 4096     /* bytes of a whole calibration text */
#define FL_CALIB_NAME_MAX 32       /* camera name incl. the NUL */
#define FL_CALIB_MAX_OFFSET_DEG 45 /* |pitch_offset_deg|, |roll_offset_deg| */

/* Which keys a calibration holds. */
#define FL_CALIB_HAS_CAMERA 1u
#define FL_CALIB_HAS_NECK 2u
#define FL_CALIB_HAS_PITCH 4u
#define FL_CALIB_HAS_ROLL 8u

typedef struct {
    uint32_t has;                      /* FL_CALIB_HAS_* */
    char camera[FL_CALIB_NAME_MAX];    /* [A-Za-z0-9_.+-], "" when absent */
    int32_t neck_height_mm;
    fl_angle_t pitch_offset;
    fl_angle_t roll_offset;
} fl_calib_t;

/* Parse len bytes of text (no NUL terminator needed; a NUL inside is an
 * error).  FL_OK or an error as above. */
fl_status_t fl_calib_parse(const char *text, size_t len, fl_calib_t *out, int32_t *err_line,
                           const char **why);

/* Overwrite the pose fields the calibration holds: neck_height_mm,
 * pitch_offset, roll_offset (the head angles are left as they are).
 * FL_ERR_NULL on a NULL argument. */
fl_status_t fl_calib_apply(const fl_calib_t *calib, fl_camera_pose_t *pose);

/* Write calib as text in the format above (header, then the keys it holds,
 * angles with 6 decimals: the binary angle parses back exactly).  Returns
 * the length written (a NUL follows it), or 0 when cap is too small
 * (FL_CALIB_TEXT_MAX always suffices), an argument is NULL, or the
 * calibration holds an invalid name or out-of-range value. */
size_t fl_calib_format(const fl_calib_t *calib, char *buf, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_CALIB_H */
