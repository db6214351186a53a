/*
 * tools/world/truth.c - exact ground truth of a rendered frame and its text file
 * (API and file format: truth.h; the format is also in fixtures/README.md).
 *
 * Algorithm.  The renderer's world (render_int.h) is built for the scene;
 * every map landmark, centre-circle arc point (every 360/TRUTH_ARC_POINTS
 * degrees) and the ball is projected with the renderer's camera (the same
 * geometry as the pixels); a point whose pixel is inside the image is
 * listed, and flagged occluded when the segment from the camera centre to
 * it meets an object (robot, post, crossbar, ball, beacon) more than a
 * tolerance before the point (1 mm for ground points; a post's or beacon's
 * own cylinder is ignored for its foot and top, and the crossbar is within
 * the post-top tolerance of one post diameter).  The border arrays are those
 * of render_frame (or recomputed by the same per-pixel-centre trace).
 *
 * Memory: a truth_t is about 30 kB (fixed arrays); no other allocation
 * than the renderer's world.  Cost: one world build plus one ray test per
 * candidate feature (or one trace per pixel without a frame).
 */
#include "world/truth.h"
#include "world/render_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BALL_LANDMARK 100000 /* skip id of the ball primitive (see render.c) */

static const char *kind_names[TRUTH_KIND_COUNT] = {
    "L", "T", "X", "penalty-mark", "centre-mark", "post-foot", "post-top",
    "circle-centre", "circle-arc", "beacon", "ball"};

const char *truth_kind_name(truth_kind_t k)
{
    return (int)k >= 0 && k < TRUTH_KIND_COUNT ? kind_names[k] : "?";
}

int truth_kind_from_name(const char *name)
{
    int i;
    if (!name)
        return -1;
    for (i = 0; i < TRUTH_KIND_COUNT; i++)
        if (!strcmp(kind_names[i], name))
            return i;
    return -1;
}

fl_landmark_kind_t truth_landmark_kind(truth_kind_t k)
{
    switch (k) {
    case TRUTH_L: return FL_LM_L;
    case TRUTH_T: return FL_LM_T;
    case TRUTH_X: return FL_LM_X;
    case TRUTH_PENALTY_MARK: return FL_LM_PENALTY_MARK;
    case TRUTH_CENTRE_MARK: return FL_LM_CENTRE_MARK;
    case TRUTH_POST_FOOT:
    case TRUTH_POST_TOP: return FL_LM_POST;
    case TRUTH_CIRCLE_CENTRE: return FL_LM_CENTRE_CIRCLE;
    case TRUTH_BEACON: return FL_LM_BEACON;
    default: return FL_LM_KIND_COUNT;
    }
}

static void add_feature(truth_t *t, const world_t *w, truth_kind_t kind, int landmark, int index,
                        double fx, double fy, double z, double tol, int skip)
{
    const render_scene_t *sc = w->sc;
    double q[3], u, v, dist, d[3], len;
    truth_feature_t *f;
    int k;
    q[0] = fx;
    q[1] = fy;
    q[2] = z;
    if (!world_project(w, q, &u, &v, &dist))
        return;
    if (u < -0.5 || u >= w->W - 0.5 || v < -0.5 || v >= w->H - 0.5)
        return;
    if (t->n >= TRUTH_MAX_FEATURES) {
        t->dropped++;
        return;
    }
    f = &t->f[t->n++];
    memset(f, 0, sizeof *f);
    f->kind = kind;
    f->landmark = landmark;
    f->index = index;
    f->u = u;
    f->v = v;
    f->field_x_mm = fx;
    f->field_y_mm = fy;
    f->z_mm = z;
    render_field_to_robot(sc, fx, fy, &f->robot_x_mm, &f->robot_y_mm);
    f->range_mm = sqrt(f->robot_x_mm * f->robot_x_mm + f->robot_y_mm * f->robot_y_mm);
    if (landmark >= 0) {
        const fl_landmark_t *lm = &w->field->landmarks[landmark];
        if (lm->kind == FL_LM_POST) {
            f->side = lm->side;
            f->goal = lm->goal;
        }
    }
    for (k = 0; k < 3; k++)
        d[k] = q[k] - w->P[k];
    len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    f->occluded = len > tol && world_hit_objects(w, w->P, d, 1e-9, (len - tol) / len, skip, NULL) >= 0;
}

