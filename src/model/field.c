/*
 * src/model/field.c - field geometries as data: one static const fl_field_t per
 * field, with every landmark (position, crossing arms, post side, colors)
 * and every straight painted line, plus lookup helpers.
 *
 * Algorithm: none at run time; the tables are written with small macros
 * from each field's defining dimensions (half length HX, half width HY, box
 * fronts and sides, circle radius), so that a crossing and the lines that
 * make it come from the same numbers.  Lookups are linear scans.
 * Invariant: every L/T/X lies where the listed lines (and the circle) meet,
 * and its arms are exactly the directions of the painted lines leaving it
 * (proved by host_tests/test_field.c, which recomputes the crossings from
 * the line list); so do seed 004's corner features of aibo2004 (a list of
 * their own, fl_field_t.features; field.features_from_lines).  Frames and units: see include/fieldloc/field.h.
 * Memory: about 4 kB of read-only tables, no mutable state, no stack use
 * beyond a few words.  Cost: find O(fields * name length); count_kind and
 * nth_kind O(landmarks) (at most 33 per field) or O(features) (18).
 *
 * Sources of the numbers (mm, line centres):
 *  spl2013  DESIGN.md "Fields" (SPL 2013 rules as used by seed 000):
 *           lines 9000 x 6000, line 50, border 700, circle d 1500, penalty
 *           area 600 x 2200, penalty marks x = +-2700, 4 yellow posts
 *           (d 100, h 800) at (+-4525, +-800).  Mark crosses 100 mm.
 *  uva2013  DESIGN.md: UvA lab field (SPL 2012 proportions): lines 6000 x
 *           4000, border 700, line 50, penalty area 600 x 2200, marks at
 *           x = +-1200, circle d 1200, yellow posts (d 100, h 800) at
 *           (+-3000, +-700).
 *  spl2020  DESIGN.md: SPL since 2020: lines 9000 x 6000, goal area 600 x
 *           2200, penalty area 1650 x 4000, marks 1300 from the goal line
 *           (x = +-3200), circle d 1500, white posts (d 100, h 800) at
 *           (+-4525, +-800), border 700, line 50.
 *  spl2016  Seed 003's field (SPL 2015-2017 rules): the spl2013 lines and
 *           box (9000 x 6000, penalty area 600 x 2200, circle d 1500,
 *           border 700, line 50) with white goals, posts (d 100, h 800)
 *           at (+-4525, +-800), and the penalty marks 1300 mm from the goal
 *           line (x = +-3200).  Checked against a public SPL field
 *           dimensions file of that era (B-Human's fieldDimensions.cfg:
 *           xPosOpponentPenaltyArea 3900, yPosLeftPenaltyArea 1100,
 *           xPosOpponentPenaltyMark 3200, xPosOpponentGoalPost 4525).
 *           Seed 003 calls the 600 x 2200 box the "penalty area"; spl2020's
 *           has the same box as its goal area and a 1650 x 4000 penalty
 *           area around it, so the two models differ.
 *  aibo2004 Four-legged league 2004.  NOT verified against the 2004 rule
 *           book (no copy was available); each number's basis:
 *           - lines 4200 x 2700 (DESIGN.md; agrees with our recollection of
 *             the GermanTeam 2004 field model, groundline x = 2100,
 *             sideline y = 1350).  The boundary was the foot of a white
 *             wall; it is modelled as a boundary line (a detector sees the
 *             same white-on-green edge, seed 004's "T-field" is the halfway
 *             line meeting the wall).
 *           - border 150: seed 004 says the field is "approximately 4.5 m x
 *             3 m", read as the walled carpet 4500 x 3000 (+-100 mm).
 *             (Seed 004's 36 x 54 grid of 10 cm cells covers 3.6 x 5.4 m,
 *             more than that; a localizer may pad its grid.)
 *           - line width 25, centre circle diameter 300 (DESIGN.md; we
 *             half-remember a radius of 180 in GermanTeam code, perhaps of
 *             the 2005 field: uncertain).
 *           - goals 600 wide (post centres at y = +-300), 300 high, mouth on
 *             the goal line (posts at x = +-2100); post "diameter" 50 for
 *             the colored side panels' front edges (guess).
 *           - penalty area (goalie box) 650 deep x 1000 wide: seed 004's
 *             "T-net" corner (box line meets the goal line next to the net)
 *             puts the box sides close to the posts; +-150 mm uncertain.
 *           - no penalty or centre marks.
 *           - goal colors: sky-blue at -x (own goal), yellow at +x: seed
 *             004's goalkeeper faces "the opposite net (yellow)".
 *           - 4 beacons (seed 004: "four uniquely colored beacons"), the
 *             2004 arrangement being one at each corner (the earlier six
 *             had two more at the halfway line; 2005 moved them).  Placed
 *             at the wall corners (+-2250, +-1500).  Each is a cylinder
 *             (d 100, h 400, guessed) with a pink band and a band of the
 *             color of the nearer goal; our convention: pink on top on
 *             the +y side, pink below on the -y side, so all four differ.
 *  hl3x2    Seed 002's field: the RoboCup Humanoid League KidSize field
 *           of 2009-2012 scaled to 3000 x 2000 mm between line centres
 *           (seed 002: "3m x 2m", "a scaled down soccer field", yellow
 *           and blue goals, YBY and BYB poles "midway from the two goals
 *           just outside the field boundary").  The league field was
 *           6000 x 4000, so every length below is the league's halved.
 *           Each number's basis ("source" = a page found and read;
 *           "recollection" = from memory of the KidSize rule books of
 *           2009-2012, no copy of which was available, NOT verified):
 *           - lines 6000 x 4000 -> 3000 x 2000: recollection; the scale
 *             1/2 and seed 002's 3 m x 2 m agree (same 3:2 aspect).
 *           - line width 50 -> 25: recollection (every RoboCup field of
 *             that time used 5 cm lines).
 *           - border 700 -> 350: recollection (KidSize border strip at
 *             least 70 cm); a public field configuration of a 6 x 4 m
 *             humanoid field of 2009 has its carpet edge 700 beyond the
 *             lines (xPosOpponentFieldBorder 3700, groundline 3000).
 *             Carpet 3700 x 2700.
 *           - centre circle diameter 1200 -> radius 300: recollection.
 *           - goal area 600 deep x 2200 wide -> 300 x 1100 (the only box
 *             of that field, stored as the penalty area like spl2013's
 *             single box): recollection, +-100 mm (scaled) uncertain.
 *           - penalty mark 1800 from the goal line -> 900, so x = +-600;
 *             mark cross 100 -> 50; a centre mark: recollection.
 *           - goals: 1500 wide, crossbar 900 high, 500 deep: source (a
 *             2009 paper summarising the 2009 KidSize rules, IEEE Xplore
 *             document 5420187: "90cm of height for the crossbar", "150cm
 *             of width", "50cm of depth").  Scaled: goal_width 800 post
 *             centre to centre (1500 inner width + one 100 post, the SPL
 *             convention of spl2013's 1600), post height 450; post
 *             diameter 100 -> 50: recollection.  Posts 12 mm behind the
 *             goal line centre (their front at the line's inner edge, as
 *             spl2013's 4525 = 4500 + 50 - 25; 12.5 truncated).
 *           - goal colours: yellow at -x, sky-blue at +x (the league's
 *             goals were yellow and sky blue; seed 002 says "blue").
 *           - landmark poles: cylinder 200 diameter, three 200 high
 *             segments: source (the same 2009 summary: "a diameter of
 *             20cm", "three segments of 20cm height").  Scaled: diameter
 *             100, height 300, bands of 100.  Placement: on the halfway
 *             line extension (source: "at each side of the two
 *             intersection points between the touch line and the center
 *             line"), 400 outside the touchline centre -> 200, so y =
 *             +-1200: the distance is recollection.
 *           - which pole where: "the lowest and the highest segments are
 *             with the same color as the goal of its left side" (source,
 *             same summary): a robot on the field facing the +y pole has
 *             the -x (yellow) goal on its left, so YBY stands at +y and
 *             BYB at -y.  Stored as beacons, color = top band, color2 =
 *             bottom band: YBY (yellow, yellow), BYB (sky-blue, sky-blue).
 */
