/* src/render_internal.h -- what the two render paths share inside the library: the renderer, its program build
 * (src/render.c) and the frame's parameter block, images and checks. src/render_scene.c is the segment path. */
#ifndef IACSG_RENDER_INTERNAL_H
#define IACSG_RENDER_INTERNAL_H
#include "clrt.h"
#include "render.h"

extern const char iacsg_cl_ia[]; /* the flattened ia/ headers (Makefile: IA_CL_HEADERS) */

typedef struct render_scene render_scene; /* the segment path's tables and buffers (render_scene.c) */
typedef struct render_fx render_fx;       /* the ray-tracing effects (render_effects.c) */

struct iacsg_renderer {
    clrt rt;
    cl_program program;
    cl_kernel kernel;
    cl_kernel effects_kernel; /* the first-root path's camera kernel with the effects, made at its first use */
    iacsg_render_config config;
    double build_seconds;
    render_scene *scene; /* NULL on the first-root path */
    render_fx *fx;       /* the effects' kernel and materials (src/render_effects.c), made at the first use */
    cl_mem tape;         /* an interpreted expression's tape (src/render_expr.c), else NULL */
    int packet_w;        /* the program's packets are packet_w x PACKET_H pixels (kernels/params.h) */
    char program_note[160]; /* iacsg_renderer_program */
};

double render_now_seconds(void);

/* The lanes of the renderer's packets: r->packet_w x PACKET_H. */
int render_packet_lanes(const iacsg_renderer *r);

/* The width in pixels of a work-item's block of r->packet_w x PACKET_H tiles, on both paths (render.c's BLOCK_ROWS
 * and kernels/scene_data.h's SCENE_BLOCK_H high). */
int render_block_w(const iacsg_renderer *r);

/* A renderer on config's device, without a program yet (destroy with iacsg_renderer_destroy); its packets 8 lanes
 * wide where `narrow` and the device's vectors are (src/render.c: render_packet_w), else 16. */
iacsg_status render_open(const iacsg_render_config *config, int narrow, iacsg_renderer **out, iacsg_error *err);

/* Builds the program from the sources with the ia/ options of the config and its packets' width, r->packet_w,
 * and creates its kernel. */
iacsg_status render_build(iacsg_renderer *r, const char *const *sources, size_t count, const char *kernel,
                          iacsg_error *err);

/* A first-root renderer: the program of the ia/ headers, expr_cl (an expression's code, or the tape
 * interpreter's) and the kernels (iacsg_cl_kernels, or for a tape iacsg_cl_tape_kernels). */
iacsg_status render_create_first_root(const char *expr_cl, const char *kernels, const iacsg_render_config *config,
                                      iacsg_renderer **out, iacsg_error *err);

/* The end of a renderer's creation: when st is IACSG_OK, compile_now (one empty launch, so that the device compiles
 * the kernel now and the time counts as build time); then *out = r, or r destroyed and the failure returned. */
iacsg_status render_finish(iacsg_renderer *r, iacsg_status st,
                           iacsg_status (*compile_now)(iacsg_renderer *, iacsg_error *), iacsg_renderer **out,
                           iacsg_error *err);

iacsg_status render_check_view(const iacsg_view *v, iacsg_error *err);
/* The parameter block (kernels/params.h) in the working precision. */
iacsg_status render_fill_params(const iacsg_view *v, int fp64, void *block, iacsg_error *err);
/* An error naming -size when a frame's buffers, `per_pixel` 4-byte values a pixel, cannot fit the device. */
iacsg_status render_check_device_memory(const iacsg_renderer *r, const iacsg_view *view, size_t n, double per_pixel,
                                        iacsg_error *err);
/* Launches kernel k (r->kernel, or the effects' camera kernel) over the view's rows in bands (render.c): of
 * max_units units, or from waited_units on where a progress or cancel callback waits for each. */
iacsg_status render_launch_bands(iacsg_renderer *r, cl_kernel k, const iacsg_view *view, size_t groups_x,
                                 int unit_rows, int waited_units, int max_units, iacsg_error *err);
