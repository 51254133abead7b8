/* implicits/emit.c -- stage 5: OpenCL C in SSA form, one statement per DAG node, so a shared subexpression is
 * computed once. The text comes only from the ops.def templates, the node numbers, the caller's prefix (checked
 * to be an identifier) and constants printed as hexadecimal floats: no user text reaches the source.
 *
 * Constants are exact hex literals for both precisions, chosen by the IACSG_K(float, double) macro when the
 * program is built (with or without IA_FP64).
 *
 * The gradient (for shading) is forward-mode: each value carries its three partial derivatives, by the
 * derivative column of ops.def. We prefer it to central differences because it is exact up to rounding, needs
 * one pass instead of six evaluations, and has no step size to tune (a step that suits a unit sphere fails on
 * x^500 or near the tiny features of a blend). The three travel as one 4-vector (iacsg_grad): one statement
 * per node instead of three, which also spares LLVM's SLP vectoriser, whose search over three parallel scalar
 * chains made most of the compile time of large expressions.
 *
 * Undefined operands follow the rule at the top of ia/ia.h: nodes that may be undefined carry flags (see
 * op_may_be_undefined), a union of them is ia_union, and the value of the whole expression is read through
 * ia_or_outside. */
#include "emit.h"
#include "emit_signs.h"
#include "ia/flush.h"
#include "strbuf.h"
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

static const char *const var_names[4] = {"x", "y", "z", "t"};

static void put_real(strbuf *b, double d, float f) {
    /* float, then double: IACSG_K picks one; the other literal vanishes in the preprocessor */
    strbuf_printf(b, "IACSG_K(");
    if (isinf(f))
        strbuf_printf(b, "%sINFINITY", f < 0 ? "-" : "");
    else
        strbuf_printf(b, "%af", (double)f);
    strbuf_printf(b, ", ");
    if (isinf(d))
        strbuf_printf(b, "%s(double)INFINITY", d < 0 ? "-" : "");
    else
        strbuf_printf(b, "%a", d);
    strbuf_printf(b, ")");
}

/* Undefined operands (the rule is at the top of ia/ia.h): a node "may be undefined" when its operation's
 * `undefined` column of ops.def is not 0 (a pole, a domain edge; pown only for negative powers), when it is an
 * empty constant, or when an operand may be, but for a union, which is undefined only where both operands are.
 * Such a node's interval code computes beside its value v<i> a flag v<i>_u (int, or ia_maskv over lanes), "may
 * be undefined somewhere on the box": its own condition or its operands' flags; the vector code also v<i>_e,
 * "undefined on all of the box" (the `empty` column), as it cannot test its lanes for empty (ia/vec.h). Nodes
 * that cannot be undefined, most of them, get no flag. */
/* Whether node n's own operation may be undefined: not a pown by n >= 0, nor a division by a constant that excludes
 * 0 in both precisions (a scale's: its point code's test of the constant was a warning of the device's compiler,
 * printed by PoCL at the first build). */
static int op_may_be_undefined(const dag *d, const dag_node *n) {
    const dag_node *B = n->op == OP_DIV ? &d->nodes[n->b] : NULL;
    if (B && B->op == OP_CONST && (B->lo > 0 || B->hi < 0) && (B->flo > 0 || B->fhi < 0))
        return 0;
    return n->op >= OP_NEG && strcmp(dag_ops[n->op].undefined, "0") != 0 && !(n->op == OP_POWN && n->n >= 0);
}

int emit_may_be_undefined(const dag *d, int root) {
    int *order = NULL, count = dag_reachable(d, root, &order), partial = count < 0;
    for (int k = 0; k < count && !partial; k++) {
        const dag_node *n = &d->nodes[order[k]];
        partial = op_may_be_undefined(d, n) || (n->op == OP_CONST && !(n->lo <= n->hi));
    }
    free(order);
    return partial;
}

typedef struct {
    const dag *d;
    unsigned char *axes;      /* per node: bit k set when its derivative along axis k is not identically 0 */
    unsigned char *undefined; /* per node: 1 when it may be undefined somewhere (it has a flag v<i>_u) */
    int axis;                 /* the gradient's component being written over lanes (AS_DERIVV): 0, 1, 2 */
    unsigned char *nonneg;    /* per node: its value over lanes starts at 0 or above (emit_signs.h) */
} emitter;

/* The text standing for operand node i in the interval code, the vector interval code (ia/vec.h: the same
 * templates with iav_ for ia_), the point code, or its gradient (an iacsg_grad vector: x, y, z, 0); the point code
 * over lanes (AS_POINTV: ia_realv values) and one component of its gradient (AS_DERIVV: the emitter's axis, an
 * ia_realv); and, for the interval code along a ray, scalar or over lanes (AS_INTERVAL_DT, AS_VECTOR_DT: values
 * and their derivatives in t, the leaves x, y, z moving at the rates dx, dy, dz), the enclosure of its derivative
 * (AS_TDERIV, AS_VTDERIV). */
typedef enum {
    AS_INTERVAL,
    AS_VECTOR,
    AS_POINT,
    AS_DERIV,
    AS_POINTV,
    AS_DERIVV,
    AS_INTERVAL_DT,
    AS_TDERIV,
    AS_VECTOR_DT,
    AS_VTDERIV
} role;
static int is_lanes_point(role r) { return r == AS_POINTV || r == AS_DERIVV; }
static int is_interval(role r) { return r != AS_POINT && r != AS_DERIV && !is_lanes_point(r); }
static int is_vector(role r) { return r == AS_VECTOR || r == AS_VECTOR_DT || r == AS_VTDERIV; }
static int is_along_ray(role r) { return r == AS_INTERVAL_DT || r == AS_VECTOR_DT; }
static int is_tderiv(role r) { return r == AS_TDERIV || r == AS_VTDERIV; }
static void put_operand(strbuf *b, const emitter *em, int i, role r) {
    const dag *d = em->d;
    const dag_node *n = &d->nodes[i];
    if (is_tderiv(r)) {
        if (n->op <= OP_Z)
            strbuf_printf(b, "d%s", var_names[n->op]);
        else if (!em->axes[i])
            strbuf_printf(b, is_vector(r) ? "iav_point(0)" : "ia_point(0)");
        else
            strbuf_printf(b, "v%d_t", i);
    } else if (r == AS_DERIVV) {
        if (!(em->axes[i] >> em->axis & 1))
            strbuf_printf(b, "IAV_R(0)");
        else if (n->op <= OP_Z)
            strbuf_printf(b, "IAV_R(1)");
        else
            strbuf_printf(b, "v%d_d%s", i, var_names[em->axis]);
    } else if (r == AS_DERIV) {
        if (n->op <= OP_Z)
            strbuf_printf(b, "(iacsg_grad)(%d, %d, %d, 0)", n->op == OP_X, n->op == OP_Y, n->op == OP_Z);
        else if (!em->axes[i])
            strbuf_printf(b, "(iacsg_grad)0");
        else
            strbuf_printf(b, "v%d_d", i);
    } else if (n->op <= OP_T) {
        strbuf_printf(b, "%s", var_names[n->op]);
    } else if (n->op == OP_CONST && is_interval(r) && dag_is_point(d, i)) {
        strbuf_printf(b, is_vector(r) ? "iav_point(" : "ia_point(");
        put_real(b, n->lo, n->flo);
        strbuf_printf(b, ")");
    } else if (n->op == OP_CONST && is_interval(r)) {
        /* an empty constant prints as [+inf, -inf], ia/'s empty */
        strbuf_printf(b, is_vector(r) ? "iav_const(" : "ia_make(");
        put_real(b, n->lo, n->flo);
        strbuf_printf(b, ", ");
        put_real(b, n->hi, n->fhi);
        strbuf_printf(b, ")");
    } else if (n->op == OP_CONST) {
        strbuf_printf(b, r == AS_POINTV ? "IAV_R(" : "");
        put_real(b, n->near, n->fnear); /* over lanes a vector: pow takes no scalar beside one */
        strbuf_printf(b, r == AS_POINTV ? ")" : "");
    } else {
        strbuf_printf(b, "v%d", i);
    }
}

