/* tests/t_ia_vec_device_fp.c -- ia/vec.h on the OpenCL device: its lanes against ia/'s scalar operations.
 *
 * ia/vec.h promises, for every lane whose operands are nonempty, exactly what ia/ia.h promises, and is built to
 * return the very bits of the scalar ia_* operation on the same device and build. So for each op, the ia/ test
 * program is built with -D IA_VW=8 and with -D IA_VW=16 (in the build options of the rigorous device tests, with
 * IA_FP64 for f64), the same cases run through ia_test_ops (scalar) and ia_test_vops (IA_VW cases per work item,
 * one per lane, tests/ia_ops.cl), and wherever the operands and the scalar result are nonempty the lane must hold
 * the scalar result bit for bit (so -0 against +0 and NaN count) and contain the MPFR values at points of the
 * inputs (pt_check of tests/oracle_ia.h). Where the scalar result is empty the lane may hold anything.
 * Cases: intervals of every pair of special values, the pinned regressions, then the random cases of the scalar
 * tests; for pown, every other group of 16 cases shares one exponent (as in real use, where n is a constant of
 * the expression): half of those cycle through a list of small, large, odd, even, negative and
 * > IA_POWN_CHAIN_MAX exponents (so each meets edge and random intervals), half are random.
 * ia_vec_fast_caught shows the check can fail (IA_FAST drops iav_'s widening too); ia_vec_contains_zero checks
 * iav_contains_zero by hand, NaN and empty lanes included. */
#include "ia/ia.h"
#include "oracle_ia.h"
#include <stdlib.h>

/* tests/t_ia_device_fp.c: the cases on a kernel with ia_test_ops's arguments, `lanes` cases per work item, in the
 * ia/ test program built in a mode (0 rigorous, 1 IA_FAST) with `extra` options after the mode's (that build's
 * "platform / device (options)": ia_dev_describe_in, tests/oracle_ia.h). */
int FP_NAME(ia_dev_ops_in)(int mode, const char *extra, const char *kernel, int lanes, int op, const ia_case *k,
                           long count, ia_real *out, char *err, size_t size);

/* tests/t_ia_device_fp.c: the cases of its ia_sin_cos test and their comparison. */
ia_case *FP_NAME(ia_sin_cos_cases)(long count, ia_real *out[4]);
long FP_NAME(ia_sin_cos_differ)(ia_real *const out[4], long count, long *first);

#define GROUP 16 /* cases are padded to a multiple of every width tested */
static const int widths[] = {8, 16};
#define NW ((int)(sizeof widths / sizeof widths[0]))

static const char *vw_option(int w) { return w == 8 ? "-D IA_VW=8" : "-D IA_VW=16"; }

/* [lo, hi] for every ordered pair of special values (lo <= hi, not [+inf, +inf] nor [-inf, -inf]). */
static int edge_intervals(ia_interval *out) {
    const ia_real v[] = {-IA_INF,
                         -IA_REAL_MAX,
                         -2,
                         -1,
                         -IA_REAL_MIN_NORMAL,
                         -IA_REAL_TRUE_MIN,
                         -0.0,
                         0,
                         IA_REAL_TRUE_MIN,
                         IA_REAL_MIN_NORMAL,
                         (ia_real)0.5,
                         1,
                         3,
                         IA_REAL_MAX,
                         IA_INF};
    const int nv = (int)(sizeof v / sizeof v[0]);
    int m = 0;
    for (int i = 0; i < nv; i++)
        for (int j = i; j < nv; j++)
            if (!(v[i] == IA_INF || v[j] == -IA_INF))
                out[m++] = ia_make(v[i], v[j]);
    return m;
}

/* pown exponents that must be met whatever the random draw gives. */
static const int pinned_n[] = {
    0,    1,    2,    3,     4,     5,     6,     7,     8,      9,       -1,      -2,      -3,     -4,
    15,   16,   17,   31,    32,    33,    63,    64,    65,     100,     127,     128,     255,    256,
    499,  500,  501,  -500,  -501,  511,   512,   513,   1000,   1023,    1024,    1025,    1026,   1100,
    2047, 2048, 4097, -1024, -1025, 65535, 65536, 65537, 100000, 1 << 20, INT_MAX, INT_MIN, -65537, -INT_MAX};
#define NPINNED_N ((long)(sizeof pinned_n / sizeof pinned_n[0]))

