/*
 * tools/loc/reliab.h - the reliability diagram of a localizer: simulated
 * walks (lr_walk_run) whose every record is scored against the truth (the
 * plain truth, not modulo the symmetry: within FL_LOC_GOOD_MM and
 * FL_LOC_GOOD_DEG, localizer.h), binned by reported reliability, and the
 * contract of localizer.h checked: for every reported value r, the share
 * of records with reliability >= r that are good is at least r.  Used by
 * `fieldloc reliability` and by the host test loc.reliability_contract.
 * Host only (double, malloc).
 */
#ifndef FL_TOOLS_RELIAB_H
#define FL_TOOLS_RELIAB_H

#include "loc/locrun.h"

#include <stdio.h>

/* One record of a walk: what the estimate says and whether it is good. */
typedef struct {
    uint8_t mode;                 /* 0 features, 1 frames */
    uint8_t field;                /* index in the caller's field list */
    uint16_t seed;
    fl_loc_estimate_t est;
    double pos_err_mm, head_err_deg;   /* against the plain truth */
    int good;
} rb_rec_t;

typedef struct {
    rb_rec_t *rec;                /* malloc'd */
    long n, cap;
} rb_set_t;

/* Run one walk and append its records.  frames: rendered frames through
 * vision (obs_cache as lr_walk_opts_t.obs_cache, NULL: render).  max_steps
 * < 0: the whole walk.  0 on success, -1 with a message in err. */
int rb_walk(rb_set_t *set, const fl_localizer_t *loc, const char *field, int field_index,
            long seed, int frames, const char *obs_cache, long max_steps, char *err,
            int err_len);
void rb_free(rb_set_t *set);

/* The contract over the records of mode (-1: all): the smallest margin
 * share(reliability >= r) - r over every reported r > 0 (positive or 0:
 * met), the r where it is smallest (*worst_r), and the records counted. */
double rb_contract(const rb_set_t *set, int mode, double *worst_r, long *count);

/* The diagram of mode (-1: all): ten bins of reported reliability (count,
 * share good), the cumulative check at r = 0.1 ... 0.9 and the exact
 * worst case; returns 0 when the contract holds, 1 when it fails. */
int rb_print(FILE *f, const rb_set_t *set, int mode, const char *title);

/* One TSV line per record (header first): the estimate's fields, the
 * errors and good; for fitting the calibration (tools/build/fit_reliability.py). */
void rb_dump(FILE *f, const rb_set_t *set, const char *const *field_names);

#endif
