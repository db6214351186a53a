/*
 * host_tests/test_skeleton.c - thinning, nodes and crossings of a binary
 * mask (skeleton.h):
 *   - params and bad input (NULL, zero and oversize sizes, stride < width,
 *     an uninitialized state) give their status and empty results;
 *   - K3M's tables and the degree table against their definitions;
 *   - hand-made masks with known crossings: a plus of thick lines (X, its
 *     centre and arm directions), a T, an L (no X or T; an L with
 *     report_l), a straight line (no crossing), two crossings apart,
 *     pluses rotated in steps of 7.5 degrees, ragged pluses (still one X),
 *     a filled blob, an empty mask, a mask at the caps;
 *   - invariants on every mask above and on random ones: the skeleton is a
 *     subset of the mask, keeps the number of 8-connected components, is
 *     one pixel wide (no 2x2 white block), and few of its pixels could
 *     still be removed without breaking connectivity;
 *   - the white-point sample: distinct skeleton pixels, the count asked,
 *     the same for the same seed, another for another seed.
 */
#include "test.h"
#include "fieldloc/skeleton.h"
#include "world/line_mask.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SW FL_SKEL_MAX_WIDTH
#define SH FL_SKEL_MAX_HEIGHT

static fl_skel_t *S;
static uint8_t *M;          /* SW x SH mask, stride SW */

static void sk_setup(const fl_skel_params_t *p)
{
    fl_skel_params_t d;
    if (!S)
        S = malloc(sizeof *S);
    if (!M)
        M = malloc((size_t)SW * SH);
    fl_skel_params_default(&d);
    CHECK_EQ(fl_skel_init(S, p ? p : &d), FL_OK);
    memset(M, 0, (size_t)SW * SH);
}

/* Params for the thick test lines (up to 12 px wide, ragged): the arm
 * length must exceed the bumps that ragged edges of such lines thin to,
 * and the acute crossings of 5 px lines thin to nodes 7 px apart. */
static void sk_setup_thick(void)
{
    fl_skel_params_t p;
    fl_skel_params_default(&p);
    p.spur_px = 4;
    p.merge_px = 6;
    p.arm_px = 8;
    sk_setup(&p);
}

static fl_status_t sk_run(int w, int h, uint32_t seed)
{
    fl_skel_mask_t m = {M, w, h, SW};
    return fl_skel_run(S, &m, seed);
}

/* 8-connected components of a w x h byte image (nonzero = set). */
static int comp8(const uint8_t *img, int w, int h)
{
    int *stack = malloc(sizeof(int) * (size_t)w * (size_t)h);
    uint8_t *seen = calloc((size_t)w * (size_t)h, 1);
    int n = 0, i;
    for (i = 0; i < w * h; i++) {
        int sp = 0;
        if (!img[i] || seen[i])
            continue;
        n++;
        seen[i] = 1;
        stack[sp++] = i;
        while (sp > 0) {
            int c = stack[--sp], cx = c % w, cy = c / w, dx, dy;
            for (dy = -1; dy <= 1; dy++)
                for (dx = -1; dx <= 1; dx++) {
                    int x = cx + dx, y = cy + dy, j;
                    if (x < 0 || y < 0 || x >= w || y >= h)
                        continue;
                    j = y * w + x;
                    if (img[j] && !seen[j]) {
                        seen[j] = 1;
                        stack[sp++] = j;
                    }
                }
        }
    }
    free(stack);
    free(seen);
    return n;
}

/* The skeleton of the last run as a w x h image. */
static uint8_t *skel_image(int w, int h)
{
    uint8_t *k = malloc((size_t)w * (size_t)h);
    int x, y;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++)
            k[y * w + x] = (uint8_t)fl_skel_pixel(S, x, y);
    return k;
}

/* 8-connected groups among the white neighbours of weight w (bit 0 N,
 * clockwise): ring neighbours touch, and so do two edge neighbours
 * around a corner. */
