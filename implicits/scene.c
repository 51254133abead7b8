/* implicits/scene.c -- the scene structure (scene.h): the builder the front ends call, destruction, and the host's
 * evaluation of a tree. Parsing the scene language is in scene_parse.c. */
#include "scene.h"
#include "array_grow.h"
#include "prim_place.h"
#include <stdlib.h>
#include <string.h>

iacsg_scene *scene_create(void) { return calloc(1, sizeof(iacsg_scene)); }

void iacsg_scene_destroy(iacsg_scene *s) {
    if (!s)
        return;
    for (int k = 0; k < s->nmaterials; k++)
        free(s->materials[k].name);
    for (int k = 0; k < s->nsolids; k++) {
        free(s->solids[k].name);
        iacsg_expr_destroy(s->solids[k].expr);
        if (s->solids[k].prim) {
            free(s->solids[k].prim->params);
            prim_unkeep(s->solids[k].prim);
        }
        free(s->solids[k].prim);
    }
    for (int k = 0; k < s->nitems; k++)
        free(s->items[k].name);
    free(s->materials);
    free(s->lights);
    free(s->solids);
    free(s->items);
    free(s->nodes);
    iacsg_expr_destroy(s->expr);
    free(s);
}

static int out_of_memory(iacsg_error *err) {
    iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the scene");
    return -1;
}

/* A copy of name, or NULL for NULL; *ok is cleared when out of memory. */
static char *copy_name(const char *name, int *ok) {
    if (!name)
        return NULL;
    char *c = malloc(strlen(name) + 1);
    if (!c)
        *ok = 0;
    else
        strcpy(c, name);
    return c;
}

int scene_add_light(iacsg_scene *s, const scene_light *light, iacsg_error *err) {
    if (!array_grow(&s->lights, s->nlights, &s->cap_lights, sizeof *s->lights, 1))
        return out_of_memory(err);
    s->lights[s->nlights] = *light;
    return s->nlights++;
}

int scene_add_material(iacsg_scene *s, const char *name, const float rgb[3], iacsg_error *err) {
    int ok = array_grow(&s->materials, s->nmaterials, &s->cap_materials, sizeof *s->materials, 1);
    scene_material m = {copy_name(name, &ok), {rgb[0], rgb[1], rgb[2]}, SCENE_DEFAULT_SPECULAR,
                        SCENE_DEFAULT_SHININESS, 0, 1};
    if (!ok) {
        free(m.name);
        return out_of_memory(err);
    }
    s->materials[s->nmaterials] = m;
    return s->nmaterials++;
}

int scene_add_solid(iacsg_scene *s, const char *name, iacsg_expr *e, iacsg_error *err) {
    int ok = array_grow(&s->solids, s->nsolids, &s->cap_solids, sizeof *s->solids, 1);
    scene_solid solid = {.name = copy_name(name, &ok), .expr = e};
    if (!ok) {
        free(solid.name);
        iacsg_expr_destroy(e);
        return out_of_memory(err);
    }
    s->solids[s->nsolids] = solid;
    return s->nsolids++;
}

int scene_add_primitive(iacsg_scene *s, const char *name, scene_prim_type type, const double *params, int nparams,
                        const double mat[16], iacsg_error *err) {
    scene_prim *p = malloc(sizeof *p);
    double *copy = malloc((size_t)(nparams > 0 ? nparams : 1) * sizeof *copy);
    int ok = p && copy && array_grow(&s->solids, s->nsolids, &s->cap_solids, sizeof *s->solids, 1);
    char *copied = copy_name(name, &ok);
    if (!ok) {
        free(p);
        free(copy);
        free(copied);
        return out_of_memory(err);
    }
    memcpy(copy, params, (size_t)nparams * sizeof *copy);
    p->type = type;
    p->nparams = nparams;
    p->params = copy;
    memcpy(p->mat, mat, sizeof p->mat);
    p->placed = NULL;
    s->solids[s->nsolids] = (scene_solid){.name = copied, .prim = p};
    return s->nsolids++;
}

int scene_add_tree(iacsg_scene *s, const uint32_t *nodes, int n, iacsg_error *err) {
    if ((uint32_t)s->nnodes + (uint32_t)n > CSG_ARG_MAX)
        return iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0, "too many boolean nodes in the scene (at most %u)",
                               (unsigned)CSG_ARG_MAX),
               -1;
    if (!array_grow(&s->nodes, s->nnodes, &s->cap_nodes, sizeof *s->nodes, n))
        return out_of_memory(err);
    int root = s->nnodes;
    for (int k = 0; k < n; k++) {
        int op = CSG_NODE_OP(nodes[k]);
        int binary = op == CSG_UNION || op == CSG_INTERSECT || op == CSG_DIFFERENCE;
        s->nodes[root + k] = binary ? CSG_NODE(op, CSG_NODE_ARG(nodes[k]) + (uint32_t)root) : nodes[k];
    }
    s->nnodes += n;
    return root;
}

static int add_item(iacsg_scene *s, scene_item item, const char *name, iacsg_error *err) {
    int ok = array_grow(&s->items, s->nitems, &s->cap_items, sizeof *s->items, 1);
    item.name = copy_name(name, &ok);
    if (!ok) {
        free(item.name);
        return out_of_memory(err);
    }
    s->items[s->nitems] = item;
    return s->nitems++;
}

int scene_add_region(iacsg_scene *s, const char *name, int tree, int material, iacsg_error *err) {
    scene_item item = {SCENE_REGION, NULL, material, tree, -1, 0, 0};
    return add_item(s, item, name, err);
}

int scene_add_surface(iacsg_scene *s, const char *name, int solid, int condition, int material, iacsg_error *err) {
    int need = condition >= 0 ? csg_stack_need(s->nodes, condition) : 0;
    if (need > CSG_STACK_MAX) /* the device evaluates it on a stack of CSG_STACK_MAX entries (csg_node.h) */
        return iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0,
                               "the condition of surface '%s' is too large: evaluating it needs %d stack entries, "
                               "at most %d (a chain of n operands of & or | needs n)",
                               name ? name : "", need, CSG_STACK_MAX),
               -1;
    scene_item item = {SCENE_SURFACE, NULL, material, condition, solid, 0, 0};
    return add_item(s, item, name, err);
}

int scene_tree_size(const iacsg_scene *s, int root) { return csg_tree_last(s->nodes, root) + 1 - root; }

int scene_tree_eval(const iacsg_scene *s, int root, const signed char *sign) {
    int n = scene_tree_size(s, root);
    unsigned char small[64] = {0}, *value = n <= 64 ? small : calloc((size_t)n, 1);
    if (!value)
        return -1;
    /* Children come after their parent: one pass from the last node back to the root. */
    for (int k = root + n - 1; k >= root; k--) {
        uint32_t node = s->nodes[k];
        int arg = (int)CSG_NODE_ARG(node), left = k + 1 < root + n ? value[k + 1 - root] : 0;
        int right = arg - root >= 0 && arg - root < n ? value[arg - root] : 0, v = 0;
        switch (CSG_NODE_OP(node)) {
        case CSG_INSIDE: v = sign[arg] < 0; break;
        case CSG_OUTSIDE: v = sign[arg] > 0; break;
        case CSG_UNION: v = left || right; break;
        case CSG_INTERSECT: v = left && right; break;
        case CSG_DIFFERENCE: v = left && !right; break;
        case CSG_NOT: v = !left; break;
        }
        value[k - root] = (unsigned char)v;
    }
    int result = value[0];
    if (value != small)
        free(value);
    return result;
}
