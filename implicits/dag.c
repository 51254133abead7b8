/* implicits/dag.c -- the hash-consed expression DAG (see dag.h). */
#include "dag.h"
#include "ia/decimal.h"
#include "ia/flush.h"
#include "strbuf.h"
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define STR(x) #x
#define LEAF {"", 0, 0, "", "", "", "", "", ""}
const dag_op_info dag_ops[OP_COUNT] = {
    [OP_X] = LEAF, [OP_Y] = LEAF, [OP_Z] = LEAF, [OP_T] = LEAF, [OP_CONST] = LEAF, [OP_PI] = LEAF, [OP_E] = LEAF,
    [OP_PARAM] = LEAF,
#define OP(id, name, arity, nary, iv, pt, d, td, oracle, undef, empty)                                               \
    [OP_##id] = {name, arity, nary, STR(iv), STR(pt), STR(d), STR(td), STR(undef), STR(empty)},
#include "ops.def"
#undef OP
};
#undef LEAF

const char *dag_op_id(dag_op op) {
    static const char *const ids[OP_COUNT] = {
        "X", "Y", "Z", "T", "CONST", "PI", "E", "PARAM",
#define OP(id, name, arity, nary, iv, pt, d, td, oracle, undef, empty) #id,
#include "ops.def"
#undef OP
    };
    return (unsigned)op < OP_COUNT ? ids[op] : "?";
}

void dag_init(dag *d) { memset(d, 0, sizeof *d); }

void dag_free(dag *d) {
    for (int i = 0; i < d->ntexts; i++)
        free(d->texts[i]);
    free(d->texts);
    free(d->nodes);
    free(d->slots);
    dag_init(d);
}

/* Bit patterns, so that -0 and 0 (and the float/double halves) are told apart exactly. */
static uint64_t bits_d(double v) {
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    return u;
}
static uint64_t bits_f(float v) {
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    return u;
}

static uint64_t mix(uint64_t h, uint64_t v) {
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 0xff51afd7ed558ccdull;
}

static uint64_t node_hash(const dag_node *n) {
    /* a constant is its value: its text only serves the oracle, so equal values share whatever text came first */
    uint64_t h = mix(mix(mix(mix(0, (uint64_t)n->op), (uint64_t)(uint32_t)n->a), (uint64_t)(uint32_t)n->b),
                     n->op == OP_CONST ? 0 : (uint64_t)(uint32_t)n->n);
    if (n->op == OP_CONST)
        h = mix(mix(mix(h, bits_d(n->lo)), bits_d(n->hi)), (bits_f(n->flo) << 32) | bits_f(n->fhi));
    return h ^ (h >> 29);
}

static int node_equal(const dag_node *p, const dag_node *q) {
    if (p->op != q->op || p->a != q->a || p->b != q->b || (p->op != OP_CONST && p->n != q->n))
        return 0;
    return p->op != OP_CONST || (bits_d(p->lo) == bits_d(q->lo) && bits_d(p->hi) == bits_d(q->hi) &&
                                 bits_d(p->near) == bits_d(q->near) && bits_f(p->flo) == bits_f(q->flo) &&
                                 bits_f(p->fhi) == bits_f(q->fhi) && bits_f(p->fnear) == bits_f(q->fnear));
}

static int grow_slots(dag *d) {
    int n = d->nslots ? d->nslots * 2 : 1024;
    int *slots = malloc((size_t)n * sizeof *slots);
    if (!slots)
        return 0;
    for (int i = 0; i < n; i++)
        slots[i] = -1;
    for (int i = 0; i < d->count; i++) {
        size_t s = (size_t)node_hash(&d->nodes[i]) & (size_t)(n - 1);
        while (slots[s] >= 0)
            s = (s + 1) & (size_t)(n - 1);
        slots[s] = i;
    }
    free(d->slots);
    d->slots = slots;
    d->nslots = n;
    return 1;
}

/* The slot holding a node equal to key, or the empty slot where it belongs; -1 with err if the table cannot grow. */
static long find_slot(dag *d, const dag_node *key, iacsg_error *err) {
    if ((d->count + 1) * 2 > d->nslots && !grow_slots(d))
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the expression graph"), -1;
    size_t mask = (size_t)(d->nslots - 1), s = (size_t)node_hash(key) & mask;
    while (d->slots[s] >= 0 && !node_equal(&d->nodes[d->slots[s]], key))
        s = (s + 1) & mask;
    return (long)s;
}

static int insert(dag *d, long slot, const dag_node *key, iacsg_error *err) {
    if (d->count >= DAG_MAX_NODES)
        return iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0, "expression too large: more than %d distinct nodes",
                               DAG_MAX_NODES),
               -1;
    if (d->count == d->cap) {
        int cap = d->cap ? d->cap * 2 : 256;
        dag_node *nodes = realloc(d->nodes, (size_t)cap * sizeof *nodes);
        if (!nodes)
            return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the expression graph"), -1;
        d->nodes = nodes;
        d->cap = cap;
    }
    d->nodes[d->count] = *key;
    d->slots[slot] = d->count;
    return d->count++;
}

static int intern(dag *d, const dag_node *key, iacsg_error *err) {
    long s = find_slot(d, key, err);
    if (s < 0)
        return -1;
    return d->slots[s] >= 0 ? d->slots[s] : insert(d, s, key, err);
}

int dag_add(dag *d, int op, int a, int b, int n, iacsg_error *err) {
    dag_node key = {op, a, b, n, 0, 0, 0, 0, 0, 0};
    return intern(d, &key, err);
}

