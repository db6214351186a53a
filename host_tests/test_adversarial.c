/*
 * host_tests/test_adversarial.c - hostile frames through the whole vision
 * path: all green, all white, all yellow, black, saturated, random
 * noise, checkerboards of line-width and single-pixel squares, 1x1, width 1,
 * odd widths, stride larger than the width, in RGB888, YUYV422 and planar.
 * Every frame must come back with a valid status, at most FL_OBS_MAX
 * observations with sane values, every stage's count within its capacity,
 * and the state still usable: a normal rendered fixture processed after the
 * hostile frames gives exactly the observations it gives on a fresh state.
 * The work per frame is bounded by the caps (config.h); the time of the
 * worst frame is measured by `make bench` (section vision), not here.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/render.h"
#include "world/adversarial.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    fl_color_table_t colors;
    fl_vision_t vis;
} adv_state_t;

static int adv_init(adv_state_t *s)
{
    fl_color_params_t cp;
    fl_vision_params_t vp;
    fl_color_params_default(&cp);
    fl_vision_params_default(&vp);
    return fl_color_init(&s->colors, &cp) == FL_OK && fl_vision_init(&s->vis, &vp) == FL_OK;
}

/* One frame; checks the outputs; returns a hash of them. */
static uint32_t adv_run(adv_state_t *s, const fl_image_t *img, const fl_camera_t *cam,
                        const fl_field_t *field, uint32_t h, int *n_obs)
{
    fl_obs_list_t obs;
    int32_t n = fl_vision_frame(&s->vis, &s->colors, img, cam, field, &obs), i;
    CHECK(n >= 0 && n <= FL_OBS_MAX);
    CHECK_EQ(obs.n, n);
    CHECK(s->vis.lines.n_points >= 0 && s->vis.lines.n_points <= FL_LINES_MAX_POINTS);
    CHECK(s->vis.lines.n_segments >= 0 && s->vis.lines.n_segments <= FL_LINES_MAX_SEGMENTS);
    CHECK(s->vis.crossings.n >= 0 && s->vis.crossings.n <= FL_CROSSINGS_MAX);
    CHECK(s->vis.posts.n >= 0 && s->vis.posts.n <= FL_GOAL_MAX_POSTS);
    for (i = 0; i < n; i++) {
        const fl_obs_t *o = &obs.obs[i];
        CHECK((int)o->kind >= 0 && (int)o->kind < FL_LM_KIND_COUNT);
        CHECK(o->range_mm >= 0 && o->range_mm <= FL_CAMERA_MAX_RANGE_MM);
        h = t_hash_i32(h, (int32_t)o->kind);
        h = t_hash_i32(h, o->range_mm);
        h = t_hash_i32(h, o->bearing);
    }
    h = t_hash_i32(h, n);
    h = t_hash_i32(h, (int32_t)s->vis.status);
    if (n_obs)
        *n_obs = n;
    return h;
}

static adv_state_t *g_state;   /* big: allocated once */

/* The golden outputs of the hostile frames: fixtures/golden/adversarial.txt,
 * one line per frame, "NAME STATUS N_OBS POINTS SEGMENTS CROSSINGS POSTS
 * 0xHASH" (integers only, so identical on every architecture).  Rewritten
 * by FIELDLOC_WRITE_GOLDEN=1 build/run_tests -k adversarial (full mode). */
#define ADV_GOLDEN "fixtures/golden/adversarial.txt"

