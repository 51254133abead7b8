/* kernels/scene_frame.h -- what the segment path's camera kernels (kernels/render_scene.cl) and their effects
 * (kernels/scene_lit.h) share: a work-item's frame (its outputs and tables) and a hit's unit normal.
 */
#ifndef KERNELS_SCENE_FRAME_H
#define KERNELS_SCENE_FRAME_H

/* The unit normal at o + t d of the solid: its gradient (scene_solid_f_grad). */
static void scene_gradient(scene_prims q, int solid, const ia_real o[3], const ia_real d[3], ia_real t, ia_real time,
                           ia_real g[3]) {
    scene_solid_f_grad(q, solid, o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2], time, &g[0], &g[1], &g[2]);
}

/* What the packets of a work-item share: the frame's parameters, tables and outputs (the kernel's arguments). */
typedef struct {
    int flags, width, height, row_end;
    __global const int *items;
    __global const uint *nodes;
    __global const float *albedo;
    __global float *rgb, *depth, *normal, *ids;
    __global int *overlap;
    __global uint *counts;
    __global int *overflow, *noverflow;
    int out0; /* where a packet's lanes write: -1 their pixels, else out0 + lane (-aa's samples) */
    __constant ia_real *fx; /* the effects' block where the packets apply them (scene_packet_lit), else 0 */
    __global uint *fx_counts; /* with them and KERNEL_STATS: each pixel's secondary rays and their evaluations */
    int linear; /* with them: the colours in linear light, unclamped (-aa's samples, summed by the host), else shown */
    int aa;     /* the image's pixels per view pixel across (-aa's samples: their pixel's row is row / aa) */
    ia_real fx_eps; /* the secondary rays' leaves (the view's eps, also for -aa's samples) */
} scene_frame;

#endif
