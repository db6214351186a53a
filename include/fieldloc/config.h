/*
 * fieldloc/config.h - every compile-time capacity of the module, in one
 * place, and the version.  Each option has a default, may be overridden
 * with -D, and is range checked here.  State structs are sized from these;
 * nothing is allocated.
 *
 * The library and every caller must see the same values: a caller built
 * with another FL_OBS_MAX than the library has a differently shaped
 * fl_obs_list_t, and the library would write past its object.  So the
 * options are folded into FL_CONFIG_FINGERPRINT (end of this file), every
 * public init passes the caller's fingerprint to the library (common.h)
 * and refuses a foreign one with FL_ERR_CONFIG.  To change an option,
 * rebuild the library with it (make CONFIG_DEFS="-DFL_OBS_MAX=64"): `make
 * install` then writes the build's values into the installed copy of this
 * file as its defaults, so callers that pass no -D match.
 */
#ifndef FIELDLOC_CONFIG_H
#define FIELDLOC_CONFIG_H

#include <stdint.h>

/* Release version of the sources (not an option).  FL_VERSION_STRING is
 * "MAJOR.MINOR.PATCH"; the installed fieldloc.pc carries the same. */
#define FL_VERSION_MAJOR 0
#define FL_VERSION_MINOR 17
#define FL_VERSION_PATCH 0
#define FL_VERSION_STRING "0.17.0"

/* Layout version of the public structs (not an option): raise it whenever
 * a public struct that an init function takes changes shape (a field
 * added, removed, retyped or moved), so that a caller compiled against
 * the old headers gets FL_ERR_CONFIG instead of a wrong layout. */
#define FL_ABI_VERSION 5

/* Largest image width or height accepted, pixels.  Default 1280 (NAO v6
 * full resolution is 1280x960).  Range 16..4096. */
#ifndef FL_IMAGE_MAX_DIM
#define FL_IMAGE_MAX_DIM 1280
#endif
#if FL_IMAGE_MAX_DIM < 16 || FL_IMAGE_MAX_DIM > 4096
#error "FL_IMAGE_MAX_DIM must be in 16..4096"
#endif

/* ---- fuzzy position grid (fuzzy.h, seed 004) ---------------------------
 * FL_FUZZY_CELL_MM   cell side, mm.  Default 100 (seed 004's 10 cm).
 *                    Range 50..250 (sub-cell offsets are int8 mm).
 * FL_FUZZY_MAX_NX/NY grid capacity in cells along field x / y.  Default
 *                    104 x 74: the SPL 2013 carpet (10.4 x 7.4 m) at 100 mm;
 *                    smaller fields use a sub-rectangle.  Range 4..255 each,
 *                    and at most 20 m per side (squared distances in the
 *                    update stay below 2^32).
 * FL_FUZZY_MAX_REGIONS  landmark regions one observation may visit (one per
 *                    matching map landmark and orientation candidate, e.g.
 *                    2 X crossings x 4 orientations = 8).  Default 48, range
 *                    8..255; extra regions are dropped and counted.
 * Memory: 8 bytes per cell + 24 bytes per column of scratch (see fuzzy.h). */
#ifndef FL_FUZZY_CELL_MM
#define FL_FUZZY_CELL_MM 100
#endif
#if FL_FUZZY_CELL_MM < 50 || FL_FUZZY_CELL_MM > 250
#error "FL_FUZZY_CELL_MM must be in 50..250"
#endif
#ifndef FL_FUZZY_MAX_NX
#define FL_FUZZY_MAX_NX 104
#endif
#ifndef FL_FUZZY_MAX_NY
#define FL_FUZZY_MAX_NY 74
#endif
#if FL_FUZZY_MAX_NX < 4 || FL_FUZZY_MAX_NX > 255 || FL_FUZZY_MAX_NY < 4 || FL_FUZZY_MAX_NY > 255
#error "FL_FUZZY_MAX_NX and FL_FUZZY_MAX_NY must be in 4..255"
#endif
#if FL_FUZZY_MAX_NX * FL_FUZZY_CELL_MM > 20000 || FL_FUZZY_MAX_NY * FL_FUZZY_CELL_MM > 20000
#error "the fuzzy grid may cover at most 20 m per side"
#endif
#ifndef FL_FUZZY_MAX_REGIONS
#define FL_FUZZY_MAX_REGIONS 48
#endif
#if FL_FUZZY_MAX_REGIONS < 8 || FL_FUZZY_MAX_REGIONS > 255
#error "FL_FUZZY_MAX_REGIONS must be in 8..255"
#endif