static void test_hostile_frames(void)
{
    static const int sizes[][2] = {{320, 240}, {640, 480}, {1, 1}, {1, 240}, {320, 1},
                                   {2, 2}, {33, 17}, {321, 239}, {208, 160}};
    static const fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422, FL_FMT_YCBCR_PLANAR};
    static const char *fmt_names[3] = {"rgb", "yuyv", "planar"};
    const fl_field_t *field = fl_field_find("spl2013");
    t_golden_lines_t gold;
    fl_camera_t cam;
    fl_camera_pose_t pose;
    fl_camera_model_t model;
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    uint32_t h = t_hash_init();
    int k, si, fi, rejected = 0;
    int nsizes = t_quick ? 4 : (int)(sizeof sizes / sizeof sizes[0]);
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    pose.head_pitch = 0;
    pose.head_yaw = 0;
    CHECK_EQ(fl_camera_init(&cam, m, &pose), FL_OK);
    t_golden_lines_begin(&gold, ADV_GOLDEN,
                         "# golden outputs of the hostile frames of tools/world/adversarial.c through "
                         "fl_vision_frame\n# (host_tests/test_adversarial.c): NAME STATUS N_OBS "
                         "POINTS SEGMENTS CROSSINGS POSTS 0xHASH\n# NAME = KIND_WxH_FORMAT_padPAD\n",
                         "adversarial");
    for (k = 0; k < ADV_COUNT; k++)
        for (si = 0; si < nsizes; si++)
            for (fi = 0; fi < 3; fi++) {
                fl_image_t img;
                fl_status_t st;
                int pad = (k + si + fi) % 3 == 0 ? 0 : 7 * (fi + 1);  /* stride > width */
                uint8_t *buf;
                uint32_t fh;
                int n_obs = 0;
                char name[64], got[T_GOLDEN_LINE_MAX];
                if (t_quick && sizes[si][0] * sizes[si][1] > 320 * 240)
                    continue;
                buf = adv_frame((adv_kind_t)k, sizes[si][0], sizes[si][1], fmts[fi], pad, &img, &st);
                CHECK(buf != NULL);
                if (!buf)
                    continue;
                if (fmts[fi] == FL_FMT_YUYV422 && (sizes[si][0] & 1)) {
                    CHECK_EQ(st, FL_ERR_FORMAT);   /* odd YUYV width is rejected */
                    rejected++;
                } else {
                    CHECK_EQ(st, FL_OK);
                }
                /* a camera model of the frame's size (a model of another
                 * size is refused: vision.mismatched_frame) */
                adv_camera_model(m, sizes[si][0], sizes[si][1], &model);
                CHECK_EQ(fl_camera_init(&cam, &model, &pose), FL_OK);
                fh = adv_run(g_state, &img, &cam, field, t_hash_init(), &n_obs);
                h = t_hash_i32(h, (int32_t)fh);
                if (st != FL_OK)
                    CHECK_EQ(g_state->vis.lines.n_points + g_state->vis.crossings.n, 0);
                snprintf(name, sizeof name, "%s_%dx%d_%s_pad%d", adv_name((adv_kind_t)k),
                         sizes[si][0], sizes[si][1], fmt_names[fi], pad);
                snprintf(got, sizeof got, "%s %d %d %d %d %d %d 0x%08lx", name,
                         (int)g_state->vis.status, n_obs,
                         (int)g_state->vis.lines.n_points, (int)g_state->vis.lines.n_segments,
                         (int)g_state->vis.crossings.n, (int)g_state->vis.posts.n,
                         (unsigned long)fh);
                t_golden_lines_check(&gold, name, got);
                free(buf);
            }
    if (!gold.out)
        t_info("%d hostile frames (%d rejected views), outputs within capacity; %d of %d "
               "identical to %s", gold.n, rejected, gold.same, gold.n, ADV_GOLDEN);
    t_golden_lines_end(&gold);   /* (fails when a frame has no golden line) */
    t_digest("adversarial.frames", h);
}

/* After all that, a real fixture gives the same result as on a fresh state. */
static void test_state_survives(void)
{
    render_frame_t fr;
    render_scene_t sc;
    fl_camera_t cam;
    adv_state_t *fresh = malloc(sizeof *fresh);
    char err[256];
    uint32_t a, b;
    FILE *f = fopen("fixtures/frames/spl2013_t_near.scene", "r");
    CHECK(fresh != NULL && f != NULL);
    if (!fresh || !f) {
        free(fresh);
        if (f) fclose(f);
        return;
    }
    CHECK_EQ(render_scene_read(f, &sc, err, sizeof err), 0);
    fclose(f);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK(adv_init(fresh));
    CHECK_EQ(fl_camera_init(&cam, sc.camera, &sc.head), FL_OK);
    a = adv_run(fresh, &fr.view, &cam, sc.field, t_hash_init(), NULL);
    b = adv_run(g_state, &fr.view, &cam, sc.field, t_hash_init(), NULL);
    CHECK_EQ(a, b);
    CHECK(fresh->vis.crossings.n > 0);   /* the fixture does show a crossing */
    render_frame_free(&fr);
    free(fresh);
}

