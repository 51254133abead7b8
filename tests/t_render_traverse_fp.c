/* tests/t_render_traverse_fp.c -- the kernel's traversal (kernels/traverse.h), compiled here as host C with the
 * same precision: node ends are the exact dyadic fraction u = i * 2^-k of the root carried through
 * t0 + w * u with two roundings, checked against MPFR, so a parent's ends are its children's and a node's end is
 * its neighbour's start (the same u); the same check finds the gaps of hi = lo + width (so it can fail); the
 * stackless walk visits the leaves in ray order and covers the root interval with no gap. */
#include "kernels/traverse.h"
#include "test.h"
#include <math.h>
#include <mpfr.h>

#ifdef IA_FP64
#define TRAVERSE_LEVELS 52
#define REAL_BITS 53
#else
#define TRAVERSE_LEVELS 24
#define REAL_BITS 24
#endif

/* A random root interval like a clipped ray's: t0 in [0, 8), w in (0, 8). */
static void random_root(test_rng_t *rng, ia_real *t0, ia_real *w) {
    *t0 = (ia_real)(8 * test_rand_unit(rng));
    *w = (ia_real)(8 * test_rand_unit(rng)) + (ia_real)1e-3;
}

/* The documented end of the fraction i * 2^-k of [t0, t0 + w], computed independently of traverse.h: u exact
 * (an integer scaled by a power of two), w * u rounded to nearest in the working precision, then t0 + that. */
static ia_real exact_node_end(ia_real t0, ia_real w, int k, unsigned long long i) {
    mpfr_t v;
    mpfr_init2(v, 256);
    mpfr_set_ui(v, (unsigned long)(i >> 32), MPFR_RNDN); /* i, exactly, from its two halves */
    mpfr_mul_2ui(v, v, 32, MPFR_RNDN);
    mpfr_add_ui(v, v, (unsigned long)(i & 0xffffffffu), MPFR_RNDN);
    mpfr_div_2ui(v, v, (unsigned long)k, MPFR_RNDN);
    mpfr_mul_d(v, v, (double)w, MPFR_RNDN); /* exact at 256 bits */
    mpfr_prec_round(v, REAL_BITS, MPFR_RNDN);
    mpfr_prec_round(v, 256, MPFR_RNDN);
    mpfr_add_d(v, v, (double)t0, MPFR_RNDN); /* exact: the exponents are close */
    mpfr_prec_round(v, REAL_BITS, MPFR_RNDN);
    double r = mpfr_get_d(v, MPFR_RNDN);
    mpfr_clear(v);
    return (ia_real)r;
}

/* A node's upper end as the kernel computes it (node_bound of the next index), and as a walk that recomputes
 * hi = lo + width would. */
static ia_real kernel_node_hi(ia_real t0, ia_real w, int k, bisect_index i) { return node_bound(t0, w, k, i + 1); }
static ia_real naive_node_hi(ia_real t0, ia_real w, int k, bisect_index i) {
    return node_bound(t0, w, k, i) + w * node_scale(k);
}

/* For random nodes and their two children: the start of each is the exact formula at its own u, and the upper
 * end given by node_hi the exact formula at the next u, which is the next node's start: a node's end that
 * differs from it is a gap or an overlap. Returns the number of ends that differ. */
static long count_wrong_ends(test_rng_t *rng, long n, ia_real (*node_hi)(ia_real, ia_real, int, bisect_index)) {
    long wrong = 0;
    for (long it = 0; it < n; it++) {
        ia_real t0, w;
        random_root(rng, &t0, &w);
        int k = (int)(test_rand_u64(rng) % TRAVERSE_LEVELS);
        bisect_index i = (bisect_index)(test_rand_u64(rng) & (((bisect_index)1 << k) - 1));
        for (int c = 0; c < 3; c++) { /* the node, then its children */
            int level = c ? k + 1 : k;
            bisect_index j = c ? 2 * i + (bisect_index)(c - 1) : i;
            ia_real lo = node_bound(t0, w, level, j), hi = node_hi(t0, w, level, j);
            CHECK(lo == exact_node_end(t0, w, level, j), "t0 %a w %a level %d index %llu: the start %a is not "
                  "t0 + w * u rounded", (double)t0, (double)w, level, (unsigned long long)j, (double)lo);
            wrong += hi != exact_node_end(t0, w, level, j + 1);
        }
    }
    return wrong;
}

