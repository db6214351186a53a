/*
 * tools/world/coach_scene.c - the coach's render scene, its point truth and
 * points files (coach_scene.h).
 */
#include "world/coach_scene.h"

#include "fieldloc/fixed.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void coach_scene_default(render_scene_t *sc, const fl_field_t *field)
{
    if (!sc)
        return;
    render_scene_default(sc, field, fl_camera_model_find(COACH_CAMERA));
    sc->robot_x_mm = COACH_X_MM;
    sc->robot_y_mm = COACH_Y_MM;
    sc->robot_heading = fl_angle_from_mdeg(COACH_HEADING_MDEG);
    sc->head.head_pitch = fl_angle_from_mdeg(COACH_HEAD_PITCH_MDEG);
    sc->clear_sides = COACH_CLEAR_SIDES;
}

/* splitmix64: the pixel noise of the point truth (own generator, so that
 * the points do not depend on the renderer's draws) */
static uint64_t mix64(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double unit_pm1(uint64_t *s)
{
    return (double)(mix64(s) >> 11) / 4503599627370496.0 - 1.0; /* [-1, 1) */
}

int coach_scene_points(const render_scene_t *sc, double noise_px, uint32_t seed,
                       fl_homog_pair_t *pairs, const char **names, int cap)
{
    fl_homog_field_point_t pts[FL_HOMOG_FIELD_POINTS];
    size_t np, i;
    int n = 0;
    uint64_t rs = ((uint64_t)seed << 1) | 1u;
    if (!sc || !sc->field || !sc->camera || !pairs || cap < 0)
        return -1;
    np = fl_homog_field_points(sc->field, pts, FL_HOMOG_FIELD_POINTS);
    for (i = 0; i < np && n < cap; i++) {
        double u, v, du = 0, dv = 0;
        if (!render_project_field(sc, pts[i].x_mm, pts[i].y_mm, 0.0, &u, &v, NULL))
            continue;
        if (u < 0.0 || v < 0.0 || u > sc->camera->width_px - 1 || v > sc->camera->height_px - 1)
            continue;
        /* a painted point on the carpet: blocked by anything nearer than it */
        if (render_occluded(sc, pts[i].x_mm, pts[i].y_mm, 0.0, 1.0, -1))
            continue;
        if (noise_px > 0.0) {
            du = noise_px * unit_pm1(&rs);
            dv = noise_px * unit_pm1(&rs);
        }
        pairs[n].u_q4 = (int32_t)floor((u + du) * 16.0 + 0.5);
        pairs[n].v_q4 = (int32_t)floor((v + dv) * 16.0 + 0.5);
        pairs[n].x_mm = pts[i].x_mm;
        pairs[n].y_mm = pts[i].y_mm;
        if (names)
            names[n] = pts[i].name;
        n++;
    }
    return n;
}

/* ---- points files ------------------------------------------------------------- */

/* A pixel coordinate: a finite decimal within the homography's range. */
static int parse_px(const char *s, int32_t *q4)
{
    char *end;
    double d = strtod(s, &end);
    if (end == s || *end != 0 || !(d == d) || fabs(d) * 16.0 > (double)FL_HOMOG_MAX_Q4)
        return 0;
    *q4 = (int32_t)floor(d * 16.0 + 0.5);
    return 1;
}

static int parse_mm(const char *s, int32_t *mm)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end != 0 || v > FL_HOMOG_MAX_MM || v < -FL_HOMOG_MAX_MM)
        return 0;
    *mm = (int32_t)v;
    return 1;
}

int coach_points_read(FILE *f, const fl_field_t *field, fl_homog_pair_t *pairs,
                      const char **names, int cap, int *n, char *err, int err_len)
{
    fl_homog_field_point_t pts[FL_HOMOG_FIELD_POINTS];
    size_t np = 0;
    char line[512];
    int lineno = 0, k = 0;
    if (n)
        *n = 0;
    if (!f || !pairs || !n || cap < 0) {
        if (err) snprintf(err, (size_t)err_len, "points: bad arguments");
        return -1;
    }
    if (field)
        np = fl_homog_field_points(field, pts, FL_HOMOG_FIELD_POINTS);
    while (fgets(line, sizeof line, f)) {
        char tok[5][64];
        char *hash = strchr(line, '#');
        int nt;
        lineno++;
#define BAD(...)                                                                      \
    do {                                                                              \
        if (err) {                                                                    \
            int o_ = snprintf(err, (size_t)err_len, "points line %d: ", lineno);     \
            if (o_ >= 0 && o_ < err_len) snprintf(err + o_, (size_t)(err_len - o_), __VA_ARGS__); \
        }                                                                             \
        return -1;                                                                    \
    } while (0)
        if (!strchr(line, '\n') && !feof(f))
            BAD("line too long");
        if (hash)
            *hash = 0;
        nt = sscanf(line, "%63s %63s %63s %63s %63s", tok[0], tok[1], tok[2], tok[3], tok[4]);
        if (nt <= 0)
            continue;
        if (k >= cap)
            BAD("more than %d points", cap);
        if (nt == 3 && (isalpha((unsigned char)tok[0][0]) || tok[0][0] == '_')) {
            size_t i;
            for (i = 0; i < np; i++)
                if (!strcmp(pts[i].name, tok[0]))
                    break;
            if (i == np)
                BAD("unknown point name '%s' (field %s)", tok[0], field ? field->name : "none");
            if (!parse_px(tok[1], &pairs[k].u_q4) || !parse_px(tok[2], &pairs[k].v_q4))
                BAD("expected NAME U V with U, V pixels");
            pairs[k].x_mm = pts[i].x_mm;
            pairs[k].y_mm = pts[i].y_mm;
            if (names)
                names[k] = pts[i].name;
        } else if (nt == 4) {
            if (!parse_px(tok[0], &pairs[k].u_q4) || !parse_px(tok[1], &pairs[k].v_q4) ||
                !parse_mm(tok[2], &pairs[k].x_mm) || !parse_mm(tok[3], &pairs[k].y_mm))
                BAD("expected U V X_MM Y_MM (pixels, integer mm)");
            if (names)
                names[k] = NULL;
        } else {
            BAD("expected 'NAME U V' or 'U V X_MM Y_MM'");
        }
#undef BAD
        k++;
    }
    if (ferror(f)) {
        if (err) snprintf(err, (size_t)err_len, "points: read error");
        return -1;
    }
    *n = k;
    return 0;
}

