/*
 * fieldloc/color.h - color classes: integer HSV and the lookup tables that
 * turn a pixel into green (field), white (lines), yellow (goals) or other.
 * Seed 000 (section 3.1, Table 1) classifies in HSV because hue hardly
 * changes with the light; this module keeps that definition and makes it
 * cheap.
 *
 * HSV.  fl_hsv_from_rgb is OpenCV's 8-bit COLOR_RGB2HSV bit for bit (hue
 * 0..179 = 2 degrees per unit, saturation and value 0..255; checked for all
 * 2^24 colors against OpenCV when the tests are built with it).
 *
 * Classes.  A class is an HSV box (fl_hsv_box_t: hue range, saturation
 * range, value range, inclusive).  The class of a color is the first box
 * that contains it in the order yellow, green, white; none: other.  White
 * is only a candidate here: the scanner (scan.h) keeps a white run only
 * when it is brighter than the neighbouring green by white_contrast_pct.
 *
 * Default boxes (fl_color_params_default), measured on the UvA 2013 images
 * of seed 000 (../shared/realdata, 23 labelled 320x240 frames, OpenCV
 * hue convention; host test color.realdata_defaults re-measures them):
 *   carpet, bottom 40 rows away from lines: hue p1/p50/p99 52/64/73; S p1
 *          82, median ~110; V p1 57, median 131, p99 171.  Everywhere
 *          below the border (far carpet included): hue p0.5..p95 49..69,
 *          S p1 56 with a pale far tail down to S ~ 45 (sheen)
 *   posts (labelled foot -> top):       hue p1..p99 26..32; S >= 167;
 *          V 166..230
 *   lines (5x5 around labelled crossings, carpet excluded): S <= 90
 *          (edge pixels mixed with carpet), V 140..255
 * Seed 000's Table 1 gives green hue 20..37 and yellow 38..75.  In the
 * 0..179 convention these rows are swapped: the measured carpet (52..73)
 * falls in 38..75 and the posts (26..32) in 20..37 (Table 1 as printed
 * finds almost none of the carpet green, the swapped rows nearly all).
 * The defaults are
 *   green  hue 46..78 (carpet p0.5..p99 +- 4 of drift; re-centred per
 *          frame by fl_color_adapt), S 49..255 (the pale far carpet; a line
 *          pixel half covered by near carpet has S ~ 40-57), V 25..255 (the
 *          carpet at half the light: V p1 57 -> 28)
 *   white  hue 0..179, S 0..48 (the boxes meet: S >= 49 is green): the
 *          trade-off between crossing precision and recall with the exact
 *          RGB path, the luma line points and the connectors (a lower
 *          bound loses recall, a higher one precision; eval-detect).  V
 *          60..255 (lines at gain 0.5 have V ~ 100); contrast 25 %: a white
 *          run must be 1.25x as bright (luma) as the green next to it
 *          (nominal lines are ~2x; pale carpet and grey clutter much less);
 *          line level 180 %: the UvA line cores clip at 255 over carpet of
 *          V 122..164 (ratio >= 1.6..2.1), rendered lines are 1.8x the
 *          carpet (fl_color_white_cap)
 *   yellow hue 15..40 (posts 26..32 +- 8 of hue drift, clear of green at
 *          46), S 90..255, V 50..255 (posts at half light: V ~ 85)
 *
 * Tables (fl_color_table_t, built by fl_color_init / rebuilt by
 * fl_color_adapt, no heap, 254 KiB; built at start-up, not per frame):
 *   YCbCr (YUYV and planar frames): BT.601 full range as src/base/image.c,
 *   R = Y + a, G = Y + b, B = Y + c with integer offsets a, b, c that
 *   depend on (Cb, Cr) only.  So for one chroma, hue H and D = max - min
 *   are constant and V = Y + M (M = max offset) while no channel clips:
 *   the class is a fixed pattern over k = V = Y + M for each (hue set, D).
 *   The chroma table holds, per (Cb, Cr), the offset of that pattern plus
 *   M, so that class = pattern[chroma[Cb << 8 | Cr] + Y]: one 16-bit and
 *   one 8-bit load per pixel, and YUYV pixel pairs share the first.  Exact
 *   (equal to fl_color_class_ycbcr_exact) whenever BT.601 conversion does
 *   not clip a channel; for clipped colors (outside the RGB gamut) the
 *   pattern is extrapolated (hue frozen, S and V from the clipped formula,
 *   chroma with D > 255 -> other).  `exact` is 0 when the patterns did not
 *   fit and D had to be quantized (never with the default boxes).
 *   RGB: the same idea with offsets (R - G, 0, B - G) from G: for one
 *   (R - G, B - G) hue and D are fixed and V = G + M, so class =
 *   pattern[rgb_chroma[cell(R - G, B - G)] + G] through the same pattern
 *   store.  The cell table is 169 x 169: each difference in one bucket per
 *   value for |R - G|, |B - G| <= FL_COLOR_RGB_EXACT (52), wider buckets
 *   (4, 6, 10) beyond.  Exact (equal to fl_color_class_rgb_exact) for
 *   every color in the exact cells when `exact` is 1: all colors with
 *   S <= 52, i.e. white and the white/green boundary; 99.6 % of the cube
 *   overall (coarse cells use the centre's hue and D and the cell's
 *   smallest M).
 *
 * Lifecycle: fl_color_init(&t, &params) -> per frame fl_scan_frame(.., &t,
 * ..) (scan.h) -> fl_color_adapt(&t, &scan.field) re-centres the green and
 * yellow hue ranges on the measured field color and rebuilds when it moved
 * (returns 1: the caller may re-scan the frame).  Callers read `params`,
 * `green`, `white`, `yellow`, `hue_shift`, `exact`; the tables are private.
 */
