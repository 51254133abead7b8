/* kernels/bisect.h -- the first root of the expression along one ray, by interval bisection (Knoll et al.,
 * Hijazi et al.), without a stack (traverse.h).
 *
 * Needs iacsg_F, the inclusion function of the expression, defined before this header (the emitted source).
 *
 * Guarantee: every node before the returned leaf was proven root-free (0 not in F over its box, and the box
 * contains the float ray's points), and the leaves tile [t0, t0 + w] without gaps. So if the float ray meets
 * the surface in [t0, t0 + w], a leaf is returned, and its start is never after the first such root.
 */
#ifndef KERNELS_BISECT_H
#define KERNELS_BISECT_H
#include "traverse.h"

/* Interval evaluations are counted only in a kernel built with -D KERNEL_STATS: the normal kernel pays
 * nothing. */
#ifdef KERNEL_STATS
#define BISECT_COUNT(n) ((n) += 1)
#else
#define BISECT_COUNT(n) ((void)(n))
#endif

/* Searches [t0, t0 + w] of the ray o + t*d at time `time` for the first leaf whose enclosure holds 0: a node no
 * wider than eps, or at the deepest level. On a hit returns 1 with the leaf in [*hit_lo, *hit_hi]. *evals
 * counts the evaluations of F (KERNEL_STATS only). */
IA_FN int bisect_first_root(const ia_real o[3], const ia_real d[3], ia_real t0, ia_real w, ia_real eps,
                            ia_interval time, ia_real *hit_lo, ia_real *hit_hi, kernel_u32 *evals) {
    int level = 0;
    bisect_index i = 0;
    do {
        ia_real lo = node_bound(t0, w, level, i), hi = node_bound(t0, w, level, i + 1);
        ia_interval t = ia_make(lo, hi);
        ia_interval f = iacsg_F(ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t), ray_extent(o[2], d[2], t),
                                time);
        BISECT_COUNT(*evals);
        if (ia_contains_zero(f)) {
            if (hi - lo <= eps || level == BISECT_MAX_LEVEL) {
                *hit_lo = lo;
                *hit_hi = hi;
                return 1;
            }
            level += 1; /* descend to the left child */
            i <<= 1;
        } else if (!node_next(&level, &i)) {
            return 0;
        }
    } while (1);
}

#endif
