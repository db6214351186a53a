/*
 * src/vision/color_int.h - shared between color.c (fl_color_init's rules,
 * the table build), color_file.c (the colour text, which reports a broken
 * rule at the line of the key it concerns) and color_auto.c (the field
 * colour from the frame, which rebuilds the tables).
 */
#ifndef FIELDLOC_COLOR_INT_H
#define FIELDLOC_COLOR_INT_H

#include "fieldloc/color.h"

/* The keys of the colour text, in file order; also what a broken rule
 * concerns. */
typedef enum {
    FL_COLOR_KEY_GREEN = 0,
    FL_COLOR_KEY_GREEN_SAT_REF,
    FL_COLOR_KEY_WHITE,
    FL_COLOR_KEY_WHITE_CONTRAST,
    FL_COLOR_KEY_WHITE_LINE,
    FL_COLOR_KEY_YELLOW,
    FL_COLOR_KEY_ADAPT_MAX_HUE,
    FL_COLOR_KEY_FIELD_AUTO,
    FL_COLOR_KEY_FIELD_HUE,
    FL_COLOR_KEY_FIELD_VAL,
    FL_COLOR_KEY_AUTO_MARGIN,
    FL_COLOR_KEY_AUTO_SHADOW,
    FL_COLOR_KEY_AUTO_YELLOW,
    FL_COLOR_KEYS
} fl_color_key_t;

/* The first rule of fl_color_init that p breaks: its key, and *why (when
 * why is not NULL) a static reason naming it; -1 ("" in *why) when p is
 * valid.  p not NULL. */
int32_t fl_color_int_fault(const fl_color_params_t *p, const char **why);

/* Rebuild every table from t's effective boxes (green, white, yellow,
 * yellow_off).  color.c. */
void fl_color_int_build(fl_color_table_t *t);

/* The tracker's state from t->params (the carpet the boxes were made
 * for), yellow_off from the params.  color_auto.c. */
void fl_color_int_track_reset(fl_color_table_t *t);

#endif /* FIELDLOC_COLOR_INT_H */
