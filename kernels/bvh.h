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

/* Component c of a ray's direction, d, and its reciprocal inv = 1 / d. */
IA_FN void bvh_ray_set(bvh_ray *r, int c, ia_real d, ia_real inv) {
    r->inv[c] = inv;
    r->divide |= d != 0 && !isfinite(inv);
}

IA_FN bvh_ray bvh_ray_of(const ia_real d[3]) {
    bvh_ray r;
    r.divide = 0;
    for (int c = 0; c < 3; c++)
        bvh_ray_set(&r, c, d[c], (ia_real)1 / d[c]);
    return r;
}

/* Lane k's ray of a packet's directions d and their reciprocals inv (computed in SIMD lanes, render_scene.cl). */
IA_FN bvh_ray bvh_ray_lane(ia_real d[3][PACKET_LANES], ia_real inv[3][PACKET_LANES], int k) {
    bvh_ray r;
    r.divide = 0;
    for (int c = 0; c < 3; c++)
        bvh_ray_set(&r, c, d[c][k], inv[c][k]);
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

/* ---- a packet's beam: the rays of a packet of pixels together, so that the BVH's top levels, which all of them
 * cross the same way, are tested once a packet, not once a ray (bvh_beam_cut). Per axis the beam holds the hull of
 * the rays' origins and of their reciprocal directions (all of one sign; or all directions 0 there, or no
 * constraint from that axis); a box's slab crossing (plane - o) * inv is monotone in o and in inv separately, so
 * its least and greatest values over the rays come from the hulls' corners (which the signs name), and, widened
 * by two more ulps than a
 * ray's (ia_lo_k is monotone to within an ulp), they hold every ray's widened crossings of bvh_node_clip. So a box
 * some ray of the packet meets is met by the beam: a cut of the beam's boxes holds every box the rays meet. */
#define BVH_BEAM_FREE 0
#define BVH_BEAM_FLAT 1 /* every direction's component is 0: the origins' hull against the slab */
#define BVH_BEAM_SLAB 2
#define BVH_CUT_MAX 12  /* the most entries of a packet's cut (each ray tests each once) */

typedef struct {
    ia_real olo[3], ohi[3], dlo[3], dhi[3], ilo[3], ihi[3], tn, tf;
    int kind[3], rays; /* rays: 0 none added yet; -1 no beam (a ray divides, bvh_ray's `divide`) */
} bvh_beam;

IA_FN void bvh_beam_start(bvh_beam *m) { m->rays = 0; }

/* Adds lane k's ray of a packet (origins o, directions d, their reciprocals inv) over [tn, tf] to the beam. */
IA_FN void bvh_beam_add_lane(bvh_beam *m, ia_real o[3][PACKET_LANES], ia_real d[3][PACKET_LANES],
                             ia_real inv[3][PACKET_LANES], int k, ia_real tn, ia_real tf) {
    if (m->rays < 0)
        return;
    bvh_ray r = bvh_ray_lane(d, inv, k);
    if (r.divide) {
        m->rays = -1;
        return;
    }
    int first = m->rays == 0;
    m->tn = first ? tn : fmin(m->tn, tn);
    m->tf = first ? tf : fmax(m->tf, tf);
    for (int c = 0; c < 3; c++) {
        ia_real oc = o[c][k], dc = d[c][k], ic = inv[c][k];
        int kind = dc == 0 ? BVH_BEAM_FLAT : BVH_BEAM_SLAB;
        int same_sign = first || dc == 0 || (m->ilo[c] > 0) == (ic > 0);
        m->kind[c] = first ? kind : m->kind[c] == kind && same_sign ? kind : BVH_BEAM_FREE;
        m->olo[c] = first ? oc : fmin(m->olo[c], oc);
        m->ohi[c] = first ? oc : fmax(m->ohi[c], oc);
        m->dlo[c] = first ? dc : fmin(m->dlo[c], dc);
        m->dhi[c] = first ? dc : fmax(m->dhi[c], dc);
        m->ilo[c] = first ? ic : fmin(m->ilo[c], ic);
        m->ihi[c] = first ? ic : fmax(m->ihi[c], ic);
    }
    m->rays += 1;
}

/* Whether the beam may meet node k's box over [*tn, *tf] (the beam's range there): 0 only where no ray of it meets
 * the box (bvh_node_clip); each ray's range in the box is then within [*tn, *tf]. */
IA_FN int bvh_beam_range(const bvh_beam *m, const KERNEL_GLOBAL ia_real *box, int k, ia_real *t_near,
                         ia_real *t_far) {
    ia_real tn = m->tn, tf = m->tf;
    for (int c = 0; c < 3; c++) {
        ia_real lo = box[6 * k + c], hi = box[6 * k + 3 + c];
        if (m->kind[c] == BVH_BEAM_FLAT) {
            if (m->ohi[c] < lo || m->olo[c] > hi)
                return 0;
            continue;
        }
        if (m->kind[c] == BVH_BEAM_FREE)
            continue;
        /* one sign of inv: the entry is the crossing of the entry plane (lo where inv > 0), least where
         * plane - o is least (inv > 0) or greatest (inv < 0), times the least inv where that is >= 0, else the
         * greatest; the exit the other way round */
        int up = m->ilo[c] > 0;
        ia_real x = up ? lo - m->ohi[c] : hi - m->olo[c], y = up ? hi - m->olo[c] : lo - m->ohi[c];
        ia_real near = x * (x >= 0 ? m->ilo[c] : m->ihi[c]), far = y * (y >= 0 ? m->ihi[c] : m->ilo[c]);
        tn = fmax(tn, ia_lo_k(near, BVH_SLAB_ULPS + 2));
        tf = fmin(tf, ia_hi_k(far, BVH_SLAB_ULPS + 2));
        if (tn > tf)
            return 0;
    }
    *t_near = tn;
    *t_far = tf;
    return 1;
}

IA_FN int bvh_beam_meets(const bvh_beam *m, const KERNEL_GLOBAL ia_real *box, int k) {
    ia_real tn, tf;
    return bvh_beam_range(m, box, k, &tn, &tf);
}

/* The beam's cut of the BVH into cut[] (returns how many entries, or -1 where there is none to take: no beam, or
 * more top-level nodes than BVH_CUT_MAX): the top-level nodes the beam meets, each inner one replaced by its
 * children that the beam meets while the cut has room, breadth first. Every box a ray of the beam meets is in an
 * entry's subtree, and the boxes on its path from there are met too (a parent's box holds its children's). */
IA_FN int bvh_beam_cut(const bvh_beam *m, const KERNEL_GLOBAL ia_real *box, const KERNEL_GLOBAL int *link, int nodes,
                       int cut[BVH_CUT_MAX]) {
    if (m->rays <= 0)
        return m->rays == 0 ? 0 : -1;
    int n = 0;
    for (int k = 0; k < nodes; k = link[2 * k + SCENE_BVH_SKIP])
        if (bvh_beam_meets(m, box, k)) {
            if (n == BVH_CUT_MAX)
                return -1;
            cut[n++] = k;
        }
    for (int i = 0; i < n;) {
        int k = cut[i];
        if (link[2 * k + SCENE_BVH_SOLID] >= 0) {
            i++;
            continue;
        }
        int left = k + 1, right = link[2 * left + SCENE_BVH_SKIP];
        int in_left = bvh_beam_meets(m, box, left), in_right = bvh_beam_meets(m, box, right);
        if (n - 1 + in_left + in_right > BVH_CUT_MAX) {
            i++;
            continue;
        }
        if (in_left && in_right) {
            cut[i] = left;
            cut[n++] = right;
        } else if (in_left || in_right) {
            cut[i] = in_left ? left : right;
        } else {
            cut[i] = cut[--n];
        }
    }
    return n;
}

/* A packet's rays against the entries of its cut, each lane's range in each entry's box as bvh_node_clip gives it
 * (te > tx where the lane's ray misses the box): the packet's rays test the cut in SIMD lanes, once, not one by
 * one (bvh_cut_lanes_fill). */
typedef struct {
    ia_real te[BVH_CUT_MAX][PACKET_LANES], tx[BVH_CUT_MAX][PACKET_LANES];
} bvh_cut_lanes;

#if IA_DEVICE && defined(IA_VW)
/* bvh_node_clip in each lane: lane k's ray (o, d, reciprocal inv; none divides) clipped from [tn, tf] to node
 * k's box in [*te, *tx], the same operations in the same order; the lanes whose ray misses the box (the parallel
 * ones outside its slab, or *te > *tx). */
IA_FN ia_maskv bvh_node_clip_lanes(const KERNEL_GLOBAL ia_real *box, int k, const ia_realv o[3], const ia_realv d[3],
                                   const ia_realv inv[3], ia_realv tn, ia_realv tf, ia_realv *te, ia_realv *tx) {
    ia_maskv miss = tn != tn; /* (none) */
    *te = tn;
    *tx = tf;
    for (int c = 0; c < 3; c++) {
        ia_realv lo = IAV_R(box[6 * k + c]), hi = IAV_R(box[6 * k + 3 + c]);
        ia_realv a = (lo - o[c]) * inv[c], b = (hi - o[c]) * inv[c];
        ia_maskv along = d[c] == 0;
        miss = miss | (along & ((o[c] < lo) | (o[c] > hi)));
        *te = select(fmax(*te, iav_lo_k(fmin(a, b), BVH_SLAB_ULPS)), *te, along);
        *tx = select(fmin(*tx, iav_hi_k(fmax(a, b), BVH_SLAB_ULPS)), *tx, along);
    }
    return miss | (*te > *tx);
}

/* Every lane's ray (origins o, directions d, reciprocals inv, over [tn, tf]) against the ncut entries of cut
 * (bvh_node_clip_lanes); 0 where a lane's ray divides (bvh_ray's `divide`). */
IA_FN int bvh_cut_lanes_fill(bvh_cut_lanes *cl, const KERNEL_GLOBAL ia_real *box, const int *cut, int ncut,
                             ia_real o[3][PACKET_LANES], ia_real d[3][PACKET_LANES], ia_real inv[3][PACKET_LANES],
                             ia_realv tn, ia_realv tf) {
    ia_realv ov[3], dv[3], iv[3];
    ia_maskv divide = tn != tn; /* (none) */
    for (int c = 0; c < 3; c++) {
        ov[c] = IAV_LOAD(o[c]);
        dv[c] = IAV_LOAD(d[c]);
        iv[c] = IAV_LOAD(inv[c]);
        divide = divide | ((dv[c] != 0) & !isfinite(iv[c]));
    }
    if (iav_any(divide))
        return 0;
    for (int j = 0; j < ncut; j++) {
        ia_realv te, tx;
        ia_maskv miss = bvh_node_clip_lanes(box, cut[j], ov, dv, iv, tn, tf, &te, &tx);
        IAV_STORE(select(te, IAV_R(IA_INF), miss), cl->te[j]);
        IAV_STORE(select(tx, IAV_R(-IA_INF), miss), cl->tx[j]);
    }
    return 1;
}
#endif

/* A ray against the BVH: the tables, the ray and its part [tn, tf] in the bounds; where cut is not 0, its packet's
 * cut (ncut entries, bvh_beam_cut) stands for the top-level nodes, and where cut_lanes is not 0, lane `lane` of it
 * is the ray's range in each of them. */
typedef struct {
    const KERNEL_GLOBAL ia_real *box;
    const KERNEL_GLOBAL int *link;
    int nodes;
    const bvh_ray *r; /* a pointer, not a copy: a copy of what was just stored lane by lane stalls its loads */
    const ia_real *o, *d;
    ia_real tn, tf;
    const int *cut;
    int ncut;
    const bvh_cut_lanes *cut_lanes;
    int lane;
} bvh_walk;

/* Adds node k to the ray's pending entries solid[], range[] (*count of them) if the ray meets its box: a leaf as
 * its solid, an inner node as -(k + 1), with the start and width (rounded up) of the ray's range [te, tx] in the
 * box (bvh_push_range: where the range is known). Returns 0 when there is no room (cap). */
IA_FN int bvh_push_range(const bvh_walk *b, int k, ia_real te, ia_real tx, KERNEL_GLOBAL int *solid,
                         KERNEL_GLOBAL ia_real *range, int *count, int cap) {
    if (*count == cap)
        return 0;
    int leaf = b->link[2 * k + SCENE_BVH_SOLID];
    solid[*count] = leaf >= 0 ? leaf : -(k + 1);
    range[2 * *count] = te;
    range[2 * *count + 1] = ia_hi(tx - te); /* the width of a walk's tree (segments.h) */
    *count += 1;
    return 1;
}
IA_FN int bvh_push(const bvh_walk *b, int k, KERNEL_GLOBAL int *solid, KERNEL_GLOBAL ia_real *range, int *count,
                   int cap) {
    ia_real te, tx;
    return !bvh_node_clip(b->box, k, b->r, b->o, b->d, b->tn, b->tf, &te, &tx) ||
           bvh_push_range(b, k, te, tx, solid, range, count, cap);
}

/* The top-level nodes the ray meets (the unbounded solids' leaves, then the root of the bounded ones), or its
 * packet's cut's entries that it meets (from its lane of the packet's, where the walk has them). */
IA_FN int bvh_roots(const bvh_walk *b, KERNEL_GLOBAL int *solid, KERNEL_GLOBAL ia_real *range, int *count, int cap) {
    if (b->cut) {
        for (int j = 0; j < b->ncut; j++) {
            const bvh_cut_lanes *cl = b->cut_lanes;
            if (cl ? !(cl->te[j][b->lane] > cl->tx[j][b->lane]) &&
                         !bvh_push_range(b, b->cut[j], cl->te[j][b->lane], cl->tx[j][b->lane], solid, range, count,
                                         cap)
                   : !bvh_push(b, b->cut[j], solid, range, count, cap))
                return 0;
        }
        return 1;
    }
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
