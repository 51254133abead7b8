/* tests/t_expr_oracle.c -- see t_expr_oracle.h. */
#include "t_expr_oracle.h"
#include "implicits/library.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RN MPFR_RNDN

/* pow on the domain of IEEE 1788 (and ia_pow): x > 0, or x = 0 with y > 0. */
static int oracle_pow(mpfr_ptr r, mpfr_srcptr a, mpfr_srcptr b, mpfr_rnd_t rnd) {
    if (mpfr_sgn(a) < 0 || (mpfr_zero_p(a) && mpfr_sgn(b) <= 0)) {
        mpfr_set_nan(r);
        return 0;
    }
    return mpfr_pow(r, a, b, rnd);
}

/* The compiler turns a power whose exponent is a constant integer of at most 65536 into pown
 * (implicits/simplify.c), defined for a negative base too: x^-1 is 1/x, x^3 is x*x*x. */
static int oracle_pown_exponent(mpfr_srcptr b) { return mpfr_integer_p(b) && mpfr_cmpabs_ui(b, 65536) <= 0; }

static void apply(int op, mpfr_ptr R, mpfr_srcptr A, mpfr_srcptr B, long N) {
    (void)B, (void)N;
    switch (op) {
#define OP(id, name, arity, nary, iv, pt, d, td, oracle, undef, empty)                                               \
    case OP_##id: oracle; break;
#include "implicits/ops.def"
#undef OP
    default: mpfr_set_nan(R);
    }
}

/* The value at p with prec bits for every node, into y. */
static int oracle_at(const iacsg_expr *e, mpfr_srcptr const p[4], mpfr_ptr y, mpfr_prec_t prec) {
    const dag *d = &e->raw;
    int *order;
    int count = dag_reachable(d, e->raw_root, &order);
    CHECK(count > 0, "out of memory");
    mpfr_t *v = malloc(((size_t)e->raw_root + 1) * sizeof *v);
    char *varies = malloc((size_t)e->raw_root + 1); /* the node depends on x, y, z or t */
    CHECK(v != NULL && varies != NULL, "out of memory");
    int ok = 1;
    for (int k = 0; k < count; k++) {
        int i = order[k];
        const dag_node *n = &d->nodes[i];
        mpfr_init2(v[i], prec);
        varies[i] = n->op <= OP_T || (n->a >= 0 && varies[n->a]) || (n->b >= 0 && varies[n->b]);
        if (n->op <= OP_T)
            mpfr_set(v[i], p[n->op], RN);
        else if (n->op == OP_CONST && n->n >= 0)
            mpfr_set_str(v[i], d->texts[n->n], 10, RN);
        else if (n->op == OP_CONST) /* exact values without text (lo == hi) */
            mpfr_set_d(v[i], n->lo, RN);
        else if (n->op == OP_PI)
            mpfr_const_pi(v[i], RN);
        else if (n->op == OP_E)
            mpfr_set_ui(v[i], 1, RN), mpfr_exp(v[i], v[i], RN);
        else if (n->op == OP_MIN && (!mpfr_number_p(v[n->a]) || !mpfr_number_p(v[n->b])))
            mpfr_set(v[i], mpfr_number_p(v[n->a]) ? v[n->a] : v[n->b], RN); /* undefined is outside (ia/ia.h) */
        else if (!mpfr_number_p(v[n->a]) || (n->b >= 0 && !mpfr_number_p(v[n->b])))
            mpfr_set_nan(v[i]); /* undefined operands make the whole expression undefined at p */
        else if (n->op == OP_POW && !varies[n->b] && oracle_pown_exponent(v[n->b]))
            mpfr_pow(v[i], v[n->a], v[n->b], RN); /* pown: +-inf at a pole, so undefined there */
        else
            apply(n->op, v[i], v[n->a], n->b >= 0 ? v[n->b] : v[n->a], n->n);
    }
    ok = mpfr_number_p(v[e->raw_root]);
    mpfr_set(y, v[e->raw_root], RN);
    for (int k = 0; k < count; k++)
        mpfr_clear(v[order[k]]);
    free(v);
    free(varies);
    free(order);
    return ok;
}

int expr_oracle(const iacsg_expr *e, const double p[4], mpfr_ptr y) {
    mpfr_t q[4];
    mpfr_srcptr qp[4];
    for (int k = 0; k < 4; k++) {
        mpfr_init2(q[k], 64);
        mpfr_set_d(q[k], p[k], RN);
        qp[k] = q[k];
    }
    int ok = oracle_at(e, qp, y, EXPR_ORACLE_PREC);
    for (int k = 0; k < 4; k++)
        mpfr_clear(q[k]);
    return ok;
}

