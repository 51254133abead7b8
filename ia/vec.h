/* ia/vec.h -- intervals of IA_VW lanes, OpenCL C only (built with -D IA_VW=4, 8 or 16): the operations of
 * ia/ over vectors of bounds, without branches, so that one work-item evaluates an expression for IA_VW rays
 * at once in SIMD registers. PoCL does not vectorise the bisection across work-items (its trip count differs
 * per ray), so the kernels do it by hand (kernels/packet.h) and need these.
 *
 * The contract differs from ia/ia.h in one point, on purpose: a lane whose operand is empty, or whose operand
 * misses the operation's domain entirely (sqrt of [-2,-1]), may hold ANY value, NaN included. Dropping the
 * emptiness tests is what makes the operations branch-free. It is enough for the renderer: a lane is empty only
 * where an operation was undefined on all of its box, and the emitted code raises that operation's flags there
 * (ia/ia.h, undefined operands: `empty` beside `undefined`); they reach every node above it up to a union or the
 * value of the whole expression, which read the lane as [+inf, +inf] whatever it holds (iav_or_outside).
 * A lane whose operands are nonempty gets exactly what ia/ia.h promises:
 * inclusion under the same rounding arguments (ia/round.h), bounds never NaN, and the same tightness.
 * A NaN that reaches the end fails iav_contains_zero, as an empty interval would.
 *
 * The polynomial operations (neg + - * sqr pown sqrt abs min max, add_r, mul_r), / and recip away from their
 * poles, and log are vector code, and so are exp, sin and cos where the device has double (ia/elem.h's reductions
 * in double; sin and cos in ia/vec_sincos.h). The others (tan atan pow, / and recip by an interval holding 0, pown
 * with a negative or very large exponent, and exp, sin and cos elsewhere) run ia/'s scalar operation lane by lane:
 * correct, not faster; a lane with a NaN bound is passed to them as empty.
 */
#ifndef IA_VEC_H
#define IA_VEC_H
#include "elem.h"
#if IA_DEVICE && defined(IA_VW)

#define IAV_CAT_(a, b) a##b
#define IAV_CAT(a, b) IAV_CAT_(a, b)
#ifdef IA_FP64
typedef IAV_CAT(double, IA_VW) ia_realv;
typedef IAV_CAT(long, IA_VW) ia_maskv; /* comparisons: -1 (all bits) in a true lane, 0 in a false one */
#else
typedef IAV_CAT(float, IA_VW) ia_realv;
typedef IAV_CAT(int, IA_VW) ia_maskv;
#endif
#define IAV_LOAD(p) IAV_CAT(vload, IA_VW)(0, p)
#define IAV_STORE(v, p) IAV_CAT(vstore, IA_VW)(v, 0, p)
#define IAV_R(x) ((ia_realv)(x))
/* For the functions whose integer argument is an expression constant: inlined, the constant unrolls their
 * loops and folds their branches (left to itself, LLVM kept iav__pown_nonneg a called loop in double, a third
 * of the tangle's render time). */
#define IAV_INLINE static inline __attribute__((always_inline))

typedef struct {
    ia_realv lo, hi;
} iav;

IA_FN iav iav_make(ia_realv lo, ia_realv hi) {
    iav r;
    r.lo = lo;
    r.hi = hi;
    return r;
}
/* Every lane the same: a constant [lo, hi], a point, or a scalar interval. */
IA_FN iav iav_const(ia_real lo, ia_real hi) { return iav_make(IAV_R(lo), IAV_R(hi)); }
IA_FN iav iav_point(ia_real x) { return iav_const(x, x); }
IA_FN iav iav_splat(ia_interval a) { return iav_const(a.lo, a.hi); }

/* Lanes where 0 may be a value; false on NaN and on empty. */
IA_FN ia_maskv iav_contains_zero(iav a) { return a.lo <= 0 && a.hi >= 0; }

/* ---- widening (ia/round.h), lane-wise: the same pads; fmin / fmax map the NaN of "inf - inf" to the finite
 * end as ia__below_max / ia__above_min do. */
