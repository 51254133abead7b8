/* implicits/scene_emit.c -- see scene_emit.h. Each dispatcher is a switch over groups of SCENE_EMIT_GROUP solids,
 * each group a function of its own (not inlined) holding a switch over its solids, whose code is inlined there:
 * inlined wherever the kernels call the dispatchers, 1000 spheres took minutes to build. The build costs about
 * 30 ms of CPU per sphere (PoCL, LLVM 15). scene_solid_Fd, each solid's value and derivative along a ray
 * (P_Fd, which the compiler emits under IACSG_SCALAR_FD), is for the walks' interval Newton (kernels/segments.h,
 * surface.h: SCENE_SOLID_FD), only in scenes of at most SCENE_EMIT_FD_MAX_SOLIDS solids: it saves a quarter to a
 * third of the evaluations, but for 1000 spheres the build took 73 s instead of 15-19 s. Outside 0..nsolids-1 the
 * enclosures are everything, which rejects nothing (and stops Newton: its derivative is unbounded).
 *
 * A BRL-CAD primitive (scene_solid.prim) is no compiled expression: its parameters, placed in the world as
 * intervals (prim_place.c), are stored into a private array by its group's scene_gG_P (as double and as float
 * literals, under #ifdef IA_FP64), and its group's dispatchers call kernels/prim.h's with them, which the program
 * holds once (src/render_scene.c puts them before the solids): a primitive has no functions of its own. That cost
 * about 2.5-3 ms of build per solid here when each had its three functions (1000 arbs or ells, medians of 3 on a
 * loaded machine; dispatching by group cut havoc's first build from 19 to 13 s), against ~30 ms for an expression; with Fd too (a scene of primitives only) the build took 25 % longer for 19 % fewer
 * evaluations and no faster frame, so the limit counts all solids. scene_solid_P hands a primitive's type and
 * parameters to the walks' closed forms (kernels/prim_segments.h), with SCENE_SOLID_PIPES where a pipe's need more
 * room.
 *
 * Small scenes of regions also get the regions' union in SIMD lanes (SCENE_REGIONS_UNION, kernels/scene_union.h's
 * pre-pass), and SCENE_REGIONS_DISJOINT where no two regions can be in at one point (regions_disjoint), with the
 * solids in lanes too (emit_solids_in_lanes). A scene's distance tolerance is SCENE_DIST_TOL (kernels/weave.h's
 * zones); such a scene is not claimed at the union's leaf, which fuses nothing. */
#include "scene_emit.h"
#include "emit.h"
#include "expr_internal.h"
#include "ia/flush.h"
#include "prim_place.h"
#include "strbuf.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SCENE_EMIT_GROUP 32
#define SCENE_EMIT_FD_MAX_SOLIDS 64

/* The functions each solid has, as the dispatchers call them; Fd, last, only with SCENE_SOLID_FD. */
static const struct {
    const char *name, *type, *params, *args, *otherwise, *prim_call;
} dispatched[] = {
    {"F", "ia_interval", "ia_interval x, ia_interval y, ia_interval z, ia_interval t", "x, y, z, t",
     "return ia_make(-IA_INF, IA_INF);", "prim_F(type, p, x, y, z)"},
    {"f_grad", "ia_real", "ia_real x, ia_real y, ia_real z, ia_real t, ia_real *gx, ia_real *gy, ia_real *gz",
     "x, y, z, t, gx, gy, gz", "*gx = *gy = *gz = 0;\n    return 0;", "prim_f_grad(type, p, x, y, z, gx, gy, gz)"},
    {"Fd", "ia_interval",
     "ia_interval x, ia_interval y, ia_interval z, ia_interval t, ia_interval dx, ia_interval dy, ia_interval dz, "
     "ia_interval *dt",
     "x, y, z, t, dx, dy, dz, dt", "*dt = ia_entire();\n    return ia_entire();",
     "prim_Fd(type, p, x, y, z, dx, dy, dz, dt)"},
};

/* A group's primitives have no functions of their own: after the cases of its expressions, the group function
 * fetches solid k's parameters (scene_gG_P: -1 for a solid that is no primitive) into room for the group's largest
 * (prim_reals[g] reals, 0 when it has none) and calls prim.h's. */
