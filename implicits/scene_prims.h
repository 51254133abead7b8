/* implicits/scene_prims.h -- the table of a scene's BRL-CAD primitives that the device reads (kernels/scene_prims.h
 * has its layout): each solid's type, and each primitive placed in the world (prim_place.c) with its intervals'
 * bounds as reals of the program's precision: a double program's the doubles moved out of the subnormals, a float
 * program's rounded outward to floats (prim_float_bound). src/render_scene.c uploads it once per renderer; the
 * scene's program (scene_emit.c) holds none of its values.
 *
 *   iacsg_scene --prim_place per primitive--> lo, hi bounds --> flushed / rounded reals --> the device's buffer
 */
#ifndef IACSG_SCENE_PRIMS_H
#define IACSG_SCENE_PRIMS_H
#include "scene.h"
#include <stddef.h>

/* The table in *reals (malloc'ed: doubles with fp64, else floats; the caller free()s it; reals may be NULL to only
 * measure), its length in *count, and in *most the most reals one primitive's parameters take (0 without
 * primitives). A primitive that describes no solid is IACSG_ERR_ARG with prim_place's message. */
iacsg_status scene_prims_table(const iacsg_scene *s, int fp64, void **reals, size_t *count, int *most,
                               iacsg_error *err);

#endif
