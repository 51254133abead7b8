/* src/render.c -- see render.h. One program per expression: the ia/ headers, the expression's emitted source
 * and the kernels, concatenated (all three embedded or generated, so nothing is read from disk). A frame is
 * traced in bands of rows, so that progress can be reported and no single launch runs for long. */
#define _DEFAULT_SOURCE /* MADV_HUGEPAGE */
#include "render_internal.h"
#include "kernels/params.h"
#include "implicits/tape.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

extern const char iacsg_cl_kernels[]; /* the flattened kernels/ (Makefile: KERNEL_SOURCES) */

/* A work-item is a block of PACKET_W x PACKET_H tiles (kernels/render.cl), BLOCK_ROWS pixel rows high. A band is
 * a launch of several rows of blocks: narrow ones at first when progress is reported or the render can be cancelled
 * (a cancel is seen between bands: `iacsg view` drops a frame when the view moves), otherwise wide enough that
 * launches are few (each wakes the device's threads and waits for the slowest), yet short enough that no
 * launch runs for long (GPU drivers may kill a kernel that holds the display for seconds). */
enum { BLOCK_ROWS = PACKET_H * TILE_SIZE, BAND_ROWS_PROGRESS = 2 * BLOCK_ROWS, BAND_ROWS = 64 * BLOCK_ROWS };
_Static_assert(BLOCK_ROWS == IACSG_ROW_ALIGN, "iacsg_view.row_first is aligned to whole blocks");

double render_now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static iacsg_status compile_now(iacsg_renderer *r, iacsg_error *err);

/* The packets' width: 2 pixels (8 lanes) where `narrow` (the first-root path) and the device's vectors of the
 * working precision hold 2 to 8 lanes (a CPU without AVX-512: PoCL on AVX2 says 8 floats, 4 doubles), else 4 (16
 * lanes: AVX-512, GPUs, which say 1, and the segment path). On a Zen 3 (AVX2), 16 -> 8 lanes, render medians in
 * turn: gyroid in a ball 183 -> 152 ms, multiple unions 166 -> 151, reference view 39 -> 37; the gyroid's
 * reflections 419 -> 309 (a packet waits for its slowest ray, and a 16-lane vector is two AVX2 registers, passed
 * through memory to every function not inlined). The segment path traces a packet's rays one at a time after its
 * passes in lanes, which 8 lanes make twice as many: sesc.csg 0.57 -> 0.72 s, icos.csg 1.09 -> 1.14, the BRL-CAD
 * models and Fig. 2's regions within the noise (medians of 7 in turn). IACSG_PACKET_LANES (8 or 16) sets it on
 * both paths, for A/B timings and the tests that render both ways. */
static int render_packet_w(const clrt *rt, int fp64, int narrow) {
    const char *set = getenv("IACSG_PACKET_LANES");
    if (set && (strcmp(set, "8") == 0 || strcmp(set, "16") == 0))
        return strcmp(set, "8") == 0 ? 2 : 4;
    cl_uint lanes = fp64 ? rt->double_lanes : rt->float_lanes;
    return narrow && lanes >= 2 && lanes <= 8 ? 2 : 4;
}

iacsg_status render_open(const iacsg_render_config *config, int narrow, iacsg_renderer **out, iacsg_error *err) {
    iacsg_renderer *r = calloc(1, sizeof *r);
    *out = NULL;
    if (!r)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    r->config = *config;
    iacsg_status st = clrt_open(&r->rt, config->device, err);
    if (st != IACSG_OK) {
        free(r);
        return st;
    }
    r->packet_w = render_packet_w(&r->rt, config->fp64, narrow);
    *out = r;
    return IACSG_OK;
}

