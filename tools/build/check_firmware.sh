#!/bin/sh
# tools/build/check_firmware.sh - prove the firmware rules on the sources in src/.
# Run by `make check` (CC and BUILD come from make).  Exit status 0 only when
# every rule holds:
#   1. every src/**/*.c compiles with -std=c99 -pedantic -Werror -Wall -Wextra
#      -Wconversion -Wshadow, and on x86 with -mgeneral-regs-only (any
#      floating-point operation is then a compile error);
#   2. no object references an allocator (malloc, calloc, realloc, free, ...)
#      and nothing but memcpy/memset/memmove/memcmp from libc (plus libgcc's
#      integer helpers on 32-bit targets; a soft-float helper fails);
#   3. every exported symbol starts with fl_;
#   4. no object has mutable file-scope (or function-static) data: nothing in
#      .data, .bss, .sdata, .sbss or common; const data in .rodata or
#      .data.rel.ro (relocated, read-only after start-up) is fine;
#   5. src/ and include/ include only <stdint.h> <stdbool.h> <stddef.h>
#      <string.h> <limits.h> and fieldloc's own headers;
#  6-9 (tools/build/check_layers.py, which holds the layer table):
#   6. include layering: each direct #include of a fieldloc header from
#      include/fieldloc/ or src/<folder>/ follows the layers (base, model, obs,
#      vision, loc, umbrella) or a listed exception; an unclassified header
#      or src/ folder fails ("assign a layer to X");
#   7. private headers: src/<folder>/<stage>_int.h only from that folder's
#      <stage>*.c; never from another stage, include/, tools/ or host_tests/;
#   8. no include circles among src/ and include/ files, among tools/ files,
#      nor among tools/ folders (io <- world <- eval <- loc <- bench <- cli);
#   9. no src/ function longer than 150 lines, except those listed in
#      tools/build/long_functions.txt (a listed one that got short fails too);
#  10. tools/ reach a localizer only through localizer.h (no fuzzy.h, no
#      fl_fuzzy_* calls), except the files check_layers.py lists with a reason.
set -u
CC=${CC:-cc}
BUILD=${BUILD:-build}
SRC=${SRC_DIR:-src}        # overridable so host_tests/test_rules.c can feed
INC=${INC_DIR:-include}    # deliberately broken sources to this script
# TOOLS_DIR, TESTS_DIR and LONG_FUNCTIONS (rules 6-9) are read by check_layers.py
out="$BUILD/check"
rm -rf "$out"; mkdir -p "$out"
fail=0
say() { echo "check: $*"; }
bad() { echo "check: FAIL: $*"; fail=1; }

case "$($CC -dumpmachine)" in
  x86_64*|i686*|i386*) nofp=-mgeneral-regs-only ;;
  *) nofp= ;;
esac
prefix=
case "$CC" in *-gcc) prefix=${CC%gcc} ;; esac
NM=${prefix}nm
OBJDUMP=${prefix}objdump
command -v "$NM" >/dev/null 2>&1 || NM=nm
command -v "$OBJDUMP" >/dev/null 2>&1 || OBJDUMP=objdump

# 1. strict compile, no floating point
n=0
fw_src=$(find "$SRC" -name '*.c' | sort)
flags="-std=c99 -pedantic -Werror -Wall -Wextra -Wconversion -Wshadow -O2 -fno-common $nofp"
# A compile that succeeded is kept in $BUILD/check-cache under a hash of
# everything it read: the compiler's identity ($CC -v), the flags, the
# source path, the list of files the preprocessor opens ($CC -M: the
# source, every header, system ones too, as resolved through the include
# path now, so a new header shadowing an old one changes the list) and the
# bytes of each.  A hit copies the object and its (empty) diagnostics
# instead of compiling; a failed compile is never cached, nor anything when
# -M fails or sha1sum is missing.  After a run where every source compiled,
# the entries it did not use are removed.
cache="$BUILD/check-cache"
ccid=
if command -v sha1sum >/dev/null 2>&1; then
  ccid=$($CC -v 2>&1) || ccid=
  mkdir -p "$cache" || ccid=
fi
compile_one() {  # $1 source, $2 object; leaves $2.failed on failure, $2.key on a cacheable key
  key=
  if [ -n "$ccid" ] && deps=$($CC $flags -I"$INC" -M "$1" 2>/dev/null); then
    files=$(printf '%s\n' "$deps" | sed -e 's/\\$//' -e 's/^[^:]*: *//' | tr -s ' \t' '\n\n' | grep .)
    if { printf '%s\n' "$ccid" "$flags" "-I$INC" "$1" $files; cat $files; } > "$2.keyin" 2>/dev/null; then
      key=$(sha1sum < "$2.keyin" | cut -c1-40)
    fi
    rm -f "$2.keyin"
  fi
  if [ -n "$key" ] && [ -f "$cache/$key.o" ] && [ -f "$cache/$key.err" ] &&
     cp "$cache/$key.o" "$2" && cp "$cache/$key.err" "$2.err"; then
    echo "$key" > "$2.key"; : > "$2.hit"; return
  fi
  if $CC $flags -I"$INC" -c "$1" -o "$2" 2>"$2.err"; then
    if [ -n "$key" ] && cp "$2" "$cache/$key.o.tmp$$" && cp "$2.err" "$cache/$key.err.tmp$$"; then
      mv "$cache/$key.o.tmp$$" "$cache/$key.o" && mv "$cache/$key.err.tmp$$" "$cache/$key.err" &&
        echo "$key" > "$2.key"
    fi
  else
    : > "$2.failed"
  fi
}
# the compiles run in parallel (all at once: a few dozen small files); the
# failures are reported afterwards in source order
for f in $fw_src; do
  compile_one "$f" "$out/$(basename "$f" .c).o" &
