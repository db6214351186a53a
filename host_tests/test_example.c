/*
 * host_tests/test_example.c - the C API example of README.md ("The C API"),
 * compiled and run on a rendered fixture, so that the README's code stays
 * true; example.readme_text checks that the README shows exactly this code,
 * example.readme_cxx that it compiles as C++ with C linkage.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/render.h"

#include <stdlib.h>
#include <string.h>

/* The README example (README.md, between the example markers, less its
 * #include line), verbatim: also compiled as C++ by example.readme_cxx. */
#include "readme_example.inc"

static void test_readme_example(void)
{
    robot_loc_t *r = malloc(sizeof *r);
    render_scene_t sc;
    render_frame_t fr;
    fl_loc_estimate_t est;
    char err[128];
    FILE *f = fopen("fixtures/frames/spl2013_t_near.scene", "r");
    int i;
    CHECK(r != NULL && f != NULL);
    if (!r || !f) {
        free(r);
        if (f) fclose(f);
        return;
    }
    CHECK_EQ(render_scene_read(f, &sc, err, sizeof err), 0);
    fclose(f);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK_EQ(loc_init(r, "spl2013"), FL_OK);
    r->loc->set_prior_half(r->state.b, sc.robot_x_mm < 0 ? -1 : 1);
    for (i = 0; i < 5; i++)   /* standing still, the same frame */
        loc_frame(r, 0, 0, 0, &fr.view, sc.head.head_pitch, sc.head.head_yaw, &est);
    CHECK(r->vision.crossings.n > 0);
    /* one T seen from one spot is ambiguous, but the true pose must stay
     * among the most possible ones */
    CHECK_LE(32768, r->loc->possibility_q16(r->state.b, sc.robot_x_mm, sc.robot_y_mm, sc.robot_heading));
    t_info("README example on spl2013_t_near: possibility of the true pose %.2f, estimate (%d, %d) mm "
           "reliability %.2f (one crossing: ambiguous), truth (%d, %d) mm",
           r->loc->possibility_q16(r->state.b, sc.robot_x_mm, sc.robot_y_mm, sc.robot_heading) / 65536.0,
           (int)est.x_mm, (int)est.y_mm, est.reliability_q16 / 65536.0, (int)sc.robot_x_mm,
           (int)sc.robot_y_mm);
    render_frame_free(&fr);
    free(r);
}

/* The text between the markers in README.md (less its #include line) and
 * host_tests/readme_example.inc must be the same, byte for byte. */
static const char *between(const char *text, const char *begin, const char *end, size_t *len)
{
    const char *a = text ? strstr(text, begin) : NULL;
    const char *b;
    if (!a)
        return NULL;
    a = strchr(a + strlen(begin), '\n');
    if (!a)
        return NULL;
    a++;
    b = strstr(a, end);
    if (!b)
        return NULL;
    while (b > a && b[-1] != '\n')   /* back to the start of the marker's line */
        b--;
    *len = (size_t)(b - a);
    return a;
}

static void test_readme_text(void)
{
    size_t nr = 0, nt = 0, lr;
    char *readme = t_read_file("README.md", &nr);
    char *ex_t = t_read_file("host_tests/readme_example.inc", &nt);
    const char *ex_r = between(readme, "<!-- example:begin -->", "<!-- example:end -->", &lr);
    static const char head[] = "```c\n#include <fieldloc/fieldloc.h>\n\n";
    CHECK(ex_r != NULL && ex_t != NULL);
    if (ex_r && ex_t) {
        CHECK(lr > sizeof head - 1 && memcmp(ex_r, head, sizeof head - 1) == 0);
        ex_r += sizeof head - 1;
        lr -= sizeof head - 1;
        CHECK(lr >= 4 && memcmp(ex_r + lr - 4, "```\n", 4) == 0);
        lr -= 4;
        if (lr != nt || memcmp(ex_r, ex_t, nt) != 0)
            t_fail_msg(__FILE__, __LINE__, "README.md's example differs from host_tests/readme_example.inc "
                       "(%zu vs %zu bytes): keep the two in step", lr, nt);
    }
    free(readme);
    free(ex_t);
}

/* The README example compiled as C++ (host_tests/cxx/readme_example.cpp, to
 * an object: not linked, so the same on every target): it must compile
 * with warnings as errors, and every fl_ function it calls must keep C
 * linkage (extern "C" in the headers): no mangled _Z...fl_ reference in the
 * object.  Skipped, with a message, when no C++ compiler is installed. */
static void test_readme_cxx(void)
{
    char cmd[1024];
    size_t n = 0;
    char *undef;
    if (system("command -v c++ > /dev/null 2>&1") != 0) {
        t_info("skipped: no C++ compiler (c++) on this machine");
        return;
    }
    CHECK_EQ(system("mkdir -p build/cxx"), 0);
    snprintf(cmd, sizeof cmd,
             "c++ -std=c++11 -Wall -Wextra -Werror -Iinclude -c host_tests/cxx/readme_example.cpp "
             "-o build/cxx/readme_example.o > build/cxx/log.txt 2>&1 && "
             "nm -u build/cxx/readme_example.o > build/cxx/undef.txt");
    if (system(cmd) != 0) {
        char *log = t_read_file("build/cxx/log.txt", &n);
        t_fail_msg(__FILE__, __LINE__, "the README example does not compile as C++:\n%s", log ? log : "");
        free(log);
        return;
    }
    undef = t_read_file("build/cxx/undef.txt", &n);
    CHECK(undef != NULL);
    if (undef) {
        CHECK(strstr(undef, "fl_localizer_find") != NULL);   /* called, unmangled */
        CHECK(strstr(undef, "fl_vision_frame") != NULL);
        if (strstr(undef, "_Z") && strstr(undef, "fl_"))
            t_fail_msg(__FILE__, __LINE__, "C++ references with mangled names (no extern \"C\"):\n%s", undef);
    }
    free(undef);
}

void suite_example(void)
{
    t_run("example.readme_api", test_readme_example);
    t_run("example.readme_text", test_readme_text);
    t_run("example.readme_cxx", test_readme_cxx);
}
