/* implicits/brlcad_tree.c -- librt's regions of a database's top objects (src/librt/db_tree.cpp, db_walk_tree),
 * as a scene (brlcad.h).
 *
 *   1. down from the top objects to region level: a region combination, or a solid that no region holds (a
 *      region is invented for it), becomes a leaf carrying its path, accumulated matrix and colour; the booleans
 *      of the combinations above stay; an air region (aircode != 0) and an empty combination are nothing
 *   2. nothing removed (A u nothing = A, A - nothing = A, nothing - A = nothing, ...), then the booleans pushed
 *      down (db_non_union_push): (A u B) - C = (A - C) u (B - C), C + (A u B) = (C + A) u (C + B),
 *      C - (A u B) = (C - A) - B; every operand of the unions left at the top is a region
 *   3. each region's tree expanded down to its solids: a solid is instanced once per distinct (name, matrix);
 *      the region is named, numbered and coloured by its first (leftmost) leaf of step 1
 *   4. the scene: a primitive solid per instance, a region per region (tree in csg_node.h form, XOR written as
 *      (A - B) u (B - A)), a material per colour: the combination's colour (set from the top down until a
 *      combination that does not inherit, none below region level), else the colour table's for the region id
 *
 * Matrices compose from the top down: a member's matrix M under an accumulated P gives P M.
 */
#include "array_grow.h"
#include "brlcad_db.h"
#include "prim_place.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { X_NOP, X_REGION, X_SOLID, X_UNION, X_INTERSECT, X_SUBTRACT, X_XOR };

typedef struct {
    int op, left, right;
    int ref; /* X_REGION: its walk state; X_SOLID: its scene solid */
} xnode;

typedef struct {
    double m[16];
    int object, path; /* path: index of its path node */
    int rgb_valid, cinherit;
    unsigned char rgb[3];
} walk_state;

typedef struct {
    int object, parent;
} path_node;

/* A tree larger than this after the push-down (which copies subtrees) is refused rather than exhausting memory. */
#define X_NODES_MAX (1 << 22)
/* The recursive walks go at most this deep in all (combination nesting times tree depth). */
#define WALK_DEPTH_MAX 10000

typedef struct {
    const brlcad_db *db;
    iacsg_error *err;
    xnode *x;
    int nx, cap_x;
    walk_state *states;
    int nstates, cap_states;
    path_node *paths;
    int npaths, cap_paths;
    int depth;
    /* instances: each object's scene solids, a chain from inst_first[object] through inst_next[solid] */
    int *inst_first, *inst_next, cap_inst;
    brlcad_model *model;
    int cap_ids;
    float (*material_rgb)[3];
} builder;

