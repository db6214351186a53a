/*
 * src/model/calib.c - the calibration text (format and errors: calib.h).
 *
 * Algorithm: one pass over the lines; each line is checked for its length
 * and NUL bytes, its comment and trailing CR dropped, split into at most
 * three words (a third word is an error: every item has one or two), and
 * the first word looked up in the key table.  The words, the numbers
 * (saturated: a long digit string is "out of range", not an overflow;
 * degrees as microdegrees, |udeg| <= 45e6 here) and the angle conversions
 * both ways (exact round trip) are fieldloc/text.h's.
 * Memory: the caller's fl_calib_t; a few locals.  Cost: O(len).
 */
#include "fieldloc/calib.h"
#include "fieldloc/text.h"

#include <string.h>

typedef struct {
    fl_status_t status;
    const char *why;
} fl_calib_err_t;

static bool fl_calib_name_ok(const char *s, size_t n)
{
    size_t i;
    if (n == 0 || n >= FL_CALIB_NAME_MAX)
        return false;
    for (i = 0; i < n; i++) {
        char c = s[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '.' || c == '+' || c == '-'))
            return false;
    }
    return true;
}

static fl_calib_err_t fl_calib_fail(fl_status_t s, const char *why)
{
    fl_calib_err_t e;
    e.status = s;
    e.why = why;
    return e;
}

/* One item (words w[0..nw-1], nw >= 1) after the header. */
static fl_calib_err_t fl_calib_item(const fl_text_word_t *w, int nw, fl_calib_t *c)
{
    uint32_t bit;
    int64_t v = 0;
    if (fl_text_word_is(&w[0], "camera"))
        bit = FL_CALIB_HAS_CAMERA;
    else if (fl_text_word_is(&w[0], "neck_height_mm"))
        bit = FL_CALIB_HAS_NECK;
    else if (fl_text_word_is(&w[0], "pitch_offset_deg"))
        bit = FL_CALIB_HAS_PITCH;
    else if (fl_text_word_is(&w[0], "roll_offset_deg"))
        bit = FL_CALIB_HAS_ROLL;
    else if (fl_text_word_is(&w[0], "fieldloc-calibration"))
        return fl_calib_fail(FL_ERR_FORMAT, "repeated header");
    else
        return fl_calib_fail(FL_ERR_NOT_FOUND, "unknown key");
    if (nw != 2)
        return fl_calib_fail(FL_ERR_FORMAT, "expected: KEY VALUE");
    if (c->has & bit)
        return fl_calib_fail(FL_ERR_FORMAT, "repeated key");
    if (bit == FL_CALIB_HAS_CAMERA) {
        if (!fl_calib_name_ok(w[1].s, w[1].n))
            return fl_calib_fail(FL_ERR_FORMAT, "bad camera name (1..31 of A-Z a-z 0-9 _ . + -)");
        memcpy(c->camera, w[1].s, w[1].n);
        c->camera[w[1].n] = '\0';
    } else if (bit == FL_CALIB_HAS_NECK) {
        if (!fl_text_int(&w[1], &v))
            return fl_calib_fail(FL_ERR_FORMAT, "not an integer");
        if (v < FL_CAMERA_NECK_MIN_MM || v > FL_CAMERA_NECK_MAX_MM)
            return fl_calib_fail(FL_ERR_RANGE, "neck_height_mm out of range (50..2000)");
        c->neck_height_mm = (int32_t)v;
    } else {
        if (!fl_text_micro(&w[1], &v))
            return fl_calib_fail(FL_ERR_FORMAT, "not a number");
        if (v < -FL_CALIB_MAX_OFFSET_DEG * 1000000LL || v > FL_CALIB_MAX_OFFSET_DEG * 1000000LL)
            return fl_calib_fail(FL_ERR_RANGE, "angle out of range (-45..45 deg)");
        if (bit == FL_CALIB_HAS_PITCH)
            c->pitch_offset = fl_text_angle(v);
        else
            c->roll_offset = fl_text_angle(v);
    }
    c->has |= bit;
    return fl_calib_fail(FL_OK, "");
}

/* One line: header or item.  *seen_header tracks the header. */
static fl_calib_err_t fl_calib_line(const char *s, size_t n, bool *seen_header, fl_calib_t *c)
{
    fl_text_word_t w[3];
    int nw;
    int64_t ver = 0;
    const char *why;
    fl_status_t st = fl_text_line(s, n, FL_CALIB_LINE_MAX, &n, &why);
    if (st != FL_OK)
        return fl_calib_fail(st, why);
    nw = fl_text_split(s, n, w, 3);
    if (nw == 0)
        return fl_calib_fail(FL_OK, "");
    if (*seen_header)
        return nw > 2 ? fl_calib_fail(FL_ERR_FORMAT, "expected: KEY VALUE")
                      : fl_calib_item(w, nw, c);
    if (!fl_text_word_is(&w[0], "fieldloc-calibration"))
        return fl_calib_fail(FL_ERR_FORMAT, "missing header 'fieldloc-calibration 1'");
    if (nw != 2 || !fl_text_int(&w[1], &ver))
        return fl_calib_fail(FL_ERR_FORMAT, "expected: fieldloc-calibration VERSION");
    if (ver != 1)
        return fl_calib_fail(FL_ERR_RANGE, "unsupported version (1 only)");
    *seen_header = true;
    return fl_calib_fail(FL_OK, "");
}

