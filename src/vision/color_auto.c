/*
 * src/vision/color_auto.c - the field colour from the frame (rules, costs:
 * include/fieldloc/color_auto.h).
 *
 * Algorithm.  Start-up: two passes over a sparse grid of the ground part
 * of the image (hue histogram -> mode and spread; S and V histograms of the
 * samples within the spread -> percentiles), then boxes relative to that
 * carpet.  Per frame: the carpet estimate of the scanner moves a tracked
 * carpet (rate-limited), the effective boxes follow it, and the tables are
 * rebuilt only past a hysteresis.
 * Memory: the caller's fl_color_estimate_t (histograms) and
 * fl_color_table_t (tracker state); a few locals.
 */
#include "fieldloc/color_auto.h"
#include "color_int.h"

#include <string.h>

/* Carpet hues searched for the mode (60..200 degrees: yellow-green to
 * cyan; every SPL carpet seen, 37..89, with room), and the half-width of
 * the window its spread is measured in (pale carpets have a wide hue
 * spread: oisin, NaoTH outdoor). */
#define FL_AUTO_HUE_MIN 30
#define FL_AUTO_HUE_MAX 100
#define FL_AUTO_SPREAD 30

static int32_t wrap180(int32_t h)
{
    h %= 180;
    return h < 0 ? h + 180 : h;
}

/* Circular difference a - b of two hues, in -90..89. */
static int32_t hdiff(int32_t a, int32_t b)
{
    int32_t d = wrap180(a - b);
    return d >= 90 ? d - 180 : d;
}

static int32_t wrap180_q4(int32_t h)
{
    h %= 180 * 16;
    return h < 0 ? h + 180 * 16 : h;
}

static int32_t clampi(int32_t x, int32_t lo, int32_t hi)
{
    return x < lo ? lo : (x > hi ? hi : x);
}

/* ---- start-up estimate ------------------------------------------------------ */

/* First sampled row of column u: below the horizon (camera) or the lower
 * half; >= h when the column has no ground. */
static int32_t first_row(const fl_image_t *img, const fl_camera_t *cam, int32_t u)
{
    int32_t hv;
    if (cam == NULL)
        return img->height / 2;
    hv = fl_camera_horizon_v_q4(cam, u * 16 + 8);
    if (hv == INT32_MIN)
        return 0;
    if (hv == INT32_MAX || hv >= img->height * 16)
        return img->height;
    return hv < 0 ? 0 : hv / 16 + 1;
}

/* One pass over the grid.  pass 1: hue histogram of saturated samples;
 * pass 2: S and V of samples inside e's hue spread.  Returns the count. */
static int32_t sample_pass(const fl_image_t *img, const fl_camera_t *cam,
                           fl_color_estimate_t *e, int32_t pass)
{
    int32_t su = img->width / 64 > 0 ? img->width / 64 : 1;
    int32_t sv = img->height / 48 > 0 ? img->height / 48 : 1;
    int32_t span = wrap180(e->hue_hi - e->hue_lo);
    int32_t u, v, n = 0;
    for (u = su / 2; u < img->width; u += su) {
        for (v = first_row(img, cam, u) + sv / 2; v < img->height; v += sv) {
            uint8_t rgb[3];
            fl_hsv_t c;
            (void)fl_image_get_rgb(img, u, v, rgb);
            c = fl_hsv_from_rgb(rgb[0], rgb[1], rgb[2]);
            if (pass == 1) {
                if (c.s < 40 || c.v < 24)
                    continue;
                e->hist_h[c.h]++;
            } else {
                if (c.s < 16 || wrap180(c.h - e->hue_lo) > span)
                    continue;
                e->hist_s[c.s]++;
                e->hist_v[c.v]++;
            }
            n++;
        }
    }
    return n;
}

/* Smallest x with hist[0..x] >= n * pct / 100 (pct 0..100). */
static uint8_t percentile(const uint16_t *hist, int32_t n, int32_t pct)
{
    int32_t x, acc = 0, want = (n * pct + 99) / 100;
    if (want < 1)
        want = 1;
    for (x = 0; x < 255; x++) {
        acc += hist[x];
        if (acc >= want)
            break;
    }
    return (uint8_t)x;
}

