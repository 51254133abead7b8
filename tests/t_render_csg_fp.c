/* tests/t_render_csg_fp.c -- expressions compiled by the real compiler (implicits/), rendered, and compared pixel
 * by pixel with exact ray intersections computed on the host in double: CSG of a sphere and a torus, and thin
 * features that point sampling misses (a slab 1e-4 thick, a rod of radius 0.004).
 *
 * Along a ray each primitive's inside is a union of t intervals, found from the roots of its polynomial in t
 * (quadratic for the sphere, slab and rod, quartic for the torus); the CSG of the insides is decided at the
 * midpoints between consecutive roots. Checked: no ray that passes through the solid (by more than 1e-6) is
 * missed, no depth is after the first root, and no depth is a ghost (its point farther than ghost_margin, in
 * t_render_util.h, from every primitive's surface: each primitive also gives its exact distance function). Also
 * a union of 32 spheres, which is emitted in groups, and the tangle, whose silhouettes the kernels decide by a mean
 * value form. */
#include "t_render_util.h"
#include "implicits/expr.h"
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

enum { MAX_ROOTS = 16 };

static double poly_eval(const double *c, int n, double t) {
    double v = c[n];
    for (int k = n - 1; k >= 0; k--)
        v = v * t + c[k];
    return v;
}

/* The real roots of sum c[k] t^k (degree n <= 4) in [lo, hi] where the sign changes, sorted: between
 * consecutive roots of the derivative the polynomial is monotone, so bisection finds each root. */
static int poly_roots(const double *c, int n, double lo, double hi, double *roots) {
    while (n > 0 && c[n] == 0)
        n--;
    if (n == 0)
        return 0;
    double dc[4], crit[MAX_ROOTS], pts[MAX_ROOTS + 2];
    for (int k = 0; k < n; k++)
        dc[k] = (k + 1) * c[k + 1];
    int nc = n > 1 ? poly_roots(dc, n - 1, lo, hi, crit) : 0, np = 0, count = 0;
    pts[np++] = lo;
    for (int k = 0; k < nc; k++)
        pts[np++] = crit[k];
    pts[np++] = hi;
    for (int k = 0; k + 1 < np; k++) {
        double a = pts[k], b = pts[k + 1], fa = poly_eval(c, n, a), fb = poly_eval(c, n, b);
        if (fa == 0 || (fa < 0) == (fb < 0))
            continue;
        for (int it = 0; it < 200 && a < b; it++) {
            double m = 0.5 * (a + b);
            if (m <= a || m >= b)
                break;
            if ((poly_eval(c, n, m) < 0) == (fa < 0))
                a = m;
            else
                b = m;
        }
        roots[count++] = b;
    }
    return count;
}

/* A primitive along the ray: a polynomial in t, negative inside. */
typedef struct {
    double c[5];
    int degree;
} ray_poly;

static ray_poly sphere_poly(const double ctr[3], double r, const double o[3], const double d[3]) {
    double oc[3] = {o[0] - ctr[0], o[1] - ctr[1], o[2] - ctr[2]};
    ray_poly p = {{0}, 2};
    for (int k = 0; k < 3; k++) {
        p.c[2] += d[k] * d[k];
        p.c[1] += 2 * oc[k] * d[k];
        p.c[0] += oc[k] * oc[k];
    }
    p.c[0] -= r * r;
    return p;
}

/* Torus around the z axis, radii R and r: (|p|^2 + R^2 - r^2)^2 - 4 R^2 (px^2 + py^2), negative inside. */
static ray_poly torus_poly(double R, double r, const double o[3], const double d[3]) {
    double A = 0, B = 0, C = R * R - r * r;
    for (int k = 0; k < 3; k++) {
        A += d[k] * d[k];
        B += 2 * o[k] * d[k];
        C += o[k] * o[k];
    }
    double q2 = d[0] * d[0] + d[1] * d[1], q1 = 2 * (o[0] * d[0] + o[1] * d[1]), q0 = o[0] * o[0] + o[1] * o[1];
    ray_poly p = {{C * C - 4 * R * R * q0, 2 * B * C - 4 * R * R * q1, B * B + 2 * A * C - 4 * R * R * q2, 2 * A * B,
                   A * A},
                  4};
    return p;
}

