/*
 * src/base/fixed.c - fixed-point core: binary angles, table trigonometry, atan2,
 * integer square roots, saturating and rounding helpers.
 *
 * Algorithms
 *   sin/cos   quadrant symmetry maps every angle to x in [0, 16384] (a
 *             quarter turn).  sin_q31[] holds round(2^31 sin) at the 257
 *             knots x = 64 i.  Q30: angle addition from the knot,
 *                 sin(k + f) = sin(k) (1 - vers(f)) + cos(k) sin(f),
 *             with sin(f) and vers(f) = 1 - cos(f) for the 64 fine steps f
 *             in their own tables (Q39, Q47), cos(k) = sin_q31[256 - i];
 *             accumulated in Q39 (64 bit), rounded once to Q30.
 *             Q15: linear interpolation between the same Q31 knots (32-bit
 *             arithmetic only), rounded once to Q15.
 *   atan2     octant reduction to 0 <= ay <= ax; ax normalised to
 *             [2^31, 2^32); t = ay/ax in Q16 by ONE 32/32-bit division by
 *             the rounded top 16 bits of ax; atan(t) by linear
 *             interpolation in a 129-entry table (quarter units); octant
 *             undone with exact integer reflections.
 *   isqrt32   normalise to y = x 4^k in [2^30, 2^32); 8-bit table estimate
 *             of sqrt(y); one integer Newton step (one 32/32 division)
 *             lands on floor(sqrt(y)) or one above; one downward
 *             correction; shift back by k (floor(floor(sqrt(y)) / 2^k) ==
 *             floor(sqrt(x))).
 *   isqrt64   normalise to [2^62, 2^64); a = isqrt32(top word); the low 16
 *             result bits from the remainder by one 32/32 division
 *             (a never-low estimate, at most 2 too high); exact 64-bit
 *             correction; shift back.
 *   hypot     exact 64-bit sum of squares (<= 2^63) through isqrt64, or
 *             isqrt32 when both |x|, |y| < 2^15.
 *
 * Accuracy (measured exhaustively by host_tests/test_fixed.c)
 *   fl_sin_q15/fl_cos_q15  |err| <= 0.66 LSB against 32768 sin except at
 *             +-90 deg where the clamp to 32767 costs 1 (bound: chord 0.154
 *             + final rounding 0.5; measured 0.6502), hence <= 1 LSB
 *             against round(32768 sin) clamped to +-32767 (header: 2).
 *   fl_sin_q30/fl_cos_q30  |err| <= 0.76 LSB = 2^-30.4 against 2^30 sin
 *             (bound: Q31 knot 0.25 + fine terms 0.01 + rounding 0.5;
 *             measured 0.7475); the camera model needs 2^-20.
 *   fl_atan2  |err| <= 0.93 unit (0.0051 deg) (bound: table 0.125 +
 *             chord 0.052 + Q16 truncation of t 0.16 + divisor rounding
 *             0.08 + final rounding 0.5; measured 0.81 unit = 0.0045 deg
 *             over 2.05e6 inputs).
 *   roots     exact floor for every input.
 *
 * Invariant: every function is total (defined for every argument value),
 * pure (no state), and bit-identical on every C99 target: no signed
 * overflow, no unsigned wrap-around (clean under clang -fsanitize=integer),
 * only in-range conversions; the one implementation-defined operation is
 * the arithmetic right shift of a negative int64 in fl_mul_q15/q30, which
 * gcc and clang define.
 *
 * Memory: no stack arrays; rodata 1028 + 256 + 256 B (sin) + 258 B (atan)
 * = 1798 B of trig tables, 384 B isqrt estimate table.
 *
 * Cost: normalisations are <= 6 unrolled compare-and-shift steps; the only
 * loop is the isqrt64 correction (<= 2 steps by the bound, 1 observed); no
 * 64-bit division anywhere except fl_div_round with operands beyond 32 bits.
 * Throughput on the x86-64 development host (gcc -O2, random inputs):
 *   sin/cos q15  ~10 integer ops, 2 table reads               ~2.4 ns
 *   sin/cos q30  3 32x32->64 multiplies, 3 table reads          ~2.7 ns
 *   atan2        one 32/32 division                             ~5.8 ns
 *   isqrt32      one 32/32 division                             ~3.3 ns
 *   isqrt64      isqrt32 + one 32/32 division + 1-2 64-bit squares ~6 ns
 */
#include "fieldloc/fixed.h"

#include <stdint.h>

