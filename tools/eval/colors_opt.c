/*
 * tools/eval/colors_opt.c - the shared --colors option (colors_opt.h).
 */
#include "eval/colors_opt.h"
#include "eval/detect.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int colors_opt_parse(const char *cmd, const char *arg, colors_opt_t *o)
{
    char err[512];
    memset(o, 0, sizeof *o);
    fl_color_params_default(&o->params);
    if (!strcmp(arg, "default")) {
        o->mode = COLORS_DEFAULT;
        return 0;
    }
    if (!strcmp(arg, "auto")) {
        o->mode = COLORS_AUTO;
        return 0;
    }
    o->mode = COLORS_FILE;
    o->path = arg;
    if (det_colors_load(arg, &o->params, err, (int)sizeof err) != 0) {
        fprintf(stderr, "fieldloc %s: %s\n", cmd, err);
        return 2;
    }
    return 0;
}

static int colors_goals_coloured(const fl_field_t *f)
{
    int k;
    for (k = 0; k < 2; k++)
        if (f->goal_color[k] == FL_COLOR_YELLOW || f->goal_color[k] == FL_COLOR_SKYBLUE)
            return 1;
    return 0;
}

void colors_opt_resolve(colors_opt_t *o, const fl_field_t *field, const char *image_path)
{
    const char *base;
    if (o->mode != COLORS_UNSET)
        return;
    o->mode = COLORS_DEFAULT;
    fl_color_params_default(&o->params);
    if (field != NULL && !colors_goals_coloured(field)) {
        o->mode = COLORS_AUTO;
        return;
    }
    if (image_path == NULL || strstr(image_path, "realdata/") == NULL)
        return;
    base = strrchr(image_path, '/');
    base = base ? base + 1 : image_path;
    if (strncmp(base, "IntelligentRoboticsLab_", 23) != 0)
        o->mode = COLORS_AUTO;
}

int colors_opt_setup(const colors_opt_t *o, fl_color_table_t *t, const fl_field_t *field,
                     const fl_image_t *img, const fl_camera_t *cam, fl_color_estimate_t *est)
{
    fl_color_params_t p = o->params;
    fl_color_estimate_t *e = est;
    int rc = 0;
    if (o->mode == COLORS_AUTO) {
        if (e == NULL)
            e = malloc(sizeof *e);
        if (e == NULL)
            return -1;
        fl_color_params_default(&p);
        /* no field: today's SPL field, white goals */
        p.auto_yellow = (uint8_t)(field != NULL && colors_goals_coloured(field));
        if (img == NULL || fl_color_estimate(img, cam, e) != FL_OK ||
            fl_color_auto_params(e, &p) != FL_OK) {
            fl_color_params_default(&p);
            rc = 1;
        }
        if (e != est)
            free(e);
    }
    if (fl_color_init(t, &p) != FL_OK)
        return -1;
    return rc;
}

int colors_opt_track(fl_color_table_t *t, const fl_scan_t *scan)
{
    return fl_color_track(t, &scan->field) == 1;
}

const char *colors_opt_name(const colors_opt_t *o)
{
    switch (o->mode) {
    case COLORS_AUTO: return "auto";
    case COLORS_FILE: return "file";
    default: return "default";
    }
}

static void colors_box(FILE *out, const char *name, const fl_hsv_box_t *b)
{
    fprintf(out, " %s %d..%d S %d..%d V %d..%d", name, b->h_lo, b->h_hi, b->s_lo, b->s_hi,
            b->v_lo, b->v_hi);
}

void colors_print_stats(FILE *out, const colors_opt_t *o, const fl_color_table_t *t,
                        const fl_color_estimate_t *est)
{
    fprintf(out, "# colors %s", colors_opt_name(o));
    if (o->mode == COLORS_AUTO && est != NULL)
        fprintf(out, ": carpet %s hue %d (%d..%d) S p5 %d med %d V p2 %d med %d p98 %d "
                "(%d of %d saturated samples)",
                est->n > 0 ? "found" : "NOT found", est->hue, est->hue_lo, est->hue_hi,
                est->s_p5, est->s_med, est->v_p2, est->v_med, est->v_p98, (int)est->n,
                (int)est->n_sat);
    fprintf(out, "\n# boxes:");
    colors_box(out, "green", &t->green);
    colors_box(out, "white", &t->white);
    if (t->yellow_off)
        fprintf(out, " yellow off");
    else
        colors_box(out, "yellow", &t->yellow);
    fprintf(out, "\n");
}
