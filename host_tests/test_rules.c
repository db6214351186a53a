/*
 * host_tests/test_rules.c - the firmware-rule checker (tools/build/check_firmware.sh)
 * must catch each kind of violation: fed a tiny source tree that breaks one
 * rule, it fails and names the rule; fed a clean one, it passes.  The tree is
 * laid out like the real one (src/<layer>/, a copy of include/, tools/,
 * host_tests/, an allow-list of long functions), so the structure rules
 * (layering, private headers, include circles, function length; in
 * tools/build/check_layers.py) get planted violations too.  Needs a shell,
 * python3 and the host compiler, so it is skipped under --quick (qemu).
 */
#include "test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A planted file: path under the temp tree (src/..., include/fieldloc/...,
 * tools/..., host_tests/..., or long.txt, the allow-list of long functions). */
struct planted { const char *path, *text; };

static int write_file(const char *dir, const char *rel, const char *text)
{
    char path[512], cmd[1024];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    snprintf(cmd, sizeof cmd, "mkdir -p \"$(dirname %s)\"", path);
    if (system(cmd) != 0)
        return -1;
    f = fopen(path, "w");
    if (!f)
        return -1;
    fputs(text, f);
    fclose(f);
    return 0;
}

/* The interpreter `python3' runs, as the checker's PYTHON (unless PYTHON
 * is set): found once, since a version-manager shim standing for python3
 * costs a fifth of a second per start, every checker run otherwise. */
static const char *rules_python(void)
{
    static char exe[512];
    static int done;
    FILE *p;
    if (!done) {
        done = 1;
        p = popen("python3 -S -c 'import sys; print(sys.executable)' 2>/dev/null", "r");
        if (p) {
            if (!fgets(exe, sizeof exe, p))
                exe[0] = 0;
            exe[strcspn(exe, "\n")] = 0;
            if (pclose(p) != 0 || strchr(exe, '\'') || exe[0] != '/')
                exe[0] = 0;
        }
    }
    return getenv("PYTHON") ? getenv("PYTHON") : exe[0] ? exe : "python3";
}

/* Run the checker on the tree in dir (its build output in dir/build);
 * the shell status, its output in log. */
static int check_tree(const char *dir, char *log, size_t n)
{
    char path[512], cmd[2048];
    FILE *f;
    int rc;
    size_t got;
    snprintf(cmd, sizeof cmd,
             "SRC_DIR=%s/src INC_DIR=%s/include TOOLS_DIR=%s/tools TESTS_DIR=%s/host_tests "
             "LONG_FUNCTIONS=%s/long.txt BUILD=%s/build CC=${CC:-cc} PYTHON='%s' "
             "sh tools/build/check_firmware.sh > %s/log 2>&1", dir, dir, dir, dir, dir, dir,
             rules_python(), dir);
    rc = system(cmd);
    snprintf(path, sizeof path, "%s/log", dir);
    f = fopen(path, "r");
    got = f ? fread(log, 1, n - 1, f) : 0;
    log[got] = 0;
    if (f)
        fclose(f);
    return rc;
}

/* Build build/rules/<name>: a copy of include/, empty tools/ and host_tests/,
 * an empty long-function list, then the planted files; run the checker on
 * it.  Returns the shell status, or -1 when the tree cannot be made. */
static int run_tree(const char *name, const struct planted *files, size_t nfiles,
                    char *log, size_t n)
{
    char dir[256], cmd[2048];
    size_t i;
    snprintf(dir, sizeof dir, "build/rules/%s", name);
    snprintf(cmd, sizeof cmd,
             "rm -rf %s && mkdir -p %s/src %s/tools %s/host_tests && cp -r include %s/ "
             "&& : > %s/long.txt", dir, dir, dir, dir, dir, dir);
    if (system(cmd) != 0)
        return -1;
    for (i = 0; i < nfiles; i++)
        if (write_file(dir, files[i].path, files[i].text) != 0)
            return -1;
    return check_tree(dir, log, n);
}

