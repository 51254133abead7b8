#!/bin/sh
# tests/bench/spheres.sh -- writes a scene of N spheres, each its own region in a random colour, for the segment
# path's rows of `make bench` (bench.sh) and for measuring by hand:
#
#   tests/bench/spheres.sh N HALF RMIN RMAX SEED [union] > FILE.csg
#
# With "union", the same spheres as one expression, their union (min), for the first-root path.
# Centres uniform in [-HALF, HALF]^3, radii uniform in [RMIN, RMAX], colours uniform in [0.15, 0.95]^3. The
# numbers come from the Park-Miller generator (x = 16807 x mod 2^31 - 1, exact in awk's doubles) rather than awk's
# rand(), whose sequence differs between awks: the same arguments give the same file on every machine.
# The bench's two: "1000 0.9 0.08 0.08 1" (dense: most rays meet many boxes) and "1000 1.8 0.04 0.12 1" (sparse).
set -eu
[ $# -eq 5 ] || { [ $# -eq 6 ] && [ "$6" = union ]; } || { echo "usage: $0 N HALF RMIN RMAX SEED [union]" >&2; exit 2; }
awk -v n="$1" -v half="$2" -v rmin="$3" -v rmax="$4" -v seed="$5" -v union="${6:-}" '
function uniform() { state = (16807 * state) % 2147483647; return state / 2147483647 }
function minus(c) { return sprintf("%s %.4f", c < 0 ? "+" : "-", c < 0 ? -c : c) }
BEGIN {
    state = seed % 2147483646 + 1
    for (k = 0; k < 8; k++) # the first draws of a small seed are small
        uniform()
    printf "# %d spheres in [-%s, %s]^3, radii %s to %s, seed %s (tests/bench/spheres.sh)\n", n, half, half, rmin, rmax, seed
    for (k = 0; k < n; k++) {
        x = (2 * uniform() - 1) * half; y = (2 * uniform() - 1) * half; z = (2 * uniform() - 1) * half
        r = rmin + (rmax - rmin) * uniform()
        red = 0.15 + 0.8 * uniform(); green = 0.15 + 0.8 * uniform(); blue = 0.15 + 0.8 * uniform()
        f = sprintf("(x %s)^2 + (y %s)^2 + (z %s)^2 - %.4f^2", minus(x), minus(y), minus(z), r)
        if (union != "") {
            printf "%s%s", k ? ", " : "min(", f
            continue
        }
        printf "material m%d = rgb(%.4f, %.4f, %.4f)\n", k, red, green, blue
        printf "solid s%d = %s\n", k, f
        printf "region r%d = s%d : m%d\n", k, k, k
    }
    if (union != "")
        printf ")\n"
}'
