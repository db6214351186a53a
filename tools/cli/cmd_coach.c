/*
 * tools/cli/cmd_coach.c - `fieldloc coach`: the coach's frame (seed 003,
 * sections 3.1-3.3) from the command line.
 *
 *   fieldloc coach IMAGE.ppm|FRAME.raw --points FILE [--background EMPTY.ppm|.raw]
 *        [--field spl2016] [--out PICTURE.png|.ppm] [--scale MM_PER_PX]
 *        [--repeat N]
 *
 * Frames: PPM, or the FLRAW container of YUYV422 / planar frames
 * (fixtures/README.md), given to the firmware in their own format.
 * Fits the image -> field homography from the points file
 * (tools/world/coach_scene.h: "NAME U V" or "U V X_MM Y_MM" lines), prints
 * it with its reprojection error and status, runs the firmware's coach
 * image path (fieldloc/coach.h) on the frame, prints each foot (team, field
 * x_mm y_mm, confidence, pixel) and writes the picture: the frame with the
 * field lines through the homography beside the top view with the feet
 * marked (tools/eval/coach_view.h).  --repeat N runs the coach path N times
 * on the frame (tools/bench/callgrind_coach.sh counts its instructions).
 * Exit status 0 done, 1 the coach path
 * refused the frame (e.g. no field in it), 2 bad input (one line on stderr
 * saying what).
 */
#include "cli/args.h"
#include "cli/registry.h"
#include "eval/coach_view.h"

#include <stdio.h>
#include <string.h>

static int usage(void)
{
    fprintf(stderr,
            "usage: fieldloc coach IMAGE.ppm|FRAME.raw --points FILE [--background EMPTY.ppm|.raw]\n"
            "         [--field NAME] [--out PICTURE.png|.ppm] [--scale MM_PER_PX] [--repeat N]\n"
            "  points file: one 'NAME U V' (e.g. centre_mark 319.5 88.2; names of\n"
            "  the field's 17 homography points) or 'U V X_MM Y_MM' per line, '#' comments;\n"
            "  --field default spl2016, --scale 5..200 mm per top-view pixel (default 20),\n"
            "  --repeat 1..1000000 runs of the coach path on the frame (for callgrind)\n");
    return 2;
}

int cmd_coach(int argc, char **argv)
{
    coach_cli_opts_t o;
    char err[600];
    int k, rc;
    memset(&o, 0, sizeof o);
    for (k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--points") && k + 1 < argc)
            o.points = argv[++k];
        else if (!strcmp(argv[k], "--background") && k + 1 < argc)
            o.background = argv[++k];
        else if (!strcmp(argv[k], "--field") && k + 1 < argc)
            o.field = argv[++k];
        else if (!strcmp(argv[k], "--out") && k + 1 < argc)
            o.out = argv[++k];
        else if (!strcmp(argv[k], "--scale") && k + 1 < argc) {
            if (arg_int("coach", "--scale", argv[++k], 5, 200, "mm per pixel", &o.mm_per_px))
                return 2;
        } else if (!strcmp(argv[k], "--repeat") && k + 1 < argc) {
            if (arg_long("coach", "--repeat", argv[++k], 1, 1000000, NULL, &o.repeat))
                return 2;
        } else if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h")) {
            usage();
            return 0;
        } else if (argv[k][0] != '-' && !o.image)
            o.image = argv[k];
        else
            return arg_unknown("coach", argv[k],
                               "--points=1 --background=1 --field=1 --out=1 --scale=1 --repeat=1");
    }
    if (!o.image || !o.points) {
        fprintf(stderr, "fieldloc coach: needs IMAGE.ppm and --points FILE (fieldloc coach --help)\n");
        return 2;
    }
    rc = coach_cli_run(&o, stdout, err, (int)sizeof err);
    if (rc != 0)
        fprintf(stderr, "fieldloc coach: %s\n", err);
    return rc;
}
