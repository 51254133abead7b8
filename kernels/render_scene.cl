/* kernels/render_scene.cl -- the entry point of the segment path, iacsg_render_scene: one work-item per block of
 * PACKET_W x PACKET_H tiles (SCENE_BLOCK_W x SCENE_BLOCK_H pixels) of the band of block rows from block_row0 or,
 * when `pixels` is not NULL, per PACKET_LANES (L) listed pixels L (block_row0 + g) + 0..L-1 (rays traced again with
 * larger buffers).
 * Rows from row_end on (past the view's band of rows, iacsg_view.row_count) are neither traced nor written.
 *
 * Per block: the union's tile pass over its PACKET_LANES tiles in SIMD lanes (scene_union.h, where the program has the
 * union), then its packets of PACKET_W x PACKET_H pixels. Per packet: the surfaces' block passes (scene_block),
 * which prove where no ray of the packet can meet a surface; the camera rays clipped to the bounds (camera.h, in
 * lanes where the program has packet.h); with the union, its first root in lanes from the tile's leaf, and where
 * the regions are disjoint the claim at that leaf (scene_union_claim). Per pixel: the ray traced one at a time
 * (scene_trace.h) with the work-item's slice of the per-ray buffers; a ray that overflows them is appended to
 * `overflow` and writes nothing. A listed pixel is traced with its own packet and its block's tile pass, so
 * exactly as in the first pass. Then, in SIMD lanes, the normals (the hit solid's gradient, facing the eye) and
 * the colours (light.h, each pixel's item's albedo), or with the effects' block `fx` (every item opaque, at most
 * one bounce, or no reflection and no shadows: src/render_effects.c) the effects (scene_lit.h: shadow rays,
 * reflected rays, transparent layers, traced as packets with the same buffers, scene_rays.h; one that overflows
 * lists its pixel as above). Outputs per pixel: rgb, depth (the claimed partition's start, +inf on a miss),
 * normal, ids (the item, -1 on a miss), overlap (another region certainly in the claimed partition, or -1), and
 * with KERNEL_STATS the evaluations, segments and partitions of each ray (and with `fx` its secondary rays and
 * their evaluations, fx_counts).
 *
 * iacsg_render_scene_samples: -aa's sample rays (src/render_effects_samples.c) as the camera rays of an image aa
 * times as wide and high, the listed packets of listed blocks traced as above, each packet's lanes written to an
 * output slot of its own instead of its pixels, with the effects' block their colours in linear light.
 */
#include "packet_camera.h"
#include "scene_trace.h"
#include "light.h"
#include "scene_union.h"
#include "scene_rays.h"
#include "scene_frame.h"
#include "scene_lit.h"

/* The block passes over the rays of the packet of pixels from (i0, j0), one per surface (surface.h): sets where
 * the rays start (starts) and returns the passes' evaluations, shared out over the packet's rays for the
 * statistics. (The same for the regions' solids, a pass proving where none can be other than OUT so that the
 * weaves start there, saved evaluations but no time: Fig. 2 as regions, 1000 spheres; BENCHMARKS.md.) */
static kernel_u32 scene_block(__constant ia_real *params, int flags, int i0, int j0, int width, int height,
                              __global const int *items, __global const uint *nodes, scene_prims prims,
                              ia_interval time, surface_start starts[SURFACE_BLOCK_MAX], scene_view *view) {
    int i1 = min(i0 + PACKET_W, width) - 1, j1 = min(j0 + PACKET_H, height) - 1;
    kernel_u32 evals = 0;
    for (int s = 0; s < min(view->nsurfaces, SURFACE_BLOCK_MAX); s++) {
        __global const int *it = items + SCENE_ITEM_INTS * view->surfaces[s];
        surface_block(params, flags & RENDER_ORTHO, i0, i1, j0, j1, width, height, it[SCENE_ITEM_SOLID],
                      it[SCENE_ITEM_ROOT], nodes, prims, time, &starts[s], &evals);
    }
    view->starts = starts;
    return (evals + PACKET_LANES - 1) / PACKET_LANES;
}

/* The rays of the packet of pixels from (i0, j0) (camera_ray), their directions' reciprocals (ik, for the BVH),
 * and where they meet the bounds (meets[k] 1, over [tn[k], tf[k]]: camera_clip); a pixel outside the image or the
 * band's rows meets nothing. In SIMD lanes (packet_camera.h, bit for bit the scalar functions' results) where the
 * program has them, else one by one. Returns whether any ray meets the bounds (from the lanes' mask: meets[]
 * read back as a vector right after its stores in parts was a store-forwarding stall, 2 % of truck's render). */
