/* tests/t_expr_gradient_lanes_fp.c -- the emitted point value and gradient over SIMD lanes (P_f_gradv, the
 * kernels' shading: kernels/render.cl's packet_gradients) against the scalar point code (P_f_grad) on the device
 * (float and double), lane by lane at random points, for every primitive, every op of ops.def and random
 * expressions:
 *   expr_lanes_gradient: where the scalar value or component is a number, the lanes' is the same number up to
 *     rounding (and the same infinity); where the scalar value is NaN (undefined), so is the lanes'. A lanes
 *     component may be a number where the scalar one is NaN: it leaves out the products by the components that
 *     are identically 0 (implicits/emit.c: lanes_derivative), which the scalar code computes as 0 * inf.
 */
#include "t_expr_oracle.h"
#include "t_lanes_run.h"

#ifdef IA_FP64
#define TOLERANCE 1e-12
#else
#define TOLERANCE 1e-5
#endif

extern const char iacsg_cl_ia[];

/* Per work-item, PACKET_LANES points of expression which[g], one per lane: in[4q ..] = x, y, z, t; out[8q ..] =
 * the lanes' value and gradient, then the scalar code's at the same point. */
static const char gradient_head[] =
    "__kernel void lanes_gradient(__global const int *which, __global const ia_real *in, __global ia_real *out) {\n"
    "    size_t g = get_global_id(0);\n"
    "    ia_real v[4][IA_VW], o[8][IA_VW];\n"
    "    for (int l = 0; l < IA_VW; l++)\n"
    "        for (int k = 0; k < 4; k++)\n"
    "            v[k][l] = in[4 * (g * IA_VW + l) + k];\n"
    "    ia_realv p[4], f = IAV_R(NAN), lanes[3] = {IAV_R(NAN), IAV_R(NAN), IAV_R(NAN)};\n"
    "    for (int c = 0; c < 4; c++)\n"
    "        p[c] = IAV_LOAD(v[c]);\n"
    "    switch (which[g]) {\n";
static const char gradient_tail[] = "    }\n"
                                    "    IAV_STORE(f, o[0]);\n"
                                    "    for (int c = 0; c < 3; c++)\n"
                                    "        IAV_STORE(lanes[c], o[1 + c]);\n"
                                    "    for (int l = 0; l < IA_VW; l++)\n"
                                    "        for (int k = 0; k < 8; k++)\n"
                                    "            out[8 * (g * IA_VW + l) + k] = o[k][l];\n"
                                    "}\n";
#define GRADIENT_IN 4
#define GRADIENT_OUT 8

/* A case of the kernel: expression i over lanes, then lane by lane. */
static size_t gradient_case(char *buf, size_t size, int i) {
    return (size_t)snprintf(buf, size,
                            "    case %d:\n        f = e%d_f_gradv(p[0], p[1], p[2], p[3], lanes);\n"
                            "        for (int l = 0; l < IA_VW; l++)\n"
                            "            o[4][l] = e%d_f_grad(v[0][l], v[1][l], v[2][l], v[3][l], &o[5][l], &o[6][l], "
                            "&o[7][l]);\n        break;\n",
                            i, i, i);
}

/* Whether the lanes' result agrees with the scalar one (see the top); counts the numbers compared, and those
 * that differ at all. */
static int agrees(double lanes, double scalar, long *numbers, long *differ) {
    if (isnan(scalar) || isinf(scalar))
        return isnan(scalar) || lanes == scalar;
    ++*numbers;
    *differ += lanes != scalar;
    return fabs(lanes - scalar) <= TOLERANCE * (1 + fabs(scalar));
}

#define MAX_EXPRS 72
#define GRADIENT_ITEMS 4 /* work-items per expression: 4 x 16 points */

TEST_FP(expr_lanes_gradient) {
    static char texts[MAX_EXPRS][EXPR_TEXT_SIZE];
    int n = expr_test_texts(test_rng(), texts, MAX_EXPRS);
    const char *sources[MAX_EXPRS + 2] = {iacsg_cl_ia};
    static char cases[MAX_EXPRS * 320];
    size_t used = 0;
    for (int i = 0; i < n; i++) {
        iacsg_expr *e;
        iacsg_error err = {0};
        char prefix[16], *src = NULL;
        CHECK(iacsg_expr_parse(texts[i], "<test>", &e, NULL) == IACSG_OK, "'%s' does not compile", texts[i]);
        snprintf(prefix, sizeof prefix, "e%d", i);
        CHECK(iacsg_expr_emit_cl(e, prefix, &src, &err) == IACSG_OK, "%s", err.message);
        iacsg_expr_destroy(e);
        CHECK(!strstr(src, "IACSG_GROUPS"), "'%s': a union in groups, which has no gradient over lanes", texts[i]);
        sources[1 + i] = src;
        used += gradient_case(cases + used, sizeof cases - used, i);
    }
    CHECK(used < sizeof cases, "the kernel's cases overflow");
    size_t items = (size_t)n * GRADIENT_ITEMS, q = items * PACKET_LANES;
    int *which = malloc(items * sizeof *which);
    double *in = malloc(GRADIENT_IN * q * sizeof *in), *out = malloc(GRADIENT_OUT * q * sizeof *out);
    CHECK(which && in && out, "out of memory");
    for (size_t g = 0; g < items; g++)
        which[g] = (int)(g / GRADIENT_ITEMS);
    for (size_t k = 0; k < q; k++) {
        double box[8];
        expr_random_box(test_rng(), box);
        expr_random_point(test_rng(), box, in + GRADIENT_IN * k);
    }
    char *kernel = lanes_kernel_source(gradient_head, cases, gradient_tail);
    sources[1 + n] = kernel;
    lanes_run(&(lanes_job){.sources = sources, .nsources = (size_t)n + 2, .kernel = "lanes_gradient", .items = items,
                           .which = which, .in = in, .in_per_query = GRADIENT_IN, .out = out,
                           .out_per_query = GRADIENT_OUT});
    free(kernel);
    for (int i = 0; i < n; i++)
        free((char *)sources[1 + i]);

    long numbers = 0, differ = 0, defined = 0;
    static const char *const names[4] = {"f", "df/dx", "df/dy", "df/dz"};
    for (size_t k = 0; k < q; k++) {
        const double *p = in + GRADIENT_IN * k, *o = out + GRADIENT_OUT * k;
        defined += !isnan(o[4]);
        CHECK(isnan(o[0]) == isnan(o[4]), "'%s' at (%a, %a, %a, %a): f = %a over lanes, %a lane by lane",
              texts[which[k / PACKET_LANES]], p[0], p[1], p[2], p[3], o[0], o[4]);
        for (int c = 0; c < 4; c++)
            CHECK(agrees(o[c], o[4 + c], &numbers, &differ),
                  "'%s' at (%a, %a, %a, %a): %s = %.17g over lanes, %.17g lane by lane",
                  texts[which[k / PACKET_LANES]], p[0], p[1], p[2], p[3], names[c], o[c], o[4 + c]);
    }
    free(which);
    free(in);
    free(out);
    test_note("%d expressions, %zu points (%ld where f is defined): %ld numbers compared, %ld not bit-identical", n, q,
              defined, numbers, differ);
    CHECK(defined > (long)q / 2 && numbers > 2 * (long)q, "too little checked to mean anything");
}
