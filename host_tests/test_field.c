/*
 * host_tests/test_field.c - field geometries (src/model/field.c).
 *
 * The crossings are recomputed here from the line list alone (segment
 * endpoints, segment x segment and segment x circle intersections, and the
 * directions in which painted lines leave each of them) and compared with
 * the landmark tables: position, kind (2 leaving lines = L, 3 = T, 4 = X)
 * and arms.  Arms are also probed geometrically: 100 mm along each arm lies
 * on paint, and 100 mm along any direction at least 20 degrees from every
 * arm does not.  Then: landmark counts against each field's rules, the
 * parameters against DESIGN.md, 180-degree and mirror symmetry, posts
 * (2 per goal, sides, colors, inside the carpet), marks, beacons, and the
 * lookup helpers with bad input.  Seed 004's corner features of aibo2004
 * are recomputed the same way (field.features_from_lines).  The digest covers every number in every
 * table.  Geometry here uses double (host only); nothing double is printed
 * outside "# " lines.
 */
#include "test.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define MAX_CAND 128
#define MAX_DIRS 16

/* ---- geometry helpers (double) ------------------------------------------ */

/* atan2 as a binary angle, rounded, wrapped to [-32768, 32767]. */
static int ang_units(double dx, double dy)
{
    long a = lround(atan2(dy, dx) * 32768.0 / PI);
    a = ((a + 32768L) % 65536L + 65536L) % 65536L - 32768L;
    return (int)a;
}

static int ang_diff(int a, int b)  /* |a - b| on the circle, binary units */
{
    long d = ((long)a - (long)b) % 65536L;
    if (d < 0)
        d += 65536L;
    if (d > 32768L)
        d = 65536L - d;
    return (int)d;
}

static int wrap_units(long a)
{
    return (int)(((a + 32768L) % 65536L + 65536L) % 65536L - 32768L);
}

static double seg_dist(const fl_field_line_t *l, double px, double py)
{
    double ax = l->x0_mm, ay = l->y0_mm, bx = l->x1_mm, by = l->y1_mm;
    double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy, t;
    if (len2 <= 0.0)
        return hypot(px - ax, py - ay);
    t = ((px - ax) * dx + (py - ay) * dy) / len2;
    if (t < 0.0)
        t = 0.0;
    if (t > 1.0)
        t = 1.0;
    return hypot(px - (ax + t * dx), py - (ay + t * dy));
}

static double min_seg_dist(const fl_field_t *f, double px, double py)
{
    double best = 1e30;
    uint16_t i;
    for (i = 0; i < f->n_lines; i++) {
        double d = seg_dist(&f->lines[i], px, py);
        if (d < best)
            best = d;
    }
    return best;
}

static double circle_dist(const fl_field_t *f, double px, double py)
{
    if (f->circle_radius_mm <= 0)
        return 1e30;
    return fabs(hypot(px, py) - f->circle_radius_mm);
}

/* Directions (binary angles) in which paint leaves (px, py): along each
 * segment through the point toward each end it does not sit on, and along
 * the circle's tangent both ways.  Returns the number of distinct ones. */
static int leaving_dirs(const fl_field_t *f, double px, double py, int *dirs)
{
    int n = 0, cand[2 * 64 + 2], nc = 0, i, j;
    uint16_t k;
    for (k = 0; k < f->n_lines && nc < 2 * 64; k++) {
        const fl_field_line_t *l = &f->lines[k];
        if (seg_dist(l, px, py) > 0.5)
            continue;
        if (hypot(l->x0_mm - px, l->y0_mm - py) > 0.5)
            cand[nc++] = ang_units(l->x0_mm - px, l->y0_mm - py);
        if (hypot(l->x1_mm - px, l->y1_mm - py) > 0.5)
            cand[nc++] = ang_units(l->x1_mm - px, l->y1_mm - py);
    }
    if (circle_dist(f, px, py) <= 0.5) {
        int r = ang_units(px, py);
        cand[nc++] = wrap_units((long)r + 16384L);
        cand[nc++] = wrap_units((long)r - 16384L);
    }
    for (i = 0; i < nc; i++) {
        for (j = 0; j < n; j++)
            if (ang_diff(cand[i], dirs[j]) <= 2)
                break;
        if (j == n && n < MAX_DIRS)
            dirs[n++] = cand[i];
    }
    return n;
}

typedef struct {
    double x, y;
} pt_t;

static int add_pt(pt_t *p, int n, double x, double y)
{
    int i;
    for (i = 0; i < n; i++)
        if (fabs(p[i].x - x) <= 0.5 && fabs(p[i].y - y) <= 0.5)
            return n;
    if (n < MAX_CAND) {
        p[n].x = x;
        p[n].y = y;
        n++;
    }
    return n;
}

/* Every point where paint could form a crossing, from the line list. */
static int candidate_points(const fl_field_t *f, pt_t *p)
{
    int n = 0;
    uint16_t i, j;
    double r = f->circle_radius_mm;
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *a = &f->lines[i];
        double ax = a->x0_mm, ay = a->y0_mm;
        double adx = a->x1_mm - ax, ady = a->y1_mm - ay;
        n = add_pt(p, n, a->x0_mm, a->y0_mm);
        n = add_pt(p, n, a->x1_mm, a->y1_mm);
        for (j = (uint16_t)(i + 1); j < f->n_lines; j++) {
            const fl_field_line_t *b = &f->lines[j];
            double bx = b->x0_mm, by = b->y0_mm;
            double bdx = b->x1_mm - bx, bdy = b->y1_mm - by;
            double den = adx * bdy - ady * bdx, t, u;
            if (fabs(den) < 1e-9)
                continue;  /* parallel: shared endpoints already listed */
            t = ((bx - ax) * bdy - (by - ay) * bdx) / den;
            u = ((bx - ax) * ady - (by - ay) * adx) / den;
            if (t >= -1e-9 && t <= 1 + 1e-9 && u >= -1e-9 && u <= 1 + 1e-9)
                n = add_pt(p, n, floor(ax + t * adx + 0.5), floor(ay + t * ady + 0.5));
        }
        if (r > 0) {
            /* |A + t D| = r */
            double qa = adx * adx + ady * ady, qb = 2 * (ax * adx + ay * ady);
            double qc = ax * ax + ay * ay - r * r, disc = qb * qb - 4 * qa * qc;
            if (qa > 0 && disc >= 0) {
                int s;
                for (s = -1; s <= 1; s += 2) {
                    double t = (-qb + s * sqrt(disc)) / (2 * qa);
                    if (t >= -1e-9 && t <= 1 + 1e-9)
                        n = add_pt(p, n, floor(ax + t * adx + 0.5), floor(ay + t * ady + 0.5));
                }
            }
        }
    }
    return n;
}

