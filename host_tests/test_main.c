/* host_tests/test_main.c - runner and harness implementation. */
#include "test.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int t_quick = 0;
int t_exhaustive = 0;

/* -k filters: a case runs when its name contains any of them (none given:
 * every case runs). */
#define T_FILTER_MAX 16
static const char *t_filters[T_FILTER_MAX];
static int t_nfilters = 0;

static int t_selected(const char *name)
{
    int k;
    if (t_nfilters == 0)
        return 1;
    for (k = 0; k < t_nfilters; k++)
        if (strstr(name, t_filters[k]))
            return 1;
    return 0;
}
static int t_passed, t_failed, t_cur_failed;
static const char *t_cur_name;

void t_check(int ok, const char *expr, const char *file, int line)
{
    if (ok)
        return;
    if (t_cur_failed < 5)
        printf("  at %s:%d: %s\n", file, line, expr);
    t_cur_failed++;
}

void t_fail_msg(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    if (t_cur_failed < 5) {
        printf("  at %s:%d: ", file, line);
        va_start(ap, fmt);
        vprintf(fmt, ap);
        va_end(ap);
        printf("\n");
    }
    t_cur_failed++;
}

void t_info(const char *fmt, ...)
{
    va_list ap;
    printf("# %s: ", t_cur_name ? t_cur_name : "-");
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
}

void t_digest(const char *label, uint32_t h)
{
    printf("digest %s 0x%08lx\n", label, (unsigned long)h);
}

void t_golden_load(t_golden_t *g, const char *path)
{
    FILE *f = fopen(path, "r");
    char buf[T_GOLDEN_LINE_MAX];
    g->n = 0;
    g->line = calloc(T_GOLDEN_LINES, sizeof *g->line);
    if (!f || !g->line) {
        if (f)
            fclose(f);
        return;
    }
    while (fgets(buf, sizeof buf, f) && g->n < T_GOLDEN_LINES) {
        buf[strcspn(buf, "\n")] = 0;
        if (buf[0] != '#' && buf[0] != 0)
            memcpy(g->line[g->n++], buf, sizeof buf);
    }
    fclose(f);
}

const char *t_golden_find(const t_golden_t *g, const char *name)
{
    size_t len = strlen(name);
    int i;
    for (i = 0; i < g->n; i++)
        if (!strncmp(g->line[i], name, len) && g->line[i][len] == ' ')
            return g->line[i];
    return NULL;
}

void t_golden_free(t_golden_t *g)
{
    free(g->line);
    g->line = NULL;
    g->n = 0;
}

void t_golden_lines_begin(t_golden_lines_t *g, const char *path, const char *header,
                          const char *rewrite_k)
{
    const char *write = getenv("FIELDLOC_WRITE_GOLDEN");
    g->path = path;
    g->rewrite_k = rewrite_k;
    g->out = NULL;
    g->n = g->same = g->missing = 0;
    t_golden_load(&g->gold, path);
    if (write && *write && !t_quick) {
        g->out = fopen(path, "w");
        CHECK(g->out != NULL);
        if (g->out)
            fputs(header, g->out);
    }
}

void t_golden_lines_check(t_golden_lines_t *g, const char *name, const char *got)
{
    const char *want = t_golden_find(&g->gold, name);
    g->n++;
    if (g->out)
        fprintf(g->out, "%s\n", got);
    if (!want)
        g->missing++;
    else if (!strcmp(want, got))
        g->same++;
    else if (!g->out) {
        t_fail_msg(__FILE__, __LINE__, "%s: %s differs (rewrite with FIELDLOC_WRITE_GOLDEN=1 "
                   "build/run_tests -k %s)", g->path, name, g->rewrite_k);
        t_info("want %s", want);
        t_info("got  %s", got);
    }
}

void t_golden_lines_end(t_golden_lines_t *g)
{
    if (g->out) {
        fclose(g->out);
        g->out = NULL;
        t_info("wrote %d golden lines to %s", g->n, g->path);
    } else if (g->missing > 0) {
        t_fail_msg(__FILE__, __LINE__, "%s: %d of %d cases have no golden line", g->path,
                   g->missing, g->n);
    }
    t_golden_free(&g->gold);
}

uint32_t t_hash_init(void) { return 2166136261u; }

uint32_t t_hash_bytes(uint32_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    while (n--) {
        h ^= *b++;
        h *= 16777619u;
    }
    return h;
}

uint32_t t_hash_i32(uint32_t h, int32_t v)
{
    unsigned char b[4];
    uint32_t u = (uint32_t)v;
    b[0] = (unsigned char)(u & 0xff);
    b[1] = (unsigned char)((u >> 8) & 0xff);
    b[2] = (unsigned char)((u >> 16) & 0xff);
    b[3] = (unsigned char)(u >> 24);
    return t_hash_bytes(h, b, 4);
}

void t_rng_seed(t_rng_t *r, uint64_t seed) { r->s = seed ? seed : 0x9e3779b97f4a7c15ull; }

uint32_t t_rng_u32(t_rng_t *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return (uint32_t)((r->s * 2685821657736338717ull) >> 32);
}

int32_t t_rng_range(t_rng_t *r, int32_t lo, int32_t hi)
{
    uint64_t span = (uint64_t)((int64_t)hi - (int64_t)lo) + 1u;
    uint64_t x = ((uint64_t)t_rng_u32(r) << 32) | t_rng_u32(r);
    return (int32_t)((int64_t)lo + (int64_t)(x % span));
}

char *t_read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long n;
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    if (buf) {
        buf[n] = 0;
        *len = (size_t)n;
    }
    return buf;
}

const char *t_realdata_dir(void)
{
    static const char *cands[] = {"../shared/realdata", "../../shared/realdata"};
    struct stat st;
    const char *env = getenv("FIELDLOC_REALDATA");
    size_t i;
    if (env && *env)
        return stat(env, &st) == 0 ? env : NULL;
    for (i = 0; i < sizeof cands / sizeof cands[0]; i++)
        if (stat(cands[i], &st) == 0 && S_ISDIR(st.st_mode))
            return cands[i];
    return NULL;
}

void t_run(const char *name, t_fn fn)
{
    if (!t_selected(name))
        return;
    t_cur_name = name;
    t_cur_failed = 0;
    fflush(stdout);
    fn();
    if (t_cur_failed) {
        printf("FAIL %s (%d failed checks)\n", name, t_cur_failed);
        t_failed++;
    } else {
        printf("ok   %s\n", name);
        t_passed++;
    }
    fflush(stdout);
    t_cur_name = NULL;
}

int main(int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            t_quick = 1;
        else if (!strcmp(argv[i], "--exhaustive"))
            t_exhaustive = 1;
        else if (!strcmp(argv[i], "-k") && i + 1 < argc && t_nfilters < T_FILTER_MAX)
            t_filters[t_nfilters++] = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--quick | --exhaustive] [-k SUBSTRING]...\n", argv[0]);
            return 2;
        }
    }
#undef T_SUITE
#define T_SUITE(name)                                                     \
    do {                                                                  \
        if (suite_##name)                                                 \
            suite_##name();                                               \
        else if (t_nfilters == 0) {                                             \
            printf("FAIL suite %s missing (no host_tests/test_%s.c)\n",   \
                   #name, #name);                                         \
            t_failed++;                                                   \
        }                                                                 \
    } while (0)
#include "suites.h"
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}
