/* tests/t_ia_tight_fp.c -- tightness of ia/: the exact range of each operation over each random case comes from
 * MPFR (end points, corners, and the interior extrema of sin, cos, sqr and even powers; poles of tan and 1/x),
 * rounded outward to the format; the result must contain it and exceed it by at most the documented number of
 * format steps on each side (ia/ia.h): 0 for the exact ops, 1 for correctly rounded ones (2 near 0), and for a
 * function with a k-ulp bound 3k+3 (2k+2 from the widening of ia/round.h, k+1 from the function itself). sin
 * and cos must return exactly +-1 when an extremum is inside, sqr and even pown exactly 0 when 0 is inside.
 * Checked on the host and on the device, whose k come from its own build (ia_test_ulp_table).
 *
 * ia_tight_catches_lazy shows that this checker fails deliberately lazy implementations. */
#include "ia/ia.h"
#include "oracle_ia.h"
#include <stdlib.h>

/* The exact range of op over case k: [*lo, *hi] as extended reals (MPFR, exact or rounded outward), or
 * *empty. *lo_ext / *hi_ext are set when that bound is an interior extremum (sin, cos: +-1; sqr, even pown: 0)
 * that must be returned exactly. Only for the ops of kinds UN, BIN, POWN, REAL. */
typedef struct {
    mpfr_t lo, hi;
    int empty, lo_ext, hi_ext;
} range_t;

static mpfr_t T1, T2, PI;
static void scratch_init(void) {
    static int done;
    if (done)
        return;
    oracle_init();
    mpfr_inits2(ORACLE_PREC, T1, T2, (mpfr_ptr)0);
    mpfr_init2(PI, 2400);
    mpfr_const_pi(PI, MPFR_RNDN);
    done = 1;
}

static void r_setd(range_t *g, double l, double h) {
    mpfr_set_d(g->lo, l, MPFR_RNDD);
    mpfr_set_d(g->hi, h, MPFR_RNDU);
}
/* Adds the value v (extended real) to the hull being built (first call: start). */
static void r_add(range_t *g, mpfr_srcptr v, int *first) {
    if (*first) {
        mpfr_set(g->lo, v, MPFR_RNDD), mpfr_set(g->hi, v, MPFR_RNDU);
        *first = 0;
        return;
    }
    if (mpfr_cmp(v, g->lo) < 0)
        mpfr_set(g->lo, v, MPFR_RNDD);
    if (mpfr_cmp(v, g->hi) > 0)
        mpfr_set(g->hi, v, MPFR_RNDU);
}

/* x * y with 0 * inf = 0, as limits of products of finite values; rounded down and up into lo/hi adds. */
static void add_product(range_t *g, double x, double y, int *first) {
    if ((x == 0 && isinf(y)) || (y == 0 && isinf(x))) {
        mpfr_set_zero(T1, 1);
        r_add(g, T1, first);
        return;
    }
    mpfr_set_d(T1, x, MPFR_RNDN);
    mpfr_mul_d(T2, T1, y, MPFR_RNDD);
    r_add(g, T2, first);
    mpfr_mul_d(T2, T1, y, MPFR_RNDU);
    r_add(g, T2, first);
}
/* x / y for y != 0 of one sign, with the limits: inf/inf spans [0, inf] with its sign, finite/inf = 0. */
static void add_quotient(range_t *g, double x, double y, int *first) {
    if (isinf(x) && isinf(y)) {
        int s = (x > 0) == (y > 0) ? 1 : -1;
        mpfr_set_zero(T1, s);
        r_add(g, T1, first);
        mpfr_set_inf(T1, s);
        r_add(g, T1, first);
        return;
    }
    mpfr_set_d(T1, x, MPFR_RNDN);
    mpfr_div_d(T2, T1, y, MPFR_RNDD);
    r_add(g, T2, first);
    mpfr_div_d(T2, T1, y, MPFR_RNDU);
    r_add(g, T2, first);
}
/* f(x) rounded down and up, added. fn: one of the UN ops (exp, log, sqrt, atan, tan, sin, cos, recip). */
static void add_fn(range_t *g, int op, double x, long n, int *first) {
    mpfr_set_d(T1, x, MPFR_RNDN);
    for (int dir = 0; dir < 2; dir++) {
        mpfr_rnd_t m = dir ? MPFR_RNDU : MPFR_RNDD;
        switch (op) {
        case ORACLE_EXP: mpfr_exp(T2, T1, m); break;
        case ORACLE_LOG: mpfr_log(T2, T1, m); break;
        case ORACLE_SQRT: mpfr_sqrt(T2, T1, m); break;
        case ORACLE_ATAN: mpfr_atan(T2, T1, m); break;
        case ORACLE_TAN: mpfr_tan(T2, T1, m); break;
        case ORACLE_SIN: mpfr_sin(T2, T1, m); break;
        case ORACLE_COS: mpfr_cos(T2, T1, m); break;
        case ORACLE_POWN: mpfr_pow_si(T2, T1, n, m); break;
        default: mpfr_ui_div(T2, 1, T1, m); break;
        }
        r_add(g, T2, first);
    }
}

