/* kernels/surface.h -- the level-set surface stage of the segment path (Hijazi et al. §4.4): along one ray, the
 * first point of a surface solid's zero set that the surface's condition may keep.
 *
 *   surface_condition   a condition (kernels/csg_node.h: INSIDE "f < 0", OUTSIDE "f > 0", and, or, not) over a
 *                       box, three-valued from interval enclosures: may it hold somewhere, may it fail somewhere
 *   surface_walk        bisection of the ray's t range over traverse.h's gap-free nodes, with its outward-rounded
 *                       ray boxes: a node is dropped where F of the surface misses 0 or its condition certainly
 *                       fails; the first node no wider than eps that survives is the hit (surface_first_root:
 *                       over the ray's own range); below a few thousand leaves, interval Newton narrows the root
 *                       of a node where F is monotone, and the walk skips what lies outside it
 *   surface_block       the same test over the box of a block of pixels' rays (tile_rays.h), down to the block's
 *                       width: the rays of the block start their walks there (surface_first_root_from), past what
 *                       it proved empty for all of them at once
 *
 * Guarantee: let p = o + t*d (exact, t in [t_near, t_far]) be a point of the float ray with F(p) = 0 where the
 * condition holds (each compared solid defined at p, with the strict sign). Every node holding t has 0 in its
 * enclosure of F and its condition may hold (inclusion), so it is never dropped, nor is any node holding t over
 * a block's box, which holds the ray's (tile_rays.h), nor where Newton's N (which holds every root of its node)
 * decides without evaluating; the nodes tile [t_near, t_far] in ray order with no gap (traverse.h), so the hit's
 * start is never after t. Conversely the hit's leaf is at
 * most eps wide, F's enclosure holds 0 over it and the condition may hold there: a miss of the surface by
 * less than the enclosures' width, or a point within a leaf of the condition's boundary, may be a hit (as the
 * first-root path may hit a surface it only grazes).
 *
 * Needs the emitted dispatcher over the scene's solids, which takes the scene's table of primitives q
 * (kernels/scene_prims.h; every function here passes it on),
 *     ia_interval scene_solid_F(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t),
 * and, where SCENE_SOLID_FD is defined, scene_solid_Fd (the value and the derivative along a direction), declared
 * before this header (tests/t_render_surface_kernel_fp.c defines its own). The hit is shaded with the
 * surface solid's gradient, turned to face the eye, by the renderer that calls this.
 */
#ifndef KERNELS_SURFACE_H
#define KERNELS_SURFACE_H
#include "csg_node.h"
#include "params.h"
#include "tile_rays.h"
#include "traverse.h"
#include "scene_prims.h"

/* The value of a condition over a box: a set of the truth values it may take there. */
#define SURFACE_MAY_HOLD 1
#define SURFACE_MAY_FAIL 2
#define SURFACE_CERTAIN SURFACE_MAY_HOLD /* holds at every point of the box */

/* A comparison of solid enclosure g with 0: INSIDE holds where g < 0, OUTSIDE where g > 0. An empty enclosure
 * (the solid is undefined throughout the box) holds nowhere. */
IA_FN int surface_compare(int op, ia_interval g) {
    if (ia_is_empty(g))
        return SURFACE_MAY_FAIL;
    int hold = op == CSG_INSIDE ? g.lo < 0 : g.hi > 0, fail = op == CSG_INSIDE ? g.hi >= 0 : g.lo <= 0;
    return (hold ? SURFACE_MAY_HOLD : 0) | (fail ? SURFACE_MAY_FAIL : 0);
}

/* not: a value that may hold may fail to be false, and the other way round. */
IA_FN int surface_not(int v) { return (v & SURFACE_MAY_HOLD) << 1 | (v & SURFACE_MAY_FAIL) >> 1; }

/* The condition at node `root` (last node `last`) of nodes over the box, each leaf's solid enclosed by
 * scene_solid_F. The nodes are visited from the last back to the root, so both children of a node are done
 * before it; the finished subtrees' values wait on a stack of 2-bit entries in one 64-bit word, the left child
 * (visited last) on top. The scene refuses a condition deeper than CSG_STACK_MAX (csg_stack_need). */
