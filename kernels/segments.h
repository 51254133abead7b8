/* kernels/segments.h -- the states of one solid along a ray: every root in its box's t range, not only the first,
 * by stackless interval bisection (traverse.h: gap-free node bounds, the ray's outward-rounded extension).
 *
 * The walk visits the nodes of [ta, ta + w] in ray order. A node where the enclosure F of the solid's function
 * over the node's box is < 0 is certainly IN, > 0 certainly OUT (also an empty F: f undefined there); a node
 * holding 0 is split down to leaves of width <= eps, which are BOUNDARY: the solid may be in or out there.
 * Each change of state is a break (scene_data.h), inserted into the ray's breaks sorted by t. The nodes tile the
 * range without gaps, so every point of the range is covered by a decided state; a solid thinner than eps still
 * leaves a BOUNDARY leaf (F over a leaf that holds it holds 0).
 *
 * Needs scene_solid_F (src/render_scene.c's program, or the host tests' own).
 */
#ifndef KERNELS_SEGMENTS_H
#define KERNELS_SEGMENTS_H
#include "traverse.h"
#include "scene_data.h"

/* Inserts a break (t, info) among the *count sorted ones, after those with t' <= t. Returns 0 when full. */
IA_FN int segments_insert(KERNEL_GLOBAL ia_real *break_t, KERNEL_GLOBAL int *break_info, int *count, int cap,
                          ia_real t, int info) {
    if (*count == cap)
        return 0;
    int k = (*count)++;
    while (k > 0 && break_t[k - 1] > t) {
        break_t[k] = break_t[k - 1];
        break_info[k] = break_info[k - 1];
        k -= 1;
    }
    break_t[k] = t;
    break_info[k] = info;
    return 1;
}

/* The state of a node from the enclosure over its box, or -1 to split it. */
IA_FN int segments_state(ia_interval f, ia_real width, ia_real eps, int level) {
    if (!(f.lo <= f.hi))
        return SCENE_OUT; /* empty: f is defined nowhere in the box */
    if (f.hi < 0)
        return SCENE_IN;
    if (f.lo > 0)
        return SCENE_OUT;
    return width <= eps || level == BISECT_MAX_LEVEL ? SCENE_BOUNDARY : -1;
}

/* The breaks of solid k (candidate slot `slot`) along the ray o + t d over [ta, tb], where it starts OUT
 * (outside its box, or before the ray's part in the bounds, which nothing sees) and ends OUT. Adds the
 * evaluations to *evals and the solid's segments (runs of IN or BOUNDARY) to *segments. Returns 0 when the
 * breaks overflow cap. */
IA_FN int segments_of_solid(int k, int slot, const ia_real o[3], const ia_real d[3], ia_real ta, ia_real tb,
                            ia_real eps, ia_real time, KERNEL_GLOBAL ia_real *break_t, KERNEL_GLOBAL int *break_info,
                            int *count, int cap, kernel_u32 *evals, kernel_u32 *segments) {
    ia_real w = ia_hi(tb - ta);
    int level = 0, state = SCENE_OUT;
    bisect_index i = 0;
    for (;;) {
        ia_real lo = node_bound(ta, w, level, i), hi = node_bound(ta, w, level, i + 1);
        ia_interval t = ia_make(lo, hi);
        ia_interval f = scene_solid_F(k, ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t),
                                      ray_extent(o[2], d[2], t), ia_point(time));
        *evals += 1;
        int s = segments_state(f, hi - lo, eps, level);
        if (s < 0) {
            level += 1;
            i *= 2;
            continue;
        }
        if (s != state) {
            if (!segments_insert(break_t, break_info, count, cap, lo, SCENE_BREAK(slot, s)))
                return 0;
            *segments += state == SCENE_OUT;
            state = s;
        }
        if (!node_next(&level, &i))
            break;
    }
    return state == SCENE_OUT ||
           segments_insert(break_t, break_info, count, cap, node_bound(ta, w, 0, 1), SCENE_BREAK(slot, SCENE_OUT));
}

#endif
