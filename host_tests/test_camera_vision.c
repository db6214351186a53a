/*
 * host_tests/test_camera_vision.c - the camera's roll and the 1280x960 NAO
 * v6 models through the renderer and the vision path.
 *
 *  - render_agreement_roll: random scenes with torso pitch / roll and a roll
 *    offset; the renderer's truth (its own double camera) against the
 *    firmware camera, with the tolerance of render.camera_agreement_*.
 *  - roll_rendered_ranges: half the spl2013 / spl2020 fixture scenes rendered
 *    level and with the torso rolled by +-5 deg; crossings detected in
 *    the rolled frames with the matching pose must give ranges as accurate
 *    as in the level frames, and detected with a level pose (roll ignored)
 *    measurably worse.
 *  - nao6_1280: the spl2020 fixture scenes rendered with the nao6 1280x960
 *    models (the vision picks a 4 px grid: 320 x 240 cells, within
 *    FL_SCAN_MAX_COLS / ROWS): crossings found with accurate ranges.
 * (The physar NAO v6 frames of ../shared/realdata are 640x480, so no real
 * 1280x960 frame is tested.)
 *
 * Crossings are matched to the truth by pixel (within 8 px at 320 wide,
 * scaled with the width), kinds L/T/X (marks count as X), truth range <=
 * 3 m, not occluded; the range error is |detected - truth| / truth.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "eval/detect.h"
#include "world/render.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int n;            /* matched crossings */
    int truth;        /* truth crossings in range */
    double sum, max;  /* relative range error */
} cv_stats_t;

static char cv_kind(truth_kind_t k)
{
    switch (k) {
    case TRUTH_L: return 'L';
    case TRUTH_T: return 'T';
    case TRUTH_X: case TRUTH_PENALTY_MARK: case TRUTH_CENTRE_MARK: return 'X';
    default: return 0;
    }
}

/* Detect in fr with cam and score the crossings against the truth t. */
static void cv_score(det_ctx_t *dc, const render_frame_t *fr, const fl_camera_t *cam,
                     const fl_field_t *field, const truth_t *t, cv_stats_t *st)
{
    det_feature_t feat[DET_MAX_FEATURES];
    double tol = 8.0 * fr->width / 320.0;
    int nd = det_run(dc, &fr->view, cam, field, NULL, feat, DET_MAX_FEATURES), i, k;
    for (k = 0; k < t->n; k++)
        if (cv_kind(t->f[k].kind) && !t->f[k].occluded && t->f[k].range_mm <= 3000)
            st->truth++;
    for (i = 0; i < nd; i++) {
        const truth_feature_t *best = NULL;
        double bd = tol, e;
        if (feat[i].kind != 'L' && feat[i].kind != 'T' && feat[i].kind != 'X')
            continue;
        for (k = 0; k < t->n; k++) {
            const truth_feature_t *f = &t->f[k];
            double d = hypot(f->u - feat[i].u, f->v - feat[i].v);
            if (cv_kind(f->kind) && !f->occluded && d <= bd) {
                bd = d;
                best = f;
            }
        }
        if (!best || best->range_mm > 3000)
            continue;
        e = fabs(feat[i].range_mm - best->range_mm) / best->range_mm;
        st->n++;
        st->sum += e;
        if (e > st->max)
            st->max = e;
    }
}

static double cv_mean(const cv_stats_t *s) { return s->n > 0 ? s->sum / s->n : 0.0; }

/* Render sc, compute its truth, camera from its head pose. */
static int cv_render(const render_scene_t *sc, render_frame_t *fr, truth_t *t)
{
    if (render_frame(sc, fr) != 0)
        return -1;
    if (truth_compute(sc, fr, t) != 0) {
        render_frame_free(fr);
        return -1;
    }
    return 0;
}

/* A detector context in *dc and a truth buffer for the rendered-scene
 * tests (free both at the end); NULL, and a failed check, when either
 * cannot be had. */
static truth_t *cv_start(det_ctx_t *dc)
{
    truth_t *t = (truth_t *)malloc(sizeof *t);
    CHECK(t != NULL);
    if (!t || det_ctx_init(dc) != 0) {
        free(t);
        CHECK(0);
        return NULL;
    }
    return t;
}