/* Tables generated with mpmath at 200-bit precision (round to nearest):
 *   sin_q31[i]       = round(2^31 sin(i pi / 512)),            i = 0..256
 *   sin_fine_q39[f]  = round(2^39 sin(f 2 pi / 65536)),        f = 0..63
 *   vers_fine_q47[f] = round(2^47 (1 - cos(f 2 pi / 65536))),  f = 0..63
 *   atan_q2[j]       = round(4 atan(j / 128) 65536 / (2 pi)),  j = 0..128
 *   isqrt_est[i]     = round(sqrt((i + 64 + 1/2) 2^24)),       i = 0..191
 * Every entry is exercised by the exhaustive sin/cos sweeps, the atan2
 * sweeps and the isqrt boundary sweeps of host_tests/test_fixed.c. */
static const uint32_t sin_q31[257] = {
    0u, 13176712u, 26352928u, 39528151u, 52701887u, 65873638u, 79042909u,
    92209205u, 105372028u, 118530885u, 131685278u, 144834714u, 157978697u,
    171116733u, 184248325u, 197372981u, 210490206u, 223599506u, 236700388u,
    249792358u, 262874923u, 275947592u, 289009871u, 302061269u, 315101295u,
    328129457u, 341145265u, 354148230u, 367137861u, 380113669u, 393075166u,
    406021865u, 418953276u, 431868915u, 444768294u, 457650927u, 470516330u,
    483364019u, 496193509u, 509004318u, 521795963u, 534567963u, 547319836u,
    560051104u, 572761285u, 585449903u, 598116479u, 610760536u, 623381598u,
    635979190u, 648552838u, 661102068u, 673626408u, 686125387u, 698598533u,
    711045377u, 723465451u, 735858287u, 748223418u, 760560380u, 772868706u,
    785147934u, 797397602u, 809617249u, 821806413u, 833964638u, 846091463u,
    858186435u, 870249095u, 882278992u, 894275671u, 906238681u, 918167572u,
    930061894u, 941921200u, 953745043u, 965532978u, 977284562u, 988999351u,
    1000676905u, 1012316784u, 1023918550u, 1035481766u, 1047005996u,
    1058490808u, 1069935768u, 1081340445u, 1092704411u, 1104027237u,
    1115308496u, 1126547765u, 1137744621u, 1148898640u, 1160009405u,
    1171076495u, 1182099496u, 1193077991u, 1204011567u, 1214899813u,
    1225742318u, 1236538675u, 1247288478u, 1257991320u, 1268646800u,
    1279254516u, 1289814068u, 1300325060u, 1310787095u, 1321199781u,
    1331562723u, 1341875533u, 1352137822u, 1362349204u, 1372509294u,
    1382617710u, 1392674072u, 1402678000u, 1412629117u, 1422527051u,
    1432371426u, 1442161874u, 1451898025u, 1461579514u, 1471205974u,
    1480777044u, 1490292364u, 1499751576u, 1509154322u, 1518500250u,
    1527789007u, 1537020244u, 1546193612u, 1555308768u, 1564365367u,
    1573363068u, 1582301533u, 1591180426u, 1599999411u, 1608758157u,
    1617456335u, 1626093616u, 1634669676u, 1643184191u, 1651636841u,
    1660027308u, 1668355276u, 1676620432u, 1684822463u, 1692961062u,
    1701035922u, 1709046739u, 1716993211u, 1724875040u, 1732691928u,
    1740443581u, 1748129707u, 1755750017u, 1763304224u, 1770792044u,
    1778213194u, 1785567396u, 1792854372u, 1800073849u, 1807225553u,
    1814309216u, 1821324572u, 1828271356u, 1835149306u, 1841958164u,
    1848697674u, 1855367581u, 1861967634u, 1868497586u, 1874957189u,
    1881346202u, 1887664383u, 1893911494u, 1900087301u, 1906191570u,
    1912224073u, 1918184581u, 1924072871u, 1929888720u, 1935631910u,
    1941302225u, 1946899451u, 1952423377u, 1957873796u, 1963250501u,
    1968553292u, 1973781967u, 1978936331u, 1984016189u, 1989021350u,
    1993951625u, 1998806829u, 2003586779u, 2008291295u, 2012920201u,
    2017473321u, 2021950484u, 2026351522u, 2030676269u, 2034924562u,
    2039096241u, 2043191150u, 2047209133u, 2051150040u, 2055013723u,
    2058800036u, 2062508835u, 2066139983u, 2069693342u, 2073168777u,
    2076566160u, 2079885360u, 2083126254u, 2086288720u, 2089372638u,
    2092377892u, 2095304370u, 2098151960u, 2100920556u, 2103610054u,
    2106220352u, 2108751352u, 2111202959u, 2113575080u, 2115867626u,
    2118080511u, 2120213651u, 2122266967u, 2124240380u, 2126133817u,
    2127947206u, 2129680480u, 2131333572u, 2132906420u, 2134398966u,
    2135811153u, 2137142927u, 2138394240u, 2139565043u, 2140655293u,
    2141664948u, 2142593971u, 2143442326u, 2144209982u, 2144896910u,
    2145503083u, 2146028480u, 2146473080u, 2146836866u, 2147119825u,
    2147321946u, 2147443222u, 2147483648u,
};
static const uint32_t sin_fine_q39[64] = {
    0u, 52707178u, 105414356u, 158121533u, 210828709u, 263535883u, 316243054u,
    368950222u, 421657387u, 474364548u, 527071705u, 579778856u, 632486003u,
    685193144u, 737900278u, 790607405u, 843314526u, 896021638u, 948728743u,
    1001435838u, 1054142925u, 1106850001u, 1159557068u, 1212264124u,
    1264971169u, 1317678202u, 1370385223u, 1423092231u, 1475799226u,
    1528506208u, 1581213176u, 1633920129u, 1686627067u, 1739333990u,
    1792040897u, 1844747787u, 1897454660u, 1950161516u, 2002868354u,
    2055575173u, 2108281974u, 2160988755u, 2213695516u, 2266402257u,
    2319108977u, 2371815676u, 2424522353u, 2477229008u, 2529935640u,
    2582642249u, 2635348833u, 2688055394u, 2740761930u, 2793468441u,
    2846174926u, 2898881385u, 2951587818u, 3004294223u, 3057000601u,
    3109706950u, 3162413271u, 3215119563u, 3267825825u, 3320532057u,
};
static const uint32_t vers_fine_q47[64] = {
    0u, 646814u, 2587258u, 5821330u, 10349030u, 16170360u, 23285318u,
    31693904u, 41396119u, 52391963u, 64681434u, 78264534u, 93141262u,
    109311618u, 126775602u, 145533214u, 165584452u, 186929318u, 209567812u,
    233499932u, 258725678u, 285245051u, 313058051u, 342164676u, 372564927u,
    404258803u, 437246304u, 471527430u, 507102180u, 543970555u, 582132553u,
    621588175u, 662337420u, 704380288u, 747716777u, 792346889u, 838270623u,
    885487977u, 933998952u, 983803547u, 1034901762u, 1087293596u, 1140979049u,
    1195958121u, 1252230810u, 1309797116u, 1368657039u, 1428810579u,
    1490257734u, 1552998504u, 1617032889u, 1682360887u, 1748982499u,
    1816897724u, 1886106560u, 1956609008u, 2028405067u, 2101494736u,
    2175878015u, 2251554902u, 2328525398u, 2406789500u, 2486347210u,
    2567198525u,
};
static const uint16_t atan_q2[129] = {
    0u, 326u, 652u, 978u, 1303u, 1629u, 1954u, 2279u, 2604u, 2929u, 3253u,
    3577u, 3900u, 4223u, 4545u, 4867u, 5188u, 5509u, 5829u, 6148u, 6467u,
    6784u, 7101u, 7418u, 7733u, 8047u, 8361u, 8673u, 8985u, 9296u, 9605u,
    9914u, 10221u, 10527u, 10832u, 11136u, 11439u, 11740u, 12040u, 12339u,
    12637u, 12933u, 13228u, 13522u, 13814u, 14105u, 14394u, 14682u, 14968u,
    15253u, 15537u, 15819u, 16100u, 16379u, 16656u, 16932u, 17206u, 17479u,
    17750u, 18020u, 18288u, 18554u, 18819u, 19083u, 19344u, 19604u, 19862u,
    20119u, 20374u, 20627u, 20879u, 21129u, 21378u, 21624u, 21870u, 22113u,
    22355u, 22595u, 22834u, 23070u, 23306u, 23539u, 23771u, 24001u, 24230u,
    24457u, 24682u, 24906u, 25128u, 25349u, 25568u, 25785u, 26001u, 26215u,
    26427u, 26638u, 26848u, 27056u, 27262u, 27467u, 27670u, 27871u, 28072u,
    28270u, 28467u, 28663u, 28857u, 29050u, 29241u, 29430u, 29619u, 29805u,
    29991u, 30175u, 30357u, 30538u, 30718u, 30896u, 31073u, 31248u, 31423u,
    31595u, 31767u, 31937u, 32106u, 32273u, 32439u, 32604u, 32768u,
};
static const uint16_t isqrt_est[192] = {
    32896u, 33150u, 33402u, 33652u, 33900u, 34147u, 34392u, 34635u, 34876u,
    35116u, 35354u, 35590u, 35825u, 36059u, 36291u, 36521u, 36750u, 36978u,
    37204u, 37429u, 37652u, 37874u, 38095u, 38315u, 38533u, 38750u, 38966u,
    39181u, 39394u, 39606u, 39818u, 40028u, 40237u, 40445u, 40652u, 40857u,
    41062u, 41266u, 41469u, 41671u, 41871u, 42071u, 42270u, 42468u, 42665u,
    42861u, 43057u, 43251u, 43445u, 43637u, 43829u, 44020u, 44210u, 44400u,
    44588u, 44776u, 44963u, 45149u, 45334u, 45519u, 45703u, 45886u, 46069u,
    46250u, 46431u, 46612u, 46791u, 46970u, 47149u, 47326u, 47503u, 47679u,
    47855u, 48030u, 48204u, 48378u, 48551u, 48723u, 48895u, 49067u, 49237u,
    49407u, 49577u, 49746u, 49914u, 50082u, 50249u, 50416u, 50582u, 50747u,
    50912u, 51077u, 51241u, 51404u, 51567u, 51730u, 51892u, 52053u, 52214u,
    52374u, 52534u, 52694u, 52853u, 53011u, 53169u, 53327u, 53484u, 53640u,
    53797u, 53952u, 54108u, 54262u, 54417u, 54571u, 54724u, 54877u, 55030u,
    55182u, 55334u, 55485u, 55636u, 55787u, 55937u, 56087u, 56236u, 56385u,
    56534u, 56682u, 56830u, 56977u, 57124u, 57271u, 57417u, 57563u, 57709u,
    57854u, 57999u, 58143u, 58287u, 58431u, 58574u, 58717u, 58860u, 59002u,
    59144u, 59286u, 59427u, 59568u, 59709u, 59849u, 59989u, 60129u, 60268u,
    60407u, 60546u, 60684u, 60822u, 60960u, 61098u, 61235u, 61372u, 61508u,
    61644u, 61780u, 61916u, 62051u, 62186u, 62321u, 62456u, 62590u, 62724u,
    62857u, 62991u, 63124u, 63256u, 63389u, 63521u, 63653u, 63785u, 63916u,
    64047u, 64178u, 64309u, 64439u, 64569u, 64699u, 64828u, 64957u, 65086u,
    65215u, 65344u, 65472u,
};

