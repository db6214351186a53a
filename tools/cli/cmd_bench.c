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
    const char *loc_frames = NULL, *param[64];
    long repeat = 1, k_obs = 5;
    int k, ran = 0, n_param = 0, vision = 0;
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
        else if (!strcmp(argv[k], "--loc-list"))
            return bench_loc_list ? bench_loc_list() : 1;
        else if (!strcmp(argv[k], "--loc-frames") && k + 1 < argc)
            loc_frames = argv[++k];
        else if (!strcmp(argv[k], "--repeat") && k + 1 < argc) {
            if (arg_long("bench", "--repeat", argv[++k], 0, 1000000, NULL, &repeat) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--obs") && k + 1 < argc) {
            if (arg_long("bench", "--obs", argv[++k], 1, 16, NULL, &k_obs) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--vision"))
            vision = 1;
        else if (!strcmp(argv[k], "--param") && k + 1 < argc) {
            if (n_param == 64)
                return 2;
            param[n_param++] = argv[++k];
        } else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            fprintf(stderr, "usage: fieldloc bench [--out FILE.tsv] [--quick] [--only SECTION] [--noise-frames DIR]\n"
                    "       fieldloc bench --loc-list\n"
                    "       fieldloc bench --loc-frames NAME [--repeat N] [--obs K] [--vision]\n"
                    "                      [--param NAME=VALUE]...\n"
                    "  sections: fixed scan vision skeleton hlvision corners adversarial fuzzy loc coach\n"
                    "  --loc-frames: N frames (predict, update with K observations, estimate) of\n"
                    "  localizer NAME after 10 s of the spl2013 walk, for callgrind\n"
                    "  (tools/bench/callgrind_loc.sh); --vision: the vision preset, a view\n");
            return 0;
        } else
            return arg_unknown("bench", argv[k], "--out=1 --only=1 --noise-frames=1 --loc-list=0 "
                                                 "--loc-frames=1 --repeat=1 --obs=1 --param=1");
    }
    if (loc_frames != NULL)
        return bench_loc_repeat ? bench_loc_repeat(loc_frames, param, n_param, repeat, (int)k_obs,
                                                   vision)
                                : 1;
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

