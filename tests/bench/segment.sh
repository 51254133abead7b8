# tests/bench/segment.sh -- the segment path's table of `make bench` (issue 11's performance bars), sourced by
# bench.sh after suite.sh: level-set surfaces (icos, sesc), Fig. 2's cube and sphere as two regions against the
# same shapes as one expression (the first-root path), and 1000 spheres each its own region (tests/bench/
# spheres.sh writes them into the bench's scratch directory, so a clone without ../shared measures the same).
# Uses bench.sh's table, row_measure, row_emit, say, raw, RUNS, WORK, HERE, QUICK.

# A verdict line of this section: seg_target TEXT MEASURED met|not met|-
seg_target() {
    case $3 in met) v="**met**" ;; "not met") v="**not met**" ;; *) v="not measured" ;; esac
    printf '| %s | %s | %s |\n' "$1" "$2" "$v" >>"$WORK/seg_targets"
}

# the render median (s) of a row of the segment table, and its CPU median (s)
seg_render() { raw seg "$1" 4; }
seg_cpu() { awk -F'\t' -v l="$1" '$1 == "seg" && $2 == l {v = $15} END {print (v == "" ? "-" : v)}' "$RAW"; }

bench_segment() {
    : >"$WORK/seg_targets"
    # the dense 1000 and, for the growth with the number of solids, 10 and 100 filling the same share of the cube
    # (radius 0.08 (1000 / N)^(1/3)); the dense 1000 also as one expression; the sparse 1000
    "$HERE/spheres.sh" 1000 0.9 0.08 0.08 1 >"$WORK/spheres_dense.csg" &&
        "$HERE/spheres.sh" 1000 0.9 0.08 0.08 1 union >"$WORK/spheres_dense_union.csg" &&
        "$HERE/spheres.sh" 100 0.9 0.1724 0.1724 1 >"$WORK/spheres_100.csg" &&
        "$HERE/spheres.sh" 10 0.9 0.3713 0.3713 1 >"$WORK/spheres_10.csg" &&
        "$HERE/spheres.sh" 1000 1.8 0.04 0.12 1 >"$WORK/spheres_sparse.csg" || return 1
    table seg "Segment path (regions and level-set surfaces): 1024x1024, eps 1e-5, default camera" scene \
        "per-ray buffer bytes | source"
    g() { # g LABEL FILE: one row, with the per-ray buffer of the first run
        row_measure "$1" "$RUNS" "$2" -size 1024x1024 -eps 1e-5
        bytes=$(awk '/^per-ray buffers:/ {print $3}' "$WORK/first.log")
        EXTRA=" ${bytes:--} | \`$(basename "$2")\` |"
        row_emit
    }
    g icos examples/icos.csg
    g sesc examples/sesc.csg
    g "Fig. 2 as regions" examples/fig2_cube_sphere_regions.csg
    g "Fig. 2 as one expression" examples/fig2_cube_sphere_union.csg
    g "1000 spheres, dense" "$WORK/spheres_dense.csg"
    if [ "$QUICK" != 1 ]; then
        g "1000 spheres, dense, as one expression" "$WORK/spheres_dense_union.csg"
        g "100 spheres" "$WORK/spheres_100.csg"
        g "10 spheres" "$WORK/spheres_10.csg"
        g "1000 spheres, sparse" "$WORK/spheres_sparse.csg"
    fi
    say ""
    say "Dense: \`tests/bench/spheres.sh 1000 0.9 0.08 0.08 1\` (radius 0.08 in [-0.9, 0.9]^3; \`... union\`: the same"
    say "as one expression, min of the 1000); 100 and 10 spheres: radius 0.1724 and 0.3713, the same share of the cube;"
    say "sparse: \`tests/bench/spheres.sh 1000 1.8 0.04 0.12 1\` (radii 0.04-0.12 in [-1.8, 1.8]^3). Per-ray buffer:"
    say "\`-stats\`, the bytes one ray's candidates and states take while it is traced (kernels/scene_data.h)."
    for l in icos sesc; do
        r=$(seg_render "$l")
        seg_target "\`$l.csg\` in 1 s or less (render)" "$(ms_of_s "$r") ms" "$(le "$r" 1)"
    done
    a=$(seg_render "Fig. 2 as regions") b=$(seg_render "Fig. 2 as one expression")
    ca=$(seg_cpu "Fig. 2 as regions") cb=$(seg_cpu "Fig. 2 as one expression")
    r=$(awk -v a="$a" -v b="$b" 'BEGIN {if (a == "-" || b == "-" || b <= 0) print "-"; else printf "%.2f", a / b}')
    c=$(awk -v a="$ca" -v b="$cb" 'BEGIN {if (a == "-" || b == "-" || b <= 0) print "-"; else printf "%.2f", a / b}')
    seg_target "Fig. 2 as regions no slower than 1.5x its single expression" \
        "render ${r}x (whole-command CPU ${c}x, diluted by the fixed costs both pay)" "$(le "$r" 1.5)"
    d=$(seg_render "1000 spheres, dense")
    seg_target "1000 spheres, each its own region, in 2 s or less (render, dense)" "$(ms_of_s "$d") ms" "$(le "$d" 2)"
    say ""
    say "| target of issue 11 | measured | verdict |"
    say "|---|---|---|"
    cat "$WORK/seg_targets" >>"$BODY"
}
