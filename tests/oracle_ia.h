/* tests/oracle_ia.h -- the format-generic half of the oracle, for tests/t_ia_*_fp.c: include it after ia/ia.h.
 *
 *   gen_real, gen_interval, gen_pown_n, gen_case   random inputs of every kind (Arb style): small, tiny, huge,
 *       subnormal, +-0, infinite, multiples of pi and pi/2 (nudged by a few ulps), integers, values near 1,
 *       random bit patterns; intervals that are empty, entire, points, a few ulps wide, straddling 0,
 *       half-unbounded, or any two of those values.
 *   gen_point                                      a real (double) in an interval, end points included: for
 *       float intervals most points are doubles that are not floats.
 *   ia_apply                                       runs one op of ia/ on a case, as the device kernel does.
 *   pt_draw, pt_check                              the points of a case with their oracle values, and the
 *       containment check of one result against them (with a message naming every input on failure).
 */
#ifndef IACSG_ORACLE_IA_H
#define IACSG_ORACLE_IA_H
#include "ia/flush.h"
#include "oracle.h"
#include "test.h"
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef IA_FP64
#define FMT_MANT 53
#define FMT_EMIN (-1021) /* MPFR exponent of the smallest normal number */
#define FMT_EMAX 1024
#define FMT_NAME "f64"
#define FP_NAME(x) x##_f64
#else
#define FMT_MANT 24
#define FMT_EMIN (-125)
#define FMT_EMAX 128
#define FMT_NAME "f32"
#define FP_NAME(x) x##_f32
#endif

/* The inputs of one operation: a (and b), the exponent n of pown, the real c of add_r, mul_r and contains. */
typedef struct {
    ia_interval a, b;
    int n;
    ia_real c;
} ia_case;

/* tests/ia_ops.cl's codes for the sin and the cos of ia_sin_cos (and over lanes iav_sin_cos), and over lanes for the
 * forms of ia/vec.h for operands >= 0 (iav_add_nn ...), after the ops of tests/oracle.h (tests/t_ia_device_fp.c,
 * t_ia_vec_device_fp.c). */
enum {
    IA_TEST_SIN_COS_SIN = 1000,
    IA_TEST_SIN_COS_COS,
    IA_TEST_ADD_NN,
    IA_TEST_ADD_R_NN,
    IA_TEST_MUL_NN,
    IA_TEST_MUL_R_NN,
    IA_TEST_MUL_N,
    IA_TEST_SQR_NN
};

#define GEN_NO_SUBNORMAL 1 /* for IA_FTZ: no subnormal bound (the contract's precondition there) */

/* A real as a device that flushes subnormals reads it: a subnormal one is a zero of its sign. */
static inline ia_real real_flushed(ia_real x) { return fabs(x) < IA_REAL_MIN_NORMAL ? copysign((ia_real)0, x) : x; }

/* Case k as a device that flushes subnormals must be given it (ia/flush.h) into *out: its intervals' subnormal
 * bounds moved outward, a subnormal real c read as zero, as the device reads it. Returns 1 if that changed k. */
static inline int case_flushed(const ia_case *k, ia_case *out) {
#ifdef IA_FP64
#define CASE_FLUSH(x, side) ia_flush_##side##_d(x)
#else
#define CASE_FLUSH(x, side) ia_flush_##side##_f(x)
#endif
    *out = *k;
    out->a = ia_make(CASE_FLUSH(k->a.lo, lo), CASE_FLUSH(k->a.hi, hi));
    out->b = ia_make(CASE_FLUSH(k->b.lo, lo), CASE_FLUSH(k->b.hi, hi));
#undef CASE_FLUSH
    out->c = real_flushed(k->c);
    return out->a.lo != k->a.lo || out->a.hi != k->a.hi || out->b.lo != k->b.lo || out->b.hi != k->b.hi ||
           out->c != k->c;
}

static inline uint32_t gen_u32(test_rng_t *r, uint32_t n) { return (uint32_t)(test_rand_u64(r) % n); }
static inline ia_real fmt_step(ia_real x, int k) { /* k ulps of the format up (k > 0) or down */
    for (; k > 0; k--)
        x = nextafter(x, IA_INF);
    for (; k < 0; k++)
        x = nextafter(x, -IA_INF);
    return x;
}
static inline double fmt_round_d(double x, int dir) { /* x to the format: down, up, or nearest (dir 0) */
#ifdef IA_FP64
    (void)dir;
    return x;
#else
    float f = (float)x;
    if (dir < 0 && (double)f > x)
        f = nextafterf(f, -INFINITY);
    if (dir > 0 && (double)f < x)
        f = nextafterf(f, INFINITY);
    return f;
#endif
}

/* How many format steps a correctly rounded result (k = 0) may be widened beyond the correctly rounded outward
 * bound at v: one, two near 0 (ia/round.h). */
static inline int fmt_k0_steps(double v) {
    return fabs(v) >= ldexp(1, FMT_MANT + 3) * (double)IA_REAL_TRUE_MIN ? 1 : 2;
}

