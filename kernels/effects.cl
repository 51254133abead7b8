/* kernels/effects.cl -- iacsg_trace_rays, the first-root path's secondary rays (src/render_effects.c): shadow
 * rays, reflected rays, rays continuing through transparent hits and the extra rays of antialiasing, listed by
 * the host in a buffer, traced by the same bisection as the camera rays (packet.h), 16 rays per work-item in SIMD
 * lanes. The host lists them in blocks of neighbouring pixels, so that a packet's rays walk similar nodes.
 *
 * A ray is EFFECTS_RAY_REALS reals: origin (3), direction (3), and the part [tn, tf] to search (then clipped to
 * the bounds). Its tree is [0, root_w], root_w past every ray's exit from the bounds. Out: the start of the hit
 * leaf (+inf on a miss), never after the ray's first root in [tn, tf] within the bounds (packet.h's guarantee),
 * and, where `normal` is not NULL, the unit normal there facing the ray (0 on a miss); where `evals` is not NULL,
 * the ray's interval evaluations (counted in a kernel built with KERNEL_STATS). The normals are render.cl's
 * packet_gradients (this file is appended to the first-root path's program after render.cl).
 */

/* The groups of a union that matter, per segment of a secondary ray's tree: all of them (`all_groups`, SEGMENTS
 * ones), since no tile pass bounded these rays. */
__kernel void iacsg_trace_rays(__constant ia_real *params, __global const ia_real *rays, int nrays, ia_real root_w,
                               ia_real eps, ia_real footprint, __global const ulong *all_groups,
                               __global ia_real *hit_t, __global float *normal, __global uint *evals) {
    int first = (int)get_global_id(0) * IA_VW;
    if (first >= nrays)
        return;
    ia_real o_k[3][IA_VW], d_k[3][IA_VW], tn_k[IA_VW], tf_k[IA_VW], valid_k[IA_VW];
    for (int k = 0; k < IA_VW; k++) {
        int ray = min(first + k, nrays - 1);
        for (int c = 0; c < 3; c++) {
            o_k[c][k] = rays[EFFECTS_RAY_REALS * ray + c];
            d_k[c][k] = rays[EFFECTS_RAY_REALS * ray + 3 + c];
        }
        tn_k[k] = rays[EFFECTS_RAY_REALS * ray + 6];
        tf_k[k] = rays[EFFECTS_RAY_REALS * ray + 7];
        valid_k[k] = first + k < nrays;
    }
    ia_realv o[3], d[3], t_near, t_far;
    for (int c = 0; c < 3; c++) {
        o[c] = IAV_LOAD(o_k[c]);
        d[c] = IAV_LOAD(d_k[c]);
    }
    ia_maskv searching = (IAV_LOAD(valid_k) != 0) & packet_clip(params, o, d, &t_near, &t_far);
    t_near = fmax(t_near, IAV_LOAD(tn_k));
    t_far = fmin(t_far, IAV_LOAD(tf_k));
    searching &= t_near <= t_far;
    ia_realv lo = IAV_R(0), hi = IAV_R(0);
    packet_index counts = (packet_index)0;
    ia_real time = params[PARAM_TIME_LO];
    ia_maskv hit = packet_first_root(all_groups, o, d, 0, root_w, (packet_int)0, (packet_index)0, t_near, t_far,
                                     searching, eps, footprint, 0, iav_const(time, params[PARAM_TIME_HI]), &lo, &hi,
                                     &counts);
    ia_real t_out[IA_VW], n_out[3][IA_VW];
    bisect_index count[IA_VW];
    IAV_STORE(counts, count);
    IAV_STORE(select(IAV_R(IA_INF), lo, hit), t_out);
    if (normal) {
        ia_realv g[3] = {IAV_R(0), IAV_R(0), IAV_R(0)}, n[3];
        if (iav_any(hit))
            packet_gradients(all_groups, 0, root_w, hit, o, d, lo * (ia_real)0.5 + hi * (ia_real)0.5, time, g);
        shade_normals(g, d, n);
        for (int c = 0; c < 3; c++)
            IAV_STORE(select(IAV_R(0), n[c], hit), n_out[c]);
    }
    for (int k = 0; k < IA_VW && first + k < nrays; k++) {
        hit_t[first + k] = t_out[k];
        if (normal)
            for (int c = 0; c < 3; c++)
                normal[3 * (first + k) + c] = (float)n_out[c][k];
        if (evals) /* with KERNEL_STATS (-stats); else 0 */
            evals[first + k] = (uint)count[k];
    }
}
