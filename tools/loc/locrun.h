/*
 * tools/loc/locrun.h - host glue between the vision path (fieldloc/vision.h)
 * and a localizer (fieldloc/localizer.h; "fuzzy" by default), shared by `fieldloc simulate
 * --frames`, `fieldloc localize`, `fieldloc demo` and the UvA spot
 * evaluation (`fieldloc localize --uva-spots`); plus the parser of the
 * `localize` sequence format.  Host only (double, malloc).
 *
 * Engine (lr_t), per frame:
 *     lr_predict(r, dx_mm, dy_mm, dtheta_rad);   odometry since the last
 *                    call (robot frame at its start, fuzzy.h convention);
 *                    rounded to integers with the remainders carried to
 *                    the next call (no drift), split into several predict
 *                    calls when a component exceeds params.odo_max_mm
 *     lr_frame(r, &image, &camera_pose);         vision -> r->obs -> update
 *     lr_estimate(r, &est);
 *
 * Sequence format (`fieldloc localize SEQUENCE.txt`), one item per line,
 * '#' starts a comment, blank lines are skipped, tokens separated by blanks:
 *     field NAME                 fl_field_find name (required, once)
 *     camera NAME                fl_camera_model_find name (required, once)
 *     prior X_MM Y_MM THETA_DEG  optional, before the first frame
 *     frame IMAGE odo DX_MM DY_MM DTHETA_DEG head PITCH_RAD YAW_RAD
 * IMAGE is a PPM (or an FLRAW fixture frame) relative to the sequence
 * file's folder (absolute paths are used as given; no blanks in names).
 * odo: motion since the previous frame, robot frame at the previous frame
 * (x forward, y left, mm; dtheta CCW, degrees); the first frame's odometry
 * is applied before it as well.  head: NAOqi HeadPitch (+ = down) and
 * HeadYaw (+ = left), radians; the neck height and pitch offset are the
 * camera model's defaults (default_neck_height_mm, default_pitch_offset).
 * The parser is strict: an unknown keyword, a wrong number of tokens, a
 * number that does not parse, is not finite or is out of range (|odo| <=
 * 20000 mm, |dtheta| <= 3600 deg, |pitch|, |yaw| <= 3.2 rad), a repeated or
 * late header, a prior after a frame, a missing field or camera, or no
 * frame at all is an error naming the line.
 */
#ifndef FL_TOOLS_LOCRUN_H
#define FL_TOOLS_LOCRUN_H

#include "eval/colors_opt.h"
#include "eval/detect.h"
#include "eval/hldetect.h"
#include "fieldloc/fieldloc.h"
#include "fieldloc/vision.h"

#include <stdint.h>
#include <stdio.h>

/* ---- engine ---------------------------------------------------------------- */

typedef struct {
    const fl_field_t *field;
    const fl_camera_model_t *model;
    det_ctx_t det;              /* color tables and vision workspace */
    fl_hlv_t *hlv;              /* seed 002's vision path, used instead of
                                   fl_vision_frame on its field (hl3x2:
                                   hld_field_wants); NULL elsewhere */
    const fl_localizer_t *loc;  /* the localizer (localizer.h) */
    void *state;                /* malloc'd, loc->state_size bytes */
    void *params;               /* malloc'd, loc->params_size bytes: the
                                   parameters given to init */
    fl_obs_list_t obs;          /* the last frame's observations */
    fl_camera_t cam;            /* the last frame's camera */
    int32_t obs_used;           /* of the last frame */
    int ignore_post_sides;      /* 1: post sides from vision are dropped
                                   (FL_SIDE_UNKNOWN) before the update */
    fl_obs_view_t view;         /* the last frame's view (negative
                                   information, loc->update;
                                   obs.h fl_vision_view) */
    double carry_x, carry_y, carry_a;   /* predict rounding remainders */
    uint32_t frames;            /* lr_frame calls that ran vision */
    FILE *stream;               /* when set, every predict and update call
                                   lr_predict / lr_frame / lr_frame_obs make
                                   is written to it (tools/loc/stream.h
                                   format, docs/STREAM.md); NULL: off */
    const colors_opt_t *colors; /* colour classes (eval/colors_opt.h), set
                                   up on the first lr_frame from its image
                                   and tracked after every one; NULL: the
                                   defaults, untouched */
    int colors_ready;           /* the first frame set them up */
    int vision;                 /* which vision path lr_frame runs (sim.h
                                   SIM_VISION_*; lr_set_vision): 0 = ltx,
                                   fl_vision_frame alone */
    fl_corners_t *corners;      /* seed 004's corner stage (malloc'd by
                                   lr_set_vision for corners / both); NULL
                                   with ltx */
} lr_t;

