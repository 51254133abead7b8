/* src/render_effects.c -- the ray-tracing effects of a frame (iacsg_effects, render.h), after its camera rays:
 *
 *   frame (each pixel's centre ray: depth, normal, id) --> one path per pixel: (pixel, weight, ray, hit)
 *     --> shade each hit: its material under the lights, each light seen or not by a shadow ray (traced)
 *     --> children: a reflected ray (weight reflect), a ray through a transparent hit (weight 1 - opacity),
 *         traced, shaded in turn, until none is left (-bounces, EFFECTS_MAX_LAYERS) --> colours summed per pixel
 *     --> -aa N: the pixels whose centre rays differ from a neighbour's (edges) get N x N paths of their own
 *   --> rgb (linear light summed, then gamma 2 as kernels/light.h encodes).
 *
 * Everything per ray runs on the device, shaded by light.h (shade_effects): an expression's paths wholly in
 * kernels/effects.cl, most often inside the camera kernel (render_effects_in_camera: render.c launches it with
 * this file's block), else after the frame (render_effects_device.c launches them: this file lists the pixels),
 * as are -aa's edges; a scene's secondary rays traced by kernels/scene_effects.cl in packets of neighbouring
 * pixels' rays and their hits shaded there (render_effects_trace.c), its -aa samples as packets of the camera
 * kernel's (render_effects_samples.c), while this file keeps the paths, their shadow rays and children; where
 * scene_lit_in_kernel says so (every item opaque and at most one bounce, or no reflection), the scene's camera
 * kernel and its -aa samples light their hits themselves, shadow rays (through transparent items too), a reflected
 * ray or transparent layers and all (kernels/scene_lit.h), but for -shade ids and depth, whose centre paths stay on the
 * device (kernels/scene_centre.cl: centre_on_device), as where none has more than one child and no shadow rays are
 * cast, the host only encoding their colours and following the children whose hits have children. So an
 * occluder or a reflected surface that a ray crosses inside the bounds is never missed, and with the default rig
 * and no effect but -aa or -background a pixel gets the colour the plain render gives it.
 */
#include "render_effects_centre.h"
#include "render_effects_edges.h"
#include "implicits/scene.h"
#include "kernels/effects.h"
#include "kernels/params.h"
#include "kernels/scene_data.h"
#include "scene_tables.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A shadow ray's leaves, in eps: as wide as the camera rays' (the seed allows coarser), here and in
 * kernels/effects.cl. A coarser leaf stays conservative (one whose enclosure holds 0 blocks the ray, so no
 * crossing is missed) but shows a near miss within it as a shadow. Measured (1024x1024, eps 1e-5): the reference
 * view's marching shadow rays take 3.80 evaluations at 1, 4, 16 and 64 eps alike (a blocked ray ends on its
 * first proven crossing, an unblocked one never reaches a leaf); Fig. 2's regions' 12.62 at eps, 10.41 at 4,
 * 8.76 at 16, yet at 4 eps its render with shadows took as long (0.256 s against 0.253, medians of 22 runs in
 * turn) and 2 pixels of Fig. 6(c) turned to shadow at its edges. So the camera rays' rigour is kept. */
#define FX_SHADOW_EPS_FACTOR 1.0
/* The first-root path's material (kernels/shade.h). */
static const float fx_expr_albedo[3] = {0.80f, 0.52f, 0.28f};
/* The plain render's background, top to bottom (kernels/light.h). */
static const float fx_default_top[3] = {0.42f, 0.46f, 0.52f}, fx_default_bottom[3] = {0.13f, 0.14f, 0.17f};
/* The default rig, the plain render's key and fill lights (kernels/light.h): right and up coefficients of the
 * direction towards each (fixed to the camera), the weight of its diffuse term and of its highlight (times the
 * material's specular). */
static const double fx_rig[2][4] = {{-0.6, 0.8, 0.85, 1.0}, {0.9, -0.2, 0.30, 0.10 / 0.45}};
/* -aa: a pixel is an edge where its centre ray's id differs from a neighbour's, or its colour by FX_AA_CONTRAST
 * (render_effects_trace.h) in a channel (shadow and reflection edges), or its depth by this fraction. */
#define FX_AA_DEPTH 0.02
/* -aa's rays have leaves no narrower than a sample's footprint (at the bounds' farthest corner) / this. */
#define FX_AA_EPS_PER_SAMPLE 4
/* The segment path's paths are shaded this many pixels (or antialiasing rays) at a time: their buffers stay small
 * and are reused. Fig. 2's regions, medians of 11-15 in turn (EPYC): at 2^14 rather than 2^15 shadows 158 -> 138
 * ms, one bounce 183 -> 141, transparency 212 -> 183, -aa 4 277 -> 268 (a chunk's paths, hits and colours stay in
 * cache); 2^13 as 2^14, 2^12 and 2^19 slower. */
#define FX_CHUNK ((size_t)1 << 14)

typedef struct {
    double v[3];      /* point: the position; dir: the unit direction towards the light */
    int point;
    double intensity; /* the diffuse term's weight */
    double highlight; /* the highlight's weight (times the material's specular) */
} fx_light;

/* A buffer that only grows: a frame's passes reuse its pages (a malloc and free per pass of several MB went to
 * mmap and back, and its pages faulted in each time). */
typedef struct {
    void *p;
    size_t bytes;
} fx_buf;

static void *reserve(fx_buf *b, size_t bytes) {
    if (bytes > b->bytes) {
        free(b->p);
        b->bytes = 0;
        if (!(b->p = malloc(bytes)))
            return NULL;
        b->bytes = bytes;
    }
    return b->p;
}

typedef struct {
    iacsg_renderer *r;
    const iacsg_view *view;
    const iacsg_effects *e;
    fx_tracer tracer;
    double cam[PARAM_COUNT]; /* the camera in double (iacsg_camera_params) */
    fx_light lights[IACSG_MAX_LIGHTS];
    int nlights;
    double depth_lo, depth_hi; /* the centre hits' range, for -shade depth */
    float *accum;              /* 3 per pixel: the frame's rgb, holding linear light until encoded */
    /* the segment path's scratch: shadow rays, their hits, the (path, light) of each; the generations of paths
     * (two, in turn); the rays, hits and colours of a generation; the device's children left to the host */
    fx_buf shadow_rays, shadow_hits, shadow_of, kids[2], rays, hits, colors, rest;
    double block[EFFECTS_COUNT]; /* the effects' parameters for the kernels (kernels/effects.h) */
    float *palette;              /* a scene's: each item's -shade ids colour, linear */
    unsigned char *item_listed;  /* a scene's: 1 where a centre hit on the item gets a path (!item_keeps) */
} fx_frame;

