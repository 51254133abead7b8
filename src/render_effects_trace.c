/* src/render_effects_trace.c -- see render_effects_trace.h. The device side of a frame's effects (parameters,
 * the kernels made at the renderer's first use), and the segment path's secondary rays and colours: the rays go
 * to the device in one buffer per call, in the working precision (kernels/effects.h), traced one per work-item
 * with per-ray buffers that every ray fits (render_scene.c); their hits are shaded a packet's lanes at a time
 * (kernels/scene_effects.cl: iacsg_scene_shade, by light.h). Where no path can have a child, the centre paths
 * stay on the device (render_effects_centre.c, with the launches shared below). */
#include "render_effects_centre.h"
#include "kernels/effects.h"
#include "kernels/params.h"
#include "kernels/scene_data.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

iacsg_status fx_of(iacsg_renderer *r, render_fx **out, iacsg_error *err) {
    if (!r->fx && !(r->fx = calloc(1, sizeof *r->fx)))
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    *out = r->fx;
    return IACSG_OK;
}

size_t fx_real_bytes(const iacsg_renderer *r) { return r->config.fp64 ? sizeof(double) : sizeof(float); }

void fx_put_real(const iacsg_renderer *r, void *block, size_t k, double v) {
    if (r->config.fp64)
        ((double *)block)[k] = v;
    else
        ((float *)block)[k] = (float)v;
}

float fx_display(float light) {
    float v = light > 0 ? light : 0; /* clamped to [0, 1] (NaN to 0) by comparisons: fminf and fmaxf are calls */
    return sqrtf(v < 1 ? v : 1);
}

void fx_encode(float *rgb, int pixel) {
    for (int c = 0; c < 3; c++)
        rgb[3 * (size_t)pixel + c] = fx_display(rgb[3 * (size_t)pixel + c]);
}

/* PoCL compiles a kernel at its first launch: one launch over no rays makes that happen when the kernel is made,
 * counted as build time (render.c: compile_now), not inside the first frame with effects. */
static iacsg_status compile_trace_now(fx_tracer *t, iacsg_error *err) {
    fx_trace_buffers none = {0};
    double eps[1] = {0};
    return t->r->scene ? fx_launch_scene(t, t->r->fx->trace, &none, 0, eps, 0, err) : fx_device_compile(t, err);
}

iacsg_status fx_tracer_open(fx_tracer *t, iacsg_renderer *r, const iacsg_view *view, iacsg_error *err) {
    memset(t, 0, sizeof *t);
    t->r = r;
    t->view = view;
    render_fx *fx = NULL;
    double block[PARAM_COUNT];
    iacsg_status st = fx_of(r, &fx, err);
    if (st == IACSG_OK)
        st = render_fill_params(view, r->config.fp64, block, err);
    if (st != IACSG_OK)
        return st;
    cl_int rc = CL_SUCCESS;
    t->params = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, PARAM_COUNT * fx_real_bytes(r),
                               block, &rc);
    CLRT_CHECK(err, rc);
    if (!fx->trace) {
        double t0 = render_now_seconds();
        fx->trace = clCreateKernel(r->program, r->scene ? "iacsg_scene_trace_rays" : "iacsg_effects", &rc);
        CLRT_CHECK(err, rc);
        st = compile_trace_now(t, err);
        if (st == IACSG_OK && r->scene) {
            fx->shade = clCreateKernel(r->program, "iacsg_scene_shade", &rc);
            CLRT_CHECK(err, rc);
            st = fx_scene_shade(t, NULL, NULL, NULL, NULL, err);
        }
        if (st == IACSG_OK && r->scene) {
            double none[EFFECTS_COUNT] = {0};
            fx->centre = clCreateKernel(r->program, "iacsg_scene_centre", &rc);
            CLRT_CHECK(err, rc);
            fx->compact = clCreateKernel(r->program, "iacsg_scene_centre_compact", &rc);
            CLRT_CHECK(err, rc);
            size_t rest = 0;
            st = fx_scene_centre(t, none, NULL, 0, NULL, 0, 0, NULL, 0, NULL, NULL, &rest, err);
        }
        r->build_seconds += render_now_seconds() - t0;
        if (st != IACSG_OK)
            return st;
    }
    st = fx_all_groups(r, &t->all_groups, err);
    if (st == IACSG_OK)
        st = fx_footprint(view, &t->footprint, err);
    return st;