#ifdef IA_FAST
#define iav_lo_k(r, k) (r)
#define iav_hi_k(r, k) (r)
#else
#define iav_lo_k(r, k) fmin(fma(fabs(r), IAV_R(-IA_PAD_C(k)), (r) - IA_PAD_T(k)), IAV_R(IA_REAL_MAX))
#define iav_hi_k(r, k) fmax(fma(fabs(r), IAV_R(IA_PAD_C(k)), (r) + IA_PAD_T(k)), IAV_R(-IA_REAL_MAX))
#endif
#define iav_lo(r) iav_lo_k(r, 0)
#define iav_hi(r) iav_hi_k(r, 0)

/* ---- exact operations */
IA_FN iav iav_neg(iav a) { return iav_make(-a.hi, -a.lo); }
/* [mig, mag]; + 0 turns a -0 lower bound into +0, as ia_abs does. */
IA_FN iav iav_abs(iav a) {
    return iav_make(fmax(fmax(a.lo, -a.hi), IAV_R(0)) + IAV_R(0), fmax(-a.lo, a.hi));
}
IA_FN iav iav_min(iav a, iav b) { return iav_make(fmin(a.lo, b.lo), fmin(a.hi, b.hi)); }
IA_FN iav iav_max(iav a, iav b) { return iav_make(fmax(a.lo, b.lo), fmax(a.hi, b.hi)); }

/* any(m) and the number of true lanes, by trees of ORs and sums of halves: PoCL's any() tests the lanes one by
 * one. A true lane of a mask is -1. */
#ifdef IA_FP64
typedef long8 iav__mask8;
typedef long4 iav__mask4;
typedef long2 iav__mask2;
#else
typedef int8 iav__mask8;
typedef int4 iav__mask4;
typedef int2 iav__mask2;
#endif
#if IA_VW == 16
#define IAV__HALVES(m, op) ((m).lo op(m).hi)
#else
#define IAV__HALVES(m, op) (m)
#endif
IA_FN int iav_any(ia_maskv m) {
    iav__mask8 m8 = IAV__HALVES(m, |);
    iav__mask4 m4 = m8.lo | m8.hi;
    iav__mask2 m2 = m4.lo | m4.hi;
    return (m2.x | m2.y) < 0;
}
IA_FN int iav_count(ia_maskv m) {
    iav__mask8 m8 = IAV__HALVES(m, +);
    iav__mask4 m4 = m8.lo + m8.hi;
    iav__mask2 m2 = m4.lo + m4.hi;
    return -(int)(m2.x + m2.y);
}

/* ia_or_outside and ia_union lane by lane. A lane's emptiness cannot be read from its bounds here (see the top),
 * so the emitted code carries it as a second flag, `empty` (undefined on all of the box; it implies
 * `undefined`): such a lane counts as [+inf, +inf], outside everywhere, the other flagged lanes as [lo, +inf]. */
IA_FN iav iav_or_outside(iav a, ia_maskv undefined, ia_maskv empty) {
    return iav_make(select(a.lo, IAV_R(IA_INF), empty), select(a.hi, IAV_R(IA_INF), undefined));
}
IA_FN iav iav_union(iav a, ia_maskv a_undefined, ia_maskv a_empty, iav b, ia_maskv b_undefined, ia_maskv b_empty) {
    return iav_min(iav_or_outside(a, a_undefined, a_empty), iav_or_outside(b, b_undefined, b_empty));
}

/* [-inf, +inf] in the lanes of m, a elsewhere: the derivative code's answer where F may be undefined. */
IA_FN iav iav_entire_where(iav a, ia_maskv m) {
    return iav_make(select(a.lo, IAV_R(-IA_INF), m), select(a.hi, IAV_R(IA_INF), m));
}

/* ia_hull of nonempty operands, and ia_dabs, ia_dmin, ia_dmax lane by lane (the same choices, as selects). */
IA_FN iav iav_hull(iav a, iav b) { return iav_make(fmin(a.lo, b.lo), fmax(a.hi, b.hi)); }
IA_FN iav iav__pick(iav when_false, iav when_true, ia_maskv m) {
    return iav_make(select(when_false.lo, when_true.lo, m), select(when_false.hi, when_true.hi, m));
}
IA_FN iav iav_dabs(iav a, iav da) {
    iav n = iav_neg(da);
    return iav__pick(iav__pick(iav_hull(da, n), n, a.hi < 0), da, a.lo > 0);
}
IA_FN iav iav_dmin(iav a, iav b, iav da, iav db) {
    return iav__pick(iav__pick(iav_hull(da, db), db, b.hi < a.lo), da, a.hi < b.lo);
}
IA_FN iav iav_dmax(iav a, iav b, iav da, iav db) {
    return iav__pick(iav__pick(iav_hull(da, db), db, b.lo > a.hi), da, a.lo > b.hi);
}

