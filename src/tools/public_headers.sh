#!/bin/sh
# src/tools/public_headers.sh OUTDIR HEADER... -- the public headers as installed: each copied into OUTDIR
# (emptied first) under its file name, with its quoted includes of other public headers reduced to their file
# names ("implicits/expr.h" -> "expr.h"), which resolve beside the including file both in OUTDIR and in
# PREFIX/include/iacsg/. Fails, naming the file, when a public header includes a header that is not public
# (it would be missing once installed), when two public headers share a file name, or when one is included by
# none of the others (so that <iacsg/iacsg.h>, which includes them, gives the whole API).
set -eu
out=$1
shift
rm -rf "$out"
mkdir -p "$out"
names=""
for h in "$@"; do
    names="$names $(basename "$h")"
done
for h in "$@"; do
    name=$(basename "$h")
    if [ -e "$out/$name" ]; then
        echo "$h: another public header is also named $name" >&2
        exit 1
    fi
    for inc in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$h"); do
        case " $names " in
        *" $(basename "$inc") "*) ;;
        *)
            echo "$h: includes \"$inc\", which is not a public header (PUBLIC_HEADERS in the Makefile)" >&2
            exit 1
            ;;
        esac
    done
    sed 's/^\([[:space:]]*#[[:space:]]*include[[:space:]]*"\)\([^"]*\/\)*\([^"/]*"\)/\1\3/' "$h" > "$out/$name"
done
for name in $names; do
    if [ "$name" != iacsg.h ] && ! grep -q "^[[:space:]]*#[[:space:]]*include[[:space:]]*\"$name\"" "$out"/*.h; then
        echo "$name: a public header that no other public header includes (add it to src/iacsg.h)" >&2
        exit 1
    fi
done
