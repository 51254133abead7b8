/* src/scene_terms.c -- see scene_terms.h. */
#include "scene_terms.h"
#include "implicits/array_grow.h"
#include "kernels/csg_node.h"
#include "kernels/scene_data.h"
#include <stdlib.h>
#include <string.h>

/* The distributed terms of a region may hold at most this many nodes for each node of its tree (plus a constant),
 * else its terms are its tree cut at its unions only: a difference distributed over n terms is copied n times. */
#define TERMS_GROWTH 4
#define TERMS_SLACK 256

/* A modifier on the way down to a term: "op node" (an intersection or difference with the subtree at `node`),
 * applied before the modifier `next` (-1: none). */
typedef struct {
    int op, node, next;
} modifier;

/* One solid's entry before the lists are sorted by solid. */
typedef struct {
    int solid, item, root, size;
} trigger;

typedef struct {
    const uint32_t *nodes; /* the scene's trees */
    modifier *mods;
    int nmods, cap_mods;
    int *stack; /* pairs (node, modifier chain) */
    int cap_stack;
    uint32_t *tree; /* the region's terms, one after another; each term's operands index tree */
    int ntree, cap_tree;
    int *term_root; /* term j is tree[term_root[j] .. term_root[j + 1]) */
    int nterms, cap_terms;
    trigger *triggers;
    int ntriggers, cap_triggers;
    int *stamp; /* per solid: the last term that listed it (1 + its number), against duplicates */
    int stamps;
    int *scratch; /* per node of a term: its triggers' count, then the relinearisation's stack need */
    int *task;
    int cap_scratch;
} builder;

static int tree_size(const uint32_t *nodes, int root) { return csg_tree_last(nodes, root) + 1 - root; }

/* Copies the subtree at src[root] to b->tree's end (room made); returns its size. */
static int copy_subtree(builder *b, const uint32_t *src, int root) {
    int size = tree_size(src, root), at = b->ntree;
    for (int j = 0; j < size; j++) {
        uint32_t node = src[root + j];
        int op = CSG_NODE_OP(node);
        int binary = op == CSG_UNION || op == CSG_INTERSECT || op == CSG_DIFFERENCE;
        b->tree[at + j] = binary ? CSG_NODE(op, CSG_NODE_ARG(node) - (uint32_t)root + (uint32_t)at) : node;
    }
    b->ntree += size;
    return size;
}

/* Appends the term `base` with the modifiers of `chain` applied in order: ((base op1 x1) op2 x2) ..., in
 * preorder the outermost operator first, then base, then x1, x2, .... Returns -1 (nothing appended) where the
 * terms would pass `limit` nodes, 0 when out of memory. */
static int emit_term(builder *b, int base, int chain, int limit) {
    int n = 0, size = tree_size(b->nodes, base);
    for (int m = chain; m >= 0; m = b->mods[m].next) {
        n += 1;
        size += 1 + tree_size(b->nodes, b->mods[m].node);
    }
    if (b->ntree + size > limit)
        return -1;
    if (!array_grow(&b->tree, b->ntree, &b->cap_tree, sizeof *b->tree, size) ||
        !array_grow(&b->term_root, b->nterms, &b->cap_terms, sizeof *b->term_root, 2))
        return 0;
    int start = b->ntree;
    b->term_root[b->nterms++] = start;
    b->ntree += n;
    copy_subtree(b, b->nodes, base);
    int i = 0;
    for (int m = chain; m >= 0; m = b->mods[m].next, i++) { /* modifier i sits at start + n - 1 - i */
        b->tree[start + n - 1 - i] = CSG_NODE(b->mods[m].op, (uint32_t)b->ntree);
        copy_subtree(b, b->nodes, b->mods[m].node);
    }
    return 1;
}

/* Splits the tree at `root` into b's terms (from none): cut at unions; with `distribute`, also down through the
 * left side of intersections and differences, which become modifiers of the terms below them. Returns 1, or
 * emit_term's -1 or 0. */
static int split(builder *b, int root, int distribute, int limit) {
    int top = 0;
    b->nmods = b->ntree = b->nterms = 0;
    if (!array_grow(&b->stack, 0, &b->cap_stack, sizeof *b->stack, 2))
        return 0;
    b->stack[top++] = root;
    b->stack[top++] = -1;
    while (top > 0) {
        int chain = b->stack[--top], k = b->stack[--top];
        uint32_t node = b->nodes[k];
        int op = CSG_NODE_OP(node), right = (int)CSG_NODE_ARG(node);
        if (op == CSG_UNION) {
            if (!array_grow(&b->stack, top, &b->cap_stack, sizeof *b->stack, 4))
                return 0;
            b->stack[top++] = right; /* popped last: the terms keep the tree's order */
            b->stack[top++] = chain;
            b->stack[top++] = k + 1;
            b->stack[top++] = chain;
        } else if (distribute && (op == CSG_INTERSECT || op == CSG_DIFFERENCE)) {
            if (!array_grow(&b->mods, b->nmods, &b->cap_mods, sizeof *b->mods, 1))
                return 0;
            b->mods[b->nmods] = (modifier){op, right, chain};
            b->stack[top++] = k + 1;
            b->stack[top++] = b->nmods++;
        } else {
            int ok = emit_term(b, k, chain, limit);
            if (ok <= 0)
                return ok;
        }
    }
    b->term_root[b->nterms] = b->ntree;
    return 1;
}