static int scene_packet_rays(__constant ia_real *params, const scene_frame *f, int i0, int j0,
                              ia_real ok[3][PACKET_LANES], ia_real dk[3][PACKET_LANES], ia_real ik[3][PACKET_LANES],
                              ia_real tn[PACKET_LANES], ia_real tf[PACKET_LANES], ia_real meets[PACKET_LANES]) {
    int ortho = f->flags & RENDER_ORTHO, width = f->width, height = f->height;
#ifdef PACKET_CAMERA_LANES
    packet_int lanes = packet_lane_numbers();
    packet_int col = i0 + lanes % PACKET_W, row = j0 + lanes / PACKET_W;
    ia_realv o[3], d[3], t_near, t_far;
    packet_rays(params, ortho, min(col, width - 1), min(row, height - 1), width, height, o, d);
    ia_maskv in = (col < width) & (row < f->row_end) & packet_clip(params, o, d, &t_near, &t_far);
    for (int c = 0; c < 3; c++) {
        IAV_STORE(o[c], ok[c]);
        IAV_STORE(d[c], dk[c]);
        IAV_STORE(IAV_R(1) / d[c], ik[c]);
    }
    IAV_STORE(t_near, tn);
    IAV_STORE(t_far, tf);
    IAV_STORE(select(IAV_R(0), IAV_R(1), in), meets);
    return iav_any(in);
#else
    int any = 0;
    for (int k = 0; k < PACKET_LANES; k++) {
        int i = i0 + k % PACKET_W, j = j0 + k / PACKET_W;
        ia_real o[3], d[3];
        camera_ray(params, ortho, min(i, width - 1), min(j, height - 1), width, height, o, d);
        meets[k] = i < width && j < f->row_end && camera_clip(params, o, d, &tn[k], &tf[k]);
        for (int c = 0; c < 3; c++) {
            ok[c][k] = o[c];
            dk[c][k] = d[c];
            ik[c][k] = (ia_real)1 / d[c];
        }
        any |= meets[k] != 0;
    }
    return any;
#endif
}

/* Drops from the packet's cut the solids proven out along every ray of its beam over the beam's range in their
 * boxes (segments_beam_out: each ray's range there is within it, and outside its box a solid is out), so that
 * its rays neither test nor solve them. */
static void scene_beam_drop_out(scene_prims prims, const bvh_beam *beam, scene_view *view, int cut[BVH_CUT_MAX]) {
#ifdef SCENE_SOLID_PRIMS
    ia_interval o[3], d[3];
    for (int c = 0; c < 3; c++) {
        o[c] = ia_make(beam->olo[c], beam->ohi[c]);
        d[c] = ia_make(beam->dlo[c], beam->dhi[c]);
    }
    for (int j = 0; j < view->ncut;) {
        int solid = view->link[2 * cut[j] + SCENE_BVH_SOLID];
        ia_real ta, tend;
        if (solid >= 0 && bvh_beam_range(beam, view->box, cut[j], &ta, &tend) &&
            segments_beam_out(prims, solid, o, d, ta, tend))
            cut[j] = cut[--view->ncut];
        else
            j++;
    }
#else
    (void)prims;
    (void)beam;
    (void)view;
    (void)cut;
#endif
}

/* Where lane k of a packet, pixel (i, j), writes its outputs: that pixel, or slot out0 + k (-aa's samples); -1 for
 * a lane outside the image or the band's rows, or other than `only` (>= 0). */
static int scene_lane_output(const scene_frame *f, int i, int j, int k, int only) {
    if (i >= f->width || j >= f->row_end || (only >= 0 && k != only))
        return -1;
    return f->out0 < 0 ? j * f->width + i : f->out0 + k;
}

/* A traced pixel's outputs but its colour and normal: depth, ids, overlap and (KERNEL_STATS) its ray's counts. */
static void scene_store_hit(const scene_frame *f, int pixel, int found, const weave_hit *hit, kernel_u32 evals,
                            kernel_u32 segments, kernel_u32 partitions) {
    if (f->depth)
        f->depth[pixel] = found ? camera_depth_round_down(hit->t) : INFINITY;
    f->ids[pixel] = found ? (float)hit->item : -1.0f;
    f->overlap[pixel] = found ? hit->overlap : -1;
#ifdef KERNEL_STATS
    f->counts[3 * pixel] = evals;
    f->counts[3 * pixel + 1] = segments;
    f->counts[3 * pixel + 2] = partitions;
#else
    (void)evals;
    (void)segments;
    (void)partitions;
#endif
}

