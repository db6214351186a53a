/*
 * host_tests/test_odocal.c - odometry scale calibration from an observer's
 * track (fieldloc/odocal.h): a side-stepping and a forward walk with known
 * systematic scale errors and noisy reports recover the gains; a wrong
 * report is gated out; an axis without motion keeps gain 1; the
 * correction's rounding carry keeps the corrected sum exact; bad input.
 */
#include "test.h"
#include "fieldloc/odocal.h"

#include <math.h>
#include <stdlib.h>

/* Deterministic report noise in [-amp, amp] mm. */
static int32_t od_noise(uint32_t *s, int32_t amp)
{
    *s = *s * 1664525u + 1013904223u;
    return (int32_t)((*s >> 8) % (uint32_t)(2 * amp + 1)) - amp;
}

/* Walks n steps of (tx, ty) mm (true, body frame) with a fixed field
 * heading head_deg, odometry = true * (1 + s), a report every 40 steps.
 * bad_fix >= 0: that sighting reports a point 3 m away (another robot). */
static void od_walk(fl_odocal_t *c, double tx, double ty, double head_deg, double sx,
                    double sy, int n, int32_t noise, int bad_fix)
{
    double x = 1000, y = -2500, cx = 0, cy = 0, h = head_deg * M_PI / 180;
    uint32_t seed = 7;
    int k, fix = 0;
    fl_odocal_init(c);
    for (k = 0; k <= n; k++) {
        if (k % 40 == 0) {
            int32_t rx = (int32_t)lround(x) + od_noise(&seed, noise);
            int32_t ry = (int32_t)lround(y) + od_noise(&seed, noise);
            if (fix == bad_fix)
                ry += 3000;
            CHECK_EQ(fl_odocal_fix(c, rx, ry), FL_OK);
            fix++;
        }
        if (k == n)
            break;
        {
            double ox = tx * (1 + sx) + cx, oy = ty * (1 + sy) + cy;
            int32_t ix = (int32_t)lround(ox), iy = (int32_t)lround(oy);
            cx = ox - ix;
            cy = oy - iy;
            CHECK_EQ(fl_odocal_odometry(c, ix, iy, 0), FL_OK);
        }
        x += tx * cos(h) - ty * sin(h);
        y += tx * sin(h) + ty * cos(h);
    }
}

static void test_sidestep(void)
{
    fl_odocal_t c;
    /* 2.5 m side-step in 500 steps of 5 mm, 13 reports +-80 mm */
    od_walk(&c, 0, 5, -90, 0.08, 0.15, 500, 80, -1);
    CHECK_EQ(c.n_fixes, 13);
    CHECK_EQ(fl_odocal_solve(&c), FL_OK);
    CHECK(c.pairs[1] >= 20);
    CHECK_EQ(c.pairs[0], 0);
    CHECK_EQ(c.gain_q16[0], FL_ODOCAL_ONE_Q16);     /* no x motion: untouched */
    /* 1 / 1.15 = 0.8696; measured 0.021 off (the reports' noise) */
    CHECK_LE(fabs(c.gain_q16[1] / 65536.0 - 1 / 1.15), 0.03);
    /* without noise: within 0.3 % */
    od_walk(&c, 0, 5, -90, 0.08, 0.15, 500, 0, -1);
    fl_odocal_solve(&c);
    CHECK_LE(fabs(c.gain_q16[1] / 65536.0 - 1 / 1.15), 0.003);
    /* a shrinking odometry (s = -0.1) */
    od_walk(&c, 0, -5, 30, 0, -0.10, 500, 0, -1);
    fl_odocal_solve(&c);
    CHECK_LE(fabs(c.gain_q16[1] / 65536.0 - 1 / 0.9), 0.003);
}

static void test_forward_turned(void)
{
    fl_odocal_t c;
    int k;
    /* forward 3 m at a field heading of 120 deg: the x axis */
    od_walk(&c, 6, 0, 120, 0.10, 0.15, 500, 50, -1);
    fl_odocal_solve(&c);
    CHECK_EQ(c.gain_q16[1], FL_ODOCAL_ONE_Q16);
    CHECK_LE(fabs(c.gain_q16[0] / 65536.0 - 1 / 1.10), 0.02);
    /* a turn in the odometry between sightings: the body-x motion is
     * summed as a vector, so a quarter turn halfway does not shorten it */
    fl_odocal_init(&c);
    CHECK_EQ(fl_odocal_fix(&c, 0, 0), FL_OK);
    for (k = 0; k < 200; k++)
        fl_odocal_odometry(&c, 11, 0, 0);
    fl_odocal_odometry(&c, 0, 0, fl_angle_from_mdeg(90000));
    fl_odocal_fix(&c, 2000, 0);
    for (k = 0; k < 200; k++)
        fl_odocal_odometry(&c, 11, 0, 0);
    fl_odocal_fix(&c, 2000, 2000);
    fl_odocal_fix(&c, 2000, 2000);
    CHECK_EQ(c.fix[2].px_x_mm, 2200);
    CHECK_EQ(c.fix[2].px_y_mm, 2200);
    fl_odocal_solve(&c);
    /* pairs (0,1), (1,2), (0,2), (0,3), (1,3): gain 1 / 1.1 each */
    CHECK_EQ(c.pairs[0], 5);
    CHECK_LE(fabs(c.gain_q16[0] / 65536.0 - 1 / 1.1), 0.003);
}

