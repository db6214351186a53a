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
 * The scoring is in tools/eval/eval_detect.c.
 */
#include "eval/detect.h"
#include "io/realdata.h"
#include "cli/registry.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cmd_eval_detect(int argc, char **argv)
{
    const char *fix = "fixtures", *real = NULL, *only = NULL;
    double max_range = 6000;
    int i, verbose = 0, n, skip_real = 0, skip_fix = 0;
    det_ctx_t ctx;
    evd_stats_t s;
    fl_vision_params_t vp;
    fl_vision_params_default(&vp);
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--fixtures") && i + 1 < argc)
            fix = argv[++i];
        else if (!strcmp(argv[i], "--realdata") && i + 1 < argc)
            real = argv[++i];
        else if (!strcmp(argv[i], "--max-range") && i + 1 < argc)
            max_range = atof(argv[++i]);
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
        /* tuning knobs (defaults: fl_vision_params_default) */
        else if (!strcmp(argv[i], "--run") && i + 1 < argc)
            vp.scan.border_run_px = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--grid") && i + 1 < argc)
            vp.scan.col_step = vp.scan.row_step = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--step") && i + 1 < argc)
            vp.lines.step_px = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--err") && i + 2 < argc) {
            vp.lines.err_base_q2 = atoi(argv[++i]);
            vp.lines.err_point_q2 = atoi(argv[++i]);
        } else if (!strcmp(argv[i], "--white") && i + 1 < argc)
            vp.lines.white_pct = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--white-s") && i + 1 < argc)
            det_white_s_hi = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--tol") && i + 1 < argc)
            vp.crossings.ground_tol_mdeg = atoi(argv[++i]) * 1000;
        else if (!strcmp(argv[i], "--minconf") && i + 1 < argc)
            vp.min_confidence = vp.crossings.min_confidence = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: fieldloc eval-detect [--fixtures DIR] [--realdata DIR] "
                            "[--max-range MM] [--only PREFIX] [--verbose]\n");
            return 2;
        }
    }
    if (det_ctx_init_params(&ctx, &vp) != 0) {
        fprintf(stderr, "eval-detect: bad parameters\n");
        return 1;
    }
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
    det_ctx_free(&ctx);
    return 0;
}
