/*
 * tools/cli/cmd_eval_relmap.c - `fieldloc eval-relmap [--seed N] [--poses N]
 * [--frames N] [--localizer NAME] [--verbose]`: seed 002's table I poses
 * and random poses on hl3x2, rendered, through seed 002's vision path and
 * a localizer from ignorance (tools/eval/eval_relmap.h says how each number
 * is measured).  Ends with the summary lines table1_max_pos_err_mm,
 * table1_max_heading_err_deg, median_pos_err_mm, median_heading_err_deg,
 * wrong_side_pct, frame_ms.
 */
#include "cli/args.h"
#include "cli/registry.h"
#include "eval/eval_relmap.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

static int erm_usage(int rc)
{
    fprintf(rc ? stderr : stdout,
            "usage: fieldloc eval-relmap [--seed N] [--poses N] [--frames N] [--localizer NAME]\n"
            "                            [--param NAME=VALUE]... [--verbose]\n"
            "  seed 002's table I poses and N random poses (default 200, 0..100000) with at\n"
            "  least two landmarks in view on field hl3x2, each rendered (camera acyut-640),\n"
            "  seen by seed 002's vision path and localized from ignorance over --frames\n"
            "  frames (default 3, 1..100) of the robot standing still; --localizer (default\n"
            "  relmap) any catalogue localizer.  Ends with table1_max_pos_err_mm,\n"
            "  table1_max_heading_err_deg, median_pos_err_mm, median_heading_err_deg,\n"
            "  wrong_side_pct, frame_ms (vision + localizer per frame, host).  --param\n"
            "  (up to 16) sets a parameter of the localizer by name, as in simulate.\n");
    return rc;
}

int cmd_eval_relmap(int argc, char **argv)
{
    er_opts_t o;
    er_result_t r;
    int i;
    memset(&o, 0, sizeof o);
    o.seed = 1;
    o.poses = 200;
    o.frames = 3;
    o.localizer = "relmap";
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return erm_usage(0);
        if (!strcmp(argv[i], "--seed") && i + 1 < argc) {
            if (arg_u32("eval-relmap", "--seed", argv[++i], &o.seed))
                return 2;
        } else if (!strcmp(argv[i], "--poses") && i + 1 < argc) {
            if (arg_int("eval-relmap", "--poses", argv[++i], 0, 100000, NULL, &o.poses))
                return 2;
        } else if (!strcmp(argv[i], "--frames") && i + 1 < argc) {
            if (arg_int("eval-relmap", "--frames", argv[++i], 1, 100, NULL, &o.frames))
                return 2;
        } else if (!strcmp(argv[i], "--localizer") && i + 1 < argc) {
            o.localizer = argv[++i];
        } else if (!strcmp(argv[i], "--param") && i + 1 < argc) {
            const char *a = argv[++i], *eq = strchr(a, '=');
            long v;
            if (o.n_param >= 16 || eq == NULL || eq == a || (size_t)(eq - a) >= sizeof o.param_name[0] ||
                arg_long("eval-relmap", "--param", eq + 1, INT32_MIN, INT32_MAX, NULL, &v)) {
                fprintf(stderr, "eval-relmap: --param wants NAME=VALUE (at most 16): %s\n", a);
                return 2;
            }
            memcpy(o.param_name[o.n_param], a, (size_t)(eq - a));
            o.param_name[o.n_param][eq - a] = '\0';
            o.param_value[o.n_param++] = (int32_t)v;
        } else if (!strcmp(argv[i], "--verbose")) {
            o.verbose = 1;
        } else {
            return arg_unknown("eval-relmap", argv[i], NULL);
        }
    }
    if (er_run(&o, stdout, &r) != 0)
        return 1;
    er_print_summary(stdout, &r);
    return 0;
}
