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
#include "implicits/scene_api.h"

IACSG_API_BEGIN

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
    /* The first-root path's program for an expression (src/render_expr.c): compiled (its own OpenCL C), or
     * interpreted (a fixed program that runs the expression's tape, built once for all expressions: for large
     * ones the compile is seconds). IACSG_TAPE_AUTO interprets expressions of at least IACSG_TAPE_MIN_NODES
     * operations or unions of at least IACSG_TAPE_MIN_PARTS parts, compiling those the interpreter cannot hold (a
     * part needing more registers than it has). */
    int tape;
    int tape_min_nodes; /* IACSG_TAPE_AUTO's threshold; 0: IACSG_TAPE_MIN_NODES (tests set it low) */
    /* The first-root path's -aa: the turns of a sample's walk in a round before it goes on in the next, among the
     * rays other packets left (src/render_effects_device.c; 0: FX_AA_TURNS; tests set it tiny). */
    int aa_turns;
} iacsg_render_config;

enum { IACSG_TAPE_AUTO = 0, IACSG_TAPE_NEVER, IACSG_TAPE_ALWAYS };
#define IACSG_TAPE_MIN_NODES 1024
#define IACSG_TAPE_MIN_PARTS 128

/* Builds the render program for `expr_cl`, the OpenCL C source of iacsg_Fv, iacsg_f_grad and so on (as
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

/* The union of the proven boxes of the solids that a scene's items use (x0,y0,z0,x1,y1,z1) for times in
 * [time[0], time[1]], for its default bounds (a plain scene: its expression's box); returns 0 when one of them
 * has none (src/scene_tables.c). */
int iacsg_scene_bounds(const iacsg_scene *s, const double time[2], double box[6]);

/* Seconds the build took (clBuildProgram and the device compiling the kernel, see render.c: compile_now), and
 * the device's name (owned by the renderer). */
double iacsg_renderer_build_seconds(const iacsg_renderer *r);
/* How the first-root path evaluates the expression: "compiled", "interpreted (...)" with the tape's size, or
 * "compiled (...)" with the reason the interpreter could not take it. Owned by the renderer. */
const char *iacsg_renderer_program(const iacsg_renderer *r);
const char *iacsg_renderer_device_name(const iacsg_renderer *r);

/* Ray-tracing effects of a frame (src/render_effects.c), all off in a zeroed struct. With none of them the frame
 * is the plain render, byte for byte; with any, the colours are computed again on the device from each pixel's
 * hits (their secondary rays traced by the same rigorous search: kernels/effects.cl, kernels/scene_effects.cl),
 * and the AOVs (depth, normals, ids) stay those of the pixel's centre ray. */
typedef enum {
    IACSG_SHADE_LIT = 0,  /* the lights (the plain render's, or `lights` with shadows and reflections) */
    IACSG_SHADE_GRADIENT, /* the colour of the normal's direction (Hijazi Fig. 6b), lit by the key light */
    IACSG_SHADE_NORMALS,  /* 0.5 + 0.5 n, unlit */
    IACSG_SHADE_DEPTH,    /* white near to black far over the hits' depth range */
    IACSG_SHADE_IDS       /* a palette colour per region or surface id */
} iacsg_shade;

typedef enum { IACSG_LIGHT_POINT = 0, IACSG_LIGHT_DIR } iacsg_light_kind;

typedef struct {
    iacsg_light_kind kind;
    double xyz[3];    /* point: the light's position; dir: the direction towards the light (any length) */
    double intensity; /* >= 0: the weight of its diffuse term (the highlight is scaled by it too) */
} iacsg_light;

#define IACSG_MAX_LIGHTS 8

typedef struct {
    iacsg_shade shade;
    int background;          /* 1: the background is a vertical gradient top -> bottom (equal ends: a colour) */
    float background_top[3], background_bottom[3]; /* display-encoded, in [0, 1] */
    /* The lights; none: the default rig, the plain render's key light (upper left of the eye, intensity 0.85)
     * and fill light (lower right, 0.30), directional and fixed to the camera. */
    iacsg_light lights[IACSG_MAX_LIGHTS];
    int nlights;
    int shadows; /* a shadow ray from every lit hit to each light */
    int bounces; /* reflection rays per path, for materials that reflect (0 to IACSG_MAX_BOUNCES) */
    /* The single expression's material (a scene's regions take theirs from their materials): the fraction of
     * light it reflects, and its transparency, 1 - opacity (0: opaque; above, each crossing of its surface is a
     * layer of that opacity, composited front to back). */
    double reflect, transparency;
    int aa; /* 1: one ray a pixel; N > 1: N x N rays in the pixels where the centre rays differ (edges) */
} iacsg_effects;

