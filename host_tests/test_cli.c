/*
 * host_tests/test_cli.c - the command-line tool as a user meets it: numeric
 * options are checked (tools/cli/args.h: a bad number, a value out of
 * range, an unknown option or a missing value exit with status 2 and one
 * line on stderr; good values still work), and the pictures carry a legend
 * strip below the image (tools/eval/picture.h, the 5 x 7 font of
 * tools/io/font.h).
 *
 * The CLI cases run the built binary, `fieldloc` next to this runner
 * (both are built by `make test`); they are skipped under --quick (qemu
 * runs only the cross-built runner) and, with a "#" line, when the binary
 * is absent (e.g. `make sanitize` builds the runner only).
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "eval/picture.h"
#include "io/font.h"
#include "io/ppm.h"
#include "io/realdata.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* ---- the font and the legend strip (no binary needed) ------------------- */

static void t_font(void)
{
    static const uint8_t white[3] = {255, 255, 255};
    /* 'T': full top row, then the middle column */
    host_image_t im = host_image_new(20, 12, 0, 0, 0);
    int r, b, x;
    CHECK_EQ(font_row('T', 0), 0x1f);
    for (r = 1; r < 7; r++)
        CHECK_EQ(font_row('T', r), 0x04);
    CHECK_EQ(font_row('T', 7), 0);
    /* a descender below the baseline for p, none for o */
    CHECK(font_row('p', 7) != 0);
    CHECK_EQ(font_row('o', 7), 0);
    CHECK_EQ(font_row(' ', 3), 0);
    /* outside printable ASCII: the '?' glyph */
    CHECK_EQ(font_row('\001', 0), font_row('?', 0));
    CHECK_EQ(font_text_width("", 1), 0);
    CHECK_EQ(font_text_width("ab", 1), 11);
    CHECK_EQ(font_text_width("ab", 2), 22);
    CHECK(im.rgb != NULL);
    if (im.rgb == NULL)
        return;
    x = font_draw(&im, 1, 2, "T", white, 1);
    CHECK_EQ(x, 1 + FONT_ADVANCE);
    /* every pixel of the glyph box matches the table */
    for (r = 0; r < FONT_H; r++)
        for (b = 0; b < FONT_W; b++) {
            const uint8_t *p = im.rgb + 3 * ((size_t)(2 + r) * 20 + (size_t)(1 + b));
            CHECK_EQ(p[0] == 255, (font_row('T', r) >> (4 - b)) & 1);
        }
    /* clipped, not crashing, at the image edge */
    font_draw(&im, 17, 8, "WW", white, 3);
    host_image_free(&im);
}

/* Count pixels of color c in rows [v0, v1) of im. */
static long count_color(const host_image_t *im, int v0, int v1, int r, int g, int b)
{
    long n = 0;
    int u, v;
    for (v = v0; v < v1 && v < im->height; v++)
        for (u = 0; u < im->width; u++) {
            const uint8_t *p = im->rgb + 3 * ((size_t)v * (size_t)im->width + (size_t)u);
            n += p[0] == r && p[1] == g && p[2] == b;
        }
    return n;
}

/* 1 when the legend strip that starts at row y0 of im begins (4 px in, 4 px
 * down) with text exactly as the font draws it at scale sc in the legend's
 * colours. */
static int caption_starts_with(const host_image_t *im, int y0, const char *text, int sc)
{
    static const uint8_t fg[3] = {PIC_LEGEND_FG, PIC_LEGEND_FG, PIC_LEGEND_FG};
    host_image_t ref = host_image_new(im->width, sc * FONT_LINE, PIC_LEGEND_BG, PIC_LEGEND_BG,
                                      PIC_LEGEND_BG);
    int v, w = font_text_width(text, sc);
    int ok = im->rgb != NULL && ref.rgb != NULL && y0 + 4 + sc * FONT_H <= im->height;
    if (ok)
        font_draw(&ref, 4, 0, text, fg, sc);
    for (v = 0; ok && v < sc * FONT_H; v++)
        ok = memcmp(im->rgb + 3 * ((size_t)(y0 + 4 + v) * (size_t)im->width + 4),
                    ref.rgb + 3 * ((size_t)v * (size_t)im->width + 4), 3 * (size_t)w) == 0;
    host_image_free(&ref);
    return ok;
}

static void t_legend(void)
{
    host_image_t img = host_image_new(200, 50, 10, 200, 30), out, narrow, nout;
    const char *cap = "a caption long enough to wrap on a narrow picture of the tools";
    int h, hn;
    CHECK(img.rgb != NULL);
    if (img.rgb == NULL)
        return;
    h = pic_legend_height(200, PIC_LEGEND_DETECT, cap);
    CHECK(h > 0);
    CHECK_EQ(pic_add_legend(&img, PIC_LEGEND_DETECT, cap, &out), 0);
    CHECK_EQ(out.width, 200);
    CHECK_EQ(out.height, 50 + h);
    if (out.rgb != NULL) {
        /* the image itself is untouched, the strip holds text and swatches */
        CHECK(memcmp(out.rgb, img.rgb, 200 * 50 * 3) == 0);
        CHECK(count_color(&out, 50, out.height, PIC_LEGEND_FG, PIC_LEGEND_FG, PIC_LEGEND_FG) > 200);
        CHECK(count_color(&out, 50, out.height, PIC_LEGEND_BG, PIC_LEGEND_BG, PIC_LEGEND_BG) > 0);
        CHECK(count_color(&out, 50, out.height, 255, 0, 0) > 0);       /* L crossing box */
        CHECK(count_color(&out, 50, out.height, 200, 255, 0) > 0);     /* post top */
        /* the first caption word, exactly as the font draws it */
        CHECK(caption_starts_with(&out, 50, "a caption", 1));
    }
    host_image_free(&out);
    /* more sets, or a narrower picture, make a taller strip */
    CHECK(pic_legend_height(200, PIC_LEGEND_DETECT | PIC_LEGEND_CLASSES, cap) > h);
    narrow = host_image_new(100, 50, 0, 0, 0);
    hn = pic_legend_height(100, PIC_LEGEND_DETECT, cap);
    CHECK(hn > h);
    CHECK_EQ(pic_legend_inplace(&narrow, PIC_LEGEND_DETECT, cap), 0);
    CHECK_EQ(narrow.height, 50 + hn);
    host_image_free(&narrow);
    /* a wide picture (frame | belief) gets the strip at twice the size */
    {
        host_image_t wide = host_image_new(1200, 20, 0, 0, 0);
        CHECK_EQ(pic_legend_inplace(&wide, PIC_LEGEND_BELIEF, "t 3.0 s"), 0);
        CHECK(caption_starts_with(&wide, 20, "t 3.0 s", 2));
        host_image_free(&wide);
    }
    memset(&nout, 0, sizeof nout);
    CHECK_EQ(pic_add_legend(&nout, PIC_LEGEND_DETECT, NULL, &out), -1);
    host_image_free(&img);
}

