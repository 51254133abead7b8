/* tests/t_ia_ops_fp.c -- containment of every ia/ operation, on the host and on the OpenCL device, against MPFR.
 *
 * For each op: pinned regression cases (iteration 0), then random cases of every kind (tests/oracle_ia.h); each
 * case runs on the host (these headers) and on the device (the same headers built by OpenCL with the options
 * of clrt_ia_options); points are drawn inside the inputs, end points included, the exact value at each comes
 * from MPFR, and both results must contain it (the device's build flushes subnormals: it is given each case as
 * case_flushed makes it, subnormal bounds moved outward, and checked at points of that case). Set ops, queries,
 * mid and width are checked exactly.
 * IACSG_TEST_MULT scales the case count; the default makes >= 10^6 checks per op over f32 and f64, host and
 * device. A failure prints the op, every input in hex, the point, the oracle value and the result. */
#include "ia/ia.h"
#include "oracle_ia.h"
#include <stdlib.h>

/* Inputs that once broke something or sit on a boundary of the definition: run first, always. */
static ia_interval pinned_interval(int i) {
    const ia_real pi_lo = IA_PI_LO, pi_hi = IA_PI_HI;
    switch (i % 24) {
    case 0: return ia_make(-0.0, -0.0);
    case 1: return ia_make(0, 0);
    case 2: return ia_make(-0.0, 2);
    case 3: return ia_make(-2, -0.0);
    case 4: return ia_make(1, 1);
    case 5: return ia_entire();
    case 6: return ia_empty();
    case 7: return ia_make(-IA_INF, -0.0);
    case 8: return ia_make(0, IA_INF);
    case 9: return ia_make(pi_lo, pi_hi);
    case 10: return ia_make(pi_lo * (ia_real)0.5, pi_hi * (ia_real)0.5);
    case 11: return ia_make(-IA_REAL_MAX, IA_REAL_MAX);
    case 12: return ia_make(IA_REAL_MAX, IA_INF);
    case 13: return ia_make(-IA_INF, -IA_REAL_MAX);
    case 14: return ia_make(IA_REAL_TRUE_MIN, IA_REAL_TRUE_MIN);
    case 15: return ia_make(-IA_REAL_TRUE_MIN, IA_REAL_TRUE_MIN);
    case 16: return ia_make(-1, 1);
    case 17: return ia_make(1, 2);
    case 18: return ia_make(-pi_hi * 2, pi_hi * 2);
    case 19: return ia_make(IA_REAL_MIN_NORMAL, 1);
    case 20: return ia_make(-3, -2);
    case 21: return ia_make((ia_real)0.5, IA_REAL_MAX);
    case 22: return ia_make(pi_hi * (ia_real)1e6, pi_hi * (ia_real)1e6 + 1);
    default: return ia_make(-IA_REAL_MAX, -1);
    }
}
#define PINNED 576 /* 24 x 24 */

static ia_case pinned_case(int i) {
    static const int ns[] = {0, 1, 2, 3, -1, -2, -3, 500, -500, 501, -501, INT_MIN, INT_MAX, 4, 7, -8};
    const ia_real cs[] = {0, -0.0, 1, -1, IA_REAL_MAX, IA_REAL_TRUE_MIN, (ia_real)0.1, -IA_REAL_MAX, 3};
    ia_case k;
    k.a = pinned_interval(i / 24);
    k.b = pinned_interval(i % 24);
    k.n = ns[i % 16];
    k.c = cs[i % 9];
    return k;
}

static void run_op(int op) {
    test_rng_t *r = test_rng();
    int np = op == ORACLE_MID ? 1 : 10;
    /* ops with a restricted domain lose about half their points: give them more cases */
    int partial = op == ORACLE_POW || op == ORACLE_LOG || op == ORACLE_SQRT;
    long count = test_iters(op == ORACLE_MID ? 300000 : partial ? 60000 : 32000);
    if (count < PINNED + 100)
        count = PINNED + 100;
    ia_case *k = malloc(sizeof *k * (size_t)count), *kd = malloc(sizeof *kd * (size_t)count);
    ia_real *host = malloc(sizeof *host * 2 * (size_t)count), *devo = malloc(sizeof *devo * 2 * (size_t)count);
    CHECK(k && kd && host && devo, "out of memory");
    int ftz = FP_NAME(ia_dev_flushes)(0), host_ftz = pt_ftz;
    for (long i = 0; i < count; i++) {
        if (i < PINNED)
            k[i] = pinned_case((int)i);
        else if (!regress_case((int)(i - PINNED), &k[i]))
            k[i] = gen_case(r, 0);
        ia_apply(op, &k[i], host + 2 * i);
        if (!ftz || !case_flushed(&k[i], &kd[i])) /* the device's case: as a flushing build must be given it */
            kd[i] = k[i];
    }
    char msg[2048];
    int have_dev = FP_NAME(ia_dev_ops)(0, op, kd, count, devo, msg, sizeof msg) == 0;
    if (!have_dev) {
        free(k), free(kd), free(host), free(devo);
        CHECK(0, "%s", msg);
    }
    pt_t p[PT_MAX];
    pt_init(p, np);
    long checks_host = 0, checks_dev = 0;
    for (long i = 0; i < count; i++) {
        pt_draw(op, &k[i], p, np, r);
        int bad = pt_check(op, &k[i], p, np, host + 2 * i, "host", msg, sizeof msg, &checks_host);
        if (!bad && ftz && case_flushed(&k[i], &kd[i])) /* the device's case has points of its own */
            pt_draw(op, &kd[i], p, np, r);
        pt_ftz = ftz;
        if (!bad)
            bad = pt_check(op, &kd[i], p, np, devo + 2 * i, "device", msg, sizeof msg, &checks_dev);
        pt_ftz = host_ftz;
        if (bad) {
            pt_clear(p, np);
            free(k), free(kd), free(host), free(devo);
            CHECK(0, "case %ld: %s", i, msg);
        }
    }
    pt_clear(p, np);
    free(k), free(kd), free(host), free(devo);
    test_note("%s " FMT_NAME ": %ld cases, %ld host + %ld device checks, 0 violations", oracle_op_name[op], count,
              checks_host, checks_dev);
}

