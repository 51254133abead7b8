/* implicits/expr.c -- the public API of expr.h: compiles a lowered DAG (simplify, the tape), emits, evaluates on
 * the host. Parsing text (iacsg_expr_parse) is in scene_parse.c, bounds in bounds.c. */
#include "expr_internal.h"
#include "ast.h"
#include "emit.h"
#include "eval.h"
#include "simplify.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

iacsg_status expr_from_dag(dag *raw, int root, const char *name, int take, iacsg_expr **out, iacsg_error *err) {
    *out = NULL;
    iacsg_expr *e = calloc(1, sizeof *e);
    if (!e)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    dag_init(&e->raw);
    dag_init(&e->simple);
    e->name = malloc(strlen(name) + 1);
    if (e->name)
        strcpy(e->name, name);
    if (take) {
        dag_free(&e->raw);
        e->raw = *raw;
        e->raw_root = root;
        dag_init(raw);
    } else {
        static const int same[4] = {-1, -1, -1, -1};
        e->raw_root = e->name ? dag_substitute(raw, root, &e->raw, same, NULL, 0, err) : -1;
    }
    if (e->name && e->raw_root >= 0)
        e->root = simplify(&e->raw, e->raw_root, &e->simple, err);
    if (!e->name || e->raw_root < 0 || e->root < 0 || (e->count = dag_reachable(&e->simple, e->root, &e->order)) < 0) {
        iacsg_status st = e->name && (e->raw_root < 0 || e->root < 0)
                              ? err->status
                              : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
        iacsg_expr_destroy(e);
        return st;
    }
    *out = e;
    return IACSG_OK;
}

void iacsg_expr_destroy(iacsg_expr *e) {
    if (!e)
        return;
    dag_free(&e->raw);
    dag_free(&e->simple);
    free(e->order);
    free(e->name);
    free(e);
}

iacsg_status iacsg_expr_emit_cl(const iacsg_expr *e, const char *prefix, char **source, iacsg_error *err) {
    return emit_cl(&e->simple, e->root, prefix, 0, source, err);
}

int iacsg_expr_uses_time(const iacsg_expr *e) {
    for (int k = 0; k < e->count; k++)
        if (e->simple.nodes[e->order[k]].op == OP_T)
            return 1;
    return 0;
}

iacsg_status iacsg_expr_eval_box(const iacsg_expr *e, int fp64, const double lo[3], const double hi[3], double t,
                                 double out[2], iacsg_error *err) {
    double vars[8] = {lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], t, t};
    return iacsg_expr_eval_vars(e, fp64, vars, out, err);
}

iacsg_status iacsg_expr_eval_vars(const iacsg_expr *e, int fp64, const double vars[8], double out[2],
                                  iacsg_error *err) {
    void *scratch = malloc(eval_scratch_size(e->root));
    if (!scratch)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    (fp64 ? eval_dag_f64 : eval_dag_f32)(&e->simple, e->order, e->count, vars, scratch, out);
    free(scratch);
    return IACSG_OK;
}

char *iacsg_expr_dump(const char *text, const char *stage, iacsg_error *err) {
    ast a;
    if (strcmp(stage, "tokens") && strcmp(stage, "ast") && strcmp(stage, "dag") && strcmp(stage, "simple")) {
        iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "unknown stage '%s' (tokens, ast, dag, simple)", stage);
        return NULL;
    }
    if (parse(text, &a, err) != IACSG_OK)
        return NULL;
    char *s = NULL;
    if (strcmp(stage, "tokens") == 0)
        s = lex_dump(text, a.toks, a.ntoks);
    else if (strcmp(stage, "ast") == 0)
        s = ast_dump(&a);
    ast_free(&a);
    if (s || strcmp(stage, "tokens") == 0 || strcmp(stage, "ast") == 0)
        return s;
    iacsg_expr *e;
    if (iacsg_expr_parse(text, "<expr>", &e, err) != IACSG_OK)
        return NULL;
    s = strcmp(stage, "dag") == 0 ? dag_dump(&e->raw, e->raw_root) : dag_dump(&e->simple, e->root);
    iacsg_expr_destroy(e);
    return s;
}
