/*
 * src/vision/coach_foot.c - a foot per jersey region (coach.h, steps 5 and
 * 6): the region's least-squares line, the walk down it through the
 * robot's non-field pixels, the foot row to a fraction of a pixel, and the
 * field point through the homography.
 *
 * The line.  u = a + b v over the region's pixels: b = (n Suv - Su Sv) /
 * (n Svv - Sv^2), a = (Su - b Sv) / n.  Numerator and denominator (< 2^58
 * for 2^24 pixels of coordinates < 2^12) are shifted right together until
 * the numerator fits 2^46, then b = num * 2^16 / den; b is clamped to
 * +-1/4 (COACH_MAX_SLOPE_Q16).  a in Q16 from (Su * 2^16 - b Sv) / n (< 2^58).  One row
 * (den = 0): b = 0 through the mean column.
 *
 * The band.  Row v of the walk looks at the pixels within hw of the line
 * (hw = half the jersey's width + 1, at most max_band_px): the legs stand
 * inside the jersey's width, and the line, through the middle of the
 * body, may pass between them.  A jersey split in parts by an arm in front
 * of it is joined first (coach_regions.c), or a part's line would run
 * along one side of the body and miss the legs.
 *
 * The sub-pixel row.  For each band column whose lowest foot pixel is in
 * the foot row or the one above it (row vb), the edge is the top of row vb
 * plus the coverage of rows vb..vb+2, a coverage being the pixel's a*
 * difference to the background over that of the pixel above vb (fully the
 * robot), less a noise floor, clamped to [0, 1].  A rendered or real pixel
 * on the edge mixes robot and carpet in proportion to its area, so the
 * coverages add up to the edge's position within the pixels.  a* rather
 * than luma: a robot's soft shadow darkens the carpet below its feet but
 * hardly moves a*.  Without a background the edge is the lowest foot row's
 * bottom (v + 1/2).  The foot pixel is the mean of those columns' edges
 * and columns.
 *
 * Scaling: pixel coordinates < 2^12, Q4 < 2^16, Q8 coverages; the edge sum
 * over at most 2 * FL_COACH_MAX_BAND_PX + 1 columns < 2^9 * 2^20 in int32.
 * Field points within FL_HOMOG_MAX_MM; the offset direction's length by
 * fl_isqrt64 of a sum of squares < 2^42.
 */
#include "coach_int.h"
#include "fieldloc/fixed.h"

#include <string.h>

/* |du/dv| of an upright robot's axis: world verticals meet in the image
 * at the vertical vanishing point, f / tan(tilt) below the principal
 * point (about 2000 px for a NAO top camera tilted 17 deg), so across a
 * 640 px frame they lean at most ~320 / 2000; 1/4 leaves room for a
 * little roll.  A jersey is not much taller than wide, so its own fit is
 * poorly conditioned and a clutter pixel or a shoulder edge can tilt it
 * far beyond that (seed 003 fits in the top view, where the warp smears
 * the jersey along the viewing ray and makes it long). */
#define COACH_MAX_SLOPE_Q16 16384

/* The line of region g: a, b in Q16. */
static void fit_line(const fl_coach_region_t *g, int32_t *a_q16, int32_t *b_q16)
{
    int64_t n = g->n, num = n * g->suv - g->su * g->sv, den = n * g->svv - g->sv * g->sv, b;
    while (num > ((int64_t)1 << 46) || num < -((int64_t)1 << 46)) {
        num /= 2;
        den /= 2;
    }
    b = den > 0 ? (num * 65536) / den : 0;
    if (b > COACH_MAX_SLOPE_Q16)
        b = COACH_MAX_SLOPE_Q16;
    if (b < -COACH_MAX_SLOPE_Q16)
        b = -COACH_MAX_SLOPE_Q16;
    *b_q16 = (int32_t)b;
    *a_q16 = (int32_t)((g->su * 65536 - b * g->sv) / n);
}

typedef struct {
    int32_t a_q16, b_q16, hw, w, h;
    uint8_t otsu;
} walk_t;

