/*
 * tools/cli/cmd_simulate.c - `fieldloc simulate`: a simulated walk (tools/world/sim.h)
 * localized through the localizer interface (include/fieldloc/localizer.h;
 * default the fuzzy position grid).
 *
 *   fieldloc simulate --field spl2013|uva2013|aibo2004|spl2020|hl3x2 --localizer fuzzy
 *                     --seed N [--features | --frames] [--steps N] [--quiet]
 *                     [--scenario FILE.walk] [--every N] [--param NAME=V]...
 *                     [--obs-cache FILE] [--print-obs] [--kidnaps N]
 *                     [--colors default|auto|FILE]
 *                     [--export-stream FILE] [--vision ltx|corners|both]
 *
 *   fieldloc simulate --coach [--localizer upf|mcl|fuzzy|relmap] [--seed N] [--runs N]
 *                     [--features | --frames] [--every N] [--quiet]
 *                     [--reseed once|spread] [--assign coach|player]
 *                     [--coach-feet coach|truth]
 *
 * --coach runs seed 003's experiments 1 and 2 (tools/loc/coachrun.h: two
 * red players side-stepping along the touchlines facing out, a coach
 * beside the field finding their feet) over --runs runs (default 20) with
 * seeds N, N+1, ... (default localizer upf, seed 1; the players see
 * through rendered frames and the vision path on every 6th step unless
 * --features / --every say otherwise).  Output: one "# run" line per run
 * (unless --quiet), "#" information lines (distances to the coach,
 * reports taken and refused, re-seeds, medians, wall time) and exactly the
 * summary lines (means over the runs, mm)
 *   coach_foot_err_near_mm X   coach's foot vs truth, robot A (3.6 m away)
 *   coach_foot_err_far_mm X    the same, robot B (8.5 m away)
 *   own_foot_err_near_mm X     robot A's own estimate vs truth, blue circle
 *   own_foot_err_far_mm X      robot B's
 *   exp2_err_a_mm X            robot A's error at the grey circle after one
 *                              correction from the coach at the blue one
 *   exp2_err_b_mm X            robot B's
 *   exp2_err_a_nocoach_mm X    the same without the correction
 *   exp2_err_b_nocoach_mm X
 *   wrong_assignments N        reports a player took that were the other
 *                              player's foot (over all runs)
 * --coach-feet truth makes the coach report the true feet: DEBUG only
 * (says so in its output), to check the rest of the chain.
 *
 * The walk is the built-in scenario of the field (fixtures/walks/NAME.walk:
 * >= 120 s of walking with head scanning, one kidnap, one penalty), with its
 * PRNG seed replaced by --seed.  --steps N stops after N simulator steps.
 * --kidnaps N (0..16) gives the walk N kidnaps instead of its own count
 * (tools/world/sim.h sim_scenario_set_kidnaps: added ones at the times
 * farthest from the start, the end, the other kidnaps and the penalty, to
 * random targets on the carpet drawn from a PRNG stream of their own, so
 * the walk is the same up to the first added kidnap; kidnap k is the same
 * for every N >= k).  The walk's name gets "+kN", so an observation cache
 * of the unchanged walk is not taken for it (and is refused rather than
 * overwritten).
 *
 * --export-stream FILE writes the localizer's inputs as a text stream
 * (docs/STREAM.md): per record the truth, the told and untold events, and
 * every predict, penalty reset and update call with the integers the
 * localizer received (frames mode: the split predict calls and the
 * observations and view vision gave); `fieldloc replay --stream FILE
 * [--localizer NAME]` runs any catalogue localizer on it and prints the
 * same step and summary lines.
 *
 * --features (default) feeds the simulator's feature-level observations
 * (fl_obs_list_t) to the localizer.  --vision chooses which: ltx (default)
 * the field's landmarks (L/T/X crossings, marks, posts, circle, beacons);
 * corners seed 004's corner features and nets (fl_field_t.features: C,
 * T-field, T-net, net; an error on a field without them); both the two
 * sets (sim.h sim_scenario_t.vision).  In frames mode it chooses the
 * vision path run on each rendered frame (locrun.h lr_set_vision): ltx
 * fl_vision_frame; corners seed 004's corner stage alone (fl_corners_run,
 * fl_corners_obs; the nets from fl_vision_frame's goal posts); both the
 * two lists together.  Per step: predict(odometry); on
 * SIM_EV_PENALIZED reset to the two touchline placement spots;
 * update(observations); estimate.
 *
 * --frames renders the frame of the true pose (sim_render_scene +
 * render_frame: the renderer's defaults, RGB888, cluttered room, sensor
 * noise; camera pose = the step's head, exactly what the renderer used)
 * and runs it through the firmware vision path (fl_vision_frame with the
 * default color tables) into the grid.  Rendering is the slow part (frames
 * are rendered in batches on lr_threads_default() threads, which does not
 * change the results), so vision runs on
 * every Nth simulator step only (--every N, default 3: 10 Hz for the 30 Hz
 * walks) and the
 * odometry of the steps between is composed (lr_odo_add) and given to one
 * predict; per vision step: predict(accumulated odometry) ; update(vision
 * observations) ; estimate; a penalty placement on a skipped step resets
 * the grid at that step and drops the odometry before it.  The metrics are
 * then computed over the vision steps only (one record per vision step,
 * printed as "# frames: ..." at the start).  Also printed: per observation
 * kind, how vision's observations compare with the map at the true pose
 * ("# vision ..." lines, tools/loc/locrun.h lr_vdiag_t) and the time spent
 * rendering and in vision + grid.
 *
 * --localizer NAME: any of the catalogue (localizer.h; default fuzzy).
 * Localizer parameters: --features uses the localizer's defaults; --frames
 * uses lr_params_frames (tools/loc/locrun.c: narrower rings for vision's
 * accurate ranges, measured there).  --param NAME=VALUE (repeatable)
 * changes one parameter of the localizer's table on top (raw integer
 * units; fuzzy: the fields of fl_fuzzy_params_t, fuzzy.h); every value
 * that differs from the defaults is printed.
 * --obs-cache FILE (frames mode, for parameter studies) stores
 * the vision observations of the walk in FILE, or reads them from it when
 * it holds those of the same walk, field, seed and --every: the localizer
 * does not change what vision sees, so a study renders once (delete the
 * file when the vision code changes: its header records the walk and the
 * --vision path only).
 *
 * --print-obs adds after each step line one "#  obs ..." line per
 * observation given to the localizer (kind, range, bearing, orientation,
 * side, confidence).
 *
 * The localizer starts in total ignorance with the prior "own half" (the
 * half of the start pose, as the game controller tells a robot at
 * kick-off).
 *
 * Output: per record (unless --quiet)
 *   step K T_S est X_MM Y_MM DEG REL truth X_MM Y_MM DEG err MM DEG
 *        STATE sd SDX_MM SDY_MM SDH_DEG mirror M
 * (on one line; REL the calibrated reliability, then the confidence of
 * localizer.h: LOST / AMBIGUOUS / TRACKING, the belief's spread, heading
 * spread ("-": none), the mirror pose's weight)
 * (K the simulator step) then "# ..." information lines and exactly these
 * summary lines:
 *   pos_rmse_mm X       root mean square position error over the records
 *                       after convergence (t >= converge_s), excluding each
 *                       kidnap's window [kidnap, recovery) (to the window's
 *                       close when it never recovers)
 *                       and the same window after the penalty placement
 *                       (the robot is told "one of the two touchline
 *                       spots"; until a landmark decides, its estimate is
 *                       either one: "# penalty_recover_s" gives the
 *                       window's length, and a "# every record" line the
 *                       RMSE with nothing excluded);
 *                       nan if no record qualifies
 *   heading_rmse_deg X  the same for the heading error (degrees)
 *   converge_s X        first time t from the start (total ignorance) such
 *                       that the error stays below 300 mm AND 15 degrees for
 *                       every record in [t, t + 1 s]; inf if never
 *   kidnap_recover_s X  per kidnap: the time from the kidnap to the first
 *                       t after it with the same 1 s criterion, the whole
 *                       second lying before the kidnap's window closes:
 *                       at the next penalty placement (a told reset: what
 *                       comes after it is not the filter recovering by
 *                       itself), the next kidnap or the end of the run;
 *                       inf ("never") otherwise.  The value is the median
 *                       over the run's kidnaps (with an even count the
 *                       mean of the two middle ones; one kidnap: its own
 *                       time); nan if the run has no kidnap.  Each kidnap
 *                       gets a line before the summary,
 *                         # kidnap K at T_S recovered after S s
 *                         # kidnap K at T_S never recovered before the
 *                           penalty placement at T | the next kidnap at T
 *                           | the run ended at T
 *                       and "# kidnap_recover_worst_s X" gives the largest
 *                       (inf when one never recovered)
 *   flips N             symmetric flips: episodes (counted once per entry)
 *                       during which the starting half is known and the
 *                       estimate is near the 180-degree mirror of the truth
 *                       (within 500 mm and 30 deg of (-x, -y, h + 180)) and
 *                       more than 1000 mm from the truth.  Only on symmetric
 *                       fields (spl2013, uva2013).
 * The "error" above: on a symmetric field, from a kidnap (the robot is told
 * nothing, so its half is unknown) until the next penalty placement (which
 * tells it the half again), the error is taken modulo the symmetry (the
 * smaller of the errors to the truth and to its mirror); otherwise it is the
 * plain error to the truth.
 */