/* ---- rounded operations. Nonempty operands have lo < +inf and hi > -inf, so a.lo + b.lo and a.lo - b.hi
 * are never inf - inf: no test needed where ia_add has one. */
IA_FN iav iav_add(iav a, iav b) { return iav_make(iav_lo(a.lo + b.lo), iav_hi(a.hi + b.hi)); }
IA_FN iav iav_sub(iav a, iav b) { return iav_make(iav_lo(a.lo - b.hi), iav_hi(a.hi - b.lo)); }
IA_FN iav iav_add_r(iav a, ia_real c) { return iav_make(iav_lo(a.lo + c), iav_hi(a.hi + c)); }

/* c is a constant of the expression: the tests on it are the same in every lane. */
IA_FN iav iav_mul_r(iav a, ia_real c) {
    if (c == 0)
        return iav_point(0);
    ia_realv p = a.lo * c, q = a.hi * c;
    return c > 0 ? iav_make(iav_lo(p), iav_hi(q)) : iav_make(iav_lo(q), iav_hi(p));
}

/* x * y with 0 * inf = 0, as ia__mul0. */
IA_FN ia_realv iav__mul0(ia_realv x, ia_realv y) {
    ia_realv p = x * y;
    return select(p, IAV_R(0), isnan(p));
}
IA_FN iav iav_mul(iav a, iav b) {
    ia_realv p1 = iav__mul0(a.lo, b.lo), p2 = iav__mul0(a.lo, b.hi);
    ia_realv p3 = iav__mul0(a.hi, b.lo), p4 = iav__mul0(a.hi, b.hi);
    return iav_make(iav_lo(fmin(fmin(p1, p2), fmin(p3, p4))), iav_hi(fmax(fmax(p1, p2), fmax(p3, p4))));
}

/* ---- operands known to start at 0 or above (lo >= 0 in every lane that counts), which the emitter proves node by
 * node (implicits/emit_signs.c). A product of such is [a.lo b.lo, a.hi b.hi], not the min and max of four; a sum or
 * product of such is >= 0 too, so its lower bound, which the widening may take below 0, is clamped at 0 (tighter
 * than iav_add's and iav_mul's, never wider), and the next operation may rely on it; such a result needs no
 * |r| to widen either bound (iav_lo's and iav_hi's values, one and two instructions fewer; iav_sqr's results are
 * >= 0 too: the tangle's rigorous kernel 3 % fewer samples), nor a clamp above. iav_mul_n takes one operand >= 0 and
 * one of any sign: two products, chosen by the other's signs, with iav_mul's bits; so has iav_sqr_nn iav_sqr's. */
#ifdef IA_FAST
#define iav__lo_nonneg(r) (r)
#define iav__hi_nonneg(r) (r)
#else
#define iav__lo_nonneg(r) fmin(fma((r), IAV_R(-IA_PAD_C(0)), (r) - IA_PAD_T(0)), IAV_R(IA_REAL_MAX)) /* for r >= 0 */
#define iav__hi_nonneg(r) fma((r), IAV_R(IA_PAD_C(0)), (r) + IA_PAD_T(0))
#endif
IA_FN ia_realv iav__lo_clamped(ia_realv r) { return fmax(iav__lo_nonneg(r), IAV_R(0)); }
IA_FN iav iav_add_nn(iav a, iav b) { return iav_make(iav__lo_clamped(a.lo + b.lo), iav__hi_nonneg(a.hi + b.hi)); }
IA_FN iav iav_add_r_nn(iav a, ia_real c) { return iav_make(iav__lo_clamped(a.lo + c), iav__hi_nonneg(a.hi + c)); }
IA_FN iav iav_mul_r_nn(iav a, ia_real c) { return iav_make(iav__lo_clamped(a.lo * c), iav__hi_nonneg(a.hi * c)); }
IA_FN iav iav_mul_nn(iav a, iav b) { /* a.lo b.lo is never 0 * inf: a nonempty lower bound is finite */
    return iav_make(iav__lo_clamped(a.lo * b.lo), iav__hi_nonneg(iav__mul0(a.hi, b.hi)));
}
IA_FN iav iav_mul_n(iav a, iav b) {
    ia_realv lo = iav__mul0(select(a.hi, a.lo, b.lo >= 0), b.lo), hi = iav__mul0(select(a.lo, a.hi, b.hi >= 0), b.hi);
    return iav_make(iav_lo(lo), iav_hi(hi));
}
IA_FN iav iav_sqr_nn(iav a) {
    return iav_make(iav__lo_clamped(a.lo * a.lo), select(iav__hi_nonneg(a.hi * a.hi), IAV_R(0), a.hi == 0));
}