/* ---- angles ------------------------------------------------------------ */

/* Scaling and overflow: low 16 bits of the two's complement value (unsigned
 * arithmetic), mapped to [-32768, 32767] without an out-of-range cast. */
fl_angle_t fl_angle_wrap(int32_t a)
{
    uint32_t u = (uint32_t)a & 0xFFFFu;
    if (u >= 0x8000u)
        return (fl_angle_t)((int32_t)u - 65536);
    return (fl_angle_t)u;
}

/* Scaling and overflow: sum/difference in int32 (|.| <= 65535), wrapped. */
fl_angle_t fl_angle_add(fl_angle_t a, fl_angle_t b)
{
    return fl_angle_wrap((int32_t)a + (int32_t)b);
}

fl_angle_t fl_angle_sub(fl_angle_t a, fl_angle_t b)
{
    return fl_angle_wrap((int32_t)a - (int32_t)b);
}

/* Magnitude of an int32 as uint32 (INT32_MIN -> 2^31) and of an int64 as
 * uint64 (INT64_MIN -> 2^63), without signed or unsigned overflow (clean
 * under -fsanitize=integer). */
static uint32_t abs_u32(int32_t v)
{
    return v < 0 ? (uint32_t)(-(v + 1)) + 1u : (uint32_t)v;
}

