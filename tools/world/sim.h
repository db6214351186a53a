/*
 * tools/world/sim.h - walk simulator: a NAO or AIBO walking a list of waypoints on
 * a field model, with head scanning, legged-robot odometry errors, slips,
 * kidnaps and penalties, and per-step feature-level observations
 * (fl_obs_list_t, include/fieldloc/obs.h) or rendered frames (tools/world/render.h)
 * at the true pose.  Host only (double allowed, no malloc needed).
 *
 * Determinism.  All randomness comes from the scenario seed through the
 * simulator's own PRNG (xorshift64*); the arithmetic is IEEE double + - * /
 * and sqrt only, with the simulator's own polynomial sin/cos/atan2 (no libm
 * transcendental), and every output is rounded to an integer.  The same
 * scenario gives identical steps (and identical trace bytes) on every run and
 * every IEEE-754 machine (x86-64, i686 with SSE2, mips).
 *
 * Frames and units: as in DESIGN.md.  Field frame: origin at the centre, x
 * toward the +x goal, y left, mm; heading CCW from +x.  Robot frame: x
 * forward, y left, origin on the ground below the head pitch axis (the
 * camera.h origin).  Angles in integer outputs are binary angles (fl_angle_t,
 * 65536 per turn).
 *
 * Time line.  Step k happens at t = k / frame_hz.  Step 0 is the start pose
 * (no motion).  For k >= 1, in this order:
 *   1. motion: the robot walks from step k-1 to step k (true_d*; a slip adds
 *      an unmodelled displacement to the true motion, not to the odometry);
 *      odometry (odo_d*) is the true walked motion corrupted by the noise
 *      model, both in the robot frame at the START of the step;
 *   2. events at this time: kidnap (true pose teleported; odometry and the
 *      localizer are told nothing) or penalty (true pose set to a touchline
 *      placement spot, facing into the field; the localizer IS told:
 *      SIM_EV_PENALIZED), end of a penalty (SIM_EV_UNPENALIZED);
 *   3. head angles for this frame, then observations of the pose after 1-2.
 * A localizer does: predict(odo) ; if (events & SIM_EV_PENALIZED) reset to
 * the two placement spots ; update(obs).
 *
 * Integrating step deltas.  Convention (true_d* and odo_d* alike): with the
 * pose (x, y, h) before the step,
 *     x += dx*cos(h) - dy*sin(h);  y += dx*sin(h) + dy*cos(h);  h += dtheta.
 * Integer deltas carry their rounding remainder to the next step (error
 * diffusion per component), so integrating the integer deltas does not
 * accumulate rounding bias; the exact double deltas are given as well.
 *
 * Typical use:
 *     sim_scenario_t sc;  sim_t sim;  sim_step_t st;
 *     sim_scenario_builtin(&sc, "spl2013");      (or sim_scenario_load)
 *     sim_init(&sim, &sc);
 *     while (sim_step(&sim, &st)) {
 *         ... st.odo_dx_mm, st.odo_dy_mm, st.odo_dtheta, st.events,
 *             st.head (fl_camera_pose_t), st.obs (fl_obs_list_t),
 *             truth: st.x_mm, st.y_mm, st.heading ...
 *     }
 */
#ifndef FL_TOOLS_SIM_H
#define FL_TOOLS_SIM_H

#include "fieldloc/camera.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"
#include "world/render.h"

#include <stdint.h>
#include <stdio.h>

#define SIM_MAX_WAYPOINTS 64
#define SIM_MAX_EVENTS 16
#define SIM_NAME_LEN 32
#define SIM_MAX_OTHERS RENDER_MAX_ROBOTS
#define SIM_BUILTIN_COUNT 5

/* Feature mode's white points (fl_obs_list_t.points, robot frame mm): a
 * uniform random sample of SIM_POINTS_PER_FRAME (at most FL_OBS_MAX_POINTS)
 * of the painted-line points the camera sees, taken every SIM_POINT_STEP_MM
 * along every line and the centre circle (across the paint: uniform within
 * the line width), with the scenario's range noise (range_sigma_pct) and
 * bearing noise (bearing_sigma_deg), as the landmarks get.  Fewer when
 * fewer are in view (none: n_points 0). */
#define SIM_POINTS_PER_FRAME (FL_OBS_MAX_POINTS < 24 ? FL_OBS_MAX_POINTS : 24)
#define SIM_POINT_STEP_MM 50

