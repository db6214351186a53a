/*
 * host_tests/test_fixed.c - suite `fixed`: the fixed-point core (src/base/fixed.c)
 * against references computed another way (double libm, exact integer
 * inequalities, a multi-limb 160-bit product, int64 division identities).
 *
 * Sweeps and their sizes (normal / --quick / --exhaustive):
 *   sin/cos Q15 and Q30     all 65536 angles in every mode
 *   atan2                   grid [-512,512]^2 + 10^6 random   (quick: grid
 *                           [-64,64]^2 + 10^5 random); extremes, axes,
 *                           diagonals and the sin/cos round trip always
 *   isqrt32                 r^2-1, r^2, (r+1)^2-1 for every r < 65536 + 10^6
 *                           random (quick: 10^5 random); --exhaustive adds
 *                           fixed.isqrt32_exhaustive_all (all 2^32 inputs)
 *   isqrt64                 s^2-1, s^2, s^2+1 for s in 0..200000, near powers
 *                           of two and 10^5 random s, + 10^6 random x
 *                           (quick: s < 20000, 10^4 random s, 10^5 random x)
 *   hypot                   extremes x extremes + 10^6 random (quick 10^5)
 *   angle conversions       all 65536 angles; mdeg in [-400000, 400000] and
 *                           urad in [-10^6, 10^6] densely + 10^6 random
 *                           (quick: 10^5); --exhaustive adds
 *                           fixed.angle_urad_exhaustive_all (all 2^32 urad)
 *   rounding helpers        extremes, ties, every shift, 10^6 random (quick
 *                           10^5)
 * Every case prints a digest of the firmware outputs of its sweep; measured
 * errors go to "# " lines only.  Nothing is timed.
 */
#include "test.h"

#include <limits.h>
#include <math.h>

#include "fieldloc/fixed.h"

#define PI_D 3.14159265358979323846

/* ---- helpers ----------------------------------------------------------- */

static long n_random(long normal, long quick) { return t_quick ? quick : normal; }

/* uint32 with a uniformly random bit length 0..32 (log-uniform magnitude). */
static uint32_t rng_log_u32(t_rng_t *r)
{
    int bits = (int)t_rng_range(r, 0, 32);
    uint32_t v = t_rng_u32(r);
    if (bits == 0)
        return 0;
    v >>= 32 - bits;
    return v | (1u << (bits - 1));
}

/* int32: half uniform over all int32, half log-uniform with random sign. */
static int32_t rng_mix_i32(t_rng_t *r)
{
    uint32_t u;
    if (t_rng_u32(r) & 1u)
        return (int32_t)t_rng_u32(r);
    u = rng_log_u32(r);
    if (t_rng_u32(r) & 1u) {
        if (u > 0x80000000u)
            u >>= 1;
        return u == 0x80000000u ? INT32_MIN : -(int32_t)u;
    }
    return (int32_t)(u >> (u > 0x7fffffffu));
}

static uint64_t rng_u64(t_rng_t *r)
{
    uint64_t hi = t_rng_u32(r);
    return (hi << 32) | t_rng_u32(r);
}

/* uint64 with a uniformly random bit length 0..64. */
static uint64_t rng_log_u64(t_rng_t *r)
{
    int bits = (int)t_rng_range(r, 0, 64);
    uint64_t v = rng_u64(r);
    if (bits == 0)
        return 0;
    v >>= 64 - bits;
    return v | ((uint64_t)1 << (bits - 1));
}

static int64_t rng_log_i64(t_rng_t *r)
{
    uint64_t u = rng_log_u64(r);
    int neg = (int)(t_rng_u32(r) & 1u);
    if (u >= ((uint64_t)1 << 63))
        return neg ? INT64_MIN : INT64_MAX;
    return neg ? -(int64_t)u : (int64_t)u;
}

static uint32_t hash_u64(uint32_t h, uint64_t v)
{
    h = t_hash_i32(h, (int32_t)(uint32_t)(v >> 32));
    return t_hash_i32(h, (int32_t)(uint32_t)v);
}

/* Mathematical a mod 65536 mapped to [-32768, 32767], via int64. */
static int32_t ref_wrap(int64_t a)
{
    int64_t m = ((a % 65536) + 65536) % 65536;
    return (int32_t)(m >= 32768 ? m - 65536 : m);
}

/* Round-half-away-from-zero of n / d (d != 0, not INT64_MIN / -1) by C
 * truncating division plus a remainder test; result as int64. */
static int64_t ref_div_round64(int64_t n, int64_t d)
{
    int64_t q = n / d, r = n % d;
    uint64_t ar = r < 0 ? (uint64_t)(-r) : (uint64_t)r; /* |r| < 2^63 */
    uint64_t ad = d == INT64_MIN ? (uint64_t)1 << 63 : (uint64_t)(d < 0 ? -d : d);
    if (2u * ar >= ad)
        q += ((n < 0) != (d < 0)) ? -1 : 1;
    return q;
}

static int32_t ref_sat32(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v;
}

/* Binary-angle difference a - ref (ref in units, double) wrapped to
 * [-32768, 32768). */
static double wrap_diff(double a, double ref)
{
    double d = a - ref;
    while (d >= 32768.0)
        d -= 65536.0;
    while (d < -32768.0)
        d += 65536.0;
    return d;
}

/* ---- angles ------------------------------------------------------------ */

