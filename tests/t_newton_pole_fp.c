/* tests/t_newton_pole_fp.c -- interval Newton next to a pole, in the packets (kernels/packet.h) and in the segment
 * path's walks (kernels/segments.h, the solid as a region): f = g(x) with a pole at x = -0.52 and a steep term,
 * seen orthographically along +x, so that every ray meets the same first root. Over a node that holds the root and
 * the pole, the derivative enclosure is one-signed and unbounded ([-inf, -c] or [1, inf]); a Newton step there
 * kept the far side of the pole and reported the second root, 0.063 later, in every pixel. Each pixel's depth
 * must be the first root's (the region's entry: f < 0 just before the pole), to within the leaf width. Float and
 * double. */
#include "t_render_util.h"
#include "implicits/scene.h"
#include "implicits/scene_emit.h"
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

/* tan's case is increasing on (-2, -0.52) (it is -cot(x + 0.52) + 1000 (x + 0.52)), with one root there, near
 * the power's -0.52 - 1/sqrt(1000): found by bisection in double. */
static double pole_tan(double x) { return tan(x + 2.0907963267948966) + 1000 * (x + 0.52); }

/* The root of an increasing f on [lo, hi] (f(lo) < 0 < f(hi)), to the resolution of doubles. */
static double increasing_root(double (*f)(double), double lo, double hi) {
    while (1) {
        double mid = lo * 0.5 + hi * 0.5;
        if (!(mid > lo && mid < hi))
            return lo;
        if (f(mid) < 0)
            lo = mid;
        else
            hi = mid;
    }
}

/* The expression rendered by the packets (a single expression). */
static void render_expression(const char *expr, const iacsg_render_config *config, const iacsg_view *view,
                              iacsg_frame *fr) {
    char *cl = newton_expr_cl(expr);
    render_cl(cl, config, view, fr);
    free(cl);
}

/* The expression as the one solid of a region, rendered by the segment path. */
static void render_region(const char *expr, const iacsg_render_config *config, const iacsg_view *view,
                          iacsg_frame *fr) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(expr, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_scene *s = scene_create();
    CHECK(s && scene_add_solid(s, NULL, e, &err) == 0, "%s", err.message);
    uint32_t node = CSG_NODE(CSG_INSIDE, 0);
    int tree = scene_add_tree(s, &node, 1, &err);
    CHECK(tree >= 0 && scene_add_region(s, NULL, tree, -1, &err) == 0, "%s", err.message);
    char *cl = NULL;
    CHECK(scene_emit_cl(s, &cl, &err) == IACSG_OK, "%s", err.message);
    CHECK(strstr(cl, "SCENE_SOLID_FD") && strstr(cl, "scene_s0_Fd("),
          "'%s': no scene_solid_Fd, so no interval Newton in the walks to test", expr);
    free(cl);
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_scene(s, config, &r, &err) == IACSG_OK, "renderer: %s", err.message);
    iacsg_status st = iacsg_render(r, view, fr, &err);
    iacsg_renderer_destroy(r);
    iacsg_scene_destroy(s);
    CHECK(st == IACSG_OK, "render: %s", err.message);
}

static void check_first_root(const char *expr, double x_root,
                             void (*render)(const char *, const iacsg_render_config *, const iacsg_view *,
                                            iacsg_frame *)) {
    iacsg_view view = {.width = 24, .height = 24, .eps = 1e-5,
                       .camera = {.eye = {-3, 0, 0}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40, .ortho_height = 4},
                       .bounds = {-2, -2, -2, 2, 2, 2}};
    iacsg_render_config config = {.device = 0, .fp64 = FP64};
    iacsg_frame fr;
    render(expr, &config, &view, &fr);
    ia_real p[PARAM_COUNT];
    view_params(&view, p);
    long missed = 0, late = 0, early = 0;
    double worst = 0;
    for (int j = 0; j < view.height; j++)
        for (int i = 0; i < view.width; i++) {
            double o[3], d[3];
            pixel_ray(p, &view, i, j, o, d);
            double t = (x_root - o[0]) / d[0]; /* d is exactly (1, 0, 0) */
            double depth = fr.depth[(size_t)j * view.width + i];
            worst = fmax(worst, fabs(depth - t));
            missed += !isfinite(depth);
            late += depth > t * (1 + 1e-12);
            early += depth < t - 2 * view.eps; /* a leaf (eps) holds the root, its box one eps further at most */
        }
    iacsg_frame_free(&fr);
    test_note("%s: first root at depth %.9g; %d pixels, worst |depth - root| %.3g", expr, x_root + 3,
              view.width * view.height, worst);
    CHECK(missed == 0 && late == 0 && early == 0,
          "%s: %ld pixels missed, %ld after the first root, %ld more than 2 eps before it (worst |depth - root| %.6g)",
          expr, missed, late, early, worst);
}

TEST_FP(newton_pole_power) {
    check_first_root("(x+0.52)^-1 - 1000*(x+0.52)", -0.52 - 1 / sqrt(1000.0), render_expression);
}

TEST_FP(newton_pole_tan) {
    CHECK(pole_tan(-2) < 0 && pole_tan(-0.5201) > 0, "the bracket does not hold the root");
    check_first_root("tan(x+2.0907963267948966) + 1000*(x+0.52)", increasing_root(pole_tan, -2, -0.5201),
                     render_expression);
}

/* The walks step Newton only on nodes narrower than SEGMENTS_NEWTON_LEAVES leaves (2.56e-3 here): with the root
 * 0.032 before the pole no such node holds both, so the second case puts the root 1e-4 before a pole at -0.521,
 * which lies in the first half of the tree's node [-2 + 757/512, -2 + 758/512]: a step there from its midpoint,
 * past the pole, kept only the far side (the second root's, 2e-4 later). */
TEST_FP(newton_pole_power_region) {
    check_first_root("(x+0.52)^-1 - 1000*(x+0.52)", -0.52 - 1 / sqrt(1000.0), render_region);
    check_first_root("(x+0.521)^-1 - 100000000*(x+0.521)", -0.5211, render_region);
}