/* One test per op (the Makefile collects TEST_FP lines), in the order of ORACLE_OPS. */
TEST_FP(ia_op_add) { run_op(ORACLE_ADD); }
TEST_FP(ia_op_sub) { run_op(ORACLE_SUB); }
TEST_FP(ia_op_mul) { run_op(ORACLE_MUL); }
TEST_FP(ia_op_div) { run_op(ORACLE_DIV); }
TEST_FP(ia_op_recip) { run_op(ORACLE_RECIP); }
TEST_FP(ia_op_sqr) { run_op(ORACLE_SQR); }
TEST_FP(ia_op_pown) { run_op(ORACLE_POWN); }
TEST_FP(ia_op_pow) { run_op(ORACLE_POW); }
TEST_FP(ia_op_sqrt) { run_op(ORACLE_SQRT); }
TEST_FP(ia_op_exp) { run_op(ORACLE_EXP); }
TEST_FP(ia_op_log) { run_op(ORACLE_LOG); }
TEST_FP(ia_op_sin) { run_op(ORACLE_SIN); }
TEST_FP(ia_op_cos) { run_op(ORACLE_COS); }
TEST_FP(ia_op_tan) { run_op(ORACLE_TAN); }
TEST_FP(ia_op_atan) { run_op(ORACLE_ATAN); }
TEST_FP(ia_op_neg) { run_op(ORACLE_NEG); }
TEST_FP(ia_op_abs) { run_op(ORACLE_ABS); }
TEST_FP(ia_op_min) { run_op(ORACLE_MIN); }
TEST_FP(ia_op_max) { run_op(ORACLE_MAX); }
TEST_FP(ia_op_hull) { run_op(ORACLE_HULL); }
TEST_FP(ia_op_intersect) { run_op(ORACLE_INTERSECT); }
TEST_FP(ia_op_mid) { run_op(ORACLE_MID); }
TEST_FP(ia_op_width) { run_op(ORACLE_WIDTH); }
TEST_FP(ia_op_add_r) { run_op(ORACLE_ADD_R); }
TEST_FP(ia_op_mul_r) { run_op(ORACLE_MUL_R); }
TEST_FP(ia_op_certainly_neg) { run_op(ORACLE_CNEG); }
TEST_FP(ia_op_certainly_pos) { run_op(ORACLE_CPOS); }
TEST_FP(ia_op_contains_zero) { run_op(ORACLE_CZERO); }
TEST_FP(ia_op_is_empty) { run_op(ORACLE_ISEMPTY); }
TEST_FP(ia_op_is_entire) { run_op(ORACLE_ISENTIRE); }
TEST_FP(ia_op_contains) { run_op(ORACLE_CONTAINS); }

/* ia_div_one_signed (the closed-form segments' divisions) is ia_div, bit for bit, wherever its divisor is one-signed
 * away from 0 and no corner is inf / inf: random and pinned dividends (empties aside) over random such divisors,
 * finite and infinite, of both signs; ia_div is the MPFR-checked one (ia_op_div). */
TEST_FP(ia_div_one_signed_is_ia_div) {
    test_rng_t *r = test_rng();
    long count = test_iters(1000000), compared = 0;
    for (long i = 0; i < count; i++) {
        ia_interval a = i < PINNED ? pinned_interval((int)i) : gen_interval(r, 0), b = gen_interval(r, 0);
        if (i % 2)
            b = ia_neg(b);
        if (ia_is_empty(a) || ia_is_empty(b) || !(b.lo > 0 || b.hi < 0) ||
            ((isinf(a.lo) || isinf(a.hi)) && (isinf(b.lo) || isinf(b.hi))))
            continue;
        ia_interval want = ia_div(a, b), got = ia_div_one_signed(a, b);
        CHECK(memcmp(&want, &got, sizeof want) == 0,
              "[%a, %a] / [%a, %a]: ia_div [%a, %a], ia_div_one_signed [%a, %a]", (double)a.lo, (double)a.hi,
              (double)b.lo, (double)b.hi, (double)want.lo, (double)want.hi, (double)got.lo, (double)got.hi);
        compared++;
    }
    CHECK(compared > count / 4, "only %ld of %ld cases had a one-signed divisor", compared, count);
    test_note(FMT_NAME ": %ld divisions identical", compared);
}