static void emit_dispatcher(strbuf *b, const iacsg_scene *s, int which, const int *prim_reals) {
    const char *name = dispatched[which].name, *type = dispatched[which].type, *params = dispatched[which].params;
    const char *args = dispatched[which].args, *otherwise = dispatched[which].otherwise;
    int nsolids = s->nsolids, groups = (nsolids + SCENE_EMIT_GROUP - 1) / SCENE_EMIT_GROUP;
    for (int g = 0; g < groups; g++) {
        strbuf_printf(b, "__attribute__((noinline)) %s scene_g%d_%s(int k, %s) {\n    switch (k) {\n", type, g, name,
                      params);
        for (int k = g * SCENE_EMIT_GROUP; k < nsolids && k < (g + 1) * SCENE_EMIT_GROUP; k++)
            if (!s->solids[k].prim)
                strbuf_printf(b, "    case %d: return scene_s%d_%s(%s);\n", k, k, name, args);
        strbuf_printf(b, "    }\n");
        if (prim_reals[g] > 0)
            strbuf_printf(b, "    ia_real p[%d];\n    int type = scene_g%d_P(k, p, %d);\n    if (type >= 0)\n"
                             "        return %s;\n", prim_reals[g], g, prim_reals[g], dispatched[which].prim_call);
        strbuf_printf(b, "    %s\n}\n", otherwise);
    }
    strbuf_printf(b, "IA_FN %s scene_solid_%s(int k, %s) {\n    switch (k / %d) {\n", type, name, params,
                  SCENE_EMIT_GROUP);
    for (int g = 0; g < groups; g++)
        strbuf_printf(b, "    case %d: return scene_g%d_%s(k, %s);\n", g, g, name, args);
    strbuf_printf(b, "    }\n    %s\n}\n", otherwise);
}

/* scene_solid_P(k, p, cap): solid k's primitive type, its parameters stored into p, or -1 when it is no primitive
 * or they need more than cap reals (kernels/segments.h's closed forms; SCENE_SOLID_PRIMS says it is there). */
static void emit_parameters_dispatcher(strbuf *b, const iacsg_scene *s) {
    int pipes = 0;
    for (int k = 0; k < s->nsolids; k++)
        pipes |= s->solids[k].prim && s->solids[k].prim->type == SCENE_PRIM_PIPE;
    if (pipes) /* the walks' room for a pipe's parameters (kernels/segments.h) */
        strbuf_printf(b, "#define SCENE_SOLID_PIPES 1\n");
    strbuf_printf(b, "#define SCENE_SOLID_PRIMS 1\nIA_FN int scene_solid_P(int k, ia_real *p, int cap) {\n"
                     "    switch (k / %d) {\n", SCENE_EMIT_GROUP);
    for (int g = 0; g * SCENE_EMIT_GROUP < s->nsolids; g++) {
        int any = 0;
        for (int k = g * SCENE_EMIT_GROUP; k < s->nsolids && k < (g + 1) * SCENE_EMIT_GROUP; k++)
            any |= s->solids[k].prim != NULL;
        if (any)
            strbuf_printf(b, "    case %d: return scene_g%d_P(k, p, cap);\n", g, g);
    }
    strbuf_printf(b, "    }\n    return -1;\n}\n");
}

/* See scene_emit.h (printf's %a took 106 ms of havoc's command: some 200,000 literals). */
int scene_emit_hex(double x, char out[32]) {
    static const char digits[] = "0123456789abcdef";
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int n = 0, biased = (int)(bits >> 52 & 0x7ff), e = biased ? biased - 1023 : -1022;
    uint64_t mantissa = bits & ((UINT64_C(1) << 52) - 1);
    if (bits >> 63)
        out[n++] = '-';
    out[n++] = '0';
    out[n++] = 'x';
    out[n++] = biased ? '1' : '0';
    if (mantissa) {
        out[n++] = '.';
        for (int shift = 48; shift >= 0; shift -= 4)
            out[n++] = digits[mantissa >> shift & 15];
        while (out[n - 1] == '0')
            n--;
    } else if (!biased) {
        e = 0;
    }
    out[n++] = 'p';
    out[n++] = e < 0 ? '-' : '+';
    e = e < 0 ? -e : e;
    char rev[4];
    int k = 0;
    do {
        rev[k++] = (char)('0' + e % 10);
        e /= 10;
    } while (e);
    while (k)
        out[n++] = rev[--k];
    return n;
}

