/*
 * tools/world/coach_scene.h - the coach's view (seed 003, section 3.1): a
 * robot standing still beside the field whose top camera sees the field in
 * perspective, the render scene of that view, the pixel truth of seed 003's
 * 17 homography points in it, and the text form of a points file (what
 * `fieldloc coach --points` reads).  Host only (double).
 *
 * The default coach: "nao6-top-640" (640 x 480) on a robot standing at
 * x = 0, y = -6000 mm (3 m beyond the -y touchline of a 6 m wide field),
 * heading +90 deg (facing +y, across the field), neck at the camera
 * model's default standing height (445 mm), level head yaw, and the head
 * pitch COACH_HEAD_PITCH_MDEG.  The pitch is the largest whole degree at
 * which the far touchline, corner to corner, is inside the image with at
 * least COACH_EDGE_MARGIN_PX to spare: the far corners are the limit (at
 * 20 deg they sit about 3 px inside the left and right edges and the
 * touchline about 44 px below the top; at 21 deg the margin is under
 * 1 px; at 23.5 deg, where the touchline itself reaches the top row, the
 * corners are 4 px outside and only the three collinear points on the
 * halfway line remain).  Measured by the suite coach_scene, which also
 * moves the coach (same rule for the pitch): 1, 2 and 2.5 m beyond the
 * touchline no pitch keeps both far corners in view and the coach sees
 * only the three collinear points of the halfway line (no fit); 3 m: 20
 * deg, 5 points; 3.5 m: 23 deg, 7; 4 m: 23 deg, 9.
 * The room side behind the coach (-y) has no clutter (clear_sides), so
 * nothing of the room stands between the coach and the field.
 */
#ifndef FL_TOOLS_COACH_SCENE_H
#define FL_TOOLS_COACH_SCENE_H

#include "fieldloc/homography.h"
#include "world/render.h"

#include <stdint.h>
#include <stdio.h>

#define COACH_CAMERA "nao6-top-640"
#define COACH_X_MM 0
#define COACH_Y_MM (-6000)
#define COACH_HEADING_MDEG 90000
#define COACH_HEAD_PITCH_MDEG 20000
#define COACH_EDGE_MARGIN_PX 2
/* the -y room side (render_scene_t.clear_sides) */
#define COACH_CLEAR_SIDES 8

/* Default coach scene on `field` (seed 003's is "spl2016"): render_scene_default
 * of the coach camera, the pose above, no robots, no ball (add the players
 * to sc->robots).  NULL field is allowed (render_frame rejects it). */
void coach_scene_default(render_scene_t *sc, const fl_field_t *field);

/*
 * The pixel positions in sc's view of those of the field's homography
 * points (fl_homog_field_points) that project inside the image (pixel
 * centres 0..W-1, 0..H-1) and that no object (robot, post, ball) hides.
 * noise_px > 0 adds uniform noise in [-noise_px, +noise_px] to u and v
 * (deterministic from seed).  Pixels in Q4 (rounded), field points in mm.
 * names (may be NULL) receives the point names (static strings).  Returns
 * the number written (at most cap), -1 on bad input.
 */
int coach_scene_points(const render_scene_t *sc, double noise_px, uint32_t seed,
                       fl_homog_pair_t *pairs, const char **names, int cap);

/*
 * Points files: text, '#' starts a comment, one point per line, either
 *     NAME U V            a named field point (fl_homog_field_points of the
 *                         field, e.g. "corner_pos_left") at pixel (U, V)
 *     U V X_MM Y_MM       pixel (U, V) shows field point (X_MM, Y_MM)
 * U and V are pixels (decimals allowed, pixel-centre convention: the top
 * left pixel's centre is 0 0), stored in Q4 (1/16 px, rounded).
 * read: 0 and *n on success; -1 with "LINE N: what" (or the file problem)
 * in err.  names (may be NULL) gets each point's name or NULL.
 */
#define COACH_POINTS_MAX 64
int coach_points_read(FILE *f, const fl_field_t *field, fl_homog_pair_t *pairs,
                      const char **names, int cap, int *n, char *err, int err_len);
int coach_points_load(const char *path, const fl_field_t *field, fl_homog_pair_t *pairs,
                      const char **names, int cap, int *n, char *err, int err_len);
/* Writes "NAME U V" for a pair with a name, "U V X_MM Y_MM" otherwise
 * (names may be NULL); U and V exactly (Q4 has four decimals). 0 on success. */
int coach_points_write(FILE *f, const fl_homog_pair_t *pairs, const char **names, int n);

/* The committed coach fixtures (fixtures/coach/, written by `make
 * fixtures`): scene 0 "coach_empty" (the default coach on spl2016, nobody
 * on the field), 1 "coach_two" (red robot A 4.6 m from the coach at
 * (-1500, -1700), blue robot B 8 m away at (1800, 1500), another noise
 * seed); coach_write_fixtures writes DIR/NAME.{ppm,scene} of both and
 * DIR/coach.points (the empty view's exact points).  0 on success. */
int coach_fixture_scene(int which, render_scene_t *sc);
int coach_write_fixtures(const char *dir);

#endif /* FL_TOOLS_COACH_SCENE_H */
