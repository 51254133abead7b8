/* src/scene_tables.c -- see scene_tables.h. */
#include "scene_tables.h"
#include "parallel.h"
#include "scene_terms.h"
#include "render.h"
#include "implicits/prim_place.h"
#include "kernels/scene_data.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

void scene_palette(int id, float rgb[3]) {
    static const float palette[8][3] = {{0.80f, 0.30f, 0.22f}, {0.25f, 0.45f, 0.85f}, {0.90f, 0.70f, 0.20f},
                                        {0.30f, 0.70f, 0.35f}, {0.65f, 0.35f, 0.75f}, {0.20f, 0.70f, 0.75f},
                                        {0.85f, 0.50f, 0.65f}, {0.60f, 0.60f, 0.55f}};
    memcpy(rgb, palette[id % 8], 3 * sizeof(float));
}

/* Shrinks a proven box (x0,y0,z0,x1,y1,z1) of a solid not depending on t: each face moves inwards by binary
 * search while the slab it leaves behind is proven free of zeros (f > 0 over it, one enclosure). The compiler's
 * boxes sit on a coarse grid of planes (implicits/bounds.c); the BVH culls rays by these, and a box 1.5 times
 * too wide on each axis made the BVH walk most of a frame of 1000 spheres. */
static void refine_box(const iacsg_expr *e, double b[6]) {
    for (int face = 0; face < 6; face++) {
        int axis = face % 3, upper = face >= 3;
        double good = b[face], bad = 0.5 * (b[axis] + b[axis + 3]);
        for (int step = 0; step < 12; step++) {
            double mid = 0.5 * (good + bad), lo[3] = {b[0], b[1], b[2]}, hi[3] = {b[3], b[4], b[5]}, f[2];
            if (upper)
                lo[axis] = mid;
            else
                hi[axis] = mid;
            iacsg_error err = {0};
            int empty = iacsg_expr_eval_box(e, 1, lo, hi, 0, f, &err) == IACSG_OK && f[0] > 0;
            *(empty ? &good : &bad) = mid;
        }
        b[face] = good;
    }
}

/* The solid's box for the kernels, for times in `time`: its proven box when its inside lies within it (f > 0 at
 * a point outside it, and so all over the connected outside, where f has no zero), else an infinite box. 1 if
 * bounded; *in_cube is set when the box holds only inside the cube of IACSG_BOUNDS_CUBE. */
static int solid_box_proven(const scene_solid *solid, const double time[2], double box[6], int *in_cube) {
    if (solid->prim) /* placed in the world (its parameters' intervals), not depending on t */
        return prim_world_box(solid->prim, box);
    const iacsg_expr *e = solid->expr;
    double b[6];
    iacsg_bounds_proof proof = iacsg_expr_bounds(e, time, b);
    int bounded = proof != IACSG_BOUNDS_NONE;
    *in_cube |= proof == IACSG_BOUNDS_IN_CUBE;
    if (bounded) {
        double p[3] = {0.5 * (b[0] + b[3]), 0.5 * (b[1] + b[4]), 0.5 * (b[2] + b[5])}, f[2];
        if (b[3] < IACSG_BOUNDS_CUBE) /* halfway from the box to the cube's side */
            p[0] = 0.5 * (b[3] + IACSG_BOUNDS_CUBE);
        else if (b[0] > -IACSG_BOUNDS_CUBE)
            p[0] = 0.5 * (b[0] - IACSG_BOUNDS_CUBE);
        else
            bounded = 0;
        iacsg_error err = {0};
        bounded = bounded && iacsg_expr_eval_box(e, 1, p, p, time[0], f, &err) == IACSG_OK && f[0] > 0;
        if (bounded && !iacsg_expr_uses_time(e))
            refine_box(e, b);
    }
    for (int k = 0; k < 3; k++) {
        box[k] = bounded ? b[k] : -INFINITY;
        box[k + 3] = bounded ? b[k + 3] : INFINITY;
    }
    return bounded;
}

/* Proves an expression solid's box once and keeps it in the solid; only for expressions without t, whose box
 * does not depend on the time asked. */
static void keep_box(scene_solid *solid) {
    static const double any_time[2] = {0, 0};
    solid->box_bounded = solid_box_proven(solid, any_time, solid->box, &solid->box_in_cube);
    solid->box_known = 1;
}

