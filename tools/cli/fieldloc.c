/*
 * tools/cli/fieldloc.c - the host command-line tool (never linked into the
 * firmware).  Each subcommand lives in its own tools/ file; the list is in
 * registry.h.  `fieldloc` alone prints the list.
 */
#include "cli/registry.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "eval_detect" -> "eval-detect" (command names use dashes on the command
 * line, underscores in C). */
static const char *dashed(const char *name)
{
    static char buf[64];
    size_t i;
    for (i = 0; name[i] && i + 1 < sizeof buf; i++)
        buf[i] = name[i] == '_' ? '-' : name[i];
    buf[i] = 0;
    return buf;
}

static void usage(void)
{
    fprintf(stderr, "usage: fieldloc COMMAND ...\n");
#define FL_USAGE(name, help)                                                 \
    fprintf(stderr, "  %-12s %s%s\n", dashed(#name), help, cmd_##name ? "" : " [not built yet]");
    FL_COMMANDS(FL_USAGE)
}

int main(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
        usage();
        return argc < 2 ? 2 : 0;
    }
#define FL_DISPATCH(name, help)                                              \
    if (!strcmp(argv[1], #name) ||                                           \
        (strchr(#name, '_') && !strcmp(argv[1], dashed(#name)))) {          \
        if (!cmd_##name) {                                                   \
            fprintf(stderr, "fieldloc: %s is not built yet\n", argv[1]);     \
            return 2;                                                        \
        }                                                                    \
        return cmd_##name(argc - 2, argv + 2);                               \
    }
    FL_COMMANDS(FL_DISPATCH)
    fprintf(stderr, "fieldloc: unknown command %s\n", argv[1]);
    usage();
    return 2;
}
