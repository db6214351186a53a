/*
 * host_tests/test_corners.c - seed 004's corner stage (corners.h).
 *   - params and bad input (NULL, zero and oversized frames, no init, a
 *     camera of another size, all-white, all-black and noise frames);
 *   - the detector on hand-made frames (green carpet, white lines 6 px
 *     wide): an L's outer and inner corner and a T's two inner corners
 *     found within 2 px, nothing on straight lines (horizontal and
 *     shallow) nor on noise;
 *   - labels and pairing: the L gives one C (open + closed), the T two
 *     closed corners and a T-field, the T under a yellow block a T-net;
 *   - the rendered aibo2004 fixtures and random rendered AIBO frames
 *     aimed at seed 004's feature points: precision and recall within
 *     3 m (printed; floors asserted as measured).
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

#define CW 208
#define CH 160

typedef struct {
    fl_color_table_t colors;
    fl_vision_t vis;
    fl_corners_t cn;
    uint8_t rgb[CW * CH * 3];
} ct_state_t;

static ct_state_t *S;

static int ct_init(void)
{
    fl_color_params_t cp;
    fl_vision_params_t vp;
    fl_corners_params_t p;
    if (!S)
        S = calloc(1, sizeof *S);
    if (!S)
        return 0;
    fl_color_params_default(&cp);
    fl_vision_params_default(&vp);
    fl_corners_params_default(&p);
    /* CORNERS_TUNE="min_var closed_white_pct t_first label_r pair_mm
     * min_mid_white rel_pct label_mode": other params, for tuning runs */
    if (getenv("CORNERS_TUNE")) {
        int a[8];
        if (sscanf(getenv("CORNERS_TUNE"), "%d %d %d %d %d %d %d %d", &a[0], &a[1], &a[2], &a[3], &a[4], &a[5], &a[6], &a[7]) == 8) {
            p.label_mode = a[7];
            p.rel_pct = a[6];
            p.min_mid_white = a[5];
            p.min_var = a[0];
            p.closed_white_pct = a[1];
            p.t_first = a[2];
            p.label_r = a[3];
            p.pair_mm = a[4];
        }
    }
    return fl_color_init(&S->colors, &cp) == FL_OK && fl_vision_init(&S->vis, &vp) == FL_OK &&
           fl_corners_init(&S->cn, &p) == FL_OK;
}

/* ---- hand-made frames ----------------------------------------------------- */

static const uint8_t CT_GREEN[3] = { 60, 140, 70 };
static const uint8_t CT_WHITE[3] = { 230, 230, 230 };
static const uint8_t CT_YELLOW[3] = { 220, 200, 30 };

static void ct_fill(const uint8_t col[3])
{
    int i;
    for (i = 0; i < CW * CH; i++)
        memcpy(S->rgb + 3 * i, col, 3);
}

/* Rectangle [x0, x1] x [y0, y1] (inclusive, clipped). */
static void ct_rect(int x0, int y0, int x1, int y1, const uint8_t col[3])
{
    int x, y;
    for (y = y0 < 0 ? 0 : y0; y <= y1 && y < CH; y++)
        for (x = x0 < 0 ? 0 : x0; x <= x1 && x < CW; x++)
            memcpy(S->rgb + 3 * (y * CW + x), col, 3);
}

/* Add uniform noise of +-amp to every channel (deterministic). */
static void ct_noise(int amp, uint64_t seed)
{
    t_rng_t r;
    int i;
    t_rng_seed(&r, seed);
    for (i = 0; i < CW * CH * 3; i++) {
        int v = S->rgb[i] + t_rng_range(&r, -amp, amp);
        S->rgb[i] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
    }
}

static fl_status_t ct_run(const fl_camera_t *cam)
{
    fl_image_t img;
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, CW, CH, 3 * CW), FL_OK);
    return fl_corners_run(&S->cn, &img, &S->colors, cam, NULL);
}

/* Index of the kept corner nearest (x, y) within tol px, else -1. */
static int ct_near(double x, double y, double tol)
{
    int i, best = -1;
    double bd = tol;
    for (i = 0; i < S->cn.n_corners; i++) {
        const double d = hypot(S->cn.corner[i].x - x, S->cn.corner[i].y - y);
        if (d <= bd) {
            bd = d;
            best = i;
        }
    }
    return best;
}