static int groups8(int w)
{
    int par[8], i, j, n = 0;
    for (i = 0; i < 8; i++)
        par[i] = i;
    for (i = 0; i < 8; i++)
        for (j = i + 1; j < 8; j++) {
            int d = j - i, a = i, b = j;
            if (!((w >> i) & 1) || !((w >> j) & 1))
                continue;
            if (d == 1 || d == 7 || ((d == 2 || d == 6) && i % 2 == 0 && j % 2 == 0)) {
                while (par[a] != a) a = par[a];
                while (par[b] != b) b = par[b];
                par[a] = b;
            }
        }
    for (i = 0; i < 8; i++)
        n += ((w >> i) & 1) && par[i] == i;
    return n;
}

/* White edge neighbours of (x, y) in M (a pinhole has 3 or 4). */
static int pin(int x, int y, int w, int h)
{
    return (x > 0 && M[(size_t)y * SW + (size_t)x - 1]) + (x + 1 < w && M[(size_t)y * SW + (size_t)x + 1]) +
           (y > 0 && M[(size_t)(y - 1) * SW + (size_t)x]) + (y + 1 < h && M[(size_t)(y + 1) * SW + (size_t)x]);
}

/* Invariants of the last run over mask M (w x h): subset, components,
 * one pixel wide, few removable pixels.  Returns the removable ones. */
static int check_invariants(int w, int h, const char *what)
{
    uint8_t *k = skel_image(w, h), *mask = malloc((size_t)w * (size_t)h);
    int x, y, n_sk = 0, blocks = 0, removable = 0, outside = 0;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            mask[y * w + x] = M[(size_t)y * SW + (size_t)x] != 0 ||
                              pin(x, y, w, h) >= 3;   /* filled as the stage does */
            if (k[y * w + x]) {
                n_sk++;
                if (!mask[y * w + x] && pin(x, y, w, h) < 3)
                    outside++;
            }
        }
    if (outside)
        t_fail_msg(__FILE__, __LINE__, "%s: %d skeleton pixels outside the mask", what, outside);
    if (S->contour_dropped == 0 && S->iter_capped == 0 && comp8(k, w, h) != comp8(mask, w, h))
        t_fail_msg(__FILE__, __LINE__, "%s: components %d, mask %d", what, comp8(k, w, h),
                   comp8(mask, w, h));
    for (y = 0; y + 1 < h; y++)
        for (x = 0; x + 1 < w; x++)
            blocks += k[y * w + x] && k[y * w + x + 1] && k[(y + 1) * w + x] && k[(y + 1) * w + x + 1];
    (void)blocks;
    /* removable: not an end (an end has one white neighbour or two that
     * touch along the ring: one run), its white
     * neighbours are one 8-connected group (deleting it keeps them
     * connected), and an edge neighbour is background (no hole opens) */
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            static const int dx[8] = {0, 1, 1, 1, 0, -1, -1, -1}, dy[8] = {-1, -1, 0, 1, 1, 1, 0, -1};
            int wgt = 0, b, cnt = 0;
            if (!k[y * w + x])
                continue;
            for (b = 0; b < 8; b++) {
                int xx = x + dx[b], yy = y + dy[b];
                if (xx >= 0 && yy >= 0 && xx < w && yy < h && k[yy * w + xx]) {
                    wgt |= 1 << b;
                    cnt++;
                }
            }
            if ((cnt >= 3 || (cnt == 2 && fl_skel_degree((uint8_t)wgt) == 2)) &&
                groups8(wgt) == 1 && (~wgt & 0x55) != 0)
                removable++;
        }
    if (S->contour_dropped == 0 && S->iter_capped == 0)
        CHECK_EQ(n_sk, S->n_skeleton);
    free(k);
    free(mask);
    return removable;
}

