/* kernels/scene_effects.cl -- the segment path's effects (src/render_effects.c): its secondary rays
 * (iacsg_scene_trace_rays) and the colours of their hits (iacsg_scene_shade).
 *
 * iacsg_scene_trace_rays: shadow and reflected rays and transparent layers from the host's ray buffer
 * (kernels/effects.h), PACKET_LANES consecutive rays per work-item (the host lists them from neighbouring pixels).
 * Where the program has the regions' union and they are disjoint (scene_union.h), the packet's rays that start
 * outside every region find the union's first root in SIMD lanes, marching off the surface they leave (march.h),
 * and claim their region at its leaf, as the camera rays do; a transparent layer's ray, which starts inside the
 * region it passes through (passing[ray]: 1 + the region, weave.h), finds where it leaves it in lanes too, and the
 * next region on (scene_rays_union); the others, and a leaf no region claims, are woven one at a time as a camera
 * ray is (scene_trace.h). The per-ray buffers have room for every solid of the scene (src/render_scene.c,
 * render_scene_trace_args), so no ray overflows. Out per ray: the claimed partition's start (+inf when nothing is
 * hit in [tn, tf] within the bounds), the unit normal there facing the ray, the item, and where `evals` is not
 * NULL the ray's interval evaluations (KERNEL_STATS). With `whether` (the scene's items all opaque: shadow rays), a
 * ray whose march proves g crossing 0 ends there without its leaf, item EFFECTS_HIT_BLOCKED, t before the
 * crossing.
 */

#if defined(SCENE_REGIONS_DISJOINT) && defined(SCENE_UNION_PREPASS)
#define SCENE_RAYS_MARCH 1
/* g's first root on the lanes of `walking` over [a, b]: with `march`, the march off the surface the ray leaves
 * (march.h: `leaving` is the start's distance from it), then for the lanes it hands over (all of them without
 * `march`) bisection with Newton from any node; *lo, *hi its leaf (with `whether`, a part where g crosses 0, wider
 * than a leaf). */
static ia_maskv scene_rays_root(const ia_realv o[3], const ia_realv d[3], ia_realv a, ia_realv b, ia_maskv walking,
                                int march, ia_realv leaving, ia_real eps, int whether, iav time, ia_realv *lo,
                                ia_realv *hi, packet_index *counts) {
    ia_maskv hit = (ia_maskv)0;
#ifdef PACKET_FDV
    if (march)
        hit = effects_march(o, d, &a, &b, &walking, leaving, eps, whether, time, lo, hi, counts);
#else
    if (march)
        hit = march_enclosure(o, d, &a, b, &walking, leaving, eps, whether, time, lo, hi, counts);
#endif
    ia_real w = march_farthest(b, walking);
    if (iav_any(walking)) /* a tree as long as the farthest ray; Newton from any node */
        hit |= packet_first_root(0, o, d, 0, w, (packet_int)0, (packet_index)0, a, b, walking, eps, IA_INF, 0, time,
                                 lo, hi, counts);
    return hit;
}

/* The lanes of `lanes` whose states (scene_union_states) let a region other than pass_k[k] - 1 be in. */
static ia_maskv scene_rays_other(scene_ray *r, const int states[SCENE_REGIONS_UNION][PACKET_LANES],
                                 const ia_real pass_k[PACKET_LANES], ia_maskv lanes) {
    ia_real on[IA_VW], other[IA_VW];
    IAV_STORE(select(IAV_R(0), IAV_R(1), lanes), on);
    for (int k = 0; k < IA_VW; k++) {
        int item, solid;
        other[k] = on[k] != 0 && scene_union_first(r, states, k, (int)pass_k[k] - 1, &item, &solid) != 0;
    }
    return IAV_LOAD(other) != 0;
}

/* Where the packet's rays (ok, dk over [tn, tf]) where meets[k] is not 0 meet a region first, in lanes, and which
 * region the claim there may not be (pass_k[k], in: 1 + the region a transparent layer's ray passes through,
 * weave.h, else 0; out: the ray's `passing` from `from` on). evals: each lane's evaluations.
 * - A ray that starts outside every region (g > 0 at t_near, its enclosure at the point): g's first root
 *   (scene_rays_root); no region is in before it (g is continuous, and a region is in only where g <= 0,
 *   scene_union.h).
 * - A transparent layer's ray (not `whether`: some item is transparent) that starts inside the region it passes through
 *   (g < 0 at t_near, and no other region may be in there): g's first root, the leaf where it leaves the region, by
 *   bisection alone (Fig. 2's glass: the march took 26.9 evaluations of g's derivative code a ray to that leaf, closing
 *   in on x^500's wall from inside, each some 2.5 of g's enclosure). g < 0 all the way there: no region's boundary is
 *   crossed (g is 0 on each, the regions being disjoint), so the ray stays in its region. Where another region may be
 *   in over that leaf (a region touching it), the leaf is claimed, not by the region passed through. Else, where g > 0
 *   at the leaf's end (the ray has left every region: the weave would claim again from there), g's first root from
 *   there on (marching), claimed by any region.
 * Out: the leaf [from, leaf_hi] and the solids' states over it (scene_union_states) for scene_union_claim; from
 * +inf where no region is on the ray, from t_near or from a leaf with leaf_hi -inf for the lanes left to the weave
 * from there; with `whether` (the scene's items all opaque), crossed_k 1 where g certainly crosses 0 in [from,
 * leaf_hi]. */