static uint64_t abs_u64(int64_t v)
{
    return v < 0 ? (uint64_t)(-(v + 1)) + 1u : (uint64_t)v;
}

/* Scaling and overflow: units = mdeg * 65536 / 360000 = mdeg * 1024 / 5625.
 * mdeg is first reduced mod 360000 to [-180000, 180000) (exact, int32);
 * |m * 1024| <= 1.85e8 fits int32; the quotient is rounded to nearest on
 * the magnitude.  Ties cannot occur (2048 mdeg = 5625 (2n + 1) has no
 * solution: even = odd), so the reduction before rounding is exact and
 * "ties away from zero" holds vacuously. */
fl_angle_t fl_angle_from_mdeg(int32_t mdeg)
{
    int32_t m = mdeg % 360000;
    uint32_t q;
    if (m >= 180000)
        m -= 360000;
    else if (m < -180000)
        m += 360000;
    q = (abs_u32(m) * 1024u + 2812u) / 5625u; /* 2812 = floor(5625 / 2) */
    return fl_angle_wrap(m < 0 ? -(int32_t)q : (int32_t)q);
}

/* Scaling and overflow: a * 360000 / 65536 = a * 5625 / 1024; |a * 5625| <=
 * 184320000 fits int32; rounded to nearest on the magnitude, ties (a = 512
 * mod 1024) away from zero.  Range [-180000, 179995]. */