static void ct_dump(const char *what)
{
    int i;
    t_info("%s: edge %d cand %d maxima %d kept %d (colour-rejected %d), features %d", what,
           (int)S->cn.n_edge, (int)S->cn.n_cand, (int)S->cn.n_maxima, (int)S->cn.n_corners,
           (int)S->cn.rejected_color, (int)S->cn.n_features);
    for (i = 0; i < S->cn.n_corners; i++) {
        const fl_corner_t *k = &S->cn.corner[i];
        t_info("  corner (%d, %d) label %d V %d resp %u white %d green %d net %d", k->x, k->y,
               k->label, k->var, (unsigned)k->response, k->n_white, k->n_green, k->n_net);
    }
    for (i = 0; i < S->cn.n_features; i++) {
        const fl_cfeat_t *f = &S->cn.feature[i];
        t_info("  feature type %d at (%.1f, %.1f) conf %d range %d bearing %.1f", f->type,
               f->u_q4 / 16.0, f->v_q4 / 16.0, f->confidence, (int)f->range_mm,
               fl_angle_to_mdeg(f->bearing) / 1000.0);
    }
}

static void test_params(void)
{
    fl_corners_params_t p;
    CHECK(ct_init());
    fl_corners_params_default(&p);
    CHECK_EQ(fl_corners_init(NULL, &p), FL_ERR_NULL);
    CHECK_EQ(fl_corners_init(&S->cn, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_corners_init_cfg(&S->cn, &p, FL_CONFIG_FINGERPRINT ^ 1u), FL_ERR_CONFIG);
    p.window_r = 5;
    CHECK_EQ(fl_corners_init(&S->cn, &p), FL_ERR_RANGE);
    fl_corners_params_default(&p);
    p.min_var = 0;
    CHECK_EQ(fl_corners_init(&S->cn, &p), FL_ERR_RANGE);
    fl_corners_params_default(&p);
    p.net.yellow.h_hi = 180;
    CHECK_EQ(fl_corners_init(&S->cn, &p), FL_ERR_RANGE);
    fl_corners_params_default(&p);
    p.closed_white_pct = 0;
    CHECK_EQ(fl_corners_init(&S->cn, &p), FL_ERR_RANGE);
    fl_corners_params_default(&p);
    CHECK_EQ(fl_corners_init(&S->cn, &p), FL_OK);
    CHECK_EQ(S->cn.params.window_r, 3);
}

static void test_bad_input(void)
{
    fl_image_t img;
    fl_camera_t cam;
    fl_camera_pose_t pose;
    fl_corners_t *raw;
    int k;
    CHECK(ct_init());
    ct_fill(CT_GREEN);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, CW, CH, 3 * CW), FL_OK);
    CHECK_EQ(fl_corners_run(NULL, &img, &S->colors, NULL, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_corners_run(&S->cn, NULL, &S->colors, NULL, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_corners_run(&S->cn, &img, NULL, NULL, NULL), FL_ERR_NULL);
    /* not initialized */
    raw = calloc(1, sizeof *raw);
    CHECK(raw != NULL);
    if (raw) {
        CHECK_EQ(fl_corners_run(raw, &img, &S->colors, NULL, NULL), FL_ERR_STATE);
        free(raw);
    }
    /* zero size, bad stride, odd YUYV, oversized, tiny */
    img.width = 0;
    CHECK(fl_corners_run(&S->cn, &img, &S->colors, NULL, NULL) != FL_OK);
    CHECK_EQ(S->cn.n_features, 0);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, CW, CH, 3 * CW), FL_OK);
    img.stride[0] = CW;
    CHECK_EQ(fl_corners_run(&S->cn, &img, &S->colors, NULL, NULL), FL_ERR_STRIDE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, CW / 2, CH / 2, 3 * CW), FL_OK);
    img.format = (fl_pixel_format_t)7;
    CHECK(fl_corners_run(&S->cn, &img, &S->colors, NULL, NULL) != FL_OK);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, 4, 4, 12), FL_OK);
    CHECK_EQ(fl_corners_run(&S->cn, &img, &S->colors, NULL, NULL), FL_ERR_SIZE);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, CW + 2, 10, 3 * (CW + 2)), FL_OK);
    CHECK_EQ(fl_corners_run(&S->cn, &img, &S->colors, NULL, NULL), FL_ERR_SIZE);
    /* a camera of another size */
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = 450;
    CHECK_EQ(fl_camera_init(&cam, fl_camera_model_find("nao4-bottom-320"), &pose), FL_OK);
    CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, CW, CH, 3 * CW), FL_OK);
    CHECK_EQ(fl_corners_run(&S->cn, &img, &S->colors, &cam, NULL), FL_ERR_MISMATCH);
    /* the measure without a valid pixel */
    {
        int32_t v = 7, a = 7;
        CHECK(!fl_corners_measure(NULL, 10, 10, &v, &a));
        CHECK(!fl_corners_measure(&S->cn, -1, 10, &v, &a));
        CHECK_EQ(v, 0);
        CHECK_EQ(a, 0);
    }
    /* all white, all black, noise: no corner, no feature, status OK */
    for (k = 0; k < 4; k++) {
        static const uint8_t black[3] = { 0, 0, 0 };
        ct_fill(k == 0 ? CT_WHITE : k == 1 ? black : CT_GREEN);
        if (k == 2)
            ct_noise(127, 99);   /* full-range noise: every colour */
        if (k == 3)
            ct_noise(12, 98);    /* carpet noise */
        CHECK_EQ(ct_run(NULL), FL_OK);
        CHECK_EQ(S->cn.n_features, 0);
        if (k != 2)
            CHECK_EQ(S->cn.n_maxima, 0);
        CHECK_LE(S->cn.n_cand, FL_CORNERS_MAX_CAND);
        CHECK_LE(S->cn.n_cand + S->cn.cand_dropped, S->cn.n_edge);
        if (k == 2)
            CHECK(S->cn.cand_dropped > 0);   /* the cap bounds the work */
        t_info("bad input frame %d: edge %d cand %d (dropped %d) maxima %d kept %d", k,
               (int)S->cn.n_edge, (int)S->cn.n_cand, (int)S->cn.cand_dropped, (int)S->cn.n_maxima,
               (int)S->cn.n_corners);
    }
}