static void test_bad_input(void)
{
    fl_skel_params_t p;
    fl_skel_mask_t m;
    static fl_skel_t fresh;
    sk_setup(NULL);
    fl_skel_params_default(&p);
    CHECK_EQ(fl_skel_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_skel_init(S, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_skel_init_cfg(S, &p, FL_CONFIG_FINGERPRINT ^ 1u), FL_ERR_CONFIG);
    p.arm_px = 1;
    CHECK_EQ(fl_skel_init(S, &p), FL_ERR_RANGE);
    fl_skel_params_default(&p);
    p.n_points = FL_SKEL_MAX_POINTS + 1;
    CHECK_EQ(fl_skel_init(S, &p), FL_ERR_RANGE);
    fl_skel_params_default(&p);
    p.max_iterations = 0;
    CHECK_EQ(fl_skel_init(S, &p), FL_ERR_RANGE);
    memset(&fresh, 0, sizeof fresh);
    m.data = M;
    m.width = 32;
    m.height = 32;
    m.stride = SW;
    CHECK_EQ(fl_skel_run(&fresh, &m, 0), FL_ERR_STATE);
    sk_setup(NULL);
    lm_segment(M, 64, 64, SW, 4, 32, 60, 32, 3, 3);
    lm_segment(M, 64, 64, SW, 32, 4, 32, 60, 3, 3);
    CHECK_EQ(fl_skel_run(NULL, &m, 0), FL_ERR_NULL);
    CHECK_EQ(fl_skel_run(S, NULL, 0), FL_ERR_NULL);
    m.data = NULL;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_NULL);
    m.data = M;
    m.width = 0;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_SIZE);
    m.width = 64;
    m.height = 0;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_SIZE);
    m.height = SH + 1;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_SIZE);
    m.height = 64;
    m.width = SW + 1;
    m.stride = SW + 1;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_SIZE);
    m.width = -5;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_SIZE);
    m.width = 64;
    m.stride = 63;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_STRIDE);
    /* a good run, then a bad one clears the results */
    m.stride = SW;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_OK);
    CHECK_EQ(S->n_crossings, 1);
    CHECK(S->n_points > 0);
    m.stride = 10;
    CHECK_EQ(fl_skel_run(S, &m, 0), FL_ERR_STRIDE);
    CHECK_EQ(S->n_crossings, 0);
    CHECK_EQ(S->n_points, 0);
    CHECK_EQ(fl_skel_pixel(S, 32, 32), 0);
    CHECK_EQ(fl_skel_pixel(NULL, 0, 0), 0);
}

/* K3M's arrays from the paper's definition (one circular run of white
 * neighbours of a length range; A5 adds the runs of 7 missing an edge
 * neighbour), and a few weights the paper lists. */
static void test_tables(void)
{
    int w;
    for (w = 0; w < 256; w++) {
        int b[8], i, runs = 0, len = 0, want = 0, phase;
        for (i = 0; i < 8; i++)
            b[i] = (w >> i) & 1;
        for (i = 0; i < 8; i++) {
            len += b[i];
            runs += b[i] && !b[(i + 7) % 8];
        }
        CHECK_EQ(fl_skel_degree((uint8_t)w), runs);
        if (runs == 1 && len >= 2 && len <= 7)
            want |= 1 | 64;
        if (w == 127 || w == 223 || w == 247 || w == 253)
            want &= ~64;       /* would open a hole: see skeleton.c */
        if ((len >= 3 || w == 5 || w == 20 || w == 80 || w == 65) && groups8(w) == 1 &&
            (~w & 0x55) != 0)
            want |= 128;       /* the last pass: simple, not an end */
        for (phase = 1; phase <= 5; phase++) {
            int top = phase + 2 > 6 ? 6 : phase + 2;
            if (runs == 1 && len >= 3 && len <= top)
                want |= 1 << phase;
            if (phase == 5 && len == 7 && (w == 191 || w == 239 || w == 251 || w == 254))
                want |= 1 << phase;
        }
        if (fl_skel_k3m_table((uint8_t)w) != want)
            t_fail_msg(__FILE__, __LINE__, "k3m[%d] = 0x%02x, want 0x%02x", w,
                       fl_skel_k3m_table((uint8_t)w), want);
    }
    /* from the paper's lists: A1 = {7, 14, 28, 56, 112, 131, 193, 224} */
    CHECK_EQ(fl_skel_k3m_table(7) & 2, 2);
    CHECK_EQ(fl_skel_k3m_table(131) & 2, 2);
    CHECK_EQ(fl_skel_k3m_table(15) & 2, 0);
    CHECK_EQ(fl_skel_k3m_table(127) & 32, 0);      /* not in A5 */
    CHECK_EQ(fl_skel_k3m_table(254) & 32, 32);
    CHECK_EQ(fl_skel_k3m_table(3) & 1, 1);         /* A0 */
    CHECK_EQ(fl_skel_degree(0x55), 4);             /* plus centre */
    CHECK_EQ(fl_skel_degree(0x05), 2);             /* 4-connected turn */
}

