/* implicits/lower.c -- stage 3: AST to DAG (see lower.h). The AST array is walked in order (children before
 * parents, statements in source order), so this is a loop. Library texts (library.c) are lowered the same way,
 * once per compile, with their parameters as OP_PARAM leaves; a call substitutes the arguments. A scene's names
 * (bindings and declarations) share one table (names.c); each declaration is handed to the front end's hook
 * (scene_parse.c) when its expressions are lowered. */
#include "lower.h"
#include "library.h"
#include "names.h"
#include "suggest.h"
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LIB_MAX_PARAMS 8

typedef struct {
    int state; /* 0 not lowered yet, 1 being lowered, 2 ready */
    int nparams;
    char names[LIB_MAX_PARAMS][LEX_MAX_NAME + 1];
    int defaults[LIB_MAX_PARAMS]; /* -1: required */
    int body[3];
} lib_lowered;

typedef struct {
    dag *d;
    lib_lowered *lib; /* lib_count entries, shared by all the texts lowered in one compile */
    iacsg_error *err;
} lower_env;

/* The names a user cannot bind: they would shadow the language. */
static const char *const csg_names[] = {"union", "intersection", "difference"};
static const char *const reserved_names[] = {"x",        "y",     "z",     "t",      "pi",      "e",
                                             "material", "solid", "region", "surface", "where", "color"};
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

static int find_op(const char *name) {
    for (int op = 0; op < OP_COUNT; op++)
        if (dag_ops[op].name[0] && strcmp(dag_ops[op].name, name) == 0)
            return op;
    return -1;
}
static int find_csg(const char *name) {
    for (int i = 0; i < COUNT(csg_names); i++)
        if (strcmp(csg_names[i], name) == 0)
            return i;
    return -1;
}
static int is_builtin(const char *name) {
    for (int i = 0; i < COUNT(reserved_names); i++)
        if (strcmp(reserved_names[i], name) == 0)
            return 1;
    return find_op(name) >= 0 || find_csg(name) >= 0 || lib_find(name) != NULL;
}

/* Everything one text's lowering needs. */
typedef struct {
    lower_env *env;
    const ast *a;
    const char *what; /* "" for user text, else "in built-in 'torus': " */
    char (*params)[LEX_MAX_NAME + 1];
    int nparams;
    name_table names;          /* the scene's bindings and declarations */
    const lower_hooks *hooks;  /* NULL for the library's texts */
    int *values;               /* AST node -> DAG node (-1 for nodes that are not values) */
} lowering;

