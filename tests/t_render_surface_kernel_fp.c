/* tests/t_render_surface_kernel_fp.c -- the level-set surface stage (kernels/surface.h), compiled here as host C
 * with the same precision (and with interval Newton, as the device has it), over solids whose values along a
 * line are known exactly: planes, spheres and boxes.
 *
 * - surface_condition over random boxes against the host's point reference (scene_tree_eval) at points of the box:
 *   where the condition holds at a point the value may hold, where it fails it may fail.
 * - surface_first_root on random rays against long double references: a root of the surface solid where the
 *   condition certainly holds is never missed and never passed; every hit is within a few leaves of the surface
 *   where the condition may hold. Also a condition thinner than eps (a band around a sphere's equator), and the
 *   rays of blocks of pixels walking from their block's first coarse node (surface_block).
 * - The evaluation stack's bound: a chain of CSG_STACK_MAX comparisons is evaluated right, one more is refused
 *   when the scene is built, with the surface's place when it comes from the language.
 */
#include "kernels/scene_prims.h"
#include "t_scene_ref.h"

/* The solids the kernel calls scene_solid_F on (their numbers are reals of the working precision, so the long
 * double references see the same solids). */
#define MAX_SOLIDS 4
static ref_solid solids[MAX_SOLIDS];

/* The inclusion function the kernel calls: each variable occurs once per term, so it is tight over a box. */
static ia_interval scene_solid_F(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t) {
    (void)q, (void)t;
    const ref_solid *s = &solids[k];
    ia_interval p[3] = {x, y, z}, f = ia_point(0);
    for (int c = 0; c < 3; c++) {
        ia_real sc = (ia_real)s->c[c];
        if (s->kind == REF_HALFSPACE)
            f = ia_add(f, ia_mul_r(p[c], sc));
        else if (s->kind == REF_SPHERE)
            f = ia_add(f, ia_sqr(ia_sub(p[c], ia_point(sc))));
        else {
            ia_interval side = ia_sub(ia_abs(ia_sub(p[c], ia_point(sc))), ia_point((ia_real)s->a[c]));
            f = c == 0 ? side : ia_max(f, side);
        }
    }
    if (s->kind == REF_HALFSPACE)
        return ia_sub(f, ia_point((ia_real)s->r));
    if (s->kind == REF_SPHERE)
        return ia_sub(f, ia_sqr(ia_point((ia_real)s->r)));
    return f;
}

/* Its derivative along the direction (dx, dy, dz), for interval Newton (surface.h): the box's is the hull of its
 * three pieces' (Clarke's generalised derivative of the max lies in it, and the mean value theorem holds with
 * it). */
#define SCENE_SOLID_FD 1
static ia_interval scene_solid_Fd(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t,
                                  ia_interval dx, ia_interval dy, ia_interval dz, ia_interval *dt) {
    const ref_solid *s = &solids[k];
    ia_interval p[3] = {x, y, z}, v[3] = {dx, dy, dz}, der = ia_point(0);
    for (int c = 0; c < 3; c++) {
        ia_interval u = ia_sub(p[c], ia_point((ia_real)s->c[c]));
        if (s->kind == REF_HALFSPACE)
            der = ia_add(der, ia_mul_r(v[c], (ia_real)s->c[c]));
        else if (s->kind == REF_SPHERE)
            der = ia_add(der, ia_mul(ia_mul_r(u, 2), v[c]));
        else {
            ia_interval piece = u.lo > 0 ? v[c] : u.hi < 0 ? ia_neg(v[c]) : ia_hull(v[c], ia_neg(v[c]));
            der = c == 0 ? piece : ia_hull(der, piece);
        }
    }
    *dt = der;
    return scene_solid_F(q, k, x, y, z, t);
}

#include "kernels/surface.h"

/* ---- long double references */

static long double solid_on_ray(const ref_solid *s, const ref_ray *ray, long double t) {
    long double p[3];
    for (int c = 0; c < 3; c++)
        p[c] = ray->o[c] + t * ray->d[c];
    return ref_solid_at(s, p);
}

