/*
 * tools/loc/coachrun.c - seed 003's experiments (tools/loc/coachrun.h).
 */
#include "loc/coachrun.h"
#include "fieldloc/coach.h"
#include "fieldloc/odocal.h"
#include "fieldloc/report.h"
#include "loc/locrun.h"
#include "world/coach_scene.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define CR_LEG_TIMEOUT_S 60.0
/* Rows of the legs: player A near the -y touchline, B near the +y one. */
static const double cr_start[2][3] = {{-3000, -2500, -90}, {3000, 2500, 90}};
static const double cr_blue[2][2] = {{-500, -2500}, {500, 2500}};
static const double cr_grey[2][2] = {{2000, -2500}, {-2000, 2500}};

void cr_scenario(sim_scenario_t *sc, int p, uint64_t seed)
{
    sim_scenario_defaults(sc, SIM_ROBOT_NAO);
    snprintf(sc->name, sizeof sc->name, "coach_%c", p == 0 ? 'a' : 'b');
    strcpy(sc->field_name, "spl2016");
    /* the NAO H25 V5 of seed 003's time: the V4 upper camera, at 320 x 240
     * (3.5 times cheaper to render than 640 x 480: 20 vs 72 ms a frame) */
    strcpy(sc->camera_name, "nao4-top-320");
    sc->field = fl_field_find(sc->field_name);
    sc->camera = fl_camera_model_find(sc->camera_name);
    /* one odometry noise stream per player and run */
    sc->seed = seed * 2u + (uint64_t)p;
    sc->duration_s = 3 * CR_LEG_TIMEOUT_S;
    sc->start_x_mm = cr_start[p][0];
    sc->start_y_mm = cr_start[p][1];
    sc->start_heading_deg = cr_start[p][2];
    sc->hold_heading = 1;
    sc->face_deg = cr_start[p][2];
    sc->route_once = 1;
    sc->waypoint[0].x_mm = cr_blue[p][0];
    sc->waypoint[0].y_mm = cr_blue[p][1];
    sc->n_waypoints = 1;
    /* looking out of the field: a narrow head scan (+-23 deg) */
    sc->yaw_amplitude_rad = 0.4;
    sc->penalty_x_mm = 0;
}

/* A player's perception and localizer (the layer above team.h). */
typedef struct {
    lr_t lr;
    lr_odo_t odo;
    fl_loc_estimate_t est;
} cr_player_t;

/* Frames mode: the vision observations of each player's vision steps.
 * Vision does not depend on the localizer and both continuations of a run
 * walk the same world, so the second pass reads what the first computed
 * instead of rendering again. */
typedef struct {
    fl_obs_list_t *obs;
    long n, cap, next;
} cr_obs_rec_t;

typedef struct {
    team_t team;
    cr_player_t pl[2];
    const cr_opts_t *o;
    colors_opt_t colors;
    cr_obs_rec_t *rec;          /* [2]: recording (pass 0) or replaying */
    int replay;
    /* odometry calibration (odocal.h): CR_CAL_COLLECT takes a coach frame
     * every second and feeds each player's odometry and its picked report
     * to cal[p]; CR_CAL_APPLY corrects the odometry with cal[p]'s gains */
    int cal_mode;
    fl_odocal_t *cal;           /* [2] */
    fl_report_tracker_t cal_tr[2];
    uint64_t seed;
    long cal_frames, cal_fixes;
    fl_coach_t *coach;          /* the first leg's coach, set up once */
    double render_s;
    long rendered;
} cr_world_t;

static void cr_world_free(cr_world_t *w)
{
    lr_free(&w->pl[0].lr);
    lr_free(&w->pl[1].lr);
}

