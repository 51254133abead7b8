/* src/render_scene.c -- the segment path (kernels/render_scene.cl): a renderer for a scene's regions and
 * surfaces. One program per scene: the ia/ headers, the solids' code (implicits/scene_emit.c) and the segment
 * path's kernels (BRL-CAD's primitives, kernels/prim.h and scene_prims.h, come before the solids, which call them).
 * The scene's tables (src/scene_tables.c) and its primitives' types and parameters (implicits/scene_prims.c, in the
 * program's precision: no literals in the program, so that models of the same kinds share one cached build) live
 * on the device for the renderer's life.
 *
 * A frame: the bands of rows, each one launch with a packet of 4x4 pixels per work-item and a slice of the
 * per-ray buffers per work-item (kernels/scene_data.h); then the rays that met more boxes than the buffers have
 * room for, listed by the kernel, traced again with four times the room (at most the scene's solids, which every
 * ray fits), until none is left; then the statistics.
 */
#include "render_internal.h"
#include "implicits/scene.h"
#include "implicits/scene_emit.h"
#include "implicits/scene_prims.h"
#include "kernels/params.h"
#include "kernels/scene_data.h"
#include "scene_tables.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const char iacsg_cl_scene_kernels[]; /* the flattened kernels of the segment path (Makefile) */
extern const char iacsg_cl_prim[];          /* the primitives' inclusion functions (kernels/prim.h) */

/* The per-ray buffers of all work-items of one launch together stay below this; bands are cut to fit. */
#define SCENE_SCRATCH_BUDGET (64.0 * 1024 * 1024)
/* A band's blocks at most (2048 rows, as render.c's): each band is a launch, ~1-2 ms on PoCL here. Bands of 2
 * blocks (64 rows) before, 16 launches a 1024x1024 frame; in one: Fig. 2's regions 68 -> 63 ms, machined_part.csg
 * 112 -> 97, m35.asc 164 -> 150, havoc 274 -> 245 (medians of 9 in turn, images the same). */
#define SCENE_BAND_BLOCKS 64
_Static_assert(IACSG_ROW_ALIGN % SCENE_BLOCK_H == 0, "iacsg_view.row_first is aligned to whole blocks");

struct render_scene {
    scene_tables t;
    cl_mem nodes, items, solid_items_start, solid_items, surfaces, albedo, bvh_link;
    cl_mem prims; /* kernels/scene_prims.h */
};

/* An OpenCL buffer holding a copy of `bytes` bytes (at least one byte, so that empty tables are buffers too). */
static cl_mem table_buffer(iacsg_renderer *r, const void *data, size_t bytes, iacsg_error *err) {
    cl_int rc = CL_SUCCESS;
    static const int zero = 0;
    cl_mem m = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes ? bytes : sizeof zero,
                              bytes ? (void *)data : (void *)&zero, &rc);
    if (rc != CL_SUCCESS)
        clrt_record(err, rc, "clCreateBuffer(table)", __func__, __LINE__);
    return m;
}

void render_scene_free(render_scene *s) {
    if (!s)
        return;
    cl_mem all[] = {s->nodes,    s->items,  s->solid_items_start, s->solid_items,
                    s->surfaces, s->albedo, s->bvh_link,          s->prims};
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        if (all[k])
            clReleaseMemObject(all[k]);
    scene_tables_free(&s->t);
    free(s);
}

static size_t real_size(const iacsg_renderer *r) { return r->config.fp64 ? sizeof(double) : sizeof(float); }