static int is_crossing(fl_landmark_kind_t k)
{
    return k == FL_LM_L || k == FL_LM_T || k == FL_LM_X;
}

static int is_mark(fl_landmark_kind_t k)
{
    return k == FL_LM_PENALTY_MARK || k == FL_LM_CENTRE_MARK;
}

/* Arm sets equal (as sets, binary units within tol). */
static int arms_equal(const int *a, int na, const int *b, int nb, int tol)
{
    int i, j;
    if (na != nb)
        return 0;
    for (i = 0; i < na; i++) {
        int found = 0;
        for (j = 0; j < nb; j++)
            if (ang_diff(a[i], b[j]) <= tol)
                found++;
        if (found != 1)
            return 0;
    }
    return 1;
}

static void lm_arms(const fl_landmark_t *lm, int *out)
{
    int i;
    for (i = 0; i < lm->n_arms && i < FL_FIELD_MAX_ARMS; i++)
        out[i] = lm->arm[i];
}

/* ---- the spec, per field (DESIGN.md "Fields" and the brief) ------------- */

typedef struct {
    const char *name;
    int32_t length, width, line, border, radius, pa_d, pa_w, ga_d, ga_w;
    int32_t pm_x, mark, goal_w, post_d, post_h;
    fl_color_t c_neg, c_pos;
    int symmetric;
    int count[FL_LM_KIND_COUNT];  /* L T X PM CM POST CC BEACON, then seed
                                     004's features: C T-field T-net net */
} spec_t;

static const spec_t specs[] = {
    {"spl2013", 9000, 6000, 50, 700, 750, 600, 2200, 0, 0, 2700, 100, 1600, 100, 800,
     FL_COLOR_YELLOW, FL_COLOR_YELLOW, 1, {8, 6, 2, 2, 1, 4, 1, 0}},
    {"uva2013", 6000, 4000, 50, 700, 600, 600, 2200, 0, 0, 1200, 100, 1400, 100, 800,
     FL_COLOR_YELLOW, FL_COLOR_YELLOW, 1, {8, 6, 2, 2, 1, 4, 1, 0}},
    /* goal area and penalty area: 4 + 4 + 4 L, 2 + 4 + 4 T */
    {"spl2020", 9000, 6000, 50, 700, 750, 1650, 4000, 600, 2200, 3200, 100, 1600, 100, 800,
     FL_COLOR_WHITE, FL_COLOR_WHITE, 1, {12, 10, 2, 2, 1, 4, 1, 0}},
    /* numbers of src/model/field.c (uncertain, see there); 4 corner beacons */
    {"aibo2004", 4200, 2700, 25, 150, 150, 650, 1000, 0, 0, 0, 0, 600, 50, 300,
     FL_COLOR_SKYBLUE, FL_COLOR_YELLOW, 0, {8, 6, 2, 0, 0, 4, 1, 4, 8, 4, 4, 2}},
    /* seed 003's field: spl2013's lines, white goals, marks at 3200 */
    {"spl2016", 9000, 6000, 50, 700, 750, 600, 2200, 0, 0, 3200, 100, 1600, 100, 800,
     FL_COLOR_WHITE, FL_COLOR_WHITE, 1, {8, 6, 2, 2, 1, 4, 1, 0}},
    /* seed 002's field: the KidSize field of 2009-2012 halved (numbers and
     * their basis in src/model/field.c); 2 three-band landmark poles */
    {"hl3x2", 3000, 2000, 25, 350, 300, 300, 1100, 0, 0, 600, 50, 800, 50, 450,
     FL_COLOR_YELLOW, FL_COLOR_SKYBLUE, 0, {8, 6, 2, 2, 1, 4, 1, 2}},
};
#define N_SPECS (sizeof specs / sizeof specs[0])

/* ---- cases --------------------------------------------------------------- */

static void test_catalogue(void)
{
    size_t i, j;
    CHECK_EQ(fl_field_count(), N_SPECS);
    for (i = 0; i < fl_field_count(); i++) {
        const fl_field_t *f = fl_field_at(i);
        CHECK(f != NULL);
        if (!f)
            continue;
        CHECK(fl_field_find(f->name) == f);
        for (j = 0; j < i; j++)
            CHECK(strcmp(fl_field_at(j)->name, f->name) != 0);
    }
    for (i = 0; i < N_SPECS; i++)
        CHECK(fl_field_find(specs[i].name) != NULL);
    CHECK(fl_field_at(fl_field_count()) == NULL);
    CHECK(fl_field_at((size_t)-1) == NULL);
    CHECK(fl_field_find(NULL) == NULL);
    CHECK(fl_field_find("") == NULL);
    CHECK(fl_field_find("nope") == NULL);
    CHECK(fl_field_find("spl201") == NULL);     /* prefix */
    CHECK(fl_field_find("spl20133") == NULL);   /* longer */
    CHECK(fl_field_find("SPL2013") == NULL);    /* case */
}