static void t_caption(void)
{
    fl_loc_estimate_t e;
    char buf[256];
    memset(&e, 0, sizeof e);
    e.x_mm = 1200;
    e.y_mm = -300;
    e.heading = 16384;               /* 90 deg */
    e.reliability_q16 = 49152;       /* 0.75 */
    pic_belief_caption(buf, sizeof buf, 12.5, 125, &e, 240.4, 3.25);
    CHECK(strstr(buf, "t 12.5 s") != NULL);
    CHECK(strstr(buf, "frame 125") != NULL);
    CHECK(strstr(buf, "estimate 1200 -300 mm 90 deg") != NULL);
    CHECK(strstr(buf, "reliability 0.75") != NULL);
    CHECK(strstr(buf, "error 240 mm 3.2 deg") != NULL || strstr(buf, "error 240 mm 3.3 deg"));
    pic_belief_caption(buf, sizeof buf, -1, 7, &e, -1, 0);
    CHECK(strstr(buf, "t ") != buf);
    CHECK(strstr(buf, "frame 7") == buf);
    CHECK(strstr(buf, "no truth") != NULL);
    /* a short buffer is cut, never overrun */
    pic_belief_caption(buf, 10, 12.5, 125, &e, 240, 3);
    CHECK(strlen(buf) == 9);
}

/* ---- the binary ------------------------------------------------------------ */

static char t_cli[1100], t_dir[1100];

/* The fieldloc binary next to this runner; 0 when found. */
static int cli_find(void)
{
    char self[1024];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    char *slash;
    if (n <= 0)
        return -1;
    self[n] = '\0';
    slash = strrchr(self, '/');
    if (slash == NULL)
        return -1;
    *slash = '\0';
    snprintf(t_cli, sizeof t_cli, "%s/fieldloc", self);
    snprintf(t_dir, sizeof t_dir, "%s/cli_test", self);
    mkdir(t_dir, 0777);
    return access(t_cli, X_OK) == 0 ? 0 : -1;
}

/* Run `fieldloc ARGS`; returns the exit status (-1: not run), stdout and
 * stderr in out / err (may be NULL). */
static int cli_run(const char *args, char *out, size_t nout, char *err, size_t nerr)
{
    char cmd[4096], path[1200];
    int rc, k;
    snprintf(cmd, sizeof cmd, "%s %s > %s/out.txt 2> %s/err.txt", t_cli, args, t_dir, t_dir);
    rc = system(cmd);
    for (k = 0; k < 2; k++) {
        char *buf = k ? err : out;
        size_t n = k ? nerr : nout, got = 0;
        FILE *f;
        if (buf == NULL)
            continue;
        snprintf(path, sizeof path, "%s/%s", t_dir, k ? "err.txt" : "out.txt");
        f = fopen(path, "r");
        if (f != NULL) {
            got = fread(buf, 1, n - 1, f);
            fclose(f);
        }
        buf[got] = '\0';
    }
    if (rc == -1 || !WIFEXITED(rc))
        return -1;
    return WEXITSTATUS(rc);
}

/* args must fail with status 2 and exactly one stderr line equal to msg. */
#define expect_error(args, msg) expect_error_at(__LINE__, args, msg)
static void expect_error_at(int line_no, const char *args, const char *msg)
{
    char err[2048], line[2048];
    int rc = cli_run(args, NULL, 0, err, sizeof err);
    snprintf(line, sizeof line, "%s\n", msg);
    if (rc != 2 || strcmp(err, line) != 0)
        t_fail_msg(__FILE__, line_no, "fieldloc %s: status %d, stderr \"%s\" (want 2, \"%s\")",
                   args, rc, err, msg);
    else
        CHECK(1);
}

#define FRAME_FAR "fixtures/frames/spl2013_t_far.raw"
#define CAM_FAR "--field spl2013 --camera nao4-top-320"

