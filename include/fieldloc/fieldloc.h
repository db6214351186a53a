/*
 * fieldloc/fieldloc.h - umbrella header: every public stage of fieldloc.
 * See docs/DESIGN.md for the data flow; each stage's header documents its
 * lifecycle.
 */
#ifndef FIELDLOC_FIELDLOC_H
#define FIELDLOC_FIELDLOC_H

#include "fieldloc/config.h"
#include "fieldloc/common.h"
#include "fieldloc/fixed.h"
#include "fieldloc/text.h"
#include "fieldloc/image.h"
#include "fieldloc/color.h"
#include "fieldloc/color_auto.h"
#include "fieldloc/scan.h"
#include "fieldloc/camera.h"
#include "fieldloc/calib.h"
#include "fieldloc/field.h"
#include "fieldloc/homography.h"
#include "fieldloc/obs.h"
#include "fieldloc/lines.h"
#include "fieldloc/circle.h"
#include "fieldloc/crossings.h"
#include "fieldloc/goal.h"
#include "fieldloc/beacon.h"
#include "fieldloc/skeleton.h"
#include "fieldloc/corners.h"
#include "fieldloc/vision.h"
#include "fieldloc/hlvision.h"
#include "fieldloc/coach.h"
#include "fieldloc/fuzzy.h"
#include "fieldloc/mcl.h"
#include "fieldloc/localizer.h"
#include "fieldloc/report.h"

#endif /* FIELDLOC_FIELDLOC_H */
