/* kernels/bisect.h -- the first root of the expression along one ray, by interval bisection (Knoll et al.,
 * Hijazi et al.), without a stack (traverse.h).
 *
 * Needs iacsg_F, the inclusion function of the expression, defined before this header (the emitted source).
 *
 * The walk is over the tree of one root interval [t0, t0 + w] shared by all the rays of a frame (the tile pass,
 * tile.h, walks the same tree), restricted to the ray's part [t_near, t_far] inside the bounds: each node is
 * clipped to it. It starts at a given node: the tile's first coarse leaf, before which the tile pass proved the
 * tile root-free. Starting there, rather than at a root of the ray's own, a ray whose surface lies after that
 * leaf continues at the leaf's level instead of descending again from the top.
 *
 * Guarantee: every node before the returned leaf was proven root-free on [t_near, t_far] (0 not in F over its
 * box, and the box contains the float ray's points), and the clipped nodes tile [t_near, t_far] without gaps.
 * So if the float ray meets the surface there, a leaf is returned, and its start is never after the first root.
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

/* Searches [t_near, t_far] of the ray o + t*d at time `time`, in the tree over [t0, t0 + w], from node
 * (level, i) on (no node before it may hold a root of this ray in [t_near, t_far]), for the first clipped node
 * whose enclosure holds 0 and that is no wider than eps, or at the deepest level. On a hit returns 1 with the
 * clipped node in [*hit_lo, *hit_hi]. *evals counts the evaluations of F (KERNEL_STATS only). */
IA_FN int bisect_first_root(const ia_real o[3], const ia_real d[3], ia_real t0, ia_real w, int level,
                            bisect_index i, ia_real t_near, ia_real t_far, ia_real eps, ia_interval time,
                            ia_real *hit_lo, ia_real *hit_hi, kernel_u32 *evals) {
    do {
        ia_real lo = node_bound(t0, w, level, i);
        if (lo > t_far) /* so is every node after it */
            return 0;
        ia_real a = lo, b = node_bound(t0, w, level, i + 1);
        if (a < t_near || b > t_far) { /* only nodes holding t_near or t_far */
            a = fmax(a, t_near);
            b = fmin(b, t_far);
        }
        if (a <= b) {
            ia_interval t = ia_make(a, b);
            ia_interval f = iacsg_F(ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t),
                                    ray_extent(o[2], d[2], t), time);
            BISECT_COUNT(*evals);
            if (ia_contains_zero(f)) {
                if (b - a <= eps || level == BISECT_MAX_LEVEL) {
                    *hit_lo = a;
                    *hit_hi = b;
                    return 1;
                }
                level += 1; /* descend to the left child */
                i <<= 1;
                continue;
            }
        }
        if (!node_next(&level, &i))
            return 0;
    } while (1);
}

#endif
