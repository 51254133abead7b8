/* implicits/brlcad_db.c -- the database the .asc readers fill (brlcad_db.h): objects by name, tree nodes,
 * matrices, the colour table; then resolution of members, refusal of dangling references and cycles, and the
 * list of top objects. */
#include "brlcad_db.h"
#include "array_grow.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int out_of_memory(iacsg_error *err) {
    iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory reading the database");
    return -1;
}

static char *copy_n(const char *s, size_t n) {
    char *c = malloc(n + 1);
    if (c) {
        memcpy(c, s, n);
        c[n] = '\0';
    }
    return c;
}

brlcad_db *brlcad_db_create(int version) {
    brlcad_db *db = calloc(1, sizeof *db);
    if (db)
        db->version = version;
    return db;
}

void brlcad_db_destroy(brlcad_db *db) {
    if (!db)
        return;
    for (int k = 0; k < db->nobjects; k++)
        free(db->objects[k].name);
    for (int k = 0; k < db->nnodes; k++)
        free(db->nodes[k].name);
    free(db->objects);
    free(db->nodes);
    free(db->params);
    free(db->mats);
    free(db->colours);
    free(db->hash);
    free(db->tops);
    free(db);
}

static uint32_t hash_name(const char *s, size_t n) {
    uint32_t h = 2166136261u; /* FNV-1a */
    for (size_t k = 0; k < n; k++)
        h = (h ^ (unsigned char)s[k]) * 16777619u;
    return h;
}

/* The slot of the name's entry, or of the empty slot where it would go. */
static int hash_slot(const brlcad_db *db, const char *s, size_t n) {
    uint32_t mask = (uint32_t)db->hash_size - 1, k = hash_name(s, n) & mask;
    for (;; k = (k + 1) & mask) {
        int e = db->hash[k];
        if (e == 0)
            return (int)k;
        const char *name = db->objects[e - 1].name;
        if (strncmp(name, s, n) == 0 && name[n] == '\0')
            return (int)k;
    }
}

static int find_n(const brlcad_db *db, const char *s, size_t n) {
    return db->hash_size ? db->hash[hash_slot(db, s, n)] - 1 : -1;
}

int brlcad_db_find(const brlcad_db *db, const char *name) { return find_n(db, name, strlen(name)); }

/* Keeps the table at most half full. */
static int hash_reserve(brlcad_db *db) {
    if (2 * (db->nobjects + 1) <= db->hash_size)
        return 1;
    int size = db->hash_size ? 2 * db->hash_size : 256;
    int *old = db->hash, old_size = db->hash_size;
    db->hash = calloc((size_t)size, sizeof *db->hash);
    if (!db->hash) {
        db->hash = old;
        return 0;
    }
    db->hash_size = size;
    for (int k = 0; k < old_size; k++)
        if (old[k]) {
            const char *name = db->objects[old[k] - 1].name;
            db->hash[hash_slot(db, name, strlen(name))] = old[k];
        }
    free(old);
    return 1;
}

static int add_object(brlcad_db *db, const char *name, size_t n, int line, iacsg_error *err) {
    if (n == 0)
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "an object without a name"), -1;
    int prev = find_n(db, name, n);
    if (prev >= 0)
        return iacsg_error_set(err, IACSG_ERR_NAME, line, 1, "'%s' is already defined (line %d)",
                               db->objects[prev].name, db->objects[prev].line),
               -1;
    if (!array_grow(&db->objects, db->nobjects, &db->cap_objects, sizeof *db->objects, 1) || !hash_reserve(db))
        return out_of_memory(err);
    brl_object o = {0};
    o.name = copy_n(name, n);
    if (!o.name)
        return out_of_memory(err);
    o.line = line;
    o.tree = -1;
    db->objects[db->nobjects] = o;
    db->hash[hash_slot(db, name, n)] = db->nobjects + 1;
    return db->nobjects++;
}