/* The rod x^2 + y^2 < r^2 and the slab z^2 < h^2: quadratics in t. */
static ray_poly rod_poly(double r, const double o[3], const double d[3]) {
    ray_poly p = {{o[0] * o[0] + o[1] * o[1] - r * r, 2 * (o[0] * d[0] + o[1] * d[1]), d[0] * d[0] + d[1] * d[1]}, 2};
    return p;
}
static ray_poly slab_poly(double h, const double o[3], const double d[3]) {
    ray_poly p = {{o[2] * o[2] - h * h, 2 * o[2] * d[2], d[2] * d[2]}, 2};
    return p;
}

typedef enum { CSG_ONLY_A, CSG_UNION, CSG_DIFF } csg_op;

static int csg_inside(csg_op op, int a, int b) {
    return op == CSG_ONLY_A ? a : op == CSG_UNION ? (a || b) : (a && !b);
}

/* The first t in [tn, tf] where the ray enters the solid, and the length of the inside piece it starts.
 * Returns 0 if there is none (a ray starting inside the solid is not used by these scenes). */
static int csg_first_entry(ray_poly pa, ray_poly pb, csg_op op, double tn, double tf, double *t, double *piece) {
    double pts[2 * MAX_ROOTS + 2];
    int n = 0;
    pts[n++] = tn;
    n += poly_roots(pa.c, pa.degree, tn, tf, pts + n);
    if (op != CSG_ONLY_A)
        n += poly_roots(pb.c, pb.degree, tn, tf, pts + n);
    pts[n++] = tf;
    for (int k = 1; k < n; k++) /* insertion sort: a handful of points */
        for (int m = k; m > 0 && pts[m] < pts[m - 1]; m--) {
            double tmp = pts[m];
            pts[m] = pts[m - 1];
            pts[m - 1] = tmp;
        }
    for (int k = 0; k + 1 < n; k++) {
        double m = 0.5 * (pts[k] + pts[k + 1]);
        if (csg_inside(op, poly_eval(pa.c, pa.degree, m) < 0, poly_eval(pb.c, pb.degree, m) < 0)) {
            if (k == 0)
                return 0;
            *t = pts[k];
            *piece = pts[k + 1] - pts[k];
            return 1;
        }
    }
    return 0;
}

typedef ray_poly (*make_poly)(const double o[3], const double d[3]);
/* The distance from a point to a primitive's surface. */
typedef double (*surface_distance)(const double p[3]);

/* A primitive: along a ray, and in space. */
typedef struct {
    make_poly poly;
    surface_distance distance;
} primitive;

/* The exact first entry of the ray into a scene in [tn, tf], and the length of the inside piece it starts. */
typedef int (*first_entry)(const void *scene, const double o[3], const double d[3], double tn, double tf, double *t,
                           double *piece);
/* The distance from a point to the nearest surface of the scene's primitives. */
typedef double (*scene_distance)(const void *scene, const double p[3]);

/* Two primitives and an operation. */
typedef struct {
    primitive a, b;
    csg_op op;
} csg_pair;
static int pair_entry(const void *scene, const double o[3], const double d[3], double tn, double tf, double *t,
                      double *piece) {
    const csg_pair *s = scene;
    return csg_first_entry(s->a.poly(o, d), s->b.poly(o, d), s->op, tn, tf, t, piece);
}
static double pair_distance(const void *scene, const double p[3]) {
    const csg_pair *s = scene;
    return fmin(s->a.distance(p), s->b.distance(p));
}

typedef struct {
    long through, misses, late, ghosts;
    double worst_gap; /* the largest distance from a depth's point to the nearest surface */
} csg_report;

