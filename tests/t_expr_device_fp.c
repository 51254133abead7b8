/* tests/t_expr_device_fp.c -- the emitted OpenCL C on the device (float and double): the enclosure F of random
 * expressions, every primitive and every op contains the MPFR value at points of random boxes; the point value f
 * and the forward-mode gradient of the smooth primitives agree with MPFR (value, central differences). All the
 * expressions go into one program, so the test costs one build per precision. (The derivative code of interval
 * Newton, over lanes as the kernels run it: tests/t_expr_lanes_fp.c.) */
#include "implicits/device_eval.h"
#include "t_expr_oracle.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#define TOL 1e-9
#else
#define FP64 0
#define TOL 2e-3
#endif

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

static int is_smooth(const char *text) {
    for (size_t i = 0; i < sizeof smooth / sizeof smooth[0]; i++)
        if (strcmp(text, smooth[i]) == 0)
            return 1;
    return 0;
}

/* The MPFR derivative along axis at p by a central difference of step h (the truncation error is O(h^2)). */
static double oracle_partial(const iacsg_expr *e, const double p[4], int axis) {
    double h = 0x1p-20, q[4];
    mpfr_t a, b;
    mpfr_inits2(EXPR_ORACLE_PREC, a, b, (mpfr_ptr)0);
    memcpy(q, p, sizeof q);
    q[axis] = p[axis] + h;
    int ok = expr_oracle(e, q, a);
    q[axis] = p[axis] - h;
    ok = ok && expr_oracle(e, q, b);
    mpfr_sub(a, a, b, MPFR_RNDN);
    double g = ok ? mpfr_get_d(a, MPFR_RNDN) / (2 * h) : NAN;
    mpfr_clears(a, b, (mpfr_ptr)0);
    return g;
}

TEST_FP(expr_device_contains) {
    static char texts[MAX_EXPRS][8192];
    const char *names[64];
    iacsg_expr *exprs[MAX_EXPRS];
    int n = 0, nprim = expr_primitive_names(names, 64);
    for (int i = 0; i < nprim; i++)
        snprintf(texts[n++], sizeof texts[0], "%s", names[i]);
    for (int i = 0; i < expr_every_op_count; i++)
        snprintf(texts[n++], sizeof texts[0], "%s", expr_every_op_texts[i]);
    while (n < MAX_EXPRS)
        expr_random_text(test_rng(), 4, texts[n++], sizeof texts[0]);
    for (int i = 0; i < n; i++)
        CHECK(iacsg_expr_parse(texts[i], "<test>", &exprs[i], NULL) == IACSG_OK, "'%s' does not compile", texts[i]);

    size_t q = (size_t)n * BOXES;
    int *which = malloc(q * sizeof *which);
    double *in = malloc(DEVICE_EVAL_IN * q * sizeof *in), *out = malloc(DEVICE_EVAL_OUT * q * sizeof *out);
    CHECK(which && in && out, "out of memory");
    for (size_t k = 0; k < q; k++) {
        which[k] = (int)(k / BOXES);
        expr_random_box(test_rng(), in + DEVICE_EVAL_IN * k);
    }
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "%s", err.message);
    iacsg_status st = device_eval(&rt, (const iacsg_expr *const *)exprs, n, FP64, q, which, in, out, &err);
    clrt_close(&rt);
    CHECK(st == IACSG_OK, "%s", err.message);

    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    long checked = 0, values = 0, grads = 0;
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
        if (which[k] >= nprim || !is_smooth(text))
            continue;
        double p[4] = {device_point(v[0]), device_point(v[2]), device_point(v[4]), device_point(v[6])};
        if (!expr_oracle(e, p, y))
            continue;
        double exact = mpfr_get_d(y, MPFR_RNDN), scale = 1 + fabs(exact);
        values++;
        CHECK(fabs(o[2] - exact) <= TOL * scale * 100, "device: %s at (%a, %a, %a): f = %.17g, exact %.17g", text,
              p[0], p[1], p[2], o[2], exact);
        for (int axis = 0; axis < 3; axis++) {
            double g = oracle_partial(e, p, axis);
            if (!isfinite(g))
                continue;
            grads++;
            CHECK(fabs(o[3 + axis] - g) <= 1e-3 * (1 + fabs(g)) * (FP64 ? 1 : 100),
                  "device: gradient of %s at (%a, %a, %a), axis %d: %.17g, central difference %.17g", text, p[0],
                  p[1], p[2], axis, o[3 + axis], g);
        }
    }
    mpfr_clear(y);
    for (int i = 0; i < n; i++)
        iacsg_expr_destroy(exprs[i]);
    free(which);
    free(in);
    free(out);
    test_note("%d expressions, %zu boxes, %ld points checked; %ld values and %ld partials of smooth primitives", n, q,
              checked, values, grads);
}
