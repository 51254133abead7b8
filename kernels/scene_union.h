/* kernels/scene_union.h -- the segment path's pre-pass over the union of its regions, where the program has it
 * (SCENE_REGIONS_UNION: implicits/scene_emit.c emits g, the regions as one expression, in lanes, for scenes of at
 * most 8 solids and regions whose solids are defined everywhere). As in the first-root path (render.cl): the
 * tile pass over a block's PACKET_LANES tiles of 8x8 pixels in SIMD lanes (tile.h, scene_union_tiles), then each
 * packet's rays search g's first root in lanes from their tile's leaf (packet.h's bisection and Newton,
 * scene_union_packet), and each ray's weave (scene_trace.h) starts at its leaf instead of where it enters the
 * bounds. Where no two regions can be in at one point (SCENE_REGIONS_DISJOINT), the leaf's partition is claimed
 * without weaving (scene_union_claim): each solid's state over the leaf, and the regions' classification there.
 *
 * Why: the weave's walks run one solid of one ray at a time, and down to the first region boundary each bisects
 * its solid's range from the top; Fig. 2 as regions took 2.5x the render of its one expression. From the leaf,
 * each walk starts at a node no wider than eps (segments_start_at), a step or two from the boundary. The tile
 * pass in lanes replaced a scalar block pass per 4x4 packet (a quarter of Fig. 2's render); the claim at the
 * leaf, the weave with its BVH and its look for an overlap past the claim (BENCHMARKS.md, tests/bench/NOTES.md).
 *
 * Guarantee: a region is in at a point only where g <= 0 (scene_emit.c). g is continuous (its solids are
 * defined everywhere); the nodes before the leaf tile [t_near, leaf) without gaps and none holds 0 in its
 * enclosure of g (proven over the tile's box of rays, tile.h, or the ray's own boxes, packet.h), so g keeps one
 * sign there; where g > 0 at t_near (its enclosure at the point), no region is in before the leaf's start, and
 * none at all on a ray without a leaf. Where g may be <= 0 at t_near (the ray may start inside a region) the ray
 * is woven from t_near as without the pre-pass. "g > 0 at t_near" comes from the tile pass where t_near is before
 * the tile's leaf and g > 0 over the tile's box at t0 (scene_union_tiles), else from g's enclosure at the point.
 * The claim at the leaf is the weave's claim of a partition that starts there: states over the leaf's box,
 * BOUNDARY where F holds 0 (the leaf is no wider than eps).
 */
#ifndef KERNELS_SCENE_UNION_H
#define KERNELS_SCENE_UNION_H

/* A tile's result of the union's tile pass: where its rays start their search (level -1: none of them meets a zero
 * of g), whether g > 0 on all its rays' points before that start (above), and the pass's evaluations for it. */
typedef struct {
    surface_start start;
    int above;
    kernel_u32 evals;
} scene_tile;

#if defined(SCENE_REGIONS_UNION) && !defined(IACSG_GROUPS)
#define SCENE_UNION_PREPASS 1
#include "tile.h"

/* g's enclosure at each lane's point o + t d (as the rays' tile pass and weave read t: exactly). */
static iav scene_union_g_at(const ia_realv o[3], const ia_realv d[3], ia_realv t, iav time) {
    iav at = iav_make(t, t);
    return iacsg_Fv(packet_extent(o[0], d[0], at), packet_extent(o[1], d[1], at), packet_extent(o[2], d[2], at), time);
}

/* The union's tile pass (tile.h, as render.cl's) over the PACKET_W x PACKET_H tiles from (tx0, ty0), searched in
 * SIMD lanes: tiles[k] tile k's first coarse leaf in the frame's tree, and whether g > 0 before it (g over the
 * tile's box at t0: the nodes before the leaf tile [t0, leaf) and none holds 0 over the tile's box, so g has no
 * zero on the tile's rays' points there, a connected set on which g, continuous, keeps one sign; for a tile
 * without a leaf, all along its rays). */
