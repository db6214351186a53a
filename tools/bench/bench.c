/* tools/bench/bench.c - the clock and the row writer of bench.h. */
#include "bench/bench.h"

#include <stdio.h>
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