static long vec_count(int op) {
    int partial = op == ORACLE_POW || op == ORACLE_LOG || op == ORACLE_SQRT;
    long count = test_iters(partial ? 60000 : 32000);
    return (count + GROUP - 1) / GROUP * GROUP;
}

/* A divisor moved off 0: the half of it on the side of its larger end ([1, 1] for [0, 0]). */
static void pole_free(ia_interval *d) {
    if (!(d->lo <= 0 && d->hi >= 0))
        return;
    if (d->hi > 0)
        d->lo = fmax(d->hi / 2, IA_REAL_TRUE_MIN);
    else if (d->lo < 0)
        d->hi = fmin(d->lo / 2, -IA_REAL_TRUE_MIN);
    else
        *d = ia_point(1);
}

/* The cases of op: with `edges`, every pair of edge intervals (one of each lane's neighbours differs) and the
 * regressions, then random; pown's exponents as said above. count is a multiple of GROUP. */
static void vec_cases(int op, int edges, test_rng_t *r, ia_case *k, long count) {
    ia_interval e[128];
    int ne = edge_intervals(e);
    const ia_real cs[] = {0, -0.0, 1, -1, (ia_real)0.1, 3, IA_REAL_MAX, -IA_REAL_MAX, IA_REAL_TRUE_MIN};
    long i = 0;
    for (; edges && i < count && i < (long)ne * ne; i++) {
        k[i] = gen_case(r, 0);
        k[i].a = e[i / ne], k[i].b = e[i % ne], k[i].c = cs[i % 9];
    }
    long regress = i; /* k[regress, i) keep their own n */
    for (int j = 0; edges && i < count && regress_case(j, &k[i]); j++, i++)
        ;
    long regress_end = i;
    for (; i < count; i++)
        k[i] = gen_case(r, 0);
    if (op == ORACLE_DIV || op == ORACLE_RECIP) /* every other group: divisors away from 0 in every lane, so
                                                    * that whole vectors take iav_div's and iav_recip's vector path */
        for (long g = 1; g < count / GROUP; g += 2)
            for (int j = 0; j < GROUP; j++)
                pole_free(op == ORACLE_DIV ? &k[g * GROUP + j].b : &k[g * GROUP + j].a);
    if (op == ORACLE_POWN)
        for (long g = 0; g < count / GROUP; g += 2) {
            if (g * GROUP < regress_end && (g + 1) * GROUP > regress)
                continue;
            int n = (g / 2) % 2 ? k[g * GROUP].n : pinned_n[(g / 4) % NPINNED_N];
            for (int j = 0; j < GROUP; j++)
                k[g * GROUP + j].n = n;
        }
    if (FP_NAME(ia_dev_flushes)(0)) /* the renderer's build flushes subnormals: the inputs it must be given */
        for (i = 0; i < count; i++)
            case_flushed(&k[i], &k[i]);
}

static int same_bits(ia_real x, ia_real y) { return memcmp(&x, &y, sizeof x) == 0; }

typedef struct {
    long checked, skipped, mismatches, zero_signs, violations, checks; /* zero_signs: mismatches only in a 0's sign */
    char first_mismatch[1024], first_violation[2048];
} vec_report;

/* Runs op's cases through ia_test_ops built in ref_mode and ia_test_vops built in vec_mode, for each width, and
 * compares (see the top); rep[w] gets the counts of widths[w]. Returns 0, or -1 with a message in err when the
 * device cannot run them. */