/* Offset from the mode (-FL_AUTO_SPREAD..FL_AUTO_SPREAD) below which
 * (dir 1: from the low end; dir -1: from the high end) pct % of the tot
 * samples within +-FL_AUTO_SPREAD of it lie. */
static int32_t hue_tail(const fl_color_estimate_t *e, int32_t mode, int32_t tot, int32_t pct,
                        int32_t dir)
{
    int32_t k, acc = 0;
    for (k = 0; k <= 2 * FL_AUTO_SPREAD; k++) {
        int32_t d = dir > 0 ? k - FL_AUTO_SPREAD : FL_AUTO_SPREAD - k;
        acc += e->hist_h[wrap180(mode + d)];
        if (acc * 100 >= tot * pct)
            return d;
    }
    return dir > 0 ? FL_AUTO_SPREAD : -FL_AUTO_SPREAD;
}

/* Mode of the hue histogram over 5 bins among the carpet hues
 * (FL_AUTO_HUE_MIN..MAX), and the spread of the samples within
 * +-FL_AUTO_SPREAD of it: the 10th / 90th percentile's distance from the
 * mode times 3/2.  For a normal spread that is the 3rd / 97th percentile
 * (1.88 against 1.28 sigma), but a weak second population in the window
 * (a bluish wall or a brown floor above the carpet, a tenth of the
 * samples) moves the 10th / 90th percentile little where it carries the
 * 3rd / 97th out to itself. */
static void hue_mode(fl_color_estimate_t *e)
{
    int32_t h, d, best = -1, mode = 0, tot = 0, lo, hi;
    for (h = FL_AUTO_HUE_MIN; h <= FL_AUTO_HUE_MAX; h++) {
        int32_t s = 0;
        for (d = -2; d <= 2; d++)
            s += e->hist_h[wrap180(h + d)];
        if (s > best) {
            best = s;
            mode = h;
        }
    }
    for (d = -FL_AUTO_SPREAD; d <= FL_AUTO_SPREAD; d++)
        tot += e->hist_h[wrap180(mode + d)];
    lo = clampi(hue_tail(e, mode, tot, 10, 1) * 3 / 2, -FL_AUTO_SPREAD, FL_AUTO_SPREAD);
    hi = clampi(hue_tail(e, mode, tot, 10, -1) * 3 / 2, -FL_AUTO_SPREAD, FL_AUTO_SPREAD);
    e->hue = (uint8_t)mode;
    e->hue_lo = (uint8_t)wrap180(mode + lo);
    e->hue_hi = (uint8_t)wrap180(mode + hi);
}

fl_status_t fl_color_estimate(const fl_image_t *img, const fl_camera_t *cam,
                              fl_color_estimate_t *e)
{
    fl_status_t st;
    if (e == NULL || img == NULL)
        return FL_ERR_NULL;
    memset(e, 0, sizeof *e);
    st = fl_image_validate(img);
    if (st != FL_OK)
        return st;
    e->n_sat = sample_pass(img, cam, e, 1);
    if (e->n_sat < 32)
        return FL_ERR_NOT_FOUND;
    hue_mode(e);
    e->n = sample_pass(img, cam, e, 2);
    if (e->n < 32) {
        e->n = 0;
        return FL_ERR_NOT_FOUND;
    }
    e->s_p5 = percentile(e->hist_s, e->n, 5);
    e->s_med = percentile(e->hist_s, e->n, 50);
    e->v_p2 = percentile(e->hist_v, e->n, 2);
    e->v_med = percentile(e->hist_v, e->n, 50);
    e->v_p98 = percentile(e->hist_v, e->n, 98);
    return FL_OK;
}

/* ---- boxes ------------------------------------------------------------------- */

/* Keep the yellow hue range 2 units clear of green's (both not wrapping
 * through 0 and yellow below green, as on every goal-yellow field); off
 * when nothing is left.  Returns 1 when yellow survives. */
