/* tests/t_render_effects_fp.c -- the ray-tracing effects (src/render_effects.c) against exact geometry, in float
 * and double: every pixel's shadow state, a mirror's reflected silhouette, a transparent layer's composite,
 * -aa's edges and interiors, and secondary rays traced alone against in a packet. The scenes are spheres and
 * planes, whose hits, shadows and reflections are solved exactly on the host for the device's own float rays
 * (t_render_util.h). */
#include "t_render_util.h"
#include "iacsg.h"
#include "kernels/effects.h"
#include "render_effects_trace.h" /* fx_trace: secondary rays traced alone or in packets */

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

/* Compiles expr and renders the view; failures end the test. */
static void render_expr(const char *expr, const iacsg_view *view, iacsg_frame *fr) {
    iacsg_render_config config = {.fp64 = FP64};
    render_expr_text(expr, &config, view, fr);
}

/* The same for a scene file's text (regions: the segment path). */
/* A scene's frame, its rays given room for `candidates` solids each (0: the default). */
static void render_scene_room(const char *text, const iacsg_view *view, int candidates, iacsg_frame *fr) {
    iacsg_error err = {0};
    iacsg_scene *s = NULL;
    CHECK(iacsg_scene_parse(text, "<test>", &s, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {.fp64 = FP64, .ray_candidates = candidates};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_scene(s, &config, &r, &err);
    iacsg_scene_destroy(s);
    CHECK(st == IACSG_OK, "%s", err.message);
    st = iacsg_render(r, view, fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s", err.message);
}

static void render_scene_text(const char *text, const iacsg_view *view, iacsg_frame *fr) {
    render_scene_room(text, view, 0, fr);
}

/* The view of the shadow and antialiasing scenes: the plane z = 0 and a sphere above it, seen from above. */
static iacsg_view ground_view(int size) {
    iacsg_view v = {.width = size, .height = size, .eps = 0x1p-14,
                    .camera = {.eye = {3.2, -2.4, 2.6}, .at = {0, 0, 0.2}, .up = {0, 0, 1}, .fov = 40},
                    .bounds = {-2, -2, -0.5, 2, 2, 1.5}};
    return v;
}

/* The orange ball above the ground of ground_view's scenes, the ground's material given as its `material g` line. */
static void render_ball_over_ground(const char *ground, const iacsg_view *view, iacsg_frame *fr) {
    char text[400];
    snprintf(text, sizeof text,
             "material m = rgb(0.8, 0.52, 0.28)\n%s\nsolid ball = move(sphere(0.5), 0, 0, 0.6)\n"
             "region b = ball : m\nregion f = z \\ ball : g\n",
             ground);
    render_scene_text(text, view, fr);
}

/* The largest difference between pixel px's colour channels in two frames. */
static double colour_difference(const iacsg_frame *a, const iacsg_frame *b, long px) {
    double most = 0;
    for (int c = 0; c < 3; c++)
        most = fmax(most, fabs(a->rgb[3 * px + c] - b->rgb[3 * px + c]));
    return most;
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

/* The same with the ball as a distance, sqrt(x^2 + y^2 + (z - 0.6)^2) - 0.5, whose derivative is unbounded at its
 * centre: a shadow ray whose steps' boxes hold the centre has no bounded F' there, and must go on by bisection
 * (kernels/effects.cl: effects_march) rather than be taken for a miss. */
TEST_FP(effects_shadow_boundary_distance) {
    iacsg_view view = ground_view(200);
    iacsg_effects fx = shadow_effects();
    view.effects = &fx;
    iacsg_frame fr;
    render_expr("min(sqrt(x^2 + y^2 + (z - 0.6)^2) - 0.5, z)", &view, &fr);
    check_shadows(view, fr);
}

/* The ground of the shadow scene under a ball that lets `fraction` of the light through (`hollow_fraction` where
 * the light's way also passes through a hollow of radius `hollow` in it, 0: none): a pixel of the ground is
 * `opacity` of its lit colour (the expression's clay albedo, the light times the fraction that reaches it) and
 * 1 - opacity of the background (the default gradient at its row, kernels/light.h), in linear light. Pixels
 * within 2e-3 of the shadow's edges, or whose ray meets the ball, are left out. */
static void check_ground_light(const iacsg_view view, iacsg_frame fr, double opacity, double fraction, double hollow,
                               double hollow_fraction) {
    sphere ball = {{0, 0, 0.6}, 0.5};
    ia_real p[PARAM_COUNT];
    view_params(&view, p);
    const double a = opacity, *light = shadow_light;
    long lit = 0, dark = 0, bad = 0, through_hollow = 0;
    double worst = 0;
    static const double top[3] = {0.42f, 0.46f, 0.52f}, bottom[3] = {0.13f, 0.14f, 0.17f};
    static const double albedo[3] = {0.80f, 0.52f, 0.28f};
    for (int j = 0; j < view.height; j++) {
        for (int i = 0; i < view.width; i++) {
            double o[3], d[3], t1, t2, hit[3], l[3], h[3];
            pixel_ray(p, &view, i, j, o, d);
            if (sphere_span(ball, o, d, &t1, &t2) || !(d[2] < 0))
                continue;
            double t = -o[2] / d[2];
            for (int k = 0; k < 3; k++) {
                hit[k] = o[k] + t * d[k];
                l[k] = light[k] - hit[k];
            }
            double dist = segment_distance(ball.c, hit, light), edge = dist - ball.r;
            if (fabs(hit[0]) > 1.99 || fabs(hit[1]) > 1.99 || fabs(edge) < 2e-3 ||
                (hollow > 0 && fabs(dist - hollow) < 2e-3))
                continue;
            double len = sqrt(dot(l, l)), T = dist < hollow ? hollow_fraction : edge < 0 ? fraction : 1;
            for (int k = 0; k < 3; k++) {
                l[k] /= len;
                h[k] = l[k] - d[k];
            }
            double nl = l[2], nh = h[2] / sqrt(dot(h, h));
            size_t px = (size_t)j * view.width + i;
            for (int c = 0; c < 3; c++) {
                double lin = albedo[c] * (0.1 + 0.9 * nl * T) + 0.45 * 0.9 * pow(nh, 48) * T;
                double shown_bg = top[c] + (bottom[c] - top[c]) * j / (view.height - 1);
                double want = sqrt(fmin(a * lin + (1 - a) * shown_bg * shown_bg, 1)); /* clipped at 1 */
                double off = fabs(fr.rgb[3 * px + c] - want);
                if (off > 1e-4 && c == 0 && bad++ < 5)
                    test_note("pixel (%d, %d), %s: red %.4f, want %.4f", i, j, T < 1 ? "in the shadow" : "lit",
                              fr.rgb[3 * px], want);
                worst = fmax(worst, off);
            }
            lit += T == 1;
            dark += T < 1;
            through_hollow += dist < hollow;
        }
    }
    iacsg_frame_free(&fr);
    CHECK(worst <= 1e-4, "a pixel of the ground is %g off its colour under the light that reaches it", worst);
    CHECK(lit > 5000 && dark > 500, "too few pixels: %ld lit, %ld in the shadow", lit, dark);
    CHECK(hollow == 0 || through_hollow > 500, "only %ld pixels lit through the hollow", through_hollow);
    test_note("%ld pixels lit, %ld in the shadow of the transparent ball (%g of the light), within %.1e", lit, dark,
              fraction, worst);
    if (hollow > 0)
        test_note("%ld of them lit through its hollow (%g of the light)", through_hollow, hollow_fraction);
}

/* The shadow scene with -opacity 0.6: the ball lets (1 - 0.6)^2 of the light through (a shadow ray crosses its
 * surface twice); the ground, the solid z < 0, is one layer where the camera ray enters it (the ray leaves the
 * bounds inside it). */
TEST_FP(effects_shadow_through_transparent) {
    iacsg_view view = ground_view(160);
    iacsg_effects fx = shadow_effects();
    fx.transparency = 0.4; /* opacity 0.6 */
    view.effects = &fx;
    iacsg_frame fr;
    render_expr("min(move(sphere(0.5), 0, 0, 0.6), z)", &view, &fr);
    check_ground_light(view, fr, 0.6, 0.4 * 0.4, 0, 0);
}

/* The same ball hollow, a shell 0.04 thick: a shadow ray through the hollow crosses four surfaces, each within
 * 0.04 of the one before (kernels/effects.cl: the shadow ray goes on past a proven crossing along its line; a
 * crossing's step taken past the next surface shows as light let through twice, not four times). */
TEST_FP(effects_shadow_through_transparent_shell) {
    iacsg_view view = ground_view(160);
    iacsg_effects fx = shadow_effects();
    fx.transparency = 0.4;
    view.effects = &fx;
    iacsg_frame fr;
    render_expr("min(max(x^2 + y^2 + (z - 0.6)^2 - 0.25, 0.2116 - x^2 - y^2 - (z - 0.6)^2), z)", &view, &fr);
    check_ground_light(view, fr, 0.6, 0.4 * 0.4, 0.46, 0.4 * 0.4 * 0.4 * 0.4);
}

/* The same as regions: a ball of opacity 0.6, a volume that a shadow ray enters once, lets 0.4 of the light
 * through onto the opaque ground. */
TEST_FP(effects_shadow_through_transparent_region) {
    iacsg_view view = ground_view(160);
    iacsg_effects fx = shadow_effects();
    view.effects = &fx;
    iacsg_frame fr;
    render_scene_text("material glass = rgb(0.3, 0.6, 0.9) opacity 0.6\nmaterial clay = rgb(0.8, 0.52, 0.28)\n"
                      "region ball = move(sphere(0.5), 0, 0, 0.6) : glass\nregion ground = z : clay\n",
                      &view, &fr);
    check_ground_light(view, fr, 1, 0.4, 0, 0);
}

/* The shadows' check on a scene file of the same ball above the ground (the segment path's shadow rays). */
static void check_scene_shadows(const char *scene) {
    iacsg_view view = ground_view(200);
    iacsg_effects fx = shadow_effects();
    view.effects = &fx;
    iacsg_frame fr;
    render_scene_text(scene, &view, &fr);
    check_shadows(view, fr);
}

/* The same scene as two regions of the expression's colour. */
TEST_FP(effects_shadow_boundary_regions) {
    check_scene_shadows("material m = rgb(0.8, 0.52, 0.28)\nsolid ball = move(sphere(0.5), 0, 0, 0.6)\n"
                        "region b = ball : m\nregion g = z : m\n");
}

/* The same as disjoint regions (the ground less the ball): the shadow rays' packets find the regions' union's first
 * root in SIMD lanes, marching off the surface they leave (kernels/scene_effects.cl, march.h: effects_march with
 * the union's derivative), and end on a proven crossing (every item opaque). */
TEST_FP(effects_shadow_boundary_disjoint) {
    check_scene_shadows("material m = rgb(0.8, 0.52, 0.28)\nsolid ball = move(sphere(0.5), 0, 0, 0.6)\n"
                        "region b = ball : m\nregion g = z \\ ball : m\n");
}

/* A secondary ray's march (kernels/march.h: effects_march, which skips the failed steps' work in packet steps
 * where every lane's step held) does not depend on the rays beside it in its packet: 16 rays off the ball of the
 * disjoint regions above, half up and away (their steps hold), half down to the ground or grazing the ball (their
 * steps fail, shrink or cross the ground), traced in one packet and each alone, give the same hits and as many
 * evaluations. Skipping either part of that work where only some lanes held fails it. */
TEST_FP(effects_march_lanes_alone) {
    iacsg_error err = {0};
    iacsg_scene *s = NULL;
    CHECK(iacsg_scene_parse("material m = rgb(0.8, 0.52, 0.28)\nsolid ball = move(sphere(0.5), 0, 0, 0.6)\n"
                            "region b = ball : m\nregion g = z \\ ball : m\n",
                            "<test>", &s, &err) == IACSG_OK,
          "%s", err.message);
    iacsg_render_config config = {.fp64 = FP64, .stats = 1};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_scene(s, &config, &r, &err);
    iacsg_scene_destroy(s);
    CHECK(st == IACSG_OK, "%s", err.message);
    iacsg_view view = ground_view(32);
    iacsg_frame fr = {0};
    st = iacsg_render(r, &view, &fr, &err); /* the frame's scene data, which the trace kernel reads */
    fx_tracer t;
    if (st == IACSG_OK)
        st = fx_tracer_open(&t, r, &view, &err);
    CHECK(st == IACSG_OK, "%s", err.message);
    fx_ray rays[16];
    for (int k = 0; k < 16; k++) { /* from 1e-3 off the ball, around it (every 2 pi / 16) */
        double a = 0.39269908169872414 * k, u[3] = {cos(a) * 0.8, sin(a) * 0.8, k % 2 ? 0.6 : -0.6};
        double len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        /* up and away; steeply down to the ground or along the ball; or down a long way (its first step holds,
         * the next crosses the ground while the rays going up hold theirs) */
        double up = k % 2 ? 1 : k % 4 ? -0.2 : -0.9;
        double d[3] = {u[0] / len + 0.3 * (k % 3), u[1] / len, up};
        double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int c = 0; c < 3; c++) {
            rays[k].o[c] = (c == 2 ? 0.6 : 0) + 0.501 * u[c] / len;
            rays[k].d[c] = d[c] / dl;
        }
        rays[k].tn = 0;
        rays[k].tf = 100;
        rays[k].passing = 0;
    }
    fx_hit together[16], alone, alone_differ = {0};
    st = fx_trace(&t, rays, 16, view.eps, 0, together, &err);
    double packet_evals = t.evals, lone_evals = 0;
    int hits = 0, differ = -1;
    for (int k = 0; k < 16 && st == IACSG_OK; k++) {
        double before = t.evals;
        st = fx_trace(&t, &rays[k], 1, view.eps, 0, &alone, &err);
        lone_evals += t.evals - before;
        hits += together[k].item >= 0;
        if (differ < 0 && (alone.t != together[k].t || alone.item != together[k].item)) {
            differ = k;
            alone_differ = alone;
        }
    }
    fx_tracer_close(&t);
    iacsg_frame_free(&fr);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s", err.message);
    CHECK(differ < 0, "ray %d: alone t %.17g item %d, in the packet t %.17g item %d", differ, alone_differ.t,
          alone_differ.item, together[differ < 0 ? 0 : differ].t, together[differ < 0 ? 0 : differ].item);
    CHECK(hits >= 4 && hits <= 12, "%d of the 16 rays hit: not a mixed packet", hits);
    CHECK(lone_evals == packet_evals, "evaluations: %.0f alone, %.0f in one packet", lone_evals, packet_evals);
}

/* The same with the ground's function z (2 + cos x), the same solid and normals, whose cosine leaves the union
 * without derivative code: the march by F's enclosure alone (march.h: march_enclosure). */
TEST_FP(effects_shadow_boundary_disjoint_enclosure) {
    check_scene_shadows("material m = rgb(0.8, 0.52, 0.28)\nsolid ball = move(sphere(0.5), 0, 0, 0.6)\n"
                        "solid ground = z * (2 + cos(x))\nregion b = ball : m\nregion g = ground \\ ball : m\n");
}

/* The segment path's centre paths, kept on the device where none can have a child (every item opaque, no reflected
 * ray: kernels/scene_centre.cl), against the host's paths of the same scene with its ground of opacity 1 - 1e-6
 * (a child-bearing material, so the host lists every path; its colour and its shadows' within 1e-5 of the opaque
 * one's): lit by a point and a dir light, with shadows, and with -background (its misses go through the paths
 * too). A pixel may differ by the shading point's rounding (the device's float ray against the host's double one)
 * or, on a shadow's boundary, by a flip: at most 1 % of them by more than 2e-3. */
TEST_FP(effects_scene_centre_on_device) {
    static const char *ground[2] = {"material g = rgb(0.7, 0.7, 0.68)",
                                    "material g = rgb(0.7, 0.7, 0.68) opacity 0.999999"};
    iacsg_effects fx = shadow_effects();
    fx.nlights = 2;
    fx.lights[1] = (iacsg_light){IACSG_LIGHT_DIR, {1, 0.5, 2}, 0.3};
    fx.background = 1;
    fx.background_top[0] = 1, fx.background_bottom[2] = 1;
    iacsg_frame fr[2];
    iacsg_view view = ground_view(96);
    view.effects = &fx;
    for (int k = 0; k < 2; k++)
        render_ball_over_ground(ground[k], &view, &fr[k]);
    long n = (long)view.width * view.height, off = 0, dark = 0, lit = 0;
    for (long px = 0; px < n; px++) {
        off += colour_difference(&fr[0], &fr[1], px) > 2e-3;
        dark += fr[0].ids[px] == 1 && fr[0].rgb[3 * px] < 0.35;
        lit += fr[0].ids[px] == 1 && fr[0].rgb[3 * px] > 0.5;
    }
    iacsg_frame_free(&fr[0]);
    iacsg_frame_free(&fr[1]);
    CHECK(dark > 100 && lit > 100, "%ld shadowed and %ld lit ground pixels: the view does not test both", dark, lit);
    CHECK(off <= n / 100, "%ld of %ld pixels differ from the host's paths by more than 2e-3", off, n);
}

/* Fails unless the frames of `scene` with `fx` given room for one solid a ray (then some secondary rays overflow:
 * more pixels are traced again than without the effects) and with the default room are the same: colours,
 * depths and ids. */
static void check_secondary_overflow(const char *scene, const iacsg_effects *fx, const char *what) {
    iacsg_view view = ground_view(96);
    iacsg_frame fr[3];
    for (int k = 0; k < 3; k++) {
        view.effects = k < 2 ? fx : NULL;
        render_scene_room(scene, &view, k == 0 ? 0 : 1, &fr[k]);
    }
    long n = (long)view.width * view.height, off = 0;
    for (long px = 0; px < n; px++)
        off += colour_difference(&fr[0], &fr[1], px) > 0 || fr[0].depth[px] != fr[1].depth[px] ||
               fr[0].ids[px] != fr[1].ids[px];
    long long again = fr[1].retraced_rays, camera_again = fr[2].retraced_rays;
    for (int k = 0; k < 3; k++)
        iacsg_frame_free(&fr[k]);
    CHECK(again > camera_again, "%lld rays traced again with %s, %lld without: none of them overflowed", again, what,
          camera_again);
    CHECK(off == 0, "%ld of %ld pixels differ from the frame with room for every solid", off, n);
    test_note("%lld pixels traced again with %s, %lld without", again, what, camera_again);
}

/* The camera kernel's secondary rays (kernels/scene_lit.h: scene_packet_lit) use its work-item's per-ray
 * buffers: a pixel whose shadow ray or reflected ray meets more solids' boxes than they hold is traced again with
 * more room, as a camera ray that overflows. With room for one solid a ray, the ground's pixels whose shadow rays,
 * or reflected rays, pass the boxes of the ball and the cap that overlaps it (regions not disjoint: each ray is
 * woven) overflow, and the frame is the one with the default room. Dropping the listing of either kind of ray that
 * overflows fails it. */
TEST_FP(effects_scene_secondary_rays_overflow) {
    static const char *scene = "material m = rgb(0.8, 0.52, 0.28)\nmaterial g = rgb(0.7, 0.7, 0.68) reflect 0.5\n"
                               "solid ball = move(sphere(0.5), 0, 0, 0.6)\nsolid cap = move(sphere(0.3), 0.2, 0, 0.9)\n"
                               "region b = ball : m\nregion c = cap : m\nregion ground = z : %s\n";
    char text[400];
    iacsg_effects fx = shadow_effects();
    snprintf(text, sizeof text, scene, "m");
    check_secondary_overflow(text, &fx, "shadow rays");
    fx.shadows = 0;
    fx.bounces = 1;
    snprintf(text, sizeof text, scene, "g");
    check_secondary_overflow(text, &fx, "reflected rays");
}

/* A reflecting ground's one bounce, its children leaves (every item opaque, no shadows), kept on the device
 * (kernels/scene_centre.cl makes the reflected rays, fx_scene_centre traces and shades them) against the host's
 * paths of the same scene with the ground of opacity 1 - 1e-6 (its transmitted rays' weight is under
 * EFFECTS_MIN_WEIGHT: a colour within 1e-5): the ball is seen in the ground, the sky elsewhere. A pixel may differ
 * by a reflected ray's rounding (from the device's float ray): at most 0.25 % of them by more than 2e-3 (the
 * ball's image is 1.7 %); and the reflection must show (against the render without a bounce). */
TEST_FP(effects_scene_reflect_on_device) {
    static const char *ground[3] = {"material g = rgb(0.7, 0.7, 0.68) reflect 0.5",
                                    "material g = rgb(0.7, 0.7, 0.68) reflect 0.5 opacity 0.999999",
                                    "material g = rgb(0.7, 0.7, 0.68) reflect 0.5"};
    iacsg_frame fr[3];
    iacsg_view view = ground_view(96);
    view.camera.eye[2] = 0.9; /* lower: the ball's image in the ground shows beside it */
    for (int k = 0; k < 3; k++) {
        iacsg_effects fx = {.bounces = k < 2, .nlights = 1};
        fx.lights[0] = (iacsg_light){IACSG_LIGHT_POINT, {shadow_light[0], shadow_light[1], shadow_light[2]}, 0.9};
        view.effects = &fx;
        render_ball_over_ground(ground[k], &view, &fr[k]);
    }
    long n = (long)view.width * view.height, off = 0, shown = 0, ball = 0;
    for (long px = 0; px < n; px++) {
        off += colour_difference(&fr[0], &fr[1], px) > 2e-3;
        shown += fr[0].ids[px] == 1 && colour_difference(&fr[0], &fr[2], px) > 0.02;
        ball += fr[0].ids[px] == 1 && fr[0].rgb[3 * px] > fr[0].rgb[3 * px + 2] + 0.05; /* the ball's orange in it */
    }
    for (int k = 0; k < 3; k++)
        iacsg_frame_free(&fr[k]);
    CHECK(shown > n / 4 && ball > n / 100, "%ld ground pixels reflect, %ld show the ball: the view does not test it",
          shown, ball);
    CHECK(off <= n / 400, "%ld of %ld pixels differ from the host's paths by more than 2e-3", off, n);
    test_note("%ld ground pixels reflect, %ld of them the ball; %ld pixels off the host's", shown, ball, off);
}

/* Transparency on the device: a glass ball under a glass lid over a ground that lets light through too, without
 * shadows and with them (the ball's shadow is cast through the lid too). The centre paths and their layers, through
 * the glass and into the ground, and their shadow rays through the lid and the ball, are the camera kernel's (kernels/scene_lit.h: scene_lanes_layers, scene_lanes_transmitted); against the
 * host's paths of the same scene, made to take them by a reflecting region outside the bounds (a material that
 * reflects with -bounces beside one that lets light through: the host's). At most 0.25 % of the pixels may differ
 * by more than 2e-3 (a layer ray's start from the device's float hit), and the glass must show. */
static void check_scene_glass(int shadows) {
    static const char *far[2] = {"", "region far = move(sphere(0.1), 0, 0, 9) : shiny\n"};
    iacsg_frame fr[3];
    iacsg_view view = ground_view(96);
    iacsg_effects fx = {.bounces = 1, .nlights = 1, .shadows = shadows};
    fx.lights[0] = (iacsg_light){IACSG_LIGHT_POINT, {shadow_light[0], shadow_light[1], shadow_light[2]}, 0.9};
    view.effects = &fx;
    for (int k = 0; k < 3; k++) {
        char text[600];
        snprintf(text, sizeof text,
                 "material glass = rgb(0.3, 0.6, 0.9) opacity %s\nmaterial clay = rgb(0.8, 0.52, 0.28) opacity 0.7\n"
                 "material shiny = rgb(0.5, 0.5, 0.5) reflect 0.5\nsolid ball = move(sphere(0.5), 0, 0, 0.6)\n"
                 "region b = ball : glass\nregion g = z \\ ball : clay\n"
                 "region lid = move(box(0.6, 0.6, 0.04), 0.3, 0.2, 1.3) : glass\n%s",
                 k < 2 ? "0.4" : "1", far[k == 1]);
        render_scene_text(text, &view, &fr[k]);
    }
    long n = (long)view.width * view.height, off = 0, shown = 0;
    for (long px = 0; px < n; px++) {
        off += colour_difference(&fr[0], &fr[1], px) > 2e-3;
        shown += fr[0].ids[px] == 0 && colour_difference(&fr[0], &fr[2], px) > 0.02;
    }
    for (int k = 0; k < 3; k++)
        iacsg_frame_free(&fr[k]);
    CHECK(shown > n / 20, "%ld ball pixels show what is behind: the view does not test it", shown);
    CHECK(off <= n / 400, "%ld of %ld pixels differ from the host's paths by more than 2e-3", off, n);
    test_note("%s: %ld ball pixels show what is behind; %ld pixels off the host's", shadows ? "shadows" : "no shadows",
              shown, off);
}

TEST_FP(effects_scene_glass_on_device) {
    check_scene_glass(0);
    check_scene_glass(1);
}

/* The unit sphere seen along -z, orthographic: the point (s, v) of the image plane is on it iff s^2 + v^2 < 1. */
static iacsg_view sphere_ortho_view(int size) {
    iacsg_view v = {.width = size, .height = size, .eps = 0x1p-14,
                    .camera = {.eye = {0, 0, 4}, .at = {0, 0, 0}, .up = {0, 1, 0}, .fov = 40, .ortho_height = 2.6},
                    .bounds = {-1.5, -1.5, -1.5, 1.5, 1.5, 1.5}};
    return v;
}

/* The fraction of pixel (i, j) of sphere_ortho_view covered by the sphere, sampled on a 32 x 32 grid. */
static double sphere_coverage(const iacsg_view *v, int i, int j) {
    double half = v->camera.ortho_height / 2, in = 0;
    for (int b = 0; b < 32; b++)
        for (int a = 0; a < 32; a++) {
            double s = (2 * (i + (a + 0.5) / 32) / v->width - 1) * half;
            double t = (1 - 2 * (j + (b + 0.5) / 32) / v->height) * half;
            in += s * s + t * t < 1;
        }
    return in / (32 * 32);
}

/* -aa 4 on a sphere: pixels well inside or outside it (their 3 x 3 neighbourhood all in or all out) keep the
 * plain render's colour; a pixel a quarter to three quarters covered, next to one wholly covered (colour S) and
 * one wholly outside (B), takes the blend sqrt(c S^2 + (1 - c) B^2) of its coverage c (linear light, gamma 2),
 * within what 4 x 4 rays and the shading's change over a pixel allow. (Where the shading itself changes fast,
 * in the highlight, neighbours differ by more than -aa's contrast threshold, so those pixels are sampled too.) */
static void check_aa_edges(void (*render)(const char *, const iacsg_view *, iacsg_frame *), const char *text) {
    iacsg_view view = sphere_ortho_view(96);
    iacsg_frame plain, aa;
    render(text, &view, &plain);
    iacsg_effects fx = {.aa = 4};
    view.effects = &fx;
    render(text, &view, &aa);
    long inside = 0, same = 0, edges = 0, bad = 0;
    double worst = 0, worst_edge = 0;
    for (int j = 1; j + 1 < view.height; j++)
        for (int i = 1; i + 1 < view.width; i++) {
            size_t px = (size_t)j * view.width + i, full = 0, empty = 0;
            double c = sphere_coverage(&view, i, j);
            int uniform = 1;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++) {
                    double cn = sphere_coverage(&view, i + di, j + dj);
                    uniform &= (cn == 0 && c == 0) || (cn == 1 && c == 1);
                    size_t n = px + (size_t)(dj * view.width + di);
                    full = cn == 1 ? n : full;
                    empty = cn == 0 ? n : empty;
                }
            if (uniform) {
                double diff = 0;
                for (int k = 0; k < 3; k++)
                    diff = fmax(diff, fabs(aa.rgb[3 * px + k] - plain.rgb[3 * px + k]));
                worst = fmax(worst, diff);
                same += diff <= 1e-5;
                inside++;
                continue;
            }
            if (!(c >= 0.25 && c <= 0.75) || !full || !empty)
                continue;
            double off = 0;
            for (int k = 0; k < 3; k++) {
                double S = plain.rgb[3 * full + k], B = plain.rgb[3 * empty + k];
                off = fmax(off, fabs(aa.rgb[3 * px + k] - sqrt(c * S * S + (1 - c) * B * B)));
            }
            worst_edge = fmax(worst_edge, off);
            if (off > 0.06 && bad++ < 5)
                test_note("edge pixel (%d, %d), %.2f covered: colour %.3f %.3f %.3f, %.3f off the blend", i, j, c,
                          aa.rgb[3 * px], aa.rgb[3 * px + 1], aa.rgb[3 * px + 2], off);
            edges++;
        }
    iacsg_frame_free(&plain);
    iacsg_frame_free(&aa);
    CHECK(bad == 0, "%ld of %ld edge pixels off the blend of their coverage", bad, edges);
    CHECK(same >= inside - inside / 20, "only %ld of %ld interior pixels have the plain render's colour", same, inside);
    CHECK(worst <= 1.0 / 128, "an interior pixel differs from the plain render by %g", worst);
    CHECK(inside > 4000 && edges > 50, "too few pixels: %ld interior, %ld edges", inside, edges);
    test_note("%ld of %ld interior pixels have the plain render's colour (the others, in the highlight, where "
              "neighbours differ by 1/16, were sampled too: within %.1e); %ld edge pixels within %.3f of the blend "
              "of their coverage", same, inside, worst, edges, worst_edge);
}

TEST_FP(effects_aa_edges) { check_aa_edges(render_expr, "sphere"); }

/* render_expr with -aa's walks in rounds of 2 turns (iacsg_render_config.aa_turns; src/render_effects_device.c):
 * nearly every sample goes on from where the last round left it, some four times. */
static void render_expr_short_rounds(const char *expr, const iacsg_view *view, iacsg_frame *fr) {
    iacsg_render_config config = {.fp64 = FP64, .aa_turns = 2};
    render_expr_text(expr, &config, view, fr);
}

/* The blends of the edges' coverage with the samples' walks in short rounds: the sphere, with interval Newton,
 * whose steps a walk that goes on starts again from their node; and as (x^2 + y^2 + z^2)^0.75 - 1, whose pow has
 * no derivative code (bisection alone). */
TEST_FP(effects_aa_edges_in_rounds) {
    check_aa_edges(render_expr_short_rounds, "sphere");
    check_aa_edges(render_expr_short_rounds, "(x^2 + y^2 + z^2)^0.75 - 1");
}

/* Bisection alone (no Newton's steps to start again) takes the same nodes in rounds as in one walk: the same
 * -aa 4 image, bit for bit, with rounds of 2 turns and of FX_AA_TURNS; and with shadows and a reflection, whose
 * rays go in packets of the paths in their order after the rounds (in the rounds' order, the order of their
 * atomic lists, they changed from run to run). */
TEST_FP(effects_aa_rounds_same_image) {
    iacsg_view view = ground_view(96);
    iacsg_effects plain = {.aa = 4}, lit = shadow_effects();
    lit.aa = 4;
    lit.bounces = 1;
    lit.reflect = 0.3;
    const iacsg_effects *fx[2] = {&plain, &lit};
    const char *text = "min((x^2 + y^2 + (z - 0.6)^2)^0.75 - 0.5^1.5, z)";
    for (int k = 0; k < 2; k++) {
        view.effects = fx[k];
        iacsg_frame whole, rounds;
        render_expr(text, &view, &whole);
        render_expr_short_rounds(text, &view, &rounds);
        size_t n = (size_t)view.width * view.height;
        long differ = 0;
        for (size_t px = 0; px < n; px++)
            differ += memcmp(whole.rgb + 3 * px, rounds.rgb + 3 * px, 3 * sizeof(float)) != 0;
        iacsg_frame_free(&whole);
        iacsg_frame_free(&rounds);
        CHECK(differ == 0, "%s: %ld pixels differ between walks in rounds of 2 turns and of the default",
              k ? "shadows and a reflection" : "plain", differ);
    }
}

/* An expression's -aa N from N = 3 traces a pixel's corners, then the rest (kernels/effects.h): together every
 * cell of the N x N grid exactly once, the corners the grid's four. */
TEST_FP(effects_aa_corners_then_rest_cover_the_grid) {
    for (int aa = 3; aa <= 16; aa++) {
        int seen[256] = {0};
        for (int set = EFFECTS_AA_CORNERS; set <= EFFECTS_AA_REST; set++)
            for (int s = 0; s < effects_aa_rays(aa, set); s++) {
                int cell = effects_aa_cell(aa, set, s), a = cell % aa, b = cell / aa;
                CHECK(cell >= 0 && cell < aa * aa, "aa %d, set %d, ray %d: cell %d outside the grid", aa, set, s, cell);
                int corner = (a == 0 || a == aa - 1) && (b == 0 || b == aa - 1);
                CHECK(corner == (set == EFFECTS_AA_CORNERS), "aa %d, set %d, ray %d: cell (%d, %d)", aa, set, s, a,
                      b);
                seen[cell]++;
            }
        for (int cell = 0; cell < aa * aa; cell++)
            CHECK(seen[cell] == 1, "aa %d: cell %d traced %d times", aa, cell, seen[cell]);
    }
}

/* The same as a region: the segment path's samples, traced as packets of the camera kernel's (4 x 4 samples of a
 * pixel, one packet). */
TEST_FP(effects_aa_edges_regions) { check_aa_edges(render_scene_text, "region ball = sphere\n"); }

/* -aa's samples start where the frame's tile pass left their tile's rays only when they lie inside the box of its
 * pixels' centre rays (kernels/effects.cl: effects_trace_samples). A box whose left and top faces pass a tenth of a
 * pixel inside pixels column 7 and row 7, past their centres (64x64, tiles of 8): the tiles left of and above it
 * are proven empty over their centre rays, yet half of those pixels' samples meet the box. Each such pixel is the
 * blend of its coverage, 1/2, between the box's colour and its own background (not the corner pixel (7, 7): no
 * neighbour across a side differs from it, so -aa's edge test passes it over). */
TEST_FP(effects_aa_samples_past_their_tile) {
    iacsg_view view = sphere_ortho_view(64);
    double half = view.camera.ortho_height / 2, edge = (15.1 / 64 - 1) * half; /* doubled column and row 15.1 */
    char text[256];
    snprintf(text, sizeof text, "max(%.17g - x, x - 1, y - %.17g, -1 - y, abs(z) - 0.5)", edge, -edge);
    iacsg_frame plain, aa;
    render_expr(text, &view, &plain);
    iacsg_effects fx = {.aa = 4};
    view.effects = &fx;
    render_expr(text, &view, &aa);
    long checked = 0;
    double worst = 0;
    for (int k = 8; k < 40; k++)
        for (int side = 0; side < 2; side++) { /* pixel (7, k), then (k, 7), and their neighbours inside the box */
            int i = side ? k : 7, j = side ? 7 : k;
            size_t px = (size_t)j * view.width + i, in = px + (side ? (size_t)view.width : 1);
            CHECK(isinf(plain.depth[px]) && isfinite(plain.depth[in]), "pixel (%d, %d) should miss the box, its "
                  "neighbour inside hit it", i, j);
            for (int ch = 0; ch < 3; ch++) {
                double S = plain.rgb[3 * in + ch], B = plain.rgb[3 * px + ch];
                worst = fmax(worst, fabs(aa.rgb[3 * px + ch] - sqrt(0.5 * S * S + 0.5 * B * B)));
            }
            checked++;
        }
    iacsg_frame_free(&plain);
    iacsg_frame_free(&aa);
    CHECK(worst <= 1e-4, "a pixel is %g off the blend of its coverage", worst);
    test_note("%ld pixels past their tiles' centre rays within %.1e of the blend of their coverage", checked, worst);
}

/* The colour's linear light (gamma 2, kernels/light.h). */
static double linear(float shown) { return (double)shown * shown; }

/* A sphere that reflects half the light, one bounce: its reflected rays leave it for good (it is convex), so each
 * of its pixels is half its plain colour and half the background of its row, in linear light (but in the
 * highlight, where the plain render clips the light at 1 and the blend takes it whole). */
TEST_FP(effects_reflect_sphere) {
    iacsg_view view = sphere_ortho_view(96);
    iacsg_frame plain, mirror;
    render_expr("sphere", &view, &plain);
    iacsg_effects fx = {.bounces = 1, .reflect = 0.5};
    view.effects = &fx;
    render_expr("sphere", &view, &mirror);
    long checked = 0;
    double worst = 0;
    for (int j = 0; j < view.height; j++)
        for (int i = 1; i < view.width; i++) {
            size_t px = (size_t)j * view.width + i, bg = (size_t)j * view.width; /* column 0 misses */
            double c = sphere_coverage(&view, i, j);
            int saturated = plain.rgb[3 * px] >= 1; /* the highlight, whose light past 1 the plain render clips */
            if (c < 1 || saturated)
                continue;
            for (int k = 0; k < 3; k++) {
                double want = sqrt(0.5 * linear(plain.rgb[3 * px + k]) + 0.5 * linear(plain.rgb[3 * bg + k]));
                worst = fmax(worst, fabs(mirror.rgb[3 * px + k] - want));
            }
            checked++;
        }
    CHECK(isinf(plain.depth[0]), "column 0 should miss the sphere");
    iacsg_frame_free(&plain);
    iacsg_frame_free(&mirror);
    CHECK(worst <= 1e-4, "a pixel is %g off half its colour and half the background", worst);
    CHECK(checked > 3000, "only %ld pixels checked", checked);
    test_note("%ld pixels within %.1e of the blend", checked, worst);
}

/* A mirror plane (a region whose material reflects all light) under a blue sphere: a pixel of the plane shows
 * blue exactly where the reflected ray from its point meets the sphere (pixels within a margin of that
 * silhouette left out). The segment path. */
TEST_FP(effects_mirror_silhouette) {
    iacsg_view view = ground_view(200);
    iacsg_effects fx = {.bounces = 1};
    view.effects = &fx;
    iacsg_frame fr;
    render_scene_text("material mirror = rgb(0.5, 0.5, 0.5) reflect 1\n"
                      "material blue = rgb(0, 0, 1) specular 0\n"
                      "region ball = move(sphere(0.5), 0, 0, 0.6) : blue\nregion ground = z : mirror\n",
                      &view, &fr);
    sphere ball = {{0, 0, 0.6}, 0.5};
    ia_real p[PARAM_COUNT];
    view_params(&view, p);
    long blue = 0, grey = 0, spared = 0, wrong = 0;
    for (int j = 0; j < view.height; j++)
        for (int i = 0; i < view.width; i++) {
            double o[3], d[3], t1, t2, hit[3], r[3];
            pixel_ray(p, &view, i, j, o, d);
            if (sphere_span(ball, o, d, &t1, &t2) || !(d[2] < 0))
                continue;
            double t = -o[2] / d[2];
            for (int k = 0; k < 3; k++) {
                hit[k] = o[k] + t * d[k];
                r[k] = k == 2 ? -d[k] : d[k];
            }
            if (fabs(hit[0]) > 1.99 || fabs(hit[1]) > 1.99)
                continue;
            /* the reflected ray's closest approach to the centre, against the radius */
            double oc[3] = {ball.c[0] - hit[0], ball.c[1] - hit[1], ball.c[2] - hit[2]};
            double s = fmax(dot(oc, r), 0), e2 = 0;
            for (int k = 0; k < 3; k++)
                e2 += (oc[k] - s * r[k]) * (oc[k] - s * r[k]);
            double dist = sqrt(e2);
            if (fabs(dist - ball.r) < 2e-3) {
                spared++;
                continue;
            }
            int want_blue = dist < ball.r;
            size_t px = (size_t)j * view.width + i;
            int shown_blue = fr.rgb[3 * px + 2] - fr.rgb[3 * px] > 0.2;
            if (shown_blue != want_blue && wrong++ < 5)
                test_note("pixel (%d, %d): the reflection %s the sphere, shown %.3f %.3f %.3f", i, j,
                          want_blue ? "meets" : "misses", fr.rgb[3 * px], fr.rgb[3 * px + 1], fr.rgb[3 * px + 2]);
            blue += want_blue;
            grey += !want_blue;
        }
    iacsg_frame_free(&fr);
    CHECK(wrong == 0, "%ld pixels of the mirror wrong", wrong);
    CHECK(blue > 500 && grey > 10000, "too few pixels: %ld reflecting the sphere, %ld not", blue, grey);
    test_note("%ld mirror pixels show the sphere, %ld the background, as the exact reflection says; %ld within "
              "2e-3 of its silhouette not checked", blue, grey, spared);
}

/* The default rig's colour (linear) of a point with unit normal n seen along d (kernels/light.h's lighting, the
 * first-root path's material): what a layer of a transparent solid contributes, times its opacity. */
static void default_lit(const double n[3], const double d[3], const double f[3], const double r[3], const double u[3],
                        double lin[3]) {
    static const double rig[2][4] = {{-0.6, 0.8, 0.85, 0.45}, {0.9, -0.2, 0.30, 0.10}};
    static const double albedo[3] = {0.80f, 0.52f, 0.28f};
    double diffuse = 0.10, highlight = 0;
    for (int l = 0; l < 2; l++) {
        double L[3], h[3];
        for (int k = 0; k < 3; k++)
            L[k] = -f[k] + rig[l][0] * r[k] + rig[l][1] * u[k];
        double len = sqrt(dot(L, L));
        for (int k = 0; k < 3; k++) {
            L[k] /= len;
            h[k] = L[k] - d[k];
        }
        double nl = dot(n, L), nh = fmax(dot(n, h) / sqrt(dot(h, h)), 0);
        if (nl > 0) {
            diffuse += rig[l][2] * nl;
            highlight += rig[l][3] * pow(nh, 48);
        }
    }
    for (int c = 0; c < 3; c++)
        lin[c] = albedo[c] * diffuse + highlight;
}

/* The layers a ray along -z through (s, v) of sphere_ortho_view crosses, front to back: their unit normals facing
 * the ray. */
typedef void layer_normals(double s, double v, double n[4][3]);

/* `expr` (four layers through every point (s, v) with s^2 + v^2 < within^2, `normals` says which) at opacity 1/2:
 * each pixel there against the composite front to back, C = sum_k a (1 - a)^k c_k + (1 - a)^4 B, with c_k each
 * layer's lit colour and B the background (linear light, clipped to 1 where highlights add up, gamma 2). */
static void check_layers(const char *expr, double within, layer_normals *normals) {
    iacsg_view view = sphere_ortho_view(96);
    view.bounds[5] = 1.5;
    iacsg_effects fx = {.transparency = 0.5};
    view.effects = &fx;
    iacsg_frame fr, plain;
    render_expr(expr, &view, &fr);
    view.effects = NULL;
    render_expr(expr, &view, &plain);
    double cam[PARAM_COUNT];
    iacsg_error err = {0};
    CHECK(iacsg_camera_params(&view.camera, view.width, view.height, cam, &err) == IACSG_OK, "%s", err.message);
    const double *f = cam + PARAM_FORWARD, *r = cam + PARAM_RIGHT, *u = cam + PARAM_UP;
    long checked = 0;
    double worst = 0, a = 0.5;
    for (int j = 0; j < view.height; j++)
        for (int i = 0; i < view.width; i++) {
            double half = view.camera.ortho_height / 2;
            double s = (2 * (i + 0.5) / view.width - 1) * half, v = (1 - 2 * (j + 0.5) / view.height) * half;
            if (s * s + v * v > within * within)
                continue;
            double n[4][3], d[3] = {f[0], f[1], f[2]};
            normals(s, v, n);
            double want[3] = {0, 0, 0}, through = 1, lin[3];
            for (int layer = 0; layer < 4; layer++) {
                default_lit(n[layer], d, f, r, u, lin);
                for (int c = 0; c < 3; c++)
                    want[c] += through * a * lin[c];
                through *= 1 - a;
            }
            size_t px = (size_t)j * view.width + i, bg = (size_t)j * view.width;
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(fr.rgb[3 * px + c] -
                                         sqrt(fmin(want[c] + through * linear(plain.rgb[3 * bg + c]), 1))));
            checked++;
        }
    CHECK(isinf(plain.depth[0]), "column 0 should miss the solid");
    iacsg_frame_free(&fr);
    iacsg_frame_free(&plain);
    CHECK(worst <= 2e-3, "a pixel is %g off the composite of its four layers", worst);
    CHECK(checked > 500, "only %ld pixels checked", checked);
    test_note("%ld pixels through four layers within %.1e of the compositing formula", checked, worst);
}

/* A slab (box) in front of a sphere of radius 1/2: the slab's two faces, the sphere's front and back. */
static void slab_sphere_normals(double s, double v, double n[4][3]) {
    double zs = sqrt(0.25 - s * s - v * v);
    double all[4][3] = {{0, 0, 1}, {0, 0, 1}, {s / 0.5, v / 0.5, zs / 0.5}, {-s / 0.5, -v / 0.5, zs / 0.5}};
    memcpy(n, all, sizeof all);
}

/* A half-transparent box (a slab) in front of a sphere, both of opacity 1/2, seen along -z: through both, a
 * pixel's ray crosses four surfaces, each a layer with the normal facing the ray (away from the sphere's
 * silhouette). */
TEST_FP(effects_transparent_layers) {
    check_layers("min(move(box(0.6, 0.6, 0.1), 0, 0, 1), sphere(0.5))", 0.45, slab_sphere_normals);
}

/* A hollow ball, radii 1/2 and 0.46: the outer sphere's front, the inner's front (the ray leaves the solid into
 * the hollow), the inner's back, the outer's back. */
static void shell_normals(double s, double v, double n[4][3]) {
    double zo = sqrt(0.25 - s * s - v * v), zi = sqrt(0.46 * 0.46 - s * s - v * v);
    double all[4][3] = {{s / 0.5, v / 0.5, zo / 0.5},
                        {s / 0.46, v / 0.46, zi / 0.46},
                        {-s / 0.46, -v / 0.46, zi / 0.46},
                        {-s / 0.5, -v / 0.5, zo / 0.5}};
    memcpy(n, all, sizeof all);
}

/* The layers of a thin shell: each ray inside the solid meets its exit within 0.04 (kernels/effects.cl's march
 * proves the crossing over a step and closes in on it by interval Newton), so a missed or misplaced exit shows as
 * a wrong normal or a missing layer. */
TEST_FP(effects_transparent_shell) {
    check_layers("max(x^2 + y^2 + z^2 - 0.25, 0.2116 - x^2 - y^2 - z^2)", 0.42, shell_normals);
}

/* The camera kernel's transparent layers search only their tile's runs, the parts of their rays where the tile
 * pass found that surface may be (kernels/tile.h: tile_runs); the host's paths (a reflection of weight 1e-6 lists
 * no ray but sends the layers there) search the whole of each ray. In perspective, through a thin disc onto a
 * file of 12 small balls 0.2 apart, each off the axis at its own angle: a tile's box meets most of them, its rays
 * only a few, so that a ray's first layers past the disc lie in runs past the TILE_RUNS-th (the last run takes
 * the rest in), and a ray crosses up to 26 surfaces (its layers past the TILE_RUN_LAYERS-th search it whole). A
 * surface that the runs left out would leave a layer out of a pixel (dropping the last run: 133 pixels off). */
TEST_FP(effects_transparent_runs_against_host) {
    char expr[2000] = "max(abs(z - 1.3) - 0.02, x^2 + y^2 - 0.2)";
    for (int k = 0; k < 12; k++) {
        size_t len = strlen(expr);
        char ball[80];
        snprintf(ball, sizeof ball, "min(move(sphere(0.04), %.3f, %.3f, %.1f), ", 0.07 * cos(k * 2.4),
                 0.07 * sin(k * 2.4), 1.0 - 0.2 * k);
        memmove(expr + strlen(ball), expr, len + 1);
        memcpy(expr, ball, strlen(ball));
        strcat(expr, ")");
    }
    iacsg_view view = {.width = 128, .height = 128, .eps = 1e-5,
                       .camera = {.eye = {0.05, 0.03, 4}, .at = {0, 0, 0}, .up = {0, 1, 0}, .fov = 12},
                       .bounds = {-1.5, -1.5, -1.5, 1.5, 1.5, 1.5}};
    iacsg_effects fx[2] = {{.transparency = 0.7}, {.transparency = 0.7, .reflect = 1e-6, .bounces = 1}};
    iacsg_frame fr[2];
    for (int k = 0; k < 2; k++) {
        view.effects = &fx[k];
        render_expr(expr, &view, &fr[k]);
    }
    long n = (long)view.width * view.height, off = 0, hits = 0;
    double worst = 0;
    for (long px = 0; px < n; px++) {
        hits += isfinite(fr[0].depth[px]);
        off += colour_difference(&fr[0], &fr[1], px) > 2.5 / 255;
        worst = fmax(worst, colour_difference(&fr[0], &fr[1], px));
    }
    for (int k = 0; k < 2; k++)
        iacsg_frame_free(&fr[k]);
    CHECK(hits > n / 4, "only %ld pixels meet the solid", hits);
    CHECK(off == 0, "%ld of %ld pixels differ from the host's paths by more than 2.5/255 (most %g)", off, n, worst);
    test_note("%ld pixels meet the solid; the camera kernel's layers within %.1e of the host's", hits, worst);
}

/* The AOVs stay the centre ray's: with -aa 4, shadows and reflections the depth, normals and ids are those of
 * the plain render, byte for byte, on both paths (only the colours change). */
/* The plain render and the render with effects fx of `text`, seen from above and aside (64x64). */
static iacsg_view plain_and_effects(const char *text, const iacsg_effects *fx, iacsg_frame *plain,
                                    iacsg_frame *effects) {
    iacsg_view view = sphere_ortho_view(64);
    view.camera = (iacsg_camera){.eye = {3, -2.5, 2}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40};
    view.bounds[2] = -2, view.bounds[5] = 2;
    render_scene_text(text, &view, plain);
    view.effects = fx;
    render_scene_text(text, &view, effects);
    return view;
}

TEST_FP(effects_aovs_unchanged) {
    const char *texts[2] = {"min(sphere, torus)",
                            "material m = rgb(1, 0, 0) reflect 0.4\nregion a = sphere : m\nregion b = torus\n"};
    iacsg_effects fx = {.aa = 4, .shadows = 1, .bounces = 2, .reflect = 0.3};
    for (int s = 0; s < 2; s++) {
        iacsg_frame plain, effects;
        iacsg_view view = plain_and_effects(texts[s], &fx, &plain, &effects);
        size_t n = (size_t)view.width * view.height;
        int same = !memcmp(plain.depth, effects.depth, n * sizeof(float)) &&
                   !memcmp(plain.normal, effects.normal, 3 * n * sizeof(float)) &&
                   !memcmp(plain.ids, effects.ids, n * sizeof(float));
        int recoloured = memcmp(plain.rgb, effects.rgb, 3 * n * sizeof(float)) != 0;
        iacsg_frame_free(&plain);
        iacsg_frame_free(&effects);
        CHECK(same, "%s: the effects changed the depth, normals or ids", s ? "regions" : "expression");
        CHECK(recoloured, "%s: the effects changed no colour", s ? "regions" : "expression");
    }
}

/* -background alone (and with -aa, off its edges) changes only the misses: every hit keeps the plain render's
 * colour bit for bit (the kernel's, where the camera kernel would light it with the effects' code otherwise, which
 * rounds differently), and a miss takes the background of its row, top to bottom (light.h: shade_background). */
TEST_FP(effects_background_keeps_hits) {
    const char *texts[2] = {"min(sphere, torus)", "region a = sphere\nregion b = torus\n"};
    iacsg_effects fx = {.background = 1, .background_top = {1, 0.5, 0}, .background_bottom = {0, 0.5, 1}};
    for (int s = 0; s < 2; s++) {
        iacsg_frame plain, effects;
        iacsg_view view = plain_and_effects(texts[s], &fx, &plain, &effects);
        long hits = 0, misses = 0, bad_hits = 0, bad_misses = 0;
        for (int j = 0; j < view.height; j++)
            for (int i = 0; i < view.width; i++) {
                size_t px = (size_t)j * view.width + i;
                if (!isinf(plain.depth[px])) {
                    hits++;
                    bad_hits += memcmp(plain.rgb + 3 * px, effects.rgb + 3 * px, 3 * sizeof(float)) != 0;
                    continue;
                }
                misses++;
                for (int c = 0; c < 3; c++) {
                    double v = (double)j / (view.height - 1);
                    double want = fx.background_top[c] + (fx.background_bottom[c] - fx.background_top[c]) * v;
                    if (fabs(effects.rgb[3 * px + c] - want) > 1e-5) {
                        bad_misses++;
                        break;
                    }
                }
            }
        iacsg_frame_free(&plain);
        iacsg_frame_free(&effects);
        CHECK(hits > 500 && misses > 500, "%s: %ld hits, %ld misses: the view does not test both",
              s ? "regions" : "expression", hits, misses);
        CHECK(bad_hits == 0, "%s: %ld of %ld hits changed colour", s ? "regions" : "expression", bad_hits, hits);
        CHECK(bad_misses == 0, "%s: %ld of %ld misses are not their row's background", s ? "regions" : "expression",
              bad_misses, misses);
    }
}

/* Half-transparent regions seen along -z: region s (`front`, of opacity 1/2) before region b (`back`, opaque), both
 * over the scene's `solids`. A region is a volume, one layer where a ray enters it: through both, a pixel within
 * 0.45 of the axis is half the front's lit colour and half the back's, in linear light, each as the plain render of
 * a scene holding it alone shows it. */
static void check_region_composite(const char *solids, const char *front, const char *back) {
    iacsg_view view = sphere_ortho_view(96);
    view.bounds[5] = 1.5;
    char both[1024], front_only[512], back_only[512];
    snprintf(both, sizeof both,
             "material glass = rgb(0.3, 0.6, 0.9) opacity 0.5\nmaterial clay = rgb(0.8, 0.52, 0.28)\n%s"
             "region s = %s : glass\nregion b = %s : clay\n", solids, front, back);
    snprintf(front_only, sizeof front_only, "material glass = rgb(0.3, 0.6, 0.9)\n%sregion s = %s : glass\n", solids,
             front);
    snprintf(back_only, sizeof back_only, "material clay = rgb(0.8, 0.52, 0.28)\n%sregion b = %s : clay\n", solids,
             back);
    iacsg_frame fr, front_fr, back_fr;
    iacsg_effects fx = {0}; /* none of the options: the material's opacity is the effect */
    view.effects = &fx;
    render_scene_text(both, &view, &fr);
    view.effects = NULL;
    render_scene_text(front_only, &view, &front_fr);
    render_scene_text(back_only, &view, &back_fr);
    long checked = 0;
    double worst = 0;
    for (int j = 0; j < view.height; j++)
        for (int i = 0; i < view.width; i++) {
            double half = view.camera.ortho_height / 2;
            double s = (2 * (i + 0.5) / view.width - 1) * half, v = (1 - 2 * (j + 0.5) / view.height) * half;
            if (s * s + v * v > 0.45 * 0.45)
                continue;
            size_t px = (size_t)j * view.width + i;
            int saturated = 0; /* the highlight, whose light past 1 a plain render clips and the blend takes whole */
            for (int c = 0; c < 3; c++)
                saturated |= front_fr.rgb[3 * px + c] >= 1 || back_fr.rgb[3 * px + c] >= 1;
            if (saturated)
                continue;
            for (int c = 0; c < 3; c++) {
                double want = sqrt(0.5 * linear(front_fr.rgb[3 * px + c]) + 0.5 * linear(back_fr.rgb[3 * px + c]));
                worst = fmax(worst, fabs(fr.rgb[3 * px + c] - want));
            }
            checked++;
        }
    iacsg_frame_free(&fr);
    iacsg_frame_free(&front_fr);
    iacsg_frame_free(&back_fr);
    CHECK(worst <= 1e-3, "%s before %s: a pixel is %g off half of each", front, back, worst);
    CHECK(checked > 500, "only %ld pixels checked", checked);
    test_note("%ld pixels through %s within %.1e of the composite of the two regions", checked, front, worst);
}

/* A slab in front of a sphere, apart: the slab's layer ray leaves it into the open and meets the sphere
 * (kernels/scene_effects.cl: from inside the slab to its exit, and on to the next region, in lanes). */
TEST_FP(effects_transparent_region) {
    check_region_composite("", "move(box(0.6, 0.6, 0.1), 0, 0, 1)", "sphere(0.5)");
}

/* Two slabs stacked, touching at z = 0, the lower one opaque: the upper's layer ray leaves it straight into the
 * lower (scene_effects.cl: the exit's leaf claimed by the region touching it, never by the region it passes
 * through; claiming the upper slab there again shows its colour twice). */
TEST_FP(effects_transparent_region_touching) {
    check_region_composite("solid top = move(box(0.6, 0.6, 0.1), 0, 0, 0.1)\n"
                           "solid bottom = move(box(0.6, 0.6, 0.1), 0, 0, -0.1)\n",
                           "top \\ bottom", "bottom");
}