static int vec_compare(int ref_mode, int vec_mode, int op, const ia_case *k, long count, test_rng_t *r, vec_report *rep,
                       char *err, size_t size) {
    ia_real *ref = malloc(sizeof *ref * 2 * (size_t)count * NW), *vec = malloc(sizeof *vec * 2 * (size_t)count * NW);
    if (!ref || !vec) {
        free(ref), free(vec);
        snprintf(err, size, "out of memory");
        return -1;
    }
    for (int w = 0; w < NW; w++)
        if (FP_NAME(ia_dev_ops_in)(ref_mode, vw_option(widths[w]), "ia_test_ops", 1, op, k, count, ref + 2 * count * w,
                                   err, size) ||
            FP_NAME(ia_dev_ops_in)(vec_mode, vw_option(widths[w]), "ia_test_vops", widths[w], op, k, count,
                                   vec + 2 * count * w, err, size)) {
            free(ref), free(vec);
            return -1;
        }
    const int np = 10, saved_ftz = pt_ftz;
    pt_t p[PT_MAX];
    pt_init(p, np);
    pt_ftz = FP_NAME(ia_dev_flushes)(vec_mode);
    memset(rep, 0, sizeof *rep * NW);
    int uses_b = oracle_op_kind[op] == ORACLE_K_BIN;
    char msg[2048];
    for (long i = 0; i < count; i++) {
        int drawn = 0, operands = !ia_is_empty(k[i].a) && !(uses_b && ia_is_empty(k[i].b));
        for (int w = 0; w < NW; w++) {
            const ia_real *s = ref + 2 * count * w + 2 * i, *v = vec + 2 * count * w + 2 * i;
            if (!operands || !(s[0] <= s[1])) {
                rep[w].skipped++;
                continue;
            }
            rep[w].checked++;
            if (!(same_bits(s[0], v[0]) && same_bits(s[1], v[1]))) {
                rep[w].zero_signs += s[0] == v[0] && s[1] == v[1];
                if (!rep[w].mismatches++)
                    snprintf(rep[w].first_mismatch, sizeof rep[w].first_mismatch,
                             "case %ld, IA_VW=%d, %s: scalar [%s, %s], vector [%s, %s]", i, widths[w],
                             case_str(op, &k[i]), oracle_hex(s[0]), oracle_hex(s[1]), oracle_hex(v[0]),
                             oracle_hex(v[1]));
            }
            if (!drawn)
                pt_draw(op, &k[i], p, np, r), drawn = 1;
            if (pt_check(op, &k[i], p, np, v, vec_mode == 1 ? "iav fast" : "iav", msg, sizeof msg, &rep[w].checks) &&
                !rep[w].violations++)
                snprintf(rep[w].first_violation, sizeof rep[w].first_violation, "case %ld, IA_VW=%d: %.1900s", i,
                         widths[w], msg);
        }
    }
    pt_ftz = saved_ftz;
    pt_clear(p, np);
    free(ref), free(vec);
    return 0;
}

static void run_vec_op(int op) {
    test_rng_t *r = test_rng();
    long count = vec_count(op);
    ia_case *k = malloc(sizeof *k * (size_t)count);
    CHECK(k, "out of memory");
    vec_cases(op, 1, r, k, count);
    vec_report rep[NW];
    char err[1024];
    int rc = vec_compare(0, 0, op, k, count, r, rep, err, sizeof err);
    free(k);
    CHECK(rc == 0, "%s", err);
    test_note("%s", FP_NAME(ia_dev_describe_in)(0, vw_option(widths[NW - 1])));
    for (int w = 0; w < NW; w++)
        test_note("%s " FMT_NAME " IA_VW=%d: %ld cases, %ld lanes bit-identical to ia/ checked (%ld skipped: empty "
                  "operand or result), %ld oracle checks, %ld mismatches (%ld only in the sign of a zero), %ld "
                  "violations",
                  oracle_op_name[op], widths[w], count, rep[w].checked, rep[w].skipped, rep[w].checks,
                  rep[w].mismatches, rep[w].zero_signs, rep[w].violations);
    for (int w = 0; w < NW; w++) {
        CHECK(rep[w].mismatches == 0, "%ld lanes differ from ia/ (%ld only in the sign of a zero); first: %s",
              rep[w].mismatches, rep[w].zero_signs, rep[w].first_mismatch);
        CHECK(rep[w].violations == 0, "%ld lanes miss the exact range; first: %s", rep[w].violations,
              rep[w].first_violation);
        CHECK(rep[w].checked > count / 2, "only %ld of %ld cases checked", rep[w].checked, count);
    }
}