/* A host array of `bytes` that a device uses in place (CL_MEM_USE_HOST_PTR), page-aligned, in huge pages from
 * 2 MB on; and a frame's image of `count` floats in one. Both are freed with free(). */
void *render_in_place_alloc(size_t bytes);
float *render_image_alloc(size_t count);

void render_scene_free(render_scene *s);
iacsg_status render_scene_frame(iacsg_renderer *r, const iacsg_view *view, iacsg_frame *frame, iacsg_error *err);

/* The segment path's side of the effects (render_scene.c; see there). */
iacsg_status render_scene_trace_args(iacsg_renderer *r, const iacsg_view *view, cl_kernel k, cl_uint first,
                                     size_t *slots, void **held, iacsg_error *err);
void render_scene_trace_release(void *held);
const float *render_scene_materials(const iacsg_renderer *r); /* SCENE_MATERIAL_FLOATS per item */

/* The effects that the camera kernel applies itself (kernels/render.cl: render_effects; kernels/render_scene.cl:
 * scene_packet_lit), where render_effects_in_camera says it can: the effects' block, a union's groups all on, the
 * secondary rays' Newton window, and with stats the secondary rays and their evaluations (counts, over counts_host;
 * 2 per `packets`: the first-root path's packets, the segment path's pixels). */
typedef struct {
    cl_mem block, all_groups, counts;
    double footprint;
    cl_uint *counts_host;
    size_t packets;
} render_fx_camera;

/* Whether the camera kernel can shade the frame's pixels with its effects, where there are hits to shade again
 * (not only -aa or -background, where the kernel's colours stand: the pass after the frame colours the misses
 * only, and each hit keeps the plain render's colour exactly). The first-root path's compiled code: no path that
 * lists a reflected ray (reflections off a transparent surface), no -shade depth (its range needs every hit
 * first). The segment path: every item opaque, at most one bounce (a reflected ray's hit has no child), lit or
 * -shade gradient or normals (-shade ids' palette and depth's range are the pass after's). */
int render_effects_in_camera(const iacsg_renderer *r, const iacsg_view *view);
/* Whether the first-root path's camera kernel's colours are the frame's: no effect, or the effects it applies
 * itself without -aa (no pass after it writes a colour). */
int render_effects_camera_final(const iacsg_renderer *r, const iacsg_view *view);
iacsg_status render_effects_camera_open(iacsg_renderer *r, const iacsg_view *view, size_t packets,
                                        render_fx_camera *c, iacsg_error *err);
void render_effects_camera_close(render_fx_camera *c);
/* The first-root path's tile pass of a frame (kernels/render.cl: tiles, tile_groups_of): per tile its first coarse
 * leaf and a union's groups, where -aa's samples inside the box of its pixels' centre rays start. */
typedef struct {
    cl_mem leaves, groups;
} render_frame_tiles;
/* The effects of a frame, after its camera rays (render_effects.c): a no-op without view->effects. in_camera:
 * the camera kernel's (then only -aa's edges are left), or NULL; tiles: the first-root path's tile pass, or NULL. */
iacsg_status render_effects_apply(iacsg_renderer *r, const iacsg_view *view, iacsg_frame *frame,
                                  const render_fx_camera *in_camera, const render_frame_tiles *tiles,
                                  iacsg_error *err);
/* Whether the effects need the frame's depth and normals (which the frame then computes, and drops after). */
int render_effects_need_aovs(const iacsg_renderer *r, const iacsg_view *view);
/* Of those, what the effects need after the camera kernel: the depths for the pass over the centre hits or for
 * -aa's edges, the normals for that pass. */
void render_effects_aovs(const iacsg_renderer *r, const iacsg_view *view, int *depth, int *normals);
/* Keeps what the effects need of a scene's materials (its items' reflect). */
iacsg_status render_effects_keep_scene(iacsg_renderer *r, const struct iacsg_scene *s, iacsg_error *err);
void render_effects_free(render_fx *fx);

#endif
