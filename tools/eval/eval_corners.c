/*
 * tools/eval/eval_corners.c - seed 004's corner features (corners.h)
 * scored against the map (`fieldloc eval-detect`: aibo_corners_*).
 *
 * Frames: the rendered aibo2004 fixtures of index.txt (each re-rendered
 * from its .scene, so the truth is the scene's own geometry) and
 * n_random (eval-detect: EVD_CORNERS_RANDOM, 36) random AIBO frames
 * 0.4..2.6 m from one of the map's feature points, facing it (+-20 deg), the head pitched to bring it into view
 * (seed 4004, every third frame YUYV, RGB or planar: the set
 * host_tests/test_corners.c corners.rendered scores with its own list).
 * Per frame: det_run's fl_vision_frame (its beacon stage finds the posts
 * the nets come from) and fl_corners_run with the scene's camera.
 * Truth: field->features of kinds C, T-field and T-net (aibo2004's 16:
 * the goal-box and field corners, the halfway line's T's at the border
 * and its crossings with the centre circle, the box lines on the goal
 * lines) projected with the scene's camera: in the image (8 px margin),
 * not occluded, within EVC_RANGE_MM of the robot.  A detection of a type
 * matches a truth point of the same kind within 150 mm + 10 % of its
 * range (ground points, robot frame).  Recall: visible truth points
 * matched; precision: detections (with a ground point within
 * EVC_RANGE_MM) within the tolerance of a map point of their kind.
 */
#include "eval/detect.h"
#include "world/render.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define EVC_RANGE_MM 3000.0

static int evc_kind(int cfeat)
{
    return cfeat == FL_CFEAT_C ? FL_LM_CORNER_C
           : cfeat == FL_CFEAT_T_FIELD ? FL_LM_CORNER_TFIELD
           : cfeat == FL_CFEAT_T_NET ? FL_LM_CORNER_TNET
                                     : -1;
}

static double evc_tol(double range) { return 150 + 0.1 * range; }

static void evc_score(const fl_corners_t *cn, const render_scene_t *sc, const fl_field_t *f,
                      evc_stats_t *s)
{
    int k, i;
    int used[FL_CORNERS_MAX_FEATURES];
    memset(used, 0, sizeof used);
    s->frames++;
    for (k = 0; k < f->n_features; k++) {
        const fl_landmark_t *t = &f->features[k];
        double u, v, rx, ry, range, bd = 1e9;
        int best = -1;
        if (t->kind != FL_LM_CORNER_C && t->kind != FL_LM_CORNER_TFIELD &&
            t->kind != FL_LM_CORNER_TNET)
            continue;
        if (!render_project_field(sc, t->x_mm, t->y_mm, 0, &u, &v, NULL) || u < 8 || v < 8 ||
            u > cn->width - 9 || v > cn->height - 9 || render_occluded(sc, t->x_mm, t->y_mm, 0, 30, -1))
            continue;
        render_field_to_robot(sc, t->x_mm, t->y_mm, &rx, &ry);
        range = hypot(rx, ry);
        if (range > EVC_RANGE_MM)
            continue;
        s->truth++;
        s->truth_t[(int)t->kind - (int)FL_LM_CORNER_C]++;
        for (i = 0; i < cn->n_features; i++) {
            const fl_cfeat_t *d = &cn->feature[i];
            double e;
            if (evc_kind(d->type) != (int)t->kind || !d->has_ground || used[i])
                continue;
            e = hypot(d->ground.x_mm - rx, d->ground.y_mm - ry);
            if (e < bd) {
                bd = e;
                best = i;
            }
        }
        if (best >= 0 && bd <= evc_tol(range)) {
            const int ty = (int)t->kind - (int)FL_LM_CORNER_C;
            const double re = fabs(cn->feature[best].range_mm - range);
            used[best] = 1;
            s->found++;
            s->err_sum += bd;
            s->found_t[ty]++;
            s->rng_sum_t[ty] += re;
            if (re > s->rng_max_t[ty])
                s->rng_max_t[ty] = re;
        }
    }
    for (i = 0; i < cn->n_features; i++) {
        const fl_cfeat_t *d = &cn->feature[i];
        int ok = used[i];
        if (evc_kind(d->type) < 0 || !d->has_ground || d->range_mm > EVC_RANGE_MM)
            continue;
        s->det++;
        s->det_t[evc_kind(d->type) - (int)FL_LM_CORNER_C]++;
        for (k = 0; k < f->n_features && !ok; k++) {
            double rx, ry;
            if ((int)f->features[k].kind != evc_kind(d->type))
                continue;
            render_field_to_robot(sc, f->features[k].x_mm, f->features[k].y_mm, &rx, &ry);
            ok = hypot(d->ground.x_mm - rx, d->ground.y_mm - ry) <= evc_tol(hypot(rx, ry));
        }
        s->correct += ok;
        s->correct_t[evc_kind(d->type) - (int)FL_LM_CORNER_C] += ok;
    }
}