/* ---- Monte Carlo localizer (mcl.h, seed 000) -----------------------------
 * FL_MCL_MAX_PARTICLES  particle capacity (the run-time count,
 *                    params.n_particles, is at most this).  Default 256,
 *                    range 8..4096.  Memory: 20 B per particle (two 8 B
 *                    buffers and a 4 B likelihood) + about 0.6 KiB. */
#ifndef FL_MCL_MAX_PARTICLES
#define FL_MCL_MAX_PARTICLES 256
#endif
#if FL_MCL_MAX_PARTICLES < 8 || FL_MCL_MAX_PARTICLES > 4096
#error "FL_MCL_MAX_PARTICLES must be in 8..4096"
#endif

/* ---- unscented particle filter (upf.h, seed 003) -------------------------
 * FL_UPF_MAX_PARTICLES  particle capacity (the run-time count,
 *                    params.n_particles, is at most this).  Default 12 (seed
 *                    003's player), range 4..64.  Memory: 56 B per particle
 *                    (sample, UKF mean and covariance, log-weight) + about
 *                    0.6 KiB. */
#ifndef FL_UPF_MAX_PARTICLES
#define FL_UPF_MAX_PARTICLES 12
#endif
#if FL_UPF_MAX_PARTICLES < 4 || FL_UPF_MAX_PARTICLES > 64
#error "FL_UPF_MAX_PARTICLES must be in 4..64"
#endif

/* ---- column scanner (scan.h, seed 000) ----------------------------------
 * FL_SCAN_MAX_COLS   grid columns of one scan (width / col_step, rounded
 *                    up).  Default 640: every column of a 640x480 frame.
 *                    Range 32..4096.
 * FL_SCAN_MAX_ROWS   grid rows (height / row_step).  Default 480.  Range
 *                    16..4096.
 * FL_SCAN_MAX_FEET   yellow->green transitions kept per frame.  Default
 *                    64, range 1..4096; more are counted (feet_dropped).
 * Memory: fl_scan_t is about 8 * rows * cols / 32 (the 2-bit class map)
 * + 120 bytes per 32 columns + 10 bytes per column and row: 86 KB at the
 * defaults.  */
#ifndef FL_SCAN_MAX_COLS
#define FL_SCAN_MAX_COLS 640
#endif
#if FL_SCAN_MAX_COLS < 32 || FL_SCAN_MAX_COLS > 4096
#error "FL_SCAN_MAX_COLS must be in 32..4096"
#endif
#ifndef FL_SCAN_MAX_ROWS
#define FL_SCAN_MAX_ROWS 480
#endif
#if FL_SCAN_MAX_ROWS < 16 || FL_SCAN_MAX_ROWS > 4096
#error "FL_SCAN_MAX_ROWS must be in 16..4096"
#endif
#ifndef FL_SCAN_MAX_FEET
#define FL_SCAN_MAX_FEET 64
#endif
#if FL_SCAN_MAX_FEET < 1 || FL_SCAN_MAX_FEET > 4096
#error "FL_SCAN_MAX_FEET must be in 1..4096"
#endif

/* ---- line points, segments and field features (lines.h, crossings.h,
 * goal.h, circle.h, vision.h; seed 000 sections 3.6-3.9) -----------------
 * FL_LINES_MAX_POINTS    line points per frame.  Default 1024, range
 *                        64..4096 (ids are uint16; more are counted).
 * FL_LINES_MAX_SEGMENTS  line segments per frame.  Default 96, range
 *                        8..1024 (more are counted).
 * FL_LINES_MAX_BUCKETS   cells of the neighbour-search bucket grid (buckets
 *                        grow when the image needs more).  Default 2048,
 *                        range 64..65535.
 * FL_LINES_WTAB          knots of the per-row projected line width table
 *                        (rows between knots interpolated).  Default 65,
 *                        range 9..1025.
 * FL_CROSSINGS_MAX       L/T/X crossings and marks per frame.  Default 24,
 *                        range 4..255 (more are counted).
 * FL_GOAL_MAX_POSTS      goal posts per frame.  Default 4, range 1..16.
 * FL_CIRCLE_MAX_CHORDS   centre-circle centre candidates per frame (from
 *                        curved segments and pairs of them).  Default 32,
 *                        range 4..255 (more are counted).
 * FL_CIRCLE_MAX_POINTS   ground points in the circle fit (more are
 *                        subsampled).  Default 192, range 16..4096.
 * Memory: fl_lines_t about 8 B per point + 96 B per segment + 2 B per
 * bucket + 4 B per width knot (about 22 KB at the defaults); crossings
 * about 50 B each, posts about 70 B each; the circle 16 B per candidate,
 * 8 B per fit point and 20 B per segment of scratch. */
