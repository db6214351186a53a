#!/bin/sh
# tools/bench/perf.sh - hot functions of the column scanner under `perf record`:
# `fieldloc scan FRAME --repeat N` (full resolution and the default grid,
# YUYV and RGB), then `perf report` sorted by self time, top 12 lines.
# Usage: sh tools/bench/perf.sh [BUILD_DIR]   (default build; needs perf)
B=${1:-build}
CLI=$B/fieldloc
RD=../shared/realdata
command -v perf >/dev/null 2>&1 || { echo "perf: not installed, skipped"; exit 0; }
[ -x "$CLI" ] || { echo "perf: $CLI not built"; exit 1; }
FRAME=$RD/IntelligentRoboticsLab_Datasets_qvga_000001.ppm
[ -f "$FRAME" ] || FRAME=fixtures/frames/spl2013_goal_both.ppm
TMP=${TMPDIR:-/tmp}/fl_perf.$$
mkdir -p "$TMP"
for args in "--format yuyv --full" "--format yuyv" "--format rgb --full"; do
    echo "== perf: fieldloc scan $(basename "$FRAME") $args --repeat 20000"
    if perf record -q -o "$TMP/perf.data" "$CLI" scan "$FRAME" $args --repeat 20000 --quiet >/dev/null 2>&1; then
        perf report -i "$TMP/perf.data" --no-children --stdio 2>/dev/null |
            grep -E '^ +[0-9]' | head -12
    else
        echo "perf record failed (perf_event_paranoid?)"
    fi
done
rm -rf "$TMP"
