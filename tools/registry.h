/*
 * tools/registry.h - the CLI's subcommands and the benchmark sections, each
 * implemented in its own tools/ file.  Weak declarations: a missing
 * implementation shows as "not built" instead of breaking the link.
 */
#ifndef FL_TOOLS_REGISTRY_H
#define FL_TOOLS_REGISTRY_H

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
    X(scan, "IMAGE.ppm [--picture OUT.ppm]: column scanner")                  \
    X(detect, "[--field F] [--camera C] [--head P Y] IMAGE.ppm: features")    \
    X(eval_detect, "score detections against ground truth")                   \
    X(simulate, "--field F --localizer fuzzy --seed N: simulated walk")       \
    X(localize, "SEQUENCE.txt: localize a frame sequence")                    \
    X(demo, "the bundled walk, with pictures")                                \
    X(bench, "[--out FILE.tsv]: benchmarks")

#define FL_DECL_CMD(name, help) int cmd_##name(int argc, char **argv) FL_WEAK;
FL_COMMANDS(FL_DECL_CMD)

/* Benchmark sections: void bench_NAME(bench_ctx_t *), each appends rows. */
typedef struct {
    FILE *tsv;             /* rows: name<TAB>fieldloc_ns<TAB>peer_ns<TAB>speedup */
    int quick;             /* fewer repetitions */
} bench_ctx_t;

/* Record one row (also printed to stdout); peer_ns <= 0 means "no peer". */
void bench_row(bench_ctx_t *ctx, const char *name, double fl_ns, double peer_ns,
               const char *peer_desc);
double bench_now_ns(void);

/* Write the vision section's noise frames to DIR (0 = ok). */
int bench_vision_write_noise(const char *dir) FL_WEAK;
int bench_scan_write_noise(const char *dir) FL_WEAK;

#define FL_BENCHES(X) X(fixed) X(scan) X(vision) X(adversarial) X(fuzzy)
#define FL_DECL_BENCH(name) void bench_##name(bench_ctx_t *ctx) FL_WEAK;
FL_BENCHES(FL_DECL_BENCH)

#endif