#include "fieldloc/field.h"

/* Arm directions, binary angles CCW from +x. */
#define A_E 0
#define A_N FL_ANGLE_90
#define A_W FL_ANGLE_180
#define A_S (-FL_ANGLE_90)

#define LM_(k, x, y, n, a0, a1, a2, a3, side, col, goal, col2)              \
    { (k), (x), (y), (n), { (a0), (a1), (a2), (a3) }, (side), (col), (goal), \
      (col2) }
#define LM_L(x, y, a, b) \
    LM_(FL_LM_L, x, y, 2, a, b, 0, 0, FL_SIDE_UNKNOWN, FL_COLOR_NONE, 0, FL_COLOR_NONE)
#define LM_T(x, y, a, b, c) \
    LM_(FL_LM_T, x, y, 3, a, b, c, 0, FL_SIDE_UNKNOWN, FL_COLOR_NONE, 0, FL_COLOR_NONE)
#define LM_CROSS4(k, x, y) \
    LM_(k, x, y, 4, A_E, A_N, A_W, A_S, FL_SIDE_UNKNOWN, FL_COLOR_NONE, 0, FL_COLOR_NONE)
#define LM_POINT(k, x, y, side, col, goal, col2) \
    LM_(k, x, y, 0, 0, 0, 0, 0, side, col, goal, col2)

