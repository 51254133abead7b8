/* tests/t_render_fp.c -- rendered depth against analytic ray intersections computed on the host in double.
 *
 * The host rebuilds each pixel's float ray with the kernel's own code (kernels/camera.h, compiled here as C with
 * the same precision) and intersects that exact ray with the spheres in double. Checked per pixel:
 *   - no miss: every ray that passes through the solid (by more than 1e-6, so the host's own rounding cannot
 *     decide) has a hit;
 *   - never late: the depth is not after the first root;
 *   - within eps: where the surface is not grazing (|n.d| > 0.25), the depth is at most k eps before the root,
 *     k = 1 + sum |n_i d_i| / |n.d|: a leaf holds the root (1 eps), or is an earlier leaf accepted because its
 *     box, not its segment, comes near the surface (the box over a segment of length eps is at most
 *     sum |n_i d_i| / |n.d| eps further from the surface along the ray than the segment is);
 *   - no ghost: every reported depth lies within ghost_margin(eps) (t_render_util.h) of a sphere's surface, on
 *     rays that miss as on rays that hit (so also no depth far before a grazing root).
 * The expressions are written by hand in OpenCL C, so these tests need nothing from the compiler.
 */
#include "t_render_util.h"
#include "render.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

/* The first boundary point of the solid along the ray, and the length of the inside piece it starts (how
 * robustly the ray is inside). Returns 0 when the ray meets no inside piece in front of the eye. */
static int solid_first_root(sphere A, sphere B, solid_op op, const double o[3], const double d[3], double *t,
                            double *piece, int *which) {
    double a1 = 0, a2 = 0, b1 = 0, b2 = 0, s1 = 0, s2 = -1;
    int ha = sphere_span(A, o, d, &a1, &a2), hb = sphere_span(B, o, d, &b1, &b2);
    *which = 0;
    switch (op) {
    case SOLID_A:
        if (ha)
            s1 = a1, s2 = a2;
        break;
    case SOLID_UNION:
        if (ha && (!hb || a1 <= b1))
            s1 = a1, s2 = hb && b1 <= a2 ? fmax(a2, b2) : a2;
        else if (hb)
            s1 = b1, s2 = ha && a1 <= b2 ? fmax(a2, b2) : b2, *which = 1;
        break;
    case SOLID_INTER:
        if (ha && hb)
            s1 = fmax(a1, b1), s2 = fmin(a2, b2), *which = b1 > a1;
        break;
    case SOLID_DIFF:
        if (ha && (!hb || b2 < a1 || b1 > a1))
            s1 = a1, s2 = hb && b1 > a1 ? fmin(a2, b1) : a2;
        else if (ha && b2 < a2)
            s1 = b2, s2 = a2, *which = 1;
        break;
    }
    if (!(s2 > s1) || s1 < 0)
        return 0;
    *t = s1;
    *piece = s2 - s1;
    return 1;
}

typedef struct {
    long hits, misses, late, checked_eps, ghosts;
    double worst_eps;  /* largest (root - depth) / (k eps) where checked */
    double evals_mean; /* interval evaluations per ray, with stats */
    double margin;     /* ghost_margin of the view's eps */
    double worst_gap;  /* the largest distance from a depth's point to the nearest surface */
} depth_report;

