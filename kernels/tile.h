/* kernels/tile.h -- coarse to fine: before the rays of a TILE_SIZE x TILE_SIZE tile are traced, the tile's
 * lane (16 tiles are searched at once) bisects the t range [TMIN, TMAX] with the box that holds every ray of the
 * tile at once. Where 0 is not in F over that box, no ray of the tile meets the surface, so the tile's rays skip
 * it; a tile with no candidate at all is background without tracing a single ray. The rays start their walks of
 * the same tree at the first surviving coarse leaf (kernels/packet.h, render.cl). For a union emitted in groups,
 * the pass also finds which groups can matter in the tile, per segment of the tree (tile_groups).
 *
 * Rigor: tile_box mirrors every rounded operation of camera_ray with the interval operation that encloses its
 * rounded result (an outward-rounded op contains the round-to-nearest one; / and sqrt, where the device does
 * not round them correctly, widened by their error bound: camera.h), so each pixel's float ray is inside the
 * box, and ray_extent's argument applies to it.
 *
 * Needs iacsg_Fv (the emitted source).
 */
#ifndef KERNELS_TILE_H
#define KERNELS_TILE_H
#include "packet.h"
#include "camera.h"

/* The float rays of columns i0..i1 and rows j0..j1 as one box-valued ray: every point o + t*d of them, t in
 * T, lies in base + T * dir. Perspective: base is the eye and dir the box of the unit directions; orthographic:
 * base is the box of the origins and dir the one direction. Computed once per tile; the search then costs one
 * multiplication and one addition per axis and node. */
typedef struct {
    ia_interval base[3], dir[3];
} tile_rays;

IA_FN void tile_rays_of(const KERNEL_CONSTANT ia_real *p, int ortho, int i0, int i1, int j0, int j1, int width,
                        int height, tile_rays *r) {
    ia_interval s = camera_s_range(p, i0, i1, width), v = camera_v_range(p, j0, j1, height);
    for (int k = 0; k < 3; k++) {
        ia_interval offset = ia_add(ia_mul_r(s, p[PARAM_RIGHT + k]), ia_mul_r(v, p[PARAM_UP + k]));
        r->base[k] = ortho ? ia_add_r(offset, p[PARAM_EYE + k]) : ia_point(p[PARAM_EYE + k]);
        r->dir[k] = ortho ? ia_point(p[PARAM_FORWARD + k]) : ia_add_r(offset, p[PARAM_FORWARD + k]);
    }
    if (ortho)
        return;
    ia_interval len = ia_sqrt(ia_add(ia_add(ia_sqr(r->dir[0]), ia_sqr(r->dir[1])), ia_sqr(r->dir[2])));
    len = camera_as_rounded(len, CAMERA_ULP_SQRT);
    for (int k = 0; k < 3; k++)
        r->dir[k] = camera_as_rounded(ia_div(r->dir[k], len), CAMERA_ULP_DIV);
}

/* The box holding the points o + t*d, t in T, of the tile's float rays. */
IA_FN void tile_box(const tile_rays *r, ia_interval t, ia_interval box[3]) {
    for (int k = 0; k < 3; k++)
        box[k] = ia_add(r->base[k], ia_mul(t, r->dir[k]));
}

/* The root interval [*t0, *t0 + *w] of the bisection tree that the tile pass and every ray of the frame walk:
 * it holds every ray's part inside the bounds (PARAM_TMIN, PARAM_TMAX). */
IA_FN void frame_root(const KERNEL_CONSTANT ia_real *p, ia_real *t0, ia_real *w) {
    *t0 = p[PARAM_TMIN];
    *w = ia_hi(p[PARAM_TMAX] - p[PARAM_TMIN]);
}

#if IA_DEVICE && defined(IA_VW)
/* Searches the frame's tree (frame_root) for the first coarse leaf of IA_VW tiles at once, one per lane (as
 * packet.h walks rays): a node where 0 may be in F over the tile's box, no longer than the tile is wide there
 * (splitting t further would not shrink the box much), or eps. Returns the lanes of `searching` whose tile may
 * hold surface, with their leaves' levels and indices; *evals counts each lane's evaluations (KERNEL_STATS).
 * base, dir: the lanes' tile_rays; spread: their angular (perspective) or linear (orthographic) sizes. */
IA_FN ia_maskv tile_first_leaves(ulong groups, const iav base[3], const iav dir[3], ia_realv spread, int ortho,
                                 ia_real t0, ia_real w, ia_real eps, ia_maskv searching, iav time,
                                 packet_int *leaf_level, packet_index *leaf_i, packet_index *evals) {
    ia_maskv found = (ia_maskv)0;
    packet_int level = (packet_int)0;
    packet_index i = (packet_index)0;
    while (iav_any(searching)) {
        ia_realv lo = packet_node_bound(t0, w, level, i), hi = packet_node_bound(t0, w, level, i + 1);
        iav t = iav_make(lo, hi), box[3];
        for (int k = 0; k < 3; k++) /* tile_box */
            box[k] = iav_add(base[k], iav_mul(t, dir[k]));
        iav f = packet_F(groups, box[0], box[1], box[2], time);
        PACKET_COUNT(*evals, searching);
        ia_maskv zero = searching & iav_contains_zero(f);
        ia_realv footprint = ortho ? spread : spread * hi;
        ia_maskv leaf = zero & ((hi - lo <= fmax(footprint, IAV_R(eps))) | (level == BISECT_MAX_LEVEL));
        *leaf_level = select(*leaf_level, level, leaf);
        *leaf_i = select(*leaf_i, i, leaf);
        found |= leaf;
        searching &= ~leaf;
        packet_advance(&searching, zero & ~leaf, &level, &i);
    }
    return found;
}

/* Of the groups of a union set in `among`, those that are not certainly positive in each lane's tile over
 * [t.lo, t.hi] (bit g of groups[lane] for group g): the others cannot change where the union is zero in the
 * boxes that the tile's rays evaluate on that part of the tree (packet_F). All ones for an expression without
 * groups. */
IA_FN void tile_groups(const iav base[3], const iav dir[3], iav t, iav time, ulong among, ulong groups[IA_VW]) {
#ifdef IACSG_GROUPS
    iav box[3];
    for (int k = 0; k < 3; k++) /* tile_box */
        box[k] = iav_add(base[k], iav_mul(t, dir[k]));
    for (int k = 0; k < IA_VW; k++)
        groups[k] = 0;
    for (int g = 0; g < IACSG_GROUPS; g++) {
        if (!(among >> g & 1))
            continue;
        ia_real lo[IA_VW];
        IAV_STORE(iacsg_Fv_group(g, box[0], box[1], box[2], time).lo, lo);
        for (int k = 0; k < IA_VW; k++)
            groups[k] |= (ulong)!(lo[k] > 0) << g;
    }
#else
    (void)base, (void)dir, (void)t, (void)time, (void)among;
    for (int k = 0; k < IA_VW; k++)
        groups[k] = ~(ulong)0;
#endif
}
#endif

#endif