/* The derivative code's products (implicits/emit.c: the derivative along a ray, whose leaves move at the rates
 * of the ray's direction, one point per lane). a * [p, p]: iav_mul's result (the same two products, the same
 * rounding) without the two products and four comparisons a point makes redundant. 2a: exact but where it
 * overflows, and there rounded towards the finite range as iav_lo and iav_hi round, not by a pad. */
IA_FN iav iav_mul_pv(iav a, ia_realv p) {
    ia_realv q1 = iav__mul0(a.lo, p), q2 = iav__mul0(a.hi, p);
    ia_maskv negative = p < 0;
    return iav_make(iav_lo(select(q1, q2, negative)), iav_hi(select(q2, q1, negative)));
}
IA_FN iav iav_twice(iav a) {
    return iav_make(fmin(a.lo + a.lo, IAV_R(IA_REAL_MAX)), fmax(a.hi + a.hi, IAV_R(-IA_REAL_MAX)));
}

/* mig = the smallest |x|, mag = the largest; [0, ...] when a straddles 0. */
IA_FN iav iav_sqr(iav a) {
    ia_realv mig = fmax(fmax(a.lo, -a.hi), IAV_R(0)), mag = fmax(-a.lo, a.hi);
    return iav_make(iav__lo_clamped(mig * mig), select(iav__hi_nonneg(mag * mag), IAV_R(0), mag == 0));
}

IA_FN iav iav_sqrt(iav a) {
    ia_realv lo = select(fmax(iav_lo_k(sqrt(a.lo), IA_ULP_SQRT), IAV_R(0)), IAV_R(0), a.lo <= 0);
    return iav_make(lo, iav_hi_k(sqrt(a.hi), IA_ULP_SQRT));
}

/* x^n for x >= 0 (possibly +inf), n >= 1, by ia__pown_nonneg's square-and-multiply, every product rounded
 * down in the lanes where down < 0 and up where it is >= 0: r*C*s + T*s moves outward by the pad of
 * ia/round.h in the lane's direction s = +-1 (fma(|r|, s C, r + s T) is ia_hi_k's form for s = 1 and
 * ia_lo_k's for s = -1). The NaN of +inf rounded down becomes MAX, and a rounded-down product never goes
 * below 0, as in the scalar version. n is a constant of the expression, so the loop unrolls. */