/* The tables, and the primitives' in the program's precision. */
static iacsg_status upload_tables(iacsg_renderer *r, render_scene *s, const iacsg_scene *scene, iacsg_error *err) {
    const scene_tables *t = &s->t;
    void *prims = NULL;
    size_t nprims = 0;
    int most = 0;
    iacsg_status st = scene_prims_table(scene, r->config.fp64, &prims, &nprims, &most, err);
    if (st == IACSG_OK && !(s->prims = table_buffer(r, prims, nprims * real_size(r), err)))
        st = IACSG_ERR_OPENCL;
    free(prims);
    if (st != IACSG_OK)
        return st;
    cl_mem *dst[] = {&s->nodes, &s->items, &s->solid_items_start, &s->solid_items, &s->surfaces, &s->albedo,
                     &s->bvh_link};
    const void *src[] = {t->nodes, t->items, t->solid_items_start, t->solid_items, t->surfaces, t->albedo,
                         t->bvh_link};
    size_t bytes[] = {sizeof(uint32_t) * (size_t)t->nnodes,
                      sizeof(int) * SCENE_ITEM_INTS * (size_t)t->nitems,
                      sizeof(int) * (size_t)(t->nsolids + 1),
                      sizeof(int) * (size_t)t->solid_items_start[t->nsolids],
                      sizeof(int) * (size_t)t->nsurfaces,
                      SCENE_MATERIAL_FLOATS * sizeof(float) * (size_t)t->nitems,
                      sizeof(int) * (2 * (size_t)t->nbvh + (size_t)t->nsolids)};
    for (size_t k = 0; k < sizeof dst / sizeof dst[0]; k++)
        if (!(*dst[k] = table_buffer(r, src[k], bytes[k], err)))
            return IACSG_ERR_OPENCL;
    return IACSG_OK;
}

/* The buffers of one frame. */
typedef struct {
    cl_mem params, box, rgb, depth, normal, ids, overlap, counts, list[2], nlist[2];
    cl_mem cand_solid, cand_range, cand_pos, cand_level, cand_index, cand_newton, cand_newton_t, state;
    int cand_cap;
    size_t slots;                /* work-items the per-ray buffers have room for */
    const render_fx_camera *fx; /* the effects the kernel applies (render_effects_in_camera), or NULL */
} scene_buffers;

static void release_scene_buffers(scene_buffers *b) {
    cl_mem *all[] = {&b->params,  &b->box,      &b->rgb,        &b->depth,      &b->normal,  &b->ids,
                     &b->overlap, &b->counts,   &b->list[0],    &b->list[1],    &b->nlist[0], &b->nlist[1],
                     &b->cand_solid, &b->cand_range, &b->cand_pos, &b->cand_level, &b->cand_index, &b->cand_newton,
                     &b->cand_newton_t, &b->state};
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        if (*all[k]) {
            clReleaseMemObject(*all[k]);
            *all[k] = NULL;
        }
}

/* The bytes of a candidate's walk (kernels/segments.h): solid, range, position, level, index and Newton's N. */
static size_t candidate_bytes(const iacsg_renderer *r) {
    return 3 * sizeof(cl_int) + 5 * real_size(r) + (r->config.fp64 ? sizeof(cl_ulong) : sizeof(cl_uint));
}

/* The bytes of one work-item's slice of the per-ray buffers: its candidates and the states of all solids. */
static size_t slot_bytes(const iacsg_renderer *r, int cand_cap) {
    return (size_t)cand_cap * candidate_bytes(r) + (size_t)r->scene->t.nsolids + 1;
}