#ifndef FL_LINES_MAX_POINTS
#define FL_LINES_MAX_POINTS 1024
#endif
#if FL_LINES_MAX_POINTS < 64 || FL_LINES_MAX_POINTS > 4096
#error "FL_LINES_MAX_POINTS must be in 64..4096"
#endif
#ifndef FL_LINES_MAX_SEGMENTS
#define FL_LINES_MAX_SEGMENTS 96
#endif
#if FL_LINES_MAX_SEGMENTS < 8 || FL_LINES_MAX_SEGMENTS > 1024
#error "FL_LINES_MAX_SEGMENTS must be in 8..1024"
#endif
#ifndef FL_LINES_MAX_BUCKETS
#define FL_LINES_MAX_BUCKETS 2048
#endif
#if FL_LINES_MAX_BUCKETS < 64 || FL_LINES_MAX_BUCKETS > 65535
#error "FL_LINES_MAX_BUCKETS must be in 64..65535"
#endif
#ifndef FL_LINES_WTAB
#define FL_LINES_WTAB 65
#endif
#if FL_LINES_WTAB < 9 || FL_LINES_WTAB > 1025
#error "FL_LINES_WTAB must be in 9..1025"
#endif
#ifndef FL_CROSSINGS_MAX
#define FL_CROSSINGS_MAX 24
#endif
#if FL_CROSSINGS_MAX < 4 || FL_CROSSINGS_MAX > 255
#error "FL_CROSSINGS_MAX must be in 4..255"
#endif
#ifndef FL_GOAL_MAX_POSTS
#define FL_GOAL_MAX_POSTS 4
#endif
#if FL_GOAL_MAX_POSTS < 1 || FL_GOAL_MAX_POSTS > 16
#error "FL_GOAL_MAX_POSTS must be in 1..16"
#endif
#ifndef FL_CIRCLE_MAX_CHORDS
#define FL_CIRCLE_MAX_CHORDS 32
#endif
#if FL_CIRCLE_MAX_CHORDS < 4 || FL_CIRCLE_MAX_CHORDS > 255
#error "FL_CIRCLE_MAX_CHORDS must be in 4..255"
#endif
#ifndef FL_CIRCLE_MAX_POINTS
#define FL_CIRCLE_MAX_POINTS 192
#endif
#if FL_CIRCLE_MAX_POINTS < 16 || FL_CIRCLE_MAX_POINTS > 4096
#error "FL_CIRCLE_MAX_POINTS must be in 16..4096"
#endif

/* Ids one fl_lines_points_near query stores (lines.h); more are counted,
 * not stored.  Default 48, range 8..256. */
#ifndef FL_LINES_NEAR_MAX
#define FL_LINES_NEAR_MAX 48
#endif
#if FL_LINES_NEAR_MAX < 8 || FL_LINES_NEAR_MAX > 256
#error "FL_LINES_NEAR_MAX must be in 8..256"
#endif

/* Capacity of one frame's observation list (obs.h, fl_obs_list_t): more
 * observations are counted in `dropped`.  Default 32, range 4..255. */
#ifndef FL_OBS_MAX
#define FL_OBS_MAX 32
#endif
#if FL_OBS_MAX < 4 || FL_OBS_MAX > 255
#error "FL_OBS_MAX must be in 4..255"
#endif
/* Painted-line points one observation list carries (obs.h,
 * fl_obs_list_t.points: a vision path's sample of ground points on white
 * lines, which a localizer may use to tell apart poses its landmarks
 * cannot); more are counted in points_dropped.  Default 24, range 0..255
 * (0: the list carries none). */
