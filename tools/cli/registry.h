/*
 * tools/cli/registry.h - the CLI's subcommands, each implemented in its own
 * tools/cli/cmd_NAME.c (the benchmark sections: bench/bench.h).  Weak declarations: a missing
 * implementation shows as "not built" instead of breaking the link.
 */
#ifndef FL_TOOLS_REGISTRY_H
#define FL_TOOLS_REGISTRY_H

#include "bench/bench.h"

#include <stdio.h>

#define FL_WEAK __attribute__((weak))

/* Subcommands: int cmd_NAME(int argc, char **argv), argv[0] = first argument
 * after the command name.  Return the process exit status. */
#define FL_COMMANDS(X)                                                        \
    X(fields, "list the field models")                                        \
    X(cameras, "list the camera models")                                      \
    X(project, "[--camera NAME] [--neck MM] [--head PITCH_RAD YAW_RAD] U V: pixel -> ground") \
    X(sizes, "static memory of every firmware state struct (sizeof)")          \
    X(render, "render one frame of the synthetic world (see --help)")        \
    X(fixtures, "regenerate the fixture set (make fixtures)")                \
    X(calibrate, "fit the UvA 2013 camera to the hand labels")                \
    X(colors, "[--out FILE]: the default colour file, commented (edit; --colors)") \
    X(calibrate_colors, "IMAGE... [--field F] [--camera C --head P Y] --out FILE: colour file from frames") \
    X(scan, "IMAGE.ppm [--picture OUT.ppm]: column scanner")                  \
    X(detect, "[--field F] [--camera C] [--head P Y] IMAGE.ppm: features")    \
    X(eval_detect, "score detections against ground truth")                   \
    X(simulate, "--field F --localizer fuzzy --seed N: simulated walk")       \
    X(localize, "SEQUENCE.txt: localize a frame sequence")                    \
    X(replay, "--stream FILE [--localizer NAME]: a localizer on an input stream") \
    X(reliability, "reliability diagram and calibration check (held-out walks)") \
    X(demo, "the bundled walk, with pictures")                                \
    X(coach, "IMAGE.ppm --points FILE [--background EMPTY.ppm] [--out PIC.png]: the coach's feet") \
    X(bench, "[--out FILE.tsv]: benchmarks")                                  \
    X(ukf_check, "[--n N] [--seed S]: the fixed-point UKF step against double") \
    X(eval_relmap, "[--seed N] [--poses N] [--localizer L]: seed 002's table I and random poses on hl3x2") \
    X(walk004, "[--features] [--out DIR]: seed 004's goal keeper localizing from ignorance (net, two C's)")

#define FL_DECL_CMD(name, help) int cmd_##name(int argc, char **argv) FL_WEAK;
FL_COMMANDS(FL_DECL_CMD)

#endif
