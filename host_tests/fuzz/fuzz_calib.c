/* libFuzzer harness: arbitrary bytes through the calibration text parser
 * (fl_calib_parse, src/model/calib.c; no NUL terminator, embedded NULs and
 * overlong lines included) and the `fieldloc calibrate --frames` list parser
 * (cf_frames_parse, tools/eval/calib_frames.c).  A calibration that parses
 * must hold in-range values and survive fl_calib_format -> fl_calib_parse
 * unchanged; an error must name a line within the text; a frame list that
 * parses must hold finite numbers and non-empty image paths. */
#include "eval/calib_frames.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fl_calib_t c, d;
    int32_t line = -1, lines = 1;
    const char *why = NULL;
    char buf[FL_CALIB_TEXT_MAX], err[256], *text;
    size_t i, n;
    cf_frames_t fr;
    fl_status_t st = fl_calib_parse((const char *)data, size, &c, &line, &why);
    for (i = 0; i < size; i++)
        lines += data[i] == '\n';
    if (why == NULL || line < 0 || line > lines)
        abort();
    if (st == FL_OK) {
        const int32_t amax = FL_CALIB_MAX_OFFSET_DEG * 65536L / 360;
        if (((c.has & FL_CALIB_HAS_NECK) &&
             (c.neck_height_mm < FL_CAMERA_NECK_MIN_MM || c.neck_height_mm > FL_CAMERA_NECK_MAX_MM)) ||
            c.pitch_offset < -amax || c.pitch_offset > amax || c.roll_offset < -amax ||
            c.roll_offset > amax)
            abort();
        n = fl_calib_format(&c, buf, sizeof buf);
        if (n == 0 || fl_calib_parse(buf, n, &d, &line, NULL) != FL_OK ||
            memcmp(&c, &d, sizeof c) != 0)
            abort();
    } else if (c.has != 0) {
        abort();
    }
    text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    if (cf_frames_parse(text, size, "fuzz", "base", &fr, err, (int)sizeof err) == 0) {
        int k;
        if (fr.n <= 0 || fr.n > CF_MAX_FRAMES)
            abort();
        for (k = 0; k < fr.n; k++)
            if (fr.f[k].image[0] == 0 || !isfinite(fr.f[k].x_mm) || !isfinite(fr.f[k].y_mm) ||
                !isfinite(fr.f[k].heading_deg) || !isfinite(fr.f[k].head_pitch_deg) ||
                !isfinite(fr.f[k].torso_roll_deg))
                abort();
        cf_frames_free(&fr);
    }
    free(text);
    return 0;
}