static void test_angle_wrap(void)
{
    static const int32_t special[] = {0, 1, -1, 32767, 32768, -32768, -32769, 65535, 65536,
                                      -65536, -65537, 98304, INT32_MAX, INT32_MIN,
                                      INT32_MIN + 1, INT32_MAX - 32768};
    uint32_t h = t_hash_init();
    t_rng_t r;
    long i, n = n_random(1000000, 100000);
    int32_t a, b;
    for (i = 0; i < (long)(sizeof special / sizeof special[0]); i++) {
        CHECK_EQ(fl_angle_wrap(special[i]), ref_wrap(special[i]));
        h = t_hash_i32(h, fl_angle_wrap(special[i]));
    }
    for (a = -200000; a <= 200000; a++)
        if (fl_angle_wrap(a) != ref_wrap(a))
            CHECK_EQ(fl_angle_wrap(a), ref_wrap(a));
    t_rng_seed(&r, 11);
    for (i = 0; i < n; i++) {
        int32_t v = (int32_t)t_rng_u32(&r);
        int32_t w = fl_angle_wrap(v);
        if (w != ref_wrap(v))
            CHECK_EQ(w, ref_wrap(v));
        h = t_hash_i32(h, w);
    }
    /* add / sub: every a against a spread of b, and random pairs */
    for (a = -32768; a <= 32767; a++) {
        for (b = -32768; b <= 32767; b += 4099) {
            fl_angle_t s = fl_angle_add((fl_angle_t)a, (fl_angle_t)b);
            fl_angle_t d = fl_angle_sub((fl_angle_t)a, (fl_angle_t)b);
            if (s != ref_wrap((int64_t)a + b) || d != ref_wrap((int64_t)a - b)) {
                CHECK_EQ(s, ref_wrap((int64_t)a + b));
                CHECK_EQ(d, ref_wrap((int64_t)a - b));
            }
            h = t_hash_i32(h, s);
            h = t_hash_i32(h, d);
        }
    }
    CHECK_EQ(fl_angle_add(32767, 1), -32768);
    CHECK_EQ(fl_angle_sub(-32768, 1), 32767);
    CHECK_EQ(fl_angle_add(-32768, -32768), 0);
    t_digest("fixed.angle_wrap", h);
}

/* mdeg -> units by int64 floor division (no pre-reduction, no tie logic:
 * 2048 mdeg is never an odd multiple of 5625). */
static int32_t ref_from_mdeg(int32_t mdeg)
{
    int64_t num = (int64_t)mdeg * 2048 + 5625, den = 11250;
    int64_t q = num / den;
    if (num % den != 0 && num < 0)
        q--;
    return ref_wrap(q);
}

static void test_angle_mdeg(void)
{
    static const int32_t special[] = {0, 1, -1, 2, -2, 3, -3, 179997, 179998, -179997,
                                      180000, -180000, 359997, 359998, 360000, -360000,
                                      INT32_MAX, INT32_MIN, INT32_MIN + 1, 2147399999};
    uint32_t h = t_hash_init();
    t_rng_t r;
    long i, n = n_random(1000000, 100000);
    int32_t a, m;
    for (a = -32768; a <= 32767; a++) {
        int32_t md = fl_angle_to_mdeg((fl_angle_t)a);
        /* reference: round half away from zero of a * 360000 / 65536 in
         * double (exact: a * 5625 / 1024 is a dyadic rational) */
        double x = a * 5625.0 / 1024.0;
        int32_t ref = (int32_t)(x < 0 ? -floor(-x + 0.5) : floor(x + 0.5));
        if (md != ref)
            CHECK_EQ(md, ref);
        if (fl_angle_from_mdeg(md) != a)
            CHECK_EQ(fl_angle_from_mdeg(md), a); /* round trip */
        h = t_hash_i32(h, md);
    }
    CHECK_EQ(fl_angle_to_mdeg(-32768), -180000);
    CHECK_EQ(fl_angle_to_mdeg(32767), 179995);
    CHECK_EQ(fl_angle_to_mdeg(512), 2813);   /* tie 2812.5, away from zero */
    CHECK_EQ(fl_angle_to_mdeg(-512), -2813);
    for (i = 0; i < (long)(sizeof special / sizeof special[0]); i++) {
        CHECK_EQ(fl_angle_from_mdeg(special[i]), ref_from_mdeg(special[i]));
        h = t_hash_i32(h, fl_angle_from_mdeg(special[i]));
    }
    for (m = -400000; m <= 400000; m++) {
        fl_angle_t v = fl_angle_from_mdeg(m);
        if (v != ref_from_mdeg(m))
            CHECK_EQ(v, ref_from_mdeg(m));
        h = t_hash_i32(h, v);
    }
    t_rng_seed(&r, 12);
    for (i = 0; i < n; i++) {
        int32_t v = rng_mix_i32(&r);
        fl_angle_t w = fl_angle_from_mdeg(v);
        if (w != ref_from_mdeg(v))
            CHECK_EQ(w, ref_from_mdeg(v));
        h = t_hash_i32(h, w);
    }
    t_digest("fixed.angle_mdeg", h);
}

/* floor(2^128 * 65536 / (2 pi 10^6)) in four 32-bit limbs, low first
 * (computed with mpmath at 400 bits; independent of the Q70 constant in
 * src/base/fixed.c).  ref = round(|urad| K) from the 160-bit product. */
static const uint32_t k_urad_q128[4] = {0x44707955u, 0x61314184u, 0xe6720050u, 0x02ab90b5u};

static int32_t ref_from_urad(int32_t urad)
{
    uint32_t u = (uint32_t)(urad < 0 ? -(int64_t)urad : (int64_t)urad);
    uint32_t limb[5];
    uint64_t carry = 0;
    int i;
    int64_t q;
    for (i = 0; i < 4; i++) {
        uint64_t p = (uint64_t)u * k_urad_q128[i] + carry;
        limb[i] = (uint32_t)p;
        carry = p >> 32;
    }
    limb[4] = (uint32_t)carry;
    q = (int64_t)limb[4] + (limb[3] >> 31);
    return ref_wrap(urad < 0 ? -q : q);
}

