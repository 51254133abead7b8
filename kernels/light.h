/* kernels/light.h -- the lighting both render paths share, in SIMD lanes (ia/vec.h): Blinn-Phong with a key
 * light and a fill light, the lights fixed to the camera (upper left and right of the eye), over a vertical
 * gradient background. Colours are linear and are encoded for display with gamma 2 at the end (a square root:
 * pow() cost a tenth of the whole render). The first-root path (shade.h) lights one albedo, the segment path
 * (render_scene.cl) each pixel's region's.
 */
#ifndef KERNELS_LIGHT_H
#define KERNELS_LIGHT_H
#include "params.h"
#if IA_DEVICE && defined(IA_VW)

typedef IAV_CAT(float, IA_VW) shade_colorv;
#ifdef IA_FP64
#define shade_to_color IAV_CAT(convert_float, IA_VW)
#else
#define shade_to_color(v) (v)
#endif

/* The unit normals from the gradients g (f < 0 inside, so they point out), turned to face the ray directions d;
 * -d in the lanes where the gradient vanishes or is not finite. */
IA_FN void shade_normals(const ia_realv g[3], const ia_realv d[3], ia_realv n[3]) {
    ia_realv len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    ia_maskv ok = (len > 0) & isfinite(len);
    ia_realv facing = select(IAV_R(1), IAV_R(-1), g[0] * d[0] + g[1] * d[1] + g[2] * d[2] > 0);
    for (int k = 0; k < 3; k++)
        n[k] = select(-d[k], facing * g[k] / len, ok);
}

/* The unit direction l0 + l1 + l2 of a light fixed to the camera: -forward + a right + b up. */
IA_FN void shade_light_direction(const KERNEL_CONSTANT ia_real *p, ia_real a, ia_real b, ia_real l[3]) {
    for (int k = 0; k < 3; k++)
        l[k] = -p[PARAM_FORWARD + k] + a * p[PARAM_RIGHT + k] + b * p[PARAM_UP + k];
    ia_real len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    for (int k = 0; k < 3; k++)
        l[k] /= len;
}

/* One light's diffuse and specular terms for unit normals n, view directions d (from the eye) and the unit light
 * direction l. */
IA_FN void shade_light(const ia_realv n[3], const ia_realv d[3], const ia_real l[3], ia_realv *diffuse,
                       ia_realv *specular) {
    ia_realv h[3], hh = IAV_R(0), nl = IAV_R(0), nh = IAV_R(0);
    for (int k = 0; k < 3; k++) {
        nl += n[k] * l[k];
        h[k] = l[k] - d[k]; /* half vector between the light and the eye */
        hh += h[k] * h[k];
    }
    for (int k = 0; k < 3; k++)
        nh += n[k] * h[k];
    nh = select(IAV_R(0), fmax(nh / sqrt(hh), IAV_R(0)), hh > 0);
    ia_realv nh4 = (nh * nh) * (nh * nh), nh16 = (nh4 * nh4) * (nh4 * nh4); /* shininess 48 = 16 + 32 */
    *diffuse = fmax(nl, IAV_R(0));
    *specular = select(IAV_R(0), nh16 * (nh16 * nh16), nl > 0);
}

/* The displayed colours rgb of the lanes: surface points of the given linear albedo with unit normals n seen along
 * d in the lanes of `surface`, the background of their rows j (as floats) of `height` in the others. */
IA_FN void shade_lit_pixels(const KERNEL_CONSTANT ia_real *p, ia_maskv surface, const ia_realv n[3],
                            const ia_realv d[3], shade_colorv j, int height, const shade_colorv albedo[3],
                            shade_colorv rgb[3]) {
    ia_real key[3], fill[3];
    shade_light_direction(p, (ia_real)-0.6, (ia_real)0.8, key);
    shade_light_direction(p, (ia_real)0.9, (ia_real)-0.2, fill);
    ia_realv kd, ks, fd, fs;
    shade_light(n, d, key, &kd, &ks);
    shade_light(n, d, fill, &fd, &fs);
    shade_colorv key_d = shade_to_color(kd), key_s = shade_to_color(ks);
    shade_colorv fill_d = shade_to_color(fd), fill_s = shade_to_color(fs);
    /* the background: a gradient from a light grey-blue at the top to a dark one below */
    shade_colorv v = j / (float)(height > 1 ? height - 1 : 1);
    IAV_CAT(int, IA_VW) on_surface = IAV_CAT(convert_int, IA_VW)(surface) != 0;
    const float top[3] = {0.42f, 0.46f, 0.52f}, bottom[3] = {0.13f, 0.14f, 0.17f};
    for (int c = 0; c < 3; c++) {
        shade_colorv lin = albedo[c] * (0.10f + 0.85f * key_d + 0.30f * fill_d) + 0.45f * key_s + 0.10f * fill_s;
        rgb[c] = select(top[c] + (bottom[c] - top[c]) * v, sqrt(fmin(lin, 1.0f)), on_surface);
    }
}

#endif
#endif
