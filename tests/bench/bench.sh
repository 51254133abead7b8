#!/bin/sh
# tests/bench/bench.sh -- `make bench`: renders the fixed suite of issue 5 and writes BENCHMARKS.md.
#
#   tests/bench/bench.sh [IACSG]        (make bench runs it with build/iacsg)
#
# Environment: BENCH_QUICK=1 (fewer runs and rows, writes $BENCH_BUILD/BENCHMARKS.quick.md, for iterating),
# BENCH_RUNS (cached runs per row, default 5), BENCH_GROWTH_RUNS (for the growth tables, default 3),
# BENCH_OUT (the report, default BENCHMARKS.md), BENCH_ONLY (space-separated table names: seed libfive ref
# res eps size modes brlcad seg), BRLCAD (a BRL-CAD build's bin directory: rt beside iacsg, tests/bench/suite_brlcad.sh), BENCH_BUILD (directory for the raw results, default build/bench).
#
# Every row is measured by running the whole `iacsg` command, never by a library call, so that its wall time is
# what a user waits for. Per row:
#   1. one first run with fresh, empty kernel caches (POCL_CACHE_DIR and IACSG_CACHE_DIR=a new directory): "first";
#   2. one untimed run, which saves the program's binary in iacsg's cache (src/clrt_cache.c: on a second build);
#   3. BENCH_RUNS runs with those now-filled caches: "cached" (medians; the render time also its minimum).
# The render time and kernel build time come from `-stats` (src/render.c: clBuildProgram, and kernel launches
# to the image in host memory); the wall time from `date +%s%N` around the command (process start to file
# written, exit). Everything runs with -stats, whose kernel counts evaluations; its cost is measured once (the
# "stats" row of the modes table).
#
# Only POSIX sh, coreutils (date %N, timeout, mktemp) and awk.
set -u

IACSG=${1:-${IACSG:-build/iacsg}}
QUICK=${BENCH_QUICK:-0}
BUILD_DIR=${BENCH_BUILD:-build/bench}
if [ "$QUICK" = 1 ]; then
    RUNS=${BENCH_RUNS:-2}
    GROWTH_RUNS=${BENCH_GROWTH_RUNS:-1}
    OUT=${BENCH_OUT:-$BUILD_DIR/BENCHMARKS.quick.md}
    GEN=$BUILD_DIR/generated.quick.md
else
    RUNS=${BENCH_RUNS:-5}
    GROWTH_RUNS=${BENCH_GROWTH_RUNS:-3}
    OUT=${BENCH_OUT:-BENCHMARKS.md}
    GEN=$BUILD_DIR/generated.md
fi
ONLY=${BENCH_ONLY:-seed libfive ref res eps size modes brlcad seg}
TIMEOUT=${BENCH_TIMEOUT:-300}
# The untimed run saves the program's binary before it ends, not in a detached saver that would still be compiling
# (seconds of PoCL's CPU) while the cached runs are timed.
export IACSG_CACHE_SAVE=wait
HERE=$(dirname "$0")

# The report is the generated tables, then the hand-written analysis tests/bench/NOTES.md (its numbers are
# dated there). `bench.sh --assemble` only re-joins them, after NOTES.md changed.
assemble() {
    { cat "$GEN"; if [ -f "$HERE/NOTES.md" ]; then echo ""; cat "$HERE/NOTES.md"; fi; } >"$OUT.tmp" &&
        mv "$OUT.tmp" "$OUT"
}
if [ "${1:-}" = --assemble ]; then
    assemble
    exit $?
fi
[ -x "$IACSG" ] || { echo "bench: $IACSG is not built (make build/iacsg)" >&2; exit 1; }
mkdir -p "$BUILD_DIR" || exit 1
WORK=$(mktemp -d "${TMPDIR:-/tmp}/iacsg-bench.XXXXXX") || exit 1
trap 'rm -rf "$WORK"' EXIT INT TERM
# A private copy of the binary (kernels and ia/ are embedded in it) and of the image library it loads from its
# own directory: others may rebuild build/iacsg meanwhile, and every row should measure the same program.
cp "$IACSG" "$WORK/iacsg" && cp "$(dirname "$IACSG")/libiacsg_image.so" "$WORK/" || exit 1
IACSG_SRC=$IACSG
IACSG=$WORK/iacsg
RAW=$BUILD_DIR/raw.tsv         # one line per row: table label ok render rmin evals-mean evals-max build1 build render1 wall1 wall runs cpu1 cpu
: >"$RAW"
BODY=$WORK/body.md             # the tables, assembled into $OUT at the end
: >"$BODY"
TARGETS=$WORK/targets.md
: >"$TARGETS"
ENVX=                          # extra environment for the next rows (e.g. POCL_MAX_PTHREAD_COUNT=1)
T_START=$(date +%s)