iacsg_status render_build(iacsg_renderer *r, const char *const *sources, size_t count, const char *kernel,
                          iacsg_error *err) {
    char options[512];
    iacsg_status st = clrt_ia_options(&r->rt, r->config.fp64, r->config.fast, options, sizeof options - 96, err);
    if (st != IACSG_OK)
        return st;
    /* IACSG_SEGMENTS_LANES=0: the segment path's planar solids solved ray by ray, not in a packet's lanes
     * (kernels/segments_lanes.h; tests/t_brlcad_lanes.c compares the two, and A/B timings take it) */
    const char *lanes = getenv("IACSG_SEGMENTS_LANES");
    snprintf(options + strlen(options), 96, " -D IA_VW=%d -D PACKET_W=%d%s%s", render_packet_lanes(r), r->packet_w,
             r->config.stats ? " -D KERNEL_STATS" : "",
             lanes && strcmp(lanes, "0") == 0 ? " -D SEGMENTS_LANES_OFF" : "");
    double t0 = render_now_seconds();
    st = clrt_build(&r->rt, sources, count, options, &r->program, err);
    r->build_seconds += render_now_seconds() - t0;
    if (st != IACSG_OK)
        return st;
    cl_int rc = CL_SUCCESS;
    r->kernel = clCreateKernel(r->program, kernel, &rc);
    CLRT_CHECK(err, rc);
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

int render_packet_lanes(const iacsg_renderer *r) { return r->packet_w * PACKET_H; }

int render_block_w(const iacsg_renderer *r) { return r->packet_w * TILE_SIZE; }

iacsg_status render_create_first_root(const char *expr_cl, const char *kernels, const iacsg_render_config *config,
                                      iacsg_renderer **out, iacsg_error *err) {
    iacsg_renderer *r;
    iacsg_status st = render_open(config, 1, &r, err);
    if (st != IACSG_OK)
        return st;
    const char *sources[] = {iacsg_cl_ia, expr_cl, kernels};
    st = render_build(r, sources, 3, "iacsg_render", err);
    return render_finish(r, st, compile_now, out, err);
}

iacsg_status iacsg_renderer_create(const char *expr_cl, const iacsg_render_config *config, iacsg_renderer **out,
                                   iacsg_error *err) {
    return render_create_first_root(expr_cl, iacsg_cl_kernels, config, out, err);
}

iacsg_status render_finish(iacsg_renderer *r, iacsg_status st,
                           iacsg_status (*compile_now)(iacsg_renderer *, iacsg_error *), iacsg_renderer **out,
                           iacsg_error *err) {
    if (st == IACSG_OK) {
        double t0 = render_now_seconds();
        st = compile_now(r, err);
        r->build_seconds += render_now_seconds() - t0;
    }
    if (st != IACSG_OK) {
        iacsg_renderer_destroy(r);
        return st;
    }
    *out = r;
    return IACSG_OK;
}

void iacsg_renderer_destroy(iacsg_renderer *r) {
    if (!r)
        return;
    if (r->kernel)
        clReleaseKernel(r->kernel);
    if (r->effects_kernel)
        clReleaseKernel(r->effects_kernel);
    if (r->program)
        clReleaseProgram(r->program);
    render_scene_free(r->scene);
    render_effects_free(r->fx);
    if (r->tape)
        clReleaseMemObject(r->tape);
    clrt_close(&r->rt);
    free(r);
}

double iacsg_renderer_build_seconds(const iacsg_renderer *r) { return r->build_seconds; }
const char *iacsg_renderer_device_name(const iacsg_renderer *r) { return r->rt.device_name; }
const char *iacsg_renderer_program(const iacsg_renderer *r) {
    return r->program_note[0] ? r->program_note : "compiled";
}

/* [TMIN, TMAX]: a t range holding every ray's part inside the box, from the parameters as the device sees them
 * (p, already rounded to the working precision). Perspective: distances from the eye to the box (|d| = 1 up to
 * rounding); orthographic: the box corners' positions along f. Widened by 1e-5 relative to the sizes
 * involved, far more than the rounding of the rays (a few ulps). */
static void t_range(double *p, int ortho) {
    double lo = INFINITY, hi = 0, gap2 = 0;
    for (int c = 0; c < 8; c++) {
        double dist2 = 0, along = 0;
        for (int k = 0; k < 3; k++) {
            double diff = p[PARAM_BOX + k + 3 * ((c >> k) & 1)] - p[PARAM_EYE + k];
            dist2 += diff * diff;
            along += diff * p[PARAM_FORWARD + k];
        }
        lo = fmin(lo, along);
        hi = fmax(hi, ortho ? along : sqrt(dist2));
    }
    if (!ortho) { /* distance from the eye to the nearest point of the box */
        for (int k = 0; k < 3; k++) {
            double e = p[PARAM_EYE + k], below = p[PARAM_BOX + k] - e, above = e - p[PARAM_BOX + 3 + k];
            double out = fmax(fmax(below, above), 0);
            gap2 += out * out;
        }
        lo = sqrt(gap2);
    }
    /* orthographic origins lie off the eye's plane by rounding proportional to their offset s r + v u */
    double slack = 1e-5 * (fabs(lo) + fabs(hi) + 1 + fabs(p[PARAM_SCALE_S]) + fabs(p[PARAM_SCALE_V]));
    p[PARAM_TMIN] = fmax(lo - slack, 0);
    p[PARAM_TMAX] = hi + slack;
}

/* The parameter block in the working precision. The box and the time are rounded outward to float, so they
 * only grow. */
iacsg_status render_fill_params(const iacsg_view *v, int fp64, void *block, iacsg_error *err) {
    double p[PARAM_COUNT];
    iacsg_status st = iacsg_camera_params(&v->camera, v->width, v->height, p, err);
    if (st != IACSG_OK)
        return st;
    for (int k = 0; k < 6; k++)
        p[PARAM_BOX + k] = v->bounds[k];
    p[PARAM_EPS] = v->eps;
    p[PARAM_TIME_LO] = v->time[0];
    p[PARAM_TIME_HI] = v->time[1];
    for (int pass = 0; pass < 2; pass++) { /* the t range is computed from the rounded values of pass 0 */
        if (pass == 1)
            t_range(p, v->camera.ortho_height > 0);
        for (int k = 0; k < PARAM_COUNT; k++) {
            int down = (k >= PARAM_BOX && k < PARAM_BOX + 3) || k == PARAM_TMIN || k == PARAM_TIME_LO;
            int up = (k >= PARAM_BOX + 3 && k < PARAM_BOX + 6) || k == PARAM_TMAX || k == PARAM_TIME_HI;
            if (fp64) {
                ((double *)block)[k] = p[k];
                continue;
            }
            float f = (float)p[k];
            if (down && (double)f > p[k])
                f = nextafterf(f, -INFINITY);
            if (up && (double)f < p[k])
                f = nextafterf(f, INFINITY);
            ((float *)block)[k] = f;
            p[k] = f;
        }
    }
    return IACSG_OK;
}

iacsg_status render_check_view(const iacsg_view *v, iacsg_error *err) {
    if (v->width < 1 || v->height < 1 || (long long)v->width * v->height > (1LL << 28))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "image size %dx%d is out of range", v->width, v->height);
    if (v->row_first < 0 || v->row_count < 0 || v->row_first % IACSG_ROW_ALIGN != 0 ||
        v->row_first + (long long)v->row_count > v->height || (v->row_count == 0 && v->row_first != 0))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "rows %d + %d of a %d-row image: not a band of it",
                               v->row_first, v->row_count, v->height);
    if (!(v->eps > 0) || !isfinite(v->eps))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "eps must be positive (got %g)", v->eps);
    for (int k = 0; k < 3; k++)
        if (!(v->bounds[k] < v->bounds[k + 3]) || !isfinite(v->bounds[k]) || !isfinite(v->bounds[k + 3]))
            return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the bounds are empty or not finite");
    if (!(v->time[0] <= v->time[1]) || !isfinite(v->time[0]) || !isfinite(v->time[1]))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the time is not a finite interval [lo, hi]");
    return IACSG_OK;
}

