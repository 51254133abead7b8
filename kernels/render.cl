/* kernels/render.cl -- the render entry point: one work-item per pixel of a band of rows.
 *
 * Per pixel: the camera ray (camera.h), clipped to the bounds (rays that miss the box cost nothing more), the
 * first root by stackless bisection (bisect.h), then the normal and the colour at the leaf's midpoint
 * (shade.h). Outputs, indexed by pixel of the whole image: rgb (3 floats, display-encoded), depth (the leaf's
 * start t, +inf on a miss), normal (3 floats, 0 on a miss), and with KERNEL_STATS the evaluation count.
 * The work-groups are 2D tiles, so neighbouring rays, which take similar paths, run together.
 */
#include "camera.h"
#include "bisect.h"
#include "shade.h"

/* The depth image is float32: in double mode round the start down, so it stays before the first root. */
static inline float depth_round_down(ia_real t) {
    float f = (float)t;
    return (ia_real)f > t ? nextafter(f, -INFINITY) : f;
}

__kernel void iacsg_render(__constant ia_real *params, int flags, int width, int height, int row0,
                           __global float *rgb, __global float *depth, __global float *normal,
                           __global uint *evals) {
    int i = (int)get_global_id(0), j = row0 + (int)get_global_id(1);
    if (i >= width || j >= height)
        return;
    size_t pixel = (size_t)j * (size_t)width + (size_t)i;
    ia_real o[3], d[3], n[3] = {0, 0, 0}, t_near, t_far, lo, hi;
    float color[3];
    kernel_u32 count = 0;
    ia_interval time = ia_point(params[PARAM_TIME]);
    camera_ray(params, flags & RENDER_ORTHO, i, j, width, height, o, d);
    int hit = camera_clip(params, o, d, &t_near, &t_far) &&
              bisect_first_root(o, d, t_near, ia_hi(t_far - t_near), params[PARAM_EPS], time, &lo, &hi, &count);
    if (hit) {
        ia_real t = lo * (ia_real)0.5 + hi * (ia_real)0.5;
        shade_normal(o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2], time.lo, d, n);
        shade_surface(params, n, d, color);
    } else {
        shade_background(j, height, color);
    }
    depth[pixel] = hit ? depth_round_down(lo) : INFINITY;
    for (int c = 0; c < 3; c++) {
        rgb[3 * pixel + c] = color[c];
        normal[3 * pixel + c] = (float)n[c];
    }
#ifdef KERNEL_STATS
    evals[pixel] = count;
#else
    (void)evals;
#endif
}