int32_t fl_angle_to_mdeg(fl_angle_t a)
{
    uint32_t q = (abs_u32(a) * 5625u + 512u) >> 10;
    return a < 0 ? -(int32_t)q : (int32_t)q;
}

/* 65536 / (2 pi 10^6) in Q70 (< 2^64), split in 32-bit halves. */
#define URAD_TO_ANGLE_Q70_HI 0xAAE42D79u
#define URAD_TO_ANGLE_Q70_LO 0x9C801418u

/* Scaling and overflow: units = |urad| * K, K = 65536 / (2 pi 10^6) in Q70,
 * as a 31 x 64 -> 96-bit product built from two 32 x 32 -> 64 products;
 * the rounding constant 2^69 is added at bit 37 of the high part, the low
 * 32 bits of the low product cannot change the floor.  Error of the
 * product < 2^-39 unit; K is irrational so exact ties do not occur, and no
 * int32 input lies closer than that to a tie (checked over all 2^32 inputs
 * against a 128-bit reference by fixed.angle_urad_exhaustive_all).  The
 * magnitude (<= 2.24e7 units) is signed and wrapped. */
fl_angle_t fl_angle_from_urad(int32_t urad)
{
    uint32_t u = abs_u32(urad);
    uint64_t lo = (uint64_t)u * URAD_TO_ANGLE_Q70_LO;
    uint64_t hi = (uint64_t)u * URAD_TO_ANGLE_Q70_HI + (lo >> 32) +
                  ((uint64_t)1 << 37);
    int32_t q = (int32_t)((uint32_t)(hi >> 38) & 0xFFFFu);
    return fl_angle_wrap(urad < 0 ? -q : q);
}

/* 2 pi 10^6 / 65536 in Q40 (47 bits). */
#define ANGLE_TO_URAD_Q40 105414357066578u

/* Scaling and overflow: |a| * K, K = 2 pi 10^6 / 65536 in Q40; product
 * <= 2^15 * 2^47 = 2^62 in uint64; rounded to nearest on the magnitude
 * (error of K < 2^-26 urad; ties impossible, K irrational).  Range
 * [-3141593, 3141497]. */
int32_t fl_angle_to_urad(fl_angle_t a)
{
    uint64_t p = (uint64_t)abs_u32(a) * ANGLE_TO_URAD_Q40;
    int32_t q = (int32_t)(uint32_t)((p + ((uint64_t)1 << 39)) >> 40);
    return a < 0 ? -q : q;
}

/* ---- trigonometry ------------------------------------------------------ */

/* sin of x in [0, 16384] units, Q30 (result in [0, 2^30]).
 * Scaling and overflow: i = x / 64 (<= 256), f = x mod 64.  Accumulator in
 * Q39 (uint64): sin_q31[i] << 8 (<= 2^39); minus sin_q31[i] * vers_q47[f]
 * (Q78, < 2^63) >> 39; plus sin_q31[256 - i] * sin_q39[f] (Q70, < 2^63)
 * >> 31.  The truncations cost < 2^-8 LSB each.  Rounded once to Q30 (add
 * half, shift 9).  No saturation needed: the sum is in [0, 2^39 + 1]. */
