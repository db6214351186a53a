#!/bin/sh
# tools/bench/callgrind_vision.sh - instructions per frame of the whole vision path
# (fl_vision_frame) under callgrind: `fieldloc detect FRAME --repeat N` for
# two N, only the calls of fl_vision_frame collected; per frame = difference
# / (N2 - N1).  Frames: the noise frames of `make bench` section vision
# (written by `fieldloc bench --noise-frames`, same pose as the bench),
# the rendered 2013 fixture spl2013_640_goal and, when ../shared/realdata is
# there, modern real 640x480 frames: physar black1 point 2 (far white goal,
# centre circle, sunlight; its record's head angles and IMU AngleX/AngleY,
# or its accelerometer's tilt) and the scarrix
# shots-on-goal and NaoTH referee frames (white goals, robots, a person;
# head level); field spl2020,
# camera nao6-top-640.  Budget: 3 M instructions per 640x480 frame.
# Usage: sh tools/bench/callgrind_vision.sh [BUILD_DIR]   (default build; needs valgrind)
# Prints: callgrind NAME instructions_per_frame
B=${1:-build}
CLI=$B/fieldloc
RD=../shared/realdata
command -v valgrind >/dev/null 2>&1 || { echo "callgrind: valgrind not installed, skipped"; exit 0; }
[ -x "$CLI" ] || { echo "callgrind: $CLI not built"; exit 1; }
TMP=${TMPDIR:-/tmp}/fl_callgrind_vision.$$
mkdir -p "$TMP"
"$CLI" bench --noise-frames "$TMP" || { echo "callgrind: noise frames not written"; rm -rf "$TMP"; exit 1; }
CG_FUNC=fl_vision_frame
CG_CMD=detect
. "$(dirname "$0")/callgrind_lib.sh"
run() {  # run NAME ARGS...
    name=$1; shift
    f=$(cg_per_call "$@") || { echo "callgrind $name failed"; return; }
    awk -v n="$name" -v f="$f" 'BEGIN { printf "callgrind %-24s %10.0f instr/frame\n", n, f }'
}
for w in 320 640; do
    for k in noise classnoise; do
        run "vision_${k}_$w" --field spl2013 --camera nao4-top-$w --neck 450 \
            --head 0.261799 0 "$TMP/vision_${k}_$w.ppm"
    done
done
run spl2013_640_goal --field spl2013 --camera nao4-top-640 --head 0 0 \
    fixtures/frames/spl2013_640_goal.ppm
PHYSAR=$RD/physar_landmark_based_slam_dataset_black1_point2_top.ppm
SCARRIX=$RD/scarrix_Detect_Foot_danu_gaolie_shots_on_goal_2002_upper.ppm
NAOTH=$RD/BerlinUnited_NaoTH-Deeplearning_referee_pose_test_image.ppm
if [ -f "$PHYSAR" ] && [ -f "$SCARRIX" ] && [ -f "$NAOTH" ]; then
    # head pitch / yaw and IMU AngleX / AngleY of physar_poses.csv, black1_point2
    run physar_point2_real640 --field spl2020 --camera nao6-top-640 --head 0.0306 0.0521 \
        --imu -0.0004 -0.1615 "$PHYSAR"
    # the same with the torso tilt of its accelerometer (localize --physar --imu accel)
    run physar_point2_accel_real640 --field spl2020 --camera nao6-top-640 --head 0.0306 0.0521 \
        --imu 0.0028 -0.0722 "$PHYSAR"
    run scarrix_2002_real640 --field spl2020 --camera nao6-top-640 --head 0 0 "$SCARRIX"
    # the slowest real frame of `make bench` (vision_naoth_640x480)
    run naoth_referee_real640 --field spl2020 --camera nao6-top-640 --head 0 0 "$NAOTH"
else
    echo "callgrind: modern real frames skipped: $RD not found"
fi
rm -rf "$TMP"
