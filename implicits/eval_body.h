/* implicits/eval_body.h -- the host evaluator, included once per precision (eval_f32.c, eval_f64.c) after
 * EVAL_SUFFIX and, for double, IA_FP64 are defined. The interval and undefined columns of ops.def are expanded
 * here as C, and undefined operands follow the rule of ia/ia.h as the emitted code does (implicits/emit.c): each
 * node carries the flag "may be undefined somewhere on the box", and a union takes a flagged operand through
 * ia_or_outside. */
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
#define OP(id, name, arity, nary, iv, pt, d, td, oracle, undef, empty)                                               \
    case OP_##id: return iv;
#include "ops.def"
#undef OP
    }
    return ia_entire(); /* pi, e and parameters: simplify.c has replaced them before any evaluation */
}

/* Whether op may be undefined somewhere on the box, from its operands' enclosures and its result R. */
static int undefined_here(int op, ia_interval A, ia_interval B, int N, ia_interval R) {
    (void)A, (void)B, (void)N, (void)R;
    switch (op) {
#define OP(id, name, arity, nary, iv, pt, d, td, oracle, undef, empty)                                               \
    case OP_##id: return undef;
#include "ops.def"
#undef OP
    }
    return 0;
}

void EVAL_NAME(eval_op_)(int op, const double a[2], const double b[2], int n, double k, double r[2]) {
    ia_interval A = ia_make(down(a[0]), up(a[1])), B = ia_make(down(b[0]), up(b[1]));
    /* constants: undefined only where empty */
    ia_interval res = op == OP_MIN ? ia_union(A, ia_is_empty(A), B, ia_is_empty(B)) : apply(op, A, B, n, (ia_real)k);
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
    unsigned char *u = (unsigned char *)(v + (count > 0 ? order[count - 1] + 1 : 0)); /* the flags, after */
    for (int k = 0; k < count; k++) {
        int i = order[k];
        const dag_node *n = &d->nodes[i];
        switch (n->op) {
        case OP_X: case OP_Y: case OP_Z: case OP_T:
            v[i] = ia_make(down(vars[2 * n->op]), up(vars[2 * n->op + 1]));
            u[i] = 0;
            break;
        case OP_CONST:
            v[i] = constant(n);
            u[i] = ia_is_empty(v[i]);
            break;
        default: {
            ia_interval a = v[n->a], b = n->b >= 0 ? v[n->b] : ia_entire();
            int ua = u[n->a], ub = n->b >= 0 && u[n->b];
            ia_real kb = n->b >= 0 ? (ia_real)d->nodes[n->b].near : 0;
            v[i] = n->op == OP_MIN ? ia_union(a, ua, b, ub) : apply(n->op, a, b, n->n, kb);
            u[i] = n->op == OP_MIN ? ua && ub : ua || ub || undefined_here(n->op, a, b, n->n, v[i]);
        }
        }
    }
    ia_interval r = count > 0 ? ia_or_outside(v[order[count - 1]], u[order[count - 1]]) : ia_empty();
    out[0] = r.lo;
    out[1] = r.hi;
}