#define IACSG_MAX_BOUNCES 16
#define IACSG_MAX_AA 16

typedef struct {
    int width, height;
    iacsg_camera camera;
    double bounds[6]; /* x0, y0, z0, x1, y1, z1: rays are clipped to this box */
    double eps;       /* leaf width of the bisection along the ray (world units) */
    /* The value of t in the expression, as an interval that encloses it: {v, v} for a double v; for a real
     * that no double equals, the doubles around it (ia_decimal_double for a decimal text, iacsg_frame_time for
     * k/n). The kernel gets it rounded outward to its precision, as every constant of the expression, so the
     * guarantees hold for the real time. */
    double time[2];
    /* Leave frame.depth, frame.normal or frame.ids NULL: the kernel then writes 4, 12 or 4 bytes a pixel fewer. */
    int no_depth, no_normals, no_ids;
    /* Called after each band of rows with the fraction done, when not NULL. */
    void (*progress)(double done, void *ctx);
    void *progress_ctx;
    /* Called after each band of rows, when not NULL: a nonzero return stops the render, which then returns
     * IACSG_ERR_CANCELLED and no frame. With it (or progress) the first band is narrow (64 rows) and the next ones
     * grow while each takes under 20 ms, so that a frame stops within some 40 ms of a cancel. */
    int (*cancel)(void *ctx);
    void *cancel_ctx;
    /* Trace only rows [row_first, row_first + row_count) of the image (row_count 0: all of them), as a band of
     * a frame shared among processes; the frame's other rows are then unspecified. row_first is a multiple of
     * IACSG_ROW_ALIGN, so that each pixel comes out exactly as in the whole frame. */
    int row_first, row_count;
    /* The ray-tracing effects, or NULL for the plain render. */
    const iacsg_effects *effects;
    /* The colours in frame.rgb8, 3 bytes a pixel (as an 8-bit image stores them), not in frame.rgb, where the
     * camera kernel's colours are final: an expression's frame with no effect, or with effects that kernel applies
     * (no -aa, no reflected ray listed); else, and for a scene, frame.rgb as without it. 3 bytes a pixel are a
     * quarter of the fresh pages 12 are, and no conversion. */
    int rgb_bytes;
} iacsg_view;

/* The rows of a band start at multiples of this (a block of the kernel's tiles, src/render.c). */
#define IACSG_ROW_ALIGN 32

#define IACSG_OVERLAP_PAIRS 4

typedef struct {
    int width, height;
    float *rgb;    /* 3 floats a pixel, display-encoded in [0, 1], row 0 at the top (or NULL: rgb8) */
    float *depth;  /* 1 float a pixel: distance from the eye (ray parameter) at the hit, +inf on a miss (or NULL) */
    float *normal; /* 3 floats a pixel: the unit normal facing the eye, 0 on a miss (or NULL) */
    float *ids;    /* 1 float a pixel: the item (region or surface) hit, -1 on a miss; an expression: 0 (or NULL) */
    /* Statistics: rays traced (those of the rows traced), and with config.stats interval evaluations per ray
     * (mean over those rays, max). */
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
    double render_seconds; /* from the first kernel launch to the images in host memory, effects included */
    /* The effects' secondary rays (shadow, reflected, transparent, antialiasing) and, with config.stats, their
     * mean interval evaluations. */
    long long secondary_rays;
    double secondary_evals_mean;
    /* With view.rgb_bytes where honoured (rgb then NULL): the colours, 3 bytes a pixel (else NULL). */
    unsigned char *rgb8;
} iacsg_frame;

/* The lights a scene file declares (`light` statements), as iacsg_effects takes them: copies them (at most
 * IACSG_MAX_LIGHTS, which a scene never has more of) into `lights` and returns their count. */
int iacsg_scene_lights(const iacsg_scene *s, iacsg_light lights[IACSG_MAX_LIGHTS]);

/* Renders one frame into *frame (its images are allocated here; free them with iacsg_frame_free). */
iacsg_status iacsg_render(iacsg_renderer *r, const iacsg_view *view, iacsg_frame *frame, iacsg_error *err);
void iacsg_frame_free(iacsg_frame *frame);

/* The time of frame k of an animation of n frames, k/n, enclosed for iacsg_view.time: time[0] <= k/n <=
 * time[1], the two equal when k/n is a double. */
void iacsg_frame_time(int k, int n, double time[2]);

IACSG_API_END
#endif