/* A flag of node i (it may be undefined): v<i>_u or v<i>_e (kind 'u' or 'e'), or true for an empty constant. */
static void put_flag(strbuf *b, const emitter *em, int i, role r, char kind) {
    if (em->d->nodes[i].op == OP_CONST)
        strbuf_printf(b, is_vector(r) ? "(ia_maskv)-1" : "1");
    else
        strbuf_printf(b, "v%d_%c", i, kind);
}

/* Node i's flags as arguments: ", u" or, over lanes, ", u, e"; false where it cannot be undefined. */
static void put_flag_arguments(strbuf *b, const emitter *em, int i, role r) {
    for (int k = 0; k < (is_vector(r) ? 2 : 1); k++) {
        strbuf_printf(b, ", ");
        if (em->undefined[i])
            put_flag(b, em, i, r, k == 0 ? 'u' : 'e');
        else
            strbuf_printf(b, is_vector(r) ? "(ia_maskv)0" : "0");
    }
}

/* Node i's interval value as the solid reads it: through ia_or_outside where it may be undefined (+inf,
 * outside, there). For the value of the whole expression, and for the parts of a union in groups (emit_group), as
 * iav_union takes them. */
static void put_solid_value(strbuf *b, const emitter *em, int i, role r) {
    if (!em->undefined[i]) {
        put_operand(b, em, i, r);
        return;
    }
    strbuf_printf(b, is_vector(r) ? "iav_or_outside(" : "ia_or_outside(");
    put_operand(b, em, i, r);
    put_flag_arguments(b, em, i, r);
    strbuf_printf(b, ")");
}

/* The value of a union (MIN) with an operand that may be undefined: ia_union (ia/interval.h) with the flags. */
static void put_union(strbuf *b, const emitter *em, int i, role r) {
    const dag_node *n = &em->d->nodes[i];
    int operands[2] = {n->a, n->b};
    strbuf_printf(b, is_vector(r) ? "iav_union(" : "ia_union(");
    for (int k = 0; k < 2; k++) {
        put_operand(b, em, operands[k], r);
        put_flag_arguments(b, em, operands[k], r);
        strbuf_printf(b, k == 0 ? ", " : ")");
    }
}

int emit_is_ident_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

/* The point code's integer powers (x^n in the value and n x^(n-1) in the gradient): on a float device with double,
 * ia_pown_point (ia/arith.h: the interval pown's chain in double, rounded once, so that a point's value lies in the
 * enclosures over it); else by repeated squaring for |n| <= 8, the built-in pown beyond. PoCL's pown goes through
 * exp and log: in the heart's frames (pown 3, twice) __pocl_expep and __pocl_epln, shading the hit pixels lane by
 * lane, took as many samples as the whole render kernel. The exponent is a constant: after inlining, the loop is a
 * few multiplications. iacsg_pown at a point, iacsg_pownv over lanes (ia/vec.h's iav_pown_point; inlined for
 * its constant, as iav_pown). */
#define POINT_POWN_OF(qualifier, real, name, point, beyond)                                                        \
    qualifier " " real " " name "(" real " a, int n) {\n"                                                        \
    "    int done;\n    " real " d = " point "(a, n, &done);\n    if (done)\n        return d;\n"               \
    "    if (n > 8 || n < -8)\n        return " beyond "(a, n);\n"                                               \
    "    " real " r = 1, p = a;\n"                                                                               \
    "    for (int m = n < 0 ? -n : n; m > 0; m >>= 1) {\n        if (m & 1)\n            r *= p;\n"           \
    "        p *= p;\n    }\n    return n < 0 ? 1 / r : r;\n}\n"
#define POINT_POWN POINT_POWN_OF("IA_FN", "ia_real", "iacsg_pown", "ia_pown_point", "pown")
/* before P_f_gradv, in the vector part of the program (a scene's program enters it after its solids' scalar code,
 * whose IACSG_K guard would hide it) */
#define POINT_POWNV                                                                                             \
    "#ifndef IACSG_POWNV\n#define IACSG_POWNV 1\n"                                                               \
    POINT_POWN_OF("IAV_INLINE", "ia_realv", "iacsg_pownv", "iav_pown_point", "iav_pown_by_lane") "#endif\n"

/* The outward enclosure [RD(1/hi), RU(1/lo)] of the reciprocals of a constant c = [lo, hi] with 0 < lo <= hi, in
 * double (d) and float (f): 1 when c is such a constant with finite reciprocals, else 0. A quotient by c is then a
 * product by it: every x/c' (c' in c) is x times a point of it, and a product is rounded once, outward, where the
 * device's division is rounded within IA_ULP_DIV (2.5 ulp in OpenCL's float) and costs more; icos.csg's
 * scale(ic, 0.4) divides x, y, z and their derivatives by 0.4 at every evaluation. The residual of q c - 1, exact
 * by fma, says on which side of 1/c the rounded q lies. */
int emit_reciprocal_enclosure(const dag_node *c, double d[2], float f[2]) {
    if (c->op != OP_CONST || !(c->lo > 0 && c->flo > 0 && isfinite(c->hi) && isfinite(c->fhi)))
        return 0;
    d[0] = 1 / c->hi;
    d[1] = 1 / c->lo;
    f[0] = 1 / c->fhi;
    f[1] = 1 / c->flo;
    if (!isfinite(d[1]) || !isfinite(f[1]))
        return 0;
    if (fma(d[0], c->hi, -1.0) > 0)
        d[0] = nextafter(d[0], 0.0);
    if (fma(d[1], c->lo, -1.0) < 0)
        d[1] = nextafter(d[1], (double)INFINITY);
    if (fmaf(f[0], c->fhi, -1.0f) > 0)
        f[0] = nextafterf(f[0], 0.0f);
    if (fmaf(f[1], c->flo, -1.0f) < 0)
        f[1] = nextafterf(f[1], INFINITY);
    d[0] = ia_flush_lo_d(d[0]), d[1] = ia_flush_hi_d(d[1]), f[0] = ia_flush_lo_f(f[0]), f[1] = ia_flush_hi_f(f[1]);
    return 1;
}

