/* implicits/lower.h -- stage 3: AST to DAG. Resolves names (scene bindings and solids, variables, constants,
 * functions of ops.def, union/intersection/difference, the library), expands library calls by substitution,
 * and builds the hash-consed DAG in which equal subexpressions are one node. */
#ifndef IACSG_LOWER_H
#define IACSG_LOWER_H
#include "ast.h"
#include "dag.h"
#include "names.h"

/* What a front end does with a scene's declarations (AST_MATERIAL, AST_SOLID, AST_REGION, AST_SURFACE): declare
 * is called for each, in source order, after its expressions are lowered (values: AST node -> DAG node, -1 for
 * nodes that are not values) and its name checked, with the names declared before it. It returns the index of
 * what it built (a material, solid, region or surface), or -1 with err set. */
typedef struct {
    void *ctx;
    int (*declare)(void *ctx, const ast *a, int node, const int *values, const name_table *names,
                   iacsg_error *err);
} lower_hooks;

/* Lowers the parsed text a into d; *root is the final expression's node, or -1 in a scene with regions or
 * surfaces. On failure returns the status with err set (line and column from the AST). hooks may be NULL for a
 * text without declarations. */
iacsg_status lower(const ast *a, dag *d, const lower_hooks *hooks, int *root, iacsg_error *err);

#endif