#include "fieldloc/fieldloc.h"
#include "cli/args.h"
#include "loc/coachrun.h"
#include "loc/locrun.h"
#include "cli/registry.h"
#include "loc/stream.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The obs cache file exists and its header names another walk. */
static int cache_of_other_walk(const char *path, const char *walk)
{
    char line[160], name[64];
    FILE *f = fopen(path, "rb");
    int other = 0;
    if (f == NULL)
        return 0;
    if (fgets(line, sizeof line, f) != NULL &&
        sscanf(line, "fieldloc-obs-cache 1 %63s", name) == 1)
        other = strcmp(name, walk) != 0;
    fclose(f);
    return other;
}

static void usage(void)
{
    fprintf(stderr,
            "usage: fieldloc simulate --field spl2013|uva2013|aibo2004|spl2020|hl3x2 [--localizer fuzzy]\n"
            "                         --seed N [--features | --frames] [--steps N] [--quiet]\n"
            "                         [--scenario FILE.walk] [--every N] [--param NAME=V]...\n"
            "                         [--obs-cache FILE] [--print-obs] [--kidnaps N]\n"
            "                         [--export-stream FILE] [--colors default|auto|FILE]\n"
            "                         [--vision ltx|corners|both]\n"
            "  --vision: what feature mode observes: ltx (default) the L/T/X crossings, marks,\n"
            "            posts and beacons; corners seed 004's corner features and nets\n"
            "            (aibo2004); both the two sets.  Frames mode: the vision path run\n"
            "            on each frame (corners: seed 004's corner stage)\n"
            "  --frames: render each frame at the true pose and run the vision path;\n"
            "            vision on every Nth step (--every, default 3 = 10 Hz at 30 Hz)\n"
            "  --seed 0..2147483647, --steps 0..100000000, --every 1..1000, --post-sides 0|1,\n"
            "  --kidnaps 0..16 (default: the walk's own)\n"
            "  --export-stream FILE: the localizer's inputs and the truth (docs/STREAM.md;\n"
            "            fieldloc replay --stream FILE runs any localizer on them)\n"
            "  --colors: frames mode colour classes (default: auto on white-goal fields)\n"
            "       fieldloc simulate --coach [--localizer upf|mcl|fuzzy|relmap] [--seed N] [--runs N]\n"
            "                         [--features | --frames] [--every N] [--quiet]\n"
            "                         [--reseed once|spread] [--assign coach|player]\n"
            "                         [--coach-feet coach|truth] [--odocal on|off]\n"
            "  --coach: seed 003's experiments 1 and 2 (two players, a coach beside the\n"
            "           field; tools/loc/coachrun.h), runs seeds N..N+runs-1 (default 1, 20)\n"
            "  --reseed once (default): one correction at the end of the first leg (seed\n"
            "           003's protocol); spread: only when the belief spread beyond 500 mm\n"
            "  --assign coach (default): the coach numbers its reports against the players'\n"
            "           broadcast estimates; player: each takes its team's report nearest\n"
            "           its own estimate\n"
            "  --coach-feet truth: DEBUG ONLY, the coach reports the true feet\n"
            "  --odocal on: the coach also sees the players once a second on the first\n"
            "           leg; each calibrates its odometry's scale from that track\n"
            "           (odocal.h); exp2_err is then that variant's, seed 003's plain\n"
            "           correction on a '#' line\n");
}