static void scene_rays_union(scene_ray *r, __constant ia_real *params, ia_real eps, int whether,
                             const ia_real ok[3][PACKET_LANES], const ia_real dk[3][PACKET_LANES],
                             const ia_real tn[PACKET_LANES], const ia_real tf[PACKET_LANES],
                             const ia_real meets[PACKET_LANES], ia_real pass_k[PACKET_LANES],
                             ia_real from[PACKET_LANES], ia_real leaf_hi[PACKET_LANES], ia_real crossed_k[PACKET_LANES],
                             int states[SCENE_REGIONS_UNION][PACKET_LANES], kernel_u32 evals[PACKET_LANES]) {
    ia_realv o[3], d[3], t_near = IAV_LOAD(tn), t_far = IAV_LOAD(tf), pass = IAV_LOAD(pass_k);
    for (int c = 0; c < 3; c++) {
        o[c] = IAV_LOAD(ok[c]);
        d[c] = IAV_LOAD(dk[c]);
    }
    iav time = iav_const(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    packet_index counts = (packet_index)0;
    ia_maskv on = IAV_LOAD(meets) != 0, passing = on & (pass > 0), outside = (ia_maskv)0, inside = (ia_maskv)0;
    if (whether)
        on &= ~passing;
    if (iav_any(on)) {
        iav g = scene_union_g_at(o, d, t_near, time);
        PACKET_COUNT(counts, on);
        outside = on & ~passing & (g.lo > 0);
        inside = passing & (g.hi < 0);
    }
    if (iav_any(inside)) { /* in no region but its own at t_near */
        scene_union_states(o, d, t_near, t_near, inside, time, states, &counts);
        inside &= ~scene_rays_other(r, states, pass_k, inside);
    }
    ia_realv leaving = effects_offset(eps, o, IAV_R(0)); /* the start's distance off its hit (offset_of) */
    ia_realv lo = IAV_R(0), hi = IAV_R(0), out_from = t_near, out_hi = IAV_R(-IA_INF);
    ia_maskv hit = (ia_maskv)0, crossed = (ia_maskv)0;
    if (iav_any(outside | inside)) {
        hit = scene_rays_root(o, d, t_near, t_far, outside, 1, leaving, eps, whether, time, &lo, &hi, &counts);
        if (iav_any(inside)) /* no march (see above) */
            hit |= scene_rays_root(o, d, t_near, t_far, inside, 0, leaving, eps, 0, time, &lo, &hi, &counts);
        crossed = hit & (hi - lo > eps); /* `whether`: a part where g crosses 0, not a leaf */
        hit &= ~crossed;
        out_from = select(out_from, select(IAV_R(IA_INF), lo, hit | crossed), outside | inside);
        out_hi = select(out_hi, hi, hit);
    }
    ia_maskv exit = inside & hit, beyond = (ia_maskv)0;
    if (iav_any(exit)) { /* the leaf where the layer's ray leaves its region, claimed by a region touching it */
        scene_union_states(o, d, lo, hi, exit, time, states, &counts);
        ia_maskv left = exit & ~scene_rays_other(r, states, pass_k, exit);
        out_hi = select(out_hi, IAV_R(-IA_INF), left); /* else woven from the leaf on, passing through */
        if (iav_any(left)) {
            PACKET_COUNT(counts, left);
            beyond = left & (scene_union_g_at(o, d, hi, time).lo > 0);
        }
    }
    if (iav_any(beyond)) { /* out of every region: the next root of g, claimed by any region */
        ia_realv lo2 = IAV_R(0), hi2 = IAV_R(0);
        ia_maskv hit2 = scene_rays_root(o, d, hi, t_far, beyond, 1, leaving, eps, 0, time, &lo2, &hi2, &counts);
        out_from = select(out_from, select(IAV_R(IA_INF), lo2, hit2), beyond);
        out_hi = select(out_hi, hi2, beyond & hit2);
        pass = select(pass, IAV_R(0), beyond);
        if (iav_any(beyond & hit2))
            scene_union_states(o, d, lo2, hi2, beyond & hit2, time, states, &counts);
    }
    if (iav_any(hit & outside))
        scene_union_states(o, d, fmax(t_near, lo), hi, hit & outside, time, states, &counts);
    IAV_STORE(select(IAV_R(0), IAV_R(1), crossed), crossed_k);
    IAV_STORE(out_from, from);
    IAV_STORE(out_hi, leaf_hi);
    IAV_STORE(pass, pass_k);
    bisect_index count[IA_VW];
    IAV_STORE(counts, count);
    for (int k = 0; k < IA_VW; k++)
        evals[k] = (kernel_u32)count[k];
}
#endif

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
    ia_real ok[3][PACKET_LANES], dk[3][PACKET_LANES], ik[3][PACKET_LANES], tn[PACKET_LANES], tf[PACKET_LANES];
    ia_real meets[PACKET_LANES], pass[PACKET_LANES], from[PACKET_LANES], leaf_hi[PACKET_LANES];
    ia_real crossed[PACKET_LANES];
    kernel_u32 from_evals[PACKET_LANES];
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
        from[k] = leaf_hi[k] = -IA_INF;
        crossed[k] = 0;
        from_evals[k] = 0;
    }
    { /* the part in the bounds (camera_clip, in lanes: packet_clip) and the inverse directions */
        ia_realv o[3], d[3], t_near, t_far;
        for (int c = 0; c < 3; c++) {
            o[c] = IAV_LOAD(ok[c]);
            d[c] = IAV_LOAD(dk[c]);
            IAV_STORE((ia_real)1 / d[c], ik[c]);
        }
        ia_maskv in = packet_clip(params, o, d, &t_near, &t_far) & (IAV_LOAD(meets) != 0);
        t_near = fmax(t_near, IAV_LOAD(tn));
        t_far = fmin(t_far, IAV_LOAD(tf));
        IAV_STORE(t_near, tn);
        IAV_STORE(t_far, tf);
        IAV_STORE(select(IAV_R(0), IAV_R(1), in & (t_near <= t_far)), meets);
    }