/* Event bits of a step. */
#define SIM_EV_KIDNAP      1u  /* truth only: teleported, nobody is told */
#define SIM_EV_PENALIZED   2u  /* told: removed and placed on a touchline
                                  spot (x = penalty_x_mm, y = +-width/2,
                                  facing into the field); stands still */
#define SIM_EV_UNPENALIZED 4u  /* told: the penalty is over, walking resumes */
#define SIM_EV_SLIP        8u  /* truth only: an unmodelled slip this step */

typedef enum { SIM_ROBOT_NAO = 0, SIM_ROBOT_AIBO = 1 } sim_robot_t;

typedef enum {
    SIM_EVENT_KIDNAP = 0,   /* teleport to (x_mm, y_mm, heading_deg) */
    SIM_EVENT_PENALTY = 1   /* removal penalty lasting duration_s; the
                               touchline side is drawn from the PRNG */
} sim_event_kind_t;

typedef struct {
    sim_event_kind_t kind;
    double t_s;                 /* time of the event */
    double x_mm, y_mm, heading_deg;   /* kidnap target */
    double duration_s;          /* penalty: time standing at the spot */
} sim_event_t;

typedef struct { double x_mm, y_mm; } sim_waypoint_t;

/* Another robot standing still on the field (teammate or opponent): drawn
 * in the rendered frames (render_robot_t, its NAO or AIBO body) and, in
 * feature mode, hiding the landmarks behind it (sim_occluded). */
typedef struct {
    double x_mm, y_mm, heading_deg;   /* feet centre, facing direction */
    render_jersey_t jersey;
} sim_other_t;

/*
 * A scenario.  Fill with sim_scenario_defaults (robot-typical values, noise
 * on, no waypoints, no events) or sim_scenario_builtin / _parse / _load.
 * All noise figures are 1-sigma unless said otherwise.  Text keys (see
 * fixtures/walks/README.md) are given in [brackets].
 */