/* An L of a 6 px line reaching the image's top and right edges: outer
 * corner at pixel (60, 85) (its edges x = 59.5 and y = 85.5), inner at
 * (65.5, 79.5). */
static void ct_draw_l(void)
{
    ct_fill(CT_GREEN);
    ct_rect(60, 0, 65, 85, CT_WHITE);
    ct_rect(60, 80, CW - 1, 85, CT_WHITE);
}

/* A T: a 6 px bar across the image (rows 60..65) and a 6 px stem down
 * from it (columns 100..105): inner corners at (99.5, 65.5), (105.5, 65.5). */
static void ct_draw_t(void)
{
    ct_fill(CT_GREEN);
    ct_rect(0, 60, CW - 1, 65, CT_WHITE);
    ct_rect(100, 66, 105, CH - 1, CT_WHITE);
}

static void test_detector(void)
{
    int i, x, y;
    CHECK(ct_init());
    /* L */
    ct_draw_l();
    ct_noise(3, 1);
    CHECK_EQ(ct_run(NULL), FL_OK);
    ct_dump("L");
    CHECK(ct_near(59.5, 85.5, 2.0) >= 0);
    CHECK(ct_near(65.5, 79.5, 2.0) >= 0);
    CHECK_EQ(S->cn.n_maxima, 2);
    /* T */
    ct_draw_t();
    ct_noise(3, 2);
    CHECK_EQ(ct_run(NULL), FL_OK);
    ct_dump("T");
    CHECK(ct_near(99.5, 65.5, 2.0) >= 0);
    CHECK(ct_near(105.5, 65.5, 2.0) >= 0);
    CHECK_EQ(S->cn.n_maxima, 2);
    /* the measure: high at the L's outer corner, low on a straight edge */
    ct_draw_l();
    CHECK_EQ(ct_run(NULL), FL_OK);
    {
        int32_t vc = 0, ac = 0, ve = 0, ae = 0;
        i = ct_near(59.5, 85.5, 2.0);
        CHECK(i >= 0);
        if (i >= 0)
            CHECK(fl_corners_measure(&S->cn, S->cn.corner[i].x, S->cn.corner[i].y, &vc, &ac));
        CHECK(fl_corners_measure(&S->cn, 140, 86, &ve, &ae));
        t_info("measure: corner V %d A %d, straight edge V %d A %d", (int)vc, (int)ac, (int)ve, (int)ae);
        CHECK(vc >= 128);
        CHECK_LE(ve, 8);
    }
    /* straight lines: horizontal and a shallow slope (1 in 4): no corner */
    ct_fill(CT_GREEN);
    ct_rect(0, 70, CW - 1, 75, CT_WHITE);
    for (x = 0; x < CW; x++)
        for (y = 0; y < 6; y++)
            ct_rect(x, 10 + x / 4 + y, x, 10 + x / 4 + y, CT_WHITE);
    ct_noise(3, 3);
    CHECK_EQ(ct_run(NULL), FL_OK);
    ct_dump("straight");
    CHECK_EQ(S->cn.n_maxima, 0);
    CHECK_EQ(S->cn.n_features, 0);
    /* noise only */
    ct_fill(CT_GREEN);
    ct_noise(10, 4);
    CHECK_EQ(ct_run(NULL), FL_OK);
    ct_dump("noise");
    CHECK_EQ(S->cn.n_maxima, 0);
    /* without smoothing the same noise gives candidates (seed 004 fig. 1) */
    {
        fl_corners_params_t p;
        fl_image_t img;
        fl_corners_params_default(&p);
        p.smooth = 0;
        CHECK_EQ(fl_corners_init(&S->cn, &p), FL_OK);
        CHECK_EQ(fl_image_init_packed(&img, FL_FMT_RGB888, S->rgb, CW, CH, 3 * CW), FL_OK);
        CHECK_EQ(fl_corners_run(&S->cn, &img, &S->colors, NULL, NULL), FL_OK);
        t_info("noise without smoothing: edge %d maxima %d", (int)S->cn.n_edge, (int)S->cn.n_maxima);
        CHECK(S->cn.n_maxima > 0);
        fl_corners_params_default(&p);
        CHECK_EQ(fl_corners_init(&S->cn, &p), FL_OK);
    }
}

