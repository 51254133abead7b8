/* implicits/emit_signs.c -- signs of the enclosures over lanes, for cheaper products and sums (emit_signs.h).
 *
 * Stages: per node, in evaluation order, whether its computed lower bound is >= 0 (squares, abs, sqrt, exp, even
 * powers, constants >= 0, and sums, products, min and max of such, which the forms below keep >= 0) -> per node,
 * the form its code over lanes takes: a product of operands >= 0 is two products, not four and a min and max of
 * them (the decocube's three factors; the heart's 0.1 x^2), a product with one such operand two chosen by the
 * other's signs, a sum of such widens its upper bound without |r| (ia/vec.h: iav_add_nn ...).
 * Measured (libfive's view): kernel samples over 6 runs at 1024x1024, decocube 6087/6178 -> 5022/5461, heart
 * 5186/5308 -> 4840/4279; an experiment build of these forms at 2048x2048, heart 84 -> 72 ms, decocube 87 -> 80.
 */
#include "emit_signs.h"

/* A constant >= 0 in both precisions, bounds and nearest value. */
static int constant_nonneg(const dag_node *c) {
    return c->op == OP_CONST && c->lo <= c->hi && c->lo >= 0 && c->flo >= 0 && c->near >= 0 && c->fnear >= 0;
}

static int is_nonneg(const unsigned char *nonneg, int i) { return i >= 0 && nonneg[i]; }

void emit_signs_mark(const dag *d, const int *order, int count, unsigned char *nonneg) {
    for (int k = 0; k < count; k++) {
        const dag_node *n = &d->nodes[order[k]];
        int a = is_nonneg(nonneg, n->a), b = is_nonneg(nonneg, n->b), v;
        switch (n->op) {
        case OP_CONST:
            v = constant_nonneg(n);
            break;
        case OP_SQR: /* each clamps its lower bound at 0 (ia/vec.h, ia/elem.h) */
        case OP_ABS:
        case OP_SQRT:
        case OP_EXP:
            v = 1;
            break;
        case OP_POWN: /* an even power's or a power of a >= 0 rounds its lower bound down to 0 at most */
            v = n->n >= 0 && (n->n % 2 == 0 || a);
            break;
        case OP_MIN:
            v = a && b;
            break;
        case OP_MAX:
            v = a || b;
            break;
        case OP_ADD: /* >= 0 where emit_signs_value takes a clamped form */
        case OP_ADD_R:
        case OP_MUL:
        case OP_MUL_R:
            (void)emit_signs_value(d, nonneg, n, &v);
            break;
        default:
            v = 0;
        }
        nonneg[order[k]] = (unsigned char)v;
    }
}

const char *emit_signs_value(const dag *d, const unsigned char *nonneg, const dag_node *n, int *clamped) {
    int a = is_nonneg(nonneg, n->a), b = is_nonneg(nonneg, n->b);
    const dag_node *B = n->b >= 0 ? &d->nodes[n->b] : NULL;
    const char *form = NULL;
    switch (n->op) {
    case OP_ADD:
        form = a && b ? emit_signs_clamped(n->op) : NULL;
        break;
    case OP_ADD_R:
        form = a && constant_nonneg(B) ? emit_signs_clamped(n->op) : NULL;
        break;
    case OP_MUL_R: /* KB > 0: a product by 0 is iav_mul_r's [0, 0] */
        form = a && constant_nonneg(B) && B->near > 0 && B->fnear > 0 ? emit_signs_clamped(n->op) : NULL;
        break;
    case OP_MUL:
        form = a && b ? emit_signs_clamped(n->op) : a ? "ia_mul_n(A, B)" : b ? "ia_mul_n(B, A)" : NULL;
        break;
    case OP_SQR:
        form = a ? "ia_sqr_nn(A)" : NULL;
        break;
    default:
        break;
    }
    *clamped = form && form == emit_signs_clamped(n->op);
    return form;
}

const char *emit_signs_clamped(int op) {
    switch (op) {
    case OP_ADD:
        return "ia_add_nn(A, B)";
    case OP_ADD_R:
        return "ia_add_r_nn(A, KB)";
    case OP_MUL:
        return "ia_mul_nn(A, B)";
    case OP_MUL_R:
        return "ia_mul_r_nn(A, KB)";
    default:
        return NULL;
    }
}