typedef struct {
    char name[SIM_NAME_LEN];              /* [name] */
    char field_name[SIM_NAME_LEN];        /* [field]  fl_field_find name */
    char camera_name[SIM_NAME_LEN];       /* [camera] fl_camera_model_find */
    const fl_field_t *field;              /* resolved from field_name */
    const fl_camera_model_t *camera;      /* resolved from camera_name */
    sim_robot_t robot;                    /* [robot nao|aibo] */
    uint64_t seed;                        /* [seed] */
    double frame_hz;                      /* [frame_hz] steps per second */
    double duration_s;                    /* [duration_s] */

    /* start pose and route */
    double start_x_mm, start_y_mm, start_heading_deg;   /* [start X Y DEG] */
    sim_waypoint_t waypoint[SIM_MAX_WAYPOINTS];         /* [waypoint X Y] */
    int n_waypoints;                      /* the route loops when done */
    double arrive_mm;                     /* [arrive_mm] waypoint reached */

    /* walking (gait limits) */
    double v_forward_mm_s;                /* [v_forward_mm_s] max forward */
    double v_backward_mm_s;               /* [v_backward_mm_s] (unused by
                                             the waypoint follower; kept for
                                             limits of the odometry check) */
    double v_side_mm_s;                   /* [v_side_mm_s] max sideways */
    double turn_deg_s;                    /* [turn_deg_s] max turn rate */
    double accel_mm_s2;                   /* [accel_mm_s2] speed ramp */
    double turn_accel_deg_s2;             /* [turn_accel_deg_s2] */

    /* head: yaw sweeps a triangle wave, pitch alternates two values */
    int32_t neck_height_mm;               /* [neck_mm] head pitch axis height */
    double pitch_offset_deg;              /* [pitch_offset_deg] extra downward
                                             tilt (fl_camera_pose_t) */
    int camera_defaults;                  /* [camera_defaults 0|1] 1: use the
                                             camera model's
                                             default_neck_height_mm and
                                             default_pitch_offset instead of
                                             neck_mm and pitch_offset_deg */
    double head_pitch_rad[2];             /* [head_pitch P0 P1] (+ = down) */
    double pitch_period_s;                /* [pitch_period_s] 0 = P0 only */
    double yaw_amplitude_rad;             /* [yaw_amplitude_rad] sweep +-A */
    double yaw_period_s;                  /* [yaw_period_s] full sweep cycle */

    /* odometry noise (legged robot) */
    double odo_scale_x, odo_scale_y, odo_scale_theta;
        /* [odo_scale SX SY STH] systematic: odometry = true * (1 + S);
           e.g. 0.10: odometry reports 10% more than was walked */
    double odo_drift_deg_per_m;           /* [odo_drift_deg_per_m] systematic
                                             heading drift per metre walked
                                             (odometry turns, robot does not) */
    double odo_sigma_trans;               /* [odo_sigma_trans] random, per
                                             step, fraction of the step length
                                             (applied to dx and dy) */
    double odo_sigma_rot;                 /* [odo_sigma_rot] random, per step,
                                             fraction of |dtheta| */
    double odo_sigma_rot_deg_per_m;       /* [odo_sigma_rot_deg_per_m] random
                                             heading noise per metre walked */
    double slip_rate_hz;                  /* [slip_rate_hz] expected slips/s
                                             while walking */
    double slip_max_mm, slip_max_deg;     /* [slip_max MM DEG] uniform in
                                             +-max, true motion only */

    /* observations */
    double max_range_mm;                  /* [max_range_mm] */
    double range_sigma_pct;               /* [range_sigma_pct] % of range */
    double bearing_sigma_deg;             /* [bearing_sigma_deg] */
    double orientation_sigma_deg;         /* [orientation_sigma_deg] */
    double p_miss;                        /* [p_miss] per visible landmark */
    double fp_per_frame;                  /* [fp_per_frame] expected false
                                             positives per frame (0..4) */
    double p_confuse;                     /* [p_confuse] L<->T confusion */
    int32_t fov_margin_px;                /* [fov_margin_px] a landmark is
                                             seen when its ground point
                                             projects at least this far
                                             inside the image */

    /* events */
    double penalty_x_mm;                  /* [penalty_x_mm] placement spot x
                                             (both touchlines) */
    sim_event_t event[SIM_MAX_EVENTS];    /* [kidnap T X Y DEG]
                                             [penalty T DURATION] */
    int n_events;

    /* robots standing on the field */
    sim_other_t other[SIM_MAX_OTHERS];    /* [other X Y DEG red|blue] */
    int n_others;

    /* route variants (both off by default; the text form names them only
     * when on, so the built-in walks' text and traces are unchanged) */
    int hold_heading;                     /* [face_deg DEG] sets it: the
                                             robot keeps facing face_deg and
                                             walks omnidirectionally toward
                                             the waypoint (forward/sideways
                                             within the gait limits), e.g.
                                             along a touchline facing out */
    double face_deg;
    int route_once;                       /* [route_once 0|1] 1: stand still
                                             at the last waypoint instead of
                                             looping (sim_arrived) */

    /* not part of the text form: 1 (the default) samples the white points
     * of feature mode (SIM_POINTS_PER_FRAME above); 0 leaves obs.points
     * empty.  The sampling projects every painted-line point in range and
     * tests it against the other robots, most of a feature-mode step's
     * work; a caller whose localizer does not read the points
     * (fl_localizer_t.reads_points) turns it off.  The landmark
     * observations, the walk and every random draw are the same either
     * way (the points have their own stream). */
    int white_points;

    /* not part of the text form: which features feature mode observes
     * (`fieldloc simulate --vision`).  SIM_VISION_LTX (0, the default) the
     * field's landmarks (L/T/X crossings, marks, posts, circle, beacons)
     * exactly as before; SIM_VISION_CORNERS seed 004's corner features and
     * nets (fl_field_t.features: a field without them sees nothing);
     * SIM_VISION_BOTH the landmarks, then the features.  The same noise,
     * miss, false-positive and visibility model for every kind; false
     * positives take a kind of the observed set(s). */
    int vision;
} sim_scenario_t;

#define SIM_VISION_LTX 0
#define SIM_VISION_CORNERS 1
#define SIM_VISION_BOTH 2

/* Robot-typical defaults (speeds, rates, noise; values and sources in
 * sim.c and fixtures/walks/README.md).  field/camera are left NULL and
 * the names empty. */
void sim_scenario_defaults(sim_scenario_t *sc, sim_robot_t robot);

/* Turn every noise source off (odometry, slips, observation noise, misses,
 * false positives, confusion); geometry, route and events are kept. */
void sim_scenario_noise_off(sim_scenario_t *sc);

/* Scenario text ("key values..." lines, '#' comments; format in
 * fixtures/walks/README.md).  Keys not given keep the defaults of the
 * `robot` key (which must come first if present).  0 on success, -1 with a
 * message in err (err may be NULL). */
