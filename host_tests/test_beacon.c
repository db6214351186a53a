/*
 * host_tests/test_beacon.c - colored landmarks (beacon.h): sky-blue goal
 * posts and corner beacons of the aibo2004 field.
 *   - params and bad input (NULL, size mismatch, tiny frames);
 *   - the aibo2004 fixtures (fixtures/frames/index.txt with the .truth
 *     files): every beacon and sky-blue post foot of the truth that is
 *     fully inside the image is found, with its colors / side, within
 *     BC_MAX_PX pixels of the true foot; every result is one of them (no
 *     false result); the range errors are printed (t_info) and bounded;
 *   - nothing on the spl2013 fixtures (run directly: fl_vision_frame does
 *     not call the stage there) nor on the hostile frames of
 *     tools/world/adversarial.h (aibo camera and field);
 *   - fl_vision_frame on aibo2004 appends the observations (color2 set
 *     for beacons) and leaves spl2013 observations without them.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/adversarial.h"
#include "eval/detect.h"
#include "world/render.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Largest foot pixel error accepted (px), and relative range error. */
#define BC_MAX_PX 4.0
#define BC_MAX_RANGE_REL 0.12

typedef struct {
    fl_color_table_t colors;
    fl_vision_t vis;
    fl_beacon_t b;
} bt_state_t;

static bt_state_t *S;

static int bt_init(void)
{
    fl_color_params_t cp;
    fl_vision_params_t vp;
    fl_beacon_params_t bp;
    if (!S)
        S = calloc(1, sizeof *S);
    if (!S)
        return 0;
    fl_color_params_default(&cp);
    fl_vision_params_default(&vp);
    fl_beacon_params_default(&bp);
    return fl_color_init(&S->colors, &cp) == FL_OK && fl_vision_init(&S->vis, &vp) == FL_OK &&
           fl_beacon_init(&S->b, &bp) == FL_OK;
}

static void test_params(void)
{
    fl_beacon_params_t p;
    CHECK(bt_init());
    fl_beacon_params_default(&p);
    CHECK_EQ(fl_beacon_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_beacon_init(&S->b, NULL), FL_ERR_NULL);
    p.pink.h_hi = 180;
    CHECK_EQ(fl_beacon_init(&S->b, &p), FL_ERR_RANGE);
    fl_beacon_params_default(&p);
    p.skyblue.s_lo = 200;
    p.skyblue.s_hi = 100;
    CHECK_EQ(fl_beacon_init(&S->b, &p), FL_ERR_RANGE);
    fl_beacon_params_default(&p);
    p.col_step = 17;
    CHECK_EQ(fl_beacon_init(&S->b, &p), FL_ERR_RANGE);
    fl_beacon_params_default(&p);
    p.below_border_px = -1;
    CHECK_EQ(fl_beacon_init(&S->b, &p), FL_ERR_RANGE);
    fl_beacon_params_default(&p);
    p.min_confidence = 256;
    CHECK_EQ(fl_beacon_init(&S->b, &p), FL_ERR_RANGE);
    fl_beacon_params_default(&p);
    CHECK_EQ(fl_beacon_init(&S->b, &p), FL_OK);
    /* the default boxes classify the renderer's paints */
    {
        uint8_t px[3 * 4] = {80, 175, 230, 245, 90, 170, 191, 185, 47, 82, 141, 85};
        fl_image_t img;
        CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, px, 4, 1, 12), FL_OK);
        CHECK_EQ(fl_beacon_pixel_color(&p, &img, 0, 0), FL_COLOR_SKYBLUE);
        CHECK_EQ(fl_beacon_pixel_color(&p, &img, 1, 0), FL_COLOR_PINK);
        CHECK_EQ(fl_beacon_pixel_color(&p, &img, 2, 0), FL_COLOR_YELLOW);
        CHECK_EQ(fl_beacon_pixel_color(&p, &img, 3, 0), FL_COLOR_NONE);
        CHECK_EQ(fl_beacon_pixel_color(&p, &img, 4, 0), FL_COLOR_NONE);
        CHECK_EQ(fl_beacon_pixel_color(&p, &img, -1, 0), FL_COLOR_NONE);
        CHECK_EQ(fl_beacon_pixel_color(NULL, &img, 0, 0), FL_COLOR_NONE);
        CHECK_EQ(fl_beacon_pixel_color(&p, NULL, 0, 0), FL_COLOR_NONE);
    }
    CHECK(!fl_vision_wants_beacons(NULL));
    CHECK(!fl_vision_wants_beacons(fl_field_find("spl2013")));
    CHECK(!fl_vision_wants_beacons(fl_field_find("uva2013")));
    CHECK(!fl_vision_wants_beacons(fl_field_find("spl2020")));
    CHECK(fl_vision_wants_beacons(fl_field_find("aibo2004")));
}

