/*
 * host_tests/test_coach.c - the coach's image path (coach.h): a* against a
 * double CIE L*a*b*, Otsu against a double reference, opening and closing
 * against a naive per-pixel reference, the feet of rendered coach views
 * (spl2016, nao6-top-640, the coach at x = 0, y = -6000 mm facing +y, head
 * 14 deg down) against the robots' true positions, occlusion, an empty
 * field, bad input.
 */
#include "test.h"
#include "fieldloc/coach.h"
#include "fieldloc/camera.h"
#include "../tools/world/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- scenes ------------------------------------------------------------ */

#define COACH_Y_MM (-6000)
#define COACH_PITCH_MDEG 14000

static void coach_scene(render_scene_t *sc, int background)
{
    render_scene_default(sc, fl_field_find("spl2016"), fl_camera_model_find("nao6-top-640"));
    sc->robot_x_mm = 0;
    sc->robot_y_mm = COACH_Y_MM;
    sc->robot_heading = fl_angle_from_mdeg(90000);
    sc->head.head_pitch = fl_angle_from_mdeg(COACH_PITCH_MDEG);
    sc->background = background;
    sc->n_robots = 0;
}

/* The homography from the renderer's projection of the field points in
 * view (pixel centres rounded to 1/16 px). */
static int coach_homog(const render_scene_t *sc, fl_homog_t *h)
{
    fl_homog_field_point_t fp[FL_HOMOG_FIELD_POINTS];
    fl_homog_pair_t pairs[FL_HOMOG_FIELD_POINTS];
    size_t n = fl_homog_field_points(sc->field, fp, FL_HOMOG_FIELD_POINTS), i, k = 0;
    for (i = 0; i < n; i++) {
        double u, v, r;
        if (!render_project_field(sc, fp[i].x_mm, fp[i].y_mm, 0, &u, &v, &r))
            continue;
        if (u < 0 || v < 0 || u > 639 || v > 479)
            continue;
        pairs[k].u_q4 = (int32_t)lround(u * 16);
        pairs[k].v_q4 = (int32_t)lround(v * 16);
        pairs[k].x_mm = fp[i].x_mm;
        pairs[k].y_mm = fp[i].y_mm;
        k++;
    }
    return fl_homog_fit(h, pairs, k) == FL_HOMOG_OK ? (int)k : -1;
}

/* A coach set up for sc's world: homography and (when bg) the empty field
 * rendered with another noise seed.  0 on success. */
static int coach_setup(fl_coach_t *c, const render_scene_t *sc, int bg)
{
    fl_coach_params_t p;
    fl_homog_t h;
    render_scene_t e = *sc;
    render_frame_t fr;
    fl_coach_params_default(&p);
    if (fl_coach_init(c, &p) != FL_OK || coach_homog(sc, &h) < 4)
        return -1;
    if (bg) {
        e.n_robots = 0;
        e.ball = 0;
        e.seed = sc->seed + 1000;
        if (render_frame(&e, &fr) != 0)
            return -1;
        if (fl_coach_set_background(c, &fr.view) != FL_OK) {
            render_frame_free(&fr);
            return -1;
        }
        render_frame_free(&fr);
    }
    return fl_coach_set_homography(c, &h, sc->field) == FL_OK ? 0 : -1;
}

static double dist_mm(double ax, double ay, double bx, double by)
{
    return sqrt((ax - bx) * (ax - bx) + (ay - by) * (ay - by));
}

static fl_coach_t g_coach;   /* ~850 KB: not on the stack */

/* ---- feet of rendered views --------------------------------------------- */

typedef struct {
    double err[256];
    int n;
} errs_t;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void errs_stats(errs_t *e, double *median, double *max)
{
    *median = *max = 0;
    if (e->n == 0)
        return;
    qsort(e->err, (size_t)e->n, sizeof e->err[0], cmp_double);
    *median = e->err[e->n / 2];
    *max = e->err[e->n - 1];
}

/* A robot wholly in the coach's view (feet and head inside the image). */
static int in_view(const render_scene_t *sc, int32_t x, int32_t y)
{
    double u, v, r, u2, v2;
    if (!render_project_field(sc, x, y, 0, &u, &v, &r) ||
        !render_project_field(sc, x, y, 720, &u2, &v2, &r))
        return 0;
    return u > 25 && u < 615 && u2 > 25 && u2 < 615 && v < 470 && v2 > 2;
}

static double g_along, g_across;
static int g_nalong;

/* Truth-matched feet of one frame: for each robot, the foot of its team
 * nearest to it (within 600 mm); returns robots matched. */