/* (Re)allocates the per-ray buffers for `slots` work-items with the given room; the states start OUT. */
static iacsg_status scratch_buffers(iacsg_renderer *r, scene_buffers *b, size_t slots, int cand_cap,
                                    iacsg_error *err) {
    cl_mem *all[] = {&b->cand_solid, &b->cand_range, &b->cand_pos,      &b->cand_level,
                     &b->cand_index, &b->cand_newton, &b->cand_newton_t, &b->state};
    size_t cands = slots * (size_t)cand_cap;
    size_t bytes[] = {cands * sizeof(cl_int),
                      cands * 2 * real_size(r),
                      cands * real_size(r),
                      cands * sizeof(cl_int),
                      cands * (r->config.fp64 ? sizeof(cl_ulong) : sizeof(cl_uint)),
                      cands * sizeof(cl_int),
                      cands * 2 * real_size(r),
                      slots * (size_t)(r->scene->t.nsolids + 1)};
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++) {
        if (*all[k])
            clReleaseMemObject(*all[k]);
        cl_int rc = CL_SUCCESS;
        *all[k] = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE, bytes[k], NULL, &rc);
        CLRT_CHECK(err, rc);
    }
    cl_uchar out = SCENE_OUT;
    CLRT_CHECK(err, clEnqueueFillBuffer(r->rt.queue, b->state, &out, 1, 0, bytes[7], 0, NULL, NULL));
    b->slots = slots;
    b->cand_cap = cand_cap;
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* The kernel's arguments but 4 (the band), 5 and 6 (the list of pixels), and the overflow list (33, 34). */
static iacsg_status set_scene_args(iacsg_renderer *r, const iacsg_view *view, const scene_buffers *b,
                                   iacsg_error *err) {
    render_scene *s = r->scene;
    cl_kernel k = r->kernel;
    cl_int flags = view->camera.ortho_height > 0 ? RENDER_ORTHO : 0, width = view->width, height = view->height;
    cl_int nbvh = s->t.nbvh, nsurfaces = s->t.nsurfaces, nsolids = s->t.nsolids + 1;
    cl_int cand_cap = b->cand_cap, row_end = view->row_count ? view->row_first + view->row_count : view->height;
    struct {
        int index;
        size_t size;
        const void *value;
    } args[] = {{0, sizeof(cl_mem), &b->params},       {1, sizeof flags, &flags},
                {2, sizeof width, &width},             {3, sizeof height, &height},
                {7, sizeof(cl_mem), &b->box},          {8, sizeof(cl_mem), &s->bvh_link},
                {9, sizeof nbvh, &nbvh},               {10, sizeof(cl_mem), &s->nodes},
                {11, sizeof(cl_mem), &s->items},       {12, sizeof(cl_mem), &s->solid_items_start},
                {13, sizeof(cl_mem), &s->solid_items}, {14, sizeof(cl_mem), &s->surfaces},
                {15, sizeof nsurfaces, &nsurfaces},    {16, sizeof(cl_mem), &s->albedo},
                {17, sizeof(cl_mem), &b->cand_solid},  {18, sizeof(cl_mem), &b->cand_range},
                {19, sizeof(cl_mem), &b->cand_pos},    {20, sizeof(cl_mem), &b->cand_level},
                {21, sizeof(cl_mem), &b->cand_index},  {22, sizeof(cl_mem), &b->cand_newton},
                {23, sizeof(cl_mem), &b->cand_newton_t}, {24, sizeof cand_cap, &cand_cap},
                {25, sizeof(cl_mem), &b->state},       {26, sizeof nsolids, &nsolids},
                {27, sizeof(cl_mem), &b->rgb},         {28, sizeof(cl_mem), b->depth ? &b->depth : NULL},
                {29, sizeof(cl_mem), b->normal ? &b->normal : NULL},
                {30, sizeof(cl_mem), b->ids ? &b->ids : NULL},
                {31, sizeof(cl_mem), &b->overlap},     {32, sizeof(cl_mem), b->counts ? &b->counts : NULL},
                {35, sizeof row_end, &row_end},       {36, sizeof(cl_mem), &s->prims},
                {37, sizeof(cl_mem), b->fx ? &b->fx->block : NULL},
                {38, sizeof(cl_mem), b->fx && b->fx->counts ? &b->fx->counts : NULL}};
    for (size_t a = 0; a < sizeof args / sizeof args[0]; a++)
        CLRT_CHECK(err, clSetKernelArg(k, (cl_uint)args[a].index, args[a].size, args[a].value));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* Arguments 4-6 and 33-34: the band's first packet row (with a list: the first packet of listed pixels, a packet's
 * lanes each), the list of pixels to trace (NULL: the band's packets), and the list the overflowing rays go to. */
static iacsg_status set_launch_args(iacsg_renderer *r, cl_int block_row0, const cl_mem *pixels, cl_int npixels,
                                    const cl_mem *overflow, const cl_mem *noverflow, iacsg_error *err) {
    cl_kernel k = r->kernel;
    CLRT_CHECK(err, clSetKernelArg(k, 4, sizeof block_row0, &block_row0));
    CLRT_CHECK(err, clSetKernelArg(k, 5, sizeof(cl_mem), pixels));
    CLRT_CHECK(err, clSetKernelArg(k, 6, sizeof npixels, &npixels));
    CLRT_CHECK(err, clSetKernelArg(k, 33, sizeof(cl_mem), overflow));
    CLRT_CHECK(err, clSetKernelArg(k, 34, sizeof(cl_mem), noverflow));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* One launch over an empty image, so that PoCL compiles the kernel now (see render.c: compile_now). */
static iacsg_status scene_compile_now(iacsg_renderer *r, iacsg_error *err) {
    iacsg_view empty = {0};
    scene_buffers none = {0};
    size_t one[2] = {1, 1};
    iacsg_status st = set_scene_args(r, &empty, &none, err);
    if (st == IACSG_OK)
        st = set_launch_args(r, 0, &none.list[0], 0, &none.list[1], &none.nlist[1], err);
    if (st != IACSG_OK)
        return st;
    CLRT_CHECK(err, clEnqueueNDRangeKernel(r->rt.queue, r->kernel, 2, NULL, one, one, 0, NULL, NULL));
    CLRT_CHECK(err, clFinish(r->rt.queue));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

iacsg_status iacsg_renderer_create_scene(const iacsg_scene *s, const iacsg_render_config *config,
                                         iacsg_renderer **out, iacsg_error *err) {
    *out = NULL;
    if (s->nitems == 0)
        return s->expr ? iacsg_renderer_create_expr(s->expr, config, out, err)
                       : iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the scene has nothing to render");
    /* the tables and the source first: OpenCL may still be loading (clrt_warm_start) */
    char *solids_cl = NULL;
    render_scene *tables = calloc(1, sizeof *tables);
    iacsg_status st = tables ? scene_tables_build(s, &tables->t, err)
                             : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    if (st == IACSG_OK)
        st = scene_emit_cl(s, &solids_cl, err);
    iacsg_renderer *r = NULL;
    if (st == IACSG_OK)
        st = render_open(config, 0, &r, err);
    if (st != IACSG_OK) {
        render_scene_free(tables);
        free(solids_cl);
        return st;
    }
    r->scene = tables;
    const char *sources[] = {iacsg_cl_ia, iacsg_cl_prim, solids_cl, iacsg_cl_scene_kernels};
    st = render_build(r, sources, 4, "iacsg_render_scene", err);
    free(solids_cl);
    if (st == IACSG_OK)
        st = upload_tables(r, r->scene, s, err);
    if (st == IACSG_OK)
        st = render_effects_keep_scene(r, s, err);
    return render_finish(r, st, scene_compile_now, out, err);
}

/* The BVH's boxes in the working precision, rounded outward. They hold where the bounds were proven
 * (implicits/bounds.c: for t in [0, 1], some only inside the cube of IACSG_BOUNDS_CUBE); a view reaching outside
 * that gets infinite boxes: every solid is then bisected along the whole ray. */
static iacsg_status box_buffer(iacsg_renderer *r, const iacsg_view *view, scene_buffers *b, iacsg_error *err) {
    const scene_tables *t = &r->scene->t;
    int proven = !t->uses_time || (view->time[0] >= 0 && view->time[1] <= 1);
    for (int k = 0; k < 3 && t->in_cube; k++)
        proven = proven && view->bounds[k] >= -IACSG_BOUNDS_CUBE && view->bounds[k + 3] <= IACSG_BOUNDS_CUBE;
    size_t count = 6 * (size_t)t->nbvh;
    void *reals = malloc(real_size(r) * (count + 1));
    if (!reals)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    for (size_t k = 0; k < count; k++) {
        int upper = k % 6 >= 3;
        double v = proven ? t->bvh_box[k] : upper ? INFINITY : -INFINITY;
        if (r->config.fp64) {
            ((double *)reals)[k] = v;
            continue;
        }
        float f = (float)v;
        if (upper && (double)f < v)
            f = nextafterf(f, INFINITY);
        if (!upper && (double)f > v)
            f = nextafterf(f, -INFINITY);
        ((float *)reals)[k] = f;
    }
    b->box = table_buffer(r, reals, real_size(r) * count, err);
    free(reals);
    return b->box ? IACSG_OK : IACSG_ERR_OPENCL;
}

/* The frame's images, the overlaps and the counts are device buffers over host arrays (CL_MEM_USE_HOST_PTR): on a
 * CPU device the kernel writes them in place, with no copy back (the counts are 12 bytes a pixel). */
static iacsg_status frame_buffers_of(iacsg_renderer *r, const iacsg_view *view, const void *params, size_t n,
                                     iacsg_frame *f, cl_int *overlap, cl_uint *counts, scene_buffers *b,
                                     iacsg_error *err) {
    cl_context ctx = r->rt.context;
    cl_int rc = CL_SUCCESS;
    b->params = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, PARAM_COUNT * real_size(r),
                               (void *)params, &rc);
    CLRT_CHECK(err, rc);
    cl_mem_flags image = CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR;
    float *images[] = {f->rgb, f->depth, f->normal, f->ids};
    cl_mem *dst[] = {&b->rgb, &b->depth, &b->normal, &b->ids};
    size_t floats[] = {3, 1, 3, 1};
    for (int k = 0; k < 4; k++) {
        if (!images[k])
            continue;
        *dst[k] = clCreateBuffer(ctx, image, floats[k] * n * sizeof(float), images[k], &rc);
        CLRT_CHECK(err, rc);
    }
    b->overlap = clCreateBuffer(ctx, image, n * sizeof(cl_int), overlap, &rc);
    CLRT_CHECK(err, rc);
    if (counts) {
        b->counts = clCreateBuffer(ctx, image, 3 * n * sizeof(cl_uint), counts, &rc);
        CLRT_CHECK(err, rc);
    }
    for (int k = 0; k < 2; k++) {
        b->list[k] = clCreateBuffer(ctx, CL_MEM_READ_WRITE, n * sizeof(cl_int), NULL, &rc);
        CLRT_CHECK(err, rc);
        b->nlist[k] = clCreateBuffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_int), NULL, &rc);
        CLRT_CHECK(err, rc);
    }
    return box_buffer(r, view, b, err);
fail:
    return IACSG_ERR_OPENCL;
}

