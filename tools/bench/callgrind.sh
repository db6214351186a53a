#!/bin/sh
# tools/bench/callgrind.sh - instructions per frame of the column scanner under
# callgrind: `fieldloc scan FRAME --repeat N` for two N, only the calls of
# fl_scan_frame collected (--toggle-collect); per frame = difference / (N2 - N1),
# so start-up, image loading and table building cancel out.
# Usage: sh tools/bench/callgrind.sh [BUILD_DIR]   (default build; needs valgrind)
# Prints: callgrind NAME instructions_per_frame instructions_per_pixel
# (classify_only_*: instructions inside the word functions only)
B=${1:-build}
CLI=$B/fieldloc
RD=../shared/realdata
command -v valgrind >/dev/null 2>&1 || { echo "callgrind: valgrind not installed, skipped"; exit 0; }
[ -x "$CLI" ] || { echo "callgrind: $CLI not built"; exit 1; }
TMP=${TMPDIR:-/tmp}/fl_callgrind.$$
mkdir -p "$TMP"
COLLECT=fl_scan_frame
refs() {  # refs N ARGS...: instructions collected inside $COLLECT
    n=$1; shift
    valgrind --tool=callgrind --toggle-collect="$COLLECT" --callgrind-out-file="$TMP/out" \
        "$CLI" scan "$@" --repeat "$n" --quiet 2>&1 | sed -n 's/.*refs: *//p' | tr -d ,
}
run() {  # run NAME W H ARGS...
    name=$1; w=$2; h=$3; shift 3
    a=$(refs 2 "$@"); b=$(refs 6 "$@")
    if [ -z "$a" ] || [ -z "$b" ]; then echo "callgrind $name failed"; return; fi
    awk -v n="$name" -v a="$a" -v b="$b" -v px=$((w * h)) \
        'BEGIN { f = (b - a) / 4; printf "callgrind %-28s %10.0f instr/frame %6.2f instr/pixel\n", n, f, f / px }'
}
REAL=$RD/IntelligentRoboticsLab_Datasets_qvga_000001.ppm
REND=fixtures/frames/spl2013_goal_both.ppm
for f in yuyv rgb; do
    if [ -f "$REAL" ]; then
        run "full_${f}_real320" 320 240 "$REAL" --format $f --full
        run "default_${f}_real320" 320 240 "$REAL" --format $f
    fi
    if [ -f "$REND" ]; then
        run "full_${f}_rend320" 320 240 "$REND" --format $f --full
        run "default_${f}_rend320" 320 240 "$REND" --format $f
    fi
done
# Uniform noise: no column has a run of N green pixels, so phase A stops
# the border search early.  The worst case is topnoise: a carpet strip on
# top, every pixel of every row classified and checked; classify_only is
# the classification alone there (the word functions: table lookups and
# packing, nothing else), the floor of any change outside them.
if "$CLI" bench --noise-frames "$TMP" >/dev/null 2>&1; then
    for f in yuyv rgb; do
        run "full_${f}_noise320" 320 240 "$TMP/vision_noise_320.ppm" --format $f --full
    done
    # the scanner's worst case: 12 carpet rows on top, uniform noise below
    # (all 240 rows classified), and there the classification alone
    for f in yuyv rgb; do
        run "full_${f}_topnoise320" 320 240 "$TMP/scan_topnoise_320.ppm" --format $f --full
        run "default_${f}_topnoise320" 320 240 "$TMP/scan_topnoise_320.ppm" --format $f
        COLLECT='word_*'
        run "classify_only_${f}_topnoise320" 320 240 "$TMP/scan_topnoise_320.ppm" --format $f --full
        COLLECT=fl_scan_frame
    done
fi
rm -rf "$TMP"