static void test_lookup_bad_input(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_field_t custom;
    int k;
    CHECK(f != NULL);
    if (!f)
        return;
    CHECK_EQ(fl_field_count_kind(NULL, FL_LM_L), 0);
    CHECK(fl_field_nth_kind(NULL, FL_LM_L, 0) == NULL);
    CHECK_EQ(fl_field_count_kind(f, FL_LM_KIND_COUNT), 0);
    CHECK_EQ(fl_field_count_kind(f, (fl_landmark_kind_t)-1), 0);
    CHECK(fl_field_nth_kind(f, FL_LM_KIND_COUNT, 0) == NULL);
    CHECK(fl_field_nth_kind(f, FL_LM_BEACON, 0) == NULL);  /* none on spl2013 */
    CHECK(fl_field_nth_kind(f, FL_LM_L, 65535) == NULL);
    for (k = 0; k < FL_LM_KIND_COUNT; k++) {
        uint16_t n = fl_field_count_kind(f, (fl_landmark_kind_t)k), i;
        const fl_landmark_t *prev = NULL;
        for (i = 0; i < n; i++) {
            const fl_landmark_t *lm = fl_field_nth_kind(f, (fl_landmark_kind_t)k, i);
            CHECK(lm != NULL);
            if (!lm)
                continue;
            CHECK_EQ(lm->kind, k);
            CHECK(lm >= f->landmarks && lm < f->landmarks + f->n_landmarks);
            CHECK(prev == NULL || lm > prev);   /* table order */
            prev = lm;
        }
        CHECK(fl_field_nth_kind(f, (fl_landmark_kind_t)k, n) == NULL);
    }
    CHECK_EQ(fl_field_carpet_half_x_mm(NULL), 0);
    CHECK_EQ(fl_field_carpet_half_y_mm(NULL), 0);
    /* a caller-made field: NULL tables, extreme sizes */
    memset(&custom, 0, sizeof custom);
    custom.n_landmarks = 5;
    CHECK_EQ(fl_field_count_kind(&custom, FL_LM_L), 0);
    CHECK(fl_field_nth_kind(&custom, FL_LM_L, 0) == NULL);
    custom.length_mm = INT32_MAX;
    custom.width_mm = INT32_MIN;
    custom.border_mm = INT32_MAX;
    CHECK_EQ(fl_field_carpet_half_x_mm(&custom), INT32_MAX);
    custom.border_mm = INT32_MIN;
    CHECK_EQ(fl_field_carpet_half_y_mm(&custom), INT32_MIN);
    custom.length_mm = 4001;
    custom.border_mm = 10;
    CHECK_EQ(fl_field_carpet_half_x_mm(&custom), 2010);
}

static void test_params(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const spec_t *e = &specs[s];
        const fl_field_t *f = fl_field_find(e->name);
        CHECK(f != NULL);
        if (!f)
            continue;
        CHECK_EQ(f->length_mm, e->length);
        CHECK_EQ(f->width_mm, e->width);
        CHECK_EQ(f->line_width_mm, e->line);
        CHECK_EQ(f->border_mm, e->border);
        CHECK_EQ(f->circle_radius_mm, e->radius);
        CHECK_EQ(f->penalty_area_depth_mm, e->pa_d);
        CHECK_EQ(f->penalty_area_width_mm, e->pa_w);
        CHECK_EQ(f->goal_area_depth_mm, e->ga_d);
        CHECK_EQ(f->goal_area_width_mm, e->ga_w);
        CHECK_EQ(f->penalty_mark_x_mm, e->pm_x);
        CHECK_EQ(f->mark_size_mm, e->mark);
        CHECK_EQ(f->goal_width_mm, e->goal_w);
        CHECK_EQ(f->post_diameter_mm, e->post_d);
        CHECK_EQ(f->post_height_mm, e->post_h);
        CHECK_EQ(f->goal_color[0], e->c_neg);
        CHECK_EQ(f->goal_color[1], e->c_pos);
        CHECK_EQ(f->symmetric, e->symmetric);
        CHECK_EQ(f->symmetric, f->goal_color[0] == f->goal_color[1]);
        CHECK_EQ(fl_field_carpet_half_x_mm(f), e->length / 2 + e->border);
        CHECK_EQ(fl_field_carpet_half_y_mm(f), e->width / 2 + e->border);
        CHECK_EQ(f->beacon_diameter_mm > 0, e->count[FL_LM_BEACON] > 0);
        CHECK_EQ(f->beacon_height_mm > 0, e->count[FL_LM_BEACON] > 0);
        CHECK(f->landmarks != NULL && f->lines != NULL);
    }
}

/* Counts per kind: the rules' numbers, and the same derived from the
 * field's parameters (boxes make 4 L and 4 T each). */
static void test_counts(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        int k, total = 0, boxes;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        boxes = (f->penalty_area_depth_mm > 0) + (f->goal_area_depth_mm > 0);
        for (k = 0; k < FL_LM_KIND_COUNT; k++) {
            CHECK_EQ(fl_field_count_kind(f, (fl_landmark_kind_t)k), specs[s].count[k]);
            total += fl_field_count_kind(f, (fl_landmark_kind_t)k);
        }
        CHECK_EQ(total, f->n_landmarks + (f->features != NULL ? f->n_features : 0));
        CHECK_EQ(fl_field_count_kind(f, FL_LM_L), 4 + 4 * boxes);
        CHECK_EQ(fl_field_count_kind(f, FL_LM_T), 2 + 4 * boxes);
        CHECK_EQ(fl_field_count_kind(f, FL_LM_X), f->circle_radius_mm > 0 ? 2 : 0);
        CHECK_EQ(fl_field_count_kind(f, FL_LM_CENTRE_CIRCLE), f->circle_radius_mm > 0);
        CHECK_EQ(fl_field_count_kind(f, FL_LM_PENALTY_MARK), f->penalty_mark_x_mm > 0 ? 2 : 0);
        CHECK_EQ(fl_field_count_kind(f, FL_LM_POST), 4);
        /* lines: 4 boundary + halfway + 3 per box per goal */
        CHECK_EQ(f->n_lines, 5 + 6 * boxes);
    }
}

/* Per-landmark field hygiene: arm slots, sides, colors, goals, positions. */
static void test_landmark_fields(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        int32_t hx, hy;
        uint16_t i, j;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        hx = fl_field_carpet_half_x_mm(f);
        hy = fl_field_carpet_half_y_mm(f);
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            int a, want = lm->kind == FL_LM_L ? 2 : lm->kind == FL_LM_T ? 3
                        : (lm->kind == FL_LM_X || is_mark(lm->kind)) ? 4 : 0;
            CHECK((int)lm->kind >= 0 && lm->kind < FL_LM_KIND_COUNT);
            CHECK_EQ(lm->n_arms, want);
            for (a = lm->n_arms; a < FL_FIELD_MAX_ARMS; a++)
                CHECK_EQ(lm->arm[a], 0);
            for (a = 0; a < lm->n_arms; a++)
                for (j = 0; j < a; j++)
                    CHECK(ang_diff(lm->arm[a], lm->arm[j]) > 1000);
            CHECK(lm->x_mm >= -hx && lm->x_mm <= hx);
            CHECK(lm->y_mm >= -hy && lm->y_mm <= hy);
            if (lm->kind != FL_LM_POST) {
                CHECK_EQ(lm->side, FL_SIDE_UNKNOWN);
                CHECK_EQ(lm->goal, 0);
            }
            if (lm->kind != FL_LM_POST && lm->kind != FL_LM_BEACON)
                CHECK_EQ(lm->color, FL_COLOR_NONE);
            if (lm->kind != FL_LM_BEACON)
                CHECK_EQ(lm->color2, FL_COLOR_NONE);
            for (j = 0; j < i; j++)   /* no duplicate of the same kind */
                CHECK(!(f->landmarks[j].kind == lm->kind && f->landmarks[j].x_mm == lm->x_mm &&
                        f->landmarks[j].y_mm == lm->y_mm));
        }
    }
}

