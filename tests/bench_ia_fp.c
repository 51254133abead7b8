/* tests/bench_ia_fp.c -- nanoseconds per ia/ operation on the host and on the OpenCL device, rigorous and fast
 * (IA_FAST), float and double: the cost of rigor. Not a test: run by `make bench-ia` (build/iacsg-tests
 * bench_ia). Inputs are moderate finite intervals (bounds in [-8, 8], widths up to 4), the same for every
 * mode. Host: one core, a loop over 4096 cases. Device: ia_bench_ops in tests/ia_ops.cl, 2^16 work items of
 * 128 applications each; the time is the kernel's wall time over all applications (throughput of the whole
 * device), loads and a sum included. IACSG_TEST_MULT scales the repetitions. */
#include "ia/ia.h"
#include "oracle_bench.h"
#include "oracle_ia.h"
#include <stdlib.h>

double FP_NAME(bench_ia_host_fast)(int op, const ia_case *k, long count, int reps);

static ia_interval bench_interval(test_rng_t *r) {
    ia_real lo = (ia_real)(test_rand_unit(r) * 16 - 8);
    return ia_make(lo, lo + (ia_real)(test_rand_unit(r) * 4));
}

TEST_FP(bench_ia) {
    test_rng_t *r = test_rng();
    const long count = 4096, items = 1l << 16;
    const int dev_reps = 128;
    int reps = (int)test_iters(100);
    ia_case *k = malloc(sizeof *k * (size_t)count);
    CHECK(k, "out of memory");
    for (long i = 0; i < count; i++) {
        k[i].a = bench_interval(r);
        k[i].b = bench_interval(r);
        k[i].n = 2 + (int)gen_u32(r, 6);
        k[i].c = (ia_real)(test_rand_unit(r) * 4 - 2);
    }
    char err[1024];
    double s;
    int have_dev = FP_NAME(ia_dev_bench)(0, ORACLE_ADD, dev_reps, k, count, items, &s, err, sizeof err) == 0;
    if (have_dev)
        test_note("device: %s", FP_NAME(ia_dev_describe)(0));
    else
        test_note("no device: %s", err);
    test_note("ns per op " FMT_NAME ":  host rigorous / fast (overhead)  |  device rigorous / fast (overhead)");
    double sum_hr = 0, sum_hf = 0, sum_dr = 0, sum_df = 0;
    for (int op = 0; op < ORACLE_NOPS; op++) {
        if (oracle_op_kind[op] == ORACLE_K_QUERY && op != ORACLE_CZERO)
            continue;
        double hr = 1e30, hf = 1e30, dr = 1e30, df = 1e30;
        for (int t = 0; t < 3; t++) { /* best of three */
            double x = bench_host_loop(op, k, count, reps), y = FP_NAME(bench_ia_host_fast)(op, k, count, reps);
            hr = x < hr ? x : hr, hf = y < hf ? y : hf;
            if (have_dev) {
                double sr = 0, sf = 0;
                if (FP_NAME(ia_dev_bench)(0, op, dev_reps, k, count, items, &sr, err, sizeof err) ||
                    FP_NAME(ia_dev_bench)(1, op, dev_reps, k, count, items, &sf, err, sizeof err)) {
                    free(k);
                    CHECK(0, "%s", err);
                }
                sr = sr * 1e9 / ((double)items * dev_reps), sf = sf * 1e9 / ((double)items * dev_reps);
                dr = sr < dr ? sr : dr, df = sf < df ? sf : df;
            }
        }
        sum_hr += hr, sum_hf += hf;
        if (have_dev)
            sum_dr += dr, sum_df += df;
        if (have_dev)
            test_note("  %-14s %7.2f / %7.2f (%+4.0f%%)  |  %7.3f / %7.3f (%+4.0f%%)", oracle_op_name[op], hr, hf,
                      (hr / hf - 1) * 100, dr, df, (dr / df - 1) * 100);
        else
            test_note("  %-14s %7.2f / %7.2f (%+4.0f%%)", oracle_op_name[op], hr, hf, (hr / hf - 1) * 100);
    }
    test_note("  %-14s %7.2f / %7.2f (%+4.0f%%)  |  %7.3f / %7.3f (%+4.0f%%)", "sum", sum_hr, sum_hf,
              (sum_hr / sum_hf - 1) * 100, sum_dr, sum_df, have_dev ? (sum_dr / sum_df - 1) * 100 : 0.0);
    free(k);
}