static void test_render_agreement_roll(void)
{
    static const char *cams[] = {"nao4-top-320", "nao4-bottom-320", "nao6-top-640", "nao6-bottom-1280"};
    static const char *fields[] = {"spl2013", "spl2020"};
    t_rng_t r;
    int k, i, n = 0, scenes = t_quick ? 4 : 16;
    double max_err = 0;
    truth_t *t = (truth_t *)malloc(sizeof *t);
    CHECK(t != NULL);
    if (!t)
        return;
    t_rng_seed(&r, 7);
    for (k = 0; k < scenes; k++) {
        render_scene_t sc;
        const fl_field_t *f = fl_field_find(fields[k % 2]);
        const fl_camera_model_t *m = fl_camera_model_find(cams[k % 4]);
        fl_camera_t cam;
        render_scene_default(&sc, f, m);
        sc.robot_x_mm = t_rng_range(&r, -f->length_mm / 2, f->length_mm / 2);
        sc.robot_y_mm = t_rng_range(&r, -f->width_mm / 2, f->width_mm / 2);
        sc.robot_heading = (fl_angle_t)t_rng_range(&r, -32768, 32767);
        sc.head.head_pitch = (fl_angle_t)t_rng_range(&r, -1000, 3500);
        sc.head.head_yaw = (fl_angle_t)t_rng_range(&r, -12000, 12000);
        sc.head.torso_pitch = (fl_angle_t)t_rng_range(&r, -1820, 1820);
        sc.head.torso_roll = (fl_angle_t)t_rng_range(&r, -1820, 1820);
        sc.head.roll_offset = (fl_angle_t)t_rng_range(&r, -546, 546);
        CHECK_EQ(truth_compute(&sc, NULL, t), 0);
        CHECK_EQ(fl_camera_init(&cam, m, &sc.head), FL_OK);
        /* the renderer's camera centre is the firmware's */
        CHECK_LE(fabs(t->cam_x_mm * 16 - cam.pos_q4[0]), 2.0);
        CHECK_LE(fabs(t->cam_y_mm * 16 - cam.pos_q4[1]), 2.0);
        CHECK_LE(fabs(t->cam_z_mm * 16 - cam.pos_q4[2]), 2.0);
        for (i = 0; i < t->n; i++) {
            const truth_feature_t *ft = &t->f[i];
            fl_point_t g;
            double e;
            if (ft->occluded || ft->z_mm != 0.0 || ft->kind == TRUTH_BALL)
                continue;
            if (!fl_camera_pixel_to_ground(&cam, (int32_t)lround(ft->u * 16), (int32_t)lround(ft->v * 16), &g)) {
                CHECK(ft->range_mm > FL_CAMERA_MAX_RANGE_MM - 500);
                continue;
            }
            e = hypot(g.x_mm - ft->robot_x_mm, g.y_mm - ft->robot_y_mm);
            n++;
            if (e > max_err)
                max_err = e;
            if (e > 3.0 + 0.01 * ft->range_mm)
                t_fail_msg(__FILE__, __LINE__, "%s scene %d: ground error %.1f mm at %.0f mm", m->name, k,
                           e, ft->range_mm);
        }
    }
    CHECK(n >= (t_quick ? 2 : 15));
    t_info("rolled scenes: %d ground features, renderer vs firmware max %.2f mm", n, max_err);
    free(t);
}

static void test_roll_rendered_ranges(void)
{
    det_ctx_t dc;
    cv_stats_t lvl, rolled, ignored;
    int i, scenes = 0;
    render_frame_t fr;
    truth_t *t = cv_start(&dc);
    if (!t)
        return;
    memset(&lvl, 0, sizeof lvl);
    memset(&rolled, 0, sizeof rolled);
    memset(&ignored, 0, sizeof ignored);
    for (i = 0; i < render_fixture_count(); i++) {
        render_scene_t sc;
        const char *name;
        const fl_field_t *field;
        fl_camera_t cam;
        fl_camera_pose_t level;
        CHECK_EQ(render_fixture_get(i, &sc, &name, NULL), 0);
        /* every other spl2013 / spl2020 fixture, the first 22 (all crossing
         * kinds; each costs two renders) */
        if (strncmp(name, "spl20", 5) != 0 || i % 2 || scenes >= 22 || (t_quick && scenes >= 4))
            continue;
        field = sc.field;
        /* level */
        if (cv_render(&sc, &fr, t) != 0 || fl_camera_init(&cam, sc.camera, &sc.head) != FL_OK) {
            CHECK(0);
            continue;
        }
        cv_score(&dc, &fr, &cam, field, t, &lvl);
        render_frame_free(&fr);
        /* torso rolled by 5 deg, alternately right and left */
        level = sc.head;
        sc.head.torso_roll = fl_angle_from_mdeg(scenes % 2 ? -5000 : 5000);
        if (cv_render(&sc, &fr, t) != 0 || fl_camera_init(&cam, sc.camera, &sc.head) != FL_OK) {
            CHECK(0);
            continue;
        }
        cv_score(&dc, &fr, &cam, field, t, &rolled);
        CHECK_EQ(fl_camera_init(&cam, sc.camera, &level), FL_OK);
        cv_score(&dc, &fr, &cam, field, t, &ignored);
        render_frame_free(&fr);
        scenes++;
    }
    det_ctx_free(&dc);
    free(t);
    t_info("%d scenes, crossings <= 3 m: level %d of %d matched, mean range error %.2f %% (max %.2f %%)",
           scenes, lvl.n, lvl.truth, 100 * cv_mean(&lvl), 100 * lvl.max);
    t_info("rolled 5 deg, matching pose: %d of %d, mean %.2f %% (max %.2f %%)", rolled.n, rolled.truth,
           100 * cv_mean(&rolled), 100 * rolled.max);
    t_info("rolled 5 deg, level pose (roll ignored): %d of %d, mean %.2f %% (max %.2f %%)", ignored.n,
           ignored.truth, 100 * cv_mean(&ignored), 100 * ignored.max);
    CHECK(lvl.n >= (t_quick ? 3 : 8) && rolled.n >= (t_quick ? 3 : 8) && ignored.n >= (t_quick ? 3 : 8));
    /* as many found, as accurate as level (within 0.5 % of range) */
    CHECK_LE(lvl.n * 3, rolled.n * 4);
    CHECK_LE(cv_mean(&rolled), cv_mean(&lvl) + 0.005);
    CHECK_LE(rolled.max, 0.05);
    /* ignoring the roll is measurably worse */
    CHECK_LE(2.0 * cv_mean(&rolled) + 0.01, cv_mean(&ignored));
}

