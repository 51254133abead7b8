/* tests/oracle.c -- see oracle.h. */
#include "oracle.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

const char *const oracle_op_name[ORACLE_NOPS] = {
#define X(NAME, name, kind) #name,
    ORACLE_OPS(X)
#undef X
};
const int oracle_op_kind[ORACLE_NOPS] = {
#define X(NAME, name, kind) ORACLE_K_##kind,
    ORACLE_OPS(X)
#undef X
};
const char *const oracle_fn_name[ORACLE_NFNS] = {"div", "sqrt", "exp", "log", "sin", "cos", "tan", "atan", "pow"};

void oracle_init(void) {
    static int done;
    if (done)
        return;
    mpfr_set_emin(mpfr_get_emin_min());
    mpfr_set_emax(mpfr_get_emax_max());
    done = 1;
}

/* Scratch operands: doubles are exact at ORACLE_PREC. */
static mpfr_t X_, Y_;
static void load(double x, double yv) {
    static int init;
    if (!init) {
        mpfr_inits2(ORACLE_PREC, X_, Y_, (mpfr_ptr)0);
        init = 1;
    }
    mpfr_set_d(X_, x, MPFR_RNDN);
    mpfr_set_d(Y_, yv, MPFR_RNDN);
}

int oracle_eval(int op, double x, double yv, long n, mpfr_ptr y, int *ternary) {
    oracle_init();
    load(x, yv);
    const mpfr_rnd_t D = MPFR_RNDD;
    int t = 0;
    switch (op) {
    case ORACLE_ADD:
    case ORACLE_ADD_R: t = mpfr_add(y, X_, Y_, D); break;
    case ORACLE_SUB: t = mpfr_sub(y, X_, Y_, D); break;
    case ORACLE_MUL:
    case ORACLE_MUL_R: t = mpfr_mul(y, X_, Y_, D); break;
    case ORACLE_DIV:
        if (yv == 0)
            return 0;
        t = mpfr_div(y, X_, Y_, D);
        break;
    case ORACLE_RECIP:
        if (x == 0)
            return 0;
        t = mpfr_ui_div(y, 1, X_, D);
        break;
    case ORACLE_SQR: t = mpfr_sqr(y, X_, D); break;
    case ORACLE_POWN:
        if (x == 0 && n < 0)
            return 0;
        if (n == 0) { /* IEEE 1788 pown: x^0 = 1 everywhere, 0^0 included */
            mpfr_set_ui(y, 1, D);
            t = 0;
        } else {
            t = mpfr_pow_si(y, X_, n, D);
        }
        break;
    case ORACLE_POW:
        if (!(x > 0 || (x == 0 && yv > 0)))
            return 0;
        t = mpfr_pow(y, X_, Y_, D);
        break;
    case ORACLE_SQRT:
        if (x < 0)
            return 0;
        t = mpfr_sqrt(y, X_, D);
        break;
    case ORACLE_EXP: t = mpfr_exp(y, X_, D); break;
    case ORACLE_LOG:
        if (!(x > 0))
            return 0;
        t = mpfr_log(y, X_, D);
        break;
    case ORACLE_SIN: t = mpfr_sin(y, X_, D); break;
    case ORACLE_COS: t = mpfr_cos(y, X_, D); break;
    case ORACLE_TAN: t = mpfr_tan(y, X_, D); break;
    case ORACLE_ATAN: t = mpfr_atan(y, X_, D); break;
    case ORACLE_NEG: t = mpfr_neg(y, X_, D); break;
    case ORACLE_ABS: t = mpfr_abs(y, X_, D); break;
    case ORACLE_MIN: t = mpfr_min(y, X_, Y_, D); break;
    case ORACLE_MAX: t = mpfr_max(y, X_, Y_, D); break;
    default: return 0;
    }
    *ternary = t;
    return 1;
}

int oracle_in(mpfr_srcptr y, int ternary, double lo, double hi) {
    if (isnan(lo) || isnan(hi) || mpfr_nan_p(y))
        return 0;
    /* y is the true value rounded down; when inexact the true value lies strictly between y and the next
     * ORACLE_PREC-bit number, and no double lies strictly inside that gap. */
    if (mpfr_cmp_d(y, lo) < 0)
        return 0;
    int c = mpfr_cmp_d(y, hi);
    return ternary == 0 ? c <= 0 : c < 0;
}