/* solid_box_proven, kept in the solid where its expression does not depend on t. */
static int solid_box(scene_solid *solid, const double time[2], double box[6], int *in_cube) {
    if (solid->prim || iacsg_expr_uses_time(solid->expr))
        return solid_box_proven(solid, time, box, in_cube);
    if (!solid->box_known)
        keep_box(solid);
    memcpy(box, solid->box, sizeof solid->box);
    *in_cube |= solid->box_in_cube;
    return solid->box_bounded;
}

/* The boxes that solid_box keeps (expressions without t), proven in threads before either pass asks for them:
 * each proof is independent (iacsg_expr_bounds keeps its state per call), and 1000 spheres took ~2 s on one
 * core. Below BOX_THREADS_MIN unproven solids, or where threads cannot start, solid_box proves them itself. */
#define BOX_THREADS_MIN 16
#define BOX_THREADS_MAX 8

typedef struct {
    scene_solid *solids;
    const int *todo;
    int ntodo, first, stride;
} box_share;

static void *prove_share(void *arg) {
    const box_share *b = arg;
    for (int i = b->first; i < b->ntodo; i += b->stride)
        keep_box(&b->solids[b->todo[i]]);
    return NULL;
}

static void prove_boxes(const iacsg_scene *s, const unsigned char *used) {
    int *todo = malloc((size_t)s->nsolids * sizeof *todo), ntodo = 0;
    if (!todo)
        return;
    for (int k = 0; k < s->nsolids; k++)
        if (used[k] && !s->solids[k].prim && !s->solids[k].box_known && !iacsg_expr_uses_time(s->solids[k].expr))
            todo[ntodo++] = k;
    int threads = parallel_cpus(BOX_THREADS_MAX);
    if (ntodo >= BOX_THREADS_MIN && threads > 1) {
        box_share share[BOX_THREADS_MAX];
        for (int k = 0; k < threads; k++)
            share[k] = (box_share){s->solids, todo, ntodo, k, threads};
        parallel_each(prove_share, share, sizeof share[0], threads);
    }
    free(todo);
}

/* ---- the BVH */

typedef struct {
    double key;
    int solid;
} keyed;

static int by_key(const void *a, const void *b) {
    double x = ((const keyed *)a)->key, y = ((const keyed *)b)->key;
    return (x > y) - (x < y);
}

typedef struct {
    const double *boxes; /* 6 per solid */
    scene_tables *t;
    keyed *scratch;
    double *after; /* the surface area of the boxes from each position on */
} bvh_builder;

/* The surface area of a box (x0 y0 z0 x1 y1 z1), half of it. */
static double box_area(const double *b) {
    double x = b[3] - b[0], y = b[4] - b[1], z = b[5] - b[2];
    return x * y + y * z + z * x;
}

static void box_grow(double *b, const double *s) {
    for (int k = 0; k < 3; k++) {
        b[k] = fmin(b[k], s[k]);
        b[k + 3] = fmax(b[k + 3], s[k + 3]);
    }
}

/* Where to split solids[0..n), sorted along an axis: the surface area heuristic (a ray that meets a node meets a
 * child with the odds of their areas, so the split minimises area(left) n_left + area(right) n_right), which on
 * the models' clusters of small parts beside long ones tests fewer boxes per ray than the median. */
static int bvh_split(bvh_builder *b, const int *solids, int n) {
    double box[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (int i = n - 1; i > 0; i--) {
        box_grow(box, b->boxes + 6 * solids[i]);
        b->after[i] = box_area(box);
    }
    double best = INFINITY;
    int split = n / 2;
    for (int k = 0; k < 6; k++)
        box[k] = k < 3 ? INFINITY : -INFINITY;
    for (int i = 1; i < n; i++) {
        box_grow(box, b->boxes + 6 * solids[i - 1]);
        double cost = box_area(box) * i + b->after[i] * (n - i);
        if (cost < best) {
            best = cost;
            split = i;
        }
    }
    return split;
}

/* Emits the subtree over solids[0..n) at the next node, split along its centres' longest axis (bvh_split). */
static void bvh_build(bvh_builder *b, int *solids, int n) {
    scene_tables *t = b->t;
    int node = t->nbvh++;
    double *box = t->bvh_box + 6 * node, lo[3] = {INFINITY, INFINITY, INFINITY},
           hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 6; k++)
        box[k] = k < 3 ? INFINITY : -INFINITY;
    for (int i = 0; i < n; i++) {
        const double *s = b->boxes + 6 * solids[i];
        for (int k = 0; k < 3; k++) {
            box[k] = fmin(box[k], s[k]);
            box[k + 3] = fmax(box[k + 3], s[k + 3]);
            double c = 0.5 * (s[k] + s[k + 3]);
            lo[k] = fmin(lo[k], c);
            hi[k] = fmax(hi[k], c);
        }
    }
    t->bvh_link[2 * node + SCENE_BVH_SOLID] = n == 1 ? solids[0] : -1;
    if (n > 1) {
        int axis = 0;
        for (int k = 1; k < 3; k++)
            axis = hi[k] - lo[k] > hi[axis] - lo[axis] ? k : axis;
        for (int i = 0; i < n; i++) {
            const double *s = b->boxes + 6 * solids[i];
            b->scratch[i].key = 0.5 * (s[axis] + s[axis + 3]);
            b->scratch[i].solid = solids[i];
        }
        qsort(b->scratch, (size_t)n, sizeof *b->scratch, by_key);
        for (int i = 0; i < n; i++)
            solids[i] = b->scratch[i].solid;
        int split = bvh_split(b, solids, n);
        bvh_build(b, solids, split);
        bvh_build(b, solids + split, n - split);
    }
    t->bvh_link[2 * node + SCENE_BVH_SKIP] = t->nbvh;
}

