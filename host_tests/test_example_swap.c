/*
 * host_tests/test_example_swap.c - the README example with its one
 * LOCALIZER line changed from "fuzzy" to "mcl" (the Makefile derives
 * build/gen/readme_example_mcl.inc from host_tests/readme_example.inc and
 * refuses unless exactly that line differs): the same code runs the Monte
 * Carlo filter.  Both variants get the same task on a rendered fixture: a
 * robot told its pose within 300 mm / 20 deg sees a T crossing from where
 * it stands; each estimate must end within 200 mm and 10 deg of the truth.
 */
#include "test.h"
#include "fieldloc/fieldloc.h"
#include "world/render.h"

#include <stdlib.h>
#include <string.h>

#include "readme_example_mcl.inc"

static void test_readme_swap(void)
{
    robot_loc_t *r = malloc(sizeof *r);
    render_scene_t sc;
    render_frame_t fr;
    fl_loc_estimate_t est;
    char err[128];
    FILE *f = fopen("fixtures/frames/spl2013_t_near.scene", "r");
    static const char calib[] = "fieldloc-calibration 1\ncamera nao4-bottom-320\n"
                                "neck_height_mm 450\npitch_offset_deg 0\nroll_offset_deg 0\n";
    int i;
    int32_t ex, ey, eh;
    CHECK(r != NULL && f != NULL);
    if (!r || !f) {
        free(r);
        if (f) fclose(f);
        return;
    }
    CHECK_EQ(render_scene_read(f, &sc, err, sizeof err), 0);
    fclose(f);
    CHECK_EQ(render_frame(&sc, &fr), 0);
    CHECK_EQ(loc_init(r, "spl2013", "nao4-bottom-320", calib, sizeof calib - 1), FL_OK);
    CHECK(r->loc == fl_localizer_find("mcl"));
    /* told roughly where it stands (300 mm, 20 deg off) */
    r->loc->reset_pose(r->state.b, sc.robot_x_mm + 200, sc.robot_y_mm - 200,
                       fl_angle_add(sc.robot_heading, fl_angle_from_mdeg(8000)), 300,
                       fl_angle_from_mdeg(20000));
    for (i = 0; i < 15; i++)   /* standing still, the same frame */
        loc_frame(r, 0, 0, 0, &fr.view, sc.head.head_pitch, sc.head.head_yaw, 0, 0, &est);
    CHECK(r->vision.crossings.n > 0);
    ex = est.x_mm - sc.robot_x_mm;
    ey = est.y_mm - sc.robot_y_mm;
    eh = fl_angle_sub(est.heading, sc.robot_heading);
    CHECK_LE(ex * ex + ey * ey, 200 * 200);
    CHECK_LE(eh < 0 ? -eh : eh, fl_angle_from_mdeg(10000));
    t_info("README example with LOCALIZER \"mcl\" on spl2013_t_near: estimate (%d, %d) mm %.1f deg, "
           "truth (%d, %d) mm %.1f deg", (int)est.x_mm, (int)est.y_mm,
           fl_angle_to_mdeg(est.heading) / 1000.0, (int)sc.robot_x_mm, (int)sc.robot_y_mm,
           fl_angle_to_mdeg(sc.robot_heading) / 1000.0);
    render_frame_free(&fr);
    free(r);
}

void suite_example_swap(void)
{
    t_run("example.readme_swap", test_readme_swap);
}