IAV_INLINE ia_realv iav__round_dir(ia_realv r, ia_realv s) {
#ifdef IA_FAST
    (void)s;
    return r;
#else
    ia_realv v = fma(fabs(r), s * IA_PAD_C(0), r + s * IA_PAD_T(0));
    return fmax(select(v, IAV_R(IA_REAL_MAX), isnan(v)), IAV_R(0));
#endif
}
#ifdef IA_DEVICE_DOUBLE
typedef IAV_CAT(double, IA_VW) iav__doublev;
typedef IAV_CAT(long, IA_VW) iav__longv;
#define iav__to_double IAV_CAT(convert_double, IA_VW)
#define iav__to_real IAV_CAT(convert_float, IA_VW)
#define iav__to_mask IAV_CAT(convert_int, IA_VW)
/* ia__float_below and ia__float_above in lanes: rounded to nearest, then a step out where that landed inside. */
IAV_INLINE ia_realv iav__float_below(iav__doublev b) {
    ia_realv f = iav__to_real(b);
#ifdef IA_FAST
    return f;
#else
    return select(f, iav_lo(f), iav__to_mask(iav__to_double(f) > b));
#endif
}
IAV_INLINE ia_realv iav__float_above(iav__doublev b) {
    ia_realv f = iav__to_real(b);
#ifdef IA_FAST
    return f;
#else
    return select(f, iav_hi(f), iav__to_mask(iav__to_double(f) < b));
#endif
}
/* ia__exp_double in lanes (ia/elem.h), the same operations in the same order: bit-identical. */
IAV_INLINE iav__doublev iav__exp_double(ia_realv x) {
    iav__doublev c = fmin(fmax(iav__to_double(x), (iav__doublev)IA__EXP_FLOOR), (iav__doublev)IA__EXP_CEIL);
    iav__doublev k = rint(c * IA__INV_LN2), r = (c - k * IA__LN2_HI) - k * IA__LN2_LO;
    return IA__EXP_POLY(r) * IAV_CAT(as_double, IA_VW)((IAV_CAT(convert_long, IA_VW)(k) + 1023) << 52);
}
/* ia__pown_double in lanes (x > 0 in the lanes that count), the same operations in the same order: bit-identical. */
IAV_INLINE ia_realv iav__pown_double(ia_realv x, unsigned int n, ia_realv s) {
    iav__doublev r = (iav__doublev)1, b = iav__to_double(x);
    for (;;) {
        if (n & 1)
            r *= b;
        n >>= 1;
        if (n == 0)
            break;
        b *= b;
    }
    iav__doublev sd = iav__to_double(s), bound = r + sd * (r * 0x1p-38);
    ia_realv f = iav__to_real(bound);
    iav__doublev back = iav__to_double(f);
    ia_maskv wrong = iav__to_mask(select(back < bound, back > bound, sd < 0));
    f = select(f, iav__round_dir(f, s), wrong);
    ia_maskv huge = ~iav__to_mask(r <= 0x1p1000), tiny = iav__to_mask(r < 0x1p-1000);
    f = select(f, select(IAV_R(IA_INF), IAV_R(IA_REAL_MAX), s < 0), huge);
    return select(f, select(iav__round_dir(IAV_R(0), s), IAV_R(0), s < 0), tiny);
}
#endif
IAV_INLINE ia_realv iav__pown_nonneg(ia_realv x, unsigned int n, ia_realv s) {
#ifdef IA_DEVICE_DOUBLE
    if (n > IA_POWN_FORMAT_MAX)
        return select(iav__pown_double(x, n, s), IAV_R(0), x == 0);
#endif
    ia_realv r = IAV_R(1), b = x;
    int first = 1; /* as in ia__pown_nonneg: the first factor unrounded */
    while (1) {
        if (n & 1)
            r = first ? b : iav__round_dir(r * b, s);
        first &= !(n & 1);
        n >>= 1;
        if (n == 0)
            return select(r, IAV_R(0), x == 0);
        b = iav__round_dir(b * b, s);
    }
}

/* The scalar ia/ operation in each lane, for the operations with no vector version. */
IA_FN ia_interval iav__lane(ia_real lo, ia_real hi) { return isnan(lo) || isnan(hi) ? ia_empty() : ia_make(lo, hi); }
#define IAV_LANEWISE(call)                                                                                     \
    ia_real alo[IA_VW], ahi[IA_VW], blo[IA_VW], bhi[IA_VW];                                                    \
    IAV_STORE(a.lo, alo);                                                                                      \
    IAV_STORE(a.hi, ahi);                                                                                      \
    IAV_STORE(b.lo, blo);                                                                                      \
    IAV_STORE(b.hi, bhi);                                                                                      \
    for (int k = 0; k < IA_VW; k++) {                                                                          \
        ia_interval A = iav__lane(alo[k], ahi[k]), B = iav__lane(blo[k], bhi[k]);                              \
        ia_interval R = call;                                                                                  \
        (void)A;                                                                                               \
        (void)B;                                                                                               \
        alo[k] = R.lo;                                                                                         \
        ahi[k] = R.hi;                                                                                         \
    }                                                                                                          \
    return iav_make(IAV_LOAD(alo), IAV_LOAD(ahi))
