/* implicits/expr.h -- the public interface of the expression compiler.
 *
 * A user writes a solid as text: f < 0 inside, f > 0 outside, f = 0 on the surface (docs/language.md). The
 * compiler turns it into OpenCL C inclusion functions over ia/ intervals, and evaluates it on the host with the
 * same ia/ code. Stages (one file each, each with a dump; see implicits/compile.h):
 *
 *   text --lex.c--> tokens --parse.c--> AST --lower.c--> DAG (hash-consed, primitives and transforms expanded)
 *        --simplify.c--> DAG (folded constants, sqr, pown) --emit.c--> OpenCL C   |   --eval_*.c--> host intervals
 *
 * Ownership: iacsg_expr_parse creates an expression that iacsg_expr_destroy frees; strings returned through
 * `char **` are malloc'ed and the caller free()s them. Functions never print and never exit.
 */
#ifndef IACSG_EXPR_H
#define IACSG_EXPR_H
#include "error.h"

IACSG_API_BEGIN

typedef struct iacsg_expr iacsg_expr; /* a compiled expression or scene (opaque) */

/* Parses an expression or a scene file's text (name is used in messages, e.g. the file name or "<expr>"). A
 * text with regions or surfaces is refused (implicits/scene.h reads it). On failure *out is NULL and err holds
 * the message, line and column. */
iacsg_status iacsg_expr_parse(const char *text, const char *name, iacsg_expr **out, iacsg_error *err);
void iacsg_expr_destroy(iacsg_expr *e);

/* OpenCL C source defining, with the given name prefix P (an identifier chosen by the caller, never user text):
 *   IA_FN ia_interval P_F(ia_interval x, ia_interval y, ia_interval z, ia_interval t);    inclusion function
 *   IA_FN ia_real     P_f_grad(ia_real x, ia_real y, ia_real z, ia_real t,
 *                              ia_real *gx, ia_real *gy, ia_real *gz);                    value and gradient
 * and, in a program built with IA_VW (the renderer's), instead of P_F: P_Fv, its enclosure over IA_VW lanes, and
 * P_f_gradv, the value and gradient at IA_VW points (ia_realv x, y, z, t, ia_realv g[3]; the kernels' shading), or
 * for a union of many parts P_Fv_group (IACSG_GROUPS of them, and no P_f_grad nor P_f_gradv: kernels/shade.h);
 * and where interval Newton pays, P_Fdv, the value and the derivative along a ray (IACSG_FDV). Undefined operands
 * follow the rule of ia/ia.h. It expects the ia/ headers before it (iacsg_cl_ia). The caller free()s *source. */
iacsg_status iacsg_expr_emit_cl(const iacsg_expr *e, const char *prefix, char **source, iacsg_error *err);

/* 1 if the expression depends on the time variable t. */
int iacsg_expr_uses_time(const iacsg_expr *e);

/* What iacsg_expr_bounds proved about the box it wrote. */
typedef enum {
    IACSG_BOUNDS_NONE = 0,  /* nothing: no box was found (box untouched) */
    IACSG_BOUNDS_IN_CUBE,   /* no zero of f in [-IACSG_BOUNDS_CUBE, IACSG_BOUNDS_CUBE]^3 outside the box; nothing
                             * is known beyond that cube */
    IACSG_BOUNDS_EVERYWHERE /* no zero of f anywhere outside the box */
} iacsg_bounds_proof;
#define IACSG_BOUNDS_CUBE 1024.0

/* A box, as x0,y0,z0,x1,y1,z1, proven (by double interval evaluation, implicits/bounds.c) to hold every zero of
 * f at every time t in [time[0], time[1]] (finite, time[0] <= time[1]; {t, t} for one time; an enclosure of a
 * real that no double equals, as ia_decimal_double gives; for an animation, the hull of its frames' times).
 * Outside the box f has no zero in the region the result names; returns IACSG_BOUNDS_NONE (0) when no box
 * could be proven. The boxes are per expression, so a scene's solids each get their own. */
iacsg_bounds_proof iacsg_expr_bounds(const iacsg_expr *e, const double time[2], double box[6]);

/* Host evaluation with the same ia/ code: an enclosure of the expression over the box lo..hi at time t (fp64
 * selects double intervals, else float intervals with the box rounded outward to floats). Box bounds are exact
 * doubles. out = {lo, hi}. */
iacsg_status iacsg_expr_eval_box(const iacsg_expr *e, int fp64, const double lo[3], const double hi[3], double t,
                                 double out[2], iacsg_error *err);

IACSG_API_END
#endif