int truth_compute(const render_scene_t *sc, const render_frame_t *frame, truth_t *t)
{
    world_t w;
    const fl_field_t *fd;
    int i, u, v;
    if (!t)
        return -1;
    memset(t, 0, sizeof *t);
    if (world_build(&w, sc) != 0)
        return -1;
    if (w.W > TRUTH_MAX_WIDTH) {
        world_free(&w);
        return -1;
    }
    fd = w.field;
    snprintf(t->field, sizeof t->field, "%s", fd->name);
    snprintf(t->camera, sizeof t->camera, "%s", sc->camera->name);
    t->width = w.W;
    t->height = w.H;
    t->robot_x_mm = sc->robot_x_mm;
    t->robot_y_mm = sc->robot_y_mm;
    t->robot_heading = sc->robot_heading;
    t->head = sc->head;
    t->cam_x_mm = w.cam_r[0];
    t->cam_y_mm = w.cam_r[1];
    t->cam_z_mm = w.cam_r[2];
    t->horizon_v = w.horizon_v;

    if (frame && frame->border_v && frame->width == w.W && frame->height == w.H) {
        memcpy(t->border_v, frame->border_v, (size_t)w.W * sizeof(int16_t));
        memcpy(t->border_end_v, frame->border_end_v, (size_t)w.W * sizeof(int16_t));
        memcpy(t->border_visible_v, frame->border_visible_v, (size_t)w.W * sizeof(int16_t));
    } else {
        for (u = 0; u < w.W; u++) {
            int first = w.H, end = w.H, vis = w.H;
            for (v = 0; v < w.H; v++) {
                sample_t s;
                world_trace(&w, u, v, &s);
                if (s.carpet) {
                    if (first == w.H)
                        first = v;
                    end = v + 1;
                }
                if (vis == w.H && (s.cls == RENDER_CLASS_GREEN || s.cls == RENDER_CLASS_LINE))
                    vis = v;
            }
            t->border_v[u] = (int16_t)first;
            t->border_end_v[u] = (int16_t)end;
            t->border_visible_v[u] = (int16_t)vis;
        }
    }

    for (i = 0; i < fd->n_landmarks; i++) {
        const fl_landmark_t *lm = &fd->landmarks[i];
        switch (lm->kind) {
        case FL_LM_L: add_feature(t, &w, TRUTH_L, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, -1); break;
        case FL_LM_T: add_feature(t, &w, TRUTH_T, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, -1); break;
        case FL_LM_X: add_feature(t, &w, TRUTH_X, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, -1); break;
        case FL_LM_PENALTY_MARK:
            add_feature(t, &w, TRUTH_PENALTY_MARK, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, -1);
            break;
        case FL_LM_CENTRE_MARK:
            add_feature(t, &w, TRUTH_CENTRE_MARK, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, -1);
            break;
        case FL_LM_CENTRE_CIRCLE:
            add_feature(t, &w, TRUTH_CIRCLE_CENTRE, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, -1);
            break;
        case FL_LM_POST:
            add_feature(t, &w, TRUTH_POST_FOOT, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, i);
            add_feature(t, &w, TRUTH_POST_TOP, i, 0, lm->x_mm, lm->y_mm, fd->post_height_mm,
                        fd->post_diameter_mm, i);
            break;
        case FL_LM_BEACON:
            add_feature(t, &w, TRUTH_BEACON, i, 0, lm->x_mm, lm->y_mm, 0, 1.0, i);
            break;
        default:
            break;
        }
    }
    if (fd->circle_radius_mm > 0) {
        for (i = 0; i < TRUTH_ARC_POINTS; i++) {
            fl_angle_t a = fl_angle_from_mdeg((int32_t)(i * (360000 / TRUTH_ARC_POINTS)));
            add_feature(t, &w, TRUTH_CIRCLE_ARC, -1, i, fd->circle_radius_mm * rcos(a),
                        fd->circle_radius_mm * rsin(a), 0, 1.0, -1);
        }
    }
    if (sc->ball) {
        /* pictured point: the ball centre; ground point below it */
        int pi;
        double r = 0;
        for (pi = 0; pi < w.np; pi++)
            if (w.prims[pi].cls == RENDER_CLASS_BALL)
                r = w.prims[pi].h[0];
        add_feature(t, &w, TRUTH_BALL, -1, 0, sc->ball_x_mm, sc->ball_y_mm, r, r, BALL_LANDMARK);
    }
    world_free(&w);
    return 0;
}

