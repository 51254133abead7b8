/* implicits/scene_emit.c -- see scene_emit.h. Each dispatcher sends a primitive to prim.h's functions and an
 * expression to its group's function: the solids in groups of SCENE_EMIT_GROUP, each group holding an expression a
 * function of its own (not inlined) with a switch over its expressions, whose code is inlined there: inlined
 * wherever the kernels call the dispatchers, 1000 spheres took minutes to build. The build costs about 30 ms of CPU
 * per sphere (PoCL, LLVM 15). scene_solid_Fd, each solid's value and derivative along a ray (P_Fd, which the
 * compiler emits under IACSG_SCALAR_FD), is for the walks' interval Newton (kernels/segments.h, surface.h:
 * SCENE_SOLID_FD), only in scenes of at most SCENE_EMIT_FD_MAX_SOLIDS solids: it saves a quarter to a third of the
 * evaluations, but for 1000 spheres the build took 73 s instead of 15-19 s. Outside 0..nsolids-1 the enclosures
 * are everything, which rejects nothing (and stops Newton: its derivative is unbounded).
 *
 * A BRL-CAD primitive (scene_solid.prim) is no code in the program: its type and parameters, placed in the world as
 * intervals, are in a device buffer (implicits/scene_prims.c, kernels/scene_prims.h's layout), which every
 * dispatcher takes (q), and a primitive goes to kernels/prim.h's functions (held once by the program:
 * src/render_scene.c puts them before the solids) with its parameters copied from it (scene_prim_F, _f_grad, _Fd,
 * out of line). So a scene of primitives only has a program that depends on neither their values nor their count:
 * only on whether it has pipes (SCENE_SOLID_PIPES, and the room for the longest, a power of two), whether it has at
 * most SCENE_EMIT_FD_MAX_SOLIDS solids (SCENE_SOLID_FD) and its distance tolerance; one cached build serves all such
 * models. (Emitted as literals, stores into a private array per solid, havoc's ~200,000 cost its first build 13 s and
 * every cached one the bitcode's parse, 47 ms: tests/bench/NOTES.md.) With Fd too (a scene of primitives only) the
 * build took 25 % longer for 19 % fewer evaluations and no faster frame, so the limit counts all solids.
 *
 * Small scenes of regions also get the regions' union in SIMD lanes (SCENE_REGIONS_UNION, kernels/scene_union.h's
 * pre-pass), and SCENE_REGIONS_DISJOINT where no two regions can be in at one point (regions_disjoint), with the
 * solids in lanes too (emit_solids_in_lanes): only scenes of expressions, compiled code anyway. A scene's distance
 * tolerance is SCENE_DIST_TOL (kernels/weave.h's zones); such a scene is not claimed at the union's leaf, which
 * fuses nothing. */
#include "scene_emit.h"
#include "emit.h"
#include "expr_internal.h"
#include "kernels/prim.h"
#include "scene_prims.h"
#include "strbuf.h"
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

/* Whether group g (solids g SCENE_EMIT_GROUP on) holds an expression: only those have a group function. */
static int group_has_expression(const iacsg_scene *s, int g) {
    for (int k = g * SCENE_EMIT_GROUP; k < s->nsolids && k < (g + 1) * SCENE_EMIT_GROUP; k++)
        if (!s->solids[k].prim)
            return 1;
    return 0;
}

/* The dispatcher scene_solid_<which>(q, k, ...): a primitive (the table q says which solids are, kernels/
 * scene_prims.h) through scene_prim_<which>, which copies its parameters into room for the scene's largest
 * (prim_room reals, 0 without primitives) and calls prim.h's; an expression through its group's function. */
