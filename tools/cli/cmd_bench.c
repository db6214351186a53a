/* tools/cli/cmd_bench.c - `fieldloc bench`: runs every benchmark section listed
 * in registry.h and writes rows name<TAB>fieldloc_ns<TAB>peer_ns<TAB>speedup. */
#include "cli/args.h"
#include "cli/registry.h"

#include <stdio.h>
#include <string.h>

int cmd_bench(int argc, char **argv)
{
    const char *out = "build/bench.tsv";
    bench_ctx_t ctx = {NULL, 0};
    const char *only = NULL;
    int k, ran = 0;
    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--out") && k + 1 < argc)
            out = argv[++k];
        else if (!strcmp(argv[k], "--only") && k + 1 < argc)
            only = argv[++k];
        else if (!strcmp(argv[k], "--quick"))
            ctx.quick = 1;
        else if (!strcmp(argv[k], "--noise-frames") && k + 1 < argc)
            return bench_vision_write_noise && bench_vision_write_noise(argv[k + 1]) == 0 &&
                           (!bench_scan_write_noise || bench_scan_write_noise(argv[k + 1]) == 0)
                       ? 0
                       : 1;
        else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            fprintf(stderr, "usage: fieldloc bench [--out FILE.tsv] [--quick] [--only SECTION] [--noise-frames DIR]\n"
                    "  sections: fixed scan vision adversarial fuzzy\n");
            return 0;
        } else
            return arg_unknown("bench", argv[k], "--out=1 --only=1 --noise-frames=1");
    }
    ctx.tsv = fopen(out, "w");
    if (!ctx.tsv) {
        perror(out);
        return 1;
    }
    fprintf(ctx.tsv, "name\tfieldloc_ns\tpeer_ns\tspeedup\n");
    printf("%-28s %12s %12s %8s  peer\n", "name", "fieldloc_ns", "peer_ns", "speedup");
#define FL_RUN_BENCH(name)                                                   \
    if (bench_##name && (!only || !strcmp(only, #name))) {                   \
        bench_##name(&ctx);                                                  \
        ran++;                                                               \
    }
    FL_BENCHES(FL_RUN_BENCH)
    fclose(ctx.tsv);
    printf("wrote %s (%d sections; times in ns per call or per frame as named)\n", out, ran);
    return 0;
}