/* Whether [lo, hi] (finite) contains a point (j + shift) * pi with j of the given parity (0 even, 1 odd). */
static int has_pi_point(double lo, double hi, double shift, int parity) {
    mpfr_t q0, q1;
    mpfr_inits2(2400, q0, q1, (mpfr_ptr)0);
    mpfr_set_d(q0, lo, MPFR_RNDN);
    mpfr_div(q0, q0, PI, MPFR_RNDD);
    mpfr_sub_d(q0, q0, shift, MPFR_RNDD);
    mpfr_set_d(q1, hi, MPFR_RNDN);
    mpfr_div(q1, q1, PI, MPFR_RNDU);
    mpfr_sub_d(q1, q1, shift, MPFR_RNDU);
    mpfr_ceil(q0, q0);
    mpfr_floor(q1, q1);
    int found = 0;
    if (mpfr_cmp(q0, q1) <= 0) {
        mpfr_sub(q1, q1, q0, MPFR_RNDN);
        if (mpfr_cmp_ui(q1, 1) >= 0)
            found = 1; /* two consecutive integers: both parities */
        else {
            mpfr_div_2ui(q0, q0, 1, MPFR_RNDN);
            int even = mpfr_integer_p(q0);
            found = parity == 0 ? even : !even;
        }
    }
    mpfr_clears(q0, q1, (mpfr_ptr)0);
    return found;
}

