#!/bin/sh
# tests/bench/mpi.sh BINARY -- the MPI scale-out of the render command on this machine (issue 15), by hand:
# frames per minute with 1 and 2 ranks, PoCL's threads against ranks, and the serial parts of a job (start-up,
# kernel build per rank, gathering bands). Prints markdown rows; BENCHMARKS.md's section "MPI scale-out" holds
# a run of it. Every time is the median of RUNS whole commands, wall clock, process start to exit.
set -eu
bin=$(realpath "${1:-build/iacsg}")
runs=${RUNS:-5}
frames=${FRAMES:-32}
size=${SIZE:-1024x1024}
scene='min(move(sphere(0.6), t, 0, 0), torus)'
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# the plain command runs itself, as each rank does, so that `times` counts its CPU (src/cli_launch.c)
export IACSG_LAUNCH_IDLE=0
mpirun="mpirun -q --oversubscribe"

# "WALL CPU" seconds of one run of "$@" (output discarded). CPU is user + system of all its processes, from the
# `times` builtin (as tests/bench/bench.sh): unlike wall time it hardly moves when other work shares the CPUs.
wall() {
    rm -f ./*.png ./*.exr
    times >"$work/times0"
    s=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    e=$(date +%s.%N)
    times >"$work/times1"
    printf '%s %s\n' "$(echo "$e - $s" | bc -l)" "$(awk 'function sec(v, a) {split(v, a, "m"); sub(/s$/, "", a[2]);
        return a[1] * 60 + a[2]} FNR == 2 {c[++f] = sec($1) + sec($2)} END {printf "%.3f", c[2] - c[1]}' \
        "$work/times0" "$work/times1")"
}
# median of column $2 (1: wall, 2: CPU) of the numbers in file $1
median_of() { awk -v c="${2:-1}" '{ print $c }' "$1" | sort -n | awk '{ t[NR] = $1 } END { printf "%.3f", t[int((NR + 1) / 2)] }'; }
# "WALL | CPU": the medians of `runs` runs of "$@"
median() {
    for k in $(seq "$runs"); do wall "$@"; done >"$work/one"
    echo "$(median_of "$work/one" 1) | $(median_of "$work/one" 2)"
}

"$bin" "$scene" -size 64x64 -eps 1e-5 -frames 1 -o warm.png >/dev/null # the kernels in PoCL's cache
"$bin" "$scene" -size 64x64 -eps 1e-5 -frames 1 -o warm.png -stats >/dev/null

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
# The configurations, run in turn `runs` times (so that a change of the machine's load hits them alike).
set -- "plain command, PoCL 2 threads|" \
       "mpirun -np 1, PoCL 2 threads|$mpirun -np 1" \
       "mpirun -np 2, PoCL 2 threads each|$mpirun -np 2" \
       "plain command, PoCL 1 thread|env POCL_MAX_PTHREAD_COUNT=1" \
       "mpirun -np 2, PoCL 1 thread each|env POCL_MAX_PTHREAD_COUNT=1 $mpirun -np 2"
for k in $(seq "$runs"); do
    n=0
    for config in "$@"; do
        n=$((n + 1))
        # shellcheck disable=SC2086 # the launcher's words are split on purpose
        wall ${config#*|} "$bin" "$scene" -size "$size" -eps 1e-5 -frames "$frames" -o f.png >>"$work/config$n"
    done
done
echo "| how ($frames frames of $size, eps 1e-5; median of $runs) | wall s | frames per minute | CPU s, all processes |"
echo "|---|---|---|---|"
n=0
for config in "$@"; do
    n=$((n + 1))
    t=$(median_of "$work/config$n" 1)
    echo "| ${config%%|*} | $t | $(echo "60 * $frames / $t" | bc -l | xargs printf '%.0f') | $(median_of "$work/config$n" 2) |"
done
echo
echo "| serial part | wall s | CPU s |"
echo "|---|---|---|"
tiny="'$scene' -size 64x64 -eps 1e-5 -frames 2 -o t.png"
plain=$(median sh -c "\"$bin\" $tiny")
one=$(median sh -c "$mpirun -np 1 \"$bin\" $tiny")
two=$(median sh -c "$mpirun -np 2 \"$bin\" $tiny")
echo "| whole command, 2 tiny frames, plain (start-up, kernel build cached, writer) | $plain |"
echo "| the same under mpirun -np 1 (+ mpirun's launch, MPI_Init, MPI_Finalize) | $one |"
echo "| the same under mpirun -np 2 (+ a second rank starting and building on the same 2 cores) | $two |"
build=$("$bin" "$scene" -size 64x64 -eps 1e-5 -o t.png -stats | sed -n 's/^kernel build: \([0-9.]*\) s/\1/p')
echo "| kernel build, cached (-stats), one process | $build | |"
cold=$(POCL_CACHE_DIR=$(mktemp -d -p "$work") "$bin" "$scene" -size 64x64 -eps 1e-5 -o t.png -stats | sed -n 's/^kernel build: \([0-9.]*\) s/\1/p')
echo "| kernel build, not cached (an empty POCL_CACHE_DIR), one process | $cold | |"
# Gathering: a frame whose rays all miss (the bounds out of view) costs little to trace, so what 2 ranks add
# to one is handing out the bands and sending rank 1's rows to rank 0 (3 floats a pixel).
empty="sphere -bounds 5,5,5,6,6,6 -at 0,0,0 -eye 0,-4,0 -size 4096x4096 -o g.png"
g1=$(median sh -c "$mpirun -np 1 \"$bin\" $empty")
g2=$(median sh -c "$mpirun -np 2 \"$bin\" $empty")
echo "| one 4096x4096 frame with nothing to trace, mpirun -np 1 (the PNG write dominates) | $g1 |"
echo "| the same in bands over 2 ranks (+ rank 1's share of the 192 MiB of floats sent to rank 0) | $g2 |"
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