wants() { case " $ONLY " in *" $1 "*) return 0 ;; esac; return 1; }
now_us() { echo $(( $(date +%s%N) / 1000 )); }
say() { printf '%s\n' "$*" >>"$BODY"; }
log() { printf 'bench [%ss]: %s\n' $(( $(date +%s) - T_START )) "$*" >&2; }
loadavg() { cut -d' ' -f1-3 /proc/loadavg 2>/dev/null; }

# median of the numbers on stdin ("-" if none)
median() { sort -g | awk '{a[NR] = $1} END {if (NR == 0) print "-"; else if (NR % 2) print a[(NR + 1) / 2];
                                              else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
minimum() { sort -g | awk 'NR == 1 {print $1} END {if (NR == 0) print "-"}'; }
maximum() { sort -g | awk '{m = $1} END {print (NR == 0) ? "-" : m}'; }
# seconds (as printed by -stats) or microseconds to milliseconds, for the tables
ms_of_s() { awk -v v="$1" 'BEGIN {if (v == "-" || v == "") print "-"; else printf "%.0f", v * 1000}'; }
ms_of_us() { awk -v v="$1" 'BEGIN {if (v == "-" || v == "") print "-"; else printf "%.0f", v / 1000}'; }

# One run of the whole command: run_once CACHE_DIR LOG ARGS...; appends "wall_us: N" and "exit: N" to LOG.
run_once() {
    cache=$1 logf=$2
    shift 2
    times >"$WORK/times0"
    t0=$(now_us)
    # shellcheck disable=SC2086 # ENVX is a list of VAR=value words
    env POCL_CACHE_DIR="$cache" IACSG_CACHE_DIR="$cache" IACSG_LAUNCH_TRACE=1 $ENVX timeout "$TIMEOUT" "$IACSG" "$@" -stats -o "$WORK/image.png" >"$logf" 2>&1
    rc=$?
    t1=$(now_us)
    times >"$WORK/times1"
    # the launched process's CPU (src/cli_launch.c reports it) is not this shell's child's
    launched=$(awk '/^iacsg: launcher: the launched process ended: / {v = $7} END {print v + 0}' "$logf")
    cpu=$(children_cpu "$WORK/times0" "$WORK/times1")
    printf 'wall_us: %s\nexit: %s\ncpu_s: %s\n' $((t1 - t0)) "$rc" "$(awk -v a="$cpu" -v b="$launched" 'BEGIN {printf "%.3f", a + b}')" >>"$logf"
    return $rc
}

# The CPU time (user + system, all threads) of the children between two outputs of the POSIX `times` builtin,
# whose second line is the children's "XmY.YYs XmY.YYs". Unlike wall time, it hardly moves when other work
# shares the CPUs, so it is the number to compare across runs on a busy machine.
children_cpu() {
    awk 'function sec(v, a) {split(v, a, "m"); sub(/s$/, "", a[2]); return a[1] * 60 + a[2]}
         FNR == 2 {c[++f] = sec($1) + sec($2)} END {printf "%.3f", c[2] - c[1]}' "$1" "$2"
}

failure() { # failure LOG: the exit status and the last line the command printed
    awk '/^exit: / {x = $2} !/^(wall_us|exit|cpu_s): / {l = $0} END {print "exit " x (x == 124 ? " (timeout)" : "") ": " l}' "$1"
}

field() { # field LOG KEY: the number after "KEY" in a -stats log
    awk -v k="$2" 'index($0, k) == 1 {s = substr($0, length(k) + 1); gsub(/[^0-9.eE+-]/, " ", s);
                                       split(s, a, " "); print a[1]; exit}' "$1"
}

