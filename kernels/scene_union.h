/* kernels/scene_union.h -- the segment path's pre-pass over the union of its regions, where the program has it
 * (SCENE_REGIONS_UNION: implicits/scene_emit.c emits g, the regions as one expression, for scenes of at most 8
 * solids and regions whose solids are defined everywhere). The packet's rays search g's first root in SIMD lanes
 * as the first-root path does (packet.h's bisection and Newton), from the node of the packet's box of rays that
 * surface.h's block pass finds (scalar: g is also solid SCENE_REGIONS_UNION of the dispatcher; in lanes, one
 * active, it cost as much as the rays' own searches), and each ray's weave (scene_trace.h) starts at its leaf
 * instead of where it enters the bounds.
 *
 * Why: the weave's walks run one solid of one ray at a time, and down to the first region boundary each bisects
 * its solid's range from the top; Fig. 2 as regions took 2.5x the render of its one expression. From the leaf,
 * each walk starts at a node no wider than eps (segments_start_at), a step or two from the boundary.
 *
 * Guarantee: a region is in at a point only where g <= 0 (scene_emit.c). g is continuous (its solids are
 * defined everywhere); the nodes before the leaf tile [t_near, leaf) without gaps and none holds 0 in its
 * enclosure of g (proven over the packet's box of rays, surface.h, or the ray's own boxes, packet.h), so g keeps one
 * sign there; where g > 0 at t_near (its enclosure at the point), no region is in before the leaf's start, and
 * none at all on a ray without a leaf. Where g may be <= 0 at t_near (the ray may start inside a region) the ray
 * is woven from t_near as without the pre-pass.
 */
#ifndef KERNELS_SCENE_UNION_H
#define KERNELS_SCENE_UNION_H
#if defined(SCENE_REGIONS_UNION) && !defined(IACSG_GROUPS)
#define SCENE_UNION_PREPASS 1

/* Where the rays of the packet of pixels from (i0, j0) start their weaves (from[k]: t_near, the leaf's start, or
 * +inf for a ray on which no region is in), and the pre-pass's evaluations of each (the leaf search's shared out). */
static void scene_union_packet(__constant ia_real *params, int flags, int i0, int j0, int width, int height,
                               ia_real from[PACKET_LANES], kernel_u32 evals[PACKET_LANES]) {
    int ortho = flags & RENDER_ORTHO, i1 = min(i0 + PACKET_W, width) - 1, j1 = min(j0 + PACKET_H, height) - 1;
    ia_real eps = params[PARAM_EPS];
    iav time = iav_const(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    surface_start block; /* the packet's node, by a scalar pass: F of solid SCENE_REGIONS_UNION is g */
    kernel_u32 block_evals = 0;
    surface_block(params, ortho, i0, i1, j0, j1, width, height, SCENE_REGIONS_UNION, -1, 0,
                  ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]), &block, &block_evals);
    packet_int lanes = packet_lane_numbers();
    packet_index counts = (packet_index)0;
    packet_int col = i0 + lanes % PACKET_W, row = j0 + lanes / PACKET_W;
    ia_realv o[3], d[3], t_near, t_far, hit_lo = IAV_R(0), hit_hi = IAV_R(0);
    packet_rays(params, ortho, min(col, width - 1), min(row, height - 1), width, height, o, d);
    ia_maskv searching = (col < width) & (row < height) & packet_clip(params, o, d, &t_near, &t_far);
    iav at = iav_make(t_near, t_near);
    ia_maskv outside = searching & (iacsg_Fv(packet_extent(o[0], d[0], at), packet_extent(o[1], d[1], at),
                                             packet_extent(o[2], d[2], at), time)
                                        .lo > 0);
    PACKET_COUNT(counts, searching);
    ia_maskv hit = (ia_maskv)0;
    if (block.level >= 0) {
        packet_index start = max((packet_index)block.i, packet_node_at(block.t0, block.w, block.level, t_near));
        ia_real pixel = (ia_real)2 * params[PARAM_SCALE_V] / (ia_real)height; /* as render.cl's trace_packet */
        hit = packet_first_root(0, o, d, block.t0, block.w, (packet_int)block.level, start, t_near, t_far, outside,
                                eps, ortho ? pixel : 0, ortho ? 0 : pixel, time, &hit_lo, &hit_hi, &counts);
    }
    IAV_STORE(select(t_near, select(IAV_R(IA_INF), hit_lo, hit), outside), from);
    bisect_index count[IA_VW];
    IAV_STORE(counts, count);
    for (int k = 0; k < IA_VW; k++)
        evals[k] = (kernel_u32)count[k] + (block_evals + PACKET_LANES - 1) / PACKET_LANES;
}
#endif
#endif