/* k * pi / 2 in the format, rounded in a random direction, then moved by up to 2 ulps. */
static inline ia_real gen_pi_multiple(test_rng_t *r) {
    long k;
    uint32_t w = gen_u32(r, 10);
    if (w < 7)
        k = (long)gen_u32(r, 25) - 12;
    else if (w < 9)
        k = (long)(gen_u32(r, 1u << 20)) - (1l << 19);
    else
        k = (long)(test_rand_u64(r) % (1ull << (FMT_MANT - 1))) - (1l << (FMT_MANT - 2));
    mpfr_t p;
    mpfr_init2(p, ORACLE_PREC);
    mpfr_const_pi(p, MPFR_RNDN);
    mpfr_mul_si(p, p, k, MPFR_RNDN);
    mpfr_div_2ui(p, p, 1, MPFR_RNDN);
    int dir = (int)gen_u32(r, 3) - 1;
    ia_real x = (ia_real)(dir == 0 ? mpfr_get_d(p, MPFR_RNDN) : oracle_round(p, dir, FMT_MANT));
#ifndef IA_FP64
    if (dir == 0)
        x = mpfr_get_flt(p, MPFR_RNDN);
#endif
    mpfr_clear(p);
    if (gen_u32(r, 2))
        x = fmt_step(x, (int)gen_u32(r, 5) - 2);
    return x;
}

/* A random finite or infinite value of the format, of a random kind. */
static inline ia_real gen_real(test_rng_t *r, int flags) {
    ia_real x;
    switch (gen_u32(r, 16)) {
    case 0:
    case 1:
    case 2: x = (ia_real)(test_rand_unit(r) * 20 - 10); break;
    case 3:
    case 4: { /* any normal magnitude */
        int e = FMT_EMIN - 1 + (int)gen_u32(r, (uint32_t)(FMT_EMAX - FMT_EMIN + 1));
        x = (ia_real)ldexp(1 + test_rand_unit(r), e);
        if (isinf(x))
            x = IA_REAL_MAX;
        break;
    }
    case 5: { /* huge */
        uint32_t w = gen_u32(r, 4);
        x = w == 0   ? IA_REAL_MAX
            : w == 1 ? fmt_step(IA_REAL_MAX, -(int)gen_u32(r, 1000))
                     : (ia_real)ldexp(1 + test_rand_unit(r), FMT_EMAX - 1 - (int)gen_u32(r, 8));
        if (isinf(x))
            x = IA_REAL_MAX;
        break;
    }
    case 6: { /* subnormal, or at the normal/subnormal border */
        uint32_t w = gen_u32(r, 4);
        x = w == 0   ? IA_REAL_TRUE_MIN
            : w == 1 ? fmt_step(IA_REAL_MIN_NORMAL, (int)gen_u32(r, 5) - 2)
                     : (ia_real)(IA_REAL_TRUE_MIN * (ia_real)(test_rand_u64(r) % (1ull << (FMT_MANT - 1))));
        break;
    }
    case 7: x = 0; break;
    case 8: x = IA_INF; break;
    case 9:
    case 10: x = gen_pi_multiple(r); break;
    case 11: x = (ia_real)((int)gen_u32(r, 49) - 24) * (ia_real)0.5; break;
    case 12: { /* near 1, 2, 1/2 */
        static const double base[] = {1, 2, 0.5, 1, 3, 10};
        x = fmt_step((ia_real)base[gen_u32(r, 6)], (int)gen_u32(r, 9) - 4);
        break;
    }
    case 13: { /* random bits, finite */
#ifdef IA_FP64
        uint64_t b = test_rand_u64(r);
        double d;
        memcpy(&d, &b, sizeof d);
        x = d;
#else
        uint32_t b = (uint32_t)test_rand_u64(r);
        float f;
        memcpy(&f, &b, sizeof f);
        x = f;
#endif
        if (!isfinite(x))
            x = 1;
        break;
    }
    case 14: x = (ia_real)ldexp(1, -(int)gen_u32(r, 60)); break;
    default: x = (ia_real)ldexp(test_rand_unit(r), (int)gen_u32(r, 40) - 20); break;
    }
    if (gen_u32(r, 2))
        x = -x;
    if ((flags & GEN_NO_SUBNORMAL) && x != 0 && fabs(x) < IA_REAL_MIN_NORMAL)
        x = x > 0 ? IA_REAL_MIN_NORMAL : -IA_REAL_MIN_NORMAL;
    return x;
}

static inline ia_real gen_finite(test_rng_t *r, int flags) {
    ia_real x;
    do
        x = gen_real(r, flags);
    while (isinf(x));
    return x;
}