done
wait
for f in $fw_src; do
  o="$out/$(basename "$f" .c).o"
  if [ -e "$o.failed" ]; then
    bad "$f does not compile under the firmware flags ($nofp):"; sed 's/^/    /' "$o.err" | head -20
  fi
  n=$((n + 1))
done
if [ -n "$ccid" ] && [ $fail -eq 0 ]; then
  used=$(cat "$out"/*.o.key 2>/dev/null)
  for e in "$cache"/*.o; do
    [ -e "$e" ] || continue
    k=$(basename "$e" .o)
    case " $(echo $used) " in *" $k "*) ;; *) rm -f "$cache/$k.o" "$cache/$k.err" ;; esac
  done
fi
rm -f "$cache"/*.tmp* "$out"/*.o.key
hits=$(ls "$out" | grep -c '\.hit$')
rm -f "$out"/*.hit
say "$n sources compiled with -std=c99 -pedantic -Werror -Wall -Wextra -Wconversion -Wshadow ${nofp:-(no -mgeneral-regs-only for this target)} ($hits unchanged, from $cache)"
objs=$(ls "$out"/*.o 2>/dev/null)
[ -n "$objs" ] || { bad "no objects"; exit 1; }

# 2. undefined symbols: no allocator, only the allowed libc functions
und=$($NM -u $objs | awk 'NF>=2 {print $NF}' | sort -u)
for s in $und; do
  case "$s" in
    malloc|calloc|realloc|free|aligned_alloc|posix_memalign|memalign|valloc|pvalloc|strdup|strndup|alloca)
      bad "allocator symbol referenced: $s" ;;
    fl_*|memcpy|memset|memmove|memcmp|_GLOBAL_OFFSET_TABLE_|__stack_chk_fail|__stack_chk_guard|_gp_disp|__gnu_local_gp|__x86.get_pc_thunk.*) ;;
    __divdi3|__udivdi3|__moddi3|__umoddi3|__udivmoddi4|__divmoddi4|__ashldi3|__ashrdi3|__lshrdi3|__muldi3|__ucmpdi2|__cmpdi2|__clzsi2|__clzdi2|__ctzsi2|__ctzdi2|__popcountsi2|__popcountdi2|__bswapsi2|__bswapdi2) ;;
    *) bad "symbol outside the allowed libc subset: $s" ;;
  esac
done
say "undefined symbols: $(echo $und | tr '\n' ' ')"

# 3. exported symbols carry the fl_ prefix
exp=$($NM -g --defined-only $objs | awk 'NF>=3 {print $3}' | sort -u)
for s in $exp; do
  case "$s" in fl_*|__x86.get_pc_thunk.*) ;; *) bad "exported symbol without fl_ prefix: $s" ;; esac
done
say "$(echo "$exp" | grep -c .) exported symbols checked for the fl_ prefix"

# 4. mutable file-scope state
mut=$($OBJDUMP -t $objs | awk '
  /^[0-9a-f]+ / {
    sec = ""; for (i = 2; i <= NF; i++) if ($i ~ /^(\.|\*COM\*)/) { sec = $i; break }
    if (sec ~ /^\.data\.rel\.ro/) next
    if (sec ~ /^(\.data|\.bss|\.sdata|\.sbss|\.tbss|\.tdata|\*COM\*)/ && $0 ~ / O /) print sec, $NF
  }' | sort -u)
if [ -n "$mut" ]; then
  bad "mutable file-scope state:"; echo "$mut" | sed 's/^/    /'
else
  say "no mutable file-scope or static data"
fi

# 5. libc headers
inc=$(grep -hoE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<[^>]+>' $(find "$SRC" -name '*.[ch]') "$INC"/fieldloc/*.h 2>/dev/null |
      sed -E 's/.*<([^>]+)>.*/\1/' | sort -u)
for h in $inc; do
  case "$h" in
    stdint.h|stdbool.h|stddef.h|string.h|limits.h) ;;
    *) bad "header outside the allowed libc subset: <$h>" ;;
  esac
done
say "system headers: $(echo $inc | tr '\n' ' ')"

# 6-10. layering, private headers, include circles, function length, tools
# through the localizer interface
# (-S: no site module; the checker needs only the standard library)
PY=${PYTHON:-python3}
SRC_DIR="$SRC" INC_DIR="$INC" "$PY" -S "$(dirname "$0")/check_layers.py" || fail=1

if [ $fail -ne 0 ]; then echo "check: FAILED"; exit 1; fi
echo "check: all firmware rules hold"