static void exact_range(int op, const ia_case *k, range_t *g) {
    scratch_init();
    double alo = k->a.lo, ahi = k->a.hi, blo = k->b.lo, bhi = k->b.hi;
    int ae = ia_is_empty(k->a), be = ia_is_empty(k->b), first = 1;
    g->empty = 0, g->lo_ext = 0, g->hi_ext = 0;
    int kind = oracle_op_kind[op];
    if (ae || ((kind == ORACLE_K_BIN) && be)) {
        g->empty = 1;
        return;
    }
    if (kind == ORACLE_K_REAL)
        blo = bhi = k->c;
    switch (op) {
    case ORACLE_ADD:
    case ORACLE_ADD_R:
        mpfr_set_d(T1, alo, MPFR_RNDN), mpfr_add_d(g->lo, T1, blo, MPFR_RNDD);
        mpfr_set_d(T1, ahi, MPFR_RNDN), mpfr_add_d(g->hi, T1, bhi, MPFR_RNDU);
        return;
    case ORACLE_SUB:
        mpfr_set_d(T1, alo, MPFR_RNDN), mpfr_sub_d(g->lo, T1, bhi, MPFR_RNDD);
        mpfr_set_d(T1, ahi, MPFR_RNDN), mpfr_sub_d(g->hi, T1, blo, MPFR_RNDU);
        return;
    case ORACLE_MUL:
    case ORACLE_MUL_R:
        add_product(g, alo, blo, &first), add_product(g, alo, bhi, &first);
        add_product(g, ahi, blo, &first), add_product(g, ahi, bhi, &first);
        return;
    case ORACLE_DIV:
        if (blo == 0 && bhi == 0) {
            g->empty = 1;
            return;
        }
        if (blo < 0 && bhi > 0) { /* two half-lines or the whole line, unless a = [0,0] */
            if (alo == 0 && ahi == 0)
                r_setd(g, 0, 0);
            else
                r_setd(g, -INFINITY, INFINITY);
            return;
        }
        if (blo == 0 || bhi == 0) { /* b touches 0 on one side */
            if (alo == 0 && ahi == 0) {
                r_setd(g, 0, 0);
                return;
            }
            if (alo < 0 && ahi > 0) {
                r_setd(g, -INFINITY, INFINITY);
                return;
            }
            /* a one-signed (a bound may be 0): the quotients from the nonzero part of b, plus the pole */
            double far = blo == 0 ? bhi : blo; /* the nonzero end */
            add_quotient(g, alo, far, &first), add_quotient(g, ahi, far, &first);
            /* the pole: x/y -> +inf when x >= 0 and y -> 0+, or x <= 0 and y -> 0- */
            mpfr_set_inf(T1, (alo >= 0 && ahi > 0) == (blo == 0) ? 1 : -1);
            r_add(g, T1, &first);
            return;
        }
        add_quotient(g, alo, blo, &first), add_quotient(g, alo, bhi, &first);
        add_quotient(g, ahi, blo, &first), add_quotient(g, ahi, bhi, &first);
        return;
    case ORACLE_RECIP:
        if (alo == 0 && ahi == 0) {
            g->empty = 1;
            return;
        }
        if (alo < 0 && ahi > 0) {
            r_setd(g, -INFINITY, INFINITY);
            return;
        }
        if (alo == 0)
            add_fn(g, op, ahi, 0, &first), mpfr_set_inf(T1, 1), r_add(g, T1, &first);
        else if (ahi == 0)
            add_fn(g, op, alo, 0, &first), mpfr_set_inf(T1, -1), r_add(g, T1, &first);
        else
            add_fn(g, op, alo, 0, &first), add_fn(g, op, ahi, 0, &first);
        return;
    case ORACLE_SQR:
    case ORACLE_POWN: {
        long n = op == ORACLE_SQR ? 2 : k->n;
        if (n == 0) {
            r_setd(g, 1, 1);
            return;
        }
        if (n < 0 && alo == 0 && ahi == 0) {
            g->empty = 1;
            return;
        }
        if ((n & 1) == 0) { /* even: a function of |x|, monotone */
            double mig = alo > 0 ? alo : ahi < 0 ? -ahi : 0, mag = fmax(fabs(alo), fabs(ahi));
            add_fn(g, ORACLE_POWN, mig, n, &first), add_fn(g, ORACLE_POWN, mag, n, &first);
            if (mig == 0 && n > 0)
                g->lo_ext = 1; /* 0 must be exact */
            return;
        }
        if (n < 0 && alo < 0 && ahi > 0) {
            r_setd(g, -INFINITY, INFINITY);
            return;
        }
        /* odd: monotone on each side; the zero end of a one-signed interval keeps its side's sign */
        add_fn(g, ORACLE_POWN, alo == 0 ? 0.0 : alo, n, &first);
        add_fn(g, ORACLE_POWN, ahi == 0 ? -0.0 : ahi, n, &first);
        return;
    }
    case ORACLE_POW: {
        if (ahi < 0) {
            g->empty = 1;
            return;
        }
        double xlo = fmax(alo, 0), xhi = ahi;
        if (xhi == 0) {
            if (bhi > 0)
                r_setd(g, 0, 0);
            else
                g->empty = 1;
            return;
        }
        double xs[2] = {xlo, xhi}, ys[2] = {blo, bhi};
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                mpfr_set_d(T1, xs[i], MPFR_RNDN), mpfr_set_d(T2, ys[j], MPFR_RNDN);
                mpfr_t v;
                mpfr_init2(v, ORACLE_PREC);
                mpfr_pow(v, T1, T2, MPFR_RNDD);
                r_add(g, v, &first);
                mpfr_set_d(T1, xs[i], MPFR_RNDN);
                mpfr_pow(v, T1, T2, MPFR_RNDU);
                r_add(g, v, &first);
                mpfr_clear(v);
            }
        return;
    }
    case ORACLE_SQRT:
        if (ahi < 0) {
            g->empty = 1;
            return;
        }
        add_fn(g, op, fmax(alo, 0), 0, &first), add_fn(g, op, ahi, 0, &first);
        return;
    case ORACLE_EXP:
    case ORACLE_ATAN: add_fn(g, op, alo, 0, &first), add_fn(g, op, ahi, 0, &first); return;
    case ORACLE_LOG:
        if (ahi <= 0) {
            g->empty = 1;
            return;
        }
        add_fn(g, op, fmax(alo, 0), 0, &first), add_fn(g, op, ahi, 0, &first);
        return;
    case ORACLE_TAN:
        if (isinf(alo) || isinf(ahi) || has_pi_point(alo, ahi, 0.5, 0) || has_pi_point(alo, ahi, 0.5, 1)) {
            r_setd(g, -INFINITY, INFINITY);
            return;
        }
        add_fn(g, op, alo, 0, &first), add_fn(g, op, ahi, 0, &first);
        return;
    case ORACLE_SIN:
    case ORACLE_COS: {
        if (isinf(alo) || isinf(ahi)) {
            r_setd(g, -1, 1);
            g->lo_ext = g->hi_ext = 1;
            return;
        }
        add_fn(g, op, alo, 0, &first), add_fn(g, op, ahi, 0, &first);
        double shift = op == ORACLE_COS ? 0 : 0.5; /* maxima at (2j + shift) pi, minima at (2j + 1 + shift) pi */
        if (has_pi_point(alo, ahi, shift, 0))
            mpfr_set_si(g->hi, 1, MPFR_RNDU), g->hi_ext = 1;
        if (has_pi_point(alo, ahi, shift, 1))
            mpfr_set_si(g->lo, -1, MPFR_RNDD), g->lo_ext = 1;
        return;
    }
    case ORACLE_NEG: r_setd(g, -ahi, -alo); return;
    case ORACLE_ABS: {
        double mig = alo > 0 ? alo : ahi < 0 ? -ahi : 0;
        r_setd(g, mig, fmax(fabs(alo), fabs(ahi)));
        return;
    }
    case ORACLE_MIN: r_setd(g, fmin(alo, blo), fmin(ahi, bhi)); return;
    case ORACLE_MAX: r_setd(g, fmax(alo, blo), fmax(ahi, bhi)); return;
    }
}

