/* tests/t_render_util.h -- what the render tests share: the analytic sphere, and the kernel's parameter block
 * rebuilt on the host so that kernels/camera.h, compiled here as C, gives the very float rays the device traced.
 * For tests/t_render*_fp.c (ia_real follows IA_FP64). */
#ifndef T_RENDER_UTIL_H
#define T_RENDER_UTIL_H
#include "kernels/camera.h"
#include "render.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    double c[3], r; /* dyadic values, exact in float and double */
} sphere;

/* What the hand-written expressions of the tests build from two spheres. */
typedef enum { SOLID_A, SOLID_UNION, SOLID_INTER, SOLID_DIFF } solid_op;

/* OpenCL C for the CSG of spheres a and b: F, Fv, f and its gradient at a point and over lanes, as the compiler
 * would emit them. */
static inline char *spheres_cl(sphere a, sphere b, solid_op op) {
    static const char *ops_F[] = {"a", "ia_min(a, b)", "ia_max(a, b)", "ia_max(a, ia_neg(b))"};
    static const char *ops_Fv[] = {"a", "iav_min(a, b)", "iav_max(a, b)", "iav_max(a, iav_neg(b))"};
    static const char *ops_f[] = {"a", "fmin(a, b)", "fmax(a, b)", "fmax(a, -b)"};
    /* The gradient of the branch that min/max selects; for the difference, -grad b when -b wins. */
    static const char *ops_g[] = {"1", "a <= b", "a >= b", "a >= -b"};
    static const char *ops_gv[] = {"(ia_maskv)-1", "a <= b", "a >= b", "a >= -b"};
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
             "#ifdef IA_VW\n"
             "IA_FN iav sph_Fv(iav x, iav y, iav z, ia_real cx, ia_real cy, ia_real cz, ia_real r) {\n"
             "  return iav_add_r(iav_add(iav_add(iav_sqr(iav_add_r(x, -cx)), iav_sqr(iav_add_r(y, -cy))),"
             " iav_sqr(iav_add_r(z, -cz))), -r * r);\n}\n"
             "IA_FN iav iacsg_Fv(iav x, iav y, iav z, iav t) {\n"
             "  iav a = sph_Fv(x, y, z, SA), b = sph_Fv(x, y, z, SB); (void)t; (void)b; return %s;\n}\n"
             "IA_FN ia_realv sph_fv(ia_realv x, ia_realv y, ia_realv z, ia_real cx, ia_real cy, ia_real cz, ia_real r)"
             " {\n"
             "  return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) - r * r;\n}\n"
             "IA_FN ia_realv iacsg_f_gradv(ia_realv x, ia_realv y, ia_realv z, ia_realv t, ia_realv g[3]) {\n"
             "  ia_realv a = sph_fv(x, y, z, SA), b = sph_fv(x, y, z, SB), p[3] = {x, y, z}; (void)t;\n"
             "  ia_real ca[4] = {SA}, cb[4] = {SB}; ia_maskv use_a = %s;\n"
             "  ia_realv sg = select(IAV_R(%s), IAV_R(1), use_a);\n"
             "  for (int c = 0; c < 3; c++)\n"
             "    g[c] = sg * 2 * (p[c] - select(IAV_R(cb[c]), IAV_R(ca[c]), use_a));\n"
             "  return %s;\n}\n"
             "#endif\n"
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
             a.c[0], a.c[1], a.c[2], a.r, b.c[0], b.c[1], b.c[2], b.r, ops_F[op], ops_Fv[op], ops_gv[op], ops_gs[op],
             ops_f[op], ops_f[op], ops_g[op], ops_gs[op]);
    return s;
}

/* The exact solutions of |o + t d - c| = r for the double values of the float ray: the inside interval
 * [*t1, *t2]; returns 0 if the ray misses. */