/* fl_beacon_pixel_color (the stage's classification, with its grey
 * pre-rejection) against the plain definition: HSV, then the boxes in the
 * order yellow, sky-blue, pink; a grid of colors (every 3rd level, every
 * 7th in quick mode), in RGB and through YCbCr planes. */
static int bt_in(const fl_hsv_box_t *b, fl_hsv_t x)
{
    return fl_hsv_box_has_hue(b, x.h) && x.s >= b->s_lo && x.s <= b->s_hi && x.v >= b->v_lo &&
           x.v <= b->v_hi;
}

static void test_classes(void)
{
    fl_beacon_params_t p;
    int r, g, b, step = t_quick ? 7 : 3, n = 0, bad = 0, counts[5] = {0, 0, 0, 0, 0};
    uint32_t h = t_hash_init();
    fl_beacon_params_default(&p);
    for (r = 0; r < 256; r += step)
        for (g = 0; g < 256; g += step)
            for (b = 0; b < 256; b += step) {
                uint8_t px[3] = {(uint8_t)r, (uint8_t)g, (uint8_t)b}, y, cb, cr;
                fl_image_t img;
                fl_hsv_t x = fl_hsv_from_rgb(px[0], px[1], px[2]);
                fl_color_t want = bt_in(&p.yellow, x)    ? FL_COLOR_YELLOW
                                   : bt_in(&p.skyblue, x) ? FL_COLOR_SKYBLUE
                                   : bt_in(&p.pink, x)    ? FL_COLOR_PINK
                                                          : FL_COLOR_NONE, got;
                fl_image_init_packed(&img, FL_FMT_RGB888, px, 1, 1, 3);
                got = fl_beacon_pixel_color(&p, &img, 0, 0);
                bad += got != want;
                counts[got]++;
                n++;
                /* planar: the same through the integer BT.601 */
                {
                    uint8_t ycc[3], rgb2[3];
                    fl_image_get_ycbcr(&img, 0, 0, ycc);
                    y = ycc[0];
                    cb = ycc[1];
                    cr = ycc[2];
                    fl_image_init_planar(&img, &y, 1, &cb, 1, &cr, 1, 1, 1);
                    fl_rgb_from_ycbcr(y, cb, cr, rgb2);
                    x = fl_hsv_from_rgb(rgb2[0], rgb2[1], rgb2[2]);
                    want = bt_in(&p.yellow, x)    ? FL_COLOR_YELLOW
                           : bt_in(&p.skyblue, x) ? FL_COLOR_SKYBLUE
                           : bt_in(&p.pink, x)    ? FL_COLOR_PINK
                                                  : FL_COLOR_NONE;
                    got = fl_beacon_pixel_color(&p, &img, 0, 0);
                    bad += got != want;
                    h = t_hash_i32(h, (int32_t)got);
                }
            }
    CHECK_EQ(bad, 0);
    CHECK(counts[FL_COLOR_YELLOW] > 0 && counts[FL_COLOR_SKYBLUE] > 0 &&
          counts[FL_COLOR_PINK] > 0);
    t_info("%d colours x 2 formats: classification = HSV boxes; yellow %d sky-blue %d pink %d",
           n, counts[FL_COLOR_YELLOW], counts[FL_COLOR_SKYBLUE], counts[FL_COLOR_PINK]);
    t_digest("beacon.classes", h);
}

