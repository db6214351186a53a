/*
 * tools/bench/bench.h - the benchmark sections of `fieldloc bench`, one
 * tools/bench/bench_NAME.c each, and the row writer they share.  Weak
 * declarations: a section that is not built shows as "not built".
 */
#ifndef FL_TOOLS_BENCH_H
#define FL_TOOLS_BENCH_H

#include <stdio.h>

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
int bench_vision_write_noise(const char *dir) __attribute__((weak));
int bench_scan_write_noise(const char *dir) __attribute__((weak));

/* bench_loc.c: the catalogue's names, one per line; and N frames of one
 * localizer after the walk (callgrind_loc.sh collects bench_loc_frame)
 * with params "NAME=VALUE" (after the vision preset when vision) and k_obs
 * observations (and a view when vision); prints a "loc NAME state_size B
 * samples P obs K frames N [vision]" line.  0 on success. */
int bench_loc_list(void) __attribute__((weak));
int bench_loc_repeat(const char *name, const char *const *param, int n_param, long repeat,
                     int k_obs, int vision) __attribute__((weak));

#define FL_BENCHES(X) X(fixed) X(scan) X(vision) X(skeleton) X(hlvision) X(corners) X(adversarial) X(fuzzy) X(loc) X(coach)
#define FL_DECL_BENCH(name) void bench_##name(bench_ctx_t *ctx) __attribute__((weak));
FL_BENCHES(FL_DECL_BENCH)

#endif
