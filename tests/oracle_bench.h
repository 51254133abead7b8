/* tests/oracle_bench.h -- the host timing loop of the ia/ benchmark, included by tests/bench_ia_fp.c (rigorous)
 * and tests/bench_ia_fast_fp.c (IA_FAST), so that both modes run the same loop over the same inputs. */
#ifndef IACSG_ORACLE_BENCH_H
#define IACSG_ORACLE_BENCH_H
#include "oracle_ia.h" /* after ia/ia.h */
#include <time.h>

/* Applies op to count cases, reps times over; returns nanoseconds per application. */
static inline double bench_host_loop(int op, const ia_case *k, long count, int reps) {
    volatile ia_real sink = 0;
    ia_real acc = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int r = 0; r < reps; r++) {
#define LOOP(expr)                                                                                                     \
    for (long i = 0; i < count; i++) {                                                                                 \
        ia_interval v = expr;                                                                                          \
        acc += v.lo - v.hi;                                                                                            \
    }                                                                                                                  \
    break;
        switch (op) {
        case ORACLE_ADD: LOOP(ia_add(k[i].a, k[i].b))
        case ORACLE_SUB: LOOP(ia_sub(k[i].a, k[i].b))
        case ORACLE_MUL: LOOP(ia_mul(k[i].a, k[i].b))
        case ORACLE_DIV: LOOP(ia_div(k[i].a, k[i].b))
        case ORACLE_RECIP: LOOP(ia_recip(k[i].a))
        case ORACLE_SQR: LOOP(ia_sqr(k[i].a))
        case ORACLE_POWN: LOOP(ia_pown(k[i].a, k[i].n))
        case ORACLE_POW: LOOP(ia_pow(k[i].a, k[i].b))
        case ORACLE_SQRT: LOOP(ia_sqrt(k[i].a))
        case ORACLE_EXP: LOOP(ia_exp(k[i].a))
        case ORACLE_LOG: LOOP(ia_log(k[i].a))
        case ORACLE_SIN: LOOP(ia_sin(k[i].a))
        case ORACLE_COS: LOOP(ia_cos(k[i].a))
        case ORACLE_TAN: LOOP(ia_tan(k[i].a))
        case ORACLE_ATAN: LOOP(ia_atan(k[i].a))
        case ORACLE_NEG: LOOP(ia_neg(k[i].a))
        case ORACLE_ABS: LOOP(ia_abs(k[i].a))
        case ORACLE_MIN: LOOP(ia_min(k[i].a, k[i].b))
        case ORACLE_MAX: LOOP(ia_max(k[i].a, k[i].b))
        case ORACLE_HULL: LOOP(ia_hull(k[i].a, k[i].b))
        case ORACLE_INTERSECT: LOOP(ia_intersect(k[i].a, k[i].b))
        case ORACLE_ADD_R: LOOP(ia_add_r(k[i].a, k[i].c))
        case ORACLE_MUL_R: LOOP(ia_mul_r(k[i].a, k[i].c))
        case ORACLE_MID: LOOP(ia_point(ia_mid(k[i].a)))
        case ORACLE_WIDTH: LOOP(ia_point(ia_width(k[i].a)))
        default: LOOP(ia_point((ia_real)ia_contains_zero(k[i].a)))
        }
#undef LOOP
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    sink = acc;
    (void)sink;
    return ((double)(t1.tv_sec - t0.tv_sec) * 1e9 + (double)(t1.tv_nsec - t0.tv_nsec)) / ((double)count * reps);
}

#endif