fail:
    return IACSG_ERR_OPENCL;
}

iacsg_status fx_all_groups(iacsg_renderer *r, cl_mem *out, iacsg_error *err) {
    cl_ulong ones[SEGMENTS];
    for (int k = 0; k < SEGMENTS; k++)
        ones[k] = ~(cl_ulong)0;
    cl_int rc = CL_SUCCESS;
    *out = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof ones, ones, &rc);
    return rc == CL_SUCCESS ? IACSG_OK : clrt_record(err, rc, "clCreateBuffer(all groups)", __func__, __LINE__);
}

iacsg_status fx_footprint(const iacsg_view *view, double *footprint, iacsg_error *err) {
    double p[PARAM_COUNT], far2 = 0;
    iacsg_status st = iacsg_camera_params(&view->camera, view->width, view->height, p, err);
    for (int k = 0; k < 3; k++) {
        double e = view->camera.eye[k], lo = view->bounds[k], hi = view->bounds[k + 3];
        far2 += fmax((e - lo) * (e - lo), (e - hi) * (e - hi));
    }
    *footprint = 2 * p[PARAM_SCALE_V] / view->height * (view->camera.ortho_height > 0 ? 1 : sqrt(far2));
    return st;
}

iacsg_status fx_block_buffer(iacsg_renderer *r, const double *block, cl_mem *out, iacsg_error *err) {
    char reals[EFFECTS_COUNT * sizeof(double)];
    for (int k = 0; k < EFFECTS_COUNT; k++)
        fx_put_real(r, reals, (size_t)k, block[k]);
    cl_int rc = CL_SUCCESS;
    *out = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, EFFECTS_COUNT * fx_real_bytes(r),
                          reals, &rc);
    return rc == CL_SUCCESS ? IACSG_OK : clrt_record(err, rc, "clCreateBuffer(effects)", __func__, __LINE__);
}

void fx_tracer_close(fx_tracer *t) {
    free(t->host);
    free(t->shade_host);
    t->host = t->shade_host = NULL;
    t->host_bytes = t->shade_bytes = 0;
    if (t->params)
        clReleaseMemObject(t->params);
    if (t->all_groups)
        clReleaseMemObject(t->all_groups);
    t->params = t->all_groups = NULL;
}



static void release_trace_buffers(fx_trace_buffers *b) {
    cl_mem all[] = {b->rays, b->t, b->normal, b->item, b->evals, b->passing};
    fx_release_all(all, 6);
}

iacsg_status fx_launch_slices(cl_command_queue q, cl_kernel k, cl_uint first_arg, cl_int count, size_t slots,
                              cl_int scale, const char *what, iacsg_error *err) {
    for (cl_int first = 0; first < count || first == 0; first += (cl_int)slots) {
        size_t global = count > 0 && (size_t)(count - first) < slots ? (size_t)(count - first) : slots, local = 1;
        cl_int value = scale * first, rc = clSetKernelArg(k, first_arg, sizeof value, &value);
        if (rc == CL_SUCCESS)
            rc = clEnqueueNDRangeKernel(q, k, 1, NULL, &global, &local, 0, NULL, NULL);
        if (rc != CL_SUCCESS)
            return clrt_record(err, rc, what, __func__, __LINE__);
    }
    return IACSG_OK;
}

/* The segment path: arguments of kernels/scene_effects.cl, launches of as many work-items (a packet's lanes of rays
 * each) as the per-ray buffers have room for (one after the other on the in-order queue, which they share). */
