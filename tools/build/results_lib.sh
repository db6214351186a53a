# tools/build/results_lib.sh - sourced by results.sh, results_seed002.sh and
# results_seed004.sh.
# run LOG CMD...: runs CMD (stdout + stderr to LOG; nothing when DRY_RUN=1),
# and when it fails prints the log's tail and calls the sourcing script's
# die.  RESULTS_NAME prefixes the command echoed on stderr.
run() {
    log=$1; shift
    echo "$RESULTS_NAME: $*" >&2
    [ "$DRY_RUN" = 1 ] && return 0
    "$@" > "$log" 2>&1
    rc=$?
    [ $rc -eq 0 ] || { tail -n 20 "$log" >&2; die "\`$*\` exited with status $rc (output in $log)"; }
}
