/*
 * src/base/text.c - words, numbers and a bounded writer for the firmware's
 * text formats (fieldloc/text.h).
 *
 * Numbers are read with saturation (a long digit string is "out of range"
 * for the caller, not an overflow): integers as int64 capped at 10^12,
 * decimals as int64 millionths (up to 9 decimals read, rounded to 6).
 * Angles: round(udeg * 65536 / 360e6) in int64 (|udeg| <= 180e6, so the
 * product stays below 2^44); the writer prints round(a * 360e6 / 65536)
 * microdegrees, which converts back to the same binary angle because one
 * unit is 5493 microdegrees (the rounding error 0.5 udeg is far below half
 * a unit).
 * Memory: none beyond the caller's buffers.  Cost: O(length).
 */
#include "fieldloc/text.h"

#include <string.h>

#define FL_TEXT_UDEG_TURN 360000000LL

/* libc's memchr is not among the functions the firmware may call. */
size_t fl_text_find(const char *s, size_t n, char c)
{
    size_t i = 0;
    while (i < n && s[i] != c)
        i++;
    return i;
}

size_t fl_text_len(const char *s, size_t max) { return fl_text_find(s, max, '\0'); }

static bool fl_text_is_space(char c) { return c == ' ' || c == '\t'; }

fl_status_t fl_text_line(const char *s, size_t n, size_t line_max, size_t *used,
                         const char **why)
{
    *used = 0;
    *why = "";
    if (n > line_max) {
        *why = "line too long";
        return FL_ERR_SIZE;
    }
    if (fl_text_find(s, n, '\0') < n) {
        *why = "NUL byte";
        return FL_ERR_FORMAT;
    }
    n = fl_text_find(s, n, '#');
    if (n > 0 && s[n - 1] == '\r')
        n--;
    *used = n;
    return FL_OK;
}

int fl_text_split(const char *s, size_t n, fl_text_word_t *w, int max)
{
    size_t i = 0;
    int nw = 0;
    while (i < n && nw < max) {
        size_t b;
        while (i < n && fl_text_is_space(s[i]))
            i++;
        if (i == n)
            break;
        b = i;
        while (i < n && !fl_text_is_space(s[i]))
            i++;
        w[nw].s = s + b;
        w[nw].n = i - b;
        nw++;
    }
    return nw;
}

bool fl_text_word_is(const fl_text_word_t *w, const char *lit)
{
    size_t n = fl_text_len(lit, FL_TEXT_LIT_MAX);
    return w->n == n && memcmp(w->s, lit, n) == 0;
}

bool fl_text_int(const fl_text_word_t *w, int64_t *v)
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
        if (x < FL_TEXT_BIG)
            x = x * 10 + (c - '0');
    }
    *v = neg ? -x : x;
    return true;
}

bool fl_text_micro(const fl_text_word_t *w, int64_t *micro)
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
        if (ip < FL_TEXT_BIG)
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
    if (ip >= FL_TEXT_BIG / 1000000)
        *micro = FL_TEXT_BIG;
    else
        *micro = ip * 1000000 + (frac + 500) / 1000;
    if (neg)
        *micro = -*micro;
    return true;
}

fl_angle_t fl_text_angle(int64_t udeg)
{
    int64_t p = udeg * 65536;
    int64_t a = p >= 0 ? (p + FL_TEXT_UDEG_TURN / 2) / FL_TEXT_UDEG_TURN
                       : -((-p + FL_TEXT_UDEG_TURN / 2) / FL_TEXT_UDEG_TURN);
    return fl_angle_wrap((int32_t)a);
}

/* ---- output ------------------------------------------------------------- */

void fl_text_out_init(fl_text_out_t *o, char *buf, size_t cap)
{
    o->buf = buf;
    o->cap = cap;
    o->n = 0;
    o->ok = buf != NULL && cap > 0;
    if (o->ok)
        buf[0] = '\0';
}

void fl_text_put(fl_text_out_t *o, const char *s, size_t n)
{
    if (!o->ok || o->n + n + 1 > o->cap) {
        o->ok = false;
        return;
    }
    memcpy(o->buf + o->n, s, n);
    o->n += n;
    o->buf[o->n] = '\0';
}

void fl_text_puts(fl_text_out_t *o, const char *s) { fl_text_put(o, s, fl_text_len(s, FL_TEXT_LIT_MAX)); }

void fl_text_put_uint(fl_text_out_t *o, int64_t v, int min_digits)
{
    char d[24];
    int n = 0;
    while ((v > 0 || n < min_digits) && n < (int)sizeof d) {
        d[sizeof d - 1 - (size_t)n] = (char)('0' + (int)(v % 10));
        v /= 10;
        n++;
    }
    fl_text_put(o, d + sizeof d - (size_t)n, (size_t)n);
}

void fl_text_put_deg(fl_text_out_t *o, fl_angle_t a)
{
    int64_t p = (int64_t)a * FL_TEXT_UDEG_TURN;
    int64_t u = p >= 0 ? (p + 32768) / 65536 : -((-p + 32768) / 65536);
    if (u < 0) {
        fl_text_puts(o, "-");
        u = -u;
    }
    fl_text_put_uint(o, u / 1000000, 1);
    fl_text_puts(o, ".");
    fl_text_put_uint(o, u % 1000000, 6);
}