/* Lists the triggers of the term tree[root .. root + size) (scene_terms.h), whose device tree is at device_root:
 * per node how many solids it would list (under a NOT, every leaf of it: the NOT may be in wherever its child is
 * out; counted as its subtree's size), then from the root down, the cheaper side of each intersection. */
static int list_triggers(builder *b, int item, int root, int size, int device_root, int device_size) {
    const uint32_t *tree = b->tree;
    int *count = b->scratch, *task = b->task, top = 0;
    for (int k = root + size - 1; k >= root; k--) {
        int op = CSG_NODE_OP(tree[k]), c = 1;
        if (op == CSG_NOT) {
            c = tree_size(tree, k + 1);
        } else if (op != CSG_INSIDE && op != CSG_OUTSIDE) {
            int l = count[k + 1 - root], r = count[CSG_NODE_ARG(tree[k]) - root];
            c = op == CSG_UNION ? l + r : op == CSG_INTERSECT ? (l <= r ? l : r) : l;
        }
        count[k - root] = c;
    }
    b->stamps += 1;
    task[top++] = root;
    while (top > 0) {
        int k = task[--top], op = CSG_NODE_OP(tree[k]), right = (int)CSG_NODE_ARG(tree[k]);
        if (op == CSG_INSIDE || op == CSG_OUTSIDE) {
            if (b->stamp[right] == b->stamps)
                continue;
            b->stamp[right] = b->stamps;
            if (!array_grow(&b->triggers, b->ntriggers, &b->cap_triggers, sizeof *b->triggers, 1))
                return 0;
            b->triggers[b->ntriggers++] = (trigger){right, item, device_root, device_size};
        } else if (op == CSG_NOT) { /* each leaf under it */
            for (int j = k + 1; j < k + tree_size(tree, k + 1) + 1; j++)
                if (CSG_NODE_OP(tree[j]) == CSG_INSIDE || CSG_NODE_OP(tree[j]) == CSG_OUTSIDE)
                    task[top++] = j;
        } else if (op == CSG_UNION) {
            task[top++] = right;
            task[top++] = k + 1;
        } else {
            task[top++] = op == CSG_INTERSECT && count[right - root] < count[k + 1 - root] ? right : k + 1;
        }
    }
    return 1;
}

/* Appends the term tree[root .. root + size) to t->nodes, children ordered so that the deeper is evaluated first
 * (kernels/classify.h: from the last node back, the second child first); a difference whose left side is deeper
 * becomes an intersection with the negated right side first. Returns the stack depth its evaluation needs. */
static int relinearise(builder *b, int root, int size, scene_tables *t) {
    const uint32_t *tree = b->tree;
    int *need = b->scratch, *task = b->task;
    for (int k = root + size - 1; k >= root; k--) {
        int op = CSG_NODE_OP(tree[k]);
        if (op == CSG_INSIDE || op == CSG_OUTSIDE) {
            need[k - root] = 1;
        } else if (op == CSG_NOT) {
            need[k - root] = need[k + 1 - root];
        } else {
            int l = need[k + 1 - root], r = need[CSG_NODE_ARG(tree[k]) - root];
            int deep = l > r ? l : r, shallow = l > r ? r : l;
            need[k - root] = deep > shallow + 1 ? deep : shallow + 1;
        }
    }
    int result = need[0], top = 0;
    enum { EMIT, EMIT_NOT, PATCH };
    task[top++] = EMIT, task[top++] = root;
    while (top > 0) {
        int arg = task[--top], kind = task[--top];
        if (kind == PATCH) {
            t->nodes[arg] = CSG_NODE(CSG_NODE_OP(t->nodes[arg]), (uint32_t)t->nnodes);
            continue;
        }
        if (kind == EMIT_NOT) {
            t->nodes[t->nnodes++] = CSG_NODE(CSG_NOT, 0);
            task[top++] = EMIT, task[top++] = arg;
            continue;
        }
        uint32_t node = tree[arg];
        int op = CSG_NODE_OP(node);
        if (op == CSG_INSIDE || op == CSG_OUTSIDE) {
            t->nodes[t->nnodes++] = node;
            continue;
        }
        if (op == CSG_NOT) {
            t->nodes[t->nnodes++] = node;
            task[top++] = EMIT, task[top++] = arg + 1;
            continue;
        }
        int left = arg + 1, right = (int)CSG_NODE_ARG(node);
        int first = left, second = right, first_kind = EMIT;
        if (need[left - root] > need[right - root]) { /* the deeper one second: evaluated first */
            first = right;
            second = left;
            if (op == CSG_DIFFERENCE) {
                op = CSG_INTERSECT;
                first_kind = EMIT_NOT;
            }
        }
        int here = t->nnodes++;
        t->nodes[here] = CSG_NODE(op, 0);
        task[top++] = EMIT, task[top++] = second; /* pushed first: done last */
        task[top++] = PATCH, task[top++] = here;
        task[top++] = first_kind, task[top++] = first;
    }
    return result;
}