/* loc NULL: "fuzzy".  params (loc->params_size bytes) NULL: the
 * localizer's defaults; otherwise adapted to the camera (params_adapt with
 * fl_loc_preset_for_width).  0 on success, -1 (message in err) on a NULL
 * field/model, out of memory or a state that does not fit. */
int lr_init(lr_t *r, const fl_localizer_t *loc, const fl_field_t *field,
            const fl_camera_model_t *model, const void *params, char *err, int err_len);
void lr_free(lr_t *r);

/* The vision path of lr_frame (seed 004's corner stage, issue 21):
 * SIM_VISION_LTX (0, what lr_init sets) fl_vision_frame's observations;
 * SIM_VISION_CORNERS fl_vision_frame still runs (its beacon stage finds
 * the goal posts the nets come from) but the list holds only
 * fl_corners_obs's C / T-field / T-net / net observations; SIM_VISION_BOTH
 * fl_vision_frame's list with the corner observations appended.  The hlv
 * path (hl3x2) ignores it.  0, or -1 (out of memory, bad value). */
int lr_set_vision(lr_t *r, int vision);

void lr_predict(lr_t *r, double dx_mm, double dy_mm, double dtheta_rad);

/* Vision on one frame with this camera pose, then the grid update.
 * Returns the number of observations applied, -1 when the image size does
 * not match the camera model or the pose is invalid (nothing applied). */
int lr_frame(lr_t *r, const fl_image_t *img, const fl_camera_pose_t *pose);

/* The same with observations from elsewhere (cache, simulator): camera
 * set up for the pose (r->cam), r->obs = *obs, update.  -1 on a bad pose. */
int lr_frame_obs(lr_t *r, const fl_camera_pose_t *pose, const fl_obs_list_t *obs);

void lr_estimate(lr_t *r, fl_loc_estimate_t *est);

/* Camera pose from the model's defaults and NAOqi head angles (rad). */
void lr_camera_pose(const fl_camera_model_t *m, double head_pitch_rad,
                    double head_yaw_rad, fl_camera_pose_t *pose);

/* Odometry accumulator: composes per-step motions (robot frame at the
 * start of each step) into one motion in the robot frame at the start of
 * the first; lr_odo_take returns it and restarts. */
typedef struct {
    double x, y, a;             /* mm, mm, rad */
} lr_odo_t;

void lr_odo_add(lr_odo_t *o, double dx_mm, double dy_mm, double dtheta_rad);

/* Errors of an estimate against a true pose: position (mm) and heading
 * (deg, 0..180), and the same against the 180-degree mirror of the truth
 * (-x, -y, heading + 180). */
void lr_pose_error(double ex, double ey, double eh_deg, double tx, double ty,
                   double th_deg, double *pos_mm, double *head_deg,
                   double *mirror_pos_mm, double *mirror_head_deg);

/* mkdir -p.  0 when the folder exists afterwards. */
int lr_mkdirs(const char *path);

/* Binary angle -> degrees in [-180, 180). */
double lr_deg(fl_angle_t a);

/* "LOST", "AMBIGUOUS", "TRACKING" (localizer.h fl_loc_state_t). */
const char *lr_state_name(fl_loc_state_t s);
/* The confidence of an estimate, appended to a line: " STATE sd X_MM Y_MM
 * HEAD_DEG mirror M" (sd_heading 32767, no heading information: "-"). */
void lr_print_conf(FILE *f, const fl_loc_estimate_t *e);

/* The localizer parameters used with the vision path (simulate --frames,
 * localize, demo): the localizer's FL_LOC_PRESET_VISION (a NAO camera;
 * fuzzy: fl_fuzzy_params_vision); lr_init applies params_adapt for the
 * actual camera (fuzzy: wide tracking rings and crossings cut at 2.5 m for
 * cameras narrower than 320 px unless --param changed ring_track_q8). */