static uint32_t quarter_sin_q30(uint32_t x)
{
    uint32_t i = x >> 6, f = x & 63u;
    uint64_t acc = (uint64_t)sin_q31[i] << 8;
    acc -= ((uint64_t)sin_q31[i] * vers_fine_q47[f]) >> 39;
    acc += ((uint64_t)sin_q31[256u - i] * sin_fine_q39[f]) >> 31;
    return (uint32_t)((acc + 256u) >> 9);
}

/* sin of x in [0, 16384] units, Q15 before clamping (result in [0, 32768]).
 * Scaling and overflow: Q31 knots; the knot difference (< 2^24) times f
 * (< 64) < 2^30 in uint32, truncated >> 6 (error < 1 Q31 LSB); the Q31 sum
 * (<= 2^31) rounded once to Q15 (add 2^15, shift 16; < 2^32). */
static uint32_t quarter_sin_q15(uint32_t x)
{
    uint32_t i = x >> 6, f = x & 63u;
    uint32_t v = sin_q31[i];
    if (f != 0u)
        v += ((sin_q31[i + 1u] - v) * f) >> 6;
    return (v + 32768u) >> 16;
}

/* Quadrant reduction of a 16-bit angle u in [0, 65535] (unsigned). */
static int32_t sin_q30_u(uint32_t u)
{
    uint32_t r = u & 0x3FFFu;
    int32_t v = (int32_t)quarter_sin_q30((u & 0x4000u) ? 16384u - r : r);
    return (u & 0x8000u) ? -v : v;
}

static int16_t sin_q15_u(uint32_t u)
{
    uint32_t r = u & 0x3FFFu;
    uint32_t m = quarter_sin_q15((u & 0x4000u) ? 16384u - r : r);
    int32_t v = (int32_t)(m > 32767u ? 32767u : m); /* clamp sin(90) */
    return (int16_t)((u & 0x8000u) ? -v : v);
}

/* Scaling and overflow: binary angle in, Q1.15 out, clamped to
 * [-32767, 32767]; 32-bit intermediates (see quarter_sin_q15). */
int16_t fl_sin_q15(fl_angle_t a)
{
    return sin_q15_u((uint32_t)(uint16_t)a);
}

int16_t fl_cos_q15(fl_angle_t a)
{
    return sin_q15_u(((uint32_t)(uint16_t)a + 16384u) & 0xFFFFu);
}

/* Scaling and overflow: binary angle in, Q2.30 out in [-2^30, 2^30];
 * 64-bit Q39 accumulator (see quarter_sin_q30). */
int32_t fl_sin_q30(fl_angle_t a)
{
    return sin_q30_u((uint32_t)(uint16_t)a);
}

int32_t fl_cos_q30(fl_angle_t a)
{
    return sin_q30_u(((uint32_t)(uint16_t)a + 16384u) & 0xFFFFu);
}

/* Scaling and overflow: magnitudes as uint32 (INT32_MIN -> 2^31), swapped
 * so that ay <= ax, both shifted left by the same amount until ax >= 2^31
 * (ay <= ax, so no overflow).  t = ay / den in Q16 with den = ax / 2^16
 * rounded (in [2^15, 2^16]), so t <= 2^17 in uint32, clamped to 2^16.
 * atan(t) in quarter units by interpolation: table (Q2, <= 32768) * 512 +
 * difference (<= 330) * fraction (< 512) < 2^25; rounded once to units
 * (add 2^10, shift 11).  Octant and quadrant reflections in int32, wrapped. */
fl_angle_t fl_atan2(int32_t y, int32_t x)
{
    uint32_t ax = abs_u32(x), ay = abs_u32(y);
    uint32_t den, t, idx, frac, v;
    int32_t ang;
    int swap = ay > ax;
    if (swap) {
        uint32_t tmp = ax;
        ax = ay;
        ay = tmp;
    }
    if (ax == 0u)
        return 0;
    if (ax < 0x10000u) {
        ax <<= 16;
        ay <<= 16;
    }
    if (ax < 0x1000000u) {
        ax <<= 8;
        ay <<= 8;
    }
    if (ax < 0x10000000u) {
        ax <<= 4;
        ay <<= 4;
    }
    if (ax < 0x40000000u) {
        ax <<= 2;
        ay <<= 2;
    }
    if (ax < 0x80000000u) {
        ax <<= 1;
        ay <<= 1;
    }
    den = (ax >> 16) + ((ax >> 15) & 1u);
    t = ay / den;
    if (t > 65536u) /* defensive: den >= ax / 2^16 - 1/2 keeps t <= 65536 */
        t = 65536u;
    idx = t >> 9;
    frac = t & 511u;
    v = (uint32_t)atan_q2[idx] << 9;
    if (frac != 0u)
        v += ((uint32_t)atan_q2[idx + 1u] - atan_q2[idx]) * frac;
    ang = (int32_t)((v + 1024u) >> 11); /* [0, 8192] */
    if (swap)
        ang = 16384 - ang;
    if (x < 0)
        ang = 32768 - ang;
    if (y < 0)
        ang = -ang;
    return fl_angle_wrap(ang);
}

