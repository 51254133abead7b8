/* kernels/traverse.h -- the stackless walk over the implicit binary tree of a ray's parameter interval.
 *
 * The root covers [t0, t0 + w]. A node is a level k and an index i in [0, 2^k); its ends are
 *     node_bound(k, i) = t0 + w * (i * 2^-k)     and     node_bound(k, i + 1).
 * i * 2^-k is exact (the index has fewer bits than the mantissa: BISECT_MAX_LEVEL), so every end is a function
 * of one dyadic number u = i * 2^-k, rounded the same way wherever it is computed. A parent's ends are therefore
 * bit-identical to its outer children's ends, and a node's end bit-identical to its right neighbour's start:
 * the leaves tile [t0, t0 + w] with no gap (recomputing hi = lo + width instead leaves one-ulp gaps). And since
 * rounding is monotone in u, the ends never cross.
 *
 * The walk needs no stack: descending goes to (k + 1, 2i); leaving a rejected node goes to (k, i + 1), then up
 * while that is a left child's position, i.e. while i is even. The walk is over when it climbs to the root's end.
 */
#ifndef KERNELS_TRAVERSE_H
#define KERNELS_TRAVERSE_H
#include "compat.h"

#ifdef IA_FP64
typedef kernel_u64 bisect_index;
#define BISECT_MAX_LEVEL 53
#else
typedef kernel_u32 bisect_index;
#define BISECT_MAX_LEVEL 24
#endif

/* 2^-level, exactly, for 0 <= level <= BISECT_MAX_LEVEL: from its exponent bits on the device, where ldexp is
 * a library routine of some twenty instructions (two per evaluation of F, in the bisection's inner loop). */
IA_FN ia_real node_scale(int level) {
#if !IA_DEVICE
    return ldexp((ia_real)1, -level);
#elif defined(IA_FP64)
    return as_double((ulong)(1023 - level) << 52);
#else
    return as_float((uint)(127 - level) << 23);
#endif
}

/* The end point of the dyadic fraction i * 2^-level of [t0, t0 + w] (the product i * 2^-level is exact). */
IA_FN ia_real node_bound(ia_real t0, ia_real w, int level, bisect_index i) {
    return t0 + w * ((ia_real)i * node_scale(level));
}

/* The index j at `level` of the node holding t: it starts at or before t (so the nodes before it end at or
 * before t) and the next one starts after t; the first or the last node when t is outside the root. The
 * estimate is corrected with node_bound itself, so its rounding costs a step or two, never a wrong start. */
IA_FN bisect_index node_at(ia_real t0, ia_real w, int level, ia_real t) {
    bisect_index last = (((bisect_index)1) << level) - 1;
    ia_real u = (t - t0) / w / node_scale(level);
    bisect_index j = u > 0 ? (bisect_index)fmin(u, (ia_real)last) : 0;
    while (j > 0 && node_bound(t0, w, level, j) > t)
        j -= 1;
    while (j < last && node_bound(t0, w, level, j + 1) <= t)
        j += 1;
    return j;
}

/* Moves from a node to the next node in ray order that is not inside it. Returns 0 when there is none. */
IA_FN int node_next(int *level, bisect_index *i) {
    *i += 1;
    while (*level > 0 && (*i & 1) == 0) {
        *i >>= 1;
        *level -= 1;
    }
    return *level > 0;
}

/* The box of the ray o + t*d over the node's t range [lo, hi] (nonempty), outward-rounded: it contains every
 * point of the float ray (the exact value o + t*d, t in [lo, hi]), so a root of f on that ray segment is never
 * excluded. o + t*d is monotone in t, so its extremes are at the ends; fma rounds each end's exact value once
 * (correctly, in OpenCL C as in C11), so one ulp outward encloses it: two widenings instead of the four of
 * ia_add_r(ia_mul_r(t, d), o), and no case analysis (this runs three times per evaluation of F). */
IA_FN ia_interval ray_extent(ia_real o, ia_real d, ia_interval t) {
    ia_real first = d >= 0 ? t.lo : t.hi, last = d >= 0 ? t.hi : t.lo;
    return ia_make(ia_lo(fma(d, first, o)), ia_hi(fma(d, last, o)));
}

/* Whether an interval Newton step along the ray may use D, the enclosure of the derivative along it over a node:
 * D must exclude 0 (f monotone there) and be BOUNDED, both ends finite (NaN is not). The emitted derivative code
 * reports [-inf, +inf] wherever an operation may be undefined on the box, so a bounded D means f is Lipschitz
 * there and the mean value theorem holds; over a pole D may be one-signed but unbounded, and a step would keep
 * the wrong side of it (the proof is at kernels/packet.h's Newton, which tests the same). */
IA_FN int newton_slope_usable(ia_interval d) {
    return isfinite(d.lo) && isfinite(d.hi) && (d.lo > 0 || d.hi < 0);
}

#endif
