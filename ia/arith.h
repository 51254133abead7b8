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

/* a + c for a finite real c (exact, not a decimal approximation). Empty stays empty. */
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

/* a * c for a finite real c. Empty stays empty; 0 * unbounded = [0,0]. */
IA_FN ia_interval ia_mul_r(ia_interval a, ia_real c) {
    if (ia_is_empty(a))
        return a;
    if (c == 0) /* exactly, also for an unbounded a */
        return ia_make(0, 0);
    ia_real p = a.lo * c, q = a.hi * c; /* c is finite and nonzero: no 0 * inf, so no NaN to resolve */
    return ia_make(ia_lo(fmin(p, q)), ia_hi(fmax(p, q)));
}

/* a^2, tighter than a * a: [0, ...] when a straddles 0. Empty stays empty. */
IA_FN ia_interval ia_sqr(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    ia_real mig = a.lo > 0 ? a.lo : (a.hi < 0 ? -a.hi : (ia_real)0);
    ia_real mag = fmax(-a.lo, a.hi);
    return ia_make(fmax(ia_lo(mig * mig), (ia_real)0), mag == 0 ? (ia_real)0 : ia_hi(mag * mag));
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

/* a / b, set-based (IEEE 1788 division restricted to one interval): b = [0,0] gives empty; a = [0,0] gives
 * [0,0]; b with 0 strictly inside gives entire (two half-lines, or all of R); b touching 0 at one end gives a
 * half-line, unless a has 0 strictly inside (then entire). */
IA_FN ia_interval ia_div(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b) || (b.lo == 0 && b.hi == 0))
        return ia_empty();
    if (a.lo == 0 && a.hi == 0)
        return ia_make(0, 0);
    if (b.lo < 0 && b.hi > 0)
        return ia_entire();
    if (b.lo == 0 || b.hi == 0) { /* a pole at the zero end of b; a bound of a at 0 gives exactly 0 */
        int a_nonneg = a.lo >= 0, a_nonpos = a.hi <= 0;
        if (!a_nonneg && !a_nonpos)
            return ia_entire();
        if (b.lo == 0) /* b = [0, h], h > 0 */
            return a_nonneg ? ia_make(a.lo == 0 ? (ia_real)0 : ia_lo_k(a.lo / b.hi, IA_ULP_DIV), IA_INF)
                            : ia_make(-IA_INF, a.hi == 0 ? (ia_real)0 : ia_hi_k(a.hi / b.hi, IA_ULP_DIV));
        /* b = [l, 0], l < 0 */
        return a_nonneg ? ia_make(-IA_INF, a.lo == 0 ? (ia_real)0 : ia_hi_k(a.lo / b.lo, IA_ULP_DIV))
                        : ia_make(a.hi == 0 ? (ia_real)0 : ia_lo_k(a.hi / b.lo, IA_ULP_DIV), IA_INF);
    }
    /* b is one-signed and away from 0: the extremes are among the four corner quotients (x/inf = 0 is the
     * limit). A corner inf/inf stands for quotients from 0 to inf of one sign: it counts as 0, and the inf is
     * the corner (inf bound of a) / (finite bound of b), which is always present. */
    ia_real q1 = a.lo / b.lo, q2 = a.lo / b.hi, q3 = a.hi / b.lo, q4 = a.hi / b.hi;
    q1 = isnan(q1) ? (ia_real)0 : q1;
    q2 = isnan(q2) ? (ia_real)0 : q2;
    q3 = isnan(q3) ? (ia_real)0 : q3;
    q4 = isnan(q4) ? (ia_real)0 : q4;
    return ia_make(ia_lo_k(fmin(fmin(q1, q2), fmin(q3, q4)), IA_ULP_DIV),
                   ia_hi_k(fmax(fmax(q1, q2), fmax(q3, q4)), IA_ULP_DIV));
}

/* a / b for a divisor b one-signed away from 0 (b.lo > 0 or b.hi < 0), neither empty: ia_div's result bit for bit
 * (an infinite b is allowed but for an inf / inf corner, which gives NaN here, a NaN that the segments' code
 * rejects), from the two corner quotients that hold its extremes (which a's and b's signs name: with b > 0 the
 * least is a.lo over b.hi where a.lo >= 0, over b.lo where it is negative, and so on), not all four and their six
 * comparisons. Rounding to nearest is monotone, so the chosen rounded quotients are the least and the greatest of
 * the four rounded ones. The closed-form segments (kernels/prim_segments.h) divide by such divisors: a plane's
 * slope along a ray that is not parallel to it, a quadric's leading coefficient and its root's stable denominator. */
