# tests/bench/suite_brlcad.sh -- the BRL-CAD table of `make bench` (issue 18), sourced by bench.sh: the seven
# sample databases (tests/data/brlcad/) rendered by the whole iacsg command at 1024x1024 from -az 25 -el 35, and,
# when BRLCAD=DIR names a BRL-CAD build (DIR/asc2g, DIR/rt), by `rt -s1024 -a 25 -e 35 -P2` on the same objects in
# the same run (asc2g makes the .g first, untimed). Medians of BRLCAD_RUNS (default 5) whole-process wall times;
# each cached iacsg run is followed by one of `rt -P2`, so that the two medians that the target divides are taken
# under the same load (rows measured one after the other read truck at 0.78x when alternated runs read 1.01x).
# Without BRLCAD the rt columns read "-".

# scene | objects (rt is given the same)
brlcad_scenes() {
    b boolean-ops all
    b operators operators
    b truck g4
    b m35 all.g
    b tank_car tank_car
    b havoc havoc
    b goliath Goliath.c
}

# The median wall time (ms) of n runs of a command: wall_median N CMD...
wall_median() {
    n=$1
    shift
    : >"$WORK/rtw"
    k=0
    while [ $k -lt "$n" ]; do
        t0=$(now_us)
        "$@" >/dev/null 2>&1 || { echo -; return; }
        t1=$(now_us)
        echo $((t1 - t0)) >>"$WORK/rtw"
        k=$((k + 1))
    done
    ms_of_us "$(median <"$WORK/rtw")"
}

# One timed run of `rt -P2` on the row's database and objects (rt_g, rt_obj), its wall time (us) into
# $WORK/rt_in_turn ("fail" when it fails): measure's BETWEEN, after each cached iacsg run.
rt_in_turn() {
    t0=$(now_us)
    if "$rtdir/rt" -s1024 -a 25 -e 35 -P2 -o "$WORK/rt.pix" "$rt_g" "$rt_obj" >/dev/null 2>&1; then
        echo $(($(now_us) - t0)) >>"$WORK/rt_in_turn"
    else
        echo fail >>"$WORK/rt_in_turn"
    fi
}

bench_brlcad() {
    runs=${BRLCAD_RUNS:-5}
    rtdir=${BRLCAD:-}
    if [ -n "$rtdir" ] && ! { [ -x "$rtdir/rt" ] && [ -x "$rtdir/asc2g" ]; }; then
        log "BRLCAD=$rtdir has no rt and asc2g"
        rtdir=
    fi
    table brlcad "BRL-CAD models: 1024x1024, -az 25 -el 35, against \`rt -s1024 -a 25 -e 35 -P2\`${rtdir:+ ($rtdir)}" \
        "scene (objects)" "read ms (cached runs) | rt -P2 wall ms | rt -P1 wall ms | speed-up (rt -P2 / iacsg cached wall)"
    : >"$WORK/brlcad_speedups"
    b() {
        [ "$QUICK" = 1 ] && case " boolean-ops truck " in *" $1 "*) ;; *) return ;; esac
        model=tests/data/brlcad/$1.asc
        rt2=- rt1=- rt_g=
        if [ -n "$rtdir" ] && "$rtdir/asc2g" "$model" "$WORK/$1.g" >/dev/null 2>&1; then
            rt_g=$WORK/$1.g rt_obj=$2 BETWEEN=rt_in_turn
            : >"$WORK/rt_in_turn"
        fi
        row_measure "$1 ($2)" "$runs" "$model" "$2" -size 1024x1024 -az 25 -el 35
        BETWEEN=
        if [ -n "$rt_g" ]; then
            if grep -q fail "$WORK/rt_in_turn"; then rt2=-; else rt2=$(ms_of_us "$(median <"$WORK/rt_in_turn")"); fi
            rt1=$(wall_median "$runs" "$rtdir/rt" -s1024 -a 25 -e 35 -P1 -o "$WORK/rt.pix" "$rt_g" "$2")
        fi
        sp=$(awk -v a="$rt2" -v b="$W_MS" 'BEGIN {if (a == "-" || b == "-" || b <= 0) print "-";
                                                  else printf "%.2f", a / b}')
        [ "$M_OK" = 1 ] && [ "$sp" != - ] && echo "$sp" >>"$WORK/brlcad_speedups"
        EXTRA=" $(ms_of_s "$M_READ") | $rt2 | $rt1 | $sp |"
        row_emit
    }
    brlcad_scenes
    if [ -s "$WORK/brlcad_speedups" ]; then
        verdict=$(awk '{n++; if ($1 <= 1) slow = 1; s += log($1)} END {g = exp(s / n);
                       printf "%s %.2f", (slow || g < 2 || n < 7) ? "not met" : "met", g}' "$WORK/brlcad_speedups")
        target "BRL-CAD models: the whole command faster than rt -P2 on every scene, 2x in the geometric mean" \
            "geometric mean speed-up ${verdict##* }x over $(wc -l <"$WORK/brlcad_speedups") scenes" "${verdict% *}"
    else
        target "BRL-CAD models: the whole command faster than rt -P2 on every scene, 2x in the geometric mean" \
            "rt not run (BRLCAD=DIR not given)" -
    fi
}
