/* kernels/effects.h -- what the host's effects (src/render_effects.c) and the trace kernels of both paths
 * (kernels/effects.cl, kernels/scene_effects.cl) share: the layout of a secondary ray in the ray buffer. */
#ifndef KERNELS_EFFECTS_H
#define KERNELS_EFFECTS_H

/* A ray: origin x y z, direction x y z, the part [tn, tf] of it to search; in the working precision. */
#define EFFECTS_RAY_REALS 8

#endif