/* Every test solid is convex along a line: its minimum over [a, b] by golden section, its maximum at an end. */
static long double argmin_on_ray(const ref_solid *s, const ref_ray *ray, long double a, long double b) {
    const long double g = 0.6180339887498948482L;
    for (int k = 0; k < 200 && b - a > 0; k++) {
        long double m1 = b - g * (b - a), m2 = a + g * (b - a);
        if (solid_on_ray(s, ray, m1) <= solid_on_ray(s, ray, m2))
            b = m2;
        else
            a = m1;
    }
    return (a + b) / 2;
}

static void range_on_ray(const ref_solid *s, const ref_ray *ray, long double a, long double b, long double *lo,
                         long double *hi) {
    long double fa = solid_on_ray(s, ray, a), fb = solid_on_ray(s, ray, b);
    *lo = fminl(solid_on_ray(s, ray, argmin_on_ray(s, ray, a, b)), fminl(fa, fb));
    *hi = fmaxl(fa, fb);
}

/* The crossings of the solid's boundary by the ray in [a, b], in order; a ray that enters the solid by less
 * than `margin` (it may only graze it) has none. */
static int crossings(const ref_solid *s, const ref_ray *ray, long double a, long double b, long double margin,
                     long double roots[2]) {
    long double in, out;
    int n = 0;
    if (!ref_span(s, ray, -margin, &in, &out) || !ref_span(s, ray, 0, &in, &out))
        return 0;
    if (in >= a && in <= b)
        roots[n++] = in;
    if (out >= a && out <= b)
        roots[n++] = out;
    return n;
}

/* The condition's possible values (SURFACE_MAY_*) where solid k takes values in [lo[k], hi[k]]: the point
 * reference scene_tree_eval over every choice of sign the ranges allow. */
static int condition_over_ranges(const iacsg_scene *scene, int root, int nsolids, const long double *lo,
                                 const long double *hi) {
    int result = 0;
    for (int choice = 0; choice < 1 << (2 * nsolids); choice++) {
        signed char sign[MAX_SOLIDS];
        int possible = 1;
        for (int k = 0; k < nsolids; k++) {
            int c = choice >> (2 * k) & 3; /* 0: negative, 1: zero, 2: positive */
            possible &= c == 0 ? lo[k] < 0 : c == 1 ? lo[k] <= 0 && hi[k] >= 0 : c == 2 ? hi[k] > 0 : 0;
            sign[k] = (signed char)(c - 1);
        }
        if (possible)
            result |= scene_tree_eval(scene, root, sign) ? SURFACE_MAY_HOLD : SURFACE_MAY_FAIL;
    }
    return result;
}

/* ---- random scenes */

static ia_real uniform(test_rng_t *rng, double a, double b) { return (ia_real)(a + (b - a) * test_rand_unit(rng)); }

static void random_solid(test_rng_t *rng, ref_solid *s) {
    s->kind = (int)(test_rand_u64(rng) % 3);
    for (int c = 0; c < 3; c++) {
        s->c[c] = uniform(rng, -0.8, 0.8);
        s->a[c] = uniform(rng, 0.2, 1.2);
    }
    s->r = s->kind == REF_HALFSPACE ? uniform(rng, -0.5, 0.5) : uniform(rng, 0.3, 1.5);
}

/* A random condition tree over solids 1..nsolids-1 in preorder with relative operands, into nodes from *n. */
static void random_tree(test_rng_t *rng, int nsolids, int depth, uint32_t *nodes, int *n) {
    int self = (*n)++;
    unsigned pick = (unsigned)(test_rand_u64(rng) % 6);
    if (depth == 0 || pick < 2) {
        nodes[self] = CSG_NODE(pick % 2 ? CSG_OUTSIDE : CSG_INSIDE, 1 + test_rand_u64(rng) % (unsigned)(nsolids - 1));
        return;
    }
    if (pick == 5) {
        nodes[self] = CSG_NODE(CSG_NOT, 0);
        random_tree(rng, nsolids, depth - 1, nodes, n);
        return;
    }
    random_tree(rng, nsolids, depth - 1, nodes, n);
    nodes[self] = CSG_NODE(CSG_UNION + (int)(pick - 2), (uint32_t)*n);
    random_tree(rng, nsolids, depth - 1, nodes, n);
}

/* A scene of nsolids random solids (solids[]) and one random condition; returns its root in scene->nodes. */
static int random_scene(test_rng_t *rng, int nsolids, iacsg_scene **scene) {
    for (int k = 0; k < nsolids; k++)
        random_solid(rng, &solids[k]);
    uint32_t nodes[64];
    int n = 0;
    random_tree(rng, nsolids, 3, nodes, &n);
    *scene = scene_create();
    CHECK(*scene, "out of memory");
    int root = scene_add_tree(*scene, nodes, n, NULL);
    CHECK(root == 0, "scene_add_tree failed");
    return root;
}

