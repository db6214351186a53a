/*
 * tools/cli/cmd_reliability.c - `fieldloc reliability`: the reliability
 * diagram of a localizer (tools/loc/reliab.h) over simulated walks, and the
 * calibration contract of include/fieldloc/localizer.h checked.
 *
 *   fieldloc reliability [--localizer fuzzy] [--fields F,F,...]
 *                        [--seeds N,N,...] [--frame-seeds N,N,...]
 *                        [--obs-cache-dir DIR] [--steps N] [--dump FILE.tsv]
 *
 * Walks: the built-in walk of every field (default spl2013, uva2013,
 * aibo2004) with each seed of --seeds in feature mode (default 1,2,3) and
 * each of --frame-seeds in frames mode (rendered frames through vision at
 * 10 Hz, the parameters of `simulate --frames`; default 1,2,3; "" or "-":
 * none).  The defaults are the held-out seeds: the calibration in src was
 * fitted on others (11 and up).  --obs-cache-dir DIR: frames mode reads (or
 * writes) the vision observations of walk F, seed S in DIR/F.S.obs
 * (simulate --obs-cache), so nothing is rendered twice.
 *
 * Prints the diagram for feature mode, frames mode and all records: per
 * bin of reported reliability (0-0.1 ... 0.9-1.0) the records and the
 * share within 500 mm and 20 deg of the truth (the plain truth: the wrong
 * half is wrong), the cumulative check share(reliability >= r) >= r at
 * r = 0, 0.1, ..., 0.9 and the exact worst case over every reported r.
 * Exit status 1 when the contract fails for feature mode, frames mode or
 * all records; 2 on bad arguments or a failed walk.
 * --uncalibrated diagrams the localizer's own measure (score_q16: fuzzy,
 * the grid's consistency x compactness x (1 - bias) x uniqueness) instead
 * of the reliability: what the calibration starts from.
 * --dump FILE.tsv writes every record (tools/build/fit_reliability.py fits
 * the calibration from such a file).
 */
#include "loc/reliab.h"
#include "cli/args.h"
#include "cli/registry.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RB_MAX_LIST 64

/* A comma-separated list of seeds 0..65535 ("" or "-": none) for option
 * opt: its length, or -1 (one message printed, as for every number of the
 * CLI) for an item that is not such a seed or more than max items. */
static int parse_list(const char *opt, const char *s, long *v, int max)
{
    char item[32];
    int n = 0;
    if (!strcmp(s, "-") || *s == '\0')
        return 0;
    for (;;) {
        const char *comma = strchr(s, ',');
        size_t len = comma ? (size_t)(comma - s) : strlen(s);
        if (n == max) {
            fprintf(stderr, "fieldloc reliability: %s: more than %d seeds\n", opt, max);
            return -1;
        }
        if (len >= sizeof item)
            len = sizeof item - 1; /* still not a seed: arg_long says so */
        memcpy(item, s, len);
        item[len] = '\0';
        if (arg_long("reliability", opt, item, 0, 65535, NULL, &v[n]) != 0)
            return -1;
        n++;
        if (!comma)
            return n;
        s = comma + 1;
    }
}

static void usage(void)
{
    fprintf(stderr, "usage: fieldloc reliability [--localizer fuzzy] [--fields F,F,...]\n"
                    "                            [--seeds N,...] [--frame-seeds N,...]\n"
                    "                            [--obs-cache-dir DIR] [--steps N] "
                    "[--dump FILE.tsv] [--uncalibrated]\n");
}

