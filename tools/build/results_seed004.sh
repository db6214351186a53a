#!/bin/sh
# The section "Seed 004's corner features" of docs/RESULTS.md: seed 004's
# corner stage (C, T-field, T-net corners and the nets; include/fieldloc/
# corners.h) beside the L/T/X path (seed 000's crossings, posts, beacons)
# on the AIBO field aibo2004, in one run: detection scoring (eval-detect's
# corner lines), the frames walks of each localizer through each vision
# path (`simulate --field aibo2004 --frames --vision ltx|corners|both`) and
# the cost per frame (`bench --only corners`).  tools/build/results.sh runs
# it (and times it); it can also run alone, to try the section:
#
#   Usage: tools/build/results_seed004.sh CLI WORK LOCALIZERS
#     CLI         the fieldloc binary (build/fieldloc)
#     WORK        a folder for the runs (made; a cache file there is reused:
#                 simulate re-renders one that holds another walk)
#     LOCALIZERS  "fuzzy mcl upf relmap" (space-separated)
#   writes the markdown to WORK/seed004.md; any failing command: its output
#   tail and a message on stderr, exit status 1.
#
# Cost with the defaults: about 80 s of CPU, 140 s wall clock with
# LOC_JOBS=1 on 2 cores shared with other work.  eval-detect a few seconds
# (it scores every detector, the corner part on 8 fixtures and 36 random
# frames), bench --only corners 2 s (wall clock: run first, alone), a
# frames walk 25 to 40 s to render per vision path and walk seed (three
# per seed, LOC_JOBS at a time), every other localizer reading the walk's
# cache in a few seconds.
#
# Environment:
#   S4_SEEDS      walk seeds (default 1); a stochastic localizer (parameter
#                 "seed") runs with --param seed=1
#   LOC_JOBS      renders at a time (default: the online CPUs)
#   OBS_CACHE_DIR copy DIR/aibo2004.SEED.obs (ltx), DIR/aibo2004.SEED.corners.obs
#                 and DIR/aibo2004.SEED.both.obs into WORK before the walks
#   LTX_OBS_DIR   results.sh's work folder: its aibo2004.SEED.obs (the ltx
#                 walk its fuzzy run rendered) is copied when present, so the
#                 ltx walk is not rendered twice
#   SKIP_BENCH=1  no bench rows (the section says so)
#   DRY_RUN=1     print the commands, run none, write no markdown (only the
#                 runs' .cmd files under WORK)
set -u
CLI=${1:?usage: results_seed004.sh CLI WORK LOCALIZERS}
WORK=${2:?usage: results_seed004.sh CLI WORK LOCALIZERS}
LOCALIZERS=${3:?usage: results_seed004.sh CLI WORK LOCALIZERS}
S4_SEEDS=${S4_SEEDS:-"1"}
LOC_JOBS=${LOC_JOBS:-$(nproc)}
OBS_CACHE_DIR=${OBS_CACHE_DIR:-}
LTX_OBS_DIR=${LTX_OBS_DIR:-}
SKIP_BENCH=${SKIP_BENCH:-0}
DRY_RUN=${DRY_RUN:-0}
F=aibo2004
VISIONS="ltx corners both"
die() {
    echo "results_seed004: FAILED: $*" >&2
    exit 1
}
# shellcheck disable=SC2034  # read by results_lib.sh's run
RESULTS_NAME=results_seed004
. "$(dirname "$0")/results_lib.sh"   # run LOG CMD...

mkdir -p "$WORK/runs" || die "cannot create $WORK/runs"
rm -f "$WORK/seed004.md"
start=$(date +%s)

# the stochastic localizers (parameter "seed"): run with --param seed=1
STOCHASTIC=$(python3 tools/build/loc_table.py catalogue --cli "$CLI" | awk '/stochastic=1/ { print $1 }' | tr '\n' ' ') ||
    die "tools/build/loc_table.py catalogue failed"
