/*
 * tools/cli/cmd_scan.c - `fieldloc scan`: run the column scanner (scan.h) on
 * one frame, print the border per column and the counts, optionally draw
 * the picture. The scanner helpers are in tools/eval/scan_tool.c.
 *
 *   fieldloc scan IMAGE.ppm|FRAME.raw [--picture OUT.ppm|OUT.png]
 *        [--format rgb|yuyv|planar] [--step COL ROW] [--full]
 *        [--run N] [--camera NAME --head PITCH_RAD YAW_RAD [--neck MM]]
 *        [--uva] [--adapt] [--repeat N] [--quiet] [--colors default|auto|FILE]
 *        [--field NAME]
 * --full is --step 1 1.  --uva takes the camera from the UvA 2013 labels
 * (camera "uva2013", the record of the image's file name).  --adapt re-scans
 * once after fl_color_adapt when the field color moved.  --repeat scans
 * the same frame N times (for callgrind: instructions per frame =
 * difference of two N / difference of N), tracking the field colour after
 * each scan.  --colors default|auto|FILE: the colour classes
 * (eval/colors_opt.h; a file that does not parse: "fieldloc scan:
 * FILE:LINE: reason", exit status 2); without it, auto for real frames
 * that are not the UvA 2013 set, else default.  --field NAME gives the
 * goal colour for auto (yellow goals keep a yellow class clear of the
 * carpet); without it, and without --uva, white goals: no yellow class.  Besides the counts over
 * the whole grid, the classes of the cells below the border (the lower
 * half in columns without one) are printed as fractions.
 * The picture has a legend strip below the frame (picture.h).  Numbers are
 * checked (tools/cli/args.h): --step 1..16 each, --run 1..255 px, --head
 * within the NAO head joints (the camera's limit otherwise), --neck
 * 50..2000 mm, --repeat 1..1000000; errors exit with status 2.
 */
#include "eval/scan_tool.h"
#include "cli/args.h"
#include "eval/colors_opt.h"
#include "eval/detect.h"
#include "eval/picture.h"

