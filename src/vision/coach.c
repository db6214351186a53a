/*
 * src/vision/coach.c - the coach's image path (coach.h): parameters, the
 * state's set-up, the order of a frame's steps, and reports.
 *
 * Scaling and overflow: see each step's file; here only counts (uint32,
 * wrapping after 2^32 frames) and the field-fraction test (field_px * 100
 * < 2^32 for frames of at most 4096 x 4096 pixels, as FL_IMAGE_MAX_DIM).
 */
#include "coach_int.h"

#include <string.h>

void fl_coach_params_default(fl_coach_params_t *p)
{
    /* The renderer's jerseys are RGB (205, 40, 45) and (40, 70, 190):
     * hue 179 / 113 (0..179), S ~200; the boxes leave room for shading and
     * the fabric texture (S down to ~100, V down to ~50) and keep clear of
     * the carpet (hue ~60), skin-free grey and white (S < 60). */
    static const fl_hsv_box_t red = {168, 8, 110, 255, 60, 255};
    static const fl_hsv_box_t blue = {100, 125, 110, 255, 50, 255};
    if (p == NULL)
        return;
    memset(p, 0, sizeof *p);
    p->red = red;
    p->blue = blue;
    p->open_radius = 1;
    p->close_radius = 2;
    p->min_region_px = 12;
    p->bg_diff = 24;
    /* a robot's soft shadow on a white line: Y 252 -> 187..232 (74 %..,
     * rendered); its dark grey feet over the line: 67 / 252 (27 %) */
    p->shadow_pct = 60;
    p->otsu_lo = 100;
    p->otsu_hi = 150;
    p->field_pct = 10;
    p->field_a_max = 120;
    p->gap_rows = 2;
    p->max_band_px = 40;
    p->foot_offset_mm = 75;
}

static bool box_ok(const fl_hsv_box_t *b)
{
    return b->h_lo <= 179 && b->h_hi <= 179 && b->s_lo <= b->s_hi && b->v_lo <= b->v_hi;
}

fl_status_t fl_coach_params_check(const fl_coach_params_t *p, const char **why)
{
    const char *w = "";
    if (p == NULL) {
        if (why != NULL)
            *why = "null pointer";
        return FL_ERR_NULL;
    }
    if (!box_ok(&p->red))
        w = "red: hue above 179 or a low bound above its high bound";
    else if (!box_ok(&p->blue))
        w = "blue: hue above 179 or a low bound above its high bound";
    else if (p->open_radius > 4)
        w = "open_radius 0..4";
    else if (p->close_radius > 8)
        w = "close_radius 0..8";
    else if (p->min_region_px == 0)
        w = "min_region_px 1..65535";
    else if (p->bg_diff == 0)
        w = "bg_diff 1..255";
    else if (p->shadow_pct == 0 || p->shadow_pct > 100)
        w = "shadow_pct 1..100";
    else if (p->otsu_lo == 0 || p->otsu_lo > p->otsu_hi || p->otsu_hi > 254)
        w = "otsu_lo..otsu_hi within 1..254";
    else if (p->field_pct == 0 || p->field_pct > 100)
        w = "field_pct 1..100";
    else if (p->field_a_max == 0)
        w = "field_a_max 1..255";
    else if (p->gap_rows > 8)
        w = "gap_rows 0..8";
    else if (p->max_band_px == 0 || p->max_band_px > FL_COACH_MAX_BAND_PX)
        w = "max_band_px 1..FL_COACH_MAX_BAND_PX";
    else if (p->foot_offset_mm < 0 || p->foot_offset_mm > 200)
        w = "foot_offset_mm 0..200";
    if (why != NULL)
        *why = w;
    return w[0] == '\0' ? FL_OK : FL_ERR_RANGE;
}

/* The jersey class table: each 8 x 8 x 8 RGB cell takes the class of its
 * centre colour (cell * 8 + 4) by the HSV boxes, red before blue.  32768
 * HSV conversions, at init only. */
static void build_classes(fl_coach_t *c)
{
    int32_t r, g, b;
    for (r = 0; r < 32; r++)
        for (g = 0; g < 32; g++)
            for (b = 0; b < 32; b++) {
                fl_hsv_t hsv = fl_hsv_from_rgb((uint8_t)(r * 8 + 4), (uint8_t)(g * 8 + 4),
                                               (uint8_t)(b * 8 + 4));
                uint8_t k = 0;
                if (fl_hsv_box_has_hue(&c->params.red, hsv.h) && hsv.s >= c->params.red.s_lo &&
                    hsv.s <= c->params.red.s_hi && hsv.v >= c->params.red.v_lo &&
                    hsv.v <= c->params.red.v_hi)
                    k = 1;
                else if (fl_hsv_box_has_hue(&c->params.blue, hsv.h) &&
                         hsv.s >= c->params.blue.s_lo && hsv.s <= c->params.blue.s_hi &&
                         hsv.v >= c->params.blue.v_lo && hsv.v <= c->params.blue.v_hi)
                    k = 2;
                c->cls[(r << 10) | (g << 5) | b] = k;
            }
}

fl_status_t fl_coach_init_cfg(fl_coach_t *c, const fl_coach_params_t *p, uint32_t caller_cfg)
{
    fl_status_t st;
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *c has another layout: no write is safe */
    if (c == NULL || p == NULL)
        return FL_ERR_NULL;
    memset(c, 0, sizeof *c);
    st = fl_coach_params_check(p, NULL);
    if (st != FL_OK)
        return st;
    c->params = *p;
    build_classes(c);
    c->initialized = 1;
    return FL_OK;
}

