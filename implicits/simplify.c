/* implicits/simplify.c -- stage 4 (see simplify.h). Its dump is dag_dump of the result. */
#include "simplify.h"
#include "eval.h"
#include <float.h>
#include <math.h>
#include <stdlib.h>

#define POWN_MAX 65536 /* larger integer exponents stay pow */
#define SPLIT_POWN_MAX 8 /* x^500 as squares of x^125: 7 % slower than its own chain (the squares test signs) */

static int point_is(const dag *d, int i, double v) { return dag_is_point(d, i) && d->nodes[i].lo == v; }

static double point_value(const dag *d, int i) { return d->nodes[i].lo; }

/* A constant from folded enclosures; its point value (for the point code) is the double midpoint. */
static int folded(dag *d, const double r64[2], const double r32[2], iacsg_error *err) {
    double near = isfinite(r64[0]) && isfinite(r64[1]) ? r64[0] * 0.5 + r64[1] * 0.5
                  : isfinite(r64[0])                  ? r64[0]
                  : isfinite(r64[1])                  ? r64[1]
                                                      : 0;
    float fnear = (float)near;
    return dag_add_const(d, r64[0], r64[1], near, (float)r32[0], (float)r32[1], fnear, NULL, err);
}

/* The exact value of op on point constants when + - * / and small powers happen to be exact in double (checked
 * with fma: the rounding error of a product or quotient is representable), else NAN. Folding 0.25^2 to the
 * point 0.0625, not to an interval around it, keeps the constant usable by the cheaper *_R ops. */
static double exact_value(int op, double a, double b, int n) {
    double r = NAN;
    switch (op) {
    case OP_NEG: return -a;
    case OP_ADD: case OP_ADD_R: case OP_SUB:
        b = op == OP_SUB ? -b : b;
        r = a + b;
        return (r - a == b && r - b == a) ? r : NAN; /* |error| of the sum is r - a - b: zero when both hold */
    case OP_MUL: case OP_MUL_R: r = a * b; return fma(a, b, -r) == 0 ? r : NAN;
    case OP_SQR: r = a * a; return fma(a, a, -r) == 0 ? r : NAN;
    case OP_DIV: r = a / b; return b != 0 && fma(r, b, -a) == 0 ? r : NAN;
    case OP_POWN:
        if (n < 0 || n > 64)
            return NAN;
        r = 1;
        for (int k = 0; k < n && !isnan(r); k++)
            r = exact_value(OP_MUL, r, a, 0);
        return r;
    }
    return NAN;
}

static int fold(dag *d, int op, int a, int b, int n, iacsg_error *err) {
    if (dag_is_point(d, a) && (b < 0 || dag_is_point(d, b))) {
        double v = exact_value(op, d->nodes[a].lo, b >= 0 ? d->nodes[b].lo : 0, n);
        if (isfinite(v) && (double)(float)v == v)
            return dag_add_real(d, v, err);
    }
    const dag_node *A = &d->nodes[a], *B = b >= 0 ? &d->nodes[b] : A;
    double a64[2] = {A->lo, A->hi}, b64[2] = {B->lo, B->hi}, a32[2] = {A->flo, A->fhi}, b32[2] = {B->flo, B->fhi};
    double r64[2], r32[2];
    eval_op_f64(op, a64, b64, n, B->near, r64);
    eval_op_f32(op, a32, b32, n, B->near, r32);
    return folded(d, r64, r32, err);
}

/* A constant enclosing the real between the reals two decimal strings denote (pi and e). */
static int constant_between(dag *d, const char *lo, const char *hi, iacsg_error *err) {
    int l = dag_add_decimal(d, lo, err), h = dag_add_decimal(d, hi, err);
    if (l < 0 || h < 0)
        return -1;
    double r64[2] = {d->nodes[l].lo, d->nodes[h].hi}, r32[2] = {d->nodes[l].flo, d->nodes[h].fhi};
    return folded(d, r64, r32, err);
}

