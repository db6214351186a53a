/*
 * tools/eval/detect.h - host helpers around the firmware vision path
 * (include/fieldloc/vision.h) shared by `fieldloc detect`, `fieldloc
 * eval-detect`, the vision benchmark and the features tests: one context
 * with the color tables and the vision workspace (malloc'd), the feature
 * list the CLI prints, camera set-up from a model name and head angles,
 * and the detection picture.  Host only (double, malloc).
 *
 * Feature kinds (the CLI's first column): L T X (crossings; penalty and
 * centre marks are X), G (goal-post foot, only when the foot is seen),
 * U (post top, when inside the image), C (centre-circle centre).
 */
#ifndef FL_TOOLS_DETECT_H
#define FL_TOOLS_DETECT_H

#include "fieldloc/fieldloc.h"
#include "fieldloc/vision.h"
#include "eval/colors_opt.h"

#include <stdint.h>

#define DET_MAX_FEATURES 64

typedef struct {
    char kind;            /* 'L' 'T' 'X' 'G' 'U' 'C' */
    double u, v;          /* pixel (pixel-centre convention) */
    double confidence;    /* 0..1 (Q0.8 / 255) */
    int32_t range_mm;     /* ground range from the robot origin */
    double bearing_deg;   /* 0 ahead, positive left */
    fl_landmark_kind_t lm;/* firmware kind (marks: PENALTY/CENTRE_MARK) */
} det_feature_t;

typedef struct {
    fl_color_table_t *colors;
    fl_vision_t *vis;
    fl_vision_params_t params;
    /* When set, det_run sets the colour tables up for each image: the
     * option resolved for the frame's field (colors_opt_resolve), then
     * colors_opt_setup when it resolves to auto (the carpet of that
     * image) or to another mode than the tables hold.  NULL: the tables
     * are left as they are (det_ctx_init: the defaults). */
    const colors_opt_t *colors_each;
    int colors_built;   /* colors_mode_t the tables hold (init: default) */
} det_ctx_t;

/* Experiment knob: when >= 0, the color tables use white S <= this and
 * green S >= this + 1 instead of the defaults (eval-detect --white-s). */
extern int det_white_s_hi;

/* Default color and vision parameters; 0 on success. */
int det_ctx_init(det_ctx_t *c);
/* Same with explicit vision parameters. */
int det_ctx_init_params(det_ctx_t *c, const fl_vision_params_t *p);
void det_ctx_free(det_ctx_t *c);

/* A colour file (fieldloc/color.h's text, `fieldloc colors` writes the
 * defaults): the defaults with the file's keys over them.  0, or -1 with
 * one line in err: "FILE:LINE: reason" ("FILE: reason" when no line is
 * to blame, "FILE: cannot open"); *p is then the defaults. */
int det_colors_load(const char *path, fl_color_params_t *p, char *err, int err_len);
/* p as a colour file with a comment per key (what `fieldloc colors`
 * prints): fl_color_params_format's lines, each key's explanation above
 * it.  Length written (NUL-terminated), 0 when p is invalid or cap too
 * small (FL_COLOR_TEXT_MAX always suffices: the parser reads the result). */
size_t det_colors_text(const fl_color_params_t *p, char *buf, size_t cap);
/* Rebuild c's color tables from p; 0, or -1 when fl_color_init refuses p. */
int det_ctx_set_colors(det_ctx_t *c, const fl_color_params_t *p);

/* Camera from a model and head angles (radians), with the model's default
 * neck height and pitch offset.  Returns fl_camera_init's status. */
fl_status_t det_camera(fl_camera_t *cam, const fl_camera_model_t *m,
                       double head_pitch_rad, double head_yaw_rad);

/* Run the vision path on one frame and list the features (at most max).
 * obs may be NULL.  Returns the number of features. */
int det_run(det_ctx_t *c, const fl_image_t *img, const fl_camera_t *cam,
            const fl_field_t *field, fl_obs_list_t *obs, det_feature_t *out,
            int max);

