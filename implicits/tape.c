/* implicits/tape.c -- tape_build (see tape.h for the stages and the layout). */
#include "tape.h"
#include "emit.h"
#include "emit_signs.h"
#include "eval.h"
#include "ia/flush.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

void tape_free(iacsg_tape *t) {
    free(t->words);
    memset(t, 0, sizeof *t);
}

/* A growable array of words. */
typedef struct {
    unsigned *w;
    size_t n, cap;
    int failed;
} words;
static size_t words_put(words *a, unsigned v) {
    if (a->n == a->cap) {
        size_t cap = a->cap ? 2 * a->cap : 1024;
        unsigned *w = realloc(a->w, cap * sizeof *w);
        if (!w) {
            a->failed = 1;
            return a->n;
        }
        a->w = w;
        a->cap = cap;
    }
    a->w[a->n] = v;
    return a->n++;
}

/* Whether an ops.def template reads the identifier `word` (B: the second operand's interval, which the *_R ops
 * do not need: they read its real value KB). */
static int template_reads(const char *tpl, const char *word) {
    size_t len = strlen(word);
    for (const char *p = tpl; (p = strstr(p, word)) != NULL; p += len) {
        int before = p > tpl && (p[-1] == '_' || p[-1] == '.' || (p[-1] >= 'A' && p[-1] <= 'Z') ||
                                 (p[-1] >= 'a' && p[-1] <= 'z') || (p[-1] >= '0' && p[-1] <= '9'));
        char c = p[len];
        int after = c == '_' || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        if (!before && !after)
            return 1;
    }
    return 0;
}
static int reads_b_interval(int op) {
    return template_reads(dag_ops[op].interval, "B") || template_reads(dag_ops[op].undefined, "B") ||
           template_reads(dag_ops[op].empty, "B");
}

/* As emit.c's op_may_be_undefined: the operation's `undefined` column applies to this node. */
static int own_undefined(const dag_node *n) {
    return n->op >= OP_NEG && strcmp(dag_ops[n->op].undefined, "0") != 0 && !(n->op == OP_POWN && n->n >= 0);
}

/* Whether the part (its nodes in order[0..count-1]) is proven > 0 or undefined over the closed half-space
 * {x_axis >= p} (side 1) or {x_axis <= p} (side 0), every other variable over all the reals. */
static int positive_beyond(const dag *d, const int *order, int count, void *scratch, int axis, int side, double p) {
    double vars[8] = {-INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY}, r[2];
    vars[2 * axis + !side] = p;
    eval_dag_f64(d, order, count, vars, scratch, r);
    return r[0] > 0; /* empty, [+inf, -inf]: undefined on all of it, outside */
}

/* The box of a part: on each side of each axis, the innermost of the planes tried (a bisection in the
 * compactified coordinate c = x / (1 + |x|)) beyond which the part is proven > 0 or undefined; +-inf where none
 * is. Only planes that were tested are kept, so the box is proven whatever the bisection meets. */
#define TAPE_BOX_STEPS 24
static void tape_part_box(const dag *d, const int *order, int count, void *scratch, double box[6]) {
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            double sign = side ? 1 : -1, outer = 1, inner = -1; /* in c, towards this side */
            double best = sign * INFINITY;
            for (int step = 0; step < TAPE_BOX_STEPS; step++) {
                double c = step == 0 ? 0.999999 : 0.5 * (inner + outer), x = sign * c / (1 - fabs(c));
                if (positive_beyond(d, order, count, scratch, axis, side, x)) {
                    best = x;
                    outer = c;
                } else if (step == 0) {
                    break; /* not even beyond 10^6: leave the side open */
                } else {
                    inner = c;
                }
            }
            box[axis + 3 * side] = best;
        }
}

/* A real of the working precision, rounded down (dir < 0), up (dir > 0) or to nearest (dir 0); a bound (dir != 0)
 * as the flushing device must be given it (ia/flush.h). */