/* The packet's colours (linear rgb in lanes) and, where the frame keeps them, normals (NULL: none hit), to its
 * pixels (pixel[k] >= 0). */
static void scene_store_colors(const scene_frame *f, const int pixel[PACKET_LANES], const shade_colorv rgb[3],
                               const ia_realv *n) {
    float color[3][PACKET_LANES];
    ia_real nk[3][PACKET_LANES];
    for (int c = 0; c < 3; c++) {
        IAV_CAT(vstore, IA_VW)(rgb[c], 0, color[c]);
        if (n && f->normal)
            IAV_STORE(n[c], nk[c]);
    }
    for (int k = 0; k < PACKET_LANES; k++) {
        if (pixel[k] < 0)
            continue;
        for (int c = 0; c < 3; c++) {
            f->rgb[3 * pixel[k] + c] = color[c][k];
            if (f->normal)
                f->normal[3 * pixel[k] + c] = n ? (float)nk[c][k] : 0.0f;
        }
    }
}

/* A packet none of whose rays can hit (none meets the bounds, or its beam meets no solid's box and there is no
 * surface): its pixels get the background of their rows and no hit, as the traced path would give them, without
 * its per-ray scaffolding (an empty frame's packets cost 6x as much through it: the per-lane arrays' stores read
 * back in lanes). */
static void scene_packet_empty(__constant ia_real *params, const scene_frame *f, int i0, int j0, int only,
                               kernel_u32 block_evals) {
    int pixel[PACKET_LANES];
    float rows[PACKET_LANES];
    weave_hit none = {0, -1, -1, -1};
    for (int k = 0; k < PACKET_LANES; k++) {
        int i = i0 + k % PACKET_W, j = j0 + k / PACKET_W;
        pixel[k] = scene_lane_output(f, i, j, k, only);
        rows[k] = (float)(min(j, f->height - 1) / f->aa);
        if (pixel[k] >= 0)
            scene_store_hit(f, pixel[k], 0, &none, block_evals, 0, 0);
    }
    shade_colorv albedo[3], rgb[3];
    for (int c = 0; c < 3; c++)
        albedo[c] = (shade_colorv)(0);
    if (f->fx) {
        scene_fx_background(f, IAV_CAT(vload, IA_VW)(0, rows), rgb);
        for (int c = 0; c < 3 && f->linear; c++)
            rgb[c] *= rgb[c];
    } else
        shade_combine((ia_maskv)0, IAV_CAT(vload, IA_VW)(0, rows), f->height / f->aa, albedo, IAV_R(0), IAV_R(0),
                      IAV_R(0), IAV_R(0), rgb);
    scene_store_colors(f, pixel, rgb, 0);
}

/* Traces the packet of pixels from (i0, j0): all its rays, or (only >= 0) lane `only` alone, a listed ray traced
 * again exactly as in the first pass. The rays and their parts in the bounds come in SIMD lanes (packet.h), then
 * each is woven alone; `tile` is the union's tile pass for the packet's tile (scene_union.h), with its evaluations
 * shared out over the tile's rays. */