static void test_lines(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        int32_t hx, hy;
        uint16_t i, j;
        int boxes[2][2], b, g;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        hx = f->length_mm / 2;
        hy = f->width_mm / 2;
        CHECK(f->circle_radius_mm < hy);
        for (i = 0; i < f->n_lines; i++) {
            const fl_field_line_t *l = &f->lines[i];
            CHECK(l->x0_mm != l->x1_mm || l->y0_mm != l->y1_mm);    /* length > 0 */
            CHECK(l->x0_mm == l->x1_mm || l->y0_mm == l->y1_mm);    /* axis-aligned */
            CHECK(l->x0_mm >= -hx && l->x0_mm <= hx && l->x1_mm >= -hx && l->x1_mm <= hx);
            CHECK(l->y0_mm >= -hy && l->y0_mm <= hy && l->y1_mm >= -hy && l->y1_mm <= hy);
            /* no two collinear segments overlap (a line would be listed twice) */
            for (j = 0; j < i; j++) {
                const fl_field_line_t *m = &f->lines[j];
                if (l->x0_mm == l->x1_mm && m->x0_mm == m->x1_mm && l->x0_mm == m->x0_mm) {
                    int32_t a0 = l->y0_mm < l->y1_mm ? l->y0_mm : l->y1_mm;
                    int32_t a1 = l->y0_mm < l->y1_mm ? l->y1_mm : l->y0_mm;
                    int32_t b0 = m->y0_mm < m->y1_mm ? m->y0_mm : m->y1_mm;
                    int32_t b1 = m->y0_mm < m->y1_mm ? m->y1_mm : m->y0_mm;
                    CHECK(a1 <= b0 || b1 <= a0);
                }
                if (l->y0_mm == l->y1_mm && m->y0_mm == m->y1_mm && l->y0_mm == m->y0_mm) {
                    int32_t a0 = l->x0_mm < l->x1_mm ? l->x0_mm : l->x1_mm;
                    int32_t a1 = l->x0_mm < l->x1_mm ? l->x1_mm : l->x0_mm;
                    int32_t b0 = m->x0_mm < m->x1_mm ? m->x0_mm : m->x1_mm;
                    int32_t b1 = m->x0_mm < m->x1_mm ? m->x1_mm : m->x0_mm;
                    CHECK(a1 <= b0 || b1 <= a0);
                }
            }
        }
        /* the boundary, the halfway line and each box's three lines exist
         * where the parameters say (probe their midpoints and ends) */
        CHECK(min_seg_dist(f, hx, 0) < 0.5 && min_seg_dist(f, -hx, 0) < 0.5);
        CHECK(min_seg_dist(f, 0, hy) < 0.5 && min_seg_dist(f, 0, -hy) < 0.5);
        CHECK(min_seg_dist(f, 0, hy / 2.0) < 0.5 && min_seg_dist(f, 0, -hy / 2.0) < 0.5);
        boxes[0][0] = f->penalty_area_depth_mm;
        boxes[0][1] = f->penalty_area_width_mm;
        boxes[1][0] = f->goal_area_depth_mm;
        boxes[1][1] = f->goal_area_width_mm;
        for (b = 0; b < 2; b++) {
            double d = boxes[b][0], w2 = boxes[b][1] / 2.0;
            if (boxes[b][0] == 0)
                continue;
            for (g = -1; g <= 1; g += 2) {
                double bx = g * (hx - d);
                CHECK(min_seg_dist(f, bx, 0) < 0.5);
                CHECK(min_seg_dist(f, bx, w2) < 0.5 && min_seg_dist(f, bx, -w2) < 0.5);
                CHECK(min_seg_dist(f, g * (hx - d / 2), w2) < 0.5);
                CHECK(min_seg_dist(f, g * (hx - d / 2), -w2) < 0.5);
                /* the box front ends at the sides: nothing beyond */
                CHECK(min_seg_dist(f, bx, w2 + 100) > 50);
            }
        }
    }
}

/* The crossings recomputed from the line list == the L/T/X landmarks, with
 * the same kind and arms; and no line ends in the open. */
static void test_crossings_from_lines(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        pt_t cand[MAX_CAND];
        int nc, c, n_cross = 0, n_lm = 0;
        uint16_t i;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        nc = candidate_points(f, cand);
        CHECK(nc < MAX_CAND);
        for (c = 0; c < nc; c++) {
            int dirs[MAX_DIRS], nd = leaving_dirs(f, cand[c].x, cand[c].y, dirs), found = 0;
            fl_landmark_kind_t want;
            CHECK(nd >= 2);                   /* no free line end */
            if (nd == 2 && ang_diff(dirs[0], dirs[1]) >= 32766)
                continue;                     /* a straight line passing through */
            CHECK(nd <= 4);
            want = nd == 2 ? FL_LM_L : nd == 3 ? FL_LM_T : FL_LM_X;
            n_cross++;
            for (i = 0; i < f->n_landmarks; i++) {
                const fl_landmark_t *lm = &f->landmarks[i];
                int arms[FL_FIELD_MAX_ARMS];
                if (!is_crossing(lm->kind) || fabs(lm->x_mm - cand[c].x) > 0.5 ||
                    fabs(lm->y_mm - cand[c].y) > 0.5)
                    continue;
                found++;
                if (lm->kind != want)
                    t_fail_msg(__FILE__, __LINE__, "%s (%d,%d): kind %d, lines make %d", f->name,
                               (int)lm->x_mm, (int)lm->y_mm, (int)lm->kind, (int)want);
                lm_arms(lm, arms);
                if (!arms_equal(arms, lm->n_arms, dirs, nd, 1))
                    t_fail_msg(__FILE__, __LINE__, "%s (%d,%d): arms differ from the lines",
                               f->name, (int)lm->x_mm, (int)lm->y_mm);
                else
                    CHECK(1);
            }
            if (found != 1)
                t_fail_msg(__FILE__, __LINE__, "%s: crossing (%.0f,%.0f) listed %d times", f->name,
                           cand[c].x, cand[c].y, found);
        }
        for (i = 0; i < f->n_landmarks; i++)
            n_lm += is_crossing(f->landmarks[i].kind);
        CHECK_EQ(n_cross, n_lm);   /* no L/T/X away from the lines */
    }
}