/* Unbounded solids first, each a leaf of its own (their boxes would make every node of the tree infinite),
 * then the BVH of the bounded ones. */
static int bvh_of(const iacsg_scene *s, const unsigned char *used, scene_tables *t) {
    double *boxes = malloc(6 * sizeof(double) * (size_t)(s->nsolids + 1));
    int *bounded = malloc(sizeof(int) * (size_t)(s->nsolids + 1));
    keyed *scratch = malloc(sizeof(keyed) * (size_t)(s->nsolids + 1));
    double *after = malloc(sizeof(double) * (size_t)(s->nsolids + 1));
    t->bvh_box = malloc(12 * sizeof(double) * (size_t)(s->nsolids + 1));
    t->bvh_link = malloc(5 * sizeof(int) * (size_t)(s->nsolids + 1)); /* the nodes', then the solids' leaves */
    int ok = boxes && bounded && scratch && after && t->bvh_box && t->bvh_link, nbounded = 0;
    prove_boxes(s, used);
    for (int k = 0; ok && k < s->nsolids; k++) {
        if (!used[k])
            continue;
        static const double times[2] = {0, 1}; /* the boxes hold for t in [0, 1] (render_scene.c) */
        if (solid_box(&s->solids[k], times, boxes + 6 * k, &t->in_cube)) {
            bounded[nbounded++] = k;
            continue;
        }
        int node = t->nbvh++;
        memcpy(t->bvh_box + 6 * node, boxes + 6 * k, 6 * sizeof(double));
        t->bvh_link[2 * node + SCENE_BVH_SKIP] = node + 1;
        t->bvh_link[2 * node + SCENE_BVH_SOLID] = k;
    }
    if (ok && nbounded > 0) {
        bvh_builder b = {boxes, t, scratch, after};
        bvh_build(&b, bounded, nbounded);
    }
    for (int k = 0; ok && k < s->nsolids; k++)
        t->bvh_link[2 * t->nbvh + k] = -1;
    for (int node = 0; ok && node < t->nbvh; node++)
        if (t->bvh_link[2 * node + SCENE_BVH_SOLID] >= 0)
            t->bvh_link[2 * t->nbvh + t->bvh_link[2 * node + SCENE_BVH_SOLID]] = node;
    free(boxes);
    free(bounded);
    free(scratch);
    free(after);
    return ok;
}

/* ---- region trees for the device */

/* Marks the solids of the tree at `root`. */
static void mark_solids(const iacsg_scene *s, int root, unsigned char *mark) {
    int last = root + scene_tree_size(s, root) - 1;
    for (int k = root; k <= last; k++) {
        int op = CSG_NODE_OP(s->nodes[k]);
        if (op == CSG_INSIDE || op == CSG_OUTSIDE)
            mark[CSG_NODE_ARG(s->nodes[k])] = 1;
    }
}

