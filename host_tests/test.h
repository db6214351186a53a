/*
 * host_tests/test.h - the tiny in-tree test harness.
 *
 * A test is a void function run by t_run(name, fn); it fails when any CHECK
 * inside it fails.  Output, one line per test:
 *     ok   suite.name
 *     FAIL suite.name   (followed by "  at file:line: expr" lines)
 * plus "digest NAME 0xXXXXXXXX" lines (hashes of firmware outputs, compared
 * across architectures by `make cross-test`) and "# ..." info lines
 * (measured errors etc.; ignored by the cross comparison because host
 * doubles may print differently on other targets).  The runner ends with
 * "N passed, N failed".
 *
 * t_quick is set by --quick (used under qemu): exhaustive sweeps run a
 * documented subset.  Outputs printed in quick mode must not depend on the
 * architecture.
 *
 * `-j N` (make test) runs the suites in N worker processes, so a suite must
 * not depend on another one (state, files): it may run alone, before or
 * after any other, or at the same time; its scratch files and folders are
 * its own.  The output keeps suites.h order.  --times prints the wall
 * time of every case on stderr.
 */
#ifndef FL_HOST_TEST_H
#define FL_HOST_TEST_H

#include <stdint.h>
#include <stddef.h>
#include <stdio.h>

extern int t_quick;
/* t_exhaustive is set by --exhaustive (`make test-exhaustive`): sweeps that
 * take minutes (every uint32 through isqrt, ...) run in full. */
extern int t_exhaustive;

typedef void (*t_fn)(void);
void t_run(const char *name, t_fn fn);
void t_check(int ok, const char *expr, const char *file, int line);
void t_fail_msg(const char *file, int line, const char *fmt, ...);
void t_info(const char *fmt, ...);
void t_digest(const char *label, uint32_t h);

/* FNV-1a, 32 bit, for digests.  Feed integers with t_hash_i32 so that the
 * hash does not depend on byte order. */
uint32_t t_hash_init(void);
uint32_t t_hash_i32(uint32_t h, int32_t v);
uint32_t t_hash_bytes(uint32_t h, const void *p, size_t n);

/* A golden file: its lines without comments ('#') and blank lines
 * (at most T_GOLDEN_LINES of up to T_GOLDEN_LINE_MAX - 1 characters);
 * t_golden_find gives the line whose first word is name, or NULL.  A
 * missing file loads as empty. */
#define T_GOLDEN_LINES 512
#define T_GOLDEN_LINE_MAX 160
typedef struct {
    char (*line)[T_GOLDEN_LINE_MAX];
    int n;
} t_golden_t;
void t_golden_load(t_golden_t *g, const char *path);
const char *t_golden_find(const t_golden_t *g, const char *name);
void t_golden_free(t_golden_t *g);

/* A golden file of one line per case ("NAME ..."), checked or rewritten:
 * t_golden_lines_begin loads path and, when FIELDLOC_WRITE_GOLDEN is set
 * (full mode only), opens it for writing with header (comment lines);
 * t_golden_lines_check writes got then, else compares it with the line of
 * name (a difference fails and names `build/run_tests -k rewrite_k`);
 * t_golden_lines_end closes and fails on cases without a line.  Counts:
 * n cases, same identical, missing without a line. */
typedef struct {
    t_golden_t gold;
    FILE *out;              /* non-NULL: rewriting */
    const char *path, *rewrite_k;
    int n, same, missing;
} t_golden_lines_t;
void t_golden_lines_begin(t_golden_lines_t *g, const char *path, const char *header,
                          const char *rewrite_k);
void t_golden_lines_check(t_golden_lines_t *g, const char *name, const char *got);
void t_golden_lines_end(t_golden_lines_t *g);

/* Deterministic PRNG (xorshift64*), identical on every target. */
typedef struct { uint64_t s; } t_rng_t;
void t_rng_seed(t_rng_t *r, uint64_t seed);
uint32_t t_rng_u32(t_rng_t *r);
int32_t t_rng_range(t_rng_t *r, int32_t lo, int32_t hi); /* inclusive */

/* A whole file, NUL-terminated, malloc'd (free it); *len = its size.
 * NULL when it cannot be read. */
char *t_read_file(const char *path, size_t *len);

/* Path of the shared real-data folder (../shared/realdata relative to the
 * repository, or $FIELDLOC_REALDATA), or NULL when absent. */
const char *t_realdata_dir(void);

#define CHECK(c) t_check(!!(c), #c, __FILE__, __LINE__)
#define CHECK_EQ(a, b)                                                      \
    do {                                                                    \
        long long t_a_ = (long long)(a), t_b_ = (long long)(b);             \
        if (t_a_ != t_b_)                                                   \
            t_fail_msg(__FILE__, __LINE__, "%s == %s (%lld != %lld)", #a,   \
                       #b, t_a_, t_b_);                                     \
        else                                                                \
            t_check(1, #a, __FILE__, __LINE__);                             \
    } while (0)
#define CHECK_LE(a, b)                                                      \
    do {                                                                    \
        double t_a_ = (double)(a), t_b_ = (double)(b);                      \
        if (!(t_a_ <= t_b_))                                                \
            t_fail_msg(__FILE__, __LINE__, "%s <= %s (%g > %g)", #a, #b,    \
                       t_a_, t_b_);                                         \
        else                                                                \
            t_check(1, #a, __FILE__, __LINE__);                             \
    } while (0)

/* Suites: one per host_tests/test_<stage>.c, listed in suites.h. */
#define T_SUITE(name) void suite_##name(void) __attribute__((weak))
#include "suites.h"

#endif