int sim_scenario_parse(sim_scenario_t *sc, const char *text, char *err,
                       int err_len);
int sim_scenario_load(sim_scenario_t *sc, const char *path, char *err,
                      int err_len);
/* Write the text form (all keys; parse(write(sc)) == sc). */
int sim_scenario_write(FILE *f, const sim_scenario_t *sc);

/* Make the walk have n kidnaps (`fieldloc simulate --kidnaps N`): n equal
 * to the scenario's own count changes nothing; fewer keeps the first n;
 * more adds kidnaps one by one, each at the time (0.1 s grid) farthest
 * from the start, the end, every kidnap and every penalty (start to end),
 * to a target drawn uniformly over the field plus half its border, heading
 * uniform (drawn again, at most 16 times, while within 500 mm of another
 * robot of the scenario), from a PRNG stream of its own derived from sc->seed (set the
 * seed first).  The walk's noise stream is not touched: the walk is
 * identical up to the first added kidnap; after it the robot is elsewhere,
 * so the observations (how many are drawn) and with them the rest of the
 * stream differ.  Kidnap k is the same for every n >= k.  A changed walk
 * gets "+kN" appended to its name.  0, or -1 when the events do not fit
 * SIM_MAX_EVENTS or two kidnaps would come closer than 2 s. */
int sim_scenario_set_kidnaps(sim_scenario_t *sc, int n);

/* The built-in scenarios behind the committed fixtures: "spl2013",
 * "uva2013", "aibo2004", "spl2020" (in that order).  Text of one (NULL if
 * unknown), and parsed. */
const char *sim_builtin_text(const char *name);
int sim_scenario_builtin(sim_scenario_t *sc, const char *name);
extern const char *const sim_builtin_names[SIM_BUILTIN_COUNT];

/* One step of the walk.  Integer fields are the outputs (rounded, used by
 * the trace and the digests); doubles are the exact values for host code. */
typedef struct {
    uint32_t index;                 /* step number, 0.. */
    int32_t t_ms;                   /* time, ms (rounded) */

    /* true pose after this step (field frame) */
    int32_t x_mm, y_mm;
    fl_angle_t heading;
    double true_x_mm, true_y_mm, true_heading_rad;

    /* true motion this step, robot frame at the start of the step, slips
     * included, teleports (kidnap, penalty) excluded */
    int32_t true_dx_mm, true_dy_mm;
    fl_angle_t true_dtheta;
    double true_dx, true_dy, true_dtheta_rad;

    /* odometry reported for this step (same frame and convention) */
    int32_t odo_dx_mm, odo_dy_mm;
    fl_angle_t odo_dtheta;
    double odo_dx, odo_dy, odo_dtheta_rad;

    /* head and camera for this frame */
    fl_camera_pose_t head;          /* neck_height_mm, head_pitch, head_yaw,
                                       pitch_offset (scenario or camera
                                       default) */
    double head_pitch_rad, head_yaw_rad;

    unsigned events;                /* SIM_EV_* bits */
    int penalized;                  /* 1 while standing at a penalty spot */

    /* observations of this frame (robot frame) */
    fl_obs_list_t obs;
    /* truth per observation: fl_field_all_at id (field->landmarks, then
     * seed 004's features), -1 for a false positive; confused[i] = 1 when the kind was swapped (L<->T) */
    int16_t obs_landmark[FL_OBS_MAX];
    uint8_t obs_confused[FL_OBS_MAX];
} sim_step_t;

/* Simulator state.  Transparent for debugging; callers only read it. */
typedef struct {
    sim_scenario_t sc;
    fl_camera_t cam;
    uint64_t rng;
    uint32_t k, n_steps;
    double x, y, h;                 /* true pose (mm, mm, rad) */
    double vx, vy, vh;              /* current commanded velocity (robot) */
    int wp;                         /* current waypoint */
    double carry[6];                /* rounding remainders: true dx dy dth,
                                       odo dx dy dth */
    double penalty_until_s;         /* > t while penalized */
    int next_event;
    int arrived;                    /* route_once: the last waypoint reached */
} sim_t;

/* Validate the scenario (field and camera found, rates and limits sane)
 * and reset.  0 on success, -1 (state unusable) otherwise. */
int sim_init(sim_t *sim, const sim_scenario_t *sc);

/* Advance one step (step 0 first) and fill *out.  Returns 0 when the walk
 * is over (duration reached; *out untouched), 1 otherwise. */
int sim_step(sim_t *sim, sim_step_t *out);