static int make(dag *d, int op, int a, int b, int n, iacsg_error *err);

/* ---- squares completed in sums ---- */

typedef struct {
    int node, sign; /* sign * node */
} term;

enum { SUM_TERMS_MAX = 64 }; /* larger sums are left as they are (each + of a chain flattens the chain below it) */

/* Appends the terms of sign * node i to t[0..n) through + - neg and the constants of +r: the new count, or -1 past
 * SUM_TERMS_MAX terms or as many levels (so that a chain of 10^5 sums is not walked down at each of its nodes). */
static int sum_terms(const dag *d, int i, int sign, term *t, int n, int depth) {
    const dag_node *N = &d->nodes[i];
    if (n < 0 || depth > SUM_TERMS_MAX)
        return -1;
    switch (N->op) {
    case OP_ADD: case OP_ADD_R:
        return sum_terms(d, N->b, sign, t, sum_terms(d, N->a, sign, t, n, depth + 1), depth + 1);
    case OP_SUB: return sum_terms(d, N->b, -sign, t, sum_terms(d, N->a, sign, t, n, depth + 1), depth + 1);
    case OP_NEG: return sum_terms(d, N->a, -sign, t, n, depth + 1);
    }
    if (n >= SUM_TERMS_MAX)
        return -1;
    t[n] = (term){i, sign};
    return n + 1;
}

/* The point coefficient c of u in term t (t = c u: u itself, or u * c), or 0. */
static double linear_in(const dag *d, term t, int u) {
    const dag_node *N = &d->nodes[t.node];
    if (t.node == u)
        return t.sign;
    return N->op == OP_MUL_R && N->a == u ? t.sign * point_value(d, N->b) : 0;
}

/* The point coefficient q of u^2 in term t (t = q u^2: u^2 itself, or u^2 * q), u in *u; or 0. */
static double square_in(const dag *d, term t, int *u) {
    const dag_node *N = &d->nodes[t.node];
    if (N->op == OP_MUL_R && d->nodes[N->a].op == OP_SQR) {
        *u = d->nodes[N->a].a;
        return t.sign * point_value(d, N->b);
    }
    *u = N->a;
    return N->op == OP_SQR ? t.sign : 0;
}

/* One pair q u^2 + c u of the terms (q, c points, h = c / 2q exact in both precisions) as q (u + h)^2, and the
 * constant -q h^2 appended: u then occurs once, so the pair's enclosure is its exact range over u's where
 * q u^2 + c u overestimates it (the tangle's x^4 - 5x^2 = (x^2 - 2.5)^2 - 6.25: over x in [1, 2], [-19, 11]
 * against [-6.25, -4]; near its surface its terms and their roundings are a tenth as large too). 1 when one was
 * found, 0 when none, -1 on error. */
/* Whether h = c / 2q is exact, a point in both precisions and not a float subnormal (the kernels flush those). */
static int exact_half_ratio(double c, double q, double *h) {
    *h = c / (2 * q);
    return c != 0 && isfinite(*h) && fma(*h, 2 * q, -c) == 0 && (double)(float)*h == *h && fabs(*h) >= FLT_MIN;
}

static int complete_one(dag *d, term *t, int n, iacsg_error *err) {
    for (int i = 0; i < n; i++) {
        int u;
        double q = square_in(d, t[i], &u);
        for (int j = 0; j < n && q != 0; j++) {
            double h, c = j == i ? 0 : linear_in(d, t[j], u);
            if (!exact_half_ratio(c, q, &h))
                continue;
            int k = dag_add_real(d, h, err), p = k < 0 ? -1 : dag_add_real(d, q, err), m = -1;
            int shifted = p < 0 ? -1 : make(d, OP_ADD, u, k, 0, err);
            int square = shifted < 0 ? -1 : make(d, OP_SQR, shifted, -1, 0, err);
            int scaled = square < 0 ? -1 : make(d, OP_MUL, square, p, 0, err);
            int h2 = scaled < 0 ? -1 : make(d, OP_SQR, k, -1, 0, err);
            int constant = h2 < 0 || (m = dag_add_real(d, -q, err)) < 0 ? -1 : make(d, OP_MUL, h2, m, 0, err);
            if (constant < 0)
                return -1;
            t[i] = (term){scaled, 1};
            t[j] = (term){constant, 1};
            return 1;
        }
    }
    return 0;
}

