/*
 * host_tests/test_rules.c - the firmware-rule checker (tools/build/check_firmware.sh)
 * must catch each kind of violation: fed a tiny source tree that breaks one
 * rule, it fails and names the rule; fed a clean one, it passes.  Needs a
 * shell and the host compiler, so it is skipped under --quick (qemu).
 */
#include "test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int run_checker(const char *name, const char *source, char *log, size_t n)
{
    char dir[256], path[512], cmd[1024];
    FILE *f;
    int rc;
    size_t got;
    snprintf(dir, sizeof dir, "build/rules/%s", name);
    snprintf(cmd, sizeof cmd, "rm -rf %s && mkdir -p %s/src", dir, dir);
    if (system(cmd) != 0)
        return -1;
    snprintf(path, sizeof path, "%s/src/t.c", dir);
    f = fopen(path, "w");
    if (!f)
        return -1;
    fputs(source, f);
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "SRC_DIR=%s/src INC_DIR=include BUILD=%s/build CC=${CC:-cc} "
             "sh tools/build/check_firmware.sh > %s/log 2>&1", dir, dir, dir);
    rc = system(cmd);
    snprintf(path, sizeof path, "%s/log", dir);
    f = fopen(path, "r");
    got = f ? fread(log, 1, n - 1, f) : 0;
    log[got] = 0;
    if (f)
        fclose(f);
    return rc;
}

static const char *clean_src =
    "#include <stdint.h>\n#include <string.h>\n"
    "static const int32_t fl_tab[2] = {1, 2};\n"
    "int32_t fl_t_sum(const int32_t *p, int32_t n)\n{\n    int32_t s = fl_tab[0];\n"
    "    while (n-- > 0)\n        s += *p++;\n    return s;\n}\n"
    "void fl_t_clear(int32_t *p) { memset(p, 0, 4 * sizeof *p); }\n";

static void expect(const char *name, const char *src, int should_pass, const char *needle)
{
    static char log[8192];
    int rc = run_checker(name, src, log, sizeof log);
    CHECK(rc != -1);
    if (should_pass)
        CHECK(rc == 0);
    else
        CHECK(rc != 0);
    if (needle && !strstr(log, needle))
        t_fail_msg(__FILE__, __LINE__, "%s: log lacks \"%s\":\n%s", name, needle, log);
}

static void test_clean(void) { expect("clean", clean_src, 1, "all firmware rules hold"); }

static void test_malloc(void)
{
    expect("malloc", "#include <stddef.h>\nvoid *malloc(size_t);\n"
           "void *fl_t_get(void) { return malloc(8); }\n", 0, "allocator symbol referenced: malloc");
    expect("free", "void free(void *);\nvoid fl_t_put(void *p) { free(p); }\n", 0,
           "allocator symbol referenced: free");
}

static void test_float(void)
{
    expect("float", "int fl_t_half(int x) { double d = x; return (int)(d * 0.5); }\n", 0,
           "does not compile under the firmware flags");
}

static void test_warning(void)
{
    expect("conversion", "#include <stdint.h>\nint16_t fl_t_n(int32_t x) { return x; }\n", 0,
           "does not compile under the firmware flags");
}

static void test_state(void)
{
    expect("global", "int fl_t_count;\nvoid fl_t_inc(void) { fl_t_count++; }\n", 0,
           "mutable file-scope state");
    expect("static_local", "int fl_t_next(void) { static int n; return ++n; }\n", 0,
           "mutable file-scope state");
    expect("static_init", "static int n = 3;\nint fl_t_next(void) { return ++n; }\n", 0,
           "mutable file-scope state");
}

static void test_prefix(void)
{
    expect("prefix", "int helper_sum(int a, int b) { return a + b; }\n", 0,
           "exported symbol without fl_ prefix: helper_sum");
}

static void test_headers(void)
{
    expect("stdio", "#include <stdio.h>\nint fl_t_x(void) { return 1; }\n", 0,
           "header outside the allowed libc subset: <stdio.h>");
    expect("libc_call", "#include <stdlib.h>\nint fl_t_a(int x) { return abs(x); }\n", 0,
           "header outside the allowed libc subset");
}

void suite_rules(void)
{
    if (t_quick)
        return;   /* needs the host compiler and a shell */
    t_run("rules.clean_source_passes", test_clean);
    t_run("rules.allocator_detected", test_malloc);
    t_run("rules.floating_point_rejected", test_float);
    t_run("rules.warnings_are_errors", test_warning);
    t_run("rules.mutable_state_detected", test_state);
    t_run("rules.prefix_enforced", test_prefix);
    t_run("rules.libc_headers_limited", test_headers);
}
