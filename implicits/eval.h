/* implicits/eval.h -- host evaluation of a DAG with ia/, in float (eval_f32.c) and double (eval_f64.c)
 * intervals: both translation units include eval_body.h, which ia/ compiles for the precision IA_FP64 selects.
 * Intervals cross this interface as pairs of doubles, which hold either precision exactly. */
#ifndef IACSG_EVAL_H
#define IACSG_EVAL_H
#include "dag.h"

/* One operation of ops.def on interval operands (b ignored for unary ops; k: the real value of a constant
 * second operand, for the *_R ops). Used for constant folding: MIN is the union, where an empty (undefined)
 * constant leaves the other. */
void eval_op_f32(int op, const double a[2], const double b[2], int n, double k, double r[2]);
void eval_op_f64(int op, const double a[2], const double b[2], int n, double k, double r[2]);

/* The enclosure of the DAG over a box: vars = {x0, x1, y0, y1, z0, z1, t0, t1}, exact doubles (rounded outward
 * to floats by the f32 version). order/count: the reachable nodes of the root in index order (dag_reachable),
 * the root last; scratch: room for the highest index + 1 intervals of either precision and as many flags
 * (eval_scratch_size). Undefined operands follow the rule at the top of ia/ia.h. */
void eval_dag_f32(const dag *d, const int *order, int count, const double vars[8], void *scratch, double out[2]);
void eval_dag_f64(const dag *d, const int *order, int count, const double vars[8], void *scratch, double out[2]);
size_t eval_scratch_size(int max_index);

#endif