static void put_real(words *a, int fp64, double v, int dir) {
    if (fp64) {
        v = dir < 0 ? ia_flush_lo_d(v) : dir > 0 ? ia_flush_hi_d(v) : v;
        unsigned w[2];
        memcpy(w, &v, sizeof v);
        words_put(a, w[0]);
        words_put(a, w[1]);
        return;
    }
    float f = (float)v;
    if (dir < 0 && (double)f > v)
        f = nextafterf(f, -INFINITY);
    if (dir > 0 && (double)f < v)
        f = nextafterf(f, INFINITY);
    f = dir < 0 ? ia_flush_lo_f(f) : dir > 0 ? ia_flush_hi_f(f) : f;
    unsigned w;
    memcpy(&w, &f, sizeof f);
    words_put(a, w);
}

typedef struct {
    const dag *d;
    int fp64;
    words code, reals;
    int nreals;
    int *slot, *last_use, *used_as_interval, *uses; /* per node */
    unsigned char *squared;   /* per node: its instruction also squares it (TAPE_THEN_SQR) */
    unsigned char *undefined; /* per node, as emit.c's */
    unsigned char *nonneg;    /* per node, as emit.c's (emit_signs.h) */
    int max_slots;
    int flagged; /* the part last lowered has an instruction that may be undefined */
} builder;

/* The real index of a constant's reals (lo, hi, near), appended. */
static int const_reals(builder *b, const dag_node *n) {
    int index = b->nreals;
    if (b->fp64) {
        put_real(&b->reals, 1, n->lo, -1);
        put_real(&b->reals, 1, n->hi, 1);
        put_real(&b->reals, 1, n->near, 0);
    } else {
        put_real(&b->reals, 0, n->flo, -1);
        put_real(&b->reals, 0, n->fhi, 1);
        put_real(&b->reals, 0, n->fnear, 0);
    }
    b->nreals += 3;
    return index;
}

/* The reals (lo, hi, near) of the reciprocals of a positive constant (emit_reciprocal_enclosure), appended. */
static int reciprocal_reals(builder *b, const double d[2], const float f[2]) {
    int index = b->nreals;
    for (int k = 0; k < 3; k++)
        put_real(&b->reals, b->fp64, b->fp64 ? d[k % 2] : f[k % 2], k == 0 ? -1 : k == 1 ? 1 : 0);
    b->nreals += 3;
    return index;
}

/* One part's instructions, its nodes in index order. Returns the number of instructions, or -1 when it needs
 * more than TAPE_SLOTS slots. */
/* Which operand of node n is a (nonempty) constant that its instruction reads from the reals itself
 * (TAPE_A_REAL or TAPE_B_REAL), sparing a load instruction; 0 for none. One at most: the instruction has one
 * real index, which the *_R operations use for KB. */
static unsigned inline_constant(const dag *d, const dag_node *n) {
    if (n->op < OP_NEG)
        return 0;
    int b_interval = n->b >= 0 && reads_b_interval(n->op);
    const dag_node *a = &d->nodes[n->a], *b = n->b >= 0 ? &d->nodes[n->b] : NULL;
    if (b_interval && b->op == OP_CONST && b->lo <= b->hi)
        return TAPE_B_REAL;
    if (a->op == OP_CONST && a->lo <= a->hi && (!b || b_interval))
        return TAPE_A_REAL;
    return 0;
}

