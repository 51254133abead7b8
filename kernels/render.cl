/* kernels/render.cl -- the entry points, run for each band of rows: iacsg_tiles, one work-item per tile, then
 * iacsg_render, one work-item per pixel, in work-groups that are the tiles (neighbouring rays take similar
 * paths through the bisection, so they run together).
 *
 * Per pixel: the camera ray (camera.h), clipped to the bounds (rays that miss the box cost nothing more); if the
 * tile may hold surface, the first root by stackless bisection (bisect.h) from the tile's first coarse leaf on
 * (tile.h); then the normal and the colour at the leaf's midpoint (shade.h). Outputs,
 * indexed by pixel of the whole image: rgb (3 floats, display-encoded), depth (the leaf's start t, +inf on a
 * miss), normal (3 floats, 0 on a miss), and with KERNEL_STATS the evaluation counts.
 */
#include "camera.h"
#include "bisect.h"
#include "tile.h"
#include "shade.h"

/* tiles[2k], tiles[2k+1]: the level and index of tile k's first coarse leaf (row-major, tiles_x per row), as
 * reals (exact: the index has fewer bits than the mantissa, see traverse.h); level -1 when no ray of the tile
 * can meet the surface. */
__kernel void iacsg_tiles(__constant ia_real *params, int flags, int width, int height, int tile_row0,
                          __global ia_real *tiles, __global uint *evals) {
    int tx = (int)get_global_id(0), ty = tile_row0 + (int)get_global_id(1);
    int tiles_x = (width + TILE_SIZE - 1) / TILE_SIZE;
    if (tx >= tiles_x || ty * TILE_SIZE >= height)
        return;
    int i0 = tx * TILE_SIZE, j0 = ty * TILE_SIZE;
    int i1 = min(i0 + TILE_SIZE, width) - 1, j1 = min(j0 + TILE_SIZE, height) - 1;
    int level = -1;
    bisect_index leaf = 0;
    kernel_u32 count = 0;
    tile_first_leaf(params, flags & RENDER_ORTHO, i0, i1, j0, j1, width, height, ia_point(params[PARAM_TIME]),
                    &level, &leaf, &count);
    size_t k = (size_t)ty * (size_t)tiles_x + (size_t)tx;
    tiles[2 * k] = (ia_real)level;
    tiles[2 * k + 1] = (ia_real)leaf;
#ifdef KERNEL_STATS
    evals[k] = count;
#else
    (void)evals;
#endif
}

/* The first root of the ray in [t_near, t_far]: the walk of the frame's tree from the tile's first coarse leaf
 * (level, leaf), or from the node holding t_near at that level when the ray enters the bounds after the leaf. */
static inline int trace(const KERNEL_CONSTANT ia_real *p, const ia_real o[3], const ia_real d[3], ia_real t_near,
                        ia_real t_far, int level, bisect_index leaf, ia_interval time, ia_real *lo, ia_real *hi,
                        kernel_u32 *count) {
    ia_real t0, w;
    frame_root(p, &t0, &w);
    bisect_index i = max(leaf, node_at(t0, w, level, t_near));
    return bisect_first_root(o, d, t0, w, level, i, t_near, t_far, p[PARAM_EPS], time, lo, hi, count);
}

/* The depth image is float32: in double mode round the start down, so it stays before the first root. */
static inline float depth_round_down(ia_real t) {
    float f = (float)t;
    return (ia_real)f > t ? nextafter(f, -INFINITY) : f;
}

__kernel void iacsg_render(__constant ia_real *params, int flags, int width, int height, int row0,
                           __global const ia_real *tiles, __global float *rgb, __global float *depth,
                           __global float *normal, __global uint *evals) {
    int i = (int)get_global_id(0), j = row0 + (int)get_global_id(1);
    if (i >= width || j >= height)
        return;
    size_t pixel = (size_t)j * (size_t)width + (size_t)i;
    ia_real o[3], d[3], n[3] = {0, 0, 0}, t_near, t_far, lo, hi;
    float color[3];
    kernel_u32 count = 0;
    ia_interval time = ia_point(params[PARAM_TIME]);
    camera_ray(params, flags & RENDER_ORTHO, i, j, width, height, o, d);
    size_t tile = (size_t)(j / TILE_SIZE) * (size_t)((width + TILE_SIZE - 1) / TILE_SIZE) + (size_t)(i / TILE_SIZE);
    int level = (int)tiles[2 * tile];
    int hit = level >= 0 && camera_clip(params, o, d, &t_near, &t_far) &&
              trace(params, o, d, t_near, t_far, level, (bisect_index)tiles[2 * tile + 1], time, &lo, &hi, &count);
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
