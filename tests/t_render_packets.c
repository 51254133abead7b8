/* tests/t_render_packets.c -- the two packet shapes (src/render.c: render_packet_w, kernels/params.h): 4 x 4 pixels
 * in 16 lanes and 2 x 4 in 8, which the device's vector width picks on the first-root path, forced here both ways
 * (IACSG_PACKET_LANES) on both paths so that every machine runs both. A camera ray's walk on the first-root path does
 * not depend on its packet (the frame's tree, each lane's own steps), so its camera frames are the same bits:
 * colours (as floats and as bytes, whole packets and the image's cut ones), depths, normals and the evaluation
 * counts; compiled, on the tape and in double. A secondary ray's tree is as long as its packet's farthest ray, so
 * the effects may move a hit within a leaf: their AOVs (the centre rays') are the same bits, their colours within
 * 2/255 (a gyroid in a ball's with the same effects: 306 of 22,500 values moved, by at most 0.0031; the sphere and
 * torus's 128, by less than 1e-4). The segment path's host lays its blocks, its -aa samples' packets and its lists
 * out by the renderer's width: regions (with the union's pre-pass, and with -aa 4, reflections and glass) and a
 * level-set surface, compared by check_scene_frames. */
#include "iacsg.h"
#include "render_internal.h"
#include "test.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *expr; /* an expression, or with `scene` a scene's text (its frames compared as a scene's) */
    iacsg_render_config config;
    int effects, bytes, scene;
} packets_case;

/* The renderer of a case's text: a scene, or one expression (a scene without items, rendered as
 * iacsg_renderer_create_expr renders it). */
static iacsg_status create_case(const packets_case *c, iacsg_renderer **r, iacsg_error *err) {
    iacsg_scene *s = NULL;
    iacsg_status st = iacsg_scene_parse(c->expr, "<test>", &s, err);
    if (st == IACSG_OK)
        st = iacsg_renderer_create_scene(s, &c->config, r, err);
    iacsg_scene_destroy(s);
    return st;
}

/* The frame of one case with packets of `lanes` lanes (r->packet_w checked); returns 0 on a failure (reported). */
static int render_with(const packets_case *c, const char *lanes, const iacsg_view *view, iacsg_frame *f) {
    iacsg_error err = {0};
    iacsg_renderer *r = NULL;
    setenv("IACSG_PACKET_LANES", lanes, 1);
    int ok = create_case(c, &r, &err) == IACSG_OK;
    unsetenv("IACSG_PACKET_LANES");
    CHECK(ok, "%s (%s lanes): %s", c->expr, lanes, err.message);
    if (!ok)
        return 0;
    CHECK(render_packet_lanes(r) == atoi(lanes), "asked for %s lanes, got %d", lanes, render_packet_lanes(r));
    ok = iacsg_render(r, view, f, &err) == IACSG_OK;
    CHECK(ok, "%s (%s lanes): %s", c->expr, lanes, err.message);
    iacsg_renderer_destroy(r);
    return ok;
}

/* The segment path: two regions of the union's pre-pass with a material that reflects and lets light through, and
 * a level set cut by two spheres (a surface: no union pre-pass). */
#define REGIONS                                                                                                        \
    "material glass = rgb(0.3, 0.5, 0.9) opacity 0.6 reflect 0.3\n"                                                    \
    "region cube = box(0.8, 0.8, 0.8) \\ sphere(1) : glass\nregion ball = move(sphere(0.6), 0.5, 0.5, 0.5)\n"
#define SURFACES                                                                                                       \
    "solid g = sin(4*x)*cos(4*y)+sin(4*y)*cos(4*z)+sin(4*z)*cos(4*x)\nsolid inner = sphere(0.5)\n"                  \
    "solid outer = sphere(1.3)\nsurface shell = g where inner > 0 & outer < 0\nregion core = inner\n"

static int same_floats(const float *a, const float *b, size_t n) {
    return (!a && !b) || (a && b && memcmp(a, b, n * sizeof(float)) == 0);
}

/* The segment path's frames: the same regions hit (ids), each hit within 2 eps of the other's (a surface's search
 * starts where its packet's block pass left it, so a hit may lie in another leaf of width eps: 3 pixels of icos.csg
 * at 512x512 by 1.3e-5), the normals within 1e-3, the colours (below) within 2/255; the counts are a packet's (its
 * tile pass's evaluations shared by its rays), so only the rays' number is compared. */