/* The point code's functions whose lanes version is not the OpenCL built-in of the same name: the powers (see
 * POINT_POWN), ia_sin_point, ia_cos_point and ia_exp_point's, ia_real_max's, and the built-ins that PoCL's vectors
 * get wrong in some lanes (ia/vec.h: IAV_POINT_LANEWISE). NULL for the others. */
static const char *lanes_function(const char *name, size_t len) {
    static const char *const lanes[][2] = {{"pown", "iacsg_pownv"},     {"sin", "iav_sin_point"},
                                           {"cos", "iav_cos_point"},    {"tan", "iav_tan_point"},
                                           {"pow", "iav_pow_point"},    {"ia_real_max", "iav_real_max"},
                                           {"exp", "iav_exp_point"}};
    for (size_t k = 0; k < sizeof lanes / sizeof lanes[0]; k++)
        if (strlen(lanes[k][0]) == len && strncmp(name, lanes[k][0], len) == 0)
            return lanes[k][1];
    return NULL;
}

/* Writes an ops.def template for node i, replacing the placeholders A, B, N, KB, DA, DB, R and RB (the
 * reciprocals of a constant B, see emit_reciprocal_enclosure). In the point code, the bounds .lo and .hi of the
 * `undefined` column are the point itself. */
static void expand(strbuf *b, const emitter *em, int i, const char *tpl, role r) {
    const dag *d = em->d;
    const dag_node *n = &d->nodes[i];
    role operand_role = r == AS_DERIV     ? AS_POINT
                        : r == AS_DERIVV  ? AS_POINTV
                        : r == AS_VTDERIV ? AS_VECTOR
                        : r == AS_TDERIV  ? AS_INTERVAL
                                          : r;
    role deriv_role = is_tderiv(r) ? r : is_lanes_point(r) ? AS_DERIVV : AS_DERIV;
    if (n->op == OP_MIN && tpl == dag_ops[OP_MIN].interval && (em->undefined[n->a] || em->undefined[n->b])) {
        put_union(b, em, i, r);
        return;
    }
    double recip[2] = {0, 0};
    float frecip[2] = {0, 0};
    if (n->op == OP_DIV && is_interval(r) && emit_reciprocal_enclosure(&d->nodes[n->b], recip, frecip))
        tpl = tpl == dag_ops[OP_DIV].interval ? "ia_mul(A, RB)"
              : tpl == dag_ops[OP_DIV].tderiv ? "ia_mul(DA, RB)" /* B's derivative is 0: (DA - R 0) / B */
                                              : tpl;
    for (const char *p = tpl; *p;) {
        int bound = strncmp(p, ".lo", 3) == 0 || strncmp(p, ".hi", 3) == 0;
        if ((r == AS_POINT || r == AS_POINTV) && bound && !emit_is_ident_char(p[3])) {
            p += 3;
            continue;
        }
        if (!emit_is_ident_char(*p)) {
            strbuf_append(b, p++, 1);
            continue;
        }
        size_t len = 1;
        while (emit_is_ident_char(p[len]))
            len++;
#define IS(word) (len == sizeof(word) - 1 && strncmp(p, word, len) == 0)
        if (IS("A"))
            put_operand(b, em, n->a, operand_role);
        else if (IS("B"))
            put_operand(b, em, n->b, operand_role);
        else if (IS("KB"))
            put_real(b, d->nodes[n->b].near, d->nodes[n->b].fnear);
        else if (IS("N"))
            strbuf_printf(b, "%d", n->n);
        else if (IS("DA"))
            put_operand(b, em, n->a, deriv_role);
        else if (IS("DB"))
            put_operand(b, em, n->b, deriv_role);
        else if (IS("R"))
            strbuf_printf(b, "v%d", i);
        else if (IS("RB")) {
            strbuf_printf(b, is_vector(r) ? "iav_const(" : "ia_make(");
            put_real(b, recip[0], frecip[0]);
            strbuf_printf(b, ", ");
            put_real(b, recip[1], frecip[1]);
            strbuf_printf(b, ")");
        }
        else if (is_vector(r) && len > 3 && strncmp(p, "ia_", 3) == 0)
            strbuf_printf(b, "iav_%.*s", (int)len - 3, p + 3);
        else if (is_lanes_point(r) && lanes_function(p, len))
            strbuf_printf(b, "%s", lanes_function(p, len));
        else if (!is_interval(r) && IS("pown"))
            strbuf_printf(b, "iacsg_pown"); /* the point code's powers: see POINT_POWN */
        else if (!is_interval(r) && (IS("sin") || IS("cos") || IS("exp")))
            strbuf_printf(b, "ia_%.*s_point", (int)len, p); /* as ia_sin, ia_cos, ia_exp compute (ia/elem.h) */
        else
            strbuf_append(b, p, len);
#undef IS
        p += len;
    }
}

/* OpenCL compilers take minutes on functions much longer than this (a union of 1024 spheres is 3419 nodes and
 * builds in about 9 s on PoCL); past it, a clear error beats a build that seems to hang. */
#define EMIT_MAX_NODES 16384

static int valid_prefix(const char *p) {
    if (!p || !*p || strlen(p) > 64 || (*p >= '0' && *p <= '9'))
        return 0;
    for (; *p; p++)
        if (!emit_is_ident_char(*p))
            return 0;
    return 1;
}

/* Node i's derivative along a ray over lanes (AS_VTDERIV): ops.def's tderiv column, except where the lanes' code
 * has a cheaper enclosure of the same value. The leaves x, y, z move at the rates dx, dy, dz, points (the ray's
 * direction), so a product with one is iav_mul_pv of its .lo; 2a is exact (iav_twice, not iav_mul_r's rounding);
 * and a sum or product with an operand whose derivative is identically 0 is the other term alone (not a rounded
 * addition of [0, 0]). Returns the template, in ops.def's placeholders; `buf` holds composed ones. */