/* Seed 004's corner features (field.h, src/model/field.c) recomputed from
 * the lines, the circle and the posts: every L of paint is a C; a T within
 * 300 mm of a goal post a T-net, any other T a T-field; every X a
 * T-field; each goal's net at the middle of its posts (the goal line),
 * with the goal's colour.  Arms as the crossing's; orientation and its
 * period as the L / T / X at the same point.  Fields without features have
 * none (NULL, 0); the features are never in landmarks nor landmarks in
 * features; fl_field_all_at lists landmarks, then features. */
static fl_landmark_kind_t feature_of(const fl_field_t *f, double x, double y, int nd)
{
    uint16_t i;
    double near = 1e30;
    if (nd == 2)
        return FL_LM_CORNER_C;
    if (nd == 4)
        return FL_LM_CORNER_TFIELD;
    for (i = 0; i < f->n_landmarks; i++)
        if (f->landmarks[i].kind == FL_LM_POST) {
            double d = hypot(f->landmarks[i].x_mm - x, f->landmarks[i].y_mm - y);
            near = d < near ? d : near;
        }
    return near <= 300.0 ? FL_LM_CORNER_TNET : FL_LM_CORNER_TFIELD;
}

static void check_feature_orientation(const fl_field_t *f, const fl_landmark_t *ft)
{
    uint16_t i;
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *lm = &f->landmarks[i];
        fl_angle_t a, b;
        if (!is_crossing(lm->kind) || lm->x_mm != ft->x_mm || lm->y_mm != ft->y_mm)
            continue;
        CHECK(fl_landmark_orientation(lm, &a));
        CHECK(fl_landmark_orientation(ft, &b));
        CHECK_EQ(a, b);
        CHECK_EQ(fl_landmark_orientation_period(lm), fl_landmark_orientation_period(ft));
        return;
    }
    t_fail_msg(__FILE__, __LINE__, "%s: feature (%d,%d) on no L/T/X", f->name, (int)ft->x_mm,
               (int)ft->y_mm);
}

static void test_features_from_lines(void)
{
    size_t s;
    for (s = 0; s < fl_field_count(); s++) {
        const fl_field_t *f = fl_field_at(s);
        pt_t cand[MAX_CAND];
        int nc, c, g, n_want = 0;
        uint16_t i, nf;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        nf = f->features != NULL ? f->n_features : 0;
        CHECK_EQ(fl_field_n_all(f), f->n_landmarks + nf);
        for (i = 0; i < f->n_landmarks; i++) {
            CHECK(!fl_landmark_kind_is_feature(f->landmarks[i].kind));
            CHECK(fl_field_all_at(f, i) == &f->landmarks[i]);
        }
        for (i = 0; i < nf; i++) {
            CHECK(fl_landmark_kind_is_feature(f->features[i].kind));
            CHECK(fl_field_all_at(f, (uint16_t)(f->n_landmarks + i)) == &f->features[i]);
        }
        CHECK(fl_field_all_at(f, (uint16_t)(f->n_landmarks + nf)) == NULL);
        if (strcmp(f->name, "aibo2004") != 0) {
            /* seed 004's features are mapped on its own field only */
            CHECK_EQ(nf, 0);
            CHECK(f->features == NULL);
            CHECK_EQ(fl_field_count_kind(f, FL_LM_CORNER_C), 0);
            CHECK(fl_field_nth_kind(f, FL_LM_NET, 0) == NULL);
            continue;
        }
        CHECK(nf > 0);
        nc = candidate_points(f, cand);
        for (c = 0; c < nc; c++) {
            int dirs[MAX_DIRS], nd = leaving_dirs(f, cand[c].x, cand[c].y, dirs), found = 0;
            fl_landmark_kind_t want;
            if (nd < 2 || (nd == 2 && ang_diff(dirs[0], dirs[1]) >= 32766))
                continue;
            want = feature_of(f, cand[c].x, cand[c].y, nd);
            n_want++;
            for (i = 0; i < nf; i++) {
                const fl_landmark_t *ft = &f->features[i];
                int arms[FL_FIELD_MAX_ARMS];
                if (ft->kind == FL_LM_NET || fabs(ft->x_mm - cand[c].x) > 0.5 ||
                    fabs(ft->y_mm - cand[c].y) > 0.5)
                    continue;
                found++;
                if (ft->kind != want)
                    t_fail_msg(__FILE__, __LINE__, "%s (%d,%d): feature kind %d, lines make %d",
                               f->name, (int)ft->x_mm, (int)ft->y_mm, (int)ft->kind, (int)want);
                lm_arms(ft, arms);
                if (!arms_equal(arms, ft->n_arms, dirs, nd, 1))
                    t_fail_msg(__FILE__, __LINE__, "%s (%d,%d): feature arms differ from the lines",
                               f->name, (int)ft->x_mm, (int)ft->y_mm);
                check_feature_orientation(f, ft);
                CHECK_EQ(ft->color, FL_COLOR_NONE);
                CHECK_EQ(ft->goal, 0);
            }
            if (found != 1)
                t_fail_msg(__FILE__, __LINE__, "%s: feature at (%.0f,%.0f) listed %d times", f->name,
                           cand[c].x, cand[c].y, found);
        }
        /* nets: one per goal, between its posts, the goal's colour */
        for (g = -1; g <= 1; g += 2) {
            double sx = 0, sy = 0;
            int np = 0, found = 0;
            for (i = 0; i < f->n_landmarks; i++)
                if (f->landmarks[i].kind == FL_LM_POST && f->landmarks[i].goal == g) {
                    sx += f->landmarks[i].x_mm;
                    sy += f->landmarks[i].y_mm;
                    np++;
                }
            CHECK_EQ(np, 2);
            n_want++;
            for (i = 0; i < nf; i++) {
                const fl_landmark_t *ft = &f->features[i];
                fl_angle_t o;
                if (ft->kind != FL_LM_NET || ft->goal != g)
                    continue;
                found++;
                CHECK(np > 0 && fabs(ft->x_mm - sx / np) <= 0.5 && fabs(ft->y_mm - sy / np) <= 0.5);
                CHECK_EQ(ft->color, f->goal_color[g > 0]);
                CHECK_EQ(ft->n_arms, 0);
                CHECK(!fl_landmark_orientation(ft, &o));
                CHECK_EQ(fl_landmark_orientation_period(ft), 0);
            }
            CHECK_EQ(found, 1);
        }
        CHECK_EQ(n_want, nf);   /* nothing listed away from the lines and goals */
        t_info("%s: %u features (C %u T-field %u T-net %u net %u), recomputed from %d line "
               "crossings and 2 goals", f->name, (unsigned)nf,
               (unsigned)fl_field_count_kind(f, FL_LM_CORNER_C),
               (unsigned)fl_field_count_kind(f, FL_LM_CORNER_TFIELD),
               (unsigned)fl_field_count_kind(f, FL_LM_CORNER_TNET),
               (unsigned)fl_field_count_kind(f, FL_LM_NET), n_want - 2);
    }
}