# measure RUNS ARGS...: sets M_* (first run, then medians over RUNS cached runs). M_OK=0 on failure. With PRIME
# set (the arguments of another command, a word list), that command runs first in the fresh cache, untimed: the
# first run then finds what the two share already built (the tape interpreter's program, for a large expression).
measure() {
    n=$1
    shift
    dir=$(mktemp -d "$WORK/kcache.XXXXXX")
    M_OK=1 M_ERR=
    # shellcheck disable=SC2086 # PRIME is a list of arguments
    [ -n "${PRIME:-}" ] && run_once "$dir" "$WORK/prime.log" $PRIME
    run_once "$dir" "$WORK/first.log" "$@" || { M_OK=0; M_ERR=$(failure "$WORK/first.log"); }
    M_BUILD1=$(field "$WORK/first.log" "kernel build:")
    M_RENDER1=$(field "$WORK/first.log" "render:")
    M_WALL1=$(field "$WORK/first.log" "wall_us:")
    M_EMEAN=$(awk '/evaluations per ray/ {sub(/.*mean /, ""); sub(/,.*/, ""); print}' "$WORK/first.log")
    M_EMAX=$(awk '/evaluations per ray/ {sub(/.*max /, ""); print}' "$WORK/first.log")
    M_BOUNDS=$(awk '/^bounds/ {print $2; exit}' "$WORK/first.log")
    M_CPU1=$(field "$WORK/first.log" "cpu_s:")
    # untimed: the second build of a program saves its binary (src/clrt_cache.c), which costs PoCL seconds once,
    # within the run (IACSG_CACHE_SAVE=wait above)
    [ "$M_OK" = 1 ] && run_once "$dir" "$WORK/run.log" "$@"
    : >"$WORK/b" ; : >"$WORK/r" ; : >"$WORK/w" ; : >"$WORK/c" ; : >"$WORK/wr" ; : >"$WORK/rd"
    k=0
    while [ "$M_OK" = 1 ] && [ $k -lt "$n" ]; do
        run_once "$dir" "$WORK/run.log" "$@" || { M_OK=0; M_ERR=$(failure "$WORK/run.log"); }
        field "$WORK/run.log" "kernel build:" >>"$WORK/b"
        field "$WORK/run.log" "render:" >>"$WORK/r"
        field "$WORK/run.log" "wall_us:" >>"$WORK/w"
        field "$WORK/run.log" "cpu_s:" >>"$WORK/c"
        field "$WORK/run.log" "write:" >>"$WORK/wr"
        field "$WORK/run.log" "read:" >>"$WORK/rd"
        [ -n "${BETWEEN:-}" ] && $BETWEEN # a peer's run in turn with ours (suite_brlcad.sh)
        k=$((k + 1))
    done
    M_BUILD=$(median <"$WORK/b")
    M_RENDER=$(median <"$WORK/r")
    M_RMIN=$(minimum <"$WORK/r")
    M_RMAX=$(maximum <"$WORK/r")
    M_WALL=$(median <"$WORK/w")
    M_CPU=$(median <"$WORK/c")
    M_WRITE=$(median <"$WORK/wr")
    M_READ=$(median <"$WORK/rd")
    rm -rf "$dir"
    [ "$M_OK" = 1 ] || { M_BUILD=- M_RENDER=- M_RMIN=- M_RMAX=- M_WALL=- M_CPU=- M_READ=-; }
    # milliseconds for the tables
    R_MS=$(ms_of_s "$M_RENDER") RMIN_MS=$(ms_of_s "$M_RMIN") RMAX_MS=$(ms_of_s "$M_RMAX") R1_MS=$(ms_of_s "$M_RENDER1")
    B_MS=$(ms_of_s "$M_BUILD") B1_MS=$(ms_of_s "$M_BUILD1")
    W_MS=$(ms_of_us "$M_WALL") W1_MS=$(ms_of_us "$M_WALL1")
    C_MS=$(ms_of_s "$M_CPU") C1_MS=$(ms_of_s "$M_CPU1")
}