static const char *vector_tderiv(const emitter *em, const dag_node *n, char *buf, size_t size) {
    int leaf_a = n->a >= 0 && em->d->nodes[n->a].op <= OP_Z, leaf_b = n->b >= 0 && em->d->nodes[n->b].op <= OP_Z;
    int zero_a = n->a >= 0 && !em->axes[n->a], zero_b = n->b >= 0 && !em->axes[n->b];
    switch (n->op) {
    case OP_SQR: /* 2a >= 0 where a is (emit_signs.h): iav_mul_n, the same bits */
        return leaf_a ? "ia_mul_pv(ia_twice(A), DA.lo)" : em->nonneg[n->a] ? "ia_mul_n(ia_twice(A), DA)"
                                                                           : "ia_mul(ia_twice(A), DA)";
    case OP_POWN:
        return leaf_a ? "ia_mul_pv(ia_mul_r(ia_pown(A, N - 1), N), DA.lo)" : dag_ops[n->op].tderiv;
    case OP_SQRT:
        return "ia_div(DA, ia_twice(R))";
    case OP_ADD:
        return zero_a ? "DB" : zero_b ? "DA" : dag_ops[n->op].tderiv;
    case OP_SUB:
        return zero_a ? "ia_neg(DB)" : zero_b ? "DA" : dag_ops[n->op].tderiv;
    case OP_MUL: { /* DA B + A DB */
        const char *first = leaf_a ? "ia_mul_pv(B, DA.lo)" : em->nonneg[n->b] ? "ia_mul_n(B, DA)" : "ia_mul(DA, B)";
        const char *second = leaf_b ? "ia_mul_pv(A, DB.lo)" : em->nonneg[n->a] ? "ia_mul_n(A, DB)" : "ia_mul(A, DB)";
        if (zero_a || zero_b)
            return zero_a ? second : first;
        snprintf(buf, size, "ia_add(%s, %s)", first, second);
        return buf;
    }
    default:
        return dag_ops[n->op].tderiv;
    }
}

/* Node i's flag of a kind, 'u' or 'e' (see op_may_be_undefined): its own condition (the undefined or empty
 * column), or its operands' flags (both, for a union). */
static void flag_statement(strbuf *b, const emitter *em, int i, role value, char kind) {
    const dag_node *n = &em->d->nodes[i];
    const char *own = kind == 'u' ? dag_ops[n->op].undefined : dag_ops[n->op].empty;
    strbuf_printf(b, "    %s v%d_%c = ", is_vector(value) ? "ia_maskv" : "int", i, kind);
    const char *join = "";
    if (op_may_be_undefined(em->d, n) && strcmp(own, "0") != 0) {
        strbuf_printf(b, "(");
        expand(b, em, i, own, value);
        strbuf_printf(b, ")");
        join = " || ";
    }
    int operands[2] = {n->a, n->b}, any = 0;
    for (int k = 0; k < 2; k++)
        if (operands[k] >= 0 && em->undefined[operands[k]]) {
            strbuf_printf(b, "%s", n->op == OP_MIN ? (k == 0 ? "(" : " && ") : join);
            put_flag(b, em, operands[k], value, kind);
            join = " || ";
            any = 1;
        }
    if (!any && !*join) /* tan is never undefined on all of a box */
        strbuf_printf(b, "0");
    strbuf_printf(b, "%s;\n", n->op == OP_MIN ? ")" : "");
}

/* The statements computing every non-leaf node, for one of the six functions. Derivatives that are 0 by
 * structure (of nodes that depend on none of x, y, z) are not computed. Where a node may be undefined, the
 * interval code computes its flag, the point code makes it NaN where its own operation is undefined (NaN then
 * spreads through the arithmetic; at a point, tan's poles are never met, so its condition on R is left out),
 * and the derivative along a ray gathers the flags of such operations in `undefined`. */
/* sin and cos of one argument share its reduction (ia/elem.h's ia_sin_cos, ia/vec_sincos.h's iav_sin_cos): in the
 * interval code, a sin and a cos over the same operand among the nodes of order[] are one statement, at the first
 * of them (a gyroid's three arguments have both: libfive's view at 1024x1024, 203 -> 139 ms), and along a ray
 * (where sin's derivative needs the cos of its argument and cos's the sin) a sin or cos without its partner computes
 * both into v<i> and v<i>_cos or v<i>_sin (icos.csg's Newton steps took 12 reductions for its 6 cosines).
 * partner[i]: that other node, or -1; a malloc'ed array indexed by node (NULL with no memory: no pairs). */
static int *sin_cos_partners(const emitter *em, const int *order, int count) {
    int *partner = malloc(((size_t)em->d->count + 1) * sizeof *partner);
    if (!partner)
        return NULL;
    for (int k = 0; k < count; k++)
        partner[order[k]] = -1;
    for (int k = 0; k < count; k++) {
        const dag_node *n = &em->d->nodes[order[k]];
        if (n->op != OP_SIN)
            continue;
        for (int q = 0; q < count && partner[order[k]] < 0; q++) {
            const dag_node *m = &em->d->nodes[order[q]];
            if (m->op == OP_COS && m->a == n->a && partner[order[q]] < 0) {
                partner[order[k]] = order[q];
                partner[order[q]] = order[k];
            }
        }
    }
    return partner;
}

/* Node i's statement where it is paired (see above): returns 1 with the template of its derivative along a ray in
 * buf (the other's value), 0 for other nodes and roles. The later node of a pair has no statement of its own. */
static int sin_cos_statement(strbuf *b, const emitter *em, const int *partner, int i, role r, char *buf,
                             size_t size) {
    const dag_node *n = &em->d->nodes[i];
    if (!is_interval(r) || (n->op != OP_SIN && n->op != OP_COS))
        return 0;
    int is_sin = n->op == OP_SIN, j = partner ? partner[i] : -1;
    if (j < 0 && !(is_along_ray(r) && em->axes[i]))
        return 0;
    char other[32];
    if (j >= 0)
        snprintf(other, sizeof other, "v%d", j);
    else
        snprintf(other, sizeof other, "v%d_%s", i, is_sin ? "cos" : "sin");
    int rate = is_vector(r) && em->d->nodes[n->a].op <= OP_Z; /* a leaf's: a point per lane (vector_tderiv) */
    if (is_sin)
        snprintf(buf, size, rate ? "ia_mul_pv(%s, DA.lo)" : "ia_mul(%s, DA)", other);
    else
        snprintf(buf, size, rate ? "ia_neg(ia_mul_pv(%s, DA.lo))" : "ia_neg(ia_mul(%s, DA))", other);
    if (j >= 0 && j < i)
        return 1;
    int vector = is_vector(r);
    strbuf_printf(b, "    %s v%d, %s;\n    %s(", vector ? "iav" : "ia_interval", i, other,
                  vector ? "iav_sin_cos" : "ia_sin_cos");
    put_operand(b, em, n->a, vector ? AS_VECTOR : AS_INTERVAL);
    if (is_sin)
        strbuf_printf(b, ", &v%d, &%s);\n", i, other);
    else
        strbuf_printf(b, ", &%s, &v%d);\n", other, i);
    return 1;
}

/* A derivative rule for node n whose operands' derivatives are identically 0 where zero_a, zero_b say: a sum's
 * or a product's other term alone (forms: a + b with a' = 0, then b' = 0; a - b; a b), else `general`. */
static const char *pruned_rule(const dag_node *n, int zero_a, int zero_b, const char *const forms[6],
                               const char *general) {
    int k = n->op == OP_ADD ? 0 : n->op == OP_SUB ? 2 : n->op == OP_MUL ? 4 : -1;
    return k < 0 ? general : zero_a ? forms[k] : zero_b ? forms[k + 1] : general;
}

/* Node i's derivative along a ray one box at a time (AS_TDERIV): ops.def's tderiv column, but a sum or product with
 * an operand whose derivative is identically 0 is the other term alone, as over lanes (vector_tderiv): not a
 * product by [0, 0] and a rounded addition of it (icos.csg's tau y, tau z, tau x). */