iacsg_status fx_launch_scene(fx_tracer *t, cl_kernel k, const fx_trace_buffers *b, cl_int n, void *eps_real,
                             cl_int whether, iacsg_error *err) {
    iacsg_renderer *r = t->r;
    void *held = NULL;
    cl_int lanes = render_packet_lanes(r), packets = (n + lanes - 1) / lanes;
    size_t slots = packets > 0 ? (size_t)packets : 1; /* n = 0: one launch that traces nothing (compile_trace_now) */
    iacsg_status st = render_scene_trace_args(r, t->view, k, 10, &slots, &held, err);
    cl_mem args[] = {t->params, b->rays, b->t, b->normal, b->item, b->evals, b->passing};
    cl_uint at[] = {0, 1, 5, 6, 7, 8, 9};
    for (int a = 0; a < 7 && st == IACSG_OK; a++)
        if (clSetKernelArg(k, at[a], sizeof(cl_mem), args[a] ? &args[a] : NULL) != CL_SUCCESS)
            st = iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "clSetKernelArg(scene trace) failed");
    if (st == IACSG_OK && (clSetKernelArg(k, 2, sizeof n, &n) != CL_SUCCESS ||
                           clSetKernelArg(k, 4, fx_real_bytes(r), eps_real) != CL_SUCCESS ||
                           clSetKernelArg(k, 30, sizeof whether, &whether) != CL_SUCCESS))
        st = iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "clSetKernelArg(scene trace) failed");
    if (st == IACSG_OK) /* argument 3: the launch's first ray */
        st = fx_launch_slices(r->rt.queue, k, 3, packets, slots, lanes,
                              "clEnqueueNDRangeKernel(iacsg_scene_trace_rays)", err);
    if (st == IACSG_OK && clFinish(r->rt.queue) != CL_SUCCESS)
        st = iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "clFinish after the scene's trace failed");
    render_scene_trace_release(held);
    return st;
}

/* Rounds up to whole pages: the parts of the host scratch start on pages, as devices prefer host arrays they
 * use in place. */
static size_t page_round(size_t bytes) { return (bytes + 4095) / 4096 * 4096; }

/* Makes a host scratch (*host, *have bytes) hold `bytes` (it only grows, so that a frame's passes reuse its
 * pages). */
static iacsg_status reserve_scratch(void **host, size_t *have, size_t bytes, iacsg_error *err) {
    if (bytes <= *have)
        return IACSG_OK;
    void *p = NULL;
    if (posix_memalign(&p, 4096, bytes) != 0)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the secondary rays");
    free(*host);
    *host = p;
    *have = bytes;
    return IACSG_OK;
}

void fx_put_ray(const iacsg_renderer *r, void *reals, size_t i, const fx_ray *y) {
    double v[EFFECTS_RAY_REALS] = {y->o[0], y->o[1], y->o[2], y->d[0], y->d[1], y->d[2], y->tn, y->tf};
    if (r->config.fp64) { /* the precision decided once a ray, not once a real: the loop is then converted in SIMD */
        memcpy((double *)reals + EFFECTS_RAY_REALS * i, v, sizeof v);
        return;
    }
    for (int k = 0; k < EFFECTS_RAY_REALS; k++)
        ((float *)reals)[EFFECTS_RAY_REALS * i + (size_t)k] = (float)v[k];
}

fx_weights fx_path_weights(const fx_item *m, double w, int bounces, int layers, int max_bounces) {
    double a = m->opacity, k = bounces < max_bounces ? m->reflect : 0, through = w * (1 - a);
    int mirrored = k > 0 && w * a * k >= EFFECTS_MIN_WEIGHT;
    int ends = through > 0 && (through < EFFECTS_MIN_WEIGHT || layers + 1 >= EFFECTS_MAX_LAYERS);
    return (fx_weights){w * a * (1 - k), ends ? through : 0, mirrored ? w * a * k : 0,
                        through > 0 && !ends ? through : 0};
}