static void test_nao6_1280(void)
{
    det_ctx_t dc;
    cv_stats_t lo, hi;
    int i, scenes = 0;
    render_frame_t fr;
    truth_t *t = cv_start(&dc);
    if (!t)
        return;
    memset(&lo, 0, sizeof lo);
    memset(&hi, 0, sizeof hi);
    for (i = 0; i < render_fixture_count(); i++) {
        render_scene_t sc;
        const char *name;
        fl_camera_t cam;
        char big[32];
        const fl_camera_model_t *m1280;
        CHECK_EQ(render_fixture_get(i, &sc, &name, NULL), 0);
        /* 2 scenes in quick mode, 3 otherwise: a 1280x960 render with its
         * truth costs about 0.6 s */
        if (strncmp(sc.camera->name, "nao6-", 5) != 0 || scenes >= (t_quick ? 2 : 3))
            continue;
        /* the same view at 320 and at 1280 wide */
        if (cv_render(&sc, &fr, t) != 0 || fl_camera_init(&cam, sc.camera, &sc.head) != FL_OK) {
            CHECK(0);
            continue;
        }
        cv_score(&dc, &fr, &cam, sc.field, t, &lo);
        render_frame_free(&fr);
        snprintf(big, sizeof big, "%.*s-1280", (int)(strrchr(sc.camera->name, '-') - sc.camera->name),
                 sc.camera->name);
        m1280 = fl_camera_model_find(big);
        CHECK(m1280 != NULL);
        if (!m1280)
            continue;
        sc.camera = m1280;
        if (cv_render(&sc, &fr, t) != 0 || fl_camera_init(&cam, sc.camera, &sc.head) != FL_OK) {
            CHECK(0);
            continue;
        }
        CHECK_EQ(fr.width, 1280);
        CHECK_EQ(fr.height, 960);
        cv_score(&dc, &fr, &cam, sc.field, t, &hi);
        /* the grid the vision chose fits the capacities */
        CHECK(1280 / dc.vis->scan_active.col_step <= FL_SCAN_MAX_COLS);
        CHECK(960 / dc.vis->scan_active.row_step <= FL_SCAN_MAX_ROWS);
        render_frame_free(&fr);
        scenes++;
    }
    det_ctx_free(&dc);
    free(t);
    t_info("%d nao6 scenes, crossings <= 3 m: 320x240 %d of %d matched, mean range error %.2f %%; "
           "1280x960 %d of %d, mean %.2f %% (max %.2f %%)", scenes, lo.n, lo.truth, 100 * cv_mean(&lo),
           hi.n, hi.truth, 100 * cv_mean(&hi), 100 * hi.max);
    CHECK(scenes >= 2);
    CHECK(hi.n >= 2);
    CHECK_LE(lo.n, 2 * hi.n);          /* found about as often as at 320 */
    CHECK_LE(hi.max, 0.05);
}

void suite_camera_vision(void)
{
    t_run("camera_vision.render_agreement_roll", test_render_agreement_roll);
    t_run("camera_vision.roll_rendered_ranges", test_roll_rendered_ranges);
    t_run("camera_vision.nao6_1280", test_nao6_1280);
}
