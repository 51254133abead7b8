/* src/render_effects_samples.c -- -aa's sample rays on the segment path, traced by the camera kernel's packets
 * (kernels/render_scene.cl: iacsg_render_scene_samples) instead of one ray per work-item:
 *
 *   edge pixels --> their samples as pixels of an image aa times as wide and high (sample (a, b) of pixel (i, j)
 *     is its pixel (aa i + a, aa j + b), whose centre is the sample's point) --> sorted by block and packet of
 *     that image: a list of blocks, each with the mask of its packets that hold samples and their output slots
 *   --> the kernel: per block its tile pass, per listed packet the camera rays' trace (beam, union leaf, claim)
 *   --> each sample's hit (depth, normal, item) from its slot's lane; or, with the effects' block, its colour (lit in
 *       the kernel: kernels/scene_lit.h's scene_packet_lit, in linear light).
 *
 * Why: the samples of one pixel are a coherent packet (at -aa 4 exactly one, 16 rays in a pixel), which the camera
 * kernel traces with one BVH cut, one search of the regions' union in SIMD lanes and one claim at its leaf, where
 * the per-ray kernel wove each ray alone from where it entered the bounds (Fig. 2 as regions: 26.7 evaluations a
 * sample, 3x the camera rays'). The samples keep their leaves (-aa's eps) and their rays (the camera rays of the
 * samples' image are the host's sample rays rounded to the working precision).
 */
#include "render_effects_trace.h"
#include "kernels/params.h"
#include "kernels/scene_data.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(SCENE_BLOCK_PACKETS == 64, "a block's packets fit the two ints of its mask");

/* Where a sample goes in the launch: its block (row-major in the samples' image), its packet there and its lane,
 * and its index in the caller's order. */
typedef struct {
    long long block;
    int packet, lane;
    size_t sample;
} sample_place;

/* The order of a launch's samples: by block, then packet. */
static unsigned long long packet_key(const sample_place *p) {
    return (unsigned long long)p->block * SCENE_BLOCK_PACKETS + (unsigned long long)p->packet;
}

/* Sorts places[0 .. n) by packet_key, equal keys in their order, by digits of 11 bits from the lowest (linear:
 * qsort's comparisons of a chunk's 16,384 samples were ~1 ms of one CPU a chunk, the device idle); tmp: room for n.
 * Returns where the sorted places are (places or tmp). */
static sample_place *sort_by_packet(sample_place *places, sample_place *tmp, size_t n) {
    enum { DIGIT = 11, BUCKETS = 1 << DIGIT };
    unsigned long long most = 0;
    for (size_t s = 0; s < n; s++)
        most = packet_key(&places[s]) > most ? packet_key(&places[s]) : most;
    for (int shift = 0; shift == 0 || (shift < 64 && most >> shift != 0); shift += DIGIT) {
        size_t at[BUCKETS + 1] = {0};
        for (size_t s = 0; s < n; s++)
            at[1 + (packet_key(&places[s]) >> shift & (BUCKETS - 1))]++;
        for (int b = 0; b < BUCKETS; b++)
            at[b + 1] += at[b];
        for (size_t s = 0; s < n; s++)
            tmp[at[packet_key(&places[s]) >> shift & (BUCKETS - 1)]++] = places[s];
        sample_place *swap = places;
        places = tmp;
        tmp = swap;
    }
    return places;
}

/* The place of pixel (vi, vj) of the samples' image, blocks_x blocks wide, with packets pw pixels wide
 * (kernels/scene_data.h's numbering: a block of pw x PACKET_H tiles, each of its tiles' packets in rows). */
static void place_of(int vi, int vj, long long blocks_x, int pw, sample_place *p) {
    int block_w = SCENE_BLOCK_W_OF(pw);
    int x = vi % block_w, y = vj % SCENE_BLOCK_H;
    int tile = y / TILE_SIZE * pw + x / TILE_SIZE;
    int in_tile = y % TILE_SIZE / PACKET_H * SCENE_TILE_PACKETS_W_OF(pw) + x % TILE_SIZE / pw;
    p->block = (long long)(vj / SCENE_BLOCK_H) * blocks_x + vi / block_w;
    p->packet = tile * SCENE_TILE_PACKETS_OF(pw) + in_tile;
    p->lane = y % PACKET_H * pw + x % pw;
}

/* The launch's list: blocks (SCENE_SAMPLES_INTS ints each) and each sample's output, out[sample] = lanes slot +
 * lane (the renderer's packets' lanes). */
typedef struct {
    int *blocks;
    int nblocks;
    size_t nslots;
    size_t *out;
} sample_list;

