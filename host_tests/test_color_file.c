/*
 * host_tests/test_color_file.c - the colour text (fieldloc/color.h): a good
 * file over the defaults, every kind of malformed line with its status and
 * line number (and the caller's params untouched), the size limits, the
 * format -> parse round trip, the one rule check shared with
 * fl_color_init, the commented file of `fieldloc colors`, and a file that
 * moves the green box changing what the vision path finds on a rendered
 * frame.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "eval/detect.h"
#include "world/render.h"
#include "world/truth.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static fl_status_t parse_str(const char *s, fl_color_params_t *p, int32_t *line,
                             const char **why)
{
    const char *w = NULL;
    fl_status_t st = fl_color_params_parse(s, strlen(s), p, line, &w);
    CHECK(w != NULL);
    if (why != NULL)
        *why = w;
    return st;
}

static void test_good(void)
{
    fl_color_params_t p, d;
    int32_t line = -1;
    const char *why = NULL;
    const char *txt = "# venue X, hall 2\n"
                      "\n"
                      "fieldloc-colors 1   # version\r\n"
                      "green 40 +80\t60 255 30 250\n"
                      "  white_line_pct 0\n"
                      "adapt_max_hue 30"; /* no final LF */
    fl_color_params_default(&d);
    fl_color_params_default(&p);
    CHECK_EQ(parse_str(txt, &p, &line, &why), FL_OK);
    CHECK_EQ(line, 0);
    CHECK_EQ(strcmp(why, ""), 0);
    CHECK_EQ(p.green.h_lo, 40);
    CHECK_EQ(p.green.h_hi, 80);
    CHECK_EQ(p.green.s_lo, 60);
    CHECK_EQ(p.green.s_hi, 255);
    CHECK_EQ(p.green.v_lo, 30);
    CHECK_EQ(p.green.v_hi, 250);
    CHECK_EQ(p.white_line_pct, 0);
    CHECK_EQ(p.adapt_max_hue, 30);
    /* the keys left out keep the caller's values */
    CHECK_EQ(p.green_sat_ref, d.green_sat_ref);
    CHECK(memcmp(&p.white, &d.white, sizeof p.white) == 0);
    CHECK(memcmp(&p.yellow, &d.yellow, sizeof p.yellow) == 0);
    CHECK_EQ(p.white_contrast_pct, d.white_contrast_pct);
    /* header only: nothing changes */
    fl_color_params_default(&p);
    CHECK_EQ(parse_str("fieldloc-colors 1\n", &p, &line, NULL), FL_OK);
    CHECK(memcmp(&p, &d, sizeof p) == 0);
    /* boundaries: a wrapping hue range (red), contrast 200, line pct 100,
     * green_sat_ref 1, every bound 0 or 255 */
    CHECK_EQ(parse_str("fieldloc-colors 1\nyellow 170 5 0 0 255 255\nwhite_contrast_pct 200\n"
                       "white_line_pct 100\ngreen_sat_ref 1\nwhite 179 179 0 255 0 255\n",
                       &p, &line, NULL),
             FL_OK);
    CHECK_EQ(p.yellow.h_lo, 170);
    CHECK_EQ(p.yellow.h_hi, 5);
    CHECK_EQ(p.yellow.v_lo, 255);
    CHECK_EQ(p.white_contrast_pct, 200);
    CHECK_EQ(p.white_line_pct, 100);
    CHECK_EQ(p.green_sat_ref, 1);
    CHECK_EQ(p.white.h_lo, 179);
}

typedef struct {
    const char *text;
    fl_status_t status;
    int32_t line;
    const char *why; /* a part of the reason */
} bad_case_t;