static int cr_world_init(cr_world_t *w, const cr_opts_t *o, const fl_localizer_t *loc,
                         uint64_t seed, char *err, int err_len)
{
    team_player_cfg_t cfg[2];
    int p;
    memset(w, 0, sizeof *w);
    w->o = o;
    colors_opt_resolve(&w->colors, fl_field_find("spl2016"), NULL);
    for (p = 0; p < 2; p++) {
        cr_scenario(&cfg[p].sc, p, seed);
        cfg[p].sc.white_points = loc->reads_points;
        cfg[p].jersey = RENDER_JERSEY_RED;
    }
    if (team_init(&w->team, cfg, 2, NULL, err, err_len) != 0)
        return -1;
    for (p = 0; p < 2; p++) {
        cr_player_t *pl = &w->pl[p];
        void *params = lr_params_new(loc);
        int rc;
        if (params == NULL)
            return -1;
        if (o->frames)
            lr_params_frames(loc, params);
        /* a stochastic localizer draws from its own stream per player and run */
        if (fl_localizer_param_find(loc, "seed") != NULL)
            fl_localizer_param_set(loc, params, "seed",
                                   (int32_t)((seed * 2u + (uint64_t)p) & 0x7fffffff));
        rc = lr_init(&pl->lr, loc, w->team.field, cfg[p].sc.camera, params, err, err_len);
        free(params);
        if (rc != 0) {
            if (p == 1)
                lr_free(&w->pl[0].lr);
            return -1;
        }
        pl->lr.colors = &w->colors;
        /* placed on the red circle, as seed 003's players */
        loc->reset_pose(pl->lr.state, (int32_t)cfg[p].sc.start_x_mm,
                        (int32_t)cfg[p].sc.start_y_mm,
                        fl_angle_from_mdeg((int32_t)(cfg[p].sc.start_heading_deg * 1000)), 100,
                        fl_angle_from_mdeg(10000));
        loc->estimate(pl->lr.state, &pl->est);
    }
    return 0;
}

/* Rendering one player's view (in a thread of its own for the second
 * player: each frame comes from its own scene, so the bytes do not depend
 * on it). */
typedef struct {
    render_scene_t scene;
    render_frame_t fr;
    int rc;
} cr_job_t;

static void *cr_render_job(void *arg)
{
    cr_job_t *j = arg;
    j->rc = render_frame(&j->scene, &j->fr);
    return NULL;
}

/* The views of the players that have a vision step now, rendered two at a
 * time.  0, or -1 on a render failure (nothing to free then). */