IA_FN ia_interval ia_div_one_signed(ia_interval a, ia_interval b) {
    if (a.lo == 0 && a.hi == 0)
        return ia_make(0, 0);
    int positive = b.lo > 0;
    ia_real num_lo = positive ? a.lo : a.hi, num_hi = positive ? a.hi : a.lo;
    ia_real lo = num_lo / (num_lo >= 0 ? b.hi : b.lo), hi = num_hi / (num_hi >= 0 ? b.lo : b.hi);
    return ia_make(ia_lo_k(lo, IA_ULP_DIV), ia_hi_k(hi, IA_ULP_DIV));
}

/* sqrt(a) on its domain: a is clipped to [0, +inf); wholly negative (or empty) gives empty. */
IA_FN ia_interval ia_sqrt(ia_interval a) {
    if (ia_is_empty(a) || a.hi < 0)
        return ia_empty();
    ia_real lo = a.lo <= 0 ? (ia_real)0 : fmax(ia_lo_k(sqrt(a.lo), IA_ULP_SQRT), (ia_real)0);
    return ia_make(lo, ia_hi_k(sqrt(a.hi), IA_ULP_SQRT));
}

/* Above this exponent ia_pown uses the platform's pow instead of square-and-multiply: the chain's rounding
 * errors compound (squaring doubles the relative error so far), to about 2.25 (n-1) ulps, while pow is
 * within IA_ULP_POW ulps, 3 IA_ULP_POW + 3 after widening. On the host, whose pow is within an ulp and
 * cheap, pow is the tighter from n = 5 on. On the device the chain goes on to n = 1024: pow there costs
 * an order of magnitude more (two calls per bound; PoCL's pow made the x^500 pseudo-cube scenes spend 60 %
 * of their time in it), and x^n has condition number n, so an error of about 2n ulps is what two ulps of
 * uncertainty in x cost anyway. */
#if IA_DEVICE
#define IA_POWN_CHAIN_MAX 1024
#else
#define IA_POWN_CHAIN_MAX ((3 * IA_ULP_POW + 3) / 2 + 1)
#endif

/* Up to this exponent the chain runs in the format itself even where the device has double: its two or three
 * products, each rounded outward, are 2.25 (n - 1) + 2 <= 18 steps out (far below what an ulp of uncertainty in x
 * costs, n ulps), and over lanes cost a fraction of ia__pown_double's conversions to double and back (the heart's
 * two cubes, libfive's view at 2048x2048: 88 -> 71 ms). */
#define IA_POWN_FORMAT_MAX 8

#ifdef IA_DEVICE_DOUBLE
/* The float at or below (above) the double b: rounded to nearest, then moved one step out (ia_lo, ia_hi) where
 * that landed on the wrong side. Without branches (select): a branch on the rounding's direction is
 * mispredicted half the time. IA_FAST rounds to nearest. */
IA_FN ia_real ia__float_below(double b) {
    ia_real f = (ia_real)b;
#ifdef IA_FAST
    return f;
#else
    return select(f, ia_lo(f), (int)((double)f > b));
#endif
}
IA_FN ia_real ia__float_above(double b) {
    ia_real f = (ia_real)b;
#ifdef IA_FAST
    return f;
#else
    return select(f, ia_hi(f), (int)((double)f < b));
#endif
}

/* x^n (x > 0, 2 <= n <= 1024) by square-and-multiply in double, rounded to nearest: within 2.25 (n - 1) 2^-53 <
 * 2^-41.8 of x^n relative (the chain's bound, above) where no partial product leaves the normal range, i.e. where
 * the result is within [2^-1000, 2^1000] (the partial powers lie between 1 and x^n). Padded by 2^-38 relative and
 * rounded outward to float (down for dir < 0), the bounds are within a step of the exact power, where the float
 * chain's were 2.25 (n - 1) ulps out, and take half the time: the pseudo-cube's x^500 was half the segment path's
 * render of Fig. 2 as regions. Below 2^-1000 (x^n is then below 2^-1000 (1 + 2^-41), far under the smallest
 * float) the bounds are 0 and the next float up; above 2^1000 (x^n beyond every float, or x = +inf) the largest
 * float and +inf, as the float chain's widening gives. */
