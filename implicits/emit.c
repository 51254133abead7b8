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
 * chains made most of the compile time of large expressions. */
#include "emit.h"
#include "strbuf.h"
#include <math.h>
#include <stdlib.h>
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

typedef struct {
    const dag *d;
    unsigned char *axes; /* per node: bit k set when its derivative along axis k is not identically 0 */
} emitter;

/* The text standing for operand node i in the interval code, the vector interval code (ia/vec.h: the same
 * templates with iav_ for ia_), the point code, or its gradient (an iacsg_grad vector: x, y, z, 0); and, for the
 * interval code along a ray (AS_INTERVAL_DT, AS_VECTOR_DT: values and their derivatives in t, the leaves x, y, z
 * moving at the rates dx, dy, dz), the enclosure of its derivative (AS_TDERIV, AS_VTDERIV). */
typedef enum { AS_INTERVAL, AS_VECTOR, AS_POINT, AS_DERIV, AS_INTERVAL_DT, AS_VECTOR_DT, AS_TDERIV, AS_VTDERIV } role;
static int is_interval(role r) { return r != AS_POINT && r != AS_DERIV; }
static int is_vector(role r) { return r == AS_VECTOR || r == AS_VECTOR_DT || r == AS_VTDERIV; }
static void put_operand(strbuf *b, const emitter *em, int i, role r) {
    const dag *d = em->d;
    const dag_node *n = &d->nodes[i];
    if (r == AS_TDERIV || r == AS_VTDERIV) {
        if (n->op <= OP_Z)
            strbuf_printf(b, "d%s", var_names[n->op]);
        else if (!em->axes[i])
            strbuf_printf(b, r == AS_VTDERIV ? "iav_point(0)" : "ia_point(0)");
        else
            strbuf_printf(b, "v%d_t", i);
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
        put_real(b, n->near, n->fnear);
    } else {
        strbuf_printf(b, "v%d", i);
    }
}

static int is_ident_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

