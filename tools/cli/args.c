/* tools/cli/args.c - checked numeric options (args.h). */
#include "cli/args.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ARG_PI 3.14159265358979323846

/* A bound as the user would write it: integers without decimals. */
static void arg_fmt(char *buf, size_t n, double x)
{
    if (fabs(x) < 1e15 && x == floor(x))
        snprintf(buf, n, "%.0f", x);
    else
        snprintf(buf, n, "%.4g", x);
}

static void arg_range_msg(const char *cmd, const char *opt, const char *text, double lo,
                          double hi, const char *unit)
{
    char a[32], b[32];
    arg_fmt(a, sizeof a, lo);
    arg_fmt(b, sizeof b, hi);
    fprintf(stderr, "fieldloc %s: %s: %s is out of range %s..%s%s%s\n", cmd, opt, text, a, b,
            unit ? " " : "", unit ? unit : "");
}

/* Text that strtol / strtod would read with a leading blank or nothing. */
static int arg_blank(const char *text)
{
    return text == NULL || text[0] == '\0' || isspace((unsigned char)text[0]);
}

int arg_long(const char *cmd, const char *opt, const char *text, long lo, long hi,
             const char *unit, long *out)
{
    char *end;
    long v;
    if (arg_blank(text)) {
        fprintf(stderr, "fieldloc %s: %s: \"%s\" is not a number\n", cmd, opt, text ? text : "");
        return -1;
    }
    errno = 0;
    v = strtol(text, &end, 10);
    if (end == text || (*end != '\0' && *end != '.' && *end != 'e' && *end != 'E')) {
        fprintf(stderr, "fieldloc %s: %s: \"%s\" is not a number\n", cmd, opt, text);
        return -1;
    }
    if (*end != '\0') {
        (void)strtod(text, &end);
        fprintf(stderr, "fieldloc %s: %s: \"%s\" is not %s\n", cmd, opt, text,
                *end == '\0' ? "an integer" : "a number");
        return -1;
    }
    if (errno == ERANGE || v < lo || v > hi) {
        arg_range_msg(cmd, opt, text, (double)lo, (double)hi, unit);
        return -1;
    }
    *out = v;
    return 0;
}

int arg_int(const char *cmd, const char *opt, const char *text, int lo, int hi,
            const char *unit, int *out)
{
    long v;
    if (arg_long(cmd, opt, text, lo, hi, unit, &v) != 0)
        return -1;
    *out = (int)v;
    return 0;
}

int arg_int32(const char *cmd, const char *opt, const char *text, int32_t lo, int32_t hi,
              const char *unit, int32_t *out)
{
    long v;
    if (arg_long(cmd, opt, text, lo, hi, unit, &v) != 0)
        return -1;
    *out = (int32_t)v;
    return 0;
}

int arg_u32(const char *cmd, const char *opt, const char *text, uint32_t *out)
{
    long long v;
    char *end;
    if (arg_blank(text) || text[0] == '-' || text[0] == '+') {
        if (!arg_blank(text) && text[0] == '-' && isdigit((unsigned char)text[1])) {
            arg_range_msg(cmd, opt, text, 0, 4294967295.0, NULL);
            return -1;
        }
        fprintf(stderr, "fieldloc %s: %s: \"%s\" is not a number\n", cmd, opt, text ? text : "");
        return -1;
    }
    errno = 0;
    v = strtoll(text, &end, 10);
    if (end == text || *end != '\0') {
        fprintf(stderr, "fieldloc %s: %s: \"%s\" is not %s\n", cmd, opt, text,
                end != text && (*end == '.' || *end == 'e' || *end == 'E') ? "an integer"
                                                                         : "a number");
        return -1;
    }
    if (errno == ERANGE || v < 0 || v > 4294967295LL) {
        arg_range_msg(cmd, opt, text, 0, 4294967295.0, NULL);
        return -1;
    }
    *out = (uint32_t)v;
    return 0;
}

int arg_double(const char *cmd, const char *opt, const char *text, double lo, double hi,
               const char *unit, double *out)
{
    char *end;
    double v;
    if (arg_blank(text)) {
        fprintf(stderr, "fieldloc %s: %s: \"%s\" is not a number\n", cmd, opt, text ? text : "");
        return -1;
    }
    errno = 0;
    v = strtod(text, &end);
    /* strtod also reads "nan", "inf" and hexadecimal: numbers only */
    if (end == text || *end != '\0' || !isfinite(v) || strpbrk(text, "xXnN") != NULL) {
        fprintf(stderr, "fieldloc %s: %s: \"%s\" is not a number\n", cmd, opt, text);
        return -1;
    }
    if (errno == ERANGE || v < lo || v > hi) {
        arg_range_msg(cmd, opt, text, lo, hi, unit);
        return -1;
    }
    *out = v;
    return 0;
}