# The standard table: header, then row LABEL ARGS... for each row.
TABLE=
EXTRA=          # extra cells for the next row (with their leading "| "), under the extra header of table
table() { # table NAME TITLE FIRST-COLUMN [EXTRA-HEADER]
    TABLE=$1
    say ""
    say "### $2"
    say ""
    if [ $# -ge 4 ]; then xh="$4 |"; xs=$(printf '%s' "$4" | sed 's/[^|]*|/---|/g; s/[^|]*$/---|/'); else xh= xs=; fi
    say "| $3 | render ms, median [min] | evals/ray mean / max | build ms first / cached | render ms first run | wall ms first / cached | CPU ms first / cached | $xh"
    say "|---|---|---|---|---|---|---|$xs"
}
row() { # row LABEL RUNS ARGS...: measure and write the row
    row_measure "$@"
    EXTRA=
    row_emit
}
row_measure() { # row_measure LABEL RUNS ARGS...: measure only (then set EXTRA and call row_emit)
    label=$1 n=$2
    shift 2
    log "$TABLE: $label"
    measure "$n" "$@"
    [ "$M_OK" = 1 ] || log "  FAILED: $M_ERR"
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$TABLE" "$label" "$M_OK" "$M_RENDER" \
        "$M_RMIN" "$M_EMEAN" "$M_EMAX" "$M_BUILD1" "$M_BUILD" "$M_RENDER1" "$M_WALL1" "$M_WALL" "$n" "$M_CPU1" "$M_CPU" >>"$RAW"
}
row_emit() {
    if [ "$M_OK" = 1 ]; then
        say "| $label | **$R_MS** [$RMIN_MS] | ${M_EMEAN:--} / ${M_EMAX:--} | $B1_MS / $B_MS | $R1_MS | $W1_MS / $W_MS | $C1_MS / $C_MS |$EXTRA"
    else
        say "| $label | FAILED: $(printf '%s' "$M_ERR" | tr '|' '/') | | | | | |$EXTRA"
    fi
}
# the last value of a column for a label in the raw results (4 render, 8 build first, 9 build cached, 12 wall)
raw() { awk -F'\t' -v t="$1" -v l="$2" -v c="$3" '$1 == t && $2 == l {v = $c} END {print (v == "" ? "-" : v)}' "$RAW"; }

target() { # target TEXT MEASURED VERDICT(met|not met|-)
    case $3 in met) v="**met**" ;; "not met") v="**not met**" ;; *) v="not measured" ;; esac
    printf '| %s | %s | %s |\n' "$1" "$2" "$v" >>"$TARGETS"
}
le() { awk -v a="$1" -v b="$2" 'BEGIN {if (a == "-" || a == "" || b == "-" || b == "") print "-";
                                      else if (a + 0 <= b + 0) print "met"; else print "not met"}'; }

# A scene: the example file when engineer 2's examples/ has it, else the expression. Prints the argument.
scene_arg() { # scene_arg FILE EXPR
    if [ -f "$1" ]; then printf '%s' "$1"; else printf '%s' "$2"; fi
}

# A union of N spheres on a grid in [-1.5,1.5]^3, one line, to a scene file: spheres N R FILE (R 0: 0.4 x the
# grid spacing; grids 1, 2x2x1, 4x2x2, 4x4x4, 8x8x4, 16x8x8).
spheres() {
    awk -v n="$1" -v r="$2" 'BEGIN {
        nx = 1; ny = 1; nz = 1; m = n
        while (m > 1) { if (nx <= ny && nx <= nz) nx *= 2; else if (ny <= nz) ny *= 2; else nz *= 2; m /= 2 }
        s = 3; if (nx > 1) s = 3 / (nx - 1); if (ny > 1 && 3 / (ny - 1) < s) s = 3 / (ny - 1)
        if (nz > 1 && 3 / (nz - 1) < s) s = 3 / (nz - 1)
        if (r == 0) r = (n == 1) ? 1 : 0.4 * s
        printf "# %d spheres of radius %g on a %dx%dx%d grid in [-1.5,1.5]^3\n", n, r, nx, ny, nz
        if (n > 1) printf "min("
        sep = ""
        for (i = 0; i < nx; i++) for (j = 0; j < ny; j++) for (k = 0; k < nz; k++) {
            cx = (nx > 1) ? -1.5 + 3 * i / (nx - 1) : 0; cy = (ny > 1) ? -1.5 + 3 * j / (ny - 1) : 0
            cz = (nz > 1) ? -1.5 + 3 * k / (nz - 1) : 0
            printf "%s(x-(%g))^2+(y-(%g))^2+(z-(%g))^2-%g", sep, cx, cy, cz, r * r
            sep = ", "
        }
        if (n > 1) printf ")"
        printf "\n"
    }' >"$3"
}

REF='min((x-0.5)^2+y^2+z^2-1, (1-sqrt(x^2+y^2))^2+z^2-0.125)'
REFVIEW="-eye 0,-4,2.5 -at 0,0,0 -up 0,0,1 -fov 40 -bounds -2,-2,-2,2,2,2"
TOP="-eye 0,0,4 -at 0,0,0 -up 0,1,0 -ortho 4 -bounds -2,-2,-2,2,2,2"