/* Probes: paint 100 mm along every arm, none 100 mm along any direction at
 * least 20 degrees from all arms (circle: probed at min(100, R/4) mm, 30
 * degrees, as it bends away from its tangent). */
static void test_arm_probes(void)
{
    size_t s;
    double worst_on = 0, best_off = 1e30;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        double tol, dc;
        uint16_t i;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        tol = f->line_width_mm / 2.0;
        dc = f->circle_radius_mm / 4.0 < 100 ? f->circle_radius_mm / 4.0 : 100;
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            int a, deg;
            if (!is_crossing(lm->kind))
                continue;
            for (a = 0; a < lm->n_arms; a++) {
                double th = lm->arm[a] * PI / 32768.0;
                double ds = min_seg_dist(f, lm->x_mm + 100 * cos(th), lm->y_mm + 100 * sin(th));
                double dcirc = circle_dist(f, lm->x_mm + dc * cos(th), lm->y_mm + dc * sin(th));
                double d = ds < dcirc ? ds : dcirc;
                if (d > worst_on)
                    worst_on = d;
                if (!(d <= tol))
                    t_fail_msg(__FILE__, __LINE__, "%s (%d,%d) arm %d: no paint (%.1f mm off)",
                               f->name, (int)lm->x_mm, (int)lm->y_mm, (int)lm->arm[a], d);
                else
                    CHECK(1);
            }
            for (deg = 0; deg < 360; deg++) {
                int u = ang_units(cos(deg * PI / 180), sin(deg * PI / 180)), away = 65536;
                double th = deg * PI / 180, ds, dcirc;
                for (a = 0; a < lm->n_arms; a++)
                    if (ang_diff(u, lm->arm[a]) < away)
                        away = ang_diff(u, lm->arm[a]);
                ds = min_seg_dist(f, lm->x_mm + 100 * cos(th), lm->y_mm + 100 * sin(th));
                dcirc = circle_dist(f, lm->x_mm + dc * cos(th), lm->y_mm + dc * sin(th));
                if (away >= 20 * 65536 / 360) {
                    if (ds < best_off)
                        best_off = ds;
                    if (!(ds > tol))
                        t_fail_msg(__FILE__, __LINE__, "%s (%d,%d): paint at %d deg, not an arm",
                                   f->name, (int)lm->x_mm, (int)lm->y_mm, deg);
                }
                if (away >= 30 * 65536 / 360 && !(dcirc > tol))
                    t_fail_msg(__FILE__, __LINE__, "%s (%d,%d): circle at %d deg, not an arm",
                               f->name, (int)lm->x_mm, (int)lm->y_mm, deg);
            }
        }
    }
    t_info("arm probes: worst on-arm distance %.2f mm, nearest off-arm paint %.1f mm",
           worst_on, best_off);
}

/* Marks and the circle centre. */
static void test_marks(void)
{
    size_t s;
    static const int axes[4] = {0, 16384, -32768, -16384};
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        uint16_t i;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        if (fl_field_count_kind(f, FL_LM_PENALTY_MARK) + fl_field_count_kind(f, FL_LM_CENTRE_MARK))
            CHECK(f->mark_size_mm > 0 && f->mark_size_mm <= 2 * f->line_width_mm + 50);
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            int arms[FL_FIELD_MAX_ARMS];
            if (lm->kind == FL_LM_CENTRE_CIRCLE) {
                CHECK(lm->x_mm == 0 && lm->y_mm == 0 && f->circle_radius_mm > 0);
                CHECK_EQ(lm->n_arms, 0);
            }
            if (!is_mark(lm->kind))
                continue;
            lm_arms(lm, arms);
            CHECK(arms_equal(arms, lm->n_arms, axes, 4, 0));
            CHECK_EQ(lm->y_mm, 0);
            if (lm->kind == FL_LM_CENTRE_MARK) {
                CHECK_EQ(lm->x_mm, 0);
                CHECK(min_seg_dist(f, 0, 0) < 0.5);      /* on the halfway line */
            } else {
                CHECK_EQ(lm->x_mm < 0 ? -lm->x_mm : lm->x_mm, f->penalty_mark_x_mm);
                CHECK(f->penalty_mark_x_mm < f->length_mm / 2);
                /* the small cross stands free of every line */
                CHECK(min_seg_dist(f, lm->x_mm, 0) > f->mark_size_mm);
            }
        }
        if (f->penalty_mark_x_mm > 0) {
            CHECK(fl_field_nth_kind(f, FL_LM_PENALTY_MARK, 0)->x_mm ==
                  -fl_field_nth_kind(f, FL_LM_PENALTY_MARK, 1)->x_mm);
        }
    }
}

