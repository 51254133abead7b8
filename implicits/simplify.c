/* implicits/simplify.c -- stage 4 (see simplify.h). Its dump is dag_dump of the result. */
#include "simplify.h"
#include "eval.h"
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

/* The node op(a, b, n), rewritten by the rules of simplify.h. The rules shrink the expression, but for one: an
 * even power a^2k becomes (a^k)^2, the same enclosure with as many roundings, so that x^4 shares the x^2 that
 * x^4 - 5x^2 computes anyway (the tangle: 3 of its 16 interval operations). The recursion is a few levels deep
 * (16 for the largest exponent). */
static int make(dag *d, int op, int a, int b, int n, iacsg_error *err) {
    if ((op == OP_ADD || op == OP_MUL || op == OP_MIN || op == OP_MAX) && b < a) {
        int swap = a; /* commutative: one order, so that x*y and y*x are one node (ia/ is symmetric here) */
        a = b;
        b = swap;
    }
    const dag_node *A = a >= 0 ? &d->nodes[a] : NULL;
    int a_op = A ? A->op : -1;
    switch (op) {
    case OP_NEG:
        if (a_op == OP_NEG)
            return A->a;
        break;
    case OP_ADD:
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
