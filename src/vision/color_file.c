/*
 * src/vision/color_file.c - the colour text (format and errors: color.h).
 *
 * Algorithm: one pass over the lines into a copy of the caller's params;
 * each line is checked and cut by fl_text_line (length, NUL, comment, CR),
 * split into at most 8 words (a box item has 7: an 8th is an error), the
 * first looked up in the key table and its values read as integers
 * 0..255.  The line of every key is kept, so that once the whole text is
 * read the one rule check fl_color_init uses (fl_color_int_fault) can name
 * the line of the key it blames.  The copy reaches the caller only when
 * everything holds.
 * Memory: a fl_color_params_t copy and a few locals.  Cost: O(len).
 */
#include "fieldloc/color.h"
#include "fieldloc/text.h"
#include "color_int.h"

#include <string.h>

#define FL_COLOR_WORDS 8 /* a box item's 7 words, plus one to see an extra */

typedef struct {
    fl_status_t status;
    const char *why;
} fl_color_err_t;

typedef struct {
    const char *name;
    int32_t n_values; /* 6: an HSV box, 1: one number */
    const char *usage;
} fl_color_key_def_t;

/* In fl_color_key_t order. */
static const fl_color_key_def_t fl_color_keys[FL_COLOR_KEYS] = {
    {"green", 6, "expected: green H_LO H_HI S_LO S_HI V_LO V_HI"},
    {"green_sat_ref", 1, "expected: green_sat_ref N"},
    {"white", 6, "expected: white H_LO H_HI S_LO S_HI V_LO V_HI"},
    {"white_contrast_pct", 1, "expected: white_contrast_pct N"},
    {"white_line_pct", 1, "expected: white_line_pct N"},
    {"yellow", 6, "expected: yellow H_LO H_HI S_LO S_HI V_LO V_HI"},
    {"adapt_max_hue", 1, "expected: adapt_max_hue N"},
    {"field_auto", 1, "expected: field_auto N"},
    {"field_hue", 1, "expected: field_hue N"},
    {"field_val", 1, "expected: field_val N"},
    {"auto_margin", 1, "expected: auto_margin N"},
    {"auto_shadow_pct", 1, "expected: auto_shadow_pct N"},
    {"auto_yellow", 1, "expected: auto_yellow N"},
};

static fl_color_err_t fl_color_fail(fl_status_t s, const char *why)
{
    fl_color_err_t e;
    e.status = s;
    e.why = why;
    return e;
}

/* The box of a box key, the byte of a one-number key. */
static fl_hsv_box_t *fl_color_box(fl_color_params_t *q, int32_t k)
{
    return k == FL_COLOR_KEY_GREEN ? &q->green : k == FL_COLOR_KEY_WHITE ? &q->white : &q->yellow;
}

static uint8_t *fl_color_number(fl_color_params_t *q, int32_t k)
{
    switch (k) {
    case FL_COLOR_KEY_GREEN_SAT_REF: return &q->green_sat_ref;
    case FL_COLOR_KEY_WHITE_CONTRAST: return &q->white_contrast_pct;
    case FL_COLOR_KEY_WHITE_LINE: return &q->white_line_pct;
    case FL_COLOR_KEY_FIELD_AUTO: return &q->field_auto;
    case FL_COLOR_KEY_FIELD_HUE: return &q->field_hue;
    case FL_COLOR_KEY_FIELD_VAL: return &q->field_val;
    case FL_COLOR_KEY_AUTO_MARGIN: return &q->auto_margin;
    case FL_COLOR_KEY_AUTO_SHADOW: return &q->auto_shadow_pct;
    case FL_COLOR_KEY_AUTO_YELLOW: return &q->auto_yellow;
    default: return &q->adapt_max_hue;
    }
}

/* One item (words w[0..nw-1], nw >= 1) after the header. */
static fl_color_err_t fl_color_item(const fl_text_word_t *w, int nw, fl_color_params_t *q,
                                    int32_t key_line[FL_COLOR_KEYS], int32_t line)
{
    uint8_t v[6];
    int32_t k, i;
    const fl_color_key_def_t *d;
    for (k = 0; k < FL_COLOR_KEYS && !fl_text_word_is(&w[0], fl_color_keys[k].name); k++)
        ;
    if (k == FL_COLOR_KEYS)
        return fl_text_word_is(&w[0], "fieldloc-colors")
                   ? fl_color_fail(FL_ERR_FORMAT, "repeated header")
                   : fl_color_fail(FL_ERR_NOT_FOUND, "unknown key");
    d = &fl_color_keys[k];
    if (nw != d->n_values + 1)
        return fl_color_fail(FL_ERR_FORMAT, d->usage);
    if (key_line[k] != 0)
        return fl_color_fail(FL_ERR_FORMAT, "repeated key");
    for (i = 0; i < d->n_values; i++) {
        int64_t x = 0;
        if (!fl_text_int(&w[1 + i], &x))
            return fl_color_fail(FL_ERR_FORMAT, "not an integer");
        if (x < 0 || x > 255)
            return fl_color_fail(FL_ERR_RANGE, "value out of range (0..255)");
        v[i] = (uint8_t)x;
    }
    if (d->n_values == 6) {
        fl_hsv_box_t *b = fl_color_box(q, k); /* field by field: no layout assumed */
        b->h_lo = v[0];
        b->h_hi = v[1];
        b->s_lo = v[2];
        b->s_hi = v[3];
        b->v_lo = v[4];
        b->v_hi = v[5];
    } else {
        *fl_color_number(q, k) = v[0];
    }
    key_line[k] = line;
    return fl_color_fail(FL_OK, "");
}