/* Whether a material of the renderer's reflects light (an expression's: e->reflect). */
static int reflects(const iacsg_renderer *r, const iacsg_effects *e) {
    int any = !r->scene && e->reflect > 0;
    for (int i = 0; r->scene && r->fx && i < r->fx->nitems; i++)
        any |= r->fx->items[i].reflect > 0;
    return any;
}

/* The least opacity of a scene's items (1 where every one is opaque). */
static double scene_least_opacity(const iacsg_renderer *r) {
    double least = 1;
    for (int i = 0; r->fx && i < r->fx->nitems; i++)
        least = fmin(least, r->fx->items[i].opacity);
    return least;
}

/* Whether a material of the renderer's lets light through (an expression's: e->transparency). */
static int transparent(const iacsg_renderer *r, const iacsg_effects *e) {
    return r->scene ? scene_least_opacity(r) < 1 : e->transparency > 0;
}

/* Whether a path may have a child: a reflected ray, or one through a transparent hit. */
static int has_children(const iacsg_renderer *r, const iacsg_effects *e) {
    return transparent(r, e) || (e->bounces > 0 && reflects(r, e));
}

int fx_traces_secondary(const iacsg_renderer *r, const iacsg_effects *e) { return e->shadows || has_children(r, e); }

/* Whether the hits are lit (light.h's shading, in colour or by the normal's direction), not a preview. */
static int lit_shading(const iacsg_effects *e) {
    return e->shade == IACSG_SHADE_LIT || e->shade == IACSG_SHADE_GRADIENT;
}

/* Whether the effects do anything: else the frame is the plain render, untouched. */
static int effects_on(const iacsg_renderer *r, const iacsg_effects *e) {
    return e && (e->shade != IACSG_SHADE_LIT || e->background || e->nlights > 0 || e->shadows ||
                 has_children(r, e) || e->aa > 1);
}

