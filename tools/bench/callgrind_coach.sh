#!/bin/sh
# tools/bench/callgrind_coach.sh - instructions per frame of the coach's image
# path (fl_coach_frame) under callgrind: `fieldloc coach FRAME --repeat N`
# for two N, only the calls of fl_coach_frame collected; per frame =
# difference / (N2 - N1), so loading, the fit and set-up cancel out.
# Frames: the committed coach fixtures (fixtures/coach/: the default coach's
# 640x480 view with two robots, the empty field as background, its points),
# and the same frame without the background (a* alone).
# Usage: sh tools/bench/callgrind_coach.sh [BUILD_DIR]   (default build; needs valgrind)
# Prints: callgrind NAME instructions_per_frame instructions_per_pixel
B=${1:-build}
CLI=$B/fieldloc
FX=fixtures/coach
command -v valgrind >/dev/null 2>&1 || { echo "callgrind: valgrind not installed, skipped"; exit 0; }
[ -x "$CLI" ] || { echo "callgrind: $CLI not built"; exit 1; }
[ -f "$FX/coach_two.ppm" ] || { echo "callgrind: $FX not found, coach skipped"; exit 0; }
TMP=${TMPDIR:-/tmp}/fl_callgrind_coach.$$
mkdir -p "$TMP"
CG_FUNC=fl_coach_frame
CG_CMD=coach
. "$(dirname "$0")/callgrind_lib.sh"
run() {  # run NAME ARGS...
    name=$1; shift
    f=$(cg_per_call "$@") || { echo "callgrind $name failed"; return; }
    awk -v n="$name" -v f="$f" -v px=307200 \
        'BEGIN { printf "callgrind %-28s %10.0f instr/frame %6.2f instr/pixel\n", n, f, f / px }'
}
run coach_frame_640x480 "$FX/coach_two.ppm" --points "$FX/coach.points" \
    --background "$FX/coach_empty.ppm"
run coach_frame_nobg_640x480 "$FX/coach_two.ppm" --points "$FX/coach.points"
rm -rf "$TMP"