static void t_numbers(void)
{
    char out[4096], err[2048];
    if (t_quick)
        return;
    if (cli_find() != 0) {
        t_info("skipped: %s not built", t_cli);
        return;
    }
    /* not a number, out of range (radians, with the NAO joint in degrees) */
    expect_error("detect " CAM_FAR " --head abc 0 " FRAME_FAR,
                 "fieldloc detect: --head pitch: \"abc\" is not a number");
    expect_error("detect " CAM_FAR " --head 100 0 " FRAME_FAR,
                 "fieldloc detect: --head pitch: 100 is out of range -0.6720..0.5149 rad "
                 "(-38.5..29.5 degrees, NAO HeadPitch)");
    expect_error("detect " CAM_FAR " --head 0 2.1 " FRAME_FAR,
                 "fieldloc detect: --head yaw: 2.1 is out of range -2.0857..2.0857 rad "
                 "(-119.5..119.5 degrees, NAO HeadYaw)");
    expect_error("detect " CAM_FAR " --head 0x1 0 " FRAME_FAR,
                 "fieldloc detect: --head pitch: \"0x1\" is not a number");
    expect_error("detect " CAM_FAR " --head nan 0 " FRAME_FAR,
                 "fieldloc detect: --head pitch: \"nan\" is not a number");
    expect_error("detect " CAM_FAR " --neck 20 " FRAME_FAR,
                 "fieldloc detect: --neck: 20 is out of range 50..2000 mm");
    expect_error("detect " CAM_FAR " --repeat -3 " FRAME_FAR,
                 "fieldloc detect: --repeat: -3 is out of range 1..1000000");
    expect_error("detect " CAM_FAR " --repeat 2.5 " FRAME_FAR,
                 "fieldloc detect: --repeat: \"2.5\" is not an integer");
    expect_error("detect " CAM_FAR " --repeat 7x " FRAME_FAR,
                 "fieldloc detect: --repeat: \"7x\" is not a number");
    expect_error("detect " CAM_FAR " --repeat 99999999999999999999 " FRAME_FAR,
                 "fieldloc detect: --repeat: 99999999999999999999 is out of range 1..1000000");
    expect_error("detect " CAM_FAR " --repeat '' " FRAME_FAR,
                 "fieldloc detect: --repeat: \"\" is not a number");
    expect_error("detect " CAM_FAR " --show rings " FRAME_FAR,
                 "fieldloc detect: --show: unknown layer \"rings\" (border, classes)");
    expect_error("detect " CAM_FAR " --bogus " FRAME_FAR,
                 "fieldloc detect: unknown option --bogus (fieldloc detect --help)");
    expect_error("detect " CAM_FAR " " FRAME_FAR " --neck",
                 "fieldloc detect: --neck needs 1 value");
    /* the camera decides the head range: the AIBO's limit is its tilt */
    expect_error("render --field aibo2004 --camera aibo-ers7 --head 2 0 --out /dev/null",
                 "fieldloc render: --head pitch: 2 is out of range -1.5708..1.5708 rad "
                 "(-90.0..90.0 degrees, camera limit: optical axis within 90 degrees of level)");
    expect_error("render --pose 6300 0 0 --out /dev/null",
                 "fieldloc render: --pose X: 6300 is out of range -6200..6200 mm "
                 "(the spl2013 carpet's half length plus 1000 mm)");
    expect_error("render --seed -1 --out /dev/null",
                 "fieldloc render: --seed: -1 is out of range 0..4294967295");
    expect_error("render --jpeg 5 --out /dev/null",
                 "fieldloc render: --jpeg: 5 is out of range 0..4");
    expect_error("render --robot 0 0 0 green --out /dev/null",
                 "fieldloc render: --robot: jersey \"green\" is not red or blue");
    expect_error("project --camera uva2013 --neck 3000 160 200",
                 "fieldloc project: --neck: 3000 is out of range 50..2000 mm");
    expect_error("project --camera uva2013 160 240",
                 "fieldloc project: V: 240 is out of range -0.5..239.5 px");
    expect_error("scan " FRAME_FAR " --step 0 2",
                 "fieldloc scan: --step COL: 0 is out of range 1..16 px");
    expect_error("simulate --field spl2013 --seed -1",
                 "fieldloc simulate: --seed: -1 is out of range 0..2147483647");
    expect_error("simulate --field spl2013 --steps ten",
                 "fieldloc simulate: --steps: \"ten\" is not a number");
    expect_error("localize x.txt --picture-every 0",
                 "fieldloc localize: --picture-every: 0 is out of range 1..1000000");
    expect_error("demo --every 0", "fieldloc demo: --every: 0 is out of range 1..1000");
    expect_error("demo --seconds -1", "fieldloc demo: --seconds: -1 is out of range 0..86400 s");
    expect_error("eval-detect --tol 46", "fieldloc eval-detect: --tol: 46 is out of range 1..45 deg");
    expect_error("eval-detect --colors build/no_such.colors",
                 "fieldloc eval-detect: build/no_such.colors: cannot open");
    expect_error("fields --all", "fieldloc fields: unknown option --all (fieldloc fields --help)");
    /* good values still work */
    CHECK_EQ(cli_run("project --camera uva2013 --head -0.54 0 160 200", out, sizeof out, err,
                     sizeof err), 0);
    CHECK(strncmp(out, "ground x_mm ", 12) == 0);
    CHECK_EQ(err[0], '\0');
    CHECK_EQ(cli_run("detect " CAM_FAR " --head 0.05 0 --neck 450 --repeat 2 " FRAME_FAR, out,
                     sizeof out, err, sizeof err), 0);
    CHECK(strstr(out, "\nG\t") != NULL || strncmp(out, "G\t", 2) == 0);
    CHECK_EQ(cli_run("simulate --field spl2013 --seed 3 --steps 20 --quiet", out, sizeof out, err,
                     sizeof err), 0);
    CHECK(strstr(out, "pos_rmse_mm") != NULL);
    CHECK_EQ(cli_run("detect --help", NULL, 0, err, sizeof err), 0);
    CHECK(strncmp(err, "usage: fieldloc detect", 22) == 0);
    /* the modern real frames: labels from tools/eval/, images from ../shared */
    if (t_realdata_dir()) {
        CHECK_EQ(cli_run("eval-detect --no-fixtures", out, sizeof out, err, sizeof err), 0);
        CHECK(strstr(out, "modern real frames (hand labels): 19 frames") != NULL);
        CHECK(strstr(out, "field border") != NULL);
    }
    /* reliability: its counts and seed lists are checked like every number
     * (refused before any walk runs) */
    expect_error("reliability --steps \"\"",
                 "fieldloc reliability: --steps: \"\" is not a number");
    expect_error("reliability --steps -1",
                 "fieldloc reliability: --steps: -1 is out of range 0..100000000");
    expect_error("reliability --seeds 1,70000",
                 "fieldloc reliability: --seeds: 70000 is out of range 0..65535");
    expect_error("reliability --frame-seeds 1,,2",
                 "fieldloc reliability: --frame-seeds: \"\" is not a number");
    expect_error("reliability --seeds - --frame-seeds \"\"",
                 "fieldloc reliability: no walk (--seeds and --frame-seeds both empty)");
    expect_error("reliability --bogus",
                 "fieldloc reliability: unknown option --bogus (fieldloc reliability --help)");
    CHECK_EQ(cli_run("reliability --help", NULL, 0, err, sizeof err), 0);
    CHECK(strncmp(err, "usage: fieldloc reliability", 27) == 0);
}