static int cr_render_views(cr_world_t *w, const int *need, cr_job_t *job)
{
    pthread_t th;
    int p, threaded = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (p = 0; p < 2; p++) {
        job[p].rc = 0;
        if (need[p])
            team_player_scene(&w->team, p, &job[p].scene);
    }
    if (need[1] && lr_threads_default() > 1)
        threaded = pthread_create(&th, NULL, cr_render_job, &job[1]) == 0;
    if (need[1] && !threaded)
        cr_render_job(&job[1]);
    if (need[0])
        cr_render_job(&job[0]);
    if (threaded)
        pthread_join(th, NULL);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    w->render_s += (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    for (p = 0; p < 2; p++)
        if (need[p] && job[p].rc != 0) {
            if (need[1 - p] && job[1 - p].rc == 0)
                render_frame_free(&job[1 - p].fr);
            return -1;
        }
    w->rendered += need[0] + need[1];
    return 0;
}

/* One team step: simulators, then every player's localizer. */
enum { CR_CAL_OFF = 0, CR_CAL_COLLECT = 1, CR_CAL_APPLY = 2 };
static void cr_cal_sight(cr_world_t *w);

static int cr_world_step(cr_world_t *w)
{
    int p, need[2] = {0, 0};
    cr_job_t job[2];
    if (team_step(&w->team) != 1)
        return 0;
    if (w->o->frames && !w->replay) {
        for (p = 0; p < 2; p++)
            need[p] = w->team.p[p].st.index % (uint32_t)w->o->every == 0;
        if ((need[0] || need[1]) && cr_render_views(w, need, job) != 0)
            return -1;
    }
    for (p = 0; p < 2; p++) {
        cr_player_t *pl = &w->pl[p];
        const sim_step_t *st = &w->team.p[p].st;
        int32_t odx = st->odo_dx_mm, ody = st->odo_dy_mm;
        double gx = 1, gy = 1;
        if (w->cal_mode == CR_CAL_COLLECT)
            fl_odocal_odometry(&w->cal[p], odx, ody, st->odo_dtheta);
        else if (w->cal_mode == CR_CAL_APPLY) {
            fl_odocal_apply(&w->cal[p], &odx, &ody);
            gx = w->cal[p].gain_q16[0] / 65536.0;
            gy = w->cal[p].gain_q16[1] / 65536.0;
        }
        if (!w->o->frames) {
            fl_loc_predict(pl->lr.loc, pl->lr.state, odx, ody, st->odo_dtheta);
            fl_loc_update(pl->lr.loc, pl->lr.state, &st->obs, NULL);
        } else {
            lr_odo_add(&pl->odo, gx * st->odo_dx, gy * st->odo_dy, st->odo_dtheta_rad);
            if (st->index % (uint32_t)w->o->every == 0) {
                cr_obs_rec_t *rec = &w->rec[p];
                lr_predict(&pl->lr, pl->odo.x, pl->odo.y, pl->odo.a);
                memset(&pl->odo, 0, sizeof pl->odo);
                if (w->replay) {
                    if (rec->next >= rec->n)
                        return -1;
                    lr_frame_obs(&pl->lr, &st->head, &rec->obs[rec->next++]);
                } else {
                    lr_frame(&pl->lr, &job[p].fr.view, &st->head);
                    render_frame_free(&job[p].fr);
                    need[p] = 0;
                    if (rec->n == rec->cap) {
                        long cap = rec->cap ? 2 * rec->cap : 1024;
                        fl_obs_list_t *q = realloc(rec->obs, (size_t)cap * sizeof *q);
                        if (q == NULL) {
                            if (p == 0 && need[1])
                                render_frame_free(&job[1].fr);
                            return -1;
                        }
                        rec->obs = q;
                        rec->cap = cap;
                    }
                    rec->obs[rec->n++] = pl->lr.obs;
                }
            }
        }
        lr_estimate(&pl->lr, &pl->est);
        if (w->o->trace != NULL)
            fprintf(w->o->trace, "# step %c %u truth %d %d %.0f est %d %d %.0f obs %d spread %u\n",
                    'A' + p, st->index, st->x_mm, st->y_mm, lr_deg(st->heading), pl->est.x_mm,
                    pl->est.y_mm, lr_deg(pl->est.heading), st->obs.n,
                    fl_loc_spread_mm(pl->lr.loc, pl->lr.state));
    }
    if (w->cal_mode == CR_CAL_COLLECT &&
        w->team.p[0].st.index % (uint32_t)lround(w->team.p[0].sim.sc.frame_hz) == 0)
        cr_cal_sight(w);
    return 1;
}

/* Walk until both players stand at the end of their route (or time out). */
static int cr_walk_leg(cr_world_t *w, int *timeout)
{
    long limit = (long)(CR_LEG_TIMEOUT_S * w->team.p[0].sim.sc.frame_hz), k;
    for (k = 0; k < limit && !team_all_arrived(&w->team); k++) {
        int r = cr_world_step(w);
        if (r != 1)
            return r < 0 ? -1 : 0;
    }
    /* a few more steps standing: the walk's last motion settles */
    for (k = 0; k < 5; k++)
        if (cr_world_step(w) != 1)
            return -1;
    *timeout = !team_all_arrived(&w->team);
    return 0;
}

typedef struct {
    int32_t x_mm, y_mm, sd_mm;
    int team;
    int confidence;
} cr_foot_t;

/* The coach's own setup for one run: its homography from the pixel
 * positions of the homography points in its view (coach_scene_points: the
 * true pixels plus CR_POINT_NOISE_PX of uniform noise, as points picked by
 * hand) and its empty-field background (the same world, no players, a
 * frame of its own noise). */
#define CR_POINT_NOISE_PX 1.0

static int cr_coach_setup(fl_coach_t *c, const team_t *team, uint64_t seed, int *n_points)
{
    render_scene_t scene;
    render_frame_t fr;
    fl_homog_pair_t pairs[COACH_POINTS_MAX];
    fl_homog_t h;
    fl_coach_params_t prm;
    int n;
    team_coach_scene(team, (uint32_t)(seed * 2654435761u) ^ 0xb6u, &scene);
    scene.n_robots = 0;
    n = coach_scene_points(&scene, CR_POINT_NOISE_PX, (uint32_t)seed, pairs, NULL,
                           COACH_POINTS_MAX);
    *n_points = n;
    fl_coach_params_default(&prm);
    if (n < 4 || fl_homog_fit(&h, pairs, (size_t)n) != FL_HOMOG_OK ||
        fl_coach_init(c, &prm) != FL_OK || fl_coach_set_homography(c, &h, team->field) != FL_OK)
        return -1;
    if (render_frame(&scene, &fr) != 0)
        return -1;
    n = fl_coach_set_background(c, &fr.view) == FL_OK ? 0 : -1;
    render_frame_free(&fr);
    return n;
}

/* The coach's feet on its frame of the current step. */
/* The coach's feet as reports (obs.h), fresh (age 0), at most
 * FL_REPORT_MAX of them; returns how many. */
static size_t cr_reports(const cr_foot_t *feet, int nf, fl_obs_report_t *rep)
{
    size_t n = 0;
    int i;
    for (i = 0; i < nf && n < FL_REPORT_MAX; i++, n++) {
        memset(&rep[n], 0, sizeof rep[n]);
        rep[n].x_mm = feet[i].x_mm;
        rep[n].y_mm = feet[i].y_mm;
        rep[n].sd_mm = feet[i].sd_mm;
        rep[n].confidence = (uint8_t)feet[i].confidence;
        rep[n].team = (uint8_t)feet[i].team;
    }
    return n;
}

static int cr_coach_feet(const cr_world_t *w, uint64_t seed, uint32_t salt, cr_foot_t *out,
                         int max)
{
    int n = 0, p;
    render_scene_t scene;
    render_frame_t fr;
    fl_coach_t *c;
    fl_coach_result_t *res;
    int n_points = 0;
    if (w->o->feet == CR_FEET_TRUTH_DEBUG) {
        for (p = 0; p < w->team.n && n < max; p++, n++) {
            out[n].x_mm = w->team.p[p].st.x_mm;
            out[n].y_mm = w->team.p[p].st.y_mm;
            out[n].sd_mm = FL_OBS_REPORT_SD_MM;
            out[n].team = FL_COLOR_RED;
            out[n].confidence = 255;
        }
        return n;
    }
    c = w->coach != NULL ? w->coach : malloc(sizeof *c);
    res = malloc(sizeof *res);
    if (c == NULL || res == NULL ||
        (w->coach == NULL && cr_coach_setup(c, &w->team, seed, &n_points) != 0)) {
        if (c != w->coach)
            free(c);
        free(res);
        return -1;
    }
    team_coach_scene(&w->team, ((uint32_t)(seed * 2654435761u) ^ 0x5eed003u) + salt * 7919u,
                     &scene);
    if (render_frame(&scene, &fr) != 0) {
        if (c != w->coach)
            free(c);
        free(res);
        return -1;
    }
    if (fl_coach_frame(c, &fr.view, res) == FL_OK) {
        fl_obs_report_t rep[FL_COACH_MAX_FEET];
        size_t i, k = fl_coach_reports(res, 0, rep, FL_COACH_MAX_FEET);
        for (i = 0; i < k && n < max; i++, n++) {
            out[n].x_mm = rep[i].x_mm;
            out[n].y_mm = rep[i].y_mm;
            out[n].sd_mm = rep[i].sd_mm;
            out[n].team = rep[i].team;
            out[n].confidence = rep[i].confidence;
        }
    }
    render_frame_free(&fr);
    if (c != w->coach)
        free(c);
    free(res);
    return n;
}

/* One sighting of the first leg: the coach's frame of this step; each
 * player picks its report as it would without a number (report.h
 * fl_report_pick: its team's report nearest its estimate, with the jump
 * and gate tests over its own tracker) and gives it to its calibration. */
static void cr_cal_sight(cr_world_t *w)
{
    cr_foot_t feet[8];
    fl_obs_report_t rep[FL_REPORT_MAX];
    size_t n = 0;
    int nf, p, n_points;
    if (w->coach == NULL && w->o->feet != CR_FEET_TRUTH_DEBUG) {
        fl_coach_t *c = malloc(sizeof *c);
        if (c == NULL || cr_coach_setup(c, &w->team, w->seed, &n_points) != 0) {
            free(c);
            return;
        }
        w->coach = c;
    }
    nf = cr_coach_feet(w, w->seed, (uint32_t)++w->cal_frames, feet, 8);
    n = cr_reports(feet, nf, rep);
    for (p = 0; p < 2 && n > 0; p++) {
        fl_report_self_t me;
        size_t idx = 0;
        memset(&me, 0, sizeof me);
        me.team = FL_COLOR_RED;
        me.now_ms = (uint32_t)w->team.p[p].st.t_ms;
        me.field = w->team.field;
        me.est = &w->pl[p].est;
        if (fl_report_pick(rep, n, &me, w->pl[p].est.x_mm, w->pl[p].est.y_mm,
                           fl_loc_spread_mm(w->pl[p].lr.loc, w->pl[p].lr.state), &w->cal_tr[p],
                           &idx) == FL_REPORT_NOT_NEEDED &&
            fl_odocal_fix(&w->cal[p], rep[idx].x_mm, rep[idx].y_mm) == FL_OK)
            w->cal_fixes++;
    }
}

static double cr_dist(double ax, double ay, double bx, double by)
{
    return sqrt((ax - bx) * (ax - bx) + (ay - by) * (ay - by));
}

static double cr_err(const cr_world_t *w, int p)
{
    const sim_step_t *st = &w->team.p[p].st;
    return cr_dist(w->pl[p].est.x_mm, w->pl[p].est.y_mm, st->x_mm, st->y_mm);
}

/* The foot that truly belongs to player p: nearest its true foot within
 * 500 mm; -1 when the coach found none there. */
static int cr_true_foot(const cr_world_t *w, int p, const cr_foot_t *feet, int n)
{
    int i, best = -1;
    double bd = 500;
    const sim_step_t *st = &w->team.p[p].st;
    for (i = 0; i < n; i++) {
        double d = cr_dist(feet[i].x_mm, feet[i].y_mm, st->x_mm, st->y_mm);
        if (d <= bd) {
            best = i;
            bd = d;
        }
    }
    return best;
}

/* The reports of the coach's frame, numbered by the coach (report.h
 * fl_report_assign against the players' broadcast estimates and spreads)
 * unless o->assign_player_side; then each player takes its report
 * (fl_report_pick: its number, or the nearest of its team to its own
 * estimate) and re-seeds (fl_report_apply; threshold 1 mm with
 * reseed_always: seed 003's one correction, else the spread rule).  A
 * report taken by a player whose true foot is another is a wrong
 * assignment. */
static void cr_correct(cr_world_t *w, const cr_opts_t *o, const fl_localizer_t *loc,
                       const cr_foot_t *feet, int nf, cr_result_t *res, int *assigned,
                       const char **what)
{
    fl_obs_report_t rep[FL_REPORT_MAX];
    fl_report_claim_t claim[2];
    fl_report_stats_t cst;
    size_t n = 0;
    int p;
    memset(&cst, 0, sizeof cst);
    n = cr_reports(feet, nf, rep);
    for (p = 0; p < 2; p++) {
        claim[p].x_mm = w->pl[p].est.x_mm;
        claim[p].y_mm = w->pl[p].est.y_mm;
        claim[p].spread_mm = fl_loc_spread_mm(loc, w->pl[p].lr.state);
        claim[p].team = FL_COLOR_RED;
        claim[p].player = (uint8_t)(p + 1);
    }
    if (!o->assign_player_side)
        fl_report_assign(rep, n, claim, 2, w->team.field, 0, &cst);
    for (p = 0; p < 2; p++) {
        fl_report_tracker_t tr, probe;
        fl_report_self_t me;
        fl_report_result_t r;
        size_t idx = 0;
        int truth = cr_true_foot(w, p, feet, nf);
        memset(&me, 0, sizeof me);
        me.team = FL_COLOR_RED;
        me.player = o->assign_player_side ? 0 : (uint8_t)(p + 1);
        me.now_ms = (uint32_t)w->team.p[p].st.t_ms;
        me.field = w->team.field;
        me.est = &w->pl[p].est;
        fl_report_tracker_init(&tr);
        probe = tr;
        /* which report it takes (the pick alone touches no filter) */
        r = fl_report_pick(rep, n, &me, w->pl[p].est.x_mm, w->pl[p].est.y_mm,
                           claim[p].spread_mm, &probe, &idx);
        assigned[p] = r == FL_REPORT_NOT_NEEDED ? (int)idx : -1;
        if (assigned[p] >= 0) {
            res->assigned++;
            res->wrong_assignments += assigned[p] != truth;
        } else
            res->unassigned++;
        r = fl_report_apply(loc, w->pl[p].lr.state, rep, n, &me, o->reseed_always ? 1u : 0u,
                            &tr);
        what[p] = fl_report_result_str(r);
        if (r == FL_REPORT_RESEEDED)
            res->reseeds++;
        else if (r == FL_REPORT_NOT_NEEDED)
            res->not_needed++;
        else
            res->refused++;
    }
}

static int cr_second_leg(cr_world_t *w, int *timeout)
{
    int p;
    for (p = 0; p < 2; p++) {
        sim_waypoint_t wp;
        wp.x_mm = cr_grey[p][0];
        wp.y_mm = cr_grey[p][1];
        sim_set_route(&w->team.p[p].sim, &wp, 1);
    }
    return cr_walk_leg(w, timeout);
}

static int cr_one_run(const cr_opts_t *o, const fl_localizer_t *loc, int r, cr_result_t *res,
                      char *err, int err_len)
{
    cr_world_t *w = malloc(sizeof *w);
    uint64_t seed = o->seed + (uint64_t)r;
    cr_foot_t feet[8];
    int nf = 0, p, pass, to = 0, assigned[2] = {-1, -1}, rc = -1;
    const char *what[2] = {"-", "-"};
    cr_obs_rec_t rec[2];
    fl_odocal_t cal[2];
    cr_result_t *scratch = NULL;
    memset(rec, 0, sizeof rec);
    fl_odocal_init(&cal[0]);
    fl_odocal_init(&cal[1]);
    if (w == NULL)
        return -1;
    /* pass 0: without the coach; 1: seed 003's one correction; 2 (odocal):
     * the correction with the odometry calibrated over the first leg */
    for (pass = 0; pass < (o->odocal ? 3 : 2); pass++) {
        int with = pass >= 1;
        if (cr_world_init(w, o, loc, seed, err, err_len) != 0)
            goto out;
        w->rec = rec;
        w->replay = pass >= 1;
        w->seed = seed;
        rec[0].next = rec[1].next = 0;
        if (pass == 0 && o->odocal) {
            w->cal = cal;
            w->cal_mode = CR_CAL_COLLECT;
            fl_report_tracker_init(&w->cal_tr[0]);
            fl_report_tracker_init(&w->cal_tr[1]);
        }
        if (cr_walk_leg(w, &to) != 0) {
            cr_world_free(w);
            snprintf(err, (size_t)err_len, "run %d: rendering failed", r);
            goto out;
        }
        if (pass < 2)
            res->leg_timeouts += to;
        if (pass == 0 && o->odocal) {
            w->cal_mode = CR_CAL_OFF;
            free(w->coach);
            w->coach = NULL;
            res->cal_frames += w->cal_frames;
            res->cal_fixes += w->cal_fixes;
            for (p = 0; p < 2; p++) {
                fl_odocal_solve(&cal[p]);
                res->cal_gain[r][p][0] = cal[p].gain_q16[0] / 65536.0;
                res->cal_gain[r][p][1] = cal[p].gain_q16[1] / 65536.0;
            }
        }
        if (!with) {
            /* Experiment 1 at the blue circles */
            nf = cr_coach_feet(w, seed, 0, feet, 8);
            if (nf < 0) {
                cr_world_free(w);
                snprintf(err, (size_t)err_len, "the coach's image path is not in this build");
                goto out;
            }
            for (p = 0; p < 2; p++) {
                const sim_step_t *st = &w->team.p[p].st;
                int f = cr_true_foot(w, p, feet, nf);
                res->own_err[r][p] = cr_err(w, p);
                res->own_head_err[r][p] =
                    fabs(lr_deg((fl_angle_t)(w->pl[p].est.heading - st->heading)));
                res->coach_dist_mm[r][p] = cr_dist(st->x_mm, st->y_mm, w->team.coach.x_mm,
                                                   w->team.coach.y_mm);
                res->coach_err[r][p] =
                    f < 0 ? NAN : cr_dist(feet[f].x_mm, feet[f].y_mm, st->x_mm, st->y_mm);
                res->coach_missed += f < 0;
            }
        } else if (pass == 1) {
            /* one correction at the blue circles */
            cr_correct(w, o, loc, feet, nf, res, assigned, what);
        } else {
            /* the same correction (its counts already taken), then the
             * calibrated odometry */
            const char *what2[2];
            int assigned2[2];
            if (scratch == NULL && (scratch = calloc(1, sizeof *scratch)) == NULL) {
                cr_world_free(w);
                goto out;
            }
            cr_correct(w, o, loc, feet, nf, scratch, assigned2, what2);
            w->cal = cal;
            w->cal_mode = CR_CAL_APPLY;
        }
        if (cr_second_leg(w, &to) != 0) {
            cr_world_free(w);
            snprintf(err, (size_t)err_len, "run %d: rendering failed", r);
            goto out;
        }
        if (pass < 2)
            res->leg_timeouts += to;
        for (p = 0; p < 2; p++) {
            if (pass == 2)
                res->exp2_cal_err[r][p] = res->exp2_err[r][p] = cr_err(w, p);
            else if (with)
                res->exp2_plain_err[r][p] = res->exp2_err[r][p] = cr_err(w, p);
            else
                res->exp2_nocoach_err[r][p] = cr_err(w, p);
        }
        res->render_s += w->render_s;
        res->rendered += w->rendered;
        cr_world_free(w);
    }
    rc = 0;
    if (o->log != NULL)
        fprintf(o->log,
                "# run %d seed %llu: A at %.0f mm from the coach: coach %.0f own %.0f "
                "exp2 %.0f nocoach %.0f; B at %.0f mm: coach %.0f own %.0f exp2 %.0f "
                "nocoach %.0f; report taken A %d (%s) B %d (%s)\n",
                r, (unsigned long long)seed, res->coach_dist_mm[r][0], res->coach_err[r][0],
                res->own_err[r][0], res->exp2_err[r][0], res->exp2_nocoach_err[r][0],
                res->coach_dist_mm[r][1], res->coach_err[r][1], res->own_err[r][1],
                res->exp2_err[r][1], res->exp2_nocoach_err[r][1], assigned[0], what[0],
                assigned[1], what[1]);
out:
    free(scratch);
    free(rec[0].obs);
    free(rec[1].obs);
    free(w);
    return rc;
}

int cr_run(const cr_opts_t *o, cr_result_t *res, char *err, int err_len)
{
    const fl_localizer_t *loc = o->loc != NULL ? o->loc : fl_localizer_find("upf");
    struct timespec t0, t1;
    int r;
    memset(res, 0, sizeof *res);
    res->odocal = o->odocal;
    if (o->runs < 1 || o->runs > CR_MAX_RUNS || (o->frames && o->every < 1)) {
        snprintf(err, (size_t)err_len, "runs 1..%d, every >= 1", CR_MAX_RUNS);
        return -1;
    }
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (r = 0; r < o->runs; r++) {
        if (cr_one_run(o, loc, r, res, err, err_len) != 0)
            return -1;
        res->runs = r + 1;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    res->wall_s = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    return 0;
}

static int cr_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Mean and median of column p of a per-run table, NaNs skipped. */
static void cr_stats(const double (*v)[2], int n, int p, double *mean, double *median)
{
    double *s = malloc((size_t)(n > 0 ? n : 1) * sizeof *s), sum = 0;
    int i, m = 0;
    *mean = *median = NAN;
    if (s == NULL)
        return;
    for (i = 0; i < n; i++)
        if (!isnan(v[i][p])) {
            s[m++] = v[i][p];
            sum += v[i][p];
        }
    if (m > 0) {
        qsort(s, (size_t)m, sizeof *s, cr_cmp);
        *mean = sum / m;
        *median = m % 2 ? s[m / 2] : 0.5 * (s[m / 2 - 1] + s[m / 2]);
    }
    free(s);
}

void cr_print_summary(FILE *f, const cr_result_t *res)
{
    static const char *const name[4][2] = {
        {"coach_foot_err_near_mm", "coach_foot_err_far_mm"},
        {"own_foot_err_near_mm", "own_foot_err_far_mm"},
        {"exp2_err_a_mm", "exp2_err_b_mm"},
        {"exp2_err_a_nocoach_mm", "exp2_err_b_nocoach_mm"}};
    const double(*tab[4])[2] = {res->coach_err, res->own_err, res->exp2_err,
                                res->exp2_nocoach_err};
    double mean[4][2], median[4][2], dmean[2], dmed[2], hmean[2], hmed[2];
    int i, p;
    for (i = 0; i < 4; i++)
        for (p = 0; p < 2; p++)
            cr_stats(tab[i], res->runs, p, &mean[i][p], &median[i][p]);
    cr_stats(res->coach_dist_mm, res->runs, 0, &dmean[0], &dmed[0]);
    cr_stats(res->coach_dist_mm, res->runs, 1, &dmean[1], &dmed[1]);
    cr_stats(res->own_head_err, res->runs, 0, &hmean[0], &hmed[0]);
    cr_stats(res->own_head_err, res->runs, 1, &hmean[1], &hmed[1]);
    fprintf(f, "# coach: %d runs; robot A (near) %.0f mm, robot B (far) %.0f mm from the "
               "coach at the blue circle (mean)\n",
            res->runs, dmean[0], dmean[1]);
    fprintf(f, "# coach: feet missed %d (no reported foot within 500 mm of a player), reports "
               "taken %d, none taken %d, re-seeds %d, not needed %d, refused %d, legs timed "
               "out %d, wall %.1f s (rendering %ld player views: %.1f s)\n",
            res->coach_missed, res->assigned, res->unassigned, res->reseeds, res->not_needed,
            res->refused, res->leg_timeouts, res->wall_s, res->rendered, res->render_s);
    fprintf(f, "# the players' own heading error at the blue circle (kept by the re-seed): "
               "A %.1f deg, B %.1f deg (mean; medians %.1f, %.1f)\n",
            hmean[0], hmean[1], hmed[0], hmed[1]);
    for (i = 0; i < 4; i++)
        for (p = 0; p < 2; p++)
            fprintf(f, "# median %s %.0f\n", name[i][p], median[i][p]);
    if (res->odocal) {
        double pm[2], pmed[2], cm[2], cmed[2], g[2][2];
        for (p = 0; p < 2; p++) {
            double sx = 0, sy = 0;
            cr_stats(res->exp2_plain_err, res->runs, p, &pm[p], &pmed[p]);
            cr_stats(res->exp2_cal_err, res->runs, p, &cm[p], &cmed[p]);
            for (i = 0; i < res->runs; i++) {
                sx += res->cal_gain[i][p][0];
                sy += res->cal_gain[i][p][1];
            }
            g[p][0] = res->runs > 0 ? sx / res->runs : NAN;
            g[p][1] = res->runs > 0 ? sy / res->runs : NAN;
        }
        fprintf(f, "# odometry calibration (odocal.h) over the first leg: %ld coach frames, "
                   "%ld reports taken; mean gains A x %.3f y %.3f, B x %.3f y %.3f\n",
                res->cal_frames, res->cal_fixes, g[0][0], g[0][1], g[1][0], g[1][1]);
        fprintf(f, "# exp2 seed 003's plain correction: A %.0f B %.0f mm (medians %.0f, %.0f)\n",
                pm[0], pm[1], pmed[0], pmed[1]);
        fprintf(f, "# exp2 correction + calibrated odometry: A %.0f B %.0f mm (medians %.0f, "
                   "%.0f)%s\n",
                cm[0], cm[1], cmed[0], cmed[1], "; the exp2_err lines below are these");
    }
    fprintf(f, "# the summary values are means over the runs (seed 003 reports averages)\n");
    for (i = 0; i < 4; i++)
        for (p = 0; p < 2; p++)
            fprintf(f, "%s %.0f\n", name[i][p], mean[i][p]);
    fprintf(f, "wrong_assignments %d\n", res->wrong_assignments);
}
