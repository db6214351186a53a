/* libFuzzer harness: arbitrary text through the UvA 2013 annotation parser
 * (uva2013_annotations.csv), the physar pose parser and the modern-frame
 * label parser (tools/eval/realdata_modern.csv). */
#include "io/realdata.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), err[128];
    rd_uva_set_t uva;
    rd_physar_set_t ph;
    rd_modern_set_t mo;
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    if (rd_uva_parse(text, &uva, err, sizeof err) == 0)
        rd_uva_free(&uva);
    if (rd_physar_parse(text, &ph, err, sizeof err) == 0)
        rd_physar_free(&ph);
    if (rd_modern_parse(text, &mo, err, sizeof err) == 0) {
        int i, k;
        /* an accepted record names a known camera and its labels lie in
         * that camera's image */
        for (i = 0; i < mo.n; i++) {
            const fl_camera_model_t *m = fl_camera_model_find(mo.rec[i].camera);
            if (!m || mo.rec[i].n_features < 0 || mo.rec[i].n_features > RD_MODERN_MAX_FEATURES)
                abort();
            for (k = 0; k < mo.rec[i].n_features; k++)
                if (!(mo.rec[i].feat[k].u >= -0.5 && mo.rec[i].feat[k].u <= m->width_px - 0.5 &&
                      mo.rec[i].feat[k].v >= -0.5 && mo.rec[i].feat[k].v <= m->height_px - 0.5))
                    abort();
        }
        rd_modern_free(&mo);
    }
    free(text);
    return 0;
}
