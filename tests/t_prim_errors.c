/* tests/t_prim_errors.c -- primitives that describe no solid are refused with one clear message naming the solid,
 * its type and the reason (implicits/prim_place.c), by prim_place and so by the scene's code generation
 * (scene_emit_cl), before anything is built; a valid one of each type is accepted with its world box (a half-space:
 * an infinite one; a pipe's bend: its whole torus's, which holds here the bend's own); and the float program's
 * parameters are the double bounds rounded outward to the nearest floats. */
#include "implicits/prim_place.h"
#include "implicits/scene_emit.h"
#include "test.h"
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

static void expect_refused(const char *name, scene_prim_type type, const double *q, int n, const double mat[16],
                           const char *reason) {
    scene_prim sp = {type, n, (double *)q, {0}, NULL};
    memcpy(sp.mat, mat, sizeof sp.mat);
    prim_placed pl;
    iacsg_error err = {0};
    CHECK(prim_place(&sp, name, &pl, &err) == IACSG_ERR_ARG, "%s was placed", name);
    CHECK(strstr(err.message, name) && strstr(err.message, reason), "%s: the message '%s' does not say '%s'", name,
          err.message, reason);
    CHECK(!strchr(err.message, '\n'), "%s: the message is more than one line", name);
    /* and the scene's code is not made */
    iacsg_scene *s = scene_create();
    CHECK(scene_add_primitive(s, name, type, q, n, mat, &err) == 0, "scene_add_primitive: %s", err.message);
    char *cl = NULL;
    iacsg_error err2 = {0};
    CHECK(scene_emit_cl(s, &cl, &err2) == IACSG_ERR_ARG && !cl && !strcmp(err.message, err2.message),
          "%s: scene_emit_cl gave '%s'", name, err2.message);
    iacsg_scene_destroy(s);
}

TEST(prim_errors_refused) {
    double ell_flat[12] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 1};
    expect_refused("flat.s", SCENE_PRIM_ELL, ell_flat, 12, identity, "semi-axes are not independent");
    double tgc_flat[18] = {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1, 0};
    expect_refused("flat.rcc", SCENE_PRIM_TGC, tgc_flat, 18, identity, "height and base axes");
    double arb_point[24] = {0};
    expect_refused("point.arb", SCENE_PRIM_ARB8, arb_point, 24, identity, "fewer than four faces");
    double tor_bad[8] = {0, 0, 0, 0, 0, 1, 1, 0};
    expect_refused("thin.tor", SCENE_PRIM_TOR, tor_bad, 8, identity, "radii are not positive");
    double tor_axis[8] = {0, 0, 0, 0, 0, 0, 1, 0.5};
    expect_refused("axis.tor", SCENE_PRIM_TOR, tor_axis, 8, identity, "axis is zero");
    double pipe_one[6] = {0, 0, 0, 1, 0, 1};
    expect_refused("one.pipe", SCENE_PRIM_PIPE, pipe_one, 6, identity, "at least two");
    double pipe_same[12] = {1, 2, 3, 1, 0, 1, 1, 2, 3, 1, 0, 1};
    expect_refused("same.pipe", SCENE_PRIM_PIPE, pipe_same, 12, identity, "all its points coincide");
    double pipe_bore[12] = {0, 0, 0, 1, 1, 1, 0, 0, 5, 1, 1, 1};
    expect_refused("bore.pipe", SCENE_PRIM_PIPE, pipe_bore, 12, identity, "diameters");
    double half[4] = {0, 0, 0, 1};
    expect_refused("zero.half", SCENE_PRIM_HALF, half, 4, identity, "normal is zero");
    double half_nan[4] = {0, 0, 1, NAN};
    expect_refused("nan.half", SCENE_PRIM_HALF, half_nan, 4, identity, "not a finite number");
    double ell[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    expect_refused("short.ell", SCENE_PRIM_ELL, ell, 11, identity, "wrong number of parameters");
    double perspective[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0.5, 1};
    expect_refused("persp.ell", SCENE_PRIM_ELL, ell, 12, perspective, "matrix is not affine");
}

