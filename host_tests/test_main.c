/* host_tests/test_main.c - runner and harness implementation. */
#include "test.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <time.h>

int t_quick = 0;
int t_exhaustive = 0;
/* --times: the wall time of every case on stderr (stdout stays comparable) */
static int t_times = 0;

static double t_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

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
    double t0;
    if (!t_selected(name))
        return;
    t_cur_name = name;
    t_cur_failed = 0;
    fflush(stdout);
    t0 = t_now();
    fn();
    if (t_times)
        fprintf(stderr, "time %8.3f s %s\n", t_now() - t0, name);
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

/* The suites in run (and output) order, from suites.h; fn is NULL for a
 * listed suite without its test file (weak symbol). */
#define T_SUITES_MAX 128
struct t_suite { const char *name; void (*fn)(void); };
static struct t_suite t_suites[T_SUITES_MAX];
static int t_nsuites = 0;

static void t_add_suite(const char *name, void (*fn)(void))
{
    if (t_nsuites < T_SUITES_MAX) {
        t_suites[t_nsuites].name = name;
        t_suites[t_nsuites].fn = fn;
    }
    t_nsuites++;
}

static void t_list_suites(void)
{
#undef T_SUITE
#define T_SUITE(name) t_add_suite(#name, suite_##name)
#include "suites.h"
}

static void t_run_suite(const struct t_suite *s)
{
    if (s->fn)
        s->fn();
    else if (t_nfilters == 0) {
        printf("FAIL suite %s missing (no host_tests/test_%s.c)\n", s->name, s->name);
        t_failed++;
    }
}

/* -j N: the suites run in N worker processes (a suite is the unit: its cases
 * share fixtures and scratch folders), each suite's stdout captured in its
 * own temporary file and copied out in suites.h order as soon as every
 * earlier suite is done, so the output is the serial run's, line for line.
 * The workers take suites from a queue, the long ones first: by the wall
 * times of the last complete parallel full run (suite_times.txt beside the
 * runner; a suite it lacks goes first), else by t_long_first (a suite
 * missing from it starts after those).  The order only balances the
 * workers.  A suite whose worker dies fails with its output so far. */
static const char *const t_long_first[] = {
    "camera_vision", "rules", "scan", "cli", "calib", "render", "walks", "fuzzy",
    "sim", "confidence", "localize", "color", "color_auto",
};

/* suite_times.txt in the runner's folder (NULL when unknown) */
static const char *t_times_path(void)
{
    static char path[1100];
    char self[1024];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    char *slash;
    if (n <= 0)
        return NULL;
    self[n] = 0;
    slash = strrchr(self, '/');
    if (!slash)
        return NULL;
    *slash = 0;
    snprintf(path, sizeof path, "%s/suite_times.txt", self);
    return path;
}

/* The queue order into order[] (t_nsuites entries). */
static void t_queue_order(int *order)
{
    double key[T_SUITES_MAX];
    const char *path = t_times_path();
    FILE *f = path ? fopen(path, "r") : NULL;
    char name[128];
    double sec;
    int i, k, n = 0;
    size_t h;
    if (f) {
        for (i = 0; i < t_nsuites; i++)
            key[i] = 1e9;                      /* not measured yet: first */
        while (fscanf(f, "%127s %lf", name, &sec) == 2)
            for (i = 0; i < t_nsuites; i++)
                if (!strcmp(t_suites[i].name, name))
                    key[i] = sec;
        fclose(f);
    } else {
        for (i = 0; i < t_nsuites; i++)
            key[i] = 0;
        for (h = 0; h < sizeof t_long_first / sizeof t_long_first[0]; h++)
            for (i = 0; i < t_nsuites; i++)
                if (!strcmp(t_suites[i].name, t_long_first[h]))
                    key[i] = 1000.0 - (double)h;
    }
    /* stable: equal keys keep suites.h order */
    for (i = 0; i < t_nsuites; i++) {
        for (k = n; k > 0 && key[order[k - 1]] < key[i]; k--)
            order[k] = order[k - 1];
        order[k] = i;
        n++;
    }
}

static void t_times_save(const double *sec)
{
    const char *path = t_times_path();
    char tmp[1200];
    FILE *f;
    int i;
    if (!path)
        return;
    snprintf(tmp, sizeof tmp, "%s.%ld", path, (long)getpid());
    f = fopen(tmp, "w");
    if (!f)
        return;
    for (i = 0; i < t_nsuites; i++)
        fprintf(f, "%s %.3f\n", t_suites[i].name, sec[i]);
    if (fclose(f) != 0 || rename(tmp, path) != 0)
        remove(tmp);
}

struct t_done { int suite, passed, failed; double sec; };