# the cache file of a walk: ltx under the name results.sh's walks use
cache() {   # SEED VISION
    if [ "$2" = ltx ]; then echo "$WORK/$F.$1.obs"; else echo "$WORK/$F.$1.$2.obs"; fi
}
# the simulate command of one run (printed in the section as it ran)
simcmd() {   # LOCALIZER VISION SEED
    p=""
    case " $STOCHASTIC " in *" $1 "*) p=" --param seed=1" ;; esac
    echo "$CLI simulate --field $F --frames --vision $2 --localizer $1 --seed $3 --quiet --obs-cache $(cache "$3" "$2")$p"
}

# ---- detection scoring and cost per frame (wall clock: alone, first)
run "$WORK/eval.out" "$CLI" eval-detect
if [ "$DRY_RUN" != 1 ]; then
    for k in aibo_corners_precision aibo_corners_recall; do
        grep -q "^$k " "$WORK/eval.out" || die "eval-detect: no $k line (output in $WORK/eval.out)"
    done
fi
t_eval=$(( $(date +%s) - start ))
if [ "$SKIP_BENCH" = 1 ]; then
    echo "results_seed004: SKIP_BENCH=1: no bench --only corners" >&2
else
    run "$WORK/bench.log" "$CLI" bench --only corners --out "$WORK/bench.tsv"
    [ "$DRY_RUN" = 1 ] || grep -q '^corners_208x160' "$WORK/bench.tsv" ||
        die "bench --only corners: no corners_208x160 row (output in $WORK/bench.log)"
fi
t_bench=$(( $(date +%s) - start - t_eval ))

# ---- the walks: copy caches, render each (seed, vision) once by the fuzzy
# grid's run ($LOC_JOBS at a time), then every other localizer reads them
copied=""
for s in $S4_SEEDS; do
    for v in $VISIONS; do
        c=$(cache "$s" "$v")
        b=$(basename "$c")
        if [ -n "$OBS_CACHE_DIR" ] && [ -f "$OBS_CACHE_DIR/$b" ]; then
            cp "$OBS_CACHE_DIR/$b" "$c" || die "cannot copy $OBS_CACHE_DIR/$b"
            copied="$copied $b"
        elif [ "$v" = ltx ] && [ -n "$LTX_OBS_DIR" ] && [ -f "$LTX_OBS_DIR/$b" ]; then
            cp "$LTX_OBS_DIR/$b" "$c" || die "cannot copy $LTX_OBS_DIR/$b"
            copied="$copied $b"
        fi
    done
done
[ -z "$copied" ] || echo "results_seed004: observation caches copied:$copied" >&2
first=""
for s in $S4_SEEDS; do
    for v in $VISIONS; do
        simcmd fuzzy "$v" "$s" > "$WORK/runs/fuzzy.$v.s$s.cmd"
        first="$first $WORK/runs/fuzzy.$v.s$s"
    done
done
for r in $first; do echo "results_seed004: $(cat "$r.cmd")" >&2; done
if [ "$DRY_RUN" != 1 ]; then
    # shellcheck disable=SC2086,SC2016  # $1: the inner sh's argument
    printf '%s\n' $first | xargs -P "$LOC_JOBS" -I{} sh -c 'sh "$1.cmd" > "$1.out" 2>&1' sh {}
    for r in $first; do
        grep -q '^flips ' "$r.out" || { tail -n 20 "$r.out" >&2; die "\`$(cat "$r.cmd")\` failed (output in $r.out)"; }
    done
fi
for s in $S4_SEEDS; do
    for l in $LOCALIZERS; do
        [ "$l" = fuzzy ] && continue
        for v in $VISIONS; do
            r=$WORK/runs/$l.$v.s$s
            simcmd "$l" "$v" "$s" > "$r.cmd"
            # shellcheck disable=SC2046
            run "$r.out" $(cat "$r.cmd")
            [ "$DRY_RUN" = 1 ] || grep -q '^flips ' "$r.out" || die "no summary lines in $r.out"
        done
    done
done
t_walks=$(( $(date +%s) - start - t_eval - t_bench ))
[ "$DRY_RUN" = 1 ] && exit 0

