/* kernels/scene_trace.h -- one ray of the segment path: its candidates (bvh.h, taken nearest first) and their
 * walks woven in t order (segments.h, weave.h) until a region claims a partition; then the surfaces (surface.h),
 * each asked for its first kept point before that.
 *
 * Guarantee: the claimed partition's start is never after the first point of the ray (in [tn, tf]) where a
 * region is in: every solid's states tile its box's range without gaps, OUT outside it; a partition holding
 * such a point has each solid's state containing its true state there, so the region's three-valued value
 * there may be in. It is at most about eps before it: a partition that may be in but is not has a solid in a
 * BOUNDARY leaf (width <= eps) that the region depends on. With a distance tolerance (weave.h's zones), read "a
 * point where a region is in" as "the start of a stretch longer than the zone where one is in", and the claim may
 * be the zone's length early.
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
    const int *cut;              /* the ray's packet's cut of the BVH (bvh.h's bvh_beam_cut), or 0 */
    int ncut;
    const bvh_cut_lanes *cut_lanes; /* the packet's rays against it, or 0; the ray is lane `lane` of them */
    int lane;
} scene_view;

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
                 ? surface_first_root_from(&v->starts[s], o, d, tn, end, v->eps, solid, cond, r->nodes,
                                           r->walks.prims, v->time, &lo, &hi, &r->evals)
                 : surface_first_root(o, d, tn, end, v->eps, solid, cond, r->nodes, r->walks.prims, v->time, &lo,
                                      &hi, &r->evals)) &&
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

/* Traces the ray o + t d over [tn, tf] (br: its bvh_ray, bvh.h), its regions from `from` on (tn; or where no
 * region can be in before, kernels/scene_union.h, whose walks then start at nodes of eps; +inf where none is
 * in): 1 with *hit, 0 when nothing is hit, SCENE_TRACE_OVERFLOW when the ray meets more boxes than r has room
 * for. Leaves every solid's state OUT. */
IA_FN int scene_trace_ray_from(const scene_view *v, scene_ray *r, const ia_real o[3], const ia_real d[3],
                               const bvh_ray *br, ia_real tn, ia_real from, ia_real tf, weave_hit *hit) {
    bvh_walk b;
    b.box = v->box;
    b.link = v->link;
    b.nodes = v->nodes;
    b.r = br;
    b.o = o;
    b.d = d;
    b.tn = from;
    b.tf = tf;
    b.cut = v->cut;
    b.ncut = v->ncut;
    b.cut_lanes = v->cut_lanes;
    b.lane = v->lane;
    r->deep = from > tn;
    r->deep_from = from;
    r->deep_eps = v->eps;
    r->nstarted = 0;
    int found = from <= tf ? weave_ray(r, &b, v->eps, v->time, hit) : 0;
    for (int c = 0; c < r->nstarted; c++)
        r->state[r->walks.solid[c]] = SCENE_OUT;
    return found < 0 ? SCENE_TRACE_OVERFLOW : scene_trace_surfaces(v, r, o, d, tn, tf, found, hit);
}

IA_FN int scene_trace_ray(const scene_view *v, scene_ray *r, const ia_real o[3], const ia_real d[3], ia_real tn,
                          ia_real tf, weave_hit *hit) {
    bvh_ray br = bvh_ray_of(d);
    return scene_trace_ray_from(v, r, o, d, &br, tn, tn, tf, hit);
}

#endif
