/*
 * fieldloc/field.h - field geometries as data.  Every landmark a detector
 * can report, every line a renderer draws, and the carpet the localizer
 * covers live in one const struct per field; no stage scatters field
 * constants.
 *
 * Field frame: origin at the centre, x toward the opponent goal, y left,
 * millimetres, line centres.  Headings and arm directions are binary angles
 * counter-clockwise from +x.
 */
#ifndef FIELDLOC_FIELD_H
#define FIELDLOC_FIELD_H

#include "fieldloc/common.h"
#include "fieldloc/fixed.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    FL_LM_L = 0,            /* L crossing (2 arms) */
    FL_LM_T = 1,            /* T crossing (3 arms) */
    FL_LM_X = 2,            /* X crossing (4 arms), e.g. halfway line x circle */
    FL_LM_PENALTY_MARK = 3, /* penalty mark (a small cross: 4 arms) */
    FL_LM_CENTRE_MARK = 4,  /* centre mark (4 arms) */
    FL_LM_POST = 5,         /* goal post foot (centre of the post base) */
    FL_LM_CENTRE_CIRCLE = 6,/* centre of the centre circle */
    FL_LM_BEACON = 7,       /* colored beacon (AIBO corners) or striped
                               landmark pole (hl3x2; color == color2) */
    /* Seed 004's corner features (its section 2): pairs of labelled
     * corners of white on carpet.  They live in fl_field_t.features, not
     * in landmarks (see there). */
    FL_LM_CORNER_C = 8,     /* C: an open corner next to a closed one (an L
                               of painted lines; arms and orientation as L) */
    FL_LM_CORNER_TFIELD = 9,/* T-field: two closed corners (a T of field
                               lines away from the nets, or an X: arms as
                               the T or X it is) */
    FL_LM_CORNER_TNET = 10, /* T-net: a closed corner next to a net-closed
                               one (a box side meeting the goal line beside
                               the net; arms as T) */
    FL_LM_NET = 11,         /* a goal net: goal centre on the goal line,
                               color = goal colour, goal = +1 / -1 */
    FL_LM_KIND_COUNT = 12
} fl_landmark_kind_t;

/* Goal post side, as seen by a robot on the field facing that goal. */
typedef enum {
    FL_SIDE_UNKNOWN = 0,
    FL_SIDE_LEFT = 1,
    FL_SIDE_RIGHT = 2
} fl_side_t;

typedef enum {
    FL_COLOR_NONE = 0,
    FL_COLOR_WHITE = 1,
    FL_COLOR_YELLOW = 2,
    FL_COLOR_SKYBLUE = 3,
    FL_COLOR_PINK = 4,
    FL_COLOR_RED = 5,       /* jerseys (SPL team colours; obs.h reports) */
    FL_COLOR_BLUE = 6
} fl_color_t;

#define FL_FIELD_MAX_ARMS 4

/*
 * One landmark.  Arms (L/T/X crossings and marks): the directions, binary
 * angles CCW from +x, of the painted lines leaving the point (for the X on
 * the halfway line x centre circle: the halfway line both ways and the
 * circle's tangent both ways; marks: their small axis-aligned cross).
 * Unused arm slots are 0; posts, circle and beacons have n_arms 0.
 */
typedef struct {
    fl_landmark_kind_t kind;
    int32_t x_mm;
    int32_t y_mm;
    uint8_t n_arms;                     /* lines leaving the point: L 2, T 3, X 4 */
    fl_angle_t arm[FL_FIELD_MAX_ARMS];  /* direction of each arm (unused: 0) */
    fl_side_t side;                     /* posts: left/right facing the goal */
    fl_color_t color;                 /* posts and beacons */
    int8_t goal;                        /* posts: +1 goal at +x, -1 at -x; else 0 */
    fl_color_t color2;                /* added: beacons: lower color band
                                           (color is the upper band);
                                           FL_COLOR_NONE for every other kind */
} fl_landmark_t;

/* A straight painted line, centre line of the paint, field frame.  Every
 * boundary, halfway and box line is listed; the centre circle is given by
 * circle_radius_mm and the marks' small crosses by mark_size_mm instead. */
