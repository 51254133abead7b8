/* ia/arith.h -- + - * / recip sqr pown sqrt, rounded outward (see ia/round.h). Contract: ia/ia.h. */
#ifndef IA_ARITH_H
#define IA_ARITH_H
#include "interval.h"

/* a + b. Empty if either is empty. Overflow gives an infinite bound on the side it overflows to. */
IA_FN ia_interval ia_add(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b))
        return ia_empty();
    return ia_make(ia_lo(a.lo + b.lo), ia_hi(a.hi + b.hi));
}

/* a - b. Empty if either is empty. */
IA_FN ia_interval ia_sub(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b))
        return ia_empty();
    return ia_make(ia_lo(a.lo - b.hi), ia_hi(a.hi - b.lo));
}

/* a + c for a real c (exact, not a decimal approximation). Empty stays empty. */
IA_FN ia_interval ia_add_r(ia_interval a, ia_real c) {
    if (ia_is_empty(a))
        return a;
    return ia_make(ia_lo(a.lo + c), ia_hi(a.hi + c));
}

/* x * y with 0 * inf = 0: an infinite bound stands for arbitrarily large finite values, and 0 times any of them
 * is 0. The only NaN a product of interval bounds can make is that one. */
IA_FN ia_real ia__mul0(ia_real x, ia_real y) {
    ia_real p = x * y;
    return isnan(p) ? (ia_real)0 : p;
}

/* a * b. Empty if either is empty; [0,0] * entire = [0,0]. */
IA_FN ia_interval ia_mul(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b))
        return ia_empty();
    ia_real p1 = ia__mul0(a.lo, b.lo), p2 = ia__mul0(a.lo, b.hi);
    ia_real p3 = ia__mul0(a.hi, b.lo), p4 = ia__mul0(a.hi, b.hi);
    return ia_make(ia_lo(fmin(fmin(p1, p2), fmin(p3, p4))), ia_hi(fmax(fmax(p1, p2), fmax(p3, p4))));
}

/* a * c for a real c. Empty stays empty; 0 * unbounded = [0,0]. */
IA_FN ia_interval ia_mul_r(ia_interval a, ia_real c) {
    if (ia_is_empty(a))
        return a;
    ia_real p = ia__mul0(a.lo, c), q = ia__mul0(a.hi, c);
    return ia_make(ia_lo(fmin(p, q)), ia_hi(fmax(p, q)));
}

/* a^2, tighter than a * a: [0, ...] when a straddles 0. Empty stays empty. */
IA_FN ia_interval ia_sqr(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    ia_real mig = a.lo > 0 ? a.lo : (a.hi < 0 ? -a.hi : (ia_real)0);
    ia_real mag = fmax(-a.lo, a.hi);
    return ia_make(mig == 0 ? (ia_real)0 : fmax(ia_lo(mig * mig), (ia_real)0), ia_hi(mag * mag));
}

/* 1 / a, set-based (IEEE 1788): 1/[0,0] is empty, 1/[0,h] = [1/h, +inf], a straddling 0 gives entire. */
IA_FN ia_interval ia_recip(ia_interval a) {
    if (ia_is_empty(a) || (a.lo == 0 && a.hi == 0))
        return ia_empty();
    if (a.lo < 0 && a.hi > 0)
        return ia_entire();
    /* 1/(+-0) would be +-inf with the wrong sign for a -0 bound: choose the sign from the side we are on. */
    ia_real lo = a.hi == 0 ? -IA_INF : ia_lo_k((ia_real)1 / a.hi, IA_ULP_DIV);
    ia_real hi = a.lo == 0 ? IA_INF : ia_hi_k((ia_real)1 / a.lo, IA_ULP_DIV);
    return ia_make(lo, hi);
}

/* a / b, set-based: b = [0,0] gives empty; a containing 0 over b containing 0 gives entire; a one-signed
 * over b containing 0 gives the (possibly two-sided, hence entire) hull. */
