/*
 * fieldloc/fixed.h - fixed-point core: binary angles, table trigonometry,
 * atan2, integer square roots, saturating and rounding helpers.
 *
 * Formats are named as in CMSIS-DSP: Qm.n has m integer bits (sign included)
 * and n fraction bits.  "Q15" below is Q1.15 in an int16_t (or int32_t),
 * "Q30" is Q2.30 in an int32_t.
 *
 * Binary angles (fl_angle_t): 65536 units per turn, stored in an int16_t as
 * [-32768, 32767], i.e. [-180 deg, +180 deg).  One unit = 360/65536 deg
 * (about 0.0055 deg).  Addition and subtraction wrap for free when done with
 * fl_angle_add / fl_angle_sub / fl_angle_wrap (never by casting a
 * possibly-out-of-range int to int16_t, which is implementation-defined).
 *
 * No function here allocates, uses floating point or touches global state.
 */
#ifndef FIELDLOC_FIXED_H
#define FIELDLOC_FIXED_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef int16_t fl_angle_t;

#define FL_ANGLE_TURN   65536L   /* units per full turn (not representable) */
#define FL_ANGLE_180    (-32768) /* -180 deg == +180 deg */
#define FL_ANGLE_90     16384
#define FL_ANGLE_45     8192

/* ---- angles ------------------------------------------------------------ */

/* a modulo 65536, mapped to [-32768, 32767].  Defined for every int32. */
fl_angle_t fl_angle_wrap(int32_t a);
fl_angle_t fl_angle_add(fl_angle_t a, fl_angle_t b);   /* a + b, wrapped */
fl_angle_t fl_angle_sub(fl_angle_t a, fl_angle_t b);   /* a - b, wrapped */

/* Millidegrees <-> binary angle.  from: any int32 millidegrees, wrapped to a
 * turn, rounded to nearest (ties away from zero).  to: [-180000, 179995]. */
fl_angle_t fl_angle_from_mdeg(int32_t mdeg);
int32_t fl_angle_to_mdeg(fl_angle_t a);

/* Microradians <-> binary angle, same rounding; from: any int32 urad.
 * to: [-3141593, 3141497]. */
fl_angle_t fl_angle_from_urad(int32_t urad);
int32_t fl_angle_to_urad(fl_angle_t a);

/* ---- trigonometry ------------------------------------------------------ */

/* sin/cos in Q1.15.  The exact value is clamped to [-32767, 32767] (so
 * sin(90 deg) = 32767); error <= 2 LSB against round(32768*sin) over all
 * 65536 inputs (tested exhaustively). */
int16_t fl_sin_q15(fl_angle_t a);
int16_t fl_cos_q15(fl_angle_t a);

/* sin/cos in Q2.30 for geometry that needs more than 15 bits (camera
 * projection).  Range [-2^30, 2^30]; absolute error documented in fixed.c
 * and tested exhaustively against double. */
int32_t fl_sin_q30(fl_angle_t a);
int32_t fl_cos_q30(fl_angle_t a);

/* Angle of the vector (x, y), i.e. atan2(y, x), as a binary angle.
 * Any int32 inputs, INT32_MIN included; atan2(0, 0) = 0.
 * Max error < 0.02 deg (tested against double). */
fl_angle_t fl_atan2(int32_t y, int32_t x);

/* ---- roots ------------------------------------------------------------- */

/* floor(sqrt(x)), exact for every input. */
uint16_t fl_isqrt32(uint32_t x);
uint32_t fl_isqrt64(uint64_t x);

/* floor(sqrt(x*x + y*y)), exact for every int32 pair (result < 2^32). */
uint32_t fl_hypot(int32_t x, int32_t y);

/* ---- saturation and rounding ------------------------------------------- */

int32_t fl_sat32(int64_t v);        /* clamp to [INT32_MIN, INT32_MAX] */
int16_t fl_sat16(int32_t v);        /* clamp to [INT16_MIN, INT16_MAX] */
uint8_t fl_satu8(int32_t v);        /* clamp to [0, 255] */

/* v / 2^shift rounded to nearest, ties away from zero; shift in [0, 62].
 * Result saturated to int32. */
int32_t fl_rshift_round(int64_t v, unsigned shift);

/* n / d rounded to nearest, ties away from zero, saturated to int32;
 * d == 0 gives INT32_MAX, INT32_MIN or 0 by the sign of n. */
int32_t fl_div_round(int64_t n, int64_t d);

/* floor(n / d) for d > 0 (floor division: no double-width cell at zero);
 * d <= 0 returns 0. */
int32_t fl_floor_div(int32_t n, int32_t d);

/* a * b for a in Q15 (or any int32) and b in Q15: (a*b) >> 15, rounded,
 * saturated to int32.  Intermediate 64 bit. */
int32_t fl_mul_q15(int32_t a, int32_t b);
/* a * b >> 30, rounded, saturated; a any int32, b Q30.  Intermediate 64 bit. */
int32_t fl_mul_q30(int32_t a, int32_t b);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_FIXED_H */