/* Number of steps of the whole walk: floor(duration_s * frame_hz) + 1. */
uint32_t sim_step_count(const sim_t *sim);

/* Between steps, for several robots walking at once (tools/world/team.h):
 * replace the robots standing on the field (the others as they are now:
 * drawn in the frames and hiding landmarks from the next step on;
 * n <= SIM_MAX_OTHERS), or the route (n waypoints, followed from the first
 * with the scenario's heading mode; clears sim_arrived).  0, or -1 on bad
 * arguments (state unchanged). */
int sim_set_others(sim_t *sim, const sim_other_t *other, int n);
int sim_set_route(sim_t *sim, const sim_waypoint_t *wp, int n);
/* route_once: 1 once the last waypoint is reached (the robot then stands). */
int sim_arrived(const sim_t *sim);

/* Observations only, for a given true pose and head: every landmark whose
 * ground point is inside the image (fov_margin_px), within max_range and
 * not hidden behind another robot (sim_occluded),
 * with the scenario's observation noise drawn from *rng (noise off gives
 * exact, deterministic observations).  Used by sim_step; exposed for
 * tests and for localizer experiments. */
void sim_observe(const sim_scenario_t *sc, const fl_camera_t *cam,
                 int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                 uint64_t *rng, sim_step_t *out);

/* Is the straight segment from the camera (cam, on the robot at x_mm,
 * y_mm, heading) to the field point (fx, fy, fz) (mm) blocked by one of the
 * scenario's other robots?  Each is three boxes in its own frame that
 * enclose the renderer's body (tools/world/render.c build_robot): legs and
 * feet, torso with arms, head (AIBO: legs, body, head).  A point under a
 * robot's feet is hidden.  1 blocked, 0 not.  Deterministic (+ - * / only). */
int sim_occluded(const sim_scenario_t *sc, const fl_camera_t *cam, int32_t x_mm,
                 int32_t y_mm, fl_angle_t heading, double fx, double fy, double fz);

/* Text trace of a whole walk (format in fixtures/walks/README.md): a header,
 * then per step one 's' line (time, true pose, true motion, odometry, head,
 * events) and one 'o' line per observation.  0 on success. */
int sim_write_trace(FILE *f, const sim_scenario_t *sc);

/* Regenerate the walk fixtures: for each built-in scenario NAME write
 * OUT_DIR/NAME.walk (its text) and OUT_DIR/NAME.trace (generated by parsing
 * that file back).  OUT_DIR must exist (e.g. "fixtures/walks").  Returns
 * the number of scenarios written (SIM_BUILTIN_COUNT) or -1 on an I/O error. */
int sim_write_walk_fixtures(const char *out_dir);

/* Mode (b), rendered frames (tools/world/render.h; the render functions are weak
 * references here, so a build without tools/world/render.c still links and these
 * two calls then do nothing / return -1): the render scene of a step (true
 * pose, head, scenario seed mixed with the step index, the scenario's other
 * robots, the renderer's defaults otherwise: RGB888, cluttered background,
 * nominal light); the caller may add lighting... before render_frame. */
void sim_render_scene(const sim_scenario_t *sc, const sim_step_t *st,
                      render_scene_t *scene);

/* Sequence file for `fieldloc localize` (the format below): renders every
 * `every`-th step (max_frames frames at most, 0 = all) as PPM images named
 * IMAGE_PREFIXnnnnn.ppm next to seq_path, and writes
 *     field NAME / camera NAME / [prior X_MM Y_MM THETA_DEG] /
 *     frame IMAGE.ppm odo DX_MM DY_MM DTHETA_DEG head PITCH_RAD YAW_RAD
 * with the odometry summed over the skipped steps (composed in the robot
 * frame of the previous frame; printed to 0.1 mm and 0.001 deg with the
 * rounding remainders carried), head angles to 1e-6 rad (they round back
 * to the same binary angles).  The first frame is step 0 (odometry 0).
 * Events are not part of the format (a penalty placement shows only as a
 * jump).  with_prior writes the start pose as prior.  The format carries
 * no neck height or pitch offset: `localize` takes the camera model's
 * defaults, so the frames are rendered with those too (the walk itself,
 * truth and odometry, is the scenario's).  0 on success. */
int sim_write_sequence(const sim_scenario_t *sc, const char *seq_path,
                       const char *image_prefix, int every, int max_frames,
                       int with_prior);

#endif /* FL_TOOLS_SIM_H */
