/* implicits/expr_internal.h -- the inside of iacsg_expr, for the stage dumps, the device evaluator and the
 * tests (which evaluate the unsimplified DAG with MPFR). Not part of the public API. */
#ifndef IACSG_EXPR_INTERNAL_H
#define IACSG_EXPR_INTERNAL_H
#include "dag.h"
#include "expr.h"

struct iacsg_expr {
    char *name;
    dag raw;    /* as lowered: literal constants keep their decimal text, pi and e are leaves */
    int raw_root;
    dag simple; /* after simplify: what is emitted and evaluated */
    int root;
    int *order; /* the reachable nodes of simple, in index order (the evaluation tape) */
    int count;
};

/* An expression of the sub-DAG of root in raw, simplified: raw is moved into it (and left empty) when take,
 * else the sub-DAG is copied. name is copied. */
iacsg_status expr_from_dag(dag *raw, int root, const char *name, int take, iacsg_expr **out, iacsg_error *err);

/* The enclosure over vars = {x0, x1, y0, y1, z0, z1, t0, t1} (exact doubles; see eval.h). */
iacsg_status iacsg_expr_eval_vars(const iacsg_expr *e, int fp64, const double vars[8], double out[2],
                                  iacsg_error *err);

/* The dump of one stage: "tokens", "ast", "dag" (raw) or "simple". NULL with err for an unknown stage. The
 * text is re-lexed and re-parsed for the first two. */
char *iacsg_expr_dump(const char *text, const char *stage, iacsg_error *err);

#endif
