/* kernels/packet_camera.h -- the camera rays of IA_VW pixels at once, one SIMD lane per ray, and where they
 * meet the bounds (OpenCL C only, where the program has IA_VW): camera.h's scalar code over vectors, for the
 * first-root packets (packet.h) and every segment-path program (render_scene.cl), whose scenes without the
 * union's pre-pass set their rays up one at a time before (camera_clip_box was 6-12 % of a BRL-CAD model's
 * render). Also the lanes' integer types and conversions that packet.h and shade.h use.
 */
#ifndef KERNELS_PACKET_CAMERA_H
#define KERNELS_PACKET_CAMERA_H
#include "camera.h"
#if IA_DEVICE && defined(IA_VW)
#define PACKET_CAMERA_LANES 1

/* Per-lane integers of the width of ia_maskv (so that select takes them), and conversions between the lane
 * types (OpenCL's convert_ functions are overloaded on the source type). */
#ifdef IA_FP64
typedef IAV_CAT(long, IA_VW) packet_int;    /* a level per lane */
typedef IAV_CAT(ulong, IA_VW) packet_index; /* bisect_index per lane */
#define packet_to_real IAV_CAT(convert_double, IA_VW)
#define packet_to_int IAV_CAT(convert_long, IA_VW)
#define packet_to_index IAV_CAT(convert_ulong, IA_VW)
#define packet_as_real IAV_CAT(as_double, IA_VW)
#define packet_as_int IAV_CAT(as_long, IA_VW)
#define PACKET_EXP_BIAS 1023
#define PACKET_MANT_BITS 52
#else
typedef IAV_CAT(int, IA_VW) packet_int;
typedef IAV_CAT(uint, IA_VW) packet_index;
#define packet_to_real IAV_CAT(convert_float, IA_VW)
#define packet_to_int IAV_CAT(convert_int, IA_VW)
#define packet_to_index IAV_CAT(convert_uint, IA_VW)
#define packet_as_real IAV_CAT(as_float, IA_VW)
#define packet_as_int IAV_CAT(as_int, IA_VW)
#define PACKET_EXP_BIAS 127
#define PACKET_MANT_BITS 23
#endif

/* Set-up, lane by lane: camera.h's and traverse.h's scalar code over vectors, the same operations in the same
 * order (FP_CONTRACT is off), so each lane's ray, clip and first node are bit for bit what the scalar
 * functions give for its pixel, which the host tests recompute. */

/* 0, 1, ..., IA_VW - 1. A vector literal: from a loop over an array PoCL stored the numbers in two halves and
 * loaded them whole at every packet, a store-forwarding stall that was a ninth of the sphere's kernel time outside
 * its root search (libfive's view, 1024x1024). */
IA_FN packet_int packet_lane_numbers(void) {
#if IA_VW == 16
    return (packet_int)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
#else
    int k[IA_VW];
    for (int n = 0; n < IA_VW; n++)
        k[n] = n;
    return packet_to_int(IAV_LOAD(k));
#endif
}

/* camera_ray_at in lanes: the rays through the points of the image whose coordinates, in pixels from its top left
 * corner, are x2 / 2 and y2 / 2 (pixel (i, j)'s centre: x2 = 2 i + 1, y2 = 2 j + 1, exact). */
IA_FN void packet_rays_at(const KERNEL_CONSTANT ia_real *p, int ortho, ia_realv x2, ia_realv y2, int width,
                          int height, ia_realv o[3], ia_realv d[3]) {
    ia_realv s = (x2 / (ia_real)width - (ia_real)1) * p[PARAM_SCALE_S];
    ia_realv v = ((ia_real)1 - y2 / (ia_real)height) * p[PARAM_SCALE_V];
    for (int k = 0; k < 3; k++) {
        ia_realv offset = s * p[PARAM_RIGHT + k] + v * p[PARAM_UP + k];
        o[k] = ortho ? p[PARAM_EYE + k] + offset : IAV_R(p[PARAM_EYE + k]);
        d[k] = ortho ? IAV_R(p[PARAM_FORWARD + k]) : p[PARAM_FORWARD + k] + offset;
    }
    if (!ortho) {
        ia_realv len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; k++)
            d[k] = d[k] / len;
    }
}

/* camera_ray for the pixels (i, j) of the lanes (in range). */
IA_FN void packet_rays(const KERNEL_CONSTANT ia_real *p, int ortho, packet_int i, packet_int j, int width, int height,
                       ia_realv o[3], ia_realv d[3]) {
    packet_rays_at(p, ortho, packet_to_real(2 * i + 1), packet_to_real(2 * j + 1), width, height, o, d);
}

/* camera_slab: where the rays enter and leave the slab lo..hi, for the lanes where d != 0. */
IA_FN void packet_slab(ia_real lo, ia_real hi, ia_realv o, ia_realv d, ia_realv *enter, ia_realv *leave) {
    ia_maskv backward = d < 0;
    ia_realv near = select(IAV_R(lo), IAV_R(hi), backward) - o, far = select(IAV_R(hi), IAV_R(lo), backward) - o;
    *enter = iav_lo_k(select(iav_lo(near), iav_hi(near), backward) / d, IA_ULP_DIV);
    *leave = iav_hi_k(select(iav_hi(far), iav_lo(far), backward) / d, IA_ULP_DIV);
}

/* camera_clip: the lanes whose ray meets the bounds, with their parts [*t_near, *t_far] inside. */
IA_FN ia_maskv packet_clip(const KERNEL_CONSTANT ia_real *p, const ia_realv o[3], const ia_realv d[3],
                           ia_realv *t_near, ia_realv *t_far) {
    ia_realv tn = IAV_R(0), tf = IAV_R(IA_INF);
    ia_maskv meets = (ia_maskv)-1;
    for (int k = 0; k < 3; k++) {
        ia_real lo = p[PARAM_BOX + k], hi = p[PARAM_BOX + 3 + k];
        ia_maskv flat = d[k] == 0; /* parallel to the slab: in it or not */
        meets &= ~(flat & (o[k] < lo | o[k] > hi));
        ia_realv enter, leave;
        packet_slab(lo, hi, o[k], d[k], &enter, &leave);
        tn = select(fmax(tn, enter), tn, flat);
        tf = select(fmin(tf, leave), tf, flat);
    }
    *t_near = tn;
    *t_far = tf;
    return meets & (tn <= tf);
}

#endif
#endif
