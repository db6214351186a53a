/*
 * host_tests/test_team.c - several players at once (tools/world/team.h) and
 * the experiment driver's mechanics (tools/loc/coachrun.h) on short runs:
 * the players see each other where they are, the coach's view shows all of
 * them, each player's odometry is its own, the heading-holding walk of the
 * sim, and the same seed gives the same bytes.
 */
#include "test.h"
#include "loc/coachrun.h"
#include "world/render.h"
#include "world/sim.h"
#include "world/team.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A short walk on spl2016 with a 320 px camera and no head yaw. */
static void short_walk(sim_scenario_t *sc, uint64_t seed, double x, double y, double deg,
                       double tx, double ty)
{
    sim_scenario_defaults(sc, SIM_ROBOT_NAO);
    strcpy(sc->field_name, "spl2016");
    strcpy(sc->camera_name, "nao4-top-320");
    sc->field = fl_field_find(sc->field_name);
    sc->camera = fl_camera_model_find(sc->camera_name);
    sc->seed = seed;
    sc->duration_s = 4;
    sc->start_x_mm = x;
    sc->start_y_mm = y;
    sc->start_heading_deg = deg;
    sc->waypoint[0].x_mm = tx;
    sc->waypoint[0].y_mm = ty;
    sc->n_waypoints = 1;
    sc->route_once = 1;
    sc->yaw_amplitude_rad = 0;
}

static double deg_of(fl_angle_t a)
{
    return (double)a * (360.0 / 65536.0);
}

static int count_class(const render_frame_t *fr, int cls)
{
    int i, n = 0;
    for (i = 0; i < fr->width * fr->height; i++)
        n += fr->mask[i] == cls;
    return n;
}

/* Player A looks along +x at player B standing 1.5 m ahead: B is in A's
 * view at B's pose of that step, and A's other-robot list holds B and the
 * coach at their current poses. */
static void test_see_each_other(void)
{
    team_player_cfg_t cfg[2];
    team_t *t = malloc(sizeof *t);
    render_scene_t scene;
    render_frame_t fr;
    sim_other_t o[SIM_MAX_OTHERS];
    int k, n, with_b;
    short_walk(&cfg[0].sc, 1, -2000, 0, 0, -1500, 0);
    short_walk(&cfg[1].sc, 2, -500, 1000, -90, -500, -1000);
    cfg[0].jersey = RENDER_JERSEY_RED;
    cfg[1].jersey = RENDER_JERSEY_BLUE;
    CHECK(t != NULL);
    if (t == NULL)
        return;
    CHECK_EQ(team_init(t, cfg, 2, NULL, NULL, 0), 0);
    for (k = 0; k < 45; k++)
        CHECK_EQ(team_step(t), 1);
    /* B has walked toward -y; A's list has B where B is now, then the coach */
    n = team_others_of(t, 0, o);
    CHECK_EQ(n, 2);
    CHECK_EQ(t->p[0].sim.sc.n_others, 2);
    CHECK(fabs(t->p[0].sim.sc.other[0].x_mm - t->p[1].sim.x) < 1e-9);
    CHECK(fabs(t->p[0].sim.sc.other[0].y_mm - t->p[1].sim.y) < 1e-9);
    CHECK(t->p[1].sim.y < 900);
    CHECK_EQ(t->p[0].sim.sc.other[0].jersey, RENDER_JERSEY_BLUE);
    CHECK_EQ(t->p[0].sim.sc.other[1].x_mm, TEAM_COACH_X_MM);
    CHECK_EQ(t->p[0].sim.sc.other[1].y_mm, TEAM_COACH_Y_MM);
    /* A's own view of this step: B in it as robot pixels */
    team_player_scene(t, 0, &scene);
    CHECK_EQ(scene.n_robots, 2);
    CHECK_EQ(scene.robots[0].x_mm, t->p[1].st.x_mm);
    CHECK_EQ(scene.robots[0].y_mm, t->p[1].st.y_mm);
    CHECK_EQ(render_frame(&scene, &fr), 0);
    with_b = count_class(&fr, RENDER_CLASS_OBJECT);
    render_frame_free(&fr);
    /* B moved off: A's view of the same pose has (almost) no robot pixels */
    scene.robots[0].x_mm = -4000;
    scene.robots[0].y_mm = 2900;
    CHECK_EQ(render_frame(&scene, &fr), 0);
    CHECK(with_b > 500);
    CHECK(count_class(&fr, RENDER_CLASS_OBJECT) < with_b / 10);
    render_frame_free(&fr);
    free(t);
}