static int ct_count(int type)
{
    int i, n = 0;
    for (i = 0; i < S->cn.n_features; i++)
        n += S->cn.feature[i].type == type;
    return n;
}

static void test_labels(void)
{
    int i;
    CHECK(ct_init());
    /* L: one C, outer open, inner closed, midpoint between them */
    ct_draw_l();
    ct_noise(3, 5);
    CHECK_EQ(ct_run(NULL), FL_OK);
    i = ct_near(59.5, 85.5, 2.0);
    CHECK(i >= 0 && S->cn.corner[i].label == FL_CORNER_OPEN);
    CHECK(i >= 0 && S->cn.corner[i].convex == 1);    /* Sojka: convex */
    i = ct_near(65.5, 79.5, 2.0);
    CHECK(i >= 0 && S->cn.corner[i].label == FL_CORNER_CLOSED);
    CHECK(i >= 0 && S->cn.corner[i].convex == -1);   /* concave */
    CHECK_EQ(S->cn.n_features, 1);
    CHECK_EQ(ct_count(FL_CFEAT_C), 1);
    if (S->cn.n_features == 1) {
        CHECK_LE(fabs(S->cn.feature[0].u_q4 / 16.0 - 62.5), 2.0);
        CHECK_LE(fabs(S->cn.feature[0].v_q4 / 16.0 - 82.5), 2.0);
        CHECK(S->cn.feature[0].confidence >= 64);
        CHECK(!S->cn.feature[0].has_ground);
    }
    /* T: two closed -> T-field */
    ct_draw_t();
    ct_noise(3, 6);
    CHECK_EQ(ct_run(NULL), FL_OK);
    CHECK_EQ(S->cn.n_corners, 2);
    for (i = 0; i < S->cn.n_corners; i++)
        CHECK_EQ(S->cn.corner[i].label, FL_CORNER_CLOSED);
    CHECK_EQ(S->cn.n_features, 1);
    CHECK_EQ(ct_count(FL_CFEAT_T_FIELD), 1);
    for (i = 0; i < S->cn.n_corners; i++)
        CHECK_EQ(S->cn.corner[i].convex, -1);
    /* T under a yellow block (the net behind the goal line): T-net */
    ct_draw_t();
    ct_rect(110, 20, 180, 50, CT_YELLOW);
    ct_noise(3, 7);
    CHECK_EQ(ct_run(NULL), FL_OK);
    ct_dump("T-net");
    CHECK_EQ(S->cn.n_features, 1);
    CHECK_EQ(ct_count(FL_CFEAT_T_NET), 1);
    /* the same with the block far away (beyond net_r): T-field again */
    ct_draw_t();
    ct_rect(170, 0, 200, 20, CT_YELLOW);
    CHECK_EQ(ct_run(NULL), FL_OK);
    CHECK_EQ(ct_count(FL_CFEAT_T_FIELD), 1);
    /* a grey (non-white, non-green) L on green: colour filter drops it */
    {
        static const uint8_t blue[3] = { 40, 40, 200 };
        ct_fill(CT_GREEN);
        ct_rect(60, 0, 65, 85, blue);
        ct_rect(60, 80, CW - 1, 85, blue);
        CHECK_EQ(ct_run(NULL), FL_OK);
        CHECK(S->cn.n_maxima >= 2);
        CHECK_EQ(S->cn.n_corners, 0);
        CHECK_EQ(S->cn.rejected_color, S->cn.n_maxima);
    }
}