IA_FN int surface_condition(const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q, int root, int last,
                            const ia_interval box[3], ia_interval time, kernel_u32 *evals) {
    kernel_u64 stack = 0;
    for (int k = last; k >= root; k--) {
        kernel_u32 node = nodes[k];
        int op = CSG_NODE_OP(node), v;
        if (op == CSG_INSIDE || op == CSG_OUTSIDE) {
            v = surface_compare(op, scene_solid_F(q, (int)CSG_NODE_ARG(node), box[0], box[1], box[2], time));
            *evals += 1;
        } else {
            int left = (int)(stack & 3);
            stack >>= 2;
            if (op == CSG_NOT) {
                v = surface_not(left);
            } else {
                int right = (int)(stack & 3);
                stack >>= 2;
                if (op == CSG_DIFFERENCE) /* left and not right */
                    right = surface_not(right);
                int both = left & right, either = left | right;
                /* or: may hold if either may, may fail only if both may; and: the other way round */
                v = op == CSG_UNION ? (either & SURFACE_MAY_HOLD) | (both & SURFACE_MAY_FAIL)
                                    : (both & SURFACE_MAY_HOLD) | (either & SURFACE_MAY_FAIL);
            }
        }
        stack = stack << 2 | (kernel_u64)v;
    }
    return (int)(stack & 3);
}

/* A surface's verdict on a node over its box, given f, F of the solid over it: whether it may hold a kept point (0
 * in f, and the condition may hold), and, through *proven, whether the condition is certain on it (see
 * surface_walk). */
IA_FN int surface_keeps(ia_interval f, const ia_interval box[3], int level, int *proven, int condition, int last,
                        const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q, ia_interval time, kernel_u32 *evals) {
    *evals += 1;
    if (!ia_contains_zero(f))
        return 0;
    int holds = level > *proven ? SURFACE_CERTAIN : surface_condition(nodes, q, condition, last, box, time, evals);
    if (holds == SURFACE_CERTAIN && level < *proven)
        *proven = level;
    return holds & SURFACE_MAY_HOLD;
}

/* The level below which no node is proven to keep its condition: every node for a surface without one. */
IA_FN int surface_unproven(int condition) { return condition >= 0 ? BISECT_MAX_LEVEL + 1 : -1; }

/* Interval Newton along the ray (where the program has scene_solid_Fd, and not with IA_FAST: unrounded, N can miss its
 * root), as segments.h does: on a node that may keep a point, no wider than SURFACE_NEWTON_LEAVES leaves, whose
 * derivative D along the ray is bounded and excludes 0 (newton_slope_usable), F is monotone and N = m - F(m) / D (m the
 * midpoint) holds its only root there (the mean value theorem). The walk keeps N for the node's subtree: a descendant
 * wholly outside N holds no root and is dropped without evaluating; one that N fills less than half of is split without
 * evaluating. A leaf is always evaluated: a hit is a leaf where F's enclosure holds 0. 4096 rather than segments.h's
 * 256: a surface walk starts at its block's node, a few pixel footprints wide, and Newton from there cut icos.csg's CPU
 * time by a fifth and sesc.csg's by 7 % (16384 did no better, 65536 worse). */
#define SURFACE_NEWTON_LEAVES 4096
#if defined(SCENE_SOLID_FD) && !defined(IA_FAST)
#define SURFACE_NEWTON 1
#endif

/* N of the node at `level` (-1: none) for its subtree. */
typedef struct {
    int level;
    ia_real a, b;
} surface_newton;

#ifdef SURFACE_NEWTON
/* One Newton step on the node [lo, hi] at `level`, given D (`slope`, from scene_solid_Fd over the ray's box there,
 * which also gave the node's F: surface_node): 0 when it holds no root, else 1, with N stored where D excludes 0
 * (intersected with an enclosing node's N: both hold). */
IA_FN int surface_newton_step(surface_newton *n, int level, const ia_real o[3], const ia_real d[3], ia_real lo,
                              ia_real hi, ia_interval slope, scene_prims q, int solid, ia_interval time,
                              kernel_u32 *evals) {
    *evals += 1;
    ia_real m = lo * (ia_real)0.5 + hi * (ia_real)0.5;
    ia_interval at = ia_point(m);
    ia_interval fm = !newton_slope_usable(slope)
                         ? ia_empty()
                         : scene_solid_F(q, solid, ray_extent(o[0], d[0], at), ray_extent(o[1], d[1], at),
                                         ray_extent(o[2], d[2], at), time);
    if (ia_is_empty(fm)) /* D holds 0 or is unbounded, or f is undefined at m: nothing learnt */
        return 1;
    ia_interval step = ia_sub(at, ia_div(fm, slope));
    ia_real a = fmax(lo, step.lo), b = fmin(hi, step.hi);
    if (n->level >= 0) {
        a = fmax(a, n->a);
        b = fmin(b, n->b);
    }
    if (!(a <= b))
        return 0;
    n->level = level;
    n->a = a;
    n->b = b;
    return 1;
}
#endif

