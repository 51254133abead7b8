/* tests/ia_ops.cl -- device side of the ia/ tests: evaluates the operations of ia/ and the raw math built-ins
 * on arrays, so the host can check the results against MPFR. Built after iacsg_cl_ia (ia/ concatenated) and
 * a prelude the host generates from tests/oracle.h: "#define IA_OP_ADD 0" ... and "#define IA_FN_DIV 0" ...
 *
 * Layout: case i has in[5i .. 5i+4] = a.lo, a.hi, b.lo, b.hi, c and n[i]; it writes out[2i], out[2i+1]
 * (an interval, or a real or truth value twice). */

IA_FN ia_interval ia_test_apply(int op, ia_interval a, ia_interval b, int n, ia_real c, ia_real *scalar,
                                int *is_scalar) {
    *is_scalar = 0;
    switch (op) {
    case IA_OP_ADD: return ia_add(a, b);
    case IA_OP_SUB: return ia_sub(a, b);
    case IA_OP_MUL: return ia_mul(a, b);
    case IA_OP_DIV: return ia_div(a, b);
    case IA_OP_RECIP: return ia_recip(a);
    case IA_OP_SQR: return ia_sqr(a);
    case IA_OP_POWN: return ia_pown(a, n);
    case IA_OP_POW: return ia_pow(a, b);
    case IA_OP_SQRT: return ia_sqrt(a);
    case IA_OP_EXP: return ia_exp(a);
    case IA_OP_LOG: return ia_log(a);
    case IA_OP_SIN: return ia_sin(a);
    case IA_OP_COS: return ia_cos(a);
    case IA_OP_TAN: return ia_tan(a);
    case IA_OP_ATAN: return ia_atan(a);
    case IA_OP_NEG: return ia_neg(a);
    case IA_OP_ABS: return ia_abs(a);
    case IA_OP_MIN: return ia_min(a, b);
    case IA_OP_MAX: return ia_max(a, b);
    case IA_OP_HULL: return ia_hull(a, b);
    case IA_OP_INTERSECT: return ia_intersect(a, b);
    case IA_OP_ADD_R: return ia_add_r(a, c);
    case IA_OP_MUL_R: return ia_mul_r(a, c);
    }
    *is_scalar = 1;
    switch (op) {
    case IA_OP_MID: *scalar = ia_mid(a); break;
    case IA_OP_WIDTH: *scalar = ia_width(a); break;
    case IA_OP_CNEG: *scalar = (ia_real)ia_certainly_neg(a); break;
    case IA_OP_CPOS: *scalar = (ia_real)ia_certainly_pos(a); break;
    case IA_OP_CZERO: *scalar = (ia_real)ia_contains_zero(a); break;
    case IA_OP_ISEMPTY: *scalar = (ia_real)ia_is_empty(a); break;
    case IA_OP_ISENTIRE: *scalar = (ia_real)ia_is_entire(a); break;
    case IA_OP_CONTAINS: *scalar = (ia_real)ia_contains(a, c); break;
    default: *scalar = (ia_real)NAN; break;
    }
    return a;
}

kernel void ia_test_ops(int op, global const ia_real *in, global const int *n, global ia_real *out) {
    size_t i = get_global_id(0);
    ia_real s = 0;
    int is_scalar;
    ia_interval r = ia_test_apply(op, ia_make(in[5 * i], in[5 * i + 1]), ia_make(in[5 * i + 2], in[5 * i + 3]),
                                  n[i], in[5 * i + 4], &s, &is_scalar);
    out[2 * i] = is_scalar ? s : r.lo;
    out[2 * i + 1] = is_scalar ? s : r.hi;
}

/* The built-ins ia/ relies on, unwidened, for measuring their ulp error. */
kernel void ia_test_fns(int fn, global const ia_real *x, global const ia_real *y, global ia_real *out) {
    size_t i = get_global_id(0);
    ia_real u = x[i], v = y[i], r;
    switch (fn) {
    case IA_FN_DIV: r = u / v; break;
    case IA_FN_SQRT: r = sqrt(u); break;
    case IA_FN_EXP: r = exp(u); break;
    case IA_FN_LOG: r = log(u); break;
    case IA_FN_SIN: r = sin(u); break;
    case IA_FN_COS: r = cos(u); break;
    case IA_FN_TAN: r = tan(u); break;
    case IA_FN_ATAN: r = atan(u); break;
    default: r = pow(u, v); break;
    }
    out[i] = r;
}

/* Benchmark: each work item applies op `reps` times to cases (i + k) mod count and sums the bounds. */
kernel void ia_bench_ops(int op, int reps, int count, global const ia_real *in, global const int *n,
                         global ia_real *out) {
    size_t i = get_global_id(0);
    ia_real acc = 0, s = 0;
    int is_scalar;
    for (int k = 0; k < reps; k++) {
        size_t j = (i + (size_t)k) % (size_t)count;
        ia_interval r = ia_test_apply(op, ia_make(in[5 * j], in[5 * j + 1]), ia_make(in[5 * j + 2], in[5 * j + 3]),
                                      n[j], in[5 * j + 4], &s, &is_scalar);
        acc += is_scalar ? s : r.lo - r.hi;
    }
    out[i] = acc;
}

/* The error bounds (ulps) this build of ia/ assumes, per IA_FN_* function, whether IA_FTZ is on, and the largest
 * exponent ia_pown computes by square-and-multiply. */
kernel void ia_test_ulp_table(global int *out) {
    if (get_global_id(0) != 0)
        return;
    out[IA_FN_DIV] = IA_ULP_DIV;
    out[IA_FN_SQRT] = IA_ULP_SQRT;
    out[IA_FN_EXP] = IA_ULP_EXP;
    out[IA_FN_LOG] = IA_ULP_LOG;
    out[IA_FN_SIN] = IA_ULP_SINCOS;
    out[IA_FN_COS] = IA_ULP_SINCOS;
    out[IA_FN_TAN] = IA_ULP_TAN;
    out[IA_FN_ATAN] = IA_ULP_ATAN;
    out[IA_FN_POW] = IA_ULP_POW;
#ifdef IA_FTZ
    out[IA_FN_POW + 1] = 1;
#else
    out[IA_FN_POW + 1] = 0;
#endif
    out[IA_FN_POW + 2] = IA_POWN_CHAIN_MAX;
}