. "$HERE/suite.sh"
. "$HERE/suite_brlcad.sh"
. "$HERE/segment.sh"

# The fixed cost of a command, median wall of 5 runs: STARTUP_MS of `iacsg devices` (the process, its shared
# libraries, the OpenCL platform and device) and PROCESS_MS of `iacsg --version` (the process and libraries).
startup_costs() {
    for what in devices --version; do
        : >"$WORK/w"
        k=0
        while [ $k -lt 5 ]; do
            t0=$(now_us); "$IACSG" "$what" >/dev/null 2>&1; t1=$(now_us)
            echo $((t1 - t0)) >>"$WORK/w"
            k=$((k + 1))
        done
        if [ "$what" = devices ]; then STARTUP_MS=$(ms_of_us "$(median <"$WORK/w")"); else PROCESS_MS=$(ms_of_us "$(median <"$WORK/w")"); fi
    done
}

# Two variants of one command run in turn, ALT_RUNS times each after one first and one untimed run (one cache
# for both), so that both medians are taken under the same load: a ratio of rows measured minutes apart moved
# by a third with the machine's other work. Sets ALT_RENDER_A, ALT_RENDER_B, ALT_CPU_A, ALT_CPU_B (medians).
# alternate FIRST-ARG "OPTIONS A" "OPTIONS B" (options split at spaces; FIRST-ARG the expression or file)
ALT_RUNS=${BENCH_ALT_RUNS:-9}
alternate() {
    arg=$1 alt_a=$2 alt_b=$3
    dir=$(mktemp -d "$WORK/kcache.XXXXXX")
    : >"$WORK/alt_ra" ; : >"$WORK/alt_rb" ; : >"$WORK/alt_ca" ; : >"$WORK/alt_cb"
    alt_ok=1
    for pass in first untimed; do
        # shellcheck disable=SC2086 # the options are lists of words
        run_once "$dir" "$WORK/alt.log" "$arg" $alt_a && run_once "$dir" "$WORK/alt.log" "$arg" $alt_b || alt_ok=0
    done
    k=0
    while [ "$alt_ok" = 1 ] && [ $k -lt "$ALT_RUNS" ]; do
        for v in a b; do
            if [ $v = a ]; then opts=$alt_a; else opts=$alt_b; fi
            # shellcheck disable=SC2086
            run_once "$dir" "$WORK/alt.log" "$arg" $opts || alt_ok=0
            field "$WORK/alt.log" "render:" >>"$WORK/alt_r$v"
            field "$WORK/alt.log" "cpu_s:" >>"$WORK/alt_c$v"
        done
        k=$((k + 1))
    done
    rm -rf "$dir"
    if [ "$alt_ok" != 1 ]; then
        ALT_RENDER_A=- ALT_RENDER_B=- ALT_CPU_A=- ALT_CPU_B=-
        return 1
    fi
    ALT_RENDER_A=$(median <"$WORK/alt_ra") ALT_RENDER_B=$(median <"$WORK/alt_rb")
    ALT_CPU_A=$(median <"$WORK/alt_ca") ALT_CPU_B=$(median <"$WORK/alt_cb")
}

# A target on a ratio of two rows' render times (A / B <= LIMIT). The render medians are noisy when other work
# shares the CPUs; the whole-command CPU times are not, and since both commands also pay the same fixed costs,
# CPU(A) / CPU(B) is below the render ratio: if it alone exceeds LIMIT, the target is certainly not met.
# ratio_target TEXT RENDER_A RENDER_B CPU_A CPU_B LIMIT
ratio_target() {
    r=$(awk -v a="$2" -v b="$3" 'BEGIN {if (a == "-" || b == "-" || b <= 0) print "-"; else printf "%.2f", a / b}')
    c=$(awk -v a="$4" -v b="$5" 'BEGIN {if (a == "-" || b == "-" || b <= 0) print "-"; else printf "%.2f", a / b}')
    v=$(awk -v r="$r" -v c="$c" -v l="$6" 'BEGIN {if (r == "-") print "-"; else if (r + 0 > l || (c != "-" && c + 0 > l)) print "not met";
                                                else print "met"}')
    target "$1" "render ${r}x (whole-command CPU ${c}x: the fixed costs both pay dilute it, so the render's own ratio is at least that)$RATIO_HOW" "$v"
}
RATIO_HOW=
# ratio_target over alternate's medians: alternated_target TEXT FIRST-ARG "OPTIONS A" "OPTIONS B" LIMIT
alternated_target() {
    alternate "$2" "$3" "$4" || log "  FAILED: $(failure "$WORK/alt.log")"
    RATIO_HOW="; medians of $ALT_RUNS runs of each, the two taken in turn: $(ms_of_s "$ALT_RENDER_A") / $(ms_of_s "$ALT_RENDER_B") ms"
    ratio_target "$1" "$ALT_RENDER_A" "$ALT_RENDER_B" "$ALT_CPU_A" "$ALT_CPU_B" "$5"
    RATIO_HOW=
}

