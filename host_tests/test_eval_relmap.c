/*
 * host_tests/test_eval_relmap.c - seed 002's evaluation (eval/eval_relmap.h,
 * `fieldloc eval-relmap`) on a few poses: it runs, keeps only poses with
 * two landmarks in view, localizes the table I poses within a metre from
 * ignorance, prints the summary lines, and repeats itself exactly.
 */
#include "test.h"
#include "eval/eval_relmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Runs the evaluation into a string (the summary lines appended). */
static int run(const er_opts_t *o, er_result_t *r, char *buf, size_t n)
{
    FILE *f = tmpfile();
    size_t got;
    int rc;
    if (f == NULL)
        return -1;
    rc = er_run(o, f, r);
    if (rc == 0)
        er_print_summary(f, r);
    rewind(f);
    got = fread(buf, 1, n - 1, f);
    buf[got] = '\0';
    fclose(f);
    return rc;
}

/* The lines of a run without the time line (the only one that may differ). */
static void drop_time(char *s)
{
    char *t = strstr(s, "# time:");
    if (t != NULL)
        *t = '\0';
}

static void test_runs(void)
{
    static char a[1 << 14], b[1 << 14];
    er_opts_t o;
    er_result_t r, r2;
    memset(&o, 0, sizeof o);
    o.seed = 3;
    o.poses = 4;
    o.frames = 1;
    o.localizer = "relmap";
    CHECK_EQ(run(&o, &r, a, sizeof a), 0);
    CHECK_EQ(r.kept, 4);
    CHECK(r.drawn >= 4);
    CHECK_EQ(r.frames_run, 3 + 4);
    /* from ignorance, one frame of each table I pose: within a metre */
    CHECK(r.table1_max_pos_mm < 1000.0);
    CHECK(r.table1_max_head_deg <= 180.0);
    CHECK(isfinite(r.median_pos_mm) && r.median_pos_mm >= 0.0);
    CHECK(r.wrong_side_pct >= 0.0 && r.wrong_side_pct <= 100.0);
    CHECK(r.frame_ms > 0.0);
    CHECK(strstr(a, "\ntable1_max_pos_err_mm ") != NULL);
    CHECK(strstr(a, "\ntable1_max_heading_err_deg ") != NULL);
    CHECK(strstr(a, "\nmedian_pos_err_mm ") != NULL);
    CHECK(strstr(a, "\nmedian_heading_err_deg ") != NULL);
    CHECK(strstr(a, "\nwrong_side_pct ") != NULL);
    CHECK(strstr(a, "\nframe_ms ") != NULL);
    CHECK(strstr(a, "# 2(a)") != NULL && strstr(a, "# 2(c)") != NULL);
    /* the same seed gives the same poses and estimates (not under --quick:
     * the emulated and instrumented runs render slowly) */
    if (!t_quick) {
        CHECK_EQ(run(&o, &r2, b, sizeof b), 0);
        drop_time(a);
        drop_time(b);
        CHECK(strcmp(a, b) == 0);
        CHECK(r.median_pos_mm == r2.median_pos_mm);
    }
    /* any catalogue localizer; an unknown one is refused */
    o.poses = 0;
    o.localizer = "mcl";
    CHECK_EQ(run(&o, &r, a, sizeof a), 0);
    CHECK_EQ(r.frames_run, 3);
    o.localizer = "nosuch";
    CHECK(run(&o, &r, a, sizeof a) != 0);
    o.localizer = "relmap";
    o.frames = 0;
    CHECK(run(&o, &r, a, sizeof a) != 0);
}

void suite_eval_relmap(void)
{
    t_run("eval_relmap.runs", test_runs);
}
