/* src/render_effects_centre.h -- the segment path's centre paths kept on the device, where none can have a child
 * or each at most one (src/render_effects.c decides; kernels/scene_centre.cl computes). */
#ifndef IACSG_RENDER_EFFECTS_CENTRE_H
#define IACSG_RENDER_EFFECTS_CENTRE_H
#include "render_effects_trace.h"

/* The segment path's centre paths of pixels[0 .. n), wholly on the device (kernels/scene_centre.cl): their camera
 * rays and hits (the frame's depth, normals and ids), with `shadows` their shadow rays (leaves eps wide) traced,
 * then their colours (iacsg_scene_shade) into out, 6 floats a path as fx_scene_shade's, or (out NULL, without
 * `children`) display-encoded into their pixels of frame->rgb, as fx_encode encodes. block: the effects'
 * parameters (EFFECTS_COUNT, kernels/effects.h). Without `children` no path may have a child (every item opaque,
 * no reflected ray). With `children` (lit, no shadows, at most one child a path: no item both reflects with
 * -bounces and lets light through), each hit's child (its reflected ray, or its ray on through a transparent hit)
 * is traced (leaves eps wide) and shaded too, each path's colour then its own and its child's, weighted as the
 * host's paths weight them; a child whose hit has a child of its own goes, with its hit, to rest (room for n;
 * *nrest of them) for the caller's paths to shade and follow, its colour not in out. */
iacsg_status fx_scene_centre(fx_tracer *t, const double *block, const int *pixels, size_t n,
                             const iacsg_frame *frame, int shadows, double eps, const float *palette,
                             int children, float *out, fx_path *rest, size_t *nrest, iacsg_error *err);

#endif
