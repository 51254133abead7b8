/* kernels/tile.h -- coarse to fine: before the rays of a TILE_SIZE x TILE_SIZE tile are traced, the tile's
 * lane (16 tiles are searched at once) bisects the t range [TMIN, TMAX] with the box that holds every ray of the
 * tile at once. Where 0 is not in F over that box, no ray of the tile meets the surface, so the tile's rays skip
 * it; a tile with no candidate at all is background without tracing a single ray. The rays start their walks of
 * the same tree at the first surviving coarse leaf (kernels/packet.h, render.cl). For a union emitted in groups,
 * the pass also finds which groups can matter in the tile, per segment of the tree (tile_groups).
 *
 * The tile's rays as one box-valued ray, and the frame's tree: tile_rays.h.
 *
 * Needs iacsg_Fv (the emitted source).
 */
#ifndef KERNELS_TILE_H
#define KERNELS_TILE_H
#include "packet.h"
#include "tile_rays.h"

#if IA_DEVICE && defined(IA_VW) && !defined(IACSG_SCALAR_CODE) /* (as packet.h) */
/* The PACKET_W x PACKET_H tiles from (tx0, ty0) in SIMD lanes, a tile a lane: their rays as boxes (tile_rays_of)
 * in base and dir, and their angular (perspective) or linear (orthographic) sizes in *spread; valid[k] is 1 where
 * lane k's tile is in the frame, else 0 (such a lane gets its edge tile's finite box, and should search nothing). */
IA_FN void tile_block_lanes(__constant ia_real *params, int ortho, int width, int height, int tx0, int ty0,
                            iav base[3], iav dir[3], ia_realv *spread, ia_real valid[IA_VW]) {
    int tiles_x = (width + TILE_SIZE - 1) / TILE_SIZE, tiles_y = (height + TILE_SIZE - 1) / TILE_SIZE;
    ia_real lo[2][3][IA_VW], hi[2][3][IA_VW], size[IA_VW];
    for (int k = 0; k < IA_VW; k++) {
        int tx = tx0 + k % PACKET_W, ty = ty0 + k / PACKET_W;
        valid[k] = tx < tiles_x && ty < tiles_y;
        tx = min(tx, tiles_x - 1);
        ty = min(ty, tiles_y - 1);
        int i0 = tx * TILE_SIZE, j0 = ty * TILE_SIZE;
        int i1 = min(i0 + TILE_SIZE, width) - 1, j1 = min(j0 + TILE_SIZE, height) - 1;
        tile_rays rays;
        tile_rays_of(params, ortho, i0, i1, j0, j1, width, height, &rays);
        for (int c = 0; c < 3; c++) {
            lo[0][c][k] = rays.base[c].lo;
            hi[0][c][k] = rays.base[c].hi;
            lo[1][c][k] = rays.dir[c].lo;
            hi[1][c][k] = rays.dir[c].hi;
        }
        size[k] = fmax(camera_s(params, i1, width) - camera_s(params, i0, width),
                       camera_v(params, j0, height) - camera_v(params, j1, height));
    }
    for (int c = 0; c < 3; c++) {
        base[c] = iav_make(IAV_LOAD(lo[0][c]), IAV_LOAD(hi[0][c]));
        dir[c] = iav_make(IAV_LOAD(lo[1][c]), IAV_LOAD(hi[1][c]));
    }
    *spread = IAV_LOAD(size);
}

/* Searches the frame's tree (frame_root) for the first coarse leaf of IA_VW tiles at once, one per lane (as
 * packet.h walks rays): a node where 0 may be in F over the tile's box, no longer than the tile is wide there
 * (splitting t further would not shrink the box much), or eps. Returns the lanes of `searching` whose tile may
 * hold surface, with their leaves' levels and indices; *evals counts each lane's evaluations (KERNEL_STATS).
 * base, dir: the lanes' tile_rays; spread: their angular (perspective) or linear (orthographic) sizes. */
IA_FN ia_maskv tile_first_leaves(PACKET_TAPE_PARAM ulong groups, const iav base[3], const iav dir[3],
                                 ia_realv spread, int ortho, ia_real t0, ia_real w, ia_real eps, ia_maskv searching,
                                 iav time,
                                 packet_int *leaf_level, packet_index *leaf_i, packet_index *evals) {
    ia_maskv found = (ia_maskv)0;
    packet_int level = (packet_int)0;
    packet_index i = (packet_index)0;
    while (iav_any(searching)) {
        ia_realv lo = packet_node_bound(t0, w, level, i), hi = packet_node_bound(t0, w, level, i + 1);
        iav t = iav_make(lo, hi), box[3];
        for (int k = 0; k < 3; k++) /* tile_box */
            box[k] = iav_add(base[k], iav_mul(t, dir[k]));
        iav f = packet_F_live(PACKET_TAPE_ARG groups, searching, box[0], box[1], box[2], time);
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
IA_FN void tile_groups(PACKET_TAPE_PARAM const iav base[3], const iav dir[3], iav t, iav time, ulong among,
                       ulong groups[IA_VW]) {
#ifdef IACSG_GROUPS
    iav box[3];
    for (int k = 0; k < 3; k++) /* tile_box */
        box[k] = iav_add(base[k], iav_mul(t, dir[k]));
    for (int k = 0; k < IA_VW; k++)
        groups[k] = 0;
#ifdef IACSG_TAPE
    ia_real hull[6]; /* for the tape's skipping of parts, once for all the groups */
    tape_hull((ia_maskv)-1, box[0], box[1], box[2], hull);
#endif
    for (int g = 0; g < IACSG_GROUPS; g++) {
        if (!(among >> g & 1))
            continue;
        ia_real lo[IA_VW];
#ifdef IACSG_TAPE
        IAV_STORE(tape_group(tape, g, hull, (ia_maskv)-1, box[0], box[1], box[2], time).lo, lo);
#else
        IAV_STORE(iacsg_Fv_group(g, box[0], box[1], box[2], time).lo, lo);
#endif
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