static void check_scene_frames(size_t k, const iacsg_frame *a, const iacsg_frame *b, size_t n, double eps) {
    long moved = 0, ids = 0;
    double worst = 0, normal = 0;
    for (size_t i = 0; i < n; i++) {
        ids += a->ids[i] != b->ids[i];
        if (isinf(a->depth[i]) || isinf(b->depth[i]))
            worst = a->depth[i] == b->depth[i] ? worst : INFINITY;
        else
            worst = fmax(worst, fabs((double)a->depth[i] - b->depth[i]));
        moved += a->depth[i] != b->depth[i];
        for (int c = 0; c < 3; c++)
            normal = fmax(normal, fabs((double)a->normal[3 * i + c] - b->normal[3 * i + c]));
    }
    test_note("case %zu: %ld of %zu depths moved, by at most %g; normals by %g", k, moved, n, worst, normal);
    CHECK(ids == 0 && worst <= 2 * eps && normal <= 1e-3 && a->rays == b->rays,
          "case %zu: %ld ids differ, depths by up to %g, normals by %g, %lld against %lld rays between 16 and 8 "
          "lanes",
          k, ids, worst, normal, a->rays, b->rays);
}

TEST(render_packet_widths_agree) {
    /* 75 x 100: a packet's width divides neither, so the right column's packets are cut */
    iacsg_view view = {.width = 75, .height = 100, .eps = 1e-5, .bounds = {-1.5, -1.5, -1.5, 1.5, 1.5, 1.5},
                       .camera = {.eye = {3, -4, 2}, .up = {0, 0, 1}, .fov = 40}};
    iacsg_effects fx = {.lights = {{IACSG_LIGHT_POINT, {2, -3, 4}, 0.9}}, .nlights = 1, .shadows = 1, .bounces = 1,
                        .reflect = 0.4, .transparency = 0.3, .aa = 4};
    /* (the sphere and torus in the default config is other tests' program too: one of its two builds is cached) */
    const packets_case cases[] = {
        {"min(sphere, torus)", {0}, 0, 1, 0},
        {"min(sphere, torus)", {0}, 1, 0, 0},
        {"min(sphere, torus)", {.fp64 = 1, .stats = 1}, 0, 0, 0},
        {"sin(4*x)*cos(4*y)+sin(4*y)*cos(4*z)+sin(4*z)*cos(4*x)", {.tape = IACSG_TAPE_ALWAYS, .stats = 1}, 0, 0, 0},
        {REGIONS, {.stats = 1}, 0, 0, 1},
        {REGIONS, {0}, 1, 0, 1},
        {SURFACES, {.stats = 1}, 0, 0, 1},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const packets_case *c = &cases[k];
        iacsg_view v = view;
        v.effects = c->effects ? &fx : NULL;
        v.rgb_bytes = c->bytes;
        iacsg_frame f16, f8;
        if (!render_with(c, "16", &v, &f16))
            continue;
        if (!render_with(c, "8", &v, &f8)) {
            iacsg_frame_free(&f16);
            continue;
        }
        size_t n = (size_t)v.width * (size_t)v.height;
        if (c->scene)
            check_scene_frames(k, &f16, &f8, n, v.eps);
        else {
            CHECK(same_floats(f16.depth, f8.depth, n) && same_floats(f16.normal, f8.normal, 3 * n) &&
                      same_floats(f16.ids, f8.ids, n),
                  "case %zu (%s): the AOVs differ between 16 and 8 lanes", k, c->expr);
            CHECK(f16.rays == f8.rays && f16.evals_mean == f8.evals_mean && f16.evals_max == f8.evals_max,
                  "case %zu: %lld rays, %.6f evaluations a ray (max %u) with 16 lanes; %lld, %.6f (%u) with 8", k,
                  f16.rays, f16.evals_mean, f16.evals_max, f8.rays, f8.evals_mean, f8.evals_max);
        }
        if (c->bytes)
            CHECK(f16.rgb8 && f8.rgb8 && memcmp(f16.rgb8, f8.rgb8, 3 * n) == 0,
                  "case %zu: the 8-bit colours differ between 16 and 8 lanes", k);
        else if (!c->effects && !c->scene)
            CHECK(same_floats(f16.rgb, f8.rgb, 3 * n), "case %zu: the colours differ between 16 and 8 lanes", k);
        else {
            long moved = 0;
            float worst = 0;
            for (size_t i = 0; i < 3 * n; i++) {
                float d = fabsf(f16.rgb[i] - f8.rgb[i]);
                moved += d > 0;
                worst = fmaxf(worst, d);
            }
            test_note("case %zu: %ld of %zu colour values moved, by at most %.4f", k, moved, 3 * n, worst);
            CHECK(worst <= 2.0f / 255, "case %zu: %ld colour values moved, by up to %g", k, moved, worst);
        }
        iacsg_frame_free(&f16);
        iacsg_frame_free(&f8);
    }
}
