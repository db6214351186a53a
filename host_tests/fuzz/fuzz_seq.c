/* libFuzzer harness: arbitrary text through the `fieldloc localize`
 * sequence-file parser (lr_seq_parse, tools/loc/locrun.c): header lines, frame
 * lines with odometry and head angles, the optional prior, comments, long
 * lines and long paths.  A parse that succeeds must give a consistent
 * sequence (known field and camera, 0 <= n <= cap, finite numbers). */
#include "loc/locrun.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), err[128];
    lr_seq_t s;
    int k;
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    if (lr_seq_parse(text, "base/dir", &s, err, (int)sizeof err) == 0) {
        if (s.field == NULL || s.camera == NULL || s.n < 0 || s.n > s.cap)
            abort();
        for (k = 0; k < s.n; k++)
            if (!isfinite(s.frame[k].odo_dx_mm) || !isfinite(s.frame[k].odo_dy_mm) ||
                !isfinite(s.frame[k].odo_dtheta_deg) || !isfinite(s.frame[k].head_pitch_rad) ||
                !isfinite(s.frame[k].head_yaw_rad) || s.frame[k].image[0] == 0)
                abort();
        lr_seq_free(&s);
    }
    free(text);
    return 0;
}
