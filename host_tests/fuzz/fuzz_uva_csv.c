/* libFuzzer harness: arbitrary text through the UvA 2013 annotation parser
 * (uva2013_annotations.csv) and the physar pose parser. */
#include "io/realdata.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), err[128];
    rd_uva_set_t uva;
    rd_physar_set_t ph;
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    if (rd_uva_parse(text, &uva, err, sizeof err) == 0)
        rd_uva_free(&uva);
    if (rd_physar_parse(text, &ph, err, sizeof err) == 0)
        rd_physar_free(&ph);
    free(text);
    return 0;
}