void oracle_fn(int fn, double x, double yv, mpfr_ptr y) {
    oracle_init();
    load(x, yv);
    const mpfr_rnd_t N = MPFR_RNDN;
    switch (fn) {
    case ORACLE_FN_DIV: mpfr_div(y, X_, Y_, N); break;
    case ORACLE_FN_SQRT: mpfr_sqrt(y, X_, N); break;
    case ORACLE_FN_EXP: mpfr_exp(y, X_, N); break;
    case ORACLE_FN_LOG: mpfr_log(y, X_, N); break;
    case ORACLE_FN_SIN: mpfr_sin(y, X_, N); break;
    case ORACLE_FN_COS: mpfr_cos(y, X_, N); break;
    case ORACLE_FN_TAN: mpfr_tan(y, X_, N); break;
    case ORACLE_FN_ATAN: mpfr_atan(y, X_, N); break;
    case ORACLE_FN_POW: mpfr_pow(y, X_, Y_, N); break;
    }
}

double oracle_ulp_error(double r, mpfr_srcptr y, int mant, int emin) {
    oracle_init();
    double max = mant == 24 ? (double)3.40282346638528859811704183484516925e+38 : 1.79769313486231570815e+308;
    if (mpfr_nan_p(y))
        return isnan(r) ? 0 : INFINITY;
    if (isnan(r))
        return INFINITY;
    if (isinf(r)) { /* overflow is right only when y is beyond the largest finite number on that side */
        if (r > 0)
            return mpfr_cmp_d(y, max) > 0 ? 0 : INFINITY;
        return mpfr_cmp_d(y, -max) < 0 ? 0 : INFINITY;
    }
    mpfr_t d;
    mpfr_init2(d, ORACLE_PREC);
    if (mpfr_inf_p(y)) { /* cannot happen with the widened exponent range, but be safe */
        mpfr_clear(d);
        return INFINITY;
    }
    mpfr_sub_d(d, y, r, MPFR_RNDN);
    mpfr_abs(d, d, MPFR_RNDN);
    long e = mpfr_zero_p(y) ? emin : mpfr_get_exp(y);
    if (e < emin)
        e = emin;
    mpfr_mul_2si(d, d, -(e - mant), MPFR_RNDN); /* divide by ulp(y) = 2^(e - mant) */
    double u = mpfr_get_d(d, MPFR_RNDU);
    mpfr_clear(d);
    return u;
}

double oracle_round(mpfr_srcptr y, int dir, int mant) {
    mpfr_rnd_t m = dir < 0 ? MPFR_RNDD : MPFR_RNDU;
    return mant == 24 ? (double)mpfr_get_flt(y, m) : mpfr_get_d(y, m);
}

int64_t oracle_ord(double x, int mant) {
    if (mant == 24) {
        float f = (float)x;
        uint32_t b;
        memcpy(&b, &f, sizeof b);
        int64_t m = (int64_t)(b & 0x7fffffffu);
        return (b >> 31) ? -m : m;
    }
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    int64_t m = (int64_t)(b & 0x7fffffffffffffffull);
    return (b >> 63) ? -m : m;
}

int64_t oracle_steps(double a, double b, int mant) {
    int64_t x = oracle_ord(a, mant), y = oracle_ord(b, mant);
    if ((x >= 0) == (y >= 0)) /* same sign: no overflow */
        return y - x;
    /* opposite signs: |y - x| = |y| + |x|, which may exceed INT64_MAX */
    uint64_t m = (uint64_t)(y >= 0 ? y : -y) + (uint64_t)(x >= 0 ? x : -x);
    int64_t d = m > (uint64_t)INT64_MAX ? INT64_MAX : (int64_t)m;
    return y >= 0 ? d : -d;
}

static char ring[24][96];
static int ring_next;
static char *ring_buf(void) {
    char *s = ring[ring_next];
    ring_next = (ring_next + 1) % 24;
    return s;
}

const char *oracle_hex(double x) {
    char *s = ring_buf();
    snprintf(s, sizeof ring[0], "%a", x);
    return s;
}

const char *oracle_str(mpfr_srcptr y) {
    char *s = ring_buf();
    mpfr_snprintf(s, sizeof ring[0], "%.30Rg", y);
    return s;
}
