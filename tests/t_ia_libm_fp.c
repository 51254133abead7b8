/* tests/t_ia_libm_fp.c -- the host libm under ia/: the maximum ulp error of each function ia/ calls (through
 * <tgmath.h>: sinf for float, sin for double, ...), measured against MPFR, must stay within the IA_ULP_* bound
 * that ia/round.h uses for the host (0 means correctly rounded: half an ulp). The maxima go into the notes. */
#include "ia/ia.h"
#include "oracle_ia.h"
#include <stdlib.h>

static ia_real host_fn(int fn, ia_real x, ia_real y) {
    switch (fn) {
    case ORACLE_FN_DIV: return x / y;
    case ORACLE_FN_SQRT: return sqrt(x);
    case ORACLE_FN_EXP: return exp(x);
    case ORACLE_FN_LOG: return log(x);
    case ORACLE_FN_SIN: return sin(x);
    case ORACLE_FN_COS: return cos(x);
    case ORACLE_FN_TAN: return tan(x);
    case ORACLE_FN_ATAN: return atan(x);
    default: return pow(x, y);
    }
}

TEST_FP(ia_libm_ulps) {
    static const int table[ORACLE_NFNS] = {IA_ULP_DIV,    IA_ULP_SQRT, IA_ULP_EXP,  IA_ULP_LOG, IA_ULP_SINCOS,
                                           IA_ULP_SINCOS, IA_ULP_TAN,  IA_ULP_ATAN, IA_ULP_POW};
    long count = test_iters(60000);
    ia_real *x = malloc(sizeof *x * (size_t)count), *y = malloc(sizeof *y * (size_t)count),
            *res = malloc(sizeof *res * (size_t)count);
    CHECK(x && y && res, "out of memory");
    ulp_report rep = {.bad = -1};
    for (int fn = 0; fn < ORACLE_NFNS; fn++) {
        test_rng_t *r = test_rng();
        for (long i = 0; i < count; i++) {
            fn_args(fn, r, &x[i], &y[i]);
            res[i] = host_fn(fn, x[i], y[i]);
        }
        ulp_report_add(&rep, fn, table[fn], x, y, res, count, 0);
    }
    free(x), free(y), free(res);
    ULP_REPORT_FINISH(rep, "host");
}