#include "io/ppm.h"
#include "io/realdata.h"
#include "cli/registry.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static int usage(void)
{
    fprintf(stderr,
            "usage: fieldloc scan IMAGE.ppm|FRAME.raw [--picture OUT.ppm|.png]\n"
            "         [--format rgb|yuyv|planar] [--step COL ROW] [--full] [--run N]\n"
            "         [--camera NAME --head PITCH_RAD YAW_RAD [--neck MM]] [--uva]\n"
            "         [--adapt] [--repeat N] [--quiet] [--colors default|auto|FILE] [--field NAME]\n"
            "  --step 1..16 1..16, --run 1..255 px, --neck 50..2000 mm, --repeat 1..1000000,\n"
            "  --head: NAO HeadPitch -0.6720..0.5149 rad, HeadYaw -2.0857..2.0857 rad\n");
    return 2;
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* Camera of a UvA 2013 image from its labels; 0 when found. */
static int uva_camera(const char *path, fl_camera_t *cam)
{
    const char *dir = rd_dir();
    char csv[4096], err[256];
    rd_uva_set_t set;
    int k, found = -1;
    const fl_camera_model_t *m = fl_camera_model_find("uva2013");
    if (!dir || !m || rd_path(csv, sizeof csv, dir, RD_UVA_CSV) != 0)
        return -1;
    if (rd_uva_load(csv, &set, err, sizeof err) != 0) {
        fprintf(stderr, "scan: %s\n", err);
        return -1;
    }
    for (k = 0; k < set.n; k++)
        if (!strcmp(set.rec[k].file, base_name(path))) {
            fl_camera_pose_t pose;
            rd_uva_camera_pose(&set.rec[k], m, &pose);
            found = fl_camera_init(cam, m, &pose) == FL_OK ? 0 : -1;
            break;
        }
    rd_uva_free(&set);
    return found;
}

/* Class fractions of the cells below the border (the lower half of the
 * grid in columns without one): the carpet where the scanner sees it. */
static void scan_print_below(const fl_scan_t *s)
{
    int32_t i, j, n[4] = {0, 0, 0, 0}, tot = 0;
    for (i = 0; i < s->cols; i++) {
        int32_t j0 = s->border_v[i] < s->height ? s->first_row[i] : s->rows / 2;
        for (j = j0; j < s->rows; j++) {
            n[fl_scan_class_at(s, i, j)]++;
            tot++;
        }
    }
    printf("below border: %d cells, green %.3f white %.3f yellow %.3f other %.3f\n", (int)tot,
           tot ? n[FL_CLASS_GREEN] / (double)tot : 0.0, tot ? n[FL_CLASS_WHITE] / (double)tot : 0.0,
           tot ? n[FL_CLASS_YELLOW] / (double)tot : 0.0, tot ? n[FL_CLASS_OTHER] / (double)tot : 0.0);
}

int cmd_scan(int argc, char **argv)
{
    const char *in = NULL, *picture = NULL, *camname = NULL, *field_name = NULL;
    const fl_field_t *field = NULL;
    colors_opt_t co;
    static fl_color_estimate_t est;
    fl_pixel_format_t fmt = 0;
    fl_scan_params_t sp;
    static fl_color_table_t colors;
    static fl_scan_t scan;
    fl_camera_t cam;
    fl_camera_pose_t pose = {460, 0, 0, 0, 0, 0, 0};
    int use_cam = 0, uva = 0, adapt = 0, quiet = 0, repeat = 1, k, i;
    double pitch = 0, yaw = 0;
    const char *head_text[2] = {NULL, NULL};
    render_frame_t fr;
    scantool_frame_t conv;
    const fl_image_t *view;
    uint8_t *rgb;
    char err[256];

    fl_scan_params_default(&sp);
    memset(&co, 0, sizeof co);
    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--picture") && k + 1 < argc)
            picture = argv[++k];
        else if (!strcmp(argv[k], "--format") && k + 1 < argc) {
            fmt = render_format_from_name(argv[++k]);
            if (!fmt)
                return usage();
        } else if (!strcmp(argv[k], "--step") && k + 2 < argc) {
            if (arg_int32("scan", "--step COL", argv[++k], 1, 16, "px", &sp.col_step) ||
                arg_int32("scan", "--step ROW", argv[++k], 1, 16, "px", &sp.row_step))
                return 2;
        } else if (!strcmp(argv[k], "--full"))
            sp.col_step = sp.row_step = 1;
        else if (!strcmp(argv[k], "--run") && k + 1 < argc) {
            if (arg_int32("scan", "--run", argv[++k], 1, 255, "px", &sp.border_run_px))
                return 2;
        } else if (!strcmp(argv[k], "--camera") && k + 1 < argc)
            camname = argv[++k];
        else if (!strcmp(argv[k], "--head") && k + 2 < argc) {
            head_text[0] = argv[++k];   /* range checked once the camera is known */
            head_text[1] = argv[++k];
            if (arg_double("scan", "--head pitch", head_text[0], -1e9, 1e9, NULL, &pitch) ||
                arg_double("scan", "--head yaw", head_text[1], -1e9, 1e9, NULL, &yaw))
                return 2;
            use_cam = 1;
        } else if (!strcmp(argv[k], "--neck") && k + 1 < argc) {
            if (arg_int32("scan", "--neck", argv[++k], FL_CAMERA_NECK_MIN_MM,
                          FL_CAMERA_NECK_MAX_MM, "mm", &pose.neck_height_mm))
                return 2;
        } else if (!strcmp(argv[k], "--uva"))
            uva = 1;
        else if (!strcmp(argv[k], "--adapt"))
            adapt = 1;
        else if (!strcmp(argv[k], "--repeat") && k + 1 < argc) {
            if (arg_int("scan", "--repeat", argv[++k], 1, 1000000, NULL, &repeat))
                return 2;
        } else if (!strcmp(argv[k], "--quiet"))
            quiet = 1;
        else if (!strcmp(argv[k], "--colors") && k + 1 < argc) {
            if (colors_opt_parse("scan", argv[++k], &co) != 0)
                return 2;
        } else if (!strcmp(argv[k], "--field") && k + 1 < argc)
            field_name = argv[++k];
        else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            usage();
            return 0;
        } else if (argv[k][0] == '-' || in)
            return arg_unknown("scan", argv[k],
                               "--picture=1 --format=1 --step=2 --run=1 --camera=1 --head=2 "
                               "--neck=1 --repeat=1 --colors=1 --field=1");
        else
            in = argv[k];
    }
    if (!in || repeat < 1)
        return usage();
    if (fl_scan_init(&scan, &sp) != FL_OK) {
        fprintf(stderr, "scan: bad --step or --run\n");
        return 2;
    }
    if (render_read_frame(in, &fr, err, sizeof err) != 0) {
        fprintf(stderr, "scan: %s\n", err);
        return 1;
    }
    /* RGB for the picture and for conversions */
    rgb = malloc((size_t)fr.width * (size_t)fr.height * 3);
    if (!rgb)
        return 1;
    for (i = 0; i < fr.width * fr.height; i++)
        fl_image_get_rgb(&fr.view, i % fr.width, i / fr.width, rgb + 3 * (size_t)i);
    view = &fr.view;
    memset(&conv, 0, sizeof conv);
    if (fmt && fmt != fr.format) {
        if (scantool_frame_from_rgb(rgb, fr.width, fr.height, fmt, &conv) != 0) {
            fprintf(stderr, "scan: cannot convert to %s\n", render_format_name(fmt));
            return 1;
        }
        view = &conv.view;
    }
    if (uva) {
        if (uva_camera(in, &cam) != 0) {
            fprintf(stderr, "scan: no UvA 2013 label record for %s (%s)\n", base_name(in),
                    rd_dir() ? "not in the CSV" : rd_skip_message());
            return 1;
        }
        use_cam = 1;
    } else if (use_cam || camname) {
        const fl_camera_model_t *m =
            fl_camera_model_find(camname ? camname : "nao4-bottom-320");
        if (!m) {
            fprintf(stderr, "scan: unknown camera %s\n", camname);
            return 2;
        }
        if (head_text[0] != NULL &&
            arg_head("scan", "--head", m, head_text[0], head_text[1], &pitch, &yaw) != 0)
            return 2;
        pose.head_pitch = (fl_angle_t)lrint(pitch * 32768.0 / M_PI);
        pose.head_yaw = (fl_angle_t)lrint(yaw * 32768.0 / M_PI);
        if (fl_camera_init(&cam, m, &pose) != FL_OK) {
            fprintf(stderr, "scan: bad camera pose\n");
            return 2;
        }
        use_cam = 1;
    }
    if (field_name != NULL && (field = fl_field_find(field_name)) == NULL) {
        fprintf(stderr, "scan: unknown field %s (see: fieldloc fields)\n", field_name);
        return 2;
    }
    if (uva && field == NULL)
        field = fl_field_find("uva2013");
    colors_opt_resolve(&co, field, in);
    if (colors_opt_setup(&co, &colors, field, view, use_cam ? &cam : NULL, &est) < 0) {
        fprintf(stderr, "scan: colour classes refused\n");
        return 2;
    }
    for (k = 0; k < repeat; k++) {
        fl_scan_frame(&scan, &colors, view, use_cam ? &cam : NULL);
        if (k + 1 < repeat)
            colors_opt_track(&colors, &scan);
    }
    if (adapt && fl_color_adapt(&colors, &scan.field) == 1) {
        printf("adapted: hue shift %d, green s_lo %d; re-scanned\n", colors.hue_shift,
               colors.green.s_lo);
        fl_scan_frame(&scan, &colors, view, use_cam ? &cam : NULL);
    }
    if (scan.status != FL_OK) {
        fprintf(stderr, "scan: %s\n", fl_status_str(scan.status));
        return 1;
    }
    if (!quiet) {
        printf("frame %dx%d %s  grid %dx%d (step %d %d)  border search from row %d\n",
               scan.width, scan.height, render_format_name(view->format), scan.cols,
               scan.rows, sp.col_step, sp.row_step, scan.start_v);
        printf("border");
        for (i = 0; i < scan.cols; i++)
            printf(" %d", scan.border_v[i]);
        printf("\n");
        printf("columns with border %d/%d\n", scan.n_border, scan.cols);
        printf("cells green %d white %d yellow %d other %d\n",
               fl_scan_count(&scan, FL_CLASS_GREEN), fl_scan_count(&scan, FL_CLASS_WHITE),
               fl_scan_count(&scan, FL_CLASS_YELLOW), fl_scan_count(&scan, FL_CLASS_OTHER));
        scan_print_below(&scan);
        if (co.mode != COLORS_DEFAULT)
            colors_print_stats(stdout, &co, &colors, &est);
        printf("white runs rejected %d, checks skipped %d, feet dropped %d\n",
               scan.white_rejected, scan.checks_skipped, scan.feet_dropped);
        printf("feet %d:", scan.n_feet);
        for (i = 0; i < scan.n_feet; i++)
            printf(" (%d,%d)", scan.feet[i].u, scan.feet[i].v);
        printf("\n");
        printf("field colour: n %d hue %d sat %d val %d luma %d (table hue shift %d)\n",
               scan.field.n, scan.field.hue, scan.field.sat, scan.field.val,
               scan.field.luma, colors.hue_shift);
    }
    if (picture) {
        host_image_t pic, out;
        size_t len = strlen(picture);
        char caption[256];
        int rc;
        pic.width = fr.width;
        pic.height = fr.height;
        pic.rgb = malloc((size_t)fr.width * (size_t)fr.height * 3);
        if (!pic.rgb)
            return 1;
        scantool_picture(&scan, rgb, fr.width, fr.height, pic.rgb);
        snprintf(caption, sizeof caption, "%s: grid %dx%d (step %d %d), border in %d/%d columns",
                 base_name(in), scan.cols, scan.rows, sp.col_step, sp.row_step, scan.n_border,
                 scan.cols);
        rc = pic_add_legend(&pic, PIC_LEGEND_SCAN, caption, &out);
        free(pic.rgb);
        if (rc != 0)
            return 1;
        if (len > 4 && !strcmp(picture + len - 4, ".png"))
            rc = png_write(picture, out.rgb, out.width, out.height);
        else
            rc = ppm_write(picture, out.rgb, out.width, out.height);
        if (rc != 0)
            fprintf(stderr, "scan: cannot write %s\n", picture);
        else if (!quiet)
            printf("picture %s\n", picture);
        host_image_free(&out);
    }
    scantool_frame_free(&conv);
    free(rgb);
    render_frame_free(&fr);
    return 0;
}