/* The exact range of every solid over the float ray's points t in [a, b], each widened by the solid's change
 * over `spread` (the box the kernel evaluates reaches that far from the segment) */
static void ranges_on_segment(int nsolids, const ref_ray *ray, long double a, long double b, long double spread,
                              long double *lo, long double *hi) {
    for (int k = 0; k < nsolids; k++) {
        range_on_ray(&solids[k], ray, a, b, &lo[k], &hi[k]);
        long double slope = 1;
        if (solids[k].kind == REF_SPHERE)
            slope = 2 * (8 + fabsl((long double)solids[k].r)); /* |grad| <= 2 |p - c| in the test's space */
        else if (solids[k].kind == REF_HALFSPACE)
            slope = fabsl((long double)solids[k].c[0]) + fabsl((long double)solids[k].c[1]) +
                    fabsl((long double)solids[k].c[2]);
        lo[k] -= slope * spread;
        hi[k] += slope * spread;
    }
}

TEST_FP(render_surface_condition_encloses_points) {
    test_rng_t *rng = test_rng();
    long holds = 0, fails = 0, undecided = 0, n = test_iters(20000);
    kernel_u32 evals = 0;
    for (long it = 0; it < n; it++) {
        iacsg_scene *scene;
        int nsolids = 2 + (int)(test_rand_u64(rng) % 3), root = random_scene(rng, nsolids, &scene);
        ia_interval box[3];
        for (int c = 0; c < 3; c++) {
            ia_real a = uniform(rng, -2, 2), w = uniform(rng, 0, test_rand_unit(rng) < 0.5 ? 0.05 : 1);
            box[c] = ia_make(a, a + w);
        }
        int v = surface_condition(scene->nodes, 0, root, csg_tree_last(scene->nodes, root), box, ia_point(0), &evals);
        holds += v == SURFACE_MAY_HOLD, fails += v == SURFACE_MAY_FAIL, undecided += v == 3;
        for (int s = 0; s < 8; s++) {
            long double p[3];
            signed char sign[MAX_SOLIDS];
            for (int c = 0; c < 3; c++)
                p[c] = (long double)box[c].lo + test_rand_unit(rng) * ((long double)box[c].hi - box[c].lo);
            for (int k = 0; k < nsolids; k++) {
                long double f = ref_solid_at(&solids[k], p);
                sign[k] = (signed char)((f > 0) - (f < 0));
            }
            int at_point = scene_tree_eval(scene, root, sign) ? SURFACE_MAY_HOLD : SURFACE_MAY_FAIL;
            CHECK(v & at_point, "case %ld: the condition %s at a point of the box, the enclosure says %d", it,
                  at_point == SURFACE_MAY_HOLD ? "holds" : "fails", v);
        }
        iacsg_scene_destroy(scene);
    }
    test_note("%ld boxes: %ld certainly hold, %ld certainly fail, %ld undecided", n, holds, fails, undecided);
    CHECK(holds > n / 20 && fails > n / 20 && undecided > n / 20, "a kind of value is too rare to test");
}

/* What the checks of surface rays saw. */
typedef struct {
    long rays, kept, hits, dropped;
} surface_tally;

#define SURFACE_EPS IA_R(0x1p-12)
#define SURFACE_TINY 1e-12L /* the long double references' own error, far below the working precision's */

/* Checks what the kernel found on the ray o + t d, t in [t_near, t_far] (hit, with the leaf [lo, hi]), for the
 * surface of solid 0 kept where the condition at `condition` of the scene holds (-1: everywhere), against the
 * exact references: a crossing of solid 0 where the condition certainly holds is never missed nor passed; a hit
 * is a leaf of at most eps where, widened by a leaf's reach, solid 0 may be 0 and the condition may hold. */
