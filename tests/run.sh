#!/usr/bin/env bash
# tests/run.sh -- what `make test` runs after building: the whole suite, the suite again under AddressSanitizer
# and UndefinedBehaviorSanitizer (a separate build, fewer property-test iterations), and valgrind's leak check
# of the compiler over examples/ (iacsg-compile-tests: the compiler's tests, without OpenImageIO). Prints each
# run's output, then one closing line "N passed, N failed" that sums them; a run that dies before its own closing
# line counts as one failure.
set -uo pipefail
build=${BUILD:-build}
asan=${ASAN_BUILD:-build-asan}
total_passed=0
total_failed=0

# run NAME COMMAND...: runs it, echoes its output, adds its closing line to the totals.
run() {
    local name=$1 log
    shift
    log=$(mktemp)
    echo "== $name: $*"
    "$@" 2>&1 | tee "$log"
    local status=${PIPESTATUS[0]}
    local summary
    summary=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1)
    rm -f "$log"
    if [ -z "$summary" ]; then
        echo "== $name: ended (status $status) before its closing line"
        total_failed=$((total_failed + 1))
        return
    fi
    local p=${summary%% passed*} f=${summary#*, }
    f=${f%% failed}
    total_passed=$((total_passed + p))
    total_failed=$((total_failed + f))
    if [ "$status" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "== $name: exit status $status with no failed test"
        total_failed=$((total_failed + 1))
    fi
}

run "suite" "$build/iacsg-tests"
IACSG_BIN="$PWD/$asan/iacsg" IACSG_TEST_MULT=${IACSG_ASAN_MULT:-0.1} \
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 LSAN_OPTIONS=suppressions="$PWD/tests/lsan.supp":print_suppressions=0 \
    run "sanitizers" "$asan/iacsg-tests"
run "valgrind" valgrind -q --leak-check=full --errors-for-leak-kinds=definite,indirect --error-exitcode=9 \
    "$build/iacsg-compile-tests" examples_compile
echo "$total_passed passed, $total_failed failed"
[ "$total_failed" -eq 0 ]