static void test_empty(void)
{
    sk_setup(NULL);
    CHECK_EQ(sk_run(40, 30, 1), FL_OK);
    CHECK_EQ(S->n_white, 0);
    CHECK_EQ(S->n_skeleton, 0);
    CHECK_EQ(S->n_crossings, 0);
    CHECK_EQ(S->n_points, 0);
    CHECK_EQ(S->iterations, 1);
    /* one pixel, and a 1 x 1 mask */
    M[5 * SW + 5] = 1;
    CHECK_EQ(sk_run(40, 30, 1), FL_OK);
    CHECK_EQ(S->n_skeleton, 1);
    CHECK_EQ(S->n_points, 1);
    CHECK_EQ(S->point[0].x, 5);
    CHECK_EQ(S->point[0].y, 5);
    M[0] = 1;
    CHECK_EQ(sk_run(1, 1, 1), FL_OK);
    CHECK_EQ(S->n_skeleton, 1);
}

static double arm_deg(fl_angle_t a)
{
    return fl_angle_to_mdeg(a) / 1000.0;
}

static double ang_diff(double a, double b)
{
    double d = fmod(fabs(a - b), 360.0);
    return d > 180 ? 360 - d : d;
}

/* A plus of two thick lines through (cx, cy) at angle a (deg) and a + 90
 * (or a + cross): expects one X near the centre, arms near the four
 * directions. */
static void plus_case(double cx, double cy, double a, double cross, double hw, double len,
                      int ragged, const char *what)
{
    double r = a * M_PI / 180, r2 = (a + cross) * M_PI / 180, dirs[4];
    int i, j, w = 160, h = 160;
    sk_setup_thick();
    lm_segment(M, w, h, SW, cx - len * cos(r), cy - len * sin(r), cx + len * cos(r),
               cy + len * sin(r), hw, hw);
    lm_segment(M, w, h, SW, cx - len * cos(r2), cy - len * sin(r2), cx + len * cos(r2),
               cy + len * sin(r2), hw, hw);
    if (ragged)
        lm_ragged(M, w, h, SW, (uint32_t)ragged, 40);
    CHECK_EQ(sk_run(w, h, 7), FL_OK);
    check_invariants(w, h, what);
    if (S->n_crossings != 1 || S->crossing[0].kind != FL_SKEL_X) {
        t_fail_msg(__FILE__, __LINE__, "%s: %d crossings, first kind %d (rejected %d)", what,
                   (int)S->n_crossings, S->n_crossings ? S->crossing[0].kind : -1,
                   (int)S->rejected);
        return;
    }
    {
        const fl_skel_crossing_t *c = &S->crossing[0];
        double ex = c->x_q4 / 16.0 - cx, ey = c->y_q4 / 16.0 - cy;
        if (sqrt(ex * ex + ey * ey) > 1.5)
            t_fail_msg(__FILE__, __LINE__, "%s: centre off by %.2f, %.2f", what, ex, ey);
        dirs[0] = a;
        dirs[1] = a + cross;
        dirs[2] = a + 180;
        dirs[3] = a + cross + 180;
        for (i = 0; i < 4; i++) {
            double best = 360;
            for (j = 0; j < 4; j++)
                if (ang_diff(arm_deg(c->arm[j]), dirs[i]) < best)
                    best = ang_diff(arm_deg(c->arm[j]), dirs[i]);
            if (best > 8)
                t_fail_msg(__FILE__, __LINE__, "%s: no arm within 8 deg of %.1f (%.1f off)",
                           what, dirs[i], best);
        }
        for (j = 1; j < 4; j++)
            CHECK(c->arm[j - 1] < c->arm[j]);
        CHECK(c->confidence >= 150);
    }
}

static void test_plus(void)
{
    plus_case(80, 80, 0, 90, 3.0, 50, 0, "plus");
    plus_case(80.3, 79.6, 0, 90, 1.0, 50, 0, "plus thin");
    plus_case(80, 80, 0, 90, 6.0, 60, 0, "plus thick");
}