/* One scene: render, vision, corners, score.  0, or -1 (not scored). */
static int evc_scene(det_ctx_t *ctx, fl_corners_t *cn, const render_scene_t *sc, evc_stats_t *s)
{
    render_frame_t fr;
    fl_camera_t cam;
    static fl_obs_list_t obs;
    static det_feature_t feat[DET_MAX_FEATURES];
    if (render_frame(sc, &fr) != 0)
        return -1;
    if (render_scene_camera(sc, &cam) != FL_OK) {
        render_frame_free(&fr);
        return -1;
    }
    /* det_run: the colour tables as the rest of eval-detect sets them up */
    (void)det_run(ctx, &fr.view, &cam, sc->field, &obs, feat, DET_MAX_FEATURES);
    if (fl_corners_run(cn, &fr.view, ctx->colors, &cam, &ctx->vis->beacons) == FL_OK)
        evc_score(cn, sc, sc->field, s);
    render_frame_free(&fr);
    return 0;
}

/* Tiny deterministic generator (xorshift64*), as the host tests' t_rng. */
static uint32_t evc_rand(uint64_t *x)
{
    *x ^= *x >> 12;
    *x ^= *x << 25;
    *x ^= *x >> 27;
    return (uint32_t)((*x * 2685821657736338717ull) >> 32);
}

int evd_corners(det_ctx_t *ctx, const char *dir, int n_random, fl_corners_t *cn, evc_stats_t *s)
{
    char path[1024], line[1024];
    const fl_field_t *field = fl_field_find("aibo2004");
    const fl_camera_model_t *m = fl_camera_model_find("aibo-ers7");
    fl_corners_params_t p;
    FILE *idx;
    uint64_t rng = 4004;
    int n = 0, tries = 0;
    fl_corners_params_default(&p);
    if (field == NULL || m == NULL || fl_corners_init(cn, &p) != FL_OK)
        return -1;
    snprintf(path, sizeof path, "%s/frames/index.txt", dir);
    idx = fopen(path, "r");
    if (idx != NULL) {
        while (fgets(line, sizeof line, idx)) {
            char name[256], file[256], fmt[32], fieldn[64], camn[64], err[256];
            static render_scene_t sc;
            if (line[0] == '#' || sscanf(line, "%255s %255s %31s %63s %63s", name, file, fmt,
                                         fieldn, camn) != 5 || strcmp(fieldn, "aibo2004") != 0)
                continue;
            snprintf(path, sizeof path, "%s/frames/%s.scene", dir, name);
            if (render_scene_load(path, &sc, err, sizeof err) == 0 && sc.field == field &&
                evc_scene(ctx, cn, &sc, s) == 0)
                s->fixtures++;
        }
        fclose(idx);
    }
    while (n < n_random && tries++ < 20 * n_random) {
        static render_scene_t sc;
        const fl_landmark_t *t = &field->features[evc_rand(&rng) % (uint32_t)field->n_features];
        const double dist = 400 + evc_rand(&rng) % 2200;
        const double ang = (evc_rand(&rng) % 3600) * M_PI / 1800;
        const double rx = t->x_mm + dist * cos(ang), ry = t->y_mm + dist * sin(ang);
        double head, u, v;
        if (t->kind == FL_LM_NET || fabs(rx) > 2050 || fabs(ry) > 1300)
            continue;
        render_scene_default(&sc, field, m);
        sc.robot_x_mm = (int32_t)rx;
        sc.robot_y_mm = (int32_t)ry;
        head = atan2(t->y_mm - ry, t->x_mm - rx) + ((int32_t)(evc_rand(&rng) % 41) - 20) * M_PI / 180;
        sc.robot_heading = fl_angle_from_mdeg((int32_t)(head * 180000 / M_PI));
        sc.head.head_pitch = fl_angle_from_mdeg((int32_t)(atan2(200, dist) * 180000 / M_PI) - 5000 +
                                                (int32_t)(evc_rand(&rng) % 10000));
        sc.seed = (uint32_t)n + 1;
        sc.format = (n % 3) == 0 ? FL_FMT_YUYV422 : (n % 3) == 1 ? FL_FMT_RGB888 : FL_FMT_YCBCR_PLANAR;
        if (!render_project_field(&sc, t->x_mm, t->y_mm, 0, &u, &v, NULL) || u < 8 || v < 8 ||
            u > m->width_px - 9 || v > m->height_px - 9)
            continue;
        if (evc_scene(ctx, cn, &sc, s) == 0)
            n++;
    }
    return s->frames;
}

void evd_corners_print(const evc_stats_t *s)
{
    static const char *const names[3] = {"C", "T-field", "T-net"};
    int k;
    printf("aibo2004 corner features (seed 004: C, T-field, T-net; %d fixtures + %d random "
           "frames, truth within %.0f m): %d of %d found, %d of %d detections right, ground "
           "error mean %.0f mm\n",
           s->fixtures, s->frames - s->fixtures, EVC_RANGE_MM / 1000, s->found, s->truth,
           s->correct, s->det, s->found ? s->err_sum / s->found : 0.0);
    for (k = 0; k < 3; k++)
        printf("  %-7s precision %.2f (%d of %d)  recall %.2f (%d of %d)  range error mean %.0f "
               "max %.0f mm\n",
               names[k], s->det_t[k] ? (double)s->correct_t[k] / s->det_t[k] : 0.0, s->correct_t[k],
               s->det_t[k], s->truth_t[k] ? (double)s->found_t[k] / s->truth_t[k] : 0.0,
               s->found_t[k], s->truth_t[k], s->found_t[k] ? s->rng_sum_t[k] / s->found_t[k] : 0.0,
               s->rng_max_t[k]);
    printf("aibo_corners_precision %.2f\n", s->det ? (double)s->correct / s->det : 0.0);
    printf("aibo_corners_recall %.2f\n", s->truth ? (double)s->found / s->truth : 0.0);
}