/* One test per op of ia/vec.h, in the order of ORACLE_OPS. */
TEST_FP(ia_vec_add) { run_vec_op(ORACLE_ADD); }
TEST_FP(ia_vec_sub) { run_vec_op(ORACLE_SUB); }
TEST_FP(ia_vec_mul) { run_vec_op(ORACLE_MUL); }
TEST_FP(ia_vec_div) { run_vec_op(ORACLE_DIV); }
TEST_FP(ia_vec_recip) { run_vec_op(ORACLE_RECIP); }
TEST_FP(ia_vec_sqr) { run_vec_op(ORACLE_SQR); }
TEST_FP(ia_vec_pown) { run_vec_op(ORACLE_POWN); }
TEST_FP(ia_vec_pow) { run_vec_op(ORACLE_POW); }
TEST_FP(ia_vec_sqrt) { run_vec_op(ORACLE_SQRT); }
TEST_FP(ia_vec_exp) { run_vec_op(ORACLE_EXP); }
TEST_FP(ia_vec_log) { run_vec_op(ORACLE_LOG); }
TEST_FP(ia_vec_sin) { run_vec_op(ORACLE_SIN); }
TEST_FP(ia_vec_cos) { run_vec_op(ORACLE_COS); }
TEST_FP(ia_vec_tan) { run_vec_op(ORACLE_TAN); }
TEST_FP(ia_vec_atan) { run_vec_op(ORACLE_ATAN); }
TEST_FP(ia_vec_neg) { run_vec_op(ORACLE_NEG); }
TEST_FP(ia_vec_abs) { run_vec_op(ORACLE_ABS); }
TEST_FP(ia_vec_min) { run_vec_op(ORACLE_MIN); }
TEST_FP(ia_vec_max) { run_vec_op(ORACLE_MAX); }
TEST_FP(ia_vec_add_r) { run_vec_op(ORACLE_ADD_R); }
TEST_FP(ia_vec_mul_r) { run_vec_op(ORACLE_MUL_R); }

/* ---- iav_sin_cos: both from one reduction of each point, the bits of iav_sin and iav_cos in every lane (which the
 * tests above hold to ia/'s and to MPFR), on ia_device_sin_cos's cases: narrow, wide, near a zero of either, past
 * the double reduction's range, points, empty and unbounded. */

TEST_FP(ia_vec_sin_cos) {
    long count = (test_iters(20000) + GROUP - 1) / GROUP * GROUP, first = -1, differ = 0;
    ia_real *out[4];
    ia_case *k = FP_NAME(ia_sin_cos_cases)(count, out);
    CHECK(k, "out of memory");
    const int ops[4] = {ORACLE_SIN, ORACLE_COS, IA_TEST_SIN_COS_SIN, IA_TEST_SIN_COS_COS};
    char err[1024] = "";
    for (int w = 0; w < NW && !err[0]; w++) {
        for (int j = 0; j < 4 && !err[0]; j++)
            if (FP_NAME(ia_dev_ops_in)(0, vw_option(widths[w]), "ia_test_vops", widths[w], ops[j], k, count, out[j],
                                       err, sizeof err))
                break;
        if (!err[0])
            differ += FP_NAME(ia_sin_cos_differ)(out, count, &first);
    }
    ia_interval a = first >= 0 ? k[first].a : ia_empty();
    free(k), free(out[0]), free(out[1]), free(out[2]), free(out[3]);
    CHECK(!err[0], "%s", err);
    CHECK(differ == 0, "%ld bounds of iav_sin_cos differ from iav_sin's or iav_cos's, first for [%a, %a]", differ,
          (double)a.lo, (double)a.hi);
    test_note("%ld intervals at IA_VW=8 and 16, sin and cos alike", count);
}

/* ---- the forms for operands that start at 0 or above (ia/vec.h: iav_add_nn ..., which the emitter calls where it
 * proves that, implicits/emit_signs.c): on vec_cases' cases with a (and b, and c, where the form needs them >= 0)
 * moved to [0, +inf) by their magnitudes, each lane holds the generic operation's bounds bit for bit, but where the
 * form clamps its lower bound at 0 (add, add_r, mul, mul_r: >= 0 as the next form needs, never below the generic
 * one), and contains the MPFR values at points of the inputs. */

/* [lo, hi] moved to [0, +inf): itself where lo >= 0 (-0 kept), its mirror where hi <= 0, else [0, max(-lo, hi)]. */
static ia_interval magnitudes(ia_interval a) {
    if (!(a.lo <= a.hi) || a.lo >= 0)
        return a;
    return a.hi <= 0 ? ia_make(-a.hi, -a.lo) : ia_make(0, fmax(-a.lo, a.hi));
}

static const struct {
    int code, op, b_nonneg, clamps;
    const char *name;
} nn_forms[] = {{IA_TEST_ADD_NN, ORACLE_ADD, 1, 1, "add_nn"},     {IA_TEST_ADD_R_NN, ORACLE_ADD_R, 1, 1, "add_r_nn"},
                {IA_TEST_MUL_NN, ORACLE_MUL, 1, 1, "mul_nn"},     {IA_TEST_MUL_R_NN, ORACLE_MUL_R, 1, 1, "mul_r_nn"},
                {IA_TEST_MUL_N, ORACLE_MUL, 0, 0, "mul_n"},       {IA_TEST_SQR_NN, ORACLE_SQR, 0, 0, "sqr_nn"}};

