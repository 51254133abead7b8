/* tests/t_expr_lanes_fp.c -- the emitted code over SIMD lanes, as the kernels run it, on the device (float and
 * double), against MPFR:
 *   expr_lanes_slope: iacsg_Fdv's enclosure of the derivative along a direction (interval Newton's F',
 *     kernels/packet.h) contains the MPFR central difference at points of random boxes, for random expressions,
 *     every primitive and every op; and its value part contains the MPFR value.
 *   expr_lanes_slope_groups: the same for unions in groups, through the kernels' packet_Fdv over their groups.
 *   expr_undefined_agree: the rule for undefined operands (ia/ia.h) in every code path on the same inputs:
 *     unions and an intersection with an operand outside its domain, of two parts and of 17 (the union in groups).
 *     The host evaluator, the scalar F and the point f (implicits/device_eval.c) and the kernels' own packet_F
 *     over lanes each enclose the MPFR value (which follows the rule) at points of the same boxes and agree on
 *     whether a box may hold the surface; f is NaN exactly where the expression is undefined; and rendered along
 *     +x, the sphere's half at x < 0 is in the image, at its exact depth.
 */
#include "clrt.h"
#include "implicits/device_eval.h"
#include "kernels/params.h"
#include "t_expr_oracle.h"
#include "t_lanes_run.h"
#include "t_render_util.h"
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

extern const char iacsg_cl_ia[], iacsg_cl_kernels[];

/* Per work-item, PACKET_LANES queries, one per lane, of expression which[g]: in[11q ..] = the box x0, x1, ..., t1
 * and a direction dx, dy, dz; out[4q ..] = the value's enclosure and the derivative's (NaN where there is none).
 * The cases (which expression, which functions) are written between the two halves. */
static const char lanes_head[] =
    "__kernel void lanes_eval(__global const int *which, __global const ia_real *in, __global ia_real *out) {\n"
    "    size_t g = get_global_id(0);\n"
    "    ia_real v[11][IA_VW];\n"
    "    for (int l = 0; l < IA_VW; l++)\n"
    "        for (int k = 0; k < 11; k++)\n"
    "            v[k][l] = in[11 * (g * IA_VW + l) + k];\n"
    "    iav b[4], d[3];\n"
    "    for (int c = 0; c < 4; c++)\n"
    "        b[c] = iav_make(IAV_LOAD(v[2 * c]), IAV_LOAD(v[2 * c + 1]));\n"
    "    for (int c = 0; c < 3; c++)\n"
    "        d[c] = iav_make(IAV_LOAD(v[8 + c]), IAV_LOAD(v[8 + c]));\n"
    "    iav r = iav_point(NAN), s = iav_point(NAN);\n"
    "    switch (which[g]) {\n";
static const char lanes_tail[] = "    }\n"
                                 "    ia_real o[4][IA_VW];\n"
                                 "    IAV_STORE(r.lo, o[0]);\n"
                                 "    IAV_STORE(r.hi, o[1]);\n"
                                 "    IAV_STORE(s.lo, o[2]);\n"
                                 "    IAV_STORE(s.hi, o[3]);\n"
                                 "    for (int l = 0; l < IA_VW; l++)\n"
                                 "        for (int k = 0; k < 4; k++)\n"
                                 "            out[4 * (g * IA_VW + l) + k] = o[k][l];\n"
                                 "}\n";

#define LANES_IN 11
#define LANES_OUT 4

/* Runs the lanes kernel with `cases` after sources[0 .. n-1] over `items` work-items and fills out (LANES_OUT
 * per query). in: LANES_IN exact doubles per query, the box (8 bounds) rounded outward to floats without fp64. */
static void lanes_eval_run(const char **sources, int n, const char *cases, size_t items, const int *which,
                           const double *in, double *out) {
    char *kernel = lanes_kernel_source(lanes_head, cases, lanes_tail);
    sources[n] = kernel;
    lanes_run(&(lanes_job){.sources = sources, .nsources = (size_t)n + 1, .kernel = "lanes_eval", .items = items,
                           .which = which, .in = in, .in_per_query = LANES_IN, .bounds_per_query = 8, .out = out,
                           .out_per_query = LANES_OUT});
    free(kernel);
}

static char *emit(const iacsg_expr *e, const char *prefix) {
    char *src = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_expr_emit_cl(e, prefix, &src, &err) == IACSG_OK, "%s", err.message);
    return src;
}

/* ---- Fdv */

/* One query's value and derivative (out: o) over the box and direction v against MPFR at 6 random points of the
 * box (the derivative only where `with_fdv`); counts the checks made. */