iacsg_status fx_sync_to_host(cl_command_queue q, cl_mem m, size_t bytes, iacsg_error *err) {
    cl_int rc = CL_SUCCESS;
    void *p = clEnqueueMapBuffer(q, m, CL_TRUE, CL_MAP_READ, 0, bytes, 0, NULL, NULL, &rc);
    CLRT_CHECK(err, rc);
    CLRT_CHECK(err, clEnqueueUnmapMemObject(q, m, p, 0, NULL, NULL));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

iacsg_status fx_trace(fx_tracer *t, const fx_ray *rays, size_t n, double eps, int whether, fx_hit *hits,
                      iacsg_error *err) {
    if (n == 0)
        return IACSG_OK;
    if (n > 0x7fffffff / EFFECTS_RAY_REALS)
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "too many secondary rays (%zu) in one pass", n);
    iacsg_renderer *r = t->r;
    size_t rb = fx_real_bytes(r);
    size_t bytes[6] = {n * EFFECTS_RAY_REALS * rb, n * rb, 3 * n * sizeof(float), n * sizeof(cl_int),
                       n * sizeof(cl_uint), n * sizeof(cl_int)};
    size_t at[6] = {0};
    for (int k = 1; k < 6; k++)
        at[k] = at[k - 1] + page_round(bytes[k - 1]);
    iacsg_status st = reserve_scratch(&t->host, &t->host_bytes, at[5] + page_round(bytes[5]), err);
    if (st != IACSG_OK)
        return st;
    char *host = t->host;
    for (size_t i = 0; i < n; i++) {
        fx_put_ray(r, host, i, &rays[i]);
        ((cl_int *)(void *)(host + at[5]))[i] = rays[i].passing;
    }
    fx_trace_buffers b = {0};
    cl_mem *dst[6] = {&b.rays, &b.t, &b.normal, &b.item, &b.evals, &b.passing};
    cl_int rc = CL_SUCCESS;
    for (int k = 0; k < 6; k++) {
        if (k == 4 && !r->config.stats)
            continue;
        cl_mem_flags flags = (k == 0 || k == 5 ? CL_MEM_READ_ONLY : CL_MEM_WRITE_ONLY) | CL_MEM_USE_HOST_PTR;
        *dst[k] = clCreateBuffer(r->rt.context, flags, bytes[k], host + at[k], &rc);
        CLRT_CHECK(err, rc);
    }
    double eps_block[1];
    fx_put_real(r, eps_block, 0, eps);
    st = fx_launch_scene(t, r->fx->trace, &b, (cl_int)n, eps_block, whether, err);
    for (int k = 1; k < 5 && st == IACSG_OK; k++) /* the outputs */
        if (*dst[k])
            st = fx_sync_to_host(r->rt.queue, *dst[k], bytes[k], err);
    const float *out_n = (const float *)(void *)(host + at[2]);
    const cl_int *out_item = (const cl_int *)(void *)(host + at[3]);
    for (size_t i = 0; st == IACSG_OK && i < n; i++) {
        hits[i].t = r->config.fp64 ? ((const double *)(void *)(host + at[1]))[i]
                                   : ((const float *)(void *)(host + at[1]))[i];
        memcpy(hits[i].n, out_n + 3 * i, sizeof hits[i].n);
        hits[i].item = isinf(hits[i].t) ? -1 : b.item ? out_item[i] : 0;
        t->evals += b.evals ? ((const cl_uint *)(void *)(host + at[4]))[i] : 0;
    }
    t->rays += (long long)n;
    release_trace_buffers(&b);
    return st;
fail:
    release_trace_buffers(&b);
    return IACSG_ERR_OPENCL;
}

/* The bytes of fx_shade_in's arrays for n hits, in iacsg_scene_shade's order of them (rays, depth, normal, item,
 * vis, row), each from a page. */
void fx_shade_parts(const iacsg_renderer *r, size_t n, size_t bytes[6]) {
    size_t rb = fx_real_bytes(r);
    size_t b[6] = {n * EFFECTS_RAY_REALS * rb, n * rb, 3 * n * sizeof(float), n * sizeof(cl_int),
                   EFFECTS_MAX_LIGHTS * n * sizeof(float), n * sizeof(cl_int)};
    memcpy(bytes, b, sizeof b);
}

iacsg_status fx_shade_inputs(fx_tracer *t, size_t n, fx_shade_in *in, iacsg_error *err) {
    size_t bytes[6], at[7] = {0};
    fx_shade_parts(t->r, n, bytes);
    for (int k = 0; k < 6; k++)
        at[k + 1] = at[k] + page_round(bytes[k] + 1);
    iacsg_status st = reserve_scratch(&t->shade_host, &t->shade_bytes, at[6], err);
    if (st != IACSG_OK)
        return st;
    char *host = t->shade_host;
    *in = (fx_shade_in){.rays = host,
                        .depth = host + at[1],
                        .normal = (float *)(void *)(host + at[2]),
                        .item = (cl_int *)(void *)(host + at[3]),
                        .vis = (float *)(void *)(host + at[4]),
                        .row = (cl_int *)(void *)(host + at[5]),
                        .n = n};
    return IACSG_OK;
}

/* Launches iacsg_scene_shade over the n hits whose arrays are hits[0 .. 6) (rays, depths, normals, items, light
 * fractions, rows: device buffers; n 0: none, a launch that only compiles it), shadow_item and shadow_slot (or
 * NULL) its arguments; their colours into out (6 floats a hit), or where out is NULL display-encoded into their
 * pixels (pixels: device buffer) of the frame rgb (a device buffer over the host's frame). */