static int lower_part(builder *b, const int *order, int count, int *result_slot) {
    const dag *d = b->d;
    for (int k = 0; k < count; k++) { /* the last instruction that reads each node */
        const dag_node *n = &d->nodes[order[k]];
        b->last_use[order[k]] = k == count - 1 ? count : -1;
        b->slot[order[k]] = -1;
        if (n->op < OP_NEG)
            continue;
        b->last_use[n->a] = k;
        b->uses[n->a]++;
        if (n->b >= 0) {
            b->last_use[n->b] = k;
            b->uses[n->b]++;
        }
        unsigned inlined = inline_constant(d, n);
        if (n->b >= 0 && reads_b_interval(n->op) && inlined != TAPE_B_REAL)
            b->used_as_interval[n->b] = 1;
        if (inlined != TAPE_A_REAL)
            b->used_as_interval[n->a] = 1;
    }
    b->used_as_interval[order[count - 1]] = 1; /* the part's value: a constant part needs its instruction */
    for (int k = 0; k < count; k++) { /* sqr(a) of an operation a read by it alone: one instruction, a's */
        const dag_node *n = &d->nodes[order[k]];
        if (n->op != OP_SQR)
            continue;
        const dag_node *a = &d->nodes[n->a];
        int a_folded = a->op == OP_SQR && b->squared[a->a]; /* a has no instruction of its own to square it */
        if (a->op >= OP_NEG && !a_folded && b->uses[n->a] == 1 && !b->undefined[n->a] && !b->undefined[order[k]])
            b->squared[n->a] = 1;
    }
    _Static_assert(TAPE_SLOTS > 4 && TAPE_SLOTS <= 32, "the free slots are the bits of an unsigned");
    unsigned free_mask = (~0u >> (32 - TAPE_SLOTS)) & ~0xfu; /* slots 0-3: x, y, z, t */
    int instructions = 0, used = 4;
    b->flagged = 0;
    for (int k = 0; k < count; k++) {
        int i = order[k];
        const dag_node *n = &d->nodes[i];
        if (n->op <= OP_T) {
            b->slot[i] = n->op;
            continue;
        }
        if (n->op == OP_CONST && !b->used_as_interval[i])
            continue; /* only read as KB */
        if (n->op == OP_SQR && b->squared[n->a]) {
            b->slot[i] = b->slot[n->a]; /* computed by a's instruction, in a's slot, read by none but this */
            continue;
        }
        int operands[2] = {n->op == OP_CONST ? -1 : n->a, n->op == OP_CONST ? -1 : n->b};
        for (int m = 0; m < 2; m++) /* free the operands' slots read for the last time: dst may take one */
            if (operands[m] >= 0 && b->last_use[operands[m]] == k && b->slot[operands[m]] >= 4)
                free_mask |= 1u << b->slot[operands[m]];
        if (!free_mask)
            return -1;
        int dst = 0;
        while (!(free_mask >> dst & 1))
            dst++;
        free_mask &= ~(1u << dst);
        used = dst + 1 > used ? dst + 1 : used;
        b->slot[i] = dst;
        unsigned inlined = inline_constant(d, n);
        unsigned flags = (b->undefined[i] ? TAPE_UNDEFINED : 0) | (own_undefined(n) ? TAPE_OWN : 0) |
                         (n->op == OP_MIN && (b->undefined[n->a] || b->undefined[n->b]) ? TAPE_UNION : 0);
        b->flagged |= flags != 0;
        int clamped;
        (void)emit_signs_value(d, b->nonneg, n, &clamped); /* the compiled code's clamped forms, for its bits */
        flags |= inlined | (b->squared[i] ? TAPE_THEN_SQR : 0) | (clamped ? TAPE_NONNEG : 0);
        /* a quotient by a positive constant: a product by its reciprocals, as the compiled code (emit.c) */
        double recip[2];
        float frecip[2];
        int by_reciprocal = n->op == OP_DIV && inlined == TAPE_B_REAL &&
                            emit_reciprocal_enclosure(&d->nodes[n->b], recip, frecip);
        int real = 0;
        if (n->op == OP_CONST)
            real = const_reals(b, n);
        else if (by_reciprocal)
            real = reciprocal_reals(b, recip, frecip);
        else if (inlined)
            real = const_reals(b, &d->nodes[inlined == TAPE_A_REAL ? n->a : n->b]);
        else if (n->b >= 0 && d->nodes[n->b].op == OP_CONST && !reads_b_interval(n->op))
            real = const_reals(b, &d->nodes[n->b]) + 2; /* KB: the nearest real */
        words_put(&b->code, (unsigned)(by_reciprocal ? OP_MUL : n->op) | flags << 8 | (unsigned)dst << 16);
        /* an operand without a slot (a constant read from the reals, or as KB only) reads slot 0 and ignores it */
        int sa = n->op != OP_CONST && b->slot[n->a] >= 0 ? b->slot[n->a] : 0;
        int sb = n->op != OP_CONST && n->b >= 0 && b->slot[n->b] >= 0 ? b->slot[n->b] : 0;
        words_put(&b->code, (unsigned)sa | (unsigned)sb << 16);
        words_put(&b->code, (unsigned)n->n);
        words_put(&b->code, (unsigned)real);
        instructions++;
    }
    for (int k = 0; k < count; k++) {
        b->used_as_interval[order[k]] = b->uses[order[k]] = 0;
        b->squared[order[k]] = 0;
    }
    b->max_slots = used > b->max_slots ? used : b->max_slots;
    *result_slot = b->slot[order[count - 1]];
    return instructions;
}