/* The four outer corners of the lines rectangle |x| <= HX, |y| <= HY. */
#define CORNERS(HX, HY)                                                     \
    LM_L(-(HX), -(HY), A_E, A_N), LM_L(-(HX), (HY), A_E, A_S),              \
    LM_L((HX), -(HY), A_W, A_N), LM_L((HX), (HY), A_W, A_S)

/* A box in front of each goal: front line at |x| = BX, sides at |y| = BY
 * running to the goal line at |x| = HX.  4 L (front corners) and 4 T
 * (sides meeting the goal lines). */
#define BOX_CROSSINGS(HX, BX, BY)                                           \
    LM_L((BX), (BY), A_E, A_S), LM_L((BX), -(BY), A_E, A_N),                \
    LM_L(-(BX), (BY), A_W, A_S), LM_L(-(BX), -(BY), A_W, A_N),              \
    LM_T((HX), (BY), A_N, A_S, A_W), LM_T((HX), -(BY), A_N, A_S, A_W),      \
    LM_T(-(HX), (BY), A_N, A_S, A_E), LM_T(-(HX), -(BY), A_N, A_S, A_E)

/* Halfway line meeting the touchlines (T) and the centre circle (X). */
#define HALFWAY_CROSSINGS(HY, R)                                            \
    LM_T(0, (HY), A_E, A_W, A_S), LM_T(0, -(HY), A_E, A_W, A_N),            \
    LM_CROSS4(FL_LM_X, 0, (R)), LM_CROSS4(FL_LM_X, 0, -(R))

/* Posts of one goal at x = GX (sign included), goal = +1 or -1: the left
 * post seen facing the goal is at y = goal * GY. */
#define POSTS(GX, GY, goal, col)                                            \
    LM_POINT(FL_LM_POST, (GX), (goal) * (GY), FL_SIDE_LEFT, col, goal, FL_COLOR_NONE), \
    LM_POINT(FL_LM_POST, (GX), -(goal) * (GY), FL_SIDE_RIGHT, col, goal, FL_COLOR_NONE)

#define CIRCLE_CENTRE \
    LM_POINT(FL_LM_CENTRE_CIRCLE, 0, 0, FL_SIDE_UNKNOWN, FL_COLOR_NONE, 0, FL_COLOR_NONE)

/* Lines: the boundary rectangle and the halfway line. */
#define BOUNDARY_LINES(HX, HY)                                              \
    { -(HX), -(HY), (HX), -(HY) }, { -(HX), (HY), (HX), (HY) },             \
    { -(HX), -(HY), -(HX), (HY) }, { (HX), -(HY), (HX), (HY) },             \
    { 0, -(HY), 0, (HY) }
/* Lines of the two boxes of BOX_CROSSINGS: front, and both sides. */
#define BOX_LINES(HX, BX, BY)                                               \
    { (BX), -(BY), (BX), (BY) }, { (BX), (BY), (HX), (BY) },                \
    { (BX), -(BY), (HX), -(BY) },                                           \
    { -(BX), -(BY), -(BX), (BY) }, { -(BX), (BY), -(HX), (BY) },            \
    { -(BX), -(BY), -(HX), -(BY) }

#define COUNT_OF(a) ((uint16_t)(sizeof(a) / sizeof((a)[0])))