/* Writes an ops.def template for node i, replacing the placeholders A, B, N, KB, DA, DB and R. */
static void expand(strbuf *b, const emitter *em, int i, const char *tpl, role r) {
    const dag *d = em->d;
    const dag_node *n = &d->nodes[i];
    role operand_role = r == AS_DERIV ? AS_POINT : r == AS_TDERIV ? AS_INTERVAL : r == AS_VTDERIV ? AS_VECTOR : r;
    role deriv_role = r == AS_TDERIV || r == AS_VTDERIV ? r : AS_DERIV;
    for (const char *p = tpl; *p;) {
        if (!is_ident_char(*p)) {
            strbuf_append(b, p++, 1);
            continue;
        }
        size_t len = 1;
        while (is_ident_char(p[len]))
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
        else if (is_vector(r) && len > 3 && strncmp(p, "ia_", 3) == 0)
            strbuf_printf(b, "iav_%.*s", (int)len - 3, p + 3);
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
        if (!is_ident_char(*p))
            return 0;
    return 1;
}

/* The statements computing every non-leaf node, for one of the six functions. Derivatives that are 0 by
 * structure (of nodes that depend on none of x, y, z) are not computed. */
static void body(strbuf *b, const emitter *em, const int *order, int count, role r) {
    role value = r == AS_INTERVAL_DT ? AS_INTERVAL : r == AS_VECTOR_DT ? AS_VECTOR : r;
    int with_derivative = r == AS_DERIV || r == AS_INTERVAL_DT || r == AS_VECTOR_DT;
    for (int k = 0; k < count; k++) {
        int i = order[k];
        const dag_node *n = &em->d->nodes[i];
        if (n->op < OP_NEG)
            continue; /* leaves are written in place */
        const char *type = !is_interval(r) ? "ia_real" : is_vector(r) ? "iav" : "ia_interval";
        strbuf_printf(b, "    %s v%d = ", type, i);
        expand(b, em, i, is_interval(r) ? dag_ops[n->op].interval : dag_ops[n->op].point, value);
        strbuf_printf(b, ";\n");
        if (!with_derivative || !em->axes[i])
            continue;
        if (r == AS_DERIV) {
            strbuf_printf(b, "    iacsg_grad v%d_d = ", i);
            expand(b, em, i, dag_ops[n->op].derivative, AS_DERIV);
        } else {
            strbuf_printf(b, "    %s v%d_t = ", type, i);
            expand(b, em, i, dag_ops[n->op].tderiv, r == AS_VECTOR_DT ? AS_VTDERIV : AS_TDERIV);
        }
        strbuf_printf(b, ";\n");
    }
}

/* The value of the expression over a box and the enclosure of its derivative along a ray through it, the box
 * moving at the rates dx, dy, dz (the ray's direction): prefix_Fdv over lanes or prefix_Fd. */
static void emit_tderiv_function(strbuf *b, const emitter *em, const int *order, int count, int root,
                                 const char *prefix, int vector) {
    const char *type = vector ? "iav" : "ia_interval";
    strbuf_printf(b, "IA_FN %s %s_Fd%s(%s x, %s y, %s z, %s t, %s dx, %s dy, %s dz, %s *dt) {\n", type, prefix,
                  vector ? "v" : "", type, type, type, type, type, type, type, type);
    body(b, em, order, count, vector ? AS_VECTOR_DT : AS_INTERVAL_DT);
    strbuf_printf(b, "    *dt = ");
    put_operand(b, em, root, vector ? AS_VTDERIV : AS_TDERIV);
    strbuf_printf(b, ";\n    return ");
    put_operand(b, em, root, vector ? AS_VECTOR : AS_INTERVAL);
    strbuf_printf(b, ";\n}\n");
}

/* A union (min) of at least this many parts is emitted in groups that the kernels can skip per tile and segment
 * of the frame's tree (kernels/packet.h); at most EMIT_MAX_GROUPS groups (a 64-bit mask), about sqrt(parts). */
#define EMIT_GROUP_MIN_PARTS 16
#define EMIT_MAX_GROUPS 64

/* The operands of the root's union: min(min(a, b), c) -> a, b, c, left to right (the DAG folds n-ary min to
 * binary). Returns their number in a malloc'ed array, 0 when the root is not a min or the parts are too many
 * (a shared min can be reached many times), -1 out of memory. */
static int union_parts(const dag *d, int root, int **out) {
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
 * once, and their min; for the interval code over lanes (r = AS_VECTOR) or the point value and gradient
 * (AS_DERIV). Returns 0 on out of memory. */
static int emit_group(strbuf *b, const emitter *em, int root, const int *parts, int first, int last, int g,
                      const char *prefix, role r, unsigned char *needed, int *order) {
    int count = group_nodes(em, parts, first, last, needed, root, order);
    if (count < 0)
        return 0;
    int vector = r == AS_VECTOR;
    if (vector)
        strbuf_printf(b, "__attribute__((noinline)) iav %s_Fv_g%d(iav x, iav y, iav z, iav t) {\n", prefix, g);
    else
        strbuf_printf(b, "__attribute__((noinline)) ia_real %s_f_grad_g%d(ia_real x, ia_real y, ia_real z, "
                         "ia_real t, iacsg_grad *g) {\n",
                      prefix, g);
    body(b, em, order, count, r);
    strbuf_printf(b, vector ? "    iav r = " : "    ia_real r = ");
    put_operand(b, em, parts[first], vector ? AS_VECTOR : AS_POINT);
    if (!vector) {
        strbuf_printf(b, ";\n    iacsg_grad rg = ");
        put_operand(b, em, parts[first], AS_DERIV);
    }
    strbuf_printf(b, ";\n");
    for (int c = first + 1; c < last; c++) {
        if (vector) {
            strbuf_printf(b, "    r = iav_min(r, ");
            put_operand(b, em, parts[c], AS_VECTOR);
            strbuf_printf(b, ");\n");
            continue;
        }
        /* as MIN's point and derivative templates: fmin, and the first operand's gradient when r <= v */
        strbuf_printf(b, "    rg = r <= ");
        put_operand(b, em, parts[c], AS_POINT);
        strbuf_printf(b, " ? rg : ");
        put_operand(b, em, parts[c], AS_DERIV);
        strbuf_printf(b, ";\n    r = fmin(r, ");
        put_operand(b, em, parts[c], AS_POINT);
        strbuf_printf(b, ");\n");
    }
    strbuf_printf(b, vector ? "    return r;\n}\n" : "    *g = rg;\n    return r;\n}\n");
    return 1;
}

/* A union in groups (see emit_group), and the function of a group's number that calls them. The kernels take
 * the min over the groups that can matter in a tile (kernels/packet.h, shade.h), so there is no whole iacsg_Fv;
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
                         "        g = r <= v ? g : gv;\n        r = fmin(r, v);\n    }\n"
                         "    *gx = g.x;\n    *gy = g.y;\n    *gz = g.z;\n    return r;\n}\n",
                      prefix, prefix, gr.count, prefix);
    }
    return 1;
}

/* Whether the kernels should refine roots by interval Newton (iacsg_Fdv, kernels/packet.h): only where its
 * derivative is about as cheap as the value and varies little over a small box. Measured on the seed scenes:
 * the reference view's sphere and torus 50 -> 40 ms, the sigmoid blend 127 -> 94, but with sin and cos (the
 * derivative of each needs the other, which runs lane by lane) 162 -> 206, and x^500 (whose derivative x^499
 * moves too fast for Newton to contract) 167 -> 188. So not with sin, cos, pow (whose derivative needs a log)
 * or powers above 8; exp, tan, atan and log have derivatives made of their own values and cheap operations. */
#define EMIT_NEWTON_MAX_POWER 8
static int newton_pays(const dag *d, const int *order, int count) {
    for (int k = 0; k < count; k++) {
        const dag_node *n = &d->nodes[order[k]];
        switch (n->op) {
        case OP_SIN:
        case OP_COS:
        case OP_POW:
            return 0;
        case OP_POWN:
            if (n->n > EMIT_NEWTON_MAX_POWER || n->n < -EMIT_NEWTON_MAX_POWER)
                return 0;
            break;
        default:
            break;
        }
    }
    return 1;
}

iacsg_status emit_cl(const dag *d, int root, const char *prefix, char **source, iacsg_error *err) {
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
    emitter em = {d, count < 0 ? NULL : malloc((size_t)root + 1)};
    if (!em.axes) {
        if (count >= 0)
            free(order);
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory generating code");
    }
    for (int k = 0; k < count; k++) {
        const dag_node *n = &d->nodes[order[k]];
        em.axes[order[k]] = n->op <= OP_Z ? (unsigned char)(1u << n->op)
                            : n->op < OP_NEG ? 0 /* t and constants */
                                             : em.axes[n->a] | (n->b >= 0 ? em.axes[n->b] : 0);
    }
    strbuf b = {0};
    strbuf_printf(&b, "/* generated by iacsg: %d nodes */\n"
                      "#ifndef IACSG_K\n#ifdef IA_FP64\n#define IACSG_K(f, d) (d)\ntypedef double4 iacsg_grad;\n#else\n"
                      "#define IACSG_K(f, d) (f)\ntypedef float4 iacsg_grad;\n#endif\n#endif\n",
                  count);
    /* Over IA_VW lanes (ia/vec.h) for the renderer's kernels, a large union in groups; the scalar interval and
     * point functions for other programs (device evaluation). A program gets only what it uses: clang parses
     * every function it is given, and for 1024 spheres each of these is 3400 statements. A program that traces
     * rays one by one but shades in lanes (the segment path) defines IACSG_SCALAR_CODE to get the scalar ones. */
    int *parts;
    int nparts = union_parts(d, root, &parts);
    strbuf_printf(&b, "#if defined(IA_VW) && !defined(IACSG_SCALAR_CODE)\n");
    int ok = nparts >= 0;
    if (nparts >= EMIT_GROUP_MIN_PARTS) {
        ok = emit_union_groups(&b, &em, root, parts, nparts, prefix, AS_VECTOR);
    } else if (ok) {
        strbuf_printf(&b, "IA_FN iav %s_Fv(iav x, iav y, iav z, iav t) {\n", prefix);
        body(&b, &em, order, count, AS_VECTOR);
        strbuf_printf(&b, "    return ");
        put_operand(&b, &em, root, AS_VECTOR);
        strbuf_printf(&b, ";\n}\n");
        if (newton_pays(d, order, count)) {
            strbuf_printf(&b, "#define IACSG_FDV 1\n");
            emit_tderiv_function(&b, &em, order, count, root, prefix, 1);
        }
    }
    strbuf_printf(&b, "#else\nIA_FN ia_interval %s_F(ia_interval x, ia_interval y, ia_interval z, ia_interval t) {\n",
                  prefix);
    body(&b, &em, order, count, AS_INTERVAL);
    strbuf_printf(&b, "    return ");
    put_operand(&b, &em, root, AS_INTERVAL);
    strbuf_printf(&b, ";\n}\n");
    emit_tderiv_function(&b, &em, order, count, root, prefix, 0);
    strbuf_printf(&b, "IA_FN ia_real %s_f(ia_real x, ia_real y, ia_real z, ia_real t) {\n", prefix);
    body(&b, &em, order, count, AS_POINT);
    strbuf_printf(&b, "    return ");
    put_operand(&b, &em, root, AS_POINT);
    strbuf_printf(&b, ";\n}\n");
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
    *source = strbuf_finish(&b);
    if (*source && !ok) {
        free(*source);
        *source = NULL;
    }
    return *source ? IACSG_OK : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory generating code");
}
