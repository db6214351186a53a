/* tools/cmd_bench.c - `fieldloc bench`: runs every benchmark section listed
 * in registry.h and writes rows name<TAB>fieldloc_ns<TAB>peer_ns<TAB>speedup. */
#include "registry.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

double bench_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

void bench_row(bench_ctx_t *ctx, const char *name, double fl_ns, double peer_ns,
               const char *peer_desc)
{
    double speedup = peer_ns > 0 && fl_ns > 0 ? peer_ns / fl_ns : 0;
    if (ctx->tsv) {
        if (peer_ns > 0)
            fprintf(ctx->tsv, "%s\t%.1f\t%.1f\t%.2f\n", name, fl_ns, peer_ns, speedup);
        else
            fprintf(ctx->tsv, "%s\t%.1f\t-\t-\n", name, fl_ns);
        fflush(ctx->tsv);
    }
    if (peer_ns > 0)
        printf("%-28s %12.1f %12.1f %8.2f  %s\n", name, fl_ns, peer_ns, speedup, peer_desc ? peer_desc : "");
    else
        printf("%-28s %12.1f %12s %8s  %s\n", name, fl_ns, "-", "-", peer_desc ? peer_desc : "");
    fflush(stdout);
}

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
        else {
            fprintf(stderr, "usage: fieldloc bench [--out FILE.tsv] [--quick] [--only SECTION] [--noise-frames DIR]\n"
                    "  sections: fixed scan vision adversarial fuzzy\n");
            return 2;
        }
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