#ifndef FL_OBS_MAX_POINTS
#define FL_OBS_MAX_POINTS 24
#endif
#if FL_OBS_MAX_POINTS < 0 || FL_OBS_MAX_POINTS > 255
#error "FL_OBS_MAX_POINTS must be in 0..255"
#endif

/* ---- relative-map position grid (relmap.h, seed 002) --------------------
 * FL_RELMAP_NX / NY   grid of position particles along field x / y.
 *                     Default 54 x 36 (seed 002's grid of its 3 x 2 m
 *                     field); on every field the same count spans the
 *                     carpet (lines plus border).  Range 8..96 each, and
 *                     NX * NY <= 2048: the grid (belief, heading and their
 *                     predict copies, 8 bytes a cell) stays within 16 KiB.
 * FL_RELMAP_MAX_CAND  particles the relative map is built for per frame
 *                     (those over the threshold, the best first).
 *                     Default 48, range 4..255.
 * FL_RELMAP_MAX_OBS   landmarks of a frame the relative map uses (the
 *                     nearest).  Default 8, range 2..32.
 * FL_RELMAP_MAX_WHITE white points projected per tied pose.  Default 16,
 *                     range 0..64. */
#ifndef FL_RELMAP_NX
#define FL_RELMAP_NX 54
#endif
#ifndef FL_RELMAP_NY
#define FL_RELMAP_NY 36
#endif
#if FL_RELMAP_NX < 8 || FL_RELMAP_NX > 96 || FL_RELMAP_NY < 8 || FL_RELMAP_NY > 96
#error "FL_RELMAP_NX and FL_RELMAP_NY must be in 8..96"
#endif
#if FL_RELMAP_NX * FL_RELMAP_NY > 2048
#error "FL_RELMAP_NX * FL_RELMAP_NY must be at most 2048 (16 KiB grid)"
#endif
#ifndef FL_RELMAP_MAX_CAND
#define FL_RELMAP_MAX_CAND 48
#endif
#if FL_RELMAP_MAX_CAND < 4 || FL_RELMAP_MAX_CAND > 255
#error "FL_RELMAP_MAX_CAND must be in 4..255"
#endif
#ifndef FL_RELMAP_MAX_OBS
#define FL_RELMAP_MAX_OBS 8
#endif
#if FL_RELMAP_MAX_OBS < 2 || FL_RELMAP_MAX_OBS > 32
#error "FL_RELMAP_MAX_OBS must be in 2..32"
#endif
#ifndef FL_RELMAP_MAX_WHITE
#define FL_RELMAP_MAX_WHITE 16
#endif
#if FL_RELMAP_MAX_WHITE < 0 || FL_RELMAP_MAX_WHITE > 64
#error "FL_RELMAP_MAX_WHITE must be in 0..64"
#endif

/* ---- colored beacons and goals (beacon.h, AIBO fields) -------------------
 * FL_BEACON_MAX_RUNS   colored vertical runs per frame.  Default 384
 *                      (a 208x160 frame full of color at the default
 *                      grid: 104 columns x a few runs), range 16..4096.
 * FL_BEACON_MAX_BLOBS  blobs per frame.  Default 48, range 4..255.
 * FL_BEACON_MAX_FOUND  beacons + posts reported per frame.  Default 8,
 *                      range 1..32.
 * Runs and blobs beyond a cap are counted and ignored. */
#ifndef FL_BEACON_MAX_RUNS
#define FL_BEACON_MAX_RUNS 384
#endif
#if FL_BEACON_MAX_RUNS < 16 || FL_BEACON_MAX_RUNS > 4096
#error "FL_BEACON_MAX_RUNS must be in 16..4096"
#endif
#ifndef FL_BEACON_MAX_BLOBS
#define FL_BEACON_MAX_BLOBS 48
#endif
#if FL_BEACON_MAX_BLOBS < 4 || FL_BEACON_MAX_BLOBS > 255
#error "FL_BEACON_MAX_BLOBS must be in 4..255"
#endif
#ifndef FL_BEACON_MAX_FOUND
#define FL_BEACON_MAX_FOUND 8
#endif
#if FL_BEACON_MAX_FOUND < 1 || FL_BEACON_MAX_FOUND > 32
#error "FL_BEACON_MAX_FOUND must be in 1..32"
#endif

