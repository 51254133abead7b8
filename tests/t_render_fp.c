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
 *     sum |n_i d_i| / |n.d| eps further from the surface along the ray than the segment is).
 * The expressions are written by hand in OpenCL C, so these tests need nothing from the compiler.
 */
#include "kernels/camera.h"
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

typedef struct {
    double c[3], r; /* dyadic values, exact in float and double */
} sphere;

typedef enum { SOLID_A, SOLID_UNION, SOLID_INTER, SOLID_DIFF } solid_op;

/* OpenCL C for the CSG of spheres a and b: F, f and its gradient, as the compiler would emit them. */
static char *spheres_cl(sphere a, sphere b, solid_op op) {
    static const char *ops_F[] = {"a", "ia_min(a, b)", "ia_max(a, b)", "ia_max(a, ia_neg(b))"};
    static const char *ops_f[] = {"a", "fmin(a, b)", "fmax(a, b)", "fmax(a, -b)"};
    /* The gradient of the branch that min/max selects; for the difference, -grad b when -b wins. */
    static const char *ops_g[] = {"1", "a <= b", "a >= b", "a >= -b"};
    static const char *ops_gs[] = {"1", "1", "1", "-1"};
    char *s = malloc(8192);
    snprintf(s, 8192,
             "IA_FN ia_interval sph_F(ia_interval x, ia_interval y, ia_interval z, ia_real cx, ia_real cy, ia_real cz,"
             " ia_real r) {\n"
             "  return ia_add_r(ia_add(ia_add(ia_sqr(ia_add_r(x, -cx)), ia_sqr(ia_add_r(y, -cy))),"
             " ia_sqr(ia_add_r(z, -cz))), -r * r);\n}\n"
             "IA_FN ia_real sph_f(ia_real x, ia_real y, ia_real z, ia_real cx, ia_real cy, ia_real cz, ia_real r) {\n"
             "  return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) - r * r;\n}\n"
             "#define SA %a, %a, %a, %a\n#define SB %a, %a, %a, %a\n"
             "IA_FN ia_interval iacsg_F(ia_interval x, ia_interval y, ia_interval z, ia_interval t) {\n"
             "  ia_interval a = sph_F(x, y, z, SA), b = sph_F(x, y, z, SB); (void)t; (void)b; return %s;\n}\n"
             "IA_FN ia_real iacsg_f(ia_real x, ia_real y, ia_real z, ia_real t) {\n"
             "  ia_real a = sph_f(x, y, z, SA), b = sph_f(x, y, z, SB); (void)t; (void)b; return %s;\n}\n"
             "IA_FN ia_real iacsg_f_grad(ia_real x, ia_real y, ia_real z, ia_real t, ia_real *gx, ia_real *gy,"
             " ia_real *gz) {\n"
             "  ia_real a = sph_f(x, y, z, SA), b = sph_f(x, y, z, SB); (void)t;\n"
             "  ia_real ca[4] = {SA}, cb[4] = {SB}; int use_a = %s; ia_real sg = use_a ? 1 : %s;\n"
             "  *gx = sg * 2 * (x - (use_a ? ca[0] : cb[0]));\n"
             "  *gy = sg * 2 * (y - (use_a ? ca[1] : cb[1]));\n"
             "  *gz = sg * 2 * (z - (use_a ? ca[2] : cb[2]));\n"
             "  return iacsg_f(x, y, z, t);\n}\n",
             a.c[0], a.c[1], a.c[2], a.r, b.c[0], b.c[1], b.c[2], b.r, ops_F[op], ops_f[op], ops_g[op], ops_gs[op]);
    return s;
}

/* The exact solutions of |o + t d - c| = r for the double values of the float ray: the inside interval
 * [*t1, *t2]; returns 0 if the ray misses. *margin is the discriminant's square root (how far from tangent). */
static int sphere_span(sphere s, const double o[3], const double d[3], double *t1, double *t2) {
    double oc[3] = {o[0] - s.c[0], o[1] - s.c[1], o[2] - s.c[2]};
    double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - s.r * s.r;
    double disc = b * b - a * c;
    if (disc < 0)
        return 0;
    double q = -(b + copysign(sqrt(disc), b)); /* no cancellation */
    double r1 = q / a, r2 = c / q;
    *t1 = fmin(r1, r2);
    *t2 = fmax(r1, r2);
    return 1;
}

