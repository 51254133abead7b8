/* kernels/scene_effects.cl -- the segment path's effects (src/render_effects.c): its secondary rays
 * (iacsg_scene_trace_rays) and the colours of their hits (iacsg_scene_shade).
 *
 * iacsg_scene_trace_rays: shadow and reflected rays and transparent layers from the host's ray buffer
 * (kernels/effects.h), PACKET_LANES consecutive rays per work-item (the host lists them from neighbouring pixels),
 * traced as a packet (scene_rays.h). The per-ray buffers have room for every solid of the scene
 * (src/render_scene.c, render_scene_trace_args), so no ray overflows. Out per ray: the claimed partition's start
 * (+inf when nothing is hit in [tn, tf] within the bounds), the unit normal there facing the ray, the item
 * (EFFECTS_HIT_BLOCKED: a shadow ray certainly blocked, with `whether`), and where `evals` is not NULL the ray's
 * interval evaluations (KERNEL_STATS).
 */

__kernel void iacsg_scene_trace_rays(__constant ia_real *params, __global const ia_real *rays, int nrays, int first_ray,
                                     ia_real eps, __global ia_real *hit_t, __global float *normal,
                                     __global int *hit_item,
                                     __global uint *evals, __global const int *passing,
                                     __global const ia_real *bvh_box, __global const int *bvh_link, int nbvh,
                                     __global const uint *nodes, __global const int *items,
                                     __global const int *solid_items_start, __global const int *solid_items,
                                     __global const int *surfaces, int nsurfaces, __global int *cand_solid,
                                     __global ia_real *cand_range, __global ia_real *cand_pos, __global int *cand_level,
                                     __global bisect_index *cand_index, __global int *cand_newton,
                                     __global ia_real *cand_newton_t, int cand_cap, __global uchar *state,
                                     int nstates, __global const ia_real *prims, int whether) {
    size_t slot = get_global_id(0);
    int first = first_ray + PACKET_LANES * (int)slot;
    if (first >= nrays)
        return;
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    scene_view view = {bvh_box, bvh_link, nbvh, surfaces, nsurfaces, eps, time, 0};
    size_t c0 = slot * (size_t)cand_cap;
    scene_ray r = {.nodes = nodes,
                   .items = items,
                   .solid_items_start = solid_items_start,
                   .solid_items = solid_items,
                   .walks = {cand_solid + c0, cand_range + 2 * c0, cand_pos + c0, cand_level + c0, cand_index + c0,
                             cand_newton + c0, cand_newton_t + 2 * c0, 0, 0, prims},
                   .cand_cap = cand_cap,
                   .state = state + slot * (size_t)nstates};
    ia_real ok[3][PACKET_LANES], dk[3][PACKET_LANES], tn[PACKET_LANES], tf[PACKET_LANES], meets[PACKET_LANES];
    ia_real pass[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        int ray = min(first + k, nrays - 1);
        const __global ia_real *q = rays + EFFECTS_RAY_REALS * (size_t)ray;
        for (int c = 0; c < 3; c++) {
            ok[c][k] = q[c];
            dk[c][k] = q[3 + c];
        }
        tn[k] = q[6];
        tf[k] = q[7];
        meets[k] = first + k < nrays;
        pass[k] = passing && first + k < nrays ? passing[ray] : 0;
    }
    int found[PACKET_LANES];
    weave_hit hits[PACKET_LANES];
    kernel_u32 ray_evals[PACKET_LANES];
    /* no overflow: the buffers hold every solid */
    scene_rays_trace(&view, &r, params, whether, 0, ok, dk, tn, tf, meets, pass, found, hits, ray_evals);
    for (int k = 0; k < PACKET_LANES && first + k < nrays; k++) {
        int ray = first + k, hit = found[k] == 1;
        ia_real o[3] = {ok[0][k], ok[1][k], ok[2][k]}, d[3] = {dk[0][k], dk[1][k], dk[2][k]}, t = hits[k].t;
        hit_t[ray] = hit ? t : IA_INF;
        hit_item[ray] = hit ? hits[k].item : -1;
        if (evals) /* counted with KERNEL_STATS (-stats) */
            evals[ray] = ray_evals[k];
        ia_real g[3] = {0, 0, 0};
        if (hit && hits[k].solid >= 0)
            scene_solid_f_grad(prims, hits[k].solid, o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2],
                               params[PARAM_TIME_LO], &g[0], &g[1], &g[2]);
        ia_real len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), facing = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
        int ok_g = len > 0 && isfinite(len);
        for (int c = 0; c < 3; c++) /* facing the ray; -d where the gradient vanishes (as light.h's shade_normals) */
            normal[3 * ray + c] = (float)(!hit ? 0 : ok_g ? (facing > 0 ? -g[c] : g[c]) / len : -d[c]);
    }
}

/* iacsg_scene_shade: the colours of the segment path's hits (src/render_effects.c lists them, with the lights each
 * sees after its shadow rays), 16 per work-item in SIMD lanes, by light.h's shade_effects with each hit's item's
 * material (SCENE_MATERIAL_FLOATS per item) and, for -shade ids, palette colour (3 linear floats per item). In
 * per hit: its ray (EFFECTS_RAY_REALS), depth, normal (3 floats, facing the ray), item (-1: a miss), the
 * fraction of each light that reaches it (EFFECTS_MAX_LIGHTS floats) and its pixel's row; shadow_item, where not
 * NULL (every item opaque: kernels/scene_centre.cl), the items that the shadow rays met, that towards light l from
 * hit i at shadow_slot[l n + i] (where vis_in is not 0), a light being seen only where its ray met nothing (-1).
 * Out per hit, 6 floats: its colour (a miss: the background) and the background of its row, both linear; or, where
 * rgb is not NULL (the centre paths have no child: kernels/scene_centre.cl), hit i's colour display-encoded (gamma 2,
 * clamped to [0, 1], as the host's fx_encode) straight into its pixel pixels[i] of the frame rgb, so that no host pass
 * copies and encodes them (the segment path's shadowed frame: ~70 CPU samples of fx_encode on one CPU). */
