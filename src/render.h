/* src/render.h -- rendering an expression or a scene: a renderer holds an OpenCL device and the program built
 * for one expression (the first-root path) or for one scene's solids, regions and surfaces (the segment path,
 * src/render_scene.c); each call of iacsg_render traces one frame of it (a view, a time) into host images.
 *
 * Guarantees of a frame (README; tests/t_render*.c check them): a surface that the pixel's float ray crosses
 * inside the bounds is never missed; the depth is never after the ray's first root in the bounds; the leaves of
 * the bisection share their end points bit for bit. They hold for rigorous builds (fast = 0).
 */
#ifndef IACSG_RENDER_H
#define IACSG_RENDER_H
#include "camera.h"
#include "error.h"
#include "implicits/expr.h"

typedef struct iacsg_scene iacsg_scene; /* implicits/scene.h */

typedef struct iacsg_renderer iacsg_renderer;

typedef struct {
    int device; /* index as `iacsg devices` lists them */
    int fp64;   /* double intervals and rays instead of float */
    int fast;   /* no outward rounding (IA_FAST): NOT rigorous, for measuring what rigor costs */
    int stats;  /* count the interval evaluations of each ray (a kernel built with -D KERNEL_STATS) */
    /* The segment path's room per ray for the solids whose boxes it meets at the start of each frame (kernels/
     * scene_data.h; 0: SCENE_RAY_CANDIDATES). Rays that need more are traced again with four times the room;
     * tests set it tiny to check that. */
    int ray_candidates;
} iacsg_render_config;

/* Builds the render program for `expr_cl`, the OpenCL C source of iacsg_F, iacsg_f and iacsg_f_grad (as
 * iacsg_expr_emit_cl writes it with the prefix "iacsg"). The source is copied. Destroy with
 * iacsg_renderer_destroy. */
iacsg_status iacsg_renderer_create(const char *expr_cl, const iacsg_render_config *config, iacsg_renderer **out,
                                   iacsg_error *err);
void iacsg_renderer_destroy(iacsg_renderer *r);

/* The same for a compiled expression (src/render_expr.c): emits its OpenCL C and builds the program. */
iacsg_status iacsg_renderer_create_expr(const iacsg_expr *e, const iacsg_render_config *config,
                                        iacsg_renderer **out, iacsg_error *err);

/* The same for a scene (src/render_scene.c). A scene with items (regions, surfaces) is rendered by the segment
 * path; a plain scene (no items) by the first-root path, as its expression. The renderer keeps what it needs
 * of the scene: the scene may be destroyed after this call. */
iacsg_status iacsg_renderer_create_scene(const iacsg_scene *s, const iacsg_render_config *config,
                                         iacsg_renderer **out, iacsg_error *err);

/* The union of the proven boxes of the solids that a scene's items use (x0,y0,z0,x1,y1,z1), for its default
 * bounds; returns 0 when one of them has none (src/scene_tables.c). */
int iacsg_scene_bounds(const iacsg_scene *s, double box[6]);

/* Seconds the build took (clBuildProgram and the device compiling the kernel, see render.c: compile_now), and
 * the device's name (owned by the renderer). */
double iacsg_renderer_build_seconds(const iacsg_renderer *r);
const char *iacsg_renderer_device_name(const iacsg_renderer *r);

typedef struct {
    int width, height;
    iacsg_camera camera;
    double bounds[6]; /* x0, y0, z0, x1, y1, z1: rays are clipped to this box */
    double eps;       /* leaf width of the bisection along the ray (world units) */
    double time;      /* the value of t in the expression */
    /* Leave frame.depth, frame.normal or frame.ids NULL: the kernel then writes 4, 12 or 4 bytes a pixel fewer. */
    int no_depth, no_normals, no_ids;
    /* Called after each band of rows with the fraction done, when not NULL. */
    void (*progress)(double done, void *ctx);
    void *progress_ctx;
    /* Called after each band of rows, when not NULL: a nonzero return stops the render, which then returns
     * IACSG_ERR_CANCELLED and no frame. */
    int (*cancel)(void *ctx);
    void *cancel_ctx;
} iacsg_view;

#define IACSG_OVERLAP_PAIRS 4

typedef struct {
    int width, height;
    float *rgb;    /* 3 floats a pixel, display-encoded in [0, 1], row 0 at the top */
    float *depth;  /* 1 float a pixel: distance from the eye (ray parameter) at the hit, +inf on a miss (or NULL) */
    float *normal; /* 3 floats a pixel: the unit normal facing the eye, 0 on a miss (or NULL) */
    float *ids;    /* 1 float a pixel: the item (region or surface) hit, -1 on a miss; an expression: 0 (or NULL) */
    /* Statistics: rays traced, and with config.stats interval evaluations per ray (mean over all rays, max). */
    long long rays;
    double evals_mean;
    unsigned evals_max;
    /* The segment path. With config.stats: segments (runs of a solid possibly in, summed over the solids a ray
     * bisects) and partitions classified per ray, mean and max. Always: partitions claimed by two regions
     * (each ray's claimed one; the first declared wins), the first few distinct pairs (winner, other), the
     * per-ray buffer bytes the frame ended with, and the rays traced again with larger buffers. */
    double segments_mean, partitions_mean;
    unsigned segments_max, partitions_max;
    long long overlaps;
    int overlap_pairs[IACSG_OVERLAP_PAIRS][2], noverlap_pairs;
    long long ray_buffer_bytes, retraced_rays;
    double render_seconds; /* from the first kernel launch to the images in host memory */
} iacsg_frame;

/* Renders one frame into *frame (its images are allocated here; free them with iacsg_frame_free). */
iacsg_status iacsg_render(iacsg_renderer *r, const iacsg_view *view, iacsg_frame *frame, iacsg_error *err);
void iacsg_frame_free(iacsg_frame *frame);

#endif