/* The coach's 640 x 480 view shows both players at their true feet. */
static void test_coach_view(void)
{
    team_player_cfg_t cfg[2];
    team_t *t = malloc(sizeof *t);
    render_scene_t scene;
    render_frame_t fr;
    int p, k;
    cr_scenario(&cfg[0].sc, 0, 7);
    cr_scenario(&cfg[1].sc, 1, 7);
    cfg[0].jersey = cfg[1].jersey = RENDER_JERSEY_RED;
    CHECK(t != NULL);
    if (t == NULL)
        return;
    CHECK_EQ(team_init(t, cfg, 2, NULL, NULL, 0), 0);
    /* to the end of the first leg (the starts are beside the coach's view) */
    for (k = 0; k < 2000 && !team_all_arrived(t); k++)
        CHECK_EQ(team_step(t), 1);
    CHECK(team_all_arrived(t));
    team_coach_scene(t, 5, &scene);
    CHECK_EQ(scene.camera->width_px, 640);
    CHECK_EQ(scene.camera->height_px, 480);
    CHECK_EQ(scene.n_robots, 2);
    CHECK_EQ(render_frame(&scene, &fr), 0);
    for (p = 0; p < 2; p++) {
        double u, v;
        int hit = 0, du, dv;
        CHECK_EQ(scene.robots[p].x_mm, t->p[p].st.x_mm);
        CHECK_EQ(scene.robots[p].jersey, RENDER_JERSEY_RED);
        /* robot pixels just above where its feet touch the carpet */
        CHECK(render_project_field(&scene, t->p[p].st.x_mm, t->p[p].st.y_mm, 0, &u, &v, NULL));
        CHECK(u >= 0 && u < 640 && v >= 0 && v < 480);
        for (dv = -12; dv <= 0; dv++)
            for (du = -4; du <= 4; du++) {
                int x = (int)u + du, y = (int)v + dv;
                if (x >= 0 && x < 640 && y >= 0 && y < 480)
                    hit += fr.mask[y * 640 + x] == RENDER_CLASS_OBJECT;
            }
        CHECK(hit > 5);
    }
    render_frame_free(&fr);
    free(t);
}

/* Each player walks with its own odometry noise: two players on parallel
 * routes with different seeds report different odometry for the same
 * walked motion, and a player's steps are those of the same walk alone
 * (here nobody stands between it and what it sees). */
static void test_odometry_independent(void)
{
    team_player_cfg_t cfg[2];
    team_t *t = malloc(sizeof *t);
    sim_t solo;
    sim_step_t st;
    int k, differ = 0, same = 1;
    short_walk(&cfg[0].sc, 11, -3000, -1500, 0, 0, -1500);
    short_walk(&cfg[1].sc, 12, -3000, 1500, 0, 0, 1500);
    cfg[0].sc.slip_rate_hz = cfg[1].sc.slip_rate_hz = 0;
    cfg[0].jersey = cfg[1].jersey = RENDER_JERSEY_RED;
    CHECK(t != NULL);
    if (t == NULL)
        return;
    CHECK_EQ(team_init(t, cfg, 2, NULL, NULL, 0), 0);
    CHECK_EQ(sim_init(&solo, &cfg[0].sc), 0);
    for (k = 0; k < 100; k++) {
        CHECK_EQ(team_step(t), 1);
        sim_step(&solo, &st);
        differ += t->p[0].st.odo_dx_mm != t->p[1].st.odo_dx_mm ||
                  t->p[0].st.odo_dy_mm != t->p[1].st.odo_dy_mm;
        same &= t->p[0].st.odo_dx_mm == st.odo_dx_mm && t->p[0].st.odo_dy_mm == st.odo_dy_mm &&
                t->p[0].st.x_mm == st.x_mm && t->p[0].st.obs.n == st.obs.n;
    }
    /* the two walks are mirror images in y with equal true motion ... */
    CHECK_EQ(t->p[0].st.true_dx_mm, t->p[1].st.true_dx_mm);
    /* ... and different odometry */
    CHECK(differ > 50);
    CHECK(same);
    free(t);
}

/* The heading-holding walk: facing out of the field (-90 deg) while
 * side-stepping 1.5 m along x, then standing at the end; the text form
 * round-trips and the built-in walks do not name the new keys. */
static void test_hold_heading(void)
{
    sim_scenario_t sc, back;
    sim_t s;
    sim_step_t st;
    double worst = 0;
    char *buf = NULL;
    size_t len = 0;
    FILE *f;
    int k, i;
    short_walk(&sc, 3, -2000, -2500, -90, -500, -2500);
    sc.hold_heading = 1;
    sc.face_deg = -90;
    sc.duration_s = 25;
    CHECK_EQ(sim_init(&s, &sc), 0);
    for (k = 0; sim_step(&s, &st); k++) {
        double d = fabs(deg_of(st.heading) + 90);
        if (d > worst)
            worst = d;
    }
    CHECK(sim_arrived(&s));
    CHECK(abs(st.x_mm - -500) < 200 && abs(st.y_mm - -2500) < 200);
    CHECK(worst < 5);
    f = open_memstream(&buf, &len);
    CHECK(f != NULL);
    if (f == NULL)
        return;
    CHECK_EQ(sim_scenario_write(f, &sc), 0);
    fclose(f);
    CHECK(strstr(buf, "face_deg -90\n") != NULL);
    CHECK(strstr(buf, "route_once 1\n") != NULL);
    CHECK_EQ(sim_scenario_parse(&back, buf, NULL, 0), 0);
    CHECK_EQ(back.hold_heading, 1);
    CHECK_EQ(back.face_deg, -90);
    CHECK_EQ(back.route_once, 1);
    free(buf);
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        const char *txt = sim_builtin_text(sim_builtin_names[i]);
        CHECK(strstr(txt, "face_deg") == NULL && strstr(txt, "route_once") == NULL);
    }
}