/* ---- spl2013 ------------------------------------------------------------ */

static const fl_landmark_t spl2013_lm[] = {
    CORNERS(4500, 3000),
    BOX_CROSSINGS(4500, 3900, 1100),
    HALFWAY_CROSSINGS(3000, 750),
    LM_CROSS4(FL_LM_PENALTY_MARK, 2700, 0),
    LM_CROSS4(FL_LM_PENALTY_MARK, -2700, 0),
    LM_CROSS4(FL_LM_CENTRE_MARK, 0, 0),
    POSTS(4525, 800, 1, FL_COLOR_YELLOW),
    POSTS(-4525, 800, -1, FL_COLOR_YELLOW),
    CIRCLE_CENTRE
};

static const fl_field_line_t spl2013_lines[] = {
    BOUNDARY_LINES(4500, 3000),
    BOX_LINES(4500, 3900, 1100)
};

/* ---- uva2013 ------------------------------------------------------------ */

static const fl_landmark_t uva2013_lm[] = {
    CORNERS(3000, 2000),
    BOX_CROSSINGS(3000, 2400, 1100),
    HALFWAY_CROSSINGS(2000, 600),
    LM_CROSS4(FL_LM_PENALTY_MARK, 1200, 0),
    LM_CROSS4(FL_LM_PENALTY_MARK, -1200, 0),
    LM_CROSS4(FL_LM_CENTRE_MARK, 0, 0),
    POSTS(3000, 700, 1, FL_COLOR_YELLOW),
    POSTS(-3000, 700, -1, FL_COLOR_YELLOW),
    CIRCLE_CENTRE
};

static const fl_field_line_t uva2013_lines[] = {
    BOUNDARY_LINES(3000, 2000),
    BOX_LINES(3000, 2400, 1100)
};

/* ---- spl2020 ------------------------------------------------------------ */

static const fl_landmark_t spl2020_lm[] = {
    CORNERS(4500, 3000),
    BOX_CROSSINGS(4500, 3900, 1100),    /* goal area 600 x 2200 */
    BOX_CROSSINGS(4500, 2850, 2000),    /* penalty area 1650 x 4000 */
    HALFWAY_CROSSINGS(3000, 750),
    LM_CROSS4(FL_LM_PENALTY_MARK, 3200, 0),
    LM_CROSS4(FL_LM_PENALTY_MARK, -3200, 0),
    LM_CROSS4(FL_LM_CENTRE_MARK, 0, 0),
    POSTS(4525, 800, 1, FL_COLOR_WHITE),
    POSTS(-4525, 800, -1, FL_COLOR_WHITE),
    CIRCLE_CENTRE
};

static const fl_field_line_t spl2020_lines[] = {
    BOUNDARY_LINES(4500, 3000),
    BOX_LINES(4500, 3900, 1100),
    BOX_LINES(4500, 2850, 2000)
};

/* ---- spl2016 ------------------------------------------------------------ */

static const fl_landmark_t spl2016_lm[] = {
    CORNERS(4500, 3000),
    BOX_CROSSINGS(4500, 3900, 1100),
    HALFWAY_CROSSINGS(3000, 750),
    LM_CROSS4(FL_LM_PENALTY_MARK, 3200, 0),
    LM_CROSS4(FL_LM_PENALTY_MARK, -3200, 0),
    LM_CROSS4(FL_LM_CENTRE_MARK, 0, 0),
    POSTS(4525, 800, 1, FL_COLOR_WHITE),
    POSTS(-4525, 800, -1, FL_COLOR_WHITE),
    CIRCLE_CENTRE
};

/* spl2016's painted lines are spl2013's (only the marks and goals moved):
 * the catalogue entry uses spl2013_lines. */

/* ---- aibo2004 (numbers and their uncertainty: file top) ----------------- */