void lr_params_frames(const fl_localizer_t *loc, void *p);

/* The localizer by name (NULL: "fuzzy"); NULL with a message naming the
 * known ones in err when unknown. */
const fl_localizer_t *lr_localizer(const char *name, char *err, int err_len);
/* malloc'd parameter block of loc (defaults); NULL when out of memory. */
void *lr_params_new(const fl_localizer_t *loc);

/* Set one parameter by name, "NAME=INTEGER" (loc's parameter table, raw
 * units).  0 on success; -1 for an unknown name, a value that does not fit
 * the field or params that fail loc->params_check. */
int lr_param_set(const fl_localizer_t *loc, void *p, const char *assign);
/* How many parameters of p differ from ref. */
int lr_param_diff(const fl_localizer_t *loc, const void *p, const void *ref);
/* " name=value" for every parameter that differs from ref (all when NULL). */
void lr_param_print(FILE *f, const fl_localizer_t *loc, const void *p, const void *ref);

/* ---- sequence files ------------------------------------------------------- */

#define LR_PATH_MAX 1024

typedef struct {
    char image[LR_PATH_MAX];    /* resolved path */
    int line;                   /* line number in the file, from 1 */
    double odo_dx_mm, odo_dy_mm, odo_dtheta_deg;
    double head_pitch_rad, head_yaw_rad;
} lr_seq_frame_t;

typedef struct {
    const fl_field_t *field;
    const fl_camera_model_t *camera;
    int has_prior;
    double prior_x_mm, prior_y_mm, prior_theta_deg;
    lr_seq_frame_t *frame;      /* malloc'd, n entries */
    int n, cap;
} lr_seq_t;

/* Parse the text (NUL-terminated); relative image names are joined to
 * base_dir (NULL or "" = as given).  0 on success; -1 with "line N: ..."
 * in err (may be NULL) and *out empty otherwise. */
int lr_seq_parse(const char *text, const char *base_dir, lr_seq_t *out,
                 char *err, int err_len);
/* Read and parse a file (images relative to its folder). */
int lr_seq_load(const char *path, lr_seq_t *out, char *err, int err_len);
void lr_seq_free(lr_seq_t *s);

/* Running a parsed sequence (what `fieldloc localize` does, documented in
 * tools/cli/cmd_localize.c): per frame predict(odo) ; image (render_read_frame:
 * PPM or FLRAW) ; vision ; update ; estimate ; "pose X Y THETA REL" line on
 * out.  A frame whose image is missing, unreadable or of the wrong size is
 * skipped with a message on stderr (odometry still applied, pose line still
 * printed). */
typedef struct {
    fl_loc_estimate_t est;
    int obs, used, ok;           /* observations, applied, image used */
} lr_frame_result_t;

typedef struct {
    FILE *out;                   /* pose lines, or NULL */
    const char *name;            /* sequence name for messages */
    const char *pictures;        /* folder for pictures, or NULL */
    const char *picture_prefix;  /* file name prefix ("frame_") */
    int picture_every;           /* every Nth frame (and the last) */
    const fl_localizer_t *loc;   /* NULL: "fuzzy" */
    const void *params;          /* NULL: defaults */
    int quiet;                   /* 1: no messages for skipped frames */
    const fl_calib_t *calib;     /* per-robot calibration applied to every
                                    frame's camera pose (fl_calib_apply), or
                                    NULL: the model's defaults */
    const colors_opt_t *colors;  /* colour classes (--colors, resolved by
                                    colors_opt_resolve for the sequence's
                                    field and first image), or NULL: the
                                    defaults */
} lr_seq_opts_t;

/* res (may be NULL) gets one entry per frame.  Returns the number of
 * frames skipped, -1 on a setup error (message on stderr). */
int lr_seq_run(const lr_seq_t *seq, const lr_seq_opts_t *o, lr_frame_result_t *res);


/* ---- simulated walks (`simulate`, `demo`) ----------------------------------- */

#include "world/render.h"
#include "world/sim.h"

/* Vision against the map, per observation kind (frames mode): every vision
 * observation is placed on the field at the TRUE pose and matched to the
 * nearest map landmark of a compatible kind (crossings and marks: any of
 * L T X penalty/centre mark; posts: posts; circle: circle) within
 * max(250 mm, 20 % of the range).  truth_visible: landmarks whose ground
 * point projects at least 4 px inside the image within the scenario's
 * max_range (the simulator's visibility rule); truth_found: those matched. */
