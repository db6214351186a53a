/* tools/io/textfile.c - error messages, number words and whole small files
 * (textfile.h). */
#include "io/textfile.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

void tf_err(char *err, int err_len, const char *fmt, ...)
{
    va_list ap;
    if (!err || err_len <= 0)
        return;
    va_start(ap, fmt);
    vsnprintf(err, (size_t)err_len, fmt, ap);
    va_end(ap);
}

const char *tf_number(const char *w, double lim, double *v)
{
    char *end;
    double d;
    errno = 0;
    d = strtod(w, &end);
    if (end == w || *end != '\0')
        return "not a number";
    if (errno == ERANGE || !isfinite(d) || fabs(d) > lim)
        return "out of range";
    *v = d;
    return NULL;
}

int tf_read(const char *path, char *buf, size_t cap, size_t *n, char *err, int err_len)
{
    FILE *fp = fopen(path, "rb");
    *n = 0;
    if (!fp) {
        tf_err(err, err_len, "%s: cannot open", path);
        return -1;
    }
    *n = fread(buf, 1, cap, fp);
    fclose(fp);
    return 0;
}

void tf_parse_err(char *err, int err_len, const char *path, int32_t line, const char *why)
{
    if (line > 0)
        tf_err(err, err_len, "%s:%d: %s", path, (int)line, why);
    else
        tf_err(err, err_len, "%s: %s", path, why);
}