static void scene_packet(__constant ia_real *params, const scene_frame *f, scene_view *view, scene_ray *ray, int i0,
                         int j0, int only, const scene_tile *tile) {
    int width = f->width, height = f->height;
    surface_start starts[SURFACE_BLOCK_MAX];
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    kernel_u32 block_evals =
        scene_block(params, f->flags, i0, j0, width, height, f->items, f->nodes, ray->walks.prims, time, starts, view);
    ia_real ok[3][PACKET_LANES], dk[3][PACKET_LANES], ik[3][PACKET_LANES], tn[PACKET_LANES], tf[PACKET_LANES];
    ia_real meets[PACKET_LANES];
    if (!scene_packet_rays(params, f, i0, j0, ok, dk, ik, tn, tf, meets)) {
        scene_packet_empty(params, f, i0, j0, only, block_evals);
        return;
    }
    ia_real from[PACKET_LANES]; /* where each ray's weave starts (scene_union.h), or -inf: its own t_near */
    ia_real leaf_hi[PACKET_LANES]; /* the end of the union's leaf starting at from[k], or -inf */
    kernel_u32 from_evals[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        from[k] = leaf_hi[k] = -IA_INF;
        from_evals[k] = 0;
    }
#ifdef SCENE_UNION_PREPASS
    int states[SCENE_REGIONS_UNION][PACKET_LANES] = {{0}}; /* the solids' states over the leaves (disjoint regions) */
    scene_union_packet(params, f->flags, height, tile, ok, dk, tn, tf, meets, from, leaf_hi, states,
                       from_evals);
#else
    (void)tile;
#endif
    int pixel[PACKET_LANES], cut[BVH_CUT_MAX];
    bvh_beam beam;
    bvh_beam_start(&beam);
    for (int k = 0; k < PACKET_LANES; k++)
        if (i0 + k % PACKET_W < width && j0 + k / PACKET_W < f->row_end && meets[k] != 0)
            bvh_beam_add_lane(&beam, ok, dk, ik, k, tn[k], tf[k]);
#ifdef SEGMENTS_LANES
    if (ray->walks.lanes)
        segments_lanes_start(ray->walks.lanes, ok, ik, tn, from, tf, view->box, view->link, view->nodes);
#endif
    view->ncut = bvh_beam_cut(&beam, view->box, view->link, view->nodes, cut);
    view->cut = view->ncut >= 0 ? cut : 0;
    scene_beam_drop_out(ray->walks.prims, &beam, view, cut);
    bvh_cut_lanes cut_lanes;
    view->cut_lanes = view->ncut > 0 && bvh_cut_lanes_fill(&cut_lanes, view->box, cut, view->ncut, ok, dk, ik,
                                                           fmax(IAV_LOAD(tn), IAV_LOAD(from)), IAV_LOAD(tf))
                          ? &cut_lanes
                          : 0;
#ifndef SCENE_UNION_PREPASS
    if (view->ncut == 0 && view->nsurfaces == 0) { /* no ray meets a solid's box (bvh_beam_cut) */
        scene_packet_empty(params, f, i0, j0, only, block_evals);
        return;
    }
#endif
    ia_real gk[3][PACKET_LANES], on[PACKET_LANES], t_hit[PACKET_LANES];
    int item_hit[PACKET_LANES];
    float color[3][PACKET_LANES], rows[PACKET_LANES];
    ia_real specular[PACKET_LANES], shininess[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        int i = i0 + k % PACKET_W, j = j0 + k / PACKET_W;
        pixel[k] = scene_lane_output(f, i, j, k, only);
        rows[k] = (float)(min(j, height - 1) / f->aa);
        weave_hit hit = {0, -1, -1, -1};
        ray->evals = ray->segments = ray->partitions = 0;
        view->lane = k;
#ifdef SEGMENTS_LANES
        if (ray->walks.lanes)
            ray->walks.lanes->lane = k;
#endif
        ia_real o[3] = {ok[0][k], ok[1][k], ok[2][k]}, d[3] = {dk[0][k], dk[1][k], dk[2][k]};
        bvh_ray br = bvh_ray_lane(dk, ik, k);
        int found = 0, claimed = 0; /* claimed: at the union's leaf (scene_union_claim), or overflowing */
        if (pixel[k] >= 0 && meets[k] != 0 && (from[k] < IA_INF || view->nsurfaces > 0)) { /* else no hit */
#ifdef SCENE_REGIONS_DISJOINT
            if (leaf_hi[k] >= from[k])
                claimed = scene_union_claim(ray, states, k, -1, fmax(tn[k], from[k]), &hit);
#endif
            found = claimed == SCENE_TRACE_OVERFLOW ? claimed
                    : claimed ? scene_trace_surfaces(view, ray, o, d, tn[k], tf[k], 1, &hit)
                              : scene_trace_ray_from(view, ray, o, d, &br, tn[k], fmax(tn[k], from[k]), tf[k], &hit);
        }
        if (found == SCENE_TRACE_OVERFLOW) {
            f->overflow[atomic_inc(f->noverflow)] = pixel[k];
            pixel[k] = -1;
            found = 0;
        }
        on[k] = found;
        t_hit[k] = found ? hit.t : 0;
        item_hit[k] = found ? hit.item : -1;
        ia_real gradient[3] = {0, 0, 0};
        if (found) /* at a point, for shading */
            scene_gradient(ray->walks.prims, hit.solid, o, d, hit.t, params[PARAM_TIME_LO], gradient);
        for (int c = 0; c < 3; c++) {
            gk[c][k] = gradient[c];
            color[c][k] = found ? f->albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_RGB + c] : 0;
        }
        specular[k] = found ? f->albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_SPECULAR] : 0;
        /* a miss: the exponent that lets light.h's shade_highlight square (48) where the hits' do, so that a hit's
         * highlight does not hang on its packet's misses (a traced-again lane's packet is misses but it) */
        shininess[k] = found ? f->albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_SHININESS] : 48;
        if (pixel[k] >= 0)
            scene_store_hit(f, pixel[k], found, &hit, ray->evals + block_evals + from_evals[k], ray->segments,
                            ray->partitions);
    }
    ia_realv g[3], d_v[3], n[3];
    shade_colorv albedo_v[3], rgb_v[3];
    for (int c = 0; c < 3; c++) {
        g[c] = IAV_LOAD(gk[c]);
        d_v[c] = IAV_LOAD(dk[c]);
        albedo_v[c] = IAV_CAT(vload, IA_VW)(0, color[c]);
    }
    ia_maskv hit_v = IAV_LOAD(on) != 0;
    shade_colorv row_v = IAV_CAT(vload, IA_VW)(0, rows);
    if (iav_any(hit_v))
        shade_normals(g, d_v, n);
    for (int c = 0; c < 3 && !iav_any(hit_v); c++)
        n[c] = IAV_R(0);
    if (f->fx)
        scene_packet_lit(params, f, view, ray, ok, dk, t_hit, item_hit, hit_v, n, pixel, row_v, albedo_v,
                         IAV_LOAD(specular), IAV_LOAD(shininess), rgb_v);
    else if (iav_any(hit_v))
        shade_lit_materials(params, hit_v, n, d_v, row_v, height / f->aa, albedo_v, IAV_LOAD(specular),
                            IAV_LOAD(shininess), rgb_v);
    else /* a packet with no hit: its background only, no normals nor lighting */
        shade_combine(hit_v, row_v, height / f->aa, albedo_v, IAV_R(0), IAV_R(0), IAV_R(0), IAV_R(0), rgb_v);
    for (int c = 0; c < 3; c++)
        n[c] = select(IAV_R(0), n[c], hit_v);
    scene_store_colors(f, pixel, rgb_v, n);
}

