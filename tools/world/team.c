/*
 * tools/world/team.c - several players and a coach (API in tools/world/team.h).
 */
#include "world/team.h"

#include <stdio.h>
#include <string.h>

void team_coach_default(team_coach_t *c)
{
    render_scene_t sc;
    memset(c, 0, sizeof *c);
    coach_scene_default(&sc, NULL);
    c->model = sc.camera;
    c->x_mm = sc.robot_x_mm;
    c->y_mm = sc.robot_y_mm;
    c->heading = sc.robot_heading;
    c->head = sc.head;
    c->jersey = RENDER_JERSEY_RED;
    c->in_players_world = 1;
}

static void team_err(char *err, int err_len, const char *msg, int i)
{
    if (err != NULL && err_len > 0)
        snprintf(err, (size_t)err_len, "player %d: %s", i, msg);
}

int team_others_of(const team_t *t, int i, sim_other_t *out)
{
    int j, n = 0;
    for (j = 0; j < t->n && n < SIM_MAX_OTHERS; j++) {
        const sim_t *s = &t->p[j].sim;
        if (j == i)
            continue;
        out[n].x_mm = s->x;
        out[n].y_mm = s->y;
        out[n].heading_deg = s->h * (180.0 / 3.14159265358979323846);
        out[n].jersey = t->p[j].jersey;
        n++;
    }
    if (t->coach.in_players_world && n < SIM_MAX_OTHERS) {
        out[n].x_mm = t->coach.x_mm;
        out[n].y_mm = t->coach.y_mm;
        out[n].heading_deg = (double)t->coach.heading * (360.0 / 65536.0);
        out[n].jersey = t->coach.jersey;
        n++;
    }
    return n;
}

static void team_set_others(team_t *t)
{
    sim_other_t o[SIM_MAX_OTHERS];
    int i;
    for (i = 0; i < t->n; i++)
        sim_set_others(&t->p[i].sim, o, team_others_of(t, i, o));
}

int team_init(team_t *t, const team_player_cfg_t *cfg, int n, const team_coach_t *coach,
              char *err, int err_len)
{
    int i;
    if (t == NULL || cfg == NULL || n < 1 || n > TEAM_MAX_PLAYERS) {
        team_err(err, err_len, "1..TEAM_MAX_PLAYERS players", 0);
        return -1;
    }
    memset(t, 0, sizeof *t);
    t->n = n;
    if (coach != NULL)
        t->coach = *coach;
    else
        team_coach_default(&t->coach);
    if (t->coach.model == NULL) {
        team_err(err, err_len, "no coach camera model", 0);
        return -1;
    }
    for (i = 0; i < n; i++) {
        if (sim_init(&t->p[i].sim, &cfg[i].sc) != 0) {
            team_err(err, err_len, "bad scenario", i);
            return -1;
        }
        if (i > 0 && cfg[i].sc.field != cfg[0].sc.field) {
            team_err(err, err_len, "not on the first player's field", i);
            return -1;
        }
        t->p[i].jersey = cfg[i].jersey;
    }
    t->field = cfg[0].sc.field;
    /* the others stand where they start from the first step on */
    team_set_others(t);
    return 0;
}

int team_step(team_t *t)
{
    int i;
    if (t == NULL || t->n < 1)
        return 0;
    for (i = 0; i < t->n; i++)
        if (t->p[i].sim.k >= t->p[i].sim.n_steps)
            return 0;
    for (i = 0; i < t->n; i++)
        sim_step(&t->p[i].sim, &t->p[i].st);
    team_set_others(t);
    t->steps++;
    return 1;
}

int team_all_arrived(const team_t *t)
{
    int i;
    for (i = 0; i < t->n; i++)
        if (!sim_arrived(&t->p[i].sim))
            return 0;
    return 1;
}

void team_coach_scene(const team_t *t, uint32_t seed, render_scene_t *scene)
{
    int i;
    coach_scene_default(scene, t->field);
    scene->camera = t->coach.model;
    scene->robot_x_mm = t->coach.x_mm;
    scene->robot_y_mm = t->coach.y_mm;
    scene->robot_heading = t->coach.heading;
    scene->head = t->coach.head;
    scene->seed = seed;
    scene->n_robots = 0;
    for (i = 0; i < t->n && i < RENDER_MAX_ROBOTS; i++) {
        render_robot_t *r = &scene->robots[scene->n_robots++];
        r->x_mm = t->p[i].st.x_mm;
        r->y_mm = t->p[i].st.y_mm;
        r->heading = t->p[i].st.heading;
        r->jersey = t->p[i].jersey;
    }
}

void team_player_scene(const team_t *t, int i, render_scene_t *scene)
{
    sim_render_scene(&t->p[i].sim.sc, &t->p[i].st, scene);
}