/* ---- rendered AIBO frames ------------------------------------------------- */

/* Seed 004's feature points on aibo2004 (src/model/field.c): C at the
 * goal-box corners, T-field where the halfway line meets the boundary,
 * T-net where the box side lines meet the goal line. */
typedef struct {
    int type;
    double x, y;
} ct_truth_t;

static const ct_truth_t CT_TRUTH[] = {
    { FL_CFEAT_C, 1450, 500 },        { FL_CFEAT_C, 1450, -500 },
    { FL_CFEAT_C, -1450, 500 },       { FL_CFEAT_C, -1450, -500 },
    { FL_CFEAT_T_FIELD, 0, 1350 },    { FL_CFEAT_T_FIELD, 0, -1350 },
    { FL_CFEAT_T_NET, 2100, 500 },    { FL_CFEAT_T_NET, 2100, -500 },
    { FL_CFEAT_T_NET, -2100, 500 },   { FL_CFEAT_T_NET, -2100, -500 },
};
#define CT_NTRUTH ((int)(sizeof CT_TRUTH / sizeof CT_TRUTH[0]))

typedef struct {
    int truth, found, det, correct, wrong_type, at_field_corner, truth_near, found_near;
    int truth_t[4], found_t[4], det_t[4], correct_t[4];
    double err_sum, err_max;
} ct_score_t;

static const char *ct_type_name(int t)
{
    return t == FL_CFEAT_C ? "C" : t == FL_CFEAT_T_FIELD ? "T-field" : "T-net";
}

/* Ground tolerance of a detection, mm (the feature's two corners span a
 * line width; the range error of a pixel grows with range). */
static double ct_tol(double range)
{
    return 150 + 0.1 * range;
}

static void ct_score(const render_scene_t *sc, ct_score_t *s)
{
    int k, i;
    int used[FL_CORNERS_MAX_FEATURES];
    memset(used, 0, sizeof used);
    for (k = 0; k < CT_NTRUTH; k++) {
        const ct_truth_t *t = &CT_TRUTH[k];
        double u, v, rx, ry, range, bd = 1e9;
        int best = -1;
        if (!render_project_field(sc, t->x, t->y, 0, &u, &v, NULL))
            continue;
        if (u < 8 || v < 8 || u > CW - 9 || v > CH - 9)
            continue;
        if (render_occluded(sc, t->x, t->y, 0, 30, -1))
            continue;
        render_field_to_robot(sc, t->x, t->y, &rx, &ry);
        range = hypot(rx, ry);
        if (range > 3000)
            continue;
        s->truth++;
        s->truth_t[t->type]++;
        s->truth_near += range <= 1500;
        for (i = 0; i < S->cn.n_features; i++) {
            const fl_cfeat_t *f = &S->cn.feature[i];
            double d;
            if (f->type != t->type || !f->has_ground)
                continue;
            d = hypot(f->ground.x_mm - rx, f->ground.y_mm - ry);
            if (d < bd) {
                bd = d;
                best = i;
            }
        }
        if (getenv("CORNERS_VERBOSE") && !(best >= 0 && bd <= ct_tol(range))) {
            int j;
            char buf[512];
            size_t o = 0;
            buf[0] = 0;
            for (j = 0; j < S->cn.n_corners && o < sizeof buf - 40; j++)
                if (hypot(S->cn.corner[j].x - u, S->cn.corner[j].y - v) < 20)
                    o += (size_t)snprintf(buf + o, sizeof buf - o, " (%d,%d L%d V%d)", S->cn.corner[j].x,
                                          S->cn.corner[j].y, S->cn.corner[j].label, S->cn.corner[j].var);
            t_info("MISS %s at px %.1f %.1f range %.0f: near%s", ct_type_name(t->type), u, v, range, buf);
        }
        if (best >= 0 && bd <= ct_tol(range)) {
            s->found++;
            s->found_t[t->type]++;
            s->found_near += range <= 1500;
            used[best] = 1;
            s->err_sum += bd;
            if (bd > s->err_max)
                s->err_max = bd;
        }
    }
    for (i = 0; i < S->cn.n_features; i++) {
        const fl_cfeat_t *f = &S->cn.feature[i];
        int ok = used[i], other = 0, fc = 0;
        if (f->type > FL_CFEAT_T_NET || !f->has_ground || f->range_mm > 3000)
            continue;
        s->det++;
        s->det_t[f->type]++;
        for (k = 0; k < CT_NTRUTH && !ok; k++) {
            double rx, ry;
            render_field_to_robot(sc, CT_TRUTH[k].x, CT_TRUTH[k].y, &rx, &ry);
            if (hypot(f->ground.x_mm - rx, f->ground.y_mm - ry) <= ct_tol(hypot(rx, ry))) {
                if (CT_TRUTH[k].type == f->type)
                    ok = 1;
                else
                    other = 1;
            }
        }
        for (k = 0; k < 4 && !ok; k++) {   /* the field corners: an L too */
            double rx, ry;
            render_field_to_robot(sc, k & 1 ? 2100 : -2100, k & 2 ? 1350 : -1350, &rx, &ry);
            if (hypot(f->ground.x_mm - rx, f->ground.y_mm - ry) <= ct_tol(hypot(rx, ry)))
                fc = 1;
        }
        if (ok) {
            s->correct++;
            s->correct_t[f->type]++;
        }
        s->wrong_type += !ok && other;
        s->at_field_corner += !ok && fc;
    }
}

