/*
 * tools/cli/cmd_walk004.c - `fieldloc walk004 [--features] [--out DIR]
 * [--pose X Y DEG] [--scan LEFT RIGHT STEP] [--pitch DEG] [--seed N]
 * [--whole-scan] [--verbose]`: seed 004's walk-through (its section 5, figures 6-7) on
 * aibo2004: the goal keeper from total ignorance fuses the yellow net and
 * two C corners as its head scans (tools/eval/walk004.h says how).  Ends
 * with the summary lines walk004_error_mm, walk004_heading_err_deg,
 * walk004_observations, walk004_reliability, walk004_p_true.
 */
#include "cli/args.h"
#include "cli/registry.h"
#include "eval/walk004.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static int w4_usage(int rc)
{
    fprintf(rc ? stderr : stdout,
            "usage: fieldloc walk004 [--features] [--out DIR] [--pose X_MM Y_MM HEADING_DEG]\n"
            "                        [--scan LEFT_DEG RIGHT_DEG STEP_DEG] [--pitch DEG]\n"
            "                        [--seed N] [--whole-scan] [--verbose]\n"
            "  seed 004's walk-through on field aibo2004 (camera aibo-ers7): the goal keeper\n"
            "  in its own box (default pose -1800 -100 10), facing the yellow net, starts\n"
            "  from total ignorance and scans its head (straight ahead, then 60 to -60 deg\n"
            "  in 10 deg steps, pitch 0); each new net or C corner it perceives is fused\n"
            "  into the fuzzy grid at once, until a net and two C's.  After each: the\n"
            "  observation, the estimate, its error, reliability, the area of the top\n"
            "  region (cells >= 0.9) and of the cells >= 1/2, the possibility of the true\n"
            "  pose.  Default: rendered frames through the corner stage; --features:\n"
            "  exact observations of the map features in view.  --out DIR: per step the\n"
            "  belief (darker = more possible) and the camera frame with the detections,\n"
            "  as PNG.  --verbose: every frame's observations and corner pairs (with --out,\n"
            "  every frame's picture).  --whole-scan: every frame of the scan is looked at\n"
            "  (fusion still stops after a net and two C's), for the counts of the map's\n"
            "  C's the corner stage reported.\n");
    return rc;
}

/* The folder and its missing parents (mkdir -p).  0 when it exists. */
static int w4_mkdirs(const char *dir)
{
    char p[1024];
    size_t k, n = strlen(dir);
    struct stat st;
    if (n == 0 || n >= sizeof p)
        return -1;
    memcpy(p, dir, n + 1);
    for (k = 1; k <= n; k++)
        if (p[k] == '/' || p[k] == '\0') {
            char c = p[k];
            p[k] = '\0';
            (void)mkdir(p, 0777);
            p[k] = c;
        }
    return stat(dir, &st) == 0 && S_ISDIR(st.st_mode) ? 0 : -1;
}

int cmd_walk004(int argc, char **argv)
{
    w4_opts_t o;
    w4_result_t r;
    int i;
    w4_opts_default(&o);
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return w4_usage(0);
        if (!strcmp(argv[i], "--features")) {
            o.features = 1;
        } else if (!strcmp(argv[i], "--whole-scan")) {
            o.whole_scan = 1;
        } else if (!strcmp(argv[i], "--verbose")) {
            o.verbose = 1;
        } else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
            o.out_dir = argv[++i];
        } else if (!strcmp(argv[i], "--seed") && i + 1 < argc) {
            if (arg_u32("walk004", "--seed", argv[++i], &o.seed))
                return 2;
        } else if (!strcmp(argv[i], "--pose") && i + 3 < argc) {
            double h;
            if (arg_int32("walk004", "--pose x", argv[i + 1], -2250, 2250, "mm", &o.x_mm) ||
                arg_int32("walk004", "--pose y", argv[i + 2], -1500, 1500, "mm", &o.y_mm) ||
                arg_double("walk004", "--pose heading", argv[i + 3], -180, 180, "deg", &h))
                return 2;
            o.heading_mdeg = (int32_t)lround(h * 1000);
            i += 3;
        } else if (!strcmp(argv[i], "--scan") && i + 3 < argc) {
            double a, b, s;
            if (arg_double("walk004", "--scan left", argv[i + 1], -120, 120, "deg", &a) ||
                arg_double("walk004", "--scan right", argv[i + 2], -120, 120, "deg", &b) ||
                arg_double("walk004", "--scan step", argv[i + 3], 1, 90, "deg", &s))
                return 2;
            if (b > a) {
                fprintf(stderr,
                        "fieldloc walk004: --scan goes left to right: LEFT_DEG >= RIGHT_DEG\n");
                return 2;
            }
            o.yaw_left_mdeg = (int32_t)lround(a * 1000);
            o.yaw_right_mdeg = (int32_t)lround(b * 1000);
            o.yaw_step_mdeg = (int32_t)lround(s * 1000);
            i += 3;
        } else if (!strcmp(argv[i], "--pitch") && i + 1 < argc) {
            double p;
            if (arg_double("walk004", "--pitch", argv[++i], -30, 60, "deg", &p))
                return 2;
            o.pitch_mdeg = (int32_t)lround(p * 1000);
        } else {
            return arg_unknown("walk004", argv[i], "--out=1 --seed=1 --pose=3 --scan=3 --pitch=1");
        }
    }
    if (o.out_dir != NULL && w4_mkdirs(o.out_dir) != 0) {
        fprintf(stderr, "fieldloc walk004: cannot create %s\n", o.out_dir);
        return 1;
    }
    if (w4_run(&o, stdout, &r) != 0)
        return 1;
    w4_print_summary(stdout, &o, &r);
    return 0;
}