static inline int sphere_span(sphere s, const double o[3], const double d[3], double *t1, double *t2) {
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

/* The distance from p to the surface of sphere s. */
static inline double sphere_surface_distance(sphere s, const double p[3]) {
    double dx = p[0] - s.c[0], dy = p[1] - s.c[1], dz = p[2] - s.c[2];
    return fabs(sqrt(dx * dx + dy * dy + dz * dz) - s.r);
}

/* How far from every primitive's surface a reported depth may lie before it is a ghost (a hit where there is no
 * surface). The kernel returns a leaf of at most eps along a unit ray whose box holds 0 in F's enclosure. In the
 * render tests each primitive's enclosure is its exact range over a box up to a few ulps (sums of squares of
 * separate coordinates, sqrt and abs of them), so on a box where every primitive keeps one sign min and max are
 * one-signed too and the box is rejected: an accepted box touches some primitive's surface, and the point at
 * the leaf's start is within the box's diagonal, eps, of it. 2 eps + 1e-5 leaves room for rounding (float
 * coordinates of a few units, F near 0 off by ~1e-6). The boundary of any CSG of the primitives lies on their
 * surfaces, so the nearest primitive surface is never farther than the solid's. */
static inline double ghost_margin(double eps) { return 2 * eps + 1e-5; }

/* The exact (double) part of the ray inside the bounds, t >= 0. */
static inline int ray_box_span(const double b[6], const double o[3], const double d[3], double *tn, double *tf) {
    *tn = 0;
    *tf = INFINITY;
    for (int k = 0; k < 3; k++) {
        if (d[k] == 0) {
            if (o[k] < b[k] || o[k] > b[k + 3])
                return 0;
            continue;
        }
        double t1 = (b[k] - o[k]) / d[k], t2 = (b[k + 3] - o[k]) / d[k];
        *tn = fmax(*tn, fmin(t1, t2));
        *tf = fmin(*tf, fmax(t1, t2));
    }
    return *tn < *tf;
}

/* The camera part of the parameter block, in the working precision, as src/render.c fills it. */
static inline void view_params(const iacsg_view *view, ia_real p[PARAM_COUNT]) {
    double pd[PARAM_COUNT] = {0};
    iacsg_error err = {0};
    CHECK(iacsg_camera_params(&view->camera, view->width, view->height, pd, &err) == IACSG_OK, "%s", err.message);
    for (int k = 0; k < PARAM_COUNT; k++)
        p[k] = (ia_real)pd[k];
}

/* A random view (up to 300x300, perspective or orthographic), one random tile of it and a random span [a, b] of
 * ray parameters: what the tile-box tests check each pixel ray of the tile against. */
typedef struct {
    int ortho, w, h, i0, i1, j0, j1;
    ia_real p[PARAM_COUNT], a, b;
} random_tile;

static inline double test_uniform(test_rng_t *rng, double lo, double hi) {
    return lo + (hi - lo) * test_rand_unit(rng);
}

/* Draws *t; 0 for a degenerate view (the eye at the target, up along the view), which the caller skips. */
static inline int random_tile_draw(test_rng_t *rng, random_tile *t) {
    int ortho = (int)(test_rand_u64(rng) & 1), w = 1 + (int)(test_rand_u64(rng) % 300),
        h = 1 + (int)(test_rand_u64(rng) % 300);
    iacsg_view v = {.width = w, .height = h,
                    .camera = {.eye = {test_uniform(rng, -5, 5), test_uniform(rng, -5, 5), test_uniform(rng, -5, 5)},
                               .at = {test_uniform(rng, -1, 1), test_uniform(rng, -1, 1), test_uniform(rng, -1, 1)},
                               .up = {test_uniform(rng, -1, 1), test_uniform(rng, -1, 1), 1},
                               .fov = test_uniform(rng, 5, 150),
                               .ortho_height = ortho ? test_uniform(rng, 0.1, 8) : 0}};
    double pd[PARAM_COUNT];
    iacsg_error err = {0};
    if (iacsg_camera_params(&v.camera, w, h, pd, &err) != IACSG_OK)
        return 0;
    view_params(&v, t->p);
    int tx = (int)(test_rand_u64(rng) % (unsigned)((w + TILE_SIZE - 1) / TILE_SIZE));
    int ty = (int)(test_rand_u64(rng) % (unsigned)((h + TILE_SIZE - 1) / TILE_SIZE));
    t->ortho = ortho;
    t->w = w;
    t->h = h;
    t->i0 = tx * TILE_SIZE;
    t->j0 = ty * TILE_SIZE;
    t->i1 = (t->i0 + TILE_SIZE < w ? t->i0 + TILE_SIZE : w) - 1;
    t->j1 = (t->j0 + TILE_SIZE < h ? t->j0 + TILE_SIZE : h) - 1;
    t->a = (ia_real)test_uniform(rng, 0, 10);
    t->b = t->a + (ia_real)test_uniform(rng, 0, 1);
    return 1;
}

/* A random -aa sample of pixel (i, j): cell (a, b) of an N x N grid, N from 2 to 16, its doubled column and row as
 * kernels/effects.cl computes them. */
static inline void random_sample(test_rng_t *rng, int i, int j, ia_real *x2, ia_real *y2) {
    int n = 2 + (int)(test_rand_u64(rng) % 15), a = (int)(test_rand_u64(rng) % (unsigned)n),
        b = (int)(test_rand_u64(rng) % (unsigned)n);
    *x2 = (ia_real)(2 * i) + (ia_real)(2 * a + 1) / (ia_real)n;
    *y2 = (ia_real)(2 * j) + (ia_real)(2 * b + 1) / (ia_real)n;
}

/* The OpenCL C the compiler emits for expr, which must carry the derivative code of interval Newton (the
 * caller free()s it). */
static inline char *newton_expr_cl(const char *expr) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    char *cl = NULL;
    CHECK(iacsg_expr_parse(expr, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_status st = iacsg_expr_emit_cl(e, "iacsg", &cl, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s", err.message);
    CHECK(strstr(cl, "IACSG_FDV"), "'%s': no derivative code, so no interval Newton to test", expr);
    return cl;
}

/* Pixel (i, j)'s float ray, exactly as the device traced it (camera.h over the same parameter block), in
 * double for the exact intersections. */
static inline void pixel_ray(const ia_real p[PARAM_COUNT], const iacsg_view *view, int i, int j, double o[3],
                             double d[3]) {
    ia_real of[3], df[3];
    camera_ray(p, view->camera.ortho_height > 0, i, j, view->width, view->height, of, df);
    for (int k = 0; k < 3; k++) {
        o[k] = of[k];
        d[k] = df[k];
    }
}

/* Builds the hand-written expression `cl` and renders it; failures end the test. */
static inline void render_cl(const char *cl, const iacsg_render_config *config, const iacsg_view *view,
                             iacsg_frame *frame) {
    iacsg_error err = {0};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create(cl, config, &r, &err);
    CHECK(st == IACSG_OK, "renderer: %s", err.message);
    st = iacsg_render(r, view, frame, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "render: %s", err.message);
}

/* Compiles the expression `expr` of the language and renders it; failures end the test. */
static inline void render_expr_text(const char *expr, const iacsg_render_config *config, const iacsg_view *view,
                                    iacsg_frame *frame) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(expr, "<test>", &e, &err) == IACSG_OK, "%s: %s", expr, err.message);
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s: %s", expr, err.message);
    st = iacsg_render(r, view, frame, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s: %s", expr, err.message);
}

#endif