static void test_angle_urad(void)
{
    static const int32_t special[] = {0, 1, -1, 47, 48, -48, 1570796, 1570797, 3141592, 3141593,
                                      -3141593, 6283185, 6283186, INT32_MAX, INT32_MIN,
                                      INT32_MIN + 1};
    uint32_t h = t_hash_init();
    t_rng_t r;
    long i, n = n_random(1000000, 100000);
    int32_t a, u;
    double maxerr = 0.0;
    for (a = -32768; a <= 32767; a++) {
        int32_t ur = fl_angle_to_urad((fl_angle_t)a);
        double x = a * (2.0 * PI_D * 1e6 / 65536.0);
        double frac = fabs(x - floor(x)) - 0.5;
        int32_t ref = (int32_t)(x < 0 ? -floor(-x + 0.5) : floor(x + 0.5));
        CHECK(fabs(frac) > 1e-6); /* the double reference is unambiguous */
        if (ur != ref)
            CHECK_EQ(ur, ref);
        if (fabs(ur - x) > maxerr)
            maxerr = fabs(ur - x);
        if (fl_angle_from_urad(ur) != a)
            CHECK_EQ(fl_angle_from_urad(ur), a); /* round trip */
        h = t_hash_i32(h, ur);
    }
    t_info("to_urad max |error| %.4f urad over all 65536 angles", maxerr);
    CHECK_EQ(fl_angle_to_urad(-32768), -3141593);
    CHECK_EQ(fl_angle_to_urad(16384), 1570796);
    for (i = 0; i < (long)(sizeof special / sizeof special[0]); i++) {
        CHECK_EQ(fl_angle_from_urad(special[i]), ref_from_urad(special[i]));
        h = t_hash_i32(h, fl_angle_from_urad(special[i]));
    }
    for (u = -1000000; u <= 1000000; u++) {
        fl_angle_t v = fl_angle_from_urad(u);
        if (v != ref_from_urad(u))
            CHECK_EQ(v, ref_from_urad(u));
        h = t_hash_i32(h, v);
    }
    t_rng_seed(&r, 13);
    for (i = 0; i < n; i++) {
        int32_t v = rng_mix_i32(&r);
        fl_angle_t w = fl_angle_from_urad(v);
        if (w != ref_from_urad(v))
            CHECK_EQ(w, ref_from_urad(v));
        h = t_hash_i32(h, w);
    }
    t_digest("fixed.angle_urad", h);
}

/* --exhaustive only: fl_angle_from_urad for all 2^32 inputs. */
static void test_angle_urad_all(void)
{
    uint64_t i;
    uint64_t sum = 0;
    long bad = 0;
    for (i = 0; i <= 0xFFFFFFFFu; i++) {
        int32_t v = (int32_t)(uint32_t)i;
        fl_angle_t w = fl_angle_from_urad(v);
        if (w != ref_from_urad(v) && bad++ < 5)
            CHECK_EQ(w, ref_from_urad(v));
        sum += (uint16_t)w;
    }
    CHECK_EQ(bad, 0);
    t_digest("fixed.angle_urad_exhaustive_all", hash_u64(t_hash_init(), sum));
}

/* ---- trigonometry ------------------------------------------------------ */

static void test_sin_cos_q15(void)
{
    uint32_t h = t_hash_init();
    double max_round = 0.0, max_exact = 0.0;
    int32_t a;
    for (a = -32768; a <= 32767; a++) {
        double x = a * (PI_D / 32768.0);
        double s = 32768.0 * sin(x), c = 32768.0 * cos(x);
        double rs = floor(s + 0.5), rc = floor(c + 0.5);
        int16_t fs = fl_sin_q15((fl_angle_t)a), fc = fl_cos_q15((fl_angle_t)a);
        rs = rs > 32767 ? 32767 : rs < -32767 ? -32767 : rs;
        rc = rc > 32767 ? 32767 : rc < -32767 ? -32767 : rc;
        if (fabs(fs - rs) > max_round)
            max_round = fabs(fs - rs);
        if (fabs(fc - rc) > max_round)
            max_round = fabs(fc - rc);
        /* against the unclamped value, except where the clamp acts */
        if (fabs(s) < 32767.0 && fabs(fs - s) > max_exact)
            max_exact = fabs(fs - s);
        if (fabs(c) < 32767.0 && fabs(fc - c) > max_exact)
            max_exact = fabs(fc - c);
        CHECK(fs >= -32767 && fc >= -32767);
        if (a != -32768 && fl_sin_q15((fl_angle_t)-a) != -fs)
            CHECK_EQ(fl_sin_q15((fl_angle_t)-a), -fs); /* odd */
        if (a != -32768 && fl_cos_q15((fl_angle_t)-a) != fc)
            CHECK_EQ(fl_cos_q15((fl_angle_t)-a), fc);  /* even */
        h = t_hash_i32(h, fs);
        h = t_hash_i32(h, fc);
    }
    t_info("sin/cos q15 max |err| %.0f LSB vs clamped round(32768 sin); %.4f LSB vs "
           "32768 sin (unclamped points)", max_round, max_exact);
    CHECK_LE(max_round, 2.0);    /* header promise */
    CHECK_LE(max_exact, 0.66);   /* src/base/fixed.c bound: chord 0.154 + rounding 0.5 */
    CHECK_EQ(fl_sin_q15(0), 0);
    CHECK_EQ(fl_sin_q15(FL_ANGLE_90), 32767);
    CHECK_EQ(fl_sin_q15(-FL_ANGLE_90), -32767);
    CHECK_EQ(fl_sin_q15(FL_ANGLE_180), 0);
    CHECK_EQ(fl_cos_q15(0), 32767);
    CHECK_EQ(fl_cos_q15(FL_ANGLE_180), -32767);
    CHECK_EQ(fl_cos_q15(FL_ANGLE_90), 0);
    CHECK_EQ(fl_sin_q15(FL_ANGLE_45), 23170); /* 32768 / sqrt(2) = 23170.475 */
    t_digest("fixed.sin_cos_q15", h);
}

static void test_sin_cos_q30(void)
{
    uint32_t h = t_hash_init();
    double maxerr = 0.0, maxround = 0.0;
    int32_t a, worst = 0;
    for (a = -32768; a <= 32767; a++) {
        double x = a * (PI_D / 32768.0);
        double s = 1073741824.0 * sin(x), c = 1073741824.0 * cos(x);
        int32_t fs = fl_sin_q30((fl_angle_t)a), fc = fl_cos_q30((fl_angle_t)a);
        double es = fabs(fs - s), ec = fabs(fc - c);
        if (es > maxerr) {
            maxerr = es;
            worst = a;
        }
        if (ec > maxerr) {
            maxerr = ec;
            worst = a;
        }
        if (fabs(fs - floor(s + 0.5)) > maxround)
            maxround = fabs(fs - floor(s + 0.5));
        if (fabs(fc - floor(c + 0.5)) > maxround)
            maxround = fabs(fc - floor(c + 0.5));
        CHECK(fs >= -(1 << 30) && fs <= (1 << 30));
        if (a != -32768 && fl_sin_q30((fl_angle_t)-a) != -fs)
            CHECK_EQ(fl_sin_q30((fl_angle_t)-a), -fs);
        if (a != -32768 && fl_cos_q30((fl_angle_t)-a) != fc)
            CHECK_EQ(fl_cos_q30((fl_angle_t)-a), fc);
        h = t_hash_i32(h, fs);
        h = t_hash_i32(h, fc);
    }
    t_info("sin/cos q30 max |err| %.4f LSB (= 2^%.2f) at angle %ld; %.0f LSB vs "
           "round(2^30 sin)", maxerr, log(maxerr / 1073741824.0) / log(2.0), (long)worst,
           maxround);
    CHECK_LE(maxerr, 0.76);            /* src/base/fixed.c bound */
    CHECK_LE(maxerr, 1073741824.0 / 1048576.0); /* requirement 2^-20 */
    CHECK_EQ(fl_sin_q30(0), 0);
    CHECK_EQ(fl_sin_q30(FL_ANGLE_90), 1 << 30);
    CHECK_EQ(fl_sin_q30(-FL_ANGLE_90), -(1 << 30));
    CHECK_EQ(fl_cos_q30(0), 1 << 30);
    CHECK_EQ(fl_cos_q30(FL_ANGLE_180), -(1 << 30));
    CHECK_EQ(fl_sin_q30(FL_ANGLE_180), 0);
    t_digest("fixed.sin_cos_q30", h);
}

