/*
 * tools/world/fixtures.c - the table of rendered fixtures (fixtures/frames/)
 * and render_fixture_get, which turns a row into a scene; written to disk
 * by `fieldloc fixtures` (tools/cli/cmd_fixtures.c, where the row format is
 * described) and read back by the tests.
 */
#include "world/render.h"

#include <stdio.h>
#include <string.h>

typedef struct {
    const char *name;
    const char *field, *camera, *format;
    int x_mm, y_mm, heading_mdeg;
    int pitch_urad, yaw_urad, neck_mm;
    unsigned seed;
    const char *extra;  /* more scene lines (render_scene.c keys), '\n' separated */
    const char *desc;
} fixture_t;

#define S13 "spl2013"
#define U13 "uva2013"
#define S20 "spl2020"
#define A04 "aibo2004"
#define B320 "nao4-bottom-320"
#define T320 "nao4-top-320"
#define H32 "hl3x2"
#define AC320 "acyut-320"

static const fixture_t fixtures[] = {
    /* ---- spl2013: every crossing type near and far, goals, circle ---- */
    {"spl2013_l_near", S13, B320, "rgb", 3700, 2300, 41000, 100000, 0, 450, 101, "",
     "field corner L about 1 m ahead"},
    {"spl2013_l_far", S13, T320, "yuyv", -500, -800, 37000, 50000, 0, 450, 102, "",
     "far field corner L (6 m) and the goal box"},
    {"spl2013_l_box", S13, T320, "rgb", 2500, 0, 20000, 300000, 0, 450, 103, "",
     "goal box L at 1.8 m, box T"},
    {"spl2013_t_near", S13, B320, "rgb", -300, 2300, 80000, 0, 0, 450, 104, "",
     "halfway line meets the touchline: T under 1 m"},
    {"spl2013_t_far", S13, T320, "yuyv", 0, 0, 14000, 50000, 0, 450, 105, "",
     "goal box T at 4.6 m from the centre, goal, penalty mark"},
    {"spl2013_t_box_near", S13, B320, "rgb", 3600, 600, 45000, 0, 0, 450, 106, "",
     "goal box side meets the goal line: T at 1 m, post foot"},
    {"spl2013_x_near", S13, B320, "rgb", -700, 200, 35000, 50000, 0, 450, 107, "",
     "halfway line crosses the centre circle: X under 1 m"},
    {"spl2013_x_far", S13, T320, "yuyv", -3800, -300, 8000, 50000, 0, 450, 108, "",
     "both X crossings and the circle at 4 m"},
    {"spl2013_penalty_near", S13, B320, "rgb", 1900, -200, 10000, 0, 0, 450, 109, "",
     "penalty mark at 0.8 m"},
    {"spl2013_penalty_far", S13, T320, "yuyv", -1000, 400, 0, 100000, 0, 450, 110, "",
     "penalty mark at 3.7 m, circle behind"},
    {"spl2013_centre_mark", S13, B320, "rgb", -900, -300, 15000, 0, 0, 450, 111, "",
     "centre mark and the circle at 1 m"},
    {"spl2013_circle", S13, T320, "rgb", -2300, 0, 0, 300000, 0, 450, 112, "",
     "the whole centre circle from 2.3 m"},
    {"spl2013_circle_side", S13, T320, "yuyv", 0, -1900, 90000, 250000, 0, 450, 113, "",
     "centre circle from the side, halfway line across"},
    {"spl2013_goal_both", S13, T320, "rgb", 2200, 0, 0, 0, 0, 450, 114, "",
     "both posts and the crossbar at 2.4 m"},
    {"spl2013_goal_both_far", S13, T320, "yuyv", -1000, 500, 0, 0, 0, 450, 115, "",
     "goal at 5.5 m"},
    {"spl2013_goal_one_post", S13, T320, "rgb", 3200, 1800, -25000, 50000, 0, 450, 116, "",
     "one post (the left one), the other outside the image"},
    {"spl2013_goal_one_post_near", S13, T320, "yuyv", 3900, -200, -60000, 200000, 0, 450, 117, "",
     "one post under 1 m with its foot"},
    {"spl2013_crossbar_only", S13, T320, "rgb", 4000, 0, 0, -300000, 0, 450, 118, "",
     "looking up under the crossbar: no post in the image"},
    {"spl2013_no_field", S13, T320, "rgb", 0, 3500, 90000, -100000, 0, 450, 119, "",
     "at the carpet edge looking out at the room: no field at all"},
    {"spl2013_no_field_end", S13, T320, "yuyv", -4800, 300, 180000, -200000, 0, 450, 120, "",
     "behind the goal line looking at the end wall: no field"},
    {"spl2013_robots_occlude", S13, T320, "rgb", -2000, 0, 0, 200000, 0, 450, 121,
     "other -600 525 -30000 red\nother -650 -506 -32000 blue\nother -300 0 -32768 red",
     "robots standing in front of the X crossings and the centre mark"},
    {"spl2013_robots_goal", S13, T320, "yuyv", 1500, 300, 0, 50000, 0, 450, 122,
     "other 4200 0 -32768 blue\nother 3000 -700 16384 red\nother 2800 900 -16384 blue\nball 1 3300 200",
     "goalkeeper between the posts, two more robots and the ball"},
    {"spl2013_ball_near", S13, B320, "rgb", -2000, 1000, -30000, 0, 0, 450, 123,
     "ball 1 -1450 700\nother -1100 400 -32768 red",
     "ball half a metre ahead, a robot behind it"},
    {"spl2013_bright", S13, T320, "rgb", 2200, 0, 0, 0, 0, 450, 124, "light 165 0 0 1",
     "goal, overexposed (gain 165%)"},
    {"spl2013_dark", S13, T320, "rgb", -2300, 0, 0, 300000, 0, 450, 125, "light 45 0 0 1\nnoise 35",
     "centre circle, dark (gain 45%) and noisy"},
    {"spl2013_gradient_shadow", S13, T320, "yuyv", 2500, 0, 20000, 300000, 0, 450, 126,
     "light 100 60 -40 1\nother 3300 500 0 red\nother 3000 -300 -32768 blue",
     "goal box with a strong brightness ramp and robot shadows"},
    {"spl2013_blur_h", S13, T320, "rgb", 2500, 0, 20000, 300000, 0, 450, 127, "blur 9 0",
     "goal box, 9 px horizontal motion blur (head turning)"},
    {"spl2013_blur_diag", S13, T320, "yuyv", -2300, 0, 0, 300000, 0, 450, 128, "blur 6 5461",
     "centre circle, 6 px motion blur at 30 degrees"},
    {"spl2013_jpeg", S13, T320, "rgb", 2200, 0, 0, 0, 0, 450, 129, "jpeg 3",
     "goal with JPEG-like 8x8 blocks (about quality 50)"},
    {"spl2013_jpeg_noise", S13, B320, "yuyv", -900, -300, 15000, 0, 0, 450, 130, "jpeg 4\nnoise 50",
     "centre mark, strong blocks and noise"},
    {"spl2013_planar_corner", S13, B320, "planar", 3700, 2300, 41000, 100000, 0, 450, 131, "",
     "field corner L, planar YCbCr"},
    {"spl2013_640_goal", S13, "nao4-top-640", "rgb", 2200, 0, 0, 0, 0, 450, 132, "",
     "both posts, 640x480 RGB"},
    {"spl2013_640_circle", S13, "nao4-bottom-640", "yuyv", -700, 200, 35000, 0, 0, 450, 133, "",
     "circle, X and centre mark near, 640x480 YUYV"},
    {"spl2013_640_box", S13, "nao4-top-640", "planar", 2500, 0, 20000, 300000, 0, 450, 134,
     "other 3400 -500 -32768 red",
     "goal box with a robot, 640x480 planar"},
    {"spl2013_nao3", S13, "nao3-bottom-320", "rgb", -700, 200, 35000, 50000, 0, 450, 135, "",
     "X crossing through the NAO v3 bottom camera"},
    {"spl2013_yaw_left", S13, T320, "yuyv", 0, -1000, 0, 150000, 800000, 450, 136, "",
     "head turned 0.8 rad left: circle and halfway line"},
    {"spl2013_yaw_right", S13, T320, "rgb", 1500, 1200, 0, 100000, -900000, 450, 137,
     "head 450 1043 -9387 546", /* = the row's pitch and yaw, plus a 3 degree pitch offset */
     "head turned 0.9 rad right, 3 degrees of extra pitch (pitch offset)"},
    {"spl2013_plain_walls", S13, T320, "rgb", 1500, 300, 0, 50000, 0, 450, 138, "background 0",
     "goal in front of plain walls (no clutter)"},

    /* ---- uva2013: the poses of the UvA 2013 dataset (x, y in mm) ---- */
    {"uva2013_qvga_000001", U13, B320, "rgb", 0, 0, 0, -541544, 1492, 450, 201, "",
     "pose of qvga_000001: own goal box, both posts, penalty mark"},
    {"uva2013_qvga_000003", U13, B320, "yuyv", 0, 0, 90000, -541544, 3026, 450, 203, "",
     "pose of qvga_000003: halfway line meets the touchline"},
    {"uva2013_qvga_000008", U13, B320, "rgb", 0, 0, -45000, -541544, -1576, 450, 208, "",
     "pose of qvga_000008: one post at the image edge"},
    {"uva2013_qvga_000013", U13, B320, "rgb", 0, 600, 180000, -541544, 3026, 450, 213, "",
     "pose of qvga_000013: the other goal and box"},
    {"uva2013_qvga_000015", U13, B320, "yuyv", 0, 600, -90000, -541544, 3026, 450, 215, "",
     "pose of qvga_000015: circle arc and the halfway line"},
    {"uva2013_qvga_000017", U13, B320, "rgb", 0, 2010, 0, -544612, 3026, 450, 217, "",
     "pose of qvga_000017: along the touchline"},
    {"uva2013_qvga_000020", U13, B320, "rgb", 0, 2010, 135000, -543078, 3026, 450, 220, "",
     "pose of qvga_000020: looking off the field"},
    {"uva2013_qvga_000024", U13, B320, "yuyv", 0, 2010, -45000, -544612, -42, 450, 224, "",
     "pose of qvga_000024: goal, box and the circle edge"},
    {"uva2013_qvga_000029", U13, B320, "rgb", 2950, 2010, 180000, -540010, -6178, 450, 229, "",
     "pose of qvga_000029: from the corner down the touchline"},
    {"uva2013_qvga_000038", U13, B320, "rgb", 2950, 1110, -135000, -544612, -4644, 450, 238, "",
     "pose of qvga_000038: diagonal across the field"},
    {"uva2013_qvga_000045", U13, B320, "yuyv", 2350, 1110, 180000, -544612, 7628, 450, 245, "",
     "pose of qvga_000045: far goal and the circle"},
    {"uva2013_qvga_000057", U13, B320, "rgb", 1150, 0, 0, -553816, -6178, 450, 257, "",
     "pose of qvga_000057: both posts close"},
    {"uva2013_straightwalk_000001", U13, B320, "rgb", -2800, 0, 0, -552282, -1576, 450, 261, "",
     "pose of straightwalk_000001: the whole field lengthwise"},
    {"uva2013_straightwalk_000009", U13, B320, "yuyv", -1200, 0, 0, -546146, 3026, 450, 269, "",
     "pose of straightwalk_000009: circle, halfway line, goal"},
    {"uva2013_triwalk_000001", U13, B320, "rgb", -3000, 0, 33600, -549214, -4644, 450, 271, "",
     "pose of triwalk_000001"},
    {"uva2013_robots", U13, B320, "yuyv", 0, 0, 0, -541544, 1492, 450, 281,
     "other 1500 200 -32768 blue\nother 2300 -500 20000 red\nball 1 900 -300",
     "qvga_000001 pose with two robots in front of the goal box and a ball"},
    /* the same poses through the camera calibrated on the real labels
     * ("uva2013": focal 275.3 px, 6.26 degree pitch offset, neck 450): these
     * frames line up with the real images to a few pixels */
    {"uva2013_cal_qvga_000001", U13, "uva2013", "rgb", 0, 0, 0, -541544, 1492, 450, 291, "",
     "qvga_000001 pose through the calibrated uva2013 camera"},
    {"uva2013_cal_qvga_000015", U13, "uva2013", "yuyv", 0, 600, -90000, -541544, 3026, 450, 292, "",
     "qvga_000015 pose through the calibrated uva2013 camera"},
    {"uva2013_cal_qvga_000045", U13, "uva2013", "yuyv", 2350, 1110, 180000, -544612, 7628, 450, 293, "",
     "qvga_000045 pose through the calibrated uva2013 camera"},
    {"uva2013_cal_straightwalk_000009", U13, "uva2013", "rgb", -1200, 0, 0, -546146, 3026, 450, 294, "",
     "straightwalk_000009 pose through the calibrated uva2013 camera"},
    {"uva2013_planar", U13, B320, "planar", 1600, 0, 0, -549214, 6094, 450, 282, "",
     "pose of straightwalk_000023 (both posts very close), planar"},

    /* ---- spl2020: white goals, large penalty area ---- */
    {"spl2020_goal_both", S20, "nao6-top-320", "rgb", 2000, 0, 0, 50000, 0, 450, 301, "",
     "white goal, both posts"},
    {"spl2020_penalty_area", S20, "nao6-top-320", "yuyv", 1200, 1300, 0, 250000, 0, 450, 302, "",
     "penalty area corner L and T"},
    {"spl2020_goal_area_near", S20, "nao6-bottom-320", "rgb", 3400, -600, -20000, 0, 0, 450, 303, "",
     "goal area L under 1 m"},
    {"spl2020_penalty_mark", S20, "nao6-top-320", "rgb", 2300, 300, 0, 300000, 0, 450, 304, "",
     "penalty mark and the penalty area"},
    {"spl2020_robots_ball", S20, "nao6-top-320", "yuyv", -1800, -400, 10000, 250000, 0, 450, 305,
     "other -600 300 -32768 blue\nother -300 -700 8000 red\nball 1 -1000 -250",
     "circle with robots and the black-and-white ball"},
    {"spl2020_bright_jpeg", S20, "nao6-top-320", "rgb", 2000, 0, 0, 50000, 0, 450, 306,
     "light 150 -30 0 1\njpeg 2",
     "white goal, bright with a ramp and JPEG blocks"},
    {"spl2020_robot_border", S20, "nao6-top-320", "rgb", 1500, 1500, 52000, 50000, 0, 450, 307,
     "other 3000 3400 -16384 blue",
     "a robot standing alone between the touchline and the border: no post"},
    {"spl2020_line_end_on", S20, "nao6-top-320", "rgb", 0, 1200, 90000, 150000, 0, 450, 308, "",
     "the halfway line end-on up to the touchline: no post"},
    {"spl2020_goal_far", S20, "nao6-top-320", "yuyv", 0, 300, 0, 0, 0, 450, 309, "",
     "white goal at 4.5 m"},
    {"spl2020_goal_one_post", S20, "nao6-top-320", "rgb", 3000, 1600, -30000, 50000, 0, 450, 310, "",
     "one white post (the left one) at 1.7 m"},
    {"spl2020_goal_robots", S20, "nao6-top-320", "rgb", 2000, 300, 0, 50000, 0, 450, 311,
     "other 4200 0 -32768 red\nother 3400 -1300 16384 blue",
     "white goal with a goalkeeper between the posts and a robot beside"},

    /* ---- aibo2004: AIBO ERS-7 camera, colored goals and beacons ---- */
    {"aibo2004_goal_yellow", A04, "aibo-ers7", "rgb", 900, 0, 0, 50000, 0, 160, 401, "",
     "the yellow goal"},
    {"aibo2004_goal_skyblue", A04, "aibo-ers7", "rgb", -900, 200, 180000, 50000, 0, 160, 402, "",
     "the sky-blue goal"},
    {"aibo2004_beacon", A04, "aibo-ers7", "rgb", 1200, 800, 35000, -50000, 0, 160, 403, "",
     "a corner beacon and the field corner"},
    {"aibo2004_circle", A04, "aibo-ers7", "yuyv", -700, 0, 0, 250000, 0, 160, 404, "",
     "centre circle and its X crossings"},
    {"aibo2004_l_corner", A04, "aibo-ers7", "rgb", 1600, 900, 40000, 200000, 0, 160, 405, "",
     "field corner L near"},
    {"aibo2004_t_box", A04, "aibo-ers7", "rgb", 1000, 300, 10000, 150000, 0, 160, 406, "",
     "goal box L and T"},
    {"aibo2004_robots_ball", A04, "aibo-ers7", "yuyv", 300, -200, 0, 100000, 0, 160, 407,
     "other 1300 100 -32768 blue\nother 900 -500 10000 red\nball 1 700 -100",
     "two AIBOs and the ball before the yellow goal"},
    {"aibo2004_dark", A04, "aibo-ers7", "planar", -900, 200, 180000, 50000, 0, 160, 408,
     "light 50 0 0 1\nnoise 30",
     "sky-blue goal, dark and noisy, planar"},
    /* ---- hl3x2: seed 002's scaled humanoid field, AcYut head camera at
     * 320 x 240 (acyut-320: acyut-640's optics; the set's size budget),
     * head 20 deg down; the three table I poses (tools/world/seed002.c) ---- */
    {"hl3x2_table1_a", H32, AC320, "yuyv", -450, 150, 60000, 349066, 0, 420, 501, "",
     "table I 2(a): the halfway T and the YBY pole only"},
    {"hl3x2_table1_b", H32, AC320, "yuyv", -250, 200, -170000, 349066, 0, 420, 502, "",
     "table I 2(b): the yellow goal's posts and its goal area"},
    {"hl3x2_table1_c", H32, AC320, "rgb", 750, 350, -175000, 349066, 0, 420, 503, "",
     "table I 2(c): yellow goal, circle X, marks, goal area"},
    {"hl3x2_pole_yby_near", H32, AC320, "yuyv", 200, 300, 95000, 349066, 0, 420, 504, "",
     "the YBY pole at 0.9 m and the halfway T"},
    {"hl3x2_pole_byb_far", H32, AC320, "yuyv", -600, 600, -72000, 349066, 0, 420, 505, "",
     "the BYB pole at 1.9 m across the field"},
    {"hl3x2_goal_skyblue", H32, AC320, "yuyv", 300, -100, 0, 349066, 0, 420, 506, "",
     "the sky-blue goal at 1.2 m, goal area, penalty mark"},
    {"hl3x2_goal_yellow_far", H32, AC320, "yuyv", 1000, 200, 180000, 261799, 0, 420, 507, "",
     "the yellow goal at 2.5 m across the circle"},
    {"hl3x2_corner_l", H32, AC320, "yuyv", -1000, 600, 140000, 349066, 0, 420, 508, "",
     "field corner L at 0.65 m"},
    {"hl3x2_centre_x", H32, AC320, "yuyv", -800, 100, 10000, 349066, 0, 420, 509, "",
     "centre circle X crossings and the centre mark"},
    {"hl3x2_box_t", H32, AC320, "yuyv", 800, -250, -25000, 349066, 0, 420, 510, "",
     "goal area L and T before the sky-blue goal"},
    {"hl3x2_pole_robot", H32, AC320, "yuyv", -900, -300, 40000, 349066, 0, 420, 511,
     "other -300 500 -16384 red",
     "the YBY pole behind a robot, the halfway T"},
};

