/* implicits/scene_emit.h -- the OpenCL C of a scene's solids for the segment path: each expression solid k's
 * functions (iacsg_expr_emit_cl with the prefix scene_s<k>; a BRL-CAD primitive has none: its parameters are in the
 * table q, implicits/scene_prims.h, and it goes to kernels/prim.h's functions; a primitive that describes no solid is
 * IACSG_ERR_ARG, prim_place.c's message) and dispatchers over the solid's number,
 *   IA_FN ia_interval scene_solid_F(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t);
 *   IA_FN ia_real scene_solid_f_grad(scene_prims q, int k, ia_real x, ia_real y, ia_real z, ia_real t,
 *                                    ia_real *gx, ia_real *gy, ia_real *gz);
 *   IA_FN ia_interval scene_solid_Fd(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t,
 *                                    ia_interval dx, ia_interval dy, ia_interval dz, ia_interval *dt);
 * (the value and the derivative along a ray, [-inf, +inf] where an operation may be undefined, for interval
 * Newton; where the program defines SCENE_SOLID_FD: scenes of at most 64 solids, for the build time), which
 * kernels/segments.h and kernels/surface.h call. The solids' code is the scalar code (IACSG_SCALAR_CODE):
 * the segment path traces one ray at a time and only shades in lanes. */
#ifndef IACSG_SCENE_EMIT_H
#define IACSG_SCENE_EMIT_H
#include "scene.h"

/* The source, malloc'ed (the caller free()s *source). */
iacsg_status scene_emit_cl(const iacsg_scene *s, char **source, iacsg_error *err);

#endif