int brlcad_db_add_prim(brlcad_db *db, const char *name, size_t n, int line, scene_prim_type type,
                       const double *params, int nparams, iacsg_error *err) {
    if (!array_grow(&db->params, db->nparams, &db->cap_params, sizeof *db->params, nparams))
        return out_of_memory(err);
    int k = add_object(db, name, n, line, err);
    if (k < 0)
        return -1;
    brl_object *o = &db->objects[k];
    o->type = type;
    o->nparams = nparams;
    o->params = db->nparams;
    memcpy(db->params + db->nparams, params, (size_t)nparams * sizeof *params);
    db->nparams += nparams;
    return k;
}

int brlcad_db_add_comb(brlcad_db *db, const char *name, size_t n, int line, iacsg_error *err) {
    int k = add_object(db, name, n, line, err);
    if (k >= 0)
        db->objects[k].is_comb = 1;
    return k;
}

int brlcad_db_leaf(brlcad_db *db, const char *name, size_t n, int line, const double *mat, iacsg_error *err) {
    if (!array_grow(&db->nodes, db->nnodes, &db->cap_nodes, sizeof *db->nodes, 1) ||
        (mat && !array_grow(&db->mats, 16 * db->nmats, &db->cap_mats, sizeof *db->mats, 16)))
        return out_of_memory(err);
    brl_node node = {BRL_LEAF, -1, -1, copy_n(name, n), -1, -1, line};
    if (!node.name)
        return out_of_memory(err);
    if (mat) {
        memcpy(db->mats + 16 * db->nmats, mat, 16 * sizeof *mat);
        node.mat = db->nmats++;
    }
    db->nodes[db->nnodes] = node;
    return db->nnodes++;
}

int brlcad_db_binary(brlcad_db *db, brl_op op, int left, int right, iacsg_error *err) {
    if (!array_grow(&db->nodes, db->nnodes, &db->cap_nodes, sizeof *db->nodes, 1))
        return out_of_memory(err);
    db->nodes[db->nnodes] = (brl_node){op, left, right, NULL, -1, -1, 0};
    return db->nnodes++;
}

int brlcad_db_add_colour(brlcad_db *db, int low, int high, const int rgb[3], iacsg_error *err) {
    if (!array_grow(&db->colours, db->ncolours, &db->cap_colours, sizeof *db->colours, 1))
        return out_of_memory(err);
    brl_colour *c = &db->colours[db->ncolours];
    c->low = low;
    c->high = high;
    for (int k = 0; k < 3; k++)
        c->rgb[k] = (unsigned char)rgb[k];
    return db->ncolours++;
}

/* Resolves the leaves of combination k's tree (an explicit stack: trees nest as deep as they have members). */
static iacsg_status resolve_tree(brlcad_db *db, int k, int *stack, iacsg_error *err) {
    int top = 0;
    if (db->objects[k].tree >= 0)
        stack[top++] = db->objects[k].tree;
    while (top > 0) {
        brl_node *n = &db->nodes[stack[--top]];
        if (n->op != BRL_LEAF) { /* the left one on top: members are resolved in the order written */
            stack[top++] = n->right;
            stack[top++] = n->left;
            continue;
        }
        n->object = brlcad_db_find(db, n->name);
        if (n->object < 0)
            return iacsg_error_set(err, IACSG_ERR_NAME, n->line, 1,
                                   "combination '%s' has a member '%s' that the database does not define",
                                   db->objects[k].name, n->name);
        db->objects[n->object].referenced = 1;
    }
    return IACSG_OK;
}

/* Depth-first over combinations, refusing a combination that contains itself. state: 0 unvisited, 1 on the
 * path, 2 done. The walk keeps its own stack of (object, next leaf to visit) over each tree's leaves. */
