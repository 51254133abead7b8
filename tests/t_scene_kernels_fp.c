/* tests/t_scene_kernels_fp.c -- the segment path's kernel stages compiled here as host C (as the device runs
 * them), with the host evaluator (iacsg_expr_eval_box, the same ia/ code) as the solids' inclusion function:
 *
 * - classify_tree in three-valued logic against every in/out assignment of the undecided solids (scene_tree_eval),
 *   on random trees, as the scene has them and relinearised for the device (src/scene_tables.c): sound, and exact
 *   where no undecided solid occurs twice;
 * - the relinearised trees' stack need, for chains of 1000 differences and unions either way round;
 * - scene_trace_ray (BVH, walks, weave) on random rays through random spheres, against their exact entry points
 *   in long double: never after the first point of a region, never a miss.
 */
#include "implicits/scene.h"
#include "scene_tables.h"
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

static const iacsg_scene *host_scene;

/* The device's scene_solid_F, by the host evaluator over the same box (its bounds are reals of the working
 * precision, so exact doubles). */
static ia_interval scene_solid_F(int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t) {
    double lo[3] = {x.lo, y.lo, z.lo}, hi[3] = {x.hi, y.hi, z.hi}, out[2];
    iacsg_error err = {0};
    if (iacsg_expr_eval_box(host_scene->solids[k].expr, FP64, lo, hi, t.lo, out, &err) != IACSG_OK)
        return ia_make(-IA_INF, IA_INF);
    return ia_make((ia_real)out[0], (ia_real)out[1]);
}

#include "kernels/scene_trace.h"

/* A random tree over nsolids solids with `leaves` leaves, relative indices (scene_add_tree), into nodes. */
static int random_tree(test_rng_t *rng, int leaves, int nsolids, uint32_t *nodes, int n) {
    if (leaves == 1) {
        nodes[n] = CSG_NODE(CSG_INSIDE, test_rand_u64(rng) % (uint64_t)nsolids);
        return n + 1;
    }
    int left = 1 + (int)(test_rand_u64(rng) % (uint64_t)(leaves - 1)), here = n;
    static const int ops[3] = {CSG_UNION, CSG_INTERSECT, CSG_DIFFERENCE};
    n = random_tree(rng, left, nsolids, nodes, n + 1);
    nodes[here] = CSG_NODE(ops[test_rand_u64(rng) % 3], n);
    return random_tree(rng, leaves - left, nsolids, nodes, n);
}

static iacsg_expr *parse(const char *text) {
    iacsg_expr *e = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse(text, "<t>", &e, &err) == IACSG_OK, "%s", err.message);
    return e;
}

/* Whether some BOUNDARY solid occurs in two leaves of the tree. */
static int repeats(const uint32_t *nodes, int n, const unsigned char *state) {
    int seen[8] = {0};
    for (int k = 0; k < n; k++) {
        int op = CSG_NODE_OP(nodes[k]), solid = (int)CSG_NODE_ARG(nodes[k]);
        if (op == CSG_INSIDE && state[solid] == SCENE_BOUNDARY && seen[solid]++)
            return 1;
    }
    return 0;
}

/* For random trees and states: classify_tree's two bits hold "in for some assignment of the BOUNDARY solids" and
 * "out for some" (exactly so where no BOUNDARY solid repeats), the same on the scene's nodes and the device's. */