/* A random interval of a random kind. */
static inline ia_interval gen_interval(test_rng_t *r, int flags) {
    uint32_t w = gen_u32(r, 100);
    if (w < 3)
        return ia_empty();
    if (w < 5)
        return ia_entire();
    if (w < 15)
        return ia_point(gen_finite(r, flags));
    if (w < 25) { /* a few ulps wide */
        ia_real x = gen_finite(r, flags), y = fmt_step(x, 1 + (int)gen_u32(r, 8));
        if ((flags & GEN_NO_SUBNORMAL) && y != 0 && fabs(y) < IA_REAL_MIN_NORMAL)
            y = IA_REAL_MIN_NORMAL;
        if ((flags & GEN_NO_SUBNORMAL) && x != 0 && fabs(x) < IA_REAL_MIN_NORMAL)
            x = -IA_REAL_MIN_NORMAL;
        return isinf(y) ? ia_make(x, x) : ia_make(x, y);
    }
    if (w < 35) /* straddling 0 */
        return ia_make(-fabs(gen_finite(r, flags)), fabs(gen_finite(r, flags)));
    if (w < 42) {
        ia_real x = gen_finite(r, flags);
        return gen_u32(r, 2) ? ia_make(x, IA_INF) : ia_make(-IA_INF, x);
    }
    for (;;) {
        ia_real x = gen_real(r, flags), y = gen_real(r, flags);
        ia_real lo = fmin(x, y), hi = fmax(x, y);
        if (lo == IA_INF || hi == -IA_INF)
            continue;
        return ia_make(lo, hi);
    }
}

static inline int gen_pown_n(test_rng_t *r) {
    uint32_t w = gen_u32(r, 100);
    int s = gen_u32(r, 2) ? -1 : 1;
    if (w < 55)
        return (int)gen_u32(r, 21) - 10;
    if (w < 80)
        return s * (int)(11 + gen_u32(r, 54));
    if (w < 92)
        return s * (int)(499 + gen_u32(r, 3));
    if (w < 98)
        return s * (int)(gen_u32(r, 0x7fffffffu));
    return w == 98 ? INT_MIN : INT_MAX;
}

static inline ia_case gen_case(test_rng_t *r, int flags) {
    ia_case k;
    k.a = gen_interval(r, flags);
    k.b = gen_interval(r, flags);
    k.n = gen_pown_n(r);
    k.c = gen_finite(r, flags);
    return k;
}

/* Inputs that broke ia/ once (found by these tests), pinned so that they run first forever. Fills k with the
 * i-th and returns 1, or 0 past the end. Values are floats, so both formats get them. */
static inline int regress_case(int i, ia_case *k) {
    static const struct {
        double alo, ahi, blo, bhi;
        int n;
        double c;
    } t[] = {
        /* the k = 0 widening under-moved near the subnormal range (the pad's product was subnormal) */
        {-0x1.8p+3, 0x1.f1881cp-127, -0x1.ep+2, -0x1.ab1366p-125, 0, 0},
        {-0x1.fffffcp-127, 0, -0x1p-126, 0x1.000004p-126, 0, 0},
        {-0x1.000004p-126, 0x1.fffffcp-127, 0, 0, 0, 0x1.02a28p-125},
        /* div: a with a zero bound over b touching 0 gave entire instead of a half-line */
        {-0.0, 0x1.de7184p+2, 0, 0x1.160724p+17, 0, 0},
        {-3, -1e-4, -3.5, 0, 0, 0},
        /* pown, negative n: a^|n| overflowed, so 1/a^|n| stopped at 1/MAX */
        {0x1.2d97c6p+4, 0x1.2d97c6p+4, 0, 0, -499, 0},
        {-0x1.6d0ff6p+2, 0x1.6645d4p+0, 0, 0, -54, 0},
        /* pown: square-and-multiply errors compound for large n */
        {-0.5, -0.5, 0, 0, 51, 0},
        {-0x1.ccf614p-3, -0x1.26e08p-15, 0, 0, 48, 0},
        /* sin of huge arguments: a / pi cannot be enclosed to within one integer */
        {0x1.403e14p+51, 0x1.403e16p+51, 0, 0, 0, 0},
        {-0x1.f70e4ap+87, -0x1.f70e4ap+87, 0, 0, 0, 0},
        /* width: hi - lo exact, widened needlessly; and 2 steps near 0 */
        {-0x0p+0, 0x1.fffff8p-127, 0, 0, 0, 0},
        {-0x1.921fb6p+2, 0x1.921fb6p+2, 0, 0, 0, 0},
    };
    if (i < 0 || (size_t)i >= sizeof t / sizeof t[0])
        return 0;
    k->a = ia_make((ia_real)t[i].alo, (ia_real)t[i].ahi);
    k->b = t[i].blo == 0 && t[i].bhi == 0 ? ia_make(1, 2) : ia_make((ia_real)t[i].blo, (ia_real)t[i].bhi);
    k->n = t[i].n;
    k->c = (ia_real)t[i].c;
    return 1;
}

/* ---- a real in an interval */