/* ---- text form -------------------------------------------------------------------------- */

static void write_row(FILE *f, const char *key, const int16_t *a, int n)
{
    int i;
    fputs(key, f);
    for (i = 0; i < n; i++)
        fprintf(f, " %d", (int)a[i]);
    fputc('\n', f);
}

int truth_write(FILE *f, const truth_t *t)
{
    int i;
    if (!f || !t)
        return -1;
    fprintf(f, "fieldloc-truth 1\n");
    fprintf(f, "field %s\n", t->field);
    fprintf(f, "camera %s %d %d\n", t->camera, t->width, t->height);
    fprintf(f, "robot %d %d %d\n", (int)t->robot_x_mm, (int)t->robot_y_mm, (int)t->robot_heading);
    fprintf(f, "head %d %d %d %d\n", (int)t->head.neck_height_mm, (int)t->head.head_pitch,
            (int)t->head.head_yaw, (int)t->head.pitch_offset);
    if (t->head.torso_pitch != 0 || t->head.torso_roll != 0 || t->head.roll_offset != 0)
        fprintf(f, "tilt %d %d %d\n", (int)t->head.torso_pitch, (int)t->head.torso_roll,
                (int)t->head.roll_offset);
    fprintf(f, "camera_centre %.3f %.3f %.3f\n", t->cam_x_mm, t->cam_y_mm, t->cam_z_mm);
    fprintf(f, "horizon %.3f\n", t->horizon_v);
    write_row(f, "border", t->border_v, t->width);
    write_row(f, "border_end", t->border_end_v, t->width);
    write_row(f, "border_visible", t->border_visible_v, t->width);
    fprintf(f, "# feature KIND LANDMARK INDEX U V RX RY FX FY Z RANGE SIDE GOAL OCCLUDED\n");
    for (i = 0; i < t->n; i++) {
        const truth_feature_t *ft = &t->f[i];
        fprintf(f, "feature %s %d %d %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %d %d %d\n",
                truth_kind_name(ft->kind), ft->landmark, ft->index, ft->u, ft->v, ft->robot_x_mm,
                ft->robot_y_mm, ft->field_x_mm, ft->field_y_mm, ft->z_mm, ft->range_mm, (int)ft->side,
                ft->goal, ft->occluded);
    }
    if (t->dropped)
        fprintf(f, "dropped %d\n", t->dropped);
    return ferror(f) ? -1 : 0;
}

static int read_row(const char *s, int16_t *a, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        char *end;
        long x = strtol(s, &end, 10);
        if (end == s || x < -32768 || x > 32767)
            return -1;
        a[i] = (int16_t)x;
        s = end;
    }
    return 0;
}

