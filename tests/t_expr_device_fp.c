/* tests/t_expr_device_fp.c -- the emitted OpenCL C on the device (float and double): the enclosure F of random
 * expressions, every primitive and every op contains the MPFR value at points of random boxes. All the
 * expressions go into one program, so the test costs one build per precision. (The derivative code of interval
 * Newton, over lanes as the kernels run it: tests/t_expr_lanes_fp.c.)
 *
 * The point value f is checked to what the arithmetic promises: the point code does the operations of the
 * interval code, each rounded to nearest (or within the function's documented ulps), and each interval operation
 * is widened past that error, so f at a point lies in F over the degenerate box of that point, as the exact value
 * does. The forward-mode gradient (used for shading only) of the smooth primitives is within GRAD_ULPS ulps of
 * 1 + |g| of the MPFR derivative. Each count of checked points has a minimum, so that nothing passes by being
 * undefined. */
#include "implicits/device_eval.h"
#include "t_expr_oracle.h"
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif
#define GRAD_ULPS 1024 /* measured at most 70 ulps of 1 + |g| in float and double (the note prints it) */

#define MAX_EXPRS 72
#define BOXES 24

/* The corner as the device holds it: rounded down to float without fp64. */
static double device_point(double v) {
    if (FP64)
        return v;
    float f = (float)v;
    return (double)f > v ? nextafterf(f, -INFINITY) : f;
}

static const char *const smooth[] = {"sphere", "torus", "tangle", "decocube", "heart", "ellipsoid", "gyroid",
                                     "bretzel4"};

/* The spacing of the working precision's numbers at |v| (subnormals included). */
static double ulp_of(double v) {
    int e;
    frexp(fmax(fabs(v), FP64 ? DBL_MIN : FLT_MIN), &e);
    return ldexp(1, e - (FP64 ? 53 : 24));
}

static int is_smooth(const char *text) {
    for (size_t i = 0; i < sizeof smooth / sizeof smooth[0]; i++)
        if (strcmp(text, smooth[i]) == 0)
            return 1;
    return 0;
}

TEST_FP(expr_device_contains) {
    static char texts[MAX_EXPRS][EXPR_TEXT_SIZE];
    iacsg_expr *exprs[MAX_EXPRS];
    int n = expr_test_texts(test_rng(), texts, MAX_EXPRS);
    const char *names[64];
    int nprim = expr_primitive_names(names, 64); /* the first texts: their gradients are checked too */
    for (int i = 0; i < n; i++)
        CHECK(iacsg_expr_parse(texts[i], "<test>", &exprs[i], NULL) == IACSG_OK, "'%s' does not compile", texts[i]);

    /* q random boxes, then the degenerate box of each one's corner */
    size_t q = (size_t)n * BOXES, all = 2 * q;
    int *which = malloc(all * sizeof *which);
    double *in = malloc(DEVICE_EVAL_IN * all * sizeof *in), *out = malloc(DEVICE_EVAL_OUT * all * sizeof *out);
    CHECK(which && in && out, "out of memory");
    for (size_t k = 0; k < q; k++) {
        double *v = in + DEVICE_EVAL_IN * k, *at = in + DEVICE_EVAL_IN * (q + k);
        which[k] = which[q + k] = (int)(k / BOXES);
        expr_random_box(test_rng(), v);
        for (int c = 0; c < 4; c++)
            at[2 * c] = at[2 * c + 1] = device_point(v[2 * c]);
    }
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "%s", err.message);
    iacsg_status st = device_eval(&rt, (const iacsg_expr *const *)exprs, n, FP64, all, which, in, out, &err);
    clrt_close(&rt);
    CHECK(st == IACSG_OK, "%s", err.message);

    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    long checked = 0, values = 0, grads = 0, off_domain = 0;
    double worst_value = 0, worst_grad = 0; /* f in ulps of the exact value; g in ulps of 1 + |g| */
    for (size_t k = 0; k < q; k++) {
        const iacsg_expr *e = exprs[which[k]];
        const char *text = texts[which[k]];
        const double *v = in + DEVICE_EVAL_IN * k, *o = out + DEVICE_EVAL_OUT * k;
        for (int s = 0; s < 6; s++) {
            double p[4];
            expr_random_point(test_rng(), v, p);
            if (!expr_oracle(e, p, y))
                continue;
            checked++;
            CHECK(mpfr_cmp_d(y, o[0]) >= 0 && mpfr_cmp_d(y, o[1]) <= 0,
                  "device: '%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a] gave [%a, %a], but at (%a, %a, %a, "
                  "%a) the value is %.20g",
                  text, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], o[0], o[1], p[0], p[1], p[2], p[3],
                  mpfr_get_d(y, MPFR_RNDN));
        }
        /* f at the corner, in F over the corner (which holds the exact value) */
        const double *at = in + DEVICE_EVAL_IN * (q + k), *po = out + DEVICE_EVAL_OUT * (q + k);
        double p[4] = {at[0], at[2], at[4], at[6]};
        if (!expr_oracle(e, p, y))
            continue;
        /* where the interval code clips a domain (sqrt of [-8.7e-8, 1.2e-7] from sin(pi)), the point code may
         * land outside it (sqrt(sin(pi rounded)) is NaN): counted, not a wrong value */
        off_domain += isnan(po[2]);
        if (isnan(po[2]))
            continue;
        values++;
        CHECK(mpfr_cmp_d(y, po[0]) >= 0 && mpfr_cmp_d(y, po[1]) <= 0 && po[2] >= po[0] && po[2] <= po[1],
              "device: '%s' at (%a, %a, %a, %a): f = %a, exact %.20g, but F there is [%a, %a]", text, p[0], p[1], p[2],
              p[3], po[2], mpfr_get_d(y, MPFR_RNDN), po[0], po[1]);
        if (isfinite(po[2]))
            worst_value = fmax(worst_value, fabs(po[2] - mpfr_get_d(y, MPFR_RNDN)) / ulp_of(mpfr_get_d(y, MPFR_RNDN)));
        if (which[k] >= nprim || !is_smooth(text))
            continue;
        for (int axis = 0; axis < 3; axis++) {
            const double dir[3] = {axis == 0, axis == 1, axis == 2};
            if (!expr_oracle_slope(e, p, dir, y))
                continue;
            grads++;
            double g = po[3 + axis], exact = mpfr_get_d(y, MPFR_RNDN), off = fabs(g - exact) / ulp_of(1 + fabs(exact));
            CHECK(off <= GRAD_ULPS, "device: gradient of %s at (%a, %a, %a), axis %d: %a, exact %.20g (%.1f ulps off)",
                  text, p[0], p[1], p[2], axis, g, exact, off);
            worst_grad = fmax(worst_grad, off);
        }
    }
    mpfr_clear(y);
    for (int i = 0; i < n; i++)
        iacsg_expr_destroy(exprs[i]);
    free(which);
    free(in);
    free(out);
    test_note("%d expressions, %zu boxes, %ld points checked; %ld values f (at most %.1f ulps off; %ld NaN at a "
              "domain's edge) in the enclosures at their points; %ld partials of smooth primitives (at most %.1f ulps "
              "of 1 + |g| off)",
              n, q, checked, values, worst_value, off_domain, grads, worst_grad);
    /* measured (float, double): ~5.7 points a box, values at 80 % of the corners, every partial */
    CHECK(checked >= (long)q * 4, "only %ld points checked", checked);
    CHECK(values >= (long)q / 2 && off_domain <= values / 100, "only %ld of %zu point values checked (%ld NaN)",
          values, q, off_domain);
    long partials = 3L * (long)(sizeof smooth / sizeof smooth[0]) * BOXES;
    CHECK(grads >= partials * 9 / 10, "only %ld of %ld partials checked", grads, partials);
}

