#!/bin/sh
# tools/bench/callgrind_loc.sh - instructions per frame of every localizer of
# the catalogue under callgrind: `fieldloc bench --loc-frames NAME --repeat N`
# (10 s of the spl2013 walk, then N times the same frame: predict, update
# with 5 observations, estimate; tools/bench/bench_loc.c), only the calls of
# bench_loc_frame collected, so per frame = collected / N (the walk before
# and the state restores between frames are not counted; every repetition
# does the same work, so one N suffices).
# For a localizer whose belief is a set of samples, the instructions per
# particle per observation: the mixed difference of four runs (P1, P2
# particles; K1, K2 observations; parameter n_particles):
#   (I(P2,K2) - I(P2,K1) - I(P1,K2) + I(P1,K1)) / ((P2 - P1) (K2 - K1))
# is the coefficient of P x K in I = a + b P + c K + d P K: what each
# observation costs each particle (placing it, associating, the likelihood),
# without the per-particle work done once per frame (motion, resampling,
# estimate) or the per-observation work done once.
# Usage: sh tools/bench/callgrind_loc.sh [BUILD_DIR]   (default build)
# The same frame again with the localizer's vision preset and a view
# (--vision: what simulate --frames and demo run).
# Prints: callgrind loc_NAME_frame N instr/frame R x fuzzy state B bytes
#         (its parts: the inclusive counts of fl_loc_predict, fl_loc_update
#         and fl_loc_estimate per frame, from callgrind_annotate)
#         callgrind loc_NAME_frame_vision N instr/frame R x fuzzy
#         callgrind loc_NAME_particle_obs N instr/particle/obs (P1..P2, K1..K2)
#         callgrind ukf_predict / ukf_update N instr/call (the UKF step of one
#         particle, ukf.h: every call of fl_ukf_predict_odo or
#         fl_ukf_update_obs, inclusive, over `fieldloc ukf-check --n 2000
#         --fixed-only`: random filter lives on a 10 m field)
B=${1:-build}
CLI=$B/fieldloc
N=10
command -v valgrind >/dev/null 2>&1 || { echo "callgrind_loc: valgrind not installed, skipped"; exit 0; }
[ -x "$CLI" ] || { echo "callgrind_loc: $CLI not built"; exit 1; }
TMP=${TMPDIR:-/tmp}/fl_callgrind_loc.$$
mkdir -p "$TMP"
refs() {  # refs NAME ARGS...: instructions collected inside bench_loc_frame (log in $TMP/log)
    name=$1; shift
    valgrind --tool=callgrind --toggle-collect=bench_loc_frame --callgrind-out-file="$TMP/out" \
        "$CLI" bench --loc-frames "$name" --repeat $N "$@" >"$TMP/log" 2>&1
    sed -n 's/.*refs: *//p' "$TMP/log" | tr -d ,
}
ref=
refv=
for name in $("$CLI" bench --loc-list); do
    i=$(refs "$name")
    LINE=$(grep '^loc ' "$TMP/log")
    if [ -z "$i" ] || [ -z "$LINE" ]; then echo "callgrind loc_$name failed"; continue; fi
    state=$(echo "$LINE" | awk '{print $4}')
    samples=$(echo "$LINE" | awk '{print $6}')
    [ "$name" = fuzzy ] && ref=$i
    parts=$(callgrind_annotate --inclusive=yes "$TMP/out" 2>/dev/null | tr -d , | awk -v N=$N '
        /localizer\.c:fl_loc_(predict|update|estimate) \[/ {
            f = $0; sub(/.*fl_loc_/, "", f); sub(/ .*/, "", f); v[f] = $1 / N }
        END { if (("predict" in v) && ("update" in v) && ("estimate" in v))
                  printf "  (predict %.0f update %.0f estimate %.0f)", v["predict"], v["update"], v["estimate"] }')
    awk -v n="loc_${name}_frame" -v i="$i" -v r="${ref:-0}" -v N=$N -v s="$state" -v p="$samples" \
        -v parts="$parts" \
        'BEGIN { f = i / N; printf "callgrind %-28s %10.0f instr/frame", n, f;
                 if (r > 0) printf "  %5.3f x fuzzy", i / r;
                 printf "  state %d B", s; if (p > 0) printf "  %d samples", p; printf "%s\n", parts }'
    # the same frame with the vision preset and a view (--vision)
    v=$(refs "$name" --vision)
    if [ -z "$v" ]; then echo "callgrind loc_${name}_frame_vision failed"; continue; fi
    [ "$name" = fuzzy ] && refv=$v
    awk -v n="loc_${name}_frame_vision" -v i="$v" -v r="${refv:-0}" -v N=$N \
        'BEGIN { printf "callgrind %-28s %10.0f instr/frame", n, i / N;
                 if (r > 0) printf "  %5.3f x fuzzy", i / r; printf "\n" }'
    if [ "$samples" -gt 0 ] 2>/dev/null; then
        p1=64; p2=256; k1=1; k2=5
        # a localizer of fewer particles (upf: capacity 12): 4..12
        "$CLI" bench --loc-frames "$name" --repeat 1 --param n_particles=$p2 >/dev/null 2>&1 ||
            { p1=4; p2=12; }
        a=$(refs "$name" --param n_particles=$p1 --obs $k1); b=$(refs "$name" --param n_particles=$p1 --obs $k2)
        c=$(refs "$name" --param n_particles=$p2 --obs $k1); d=$(refs "$name" --param n_particles=$p2 --obs $k2)
        if [ -z "$a" ] || [ -z "$b" ] || [ -z "$c" ] || [ -z "$d" ]; then
            echo "callgrind loc_${name}_particle_obs failed"; continue
        fi
        awk -v n="loc_${name}_particle_obs" -v a="$a" -v b="$b" -v c="$c" -v d="$d" -v N=$N \
            -v p1=$p1 -v p2=$p2 -v k1=$k1 -v k2=$k2 \
            'BEGIN { printf "callgrind %-28s %10.1f instr/particle/obs  (%d..%d particles x %d..%d obs; per frame %.0f %.0f %.0f %.0f)\n",
                     n, (d - c - b + a) / N / ((p2 - p1) * (k2 - k1)), p1, p2, k1, k2, a / N, b / N, c / N, d / N }'
    fi
done
for f in predict update; do
    fn=fl_ukf_predict_odo; [ $f = update ] && fn=fl_ukf_update_obs
    valgrind --tool=callgrind --toggle-collect=$fn --callgrind-out-file="$TMP/out" \
        "$CLI" ukf-check --n 2000 --fixed-only >"$TMP/log" 2>&1
    i=$(sed -n 's/.*refs: *//p' "$TMP/log" | tr -d ,)
    c=$(sed -n "s/^${f}s //p" "$TMP/log")
    if [ -z "$i" ] || [ -z "$c" ]; then echo "callgrind ukf_$f failed"; continue; fi
    awk -v n="ukf_$f" -v i="$i" -v c="$c" \
        'BEGIN { printf "callgrind %-28s %10.0f instr/call  (%d calls)\n", n, i / c, c }'
done
rm -rf "$TMP"