/* Draw the last frame's stages over an RGB copy of the image: line points
 * (grey), segments (blue; circle chords cyan), crossings (L red, T orange,
 * X magenta, marks purple), posts (G green, U yellow-green, width bar),
 * circle (the fitted circle projected, C centre). */
void det_draw(const det_ctx_t *c, uint8_t *rgb, int width, int height,
              const fl_camera_t *cam, const fl_field_t *field);

/* An RGB888 copy of any fl_image_t (malloc'd, width*height*3). */
uint8_t *det_rgb_copy(const fl_image_t *img);

/* ---- evaluation (tools/cli/cmd_eval_detect.c) ---------------------------------- */

typedef struct {
    int frames;
    int cross_tp, cross_fp, cross_fn, type_ok;
    int type_det[3], type_hit[3], type_truth[3];   /* L, T, X */
    int foot_tp, foot_fp, foot_fn;
    int top_tp, top_fp, top_fn;
    int circle_tp, circle_fp, circle_fn;           /* centre pixel, 8 px */
    int rng_n[6];                                  /* distance bins */
    int cross_bin_truth[6], cross_bin_hit[6];      /* crossing recall by bin */
    double rng_sum[6], rng_max[6];                 /* relative range error */
} evd_stats_t;

void evd_stats_clear(evd_stats_t *s);
/* Score the rendered fixtures of dir (index.txt); names starting with
 * only_prefix when not NULL.  Returns frames scored, -1 without index. */
int evd_fixtures(det_ctx_t *ctx, const char *dir, double max_range, int verbose,
                 evd_stats_t *s, const char *only_prefix);
/* Score the UvA 2013 frames of the real-data folder dir.  Returns frames
 * scored, -1 when the labels cannot be read. */
int evd_uva(det_ctx_t *ctx, const char *dir, int verbose, evd_stats_t *s);
void evd_print(const char *title, const evd_stats_t *s, int ranges);

/* Field-border score of the modern frames' B labels: the scanner's border
 * (fl_scan_t.border_v, linear between grid columns) against the labelled
 * topmost carpet row. */
#define EVD_BORDER_TOL_PX 3.0
typedef struct {
    int n;              /* labelled columns scored */
    int within;         /* |found - label| <= EVD_BORDER_TOL_PX */
    int none;           /* columns where the scanner found no border */
    double sum, worst;  /* px */
    char worst_at[128]; /* "index u U" of the worst column */
} evd_border_t;
void evd_border_clear(evd_border_t *b);
/* Score the modern frames (tools/eval/realdata_modern.csv at csv, images
 * in the real-data folder dir) as evd_uva scores the UvA set, on field
 * spl2020 with each row's camera and head angles (0 when not labelled);
 * B labels go to b.  Returns frames scored, -1 when the labels cannot be
 * read. */
int evd_modern(det_ctx_t *ctx, const char *dir, const char *csv, int verbose, evd_stats_t *s,
               evd_border_t *b);
void evd_border_print(const evd_border_t *b);
/* Seed 004's corner features on aibo2004 (tools/eval/eval_corners.c):
 * the aibo2004 fixtures of dir's index.txt and n_random rendered AIBO frames
 * scored against the map's C / T-field / T-net points within 3 m.  cn:
 * the caller's corner state (large).  Returns frames scored, -1 without
 * the field or camera. */
typedef struct {
    int frames, fixtures;
    int truth, found, det, correct;
    double err_sum;
    /* per type, [0] C, [1] T-field, [2] T-net; range error of the found
     * (|detected - true range|, mm) */
    int truth_t[3], found_t[3], det_t[3], correct_t[3];
    double rng_sum_t[3], rng_max_t[3];
} evc_stats_t;
#define EVD_CORNERS_RANDOM 36
int evd_corners(det_ctx_t *ctx, const char *dir, int n_random, fl_corners_t *cn, evc_stats_t *s);
/* The summary line, one line per type and aibo_corners_precision /
 * aibo_corners_recall. */
void evd_corners_print(const evc_stats_t *s);
/* Folder for a picture of every scored frame (NULL: none). */
void evd_set_pictures(const char *dir);

#endif