static const char *scalar_tderiv(const emitter *em, const dag_node *n) {
    static const char *const forms[6] = {"DB", "DA", "ia_neg(DB)", "DA", "ia_mul(A, DB)", "ia_mul(DA, B)"};
    return pruned_rule(n, n->a >= 0 && !em->axes[n->a], n->b >= 0 && !em->axes[n->b], forms,
                       dag_ops[n->op].tderiv);
}

/* Node n's derivative along the emitter's axis over lanes (AS_DERIVV): ops.def's derivative column, pruned as
 * scalar_tderiv (the scalar code's 4-vectors compute the product by 0 and add it; they differ only where that
 * product is NaN, where the other operand is infinite or NaN). */
static const char *lanes_derivative(const emitter *em, const dag_node *n) {
    static const char *const forms[6] = {"DB", "DA", "-DB", "DA", "A * DB", "DA * B"};
    return pruned_rule(n, n->a >= 0 && !(em->axes[n->a] >> em->axis & 1),
                       n->b >= 0 && !(em->axes[n->b] >> em->axis & 1), forms, dag_ops[n->op].derivative);
}

/* Node i's gradient over lanes: a statement per axis its derivative depends on (v<i>_dx, _dy, _dz). */
static void lanes_gradient_statements(strbuf *b, const emitter *em, int i) {
    emitter along = *em;
    for (along.axis = 0; along.axis < 3; along.axis++) {
        if (!(em->axes[i] >> along.axis & 1))
            continue;
        strbuf_printf(b, "    ia_realv v%d_d%s = ", i, var_names[along.axis]);
        expand(b, &along, i, lanes_derivative(&along, &em->d->nodes[i]), AS_DERIVV);
        strbuf_printf(b, ";\n");
    }
}

/* The point code's statement making node i NaN where its own operation is undefined at the point (value: AS_POINT
 * or AS_POINTV); over lanes a select on the condition's mask (OpenCL's ?: would take a vector condition too). */
static void nan_where_undefined(strbuf *b, const emitter *em, int i, role value) {
    const char *condition = dag_ops[em->d->nodes[i].op].undefined;
    if (value == AS_POINTV) {
        strbuf_printf(b, "    v%d = select(v%d, IAV_R(NAN), ", i, i);
        expand(b, em, i, condition, value);
        strbuf_printf(b, ");\n");
    } else {
        strbuf_printf(b, "    v%d = ", i);
        expand(b, em, i, condition, value);
        strbuf_printf(b, " ? (ia_real)NAN : v%d;\n", i);
    }
}

static void body(strbuf *b, const emitter *em, const int *order, int count, role r) {
    int *partner = is_interval(r) ? sin_cos_partners(em, order, count) : NULL;
    role value = r == AS_VECTOR_DT     ? AS_VECTOR
                 : r == AS_INTERVAL_DT ? AS_INTERVAL
                 : r == AS_DERIV       ? AS_POINT
                 : r == AS_DERIVV      ? AS_POINTV
                                       : r;
    for (int k = 0; k < count; k++) {
        int i = order[k];
        const dag_node *n = &em->d->nodes[i];
        if (n->op < OP_NEG)
            continue; /* leaves are written in place */
        const char *type = is_lanes_point(r) ? "ia_realv"
                           : !is_interval(r) ? "ia_real"
                           : is_vector(r)    ? "iav"
                                             : "ia_interval";
        char paired[64];
        int sin_cos = sin_cos_statement(b, em, partner, i, r, paired, sizeof paired);
        if (!sin_cos) {
            strbuf_printf(b, "    %s v%d = ", type, i);
            int clamped;
            const char *signed_form = value == AS_VECTOR ? emit_signs_value(em->d, em->nonneg, n, &clamped) : NULL;
            expand(b, em, i,
                   signed_form      ? signed_form
                   : is_interval(r) ? dag_ops[n->op].interval
                                    : dag_ops[n->op].point,
                   value);
            strbuf_printf(b, ";\n");
        }
        int own = op_may_be_undefined(em->d, n);
        if (em->undefined[i] && is_interval(r))
            flag_statement(b, em, i, value, 'u');
        if (em->undefined[i] && is_vector(r))
            flag_statement(b, em, i, value, 'e');
        if (own && is_along_ray(r))
            strbuf_printf(b, "    undefined |= v%d_u;\n", i);
        if (own && !is_interval(r) && !strstr(dag_ops[n->op].undefined, "R."))
            nan_where_undefined(b, em, i, value);
        if ((r != AS_DERIV && r != AS_DERIVV && !is_along_ray(r)) || !em->axes[i])
            continue;
        if (r == AS_DERIVV) {
            lanes_gradient_statements(b, em, i);
            continue;
        }
        if (r == AS_DERIV) {
            strbuf_printf(b, "    iacsg_grad v%d_d = ", i);
            expand(b, em, i, dag_ops[n->op].derivative, AS_DERIV);
        } else {
            char composed[64];
            strbuf_printf(b, "    %s v%d_t = ", type, i);
            if (r == AS_VECTOR_DT)
                expand(b, em, i, sin_cos ? paired : vector_tderiv(em, n, composed, sizeof composed), AS_VTDERIV);
            else
                expand(b, em, i, sin_cos ? paired : scalar_tderiv(em, n), AS_TDERIV);
        }
        strbuf_printf(b, ";\n");
    }
    free(partner);
}

/* Whether any node of order[] has an operation that may be undefined. */
static int any_partial(const emitter *em, const int *order, int count) {
    for (int k = 0; k < count; k++)
        if (op_may_be_undefined(em->d, &em->d->nodes[order[k]]))
            return 1;
    return 0;
}

/* The value of the expression over a box and the enclosure of its derivative along a ray through it, the box
 * moving at the rates dx, dy, dz (the ray's direction), for interval Newton: prefix_Fdv over lanes (r =
 * AS_VECTOR_DT), prefix_Fd one box at a time (AS_INTERVAL_DT). Where an operation may be undefined on the box (a
 * pole, a domain edge), F may be undefined or jump there, and the mean value theorem Newton relies on fails: the
 * derivative is reported as [-inf, +inf] there (in that lane). */
static void emit_tderiv_function(strbuf *b, const emitter *em, const int *order, int count, int root,
                                 const char *prefix, role r) {
    int vector = is_vector(r);
    const char *type = vector ? "iav" : "ia_interval";
    /* over lanes inlined: called, its 7 interval vectors went through memory */
    strbuf_printf(b, "%s %s %s_Fd%s(%s x, %s y, %s z, %s t, %s dx, %s dy, %s dz, %s *dt) {\n",
                  vector ? "IAV_INLINE" : "IA_FN", type, prefix, vector ? "v" : "", type, type, type, type, type, type,
                  type, type);
    int partial = any_partial(em, order, count);
    if (partial)
        strbuf_printf(b, vector ? "    ia_maskv undefined = 0;\n" : "    int undefined = 0;\n");
    body(b, em, order, count, r);
    strbuf_printf(b, !partial  ? "    *dt = "
                     : vector ? "    *dt = iav_entire_where("
                              : "    *dt = undefined ? ia_entire() : ");
    put_operand(b, em, root, vector ? AS_VTDERIV : AS_TDERIV);
    strbuf_printf(b, partial && vector ? ", undefined);\n    return " : ";\n    return ");
    put_solid_value(b, em, root, vector ? AS_VECTOR : AS_INTERVAL);
    strbuf_printf(b, ";\n}\n");
}