static void ct_print(const char *what, const ct_score_t *s)
{
    int t;
    t_info("%s: recall %d/%d (%.2f), precision %d/%d (%.2f) within 3 m; wrong type %d, "
           "false at field corners %d; ground error mean %.0f max %.0f mm",
           what, s->found, s->truth, s->truth ? (double)s->found / s->truth : 0, s->correct, s->det,
           s->det ? (double)s->correct / s->det : 0, s->wrong_type, s->at_field_corner,
           s->found ? s->err_sum / s->found : 0, s->err_max);
    t_info("  recall up to 1.5 m %d/%d, 1.5..3 m %d/%d", s->found_near, s->truth_near,
           s->found - s->found_near, s->truth - s->truth_near);
    for (t = 1; t <= 3; t++)
        t_info("  %-7s recall %d/%d precision %d/%d", ct_type_name(t), s->found_t[t], s->truth_t[t],
               s->correct_t[t], s->det_t[t]);
}

/* Run the vision (for the beacon stage's posts) and the corners on a
 * rendered frame. */
static fl_status_t ct_frame(const render_frame_t *fr, const fl_camera_t *cam, const fl_field_t *field)
{
    fl_obs_list_t obs;
    fl_vision_frame(&S->vis, &S->colors, &fr->view, cam, field, &obs);
    return fl_corners_run(&S->cn, &fr->view, &S->colors, cam, &S->vis.beacons);
}

static void test_fixtures(void)
{
    static const char *const names[2] = { "aibo2004_l_corner", "aibo2004_t_box" };
    const fl_field_t *field = fl_field_find("aibo2004");
    int n;
    CHECK(ct_init());
    CHECK(field != NULL);
    for (n = 0; n < 2 && field; n++) {
        char path[256], err[256];
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        ct_score_t s;
        snprintf(path, sizeof path, "fixtures/frames/%s.scene", names[n]);
        if (render_scene_load(path, &sc, err, sizeof err) != 0) {
            t_info("skipped %s: %s (run from the repository root)", names[n], err);
            continue;
        }
        if (render_frame(&sc, &fr) != 0 || render_scene_camera(&sc, &cam) != FL_OK) {
            CHECK(0);
            continue;
        }
        CHECK_EQ(ct_frame(&fr, &cam, field), FL_OK);
        ct_dump(names[n]);
        memset(&s, 0, sizeof s);
        ct_score(&sc, &s);
        ct_print(names[n], &s);
        if (n == 1) {
            /* the goal box's corner (1450, 500) at 0.5 m: a C */
            CHECK_EQ(s.found_t[FL_CFEAT_C], 1);
            /* the yellow goal: a net feature from the beacon stage's post */
            CHECK_EQ(ct_count(FL_CFEAT_NET_YELLOW), 1);
        }
        render_frame_free(&fr);
    }
}

/* fl_corners_obs on the rendered aibo2004_t_box fixture: its goal-box
 * corner (1450, 500) at about 0.5 m comes out as an FL_LM_CORNER_C
 * observation near the true range and bearing, the yellow goal as an
 * FL_LM_NET of colour yellow; appending keeps what the list held, a full
 * list counts the rest in dropped; NULL and an uninitialized state give 0. */