static int fail(lowering *l, long tok, iacsg_status status, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int fail(lowering *l, long tok, iacsg_status status, const char *fmt, ...) {
    const token *t = &l->a->toks[tok];
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    /* errors inside the library's own texts have no place in the user's text */
    iacsg_error_set(l->env->err, status, l->what[0] ? 0 : t->line, l->what[0] ? 0 : t->column, "%s%s", l->what, msg);
    return -1;
}

static const char *lib_kind_name(lib_kind k) {
    return k == LIB_PRIMITIVE ? "primitive" : k == LIB_BLEND ? "blend" : "transform";
}

/* "unknown primitive 'tours', did you mean 'torus'?"; an operand of a region or condition is an unknown solid. */
static int fail_unknown(lowering *l, long tok, const char *name, int called, int operand) {
    int later = called || l->what[0] ? 0 : ast_declaration_line(l->a, name, tok);
    if (later)
        return fail(l, tok, IACSG_ERR_NAME, "'%s' is used before its declaration (line %d)", name, later);
    suggestion s;
    suggest_init(&s, name);
    for (int op = 0; op < OP_COUNT; op++)
        if (dag_ops[op].name[0])
            suggest_offer(&s, dag_ops[op].name);
    for (int i = 0; i < COUNT(csg_names); i++)
        suggest_offer(&s, csg_names[i]);
    for (int i = 0; i < lib_count; i++)
        suggest_offer(&s, lib_entries[i].name);
    if (!called) {
        for (int i = 0; i < 6; i++)
            suggest_offer(&s, reserved_names[i]);
        for (int i = 0; i < l->nparams; i++)
            suggest_offer(&s, l->params[i]);
        for (int i = 0; i < l->names.nslots; i++) {
            const name_entry *n = &l->names.slots[i];
            if (n->name[0] && (n->kind == NAME_BINDING || n->kind == NAME_SOLID))
                suggest_offer(&s, n->name);
        }
    }
    if (!s.best)
        return fail(l, tok, IACSG_ERR_NAME, "unknown %s '%s'", called ? "function" : operand ? "solid" : "name", name);
    const lib_entry *e = lib_find(s.best);
    const name_entry *n = names_find(&l->names, s.best);
    const char *kind = e ? lib_kind_name(e->kind)
                       : find_op(s.best) >= 0 || find_csg(s.best) >= 0 ? "function"
                       : (n && n->kind == NAME_SOLID) || operand        ? "solid"
                                                                        : "name";
    return fail(l, tok, IACSG_ERR_NAME, "unknown %s '%s', did you mean '%s'?", kind, name, s.best);
}

static int lower_text(lower_env *env, const char *text, const char *what, char (*params)[LEX_MAX_NAME + 1],
                      int nparams);

/* Lowers a library entry's signature (its parameters and defaults) and bodies, once. */
static int load_lib(lower_env *env, const lib_entry *e, lib_lowered *L) {
    if (L->state == 2)
        return 0;
    if (L->state == 1)
        return iacsg_error_set(env->err, IACSG_ERR_SYNTAX, 0, 0, "built-in '%s' refers to itself", e->name), -1;
    L->state = 1;
    char what[128];
    snprintf(what, sizeof what, "in built-in '%s': ", e->name);
    ast sig;
    if (parse(e->signature, &sig, env->err) != IACSG_OK)
        return -1;
    const ast_node *call = &sig.nodes[sig.root];
    if (call->kind != AST_CALL || call->nargs > LIB_MAX_PARAMS) {
        ast_free(&sig);
        return iacsg_error_set(env->err, IACSG_ERR_SYNTAX, 0, 0, "built-in '%s' has a bad signature", e->name), -1;
    }
    int ok = 1;
    L->nparams = call->nargs;
    for (int k = 0; ok && k < L->nparams; k++) {
        const ast_arg *g = &sig.args[call->first + k];
        long name_tok = g->keyword >= 0 ? g->keyword : sig.nodes[g->value].tok;
        ast_token_text(&sig, name_tok, L->names[k], sizeof L->names[k]);
        L->defaults[k] = -1;
        if (g->keyword >= 0) {
            /* the default is an expression in the earlier parameters: lower its source text alone */
            const token *first = &sig.toks[g->keyword + 2];
            long end = g->keyword + 2;
            int depth = 0;
            while (sig.toks[end].kind != TOK_END && !(depth == 0 && sig.toks[end].kind == TOK_PUNCT &&
                                                      (sig.toks[end].ch == ',' || sig.toks[end].ch == ')'))) {
                depth += sig.toks[end].ch == '(' ? 1 : sig.toks[end].ch == ')' ? -1 : 0;
                end++;
            }
            char text[256];
            size_t len = sig.toks[end].start - first->start;
            snprintf(text, sizeof text, "%.*s", (int)len, e->signature + first->start);
            L->defaults[k] = lower_text(env, text, what, L->names, k);
            ok = L->defaults[k] >= 0;
        }
    }
    ast_free(&sig);
    if (!ok)
        return -1;
    int nbodies = e->kind == LIB_TRANSFORM ? 3 : 1;
    for (int i = 0; i < nbodies; i++) {
        size_t size = strlen(e->prelude) + strlen(e->body[i]) + 2;
        char *text = malloc(size);
        if (!text)
            return iacsg_error_set(env->err, IACSG_ERR_NOMEM, 0, 0, "out of memory"), -1;
        snprintf(text, size, "%s\n%s", e->prelude, e->body[i]);
        L->body[i] = lower_text(env, text, what, L->names, L->nparams);
        free(text);
        if (L->body[i] < 0)
            return -1;
    }
    L->state = 2;
    return 0;
}

/* The call name(args) of a library entry (call is NULL for a bare name at token tok): binds the arguments to
 * the parameters and substitutes. */
static int call_lib(lowering *l, const ast_node *call, long tok, const char *name, const lib_entry *e) {
    lower_env *env = l->env;
    lib_lowered *L = &env->lib[e - lib_entries];
    if (load_lib(env, e, L) < 0)
        return -1;
    int params[LIB_MAX_PARAMS];
    for (int k = 0; k < L->nparams; k++)
        params[k] = -1;
    char kw[LEX_MAX_NAME + 1];
    for (int i = 0; call && i < call->nargs; i++) {
        const ast_arg *g = &l->a->args[call->first + i];
        int k = i;
        if (g->keyword >= 0) {
            ast_token_text(l->a, g->keyword, kw, sizeof kw);
            for (k = 0; k < L->nparams && strcmp(L->names[k], kw) != 0; k++)
                ;
            if (k == L->nparams) {
                suggestion s;
                suggest_init(&s, kw);
                for (int j = 0; j < L->nparams; j++)
                    suggest_offer(&s, L->names[j]);
                if (s.best)
                    return fail(l, g->keyword, IACSG_ERR_NAME, "'%s' has no parameter '%s', did you mean '%s'?",
                                name, kw, s.best);
                return fail(l, g->keyword, IACSG_ERR_NAME, "'%s' has no parameter '%s'", name, kw);
            }
            if (params[k] >= 0)
                return fail(l, g->keyword, IACSG_ERR_ARITY, "'%s' is given twice in the call of '%s'", kw, name);
        } else if (i > 0 && l->a->args[call->first + i - 1].keyword >= 0) {
            return fail(l, call->tok, IACSG_ERR_SYNTAX, "in the call of '%s': a positional argument follows a keyword",
                        name);
        } else if (i >= L->nparams) {
            return fail(l, call->tok, IACSG_ERR_ARITY, "'%s' takes at most %d argument%s", name, L->nparams,
                        L->nparams == 1 ? "" : "s");
        }
        params[k] = l->values[g->value];
    }
    static const int same[4] = {-1, -1, -1, -1};
    for (int k = 0; k < L->nparams; k++)
        if (params[k] < 0) {
            if (L->defaults[k] < 0)
                return fail(l, tok, IACSG_ERR_ARITY, "'%s' needs its argument '%s'", name, L->names[k]);
            params[k] = dag_substitute(env->d, L->defaults[k], env->d, same, params, k, env->err);
            if (params[k] < 0)
                return -1;
        }
    if (e->kind != LIB_TRANSFORM)
        return dag_substitute(env->d, L->body[0], env->d, same, params, L->nparams, env->err);
    int coords[4] = {-1, -1, -1, -1};
    for (int i = 0; i < 3; i++)
        if ((coords[i] = dag_substitute(env->d, L->body[i], env->d, same, params, L->nparams, env->err)) < 0)
            return -1;
    return dag_substitute(env->d, params[0], env->d, coords, NULL, 0, env->err);
}

/* union / intersection / difference and the n-ary functions: a left fold. */
static int fold(lowering *l, const ast_node *call, int op, int negate_rest) {
    dag *d = l->env->d;
    int r = l->values[l->a->args[call->first].value];
    for (int i = 1; i < call->nargs && r >= 0; i++) {
        int b = l->values[l->a->args[call->first + i].value];
        if (negate_rest && (b = dag_add(d, OP_NEG, b, -1, 0, l->env->err)) < 0)
            return -1;
        r = dag_add(d, op, r, b, 0, l->env->err);
    }
    return r;
}

static int lower_call(lowering *l, const ast_node *n) {
    char name[LEX_MAX_NAME + 1];
    ast_token_text(l->a, n->tok, name, sizeof name);
    const lib_entry *e = lib_find(name);
    if (e)
        return call_lib(l, n, n->tok, name, e);
    int op = find_op(name), csg = find_csg(name);
    if (op < 0 && csg < 0) {
        for (int i = 0; i < l->nparams; i++)
            if (strcmp(l->params[i], name) == 0)
                return fail(l, n->tok, IACSG_ERR_NAME, "'%s' is not a function", name);
        const name_entry *b = names_find(&l->names, name);
        if (b)
            return fail(l, n->tok, IACSG_ERR_NAME, "'%s' is a %s, not a function", name, name_kind_word(b->kind));
        if (is_builtin(name))
            return fail(l, n->tok, IACSG_ERR_NAME, "'%s' is not a function", name);
        return fail_unknown(l, n->tok, name, 1, 0);
    }
    for (int i = 0; i < n->nargs; i++)
        if (l->a->args[n->first + i].keyword >= 0)
            return fail(l, l->a->args[n->first + i].keyword, IACSG_ERR_NAME, "'%s' takes no keyword arguments", name);
    int arity = csg >= 0 ? 1 : dag_ops[op].arity, nary = csg >= 0 || dag_ops[op].nary;
    if (nary ? n->nargs < arity : n->nargs != arity) {
        return fail(l, n->tok, IACSG_ERR_ARITY, "'%s' takes %s%d argument%s, got %d", name, nary ? "at least " : "",
                    arity, arity == 1 ? "" : "s", n->nargs);
    }
    if (csg >= 0)
        return fold(l, n, csg == 0 ? OP_MIN : OP_MAX, csg == 2);
    if (nary)
        return fold(l, n, op, 0);
    int a = l->values[l->a->args[n->first].value];
    int b = arity > 1 ? l->values[l->a->args[n->first + 1].value] : -1;
    return dag_add(l->env->d, op, a, b, 0, l->env->err);
}

static int lower_name(lowering *l, const ast_node *n) {
    char name[LEX_MAX_NAME + 1];
    ast_token_text(l->a, n->tok, name, sizeof name);
    dag *d = l->env->d;
    for (int i = 0; i < l->nparams; i++)
        if (strcmp(l->params[i], name) == 0)
            return dag_add(d, OP_PARAM, -1, -1, i, l->env->err);
    const name_entry *b = names_find(&l->names, name);
    if (b && (b->kind == NAME_BINDING || b->kind == NAME_SOLID))
        return b->node;
    if (b)
        return fail(l, n->tok, IACSG_ERR_NAME, "'%s' is a %s, not %s", name, name_kind_word(b->kind),
                    n->op == AST_OPERAND ? "a solid" : "an expression");
    static const char *const leaves[] = {"x", "y", "z", "t", "pi", "e"};
    static const int leaf_ops[] = {OP_X, OP_Y, OP_Z, OP_T, OP_PI, OP_E};
    for (int i = 0; i < COUNT(leaves); i++)
        if (strcmp(leaves[i], name) == 0)
            return dag_add(d, leaf_ops[i], -1, -1, 0, l->env->err);
    const lib_entry *e = lib_find(name);
    if (e && e->kind == LIB_PRIMITIVE)
        return call_lib(l, NULL, n->tok, name, e);
    if (e || find_op(name) >= 0 || find_csg(name) >= 0)
        return fail(l, n->tok, IACSG_ERR_ARITY, "'%s' needs arguments: write %s(...)", name, name);
    if (is_builtin(name))
        return fail(l, n->tok, IACSG_ERR_NAME, "'%s' is reserved for multi-material scenes", name);
    return fail_unknown(l, n->tok, name, 0, n->op == AST_OPERAND);
}

/* Enters the name of a binding or declaration (node: its DAG node for a binding or solid, index: its index in
 * the scene) into the namespace; 0 with err set when it is built in or taken. */
static int declare_name(lowering *l, const ast_node *n, name_kind kind, int node, int index) {
    char name[LEX_MAX_NAME + 1];
    ast_token_text(l->a, n->tok, name, sizeof name);
    if (is_builtin(name))
        return kind == NAME_BINDING ? fail(l, n->tok, IACSG_ERR_NAME, "cannot bind '%s': it is a built-in name", name)
                                    : fail(l, n->tok, IACSG_ERR_NAME, "cannot name a %s '%s': it is a built-in name",
                                           name_kind_word(kind), name);
    const name_entry *b = names_find(&l->names, name);
    if (b && b->kind == NAME_BINDING)
        return fail(l, n->tok, IACSG_ERR_NAME, "'%s' is already bound (line %d)", name, b->line);
    if (b)
        return fail(l, n->tok, IACSG_ERR_NAME, "'%s' is already declared as a %s (line %d)", name,
                    name_kind_word(b->kind), b->line);
    if (!names_add(&l->names, name, kind, node, index, l->a->toks[n->tok].line))
        return iacsg_error_set(l->env->err, IACSG_ERR_NOMEM, 0, 0, "out of memory"), -1;
    return 0;
}

static int lower_bind(lowering *l, const ast_node *n) {
    return declare_name(l, n, NAME_BINDING, l->values[n->a], -1) < 0 ? -1 : l->values[n->a];
}

/* A material, light, solid, region or surface: its name is checked, the front end's hook builds it (in source order,
 * after its expressions are lowered), then the name is entered with the index the hook gave. */
static int lower_declaration(lowering *l, int i) {
    static const name_kind kinds[] = {[AST_MATERIAL] = NAME_MATERIAL, [AST_LIGHT] = NAME_LIGHT,
                                      [AST_SOLID] = NAME_SOLID,       [AST_REGION] = NAME_REGION,
                                      [AST_SURFACE] = NAME_SURFACE};
    const ast_node *n = &l->a->nodes[i];
    char name[LEX_MAX_NAME + 1];
    if (!l->hooks)
        return fail(l, n->tok, IACSG_ERR_SYNTAX, "'%s' declares nothing here",
                    ast_token_text(l->a, n->tok - 1, name, sizeof name));
    if (is_builtin(ast_token_text(l->a, n->tok, name, sizeof name)) || names_find(&l->names, name))
        return declare_name(l, n, kinds[n->kind], -1, -1);
    int index = l->hooks->declare(l->hooks->ctx, l->a, i, l->values, &l->names, l->env->err);
    if (index < 0)
        return -1;
    int node = n->kind == AST_SOLID ? l->values[n->a] : -1;
    return declare_name(l, n, kinds[n->kind], node, index) < 0 ? -1 : node >= 0 ? node : index;
}

/* Lowers a's nodes in order; *root is the final expression's node (-1 in a scene without one). 0, or -1 with
 * err set. */
static int lower_ast(lower_env *env, const ast *a, const char *what, char (*params)[LEX_MAX_NAME + 1], int nparams,
                     const lower_hooks *hooks, int *root) {
    static const int bin_ops[] = {['+'] = OP_ADD, ['-'] = OP_SUB, ['*'] = OP_MUL, ['/'] = OP_DIV,
                                  ['^'] = OP_POW, ['|'] = OP_MIN, ['&'] = OP_MAX,  ['\\'] = OP_MAX};
    lowering l = {env, a, what, params, nparams, {NULL, 0, 0}, hooks, malloc((size_t)a->count * sizeof(int))};
    int r = 0;
    if (!l.values)
        return iacsg_error_set(env->err, IACSG_ERR_NOMEM, 0, 0, "out of memory"), -1;
    for (int i = 0; i < a->count && r >= 0; i++) {
        const ast_node *n = &a->nodes[i];
        char num[LEX_MAX_NUMBER + 1];
        switch (n->kind) {
        case AST_NUM:
            r = dag_add_decimal(env->d, ast_token_text(a, n->tok, num, sizeof num), env->err);
            break;
        case AST_NAME: r = lower_name(&l, n); break;
        case AST_CALL: r = lower_call(&l, n); break;
        case AST_BIND: r = lower_bind(&l, n); break;
        case AST_NEG: r = dag_add(env->d, OP_NEG, l.values[n->a], -1, 0, env->err); break;
        case AST_BIN: {
            int b = l.values[n->b];
            if (n->op == '\\') /* a \ b = max(a, -b) */
                b = dag_add(env->d, OP_NEG, b, -1, 0, env->err);
            r = b < 0 ? -1 : dag_add(env->d, bin_ops[(unsigned char)n->op], l.values[n->a], b, 0, env->err);
            break;
        }
        case AST_MATERIAL:
        case AST_LIGHT:
        case AST_SOLID:
        case AST_REGION:
        case AST_SURFACE: r = lower_declaration(&l, i); break;
        case AST_BOOL: /* the structure of regions and conditions: the hook reads it from the AST */
        case AST_COND:
        case AST_NOT:
        case AST_CMP: r = 0; break;
        }
        l.values[i] = n->kind <= AST_BIND || n->kind == AST_SOLID ? r : -1;
    }
    if (r >= 0)
        *root = a->root >= 0 ? l.values[a->root] : -1;
    free(l.values);
    names_free(&l.names);
    return r < 0 ? -1 : 0;
}

static int lower_text(lower_env *env, const char *text, const char *what, char (*params)[LEX_MAX_NAME + 1],
                      int nparams) {
    ast a;
    if (parse(text, &a, env->err) != IACSG_OK)
        return -1;
    int root = -1;
    int r = lower_ast(env, &a, what, params, nparams, NULL, &root);
    ast_free(&a);
    return r < 0 ? -1 : root;
}

iacsg_status lower(const ast *a, dag *d, const lower_hooks *hooks, int *root, iacsg_error *err) {
    lib_lowered *lib = calloc((size_t)lib_count, sizeof *lib);
    if (!lib)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    lower_env env = {d, lib, err};
    int r = lower_ast(&env, a, "", NULL, 0, hooks, root);
    free(lib);
    return r < 0 ? err->status : IACSG_OK;
}