int coach_points_load(const char *path, const fl_field_t *field, fl_homog_pair_t *pairs,
                      const char **names, int cap, int *n, char *err, int err_len)
{
    FILE *f;
    int r;
    if (n)
        *n = 0;
    if (!path || !(f = fopen(path, "r"))) {
        if (err) snprintf(err, (size_t)err_len, "%s: cannot open", path ? path : "(null)");
        return -1;
    }
    r = coach_points_read(f, field, pairs, names, cap, n, err, err_len);
    fclose(f);
    if (r != 0 && err) {
        /* name the file in front of the line number */
        char tmp[256];
        snprintf(tmp, sizeof tmp, "%s", err);
        snprintf(err, (size_t)err_len, "%s: %s", path, tmp);
    }
    return r;
}

int coach_points_write(FILE *f, const fl_homog_pair_t *pairs, const char **names, int n)
{
    int i;
    if (!f || (!pairs && n > 0))
        return -1;
    fprintf(f, "# fieldloc coach points: NAME U V or U V X_MM Y_MM (pixels, pixel centres)\n");
    for (i = 0; i < n; i++) {
        if (names && names[i])
            fprintf(f, "%s %.4f %.4f\n", names[i], pairs[i].u_q4 / 16.0, pairs[i].v_q4 / 16.0);
        else
            fprintf(f, "%.4f %.4f %d %d\n", pairs[i].u_q4 / 16.0, pairs[i].v_q4 / 16.0,
                    (int)pairs[i].x_mm, (int)pairs[i].y_mm);
    }
    return ferror(f) ? -1 : 0;
}

/* ---- the committed coach fixtures ---------------------------------------------- */

int coach_fixture_scene(int which, render_scene_t *sc)
{
    coach_scene_default(sc, fl_field_find("spl2016"));
    if (which == 0) /* the empty field, per-frame noise of its own */
        return 0;
    if (which != 1)
        return -1;
    sc->seed = 2;
    /* robot A 4.6 m from the coach (red), robot B 8 m away (blue) */
    sc->n_robots = 2;
    sc->robots[0].x_mm = -1500;
    sc->robots[0].y_mm = -1700;
    sc->robots[0].heading = fl_angle_from_mdeg(30000);
    sc->robots[0].jersey = RENDER_JERSEY_RED;
    sc->robots[1].x_mm = 1800;
    sc->robots[1].y_mm = 1500;
    sc->robots[1].heading = fl_angle_from_mdeg(-150000);
    sc->robots[1].jersey = RENDER_JERSEY_BLUE;
    return 0;
}

int coach_write_fixtures(const char *dir)
{
    static const char *const names[2] = {"coach_empty", "coach_two"};
    fl_homog_pair_t pairs[FL_HOMOG_FIELD_POINTS];
    const char *pnames[FL_HOMOG_FIELD_POINTS];
    char path[1024];
    int i, n, bad = 0;
    FILE *f;
    if (!dir)
        return -1;
    for (i = 0; i < 2; i++) {
        render_scene_t sc;
        render_frame_t fr;
        coach_fixture_scene(i, &sc);
        if (render_frame(&sc, &fr) != 0)
            return -1;
        snprintf(path, sizeof path, "%s/%s.ppm", dir, names[i]);
        bad |= render_write_frame(path, &fr) != 0;
        render_frame_free(&fr);
        snprintf(path, sizeof path, "%s/%s.scene", dir, names[i]);
        bad |= render_scene_save(path, &sc) != 0;
        if (i == 0) {
            n = coach_scene_points(&sc, 0.0, 0, pairs, pnames, FL_HOMOG_FIELD_POINTS);
            snprintf(path, sizeof path, "%s/coach.points", dir);
            if (n < 0 || (f = fopen(path, "w")) == NULL)
                return -1;
            fprintf(f, "# the coach's view of seed 003's points (coach_empty.scene), exact pixels\n");
            bad |= coach_points_write(f, pairs, pnames, n) != 0;
            bad |= fclose(f) != 0;
        }
    }
    return bad ? -1 : 0;
}
