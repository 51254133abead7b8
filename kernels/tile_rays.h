/* kernels/tile_rays.h -- the rays of a block of pixels as one box-valued ray, and the root of the bisection tree
 * that every ray of a frame walks: what a coarse pass over a block (kernels/tile.h for the first-root path,
 * kernels/surface.h for level-set surfaces) shares with its rays.
 *
 * Rigor: tile_rays_of mirrors every rounded operation of camera_ray with the interval operation that encloses
 * its rounded result (an outward-rounded op contains the round-to-nearest one; / and sqrt, where the device does
 * not round them correctly, widened by their error bound: camera.h), so each pixel's float ray is inside the
 * box, and ray_extent's argument applies to it.
 */
#ifndef KERNELS_TILE_RAYS_H
#define KERNELS_TILE_RAYS_H
#include "camera.h"

/* The float rays of columns i0..i1 and rows j0..j1 as one box-valued ray: every point o + t*d of them, t in
 * T, lies in base + T * dir; so do those of the rays between their centres (camera_ray_at, doubled columns from
 * 2 i0 + 1 to 2 i1 + 1 and rows from 2 j0 + 1 to 2 j1 + 1: -aa's samples there). Perspective: base is the eye
 * and dir the box of the unit directions; orthographic: base is the box of the origins and dir the one direction.
 * Computed once per tile; the search then costs one multiplication and one addition per axis and node. */
typedef struct {
    ia_interval base[3], dir[3];
} tile_rays;

IA_FN void tile_rays_of(const KERNEL_CONSTANT ia_real *p, int ortho, int i0, int i1, int j0, int j1, int width,
                        int height, tile_rays *r) {
    ia_interval s = camera_s_range(p, i0, i1, width), v = camera_v_range(p, j0, j1, height);
    for (int k = 0; k < 3; k++) {
        ia_interval offset = ia_add(ia_mul_r(s, p[PARAM_RIGHT + k]), ia_mul_r(v, p[PARAM_UP + k]));
        r->base[k] = ortho ? ia_add_r(offset, p[PARAM_EYE + k]) : ia_point(p[PARAM_EYE + k]);
        r->dir[k] = ortho ? ia_point(p[PARAM_FORWARD + k]) : ia_add_r(offset, p[PARAM_FORWARD + k]);
    }
    if (ortho)
        return;
    ia_interval len = ia_sqrt(ia_add(ia_add(ia_sqr(r->dir[0]), ia_sqr(r->dir[1])), ia_sqr(r->dir[2])));
    len = camera_as_rounded(len, CAMERA_ULP_SQRT);
    for (int k = 0; k < 3; k++)
        r->dir[k] = camera_as_rounded(ia_div(r->dir[k], len), CAMERA_ULP_DIV);
}

/* The box holding the points o + t*d, t in T, of the tile's float rays. */
IA_FN void tile_box(const tile_rays *r, ia_interval t, ia_interval box[3]) {
    for (int k = 0; k < 3; k++)
        box[k] = ia_add(r->base[k], ia_mul(t, r->dir[k]));
}

/* The root interval [*t0, *t0 + *w] of the bisection tree that the tile pass and every ray of the frame walk:
 * it holds every ray's part inside the bounds (PARAM_TMIN, PARAM_TMAX). */
IA_FN void frame_root(const KERNEL_CONSTANT ia_real *p, ia_real *t0, ia_real *w) {
    *t0 = p[PARAM_TMIN];
    *w = ia_hi(p[PARAM_TMAX] - p[PARAM_TMIN]);
}

#endif
