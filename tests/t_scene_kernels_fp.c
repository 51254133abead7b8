/* tests/t_scene_kernels_fp.c -- the segment path's kernel stages compiled here as host C (as the device runs
 * them), with the host evaluator (iacsg_expr_eval_box, the same ia/ code) as the solids' inclusion function:
 *
 * - classify_tree in three-valued logic against every in/out assignment of the undecided solids (scene_tree_eval),
 *   on random trees: sound, and exact where no undecided solid occurs twice; the weave's value of a region from its
 *   terms (src/scene_terms.h) the same, and its first region among two;
 * - the terms' stack need, for chains of 1000 differences and unions either way round; the split of a difference
 *   over unions, distributed and (past the copies' bound) not;
 * - scene_trace_ray (BVH, walks, weave) on random rays through random spheres, against their exact entry points
 *   in long double: never after the first point of a region, never a miss.
 */
#include "implicits/scene.h"
#include "kernels/scene_prims.h"
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
static ia_interval scene_solid_F(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t) {
    (void)q;
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

/* A scene_ray over the tables where the first n solids are started candidates with the given states (the weave's
 * view of a partition). */
static scene_ray partition_of(const scene_tables *t, int *solid, int n, unsigned char *state) {
    for (int k = 0; k < n; k++)
        solid[k] = k;
    scene_ray r = {t->nodes, t->items, t->solid_items_start, t->solid_items, {solid, 0, 0, 0, 0, 0, 0, 0, 0, 0},
                   n, n, n, state, 0, 0, 0, 0, 0, 0, 0};
    return r;
}

/* For random trees and states: classify_tree's two bits hold "in for some assignment of the BOUNDARY solids" and
 * "out for some" (exactly so where no BOUNDARY solid repeats); the weave's value of the region, from the terms
 * that its solids not OUT trigger (src/scene_terms.h), is the same two bits; and weave_first_region names the
 * first of two such regions that may be in (or is certainly in). */
TEST_FP(scene_classify_three_valued) {
    enum { SOLIDS = 5 };
    test_rng_t *rng = test_rng();
    iacsg_error err = {0};
    long trees = test_iters(200), checked = 0, exact = 0, terms = 0;
    for (long it = 0; it < trees; it++) {
        iacsg_scene *s = scene_create();
        for (int k = 0; k < SOLIDS; k++)
            scene_add_solid(s, NULL, parse("sphere"), &err);
        uint32_t nodes[2][64];
        int n[2], root[2];
        for (int j = 0; j < 2; j++) {
            n[j] = random_tree(rng, 1 + (int)(test_rand_u64(rng) % 12), SOLIDS, nodes[j], 0);
            root[j] = scene_add_tree(s, nodes[j], n[j], &err);
            CHECK(root[j] >= 0 && scene_add_region(s, NULL, root[j], -1, &err) == j, "%s", err.message);
        }
        scene_tables t;
        CHECK(scene_tables_build(s, &t, &err) == IACSG_OK, "%s", err.message);
        terms += t.solid_items_start[SOLIDS] / SCENE_TERM_INTS;
        for (int code = 0; code < 243; code++) { /* every state of 5 solids */
            unsigned char state[SOLIDS];
            int c = code, boundary[SOLIDS], nb = 0, got[2];
            for (int k = 0; k < SOLIDS; k++, c /= 3) {
                state[k] = (unsigned char)(c % 3);
                if (state[k] == SCENE_BOUNDARY)
                    boundary[nb++] = k;
            }
            int solid[SOLIDS];
            scene_ray r = partition_of(&t, solid, SOLIDS, state);
            for (int j = 0; j < 2; j++) {
                int may_in = 0, may_out = 0;
                for (int a = 0; a < 1 << nb; a++) {
                    signed char sign[SOLIDS];
                    for (int k = 0; k < SOLIDS; k++)
                        sign[k] = state[k] == SCENE_IN ? -1 : 1;
                    for (int b = 0; b < nb; b++)
                        sign[boundary[b]] = a >> b & 1 ? -1 : 1;
                    int v = scene_tree_eval(s, root[j], sign);
                    may_in |= v;
                    may_out |= !v;
                }
                int expect = (may_in ? CLASSIFY_MAY_IN : 0) | (may_out ? CLASSIFY_MAY_OUT : 0);
                got[j] = classify_tree(s->nodes, root[j], n[j], state);
                int device = weave_value(&r, j);
                /* sound always; exact unless an undecided solid occurs twice (a \ a may be in, say the bits) */
                CHECK((got[j] & expect) == expect && device == got[j] && (got[j] == expect || repeats(nodes[j], n[j], state)),
                      "tree %ld.%d, states %d: %d, by the terms %d, exact %d", it, j, code, got[j], device, expect);
                exact += got[j] == expect;
                checked++;
            }
            int first = -1, certain = -1;
            int found = weave_first_region(&r, 0, -1, &first), found_certain = weave_first_region(&r, 1, -1, &certain);
            int want = got[0] & CLASSIFY_MAY_IN ? 0 : got[1] & CLASSIFY_MAY_IN ? 1 : -1;
            int want_certain = got[0] == CLASSIFY_MAY_IN ? 0 : got[1] == CLASSIFY_MAY_IN ? 1 : -1;
            CHECK((found ? first : -1) == want && (found_certain ? certain : -1) == want_certain,
                  "trees %ld, states %d: first %d (%d), certainly %d (%d)", it, code, found ? first : -1, want,
                  found_certain ? certain : -1, want_certain);
        }
        scene_tables_free(&t);
        iacsg_scene_destroy(s);
    }
    test_note("%ld trees in %ld terms, %ld states, %ld of them exact", 2 * trees, terms, checked, exact);
}

/* The largest stack that a solid's terms need (kernels/classify.h: from the last node back). */
static int terms_stack_need(const scene_tables *t, int solid) {
    int need = 0;
    for (int j = t->solid_items_start[solid]; j < t->solid_items_start[solid + 1]; j += SCENE_TERM_INTS) {
        int depth = 0, first = t->solid_items[j + SCENE_TERM_ROOT], size = t->solid_items[j + SCENE_TERM_SIZE];
        for (int k = first + size - 1; k >= first; k--) {
            int o = CSG_NODE_OP(t->nodes[k]);
            depth += o == CSG_INSIDE ? 1 : o == CSG_NOT ? 0 : -1;
            need = depth > need ? depth : need;
        }
    }
    return need;
}

/* Left-deep chains of 1000 differences and of 1000 unions, which a plain evaluation from the last node would
 * stack 1000 deep: the difference chain is one term that the device's order evaluates with 2, the union chain
 * 1001 terms of one leaf. */
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
        int need = terms_stack_need(&t, 0), nterms = t.solid_items_start[1] / SCENE_TERM_INTS;
        CHECK(need <= 2 && nterms == (op ? CHAIN + 1 : 1), "%s chain: stack %d, %d terms", op ? "union" : "difference",
              need, nterms);
        int solid[1];
        unsigned char in[1] = {SCENE_IN};
        scene_ray r = partition_of(&t, solid, 1, in);
        CHECK(weave_value(&r, 0) == (op ? CLASSIFY_MAY_IN : CLASSIFY_MAY_OUT), "value");
        scene_tables_free(&t);
        iacsg_scene_destroy(s);
    }
}