static int match_feet(const render_scene_t *sc, const fl_coach_result_t *res, errs_t *near,
                      errs_t *far, int *wrong_team)
{
    int i, k, matched = 0;
    for (i = 0; i < sc->n_robots; i++) {
        const render_robot_t *rb = &sc->robots[i];
        fl_color_t team = rb->jersey == RENDER_JERSEY_BLUE ? FL_COLOR_BLUE : FL_COLOR_RED;
        double best = 1e9;
        int best_team = 0;
        for (k = 0; k < res->n_feet; k++) {
            double d = dist_mm(res->feet[k].x_mm, res->feet[k].y_mm, rb->x_mm, rb->y_mm);
            if (d < best) {
                best = d;
                best_team = res->feet[k].team;
            }
        }
        if (getenv("COACH_DUMP") && best > 80)
            t_info("  robot %d (%d, %d) heading %d jersey %d: nearest foot %.0f mm", i, rb->x_mm,
                   rb->y_mm, rb->heading, rb->jersey, best);
        if (best > 600)
            continue;
        {
            /* signed error along the ray from the coach (+: beyond the robot) */
            int kb = 0;
            double rx = rb->x_mm - sc->robot_x_mm, ry = rb->y_mm - sc->robot_y_mm, rl;
            for (k = 0; k < res->n_feet; k++)
                if (dist_mm(res->feet[k].x_mm, res->feet[k].y_mm, rb->x_mm, rb->y_mm) <= best)
                    kb = k;
            rl = sqrt(rx * rx + ry * ry);
            g_along += ((res->feet[kb].x_mm - rb->x_mm) * rx + (res->feet[kb].y_mm - rb->y_mm) * ry) / rl;
            g_across += fabs(((res->feet[kb].x_mm - rb->x_mm) * ry - (res->feet[kb].y_mm - rb->y_mm) * rx) / rl);
            g_nalong++;
        }
        matched++;
        if (best_team != (int)team)
            (*wrong_team)++;
        if (dist_mm(rb->x_mm, rb->y_mm, sc->robot_x_mm, sc->robot_y_mm) < 5000) {
            if (near->n < 256)
                near->err[near->n++] = best;
        } else if (far->n < 256) {
            far->err[far->n++] = best;
        }
    }
    return matched;
}

/* Digest of a result (feet, threshold, counters) for the cross-arch check. */
static uint32_t result_hash(uint32_t h, const fl_coach_result_t *r)
{
    int k;
    uint32_t v[6];
    for (k = 0; k < r->n_feet; k++) {
        const fl_coach_foot_t *f = &r->feet[k];
        int j;
        v[0] = (uint32_t)f->x_mm;
        v[1] = (uint32_t)f->y_mm;
        v[2] = (uint32_t)f->u_q4;
        v[3] = (uint32_t)f->v_q4;
        v[4] = (uint32_t)f->team | ((uint32_t)f->confidence << 8) | ((uint32_t)f->sd_mm << 16);
        v[5] = f->jersey_px;
        for (j = 0; j < 6; j++)
            h = (h ^ v[j]) * 16777619u;
    }
    return (h ^ ((uint32_t)r->n_feet | (uint32_t)r->otsu << 8 | (uint32_t)r->no_foot << 16)) *
           16777619u;
}

/* Robots at random places in view (at least 700 mm apart), random headings
 * and jerseys; n frames; the errors of the matched feet. */
static void run_feet(int frames, int per_frame, int clutter, uint64_t seed, errs_t *near,
                     errs_t *far, int *robots, int *matched, int *wrong_team, int *extra,
                     uint32_t *hash)
{
    t_rng_t rng;
    int f;
    t_rng_seed(&rng, seed);
    for (f = 0; f < frames; f++) {
        render_scene_t sc;
        render_frame_t fr;
        fl_coach_result_t res;
        int i, tries = 0;
        coach_scene(&sc, clutter);
        sc.seed = (uint32_t)(100 + f);
        sc.world_seed = (uint32_t)(1 + f % 3);
        while (sc.n_robots < per_frame && tries++ < 1000) {
            int32_t x = t_rng_range(&rng, -4500, 4500), y = t_rng_range(&rng, -3000, 3000);
            int ok = in_view(&sc, x, y);
            for (i = 0; i < sc.n_robots && ok; i++)
                ok = dist_mm(x, y, sc.robots[i].x_mm, sc.robots[i].y_mm) > 700;
            if (!ok)
                continue;
            sc.robots[sc.n_robots].x_mm = x;
            sc.robots[sc.n_robots].y_mm = y;
            sc.robots[sc.n_robots].heading = (fl_angle_t)t_rng_range(&rng, 0, 65535);
            sc.robots[sc.n_robots].jersey = t_rng_range(&rng, 0, 1) ? RENDER_JERSEY_BLUE
                                                                    : RENDER_JERSEY_RED;
            sc.n_robots++;
        }
        CHECK_EQ(coach_setup(&g_coach, &sc, 1), 0);
        CHECK_EQ(render_frame(&sc, &fr), 0);
        CHECK_EQ(fl_coach_frame(&g_coach, &fr.view, &res), FL_OK);
        *robots += sc.n_robots;
        i = match_feet(&sc, &res, near, far, wrong_team);
        *matched += i;
        *extra += res.n_feet > i ? res.n_feet - i : 0;
        *hash = result_hash(*hash, &res);
        if (getenv("COACH_DUMP")) {
            char path[64];
            snprintf(path, sizeof path, "build/coach_feet%d.ppm", f);
            render_write_frame(path, &fr);
            t_info(" frame %d: %u feet, regions %u/%u small %u no_foot %u off %u", f, res.n_feet,
                   res.regions[0], res.regions[1], res.small_regions, res.no_foot, res.off_field);
            for (i = 0; i < res.n_feet; i++)
                t_info("  foot team %d (%d, %d) px (%.2f, %.2f) rows %d..%d jersey %u", res.feet[i].team,
                       res.feet[i].x_mm, res.feet[i].y_mm, res.feet[i].u_q4 / 16.0,
                       res.feet[i].v_q4 / 16.0, res.feet[i].top_v, res.feet[i].bottom_v,
                       res.feet[i].jersey_px);
            for (i = 0; i < sc.n_robots; i++)
                t_info("  robot (%d, %d)", sc.robots[i].x_mm, sc.robots[i].y_mm);
        }
        render_frame_free(&fr);
    }
}

