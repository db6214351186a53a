/*
 * host_tests/test_example.c - the C API example of README.md ("The C API"),
 * compiled and run on a rendered fixture, so that the README's code stays
 * true; example.readme_text checks that the README shows exactly this code.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/render.h"

#include <stdlib.h>
#include <string.h>

/* ---- the README example, verbatim from here ---- */
#define LOCALIZER "fuzzy"   /* the one line that picks the filter (localizer.h catalogue) */

typedef struct {
    fl_color_table_t colors;   /* ~230 KiB, built once */
    fl_vision_t vision;        /* ~120 KiB, all buffers of the vision path */
    const fl_localizer_t *loc; /* the localizer's functions */
    const fl_field_t *field;
    union { int64_t align; void *p; uint8_t b[72 * 1024]; } state;   /* the belief (fuzzy ~63 KiB) */
    union { int64_t align; void *p; uint8_t b[512]; } params;
} robot_loc_t;

static fl_status_t loc_init(robot_loc_t *r, const char *field_name)
{
    fl_color_params_t cp;
    fl_vision_params_t vp;
    fl_status_t s;
    r->loc = fl_localizer_find(LOCALIZER);
    r->field = fl_field_find(field_name);
    if (r->loc == NULL) return FL_ERR_NOT_FOUND;
    if (r->loc->state_size > sizeof r->state || r->loc->params_size > sizeof r->params)
        return FL_ERR_SIZE;
    fl_color_params_default(&cp);               /* HSV boxes from the UvA 2013 images */
    fl_vision_params_default(&vp);
    /* parameters for vision's observations; the camera's width picks the preset */
    r->loc->params_preset(r->params.b,
                          fl_loc_preset_for_width(fl_camera_model_find("nao4-bottom-320")->width_px));
    if ((s = fl_color_init(&r->colors, &cp)) != FL_OK) return s;
    if ((s = fl_vision_init(&r->vision, &vp)) != FL_OK) return s;
    return fl_loc_init(r->loc, r->state.b, r->field, r->params.b);   /* total ignorance */
}

/* once per camera frame: odometry since the last frame (robot frame, mm,
 * binary angle), the frame, the head joints */
static void loc_frame(robot_loc_t *r, int32_t odo_dx_mm, int32_t odo_dy_mm, fl_angle_t odo_dtheta,
                      const fl_image_t *img, fl_angle_t head_pitch, fl_angle_t head_yaw,
                      fl_loc_estimate_t *est)
{
    const fl_camera_model_t *m = fl_camera_model_find("nao4-bottom-320");
    fl_camera_pose_t pose = {m->default_neck_height_mm, head_pitch, head_yaw, m->default_pitch_offset};
    fl_camera_t cam;
    fl_obs_list_t obs;
    fl_obs_view_t view;
    fl_camera_init(&cam, m, &pose);
    fl_vision_frame(&r->vision, &r->colors, img, &cam, r->field, &obs);  /* -> observations */
    fl_vision_view(&cam, &view);   /* where landmarks would surely have been seen */
    fl_loc_predict(r->loc, r->state.b, odo_dx_mm, odo_dy_mm, odo_dtheta);
    fl_loc_update(r->loc, r->state.b, &obs, &view);   /* observations + negative information */
    fl_loc_estimate(r->loc, r->state.b, est);   /* x_mm, y_mm, heading, reliability_q16 */
}
/* ---- end of the README example ---- */

static void test_readme_example(void)
{
    robot_loc_t *r = malloc(sizeof *r);
    render_scene_t sc;
    render_frame_t fr;
    fl_loc_estimate_t est;
    char err[128];
    FILE *f = fopen("fixtures/frames/spl2013_t_near.scene", "r");
    int i;
    CHECK(r != NULL && f != NULL);
    if (!r || !f) {
        free(r);
        if (f) fclose(f);
        return;
    }
    CHECK_EQ(render_scene_read(f, &sc, err, sizeof err), 0);
    fclose(f);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK_EQ(loc_init(r, "spl2013"), FL_OK);
    r->loc->set_prior_half(r->state.b, sc.robot_x_mm < 0 ? -1 : 1);
    for (i = 0; i < 5; i++)   /* standing still, the same frame */
        loc_frame(r, 0, 0, 0, &fr.view, sc.head.head_pitch, sc.head.head_yaw, &est);
    CHECK(r->vision.crossings.n > 0);
    /* one T seen from one spot is ambiguous, but the true pose must stay
     * among the most possible ones */
    CHECK_LE(32768, r->loc->possibility_q16(r->state.b, sc.robot_x_mm, sc.robot_y_mm, sc.robot_heading));
    t_info("README example on spl2013_t_near: possibility of the true pose %.2f, estimate (%d, %d) mm "
           "reliability %.2f (one crossing: ambiguous), truth (%d, %d) mm",
           r->loc->possibility_q16(r->state.b, sc.robot_x_mm, sc.robot_y_mm, sc.robot_heading) / 65536.0,
           (int)est.x_mm, (int)est.y_mm, est.reliability_q16 / 65536.0, (int)sc.robot_x_mm,
           (int)sc.robot_y_mm);
    render_frame_free(&fr);
    free(r);
}

/* The text between the markers in README.md (less its #include line) and
 * between the markers in this file must be the same, line for line. */
static const char *between(const char *text, const char *begin, const char *end, size_t *len)
{
    const char *a = text ? strstr(text, begin) : NULL;
    const char *b;
    if (!a)
        return NULL;
    a = strchr(a + strlen(begin), '\n');
    if (!a)
        return NULL;
    a++;
    b = strstr(a, end);
    if (!b)
        return NULL;
    while (b > a && b[-1] != '\n')   /* back to the start of the marker's line */
        b--;
    *len = (size_t)(b - a);
    return a;
}

static void test_readme_text(void)
{
    size_t nr = 0, nt = 0, lr, lt;
    char *readme = t_read_file("README.md", &nr);
    char *self = t_read_file("host_tests/test_example.c", &nt);
    const char *ex_r = between(readme, "<!-- example:begin -->", "<!-- example:end -->", &lr);
    const char *ex_t = between(self, "/* ---- the README example, verbatim from here", "/* ---- end of the README example", &lt);
    static const char head[] = "```c\n#include <fieldloc/fieldloc.h>\n\n";
    CHECK(ex_r != NULL && ex_t != NULL);
    if (ex_r && ex_t) {
        CHECK(lr > sizeof head - 1 && memcmp(ex_r, head, sizeof head - 1) == 0);
        ex_r += sizeof head - 1;
        lr -= sizeof head - 1;
        CHECK(lr >= 4 && memcmp(ex_r + lr - 4, "```\n", 4) == 0);
        lr -= 4;
        if (lr != lt || memcmp(ex_r, ex_t, lt) != 0)
            t_fail_msg(__FILE__, __LINE__, "README.md's example differs from host_tests/test_example.c "
                       "(%zu vs %zu bytes): keep the two in step", lr, lt);
    }
    free(readme);
    free(self);
}

void suite_example(void)
{
    t_run("example.readme_api", test_readme_example);
    t_run("example.readme_text", test_readme_text);
}