/* ---- atan2 -------------------------------------------------------------- */

typedef struct {
    double maxerr; /* units */
    int32_t wy, wx;
    uint32_t h;
    long n;
} atan_acc_t;

static void atan_one(atan_acc_t *acc, int32_t y, int32_t x)
{
    fl_angle_t a = fl_atan2(y, x);
    double ref = (x == 0 && y == 0) ? 0.0 : atan2((double)y, (double)x) * (32768.0 / PI_D);
    double e = fabs(wrap_diff(a, ref));
    if (e > acc->maxerr) {
        acc->maxerr = e;
        acc->wy = y;
        acc->wx = x;
    }
    acc->h = t_hash_i32(acc->h, a);
    acc->n++;
}

static void atan_report(const atan_acc_t *acc, const char *what)
{
    t_info("atan2 %s: %ld inputs, max |err| %.4f units = %.5f deg at (y=%ld, x=%ld)", what,
           acc->n, acc->maxerr, acc->maxerr * 360.0 / 65536.0, (long)acc->wy, (long)acc->wx);
    CHECK_LE(acc->maxerr * 360.0 / 65536.0, 0.0199); /* requirement < 0.02 deg */
    CHECK_LE(acc->maxerr, 0.93);                     /* src/base/fixed.c bound */
}

static void test_atan2_special(void)
{
    static const int32_t mags[] = {1, 2, 3, 7, 100, 255, 256, 32767, 32768, 65535, 65536,
                                   46341, 1 << 20, (1 << 24) + 1, 1 << 30, 0x7FFF8000,
                                   0x7FFFFFFE, INT32_MAX};
    atan_acc_t acc = {0, 0, 0, 0, 0};
    int32_t a;
    size_t i, j;
    acc.h = t_hash_init();
    CHECK_EQ(fl_atan2(0, 0), 0);
    atan_one(&acc, 0, 0);
    /* axes and diagonals are exact */
    for (i = 0; i < sizeof mags / sizeof mags[0]; i++) {
        int32_t m = mags[i];
        CHECK_EQ(fl_atan2(0, m), 0);
        CHECK_EQ(fl_atan2(m, 0), 16384);
        CHECK_EQ(fl_atan2(0, -m), -32768);
        CHECK_EQ(fl_atan2(-m, 0), -16384);
        CHECK_EQ(fl_atan2(m, m), 8192);
        CHECK_EQ(fl_atan2(m, -m), 24576);
        CHECK_EQ(fl_atan2(-m, -m), -24576);
        CHECK_EQ(fl_atan2(-m, m), -8192);
        atan_one(&acc, m, m);
        atan_one(&acc, -m, m);
    }
    CHECK_EQ(fl_atan2(0, INT32_MIN), -32768);
    CHECK_EQ(fl_atan2(INT32_MIN, 0), -16384);
    CHECK_EQ(fl_atan2(INT32_MIN, INT32_MIN), -24576);
    /* every pair of extremes, all sign combinations */
    {
        static const int32_t ext[] = {0, 1, -1, 2, -2, INT32_MAX, INT32_MIN, INT32_MIN + 1,
                                      INT32_MAX - 1, 1 << 30, -(1 << 30), 65536, -65536,
                                      46340, -46341};
        for (i = 0; i < sizeof ext / sizeof ext[0]; i++)
            for (j = 0; j < sizeof ext / sizeof ext[0]; j++)
                atan_one(&acc, ext[i], ext[j]);
    }
    atan_report(&acc, "axes, diagonals, extremes");
    /* round trip through the Q30 unit circle and scaled versions of it */
    {
        int maxd = 0;
        for (a = -32768; a <= 32767; a++) {
            int32_t s = fl_sin_q30((fl_angle_t)a), c = fl_cos_q30((fl_angle_t)a);
            int d1 = fl_angle_sub(fl_atan2(s, c), (fl_angle_t)a);
            if (d1 < 0)
                d1 = -d1;
            if (d1 > maxd)
                maxd = d1;
            CHECK(d1 <= 1);
            acc.h = t_hash_i32(acc.h, fl_atan2(s, c));
            acc.h = t_hash_i32(acc.h, fl_atan2(s >> 20, c >> 20));
        }
        t_info("atan2(sin_q30(a), cos_q30(a)) - a: max %d unit over all 65536 a", maxd);
    }
    t_digest("fixed.atan2_special", acc.h);
}

static void test_atan2_grid(void)
{
    int32_t lim = t_quick ? 64 : 512, x, y;
    atan_acc_t acc = {0, 0, 0, 0, 0};
    acc.h = t_hash_init();
    for (y = -lim; y <= lim; y++)
        for (x = -lim; x <= lim; x++)
            atan_one(&acc, y, x);
    atan_report(&acc, t_quick ? "grid [-64,64]^2" : "grid [-512,512]^2");
    t_digest("fixed.atan2_grid", acc.h);
}