typedef struct {
    uint32_t n_obs, matched, wrong_kind, false_pos;
    uint32_t truth_visible, truth_found;
    double sum_abs_range_pct, sum_abs_bearing_deg;   /* over matched */
    uint32_t side_known, side_wrong;   /* posts: matched with a side given,
                                          and of those, the wrong side */
} lr_vdiag_t;

struct lr_walk_step;

typedef struct {
    int frames;                   /* 1: rendered frames -> vision -> grid;
                                     0: the simulator's observations */
    int every;                    /* frames mode: vision and update on every
                                     Nth step (odometry accumulated between) */
    long max_steps;               /* < 0: the whole walk */
    int threads;                  /* frames mode: rendering threads (0:
                                     lr_threads_default) */
    int ignore_post_sides;        /* lr_t.ignore_post_sides */
    const char *obs_cache;        /* frames mode, for parameter studies:
                                     when this file holds the vision
                                     observations of the same walk (field,
                                     seed, every), they are read instead of
                                     rendering (vision does not depend on
                                     the localizer); otherwise they are
                                     computed and written to it.  NULL: off */
    const fl_localizer_t *loc;    /* NULL: "fuzzy" */
    const void *params;           /* NULL: defaults */
    FILE *steps;                  /* per-record "step ..." lines; NULL: none */
    FILE *stream;                 /* the localizer's inputs and the truth
                                     per record (docs/STREAM.md, written by
                                     tools/loc/stream.h); NULL: none */
    int print_obs;                /* 1: after each step line, one "#  obs"
                                     line per observation of the record */
    /* called after every record (frames mode: every vision step) */
    void (*hook)(void *user, const struct lr_walk_step *ws);
    void *user;
    const colors_opt_t *colors;   /* frames mode: colour classes (lr_t.colors;
                                     an obs_cache holds the observations of
                                     the colours it was written with); NULL:
                                     the defaults */
} lr_walk_opts_t;

typedef struct lr_walk_step {
    const sim_scenario_t *sc;
    const sim_step_t *st;
    lr_t *lr;                     /* grid, obs, cam of this record */
    const fl_loc_estimate_t *est;
    const render_frame_t *frame;  /* frames mode; NULL otherwise */
    long record;                  /* record index */
    double t_s, pos_err_mm, head_err_deg;   /* error used by the metrics */
    int half_known;
    unsigned events;              /* SIM_EV_* of the simulator steps since the
                                     previous record (this one included) */
} lr_walk_step_t;

/* One kidnap of a walk and its recovery (lr_walk_result_t.kidnap). */
#define LR_MAX_KIDNAPS 64

typedef enum {
    LR_KIDNAP_RECOVERED = 0,      /* recovered by itself */
    LR_KIDNAP_TOLD = 1,           /* not before the next penalty placement
                                     (a told reset) */
    LR_KIDNAP_NEXT = 2,           /* not before the next kidnap */
    LR_KIDNAP_END = 3             /* not before the end of the run */
} lr_kidnap_end_t;

typedef struct {
    double t_s;                   /* time of the kidnap (its simulator step) */
    double recover_s;             /* INFINITY: never (by itself) */
    lr_kidnap_end_t end;          /* why the window closed */
    double end_s;                 /* time of the record that closed it */
} lr_kidnap_t;

typedef struct {
    long steps, records, used;    /* simulator steps, records, records in
                                     the RMSE */
    double dt_s;                  /* seconds per record */
    double pos_rmse_mm, heading_rmse_deg;   /* NAN when used == 0 */
    double converge_s;            /* INFINITY if never */
    double kidnap_recover_s;      /* median over the kidnaps of
                                     kidnap[].recover_s (two middle values:
                                     their mean); NAN: no kidnap, INFINITY:
                                     never */
    double kidnap_recover_worst_s;    /* the largest; NAN: no kidnap */
    int n_kidnaps;                /* kidnaps that fall in a record (at most
                                     LR_MAX_KIDNAPS; later ones ignored) */
    lr_kidnap_t kidnap[LR_MAX_KIDNAPS];
    double penalty_recover_s;     /* the same from the first penalty
                                     placement (excluded like the kidnap's
                                     window: the two touchline spots are
                                     equally likely until a landmark is seen) */
    double pos_rmse_all_mm, heading_rmse_all_deg;  /* after convergence,
                                     nothing excluded (information) */
    long flips;
    double final_pos_err_mm, final_head_err_deg;
    fl_loc_stats_t stats;
    lr_vdiag_t vdiag[FL_LM_KIND_COUNT];
    double render_s, vision_grid_s;   /* wall time spent */
} lr_walk_result_t;

