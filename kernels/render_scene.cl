/* kernels/render_scene.cl -- the entry point of the segment path, iacsg_render_scene: one work-item per packet
 * of PACKET_W x PACKET_H pixels, either a block of the band of packet rows from block_row0 or, when `pixels` is
 * not NULL, the listed pixels 16 (block_row0 + g) + 0..15 (rays traced again with larger buffers). Rows from
 * row_end on (past the view's band of rows, iacsg_view.row_count) are neither traced nor written.
 *
 * Per packet: the surfaces' block passes (scene_block), which prove where no ray of the packet can meet a
 * surface; a listed pixel gets its own packet's, so it is traced again exactly as in the first pass.
 * Per pixel: the camera ray (camera.h) clipped to the bounds, traced one at a time (scene_trace.h) with the
 * work-item's slice of the per-ray buffers; a ray that overflows them is appended to `overflow` and writes
 * nothing. Then, in SIMD lanes, the normals (the hit solid's gradient, facing the eye) and the colours (light.h,
 * each pixel's item's albedo). Outputs per pixel: rgb, depth (the claimed partition's start, +inf on a miss),
 * normal, ids (the item, -1 on a miss), overlap (another region certainly in the claimed partition, or -1), and
 * with KERNEL_STATS the evaluations, segments and partitions of each ray.
 */
#include "scene_trace.h"
#include "light.h"
#include "scene_union.h"

/* The unit normal at o + t d of the solid: its gradient (scene_solid_f_grad). */
static void scene_gradient(int solid, const ia_real o[3], const ia_real d[3], ia_real t, ia_real time,
                           ia_real g[3]) {
    scene_solid_f_grad(solid, o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2], time, &g[0], &g[1], &g[2]);
}

/* The block passes over the rays of the packet of pixels from (i0, j0), one per surface (surface.h): sets where
 * the rays start (starts) and returns the passes' evaluations, shared out over the packet's rays for the
 * statistics. (The same for the regions' solids, a pass proving where none can be other than OUT so that the
 * weaves start there, saved evaluations but no time: Fig. 2 as regions, 1000 spheres; BENCHMARKS.md.) */
static kernel_u32 scene_block(__constant ia_real *params, int flags, int i0, int j0, int width, int height,
                              __global const int *items, __global const uint *nodes, ia_interval time,
                              surface_start starts[SURFACE_BLOCK_MAX], scene_view *view) {
    int i1 = min(i0 + PACKET_W, width) - 1, j1 = min(j0 + PACKET_H, height) - 1;
    kernel_u32 evals = 0;
    for (int s = 0; s < min(view->nsurfaces, SURFACE_BLOCK_MAX); s++) {
        __global const int *it = items + SCENE_ITEM_INTS * view->surfaces[s];
        surface_block(params, flags & RENDER_ORTHO, i0, i1, j0, j1, width, height, it[SCENE_ITEM_SOLID],
                      it[SCENE_ITEM_ROOT], nodes, time, &starts[s], &evals);
    }
    view->starts = starts;
    return (evals + PACKET_LANES - 1) / PACKET_LANES;
}