fl_status_t fl_calib_parse(const char *text, size_t len, fl_calib_t *out, int32_t *err_line,
                           const char **why)
{
    fl_calib_err_t e = fl_calib_fail(FL_OK, "");
    size_t pos = 0;
    int32_t line = 0;
    bool seen_header = false;
    if (err_line != NULL)
        *err_line = 0;
    if (why != NULL)
        *why = "";
    if (out == NULL || (text == NULL && len > 0)) {
        if (why != NULL)
            *why = "null pointer";
        return FL_ERR_NULL;
    }
    memset(out, 0, sizeof *out);
    if (len > FL_CALIB_TEXT_MAX) {
        e = fl_calib_fail(FL_ERR_SIZE, "text too long");
    } else {
        while (pos < len) {
            const char *s = text + pos;
            size_t n = fl_text_find(s, len - pos, '\n');
            line++;
            e = fl_calib_line(s, n, &seen_header, out);
            if (e.status != FL_OK)
                break;
            pos += n + 1;
        }
        if (e.status == FL_OK && !seen_header) {
            line = 0;
            e = fl_calib_fail(FL_ERR_FORMAT, "missing header 'fieldloc-calibration 1'");
        }
    }
    if (e.status != FL_OK) {
        memset(out, 0, sizeof *out);
        if (err_line != NULL)
            *err_line = len > FL_CALIB_TEXT_MAX ? 0 : line;
        if (why != NULL)
            *why = e.why;
    }
    return e.status;
}

fl_status_t fl_calib_apply(const fl_calib_t *calib, fl_camera_pose_t *pose)
{
    if (calib == NULL || pose == NULL)
        return FL_ERR_NULL;
    if (calib->has & FL_CALIB_HAS_NECK)
        pose->neck_height_mm = calib->neck_height_mm;
    if (calib->has & FL_CALIB_HAS_PITCH)
        pose->pitch_offset = calib->pitch_offset;
    if (calib->has & FL_CALIB_HAS_ROLL)
        pose->roll_offset = calib->roll_offset;
    return FL_OK;
}

/* ---- writer ------------------------------------------------------------- */

size_t fl_calib_format(const fl_calib_t *calib, char *buf, size_t cap)
{
    fl_text_out_t o;
    const int32_t amax = (int32_t)(FL_CALIB_MAX_OFFSET_DEG * 65536L / 360);
    if (calib == NULL || buf == NULL || cap == 0)
        return 0;
    buf[0] = '\0';
    if (((calib->has & FL_CALIB_HAS_CAMERA) &&
         !fl_calib_name_ok(calib->camera, fl_text_len(calib->camera, FL_CALIB_NAME_MAX))) ||
        ((calib->has & FL_CALIB_HAS_NECK) && (calib->neck_height_mm < FL_CAMERA_NECK_MIN_MM ||
                                              calib->neck_height_mm > FL_CAMERA_NECK_MAX_MM)) ||
        ((calib->has & FL_CALIB_HAS_PITCH) &&
         (calib->pitch_offset < -amax || calib->pitch_offset > amax)) ||
        ((calib->has & FL_CALIB_HAS_ROLL) &&
         (calib->roll_offset < -amax || calib->roll_offset > amax)))
        return 0;
    fl_text_out_init(&o, buf, cap);
    fl_text_puts(&o, "fieldloc-calibration 1\n");
    if (calib->has & FL_CALIB_HAS_CAMERA) {
        fl_text_puts(&o, "camera ");
        fl_text_puts(&o, calib->camera);
        fl_text_puts(&o, "\n");
    }
    if (calib->has & FL_CALIB_HAS_NECK) {
        fl_text_puts(&o, "neck_height_mm ");
        fl_text_put_uint(&o, calib->neck_height_mm, 1);
        fl_text_puts(&o, "\n");
    }
    if (calib->has & FL_CALIB_HAS_PITCH) {
        fl_text_puts(&o, "pitch_offset_deg ");
        fl_text_put_deg(&o, calib->pitch_offset);
        fl_text_puts(&o, "\n");
    }
    if (calib->has & FL_CALIB_HAS_ROLL) {
        fl_text_puts(&o, "roll_offset_deg ");
        fl_text_put_deg(&o, calib->roll_offset);
        fl_text_puts(&o, "\n");
    }
    if (!o.ok) {
        buf[0] = '\0';
        return 0;
    }
    return o.n;
}
