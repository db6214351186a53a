#!/bin/sh
# tools/bench/callgrind_vision.sh - instructions per frame of the whole vision path
# (fl_vision_frame) under callgrind: `fieldloc detect FRAME --repeat N` for
# two N, only the calls of fl_vision_frame collected; per frame = difference
# / (N2 - N1).  Frames: the noise frames of `make bench` section vision
# (written by `fieldloc bench --noise-frames`, same pose as the bench) and
# the fixture spl2013_640_goal.
# Usage: sh tools/bench/callgrind_vision.sh [BUILD_DIR]   (default build; needs valgrind)
# Prints: callgrind NAME instructions_per_frame
B=${1:-build}
CLI=$B/fieldloc
command -v valgrind >/dev/null 2>&1 || { echo "callgrind: valgrind not installed, skipped"; exit 0; }
[ -x "$CLI" ] || { echo "callgrind: $CLI not built"; exit 1; }
TMP=${TMPDIR:-/tmp}/fl_callgrind_vision.$$
mkdir -p "$TMP"
"$CLI" bench --noise-frames "$TMP" || { echo "callgrind: noise frames not written"; rm -rf "$TMP"; exit 1; }
refs() {  # refs N ARGS...: instructions collected inside fl_vision_frame
    n=$1; shift
    valgrind --tool=callgrind --toggle-collect=fl_vision_frame --callgrind-out-file="$TMP/out" \
        "$CLI" detect "$@" --repeat "$n" 2>&1 >/dev/null | sed -n 's/.*refs: *//p' | tr -d ,
}
run() {  # run NAME ARGS...
    name=$1; shift
    a=$(refs 1 "$@"); b=$(refs 3 "$@")
    if [ -z "$a" ] || [ -z "$b" ]; then echo "callgrind $name failed"; return; fi
    awk -v n="$name" -v a="$a" -v b="$b" \
        'BEGIN { printf "callgrind %-24s %10.0f instr/frame\n", n, (b - a) / 2 }'
}
for w in 320 640; do
    for k in noise classnoise; do
        run "vision_${k}_$w" --field spl2013 --camera nao4-top-$w --neck 450 \
            --head 0.261799 0 "$TMP/vision_${k}_$w.ppm"
    done
done
run spl2013_640_goal --field spl2013 --camera nao4-top-640 --head 0 0 \
    fixtures/frames/spl2013_640_goal.ppm
rm -rf "$TMP"
