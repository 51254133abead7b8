/* kernels/camera.h -- the primary ray of a pixel, and its clipping to the bounds.
 *
 * The convention (README): f, r, u are the camera's forward, right and up unit vectors (params.h). Pixel
 * (i, j), i = 0..W-1 left to right and j = 0..H-1 top to bottom, has
 *     s = (2(i + 1/2)/W - 1) * SCALE_S,   v = (1 - 2(j + 1/2)/H) * SCALE_V,
 * direction normalize(f + s*r + v*u) from the eye; orthographic: origin eye + s*r + v*u, direction f.
 * Every operation here is +, -, *, / or sqrt, written in a fixed order, so the host computes the same float
 * ray bit for bit when the device rounds / and sqrt correctly (fp64 always; float with IA_CR_DIVSQRT). The
 * rendered ray IS this float ray: the bisection encloses its points rigorously (traverse.h), so rounding here
 * only moves the ray by an ulp, it never makes the renderer miss a surface the float ray crosses. Where / and
 * sqrt are not correctly rounded (the OpenCL spec allows 2.5 and 3 ulps in float), the tile pass's box of a
 * tile's rays (tile.h) allows for their error: camera_s_range, camera_v_range.
 */
#ifndef KERNELS_CAMERA_H
#define KERNELS_CAMERA_H
#include "params.h"

/* The error bounds, in ulps, of the / and sqrt that compute the pixel rays: the device's (ia/round.h). Host
 * tests set them to model a device without correctly rounded ones (tests/t_render_tile_inexact.c). */
#ifndef CAMERA_ULP_DIV
#define CAMERA_ULP_DIV IA_ULP_DIV
#define CAMERA_ULP_SQRT IA_ULP_SQRT
#endif

/* The screen coordinates s of column i and v of row j (camera_ray_at's of doubled column 2 i + 1 and row 2 j + 1).
 * Each is a chain of monotone rounded operations, so s increases with the doubled column and v decreases with the
 * doubled row also in floating point (kernels/tile.h relies on it). */
IA_FN ia_real camera_s(const KERNEL_CONSTANT ia_real *p, int i, int width) {
    return ((ia_real)(2 * i + 1) / (ia_real)width - (ia_real)1) * p[PARAM_SCALE_S];
}
IA_FN ia_real camera_v(const KERNEL_CONSTANT ia_real *p, int j, int height) {
    return ((ia_real)1 - (ia_real)(2 * j + 1) / (ia_real)height) * p[PARAM_SCALE_V];
}

/* Enclosures of camera_s of columns i0..i1 and camera_v of rows j0..j1, and of the s and v of every ray between
 * (doubled columns and rows between the ends' centres). With a correctly rounded / they are monotone in the doubled
 * column or row, so the ends' values are the bounds. Otherwise each quotient x2 / n may be CAMERA_ULP_DIV ulps off
 * either way, and need not be monotone: the ends' quotients widened by twice that (their own error and a ray's),
 * then the rest in outward rounding, which contains its rounded results. */
#if CAMERA_ULP_DIV == 0
IA_FN ia_interval camera_s_range(const KERNEL_CONSTANT ia_real *p, int i0, int i1, int width) {
    return ia_make(camera_s(p, i0, width), camera_s(p, i1, width));
}
IA_FN ia_interval camera_v_range(const KERNEL_CONSTANT ia_real *p, int j0, int j1, int height) {
    return ia_make(camera_v(p, j1, height), camera_v(p, j0, height));
}
#else
IA_FN ia_interval camera_quotients(int k0, int k1, int n) {
    return ia_make(ia_lo_k((ia_real)(2 * k0 + 1) / (ia_real)n, 2 * CAMERA_ULP_DIV),
                   ia_hi_k((ia_real)(2 * k1 + 1) / (ia_real)n, 2 * CAMERA_ULP_DIV));
}
IA_FN ia_interval camera_s_range(const KERNEL_CONSTANT ia_real *p, int i0, int i1, int width) {
    return ia_mul_r(ia_add_r(camera_quotients(i0, i1, width), (ia_real)-1), p[PARAM_SCALE_S]);
}
IA_FN ia_interval camera_v_range(const KERNEL_CONSTANT ia_real *p, int j0, int j1, int height) {
    return ia_mul_r(ia_add_r(ia_neg(camera_quotients(j0, j1, height)), (ia_real)1), p[PARAM_SCALE_V]);
}
#endif

/* An enclosure of exact values widened to hold them as an operation with a k-ulp error computes them (the
 * pixels' own / and sqrt); for k = 0 it holds them already: an outward-rounded bound lies beyond the
 * rounded-to-nearest one. */