static int intern_text(dag *d, const char *text, iacsg_error *err) {
    if (d->ntexts == d->captexts) {
        int cap = d->captexts ? d->captexts * 2 : 16;
        char **texts = realloc(d->texts, (size_t)cap * sizeof *texts);
        if (!texts)
            return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory"), -1;
        d->texts = texts;
        d->captexts = cap;
    }
    char *copy = malloc(strlen(text) + 1);
    if (!copy)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory"), -1;
    strcpy(copy, text);
    d->texts[d->ntexts] = copy;
    return d->ntexts++;
}

int dag_add_const(dag *d, double lo, double hi, double near, float flo, float fhi, float fnear, const char *text,
                  iacsg_error *err) {
    lo = ia_flush_lo_d(lo), hi = ia_flush_hi_d(hi), flo = ia_flush_lo_f(flo), fhi = ia_flush_hi_f(fhi);
    dag_node key = {OP_CONST, -1, -1, -1, lo, hi, near, flo, fhi, fnear};
    long s = find_slot(d, &key, err);
    if (s < 0)
        return -1;
    if (d->slots[s] >= 0)
        return d->slots[s];
    if (text && (key.n = intern_text(d, text, err)) < 0)
        return -1;
    return insert(d, s, &key, err);
}

int dag_add_decimal(dag *d, const char *text, iacsg_error *err) {
    double lo, hi;
    float flo, fhi;
    if (ia_decimal_double(text, &lo, &hi) != 0 || ia_decimal_float(text, &flo, &fhi) != 0)
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, 0, 0, "'%s' is not a number", text), -1;
    return dag_add_const(d, lo, hi, strtod(text, NULL), flo, fhi, strtof(text, NULL), text, err);
}

int dag_add_real(dag *d, double v, iacsg_error *err) {
    float f = (float)v, flo = f, fhi = f;
    if ((double)f > v)
        flo = nextafterf(f, -INFINITY);
    else if ((double)f < v)
        fhi = nextafterf(f, INFINITY);
    return dag_add_const(d, v, v, v, flo, fhi, f, NULL, err);
}

int dag_is_point(const dag *d, int i) {
    const dag_node *n = &d->nodes[i];
    return n->op == OP_CONST && n->lo == n->hi && n->flo == n->fhi && (double)n->flo == n->lo && isfinite(n->lo);
}

int dag_reachable(const dag *d, int root, int **out) {
    unsigned char *seen = calloc((size_t)root + 1, 1);
    int *stack = malloc(((size_t)root + 1) * sizeof *stack);
    int count = 0, top = 0;
    if (!seen || !stack) {
        free(seen);
        free(stack);
        return -1;
    }
    stack[top++] = root;
    seen[root] = 1;
    while (top > 0) {
        const dag_node *n = &d->nodes[stack[--top]];
        count++;
        if (n->a >= 0 && !seen[n->a])
            seen[n->a] = 1, stack[top++] = n->a;
        if (n->b >= 0 && !seen[n->b])
            seen[n->b] = 1, stack[top++] = n->b;
    }
    int k = 0;
    for (int i = 0; i <= root; i++) /* the seen flags, read in index order, are the sorted list */
        if (seen[i])
            stack[k++] = i;
    free(seen);
    *out = stack;
    return count;
}

int dag_substitute(const dag *src, int root, dag *dst, const int map_var[4], const int *params, int nparams,
                   iacsg_error *err) {
    int *order;
    int count = dag_reachable(src, root, &order);
    if (count < 0)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory"), -1;
    int *image = malloc((size_t)(root + 1) * sizeof *image);
    if (!image) {
        free(order);
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory"), -1;
    }
    int result = -1;
    for (int k = 0; k < count; k++) {
        int i = order[k];
        dag_node n = src->nodes[i]; /* a copy: adding to dst may move src->nodes when dst == src */
        int r;
        if (n.op <= OP_T && map_var[n.op] >= 0)
            r = map_var[n.op];
        else if (n.op == OP_PARAM && n.n < nparams)
            r = params[n.n];
        else if (n.op == OP_CONST)
            r = dag_add_const(dst, n.lo, n.hi, n.near, n.flo, n.fhi, n.fnear, n.n >= 0 ? src->texts[n.n] : NULL,
                              err);
        else
            r = dag_add(dst, n.op, n.a >= 0 ? image[n.a] : -1, n.b >= 0 ? image[n.b] : -1, n.n, err);
        if (r < 0)
            goto done;
        image[i] = r;
    }
    result = image[root];
done:
    free(order);
    free(image);
    return result;
}

char *dag_dump(const dag *d, int root) {
    int *order;
    int count = dag_reachable(d, root, &order);
    if (count < 0)
        return NULL;
    strbuf b = {0};
    for (int k = 0; k < count; k++) {
        const dag_node *n = &d->nodes[order[k]];
        strbuf_printf(&b, "v%d = %s", order[k], dag_op_id(n->op));
        if (n->op == OP_CONST)
            strbuf_printf(&b, " [%a, %a] f[%a, %a]%s%s", n->lo, n->hi, (double)n->flo, (double)n->fhi,
                          n->n >= 0 ? " " : "", n->n >= 0 ? d->texts[n->n] : "");
        if (n->a >= 0)
            strbuf_printf(&b, " v%d", n->a);
        if (n->b >= 0)
            strbuf_printf(&b, " v%d", n->b);
        if (n->op == OP_POWN || n->op == OP_PARAM)
            strbuf_printf(&b, " %d", n->n);
        strbuf_printf(&b, "\n");
    }
    free(order);
    return strbuf_finish(&b);
}
