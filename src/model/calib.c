/*
 * src/model/calib.c - the calibration text (format and errors: calib.h).
 *
 * Algorithm: one pass over the lines; each line is checked for its length
 * and NUL bytes, its comment and trailing CR dropped, split into at most
 * three words (a third word is an error: every item has one or two), and
 * the first word looked up in the key table.  Numbers are parsed with
 * saturation (a long digit string is "out of range", not an overflow):
 * integers as int64 capped at 10^12, degrees as int64 microdegrees (up to 9
 * decimals read, rounded to 6), converted to binary angles by
 * round(udeg * 65536 / 360e6) in int64 (|udeg| <= 45e6 here, so the
 * product stays below 2^42).  The writer prints round(a * 360e6 / 65536)
 * microdegrees, which converts back to the same binary angle because one
 * unit is 5493 microdegrees (the rounding error 0.5 udeg is far below half
 * a unit).
 * Memory: the caller's fl_calib_t; a few locals.  Cost: O(len).
 */
#include "fieldloc/calib.h"

#include <string.h>

#define FL_CALIB_UDEG_TURN 360000000LL
#define FL_CALIB_BIG 1000000000000LL /* saturation of parsed numbers */

/* A word of a line: start and length. */
typedef struct {
    const char *s;
    size_t n;
} fl_calib_word_t;

typedef struct {
    fl_status_t status;
    const char *why;
} fl_calib_err_t;

/* Index of the first c in s[0..n-1], n when none (libc's memchr is not
 * among the functions the firmware may call). */
static size_t fl_calib_find(const char *s, size_t n, char c)
{
    size_t i = 0;
    while (i < n && s[i] != c)
        i++;
    return i;
}

/* Length of a NUL-terminated string of at most max bytes (max when no NUL). */
static size_t fl_calib_len(const char *s, size_t max) { return fl_calib_find(s, max, '\0'); }

static bool fl_calib_is_space(char c) { return c == ' ' || c == '\t'; }

static bool fl_calib_word_is(const fl_calib_word_t *w, const char *lit)
{
    size_t n = fl_calib_len(lit, FL_CALIB_LINE_MAX);
    return w->n == n && memcmp(w->s, lit, n) == 0;
}

/* Decimal integer with optional sign; saturates at FL_CALIB_BIG.  False
 * when the word is not a number. */
static bool fl_calib_int(const fl_calib_word_t *w, int64_t *v)
{
    size_t i = 0;
    int64_t x = 0;
    bool neg = false;
    if (w->n > 0 && (w->s[0] == '-' || w->s[0] == '+')) {
        neg = w->s[0] == '-';
        i = 1;
    }
    if (i == w->n)
        return false;
    for (; i < w->n; i++) {
        char c = w->s[i];
        if (c < '0' || c > '9')
            return false;
        if (x < FL_CALIB_BIG)
            x = x * 10 + (c - '0');
    }
    *v = neg ? -x : x;
    return true;
}

/* Decimal degrees -> microdegrees (rounded half away from zero at the 7th
 * decimal, saturated at FL_CALIB_BIG).  False when not a number: no digit,
 * a stray character, or more than 9 decimals. */
static bool fl_calib_udeg(const fl_calib_word_t *w, int64_t *udeg)
{
    size_t i = 0;
    int64_t ip = 0, frac = 0; /* frac: 9 decimals */
    int nd = 0, nf = 0;
    bool neg = false;
    if (w->n > 0 && (w->s[0] == '-' || w->s[0] == '+')) {
        neg = w->s[0] == '-';
        i = 1;
    }
    for (; i < w->n && w->s[i] >= '0' && w->s[i] <= '9'; i++, nd++)
        if (ip < FL_CALIB_BIG)
            ip = ip * 10 + (w->s[i] - '0');
    if (i < w->n && w->s[i] == '.') {
        for (i++; i < w->n && w->s[i] >= '0' && w->s[i] <= '9'; i++, nf++) {
            if (nf >= 9)
                return false;
            frac = frac * 10 + (w->s[i] - '0');
        }
    }
    if (i != w->n || nd + nf == 0)
        return false;
    for (; nf < 9; nf++)
        frac *= 10;
    if (ip >= FL_CALIB_BIG / 1000000)
        *udeg = FL_CALIB_BIG;
    else
        *udeg = ip * 1000000 + (frac + 500) / 1000;
    if (neg)
        *udeg = -*udeg;
    return true;
}