static void check_query(const iacsg_expr *e, const char *text, int with_fdv, const double *v, const double *o,
                        mpfr_ptr y, long *values, long *slopes) {
    for (int s = 0; s < 6; s++) {
        double p[4];
        expr_random_point(test_rng(), v, p);
        if (!expr_oracle(e, p, y))
            continue;
        (*values)++;
        CHECK(mpfr_cmp_d(y, o[0]) >= 0 && mpfr_cmp_d(y, o[1]) <= 0,
              "lanes: '%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a] gave [%a, %a], but at (%a, %a, %a, %a) "
              "the value is %.20g",
              text, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], o[0], o[1], p[0], p[1], p[2], p[3],
              mpfr_get_d(y, MPFR_RNDN));
        if (!with_fdv || !expr_oracle_slope(e, p, v + 8, y))
            continue;
        (*slopes)++;
        CHECK(mpfr_cmp_d(y, o[2]) >= 0 && mpfr_cmp_d(y, o[3]) <= 0,
              "lanes: '%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a] gave the derivative along (%a, %a, %a) "
              "in [%a, %a], but at (%a, %a, %a, %a) it is %.20g",
              text, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], o[2], o[3], p[0], p[1], p[2],
              p[3], mpfr_get_d(y, MPFR_RNDN));
    }
}

/* Random boxes, and directions the device holds exactly, for q queries. */
static void slope_queries(size_t q, double *in) {
    for (size_t k = 0; k < q; k++) {
        expr_random_box(test_rng(), in + LANES_IN * k);
        for (int c = 0; c < 3; c++)
            in[LANES_IN * k + 8 + c] = (float)(2 * test_rand_unit(test_rng()) - 1);
    }
}

#define MAX_EXPRS 72
#define SLOPE_ITEMS 6 /* work-items per expression: 6 x 16 boxes */

TEST_FP(expr_lanes_slope) {
    static char texts[MAX_EXPRS][EXPR_TEXT_SIZE];
    iacsg_expr *exprs[MAX_EXPRS];
    int n = expr_test_texts(test_rng(), texts, MAX_EXPRS);
    const char *sources[MAX_EXPRS + 2] = {iacsg_cl_ia};
    static char cases[MAX_EXPRS * 200];
    size_t used = 0;
    int with_fdv[MAX_EXPRS], nfdv = 0;
    for (int i = 0; i < n; i++) {
        CHECK(iacsg_expr_parse(texts[i], "<test>", &exprs[i], NULL) == IACSG_OK, "'%s' does not compile", texts[i]);
        char prefix[16], call[32];
        snprintf(prefix, sizeof prefix, "e%d", i);
        char *src = emit(exprs[i], prefix);
        snprintf(call, sizeof call, "e%d_Fdv(", i);
        with_fdv[i] = strstr(src, call) != NULL;
        CHECK(!strstr(src, "IACSG_GROUPS"), "'%s': a union in groups; the test calls e<k>_Fv", texts[i]);
        nfdv += with_fdv[i];
        sources[1 + i] = src;
        used += (size_t)snprintf(cases + used, sizeof cases - used, "    case %d: r = e%d_Fv(b[0], b[1], b[2], b[3]);",
                                 i, i);
        if (with_fdv[i])
            used += (size_t)snprintf(cases + used, sizeof cases - used,
                                     " (void)e%d_Fdv(b[0], b[1], b[2], b[3], d[0], d[1], d[2], &s);", i);
        used += (size_t)snprintf(cases + used, sizeof cases - used, " break;\n");
    }
    size_t items = (size_t)n * SLOPE_ITEMS, q = items * PACKET_LANES;
    int *which = malloc(items * sizeof *which);
    double *in = malloc(LANES_IN * q * sizeof *in), *out = malloc(LANES_OUT * q * sizeof *out);
    CHECK(which && in && out, "out of memory");
    for (size_t g = 0; g < items; g++)
        which[g] = (int)(g / SLOPE_ITEMS);
    slope_queries(q, in);
    lanes_eval_run(sources, n + 1, cases, items, which, in, out);
    for (int i = 0; i < n; i++)
        free((char *)sources[1 + i]);

    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    long values = 0, slopes = 0;
    for (size_t k = 0; k < q; k++) {
        int x = which[k / PACKET_LANES];
        check_query(exprs[x], texts[x], with_fdv[x], in + LANES_IN * k, out + LANES_OUT * k, y, &values, &slopes);
    }
    mpfr_clear(y);
    for (int i = 0; i < n; i++)
        iacsg_expr_destroy(exprs[i]);
    free(which);
    free(in);
    free(out);
    test_note("%d expressions (%d with derivative code), %zu boxes: %ld values and %ld derivatives checked", n, nfdv,
              q, values, slopes);
    CHECK(nfdv >= 24 && slopes >= 20000, "too little checked to mean anything");
}

