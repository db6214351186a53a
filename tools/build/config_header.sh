#!/bin/sh
# tools/build/config_header.sh - the config.h that `make install` installs:
# include/fieldloc/config.h with the default of every option (each
# "#ifndef FL_X" / "#define FL_X VALUE" pair) replaced by the value the
# library was compiled with, so that a caller who passes no -D gets the
# library's layout (and FL_CONFIG_FINGERPRINT) exactly.
#
#   sh tools/build/config_header.sh include/fieldloc/config.h CC FLAGS... > out
#
# The values come from the compiler itself (CC FLAGS -dM -E on config.h,
# with the very flags of the library's objects), so an override given by
# any route (CONFIG_DEFS, ARCHFLAGS, CC="gcc -D...") is seen.  Fails when
# an option has no value or the output would not define every option.
set -eu
src=$1
shift
defs=$("$@" -dM -E -x c "$src") || { echo "config_header.sh: cannot preprocess $src" >&2; exit 1; }
printf '%s\n' "$defs" | awk -v src="$src" '
  FNR == NR {   # the macro dump: "#define NAME VALUE"
      if ($1 == "#define" && $2 ~ /^FL_/) {
          v = $0
          sub(/^#define[ \t]+[A-Za-z0-9_]+[ \t]*/, "", v)
          val[$2] = v
      }
      next
  }
  FNR == 1 { first = 1 }
  {
      if (guard != "" && $1 == "#define" && $2 == guard) {
          if (!(guard in val) || val[guard] == "") {
              print "config_header.sh: no value for " guard > "/dev/stderr"
              bad = 1
          }
          print "#define " guard " " val[guard]
          if (val[guard] != $3)
              changed++
          options++
          guard = ""
          next
      }
      guard = ($1 == "#ifndef" && $2 ~ /^FL_/) ? $2 : ""
      print
      if (first && $0 ~ /^ \*\/$/) {
          print "/* Installed by `make install`: the default of every option below is"
          print " * the value the installed libfieldloc.a was built with.  Callers must"
          print " * not override them (the library refuses a caller whose"
          print " * FL_CONFIG_FINGERPRINT differs: FL_ERR_CONFIG). */"
          first = 0
      }
  }
  END {
      if (options == 0) { print "config_header.sh: no option found in " src > "/dev/stderr"; bad = 1 }
      exit bad
  }' - "$src"