static iacsg_status refuse_cycles(const brlcad_db *db, const int *leaves, const int *first_leaf, iacsg_error *err) {
    unsigned char *state = calloc((size_t)db->nobjects + 1, 1);
    int *path = malloc(((size_t)db->nobjects + 1) * 2 * sizeof *path);
    iacsg_status st = IACSG_OK;
    if (!state || !path)
        st = (iacsg_status)(out_of_memory(err), IACSG_ERR_NOMEM);
    for (int root = 0; st == IACSG_OK && root < db->nobjects; root++) {
        if (!db->objects[root].is_comb || state[root])
            continue;
        int depth = 0;
        path[0] = root;
        path[1] = first_leaf[root];
        state[root] = 1;
        while (depth >= 0 && st == IACSG_OK) {
            int obj = path[2 * depth], *next = &path[2 * depth + 1];
            if (*next == first_leaf[obj + 1]) {
                state[obj] = 2;
                depth--;
                continue;
            }
            int child = db->nodes[leaves[(*next)++]].object;
            if (!db->objects[child].is_comb || state[child] == 2)
                continue;
            if (state[child] == 1) {
                st = iacsg_error_set(err, IACSG_ERR_NAME, db->objects[child].line, 1,
                                     "combination '%s' contains itself (a cycle through '%s')",
                                     db->objects[child].name, db->objects[obj].name);
                break;
            }
            state[child] = 1;
            depth++;
            path[2 * depth] = child;
            path[2 * depth + 1] = first_leaf[child];
        }
    }
    free(state);
    free(path);
    return st;
}

/* The leaves of every combination, grouped by combination: leaves[first_leaf[k] .. first_leaf[k + 1] - 1]. */
static void list_leaves(const brlcad_db *db, int *leaves, int *first_leaf, int *stack) {
    int n = 0;
    for (int k = 0; k < db->nobjects; k++) {
        first_leaf[k] = n;
        int top = 0;
        if (db->objects[k].is_comb && db->objects[k].tree >= 0)
            stack[top++] = db->objects[k].tree;
        while (top > 0) {
            const brl_node *node = &db->nodes[stack[--top]];
            if (node->op == BRL_LEAF) {
                leaves[n++] = (int)(node - db->nodes);
            } else {
                stack[top++] = node->left;
                stack[top++] = node->right;
            }
        }
    }
    first_leaf[db->nobjects] = n;
}

iacsg_status brlcad_db_finish(brlcad_db *db, iacsg_error *err) {
    int *stack = malloc(((size_t)db->nnodes + 1) * sizeof *stack);
    int *leaves = malloc(((size_t)db->nnodes + 1) * sizeof *leaves);
    int *first_leaf = malloc(((size_t)db->nobjects + 1) * sizeof *first_leaf);
    iacsg_status st = IACSG_OK;
    if (!stack || !leaves || !first_leaf)
        st = (iacsg_status)(out_of_memory(err), IACSG_ERR_NOMEM);
    for (int k = 0; st == IACSG_OK && k < db->nobjects; k++)
        if (db->objects[k].is_comb)
            st = resolve_tree(db, k, stack, err);
    if (st == IACSG_OK) {
        list_leaves(db, leaves, first_leaf, stack);
        st = refuse_cycles(db, leaves, first_leaf, err);
    }
    if (st == IACSG_OK) {
        db->tops = malloc(((size_t)db->nobjects + 1) * sizeof *db->tops);
        if (!db->tops)
            st = (iacsg_status)(out_of_memory(err), IACSG_ERR_NOMEM);
        for (int k = 0; st == IACSG_OK && k < db->nobjects; k++)
            if (!db->objects[k].referenced)
                db->tops[db->ntops++] = k;
    }
    free(stack);
    free(leaves);
    free(first_leaf);
    return st;
}

iacsg_status brlcad_db_read(const char *text, size_t len, brlcad_db **out, iacsg_error *err) {
    *out = NULL;
    size_t nul = strlen(text);
    if (nul < len) {
        int line = 1;
        for (size_t k = 0; k < nul; k++)
            line += text[k] == '\n';
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "a NUL byte in the database text");
    }
    const char *p = text;
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
        p++;
    int v4 = p[0] == 'I' && (p[1] == ' ' || p[1] == '\t');
    iacsg_status st = v4 ? brlcad_read_v4(text, len, out, err) : brlcad_read_v5(text, len, out, err);
    if (st == IACSG_OK)
        st = brlcad_db_finish(*out, err);
    if (st != IACSG_OK) {
        brlcad_db_destroy(*out);
        *out = NULL;
    }
    return st;
}

int brlcad_db_top_count(const brlcad_db *db) { return db->ntops; }

const char *brlcad_db_top_name(const brlcad_db *db, int k) { return db->objects[db->tops[k]].name; }
