/*
 * tools/io/textfile.h - host-only helpers shared by the tools that read the
 * firmware's text formats (calibration, colours, frames lists, real-data
 * tables, sequences): a message into the caller's error buffer, a strict
 * number word, and a small file read whole for one of the firmware's
 * parsers.
 */
#ifndef FL_TOOLS_TEXTFILE_H
#define FL_TOOLS_TEXTFILE_H

#include <stddef.h>
#include <stdint.h>

/* printf into err; nothing when err is NULL or err_len <= 0. */
void tf_err(char *err, int err_len, const char *fmt, ...);

/* A strict number word: all of w read by strtod, finite, |v| <= lim.  NULL
 * with *v set, else "not a number" or "out of range" (overflow too). */
const char *tf_number(const char *w, double lim, double *v);

/* Up to cap bytes of path into buf, *n of them.  Given one byte more than
 * its format allows, a firmware parser refuses an overlong file itself.
 * 0, or -1 with "PATH: cannot open" in err. */
int tf_read(const char *path, char *buf, size_t cap, size_t *n, char *err, int err_len);

/* A firmware parser's refusal: "PATH:LINE: WHY", or "PATH: WHY" for line 0
 * (a fault of the whole text). */
void tf_parse_err(char *err, int err_len, const char *path, int32_t line, const char *why);

#endif
