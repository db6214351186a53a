/*
 * tools/world/team.h - several players walking at once on one field, plus a
 * coach standing still beside it (seed 003's setting).  Host only.
 *
 * Each player is its own walk (tools/world/sim.h sim_t: its own scenario,
 * route, odometry noise and PRNG seed) and wears a jersey colour.  Per
 * team_step, in order:
 *   1. every player's simulator advances one step (motion, odometry, head;
 *      its feature observations are drawn with the other robots standing
 *      where they were after the previous step: up to one step, ~6 mm at
 *      180 mm/s and 30 Hz, behind);
 *   2. every player's list of other robots (sim_set_others) is set to the
 *      other players at their true poses of this step, plus the coach, so
 *      a player's rendered view of this step (team_player_scene) shows
 *      them where they are.
 * Each player's vision and localizer live one layer up (tools/loc/coachrun.h:
 * the tools folders may not include each other in a circle, and tools/loc
 * already builds on tools/world): there a player's rendered frames go
 * through the firmware vision path, or its feature observations are used,
 * into its own localizer.
 * The coach's view (team_coach_scene) is the 640 x 480 frame of the coach's
 * camera with every player at its true pose (render_robot_t with its
 * jersey: legs, feet on the carpet, occlusions by the renderer).
 *
 * Determinism: everything comes from the scenarios' seeds and the render
 * seeds; the same configuration gives the same bytes on every run.
 */
#ifndef FL_TOOLS_TEAM_H
#define FL_TOOLS_TEAM_H

#include "fieldloc/fieldloc.h"
#include "world/coach_scene.h"
#include "world/render.h"
#include "world/sim.h"

#define TEAM_MAX_PLAYERS 4

/* The coach of seed 003 (its figure 1): tools/world/coach_scene.h's default
 * (a NAO standing still 3 m beyond the -y touchline at the halfway line,
 * facing the field, "nao6-top-640" at the model's standing neck height,
 * head pitched so that the far touchline is just inside the image). */
#define TEAM_COACH_X_MM COACH_X_MM
#define TEAM_COACH_Y_MM COACH_Y_MM

typedef struct {
    const fl_camera_model_t *model;   /* COACH_CAMERA */
    int32_t x_mm, y_mm;
    fl_angle_t heading;
    fl_camera_pose_t head;            /* the model's neck height and pitch
                                         offset, head pitch, yaw 0 */
    render_jersey_t jersey;           /* the coach's own team */
    int in_players_world;             /* 1: the players see it (an other
                                         robot standing off the carpet) */
} team_coach_t;

/* The default coach above (jersey red, seen by the players). */
void team_coach_default(team_coach_t *c);

typedef struct {
    sim_scenario_t sc;                /* its walk (route, noise, seed) */
    render_jersey_t jersey;
} team_player_cfg_t;

typedef struct {
    sim_t sim;
    sim_step_t st;                    /* the last step */
    render_jersey_t jersey;
} team_player_t;

typedef struct {
    int n;
    team_player_t p[TEAM_MAX_PLAYERS];
    team_coach_t coach;
    const fl_field_t *field;
    long steps;                       /* team_step calls that ran */
} team_t;

/* n players (1..TEAM_MAX_PLAYERS, all on the first one's field).  0, or -1
 * with a message (nothing to free then). */
int team_init(team_t *t, const team_player_cfg_t *cfg, int n, const team_coach_t *coach,
              char *err, int err_len);

/* One step of every player (above).  1 on success, 0 when a walk is over
 * (nothing stepped). */
int team_step(team_t *t);

/* Every player with route_once has reached its last waypoint. */
int team_all_arrived(const team_t *t);

/* The robots every player i sees (the others and the coach), as sim_other_t
 * at the current true poses; returns the count. */
int team_others_of(const team_t *t, int i, sim_other_t *out);

/* The coach's render scene: its camera and pose, every player at its true
 * pose with its jersey, render seed `seed` (world_seed 1, the renderer's
 * defaults otherwise).  The background frame (no players) is the same with
 * n_robots = 0. */
void team_coach_scene(const team_t *t, uint32_t seed, render_scene_t *scene);

/* Player i's own view of its last step: sim_render_scene (its head, the
 * other robots of this step), render seed mixed with the step as sim's. */
void team_player_scene(const team_t *t, int i, render_scene_t *scene);

#endif /* FL_TOOLS_TEAM_H */