IA_FN ia_interval ia_div(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b) || (b.lo == 0 && b.hi == 0))
        return ia_empty();
    if (b.lo <= 0 && b.hi >= 0) {
        if (a.lo == 0 && a.hi == 0)
            return ia_make(0, 0);
        /* recip then mul: two roundings, but this branch is rare and its results have an infinite side. */
        ia_interval r = ia_recip(b);
        if (a.lo <= 0 && a.hi >= 0)
            return ia_entire();
        return ia_mul(a, r);
    }
    /* b is one-signed and nonzero: the extremes are among the four corner quotients (inf/inf cannot occur:
     * a bound of b is finite on the side facing 0, and x/inf = 0 is exact). */
    ia_real q1 = a.lo / b.lo, q2 = a.lo / b.hi, q3 = a.hi / b.lo, q4 = a.hi / b.hi;
    q1 = isnan(q1) ? (ia_real)0 : q1; /* inf/inf: only when both bounds are infinite on the far sides */
    q2 = isnan(q2) ? (ia_real)0 : q2;
    q3 = isnan(q3) ? (ia_real)0 : q3;
    q4 = isnan(q4) ? (ia_real)0 : q4;
    return ia_make(ia_lo_k(fmin(fmin(q1, q2), fmin(q3, q4)), IA_ULP_DIV),
                   ia_hi_k(fmax(fmax(q1, q2), fmax(q3, q4)), IA_ULP_DIV));
}

/* sqrt(a) on its domain: a is clipped to [0, +inf); wholly negative (or empty) gives empty. */
IA_FN ia_interval ia_sqrt(ia_interval a) {
    if (ia_is_empty(a) || a.hi < 0)
        return ia_empty();
    ia_real lo = a.lo <= 0 ? (ia_real)0 : fmax(ia_lo_k(sqrt(a.lo), IA_ULP_SQRT), (ia_real)0);
    return ia_make(lo, ia_hi_k(sqrt(a.hi), IA_ULP_SQRT));
}

/* x^n for x >= 0 (possibly +inf) and n >= 1, rounded down (dir < 0) or up (dir > 0) at every step: the
 * factors are nonnegative, so rounding each partial product the same way bounds the exact power. */
IA_FN ia_real ia__pown_nonneg(ia_real x, unsigned int n, int dir) {
    ia_real r = 1, b = x;
    while (1) {
        if (n & 1)
            r = dir < 0 ? fmax(ia_lo(r * b), (ia_real)0) : ia_hi(r * b);
        n >>= 1;
        if (n == 0)
            return r;
        b = dir < 0 ? fmax(ia_lo(b * b), (ia_real)0) : ia_hi(b * b);
    }
}

/* a^m for m >= 1. */
IA_FN ia_interval ia__pown_pos(ia_interval a, unsigned int m) {
    if (m == 1)
        return a;
    if (m == 2)
        return ia_sqr(a);
    if ((m & 1) == 0) {
        ia_interval g = ia_abs(a);
        ia_real lo = g.lo == 0 ? (ia_real)0 : ia__pown_nonneg(g.lo, m, -1);
        return ia_make(lo, ia__pown_nonneg(g.hi, m, 1));
    }
    /* odd: increasing, the sign follows the base */
    ia_real lo = a.lo >= 0 ? ia__pown_nonneg(a.lo, m, -1) : -ia__pown_nonneg(-a.lo, m, 1);
    ia_real hi = a.hi >= 0 ? ia__pown_nonneg(a.hi, m, 1) : -ia__pown_nonneg(-a.hi, m, -1);
    return ia_make(lo, hi);
}

/* a^n for an integer n of either sign (IEEE 1788 pown): a^0 = [1,1] for nonempty a (0^0 = 1); even n over an
 * interval straddling 0 starts at 0; negative n is 1 / a^|n|, so pown([0,0], -n) is empty. */
IA_FN ia_interval ia_pown(ia_interval a, int n) {
    if (ia_is_empty(a))
        return a;
    if (n == 0)
        return ia_point(1);
    if (n > 0)
        return ia__pown_pos(a, (unsigned int)n);
    return ia_recip(ia__pown_pos(a, 0u - (unsigned int)n)); /* 0u - n: no overflow at INT_MIN */
}

#endif