int cmd_reliability(int argc, char **argv)
{
    const char *localizer = NULL, *fields = "spl2013,uva2013,aibo2004", *cache_dir = NULL;
    const char *dump = NULL, *seeds_s = "1,2,3", *fseeds_s = "1,2,3";
    const char *fname[16];
    char fbuf[256], err[256], path[1200], *tok, *save = NULL;
    long seeds[RB_MAX_LIST], fseeds[RB_MAX_LIST], steps = -1;
    int nseeds, nfseeds, nf = 0, k, i, mode, rc = 0, uncal = 0;
    long r;
    const fl_localizer_t *loc;
    rb_set_t set;

    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--localizer") && k + 1 < argc)
            localizer = argv[++k];
        else if (!strcmp(argv[k], "--fields") && k + 1 < argc)
            fields = argv[++k];
        else if (!strcmp(argv[k], "--seeds") && k + 1 < argc)
            seeds_s = argv[++k];
        else if (!strcmp(argv[k], "--frame-seeds") && k + 1 < argc)
            fseeds_s = argv[++k];
        else if (!strcmp(argv[k], "--obs-cache-dir") && k + 1 < argc)
            cache_dir = argv[++k];
        else if (!strcmp(argv[k], "--uncalibrated"))
            uncal = 1;
        else if (!strcmp(argv[k], "--dump") && k + 1 < argc)
            dump = argv[++k];
        else if (!strcmp(argv[k], "--steps") && k + 1 < argc) {
            if (arg_long("reliability", "--steps", argv[++k], 0, 100000000L, NULL, &steps) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            usage();
            return 0;
        } else
            return arg_unknown("reliability", argv[k],
                               "--localizer=1 --fields=1 --seeds=1 --frame-seeds=1 "
                               "--obs-cache-dir=1 --dump=1 --steps=1");
    }
    nseeds = parse_list("--seeds", seeds_s, seeds, RB_MAX_LIST);
    nfseeds = parse_list("--frame-seeds", fseeds_s, fseeds, RB_MAX_LIST);
    if (nseeds < 0 || nfseeds < 0)
        return 2;
    if (nseeds + nfseeds == 0) {
        fprintf(stderr, "fieldloc reliability: no walk (--seeds and --frame-seeds both empty)\n");
        return 2;
    }
    if ((loc = lr_localizer(localizer, err, (int)sizeof err)) == NULL) {
        fprintf(stderr, "reliability: %s\n", err);
        return 2;
    }
    if (strlen(fields) >= sizeof fbuf) {
        fprintf(stderr, "fieldloc reliability: --fields: list too long\n");
        return 2;
    }
    snprintf(fbuf, sizeof fbuf, "%s", fields);
    for (tok = strtok_r(fbuf, ",", &save); tok != NULL && nf < 16;
         tok = strtok_r(NULL, ",", &save))
        fname[nf++] = tok;
    if (tok != NULL) {
        fprintf(stderr, "fieldloc reliability: --fields: more than 16 fields\n");
        return 2;
    }
    if (nf == 0) {
        usage();
        return 2;
    }
    memset(&set, 0, sizeof set);
    printf("# reliability of localizer %s: fields %s; feature seeds %s; frame seeds %s\n",
           loc->name, fields, nseeds ? seeds_s : "none", nfseeds ? fseeds_s : "none");
    fflush(stdout);
    for (mode = 0; mode < 2; mode++) {
        int ns = mode ? nfseeds : nseeds;
        for (i = 0; i < nf; i++)
            for (k = 0; k < ns; k++) {
                long s = mode ? fseeds[k] : seeds[k];
                const char *cache = NULL;
                if (mode && cache_dir != NULL) {
                    snprintf(path, sizeof path, "%s/%s.%ld.obs", cache_dir, fname[i], s);
                    cache = path;
                }
                if (rb_walk(&set, loc, fname[i], i, s, mode, cache, steps, err,
                            (int)sizeof err) != 0) {
                    fprintf(stderr, "reliability: %s seed %ld %s: %s\n", fname[i], s,
                            mode ? "frames" : "features", err);
                    rb_free(&set);
                    return 2;
                }
            }
    }
    if (uncal) {
        printf("# --uncalibrated: the diagram of score_q16, the localizer's own measure\n");
        for (r = 0; r < set.n; r++)
            set.rec[r].est.reliability_q16 = set.rec[r].est.score_q16;
    }
    if (nseeds > 0)
        rc |= rb_print(stdout, &set, 0, "feature mode");
    if (nfseeds > 0)
        rc |= rb_print(stdout, &set, 1, "frames mode");
    if (nseeds > 0 && nfseeds > 0)
        rc |= rb_print(stdout, &set, -1, "all records");
    if (dump != NULL) {
        FILE *f = fopen(dump, "w");
        if (f == NULL) {
            fprintf(stderr, "reliability: cannot write %s\n", dump);
            rc = 2;
        } else {
            rb_dump(f, &set, fname);
            fclose(f);
        }
    }
    printf("reliability contract %s\n", rc == 0 ? "met" : rc == 1 ? "FAILS" : "unchecked");
    rb_free(&set);
    return rc;
}