/* Renders the solid, given as OpenCL C (cl), and compares every pixel with the analytic first root. */
static depth_report check_solid(sphere A, sphere B, solid_op op, const char *cl, const iacsg_view *view, int stats) {
    depth_report rep = {.margin = ghost_margin(view->eps)};
    iacsg_render_config config = {.device = 0, .fp64 = FP64, .stats = stats};
    iacsg_frame fr;
    render_cl(cl, &config, view, &fr);

    ia_real p[PARAM_COUNT];
    view_params(view, p);
    for (int j = 0; j < view->height; j++)
        for (int i = 0; i < view->width; i++) {
            double o[3], d[3], t, piece;
            pixel_ray(p, view, i, j, o, d);
            int which;
            double depth = fr.depth[(size_t)j * view->width + i];
            int hit = solid_first_root(A, B, op, o, d, &t, &piece, &which);
            if (isfinite(depth)) {
                double q[3] = {o[0] + depth * d[0], o[1] + depth * d[1], o[2] + depth * d[2]};
                double gap = fmin(sphere_surface_distance(A, q), sphere_surface_distance(B, q));
                rep.worst_gap = fmax(rep.worst_gap, gap);
                if (gap > rep.margin && rep.ghosts++ < 5)
                    test_note("ghost pixel (%d, %d): depth %.9g is %.3g from the surface", i, j, depth, gap);
            }
            if (!hit || piece < 1e-6)
                continue;
            if (!isfinite(depth)) {
                if (rep.misses++ < 5)
                    test_note("missed pixel (%d, %d): root at t = %.9g", i, j, t);
                continue;
            }
            rep.hits++;
            if (depth > t * (1 + 1e-12)) {
                if (rep.late++ < 5)
                    test_note("late pixel (%d, %d): depth %.9g after the root %.9g", i, j, depth, t);
            }
            sphere s = which ? B : A;
            double n[3], nn = 0, nd = 0, nd_abs = 0;
            for (int k = 0; k < 3; k++) {
                n[k] = o[k] + t * d[k] - s.c[k];
                nn += n[k] * n[k];
                nd += n[k] * d[k];
                nd_abs += fabs(n[k] * d[k]);
            }
            if (fabs(nd) / sqrt(nn) > 0.25) {
                rep.checked_eps++;
                rep.worst_eps = fmax(rep.worst_eps, (t - depth) / (view->eps * (1 + nd_abs / fabs(nd))));
            }
        }
    rep.evals_mean = fr.evals_mean;
    iacsg_frame_free(&fr);
    return rep;
}

/* ... written by hand (spheres_cl: bisection only, no derivative code) */
static depth_report check_spheres(sphere A, sphere B, solid_op op, const iacsg_view *view) {
    char *cl = spheres_cl(A, B, op);
    depth_report rep = check_solid(A, B, op, cl, view, 0);
    free(cl);
    return rep;
}

/* ... or compiled from an expression (with iacsg_Fdv where the compiler emits it) */
static depth_report check_expression(sphere A, sphere B, solid_op op, const char *expr, const iacsg_view *view) {
    char *cl = newton_expr_cl(expr);
    depth_report rep = check_solid(A, B, op, cl, view, 1);
    free(cl);
    return rep;
}