/* Band of row v: [*u0, *u1]; false when it lies outside the image. */
static bool band(const walk_t *k, int32_t v, int32_t *u0, int32_t *u1)
{
    int32_t uc = (int32_t)(((int64_t)k->a_q16 + (int64_t)k->b_q16 * v + 32768) >> 16);
    *u0 = uc - k->hw < 0 ? 0 : uc - k->hw;
    *u1 = uc + k->hw > k->w - 1 ? k->w - 1 : uc + k->hw;
    return *u0 <= *u1;
}

static bool moved_bit(const fl_coach_t *c, int32_t w, int32_t u, int32_t v)
{
    return ((c->moved[(size_t)v * (size_t)fl_coach_words(w) + (size_t)(u >> 5)] >> (u & 31)) & 1u) != 0;
}

/* A foot pixel: non-field by a*, and moved when there is a background. */
static bool foot_px(const fl_coach_t *c, const fl_image_t *img, const walk_t *k, int32_t u,
                    int32_t v, bool *nonfield)
{
    uint8_t rgb[3];
    fl_coach_int_rgb(img, u, v, rgb);
    *nonfield = fl_coach_lab_a(rgb[0], rgb[1], rgb[2]) > k->otsu;
    return *nonfield && (!c->has_background || moved_bit(c, img->width, u, v));
}

/* Any jersey pixel (either team) in row v, columns u0..u1. */
static bool jersey_in(const fl_coach_t *c, int32_t w, int32_t v, int32_t u0, int32_t u1)
{
    size_t row = (size_t)v * (size_t)fl_coach_words(w);
    int32_t u;
    for (u = u0; u <= u1; u++)
        if (((c->mask[0][row + (size_t)(u >> 5)] | c->mask[1][row + (size_t)(u >> 5)]) >>
             (u & 31)) & 1u)
            return true;
    return false;
}

/* Walk down from row v0: the lowest foot row of the non-field run that
 * starts there (-1: none).  A jersey below the region's own (v_end) in
 * the band is another robot in front: its body would pass for this one's
 * legs, so the walk gives up (no foot rather than the front robot's). */
static int32_t walk_down(const fl_coach_t *c, const fl_image_t *img, const walk_t *k, int32_t v0,
                         int32_t v_end)
{
    int32_t v, gap = 0, foot = -1;
    for (v = v0; v < k->h; v++) {
        int32_t u, u0, u1;
        bool nf_row = false, foot_row = false;
        if (!band(k, v, &u0, &u1))
            break;
        if (v > v_end + 2 && jersey_in(c, img->width, v, u0, u1))
            return -1;
        for (u = u0; u <= u1; u++) {
            bool nf;
            if (foot_px(c, img, k, u, v, &nf))
                foot_row = true;
            nf_row = nf_row || nf;
        }
        if (foot_row)
            foot = v;
        if (nf_row)
            gap = 0;
        else if (++gap > c->params.gap_rows)
            break;
    }
    return foot;
}

/* a* difference to the background at (u, v). */
static int32_t a_diff(const fl_coach_t *c, const fl_image_t *img, int32_t u, int32_t v)
{
    uint8_t rgb[3];
    int32_t d;
    fl_coach_int_rgb(img, u, v, rgb);
    d = (int32_t)fl_coach_lab_a(rgb[0], rgb[1], rgb[2]) - c->bg_a[(size_t)v * (size_t)c->width + (size_t)u];
    return d < 0 ? -d : d;
}

/* Edge of column u below its lowest foot pixel vb, Q8 rows (pixel
 * centres at integers); -1 when the pixel above is not clearly robot. */
#define COACH_NOISE_FLOOR 3
static int32_t column_edge_q8(const fl_coach_t *c, const fl_image_t *img, int32_t u, int32_t vb)
{
    int32_t full, j, sum = 0;
    if (!c->has_background)
        return vb * 256 + 128;
    if (vb < 1)
        return -1;
    full = a_diff(c, img, u, vb - 1) - COACH_NOISE_FLOOR;
    if (full < 4)
        return -1;
    for (j = vb; j <= vb + 2 && j < img->height; j++) {
        int32_t d = a_diff(c, img, u, j) - COACH_NOISE_FLOOR;
        if (d > 0)
            sum += d * 256 / full > 256 ? 256 : d * 256 / full;
    }
    return vb * 256 - 128 + sum;
}