TEST_FP(render_traverse_node_ends_exact) {
    long n = test_iters(100000);
    long wrong = count_wrong_ends(test_rng(), n, kernel_node_hi);
    long naive = count_wrong_ends(test_rng(), n, naive_node_hi);
    test_note("%ld nodes and their children: %ld ends not the next node's start; with hi = lo + width %ld", n,
              wrong, naive);
    CHECK(wrong == 0, "%ld node ends differ from the next node's start", wrong);
    CHECK(naive > 0, "hi = lo + width never left a gap: the check cannot tell a gap-prone walk");
}

/* Walks the whole tree down to `depth`, descending at every node above it: the leaves must come in order,
 * each starting exactly where the previous ended, from t0 to the root's end. */
TEST_FP(render_traverse_walk_covers_root) {
    test_rng_t *rng = test_rng();
    for (long it = 0; it < test_iters(50); it++) {
        ia_real t0, w;
        random_root(rng, &t0, &w);
        int depth = 1 + (int)(test_rand_u64(rng) % 12), level = 0;
        bisect_index i = 0;
        ia_real prev_hi = t0;
        long leaves = 0;
        do {
            while (level < depth) {
                level += 1;
                i <<= 1;
            }
            ia_real lo = node_bound(t0, w, level, i), hi = node_bound(t0, w, level, i + 1);
            CHECK(lo == prev_hi, "leaf %ld starts at %a, the previous ended at %a", leaves, (double)lo,
                  (double)prev_hi);
            prev_hi = hi;
            leaves++;
        } while (node_next(&level, &i));
        CHECK(leaves == 1L << depth, "depth %d: %ld leaves visited", depth, leaves);
        CHECK(prev_hi == node_bound(t0, w, 0, 1), "the walk ended at %a, not at the root's end", (double)prev_hi);
    }
}

/* node_at gives the node holding t (the first or the last one outside the root): the walk may start there
 * without skipping a node that reaches past t. */
TEST_FP(render_traverse_node_at) {
    test_rng_t *rng = test_rng();
    for (long it = 0; it < test_iters(100000); it++) {
        ia_real t0, w;
        random_root(rng, &t0, &w);
        int k = (int)(test_rand_u64(rng) % TRAVERSE_LEVELS);
        ia_real t = t0 + (ia_real)((1.2 * test_rand_unit(rng) - 0.1) * (double)w);
        bisect_index j = node_at(t0, w, k, t), last = ((bisect_index)1 << k) - 1;
        CHECK(j <= last, "level %d: index %llu past the last node", k, (unsigned long long)j);
        CHECK(j == 0 || node_bound(t0, w, k, j) <= t, "level %d index %llu starts after t = %a", k,
              (unsigned long long)j, (double)t);
        CHECK(j == last || node_bound(t0, w, k, j + 1) > t, "level %d index %llu ends at or before t = %a", k,
              (unsigned long long)j, (double)t);
    }
}

/* Whether lo <= o + d*t <= hi for the exact value, in MPFR at a precision that holds it exactly (the product
 * has at most 106 significant bits, the sum adds the exponent range between them). */
static int ray_point_inside(ia_real o, ia_real d, ia_real t, ia_real lo, ia_real hi) {
    mpfr_t v, p;
    mpfr_inits2(2400, v, p, (mpfr_ptr)0);
    mpfr_set_d(p, (double)d, MPFR_RNDN);
    mpfr_mul_d(p, p, (double)t, MPFR_RNDN);
    mpfr_add_d(v, p, (double)o, MPFR_RNDN);
    int inside = mpfr_cmp_d(v, (double)lo) >= 0 && mpfr_cmp_d(v, (double)hi) <= 0;
    mpfr_clears(v, p, (mpfr_ptr)0);
    return inside;
}

/* The box of a ray segment contains the exact points o + t*d, t in the segment, at its end points (the extremes
 * of a linear function). Near o + t*d = 0 the box is a few ulps of a tiny number wide (ray_extent rounds each
 * end once), so the check is exact. */
TEST_FP(render_traverse_ray_extent_contains_ray) {
    test_rng_t *rng = test_rng();
    for (long it = 0; it < test_iters(100000); it++) {
        ia_real o = (ia_real)(8 * test_rand_unit(rng) - 4), d = (ia_real)(2 * test_rand_unit(rng) - 1);
        ia_real a = (ia_real)(8 * test_rand_unit(rng)), b = a + (ia_real)(test_rand_unit(rng) * 1e-3);
        ia_interval x = ray_extent(o, d, ia_make(a, b));
        CHECK(ray_point_inside(o, d, a, x.lo, x.hi) && ray_point_inside(o, d, b, x.lo, x.hi),
              "o=%a d=%a t=[%a,%a]: box [%a,%a] misses the ray", (double)o, (double)d, (double)a, (double)b,
              (double)x.lo, (double)x.hi);
    }
}