/* Microdegrees (|udeg| <= 180e6) -> binary angle, rounded to nearest. */
static fl_angle_t fl_calib_angle(int64_t udeg)
{
    int64_t p = udeg * 65536;
    int64_t a = p >= 0 ? (p + FL_CALIB_UDEG_TURN / 2) / FL_CALIB_UDEG_TURN
                       : -((-p + FL_CALIB_UDEG_TURN / 2) / FL_CALIB_UDEG_TURN);
    return fl_angle_wrap((int32_t)a);
}

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
static fl_calib_err_t fl_calib_item(const fl_calib_word_t *w, int nw, fl_calib_t *c)
{
    uint32_t bit;
    int64_t v = 0;
    if (fl_calib_word_is(&w[0], "camera"))
        bit = FL_CALIB_HAS_CAMERA;
    else if (fl_calib_word_is(&w[0], "neck_height_mm"))
        bit = FL_CALIB_HAS_NECK;
    else if (fl_calib_word_is(&w[0], "pitch_offset_deg"))
        bit = FL_CALIB_HAS_PITCH;
    else if (fl_calib_word_is(&w[0], "roll_offset_deg"))
        bit = FL_CALIB_HAS_ROLL;
    else if (fl_calib_word_is(&w[0], "fieldloc-calibration"))
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
        if (!fl_calib_int(&w[1], &v))
            return fl_calib_fail(FL_ERR_FORMAT, "not an integer");
        if (v < FL_CAMERA_NECK_MIN_MM || v > FL_CAMERA_NECK_MAX_MM)
            return fl_calib_fail(FL_ERR_RANGE, "neck_height_mm out of range (50..2000)");
        c->neck_height_mm = (int32_t)v;
    } else {
        if (!fl_calib_udeg(&w[1], &v))
            return fl_calib_fail(FL_ERR_FORMAT, "not a number");
        if (v < -FL_CALIB_MAX_OFFSET_DEG * 1000000LL || v > FL_CALIB_MAX_OFFSET_DEG * 1000000LL)
            return fl_calib_fail(FL_ERR_RANGE, "angle out of range (-45..45 deg)");
        if (bit == FL_CALIB_HAS_PITCH)
            c->pitch_offset = fl_calib_angle(v);
        else
            c->roll_offset = fl_calib_angle(v);
    }
    c->has |= bit;
    return fl_calib_fail(FL_OK, "");
}

/* Split a line (comment and CR already cut) into words; at most 3 kept,
 * the count returned (up to 3: 3 means "too many"). */
static int fl_calib_split(const char *s, size_t n, fl_calib_word_t w[3])
{
    size_t i = 0;
    int nw = 0;
    while (i < n && nw < 3) {
        size_t b;
        while (i < n && fl_calib_is_space(s[i]))
            i++;
        if (i == n)
            break;
        b = i;
        while (i < n && !fl_calib_is_space(s[i]))
            i++;
        w[nw].s = s + b;
        w[nw].n = i - b;
        nw++;
    }
    return nw;
}