/* A bound as a literal of each precision, the program's float and double variants of the parameters (in p[0] and
 * p[1], under #ifdef IA_FP64, so that the preprocessor skips the other instead of expanding a macro per literal):
 * the double itself, and its float rounded outward (down for a lower bound); either moved out of the subnormals
 * (ia/flush.h). */
static void emit_bound(strbuf p[2], double x, int upper) {
    float f = prim_float_bound(x, upper);
    for (int fp64 = 0; fp64 < 2; fp64++) {
        double v = fp64 ? (upper ? ia_flush_hi_d(x) : ia_flush_lo_d(x)) : (double)f;
        char text[32];
        int n = isinf(v) ? snprintf(text, sizeof text, "%sINFINITY", v < 0 ? "-" : "") : scene_emit_hex(v, text);
        if (!fp64 && !isinf(v))
            text[n++] = 'f';
        strbuf_append(&p[fp64], text, (size_t)n);
    }
}

/* Text for both variants of the parameters. */
static void emit_both(strbuf p[2], const char *text) {
    for (int fp64 = 0; fp64 < 2; fp64++)
        strbuf_append(&p[fp64], text, strlen(text));
}

/* A primitive: its placed parameters as stores into p, the case k of its group's scene_gG_P, which returns its
 * type (stores, not an initialised array, which compilers put in __constant memory, 64 KB on some GPUs); the
 * dispatchers call kernels/prim.h's out-of-line functions with them. *reals: the room they need. */
static iacsg_status emit_primitive(strbuf params[2], const scene_solid *solid, int k, int *reals, iacsg_error *err) {
    prim_placed placed;
    iacsg_status st = prim_place(solid->prim, solid->name, &placed, err);
    if (st != IACSG_OK)
        return st;
    int nreal = 2 * placed.n, padded = (nreal + 7) / 8 * 8;
    char text[96];
    snprintf(text, sizeof text, "    case %d:\n        if (cap < %d)\n            return -1;\n", k, padded);
    emit_both(params, text);
    for (int i = 0; i < padded; i++) {
        if (i % 8 == 0)
            emit_both(params, "        vstore8((prim_real8)(");
        if (i < nreal)
            emit_bound(params, i % 2 ? placed.hi[i / 2] : placed.lo[i / 2], i % 2);
        else
            emit_both(params, "0");
        snprintf(text, sizeof text, i % 8 == 7 ? "), %d, p);\n" : ", ", i / 8);
        emit_both(params, text);
    }
    snprintf(text, sizeof text, "        return %d;\n", placed.type);
    emit_both(params, text);
    *reals = padded;
    prim_placed_free(&placed);
    return IACSG_OK;
}

/* The union of the regions as one expression (kernels/render_scene.cl's pre-pass), over the regions' trees:
 * union min, intersection max, difference max(a, -b), "f > 0" -f. A region is in at a point only where this is
 * <= 0 (in: f < 0 at an INSIDE leaf, not in: f >= 0; min and max keep both). Only in scenes of at most
 * SCENE_EMIT_UNION_MAX solids and regions, all expressions defined everywhere (continuous: the pre-pass's sign
 * argument needs it), and with at least one region. */
#define SCENE_EMIT_UNION_MAX 8
static int union_of_tree(dag *d, const uint32_t *nodes, int k, const int *solid, iacsg_error *err) {
    uint32_t node = nodes[k];
    int op = CSG_NODE_OP(node), arg = (int)CSG_NODE_ARG(node);
    if (op == CSG_INSIDE || op == CSG_OUTSIDE)
        return op == CSG_INSIDE ? solid[arg] : dag_add(d, OP_NEG, solid[arg], -1, 0, err);
    int a = union_of_tree(d, nodes, k + 1, solid, err);
    if (a < 0 || op == CSG_NOT)
        return a < 0 ? a : dag_add(d, OP_NEG, a, -1, 0, err);
    int b = union_of_tree(d, nodes, arg, solid, err);
    if (b >= 0 && op == CSG_DIFFERENCE)
        b = dag_add(d, OP_NEG, b, -1, 0, err);
    return b < 0 ? b : dag_add(d, op == CSG_UNION ? OP_MIN : OP_MAX, a, b, 0, err);
}

