/*
 * tools/cli/cmd_colors.c - `fieldloc colors [--out FILE]`: the default colour
 * classes as a colour file (fieldloc/color.h's text) with a comment per key,
 * on stdout or into FILE, to be edited at a venue and read back with
 * `fieldloc detect|scan|localize --colors FILE` (or by the firmware through
 * fl_color_params_parse) without rebuilding.
 */
#include "eval/detect.h"
#include "cli/args.h"
#include "cli/registry.h"

#include <stdio.h>
#include <string.h>

static int colors_usage(void)
{
    fprintf(stderr, "usage: fieldloc colors [--out FILE]\n"
                    "  prints the default colour file (fieldloc-colors 1), one comment per key\n");
    return 2;
}

int cmd_colors(int argc, char **argv)
{
    const char *out = NULL;
    char text[FL_COLOR_TEXT_MAX];
    fl_color_params_t p;
    size_t n;
    int i;
    FILE *f;
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            colors_usage();
            return 0;
        } else
            return arg_unknown("colors", argv[i], "--out=1");
    }
    fl_color_params_default(&p);
    n = det_colors_text(&p, text, sizeof text);
    if (n == 0) {
        fprintf(stderr, "fieldloc colors: the defaults do not fit a colour file\n");
        return 1;
    }
    f = out ? fopen(out, "w") : stdout;
    if (!f) {
        fprintf(stderr, "fieldloc colors: %s: cannot write\n", out);
        return 1;
    }
    if (fwrite(text, 1, n, f) != n || (out && fclose(f) != 0)) {
        fprintf(stderr, "fieldloc colors: %s: cannot write\n", out ? out : "stdout");
        return 1;
    }
    return 0;
}