TEST_FP(scene_classify_three_valued) {
    enum { SOLIDS = 5 };
    test_rng_t *rng = test_rng();
    iacsg_error err = {0};
    long trees = test_iters(200), checked = 0, exact = 0;
    for (long it = 0; it < trees; it++) {
        iacsg_scene *s = scene_create();
        for (int k = 0; k < SOLIDS; k++)
            scene_add_solid(s, NULL, parse("sphere"), &err);
        uint32_t nodes[64];
        int n = random_tree(rng, 1 + (int)(test_rand_u64(rng) % 12), SOLIDS, nodes, 0);
        int root = scene_add_tree(s, nodes, n, &err);
        CHECK(root >= 0 && scene_add_region(s, NULL, root, -1, &err) == 0, "%s", err.message);
        scene_tables t;
        CHECK(scene_tables_build(s, &t, &err) == IACSG_OK, "%s", err.message);
        for (int code = 0; code < 243; code++) { /* every state of 5 solids */
            unsigned char state[SOLIDS];
            int c = code, boundary[SOLIDS], nb = 0;
            for (int k = 0; k < SOLIDS; k++, c /= 3) {
                state[k] = (unsigned char)(c % 3);
                if (state[k] == SCENE_BOUNDARY)
                    boundary[nb++] = k;
            }
            int may_in = 0, may_out = 0;
            for (int a = 0; a < 1 << nb; a++) {
                signed char sign[SOLIDS];
                for (int k = 0; k < SOLIDS; k++)
                    sign[k] = state[k] == SCENE_IN ? -1 : 1;
                for (int b = 0; b < nb; b++)
                    sign[boundary[b]] = a >> b & 1 ? -1 : 1;
                int v = scene_tree_eval(s, root, sign);
                may_in |= v;
                may_out |= !v;
            }
            int expect = (may_in ? CLASSIFY_MAY_IN : 0) | (may_out ? CLASSIFY_MAY_OUT : 0);
            int got = classify_tree(s->nodes, root, n, state);
            int device = classify_tree(t.nodes, t.items[SCENE_ITEM_ROOT], t.items[SCENE_ITEM_SIZE], state);
            /* sound always; exact unless an undecided solid occurs twice (a \ a may be in, say the bits) */
            CHECK((got & expect) == expect && device == got && (got == expect || repeats(nodes, n, state)),
                  "tree %ld, states %d: %d and %d on the device's nodes, exact %d", it, code, got, device, expect);
            exact += got == expect;
            checked++;
        }
        scene_tables_free(&t);
        iacsg_scene_destroy(s);
    }
    test_note("%ld trees, %ld states, %ld of them exact", trees, checked, exact);
}

/* Left-deep chains of 1000 differences and of 1000 unions, which a plain evaluation from the last node would
 * stack 1000 deep: the device's order needs 2. */
TEST_FP(scene_classify_stack_bound) {
    enum { CHAIN = 1000 };
    iacsg_error err = {0};
    for (int op = 0; op < 2; op++) {
        iacsg_scene *s = scene_create();
        scene_add_solid(s, NULL, parse("sphere"), &err);
        static uint32_t nodes[2 * CHAIN + 1];
        for (int k = 0; k < CHAIN; k++) /* ((a op a) op a) op ...: node k's right child is the leaf at 2 CHAIN - k */
            nodes[k] = CSG_NODE(op ? CSG_UNION : CSG_DIFFERENCE, 2 * CHAIN - k);
        for (int k = CHAIN; k <= 2 * CHAIN; k++)
            nodes[k] = CSG_NODE(CSG_INSIDE, 0);
        int root = scene_add_tree(s, nodes, 2 * CHAIN + 1, &err);
        CHECK(root >= 0 && scene_add_region(s, NULL, root, -1, &err) == 0, "%s", err.message);
        scene_tables t;
        CHECK(scene_tables_build(s, &t, &err) == IACSG_OK, "%s", err.message);
        int depth = 0, need = 0, size = t.items[SCENE_ITEM_SIZE], first = t.items[SCENE_ITEM_ROOT];
        for (int k = first + size - 1; k >= first; k--) {
            int o = CSG_NODE_OP(t.nodes[k]);
            depth += o == CSG_INSIDE ? 1 : o == CSG_NOT ? 0 : -1;
            need = depth > need ? depth : need;
        }
        CHECK(need <= 2, "%s chain: stack %d", op ? "union" : "difference", need);
        unsigned char in[1] = {SCENE_IN};
        CHECK(classify_tree(t.nodes, first, size, in) == (op ? CLASSIFY_MAY_IN : CLASSIFY_MAY_OUT), "value");
        scene_tables_free(&t);
        iacsg_scene_destroy(s);
    }
}

