/* implicits/dag.h -- the expression DAG: nodes in an array, each node's operands at smaller indices (so the
 * index order is a topological order and every pass is a loop, never a recursion), identical nodes shared by
 * hash-consing. Leaves are the variables, constants (intervals in both precisions) and primitive parameters;
 * the other ops come from implicits/ops.def. */
#ifndef IACSG_DAG_H
#define IACSG_DAG_H
#include "error.h"
#include <stddef.h>

typedef enum {
    OP_X, OP_Y, OP_Z, OP_T, /* the variables */
    OP_CONST,               /* a constant: enclosing intervals in both precisions (and its decimal text, if any) */
    OP_PI, OP_E,            /* the real constants, folded to intervals by simplify.c */
    OP_PARAM,               /* parameter n of a primitive's body, replaced when the primitive is called */
#define OP(id, name, arity, nary, iv, pt, d, td, oracle, undef, empty) OP_##id,
#include "ops.def"
#undef OP
    OP_COUNT
} dag_op;

typedef struct {
    const char *name; /* "" for operators, leaves and internal ops */
    int arity, nary;
    const char *interval, *point, *derivative, *tderiv, *undefined, *empty; /* ops.def's columns ("" for leaves) */
} dag_op_info;
extern const dag_op_info dag_ops[OP_COUNT];
const char *dag_op_id(dag_op op); /* "ADD", "X", ... for dumps */

typedef struct {
    int op;
    int a, b; /* operand node indices, -1 when absent */
    int n;    /* POWN exponent, PARAM index, CONST text index into dag.texts (-1 if none) */
    double lo, hi, near;  /* CONST: double enclosure and the nearest double (for point code) */
    float flo, fhi, fnear; /* CONST: float enclosure and the nearest float */
} dag_node;

#define DAG_MAX_NODES (1 << 22)

typedef struct {
    dag_node *nodes;
    int count, cap;
    int *slots; /* hash table of node indices, -1 empty; size a power of two */
    int nslots;
    char **texts; /* decimal texts of literal constants, interned */
    int ntexts, captexts;
} dag;

void dag_init(dag *d);
void dag_free(dag *d);

/* The node (op, a, b, n), shared if it exists. Returns its index, or -1 with err set (memory or size limit). */
int dag_add(dag *d, int op, int a, int b, int n, iacsg_error *err);
/* A constant with the given enclosures (text: its decimal spelling for the exact oracle, or NULL). */
int dag_add_const(dag *d, double lo, double hi, double near, float flo, float fhi, float fnear, const char *text,
                  iacsg_error *err);
/* A constant from a decimal string (the reals it denotes, enclosed): -1 with err if it is not a number. */
int dag_add_decimal(dag *d, const char *text, iacsg_error *err);
/* The exactly representable constant v (in both precisions when v is a float; else an enclosure). */
int dag_add_real(dag *d, double v, iacsg_error *err);

/* 1 if node i is a constant that is the same single real number in float and in double. */
int dag_is_point(const dag *d, int i);

/* Copies the sub-DAG of `root` from src into dst (which may be src), replacing each leaf op OP_X..OP_PARAM
 * through map: map_var[0..3] for x,y,z,t (-1 keeps the variable), params[k] for OP_PARAM k. Returns the new root,
 * or -1 with err set. Linear in the size of the sub-DAG; iterative. */
int dag_substitute(const dag *src, int root, dag *dst, const int map_var[4], const int *params, int nparams,
                   iacsg_error *err);

/* The nodes reachable from root, in increasing index order (a topological order). *out is malloc'ed. Returns
 * the count, or -1 on out of memory. */
int dag_reachable(const dag *d, int root, int **out);

/* Writes one line per reachable node ("v12 = MUL v3 v7") to a malloc'ed string. NULL on out of memory. */
char *dag_dump(const dag *d, int root);

#endif