/* Compiles `expr`, renders it, and checks each pixel against the exact first entry; reports under `name`. */
static csg_report check_scene(const char *name, const char *expr, first_entry entry, scene_distance distance,
                              const void *scene, const iacsg_view *view, int tape) {
    csg_report rep = {0};
    double margin = ghost_margin(view->eps);
    iacsg_render_config config = {.fp64 = FP64, .tape = tape};
    iacsg_frame fr;
    render_expr_text(expr, &config, view, &fr);
    ia_real p[PARAM_COUNT];
    view_params(view, p);
    for (int j = 0; j < view->height; j++)
        for (int i = 0; i < view->width; i++) {
            double o[3], d[3], tn, tf, t, piece;
            pixel_ray(p, view, i, j, o, d);
            double depth = fr.depth[(size_t)j * view->width + i];
            if (isfinite(depth)) {
                double q[3] = {o[0] + depth * d[0], o[1] + depth * d[1], o[2] + depth * d[2]}, gap = distance(scene, q);
                rep.worst_gap = fmax(rep.worst_gap, gap);
                if (gap > margin && rep.ghosts++ < 5)
                    test_note("%s: ghost pixel (%d, %d): depth %.9g is %.3g from every surface", name, i, j, depth,
                              gap);
            }
            if (!ray_box_span(view->bounds, o, d, &tn, &tf) || !entry(scene, o, d, tn, tf, &t, &piece) || piece < 1e-6)
                continue;
            rep.through++;
            if (!isfinite(depth)) {
                if (rep.misses++ < 5)
                    test_note("%s: missed pixel (%d, %d), entry at t = %.9g", name, i, j, t);
            } else if (depth > t * (1 + 1e-12) && rep.late++ < 5) {
                test_note("%s: pixel (%d, %d) depth %.9g after the entry %.9g", name, i, j, depth, t);
            }
        }
    iacsg_frame_free(&fr);
    test_note("%s: %ld rays through the solid, %ld missed, %ld late, %ld ghosts (depths within %.2g of a surface, "
              "margin %.2g)",
              name, rep.through, rep.misses, rep.late, rep.ghosts, rep.worst_gap, margin);
    CHECK(rep.through > 100, "%s: too few rays through the solid (%ld)", name, rep.through);
    CHECK(rep.misses == 0 && rep.late == 0, "%s: %ld missed and %ld late pixels", name, rep.misses, rep.late);
    CHECK(rep.ghosts == 0, "%s: %ld ghost pixels (a depth farther than %.3g from every surface)", name, rep.ghosts,
          margin);
    return rep;
}

static csg_report check_expr(const char *expr, primitive a, primitive b, csg_op op, const iacsg_view *view) {
    csg_pair pair = {a, b, op};
    return check_scene(expr, expr, pair_entry, pair_distance, &pair, view, IACSG_TAPE_NEVER);
}