static int32_t yellow_clear(const fl_hsv_box_t *g, fl_hsv_box_t *y)
{
    if (y->h_lo > y->h_hi || g->h_lo > g->h_hi || y->h_lo >= g->h_lo)
        return !(y->h_lo <= y->h_hi && fl_hsv_box_has_hue(g, y->h_lo));
    if (y->h_hi + 2 >= g->h_lo) {
        if (g->h_lo < y->h_lo + 3)
            return 0;
        y->h_hi = (uint8_t)(g->h_lo - 3);
    }
    return 1;
}

fl_status_t fl_color_auto_params(const fl_color_estimate_t *e, fl_color_params_t *p)
{
    fl_color_params_t q;
    int32_t lo, hi, s_lo;
    if (e == NULL || p == NULL)
        return FL_ERR_NULL;
    if (e->n <= 0)
        return FL_ERR_NOT_FOUND;
    if (fl_color_params_check(p, NULL) != FL_OK)
        return FL_ERR_RANGE;
    q = *p;
    lo = hdiff(e->hue_lo, e->hue) - q.auto_margin;
    if (q.auto_yellow && q.yellow.h_lo <= q.yellow.h_hi) {
        /* on a yellow-goal field the posts' hue is not carpet: the spread
         * stops 3 units above the yellow box (unless the carpet itself is
         * that close: then yellow_clear trims the yellow box) */
        int32_t floor = hdiff(q.yellow.h_hi + 3, e->hue);
        if (floor < 0 && lo < floor)
            lo = floor;
    }
    lo = clampi(lo, -30, -12);
    hi = clampi(hdiff(e->hue_hi, e->hue) + q.auto_margin, 12, 30);
    s_lo = clampi(e->s_med / 2, 24, 49);
    q.green.h_lo = (uint8_t)wrap180(e->hue + lo);
    q.green.h_hi = (uint8_t)wrap180(e->hue + hi);
    q.green.s_lo = (uint8_t)s_lo;
    q.green.s_hi = 255;
    q.green.v_lo = (uint8_t)clampi(e->v_p2 * q.auto_shadow_pct / 100, 8, 255);
    q.green.v_hi = 255;
    q.white.h_lo = 0;
    q.white.h_hi = 179;
    q.white.s_lo = 0;
    q.white.s_hi = (uint8_t)(s_lo - 1);
    q.white.v_lo = (uint8_t)clampi(e->v_p2 / 2, 30, 160);
    q.white.v_hi = 255;
    if (q.auto_yellow && !yellow_clear(&q.green, &q.yellow))
        q.auto_yellow = 0;
    q.green_sat_ref = (uint8_t)(e->s_med > 0 ? e->s_med : 1);
    q.field_hue = e->hue;
    q.field_val = (uint8_t)(e->v_med > 0 ? e->v_med : 1);
    q.field_auto = 1;
    if (fl_color_params_check(&q, NULL) != FL_OK)
        return FL_ERR_RANGE;
    *p = q;
    return FL_OK;
}

/* ---- per-frame tracking -------------------------------------------------------- */

void fl_color_int_track_reset(fl_color_table_t *t)
{
    const fl_color_params_t *p = &t->params;
    t->track_hue_q4 = (int16_t)(p->field_hue * 16);
    t->track_sat = p->green_sat_ref;
    t->track_val = p->field_val;
    t->track_frames = 0;
    t->track_rebuilds = 0;
    t->track_wait = 0;
    t->yellow_off = (uint8_t)(p->field_auto && !p->auto_yellow);
}

/* x moved toward target by half the way (at least 1), at most lim. */
static int32_t step_toward(int32_t x, int32_t target, int32_t lim)
{
    int32_t d = target - x, s = d / 2;
    if (s == 0)
        s = d;
    return x + clampi(s, -lim, lim);
}

/* v scaled by num / den, kept within v / 2 .. min(2 v, cap). */
static int32_t scale_v(int32_t v, int32_t num, int32_t den, int32_t cap)
{
    /* Scaling: v, num <= 255 */
    int32_t x = v * num / den, hi = 2 * v < cap ? 2 * v : cap;
    return clampi(x, v / 2, hi < v / 2 ? v / 2 : hi);
}

