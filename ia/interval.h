/* ia/interval.h -- the interval type, constructors, queries and the exact operations (no rounding involved).
 * The contract for all of ia/ is stated in ia/ia.h. */
#ifndef IA_INTERVAL_H
#define IA_INTERVAL_H
#include "round.h"

/* A closed interval [lo, hi] of reals. Empty is [+inf, -inf]; every other value has lo <= hi, lo < +inf and
 * hi > -inf. Infinite bounds mean "unbounded": [-inf, +inf] is the whole real line. */
typedef struct {
    ia_real lo, hi;
} ia_interval;

IA_FN ia_interval ia_make(ia_real lo, ia_real hi) {
    ia_interval r;
    r.lo = lo;
    r.hi = hi;
    return r;
}
IA_FN ia_interval ia_point(ia_real x) { return ia_make(x, x); }
IA_FN ia_interval ia_empty(void) { return ia_make(IA_INF, -IA_INF); }
IA_FN ia_interval ia_entire(void) { return ia_make(-IA_INF, IA_INF); }

/* ---- queries. Each is a guarantee about every point of the interval, hence vacuously true on empty. */
IA_FN IA_BOOL ia_is_empty(ia_interval a) { return !(a.lo <= a.hi); }
IA_FN IA_BOOL ia_is_entire(ia_interval a) { return a.lo == -IA_INF && a.hi == IA_INF; }
/* Every point is < 0 (the point is certainly inside the solid). */
IA_FN IA_BOOL ia_certainly_neg(ia_interval a) { return a.hi < 0 || ia_is_empty(a); }
/* Every point is > 0 (certainly outside). */
IA_FN IA_BOOL ia_certainly_pos(ia_interval a) { return a.lo > 0 || ia_is_empty(a); }
/* 0 may be a value: the only case in which a surface can pass through the box. False on empty. */
IA_FN IA_BOOL ia_contains_zero(ia_interval a) { return a.lo <= 0 && a.hi >= 0; }
IA_FN IA_BOOL ia_contains(ia_interval a, ia_real x) { return a.lo <= x && x <= a.hi; }

/* Width hi - lo rounded up (exact when the difference is a float); +inf for unbounded, 0 for empty (so
 * bisection never splits an empty). */
IA_FN ia_real ia_width(ia_interval a) {
    if (ia_is_empty(a))
        return 0;
    ia_real w = a.hi - a.lo;
#ifndef IA_FTZ /* (flushing could make an inexact difference look exact) */
    /* Fast2Sum: with |big| >= |small|, small - (w - big) is exactly the rounding error of big + small */
    int hi_big = fabs(a.hi) >= fabs(a.lo);
    ia_real big = hi_big ? a.hi : -a.lo, small = hi_big ? -a.lo : a.hi;
    if (small - (w - big) == 0)
        return w;
#endif
    return ia_hi(w);
}

/* A point of the interval near its centre, as IEEE 1788 mid: 0 for entire, +-MAX for half-unbounded,
 * NaN for empty. The halves are summed so that [-MAX, MAX] does not overflow. */
IA_FN ia_real ia_mid(ia_interval a) {
    if (ia_is_empty(a))
        return (ia_real)NAN;
    if (a.lo == -IA_INF)
        return a.hi == IA_INF ? (ia_real)0 : -IA_REAL_MAX;
    if (a.hi == IA_INF)
        return IA_REAL_MAX;
    ia_real m = a.lo * (ia_real)0.5 + a.hi * (ia_real)0.5;
    return fmin(fmax(m, a.lo), a.hi); /* halving subnormals can round outside */
}

/* ---- exact operations: their bounds are bounds of the inputs, so no widening. */

/* -a. Empty stays empty. */
IA_FN ia_interval ia_neg(ia_interval a) { return ia_make(-a.hi, -a.lo); }