static const fl_landmark_t aibo2004_lm[] = {
    CORNERS(2100, 1350),
    BOX_CROSSINGS(2100, 1450, 500),
    HALFWAY_CROSSINGS(1350, 150),
    POSTS(2100, 300, 1, FL_COLOR_YELLOW),
    POSTS(-2100, 300, -1, FL_COLOR_SKYBLUE),
    CIRCLE_CENTRE,
    LM_POINT(FL_LM_BEACON, 2250, 1500, FL_SIDE_UNKNOWN, FL_COLOR_PINK, 0, FL_COLOR_YELLOW),
    LM_POINT(FL_LM_BEACON, 2250, -1500, FL_SIDE_UNKNOWN, FL_COLOR_YELLOW, 0, FL_COLOR_PINK),
    LM_POINT(FL_LM_BEACON, -2250, 1500, FL_SIDE_UNKNOWN, FL_COLOR_PINK, 0, FL_COLOR_SKYBLUE),
    LM_POINT(FL_LM_BEACON, -2250, -1500, FL_SIDE_UNKNOWN, FL_COLOR_SKYBLUE, 0, FL_COLOR_PINK)
};

static const fl_field_line_t aibo2004_lines[] = {
    BOUNDARY_LINES(2100, 1350),
    BOX_LINES(2100, 1450, 500)
};

/* Seed 004's corner features on this model (its section 2; the list is
 * recomputed from the lines, the circle and the posts by
 * host_tests/test_field.c).  Seed 004 names where each type occurs (C "in
 * the goal keeper area", T-field "the intersection of the walls and the
 * inner field lines", T-net "goal field lines and the net") but gives no
 * map; which crossing is which type below is inferred from its corner
 * labels, seen from the field:
 *   C        every L of painted lines: the 4 goalie-box corners (+-1450,
 *            +-500) and the 4 field corners (+-2100, +-1350).  An L shows
 *            a closed corner (white on both sides of the pixel, inside
 *            the bend) next to an open one (carpet around it, outside).
 *            On seed 004's walled field the field corners were wall
 *            corners (white wall, no carpet beyond); in this model the
 *            boundary is a painted line with 150 mm of carpet beyond it
 *            (file top), so they look like the box corners.  Inferred.
 *   T-net    every T within 300 mm of a goal post: the box sides meeting
 *            the goal lines (+-2100, +-500), 200 mm beside the posts (+-300):
 *            the net fills the window of the corner on the goal side.
 *            Inferred (the box width is itself +-150 mm uncertain).
 *   T-field  every other T (the halfway line meeting the touchlines, (0,
 *            +-1350): seed 004's halfway line meeting the wall) and every
 *            X (the halfway line crossing the circle, (0, +-150): an X's
 *            four concave corners are closed corners, which pair up as
 *            T-fields).  The X's are inferred: seed 004 does not say.
 *   nets     the goal centres on the goal lines (+-2100, 0), colour of the
 *            goal, goal +1 / -1 (as posts).
 * Arms (and so orientations, obs.h) as the L, T or X each feature is. */
#define FT_L(k, x, y, a, b) \
    LM_(k, x, y, 2, a, b, 0, 0, FL_SIDE_UNKNOWN, FL_COLOR_NONE, 0, FL_COLOR_NONE)
#define FT_T(k, x, y, a, b, c) \
    LM_(k, x, y, 3, a, b, c, 0, FL_SIDE_UNKNOWN, FL_COLOR_NONE, 0, FL_COLOR_NONE)

static const fl_landmark_t aibo2004_features[] = {
    /* C: box front corners, then field corners */
    FT_L(FL_LM_CORNER_C, 1450, 500, A_E, A_S), FT_L(FL_LM_CORNER_C, 1450, -500, A_E, A_N),
    FT_L(FL_LM_CORNER_C, -1450, 500, A_W, A_S), FT_L(FL_LM_CORNER_C, -1450, -500, A_W, A_N),
    FT_L(FL_LM_CORNER_C, -2100, -1350, A_E, A_N), FT_L(FL_LM_CORNER_C, -2100, 1350, A_E, A_S),
    FT_L(FL_LM_CORNER_C, 2100, -1350, A_W, A_N), FT_L(FL_LM_CORNER_C, 2100, 1350, A_W, A_S),
    /* T-field: halfway line x touchlines, halfway line x circle */
    FT_T(FL_LM_CORNER_TFIELD, 0, 1350, A_E, A_W, A_S),
    FT_T(FL_LM_CORNER_TFIELD, 0, -1350, A_E, A_W, A_N),
    LM_CROSS4(FL_LM_CORNER_TFIELD, 0, 150), LM_CROSS4(FL_LM_CORNER_TFIELD, 0, -150),
    /* T-net: box sides x goal lines */
    FT_T(FL_LM_CORNER_TNET, 2100, 500, A_N, A_S, A_W),
    FT_T(FL_LM_CORNER_TNET, 2100, -500, A_N, A_S, A_W),
    FT_T(FL_LM_CORNER_TNET, -2100, 500, A_N, A_S, A_E),
    FT_T(FL_LM_CORNER_TNET, -2100, -500, A_N, A_S, A_E),
    /* nets */
    LM_POINT(FL_LM_NET, 2100, 0, FL_SIDE_UNKNOWN, FL_COLOR_YELLOW, 1, FL_COLOR_NONE),
    LM_POINT(FL_LM_NET, -2100, 0, FL_SIDE_UNKNOWN, FL_COLOR_SKYBLUE, -1, FL_COLOR_NONE)
};