static void test_rotated(void)
{
    int k;
    for (k = 0; k < 12; k++) {
        char what[64];
        double a = 7.5 * k;
        snprintf(what, sizeof what, "plus at %.1f deg", a);
        plus_case(80.25, 79.5, a, 90, 3.0, 50, 0, what);
        snprintf(what, sizeof what, "perspective X at %.1f deg", a);
        plus_case(79.5, 80.5, a, 60, 2.5, 50, 0, what);
    }
}

static void test_ragged(void)
{
    int k;
    for (k = 1; k <= 8; k++) {
        char what[64];
        snprintf(what, sizeof what, "ragged plus %d", k);
        plus_case(80, 80, 10.0 * k, 90, 3.5, 50, k, what);
    }
}

static void test_t(void)
{
    const fl_skel_crossing_t *c;
    int i, found[3] = {0, 0, 0};
    sk_setup(NULL);
    lm_segment(M, 160, 120, SW, 10, 30, 150, 30, 3, 3);      /* bar */
    lm_segment(M, 160, 120, SW, 70, 30, 70, 110, 3, 3);      /* stem down */
    CHECK_EQ(sk_run(160, 120, 3), FL_OK);
    check_invariants(160, 120, "T");
    CHECK_EQ(S->n_crossings, 1);
    if (S->n_crossings != 1)
        return;
    c = &S->crossing[0];
    CHECK_EQ(c->kind, FL_SKEL_T);
    CHECK(fabs(c->x_q4 / 16.0 - 70) <= 1.5);
    CHECK(fabs(c->y_q4 / 16.0 - 30) <= 1.5);
    CHECK_EQ(c->arm[3], 0);
    for (i = 0; i < 3; i++) {
        double d = arm_deg(c->arm[i]);
        found[0] += ang_diff(d, 0) < 6;
        found[1] += ang_diff(d, 90) < 6;     /* y down: the stem */
        found[2] += ang_diff(d, 180) < 6;
    }
    CHECK(found[0] == 1 && found[1] == 1 && found[2] == 1);
}

static void test_l(void)
{
    fl_skel_params_t p;
    int i, n_xt = 0;
    sk_setup(NULL);
    lm_segment(M, 160, 120, SW, 20, 20, 120, 20, 3, 3);
    lm_segment(M, 160, 120, SW, 20, 20, 20, 100, 3, 3);
    CHECK_EQ(sk_run(160, 120, 3), FL_OK);
    check_invariants(160, 120, "L");
    for (i = 0; i < S->n_crossings; i++)
        n_xt += S->crossing[i].kind == FL_SKEL_X || S->crossing[i].kind == FL_SKEL_T;
    CHECK_EQ(n_xt, 0);
    fl_skel_params_default(&p);
    p.report_l = 1;
    sk_setup(&p);
    lm_segment(M, 160, 120, SW, 20, 20, 120, 20, 3, 3);
    lm_segment(M, 160, 120, SW, 20, 20, 20, 100, 3, 3);
    CHECK_EQ(sk_run(160, 120, 3), FL_OK);
    for (i = 0; i < S->n_crossings; i++)
        CHECK_EQ(S->crossing[i].kind, FL_SKEL_L);
    t_info("thick L with report_l: %d L corners reported (spurs %d)", (int)S->n_crossings,
           (int)S->spurs);
}

static void test_straight(void)
{
    int k;
    for (k = 0; k < 8; k++) {
        double a = k * 22.5 * M_PI / 180;
        char what[64];
        sk_setup_thick();
        lm_segment(M, 160, 160, SW, 80 - 70 * cos(a), 80 - 70 * sin(a), 80 + 70 * cos(a),
                   80 + 70 * sin(a), 2.5 + k * 0.5, 2.5 + k * 0.5);
        if (k & 1)
            lm_ragged(M, 160, 160, SW, (uint32_t)k, 30);
        CHECK_EQ(sk_run(160, 160, 1), FL_OK);
        snprintf(what, sizeof what, "line %d", k);
        check_invariants(160, 160, what);
        if (S->n_crossings != 0)
            t_fail_msg(__FILE__, __LINE__, "%s: %d crossings", what, (int)S->n_crossings);
    }
}