/* Spreads the low 21 bits of v to every third bit. */
static unsigned long long spread3(unsigned long long v) {
    unsigned long long r = 0;
    for (int k = 0; k < 21; k++)
        r |= (v >> k & 1) << (3 * k);
    return r;
}

static const unsigned long long *sort_keys;
static int by_key(const void *a, const void *b) {
    unsigned long long ka = sort_keys[*(const int *)a], kb = sort_keys[*(const int *)b];
    return ka < kb ? -1 : ka > kb;
}

/* Reorders parts[] (and their boxes, 6 doubles each) by the Morton code of their boxes' centres over the hull
 * of the bounded ones; unbounded parts keep their order after them. keys: room for n. */
static void morton_order(double *boxes, int n, int *parts, unsigned long long *keys) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int p = 0; p < n; p++)
        for (int k = 0; k < 3; k++) {
            double c = 0.5 * (boxes[6 * p + k] + boxes[6 * p + k + 3]);
            if (isfinite(c)) {
                lo[k] = fmin(lo[k], c);
                hi[k] = fmax(hi[k], c);
            }
        }
    int *index = malloc((size_t)n * sizeof *index);
    double *moved = malloc((size_t)n * sizeof(double[6]));
    int *parts_moved = malloc((size_t)n * sizeof *parts_moved);
    if (!index || !moved || !parts_moved) { /* the order only speeds rendering up */
        free(index);
        free(moved);
        free(parts_moved);
        return;
    }
    for (int p = 0; p < n; p++) {
        unsigned long long key = 0;
        int bounded = 1;
        for (int k = 0; k < 3; k++) {
            double c = 0.5 * (boxes[6 * p + k] + boxes[6 * p + k + 3]);
            bounded &= isfinite(c);
            double u = hi[k] > lo[k] && isfinite(c) ? (c - lo[k]) / (hi[k] - lo[k]) : 0;
            key |= spread3((unsigned long long)(u * 2097151.0)) << k;
        }
        keys[p] = bounded ? key : (1ull << 63) + (unsigned long long)p;
        index[p] = p;
    }
    sort_keys = keys;
    qsort(index, (size_t)n, sizeof *index, by_key);
    for (int p = 0; p < n; p++) {
        memcpy(moved + 6 * p, boxes + 6 * index[p], sizeof(double[6]));
        parts_moved[p] = parts[index[p]];
    }
    memcpy(boxes, moved, (size_t)n * sizeof(double[6]));
    memcpy(parts, parts_moved, (size_t)n * sizeof *parts);
    free(index);
    free(moved);
    free(parts_moved);
}

