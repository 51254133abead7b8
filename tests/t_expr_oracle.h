/* tests/t_expr_oracle.h -- helpers for the compiler's property tests: the MPFR value of an expression's
 * unsimplified DAG (driven by the oracle column of implicits/ops.def), random expression texts, random boxes,
 * and the every-op list. */
#ifndef IACSG_T_EXPR_ORACLE_H
#define IACSG_T_EXPR_ORACLE_H
#include "implicits/expr_internal.h"
#include "test.h"
#include <mpfr.h>

#define EXPR_ORACLE_PREC 256

/* The value at (x, y, z, t) of the expression as written (its unsimplified DAG, decimal constants read exactly
 * to EXPR_ORACLE_PREC bits), into y (initialised by the caller). A subexpression undefined or infinite at p is
 * undefined, and follows the rule of ia/ia.h: a union is its other operand there, any other operation is
 * undefined. Returns 0 where the whole expression is undefined, else 1. */
int expr_oracle(const iacsg_expr *e, const double p[4], mpfr_ptr y);

/* The derivative at p along dir (x, y, z) of the same, by a central difference of step 2^-80 at
 * EXPR_ORACLE_PREC bits (exact arguments; its error is far below a double's ulp wherever the expression is
 * smooth, and between the one-sided derivatives at a kink), into slope; where the difference cancels (a slope
 * far smaller than f), again at 4 times the precision. Returns 0 where a side is undefined, or the slope is not
 * known even then. */
int expr_oracle_slope(const iacsg_expr *e, const double p[4], const double dir[3], mpfr_ptr slope);

/* A random expression text of at most `depth` levels into buf (size >= 4096): variables, decimal constants,
 * pi and e, + - * / ^, every named function of ops.def, CSG, primitives, blends and transforms. */
void expr_random_text(test_rng_t *r, int depth, char *buf, size_t size);

/* A random box {x0, x1, y0, y1, z0, z1, t0, t1} around [-2, 2]^3 x [0, 1], of widths from 2^-30 to 4 (some
 * degenerate), and a random point in it (a corner, or uniform). */
void expr_random_box(test_rng_t *r, double vars[8]);
void expr_random_point(test_rng_t *r, const double vars[8], double p[4]);

/* Texts that, compiled, use every op of ops.def between them (tests check they do). */
extern const char *const expr_every_op_texts[];
extern const int expr_every_op_count;

/* The primitives of the library (every LIB_PRIMITIVE, called bare), for the per-primitive tests. */
int expr_primitive_names(const char **names, int max);

/* The device tests' expressions: every primitive, every op's text, the sums the simplifier rewrites, then random
 * texts of depth 4 until there are max (which must leave room for the first three); returns max. */
#define EXPR_TEXT_SIZE 8192
int expr_test_texts(test_rng_t *r, char (*texts)[EXPR_TEXT_SIZE], int max);

#endif
