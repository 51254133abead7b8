/* kernels/scene_effects.cl -- iacsg_scene_trace_rays, the segment path's secondary rays (src/render_effects.c):
 * shadow, reflected and antialiasing rays from the host's ray buffer (kernels/effects.h), each traced as a camera
 * ray is (scene_trace.h), one ray per work-item. The per-ray buffers have room for every solid of the scene
 * (src/render_scene.c, render_scene_trace_args), so no ray overflows. Out per ray: the claimed partition's start
 * (+inf when nothing is hit in [tn, tf] within the bounds), the unit normal there facing the ray, the item, and
 * where `evals` is not NULL the ray's interval evaluations (KERNEL_STATS). A ray continued through a transparent
 * region starts inside it and passes through it (passing[ray]: 1 + the region, weave.h).
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
                                     int nstates) {
    size_t slot = get_global_id(0);
    int ray = first_ray + (int)slot;
    if (ray >= nrays)
        return;
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    scene_view view = {bvh_box, bvh_link, nbvh, surfaces, nsurfaces, eps, time, 0};
    size_t c0 = slot * (size_t)cand_cap;
    scene_ray r = {.nodes = nodes,
                   .items = items,
                   .solid_items_start = solid_items_start,
                   .solid_items = solid_items,
                   .walks = {cand_solid + c0, cand_range + 2 * c0, cand_pos + c0, cand_level + c0, cand_index + c0,
                             cand_newton + c0, cand_newton_t + 2 * c0},
                   .cand_cap = cand_cap,
                   .state = state + slot * (size_t)nstates,
                   .passing = passing ? passing[ray] : 0};
    const __global ia_real *q = rays + EFFECTS_RAY_REALS * (size_t)ray;
    ia_real o[3] = {q[0], q[1], q[2]}, d[3] = {q[3], q[4], q[5]}, tn, tf;
    weave_hit hit = {0, -1, -1, -1};
    int found = camera_clip(params, o, d, &tn, &tf);
    tn = fmax(tn, q[6]);
    tf = fmin(tf, q[7]);
    found = found && tn <= tf && scene_trace_ray(&view, &r, o, d, tn, tf, &hit) == 1;
    hit_t[ray] = found ? hit.t : IA_INF;
    hit_item[ray] = found ? hit.item : -1;
    if (evals) /* counted with KERNEL_STATS (-stats) */
        evals[ray] = r.evals;
    ia_real g[3] = {0, 0, 0};
    if (found)
        scene_solid_f_grad(hit.solid, o[0] + hit.t * d[0], o[1] + hit.t * d[1], o[2] + hit.t * d[2],
                           params[PARAM_TIME_LO], &g[0], &g[1], &g[2]);
    ia_real len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), facing = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
    int ok = len > 0 && isfinite(len);
    for (int c = 0; c < 3; c++) /* facing the ray; -d where the gradient vanishes (as light.h's shade_normals) */
        normal[3 * ray + c] = (float)(!found ? 0 : ok ? (facing > 0 ? -g[c] : g[c]) / len : -d[c]);
}