static void test_atan2_random(void)
{
    long i, n = n_random(1000000, 100000);
    t_rng_t r;
    atan_acc_t acc = {0, 0, 0, 0, 0};
    acc.h = t_hash_init();
    t_rng_seed(&r, 21);
    for (i = 0; i < n; i++) {
        int32_t x, y;
        switch (i & 3) {
        case 0: /* uniform int32 */
            x = (int32_t)t_rng_u32(&r);
            y = (int32_t)t_rng_u32(&r);
            break;
        case 1: /* independent log-uniform magnitudes */
            x = rng_mix_i32(&r);
            y = rng_mix_i32(&r);
            break;
        default: { /* same bit length: directions spread over all octants */
            int bits = (int)t_rng_range(&r, 1, 31);
            x = (int32_t)(t_rng_u32(&r) >> (32 - bits));
            y = (int32_t)(t_rng_u32(&r) >> (32 - bits));
            if (t_rng_u32(&r) & 1u)
                x = -x;
            if (t_rng_u32(&r) & 1u)
                y = -y;
        } break;
        }
        atan_one(&acc, y, x);
    }
    atan_report(&acc, t_quick ? "10^5 random" : "10^6 random");
    t_digest("fixed.atan2_random", acc.h);
}

/* ---- roots ------------------------------------------------------------- */

static int isqrt32_ok(uint32_t x, uint32_t r)
{
    return (uint64_t)r * r <= x && ((uint64_t)r + 1) * ((uint64_t)r + 1) > x;
}

static int isqrt64_ok(uint64_t x, uint32_t r)
{
    if ((uint64_t)r * r > x)
        return 0;
    if (r == 0xFFFFFFFFu)
        return 1; /* (r + 1)^2 = 2^64 > every x */
    return ((uint64_t)r + 1) * ((uint64_t)r + 1) > x;
}

static void test_isqrt32(void)
{
    uint32_t h = t_hash_init();
    uint32_t s;
    long i, n = n_random(1000000, 100000), bad = 0;
    t_rng_t r;
    for (s = 0; s <= 65535u; s++) {
        uint32_t x[3];
        int k;
        x[0] = s ? s * s - 1u : 0xFFFFFFFFu; /* s = 0: UINT32_MAX instead */
        x[1] = s * s;
        x[2] = (uint32_t)(((uint64_t)s + 1) * ((uint64_t)s + 1) - 1u);
        for (k = 0; k < 3; k++) {
            uint16_t v = fl_isqrt32(x[k]);
            if (!isqrt32_ok(x[k], v) && bad++ < 5)
                t_fail_msg(__FILE__, __LINE__, "isqrt32(%lu) = %u", (unsigned long)x[k], v);
            h = t_hash_i32(h, v);
        }
    }
    CHECK_EQ(fl_isqrt32(0xFFFFFFFFu), 65535);
    CHECK_EQ(fl_isqrt32(0), 0);
    CHECK_EQ(fl_isqrt32(3), 1);
    CHECK_EQ(fl_isqrt32(4), 2);
    t_rng_seed(&r, 31);
    for (i = 0; i < n; i++) {
        uint32_t x = (i & 1) ? t_rng_u32(&r) : rng_log_u32(&r);
        uint16_t v = fl_isqrt32(x);
        if (!isqrt32_ok(x, v) && bad++ < 5)
            t_fail_msg(__FILE__, __LINE__, "isqrt32(%lu) = %u", (unsigned long)x, v);
        h = t_hash_i32(h, v);
    }
    CHECK_EQ(bad, 0);
    t_digest("fixed.isqrt32", h);
}

/* --exhaustive only: every uint32. */
static void test_isqrt32_all(void)
{
    uint64_t x, sum = 0;
    long bad = 0;
    for (x = 0; x <= 0xFFFFFFFFu; x++) {
        uint16_t v = fl_isqrt32((uint32_t)x);
        if (!isqrt32_ok((uint32_t)x, v) && bad++ < 5)
            t_fail_msg(__FILE__, __LINE__, "isqrt32(%lu) = %u", (unsigned long)x, v);
        sum += v;
    }
    CHECK_EQ(bad, 0);
    t_digest("fixed.isqrt32_exhaustive_all", hash_u64(t_hash_init(), sum));
}

static void isqrt64_check(uint64_t x, uint32_t *h, long *bad)
{
    uint32_t v = fl_isqrt64(x);
    if (!isqrt64_ok(x, v) && (*bad)++ < 5)
        t_fail_msg(__FILE__, __LINE__, "isqrt64(%llu) = %lu", (unsigned long long)x,
                   (unsigned long)v);
    *h = t_hash_i32(*h, (int32_t)v);
}

static void isqrt64_square(uint64_t s, uint32_t *h, long *bad)
{
    uint64_t q = s * s; /* s < 2^32 */
    if (q > 0)
        isqrt64_check(q - 1u, h, bad);
    isqrt64_check(q, h, bad);
    isqrt64_check(q + 1u, h, bad);
}

static void test_isqrt64(void)
{
    uint32_t h = t_hash_init();
    long i, bad = 0;
    long nx = n_random(1000000, 100000), ns = n_random(100000, 10000);
    uint64_t s, lim = t_quick ? 20000 : 200000;
    int k, j;
    t_rng_t r;
    for (s = 0; s <= lim; s++)
        isqrt64_square(s, &h, &bad);
    for (k = 16; k <= 32; k++)
        for (j = -3; j <= 3; j++) {
            uint64_t v = (uint64_t)(((int64_t)1 << k) + j);
            if (v <= 0xFFFFFFFFu)
                isqrt64_square(v, &h, &bad);
        }
    t_rng_seed(&r, 41);
    for (i = 0; i < ns; i++)
        isqrt64_square((i & 1) ? t_rng_u32(&r) : rng_log_u32(&r), &h, &bad);
    for (i = 0; i < nx; i++)
        isqrt64_check((i & 1) ? rng_u64(&r) : rng_log_u64(&r), &h, &bad);
    isqrt64_check(UINT64_MAX, &h, &bad);
    isqrt64_check(UINT64_MAX - 1u, &h, &bad);
    isqrt64_check((uint64_t)1 << 63, &h, &bad);
    isqrt64_check(((uint64_t)1 << 32) - 1u, &h, &bad);
    isqrt64_check((uint64_t)1 << 32, &h, &bad);
    CHECK_EQ(fl_isqrt64(UINT64_MAX), 0xFFFFFFFFu);
    CHECK_EQ(fl_isqrt64((uint64_t)0xFFFFFFFFu * 0xFFFFFFFFu - 1u), 0xFFFFFFFEu);
    CHECK_EQ(bad, 0);
    t_digest("fixed.isqrt64", h);
}