static void test_bad_input(void)
{
    uint8_t px[208 * 160 * 3];
    fl_image_t img, small;
    fl_camera_t cam;
    fl_camera_pose_t pose = {160, 0, 0, 0, 0, 0, 0};
    const fl_field_t *f = fl_field_find("aibo2004");
    int i;
    CHECK(bt_init());
    CHECK_EQ(fl_camera_init(&cam, fl_camera_model_find("aibo-ers7"), &pose), FL_OK);
    /* sky-blue above, pink below, green at the bottom */
    for (i = 0; i < 208 * 160; i++) {
        int v = i / 208;
        const uint8_t *c = v < 60 ? (const uint8_t *)"\x50\xaf\xe6"
                         : v < 100 ? (const uint8_t *)"\xf5\x5a\xaa"
                                   : (const uint8_t *)"\x52\x8d\x55";
        memcpy(px + 3 * i, c, 3);
    }
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, px, 208, 160, 208 * 3), FL_OK);
    CHECK_EQ(fl_image_init_packed(&small, FL_FMT_RGB888, px, 100, 80, 208 * 3), FL_OK);
    CHECK_EQ(fl_beacon_find(NULL, &S->vis.scan, &img, &S->colors, &cam, f), 0);
    CHECK_EQ(fl_beacon_find(&S->b, NULL, &img, &S->colors, &cam, f), 0);
    /* a scan of another frame size */
    fl_scan_frame(&S->vis.scan, &S->colors, &img, &cam);
    CHECK_EQ(fl_beacon_find(&S->b, &S->vis.scan, &small, &S->colors, &cam, f), 0);
    CHECK_EQ(fl_beacon_find(&S->b, &S->vis.scan, NULL, &S->colors, &cam, f), 0);
    CHECK_EQ(fl_beacon_find(&S->b, &S->vis.scan, &img, NULL, &cam, f), 0);
    /* no camera, no field: image positions only, bounded */
    fl_beacon_find(&S->b, &S->vis.scan, &img, &S->colors, NULL, NULL);
    CHECK(S->b.n >= 0 && S->b.n <= FL_BEACON_MAX_FOUND);
    for (i = 0; i < S->b.n; i++)
        CHECK_EQ(S->b.found[i].range_mm, 0);
    CHECK(S->b.n_runs <= FL_BEACON_MAX_RUNS && S->b.n_blobs <= FL_BEACON_MAX_BLOBS);
    /* whole-frame color: a wall of sky-blue over pink is neither a goal
     * (its bottom is on pink, not on the carpet) nor a beacon (no base) */
    fl_beacon_find(&S->b, &S->vis.scan, &img, &S->colors, &cam, f);
    CHECK_EQ(S->b.n, 0);
}

/* ---- fixtures ----------------------------------------------------------------- */

typedef struct {
    int frames, beacons, beacons_found, posts, posts_found, false_results;
    double max_px, max_rel;
    uint32_t h;
} bt_stats_t;

/* Beacon / post width (px) of a truth feature at its range (pinhole). */
static double bt_width_px(const fl_camera_t *cam, double diam, double range)
{
    return cam->model.focal_q4 / 16.0 * diam / (range > 1 ? range : 1);
}