static void test_feet(void)
{
    errs_t near, far;
    int robots = 0, matched = 0, wrong = 0, extra = 0;
    uint32_t hash = 2166136261u;
    double nm, nx, fm, fx;
    int frames = t_quick ? 4 : 40;
    near.n = far.n = 0;
    run_feet(frames, 3, 0, 7, &near, &far, &robots, &matched, &wrong, &extra, &hash);
    errs_stats(&near, &nm, &nx);
    errs_stats(&far, &fm, &fx);
    t_info("coach feet, %d frames, %d robots (3 per frame, random heading): %d found, "
           "%d wrong team, %d extra", frames, robots, matched, wrong, extra);
    t_info("coach foot error within 5 m: median %.0f mm max %.0f mm (%d); beyond: median %.0f "
           "mm max %.0f mm (%d)", nm, nx, near.n, fm, fx, far.n);
    t_info("coach foot error along the ray from the coach: mean %+.0f mm; across: mean |.| %.0f mm",
           g_along / (g_nalong ? g_nalong : 1), g_across / (g_nalong ? g_nalong : 1));
    t_digest("coach.feet", hash);
    CHECK(matched >= robots * 9 / 10);
    CHECK_EQ(wrong, 0);
    CHECK_LE(extra, robots / 20);
    /* measured (40 frames, 112 feet): within 5 m median 25 max 41 mm,
     * beyond median 22 max 80 mm; the targets are 80 mm within 5 m and
     * 150 mm beyond (quick mode: 4 frames, 11 feet) */
    CHECK_LE(nm, 40);
    CHECK_LE(fm, 40);
    CHECK_LE(nx, 80);
    CHECK_LE(fx, 120);
}

/* ---- building blocks ----------------------------------------------------- */

