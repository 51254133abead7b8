/* kernels/tile.h -- coarse to fine: before the rays of a TILE_SIZE x TILE_SIZE tile are traced, the tile's
 * lane (PACKET_LANES tiles are searched at once) bisects the t range [TMIN, TMAX] with the box that holds every ray
 * of the tile at once. Where 0 is not in F over that box, no ray of the tile meets the surface, so the tile's rays skip
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

/* A tile's runs (tile_runs) in its camera rays' t, for their transparent layers (kernels/effects.cl). */
typedef struct {
    ia_real lo[TILE_RUNS], hi[TILE_RUNS];
    int n;
} tile_layer_runs;

#if IA_DEVICE && defined(IA_VW) && !defined(IACSG_SCALAR_CODE) /* (as packet.h) */
/* The pixels of tile (tx, ty): columns *i0..*i1, rows *j0..*j1 (the frame's last tiles may be narrower). */
IA_FN void tile_pixels(int tx, int ty, int width, int height, int *i0, int *i1, int *j0, int *j1) {
    *i0 = tx * TILE_SIZE;
    *j0 = ty * TILE_SIZE;
    *i1 = min(*i0 + TILE_SIZE, width) - 1;
    *j1 = min(*j0 + TILE_SIZE, height) - 1;
}

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
        int i0, i1, j0, j1;
        tile_pixels(tx, ty, width, height, &i0, &i1, &j0, &j1);
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

/* Node (level, i) of the frame's tree [t0, t0 + w], [*lo, *hi], over each lane's tile box (base + t dir): in *zero
 * the lanes of `searching` where 0 may be in F over it, and returned those where it is a coarse leaf, no longer
 * than the tile is wide there (splitting t further would not shrink the box much), or eps. Counts the lanes'
 * evaluations (KERNEL_STATS). */
IA_FN ia_maskv tile_node(PACKET_TAPE_PARAM ulong groups, const iav base[3], const iav dir[3], ia_realv spread,
                         int ortho, ia_real t0, ia_real w, ia_real eps, ia_maskv searching, packet_int level,
                         packet_index i, iav time, ia_maskv *zero, ia_realv *lo, ia_realv *hi, packet_index *evals) {
    *lo = packet_node_bound(t0, w, level, i);
    *hi = packet_node_bound(t0, w, level, i + 1);
    iav t = iav_make(*lo, *hi), box[3];
    for (int k = 0; k < 3; k++) /* tile_box */
        box[k] = iav_add(base[k], iav_mul(t, dir[k]));
    iav f = packet_F_live(PACKET_TAPE_ARG groups, searching, box[0], box[1], box[2], time);
    PACKET_COUNT(*evals, searching);
    *zero = searching & iav_contains_zero(f);
    ia_realv footprint = ortho ? spread : spread * *hi;
    return *zero & ((*hi - *lo <= fmax(footprint, IAV_R(eps))) | (level == BISECT_MAX_LEVEL));
}

/* Searches the frame's tree (frame_root) for the first coarse leaf of IA_VW tiles at once, one per lane (as
 * packet.h walks rays): a node where 0 may be in F over the tile's box (tile_node). Returns the lanes of
 * `searching` whose tile may hold surface, with their leaves' levels and indices; *evals counts each lane's
 * evaluations (KERNEL_STATS).
 * base, dir: the lanes' tile_rays; spread: their angular (perspective) or linear (orthographic) sizes. */
IA_FN ia_maskv tile_first_leaves(PACKET_TAPE_PARAM ulong groups, const iav base[3], const iav dir[3],
                                 ia_realv spread, int ortho, ia_real t0, ia_real w, ia_real eps, ia_maskv searching,
                                 iav time,
                                 packet_int *leaf_level, packet_index *leaf_i, packet_index *evals) {
    ia_maskv found = (ia_maskv)0;
    packet_int level = (packet_int)0;
    packet_index i = (packet_index)0;
    while (iav_any(searching)) {
        ia_maskv zero;
        ia_realv lo, hi;
        ia_maskv leaf = tile_node(PACKET_TAPE_ARG groups, base, dir, spread, ortho, t0, w, eps, searching, level, i,
                                  time, &zero, &lo, &hi, evals);
        *leaf_level = select(*leaf_level, level, leaf);
        *leaf_i = select(*leaf_i, i, leaf);
        found |= leaf;
        searching &= ~leaf;
        packet_advance(&searching, zero & ~leaf, &level, &i);
    }
    return found;
}

/* How far the ray of a path's TILE_RUN_LAYERS-th layer may be off its camera ray, in each coordinate: each layer
 * starts off the hit before it (march.h: effects_offset, at most 4 eps + 4e-6 (1 + |p|_1 + t) over the bounds and
 * the frame's t), the hit point and the layer's start t rounded (well under 1e-6 of their size). */
IA_FN ia_real tile_layer_margin(const KERNEL_CONSTANT ia_real *params) {
    ia_real big = 0;
    for (int c = 0; c < 6; c++)
        big = fmax(big, fabs(params[PARAM_BOX + c]));
    ia_real size = 1 + 3 * big + fabs(params[PARAM_TMAX]);
    return TILE_RUN_LAYERS * (4 * params[PARAM_EPS] + (ia_real)5e-6 * size);
}

/* The runs of IA_VW tiles at once, a tile a lane (for the transparent layers of the tile's rays, kernels/effects.cl):
 * the walk of tile_first_leaves from each lane's node (level, i) to the end of the tree, each coarse leaf that may
 * hold surface joined to the run before it where they touch, else the start of the next run (the TILE_RUNS-th run
 * takes every later leaf in, across the gaps). Every part of the tree past the lane's node and outside its runs is
 * proven root-free for every ray in its tile's box. *nruns: the runs of each lane (0: none). */
IA_FN void tile_runs(PACKET_TAPE_PARAM ulong groups, const iav base[3], const iav dir[3], ia_realv spread, int ortho,
                     ia_real t0, ia_real w, ia_real eps, ia_maskv searching, packet_int level, packet_index i,
                     iav time, ia_realv run_lo[TILE_RUNS], ia_realv run_hi[TILE_RUNS], packet_int *nruns,
                     packet_index *evals) {
    packet_int n = (packet_int)0;
    ia_realv last_hi = IAV_R(-IA_INF);
    for (int k = 0; k < TILE_RUNS; k++)
        run_lo[k] = run_hi[k] = IAV_R(0);
    while (iav_any(searching)) {
        ia_maskv zero;
        ia_realv lo, hi;
        ia_maskv leaf = tile_node(PACKET_TAPE_ARG groups, base, dir, spread, ortho, t0, w, eps, searching, level, i,
                                  time, &zero, &lo, &hi, evals);
        if (iav_any(leaf)) {
            /* touching nodes share a bound bit for bit: both are t0 + w (i 2^-level) of the same i 2^-level */
            ia_maskv joins = leaf & ((lo <= last_hi) | (n == TILE_RUNS));
            ia_maskv starts = leaf & ~joins;
            for (int k = 0; k < TILE_RUNS; k++) {
                run_lo[k] = select(run_lo[k], lo, starts & (n == k));
                run_hi[k] = select(run_hi[k], hi, (starts & (n == k)) | (joins & (n == k + 1)));
            }
            n = select(n, n + 1, starts);
            last_hi = select(last_hi, hi, leaf);
        }
        packet_advance(&searching, zero & ~leaf, &level, &i);
    }
    *nruns = n;
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
