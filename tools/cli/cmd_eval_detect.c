/*
 * tools/cli/cmd_eval_detect.c - `fieldloc eval-detect [--fixtures DIR]
 * [--realdata DIR] [--max-range MM] [--verbose]`: scores the vision path
 *   (1) on the rendered fixtures (fixtures/frames/index.txt + *.truth):
 *       camera pose from the truth file; crossings (L T X; penalty and
 *       centre marks are X) and yellow post feet;
 *   (2) on the UvA 2013 frames of ../shared/realdata against
 *       uva2013_annotations.csv: camera "uva2013" with each record's head
 *       angles (rd_uva_camera_pose), field uva2013.
 * Matching: greedy by distance, nearest pairs first, one-to-one; a
 * crossing matches within 8 px whatever its type (type accuracy = matched
 * pairs of the same type / matched pairs), a post foot (G) within 6 px, a
 * post top (U) within 6 px (reported, no target).  Per type, a detection
 * "hits" when matched to a truth of its type: precision = hits /
 * detections of the type, recall = hits / truth of the type.
 * Rendered frames: only truth within --max-range (default 6000 mm) and not
 * occluded is required; a detection matched to other truth (farther or
 * occluded) is neither a hit nor a false positive; an unmatched detection
 * whose own range is beyond max-range is ignored.  Range errors of matched
 * crossings and feet by distance bin (|r - r_true| / r_true).
 *   (3) on the other real frames of ../shared/realdata (physar, HTWK,
 *       NaoTH, dbloisi, scarrix) against the project's own labels
 *       tools/eval/realdata_modern.csv (rd_modern_csv(): found from the
 *       working directory or the executable; --modern FILE overrides):
 *       field spl2020 (white goals), each row's camera and head angles
 *       (0 when not labelled); crossings and post feet as in (2), plus the
 *       field border: the fraction of labelled columns (B) whose scanner
 *       border lies within 3 px of the labelled topmost carpet row, the
 *       mean and the worst.
 * The scoring is in tools/eval/eval_detect.c.  --pictures DIR writes one
 * picture per frame (stages, truth rings, legend strip).
 * --colors default|auto|FILE (eval/colors_opt.h): the colour classes; auto
 * estimates the carpet of each frame.  Without it: auto on the white-goal
 * fixtures (spl2020), default on the others and the UvA 2013 frames.
 * Numbers are checked (tools/cli/args.h; the ranges of the vision
 * parameters, lines.h / crossings.h / scan.h); errors exit with status 2.
 */
#include "cli/args.h"
#include "eval/colors_opt.h"
#include "eval/detect.h"
#include "io/realdata.h"
#include "cli/registry.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int evd_usage(int rc)
{
    fprintf(stderr,
            "usage: fieldloc eval-detect [--fixtures DIR] [--realdata DIR] [--max-range MM]\n"
            "         [--only PREFIX] [--verbose] [--pictures DIR] [--no-real] [--no-fixtures]\n"
            "         [--modern FILE] [--no-modern] [--colors default|auto|FILE]\n"
            "  tuning: --run 1..255 px  --grid 1..16 px  --step 1..64 px  --err BASE POINT\n"
            "          (0..65535 each)  --white 0..100 %%  --white-s 0..254  --tol 1..45 deg\n"
            "          --minconf 0..255;  --max-range 100..20000 mm\n");
    return rc;
}