/* The k of the function behind op in the given ulp table (host or device), or -1 for correctly rounded ops
 * and -2 for exact ones. */
static int op_k(int op, const int *table) {
    switch (op) {
    case ORACLE_NEG:
    case ORACLE_ABS:
    case ORACLE_MIN:
    case ORACLE_MAX: return -2;
    case ORACLE_DIV:
    case ORACLE_RECIP: return table[ORACLE_FN_DIV] == 0 ? -1 : table[ORACLE_FN_DIV];
    case ORACLE_SQRT: return table[ORACLE_FN_SQRT] == 0 ? -1 : table[ORACLE_FN_SQRT];
    case ORACLE_EXP: return table[ORACLE_FN_EXP];
    case ORACLE_LOG: return table[ORACLE_FN_LOG];
    case ORACLE_SIN:
    case ORACLE_COS: return table[ORACLE_FN_SIN];
    case ORACLE_TAN: return table[ORACLE_FN_TAN];
    case ORACLE_ATAN: return table[ORACLE_FN_ATAN];
    case ORACLE_POW: return table[ORACLE_FN_POW];
    default: return -1; /* + - * sqr pown add_r mul_r */
    }
}

/* Allowed steps beyond the outward-rounded exact bound v, for op with error k (op_k); kpow is the table's
 * IA_ULP_POW and chain_max its IA_POWN_CHAIN_MAX (ia_pown switches to pow above it). */
static long allowed_steps(int op, int k, int kpow, long chain_max, const ia_case *c, double v) {
    int tiny = fabs(v) < ldexp(1, FMT_MANT + 3) * (double)IA_REAL_TRUE_MIN;
    if (k == -2)
        return 0;
    if (op == ORACLE_POWN && c->n != 0 && c->n != 1 && c->n != 2) {
        unsigned long m = c->n < 0 ? 0ul - (unsigned long)(long)c->n : (unsigned long)c->n;
        long s;
        if ((long)m <= chain_max) /* square-and-multiply: errors compound to 2.25 (m - 1) steps */
            s = (long)(2.25 * (double)(m - 1) + 0.999) + 2;
        else /* pow, or two pows and a product */
            s = m < 65536 ? 3l * kpow + 3 : 6l * kpow + 8;
        if (c->n < 0) /* the reciprocal: one more rounding, and the relative error may double in steps */
            s = 2 * s + 4;
        return s + (tiny ? s : 0);
    }
    if (k == -1)
        return fmt_k0_steps(v);
    return 3l * k + 3 + (tiny ? k + 1 : 0);
}