/* The first boundary point of the solid along the ray, and the length of the inside piece it starts (how
 * robustly the ray is inside). Returns 0 when the ray meets no inside piece in front of the eye. */
static int solid_first_root(sphere A, sphere B, solid_op op, const double o[3], const double d[3], double *t,
                            double *piece, int *which) {
    double a1, a2, b1, b2, s1 = 0, s2 = -1;
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
    double worst_eps; /* largest (root - depth) / (k eps) where checked */
} depth_report;

/* Renders the solid and compares every pixel with the analytic first root. */
static depth_report check_spheres(sphere A, sphere B, solid_op op, const iacsg_view *view, int fast) {
    depth_report rep = {0};
    iacsg_error err = {0};
    iacsg_render_config config = {.device = 0, .fp64 = FP64, .fast = fast};
    iacsg_renderer *r = NULL;
    char *cl = spheres_cl(A, B, op);
    iacsg_status st = iacsg_renderer_create(cl, &config, &r, &err);
    free(cl);
    CHECK(st == IACSG_OK, "renderer: %s", err.message);
    iacsg_frame fr;
    st = iacsg_render(r, view, &fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "render: %s", err.message);

    double pd[PARAM_COUNT];
    ia_real p[PARAM_COUNT];
    CHECK(iacsg_camera_params(&view->camera, view->width, view->height, pd, &err) == IACSG_OK, "%s", err.message);
    for (int k = 0; k < PARAM_COUNT; k++)
        p[k] = (ia_real)pd[k];
    int ortho = view->camera.ortho_height > 0;
    for (int j = 0; j < view->height; j++)
        for (int i = 0; i < view->width; i++) {
            ia_real of[3], df[3];
            camera_ray(p, ortho, i, j, view->width, view->height, of, df);
            double o[3] = {of[0], of[1], of[2]}, d[3] = {df[0], df[1], df[2]}, t, piece;
            int which;
            double depth = fr.depth[(size_t)j * view->width + i];
            int hit = solid_first_root(A, B, op, o, d, &t, &piece, &which);
            if (!hit || piece < 1e-6) {
                rep.ghosts += !hit && isfinite(depth);
                continue;
            }
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
    iacsg_frame_free(&fr);
    return rep;
}

static iacsg_view small_view(int size, double eps) {
    iacsg_view v = {.width = size, .height = size, .eps = eps,
                    .camera = {.eye = {0.5, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40},
                    .bounds = {-2, -2, -2, 2, 2, 2}};
    return v;
}

static void expect_exact(depth_report rep, const char *what) {
    test_note("%s: %ld hits, %ld checked for eps (worst %.3f k eps), %ld ghost pixels", what, rep.hits,
              rep.checked_eps, rep.worst_eps, rep.ghosts);
    CHECK(rep.hits > 500, "%s: too few hits (%ld) to mean anything", what, rep.hits);
    CHECK(rep.misses == 0, "%s: %ld missed pixels", what, rep.misses);
    CHECK(rep.late == 0, "%s: %ld pixels with the depth after the first root", what, rep.late);
    CHECK(rep.worst_eps <= 1, "%s: depth %.3f k eps before the root on a non-grazing pixel", what, rep.worst_eps);
}

static const sphere unit_sphere = {{0, 0, 0}, 1};
static const sphere sphere_a = {{-0.375, 0, 0}, 0.75}, sphere_b = {{0.25, 0.125, 0.125}, 0.625};

TEST_FP(render_sphere_depth) {
    iacsg_view v = small_view(128, 0x1p-16);
    expect_exact(check_spheres(unit_sphere, unit_sphere, SOLID_A, &v, 0), "sphere");
}

TEST_FP(render_sphere_ortho_depth) {
    iacsg_view v = small_view(128, 1e-5);
    v.camera.ortho_height = 2.5;
    expect_exact(check_spheres(unit_sphere, unit_sphere, SOLID_A, &v, 0), "sphere, orthographic");
}

TEST_FP(render_spheres_csg_depth) {
    iacsg_view v = small_view(128, 1e-5);
    expect_exact(check_spheres(sphere_a, sphere_b, SOLID_UNION, &v, 0), "union");
    expect_exact(check_spheres(sphere_a, sphere_b, SOLID_INTER, &v, 0), "intersection");
    expect_exact(check_spheres(sphere_a, sphere_b, SOLID_DIFF, &v, 0), "difference");
}
