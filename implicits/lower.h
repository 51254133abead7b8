/* implicits/lower.h -- stage 3: AST to DAG. Resolves names (scene bindings, variables, constants, functions of
 * ops.def, union/intersection/difference, the library), expands library calls by substitution, and builds the
 * hash-consed DAG in which equal subexpressions are one node. */
#ifndef IACSG_LOWER_H
#define IACSG_LOWER_H
#include "ast.h"
#include "dag.h"

/* Lowers the parsed text a into d; returns the root node or -1 with err set (line and column from the AST). */
int lower(const ast *a, dag *d, iacsg_error *err);

#endif
