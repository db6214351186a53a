/*
 * tools/world/render_scene.c - the text form of a render_scene_t (render.h), so
 * that every fixture can be re-rendered from its description.
 *
 * Format (one "key values" line each, '#' starts a comment; all values are
 * integers, angles are binary angles, 65536 per turn):
 *   fieldloc-scene 1
 *   field NAME                  fl_field_find name
 *   camera NAME                 fl_camera_model_find name
 *   format rgb|yuyv|planar
 *   robot X_MM Y_MM HEADING     robot pose, field frame
 *   head NECK_MM PITCH YAW PITCH_OFFSET
 *   tilt TORSO_PITCH TORSO_ROLL ROLL_OFFSET   camera.h's IMU angles and
 *                               roll offset (written only when not all 0)
 *   seed N                      per-frame noise
 *   world_seed N                room clutter, carpet texture, shadows
 *   background 0|1
 *   clear_sides MASK            room sides without clutter (written only
 *                               when not 0)
 *   ball 0|1 X_MM Y_MM
 *   light GAIN_PCT GRAD_X_PCT GRAD_Y_PCT SHADOWS
 *   noise NOISE_X10
 *   jpeg STRENGTH
 *   blur LENGTH_PX DIRECTION
 *   supersample N
 *   other X_MM Y_MM HEADING red|blue     one line per robot on the field
 * Missing keys keep render_scene_default's values (head: the camera's
 * default neck height, level head).  Unknown keys are an error.
 * Invariant: write then read gives back an identical struct (all integers).
 */
#include "world/render_int.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int render_scene_write(FILE *f, const render_scene_t *sc)
{
    int i;
    if (!f || !sc || !sc->field || !sc->camera)
        return -1;
    fprintf(f, "fieldloc-scene 1\n");
    fprintf(f, "field %s\n", sc->field->name);
    fprintf(f, "camera %s\n", sc->camera->name);
    fprintf(f, "format %s\n", render_format_name(sc->format));
    fprintf(f, "robot %d %d %d   # heading %.3f deg\n", (int)sc->robot_x_mm, (int)sc->robot_y_mm,
            (int)sc->robot_heading, fl_angle_to_mdeg(sc->robot_heading) / 1000.0);
    fprintf(f, "head %d %d %d %d   # pitch %.4f yaw %.4f offset %.4f rad\n",
            (int)sc->head.neck_height_mm, (int)sc->head.head_pitch, (int)sc->head.head_yaw,
            (int)sc->head.pitch_offset, fl_angle_to_urad(sc->head.head_pitch) / 1e6,
            fl_angle_to_urad(sc->head.head_yaw) / 1e6, fl_angle_to_urad(sc->head.pitch_offset) / 1e6);
    if (sc->head.torso_pitch != 0 || sc->head.torso_roll != 0 || sc->head.roll_offset != 0)
        fprintf(f, "tilt %d %d %d   # torso pitch %.4f roll %.4f, roll offset %.4f rad\n",
                (int)sc->head.torso_pitch, (int)sc->head.torso_roll, (int)sc->head.roll_offset,
                fl_angle_to_urad(sc->head.torso_pitch) / 1e6, fl_angle_to_urad(sc->head.torso_roll) / 1e6,
                fl_angle_to_urad(sc->head.roll_offset) / 1e6);
    fprintf(f, "seed %lu\n", (unsigned long)sc->seed);
    fprintf(f, "world_seed %lu\n", (unsigned long)sc->world_seed);
    fprintf(f, "background %d\n", sc->background);
    if (sc->clear_sides != 0)
        fprintf(f, "clear_sides %d\n", (int)sc->clear_sides);
    fprintf(f, "ball %d %d %d\n", sc->ball, (int)sc->ball_x_mm, (int)sc->ball_y_mm);
    fprintf(f, "light %d %d %d %d\n", (int)sc->gain_pct, (int)sc->grad_x_pct, (int)sc->grad_y_pct,
            (int)sc->shadows);
    fprintf(f, "noise %d\n", (int)sc->noise_x10);
    fprintf(f, "jpeg %d\n", (int)sc->jpeg);
    fprintf(f, "blur %d %d\n", (int)sc->blur_px, (int)sc->blur_dir);
    fprintf(f, "supersample %d\n", (int)sc->supersample);
    for (i = 0; i < sc->n_robots && i < RENDER_MAX_ROBOTS; i++)
        fprintf(f, "other %d %d %d %s\n", (int)sc->robots[i].x_mm, (int)sc->robots[i].y_mm,
                (int)sc->robots[i].heading, sc->robots[i].jersey == RENDER_JERSEY_BLUE ? "blue" : "red");
    return ferror(f) ? -1 : 0;
}

