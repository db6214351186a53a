/*
 * fieldloc/coach.h - the coach's image path (seed 003, sections 3.2-3.3): a
 * camera standing still beside the field finds each player's foot in its
 * frame and maps it through an image -> field homography (homography.h) to
 * a position report for the players' localizers (obs.h fl_obs_report_t).
 *
 * Method, in integers, per frame:
 *   1. Classes.  Every pixel -> jersey class (FL_COLOR_RED, FL_COLOR_BLUE
 *      or none) through a 32 x 32 x 32 RGB cell table built at init from the
 *      HSV boxes (fl_hsv_from_rgb at each cell's centre, as color.c builds
 *      its tables from boxes); YCbCr frames go through fl_rgb_from_ycbcr.
 *      The same pass computes the CIE L*a*b* a* channel (8-bit, a* + 128 as
 *      OpenCV's 8-bit Lab: sRGB linearisation and a cube root from
 *      generated tables) and its histogram.
 *   2. Field segmentation: Otsu's threshold over the a* histogram (clamped
 *      to [otsu_lo, otsu_hi]); a* above it is "non-field" (the carpet is
 *      green, a* < 0).  Background subtraction: a pixel "moved" when
 *      |Y - Y_bg| + |a* - a*_bg| > bg_diff against the stored empty-field
 *      frame (so a painted white line, non-field by a* alone, never
 *      extends a foot), unless the change is a shadow (darker by at most
 *      shadow_pct with a* unchanged: a robot's shadow on a white line).
 *   3. Jersey masks, bit-packed (32 pixels per uint32 word): binary opening
 *      then closing with square structuring elements (word-parallel shifts,
 *      ands and ors; outside the image counts as set for erosion and clear
 *      for dilation, as OpenCV's default border).
 *   4. Connected regions (4-connected runs, union-find) per jersey; parts
 *      of one jersey split by an arm in front of it (same team, boxes
 *      within the smaller part's height) are joined; regions below
 *      min_region_px are dropped.
 *   5. Per region, the least-squares line u = a + b v through its pixels
 *      (the robot's body axis: upright robots are near-vertical in the
 *      image, so u is regressed on v), its slope limited to +-1/4 (an
 *      upright robot's lean in the image).
 *   6. The foot: walking down that line from the jersey, the run of rows
 *      whose band (the jersey's half width on each side of the line) holds
 *      a non-field pixel, connected to the jersey, is the robot's
 *      non-field region on the line; the lowest row of it holding a pixel
 *      that is both non-field and moved is the foot row, refined to a
 *      fraction of a pixel from the a* difference to the background across
 *      the bottom edge over the band's columns; the foot column is the
 *      middle of that row's run of foot pixels.  A jersey of another
 *      robot met in the band below the region ends the walk with no foot
 *      (that robot stands in front: its legs would pass for this one's).
 *      The foot pixel maps through
 *      the homography to the field; foot_offset_mm moves it away from the
 *      camera (the lowest visible point is the front of the feet, not
 *      their centre).
 * Seed 003 warps the whole image to a top view first and then searches.
 * The search here stays in the image and maps only the foot: a homography
 * maps lines to lines and preserves the order of points along a line
 * between the camera and the horizon, so the robot's line, its runs and
 * its lowest point (nearest the camera) are the same set, in the same
 * order, in both views.  Where the two differ: morphology and the
 * regression weight pixels by image area, not ground area (a far robot's
 * jersey is smaller), and a least-squares line is not invariant under a
 * projective map; both only move the line within the jersey, and the foot
 * is taken at the bottom of the legs below it, which the image view keeps
 * sharper than a resampled top view.
 *
 * Memory: the caller's fl_coach_t, every buffer inside (no heap, nothing
 * on the stack beyond a few hundred bytes).  At the defaults
 * (FL_COACH_MAX_WIDTH x FL_COACH_MAX_HEIGHT = 640 x 480): the background
 * (Y and a*: 2 bytes per pixel) 614400 bytes, four bit masks 4 x 38400,
 * the RGB cell table 32768, runs 49152, regions 3584: 856632 bytes in all
 * on x86-64 (sizeof(fl_coach_t); the host test coach.sizes prints it).
 *
 * Work per frame (worst case, W x H pixels): one pass over the pixels
 * (class and a* lookups, histogram, background difference), morphology
 * 4 * (open_radius + close_radius) word passes over each of two masks
 * (W / 32 x H words each), run extraction over the mask bits, at most
 * FL_COACH_MAX_RUNS runs and FL_COACH_MAX_REGIONS regions (joining parts:
 * at most REGIONS^3 / 2 box tests), and per region kept (at most
 * FL_COACH_MAX_REGIONS walks; at most FL_COACH_MAX_FEET reported) at most
 * H rows of at most 2 * max_band_px + 1 pixels plus the sub-pixel row
 * (5 pixels per band column) and the foot run (2 rows of at most 3 band
 * widths).  At the defaults the pixel pass dominates: ~3.3 ms per
 * 640 x 480 RGB frame on the development host (coach.cost).
 *
 * Bad input: NULL, a frame of another size than the background (or beyond
 * the capacities), an unknown format, no homography set, a degenerate
 * homography, a frame with no field: a status, an empty result, a counter
 * in fl_coach_t, and the state stays valid.
 */