TEST(prim_errors_valid_boxes) {
    static const struct {
        scene_prim_type type;
        int n;
        double q[24];
    } valid[] = {
        {SCENE_PRIM_HALF, 4, {0, 0, 1, 2}},
        {SCENE_PRIM_ARB8, 24, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1}},
        {SCENE_PRIM_ELL, 12, {1, 2, 3, 1, 0, 0, 0, 2, 0, 0, 0, 3}},
        {SCENE_PRIM_TGC, 18, {0, 0, 0, 0, 0, 2, 1, 0, 0, 0, 1, 0, 0.5, 0, 0, 0, 0.5, 0}},
        {SCENE_PRIM_TOR, 8, {0, 0, 0, 0, 0, 1, 2, 0.5}},
        {SCENE_PRIM_EHY, 12, {0, 0, 0, 0, 0, 2, 1, 0, 0, 1, 0.5, 0.2}},
        {SCENE_PRIM_PIPE, 18, {0, 0, 0, 1, 0.5, 2, 5, 0, 0, 1, 0.5, 2, 5, 5, 0, 1, 0.5, 2}},
    };
    /* the boxes the shapes are known to have (a torus's: radius 2.5 across its axis, 0.5 along it) */
    static const double expect[][6] = {{-INFINITY, -INFINITY, -INFINITY, INFINITY, INFINITY, INFINITY},
                                       {0, 0, 0, 1, 1, 1},
                                       {0, 0, 0, 2, 4, 6},
                                       {-1, -1, 0, 1, 1, 2},
                                       {-2.5, -2.5, -0.5, 2.5, 2.5, 0.5},
                                       {-1, -0.5, 0, 1, 0.5, 2},
                                       {0, -0.5, -0.5, 5.5, 5, 0.5}};
    for (size_t k = 0; k < sizeof valid / sizeof valid[0]; k++) {
        scene_prim sp = {valid[k].type, valid[k].n, (double *)valid[k].q, {0}, NULL};
        memcpy(sp.mat, identity, sizeof sp.mat);
        double box[6];
        int bounded = prim_world_box(&sp, box);
        CHECK(bounded == (valid[k].type != SCENE_PRIM_HALF), "type %d: bounded %d", valid[k].type, bounded);
        /* holds the shape, within 1e-12 */
        for (int c = 0; c < 6; c++)
            CHECK(c < 3 ? box[c] <= expect[k][c] && box[c] >= expect[k][c] - 1e-12
                        : box[c] >= expect[k][c] && box[c] <= expect[k][c] + 1e-12,
                  "type %d: box[%d] = %.17g, the shape's %.17g", valid[k].type, c, box[c], expect[k][c]);
    }
}

/* A float program's parameters: each double bound rounded outward to the nearest float on its side (so the float
 * intervals hold the double ones, and no wider than one float step). */
TEST(prim_float_bound_outward) {
    test_rng_t *rng = test_rng();
    long n = test_iters(100000);
    for (long k = 0; k < n; k++) {
        double x = ldexp(test_rand_unit(rng) - 0.5, (int)(test_rand_u64(rng) % 200) - 100);
        if (k % 7 == 0)
            x = (double)(float)x; /* exactly a float: kept */
        float lo = prim_float_bound(x, 0), hi = prim_float_bound(x, 1);
        CHECK((double)lo <= x && x <= (double)hi, "%a: [%a, %a] does not hold it", x, (double)lo, (double)hi);
        CHECK((double)nextafterf(lo, INFINITY) > x && (double)nextafterf(hi, -INFINITY) < x,
              "%a: [%a, %a] is not the nearest floats", x, (double)lo, (double)hi);
    }
    CHECK(prim_float_bound(1e300, 1) == INFINITY && prim_float_bound(1e300, 0) == FLT_MAX, "beyond the floats' range");
    /* the kernels flush subnormals: a subnormal bound moves out to 0 or the smallest normal float (ia/flush.h) */
    CHECK(prim_float_bound(1e-40, 0) == 0 && prim_float_bound(1e-40, 1) == FLT_MIN &&
              prim_float_bound(-1e-40, 0) == -FLT_MIN && prim_float_bound(-1e-40, 1) == 0,
          "subnormal bounds: [%a, %a] and [%a, %a]", (double)prim_float_bound(1e-40, 0),
          (double)prim_float_bound(1e-40, 1), (double)prim_float_bound(-1e-40, 0), (double)prim_float_bound(-1e-40, 1));
}
