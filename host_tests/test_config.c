/*
 * host_tests/test_config.c - the configuration fingerprint (config.h,
 * common.h): a caller compiled with other config.h values than the library
 * is refused by every init (FL_ERR_CONFIG, its objects untouched), one
 * compiled with the same values is not; and `make install` of a library
 * built with other capacities installs a config.h whose defaults are those
 * capacities.
 *
 * The callers (host_tests/config/caller.c) are compiled and run at test
 * time with this build's compiler, flags and library (the Makefile bakes
 * them in: FL_TEST_CC, FL_TEST_FLAGS, FL_TEST_BUILD, FL_TEST_EXEC, the
 * latter the qemu-user of a cross build), so the test runs the same under
 * `make cross-test` and `make sanitize`.  The installed tree (a recursive
 * `make install`, about 10 s the first time) runs in full mode of a native
 * unsanitized build only.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef FL_TEST_CC
#define FL_TEST_CC "cc"
#endif
#ifndef FL_TEST_FLAGS
#define FL_TEST_FLAGS ""
#endif
#ifndef FL_TEST_ARCHFLAGS
#define FL_TEST_ARCHFLAGS ""
#endif
#ifndef FL_TEST_BUILD
#define FL_TEST_BUILD "build"
#endif
#ifndef FL_TEST_EXEC
#define FL_TEST_EXEC ""
#endif

#define CFG_DIR FL_TEST_BUILD "/config"

/* Every init the caller reports, in its order. */
static const char *const cfg_inits[] = {"camera", "color", "scan", "lines", "crossings",
                                        "beacon", "vision", "fuzzy", "loc_init",
                                        "loc_table_init"};
#define CFG_N_INITS (sizeof cfg_inits / sizeof cfg_inits[0])

typedef struct {
    int status[CFG_N_INITS];
    int flag[CFG_N_INITS];   /* untouched (direct inits) / empty (localizer) */
    int seen[CFG_N_INITS];
    unsigned long fp_caller, fp_library;
    int obs_max;
    char version_caller[32], version_library[32];
    char status_str[256];
} cfg_out_t;

static void cfg_show_log(const char *path, const char *what)
{
    size_t n = 0;
    char *log = t_read_file(path, &n);
    t_fail_msg(__FILE__, __LINE__, "%s:\n%s", what, log ? log : "(no log)");
    free(log);
}

/* Compile host_tests/config/caller.c as `name` with flags (include path,
 * -D) and lib, run it, parse its lines.  0 on success. */
static int cfg_caller(const char *name, const char *cc, const char *flags, const char *lib,
                      cfg_out_t *o)
{
    char cmd[2048], path[256], log[256];
    char *text, *line, *save = NULL;
    size_t n = 0;
    memset(o, 0, sizeof *o);
    snprintf(log, sizeof log, CFG_DIR "/%s.log", name);
    snprintf(cmd, sizeof cmd,
             "mkdir -p " CFG_DIR " && %s -std=c99 -Wall -Wextra %s host_tests/config/caller.c %s "
             "-o " CFG_DIR "/%s > %s 2>&1",
             cc, flags, lib, name, log);
    if (system(cmd) != 0) {
        cfg_show_log(log, "the caller does not compile");
        return -1;
    }
    snprintf(path, sizeof path, CFG_DIR "/%s.out", name);
    snprintf(cmd, sizeof cmd, "%s " CFG_DIR "/%s > %s 2> %s", FL_TEST_EXEC, name, path, log);
    if (system(cmd) != 0) {
        cfg_show_log(log, "the caller does not run");
        return -1;
    }
    text = t_read_file(path, &n);
    if (!text)
        return -1;
    for (line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        char word[32];
        int a, b;
        size_t i;
        if (sscanf(line, "fingerprint 0x%lx 0x%lx", &o->fp_caller, &o->fp_library) == 2)
            continue;
        if (sscanf(line, "version %31s %31s", o->version_caller, o->version_library) == 2)
            continue;
        if (sscanf(line, "fl_obs_max %d", &o->obs_max) == 1)
            continue;
        if (strncmp(line, "status_str ", 11) == 0) {
            snprintf(o->status_str, sizeof o->status_str, "%s", line + 11);
            continue;
        }
        if (sscanf(line, "%31s %d %d", word, &a, &b) != 3)
            continue;
        for (i = 0; i < CFG_N_INITS; i++)
            if (strcmp(word, cfg_inits[i]) == 0) {
                o->status[i] = a;
                o->flag[i] = b;
                o->seen[i]++;
            }
    }
    free(text);
    return 0;
}