typedef struct {
    int32_t x0_mm, y0_mm, x1_mm, y1_mm;
} fl_field_line_t;

typedef struct {
    const char *name;            /* "spl2013", "uva2013", "spl2020", "aibo2004",
                                    "spl2016", "hl3x2"
                                    (aibo2004, hl3x2: partly unverified numbers,
                                    sources and uncertainty in src/model/field.c) */
    int32_t length_mm;           /* between goal line centres (x extent) */
    int32_t width_mm;            /* between touchline centres (y extent) */
    int32_t line_width_mm;
    int32_t border_mm;           /* carpet beyond the lines, each side */
    int32_t circle_radius_mm;    /* centre circle, to the line centre */
    int32_t penalty_area_depth_mm, penalty_area_width_mm;   /* 0 if none */
    int32_t goal_area_depth_mm, goal_area_width_mm;         /* 0 if none */
    int32_t penalty_mark_x_mm;   /* |x| of the penalty marks, 0 if none */
    int32_t mark_size_mm;        /* penalty/centre mark cross size, 0 if none */
    int32_t goal_width_mm;       /* post centre to post centre */
    int32_t post_diameter_mm, post_height_mm;
    fl_color_t goal_color[2];  /* [0] goal at -x, [1] goal at +x */
    bool symmetric;              /* true when the field looks the same turned
                                    by 180 degrees (identical goals) */
    const fl_landmark_t *landmarks;
    uint16_t n_landmarks;
    const fl_field_line_t *lines;
    uint16_t n_lines;
    /* added: colored beacons (AIBO fields) or landmark poles (hl3x2),
     * 0 when the field has none */
    int32_t beacon_diameter_mm, beacon_height_mm;
    /* added: seed 004's corner features (FL_LM_CORNER_C, _TFIELD, _TNET,
     * FL_LM_NET), NULL / 0 for a field without them.  A list of their own,
     * not part of landmarks: the L/T/X vision path, negative information
     * (which iterates landmarks) and simulate's L/T/X feature mode see the
     * field as before; fl_field_count_kind / fl_field_nth_kind look here
     * for these kinds, so a localizer that enumerates candidates through
     * them gets the features with no table of its own. */
    const fl_landmark_t *features;
    uint16_t n_features;
} fl_field_t;

/* Carpet extent, derived: |x| <= length/2 + border, |y| <= width/2 + border
 * (length/2 truncated toward zero; saturated to int32; NULL gives 0). */
int32_t fl_field_carpet_half_x_mm(const fl_field_t *f);
int32_t fl_field_carpet_half_y_mm(const fl_field_t *f);
/* The catalogue: "spl2013", "uva2013", "spl2020", "aibo2004", "spl2016",
 * "hl3x2" (in that order; see src/model/field.c for every number and its source).  Names are
 * compared exactly (case-sensitive); NULL name gives NULL. */
const fl_field_t *fl_field_find(const char *name);  /* NULL if unknown */
size_t fl_field_count(void);
const fl_field_t *fl_field_at(size_t i);            /* NULL if out of range */

/* Number of landmarks of a kind, and the i-th of them (NULL if none), in
 * table order: landmarks for kinds up to FL_LM_BEACON, features for
 * FL_LM_CORNER_C ... FL_LM_NET.  NULL field or an unknown kind gives 0 /
 * NULL. */
uint16_t fl_field_count_kind(const fl_field_t *f, fl_landmark_kind_t kind);
const fl_landmark_t *fl_field_nth_kind(const fl_field_t *f,
                                       fl_landmark_kind_t kind, uint16_t i);

/* True for seed 004's feature kinds (FL_LM_CORNER_C ... FL_LM_NET), the
 * kinds listed in fl_field_t.features. */
bool fl_landmark_kind_is_feature(fl_landmark_kind_t kind);

/* Landmarks and features as one list: index i < n_landmarks is
 * landmarks[i], i - n_landmarks is features[i - n_landmarks] (for
 * localizers that keep landmark ids).  NULL field gives 0 / NULL; an
 * index out of range gives NULL. */
uint16_t fl_field_n_all(const fl_field_t *f);
const fl_landmark_t *fl_field_all_at(const fl_field_t *f, uint16_t i);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_FIELD_H */