iacsg_status fx_shade_launch(fx_tracer *t, const double *block, const cl_mem hits[6], cl_mem shadow_item,
                             cl_mem shadow_slot, size_t n, const float *palette, float *out, cl_mem pixels, cl_mem rgb,
                             iacsg_error *err) {
    iacsg_renderer *r = t->r;
    size_t rb = fx_real_bytes(r), nitems = r->fx->nitems > 0 ? (size_t)r->fx->nitems : 1;
    cl_mem mem[3] = {0}; /* block, materials, palette */
    cl_mem out_mem = NULL;
    char reals[EFFECTS_COUNT * sizeof(double)];
    for (int k = 0; block && k < EFFECTS_COUNT; k++)
        fx_put_real(r, reals, (size_t)k, block[k]);
    const void *host[3] = {reals, render_scene_materials(r), palette};
    size_t bytes[3] = {EFFECTS_COUNT * rb, SCENE_MATERIAL_FLOATS * nitems * sizeof(float), 3 * nitems * sizeof(float)};
    cl_int rc = CL_SUCCESS;
    iacsg_status st = IACSG_OK;
    for (int b = 0; b < 3 && st == IACSG_OK && n > 0; b++) {
        mem[b] = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes[b], (void *)host[b], &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(iacsg_scene_shade)", __func__, __LINE__);
    }
    if (st == IACSG_OK && n > 0 && out) {
        out_mem = clCreateBuffer(r->rt.context, CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR, 6 * n * sizeof(float), out,
                                 &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(iacsg_scene_shade)", __func__, __LINE__);
    }
    cl_kernel k = r->fx->shade;
    cl_int height = t->view->height, count = (cl_int)n;
    const cl_mem *args[] = {&t->params, &mem[0], &mem[1], &mem[2], NULL,     &hits[0], &hits[1],
                            &hits[2],   &hits[3], &hits[4], &hits[5], NULL,    &out_mem, &shadow_item,
                            &shadow_slot, &pixels, &rgb};
    for (cl_uint a = 0; a < 17 && st == IACSG_OK; a++) {
        rc = a == 4 ? clSetKernelArg(k, a, sizeof height, &height)
             : a == 11 ? clSetKernelArg(k, a, sizeof count, &count)
                       : clSetKernelArg(k, a, sizeof(cl_mem), *args[a] ? args[a] : NULL);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clSetKernelArg(iacsg_scene_shade)", __func__, __LINE__);
    }
    size_t lanes = (size_t)render_packet_lanes(r), local = 1;
    size_t global = n > 0 ? (n + lanes - 1) / lanes : 1; /* n = 0: compile it now */
    if (st == IACSG_OK) {
        rc = clEnqueueNDRangeKernel(r->rt.queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
        if (rc == CL_SUCCESS)
            rc = clFinish(r->rt.queue);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clEnqueueNDRangeKernel(iacsg_scene_shade)", __func__, __LINE__);
    }
    if (st == IACSG_OK && out_mem)
        st = fx_sync_to_host(r->rt.queue, out_mem, 6 * n * sizeof(float), err);
    fx_release_all(mem, 3);
    fx_release_all(&out_mem, 1);
    return st;
}

void fx_release_all(cl_mem *mem, int count) {
    for (int b = 0; b < count; b++)
        if (mem[b])
            clReleaseMemObject(mem[b]);
}

iacsg_status fx_scene_shade(fx_tracer *t, const double *block, const fx_shade_in *in, const float *palette,
                            float *out, iacsg_error *err) {
    size_t n = in ? in->n : 0, bytes[6];
    fx_shade_parts(t->r, n, bytes);
    cl_mem hits[6] = {0};
    iacsg_status st = IACSG_OK;
    for (int b = 0; b < 6 && st == IACSG_OK && n > 0; b++) { /* read in place, where the host wrote them */
        const void *arrays[6] = {in->rays, in->depth, in->normal, in->item, in->vis, in->row};
        cl_int rc = CL_SUCCESS;
        hits[b] = clCreateBuffer(t->r->rt.context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes[b],
                                 (void *)arrays[b], &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(iacsg_scene_shade)", __func__, __LINE__);
    }
    if (st == IACSG_OK)
        st = fx_shade_launch(t, block, hits, NULL, NULL, n, palette, out, NULL, NULL, err);
    fx_release_all(hits, 6);
    return st;
}