#ifdef SCENE_RAYS_MARCH
    int states[SCENE_REGIONS_UNION][PACKET_LANES] = {{0}};
    scene_rays_union(&r, params, eps, whether, ok, dk, tn, tf, meets, pass, from, leaf_hi, crossed, states,
                     from_evals);
#else
    (void)whether;
#endif
    for (int k = 0; k < PACKET_LANES && first + k < nrays; k++) {
        int ray = first + k;
        ia_real o[3] = {ok[0][k], ok[1][k], ok[2][k]}, d[3] = {dk[0][k], dk[1][k], dk[2][k]};
        bvh_ray br = bvh_ray_lane(dk, ik, k);
        weave_hit hit = {0, -1, -1, -1};
        r.evals = 0;
        r.passing = (int)pass[k]; /* from `from` on */
        int found = 0, claimed = 0;
        if (crossed[k] != 0) { /* certainly blocked (`whether`) */
            found = 1;
            hit.t = from[k];
            hit.item = EFFECTS_HIT_BLOCKED;
        } else if (meets[k] != 0) {
#ifdef SCENE_RAYS_MARCH
            if (leaf_hi[k] >= from[k])
                claimed = scene_union_claim(&r, states, k, r.passing - 1, fmax(tn[k], from[k]), &hit);
#endif
            if (claimed < 0)
                r.passing = passing ? passing[ray] : 0;
            /* no overflow: the buffers hold every solid (the claim's overflow would be woven from t_near) */
            found = claimed > 0 ? scene_trace_surfaces(&view, &r, o, d, tn[k], tf[k], 1, &hit)
                                : scene_trace_ray_from(&view, &r, o, d, &br, tn[k],
                                                       claimed < 0 ? tn[k] : fmax(tn[k], from[k]), tf[k], &hit);
        }
        found = found == 1;
        hit_t[ray] = found ? hit.t : IA_INF;
        hit_item[ray] = found ? hit.item : -1;
        if (evals) /* counted with KERNEL_STATS (-stats) */
            evals[ray] = r.evals + from_evals[k];
        ia_real g[3] = {0, 0, 0};
        if (found && hit.solid >= 0)
            scene_solid_f_grad(prims, hit.solid, o[0] + hit.t * d[0], o[1] + hit.t * d[1], o[2] + hit.t * d[2],
                               params[PARAM_TIME_LO], &g[0], &g[1], &g[2]);
        ia_real len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), facing = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
        int ok_g = len > 0 && isfinite(len);
        for (int c = 0; c < 3; c++) /* facing the ray; -d where the gradient vanishes (as light.h's shade_normals) */
            normal[3 * ray + c] = (float)(!found ? 0 : ok_g ? (facing > 0 ? -g[c] : g[c]) / len : -d[c]);
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