/* walk004: the summary lines, the options' errors. */
static void t_walk004_cli(void)
{
    char out[16384], err[2048];
    if (t_quick)
        return;
    if (cli_find() != 0) {
        t_info("skipped: %s not built", t_cli);
        return;
    }
    CHECK_EQ(cli_run("walk004 --features", out, sizeof out, err, sizeof err), 0);
    CHECK(strstr(out, "\n1 net-yellow ") != NULL);
    CHECK(strstr(out, "\n3 C ") != NULL);
    CHECK(strstr(out, "\nwalk004_error_mm ") != NULL);
    CHECK(strstr(out, "\nwalk004_heading_err_deg ") != NULL);
    CHECK(strstr(out, "\nwalk004_observations 3\n") != NULL);
    expect_error("walk004 --scan -60 60 10",
                 "fieldloc walk004: --scan goes left to right: LEFT_DEG >= RIGHT_DEG");
    expect_error("walk004 --pose 0 0", "fieldloc walk004: --pose needs 3 values");
    expect_error("walk004 --bogus",
                 "fieldloc walk004: unknown option --bogus (fieldloc walk004 --help)");
    CHECK_EQ(cli_run("walk004 --help", out, sizeof out, NULL, 0), 0);
    CHECK(strncmp(out, "usage: fieldloc walk004", 23) == 0);
}

/* Read a picture written by the CLI; 0 when read. */
static int read_pic(const char *name, host_image_t *img)
{
    char path[1300], err[256];
    snprintf(path, sizeof path, "%s/%s", t_dir, name);
    return ppm_read(path, img, err, (int)sizeof err);
}