int expr_oracle_slope(const iacsg_expr *e, const double p[4], const double dir[3], mpfr_ptr slope) {
    mpfr_t q[4];
    mpfr_srcptr qp[4];
    for (int k = 0; k < 4; k++) {
        mpfr_init2(q[k], EXPR_ORACLE_PREC);
        qp[k] = q[k];
    }
    int defined = 1, known = 0;
    /* (f(p + h dir) - f(p - h dir)) / 2h keeps prec - 80 bits of f's magnitude: a slope far smaller than f (x^500
     * with |x| < 1 in x^500 - 1) cancels, and is computed again with 4 times the bits; past that, a difference
     * of 0 is taken as a slope of 0 */
    for (mpfr_prec_t prec = EXPR_ORACLE_PREC; defined && !known && prec <= 4 * EXPR_ORACLE_PREC; prec *= 4) {
        mpfr_t f[2];
        mpfr_inits2(prec, f[0], f[1], (mpfr_ptr)0);
        for (int side = 0; side < 2 && defined; side++) {
            for (int k = 0; k < 4; k++) { /* p +- 2^-80 dir, exact in EXPR_ORACLE_PREC bits */
                mpfr_set_d(q[k], k < 3 ? dir[k] : 0, RN);
                mpfr_mul_2si(q[k], q[k], -80, RN);
                if (side)
                    mpfr_neg(q[k], q[k], RN);
                mpfr_add_d(q[k], q[k], p[k], RN);
            }
            defined = oracle_at(e, qp, f[side], prec);
        }
        if (defined) {
            mpfr_sub(f[1], f[0], f[1], RN);
            known = mpfr_zero_p(f[1]) ? prec > EXPR_ORACLE_PREC
                                      : mpfr_zero_p(f[0]) || mpfr_get_exp(f[0]) - mpfr_get_exp(f[1]) < prec - 140;
            mpfr_mul_2si(slope, f[1], 79, RN);
        }
        mpfr_clears(f[0], f[1], (mpfr_ptr)0);
    }
    for (int k = 0; k < 4; k++)
        mpfr_clear(q[k]);
    return defined && known;
}

static double unit(test_rng_t *r) { return test_rand_unit(r); }
static int below(test_rng_t *r, int n) { return (int)(test_rand_u64(r) % (uint64_t)n); }

static const char *const constants[] = {"0.1", "3", "2.5e-1", "0.7", "1.5", "pi", "e", "1e-3", "0.3333", "2"};

/* Appends a random expression of depth <= depth. The buffer is big enough for depth <= 5 at any branching. */
static void gen(test_rng_t *r, int depth, char *buf, size_t size) {
    size_t len = strlen(buf);
    char *out = buf + len;
    size_t room = size - len;
    if (room < 64)
        return;
    if (depth <= 0 || below(r, 5) == 0) {
        static const char *const vars[] = {"x", "y", "z", "t", "x", "y"};
        if (below(r, 3) == 0)
            snprintf(out, room, "%s", constants[below(r, 10)]);
        else
            snprintf(out, room, "%s", vars[below(r, 6)]);
        return;
    }
    int kind = below(r, 10);
    if (kind <= 3) { /* binary operator */
        static const char ops[] = "+-*/|&\\";
        strcat(buf, "(");
        gen(r, depth - 1, buf, size);
        size_t l = strlen(buf);
        snprintf(buf + l, size - l, " %c ", ops[below(r, 7)]);
        gen(r, depth - 1, buf, size);
        strcat(buf, ")");
    } else if (kind == 4) { /* powers: integer (pown, sqr) or real (pow) */
        static const char *const exps[] = {"2", "3", "4", "-1", "-2", "0.5", "1.5", "5"};
        strcat(buf, "(");
        gen(r, depth - 1, buf, size);
        size_t l = strlen(buf);
        snprintf(buf + l, size - l, ")^%s", exps[below(r, 8)]);
    } else if (kind <= 7) { /* a function of ops.def */
        int op;
        do
            op = below(r, OP_COUNT);
        while (!dag_ops[op].name[0]);
        snprintf(out, room, "%s(", dag_ops[op].name);
        for (int k = 0; k < dag_ops[op].arity + (dag_ops[op].nary && below(r, 2)); k++) {
            if (k)
                strcat(buf, ", ");
            gen(r, depth - 1, buf, size);
        }
        strcat(buf, ")");
    } else if (kind == 8) { /* a transform of a subexpression */
        static const char *const forms[] = {"move(%s, 0.5, -0.25, 0.1)", "scale(%s, 1.5)", "scale(%s, 0.5, 2, 1)",
                                            "rotatex(%s, 0.3)", "rotatey(%s, pi/3)", "rotatez(%s, -1)",
                                            "rotate(%s, 0.7, 1, 2, 3)"};
        char sub[4096] = "";
        gen(r, depth - 1, sub, sizeof sub < room ? sizeof sub : room);
        snprintf(out, room, forms[below(r, 7)], sub);
    } else { /* a primitive or blend */
        static const char *const forms[] = {"sphere", "torus(R=0.8, r=0.3)", "tangle", "decocube", "heart",
                                            "box(0.5, 1)", "cone", "capsule", "gyroid(k=2)", "citrus",
                                            "smooth_union(sphere, box, 0.1)", "sigmoid_blend(decocube, sphere)",
                                            "product(x, y - 0.5)", "morph(sphere, box, 0.3)"};
        snprintf(out, room, "%s", forms[below(r, 14)]);
    }
}