static void hypot_check(int32_t x, int32_t y, uint32_t *h, long *bad)
{
    uint32_t v = fl_hypot(x, y);
    uint64_t ax = (uint64_t)(x < 0 ? -(int64_t)x : (int64_t)x);
    uint64_t ay = (uint64_t)(y < 0 ? -(int64_t)y : (int64_t)y);
    uint64_t ss = ax * ax + ay * ay; /* <= 2^63 */
    if (!isqrt64_ok(ss, v) && (*bad)++ < 5)
        t_fail_msg(__FILE__, __LINE__, "hypot(%ld, %ld) = %lu", (long)x, (long)y,
                   (unsigned long)v);
    *h = t_hash_i32(*h, (int32_t)v);
}

static void test_hypot(void)
{
    static const int32_t ext[] = {0, 1, -1, 2, 3, -4, 32767, -32768, 32768, 46340, 46341,
                                  -46341, 65535, 65536, 1 << 30, -(1 << 30), INT32_MAX,
                                  INT32_MIN, INT32_MIN + 1, INT32_MAX - 1};
    uint32_t h = t_hash_init();
    long i, bad = 0, n = n_random(1000000, 100000);
    size_t a, b;
    t_rng_t r;
    for (a = 0; a < sizeof ext / sizeof ext[0]; a++)
        for (b = 0; b < sizeof ext / sizeof ext[0]; b++)
            hypot_check(ext[a], ext[b], &h, &bad);
    CHECK_EQ(fl_hypot(3, -4), 5);
    CHECK_EQ(fl_hypot(INT32_MIN, 0), 0x80000000u);
    CHECK(fl_hypot(INT32_MIN, INT32_MIN) > 3037000000u);
    t_info("hypot(INT32_MIN, INT32_MIN) = %lu", (unsigned long)fl_hypot(INT32_MIN, INT32_MIN));
    t_rng_seed(&r, 51);
    for (i = 0; i < n; i++) {
        int32_t x, y;
        if (i & 1) {
            x = (int32_t)t_rng_u32(&r);
            y = (int32_t)t_rng_u32(&r);
        } else {
            x = rng_mix_i32(&r);
            y = rng_mix_i32(&r);
        }
        hypot_check(x, y, &h, &bad);
    }
    /* Pythagorean triples (exact squares) and +-1 around them */
    for (i = 0; i < 2000; i++) {
        int32_t m = t_rng_range(&r, 1, 20000), k = t_rng_range(&r, 1, 20000);
        int32_t x = m * m - k * k, y = 2 * m * k; /* hypot = m^2 + k^2 */
        hypot_check(x, y, &h, &bad);
        hypot_check(x + 1, y, &h, &bad);
        hypot_check(x - 1, y, &h, &bad);
    }
    CHECK_EQ(bad, 0);
    t_digest("fixed.hypot", h);
}

/* ---- saturation and rounding ------------------------------------------- */

static void test_saturate(void)
{
    static const int64_t v64[] = {0, 1, -1, INT32_MAX, INT32_MIN, (int64_t)INT32_MAX + 1,
                                  (int64_t)INT32_MIN - 1, INT64_MAX, INT64_MIN,
                                  INT64_MAX - 1, INT64_MIN + 1, (int64_t)1 << 32,
                                  -((int64_t)1 << 32)};
    uint32_t h = t_hash_init();
    size_t i;
    int32_t v;
    long k, n = n_random(1000000, 100000);
    t_rng_t r;
    for (i = 0; i < sizeof v64 / sizeof v64[0]; i++) {
        int32_t s = fl_sat32(v64[i]);
        /* reference: the value itself when it survives the round trip */
        int in = v64[i] >= -2147483647 - 1 && v64[i] <= 2147483647;
        CHECK_EQ(s, in ? v64[i] : (v64[i] < 0 ? INT32_MIN : INT32_MAX));
        h = t_hash_i32(h, s);
    }
    t_rng_seed(&r, 61);
    for (k = 0; k < n; k++) {
        int64_t x = rng_log_i64(&r);
        double dx = (double)x;
        int32_t s = fl_sat32(x);
        int32_t ref = dx >= 2147483648.0 ? INT32_MAX : dx < -2147483648.0 ? INT32_MIN : (int32_t)x;
        if (s != ref)
            CHECK_EQ(s, ref);
        h = t_hash_i32(h, s);
    }
    for (v = -70000; v <= 70000; v++) {
        int16_t s = fl_sat16(v);
        uint8_t u = fl_satu8(v);
        int32_t rs = v < -32768 ? -32768 : v > 32767 ? 32767 : v;
        int32_t ru = v < 0 ? 0 : v > 255 ? 255 : v;
        if (s != rs || u != ru) {
            CHECK_EQ(s, rs);
            CHECK_EQ(u, ru);
        }
        h = t_hash_i32(h, s);
        h = t_hash_i32(h, u);
    }
    CHECK_EQ(fl_sat16(INT32_MAX), 32767);
    CHECK_EQ(fl_sat16(INT32_MIN), -32768);
    CHECK_EQ(fl_satu8(INT32_MAX), 255);
    CHECK_EQ(fl_satu8(INT32_MIN), 0);
    t_digest("fixed.saturate", h);
}

/* Reference for rshift_round with shift <= 62: truncating division by 2^s. */
static int32_t ref_rshift(int64_t v, unsigned s)
{
    if (s == 0)
        return ref_sat32(v);
    return ref_sat32(ref_div_round64(v, (int64_t)1 << s));
}