static iacsg_view small_view(int size, double eps) {
    iacsg_view v = {.width = size, .height = size, .eps = eps,
                    .camera = {.eye = {0.5, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40},
                    .bounds = {-2, -2, -2, 2, 2, 2}};
    return v;
}

static void expect_exact(depth_report rep, const char *what) {
    test_note("%s: %ld hits, %ld checked for eps (worst %.3f k eps), %ld ghost pixels (depths within %.2g of a "
              "surface, margin %.2g)",
              what, rep.hits, rep.checked_eps, rep.worst_eps, rep.ghosts, rep.worst_gap, rep.margin);
    CHECK(rep.hits > 500, "%s: too few hits (%ld) to mean anything", what, rep.hits);
    CHECK(rep.misses == 0, "%s: %ld missed pixels", what, rep.misses);
    CHECK(rep.late == 0, "%s: %ld pixels with the depth after the first root", what, rep.late);
    CHECK(rep.worst_eps <= 1, "%s: depth %.3f k eps before the root on a non-grazing pixel", what, rep.worst_eps);
    CHECK(rep.ghosts == 0, "%s: %ld ghost pixels (a depth farther than %.3g from every surface)", what, rep.ghosts,
          rep.margin);
}

static const sphere unit_sphere = {{0, 0, 0}, 1};
static const sphere sphere_a = {{-0.375, 0, 0}, 0.75}, sphere_b = {{0.25, 0.125, 0.125}, 0.625};

TEST_FP(render_sphere_depth) {
    iacsg_view v = small_view(128, 0x1p-16);
    expect_exact(check_spheres(unit_sphere, unit_sphere, SOLID_A, &v), "sphere");
}

TEST_FP(render_sphere_ortho_depth) {
    iacsg_view v = small_view(128, 1e-5);
    v.camera.ortho_height = 2.5;
    expect_exact(check_spheres(unit_sphere, unit_sphere, SOLID_A, &v), "sphere, orthographic");
}

/* The eye inside the bounds: rays start at t = 0, not at the box. */
TEST_FP(render_sphere_eye_inside_bounds) {
    iacsg_view v = small_view(96, 1e-5);
    for (int k = 0; k < 3; k++) {
        v.bounds[k] = -6.5;
        v.bounds[k + 3] = 5.25;
    }
    expect_exact(check_spheres(unit_sphere, unit_sphere, SOLID_A, &v), "sphere, eye inside, perspective");
    v.camera.ortho_height = 2.5;
    expect_exact(check_spheres(unit_sphere, unit_sphere, SOLID_A, &v), "sphere, eye inside, orthographic");
}

/* Interval Newton (kernels/packet.h) takes the leaves from a few pixel footprints down to eps: with eps far
 * below the footprint, the same exact depths as bisection in fewer evaluations (the unit sphere at eps 4e-6:
 * 11.2 per ray by bisection alone, 6.8 with Newton); and through min and max (Clarke's derivative at a tie). */
TEST_FP(render_newton_depth) {
    iacsg_view v = small_view(128, 4e-6);
    depth_report rep = check_expression(unit_sphere, unit_sphere, SOLID_A, "x^2+y^2+z^2-1", &v);
    expect_exact(rep, "sphere, compiled, eps far below the footprint");
    test_note("sphere: %.2f interval evaluations per ray", rep.evals_mean);
    CHECK(rep.evals_mean < 9, "%.2f evaluations per ray: interval Newton did not refine the roots", rep.evals_mean);
    const char *a = "(x+0.375)^2+y^2+z^2-0.5625", *b = "(x-0.25)^2+(y-0.125)^2+(z-0.125)^2-0.390625";
    char expr[256];
    snprintf(expr, sizeof expr, "min(%s, %s)", a, b);
    expect_exact(check_expression(sphere_a, sphere_b, SOLID_UNION, expr, &v), "union, compiled");
    snprintf(expr, sizeof expr, "max(%s, %s)", a, b);
    expect_exact(check_expression(sphere_a, sphere_b, SOLID_INTER, expr, &v), "intersection, compiled");
    snprintf(expr, sizeof expr, "max(%s, -(%s))", a, b);
    expect_exact(check_expression(sphere_a, sphere_b, SOLID_DIFF, expr, &v), "difference, compiled");
}

/* Rays that graze the unit sphere, an orthographic view 2e-3 high centred 5e-4 inside its silhouette: each ray's F
 * has its minimum within 2e-3 of 0, so Newton's first part holds a slope of both signs and the ray goes on by the
 * mean value form, whose Newton steps start where its stretch of the ray is monotone (kernels/packet.h). Every
 * hit, miss and depth as exact as elsewhere, at eps 1e-6 (Newton from 64 leaves, below 32 footprints of 1.6e-5). */
TEST_FP(render_newton_grazing_depth) {
    iacsg_view v = {.width = 128, .height = 128, .eps = 1e-6,
                    .camera = {.eye = {-3, 0.9995, 0}, .at = {0, 0.9995, 0}, .up = {0, 0, 1}, .ortho_height = 2e-3},
                    .bounds = {-2, -2, -2, 2, 2, 2}};
    depth_report rep = check_expression(unit_sphere, unit_sphere, SOLID_A, "x^2+y^2+z^2-1", &v);
    expect_exact(rep, "sphere, grazing rays");
    test_note("grazing rays: %.2f interval evaluations per ray", rep.evals_mean);
}

TEST_FP(render_spheres_csg_depth) {
    iacsg_view v = small_view(128, 1e-5);
    expect_exact(check_spheres(sphere_a, sphere_b, SOLID_UNION, &v), "union");
    expect_exact(check_spheres(sphere_a, sphere_b, SOLID_INTER, &v), "intersection");
    expect_exact(check_spheres(sphere_a, sphere_b, SOLID_DIFF, &v), "difference");
}