/* The mean over `rays` rays counts the tiles' evaluations too, shared among the rays; the max is a ray's own.
 * packets: each packet's sum and maximum of its rays' counts (kernels/render.cl), `npackets` of them. */
static void summarize_evals(const cl_uint *packets, size_t npackets, size_t rays, const cl_uint *tile_evals,
                            size_t tiles_n, iacsg_frame *f) {
    double sum = 0;
    for (size_t k = 0; k < npackets; k++) {
        sum += packets[2 * k];
        if (packets[2 * k + 1] > f->evals_max)
            f->evals_max = packets[2 * k + 1];
    }
    for (size_t k = 0; k < tiles_n; k++)
        sum += tile_evals[k];
    f->evals_mean = rays ? sum / (double)rays : 0;
}

/* The device buffers of one frame. */
typedef struct {
    cl_mem params, rgb, depth, normal, tiles, groups, evals, tile_evals; /* the last two only with stats */
    int rgb_bytes;   /* rgb holds 3 bytes a pixel (frame.rgb8: RENDER_BYTES), else 3 floats */
} frame_buffers;

static void release_buffers(frame_buffers *b) {
    cl_mem *all[] = {&b->params, &b->rgb, &b->depth, &b->normal, &b->tiles, &b->groups, &b->evals, &b->tile_evals};
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        if (*all[k])
            clReleaseMemObject(*all[k]);
}