static void check_surface_hit(const iacsg_scene *scene, int nsolids, int condition, const ia_real o[3],
                              const ia_real d[3], ia_real t_near, ia_real t_far, int hit, ia_real lo, ia_real hi,
                              surface_tally *tally) {
    const ia_real eps = SURFACE_EPS;
    ref_ray ray;
    for (int c = 0; c < 3; c++) {
        ray.o[c] = o[c];
        ray.d[c] = d[c];
    }
    /* the first crossing of the surface solid where the condition certainly holds */
    long double roots[2], first_kept = INFINITY;
    int nroots = crossings(&solids[0], &ray, t_near, t_far, SURFACE_TINY, roots);
    for (int r = nroots - 1; r >= 0; r--) {
        long double glo[MAX_SOLIDS], ghi[MAX_SOLIDS];
        ranges_on_segment(nsolids, &ray, roots[r], roots[r], SURFACE_TINY, glo, ghi);
        int v = condition < 0 ? SURFACE_CERTAIN : condition_over_ranges(scene, condition, nsolids, glo, ghi);
        if (v == SURFACE_CERTAIN)
            first_kept = roots[r];
        tally->dropped += v == SURFACE_MAY_FAIL;
    }
    long it = tally->rays++;
    tally->kept += first_kept < INFINITY;
    tally->hits += hit;
    CHECK(hit || first_kept == INFINITY, "ray %ld: missed the kept root at t = %.17Lg", it, first_kept);
    CHECK(!hit || lo <= first_kept + SURFACE_TINY, "ray %ld: hit at %.9g, after the kept root at %.17Lg", it,
          (double)lo, first_kept);
    if (!hit)
        return;
    CHECK(hi - lo <= eps && t_near <= lo && hi <= t_far, "ray %ld: leaf [%a, %a] wider than eps or outside", it,
          (double)lo, (double)hi);
    long double glo[MAX_SOLIDS], ghi[MAX_SOLIDS], spread = 2 * (long double)eps;
    ranges_on_segment(nsolids, &ray, lo, hi, spread, glo, ghi);
    CHECK(glo[0] <= 0 && ghi[0] >= 0, "ray %ld: hit [%a, %a] where the surface solid is in [%Lg, %Lg]", it,
          (double)lo, (double)hi, glo[0], ghi[0]);
    CHECK(condition < 0 || condition_over_ranges(scene, condition, nsolids, glo, ghi) & SURFACE_MAY_HOLD,
          "ray %ld: hit [%a, %a] where the condition certainly fails", it, (double)lo, (double)hi);
}

/* surface_first_root on the ray, checked. */
static void check_surface_ray(const iacsg_scene *scene, int nsolids, int condition, const ia_real o[3],
                              const ia_real d[3], ia_real t_near, ia_real t_far, surface_tally *tally) {
    ia_real lo = 0, hi = 0;
    kernel_u32 evals = 0;
    int hit = surface_first_root(o, d, t_near, t_far, SURFACE_EPS, 0, condition, scene->nodes, 0, ia_point(0), &lo,
                                 &hi, &evals);
    check_surface_hit(scene, nsolids, condition, o, d, t_near, t_far, hit, lo, hi, tally);
}

/* A unit direction in the working precision from `from` towards `to`. */
static void direction(const ia_real from[3], const ia_real to[3], ia_real d[3]) {
    ia_real len = 0;
    for (int c = 0; c < 3; c++) {
        d[c] = to[c] - from[c];
        len += d[c] * d[c];
    }
    len = sqrt(len);
    for (int c = 0; c < 3; c++)
        d[c] /= len;
}

TEST_FP(render_surface_first_root_vs_exact) {
    test_rng_t *rng = test_rng();
    surface_tally tally = {0};
    long n = test_iters(3000);
    for (long it = 0; it < n; it++) {
        iacsg_scene *scene;
        int nsolids = 2 + (int)(test_rand_u64(rng) % 3), root = random_scene(rng, nsolids, &scene);
        /* a ray from a point around the scene towards a point near its middle */
        ia_real o[3], to[3], d[3];
        for (int c = 0; c < 3; c++) {
            o[c] = uniform(rng, -4, 4);
            to[c] = uniform(rng, -0.7, 0.7);
        }
        direction(o, to, d);
        ia_real t_near = uniform(rng, 0, 1), t_far = t_near + uniform(rng, 4, 8);
        check_surface_ray(scene, nsolids, test_rand_u64(rng) % 8 ? root : -1, o, d, t_near, t_far, &tally);
        iacsg_scene_destroy(scene);
    }
    test_note("%ld rays: %ld with a kept root, %ld hits, %ld roots dropped by their condition", n, tally.kept,
              tally.hits, tally.dropped);
    CHECK(tally.kept > n / 10 && tally.dropped > n / 10, "too few kept or dropped roots to test");
}