/* The three-valued value of tree node k, recursively (classify_tree's stack holds 64 values: not this tree's). */
static int tree_value(const uint32_t *nodes, int k, const unsigned char *state) {
    int op = CSG_NODE_OP(nodes[k]);
    if (op == CSG_INSIDE)
        return classify_leaf(state[CSG_NODE_ARG(nodes[k])]);
    int a = tree_value(nodes, k + 1, state), b = tree_value(nodes, (int)CSG_NODE_ARG(nodes[k]), state);
    int in = op == CSG_UNION ? (a | b) & 1 : op == CSG_INTERSECT ? a & b & 1 : a & b >> 1 & 1;
    int out = op == CSG_UNION ? a & b & 2 : op == CSG_INTERSECT ? (a | b) & 2 : (a | b << 1) & 2;
    return in | out;
}

/* (a1 u ... u a100) - (x1 u ... u x100): distributed, the difference would be copied 100 times; the region is cut at
 * its unions only, one term that each a triggers and no x. And (a u b) - x distributed: a and b each trigger a
 * term of three nodes, x none. The weave's value is the tree's for random states either way. */
TEST_FP(scene_terms_split) {
    enum { N = 100 };
    test_rng_t *rng = test_rng();
    iacsg_error err = {0};
    for (int big = 0; big < 2; big++) {
        int n = big ? N : 2, nsolids = big ? 2 * N : 3;
        iacsg_scene *s = scene_create();
        for (int k = 0; k < nsolids; k++)
            scene_add_solid(s, NULL, parse("sphere"), &err);
        static uint32_t nodes[4 * N];
        int size = 0;
        nodes[size++] = 0; /* the difference, its right side patched below */
        for (int side = 0; side < 2; side++) { /* a chain of unions over a's, then over x's (one x when small) */
            int leaves = side && !big ? 1 : n, first = side ? n : 0;
            for (int k = 0; k < leaves - 1; k++)
                nodes[size + k] = CSG_NODE(CSG_UNION, size + 2 * (leaves - 1) - k);
            for (int k = 0; k < leaves; k++)
                nodes[size + leaves - 1 + k] = CSG_NODE(CSG_INSIDE, first + k);
            if (side == 0)
                nodes[0] = CSG_NODE(CSG_DIFFERENCE, size + 2 * leaves - 1);
            size += 2 * leaves - 1;
        }
        int root = scene_add_tree(s, nodes, size, &err);
        CHECK(root >= 0 && scene_add_region(s, NULL, root, -1, &err) == 0, "%s", err.message);
        scene_tables t;
        CHECK(scene_tables_build(s, &t, &err) == IACSG_OK, "%s", err.message);
        for (int k = 0; k < nsolids; k++) {
            int entries = (t.solid_items_start[k + 1] - t.solid_items_start[k]) / SCENE_TERM_INTS;
            const int *e = t.solid_items + t.solid_items_start[k];
            CHECK(entries == (k < n), "solid %d triggers %d terms", k, entries);
            if (entries) /* one term, the whole region, when big */
                CHECK(e[SCENE_TERM_SIZE] == (big ? size : 3) && (!big || e[SCENE_TERM_ROOT] == t.solid_items[1]),
                      "solid %d's term at %d, %d nodes", k, e[SCENE_TERM_ROOT], e[SCENE_TERM_SIZE]);
        }
        unsigned char *state = calloc((size_t)nsolids, 1);
        int *solid = malloc(sizeof(int) * (size_t)nsolids);
        for (int it = 0; it < 200; it++) {
            for (int k = 0; k < nsolids; k++) /* mostly OUT, as along a ray */
                state[k] = test_rand_u64(rng) % 8 < 6 ? SCENE_OUT : (unsigned char)(1 + test_rand_u64(rng) % 2);
            scene_ray r = partition_of(&t, solid, nsolids, state);
            int want = tree_value(s->nodes, root, state), got = weave_value(&r, 0);
            CHECK(got == want, "states %d: %d by the terms, %d by the tree", it, got, want);
        }
        free(state);
        free(solid);
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
    scene_view v = {box, t.bvh_link, t.nbvh, t.surfaces, 0, (ia_real)0x1p-12, {0, 0}, 0, 0, 0, 0, 0};
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
        scene_ray ray = {t.nodes, t.items, t.solid_items_start, t.solid_items,
                         {solid, range, pos, level, index, newton, newton_t, 0, 0, 0}, N, 0, 0, state,
                         0, 0, 0, 0, 0, 0, 0};
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

/* The solids (and their ranges) of the BVH's leaves that the ray meets, from the top-level nodes (cut 0) or from a
 * packet's cut: every inner node pending is expanded. Returns how many, or -1 when they pass `cap`. */
static int bvh_leaves(const bvh_walk *b, int *solid, ia_real *range, int cap) {
    int count = 0;
    if (!bvh_roots(b, solid, range, &count, cap))
        return -1;
    for (int c = 0; c < count;)
        if (solid[c] < 0) {
            if (!bvh_expand(b, c, solid, range, &count, cap))
                return -1;
        } else {
            c++;
        }
    return count;
}

/* Whether two lists of leaves hold the same solids with the same ranges, bit for bit (in any order). */
static int same_leaves(const int *sa, const ia_real *ra, int na, const int *sb, const ia_real *rb, int nb) {
    if (na != nb)
        return 0;
    for (int i = 0; i < na; i++) {
        int j = 0;
        while (j < nb && !(sb[j] == sa[i] && rb[2 * j] == ra[2 * i] && rb[2 * j + 1] == ra[2 * i + 1]))
            j++;
        if (j == nb)
            return 0;
    }
    return 1;
}

/* Packets of 16 rays (a common direction and origins on a small grid, as an orthographic camera's; or a common
 * origin and a fan of directions, as a perspective one's; some with a direction component 0 in every ray or of
 * both signs) against the BVH of 64 random spheres and a half-space: every ray meets, from its packet's cut
 * (bvh_beam_cut), exactly the leaves with exactly the ranges it meets from the top-level nodes. */
TEST_FP(scene_bvh_beam_cut) {
    enum { N = 64, LANES = PACKET_LANES };
    test_rng_t *rng = test_rng();
    iacsg_error err = {0};
    iacsg_scene *s = scene_create();
    for (int k = 0; k < N; k++) {
        char text[256];
        double c[3], r = ldexp(floor(ldexp(0.05 + 0.2 * test_rand_unit(rng), 10)), -10);
        for (int a = 0; a < 3; a++)
            c[a] = ldexp(floor(ldexp(test_rand_unit(rng) * 2 - 1, 10)), -10);
        snprintf(text, sizeof text, "(x - %.20g)^2 + (y - %.20g)^2 + (z - %.20g)^2 - %.30g", c[0], c[1], c[2], r * r);
        scene_add_solid(s, NULL, parse(text), &err);
        uint32_t leaf = CSG_NODE(CSG_INSIDE, k);
        scene_add_region(s, NULL, scene_add_tree(s, &leaf, 1, &err), -1, &err);
    }
    scene_add_solid(s, NULL, parse("z + 0.5"), &err); /* unbounded: a top-level leaf of its own */
    uint32_t half = CSG_NODE(CSG_INSIDE, N);
    scene_add_region(s, NULL, scene_add_tree(s, &half, 1, &err), -1, &err);
    scene_tables t;
    CHECK(scene_tables_build(s, &t, &err) == IACSG_OK, "%s", err.message);
    ia_real *box = malloc(sizeof(ia_real) * 6 * (size_t)t.nbvh);
    for (int k = 0; k < 6 * t.nbvh; k++)
        box[k] = (ia_real)t.bvh_box[k];
    long packets = test_iters(2000), cuts = 0, entries = 0, rays = 0, leaves = 0;
    for (long it = 0; it < packets; it++) {
        ia_real o[3][LANES], d[3][LANES], inv[3][LANES], tn[LANES], tf[LANES], base_o[3], base_d[3], u[3], v[3];
        int ortho = it % 2, zero = test_rand_u64(rng) % 4 == 0 ? (int)(test_rand_u64(rng) % 3) : -1;
        double spread = ldexp(1, -(int)(test_rand_u64(rng) % 12));
        for (int a = 0; a < 3; a++) {
            base_o[a] = (ia_real)(test_rand_unit(rng) * 6 - 3);
            base_d[a] = (ia_real)(test_rand_unit(rng) * 0.6 - 0.3) - base_o[a] / 3;
            u[a] = (ia_real)((test_rand_unit(rng) - 0.5) * spread);
            v[a] = (ia_real)((test_rand_unit(rng) - 0.5) * spread);
        }
        bvh_beam m;
        bvh_beam_start(&m);
        for (int k = 0; k < LANES; k++) {
            ia_real i = (ia_real)(k % 4), j = (ia_real)(k / 4);
            for (int a = 0; a < 3; a++) {
                o[a][k] = ortho ? base_o[a] + i * u[a] + j * v[a] : base_o[a];
                d[a][k] = ortho ? base_d[a] : base_d[a] + i * u[a] + j * v[a];
                if (a == zero)
                    d[a][k] = 0;
                inv[a][k] = (ia_real)1 / d[a][k];
            }
            tn[k] = (ia_real)test_rand_unit(rng);
            tf[k] = tn[k] + (ia_real)(8 * test_rand_unit(rng));
            bvh_beam_add_lane(&m, o, d, inv, k, tn[k], tf[k]);
        }
        int cut[BVH_CUT_MAX], ncut = bvh_beam_cut(&m, box, t.bvh_link, t.nbvh, cut);
        if (ncut < 0)
            continue;
        cuts++;
        entries += ncut;
        for (int k = 0; k < LANES; k++) {
            int sa[2 * N + 2], sb[2 * N + 2];
            ia_real ra[4 * N + 4], rb[4 * N + 4];
            bvh_ray r = bvh_ray_lane(d, inv, k);
            ia_real ok[3] = {o[0][k], o[1][k], o[2][k]}, dk[3] = {d[0][k], d[1][k], d[2][k]};
            bvh_walk b = {box, t.bvh_link, t.nbvh, &r, ok, dk, tn[k], tf[k], 0, 0, 0, 0};
            int na = bvh_leaves(&b, sa, ra, 2 * N + 2);
            b.cut = cut;
            b.ncut = ncut;
            int nb = bvh_leaves(&b, sb, rb, 2 * N + 2);
            rays++;
            leaves += na;
            CHECK(na >= 0 && same_leaves(sa, ra, na, sb, rb, nb),
                  "packet %ld (%s, direction %d zero), ray %d: %d leaves from the roots, %d from the cut of %d", it,
                  ortho ? "orthographic" : "perspective", zero, k, na, nb, ncut);
        }
    }
    CHECK(cuts > packets / 2, "%ld packets of %ld had a cut", cuts, packets);
    test_note("%ld packets with a cut of %.1f entries on average, %ld rays, %.2f leaves a ray", cuts,
              (double)entries / (double)cuts, rays, (double)leaves / (double)rays);
    free(box);
    scene_tables_free(&t);
    iacsg_scene_destroy(s);
}