IA_FN ia_real ia__pown_double(ia_real x, unsigned int n, int dir) {
    double r = 1, b = x;
    for (;;) {
        if (n & 1)
            r *= b;
        n >>= 1;
        if (n == 0)
            break;
        b *= b;
    }
    if (!(r <= 0x1p1000))
        return dir < 0 ? IA_REAL_MAX : IA_INF;
    if (r < 0x1p-1000)
        return dir < 0 ? (ia_real)0 : ia_hi((ia_real)0);
    return dir < 0 ? fmax(ia__float_below(r - r * 0x1p-38), (ia_real)0) : ia__float_above(r + r * 0x1p-38);
}
#endif

/* x^n at a point, for the emitted point code (iacsg_pown, implicits/emit.c): on a float device with double, the
 * chain of ia__pown_double rounded to nearest once (1 / it for n < 0), so that the value lies in ia_pown's bounds
 * over any interval holding x; n = 0 or |n| beyond the chain, pown. Returns 0 in *done where it does not apply. */
IA_FN ia_real ia_pown_point(ia_real x, int n, int *done) {
#ifdef IA_DEVICE_DOUBLE
    unsigned int m = n < 0 ? 0u - (unsigned int)n : (unsigned int)n;
    *done = m >= 1 && m <= IA_POWN_CHAIN_MAX;
    double r = 1, b = x;
    for (; *done && m > 0; m >>= 1) {
        if (m & 1)
            r *= b;
        b *= b;
    }
    return (ia_real)(n < 0 ? 1 / r : r);
#else
    (void)x, (void)n;
    *done = 0;
    return 0;
#endif
}

/* x^n for x >= 0 (possibly +inf) and n >= 1, rounded down (dir < 0) or up (dir > 0). Square-and-multiply
 * rounds every partial product the same way (the factors are nonnegative, so that bounds the exact power);
 * for large n, pow widened by its error bound, the exponent split in two when the format cannot hold it. */
IA_FN ia_real ia__pown_nonneg(ia_real x, unsigned int n, int dir) {
    ia_real r = 1, b = x;
    if (x == 0)
        return 0;
#ifdef IA_DEVICE_DOUBLE
    if (n > IA_POWN_FORMAT_MAX && n <= IA_POWN_CHAIN_MAX)
        return ia__pown_double(x, n, dir);
#endif
    if (n > IA_POWN_CHAIN_MAX) {
        unsigned int n_hi = n & ~0xffffu, n_lo = n & 0xffffu; /* 16 significant bits each: exact as floats */
        ia_real p = pow(x, (ia_real)n_lo);
        p = n_lo == 0 ? (ia_real)1 : dir < 0 ? fmax(ia_lo_k(p, IA_ULP_POW), (ia_real)0) : ia_hi_k(p, IA_ULP_POW);
        if (n_hi == 0)
            return p;
        ia_real q = pow(x, (ia_real)n_hi);
        q = dir < 0 ? fmax(ia_lo_k(q, IA_ULP_POW), (ia_real)0) : ia_hi_k(q, IA_ULP_POW);
        return dir < 0 ? fmax(ia_lo(ia__mul0(p, q)), (ia_real)0) : ia_hi(ia__mul0(p, q));
    }
    int first = 1; /* the first factor is taken as it is: 1 * b is exact, no rounding to pad */
    while (1) {
        if (n & 1)
            r = first ? b : dir < 0 ? fmax(ia_lo(r * b), (ia_real)0) : ia_hi(r * b);
        first &= !(n & 1);
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
 * interval holding 0 starts at exactly 0; negative n is 1 / a^|n| set-based, so pown([0,0], -n) is empty and
 * odd -n over an interval with 0 inside is entire. Square-and-multiply up to |n| = IA_POWN_CHAIN_MAX, pow
 * above (see there). */
IA_FN ia_interval ia_pown(ia_interval a, int n) {
    if (ia_is_empty(a))
        return a;
    if (n == 0)
        return ia_point(1);
    if (n > 0)
        return ia__pown_pos(a, (unsigned int)n);
    unsigned int m = 0u - (unsigned int)n; /* no overflow at INT_MIN */
    if ((m & 1) == 0)
        a = ia_abs(a); /* x^-m = |x|^-m: one-signed, so that 1/a below is one interval */
    /* 1/a^m and (1/a)^m are both enclosures: the first is tight where a^m is in range, the second where it
     * overflows or is subnormal (1/a^m then only knows "below 1/MAX"). Keep the common part. */
    return ia_intersect(ia_recip(ia__pown_pos(a, m)), ia__pown_pos(ia_recip(a), m));
}

#endif