# ---- the section
# KEY FILE: the value of a summary line ("-" when absent)
val() {
    v=$(awk -v k="$1" '$1 == k { print $2; exit }' "$2")
    echo "${v:--}"
}
# A / B to two decimals; "-" when either is not a positive number
ratio() {
    awk -v a="$1" -v b="$2" 'BEGIN {
        if (a !~ /^[0-9.]+$/ || b !~ /^[0-9.]+$/ || b + 0 <= 0) { print "-"; exit }
        printf "%.2f\n", a / b }'
}
# verdict A OP B: met / **MISSED** (a "-": not measured)
cmp() {
    awk -v a="$1" -v op="$2" -v b="$3" 'BEGIN {
        if (a !~ /^[0-9.]+$/ || b !~ /^[0-9.]+$/) { print "**MISSED** (not measured)"; exit }
        ok = (op == "<=") ? (a + 0 <= b + 0) : (a + 0 < b + 0)
        print ok ? "met" : "**MISSED**" }'
}
bench_ns() {   # ROW: ns per frame as ms with two decimals
    awk -v k="$1" '$1 == k { printf "%.2f", $2 / 1e6; f = 1 } END { if (!f) printf "-" }' "$WORK/bench.tsv"
}
{
echo "## Seed 004's corner features"
echo
echo "Seed 004's own vision path on the AIBO field \`aibo2004\` (include/fieldloc/corners.h: Sojka's"
echo "gradient corners on the 208x160 frame, kept on field-line colour, labelled open / closed /"
echo "net-closed, paired into C, T-field and T-net features; the goal colour regions as nets) beside"
echo "seed 000's L/T/X path (crossings, posts, beacons), measured in one run of"
echo "tools/build/results_seed004.sh. Targets (issue 21): corner features precision >= 0.9 and recall"
echo ">= 0.8 within 3 m; localization with the corner path alone no worse than with the L/T/X path;"
echo "with both, better than either."
echo
echo "### Detection"
echo
echo "Command: \`$CLI eval-detect\` (its aibo2004 corner lines; tools/eval/eval_corners.c): the corner"
echo "stage on the rendered AIBO fixtures and random rendered frames, its features matched to the map's"
echo "at the true pose within 3 m, per type precision, recall and range error (mm)."
echo
echo "| target | measured | |"
echo "|---|---|---|"
p=$(val aibo_corners_precision "$WORK/eval.out")
r=$(val aibo_corners_recall "$WORK/eval.out")
echo "| corner features precision >= 0.9 | $p | $(cmp 0.9 '<=' "$p") |"
echo "| corner features recall >= 0.8 | $r | $(cmp 0.8 '<=' "$r") |"
echo
echo '```'
echo "\$ $CLI eval-detect | grep -A5 'corner features'"
grep -A5 '^aibo2004 corner features' "$WORK/eval.out"
echo '```'
echo
echo "### Walks through each vision path"
echo
echo "Command per run: \`$CLI simulate --field $F --frames --vision V --localizer L --seed SEED --quiet"
echo "--obs-cache FILE [--param seed=1]\`, walk seeds $(echo "$S4_SEEDS" | tr ' ' ,), a stochastic localizer with"
echo "random-generator seed 1. The field's built-in walk (fixtures/walks/aibo2004.walk) rendered"
echo "with the aibo-ers7 camera at the true pose, the vision path on every 3rd step (10 Hz): \`ltx\`"
echo "fl_vision_frame, \`corners\` the corner stage alone (its nets from fl_vision_frame's goal"
echo "posts), \`both\` the two lists. Each (seed, path) rendered once, by the fuzzy grid's run, into"
echo "FILE; the other localizers read it. Columns: the simulate summary lines (definitions at the top"
echo "of tools/cli/cmd_simulate.c): position and heading RMSE after convergence outside the kidnap's"
echo "and penalty's recovery windows, convergence and kidnap recovery time, symmetric flips; \`/ ltx\`:"
echo "the ratio to the same localizer's ltx run (below 1: better than ltx). One walk per row: a"
echo "single seed's figures, not a spread."
echo
echo "| localizer | seed | vision | pos RMSE mm | / ltx | heading RMSE deg | / ltx | converge s | kidnap recover s | / ltx | flips |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for s in $S4_SEEDS; do
    for l in $LOCALIZERS; do
        base=$WORK/runs/$l.ltx.s$s.out
        for v in $VISIONS; do
            o=$WORK/runs/$l.$v.s$s.out
            pp=$(val pos_rmse_mm "$o"); hh=$(val heading_rmse_deg "$o"); kk=$(val kidnap_recover_s "$o")
            echo "| $l | $s | $v | $pp | $(ratio "$pp" "$(val pos_rmse_mm "$base")") | $hh |" \
                 "$(ratio "$hh" "$(val heading_rmse_deg "$base")") | $(val converge_s "$o") | $kk |" \
                 "$(ratio "$kk" "$(val kidnap_recover_s "$base")") | $(val flips "$o") |"
        done
    done
done
echo
echo "The localization targets per localizer and seed, on position RMSE (the column above):"
echo
echo "| localizer | seed | corners alone no worse than ltx | both better than either |"
echo "|---|---|---|---|"
for s in $S4_SEEDS; do
    for l in $LOCALIZERS; do
        pl=$(val pos_rmse_mm "$WORK/runs/$l.ltx.s$s.out")
        pc=$(val pos_rmse_mm "$WORK/runs/$l.corners.s$s.out")
        pb=$(val pos_rmse_mm "$WORK/runs/$l.both.s$s.out")
        best=$(awk -v a="$pl" -v b="$pc" 'BEGIN { if (a !~ /^[0-9.]+$/) print b; else if (b !~ /^[0-9.]+$/) print a; else print (a + 0 < b + 0) ? a : b }')
        echo "| $l | $s | $pc vs $pl: $(cmp "$pc" '<=' "$pl") | $pb vs $best: $(cmp "$pb" '<' "$best") |"
    done
done
echo
echo "The summary lines as printed, per run; for the fuzzy grid's (rendering) runs also what vision"
echo "reported per kind against the map at the true pose (\`# vision\` lines; the cost per frame: below)."
echo
echo '```'
for s in $S4_SEEDS; do
    for l in $LOCALIZERS; do
        for v in $VISIONS; do
            r=$WORK/runs/$l.$v.s$s
            echo "\$ $(cat "$r.cmd")"
            if [ "$l" = fuzzy ]; then
                grep -E '^# vision' "$r.out"
            fi
            grep -E '^# localizer:|^(pos_rmse_mm|heading_rmse_deg|converge_s|kidnap_recover_s|flips) ' "$r.out"
        done
    done
done
echo '```'
echo
echo "### Cost per frame"
echo
if [ "$SKIP_BENCH" = 1 ]; then
echo "**Skipped** (SKIP_BENCH=1)."
else
echo "Command: \`$CLI bench --only corners --out bench.tsv\` (tools/bench/bench_corners.c): 16 rendered"
echo "aibo2004 frames (planar YCbCr, random poses, head 5-25 degrees down), wall clock on this machine"
echo "under its load (ns per frame): \`vision_aibo_208x160\` the L/T/X path (fl_vision_frame),"
echo "\`corners_208x160\` the corner stage after it on the same frames, \`corners_worst_208\` its"
echo "slowest frame. The \`corners\` path in frames mode costs the first two rows (its nets take"
echo "fl_vision_frame's posts), \`both\` the same."
echo
echo "| path | ms per frame (mean) | / ltx |"
echo "|---|---|---|"
vl=$(bench_ns vision_aibo_208x160); vc=$(bench_ns corners_208x160)
vb=$(awk -v a="$vl" -v b="$vc" 'BEGIN { if (a ~ /^[0-9.]+$/ && b ~ /^[0-9.]+$/) printf "%.2f", a + b; else printf "-" }')
echo "| ltx (fl_vision_frame) | $vl | 1.00 |"
echo "| the corner stage alone (fl_corners_run) | $vc | $(ratio "$vc" "$vl") |"
echo "| corners or both (the two) | $vb | $(ratio "$vb" "$vl") |"
echo "| the corner stage's slowest frame | $(bench_ns corners_worst_208) | |"
echo
echo '```'
cat "$WORK/bench.tsv"
echo '```'
fi
echo
echo "Time of this section: $(( $(date +%s) - start )) s (eval-detect $t_eval s, bench $t_bench s, the walks $t_walks s;"
echo "renders at a time: $LOC_JOBS)."
echo
} > "$WORK/seed004.md" || die "cannot write $WORK/seed004.md"
echo "results_seed004: wrote $WORK/seed004.md" >&2
