/* implicits/simplify.h -- stage 4: a simplified copy of a DAG. Constants are folded into intervals (in both
 * precisions, with ia/ itself, so folding is as rigorous as evaluating); pi and e become constants; x*x and
 * x^2 become sqr (tighter: sqr of an interval straddling 0 starts at 0); integer exponents become pown, other
 * exponents pow; exactly representable constants in + - * / become the *_R point ops; and a few identities
 * (x+0, x*1, 1/x as recip, x+x as 2x, --x, min(x,x), |-x|, ...) disappear; operands of + * min max are put
 * in one order, so y*x and x*y are one node. In a sum (its terms through + - neg, up to 64 of them), a pair
 * q u^2 + c u of point coefficients becomes q (u + c/2q)^2 - c^2/4q where c/2q is exact, so that u occurs once
 * and the pair's enclosure is its range (the tangle's x^4 - 5x^2: (x^2 - 2.5)^2 - 6.25), and the sum's constants
 * are folded into one. Every rule keeps the real function, so inclusion holds. */
#ifndef IACSG_SIMPLIFY_H
#define IACSG_SIMPLIFY_H
#include "dag.h"

/* Writes the simplified sub-DAG of src's root into dst; returns the new root or -1 with err set. */
int simplify(const dag *src, int root, dag *dst, iacsg_error *err);

#endif