static int angle_ok(long a) { return a >= -32768 && a <= 32767; }

int render_scene_read(FILE *f, render_scene_t *sc, char *err, int err_len)
{
    char line[512];
    int lineno = 0, have_head = 0, have_magic = 0;
    render_scene_t s;
    if (!f || !sc)
        return -1;
    render_scene_default(&s, NULL, NULL);
    while (fgets(line, sizeof line, f)) {
        char key[32], a[64];
        long v[4];
        int n;
        char *hash = strchr(line, '#');
        lineno++;
        if (hash)
            *hash = 0;
        if (sscanf(line, "%31s", key) != 1)
            continue;
#define BAD(msg)                                                                    \
    do {                                                                            \
        if (err) snprintf(err, (size_t)err_len, "scene line %d: %s", lineno, msg); \
        return -1;                                                                  \
    } while (0)
        if (!have_magic) {
            if (strcmp(key, "fieldloc-scene") != 0 || sscanf(line, "%*s %ld", &v[0]) != 1 || v[0] != 1)
                BAD("expected 'fieldloc-scene 1'");
            have_magic = 1;
        } else if (!strcmp(key, "field")) {
            if (sscanf(line, "%*s %63s", a) != 1 || !(s.field = fl_field_find(a)))
                BAD("unknown field");
        } else if (!strcmp(key, "camera")) {
            if (sscanf(line, "%*s %63s", a) != 1 || !(s.camera = fl_camera_model_find(a)))
                BAD("unknown camera");
        } else if (!strcmp(key, "format")) {
            if (sscanf(line, "%*s %63s", a) != 1 || !render_format_from_name(a))
                BAD("unknown format");
            s.format = render_format_from_name(a);
        } else if (!strcmp(key, "robot")) {
            if (sscanf(line, "%*s %ld %ld %ld", &v[0], &v[1], &v[2]) != 3 || !angle_ok(v[2]))
                BAD("robot X Y HEADING");
            s.robot_x_mm = (int32_t)v[0];
            s.robot_y_mm = (int32_t)v[1];
            s.robot_heading = (fl_angle_t)v[2];
        } else if (!strcmp(key, "head")) {
            if (sscanf(line, "%*s %ld %ld %ld %ld", &v[0], &v[1], &v[2], &v[3]) != 4 ||
                !angle_ok(v[1]) || !angle_ok(v[2]) || !angle_ok(v[3]))
                BAD("head NECK PITCH YAW OFFSET");
            s.head.neck_height_mm = (int32_t)v[0];
            s.head.head_pitch = (fl_angle_t)v[1];
            s.head.head_yaw = (fl_angle_t)v[2];
            s.head.pitch_offset = (fl_angle_t)v[3];
            have_head = 1;
        } else if (!strcmp(key, "tilt")) {
            if (sscanf(line, "%*s %ld %ld %ld", &v[0], &v[1], &v[2]) != 3 ||
                !angle_ok(v[0]) || !angle_ok(v[1]) || !angle_ok(v[2]))
                BAD("tilt TORSO_PITCH TORSO_ROLL ROLL_OFFSET");
            s.head.torso_pitch = (fl_angle_t)v[0];
            s.head.torso_roll = (fl_angle_t)v[1];
            s.head.roll_offset = (fl_angle_t)v[2];
        } else if (!strcmp(key, "seed") || !strcmp(key, "world_seed")) {
            unsigned long u;
            if (sscanf(line, "%*s %lu", &u) != 1)
                BAD("seed N");
            if (!strcmp(key, "seed"))
                s.seed = (uint32_t)u;
            else
                s.world_seed = (uint32_t)u;
        } else if (!strcmp(key, "background")) {
            if (sscanf(line, "%*s %ld", &v[0]) != 1)
                BAD("background 0|1");
            s.background = v[0] != 0;
        } else if (!strcmp(key, "clear_sides")) {
            if (sscanf(line, "%*s %ld", &v[0]) != 1 || v[0] < 0 || v[0] > 15)
                BAD("clear_sides 0..15");
            s.clear_sides = (int32_t)v[0];
        } else if (!strcmp(key, "ball")) {
            if (sscanf(line, "%*s %ld %ld %ld", &v[0], &v[1], &v[2]) != 3)
                BAD("ball 0|1 X Y");
            s.ball = v[0] != 0;
            s.ball_x_mm = (int32_t)v[1];
            s.ball_y_mm = (int32_t)v[2];
        } else if (!strcmp(key, "light")) {
            if (sscanf(line, "%*s %ld %ld %ld %ld", &v[0], &v[1], &v[2], &v[3]) != 4)
                BAD("light GAIN GX GY SHADOWS");
            s.gain_pct = (int32_t)v[0];
            s.grad_x_pct = (int32_t)v[1];
            s.grad_y_pct = (int32_t)v[2];
            s.shadows = (int32_t)v[3];
        } else if (!strcmp(key, "noise") || !strcmp(key, "jpeg") || !strcmp(key, "supersample")) {
            if (sscanf(line, "%*s %ld", &v[0]) != 1)
                BAD("expected a number");
            if (!strcmp(key, "noise"))
                s.noise_x10 = (int32_t)v[0];
            else if (!strcmp(key, "jpeg"))
                s.jpeg = (int32_t)v[0];
            else
                s.supersample = (int32_t)v[0];
        } else if (!strcmp(key, "blur")) {
            if (sscanf(line, "%*s %ld %ld", &v[0], &v[1]) != 2 || !angle_ok(v[1]))
                BAD("blur PX DIR");
            s.blur_px = (int32_t)v[0];
            s.blur_dir = (fl_angle_t)v[1];
        } else if (!strcmp(key, "other")) {
            render_robot_t *rb;
            n = sscanf(line, "%*s %ld %ld %ld %63s", &v[0], &v[1], &v[2], a);
            if (n != 4 || !angle_ok(v[2]) || (strcmp(a, "red") && strcmp(a, "blue")))
                BAD("other X Y HEADING red|blue");
            if (s.n_robots >= RENDER_MAX_ROBOTS)
                BAD("too many robots");
            rb = &s.robots[s.n_robots++];
            rb->x_mm = (int32_t)v[0];
            rb->y_mm = (int32_t)v[1];
            rb->heading = (fl_angle_t)v[2];
            rb->jersey = strcmp(a, "blue") ? RENDER_JERSEY_RED : RENDER_JERSEY_BLUE;
        } else {
            BAD("unknown key");
        }
#undef BAD
    }
    if (!have_magic || !s.field || !s.camera) {
        if (err) snprintf(err, (size_t)err_len, "scene: needs 'fieldloc-scene 1', field and camera");
        return -1;
    }
    if (!have_head) {
        render_scene_t d;
        render_scene_default(&d, s.field, s.camera);
        s.head = d.head;
    }
    *sc = s;
    return 0;
}

int render_scene_save(const char *path, const render_scene_t *sc)
{
    FILE *f = fopen(path, "w");
    int r;
    if (!f)
        return -1;
    r = render_scene_write(f, sc);
    if (fclose(f) != 0)
        r = -1;
    return r;
}

int render_scene_load(const char *path, render_scene_t *sc, char *err, int err_len)
{
    FILE *f = fopen(path, "r");
    int r;
    if (!f) {
        if (err) snprintf(err, (size_t)err_len, "%s: cannot open", path);
        return -1;
    }
    r = render_scene_read(f, sc, err, err_len);
    fclose(f);
    return r;
}