#ifndef FIELDLOC_COACH_H
#define FIELDLOC_COACH_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/color.h"
#include "fieldloc/field.h"
#include "fieldloc/homography.h"
#include "fieldloc/image.h"
#include "fieldloc/obs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parameters (fl_coach_params_default gives the measured defaults). */
typedef struct {
    fl_hsv_box_t red;        /* jersey FL_COLOR_RED (hue may wrap: 170..8) */
    fl_hsv_box_t blue;       /* jersey FL_COLOR_BLUE */
    uint8_t open_radius;     /* opening: square (2r+1)^2, r 0..4 (0: off) */
    uint8_t close_radius;    /* closing: the same, r 0..8 */
    uint16_t min_region_px;  /* smallest jersey region kept, 1..65535 px */
    uint8_t bg_diff;         /* moved: |dY| + |da*| above this, 1..255 */
    uint8_t shadow_pct;      /* ... unless it is a shadow: darker than the
                                background but by at most this factor
                                (Y >= Y_bg * shadow_pct / 100) with |da*|
                                <= bg_diff / 4; 1..100 (100: no shadows) */
    uint8_t otsu_lo, otsu_hi;/* the a* threshold (a* + 128) is clamped to
                                [otsu_lo, otsu_hi], 1 <= lo <= hi <= 254 */
    uint8_t field_pct;       /* a frame whose pixels at or below the
                                threshold are fewer than this % has no
                                field (FL_ERR_NOT_FOUND), 1..100 */
    uint8_t field_a_max;     /* ... and so has one whose below-threshold
                                pixels have a mean a* + 128 above this
                                (not green), 1..255 */
    uint8_t gap_rows;        /* rows without a non-field pixel bridged in
                                the walk down the line, 0..8 */
    uint8_t max_band_px;     /* band half width cap, 1..FL_COACH_MAX_BAND_PX */
    int16_t foot_offset_mm;  /* moved away from the camera on the field,
                                0..200 */
} fl_coach_params_t;

void fl_coach_params_default(fl_coach_params_t *p);

/* FL_OK, FL_ERR_NULL or FL_ERR_RANGE; *why (when why is not NULL) a static
 * reason naming the field ("" when valid). */
fl_status_t fl_coach_params_check(const fl_coach_params_t *p, const char **why);

/* One foot found in a frame. */
typedef struct {
    fl_color_t team;         /* FL_COLOR_RED or FL_COLOR_BLUE */
    int32_t x_mm, y_mm;      /* field frame */
    uint8_t confidence;      /* Q0.8 */
    int32_t u_q4, v_q4;      /* foot pixel, 1/16 px (sub-pixel row) */
    int32_t sd_mm;           /* position sd from the ground size of one
                                pixel row at the foot (FL_OBS_REPORT_SD_MIN_MM
                                ..FL_OBS_REPORT_SD_MAX_MM) */
    uint32_t jersey_px;      /* pixels of the jersey region */
    int32_t line_a_q16;      /* body line u = a + b v: a in Q16 px */
    int32_t line_b_q16;      /* b in Q16 (du/dv) */
    int32_t top_v, bottom_v; /* jersey rows (px) */
} fl_coach_foot_t;