static void scene_union_tiles(__constant ia_real *params, int flags, int width, int height, int tx0, int ty0,
                              scene_tile tiles[PACKET_LANES]) {
    int ortho = flags & RENDER_ORTHO;
    iav base_v[3], dir_v[3];
    ia_real valid[IA_VW];
    ia_realv spread;
    tile_block_lanes(params, ortho, width, height, tx0, ty0, base_v, dir_v, &spread, valid);
    ia_real t0, w;
    frame_root(params, &t0, &w);
    packet_int level = (packet_int)0;
    packet_index leaf = (packet_index)0, counts = (packet_index)0;
    iav time = iav_const(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    ia_maskv found = tile_first_leaves(~(ulong)0, base_v, dir_v, spread, ortho, t0, w, params[PARAM_EPS],
                                       IAV_LOAD(valid) != 0, time, &level, &leaf, &counts);
    iav at = iav_make(IAV_R(t0), IAV_R(t0)), box[3];
    for (int c = 0; c < 3; c++)
        box[c] = iav_add(base_v[c], iav_mul(at, dir_v[c]));
    ia_maskv searched = IAV_LOAD(valid) != 0;
    ia_maskv above_v = searched & (iacsg_Fv(box[0], box[1], box[2], time).lo > 0);
    PACKET_COUNT(counts, searched);
    ia_real level_r[IA_VW], leaf_r[IA_VW], above[IA_VW];
    bisect_index count[IA_VW];
    IAV_STORE(select(IAV_R(0), IAV_R(1), above_v), above);
    IAV_STORE(select((ia_realv)-1, packet_to_real(level), found), level_r);
    IAV_STORE(packet_to_real(leaf), leaf_r);
    IAV_STORE(counts, count);
    for (int k = 0; k < IA_VW; k++) {
        tiles[k].start.t0 = t0;
        tiles[k].start.w = w;
        tiles[k].start.level = (int)level_r[k];
        tiles[k].start.i = (bisect_index)leaf_r[k];
        tiles[k].above = above[k] != 0;
        tiles[k].evals = (kernel_u32)count[k];
    }
}

#ifdef SCENE_REGIONS_DISJOINT
/* Each solid's state over the leaf [lo, hi] of g of each lane of `hit` (OUT where F > 0 or is empty, IN where
 * F < 0, else BOUNDARY: the leaf is no wider than eps), in lanes (scene_solid_Fv), for scene_union_claim; the other
 * lanes' states are kept. */
static void scene_union_states(const ia_realv o[3], const ia_realv d[3], ia_realv lo, ia_realv hi, ia_maskv hit,
                               iav time, int states[SCENE_REGIONS_UNION][PACKET_LANES], packet_index *evals) {
    iav t = iav_make(lo, hi);
    iav x = packet_extent(o[0], d[0], t), y = packet_extent(o[1], d[1], t), z = packet_extent(o[2], d[2], t);
    for (int k = 0; k < SCENE_REGIONS_UNION; k++) {
        iav f = scene_solid_Fv(k, x, y, z, time);
        PACKET_COUNT(*evals, hit);
        ia_maskv out = !(f.lo <= f.hi) | (f.lo > 0);
        ia_maskv s = select(select((ia_maskv)SCENE_BOUNDARY, (ia_maskv)SCENE_IN, f.hi < 0), (ia_maskv)SCENE_OUT, out);
        IAV_CAT(int, IA_VW) was = IAV_CAT(vload, IA_VW)(0, states[k]); /* a mask of longs in double */
        IAV_CAT(vstore, IA_VW)(select(was, IAV_CAT(convert_int, IA_VW)(s), IAV_CAT(convert_int, IA_VW)(hit)), 0,
                               states[k]);
    }
}

/* The first declared region other than `except` (-1: none) that may be in where the scene's solids have the states
 * of lane `lane` (scene_union_states): 1 with *item, 0 when none may be in there (*item WEAVE_NONE),
 * SCENE_TRACE_OVERFLOW when more solids may be in there than the ray's buffer lists. The solids not OUT are left
 * listed in r->walks.solid[0 .. nstarted), the states table all OUT. For the claim's normal, *solid: a solid of
 * that region in a BOUNDARY state, else one not OUT (-1 without a region). */
IA_FN int scene_union_first(scene_ray *r, const int states[SCENE_REGIONS_UNION][PACKET_LANES], int lane, int except,
                            int *item, int *solid) {
    r->nstarted = 0;
    *item = WEAVE_NONE;
    *solid = -1;
    for (int k = 0; k < SCENE_REGIONS_UNION; k++) { /* the scene's solids */
        int s = states[k][lane];
        if (s == SCENE_OUT)
            continue;
        if (r->nstarted == r->cand_cap) { /* no room to list it: traced again with more */
            for (int c = 0; c < r->nstarted; c++)
                r->state[r->walks.solid[c]] = SCENE_OUT;
            return SCENE_TRACE_OVERFLOW;
        }
        r->state[k] = (unsigned char)s;
        r->walks.solid[r->nstarted++] = k;
    }
    int found = weave_first_region(r, 0, except, item), rank = 2;
    for (int c = 0; found && c < r->nstarted; c++) {
        int k = r->walks.solid[c], boundary = r->state[k] == SCENE_BOUNDARY;
        const KERNEL_GLOBAL int *it = r->items + SCENE_ITEM_INTS * *item;
        if (classify_tree_holds(r->nodes, it[SCENE_ITEM_ROOT], it[SCENE_ITEM_SIZE], k) && (boundary ? 0 : 1) < rank) {
            *solid = k;
            rank = boundary ? 0 : 1;
        }
    }
    for (int c = 0; c < r->nstarted; c++)
        r->state[r->walks.solid[c]] = SCENE_OUT;
    return found;
}

/* Claims the ray's partition at g's leaf from lo on (before lo no region is in, but for `except`, -1: none, the
 * region a transparent layer's ray passes through, weave.h) when some region other than `except` may be in over
 * it, as weave_ray would claim a partition starting at lo: the first declared such region (scene_union_first).
 * No two regions can be in at one point (implicits/scene_emit.c: regions_disjoint), so there is no overlap to
 * weave on for. Returns 0 when no region may be in over the leaf (the ray is then woven from lo),
 * SCENE_TRACE_OVERFLOW when more solids may be in there than the ray's buffer lists. */
IA_FN int scene_union_claim(scene_ray *r, const int states[SCENE_REGIONS_UNION][PACKET_LANES], int lane, int except,
                            ia_real lo, weave_hit *hit) {
    int item, solid, found = scene_union_first(r, states, lane, except, &item, &solid);
    if (found <= 0)
        return found;
    r->segments += (kernel_u32)r->nstarted;
    r->partitions += 1;
    hit->t = lo;
    hit->item = item;
    hit->solid = solid;
    hit->overlap = -1;
    return 1;
}
#endif

/* Where the packet's rays (ok, dk, their parts [tn, tf] in the bounds where meets is not 0) start their weaves, from
 * their tile's leaf (scene_union_tiles): from[k] t_near, the leaf's start, or +inf for a ray on which no region is
 * in; leaf_hi[k] the leaf's end (-inf without a leaf); evals[k] the pre-pass's evaluations of each (the tile pass's
 * shared out over the tile's rays); with disjoint regions, states[k][lane] solid k's over the leaf
 * (scene_union_states). */
static void scene_union_packet(__constant ia_real *params, int flags, int height, const scene_tile *tile,
                               const ia_real ok[3][PACKET_LANES],
                               const ia_real dk[3][PACKET_LANES], const ia_real tn[PACKET_LANES],
                               const ia_real tf[PACKET_LANES], const ia_real meets[PACKET_LANES],
                               ia_real from[PACKET_LANES], ia_real leaf_hi[PACKET_LANES],
                               int states[SCENE_REGIONS_UNION][PACKET_LANES], kernel_u32 evals[PACKET_LANES]) {
    int ortho = flags & RENDER_ORTHO;
    ia_realv o[3], d[3], t_near = IAV_LOAD(tn), t_far = IAV_LOAD(tf);
    for (int c = 0; c < 3; c++) {
        o[c] = IAV_LOAD(ok[c]);
        d[c] = IAV_LOAD(dk[c]);
    }
    ia_maskv searching = IAV_LOAD(meets) != 0;
    iav time = iav_const(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    packet_index counts = (packet_index)0;
    const surface_start *leaf = &tile->start;
    /* g > 0 at t_near: known where t_near is before the tile's leaf and g > 0 there (scene_union_tiles), else by
     * g's enclosure at the point */
    ia_real t_leaf = leaf->level >= 0 ? node_bound(leaf->t0, leaf->w, leaf->level, leaf->i) : IA_INF;
    ia_maskv outside = tile->above ? searching & (t_near < t_leaf) : (ia_maskv)0, unknown = searching & ~outside;
    if (iav_any(unknown)) {
        outside |= unknown & (scene_union_g_at(o, d, t_near, time).lo > 0);
        PACKET_COUNT(counts, unknown);
    }
    ia_maskv hit = (ia_maskv)0;
    ia_realv hit_lo = IAV_R(0), hit_hi = IAV_R(0);
    if (leaf->level >= 0 && iav_any(outside)) {
        packet_index start = max((packet_index)leaf->i, packet_node_at(leaf->t0, leaf->w, leaf->level, t_near));
        ia_real pixel = (ia_real)2 * params[PARAM_SCALE_V] / (ia_real)height; /* as render.cl's trace_packet */
        hit = packet_first_root(0, o, d, leaf->t0, leaf->w, (packet_int)leaf->level, start, t_near, t_far, outside,
                                params[PARAM_EPS], ortho ? pixel : 0, ortho ? 0 : pixel, time, &hit_lo, &hit_hi,
                                &counts);
    }
    IAV_STORE(select(t_near, select(IAV_R(IA_INF), hit_lo, hit), outside), from);
    IAV_STORE(select(IAV_R(-IA_INF), hit_hi, hit), leaf_hi);
#ifdef SCENE_REGIONS_DISJOINT
    if (iav_any(hit))
        scene_union_states(o, d, fmax(t_near, hit_lo), hit_hi, hit, time, states, &counts);
#else
    (void)states;
#endif
    bisect_index count[IA_VW];
    IAV_STORE(counts, count);
    kernel_u32 shared = (tile->evals + TILE_SIZE * TILE_SIZE - 1) / (TILE_SIZE * TILE_SIZE);
    for (int k = 0; k < IA_VW; k++)
        evals[k] = (kernel_u32)count[k] + shared;
}

#endif
#endif