/* The sum a + b (op OP_ADD) or a - b (OP_SUB) with squares completed (complete_one) where its terms hold such
 * pairs, rebuilt in the terms' order with its constants folded into one at the end (also where it holds two
 * constants and no pair); -2 where it holds neither (the caller then makes the node as it is). */
static int complete_squares(dag *d, int op, int a, int b, iacsg_error *err) {
    term t[SUM_TERMS_MAX];
    if (d->nodes[a].op == OP_CONST && d->nodes[b].op == OP_CONST) /* folded by make */
        return -2;
    int n = sum_terms(d, b, op == OP_SUB ? -1 : 1, t, sum_terms(d, a, 1, t, 0, 0), 0), found = 0, r = 0, nconst = 0;
    while (n > 0 && (r = complete_one(d, t, n, err)) == 1)
        found = 1;
    for (int k = 0; k < n; k++)
        nconst += d->nodes[t[k].node].op == OP_CONST;
    if (r < 0)
        return -1;
    if (n <= 0 || (!found && nconst < 2))
        return -2;
    int sum = -1, constants = -1;
    for (int pass = 0; pass < 2; pass++) /* the variable terms, then the constants */
        for (int k = 0; k < n; k++) {
            if ((d->nodes[t[k].node].op == OP_CONST) != pass)
                continue;
            int *acc = pass ? &constants : &sum;
            *acc = *acc >= 0   ? make(d, t[k].sign > 0 ? OP_ADD : OP_SUB, *acc, t[k].node, 0, err)
                   : t[k].sign > 0 ? t[k].node
                                   : make(d, OP_NEG, t[k].node, -1, 0, err);
            if (*acc < 0)
                return -1;
        }
    return sum < 0 ? constants : constants < 0 ? sum : make(d, OP_ADD, sum, constants, 0, err);
}

/* A product rewritten towards tighter enclosures: a point factor pulled out, (k a) b = k (a b), so that equal powers
 * meet, a^n b^n = (a b)^n (n >= 2: the same range, one rounding less), and u (k u + c) = k u^2 + c u, whose square
 * complete_squares then completes (only where it will). Hauser's citrus, x^2 + z^2 - 4 y^3 (1 - y)^3, becomes
 * x^2 + z^2 - 4 (0.25 - (y - 0.5)^2)^3, whose enclosures prove it within 0.3 of y's axis in z where they proved
 * 53.8 (and the command's default view, framed on that box, showed nothing). -2 where no rule applies. */
