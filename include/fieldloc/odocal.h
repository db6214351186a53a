/*
 * fieldloc/odocal.h - odometry scale calibration from an observer's track.
 *
 * A walking robot's odometry has systematic errors: the distance it reports
 * along each body axis is the true one times (1 + s) with s of several per
 * cent (side-stepping NAOs: 10-20 %).  Between two sightings of the same
 * player by a coach beside the field (obs.h fl_obs_report_t, seed 003),
 * the distance the coach saw it walk is a measurement of the true distance;
 * the odometry's motion over the same interval is known to the player.  So
 * the track of the coach's reports against the player's own odometry
 * calibrates the odometry's scale per body axis, with no landmark at all.
 *
 * The model (one axis at a time, the other at unit gain):
 *   |report_j - report_i|^2 = gx^2 |Px_j - Px_i|^2 + gy^2 |Py_j - Py_i|^2
 * where Px (Py) is the odometry's motion along the body's x (y) axis,
 * summed as a vector in the odometry's own frame (so a turn between the
 * sightings is allowed), and gx, gy are the gains that turn odometry into
 * true motion (gain = 1 / (1 + s)).  A pair of sightings measures the gain
 * of axis a when its motion along a is at least FL_ODOCAL_MIN_BASELINE_MM
 * and the other axis' motion at most a quarter of it; gain^2 is the least
 * squares solution over all such pairs, each pair gated (its own gain
 * within [FL_ODOCAL_GAIN_MIN_Q16, FL_ODOCAL_GAIN_MAX_Q16]) so a wrong
 * report (another robot's foot) is dropped instead of averaged in.  An
 * axis without FL_ODOCAL_MIN_PAIRS gated pairs keeps gain 1 (nothing is
 * changed on a guess).
 *
 * Use (one player):
 *     fl_odocal_init(&c);
 *     each odometry step:     fl_odocal_odometry(&c, dx_mm, dy_mm, dtheta);
 *     each report taken:      fl_odocal_fix(&c, report.x_mm, report.y_mm);
 *     when enough are in:     fl_odocal_solve(&c);
 *     afterwards, each step:  fl_odocal_apply(&c, &dx_mm, &dy_mm);  before
 *                             the localizer's predict.
 *
 * Capacity FL_ODOCAL_MAX_FIXES sightings (config.h); the solve is
 * O(FL_ODOCAL_MAX_FIXES^2) pairs, integer only.  Bounded output: a gain
 * is always within [FL_ODOCAL_GAIN_MIN_Q16, FL_ODOCAL_GAIN_MAX_Q16].
 */
#ifndef FIELDLOC_ODOCAL_H
#define FIELDLOC_ODOCAL_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FL_ODOCAL_ONE_Q16 65536
#define FL_ODOCAL_GAIN_MIN_Q16 45875     /* 0.70 */
#define FL_ODOCAL_GAIN_MAX_Q16 85197     /* 1.30 */
#define FL_ODOCAL_MIN_BASELINE_MM 800
#define FL_ODOCAL_MIN_PAIRS 3

/* One sighting: the odometry's summed motion per body axis (odometry
 * frame, mm) when the report was taken, and the report (field, mm). */
typedef struct {
    int32_t px_x_mm, px_y_mm;   /* body-x motion */
    int32_t py_x_mm, py_y_mm;   /* body-y motion */
    int32_t rx_mm, ry_mm;
} fl_odocal_fix_t;

typedef struct {
    fl_odocal_fix_t fix[FL_ODOCAL_MAX_FIXES];
    uint32_t n_fixes;
    uint32_t fixes_refused;        /* fl_odocal_fix beyond the capacity */
    int64_t px_x_q15, px_y_q15;    /* summed body-x motion, mm Q15 */
    int64_t py_x_q15, py_y_q15;    /* summed body-y motion, mm Q15 */
    fl_angle_t heading;            /* the odometry's own heading */
    int32_t gain_q16[2];           /* x, y: true = odometry * gain / 2^16 */
    uint32_t pairs[2];             /* pairs used per axis by the last solve */
    uint32_t pairs_gated[2];       /* pairs with the baseline, gated out */
    int64_t carry[2];              /* fl_odocal_apply's rounding remainder */
} fl_odocal_t;

/* Empty track, gains 1. FL_ERR_NULL for NULL. */
fl_status_t fl_odocal_init(fl_odocal_t *c);

/* One odometry step (robot frame at the start of the step, as
 * localizer.h fl_loc_predict), uncorrected.  Steps longer than 1000 mm
 * are refused (FL_ERR_RANGE, the track unchanged). */
fl_status_t fl_odocal_odometry(fl_odocal_t *c, int32_t dx_mm, int32_t dy_mm,
                               fl_angle_t dtheta);

/* A report of this player taken now (after the odometry steps up to now).
 * FL_ERR_SIZE when FL_ODOCAL_MAX_FIXES are in (counted, nothing stored);
 * FL_ERR_RANGE for a position beyond +-100 m. */
fl_status_t fl_odocal_fix(fl_odocal_t *c, int32_t x_mm, int32_t y_mm);

/* Least squares over the pairs of sightings (above); sets gain_q16 and
 * pairs.  Returns FL_OK (an axis without enough pairs keeps gain 1). */
fl_status_t fl_odocal_solve(fl_odocal_t *c);

/* Corrects one odometry step in place: d = d * gain, rounding carried to
 * the next step (the corrected sum never drifts by rounding). */
fl_status_t fl_odocal_apply(fl_odocal_t *c, int32_t *dx_mm, int32_t *dy_mm);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_ODOCAL_H */