/* Rendering threads: $FIELDLOC_THREADS when set, else the online CPUs;
 * 1..LR_MAX_THREADS.  Results do not depend on it (each frame is rendered
 * from its own scene, deterministically). */
#define LR_MAX_THREADS 8
int lr_threads_default(void);

/* Run the walk (metrics as documented in tools/cli/cmd_simulate.c).  0 on
 * success, -1 with a message. */
int lr_walk_run(const sim_scenario_t *sc, const lr_walk_opts_t *o,
                lr_walk_result_t *res, char *err, int err_len);
/* The summary: "# kidnap ..." lines (one per kidnap), "#
 * kidnap_recover_worst_s", "# penalty_recover_s", "# every record", then
 * the lines pos_rmse_mm ... flips (exact format). */
void lr_walk_print_summary(FILE *f, const lr_walk_result_t *res);
/* "# localizer: N kidnaps detected, ..." (the localizer's counters). */
void lr_walk_print_stats(FILE *f, const lr_walk_result_t *res);

/* ---- the metrics of a walk, record by record (simulate and replay) ------ */

/* Feed, per record: the events of the simulator steps since the previous
 * record, in step order (lr_metrics_event), then the record
 * (lr_metrics_record); finally lr_metrics_finish fills the metrics of
 * lr_walk_result_t (records, used, RMSEs, convergence, kidnaps, penalty,
 * flips, final errors).  Definitions: tools/cli/cmd_simulate.c. */
struct lr_rec;

typedef struct {
    int sym;                      /* the field is symmetric */
    int half_known;               /* after the events fed so far */
    struct lr_rec *rec;           /* malloc'd, grows */
    long n, cap;
    int n_kid;
    long kid_rec[LR_MAX_KIDNAPS], kid_end[LR_MAX_KIDNAPS];   /* -1: open */
    double kid_t[LR_MAX_KIDNAPS], kid_end_t[LR_MAX_KIDNAPS];
    lr_kidnap_end_t kid_why[LR_MAX_KIDNAPS];
    long i_penalty;               /* first record with a placement, -1 */
    double last_pos_err, last_head_err;
} lr_metrics_t;

int lr_metrics_init(lr_metrics_t *m, int symmetric);
void lr_metrics_free(lr_metrics_t *m);
/* One simulator step's events (SIM_EV_* bits; slips ignored) at t_s, taken
 * in the order unpenalized, kidnap, penalized; they belong to the next
 * record. */
void lr_metrics_event(lr_metrics_t *m, unsigned events, double t_s);
/* One record: the estimate against the truth (integers as the simulator
 * gives them).  Errors in *pos_err_mm / *head_err_deg (may be NULL);
 * -1 when out of memory, else the record's index. */
long lr_metrics_record(lr_metrics_t *m, double t_s, const fl_loc_estimate_t *est,
                       int32_t truth_x_mm, int32_t truth_y_mm, fl_angle_t truth_heading,
                       double *pos_err_mm, double *head_err_deg);
void lr_metrics_finish(lr_metrics_t *m, lr_walk_result_t *res);

/* The per-record line of simulate and replay ("step K T_S est ...", with
 * the newline) and the "#  obs ..." lines (--print-obs). */
void lr_print_step(FILE *f, uint32_t step, double t_s, const fl_loc_estimate_t *est,
                   int32_t truth_x_mm, int32_t truth_y_mm, fl_angle_t truth_heading,
                   double pos_err_mm, double head_err_deg);
void lr_print_obs(FILE *f, const fl_obs_list_t *ol);
/* "# vision ..." lines of the per-kind diagnosis. */
void lr_walk_print_vdiag(FILE *f, const lr_walk_result_t *res);

#endif