static void test_obs(void)
{
    const fl_field_t *field = fl_field_find("aibo2004");
    char err[256];
    render_scene_t sc;
    render_frame_t fr;
    fl_camera_t cam;
    static fl_obs_list_t obs;
    static fl_corners_t blank;
    fl_obs_t first;
    int i, n, n_c = 0, n_net = 0, c_ok = 0;
    double rx, ry, best = 1e9, best_b = 0;
    CHECK(ct_init());
    CHECK(field != NULL);
    if (!field)
        return;
    if (render_scene_load("fixtures/frames/aibo2004_t_box.scene", &sc, err, sizeof err) != 0) {
        t_info("skipped: %s (run from the repository root)", err);
        return;
    }
    if (render_frame(&sc, &fr) != 0 || render_scene_camera(&sc, &cam) != FL_OK) {
        CHECK(0);
        return;
    }
    CHECK_EQ(ct_frame(&fr, &cam, field), FL_OK);
    render_frame_free(&fr);
    render_field_to_robot(&sc, 1450, 500, &rx, &ry);
    fl_obs_list_clear(&obs);
    memset(&first, 0, sizeof first);
    first.kind = FL_LM_POST;
    first.range_mm = 1000;
    CHECK(fl_obs_list_push(&obs, &first));
    n = (int)fl_corners_obs(&S->cn, &obs);
    CHECK(n >= 2);
    CHECK_EQ(obs.n, n + 1);
    CHECK_EQ(obs.obs[0].kind, FL_LM_POST);   /* appended, not cleared */
    CHECK_EQ(obs.dropped, 0);
    for (i = 1; i < obs.n; i++) {
        const fl_obs_t *o = &obs.obs[i];
        CHECK(fl_landmark_kind_is_feature(o->kind));
        CHECK(o->range_mm > 0 && o->range_mm <= 4500);
        CHECK(o->confidence > 0);
        CHECK(!o->has_orientation);
        if (o->kind == FL_LM_NET) {
            n_net++;
            CHECK_EQ(o->color, FL_COLOR_YELLOW);
        } else {
            CHECK_EQ(o->color, FL_COLOR_NONE);
        }
        if (o->kind == FL_LM_CORNER_C) {
            const double a = fl_angle_to_mdeg(o->bearing) * M_PI / 180000.0;
            const double d = hypot(o->range_mm * cos(a) - rx, o->range_mm * sin(a) - ry);
            n_c++;
            if (d < best) {
                best = d;
                best_b = fabs(fl_angle_to_mdeg(o->bearing) / 1000.0 - atan2(ry, rx) * 180 / M_PI);
                c_ok = abs((int)o->range_mm - (int)lround(hypot(rx, ry)));
            }
        }
    }
    t_info("t_box: %d obs, %d C, %d net; the box corner at %.0f mm: C %.0f mm off, range error %d "
           "mm, bearing error %.1f deg", n, n_c, n_net, hypot(rx, ry), best, c_ok, best_b);
    CHECK(n_c >= 1);
    CHECK_EQ(n_net, 1);
    /* measured: 3 mm off (range error 0 mm, bearing 0.4 deg) at 0.49 m;
     * bounds a line width (25 mm) and 2 degrees */
    CHECK_LE(best, 25);
    CHECK_LE(c_ok, 25);
    CHECK_LE(best_b, 2);
    /* a full list: the rest counted */
    obs.n = FL_OBS_MAX - 1;
    obs.dropped = 0;
    CHECK_EQ(fl_corners_obs(&S->cn, &obs), 1);
    CHECK_EQ(obs.n, FL_OBS_MAX);
    CHECK_EQ(obs.dropped, n - 1);
    CHECK_EQ(fl_corners_obs(NULL, &obs), 0);
    CHECK_EQ(fl_corners_obs(&S->cn, NULL), 0);
    CHECK_EQ(fl_corners_obs(&blank, &obs), 0);
}

/* eval-detect's corner score (tools/eval/eval_corners.c) on the aibo2004
 * fixtures alone (no random frames): every aibo2004 fixture scored, the
 * counts consistent, the goal-box C of aibo2004_t_box among the found. */
static void test_eval(void)
{
    det_ctx_t dc;
    evc_stats_t cs;
    CHECK(ct_init());
    memset(&cs, 0, sizeof cs);
    CHECK_EQ(det_ctx_init(&dc), 0);
    CHECK_EQ(evd_corners(&dc, "fixtures", 0, &S->cn, &cs), 8);
    det_ctx_free(&dc);
    t_info("aibo2004 fixtures: %d frames, found %d of %d, %d of %d detections right", cs.frames,
           cs.found, cs.truth, cs.correct, cs.det);
    CHECK_EQ(cs.fixtures, 8);
    CHECK(cs.truth >= 1 && cs.found >= 1);
    CHECK_LE(cs.found, cs.truth);
    CHECK_LE(cs.correct, cs.det);
    CHECK_LE(cs.err_sum, 300.0 * cs.found);
}