static void test_rshift_round(void)
{
    static const int64_t v64[] = {0, 1, -1, 2, -2, 3, -3, INT64_MAX, INT64_MIN, INT64_MAX - 1,
                                  INT64_MIN + 1, INT32_MAX, INT32_MIN, (int64_t)1 << 62,
                                  -((int64_t)1 << 62), ((int64_t)1 << 62) - 1};
    uint32_t h = t_hash_init();
    size_t i;
    unsigned s;
    long k, n = n_random(1000000, 100000);
    t_rng_t r;
    for (s = 0; s <= 62; s++) {
        for (i = 0; i < sizeof v64 / sizeof v64[0]; i++) {
            int32_t q = fl_rshift_round(v64[i], s);
            CHECK_EQ(q, ref_rshift(v64[i], s));
            h = t_hash_i32(h, q);
        }
        if (s >= 1) {
            /* ties: (2m + 1) 2^(s-1), both signs, away from zero */
            int64_t m;
            for (m = 0; m < 4 && s <= 60; m++) { /* 7 2^59 < 2^63 */
                int64_t t = (2 * m + 1) * ((int64_t)1 << (s - 1));
                {
                    CHECK_EQ(fl_rshift_round(t, s), ref_sat32(m + 1));
                    CHECK_EQ(fl_rshift_round(-t, s), ref_sat32(-m - 1));
                    CHECK_EQ(fl_rshift_round(t - 1, s), ref_sat32(m));
                    CHECK_EQ(fl_rshift_round(-t + 1, s), ref_sat32(-m));
                }
            }
        }
    }
    /* shifts beyond 62, mathematically */
    CHECK_EQ(fl_rshift_round(INT64_MAX, 63), 1);      /* 0.99999 */
    CHECK_EQ(fl_rshift_round(INT64_MIN, 63), -1);     /* -1 */
    CHECK_EQ(fl_rshift_round((int64_t)1 << 62, 63), 1);       /* tie 0.5 */
    CHECK_EQ(fl_rshift_round(((int64_t)1 << 62) - 1, 63), 0);
    CHECK_EQ(fl_rshift_round(-((int64_t)1 << 62), 63), -1);
    CHECK_EQ(fl_rshift_round(INT64_MIN, 64), -1);     /* tie -0.5 */
    CHECK_EQ(fl_rshift_round(INT64_MAX, 64), 0);
    CHECK_EQ(fl_rshift_round(INT64_MIN, 65), 0);
    CHECK_EQ(fl_rshift_round(INT64_MIN, 1000), 0);
    t_rng_seed(&r, 71);
    for (k = 0; k < n; k++) {
        int64_t v = rng_log_i64(&r);
        unsigned sh = (unsigned)t_rng_range(&r, 0, 62);
        int32_t q = fl_rshift_round(v, sh);
        if (q != ref_rshift(v, sh))
            CHECK_EQ(q, ref_rshift(v, sh));
        h = t_hash_i32(h, q);
    }
    t_digest("fixed.rshift_round", h);
}

static int32_t ref_div_round(int64_t n, int64_t d)
{
    if (d == 0)
        return n > 0 ? INT32_MAX : n < 0 ? INT32_MIN : 0;
    if (n == INT64_MIN && d == -1)
        return INT32_MAX;
    return ref_sat32(ref_div_round64(n, d));
}

static void test_div_round(void)
{
    static const int64_t v64[] = {0, 1, -1, 2, -2, 3, -3, 5, -5, 7, -7, INT64_MAX, INT64_MIN,
                                  INT64_MIN + 1, INT32_MAX, INT32_MIN, (int64_t)INT32_MAX + 1,
                                  (int64_t)UINT32_MAX, -(int64_t)UINT32_MAX,
                                  (int64_t)1 << 32, (int64_t)1 << 62};
    uint32_t h = t_hash_init();
    size_t i, j;
    long k, n = n_random(1000000, 100000);
    int32_t a, b;
    t_rng_t r;
    for (i = 0; i < sizeof v64 / sizeof v64[0]; i++)
        for (j = 0; j < sizeof v64 / sizeof v64[0]; j++) {
            int32_t q = fl_div_round(v64[i], v64[j]);
            CHECK_EQ(q, ref_div_round(v64[i], v64[j]));
            h = t_hash_i32(h, q);
        }
    CHECK_EQ(fl_div_round(5, 2), 3);   /* ties away from zero */
    CHECK_EQ(fl_div_round(-5, 2), -3);
    CHECK_EQ(fl_div_round(5, -2), -3);
    CHECK_EQ(fl_div_round(-5, -2), 3);
    CHECK_EQ(fl_div_round(7, 0), INT32_MAX);
    CHECK_EQ(fl_div_round(-7, 0), INT32_MIN);
    CHECK_EQ(fl_div_round(0, 0), 0);
    CHECK_EQ(fl_div_round(INT64_MIN, -1), INT32_MAX);
    CHECK_EQ(fl_div_round(INT64_MIN, INT64_MIN), 1);
    CHECK_EQ(fl_div_round(INT64_MIN / 2, INT64_MIN), 1);     /* 0.5 */
    CHECK_EQ(fl_div_round(INT64_MIN / 2 + 1, INT64_MIN), 0); /* < 0.5 */
    for (a = -300; a <= 300; a++)
        for (b = -40; b <= 40; b++) {
            int32_t q = fl_div_round(a, b);
            /* independent reference for small values: exact doubles */
            double x = b ? (double)a / b : 0.0;
            int32_t ref = b == 0 ? (a > 0 ? INT32_MAX : a < 0 ? INT32_MIN : 0)
                                 : (int32_t)(x < 0 ? -floor(-x + 0.5) : floor(x + 0.5));
            if (q != ref)
                CHECK_EQ(q, ref);
            h = t_hash_i32(h, q);
        }
    t_rng_seed(&r, 81);
    for (k = 0; k < n; k++) {
        int64_t nn = rng_log_i64(&r), dd = rng_log_i64(&r);
        int32_t q;
        if (k & 1) /* quotients near the int32 range */
            dd = (int64_t)(rng_log_u32(&r) >> 1) * ((k & 2) ? 1 : -1);
        q = fl_div_round(nn, dd);
        if (q != ref_div_round(nn, dd))
            CHECK_EQ(q, ref_div_round(nn, dd));
        h = t_hash_i32(h, q);
    }
    t_digest("fixed.div_round", h);
}

static int32_t ref_floor_div(int32_t n, int32_t d)
{
    int64_t m;
    if (d <= 0)
        return 0;
    m = (((int64_t)n % d) + d) % d; /* mathematical modulo in [0, d) */
    return (int32_t)(((int64_t)n - m) / d);
}

