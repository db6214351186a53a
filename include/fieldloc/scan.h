/*
 * fieldloc/scan.h - the column scanner (seed 000, sections 3.4-3.5 and the
 * scan part of 3.8): field border, white and yellow binarization below it,
 * yellow histograms and yellow->green transitions, in one top-down pass per
 * scanned column.
 *
 * Scan grid.  Columns u = i * col_step (i = 0 .. cols - 1), rows v = j *
 * row_step (j = 0 .. rows - 1).  col_step = row_step = 1 classifies every
 * pixel ("full resolution"); the default 2 x 2 grid (160 x 120 cells at
 * 320x240) is what the line-point and goal stages need.
 *
 * Field border (seed 000, 3.4).  In each grid column, from the first
 * searched row (0, or with a camera the horizon minus horizon_margin_px, so
 * that green clutter above the horizon is never the field) down: the first
 * run of border_run_px consecutive green pixels (ceil(N / row_step)
 * samples); the border is the first pixel row of that run (refined to the
 * pixel between grid rows).  Three corrections follow, each bounded and
 * local: (1) a thin white stretch (<= 2 N px, a line) with carpet above it
 * moves the border up to the top of that carpet (far away the carpet beyond
 * the boundary line is thinner than N); with a post above it, to the top of
 * the line; in an image that sees only ground, to the top row when the
 * white reaches it and carpet shows in the top row within 32 px (a line
 * cut by the image edge, not the white-ish floor beyond the field); (2) green clutter beyond the carpet (a couch, a bin, a green
 * shirt), seen as a bump above the border of the flat stretch of columns
 * next to it, is skipped: the border is the next run below it when a
 * floor-like gap separates them and it comes back to the level; (3) a
 * column without any run between columns with one (a line running down the
 * column) gets the top of its lowest stretch of field colors (green and
 * white).  No run: border = height.
 * Output: the class map.  Two bits per grid cell (fl_color_class_t), 32
 * cells per uint64_t, cell i of a row in word i / 32 at bits
 * 63 - 2 (i % 32) (high) and 62 - 2 (i % 32) (low): map[j][w].  Below the
 * border every cell holds its class (green, white, yellow, other); above
 * the border every cell is OTHER (background) except the yellow of goal
 * posts: where yellow touches the border from above (the post foot is the
 * border of its columns), the yellow run is followed upward and kept.
 * White is a color candidate kept only when it contrasts with the green
 * next to it: at the top of each vertical white run the luma of the run
 * (brightest pixel from its first sample to the next) must be >=
 * (100 + white_contrast_pct) % of the green next to it: the darkest green
 * of the 1 to 3 samples above, else a green sample up to 2 columns left or
 * right, else the previous frame's field luma (no reference at all: kept).
 * A run whose brightest pixel clips (luma >= 250) is kept: over carpet
 * brighter than ~200 the contrast asked for is beyond the sensor.
 * Adjacent starts in a row share one check.  Failing runs become OTHER down
 * to their end.  Checks per column are capped (checks_per_column; further
 * runs are kept unchecked and counted in checks_skipped).
 * Memory of the map: rows x words x 8 bytes (76.8 KB at the 640x480
 * capacity), the same as two 1-bit masks.
 *
 * Goal-post cues (seed 000, 3.8): yellow_cols[i] / yellow_rows[j] count the
 * yellow cells of each grid column / row (those kept above the border
 * included); feet[] lists yellow->green transitions, (u, v) = the first
 * green pixel below yellow: below the border two yellow samples right above
 * (or above one non-green sample) and green now; at the border, a post
 * (at least 2 yellow samples kept above it).  At most feet_per_column per
 * column and FL_SCAN_MAX_FEET in all (the rest counted in feet_dropped).
 *
 * Field color: every estimate_step_px-th pixel (in u and v) below the
 * border is converted to HSV; the hue centre (mean around the histogram
 * mode, within +-30 of the green range's centre, S >= half of green s_lo)
 * and the mean S, V and luma go to `field` for fl_color_adapt (color.h).
 *
 * Lifecycle: fl_scan_init(&s, &params) once; fl_scan_frame(&s, &colors,
 * &image, camera or NULL) per frame.  Callers read everything before the
 * "private" mark.  Worst case per frame: every grid cell classified once
 * in B (a border in row 0 of every column: carpet on top, noise below),
 * plus the candidate rows of each band of 32 columns (every ns-th) and up
 * to 2 (ns - 1) rows around each for the run test, per column a few
 * samples around the border, the post trace and the repair (each at most
 * one column height), plus capped per-column checks and feet; measured on
 * the noise frames of bench_scan ("topnoise" is the worst).  A band in
 * which no column has a run of ns green samples is never classified below
 * its candidate rows (uniform noise: little work, empty result).
 */
#ifndef FIELDLOC_SCAN_H
#define FIELDLOC_SCAN_H

#include "fieldloc/camera.h"
#include "fieldloc/color.h"
#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/image.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FL_SCAN_WORDS ((FL_SCAN_MAX_COLS + 31) / 32)
#define FL_SCAN_COUNT_BITS 13   /* bit-sliced counter planes: up to 8191 */