typedef struct {
    fl_coach_foot_t feet[FL_COACH_MAX_FEET];   /* by jersey size, largest first */
    uint16_t n_feet;
    uint16_t dropped;        /* feet beyond FL_COACH_MAX_FEET (counted) */
    uint8_t otsu;            /* the a* threshold of the frame (a* + 128) */
    uint8_t has_background;  /* 1: feet used background subtraction */
    uint16_t regions[2];     /* jersey regions kept: [0] red, [1] blue */
    uint16_t small_regions;  /* regions below min_region_px */
    uint16_t off_field;      /* feet off the carpet or beyond the horizon */
    uint16_t no_foot;        /* regions with no foot below them */
    uint16_t runs_dropped;   /* mask runs beyond FL_COACH_MAX_RUNS */
    uint16_t regions_dropped;/* regions beyond FL_COACH_MAX_REGIONS */
    uint32_t field_px;       /* pixels at or below the threshold */
    uint16_t duplicates;     /* feet of a jersey part whose foot was already
                                found (an arm splits a jersey), not reported */
} fl_coach_result_t;

/* Private: a run of set mask bits in one row, and a region's sums. */
typedef struct {
    int16_t u0, u1, v;       /* pixels u0..u1 of row v */
    uint16_t parent;         /* union-find */
    uint16_t region;         /* region index, FL_COACH_NO_REGION if none */
    uint16_t team;           /* 0 red, 1 blue */
} fl_coach_run_t;
#define FL_COACH_NO_REGION 0xFFFFu

typedef struct {
    int64_t su, sv, suu, suv, svv;
    uint32_t n;
    int16_t u_min, u_max, v_min, v_max;
    uint8_t team;            /* 0 red, 1 blue */
    uint8_t reserved[3];
} fl_coach_region_t;

#define FL_COACH_WORDS ((FL_COACH_MAX_WIDTH + 31) / 32)
#define FL_COACH_MASK_WORDS (FL_COACH_WORDS * FL_COACH_MAX_HEIGHT)

/* The coach's state: caller-owned, every buffer inside.  Fields up to
 * `frames_*` may be read; the rest is private. */
typedef struct {
    fl_coach_params_t params;
    uint8_t initialized;     /* fl_coach_init succeeded */
    uint8_t has_homog;       /* fl_coach_set_homography succeeded */
    uint8_t has_background;  /* fl_coach_set_background succeeded */
    uint8_t reserved;
    int32_t width, height;   /* of the background (0 before it) */
    fl_homog_t homog;
    const fl_field_t *field;
    /* counters */
    uint32_t frames;         /* fl_coach_frame calls with a valid state */
    uint32_t frames_ok;      /* frames that gave a result (maybe 0 feet) */
    uint32_t frames_bad;     /* refused: NULL, size, format */
    uint32_t frames_no_homog;/* refused: no homography set */
    uint32_t frames_no_field;/* refused: no field in the frame */
    uint32_t homog_refused;  /* fl_coach_set_homography refusals */
    /* private */
    uint8_t cls[32768];      /* RGB cell (5 bits each) -> 0 none, 1 red, 2 blue */
    uint32_t hist[256];      /* a* histogram of the frame */
    uint8_t bg_y[FL_COACH_MAX_WIDTH * FL_COACH_MAX_HEIGHT];
    uint8_t bg_a[FL_COACH_MAX_WIDTH * FL_COACH_MAX_HEIGHT];
    uint32_t mask[2][FL_COACH_MASK_WORDS];  /* jersey masks red, blue */
    uint32_t moved[FL_COACH_MASK_WORDS];    /* background difference */
    uint32_t tmp[FL_COACH_MASK_WORDS];      /* morphology scratch */
    uint8_t row_rgb[3 * FL_COACH_MAX_WIDTH];
    uint16_t n_runs, n_regions;
    fl_coach_run_t runs[FL_COACH_MAX_RUNS];
    fl_coach_region_t regions[FL_COACH_MAX_REGIONS];
} fl_coach_t;