static void test_floor_div(void)
{
    static const int32_t ext[] = {0, 1, -1, 2, -2, 3, -3, 100, -100, INT32_MAX, INT32_MIN,
                                  INT32_MIN + 1, INT32_MAX - 1};
    uint32_t h = t_hash_init();
    size_t i, j;
    int32_t a, b;
    long k, n = n_random(1000000, 100000);
    t_rng_t r;
    for (i = 0; i < sizeof ext / sizeof ext[0]; i++)
        for (j = 0; j < sizeof ext / sizeof ext[0]; j++) {
            int32_t q = fl_floor_div(ext[i], ext[j]);
            CHECK_EQ(q, ref_floor_div(ext[i], ext[j]));
            h = t_hash_i32(h, q);
        }
    CHECK_EQ(fl_floor_div(-1, 100), -1); /* no double-width cell at zero */
    CHECK_EQ(fl_floor_div(-100, 100), -1);
    CHECK_EQ(fl_floor_div(-101, 100), -2);
    CHECK_EQ(fl_floor_div(99, 100), 0);
    CHECK_EQ(fl_floor_div(INT32_MIN, 1), INT32_MIN);
    CHECK_EQ(fl_floor_div(5, 0), 0);
    CHECK_EQ(fl_floor_div(5, -3), 0);
    for (a = -1000; a <= 1000; a++)
        for (b = -2; b <= 50; b++) {
            int32_t q = fl_floor_div(a, b);
            int32_t ref = b <= 0 ? 0 : (int32_t)floor((double)a / b);
            if (q != ref)
                CHECK_EQ(q, ref);
            h = t_hash_i32(h, q);
        }
    t_rng_seed(&r, 91);
    for (k = 0; k < n; k++) {
        int32_t nn = rng_mix_i32(&r), dd = rng_mix_i32(&r);
        int32_t q = fl_floor_div(nn, dd);
        if (q != ref_floor_div(nn, dd))
            CHECK_EQ(q, ref_floor_div(nn, dd));
        h = t_hash_i32(h, q);
    }
    t_digest("fixed.floor_div", h);
}

static void test_mul_q(void)
{
    static const int32_t ext[] = {0, 1, -1, 16384, -16384, 32767, -32768, 32768, 3, -3,
                                  1 << 29, -(1 << 29), 1 << 30, -(1 << 30), INT32_MAX,
                                  INT32_MIN, INT32_MIN + 1};
    uint32_t h = t_hash_init();
    size_t i, j;
    long k, n = n_random(1000000, 100000);
    t_rng_t r;
    for (i = 0; i < sizeof ext / sizeof ext[0]; i++)
        for (j = 0; j < sizeof ext / sizeof ext[0]; j++) {
            int64_t p = (int64_t)ext[i] * ext[j];
            int32_t q15 = fl_mul_q15(ext[i], ext[j]), q30 = fl_mul_q30(ext[i], ext[j]);
            CHECK_EQ(q15, ref_rshift(p, 15));
            CHECK_EQ(q30, ref_rshift(p, 30));
            h = t_hash_i32(h, q15);
            h = t_hash_i32(h, q30);
        }
    CHECK_EQ(fl_mul_q15(1, 16384), 1);   /* 0.5 -> 1 */
    CHECK_EQ(fl_mul_q15(-1, 16384), -1); /* -0.5 -> -1 */
    CHECK_EQ(fl_mul_q15(3, 16384), 2);   /* 1.5 -> 2 */
    CHECK_EQ(fl_mul_q15(-3, 16384), -2);
    CHECK_EQ(fl_mul_q15(1, 16383), 0);
    CHECK_EQ(fl_mul_q15(-1, 16383), 0);
    CHECK_EQ(fl_mul_q15(INT32_MIN, INT32_MIN), INT32_MAX);
    CHECK_EQ(fl_mul_q15(INT32_MIN, 32767), -2147418112); /* -2^31 * (1 - 2^-15) exact */
    CHECK_EQ(fl_mul_q15(INT32_MIN, 32768), INT32_MIN);
    CHECK_EQ(fl_mul_q15(INT32_MAX, 32768), INT32_MAX);
    CHECK_EQ(fl_mul_q30(-1, 1 << 29), -1);
    CHECK_EQ(fl_mul_q30(INT32_MIN, 1 << 30), INT32_MIN);
    CHECK_EQ(fl_mul_q30(INT32_MIN, INT32_MIN), INT32_MAX);
    CHECK_EQ(fl_mul_q30(INT32_MIN, -(1 << 30)), INT32_MAX);
    t_rng_seed(&r, 101);
    for (k = 0; k < n; k++) {
        int32_t a = rng_mix_i32(&r), b = rng_mix_i32(&r);
        int64_t p = (int64_t)a * b;
        int32_t q15 = fl_mul_q15(a, b), q30 = fl_mul_q30(a, b);
        if (q15 != ref_rshift(p, 15))
            CHECK_EQ(q15, ref_rshift(p, 15));
        if (q30 != ref_rshift(p, 30))
            CHECK_EQ(q30, ref_rshift(p, 30));
        h = t_hash_i32(h, q15);
        h = t_hash_i32(h, q30);
    }
    t_digest("fixed.mul_q15_q30", h);
}

void suite_fixed(void)
{
    t_run("fixed.angle_wrap", test_angle_wrap);
    t_run("fixed.angle_mdeg", test_angle_mdeg);
    t_run("fixed.angle_urad", test_angle_urad);
    if (t_exhaustive)
        t_run("fixed.angle_urad_exhaustive_all", test_angle_urad_all);
    t_run("fixed.sin_cos_q15", test_sin_cos_q15);
    t_run("fixed.sin_cos_q30", test_sin_cos_q30);
    t_run("fixed.atan2_special", test_atan2_special);
    t_run("fixed.atan2_grid", test_atan2_grid);
    t_run("fixed.atan2_random", test_atan2_random);
    t_run("fixed.isqrt32", test_isqrt32);
    if (t_exhaustive)
        t_run("fixed.isqrt32_exhaustive_all", test_isqrt32_all);
    t_run("fixed.isqrt64", test_isqrt64);
    t_run("fixed.hypot", test_hypot);
    t_run("fixed.saturate", test_saturate);
    t_run("fixed.rshift_round", test_rshift_round);
    t_run("fixed.div_round", test_div_round);
    t_run("fixed.floor_div", test_floor_div);
    t_run("fixed.mul_q15_q30", test_mul_q);
}
