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
 * A BRL-CAD primitive with a closed form (prim_segments.h; a pipe's in a scene with SCENE_SOLID_PIPES, without a
 * bore) walks by it instead: its first step
 * solves it along the ray, and the walk then moves through its four changes (segments_closed_step), solving again
 * after them where a torus or a general tgc may be in again; where the closed form cannot decide (a ray along a
 * cone's side line) it bisects.
 *
 * Needs scene_solid_F (src/render_scene.c's program, or the host tests' own), and with SCENE_SOLID_PRIMS (a scene
 * with primitives) scene_solid_P: a solid's primitive type and parameters (kernels/scene_prims.h), each from the
 * scene's table of primitives, which the walks keep (prims).
 */
#ifndef KERNELS_SEGMENTS_H
#define KERNELS_SEGMENTS_H
#include "traverse.h"
#include "scene_data.h"
#include "scene_prims.h"
#include "prim_segments.h"
#include "segments_lanes_frame.h"
#if !IA_DEVICE
#include <string.h>
#endif

/* A candidate's walk: node (level[c], index[c]) of the tree over [range[2c], range[2c] + range[2c + 1]], whose
 * start is pos[c]; level SEGMENTS_CLOSING when the walk has covered the range and the solid's final OUT at its
 * end is due at pos[c]; pos[c] = +inf when nothing is left. A closed-form walk has level SEGMENTS_CLOSED and keeps
 * its four changes (prim_segments) in range[2c], range[2c + 1], newton_t[2c], newton_t[2c + 1]. */
typedef struct {
    KERNEL_GLOBAL int *solid;
    KERNEL_GLOBAL ia_real *range; /* start, width */
    KERNEL_GLOBAL ia_real *pos;
    KERNEL_GLOBAL int *level;
    KERNEL_GLOBAL bisect_index *index;
    KERNEL_GLOBAL int *newton;       /* -1, or level << 2 | state before the root (see segments_newton) */
    KERNEL_GLOBAL ia_real *newton_t; /* the interval N holding the roots of that node */
    prim_dirs *dirs; /* the solids' direction terms where every ray has the same direction (prim_segments.h), or 0 */
    segments_lanes *lanes; /* with dirs, the packet's planar solids solved in lanes (segments_lanes.h), or 0 */
    scene_prims prims;     /* the scene's primitives (kernels/scene_prims.h), for the solids' dispatchers */
} segments_walks;

#define SEGMENTS_CLOSING (-1)
#define SEGMENTS_CLOSED (-2)

#ifdef SCENE_SOLID_PRIMS
/* A real kept in a closed-form walk's node index (which it does not use): the point it solves again from. */
IA_FN bisect_index segments_bits_of(ia_real x) {
#if IA_DEVICE && defined(IA_FP64)
    return as_ulong(x);
#elif IA_DEVICE
    return as_uint(x);
#else
    bisect_index b;
    memcpy(&b, &x, sizeof b);
    return b;
#endif
}
IA_FN ia_real segments_real_of(bisect_index b) {
#if IA_DEVICE && defined(IA_FP64)
    return as_double(b);
#elif IA_DEVICE
    return as_float(b);
#else
    ia_real x;
    memcpy(&x, &b, sizeof x);
    return x;
#endif
}

/* Room for a solid's parameters: a pipe's where the scene has pipes (SCENE_SOLID_PIPES, up to
 * PRIM_PIPE_SEGMENTS_PARTS parts; a longer one bisects), else an arb8's. */
#ifdef SCENE_SOLID_PIPES
#define SEGMENTS_PARAM_REALS PRIM_PIPE_SEGMENTS_REALS
#else
#define SEGMENTS_PARAM_REALS PRIM_SEGMENTS_REALS
#endif

/* Keeps a solve's result r (prim_segments) with its changes e and the point to solve again from in candidate c's
 * walk; returns whether there is one (r > 0). */
IA_FN int segments_closed_keep(const segments_walks *w, int c, int r, const ia_real e[4], ia_real resume) {
    if (r == 0)
        return 0;
    w->level[c] = SEGMENTS_CLOSED;
    w->newton[c] = r == 2;
    w->index[c] = segments_bits_of(resume);
    w->range[2 * c] = e[0];
    w->range[2 * c + 1] = e[1];
    w->newton_t[2 * c] = e[2];
    w->newton_t[2 * c + 1] = e[3];
    return 1;
}

/* Solves candidate c's solid in closed form over [ta, tend] where it has one, keeping the changes (and where it may
 * be in again after them, newton[c] = 1 and in index[c] the point to solve again from, to the end); 0 when it must
 * bisect. A packet's planar solid, ell, quadric tgc or ehy is solved for all its rays at once where its walks have
 * the lanes. */
IA_FN int segments_closed_solve(const segments_walks *w, int c, const ia_real o[3], const ia_real d[3], ia_real ta,
                                ia_real tend, ia_real eps, kernel_u32 *evals) {
    ia_real p[SEGMENTS_PARAM_REALS], e[4], resume = tend;
    int k = w->solid[c], r;
#ifdef SEGMENTS_LANES
    r = w->lanes && segments_lanes_holds(w->lanes, k) ? segments_lanes_changes(w->lanes, k, ta, tend, e, evals) : -1;
    if (r >= 0)
        return segments_closed_keep(w, c, r, e, resume);
#endif
    int type = scene_solid_P(w->prims, k, p, SEGMENTS_PARAM_REALS), slot = k % PRIM_DIRS_SLOTS;
    int kept = w->dirs && (type == PRIM_HALF || type == PRIM_ARB8 || type == PRIM_ELL || type == PRIM_TGC ||
                           type == PRIM_EHY || type == PRIM_TOR); /* the types with direction terms */
    int known = kept && w->dirs->solid[slot] == k;
#ifdef SEGMENTS_LANES
    if (w->lanes && kept && segments_lanes_fits(type) && !segments_lanes_holds(w->lanes, k)) {
        segments_lanes_fill_solid(w->lanes, k, type, p, d, w->dirs->v[slot], known);
        w->dirs->solid[slot] = k;
        known = 1;
        r = segments_lanes_changes(w->lanes, k, ta, tend, e, evals);
        if (r >= 0)
            return segments_closed_keep(w, c, r, e, resume);
    }
#endif
    r = type < 0 ? 0
                 : prim_segments(type, p, o, d, ta, tend, eps, e, &resume, evals, kept ? w->dirs->v[slot] : 0, known);
    if (kept)
        w->dirs->solid[slot] = k;
    return segments_closed_keep(w, c, r, e, resume);
}

/* Whether solid k is proven out along every ray of a packet's beam (o and d: the hulls of its origins and
 * directions) over [ta, tend] (prim_segments_beam_out); 0 where not proven. */
IA_FN int segments_beam_out(scene_prims q, int k, const ia_interval o[3], const ia_interval d[3], ia_real ta,
                            ia_real tend) {
    ia_real p[SEGMENTS_PARAM_REALS];
    int type = scene_solid_P(q, k, p, SEGMENTS_PARAM_REALS);
    return type >= 0 && prim_segments_beam_out(type, p, o, d, ta, tend);
}

/* A closed-form walk's change j (segments_closed_keep), read alone: a pair read back just after the keep's scalar
 * stores waits for them to retire (a store-forwarding stall, 3.5 % of scene_packet on operators). */
IA_FN ia_real segments_closed_change(const segments_walks *w, int c, int j) {
    return j < 2 ? w->range[2 * c + j] : w->newton_t[2 * c + j - 2];
}

/* A closed-form walk's step: the state from pos[c] on, after the changes at or before it (OUT, BOUNDARY, IN,
 * BOUNDARY, OUT), and pos[c] on to the next change. Past the last change of a solid that may be in again, OUT up
 * to the point to solve again from, and there it solves again, to the end of the solid's own bounding sphere
 * (beyond the BVH's range: the solid is OUT there, and the closed form says so); where that fails, which finite
 * coefficients never do, the rest is BOUNDARY. */
IA_FN int segments_closed_step(const segments_walks *w, int c, const ia_real o[3], const ia_real d[3], ia_real eps,
                               kernel_u32 *evals) {
    for (int pass = 0;; pass++) {
        int j = 0;
        while (j < 4 && segments_closed_change(w, c, j) <= w->pos[c])
            j++;
        if (j == 4 && w->newton[c] == 1) {
            ia_real resume = segments_real_of(w->index[c]);
            if (w->pos[c] < resume) {
                w->pos[c] = resume;
                return SCENE_OUT;
            }
            if (pass == 0 && segments_closed_solve(w, c, o, d, resume, IA_INF, eps, evals))
                continue; /* a solve moves on by one state at least */
            w->newton[c] = 0;
            w->pos[c] = IA_INF;
            return SCENE_BOUNDARY;
        }
        w->pos[c] = j < 4 ? segments_closed_change(w, c, j) : IA_INF;
        return j == 2 ? SCENE_IN : j & 1 ? SCENE_BOUNDARY : SCENE_OUT;
    }
}
#endif

/* Starts candidate c's walk at the first node of `level` (0: the range's root). Any level tiles the range: the
 * walk climbs from a deep first node as node_next leaves it (kernels/scene_union.h starts at nodes of eps). */
IA_FN void segments_start_at(const segments_walks *w, int c, int level) {
    w->level[c] = level;
    w->index[c] = 0;
    w->pos[c] = w->range[2 * c];
    w->newton[c] = -1;
}

IA_FN void segments_start(const segments_walks *w, int c) { segments_start_at(w, c, 0); }

/* The first level whose nodes are no wider than eps over a range of that width (at most the deepest). */
IA_FN int segments_leaf_level(ia_real width, ia_real eps) {
    int level = 0;
    while (level < BISECT_MAX_LEVEL && width * node_scale(level) > eps)
        level += 1;
    return level;
}

/* Interval Newton along the ray (where the program has scene_solid_Fd, and not with IA_FAST: unrounded, N can miss its
 * root). On a node [lo, hi] that holds 0, no wider than SEGMENTS_NEWTON_LEAVES leaves, whose derivative along the ray D
 * is bounded and excludes 0 (newton_slope_usable: never across a pole): f is monotone there, and N = m - F(m) / D (m
 * the midpoint) holds every root in the node (the mean value theorem). The walk keeps N for the node's subtree: a
 * descendant wholly before N has the state f has before the root (IN where D > 0, f rising through 0; else OUT), one
 * wholly after it the other, both without evaluating F; only nodes over N are split, and once N is under half of a
 * node's width the walk splits without evaluating, while wider ones narrow N by another step. Returns the node's state
 * when N misses it (no root: f's sign at m), else -1 with N stored, or -1 and nothing stored where D is not usable. */
#define SEGMENTS_NEWTON_LEAVES 256
#if defined(SCENE_SOLID_FD) && !defined(IA_FAST)
IA_FN int segments_newton(const segments_walks *w, int c, const ia_real o[3], const ia_real d[3], ia_real lo,
                          ia_real hi, int level, ia_interval time, kernel_u32 *evals) {
    ia_interval t = ia_make(lo, hi), slope;
    scene_solid_Fd(w->prims, w->solid[c], ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t),
                   ray_extent(o[2], d[2], t), time, ia_point(d[0]), ia_point(d[1]), ia_point(d[2]), &slope);
    *evals += 1;
    if (!newton_slope_usable(slope))
        return -1;
    ia_real m = lo * (ia_real)0.5 + hi * (ia_real)0.5;
    ia_interval at = ia_point(m);
    ia_interval fm = scene_solid_F(w->prims, w->solid[c], ray_extent(o[0], d[0], at), ray_extent(o[1], d[1], at),
                                   ray_extent(o[2], d[2], at), time);
    *evals += 1;
    ia_interval n = ia_sub(at, ia_div(fm, slope));
    ia_real a = fmax(lo, n.lo), b = fmin(hi, n.hi);
    if (w->newton[c] >= 0) { /* within an earlier N's node: both hold */
        a = fmax(a, w->newton_t[2 * c]);
        b = fmin(b, w->newton_t[2 * c + 1]);
    }
    if (!(a <= b)) /* no root in the node: f keeps the sign it has at m */
        return fm.hi < 0 ? SCENE_IN : fm.lo > 0 ? SCENE_OUT : -1;
    w->newton[c] = level << 2 | (slope.lo > 0 ? SCENE_IN : SCENE_OUT);
    w->newton_t[2 * c] = a;
    w->newton_t[2 * c + 1] = b;
    return -1;
}
#endif

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
                        ia_real eps, ia_interval time, kernel_u32 *evals) {
    ia_real ta = w->range[2 * c], width = w->range[2 * c + 1];
    int level = w->level[c];
    if (level == SEGMENTS_CLOSING) {
        w->pos[c] = IA_INF;
        return SCENE_OUT;
    }
#ifdef SCENE_SOLID_PRIMS
    if (level == SEGMENTS_CLOSED || (level == 0 && w->index[c] == 0 &&
                                     segments_closed_solve(w, c, o, d, ta, node_bound(ta, width, 0, 1), eps, evals)))
        return segments_closed_step(w, c, o, d, eps, evals);
#endif
    bisect_index i = w->index[c];
    int s;
    for (;;) {
        ia_real lo = node_bound(ta, width, level, i), hi = node_bound(ta, width, level, i + 1);
        int newton = w->newton[c];
        if (newton >= 0) { /* inside the subtree of a node with N */
            ia_real a = w->newton_t[2 * c], b = w->newton_t[2 * c + 1];
            int before = newton & 3;
            if (hi < a || lo > b) {
                s = hi < a ? before : SCENE_IN + SCENE_OUT - before;
                break;
            }
            if (b - a <= (hi - lo) * (ia_real)0.5 && hi - lo > eps && level < BISECT_MAX_LEVEL) {
                level += 1;
                i *= 2;
                continue;
            }
        }
        ia_interval t = ia_make(lo, hi);
        ia_interval f = scene_solid_F(w->prims, w->solid[c], ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t),
                                      ray_extent(o[2], d[2], t), time);
        *evals += 1;
        s = segments_state(f, hi - lo, eps, level);
#if defined(SCENE_SOLID_FD) && !defined(IA_FAST)
        if (s < 0 && hi - lo <= SEGMENTS_NEWTON_LEAVES * eps)
            s = segments_newton(w, c, o, d, lo, hi, level, time, evals);
#endif
        if (s >= 0)
            break;
        level += 1;
        i *= 2;
    }
    if (node_next(&level, &i)) {
        w->pos[c] = node_bound(ta, width, level, i);
        if (level <= w->newton[c] >> 2) /* out of the subtree where N holds */
            w->newton[c] = -1;
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