#define IAV_UNARY_BY_LANE(name)                                                                                \
    IA_FN iav iav_##name(iav a) {                                                                              \
        iav b = a;                                                                                             \
        IAV_LANEWISE(ia_##name(A));                                                                            \
    }
#define IAV_BINARY_BY_LANE(name)                                                                               \
    IA_FN iav iav_##name(iav a, iav b) { IAV_LANEWISE(ia_##name(A, B)); }
IA_FN iav iav__recip_by_lane(iav a) {
    iav b = a;
    IAV_LANEWISE(ia_recip(A));
}
__attribute__((noinline)) static iav iav__div_by_lane(iav a, iav b) { IAV_LANEWISE(ia_div(A, B)); }
#ifdef IA_DEVICE_DOUBLE
/* ia_exp's bounds from ia__exp_double, in lanes. */
IA_FN iav iav_exp(iav a) {
    iav__doublev lo = iav__exp_double(a.lo), hi = iav__exp_double(a.hi);
    return iav_make(fmax(iav__float_below(lo - lo * IA__EXP_PAD), IAV_R(0)), iav__float_above(hi + hi * IA__EXP_PAD));
}
#else
IAV_UNARY_BY_LANE(exp)
#endif
IAV_UNARY_BY_LANE(atan)
IAV_UNARY_BY_LANE(tan)
IAV_BINARY_BY_LANE(pow)
IA_FN iav iav__pown_by_lane(iav a, int n) {
    iav b = a;
    IAV_LANEWISE(ia_pown(A, n));
}

/* 1 / a and a / b, as ia_recip and ia_div, in vector code when no lane's divisor holds or touches 0 (the usual
 * case: a scale by a constant, a positive denominator); otherwise, for the poles' half-lines and entire
 * results, lane by lane. */
IA_FN ia_maskv iav__has_pole(iav b) { return b.lo <= 0 && b.hi >= 0; }
IA_FN iav iav_recip(iav a) {
    if (iav_any(iav__has_pole(a)))
        return iav__recip_by_lane(a);
    return iav_make(iav_lo_k(1 / a.hi, IA_ULP_DIV), iav_hi_k(1 / a.lo, IA_ULP_DIV));
}
/* x / y with inf / inf = 0, as ia_div's corners. */
IA_FN ia_realv iav__quot0(ia_realv x, ia_realv y) {
    ia_realv q = x / y;
    return select(q, IAV_R(0), isnan(q));
}
IAV_INLINE iav iav_div(iav a, iav b) {
    if (iav_any(iav__has_pole(b)))
        return iav__div_by_lane(a, b);
    ia_realv q1 = iav__quot0(a.lo, b.lo), q2 = iav__quot0(a.lo, b.hi);
    ia_realv q3 = iav__quot0(a.hi, b.lo), q4 = iav__quot0(a.hi, b.hi);
    ia_maskv zero = a.lo == 0 && a.hi == 0; /* exactly [0, 0] */
    return iav_make(select(iav_lo_k(fmin(fmin(q1, q2), fmin(q3, q4)), IA_ULP_DIV), IAV_R(0), zero),
                    select(iav_hi_k(fmax(fmax(q1, q2), fmax(q3, q4)), IA_ULP_DIV), IAV_R(0), zero));
}

/* log, as ia_log: a.hi <= 0 is outside the domain (any value); a.lo <= 0 reaches down to -inf. PoCL's vector
 * log is its scalar log lane by lane (tests/t_ia_vec_device_fp.c finds them bit-identical), so the scalar
 * function's measured error bound (tests/t_ia_device_fp.c) covers it. Its vector exp and atan are not (they
 * differ in about 1 lane in 300 to 10000), so those run lane by lane. */
IA_FN iav iav_log(iav a) {
    return iav_make(select(iav_lo_k(log(a.lo), IA_ULP_LOG), IAV_R(-IA_INF), a.lo <= 0),
                    iav_hi_k(log(a.hi), IA_ULP_LOG));
}

/* a^n for an integer constant n. Even n: |a|'s ends; odd n: increasing, each end's sign chooses the
 * direction of its chain and the sign of its result. Negative n, and n beyond the device's square-and-multiply
 * range (IA_POWN_CHAIN_MAX, ia/arith.h), lane by lane. */
