# tools/bench/callgrind_lib.sh - sourced by callgrind_coach.sh and
# callgrind_vision.sh: the instructions one `fieldloc CMD ... --repeat N`
# spends inside one function, per call, as the difference of two repeat
# counts (1 and 3), so that loading and set-up cancel out.
# The caller sets CLI (the fieldloc binary), TMP (a scratch folder),
# CG_FUNC (the function whose calls are collected) and CG_CMD (the
# subcommand).
cg_refs() {  # cg_refs N ARGS...: instructions collected inside $CG_FUNC
    n=$1; shift
    valgrind --tool=callgrind --toggle-collect="$CG_FUNC" --callgrind-out-file="$TMP/out" \
        "$CLI" "$CG_CMD" "$@" --repeat "$n" 2>&1 >/dev/null | sed -n 's/.*refs: *//p' | tr -d ,
}
cg_per_call() {  # cg_per_call ARGS...: prints instructions per call; fails if a run did
    a=$(cg_refs 1 "$@"); b=$(cg_refs 3 "$@")
    if [ -z "$a" ] || [ -z "$b" ]; then return 1; fi
    awk -v a="$a" -v b="$b" 'BEGIN { printf "%.0f\n", (b - a) / 2 }'
}