static int product_rules(dag *d, int a, int b, iacsg_error *err) {
    for (int swap = 0; swap < 2; swap++) {
        int p = swap ? b : a, other = swap ? a : b;
        dag_node P = d->nodes[p]; /* a copy: make() may move the nodes */
        if (P.op == OP_MUL_R && d->nodes[other].op != OP_CONST) {
            int m = make(d, OP_MUL, P.a, other, 0, err);
            return m < 0 ? -1 : make(d, OP_MUL_R, m, P.b, 0, err);
        }
    }
    dag_node A = d->nodes[a], B = d->nodes[b];
    if (A.op == B.op && (A.op == OP_SQR || (A.op == OP_POWN && A.n == B.n && A.n >= 2))) {
        int m = make(d, OP_MUL, A.a, B.a, 0, err);
        return m < 0 ? -1 : make(d, A.op, m, -1, A.n, err);
    }
    for (int swap = 0; swap < 2; swap++) {
        int u = swap ? b : a, v = swap ? a : b;
        term t[SUM_TERMS_MAX];
        if (d->nodes[u].op == OP_CONST || sum_terms(d, v, 1, t, 0, SUM_TERMS_MAX - 2) != 2)
            continue;
        for (int i = 0; i < 2; i++) {
            double k = linear_in(d, t[i], u), c = t[1 - i].sign * point_value(d, t[1 - i].node), h;
            if (k == 0 || !dag_is_point(d, t[1 - i].node) || !exact_half_ratio(c, k, &h))
                continue;
            int kc = dag_add_real(d, k, err), cc = kc < 0 ? -1 : dag_add_real(d, c, err);
            int sq = cc < 0 ? -1 : make(d, OP_SQR, u, -1, 0, err);
            int quadratic = sq < 0 ? -1 : make(d, OP_MUL, sq, kc, 0, err);
            int linear = quadratic < 0 ? -1 : make(d, OP_MUL, u, cc, 0, err);
            return linear < 0 ? -1 : make(d, OP_ADD, quadratic, linear, 0, err);
        }
    }
    return -2;
}

/* The node op(a, b, n), rewritten by the rules of simplify.h. The rules shrink the expression, but for one: an
 * even power a^2k becomes (a^k)^2, the same enclosure with as many roundings, so that x^4 shares the x^2 that
 * x^4 - 5x^2 computes anyway (the tangle: 3 of its 16 interval operations). The recursion is a few levels deep
 * (16 for the largest exponent; complete_squares adds a few: the sums it builds hold no pair). */