#ifndef FIELDLOC_COLOR_H
#define FIELDLOC_COLOR_H

#include "fieldloc/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- HSV ----------------------------------------------------------------- */

typedef struct {
    uint8_t h;   /* hue, 0..179 (2 degrees per unit; red = 0, green = 60) */
    uint8_t s;   /* saturation, 0..255 */
    uint8_t v;   /* value = max(R, G, B) */
} fl_hsv_t;

/* OpenCV 8-bit RGB -> HSV (COLOR_RGB2HSV), exactly. */
fl_hsv_t fl_hsv_from_rgb(uint8_t r, uint8_t g, uint8_t b);

/* n pixels of packed RGB888 -> packed H, S, V bytes (may not overlap). */
void fl_hsv_from_rgb_row(const uint8_t *rgb, uint8_t *hsv, int32_t n);

/* Integer BT.601 full range, the same arithmetic as src/base/image.c:
 * Y, Cb, Cr -> R, G, B (rounded, clamped) and R, G, B -> Y (luma). */
void fl_rgb_from_ycbcr(uint8_t y, uint8_t cb, uint8_t cr, uint8_t rgb[3]);
uint8_t fl_luma_from_rgb(uint8_t r, uint8_t g, uint8_t b);

/* ---- classes ------------------------------------------------------------- */

/* Class codes: 2 bits, the values stored in the scanner's class map. */
typedef enum {
    FL_CLASS_OTHER = 0,
    FL_CLASS_GREEN = 1,
    FL_CLASS_WHITE = 2,
    FL_CLASS_YELLOW = 3
} fl_color_class_t;

/* An HSV box, all bounds inclusive.  Hue 0..179; h_lo > h_hi means the
 * range wraps through 0 (e.g. 170..5 for red).  s_lo <= s_hi, v_lo <= v_hi. */
typedef struct {
    uint8_t h_lo, h_hi;
    uint8_t s_lo, s_hi;
    uint8_t v_lo, v_hi;
} fl_hsv_box_t;

/* At most 8 parameters per class: a box (6) plus class-specific numbers
 * (green 1, white 2, yellow 0; adapt_max_hue is shared). */