static iacsg_status list_samples(const iacsg_renderer *r, int width, int aa, const int *pixels, size_t npixels,
                                 sample_list *l, iacsg_error *err) {
    size_t per = (size_t)aa * (size_t)aa, n = npixels * per, lanes = (size_t)render_packet_lanes(r);
    long long blocks_x = ((long long)width * aa + render_block_w(r) - 1) / render_block_w(r);
    sample_place *places = malloc((n + 1) * sizeof *places), *tmp = malloc((n + 1) * sizeof *tmp);
    l->blocks = malloc((n + 1) * SCENE_SAMPLES_INTS * sizeof *l->blocks);
    l->out = malloc((n + 1) * sizeof *l->out);
    l->nblocks = 0;
    l->nslots = 0;
    if (!places || !tmp || !l->blocks || !l->out) {
        free(places);
        free(tmp);
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for -aa's samples");
    }
    for (size_t q = 0; q < npixels; q++)
        for (int b = 0; b < aa; b++)
            for (int a = 0; a < aa; a++) {
                size_t s = q * per + (size_t)(b * aa + a);
                place_of(pixels[q] % width * aa + a, pixels[q] / width * aa + b, blocks_x, r->packet_w, &places[s]);
                places[s].sample = s;
            }
    const sample_place *sorted = sort_by_packet(places, tmp, n);
    int *block = NULL;
    for (size_t s = 0; s < n; s++) {
        const sample_place *p = &sorted[s];
        int new_block = s == 0 || p->block != sorted[s - 1].block;
        if (new_block) {
            block = l->blocks + SCENE_SAMPLES_INTS * (size_t)l->nblocks++;
            block[SCENE_SAMPLES_BX] = (int)(p->block % blocks_x);
            block[SCENE_SAMPLES_BY] = (int)(p->block / blocks_x);
            block[SCENE_SAMPLES_MASK] = block[SCENE_SAMPLES_MASK + 1] = 0;
            block[SCENE_SAMPLES_SLOT] = (int)l->nslots;
        }
        if (new_block || p->packet != sorted[s - 1].packet) {
            block[SCENE_SAMPLES_MASK + p->packet / 32] |= (int)(1u << (p->packet % 32));
            l->nslots++;
        }
        l->out[p->sample] = lanes * (l->nslots - 1) + (size_t)p->lane;
    }
    free(places);
    free(tmp);
    return IACSG_OK;
}

/* The kernel's outputs, the packets' lanes a slot, in host arrays the device writes in place; arguments 8 on in this
 * order. */
enum {
    OUT_RGB,
    OUT_DEPTH,
    OUT_NORMAL,
    OUT_IDS,
    OUT_OVERLAP,
    OUT_COUNTS,
    OUT_OVERFLOW,
    OUT_NOVERFLOW,
    OUT_FX_COUNTS, /* with the effects and -stats: each lane's secondary rays and their evaluations */
    OUT_ALL
};

typedef struct {
    void *host[OUT_ALL];
    cl_mem mem[OUT_ALL];
    size_t bytes[OUT_ALL];
} sample_outputs;

static void release_outputs(sample_outputs *o) {
    for (int k = 0; k < OUT_ALL; k++) {
        if (o->mem[k])
            clReleaseMemObject(o->mem[k]);
        free(o->host[k]);
    }
}

static iacsg_status make_outputs(iacsg_renderer *r, size_t lanes, int lit, sample_outputs *o, iacsg_error *err) {
    size_t each[OUT_ALL] = {3 * sizeof(float),   sizeof(float),  3 * sizeof(float), sizeof(float), sizeof(cl_int),
                            3 * sizeof(cl_uint), sizeof(cl_int), 0,                 2 * sizeof(cl_uint)};
    memset(o, 0, sizeof *o);
    for (int k = 0; k < OUT_ALL; k++) {
        if ((k == OUT_COUNTS || k == OUT_FX_COUNTS) && !r->config.stats)
            continue;
        if (k == OUT_FX_COUNTS && !lit)
            continue;
        o->bytes[k] = k == OUT_NOVERFLOW ? sizeof(cl_int) : each[k] * (lanes > 0 ? lanes : 1);
        o->host[k] = calloc(1, o->bytes[k]); /* noverflow starts at 0 */
        cl_int rc = CL_SUCCESS;
        if (o->host[k])
            o->mem[k] = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, o->bytes[k], o->host[k],
                                       &rc);
        if (!o->host[k])
            return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for -aa's samples");
        if (rc != CL_SUCCESS)
            return clrt_record(err, rc, "clCreateBuffer(-aa's samples)", __func__, __LINE__);
    }
    return IACSG_OK;
}

