/* kernels/scene_trace.h -- one ray of the segment path: its candidates (bvh.h, taken nearest first) and their
 * walks woven in t order (segments.h, weave.h) until a region claims a partition; then the surfaces (surface.h),
 * each asked for its first kept point before that.
 *
 * Guarantee: the claimed partition's start is never after the first point of the ray (in [tn, tf]) where a
 * region is in: every solid's states tile its box's range without gaps, OUT outside it; a partition holding
 * such a point has each solid's state containing its true state there, so the region's three-valued value
 * there may be in. It is at most about eps before it: a partition that may be in but is not has a solid in a
 * BOUNDARY leaf (width <= eps) that the region depends on.
 */
#ifndef KERNELS_SCENE_TRACE_H
#define KERNELS_SCENE_TRACE_H
#include "weave.h"
#include "surface.h"

typedef struct {
    const KERNEL_GLOBAL ia_real *box; /* the BVH (scene_data.h) */
    const KERNEL_GLOBAL int *link;
    int nodes;
    const KERNEL_GLOBAL int *surfaces; /* the items that are surfaces */
    int nsurfaces;
    ia_real eps;
    ia_interval time;            /* encloses the value of t */
    const surface_start *starts; /* the first SURFACE_BLOCK_MAX surfaces' block starts (surface.h), or 0 */
    ia_real from; /* no solid of the BVH is other than OUT before it on the ray (scene_block_start; 0: none known) */
} scene_view;

/* Whether some solid of the BVH may be other than OUT somewhere in the box: its box (scene_data.h: OUT outside
 * it) meets the box and its enclosure there is neither empty nor > 0 (segments_state). Stackless: the BVH is in
 * preorder, a missed node's subtree is skipped by its link. Stops at the first such solid. */
IA_FN int scene_box_may_enter(const scene_view *v, const ia_interval box[3], kernel_u32 *evals) {
    for (int k = 0; k < v->nodes;) {
        int meets = 1;
        for (int c = 0; c < 3; c++)
            meets &= !(box[c].hi < v->box[6 * k + c] || box[c].lo > v->box[6 * k + 3 + c]);
        int solid = v->link[2 * k + SCENE_BVH_SOLID];
        if (meets && solid >= 0) {
            ia_interval f = scene_solid_F(solid, box[0], box[1], box[2], v->time);
            *evals += 1;
            if (f.lo <= f.hi && !(f.lo > 0))
                return 1;
        }
        k = meets ? k + 1 : v->link[2 * k + SCENE_BVH_SKIP];
    }
    return 0;
}

/* Coarse to fine, as surface_block does for a surface: the start of the first node of the frame's tree where
 * some solid of the BVH may be other than OUT for some ray of a block of pixels (tested over the box holding all
 * their rays, tile_rays.h), no longer than the block is wide there or eps; +inf when there is none. Before it,
 * every solid is OUT on every ray of the block (each dropped node's box holds those rays' points there, and the
 * nodes tile the frame's root, which holds every ray's part in the bounds): their weaves start there. */
IA_FN ia_real scene_block_start(const KERNEL_CONSTANT ia_real *p, int ortho, int i0, int i1, int j0, int j1,
                                int width, int height, const scene_view *v, ia_real *node, kernel_u32 *evals) {
    tile_rays rays;
    tile_rays_of(p, ortho, i0, i1, j0, j1, width, height, &rays);
    ia_real spread = fmax(camera_s(p, i1, width) - camera_s(p, i0, width),
                          camera_v(p, j0, height) - camera_v(p, j1, height));
    ia_real t0, w;
    frame_root(p, &t0, &w);
    int level = 0;
    bisect_index i = 0;
    for (;;) {
        ia_real lo = node_bound(t0, w, level, i), hi = node_bound(t0, w, level, i + 1);
        ia_interval box[3];
        tile_box(&rays, ia_make(lo, hi), box);
        if (scene_box_may_enter(v, box, evals)) {
            if (hi - lo <= fmax(ortho ? spread : spread * hi, v->eps) || level == BISECT_MAX_LEVEL) {
                *node = hi - lo;
                return lo;
            }
            level += 1;
            i <<= 1;
        } else if (!node_next(&level, &i)) {
            return IA_INF;
        }
    }
}

#define SCENE_TRACE_OVERFLOW (-1)

/* The surfaces' first kept points in [tn, hit->t] (or tf without a hit): the nearest replaces the hit. */
IA_FN int scene_trace_surfaces(const scene_view *v, scene_ray *r, const ia_real o[3], const ia_real d[3],
                               ia_real tn, ia_real tf, int found, weave_hit *hit) {
    for (int s = 0; s < v->nsurfaces; s++) {
        int item = v->surfaces[s];
        const KERNEL_GLOBAL int *it = r->items + SCENE_ITEM_INTS * item;
        ia_real lo, hi, end = found ? hit->t : tf;
        int solid = it[SCENE_ITEM_SOLID], cond = it[SCENE_ITEM_ROOT];
        if ((v->starts && s < SURFACE_BLOCK_MAX
                 ? surface_first_root_from(&v->starts[s], o, d, tn, end, v->eps, solid, cond, r->nodes, v->time, &lo,
                                           &hi, &r->evals)
                 : surface_first_root(o, d, tn, end, v->eps, solid, cond, r->nodes, v->time, &lo, &hi, &r->evals)) &&
            (!found || lo < hit->t)) {
            found = 1;
            hit->t = lo;
            hit->item = item;
            hit->solid = it[SCENE_ITEM_SOLID];
            hit->overlap = -1;
        }
    }
    return found;
}

/* Traces the ray o + t d over [tn, tf]: 1 with *hit, 0 when nothing is hit, SCENE_TRACE_OVERFLOW when the ray
 * meets more boxes than r has room for. Leaves every solid's state OUT. */
IA_FN int scene_trace_ray(const scene_view *v, scene_ray *r, const ia_real o[3], const ia_real d[3], ia_real tn,
                          ia_real tf, weave_hit *hit) {
    bvh_walk b;
    b.box = v->box;
    b.link = v->link;
    b.nodes = v->nodes;
    b.r = bvh_ray_of(d);
    b.o = o;
    b.d = d;
    b.tn = fmax(tn, v->from);
    b.tf = tf;
    r->nstarted = 0;
    int found = b.tn <= tf ? weave_ray(r, &b, v->eps, v->time, hit) : 0;
    for (int c = 0; c < r->nstarted; c++)
        r->state[r->walks.solid[c]] = SCENE_OUT;
    return found < 0 ? SCENE_TRACE_OVERFLOW : scene_trace_surfaces(v, r, o, d, tn, tf, found, hit);
}

#endif