log "start: $IACSG_SRC, runs $RUNS (growth $GROWTH_RUNS), quick $QUICK, load $(loadavg)"
LOAD0=$(loadavg)
startup_costs
DEVICE=$("$IACSG" devices 2>/dev/null | head -n 1 | sed 's/^0: //')

bench_suite   # suite.sh: the tables
if wants seg; then bench_segment; fi   # segment.sh: the segment path's table

LOAD1=$(loadavg)
ELAPSED=$(( $(date +%s) - T_START ))
{
    echo "# Benchmarks"
    echo ""
    echo "Written by \`make bench\` (tests/bench/bench.sh, scenes in tests/bench/suite.sh)$( [ "$QUICK" = 1 ] && echo ', QUICK mode: fewer runs and rows')."
    echo "Do not edit by hand: run \`make bench\` again."
    echo ""
    echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC'), bench took ${ELAPSED} s"
    echo "- git commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD -- ia implicits kernels src 2>/dev/null || echo ' (with uncommitted changes in ia/ implicits/ kernels/ src/)')"
    echo "- machine: $(lscpu 2>/dev/null | awk -F: '/^Model name/ {gsub(/^ +/, "", $2); print $2}'), $(nproc) CPUs ($(lscpu 2>/dev/null | awk -F: '/^Thread\(s\) per core/ {gsub(/ /, "", $2); t = $2} /^Core\(s\) per socket/ {gsub(/ /, "", $2); c = $2} /^Hypervisor vendor/ {gsub(/^ +/, "", $2); h = " under " $2} END {print c " cores per socket, " t " thread per core" h}'))"
    echo "- OpenCL device: $DEVICE, $(dpkg-query -W -f='${Package} ${Version}' pocl-opencl-icd 2>/dev/null)"
    echo "- load average at start / end: $LOAD0 / $LOAD1 (the 2 CPUs may be shared with other work: see the [min] column)"
    echo "- runs per row: 1 first run (empty PoCL and iacsg kernel caches), 1 untimed run (it has the program's binary saved), $RUNS cached runs ($GROWTH_RUNS in the growth tables)"
    echo ""
    echo "Columns: **render** is the \`-stats\` render time (kernel launches to the image in host memory), median of the"
    echo "cached runs, [minimum]; **evals/ray** the interval evaluations of F per ray; **build** the \`-stats\` kernel"
    echo "build time on the first run (empty cache) and cached: clBuildProgram and the empty launch that makes PoCL compile"
    echo "the kernel's machine code (it would otherwise do so at the first real launch); **render first run** the first"
    echo "frame's render; **wall** the whole command, process start to image written, first run"
    echo "and cached (median); **CPU** the whole command's user + system time, all threads (first / cached median), with"
    echo "that of the process the launcher forked for it (src/cli_launch.c reports it): it hardly moves when other work"
    echo "shares the CPUs, so compare it across runs and machine states. It leaves out the two servers' own loads (the"
    echo "image writer's OpenImageIO, ~0.12 s of CPU, and the launcher's OpenCL driver, ~0.1 s, for the first command of"
    echo "a while, none for the next; a first run pays them only when no server was running)."
    echo "The fixed start-up of a command (through the launcher: its fork, the OpenCL platform and device: \`iacsg devices\`) is"
    echo "**${STARTUP_MS} ms** (median of 5): wall - build - render - start-up is parsing, writing (the \`-stats\` write:"
    echo "the image to 8 bits where the camera kernel did not write bytes, the PNG in the writer, the rename) and exit."
    echo ""
    echo "## Targets (issue 5, and issue 16 where it set a tighter one)"
    echo ""
    echo "| target | measured | verdict |"
    echo "|---|---|---|"
    cat "$TARGETS"
    cat "$BODY"
} >"$GEN"
assemble

log "wrote $OUT (raw numbers in $RAW)"