static void test_malformed(void)
{
#define H "fieldloc-colors 1\n"
    static const bad_case_t cases[] = {
        {"", FL_ERR_FORMAT, 0, "missing header"},                       /* empty */
        {"# only a comment\n\n", FL_ERR_FORMAT, 0, "missing header"},
        {"green 46 78 49 255 25 255\n", FL_ERR_FORMAT, 1, "missing header"},
        {"\nfieldloc-colors 2\n", FL_ERR_RANGE, 2, "version"},
        {"fieldloc-colors\n", FL_ERR_FORMAT, 1, "VERSION"},
        {"fieldloc-calibration 1\n", FL_ERR_FORMAT, 1, "missing header"},
        {H "blue 100 120 50 255 20 255\n", FL_ERR_NOT_FOUND, 2, "unknown key"},
        {H "Green 46 78 49 255 25 255\n", FL_ERR_NOT_FOUND, 2, "unknown key"},
        {H "green 46 78 49 2x5 25 255\n", FL_ERR_FORMAT, 2, "not an integer"},
        {H "green_sat_ref 10.5\n", FL_ERR_FORMAT, 2, "not an integer"},
        {H "adapt_max_hue -\n", FL_ERR_FORMAT, 2, "not an integer"},
        {H "\nwhite_contrast_pct 0x10\n", FL_ERR_FORMAT, 3, "not an integer"},
        {H "green_sat_ref 256\n", FL_ERR_RANGE, 2, "0..255"},
        {H "green 46 78 -1 255 25 255\n", FL_ERR_RANGE, 2, "0..255"},
        {H "yellow 15 40 90 99999999999999999999999 50 255\n", FL_ERR_RANGE, 2, "0..255"},
        {H "green 46 180 49 255 25 255\n", FL_ERR_RANGE, 2, "green: hue above 179"},
        {H "# c\nwhite 180 179 0 48 60 255\n", FL_ERR_RANGE, 3, "white: hue above 179"},
        {H "green 46 78 200 100 25 255\n", FL_ERR_RANGE, 2, "green: S_LO > S_HI"},
        {H "green_sat_ref 50\n\nyellow 15 40 90 255 60 50\n", FL_ERR_RANGE, 4,
         "yellow: V_LO > V_HI"},
        {H "white_contrast_pct 201\n", FL_ERR_RANGE, 2, "white_contrast_pct"},
        {H "adapt_max_hue 31\n", FL_ERR_RANGE, 2, "adapt_max_hue"},
        {H "green_sat_ref 0\n", FL_ERR_RANGE, 2, "green_sat_ref"},
        /* the rule is checked once the text is read, at the key's own line */
        {H "white_line_pct 99\nadapt_max_hue 3\n", FL_ERR_RANGE, 2, "white_line_pct"},
        {H "green 46 78 49 255 25\n", FL_ERR_FORMAT, 2, "green H_LO"},    /* word count */
        {H "green 46 78 49 255 25 255 7\n", FL_ERR_FORMAT, 2, "green H_LO"},
        {H "yellow\n", FL_ERR_FORMAT, 2, "yellow H_LO"},
        {H "adapt_max_hue\n", FL_ERR_FORMAT, 2, "adapt_max_hue N"},
        {H "adapt_max_hue 3 4\n", FL_ERR_FORMAT, 2, "adapt_max_hue N"},
        {H "adapt_max_hue 3\nadapt_max_hue 4\n", FL_ERR_FORMAT, 3, "repeated key"},
        {H H, FL_ERR_FORMAT, 2, "repeated header"},
        /* the field_auto keys */
        {H "field_auto 2\n", FL_ERR_RANGE, 2, "field_auto 0 or 1"},
        {H "field_auto 1\n# c\nfield_hue 180\n", FL_ERR_RANGE, 4, "field_hue above 179"},
        {H "field_val 0\n", FL_ERR_RANGE, 2, "field_val 0"},
        {H "auto_margin 31\n", FL_ERR_RANGE, 2, "auto_margin above 30"},
        {H "auto_shadow_pct 9\n", FL_ERR_RANGE, 2, "auto_shadow_pct 10..100"},
        {H "auto_shadow_pct 101\n", FL_ERR_RANGE, 2, "auto_shadow_pct 10..100"},
        {H "auto_yellow 3\n", FL_ERR_RANGE, 2, "auto_yellow 0 or 1"},
        {H "field_auto yes\n", FL_ERR_FORMAT, 2, "not an integer"},
        {H "field_hue 60 70\n", FL_ERR_FORMAT, 2, "field_hue N"},
        {H "auto_yellow 0\nauto_yellow 1\n", FL_ERR_FORMAT, 3, "repeated key"},
    };
#undef H
    size_t i;
    fl_color_params_t d;
    fl_color_params_default(&d);
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fl_color_params_t p;
        int32_t line = -1;
        const char *why = NULL;
        fl_status_t st;
        fl_color_params_default(&p);
        st = parse_str(cases[i].text, &p, &line, &why);
        if (st != cases[i].status || line != cases[i].line || why == NULL ||
            strstr(why, cases[i].why) == NULL)
            t_fail_msg(__FILE__, __LINE__, "case %u: status %d line %d '%s', want %d line %d '%s'",
                       (unsigned)i, (int)st, (int)line, why ? why : "(null)",
                       (int)cases[i].status, (int)cases[i].line, cases[i].why);
        if (memcmp(&p, &d, sizeof p) != 0) /* *p unchanged on error */
            t_fail_msg(__FILE__, __LINE__, "case %u: params changed", (unsigned)i);
    }
}

