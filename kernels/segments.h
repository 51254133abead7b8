/* kernels/segments.h -- the states of one solid along a ray: every root in its box's t range, not only the first,
 * by stackless interval bisection (traverse.h: gap-free node bounds, the ray's outward-rounded extension).
 *
 * A walk visits the nodes of [ta, ta + w] in ray order. A node where the enclosure F of the solid's function
 * over the node's box is < 0 is certainly IN, > 0 certainly OUT (also an empty F: f undefined there); a node
 * holding 0 is split down to leaves of width <= eps, which are BOUNDARY: the solid may be in or out there. The
 * accepted nodes tile the range without gaps, so every point of it gets a decided state; a solid thinner than
 * eps still leaves a BOUNDARY leaf (F over a leaf that holds it holds 0).
 *
 * The walk is resumable: each candidate of a ray keeps its node (level, index) and the start of that node (its
 * position), and segments_step advances it by one accepted node. The weave (scene_trace.h) always steps the
 * candidate whose position is the least, so the state changes of all solids come out in t order without being
 * stored or sorted, and the walks stop at the first claimed partition: a ray that hits the front of a solid never
 * bisects its back, nor the solids behind.
 *
 * Needs scene_solid_F (src/render_scene.c's program, or the host tests' own).
 */
#ifndef KERNELS_SEGMENTS_H
#define KERNELS_SEGMENTS_H
#include "traverse.h"
#include "scene_data.h"

/* A candidate's walk: node (level[c], index[c]) of the tree over [range[2c], range[2c] + range[2c + 1]], whose
 * start is pos[c]; level SEGMENTS_CLOSING when the walk has covered the range and the solid's final OUT at its
 * end is due at pos[c]; pos[c] = +inf when nothing is left. */
typedef struct {
    KERNEL_GLOBAL int *solid;
    KERNEL_GLOBAL ia_real *range; /* start, width */
    KERNEL_GLOBAL ia_real *pos;
    KERNEL_GLOBAL int *level;
    KERNEL_GLOBAL bisect_index *index;
} segments_walks;

#define SEGMENTS_CLOSING (-1)

IA_FN void segments_start(const segments_walks *w, int c) {
    w->level[c] = 0;
    w->index[c] = 0;
    w->pos[c] = w->range[2 * c];
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

/* Advances candidate c's walk by one accepted node: returns the solid's state from pos[c] on (the accepted
 * node's start, or the range's end for the final OUT), and moves pos[c] on. The solid is OUT before the range
 * and after it. Adds the evaluations to *evals. */
IA_FN int segments_step(const segments_walks *w, int c, const ia_real o[3], const ia_real d[3],
                        ia_real eps, ia_real time, kernel_u32 *evals) {
    ia_real ta = w->range[2 * c], width = w->range[2 * c + 1];
    int level = w->level[c];
    if (level == SEGMENTS_CLOSING) {
        w->pos[c] = IA_INF;
        return SCENE_OUT;
    }
    bisect_index i = w->index[c];
    int s;
    for (;;) {
        ia_real lo = node_bound(ta, width, level, i), hi = node_bound(ta, width, level, i + 1);
        ia_interval t = ia_make(lo, hi);
        ia_interval f = scene_solid_F(w->solid[c], ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t),
                                      ray_extent(o[2], d[2], t), ia_point(time));
        *evals += 1;
        s = segments_state(f, hi - lo, eps, level);
        if (s >= 0)
            break;
        level += 1;
        i *= 2;
    }
    if (node_next(&level, &i)) {
        w->pos[c] = node_bound(ta, width, level, i);
    } else if (s != SCENE_OUT) { /* the final OUT at the range's end */
        level = SEGMENTS_CLOSING;
        w->pos[c] = node_bound(ta, width, 0, 1);
    } else {
        w->pos[c] = IA_INF;
    }
    w->level[c] = level;
    w->index[c] = i;
    return s;
}

#endif
