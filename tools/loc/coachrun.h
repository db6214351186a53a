/*
 * tools/loc/coachrun.h - seed 003's two experiments (its sections 4.1-4.4)
 * in the simulator: two players walk routes where lines and goals are hard
 * to see while a coach beside the field estimates their feet; Experiment 1
 * compares the coach's foot estimate with each player's own estimate,
 * Experiment 2 the players' self-localization at the end of a second leg
 * with and without one re-seed from the coach's report.  Host only.
 *
 * How the routes read seed 003's figures 11-12 (the figures themselves are
 * not in the text; their captions and section 4.1 are): two players of the
 * SAME team (red jerseys, the coach's team: seed 003's coach finds "the
 * own team's jersey", so telling the two apart is left to the assignment),
 * robot A walking near the coach, robot B far from it, each side-stepping
 * along a touchline facing out of the field (the player sees the touchline
 * at its feet, the carpet's border and the room, rarely a crossing or a
 * goal; its head scans +-0.4 rad only).  Red circle = start, blue circle =
 * end of the first leg (2.5 m), grey circle = end of the second leg (2.5 m
 * further the same way).  The coach stands at x = 0, y = -6000 (team.h):
 *     A: (-3000, -2500) -> blue (-500, -2500) -> grey (2000, -2500),
 *        facing -y (out over the -y touchline): 3.5 m from the coach at blue
 *     B: (3000, 2500) -> blue (500, 2500) -> grey (-2000, 2500),
 *        facing +y (out over the +y touchline): 8.5 m from the coach at blue
 * Both players know their start pose (seed 003 sets them on the red
 * circles; the localizer starts there with 100 mm / 10 deg).
 *
 * One run (seed s): both walk the first leg; when both have arrived the
 * coach takes one frame (team_coach_scene) and estimates the feet
 * (Experiment 1: each player's true foot against the nearest foot the
 * coach reports, and against the player's own estimate).  The run then
 * continues twice from the same state: without the coach, and with one
 * application of the reports (report.h: the coach numbers its reports
 * against the estimates the players broadcast, fl_report_assign; each
 * player takes its own, fl_report_pick, and re-seeds through
 * fl_report_apply -> fl_loc_reseed); both walk the second leg and the
 * error of each player's estimate at the grey circle is Experiment 2.  The two
 * continuations are computed by running the same deterministic world twice
 * (identical up to the blue circle).
 */
#ifndef FL_TOOLS_COACHRUN_H
#define FL_TOOLS_COACHRUN_H

#include "fieldloc/fieldloc.h"
#include "world/team.h"

#include <stdint.h>
#include <stdio.h>

/* Where the coach's feet come from. */
typedef enum {
    CR_FEET_COACH = 0,        /* the coach's image path on its rendered frame */
    CR_FEET_TRUTH_DEBUG = 1   /* DEBUG ONLY: the true feet (checks the rest of
                                 the experiment; never a measured result) */
} cr_feet_t;

typedef struct {
    const fl_localizer_t *loc;   /* NULL: "upf" */
    uint64_t seed;               /* first run's seed; run r uses seed + r */
    int runs;                    /* >= 1 */
    int frames;                  /* 1: players' rendered frames -> vision */
    int every;                   /* frames: vision every Nth step */
    cr_feet_t feet;
    int reseed_always;           /* 1: Experiment 2 re-seeds every player
                                    that got a report at the blue circle
                                    (seed 003 4.3: "correct the particle
                                    position only once ... at the blue
                                    circles"); 0: only a player whose belief
                                    has spread beyond FL_LOC_RESEED_SPREAD_MM
                                    (the online rule of its section 3) */
    int assign_player_side;      /* 1: no numbering by the coach; each
                                    player takes the report of its team
                                    nearest its own estimate (report.h
                                    fl_report_pick); 0: the coach numbers
                                    the reports (fl_report_assign) against
                                    the players' broadcast estimates */
    int odocal;                  /* 1: a third continuation: the coach also
                                    sees the players once a second over the
                                    first leg, each player calibrates its
                                    odometry's scale from that track
                                    (odocal.h) and corrects its odometry
                                    after the correction; exp2_err is then
                                    that variant's, exp2_plain_err seed
                                    003's */
    FILE *log;                   /* per-run "# run ..." lines, or NULL */
    FILE *trace;                 /* per-step "# step ..." lines, or NULL */
} cr_opts_t;

#define CR_MAX_RUNS 1000

typedef struct {
    int runs;
    /* per run, per player (0 = A near, 1 = B far) */
    double coach_err[CR_MAX_RUNS][2];    /* NAN: the coach found no foot */
    double own_err[CR_MAX_RUNS][2];
    double own_head_err[CR_MAX_RUNS][2];    /* degrees, 0..180 */
    double exp2_err[CR_MAX_RUNS][2];
    double exp2_nocoach_err[CR_MAX_RUNS][2];
    double exp2_plain_err[CR_MAX_RUNS][2];  /* seed 003's correction only */
    double exp2_cal_err[CR_MAX_RUNS][2];    /* odocal: + calibrated odometry */
    double cal_gain[CR_MAX_RUNS][2][2];     /* odocal: per player x, y gain */
    long cal_frames, cal_fixes;
    int odocal;
    double coach_dist_mm[CR_MAX_RUNS][2];   /* true distance coach -> foot */
    int reseeds, not_needed, refused, assigned, unassigned, wrong_assignments, coach_missed;
    int leg_timeouts;
    double wall_s, render_s;
    long rendered;
} cr_result_t;

/* The scenario of player p (0 = A, 1 = B) for run seed s: leg 1 route. */
void cr_scenario(sim_scenario_t *sc, int p, uint64_t seed);

/* All runs.  0, or -1 with a message. */
int cr_run(const cr_opts_t *o, cr_result_t *res, char *err, int err_len);

/* "# ..." information (medians, counts) and the summary lines
 * coach_foot_err_near_mm ... wrong_assignments (exact format: means). */
void cr_print_summary(FILE *f, const cr_result_t *res);

#endif /* FL_TOOLS_COACHRUN_H */
