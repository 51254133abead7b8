/* tests/bench_ia_fast_fp.c -- ia/ in fast mode (IA_FAST: no widening) on the host, for tests/bench_ia_fp.c. */
#define IA_FAST 1
#include "ia/ia.h"
#include "oracle_bench.h"
#include "oracle_ia.h"

double FP_NAME(bench_ia_host_fast)(int op, const ia_case *k, long count, int reps);
double FP_NAME(bench_ia_host_fast)(int op, const ia_case *k, long count, int reps) {
    return bench_host_loop(op, k, count, reps);
}
