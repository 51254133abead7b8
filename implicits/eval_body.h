/* implicits/eval_body.h -- the host evaluator, included once per precision (eval_f32.c, eval_f64.c) after
 * EVAL_SUFFIX and, for double, IA_FP64 are defined. The interval column of ops.def is expanded here as C. */
#include "eval.h"
#include "ia/ia.h"

#define EVAL_CAT2(a, b) a##b
#define EVAL_CAT(a, b) EVAL_CAT2(a, b)
#define EVAL_NAME(name) EVAL_CAT(name, EVAL_SUFFIX)

/* A double lower bound rounded down to ia_real (exact for double). */
static ia_real down(double v) {
    ia_real r = (ia_real)v;
    return (double)r > v ? nextafter(r, -IA_INF) : r;
}
static ia_real up(double v) {
    ia_real r = (ia_real)v;
    return (double)r < v ? nextafter(r, IA_INF) : r;
}

static ia_interval apply(int op, ia_interval A, ia_interval B, int N, ia_real KB) {
    (void)B, (void)N, (void)KB;
    switch (op) {
#define OP(id, name, arity, nary, iv, pt, d, td, oracle)                                                          \
    case OP_##id: return iv;
#include "ops.def"
#undef OP
    }
    return ia_entire(); /* pi, e and parameters: simplify.c has replaced them before any evaluation */
}

void EVAL_NAME(eval_op_)(int op, const double a[2], const double b[2], int n, double k, double r[2]) {
    ia_interval res = apply(op, ia_make(down(a[0]), up(a[1])), ia_make(down(b[0]), up(b[1])), n, (ia_real)k);
    r[0] = res.lo;
    r[1] = res.hi;
}

static ia_interval constant(const dag_node *c) {
#ifdef IA_FP64
    return ia_make(c->lo, c->hi);
#else
    return ia_make(c->flo, c->fhi);
#endif
}

void EVAL_NAME(eval_dag_)(const dag *d, const int *order, int count, const double vars[8], void *scratch,
                          double out[2]) {
    ia_interval *v = scratch;
    for (int k = 0; k < count; k++) {
        int i = order[k];
        const dag_node *n = &d->nodes[i];
        switch (n->op) {
        case OP_X: case OP_Y: case OP_Z: case OP_T:
            v[i] = ia_make(down(vars[2 * n->op]), up(vars[2 * n->op + 1]));
            break;
        case OP_CONST: v[i] = constant(n); break;
        default: {
            ia_interval b = n->b >= 0 ? v[n->b] : ia_entire();
            ia_real kb = n->b >= 0 ? (ia_real)d->nodes[n->b].near : 0;
            v[i] = apply(n->op, v[n->a], b, n->n, kb);
        }
        }
    }
    ia_interval r = count > 0 ? v[order[count - 1]] : ia_empty();
    out[0] = r.lo;
    out[1] = r.hi;
}