/* Whether the walk may keep the node [lo, hi] at `level` (clipped to the ray's part, nonempty). */
IA_FN int surface_node(const ia_real o[3], const ia_real d[3], ia_real lo, ia_real hi, int level, ia_real eps,
                       int *proven, surface_newton *n, int solid, int condition, int last,
                       const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q, ia_interval time, kernel_u32 *evals) {
    int wide = hi - lo > eps && level < BISECT_MAX_LEVEL;
#ifdef SURFACE_NEWTON
    if (n->level >= 0 && level > n->level) { /* inside the node whose N is kept */
        if (hi < n->a || lo > n->b)
            return 0;
        if (wide && n->b - n->a <= (hi - lo) * (ia_real)0.5)
            return 1;
    }
#endif
    ia_interval t = ia_make(lo, hi), box[3];
    for (int k = 0; k < 3; k++)
        box[k] = ray_extent(o[k], d[k], t);
#ifdef SURFACE_NEWTON
    /* where a kept node would take a Newton step, F comes with D from one call (sharing its sines' and cosines'
     * reductions: implicits/emit.c), not from two */
    int newton = wide && hi - lo <= SURFACE_NEWTON_LEAVES * eps;
    ia_interval slope, f = newton ? scene_solid_Fd(q, solid, box[0], box[1], box[2], time, ia_point(d[0]),
                                                   ia_point(d[1]), ia_point(d[2]), &slope)
                                  : scene_solid_F(q, solid, box[0], box[1], box[2], time);
    int keep = surface_keeps(f, box, level, proven, condition, last, nodes, q, time, evals);
    if (keep && newton)
        keep = surface_newton_step(n, level, o, d, lo, hi, slope, q, solid, time, evals);
#else
    (void)n, (void)wide;
    int keep = surface_keeps(scene_solid_F(q, solid, box[0], box[1], box[2], time), box, level, proven, condition, last,
                             nodes, q, time, evals);
#endif
    return keep;
}

/* The first point of solid `solid`'s zero set on the float ray o + t*d, t in [t_near, t_far] (finite), where the
 * condition at node `condition` of nodes (-1: none, the whole zero set) may hold, walking the tree of
 * [t0, t0 + w] from node (level, i) on, each node clipped to [t_near, t_far] (no node before it may hold such a
 * point). Returns 1 with the hit's leaf [*hit_lo, *hit_hi] (at most eps wide, or at the deepest level), 0 when
 * the ray has none. Where a node's condition is certain, its descendants inherit it: `proven` is that node's
 * level, and the walk is inside it while it is deeper (it leaves a node's subtree only by climbing to the node's
 * level or above, traverse.h's node_next); so with a Newton node's N. */
IA_FN int surface_walk(const ia_real o[3], const ia_real d[3], ia_real t0, ia_real w, int level, bisect_index i,
                       ia_real t_near, ia_real t_far, ia_real eps, int solid, int condition,
                       const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q, ia_interval time, ia_real *hit_lo,
                       ia_real *hit_hi, kernel_u32 *evals) {
    int last = condition >= 0 ? csg_tree_last(nodes, condition) : -1, unproven = surface_unproven(condition);
    int proven = unproven;
    surface_newton n = {-1, 0, 0};
    for (;;) {
        ia_real start = node_bound(t0, w, level, i);
        if (start > t_far) /* so is every later node */
            return 0;
        ia_real lo = fmax(start, t_near), hi = fmin(node_bound(t0, w, level, i + 1), t_far);
        /* (a node that ends before t_near is not kept) */
        int keep = lo <= hi &&
                   surface_node(o, d, lo, hi, level, eps, &proven, &n, solid, condition, last, nodes, q, time, evals);
        if (keep && (hi - lo <= eps || level == BISECT_MAX_LEVEL)) {
            *hit_lo = lo;
            *hit_hi = hi;
            return 1;
        }
        if (keep) {
            level += 1;
            i <<= 1;
        } else {
            if (!node_next(&level, &i))
                return 0;
            if (level <= proven)
                proven = unproven;
            if (level <= n.level)
                n.level = -1;
        }
    }
}