static double d_lin(int c)
{
    double x = c / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

static double d_f(double t)
{
    double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

static double d_lab_a(int r, int g, int b)
{
    double R = d_lin(r), G = d_lin(g), B = d_lin(b);
    double X = (0.412453 * R + 0.357580 * G + 0.180423 * B) / 0.950456;
    double Y = 0.212671 * R + 0.715160 * G + 0.072169 * B;
    return 500.0 * (d_f(X) - d_f(Y)) + 128.0;
}

static void test_lab_a(void)
{
    int r, g, b, step = t_quick ? 15 : 3, n = 0, off1 = 0;
    double worst = 0;
    uint32_t h = 2166136261u;
    for (r = 0; r < 256; r += step)
        for (g = 0; g < 256; g += step)
            for (b = 0; b < 256; b += step) {
                double ref = d_lab_a(r, g, b);
                int got = fl_coach_lab_a((uint8_t)r, (uint8_t)g, (uint8_t)b), want;
                double e;
                if (ref < 0)
                    ref = 0;
                if (ref > 255)
                    ref = 255;
                e = fabs(got - ref);
                want = (int)lround(ref);
                if (e > worst)
                    worst = e;
                off1 += got != want;
                n++;
                h = (h ^ (uint32_t)got) * 16777619u;
            }
    t_info("a*: %d colours, worst |integer - double| %.3f, %d (%.2f %%) not the rounded double",
           n, worst, off1, 100.0 * off1 / n);
    t_digest("coach.lab_a", h);
    CHECK_LE(worst, 1.0);
    CHECK_LE(off1, n / 20);
    /* grey is a* = 0 exactly; the carpet green below, the jerseys above */
    CHECK_EQ(fl_coach_lab_a(255, 255, 255), 128);
    CHECK_EQ(fl_coach_lab_a(0, 0, 0), 128);
    CHECK_EQ(fl_coach_lab_a(128, 128, 128), 128);
    CHECK(fl_coach_lab_a(60, 140, 60) < 100);
    CHECK(fl_coach_lab_a(205, 40, 45) > 180);
    CHECK(fl_coach_lab_a(40, 70, 190) > 128);
}

/* The between-class variance of threshold t, in double. */
static double d_between(const uint32_t *hist, int t)
{
    double n = 0, s = 0, w0 = 0, s0 = 0, w1, m0, m1;
    int i;
    for (i = 0; i < 256; i++) {
        n += hist[i];
        s += (double)hist[i] * i;
        if (i <= t) {
            w0 += hist[i];
            s0 += (double)hist[i] * i;
        }
    }
    w1 = n - w0;
    if (w0 == 0 || w1 == 0)
        return 0;
    m0 = s0 / w0;
    m1 = (s - s0) / w1;
    return w0 * w1 * (m0 - m1) * (m0 - m1);
}

static void test_otsu(void)
{
    static uint32_t hist[256];
    t_rng_t rng;
    int k, t, worst_t = 0;
    double worst = 0;
    t_rng_seed(&rng, 3);
    memset(hist, 0, sizeof hist);
    CHECK_EQ(fl_coach_otsu(hist), 0);       /* empty */
    CHECK_EQ(fl_coach_otsu(NULL), 0);
    hist[77] = 1000;
    CHECK_EQ(fl_coach_otsu(hist), 0);       /* one value: no split */
    hist[200] = 10;
    t = fl_coach_otsu(hist);                 /* two spikes: between them */
    CHECK(t >= 77 && t < 200);
    for (k = 0; k < (t_quick ? 200 : 2000); k++) {
        int i, modes = t_rng_range(&rng, 1, 4), m, best = 0;
        double vmax = 0, got;
        uint32_t total = (uint32_t)t_rng_range(&rng, 10, 1 << t_rng_range(&rng, 4, 22));
        memset(hist, 0, sizeof hist);
        for (m = 0; m < modes; m++) {
            int c = t_rng_range(&rng, 0, 255), w = t_rng_range(&rng, 0, 30);
            uint32_t part = total / (uint32_t)modes;
            for (i = 0; i < (int)part; i += 1 + (int)(part / 4096)) {
                int v = c + t_rng_range(&rng, -w, w);
                if (v >= 0 && v < 256)
                    hist[v] += 1 + part / 4096;
            }
        }
        for (i = 0; i < 255; i++)
            if (d_between(hist, i) > vmax) {
                vmax = d_between(hist, i);
                best = i;
            }
        t = fl_coach_otsu(hist);
        got = d_between(hist, t);
        if (vmax > 0 && 1.0 - got / vmax > worst) {
            worst = 1.0 - got / vmax;
            worst_t = t - best;
        }
    }
    t_info("Otsu: worst relative shortfall of the between-class variance %.2e (threshold %+d "
           "from the double's)", worst, worst_t);
    CHECK_LE(worst, 1e-3);
}

/* Naive reference: erosion / dilation with a (2r+1)^2 square, outside set
 * (erosion) / clear (dilation). */
static int px_get(const uint8_t *m, int w, int h, int u, int v, int outside)
{
    if (u < 0 || v < 0 || u >= w || v >= h)
        return outside;
    return m[v * w + u];
}

static void naive(uint8_t *m, uint8_t *tmp, int w, int h, int r, int erode)
{
    int u, v, du, dv;
    memcpy(tmp, m, (size_t)(w * h));
    for (v = 0; v < h; v++)
        for (u = 0; u < w; u++) {
            int x = erode;
            for (dv = -r; dv <= r; dv++)
                for (du = -r; du <= r; du++) {
                    int p = px_get(tmp, w, h, u + du, v + dv, erode);
                    x = erode ? (x && p) : (x || p);
                }
            m[v * w + u] = (uint8_t)x;
        }
}

static void pack(const uint8_t *m, uint32_t *bits, int w, int h)
{
    int u, v, words = (w + 31) / 32;
    memset(bits, 0, sizeof(uint32_t) * (size_t)(words * h));
    for (v = 0; v < h; v++)
        for (u = 0; u < w; u++)
            if (m[v * w + u])
                bits[v * words + u / 32] |= 1u << (u % 32);
}

static int same(const uint8_t *m, const uint32_t *bits, int w, int h)
{
    int u, v, words = (w + 31) / 32;
    for (v = 0; v < h; v++) {
        for (u = 0; u < w; u++)
            if (m[v * w + u] != ((bits[v * words + u / 32] >> (u % 32)) & 1u))
                return 0;
        for (u = w; u < words * 32; u++)   /* bits beyond the width stay clear */
            if ((bits[v * words + u / 32] >> (u % 32)) & 1u)
                return 0;
    }
    return 1;
}

static void test_morph(void)
{
    static uint8_t m[100 * 40], t[100 * 40], keep[100 * 40];
    static uint32_t bits[4 * 40], tmp[4 * 40];
    t_rng_t rng;
    int k, bad = 0, cases = t_quick ? 100 : 600;
    t_rng_seed(&rng, 5);
    for (k = 0; k < cases; k++) {
        int w = t_rng_range(&rng, 1, 100), h = t_rng_range(&rng, 1, 40);
        int r = t_rng_range(&rng, 0, 3), dens = t_rng_range(&rng, 5, 95), i, op = k & 1;
        for (i = 0; i < w * h; i++)
            m[i] = (uint8_t)(t_rng_range(&rng, 0, 99) < dens);
        memcpy(keep, m, (size_t)(w * h));
        pack(m, bits, w, h);
        if (op == 0) {
            naive(m, t, w, h, r, 1);
            naive(m, t, w, h, r, 0);
            fl_coach_open(bits, tmp, w, h, r);
        } else {
            naive(m, t, w, h, r, 0);
            naive(m, t, w, h, r, 1);
            fl_coach_close(bits, tmp, w, h, r);
        }
        if (!same(m, bits, w, h))
            bad++;
    }
    CHECK_EQ(bad, 0);
    /* a speck goes, a block stays (opening); a gap fills (closing) */
    memset(m, 0, sizeof m);
    for (k = 10; k < 20; k++) {
        m[k * 100 + 30] = 1;            /* a 1-px wide stroke */
        memset(m + k * 100 + 50, 1, 8); /* an 8 x 10 block */
    }
    m[5 * 100 + 5] = 1;                 /* a speck */
    pack(m, bits, 100, 40);
    fl_coach_open(bits, tmp, 100, 40, 1);
    CHECK_EQ(bits[5 * 4] & (1u << 5), 0);
    CHECK_EQ((bits[15 * 4] >> 30) & 1u, 0);
    CHECK_EQ((bits[15 * 4 + 1] >> (50 - 32)) & 0xFFu, 0xFFu);
    memset(m, 0, sizeof m);
    for (k = 10; k < 20; k++) {
        memset(m + k * 100 + 40, 1, 6);
        memset(m + k * 100 + 47, 1, 6);  /* a one-pixel gap at 46 */
    }
    pack(m, bits, 100, 40);
    fl_coach_close(bits, tmp, 100, 40, 1);
    CHECK_EQ((bits[15 * 4 + 1] >> (46 - 32)) & 1u, 1u);
    (void)keep;
}

/* ---- scenes: empty field, occlusion, formats ------------------------------ */

/* Render sc and run the set-up coach on it (format fmt). */
static fl_status_t frame_of(const render_scene_t *sc0, fl_pixel_format_t fmt,
                            fl_coach_result_t *res)
{
    render_scene_t sc = *sc0;
    render_frame_t fr;
    fl_status_t st;
    sc.format = fmt;
    if (render_frame(&sc, &fr) != 0)
        return FL_ERR_NULL;
    st = fl_coach_frame(&g_coach, &fr.view, res);
    render_frame_free(&fr);
    return st;
}

static void test_empty_field(void)
{
    render_scene_t sc;
    fl_coach_result_t res;
    int s;
    for (s = 0; s < 3; s++) {
        coach_scene(&sc, s == 2);
        sc.seed = (uint32_t)(40 + s);
        sc.world_seed = (uint32_t)(1 + s);
        CHECK_EQ(coach_setup(&g_coach, &sc, s != 1), 0);
        CHECK_EQ(frame_of(&sc, FL_FMT_RGB888, &res), FL_OK);
        CHECK_EQ(res.n_feet, 0);
        t_info("empty field (%s background, %s): %u feet, %u+%u regions, a* threshold %u, "
               "field %u px", s != 1 ? "with" : "no", s == 2 ? "cluttered room" : "plain walls",
               res.n_feet, res.regions[0], res.regions[1], res.otsu, res.field_px);
    }
}

/* Two robots on one line of sight from the coach, the far one partly
 * hidden behind the near one; and two side by side, legs apart. */
static void test_occlusion(void)
{
    static const int32_t cases[][4] = {
        {0, -1500, 0, 0},        /* far one 1.5 m behind: its feet hidden? */
        {-500, -2000, -350, -1000},
        {1000, -500, 1300, 1500},
        {-1500, 0, -1150, 0},    /* side by side, 350 mm apart */
        {150, -1800, 400, 0},    /* the far one's legs behind the near one */
        {-300, -1500, -650, 500},
    };
    int i, k;
    for (i = 0; i < 6; i++) {
        render_scene_t sc;
        fl_coach_result_t res;
        errs_t near, far;
        int wrong = 0, m;
        near.n = far.n = 0;
        coach_scene(&sc, 0);
        sc.seed = (uint32_t)(60 + i);
        sc.n_robots = 2;
        for (k = 0; k < 2; k++) {
            sc.robots[k].x_mm = cases[i][2 * k];
            sc.robots[k].y_mm = cases[i][2 * k + 1];
            sc.robots[k].heading = fl_angle_from_mdeg(30000 + 50000 * k);
            sc.robots[k].jersey = (i + k) & 1 ? RENDER_JERSEY_BLUE : RENDER_JERSEY_RED;
        }
        if (i == 3)
            sc.robots[1].jersey = sc.robots[0].jersey;   /* same team, adjacent */
        CHECK_EQ(coach_setup(&g_coach, &sc, 1), 0);
        CHECK_EQ(frame_of(&sc, FL_FMT_RGB888, &res), FL_OK);
        if (getenv("COACH_DUMP")) {
            render_frame_t fr;
            char path[64];
            snprintf(path, sizeof path, "build/coach_occ%d.ppm", i);
            if (render_frame(&sc, &fr) == 0) {
                render_write_frame(path, &fr);
                render_frame_free(&fr);
            }
        }
        m = match_feet(&sc, &res, &near, &far, &wrong);
        if (getenv("COACH_DUMP"))
            for (k = 0; k < res.n_feet; k++)
                t_info("  foot %d team %d (%d, %d) px (%.2f, %.2f) line a %.1f b %.3f rows %d..%d",
                       k, res.feet[k].team, res.feet[k].x_mm, res.feet[k].y_mm,
                       res.feet[k].u_q4 / 16.0, res.feet[k].v_q4 / 16.0,
                       res.feet[k].line_a_q16 / 65536.0, res.feet[k].line_b_q16 / 65536.0,
                       res.feet[k].top_v, res.feet[k].bottom_v);
        t_info("occlusion case %d: robots (%d, %d) and (%d, %d): %u feet, %d matched, errors "
               "%.0f %.0f mm", i, cases[i][0], cases[i][1], cases[i][2], cases[i][3],
               res.n_feet, m, near.n ? near.err[0] : (far.n ? far.err[0] : -1.0),
               far.n > (near.n ? 0 : 1) ? far.err[near.n ? 0 : 1] : -1.0);
        CHECK_EQ(wrong, 0);
        CHECK(m >= 1);
        CHECK_LE(res.n_feet, 2);
        /* no foot is the wrong robot's: each lies near one robot */
        for (k = 0; k < res.n_feet; k++) {
            double d0 = dist_mm(res.feet[k].x_mm, res.feet[k].y_mm, sc.robots[0].x_mm,
                                sc.robots[0].y_mm);
            double d1 = dist_mm(res.feet[k].x_mm, res.feet[k].y_mm, sc.robots[1].x_mm,
                                sc.robots[1].y_mm);
            CHECK_LE(d0 < d1 ? d0 : d1, 150);
        }
    }
}

/* The same scene as RGB, YUYV and planar frames: the same robots found, the
 * feet within a few cm (chroma subsampling and the YCbCr rounding move
 * edge pixels). */
static void test_formats(void)
{
    static const fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422,
                                              FL_FMT_YCBCR_PLANAR};
    render_scene_t sc;
    fl_coach_result_t res[3];
    int f, k;
    coach_scene(&sc, 0);
    sc.n_robots = 2;
    sc.robots[0].x_mm = -800;
    sc.robots[0].y_mm = -1800;
    sc.robots[0].jersey = RENDER_JERSEY_RED;
    sc.robots[1].x_mm = 1500;
    sc.robots[1].y_mm = 1200;
    sc.robots[1].jersey = RENDER_JERSEY_BLUE;
    CHECK_EQ(coach_setup(&g_coach, &sc, 1), 0);
    for (f = 0; f < 3; f++) {
        CHECK_EQ(frame_of(&sc, fmts[f], &res[f]), FL_OK);
        CHECK_EQ(res[f].n_feet, 2);
    }
    for (f = 1; f < 3; f++)
        for (k = 0; k < 2 && k < res[f].n_feet && k < res[0].n_feet; k++) {
            double d = dist_mm(res[f].feet[k].x_mm, res[f].feet[k].y_mm, res[0].feet[k].x_mm,
                               res[0].feet[k].y_mm);
            t_info("format %s, foot %d: %.0f mm from the RGB frame's",
                   render_format_name(fmts[f]), k, d);
            CHECK_EQ(res[f].feet[k].team, res[0].feet[k].team);
            CHECK_LE(d, 60);
        }
}

/* ---- bad input --------------------------------------------------------------- */

static void test_bad_input(void)
{
    fl_coach_params_t p, q;
    fl_coach_result_t res;
    fl_obs_report_t rep[4];
    fl_homog_t h, none;
    render_scene_t sc;
    render_frame_t fr;
    fl_image_t img;
    const char *why = NULL;
    static uint8_t grey[640 * 480 * 3], small[320 * 240 * 3];
    uint32_t frames;

    fl_coach_params_default(&p);
    CHECK_EQ(fl_coach_params_check(&p, &why), FL_OK);
    CHECK_EQ(why[0], '\0');
    CHECK_EQ(fl_coach_params_check(NULL, &why), FL_ERR_NULL);
    q = p; q.red.h_lo = 180;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    CHECK(strstr(why, "red") != NULL);
    q = p; q.blue.s_lo = 200; q.blue.s_hi = 100;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.open_radius = 5;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.close_radius = 9;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.min_region_px = 0;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.otsu_lo = 160;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.otsu_hi = 255;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.field_pct = 101;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.shadow_pct = 0;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.max_band_px = FL_COACH_MAX_BAND_PX + 1;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    q = p; q.foot_offset_mm = -1;
    CHECK_EQ(fl_coach_params_check(&q, &why), FL_ERR_RANGE);
    CHECK(why[0] != '\0');
    q = p; q.red.h_lo = 180;
    CHECK_EQ(fl_coach_init(&g_coach, &q), FL_ERR_RANGE);
    CHECK_EQ(fl_coach_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_coach_init(&g_coach, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_coach_init_cfg(&g_coach, &p, FL_CONFIG_FINGERPRINT ^ 1u), FL_ERR_CONFIG);

    /* not initialised (the failed init above left it empty) */
    coach_scene(&sc, 0);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK_EQ(fl_coach_frame(&g_coach, &fr.view, &res), FL_ERR_STATE);
    CHECK_EQ(fl_coach_set_background(&g_coach, &fr.view), FL_ERR_STATE);
    CHECK_EQ(fl_coach_frame(NULL, &fr.view, &res), FL_ERR_NULL);

    /* no homography, then a refused one */
    CHECK_EQ(fl_coach_init(&g_coach, &p), FL_OK);
    CHECK_EQ(fl_coach_frame(&g_coach, &fr.view, &res), FL_ERR_STATE);
    CHECK_EQ(g_coach.frames_no_homog, 1);
    memset(&none, 0, sizeof none);
    CHECK_EQ(fl_coach_set_homography(&g_coach, &none, sc.field), FL_ERR_RANGE);
    CHECK_EQ(fl_coach_set_homography(&g_coach, NULL, sc.field), FL_ERR_NULL);
    CHECK(coach_homog(&sc, &h) >= 4);
    CHECK_EQ(fl_coach_set_homography(&g_coach, &h, NULL), FL_ERR_NULL);
    CHECK_EQ(g_coach.homog_refused, 3);
    CHECK_EQ(fl_coach_frame(&g_coach, &fr.view, &res), FL_ERR_STATE);
    /* the coach's map upside down (v -> 479 - v): the frame's bottom row
     * is then the real top row, above the horizon */
    {
        fl_homog_field_point_t fp[FL_HOMOG_FIELD_POINTS];
        fl_homog_pair_t pr[FL_HOMOG_FIELD_POINTS];
        fl_homog_t flip;
        size_t n = fl_homog_field_points(sc.field, fp, FL_HOMOG_FIELD_POINTS), j, m = 0;
        for (j = 0; j < n; j++) {
            double u, v, r;
            if (!render_project_field(&sc, fp[j].x_mm, fp[j].y_mm, 0, &u, &v, &r) || u < 0 ||
                u > 639 || v < 0 || v > 479)
                continue;
            pr[m].u_q4 = (int32_t)lround(u * 16);
            pr[m].v_q4 = (int32_t)lround((479 - v) * 16);
            pr[m].x_mm = fp[j].x_mm;
            pr[m].y_mm = fp[j].y_mm;
            m++;
        }
        CHECK_EQ(fl_homog_fit(&flip, pr, m), FL_HOMOG_OK);
        CHECK_EQ(fl_coach_set_homography(&g_coach, &flip, sc.field), FL_ERR_RANGE);
        CHECK_EQ(g_coach.has_homog, 0);
    }
    CHECK_EQ(fl_coach_set_homography(&g_coach, &h, sc.field), FL_OK);

    /* NULLs, a frame of another size, a broken view */
    frames = g_coach.frames_bad;
    CHECK_EQ(fl_coach_frame(&g_coach, NULL, &res), FL_ERR_NULL);
    CHECK_EQ(fl_coach_frame(&g_coach, &fr.view, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_coach_set_background(&g_coach, &fr.view), FL_OK);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, small, 320, 240, 960), FL_OK);
    CHECK_EQ(fl_coach_frame(&g_coach, &img, &res), FL_ERR_SIZE);
    CHECK_EQ(res.n_feet, 0);
    img = fr.view;
    img.format = (fl_pixel_format_t)9;
    CHECK_EQ(fl_coach_frame(&g_coach, &img, &res), FL_ERR_FORMAT);
    img = fr.view;
    img.stride[0] = 10;
    CHECK_EQ(fl_coach_frame(&g_coach, &img, &res), FL_ERR_STRIDE);
    CHECK_EQ(g_coach.frames_bad, frames + 4);
    CHECK_EQ(fl_coach_set_background(&g_coach, &img), FL_ERR_STRIDE);
    CHECK_EQ(g_coach.has_background, 0);
    /* beyond the capacity */
    {
        static uint8_t big[(FL_COACH_MAX_WIDTH + 2) * 3 * 32];
        CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, big, FL_COACH_MAX_WIDTH + 2, 32,
                                      (FL_COACH_MAX_WIDTH + 2) * 3), FL_OK);
        CHECK_EQ(fl_coach_frame(&g_coach, &img, &res), FL_ERR_SIZE);
        CHECK_EQ(fl_coach_set_background(&g_coach, &img), FL_ERR_SIZE);
    }

    /* no field: a grey frame, then the state still works */
    memset(grey, 128, sizeof grey);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, grey, 640, 480, 1920), FL_OK);
    CHECK_EQ(fl_coach_frame(&g_coach, &img, &res), FL_ERR_NOT_FOUND);
    CHECK_EQ(res.n_feet, 0);
    CHECK_EQ(g_coach.frames_no_field, 1);
    memset(grey, 0, sizeof grey);
    CHECK_EQ(fl_coach_frame(&g_coach, &img, &res), FL_ERR_NOT_FOUND);
    CHECK_EQ(fl_coach_frame(&g_coach, &fr.view, &res), FL_OK);
    CHECK_EQ(res.n_feet, 0);

    /* reports */
    memset(&res, 0, sizeof res);
    res.n_feet = 1;
    res.feet[0].team = FL_COLOR_BLUE;
    res.feet[0].x_mm = 100;
    res.feet[0].y_mm = -200;
    res.feet[0].sd_mm = 60;
    res.feet[0].confidence = 200;
    CHECK_EQ(fl_coach_reports(&res, 40, rep, 4), 1);
    CHECK_EQ(rep[0].team, FL_COLOR_BLUE);
    CHECK_EQ(rep[0].player, 0);
    CHECK_EQ(rep[0].age_ms, 40);
    CHECK_EQ(fl_obs_report_check(&rep[0], sc.field), FL_OK);
    CHECK_EQ(fl_coach_reports(&res, -1, rep, 4), 0);
    CHECK_EQ(fl_coach_reports(NULL, 0, rep, 4), 0);
    CHECK_EQ(fl_coach_reports(&res, 0, rep, 0), 0);
    render_frame_free(&fr);
}