int cmd_eval_detect(int argc, char **argv)
{
    const char *fix = "fixtures", *real = NULL, *only = NULL, *modern = NULL;
    double max_range = 6000;
    int i, verbose = 0, n, skip_real = 0, skip_fix = 0, skip_modern = 0;
    det_ctx_t ctx;
    evd_stats_t s;
    evd_border_t bs;
    fl_vision_params_t vp;
    static const char C[] = "eval-detect";
    colors_opt_t colors;
    memset(&colors, 0, sizeof colors);   /* unset: the policy per field */
    fl_vision_params_default(&vp);
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--fixtures") && i + 1 < argc)
            fix = argv[++i];
        else if (!strcmp(argv[i], "--realdata") && i + 1 < argc)
            real = argv[++i];
        else if (!strcmp(argv[i], "--max-range") && i + 1 < argc) {
            if (arg_double("eval-detect", "--max-range", argv[++i], 100, FL_CAMERA_MAX_RANGE_MM,
                           "mm", &max_range) != 0)
                return 2;
        }
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--verbose"))
            verbose = 1;
        else if (!strcmp(argv[i], "--pictures") && i + 1 < argc)
            evd_set_pictures(argv[++i]);
        else if (!strcmp(argv[i], "--no-real"))
            skip_real = 1;
        else if (!strcmp(argv[i], "--no-fixtures"))
            skip_fix = 1;
        else if (!strcmp(argv[i], "--modern") && i + 1 < argc)
            modern = argv[++i];
        else if (!strcmp(argv[i], "--no-modern"))
            skip_modern = 1;
        else if (!strcmp(argv[i], "--colors") && i + 1 < argc) {
            if (colors_opt_parse(C, argv[++i], &colors) != 0)
                return 2;
        }
        /* tuning knobs (defaults: fl_vision_params_default) */
        else if (!strcmp(argv[i], "--run") && i + 1 < argc) {
            if (arg_int32(C, "--run", argv[++i], 1, 255, "px", &vp.scan.border_run_px))
                return 2;
        } else if (!strcmp(argv[i], "--grid") && i + 1 < argc) {
            if (arg_int32(C, "--grid", argv[++i], 1, 16, "px", &vp.scan.col_step))
                return 2;
            vp.scan.row_step = vp.scan.col_step;
        } else if (!strcmp(argv[i], "--step") && i + 1 < argc) {
            if (arg_int32(C, "--step", argv[++i], 1, 64, "px", &vp.lines.step_px))
                return 2;
        } else if (!strcmp(argv[i], "--err") && i + 2 < argc) {
            if (arg_int32(C, "--err BASE", argv[++i], 0, 65535, NULL, &vp.lines.err_base_q2) ||
                arg_int32(C, "--err POINT", argv[++i], 0, 65535, NULL, &vp.lines.err_point_q2))
                return 2;
        } else if (!strcmp(argv[i], "--white") && i + 1 < argc) {
            if (arg_int32(C, "--white", argv[++i], 0, 100, "%", &vp.lines.white_pct))
                return 2;
        } else if (!strcmp(argv[i], "--white-s") && i + 1 < argc) {
            /* green S >= this + 1 must stay a byte */
            if (arg_int(C, "--white-s", argv[++i], 0, 254, NULL, &det_white_s_hi))
                return 2;
        } else if (!strcmp(argv[i], "--tol") && i + 1 < argc) {
            if (arg_int32(C, "--tol", argv[++i], 1, 45, "deg", &vp.crossings.ground_tol_mdeg))
                return 2;
            vp.crossings.ground_tol_mdeg *= 1000;
        } else if (!strcmp(argv[i], "--minconf") && i + 1 < argc) {
            if (arg_int32(C, "--minconf", argv[++i], 0, 255, NULL, &vp.min_confidence))
                return 2;
            vp.crossings.min_confidence = vp.min_confidence;
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return evd_usage(0);
        else
            return arg_unknown(C, argv[i],
                               "--fixtures=1 --realdata=1 --max-range=1 --only=1 --pictures=1 "
                               "--run=1 --grid=1 --step=1 --err=2 --white=1 --white-s=1 --tol=1 "
                               "--minconf=1 --modern=1 --colors=1");
    }
    if (det_ctx_init_params(&ctx, &vp) != 0) {
        fprintf(stderr, "eval-detect: bad parameters\n");
        return 1;
    }
    ctx.colors_each = &colors;
    evd_stats_clear(&s);
    n = skip_fix ? -2 : evd_fixtures(&ctx, fix, max_range, verbose, &s, only);
    if (n == -2)
        ;
    else if (n < 0)
        printf("rendered fixtures: %s/frames/index.txt not found\n", fix);
    else {
        char title[128];
        snprintf(title, sizeof title, "rendered fixtures (truth within %.0f mm)", max_range);
        evd_print(title, &s, 1);
    }
    if (!skip_fix) {
        /* seed 004's corner stage on the aibo2004 frames */
        fl_corners_t *cn = malloc(sizeof *cn);
        evc_stats_t cs;
        memset(&cs, 0, sizeof cs);
        if (cn == NULL || evd_corners(&ctx, fix, EVD_CORNERS_RANDOM, cn, &cs) < 0)
            printf("aibo2004 corner features: not scored (out of memory or no field)\n");
        else
            evd_corners_print(&cs);
        free(cn);
    }
    if (!real)
        real = rd_dir();
    evd_stats_clear(&s);
    if (skip_real)
        ;
    else if (!real)
        printf("UvA 2013 frames: %s\n", rd_skip_message());
    else if (evd_uva(&ctx, real, verbose, &s) < 0)
        printf("UvA 2013 frames: cannot read %s/%s\n", real, RD_UVA_CSV);
    else
        evd_print("UvA 2013 real frames (hand labels)", &s, 0);
    evd_stats_clear(&s);
    evd_border_clear(&bs);
    if (!modern)
        modern = rd_modern_csv();
    if (skip_real || skip_modern)
        ;
    else if (!real)
        printf("modern real frames: %s\n", rd_skip_message());
    else if (!modern)
        printf("modern real frames: tools/eval/%s not found\n", RD_MODERN_CSV);
    else if (evd_modern(&ctx, real, modern, verbose, &s, &bs) < 0)
        printf("modern real frames: cannot read %s\n", modern);
    else {
        evd_print("modern real frames (hand labels)", &s, 0);
        evd_border_print(&bs);
    }
    det_ctx_free(&ctx);
    return 0;
}