IA_FN ia_interval camera_as_rounded(ia_interval a, int k) {
    return k == 0 ? a : ia_make(ia_lo_k(a.lo, k), ia_hi_k(a.hi, k));
}

/* The ray through doubled column x2 and doubled row y2 (camera_s, camera_v; -aa's samples between the centres:
 * packet_camera.h's packet_rays_at, the same operations in lanes). */
IA_FN void camera_ray_at(const KERNEL_CONSTANT ia_real *p, int ortho, ia_real x2, ia_real y2, int width, int height,
                         ia_real o[3], ia_real d[3]) {
    ia_real s = (x2 / (ia_real)width - (ia_real)1) * p[PARAM_SCALE_S];
    ia_real v = ((ia_real)1 - y2 / (ia_real)height) * p[PARAM_SCALE_V];
    for (int k = 0; k < 3; k++) {
        ia_real offset = s * p[PARAM_RIGHT + k] + v * p[PARAM_UP + k];
        o[k] = ortho ? p[PARAM_EYE + k] + offset : p[PARAM_EYE + k];
        d[k] = ortho ? p[PARAM_FORWARD + k] : p[PARAM_FORWARD + k] + offset;
    }
    if (!ortho) {
        ia_real len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; k++)
            d[k] = d[k] / len;
    }
}

IA_FN void camera_ray(const KERNEL_CONSTANT ia_real *p, int ortho, int i, int j, int width, int height,
                      ia_real o[3], ia_real d[3]) {
    camera_ray_at(p, ortho, (ia_real)(2 * i + 1), (ia_real)(2 * j + 1), width, height, o, d);
}

/* Where the ray enters and leaves the slab lo..hi of one axis (d != 0), enclosed: the exact crossings
 * (plane - o) / d of the near plane (lo for d > 0, hi for d < 0) and of the far one, each difference one ulp
 * outward, then divided by the point d, which is monotone (increasing for d > 0), so each quotient widened by
 * the division's error bound. Only the bound that counts is divided: the entry's lower, the exit's upper (with
 * a correctly rounded /, what the least and the greatest of both planes' enclosures were, at half the
 * divisions: 12 a packet of 16 rays in lanes, a tenth of the sphere's per-pixel work). */
IA_FN void camera_slab(ia_real lo, ia_real hi, ia_real o, ia_real d, ia_real *enter, ia_real *leave) {
    int backward = d < 0;
    ia_real near = (backward ? hi : lo) - o, far = (backward ? lo : hi) - o;
    *enter = ia_lo_k((backward ? ia_hi(near) : ia_lo(near)) / d, IA_ULP_DIV);
    *leave = ia_hi_k((backward ? ia_lo(far) : ia_hi(far)) / d, IA_ULP_DIV);
}

/* The part [tn, tf] of the ray o + t*d inside the box lo..hi, widened outward: every t in [tn, tf] whose exact
 * point o + t*d lies in the box is in [*t_near, *t_far]. Returns 0 when the ray misses the box there. Infinite
 * box bounds are allowed (a box holding everything). */
IA_FN int camera_clip_box(const ia_real lo[3], const ia_real hi[3], const ia_real o[3], const ia_real d[3], ia_real tn,
                          ia_real tf, ia_real *t_near, ia_real *t_far) {
    for (int k = 0; k < 3; k++) {
        if (d[k] == 0) {
            if (o[k] < lo[k] || o[k] > hi[k])
                return 0;
            continue;
        }
        ia_real enter, leave;
        camera_slab(lo[k], hi[k], o[k], d[k], &enter, &leave);
        tn = fmax(tn, enter);
        tf = fmin(tf, leave);
    }
    *t_near = tn;
    *t_far = tf;
    return tn <= tf;
}

/* The part t >= 0 of the ray o + t*d inside the box (params.h, PARAM_BOX), widened outward: every t >= 0
 * whose exact point o + t*d lies in the box is in [*t_near, *t_far]. Returns 0 when the ray misses the box. */
IA_FN int camera_clip(const KERNEL_CONSTANT ia_real *p, const ia_real o[3], const ia_real d[3], ia_real *t_near,
                      ia_real *t_far) {
    ia_real lo[3] = {p[PARAM_BOX], p[PARAM_BOX + 1], p[PARAM_BOX + 2]};
    ia_real hi[3] = {p[PARAM_BOX + 3], p[PARAM_BOX + 4], p[PARAM_BOX + 5]};
    return camera_clip_box(lo, hi, o, d, 0, IA_INF, t_near, t_far);
}

/* The depth image is float32: in double mode the start of a leaf is rounded down, so it stays before the root. */
IA_FN float camera_depth_round_down(ia_real t) {
    float f = (float)t;
    return (ia_real)f > t ? nextafter(f, -INFINITY) : f;
}

#endif