fl_status_t fl_coach_set_homography(fl_coach_t *c, const fl_homog_t *h, const fl_field_t *field)
{
    fl_point_t pt;
    int32_t w, hh;
    if (c == NULL || !c->initialized)
        return c == NULL ? FL_ERR_NULL : FL_ERR_STATE;
    c->has_homog = 0;
    if (h == NULL || field == NULL) {
        c->homog_refused++;
        return FL_ERR_NULL;
    }
    w = c->has_background ? c->width : FL_COACH_MAX_WIDTH;
    hh = c->has_background ? c->height : FL_COACH_MAX_HEIGHT;
    if (!h->valid || fl_homog_image_to_field(h, w * 8, (hh - 1) * 16, &pt) != FL_HOMOG_OK) {
        c->homog_refused++;
        return FL_ERR_RANGE;
    }
    c->homog = *h;
    c->field = field;
    c->has_homog = 1;
    return FL_OK;
}

/* The view's own problems, then the coach's capacity. */
static fl_status_t check_view(const fl_image_t *img)
{
    fl_status_t st = fl_image_validate(img);
    if (st != FL_OK)
        return st;
    if (img->width > FL_COACH_MAX_WIDTH || img->height > FL_COACH_MAX_HEIGHT)
        return FL_ERR_SIZE;
    return FL_OK;
}

fl_status_t fl_coach_set_background(fl_coach_t *c, const fl_image_t *empty_field)
{
    fl_status_t st;
    if (c == NULL || !c->initialized)
        return c == NULL ? FL_ERR_NULL : FL_ERR_STATE;
    c->has_background = 0;
    c->width = 0;
    c->height = 0;
    if (empty_field == NULL)
        return FL_ERR_NULL;
    st = check_view(empty_field);
    if (st != FL_OK)
        return st;
    c->width = empty_field->width;
    c->height = empty_field->height;
    fl_coach_int_store_background(c, empty_field);
    c->has_background = 1;
    return FL_OK;
}

void fl_coach_clear_background(fl_coach_t *c)
{
    if (c == NULL)
        return;
    c->has_background = 0;
    c->width = 0;
    c->height = 0;
}

/* Otsu's threshold, clamped, and the no-field test (FL_OK or
 * FL_ERR_NOT_FOUND). */
static fl_status_t segment_field(fl_coach_t *c, int32_t n_px, fl_coach_result_t *out)
{
    uint32_t t = fl_coach_otsu(c->hist), i, below = 0;
    uint64_t sum = 0;
    if (t < c->params.otsu_lo)
        t = c->params.otsu_lo;
    if (t > c->params.otsu_hi)
        t = c->params.otsu_hi;
    for (i = 0; i <= t; i++) {
        below += c->hist[i];
        sum += (uint64_t)c->hist[i] * i;
    }
    out->otsu = (uint8_t)t;
    out->field_px = below;
    if ((uint64_t)below * 100u < (uint64_t)c->params.field_pct * (uint32_t)n_px ||
        sum > (uint64_t)below * c->params.field_a_max)
        return FL_ERR_NOT_FOUND;
    return FL_OK;
}

/* The checks of a frame: FL_OK or the refusal (counted). */
static fl_status_t frame_checks(fl_coach_t *c, const fl_image_t *img)
{
    fl_status_t st;
    c->frames++;
    if (img == NULL) {
        c->frames_bad++;
        return FL_ERR_NULL;
    }
    st = check_view(img);
    if (st == FL_OK && c->has_background && (img->width != c->width || img->height != c->height))
        st = FL_ERR_SIZE;
    if (st != FL_OK) {
        c->frames_bad++;
        return st;
    }
    if (!c->has_homog) {
        c->frames_no_homog++;
        return FL_ERR_STATE;
    }
    return FL_OK;
}

fl_status_t fl_coach_frame(fl_coach_t *c, const fl_image_t *img, fl_coach_result_t *out)
{
    fl_status_t st;
    int32_t t;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    if (c == NULL || out == NULL)
        return FL_ERR_NULL;
    if (!c->initialized)
        return FL_ERR_STATE;
    st = frame_checks(c, img);
    if (st != FL_OK)
        return st;
    fl_coach_int_pixels(c, img);
    st = segment_field(c, img->width * img->height, out);
    if (st != FL_OK) {
        c->frames_no_field++;
        return st;
    }
    out->has_background = c->has_background;
    for (t = 0; t < 2; t++) {
        fl_coach_open(c->mask[t], c->tmp, img->width, img->height, c->params.open_radius);
        fl_coach_close(c->mask[t], c->tmp, img->width, img->height, c->params.close_radius);
    }
    fl_coach_int_regions(c, img->width, img->height, out);
    fl_coach_int_feet(c, img, out);
    c->frames_ok++;
    return FL_OK;
}

size_t fl_coach_reports(const fl_coach_result_t *r, int32_t age_ms, fl_obs_report_t *out,
                        size_t cap)
{
    size_t i, n = 0;
    if (r == NULL || out == NULL || age_ms < 0)
        return 0;
    for (i = 0; i < r->n_feet && i < FL_COACH_MAX_FEET && n < cap; i++) {
        const fl_coach_foot_t *f = &r->feet[i];
        fl_obs_report_t *o = &out[n++];
        memset(o, 0, sizeof *o);
        o->x_mm = f->x_mm;
        o->y_mm = f->y_mm;
        o->sd_mm = f->sd_mm;
        o->confidence = f->confidence;
        o->team = (uint8_t)f->team;
        o->player = 0;
        o->age_ms = age_ms;
    }
    return n;
}