typedef struct {
    long cases, max_lo, max_hi;
} tight_stats;

/* A build that flushes subnormals (the table's IA_FTZ flag) has the normal numbers and 0 as its grid: the exact
 * bound v rounded outward onto it, and its steps from a to b skip the subnormals. Each of `allowed` roundings
 * and widenings there may also add its TINY, the smallest normal number, which near 0 is many steps: a bound
 * within that much of v also passes. */
static double ftz_round(double v, int up) { return up ? ia_flush_hi_d(v) : ia_flush_lo_d(v); }
static long ftz_steps(double a, double b) {
    long s = (long)oracle_steps(a, b, FMT_MANT), subnormals = (long)((1ull << (FMT_MANT - 1)) - 1);
    if (a <= -(double)IA_REAL_MIN_NORMAL && b >= 0)
        s -= subnormals;
    if (a <= 0 && b >= (double)IA_REAL_MIN_NORMAL)
        s -= subnormals;
    return s;
}
static int ftz_within(double bound, double v, long allowed) {
    double ulp = fabs((double)fmt_step((ia_real)v, 1) - v);
    return fabs(bound - v) <= (double)(allowed + 1) * (ulp + (double)IA_REAL_MIN_NORMAL);
}

/* Checks result out of op on case k; returns 0 (updating stats), or 1 with a message. */
static int tight_check(int op, const ia_case *k, const ia_real out[2], const int *table, const char *who,
                       tight_stats *st, char *msg, size_t size) {
    range_t g;
    mpfr_inits2(ORACLE_PREC, g.lo, g.hi, (mpfr_ptr)0);
    exact_range(op, k, &g);
    int bad = 0;
    double lo = out[0], hi = out[1];
    double L = 0, U = 0;
    if (g.empty) {
        if (!(lo == INFINITY && hi == -INFINITY)) {
            snprintf(msg, size, "%s %s: exact range empty, result [%s, %s]", who, case_str(op, k), oracle_hex(lo),
                     oracle_hex(hi));
            bad = 1;
        }
    } else {
        L = oracle_round(g.lo, -1, FMT_MANT), U = oracle_round(g.hi, 1, FMT_MANT);
        int kk = op_k(op, table), ftz = table[ORACLE_NFNS];
        if (ftz)
            L = ftz_round(L, 0), U = ftz_round(U, 1);
        long el = ftz ? ftz_steps(lo, L) : (long)oracle_steps(lo, L, FMT_MANT),
             eh = ftz ? ftz_steps(U, hi) : (long)oracle_steps(U, hi, FMT_MANT);
        long al = g.lo_ext ? 0 : allowed_steps(op, kk, table[ORACLE_FN_POW], table[ORACLE_NFNS + 1], k, L),
             ah = g.hi_ext ? 0 : allowed_steps(op, kk, table[ORACLE_FN_POW], table[ORACLE_NFNS + 1], k, U);
        if (ftz && el > al && lo <= L && ftz_within(lo, L, al))
            el = al;
        if (ftz && eh > ah && hi >= U && ftz_within(hi, U, ah))
            eh = ah;
        if (isnan(lo) || isnan(hi) || el < 0 || eh < 0 || el > al || eh > ah) {
            snprintf(msg, size,
                     "%s %s " FMT_NAME ": result [%s, %s], exact range rounded outward [%s, %s]: %ld and %ld steps "
                     "outside (allowed %ld and %ld)",
                     who, case_str(op, k), oracle_hex(lo), oracle_hex(hi), oracle_hex(L), oracle_hex(U), el, eh, al,
                     ah);
            bad = 1;
        } else {
            if (el > st->max_lo && isfinite(L))
                st->max_lo = el;
            if (eh > st->max_hi && isfinite(U))
                st->max_hi = eh;
        }
    }
    st->cases++;
    mpfr_clears(g.lo, g.hi, (mpfr_ptr)0);
    return bad;
}