/* Localizer abuse, end to end through the public API: a robot
 * tracked at a known pose gets contradicting observations (a centre mark at
 * 200 mm when it stands 2.5 m from it, every frame) and absurd odometry.
 * The grid stays valid, the estimate stays on the carpet, reliability drops
 * below its tracked level, and the events are counted. */
static void test_localizer_contradiction(void)
{
    const fl_field_t *f = fl_field_find("spl2013");
    fl_fuzzy_t *g = malloc(sizeof *g);
    fl_fuzzy_estimate_t e0, e;
    fl_obs_t o;
    uint16_t lowest;
    int k;
    CHECK(g != NULL);
    if (!g)
        return;
    CHECK_EQ(fl_fuzzy_init(g, f, NULL), FL_OK);
    fl_fuzzy_reset_pose(g, -2500, 0, 0, 150, fl_angle_from_mdeg(5000));
    CHECK(fl_fuzzy_estimate(g, &e0));
    CHECK_LE(32768, e0.reliability_q16);   /* a known pose is reliable */
    memset(&o, 0, sizeof o);
    o.kind = FL_LM_CENTRE_MARK;
    o.range_mm = 200;
    o.bearing = 0;
    o.confidence = 255;
    lowest = e0.reliability_q16;
    for (k = 0; k < 40; k++) {
        fl_obs_list_t list;
        fl_fuzzy_predict(g, 0, 0, 0);
        list.n = 1;
        list.obs[0] = o;
        fl_fuzzy_update(g, &list);
        CHECK(fl_fuzzy_check(g));
        CHECK(fl_fuzzy_estimate(g, &e));
        CHECK(e.x_mm >= -g->half_x_mm && e.x_mm <= g->half_x_mm);
        CHECK(e.y_mm >= -g->half_y_mm && e.y_mm <= g->half_y_mm);
        if (e.reliability_q16 < lowest)
            lowest = e.reliability_q16;
    }
    t_info("contradicting observations: reliability %.2f tracked, lowest %.2f; kidnaps %u, "
           "gated %u, empty resets %u",
           e0.reliability_q16 / 65536.0, lowest / 65536.0, (unsigned)g->stats.kidnaps,
           (unsigned)g->stats.obs_gated, (unsigned)g->stats.empty_resets);
    CHECK(lowest < e0.reliability_q16 / 2);   /* reliability drops */
    CHECK(g->stats.kidnaps + g->stats.obs_gated + g->stats.empty_resets > 0);   /* counted */
    /* absurd odometry: ignored and counted, the state valid */
    fl_fuzzy_reset_pose(g, 1000, 500, 0, 150, fl_angle_from_mdeg(5000));
    fl_fuzzy_predict(g, 10000, 0, 0);
    fl_fuzzy_predict(g, INT32_MIN, INT32_MAX, (fl_angle_t)-32768);
    CHECK_EQ(g->stats.odo_rejected, 2);
    CHECK(fl_fuzzy_check(g));
    CHECK(fl_fuzzy_estimate(g, &e));
    CHECK(e.x_mm >= -g->half_x_mm && e.x_mm <= g->half_x_mm);
    CHECK(e.y_mm >= -g->half_y_mm && e.y_mm <= g->half_y_mm);
    free(g);
}

void suite_adversarial(void)
{
    g_state = malloc(sizeof *g_state);
    if (!g_state || !adv_init(g_state)) {
        printf("FAIL adversarial: cannot initialise\n");
        free(g_state);
        return;
    }
    t_run("adversarial.hostile_frames", test_hostile_frames);
    t_run("adversarial.state_survives", test_state_survives);
    t_run("adversarial.localizer_contradiction", test_localizer_contradiction);
    free(g_state);
}