/* The frame's buffers must fit the device: checked up front, so that a too-large image gets a message in
 * terms of -size rather than an OpenCL error code. The largest buffer holds 3 floats a pixel; the frame's buffers
 * together `per_pixel` 4-byte values a pixel (the first-root path: 7, 8 with -stats). */
iacsg_status render_check_device_memory(const iacsg_renderer *r, const iacsg_view *view, size_t n, double per_pixel,
                                        iacsg_error *err) {
    double mib = 1024.0 * 1024.0;
    double largest = 3.0 * (double)n * sizeof(float), total = per_pixel * (double)n * sizeof(float);
    if (largest <= (double)r->rt.max_alloc_size && total <= (double)r->rt.global_mem_size)
        return IACSG_OK;
    return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0,
                           "a %dx%d image needs %.0f MiB of device memory (%.0f MiB in one buffer); '%s' has %.0f MiB "
                           "(%.0f MiB in one buffer): use a smaller -size",
                           view->width, view->height, total / mib, largest / mib, r->rt.device_name,
                           (double)r->rt.global_mem_size / mib, (double)r->rt.max_alloc_size / mib);
}

/* The images are device buffers over the frame's own host arrays (CL_MEM_USE_HOST_PTR): on a CPU device the
 * kernel writes them in place, where a copy would cost as much as a third of an empty frame. So are the counts
 * of -stats (evals, tile_evals; NULL without). */
/* The bytes of b's colour image of n pixels: 3 bytes a pixel (frame.rgb8) or 3 floats. */
static size_t rgb_image_size(const frame_buffers *b, size_t n) { return 3 * n * (b->rgb_bytes ? 1 : sizeof(float)); }

static iacsg_status create_buffers(iacsg_renderer *r, const void *params, size_t n, size_t tiles_n,
                                   size_t packets_n, iacsg_frame *f, cl_uint *evals, cl_uint *tile_evals,
                                   frame_buffers *b, iacsg_error *err) {
    cl_context ctx = r->rt.context;
    size_t real_size = r->config.fp64 ? sizeof(double) : sizeof(float);
    cl_int rc = CL_SUCCESS;
    b->params = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, PARAM_COUNT * real_size,
                               (void *)params, &rc);
    CLRT_CHECK(err, rc);
    cl_mem_flags image = CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR;
    b->rgb_bytes = f->rgb8 != NULL;
    b->rgb = clCreateBuffer(ctx, image, rgb_image_size(b, n), b->rgb_bytes ? (void *)f->rgb8 : (void *)f->rgb, &rc);
    CLRT_CHECK(err, rc);
    if (f->depth) {
        b->depth = clCreateBuffer(ctx, image, n * sizeof(float), f->depth, &rc);
        CLRT_CHECK(err, rc);
    }
    if (f->normal) {
        b->normal = clCreateBuffer(ctx, image, 3 * n * sizeof(float), f->normal, &rc);
        CLRT_CHECK(err, rc);
    }
    b->tiles = clCreateBuffer(ctx, CL_MEM_READ_WRITE, 2 * tiles_n * real_size, NULL, &rc);
    CLRT_CHECK(err, rc);
    _Static_assert(SEGMENTS <= TAPE_MAX_SEGMENTS, "a tape evaluation merges the lists of up to SEGMENTS segments");
    size_t tile_words = SEGMENTS * (r->tape ? 1 + TAPE_TILE_WORDS : 1); /* kernels/render.cl: TILE_GROUPS_WORDS */
    b->groups = clCreateBuffer(ctx, CL_MEM_READ_WRITE, tiles_n * tile_words * sizeof(cl_ulong), NULL, &rc);
    CLRT_CHECK(err, rc);
    if (evals) { /* in place too: a read-back copied them into pages faulted in for it */
        b->evals = clCreateBuffer(ctx, image, 2 * packets_n * sizeof(cl_uint), evals, &rc);
        CLRT_CHECK(err, rc);
        b->tile_evals = clCreateBuffer(ctx, image, tiles_n * sizeof(cl_uint), tile_evals, &rc);
        CLRT_CHECK(err, rc);
    }
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* The arguments of kernel k (iacsg_render, or with fx iacsg_render_effects and the effects it applies) but the
 * band's first row (index 4): the kernels of both paths start with params, flags, width, height. */