IAV_INLINE iav iav_pown(iav a, int n) {
    if (n == 0)
        return iav_point(1);
    if (n == 1)
        return a;
    if (n == 2)
        return iav_sqr(a);
    if (n < 0 || n > IA_POWN_CHAIN_MAX)
        return iav__pown_by_lane(a, n);
    unsigned int m = (unsigned int)n;
    if ((m & 1) == 0) {
        iav g = iav_abs(a);
        return iav_make(iav__pown_nonneg(g.lo, m, IAV_R(-1)), iav__pown_nonneg(g.hi, m, IAV_R(1)));
    }
    /* a.lo >= 0: round its power down; a.lo < 0: round |a.lo|^n up and negate. Symmetrically for a.hi. */
    ia_realv s_lo = select(IAV_R(-1), IAV_R(1), a.lo < 0), s_hi = select(IAV_R(1), IAV_R(-1), a.hi < 0);
    ia_realv lo = iav__pown_nonneg(fabs(a.lo), m, s_lo), hi = iav__pown_nonneg(fabs(a.hi), m, s_hi);
    return iav_make(select(lo, -lo, a.lo < 0), select(hi, -hi, a.hi < 0));
}


/* ---- points over lanes, for the emitted point code's lanes version (implicits/emit.c: P_f_gradv): ia/'s point
 * functions with the same operations in the same order, so that each lane holds the scalar one's bits. */

/* The scalar call in each lane (A, B: a's and b's), for the built-ins whose vector versions PoCL gets wrong in
 * some lanes: double pow and pown beside lanes holding NaN or infinities (pow(1.30, 1.5) = 0.52 there), float sin,
 * cos and tan beside lanes of large arguments (measured on PoCL 5, LLVM 15; float pow and pown, double sin, cos,
 * and exp, log, atan, sqrt of both were right). */
#define IAV_POINT_LANEWISE(call)                                                                               \
    ia_real as[IA_VW], bs[IA_VW];                                                                              \
    IAV_STORE(a, as);                                                                                          \
    IAV_STORE(b, bs);                                                                                          \
    for (int k = 0; k < IA_VW; k++) {                                                                          \
        ia_real A = as[k], B = bs[k];                                                                          \
        (void)B;                                                                                               \
        as[k] = call;                                                                                          \
    }                                                                                                          \
    return IAV_LOAD(as)
IA_FN ia_realv iav_pow_point(ia_realv a, ia_realv b) { IAV_POINT_LANEWISE(pow(A, B)); }
IA_FN ia_realv iav_tan_point(ia_realv a) {
    ia_realv b = a;
    IAV_POINT_LANEWISE(tan(A));
}
/* ia_exp_point: from ia__exp_double in lanes where the device has double (the same bits), else lane by lane. */
IA_FN ia_realv iav_exp_point(ia_realv a) {
#ifdef IA_DEVICE_DOUBLE
    return iav__to_real(iav__exp_double(a));
#else
    ia_realv b = a;
    IAV_POINT_LANEWISE(ia_exp_point(A));
#endif
}
IAV_INLINE ia_realv iav_pown_by_lane(ia_realv a, int n) {
    ia_realv b = a;
    IAV_POINT_LANEWISE(pown(A, n));
}

/* ia_real_max: NaN where either operand is (fmax would drop it). */
IA_FN ia_realv iav_real_max(ia_realv a, ia_realv b) { return select(fmax(a, b), IAV_R(NAN), isnan(a) | isnan(b)); }

/* ia_pown_point: on a float device with double, the chain in double rounded to nearest once; *done 0 where it
 * does not apply (n = 0, |n| beyond the chain, or no double). */
IAV_INLINE ia_realv iav_pown_point(ia_realv x, int n, int *done) {
#ifdef IA_DEVICE_DOUBLE
    unsigned int m = n < 0 ? 0u - (unsigned int)n : (unsigned int)n;
    *done = m >= 1 && m <= IA_POWN_CHAIN_MAX;
    iav__doublev r = (iav__doublev)1, b = iav__to_double(x);
    for (; *done && m > 0; m >>= 1) {
        if (m & 1)
            r *= b;
        b *= b;
    }
    return iav__to_real(n < 0 ? 1 / r : r);
#else
    (void)n;
    *done = 0;
    return x;
#endif
}

#endif
#endif
