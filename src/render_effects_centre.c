/* src/render_effects_centre.c -- see render_effects_centre.h:
 *
 *   iacsg_scene_centre (the listed pixels' camera rays in lanes, their shading inputs, their shadow rays staged and
 *   counted per work-item) --> the counts summed on the host (centre_offsets) --> iacsg_scene_centre_compact (the
 *   live shadow rays in the host's order) --> the scene's trace kernel --> iacsg_scene_shade
 *   --> with `children` (at most one a path): the reflected or transmitted rays that iacsg_scene_centre made --> the
 *   trace kernel --> iacsg_scene_shade of their hits (each lit by every light, as its parent: no shadows) --> the
 *   weighted sums of the two colours; the children whose hits have children go back to the host's paths.
 */
#include "render_effects_centre.h"
#include "kernels/effects.h"
#include "kernels/params.h"
#include "kernels/scene_data.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The centre paths' shadow rays: their work-items' counts (iacsg_scene_centre, nl a work-item, light by light) read
 * back and summed into each one's first place (offsets, into *mem); returns how many there are, or -1 on an error. */
static long centre_offsets(fx_tracer *t, cl_mem counts, size_t groups, size_t nl, cl_mem *mem, iacsg_error *err) {
    cl_int *at = malloc(nl * groups * sizeof *at + 1), rc = CL_OUT_OF_HOST_MEMORY;
    long total = 0;
    if (at)
        rc = clEnqueueReadBuffer(t->r->rt.queue, counts, CL_TRUE, 0, nl * groups * sizeof *at, at, 0, NULL, NULL);
    for (size_t g = 0; rc == CL_SUCCESS && g < nl * groups; g++) { /* exclusive prefix sum, in place */
        cl_int c = at[g];
        at[g] = (cl_int)total;
        total += c;
    }
    if (rc == CL_SUCCESS)
        *mem = clCreateBuffer(t->r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, nl * groups * sizeof *at + 1,
                              at, &rc);
    free(at);
    if (rc != CL_SUCCESS) {
        clrt_record(err, rc, "the centre paths' shadow rays", __func__, __LINE__);
        return -1;
    }
    return total;
}

/* With -stats: the evaluations of the m rays traced (evals), `live` of them not empty, into t's counts as the host's
 * rays were. */
static iacsg_status count_centre_rays(fx_tracer *t, cl_mem evals, size_t m, size_t live, iacsg_error *err) {
    cl_uint *each = malloc(m * sizeof *each + 1);
    cl_int rc = !each ? CL_OUT_OF_HOST_MEMORY
                      : clEnqueueReadBuffer(t->r->rt.queue, evals, CL_TRUE, 0, m * sizeof *each, each, 0, NULL, NULL);
    for (size_t j = 0; rc == CL_SUCCESS && j < m; j++)
        t->evals += each[j];
    t->rays += rc == CL_SUCCESS ? (long long)live : 0;
    free(each);
    return rc == CL_SUCCESS ? IACSG_OK : clrt_record(err, rc, "the centre paths' counts", __func__, __LINE__);
}

/* Launches kernel k over `global` work-items, one a group (global 0: one that does nothing, so that PoCL compiles
 * it), after setting its arguments: values[a] of sizes[a] bytes, a cl_mem where bit a of `mems` is set (NULL where
 * it is NULL). */