/* The union's tile pass over the block of tiles from (tx0, ty0), where the program has the union (else nothing). */
static void scene_tiles(__constant ia_real *params, const scene_frame *f, int tx0, int ty0,
                        scene_tile tiles[PACKET_LANES]) {
#ifdef SCENE_UNION_PREPASS
    scene_union_tiles(params, f->flags, f->width, f->height, tx0, ty0, tiles);
#else
    (void)params;
    (void)f;
    (void)tx0;
    (void)ty0;
    for (int k = 0; k < PACKET_LANES; k++) {
        tiles[k].start.level = -1;
        tiles[k].above = 0;
        tiles[k].evals = 0;
    }
#endif
}

/* A work-item's table of its packet's planar solids solved in lanes (segments_lanes.h), where the program has them. */
#ifdef SEGMENTS_LANES
#define SCENE_LANES_DECLARE(name) segments_lanes name
#define SCENE_LANES_OF(name) (&(name))
#else
#define SCENE_LANES_DECLARE(name) (void)0
#define SCENE_LANES_OF(name) 0
#endif

/* A work-item's ray state over its slice `slot` of the per-ray buffers; dirs: where an orthographic view's rays,
 * which share their direction, keep the primitives' work on it. */
static scene_ray scene_slot_ray(__global const uint *nodes, __global const int *items,
                                __global const int *solid_items_start, __global const int *solid_items,
                                __global int *cand_solid, __global ia_real *cand_range, __global ia_real *cand_pos,
                                __global int *cand_level, __global bisect_index *cand_index, __global int *cand_newton,
                                __global ia_real *cand_newton_t, int cand_cap, __global uchar *state, int nsolids,
                                size_t slot, int flags, prim_dirs *dirs, segments_lanes *lanes, scene_prims prims) {
    size_t first = slot * (size_t)cand_cap;
    for (int k = 0; k < PRIM_DIRS_SLOTS; k++)
        dirs->solid[k] = -1;
    scene_ray ray = {nodes,
                     items,
                     solid_items_start,
                     solid_items,
                     {cand_solid + first, cand_range + 2 * first, cand_pos + first, cand_level + first,
                      cand_index + first, cand_newton + first, cand_newton_t + 2 * first,
                      flags & RENDER_ORTHO ? dirs : 0,
                      flags & RENDER_ORTHO ? lanes : 0,
                      prims},
                     cand_cap,
                     0,
                     0,
                     state + slot * nsolids,
                     0,
                     0,
                     0};
    return ray;
}