/* A condition thinner than eps: the unit sphere kept in the slab |z| < 2^-15 (an eighth of eps), a band around
 * its equator. Rays aimed at points of the equator cross the sphere inside the band: none may be missed. */
TEST_FP(render_surface_thin_condition) {
    test_rng_t *rng = test_rng();
    solids[0] = ref_sphere(0, 0, 0, 1);
    solids[1] = ref_box(0, 0, 0, 2, 2, 0x1p-15);
    iacsg_scene *scene = scene_create();
    CHECK(scene, "out of memory");
    uint32_t inside_slab = CSG_NODE(CSG_INSIDE, 1);
    int root = scene_add_tree(scene, &inside_slab, 1, NULL);
    surface_tally tally = {0};
    long n = test_iters(2000);
    for (long it = 0; it < n; it++) {
        double phi = 6.283185307179586 * test_rand_unit(rng), elevation = 1.4 * test_rand_unit(rng) - 0.7;
        ia_real to[3] = {(ia_real)cos(phi), (ia_real)sin(phi), 0}, o[3], d[3];
        for (int c = 0; c < 3; c++) /* from outside, on the side of the point the ray aims at */
            o[c] = to[c] * (ia_real)3 + (c == 2 ? (ia_real)(3 * elevation) : uniform(rng, -1, 1));
        direction(o, to, d);
        check_surface_ray(scene, 2, root, o, d, 0, 6, &tally);
    }
    iacsg_scene_destroy(scene);
    test_note("%ld rays at the equator: %ld with a kept root, %ld hits", n, tally.kept, tally.hits);
    CHECK(tally.kept > n / 2, "only %ld of %ld rays cross the band where it certainly holds", tally.kept, n);
}

/* Coarse to fine: the rays of random 4x4 blocks of pixels (kernels/camera.h) start their walks of the frame's
 * tree at the block's first coarse node (surface_block, over the box of the block's rays), or are misses when it
 * has none; each ray is checked as above. Counts how deep in the tree the rays start. */
TEST_FP(render_surface_block_start) {
    test_rng_t *rng = test_rng();
    surface_tally tally = {0};
    long blocks = test_iters(400), skipped = 0, empty = 0;
    kernel_u32 evals = 0;
    for (long it = 0; it < blocks; it++) {
        iacsg_scene *scene;
        int nsolids = 2 + (int)(test_rand_u64(rng) % 3), root = random_scene(rng, nsolids, &scene);
        int condition = test_rand_u64(rng) % 8 ? root : -1, ortho = test_rand_u64(rng) % 4 == 0;
        iacsg_view view = {.width = 64, .height = 64};
        view.camera = (iacsg_camera){.eye = {uniform(rng, -4, 4), uniform(rng, -4, 4), uniform(rng, 2, 4)},
                                     .up = {0, 0, 1}, .fov = 40, .ortho_height = ortho ? 3 : 0};
        ia_real p[PARAM_COUNT];
        view_params(&view, p);
        p[PARAM_TMIN] = 0;
        p[PARAM_TMAX] = 9;
        p[PARAM_EPS] = SURFACE_EPS;
        int i0 = 4 * (int)(test_rand_u64(rng) % 16), j0 = 4 * (int)(test_rand_u64(rng) % 16);
        surface_start start;
        surface_block(p, ortho, i0, i0 + 3, j0, j0 + 3, 64, 64, 0, condition, scene->nodes, 0, ia_point(0), &start,
                      &evals);
        empty += start.level < 0;
        for (int k = 0; k < 16; k++) {
            ia_real o[3], d[3], t_near = uniform(rng, 0, 1), t_far = uniform(rng, 6, 9), lo = 0, hi = 0;
            camera_ray(p, ortho, i0 + k % 4, j0 + k / 4, 64, 64, o, d);
            int hit = surface_first_root_from(&start, o, d, t_near, t_far, SURFACE_EPS, 0, condition, scene->nodes, 0,
                                              ia_point(0), &lo, &hi, &evals);
            skipped += start.level > 0 ? start.level : 0;
            check_surface_hit(scene, nsolids, condition, o, d, t_near, t_far, hit, lo, hi, &tally);
        }
        iacsg_scene_destroy(scene);
    }
    test_note("%ld blocks (%ld proven empty), %ld rays: %ld with a kept root, %ld hits; rays started %.1f levels "
              "down",
              blocks, empty, tally.rays, tally.kept, tally.hits, (double)skipped / (double)tally.rays);
    CHECK(tally.kept > tally.rays / 10 && empty > 0 && skipped > tally.rays, "too few cases of each kind");
}