TEST_FP(ia_vec_nonneg_forms) {
    test_rng_t *r = test_rng();
    long count = vec_count(ORACLE_MUL);
    ia_case *k = malloc(sizeof *k * (size_t)count);
    ia_real *generic = malloc(sizeof *generic * 2 * (size_t)count), *form = malloc(sizeof *form * 2 * (size_t)count);
    CHECK(k && generic && form, "out of memory");
    const int np = 10, saved_ftz = pt_ftz;
    pt_t p[PT_MAX];
    pt_init(p, np);
    pt_ftz = FP_NAME(ia_dev_flushes)(0);
    char err[1024] = "", msg[2048], first[2048] = "";
    long checked = 0, differ = 0, violations = 0, checks = 0, clamped = 0;
    for (size_t f = 0; f < sizeof nn_forms / sizeof nn_forms[0] && !err[0]; f++) {
        vec_cases(nn_forms[f].op, 1, r, k, count);
        for (long i = 0; i < count; i++) {
            k[i].a = magnitudes(k[i].a);
            if (nn_forms[f].b_nonneg)
                k[i].b = magnitudes(k[i].b);
            if (nn_forms[f].code == IA_TEST_ADD_R_NN || nn_forms[f].code == IA_TEST_MUL_R_NN)
                k[i].c = k[i].c == 0 ? 1 : fabs(k[i].c); /* the emitter's constants: >= 0, > 0 for a product */
        }
        for (int w = 0; w < NW && !err[0]; w++) {
            if (FP_NAME(ia_dev_ops_in)(0, vw_option(widths[w]), "ia_test_vops", widths[w], nn_forms[f].op, k, count,
                                       generic, err, sizeof err) ||
                FP_NAME(ia_dev_ops_in)(0, vw_option(widths[w]), "ia_test_vops", widths[w], nn_forms[f].code, k, count,
                                       form, err, sizeof err))
                break;
            int uses_b = oracle_op_kind[nn_forms[f].op] == ORACLE_K_BIN;
            for (long i = 0; i < count; i++) {
                const ia_real *g = generic + 2 * i, *v = form + 2 * i;
                if (ia_is_empty(k[i].a) || (uses_b && ia_is_empty(k[i].b)) || !(g[0] <= g[1]))
                    continue;
                checked++;
                int clamp = nn_forms[f].clamps && g[0] <= 0;
                clamped += clamp && g[0] < 0;
                int same = (clamp ? v[0] == 0 : same_bits(v[0], g[0])) && same_bits(v[1], g[1]);
                if (!same && differ++ == 0)
                    snprintf(first, sizeof first, "%s, IA_VW=%d, %s: generic [%s, %s], form [%s, %s]",
                             nn_forms[f].name, widths[w], case_str(nn_forms[f].op, &k[i]), oracle_hex(g[0]),
                             oracle_hex(g[1]), oracle_hex(v[0]), oracle_hex(v[1]));
                pt_draw(nn_forms[f].op, &k[i], p, np, r);
                if (pt_check(nn_forms[f].op, &k[i], p, np, v, nn_forms[f].name, msg, sizeof msg, &checks) &&
                    violations++ == 0)
                    snprintf(first, sizeof first, "%.2000s", msg);
            }
        }
    }
    pt_ftz = saved_ftz;
    pt_clear(p, np);
    free(k), free(generic), free(form);
    CHECK(!err[0], "%s", err);
    test_note("%ld lanes of 6 forms at IA_VW=8 and 16 (%ld lower bounds clamped from below 0), %ld oracle checks",
              checked, clamped, checks);
    CHECK(differ == 0 && violations == 0, "%ld lanes differ from the generic operation, %ld miss the exact range; "
          "first: %s", differ, violations, first);
    CHECK(clamped > 0 && checked > 6 * count, "only %ld lanes checked, %ld clamped", checked, clamped);
}

/* ---- the comparison can fail: iav_ built with IA_FAST (no widening) against the rigorous ia/ */