/* One work-item per block of PACKET_W x PACKET_H tiles (SCENE_BLOCK_W x SCENE_BLOCK_H pixels) from block row
 * block_row0 on, or, when `pixels` is not NULL, per PACKET_LANES (L) listed pixels (block_row0 + g) L + 0..L-1, each
 * traced again with its own packet, its block's tile pass included. */
__kernel void iacsg_render_scene(__constant ia_real *params, int flags, int width, int height, int block_row0,
                                 __global const int *pixels, int npixels, __global const ia_real *bvh_box,
                                 __global const int *bvh_link, int nbvh, __global const uint *nodes,
                                 __global const int *items, __global const int *solid_items_start,
                                 __global const int *solid_items, __global const int *surfaces, int nsurfaces,
                                 __global const float *albedo, __global int *cand_solid, __global ia_real *cand_range,
                                 __global ia_real *cand_pos, __global int *cand_level,
                                 __global bisect_index *cand_index, __global int *cand_newton,
                                 __global ia_real *cand_newton_t, int cand_cap, __global uchar *state, int nsolids,
                                 __global float *rgb, __global float *depth, __global float *normal,
                                 __global float *ids, __global int *overlap, __global uint *counts,
                                 __global int *overflow, __global int *noverflow, int row_end,
                                 __global const ia_real *prims, __constant ia_real *fx, __global uint *fx_counts) {
    size_t slot = get_global_id(1) * get_global_size(0) + get_global_id(0);
    int bx = (int)get_global_id(0) * SCENE_BLOCK_W, by = (block_row0 + (int)get_global_id(1)) * SCENE_BLOCK_H;
    if (!pixels && (bx >= width || by >= height))
        return;
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    scene_view view = {bvh_box, bvh_link, nbvh, surfaces, nsurfaces, params[PARAM_EPS], time, 0};
    prim_dirs dirs; /* every ray of an orthographic view has the same direction */
    SCENE_LANES_DECLARE(lanes);
    scene_ray ray = scene_slot_ray(nodes, items, solid_items_start, solid_items, cand_solid, cand_range, cand_pos,
                                   cand_level, cand_index, cand_newton, cand_newton_t, cand_cap, state, nsolids, slot,
                                   flags, &dirs, SCENE_LANES_OF(lanes), prims);
    scene_frame f = {flags, width, height, row_end, items, nodes, albedo, rgb, depth, normal, ids,
                     overlap, counts, overflow, noverflow, -1, fx, fx_counts, 0, 1, params[PARAM_EPS]};
    scene_tile tiles[PACKET_LANES];
    if (pixels) {
        for (int k = 0; k < PACKET_LANES; k++) {
            int n = (block_row0 + (int)slot) * PACKET_LANES + k;
            if (n >= npixels)
                return;
            int i = pixels[n] % width, j = pixels[n] / width;
            int tx = i / TILE_SIZE, ty = j / TILE_SIZE, tx0 = tx - tx % PACKET_W, ty0 = ty - ty % PACKET_H;
            int t = (ty - ty0) * PACKET_W + tx - tx0;
            scene_tiles(params, &f, tx0, ty0, tiles);
            scene_packet(params, &f, &view, &ray, i - i % PACKET_W, j - j % PACKET_H,
                         j % PACKET_H * PACKET_W + i % PACKET_W, &tiles[t]);
        }
        return;
    }
    scene_tiles(params, &f, bx / TILE_SIZE, by / TILE_SIZE, tiles);
    for (int t = 0; t < PACKET_LANES; t++)
        for (int j = 0; j < TILE_SIZE; j += PACKET_H)
            for (int i = 0; i < TILE_SIZE; i += PACKET_W) {
                int i0 = bx + t % PACKET_W * TILE_SIZE + i, j0 = by + t / PACKET_W * TILE_SIZE + j;
                if (i0 < width && j0 < min(height, row_end))
                    scene_packet(params, &f, &view, &ray, i0, j0, -1, &tiles[t]);
            }
}