typedef struct {
    size_t bytes;
    const void *v;
} kernel_arg;

/* Launches iacsg_render_scene_samples over the list (no block: one work-item that traces nothing, so that PoCL
 * compiles the kernel) with the samples' image's camera `params`, in launches of as many work-items as the
 * per-ray buffers have room for, and makes the outputs current on the host. */
static iacsg_status launch_samples(fx_tracer *t, const iacsg_view *samples_view, cl_mem params, const sample_list *l,
                                   cl_mem block, sample_outputs *o, iacsg_error *err) {
    iacsg_renderer *r = t->r;
    cl_kernel k = r->fx->samples;
    cl_int rc = CL_SUCCESS, flags = samples_view->camera.ortho_height > 0 ? RENDER_ORTHO : 0;
    cl_int width = samples_view->width, height = samples_view->height, nblocks = l->nblocks;
    static const int no_block[SCENE_SAMPLES_INTS];
    cl_mem blocks = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                   (l->nblocks > 0 ? (size_t)l->nblocks : 1) * SCENE_SAMPLES_INTS * sizeof(int),
                                   l->nblocks > 0 ? (void *)l->blocks : (void *)no_block, &rc);
    if (rc != CL_SUCCESS)
        return clrt_record(err, rc, "clCreateBuffer(-aa's blocks)", __func__, __LINE__);
    size_t nitems = r->fx->nitems > 0 ? (size_t)r->fx->nitems : 1;
    cl_mem albedo = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                   SCENE_MATERIAL_FLOATS * nitems * sizeof(float), (void *)render_scene_materials(r),
                                   &rc);
    void *held = NULL;
    size_t slots = nblocks > 0 ? (size_t)nblocks : 1;
    iacsg_status st = rc == CL_SUCCESS ? render_scene_trace_args(r, samples_view, k, 16, &slots, &held, err)
                                       : clrt_record(err, rc, "clCreateBuffer(albedo)", __func__, __LINE__);
    cl_int aa = samples_view->width / t->view->width;
    char fx_eps[sizeof(double)]; /* the secondary rays' leaves: the view's eps, as the host's paths */
    fx_put_real(r, fx_eps, 0, t->view->eps);
    kernel_arg args[8 + OUT_FX_COUNTS] = {{sizeof(cl_mem), &params}, {sizeof flags, &flags}, {sizeof width, &width},
                                          {sizeof height, &height},  {sizeof(cl_mem), &blocks},
                                          {sizeof nblocks, &nblocks}, {0, NULL}, {sizeof(cl_mem), &albedo}};
    for (int a = 0; a < OUT_FX_COUNTS; a++)
        args[8 + a] = (kernel_arg){sizeof(cl_mem), o->mem[a] ? &o->mem[a] : NULL};
    /* after the scene's arguments (render_scene_trace_args: 16 to 35): the effects' block, their counts, aa, eps */
    kernel_arg fx_args[4] = {{sizeof(cl_mem), block ? &block : NULL},
                             {sizeof(cl_mem), o->mem[OUT_FX_COUNTS] ? &o->mem[OUT_FX_COUNTS] : NULL},
                             {sizeof aa, &aa},
                             {fx_real_bytes(r), fx_eps}};
    for (cl_uint a = 0; a < 8 + OUT_FX_COUNTS + 4 && st == IACSG_OK; a++) {
        const kernel_arg *g = a < 8 + OUT_FX_COUNTS ? &args[a] : &fx_args[a - 8 - OUT_FX_COUNTS];
        cl_uint index = a < 8 + OUT_FX_COUNTS ? a : 36 + a - 8 - OUT_FX_COUNTS;
        rc = a == 6 ? CL_SUCCESS : clSetKernelArg(k, index, g->bytes, g->v); /* 6: each launch's first block */
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clSetKernelArg(iacsg_render_scene_samples)", __func__, __LINE__);
    }
    if (st == IACSG_OK)
        st = fx_launch_slices(r->rt.queue, k, 6, nblocks, slots, 1, /* argument 6: the launch's first block */
                              "clEnqueueNDRangeKernel(iacsg_render_scene_samples)", err);
    for (int a = 0; a < OUT_ALL && st == IACSG_OK; a++)
        if (o->mem[a])
            st = fx_sync_to_host(r->rt.queue, o->mem[a], o->bytes[a], err);
    render_scene_trace_release(held);
    clReleaseMemObject(blocks);
    if (albedo)
        clReleaseMemObject(albedo);
    return st;
}