/* Whether region tree node k holds where the solids set in `inside` are in and the others out. */
static int region_holds(const uint32_t *nodes, int k, unsigned inside) {
    uint32_t node = nodes[k];
    int op = CSG_NODE_OP(node), arg = (int)CSG_NODE_ARG(node);
    if (op == CSG_INSIDE || op == CSG_OUTSIDE)
        return (int)(inside >> arg & 1) == (op == CSG_INSIDE);
    int a = region_holds(nodes, k + 1, inside);
    if (op == CSG_NOT)
        return !a;
    int b = region_holds(nodes, arg, inside);
    return op == CSG_UNION ? a || b : op == CSG_INTERSECT ? a && b : a && !b;
}

/* Whether no two regions can both be in at a point, whatever the solids' shapes: no assignment of in and out to
 * the solids (at most SCENE_EMIT_UNION_MAX) makes two regions' trees hold. Then no partition has an overlap (both
 * regions certainly in there would give such an assignment), and kernels/scene_union.h claims a ray's partition
 * at the union's leaf without weaving on to look for one (SCENE_REGIONS_DISJOINT). */
static int regions_disjoint(const iacsg_scene *s) {
    for (unsigned inside = 0; inside < 1u << s->nsolids; inside++) {
        int holding = 0;
        for (int k = 0; k < s->nitems; k++)
            holding += s->items[k].kind == SCENE_REGION && region_holds(s->nodes, s->items[k].tree, inside);
        if (holding > 1)
            return 0;
    }
    return 1;
}

/* The union's vector code when the scene qualifies (iacsg_Fv, and where Newton pays iacsg_Fdv; else NULL). The
 * caller free()s it. */
static iacsg_status emit_regions_union(const iacsg_scene *s, char **vector, iacsg_error *err) {
    *vector = NULL;
    int regions = 0;
    for (int k = 0; k < s->nitems; k++)
        regions += s->items[k].kind == SCENE_REGION;
    if (regions == 0 || regions > SCENE_EMIT_UNION_MAX || s->nsolids > SCENE_EMIT_UNION_MAX)
        return IACSG_OK;
    for (int k = 0; k < s->nsolids; k++)
        if (!s->solids[k].expr || emit_may_be_undefined(&s->solids[k].expr->simple, s->solids[k].expr->root))
            return IACSG_OK;
    dag d;
    dag_init(&d);
    static const int same[4] = {-1, -1, -1, -1};
    int solid[SCENE_EMIT_UNION_MAX], root = -1, failed = 0;
    for (int k = 0; k < s->nsolids && !failed; k++)
        failed = (solid[k] = dag_substitute(&s->solids[k].expr->simple, s->solids[k].expr->root, &d, same, NULL, 0,
                                            err)) < 0;
    for (int k = 0; k < s->nitems && !failed; k++) {
        if (s->items[k].kind != SCENE_REGION)
            continue;
        int r = union_of_tree(&d, s->nodes, s->items[k].tree, solid, err);
        root = r < 0 || root < 0 ? r : dag_add(&d, OP_MIN, root, r, 0, err);
        failed = root < 0;
    }
    iacsg_expr *u = NULL;
    iacsg_status st = failed ? err->status : expr_from_dag(&d, root, "regions", 1, &u, err);
    dag_free(&d);
    if (st == IACSG_OK)
        st = emit_cl(&u->simple, u->root, "iacsg", 1, vector, err); /* march.h's secondary rays use it */
    iacsg_expr_destroy(u);
    return st;
}

/* For disjoint regions (kernels/scene_union.h claims at the union's leaf): each solid's code in lanes as scene_vK_Fv
 * and their dispatcher scene_solid_Fv, for the solids' states over the packet's leaves. */
static iacsg_status emit_solids_in_lanes(strbuf *b, const iacsg_scene *s, iacsg_error *err) {
    for (int k = 0; k < s->nsolids; k++) {
        char prefix[32], *text = NULL;
        snprintf(prefix, sizeof prefix, "scene_v%d", k);
        iacsg_status st = iacsg_expr_emit_cl(s->solids[k].expr, prefix, &text, err);
        if (st != IACSG_OK)
            return st;
        strbuf_printf(b, "%s", text);
        free(text);
    }
    strbuf_printf(b, "IA_FN iav scene_solid_Fv(int k, iav x, iav y, iav z, iav t) {\n    switch (k) {\n");
    for (int k = 0; k < s->nsolids; k++)
        strbuf_printf(b, "    case %d: return scene_v%d_Fv(x, y, z, t);\n", k, k);
    strbuf_printf(b, "    }\n    return iav_const(-IA_INF, IA_INF);\n}\n");
    return IACSG_OK;
}

