/*
 * host_tests/test_adversarial.c - hostile frames through the whole vision
 * path (issue 7): all green, all white, all yellow, black, saturated, random
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
#include "render.h"
#include "adversarial.h"

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
                        const fl_field_t *field, uint32_t h)
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
    return h;
}

static adv_state_t *g_state;   /* big: allocated once */

static void test_hostile_frames(void)
{
    static const int sizes[][2] = {{320, 240}, {640, 480}, {1, 1}, {1, 240}, {320, 1},
                                   {2, 2}, {33, 17}, {321, 239}, {208, 160}};
    static const fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422, FL_FMT_YCBCR_PLANAR};
    const fl_field_t *field = fl_field_find("spl2013");
    fl_camera_t cam;
    fl_camera_pose_t pose;
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    uint32_t h = t_hash_init();
    int k, si, fi, frames = 0, rejected = 0, nsizes = t_quick ? 4 : (int)(sizeof sizes / sizeof sizes[0]);
    pose.neck_height_mm = m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    pose.head_pitch = 0;
    pose.head_yaw = 0;
    CHECK_EQ(fl_camera_init(&cam, m, &pose), FL_OK);
    for (k = 0; k < ADV_COUNT; k++)
        for (si = 0; si < nsizes; si++)
            for (fi = 0; fi < 3; fi++) {
                fl_image_t img;
                fl_status_t st;
                int pad = (k + si + fi) % 3 == 0 ? 0 : 7 * (fi + 1);  /* stride > width */
                uint8_t *buf;
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
                h = adv_run(g_state, &img, &cam, field, h);
                if (st != FL_OK)
                    CHECK_EQ(g_state->vis.lines.n_points + g_state->vis.crossings.n, 0);
                frames++;
                free(buf);
            }
    t_info("%d hostile frames (%d rejected views), outputs within capacity", frames, rejected);
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
    a = adv_run(fresh, &fr.view, &cam, sc.field, t_hash_init());
    b = adv_run(g_state, &fr.view, &cam, sc.field, t_hash_init());
    CHECK_EQ(a, b);
    CHECK(fresh->vis.crossings.n > 0);   /* the fixture does show a crossing */
    render_frame_free(&fr);
    free(fresh);
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
    free(g_state);
}