static void t_pictures(void)
{
    char args[4096], out[4096], err[2048];
    host_image_t plain, classes, border, scan, mask, belief;
    int hplain;
    if (t_quick)
        return;
    if (cli_find() != 0) {
        t_info("skipped: %s not built", t_cli);
        return;
    }
    /* detect --picture: the frame (320 x 240) with the legend strip below */
    snprintf(args, sizeof args, "detect " CAM_FAR " --head 0.05 0 " FRAME_FAR
             " --picture %s/plain.ppm", t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    snprintf(args, sizeof args, "detect " CAM_FAR " --head 0.05 0 " FRAME_FAR
             " --picture %s/classes.ppm --show classes", t_dir);
    CHECK_EQ(cli_run(args, NULL, 0, err, sizeof err), 0);
    snprintf(args, sizeof args, "detect " CAM_FAR " --head 0.05 0 " FRAME_FAR
             " --picture %s/border.ppm --show border", t_dir);
    CHECK_EQ(cli_run(args, NULL, 0, err, sizeof err), 0);
    if (read_pic("plain.ppm", &plain) != 0 || read_pic("classes.ppm", &classes) != 0 ||
        read_pic("border.ppm", &border) != 0) {
        t_fail_msg(__FILE__, __LINE__, "detect pictures readable");
        return;
    }
    hplain = plain.height - 240;
    CHECK_EQ(plain.width, 320);
    CHECK_EQ(hplain, pic_legend_height(320, PIC_LEGEND_DETECT, "spl2013_t_far.raw: 10 features "
                                       "(field spl2013, camera nao4-top-320)"));
    CHECK(count_color(&plain, 240, plain.height, PIC_LEGEND_FG, PIC_LEGEND_FG, PIC_LEGEND_FG) >
          500);
    /* the caption starts with the file name, drawn by the font */
    CHECK(caption_starts_with(&plain, 240, "spl2013_t_far.raw:", 1));
    /* the class map changes the image part (every cell tinted) and adds its
     * legend; the border layer draws the red border into the image */
    CHECK(classes.height > plain.height);
    CHECK(memcmp(classes.rgb, plain.rgb, 320 * 240 * 3) != 0);
    CHECK(count_color(&classes, 0, 240, 255, 0, 0) <= count_color(&border, 0, 240, 255, 0, 0));
    CHECK(count_color(&border, 0, 240, 255, 0, 0) > count_color(&plain, 0, 240, 255, 0, 0) + 100);
    CHECK(count_color(&classes, 240, classes.height, 0, 170, 0) > 0);   /* green swatch */
    host_image_free(&plain);
    host_image_free(&classes);
    host_image_free(&border);
    /* scan --picture and render --mask */
    snprintf(args, sizeof args, "scan " FRAME_FAR " --quiet --picture %s/scan.ppm", t_dir);
    CHECK_EQ(cli_run(args, NULL, 0, err, sizeof err), 0);
    if (read_pic("scan.ppm", &scan) == 0) {
        CHECK_EQ(scan.height, 240 + pic_legend_height(320, PIC_LEGEND_SCAN,
                                                      "spl2013_t_far.raw: grid 160x120 (step 2 "
                                                      "2), border in 160/160 columns"));
        CHECK(count_color(&scan, 240, scan.height, PIC_LEGEND_FG, PIC_LEGEND_FG, PIC_LEGEND_FG) >
              200);
        host_image_free(&scan);
    } else
        t_fail_msg(__FILE__, __LINE__, "scan picture readable");
    snprintf(args, sizeof args, "render --out %s/r.ppm --mask %s/mask.ppm", t_dir, t_dir);
    CHECK_EQ(cli_run(args, NULL, 0, err, sizeof err), 0);
    if (read_pic("mask.ppm", &mask) == 0) {
        CHECK(mask.height > 240);
        CHECK(count_color(&mask, 240, mask.height, 255, 120, 0) > 0);   /* ball swatch */
        host_image_free(&mask);
    } else
        t_fail_msg(__FILE__, __LINE__, "mask picture readable");
    /* demo: the belief picture's strip has the time, error and reliability */
    snprintf(args, sizeof args, "demo --seconds 0.5 --picture-every-s 0 --no-png --out %s/demo",
             t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    if (read_pic("demo/belief_final.ppm", &belief) == 0) {
        /* spl2013 grid: 104 x 74 cells at 8 px */
        CHECK_EQ(belief.width, 832);
        CHECK(belief.height > 592);
        CHECK(count_color(&belief, 592, belief.height, PIC_LEGEND_FG, PIC_LEGEND_FG,
                          PIC_LEGEND_FG) > 500);
        /* first caption line: "t 0.5 s  frame 5  estimate ..." */
        CHECK(caption_starts_with(&belief, 592, "t 0.5 s  frame 5  estimate", 1));
        host_image_free(&belief);
    } else
        t_fail_msg(__FILE__, __LINE__, "demo belief picture readable");
}

/* bench --loc-frames (what callgrind_loc.sh counts): every catalogue
 * localizer listed; the frames run and the line the script parses names
 * the state size; bad names and parameters refused. */
static void t_bench_loc(void)
{
    char out[4096], err[2048], want[256];
    uint16_t i;
    if (t_quick)
        return;
    if (cli_find() != 0) {
        t_info("skipped: %s not built", t_cli);
        return;
    }
    CHECK_EQ(cli_run("bench --loc-list", out, sizeof out, NULL, 0), 0);
    for (i = 0; i < fl_localizer_count(); i++) {
        snprintf(want, sizeof want, "%s\n", fl_localizer_get(i)->name);
        CHECK(strstr(out, want) != NULL);
    }
    CHECK_EQ(cli_run("bench --loc-frames fuzzy --repeat 2 --obs 3", out, sizeof out, NULL, 0), 0);
    snprintf(want, sizeof want, "loc fuzzy state_size %lu samples 0 obs 3 frames 2\n",
             (unsigned long)fl_localizer_fuzzy.state_size);
    CHECK(strcmp(out, want) == 0);
    CHECK_EQ(cli_run("bench --loc-frames fuzzy --param nosuch=1", NULL, 0, err, sizeof err), 2);
    CHECK(strstr(err, "nosuch=1") != NULL);
}

/* Pixels of the box [u0, u1) x [v0, v1) colored as a particle of the
 * estimate's cluster (pic_particle_color, any weight). */
static long count_cluster_px(const host_image_t *im, int u0, int u1, int v0, int v1)
{
    static uint8_t *is_col;
    long n = 0;
    int u, v;
    if (is_col == NULL) {
        int w;
        is_col = calloc(1u << 21, 1);   /* one bit per 24-bit color */
        if (is_col == NULL)
            return -1;
        for (w = 0; w <= 65535; w++) {
            uint8_t c[3];
            uint32_t k;
            pic_particle_color(w / 65535.0, 1, c);
            k = (uint32_t)c[0] << 16 | (uint32_t)c[1] << 8 | c[2];
            is_col[k >> 3] = (uint8_t)(is_col[k >> 3] | 1u << (k & 7));
        }
    }
    for (v = v0; v < v1 && v < im->height; v++)
        for (u = u0; u < u1 && u < im->width; u++) {
            const uint8_t *p = im->rgb + 3 * ((size_t)v * (size_t)im->width + (size_t)u);
            uint32_t k = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
            n += (is_col[k >> 3] >> (k & 7)) & 1;
        }
    return n;
}

/* demo with the particle filter, and --compare: the belief picture shows
 * the particles of the estimate's cluster, on the field and in the 4 x
 * view beside it (as tall as the picture); the second pass over the
 * cached observations (here the same filter, same seed) gives the same
 * summary, the side-by-side picture of the last record has both beliefs
 * and a caption naming both; the observation cache is removed. */
static void t_demo_compare(void)
{
    char args[2048], out[8192], *second;
    host_image_t both, belief;
    if (t_quick)
        return;
    if (cli_find() != 0) {
        t_info("skipped: %s not built", t_cli);
        return;
    }
    snprintf(args, sizeof args,
             "demo --seconds 0.2 --picture-every-s 0 --no-png --out %s/cmp --localizer mcl "
             "--compare mcl", t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, NULL, 0), 0);
    second = strstr(out, "# compare: mcl on the same observations\n");
    CHECK(second != NULL);
    if (second != NULL) {
        const char *a = strstr(out, "\npos_rmse_mm "), *b = strstr(second, "\npos_rmse_mm ");
        CHECK(a != NULL && b != NULL && a < second && strncmp(a, b, 24) == 0);
    }
    if (read_pic("cmp/belief_final.ppm", &belief) == 0) {
        CHECK_EQ(belief.width, 832 + 4 + 592);
        CHECK(count_cluster_px(&belief, 0, 832, 0, 592) >= 100);
        CHECK(count_cluster_px(&belief, 836, 836 + 592, 0, 592) >= 1000);
        host_image_free(&belief);
    } else
        t_fail_msg(__FILE__, __LINE__, "mcl belief picture readable");
    if (read_pic("cmp/compare_demo_final.ppm", &both) == 0) {
        CHECK_EQ(both.width, 2 * (832 + 4 + 592) + 8);
        CHECK(both.height > 592);
        CHECK(caption_starts_with(&both, 592, "left mcl: t 0.2 s", 2));
        CHECK(count_cluster_px(&both, 1436, 1436 + 832, 0, 592) >= 100);
        host_image_free(&both);
    } else
        t_fail_msg(__FILE__, __LINE__, "compare picture readable");
    snprintf(args, sizeof args, "%s/cmp/compare_obs.cache", t_dir);
    CHECK(access(args, F_OK) != 0);
}

/* ---- calibration files end to end ------------------------------------------ */

static int write_text(const char *name, const char *text)
{
    char path[1200];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", t_dir, name);
    f = fopen(path, "w");
    if (f == NULL)
        return -1;
    fputs(text, f);
    return fclose(f);
}

/* simulate --export-stream, replay --stream end to end: the same step and
 * summary lines; a malformed stream refused with its line (status 2, one
 * stderr line); --kidnaps checked like every number. */
static void t_stream(void)
{
    static char out[1 << 16], out2[1 << 16];
    char err[1024], args[2600], msg[1400];
    const char *a, *b;
    if (cli_find() != 0) {
        t_info("cli.stream: %s not built, skipped", t_cli);
        return;
    }
    expect_error("simulate --field spl2013 --kidnaps 17",
                 "fieldloc simulate: --kidnaps: 17 is out of range 0..16");
    snprintf(args, sizeof args, "simulate --field aibo2004 --seed 4 --steps 60 --kidnaps 3 "
                                "--export-stream %s/walk.stream", t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    snprintf(args, sizeof args, "replay --stream %s/walk.stream --localizer fuzzy", t_dir);
    CHECK_EQ(cli_run(args, out2, sizeof out2, err, sizeof err), 0);
    CHECK_EQ(err[0], '\0');
    /* from the first step line to the end, except simulate's "# steps" and
     * replay's "# records" lines (the one-line counts each prints) */
    a = strstr(out, "\nstep 0 ");
    b = strstr(out2, "\nstep 0 ");
    CHECK(a != NULL && b != NULL);
    if (a != NULL && b != NULL) {
        const char *ea = strstr(a, "\n# steps "), *eb = strstr(b, "\n# records ");
        CHECK(ea != NULL && eb != NULL);
        if (ea != NULL && eb != NULL) {
            CHECK_EQ(ea - a, eb - b);
            CHECK(strncmp(a, b, (size_t)(ea - a)) == 0);
            ea = strstr(ea, "\n# localizer:");
            eb = strstr(eb, "\n# localizer:");
            CHECK(ea != NULL && eb != NULL && strcmp(ea, eb) == 0);
        }
    }
    CHECK_EQ(write_text("bad.stream", "fieldloc-stream 1\nfield spl2013\ncamera nao4-top-320\n"
                                      "mode features\nevery 1\nframe_hz 30\nprior_half 1\n"
                                      "record 0 0 0 0 0 0\npredict 1 2 three\n"), 0);
    snprintf(args, sizeof args, "replay --stream %s/bad.stream", t_dir);
    snprintf(msg, sizeof msg, "replay: %s/bad.stream: line 9: 'three' is not an integer in its "
                              "range", t_dir);
    expect_error_at(__LINE__, args, msg);
}

/* simulate --vision (seed 004's corner features): refused on a field
 * without them (feature and frames mode) and for an unknown value; a corners walk exported as a stream (kinds c f n
 * N) replays to the same step lines. */
static void t_vision(void)
{
    static char out[1 << 16], out2[1 << 16];
    char err[1024], args[2600];
    const char *a, *b, *ea, *eb;
    if (cli_find() != 0) {
        t_info("cli.vision: %s not built, skipped", t_cli);
        return;
    }
    expect_error("simulate --field spl2013 --features --vision corners",
                 "simulate: --vision corners: field spl2013 has no corner features (seed 004's, "
                 "fl_field_t.features; aibo2004 has them)");
    expect_error("simulate --field spl2013 --frames --vision both",
                 "simulate: --vision both: field spl2013 has no corner features (seed 004's, "
                 "fl_field_t.features; aibo2004 has them)");
    expect_error("simulate --field aibo2004 --vision lines", "simulate: --vision ltx|corners|both");
    snprintf(args, sizeof args, "simulate --field aibo2004 --seed 2 --steps 90 --vision corners "
                                "--export-stream %s/corners.stream", t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    CHECK(strstr(out, "# vision corners: ") != NULL);
    snprintf(args, sizeof args, "replay --stream %s/corners.stream --localizer fuzzy", t_dir);
    CHECK_EQ(cli_run(args, out2, sizeof out2, err, sizeof err), 0);
    CHECK_EQ(err[0], '\0');
    a = strstr(out, "\nstep 0 ");
    b = strstr(out2, "\nstep 0 ");
    CHECK(a != NULL && b != NULL);
    if (a == NULL || b == NULL)
        return;
    ea = strstr(a, "\n# steps ");
    eb = strstr(b, "\n# records ");
    CHECK(ea != NULL && eb != NULL);
    if (ea == NULL || eb == NULL)
        return;
    CHECK_EQ(ea - a, eb - b);
    CHECK(strncmp(a, b, (size_t)(ea - a)) == 0);
    /* the stream holds every feature kind's letter */
    {
        static char st[1 << 20];
        char path[1200];
        FILE *f;
        size_t got = 0;
        snprintf(path, sizeof path, "%s/corners.stream", t_dir);
        f = fopen(path, "r");
        CHECK(f != NULL);
        if (f != NULL) {
            got = fread(st, 1, sizeof st - 1, f);
            fclose(f);
        }
        st[got] = '\0';
        CHECK(strstr(st, "\nobs c ") != NULL && strstr(st, "\nobs f ") != NULL &&
              strstr(st, "\nobs n ") != NULL && strstr(st, "\nobs N ") != NULL);
        CHECK(strstr(st, "\nobs L ") == NULL && strstr(st, "\nobs G ") == NULL);
    }
    /* frames mode: the corner stage on 11 rendered frames; its
     * observations only (no L/T/X), cached under a key naming the vision
     * path and read back to the same step lines; an ltx run on that cache
     * file does not read it (another key) */
    {
        static char o3[1 << 16], o4[1 << 16];
        char path[1200], head[256];
        const char *v;
        int nobs = -1, nl = -1;
        FILE *f;
        snprintf(path, sizeof path, "%s/corners.obs", t_dir);
        remove(path);
        snprintf(args, sizeof args, "simulate --field aibo2004 --seed 2 --frames --steps 31 "
                                    "--vision corners --obs-cache %s", path);
        CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
        CHECK(strstr(out, "# vision corners: ") != NULL);
        v = strstr(out, "# vision corner_c ");
        CHECK(v != NULL && sscanf(v, "# vision corner_c %d", &nobs) == 1 && nobs > 0);
        v = strstr(out, "# vision L ");
        CHECK(v != NULL && sscanf(v, "# vision L %d", &nl) == 1 && nl == 0);
        f = fopen(path, "rb");
        CHECK(f != NULL && fgets(head, sizeof head, f) != NULL);
        if (f != NULL)
            fclose(f);
        CHECK(strstr(head, " corners\n") != NULL);
        CHECK_EQ(cli_run(args, o3, sizeof o3, err, sizeof err), 0);
        a = strstr(out, "\nstep 0 ");
        b = strstr(o3, "\nstep 0 ");
        ea = a ? strstr(a, "\n# steps ") : NULL;
        eb = b ? strstr(b, "\n# steps ") : NULL;
        CHECK(ea != NULL && eb != NULL && ea - a == eb - b && strncmp(a, b, (size_t)(ea - a)) == 0);
        snprintf(args, sizeof args, "simulate --field aibo2004 --seed 2 --frames --steps 31 "
                                    "--obs-cache %s", path);
        CHECK_EQ(cli_run(args, o4, sizeof o4, err, sizeof err), 0);
        v = strstr(o4, "# vision corner_c ");
        CHECK(v == NULL || (sscanf(v, "# vision corner_c %d", &nobs) == 1 && nobs == 0));
        v = strstr(o4, "# vision L ");
        CHECK(v != NULL && sscanf(v, "# vision L %d", &nl) == 1 && nl > 0);
    }
}

/* calibrate --frames: frames rendered by `fieldloc render` with a neck of
 * 480 mm and a pitch offset of 0.04 rad (2.29 deg) against the camera's
 * 445 mm / 0, fitted, written, read back by detect --calib and localize
 * --calib; malformed frames and calibration files refused with their line
 * (status 2, one stderr line). */
static void t_calib_files(void)
{
    static const int shot[4][5] = {
        {-2500, 0, 0, 0, 18}, {-1500, 1500, -30, 10, 20}, {0, -1500, 90, -20, 16},
        {2000, 1000, 0, 0, 20}};
    char args[4096], out[8192], err[2048], want[1400], frames[1024] = "";
    int k, rc;
    if (t_quick)
        return;
    if (cli_find() != 0) {
        t_info("skipped: %s not built", t_cli);
        return;
    }
    for (k = 0; k < 4; k++) {
        char line[128];
        snprintf(args, sizeof args,
                 "render --field spl2013 --camera nao4-top-320 --pose %d %d %d --head %.6f %.6f "
                 "--neck 480 --pitch-offset 0.04 --seed %d --out %s/cal%d.ppm",
                 shot[k][0], shot[k][1], shot[k][2], shot[k][4] * 3.14159265358979 / 180,
                 shot[k][3] * 3.14159265358979 / 180, k + 1, t_dir, k);
        CHECK_EQ(cli_run(args, NULL, 0, err, sizeof err), 0);
        snprintf(line, sizeof line, "cal%d.ppm %d %d %d %d %d\n", k, shot[k][0], shot[k][1],
                 shot[k][2], shot[k][3], shot[k][4]);
        strcat(frames, line);
    }
    CHECK_EQ(write_text("cal_frames.txt", frames), 0);
    snprintf(args, sizeof args,
             "calibrate --field spl2013 --camera nao4-top-320 --frames %s/cal_frames.txt "
             "--out %s/robot.calib", t_dir, t_dir);
    rc = cli_run(args, out, sizeof out, err, sizeof err);
    CHECK_EQ(rc, 0);
    CHECK(strstr(out, "total: 4 frames (0 skipped)") != NULL);
    {
        char path[1200], text[FL_CALIB_TEXT_MAX + 1];
        FILE *f;
        size_t n = 0;
        fl_calib_t c;
        snprintf(path, sizeof path, "%s/robot.calib", t_dir);
        f = fopen(path, "rb");
        if (f != NULL) {
            n = fread(text, 1, sizeof text, f);
            fclose(f);
        }
        CHECK_EQ(fl_calib_parse(text, n, &c, NULL, NULL), FL_OK);
        CHECK(strcmp(c.camera, "nao4-top-320") == 0);
        /* 10 mm, 0.3 deg (55 binary units) as in calib.fit_recovers */
        CHECK(abs(c.neck_height_mm - 480) <= 10);
        CHECK(abs(c.pitch_offset - fl_angle_from_urad(40000)) <= 55);
        CHECK(abs(c.roll_offset) <= 55);
        t_info("fitted neck %d mm, pitch offset %d, roll offset %d (binary units; true 480, %d, 0)",
               (int)c.neck_height_mm, (int)c.pitch_offset, (int)c.roll_offset,
               (int)fl_angle_from_urad(40000));
    }
    /* detect --calib: seen from (-2500, 0), the centre-circle X crossings
     * are at sqrt(2500^2 + 750^2) = 2610 mm, the centre mark at 2500 mm
     * (with the camera's defaults they come out about 17 % long) */
    snprintf(args, sizeof args,
             "detect --field spl2013 --camera nao4-top-320 --head 0.314159 0 --calib "
             "%s/robot.calib %s/cal0.ppm", t_dir, t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    {
        const char *p = out;
        int n_x = 0;
        while ((p = strstr(p, "X\t")) != NULL) {
            double u, v, conf, bearing;
            int range;
            if (sscanf(p, "X\t%lf\t%lf\t%lf\t%d\t%lf", &u, &v, &conf, &range, &bearing) == 5) {
                CHECK(abs(range - 2610) <= 40 || abs(range - 2500) <= 40);
                n_x++;
            }
            p += 2;
        }
        CHECK_EQ(n_x, 3);
    }
    /* errors: the frames file and the calibration file name their line */
    CHECK_EQ(write_text("bad_frames.txt", "# pose set by hand\ncal0.ppm 0 0 0 0\n"), 0);
    snprintf(args, sizeof args,
             "calibrate --field spl2013 --camera nao4-top-320 --frames %s/bad_frames.txt", t_dir);
    snprintf(want, sizeof want,
             "calibrate: %s/bad_frames.txt:2: expected: IMAGE X_MM Y_MM HEADING_DEG HEAD_YAW_DEG "
             "HEAD_PITCH_DEG [TORSO_PITCH_DEG TORSO_ROLL_DEG]", t_dir);
    expect_error(args, want);
    CHECK_EQ(write_text("bad.calib", "fieldloc-calibration 1\ncamera nao4-top-320\n"
                                     "focal_px 280\n"), 0);
    snprintf(args, sizeof args, "detect " CAM_FAR " --calib %s/bad.calib " FRAME_FAR, t_dir);
    snprintf(want, sizeof want, "detect: %s/bad.calib:3: unknown key", t_dir);
    expect_error(args, want);
    CHECK_EQ(write_text("seq.txt", "field spl2013\ncamera nao4-top-320\n"
                                   "frame cal0.ppm odo 0 0 0 head 0.314159 0\n"), 0);
    snprintf(args, sizeof args, "localize %s/seq.txt --calib %s/bad.calib", t_dir, t_dir);
    snprintf(want, sizeof want, "localize: %s/bad.calib:3: unknown key", t_dir);
    expect_error(args, want);
    /* another camera's calibration is refused */
    CHECK_EQ(write_text("uva.calib", "fieldloc-calibration 1\ncamera uva2013\n"), 0);
    snprintf(args, sizeof args, "localize %s/seq.txt --calib %s/uva.calib", t_dir, t_dir);
    snprintf(want, sizeof want,
             "localize: %s/uva.calib is for camera uva2013, the sequence uses nao4-top-320", t_dir);
    expect_error(args, want);
    snprintf(args, sizeof args, "localize %s/seq.txt --calib %s/robot.calib", t_dir, t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    CHECK(strncmp(out, "pose ", 5) == 0);
}

/* `localize --physar` (tools/loc/physar.h) and `detect --imu`: the option
 * errors, and a short run (2 frames per point, one localizer): one line
 * per point and the summary with the real-data folder, one skip line
 * without it. */
static void t_physar_cli(void)
{
    char out[8192], err[2048];
    const char *p;
    int rc, n_point = 0;
    if (t_quick)
        return;
    if (cli_find() != 0) {
        t_info("skipped: %s not built", t_cli);
        return;
    }
    expect_error("localize --physar --imu gyro",
                 "fieldloc localize: --imu: \"gyro\" is not angles, accel or off");
    expect_error("localize --physar --repeat 0",
                 "fieldloc localize: --repeat: 0 is out of range 1..1000");
    expect_error("detect " CAM_FAR " --imu 0 0.9 " FRAME_FAR,
                 "fieldloc detect: --imu angley: 0.9 is out of range -0.7854..0.7854 rad");
    /* --repeat and --imu belong to --physar; --param needs --localizer there */
    CHECK_EQ(cli_run("localize --repeat 3 --uva-spots", NULL, 0, NULL, 0), 2);
    CHECK_EQ(cli_run("localize --physar --param seed=2", NULL, 0, NULL, 0), 2);
    CHECK_EQ(cli_run("detect " CAM_FAR " --imu 0.01 -0.02 " FRAME_FAR, NULL, 0, NULL, 0), 0);
    rc = cli_run("localize --physar --localizer fuzzy --repeat 2 --imu off", out, sizeof out, err,
                 sizeof err);
    CHECK_EQ(rc, 0);
    if (strncmp(out, "physar: skipped", 15) == 0) {
        t_info("%s", rd_skip_message());
        return;
    }
    for (p = out; (p = strstr(p, "\nphysar fuzzy  black1_point")) != NULL; p++)
        n_point++;
    CHECK_EQ(n_point, 5);
    CHECK(strstr(out, "\nphysar_summary fuzzy  points 5 goal_met ") != NULL);
    CHECK(strstr(out, "physar mcl") == NULL);
}

/* Today's field in the synthetic world: simulate --field spl2020 (feature
 * mode, 30 s) tracks within a bound (seed 1 measured 83 mm, 1.68 deg; seeds
 * 1-5 60-83 mm, 1.45-1.68 deg), and demo --field spl2020 writes its pictures (the frame
 * half at the walk's 640 x 480). */
static void t_spl2020(void)
{
    char out[4096], err[512], args[1400];
    const char *p;
    double pos = -1, head = -1;
    host_image_t frame;
    if (cli_find() != 0) {
        t_info("cli.spl2020: %s not built, skipped", t_cli);
        return;
    }
    CHECK_EQ(cli_run("simulate --field spl2020 --seed 1 --steps 900 --quiet", out, sizeof out,
                     err, sizeof err), 0);
    CHECK(strstr(out, "# simulate field spl2020 ") != NULL);
    p = strstr(out, "\npos_rmse_mm ");
    CHECK(p != NULL && sscanf(p, "\npos_rmse_mm %lf", &pos) == 1);
    p = strstr(out, "\nheading_rmse_deg ");
    CHECK(p != NULL && sscanf(p, "\nheading_rmse_deg %lf", &head) == 1);
    t_info("simulate spl2020 seed 1, 30 s features: pos rmse %.1f mm, heading %.2f deg", pos, head);
    CHECK(pos >= 0 && pos <= 150);
    CHECK(head >= 0 && head <= 3);
    if (t_quick)
        return;
    snprintf(args, sizeof args,
             "demo --field spl2020 --seconds 0.5 --picture-every-s 0 --no-png --out %s/demo2020", t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    CHECK(strstr(out, "field spl2020, camera nao6-top-640") != NULL);
    if (read_pic("demo2020/frame_final.ppm", &frame) == 0) {
        CHECK(frame.width >= 640);
        CHECK(frame.height >= 480);
        host_image_free(&frame);
    } else
        t_fail_msg(__FILE__, __LINE__, "demo spl2020 frame picture readable");
    if (read_pic("demo2020/demo_final.ppm", &frame) == 0) {
        CHECK(frame.width > 640);   /* the frame beside the belief */
        host_image_free(&frame);
    } else
        t_fail_msg(__FILE__, __LINE__, "demo spl2020 picture readable");
}

/* `fieldloc coach` as a user meets it: its options and files (the path
 * itself: host_tests/test_coach_cli.c). */
static void t_coach(void)
{
    char out[8192], err[512], args[1400];
    if (cli_find() != 0) {
        t_info("cli.coach: %s not built, skipped", t_cli);
        return;
    }
    expect_error("coach", "fieldloc coach: needs IMAGE.ppm and --points FILE (fieldloc coach --help)");
    expect_error("coach a.ppm --points p --scale 3",
                 "fieldloc coach: --scale: 3 is out of range 5..200 mm per pixel");
    expect_error("coach a.ppm --points", "fieldloc coach: --points needs 1 value");
    expect_error("coach a.ppm --points p --bogus",
                 "fieldloc coach: unknown option --bogus (fieldloc coach --help)");
    expect_error("coach /nonexistent.ppm --points fixtures/coach/coach.points",
                 "fieldloc coach: image /nonexistent.ppm: cannot open");
    expect_error("coach fixtures/coach/coach_two.ppm --points /nonexistent.points",
                 "fieldloc coach: /nonexistent.points: cannot open");
    if (t_quick)
        return;
    snprintf(args, sizeof args,
             "coach fixtures/coach/coach_two.ppm --points fixtures/coach/coach.points "
             "--background fixtures/coach/coach_empty.ppm --out %s/coach.png",
             t_dir);
    CHECK_EQ(cli_run(args, out, sizeof out, err, sizeof err), 0);
    CHECK(strstr(out, "homography_status ok\n") != NULL);
    CHECK(strstr(out, "\nfoot red ") != NULL);
    CHECK(strstr(out, "\nfoot blue ") != NULL);
    CHECK(strstr(out, "\npicture ") != NULL);
    CHECK_EQ(err[0], 0);
}

void suite_cli(void)
{
    t_run("cli.font", t_font);
    t_run("cli.legend", t_legend);
    t_run("cli.caption", t_caption);
    t_run("cli.numbers", t_numbers);
    t_run("cli.pictures", t_pictures);
    t_run("cli.bench_loc", t_bench_loc);
    t_run("cli.demo_compare", t_demo_compare);
    t_run("cli.calib_files", t_calib_files);
    t_run("cli.stream", t_stream);
    t_run("cli.vision", t_vision);
    t_run("cli.physar", t_physar_cli);
    t_run("cli.spl2020", t_spl2020);
    t_run("cli.coach", t_coach);
    t_run("cli.walk004", t_walk004_cli);
}
