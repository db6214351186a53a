#!/usr/bin/env python3
"""tools/build/gen_hsv_tables.py - prints the two static const tables of src/vision/color.c
that make fl_hsv_from_rgb equal to OpenCV's 8-bit RGB->HSV (hue 0..179).

OpenCV (modules/imgproc/src/color_hsv.simd.hpp, RGB2HSV_b) builds, with
hsv_shift = 12:
    sdiv_table[i]    = saturate_cast<int>((255 << 12) / (1.0 * i))
    hdiv_table180[i] = saturate_cast<int>((180 << 12) / (6.0 * i))
saturate_cast<int>(double) is cvRound: round to nearest, ties to even.  No
quotient here is a tie (checked below), so round-half-up in exact integer
arithmetic gives the same values:  (2 * num + den) // (2 * den).
Usage: python3 tools/build/gen_hsv_tables.py > /tmp/t.c, paste into src/vision/color.c
(the host test color.hsv_tables recomputes them in double with rint()).
"""

def table(num, den_mul):
    out = [0]
    for i in range(1, 256):
        den = den_mul * i
        assert (2 * num) % (2 * den) != den, "tie"  # cvRound ties never occur
        out.append((2 * num + den) // (2 * den))
    return out

def emit(name, vals):
    print("static const int32_t %s[256] = {" % name)
    for k in range(0, 256, 8):
        print("    " + ", ".join("%d" % v for v in vals[k:k + 8]) + ",")
    print("};")

emit("hsv_sdiv", table(255 << 12, 1))
emit("hsv_hdiv", table(180 << 12, 6))
