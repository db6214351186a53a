/*
 * tools/cli/cmd_replay.c - `fieldloc replay`: any catalogue localizer on a
 * localizer input stream (docs/STREAM.md; written by `fieldloc simulate
 * --export-stream FILE`).
 *
 *   fieldloc replay --stream FILE [--localizer NAME] [--param NAME=V]...
 *                   [--quiet] [--print-obs]
 *
 * The localizer (default fuzzy) gets the stream's calls in file order and
 * nothing else: set_prior_half (header prior_half), then per record its
 * predict, reset_penalty and update calls with the integers written, then
 * estimate.  Parameters: the localizer's defaults for a features stream,
 * lr_params_frames for a frames stream (as simulate chooses them), then
 * --param NAME=VALUE, then params_adapt for the stream's camera (lr_init).
 *
 * Output: a "# replay ..." header, per record (unless --quiet) the step
 * line of `fieldloc simulate` (and with --print-obs its "#  obs" lines),
 * then "# records", the "# localizer:" counters and the summary lines of
 * simulate (the kidnap lines, penalty_recover_s, every record, pos_rmse_mm
 * ... flips; definitions in tools/cli/cmd_simulate.c, computed from the
 * stream's truth and events).  Replaying a stream with the localizer and
 * parameters of the simulate run that wrote it prints the same step and
 * summary lines, byte for byte.  Not printed: simulate's vision diagnosis
 * and times (the stream has no images).
 *
 * Errors: a stream that cannot be read or does not parse ("replay:
 * FILE: line N: reason"), an unknown localizer or a bad --param:
 * nothing on stdout, exit status 2.
 */
#include "fieldloc/fieldloc.h"
#include "cli/args.h"
#include "cli/registry.h"
#include "loc/locrun.h"
#include "loc/stream.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(void)
{
    fprintf(stderr,
            "usage: fieldloc replay --stream FILE [--localizer NAME] [--param NAME=V]...\n"
            "                       [--quiet] [--print-obs]\n"
            "  runs the localizer on a stream of `simulate --export-stream` (docs/STREAM.md)\n"
            "  and prints simulate's step and summary lines\n");
}

int cmd_replay(int argc, char **argv)
{
    const char *path = NULL, *localizer = NULL, *param[64];
    int n_param = 0, quiet = 0, print_obs = 0, k, rc = 2;
    const fl_localizer_t *loc;
    void *params = NULL, *defaults = NULL;
    ls_stream_t s;
    lr_walk_result_t res;
    char err[512];

    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--stream") && k + 1 < argc)
            path = argv[++k];
        else if (!strcmp(argv[k], "--localizer") && k + 1 < argc)
            localizer = argv[++k];
        else if (!strcmp(argv[k], "--param") && k + 1 < argc) {
            if (n_param < 64)
                param[n_param++] = argv[++k];
        } else if (!strcmp(argv[k], "--quiet"))
            quiet = 1;
        else if (!strcmp(argv[k], "--print-obs"))
            print_obs = 1;
        else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            usage();
            return 0;
        } else
            return arg_unknown("replay", argv[k], "--stream=1 --localizer=1 --param=1");
    }
    if (path == NULL) {
        usage();
        return 2;
    }
    if ((loc = lr_localizer(localizer, err, (int)sizeof err)) == NULL) {
        fprintf(stderr, "replay: %s\n", err);
        return 2;
    }
    if (ls_load(path, &s, err, (int)sizeof err) != 0) {
        fprintf(stderr, "replay: %s\n", err);
        return 2;
    }
    params = lr_params_new(loc);
    defaults = lr_params_new(loc);
    if (params == NULL || defaults == NULL) {
        fprintf(stderr, "replay: out of memory\n");
        rc = 1;
        goto done;
    }
    if (s.frames)
        lr_params_frames(loc, params);
    for (k = 0; k < n_param; k++) {
        if (lr_param_set(loc, params, param[k]) != 0) {
            fprintf(stderr, "replay: bad --param '%s' (NAME=INTEGER, a parameter of "
                            "localizer %s, in range)\n", param[k], loc->name);
            rc = 2;
            goto done;
        }
    }
    printf("# replay %s: field %s camera %s scenario %s seed %llu %s every %d, localizer %s, "
           "%ld records\n",
           path, s.field->name, s.camera->name, s.scenario[0] ? s.scenario : "-",
           (unsigned long long)s.seed, s.frames ? "frames" : "features", s.every, loc->name,
           s.n_rec);
    if (lr_param_diff(loc, params, defaults) != 0) {
        printf("# localizer params changed from fl_%s_params_default:", loc->name);
        lr_param_print(stdout, loc, params, defaults);
        printf("\n");
    }
    fflush(stdout);
    if (ls_replay(&s, loc, params, quiet ? NULL : stdout, print_obs, &res, err,
                  (int)sizeof err) != 0) {
        fprintf(stderr, "replay: %s\n", err);
        rc = 1;
        goto done;
    }
    printf("# records %ld, rmse over %ld records\n", res.records, res.used);
    lr_walk_print_stats(stdout, &res);
    lr_walk_print_summary(stdout, &res);
    rc = 0;
done:
    ls_free(&s);
    free(params);
    free(defaults);
    return rc;
}
