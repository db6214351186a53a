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
        if (best > 600)
            continue;
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
    t_digest("coach.feet", hash);
    CHECK(matched >= robots * 9 / 10);
    CHECK_EQ(wrong, 0);
    CHECK_LE(extra, robots / 20);
    CHECK_LE(nm, 80);
    CHECK_LE(fm, 150);
}

void suite_coach(void)
{
    t_run("coach.feet", test_feet);
}