static void test_limits(void)
{
    char buf[FL_COLOR_TEXT_MAX + 64];
    fl_color_params_t p, d;
    int32_t line = -1;
    const char *why = NULL;
    size_t n;
    fl_color_params_default(&d);
    p = d;
    /* overlong line (line 3), even inside a comment */
    n = (size_t)snprintf(buf, sizeof buf, "fieldloc-colors 1\n\n#");
    memset(buf + n, 'x', FL_COLOR_LINE_MAX);
    strcpy(buf + n + FL_COLOR_LINE_MAX, "\nadapt_max_hue 3\n");
    CHECK_EQ(parse_str(buf, &p, &line, &why), FL_ERR_SIZE);
    CHECK_EQ(line, 3);
    CHECK(strstr(why, "too long") != NULL);
    CHECK(memcmp(&p, &d, sizeof p) == 0);
    /* exactly FL_COLOR_LINE_MAX bytes is fine ('#' and LINE_MAX - 1 x) */
    memset(buf + n, 'x', FL_COLOR_LINE_MAX - 1);
    strcpy(buf + n + FL_COLOR_LINE_MAX - 1, "\nadapt_max_hue 3\n");
    CHECK_EQ(parse_str(buf, &p, &line, NULL), FL_OK);
    CHECK_EQ(p.adapt_max_hue, 3);
    /* embedded NUL on line 2 */
    p = d;
    memcpy(buf, "fieldloc-colors 1\nadapt_max_hue 1\0" "2\n", 35);
    CHECK_EQ(fl_color_params_parse(buf, 35, &p, &line, &why), FL_ERR_FORMAT);
    CHECK_EQ(line, 2);
    CHECK(strstr(why, "NUL") != NULL);
    CHECK(memcmp(&p, &d, sizeof p) == 0);
    /* the length bounds the parse: the NUL after len is never read */
    CHECK_EQ(fl_color_params_parse(buf, 33, &p, &line, &why), FL_OK);
    CHECK_EQ(p.adapt_max_hue, 1);
    /* whole text too long */
    p = d;
    memset(buf, '\n', sizeof buf);
    memcpy(buf, "fieldloc-colors 1\n", 18);
    CHECK_EQ(fl_color_params_parse(buf, FL_COLOR_TEXT_MAX, &p, &line, &why), FL_OK);
    CHECK_EQ(fl_color_params_parse(buf, FL_COLOR_TEXT_MAX + 1, &p, &line, &why), FL_ERR_SIZE);
    CHECK_EQ(line, 0);
    /* a broken rule in a value the text does not set: line 0 */
    p = d;
    p.green_sat_ref = 0;
    CHECK_EQ(parse_str("fieldloc-colors 1\nadapt_max_hue 2\n", &p, &line, &why), FL_ERR_RANGE);
    CHECK_EQ(line, 0);
    CHECK(strstr(why, "green_sat_ref") != NULL);
    CHECK_EQ(p.adapt_max_hue, d.adapt_max_hue);
    /* ... and mended by the text */
    CHECK_EQ(parse_str("fieldloc-colors 1\ngreen_sat_ref 90\n", &p, &line, NULL), FL_OK);
    CHECK_EQ(p.green_sat_ref, 90);
    /* NULL arguments */
    CHECK_EQ(fl_color_params_parse(NULL, 5, &p, &line, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_color_params_parse(buf, 5, NULL, NULL, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_color_params_parse(NULL, 0, &p, NULL, NULL), FL_ERR_FORMAT);
    CHECK_EQ(fl_color_params_format(NULL, buf, sizeof buf), 0u);
    CHECK_EQ(fl_color_params_format(&d, NULL, sizeof buf), 0u);
    CHECK_EQ(fl_color_params_check(NULL, &why), FL_ERR_NULL);
}

/* Valid random params: every field over its whole allowed range. */
static void random_params(t_rng_t *r, fl_color_params_t *p)
{
    fl_hsv_box_t *b[3] = {&p->green, &p->white, &p->yellow};
    int k;
    memset(p, 0, sizeof *p);
    for (k = 0; k < 3; k++) {
        int32_t s0 = t_rng_range(r, 0, 255), s1 = t_rng_range(r, 0, 255);
        int32_t v0 = t_rng_range(r, 0, 255), v1 = t_rng_range(r, 0, 255);
        b[k]->h_lo = (uint8_t)t_rng_range(r, 0, 179);
        b[k]->h_hi = (uint8_t)t_rng_range(r, 0, 179);
        b[k]->s_lo = (uint8_t)(s0 < s1 ? s0 : s1);
        b[k]->s_hi = (uint8_t)(s0 < s1 ? s1 : s0);
        b[k]->v_lo = (uint8_t)(v0 < v1 ? v0 : v1);
        b[k]->v_hi = (uint8_t)(v0 < v1 ? v1 : v0);
    }
    p->green_sat_ref = (uint8_t)t_rng_range(r, 1, 255);
    p->white_contrast_pct = (uint8_t)t_rng_range(r, 0, 200);
    p->white_line_pct = (uint8_t)(t_rng_range(r, 0, 3) == 0 ? 0 : t_rng_range(r, 100, 255));
    p->adapt_max_hue = (uint8_t)t_rng_range(r, 0, 30);
    p->field_auto = (uint8_t)t_rng_range(r, 0, 1);
    p->field_hue = (uint8_t)t_rng_range(r, 0, 179);
    p->field_val = (uint8_t)t_rng_range(r, 1, 255);
    p->auto_margin = (uint8_t)t_rng_range(r, 0, 30);
    p->auto_shadow_pct = (uint8_t)t_rng_range(r, 10, 100);
    p->auto_yellow = (uint8_t)t_rng_range(r, 0, 1);
}

static void test_round_trip(void)
{
    char buf[FL_COLOR_TEXT_MAX];
    fl_color_params_t p, q;
    t_rng_t r;
    int32_t line;
    int i;
    size_t n;
    fl_color_params_default(&p);
    n = fl_color_params_format(&p, buf, sizeof buf);
    CHECK_EQ(n, strlen(buf));
    CHECK(strcmp(buf, "fieldloc-colors 1\n"
                      "green 46 78 49 255 25 255\n"
                      "green_sat_ref 106\n"
                      "white 0 179 0 48 60 255\n"
                      "white_contrast_pct 25\n"
                      "white_line_pct 180\n"
                      "yellow 15 40 90 255 50 255\n"
                      "adapt_max_hue 16\n"
                      "field_auto 0\n"
                      "field_hue 64\n"
                      "field_val 131\n"
                      "auto_margin 4\n"
                      "auto_shadow_pct 25\n"
                      "auto_yellow 1\n") == 0);
    /* parsed over params that differ in every field: p exactly */
    t_rng_seed(&r, 11);
    for (i = 0; i < 2000; i++) {
        random_params(&r, &p);
        random_params(&r, &q);
        n = fl_color_params_format(&p, buf, sizeof buf);
        if (n == 0 || n != strlen(buf) || fl_color_params_parse(buf, n, &q, &line, NULL) != FL_OK ||
            memcmp(&p, &q, sizeof p) != 0) {
            t_fail_msg(__FILE__, __LINE__, "round trip %d: '%s'", i, buf);
            break;
        }
    }
    /* too small a buffer, invalid params */
    fl_color_params_default(&p);
    n = fl_color_params_format(&p, buf, sizeof buf);
    CHECK_EQ(fl_color_params_format(&p, buf, n), 0u);
    CHECK_EQ(buf[0], '\0');
    CHECK_EQ(fl_color_params_format(&p, buf, n + 1), n);
    p.white.v_lo = 200;
    p.white.v_hi = 100;
    CHECK_EQ(fl_color_params_format(&p, buf, sizeof buf), 0u);
    CHECK_EQ(buf[0], '\0');
}

/* fl_color_params_check is fl_color_init's rule set: both agree on random
 * params with one field pushed out of its range now and then. */
static void test_check_is_init(void)
{
    fl_color_table_t *t = (fl_color_table_t *)malloc(sizeof *t);
    fl_color_params_t p;
    t_rng_t r;
    int i, bad = 0, n = t_quick ? 24 : 96;
    CHECK(t != NULL);
    if (!t)
        return;
    t_rng_seed(&r, 5);
    for (i = 0; i < n; i++) {
        const char *why = NULL;
        fl_status_t c, s;
        random_params(&r, &p);
        switch (t_rng_range(&r, 0, 10)) {
        case 0: p.green.h_hi = (uint8_t)t_rng_range(&r, 170, 255); break;
        case 1: p.white.s_lo = (uint8_t)(p.white.s_hi + t_rng_range(&r, 0, 2)); break;
        case 2: p.yellow.v_hi = (uint8_t)(p.yellow.v_lo - t_rng_range(&r, 0, 2)); break;
        case 3: p.white_contrast_pct = (uint8_t)t_rng_range(&r, 195, 205); break;
        case 4: p.adapt_max_hue = (uint8_t)t_rng_range(&r, 28, 32); break;
        case 5: p.green_sat_ref = (uint8_t)t_rng_range(&r, 0, 1); break;
        case 6: p.white_line_pct = (uint8_t)t_rng_range(&r, 0, 101); break;
        case 7: p.field_hue = (uint8_t)t_rng_range(&r, 178, 181); break;
        case 8: p.auto_shadow_pct = (uint8_t)t_rng_range(&r, 8, 11); break;
        case 9: p.field_auto = (uint8_t)t_rng_range(&r, 0, 2); break;
        default: break;
        }
        c = fl_color_params_check(&p, &why);
        s = fl_color_init(t, &p);
        CHECK_EQ(c, s);
        CHECK_EQ(c == FL_OK, why != NULL && why[0] == '\0');
        bad += c != FL_OK;
    }
    CHECK(bad > n / 4 && bad < n); /* both outcomes were tried */
    free(t);
}

/* `fieldloc colors`: the commented defaults parse back to the defaults
 * (over params that differ everywhere), within the format's limits. */
static void test_commented_file(void)
{
    char buf[FL_COLOR_TEXT_MAX];
    fl_color_params_t d, q;
    t_rng_t r;
    size_t n, pos = 0;
    int32_t line = -1;
    fl_color_params_default(&d);
    n = det_colors_text(&d, buf, sizeof buf);
    CHECK(n > 0 && n < FL_COLOR_TEXT_MAX);
    while (pos < n) {
        size_t len = strcspn(buf + pos, "\n");
        CHECK_LE(len, (size_t)FL_COLOR_LINE_MAX);
        pos += len + 1;
    }
    CHECK(strstr(buf, "\n# field carpet") != NULL);
    t_rng_seed(&r, 3);
    random_params(&r, &q);
    CHECK_EQ(fl_color_params_parse(buf, n, &q, &line, NULL), FL_OK);
    CHECK(memcmp(&q, &d, sizeof q) == 0);
    CHECK_EQ(det_colors_text(&d, buf, 40), 0u);
}

/* The loader of the CLI's --colors: "FILE:LINE: reason". */
static void test_load(void)
{
    char path[64], err[256];
    fl_color_params_t p, d;
    FILE *f;
    int fd;
    strcpy(path, "/tmp/fl_colors_XXXXXX");
    fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd < 0)
        return;
    f = fdopen(fd, "w");
    fputs("fieldloc-colors 1\n# lines\nwhite 0 179 0 40 60 255\nwhite_contrast_pct 30\n", f);
    fclose(f);
    fl_color_params_default(&d);
    CHECK_EQ(det_colors_load(path, &p, err, sizeof err), 0);
    CHECK_EQ(p.white.s_hi, 40);
    CHECK_EQ(p.white_contrast_pct, 30);
    CHECK_EQ(p.adapt_max_hue, d.adapt_max_hue);
    f = fopen(path, "w");
    fputs("fieldloc-colors 1\n# lines\nwhite 0 180 0 40 60 255\n", f);
    fclose(f);
    CHECK_EQ(det_colors_load(path, &p, err, sizeof err), -1);
    CHECK(strstr(err, path) == err);
    CHECK(strcmp(err + strlen(path), ":3: white: hue above 179") == 0);
    CHECK(memcmp(&p, &d, sizeof p) == 0);
    unlink(path);
    CHECK_EQ(det_colors_load(path, &p, err, sizeof err), -1);
    CHECK(strstr(err, "cannot open") != NULL);
}

/* A file that moves the green box off the carpet: the vision path finds no
 * field and no features on a rendered frame; the defaults read from a file
 * give exactly the built-in result. */
static void test_changes_detection(void)
{
    static truth_t tr;
    render_frame_t fr;
    fl_camera_t cam;
    fl_obs_list_t obs;
    det_ctx_t dc;
    fl_color_params_t p;
    char err[256], text[FL_COLOR_TEXT_MAX];
    int32_t n_default, segs_default, x_default, line;
    size_t n;
    const fl_field_t *field = fl_field_find("spl2013");
    if (truth_load("fixtures/frames/spl2013_circle_side.truth", &tr, err, sizeof err) != 0 ||
        render_read_frame("fixtures/frames/spl2013_circle_side.raw", &fr, err, sizeof err) != 0) {
        t_info("skipped: fixture spl2013_circle_side not found (run from the repository root)");
        return;
    }
    CHECK_EQ(fl_camera_init(&cam, fl_camera_model_find("nao4-top-320"), &tr.head), FL_OK);
    CHECK_EQ(det_ctx_init(&dc), 0);
    fl_vision_frame(dc.vis, dc.colors, &fr.view, &cam, field, &obs);
    n_default = obs.n;
    segs_default = dc.vis->lines.n_segments;
    x_default = dc.vis->crossings.n;
    CHECK(n_default >= 3);
    CHECK(x_default >= 2);
    /* green moved to blue hues: no carpet, so no lines, no features */
    fl_color_params_default(&p);
    CHECK_EQ(parse_str("fieldloc-colors 1\ngreen 100 120 49 255 25 255\n", &p, &line, NULL),
             FL_OK);
    CHECK_EQ(det_ctx_set_colors(&dc, &p), 0);
    fl_vision_frame(dc.vis, dc.colors, &fr.view, &cam, field, &obs);
    CHECK_EQ(obs.n, 0);
    CHECK_EQ(dc.vis->lines.n_segments, 0);
    CHECK_EQ(dc.vis->crossings.n, 0);
    /* the defaults as text: the same detection as the built-in tables */
    fl_color_params_default(&p);
    n = fl_color_params_format(&p, text, sizeof text);
    memset(&p, 0, sizeof p);
    p.green_sat_ref = 1;
    CHECK_EQ(fl_color_params_parse(text, n, &p, &line, NULL), FL_OK);
    CHECK_EQ(det_ctx_set_colors(&dc, &p), 0);
    fl_vision_frame(dc.vis, dc.colors, &fr.view, &cam, field, &obs);
    CHECK_EQ(obs.n, n_default);
    CHECK_EQ(dc.vis->lines.n_segments, segs_default);
    CHECK_EQ(dc.vis->crossings.n, x_default);
    t_info("spl2013_circle_side: %d observations, %d segments, %d crossings with the defaults; "
           "none with green hue 100..120",
           (int)n_default, (int)segs_default, (int)x_default);
    det_ctx_free(&dc);
    render_frame_free(&fr);
}

void suite_color_file(void)
{
    t_run("color_file.good", test_good);
    t_run("color_file.malformed", test_malformed);
    t_run("color_file.limits", test_limits);
    t_run("color_file.round_trip", test_round_trip);
    t_run("color_file.check_is_init", test_check_is_init);
    t_run("color_file.commented_file", test_commented_file);
    t_run("color_file.load", test_load);
    t_run("color_file.changes_detection", test_changes_detection);
}