/* -aa's sample rays (src/render_effects_samples.c): sample (a, b) of pixel (i, j) is pixel (aa i + a, aa j + b) of
 * an image aa times as wide and high (width, height; params is that image's camera, with -aa's eps), whose centre
 * is the sample's point. One work-item per listed block (SCENE_SAMPLES_INTS ints each, kernels/scene_data.h) from
 * first_block on: the block's tile pass, then each listed packet traced as the camera rays are, its lanes written
 * to slot s, outputs PACKET_LANES s + lane (rgb, depth, normal, ids, overlap, counts as iacsg_render_scene's). A
 * sample's pixel of 4x4 samples is one packet (two of 8 lanes), a coherent beam: the BVH cut, the union's leaf and
 * the claim at it serve all its rays. The per-ray buffers hold every solid (src/render_scene.c:
 * render_scene_trace_args), so no ray overflows; `overflow` lists any that would. With the effects' block fx, each
 * sample's colour is lit by it (scene_packet_lit, shadow and reflected rays and all, with leaves of fx_eps, the
 * view's, as the host's paths; the background of its pixel's row) in linear light, with KERNEL_STATS its secondary
 * rays and their evaluations to fx_counts (2 a slot's lane). */
__kernel void iacsg_render_scene_samples(__constant ia_real *params, int flags, int width, int height,
                                         __global const int *blocks, int nblocks, int first_block,
                                         __global const float *albedo, __global float *rgb, __global float *depth,
                                         __global float *normal, __global float *ids, __global int *overlap,
                                         __global uint *counts, __global int *overflow, __global int *noverflow,
                                         __global const ia_real *bvh_box, __global const int *bvh_link, int nbvh,
                                         __global const uint *nodes, __global const int *items,
                                         __global const int *solid_items_start, __global const int *solid_items,
                                         __global const int *surfaces, int nsurfaces, __global int *cand_solid,
                                         __global ia_real *cand_range, __global ia_real *cand_pos,
                                         __global int *cand_level, __global bisect_index *cand_index,
                                         __global int *cand_newton, __global ia_real *cand_newton_t, int cand_cap,
                                         __global uchar *state, int nsolids, __global const ia_real *prims,
                                         __constant ia_real *fx, __global uint *fx_counts, int aa,
                                         ia_real fx_eps) {
    size_t slot = get_global_id(0);
    int listed = first_block + (int)slot;
    if (listed >= nblocks)
        return;
    __global const int *block = blocks + SCENE_SAMPLES_INTS * (size_t)listed;
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    scene_view view = {bvh_box, bvh_link, nbvh, surfaces, nsurfaces, params[PARAM_EPS], time, 0};
    prim_dirs dirs;
    SCENE_LANES_DECLARE(lanes);
    scene_ray ray = scene_slot_ray(nodes, items, solid_items_start, solid_items, cand_solid, cand_range, cand_pos,
                                   cand_level, cand_index, cand_newton, cand_newton_t, cand_cap, state, nsolids, slot,
                                   flags, &dirs, SCENE_LANES_OF(lanes), prims);
    scene_frame f = {flags, width, height, height, items, nodes, albedo, rgb, depth, normal, ids,
                     overlap, counts, overflow, noverflow, 0, fx, fx_counts, fx != 0, aa, fx_eps};
    int bx = block[SCENE_SAMPLES_BX] * SCENE_BLOCK_W, by = block[SCENE_SAMPLES_BY] * SCENE_BLOCK_H;
    int out = block[SCENE_SAMPLES_SLOT];
    scene_tile tiles[PACKET_LANES];
    scene_tiles(params, &f, bx / TILE_SIZE, by / TILE_SIZE, tiles);
    for (int p = 0; p < SCENE_BLOCK_PACKETS; p++) {
        if (!(((uint)block[SCENE_SAMPLES_MASK + p / 32] >> (p % 32)) & 1))
            continue;
        int t = p / SCENE_TILE_PACKETS, q = p % SCENE_TILE_PACKETS;
        int i0 = bx + t % PACKET_W * TILE_SIZE + q % SCENE_TILE_PACKETS_W * PACKET_W;
        int j0 = by + t / PACKET_W * TILE_SIZE + q / SCENE_TILE_PACKETS_W * PACKET_H;
        f.out0 = PACKET_LANES * out++;
        scene_packet(params, &f, &view, &ray, i0, j0, -1, &tiles[t]);
    }
}