/* Whether `text` compiles with derivative code (where it has no union in groups). */
static int has_fdv(const char *text) {
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(text, "<test>", &e, NULL) == IACSG_OK, "'%s' does not compile", text);
    char *src = emit(e, "h");
    int with = strstr(src, "h_Fdv(") != NULL;
    free(src);
    iacsg_expr_destroy(e);
    return with;
}

#define GROUP_UNIONS 1
#define GROUP_PARTS 20 /* at least EMIT_GROUP_MIN_PARTS (implicits/emit.c): 5 groups of 4 */
#define GROUP_ITEMS 120

/* Unions in groups of parts with derivative code, whose groups' derivative code is a function each
 * (implicits/emit.c), through the kernels' packet_Fdv over all the groups (kernels/packet.h: the min of their values
 * and the min's derivative by iav_dmin), as the effects' march takes it: the value and the derivative enclose
 * MPFR's at points of random boxes. */
TEST_FP(expr_lanes_slope_groups) {
    static char texts[2 * MAX_EXPRS][EXPR_TEXT_SIZE];
    int n = expr_test_texts(test_rng(), texts, 2 * MAX_EXPRS), next = 0;
    size_t size = GROUP_PARTS * EXPR_TEXT_SIZE + 8, q = GROUP_ITEMS * PACKET_LANES;
    char *text = malloc(size);
    int *which = calloc(GROUP_ITEMS, sizeof *which);
    double *in = malloc(LANES_IN * q * sizeof *in), *out = malloc(LANES_OUT * q * sizeof *out);
    CHECK(text && which && in && out, "out of memory");
    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    long values = 0, slopes = 0;
    for (int u = 0; u < GROUP_UNIONS; u++) {
        size_t used = (size_t)snprintf(text, size, "min(");
        for (int parts = 0; parts < GROUP_PARTS; next++) {
            CHECK(next < n, "too few expressions with derivative code for %d unions", GROUP_UNIONS);
            if (has_fdv(texts[next]))
                used += (size_t)snprintf(text + used, size - used, "%s%s", parts++ ? ", " : "", texts[next]);
        }
        snprintf(text + used, size - used, ")");
        iacsg_expr *e = NULL;
        CHECK(iacsg_expr_parse(text, "<test>", &e, NULL) == IACSG_OK, "'%.80s...' does not compile", text);
        char *src = emit(e, "iacsg");
        CHECK(strstr(src, "iacsg_Fdv_group("), "'%.80s...': no derivative code for its groups", text);
        const char *sources[4] = {iacsg_cl_ia, src, iacsg_cl_kernels};
        slope_queries(q, in);
        lanes_eval_run(sources, 3, "    case 0: r = packet_Fdv(~(ulong)0, b[0], b[1], b[2], b[3], d, &s); break;\n",
                       GROUP_ITEMS, which, in, out);
        free(src);
        for (size_t k = 0; k < q; k++)
            check_query(e, text, 1, in + LANES_IN * k, out + LANES_OUT * k, y, &values, &slopes);
        iacsg_expr_destroy(e);
    }
    mpfr_clear(y);
    free(text);
    free(which);
    free(in);
    free(out);
    test_note("%d unions of %d parts in groups, %zu boxes each: %ld values and %ld derivatives checked", GROUP_UNIONS,
              GROUP_PARTS, q, values, slopes);
    CHECK(slopes >= 5000, "too little checked to mean anything");
}

/* ---- undefined operands */

/* 15 small spheres far from the others (z = 1.9), so that a union with them has 17 parts: the groups. */
static void union_in_groups(const char *first, char *buf, size_t size) {
    size_t used = (size_t)snprintf(buf, size, "union(%s, sphere", first);
    for (int k = 0; k < 15; k++)
        used += (size_t)snprintf(buf + used, size - used, ", move(sphere(0.05), %g, 1.9, 1.9)", -1.5 + 0.2 * k);
    snprintf(buf + used, size - used, ")");
}

/* The corner as the device holds it: rounded down to float without fp64 (device_eval.h). */
static double device_point(double v) {
    if (FP64)
        return v;
    float f = (float)v;
    return (double)f > v ? nextafterf(f, -INFINITY) : f;
}

