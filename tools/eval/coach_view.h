/*
 * tools/eval/coach_view.h - the coach's frame as `fieldloc coach` shows it:
 * the fitted homography as a plain 3 x 3 matrix, the top view of the field
 * (the frame warped onto the field plane, seed 003's "true perspective
 * image", figure 4) with the field lines drawn and the feet marked, and the
 * whole command path (points file -> fl_homog_fit -> fl_coach_frame ->
 * printout and picture), callable without the CLI for the tests.  Host
 * only (double, malloc).
 *
 * Top view geometry: the field's carpet at mm_per_px (default 20 mm per
 * pixel: spl2016 gives 521 x 371 pixels), +x to the right, +y up, the
 * field centre in the middle.  Each top-view pixel is the field point at
 * its centre mapped into the frame by fl_homog_field_to_image and sampled
 * bilinearly; points beyond the frame or the horizon are dark grey.
 */
#ifndef FL_TOOLS_COACH_VIEW_H
#define FL_TOOLS_COACH_VIEW_H

#include "fieldloc/fieldloc.h"
#include "fieldloc/homography.h"
#include "io/ppm.h"

#include <stdio.h>

#define COACH_TOP_MM_PER_PX 20

/* image -> field as a 3 x 3 matrix in pixels (pixel-centre convention) and
 * mm, row major, scaled so that m[8] = 1 (or, when m[8] is near 0, so
 * that the largest |entry| is 1).  0 on success, -1 when h is not fitted. */
int coach_homog_matrix(const fl_homog_t *h, double m[9]);

/* Top view of img (RGB888, w x h) through h.  0 on success (out->rgb
 * malloc'd), -1 on bad input. */
int coach_topview(const fl_homog_t *h, const host_image_t *img, const fl_field_t *f,
                  int mm_per_px, host_image_t *out);
/* Field point -> top-view pixel (double, pixel centres) of a picture made
 * by coach_topview with the same field and scale. */
void coach_topview_px(const fl_field_t *f, int mm_per_px, double x_mm, double y_mm, double *u,
                      double *v);
/* The field's lines and centre circle over a top view (white, 1 px). */
void coach_topview_lines(host_image_t *top, const fl_field_t *f, int mm_per_px);
/* A foot: a ring in the jersey colour (red / blue, else yellow) with a dark
 * edge and a cross at the point. */
void coach_mark(host_image_t *im, double u, double v, fl_color_t team);

/* The command's inputs. */
typedef struct {
    const char *image;        /* frame: PPM (P6), or the FLRAW container of
                                 a YUYV422 / planar frame (render.h) */
    const char *points;       /* points file (world/coach_scene.h) */
    const char *background;   /* empty-field frame (the same kinds), or NULL */
    const char *field;        /* field name, default "spl2016" */
    const char *out;          /* picture (.png: PNG, else PPM), or NULL */
    int mm_per_px;            /* top view scale, 0: COACH_TOP_MM_PER_PX */
    long repeat;              /* fl_coach_frame runs on the frame (for
                                 callgrind: tools/bench/callgrind_coach.sh);
                                 0 or 1: once */
} coach_cli_opts_t;

/* Run `fieldloc coach`: prints to out, errors as one line in err ("what is
 * wrong"), returns the exit status: 0 done (maybe 0 feet), 1 the frame
 * refused by the coach path (no field, size), 2 bad input (a file missing
 * or unreadable, a bad points line, unknown field, too few or degenerate
 * points, a homography the coach refuses). */
int coach_cli_run(const coach_cli_opts_t *o, FILE *out, char *err, int err_len);

#endif /* FL_TOOLS_COACH_VIEW_H */