/* ---- homography (homography.h, seed 003) ---------------------------------
 * FL_HOMOG_MAX_POINTS  correspondences one fit accepts.  Default 17 (the
 *                    field points seed 003 names).  Range 4..64.  No struct
 *                    is sized by it; it bounds the fit's work. */
#ifndef FL_HOMOG_MAX_POINTS
#define FL_HOMOG_MAX_POINTS 17
#endif
#if FL_HOMOG_MAX_POINTS < 4 || FL_HOMOG_MAX_POINTS > 64
#error "FL_HOMOG_MAX_POINTS must be in 4..64"
#endif

/* ---- the coach's image path (coach.h, seed 003) ---------------------------
 * FL_COACH_MAX_WIDTH/HEIGHT  largest coach frame, pixels.  Default 640 x 480
 *                    (NAO v6 top camera at the coach's resolution).  Range
 *                    32..FL_IMAGE_MAX_DIM each.  Memory: 2 bytes per pixel
 *                    (stored background) + 4 bit masks (coach.h).
 * FL_COACH_MAX_RUNS  set-bit runs of the two jersey masks in one frame.
 *                    Default 4096, range 64..65535 (16-bit union-find);
 *                    extra runs are dropped and counted.
 * FL_COACH_MAX_REGIONS  connected jersey regions in one frame.  Default 64,
 *                    range 4..1024; extra regions are dropped and counted.
 * FL_COACH_MAX_FEET  feet reported per frame (players seen).  Default 12
 *                    (two teams of six), range 1..64.
 * FL_COACH_MAX_BAND_PX  half width of the band searched for the legs on
 *                    each side of a robot's line, pixels.  Default 48,
 *                    range 4..255. */
#ifndef FL_COACH_MAX_WIDTH
#define FL_COACH_MAX_WIDTH 640
#endif
#ifndef FL_COACH_MAX_HEIGHT
#define FL_COACH_MAX_HEIGHT 480
#endif
#if FL_COACH_MAX_WIDTH < 32 || FL_COACH_MAX_WIDTH > FL_IMAGE_MAX_DIM || \
    FL_COACH_MAX_HEIGHT < 32 || FL_COACH_MAX_HEIGHT > FL_IMAGE_MAX_DIM
#error "FL_COACH_MAX_WIDTH and FL_COACH_MAX_HEIGHT must be in 32..FL_IMAGE_MAX_DIM"
#endif
#ifndef FL_COACH_MAX_RUNS
#define FL_COACH_MAX_RUNS 4096
#endif
#if FL_COACH_MAX_RUNS < 64 || FL_COACH_MAX_RUNS > 65535
#error "FL_COACH_MAX_RUNS must be in 64..65535"
#endif
#ifndef FL_COACH_MAX_REGIONS
#define FL_COACH_MAX_REGIONS 64
#endif
#if FL_COACH_MAX_REGIONS < 4 || FL_COACH_MAX_REGIONS > 1024
#error "FL_COACH_MAX_REGIONS must be in 4..1024"
#endif
#ifndef FL_COACH_MAX_FEET
#define FL_COACH_MAX_FEET 12
#endif
#if FL_COACH_MAX_FEET < 1 || FL_COACH_MAX_FEET > 64
#error "FL_COACH_MAX_FEET must be in 1..64"
#endif
#ifndef FL_COACH_MAX_BAND_PX
#define FL_COACH_MAX_BAND_PX 48
#endif
#if FL_COACH_MAX_BAND_PX < 4 || FL_COACH_MAX_BAND_PX > 255
#error "FL_COACH_MAX_BAND_PX must be in 4..255"
#endif

/* ---- observer reports (report.h, seed 003) -------------------------------
 * FL_REPORT_MAX        reports one coach frame (and one message) carries.
 *                      Default 10 (two SPL teams of 5).  Range 1..12 (the
 *                      assignment's tie-breaking perturbation needs
 *                      (FL_REPORT_MAX_PLAYERS + 1)^FL_REPORT_MAX < 2^39).
 *                      Sizes fl_report_msg_t and the message
 *                      (FL_REPORT_MSG_BYTES = 12 + 12 x FL_REPORT_MAX).
 * FL_REPORT_MAX_PLAYERS  claims (players) per team the coach's assignment
 *                      matches.  Default 6 (5 players and a substitute).
 *                      Range 1..8. */