static void bt_check_frame(const char *name, const truth_t *tr, const fl_camera_t *cam,
                           const fl_field_t *field, bt_stats_t *st, int posts)
{
    const fl_beacon_t *b = &S->vis.beacons;
    int i, k;
    int matched[FL_BEACON_MAX_FOUND];
    memset(matched, 0, sizeof matched);
    for (k = 0; k < tr->n; k++) {
        const truth_feature_t *t = &tr->f[k];
        const fl_landmark_t *lm;
        double half, best = 1e9;
        int bi = -1;
        if (t->occluded || t->landmark < 0)
            continue;
        lm = &field->landmarks[t->landmark];
        if (t->kind == TRUTH_BEACON) {
            half = 0.5 * bt_width_px(cam, field->beacon_diameter_mm, t->range_mm) + 1;
        } else if (t->kind == TRUTH_POST_FOOT && posts) {
            half = 0.5 * bt_width_px(cam, field->post_diameter_mm, t->range_mm) + 1;
        } else {
            continue;
        }
        if (t->u - half < 0 || t->u + half > tr->width - 1)
            continue;   /* cut by the image edge: not required */
        if (t->kind == TRUTH_BEACON)
            st->beacons++;
        else
            st->posts++;
        for (i = 0; i < b->n; i++) {
            const fl_beacon_found_t *f = &b->found[i];
            double d = hypot(f->u_q4 / 16.0 - t->u, f->v_q4 / 16.0 - t->v);
            if (matched[i] || f->kind != (t->kind == TRUTH_BEACON ? FL_LM_BEACON : FL_LM_POST))
                continue;
            if (d < best) {
                best = d;
                bi = i;
            }
        }
        if (bi < 0 || best > BC_MAX_PX) {
            t_fail_msg(__FILE__, __LINE__, "%s: %s of landmark %d at (%.1f, %.1f) not found "
                       "(nearest %.1f px)", name, t->kind == TRUTH_BEACON ? "beacon" : "post",
                       t->landmark, t->u, t->v, best);
            continue;
        }
        {
            const fl_beacon_found_t *f = &b->found[bi];
            double rel = fabs(f->range_mm - t->range_mm) / t->range_mm;
            matched[bi] = 1;
            if (t->kind == TRUTH_BEACON) {
                st->beacons_found++;
                CHECK_EQ(f->color2, lm->color2);
                if (f->color != FL_COLOR_NONE)
                    CHECK_EQ(f->color, lm->color);
            } else {
                st->posts_found++;
                CHECK_EQ(f->side, lm->side);
                CHECK_EQ(f->color, lm->color);
            }
            t_info("%s: %s%s lm %d foot err %.2f px, range %d mm vs %.0f (%.1f %%)%s", name,
                   t->kind == TRUTH_BEACON ? "beacon" : "post",
                   lm->color == FL_COLOR_SKYBLUE ? " sky-blue" : "", t->landmark, best,
                   (int)f->range_mm, t->range_mm, 100 * rel,
                   f->foot_visible ? "" : " (from size)");
            CHECK_LE(rel, BC_MAX_RANGE_REL);
            if (best > st->max_px)
                st->max_px = best;
            if (rel > st->max_rel)
                st->max_rel = rel;
        }
    }
    for (i = 0; i < b->n; i++) {
        const fl_beacon_found_t *f = &b->found[i];
        st->h = t_hash_i32(st->h, (int32_t)f->kind);
        st->h = t_hash_i32(st->h, (int32_t)f->color);
        st->h = t_hash_i32(st->h, (int32_t)f->color2);
        st->h = t_hash_i32(st->h, (int32_t)f->side);
        st->h = t_hash_i32(st->h, f->u_q4);
        st->h = t_hash_i32(st->h, f->v_q4);
        st->h = t_hash_i32(st->h, f->range_mm);
        st->h = t_hash_i32(st->h, f->bearing);
        st->h = t_hash_i32(st->h, f->confidence);
        if (!matched[i]) {
            /* a result on a landmark cut by the image edge is fine when it
             * is that landmark; anything else is a false result */
            int ok = 0;
            for (k = 0; k < tr->n; k++) {
                const truth_feature_t *t = &tr->f[k];
                if ((t->kind == TRUTH_BEACON && f->kind == FL_LM_BEACON) ||
                    (t->kind == TRUTH_POST_FOOT && f->kind == FL_LM_POST))
                    if (fabs(f->u_q4 / 16.0 - t->u) <= 8 && fabs(f->v_q4 / 16.0 - t->v) <= 8)
                        ok = 1;
            }
            if (!ok) {
                st->false_results++;
                t_fail_msg(__FILE__, __LINE__, "%s: false %s at (%.1f, %.1f)", name,
                           f->kind == FL_LM_BEACON ? "beacon" : "post", f->u_q4 / 16.0,
                           f->v_q4 / 16.0);
            }
        }
    }
}