static void test_sizes(void)
{
    t_info("sizeof(fl_coach_t) = %u bytes at %d x %d (background %u, masks %u, class table "
           "%u, runs %u, regions %u)", (unsigned)sizeof(fl_coach_t), FL_COACH_MAX_WIDTH,
           FL_COACH_MAX_HEIGHT, (unsigned)(sizeof g_coach.bg_y + sizeof g_coach.bg_a),
           (unsigned)(sizeof g_coach.mask + sizeof g_coach.moved + sizeof g_coach.tmp),
           (unsigned)sizeof g_coach.cls, (unsigned)sizeof g_coach.runs,
           (unsigned)sizeof g_coach.regions);
    CHECK_LE(sizeof(fl_coach_t), 2u * FL_COACH_MAX_WIDTH * FL_COACH_MAX_HEIGHT +
                                     16u * FL_COACH_MASK_WORDS + 32768u + 2048u +
                                     3u * FL_COACH_MAX_WIDTH + 12u * FL_COACH_MAX_RUNS +
                                     64u * FL_COACH_MAX_REGIONS + 512u);
}

/* A robot on the halfway line (x = 0), the line running on toward the
 * coach below its feet: a* alone calls the paint non-field, so without the
 * background the walk runs on down the line; with it the foot stops at the
 * feet. */