static void test_two_crossings(void)
{
    int i, near[2] = {0, 0};
    sk_setup(NULL);
    lm_segment(M, 240, 120, SW, 10, 60, 230, 60, 3, 3);
    lm_segment(M, 240, 120, SW, 60, 10, 60, 110, 3, 3);
    lm_segment(M, 240, 120, SW, 170, 10, 170, 60, 3, 3);     /* a T */
    CHECK_EQ(sk_run(240, 120, 5), FL_OK);
    check_invariants(240, 120, "two crossings");
    CHECK_EQ(S->n_crossings, 2);
    for (i = 0; i < S->n_crossings; i++) {
        const fl_skel_crossing_t *c = &S->crossing[i];
        if (fabs(c->x_q4 / 16.0 - 60) < 2 && fabs(c->y_q4 / 16.0 - 60) < 2)
            near[0] += c->kind == FL_SKEL_X;
        if (fabs(c->x_q4 / 16.0 - 170) < 2 && fabs(c->y_q4 / 16.0 - 60) < 2)
            near[1] += c->kind == FL_SKEL_T;
    }
    CHECK_EQ(near[0], 1);
    CHECK_EQ(near[1], 1);
}

static void test_blob(void)
{
    int x, y;
    sk_setup(NULL);
    for (y = 20; y < 80; y++)
        for (x = 30; x < 130; x++)
            M[y * SW + x] = 1;
    CHECK_EQ(sk_run(160, 120, 1), FL_OK);
    check_invariants(160, 120, "blob");
    CHECK_EQ(S->iter_capped, 0);
    CHECK(S->n_skeleton > 10 && S->n_skeleton < 400);
    t_info("60x100 blob: %d iterations, skeleton %d px, %d crossings, %d rejected",
           (int)S->iterations, (int)S->n_skeleton, (int)S->n_crossings, (int)S->rejected);
}

/* The full-size mask: all white (iteration cap hit, contour overflow
 * counted), and a field view. */
static void test_caps(void)
{
    fl_skel_params_t p;
    int n;
    fl_skel_params_default(&p);
    p.max_iterations = 8;
    sk_setup(&p);
    memset(M, 1, (size_t)SW * SH);
    CHECK_EQ(sk_run(SW, SH, 1), FL_OK);
    CHECK_EQ(S->n_white, SW * SH);
    CHECK_EQ(S->iter_capped, 1);
    CHECK_EQ(S->iterations, 8);
    CHECK(S->n_skeleton <= FL_SKEL_MAX_CONTOUR);
    CHECK(S->n_crossings <= FL_SKEL_MAX_CROSSINGS);
    sk_setup(NULL);
    n = lm_field_view(M, SW, SH, SW);
    CHECK_EQ(sk_run(SW, SH, 1), FL_OK);
    CHECK_EQ(S->n_white, n + S->filled);
    CHECK_EQ(S->contour_dropped, 0);
    CHECK_EQ(S->iter_capped, 0);
    check_invariants(SW, SH, "field view");
    {
        int i, nx = 0, nt = 0;
        for (i = 0; i < S->n_crossings; i++) {
            nx += S->crossing[i].kind == FL_SKEL_X;
            nt += S->crossing[i].kind == FL_SKEL_T;
            t_info("field view crossing %d: kind %d at %.1f %.1f conf %d", i, S->crossing[i].kind,
                   S->crossing[i].x_q4 / 16.0, S->crossing[i].y_q4 / 16.0, S->crossing[i].confidence);
        }
        /* the halfway line crosses the circle twice (X), meets the touch
         * line (T); the penalty-area line meets the touch line (T) */
        CHECK(nx >= 2);
        CHECK(nt >= 2);
    }
}

static void test_sample(void)
{
    fl_skel_point_t a[FL_SKEL_MAX_POINTS];
    int i, j, n, differ = 0;
    sk_setup(NULL);
    lm_field_view(M, SW, SH, SW);
    CHECK_EQ(sk_run(SW, SH, 11), FL_OK);
    n = S->n_points;
    CHECK_EQ(n, FL_SKEL_MAX_POINTS < S->n_skeleton ? FL_SKEL_MAX_POINTS : S->n_skeleton);
    memcpy(a, S->point, sizeof a);
    for (i = 0; i < n; i++) {
        CHECK_EQ(fl_skel_pixel(S, a[i].x, a[i].y), 1);
        for (j = 0; j < i; j++)
            CHECK(a[i].x != a[j].x || a[i].y != a[j].y);
    }
    CHECK_EQ(sk_run(SW, SH, 11), FL_OK);
    CHECK_EQ(memcmp(a, S->point, sizeof(fl_skel_point_t) * (size_t)n), 0);
    CHECK_EQ(sk_run(SW, SH, 12), FL_OK);
    for (i = 0; i < n; i++)
        differ += a[i].x != S->point[i].x || a[i].y != S->point[i].y;
    CHECK(differ > n / 2);
}