iacsg_status tape_build(const dag *d, int root, int fp64, iacsg_tape *out, iacsg_error *err) {
    memset(out, 0, sizeof *out);
    int *parts = NULL, nparts = emit_union_parts(d, root, &parts);
    if (nparts == 0) { /* not a union: one part */
        parts = malloc(sizeof *parts);
        if (parts)
            parts[0] = root;
        nparts = parts ? 1 : -1;
    }
    size_t nodes = (size_t)root + 1;
    builder b = {.d = d,
                 .fp64 = fp64,
                 .slot = malloc(nodes * sizeof(int)),
                 .last_use = malloc(nodes * sizeof(int)),
                 .used_as_interval = calloc(nodes, sizeof(int)),
                 .uses = calloc(nodes, sizeof(int)),
                 .squared = calloc(nodes, 1),
                 .undefined = calloc(nodes, 1),
                 .nonneg = calloc(nodes, 1)};
    void *scratch = malloc(eval_scratch_size(root));
    unsigned *table = malloc(((size_t)(nparts > 0 ? nparts : 1)) * TAPE_PART_WORDS * sizeof *table);
    iacsg_status st = IACSG_OK;
    if (nparts < 0 || !b.slot || !b.last_use || !b.used_as_interval || !b.uses || !b.squared || !b.undefined ||
        !b.nonneg || !scratch || !table) {
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the tape");
        goto done;
    }
    int *order;
    int count = dag_reachable(d, root, &order);
    if (count < 0) {
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the tape");
        goto done;
    }
    for (int k = 0; k < count; k++) { /* which nodes may be undefined, as emit.c decides */
        const dag_node *n = &d->nodes[order[k]];
        int i = order[k];
        if (n->op < OP_NEG)
            b.undefined[i] = n->op == OP_CONST && !(n->lo <= n->hi);
        else if (n->op == OP_MIN)
            b.undefined[i] = b.undefined[n->a] && b.undefined[n->b];
        else
            b.undefined[i] = own_undefined(n) || b.undefined[n->a] || (n->b >= 0 && b.undefined[n->b]);
    }
    emit_signs_mark(d, order, count, b.nonneg);
    free(order);
    /* each part's box, and the parts in the order of their boxes' centres along a Morton curve, so that the
     * consecutive parts of a group lie close together: tight group boxes and masks (unbounded parts last) */
    double *boxes = malloc((size_t)nparts * sizeof(double[6]));
    unsigned long long *keys = malloc((size_t)nparts * sizeof *keys);
    if (!boxes || !keys) {
        free(boxes);
        free(keys);
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the tape");
        goto done;
    }
    for (int p = 0; p < nparts && st == IACSG_OK; p++) {
        int *part_order;
        int part_count = dag_reachable(d, parts[p], &part_order);
        if (part_count < 0)
            st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the tape");
        else
            tape_part_box(d, part_order, part_count, scratch, boxes + 6 * p);
        free(part_order);
    }
    morton_order(boxes, nparts, parts, keys);
    /* as many groups as the masks can name (emit.c makes about sqrt(parts)): the finer the groups, the fewer
     * parts a tile's mask leaves to test */
    int per_group = (nparts + TAPE_MAX_GROUPS - 1) / TAPE_MAX_GROUPS;
    int ngroups = (nparts + per_group - 1) / per_group;
    /* the reals: a 0 (the KB of instructions without one), each part's box, each group's (their hull) */
    put_real(&b.reals, fp64, 0, 0);
    b.nreals = 1 + 6 * (nparts + ngroups);
    for (int p = 0; p < nparts; p++) {
        int bounded = 1;
        for (int k = 0; k < 6; k++) {
            put_real(&b.reals, fp64, boxes[6 * p + k], k < 3 ? -1 : 1);
            bounded &= isfinite(boxes[6 * p + k]);
        }
        out->bounded_parts += bounded;
    }
    for (int g = 0; g < ngroups; g++) {
        double hull[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
        for (int p = g * per_group; p < nparts && p < (g + 1) * per_group; p++)
            for (int k = 0; k < 3; k++) {
                hull[k] = fmin(hull[k], boxes[6 * p + k]);
                hull[k + 3] = fmax(hull[k + 3], boxes[6 * p + k + 3]);
            }
        for (int k = 0; k < 6; k++)
            put_real(&b.reals, fp64, hull[k], k < 3 ? -1 : 1);
    }
    free(boxes);
    free(keys);
    int newton = 1; /* every part defined everywhere, and Newton pays for it (emit.c) */
    for (int p = 0; p < nparts && st == IACSG_OK; p++) {
        int *part_order;
        int part_count = dag_reachable(d, parts[p], &part_order);
        if (part_count < 0) {
            st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the tape");
            break;
        }
        if (part_count > TAPE_MAX_PART_NODES) {
            free(part_order);
            st = iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0,
                                 "a part of %d operations is too long to interpret (at most %d)", part_count,
                                 TAPE_MAX_PART_NODES);
            break;
        }
        int first = out->instructions, result = 0;
        int n = lower_part(&b, part_order, part_count, &result);
        newton &= n >= 0 && !b.flagged && emit_newton_pays(d, part_order, part_count);
        free(part_order);
        if (n < 0) {
            st = iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0,
                                 "a part of the expression needs more than %d registers for the interpreter",
                                 TAPE_SLOTS);
            break;
        }
        out->instructions += n;
        table[TAPE_PART_WORDS * p] = (unsigned)first;
        table[TAPE_PART_WORDS * p + 1] = (unsigned)n;
        table[TAPE_PART_WORDS * p + 2] =
            (unsigned)result | (unsigned)b.undefined[parts[p]] << 16 | (unsigned)b.flagged << 17;
        table[TAPE_PART_WORDS * p + 3] = (unsigned)(1 + 6 * p);
    }
    if (st != IACSG_OK)
        goto done;
    struct {
        int count, per_group;
    } g = {ngroups, per_group};
    words all = {0};
    for (int k = 0; k < TAPE_W_GROUP_TABLE; k++)
        words_put(&all, 0);
    for (int k = 0; k <= g.count; k++)
        words_put(&all, (unsigned)(k * g.per_group < nparts ? k * g.per_group : nparts));
    for (int k = 0; k < g.count; k++) /* the groups' boxes */
        words_put(&all, (unsigned)(1 + 6 * (nparts + k)));
    all.w[TAPE_W_GROUPS] = (unsigned)g.count;
    all.w[TAPE_W_PARTS] = (unsigned)nparts;
    all.w[TAPE_W_NEWTON] = (unsigned)newton;
    all.w[TAPE_W_PART_TABLE] = (unsigned)all.n;
    for (size_t k = 0; k < (size_t)nparts * TAPE_PART_WORDS; k++)
        words_put(&all, table[k]);
    all.w[TAPE_W_CODE] = (unsigned)all.n;
    for (size_t k = 0; k < b.code.n; k++)
        words_put(&all, b.code.w[k]);
    if (all.n % 2)
        words_put(&all, 0); /* doubles from an even word */
    all.w[TAPE_W_REALS] = (unsigned)all.n;
    for (size_t k = 0; k < b.reals.n; k++)
        words_put(&all, b.reals.w[k]);
    if (all.failed || b.code.failed || b.reals.failed) {
        free(all.w);
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the tape");
        goto done;
    }
    out->words = all.w;
    out->count = all.n;
    out->groups = g.count;
    out->parts = nparts;
    out->max_slots = b.max_slots;
    out->newton = newton;
done:
    free(parts);
    free(b.slot);
    free(b.last_use);
    free(b.used_as_interval);
    free(b.uses);
    free(b.squared);
    free(b.undefined);
    free(b.nonneg);
    free(b.code.w);
    free(b.reals.w);
    free(scratch);
    free(table);
    return st;
}