static int make(dag *d, int op, int a, int b, int n, iacsg_error *err) {
    if ((op == OP_ADD || op == OP_MUL || op == OP_MIN || op == OP_MAX) && b < a) {
        int swap = a; /* commutative: one order, so that x*y and y*x are one node (ia/ is symmetric here) */
        a = b;
        b = swap;
    }
    const dag_node *A = a >= 0 ? &d->nodes[a] : NULL;
    int a_op = A ? A->op : -1, r;
    switch (op) {
    case OP_NEG:
        if (a_op == OP_NEG)
            return A->a;
        break;
    case OP_ADD:
        if ((r = complete_squares(d, op, a, b, err)) != -2)
            return r;
        if (a == b) { /* x + x = 2x, one exact scaling */
            int two = dag_add_real(d, 2, err);
            return two < 0 ? -1 : make(d, OP_MUL_R, a, two, 0, err);
        }
        if (point_is(d, a, 0))
            return b;
        if (point_is(d, b, 0))
            return a;
        if (dag_is_point(d, b) && d->nodes[a].op != OP_CONST)
            return make(d, OP_ADD_R, a, b, 0, err);
        if (dag_is_point(d, a) && d->nodes[b].op != OP_CONST)
            return make(d, OP_ADD_R, b, a, 0, err);
        break;
    case OP_SUB:
        if ((r = complete_squares(d, op, a, b, err)) != -2)
            return r;
        if (point_is(d, b, 0))
            return a;
        if (point_is(d, a, 0))
            return make(d, OP_NEG, b, -1, 0, err);
        if (dag_is_point(d, b) && d->nodes[a].op != OP_CONST) {
            int c = dag_add_real(d, -point_value(d, b), err);
            return c < 0 ? -1 : make(d, OP_ADD_R, a, c, 0, err);
        }
        break;
    case OP_MUL:
        if (a == b)
            return make(d, OP_SQR, a, -1, 0, err);
        if ((r = product_rules(d, a, b, err)) != -2)
            return r;
        if (dag_is_point(d, a) && !dag_is_point(d, b)) { /* the point on the right: b * a */
            int swap = a;
            a = b;
            b = swap;
        }
        if (point_is(d, b, 1))
            return a;
        if (point_is(d, b, -1))
            return make(d, OP_NEG, a, -1, 0, err);
        if (dag_is_point(d, b) && d->nodes[a].op != OP_CONST)
            return make(d, OP_MUL_R, a, b, 0, err);
        break;
    case OP_DIV:
        if (point_is(d, a, 1) && d->nodes[b].op != OP_CONST)
            return make(d, OP_RECIP, b, -1, 0, err);
        if (dag_is_point(d, b) && d->nodes[a].op != OP_CONST) {
            int e;
            double v = point_value(d, b);
            if (v != 0 && frexp(v, &e) == 0.5) { /* a power of two: the reciprocal is exact */
                int c = dag_add_real(d, 1 / v, err);
                if (c < 0)
                    return -1;
                if (dag_is_point(d, c))
                    return make(d, OP_MUL_R, a, c, 0, err);
            }
        }
        break;
    case OP_POW:
        if (dag_is_point(d, b)) {
            double v = point_value(d, b);
            if (v == floor(v) && fabs(v) <= POWN_MAX)
                return make(d, OP_POWN, a, -1, (int)v, err);
            if (v == 0.5) /* the same domain (a >= 0), and sqrt is correctly rounded */
                return make(d, OP_SQRT, a, -1, 0, err);
        }
        break;
    case OP_POWN:
        if (n == 1)
            return a;
        if (n == 2)
            return make(d, OP_SQR, a, -1, 0, err);
        if (n % 2 == 0 && (a_op == OP_NEG || a_op == OP_ABS))
            return make(d, OP_POWN, A->a, -1, n, err);
        if (n % 2 == 0 && n > 2 && n <= SPLIT_POWN_MAX && a_op != OP_CONST) { /* a^2k = (a^k)^2, see above */
            int half = make(d, OP_POWN, a, -1, n / 2, err);
            return half < 0 ? -1 : make(d, OP_SQR, half, -1, 0, err);
        }
        break;
    case OP_SQR:
        if (a_op == OP_NEG || a_op == OP_ABS)
            return make(d, OP_SQR, A->a, -1, 0, err);
        break;
    case OP_ABS:
        if (a_op == OP_NEG)
            return make(d, OP_ABS, A->a, -1, 0, err);
        if (a_op == OP_ABS || a_op == OP_SQR)
            return a;
        break;
    case OP_MIN:
    case OP_MAX:
        if (a == b)
            return a;
        break;
    }
    if (op >= OP_NEG && A && A->op == OP_CONST && (b < 0 || d->nodes[b].op == OP_CONST))
        return fold(d, op, a, b, n, err);
    return dag_add(d, op, a, b, n, err);
}

int simplify(const dag *src, int root, dag *dst, iacsg_error *err) {
    int *order;
    int count = dag_reachable(src, root, &order);
    int *image = count < 0 ? NULL : malloc(((size_t)root + 1) * sizeof *image);
    if (!image) {
        if (count >= 0)
            free(order);
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory simplifying the expression"), -1;
    }
    int r = 0;
    for (int k = 0; k < count && r >= 0; k++) {
        const dag_node n = src->nodes[order[k]];
        switch (n.op) {
        case OP_CONST:
            r = dag_add_const(dst, n.lo, n.hi, n.near, n.flo, n.fhi, n.fnear, NULL, err);
            break;
        case OP_PI:
            r = constant_between(dst, "3.14159265358979323846264338327950288419",
                                 "3.14159265358979323846264338327950288420", err);
            break;
        case OP_E:
            r = constant_between(dst, "2.71828182845904523536028747135266249775",
                                 "2.71828182845904523536028747135266249776", err);
            break;
        case OP_X: case OP_Y: case OP_Z: case OP_T: case OP_PARAM:
            r = dag_add(dst, n.op, -1, -1, n.n, err);
            break;
        default:
            r = make(dst, n.op, image[n.a], n.b >= 0 ? image[n.b] : -1, n.n, err);
        }
        image[order[k]] = r;
    }
    r = r < 0 ? -1 : image[root];
    free(order);
    free(image);
    return r;
}