typedef struct {
    fl_hsv_box_t green;
    uint8_t green_sat_ref;      /* carpet saturation the box was made for;
                                   fl_color_adapt lowers green.s_lo by
                                   field sat / green_sat_ref (1..255) */
    fl_hsv_box_t white;
    uint8_t white_contrast_pct; /* white run luma >= green luma *
                                   (100 + pct) / 100; 0..200 */
    uint8_t white_line_pct;     /* line brightness / field brightness, %
                                   (the lines' per-frame white level:
                                   fl_color_adapt caps white.s_hi where
                                   lines clip); 0 (off) or 100..255 */
    fl_hsv_box_t yellow;
    uint8_t adapt_max_hue;      /* largest hue re-centring, 0..30 units
                                   (0: fl_color_adapt never moves hues) */
    /* Field colour from the frame (color_auto.h).  Ignored while
     * field_auto is 0, which is what fl_color_params_default gives. */
    uint8_t field_auto;         /* 1: the boxes above are relative to the
                                   carpet (field_hue, field_val,
                                   green_sat_ref) and fl_color_track moves
                                   them with the measured carpet; 0..1 */
    uint8_t field_hue;          /* carpet hue the boxes were made for, 0..179 */
    uint8_t field_val;          /* carpet median V they were made for, 1..255 */
    uint8_t auto_margin;        /* hue units fl_color_auto_params adds on
                                   each side of the carpet's hue spread,
                                   0..30 */
    uint8_t auto_shadow_pct;    /* green V_LO = this % of the carpet's
                                   dark end (hard shadows), 10..100 */
    uint8_t auto_yellow;        /* 1: yellow goals (a yellow box kept clear
                                   of the carpet hue); 0: white goals, no
                                   yellow class at all (auto mode only) */
} fl_color_params_t;

/* The measured defaults described at the top of this file. */
void fl_color_params_default(fl_color_params_t *p);

/* fl_color_init's rules (listed there): FL_OK, FL_ERR_NULL or FL_ERR_RANGE;
 * *why (when why is not NULL) a static reason naming the key, e.g.
 * "green: hue above 179" ("" when valid). */
fl_status_t fl_color_params_check(const fl_color_params_t *p, const char **why);

/* ---- colour text ---------------------------------------------------------
 * The classes as text, so a team can tune them at a venue without
 * rebuilding (`fieldloc colors` writes the defaults with a comment per key;
 * `--colors FILE` of detect, scan and localize reads one).  The same
 * conventions as the calibration text (calib.h, via text.h):
 *     fieldloc-colors 1                header, the first item (version 1)
 *     green H_LO H_HI S_LO S_HI V_LO V_HI
 *     green_sat_ref N
 *     white H_LO H_HI S_LO S_HI V_LO V_HI
 *     white_contrast_pct N
 *     white_line_pct N
 *     yellow H_LO H_HI S_LO S_HI V_LO V_HI
 *     adapt_max_hue N
 *     field_auto N                     0 fixed boxes, 1 carpet-relative
 *     field_hue N
 *     field_val N
 *     auto_margin N
 *     auto_shadow_pct N
 *     auto_yellow N
 * (the fl_color_params_t fields of the same names; N and the box bounds
 * are decimal integers 0..255 with an optional '+').  Every key but the
 * header is optional and may appear at most once; '#' starts a comment
 * (whole line or after an item); blank lines, spaces, tabs and a CR before
 * the LF are ignored.  Lines are at most FL_COLOR_LINE_MAX bytes (without
 * the LF), the text at most FL_COLOR_TEXT_MAX bytes.
 *
 * Errors (fl_color_params_parse's status; *err_line = 1-based line, 0 when
 * the text as a whole is at fault):
 *     FL_ERR_NULL       text (with len > 0) or p NULL
 *     FL_ERR_SIZE       text longer than FL_COLOR_TEXT_MAX (line 0), or a
 *                       line longer than FL_COLOR_LINE_MAX
 *     FL_ERR_FORMAT     no header first (line of the first item; 0 for a
 *                       text without items), a value that is not an
 *                       integer, a wrong number of values, a repeated key,
 *                       a NUL byte
 *     FL_ERR_NOT_FOUND  unknown key
 *     FL_ERR_RANGE      header version other than 1, a value outside
 *                       0..255, or a result that breaks a rule of
 *                       fl_color_init (fl_color_params_check: a hue above
 *                       179, S_LO > S_HI, ...), checked once the whole
 *                       text is read and reported at the line of the key
 *                       concerned (0 when that key is not in the text: the
 *                       value came from *p)
 * *why (when why is not NULL) gets a static one-line reason ("unknown
 * key", "green: hue above 179", ...).
 *
 * Memory: the caller's fl_color_params_t.  Cost: one pass over the text. */