static void test_posts(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        int per_goal[2] = {0, 0}, left[2] = {0, 0};
        uint16_t i;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        for (i = 0; i < fl_field_count_kind(f, FL_LM_POST); i++) {
            const fl_landmark_t *p = fl_field_nth_kind(f, FL_LM_POST, i);
            int gi;
            double off;
            if (!p) {
                CHECK(p != NULL);
                continue;
            }
            CHECK(p->goal == 1 || p->goal == -1);
            gi = p->goal > 0;
            per_goal[gi]++;
            CHECK(p->x_mm * p->goal > 0);                              /* at its goal's end */
            CHECK_EQ(2 * (p->y_mm < 0 ? -p->y_mm : p->y_mm), f->goal_width_mm);
            /* on or just behind the goal line: within half a line + a radius */
            off = fabs(fabs((double)p->x_mm) - f->length_mm / 2.0);
            CHECK(off <= f->line_width_mm / 2.0 + f->post_diameter_mm / 2.0);
            CHECK(fabs((double)p->x_mm) >= f->length_mm / 2.0);
            CHECK(abs(p->x_mm) + f->post_diameter_mm / 2 <= fl_field_carpet_half_x_mm(f));
            CHECK(abs(p->y_mm) + f->post_diameter_mm / 2 <= fl_field_carpet_half_y_mm(f));
            /* facing the goal at +x, left is +y; facing -x, left is -y */
            CHECK(p->side == FL_SIDE_LEFT || p->side == FL_SIDE_RIGHT);
            CHECK_EQ(p->side == FL_SIDE_LEFT, p->y_mm * p->goal > 0);
            left[gi] += p->side == FL_SIDE_LEFT;
            CHECK_EQ(p->color, f->goal_color[gi]);
            CHECK_EQ(p->n_arms, 0);
        }
        CHECK_EQ(per_goal[0], 2);
        CHECK_EQ(per_goal[1], 2);
        CHECK_EQ(left[0], 1);
        CHECK_EQ(left[1], 1);
        CHECK(f->goal_width_mm < f->width_mm);
        if (f->penalty_area_width_mm > 0)
            CHECK(f->goal_width_mm < f->penalty_area_width_mm);
    }
}

static void test_beacons(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        uint16_t i, j, n;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        n = fl_field_count_kind(f, FL_LM_BEACON);
        for (i = 0; i < n; i++) {
            const fl_landmark_t *b = fl_field_nth_kind(f, FL_LM_BEACON, i);
            fl_color_t end = f->goal_color[b->x_mm > 0];
            if (b->color == b->color2) {
                /* three-band landmark pole (hl3x2): on the halfway line
                 * extension just outside a touchline, within the carpet;
                 * its outer bands have the color of the goal on the left
                 * of a robot on the field facing it (+y pole: the -x
                 * goal), the middle band the other goal's */
                CHECK_EQ(b->x_mm, 0);
                CHECK(abs(b->y_mm) > f->width_mm / 2 + f->line_width_mm / 2 +
                                         f->beacon_diameter_mm / 2);
                CHECK(abs(b->y_mm) + f->beacon_diameter_mm / 2 <= fl_field_carpet_half_y_mm(f));
                CHECK_EQ(b->color, f->goal_color[b->y_mm > 0 ? 0 : 1]);
                CHECK(!f->symmetric);
                for (j = 0; j < i; j++)
                    CHECK(fl_field_nth_kind(f, FL_LM_BEACON, j)->color != b->color);
                continue;
            }
            /* outside the lines, one band pink, the other the nearer goal's */
            CHECK(abs(b->x_mm) > f->length_mm / 2 && abs(b->y_mm) > f->width_mm / 2);
            CHECK(b->x_mm != 0);
            CHECK((b->color == FL_COLOR_PINK && b->color2 == end) ||
                  (b->color2 == FL_COLOR_PINK && b->color == end));
            for (j = 0; j < i; j++) {   /* every beacon unique */
                const fl_landmark_t *c = fl_field_nth_kind(f, FL_LM_BEACON, j);
                CHECK(!(c->color == b->color && c->color2 == b->color2));
            }
        }
        if (n > 0)
            CHECK(f->beacon_diameter_mm > 0 && f->beacon_height_mm > 0);
        /* AIBO beacons (two bands) stand above the goals; the KidSize
         * poles (three bands, 600 mm) are lower than the crossbar (900) */
        if (n > 0) {
            const fl_landmark_t *b0 = fl_field_nth_kind(f, FL_LM_BEACON, 0);
            if (b0->color != b0->color2)
                CHECK(f->beacon_height_mm > f->post_height_mm);
            else
                CHECK(f->beacon_height_mm < f->post_height_mm);
        }
    }
}

/* Image of landmark lm under 180-degree rotation (rot=1) or the mirror
 * y -> -y (rot=0) is present in the field, colors and sides included. */
static int image_present(const fl_field_t *f, const fl_landmark_t *lm, int rot)
{
    int tx = rot ? -lm->x_mm : lm->x_mm, ty = -lm->y_mm, a;
    int arms[FL_FIELD_MAX_ARMS], arms2[FL_FIELD_MAX_ARMS];
    fl_side_t side = lm->side;
    int goal = rot ? -lm->goal : lm->goal;
    uint16_t i;
    if (!rot && side != FL_SIDE_UNKNOWN)
        side = side == FL_SIDE_LEFT ? FL_SIDE_RIGHT : FL_SIDE_LEFT;
    for (a = 0; a < lm->n_arms; a++)
        arms[a] = rot ? wrap_units((long)lm->arm[a] + 32768L) : wrap_units(-(long)lm->arm[a]);
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *m = &f->landmarks[i];
        if (m->kind != lm->kind || m->x_mm != tx || m->y_mm != ty)
            continue;
        lm_arms(m, arms2);
        if (arms_equal(arms, lm->n_arms, arms2, m->n_arms, 0) && m->side == side &&
            m->goal == goal && m->color == lm->color && m->color2 == lm->color2)
            return 1;
    }
    return 0;
}

static int line_image_present(const fl_field_t *f, const fl_field_line_t *l, int rot)
{
    int32_t x0 = rot ? -l->x0_mm : l->x0_mm, x1 = rot ? -l->x1_mm : l->x1_mm;
    int32_t y0 = -l->y0_mm, y1 = -l->y1_mm;
    uint16_t i;
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *m = &f->lines[i];
        if ((m->x0_mm == x0 && m->y0_mm == y0 && m->x1_mm == x1 && m->y1_mm == y1) ||
            (m->x0_mm == x1 && m->y0_mm == y1 && m->x1_mm == x0 && m->y1_mm == y0))
            return 1;
    }
    return 0;
}