/* `simulate --coach`: seed 003's two experiments (tools/loc/coachrun.h). */
static int simulate_coach(const char *localizer, long seed, long runs, int frames, long every,
                          int quiet, int truth_feet, int reseed_always, int player_side,
                          int odocal)
{
    cr_opts_t o;
    cr_result_t *res;
    char err[256];
    memset(&o, 0, sizeof o);
    if ((o.loc = lr_localizer(localizer != NULL ? localizer : "upf", err, (int)sizeof err)) ==
        NULL) {
        fprintf(stderr, "simulate: %s\n", err);
        return 2;
    }
    o.seed = (uint64_t)(seed >= 0 ? seed : 1);
    o.runs = (int)runs;
    o.frames = frames;
    o.every = (int)every;
    o.feet = truth_feet ? CR_FEET_TRUTH_DEBUG : CR_FEET_COACH;
    o.reseed_always = reseed_always;
    o.assign_player_side = player_side;
    o.odocal = odocal;
    o.log = quiet ? NULL : stdout;
    o.trace = getenv("FIELDLOC_COACH_TRACE") != NULL ? stdout : NULL;
    if ((res = malloc(sizeof *res)) == NULL) {
        fprintf(stderr, "simulate: out of memory\n");
        return 1;
    }
    printf("# simulate --coach localizer %s seeds %llu..%llu, players %s (vision every %d%s)\n",
           o.loc->name, (unsigned long long)o.seed,
           (unsigned long long)(o.seed + (uint64_t)o.runs - 1),
           frames ? "rendered frames -> vision" : "feature observations",
           frames ? o.every : 1, frames ? "" : ": every step");
    if (truth_feet)
        printf("# DEBUG: --coach-feet truth: the coach reports the TRUE feet; the coach_foot_* "
               "and exp2_* numbers below measure nothing of the coach's vision\n");
    fflush(stdout);
    if (cr_run(&o, res, err, (int)sizeof err) != 0) {
        fprintf(stderr, "simulate: %s\n", err);
        free(res);
        return 1;
    }
    cr_print_summary(stdout, res);
    free(res);
    return 0;
}