int truth_read(FILE *f, truth_t *t, char *err, int err_len)
{
    char *line;
    size_t cap = 16384;
    int lineno = 0, magic = 0;
    if (!f || !t)
        return -1;
    memset(t, 0, sizeof *t);
    line = (char *)malloc(cap);
    if (!line)
        return -1;
#define TBAD(msg)                                                                   \
    do {                                                                            \
        if (err) snprintf(err, (size_t)err_len, "truth line %d: %s", lineno, msg); \
        free(line);                                                                 \
        return -1;                                                                  \
    } while (0)
    while (fgets(line, (int)cap, f)) {
        char key[32], *rest;
        long a[4];
        lineno++;
        if (!strchr(line, '\n') && !feof(f))
            TBAD("line too long");
        if (line[0] == '#' || sscanf(line, "%31s", key) != 1)
            continue;
        rest = strstr(line, key) + strlen(key);
        if (!magic) {
            if (strcmp(key, "fieldloc-truth") || sscanf(rest, "%ld", &a[0]) != 1 || a[0] != 1)
                TBAD("expected 'fieldloc-truth 1'");
            magic = 1;
        } else if (!strcmp(key, "field")) {
            if (sscanf(rest, "%31s", t->field) != 1)
                TBAD("field NAME");
        } else if (!strcmp(key, "camera")) {
            if (sscanf(rest, "%31s %d %d", t->camera, &t->width, &t->height) != 3 || t->width <= 0 ||
                t->width > TRUTH_MAX_WIDTH || t->height <= 0)
                TBAD("camera NAME W H");
        } else if (!strcmp(key, "robot")) {
            if (sscanf(rest, "%ld %ld %ld", &a[0], &a[1], &a[2]) != 3 || a[2] < -32768 || a[2] > 32767)
                TBAD("robot X Y HEADING");
            t->robot_x_mm = (int32_t)a[0];
            t->robot_y_mm = (int32_t)a[1];
            t->robot_heading = (fl_angle_t)a[2];
        } else if (!strcmp(key, "head")) {
            if (sscanf(rest, "%ld %ld %ld %ld", &a[0], &a[1], &a[2], &a[3]) != 4)
                TBAD("head NECK PITCH YAW OFFSET");
            t->head.neck_height_mm = (int32_t)a[0];
            t->head.head_pitch = (fl_angle_t)a[1];
            t->head.head_yaw = (fl_angle_t)a[2];
            t->head.pitch_offset = (fl_angle_t)a[3];
        } else if (!strcmp(key, "tilt")) {
            if (sscanf(rest, "%ld %ld %ld", &a[0], &a[1], &a[2]) != 3)
                TBAD("tilt TORSO_PITCH TORSO_ROLL ROLL_OFFSET");
            t->head.torso_pitch = (fl_angle_t)a[0];
            t->head.torso_roll = (fl_angle_t)a[1];
            t->head.roll_offset = (fl_angle_t)a[2];
        } else if (!strcmp(key, "camera_centre")) {
            if (sscanf(rest, "%lf %lf %lf", &t->cam_x_mm, &t->cam_y_mm, &t->cam_z_mm) != 3)
                TBAD("camera_centre X Y Z");
        } else if (!strcmp(key, "horizon")) {
            if (sscanf(rest, "%lf", &t->horizon_v) != 1)
                TBAD("horizon V");
        } else if (!strcmp(key, "border") || !strcmp(key, "border_end") || !strcmp(key, "border_visible")) {
            int16_t *row = !strcmp(key, "border") ? t->border_v
                           : !strcmp(key, "border_end") ? t->border_end_v : t->border_visible_v;
            if (t->width <= 0 || read_row(rest, row, t->width) != 0)
                TBAD("border row: camera line first, then WIDTH numbers");
        } else if (!strcmp(key, "feature")) {
            truth_feature_t *ft;
            char kname[32];
            int side, k;
            if (t->n >= TRUTH_MAX_FEATURES)
                TBAD("too many features");
            ft = &t->f[t->n];
            memset(ft, 0, sizeof *ft);
            if (sscanf(rest, "%31s %d %d %lf %lf %lf %lf %lf %lf %lf %lf %d %d %d", kname, &ft->landmark,
                       &ft->index, &ft->u, &ft->v, &ft->robot_x_mm, &ft->robot_y_mm, &ft->field_x_mm,
                       &ft->field_y_mm, &ft->z_mm, &ft->range_mm, &side, &ft->goal, &ft->occluded) != 14)
                TBAD("feature: 14 fields");
            k = truth_kind_from_name(kname);
            if (k < 0 || side < 0 || side > 2)
                TBAD("feature: unknown kind or side");
            ft->kind = (truth_kind_t)k;
            ft->side = (fl_side_t)side;
            t->n++;
        } else if (!strcmp(key, "dropped")) {
            if (sscanf(rest, "%d", &t->dropped) != 1)
                TBAD("dropped N");
        } else {
            TBAD("unknown key");
        }
    }
#undef TBAD
    free(line);
    if (!magic || t->width <= 0) {
        if (err) snprintf(err, (size_t)err_len, "truth: missing header or camera line");
        return -1;
    }
    return 0;
}

int truth_save(const char *path, const truth_t *t)
{
    FILE *f = fopen(path, "w");
    int r;
    if (!f)
        return -1;
    r = truth_write(f, t);
    if (fclose(f) != 0)
        r = -1;
    return r;
}

int truth_load(const char *path, truth_t *t, char *err, int err_len)
{
    FILE *f = fopen(path, "r");
    int r;
    if (!f) {
        if (err) snprintf(err, (size_t)err_len, "%s: cannot open", path);
        return -1;
    }
    r = truth_read(f, t, err, err_len);
    fclose(f);
    return r;
}
