/* implicits/scene_parse.c -- the scene language's front end: text to a scene (scene.h), and iacsg_expr_parse,
 * which is the same front end for a text without regions or surfaces.
 *
 *   text --parse.c--> AST --lower.c--> one shared DAG, and, through this file's hook, each declaration in source
 *   order: materials, solids (DAG nodes), regions' trees and surfaces' conditions (32-bit nodes, scene_add_tree)
 *   --> each solid's own iacsg_expr (its sub-DAG copied out and simplified)   |   a plain scene's final expression
 *
 * Solids: a `solid` declaration makes a named one; a region's or condition's operand that is not a solid's name
 * is an expression written inline and makes an unnamed one, unless an earlier solid has the same DAG node (the
 * DAG is hash-consed, so `sphere(1.2)` written twice, or a binding of it, is one solid). Every solid's index fits
 * the nodes' 29-bit operand. Solids that no region or surface uses are dropped at the end; the others keep their
 * order.
 */
#include "ast.h"
#include "expr_internal.h"
#include "lower.h"
#include "scene.h"
#include "suggest.h"
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The optional keywords of a material, after rgb(...): a new one is a row here and a field of scene_material. */
static const struct {
    const char *name;
    size_t offset; /* of its float in scene_material */
    float lo, hi;  /* the values allowed */
} material_keywords[] = {
    {"specular", offsetof(scene_material, specular), 0, 1},
    {"shininess", offsetof(scene_material, shininess), 0, 10000},
    {"reflect", offsetof(scene_material, reflect), 0, 1},
    {"opacity", offsetof(scene_material, opacity), 0, 1},
};
#define NKEYWORDS ((int)(sizeof material_keywords / sizeof material_keywords[0]))

typedef struct {
    iacsg_scene *s;
    const ast *a;
    const int *values;
    const name_table *names;
    iacsg_error *err;
    int *solid_node; /* solid -> its node in the shared DAG */
    int cap_solid_node;
    int *solid_of_node; /* shared DAG node -> the first solid that is it, or -1 */
    int nsolid_of_node;
    uint32_t *tree; /* the tree being built */
    int cap_tree;
    int *stack; /* (AST node, index of the parent whose right child it is, or -1) pairs */
    int cap_stack;
} builder;