/* ---- hl3x2 (numbers and their basis: file top) ---------------------- */

static const fl_landmark_t hl3x2_lm[] = {
    CORNERS(1500, 1000),
    BOX_CROSSINGS(1500, 1200, 550),
    HALFWAY_CROSSINGS(1000, 300),
    LM_CROSS4(FL_LM_PENALTY_MARK, 600, 0),
    LM_CROSS4(FL_LM_PENALTY_MARK, -600, 0),
    LM_CROSS4(FL_LM_CENTRE_MARK, 0, 0),
    POSTS(1512, 400, 1, FL_COLOR_SKYBLUE),
    POSTS(-1512, 400, -1, FL_COLOR_YELLOW),
    CIRCLE_CENTRE,
    /* three-band poles: color == color2 (top and bottom band) */
    LM_POINT(FL_LM_BEACON, 0, 1200, FL_SIDE_UNKNOWN, FL_COLOR_YELLOW, 0, FL_COLOR_YELLOW),
    LM_POINT(FL_LM_BEACON, 0, -1200, FL_SIDE_UNKNOWN, FL_COLOR_SKYBLUE, 0, FL_COLOR_SKYBLUE)
};

static const fl_field_line_t hl3x2_lines[] = {
    BOUNDARY_LINES(1500, 1000),
    BOX_LINES(1500, 1200, 550)
};

/* ---- catalogue ---------------------------------------------------------- */

static const fl_field_t fields[] = {
    {
        "spl2013", 9000, 6000, 50, 700, 750, 600, 2200, 0, 0, 2700, 100,
        1600, 100, 800, { FL_COLOR_YELLOW, FL_COLOR_YELLOW }, true,
        spl2013_lm, COUNT_OF(spl2013_lm), spl2013_lines, COUNT_OF(spl2013_lines),
        0, 0, NULL, 0
    },
    {
        "uva2013", 6000, 4000, 50, 700, 600, 600, 2200, 0, 0, 1200, 100,
        1400, 100, 800, { FL_COLOR_YELLOW, FL_COLOR_YELLOW }, true,
        uva2013_lm, COUNT_OF(uva2013_lm), uva2013_lines, COUNT_OF(uva2013_lines),
        0, 0, NULL, 0
    },
    {
        "spl2020", 9000, 6000, 50, 700, 750, 1650, 4000, 600, 2200, 3200, 100,
        1600, 100, 800, { FL_COLOR_WHITE, FL_COLOR_WHITE }, true,
        spl2020_lm, COUNT_OF(spl2020_lm), spl2020_lines, COUNT_OF(spl2020_lines),
        0, 0, NULL, 0
    },
    {
        "aibo2004", 4200, 2700, 25, 150, 150, 650, 1000, 0, 0, 0, 0,
        600, 50, 300, { FL_COLOR_SKYBLUE, FL_COLOR_YELLOW }, false,
        aibo2004_lm, COUNT_OF(aibo2004_lm), aibo2004_lines, COUNT_OF(aibo2004_lines),
        100, 400, aibo2004_features, COUNT_OF(aibo2004_features)
    },
    {
        "spl2016", 9000, 6000, 50, 700, 750, 600, 2200, 0, 0, 3200, 100,
        1600, 100, 800, { FL_COLOR_WHITE, FL_COLOR_WHITE }, true,
        spl2016_lm, COUNT_OF(spl2016_lm), spl2013_lines, COUNT_OF(spl2013_lines),
        0, 0, NULL, 0
    },
    {
        "hl3x2", 3000, 2000, 25, 350, 300, 300, 1100, 0, 0, 600, 50,
        800, 50, 450, { FL_COLOR_YELLOW, FL_COLOR_SKYBLUE }, false,
        hl3x2_lm, COUNT_OF(hl3x2_lm), hl3x2_lines, COUNT_OF(hl3x2_lines),
        100, 300, NULL, 0
    }
};