/* ---- roots ------------------------------------------------------------- */

/* Scaling and overflow: y = x * 4^k in [2^30, 2^32) (uint32); estimate e in
 * [2^15, 2^16) from the top 8 bits (relative error <= 2^-8); integer Newton
 * r = (e + floor(y / e)) / 2 (sum < 2^16 + 2^17) is never below
 * floor(sqrt(y)) (AM-GM survives the floors) and at most 1 above it
 * (quadratic convergence: error <= (2^8)^2 / (2 e) <= 1); clamped to 65535
 * so that r * r fits uint32; one downward correction; shift back by k
 * (exact: nested floors).  Proved for all 2^32 inputs by
 * fixed.isqrt32_exhaustive_all. */
uint16_t fl_isqrt32(uint32_t x)
{
    uint32_t y = x, e, r;
    unsigned s = 0;
    if (x == 0u)
        return 0;
    if (y < 0x10000u) {
        y <<= 16;
        s += 8;
    }
    if (y < 0x1000000u) {
        y <<= 8;
        s += 4;
    }
    if (y < 0x10000000u) {
        y <<= 4;
        s += 2;
    }
    if (y < 0x40000000u) {
        y <<= 2;
        s += 1;
    }
    e = isqrt_est[(y >> 24) - 64u];
    r = (e + y / e) >> 1;
    if (r > 65535u)
        r = 65535u;
    if (r * r > y)
        r--;
    return (uint16_t)(r >> s);
}

/* Scaling and overflow: x < 2^32 goes to fl_isqrt32.  Otherwise y = x * 4^k
 * in [2^62, 2^64) (k <= 15); a = floor(sqrt(y / 2^32)) in [2^15, 2^16);
 * remainder rem = y - a^2 2^32 < (2a + 1) 2^32 < 2^49 (uint64); low part
 * b = floor(rem / (a 2^17)) via (rem >> 17) / a, a 32/32 division, never
 * below the true low part and at most 2 above it (the ignored b^2 term is
 * < a 2^17 plus one floor); clamped to 65535; r = a 2^16 + b < 2^32, r^2 in
 * uint64; decremented while r^2 > y (<= 2 steps); shift back by k. */
uint32_t fl_isqrt64(uint64_t x)
{
    uint64_t y = x, rem;
    uint32_t a, b, r;
    unsigned s = 0;
    if (x <= 0xFFFFFFFFu)
        return fl_isqrt32((uint32_t)x);
    if (y < ((uint64_t)1 << 48)) {
        y <<= 16;
        s += 8;
    }
    if (y < ((uint64_t)1 << 56)) {
        y <<= 8;
        s += 4;
    }
    if (y < ((uint64_t)1 << 60)) {
        y <<= 4;
        s += 2;
    }
    if (y < ((uint64_t)1 << 62)) {
        y <<= 2;
        s += 1;
    }
    a = fl_isqrt32((uint32_t)(y >> 32));
    rem = y - ((uint64_t)(a * a) << 32);
    b = (uint32_t)(rem >> 17) / a;
    if (b > 65535u)
        b = 65535u;
    r = (a << 16) + b;
    while ((uint64_t)r * r > y)
        r--;
    return r >> s;
}

/* Scaling and overflow: magnitudes as uint32 (<= 2^31); squares and their
 * sum in uint64 (<= 2^63, exact); isqrt32 when both < 2^15 (sum < 2^31).
 * Result <= floor(2^31.5) = 3037000499. */
uint32_t fl_hypot(int32_t x, int32_t y)
{
    uint32_t ax = abs_u32(x), ay = abs_u32(y);
    if ((ax | ay) < 0x8000u)
        return fl_isqrt32(ax * ax + ay * ay);
    return fl_isqrt64((uint64_t)ax * ax + (uint64_t)ay * ay);
}

/* ---- saturation and rounding ------------------------------------------- */

