/* libFuzzer harness: arbitrary bytes through the host PPM reader. */
#include "io/ppm.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    host_image_t img;
    char err[128];
    FILE *f;
    if (size == 0)
        return 0;
    f = fmemopen((void *)data, size, "rb");
    if (!f)
        return 0;
    if (ppm_read_file(f, "fuzz", &img, err, sizeof err) == 0) {
        /* touch every pixel: a wrong size would show under ASan */
        size_t i, n = (size_t)img.width * (size_t)img.height * 3;
        unsigned s = 0;
        for (i = 0; i < n; i++)
            s += img.rgb[i];
        (void)s;
        host_image_free(&img);
    }
    fclose(f);
    return 0;
}