void expr_random_text(test_rng_t *r, int depth, char *buf, size_t size) {
    buf[0] = '\0';
    gen(r, depth, buf, size);
}

void expr_random_box(test_rng_t *r, double v[8]) {
    for (int k = 0; k < 4; k++) {
        double c = k < 3 ? 4 * unit(r) - 2 : unit(r);
        double w = below(r, 8) == 0 ? 0 : ldexp(unit(r), -below(r, 31)) * 4;
        v[2 * k] = c - w / 2;
        v[2 * k + 1] = c + w / 2;
    }
}

void expr_random_point(test_rng_t *r, const double v[8], double p[4]) {
    int corner = below(r, 3) == 0;
    for (int k = 0; k < 4; k++) {
        double u = corner ? (double)below(r, 2) : unit(r);
        p[k] = v[2 * k] + u * (v[2 * k + 1] - v[2 * k]);
        if (p[k] < v[2 * k] || p[k] > v[2 * k + 1])
            p[k] = v[2 * k];
    }
}

const char *const expr_every_op_texts[] = {
    "-x",      "x + y",     "x - y",      "x * y",       "x / y",      "x + 0.5",     "x * 0.5",
    "x^3",     "sqr(x)",    "recip(x)",   "sqrt(x)",     "exp(x)",     "log(x)",      "sin(x)",
    "cos(x)",  "tan(x)",    "atan(x)",    "abs(x)",      "min(x, y)",  "max(x, y)",   "pow(x, y)",
};
const int expr_every_op_count = (int)(sizeof expr_every_op_texts / sizeof expr_every_op_texts[0]);

/* Sums and products the simplifier rewrites (implicits/simplify.c: squares completed, constants folded together,
 * point factors pulled out, equal powers joined, u (k u + c) expanded), so that the oracle (the expression as
 * written) checks the rewritten code's enclosures. */
static const char *const rewritten_texts[] = {
    "x^4 - 5*x^2 + y", "x*x - 3*x + 1 + z", "2*x^2 + x - y*y", "y - x^2 + 0.75*x", "8*x^4 - 8*x^2 + 1 - z",
    "z + sqr(x + y) - 0.5*(x + y) + 2", "-(x^2) * 3 + 0.1 + 1.5*x - 0.3333", "4*y^3*(1 - y)^3 + x",
    "x*(x + 1) - y", "x^2*y^2 - z", "2*x*y + z*(3 - 2*z)", "(y - 1)^5 * (0.5*z)^5 * 3",
};

int expr_primitive_names(const char **names, int max) {
    int n = 0;
    for (int i = 0; i < lib_count && n < max; i++)
        if (lib_entries[i].kind == LIB_PRIMITIVE)
            names[n++] = lib_entries[i].name;
    return n;
}

int expr_test_texts(test_rng_t *r, char (*texts)[EXPR_TEXT_SIZE], int max) {
    const char *names[64];
    int n = 0, nprim = expr_primitive_names(names, 64);
    for (int i = 0; i < nprim && n < max; i++)
        snprintf(texts[n++], EXPR_TEXT_SIZE, "%s", names[i]);
    for (int i = 0; i < expr_every_op_count && n < max; i++)
        snprintf(texts[n++], EXPR_TEXT_SIZE, "%s", expr_every_op_texts[i]);
    for (size_t i = 0; i < sizeof rewritten_texts / sizeof rewritten_texts[0] && n < max; i++)
        snprintf(texts[n++], EXPR_TEXT_SIZE, "%s", rewritten_texts[i]);
    while (n < max)
        expr_random_text(r, 4, texts[n++], EXPR_TEXT_SIZE);
    return n;
}