static int run_checker(const char *name, const char *source, char *log, size_t n)
{
    struct planted one;
    one.path = "src/base/t.c";
    one.text = source;
    return run_tree(name, &one, 1, log, n);
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

static void expect_tree(const char *name, const struct planted *files, size_t nfiles,
                        int should_pass, const char *needle)
{
    static char log[16384];
    int rc = run_tree(name, files, nfiles, log, sizeof log);
    CHECK(rc != -1);
    if (should_pass)
        CHECK(rc == 0);
    else
        CHECK(rc != 0);
    if (needle && !strstr(log, needle))
        t_fail_msg(__FILE__, __LINE__, "%s: log lacks \"%s\":\n%s", name, needle, log);
}

#define NPLANTED(a) (sizeof (a) / sizeof (a)[0])

static void test_layer_vision_fuzzy(void)
{
    struct planted t[2];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "src/vision/v.c";
    t[1].text = "#include \"fieldloc/fuzzy.h\"\nint fl_t_v(void) { return 0; }\n";
    expect_tree("layer_vision_fuzzy", t, NPLANTED(t), 0,
                "(vision) includes fieldloc/fuzzy.h (loc)");
}

static void test_layer_loc_camera(void)
{
    struct planted t[2];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "src/loc/l.c";
    t[1].text = "#include \"fieldloc/camera.h\"\nint fl_t_l(void) { return 0; }\n";
    expect_tree("layer_loc_camera", t, NPLANTED(t), 0, "(loc) includes fieldloc/camera.h (model)");
}

static void test_layer_loc_header_scan(void)
{
    struct planted t[2];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "include/fieldloc/localizer.h";
    t[1].text = "#ifndef FL_T_LOCALIZER_H\n#define FL_T_LOCALIZER_H\n"
                "#include \"fieldloc/scan.h\"\n#endif\n";
    expect_tree("layer_loc_header_scan", t, NPLANTED(t), 0,
                "localizer.h (loc) includes fieldloc/scan.h (vision)");
}

static void test_layer_unknown(void)
{
    struct planted t[3];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "include/fieldloc/mystery.h";
    t[1].text = "#include \"fieldloc/common.h\"\n";
    expect_tree("layer_unknown_header", t, 2, 0,
                "assign a layer to mystery.h in tools/build/check_layers.py");
    t[1].path = "src/extra/e.c";
    t[1].text = "int fl_t_e(void) { return 0; }\n";
    expect_tree("layer_unknown_folder", t, 2, 0, "assign a layer to src folder");
}

static void test_private_headers(void)
{
    struct planted t[3];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "src/vision/scan_int.h";
    t[1].text = "#include \"fieldloc/scan.h\"\n";
    t[2].path = "src/vision/scan_fast.c";
    t[2].text = "#include \"scan_int.h\"\nint fl_t_s(void) { return 0; }\n";
    expect_tree("private_same_stage", t, 3, 1, "all firmware rules hold");
    t[2].path = "src/vision/lines_walk.c";
    expect_tree("private_other_stage", t, 3, 0, "private header scan_int.h included by");
    t[2].path = "tools/eval/probe.c";
    t[2].text = "#include \"../../src/vision/scan_int.h\"\n";
    expect_tree("private_from_tools", t, 3, 0, "private header scan_int.h included by");
}

static void test_include_circle(void)
{
    struct planted t[5];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "src/base/p.h";
    t[1].text = "#ifndef FL_T_P_H\n#define FL_T_P_H\n#include \"q.h\"\n#endif\n";
    t[2].path = "src/base/q.h";
    t[2].text = "#ifndef FL_T_Q_H\n#define FL_T_Q_H\n#include \"p.h\"\n#endif\n";
    expect_tree("circle_src_files", t, 3, 0, "include circle in src/include: ");
    /* tools folders: a -> b is fine, a -> b -> a is a circle (no file circle) */
    t[1].path = "tools/a/x.c";
    t[1].text = "#include \"b/y.h\"\n";
    t[2].path = "tools/b/y.h";
    t[2].text = "int y(void);\n";
    t[3].path = "tools/b/z.c";
    t[3].text = "#include \"a/w.h\"\n";
    t[4].path = "tools/a/w.h";
    t[4].text = "int w(void);\n";
    expect_tree("circle_tools_dag", t, 3, 1, "all firmware rules hold");
    expect_tree("circle_tools_folders", t, 5, 0, "include circle among tools folders: a -> b -> a");
}

/* "#include <stdint.h>", a blank line, then a function of exactly `lines'
 * lines from its signature to its closing brace. */
static void test_tools_through_interface(void)
{
    struct planted t[2];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "tools/loc/run.c";
    t[1].text = "#include \"fieldloc/localizer.h\"\n"
                "/* fl_fuzzy_init is named in a comment only */\n"
                "int run(void) { return fl_localizer_count(); }\n";
    expect_tree("tools_interface_ok", t, 2, 1, "through localizer.h only");
    t[1].text = "#include \"fieldloc/fuzzy.h\"\nint run(void) { return 0; }\n";
    expect_tree("tools_include_fuzzy", t, 2, 0,
                "includes fieldloc/fuzzy.h: tools use a localizer through localizer.h only");
    t[1].text = "#include \"fieldloc/fieldloc.h\"\n"
                "int run(void *g) { return fl_fuzzy_check(g); }\n";
    expect_tree("tools_call_fuzzy", t, 2, 0,
                "calls fl_fuzzy_check: tools use a localizer through localizer.h only");
}

static const char *long_function(int lines)
{
    static char buf[8192];
    size_t k;
    int i;
    k = (size_t)snprintf(buf, sizeof buf, "#include <stdint.h>\n\nint32_t fl_t_long(int32_t x)\n{\n");
    for (i = 0; i < lines - 4; i++)
        k += (size_t)snprintf(buf + k, sizeof buf - k, "    x += 1;\n");
    snprintf(buf + k, sizeof buf - k, "    return x;\n}\n");
    return buf;
}

static void test_function_length(void)
{
    struct planted t[3];
    t[0].path = "src/base/t.c";
    t[0].text = clean_src;
    t[1].path = "src/vision/long.c";
    t[1].text = long_function(150);
    expect_tree("function_150_lines", t, 2, 1, "all firmware rules hold");
    t[1].text = long_function(151);
    expect_tree("function_151_lines", t, 2, 0, "fl_t_long is 151 lines");
    t[2].path = "long.txt";
    t[2].text = "# allowed\nvision/long.c:fl_t_long\n";
    expect_tree("function_151_listed", t, 3, 1, "all firmware rules hold");
    t[1].text = long_function(150);
    expect_tree("function_listed_short", t, 3, 0,
                "vision/long.c:fl_t_long is no longer longer than 150 lines");
}

/* The strict compile is cached by content (BUILD/check-cache): a rerun on
 * the same tree reuses the object, and a change in a header the source
 * includes (not in the source itself) is compiled and judged afresh, both
 * ways: a violation planted in the header fails, taking it out passes. */
static void test_cache(void)
{
    static char log[16384];
    const char *dir = "build/rules/cache";
    struct planted t[1];
    size_t len = 0;
    char *hdr = t_read_file("include/fieldloc/fixed.h", &len), *bad;
    CHECK(hdr != NULL);
    if (!hdr)
        return;
    bad = malloc(len + 64);
    CHECK(bad != NULL);
    if (!bad) {
        free(hdr);
        return;
    }
    snprintf(bad, len + 64, "%sint32_t fl_t_hidden_state;\n", hdr);
    t[0].path = "src/base/t.c";
    t[0].text = "#include \"fieldloc/fixed.h\"\n"
                "int32_t fl_t_twice(int32_t x) { return fl_sat32((int64_t)x * 2); }\n";
    CHECK_EQ(run_tree("cache", t, 1, log, sizeof log), 0);
    CHECK(strstr(log, "(0 unchanged,") != NULL);
    CHECK_EQ(check_tree(dir, log, sizeof log), 0);
    CHECK(strstr(log, "1 sources compiled") != NULL && strstr(log, "(1 unchanged,") != NULL);
    CHECK_EQ(write_file(dir, "include/fieldloc/fixed.h", bad), 0);
    CHECK(check_tree(dir, log, sizeof log) != 0);
    CHECK(strstr(log, "(0 unchanged,") != NULL);
    CHECK(strstr(log, "mutable file-scope state") != NULL);
    CHECK_EQ(write_file(dir, "include/fieldloc/fixed.h", hdr), 0);
    CHECK_EQ(check_tree(dir, log, sizeof log), 0);
    CHECK(strstr(log, "all firmware rules hold") != NULL);
    free(bad);
    free(hdr);
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
    t_run("rules.layer_vision_includes_fuzzy", test_layer_vision_fuzzy);
    t_run("rules.layer_loc_includes_camera", test_layer_loc_camera);
    t_run("rules.layer_loc_header_includes_scan", test_layer_loc_header_scan);
    t_run("rules.layer_unknown_header_or_folder", test_layer_unknown);
    t_run("rules.private_header_other_stage_or_tools", test_private_headers);
    t_run("rules.include_circles", test_include_circle);
    t_run("rules.function_length", test_function_length);
    t_run("rules.tools_through_localizer_interface", test_tools_through_interface);
    t_run("rules.check_cache_follows_headers", test_cache);
}