/* The point value and gradient over lanes, for the kernels' shading (kernels/render.cl: packet_gradients): the
 * point code's operations in SIMD lanes, each gradient component a vector of its own, and only those that are not
 * identically 0 (where the scalar code computes a 4-vector per node and lane). */
static void emit_lanes_gradient(strbuf *b, const emitter *em, const int *order, int count, int root,
                                const char *prefix) {
    strbuf_printf(b, "IA_FN ia_realv %s_f_gradv(ia_realv x, ia_realv y, ia_realv z, ia_realv t, ia_realv g[3]) {\n",
                  prefix);
    body(b, em, order, count, AS_DERIVV);
    emitter along = *em;
    for (along.axis = 0; along.axis < 3; along.axis++) {
        strbuf_printf(b, "    g[%d] = ", along.axis);
        put_operand(b, &along, root, AS_DERIVV);
        strbuf_printf(b, ";\n");
    }
    strbuf_printf(b, "    return ");
    put_operand(b, em, root, AS_POINTV);
    strbuf_printf(b, ";\n}\n");
}

/* A union (min) of at least this many parts is emitted in groups that the kernels can skip per tile and segment
 * of the frame's tree (kernels/packet.h); at most EMIT_MAX_GROUPS groups (a 64-bit mask), about sqrt(parts). */
#define EMIT_GROUP_MIN_PARTS 16
#define EMIT_MAX_GROUPS 64

/* The operands of the root's union: min(min(a, b), c) -> a, b, c, left to right (the DAG folds n-ary min to
 * binary). Returns their number in a malloc'ed array, 0 when the root is not a min or the parts are too many
 * (a shared min can be reached many times), -1 out of memory. */
int emit_union_parts(const dag *d, int root, int **out) {
    *out = NULL;
    if (d->nodes[root].op != OP_MIN)
        return 0;
    int *work = malloc(2 * EMIT_MAX_NODES * sizeof *work), *parts = malloc(EMIT_MAX_NODES * sizeof *parts);
    if (!work || !parts) {
        free(work);
        free(parts);
        return -1;
    }
    int top = 0, count = 0;
    work[top++] = root;
    while (top > 0 && count < EMIT_MAX_NODES && top < 2 * EMIT_MAX_NODES - 1) {
        const dag_node *n = &d->nodes[work[--top]];
        if (n->op == OP_MIN) { /* b below a, so a comes out first */
            work[top++] = n->b;
            work[top++] = n->a;
        } else {
            parts[count++] = (int)(n - d->nodes);
        }
    }
    free(work);
    if (top > 0) { /* too many */
        free(parts);
        return 0;
    }
    *out = parts;
    return count;
}

/* How a union's parts are grouped: ~sqrt(n) groups of consecutive parts (scene files list neighbouring solids
 * together, so a group tends to be compact in space), at most EMIT_MAX_GROUPS. */
typedef struct {
    int count, per_group;
} grouping;
static grouping group_parts(int nparts) {
    int groups = (int)ceil(sqrt((double)nparts));
    groups = groups > EMIT_MAX_GROUPS ? EMIT_MAX_GROUPS : groups;
    grouping g = {0, (nparts + groups - 1) / groups};
    g.count = (nparts + g.per_group - 1) / g.per_group;
    return g;
}

/* The nodes that parts[first .. last-1] need, in index order (an evaluation order), into order[]; their number,
 * or -1 out of memory. needed: room for root + 1 flags. */
static int group_nodes(const emitter *em, const int *parts, int first, int last, unsigned char *needed, int root,
                       int *order) {
    memset(needed, 0, (size_t)root + 1);
    for (int c = first; c < last; c++) {
        int *reach;
        int count = dag_reachable(em->d, parts[c], &reach);
        if (count < 0)
            return -1;
        for (int k = 0; k < count; k++)
            needed[reach[k]] = 1;
        free(reach);
    }
    int count = 0;
    for (int i = 0; i <= root; i++)
        if (needed[i])
            order[count++] = i;
    return count;
}

/* One group of a union as a function (not inlined) of its own: the nodes its parts need, shared ones computed
 * once, and their min; for the interval code over lanes (r = AS_VECTOR), with the enclosure of the min's derivative
 * along the rays (AS_VECTOR_DT: iav_dmin over the parts, as emit_tderiv_function's whole expression), or the point
 * value and gradient (AS_DERIV). Returns 0 on out of memory. */
static int emit_group(strbuf *b, const emitter *em, int root, const int *parts, int first, int last, int g,
                      const char *prefix, role r, unsigned char *needed, int *order) {
    int count = group_nodes(em, parts, first, last, needed, root, order);
    if (count < 0)
        return 0;
    int vector = is_vector(r), along = r == AS_VECTOR_DT, partial = along && any_partial(em, order, count);
    if (along)
        strbuf_printf(b, "__attribute__((noinline)) iav %s_Fdv_g%d(iav x, iav y, iav z, iav t, iav dx, iav dy, "
                         "iav dz, iav *dt) {\n",
                      prefix, g);
    else if (vector)
        strbuf_printf(b, "__attribute__((noinline)) iav %s_Fv_g%d(iav x, iav y, iav z, iav t) {\n", prefix, g);
    else
        strbuf_printf(b, "__attribute__((noinline)) ia_real %s_f_grad_g%d(ia_real x, ia_real y, ia_real z, "
                         "ia_real t, iacsg_grad *g) {\n",
                      prefix, g);
    if (partial)
        strbuf_printf(b, "    ia_maskv undefined = 0;\n");
    body(b, em, order, count, r);
    strbuf_printf(b, vector ? "    iav r = " : "    ia_real r = ");
    if (vector)
        put_solid_value(b, em, parts[first], AS_VECTOR);
    else
        put_operand(b, em, parts[first], AS_POINT);
    if (along) {
        strbuf_printf(b, ", r_t = ");
        put_operand(b, em, parts[first], AS_VTDERIV);
    } else if (!vector) {
        strbuf_printf(b, ";\n    iacsg_grad rg = ");
        put_operand(b, em, parts[first], AS_DERIV);
    }
    strbuf_printf(b, ";\n");
    for (int c = first + 1; c < last; c++) {
        if (along) {
            strbuf_printf(b, "    r_t = iav_dmin(r, ");
            put_solid_value(b, em, parts[c], AS_VECTOR);
            strbuf_printf(b, ", r_t, ");
            put_operand(b, em, parts[c], AS_VTDERIV);
            strbuf_printf(b, ");\n");
        }
        if (vector) {
            strbuf_printf(b, "    r = iav_min(r, ");
            put_solid_value(b, em, parts[c], AS_VECTOR);
            strbuf_printf(b, ");\n");
            continue;
        }
        /* as MIN's point and derivative templates: fmin, and the first operand's gradient when r <= v or v is
         * undefined */
        strbuf_printf(b, "    rg = isnan(");
        put_operand(b, em, parts[c], AS_POINT);
        strbuf_printf(b, ") || r <= ");
        put_operand(b, em, parts[c], AS_POINT);
        strbuf_printf(b, " ? rg : ");
        put_operand(b, em, parts[c], AS_DERIV);
        strbuf_printf(b, ";\n    r = fmin(r, ");
        put_operand(b, em, parts[c], AS_POINT);
        strbuf_printf(b, ");\n");
    }
    if (along)
        strbuf_printf(b, partial ? "    *dt = iav_entire_where(r_t, undefined);\n" : "    *dt = r_t;\n");
    strbuf_printf(b, vector ? "    return r;\n}\n" : "    *g = rg;\n    return r;\n}\n");
    return 1;
}