static int nomem(builder *b) {
    iacsg_error_set(b->err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the scene of the database");
    return -1;
}

static int new_x(builder *b, int op, int left, int right, int ref) {
    if (b->nx >= X_NODES_MAX)
        return iacsg_error_set(b->err, IACSG_ERR_LIMIT, 0, 0, "the booleans above region level expand to more than "
                               "%d nodes", X_NODES_MAX), -1;
    if (!array_grow(&b->x, b->nx, &b->cap_x, sizeof *b->x, 1))
        return nomem(b);
    b->x[b->nx] = (xnode){op, left, right, ref};
    return b->nx++;
}

static int enter(builder *b) {
    if (++b->depth > WALK_DEPTH_MAX)
        return iacsg_error_set(b->err, IACSG_ERR_LIMIT, 0, 0, "the combinations nest more than %d levels deep in "
                               "all (members of members ...)", WALK_DEPTH_MAX), 0;
    return 1;
}

static void mat_mul(const double *a, const double *c, double *out) {
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            out[4 * i + j] = a[4 * i] * c[j] + a[4 * i + 1] * c[4 + j] + a[4 * i + 2] * c[8 + j] +
                             a[4 * i + 3] * c[12 + j];
}

/* The state under member `leaf` (a tree node) of the object of state s: matrix composed, path extended. */
static int member_state(builder *b, int s, int leaf) {
    const brl_node *n = &b->db->nodes[leaf];
    if (!array_grow(&b->states, b->nstates, &b->cap_states, sizeof *b->states, 1) ||
        !array_grow(&b->paths, b->npaths, &b->cap_paths, sizeof *b->paths, 1))
        return nomem(b);
    walk_state *t = &b->states[b->nstates];
    *t = b->states[s];
    if (n->mat >= 0)
        mat_mul(b->states[s].m, b->db->mats + 16 * n->mat, t->m);
    t->object = n->object;
    b->paths[b->npaths] = (path_node){n->object, b->states[s].path};
    t->path = b->npaths++;
    return b->nstates++;
}

/* A combination's colour, applied as librt does above region level (db_apply_state_from_comb). */
static void apply_colour(walk_state *s, const brl_object *o) {
    if (o->rgb_valid && !s->cinherit) {
        s->rgb_valid = 1;
        memcpy(s->rgb, o->rgb, 3);
        s->cinherit = o->inherit;
    }
}

static const int op_of[] = {[BRL_UNION] = X_UNION, [BRL_INTERSECT] = X_INTERSECT, [BRL_SUBTRACT] = X_SUBTRACT,
                            [BRL_XOR] = X_XOR};

/* A combination's tree at walk state s with each member replaced by leaf(member's state): step 1 (leaf =
 * to_regions) and step 3 (leaf = to_solids) walk it alike. */
static int tree_map(builder *b, int node, int s, int (*leaf)(builder *, int)) {
    if (!enter(b))
        return -1;
    const brl_node *n = &b->db->nodes[node];
    int r;
    if (n->op == BRL_LEAF) {
        int t = member_state(b, s, node);
        r = t < 0 ? -1 : leaf(b, t);
    } else {
        int l = tree_map(b, n->left, s, leaf);
        int rr = l < 0 ? -1 : tree_map(b, n->right, s, leaf);
        r = rr < 0 ? -1 : new_x(b, op_of[n->op], l, rr, -1);
    }
    b->depth--;
    return r;
}

/* Step 1 at walk state s: the tree of region leaves of its object, or -1. */
static int to_regions(builder *b, int s) {
    const brl_object *o = &b->db->objects[b->states[s].object];
    if (!o->is_comb)
        return new_x(b, X_REGION, -1, -1, s); /* a solid that no region holds: a region is invented for it */
    apply_colour(&b->states[s], o);
    if (o->region)
        return o->aircode != 0 ? (b->model->nair++, 0) : new_x(b, X_REGION, -1, -1, s); /* air: left out, as rt does */
    return o->tree < 0 ? 0 : tree_map(b, o->tree, s, to_regions);
}

/* Step 2: the tree with nothing (X_NOP, node 0) removed; 0 when nothing is left. */
static int drop_nothing(builder *b, int k) {
    xnode *n = &b->x[k];
    if (n->op == X_NOP || n->op == X_REGION || n->op == X_SOLID)
        return k;
    int op = n->op, l = drop_nothing(b, n->left), r = drop_nothing(b, b->x[k].right);
    b->x[k].left = l;
    b->x[k].right = r;
    if (l == 0)
        return op == X_UNION || op == X_XOR ? r : 0;
    if (r == 0)
        return op == X_INTERSECT ? 0 : l;
    return k;
}

/* A copy of the subtree at k. */
static int copy_tree(builder *b, int k) {
    xnode n = b->x[k];
    if (n.op == X_REGION || n.op == X_SOLID || n.op == X_NOP)
        return new_x(b, n.op, -1, -1, n.ref);
    int l = copy_tree(b, n.left);
    int r = l < 0 ? -1 : copy_tree(b, n.right);
    return r < 0 ? -1 : new_x(b, n.op, l, r, -1);
}

/* db_non_union_push, on a tree without nothing in it; 0 or -1. */
static int push_down(builder *b, int k) {
    if (b->x[k].op == X_REGION || b->x[k].op == X_SOLID)
        return 0;
    if (!enter(b) || push_down(b, b->x[k].left) < 0 || push_down(b, b->x[k].right) < 0)
        return -1;
    xnode n = b->x[k];
    int repush = 0;
    if ((n.op == X_INTERSECT || n.op == X_SUBTRACT) && b->x[n.left].op == X_UNION) {
        /* (A u B) op C -> (A op C) u (B op C') */
        int a = b->x[n.left].left, bb = b->x[n.left].right, c2 = copy_tree(b, n.right);
        if (c2 < 0)
            return -1;
        b->x[n.left] = (xnode){n.op, a, n.right, -1};
        int rhs = new_x(b, n.op, bb, c2, -1);
        if (rhs < 0)
            return -1;
        b->x[k] = (xnode){X_UNION, n.left, rhs, -1};
        repush = 1;
    } else if (n.op == X_INTERSECT && b->x[n.right].op == X_UNION) {
        /* C + (A u B) -> (C + A) u (C' + B) */
        int a = b->x[n.right].left, bb = b->x[n.right].right, c2 = copy_tree(b, n.left);
        if (c2 < 0)
            return -1;
        int lhs = new_x(b, X_INTERSECT, n.left, a, -1);
        if (lhs < 0)
            return -1;
        b->x[n.right] = (xnode){X_INTERSECT, c2, bb, -1};
        b->x[k] = (xnode){X_UNION, lhs, n.right, -1};
        repush = 1;
    } else if (n.op == X_SUBTRACT && b->x[n.right].op == X_UNION) {
        /* C - (A u B) -> (C - A) - B */
        int a = b->x[n.right].left, bb = b->x[n.right].right;
        b->x[n.right] = (xnode){X_SUBTRACT, n.left, a, -1};
        b->x[k] = (xnode){X_SUBTRACT, n.right, bb, -1};
        repush = 1;
    }
    int r = repush && (push_down(b, b->x[k].left) < 0 || push_down(b, b->x[k].right) < 0) ? -1 : 0;
    b->depth--;
    return r;
}

/* The region tops: the operands of the unions at the top, left to right (db_tally_subtree_regions). */
static int list_region_tops(builder *b, int k, int **tops, int *n, int *cap) {
    if (b->x[k].op == X_UNION)
        return list_region_tops(b, b->x[k].left, tops, n, cap) < 0 ? -1
                                                                   : list_region_tops(b, b->x[k].right, tops, n, cap);
    if (!array_grow(tops, *n, cap, sizeof **tops, 1))
        return nomem(b);
    (*tops)[(*n)++] = k;
    return 0;
}

/* librt's test for one instance (bn_mat_is_equal with rt's tolerances): translations within BRLCAD_DIST_TOL, the
 * other numbers within 1e-6. */
static int same_matrix(const double *a, const double *c) {
    for (int k = 0; k < 16; k++) {
        double tol = k == 3 || k == 7 || k == 11 ? BRLCAD_DIST_TOL : 1e-6, d = a[k] - c[k];
        if (!(d > -tol && d < tol))
            return 0;
    }
    return 1;
}

/* The scene solid of primitive `object` under matrix m: an existing instance of it, or a new one. */
static int instance(builder *b, int object, const double *m) {
    iacsg_scene *sc = b->model->scene;
    if (!b->inst_first) {
        b->inst_first = malloc((size_t)b->db->nobjects * sizeof *b->inst_first);
        if (!b->inst_first)
            return nomem(b);
        for (int k = 0; k < b->db->nobjects; k++)
            b->inst_first[k] = -1;
    }
    for (int k = b->inst_first[object]; k >= 0; k = b->inst_next[k])
        if (same_matrix(sc->solids[k].prim->mat, m))
            return k;
    if (!array_grow(&b->inst_next, sc->nsolids, &b->cap_inst, sizeof *b->inst_next, 1))
        return nomem(b);
    const brl_object *o = &b->db->objects[object];
    int k = scene_add_primitive(sc, o->name, o->type, b->db->params + o->params, o->nparams, m, b->err);
    if (k >= 0) {
        b->inst_next[k] = b->inst_first[object];
        b->inst_first[object] = k;
    }
    return k;
}

/* Step 3 below a region leaf: the object of state s down to its solids. */
static int to_solids(builder *b, int s) {
    const brl_object *o = &b->db->objects[b->states[s].object];
    if (o->is_comb)
        return o->tree < 0 ? 0 : tree_map(b, o->tree, s, to_solids);
    int k = instance(b, b->states[s].object, b->states[s].m);
    return k < 0 ? -1 : new_x(b, X_SOLID, -1, -1, k);
}

/* Step 3 for a region top: its region leaves expanded; *first is the first leaf's state. */
static int expand_region(builder *b, int k, int *first) {
    xnode n = b->x[k];
    if (n.op == X_REGION) {
        if (*first < 0)
            *first = n.ref;
        return to_solids(b, n.ref);
    }
    if (!enter(b))
        return -1;
    int l = expand_region(b, n.left, first);
    int r = l < 0 ? -1 : expand_region(b, n.right, first);
    b->depth--;
    return r < 0 ? -1 : new_x(b, n.op, l, r, -1);
}

/* Step 4: the csg_node form of the tree at k appended to out (operands relative to its start). */
static int emit(builder *b, int k, uint32_t **out, int *n, int *cap, int xor_swap) {
    xnode x = b->x[k];
    if (!array_grow(out, *n, cap, sizeof **out, 1))
        return nomem(b);
    int at = (*n)++;
    if (x.op == X_SOLID) {
        (*out)[at] = CSG_NODE(CSG_INSIDE, (uint32_t)x.ref);
        return 0;
    }
    if (*n > X_NODES_MAX)
        return iacsg_error_set(b->err, IACSG_ERR_LIMIT, 0, 0, "a region's tree has more than %d nodes", X_NODES_MAX),
               -1;
    if (x.op == X_XOR && !xor_swap) { /* A ^ B = (A - B) u (B - A) */
        (*out)[at] = CSG_NODE(CSG_UNION, 0);
        if (emit(b, k, out, n, cap, 1) < 0)
            return -1;
        (*out)[at] = CSG_NODE(CSG_UNION, (uint32_t)*n);
        return emit(b, k, out, n, cap, 2);
    }
    int op = xor_swap ? CSG_DIFFERENCE
             : x.op == X_UNION     ? CSG_UNION
             : x.op == X_INTERSECT ? CSG_INTERSECT
                                   : CSG_DIFFERENCE;
    int first = xor_swap == 2 ? x.right : x.left, second = xor_swap == 2 ? x.left : x.right;
    if (emit(b, first, out, n, cap, 0) < 0)
        return -1;
    (*out)[at] = CSG_NODE(op, (uint32_t)*n);
    return emit(b, second, out, n, cap, 0);
}

static char *path_name(builder *b, int path) {
    size_t len = 0;
    for (int p = path; p >= 0; p = b->paths[p].parent)
        len += 1 + strlen(b->db->objects[b->paths[p].object].name);
    char *s = malloc(len + 1);
    if (!s)
        return NULL;
    s[len] = '\0';
    for (int p = path; p >= 0; p = b->paths[p].parent) {
        const char *name = b->db->objects[b->paths[p].object].name;
        size_t n = strlen(name);
        len -= n + 1;
        s[len] = '/';
        memcpy(s + len + 1, name, n);
    }
    return s;
}

/* The material of a region first reached through state s with region id `id`; -1 for the palette, -2 when out
 * of memory. */
static int region_material(builder *b, const walk_state *s, int id) {
    float rgb[3];
    if (s->rgb_valid) {
        for (int k = 0; k < 3; k++)
            rgb[k] = (float)s->rgb[k] / 255.0f;
    } else {
        int c = 0;
        while (c < b->db->ncolours && !(b->db->colours[c].low <= id && id <= b->db->colours[c].high))
            c++;
        if (c == b->db->ncolours)
            return -1;
        for (int k = 0; k < 3; k++) /* librt's rounding for the table */
            rgb[k] = ((float)b->db->colours[c].rgb[k] + 0.5f) / 255.0f;
    }
    for (int k = 0; k < 3; k++)
        rgb[k] *= rgb[k]; /* the scene's albedo is linear; the image is encoded with gamma 2 (kernels/light.h) */
    iacsg_scene *sc = b->model->scene;
    for (int m = 0; m < sc->nmaterials; m++)
        if (memcmp(sc->materials[m].rgb, rgb, sizeof rgb) == 0)
            return m;
    char name[32];
    snprintf(name, sizeof name, "%.0f/%.0f/%.0f", sqrt(rgb[0]) * 255, sqrt(rgb[1]) * 255, sqrt(rgb[2]) * 255);
    return scene_add_material(sc, name, rgb, b->err) < 0 ? -2 : sc->nmaterials - 1;
}

static iacsg_status add_region(builder *b, int top) {
    int first = -1, tree = expand_region(b, top, &first);
    if (tree < 0)
        return b->err->status;
    tree = drop_nothing(b, tree);
    if (tree == 0)
        return IACSG_OK; /* an empty region, which librt ignores */
    uint32_t *nodes = NULL;
    int n = 0, cap = 0;
    if (emit(b, tree, &nodes, &n, &cap, 0) < 0) {
        free(nodes);
        return b->err->status;
    }
    const walk_state *s = &b->states[first];
    const brl_object *o = &b->db->objects[s->object];
    int id = o->is_comb ? o->region_id : 0;
    int material = region_material(b, s, id);
    char *name = path_name(b, s->path);
    if (!name && material >= -1)
        nomem(b);
    int root = material < -1 || !name ? -1 : scene_add_tree(b->model->scene, nodes, n, b->err);
    int item = root < 0 ? -1 : scene_add_region(b->model->scene, name, root, material, b->err);
    free(nodes);
    free(name);
    if (item < 0)
        return b->err->status;
    if (!array_grow(&b->model->region_ids, item, &b->cap_ids, sizeof *b->model->region_ids, 1))
        return (iacsg_status)(nomem(b), IACSG_ERR_NOMEM);
    b->model->region_ids[item] = id;
    return IACSG_OK;
}

/* The top object `name`'s index, or -1 with a message that suggests the closest top object. */
static int find_top(builder *b, const char *name) {
    int k = brlcad_db_find(b->db, name);
    if (k >= 0)
        return k;
    char tops[200] = "";
    size_t len = 0;
    for (int t = 0; t < b->db->ntops && len < sizeof tops - 60; t++)
        len += (size_t)snprintf(tops + len, sizeof tops - len, "%s%s", t ? ", " : "",
                                b->db->objects[b->db->tops[t]].name);
    iacsg_error_set(b->err, IACSG_ERR_NAME, 0, 0, "the database has no object '%s' (its top objects: %s%s)", name,
                    tops, b->db->ntops > 0 && len >= sizeof tops - 60 ? ", ..." : "");
    return -1;
}

static iacsg_status build(builder *b, const char *const *objects, int nobjects) {
    int whole = 0, ntops = nobjects ? nobjects : b->db->ntops;
    if (new_x(b, X_NOP, -1, -1, -1) < 0) /* node 0: nothing */
        return b->err->status;
    for (int t = 0; t < ntops; t++) {
        int object = nobjects ? find_top(b, objects[t]) : b->db->tops[t];
        if (object < 0)
            return b->err->status;
        if (!array_grow(&b->states, b->nstates, &b->cap_states, sizeof *b->states, 1) ||
            !array_grow(&b->paths, b->npaths, &b->cap_paths, sizeof *b->paths, 1))
            return (iacsg_status)(nomem(b), IACSG_ERR_NOMEM);
        walk_state *s = &b->states[b->nstates];
        memset(s, 0, sizeof *s);
        for (int k = 0; k < 16; k += 5)
            s->m[k] = 1;
        s->object = object;
        b->paths[b->npaths] = (path_node){object, -1};
        s->path = b->npaths++;
        int tree = to_regions(b, b->nstates++);
        if (tree < 0)
            return b->err->status;
        whole = t == 0 ? tree : new_x(b, X_UNION, whole, tree, -1);
        if (whole < 0)
            return b->err->status;
    }
    whole = drop_nothing(b, whole);
    int *tops = NULL, n = 0, cap = 0;
    iacsg_status st = IACSG_OK;
    if (whole != 0 && (push_down(b, whole) < 0 || list_region_tops(b, whole, &tops, &n, &cap) < 0))
        st = b->err->status;
    for (int k = 0; k < n && st == IACSG_OK; k++)
        st = add_region(b, tops[k]);
    free(tops);
    return st;
}

iacsg_status brlcad_model_build(const brlcad_db *db, const char *const *objects, int nobjects, brlcad_model *out,
                                iacsg_error *err) {
    memset(out, 0, sizeof *out);
    builder b = {0};
    b.db = db;
    b.err = err;
    b.model = out;
    out->scene = scene_create();
    if (out->scene)
        out->scene->dist_tol = BRLCAD_DIST_TOL;
    iacsg_status st = out->scene ? build(&b, objects, nobjects) : (iacsg_status)(nomem(&b), IACSG_ERR_NOMEM);
    if (st == IACSG_OK && out->scene->nitems == 0)
        st = iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the objects hold no region to render (all empty or air)");
    free(b.x);
    free(b.states);
    free(b.paths);
    free(b.inst_first);
    free(b.inst_next);
    if (st != IACSG_OK) {
        brlcad_model_free(out);
        return st;
    }
    out->ninstances = out->scene->nsolids;
    for (int k = 0; k < out->scene->nsolids; k++) /* placed once: for rt's model box, the BVH and the program */
        if (out->scene->solids[k].prim)
            prim_keep(out->scene->solids[k].prim);
    return IACSG_OK;
}

void brlcad_model_free(brlcad_model *m) {
    iacsg_scene_destroy(m->scene);
    free(m->region_ids);
    memset(m, 0, sizeof *m);
}

/* The box of region `item`'s tree as rt_bound_tree makes it: a union's hull, an intersection's overlap, the left
 * side of a difference; from the last node back to the root, boxes of finished subtrees on a stack. 0 when
 * unbounded (a half-space under a union) or when a solid is not valid (the renderer says why). solid_boxes: each
 * solid's world box, infinite where it is unbounded (a solid is a leaf of many regions after the push-down:
 * placing it at each took 0.1 s of havoc's command). */
static int region_box(const iacsg_scene *s, const double (*solid_boxes)[6], int item, double box[6]) {
    int root = s->items[item].tree, n = scene_tree_size(s, root), top = 0, ok = 1;
    double(*stack)[6] = malloc((size_t)n * sizeof *stack);
    if (!stack)
        return 0;
    for (int k = root + n - 1; k >= root; k--) {
        int op = CSG_NODE_OP(s->nodes[k]);
        if (op == CSG_INSIDE) {
            memcpy(stack[top++], solid_boxes[CSG_NODE_ARG(s->nodes[k])], sizeof stack[0]);
            continue;
        }
        /* children come after their parent: the left operand is on top, the right below it */
        double *l = stack[top - 1], *r = stack[top - 2];
        for (int j = 0; j < 3 && op != CSG_DIFFERENCE; j++) {
            int u = op == CSG_UNION;
            r[j] = u ? fmin(l[j], r[j]) : fmax(l[j], r[j]);
            r[j + 3] = u ? fmax(l[j + 3], r[j + 3]) : fmin(l[j + 3], r[j + 3]);
        }
        if (op == CSG_DIFFERENCE)
            memcpy(r, l, sizeof stack[0]);
        top--;
    }
    memcpy(box, stack[0], sizeof stack[0]);
    free(stack);
    for (int j = 0; j < 6; j++)
        ok &= isfinite(box[j]);
    return ok;
}

int brlcad_scene_bounds(const iacsg_scene *s, double box[6]) {
    int any = 0;
    double(*solid_boxes)[6] = malloc((size_t)(s->nsolids ? s->nsolids : 1) * sizeof *solid_boxes);
    if (!solid_boxes)
        return 0;
    for (int k = 0; k < s->nsolids; k++) {
        const scene_prim *p = s->solids[k].prim;
        if (!p || !prim_world_box(p, solid_boxes[k])) /* unbounded: the infinite box, as librt */
            for (int j = 0; j < 3; j++)
                solid_boxes[k][j] = -INFINITY, solid_boxes[k][j + 3] = INFINITY;
    }
    for (int k = 0; k < 3; k++) {
        box[k] = INFINITY;
        box[k + 3] = -INFINITY;
    }
    for (int r = 0; r < s->nitems; r++) {
        double b[6];
        if (s->items[r].kind != SCENE_REGION || !region_box(s, (const double(*)[6])solid_boxes, r, b))
            continue; /* an unbounded region (a half-space) is left out, as librt leaves it out */
        for (int j = 0; j < 3; j++) {
            box[j] = fmin(box[j], b[j]);
            box[j + 3] = fmax(box[j + 3], b[j + 3]);
        }
        any = 1;
    }
    free(solid_boxes);
    for (int j = 0; j < 3 && any; j++) { /* whole mm outward, as rt_prep rounds its model box */
        box[j] = floor(box[j]);
        box[j + 3] = ceil(box[j + 3]);
    }
    return any;
}