static void test_on_line(void)
{
    render_scene_t sc;
    fl_coach_result_t res;
    double err[2] = {-1, -1};
    int bg;
    coach_scene(&sc, 0);
    sc.seed = 77;
    sc.n_robots = 1;
    sc.robots[0].x_mm = 0;
    sc.robots[0].y_mm = -1000;
    sc.robots[0].heading = fl_angle_from_mdeg(90000);
    sc.robots[0].jersey = RENDER_JERSEY_RED;
    for (bg = 0; bg < 2; bg++) {
        CHECK_EQ(coach_setup(&g_coach, &sc, bg), 0);
        CHECK_EQ(frame_of(&sc, FL_FMT_RGB888, &res), FL_OK);
        CHECK_EQ(res.n_feet, 1);
        CHECK_EQ(res.has_background, bg);
        if (res.n_feet == 1)
            err[bg] = dist_mm(res.feet[0].x_mm, res.feet[0].y_mm, 0, -1000);
    }
    t_info("robot on the halfway line 5 m from the coach: foot error %.0f mm with the "
           "background, %.0f mm from a* alone", err[1], err[0]);
    CHECK(err[1] >= 0 && err[1] <= 80);
    CHECK(err[0] > err[1] + 200);
}

/* Host time of one frame (3 robots, background set). */
static void test_cost(void)
{
    render_scene_t sc;
    render_frame_t fr;
    fl_coach_result_t res;
    clock_t t0;
    int i, n = t_quick ? 2 : 20;
    coach_scene(&sc, 0);
    sc.n_robots = 3;
    sc.robots[0].x_mm = -1000; sc.robots[0].y_mm = -2000;
    sc.robots[1].x_mm = 500; sc.robots[1].y_mm = 0;
    sc.robots[1].jersey = RENDER_JERSEY_BLUE;
    sc.robots[2].x_mm = 2500; sc.robots[2].y_mm = 2000;
    CHECK_EQ(coach_setup(&g_coach, &sc, 1), 0);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    t0 = clock();
    for (i = 0; i < n; i++)
        CHECK_EQ(fl_coach_frame(&g_coach, &fr.view, &res), FL_OK);
    t_info("coach frame 640x480 RGB, 3 robots: %.2f ms on this host (%d frames)",
           1000.0 * (double)(clock() - t0) / CLOCKS_PER_SEC / n, n);
    CHECK_EQ(res.n_feet, 3);
    if (getenv("COACH_DUMP")) {
        render_write_frame("build/coach_cost.ppm", &fr);
        for (i = 0; i < res.n_feet; i++)
            t_info("  foot team %d (%d, %d) px (%.2f, %.2f) rows %d..%d jersey %u b %.3f",
                   res.feet[i].team, res.feet[i].x_mm, res.feet[i].y_mm, res.feet[i].u_q4 / 16.0,
                   res.feet[i].v_q4 / 16.0, res.feet[i].top_v, res.feet[i].bottom_v,
                   res.feet[i].jersey_px, res.feet[i].line_b_q16 / 65536.0);
    }
    render_frame_free(&fr);
}

void suite_coach(void)
{
    t_run("coach.lab_a", test_lab_a);
    t_run("coach.otsu", test_otsu);
    t_run("coach.morph_reference", test_morph);
    t_run("coach.sizes", test_sizes);
    t_run("coach.bad_input", test_bad_input);
    t_run("coach.empty_field", test_empty_field);
    t_run("coach.occlusion", test_occlusion);
    t_run("coach.formats", test_formats);
    t_run("coach.on_line", test_on_line);
    t_run("coach.cost", test_cost);
    t_run("coach.feet", test_feet);
}
