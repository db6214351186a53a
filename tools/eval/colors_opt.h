/*
 * tools/eval/colors_opt.h - the `--colors default|auto|FILE` option every
 * command that runs vision shares (one parser, one policy).
 *
 *   default   the 2013 UvA boxes (fl_color_params_default), today's
 *             behaviour
 *   auto      the field colour from the frame: fl_color_estimate on the
 *             first frame (below its horizon), fl_color_auto_params, and
 *             fl_color_track after every frame of a sequence or walk
 *             (fieldloc/color_auto.h); no yellow class on a field with
 *             white goals
 *   FILE      a `fieldloc-colors 1` file (`fieldloc colors`, `fieldloc
 *             calibrate-colors`): the defaults with its keys over them;
 *             a file with field_auto 1 is tracked per frame as well
 * Without the option (policy, colors_opt_resolve): auto on fields whose
 * goals are not yellow or sky-blue (spl2020) and on real frames that are
 * not the UvA 2013 set (a path under a realdata folder whose name does
 * not start with IntelligentRoboticsLab_); default on the coloured-goal
 * fields (spl2013, uva2013, aibo2004), so their outputs are unchanged.
 */
#ifndef FL_TOOLS_COLORS_OPT_H
#define FL_TOOLS_COLORS_OPT_H

#include "fieldloc/fieldloc.h"

#include <stdio.h>

typedef enum {
    COLORS_UNSET = 0,
    COLORS_DEFAULT,
    COLORS_AUTO,
    COLORS_FILE
} colors_mode_t;

typedef struct {
    colors_mode_t mode;
    const char *path;           /* COLORS_FILE */
    fl_color_params_t params;   /* COLORS_FILE: as read; else defaults */
} colors_opt_t;

/* Parse the option's value (a file is read now).  0, or 2 after one line
 * on stderr "fieldloc CMD: FILE:LINE: reason". */
int colors_opt_parse(const char *cmd, const char *arg, colors_opt_t *o);

/* The policy above for an unset option (field may be NULL, image_path
 * may be NULL); a set one is kept. */
void colors_opt_resolve(colors_opt_t *o, const fl_field_t *field, const char *image_path);

/* Build t for the first frame: the defaults, the file's params, or (auto)
 * the estimate of img below cam's horizon (cam may be NULL) with
 * auto_yellow from the field's goal colour (field NULL: today's SPL field,
 * white goals, no yellow class).  est (may be NULL) receives
 * the estimate.  0; -1 when the tables were refused (cannot happen for a
 * parsed file); 1 when auto found no carpet (default boxes used). */
int colors_opt_setup(const colors_opt_t *o, fl_color_table_t *t, const fl_field_t *field,
                     const fl_image_t *img, const fl_camera_t *cam, fl_color_estimate_t *est);

/* After a frame: fl_color_track on the scanner's field estimate (a no-op
 * unless the tables are carpet-relative).  1 when rebuilt. */
int colors_opt_track(fl_color_table_t *t, const fl_scan_t *scan);

/* One comment line per fact: the mode, (auto) the carpet estimate, and
 * the effective boxes of t ("# colors ..."). */
void colors_print_stats(FILE *out, const colors_opt_t *o, const fl_color_table_t *t,
                        const fl_color_estimate_t *est);

/* The name of a mode, for messages ("default", "auto", "file"). */
const char *colors_opt_name(const colors_opt_t *o);

#endif