/* The exact inside (a, b) of a sphere along the ray in long double; 0 if none. */
static int sphere_inside(const double c[3], double r, const long double o[3], const long double d[3], long double *a,
                         long double *b) {
    long double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
    long double qa = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], qb = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    long double disc = qb * qb - qa * (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - (long double)r * r);
    if (disc <= 0)
        return 0;
    long double q = -(qb + copysignl(sqrtl(disc), qb));
    *a = fminl(q / qa, (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - (long double)r * r) / q);
    *b = fmaxl(q / qa, (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - (long double)r * r) / q);
    return 1;
}

/* Random rays through 24 random spheres, each its own region: the trace's hit is never after the first sphere
 * entry (nor a miss), and its id is that sphere's unless another sphere's boundary is within 4 eps. */
TEST_FP(scene_trace_spheres) {
    enum { N = 24 };
    test_rng_t *rng = test_rng();
    iacsg_error err = {0};
    iacsg_scene *s = scene_create();
    double c[N][3], r[N];
    for (int k = 0; k < N; k++) {
        char text[256];
        for (int a = 0; a < 3; a++) /* dyadic centres and radii: the same reals in every precision */
            c[k][a] = ldexp(floor(ldexp(test_rand_unit(rng) * 2 - 1, 10)), -10);
        r[k] = ldexp(floor(ldexp(0.05 + 0.25 * test_rand_unit(rng), 10)), -10);
        snprintf(text, sizeof text, "(x - %.20g)^2 + (y - %.20g)^2 + (z - %.20g)^2 - %.30g", c[k][0], c[k][1], c[k][2],
                 r[k] * r[k]);
        scene_add_solid(s, NULL, parse(text), &err);
        uint32_t leaf = CSG_NODE(CSG_INSIDE, k);
        scene_add_region(s, NULL, scene_add_tree(s, &leaf, 1, &err), -1, &err);
    }
    scene_tables t;
    CHECK(scene_tables_build(s, &t, &err) == IACSG_OK, "%s", err.message);
    host_scene = s;
    ia_real box[6 * 2 * N], range[2 * N], pos[N], newton_t[2 * N];
    int solid[N], level[N], newton[N];
    bisect_index index[N];
    unsigned char state[N] = {0};
    for (int k = 0; k < 6 * t.nbvh; k++)
        box[k] = (ia_real)t.bvh_box[k]; /* the spheres' boxes are dyadic with few bits: exact */
    scene_view v = {box, t.bvh_link, t.nbvh, t.surfaces, 0, (ia_real)0x1p-12, {0, 0}, 0};
    long rays = test_iters(3000), hits = 0, near = 0;
    for (long it = 0; it < rays; it++) {
        ia_real o[3], d[3], len = 0;
        for (int a = 0; a < 3; a++) {
            o[a] = (ia_real)(test_rand_unit(rng) * 6 - 3);
            d[a] = (ia_real)(test_rand_unit(rng) * 0.6 - 0.3) - o[a] / 3;
            len += d[a] * d[a];
        }
        for (int a = 0; a < 3; a++)
            d[a] /= sqrt(len);
        scene_ray ray = {t.nodes, t.items, t.solid_items_start, t.solid_items, {solid, range, pos, level, index, newton, newton_t},
                         N, 0, 0, state, 0, 0, 0, 0, 0, 0, 0};
        weave_hit hit = {0, -1, -1, -1};
        int found = scene_trace_ray(&v, &ray, o, d, 0, 8, &hit);
        long double lo[3] = {o[0], o[1], o[2]}, ld[3] = {d[0], d[1], d[2]}, first = INFINITY, a, b;
        int id = -1;
        for (int k = 0; k < N; k++)
            if (sphere_inside(c[k], r[k], lo, ld, &a, &b) && a < first && a > 0) {
                first = a;
                id = k;
            }
        for (int k = 0; k < N; k++)
            CHECK(state[k] == SCENE_OUT, "ray %ld left solid %d's state %d", it, k, state[k]);
        if (id < 0)
            continue;
        hits++;
        CHECK(found == 1 && hit.t <= first, "ray %ld: %s at %.12Lg, the first sphere %d at %.12Lg", it,
              found ? "hit" : "missed", (long double)hit.t, id, first);
        near += hit.item != id;
    }
    test_note("%ld rays, %ld through spheres, %ld claimed by another sphere near its boundary", rays, hits, near);
    scene_tables_free(&t);
    iacsg_scene_destroy(s);
}