/* As the device's table (ia_dev_ulp_table): the ulps, no IA_FTZ, the pown chain's limit. */
static const int host_table[ORACLE_NFNS + 2] = {IA_ULP_DIV,  IA_ULP_SQRT,   IA_ULP_EXP, IA_ULP_LOG,
                                                IA_ULP_SINCOS, IA_ULP_SINCOS, IA_ULP_TAN, IA_ULP_ATAN,
                                                IA_ULP_POW,  0,             IA_POWN_CHAIN_MAX};

static int tight_op(int op) {
    int kind = oracle_op_kind[op];
    return kind == ORACLE_K_UN || kind == ORACLE_K_BIN || kind == ORACLE_K_POWN || kind == ORACLE_K_REAL;
}

TEST_FP(ia_tight) {
    test_rng_t *r = test_rng();
    long count = test_iters(6000) + 20;
    char msg[2048], line[4096] = "";
    size_t len = 0;
    int dev_table[ORACLE_NFNS + 2];
    CHECK(FP_NAME(ia_dev_ulp_table)(dev_table, msg, sizeof msg) == 0, "%s", msg);
    ia_case *k = malloc(sizeof *k * (size_t)count), *kd = malloc(sizeof *kd * (size_t)count);
    ia_real *host = malloc(sizeof *host * 2 * (size_t)count), *devo = malloc(sizeof *devo * 2 * (size_t)count);
    CHECK(k && kd && host && devo, "out of memory");
    long total = 0;
    for (int op = 0; op < ORACLE_NOPS; op++) {
        if (!tight_op(op))
            continue;
        for (long i = 0; i < count; i++) {
            if (!regress_case((int)i, &k[i])) /* pinned regressions first */
                k[i] = gen_case(r, 0);
            ia_apply(op, &k[i], host + 2 * i);
            if (!dev_table[ORACLE_NFNS] || !case_flushed(&k[i], &kd[i])) /* the device's case, see t_ia_ops_fp.c */
                kd[i] = k[i];
        }
        if (FP_NAME(ia_dev_ops)(0, op, kd, count, devo, msg, sizeof msg)) {
            free(k), free(kd), free(host), free(devo);
            CHECK(0, "%s", msg);
        }
        tight_stats sh = {0, 0, 0}, sd = {0, 0, 0};
        for (long i = 0; i < count; i++) {
            if (tight_check(op, &k[i], host + 2 * i, host_table, "host", &sh, msg, sizeof msg) ||
                tight_check(op, &kd[i], devo + 2 * i, dev_table, "device", &sd, msg, sizeof msg)) {
                free(k), free(kd), free(host), free(devo);
                CHECK(0, "case %ld: %s", i, msg);
            }
        }
        total += sh.cases + sd.cases;
        len += (size_t)snprintf(line + len, sizeof line - len, " %s %ld/%ld", oracle_op_name[op],
                                sh.max_lo > sh.max_hi ? sh.max_lo : sh.max_hi,
                                sd.max_lo > sd.max_hi ? sd.max_lo : sd.max_hi);
    }
    free(k), free(kd), free(host), free(devo);
    test_note("%ld range checks " FMT_NAME "; max steps beyond the tightest bound, host/device:%s", total, line);
}

/* sin and cos on intervals near the multiples k pi/2 (|k| up to 2^18) where the device's float build reduces its
 * arguments itself (ia/elem.h): points, a few ulps, up to 2^-11 wide (its midpoint form) and wider (its end points),
 * on either side of the extremum or zero; containment and tightness of the exact range, host and device. */