/* Every init reported once with status want; refused ones left their
 * object untouched (the localizer's empty), accepted ones wrote it. */
static void cfg_expect(const cfg_out_t *o, const char *name, int want)
{
    size_t i;
    for (i = 0; i < CFG_N_INITS; i++) {
        if (o->seen[i] != 1 || o->status[i] != want || o->flag[i] != (want != FL_OK))
            t_fail_msg(__FILE__, __LINE__, "%s: %s: seen %d, status %d (want %d), %s %d",
                       name, cfg_inits[i], o->seen[i], o->status[i], want,
                       i < 8 ? "untouched" : "empty", o->flag[i]);
    }
    if (want == FL_OK) {
        CHECK_EQ(o->fp_caller, o->fp_library);
    } else {
        CHECK(o->fp_caller != o->fp_library);
        CHECK(strstr(o->status_str, "rebuild with the installed config.h") != NULL);
    }
    CHECK(strcmp(o->version_library, FL_VERSION_STRING) == 0);
}

static void test_fingerprint(void)
{
    char v[32];
    CHECK_EQ(fl_config_fingerprint(), FL_CONFIG_FINGERPRINT);
    CHECK(strcmp(fl_version(), FL_VERSION_STRING) == 0);
    snprintf(v, sizeof v, "%d.%d.%d", FL_VERSION_MAJOR, FL_VERSION_MINOR, FL_VERSION_PATCH);
    CHECK(strcmp(v, FL_VERSION_STRING) == 0);
    CHECK(FL_ERR_CONFIG != FL_OK && strcmp(fl_status_str(FL_ERR_CONFIG), "unknown status") != 0);
    /* the fingerprint is the same on every target (cross-test compares) */
    t_digest("config.fingerprint", fl_config_fingerprint());
}

/* Every option of config.h (each "#ifndef FL_X") is mixed into
 * FL_CONFIG_FINGERPRINT: an option added without it would let callers
 * with another value through. */
static void test_fingerprint_lists_every_option(void)
{
    size_t n = 0;
    char *text = t_read_file("include/fieldloc/config.h", &n);
    const char *p, *fp;
    int options = 0;
    CHECK(text != NULL);
    if (!text)
        return;
    fp = strstr(text, "#define FL_CONFIG_FINGERPRINT");
    CHECK(fp != NULL);
    for (p = text; fp && (p = strstr(p, "#ifndef FL_")) != NULL; p++) {
        char name[64], want[80];
        if (sscanf(p + 8, "%63[A-Z0-9_]", name) != 1)
            continue;
        snprintf(want, sizeof want, "%s)", name);   /* an argument of a mix */
        if (!strstr(fp, want))
            t_fail_msg(__FILE__, __LINE__, "config.h option %s is not in FL_CONFIG_FINGERPRINT", name);
        options++;
    }
    CHECK(options >= 21);
    CHECK(strstr(fp ? fp : "", "FL_ABI_VERSION)") != NULL);
    free(text);
}

/* A caller built with the library's configuration, and one with another
 * FL_OBS_MAX, against this build's libfieldloc.a. */
static void test_caller_mismatch(void)
{
    cfg_out_t same, other;
    char flags[1024];
    int obs_max = FL_OBS_MAX == 64 ? 48 : 64;
    snprintf(flags, sizeof flags, "%s -Iinclude", FL_TEST_FLAGS);
    if (cfg_caller("caller_same", FL_TEST_CC, flags, FL_TEST_BUILD "/libfieldloc.a", &same) == 0) {
        cfg_expect(&same, "same config.h", FL_OK);
        CHECK_EQ(same.obs_max, FL_OBS_MAX);
        CHECK_EQ(same.fp_library, FL_CONFIG_FINGERPRINT);
    } else {
        CHECK(0);
    }
    snprintf(flags, sizeof flags, "%s -Iinclude -UFL_OBS_MAX -DFL_OBS_MAX=%d", FL_TEST_FLAGS,
             obs_max);
    if (cfg_caller("caller_other", FL_TEST_CC, flags, FL_TEST_BUILD "/libfieldloc.a", &other) == 0) {
        cfg_expect(&other, "FL_OBS_MAX changed", FL_ERR_CONFIG);
        CHECK_EQ(other.obs_max, obs_max);
        CHECK_EQ(other.fp_library, FL_CONFIG_FINGERPRINT);
    } else {
        CHECK(0);
    }
}