#define N_FIXTURES ((int)(sizeof fixtures / sizeof fixtures[0]))

int render_fixture_count(void) { return N_FIXTURES; }

int render_fixture_get(int i, render_scene_t *sc, const char **name, const char **description)
{
    const fixture_t *f;
    const fl_camera_model_t *m;
    char text[1024];
    FILE *mem;
    int r;
    if (i < 0 || i >= N_FIXTURES || !sc)
        return -1;
    f = &fixtures[i];
    m = fl_camera_model_find(f->camera);
    snprintf(text, sizeof text,
             "fieldloc-scene 1\nfield %s\ncamera %s\nformat %s\nrobot %d %d %d\nhead %d %d %d %d\n"
             "seed %u\nworld_seed %u\n%s\n",
             f->field, f->camera, f->format, f->x_mm, f->y_mm, (int)fl_angle_from_mdeg(f->heading_mdeg),
             f->neck_mm, (int)fl_angle_from_urad(f->pitch_urad), (int)fl_angle_from_urad(f->yaw_urad),
             m ? (int)m->default_pitch_offset : 0, f->seed, f->seed, f->extra);
    mem = tmpfile();
    if (!mem)
        return -1;
    fputs(text, mem);
    rewind(mem);
    r = render_scene_read(mem, sc, NULL, 0);
    fclose(mem);
    if (r != 0)
        return -1;
    if (name)
        *name = f->name;
    if (description)
        *description = f->desc;
    return 0;
}