/* One line: header or item.  *seen_header tracks the header. */
static fl_calib_err_t fl_calib_line(const char *s, size_t n, bool *seen_header, fl_calib_t *c)
{
    fl_calib_word_t w[3];
    int nw;
    int64_t ver = 0;
    if (n > FL_CALIB_LINE_MAX)
        return fl_calib_fail(FL_ERR_SIZE, "line too long");
    if (fl_calib_find(s, n, '\0') < n)
        return fl_calib_fail(FL_ERR_FORMAT, "NUL byte");
    n = fl_calib_find(s, n, '#');
    if (n > 0 && s[n - 1] == '\r')
        n--;
    nw = fl_calib_split(s, n, w);
    if (nw == 0)
        return fl_calib_fail(FL_OK, "");
    if (*seen_header)
        return nw > 2 ? fl_calib_fail(FL_ERR_FORMAT, "expected: KEY VALUE")
                      : fl_calib_item(w, nw, c);
    if (!fl_calib_word_is(&w[0], "fieldloc-calibration"))
        return fl_calib_fail(FL_ERR_FORMAT, "missing header 'fieldloc-calibration 1'");
    if (nw != 2 || !fl_calib_int(&w[1], &ver))
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
            size_t n = fl_calib_find(s, len - pos, '\n');
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

typedef struct {
    char *buf;
    size_t cap, n;
    bool ok;
} fl_calib_out_t;

static void fl_calib_put(fl_calib_out_t *o, const char *s, size_t n)
{
    if (!o->ok || o->n + n + 1 > o->cap) {
        o->ok = false;
        return;
    }
    memcpy(o->buf + o->n, s, n);
    o->n += n;
    o->buf[o->n] = '\0';
}

/* s: a literal or a checked camera name (NUL within FL_CALIB_NAME_MAX). */
static void fl_calib_puts(fl_calib_out_t *o, const char *s)
{
    fl_calib_put(o, s, fl_calib_len(s, FL_CALIB_LINE_MAX));
}

/* Non-negative v with at least min_digits digits. */
static void fl_calib_put_uint(fl_calib_out_t *o, int64_t v, int min_digits)
{
    char d[24];
    int n = 0;
    while ((v > 0 || n < min_digits) && n < (int)sizeof d) {
        d[sizeof d - 1 - (size_t)n] = (char)('0' + (int)(v % 10));
        v /= 10;
        n++;
    }
    fl_calib_put(o, d + sizeof d - (size_t)n, (size_t)n);
}

static void fl_calib_put_deg(fl_calib_out_t *o, fl_angle_t a)
{
    int64_t p = (int64_t)a * FL_CALIB_UDEG_TURN;
    int64_t u = p >= 0 ? (p + 32768) / 65536 : -((-p + 32768) / 65536);
    if (u < 0) {
        fl_calib_puts(o, "-");
        u = -u;
    }
    fl_calib_put_uint(o, u / 1000000, 1);
    fl_calib_puts(o, ".");
    fl_calib_put_uint(o, u % 1000000, 6);
}

size_t fl_calib_format(const fl_calib_t *calib, char *buf, size_t cap)
{
    fl_calib_out_t o;
    const int32_t amax = (int32_t)(FL_CALIB_MAX_OFFSET_DEG * 65536L / 360);
    if (calib == NULL || buf == NULL || cap == 0)
        return 0;
    buf[0] = '\0';
    if (((calib->has & FL_CALIB_HAS_CAMERA) &&
         !fl_calib_name_ok(calib->camera, fl_calib_len(calib->camera, FL_CALIB_NAME_MAX))) ||
        ((calib->has & FL_CALIB_HAS_NECK) && (calib->neck_height_mm < FL_CAMERA_NECK_MIN_MM ||
                                              calib->neck_height_mm > FL_CAMERA_NECK_MAX_MM)) ||
        ((calib->has & FL_CALIB_HAS_PITCH) &&
         (calib->pitch_offset < -amax || calib->pitch_offset > amax)) ||
        ((calib->has & FL_CALIB_HAS_ROLL) &&
         (calib->roll_offset < -amax || calib->roll_offset > amax)))
        return 0;
    o.buf = buf;
    o.cap = cap;
    o.n = 0;
    o.ok = true;
    fl_calib_puts(&o, "fieldloc-calibration 1\n");
    if (calib->has & FL_CALIB_HAS_CAMERA) {
        fl_calib_puts(&o, "camera ");
        fl_calib_puts(&o, calib->camera);
        fl_calib_puts(&o, "\n");
    }
    if (calib->has & FL_CALIB_HAS_NECK) {
        fl_calib_puts(&o, "neck_height_mm ");
        fl_calib_put_uint(&o, calib->neck_height_mm, 1);
        fl_calib_puts(&o, "\n");
    }
    if (calib->has & FL_CALIB_HAS_PITCH) {
        fl_calib_puts(&o, "pitch_offset_deg ");
        fl_calib_put_deg(&o, calib->pitch_offset);
        fl_calib_puts(&o, "\n");
    }
    if (calib->has & FL_CALIB_HAS_ROLL) {
        fl_calib_puts(&o, "roll_offset_deg ");
        fl_calib_put_deg(&o, calib->roll_offset);
        fl_calib_puts(&o, "\n");
    }
    if (!o.ok) {
        buf[0] = '\0';
        return 0;
    }
    return o.n;
}