static int t_write_all(int fd, const void *p, size_t n)
{
    const char *b = p;
    while (n > 0) {
        ssize_t w = write(fd, b, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        b += w;
        n -= (size_t)w;
    }
    return 0;
}

static void t_copy_out(int fd)
{
    char buf[65536];
    off_t off = 0;
    ssize_t r;
    fflush(stdout);
    while ((r = pread(fd, buf, sizeof buf, off)) > 0) {
        if (t_write_all(STDOUT_FILENO, buf, (size_t)r) != 0)
            break;
        off += r;
    }
}

static void t_cloexec(int fd) { fcntl(fd, F_SETFD, fcntl(fd, F_GETFD) | FD_CLOEXEC); }

static int t_run_parallel(int jobs)
{
    int order[T_SUITES_MAX], out[T_SUITES_MAX], state[T_SUITES_MAX];
    int work[2], done[2], n = t_nsuites, i, k, next = 0, status, all = 1;
    double sec[T_SUITES_MAX];
    pid_t pid;
    struct t_done d;
    memset(&d, 0, sizeof d);   /* its padding goes down the pipe too */
    t_queue_order(order);
    for (i = 0; i < t_nsuites; i++) {
        FILE *f = tmpfile();
        if (!f) {
            perror("run_tests: tmpfile");
            return -1;
        }
        out[i] = fileno(f);
        t_cloexec(out[i]);
        state[i] = 0;
    }
    if (pipe(work) != 0 || pipe(done) != 0) {
        perror("run_tests: pipe");
        return -1;
    }
    t_cloexec(work[0]);
    t_cloexec(work[1]);
    t_cloexec(done[0]);
    t_cloexec(done[1]);
    /* the whole queue fits in the pipe; a worker's read of one int is atomic */
    if (t_write_all(work[1], order, (size_t)n * sizeof order[0]) != 0)
        return -1;
    close(work[1]);
    fflush(stdout);
    fflush(stderr);
    for (k = 0; k < jobs; k++) {
        pid = fork();
        if (pid < 0) {
            perror("run_tests: fork");
            if (k == 0)
                return -1;
            break;
        }
        if (pid == 0) {
            close(done[0]);
            while (read(work[0], &i, sizeof i) == (ssize_t)sizeof i) {
                fflush(stdout);
                if (dup2(out[i], STDOUT_FILENO) < 0)
                    _exit(1);
                double t0 = t_now();
                t_passed = t_failed = 0;
                t_run_suite(&t_suites[i]);
                fflush(stdout);
                d.sec = t_now() - t0;
                d.suite = i;
                d.passed = t_passed;
                d.failed = t_failed;
                if (t_write_all(done[1], &d, sizeof d) != 0)
                    _exit(1);
            }
            _exit(0);
        }
    }
    close(work[0]);
    close(done[1]);
    t_passed = t_failed = 0;
    for (;;) {
        ssize_t r = read(done[0], &d, sizeof d);
        if (r < 0 && errno == EINTR)
            continue;
        if (r != (ssize_t)sizeof d)
            break;
        state[d.suite] = 1;
        sec[d.suite] = d.sec;
        t_passed += d.passed;
        t_failed += d.failed;
        while (next < t_nsuites && state[next]) {
            t_copy_out(out[next]);
            next++;
        }
    }
    /* a worker that exits non-zero failed even when its suites passed:
     * valgrind's --error-exitcode and the sanitizers report that way */
    for (;;) {
        pid = wait(&status);
        if (pid < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            printf("FAIL worker process %ld ended with %s %d\n", (long)pid,
                   WIFEXITED(status) ? "exit status" : "signal",
                   WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status));
            fflush(stdout);
            t_failed++;
            all = 0;
        }
    }
    for (; next < t_nsuites; next++) {
        t_copy_out(out[next]);
        if (!state[next]) {
            printf("FAIL suite %s did not finish (its worker process died)\n",
                   t_suites[next].name);
            fflush(stdout);
            t_failed++;
            all = 0;
        }
    }
    /* the times of a complete run order the next one */
    if (all && t_nfilters == 0 && !t_quick && !t_exhaustive)
        t_times_save(sec);
    return 0;
}

int main(int argc, char **argv)
{
    int i, jobs = 1;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            t_quick = 1;
        else if (!strcmp(argv[i], "--exhaustive"))
            t_exhaustive = 1;
        else if (!strcmp(argv[i], "--times"))
            t_times = 1;
        else if (!strcmp(argv[i], "-j") && i + 1 < argc && atoi(argv[i + 1]) >= 1)
            jobs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "-k") && i + 1 < argc && t_nfilters < T_FILTER_MAX)
            t_filters[t_nfilters++] = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--quick | --exhaustive] [--times] [-j JOBS] "
                    "[-k SUBSTRING]...\n", argv[0]);
            return 2;
        }
    }
    t_list_suites();
    if (t_nsuites > T_SUITES_MAX) {
        printf("FAIL more suites than T_SUITES_MAX (%d)\n", T_SUITES_MAX);
        t_failed++;
        t_nsuites = T_SUITES_MAX;
    }
    if (jobs < 2 || t_run_parallel(jobs) != 0)
        for (i = 0; i < t_nsuites; i++)
            t_run_suite(&t_suites[i]);
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}
