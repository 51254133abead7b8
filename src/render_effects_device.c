/* src/render_effects_device.c -- the first-root path's effects on the device (kernels/effects.cl): the paths of
 * one kind (the frame's centre rays, or -aa's rays) launched in slices, each launch colouring the frame and
 * listing the paths' reflected rays, which the next launch takes (one launch per bounce):
 *
 *   pixels (block order) --> iacsg_effects (mode) --> a centre ray's colour in its pixel (final where it listed
 *     no reflected ray), -aa's colours summed per pixel (n >= 3: the n x n grid's corners first, then the rest of
 *     it only in the pixels whose corners differ or list a reflected ray: the others take the corners' mean; -aa's
 *     walks in FX_AA_ROUNDS launches queued in turn, the paths a round leaves going on in the next, in full
 *     packets); reflected rays
 *     --> iacsg_effects (EFFECTS_MODE_PATHS, bounce + 1) --> colours summed per pixel --> ... until none is listed
 *   --> the pixels summed on the host encoded (gamma 2)
 *
 * The host only converts the effects' block to the working precision, moves the lists and sums the colours of
 * the paths that share a pixel.
 */
#include "render_effects_trace.h"
#include "kernels/effects.h"
#include "kernels/params.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Paths times their reflected rays' slots per launch: its buffers stay a few MB. Paths that list no reflected ray
 * go FX_DEVICE_PATHS a launch: a megapixel's hits in one launch (each launch waits for its end, costly on a busy
 * machine). */
#define FX_DEVICE_SLOTS ((size_t)1 << 18)
#define FX_DEVICE_PATHS ((size_t)1 << 20)

/* The paths of one launch at most. */
static size_t launch_paths(int kid_slots) {
    return kid_slots ? FX_DEVICE_SLOTS / (size_t)kid_slots : FX_DEVICE_PATHS;
}

/* A generation of paths of the mode EFFECTS_MODE_PATHS: their pixels and records (EFFECTS_PATH_REALS each, in the
 * working precision). Grows. */
typedef struct {
    int *pixel;
    char *rec;
    size_t n, cap;
} fx_generation;

static int generation_reserve(fx_generation *g, size_t n, size_t rb) {
    if (n <= g->cap)
        return 1;
    size_t cap = 2 * n + 64; /* doubling: each growth copies what is there */
    int *p = realloc(g->pixel, cap * sizeof *p);
    if (p)
        g->pixel = p;
    char *q = p ? realloc(g->rec, cap * EFFECTS_PATH_REALS * rb) : NULL;
    if (q)
        g->rec = q;
    if (!p || !q)
        return 0;
    g->cap = cap;
    return 1;
}

/* The host side of the launches of one frame. */
typedef struct {
    fx_tracer *t;
    cl_kernel k;
    cl_mem fx, depth, normal, rgb;
    const iacsg_view *view;
    int kid_slots; /* reflected rays a path may list */
    float *accum;  /* the frame's rgb */
    int *summed;   /* the pixels whose light is summed here, to encode at the end */
    size_t nsummed;
    const double *aa_eps_footprint; /* -aa: the leaves' width and Newton's window */
    int aa_set;                     /* -aa: the rays of each pixel traced (kernels/effects.h: EFFECTS_AA_ALL...) */
    float *corners;                 /* EFFECTS_AA_CORNERS: each path's colour, 3 floats, in the order traced */
    unsigned char *corner_kids;     /* and per pixel whether a corner listed a reflected ray */
    size_t ncorners;                /* the paths kept so far */
    /* per launch, reused: colours, reflected rays and their counts, statistics */
    float *color;
    char *kids;
    int *nkids;
    cl_uint *stats;
} fx_device;

static iacsg_status set_arg(cl_kernel k, cl_uint at, size_t bytes, const void *v, iacsg_error *err) {
    cl_int rc = clSetKernelArg(k, at, bytes, v);
    return rc == CL_SUCCESS ? IACSG_OK : clrt_record(err, rc, "clSetKernelArg(iacsg_effects)", __func__, __LINE__);
}