#define FL_COLOR_LINE_MAX 128      /* bytes per line, without the LF */
#define FL_COLOR_TEXT_MAX 4096     /* bytes of a whole colour text */

/* Parse len bytes of text (no NUL terminator needed; a NUL inside is an
 * error) over *p: keys the text leaves out keep the values *p has, so call
 * fl_color_params_default(p) first for "the defaults with these changes".
 * FL_OK (*p updated, valid for fl_color_init) or an error as above (*p
 * unchanged). */
fl_status_t fl_color_params_parse(const char *text, size_t len, fl_color_params_t *p,
                                  int32_t *err_line, const char **why);

/* Write p as text in the format above: the header, then every key in the
 * order listed, one per line.  Parsing it over any params gives p back
 * exactly.  Returns the length written (a NUL follows it), or 0 when cap is
 * too small (FL_COLOR_TEXT_MAX always suffices; 384 does for this
 * version), an argument is NULL, or p breaks a rule of
 * fl_color_params_check. */
size_t fl_color_params_format(const fl_color_params_t *p, char *buf, size_t cap);

/* Field color measured by the scanner (scan.h, fl_scan_t.field). */
typedef struct {
    int32_t n;          /* samples used; 0 = no estimate */
    uint8_t hue;        /* centre, 0..179 */
    uint8_t sat;        /* mean saturation of the samples */
    uint8_t val;        /* mean value */
    uint8_t luma;       /* mean BT.601 luma */
} fl_field_color_t;

/* Capacity of the YCbCr pattern store, bytes (the defaults use ~62 KiB). */
#define FL_COLOR_PATTERN_BYTES 65536
/* Cells per axis of the RGB chroma table: R - G and B - G each in 169
 * buckets, exact (one value) for |difference| <= FL_COLOR_RGB_EXACT. */
#define FL_COLOR_RGB_SIDE 169
#define FL_COLOR_RGB_EXACT 52

typedef struct {
    fl_color_params_t params;   /* as given to fl_color_init */
    /* Effective boxes: params with the adaptation applied. */
    fl_hsv_box_t green, white, yellow;
    int8_t hue_shift;           /* applied to the green and yellow hues */
    uint8_t exact;              /* 1: YCbCr tables exact (see file top) */
    uint16_t n_patterns;        /* YCbCr patterns in use */
    uint8_t d_quant;            /* D bucket size used for the patterns */
    uint8_t yellow_off;         /* 1: no yellow class (field_auto with
                                   auto_yellow 0) */
    uint8_t track_wait;         /* frames before fl_color_track may
                                   rebuild again */
    uint8_t reserved[1];
    /* fl_color_track's state (color_auto.h): the carpet as tracked (hue
     * in 1/16 units, S, V) and what the tables were last built for */
    int16_t track_hue_q4;
    uint8_t track_sat, track_val;
    uint32_t track_frames;      /* frames tracked */
    uint32_t track_rebuilds;    /* table rebuilds by fl_color_track */
    /* private */
    uint16_t chroma[65536];     /* (Cb << 8 | Cr) -> pattern index - ... + M */
    uint8_t pattern[FL_COLOR_PATTERN_BYTES];
    /* RGB: (R - G, B - G) -> cell (rgb_dr[R - G + 255] + rgb_db[B - G +
     * 255]) -> pattern index + M, class = pattern[rgb_chroma[cell] + G] */
    uint32_t rgb_dr[511], rgb_db[511];
    uint16_t rgb_chroma[FL_COLOR_RGB_SIDE * FL_COLOR_RGB_SIDE];
    /* scratch of a table build (dead between calls): kept here, not on
     * the stack, so init/adapt/reset stay within the 4 KiB stack budget */
    uint16_t build_base[7][256];   /* hue sets 1..7 (0: no hue, all other) */
    int16_t build_step[256];
} fl_color_table_t;