static int out_of_memory(builder *b) {
    return iacsg_error_set(b->err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the scene"), -1;
}

/* Makes room for n ints in *p (capacity *cap); 0 when out of memory. */
static int reserve(void *p, int *cap, int n, size_t size) {
    if (n <= *cap)
        return 1;
    int c = *cap ? *cap : 64;
    while (c < n)
        c *= 2;
    void *q = realloc(*(void **)p, (size_t)c * size);
    if (!q)
        return 0;
    *(void **)p = q;
    *cap = c;
    return 1;
}

static int fail_at(builder *b, long tok, iacsg_status status, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int fail_at(builder *b, long tok, iacsg_status status, const char *fmt, ...) {
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    const token *t = &b->a->toks[tok];
    iacsg_error_set(b->err, status, t->line, t->column, "%s", msg);
    return -1;
}

/* The token where an operand's text starts (an operator's left operand comes first). */
static long first_token(const ast *a, int node) {
    while (a->nodes[node].kind == AST_BIN || a->nodes[node].kind == AST_BOOL)
        node = a->nodes[node].a;
    return a->nodes[node].tok;
}

/* A new solid (name NULL for an inline one) of the shared DAG's node, declared at token tok. */
static int add_solid(builder *b, const char *name, int node, long tok) {
    if ((uint32_t)b->s->nsolids >= CSG_ARG_MAX)
        return fail_at(b, tok, IACSG_ERR_LIMIT, "too many solids (at most %u)", (unsigned)CSG_ARG_MAX);
    if (!reserve(&b->solid_node, &b->cap_solid_node, b->s->nsolids + 1, sizeof(int)))
        return out_of_memory(b);
    if (node >= b->nsolid_of_node) {
        int n = b->nsolid_of_node;
        if (!reserve(&b->solid_of_node, &b->nsolid_of_node, node + 1, sizeof(int)))
            return out_of_memory(b);
        for (int k = n; k < b->nsolid_of_node; k++)
            b->solid_of_node[k] = -1;
    }
    int k = scene_add_solid(b->s, name, NULL, b->err);
    if (k < 0)
        return -1;
    b->s->solids[k].line = b->a->toks[tok].line;
    b->s->solids[k].column = b->a->toks[tok].column;
    b->solid_node[k] = node;
    if (b->solid_of_node[node] < 0)
        b->solid_of_node[node] = k;
    return k;
}

/* The solid of an operand of a region or condition, or of a surface's expression: a solid's name, else the
 * solid of the expression (an earlier one with the same DAG node, or a new inline one). */
static int operand_solid(builder *b, int node) {
    const ast_node *n = &b->a->nodes[node];
    if (n->kind == AST_NAME) {
        char name[LEX_MAX_NAME + 1];
        const name_entry *e = names_find(b->names, ast_token_text(b->a, n->tok, name, sizeof name));
        if (e && e->kind == NAME_SOLID)
            return e->index;
    }
    int d = b->values[node];
    if (d < b->nsolid_of_node && b->solid_of_node[d] >= 0)
        return b->solid_of_node[d];
    return add_solid(b, NULL, d, first_token(b->a, node));
}

/* Pushes (node, parent) on the stack. */
static int push(builder *b, int *top, int node, int parent) {
    if (!reserve(&b->stack, &b->cap_stack, *top + 2, sizeof(int)))
        return out_of_memory(b);
    b->stack[(*top)++] = node;
    b->stack[(*top)++] = parent;
    return 0;
}

/* The 32-bit tree (kernels/csg_node.h) of a region's boolean expression or a surface's condition rooted at AST
 * node root, added to the scene: its root's index in s->nodes, or -1. Depth first with an explicit stack: a node
 * is written, its right child pushed, then its left child, which is therefore written right after it. */
static int build_tree(builder *b, int root) {
    int top = 0, count = 0;
    if (push(b, &top, root, -1) < 0)
        return -1;
    while (top > 0) {
        int parent = b->stack[--top], i = b->stack[--top];
        const ast_node *n = &b->a->nodes[i];
        if (!reserve(&b->tree, &b->cap_tree, count + 1, sizeof(uint32_t)))
            return out_of_memory(b);
        int k = count++;
        if (parent >= 0) /* the right child: its index is the parent's operand */
            b->tree[parent] = CSG_NODE(CSG_NODE_OP(b->tree[parent]), (uint32_t)k);
        int op = -1, solid = -1;
        switch (n->kind) {
        case AST_BOOL: op = n->op == '|' ? CSG_UNION : n->op == '&' ? CSG_INTERSECT : CSG_DIFFERENCE; break;
        case AST_COND: op = n->op == '|' ? CSG_UNION : CSG_INTERSECT; break;
        case AST_NOT: op = CSG_NOT; break;
        case AST_CMP:
            op = n->op == '<' ? CSG_INSIDE : CSG_OUTSIDE;
            solid = operand_solid(b, n->a);
            break;
        default: /* an operand of a region */
            op = CSG_INSIDE;
            solid = operand_solid(b, i);
            break;
        }
        if (op <= CSG_OUTSIDE && solid < 0)
            return -1;
        b->tree[k] = CSG_NODE(op, op <= CSG_OUTSIDE ? (uint32_t)solid : 0u);
        if (op == CSG_NOT || op >= CSG_UNION) {
            if ((op != CSG_NOT && push(b, &top, n->b, k) < 0) || push(b, &top, n->a, -1) < 0)
                return -1;
        }
    }
    return scene_add_tree(b->s, b->tree, count, b->err);
}

/* The material named at token tok (-1 for none: the palette). */
static int material_ref(builder *b, long tok) {
    if (tok < 0)
        return -1;
    char name[LEX_MAX_NAME + 1];
    ast_token_text(b->a, tok, name, sizeof name);
    const name_entry *e = names_find(b->names, name);
    if (e && e->kind == NAME_MATERIAL)
        return e->index;
    if (e)
        return fail_at(b, tok, IACSG_ERR_NAME, "'%s' is a %s, not a material", name, name_kind_word(e->kind));
    int later = ast_declaration_line(b->a, name, tok);
    if (later)
        return fail_at(b, tok, IACSG_ERR_NAME, "'%s' is used before its declaration (line %d)", name, later);
    suggestion s;
    suggest_init(&s, name);
    for (int i = 0; i < b->names->nslots; i++)
        if (b->names->slots[i].name[0] && b->names->slots[i].kind == NAME_MATERIAL)
            suggest_offer(&s, b->names->slots[i].name);
    if (s.best)
        return fail_at(b, tok, IACSG_ERR_NAME, "unknown material '%s', did you mean '%s'?", name, s.best);
    return fail_at(b, tok, IACSG_ERR_NAME, "unknown material '%s'", name);
}

/* The value of a material's number (AST_NUM or AST_NEG of one) and its text as written. */
static double number_value(builder *b, int node, char *text, size_t size) {
    const ast_node *n = &b->a->nodes[node];
    int negative = n->kind == AST_NEG;
    char digits[LEX_MAX_NUMBER + 1];
    ast_token_text(b->a, negative ? b->a->nodes[n->a].tok : n->tok, digits, sizeof digits);
    snprintf(text, size, "%s%s", negative ? "-" : "", digits);
    double v = strtod(digits, NULL);
    return negative ? -v : v;
}

static int declare_material(builder *b, const ast_node *n, const char *name) {
    float rgb[3];
    char text[LEX_MAX_NUMBER + 2];
    for (int k = 0; k < 3; k++) {
        int v = b->a->args[n->first + k].value;
        double c = number_value(b, v, text, sizeof text);
        if (!(c >= 0 && c <= 1))
            return fail_at(b, b->a->nodes[v].tok, IACSG_ERR_ARG, "rgb component %s is outside [0, 1]", text);
        rgb[k] = (float)c;
    }
    int m = scene_add_material(b->s, name, rgb, b->err);
    if (m < 0)
        return -1;
    long given[NKEYWORDS];
    for (int j = 0; j < NKEYWORDS; j++)
        given[j] = -1;
    for (int k = 3; k < n->nargs; k++) {
        const ast_arg *g = &b->a->args[n->first + k];
        char word[LEX_MAX_NAME + 1];
        ast_token_text(b->a, g->keyword, word, sizeof word);
        int j = 0;
        while (j < NKEYWORDS && strcmp(material_keywords[j].name, word) != 0)
            j++;
        if (j == NKEYWORDS) {
            suggestion s;
            suggest_init(&s, word);
            for (j = 0; j < NKEYWORDS; j++)
                suggest_offer(&s, material_keywords[j].name);
            if (s.best)
                return fail_at(b, g->keyword, IACSG_ERR_NAME, "unknown material keyword '%s', did you mean '%s'?",
                               word, s.best);
            char known[160] = "";
            for (j = 0; j < NKEYWORDS; j++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", j ? ", " : "",
                         material_keywords[j].name);
            return fail_at(b, g->keyword, IACSG_ERR_NAME, "unknown material keyword '%s' (%s)", word, known);
        }
        if (given[j] >= 0)
            return fail_at(b, g->keyword, IACSG_ERR_ARG, "'%s' is given twice for material '%s'", word, name);
        given[j] = g->keyword;
        double v = number_value(b, g->value, text, sizeof text);
        if (!(v >= material_keywords[j].lo && v <= material_keywords[j].hi))
            return fail_at(b, b->a->nodes[g->value].tok, IACSG_ERR_ARG, "%s %s is outside [%g, %g]", word, text,
                           material_keywords[j].lo, material_keywords[j].hi);
        *(float *)((char *)&b->s->materials[m] + material_keywords[j].offset) = (float)v;
    }
    return m;
}

/* A light: its position or direction (not 0 for a direction), and its keyword intensity (>= 0, default 1). */
static int declare_light(builder *b, const ast_node *n, long keyword) {
    scene_light light = {n->op == 'd', {0, 0, 0}, 1};
    char text[LEX_MAX_NUMBER + 2], word[LEX_MAX_NAME + 1];
    if (b->s->nlights == SCENE_MAX_LIGHTS)
        return fail_at(b, keyword, IACSG_ERR_ARG, "a scene has at most %d lights", SCENE_MAX_LIGHTS);
    for (int k = 0; k < 3; k++)
        light.xyz[k] = number_value(b, b->a->args[n->first + k].value, text, sizeof text);
    if (light.dir && light.xyz[0] == 0 && light.xyz[1] == 0 && light.xyz[2] == 0)
        return fail_at(b, b->a->nodes[b->a->args[n->first].value].tok, IACSG_ERR_ARG,
                       "a light's direction must not be 0, 0, 0");
    for (int k = 3; k < n->nargs; k++) {
        const ast_arg *g = &b->a->args[n->first + k];
        ast_token_text(b->a, g->keyword, word, sizeof word);
        if (strcmp(word, "intensity") != 0)
            return fail_at(b, g->keyword, IACSG_ERR_NAME, "unknown light keyword '%s' (intensity)", word);
        if (k > 3)
            return fail_at(b, g->keyword, IACSG_ERR_ARG, "'intensity' is given twice");
        light.intensity = number_value(b, g->value, text, sizeof text);
        if (!(light.intensity >= 0 && light.intensity <= 1e6))
            return fail_at(b, b->a->nodes[g->value].tok, IACSG_ERR_ARG, "light intensity %s is outside [0, 1e6]",
                           text);
    }
    return scene_add_light(b->s, &light, b->err);
}

/* lower_hooks.declare: builds one declaration. */
static int declare(void *ctx, const ast *a, int node, const int *values, const name_table *names,
                   iacsg_error *err) {
    builder *b = ctx;
    b->a = a;
    b->values = values;
    b->names = names;
    b->err = err;
    const ast_node *n = &a->nodes[node];
    long keyword = n->tok - 1;
    char name[LEX_MAX_NAME + 1];
    ast_token_text(a, n->tok, name, sizeof name);
    int index;
    switch (n->kind) {
    case AST_MATERIAL: return declare_material(b, n, name);
    case AST_LIGHT: return declare_light(b, n, keyword);
    case AST_SOLID: return add_solid(b, name, values[n->a], keyword);
    case AST_REGION: {
        int tree = build_tree(b, n->a), material = tree < 0 ? -1 : material_ref(b, n->first);
        if (tree < 0 || (n->first >= 0 && material < 0))
            return -1;
        index = scene_add_region(b->s, name, tree, material, err);
        break;
    }
    default: { /* AST_SURFACE */
        int solid = operand_solid(b, n->a);
        int cond = solid < 0 || n->b < 0 ? -1 : build_tree(b, n->b);
        int material = solid < 0 || (n->b >= 0 && cond < 0) ? -1 : material_ref(b, n->first);
        if (solid < 0 || (n->b >= 0 && cond < 0) || (n->first >= 0 && material < 0))
            return -1;
        index = scene_add_surface(b->s, name, solid, cond, material, err);
        break;
    }
    }
    if (index >= 0) {
        b->s->items[index].line = a->toks[keyword].line;
        b->s->items[index].column = a->toks[keyword].column;
    } else if (err && err->line == 0) { /* the builder's refusal (a condition too large) has no place */
        err->line = a->toks[keyword].line;
        err->column = a->toks[keyword].column;
    }
    return index;
}

/* Drops the solids that no region or surface uses (those used only in other solids' expressions, or not at
 * all): the renderer finds segments for every solid of the scene. The others keep their order. */
static iacsg_status drop_unused_solids(builder *b, iacsg_error *err) {
    iacsg_scene *s = b->s;
    int *index = calloc((size_t)s->nsolids + 1, sizeof *index); /* 1 + the new index, 0 while unused */
    if (!index)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory building the scene");
    /* every node belongs to a region's tree or a surface's condition */
    for (int k = 0; k < s->nnodes; k++)
        if (CSG_NODE_OP(s->nodes[k]) <= CSG_OUTSIDE)
            index[CSG_NODE_ARG(s->nodes[k])] = 1;
    for (int k = 0; k < s->nitems; k++)
        if (s->items[k].kind == SCENE_SURFACE)
            index[s->items[k].solid] = 1;
    int n = 0;
    for (int k = 0; k < s->nsolids; k++) {
        if (!index[k]) {
            free(s->solids[k].name);
            continue;
        }
        s->solids[n] = s->solids[k];
        b->solid_node[n] = b->solid_node[k];
        index[k] = ++n;
    }
    s->nsolids = n;
    for (int k = 0; k < s->nnodes; k++)
        if (CSG_NODE_OP(s->nodes[k]) <= CSG_OUTSIDE)
            s->nodes[k] = CSG_NODE(CSG_NODE_OP(s->nodes[k]), (uint32_t)index[CSG_NODE_ARG(s->nodes[k])] - 1);
    for (int k = 0; k < s->nitems; k++)
        if (s->items[k].kind == SCENE_SURFACE)
            s->items[k].solid = index[s->items[k].solid] - 1;
    free(index);
    return IACSG_OK;
}

/* Compiles every solid used out of the shared DAG d, or, in a plain scene (no items), makes d the final
 * expression's and drops the solids (there they are bindings). */
static iacsg_status compile(builder *b, dag *d, int root, const char *name, iacsg_error *err) {
    iacsg_scene *s = b->s;
    if (s->nitems == 0) {
        for (int k = 0; k < s->nsolids; k++)
            free(s->solids[k].name);
        s->nsolids = 0;
        return expr_from_dag(d, root, name, 1, &s->expr, err);
    }
    iacsg_status st = drop_unused_solids(b, err);
    for (int k = 0; k < s->nsolids && st == IACSG_OK; k++) {
        st = expr_from_dag(d, b->solid_node[k], name, 0, &s->solids[k].expr, err);
    }
    return st;
}

/* The scene of text; with expression_only, a region or surface is an error (iacsg_expr_parse). */
static iacsg_status scene_parse(const char *text, const char *name, int expression_only, iacsg_scene **out,
                                iacsg_error *err) {
    *out = NULL;
    ast a;
    iacsg_status st = parse(text, &a, err);
    if (st != IACSG_OK)
        return st;
    for (int i = 0; expression_only && i < a.count; i++)
        if (a.nodes[i].kind == AST_REGION || a.nodes[i].kind == AST_SURFACE) {
            const token *t = &a.toks[a.nodes[i].tok - 1];
            st = iacsg_error_set(err, IACSG_ERR_SYNTAX, t->line, t->column,
                                 "a %s makes a multi-material scene, not one expression (such scenes are read "
                                 "from files, by iacsg_scene_parse)",
                                 a.nodes[i].kind == AST_REGION ? "region" : "surface");
            ast_free(&a);
            return st;
        }
    builder b = {scene_create(), &a, NULL, NULL, err, NULL, 0, NULL, 0, NULL, 0, NULL, 0};
    dag d;
    dag_init(&d);
    lower_hooks hooks = {&b, declare};
    int root = -1;
    st = b.s ? lower(&a, &d, &hooks, &root, err) : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    ast_free(&a);
    if (st == IACSG_OK)
        st = compile(&b, &d, root, name, err);
    dag_free(&d);
    free(b.solid_node);
    free(b.solid_of_node);
    free(b.tree);
    free(b.stack);
    if (st != IACSG_OK) {
        iacsg_scene_destroy(b.s);
        return st;
    }
    *out = b.s;
    return IACSG_OK;
}

iacsg_status iacsg_scene_parse(const char *text, const char *name, iacsg_scene **out, iacsg_error *err) {
    iacsg_error local;
    return scene_parse(text, name ? name : "<scene>", 0, out, err ? err : &local);
}

iacsg_status iacsg_expr_parse(const char *text, const char *name, iacsg_expr **out, iacsg_error *err) {
    iacsg_error local;
    iacsg_scene *s;
    *out = NULL;
    iacsg_status st = scene_parse(text, name ? name : "<expr>", 1, &s, err ? err : &local);
    if (st != IACSG_OK)
        return st;
    *out = s->expr;
    s->expr = NULL;
    iacsg_scene_destroy(s);
    return IACSG_OK;
}