static inline double pt_clamp(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

/* A double in a (NaN when a is empty). Unbounded sides are explored up to the format's MAX and beyond
 * (a float interval [1, +inf] contains 1e300). */
static inline double gen_point(test_rng_t *r, ia_interval a) {
    if (ia_is_empty(a))
        return NAN;
    double lo = a.lo, hi = a.hi;
    if (lo == hi)
        return lo;
    static const double far[] = {(double)IA_REAL_MAX, 1e300, 1.7976931348623157e308, 1e10};
    double flo = lo == -INFINITY ? -far[gen_u32(r, 4)] : lo, fhi = hi == INFINITY ? far[gen_u32(r, 4)] : hi;
    if (flo > fhi) { /* e.g. [-inf, -1e30] with a far value above: go further out, up to the largest double */
        if (lo == -INFINITY)
            flo = fmax(fhi - fabs(fhi) * test_rand_unit(r) * 8 - 1, -1.7976931348623157e308);
        else
            fhi = fmin(flo + fabs(flo) * test_rand_unit(r) * 8 + 1, 1.7976931348623157e308);
    }
    double x;
    uint32_t w = gen_u32(r, 100);
    if (w < 15)
        x = flo;
    else if (w < 30)
        x = fhi;
    else if (w < 55) {
        double u = test_rand_unit(r);
        x = flo * (1 - u) + fhi * u;
        if (!isfinite(x))
            x = flo * 0.5 * (1 - u) * 2 + fhi * u; /* overflow on huge spans: fall back */
        if (!isfinite(x))
            x = u < 0.5 ? flo : fhi;
    } else if (w < 75) { /* a random magnitude with the sign of a random end point */
        double m = ldexp(1 + test_rand_unit(r), (int)gen_u32(r, 2100) - 1075);
        x = gen_u32(r, 2) ? m : -m;
        if (!(x >= flo && x <= fhi))
            x = flo * 0.5 + fhi * 0.5;
    } else if (w < 88) { /* a few doubles inside an end point */
        int k = 1 + (int)gen_u32(r, 4);
        x = gen_u32(r, 2) ? flo : fhi;
        for (int i = 0; i < k; i++)
            x = nextafter(x, x == flo ? fhi : flo);
    } else if (w < 93) {
        x = 0;
    } else { /* the double nearest a multiple of pi/2 inside, if there is one */
        double q = (flo * 0.5 + fhi * 0.5) / 1.5707963267948966;
        if (fabs(q) < 1e15)
            x = (nearbyint(q) + (double)((int)gen_u32(r, 3) - 1)) * 1.5707963267948966;
        else
            x = flo;
    }
    x = pt_clamp(x, flo, fhi);
    if (!(x >= lo && x <= hi))
        x = lo > -INFINITY ? lo : hi;
    return x;
}

/* ---- running one op */

static inline void ia_apply(int op, const ia_case *k, ia_real out[2]) {
    ia_interval r = ia_empty();
    ia_real v = 0;
    int scalar = 0;
    switch (op) {
    case ORACLE_ADD: r = ia_add(k->a, k->b); break;
    case ORACLE_SUB: r = ia_sub(k->a, k->b); break;
    case ORACLE_MUL: r = ia_mul(k->a, k->b); break;
    case ORACLE_DIV: r = ia_div(k->a, k->b); break;
    case ORACLE_RECIP: r = ia_recip(k->a); break;
    case ORACLE_SQR: r = ia_sqr(k->a); break;
    case ORACLE_POWN: r = ia_pown(k->a, k->n); break;
    case ORACLE_POW: r = ia_pow(k->a, k->b); break;
    case ORACLE_SQRT: r = ia_sqrt(k->a); break;
    case ORACLE_EXP: r = ia_exp(k->a); break;
    case ORACLE_LOG: r = ia_log(k->a); break;
    case ORACLE_SIN: r = ia_sin(k->a); break;
    case ORACLE_COS: r = ia_cos(k->a); break;
    case ORACLE_TAN: r = ia_tan(k->a); break;
    case ORACLE_ATAN: r = ia_atan(k->a); break;
    case ORACLE_NEG: r = ia_neg(k->a); break;
    case ORACLE_ABS: r = ia_abs(k->a); break;
    case ORACLE_MIN: r = ia_min(k->a, k->b); break;
    case ORACLE_MAX: r = ia_max(k->a, k->b); break;
    case ORACLE_HULL: r = ia_hull(k->a, k->b); break;
    case ORACLE_INTERSECT: r = ia_intersect(k->a, k->b); break;
    case ORACLE_MID: v = ia_mid(k->a), scalar = 1; break;
    case ORACLE_WIDTH: v = ia_width(k->a), scalar = 1; break;
    case ORACLE_ADD_R: r = ia_add_r(k->a, k->c); break;
    case ORACLE_MUL_R: r = ia_mul_r(k->a, k->c); break;
    case ORACLE_CNEG: v = (ia_real)ia_certainly_neg(k->a), scalar = 1; break;
    case ORACLE_CPOS: v = (ia_real)ia_certainly_pos(k->a), scalar = 1; break;
    case ORACLE_CZERO: v = (ia_real)ia_contains_zero(k->a), scalar = 1; break;
    case ORACLE_ISEMPTY: v = (ia_real)ia_is_empty(k->a), scalar = 1; break;
    case ORACLE_ISENTIRE: v = (ia_real)ia_is_entire(k->a), scalar = 1; break;
    case ORACLE_CONTAINS: v = (ia_real)ia_contains(k->a, k->c), scalar = 1; break;
    }
    out[0] = scalar ? v : r.lo;
    out[1] = scalar ? v : r.hi;
}

/* ---- points with their exact values, and the containment check */

#define PT_MAX 64
typedef struct {
    double x, y; /* the point of a, and of b (or c) */
    int def, t;  /* in the domain; ternary of v */
    mpfr_t v;    /* the exact value rounded down (see oracle_in) */
} pt_t;

static inline void pt_init(pt_t *p, int n) {
    oracle_init();
    for (int i = 0; i < n; i++)
        mpfr_init2(p[i].v, ORACLE_PREC);
}
static inline void pt_clear(pt_t *p, int n) {
    for (int i = 0; i < n; i++)
        mpfr_clear(p[i].v);
}

/* Draws up to n points of the case for op, with the exact value of op at each; returns how many. */
static inline int pt_draw(int op, const ia_case *k, pt_t *p, int n, test_rng_t *r) {
    int kind = oracle_op_kind[op];
    for (int i = 0; i < n; i++) {
        p[i].x = gen_point(r, k->a);
        p[i].y = kind == ORACLE_K_REAL || op == ORACLE_CONTAINS ? (double)k->c
                 : op == ORACLE_WIDTH                           ? gen_point(r, k->a)
                                                                : gen_point(r, k->b);
        p[i].def = 0;
        p[i].t = 0;
        if (kind == ORACLE_K_UN || kind == ORACLE_K_BIN || kind == ORACLE_K_POWN || kind == ORACLE_K_REAL) {
            if (isnan(p[i].x) || isnan(p[i].y))
                continue;
            p[i].def = oracle_eval(op, p[i].x, p[i].y, k->n, p[i].v, &p[i].t);
        } else if (op == ORACLE_WIDTH && !isnan(p[i].x)) { /* |x - y| for two points of a */
            double hi = fmax(p[i].x, p[i].y), lo = fmin(p[i].x, p[i].y);
            p[i].def = oracle_eval(ORACLE_SUB, hi, lo, 0, p[i].v, &p[i].t);
        }
    }
    return n;
}

/* Results come from an IA_FTZ build: mid and width may be a smallest normal away from the exact value. */
#ifdef IA_FTZ
static int pt_ftz = 1;
#else
static int pt_ftz = 0;
#endif

static inline int fmt_is_valid(ia_real lo, ia_real hi) { /* a well-formed interval of ia/ */
    if (isnan(lo) || isnan(hi))
        return 0;
    if (lo == IA_INF || hi == -IA_INF)
        return lo == IA_INF && hi == -IA_INF;
    return lo <= hi;
}

static inline const char *case_str(int op, const ia_case *k) {
    static char s[512];
    snprintf(s, sizeof s, "%s: a = [%s, %s], b = [%s, %s], n = %d, c = %s", oracle_op_name[op], oracle_hex(k->a.lo),
             oracle_hex(k->a.hi), oracle_hex(k->b.lo), oracle_hex(k->b.hi), k->n, oracle_hex(k->c));
    return s;
}

/* Checks one result of op on case k against the points; returns 0, or 1 with a message in msg. *checks counts
 * the containment checks made. `who` names the evaluator (host, device, ...). */
static inline int pt_check(int op, const ia_case *k, const pt_t *p, int n, const ia_real out[2], const char *who,
                           char *msg, size_t size, long *checks) {
    int kind = oracle_op_kind[op];
    double lo = out[0], hi = out[1];
    int a_empty = ia_is_empty(k->a), b_empty = ia_is_empty(k->b);
#define FAIL(...)                                                                                                      \
    do {                                                                                                               \
        int m_ = snprintf(msg, size, "%s %s " FMT_NAME ", %s: ", who, oracle_op_name[op], case_str(op, k));            \
        if (m_ > 0 && (size_t)m_ < size)                                                                               \
            snprintf(msg + m_, size - (size_t)m_, __VA_ARGS__);                                                        \
        return 1;                                                                                                      \
    } while (0)
    if (kind == ORACLE_K_UN || kind == ORACLE_K_BIN || kind == ORACLE_K_POWN || kind == ORACLE_K_REAL ||
        kind == ORACLE_K_SET) {
        (*checks)++;
        if (!fmt_is_valid(out[0], out[1]))
            FAIL("result [%s, %s] is not a valid interval", oracle_hex(lo), oracle_hex(hi));
        int uses_b = kind == ORACLE_K_BIN || kind == ORACLE_K_SET;
        if (kind != ORACLE_K_SET && (a_empty || (uses_b && b_empty)) && !(lo == INFINITY && hi == -INFINITY))
            FAIL("empty input gave [%s, %s]", oracle_hex(lo), oracle_hex(hi));
    }
    switch (kind) {
    case ORACLE_K_UN:
    case ORACLE_K_BIN:
    case ORACLE_K_POWN:
    case ORACLE_K_REAL:
        for (int i = 0; i < n; i++) {
            if (!p[i].def)
                continue;
            (*checks)++;
            if (!oracle_in(p[i].v, p[i].t, lo, hi))
                FAIL("at x = %s, y = %s the exact value %s%s is not in the result [%s, %s]", oracle_hex(p[i].x),
                     oracle_hex(p[i].y), oracle_str(p[i].v), p[i].t ? "+" : "", oracle_hex(lo), oracle_hex(hi));
        }
        return 0;
    case ORACLE_K_SET: {
        ia_interval ex = op == ORACLE_HULL ? ia_hull(k->a, k->b) : ia_intersect(k->a, k->b);
        /* the exact answer, written out independently of ia/ */
        double elo, ehi;
        if (op == ORACLE_HULL) {
            elo = a_empty ? (double)k->b.lo : b_empty ? (double)k->a.lo : fmin(k->a.lo, k->b.lo);
            ehi = a_empty ? (double)k->b.hi : b_empty ? (double)k->a.hi : fmax(k->a.hi, k->b.hi);
        } else {
            elo = fmax(k->a.lo, k->b.lo), ehi = fmin(k->a.hi, k->b.hi);
            if (a_empty || b_empty || elo > ehi)
                elo = INFINITY, ehi = -INFINITY;
        }
        (void)ex;
        for (int i = 0; i < n; i++) {
            double xs[2] = {p[i].x, p[i].y};
            for (int j = 0; j < 2; j++) {
                double x = xs[j];
                if (isnan(x))
                    continue;
                int must = op == ORACLE_HULL || (x >= k->a.lo && x <= k->a.hi && x >= k->b.lo && x <= k->b.hi);
                (*checks)++;
                if (must && !(x >= lo && x <= hi))
                    FAIL("the point %s is not in the result [%s, %s]", oracle_hex(x), oracle_hex(lo), oracle_hex(hi));
            }
        }
        if (!(lo == elo && hi == ehi))
            FAIL("result [%s, %s], exact [%s, %s]", oracle_hex(lo), oracle_hex(hi), oracle_hex(elo), oracle_hex(ehi));
        return 0;
    }
    case ORACLE_K_QUERY: {
        int q = out[0] != 0, e;
        double alo = k->a.lo, ahi = k->a.hi, c = k->c;
        switch (op) {
        case ORACLE_CNEG: e = a_empty || ahi < 0; break;
        case ORACLE_CPOS: e = a_empty || alo > 0; break;
        case ORACLE_CZERO: e = !a_empty && alo <= 0 && ahi >= 0; break;
        case ORACLE_ISEMPTY: e = a_empty; break;
        case ORACLE_ISENTIRE: e = alo == -INFINITY && ahi == INFINITY; break;
        default: e = alo <= c && c <= ahi; break;
        }
        if (!(out[0] == 0 || out[0] == 1))
            FAIL("query returned %s", oracle_hex(out[0]));
        for (int i = 0; i < n; i++) { /* a claim about every point must hold at each point */
            double x = p[i].x;
            if (isnan(x))
                continue;
            (*checks)++;
            int bad = (op == ORACLE_CNEG && q && !(x < 0)) || (op == ORACLE_CPOS && q && !(x > 0)) ||
                      (op == ORACLE_CZERO && !q && x == 0) || (op == ORACLE_ISEMPTY && q);
            if (bad)
                FAIL("claim %d is false at the point %s", q, oracle_hex(x));
        }
        if (q != e)
            FAIL("returned %d, exact answer %d", q, e);
        return 0;
    }
    case ORACLE_K_NUM:
        (*checks)++;
        if (op == ORACLE_MID) {
            double m = out[0], alo = k->a.lo, ahi = k->a.hi;
            if (a_empty) {
                if (!isnan(m))
                    FAIL("mid of empty is %s, not NaN", oracle_hex(m));
                return 0;
            }
            if (alo == -INFINITY || ahi == INFINITY) {
                double e = alo == -INFINITY && ahi == INFINITY ? 0
                           : alo == -INFINITY                  ? -(double)IA_REAL_MAX
                                                               : (double)IA_REAL_MAX;
                if (m != e)
                    FAIL("mid is %s, expected %s", oracle_hex(m), oracle_hex(e));
                return 0;
            }
            if (!(m >= alo && m <= ahi))
                FAIL("mid %s is not in a", oracle_hex(m));
            /* within one format step of the exact centre */
            mpfr_t cen;
            mpfr_init2(cen, 4096); /* the sum of two doubles is exact at 4096 bits */
            mpfr_set_d(cen, alo, MPFR_RNDN);
            mpfr_add_d(cen, cen, ahi, MPFR_RNDN);
            mpfr_div_2ui(cen, cen, 1, MPFR_RNDN);
            double cd = oracle_round(cen, -1, FMT_MANT), cu = oracle_round(cen, 1, FMT_MANT);
            mpfr_clear(cen);
            int far = oracle_steps(cd, m, FMT_MANT) < -1 || oracle_steps(cu, m, FMT_MANT) > 1;
            if (pt_ftz && far && fabs(m - cd) <= (double)IA_REAL_MIN_NORMAL) /* no subnormals: MIN steps */
                far = 0;
            if (far)
                FAIL("mid %s is more than one step from the centre [%s, %s]", oracle_hex(m), oracle_hex(cd),
                     oracle_hex(cu));
            return 0;
        } else {
            double w = out[0];
            if (a_empty) {
                if (w != 0)
                    FAIL("width of empty is %s", oracle_hex(w));
                return 0;
            }
            if (isnan(w) || w < 0)
                FAIL("width %s", oracle_hex(w));
            for (int i = 0; i < n; i++) {
                if (!p[i].def)
                    continue;
                (*checks)++;
                if (!oracle_in(p[i].v, p[i].t, -INFINITY, w))
                    FAIL("width %s < |x - y| = %s for x = %s, y = %s", oracle_hex(w), oracle_str(p[i].v),
                         oracle_hex(p[i].x), oracle_hex(p[i].y));
            }
            /* and not more than one step above the exact hi - lo rounded up */
            if (isfinite(k->a.lo) && isfinite(k->a.hi)) {
                mpfr_t d;
                mpfr_init2(d, 4096);
                mpfr_set_d(d, k->a.hi, MPFR_RNDN);
                mpfr_sub_d(d, d, k->a.lo, MPFR_RNDU);
                double du = oracle_round(d, 1, FMT_MANT);
                int sub = mpfr_cmp_d(d, w) > 0;
                mpfr_clear(d);
                int loose = oracle_steps(du, w, FMT_MANT) > fmt_k0_steps(du);
                /* flushing, the widening adds MIN, and an ulp more where r + MIN rounds up (a tie for the ulp 2 MIN) */
                if (pt_ftz && loose && w - du <= 2 * (double)IA_REAL_MIN_NORMAL + (fmt_step((ia_real)du, 1) - du))
                    loose = 0;
                if (sub || loose)
                    FAIL("width %s, exact width rounded up %s", oracle_hex(w), oracle_hex(du));
            } else if (w != INFINITY) {
                FAIL("width of an unbounded interval is %s", oracle_hex(w));
            }
            return 0;
        }
    }
#undef FAIL
    return 0;
}

/* ---- ulp errors of the math functions ia/ relies on */

/* Arguments for measuring fn: its whole domain, with weight on the ranges ia/ meets (tests/oracle_ia.h). */
static inline void fn_args(int fn, test_rng_t *r, ia_real *x, ia_real *y) {
    ia_real u = gen_finite(r, 0), v = gen_finite(r, 0);
    switch (fn) {
    case ORACLE_FN_SQRT:
    case ORACLE_FN_LOG: u = fabs(u); break;
    case ORACLE_FN_EXP: /* mostly where exp is finite and not 0 */
        if (gen_u32(r, 4))
            u = (ia_real)((test_rand_unit(r) * 2 - 1) * (FMT_MANT == 24 ? 104 : 745));
        break;
    case ORACLE_FN_POW: /* x > 0, |y| moderate: x^y mostly in range */
        u = fabs(u);
        if (gen_u32(r, 4))
            v = (ia_real)((test_rand_unit(r) * 2 - 1) * (gen_u32(r, 2) ? 4 : 64));
        break;
    case ORACLE_FN_SIN:
    case ORACLE_FN_COS:
    case ORACLE_FN_TAN:
        if (gen_u32(r, 2))
            u = (ia_real)((test_rand_unit(r) * 2 - 1) * 16);
        break;
    default: break;
    }
    *x = u, *y = v;
}

/* Max ulp error of fn over `count` arguments; the worst argument in *wx, *wy. With ftz (a device that flushes
 * subnormals, given arguments as real_flushed makes them), an error within the smallest normal number is its
 * flush, which ia/round.h's TINY covers there, and does not count. */
static inline double fn_measure(int fn, const ia_real *x, const ia_real *y, const ia_real *res, long count, int ftz,
                                double *wx, double *wy) {
    mpfr_t e, gap;
    mpfr_inits2(ORACLE_PREC, e, gap, (mpfr_ptr)0);
    double worst = 0;
    for (long i = 0; i < count; i++) {
        if (isnan(res[i]) && (fn == ORACLE_FN_DIV ? y[i] == 0 : 0))
            continue;
        oracle_fn(fn, x[i], y[i], e);
        if (mpfr_nan_p(e))
            continue; /* 0/0, inf/inf: not used by ia/ */
        if (ftz && isfinite(res[i]) && mpfr_number_p(e)) {
            mpfr_sub_d(gap, e, res[i], MPFR_RNDA);
            mpfr_abs(gap, gap, MPFR_RNDN);
            if (mpfr_cmp_d(gap, (double)IA_REAL_MIN_NORMAL) <= 0)
                continue;
        }
        double u = oracle_ulp_error(res[i], e, FMT_MANT, FMT_EMIN);
        if (u > worst)
            worst = u, *wx = x[i], *wy = y[i];
    }
    mpfr_clears(e, gap, (mpfr_ptr)0);
    return worst;
}

/* The max ulp error of each function, measured one function at a time, against the IA_ULP_* bounds of a table
 * (0 means correctly rounded: half an ulp); the first function over its bound is kept for the failure message. */
typedef struct {
    char line[1024];
    size_t len;
    int bad, bad_bound;
    double bad_u, bad_x, bad_y;
} ulp_report;

static inline void ulp_report_add(ulp_report *rep, int fn, int table_ulps, const ia_real *x, const ia_real *y,
                                  const ia_real *res, long count, int ftz) {
    double wx = 0, wy = 0, u = fn_measure(fn, x, y, res, count, ftz, &wx, &wy);
    double bound = table_ulps == 0 ? 0.5 : table_ulps;
    if (rep->len < sizeof rep->line)
        rep->len += (size_t)snprintf(rep->line + rep->len, sizeof rep->line - rep->len, " %s %.3g (<= %g)",
                                     oracle_fn_name[fn], u, bound);
    if (u > bound && rep->bad < 0)
        rep->bad = fn, rep->bad_bound = table_ulps, rep->bad_u = u, rep->bad_x = wx, rep->bad_y = wy;
}

/* Notes the maxima and fails the test if a function exceeded its bound; `who` is "host" or "device". */
#define ULP_REPORT_FINISH(rep, who)                                                                            \
    do {                                                                                                       \
        test_note(who " max ulp error " FMT_NAME ":%s", (rep).line);                                           \
        CHECK((rep).bad < 0, who " %s " FMT_NAME " error %.3g ulps exceeds the IA_ULP bound %d at x = %s, y = %s", \
              (rep).bad >= 0 ? oracle_fn_name[(rep).bad] : "", (rep).bad_u, (rep).bad_bound,                  \
              oracle_hex((rep).bad_x), oracle_hex((rep).bad_y));                                               \
    } while (0)

/* An evaluator of op on count cases into out (two reals a case); returns 0, or nonzero with a message. */
typedef int (*pt_evaluator)(int op, const ia_case *k, long count, ia_real *out, char *msg, size_t size);

/* Containment of every op on count random cases evaluated by eval: with ftz (an IA_FTZ build: the host in MXCSR
 * FTZ+DAZ, a device that flushes subnormals) on cases without subnormal bounds, IA_FTZ's precondition, and with
 * pt_ftz's allowances. Returns 0 with *checks counted, or nonzero with the first violation in msg. */
static inline int pt_check_all_ops(test_rng_t *r, long count, int ftz, pt_evaluator eval, const char *who,
                                   long *checks, char *msg, size_t size) {
    const int np = 10;
    ia_case *k = calloc((size_t)count, sizeof *k);
    ia_real *out = malloc(sizeof *out * 2 * (size_t)count);
    if (!k || !out) {
        free(k), free(out);
        snprintf(msg, size, "out of memory");
        return 1;
    }
    pt_t p[PT_MAX];
    pt_init(p, np);
    int saved = pt_ftz, bad = 0;
    pt_ftz = ftz;
    for (int op = 0; op < ORACLE_NOPS && !bad; op++) {
        for (long i = 0; i < count; i++)
            k[i] = gen_case(r, ftz ? GEN_NO_SUBNORMAL : 0);
        bad = eval(op, k, count, out, msg, size);
        for (long i = 0; !bad && i < count; i++) {
            pt_draw(op, &k[i], p, np, r);
            bad = pt_check(op, &k[i], p, np, out + 2 * i, who, msg, size, checks);
        }
    }
    pt_ftz = saved;
    pt_clear(p, np);
    free(k), free(out);
    return bad;
}

/* ---- the device (tests/t_ia_device_fp.c): one OpenCL device, the ia/ test program built once per format with
 * the options of clrt_ia_options, in a mode: 0 rigorous, 1 fast (IA_FAST), 2 rigorous keeping subnormals.
 * Each returns 0, or -1 with a message in err. */
int FP_NAME(ia_dev_ops)(int mode, int op, const ia_case *k, long count, ia_real *out, char *err, size_t size);
int FP_NAME(ia_dev_fns)(int fn, const ia_real *x, const ia_real *y, long count, ia_real *out, char *err, size_t size);
/* Times `reps` applications of op per work item over `items` work items; *seconds is the kernel's wall time. */
int FP_NAME(ia_dev_bench)(int fast, int op, int reps, const ia_case *k, long count, long items, double *seconds,
                          char *err, size_t size);
/* The device build's IA_ULP_* per ORACLE_FN_*, then 1 if it was built with IA_FTZ, then its IA_POWN_CHAIN_MAX
 * (ORACLE_NFNS + 2 ints). */
int FP_NAME(ia_dev_ulp_table)(int *out, char *err, size_t size);
/* "platform / device (build options)" of a mode's build, after a successful call of the above. */
const char *FP_NAME(ia_dev_describe)(int mode);
/* 1 if a mode's build flushes subnormals (IA_FTZ: the renderer's, modes 0 and 1; mode 2 only on a device without
 * them): its cases must then be given as case_flushed makes them. */
int FP_NAME(ia_dev_flushes)(int mode);
/* "platform / device (build options)" of the build in a mode with extra options (see ia_dev_ops_in). */
const char *FP_NAME(ia_dev_describe_in)(int mode, const char *extra);

#endif