/* Run every fixture of the index whose name starts with prefix; fn checks. */
static int bt_fixtures(const char *prefix, bt_stats_t *st, int direct)
{
    FILE *idx = fopen("fixtures/frames/index.txt", "r");
    char line[1024];
    int frames = 0;
    if (!idx)
        return -1;
    while (fgets(line, sizeof line, idx)) {
        char name[256], file[256], fmt[32], fieldn[64], camn[64], path[1024], err[256];
        static truth_t tr;
        render_frame_t fr;
        fl_camera_t c;
        fl_obs_list_t obs;
        const fl_field_t *field;
        int i;
        if (line[0] == '#' ||
            sscanf(line, "%255s %255s %31s %63s %63s", name, file, fmt, fieldn, camn) != 5 ||
            strncmp(name, prefix, strlen(prefix)) != 0)
            continue;
        snprintf(path, sizeof path, "fixtures/frames/%s.truth", name);
        if (truth_load(path, &tr, err, sizeof err) != 0)
            continue;
        snprintf(path, sizeof path, "fixtures/frames/%s", file);
        if (render_read_frame(path, &fr, err, sizeof err) != 0)
            continue;
        field = fl_field_find(fieldn);
        if (fl_camera_init(&c, fl_camera_model_find(camn), &tr.head) != FL_OK || !field) {
            render_frame_free(&fr);
            continue;
        }
        fl_vision_frame(&S->vis, &S->colors, &fr.view, &c, field, &obs);
        frames++;
        if (direct) {
            /* the stage itself, which fl_vision_frame skips on this field,
             * for beacons and sky-blue goals (its yellow-goal mode is for
             * the AIBO box goals and is not meant for SPL goals): nothing */
            CHECK_EQ(S->vis.beacons.n, 0);
            for (i = 0; i < obs.n; i++)
                CHECK(obs.obs[i].kind != FL_LM_BEACON && obs.obs[i].color2 == FL_COLOR_NONE);
            fl_beacon_find(&S->b, &S->vis.scan, &fr.view, &S->colors, &c, field);
            if (S->b.n != 0)
                t_fail_msg(__FILE__, __LINE__, "%s: %d coloured landmarks on %s", name,
                           (int)S->b.n, fieldn);
            st->h = t_hash_i32(st->h, S->b.n_runs);
            st->h = t_hash_i32(st->h, S->b.n_blobs);
        } else {
            bt_check_frame(name, &tr, &c, field, st, 1);
            /* the observations: every result with a range is appended,
             * except a post fl_goal_find reported already */
            for (i = 0; i < S->vis.beacons.n; i++) {
                const fl_beacon_found_t *f = &S->vis.beacons.found[i];
                int k, seen = 0;
                if (f->range_mm <= 0 || f->confidence < S->vis.params.min_confidence)
                    continue;
                for (k = 0; k < obs.n; k++)
                    if (obs.obs[k].kind == f->kind && obs.obs[k].u_q4 == f->u_q4 &&
                        obs.obs[k].v_q4 == f->v_q4 && obs.obs[k].range_mm == f->range_mm &&
                        obs.obs[k].color == f->color && obs.obs[k].color2 == f->color2)
                        seen = 1;
                for (k = 0; k < S->vis.posts.n && f->kind == FL_LM_POST; k++)
                    if (abs(S->vis.posts.post[k].foot_u_q4 - f->u_q4) <= 16 * 16)
                        seen = 1;
                CHECK(seen);
            }
        }
        render_frame_free(&fr);
    }
    fclose(idx);
    st->frames = frames;
    return frames;
}

static void test_aibo_fixtures(void)
{
    bt_stats_t st;
    memset(&st, 0, sizeof st);
    st.h = t_hash_init();
    CHECK(bt_init());
    if (bt_fixtures("aibo2004", &st, 0) < 0) {
        t_info("skipped: fixtures/frames/index.txt not found (run from the repository root)");
        return;
    }
    CHECK(st.frames >= 8);
    CHECK(st.beacons >= 2 && st.posts >= 2);
    CHECK_EQ(st.beacons_found, st.beacons);
    CHECK_EQ(st.posts_found, st.posts);
    CHECK_EQ(st.false_results, 0);
    t_info("aibo2004: %d frames, beacons %d/%d, posts (sky-blue and yellow) %d/%d, max foot error %.2f px, "
           "max range error %.1f %%", st.frames, st.beacons_found, st.beacons, st.posts_found,
           st.posts, st.max_px, 100 * st.max_rel);
    t_digest("beacon.aibo_fixtures", st.h);
}