static void emit_dispatcher(strbuf *b, const iacsg_scene *s, int which, int prim_room) {
    const char *name = dispatched[which].name, *type = dispatched[which].type, *params = dispatched[which].params;
    const char *args = dispatched[which].args, *otherwise = dispatched[which].otherwise;
    int nsolids = s->nsolids, groups = (nsolids + SCENE_EMIT_GROUP - 1) / SCENE_EMIT_GROUP, expressions = 0;
    for (int g = 0; g < groups; g++) {
        if (!group_has_expression(s, g))
            continue;
        expressions = 1;
        strbuf_printf(b, "__attribute__((noinline)) %s scene_g%d_%s(int k, %s) {\n    switch (k) {\n", type, g, name,
                      params);
        for (int k = g * SCENE_EMIT_GROUP; k < nsolids && k < (g + 1) * SCENE_EMIT_GROUP; k++)
            if (!s->solids[k].prim)
                strbuf_printf(b, "    case %d: return scene_s%d_%s(%s);\n", k, k, name, args);
        strbuf_printf(b, "    }\n    %s\n}\n", otherwise);
    }
    if (prim_room > 0)
        strbuf_printf(b, "__attribute__((noinline)) %s scene_prim_%s(scene_prims q, int k, %s) {\n"
                         "    ia_real p[%d];\n    int type = scene_solid_P(q, k, p, %d);\n    return %s;\n}\n",
                      type, name, params, prim_room, prim_room, dispatched[which].prim_call);
    strbuf_printf(b, "IA_FN %s scene_solid_%s(scene_prims q, int k, %s) {\n", type, name, params);
    if (prim_room > 0)
        strbuf_printf(b, "    if (scene_prims_type(q, k) >= 0)\n        return scene_prim_%s(q, k, %s);\n", name,
                      args);
    else
        strbuf_printf(b, "    (void)q;\n");
    if (expressions)
        strbuf_printf(b, "    switch (k / %d) {\n", SCENE_EMIT_GROUP);
    for (int g = 0; g < groups; g++)
        if (group_has_expression(s, g))
            strbuf_printf(b, "    case %d: return scene_g%d_%s(k, %s);\n", g, g, name, args);
    strbuf_printf(b, "%s    %s\n}\n", expressions ? "    }\n" : "", otherwise);
}

/* The room the dispatchers give a primitive's parameters (0 without primitives): an arb8's, the most of the types
 * but a pipe's, or for a scene with pipes the power of two that holds its longest, so that models of the same kinds
 * mostly share a program. *pipes: whether it has any (SCENE_SOLID_PIPES). */
static iacsg_status primitives_room(const iacsg_scene *s, int *room, int *pipes, iacsg_error *err) {
    size_t count;
    int most;
    iacsg_status st = scene_prims_table(s, 0, NULL, &count, &most, err);
    *pipes = 0;
    for (int k = 0; k < s->nsolids; k++)
        *pipes |= s->solids[k].prim && s->solids[k].prim->type == SCENE_PRIM_PIPE;
    *room = most == 0 ? 0 : 2 * PRIM_ARB8_N;
    while (*pipes && *room < most)
        *room *= 2;
    return st;
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
    strbuf b = {0}, code = {0};
    int with_fd = s->nsolids <= SCENE_EMIT_FD_MAX_SOLIDS, prim_room = 0, pipes = 0;
    strbuf_printf(&b, "/* generated by iacsg: a scene's solids */\n#define IACSG_SCALAR_CODE 1\n%s",
                  with_fd ? "#define IACSG_SCALAR_FD 1\n#define SCENE_SOLID_FD 1\n" : "");
    if (s->dist_tol > 0)
        strbuf_printf(&b, "#define SCENE_DIST_TOL %.17g\n", s->dist_tol);
    iacsg_status st = primitives_room(s, &prim_room, &pipes, err);
    if (prim_room > 0) /* kernels/segments.h's closed forms; with pipes, its room for their parameters */
        strbuf_printf(&b, "#define SCENE_SOLID_PRIMS 1\n%s", pipes ? "#define SCENE_SOLID_PIPES 1\n" : "");
    for (int k = 0; st == IACSG_OK && k < s->nsolids; k++) {
        if (s->solids[k].prim)
            continue;
        char prefix[32], *text = NULL;
        snprintf(prefix, sizeof prefix, "scene_s%d", k);
        st = iacsg_expr_emit_cl(s->solids[k].expr, prefix, &text, err);
        if (text)
            strbuf_printf(&code, "%s", text);
        free(text);
    }
    char *code_text = strbuf_finish(&code), *vector = NULL;
    if (st == IACSG_OK)
        st = emit_regions_union(s, &vector, err);
    if (st == IACSG_OK) {
        strbuf_printf(&b, "%s", code_text ? code_text : "");
        for (size_t which = 0; which < sizeof dispatched / sizeof dispatched[0] - !with_fd; which++)
            emit_dispatcher(&b, s, (int)which, prim_room);
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