__kernel void iacsg_scene_shade(__constant ia_real *params, __constant ia_real *fx, __global const float *materials,
                                __global const float *palette, int height, __global const ia_real *rays,
                                __global const ia_real *hit_t, __global const float *hit_n,
                                __global const int *hit_item, __global const float *vis_in,
                                __global const int *rows, int n, __global float *out,
                                __global const int *shadow_item, __global const int *shadow_slot,
                                __global const int *pixels, __global float *rgb) {
    int first = (int)get_global_id(0) * IA_VW, nlights = (int)fx[EFFECTS_NLIGHTS];
    if (first >= n)
        return;
    ia_real o_k[3][IA_VW], d_k[3][IA_VW], n_k[3][IA_VW], t_k[IA_VW], on_k[IA_VW], row_k[IA_VW];
    ia_real specular_k[IA_VW], shininess_k[IA_VW], seen_k[EFFECTS_MAX_LIGHTS][IA_VW];
    float albedo_k[3][IA_VW], id_k[3][IA_VW];
    for (int k = 0; k < IA_VW; k++) {
        int i = min(first + k, n - 1), item = hit_item[i], it = max(item, 0);
        __global const ia_real *q = rays + EFFECTS_RAY_REALS * (size_t)i;
        __global const float *m = materials + SCENE_MATERIAL_FLOATS * it;
        for (int c = 0; c < 3; c++) {
            o_k[c][k] = q[c];
            d_k[c][k] = q[3 + c];
            n_k[c][k] = hit_n[3 * i + c];
            albedo_k[c][k] = m[SCENE_MATERIAL_RGB + c];
            id_k[c][k] = palette[3 * it + c];
        }
        on_k[k] = item >= 0;
        t_k[k] = item >= 0 ? hit_t[i] : 0;
        row_k[k] = (ia_real)rows[i];
        specular_k[k] = m[SCENE_MATERIAL_SPECULAR];
        shininess_k[k] = m[SCENE_MATERIAL_SHININESS];
        for (int l = 0; l < nlights; l++) {
            float v = vis_in[EFFECTS_MAX_LIGHTS * i + l];
            seen_k[l][k] = v != 0 && shadow_item && shadow_item[shadow_slot[(size_t)l * n + i]] != -1 ? 0 : v;
        }
    }
    ia_realv o[3], d[3], nv[3], p[3], t = IAV_LOAD(t_k);
    shade_colorv albedo[3], id_rgb[3], lin[3], bg[3];
    ia_maskv hit = IAV_LOAD(on_k) != 0;
    ia_realv vis[EFFECTS_MAX_LIGHTS];
    for (int c = 0; c < 3; c++) {
        o[c] = IAV_LOAD(o_k[c]);
        d[c] = IAV_LOAD(d_k[c]);
        nv[c] = IAV_LOAD(n_k[c]);
        p[c] = o[c] + t * d[c];
        albedo[c] = IAV_CAT(vload, IA_VW)(0, albedo_k[c]);
        id_rgb[c] = IAV_CAT(vload, IA_VW)(0, id_k[c]);
    }
    for (int l = 0; l < EFFECTS_MAX_LIGHTS; l++) /* shade_effects reads the first nlights */
        vis[l] = l < nlights ? select(IAV_R(0), IAV_LOAD(seen_k[l]), hit) : IAV_R(0);
    ia_real units[EFFECTS_MAX_LIGHTS][3];
    shade_light_units(params, fx, units);
    shade_effects(fx, units, p, t, nv, d, vis, albedo, IAV_LOAD(specular_k), IAV_LOAD(shininess_k), id_rgb, lin);
    float top[3], bottom[3];
    for (int c = 0; c < 3; c++) {
        top[c] = (float)fx[EFFECTS_BG_TOP + c];
        bottom[c] = (float)fx[EFFECTS_BG_BOTTOM + c];
    }
    shade_background(IAV_CAT(convert_float, IA_VW)(IAV_LOAD(row_k)), height, top, bottom, bg);
    IAV_CAT(int, IA_VW) on = IAV_CAT(convert_int, IA_VW)(hit) != 0;
    float colour[3][IA_VW], back[3][IA_VW];
    for (int c = 0; c < 3; c++) {
        bg[c] *= bg[c];
        shade_colorv shown = select(bg[c], lin[c], on);
        if (rgb) /* clamped as fx_encode clamps (fmax takes 0 over NaN) */
            shown = sqrt(fmin(fmax(shown, 0.0f), 1.0f));
        IAV_CAT(vstore, IA_VW)(shown, 0, colour[c]);
        IAV_CAT(vstore, IA_VW)(bg[c], 0, back[c]);
    }
    for (int k = 0; k < IA_VW && first + k < n; k++)
        for (int c = 0; c < 3; c++) {
            if (rgb) {
                rgb[3 * (size_t)pixels[first + k] + c] = colour[c][k];
                continue;
            }
            out[6 * (first + k) + c] = colour[c][k];
            out[6 * (first + k) + 3 + c] = back[c][k];
        }
}