/* A fill, not a non-blocking write: the write would read `zero` after it went out of scope (it did, listing
 * garbage pixels for re-tracing), while a fill copies its pattern at once. */
static iacsg_status zero_count(iacsg_renderer *r, cl_mem count, iacsg_error *err) {
    cl_int zero = 0;
    CLRT_CHECK(err, clEnqueueFillBuffer(r->rt.queue, count, &zero, sizeof zero, 0, sizeof zero, 0, NULL, NULL));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* The first pass: the view's rows (render_launch_bands) in bands of blocks (SCENE_BLOCK_H rows), each cut so that
 * its work-items' per-ray buffers fit the budget. Rays that overflow are listed in list[0]. */
static iacsg_status first_pass(iacsg_renderer *r, const iacsg_view *view, scene_buffers *b, iacsg_error *err) {
    size_t block_w = (size_t)render_block_w(r), groups_x = ((size_t)view->width + block_w - 1) / block_w;
    int rows = view->row_count ? view->row_count : view->height;
    size_t block_rows = ((size_t)rows + SCENE_BLOCK_H - 1) / SCENE_BLOCK_H;
    double per_row = (double)groups_x * (double)slot_bytes(r, b->cand_cap);
    size_t most = (size_t)fmax(1, fmin(SCENE_BAND_BLOCKS, SCENE_SCRATCH_BUDGET / per_row));
    most = most < block_rows ? most : block_rows;
    iacsg_status st = scratch_buffers(r, b, groups_x * most, b->cand_cap, err);
    if (st == IACSG_OK)
        st = zero_count(r, b->nlist[0], err);
    if (st == IACSG_OK)
        st = set_scene_args(r, view, b, err);
    cl_mem none = NULL;
    if (st == IACSG_OK)
        st = set_launch_args(r, 0, &none, 0, &b->list[0], &b->nlist[0], err);
    if (st == IACSG_OK)
        st = render_launch_bands(r, r->kernel, view, groups_x, SCENE_BLOCK_H, 1, (int)most, err);
    return st;
}

/* Traces the listed rays again with four times the room until none overflows. */
static iacsg_status retrace(iacsg_renderer *r, const iacsg_view *view, scene_buffers *b, iacsg_frame *f,
                            iacsg_error *err) {
    int from = 0;
    for (;;) {
        cl_int listed = 0;
        CLRT_CHECK(err, clEnqueueReadBuffer(r->rt.queue, b->nlist[from], CL_TRUE, 0, sizeof listed, &listed, 0, NULL,
                                            NULL));
        if (listed == 0)
            return IACSG_OK;
        f->retraced_rays += listed;
        int cand_cap = 4 * b->cand_cap; /* a ray meets at most every solid: this ends */
        if (cand_cap > r->scene->t.nsolids)
            cand_cap = r->scene->t.nsolids;
        size_t lanes = (size_t)render_packet_lanes(r), slots = ((size_t)listed + lanes - 1) / lanes;
        size_t fit = (size_t)fmax(1, SCENE_SCRATCH_BUDGET / (double)slot_bytes(r, cand_cap));
        iacsg_status st = scratch_buffers(r, b, slots < fit ? slots : fit, cand_cap, err);
        if (st == IACSG_OK)
            st = set_scene_args(r, view, b, err);
        if (st == IACSG_OK)
            st = zero_count(r, b->nlist[1 - from], err);
        /* launches of at most b->slots work-items, each over its part of the list */
        for (size_t first = 0; st == IACSG_OK && first < slots; first += b->slots) {
            size_t count = slots - first < b->slots ? slots - first : b->slots;
            st = set_launch_args(r, (cl_int)first, &b->list[from], listed, &b->list[1 - from], &b->nlist[1 - from],
                                 err);
            size_t global[2] = {count, 1}, local[2] = {1, 1};
            if (st == IACSG_OK)
                CLRT_CHECK(err, clEnqueueNDRangeKernel(r->rt.queue, r->kernel, 2, NULL, global, local, 0, NULL, NULL));
        }
        if (st != IACSG_OK)
            return st;
        from = 1 - from;
    }
fail:
    return IACSG_ERR_OPENCL;
}

/* The statistics of the frame from the per-pixel overlaps and counts. */
static void summarize(const cl_int *overlap, const cl_uint *counts, const float *ids, size_t n, iacsg_frame *f) {
    double segments = 0, partitions = 0, evals = 0;
    for (size_t k = 0; k < n; k++) {
        if (overlap[k] >= 0) {
            int pair[2] = {(int)ids[k], overlap[k]}, seen = 0;
            f->overlaps += 1;
            for (int p = 0; p < f->noverlap_pairs; p++)
                seen |= f->overlap_pairs[p][0] == pair[0] && f->overlap_pairs[p][1] == pair[1];
            if (!seen && f->noverlap_pairs < IACSG_OVERLAP_PAIRS) {
                f->overlap_pairs[f->noverlap_pairs][0] = pair[0];
                f->overlap_pairs[f->noverlap_pairs++][1] = pair[1];
            }
        }
        if (!counts)
            continue;
        const cl_uint *c = counts + 3 * k;
        evals += c[0];
        segments += c[1];
        partitions += c[2];
        f->evals_max = c[0] > f->evals_max ? c[0] : f->evals_max;
        f->segments_max = c[1] > f->segments_max ? c[1] : f->segments_max;
        f->partitions_max = c[2] > f->partitions_max ? c[2] : f->partitions_max;
    }
    f->evals_mean = evals / (double)n;
    f->segments_mean = segments / (double)n;
    f->partitions_mean = partitions / (double)n;
}

static iacsg_status read_scene_back(iacsg_renderer *r, const scene_buffers *b, size_t n, iacsg_error *err) {
    cl_command_queue q = r->rt.queue;
    cl_mem in_place[7] = {b->rgb, b->depth, b->normal, b->ids, b->overlap, b->counts, b->fx ? b->fx->counts : NULL};
    size_t sizes[7] = {3 * n * sizeof(float), n * sizeof(float),   3 * n * sizeof(float), n * sizeof(float),
                       n * sizeof(cl_int),    3 * n * sizeof(cl_uint), 2 * n * sizeof(cl_uint)};
    for (int k = 0; k < 7; k++) { /* mapping a USE_HOST_PTR buffer makes its host array current */
        if (!in_place[k])
            continue;
        cl_int rc = CL_SUCCESS;
        void *p = clEnqueueMapBuffer(q, in_place[k], CL_FALSE, CL_MAP_READ, 0, sizes[k], 0, NULL, NULL, &rc);
        CLRT_CHECK(err, rc);
        CLRT_CHECK(err, clEnqueueUnmapMemObject(q, in_place[k], p, 0, NULL, NULL));
    }
    CLRT_CHECK(err, clFinish(q));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

iacsg_status render_scene_frame(iacsg_renderer *r, const iacsg_view *view, iacsg_frame *frame, iacsg_error *err) {
    memset(frame, 0, sizeof *frame);
    double params[PARAM_COUNT];
    iacsg_status st = render_check_view(view, err);
    if (st == IACSG_OK)
        st = render_fill_params(view, r->config.fp64, params, err);
    if (st != IACSG_OK)
        return st;
    size_t n = (size_t)view->width * (size_t)view->height;
    frame->width = view->width;
    frame->height = view->height;
    frame->rgb = render_image_alloc(3 * n);
    int fx_depth, fx_normal;
    render_effects_aovs(r, view, &fx_depth, &fx_normal);
    frame->depth = view->no_depth && !fx_depth ? NULL : render_image_alloc(n);
    frame->normal = view->no_normals && !fx_normal ? NULL : render_image_alloc(3 * n);
    frame->ids = render_image_alloc(n); /* the overlaps' statistics need them */
    cl_int *overlap = render_in_place_alloc(n * sizeof(cl_int));
    cl_uint *counts = r->config.stats ? render_in_place_alloc(3 * n * sizeof(cl_uint)) : NULL;
    if (!frame->rgb || (!frame->depth && (!view->no_depth || fx_depth)) ||
        (!frame->normal && (!view->no_normals || fx_normal)) || !frame->ids || !overlap || (r->config.stats && !counts))
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for a %dx%d image", view->width,
                             view->height);
    scene_buffers b = {0};
    b.cand_cap = r->config.ray_candidates > 0 ? r->config.ray_candidates : SCENE_RAY_CANDIDATES;
    /* rgb, depth, normal, ids, overlap, two lists of re-traced pixels (and 3 counts with stats, 2 more where the
     * kernel counts its effects' rays) */
    int fx_in_camera = render_effects_in_camera(r, view);
    if (st == IACSG_OK)
        st = render_check_device_memory(r, view, n, r->config.stats ? 15 + 2 * fx_in_camera : 12, err);
    render_fx_camera fx_camera = {0};
    if (st == IACSG_OK && fx_in_camera) {
        st = render_effects_camera_open(r, view, n, &fx_camera, err); /* counts: 2 a pixel */
        b.fx = &fx_camera;
    }
    if (st == IACSG_OK)
        st = frame_buffers_of(r, view, params, n, frame, overlap, counts, &b, err);
    double t0 = render_now_seconds();
    if (st == IACSG_OK)
        st = first_pass(r, view, &b, err);
    if (st == IACSG_OK)
        st = retrace(r, view, &b, frame, err);
    if (st == IACSG_OK)
        st = read_scene_back(r, &b, n, err);
    if (st == IACSG_OK) {
        frame->render_seconds = render_now_seconds() - t0;
        /* the rays of the rows traced */
        size_t at = (size_t)view->row_first * (size_t)view->width;
        size_t traced = view->row_count ? (size_t)view->row_count * (size_t)view->width : n;
        frame->rays = (long long)traced;
        frame->ray_buffer_bytes = (long long)slot_bytes(r, b.cand_cap);
        summarize(overlap + at, counts ? counts + 3 * at : NULL, frame->ids + at, traced, frame);
        st = render_effects_apply(r, view, frame, b.fx, NULL, err);
        float **unasked[] = {view->no_depth ? &frame->depth : NULL, view->no_normals ? &frame->normal : NULL};
        for (int k = 0; k < 2; k++)
            if (unasked[k]) {
                free(*unasked[k]);
                *unasked[k] = NULL;
            }
        if (view->no_ids) {
            free(frame->ids);
            frame->ids = NULL;
        }
    }
    release_scene_buffers(&b);
    render_effects_camera_close(&fx_camera);
    free(overlap);
    free(counts);
    if (st != IACSG_OK)
        iacsg_frame_free(frame);
    return st;
}

/* The effects' trace kernel (kernels/scene_effects.cl, src/render_effects.c) gets the scene from argument `first`
 * on: the tables, the view's BVH boxes, per-ray buffers for at most *slots work-items (fewer when they would
 * pass the launch budget; *slots is set to the count) with room for every solid, so that no ray overflows, then the
 * primitives' table (kernels/scene_prims.h). The frame's buffers go to *held, released by
 * render_scene_trace_release. */
iacsg_status render_scene_trace_args(iacsg_renderer *r, const iacsg_view *view, cl_kernel k, cl_uint first,
                                     size_t *slots, void **held, iacsg_error *err) {
    render_scene *s = r->scene;
    scene_buffers *b = calloc(1, sizeof *b);
    *held = b;
    if (!b)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    cl_int cap = s->t.nsolids > 0 ? s->t.nsolids : 1, nbvh = s->t.nbvh, nsurfaces = s->t.nsurfaces;
    cl_int nstates = s->t.nsolids + 1;
    size_t fit = (size_t)fmax(1, SCENE_SCRATCH_BUDGET / (double)slot_bytes(r, cap));
    iacsg_status st = box_buffer(r, view, b, err);
    if (st == IACSG_OK)
        st = scratch_buffers(r, b, *slots < fit ? *slots : fit, cap, err);
    if (st != IACSG_OK)
        return st;
    *slots = b->slots;
    const void *args[] = {&b->box,        &s->bvh_link,   &nbvh,        &s->nodes,       &s->items,
                          &s->solid_items_start, &s->solid_items, &s->surfaces, &nsurfaces, &b->cand_solid,
                          &b->cand_range, &b->cand_pos,   &b->cand_level, &b->cand_index, &b->cand_newton,
                          &b->cand_newton_t, &cap,        &b->state,    &nstates,      &s->prims};
    for (cl_uint a = 0; a < sizeof args / sizeof args[0]; a++) {
        int is_int = args[a] == &nbvh || args[a] == &nsurfaces || args[a] == &cap || args[a] == &nstates;
        CLRT_CHECK(err, clSetKernelArg(k, first + a, is_int ? sizeof(cl_int) : sizeof(cl_mem), args[a]));
    }
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

void render_scene_trace_release(void *held) {
    if (held)
        release_scene_buffers(held);
    free(held);
}

const float *render_scene_materials(const iacsg_renderer *r) { return r->scene->t.albedo; }
