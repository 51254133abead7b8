/* src/render_effects_trace.h -- the effects' secondary rays on the device: a list of rays in, each one's first
 * hit out, traced by the render path's own bisection (kernels/effects.cl for an expression, kernels/scene_effects.cl
 * for a scene's regions and surfaces). src/render_effects.c decides which rays; this file only traces them. */
#ifndef IACSG_RENDER_EFFECTS_TRACE_H
#define IACSG_RENDER_EFFECTS_TRACE_H
#include "render_internal.h"

typedef struct {
    double o[3], d[3]; /* origin, direction (unit) */
    double tn, tf;     /* the part searched, then clipped to the bounds */
    int passing;       /* the segment path: 1 + a region the ray starts in and passes through (weave.h), or 0 */
} fx_ray;

typedef struct {
    double t;   /* the hit leaf's start (never after the first root in [tn, tf]), +inf on a miss */
    float n[3]; /* the unit normal there, facing the ray */
    int item;   /* the region or surface hit (an expression: 0), -1 on a miss, or EFFECTS_HIT_BLOCKED (fx_trace) */
} fx_hit;

typedef struct {
    float reflect, opacity;
    int region; /* a region (a volume: a ray passes through it) rather than a surface */
} fx_item;

/* A path of the segment path's effects: a ray of a pixel, the weight of its colour in the pixel's, the
 * reflections and transparent layers it has taken, and its hit once traced. */
typedef struct {
    int pixel;
    double w; /* the weight of its colour in the pixel's */
    int bounces, layers;
    fx_ray ray;
    fx_hit hit;
} fx_path;

/* What a lit hit on material m gives a path of weight w that has taken `bounces` reflections (of at most
 * max_bounces) and `layers` transparent layers: the weight of the hit's own colour; of its row's background where
 * the path ends in a transparent hit (EFFECTS_MAX_LAYERS, EFFECTS_MIN_WEIGHT), else 0; and of its reflected and
 * transmitted children (0: none). */
typedef struct {
    double shown, left, mirror, through;
} fx_weights;
fx_weights fx_path_weights(const fx_item *m, double w, int bounces, int layers, int max_bounces);

/* What a renderer keeps for its effects (render_internal.h: r->fx), made at the first use. */
struct render_fx {
    cl_kernel trace; /* iacsg_effects (kernels/effects.cl) or iacsg_scene_trace_rays */
    cl_kernel shade; /* a scene's: iacsg_scene_shade */
    cl_kernel samples; /* a scene's -aa samples: iacsg_render_scene_samples (kernels/render_scene.cl) */
    cl_kernel centre;  /* a scene's centre paths on the device: iacsg_scene_centre (kernels/scene_centre.cl) */
    cl_kernel compact; /* and their shadow rays' compaction: iacsg_scene_centre_compact */
    fx_item *items;  /* a scene's items' materials, as the effects need them */
    int nitems;
};

/* -aa: two display colours differ (an edge pixel's neighbour's, the corners of the first-root path's rays in a
 * pixel) where a channel differs by more than this. */
#define FX_AA_CONTRAST (1.0 / 16)

/* The working precision's bytes per real; v stored as such a real at index k of `block`. */
size_t fx_real_bytes(const iacsg_renderer *r);
void fx_put_real(const iacsg_renderer *r, void *block, size_t k, double v);
/* Makes the host array of a CL_MEM_USE_HOST_PTR buffer current after the kernels wrote it (a no-op on a CPU
 * device). */
iacsg_status fx_sync_to_host(cl_command_queue q, cl_mem m, size_t bytes, iacsg_error *err);
/* A channel's linear light to its display value (kernels/light.h: gamma 2, clamped to [0, 1], NaN to 0); fx_encode:
 * a pixel's summed linear light (3 floats of rgb) to its display colour, in place. */
float fx_display(float light);
void fx_encode(float *rgb, int pixel);

/* Whether a frame's paths trace secondary rays: shadow rays, reflected rays or rays through transparent hits. */
int fx_traces_secondary(const iacsg_renderer *r, const iacsg_effects *e);

/* Makes r->fx (without its kernel) when it is not there yet. */
iacsg_status fx_of(iacsg_renderer *r, render_fx **out, iacsg_error *err);

/* The device side of one frame's effects: its parameter block and, made at the renderer's first use, the trace
 * kernel. */
typedef struct {
    iacsg_renderer *r;
    const iacsg_view *view;
    cl_mem params, all_groups;
    render_frame_tiles tiles; /* the frame's tile pass, where -aa's samples start (first-root path), or none */
    double footprint; /* a pixel's footprint at the bounds' farthest corner */
    void *host;       /* the rays and hits of a call, in the working precision; grows, reused by each call */
    long long rays;   /* secondary rays traced, and their interval evaluations (with config.stats) */
    double evals;
    size_t host_bytes;
    void *shade_host; /* fx_shade_in's arrays, the same way */
    size_t shade_bytes;
} fx_tracer;

iacsg_status fx_tracer_open(fx_tracer *t, iacsg_renderer *r, const iacsg_view *view, iacsg_error *err);
/* A buffer of SEGMENTS masks all on: the secondary rays search every group of a union. */
iacsg_status fx_all_groups(iacsg_renderer *r, cl_mem *out, iacsg_error *err);
/* A pixel's footprint at the bounds' farthest corner: the secondary rays' Newton window. */
iacsg_status fx_footprint(const iacsg_view *view, double *footprint, iacsg_error *err);
/* The effects' block (EFFECTS_COUNT, kernels/effects.h) in a device buffer, in the working precision. */
iacsg_status fx_block_buffer(iacsg_renderer *r, const double *block, cl_mem *out, iacsg_error *err);
void fx_tracer_close(fx_tracer *t);