static void test_symmetry(void)
{
    size_t s;
    for (s = 0; s < N_SPECS; s++) {
        const fl_field_t *f = fl_field_find(specs[s].name);
        int all_rot = 1, posts_rot = 0, beacons_rot = 0, beacons_mirror = 0;
        uint16_t i;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        for (i = 0; i < f->n_lines; i++) {
            CHECK(line_image_present(f, &f->lines[i], 1));
            CHECK(line_image_present(f, &f->lines[i], 0));
        }
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            int r = image_present(f, lm, 1), m = image_present(f, lm, 0);
            all_rot &= r;
            if (lm->kind == FL_LM_POST)
                posts_rot += r;
            if (lm->kind == FL_LM_BEACON) {
                beacons_rot += r;
                beacons_mirror += m;
            } else {
                CHECK(m);   /* every field is mirror-symmetric about y = 0 but beacons */
            }
            if (lm->kind != FL_LM_POST && lm->kind != FL_LM_BEACON)
                CHECK(r);   /* lines, crossings, marks, circle: always symmetric */
        }
        CHECK_EQ(all_rot, f->symmetric);
        if (f->symmetric) {
            CHECK_EQ(posts_rot, 4);
        } else {
            CHECK_EQ(posts_rot, 0);    /* differently colored goals */
            CHECK_EQ(beacons_rot, 0);
        }
        CHECK_EQ(beacons_mirror, 0);
    }
}

static void test_digest(void)
{
    size_t s;
    for (s = 0; s < fl_field_count(); s++) {
        const fl_field_t *f = fl_field_at(s);
        uint32_t h = t_hash_init();
        char label[64];
        uint16_t i;
        int a;
        if (!f) {
            CHECK(f != NULL);
            continue;
        }
        h = t_hash_bytes(h, f->name, strlen(f->name));
        h = t_hash_i32(h, f->length_mm);
        h = t_hash_i32(h, f->width_mm);
        h = t_hash_i32(h, f->line_width_mm);
        h = t_hash_i32(h, f->border_mm);
        h = t_hash_i32(h, f->circle_radius_mm);
        h = t_hash_i32(h, f->penalty_area_depth_mm);
        h = t_hash_i32(h, f->penalty_area_width_mm);
        h = t_hash_i32(h, f->goal_area_depth_mm);
        h = t_hash_i32(h, f->goal_area_width_mm);
        h = t_hash_i32(h, f->penalty_mark_x_mm);
        h = t_hash_i32(h, f->mark_size_mm);
        h = t_hash_i32(h, f->goal_width_mm);
        h = t_hash_i32(h, f->post_diameter_mm);
        h = t_hash_i32(h, f->post_height_mm);
        h = t_hash_i32(h, (int32_t)f->goal_color[0]);
        h = t_hash_i32(h, (int32_t)f->goal_color[1]);
        h = t_hash_i32(h, f->symmetric);
        h = t_hash_i32(h, f->beacon_diameter_mm);
        h = t_hash_i32(h, f->beacon_height_mm);
        h = t_hash_i32(h, fl_field_carpet_half_x_mm(f));
        h = t_hash_i32(h, fl_field_carpet_half_y_mm(f));
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            h = t_hash_i32(h, (int32_t)lm->kind);
            h = t_hash_i32(h, lm->x_mm);
            h = t_hash_i32(h, lm->y_mm);
            h = t_hash_i32(h, lm->n_arms);
            for (a = 0; a < FL_FIELD_MAX_ARMS; a++)
                h = t_hash_i32(h, lm->arm[a]);
            h = t_hash_i32(h, (int32_t)lm->side);
            h = t_hash_i32(h, (int32_t)lm->color);
            h = t_hash_i32(h, (int32_t)lm->color2);
            h = t_hash_i32(h, lm->goal);
        }
        for (i = 0; i < (f->features != NULL ? f->n_features : 0); i++) {
            const fl_landmark_t *lm = &f->features[i];
            h = t_hash_i32(h, (int32_t)lm->kind);
            h = t_hash_i32(h, lm->x_mm);
            h = t_hash_i32(h, lm->y_mm);
            h = t_hash_i32(h, lm->n_arms);
            for (a = 0; a < FL_FIELD_MAX_ARMS; a++)
                h = t_hash_i32(h, lm->arm[a]);
            h = t_hash_i32(h, (int32_t)lm->color);
            h = t_hash_i32(h, lm->goal);
        }
        for (i = 0; i < f->n_lines; i++) {
            h = t_hash_i32(h, f->lines[i].x0_mm);
            h = t_hash_i32(h, f->lines[i].y0_mm);
            h = t_hash_i32(h, f->lines[i].x1_mm);
            h = t_hash_i32(h, f->lines[i].y1_mm);
        }
        snprintf(label, sizeof label, "field.%s", f->name);
        t_digest(label, h);
        t_info("%s: %u landmarks (L %u T %u X %u PM %u CM %u post %u circle %u beacon %u), "
               "%u lines, carpet %ld x %ld mm", f->name, (unsigned)f->n_landmarks,
               (unsigned)fl_field_count_kind(f, FL_LM_L), (unsigned)fl_field_count_kind(f, FL_LM_T),
               (unsigned)fl_field_count_kind(f, FL_LM_X),
               (unsigned)fl_field_count_kind(f, FL_LM_PENALTY_MARK),
               (unsigned)fl_field_count_kind(f, FL_LM_CENTRE_MARK),
               (unsigned)fl_field_count_kind(f, FL_LM_POST),
               (unsigned)fl_field_count_kind(f, FL_LM_CENTRE_CIRCLE),
               (unsigned)fl_field_count_kind(f, FL_LM_BEACON), (unsigned)f->n_lines,
               2L * fl_field_carpet_half_x_mm(f), 2L * fl_field_carpet_half_y_mm(f));
    }
}

void suite_field(void)
{
    t_run("field.catalogue", test_catalogue);
    t_run("field.lookup_bad_input", test_lookup_bad_input);
    t_run("field.params", test_params);
    t_run("field.counts", test_counts);
    t_run("field.landmark_fields", test_landmark_fields);
    t_run("field.lines", test_lines);
    t_run("field.crossings_from_lines", test_crossings_from_lines);
    t_run("field.features_from_lines", test_features_from_lines);
    t_run("field.arm_probes", test_arm_probes);
    t_run("field.marks", test_marks);
    t_run("field.posts", test_posts);
    t_run("field.beacons", test_beacons);
    t_run("field.symmetry", test_symmetry);
    t_run("field.digest", test_digest);
}