#ifndef FL_REPORT_MAX
#define FL_REPORT_MAX 10
#endif
#if FL_REPORT_MAX < 1 || FL_REPORT_MAX > 12
#error "FL_REPORT_MAX must be in 1..12"
#endif
#ifndef FL_REPORT_MAX_PLAYERS
#define FL_REPORT_MAX_PLAYERS 6
#endif
#if FL_REPORT_MAX_PLAYERS < 1 || FL_REPORT_MAX_PLAYERS > 8
#error "FL_REPORT_MAX_PLAYERS must be in 1..8"
#endif

/* ---- odometry calibration (odocal.h) ------------------------------------
 * FL_ODOCAL_MAX_FIXES  an observer's sightings of one player the odometry
 *                      calibration keeps (one a second over a 30 s walk:
 *                      32).  The solve visits every pair (n^2 / 2).  Range
 *                      4..64 (the pair sums' int64 headroom). */
#ifndef FL_ODOCAL_MAX_FIXES
#define FL_ODOCAL_MAX_FIXES 32
#endif
#if FL_ODOCAL_MAX_FIXES < 4 || FL_ODOCAL_MAX_FIXES > 64
#error "FL_ODOCAL_MAX_FIXES must be in 4..64"
#endif

/* ---- skeleton and line crossings (skeleton.h, seed 002) -----------------
 * FL_SKEL_MAX_WIDTH/HEIGHT  largest mask, pixels.  Default 320 x 240 (a
 *                    humanoid's 640 x 480 frame subsampled by 2).  Range
 *                    16..FL_IMAGE_MAX_DIM each.
 * FL_SKEL_MAX_CONTOUR  contour list of the thinning (white pixels that may
 *                    still change, then the skeleton).  Default 16384,
 *                    range 64..1048576; pixels beyond it are never thinned
 *                    and are counted.
 * FL_SKEL_MAX_NODES  skeleton pixels of degree >= 3 per run.  Default 256,
 *                    range 8..4096 (more are counted).
 * FL_SKEL_MAX_CROSSINGS  crossings reported per run.  Default 16, range
 *                    1..255 (more are counted).
 * FL_SKEL_MAX_POINTS  skeleton pixels sampled per run (white points).
 *                    Default 48, range 0..1024.
 * Memory: 2 bytes per mask pixel (plus a 1-pixel border) + 4 B per
 * contour entry + 6 B per node + 16 B per crossing + 4 B per point: about
 * 220 KB at the defaults. */
#ifndef FL_SKEL_MAX_WIDTH
#define FL_SKEL_MAX_WIDTH 320
#endif
#ifndef FL_SKEL_MAX_HEIGHT
#define FL_SKEL_MAX_HEIGHT 240
#endif
#if FL_SKEL_MAX_WIDTH < 16 || FL_SKEL_MAX_WIDTH > FL_IMAGE_MAX_DIM || \
    FL_SKEL_MAX_HEIGHT < 16 || FL_SKEL_MAX_HEIGHT > FL_IMAGE_MAX_DIM
#error "FL_SKEL_MAX_WIDTH and FL_SKEL_MAX_HEIGHT must be in 16..FL_IMAGE_MAX_DIM"
#endif
#ifndef FL_SKEL_MAX_CONTOUR
#define FL_SKEL_MAX_CONTOUR 16384
#endif
#if FL_SKEL_MAX_CONTOUR < 64 || FL_SKEL_MAX_CONTOUR > 1048576
#error "FL_SKEL_MAX_CONTOUR must be in 64..1048576"
#endif
#ifndef FL_SKEL_MAX_NODES
#define FL_SKEL_MAX_NODES 256
#endif
#if FL_SKEL_MAX_NODES < 8 || FL_SKEL_MAX_NODES > 4096
#error "FL_SKEL_MAX_NODES must be in 8..4096"
#endif
#ifndef FL_SKEL_MAX_CROSSINGS
#define FL_SKEL_MAX_CROSSINGS 16
#endif
#if FL_SKEL_MAX_CROSSINGS < 1 || FL_SKEL_MAX_CROSSINGS > 255
#error "FL_SKEL_MAX_CROSSINGS must be in 1..255"
#endif
#ifndef FL_SKEL_MAX_POINTS
#define FL_SKEL_MAX_POINTS 48
#endif
#if FL_SKEL_MAX_POINTS < 0 || FL_SKEL_MAX_POINTS > 1024
#error "FL_SKEL_MAX_POINTS must be in 0..1024"
#endif