/* -aa's launches over a slice of paths: rounds of FX_AA_TURNS turns of their walks (or the config's aa_turns), a
 * round's leftover paths the next round's (kernels/effects.cl: iacsg_effects), the last round to their ends. A
 * packet waits for its slowest ray: the samples of the multiple unions' edges kept 47-50 % of their packets' lanes
 * busy (the reference view's and a gyroid's 63-66 %). The paths left after each round, the multiple unions' -aa 4
 * rest rays: 95,328 -> 28,378 -> 9,227 -> 3,495 -> 1,606; its -aa 4 frame 195-207 -> 171-177 ms (medians of 7 in
 * turn, three pairs), the reference view's and the gyroid's within the noise (2 % of the reference view's samples go
 * on after a round; 3 rounds instead of 5: the multiple unions 184 ms). Rounds are queued in turn, with no wait
 * between (a wait costs ~2 ms on PoCL): rounds that the host listed after each launch gained half as much on the
 * multiple unions and cost the gyroid 3 %. */
#define FX_AA_ROUNDS 5
#define FX_AA_TURNS 48
#define FX_AA_ITEMS 64 /* a round's work-items at least */

/* The arguments of iacsg_effects from `at` on for -aa's round r of FX_AA_ROUNDS over lists[2] and counts, their
 * hits in `hits` where it is not NULL (r = FX_AA_ROUNDS: the shading after them, round -1); none without buffers
 * (another mode). */
static iacsg_status set_round_args(fx_device *x, cl_uint at, const cl_mem buffers[4], cl_int r, iacsg_error *err) {
    const cl_mem *lists = buffers, *counts = &buffers[2], *hits = &buffers[3];
    int on = buffers[0] != NULL, tracing = on && r < FX_AA_ROUNDS;
    const cl_mem *from = tracing && r > 0 ? &lists[(r + 1) % 2] : NULL;
    const cl_mem *left = tracing && r + 1 < FX_AA_ROUNDS ? &lists[r % 2] : NULL;
    cl_int turns = x->t->r->config.aa_turns > 0 ? x->t->r->config.aa_turns : FX_AA_TURNS;
    cl_int round = tracing ? r : -1;
    iacsg_status st = set_arg(x->k, at, sizeof(cl_mem), from, err);
    if (st == IACSG_OK)
        st = set_arg(x->k, at + 1, sizeof(cl_mem), left, err);
    if (st == IACSG_OK)
        st = set_arg(x->k, at + 2, sizeof(cl_mem), tracing ? counts : NULL, err);
    if (st == IACSG_OK)
        st = set_arg(x->k, at + 3, sizeof round, &round, err);
    if (st == IACSG_OK)
        st = set_arg(x->k, at + 4, sizeof turns, &turns, err);
    return st == IACSG_OK ? set_arg(x->k, at + 5, sizeof(cl_mem), *hits ? hits : NULL, err) : st;
}

/* One launch over paths [0, n) of `mode` (kernels/effects.cl's arguments), n at most launch_paths(kid_slots), in
 * rounds for -aa: adds their colours to the frame and appends their reflected rays to `next`. */
