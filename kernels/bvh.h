/* kernels/bvh.h -- the candidates of a ray: the solids whose proven boxes it meets, found by a stackless walk
 * of the BVH over the boxes (kernels/scene_data.h: nodes in preorder, each with the node after its subtree), so
 * that a ray costs what it meets, not what the scene holds. Each candidate comes with the t range where the ray
 * is inside its box (camera_clip_box, widened outward: outside it the solid's state is certainly OUT), and the
 * candidates are sorted by that range's start, so that the weave can close every partition before the next
 * entry (kernels/weave.h).
 */
#ifndef KERNELS_BVH_H
#define KERNELS_BVH_H
#include "camera.h"
#include "scene_data.h"

/* Whether the ray meets node k's box on [tn, tf], and where. */
IA_FN int bvh_node_clip(const KERNEL_GLOBAL ia_real *box, int k, const ia_real o[3], const ia_real d[3], ia_real tn,
                        ia_real tf, ia_real *t_near, ia_real *t_far) {
    ia_real lo[3], hi[3];
    for (int c = 0; c < 3; c++) {
        lo[c] = box[6 * k + c];
        hi[c] = box[6 * k + 3 + c];
    }
    return camera_clip_box(lo, hi, o, d, tn, tf, t_near, t_far);
}

/* The candidates of the ray o + t d on [tn, tf]: solid[c] and its range, from range[2c] on for range[2c+1]
 * (rounded up), sorted by range start. Returns their number, or -1 when there are more than cap. */
IA_FN int bvh_candidates(const KERNEL_GLOBAL ia_real *box, const KERNEL_GLOBAL int *link, int nodes,
                         const ia_real o[3], const ia_real d[3], ia_real tn, ia_real tf, KERNEL_GLOBAL int *solid,
                         KERNEL_GLOBAL ia_real *range, int cap) {
    int count = 0, k = 0;
    while (k < nodes) {
        ia_real te, tx;
        if (!bvh_node_clip(box, k, o, d, tn, tf, &te, &tx)) {
            k = link[2 * k + SCENE_BVH_SKIP];
            continue;
        }
        int leaf = link[2 * k + SCENE_BVH_SOLID];
        k += 1;
        if (leaf < 0)
            continue;
        if (count == cap)
            return -1;
        int c = count++; /* insertion by entry: candidates are few */
        while (c > 0 && range[2 * (c - 1)] > te) {
            solid[c] = solid[c - 1];
            range[2 * c] = range[2 * (c - 1)];
            range[2 * c + 1] = range[2 * (c - 1) + 1];
            c -= 1;
        }
        solid[c] = leaf;
        range[2 * c] = te;
        range[2 * c + 1] = ia_hi(tx - te); /* the width of the walk's tree (segments.h) */
    }
    return count;
}

#endif