TEST_FP(ia_tight_sincos_quadrants) {
    test_rng_t *r = test_rng();
    long count = test_iters(20000);
    char msg[2048];
    int dev_table[ORACLE_NFNS + 2];
    CHECK(FP_NAME(ia_dev_ulp_table)(dev_table, msg, sizeof msg) == 0, "%s", msg);
    ia_case *k = calloc((size_t)count, sizeof *k);
    ia_real *devo = malloc(sizeof *devo * 2 * (size_t)count), host[2];
    CHECK(k && devo, "out of memory");
    for (long i = 0; i < count; i++) {
        long q = gen_u32(r, 2) ? (long)gen_u32(r, 9) - 4 : (long)gen_u32(r, 1u << 19) - (1l << 18);
        ia_real x = (ia_real)((double)q * 1.57079632679489661923);
        x = fmt_step(x, (int)gen_u32(r, 7) - 3);
        double w = gen_u32(r, 4) == 0 ? 0 : ldexp(test_rand_unit(r), -(int)gen_u32(r, 24));
        double before = w * test_rand_unit(r);
        k[i].a = ia_make((ia_real)ia_lo((ia_real)(x - before)), (ia_real)ia_hi((ia_real)(x - before + w)));
        if (gen_u32(r, 8) == 0)
            k[i].a = ia_make(x, fmt_step(x, 1 + (int)gen_u32(r, 4)));
        if (dev_table[ORACLE_NFNS]) /* (near k = 0) as the device, which flushes subnormals, must be given them */
            case_flushed(&k[i], &k[i]);
    }
    static const int ops[] = {ORACLE_SIN, ORACLE_COS};
    long max_steps = 0;
    for (int o = 0; o < 2; o++) {
        CHECK(FP_NAME(ia_dev_ops)(0, ops[o], k, count, devo, msg, sizeof msg) == 0, "%s", msg);
        tight_stats sh = {0, 0, 0}, sd = {0, 0, 0};
        for (long i = 0; i < count; i++) {
            ia_apply(ops[o], &k[i], host);
            if (tight_check(ops[o], &k[i], host, host_table, "host", &sh, msg, sizeof msg) ||
                tight_check(ops[o], &k[i], devo + 2 * i, dev_table, "device", &sd, msg, sizeof msg)) {
                free(k), free(devo);
                CHECK(0, "case %ld: %s", i, msg);
            }
        }
        max_steps = sd.max_lo > max_steps ? sd.max_lo : max_steps;
        max_steps = sd.max_hi > max_steps ? sd.max_hi : max_steps;
    }
    free(k), free(devo);
    test_note("%ld intervals near multiples of pi/2, sin and cos contained and tight; device at most %ld steps out",
              count, max_steps);
}

/* Pinned: the exact extrema and the exact 0 of the contract. */
TEST_FP(ia_tight_extrema) {
    const ia_real pi_lo = IA_PI_LO, pi_hi = IA_PI_HI;
    ia_interval s = ia_sin(ia_make(1, 2)); /* pi/2 inside */
    CHECK(s.hi == 1, "sin([1,2]).hi = %s, not 1", oracle_hex(s.hi));
    s = ia_cos(ia_make(3, 4)); /* pi inside */
    CHECK(s.lo == -1, "cos([3,4]).lo = %s, not -1", oracle_hex(s.lo));
    s = ia_cos(ia_make(-1, 1));
    CHECK(s.hi == 1, "cos([-1,1]).hi = %s", oracle_hex(s.hi));
    s = ia_sin(ia_make(-2, -1));
    CHECK(s.lo == -1, "sin([-2,-1]).lo = %s", oracle_hex(s.lo));
    s = ia_sin(ia_make(pi_lo * 2, pi_hi * 2 + 1)); /* 2 pi inside: sin rises through 0, no extremum */
    CHECK(s.lo > -1 && s.hi < 1, "sin([2pi, 2pi+1]) = [%s, %s]", oracle_hex(s.lo), oracle_hex(s.hi));
    ia_interval q = ia_sqr(ia_make(-3, 2));
    CHECK(q.lo == 0, "sqr([-3,2]).lo = %s", oracle_hex(q.lo));
    for (int n = 2; n <= 500; n += 2) {
        q = ia_pown(ia_make(-(ia_real)1.5, (ia_real)0.5), n);
        CHECK(q.lo == 0 && !(q.hi < 0), "pown([-1.5,0.5], %d).lo = %s", n, oracle_hex(q.lo));
    }
    q = ia_pown(ia_make(-0.0, 0), 4);
    CHECK(q.lo == 0 && q.hi == 0, "pown([-0,0], 4) = [%s, %s]", oracle_hex(q.lo), oracle_hex(q.hi));
}