/* Region `item`'s terms: split, each relinearised into t->nodes and its triggers listed. */
static iacsg_status region_terms(builder *b, const iacsg_scene *s, int item, scene_tables *t, int *cap,
                                 iacsg_error *err) {
    const scene_item *it = &s->items[item];
    int size = tree_size(s->nodes, it->tree), ok = split(b, it->tree, 1, TERMS_GROWTH * size + TERMS_SLACK);
    if (ok < 0) /* cut at the unions only: the terms hold the tree's nodes, less its unions */
        ok = split(b, it->tree, 0, size);
    if (ok <= 0)
        goto nomem;
    for (int j = 0; j < b->nterms; j++) {
        int root = b->term_root[j], n = b->term_root[j + 1] - root;
        /* a relinearised term gains at most a NOT per difference */
        if (!array_grow(&b->scratch, 0, &b->cap_scratch, sizeof *b->scratch, n) ||
            !array_grow(&t->nodes, t->nnodes, cap, sizeof *t->nodes, 2 * n) ||
            !(b->task = realloc(b->task, sizeof *b->task * (size_t)(4 * n + 2))))
            goto nomem;
        int device_root = t->nnodes, need = relinearise(b, root, n, t);
        if (need > SCENE_TREE_STACK)
            return iacsg_error_set(err, IACSG_ERR_LIMIT, it->line, it->column,
                                   "region '%s' is too large to evaluate (a stack of %d, at most %d)",
                                   it->name ? it->name : "", need, SCENE_TREE_STACK);
        if (!list_triggers(b, item, root, n, device_root, t->nnodes - device_root))
            goto nomem;
    }
    return IACSG_OK;
nomem:
    return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory preparing the scene");
}

/* The lists from the triggers, by solid, each in the order of the regions (a stable counting sort). */
static int lists_of(const builder *b, int nsolids, scene_tables *t) {
    t->solid_items_start = calloc((size_t)nsolids + 2, sizeof(int));
    t->solid_items = malloc(sizeof(int) * SCENE_TERM_INTS * (size_t)(b->ntriggers + 1));
    if (!t->solid_items_start || !t->solid_items)
        return 0;
    int *start = t->solid_items_start;
    for (int j = 0; j < b->ntriggers; j++)
        start[b->triggers[j].solid + 2] += SCENE_TERM_INTS;
    for (int k = 1; k <= nsolids; k++)
        start[k + 1] += start[k];
    for (int j = 0; j < b->ntriggers; j++) { /* start[k + 1] is where solid k's next entry goes */
        const trigger *g = &b->triggers[j];
        int *e = t->solid_items + start[g->solid + 1];
        e[SCENE_TERM_ITEM] = g->item;
        e[SCENE_TERM_ROOT] = g->root;
        e[SCENE_TERM_SIZE] = g->size;
        start[g->solid + 1] += SCENE_TERM_INTS;
    }
    return 1;
}

iacsg_status scene_terms_build(const iacsg_scene *s, scene_tables *t, int *cap, unsigned char *used,
                               iacsg_error *err) {
    builder b = {.nodes = s->nodes};
    b.stamp = calloc((size_t)s->nsolids + 1, sizeof *b.stamp);
    iacsg_status st =
        b.stamp ? IACSG_OK : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory preparing the scene");
    for (int item = 0; st == IACSG_OK && item < s->nitems; item++) {
        if (s->items[item].kind != SCENE_REGION)
            continue;
        int root = s->items[item].tree, last = csg_tree_last(s->nodes, root);
        for (int k = root; k <= last; k++)
            if (CSG_NODE_OP(s->nodes[k]) == CSG_INSIDE || CSG_NODE_OP(s->nodes[k]) == CSG_OUTSIDE)
                used[CSG_NODE_ARG(s->nodes[k])] = 1;
        st = region_terms(&b, s, item, t, cap, err);
    }
    if (st == IACSG_OK && !lists_of(&b, s->nsolids, t))
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory preparing the scene");
    free(b.mods);
    free(b.stack);
    free(b.tree);
    free(b.term_root);
    free(b.triggers);
    free(b.stamp);
    free(b.scratch);
    free(b.task);
    return st;
}