/* A union in groups (see emit_group), and the function of a group's number that calls them. The kernels take
 * the min over the groups that can matter in a tile (kernels/packet.h, shade.h), so there is no whole iacsg_Fv (nor
 * iacsg_Fdv: with AS_VECTOR_DT, iacsg_Fdv_group, whose min packet_Fdv takes with its derivative);
 * the whole gradient, the min over all groups, is for the other programs (device evaluation). A function per
 * group keeps LLVM's compile time down, which grows faster than linearly in a function's length: 1024 spheres
 * built in 5.5-5.7 s instead of 7-8 s with one function holding every group (and 18 s as one block). Returns 0
 * on out of memory. */
static int emit_union_groups(strbuf *b, const emitter *em, int root, const int *parts, int nparts,
                             const char *prefix, role r) {
    grouping gr = group_parts(nparts);
    unsigned char *needed = malloc((size_t)root + 1);
    int *order = malloc(((size_t)root + 1) * sizeof *order);
    int ok = needed && order;
    for (int g = 0; g < gr.count && ok; g++) {
        int first = g * gr.per_group, last = first + gr.per_group < nparts ? first + gr.per_group : nparts;
        ok = emit_group(b, em, root, parts, first, last, g, prefix, r, needed, order);
    }
    free(needed);
    free(order);
    if (!ok)
        return 0;
    if (r == AS_VECTOR_DT) { /* kernels/packet.h: packet_Fdv takes the min over the groups it is given */
        strbuf_printf(b, "#define IACSG_FDV 1\nIA_FN iav %s_Fdv_group(int group, iav x, iav y, iav z, iav t, iav dx, "
                         "iav dy, iav dz, iav *dt) {\n    switch (group) {\n",
                      prefix);
        for (int g = 0; g < gr.count; g++)
            strbuf_printf(b, "    case %d: return %s_Fdv_g%d(x, y, z, t, dx, dy, dz, dt);\n", g, prefix, g);
        strbuf_printf(b, "    }\n    *dt = iav_point(0);\n    return iav_point(IA_INF);\n}\n");
        return 1;
    }
    int vector = r == AS_VECTOR;
    if (vector)
        strbuf_printf(b, "#define IACSG_GROUPS %d\nIA_FN iav %s_Fv_group(int group, iav x, iav y, iav z, iav t) {\n"
                         "    switch (group) {\n",
                      gr.count, prefix);
    else
        strbuf_printf(b, "IA_FN ia_real %s_f_grad_group(int group, ia_real x, ia_real y, ia_real z, ia_real t, "
                         "iacsg_grad *g) {\n    switch (group) {\n",
                      prefix);
    for (int g = 0; g < gr.count; g++)
        strbuf_printf(b, vector ? "    case %d: return %s_Fv_g%d(x, y, z, t);\n"
                                : "    case %d: return %s_f_grad_g%d(x, y, z, t, g);\n",
                      g, prefix, g);
    if (vector) {
        strbuf_printf(b, "    }\n    return iav_point(IA_INF);\n}\n");
    } else {
        strbuf_printf(b, "    }\n    *g = (iacsg_grad)0;\n    return (ia_real)INFINITY;\n}\n");
        strbuf_printf(b, "IA_FN ia_real %s_f_grad(ia_real x, ia_real y, ia_real z, ia_real t, ia_real *gx, "
                         "ia_real *gy, ia_real *gz) {\n"
                         "    iacsg_grad g, gv;\n    ia_real r = %s_f_grad_group(0, x, y, z, t, &g);\n"
                         "    for (int group = 1; group < %d; group++) {\n"
                         "        ia_real v = %s_f_grad_group(group, x, y, z, t, &gv);\n"
                         "        g = isnan(v) || r <= v ? g : gv;\n        r = fmin(r, v);\n    }\n"
                         "    *gx = g.x;\n    *gy = g.y;\n    *gz = g.z;\n    return r;\n}\n",
                      prefix, prefix, gr.count, prefix);
    }
    return 1;
}

/* Whether the kernels should refine roots by interval Newton (iacsg_Fdv, kernels/packet.h): only where its
 * derivative is about as cheap as the value and varies little over a small box. Measured on the seed scenes:
 * the reference view's sphere and torus 50 -> 40 ms, the sigmoid blend 127 -> 94, but x^500 (whose derivative
 * x^499 moves too fast for Newton to contract) 167 -> 188. So not with pow (whose derivative needs a log) or
 * powers above 8; exp, tan, atan and log have derivatives made of their own values and cheap operations, and sin
 * and cos each other, from the same reduction (sin_cos_statement). (When sin and cos ran lane by lane, Newton took
 * a trigonometric scene from 162 to 206 ms; now a gyroid in a ball at eps 1e-5 goes 260 -> 214 ms, 7.70 -> 6.23
 * evaluations a ray, at most 1696 -> 166, and Fig. 7's trigtorus | sphere 57 -> 53 ms.)
 * The segment path's secondary rays (kernels/scene_effects.cl) march with the derivative at any power
 * (IACSG_FDV_MARCH, march.h's effects_march): its mean value form bounds F over a step along the ray, where F's
 * enclosure over the step's box (each coordinate on its own) reaches back towards the surface the ray leaves.
 * Fig. 2's regions (x^500): 14.75 -> 4.54 evaluations a shadow ray, the shadow rays' kernel 17 % less CPU, a cold
 * kernel build 5.4 -> 6.7 s. The first-root path's (kernels/effects.cl) keep the enclosure: Fig. 2 as one
 * expression, 15.46 -> 3.76 evaluations a shadow ray but no less CPU (its x^500's derivative costs as much); so
 * only the regions' union is emitted with it (emit_cl's `march`), and no other program pays for its build. */
#define EMIT_NEWTON_MAX_POWER 8
static int newton_pays(const dag *d, const int *order, int count, int max_power) {
    for (int k = 0; k < count; k++) {
        const dag_node *n = &d->nodes[order[k]];
        switch (n->op) {
        case OP_POW:
            return 0;
        case OP_POWN:
            if (n->n > max_power || n->n < -max_power)
                return 0;
            break;
        default:
            break;
        }
    }
    return 1;
}