iacsg_status scene_emit_cl(const iacsg_scene *s, char **source, iacsg_error *err) {
    *source = NULL;
    strbuf b = {0}, params[2] = {{0}, {0}}, code = {0}, dispatch = {0};
    int with_fd = s->nsolids <= SCENE_EMIT_FD_MAX_SOLIDS, open_group = -1;
    strbuf_printf(&b, "/* generated by iacsg: the %d solids of a scene */\n#define IACSG_SCALAR_CODE 1\n%s", s->nsolids,
                  with_fd ? "#define IACSG_SCALAR_FD 1\n#define SCENE_SOLID_FD 1\n" : "");
    if (s->dist_tol > 0)
        strbuf_printf(&b, "#define SCENE_DIST_TOL %.17g\n", s->dist_tol);
    int *prim_reals = calloc((size_t)(s->nsolids / SCENE_EMIT_GROUP + 1), sizeof(int));
    iacsg_status st = prim_reals ? IACSG_OK : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory generating code");
    for (int k = 0; st == IACSG_OK && k < s->nsolids; k++) {
        char prefix[32], *text = NULL;
        snprintf(prefix, sizeof prefix, "scene_s%d", k);
        if (s->solids[k].prim && open_group != k / SCENE_EMIT_GROUP) { /* the group's parameter function */
            if (open_group >= 0)
                emit_both(params, "    }\n    return -1;\n}\n");
            open_group = k / SCENE_EMIT_GROUP;
            char head[128];
            snprintf(head, sizeof head,
                     "__attribute__((noinline)) int scene_g%d_P(int k, ia_real *p, int cap) {\n    switch (k) {\n",
                     open_group);
            emit_both(params, head);
        }
        int reals = 0;
        st = s->solids[k].prim ? emit_primitive(params, &s->solids[k], k, &reals, err)
                               : iacsg_expr_emit_cl(s->solids[k].expr, prefix, &text, err);
        if (reals > prim_reals[k / SCENE_EMIT_GROUP])
            prim_reals[k / SCENE_EMIT_GROUP] = reals;
        if (text)
            strbuf_printf(&code, "%s", text);
        free(text);
    }
    if (open_group >= 0) {
        emit_both(params, "    }\n    return -1;\n}\n");
        emit_parameters_dispatcher(&dispatch, s);
    }
    char *params32 = strbuf_finish(&params[0]), *params64 = strbuf_finish(&params[1]);
    char *dispatch_text = strbuf_finish(&dispatch), *code_text = strbuf_finish(&code), *vector = NULL;
    if (st == IACSG_OK)
        st = emit_regions_union(s, &vector, err);
    if (st == IACSG_OK) {
        if (params64 && params32)
            strbuf_printf(&b, "#ifdef IA_FP64\n%s#else\n%s#endif\n%s", params64, params32,
                          dispatch_text ? dispatch_text : "");
        strbuf_printf(&b, "%s", code_text ? code_text : "");
        for (size_t which = 0; which < sizeof dispatched / sizeof dispatched[0] - !with_fd; which++)
            emit_dispatcher(&b, s, (int)which, prim_reals);
        /* last: without IACSG_SCALAR_CODE the program holds kernels/packet.h and tile.h */
        int disjoint = vector && !(s->dist_tol > 0) && regions_disjoint(s); /* a claim at the leaf fuses nothing */
        if (vector)
            strbuf_printf(&b, "#undef IACSG_SCALAR_CODE\n#define SCENE_REGIONS_UNION %d\n%s", s->nsolids,
                          disjoint ? "#define SCENE_REGIONS_DISJOINT 1\n" : "");
        if (disjoint) /* then the union's: IACSG_FDV says whether it (not a solid) has iacsg_Fdv */
            st = emit_solids_in_lanes(&b, s, err);
        if (vector)
            strbuf_printf(&b, "#undef IACSG_FDV\n#undef IACSG_FDV_MARCH\n%s", vector);
    }
    free(prim_reals);
    free(params32);
    free(params64);
    free(dispatch_text);
    free(code_text);
    free(vector);
    *source = strbuf_finish(&b);
    if (st != IACSG_OK) {
        free(*source);
        *source = NULL;
        return st;
    }
    return *source ? IACSG_OK : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory generating code");
}