static int cfg_file_has(const char *path, const char *needle)
{
    size_t n = 0;
    char *text = t_read_file(path, &n);
    int ok = text && strstr(text, needle) != NULL;
    if (!ok)
        t_fail_msg(__FILE__, __LINE__, "%s lacks \"%s\"", path, needle);
    free(text);
    return ok;
}

/* make install of a library built with other capacities: the installed
 * config.h has them as defaults, a caller compiled against the installed
 * headers with no -D matches, one with the in-tree default does not. */
static void test_install_tree(void)
{
    char cwd[512], dest[700], vars[1500], cmd[4096], flags[1024], lib[800], path[900], want[64];
    const char *log = CFG_DIR "/install.log";
    cfg_out_t inst, old;
    int obs_max = FL_OBS_MAX == 48 ? 40 : 48, cols = FL_SCAN_MAX_COLS == 320 ? 256 : 320;
    if (t_quick || FL_TEST_ARCHFLAGS[0] != '\0' || FL_TEST_EXEC[0] != '\0') {
        t_info("skipped: full mode of a native build without ARCHFLAGS only");
        return;
    }
    if (!getcwd(cwd, sizeof cwd)) {
        CHECK(0);
        return;
    }
    snprintf(dest, sizeof dest, "%s/" CFG_DIR "/dest", cwd);
    /* the caller's MAKEFLAGS (a jobserver of `make test`) do not apply;
     * the same variables for install and uninstall, else the tree's flags
     * stamp changes and the next run rebuilds it */
    snprintf(vars, sizeof vars,
             "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory -j2 "
             "BUILD=" CFG_DIR "/tree CC='%s' OPT=-O1 WITH_OPENCV=0 "
             "CONFIG_DEFS='-DFL_OBS_MAX=%d -DFL_SCAN_MAX_COLS=%d' DESTDIR=%s PREFIX=/opt/fieldloc",
             FL_TEST_CC, obs_max, cols, dest);
    snprintf(cmd, sizeof cmd, "rm -rf %s && mkdir -p " CFG_DIR " && %s install > %s 2>&1", dest,
             vars, log);
    if (system(cmd) != 0) {
        cfg_show_log(log, "make install failed");
        return;
    }
    snprintf(path, sizeof path, "%s/opt/fieldloc/include/fieldloc/config.h", dest);
    snprintf(want, sizeof want, "#define FL_OBS_MAX %d\n", obs_max);
    cfg_file_has(path, want);
    snprintf(want, sizeof want, "#define FL_SCAN_MAX_COLS %d\n", cols);
    cfg_file_has(path, want);
    cfg_file_has(path, "Installed by `make install`");
    snprintf(path, sizeof path, "%s/opt/fieldloc/include/fieldloc/vision.h", dest);
    cfg_file_has(path, "fl_vision_init_cfg");
    snprintf(path, sizeof path, "%s/opt/fieldloc/lib/pkgconfig/fieldloc.pc", dest);
    cfg_file_has(path, "Version: " FL_VERSION_STRING "\n");
    cfg_file_has(path, "prefix=/opt/fieldloc\n");

    snprintf(lib, sizeof lib, "%s/opt/fieldloc/lib/libfieldloc.a", dest);
    snprintf(flags, sizeof flags, "-I%s/opt/fieldloc/include", dest);
    if (cfg_caller("caller_installed", FL_TEST_CC, flags, lib, &inst) == 0) {
        cfg_expect(&inst, "installed headers, no -D", FL_OK);
        CHECK_EQ(inst.obs_max, obs_max);
        CHECK(inst.fp_library != FL_CONFIG_FINGERPRINT);   /* not the in-tree layout */
    } else {
        CHECK(0);
    }
    snprintf(flags, sizeof flags, "-I%s/opt/fieldloc/include -UFL_OBS_MAX -DFL_OBS_MAX=%d", dest,
             (int)FL_OBS_MAX);
    if (cfg_caller("caller_installed_other", FL_TEST_CC, flags, lib, &old) == 0)
        cfg_expect(&old, "installed headers, the in-tree FL_OBS_MAX", FL_ERR_CONFIG);
    else
        CHECK(0);

    snprintf(cmd, sizeof cmd,
             "%s uninstall >> %s 2>&1 && ! test -e %s/opt/fieldloc/include/fieldloc && ! test -e %s",
             vars, log, dest, lib);
    CHECK_EQ(system(cmd), 0);
}

void suite_config(void)
{
    t_run("config.fingerprint", test_fingerprint);
    t_run("config.fingerprint_lists_every_option", test_fingerprint_lists_every_option);
    t_run("config.caller_mismatch", test_caller_mismatch);
    t_run("config.install_tree", test_install_tree);
}