/* Same seed, same bytes: two team runs hash alike (truth, odometry,
 * observations of every player, and the coach's frame), and so does one
 * run of the experiment driver (feature mode, DEBUG truth feet: the
 * mechanics only). */
static uint32_t team_hash(uint64_t seed)
{
    team_player_cfg_t cfg[2];
    team_t *t = malloc(sizeof *t);
    render_scene_t scene;
    render_frame_t fr;
    uint32_t h = t_hash_init();
    int p, k, i;
    if (t == NULL)
        return 0;
    cr_scenario(&cfg[0].sc, 0, seed);
    cr_scenario(&cfg[1].sc, 1, seed);
    cfg[0].jersey = cfg[1].jersey = RENDER_JERSEY_RED;
    if (team_init(t, cfg, 2, NULL, NULL, 0) != 0) {
        free(t);
        return 0;
    }
    for (k = 0; k < 60 && team_step(t) == 1; k++)
        for (p = 0; p < 2; p++) {
            const sim_step_t *st = &t->p[p].st;
            h = t_hash_i32(h, st->x_mm);
            h = t_hash_i32(h, st->y_mm);
            h = t_hash_i32(h, st->heading);
            h = t_hash_i32(h, st->odo_dx_mm);
            h = t_hash_i32(h, st->odo_dy_mm);
            h = t_hash_i32(h, st->odo_dtheta);
            for (i = 0; i < st->obs.n; i++)
                h = t_hash_i32(h, st->obs.obs[i].range_mm);
        }
    team_coach_scene(t, 9, &scene);
    if (render_frame(&scene, &fr) == 0) {
        h = t_hash_bytes(h, fr.data, fr.size);
        render_frame_free(&fr);
    }
    free(t);
    return h;
}

static void test_deterministic(void)
{
    cr_opts_t o;
    cr_result_t *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    char err[128];
    CHECK_EQ(team_hash(3), team_hash(3));
    CHECK(team_hash(3) != team_hash(4));
    CHECK(a != NULL && b != NULL);
    if (a == NULL || b == NULL) {
        free(a);
        free(b);
        return;
    }
    memset(&o, 0, sizeof o);
    o.loc = fl_localizer_find("mcl");
    o.seed = 5;
    o.runs = 1;
    o.feet = CR_FEET_TRUTH_DEBUG;
    o.reseed_always = 1;
    CHECK_EQ(cr_run(&o, a, err, (int)sizeof err), 0);
    CHECK_EQ(cr_run(&o, b, err, (int)sizeof err), 0);
    CHECK(memcmp(a->own_err, b->own_err, sizeof a->own_err) == 0);
    CHECK(memcmp(a->exp2_err, b->exp2_err, sizeof a->exp2_err) == 0);
    CHECK(memcmp(a->exp2_nocoach_err, b->exp2_nocoach_err, sizeof a->exp2_nocoach_err) == 0);
    /* the robots stood near / far from the coach at the blue circle */
    CHECK(a->coach_dist_mm[0][0] < 5000);
    CHECK(a->coach_dist_mm[0][1] > 5000);
    CHECK_EQ(a->leg_timeouts, 0);
    CHECK_EQ(a->reseeds, 2);
    CHECK_EQ(a->wrong_assignments, 0);
    {
        /* the summary: exactly these lines, in this order, at the end */
        static const char *const names[9] = {
            "coach_foot_err_near_mm ", "coach_foot_err_far_mm ", "own_foot_err_near_mm ",
            "own_foot_err_far_mm ", "exp2_err_a_mm ", "exp2_err_b_mm ",
            "exp2_err_a_nocoach_mm ", "exp2_err_b_nocoach_mm ", "wrong_assignments "};
        char *buf = NULL, *q;
        size_t len = 0;
        int i;
        FILE *f = open_memstream(&buf, &len);
        CHECK(f != NULL);
        if (f != NULL) {
            cr_print_summary(f, a);
            fclose(f);
            q = buf;
            for (i = 0; i < 9 && q != NULL; i++) {
                char key[64];
                snprintf(key, sizeof key, "\n%s", names[i]);
                q = strstr(q, key);
                CHECK(q != NULL);
                if (q != NULL)
                    q++;
            }
            CHECK(q != NULL && strchr(q, '\n') != NULL && strchr(q, '\n')[1] == '\0');
            CHECK(strstr(buf, "wrong_assignments 0\n") != NULL);
            free(buf);
        }
    }
    free(a);
    free(b);
}

void suite_team(void)
{
    t_run("team.see_each_other", test_see_each_other);
    t_run("team.coach_view", test_coach_view);
    t_run("team.odometry_independent", test_odometry_independent);
    t_run("team.hold_heading", test_hold_heading);
    t_run("team.deterministic", test_deterministic);
}