static void test_spl_none(void)
{
    bt_stats_t st;
    fl_beacon_params_t p;
    memset(&st, 0, sizeof st);
    st.h = t_hash_init();
    CHECK(bt_init());
    fl_beacon_params_default(&p);
    p.yellow_goals = 0;
    CHECK_EQ(fl_beacon_init(&S->b, &p), FL_OK);
    if (bt_fixtures("spl2013", &st, 1) < 0) {
        t_info("skipped: fixtures/frames/index.txt not found");
        return;
    }
    CHECK(st.frames >= 20);
    t_info("spl2013: %d frames, no beacon, no sky-blue post", st.frames);
    t_digest("beacon.spl2013", st.h);
}

static void test_adversarial(void)
{
    static const int sizes[][2] = {{208, 160}, {320, 240}, {1, 1}, {2, 2}, {33, 17}, {640, 480}};
    static const fl_pixel_format_t fmts[3] = {FL_FMT_RGB888, FL_FMT_YUYV422,
                                              FL_FMT_YCBCR_PLANAR};
    const fl_field_t *field = fl_field_find("aibo2004");
    fl_camera_t cam;
    fl_camera_pose_t pose = {160, 0, 0, 0, 0, 0, 0};
    uint32_t h = t_hash_init();
    int k, si, fi, frames = 0;
    int nsizes = t_quick ? 5 : (int)(sizeof sizes / sizeof sizes[0]);
    CHECK(bt_init());
    CHECK_EQ(fl_camera_init(&cam, fl_camera_model_find("aibo-ers7"), &pose), FL_OK);
    for (k = 0; k < ADV_COUNT; k++)
        for (si = 0; si < nsizes; si++)
            for (fi = 0; fi < 3; fi++) {
                fl_image_t img;
                fl_status_t st;
                fl_obs_list_t obs;
                uint8_t *buf = adv_frame((adv_kind_t)k, sizes[si][0], sizes[si][1], fmts[fi],
                                         (k + fi) % 2 ? 5 : 0, &img, &st);
                int i;
                fl_camera_model_t model;
                if (!buf)
                    continue;
                /* a camera model of the frame's size (another is refused) */
                adv_camera_model(fl_camera_model_find("aibo-ers7"), sizes[si][0], sizes[si][1],
                                 &model);
                CHECK_EQ(fl_camera_init(&cam, &model, &pose), FL_OK);
                fl_vision_frame(&S->vis, &S->colors, &img, &cam, field, &obs);
                CHECK(S->vis.beacons.n >= 0 && S->vis.beacons.n <= FL_BEACON_MAX_FOUND);
                CHECK(S->vis.beacons.n_runs <= FL_BEACON_MAX_RUNS);
                if (S->vis.beacons.n != 0)
                    t_fail_msg(__FILE__, __LINE__, "%s %dx%d fmt %d: %d results",
                               adv_name((adv_kind_t)k), sizes[si][0], sizes[si][1], (int)fmts[fi],
                               (int)S->vis.beacons.n);
                for (i = 0; i < obs.n; i++)
                    CHECK(obs.obs[i].kind != FL_LM_BEACON);
                h = t_hash_i32(h, S->vis.beacons.n_runs);
                h = t_hash_i32(h, S->vis.beacons.samples);
                h = t_hash_i32(h, S->vis.beacons.runs_dropped);
                frames++;
                free(buf);
            }
    t_info("%d hostile frames on aibo2004: no beacon, no sky-blue post", frames);
    t_digest("beacon.adversarial", h);
}

void suite_beacon(void)
{
    t_run("beacon.params", test_params);
    t_run("beacon.classes", test_classes);
    t_run("beacon.bad_input", test_bad_input);
    t_run("beacon.aibo_fixtures", test_aibo_fixtures);
    t_run("beacon.spl2013_none", test_spl_none);
    t_run("beacon.adversarial", test_adversarial);
    free(S);
    S = NULL;
}