/* The effective boxes of the tracked carpet, into t (not built). */
static void track_boxes(fl_color_table_t *t, int32_t shift)
{
    const fl_color_params_t *p = &t->params;
    int32_t s_lo;
    t->green = p->green;
    t->white = p->white;
    t->yellow = p->yellow;
    t->hue_shift = (int8_t)clampi(shift, -90, 89);
    if (!(p->green.h_lo == 0 && p->green.h_hi == 179)) {
        t->green.h_lo = (uint8_t)wrap180(p->green.h_lo + shift);
        t->green.h_hi = (uint8_t)wrap180(p->green.h_hi + shift);
    }
    /* Scaling: s_lo * sat <= 255 * 255 */
    s_lo = clampi(p->green.s_lo * t->track_sat / p->green_sat_ref, p->green.s_lo / 2,
                  p->green.s_lo);
    t->green.s_lo = (uint8_t)s_lo;
    if (t->white.s_hi >= s_lo)
        t->white.s_hi = (uint8_t)(s_lo - 1 > p->white.s_lo ? s_lo - 1 : p->white.s_lo);
    t->green.v_lo = (uint8_t)scale_v(p->green.v_lo, t->track_val, p->field_val, p->green.v_hi);
    t->white.v_lo = (uint8_t)scale_v(p->white.v_lo, t->track_val, p->field_val, p->white.v_hi);
    t->yellow_off = (uint8_t)(!p->auto_yellow || !yellow_clear(&t->green, &t->yellow));
}

static int32_t iabs(int32_t x)
{
    return x < 0 ? -x : x;
}

/* The hysteresis: t's new effective boxes differ enough from the ones the
 * tables were built for (shift, green g, white w). */
static bool moved(const fl_color_table_t *t, int32_t old_shift, const fl_hsv_box_t *g,
                  const fl_hsv_box_t *w)
{
    return iabs(t->hue_shift - old_shift) >= 2 || iabs(t->green.s_lo - g->s_lo) >= 6 ||
           iabs(t->green.v_lo - g->v_lo) >= 8 || iabs(t->white.v_lo - w->v_lo) >= 8;
}

int fl_color_track(fl_color_table_t *t, const fl_field_color_t *field)
{
    fl_hsv_box_t g, w, y;
    int8_t old_shift;
    uint8_t old_off;
    int32_t h, d, shift;
    if (t == NULL || field == NULL)
        return FL_ERR_NULL;
    if (!t->params.field_auto || field->n < 16 || field->hue > 179)
        return 0;
    g = t->green;
    h = t->track_hue_q4;
    /* the measurement relative to the tracked hue, 1/16 units, wrapped */
    d = wrap180_q4(field->hue * 16 - h);
    if (d >= 90 * 16)
        d -= 180 * 16;
    if (d > 30 * 16 || d < -30 * 16)
        return 0;   /* not the carpet the boxes are tracking */
    t->track_frames++;
    if (t->track_wait > 0)
        t->track_wait--;
    t->track_hue_q4 = (int16_t)wrap180_q4(step_toward(h, h + d, FL_COLOR_TRACK_HUE_Q4));
    t->track_sat = (uint8_t)step_toward(t->track_sat, field->sat, FL_COLOR_TRACK_SAT);
    t->track_val = (uint8_t)step_toward(t->track_val, field->val, FL_COLOR_TRACK_VAL);
    w = t->white;
    y = t->yellow;
    old_shift = t->hue_shift;
    old_off = t->yellow_off;
    shift = hdiff((t->track_hue_q4 + 8) / 16, t->params.field_hue);
    track_boxes(t, shift);
    if (t->track_wait > 0 || !moved(t, old_shift, &g, &w)) {
        /* within the hysteresis, or too soon after the last rebuild: the
         * boxes the tables were built for stay */
        t->green = g;
        t->white = w;
        t->yellow = y;
        t->hue_shift = old_shift;
        t->yellow_off = old_off;
        return 0;
    }
    fl_color_int_build(t);
    t->track_rebuilds++;
    t->track_wait = FL_COLOR_TRACK_GAP - 1;
    return 1;
}