/* Random AIBO poses 0.4..2.6 m from one of seed 004's feature points,
 * facing it (+-20 deg), the head pitched to bring it into view; every
 * third frame YUYV, planar or RGB. */
static void test_rendered(void)
{
    const fl_field_t *field = fl_field_find("aibo2004");
    const fl_camera_model_t *m = fl_camera_model_find("aibo-ers7");
    const int frames = t_quick ? 12 : 36;
    ct_score_t s;
    t_rng_t rng;
    int n = 0, tries = 0;
    CHECK(ct_init());
    CHECK(field != NULL && m != NULL);
    if (!field || !m)
        return;
    memset(&s, 0, sizeof s);
    t_rng_seed(&rng, 4004);
    while (n < frames && tries++ < 20 * frames) {
        const ct_truth_t *t = &CT_TRUTH[t_rng_u32(&rng) % CT_NTRUTH];
        const double dist = 400 + t_rng_u32(&rng) % 2200;
        const double ang = (t_rng_u32(&rng) % 3600) * M_PI / 1800;
        const double rx = t->x + dist * cos(ang), ry = t->y + dist * sin(ang);
        render_scene_t sc;
        render_frame_t fr;
        fl_camera_t cam;
        double head, u, v;
        if (fabs(rx) > 2050 || fabs(ry) > 1300)
            continue;
        render_scene_default(&sc, field, m);
        sc.robot_x_mm = (int32_t)rx;
        sc.robot_y_mm = (int32_t)ry;
        head = atan2(t->y - ry, t->x - rx) + ((int32_t)(t_rng_u32(&rng) % 41) - 20) * M_PI / 180;
        sc.robot_heading = fl_angle_from_mdeg((int32_t)(head * 180000 / M_PI));
        sc.head.head_pitch = fl_angle_from_mdeg((int32_t)(atan2(200, dist) * 180000 / M_PI) - 5000 +
                                                (int32_t)(t_rng_u32(&rng) % 10000));
        sc.seed = (uint32_t)n + 1;
        sc.format = (n % 3) == 0 ? FL_FMT_YUYV422 : (n % 3) == 1 ? FL_FMT_RGB888 : FL_FMT_YCBCR_PLANAR;
        if (!render_project_field(&sc, t->x, t->y, 0, &u, &v, NULL) || u < 8 || v < 8 || u > CW - 9 ||
            v > CH - 9)
            continue;
        if (render_frame(&sc, &fr) != 0 || render_scene_camera(&sc, &cam) != FL_OK) {
            CHECK(0);
            continue;
        }
        CHECK_EQ(ct_frame(&fr, &cam, field), FL_OK);
        ct_score(&sc, &s);
        if (getenv("CORNERS_VERBOSE")) {
            char path[64];
            t_info("frame %d: robot %d %d heading %d, target %s (%.0f, %.0f) at %.0f mm, px %.1f %.1f", n,
                   (int)sc.robot_x_mm, (int)sc.robot_y_mm, (int)(fl_angle_to_mdeg(sc.robot_heading) / 1000),
                   ct_type_name(t->type), t->x, t->y, dist, u, v);
            ct_dump("  frame");
            snprintf(path, sizeof path, "/tmp/hc/r%02d.ppm", n);
            render_write_frame(path, &fr);
        }
        render_frame_free(&fr);
        n++;
    }
    CHECK_EQ(n, frames);
    ct_print("rendered aibo2004", &s);
    CHECK(s.truth >= frames);
    /* floors under the measured values (36 frames: recall 25/64 = 0.39,
     * precision 28/39 = 0.72; --quick, 12 frames: 7/22 = 0.32, 8/9 =
     * 0.89; label_mode 3 and the net's foot, corners.h), still under issue
     * 21's targets (0.8, 0.9): see docs/DESIGN.md 14c */
    CHECK(s.found * 100 >= 30 * s.truth);
    CHECK(s.correct * 100 >= 62 * s.det);
    CHECK_LE(s.err_max, 300);
}

void suite_corners(void)
{
    t_run("corners.params", test_params);
    t_run("corners.bad_input", test_bad_input);
    t_run("corners.detector", test_detector);
    t_run("corners.labels", test_labels);
    t_run("corners.fixtures", test_fixtures);
    t_run("corners.obs", test_obs);
    t_run("corners.eval", test_eval);
    t_run("corners.rendered", test_rendered);
    free(S);
    S = NULL;
}
