/* tests/t_render_effects_fp.c -- the ray-tracing effects (src/render_effects.c) against exact geometry, in float
 * and double: every pixel's shadow state, a mirror's reflected silhouette, a transparent layer's composite, and
 * -aa's edges and interiors. The scenes are spheres and planes, whose hits, shadows and reflections are solved
 * exactly on the host for the device's own float rays (t_render_util.h). */
#include "t_render_util.h"
#include "iacsg.h"

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

/* Compiles expr and renders the view; failures end the test. */
static void render_expr(const char *expr, const iacsg_view *view, iacsg_frame *fr) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(expr, "<test>", &e, &err) == IACSG_OK, "%s: %s", expr, err.message);
    iacsg_render_config config = {.fp64 = FP64};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, &config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s: %s", expr, err.message);
    st = iacsg_render(r, view, fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s: %s", expr, err.message);
}

/* The same for a scene file's text (regions: the segment path). */
static void render_scene_text(const char *text, const iacsg_view *view, iacsg_frame *fr) {
    iacsg_error err = {0};
    iacsg_scene *s = NULL;
    CHECK(iacsg_scene_parse(text, "<test>", &s, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {.fp64 = FP64};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_scene(s, &config, &r, &err);
    iacsg_scene_destroy(s);
    CHECK(st == IACSG_OK, "%s", err.message);
    st = iacsg_render(r, view, fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s", err.message);
}

/* The view of the shadow and antialiasing scenes: the plane z = 0 and a sphere above it, seen from above. */
static iacsg_view ground_view(int size) {
    iacsg_view v = {.width = size, .height = size, .eps = 0x1p-14,
                    .camera = {.eye = {3.2, -2.4, 2.6}, .at = {0, 0, 0.2}, .up = {0, 0, 1}, .fov = 40},
                    .bounds = {-2, -2, -0.5, 2, 2, 1.5}};
    return v;
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The distance from c to the segment from p to q. */
static double segment_distance(const double c[3], const double p[3], const double q[3]) {
    double pq[3], pc[3];
    for (int k = 0; k < 3; k++) {
        pq[k] = q[k] - p[k];
        pc[k] = c[k] - p[k];
    }
    double s = fmin(fmax(dot(pc, pq) / dot(pq, pq), 0), 1), e2 = 0;
    for (int k = 0; k < 3; k++)
        e2 += (pc[k] - s * pq[k]) * (pc[k] - s * pq[k]);
    return sqrt(e2);
}

/* A sphere of radius 1/2 at (0, 0, 0.6) above the plane z = 0, lit by one point light: each pixel of the plane is
 * in shadow exactly where the segment from its point to the light passes through the sphere, and each pixel of
 * the sphere where its normal faces away from the light. A shadowed pixel has the ambient term alone, red
 * sqrt(0.8 * 0.1); a lit one more. Pixels within a margin of either boundary are left out: the hit point lies
 * up to a few eps before the surface and a shadow ray starts 4 eps + 4e-6 off it (src/render_effects.c). */
static const double shadow_light[3] = {0.8, 0.5, 2.5};

static iacsg_effects shadow_effects(void) {
    iacsg_effects fx = {.shadows = 1, .nlights = 1};
    fx.lights[0] = (iacsg_light){IACSG_LIGHT_POINT, {shadow_light[0], shadow_light[1], shadow_light[2]}, 0.9};
    return fx;
}

static void check_shadows(const iacsg_view view, iacsg_frame fr) {
    const double *light = shadow_light;
    sphere ball = {{0, 0, 0.6}, 0.5};
    ia_real p[PARAM_COUNT];
    view_params(&view, p);
    const double shadowed_red = sqrt(0.8 * 0.1), margin = 2e-3;
    long lit = 0, dark = 0, spared = 0, wrong = 0;
    for (int j = 0; j < view.height; j++)
        for (int i = 0; i < view.width; i++) {
            double o[3], d[3], t1, t2, hit[3];
            pixel_ray(p, &view, i, j, o, d);
            size_t px = (size_t)j * view.width + i;
            int on_ball = sphere_span(ball, o, d, &t1, &t2) && t1 > 0, shadow;
            double t = on_ball ? t1 : -o[2] / d[2], edge;
            if (!on_ball && !(d[2] < 0)) {
                CHECK(isinf(fr.depth[px]), "pixel (%d, %d) misses everything but has depth %g", i, j, fr.depth[px]);
                continue;
            }
            for (int k = 0; k < 3; k++)
                hit[k] = o[k] + t * d[k];
            if (fabs(hit[0]) > 1.99 || fabs(hit[1]) > 1.99) /* near the bounds' sides */
                continue;
            if (on_ball) {
                double n[3], l[3];
                for (int k = 0; k < 3; k++) {
                    n[k] = (hit[k] - ball.c[k]) / ball.r;
                    l[k] = light[k] - hit[k];
                }
                double nl = dot(n, l) / sqrt(dot(l, l));
                shadow = nl <= 0;
                edge = fabs(nl) / 10;
            } else {
                double dist = segment_distance(ball.c, hit, light);
                shadow = dist < ball.r;
                edge = fabs(dist - ball.r);
            }
            if (edge < margin) {
                spared++;
                continue;
            }
            int shown_dark = fr.rgb[3 * px] <= shadowed_red + 1e-3;
            if (shown_dark != shadow && wrong++ < 5)
                test_note("pixel (%d, %d) on the %s: %s, shown %s (red %.4f)", i, j, on_ball ? "ball" : "plane",
                          shadow ? "in shadow" : "lit", shown_dark ? "dark" : "lit", fr.rgb[3 * px]);
            lit += !shadow;
            dark += shadow;
        }
    iacsg_frame_free(&fr);
    CHECK(wrong == 0, "%ld pixels lit or shadowed wrongly", wrong);
    CHECK(lit > 10000 && dark > 1000, "too few pixels checked: %ld lit, %ld in shadow", lit, dark);
    test_note("%ld lit, %ld in shadow, all as the exact boundary says; %ld within %g of it not checked", lit, dark,
              spared, margin);
}

TEST_FP(effects_shadow_boundary) {
    iacsg_view view = ground_view(200);
    iacsg_effects fx = shadow_effects();
    view.effects = &fx;
    iacsg_frame fr;
    render_expr("min(move(sphere(0.5), 0, 0, 0.6), z)", &view, &fr);
    check_shadows(view, fr);
}

/* The same scene as two regions of the expression's colour: the segment path's shadow rays. */
TEST_FP(effects_shadow_boundary_regions) {
    iacsg_view view = ground_view(200);
    iacsg_effects fx = shadow_effects();
    view.effects = &fx;
    iacsg_frame fr;
    render_scene_text("material m = rgb(0.8, 0.52, 0.28)\nsolid ball = move(sphere(0.5), 0, 0, 0.6)\n"
                      "region b = ball : m\nregion g = z : m\n",
                      &view, &fr);
    check_shadows(view, fr);
}
