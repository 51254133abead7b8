/* kernels/shade.h -- the normals and colours of a packet's pixels on the first-root path, in SIMD lanes, by the
 * lighting of light.h (lane by lane, it was three quarters of a frame's fixed cost once).
 *
 * The gradient is the emitted iacsg_f_gradv (kernels/render.cl: packet_gradients), or for a union in groups by
 * differences of its enclosures (packet_F), below.
 */
#ifndef KERNELS_SHADE_H
#define KERNELS_SHADE_H
#include "packet.h"
#include "light.h"

/* The gradient at points p of the lanes of a union in groups, by central differences of its enclosures'
 * midpoints at points (over the groups set in `groups`, or a tape's lists of the tile's parts: the others are certainly
 * positive around p, so the part that is 0 there is among these). The compiler gives such unions no gradient code for
 * the kernels: for 1024 spheres it was a quarter of the 7 s build. The step, 2^-10 of the coordinate's scale, keeps
 * float rounding and the curvature of the parts far below what shading shows; only within a step of the edge between
 * two parts does the normal blend theirs. */
#define SHADE_DIFFERENCE_STEP ((ia_real)0x1p-10)
IA_FN void shade_gradients_by_differences(PACKET_TAPE_PARAM packet_parts groups, const ia_realv p[3], iav time,
                                          ia_realv g[3]) {
    for (int c = 0; c < 3; c++) {
        ia_realv h = SHADE_DIFFERENCE_STEP * (1 + fabs(p[c]));
        ia_realv up[3] = {p[0], p[1], p[2]}, down[3] = {p[0], p[1], p[2]};
        up[c] = p[c] + h;
        down[c] = p[c] - h;
        iav fu = packet_F_points(PACKET_TAPE_ARG groups, iav_make(up[0], up[0]), iav_make(up[1], up[1]),
                                 iav_make(up[2], up[2]), time);
        iav fd = packet_F_points(PACKET_TAPE_ARG groups, iav_make(down[0], down[0]), iav_make(down[1], down[1]),
                                 iav_make(down[2], down[2]), time);
        g[c] = ((fu.lo + fu.hi) - (fd.lo + fd.hi)) * (ia_real)0.5 / (up[c] - down[c]);
    }
}

/* The colours of the first-root path: the lighting of light.h with one albedo for the whole surface; a packet
 * with no hit only its background (the lights' set-up and the lanes' lighting were two thirds of an empty
 * frame's kernel time). */
IA_FN void shade_pixels(const KERNEL_CONSTANT ia_real *p, ia_maskv surface, const ia_realv n[3], const ia_realv d[3],
                        packet_int j, int height, shade_colorv rgb[3]) {
    const shade_colorv albedo[3] = {(shade_colorv)0.80f, (shade_colorv)0.52f, (shade_colorv)0.28f};
    shade_colorv rows = IAV_CAT(convert_float, IA_VW)(j);
    if (iav_any(surface))
        shade_lit_pixels(p, surface, n, d, rows, height, albedo, rgb);
    else
        shade_combine(surface, rows, height, albedo, IAV_R(0), IAV_R(0), IAV_R(0), IAV_R(0), rgb);
}

#endif