/* One line: header or item.  *seen_header tracks the header. */
static fl_color_err_t fl_color_line(const char *s, size_t n, bool *seen_header,
                                    fl_color_params_t *q, int32_t key_line[FL_COLOR_KEYS],
                                    int32_t line)
{
    fl_text_word_t w[FL_COLOR_WORDS];
    int nw;
    int64_t ver = 0;
    const char *why;
    fl_status_t st = fl_text_line(s, n, FL_COLOR_LINE_MAX, &n, &why);
    if (st != FL_OK)
        return fl_color_fail(st, why);
    nw = fl_text_split(s, n, w, FL_COLOR_WORDS);
    if (nw == 0)
        return fl_color_fail(FL_OK, "");
    if (*seen_header)
        return fl_color_item(w, nw, q, key_line, line);
    if (!fl_text_word_is(&w[0], "fieldloc-colors"))
        return fl_color_fail(FL_ERR_FORMAT, "missing header 'fieldloc-colors 1'");
    if (nw != 2 || !fl_text_int(&w[1], &ver))
        return fl_color_fail(FL_ERR_FORMAT, "expected: fieldloc-colors VERSION");
    if (ver != 1)
        return fl_color_fail(FL_ERR_RANGE, "unsupported version (1 only)");
    *seen_header = true;
    return fl_color_fail(FL_OK, "");
}

fl_status_t fl_color_params_parse(const char *text, size_t len, fl_color_params_t *p,
                                  int32_t *err_line, const char **why)
{
    fl_color_err_t e = fl_color_fail(FL_OK, "");
    fl_color_params_t q;
    int32_t key_line[FL_COLOR_KEYS];
    size_t pos = 0;
    int32_t line = 0, k;
    bool seen_header = false;
    if (err_line != NULL)
        *err_line = 0;
    if (why != NULL)
        *why = "";
    if (p == NULL || (text == NULL && len > 0)) {
        if (why != NULL)
            *why = "null pointer";
        return FL_ERR_NULL;
    }
    q = *p;
    memset(key_line, 0, sizeof key_line);
    if (len > FL_COLOR_TEXT_MAX) {
        e = fl_color_fail(FL_ERR_SIZE, "text too long");
    } else {
        while (pos < len) {
            const char *s = text + pos;
            size_t n = fl_text_find(s, len - pos, '\n');
            line++;
            e = fl_color_line(s, n, &seen_header, &q, key_line, line);
            if (e.status != FL_OK)
                break;
            pos += n + 1;
        }
        if (e.status == FL_OK && !seen_header) {
            line = 0;
            e = fl_color_fail(FL_ERR_FORMAT, "missing header 'fieldloc-colors 1'");
        }
        if (e.status == FL_OK && (k = fl_color_int_fault(&q, &e.why)) >= 0) {
            e.status = FL_ERR_RANGE;
            line = key_line[k];
        }
    }
    if (e.status != FL_OK) {
        if (err_line != NULL)
            *err_line = len > FL_COLOR_TEXT_MAX ? 0 : line;
        if (why != NULL)
            *why = e.why;
        return e.status;
    }
    *p = q;
    return FL_OK;
}

size_t fl_color_params_format(const fl_color_params_t *p, char *buf, size_t cap)
{
    fl_text_out_t o;
    fl_color_params_t c;
    int32_t k, i;
    if (p == NULL || buf == NULL || cap == 0)
        return 0;
    c = *p;
    buf[0] = '\0';
    if (fl_color_int_fault(p, NULL) >= 0)
        return 0;
    fl_text_out_init(&o, buf, cap);
    fl_text_puts(&o, "fieldloc-colors 1\n");
    for (k = 0; k < FL_COLOR_KEYS; k++) {
        const fl_color_key_def_t *d = &fl_color_keys[k];
        uint8_t v[6];
        if (d->n_values == 6) {
            const fl_hsv_box_t *b = fl_color_box(&c, k);
            v[0] = b->h_lo;
            v[1] = b->h_hi;
            v[2] = b->s_lo;
            v[3] = b->s_hi;
            v[4] = b->v_lo;
            v[5] = b->v_hi;
        } else {
            v[0] = *fl_color_number(&c, k);
        }
        fl_text_puts(&o, d->name);
        for (i = 0; i < d->n_values; i++) {
            fl_text_puts(&o, " ");
            fl_text_put_uint(&o, v[i], 1);
        }
        fl_text_puts(&o, "\n");
    }
    if (!o.ok) {
        buf[0] = '\0';
        return 0;
    }
    return o.n;
}
