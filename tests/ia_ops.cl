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
    case IA_TEST_SIN_COS_SIN:
    case IA_TEST_SIN_COS_COS: { /* ia_sin_cos's results (tests/t_ia_device_fp.c compares them with ia_sin, ia_cos) */
        ia_interval s, co;
        ia_sin_cos(a, &s, &co);
        return op == IA_TEST_SIN_COS_SIN ? s : co;
    }
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

#ifdef IA_VW
/* ---- ia/vec.h (built with -D IA_VW=8, 16, ...): the layout of ia_test_ops, IA_VW consecutive cases per work item,
 * gathered into the lanes of one iav, so that the host can compare every lane with ia_test_ops on the same case.
 * pown, add_r and mul_r take a constant of the expression (n, c), the same in every lane in real use: for lane j
 * the whole vector goes through the op with case j's constant, and lane j of that result is kept, so every n
 * and c meets IA_VW different intervals at once. IA_OP_CZERO writes iav_contains_zero's lane (-1 or 0) twice. */
#ifdef IA_FP64
typedef long ia_test_mask;
#else
typedef int ia_test_mask;
#endif

IA_FN iav ia_test_vapply(int op, iav a, iav b, int n, ia_real c) {
    switch (op) {
    case IA_OP_ADD: return iav_add(a, b);
    case IA_OP_SUB: return iav_sub(a, b);
    case IA_OP_MUL: return iav_mul(a, b);
    case IA_OP_DIV: return iav_div(a, b);
    case IA_OP_RECIP: return iav_recip(a);
    case IA_OP_SQR: return iav_sqr(a);
    case IA_OP_POWN: return iav_pown(a, n);
    case IA_OP_POW: return iav_pow(a, b);
    case IA_OP_SQRT: return iav_sqrt(a);
    case IA_OP_EXP: return iav_exp(a);
    case IA_OP_LOG: return iav_log(a);
    case IA_OP_SIN: return iav_sin(a);
    case IA_OP_COS: return iav_cos(a);
    case IA_OP_TAN: return iav_tan(a);
    case IA_OP_ATAN: return iav_atan(a);
    case IA_OP_NEG: return iav_neg(a);
    case IA_OP_ABS: return iav_abs(a);
    case IA_OP_MIN: return iav_min(a, b);
    case IA_OP_MAX: return iav_max(a, b);
    case IA_OP_ADD_R: return iav_add_r(a, c);
    case IA_OP_MUL_R: return iav_mul_r(a, c);
    case IA_TEST_SIN_COS_SIN:
    case IA_TEST_SIN_COS_COS: { /* iav_sin_cos's (tests/t_ia_vec_device_fp.c compares them with iav_sin, iav_cos) */
        iav s, co;
        iav_sin_cos(a, &s, &co);
        return op == IA_TEST_SIN_COS_SIN ? s : co;
    }
    case IA_TEST_ADD_NN: return iav_add_nn(a, b);
    case IA_TEST_ADD_R_NN: return iav_add_r_nn(a, c);
    case IA_TEST_MUL_NN: return iav_mul_nn(a, b);
    case IA_TEST_MUL_R_NN: return iav_mul_r_nn(a, c);
    case IA_TEST_MUL_N: return iav_mul_n(a, b);
    case IA_TEST_SQR_NN: return iav_sqr_nn(a);
    }
    return iav_point((ia_real)NAN);
}

kernel void ia_test_vops(int op, global const ia_real *in, global const int *n, global ia_real *out) {
    size_t base = get_global_id(0) * IA_VW;
    ia_real alo[IA_VW], ahi[IA_VW], blo[IA_VW], bhi[IA_VW], rlo[IA_VW], rhi[IA_VW], tlo[IA_VW], thi[IA_VW];
    for (int j = 0; j < IA_VW; j++) {
        global const ia_real *p = in + 5 * (base + (size_t)j);
        alo[j] = p[0], ahi[j] = p[1], blo[j] = p[2], bhi[j] = p[3];
    }
    iav a = iav_make(IAV_LOAD(alo), IAV_LOAD(ahi)), b = iav_make(IAV_LOAD(blo), IAV_LOAD(bhi));
    if (op == IA_OP_CZERO) {
        ia_test_mask m[IA_VW];
        IAV_STORE(iav_contains_zero(a), m);
        for (int j = 0; j < IA_VW; j++)
            rlo[j] = rhi[j] = (ia_real)m[j];
    } else if (op == IA_OP_POWN || op == IA_OP_ADD_R || op == IA_OP_MUL_R || op == IA_TEST_ADD_R_NN ||
               op == IA_TEST_MUL_R_NN) {
        for (int j = 0; j < IA_VW; j++) {
            size_t i = base + (size_t)j;
            iav r = ia_test_vapply(op, a, b, n[i], in[5 * i + 4]);
            IAV_STORE(r.lo, tlo);
            IAV_STORE(r.hi, thi);
            rlo[j] = tlo[j], rhi[j] = thi[j];
        }
    } else {
        iav r = ia_test_vapply(op, a, b, 0, 0);
        IAV_STORE(r.lo, rlo);
        IAV_STORE(r.hi, rhi);
    }
    for (int j = 0; j < IA_VW; j++) {
        out[2 * (base + (size_t)j)] = rlo[j];
        out[2 * (base + (size_t)j) + 1] = rhi[j];
    }
}
#endif