/* Validate params and build the tables.  FL_ERR_NULL, FL_ERR_RANGE (a hue
 * above 179, lo > hi for S or V, contrast > 200, adapt_max_hue > 30,
 * green_sat_ref 0, white_line_pct 1..99); on error *t is left classifying
 * everything as other.  FL_ERR_CONFIG (common.h: the caller's config.h
 * differs from the library's): nothing written. */
fl_status_t fl_color_init_cfg(fl_color_table_t *t, const fl_color_params_t *p,
                              uint32_t caller_cfg);
static inline fl_status_t fl_color_init(fl_color_table_t *t, const fl_color_params_t *p)
{
    return fl_color_init_cfg(t, p, FL_CONFIG_FINGERPRINT);
}

/* Re-centre on a field-color estimate (at least 16 samples): hue shift =
 * estimate hue - centre of params.green's hue range, limited to
 * +-adapt_max_hue, applied to green and yellow; green.s_lo scaled down by
 * sat / green_sat_ref (never up, never below half); white.s_hi capped by
 * the per-frame white level (fl_color_white_cap).  Rebuilds when the shift
 * moved by >= 2, s_lo by >= 6 or the white cap by >= 3 and returns 1; 0
 * when nothing changed or the estimate is empty; FL_ERR_NULL. */
int fl_color_adapt(fl_color_table_t *t, const fl_field_color_t *field);

/* Per-frame white level.  Where the field is bright the lines clip at 255
 * and the blurred pixel at a line's edge, a mix of carpet and a line
 * brighter than the sensor can show, clips to a near-grey: a pixel only a
 * third covered by the line looks white (S ~ 30 at 1.6x the nominal light)
 * and lines come out a pixel wider on each side.  The cap is the
 * saturation of a pixel 3/8 covered by a line white_line_pct % as bright as
 * the field, after the clip: 255 - min channel of that mix, where the
 * field's min channel is val - sat * val / 255.  While the lines do not
 * clip that number is above any sensible s_hi (the real mix saturation is
 * lower), so the cap only acts on bright frames.  Returns the effective
 * white s_hi: min(params.white.s_hi, max(cap, params.white.s_lo)); the
 * unchanged s_hi when white_line_pct is 0 or the estimate is empty.
 * Scaling: val, sat <= 255; val * white_line_pct <= 65025; the mix sum
 * 5 * 255 + 3 * 650 < 2^12; integer floor divisions. */
int32_t fl_color_white_cap(const fl_color_params_t *p, const fl_field_color_t *field);

/* Back to params (shift 0) and rebuild.  FL_OK or FL_ERR_NULL. */
fl_status_t fl_color_reset(fl_color_table_t *t);

/* Class of one color through the tables (what the scanner uses). */
fl_color_class_t fl_color_class_rgb(const fl_color_table_t *t, uint8_t r,
                                    uint8_t g, uint8_t b);
fl_color_class_t fl_color_class_ycbcr(const fl_color_table_t *t, uint8_t y,
                                      uint8_t cb, uint8_t cr);

/* The definition the tables implement (slow, for tests and tools): HSV
 * through fl_hsv_from_rgb (after fl_rgb_from_ycbcr), then the boxes. */
fl_color_class_t fl_color_class_hsv(const fl_color_table_t *t, fl_hsv_t hsv);
fl_color_class_t fl_color_class_rgb_exact(const fl_color_table_t *t, uint8_t r,
                                          uint8_t g, uint8_t b);
fl_color_class_t fl_color_class_ycbcr_exact(const fl_color_table_t *t,
                                            uint8_t y, uint8_t cb, uint8_t cr);

/* Hue h (0..179) inside box b's hue range (wrapping ranges included). */
bool fl_hsv_box_has_hue(const fl_hsv_box_t *b, int32_t h);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_COLOR_H */