/* The checker must fail lazy but safe implementations: a 1788 hull that is too wide is a defect. */
static void lazy_apply(int variant, int op, const ia_case *k, ia_real out[2]) {
    ia_apply(op, k, out);
    if (out[0] == IA_INF) /* empty stays empty */
        return;
    switch (variant) {
    case 0: out[0] = -IA_INF, out[1] = IA_INF; break;                   /* entire */
    case 1: out[0] = fmin(out[0], -1), out[1] = fmax(out[1], 1); break; /* sin, cos: [-1, 1] always */
    case 2: out[0] = ia_lo(out[0]); break;                              /* 1 more step down */
    case 3: out[0] = ia_lo(ia_lo(ia_lo(ia_lo(out[0])))); break;         /* pown: starts below 0 */
    case 4: out[0] = fmin(out[0], -1), out[1] = fmax(out[1], 1); break;
    }
}

TEST_FP(ia_tight_catches_lazy) {
    static const struct {
        int variant, op;
        ia_interval a;
        int n;
        const char *what;
    } lazy[] = {
        {0, ORACLE_EXP, {1, 2}, 0, "exp returning entire"},
        {0, ORACLE_ADD, {1, 2}, 0, "add returning entire"},
        {1, ORACLE_SIN, {0.25f, 0.5f}, 0, "sin returning [-1, 1] without looking for extrema"},
        {1, ORACLE_COS, {0.25f, 0.5f}, 0, "cos returning [-1, 1]"},
        {2, ORACLE_NEG, {1, 2}, 0, "neg widened by one step (an exact op)"},
        {3, ORACLE_POWN, {-1, 2}, 4, "even pown straddling 0 not starting at exactly 0"},
        {3, ORACLE_SQR, {-1, 2}, 0, "sqr straddling 0 not starting at exactly 0"},
        {2, ORACLE_ADD, {1, 1}, 0, "add widened by two steps"},
        {4, ORACLE_MUL, {1, 2}, 0, "mul padded by 1 around the result"},
    };
    char msg[2048];
    for (size_t i = 0; i < sizeof lazy / sizeof lazy[0]; i++) {
        ia_case k;
        k.a = lazy[i].a;
        k.b = ia_make((ia_real)0.5, (ia_real)0.75);
        k.n = lazy[i].n;
        k.c = 1;
        ia_real good[2], bad[2];
        ia_apply(lazy[i].op, &k, good);
        lazy_apply(lazy[i].variant, lazy[i].op, &k, bad);
        if (lazy[i].variant == 2 && lazy[i].op == ORACLE_ADD)
            bad[0] = ia_lo(bad[0]);
        tight_stats st = {0, 0, 0};
        CHECK(tight_check(lazy[i].op, &k, good, host_table, "host", &st, msg, sizeof msg) == 0, "the real %s fails: %s",
              oracle_op_name[lazy[i].op], msg);
        CHECK(tight_check(lazy[i].op, &k, bad, host_table, "lazy", &st, msg, sizeof msg) == 1,
              "the checker accepted %s: [%s, %s]", lazy[i].what, oracle_hex(bad[0]), oracle_hex(bad[1]));
    }
    /* and the containment checker catches a bound one step too tight (what IA_FAST does) */
    ia_case k;
    k.a = ia_make(1, 1), k.b = ia_make((ia_real)0.1, (ia_real)0.1), k.n = 0, k.c = 0;
    ia_real out[2];
    ia_apply(ORACLE_ADD, &k, out);
    out[1] = nextafter(out[1], -IA_INF);
    out[1] = nextafter(out[1], -IA_INF);
    pt_t p[1];
    pt_init(p, 1);
    p[0].x = 1, p[0].y = (double)k.b.hi;
    p[0].def = oracle_eval(ORACLE_ADD, p[0].x, p[0].y, 0, p[0].v, &p[0].t);
    long checks = 0;
    int caught = pt_check(ORACLE_ADD, &k, p, 1, out, "slipped", msg, sizeof msg, &checks);
    pt_clear(p, 1);
    CHECK(caught, "the containment checker accepted an upper bound 2 steps below the sum");
    test_note("the tightness checker rejects %zu lazy variants; the containment checker a 2-step slip",
              sizeof lazy / sizeof lazy[0]);
}