/* A foot pixel in row vf or the row above it. */
static bool foot_at(const fl_coach_t *c, const fl_image_t *img, const walk_t *k, int32_t u,
                    int32_t vf)
{
    bool nf;
    return foot_px(c, img, k, u, vf, &nf) || (vf > 0 && foot_px(c, img, k, u, vf - 1, &nf));
}

/* The feet's column: the middle of the run of foot pixels (rows vf - 1
 * and vf) through the band's, followed beyond the band by at most its
 * width on each side.  A robot seen turned shows its jersey beside the arm
 * in front of it, so the band may sit over one side of the feet. */
static void foot_centre(const fl_coach_t *c, const fl_image_t *img, const walk_t *k, int32_t vf,
                        int32_t u0, int32_t u1, int32_t *u_q4)
{
    int32_t lo = -1, hi = -1, u, lim;
    for (u = u0; u <= u1; u++)
        if (foot_at(c, img, k, u, vf)) {
            if (lo < 0)
                lo = u;
            hi = u;
        }
    if (lo < 0)
        return;
    lim = u0 - (u1 - u0) < 0 ? 0 : u0 - (u1 - u0);
    while (lo - 1 >= lim && foot_at(c, img, k, lo - 1, vf))
        lo--;
    lim = u1 + (u1 - u0) > k->w - 1 ? k->w - 1 : u1 + (u1 - u0);
    while (hi + 1 <= lim && foot_at(c, img, k, hi + 1, vf))
        hi++;
    *u_q4 = (lo + hi) * 8;
}

/* The foot pixel (Q4) below foot row vf. */
static void foot_pixel(const fl_coach_t *c, const fl_image_t *img, const walk_t *k, int32_t vf,
                       int32_t *u_q4, int32_t *v_q4)
{
    int32_t u, u0, u1, n = 0, su = 0, sv = 0;
    if (band(k, vf, &u0, &u1)) {
        for (u = u0; u <= u1; u++) {
            bool nf;
            int32_t vb = -1, e;
            if (foot_px(c, img, k, u, vf, &nf))
                vb = vf;
            else if (vf > 0 && foot_px(c, img, k, u, vf - 1, &nf))
                vb = vf - 1;
            if (vb < 0 || (e = column_edge_q8(c, img, u, vb)) < 0)
                continue;
            n++;
            su += u;
            sv += e;
        }
    }
    if (n == 0) {
        *u_q4 = (int32_t)(((int64_t)k->a_q16 + (int64_t)k->b_q16 * vf) >> 12);
        *v_q4 = vf * 16 + 8;
        return;
    }
    *u_q4 = (su * 16 + n / 2) / n;
    *v_q4 = (sv / n + 8) >> 4;
    foot_centre(c, img, k, vf, u0, u1, u_q4);
}

/* The field point of a foot pixel, moved foot_offset_mm away from the
 * camera (the image's up direction at the foot), and the ground length of
 * one pixel row there; false when it does not map onto the carpet. */
static bool to_field(const fl_coach_t *c, fl_coach_foot_t *f)
{
    fl_point_t p, q;
    int64_t dx, dy;
    uint32_t len;
    if (fl_homog_image_to_field(&c->homog, f->u_q4, f->v_q4, &p) != FL_HOMOG_OK)
        return false;
    f->sd_mm = FL_OBS_REPORT_SD_MAX_MM;
    if (fl_homog_image_to_field(&c->homog, f->u_q4, f->v_q4 - 8 * 16, &q) == FL_HOMOG_OK) {
        dx = (int64_t)q.x_mm - p.x_mm;
        dy = (int64_t)q.y_mm - p.y_mm;
        len = fl_isqrt64((uint64_t)(dx * dx + dy * dy));
        if (len > 0) {
            p.x_mm += (int32_t)(dx * c->params.foot_offset_mm / (int64_t)len);
            p.y_mm += (int32_t)(dy * c->params.foot_offset_mm / (int64_t)len);
            /* a quarter row of error on top of the ~40 mm of the feet's
             * shape (measured: coach.feet prints the errors) */
            f->sd_mm = 40 + (int32_t)(len / 8u / 4u);
        }
    }
    if (f->sd_mm > FL_OBS_REPORT_SD_MAX_MM)
        f->sd_mm = FL_OBS_REPORT_SD_MAX_MM;
    if (f->sd_mm < FL_OBS_REPORT_SD_MIN_MM)
        f->sd_mm = FL_OBS_REPORT_SD_MIN_MM;
    f->x_mm = p.x_mm;
    f->y_mm = p.y_mm;
    return p.x_mm >= -fl_field_carpet_half_x_mm(c->field) &&
           p.x_mm <= fl_field_carpet_half_x_mm(c->field) &&
           p.y_mm >= -fl_field_carpet_half_y_mm(c->field) &&
           p.y_mm <= fl_field_carpet_half_y_mm(c->field);
}