typedef struct {
    int32_t col_step;           /* px between scanned columns, 1..16 */
    int32_t row_step;           /* px between scanned rows, 1..16 */
    int32_t border_run_px;      /* N of seed 000, 1..255 px (the run is
                                   ceil(N / row_step) <= 255 samples) */
    int32_t horizon_margin_px;  /* search starts this far above the horizon,
                                   0..255 px (with a camera) */
    int32_t feet_per_column;    /* 0..255 */
    int32_t checks_per_column;  /* white contrast checks, 0..255 */
    int32_t estimate_step_px;   /* field-color sample spacing, 0 (off) or
                                   1..255 px */
} fl_scan_params_t;

/* col/row step 2, N 8 px, margin 2 px, 4 feet and 32 checks per column,
 * field-color samples every 24 px. */
void fl_scan_params_default(fl_scan_params_t *p);

typedef struct {
    int16_t u;                  /* column, px */
    int16_t v;                  /* first green row below the yellow, px */
} fl_scan_foot_t;

typedef struct {
    fl_scan_params_t params;
    /* ---- results of the last fl_scan_frame ---- */
    fl_status_t status;         /* FL_OK, or why the result is empty */
    int32_t width, height;      /* image, px (0 when empty) */
    int32_t cols, rows, words;  /* grid cells and map words per row */
    int32_t start_v;            /* first row searched for the border, px */
    bool below_horizon;         /* camera given and the whole image sees ground */
    int32_t n_border;           /* grid columns with a border */
    int16_t border_v[FL_SCAN_MAX_COLS];     /* px; height = none */
    uint64_t map[FL_SCAN_MAX_ROWS][FL_SCAN_WORDS];
    uint16_t yellow_cols[FL_SCAN_MAX_COLS];
    uint16_t yellow_rows[FL_SCAN_MAX_ROWS];
    int32_t n_feet;
    fl_scan_foot_t feet[FL_SCAN_MAX_FEET];
    fl_field_color_t field;
    /* counters of this frame */
    int32_t feet_dropped;       /* beyond a cap */
    int32_t checks_skipped;     /* white runs kept without a check (cap) */
    int32_t white_rejected;     /* white runs turned OTHER (contrast) */
    /* ---- private: per-frame scratch ---- */
    int16_t first_row[FL_SCAN_MAX_COLS];    /* grid row of the border */
    uint8_t col_feet[FL_SCAN_MAX_COLS];
    uint8_t col_checks[FL_SCAN_MAX_COLS];
    uint64_t ycount[FL_SCAN_WORDS][FL_SCAN_COUNT_BITS];
    uint64_t post_top[FL_SCAN_WORDS];    /* border right below yellow */
    uint16_t hue_hist[180];
    /* phase B's border row (gend_row) and the first non-green grid row
     * below it (gend; none when the column's bit in gend_none is set), for
     * src/vision/scan_border.c, rerun_column */
    int16_t gend_row[FL_SCAN_MAX_COLS];
    int16_t gend[FL_SCAN_MAX_COLS];
    uint64_t gend_none[FL_SCAN_WORDS];
} fl_scan_t;

/* Validate params (FL_ERR_RANGE) and clear the state.  FL_ERR_NULL.
 * FL_ERR_CONFIG (common.h: the caller's config.h differs from the
 * library's): nothing written. */
fl_status_t fl_scan_init_cfg(fl_scan_t *s, const fl_scan_params_t *p, uint32_t caller_cfg);
static inline fl_status_t fl_scan_init(fl_scan_t *s, const fl_scan_params_t *p)
{
    return fl_scan_init_cfg(s, p, FL_CONFIG_FINGERPRINT);
}

/* Scan one frame.  colors: tables from fl_color_init.  camera may be NULL
 * (border search from row 0).  Returns n_border; 0 with an empty result
 * (width = 0, status set) on a NULL, invalid image or a grid larger than
 * FL_SCAN_MAX_COLS x FL_SCAN_MAX_ROWS, and FL_ERR_RANGE when s->params
 * is out of fl_scan_init's ranges (s never initialised, e.g. zeroed). */
int32_t fl_scan_frame(fl_scan_t *s, const fl_color_table_t *colors,
                      const fl_image_t *img, const fl_camera_t *camera);

/* Class of grid cell (i, j); OTHER outside the grid. */
fl_color_class_t fl_scan_class_at(const fl_scan_t *s, int32_t i, int32_t j);

/* Cells of class c in word w of grid row j as a 32-bit mask, bit 31 - k =
 * cell 32 w + k (MSB first, like PBM).  0 outside the grid. */
uint32_t fl_scan_mask_word(const fl_scan_t *s, int32_t j, int32_t w,
                           fl_color_class_t c);

/* Number of cells of class c in the map. */
int32_t fl_scan_count(const fl_scan_t *s, fl_color_class_t c);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_SCAN_H */
