/*
 * tools/loc/stream.h - localizer input streams: the exact inputs a walk
 * gives a localizer (predict, penalty reset and update calls, in order,
 * with every integer as the localizer received it) and the truth per
 * record, as a versioned text file (format: docs/STREAM.md).  Written by
 * `fieldloc simulate --export-stream FILE` (lr_walk_opts_t.stream), read
 * back by `fieldloc replay --stream FILE`, which runs any catalogue
 * localizer on those inputs and prints what simulate prints.  Host only.
 *
 * The writer functions print one line each (ls_write_update: the update
 * line and its observation lines).  The reader is strict: an unknown
 * keyword, a wrong number of tokens, a number that does not parse or is
 * outside its type or range, a record index out of sequence, an
 * observation line outside an update, a missing header key, or a missing
 * or wrong "end" line is an error "line N: ...".
 */
#ifndef FL_TOOLS_STREAM_H
#define FL_TOOLS_STREAM_H

#include "loc/locrun.h"

#include <stdint.h>
#include <stdio.h>

#define LS_VERSION 1

/* ---- writer ---------------------------------------------------------------- */

/* Header: version line, scenario, field, camera, seed, mode, every,
 * frame_hz, period_s, post_sides, prior_half, penalty_x_mm. */
void ls_write_header(FILE *f, const sim_scenario_t *sc, int frames, int every, int post_sides,
                     int prior_half);
/* "record K STEP T_MS X_MM Y_MM HEADING HEADING_DEG" (the truth). */
void ls_write_record(FILE *f, long index, uint32_t step, int32_t t_ms, int32_t x_mm,
                     int32_t y_mm, fl_angle_t heading);
/* The event lines of one simulator step (SIM_EV_* bits; slips are not
 * written): unpenalized, kidnap, penalized, in that order; x, y, heading:
 * the truth after the step. */
void ls_write_events(FILE *f, unsigned events, uint32_t step, int32_t t_ms, int32_t x_mm,
                     int32_t y_mm, fl_angle_t heading);
void ls_write_predict(FILE *f, int32_t dx_mm, int32_t dy_mm, fl_angle_t dtheta);
void ls_write_reset_penalty(FILE *f, int32_t x_mm, int32_t pos_unc_mm, fl_angle_t heading_unc);
/* view NULL: the update had none ("noview"). */
void ls_write_update(FILE *f, const fl_obs_list_t *obs, const fl_obs_view_t *view);
void ls_write_end(FILE *f, long records);

/* ---- reader ---------------------------------------------------------------- */

typedef enum { LS_OP_PREDICT = 0, LS_OP_RESET_PENALTY = 1, LS_OP_UPDATE = 2 } ls_op_kind_t;

typedef struct {
    ls_op_kind_t kind;
    int32_t a, b;                 /* predict: dx, dy; reset: x, pos_unc */
    fl_angle_t angle;             /* predict: dtheta; reset: heading_unc */
    uint32_t obs0;                /* update: first observation in obs[] */
    uint16_t n_obs, dropped;      /* update: list.n, list.dropped */
    int has_view;                 /* update: 0 = noview (NULL) */
    fl_obs_view_t view;
} ls_op_t;

typedef struct {
    unsigned bits;                /* one of SIM_EV_UNPENALIZED, _KIDNAP,
                                     _PENALIZED */
    uint32_t step;
    int32_t t_ms, x_mm, y_mm;
    fl_angle_t heading;
} ls_event_t;

typedef struct {
    uint32_t step;
    int32_t t_ms, x_mm, y_mm;     /* truth */
    fl_angle_t heading;
    uint32_t ev0, n_ev;           /* events[ev0 .. ev0 + n_ev) */
    uint32_t op0, n_op;           /* ops[op0 .. op0 + n_op) */
    int line;
} ls_record_t;

typedef struct {
    /* header */
    int version;
    char scenario[64];
    const fl_field_t *field;
    const fl_camera_model_t *camera;
    uint64_t seed;
    int frames;                   /* mode: 1 frames, 0 features */
    int every;
    double frame_hz, period_s;
    int post_sides;
    int prior_half;               /* -1, 1, 0: none */
    int32_t penalty_x_mm;
    /* body (malloc'd) */
    ls_record_t *rec;
    ls_event_t *ev;
    ls_op_t *op;
    fl_obs_t *obs;
    long n_rec, n_ev, n_op, n_obs;
    long cap_rec, cap_ev, cap_op, cap_obs;
} ls_stream_t;

/* Read and parse a stream file.  0 on success; -1 with "PATH: line N:
 * WHY" (or "PATH: WHY") in err and *s empty otherwise. */
int ls_load(const char *path, ls_stream_t *s, char *err, int err_len);
/* The same from an open file (name used in messages). */
int ls_read(FILE *f, const char *name, ls_stream_t *s, char *err, int err_len);
void ls_free(ls_stream_t *s);

/* Run loc (params: the block given to lr_init, NULL: defaults) on the
 * stream's inputs, in order: set_prior_half, then per record its events
 * (metrics only: the localizer is told what the ops say), its ops, the
 * estimate.  The per-record "step" lines (and with print_obs the "#  obs"
 * lines) go to steps (NULL: none), as simulate prints them; res gets the
 * metrics (steps = the last record's step + 1; no vision diagnosis, no
 * times).  0, or -1 with a message. */
int ls_replay(const ls_stream_t *s, const fl_localizer_t *loc, const void *params, FILE *steps,
              int print_obs, lr_walk_result_t *res, char *err, int err_len);

#endif
