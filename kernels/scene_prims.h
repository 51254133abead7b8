/* kernels/scene_prims.h -- a scene's BRL-CAD primitives on the device: their types and placed parameters in one
 * buffer of reals of the program's precision (implicits/scene_prims.c fills it, src/render_scene.c uploads it once
 * per renderer), not literals in the program, so that a scene's program does not depend on its primitives' values
 * or count and one cached build serves every model of the same kinds (implicits/scene_emit.c).
 *
 *   q[0]                          the number of solids n
 *   q[1 + 3k], q[2 + 3k], q[3 + 3k] solid k's type (PRIM_*, -1 for an expression), the offset of its parameters
 *                                 in q and their count, a multiple of 8 (zeros after kernels/prim.h's intervals)
 *   q[offset .. offset + count)   its parameters (prim.h's lo, hi pairs)
 *
 * The integers are exact in float (offsets below 2^24). Without global pointers at program scope (OpenCL 1.2),
 * every caller of the solids' dispatchers is handed q: the walks keep it (segments.h), the surfaces' functions and
 * the kernels' shading take it. The dispatchers copy a primitive's parameters into a private array and call
 * prim.h's functions with it.
 */
#ifndef KERNELS_SCENE_PRIMS_H
#define KERNELS_SCENE_PRIMS_H
#include "compat.h"
#include "prim.h"

typedef const KERNEL_GLOBAL ia_real *scene_prims;

#define SCENE_PRIMS_HEADER 1
#define SCENE_PRIMS_ENTRY 3
/* A primitive's parameters take a multiple of this many reals (the device copies them 8 at a time). */
#define SCENE_PRIMS_ALIGN 8

/* Solid k's primitive type, or -1 for an expression or a k outside the scene. */
IA_FN int scene_prims_type(scene_prims q, int k) {
    return k >= 0 && k < (int)q[0] ? (int)q[SCENE_PRIMS_HEADER + SCENE_PRIMS_ENTRY * k] : -1;
}

/* Solid k's primitive type with its parameters copied into p, or -1 when it is no primitive or they need more
 * than cap reals (kernels/segments.h's closed forms, which a longer pipe leaves to bisection). */
IA_FN int scene_solid_P(scene_prims q, int k, ia_real *p, int cap) {
    int type = scene_prims_type(q, k);
    if (type < 0)
        return -1;
    scene_prims entry = q + SCENE_PRIMS_HEADER + SCENE_PRIMS_ENTRY * k;
    int offset = (int)entry[1], count = (int)entry[2];
    if (cap < count)
        return -1;
#if IA_DEVICE
    for (int i = 0; i < count; i += SCENE_PRIMS_ALIGN)
        vstore8(vload8(0, q + offset + i), 0, p + i);
#else
    for (int i = 0; i < count; i++)
        p[i] = q[offset + i];
#endif
    return type;
}

#endif
