// host_tests/cxx/readme_example.cpp - the README's C API example compiled as
// C++ by the test example.readme_cxx (to an object, not linked): C++
// frameworks include the headers as they are.
#include <fieldloc/fieldloc.h>

#include "../readme_example.inc"

// Uses both functions of the example, so that the object references every
// library function they call.
int readme_example_run(robot_loc_t *r, const fl_image_t *img);
int readme_example_run(robot_loc_t *r, const fl_image_t *img)
{
    static const char calib[] = "fieldloc-calibration 1\nneck_height_mm 450\n";
    fl_loc_estimate_t est;
    if (loc_init(r, "spl2013", "nao6-top-640", calib, sizeof calib - 1) != FL_OK)
        return 1;
    loc_frame(r, 0, 0, 0, img, 0, 0, 0, 0, &est);
    return est.localized ? 0 : 2;
}