static int arg_is_nao(const fl_camera_model_t *m)
{
    return m != NULL && (strncmp(m->name, "nao", 3) == 0 || strcmp(m->name, "uva2013") == 0);
}

void arg_head_range(const fl_camera_model_t *m, double *pitch_lo, double *pitch_hi,
                    double *yaw_lo, double *yaw_hi, const char **what)
{
    if (m == NULL || arg_is_nao(m)) {
        *pitch_lo = ARG_NAO_PITCH_MIN_RAD;
        *pitch_hi = ARG_NAO_PITCH_MAX_RAD;
        *yaw_lo = -ARG_NAO_YAW_MAX_RAD;
        *yaw_hi = ARG_NAO_YAW_MAX_RAD;
        *what = "NAO";
    } else {
        /* the camera model's limit: total downward tilt within +-90 deg */
        double tilt = (m->mount_tilt + m->default_pitch_offset) * (ARG_PI / 32768.0);
        *pitch_lo = -ARG_PI / 2 - tilt;
        *pitch_hi = ARG_PI / 2 - tilt;
        *yaw_lo = -ARG_PI;
        *yaw_hi = ARG_PI;
        *what = "camera";
    }
}

static int arg_angle(const char *cmd, const char *opt, const char *which, const char *text,
                     double lo, double hi, const char *what, double *out)
{
    char name[64];
    snprintf(name, sizeof name, "%s %s", opt, which);
    if (arg_double(cmd, name, text, -1e9, 1e9, NULL, out) != 0)
        return -1;
    if (*out < lo || *out > hi) {
        int nao = !strcmp(what, "NAO");
        fprintf(stderr,
                "fieldloc %s: %s: %s is out of range %.4f..%.4f rad (%.1f..%.1f degrees, %s%s)\n",
                cmd, name, text, lo, hi, lo * 180 / ARG_PI, hi * 180 / ARG_PI,
                nao ? "NAO Head" : "camera limit: optical axis within 90 degrees of level",
                nao ? (which[0] == 'p' ? "Pitch" : "Yaw") : "");
        return -1;
    }
    return 0;
}

int arg_head(const char *cmd, const char *opt, const fl_camera_model_t *m,
             const char *pitch_text, const char *yaw_text, double *pitch_rad,
             double *yaw_rad)
{
    double plo, phi, ylo, yhi;
    const char *what;
    arg_head_range(m, &plo, &phi, &ylo, &yhi, &what);
    if (arg_angle(cmd, opt, "pitch", pitch_text, plo, phi, what, pitch_rad) != 0 ||
        arg_angle(cmd, opt, "yaw", yaw_text, ylo, yhi, what, yaw_rad) != 0)
        return -1;
    return 0;
}

int arg_field_mm(const char *cmd, const char *opt, const char *text, const fl_field_t *f,
                 char axis, double *out)
{
    double half = axis == 'x' ? fl_field_carpet_half_x_mm(f) : fl_field_carpet_half_y_mm(f);
    char unit[64];
    half += ARG_FIELD_MARGIN_MM;
    snprintf(unit, sizeof unit, "mm (the %s carpet's half %s plus %d mm)", f->name,
             axis == 'x' ? "length" : "width", ARG_FIELD_MARGIN_MM);
    return arg_double(cmd, opt, text, -half, half, unit, out);
}

int arg_unknown(const char *cmd, const char *arg, const char *valued)
{
    size_t n = strlen(arg);
    const char *p = valued;
    if (arg[0] != '-' || arg[1] == '\0') {
        fprintf(stderr, "fieldloc %s: unexpected argument %s (fieldloc %s --help)\n", cmd, arg,
                cmd);
        return 2;
    }
    while (p != NULL && (p = strstr(p, arg)) != NULL) {
        if ((p == valued || p[-1] == ' ') && p[n] == '=') {
            int k = atoi(p + n + 1);
            fprintf(stderr, "fieldloc %s: %s needs %d value%s\n", cmd, arg, k, k == 1 ? "" : "s");
            return 2;
        }
        p += n;
    }
    fprintf(stderr, "fieldloc %s: unknown option %s (fieldloc %s --help)\n", cmd, arg, cmd);
    return 2;
}
