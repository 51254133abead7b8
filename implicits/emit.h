/* implicits/emit.h -- stage 5: OpenCL C from a simplified DAG (the functions P_F, P_f, P_f_grad of expr.h). */
#ifndef IACSG_EMIT_H
#define IACSG_EMIT_H
#include "dag.h"

/* The source for the sub-DAG of root with name prefix `prefix` (checked to be a C identifier). The caller
 * free()s *source. `march`: also the derivative along the ray where only a power above interval Newton's limit
 * keeps it out (IACSG_FDV_MARCH: for the segment path's marching secondary rays, not worth its build elsewhere). */
iacsg_status emit_cl(const dag *d, int root, const char *prefix, int march, char **source, iacsg_error *err);

/* The operands of the root's union (min(min(a, b), c) -> a, b, c, left to right): their number, in a malloc'ed
 * *out; 0 (and *out NULL) when the root is not a min or the parts are too many, -1 out of memory. */
int emit_union_parts(const dag *d, int root, int **out);

/* 1 when interval Newton pays for the nodes order[0 .. count-1] (their derivative is about as cheap as their
 * value: no pow or high power, emit.c says why); the tape interpreter (tape.c) asks it per part. */
int emit_newton_pays(const dag *d, const int *order, int count);

/* 1 for a character of a C identifier (the templates of ops.def are scanned word by word). */
int emit_is_ident_char(char c);

/* 1 when some node reachable from root may be undefined somewhere (a pole, a domain edge, an empty constant). */
int emit_may_be_undefined(const dag *d, int root);
/* The outward enclosure of the reciprocals of constant node c in double (d) and float (f), where c is a positive
 * constant with finite reciprocals (returns 1; else 0): a quotient by c is emitted as a product by it, and the
 * tape interpreter (tape.c) does the same, to stay bit for bit the compiled code. */
int emit_reciprocal_enclosure(const dag_node *c, double d[2], float f[2]);

#endif