static iacsg_view view_of(int w, int h, double eps) {
    iacsg_view v = {.width = w, .height = h, .eps = eps, .bounds = {-2, -2, -2, 2, 2, 2},
                    .camera = {.eye = {0.3, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40}};
    return v;
}

static const sphere ball_sphere = {{0.5, 0, 0}, 1}, small_ball_sphere = {{0.5, 0, 0.25}, 0.5};
static ray_poly ball_poly(const double o[3], const double d[3]) { return sphere_poly(ball_sphere.c, 1, o, d); }
static double ball_distance(const double p[3]) { return sphere_surface_distance(ball_sphere, p); }
static ray_poly small_ball_poly(const double o[3], const double d[3]) {
    return sphere_poly(small_ball_sphere.c, 0.5, o, d);
}
static double small_ball_distance(const double p[3]) { return sphere_surface_distance(small_ball_sphere, p); }
static ray_poly ring_poly(const double o[3], const double d[3]) { return torus_poly(1, 0.375, o, d); }
static double ring_distance(const double p[3]) {
    return fabs(hypot(hypot(p[0], p[1]) - 1, p[2]) - 0.375);
}
static ray_poly rod_poly_of(const double o[3], const double d[3]) { return rod_poly(0.004, o, d); }
static double rod_distance(const double p[3]) { return fabs(hypot(p[0], p[1]) - 0.004); }
static ray_poly slab_poly_of(const double o[3], const double d[3]) { return slab_poly(5e-5, o, d); }
static double slab_distance(const double p[3]) { return fabs(fabs(p[2]) - 5e-5); }
static const primitive ball = {ball_poly, ball_distance}, small_ball = {small_ball_poly, small_ball_distance},
                       ring = {ring_poly, ring_distance}, rod = {rod_poly_of, rod_distance},
                       slab = {slab_poly_of, slab_distance};

TEST_FP(render_csg_sphere_torus) {
    iacsg_view v = view_of(128, 128, 1e-5);
    check_expr("min((x-0.5)^2+y^2+z^2-1, (1-sqrt(x^2+y^2))^2+z^2-0.140625)", ball, ring, CSG_UNION, &v);
    check_expr("max((1-sqrt(x^2+y^2))^2+z^2-0.140625, -((x-0.5)^2+y^2+(z-0.25)^2-0.25))", ring, small_ball, CSG_DIFF,
               &v);
}

/* A slab 1e-4 thick seen at a slant, and a rod of radius 0.004 across a view in which it is half a pixel wide
 * (only the middle column of the odd-width image passes through it): every ray through either must hit. */
TEST_FP(render_thin_features) {
    iacsg_view v = view_of(96, 96, 1e-5);
    check_expr("abs(z) - 0.00005", slab, slab, CSG_ONLY_A, &v);
    iacsg_view side = {.width = 63, .height = 127, .eps = 1e-5, .bounds = {-1, -1, -1, 1, 1, 1},
                       .camera = {.eye = {3, 0.001, 0.1}, .at = {0, 0.001, 0.1}, .up = {0, 0, 1}, .fov = 20}};
    check_expr("sqrt(x^2 + y^2) - 0.004", rod, rod, CSG_ONLY_A, &side);
}

/* A union of many spheres (a 4x4x2 grid of radius 0.3): enough parts that the compiler emits it in groups and
 * the tile pass leaves out, per block of tiles, the groups that cannot matter there (kernels/packet.h). The
 * first entry is the earliest of the spheres' own. */
enum { GRID_X = 4, GRID_Y = 4, GRID_Z = 2 };
static void grid_centre(int n, double c[3]) {
    c[0] = -1.2 + 0.8 * (n % GRID_X);
    c[1] = -1.2 + 0.8 * (n / GRID_X % GRID_Y);
    c[2] = -0.4 + 0.8 * (n / (GRID_X * GRID_Y));
}
static int grid_entry(const void *scene, const double o[3], const double d[3], double tn, double tf, double *t,
                      double *piece) {
    (void)scene;
    int found = 0;
    for (int n = 0; n < GRID_X * GRID_Y * GRID_Z; n++) {
        double c[3], roots[MAX_ROOTS];
        grid_centre(n, c);
        ray_poly p = sphere_poly(c, 0.3, o, d);
        if (poly_roots(p.c, p.degree, tn, tf, roots) == 2 && (!found || roots[0] < *t)) {
            *t = roots[0];
            *piece = roots[1] - roots[0];
            found = 1;
        }
    }
    return found;
}
static double grid_distance(const void *scene, const double p[3]) {
    (void)scene;
    double nearest = INFINITY;
    for (int n = 0; n < GRID_X * GRID_Y * GRID_Z; n++) {
        sphere s = {{0, 0, 0}, 0.3};
        grid_centre(n, s.c);
        nearest = fmin(nearest, sphere_surface_distance(s, p));
    }
    return nearest;
}

/* The normals of the union in groups, which the kernels compute by differences (kernels/shade.h), against the
 * exact ones at the entry points (the spheres are disjoint: no edges to blend across). */
static void check_grid_normals(const char *expr, const iacsg_view *view, int tape) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(expr, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {.fp64 = FP64, .tape = tape};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, &config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s", err.message);
    iacsg_frame fr;
    st = iacsg_render(r, view, &fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s", err.message);
    ia_real p[PARAM_COUNT];
    view_params(view, p);
    long checked = 0;
    double worst = 0;
    for (int j = 0; j < view->height; j++)
        for (int i = 0; i < view->width; i++) {
            double o[3], d[3], tn, tf, best = INFINITY, piece = 0, centre[3] = {0, 0, 0};
            pixel_ray(p, view, i, j, o, d);
            if (!ray_box_span(view->bounds, o, d, &tn, &tf))
                continue;
            for (int n = 0; n < GRID_X * GRID_Y * GRID_Z; n++) {
                double c[3], roots[MAX_ROOTS];
                grid_centre(n, c);
                ray_poly poly = sphere_poly(c, 0.3, o, d);
                if (poly_roots(poly.c, poly.degree, tn, tf, roots) == 2 && roots[0] < best)
                    best = roots[0], piece = roots[1] - roots[0], memcpy(centre, c, sizeof c);
            }
            /* away from silhouettes, where the normal turns fastest */
            if (!isfinite(best) || piece < 0.05 || !isfinite(fr.depth[(size_t)j * view->width + i]))
                continue;
            double err2 = 0;
            for (int k = 0; k < 3; k++) {
                double exact = (o[k] + best * d[k] - centre[k]) / 0.3;
                double got = fr.normal[3 * ((size_t)j * view->width + i) + k];
                err2 += (got - exact) * (got - exact);
            }
            worst = fmax(worst, sqrt(err2));
            checked++;
        }
    iacsg_frame_free(&fr);
    test_note("normals by differences: %ld pixels, largest error %.2g", checked, worst);
    CHECK(checked > 1000, "only %ld pixels checked", checked);
    CHECK(worst < 2e-3, "a normal %.3g from the exact one", worst);
}

/* The tangle x^4 - 5x^2 + y^4 - 5y^2 + z^4 - 5z^2 + 11.8, a quartic along a ray. Its silhouettes are where the
 * kernels bound F by its mean value form after Newton gives up on a ray (kernels/packet.h: packet_mean_value). */
static ray_poly tangle_poly(const double o[3], const double d[3]) {
    ray_poly p = {{11.8}, 4};
    for (int k = 0; k < 3; k++) { /* (o + d t)^2 = s0 + s1 t + s2 t^2; its square minus 5 times it */
        double s0 = o[k] * o[k], s1 = 2 * o[k] * d[k], s2 = d[k] * d[k];
        p.c[0] += s0 * s0 - 5 * s0;
        p.c[1] += 2 * s0 * s1 - 5 * s1;
        p.c[2] += s1 * s1 + 2 * s0 * s2 - 5 * s2;
        p.c[3] += 2 * s1 * s2;
        p.c[4] += s2 * s2;
    }
    return p;
}
/* A lower bound of the distance to the tangle's surface: |F(p)| over a bound of |grad F| in [-3, 3]^3 (each
 * component |4x^3 - 10x| <= 138), so that a depth found farther than the margin is a ghost for certain. */
static double tangle_distance(const double p[3]) {
    double f = 11.8;
    for (int k = 0; k < 3; k++)
        f += p[k] * p[k] * p[k] * p[k] - 5 * p[k] * p[k];
    return fabs(f) / (138 * sqrt(3));
}
static const primitive tangle = {tangle_poly, tangle_distance};

TEST_FP(render_tangle_silhouettes) {
    iacsg_view v = view_of(128, 128, 1e-5);
    for (int k = 0; k < 3; k++) {
        v.bounds[k] = -3;
        v.bounds[k + 3] = 3;
    }
    v.camera.eye[1] = -6; /* outside the bounds */
    check_expr("x^4-5*x^2+y^4-5*y^2+z^4-5*z^2+11.8", tangle, tangle, CSG_ONLY_A, &v);
}

/* The union of the grid, compiled (tape off) or interpreted (on, kernels/tape_eval.h: each sphere skipped
 * wherever its box meets no ray's): the same pixels must hold. */
static void check_grid(int tape) {
    char expr[4096] = "min(", *end = expr + strlen(expr);
    for (int n = 0; n < GRID_X * GRID_Y * GRID_Z; n++) {
        double c[3];
        grid_centre(n, c);
        end += snprintf(end, sizeof expr - (size_t)(end - expr), "%s(x-%g)^2+(y-%g)^2+(z-%g)^2-0.09", n ? ", " : "",
                        c[0], c[1], c[2]);
    }
    snprintf(end, sizeof expr - (size_t)(end - expr), ")");
    iacsg_view v = view_of(160, 160, 1e-5);
    check_scene(tape == IACSG_TAPE_ALWAYS ? "a union of 32 spheres, interpreted" : "a union of 32 spheres", expr,
                grid_entry, grid_distance, NULL, &v, tape);
    check_grid_normals(expr, &v, tape);
}

TEST_FP(render_union_of_many_spheres) { check_grid(IACSG_TAPE_NEVER); }
TEST_FP(render_union_of_many_spheres_tape) { check_grid(IACSG_TAPE_ALWAYS); }