/* Scaling and overflow: int64 in, compare and clamp, int32 out. */
int32_t fl_sat32(int64_t v)
{
    if (v > INT32_MAX)
        return INT32_MAX;
    if (v < INT32_MIN)
        return INT32_MIN;
    return (int32_t)v;
}

/* Scaling and overflow: int32 in, clamp to [-32768, 32767], int16 out. */
int16_t fl_sat16(int32_t v)
{
    if (v > INT16_MAX)
        return INT16_MAX;
    if (v < INT16_MIN)
        return INT16_MIN;
    return (int16_t)v;
}

/* Scaling and overflow: int32 in, clamp to [0, 255], uint8 out. */
uint8_t fl_satu8(int32_t v)
{
    if (v > 255)
        return 255;
    if (v < 0)
        return 0;
    return (uint8_t)v;
}

/* A magnitude (uint64) with a sign, saturated to int32. */
static int32_t sat_signed_mag(uint64_t m, int neg)
{
    if (neg)
        return m >= 0x80000000u ? INT32_MIN : -(int32_t)(uint32_t)m;
    return m > 0x7FFFFFFFu ? INT32_MAX : (int32_t)(uint32_t)m;
}

/* Scaling and overflow: works on the magnitude |v| as uint64 (<= 2^63, so
 * INT64_MIN is exact); q = (|v| >> shift) + bit (shift - 1) of |v| (the
 * half), which rounds ties away from zero and cannot overflow; sign
 * restored; saturated to int32.  Shifts beyond 62 are exact too (63: +-1
 * when |v| >= 2^62; 64: -1 for INT64_MIN only; >= 65: 0). */
int32_t fl_rshift_round(int64_t v, unsigned shift)
{
    uint64_t m = abs_u64(v);
    uint64_t q;
    if (shift == 0u)
        q = m;
    else if (shift < 64u)
        q = (m >> shift) + ((m >> (shift - 1u)) & 1u);
    else
        q = (shift == 64u && m == ((uint64_t)1 << 63)) ? 1u : 0u;
    return sat_signed_mag(q, v < 0);
}

/* Scaling and overflow: magnitudes |n|, |d| as uint64 (INT64_MIN exact);
 * 32/32-bit division when both fit 32 bits, else 64-bit; round up when the
 * remainder r >= |d| - r (ties away from zero; no overflow); sign restored;
 * saturated to int32 (INT64_MIN / -1 and friends saturate).  d == 0 gives
 * INT32_MAX, INT32_MIN or 0 by the sign of n. */
int32_t fl_div_round(int64_t n, int64_t d)
{
    uint64_t un, ud, q, r;
    if (d == 0)
        return n > 0 ? INT32_MAX : (n < 0 ? INT32_MIN : 0);
    un = abs_u64(n);
    ud = abs_u64(d);
    if ((un | ud) <= 0xFFFFFFFFu) {
        uint32_t n32 = (uint32_t)un, d32 = (uint32_t)ud;
        q = n32 / d32;
        r = n32 % d32;
    } else {
        q = un / ud;
        r = un % ud;
    }
    if (r >= ud - r)
        q++;
    return sat_signed_mag(q, (n < 0) != (d < 0));
}

/* Scaling and overflow: int32 division (C99 truncates toward zero), then one
 * step down when the remainder is nonzero and n < 0.  d > 0 so n / d cannot
 * overflow and |result| <= |n|.  d <= 0 returns 0. */
int32_t fl_floor_div(int32_t n, int32_t d)
{
    int32_t q, r;
    if (d <= 0)
        return 0;
    q = n / d;
    r = n % d;
    if (r != 0 && n < 0)
        q--;
    return q;
}

/* Scaling and overflow: int32 x int32 -> int64 product (|p| <= 2^62, exact);
 * + 2^14 - (p < 0), then arithmetic shift right 15 (floor): this is round
 * to nearest with ties away from zero for both signs, so mul_q15(-a, b) ==
 * -mul_q15(a, b); |p + 2^14| < 2^63; saturated to int32. */
int32_t fl_mul_q15(int32_t a, int32_t b)
{
    int64_t p = (int64_t)a * b;
    return fl_sat32((p + 16384 - (p < 0)) >> 15);
}

/* Scaling and overflow: as fl_mul_q15 with shift 30 and half 2^29. */
int32_t fl_mul_q30(int32_t a, int32_t b)
{
    int64_t p = (int64_t)a * b;
    return fl_sat32((p + 536870912 - (p < 0)) >> 30);
}