/* A chain c0 & c1 & ... of k comparisons (left deep, as the parser builds it) over solids 0 and 1. */
static int chain(iacsg_scene *scene, int k, int op) {
    uint32_t nodes[2 * CSG_STACK_MAX + 4];
    int n = 0;
    for (int j = 0; j < k - 1; j++)
        nodes[n++] = CSG_NODE(op, 0); /* right operands set below */
    nodes[n++] = CSG_NODE(CSG_INSIDE, 0);
    for (int j = k - 2; j >= 0; j--) { /* node j's right child follows node j+1's subtree */
        nodes[j] = CSG_NODE(op, (uint32_t)n);
        nodes[n++] = CSG_NODE((k - j) % 2 ? CSG_OUTSIDE : CSG_INSIDE, (uint32_t)(j % 2));
    }
    return scene_add_tree(scene, nodes, n, NULL);
}

TEST_FP(render_surface_condition_stack_bound) {
    solids[0] = ref_halfspace(1, 0, 0, 0); /* x < 0 */
    solids[1] = ref_halfspace(0, 1, 0, 0); /* y < 0 */
    iacsg_scene *scene = scene_create();
    CHECK(scene, "out of memory");
    int ops[2] = {CSG_INTERSECT, CSG_UNION};
    kernel_u32 evals = 0;
    for (int o = 0; o < 2; o++) {
        int fits = chain(scene, CSG_STACK_MAX, ops[o]), over = chain(scene, CSG_STACK_MAX + 1, ops[o]);
        CHECK(fits >= 0 && over >= 0, "scene_add_tree failed");
        CHECK(csg_stack_need(scene->nodes, fits) == CSG_STACK_MAX, "a chain of %d needs %d", CSG_STACK_MAX,
              csg_stack_need(scene->nodes, fits));
        iacsg_error err = {0};
        CHECK(scene_add_surface(scene, "fits", 0, fits, -1, &err) >= 0, "a chain of %d refused: %s", CSG_STACK_MAX,
              err.message);
        CHECK(scene_add_surface(scene, "over", 0, over, -1, &err) < 0, "a chain of %d accepted",
              CSG_STACK_MAX + 1);
        if (o == 0)
            test_note("%s", err.message);
        /* at points of each quadrant (boxes inside it) the chain's value matches the point reference */
        for (int q = 0; q < 4; q++) {
            ia_real sx = q & 1 ? 1 : -1, sy = q & 2 ? 1 : -1;
            ia_interval box[3] = {ia_make(sx * IA_R(0.5), sx * IA_R(0.5)), ia_make(sy * IA_R(0.25), sy * IA_R(0.25)),
                                  ia_point(0)};
            signed char sign[2] = {(signed char)sx, (signed char)sy};
            int want = scene_tree_eval(scene, fits, sign) ? SURFACE_MAY_HOLD : SURFACE_MAY_FAIL;
            int got =
                surface_condition(scene->nodes, 0, fits, csg_tree_last(scene->nodes, fits), box, ia_point(0), &evals);
            CHECK(got == want, "quadrant %d: the chain gives %d, the reference %d", q, got, want);
        }
    }
    iacsg_scene_destroy(scene);
    /* from the language: the refusal names the surface's line */
    char text[2048] = "solid a = sphere\nsurface deep = a where x < 0";
    for (int k = 1; k <= CSG_STACK_MAX; k++)
        snprintf(text + strlen(text), sizeof text - strlen(text), " & x - %d < 0", k);
    iacsg_error err = {0};
    CHECK(iacsg_scene_parse(text, "deep.csg", &scene, &err) != IACSG_OK && scene == NULL, "a chain of %d accepted",
          CSG_STACK_MAX + 1);
    CHECK(err.line == 2 && err.column == 1 && strstr(err.message, "'deep'"), "%d:%d: %s", err.line, err.column,
          err.message);
}
