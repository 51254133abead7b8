/* kernels/scene_centre.cl -- the segment path's centre paths kept on the device (src/render_effects.c, where no
 * path can have a child and the camera kernel does not light them itself, -shade ids and depth; or each has at
 * most one child, which the device traces: see below), from the camera kernel's hits:
 *
 *   the listed pixels, PACKET_LANES per work-item --> each one's camera ray (camera_ray: the ray the camera kernel
 *   traced), its hit (the frame's depth, normal, id) and row: iacsg_scene_shade's inputs
 *   --> with shadows, per light where it is in front of the hit: the shadow ray from off the surface to it
 *       (effects.cl's, in lanes), staged at l n + i, and each work-item's count of them
 *   --> (the host sums the counts: each work-item's first place) iacsg_scene_centre_compact: the live rays in the
 *       host's order, light by light, path by path (neighbouring pixels' rays in a packet, none empty)
 *   --> iacsg_scene_trace_rays --> iacsg_scene_shade, a light seen where its ray met nothing.
 *   --> where `kind` is not NULL (no shadows; a path has at most one child), each hit's child by kind[item]
 *       (EFFECTS_KID_*, effects.h): its reflected ray from off its surface, or its ray on through it from
 *       just past it (passing the region it enters: kid_pass, weave.h), into `kids` at i (an empty ray, [1, 0],
 *       where it has none, or a miss) --> iacsg_scene_trace_rays --> iacsg_scene_shade: the children's colours.
 *
 * So no host pass builds a path, a camera ray in double, a shadow ray, a reflected ray or the shading's inputs.
 */