static iacsg_status set_args(iacsg_renderer *r, cl_kernel k, const iacsg_view *view, frame_buffers *b,
                             const render_fx_camera *fx, iacsg_error *err) {
    cl_int flags = (view->camera.ortho_height > 0 ? RENDER_ORTHO : 0) | (b->rgb_bytes ? RENDER_BYTES : 0);
    cl_int width = view->width, height = view->height; /* argument 4, the band's first block row, is set per launch */
    CLRT_CHECK(err, clSetKernelArg(k, 0, sizeof(cl_mem), &b->params));
    CLRT_CHECK(err, clSetKernelArg(k, 1, sizeof(cl_int), &flags));
    CLRT_CHECK(err, clSetKernelArg(k, 2, sizeof(cl_int), &width));
    CLRT_CHECK(err, clSetKernelArg(k, 3, sizeof(cl_int), &height));
    CLRT_CHECK(err, clSetKernelArg(k, 5, sizeof(cl_mem), &b->tiles));
    CLRT_CHECK(err, clSetKernelArg(k, 6, sizeof(cl_mem), &b->rgb));
    CLRT_CHECK(err, clSetKernelArg(k, 7, sizeof(cl_mem), b->depth ? &b->depth : NULL));
    CLRT_CHECK(err, clSetKernelArg(k, 8, sizeof(cl_mem), b->normal ? &b->normal : NULL));
    CLRT_CHECK(err, clSetKernelArg(k, 9, sizeof(cl_mem), b->evals ? &b->evals : NULL));
    CLRT_CHECK(err, clSetKernelArg(k, 10, sizeof(cl_mem), b->tile_evals ? &b->tile_evals : NULL));
    CLRT_CHECK(err, clSetKernelArg(k, 11, sizeof(cl_mem), &b->groups));
    CLRT_CHECK(err, clSetKernelArg(k, 12, sizeof(cl_mem), r->tape ? &r->tape : NULL));
    if (!fx)
        return IACSG_OK;
    CLRT_CHECK(err, clSetKernelArg(k, 13, sizeof(cl_mem), &fx->block));
    CLRT_CHECK(err, clSetKernelArg(k, 14, sizeof(cl_mem), &fx->all_groups));
    double footprint = fx->footprint;
    float footprint_f = (float)footprint;
    CLRT_CHECK(err, r->config.fp64 ? clSetKernelArg(k, 15, sizeof footprint, &footprint)
                                   : clSetKernelArg(k, 15, sizeof footprint_f, &footprint_f));
    CLRT_CHECK(err, clSetKernelArg(k, 16, sizeof(cl_mem), &fx->counts));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* PoCL compiles a kernel's code for the CPU at its first launch, not in clBuildProgram: for a large expression
 * most of the build. One launch over an empty image (every work-item returns at once, before touching a buffer,
 * all of which are NULL) makes that happen here, where it counts as build time, and not inside the first frame's
 * render time. The launch has the local size of the real ones (launch_bands), which is what PoCL compiles for. */
static iacsg_status compile_kernel_now(iacsg_renderer *r, cl_kernel k, int effects, iacsg_error *err) {
    iacsg_view empty = {0};
    frame_buffers none = {0};
    render_fx_camera no_effects = {0};
    cl_int first_row = 0;
    iacsg_status st = set_args(r, k, &empty, &none, effects ? &no_effects : NULL, err);
    if (st != IACSG_OK)
        return st;
    size_t one[2] = {1, 1};
    CLRT_CHECK(err, clSetKernelArg(k, 4, sizeof(cl_int), &first_row));
    CLRT_CHECK(err, clEnqueueNDRangeKernel(r->rt.queue, k, 2, NULL, one, one, 0, NULL, NULL));
    CLRT_CHECK(err, clFinish(r->rt.queue));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

static iacsg_status compile_now(iacsg_renderer *r, iacsg_error *err) {
    return compile_kernel_now(r, r->kernel, 0, err);
}

/* The camera kernel with the effects (kernels/effects.cl: iacsg_render_effects), made and compiled at its first
 * use (counted as build time). */
static iacsg_status effects_kernel(iacsg_renderer *r, cl_kernel *out, iacsg_error *err) {
    if (!r->effects_kernel) {
        double t0 = render_now_seconds();
        cl_int rc = CL_SUCCESS;
        r->effects_kernel = clCreateKernel(r->program, "iacsg_render_effects", &rc);
        CLRT_CHECK(err, rc);
        iacsg_status st = compile_kernel_now(r, r->effects_kernel, 1, err);
        r->build_seconds += render_now_seconds() - t0;
        if (st != IACSG_OK)
            return st;
    }
    *out = r->effects_kernel;
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* A waited band (progress or cancel) that took less than half this grows towards it. */
#define BAND_SECONDS 0.04

/* The view's rows, [row_first, row_first + row_count) or all of them, in bands of `max_units` units of `unit_rows`
 * rows, one launch each over `groups_x` x (the band's units) work-items, kernel argument 4 the band's first unit.
 * With a progress or cancel callback, waits for each band, the first `waited_units` long, and a band that took
 * under BAND_SECONDS / 2 makes the next one longer (up to 16 times, and up to `max_units`), so that a frame stops
 * soon after a cancel but does not
 * pay a launch and its wait per narrow band: on PoCL here each cost ~2 ms, and a 1024x1024 reference view in 16
 * bands of 64 rows (the command's own, when stderr is a terminal) took 29-44 ms against 24-30 in one. Both paths:
 * units of blocks (here and in render_scene.c), each a divisor of IACSG_ROW_ALIGN so that a band starts on a whole
 * unit. */
iacsg_status render_launch_bands(iacsg_renderer *r, cl_kernel k, const iacsg_view *view, size_t groups_x,
                                 int unit_rows, int waited_units, int max_units, iacsg_error *err) {
    cl_command_queue q = r->rt.queue;
    int first = view->row_first, end = view->row_count ? first + view->row_count : view->height;
    int waited = view->progress || view->cancel;
    int band = (waited && waited_units < max_units ? waited_units : max_units) * unit_rows;
    for (int row0 = first, rows = 0; row0 < end; row0 += rows) {
        rows = end - row0 < band ? end - row0 : band;
        double started = render_now_seconds();
        cl_int unit0 = row0 / unit_rows;
        size_t global[2] = {groups_x, (size_t)(rows + unit_rows - 1) / unit_rows};
        CLRT_CHECK(err, clSetKernelArg(k, 4, sizeof(cl_int), &unit0));
        size_t local[2] = {1, 1}; /* work-items are independent: let the device spread them over all its cores */
        CLRT_CHECK(err, clEnqueueNDRangeKernel(q, k, 2, NULL, global, local, 0, NULL, NULL));
        if (!waited)
            continue;
        CLRT_CHECK(err, clFinish(q));
        if (view->progress)
            view->progress((double)(row0 + rows - first) / (end - first), view->progress_ctx);
        if (view->cancel && view->cancel(view->cancel_ctx))
            return iacsg_error_set(err, IACSG_ERR_CANCELLED, 0, 0, "render cancelled");
        double took = render_now_seconds() - started, grow = took > 0 ? fmin(16, BAND_SECONDS / took) : 16;
        if (took < BAND_SECONDS / 2 && band < max_units * unit_rows)
            band = (int)fmin((double)max_units, fmax(1, floor(band / unit_rows * grow))) * unit_rows;
    }
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* Each band of rows, one launch (each block's tiles, then its pixels). */
static iacsg_status launch_bands(iacsg_renderer *r, cl_kernel k, const iacsg_view *view, iacsg_error *err) {
    size_t block_w = (size_t)render_block_w(r);
    return render_launch_bands(r, k, view, ((size_t)view->width + block_w - 1) / block_w, BLOCK_ROWS,
                               BAND_ROWS_PROGRESS / BLOCK_ROWS, BAND_ROWS / BLOCK_ROWS, err);
}

/* Brings the images (and the counts, with stats) to the host and waits for them. */
static iacsg_status read_back(iacsg_renderer *r, const frame_buffers *b, const render_fx_camera *fx, size_t n,
                              size_t tiles_n, size_t packets_n, iacsg_error *err) {
    cl_command_queue q = r->rt.queue;
    /* Mapping a USE_HOST_PTR buffer makes its host array current (a no-op on a CPU device). */
    cl_mem images[6] = {b->rgb, b->depth, b->normal, b->evals, b->tile_evals, fx->counts};
    size_t sizes[6] = {rgb_image_size(b, n), n * sizeof(float), 3 * n * sizeof(float),
                       2 * packets_n * sizeof(cl_uint), tiles_n * sizeof(cl_uint), 2 * packets_n * sizeof(cl_uint)};
    for (int k = 0; k < 6; k++) {
        if (!images[k])
            continue;
        cl_int rc = CL_SUCCESS;
        void *p = clEnqueueMapBuffer(q, images[k], CL_FALSE, CL_MAP_READ, 0, sizes[k], 0, NULL, NULL, &rc);
        CLRT_CHECK(err, rc);
        CLRT_CHECK(err, clEnqueueUnmapMemObject(q, images[k], p, 0, NULL, NULL));
    }
    CLRT_CHECK(err, clFinish(q));
    return IACSG_OK;
fail:
    return IACSG_ERR_OPENCL;
}

/* A host array of `bytes` that a device uses in place, page-aligned as devices prefer them. An image is written
 * once into fresh pages: from 2 MB on it is aligned to and asks for huge pages (where transparent huge pages
 * are on or on request, as Debian's default), one fault per 2 MB instead of 512, and is a whole number of them
 * (a 1024x1024 frame's 3 MB of bytes had its last 1 MB in 256 small pages: those faults and the misses of the
 * kernel's first stores were 3 of an empty frame's 5 ms). */
void *render_in_place_alloc(size_t bytes) {
    enum { HUGE_PAGE = 2 << 20 };
    void *p = NULL;
    if (bytes >= HUGE_PAGE && bytes <= SIZE_MAX - HUGE_PAGE)
        bytes = (bytes + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
    if (posix_memalign(&p, bytes >= HUGE_PAGE ? HUGE_PAGE : 4096, bytes) != 0)
        return NULL;
#ifdef MADV_HUGEPAGE
    if (bytes >= HUGE_PAGE)
        madvise(p, bytes, MADV_HUGEPAGE); /* advice only: where it fails, small pages as before */
#endif
    return p;
}

/* A frame's image of `count` floats (render_in_place_alloc). */
float *render_image_alloc(size_t count) { return render_in_place_alloc(count * sizeof(float)); }

/* An expression's ids from its depth: 0 where the ray hits, -1 where it misses. */
static void ids_from_depth(const float *depth, size_t n, float *ids) {
    for (size_t k = 0; k < n; k++)
        ids[k] = isinf(depth[k]) ? -1.0f : 0.0f;
}

iacsg_status iacsg_render(iacsg_renderer *r, const iacsg_view *view, iacsg_frame *frame, iacsg_error *err) {
    if (r->scene)
        return render_scene_frame(r, view, frame, err);
    memset(frame, 0, sizeof *frame);
    double params[PARAM_COUNT]; /* room for either precision */
    iacsg_status st = render_check_view(view, err);
    if (st == IACSG_OK && r->tape && render_effects_need_aovs(r, view)) /* effects.cl is compiled code's */
        st = iacsg_error_set(err, IACSG_ERR_ARG, 0, 0,
                             "the ray-tracing effects need a compiled expression (-tape off; "
                             "render config tape = IACSG_TAPE_NEVER)");
    if (st == IACSG_OK)
        st = render_fill_params(view, r->config.fp64, params, err);
    if (st != IACSG_OK)
        return st;
    size_t n = (size_t)view->width * (size_t)view->height;
    size_t tiles_n = (((size_t)view->width + TILE_SIZE - 1) / TILE_SIZE) *
                     (((size_t)view->height + TILE_SIZE - 1) / TILE_SIZE);
    size_t packets_x = ((size_t)view->width + (size_t)r->packet_w - 1) / (size_t)r->packet_w;
    size_t packets_n = packets_x * (((size_t)view->height + PACKET_H - 1) / PACKET_H);
    frame_buffers buffers = {0};
    cl_uint *evals = NULL, *tile_evals = NULL;
    frame->width = view->width;
    frame->height = view->height;
    if (view->rgb_bytes && render_effects_camera_final(r, view))
        frame->rgb8 = render_in_place_alloc(3 * n);
    else
        frame->rgb = render_image_alloc(3 * n);
    int in_camera = render_effects_in_camera(r, view), fx_depth, fx_normal;
    render_effects_aovs(r, view, &fx_depth, &fx_normal);
    render_fx_camera fx_camera = {0};
    cl_kernel kernel = r->kernel;
    if (st == IACSG_OK && in_camera)
        st = render_effects_camera_open(r, view, packets_n, &fx_camera, err);
    if (st == IACSG_OK && in_camera)
        st = effects_kernel(r, &kernel, err);
    int need_depth = !view->no_depth || !view->no_ids || fx_depth; /* the ids come from the depth */
    frame->depth = need_depth ? render_image_alloc(n) : NULL;
    frame->normal = view->no_normals && !fx_normal ? NULL : render_image_alloc(3 * n);
    frame->ids = view->no_ids ? NULL : render_image_alloc(n);
    if (r->config.stats) {
        evals = render_in_place_alloc(2 * packets_n * sizeof(cl_uint));
        tile_evals = render_in_place_alloc(tiles_n * sizeof(cl_uint));
    }
    if ((!frame->rgb && !frame->rgb8) || (!frame->depth && need_depth) ||
        (!frame->normal && (!view->no_normals || fx_normal)) || (!frame->ids && !view->no_ids) ||
        (r->config.stats && (!evals || !tile_evals)))
        st = st != IACSG_OK ? st
                            : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for a %dx%d image",
                                              view->width, view->height);
    if (st == IACSG_OK)
        st = render_check_device_memory(r, view, n, r->config.stats ? 8 : 7, err);
    if (st == IACSG_OK)
        st = create_buffers(r, params, n, tiles_n, packets_n, frame, evals, tile_evals, &buffers, err);
    if (st == IACSG_OK)
        st = set_args(r, kernel, view, &buffers, in_camera ? &fx_camera : NULL, err);
    double t0 = render_now_seconds();
    if (st == IACSG_OK)
        st = launch_bands(r, kernel, view, err);
    if (st == IACSG_OK)
        st = read_back(r, &buffers, &fx_camera, n, tiles_n, packets_n, err);
    if (st == IACSG_OK) {
        frame->render_seconds = render_now_seconds() - t0;
        /* the rays of the rows traced, and their tiles' counts (a band's rows start on whole tiles) */
        size_t first = (size_t)view->row_first, rows = view->row_count ? (size_t)view->row_count : (size_t)view->height;
        size_t tiles_x = ((size_t)view->width + TILE_SIZE - 1) / TILE_SIZE;
        frame->rays = (long long)(rows * (size_t)view->width);
        if (evals)
            summarize_evals(evals + 2 * (first / PACKET_H * packets_x), (rows + PACKET_H - 1) / PACKET_H * packets_x,
                            rows * (size_t)view->width, tile_evals + first / TILE_SIZE * tiles_x,
                            (rows + TILE_SIZE - 1) / TILE_SIZE * tiles_x,
                            frame);
        if (frame->ids)
            ids_from_depth(frame->depth, n, frame->ids);
        render_frame_tiles tiles = {buffers.tiles, buffers.groups};
        st = render_effects_apply(r, view, frame, in_camera ? &fx_camera : NULL, &tiles, err);
        if (view->no_normals && frame->normal) {
            free(frame->normal);
            frame->normal = NULL;
        }
        if (view->no_depth) {
            free(frame->depth);
            frame->depth = NULL;
        }
    }
    release_buffers(&buffers);
    render_effects_camera_close(&fx_camera);
    free(evals);
    free(tile_evals);
    if (st != IACSG_OK)
        iacsg_frame_free(frame);
    return st;
}

void iacsg_frame_free(iacsg_frame *frame) {
    free(frame->rgb);
    free(frame->rgb8);
    frame->rgb8 = NULL;
    free(frame->depth);
    free(frame->normal);
    free(frame->ids);
    frame->rgb = frame->depth = frame->normal = frame->ids = NULL;
}

void iacsg_frame_time(int k, int n, double time[2]) {
    double q = (double)k / n, r = fma(q, n, -(double)k); /* q n - k, rounded once: its sign is exact */
    time[0] = r > 0 ? nextafter(q, -INFINITY) : q;
    time[1] = r < 0 ? nextafter(q, INFINITY) : q;
}