/* |a|: [mig, mag], a zero lower bound always +0. Empty stays empty. */
IA_FN ia_interval ia_abs(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    if (a.lo >= 0)
        return ia_make(a.lo + (ia_real)0, a.hi); /* + 0 turns -0 into +0 */
    if (a.hi <= 0)
        return ia_make(-a.hi + (ia_real)0, -a.lo);
    return ia_make(0, fmax(-a.lo, a.hi));
}

/* min and max of intervals (IEEE 1788): with an empty operand the result is empty. The CSG union of operands
 * that may be undefined is ia_union (below). */
IA_FN ia_interval ia_min(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b))
        return ia_empty();
    return ia_make(fmin(a.lo, b.lo), fmin(a.hi, b.hi));
}
IA_FN ia_interval ia_max(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b))
        return ia_empty();
    return ia_make(fmax(a.lo, b.lo), fmax(a.hi, b.hi));
}

/* An enclosure a of a value that may be undefined somewhere on the box (`undefined`: the flag the emitted code
 * carries, ia/ia.h), read as a solid reads it, undefined counting as +inf (outside): [a.lo, +inf]. Empty (undefined
 * everywhere) stays empty. */
IA_FN ia_interval ia_or_outside(ia_interval a, int undefined) {
    return undefined && !ia_is_empty(a) ? ia_make(a.lo, IA_INF) : a;
}

/* The CSG union of a and b, min under the rule of ia/ia.h for undefined operands, given their flags: an operand
 * undefined everywhere (empty) leaves the other; one undefined somewhere enters the min through ia_or_outside,
 * so the result holds the other operand's values where it is undefined. */
IA_FN ia_interval ia_union(ia_interval a, int a_undefined, ia_interval b, int b_undefined) {
    if (ia_is_empty(a))
        return b;
    if (ia_is_empty(b))
        return a;
    return ia_min(ia_or_outside(a, a_undefined), ia_or_outside(b, b_undefined));
}

/* max of two point values, undefined (NaN) where either is: the point code's max (C's fmax would drop a NaN,
 * which is min's rule, not max's; see ia/ia.h). */
IA_FN ia_real ia_real_max(ia_real a, ia_real b) { return isnan(a) || isnan(b) ? (ia_real)NAN : fmax(a, b); }

/* The smallest interval containing both; empty is the identity. */
IA_FN ia_interval ia_hull(ia_interval a, ia_interval b) {
    if (ia_is_empty(a))
        return b;
    if (ia_is_empty(b))
        return a;
    return ia_make(fmin(a.lo, b.lo), fmax(a.hi, b.hi));
}

/* Enclosures of the derivatives of |a|, min(a, b) and max(a, b) from enclosures da, db of the operands'
 * derivatives, a and b being the operands' enclosures over the same box (the interval derivative code of
 * implicits/ops.def, for interval Newton). Where the box does not decide which side holds, the hull of both:
 * Clarke's generalized derivative, for which the mean value theorem Newton relies on still holds. */
IA_FN ia_interval ia_dabs(ia_interval a, ia_interval da) {
    return a.lo > 0 ? da : a.hi < 0 ? ia_neg(da) : ia_hull(da, ia_neg(da));
}
IA_FN ia_interval ia_dmin(ia_interval a, ia_interval b, ia_interval da, ia_interval db) {
    return a.hi < b.lo ? da : b.hi < a.lo ? db : ia_hull(da, db);
}
IA_FN ia_interval ia_dmax(ia_interval a, ia_interval b, ia_interval da, ia_interval db) {
    return a.lo > b.hi ? da : b.lo > a.hi ? db : ia_hull(da, db);
}

/* The common part; empty when they are disjoint. */
IA_FN ia_interval ia_intersect(ia_interval a, ia_interval b) {
    ia_interval r = ia_make(fmax(a.lo, b.lo), fmin(a.hi, b.hi));
    return ia_is_empty(r) ? ia_empty() : r;
}

#endif