/* The kernels flush subnormals (ia/flush.h): a subnormal constant, or a subnormal bound of a query's box, read as
 * zero would lose a product of it with a large number. Both are handed to the device moved out of the
 * subnormals, so tiny * big keeps its exact value, 1e-10, of either sign. */
TEST_FP(expr_device_subnormal_bounds) {
    const double tiny = FP64 ? 1e-310 : 1e-40, big = FP64 ? 1e300 : 1e30;
    char texts[2][64];
    snprintf(texts[0], sizeof texts[0], "x*%g", tiny);
    snprintf(texts[1], sizeof texts[1], "x*y");
    iacsg_expr *exprs[2];
    for (int i = 0; i < 2; i++)
        CHECK(iacsg_expr_parse(texts[i], "<test>", &exprs[i], NULL) == IACSG_OK, "'%s' does not compile", texts[i]);
    int which[4] = {0, 0, 1, 1};
    double in[4 * DEVICE_EVAL_IN] = {0}, out[4 * DEVICE_EVAL_OUT], want[4];
    for (int k = 0; k < 4; k++) {
        double *v = in + DEVICE_EVAL_IN * k, sign = k % 2 ? -1 : 1;
        v[0] = v[1] = which[k] ? sign * tiny : sign * big; /* x */
        v[2] = v[3] = big;                                 /* y */
        want[k] = which[k] ? sign * tiny * big : sign * big * tiny;
    }
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "%s", err.message);
    iacsg_status st = device_eval(&rt, (const iacsg_expr *const *)exprs, 2, FP64, 4, which, in, out, &err);
    clrt_close(&rt);
    iacsg_expr_destroy(exprs[0]), iacsg_expr_destroy(exprs[1]);
    CHECK(st == IACSG_OK, "%s", err.message);
    for (int k = 0; k < 4; k++) {
        const double *o = out + DEVICE_EVAL_OUT * k;
        CHECK(o[0] <= want[k] && want[k] <= o[1], "device: '%s' at x = %g, y = %g gave [%a, %a], not holding %g",
              texts[which[k]], in[DEVICE_EVAL_IN * k], in[DEVICE_EVAL_IN * k + 2], o[0], o[1], want[k]);
    }
    test_note("%s and x*y with x = +-%g: each holds +-%g", texts[0], tiny, tiny * big);
}