int emit_newton_pays(const dag *d, const int *order, int count) {
    return newton_pays(d, order, count, EMIT_NEWTON_MAX_POWER);
}

iacsg_status emit_cl(const dag *d, int root, const char *prefix, int march, char **source, iacsg_error *err) {
    *source = NULL;
    if (!valid_prefix(prefix))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the name prefix for generated code must be an identifier");
    int *order;
    int count = dag_reachable(d, root, &order);
    if (count > EMIT_MAX_NODES) {
        free(order);
        return iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0,
                               "expression too long to compile: %d operations after simplification (at most %d)",
                               count, EMIT_MAX_NODES);
    }
    emitter em = {d, count < 0 ? NULL : malloc((size_t)root + 1), count < 0 ? NULL : malloc((size_t)root + 1), 0,
                  count < 0 ? NULL : malloc((size_t)root + 1)};
    if (!em.axes || !em.undefined || !em.nonneg) {
        if (count >= 0)
            free(order);
        free(em.axes);
        free(em.undefined);
        free(em.nonneg);
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory generating code");
    }
    for (int k = 0; k < count; k++) {
        const dag_node *n = &d->nodes[order[k]];
        int i = order[k], a = n->a, b2 = n->b;
        em.axes[i] = n->op <= OP_Z ? (unsigned char)(1u << n->op)
                     : n->op < OP_NEG ? 0 /* t and constants */
                                      : em.axes[a] | (b2 >= 0 ? em.axes[b2] : 0);
        if (n->op < OP_NEG)
            em.undefined[i] = n->op == OP_CONST && !(n->lo <= n->hi);
        else if (n->op == OP_MIN)
            em.undefined[i] = em.undefined[a] && em.undefined[b2];
        else
            em.undefined[i] = op_may_be_undefined(d, n) || em.undefined[a] || (b2 >= 0 && em.undefined[b2]);
    }
    emit_signs_mark(d, order, count, em.nonneg);
    strbuf b = {0};
    strbuf_printf(&b, "/* generated by iacsg: %d nodes */\n"
                      "#ifndef IACSG_K\n#ifdef IA_FP64\n#define IACSG_K(f, d) (d)\ntypedef double4 iacsg_grad;\n#else\n"
                      "#define IACSG_K(f, d) (f)\ntypedef float4 iacsg_grad;\n#endif\n%s#endif\n",
                  count, POINT_POWN);
    /* Over IA_VW lanes (ia/vec.h) for the renderer's kernels, a large union in groups; the scalar interval
     * function for other programs (device evaluation); the point value and gradient for both. A program gets
     * only what it uses: clang parses every function it is given, and for 1024 spheres each of these is 3400
     * statements. A program that traces rays one by one but shades in lanes (the segment path) defines
     * IACSG_SCALAR_CODE to get the scalar ones, and IACSG_SCALAR_FD for the scalar derivative along a ray, P_Fd. */
    int *parts;
    int nparts = emit_union_parts(d, root, &parts);
    strbuf_printf(&b, "#if defined(IA_VW) && !defined(IACSG_SCALAR_CODE)\n");
    int ok = nparts >= 0;
    if (nparts >= EMIT_GROUP_MIN_PARTS) {
        ok = emit_union_groups(&b, &em, root, parts, nparts, prefix, AS_VECTOR);
        /* each group's derivative too, for the packets' Newton and the effects' march (a regions' union in groups
         * has no use for it: the segment path marches only a union it pre-passes, kernels/scene_union.h) */
        if (ok && !march && newton_pays(d, order, count, EMIT_NEWTON_MAX_POWER))
            ok = emit_union_groups(&b, &em, root, parts, nparts, prefix, AS_VECTOR_DT);
    } else if (ok) {
        strbuf_printf(&b, "IA_FN iav %s_Fv(iav x, iav y, iav z, iav t) {\n", prefix);
        body(&b, &em, order, count, AS_VECTOR);
        strbuf_printf(&b, "    return ");
        put_solid_value(&b, &em, root, AS_VECTOR);
        strbuf_printf(&b, ";\n}\n");
        int newton = newton_pays(d, order, count, EMIT_NEWTON_MAX_POWER);
        if (newton || (march && newton_pays(d, order, count, INT_MAX))) {
            strbuf_printf(&b, newton ? "#define IACSG_FDV 1\n" : "#define IACSG_FDV_MARCH 1\n");
            emit_tderiv_function(&b, &em, order, count, root, prefix, AS_VECTOR_DT);
        }
        strbuf_printf(&b, "%s", POINT_POWNV);
        emit_lanes_gradient(&b, &em, order, count, root, prefix);
    }
    strbuf_printf(&b, "#else\nIA_FN ia_interval %s_F(ia_interval x, ia_interval y, ia_interval z, ia_interval t) {\n",
                  prefix);
    body(&b, &em, order, count, AS_INTERVAL);
    strbuf_printf(&b, "    return ");
    put_solid_value(&b, &em, root, AS_INTERVAL);
    strbuf_printf(&b, ";\n}\n");
    /* the segment path's walks (kernels/segments.h, surface.h) step interval Newton one box at a time with it,
     * for every solid: there a step decides whole subtrees, so unlike the packets' it pays on high powers too */
    strbuf_printf(&b, "#ifdef IACSG_SCALAR_FD\n");
    emit_tderiv_function(&b, &em, order, count, root, prefix, AS_INTERVAL_DT);
    strbuf_printf(&b, "#endif\n");
    /* a union in groups: the kernels shade it by differences of iacsg_Fv (kernels/shade.h), its gradient code
     * would be a quarter of their build */
    if (nparts >= EMIT_GROUP_MIN_PARTS)
        ok = ok && emit_union_groups(&b, &em, root, parts, nparts, prefix, AS_DERIV);
    strbuf_printf(&b, "#endif\n");
    if (nparts < EMIT_GROUP_MIN_PARTS) {
        strbuf_printf(&b, "IA_FN ia_real %s_f_grad(ia_real x, ia_real y, ia_real z, ia_real t, ia_real *gx, "
                          "ia_real *gy, ia_real *gz) {\n",
                      prefix);
        body(&b, &em, order, count, AS_DERIV);
        strbuf_printf(&b, "    iacsg_grad g = ");
        put_operand(&b, &em, root, AS_DERIV);
        strbuf_printf(&b, ";\n    *gx = g.x;\n    *gy = g.y;\n    *gz = g.z;\n    return ");
        put_operand(&b, &em, root, AS_POINT);
        strbuf_printf(&b, ";\n}\n");
    }
    free(parts);
    free(order);
    free(em.axes);
    free(em.undefined);
    free(em.nonneg);
    *source = strbuf_finish(&b);
    if (*source && !ok) {
        free(*source);
        *source = NULL;
    }
    return *source ? IACSG_OK : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory generating code");
}
