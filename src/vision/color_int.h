/*
 * src/vision/color_int.h - shared between color.c (fl_color_init's rules)
 * and color_file.c (the colour text, which reports a broken rule at the
 * line of the key it concerns).
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
    FL_COLOR_KEYS
} fl_color_key_t;

/* The first rule of fl_color_init that p breaks: its key, and *why (when
 * why is not NULL) a static reason naming it; -1 ("" in *why) when p is
 * valid.  p not NULL. */
int32_t fl_color_int_fault(const fl_color_params_t *p, const char **why);

#endif /* FIELDLOC_COLOR_INT_H */