int render_effects_need_aovs(const iacsg_renderer *r, const iacsg_view *view) { return effects_on(r, view->effects); }

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void normalize3(double v[3]) {
    double len = sqrt(dot3(v, v));
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

/* The right and up coordinates (s, v) on the image plane of the point x, y of the image, in pixels from its top
 * left corner (pixel (i, j)'s centre is (i + 1/2, j + 1/2)): kernels/camera.h's convention, in double. */
static double image_s(const fx_frame *f, double x) { return (2 * x / f->view->width - 1) * f->cam[PARAM_SCALE_S]; }
static double image_v(const fx_frame *f, double y) { return (1 - 2 * y / f->view->height) * f->cam[PARAM_SCALE_V]; }

/* Axis k of the camera ray through (s, v) on the image plane: its origin's, into *o, and its direction's,
 * unnormalised (returned). */
static double camera_axis(const double *p, int ortho, int k, double s, double v, double *o) {
    double offset = s * p[PARAM_RIGHT + k] + v * p[PARAM_UP + k];
    *o = p[PARAM_EYE + k] + (ortho ? offset : 0);
    return p[PARAM_FORWARD + k] + (ortho ? 0 : offset);
}

/* The camera ray through the point (s, v) of the image plane (image_s, image_v). Its direction is normalised
 * as normalize3 does but in registers: read back from memory as a pair (GCC's vectors), its two 8-byte stores
 * just made cannot be forwarded, a stall that held each ray until the one before was stored (most of the time
 * of a frame's centre rays). */
static void camera_ray_sv(const fx_frame *f, double s, double v, fx_ray *ray) {
    const double *p = f->cam;
    int ortho = f->view->camera.ortho_height > 0;
    double d0 = camera_axis(p, ortho, 0, s, v, &ray->o[0]), d1 = camera_axis(p, ortho, 1, s, v, &ray->o[1]);
    double d2 = camera_axis(p, ortho, 2, s, v, &ray->o[2]), len = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    ray->d[0] = d0 / len;
    ray->d[1] = d1 / len;
    ray->d[2] = d2 / len;
    ray->tn = 0;
    ray->tf = INFINITY;
    ray->passing = 0;
}

/* The camera ray through the point (x, y) of the image, in pixels from its top left corner. */
static void camera_ray_at(const fx_frame *f, double x, double y, fx_ray *ray) {
    camera_ray_sv(f, image_s(f, x), image_v(f, y), ray);
}

/* The lights: the view's, or the default rig, the plain render's key and fill lights fixed to the camera. */
static void resolve_lights(fx_frame *f) {
    const iacsg_effects *e = f->e;
    if (e->nlights == 0) {
        for (int l = 0; l < 2; l++) {
            fx_light *L = &f->lights[l];
            for (int k = 0; k < 3; k++)
                L->v[k] = -f->cam[PARAM_FORWARD + k] + fx_rig[l][0] * f->cam[PARAM_RIGHT + k] +
                          fx_rig[l][1] * f->cam[PARAM_UP + k];
            normalize3(L->v);
            L->point = 0;
            L->intensity = fx_rig[l][2];
            L->highlight = fx_rig[l][3];
        }
        f->nlights = 2;
        return;
    }
    for (int l = 0; l < e->nlights && l < IACSG_MAX_LIGHTS; l++) {
        fx_light *L = &f->lights[l];
        memcpy(L->v, e->lights[l].xyz, sizeof L->v);
        L->point = e->lights[l].kind == IACSG_LIGHT_POINT;
        if (!L->point)
            normalize3(L->v);
        L->intensity = L->highlight = e->lights[l].intensity;
    }
    f->nlights = e->nlights < IACSG_MAX_LIGHTS ? e->nlights : IACSG_MAX_LIGHTS;
}

/* How far a secondary ray starts off its hit: past the hit leaf's distance from the surface (a few eps) and the
 * rounding of the hit point (the depth is float32 and the host's ray differs from the device's by ulps). */
static double offset_of(const fx_frame *f, const double p[3], double t) {
    double scale = 1 + fabs(p[0]) + fabs(p[1]) + fabs(p[2]) + fabs(t);
    return 4 * f->view->eps + 4e-6 * scale;
}

static void hit_point(const fx_path *q, double p[3]) {
    for (int k = 0; k < 3; k++)
        p[k] = q->ray.o[k] + q->hit.t * q->ray.d[k];
}

/* The ray from (x, y, z) to light L: its origin, unit direction and [0, the distance]. The origin comes as
 * values and the direction is normalised in registers, not read back from the ray: see camera_ray_sv. */
static void aim_at_light(const fx_light *L, double x, double y, double z, fx_ray *ray) {
    ray->o[0] = x;
    ray->o[1] = y;
    ray->o[2] = z;
    ray->tn = 0;
    if (!L->point) {
        memcpy(ray->d, L->v, sizeof ray->d);
        ray->tf = INFINITY;
        return;
    }
    double lx = L->v[0] - x, ly = L->v[1] - y, lz = L->v[2] - z, dist = sqrt(lx * lx + ly * ly + lz * lz);
    ray->d[0] = lx / dist;
    ray->d[1] = ly / dist;
    ray->d[2] = lz / dist;
    ray->tf = dist;
}

/* The shadow ray from the hit of q to light L: from the hit moved off the surface along its normal (which faces
 * the ray, on the light's side when the light is in front of the surface), to the light. Returns 0 when the
 * light is behind the surface there (no ray: the diffuse term is 0 anyway). */
static int shadow_ray(const fx_frame *f, const fx_path *q, const fx_light *L, fx_ray *ray) {
    double p[3], l[3], n[3] = {q->hit.n[0], q->hit.n[1], q->hit.n[2]};
    hit_point(q, p);
    for (int k = 0; k < 3; k++) /* towards the light, unnormalised: only its side of the surface counts here */
        l[k] = L->point ? L->v[k] - p[k] : L->v[k];
    if (dot3(n, l) <= 0)
        return 0;
    double off = offset_of(f, p, q->hit.t);
    aim_at_light(L, p[0] + off * n[0], p[1] + off * n[1], p[2] + off * n[2], ray);
    ray->passing = 0;
    return 1;
}

static void add(float *accum, int pixel, double w, const double lin[3]) {
    for (int c = 0; c < 3; c++)
        accum[3 * (size_t)pixel + c] += (float)(w * lin[c]);
}

/* The fraction of light l that reaches the hit of paths[i], vis[EFFECTS_MAX_LIGHTS i + l]: none where the light
 * is behind its surface; else what a shadow ray from off the surface to the light lets through: 1 - opacity of
 * each transparent item it meets (a region is a volume, entered once: the ray goes on from inside it, passing
 * through it as a camera ray does; a surface is crossed), none past an opaque one; for at most EFFECTS_MAX_LAYERS
 * items, or until less than EFFECTS_MIN_WEIGHT of the light is left. */
static iacsg_status shadow_fractions(fx_frame *f, const fx_path *paths, size_t n, float *vis, iacsg_error *err) {
    size_t nl = (size_t)f->nlights, m = 0;
    fx_ray *rays = reserve(&f->shadow_rays, (n * nl + 1) * sizeof *rays);
    fx_hit *hits = reserve(&f->shadow_hits, (n * nl + 1) * sizeof *hits);
    long *owner = reserve(&f->shadow_of, (n * nl + 1) * sizeof *owner); /* the (path, light) of each ray */
    if (!rays || !hits || !owner)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
    memset(vis, 0, EFFECTS_MAX_LIGHTS * n * sizeof *vis); /* the lights not there, and those behind a surface */
    for (size_t l = 0; l < nl; l++) /* light by light: neighbouring paths' rays, a coherent packet */
        for (size_t i = 0; i < n; i++)
            if (paths[i].hit.item >= 0 && shadow_ray(f, &paths[i], &f->lights[l], &rays[m])) {
                vis[EFFECTS_MAX_LIGHTS * i + l] = 1;
                owner[m++] = (long)(EFFECTS_MAX_LIGHTS * i + l);
            }
    for (int layer = 0; m > 0 && layer < EFFECTS_MAX_LAYERS; layer++) {
        int whether = !transparent(f->r, f->e); /* every item opaque: a ray proven blocked needs no leaf */
        iacsg_status st = fx_trace(&f->tracer, rays, m, FX_SHADOW_EPS_FACTOR * f->view->eps, whether, hits, err);
        if (st != IACSG_OK)
            return st;
        size_t next = 0;
        for (size_t j = 0; j < m; j++) { /* in place: ray j is read before ray next <= j is written */
            if (hits[j].item == EFFECTS_HIT_BLOCKED)
                vis[owner[j]] = 0;
            if (hits[j].item < 0)
                continue; /* it reached the light, or is blocked */
            const fx_item *it = &f->r->fx->items[hits[j].item];
            float *v = &vis[owner[j]];
            *v *= 1 - it->opacity;
            if (*v < EFFECTS_MIN_WEIGHT)
                continue;
            fx_path past = {.ray = rays[j], .hit = hits[j]}; /* on from past it: its normal faces the ray */
            double p[3];
            hit_point(&past, p);
            double off = offset_of(f, p, hits[j].t);
            const float *n = hits[j].n;
            fx_ray *y = &rays[next];
            aim_at_light(&f->lights[owner[j] % EFFECTS_MAX_LIGHTS], p[0] - off * n[0], p[1] - off * n[1],
                         p[2] - off * n[2], y);
            y->passing = it->region ? 1 + hits[j].item : 0;
            owner[next++] = owner[j];
        }
        m = next;
    }
    return IACSG_OK;
}

/* Adds the colours of paths[0 .. n) that their hits give now, lit as far as their shadow rays let the lights
 * through; kids gets their children, reflected and transmitted rays not yet traced (*nout of them, at most 2n). */
static iacsg_status shade_generation(fx_frame *f, const fx_path *paths, size_t n, fx_path *kids, size_t *nout,
                                     iacsg_error *err) {
    const iacsg_effects *e = f->e;
    int lit = lit_shading(e);
    fx_shade_in in;
    float *out = reserve(&f->colors, (6 * n + 1) * sizeof *out);
    iacsg_status st = out ? fx_shade_inputs(&f->tracer, n, &in, err)
                          : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
    if (st == IACSG_OK && lit && e->shadows)
        st = shadow_fractions(f, paths, n, in.vis, err);
    for (size_t k = 0; st == IACSG_OK && !(lit && e->shadows) && k < EFFECTS_MAX_LIGHTS * n; k++)
        in.vis[k] = 1;
    /* the colours of the hits, on the device (light.h), their inputs written where it reads them */
    for (size_t i = 0; st == IACSG_OK && i < n; i++) {
        const fx_path *q = &paths[i];
        fx_put_ray(f->r, in.rays, i, &q->ray);
        fx_put_real(f->r, in.depth, i, isinf(q->hit.t) ? 0 : q->hit.t);
        memcpy(in.normal + 3 * i, q->hit.n, sizeof q->hit.n);
        in.item[i] = q->hit.item;
        in.row[i] = q->pixel / f->view->width;
    }
    if (st == IACSG_OK)
        st = fx_scene_shade(&f->tracer, f->block, &in, f->palette, out, err);
    if (st != IACSG_OK)
        return st;
    size_t nkids = 0;
    for (size_t i = 0; i < n; i++) {
        const fx_path *q = &paths[i];
        const float *color = out + 6 * i, *background = color + 3;
        double lin[3] = {color[0], color[1], color[2]};
        if (q->hit.item < 0 || !lit) { /* the background, or a preview's colour */
            add(f->accum, q->pixel, q->w, lin);
            continue;
        }
        const fx_item *m = &f->r->fx->items[q->hit.item];
        fx_weights wt = fx_path_weights(m, q->w, q->bounces, q->layers, e->bounces);
        add(f->accum, q->pixel, wt.shown, lin);
        if (wt.left > 0) { /* what is left of the path */
            double left[3] = {background[0], background[1], background[2]};
            add(f->accum, q->pixel, wt.left, left);
        }
        if (wt.mirror == 0 && wt.through == 0)
            continue; /* no child (most hits): its start is not needed */
        double p[3], n3[3] = {q->hit.n[0], q->hit.n[1], q->hit.n[2]};
        hit_point(q, p);
        double off = offset_of(f, p, q->hit.t);
        if (wt.mirror > 0) { /* the mirror direction, from off the surface */
            fx_path *c = &kids[nkids++];
            *c = *q;
            c->w = wt.mirror;
            c->bounces++;
            double dn = dot3(q->ray.d, n3);
            for (int j = 0; j < 3; j++) {
                c->ray.o[j] = p[j] + off * n3[j];
                c->ray.d[j] = q->ray.d[j] - 2 * dn * n3[j];
            }
            normalize3(c->ray.d);
            c->ray.tn = 0;
            c->ray.tf = INFINITY;
            c->ray.passing = 0;
        }
        if (wt.through > 0) { /* on through the surface: from just past it, the same direction */
            fx_path *c = &kids[nkids++];
            *c = *q;
            c->w = wt.through;
            c->layers++;
            for (int j = 0; j < 3; j++)
                c->ray.o[j] = p[j] - off * n3[j];
            c->ray.tn = 0;
            c->ray.tf = INFINITY;
            /* a region is a volume: the ray, now inside it, passes through it to what lies behind (one layer
             * where it enters); a surface is crossed like the expression's */
            c->ray.passing = m->region ? 1 + q->hit.item : 0;
        }
    }
    *nout = nkids;
    return IACSG_OK;
}

/* Traces the rays of paths[0 .. n) into their hits, with leaves of width eps (fx_trace). */
static iacsg_status trace_paths(fx_frame *f, fx_path *paths, size_t n, double eps, iacsg_error *err) {
    fx_ray *rays = reserve(&f->rays, (n + 1) * sizeof *rays);
    fx_hit *hits = reserve(&f->hits, (n + 1) * sizeof *hits);
    iacsg_status st = rays && hits ? IACSG_OK : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    for (size_t i = 0; st == IACSG_OK && i < n; i++)
        rays[i] = paths[i].ray;
    if (st == IACSG_OK)
        st = fx_trace(&f->tracer, rays, n, eps, 0, hits, err);
    for (size_t i = 0; st == IACSG_OK && i < n; i++)
        paths[i].hit = hits[i];
    return st;
}

/* Shades paths (their hits known; the caller's) and all their descendants into f->accum. */
static iacsg_status run_paths(fx_frame *f, fx_path *first, size_t n, iacsg_error *err) {
    iacsg_status st = IACSG_OK;
    fx_path *paths = first;
    for (int g = 0; n > 0 && st == IACSG_OK; g = 1 - g) { /* a path has at most 2 children */
        fx_path *kids = reserve(&f->kids[g], (2 * n + 1) * sizeof *kids);
        size_t nk = 0;
        st = kids ? shade_generation(f, paths, n, kids, &nk, err)
                  : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
        paths = kids;
        n = nk;
        if (st == IACSG_OK)
            st = trace_paths(f, paths, n, f->view->eps, err);
    }
    return st;
}

/* The rows the view traces. */
static void traced_rows(const iacsg_view *v, int *row0, int *row1) {
    *row0 = v->row_first;
    *row1 = v->row_count ? v->row_first + v->row_count : v->height;
}

/* Whether the kernel's default rig alone lights the hits as the host would (kernels/light.h): lit, no light of
 * the command's or the scene's, no shadow. */
static int rig_alone(const iacsg_effects *e) { return e->shade == IACSG_SHADE_LIT && e->nlights == 0 && !e->shadows; }

/* Whether the host would light each centre hit exactly as the kernel did (the rig alone, no reflection, no
 * transparency), so that the kernel's colours stand. */
static int kernel_colors_hold(const iacsg_renderer *r, const iacsg_effects *e) {
    return rig_alone(e) && !has_children(r, e);
}

/* Whether the kernel's colour stands for a scene's centre hit on item i: the rig alone lights it and its
 * material neither reflects nor lets light through, so its path would have no child and the host's colour would
 * be the kernel's. The mirror's and the glass's other items then get no path at all. */
static int item_keeps(const fx_frame *f, int i) {
    const fx_item *m = &f->r->fx->items[i];
    return rig_alone(f->e) && !(f->e->bounces > 0 && m->reflect > 0) && m->opacity >= 1;
}

/* Whether a scene's camera kernel (and -aa's samples) can light its hits with the effects (kernels/scene_lit.h:
 * scene_packet_lit), lit or -shade gradient or normals (-shade ids' palette and depth's range are the host's): where
 * every item is opaque, at most one bounce (a reflected ray's hit has no child); where some item lets light
 * through, no reflected ray. */
static int scene_lit_in_kernel(const iacsg_renderer *r, const iacsg_effects *e) {
    int mirrors = reflects(r, e) && e->bounces > 0;
    return e->shade != IACSG_SHADE_DEPTH && e->shade != IACSG_SHADE_IDS &&
           (transparent(r, e) ? !mirrors : !mirrors || e->bounces == 1);
}

/* The reflected rays a first-root path's path may list for a next launch: only off a transparent surface (off an
 * opaque one the path goes on in its lane), one per layer at most. */
static int expr_kid_slots(const iacsg_effects *e) {
    return e->bounces > 0 && e->reflect > 0 && e->transparency > 0 ? EFFECTS_MAX_LAYERS : 0;
}

/* The traced pixels in blocks of 4x4 that get a path (a miss where -background changes it, a hit where the
 * kernel's colour does not stand), in that order, into out (room for every traced pixel); returns how many. Block
 * order, so that the secondary rays of a packet (kernels/effects.cl) come from neighbouring pixels. One pass that
 * lists as it goes: a list of every pixel first, then filtered, cost a megapixel's 4 MB (its page faults) and a
 * pass more, all on one CPU. */
static size_t block_select(const fx_frame *f, const iacsg_frame *fr, int *out) {
    const iacsg_view *v = f->view;
    /* in locals, and item_keeps by its table: the stores to out may alias what f points to, and reloading it for
     * each of a megapixel's hits was most of this pass */
    int row0, row1, keep = kernel_colors_hold(f->r, f->e), background = f->e->background, width = v->width;
    const float *depth = fr->depth, *ids = fr->ids;
    const unsigned char *item_listed = ids ? f->item_listed : NULL; /* NULL: every hit listed */
    traced_rows(v, &row0, &row1);
    size_t n = 0;
    for (int bj = row0; bj < row1; bj += PACKET_H)
        for (int bi = 0; bi < width; bi += PACKET_W)
            for (int j = bj; j < bj + PACKET_H && j < row1; j++)
                for (int i = bi; i < bi + PACKET_W && i < width; i++) {
                    int pixel = j * width + i;
                    if (isinf(depth[pixel]) ? background : !keep && (!item_listed || item_listed[(int)ids[pixel]]))
                        out[n++] = pixel;
                }
    return n;
}

/* Room for a list of the traced pixels (block_select). */
static int *pixel_list(const fx_frame *f) {
    int row0, row1;
    traced_rows(f->view, &row0, &row1);
    return malloc(((size_t)(row1 - row0) * (size_t)f->view->width + 1) * sizeof(int));
}

/* The centre hits' depth range, where -shade depth needs it (a pass over the frame's megapixel of depths costs a
 * few ms, all on one CPU). */
static void depth_range(fx_frame *f, const iacsg_frame *fr) {
    int row0, row1;
    traced_rows(f->view, &row0, &row1);
    f->depth_lo = INFINITY;
    f->depth_hi = -INFINITY;
    for (size_t p = (size_t)row0 * (size_t)f->view->width; f->e->shade == IACSG_SHADE_DEPTH &&
                                                              p < (size_t)row1 * (size_t)f->view->width; p++)
        if (!isinf(fr->depth[p])) {
            f->depth_lo = fmin(f->depth_lo, fr->depth[p]);
            f->depth_hi = fmax(f->depth_hi, fr->depth[p]);
        }
}

/* The path of a pixel's centre ray, its hit the frame's (depth, normal, id); col_s and row_v: image_s and image_v
 * of each column's and row's centre (a megapixel's divisions made once a column and row). */
static void centre_path(const fx_frame *f, const iacsg_frame *fr, const double *col_s, const double *row_v, int pixel,
                        fx_path *q) {
    memset(q, 0, sizeof *q);
    q->pixel = pixel;
    q->w = 1;
    camera_ray_sv(f, col_s[pixel % f->view->width], row_v[pixel / f->view->width], &q->ray);
    q->hit.t = fr->depth[pixel];
    memcpy(q->hit.n, fr->normal + 3 * (size_t)pixel, sizeof q->hit.n);
    q->hit.item = isinf(q->hit.t) ? -1 : fr->ids ? (int)fr->ids[pixel] : 0;
}

/* The traced pixels on an edge (fx_find_edges), in block order, into edges; returns how many, or -1 out of
 * memory. */
static long edge_pixels(const fx_frame *f, const iacsg_frame *fr, int *edges) {
    int row0, row1;
    traced_rows(f->view, &row0, &row1);
    return fx_find_edges(fr, row0, row1, (float)FX_AA_CONTRAST, (float)FX_AA_DEPTH, edges);
}

/* -aa's rays' leaves: eps, or a quarter of a sample's footprint where that is wider. A ray that passes that close
 * to a surface may be shown hitting it, so a silhouette grows by at most a quarter of a sample; the samples only
 * colour the pixel (its depth is the centre ray's). Rays grazing silhouettes are the costly ones: on
 * min(sphere, torus) (eps 1e-5) 136 evaluations a sample at eps, 73 so (the camera rays: 2.4). */
static double aa_eps(const fx_frame *f) {
    return fmax(f->view->eps, f->tracer.footprint / (FX_AA_EPS_PER_SAMPLE * f->e->aa));
}

/* The hits of -aa's sample rays paths[0 .. n), the aa x aa of each of pixels[0 .. npixels) in antialias's order,
 * traced as packets of the camera kernel's (fx_scene_samples) with -aa's leaves. */
static iacsg_status trace_samples(fx_frame *f, const int *pixels, size_t npixels, fx_path *paths, size_t n,
                                  iacsg_error *err) {
    fx_hit *hits = reserve(&f->hits, (n + 1) * sizeof *hits);
    if (!hits)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for -aa's samples");
    iacsg_status st = fx_scene_samples(&f->tracer, f->e->aa, aa_eps(f), pixels, npixels, hits, NULL, NULL, err);
    for (size_t i = 0; st == IACSG_OK && i < n; i++)
        paths[i].hit = hits[i];
    return st;
}

/* -aa N on the segment path: the pixels on an edge get N x N rays of their own, on a regular grid in the pixel,
 * each weighing 1 / N^2; their centre rays' colours are replaced. Where the camera kernel can light the samples
 * (scene_lit_in_kernel) it gives their colours; else they are paths of the host's. */
static iacsg_status antialias(fx_frame *f, iacsg_frame *fr, fx_path *paths, iacsg_error *err) {
    const iacsg_view *v = f->view;
    int aa = f->e->aa, w = v->width, lit = scene_lit_in_kernel(f->r, f->e);
    float *colours = lit ? reserve(&f->colors, (3 * FX_CHUNK + 1) * sizeof *colours) : NULL;
    if (lit && !colours)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for -aa's samples");
    int *edges = pixel_list(f);
    if (!edges)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    long found = edge_pixels(f, fr, edges);
    if (found < 0) {
        free(edges);
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    }
    size_t nedges = (size_t)found;
    iacsg_status st = IACSG_OK;
    size_t samples = (size_t)aa * aa, per_chunk = FX_CHUNK / samples, k = 0;
    while (st == IACSG_OK && k < nedges) { /* the edge pixels in block order, per_chunk at a time */
        size_t first = k;
        k = first + (nedges - first < per_chunk ? nedges - first : per_chunk);
        for (size_t q = first; q < k; q++) /* the samples' light replaces the centre ray's colour */
            for (int c = 0; c < 3; c++)
                fr->rgb[3 * (size_t)edges[q] + c] = 0;
        if (lit) { /* sample s of the chunk is sample s mod aa^2 of its pixel */
            st = fx_scene_samples(&f->tracer, aa, aa_eps(f), edges + first, k - first, NULL, f->block, colours, err);
            for (size_t s = 0; st == IACSG_OK && s < (k - first) * samples; s++) {
                double lin[3] = {colours[3 * s], colours[3 * s + 1], colours[3 * s + 2]};
                add(f->accum, edges[first + s / samples], 1.0 / samples, lin);
            }
        } else {
            size_t n = 0;
            for (size_t q = first; q < k; q++) {
                int pixel = edges[q], i = pixel % w, j = pixel / w;
                for (int b = 0; b < aa; b++)
                    for (int a = 0; a < aa; a++) {
                        fx_path *p = &paths[n++];
                        memset(p, 0, sizeof *p);
                        p->pixel = pixel;
                        p->w = 1.0 / samples;
                        camera_ray_at(f, i + (a + 0.5) / aa, j + (b + 0.5) / aa, &p->ray);
                    }
            }
            st = trace_samples(f, edges + first, k - first, paths, n, err);
            if (st == IACSG_OK)
                st = run_paths(f, paths, n, err);
        }
        for (size_t q = first; st == IACSG_OK && q < k; q++)
            fx_encode(fr->rgb, edges[q]);
    }
    free(edges);
    return st;
}

/* The first-root path's effects' block (kernels/effects.h): the view's lights or the default rig (its lights
 * computed on the device as the plain kernel computes them), the expression's material. */
static void effects_block(const fx_frame *f, double b[EFFECTS_COUNT]) {
    const iacsg_effects *e = f->e;
    memset(b, 0, EFFECTS_COUNT * sizeof *b);
    b[EFFECTS_SHADE] = e->shade;
    b[EFFECTS_SHADOWS] = e->shadows;
    b[EFFECTS_BOUNCES] = e->bounces;
    for (int c = 0; c < 3; c++) {
        float rgb[3];
        scene_palette(0, rgb);
        b[EFFECTS_ALBEDO + c] = fx_expr_albedo[c];
        b[EFFECTS_BG_TOP + c] = e->background ? e->background_top[c] : fx_default_top[c];
        b[EFFECTS_BG_BOTTOM + c] = e->background ? e->background_bottom[c] : fx_default_bottom[c];
        b[EFFECTS_ID_RGB + c] = rgb[c];
    }
    b[EFFECTS_SPECULAR] = SCENE_DEFAULT_SPECULAR;
    b[EFFECTS_SHININESS] = SCENE_DEFAULT_SHININESS;
    b[EFFECTS_REFLECT] = e->reflect;
    /* a scene's: its items' least (kernels/scene_lit.h), as transparent() reads it */
    b[EFFECTS_OPACITY] = f->r->scene ? scene_least_opacity(f->r) : 1 - e->transparency;
    b[EFFECTS_DEPTH_LO] = f->depth_lo;
    b[EFFECTS_DEPTH_HI] = f->depth_hi;
    b[EFFECTS_NLIGHTS] = f->nlights;
    for (int l = 0; l < f->nlights; l++) {
        double *L = b + EFFECTS_LIGHTS + EFFECTS_LIGHT_REALS * l;
        L[EFFECTS_LIGHT_KIND] = e->nlights == 0 ? EFFECTS_LIGHT_CAMERA
                                : f->lights[l].point ? EFFECTS_LIGHT_POINT
                                                     : EFFECTS_LIGHT_DIR;
        for (int k = 0; k < 3; k++)
            L[EFFECTS_LIGHT_XYZ + k] = e->nlights == 0 ? (k < 2 ? fx_rig[l][k] : 0) : f->lights[l].v[k];
        L[EFFECTS_LIGHT_INTENSITY] = f->lights[l].intensity;
        L[EFFECTS_LIGHT_HIGHLIGHT] = f->lights[l].highlight;
    }
}

/* The first-root path: the centre rays' colours (the hits', and the misses' where the background is not the
 * kernel's; none where the kernel's colours stand, nor where the camera kernel applied the effects: in_camera),
 * then -aa's edges, all shaded on the device (render_effects_device.c). */
static iacsg_status apply_expr(fx_frame *f, iacsg_frame *frame, int in_camera, iacsg_error *err) {
    const iacsg_effects *e = f->e;
    int kid_slots = expr_kid_slots(e);
    int *listed = pixel_list(f);
    if (!listed)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
    iacsg_status st = IACSG_OK;
    size_t n;
    if (!in_camera) {
        n = block_select(f, frame, listed);
        double centre[2] = {0, f->tracer.footprint}; /* Newton's window for the walks of the secondary rays */
        st = fx_device_run(&f->tracer, f->block, kid_slots, EFFECTS_MODE_CENTRE, listed, n, 1, centre, frame, err);
    }
    if (st == IACSG_OK && e->aa > 1) {
        double aa[2] = {aa_eps(f), f->tracer.footprint};
        long edges = edge_pixels(f, frame, listed);
        n = edges > 0 ? (size_t)edges : 0;
        if (edges < 0)
            st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
        if (st == IACSG_OK)
            st = fx_device_run(&f->tracer, f->block, kid_slots, EFFECTS_MODE_AA, listed, n, e->aa, aa, frame, err);
    }
    free(listed);
    return st;
}

/* Whether fx_scene_centre can make, trace and shade a segment path's children (lit, no shadows, at most one child
 * a path: no material may both reflect and let light through). */
static int children_on_device(const fx_frame *f) {
    const iacsg_effects *e = f->e;
    int lit = lit_shading(e);
    return lit && !e->shadows && !(transparent(f->r, e) && e->bounces > 0 && reflects(f->r, e));
}

/* The centre paths of pixels[0 .. count) where none has a child, or children_on_device, FX_CHUNK at a time, on the
 * device (fx_scene_centre: their rays, shadow rays, children and colours, display-encoded into the frame where no
 * path has a child); the host only sums and encodes the colours of paths with children, and follows the children
 * whose hits have children (run_paths). Their rays are the camera kernel's, in the
 * working precision (the host's were in double, rounded): a shading point, a shadow ray's or a child's start may
 * move by ulps. */
static iacsg_status centre_on_device(fx_frame *f, iacsg_frame *frame, const int *pixels, size_t count,
                                     iacsg_error *err) {
    const iacsg_effects *e = f->e;
    int lit = lit_shading(e);
    float *out = reserve(&f->colors, (6 * FX_CHUNK + 1) * sizeof *out);
    fx_path *rest = reserve(&f->rest, FX_CHUNK * sizeof *rest);
    iacsg_status st = out && rest ? IACSG_OK
                                  : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
    int children = has_children(f->r, e);
    for (size_t k = 0; st == IACSG_OK && k < count; k += FX_CHUNK) {
        size_t n = count - k < FX_CHUNK ? count - k : FX_CHUNK, nrest = 0;
        /* without children the device encodes the colours into the frame itself */
        st = fx_scene_centre(&f->tracer, f->block, pixels + k, n, frame, lit && e->shadows,
                             FX_SHADOW_EPS_FACTOR * f->view->eps, f->palette, children, children ? out : NULL, rest,
                             &nrest, err);
        if (!children)
            continue;
        for (size_t q = 0; st == IACSG_OK && q < n; q++) /* a path's colour, all of its pixel's but rest's */
            memcpy(frame->rgb + 3 * (size_t)pixels[k + q], out + 6 * q, 3 * sizeof(float));
        if (st == IACSG_OK && nrest > 0)
            st = run_paths(f, rest, nrest, err);
        for (size_t q = 0; st == IACSG_OK && q < n; q++)
            fx_encode(frame->rgb, pixels[k + q]);
    }
    return st;
}

/* The segment path: the centre rays' colours FX_CHUNK hits at a time (a miss is its background, and a hit keeps
 * the kernel's colour where the host's would be the same; none where the camera kernel applied the effects:
 * in_camera); then -aa decides its edges on them. */
static iacsg_status apply_scene(fx_frame *f, iacsg_frame *frame, int in_camera, iacsg_error *err) {
    iacsg_status st = IACSG_OK;
    fx_path *paths = malloc(FX_CHUNK * sizeof *paths);
    int *listed = pixel_list(f);
    double *col_s = malloc((size_t)f->view->width * sizeof *col_s);
    double *row_v = malloc((size_t)f->view->height * sizeof *row_v);
    if (!paths || !listed || !col_s || !row_v) {
        free(paths);
        free(listed);
        free(col_s);
        free(row_v);
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
    }
    for (int i = 0; i < f->view->width; i++)
        col_s[i] = image_s(f, i + 0.5);
    for (int j = 0; j < f->view->height; j++)
        row_v[j] = image_v(f, j + 0.5);
    size_t count = in_camera ? 0 : block_select(f, frame, listed);
    int on_device = !has_children(f->r, f->e) || children_on_device(f);
    if (on_device)
        st = centre_on_device(f, frame, listed, count, err);
    for (size_t k = on_device ? count : 0; st == IACSG_OK && k < count;) {
        size_t n = 0;
        for (; k < count && n < FX_CHUNK; k++) {
            int pixel = listed[k];
            memset(frame->rgb + 3 * (size_t)pixel, 0, 3 * sizeof(float));
            centre_path(f, frame, col_s, row_v, pixel, &paths[n++]);
        }
        st = run_paths(f, paths, n, err);
        for (size_t q = 0; st == IACSG_OK && q < n; q++)
            fx_encode(frame->rgb, paths[q].pixel);
    }
    if (st == IACSG_OK && f->e->aa > 1)
        st = antialias(f, frame, paths, err);
    free(paths);
    free(listed);
    free(col_s);
    free(row_v);
    return st;
}

/* What a frame's effects need before its pixels: the camera, the lights, the effects' block. */
static iacsg_status frame_open(fx_frame *f, iacsg_renderer *r, const iacsg_view *view, iacsg_error *err) {
    memset(f, 0, sizeof *f);
    f->r = r;
    f->view = view;
    f->e = view->effects;
    iacsg_status st = iacsg_camera_params(&view->camera, view->width, view->height, f->cam, err);
    resolve_lights(f);
    effects_block(f, f->block);
    return st;
}

void render_effects_aovs(const iacsg_renderer *r, const iacsg_view *view, int *depth, int *normals) {
    const iacsg_effects *e = view->effects;
    int on = effects_on(r, e);
    int centre_pass = on && !render_effects_in_camera(r, view) && (!kernel_colors_hold(r, e) || e->background);
    *depth = centre_pass || (on && e->aa > 1);
    *normals = centre_pass;
}

int render_effects_in_camera(const iacsg_renderer *r, const iacsg_view *view) {
    const iacsg_effects *e = view->effects;
    if (!effects_on(r, e) || kernel_colors_hold(r, e))
        return 0;
    if (r->scene)
        return scene_lit_in_kernel(r, e);
    return !r->tape && e->shade != IACSG_SHADE_DEPTH && expr_kid_slots(e) == 0;
}

int render_effects_camera_final(const iacsg_renderer *r, const iacsg_view *view) {
    return !effects_on(r, view->effects) || (render_effects_in_camera(r, view) && view->effects->aa <= 1);
}

iacsg_status render_effects_camera_open(iacsg_renderer *r, const iacsg_view *view, size_t packets,
                                        render_fx_camera *c, iacsg_error *err) {
    memset(c, 0, sizeof *c);
    fx_frame f;
    iacsg_status st = frame_open(&f, r, view, err);
    if (st == IACSG_OK)
        st = fx_block_buffer(r, f.block, &c->block, err);
    if (st == IACSG_OK)
        st = fx_all_groups(r, &c->all_groups, err);
    if (st == IACSG_OK)
        st = fx_footprint(view, &c->footprint, err);
    if (st == IACSG_OK && r->config.stats) {
        /* in huge pages where it can (a megapixel's 8 MB in small pages: ~2,000 page faults when summed) */
        if (!(c->counts_host = render_in_place_alloc(2 * packets * sizeof(cl_uint))))
            return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects' counts");
        memset(c->counts_host, 0, 2 * packets * sizeof(cl_uint)); /* 0 for the packets of rows not traced */
        c->packets = packets;
        cl_int rc = CL_SUCCESS;
        c->counts = clCreateBuffer(r->rt.context, CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR,
                                   2 * packets * sizeof(cl_uint), c->counts_host, &rc);
        if (rc != CL_SUCCESS)
            st = clrt_record(err, rc, "clCreateBuffer(effects' counts)", __func__, __LINE__);
    }
    return st;
}

void render_effects_camera_close(render_fx_camera *c) {
    cl_mem all[3] = {c->block, c->all_groups, c->counts};
    for (int k = 0; k < 3; k++)
        if (all[k])
            clReleaseMemObject(all[k]);
    free(c->counts_host);
    memset(c, 0, sizeof *c);
}

iacsg_status render_effects_apply(iacsg_renderer *r, const iacsg_view *view, iacsg_frame *frame,
                                  const render_fx_camera *in_camera, const render_frame_tiles *tiles,
                                  iacsg_error *err) {
    if (!effects_on(r, view->effects))
        return IACSG_OK;
    double t0 = render_now_seconds();
    long long camera_rays = 0; /* the camera kernel's secondary rays and their evaluations */
    double camera_evals = 0;
    for (size_t k = 0; in_camera && k < in_camera->packets; k++) {
        camera_rays += in_camera->counts_host[2 * k];
        camera_evals += in_camera->counts_host[2 * k + 1];
    }
    fx_frame f;
    iacsg_status st = frame_open(&f, r, view, err);
    int left = !in_camera || view->effects->aa > 1; /* anything the camera kernel did not do */
    if (st == IACSG_OK && left)
        st = fx_tracer_open(&f.tracer, r, view, err);
    if (tiles)
        f.tracer.tiles = *tiles;
    f.accum = frame->rgb;
    depth_range(&f, frame);
    f.block[EFFECTS_DEPTH_LO] = f.depth_lo;
    f.block[EFFECTS_DEPTH_HI] = f.depth_hi;
    if (st == IACSG_OK && r->scene) { /* -shade ids: each item's palette colour */
        int nitems = r->fx && r->fx->nitems > 0 ? r->fx->nitems : 1;
        if (!(f.palette = malloc(3 * (size_t)nitems * sizeof *f.palette)))
            st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
        for (int i = 0; st == IACSG_OK && i < nitems; i++)
            scene_palette(i, f.palette + 3 * i);
        if (st == IACSG_OK && !(f.item_listed = malloc((size_t)nitems)))
            st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the effects");
        for (int i = 0; st == IACSG_OK && i < nitems; i++)
            f.item_listed[i] = !(r->fx && i < r->fx->nitems && item_keeps(&f, i));
    }
    if (st == IACSG_OK && left)
        st = r->scene ? apply_scene(&f, frame, in_camera != NULL, err)
                      : apply_expr(&f, frame, in_camera != NULL, err);
    free(f.palette);
    free(f.item_listed);
    fx_buf *bufs[] = {&f.shadow_rays, &f.shadow_hits, &f.shadow_of, &f.kids[0], &f.kids[1],
                      &f.rays,        &f.hits,        &f.colors,    &f.rest};
    for (size_t k = 0; k < sizeof bufs / sizeof bufs[0]; k++)
        free(bufs[k]->p);
    frame->secondary_rays = f.tracer.rays + camera_rays;
    frame->secondary_evals_mean = frame->secondary_rays ? (f.tracer.evals + camera_evals) / frame->secondary_rays : 0;
    fx_tracer_close(&f.tracer);
    frame->render_seconds += render_now_seconds() - t0;
    return st;
}

iacsg_status render_effects_keep_scene(iacsg_renderer *r, const iacsg_scene *s, iacsg_error *err) {
    render_fx *fx = NULL;
    iacsg_status st = fx_of(r, &fx, err);
    if (st != IACSG_OK)
        return st;
    fx->items = malloc(sizeof *fx->items * (size_t)(s->nitems + 1));
    if (!fx->items)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    fx->nitems = s->nitems;
    for (int i = 0; i < s->nitems; i++) {
        int m = s->items[i].material;
        fx->items[i].reflect = m >= 0 ? s->materials[m].reflect : 0;
        fx->items[i].opacity = m >= 0 ? s->materials[m].opacity : 1;
        fx->items[i].region = s->items[i].kind == SCENE_REGION;
    }
    return IACSG_OK;
}

_Static_assert(SCENE_MAX_LIGHTS == IACSG_MAX_LIGHTS, "a scene's lights fit iacsg_effects");

int iacsg_scene_lights(const iacsg_scene *s, iacsg_light lights[IACSG_MAX_LIGHTS]) {
    for (int l = 0; l < s->nlights; l++) {
        lights[l].kind = s->lights[l].dir ? IACSG_LIGHT_DIR : IACSG_LIGHT_POINT;
        memcpy(lights[l].xyz, s->lights[l].xyz, sizeof lights[l].xyz);
        lights[l].intensity = s->lights[l].intensity;
    }
    return s->nlights;
}

void render_effects_free(render_fx *fx) {
    if (!fx)
        return;
    cl_kernel kernels[] = {fx->trace, fx->shade, fx->samples, fx->centre, fx->compact};
    for (size_t k = 0; k < sizeof kernels / sizeof kernels[0]; k++)
        if (kernels[k])
            clReleaseKernel(kernels[k]);
    free(fx->items);
    free(fx);
}
