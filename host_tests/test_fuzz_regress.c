/*
 * host_tests/test_fuzz_regress.c - every input that crashed a fuzz harness
 * (make fuzz-smoke), replayed through the same code as a named test.  The
 * inputs live in host_tests/fuzz/regress/HARNESS/; under `make sanitize`
 * these tests also prove the undefined behaviour is gone.
 */
#include "test.h"
#include "io/realdata.h"
#include "world/sim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* fuzz_uva_csv found: a number like 17777777777777777777777777777777777 in
 * an integer column was converted to int (undefined).  The parser must
 * reject the row with a message instead. */
static void test_uva_csv_huge_number(void)
{
    static const char *files[] = {"host_tests/fuzz/regress/uva_csv/huge_number_1.csv"};
    size_t i, n;
    for (i = 0; i < sizeof files / sizeof files[0]; i++) {
        char err[256] = "";
        rd_uva_set_t set;
        char *text = t_read_file(files[i], &n);
        CHECK(text != NULL);
        if (!text)
            continue;
        CHECK(rd_uva_parse(text, &set, err, sizeof err) != 0);
        CHECK(strstr(err, "bad number in column in_realdata") != NULL);
        free(text);
    }
    /* and the smallest form of it */
    {
        const char *row = "file,in_realdata,set,index,x_cm,y_cm,theta_deg,head_pitch_rad,"
                          "head_yaw_rad,n_features,features\n"
                          "a.ppm,17777777777777777777777777777777777,qvga,1,0,0,0,0,0,0,\"\"\n";
        char err[256] = "";
        rd_uva_set_t set;
        CHECK(rd_uva_parse(row, &set, err, sizeof err) != 0);
        CHECK(strstr(err, "bad number") != NULL);
    }
}

/* fuzz_walk found: a walk whose start heading was 7.8e37 deg passed the
 * scenario check, and sim_init's angle wrap converted 2e38 to long long
 * (undefined).  The check must refuse start and kidnap poses beyond
 * +-20000 mm / +-360 deg, naming the key. */
static void test_walk_huge_start_heading(void)
{
    static sim_scenario_t sc;
    char err[256] = "";
    size_t n;
    char *text = t_read_file("host_tests/fuzz/regress/walk/huge_start_heading_1.walk", &n);
    CHECK(text != NULL);
    if (!text)
        return;
    CHECK(sim_scenario_parse(&sc, text, err, sizeof err) != 0);
    CHECK(strstr(err, "start outside") != NULL);
    free(text);
}

void suite_fuzz_regress(void)
{
    t_run("fuzz_regress.walk_huge_start_heading", test_walk_huge_start_heading);
    t_run("fuzz_regress.uva_csv_huge_number", test_uva_csv_huge_number);
}
