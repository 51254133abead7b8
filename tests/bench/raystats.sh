#!/bin/sh
# tests/bench/raystats.sh -- build and run tests/bench/raystats.c for one expression (see that file).
#
#   tests/bench/raystats.sh EXPR [W H EPS EX EY EZ AX AY AZ UX UY UZ FOV ORTHO X0 Y0 Z0 X1 Y1 Z1 TIME]
#
# Without a view, the reference view of issue 5 at 512x512, eps 1e-5. IACSG (default build/iacsg) emits EXPR;
# CC (default cc) builds the host program with -O2, float intervals, rigorous rounding.
set -eu
IACSG=${IACSG:-build/iacsg}
CC=${CC:-cc}
[ $# -ge 1 ] || { echo "usage: $0 EXPR [view...]" >&2; exit 2; }
expr=$1
shift
[ $# -gt 0 ] || set -- 512 512 1e-5 0 -4 2.5 0 0 0 0 0 1 40 0 -2 -2 -2 2 2 2 0
dir=$(mktemp -d "${TMPDIR:-/tmp}/raystats.XXXXXX")
trap 'rm -rf "$dir"' EXIT
"$IACSG" compile "$expr" >"$dir/expr.h"
$CC -std=c11 -O2 -I. -Isrc -D_POSIX_C_SOURCE=200809L -DEXPR_H="\"$dir/expr.h\"" -o "$dir/raystats" \
    tests/bench/raystats.c src/camera.c src/error.c -lm
"$dir/raystats" "$@"
