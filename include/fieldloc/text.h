/*
 * fieldloc/text.h - the pieces shared by the firmware's small text formats
 * (calib.h's calibration, color.h's colour classes): words of a line,
 * strict integer and decimal numbers, and a bounded output buffer.  No
 * heap, no floating point, no NUL terminators needed on input; every loop
 * is bounded by the lengths given.
 *
 * The conventions of those formats (one item per line, '#' comments,
 * blank lines, spaces / tabs between words, a CR before the LF ignored)
 * live here so that both read text the same way; the keys, limits and
 * error reasons are each format's own.
 *
 * Numbers: an optional sign, then digits (decimals: digits with an
 * optional '.' and at most 9 decimals, at least one digit in all); nothing
 * else, no blanks.  Magnitudes saturate at FL_TEXT_BIG, so an absurdly long
 * digit string reads as a large number (the format reports "out of
 * range"), never an overflow.
 */
#ifndef FIELDLOC_TEXT_H
#define FIELDLOC_TEXT_H

#include "fieldloc/common.h"
#include "fieldloc/fixed.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FL_TEXT_BIG 1000000000000LL  /* saturation of parsed numbers (10^12) */
#define FL_TEXT_LIT_MAX 256          /* longest literal fl_text_word_is and
                                        fl_text_puts read */

/* A word of a line: start and length. */
typedef struct {
    const char *s;
    size_t n;
} fl_text_word_t;

/* Index of the first c in s[0..n-1], n when none. */
size_t fl_text_find(const char *s, size_t n, char c);

/* Length of a NUL-terminated string of at most max bytes (max when no NUL). */
size_t fl_text_len(const char *s, size_t max);

/* One line (s[0..n-1], without its LF) made ready for splitting: FL_OK and
 * *used = the length before the comment and a trailing CR; FL_ERR_SIZE
 * ("line too long") when n > line_max; FL_ERR_FORMAT ("NUL byte") for a
 * NUL inside.  *why gets the reason (not NULL). */
fl_status_t fl_text_line(const char *s, size_t n, size_t line_max, size_t *used,
                         const char **why);

/* Split s[0..n-1] at spaces and tabs into at most max words; returns the
 * number found, at most max (max: there may be more). */
int fl_text_split(const char *s, size_t n, fl_text_word_t *w, int max);

/* Word equal to the literal lit. */
bool fl_text_word_is(const fl_text_word_t *w, const char *lit);

/* Decimal integer with optional sign, saturated at +-FL_TEXT_BIG.  False
 * when the word is not one. */
bool fl_text_int(const fl_text_word_t *w, int64_t *v);

/* Decimal number -> millionths (rounded half away from zero at the 7th
 * decimal; saturated at +-FL_TEXT_BIG).  False when not a number: no
 * digit, a stray character, or more than 9 decimals. */
bool fl_text_micro(const fl_text_word_t *w, int64_t *micro);

/* Microdegrees (|udeg| <= 180e6) -> binary angle, rounded to nearest. */
fl_angle_t fl_text_angle(int64_t udeg);

/* ---- output -------------------------------------------------------------- */

/* Bounded writer into buf[0..cap-1], always NUL-terminated; ok turns false
 * (and stays) when something did not fit. */
typedef struct {
    char *buf;
    size_t cap, n;
    bool ok;
} fl_text_out_t;

/* Start writing (buf NULL or cap 0: ok false from the start). */
void fl_text_out_init(fl_text_out_t *o, char *buf, size_t cap);
void fl_text_put(fl_text_out_t *o, const char *s, size_t n);
/* s: a literal or a checked string (NUL within FL_TEXT_LIT_MAX). */
void fl_text_puts(fl_text_out_t *o, const char *s);
/* Non-negative v with at least min_digits digits. */
void fl_text_put_uint(fl_text_out_t *o, int64_t v, int min_digits);
/* Binary angle as decimal degrees with 6 decimals: round(a * 360e6 /
 * 65536) microdegrees, which fl_text_micro + fl_text_angle read back to
 * the same angle (one unit is 5493 microdegrees). */
void fl_text_put_deg(fl_text_out_t *o, fl_angle_t a);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_TEXT_H */
