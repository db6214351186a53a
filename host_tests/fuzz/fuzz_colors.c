/* libFuzzer harness: arbitrary bytes through the colour text parser
 * (fl_color_params_parse, src/vision/color_file.c; no NUL terminator,
 * embedded NULs and overlong lines included), over the defaults.  A text
 * that parses must give params fl_color_init accepts and that survive
 * fl_color_params_format -> fl_color_params_parse unchanged; an error must
 * name a line within the text, give a reason and leave the params as they
 * were. */
#include "fieldloc/fieldloc.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fl_color_params_t p, d, q;
    int32_t line = -1, lines = 1;
    const char *why = NULL;
    char buf[FL_COLOR_TEXT_MAX];
    size_t i, n;
    fl_status_t st;
    fl_color_params_default(&p);
    d = p;
    st = fl_color_params_parse((const char *)data, size, &p, &line, &why);
    for (i = 0; i < size; i++)
        lines += data[i] == '\n';
    if (why == NULL || line < 0 || line > lines)
        abort();
    if (st == FL_OK) {
        if (fl_color_params_check(&p, NULL) != FL_OK)
            abort();
        n = fl_color_params_format(&p, buf, sizeof buf);
        memset(&q, 0, sizeof q);
        if (n == 0 || fl_color_params_parse(buf, n, &q, &line, NULL) != FL_OK ||
            memcmp(&p, &q, sizeof p) != 0)
            abort();
    } else if (why[0] == '\0' || memcmp(&p, &d, sizeof p) != 0) {
        abort();
    }
    return 0;
}