static int holds(mpfr_srcptr y, const double r[2]) { return mpfr_cmp_d(y, r[0]) >= 0 && mpfr_cmp_d(y, r[1]) <= 0; }
static int may_hold_zero(const double r[2]) { return r[0] <= 0 && r[1] >= 0; }

#define AGREE_ITEMS 40 /* work-items per expression: 40 x 16 boxes */

/* The boxes: the issue's [-1.01, -0.99] x {0} x {0} (only the sphere is defined there), boxes across x = 0, and
 * random ones. */
static void agree_box(size_t k, double v[LANES_IN]) {
    static const double issue[8] = {-1.01, -0.99, 0, 0, 0, 0, 0, 0};
    if (k == 0)
        memcpy(v, issue, sizeof issue);
    else
        expr_random_box(test_rng(), v);
    if (k % 3 == 1) { /* across the domain edge x = 0 */
        double w = ldexp(1, -(int)(k % 40));
        v[0] = -w * test_rand_unit(test_rng());
        v[1] = w * test_rand_unit(test_rng());
    }
    v[8] = 1, v[9] = v[10] = 0;
}

/* `is_union`: the sphere is kept where the other operand is undefined (in an intersection it is not). */
static void check_agreement(const char *text, int is_union) {
    iacsg_expr *e = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    char *src = emit(e, "iacsg");
    int grouped = strstr(src, "IACSG_GROUPS") != NULL;
    const char *sources[4] = {iacsg_cl_ia, src, iacsg_cl_kernels};
    size_t q = AGREE_ITEMS * PACKET_LANES;
    int *which = calloc(AGREE_ITEMS, sizeof *which), *which_q = calloc(q, sizeof *which_q);
    double *in = malloc(LANES_IN * q * sizeof *in), *lanes = malloc(LANES_OUT * q * sizeof *lanes);
    double *dev_in = malloc(DEVICE_EVAL_IN * q * sizeof *dev_in), *dev = malloc(DEVICE_EVAL_OUT * q * sizeof *dev);
    CHECK(which && which_q && in && lanes && dev_in && dev, "out of memory");
    for (size_t k = 0; k < q; k++) {
        agree_box(k, in + LANES_IN * k);
        memcpy(dev_in + DEVICE_EVAL_IN * k, in + LANES_IN * k, DEVICE_EVAL_IN * sizeof *dev_in);
    }
    /* the kernels' union of the groups (packet_F), as the renderer evaluates it */
    lanes_eval_run(sources, 3, "    case 0: r = packet_F(~(ulong)0, b[0], b[1], b[2], b[3]); break;\n", AGREE_ITEMS,
                   which, in, lanes);
    free(src);
    clrt rt;
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "%s", err.message);
    iacsg_status st = device_eval(&rt, (const iacsg_expr *const *)&e, 1, FP64, q, which_q, dev_in, dev, &err);
    clrt_close(&rt);
    CHECK(st == IACSG_OK, "%s", err.message);

    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    long checked = 0, points = 0, undefined_points = 0, off_domain = 0, decided = 0;
    for (size_t k = 0; k < q; k++) {
        const double *v = in + LANES_IN * k, *l = lanes + LANES_OUT * k, *d = dev + DEVICE_EVAL_OUT * k;
        double host[2];
        CHECK(iacsg_expr_eval_vars(e, FP64, v, host, &err) == IACSG_OK, "%s", err.message);
        if (k == 0) /* the issue's box: the sphere's surface is there, at x = -1 */
            CHECK(may_hold_zero(host) == is_union && may_hold_zero(d) == is_union && may_hold_zero(l) == is_union,
                  "'%s' over [-1.01, -0.99] x {0} x {0}: host [%a, %a], F [%a, %a], lanes [%a, %a] (the sphere "
                  "alone is [-0.0199, 0.0201])",
                  text, host[0], host[1], d[0], d[1], l[0], l[1]);
        for (int s = 0; s < 6; s++) {
            double p[4];
            expr_random_point(test_rng(), v, p);
            if (!expr_oracle(e, p, y))
                continue;
            checked++;
            CHECK(holds(y, host) && holds(y, d) && holds(y, l),
                  "'%s' over x [%a, %a] y [%a, %a] z [%a, %a]: host [%a, %a], F [%a, %a], lanes [%a, %a], but at "
                  "(%a, %a, %a) the value is %.17g",
                  text, v[0], v[1], v[2], v[3], v[4], v[5], host[0], host[1], d[0], d[1], l[0], l[1], p[0], p[1],
                  p[2], mpfr_get_d(y, MPFR_RNDN));
        }
        /* whether the box may hold the surface, where no bound is near 0 (rounding differs between them) */
        double near = 1e-4;
        if (fabs(host[0]) > near && fabs(host[1]) > near && fabs(d[0]) > near && fabs(d[1]) > near &&
            fabs(l[0]) > near && fabs(l[1]) > near) {
            decided++;
            CHECK(may_hold_zero(host) == may_hold_zero(d) && may_hold_zero(d) == may_hold_zero(l),
                  "'%s' over x [%a, %a] y [%a, %a] z [%a, %a]: host [%a, %a], F [%a, %a], lanes [%a, %a] disagree on 0",
                  text, v[0], v[1], v[2], v[3], v[4], v[5], host[0], host[1], d[0], d[1], l[0], l[1]);
        }
        /* the point code at the corner */
        double c[4] = {device_point(v[0]), device_point(v[2]), device_point(v[4]), device_point(v[6])};
        int defined = expr_oracle(e, c, y);
        points++;
        undefined_points += !defined;
        off_domain += c[0] < 0; /* where sqrt(x) or log(x) is undefined */
        CHECK(defined == !isnan(d[2]), "'%s' at (%a, %a, %a): f = %.17g, but the expression is %s there", text, c[0],
              c[1], c[2], d[2], defined ? "defined" : "undefined");
        if (defined) {
            double exact = mpfr_get_d(y, MPFR_RNDN);
            CHECK(fabs(d[2] - exact) <= (FP64 ? 1e-12 : 1e-5) * (1 + fabs(exact)), "'%s' at (%a, %a, %a): f = %.17g, "
                  "exact %.17g", text, c[0], c[1], c[2], d[2], exact);
        }
    }
    mpfr_clear(y);
    iacsg_expr_destroy(e);
    free(which);
    free(which_q);
    free(in);
    free(lanes);
    free(dev_in);
    free(dev);
    test_note("%s%.60s...: %zu boxes, %ld values in host, F and lanes, %ld boxes decided alike; f at %ld corners (%ld "
              "at x < 0, %ld undefined)",
              grouped ? "(groups) " : "", text, q, checked, decided, points, off_domain, undefined_points);
    CHECK(checked > 1000 && decided > 100 && off_domain > 50 && points - undefined_points > 50,
          "too little checked to mean anything");
}