static iacsg_status launch(fx_device *x, int mode, const int *pixels, size_t npixels, const char *recs, size_t n,
                           int aa, fx_generation *next, iacsg_error *err) {
    iacsg_renderer *r = x->t->r;
    size_t rb = fx_real_bytes(r);
    cl_mem mem[6] = {0}, rounds_mem[4] = {0}; /* pixels, paths, colours, kids, nkids, stats; -aa's rounds' */
    size_t bytes[6] = {npixels * sizeof(int), n * EFFECTS_PATH_REALS * rb, 3 * n * sizeof(float),
                       n * (size_t)x->kid_slots * EFFECTS_PATH_REALS * rb, n * sizeof(int), 2 * n * sizeof(cl_uint)};
    void *host[6] = {(void *)pixels, (void *)recs, x->color, x->kids, x->nkids, x->stats};
    iacsg_status st = IACSG_OK;
    for (int b = 0; b < 6 && st == IACSG_OK; b++) {
        if (!host[b] || bytes[b] == 0 || (b == 1 && mode != EFFECTS_MODE_PATHS) ||
            ((b == 3 || b == 4) && !x->kid_slots))
            continue;
        cl_int rc = CL_SUCCESS;
        mem[b] = clCreateBuffer(r->rt.context, (b < 2 ? CL_MEM_READ_ONLY : CL_MEM_WRITE_ONLY) | CL_MEM_USE_HOST_PTR,
                                bytes[b], host[b], &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(effects)", __func__, __LINE__);
    }
    /* -aa's rounds (else one launch): the paths a round leaves, in turn, and how many each leaves; where the paths
     * trace secondary rays, the walks' hits and the shading after the rounds */
    int secondary = fx_traces_secondary(r, x->view->effects);
    int launches = mode == EFFECTS_MODE_AA && n > 0 ? FX_AA_ROUNDS + secondary : 1;
    if (launches > 1 && st == IACSG_OK) {
        cl_int rc = CL_SUCCESS, zero[FX_AA_ROUNDS] = {0};
        size_t sizes[4] = {n * EFFECTS_LEFT_REALS * rb, n * EFFECTS_LEFT_REALS * rb, sizeof zero, 4 * n * rb};
        for (int k = 0; k < 3 + secondary && rc == CL_SUCCESS; k++)
            rounds_mem[k] = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE | (k == 2 ? CL_MEM_COPY_HOST_PTR : 0),
                                           sizes[k], k == 2 ? zero : NULL, &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(effects)", __func__, __LINE__);
    }
    cl_int flags = x->view->camera.ortho_height > 0 ? RENDER_ORTHO : 0, w = x->view->width, h = x->view->height;
    cl_int ni = (cl_int)n, cl_mode = mode, cl_aa = aa, slots = x->kid_slots, set = x->aa_set;
    char aa_eps[8], footprint[8];
    double reals[2] = {x->aa_eps_footprint[0], x->aa_eps_footprint[1]};
    char *dst[2] = {aa_eps, footprint};
    for (int q = 0; q < 2; q++) {
        double one[1];
        fx_put_real(r, one, 0, reals[q]);
        memcpy(dst[q], one, rb);
    }
    struct {
        size_t bytes;
        const void *v;
    } args[] = {{sizeof(cl_mem), &x->t->params}, {sizeof(cl_mem), &x->fx},   {sizeof cl_mode, &cl_mode},
                {sizeof flags, &flags},          {sizeof w, &w},             {sizeof h, &h},
                {sizeof(cl_mem), &mem[0]},       {sizeof(cl_mem), &mem[1]},  {sizeof ni, &ni},
                {sizeof cl_aa, &cl_aa},          {sizeof(cl_mem), &x->depth},
                {sizeof(cl_mem), &x->normal},    {rb, aa_eps},
                {rb, footprint},                 {sizeof(cl_mem), &x->t->all_groups}, {sizeof(cl_mem), &x->rgb},
                {sizeof(cl_mem), &mem[2]},       {sizeof(cl_mem), &mem[3]},  {sizeof(cl_mem), &mem[4]},
                {sizeof slots, &slots},          {sizeof(cl_mem), &mem[5]},  {sizeof set, &set},
                {sizeof(cl_mem), x->t->tiles.leaves ? &x->t->tiles.leaves : NULL},
                {sizeof(cl_mem), x->t->tiles.groups ? &x->t->tiles.groups : NULL}};
    for (cl_uint a = 0; a < sizeof args / sizeof args[0] && st == IACSG_OK; a++)
        st = set_arg(x->k, a, args[a].bytes, args[a].v, err);
    size_t lanes = (size_t)render_packet_lanes(r), local = 1;
    size_t global = n > 0 ? (n + lanes - 1) / lanes : 1; /* n = 0: compile_now */
    cl_int rc = CL_SUCCESS;
    for (cl_int round = 0; round < launches && st == IACSG_OK && rc == CL_SUCCESS; round++) {
        st = set_round_args(x, sizeof args / sizeof args[0], rounds_mem, round, err);
        /* a round leaves about a third of its paths: a quarter of the last round's work-items, each packet after
         * its own as many packets on (empty work-items cost a launch ~40 % of a gyroid's -aa 4 samples' time); the
         * shading, a work-item a packet */
        int shift = round < FX_AA_ROUNDS ? 2 * round : 0;
        size_t items = (global >> shift) > FX_AA_ITEMS ? global >> shift : FX_AA_ITEMS;
        items = items < global ? items : global;
        if (st == IACSG_OK)
            rc = clEnqueueNDRangeKernel(r->rt.queue, x->k, 1, NULL, &items, &local, 0, NULL, NULL);
    }
    if (st == IACSG_OK && rc == CL_SUCCESS)
        rc = clFinish(r->rt.queue);
    if (st == IACSG_OK && rc != CL_SUCCESS)
        st = clrt_record(err, rc, "clEnqueueNDRangeKernel(iacsg_effects)", __func__, __LINE__);
    /* a CPU device wrote the host arrays in place; another is made to by mapping them */
    for (int b = 2; b < 6 && st == IACSG_OK; b++)
        if (mem[b])
            st = fx_sync_to_host(r->rt.queue, mem[b], bytes[b], err);
    size_t samples = mode == EFFECTS_MODE_AA ? (size_t)effects_aa_rays(aa, x->aa_set) : 1;
    int keep = mode == EFFECTS_MODE_AA && x->aa_set == EFFECTS_AA_CORNERS;
    /* centre rays that list no reflected ray and count nothing left all in the frame: no pass over them */
    int per_path = mode != EFFECTS_MODE_CENTRE || mem[5] || x->kid_slots;
    for (size_t i = 0; st == IACSG_OK && per_path && i < n; i++) {
        int pixel = pixels[i / samples];
        for (int c = 0; mode != EFFECTS_MODE_CENTRE && c < 3; c++) /* a centre ray's is in the frame already */
            x->accum[3 * (size_t)pixel + c] += x->color[3 * i + c];
        if (mem[5]) {
            x->t->rays += x->stats[2 * i];
            x->t->evals += x->stats[2 * i + 1];
        }
        int nk = x->kid_slots ? x->nkids[i] : 0;
        if (keep) {
            memcpy(x->corners + 3 * x->ncorners, x->color + 3 * i, 3 * sizeof(float));
            x->corner_kids[x->ncorners++ / 4] |= nk > 0;
        }
        if (mode == EFFECTS_MODE_CENTRE && nk > 0) /* its linear light, which the reflected rays add to */
            x->summed[x->nsummed++] = pixel;
        if (nk > 0 && !generation_reserve(next, next->n + (size_t)nk, rb))
            st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the reflected rays");
        for (int q = 0; st == IACSG_OK && q < nk; q++) {
            next->pixel[next->n] = pixel;
            memcpy(next->rec + next->n * EFFECTS_PATH_REALS * rb,
                   x->kids + (i * (size_t)x->kid_slots + (size_t)q) * EFFECTS_PATH_REALS * rb, EFFECTS_PATH_REALS * rb);
            next->n++;
        }
    }
    cl_mem all[] = {mem[0],        mem[1],        mem[2],        mem[3],       mem[4],
                    mem[5],        rounds_mem[0], rounds_mem[1], rounds_mem[2], rounds_mem[3]};
    for (size_t b = 0; b < sizeof all / sizeof all[0]; b++)
        if (all[b])
            clReleaseMemObject(all[b]);
    return st;
}

/* The launches over n paths of `mode`, in slices that the per-launch buffers hold (for -aa, whole pixels). */
static iacsg_status launch_all(fx_device *x, int mode, const int *pixels, const char *recs, size_t n, int aa,
                               fx_generation *next, iacsg_error *err) {
    size_t rb = fx_real_bytes(x->t->r);
    size_t samples = mode == EFFECTS_MODE_AA ? (size_t)effects_aa_rays(aa, x->aa_set) : 1;
    size_t slice = launch_paths(x->kid_slots) / (samples * PACKET_LANES) * samples * PACKET_LANES;
    iacsg_status st = IACSG_OK;
    for (size_t at = 0; st == IACSG_OK && at < n; at += slice) {
        size_t m = n - at < slice ? n - at : slice;
        st = launch(x, mode, pixels + at / samples, (m + samples - 1) / samples,
                    recs ? recs + at * EFFECTS_PATH_REALS * rb : NULL, m, aa, next, err);
    }
    return st;
}

/* -aa's corners agree where each channel of their display colours spans at most this: half the edge test's
 * contrast, so that their mean is as close to the pixel's as all the grid's rays' (a sphere's highlight at -aa 4,
 * against the plain render: 6.1e-3 so, as with 16 rays; 1.0e-2 at 1/16). */
#define FX_AA_CORNERS_AGREE (FX_AA_CONTRAST / 2)

/* -aa's rays of pixels[0 .. npixels) for aa >= 3, their colours summed into the frame: the grid's corners, then
 * the rest of it where the corners disagree (FX_AA_CORNERS_AGREE) or one listed a reflected ray (whose light comes
 * later); a pixel whose corners agree takes their mean. On the reference view at -aa 4, 42 % of the edge pixels
 * came out of all 16 rays with their centre ray's colour; half of them are left at their corners so (61,476
 * rays against 97,920). */
static iacsg_status launch_aa_adaptive(fx_device *x, const int *pixels, size_t npixels, int aa,
                                       fx_generation *next, iacsg_error *err) {
    x->corners = malloc((12 * npixels + 1) * sizeof *x->corners);
    x->corner_kids = calloc(npixels + 1, 1);
    x->ncorners = 0;
    int *rest = malloc((npixels + 1) * sizeof *rest);
    iacsg_status st = x->corners && x->corner_kids && rest
                          ? IACSG_OK
                          : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for -aa's rays");
    x->aa_set = EFFECTS_AA_CORNERS;
    if (st == IACSG_OK)
        st = launch_all(x, EFFECTS_MODE_AA, pixels, NULL, 4 * npixels, aa, next, err);
    size_t nrest = 0;
    float w = 1.0f / (float)(aa * aa); /* each ray's weight; the corners' mean is their sum / (4 w) */
    for (size_t q = 0; st == IACSG_OK && q < npixels; q++) {
        const float *c = x->corners + 12 * q;
        int differ = x->corner_kids[q];
        for (int ch = 0; ch < 3 && !differ; ch++) {
            float lo = fx_display(c[ch] / w), hi = lo; /* the display colour of each corner's own light */
            for (int k = 1; k < 4; k++) {
                float v = fx_display(c[3 * k + ch] / w);
                lo = fminf(lo, v);
                hi = fmaxf(hi, v);
            }
            differ = hi - lo > (float)FX_AA_CORNERS_AGREE;
        }
        if (differ)
            rest[nrest++] = pixels[q];
        else
            for (int ch = 0; ch < 3; ch++)
                x->accum[3 * (size_t)pixels[q] + ch] /= 4 * w;
    }
    x->aa_set = EFFECTS_AA_REST;
    if (st == IACSG_OK && nrest > 0)
        st = launch_all(x, EFFECTS_MODE_AA, rest, NULL, nrest * (size_t)effects_aa_rays(aa, EFFECTS_AA_REST), aa,
                        next, err);
    x->aa_set = EFFECTS_AA_ALL;
    free(x->corners);
    free(x->corner_kids);
    x->corners = NULL;
    x->corner_kids = NULL;
    free(rest);
    return st;
}

iacsg_status fx_device_run(fx_tracer *t, const double *block, int kid_slots, int mode, const int *pixels,
                           size_t npixels, int aa, const double aa_eps_footprint[2], iacsg_frame *frame,
                           iacsg_error *err) {
    iacsg_renderer *r = t->r;
    size_t rb = fx_real_bytes(r), n = npixels * (mode == EFFECTS_MODE_AA ? (size_t)aa * aa : 1);
    if (n == 0)
        return IACSG_OK;
    fx_device x = {.t = t, .k = r->fx->trace, .view = t->view, .kid_slots = kid_slots, .accum = frame->rgb,
                   .aa_eps_footprint = aa_eps_footprint};
    fx_generation gen[2] = {{0}};
    size_t slots = FX_DEVICE_SLOTS, paths = launch_paths(kid_slots) + PACKET_LANES;
    x.color = malloc(3 * paths * sizeof(float));
    x.nkids = malloc(paths * sizeof(int));
    x.stats = r->config.stats ? malloc(2 * paths * sizeof(cl_uint)) : NULL;
    x.kids = kid_slots ? malloc((slots + PACKET_LANES * (size_t)kid_slots) * EFFECTS_PATH_REALS * rb) : NULL;
    size_t npix = (size_t)frame->width * (size_t)frame->height;
    cl_int rc = CL_SUCCESS;
    iacsg_status st = IACSG_OK;
    x.summed = malloc((npixels + 1) * sizeof *x.summed);
    if (!x.color || !x.nkids || (r->config.stats && !x.stats) || (kid_slots && !x.kids) || !x.summed)
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
    if (st == IACSG_OK)
        st = fx_block_buffer(r, block, &x.fx, err);
    if (st == IACSG_OK && mode == EFFECTS_MODE_CENTRE) { /* the centre hits (other modes trace their rays) */
        x.depth = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, npix * sizeof(float),
                                 frame->depth, &rc);
        if (rc == CL_SUCCESS)
            x.normal = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR,
                                      3 * npix * sizeof(float), frame->normal, &rc);
    }
    if (st == IACSG_OK) {
        if (rc == CL_SUCCESS)
            x.rgb = clCreateBuffer(r->rt.context, CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, 3 * npix * sizeof(float),
                                   frame->rgb, &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(effects)", __func__, __LINE__);
    }
    if (st == IACSG_OK && mode == EFFECTS_MODE_AA) /* the samples' light replaces the centre ray's colour */
        for (size_t k = 0; k < npixels; k++) {
            memset(frame->rgb + 3 * (size_t)pixels[k], 0, 3 * sizeof(float));
            x.summed[x.nsummed++] = pixels[k];
        }
    /* room for one reflected ray a path, what a frame without transparency lists at most */
    if (st == IACSG_OK && kid_slots && !generation_reserve(&gen[0], n, rb))
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the reflected rays");
    if (st == IACSG_OK)
        st = mode == EFFECTS_MODE_AA && aa >= 3 ? launch_aa_adaptive(&x, pixels, npixels, aa, &gen[0], err)
                                                : launch_all(&x, mode, pixels, NULL, n, aa, &gen[0], err);
    for (int g = 0; st == IACSG_OK && gen[g].n > 0; g = 1 - g) {
        gen[1 - g].n = 0;
        st = launch_all(&x, EFFECTS_MODE_PATHS, gen[g].pixel, gen[g].rec, gen[g].n, aa, &gen[1 - g], err);
        gen[g].n = 0;
    }
    if (st == IACSG_OK && x.rgb) /* the frame current on the host after the kernels wrote it */
        st = fx_sync_to_host(r->rt.queue, x.rgb, 3 * npix * sizeof(float), err);
    for (size_t k = 0; st == IACSG_OK && k < x.nsummed; k++)
        fx_encode(frame->rgb, x.summed[k]);
    cl_mem all[4] = {x.fx, x.depth, x.normal, x.rgb};
    for (int k = 0; k < 4; k++)
        if (all[k])
            clReleaseMemObject(all[k]);
    for (int g = 0; g < 2; g++) {
        free(gen[g].pixel);
        free(gen[g].rec);
    }
    free(x.color);
    free(x.nkids);
    free(x.stats);
    free(x.kids);
    free(x.summed);
    return st;
}

iacsg_status fx_device_compile(fx_tracer *t, iacsg_error *err) {
    fx_device x = {.t = t, .k = t->r->fx->trace, .view = t->view};
    double none[2] = {0, 0};
    x.aa_eps_footprint = none;
    int pixel = 0;
    return launch(&x, EFFECTS_MODE_CENTRE, &pixel, 0, NULL, 0, 1, NULL, err);
}