/* ---- seed 002's vision path (hlvision.h) ---------------------------------
 * The white-surrounded-by-green mask it builds is the skeleton stage's
 * input: its largest size is FL_SKEL_MAX_WIDTH x FL_SKEL_MAX_HEIGHT.
 * FL_HLV_MAX_RUNS      colour runs kept per scanned column (a column
 *                      through a pole over the field has about 6).  Default
 *                      32, range 4..255.
 * FL_HLV_MAX_OBJECTS   posts and poles per frame (4 posts and 2 poles on
 *                      hl3x2, plus clutter).  Default 16, range 2..64. */
#ifndef FL_HLV_MAX_RUNS
#define FL_HLV_MAX_RUNS 32
#endif
#if FL_HLV_MAX_RUNS < 4 || FL_HLV_MAX_RUNS > 255
#error "FL_HLV_MAX_RUNS must be in 4..255"
#endif
#ifndef FL_HLV_MAX_OBJECTS
#define FL_HLV_MAX_OBJECTS 16
#endif
#if FL_HLV_MAX_OBJECTS < 2 || FL_HLV_MAX_OBJECTS > 64
#error "FL_HLV_MAX_OBJECTS must be in 2..64"
#endif

/* ---- seed 004's corner stage (corners.h) ---------------------------------
 * FL_CORNERS_MAX_WIDTH/HEIGHT  largest frame, pixels.  Default 208 x 160
 *                    (the AIBO ERS-7's frame).  Range 16..FL_IMAGE_MAX_DIM
 *                    each.  Memory: 12 bytes per pixel (smoothed luma,
 *                    luma, gradient size, normal and doubled angle, the
 *                    response): 400 KB at the default.
 * FL_CORNERS_MAX_CAND  candidates (edge pixels) evaluated per frame.
 *                    Default 8192 (a quarter of the AIBO frame; a field
 *                    view has 1000..3000), range 64..1048576; more are
 *                    counted and not evaluated (bounded work on noise).
 * FL_CORNERS_MAX_CORNERS  labelled corners kept per frame.  Default 64,
 *                    range 4..1024.
 * FL_CORNERS_MAX_FEATURES  features (C, T-field, T-net, nets) per frame.
 *                    Default 16, range 2..255. */
#ifndef FL_CORNERS_MAX_WIDTH
#define FL_CORNERS_MAX_WIDTH 208
#endif
#ifndef FL_CORNERS_MAX_HEIGHT
#define FL_CORNERS_MAX_HEIGHT 160
#endif
#if FL_CORNERS_MAX_WIDTH < 16 || FL_CORNERS_MAX_WIDTH > FL_IMAGE_MAX_DIM || \
    FL_CORNERS_MAX_HEIGHT < 16 || FL_CORNERS_MAX_HEIGHT > FL_IMAGE_MAX_DIM
#error "FL_CORNERS_MAX_WIDTH and FL_CORNERS_MAX_HEIGHT must be in 16..FL_IMAGE_MAX_DIM"
#endif
#ifndef FL_CORNERS_MAX_CAND
#define FL_CORNERS_MAX_CAND 8192
#endif
#if FL_CORNERS_MAX_CAND < 64 || FL_CORNERS_MAX_CAND > 1048576
#error "FL_CORNERS_MAX_CAND must be in 64..1048576"
#endif
#ifndef FL_CORNERS_MAX_CORNERS
#define FL_CORNERS_MAX_CORNERS 64
#endif
#if FL_CORNERS_MAX_CORNERS < 4 || FL_CORNERS_MAX_CORNERS > 1024
#error "FL_CORNERS_MAX_CORNERS must be in 4..1024"
#endif
#ifndef FL_CORNERS_MAX_FEATURES
#define FL_CORNERS_MAX_FEATURES 16
#endif
#if FL_CORNERS_MAX_FEATURES < 2 || FL_CORNERS_MAX_FEATURES > 255
#error "FL_CORNERS_MAX_FEATURES must be in 2..255"
#endif