#define N_FIELDS (sizeof(fields) / sizeof(fields[0]))

/* Exact, case-sensitive string equality (no strcmp: the firmware may only
 * call memcpy/memset/memmove/memcmp from libc). */
static bool name_equal(const char *a, const char *b)
{
    size_t i = 0;
    while (a[i] != '\0' && a[i] == b[i])
        i++;
    return a[i] == b[i];
}

/* Scaling and overflow: half + border computed in 64 bit (any int32 inputs),
 * half = v / 2 truncated toward zero, result saturated to int32. */
static int32_t half_plus(int32_t v, int32_t border)
{
    int64_t s = (int64_t)(v / 2) + (int64_t)border;
    if (s > INT32_MAX)
        return INT32_MAX;
    if (s < INT32_MIN)
        return INT32_MIN;
    return (int32_t)s;
}

int32_t fl_field_carpet_half_x_mm(const fl_field_t *f)
{
    return f == NULL ? 0 : half_plus(f->length_mm, f->border_mm);
}

int32_t fl_field_carpet_half_y_mm(const fl_field_t *f)
{
    return f == NULL ? 0 : half_plus(f->width_mm, f->border_mm);
}

const fl_field_t *fl_field_find(const char *name)
{
    size_t i;
    if (name == NULL)
        return NULL;
    for (i = 0; i < N_FIELDS; i++)
        if (name_equal(fields[i].name, name))
            return &fields[i];
    return NULL;
}

size_t fl_field_count(void)
{
    return N_FIELDS;
}

const fl_field_t *fl_field_at(size_t i)
{
    return i < N_FIELDS ? &fields[i] : NULL;
}

bool fl_landmark_kind_is_feature(fl_landmark_kind_t kind)
{
    return (int)kind >= (int)FL_LM_CORNER_C && (int)kind <= (int)FL_LM_NET;
}

/* The table a kind lives in: features for seed 004's kinds. */
static void kind_table(const fl_field_t *f, fl_landmark_kind_t kind,
                       const fl_landmark_t **t, uint16_t *n)
{
    if (fl_landmark_kind_is_feature(kind)) {
        *t = f->features;
        *n = f->features == NULL ? 0 : f->n_features;
    } else {
        *t = f->landmarks;
        *n = f->landmarks == NULL ? 0 : f->n_landmarks;
    }
}

uint16_t fl_field_count_kind(const fl_field_t *f, fl_landmark_kind_t kind)
{
    const fl_landmark_t *t;
    uint16_t i, nt, n = 0;
    if (f == NULL)
        return 0;
    kind_table(f, kind, &t, &nt);
    for (i = 0; i < nt; i++)
        if (t[i].kind == kind)
            n++;
    return n;
}

const fl_landmark_t *fl_field_nth_kind(const fl_field_t *f,
                                       fl_landmark_kind_t kind, uint16_t i)
{
    const fl_landmark_t *t;
    uint16_t j, nt, n = 0;
    if (f == NULL)
        return NULL;
    kind_table(f, kind, &t, &nt);
    for (j = 0; j < nt; j++) {
        if (t[j].kind != kind)
            continue;
        if (n == i)
            return &t[j];
        n++;
    }
    return NULL;
}

uint16_t fl_field_n_all(const fl_field_t *f)
{
    uint32_t n;
    if (f == NULL)
        return 0;
    n = (f->landmarks == NULL ? 0u : f->n_landmarks) +
        (f->features == NULL ? 0u : f->n_features);
    return n > UINT16_MAX ? (uint16_t)UINT16_MAX : (uint16_t)n;
}

const fl_landmark_t *fl_field_all_at(const fl_field_t *f, uint16_t i)
{
    uint16_t nl;
    if (f == NULL)
        return NULL;
    nl = f->landmarks == NULL ? 0 : f->n_landmarks;
    if (i < nl)
        return &f->landmarks[i];
    if (f->features != NULL && (uint32_t)i - nl < f->n_features)
        return &f->features[i - nl];
    return NULL;
}