int cmd_simulate(int argc, char **argv)
{
    const char *field_name = NULL, *localizer = NULL, *scen_path = NULL;
    long seed = -1, max_steps = -1, every = 3;
    int frames = 0, quiet = 0, print_obs = 0, post_sides = 1, k;
    static sim_scenario_t sc;
    lr_walk_opts_t o;
    lr_walk_result_t res;
    char err[256];
    const char *obs_cache = NULL, *param[64], *stream_path = NULL;
    colors_opt_t colors;
    long kidnaps = -1, runs = 20;
    int vision = SIM_VISION_LTX;
    int coach = 0, truth_feet = 0, reseed_always = 1, player_side = 0, mode_given = 0, every_given = 0;
    int odocal = 0;
    FILE *stream = NULL;
    int n_param = 0;
    const fl_localizer_t *loc;
    void *params = NULL, *defaults = NULL;
    int rc;

    memset(&colors, 0, sizeof colors);
    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--field") && k + 1 < argc)
            field_name = argv[++k];
        else if (!strcmp(argv[k], "--colors") && k + 1 < argc) {
            /* frames mode: colour classes (eval/colors_opt.h), auto
             * estimated on the first frame and tracked on every one */
            if (colors_opt_parse("simulate", argv[++k], &colors) != 0)
                return 2;
        }
        else if (!strcmp(argv[k], "--localizer") && k + 1 < argc)
            localizer = argv[++k];
        else if (!strcmp(argv[k], "--seed") && k + 1 < argc) {
            if (arg_long("simulate", "--seed", argv[++k], 0, 2147483647L, NULL, &seed) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--steps") && k + 1 < argc) {
            if (arg_long("simulate", "--steps", argv[++k], 0, 100000000L, NULL, &max_steps))
                return 2;
        } else if (!strcmp(argv[k], "--every") && k + 1 < argc) {
            if (arg_long("simulate", "--every", argv[++k], 1, 1000, NULL, &every) != 0)
                return 2;
            every_given = 1;
        } else if (!strcmp(argv[k], "--param") && k + 1 < argc) {
            if (n_param < 64)
                param[n_param++] = argv[++k];
        } else if (!strcmp(argv[k], "--obs-cache") && k + 1 < argc)
            obs_cache = argv[++k];
        else if (!strcmp(argv[k], "--export-stream") && k + 1 < argc)
            stream_path = argv[++k];
        else if (!strcmp(argv[k], "--kidnaps") && k + 1 < argc) {
            if (arg_long("simulate", "--kidnaps", argv[++k], 0, SIM_MAX_EVENTS, NULL, &kidnaps))
                return 2;
        } else if (!strcmp(argv[k], "--scenario") && k + 1 < argc)
            scen_path = argv[++k];
        else if (!strcmp(argv[k], "--coach"))
            coach = 1;
        else if (!strcmp(argv[k], "--runs") && k + 1 < argc) {
            if (arg_long("simulate", "--runs", argv[++k], 1, CR_MAX_RUNS, NULL, &runs) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--reseed") && k + 1 < argc) {
            ++k;
            if (!strcmp(argv[k], "once") || !strcmp(argv[k], "spread"))
                reseed_always = !strcmp(argv[k], "once");
            else {
                fprintf(stderr, "simulate: --reseed once|spread\n");
                return 2;
            }
        } else if (!strcmp(argv[k], "--odocal") && k + 1 < argc) {
            ++k;
            if (!strcmp(argv[k], "on") || !strcmp(argv[k], "off"))
                odocal = !strcmp(argv[k], "on");
            else {
                fprintf(stderr, "simulate: --odocal on|off\n");
                return 2;
            }
        } else if (!strcmp(argv[k], "--assign") && k + 1 < argc) {
            ++k;
            if (!strcmp(argv[k], "coach") || !strcmp(argv[k], "player"))
                player_side = !strcmp(argv[k], "player");
            else {
                fprintf(stderr, "simulate: --assign coach|player\n");
                return 2;
            }
        } else if (!strcmp(argv[k], "--coach-feet") && k + 1 < argc) {
            ++k;
            if (!strcmp(argv[k], "truth"))
                truth_feet = 1;
            else if (!strcmp(argv[k], "coach"))
                truth_feet = 0;
            else {
                fprintf(stderr, "simulate: --coach-feet coach|truth\n");
                return 2;
            }
        } else if (!strcmp(argv[k], "--frames")) {
            frames = 1;
            mode_given = 1;
        } else if (!strcmp(argv[k], "--features")) {
            frames = 0;
            mode_given = 1;
        } else if (!strcmp(argv[k], "--vision") && k + 1 < argc) {
            ++k;
            if (!strcmp(argv[k], "ltx"))
                vision = SIM_VISION_LTX;
            else if (!strcmp(argv[k], "corners"))
                vision = SIM_VISION_CORNERS;
            else if (!strcmp(argv[k], "both"))
                vision = SIM_VISION_BOTH;
            else {
                fprintf(stderr, "simulate: --vision ltx|corners|both\n");
                return 2;
            }
        }
        else if (!strcmp(argv[k], "--quiet"))
            quiet = 1;
        else if (!strcmp(argv[k], "--print-obs"))
            print_obs = 1;
        else if (!strcmp(argv[k], "--post-sides") && k + 1 < argc) {
            if (arg_int("simulate", "--post-sides", argv[++k], 0, 1, NULL, &post_sides) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            usage();
            return 0;
        } else
            return arg_unknown("simulate", argv[k],
                               "--field=1 --localizer=1 --seed=1 --steps=1 --every=1 --param=1 "
                               "--obs-cache=1 --scenario=1 --post-sides=1 --export-stream=1 "
                               "--kidnaps=1 --colors=1 --runs=1 --coach-feet=1 --reseed=1 --assign=1 "
                               "--odocal=1 --vision=1");
    }
    if (coach)
        /* the players see through rendered frames and the vision path
         * unless --features; vision every 6th step (5 Hz) keeps 20 runs
         * at a few minutes */
        return simulate_coach(localizer, seed, runs, mode_given ? frames : 1,
                              every_given ? every : 6, quiet, truth_feet, reseed_always,
                              player_side, odocal);
    if (scen_path == NULL && field_name == NULL) {
        usage();
        return 2;
    }
    if ((loc = lr_localizer(localizer, err, (int)sizeof err)) == NULL) {
        fprintf(stderr, "simulate: %s\n", err);
        return 2;
    }
    params = lr_params_new(loc);
    defaults = lr_params_new(loc);
    if (params == NULL || defaults == NULL) {
        fprintf(stderr, "simulate: out of memory\n");
        free(params);
        free(defaults);
        return 1;
    }
    /* the localizer's parameters: the mode's base set, then --param */
    if (frames)
        lr_params_frames(loc, params);
    for (k = 0; k < n_param; k++) {
        if (lr_param_set(loc, params, param[k]) != 0) {
            fprintf(stderr, "simulate: bad --param '%s' (NAME=INTEGER, a parameter of "
                            "localizer %s, in range)\n", param[k], loc->name);
            free(params);
            free(defaults);
            return 2;
        }
    }
    if (scen_path != NULL) {
        if (sim_scenario_load(&sc, scen_path, err, (int)sizeof err) != 0) {
            fprintf(stderr, "simulate: %s: %s\n", scen_path, err);
            rc = 1;
            goto done;
        }
    } else if (sim_scenario_builtin(&sc, field_name) != 0) {
        fprintf(stderr, "simulate: no built-in walk for field '%s' (spl2013, uva2013, aibo2004, spl2020, hl3x2)\n",
                field_name);
        rc = 2;
        goto done;
    }
    if (seed >= 0)
        sc.seed = (uint64_t)seed;
    if (vision != SIM_VISION_LTX) {
        if (sc.field->features == NULL || sc.field->n_features == 0) {
            fprintf(stderr, "simulate: --vision %s: field %s has no corner features "
                            "(seed 004's, fl_field_t.features; aibo2004 has them)\n",
                    vision == SIM_VISION_BOTH ? "both" : "corners", sc.field->name);
            rc = 2;
            goto done;
        }
        sc.vision = vision;
    }
    if (kidnaps >= 0) {
        char was[SIM_NAME_LEN];
        memcpy(was, sc.name, sizeof was);
        if (sim_scenario_set_kidnaps(&sc, (int)kidnaps) != 0) {
            fprintf(stderr, "simulate: --kidnaps %ld does not fit the walk (at most %d events, "
                            "kidnaps at least 2 s apart and off the penalties)\n",
                    kidnaps, SIM_MAX_EVENTS);
            rc = 2;
            goto done;
        }
        if (strcmp(was, sc.name) != 0 && obs_cache != NULL && frames &&
            cache_of_other_walk(obs_cache, sc.name)) {
            /* it would be overwritten with this walk's observations */
            fprintf(stderr, "simulate: %s holds the observations of another walk; --kidnaps "
                            "changes the walk: give a cache file of its own\n", obs_cache);
            rc = 2;
            goto done;
        }
    }
    if (stream_path != NULL && (stream = fopen(stream_path, "w")) == NULL) {
        fprintf(stderr, "simulate: cannot write %s\n", stream_path);
        rc = 1;
        goto done;
    }
    memset(&o, 0, sizeof o);
    o.frames = frames;
    o.every = (int)every;
    o.max_steps = max_steps;
    o.steps = quiet ? NULL : stdout;
    o.print_obs = print_obs;
    o.ignore_post_sides = !post_sides;
    o.loc = loc;
    o.params = params;
    o.obs_cache = obs_cache;
    o.stream = stream;
    colors_opt_resolve(&colors, sc.field, NULL);
    o.colors = &colors;
    printf("# simulate field %s localizer %s seed %llu %s, %.0f s at %.0f Hz\n",
           sc.field->name, loc->name, (unsigned long long)sc.seed, frames ? "frames" : "features",
           sc.duration_s, sc.frame_hz);
    if (sc.vision != SIM_VISION_LTX)
        printf("# vision %s: seed 004's corner features (C, T-field, T-net, nets)%s\n",
               sc.vision == SIM_VISION_BOTH ? "both" : "corners",
               sc.vision == SIM_VISION_BOTH ? " and the L/T/X landmarks" : "");
    if (frames)
        printf("# frames: camera %s %dx%d rendered at the true pose, vision on every %ld%s step "
               "(%.1f Hz), odometry accumulated between; metrics over the vision steps\n",
               sc.camera->name, (int)sc.camera->width_px, (int)sc.camera->height_px, every,
               every == 1 ? "st" : every == 2 ? "nd" : every == 3 ? "rd" : "th",
               sc.frame_hz / (double)every);
    if (lr_param_diff(loc, params, defaults) != 0) {
        printf("# localizer params changed from fl_%s_params_default:", loc->name);
        lr_param_print(stdout, loc, params, defaults);
        printf("\n");
    }
    fflush(stdout);
    if (lr_walk_run(&sc, &o, &res, err, (int)sizeof err) != 0) {
        fprintf(stderr, "simulate: %s\n", err);
        rc = 1;
        goto done;
    }
    printf("# steps %ld (%.1f s), %ld records, rmse over %ld records\n", res.steps,
           (double)res.steps / sc.frame_hz, res.records, res.used);
    lr_walk_print_stats(stdout, &res);
    if (frames) {
        lr_walk_print_vdiag(stdout, &res);
        printf("# time: rendering %.1f s, vision + grid %.1f s (%.2f ms per frame)\n",
               res.render_s, res.vision_grid_s,
               res.records ? 1000.0 * res.vision_grid_s / (double)res.records : 0.0);
    }
    lr_walk_print_summary(stdout, &res);
    rc = 0;
done:
    if (stream != NULL && fclose(stream) != 0 && rc == 0) {
        fprintf(stderr, "simulate: error writing %s\n", stream_path);
        rc = 1;
    }
    free(params);
    free(defaults);
    return rc;
}