TEST_FP(ia_vec_fast_caught) {
    static const int ops[] = {ORACLE_ADD, ORACLE_SUB, ORACLE_MUL, ORACLE_SQR, ORACLE_SQRT};
    test_rng_t *r = test_rng();
    long count = (test_iters(4000) + GROUP - 1) / GROUP * GROUP;
    ia_case *k = malloc(sizeof *k * (size_t)count);
    CHECK(k, "out of memory");
    char err[1024], line[1024] = "", first[2048] = "", missed[256] = "";
    size_t len = 0, mlen = 0;
    for (size_t o = 0; o < sizeof ops / sizeof ops[0]; o++) {
        int op = ops[o];
        vec_cases(op, 0, r, k, count);
        vec_report rep[NW];
        if (vec_compare(0, 1, op, k, count, r, rep, err, sizeof err)) {
            free(k);
            CHECK(0, "%s", err);
        }
        for (int w = 0; w < NW; w++) {
            len += (size_t)snprintf(line + len, sizeof line - len, " %s/%d %ld+%ld", oracle_op_name[op], widths[w],
                                    rep[w].mismatches, rep[w].violations);
            if (!first[0] && rep[w].violations)
                snprintf(first, sizeof first, "%s", rep[w].first_violation);
            if (!rep[w].mismatches || !rep[w].violations)
                mlen += (size_t)snprintf(missed + mlen, sizeof missed - mlen, " %s/IA_VW=%d", oracle_op_name[op],
                                         widths[w]);
        }
    }
    free(k);
    test_note("%s", FP_NAME(ia_dev_describe_in)(1, vw_option(widths[NW - 1])));
    test_note("fast iav_ " FMT_NAME " against rigorous ia/, %ld cases per op, op/IA_VW mismatches+violations:%s", count,
              line);
    test_note("first: %.400s", first);
    CHECK(!missed[0], "the check saw no mismatch or no violation of the fast build in:%s", missed);
}

/* ---- iav_contains_zero: false on NaN and on empty lanes */

TEST_FP(ia_vec_contains_zero) {
    /* the smallest positive number of the build: the smallest normal one where it flushes subnormals */
    const ia_real tm = FP_NAME(ia_dev_flushes)(0) ? IA_REAL_MIN_NORMAL : IA_REAL_TRUE_MIN;
    static const struct {
        double lo, hi;
        int zero;
    } t[GROUP] = {{-1, 1, 1},
                  {0, 0, 1},
                  {-0.0, -0.0, 1},
                  {-0.0, 0, 1},
                  {1, 2, 0},
                  {-2, -1, 0},
                  {NAN, 1, 0},
                  {-1, NAN, 0},
                  {NAN, NAN, 0},
                  {INFINITY, -INFINITY, 0},
                  {-INFINITY, INFINITY, 1},
                  {0, INFINITY, 1},
                  {-INFINITY, -0.0, 1},
                  {0x1p-1074, 1, 0},
                  {-1, -0x1p-1074, 0},
                  {INFINITY, 0, 0}};
    ia_case k[2 * GROUP];
    for (int i = 0; i < 2 * GROUP; i++) { /* the cases, then again in reverse order, so each meets other lanes */
        int j = i < GROUP ? i : 2 * GROUP - 1 - i;
        ia_real lo = (ia_real)t[j].lo, hi = (ia_real)t[j].hi;
        if (j == 13)
            lo = tm;
        if (j == 14)
            hi = -tm;
        k[i].a = ia_make(lo, hi), k[i].b = ia_make(0, 0), k[i].n = 0, k[i].c = 0;
    }
    ia_real out[4 * GROUP];
    char err[1024];
    long checked = 0;
    for (int w = 0; w < NW; w++) {
        CHECK(FP_NAME(ia_dev_ops_in)(0, vw_option(widths[w]), "ia_test_vops", widths[w], ORACLE_CZERO, k, 2 * GROUP,
                                     out, err, sizeof err) == 0,
              "%s", err);
        for (int i = 0; i < 2 * GROUP; i++, checked++) {
            int j = i < GROUP ? i : 2 * GROUP - 1 - i;
            ia_real want = t[j].zero ? -1 : 0;
            CHECK(same_bits(out[2 * i], want) && same_bits(out[2 * i + 1], want),
                  "IA_VW=%d: iav_contains_zero([%s, %s]) lane is %s, expected %s", widths[w], oracle_hex(k[i].a.lo),
                  oracle_hex(k[i].a.hi), oracle_hex(out[2 * i]), oracle_hex(want));
        }
    }
    test_note("iav_contains_zero " FMT_NAME ": %ld lanes over IA_VW=8 and 16 (NaN and empty lanes false), all right",
              checked);
}