/* The samples' image: aa times the view's width and height, -aa's eps, all of its rows. */
static iacsg_status samples_params(fx_tracer *t, int aa, double eps, iacsg_view *v, cl_mem *params,
                                   iacsg_error *err) {
    *v = *t->view;
    v->width *= aa;
    v->height *= aa;
    v->eps = eps;
    v->row_first = v->row_count = 0;
    double block[PARAM_COUNT];
    iacsg_status st = render_fill_params(v, t->r->config.fp64, block, err);
    cl_int rc = CL_SUCCESS;
    if (st == IACSG_OK)
        *params = clCreateBuffer(t->r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                 PARAM_COUNT * fx_real_bytes(t->r), block, &rc);
    return st != IACSG_OK || rc == CL_SUCCESS ? st : clrt_record(err, rc, "clCreateBuffer(params)", __func__, __LINE__);
}

/* Makes the kernel at its first use; PoCL compiles it at its first launch, here over no block (build time). */
static iacsg_status samples_kernel(fx_tracer *t, iacsg_error *err) {
    iacsg_renderer *r = t->r;
    if (r->fx->samples)
        return IACSG_OK;
    double t0 = render_now_seconds();
    cl_int rc = CL_SUCCESS;
    r->fx->samples = clCreateKernel(r->program, "iacsg_render_scene_samples", &rc);
    if (rc != CL_SUCCESS)
        return clrt_record(err, rc, "clCreateKernel(iacsg_render_scene_samples)", __func__, __LINE__);
    iacsg_view v;
    cl_mem params = NULL;
    sample_list none = {0};
    sample_outputs o = {0};
    iacsg_status st = samples_params(t, 1, t->view->eps, &v, &params, err);
    if (st == IACSG_OK)
        st = make_outputs(r, 0, 0, &o, err);
    if (st == IACSG_OK)
        st = launch_samples(t, &v, params, &none, NULL, &o, err);
    release_outputs(&o);
    if (params)
        clReleaseMemObject(params);
    r->build_seconds += render_now_seconds() - t0;
    return st;
}

iacsg_status fx_scene_samples(fx_tracer *t, int aa, double eps, const int *pixels, size_t npixels, fx_hit *hits,
                              const double *block, float *rgb, iacsg_error *err) {
    iacsg_renderer *r = t->r;
    sample_list l = {0};
    sample_outputs o = {0};
    iacsg_view v;
    cl_mem params = NULL, fx = NULL;
    iacsg_status st = samples_kernel(t, err);
    if (st == IACSG_OK && block)
        st = fx_block_buffer(r, block, &fx, err);
    if (st == IACSG_OK)
        st = list_samples(r, t->view->width, aa, pixels, npixels, &l, err);
    if (st == IACSG_OK)
        st = samples_params(t, aa, eps, &v, &params, err);
    if (st == IACSG_OK)
        st = make_outputs(r, (size_t)render_packet_lanes(r) * l.nslots, block != NULL, &o, err);
    if (st == IACSG_OK)
        st = launch_samples(t, &v, params, &l, fx, &o, err);
    if (st == IACSG_OK && *(const cl_int *)o.host[OUT_NOVERFLOW] != 0) /* the buffers hold every solid */
        st = iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "-aa's sample rays overflowed their buffers");
    const float *depth = o.host[OUT_DEPTH], *normal = o.host[OUT_NORMAL], *ids = o.host[OUT_IDS];
    const float *colour = o.host[OUT_RGB];
    const cl_uint *counts = o.host[OUT_COUNTS], *fx_counts = o.host[OUT_FX_COUNTS];
    size_t n = npixels * (size_t)aa * (size_t)aa;
    for (size_t s = 0; st == IACSG_OK && s < n; s++) {
        size_t at = l.out[s];
        if (rgb)
            memcpy(rgb + 3 * s, colour + 3 * at, 3 * sizeof(float));
        if (hits) {
            fx_hit *h = &hits[s];
            h->t = isinf(depth[at]) ? INFINITY : depth[at];
            h->item = isinf(depth[at]) ? -1 : (int)ids[at];
            memcpy(h->n, normal + 3 * at, sizeof h->n);
        }
        t->evals += counts ? counts[3 * at] : 0;
        t->rays += fx_counts ? fx_counts[2 * at] : 0;
        t->evals += fx_counts ? fx_counts[2 * at + 1] : 0;
    }
    t->rays += st == IACSG_OK ? (long long)n : 0;
    release_outputs(&o);
    if (params)
        clReleaseMemObject(params);
    if (fx)
        clReleaseMemObject(fx);
    free(l.blocks);
    free(l.out);
    return st;
}