/* Rendered along +x: every ray through the unit disk of the yz plane meets the sphere's half at x < 0 first. */
static void check_sphere_half(const char *text) {
    iacsg_expr *e = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    char *cl = emit(e, "iacsg");
    iacsg_expr_destroy(e);
    iacsg_view view = {.width = 32, .height = 32, .eps = 1e-5,
                       .camera = {.eye = {-3, 0, 0}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40, .ortho_height = 4},
                       .bounds = {-2, -2, -2, 2, 2, 2}};
    iacsg_render_config config = {.device = 0, .fp64 = FP64};
    iacsg_frame fr;
    render_cl(cl, &config, &view, &fr);
    free(cl);
    ia_real p[PARAM_COUNT];
    view_params(&view, p);
    long inside = 0, wrong = 0;
    for (int j = 0; j < view.height; j++)
        for (int i = 0; i < view.width; i++) {
            double o[3], d[3];
            pixel_ray(p, &view, i, j, o, d);
            double rr = o[1] * o[1] + o[2] * o[2];
            if (rr > 0.9) /* near the rim the root is grazing */
                continue;
            inside++;
            double root = -sqrt(1 - rr) - o[0], depth = fr.depth[(size_t)j * view.width + i];
            if (!(depth <= root * (1 + 1e-12) && depth >= root - 1e-3) && wrong++ < 5)
                test_note("pixel (%d, %d): depth %.9g, the sphere at %.9g", i, j, depth, root);
        }
    iacsg_frame_free(&fr);
    CHECK(inside > 150 && wrong == 0, "'%.60s...': %ld of %ld pixels miss the sphere's half at x < 0", text, wrong,
          inside);
}

TEST_FP(expr_undefined_agree) {
    char grouped[2048];
    check_agreement("min(sphere, sqrt(x) - 1)", 1);
    check_agreement("max(sphere, sqrt(x) - 1)", 0);
    check_agreement("min(sphere, log(x) + 1)", 1);
    union_in_groups("sqrt(x) - 1", grouped, sizeof grouped);
    check_agreement(grouped, 1);
    check_sphere_half("min(sphere, sqrt(x) - 1)");
    check_sphere_half(grouped);
}
