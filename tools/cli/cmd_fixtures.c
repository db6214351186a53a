/*
 * tools/cli/cmd_fixtures.c - `fieldloc fixtures [--out DIR] [--only NAME]`
 * (`make fixtures`): regenerates the committed rendered fixture set
 * DIR/frames/ (frame, truth and scene per fixture, plus index.txt) from the
 * table below, the walk scenarios DIR/walks/ through the simulator's
 * sim_write_walk_fixtures when it is linked in, and the coach's views
 * DIR/coach/ (tools/world/coach_scene.h coach_write_fixtures).
 *
 * Each table row is turned into scene text (render_scene_read), so a row
 * says exactly what its .scene file will say; `extra` lines come last and
 * override (e.g. a "head" line with a pitch offset).  Angles: robot heading in
 * millidegrees, head pitch / yaw in microradians (NAOqi: pitch > 0 looks
 * down), converted with fl_angle_from_mdeg / fl_angle_from_urad; the pitch
 * offset is the camera's default_pitch_offset (non-zero only for the
 * calibrated "uva2013" camera).
 * world_seed = seed: each fixture gets its own room clutter.
 * Deterministic: the same binary writes identical bytes on every run.
 */
#include "world/render.h"
#include "world/truth.h"
#include "cli/args.h"
#include "cli/registry.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>

/* The simulator's walk fixtures (tools/world/sim.c), when linked. */
int sim_write_walk_fixtures(const char *out_dir) __attribute__((weak));
/* The coach's fixtures (tools/world/coach_scene.c). */
int coach_write_fixtures(const char *dir) __attribute__((weak));

static int ensure_dir(const char *path)
{
    struct stat st;
    if (stat(path, &st) == 0)
        return S_ISDIR(st.st_mode) ? 0 : -1;
    return mkdir(path, 0777);
}

/* Counts of visible (not occluded) features of a truth, for the summary. */
static void count_features(const truth_t *t, int near[TRUTH_KIND_COUNT], int far[TRUTH_KIND_COUNT],
                           int all[TRUTH_KIND_COUNT])
{
    int i;
    for (i = 0; i < t->n; i++) {
        const truth_feature_t *f = &t->f[i];
        if (f->occluded)
            continue;
        all[f->kind]++;
        if (f->range_mm < 1500)
            near[f->kind]++;
        if (f->range_mm > 3000)
            far[f->kind]++;
    }
}

int cmd_fixtures(int argc, char **argv)
{
    const char *out = "fixtures", *only = NULL;
    char dir[512], path[1024];
    FILE *index = NULL;
    int i, n = 0, k, errors = 0, occluded = 0, nofield = 0, formats[4] = {0, 0, 0, 0};
    int near[TRUTH_KIND_COUNT] = {0}, far[TRUTH_KIND_COUNT] = {0}, all[TRUTH_KIND_COUNT] = {0};
    truth_t *t;
    clock_t t0 = clock();

    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fprintf(stderr, "usage: fieldloc fixtures [--out DIR] [--only NAME]\n"
                            "  writes DIR/frames/NAME.{ppm|raw,truth,scene} and DIR/frames/index.txt,\n"
                            "  DIR/walks/ when the walk simulator is built in, and DIR/coach/\n");
            return 0;
        } else
            return arg_unknown("fixtures", argv[i], "--out=1 --only=1");
    }
    snprintf(dir, sizeof dir, "%s/frames", out);
    if (ensure_dir(out) != 0 || ensure_dir(dir) != 0) {
        fprintf(stderr, "fixtures: cannot create %s\n", dir);
        return 1;
    }
    t = (truth_t *)malloc(sizeof *t);
    if (!t)
        return 1;
    if (!only) {
        snprintf(path, sizeof path, "%s/index.txt", dir);
        index = fopen(path, "w");
        if (!index) {
            fprintf(stderr, "fixtures: cannot write %s\n", path);
            free(t);
            return 1;
        }
        fprintf(index, "# rendered fixtures (fieldloc fixtures): NAME FRAME_FILE FORMAT FIELD CAMERA "
                       "DESCRIPTION\n");
    }
    for (i = 0; i < render_fixture_count(); i++) {
        render_scene_t sc;
        render_frame_t fr;
        const char *name, *desc, *ext;
        char frame_file[300];
        if (render_fixture_get(i, &sc, &name, &desc) != 0) {
            fprintf(stderr, "fixtures: bad table row %d\n", i);
            errors++;
            continue;
        }
        if (only && strcmp(only, name))
            continue;
        if (render_frame(&sc, &fr) != 0 || truth_compute(&sc, &fr, t) != 0) {
            fprintf(stderr, "fixtures: cannot render %s\n", name);
            errors++;
            continue;
        }
        ext = sc.format == FL_FMT_RGB888 ? "ppm" : "raw";
        snprintf(frame_file, sizeof frame_file, "%s.%s", name, ext);
        snprintf(path, sizeof path, "%s/%s", dir, frame_file);
        if (render_write_frame(path, &fr) != 0)
            errors++;
        snprintf(path, sizeof path, "%s/%s.truth", dir, name);
        if (truth_save(path, t) != 0)
            errors++;
        snprintf(path, sizeof path, "%s/%s.scene", dir, name);
        if (render_scene_save(path, &sc) != 0)
            errors++;
        if (index)
            fprintf(index, "%s %s %s %s %s %s\n", name, frame_file, render_format_name(sc.format),
                    sc.field->name, sc.camera->name, desc);
        count_features(t, near, far, all);
        for (k = 0; k < t->n; k++)
            occluded += t->f[k].occluded;
        for (k = 0; k < t->width && t->border_v[k] == t->height; k++)
            ;
        nofield += k == t->width;
        formats[sc.format == FL_FMT_RGB888 ? 1 : sc.format == FL_FMT_YUYV422 ? 2 : 3]++;
        render_frame_free(&fr);
        n++;
    }
    if (index && fclose(index) != 0)
        errors++;
    free(t);
    printf("fixtures: %d frames in %s (rgb %d, yuyv %d, planar %d), %.1f s\n", n, dir, formats[1],
           formats[2], formats[3], (double)(clock() - t0) / CLOCKS_PER_SEC);
    printf("visible features (near < 1.5 m / far > 3 m / all):");
    for (k = 0; k < TRUTH_KIND_COUNT; k++)
        printf(" %s %d/%d/%d", truth_kind_name((truth_kind_t)k), near[k], far[k], all[k]);
    printf("\noccluded features listed: %d; frames without any field: %d\n", occluded, nofield);
    if (!only) {
        if (sim_write_walk_fixtures) {
            snprintf(path, sizeof path, "%s/walks", out);
            if (ensure_dir(path) != 0 || sim_write_walk_fixtures(path) < 0) {
                fprintf(stderr, "fixtures: walk scenarios failed in %s\n", path);
                errors++;
            } else {
                printf("fixtures: walk scenarios written to %s\n", path);
            }
        } else {
            printf("fixtures: walk simulator not built in; %s/walks left alone\n", out);
        }
        if (coach_write_fixtures) {
            snprintf(path, sizeof path, "%s/coach", out);
            if (ensure_dir(path) != 0 || coach_write_fixtures(path) != 0) {
                fprintf(stderr, "fixtures: coach fixtures failed in %s\n", path);
                errors++;
            } else {
                printf("fixtures: coach views written to %s\n", path);
            }
        }
    }
    return errors ? 1 : 0;
}