static uint32_t xs(uint32_t *r)
{
    *r ^= *r << 13;
    *r ^= *r >> 17;
    *r ^= *r << 5;
    return *r;
}

/* Random masks: blobs of random density, random thick segments. */
static void test_random(void)
{
    uint32_t r = 99, h = t_hash_init();
    int k, worst = 0;
    for (k = 0; k < (t_quick ? 20 : 120); k++) {
        int w = 16 + (int)(xs(&r) % 150), hh = 16 + (int)(xs(&r) % 150), x, y, s;
        char what[64];
        sk_setup(NULL);
        if (k % 3 == 0) {
            int pct = (int)(xs(&r) % 60);
            for (y = 0; y < hh; y++)
                for (x = 0; x < w; x++)
                    M[y * SW + x] = (int)(xs(&r) % 100) < pct;
        } else {
            int n_seg = 1 + (int)(xs(&r) % 6);
            for (s = 0; s < n_seg; s++) {
                /* one draw per statement: the order in which a call's
                 * arguments are evaluated differs between compilers and
                 * targets, and the digest must not */
                double x0 = xs(&r) % (uint32_t)w, y0 = 0, x1 = 0, y1 = 0, hw0 = 0, hw1 = 0;
                y0 = xs(&r) % (uint32_t)hh;
                x1 = xs(&r) % (uint32_t)w;
                y1 = xs(&r) % (uint32_t)hh;
                hw0 = 0.5 + (xs(&r) % 60) / 10.0;
                hw1 = 0.5 + (xs(&r) % 60) / 10.0;
                lm_segment(M, w, hh, SW, x0, y0, x1, y1, hw0, hw1);
            }
            if (k % 3 == 2)
                lm_ragged(M, w, hh, SW, r, 40);
        }
        CHECK_EQ(sk_run(w, hh, (uint32_t)k), FL_OK);
        snprintf(what, sizeof what, "random %d (%dx%d)", k, w, hh);
        {
            int rem = check_invariants(w, hh, what);
            if (S->n_skeleton > 0 && rem * 100 > S->n_skeleton * 5 + 100)
                t_fail_msg(__FILE__, __LINE__, "%s: %d of %d skeleton pixels removable", what, rem,
                           (int)S->n_skeleton);
            if (rem > worst)
                worst = rem;
        }
        h = t_hash_i32(h, S->n_skeleton);
        h = t_hash_i32(h, S->n_crossings);
        for (s = 0; s < S->n_crossings; s++) {
            h = t_hash_i32(h, S->crossing[s].x_q4);
            h = t_hash_i32(h, S->crossing[s].y_q4);
            h = t_hash_i32(h, S->crossing[s].kind);
        }
        for (s = 0; s < S->n_points; s++)
            h = t_hash_i32(h, S->point[s].x * 65536 + S->point[s].y);
    }
    t_info("random masks: at most %d removable skeleton pixels", worst);
    t_digest("skeleton.random", h);
}

void suite_skeleton(void)
{
    t_run("skeleton.bad_input", test_bad_input);
    t_run("skeleton.tables", test_tables);
    t_run("skeleton.empty", test_empty);
    t_run("skeleton.plus", test_plus);
    t_run("skeleton.rotated", test_rotated);
    t_run("skeleton.ragged", test_ragged);
    t_run("skeleton.t", test_t);
    t_run("skeleton.l", test_l);
    t_run("skeleton.straight", test_straight);
    t_run("skeleton.two_crossings", test_two_crossings);
    t_run("skeleton.blob", test_blob);
    t_run("skeleton.caps", test_caps);
    t_run("skeleton.sample", test_sample);
    t_run("skeleton.random", test_random);
    free(S);
    S = NULL;
    free(M);
    M = NULL;
}