/* surface_walk over the ray's own tree, [t_near, t_near + w] with w the width rounded up. */
IA_FN int surface_first_root(const ia_real o[3], const ia_real d[3], ia_real t_near, ia_real t_far, ia_real eps,
                             int solid, int condition, const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q,
                             ia_interval time, ia_real *hit_lo, ia_real *hit_hi, kernel_u32 *evals) {
    if (!(t_near <= t_far))
        return 0;
    return surface_walk(o, d, t_near, ia_hi(t_far - t_near), 0, 0, t_near, t_far, eps, solid, condition, nodes, q, time,
                        hit_lo, hit_hi, evals);
}

/* Coarse to fine, as kernels/tile.h does for the first-root path: the first node of the frame's tree
 * [t0, t0 + w] that may keep a point of the surface for some ray of a block of pixels, tested over the box that
 * holds all their rays (tile_rays), and no longer than the block is wide there (splitting t further would not
 * shrink the box much: `spread` is the block's angular size, or its linear size when orthographic) or eps.
 * Returns 0 when there is none (no ray of the block can hit the surface), else 1 with the node. */
IA_FN int surface_block_start(const tile_rays *r, ia_real spread, int ortho, ia_real t0, ia_real w, ia_real eps,
                              int solid, int condition, const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q,
                              ia_interval time, int *level, bisect_index *i, kernel_u32 *evals) {
    int last = condition >= 0 ? csg_tree_last(nodes, condition) : -1, unproven = surface_unproven(condition);
    int proven = unproven;
    *level = 0;
    *i = 0;
    for (;;) {
        ia_real lo = node_bound(t0, w, *level, *i), hi = node_bound(t0, w, *level, *i + 1);
        ia_interval box[3];
        tile_box(r, ia_make(lo, hi), box);
        if (surface_keeps(scene_solid_F(q, solid, box[0], box[1], box[2], time), box, *level, &proven, condition, last,
                          nodes, q, time, evals)) {
            if (hi - lo <= fmax(ortho ? spread : spread * hi, eps) || *level == BISECT_MAX_LEVEL)
                return 1;
            *level += 1;
            *i <<= 1;
        } else {
            if (!node_next(level, i))
                return 0;
            if (*level <= proven)
                proven = unproven;
        }
    }
}

/* Where the rays of a block of pixels start their walks for one surface: the frame's tree, and its node (level
 * -1: no ray of the block can hit the surface). */
typedef struct {
    ia_real t0, w;
    int level;
    bisect_index i;
} surface_start;

/* The surfaces of a scene that get a block pass; the others are walked ray by ray from the top. */
#define SURFACE_BLOCK_MAX 8

/* The start of the rays of pixels i0..i1 x j0..j1 (in the image) of the frame of parameter block p. */
IA_FN void surface_block(const KERNEL_CONSTANT ia_real *p, int ortho, int i0, int i1, int j0, int j1, int width,
                         int height, int solid, int condition, const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q,
                         ia_interval time, surface_start *start, kernel_u32 *evals) {
    tile_rays rays;
    tile_rays_of(p, ortho, i0, i1, j0, j1, width, height, &rays);
    ia_real spread =
        fmax(camera_s(p, i1, width) - camera_s(p, i0, width), camera_v(p, j0, height) - camera_v(p, j1, height));
    frame_root(p, &start->t0, &start->w);
    if (!surface_block_start(&rays, spread, ortho, start->t0, start->w, p[PARAM_EPS], solid, condition, nodes, q, time,
                             &start->level, &start->i, evals))
        start->level = -1;
}

/* surface_walk for one ray of the block, on its part [t_near, t_far] inside the frame's root. */
IA_FN int surface_first_root_from(const surface_start *start, const ia_real o[3], const ia_real d[3], ia_real t_near,
                                  ia_real t_far, ia_real eps, int solid, int condition,
                                  const KERNEL_GLOBAL kernel_u32 *nodes, scene_prims q, ia_interval time,
                                  ia_real *hit_lo, ia_real *hit_hi, kernel_u32 *evals) {
    if (start->level < 0 || !(t_near <= t_far))
        return 0;
    bisect_index i = node_at(start->t0, start->w, start->level, t_near);
    return surface_walk(o, d, start->t0, start->w, start->level, i > start->i ? i : start->i, t_near, t_far, eps, solid,
                        condition, nodes, q, time, hit_lo, hit_hi, evals);
}

#endif