/* Initialise *c with params (a copy is kept; no homography, no background).
 * FL_ERR_CONFIG (caller built with other capacities: nothing written),
 * FL_ERR_NULL, FL_ERR_RANGE (fl_coach_params_check). */
fl_status_t fl_coach_init_cfg(fl_coach_t *c, const fl_coach_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_coach_init(fl_coach_t *c, const fl_coach_params_t *p)
{
    return fl_coach_init_cfg(c, p, FL_CONFIG_FINGERPRINT);
}

/* The image -> field map (a copy is kept) and the field the feet must lie
 * on (its carpet).  FL_ERR_NULL, FL_ERR_STATE (c not initialised),
 * FL_ERR_RANGE (h not fitted, or the bottom centre of the frame (of the
 * background, else of a FL_COACH_MAX_WIDTH x FL_COACH_MAX_HEIGHT frame),
 * which shows the ground nearest the camera, does not map to the field
 * plane: a map that cannot be the coach's); on error the previous
 * homography is dropped (frames are refused until a good one). */
fl_status_t fl_coach_set_homography(fl_coach_t *c, const fl_homog_t *h, const fl_field_t *field);

/* Store the empty field (Y and a* per pixel).  Fixes the frame size:
 * later frames must have it.  FL_ERR_NULL, FL_ERR_STATE, FL_ERR_SIZE
 * (beyond FL_COACH_MAX_WIDTH x FL_COACH_MAX_HEIGHT), FL_ERR_FORMAT, or
 * fl_image_validate's status; on error no background is kept. */
fl_status_t fl_coach_set_background(fl_coach_t *c, const fl_image_t *empty_field);

/* Forget the background (feet from a* alone; the frame size is free again). */
void fl_coach_clear_background(fl_coach_t *c);

/* One frame.  *out is always written (empty on error).  FL_OK (n_feet may
 * be 0), FL_ERR_NULL, FL_ERR_STATE (not initialised or no homography),
 * FL_ERR_SIZE (another size than the background, or beyond the
 * capacities), FL_ERR_FORMAT / FL_ERR_STRIDE (fl_image_validate),
 * FL_ERR_NOT_FOUND (no field in the frame). */
fl_status_t fl_coach_frame(fl_coach_t *c, const fl_image_t *img, fl_coach_result_t *out);

/* The feet of a result as reports (obs.h): sd_mm from the foot, team the
 * jersey colour, player 0 (unknown), age_ms as given.  Writes at most cap
 * and returns how many (0 for NULL or a negative age). */
size_t fl_coach_reports(const fl_coach_result_t *r, int32_t age_ms, fl_obs_report_t *out,
                        size_t cap);

/* Building blocks, public for tests and tools. */
/* a* + 128 of an sRGB colour (8-bit, as OpenCV's COLOR_RGB2Lab a channel
 * to within one level). */
uint8_t fl_coach_lab_a(uint8_t r, uint8_t g, uint8_t b);
/* Otsu's threshold over a 256-bin histogram: the t maximising the
 * between-class variance of bins 0..t against t+1..255 (the smallest such
 * t on ties, to the integer precision documented in coach_otsu.c); 0 for
 * an empty or single-valued histogram. */
uint8_t fl_coach_otsu(const uint32_t hist[256]);
/* Opening / closing of a bit mask (w x h pixels, words = (w + 31) / 32 per
 * row, bit u & 31 of word u >> 5 is pixel u) with a (2r+1)^2 square, in
 * place; tmp holds words * h words.  w, h >= 1, r >= 0. */
void fl_coach_open(uint32_t *mask, uint32_t *tmp, int32_t w, int32_t h, int32_t r);
void fl_coach_close(uint32_t *mask, uint32_t *tmp, int32_t w, int32_t h, int32_t r);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_COACH_H */