__kernel void iacsg_render_scene(__constant ia_real *params, int flags, int width, int height, int block_row0,
                                 __global const int *pixels, int npixels, __global const ia_real *bvh_box,
                                 __global const int *bvh_link, int nbvh, __global const uint *nodes,
                                 __global const int *items, __global const int *solid_items_start,
                                 __global const int *solid_items, __global const int *surfaces, int nsurfaces,
                                 __global const float *albedo, __global int *cand_solid, __global ia_real *cand_range,
                                 __global ia_real *cand_pos, __global int *cand_level, __global bisect_index *cand_index,
                                 __global int *cand_newton, __global ia_real *cand_newton_t, int cand_cap, __global uchar *state, int nsolids, __global float *rgb, __global float *depth,
                                 __global float *normal, __global float *ids, __global int *overlap,
                                 __global uint *counts, __global int *overflow, __global int *noverflow,
                                 int row_end) {
    size_t slot = get_global_id(1) * get_global_size(0) + get_global_id(0);
    int i0 = (int)get_global_id(0) * PACKET_W, j0 = (block_row0 + (int)get_global_id(1)) * PACKET_H;
    if (!pixels && (i0 >= width || j0 >= height))
        return;
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    scene_view view = {bvh_box, bvh_link, nbvh, surfaces, nsurfaces, params[PARAM_EPS], time, 0};
    size_t first = slot * (size_t)cand_cap;
    scene_ray ray = {nodes,
                     items,
                     solid_items_start,
                     solid_items,
                     {cand_solid + first, cand_range + 2 * first, cand_pos + first, cand_level + first, cand_index + first,
                      cand_newton + first, cand_newton_t + 2 * first},
                     cand_cap,
                     0,
                     0,
                     state + slot * nsolids,
                     0,
                     0,
                     0};
    surface_start starts[SURFACE_BLOCK_MAX];
    kernel_u32 block_evals =
        pixels ? 0 : scene_block(params, flags, i0, j0, width, height, items, nodes, time, starts, &view);
    ia_real from[PACKET_LANES]; /* where each ray's weave starts (scene_union.h), or -inf: its own t_near */
    kernel_u32 from_evals[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        from[k] = -IA_INF;
        from_evals[k] = 0;
    }
#ifdef SCENE_UNION_PREPASS
    if (!pixels)
        scene_union_packet(params, flags, i0, j0, width, height, from, from_evals);
#endif
    int pixel[PACKET_LANES];
    ia_real dk[3][PACKET_LANES], gk[3][PACKET_LANES], on[PACKET_LANES];
    float rows[PACKET_LANES], color[3][PACKET_LANES];
    ia_real specular[PACKET_LANES], shininess[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        int i = i0 + k % PACKET_W, j = j0 + k / PACKET_W;
        if (pixels) {
            int n = (block_row0 + (int)slot) * PACKET_LANES + k;
            i = n < npixels ? pixels[n] % width : width;
            j = n < npixels ? pixels[n] / width : height;
        }
        pixel[k] = i < width && j < row_end ? j * width + i : -1; /* the band's rows only */
        int lane = k;
        if (pixels && pixel[k] >= 0) { /* traced as in the first pass: from its packet's block passes */
            block_evals = scene_block(params, flags, i - i % PACKET_W, j - j % PACKET_H, width, height, items, nodes,
                                      time, starts, &view);
#ifdef SCENE_UNION_PREPASS
            scene_union_packet(params, flags, i - i % PACKET_W, j - j % PACKET_H, width, height, from, from_evals);
            lane = j % PACKET_H * PACKET_W + i % PACKET_W;
#endif
        }
        rows[k] = (float)min(j, height - 1);
        ia_real o[3], d[3], tn, tf;
        camera_ray(params, flags & RENDER_ORTHO, min(i, width - 1), min(j, height - 1), width, height, o, d);
        weave_hit hit = {0, -1, -1, -1};
        ray.evals = ray.segments = ray.partitions = 0;
        int found = pixel[k] >= 0 && camera_clip(params, o, d, &tn, &tf)
                        ? scene_trace_ray_from(&view, &ray, o, d, tn, fmax(tn, from[lane]), tf, &hit)
                        : 0;
        if (found == SCENE_TRACE_OVERFLOW) {
            overflow[atomic_inc(noverflow)] = pixel[k];
            pixel[k] = -1;
            found = 0;
        }
        on[k] = found;
        ia_real gradient[3] = {0, 0, 0};
        if (found)
            scene_gradient(hit.solid, o, d, hit.t, params[PARAM_TIME_LO], gradient); /* a point for shading */
        for (int c = 0; c < 3; c++) {
            dk[c][k] = d[c];
            gk[c][k] = gradient[c];
            color[c][k] = found ? albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_RGB + c] : 0;
        }
        specular[k] = found ? albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_SPECULAR] : 0;
        shininess[k] = found ? albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_SHININESS] : 1;
        if (pixel[k] < 0)
            continue;
        if (depth)
            depth[pixel[k]] = found ? camera_depth_round_down(hit.t) : INFINITY;
        ids[pixel[k]] = found ? (float)hit.item : -1.0f;
        overlap[pixel[k]] = found ? hit.overlap : -1;
#ifdef KERNEL_STATS
        counts[3 * pixel[k]] = ray.evals + block_evals + from_evals[lane];
        counts[3 * pixel[k] + 1] = ray.segments;
        counts[3 * pixel[k] + 2] = ray.partitions;
#else
        (void)counts;
#endif
    }
    ia_realv g[3], d[3], n[3];
    shade_colorv albedo_v[3], rgb_v[3];
    for (int c = 0; c < 3; c++) {
        g[c] = IAV_LOAD(gk[c]);
        d[c] = IAV_LOAD(dk[c]);
        albedo_v[c] = IAV_CAT(vload, IA_VW)(0, color[c]);
    }
    shade_normals(g, d, n);
    ia_maskv hit_v = IAV_LOAD(on) != 0;
    shade_lit_materials(params, hit_v, n, d, IAV_CAT(vload, IA_VW)(0, rows), height, albedo_v, IAV_LOAD(specular),
                        IAV_LOAD(shininess), rgb_v);
    ia_real nk[3][PACKET_LANES];
    for (int c = 0; c < 3; c++) {
        IAV_STORE(select(IAV_R(0), n[c], hit_v), nk[c]);
        IAV_CAT(vstore, IA_VW)(rgb_v[c], 0, color[c]);
    }
    for (int k = 0; k < PACKET_LANES; k++) {
        if (pixel[k] < 0)
            continue;
        for (int c = 0; c < 3; c++) {
            rgb[3 * pixel[k] + c] = color[c][k];
            if (normal)
                normal[3 * pixel[k] + c] = (float)nk[c][k];
        }
    }
}
