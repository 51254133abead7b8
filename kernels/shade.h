/* kernels/shade.h -- the colour of a pixel: Blinn-Phong with a key light and a fill light, the lights fixed to
 * the camera (upper left and right of the eye), over a vertical gradient background. Colours are linear and
 * are encoded for display with gamma 2 at the end (a square root: pow() cost a tenth of the whole render).
 *
 * Needs iacsg_f_grad, the point value and gradient of the expression, or its groups (the emitted source).
 */
#ifndef KERNELS_SHADE_H
#define KERNELS_SHADE_H
#include "params.h"

/* The gradient at p. For a union emitted in groups, over the groups set in `groups` (the tile's, packet_F): the
 * others are certainly positive around p, so the part that is 0 there is among these. */
IA_FN void shade_gradient(ulong groups, ia_real x, ia_real y, ia_real z, ia_real time, ia_real g[3]) {
#ifdef IACSG_GROUPS
    iacsg_grad grad = (iacsg_grad)0, part;
    ia_real f = (ia_real)INFINITY;
    for (int k = 0; k < IACSG_GROUPS; k++) {
        if (!(groups >> k & 1))
            continue;
        ia_real v = iacsg_f_grad_group(k, x, y, z, time, &part);
        grad = f <= v ? grad : part; /* as the emitted iacsg_f_grad */
        f = fmin(f, v);
    }
    g[0] = grad.x;
    g[1] = grad.y;
    g[2] = grad.z;
#else
    (void)groups;
    iacsg_f_grad(x, y, z, time, &g[0], &g[1], &g[2]);
#endif
}

/* The unit normal at p, from the gradient (f < 0 inside, so it points out), turned to face the ray direction d.
 * Returns 0 when the gradient vanishes or is not finite there; n is then -d. */
IA_FN int shade_normal(ulong groups, ia_real x, ia_real y, ia_real z, ia_real time, const ia_real d[3], ia_real n[3]) {
    shade_gradient(groups, x, y, z, time, n);
    ia_real len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    int ok = len > 0 && isfinite(len);
    ia_real facing = n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0 ? (ia_real)-1 : (ia_real)1;
    for (int k = 0; k < 3; k++)
        n[k] = ok ? facing * n[k] / len : -d[k];
    return ok;
}

/* One light's diffuse and specular terms for unit normal n, view direction d (from the eye) and a light
 * direction l0 + l1 + l2 (not yet unit). */
IA_FN void shade_light(const ia_real n[3], const ia_real d[3], const ia_real l[3], ia_real *diffuse,
                       ia_real *specular) {
    ia_real ll = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    ia_real h[3], hh = 0, nl = 0, nh = 0;
    for (int k = 0; k < 3; k++) {
        nl += n[k] * l[k] / ll;
        h[k] = l[k] / ll - d[k]; /* half vector between the light and the eye */
        hh += h[k] * h[k];
    }
    for (int k = 0; k < 3; k++)
        nh += n[k] * h[k];
    nh = hh > 0 ? fmax(nh / sqrt(hh), (ia_real)0) : (ia_real)0;
    ia_real nh4 = (nh * nh) * (nh * nh), nh16 = (nh4 * nh4) * (nh4 * nh4); /* shininess 48 = 16 + 32 */
    *diffuse = fmax(nl, (ia_real)0);
    *specular = nl > 0 ? nh16 * (nh16 * nh16) : (ia_real)0;
}

/* The displayed colour of a surface point with unit normal n seen along d. */
IA_FN void shade_surface(const KERNEL_CONSTANT ia_real *p, const ia_real n[3], const ia_real d[3], float rgb[3]) {
    ia_real key[3], fill[3], kd, ks, fd, fs;
    for (int k = 0; k < 3; k++) {
        ia_real f = p[PARAM_FORWARD + k], r = p[PARAM_RIGHT + k], u = p[PARAM_UP + k];
        key[k] = -f - (ia_real)0.6 * r + (ia_real)0.8 * u;
        fill[k] = -f + (ia_real)0.9 * r - (ia_real)0.2 * u;
    }
    shade_light(n, d, key, &kd, &ks);
    shade_light(n, d, fill, &fd, &fs);
    const float base[3] = {0.80f, 0.52f, 0.28f};
    for (int c = 0; c < 3; c++) {
        float lin = base[c] * (0.10f + 0.85f * (float)kd + 0.30f * (float)fd) + 0.45f * (float)ks +
                    0.10f * (float)fs;
        rgb[c] = sqrt(fmin(lin, 1.0f));
    }
}

/* The background of row j of `height`: a gradient from a light grey-blue at the top to a dark one below. */
IA_FN void shade_background(int j, int height, float rgb[3]) {
    float v = (float)j / (float)(height > 1 ? height - 1 : 1);
    const float top[3] = {0.42f, 0.46f, 0.52f}, bottom[3] = {0.13f, 0.14f, 0.17f};
    for (int c = 0; c < 3; c++)
        rgb[c] = top[c] + (bottom[c] - top[c]) * v;
}

#endif