static iacsg_status launch_with(iacsg_renderer *r, cl_kernel k, size_t global, int count, const size_t *sizes,
                                const void *const *values, unsigned long mems, const char *what, iacsg_error *err) {
    cl_int rc = CL_SUCCESS;
    for (int a = 0; a < count && rc == CL_SUCCESS; a++) {
        int null_mem = (mems >> a & 1) && !*(const cl_mem *)values[a];
        rc = clSetKernelArg(k, (cl_uint)a, null_mem ? sizeof(cl_mem) : sizes[a], null_mem ? NULL : values[a]);
    }
    size_t local = 1;
    global = global > 0 ? global : 1;
    if (rc == CL_SUCCESS)
        rc = clEnqueueNDRangeKernel(r->rt.queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
    return rc == CL_SUCCESS ? IACSG_OK : clrt_record(err, rc, what, __func__, __LINE__);
}

/* The child a centre hit on each item gets (EFFECTS_KID_*, kernels/effects.h), as shade_generation decides for a
 * path of weight 1 at the first generation (fx_path_weights); NULL when out of memory. */
static cl_int *kid_kinds(const render_fx *fx, int max_bounces) {
    cl_int *kind = malloc((size_t)fx->nitems * sizeof *kind + 1);
    for (int i = 0; kind && i < fx->nitems; i++) {
        fx_weights w = fx_path_weights(&fx->items[i], 1, 0, 0, max_bounces);
        kind[i] = w.mirror > 0    ? EFFECTS_KID_REFLECTED
                  : w.through > 0 ? (fx->items[i].region ? EFFECTS_KID_THROUGH_REGION : EFFECTS_KID_THROUGH)
                                  : EFFECTS_KID_NONE;
    }
    return kind;
}

/* A centre path's child i as the host's path of it (its ray and hit read back from the device: float to double
 * and back is exact), weight w. */
static fx_path kid_path(const iacsg_renderer *r, const void *rays, const void *t, const float *normal,
                        const cl_int *item, const cl_int *pass, size_t i, int pixel, double w, int reflected) {
    fx_path q = {.pixel = pixel, .w = w, .bounces = reflected, .layers = !reflected};
    double v[EFFECTS_RAY_REALS];
    for (int k = 0; k < EFFECTS_RAY_REALS; k++)
        v[k] = r->config.fp64 ? ((const double *)rays)[EFFECTS_RAY_REALS * i + (size_t)k]
                              : ((const float *)rays)[EFFECTS_RAY_REALS * i + (size_t)k];
    q.ray = (fx_ray){{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v[7], pass[i]};
    q.hit.t = r->config.fp64 ? ((const double *)t)[i] : ((const float *)t)[i];
    memcpy(q.hit.n, normal + 3 * i, sizeof q.hit.n);
    q.hit.item = isinf(q.hit.t) ? -1 : item[i];
    return q;
}

/* Reads device buffer m (bytes) into host memory *to (malloc'd; the caller frees it). */
static cl_int read_back(cl_command_queue q, cl_mem m, size_t bytes, void **to) {
    *to = malloc(bytes + 1);
    return *to ? clEnqueueReadBuffer(q, m, CL_TRUE, 0, bytes, *to, 0, NULL, NULL) : CL_OUT_OF_HOST_MEMORY;
}

/* The children of fx_scene_centre: the n rays `kids` (iacsg_scene_centre's, some empty; kid_pass their passing)
 * traced, their hits shaded with their parents' light fractions and rows (hits[4], hits[5]), and added to the
 * paths' colours in out (6 floats a path) as the host's paths add them (fx_path_weights, each weighted colour
 * rounded to float in turn). A child whose hit has a child of its own goes to rest (*nrest of them) instead, for
 * the host's paths to shade and follow. With -stats, the children counted as rays. */
static iacsg_status centre_kids(fx_tracer *t, const double *block, const cl_mem hits[6], cl_mem kids,
                                cl_mem kid_pass, size_t n, void *eps_real, const float *palette, const int *pixels,
                                const iacsg_frame *frame, float *out, fx_path *rest, size_t *nrest,
                                iacsg_error *err) {
    iacsg_renderer *r = t->r;
    int max_bounces = t->view->effects->bounces;
    size_t rb = fx_real_bytes(r);
    size_t bytes[4] = {n * rb, 3 * n * sizeof(float), n * sizeof(cl_int), n * sizeof(cl_uint)};
    cl_mem kh[4] = {0}; /* their t, normals, items, evaluations */
    void *back[5] = {0}; /* read back: their items, then for rest their rays, t, normals and passing */
    float *kid_out = malloc(6 * n * sizeof *kid_out);
    cl_int rc = kid_out ? CL_SUCCESS : CL_OUT_OF_HOST_MEMORY;
    for (int b = 0; b < 4 && rc == CL_SUCCESS; b++)
        if (b < 3 || r->config.stats)
            kh[b] = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE, bytes[b], NULL, &rc);
    iacsg_status st = rc == CL_SUCCESS ? IACSG_OK : clrt_record(err, rc, "clCreateBuffer(kids)", __func__, __LINE__);
    fx_trace_buffers b = {kids, kh[0], kh[1], kh[2], kh[3], kid_pass};
    if (st == IACSG_OK)
        st = fx_launch_scene(t, r->fx->trace, &b, (cl_int)n, eps_real, 0, err);
    const cl_mem kid_hits[6] = {kids, kh[0], kh[1], kh[2], hits[4], hits[5]};
    if (st == IACSG_OK)
        st = fx_shade_launch(t, block, kid_hits, NULL, NULL, n, palette, kid_out, NULL, NULL, err);
    if (st == IACSG_OK && (rc = read_back(r->rt.queue, kh[2], bytes[2], &back[0])) != CL_SUCCESS)
        st = clrt_record(err, rc, "the children's items", __func__, __LINE__);
    const cl_int *kid_item = back[0];
    const cl_mem rest_mem[4] = {kids, kh[0], kh[1], kid_pass};
    size_t rest_bytes[4] = {n * EFFECTS_RAY_REALS * rb, bytes[0], bytes[1], n * sizeof(cl_int)}, live = 0;
    *nrest = 0;
    for (size_t i = 0; st == IACSG_OK && i < n; i++) {
        int item = isinf(frame->depth[pixels[i]]) ? -1 : (int)frame->ids[pixels[i]];
        if (item < 0)
            continue; /* a miss: its background, weight 1 */
        fx_weights w0 = fx_path_weights(&r->fx->items[item], 1, 0, 0, max_bounces);
        float *colour = out + 6 * i, *kid = kid_out + 6 * i;
        double wk = w0.mirror + w0.through; /* at most one of them (render_effects.c: children_on_device) */
        fx_weights w1 = {wk, 0, 0, 0};      /* a child that misses: its background */
        int k1 = wk > 0 ? kid_item[i] : -1;
        if (wk > 0 && k1 >= 0)
            w1 = fx_path_weights(&r->fx->items[k1], wk, w0.mirror > 0, w0.through > 0, max_bounces);
        for (int c = 0; c < 3; c++) {
            colour[c] = (float)(w0.shown * colour[c]);
            colour[c] += w0.left > 0 ? (float)(w0.left * colour[3 + c]) : 0;
        }
        live += wk > 0;
        if (w1.mirror > 0 || w1.through > 0) { /* the children's rays and hits read back at the first such */
            for (int m = 0; m < 4 && st == IACSG_OK && !back[4]; m++)
                if ((rc = read_back(r->rt.queue, rest_mem[m], rest_bytes[m], &back[1 + m])) != CL_SUCCESS)
                    st = clrt_record(err, rc, "the children with children", __func__, __LINE__);
            if (st == IACSG_OK)
                rest[(*nrest)++] = kid_path(r, back[1], back[2], back[3], kid_item, back[4], i, pixels[i], wk,
                                            w0.mirror > 0);
            continue;
        }
        for (int c = 0; c < 3 && wk > 0; c++) {
            colour[c] += (float)(w1.shown * kid[c]);
            colour[c] += w1.left > 0 ? (float)(w1.left * kid[3 + c]) : 0;
        }
    }
    if (st == IACSG_OK && r->config.stats)
        st = count_centre_rays(t, kh[3], n, live, err);
    fx_release_all(kh, 4);
    for (int m = 0; m < 5; m++)
        free(back[m]);
    free(kid_out);
    return st;
}

iacsg_status fx_scene_centre(fx_tracer *t, const double *block, const int *pixels, size_t n,
                             const iacsg_frame *frame, int shadows, double eps, const float *palette,
                             int children, float *out, fx_path *rest, size_t *nrest, iacsg_error *err) {
    iacsg_renderer *r = t->r;
    const iacsg_view *v = t->view;
    size_t rb = fx_real_bytes(r), area = (size_t)v->width * v->height, lanes = (size_t)render_packet_lanes(r);
    size_t groups = (n + lanes - 1) / lanes;
    size_t nl = shadows ? (size_t)block[EFFECTS_NLIGHTS] : 0, bytes[6];
    fx_shade_parts(r, n, bytes);
    /* in: the pixels, the frame's depth, normals, ids; the hits' arrays (fx_shade_parts); the shadow rays staged, the
     * work-items' counts of them, their places; then the live ones, their t, normals, items and evaluations */
    cl_mem in[4] = {0}, hits[6] = {0}, stage[4] = {0}, sh[5] = {0}, fx = NULL, kid[3] = {0}; /* kinds, rays, passing */
    const void *in_host[4] = {pixels, frame ? frame->depth : NULL, frame ? frame->normal : NULL,
                              frame ? frame->ids : NULL};
    size_t in_bytes[4] = {n * sizeof(int), area * sizeof(float), 3 * area * sizeof(float), area * sizeof(float)};
    size_t stage_bytes[3] = {nl * n * EFFECTS_RAY_REALS * rb, nl * groups * sizeof(cl_int), nl * n * sizeof(cl_int)};
    cl_int rc = CL_SUCCESS;
    for (int b = 0; b < 4 && rc == CL_SUCCESS && n > 0; b++)
        in[b] = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, in_bytes[b], (void *)in_host[b],
                               &rc);
    for (int b = 0; b < 6 && rc == CL_SUCCESS && n > 0; b++)
        hits[b] = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE, bytes[b], NULL, &rc);
    for (int b = 0; b < 3 && rc == CL_SUCCESS && nl * n > 0; b++)
        stage[b] = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE, stage_bytes[b], NULL, &rc);
    cl_int *kinds = children && n > 0 ? kid_kinds(r->fx, v->effects->bounces) : NULL;
    if (children && n > 0 && !kinds)
        rc = CL_OUT_OF_HOST_MEMORY;
    size_t kid_bytes[3] = {(size_t)r->fx->nitems * sizeof(cl_int) + 1, n * EFFECTS_RAY_REALS * rb, n * sizeof(cl_int)};
    for (int b = 0; b < 3 && rc == CL_SUCCESS && kinds; b++)
        kid[b] = clCreateBuffer(r->rt.context, b == 0 ? CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR : CL_MEM_READ_WRITE,
                                kid_bytes[b], b == 0 ? (void *)kinds : NULL, &rc);
    char eps_real[sizeof(double)], reals[EFFECTS_COUNT * sizeof(double)];
    fx_put_real(r, eps_real, 0, eps);
    for (int k = 0; k < EFFECTS_COUNT; k++)
        fx_put_real(r, reals, (size_t)k, block[k]);
    if (rc == CL_SUCCESS && n > 0)
        fx = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, EFFECTS_COUNT * rb, reals, &rc);
    iacsg_status st = rc == CL_SUCCESS ? IACSG_OK : clrt_record(err, rc, "clCreateBuffer(centre)", __func__, __LINE__);
    cl_int flags = v->camera.ortho_height > 0 ? RENDER_ORTHO : 0, width = v->width, height = v->height;
    cl_int count = (cl_int)n, with_shadows = shadows, lights = (cl_int)nl;
    const void *values[23] = {&t->params, &fx,      &flags,   &width,   &height,  &in[0],    &count,    &in[1],
                              &in[2],     &in[3],   &with_shadows,      eps_real, &hits[0], &hits[1],  &hits[2],
                              &hits[3],   &hits[4], &hits[5], &stage[0], &stage[1], &kid[0], &kid[1],  &kid[2]};
    unsigned long mems = 0x7ffffful & ~(1ul << 2 | 1ul << 3 | 1ul << 4 | 1ul << 6 | 1ul << 10 | 1ul << 11);
    size_t sizes[23];
    for (int a = 0; a < 23; a++)
        sizes[a] = mems >> a & 1 ? sizeof(cl_mem) : a == 11 ? rb : sizeof(cl_int);
    if (st == IACSG_OK)
        st = launch_with(r, r->fx->centre, groups, 23, sizes, values, mems, "iacsg_scene_centre", err);
    const void *compact_values[7] = {&count, &lights, &hits[4], &stage[3], &stage[0], &sh[0], &stage[2]};
    size_t compact_sizes[7] = {sizeof(cl_int), sizeof(cl_int), sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem),
                               sizeof(cl_mem), sizeof(cl_mem)};
    long m = 0;
    if (st == IACSG_OK && n == 0) /* only compiling: the compaction's kernel too */
        st = launch_with(r, r->fx->compact, 0, 7, compact_sizes, compact_values, 0x7c, "iacsg_scene_centre_compact",
                         err);
    if (st == IACSG_OK && nl * n > 0 && (m = centre_offsets(t, stage[1], groups, nl, &stage[3], err)) < 0)
        st = IACSG_ERR_OPENCL;
    size_t sh_bytes[5] = {(size_t)m * EFFECTS_RAY_REALS * rb, (size_t)m * rb, 3 * (size_t)m * sizeof(float),
                          (size_t)m * sizeof(cl_int), (size_t)m * sizeof(cl_uint)};
    for (int b = 0; b < 5 && st == IACSG_OK && m > 0; b++)
        if (b < 4 || r->config.stats) {
            sh[b] = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE, sh_bytes[b], NULL, &rc);
            if (rc != CL_SUCCESS)
                st = clrt_record(err, rc, "clCreateBuffer(centre)", __func__, __LINE__);
        }
    if (st == IACSG_OK && m > 0)
        st = launch_with(r, r->fx->compact, groups, 7, compact_sizes, compact_values, 0x7c,
                         "iacsg_scene_centre_compact", err);
    if (st == IACSG_OK && m > 0) { /* one layer: every item is opaque, so a ray proven blocked needs no leaf */
        fx_trace_buffers b = {sh[0], sh[1], sh[2], sh[3], sh[4], NULL};
        st = fx_launch_scene(t, r->fx->trace, &b, (cl_int)m, eps_real, 1, err);
    }
    if (st == IACSG_OK && n == 0 && clFinish(r->rt.queue) != CL_SUCCESS)
        st = iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "clFinish after iacsg_scene_centre failed");
    cl_mem rgb = NULL; /* without children, the colours go display-encoded into the frame (out NULL) */
    if (st == IACSG_OK && n > 0 && !out) {
        rgb = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, 3 * area * sizeof(float),
                             frame->rgb, &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(centre)", __func__, __LINE__);
    }
    if (st == IACSG_OK && n > 0)
        st = fx_shade_launch(t, block, hits, m > 0 ? sh[3] : NULL, stage[2], n, palette, out, in[0], rgb, err);
    if (st == IACSG_OK && rgb)
        st = fx_sync_to_host(r->rt.queue, rgb, 3 * area * sizeof(float), err);
    fx_release_all(&rgb, 1);
    if (st == IACSG_OK && m > 0 && r->config.stats)
        st = count_centre_rays(t, sh[4], (size_t)m, (size_t)m, err);
    *nrest = 0;
    if (st == IACSG_OK && kinds)
        st = centre_kids(t, block, hits, kid[1], kid[2], n, eps_real, palette, pixels, frame, out, rest, nrest, err);
    fx_release_all(in, 4);
    fx_release_all(hits, 6);
    fx_release_all(stage, 4);
    fx_release_all(sh, 5);
    fx_release_all(kid, 3);
    free(kinds);
    if (fx)
        clReleaseMemObject(fx);
    return st;
}
