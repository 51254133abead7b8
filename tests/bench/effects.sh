#!/bin/bash
# tests/bench/effects.sh BINARY -- what each ray-tracing effect costs against the plain render of the same view
# (issue 12), by hand: the render time that -stats prints (camera rays, effects and secondary rays included;
# not the kernel build, nor the process), the median of RUNS runs with the variants taken in turn, so that a
# ratio compares runs under the same load; and the secondary rays' interval evaluations (exact, load-free).
# Prints markdown rows; tests/bench/NOTES.md's section "Ray-tracing effects" holds runs of it. BENCH_ONLY: the views
# to run, of "reference regions unions gyroid" (all by default): issue 12's two views, and beside them two other
# kinds of shape: Fig. 7's multiple unions (its pseudo-cube's x^500 has no derivative code, so its secondary rays
# walk rather than march) and a gyroid in a ball (trigonometric, many surfaces a ray).
set -eu
# a first run's program saved before the next starts, not by a detached saver beside the timed runs (as bench.sh)
export IACSG_CACHE_SAVE=${IACSG_CACHE_SAVE:-wait}
bin=$(realpath "${1:-build/iacsg}")
runs=${RUNS:-5}
here=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
ref=(-eye 0,-4,2.5 -at 0,0,0 -up 0,0,1 -fov 40 -bounds -2,-2,-2,2,2,2 -size 1024x1024 -eps 1e-5)
# Fig. 2's cube and sphere as regions, and the same with its grey material reflecting half the light, or letting
# half of it through
cp "$here/examples/fig2_cube_sphere_regions.csg" fig2.csg
sed 's/^material grey = rgb(0.6, 0.6, 0.62)$/& reflect 0.5/' fig2.csg >fig2_mirror.csg
sed 's/^material grey = rgb(0.6, 0.6, 0.62)$/& opacity 0.5/' fig2.csg >fig2_glass.csg
# the light for the shadows: one point light above and to the side
light=(-light point,1.5,-2,4,0.9)

# "SECONDS EVALS" of one run: -stats' render time, the secondary rays' evaluations per ray (0 without)
one() {
    "$bin" "$@" -stats -o out.png >stats.txt 2>&1 || { cat stats.txt >&2; exit 1; }
    printf '%s %s\n' "$(sed -n 's/^render: \([0-9.]*\) s$/\1/p' stats.txt)" \
        "$(sed -n 's/^secondary rays: .*mean \([0-9.]*\)$/\1/p' stats.txt | grep . || echo 0)"
}

median() { sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

# table NAME INPUT ARGS... : the variants of one view, in turn, RUNS times
table() {
    name=$1 input=$2
    shift 2
    variants=("plain" "shadows" "one bounce" "transparency" "aa 4")
    rm -f ./*.times
    for r in $(seq "$runs"); do
        for v in "${variants[@]}"; do
            case $v in
            plain) set -- ;;
            shadows) set -- "${light[@]}" -shadows ;;
            "one bounce") set -- -bounces 1 -reflect 0.5 ;;
            transparency) set -- -opacity 0.5 ;;
            "aa 4") set -- -aa 4 ;;
            esac
            in=$input
            if [ "$name" = regions ]; then # the materials' reflect and opacity
                [ "$v" = "one bounce" ] && set -- -bounces 1 && in=fig2_mirror.csg
                [ "$v" = transparency ] && set -- && in=fig2_glass.csg
            fi
            one "$in" "${view[@]}" "$@" >>"$v.times"
        done
    done
    base=$(cut -d' ' -f1 plain.times | median)
    for v in "${variants[@]}"; do
        [ -f "$v.times" ] || continue
        t=$(cut -d' ' -f1 "$v.times" | median)
        e=$(cut -d' ' -f2 "$v.times" | median)
        printf '| %s | %s | %s | %.2fx | %s |\n' "$name" "$v" "$t" "$(echo "$t / $base" | bc -l)" "$e"
    done
}

only=${BENCH_ONLY:-reference regions unions gyroid}
echo "| view | effect | render s (median of $runs) | against plain | evaluations per secondary ray |"
echo "|---|---|---|---|---|"
if [[ " $only " == *" reference "* ]]; then
    view=("${ref[@]}")
    table "reference view" "min((x-0.5)^2+y^2+z^2-1, (1-sqrt(x^2+y^2))^2+z^2-0.125)"
fi
if [[ " $only " == *" regions "* ]]; then
    view=(-size 1024x1024 -eps 1e-5)
    table regions fig2.csg
fi
if [[ " $only " == *" unions "* ]]; then
    view=(-size 1024x1024 -eps 1e-5)
    table "multiple unions" "$here/examples/fig7_multiple_unions.csg"
fi
if [[ " $only " == *" gyroid "* ]]; then
    view=(-size 1024x1024 -eps 1e-5)
    table "gyroid in a ball" "max(sin(4*x)*cos(4*y)+sin(4*y)*cos(4*z)+sin(4*z)*cos(4*x), x^2+y^2+z^2-3.61)"
fi