__kernel void iacsg_scene_centre(__constant ia_real *params, __constant ia_real *fx, int flags, int width, int height,
                                 __global const int *pixels, int n, __global const float *depth,
                                 __global const float *normal, __global const float *ids, int shadows, ia_real eps,
                                 __global ia_real *rays, __global ia_real *hit_t, __global float *hit_n,
                                 __global int *hit_item, __global float *vis, __global int *rows,
                                 __global ia_real *staged, __global int *counts, __global const int *kind,
                                 __global ia_real *kids, __global int *kid_pass) {
    int first = (int)get_global_id(0) * IA_VW;
    if (first >= n)
        return;
    ia_real col_k[IA_VW], row_k[IA_VW], n_k[3][IA_VW], t_k[IA_VW], on_k[IA_VW], mirror_k[IA_VW], through_k[IA_VW];
    for (int k = 0; k < IA_VW; k++) {
        int i = min(first + k, n - 1), pixel = pixels[i];
        float t = depth[pixel];
        int hit = !isinf(t);
        col_k[k] = pixel % width;
        row_k[k] = rows[i] = pixel / width;
        for (int c = 0; c < 3; c++)
            hit_n[3 * i + c] = n_k[c][k] = normal[3 * (size_t)pixel + c];
        hit_t[i] = t_k[k] = hit ? t : 0;
        hit_item[i] = hit ? (int)ids[pixel] : -1;
        on_k[k] = hit;
        int kid = kind && hit ? kind[(int)ids[pixel]] : EFFECTS_KID_NONE;
        mirror_k[k] = kid == EFFECTS_KID_REFLECTED;
        through_k[k] = kid == EFFECTS_KID_THROUGH || kid == EFFECTS_KID_THROUGH_REGION;
        if (kind && first + k < n)
            kid_pass[first + k] = kid == EFFECTS_KID_THROUGH_REGION ? 1 + (int)ids[pixel] : 0;
    }
    /* the camera rays in lanes (packet_camera.h: bit for bit camera_ray's, the camera kernel's rays) */
    ia_realv o[3], d[3], p[3], nv[3], t = IAV_LOAD(t_k);
    packet_rays(params, flags & RENDER_ORTHO, packet_to_int(IAV_LOAD(col_k)), packet_to_int(IAV_LOAD(row_k)), width,
                height, o, d);
    ia_real ray_k[EFFECTS_RAY_REALS][IA_VW];
    for (int c = 0; c < 3; c++) {
        nv[c] = IAV_LOAD(n_k[c]);
        p[c] = o[c] + t * d[c];
        IAV_STORE(o[c], ray_k[c]);
        IAV_STORE(d[c], ray_k[3 + c]);
    }
    for (int k = 0; k < IA_VW && first + k < n; k++) {
        for (int c = 0; c < 6; c++)
            rays[EFFECTS_RAY_REALS * (size_t)(first + k) + c] = ray_k[c][k];
        rays[EFFECTS_RAY_REALS * (size_t)(first + k) + 6] = 0;
        rays[EFFECTS_RAY_REALS * (size_t)(first + k) + 7] = IA_INF;
    }
    ia_maskv hit = IAV_LOAD(on_k) != 0;
    ia_realv so[3], off = effects_off_surface(eps, p, t, nv, so); /* on the side the normal faces (the ray's) */
    if (kind) { /* the mirror direction d - 2 (d.n) n from off the surface (as the shadow rays start), or d on
                 * from just past it */
        ia_realv dn = d[0] * nv[0] + d[1] * nv[1] + d[2] * nv[2], kd[3];
        for (int c = 0; c < 3; c++)
            kd[c] = d[c] - 2 * dn * nv[c];
        ia_realv len = sqrt(kd[0] * kd[0] + kd[1] * kd[1] + kd[2] * kd[2]);
        ia_maskv mirror = IAV_LOAD(mirror_k) != 0, through = IAV_LOAD(through_k) != 0, live = mirror | through;
        ia_real kid_k[EFFECTS_RAY_REALS][IA_VW];
        for (int c = 0; c < 3; c++) {
            ia_realv ko = select(select(IAV_R(0), p[c] - off * nv[c], through), so[c], mirror);
            IAV_STORE(ko, kid_k[c]);
            IAV_STORE(select(select(IAV_R(c == 2), d[c], through), kd[c] / len, mirror), kid_k[3 + c]);
        }
        IAV_STORE(select(IAV_R(1), IAV_R(0), live), kid_k[6]);
        IAV_STORE(select(IAV_R(0), IAV_R(IA_INF), live), kid_k[7]);
        for (int k = 0; k < IA_VW && first + k < n; k++)
            for (int c = 0; c < EFFECTS_RAY_REALS; c++)
                kids[EFFECTS_RAY_REALS * (size_t)(first + k) + c] = kid_k[c][k];
    }
    int nlights = (int)fx[EFFECTS_NLIGHTS];
    ia_real units[EFFECTS_MAX_LIGHTS][3];
    shade_light_units(params, fx, units);
    for (int l = 0; l < nlights; l++) { /* a light past nlights is never read (iacsg_scene_shade: shade_effects) */
        ia_realv seen = IAV_R(!shadows); /* without shadows every light, as the host's paths had it */
        if (shadows) {
            __constant ia_real *L = fx + EFFECTS_LIGHTS + EFFECTS_LIGHT_REALS * l;
            ia_realv sd[3];
            ia_maskv ray = shade_facing(L, units[l], p, nv, hit);
            ia_realv dist = shade_towards(L, units[l], so, sd);
            ia_real s_k[EFFECTS_RAY_REALS][IA_VW];
            for (int c = 0; c < 3; c++) {
                IAV_STORE(so[c], s_k[c]);
                IAV_STORE(sd[c], s_k[3 + c]);
            }
            IAV_STORE(IAV_R(0), s_k[6]);
            IAV_STORE(dist, s_k[7]);
            seen = select(IAV_R(0), IAV_R(1), ray);
            ia_real live_k[IA_VW];
            IAV_STORE(seen, live_k);
            int live = 0;
            for (int k = 0; k < IA_VW && first + k < n; k++) {
                live += live_k[k] != 0;
                for (int c = 0; live_k[k] != 0 && c < EFFECTS_RAY_REALS; c++)
                    staged[EFFECTS_RAY_REALS * ((size_t)l * n + first + k) + c] = s_k[c][k];
            }
            counts[l * ((n + IA_VW - 1) / IA_VW) + first / IA_VW] = live;
        }
        float seen_k[IA_VW];
        IAV_CAT(vstore, IA_VW)(IAV_CAT(convert_float, IA_VW)(seen), 0, seen_k);
        for (int k = 0; k < IA_VW && first + k < n; k++)
            vis[EFFECTS_MAX_LIGHTS * (first + k) + l] = seen_k[k];
    }
}

/* iacsg_scene_centre_compact: the live shadow rays (a light in front of the hit) of work-item g of
 * iacsg_scene_centre moved from `staged` to their places in the host's order (light by light, path by path:
 * offsets[l groups + g], the exclusive prefix sum of the counts), so that each packet of the trace holds 16 live
 * rays of neighbouring pixels; slot[l n + i]: the place of ray (l, i), -1 where there is none. */
__kernel void iacsg_scene_centre_compact(int n, int nlights, __global const float *vis, __global const int *offsets,
                                         __global const ia_real *staged, __global ia_real *rays,
                                         __global int *slot) {
    int g = (int)get_global_id(0), groups = (n + IA_VW - 1) / IA_VW, first = g * IA_VW;
    if (first >= n)
        return;
    for (int l = 0; l < nlights; l++) {
        int at = offsets[l * groups + g];
        for (int k = 0; k < IA_VW && first + k < n; k++) {
            size_t i = (size_t)(first + k);
            int live = vis[EFFECTS_MAX_LIGHTS * i + l] != 0;
            slot[(size_t)l * n + i] = live ? at : -1;
            for (int c = 0; live && c < EFFECTS_RAY_REALS; c++)
                rays[EFFECTS_RAY_REALS * (size_t)at + c] = staged[EFFECTS_RAY_REALS * ((size_t)l * n + i) + c];
            at += live;
        }
    }
}