static void test_gate_and_bounds(void)
{
    fl_odocal_t c;
    /* sighting 6 is another robot's foot 3 m away: its pairs are gated */
    od_walk(&c, 0, 5, -90, 0.08, 0.15, 500, 80, 6);
    fl_odocal_solve(&c);
    CHECK(c.pairs_gated[1] >= 6);
    CHECK_LE(fabs(c.gain_q16[1] / 65536.0 - 1 / 1.15), 0.03);
    /* a walk too short for the baseline: nothing changes */
    od_walk(&c, 0, 5, -90, 0.08, 0.15, 120, 0, -1);
    fl_odocal_solve(&c);
    CHECK_EQ(c.pairs[1], 0);
    CHECK_EQ(c.gain_q16[1], FL_ODOCAL_ONE_Q16);
    /* an odometry 60 % long: every pair beyond the bound is gated, gain 1 */
    od_walk(&c, 0, 5, -90, 0, 0.6, 500, 0, -1);
    fl_odocal_solve(&c);
    CHECK_EQ(c.pairs[1], 0);
    CHECK_EQ(c.gain_q16[1], FL_ODOCAL_ONE_Q16);
}

static void test_apply_carry(void)
{
    fl_odocal_t c;
    int32_t sx = 0, sy = 0, k;
    fl_odocal_init(&c);
    c.gain_q16[0] = 58000;
    c.gain_q16[1] = 70000;
    for (k = 0; k < 1000; k++) {
        int32_t dx = 3 - (k % 7), dy = 5;
        CHECK_EQ(fl_odocal_apply(&c, &dx, &dy), FL_OK);
        sx += dx;
        sy += dy;
    }
    /* sum of (3 - k % 7) over 1000 steps: 142 full cycles (0) + 3+2+1+0+-1+-2 = 3 */
    CHECK_LE(abs(sx - (int32_t)lround(3 * 58000 / 65536.0)), 1);
    CHECK_LE(abs(sy - (int32_t)lround(5000 * 70000 / 65536.0)), 1);
}

static void test_bad_input(void)
{
    fl_odocal_t c;
    int32_t a = 1, b = 1;
    int k;
    CHECK_EQ(fl_odocal_init(NULL), FL_ERR_NULL);
    CHECK_EQ(fl_odocal_odometry(NULL, 0, 0, 0), FL_ERR_NULL);
    CHECK_EQ(fl_odocal_fix(NULL, 0, 0), FL_ERR_NULL);
    CHECK_EQ(fl_odocal_solve(NULL), FL_ERR_NULL);
    CHECK_EQ(fl_odocal_apply(NULL, &a, &b), FL_ERR_NULL);
    fl_odocal_init(&c);
    CHECK_EQ(fl_odocal_apply(&c, NULL, &b), FL_ERR_NULL);
    CHECK_EQ(fl_odocal_odometry(&c, 1001, 0, 0), FL_ERR_RANGE);
    CHECK_EQ(c.px_x_q15, 0);
    CHECK_EQ(fl_odocal_fix(&c, 0, 100001), FL_ERR_RANGE);
    CHECK_EQ(c.n_fixes, 0);
    for (k = 0; k < FL_ODOCAL_MAX_FIXES; k++)
        CHECK_EQ(fl_odocal_fix(&c, k, 0), FL_OK);
    CHECK_EQ(fl_odocal_fix(&c, 0, 0), FL_ERR_SIZE);
    CHECK_EQ(c.fixes_refused, 1);
    CHECK_EQ(c.n_fixes, FL_ODOCAL_MAX_FIXES);
    /* extreme values stay bounded */
    fl_odocal_init(&c);
    for (k = 0; k < 400; k++)
        fl_odocal_odometry(&c, 1000, -1000, 0);
    fl_odocal_fix(&c, 100000, -100000);
    fl_odocal_fix(&c, -100000, 100000);
    CHECK_EQ(fl_odocal_solve(&c), FL_OK);
    CHECK(c.gain_q16[0] >= FL_ODOCAL_GAIN_MIN_Q16 && c.gain_q16[0] <= FL_ODOCAL_GAIN_MAX_Q16);
    CHECK(c.gain_q16[1] >= FL_ODOCAL_GAIN_MIN_Q16 && c.gain_q16[1] <= FL_ODOCAL_GAIN_MAX_Q16);
}

void suite_odocal(void)
{
    t_run("odocal.sidestep", test_sidestep);
    t_run("odocal.forward_turned", test_forward_turned);
    t_run("odocal.gate_and_bounds", test_gate_and_bounds);
    t_run("odocal.apply_carry", test_apply_carry);
    t_run("odocal.bad_input", test_bad_input);
}