/* The first-root path's effects on the device (src/render_effects_device.c, kernels/effects.cl): the paths of
 * `mode` (kernels/effects.h: the centre rays of pixels[0 .. npixels), or -aa's aa x aa rays in each of them, with
 * leaves aa_eps_footprint[0] wide and Newton's window aa_eps_footprint[1]) and the reflected rays they lead to,
 * bounce after bounce, each path listing at most kid_slots of them; the pixels' colours in the frame (its depth
 * and normals the centre rays' hits) are replaced by theirs, display-encoded. `block`: the effects' parameters
 * (EFFECTS_COUNT, kernels/effects.h). */
iacsg_status fx_device_run(fx_tracer *t, const double *block, int kid_slots, int mode, const int *pixels,
                           size_t npixels, int aa, const double aa_eps_footprint[2], iacsg_frame *frame,
                           iacsg_error *err);
/* One launch over no paths: PoCL compiles the kernel then (render_effects_trace.c: compile_trace_now). */
iacsg_status fx_device_compile(fx_tracer *t, iacsg_error *err);

/* Launches kernel k over `count` work-items, at most `slots` a launch (count 0: one launch of `slots` that does
 * nothing, so that PoCL compiles the kernel), one after the other on the in-order queue q; argument `first_arg`
 * (a cl_int) is each launch's first work-item times `scale`. `what` names the call in an error. */
iacsg_status fx_launch_slices(cl_command_queue q, cl_kernel k, cl_uint first_arg, cl_int count, size_t slots,
                              cl_int scale, const char *what, iacsg_error *err);

/* The segment path's secondary rays: traces rays[0 .. n) with leaves of width eps into hits[0 .. n). With
 * `whether` (only when every item is opaque), a ray may end on a proven crossing, item EFFECTS_HIT_BLOCKED. */
iacsg_status fx_trace(fx_tracer *t, const fx_ray *rays, size_t n, double eps, int whether, fx_hit *hits,
                      iacsg_error *err);

/* The segment path's -aa samples (src/render_effects_samples.c): the aa x aa sample rays of each of
 * pixels[0 .. npixels), sample (a, b) of pixel q through (i + (a + 1/2) / aa, j + (b + 1/2) / aa) into
 * hits[aa^2 q + aa b + a], traced by the camera kernel's packets with leaves of width eps. With the effects' block
 * `block` (where the camera kernel can light them: render_effects.c), each sample's colour lit by it, in linear
 * light, into rgb (3 floats a sample; hits then only counted). */
iacsg_status fx_scene_samples(fx_tracer *t, int aa, double eps, const int *pixels, size_t npixels, fx_hit *hits,
                              const double *block, float *rgb, iacsg_error *err);

/* Ray y as reals i of `reals` (EFFECTS_RAY_REALS each, kernels/effects.h), in the working precision. */
void fx_put_ray(const iacsg_renderer *r, void *reals, size_t i, const fx_ray *y);

/* The inputs of iacsg_scene_shade (kernels/scene_effects.cl) for n hits, in its layout and the working precision,
 * written by the caller where the device reads them (no copy): hit i's ray (fx_put_ray), its t (0 on a miss),
 * unit normal facing the ray, item (-1: a miss), the fractions vis[EFFECTS_MAX_LIGHTS i + l] of each light l that
 * reach it, and its pixel's row. */
typedef struct {
    void *rays, *depth;
    float *normal, *vis;
    cl_int *item, *row;
    size_t n;
} fx_shade_in;

/* Room for the inputs of n hits, in t's scratch (reused by the next call). */
iacsg_status fx_shade_inputs(fx_tracer *t, size_t n, fx_shade_in *in, iacsg_error *err);

/* The segment path's colours (kernels/scene_effects.cl: iacsg_scene_shade) of the hits of `in`, each lit by the
 * lights of the effects' block (EFFECTS_COUNT, kernels/effects.h); palette: 3 linear floats per item (-shade ids).
 * Out: 6 floats per hit, its colour (a miss: the background) and its row's background, linear. in NULL: only
 * compiles the kernel. */
iacsg_status fx_scene_shade(fx_tracer *t, const double *block, const fx_shade_in *in, const float *palette,
                            float *out, iacsg_error *err);

/* Shared with render_effects_centre.c. The device buffers of one trace call; the scene's trace kernel k over n rays
 * (render_effects_trace.c: its launches); the bytes of fx_shade_in's arrays for n hits; iacsg_scene_shade over n
 * hits in device buffers (shadow_item and shadow_slot: the centre paths' shadow rays, or NULL), into out or, out
 * NULL, display-encoded into their pixels of the frame rgb; buffers released. */
typedef struct fx_trace_buffers {
    cl_mem rays, t, normal, item, evals, passing;
} fx_trace_buffers;
iacsg_status fx_launch_scene(fx_tracer *t, cl_kernel k, const fx_trace_buffers *b, cl_int n, void *eps_real,
                             cl_int whether, iacsg_error *err);
void fx_shade_parts(const iacsg_renderer *r, size_t n, size_t bytes[6]);
iacsg_status fx_shade_launch(fx_tracer *t, const double *block, const cl_mem hits[6], cl_mem shadow_item,
                             cl_mem shadow_slot, size_t n, const float *palette, float *out, cl_mem pixels, cl_mem rgb,
                             iacsg_error *err);
void fx_release_all(cl_mem *mem, int count);

#endif
