/* kernels/bvh.h -- the candidates of a ray: the solids whose proven boxes it meets, found in the BVH over the
 * boxes (kernels/scene_data.h: nodes in preorder, each with the node after its subtree) lazily and nearest
 * first: the ray keeps its pending entries (nodes and solids whose boxes it meets, each with the t range where it
 * is inside the box, widened outward) and the weave (weave.h) expands the pending node that the ray enters first
 * only when it needs what lies there. So a ray costs what it meets before its hit, not what the scene holds.
 * Outside its box's range a solid is certainly OUT.
 */
#ifndef KERNELS_BVH_H
#define KERNELS_BVH_H
#include "camera.h"
#include "scene_data.h"

/* The BVH tests boxes by multiplying with the ray's reciprocal direction instead of dividing by it: (plane - o)
 * * inv has a relative error below 2u + that of inv (u = half an ulp at 1; inv: IA_ULP_DIV ulps, or half an ulp
 * when division is correctly rounded), so below BVH_SLAB_ULPS ulps of the exact crossing, and ia_lo_k / ia_hi_k
 * by that many ulps enclose it. Where 1/d overflows (|d| below the reciprocal of the largest real) the ray
 * falls back to camera_clip_box's division for every box. */
#define BVH_SLAB_ULPS (3 + 2 * IA_ULP_DIV)

typedef struct {
    ia_real inv[3];
    int divide; /* some 1/d is not finite */
} bvh_ray;

IA_FN bvh_ray bvh_ray_of(const ia_real d[3]) {
    bvh_ray r;
    r.divide = 0;
    for (int c = 0; c < 3; c++) {
        r.inv[c] = (ia_real)1 / d[c];
        r.divide |= d[c] != 0 && !isfinite(r.inv[c]);
    }
    return r;
}

/* Whether the ray meets node k's box on [tn, tf], and where (widened outward, as camera_clip_box). Infinite
 * box bounds give infinite crossings, never NaN (d = 0 is tested apart). */
IA_FN int bvh_node_clip(const KERNEL_GLOBAL ia_real *box, int k, const bvh_ray *r, const ia_real o[3],
                        const ia_real d[3], ia_real tn, ia_real tf, ia_real *t_near, ia_real *t_far) {
    ia_real lo[3], hi[3];
    for (int c = 0; c < 3; c++) {
        lo[c] = box[6 * k + c];
        hi[c] = box[6 * k + 3 + c];
    }
    if (r->divide)
        return camera_clip_box(lo, hi, o, d, tn, tf, t_near, t_far);
    for (int c = 0; c < 3; c++) {
        if (d[c] == 0) {
            if (o[c] < lo[c] || o[c] > hi[c])
                return 0;
            continue;
        }
        ia_real a = (lo[c] - o[c]) * r->inv[c], b = (hi[c] - o[c]) * r->inv[c];
        tn = fmax(tn, ia_lo_k(fmin(a, b), BVH_SLAB_ULPS));
        tf = fmin(tf, ia_hi_k(fmax(a, b), BVH_SLAB_ULPS));
        if (tn > tf)
            return 0;
    }
    *t_near = tn;
    *t_far = tf;
    return 1;
}

/* A ray against the BVH: the tables, the ray and its part [tn, tf] in the bounds. */
typedef struct {
    const KERNEL_GLOBAL ia_real *box;
    const KERNEL_GLOBAL int *link;
    int nodes;
    bvh_ray r;
    const ia_real *o, *d;
    ia_real tn, tf;
} bvh_walk;

/* Adds node k to the ray's pending entries solid[], range[] (*count of them) if the ray meets its box: a leaf as
 * its solid, an inner node as -(k + 1), with the start and width (rounded up) of the ray's range in the box.
 * Returns 0 when there is no room (cap). */
IA_FN int bvh_push(const bvh_walk *b, int k, KERNEL_GLOBAL int *solid, KERNEL_GLOBAL ia_real *range, int *count,
                   int cap) {
    ia_real te, tx;
    if (!bvh_node_clip(b->box, k, &b->r, b->o, b->d, b->tn, b->tf, &te, &tx))
        return 1;
    if (*count == cap)
        return 0;
    int leaf = b->link[2 * k + SCENE_BVH_SOLID];
    solid[*count] = leaf >= 0 ? leaf : -(k + 1);
    range[2 * *count] = te;
    range[2 * *count + 1] = ia_hi(tx - te); /* the width of a walk's tree (segments.h) */
    *count += 1;
    return 1;
}

/* The top-level nodes the ray meets (the unbounded solids' leaves, then the root of the bounded ones). */
IA_FN int bvh_roots(const bvh_walk *b, KERNEL_GLOBAL int *solid, KERNEL_GLOBAL ia_real *range, int *count, int cap) {
    for (int k = 0; k < b->nodes; k = b->link[2 * k + SCENE_BVH_SKIP])
        if (!bvh_push(b, k, solid, range, count, cap))
            return 0;
    return 1;
}

/* Replaces the pending inner node at position c by its children that the ray meets (the left child is the next
 * node, the right one follows the left's subtree). Returns 0 when there is no room. */
IA_FN int bvh_expand(const bvh_walk *b, int c, KERNEL_GLOBAL int *solid, KERNEL_GLOBAL ia_real *range, int *count,
                     int cap) {
    int k = -solid[c] - 1, left = k + 1, right = b->link[2 * left + SCENE_BVH_SKIP];
    *count -= 1; /* the last entry takes its place */
    solid[c] = solid[*count];
    range[2 * c] = range[2 * *count];
    range[2 * c + 1] = range[2 * *count + 1];
    return bvh_push(b, left, solid, range, count, cap) && bvh_push(b, right, solid, range, count, cap);
}

#endif