/* The foot of region g into *f; false (counted by the caller) if none. */
static bool region_foot(const fl_coach_t *c, const fl_image_t *img, uint8_t otsu,
                        const fl_coach_region_t *g, fl_coach_foot_t *f, bool *off)
{
    walk_t k;
    int32_t vf, hw = (g->u_max - g->u_min + 1) / 2 + 1;
    *off = false;
    fit_line(g, &k.a_q16, &k.b_q16);
    k.hw = hw < 2 ? 2 : (hw > c->params.max_band_px ? c->params.max_band_px : hw);
    k.w = img->width;
    k.h = img->height;
    k.otsu = otsu;
    vf = walk_down(c, img, &k, (int32_t)(g->sv / (int64_t)g->n), g->v_max);
    if (vf < 0)
        return false;
    memset(f, 0, sizeof *f);
    f->team = g->team == 0 ? FL_COLOR_RED : FL_COLOR_BLUE;
    f->jersey_px = g->n;
    f->line_a_q16 = k.a_q16;
    f->line_b_q16 = k.b_q16;
    f->top_v = g->v_min;
    f->bottom_v = g->v_max;
    foot_pixel(c, img, &k, vf, &f->u_q4, &f->v_q4);
    f->confidence = c->has_background ? 200 : 120;
    if (!to_field(c, f)) {
        *off = true;
        return false;
    }
    return true;
}

/* The new foot (out->feet[n_feet]) is one already found: a jersey split
 * in parts (an arm in front of it) walks down to the same feet.  Same
 * team, foot rows within 2 px and columns within the part's width. */
static bool duplicate(const fl_coach_result_t *out, const fl_coach_region_t *g)
{
    const fl_coach_foot_t *f = &out->feet[out->n_feet];
    int32_t w_q4 = (g->u_max - g->u_min + 1) * 16;
    uint16_t i;
    for (i = 0; i < out->n_feet; i++) {
        const fl_coach_foot_t *e = &out->feet[i];
        int32_t du = e->u_q4 - f->u_q4, dv = e->v_q4 - f->v_q4;
        if (e->team == f->team && dv <= 32 && dv >= -32 && du <= w_q4 && du >= -w_q4)
            return true;
    }
    return false;
}

static void bump(uint16_t *n)
{
    if (*n < 0xFFFFu)
        (*n)++;
}

void fl_coach_int_feet(fl_coach_t *c, const fl_image_t *img, fl_coach_result_t *out)
{
    uint16_t i;
    for (i = 0; i < c->n_regions; i++) {
        c->regions[i].reserved[0] = c->regions[i].n < c->params.min_region_px;
        if (c->regions[i].n == 0)
            continue;           /* joined into another part */
        if (c->regions[i].reserved[0])
            bump(&out->small_regions);
        else
            bump(&out->regions[c->regions[i].team]);
    }
    for (;;) {
        int32_t best = -1;
        bool off;
        for (i = 0; i < c->n_regions; i++)
            if (!c->regions[i].reserved[0] && (best < 0 || c->regions[i].n > c->regions[best].n))
                best = i;
        if (best < 0)
            break;
        c->regions[best].reserved[0] = 1;
        if (out->n_feet >= FL_COACH_MAX_FEET) {
            bump(&out->dropped);
            continue;
        }
        if (region_foot(c, img, out->otsu, &c->regions[best], &out->feet[out->n_feet], &off)) {
            if (duplicate(out, &c->regions[best]))
                bump(&out->duplicates);
            else
                out->n_feet++;
        }
        else if (off)
            bump(&out->off_field);
        else
            bump(&out->no_foot);
    }
}
