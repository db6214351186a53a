/* libFuzzer harness: arbitrary text through the fixture readers (truth and
 * scene files). */
#include "world/render.h"
#include "world/truth.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[128];
    FILE *f;
    truth_t *t;
    render_scene_t sc;
    if (size == 0)
        return 0;
    t = malloc(sizeof *t);
    if (!t)
        return 0;
    f = fmemopen((void *)data, size, "r");
    if (f) {
        (void)truth_read(f, t, err, sizeof err);
        fclose(f);
    }
    f = fmemopen((void *)data, size, "r");
    if (f) {
        (void)render_scene_read(f, &sc, err, sizeof err);
        fclose(f);
    }
    free(t);
    return 0;
}
