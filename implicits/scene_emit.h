/* implicits/scene_emit.h -- the OpenCL C of a scene's solids for the segment path: each solid k's functions
 * (iacsg_expr_emit_cl with the prefix scene_s<k>, or for a BRL-CAD primitive calls of kernels/prim.h's functions
 * with its placed parameters; a primitive that describes no solid is IACSG_ERR_ARG, prim_place.c's message) and
 * dispatchers over the solid's number,
 *   IA_FN ia_interval scene_solid_F(int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t);
 *   IA_FN ia_real scene_solid_f_grad(int k, ia_real x, ia_real y, ia_real z, ia_real t,
 *                                    ia_real *gx, ia_real *gy, ia_real *gz);
 *   IA_FN ia_interval scene_solid_Fd(int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t,
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

/* A finite double as the exact C hexadecimal literal that printf's "%a" writes (glibc's form: 0x1.8p+1, 0x0p+0,
 * subnormals as 0x0.xp-1022), without printf. Returns its length (at most 24). */
int scene_emit_hex(double x, char out[32]);

#endif