/* ---- the configuration fingerprint ---------------------------------------
 * FNV-1a over 32-bit words: the layout version, then every option above
 * (each one guarded by #ifndef in this file; the host test config.
 * fingerprint_lists_every_option keeps the list complete).  Each step,
 * for a fixed word, is a bijection of the running hash, so a change of
 * any one value always changes the fingerprint.  A constant expression of type uint32_t, equal
 * on every target (unsigned long arithmetic, reduced to 32 bits at each
 * step); fl_config_fingerprint() (common.h) is the library's own. */
#define FL_CFG_MIX_(h, v) \
    (((((h) ^ ((unsigned long)(v) & 0xFFFFFFFFUL)) * 16777619UL)) & 0xFFFFFFFFUL)
/* Mixed group by group (at most 16 options each): the whole chain written
 * as one nested expression went past clang's limit of 256 nested brackets.
 * Each group is an FNV-1a chain from the offset basis; the fingerprint
 * chains the groups' values.  Each option is still mixed by a bijection of
 * its group's hash, and each group's value by a bijection of the
 * fingerprint, so one changed value always changes the fingerprint. */
#define FL_CONFIG_FINGERPRINT ((uint32_t)(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(2166136261UL, FL_CFG_G0_), FL_CFG_G1_), FL_CFG_G2_), FL_CFG_G3_)))
#define FL_CFG_G0_ \
    (FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(2166136261UL, FL_ABI_VERSION), FL_IMAGE_MAX_DIM), FL_FUZZY_CELL_MM), \
    FL_FUZZY_MAX_NX), FL_FUZZY_MAX_NY), FL_FUZZY_MAX_REGIONS), FL_MCL_MAX_PARTICLES), \
    FL_UPF_MAX_PARTICLES), FL_SCAN_MAX_COLS), FL_SCAN_MAX_ROWS), FL_SCAN_MAX_FEET), \
    FL_LINES_MAX_POINTS), FL_LINES_MAX_SEGMENTS), FL_LINES_MAX_BUCKETS), FL_LINES_WTAB), \
    FL_CROSSINGS_MAX))
#define FL_CFG_G1_ \
    (FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(2166136261UL, FL_GOAL_MAX_POSTS), FL_CIRCLE_MAX_CHORDS), FL_CIRCLE_MAX_POINTS), \
    FL_LINES_NEAR_MAX), FL_OBS_MAX), FL_BEACON_MAX_RUNS), FL_BEACON_MAX_BLOBS), \
    FL_BEACON_MAX_FOUND), FL_HOMOG_MAX_POINTS), FL_COACH_MAX_WIDTH), FL_COACH_MAX_HEIGHT), \
    FL_COACH_MAX_RUNS), FL_COACH_MAX_REGIONS), FL_COACH_MAX_FEET), FL_COACH_MAX_BAND_PX), \
    FL_REPORT_MAX))
#define FL_CFG_G2_ \
    (FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(2166136261UL, FL_REPORT_MAX_PLAYERS), FL_ODOCAL_MAX_FIXES), FL_OBS_MAX_POINTS), \
    FL_SKEL_MAX_WIDTH), FL_SKEL_MAX_HEIGHT), FL_SKEL_MAX_CONTOUR), FL_SKEL_MAX_NODES), \
    FL_SKEL_MAX_CROSSINGS), FL_SKEL_MAX_POINTS), FL_HLV_MAX_RUNS), FL_HLV_MAX_OBJECTS), \
    FL_RELMAP_NX), FL_RELMAP_NY), FL_RELMAP_MAX_CAND), FL_RELMAP_MAX_OBS), \
    FL_RELMAP_MAX_WHITE))
#define FL_CFG_G3_ \
    (FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(FL_CFG_MIX_(2166136261UL, FL_CORNERS_MAX_WIDTH), FL_CORNERS_MAX_HEIGHT), FL_CORNERS_MAX_CAND), \
    FL_CORNERS_MAX_CORNERS), FL_CORNERS_MAX_FEATURES))

#endif /* FIELDLOC_CONFIG_H */