iacsg_status scene_tables_build(const iacsg_scene *s, scene_tables *t, iacsg_error *err) {
    memset(t, 0, sizeof *t);
    t->nsolids = s->nsolids;
    t->nitems = s->nitems;
    int cap = s->nnodes + 1;
    unsigned char *used = calloc((size_t)s->nsolids + 1, 1);
    t->nodes = malloc(sizeof(uint32_t) * (size_t)cap);
    t->items = malloc(sizeof(int) * SCENE_ITEM_INTS * (size_t)(s->nitems + 1));
    t->surfaces = malloc(sizeof(int) * (size_t)(s->nitems + 1));
    t->albedo = malloc(SCENE_MATERIAL_FLOATS * sizeof(float) * (size_t)(s->nitems + 1));
    iacsg_status st = used && t->nodes && t->items && t->surfaces && t->albedo
                          ? IACSG_OK
                          : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory preparing the scene");
    if (st == IACSG_OK && s->nnodes > 0)
        memcpy(t->nodes, s->nodes, sizeof(uint32_t) * (size_t)s->nnodes);
    t->nnodes = s->nnodes;
    for (int i = 0; st == IACSG_OK && i < s->nitems; i++) {
        const scene_item *it = &s->items[i];
        int *out = t->items + SCENE_ITEM_INTS * i;
        out[SCENE_ITEM_KIND] = it->kind == SCENE_REGION ? SCENE_KIND_REGION : SCENE_KIND_SURFACE;
        out[SCENE_ITEM_SOLID] = it->solid;
        out[SCENE_ITEM_ROOT] = it->tree;
        out[SCENE_ITEM_SIZE] = it->tree >= 0 ? scene_tree_size(s, it->tree) : 0;
        float *m = t->albedo + SCENE_MATERIAL_FLOATS * i;
        if (it->material >= 0)
            memcpy(m + SCENE_MATERIAL_RGB, s->materials[it->material].rgb, 3 * sizeof(float));
        else
            scene_palette(i, m + SCENE_MATERIAL_RGB);
        const scene_material *mat = it->material >= 0 ? &s->materials[it->material] : NULL;
        m[SCENE_MATERIAL_SPECULAR] = mat ? mat->specular : SCENE_DEFAULT_SPECULAR;
        m[SCENE_MATERIAL_SHININESS] = mat ? mat->shininess : SCENE_DEFAULT_SHININESS;
        m[SCENE_MATERIAL_REFLECT] = mat ? mat->reflect : 0;
        m[SCENE_MATERIAL_OPACITY] = mat ? mat->opacity : 1;
        if (it->kind == SCENE_SURFACE)
            t->surfaces[t->nsurfaces++] = i;
    }
    for (int k = 0; k < s->nsolids; k++)
        t->uses_time |= s->solids[k].expr && iacsg_expr_uses_time(s->solids[k].expr);
    if (st == IACSG_OK)
        st = scene_terms_build(s, t, &cap, used, err);
    if (st == IACSG_OK && !bvh_of(s, used, t))
        st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory preparing the scene");
    free(used);
    if (st != IACSG_OK)
        scene_tables_free(t);
    return st;
}

void scene_tables_free(scene_tables *t) {
    free(t->bvh_box);
    free(t->bvh_link);
    free(t->nodes);
    free(t->items);
    free(t->solid_items_start);
    free(t->solid_items);
    free(t->surfaces);
    free(t->albedo);
    memset(t, 0, sizeof *t);
}

int iacsg_scene_uses_time(const iacsg_scene *s) {
    int uses = s->expr && iacsg_expr_uses_time(s->expr);
    for (int k = 0; k < s->nsolids; k++)
        uses |= s->solids[k].expr && iacsg_expr_uses_time(s->solids[k].expr);
    return uses;
}

int iacsg_scene_bounds(const iacsg_scene *s, const double time[2], double box[6]) {
    if (s->nitems == 0)
        return s->expr && iacsg_expr_bounds(s->expr, time, box) != IACSG_BOUNDS_NONE;
    unsigned char *used = calloc((size_t)s->nsolids + 1, 1);
    if (!used)
        return 0;
    for (int i = 0; i < s->nitems; i++) {
        if (s->items[i].tree >= 0)
            mark_solids(s, s->items[i].tree, used);
        if (s->items[i].solid >= 0)
            used[s->items[i].solid] = 1;
    }
    int ok = 1, any = 0;
    for (int k = 0; k < 3; k++) {
        box[k] = INFINITY;
        box[k + 3] = -INFINITY;
    }
    prove_boxes(s, used);
    for (int k = 0; ok && k < s->nsolids; k++) {
        double b[6];
        if (!used[k])
            continue;
        int in_cube = 0;
        ok = solid_box(&s->solids[k], time, b, &in_cube);
        for (int c = 0; ok && c < 3; c++) {
            box[c] = fmin(box[c], b[c]);
            box[c + 3] = fmax(box[c + 3], b[c + 3]);
        }
        any = 1;
    }
    free(used);
    return ok && any;
}
