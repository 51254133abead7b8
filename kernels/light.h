/* kernels/light.h -- the lighting both render paths share, in SIMD lanes (ia/vec.h): Blinn-Phong with a key
 * light and a fill light, the lights fixed to the camera (upper left and right of the eye), over a vertical
 * gradient background. Colours are linear and are encoded for display with gamma 2 at the end (a square root:
 * pow() cost a tenth of the whole render). The first-root path (shade.h) lights one albedo, the segment path
 * (render_scene.cl) each pixel's material: its albedo, highlight weight and exponent.
 */
#ifndef KERNELS_LIGHT_H
#define KERNELS_LIGHT_H
#include "params.h"
#include "effects.h"
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

/* The unit direction l0 + l1 + l2 of a light fixed to the camera: -forward + a right + b up. In locals: stored
 * into l and read back at once, its scalars stalled on store forwarding (a fifth of effects_centre's CPU samples
 * with the default rig, the effects' block's units worked out for each packet). */
IA_FN void shade_light_direction(const KERNEL_CONSTANT ia_real *p, ia_real a, ia_real b, ia_real l[3]) {
    ia_real x = -p[PARAM_FORWARD] + a * p[PARAM_RIGHT] + b * p[PARAM_UP];
    ia_real y = -p[PARAM_FORWARD + 1] + a * p[PARAM_RIGHT + 1] + b * p[PARAM_UP + 1];
    ia_real z = -p[PARAM_FORWARD + 2] + a * p[PARAM_RIGHT + 2] + b * p[PARAM_UP + 2];
    ia_real len = sqrt(x * x + y * y + z * z);
    l[0] = x / len;
    l[1] = y / len;
    l[2] = z / len;
}

/* One light's diffuse term and the cosine nh between the normal and the half vector (0 where the light is behind
 * the surface), for unit normals n, view directions d (from the eye) and the unit light directions l. */
IA_FN void shade_light(const ia_realv n[3], const ia_realv d[3], const ia_realv l[3], ia_realv *diffuse,
                       ia_realv *nh_out) {
    ia_realv h[3], hh = IAV_R(0), nl = IAV_R(0), nh = IAV_R(0);
    for (int k = 0; k < 3; k++) {
        nl += n[k] * l[k];
        h[k] = l[k] - d[k]; /* half vector between the light and the eye */
        hh += h[k] * h[k];
    }
    for (int k = 0; k < 3; k++)
        nh += n[k] * h[k];
    nh = select(IAV_R(0), fmax(nh / sqrt(hh), IAV_R(0)), hh > 0);
    *diffuse = fmax(nl, IAV_R(0));
    *nh_out = select(IAV_R(0), nh, nl > 0);
}

/* nh^48, the first-root path's highlight, by squaring (pow() cost a tenth of the whole render). */
IA_FN ia_realv shade_power48(ia_realv nh) {
    ia_realv nh4 = (nh * nh) * (nh * nh), nh16 = (nh4 * nh4) * (nh4 * nh4); /* 48 = 16 + 32 */
    return nh16 * (nh16 * nh16);
}

/* The background of rows j (as floats) of `height`, display-encoded: top and bottom three floats each. */
IA_FN void shade_background(shade_colorv j, int height, const float top[3], const float bottom[3],
                            shade_colorv rgb[3]) {
    shade_colorv v = j / (float)(height > 1 ? height - 1 : 1);
    for (int c = 0; c < 3; c++)
        rgb[c] = top[c] + (bottom[c] - top[c]) * v;
}

/* The displayed colours rgb: albedo lit by the key and fill lights' diffuse terms kd, fd, plus the highlights
 * ks, fs (weights included), in the lanes of `surface`; the background of their rows j (as floats) of `height`
 * in the others. */
IA_FN void shade_combine(ia_maskv surface, shade_colorv j, int height, const shade_colorv albedo[3], ia_realv kd,
                         ia_realv fd, ia_realv ks, ia_realv fs, shade_colorv rgb[3]) {
    shade_colorv key_d = shade_to_color(kd), key_s = shade_to_color(ks);
    shade_colorv fill_d = shade_to_color(fd), fill_s = shade_to_color(fs);
    /* the background: a gradient from a light grey-blue at the top to a dark one below */
    IAV_CAT(int, IA_VW) on_surface = IAV_CAT(convert_int, IA_VW)(surface) != 0;
    const float top[3] = {0.42f, 0.46f, 0.52f}, bottom[3] = {0.13f, 0.14f, 0.17f};
    shade_colorv bg[3];
    shade_background(j, height, top, bottom, bg);
    for (int c = 0; c < 3; c++) {
        shade_colorv lin = albedo[c] * (0.10f + 0.85f * key_d + 0.30f * fill_d) + key_s + fill_s;
        rgb[c] = select(bg[c], sqrt(fmin(lin, 1.0f)), on_surface);
    }
}

/* The key light (upper left of the eye) and the fill light (lower right), fixed to the camera. */
IA_FN void shade_lights(const KERNEL_CONSTANT ia_real *p, const ia_realv n[3], const ia_realv d[3], ia_realv *kd,
                        ia_realv *knh, ia_realv *fd, ia_realv *fnh) {
    ia_real key[3], fill[3];
    shade_light_direction(p, (ia_real)-0.6, (ia_real)0.8, key);
    shade_light_direction(p, (ia_real)0.9, (ia_real)-0.2, fill);
    ia_realv key_v[3] = {IAV_R(key[0]), IAV_R(key[1]), IAV_R(key[2])};
    ia_realv fill_v[3] = {IAV_R(fill[0]), IAV_R(fill[1]), IAV_R(fill[2])};
    shade_light(n, d, key_v, kd, knh);
    shade_light(n, d, fill_v, fd, fnh);
}

/* The first-root path's colours: one albedo, highlights of weight 0.45 (key) and 0.10 (fill), exponent 48. */
IA_FN void shade_lit_pixels(const KERNEL_CONSTANT ia_real *p, ia_maskv surface, const ia_realv n[3],
                            const ia_realv d[3], shade_colorv j, int height, const shade_colorv albedo[3],
                            shade_colorv rgb[3]) {
    ia_realv kd, knh, fd, fnh;
    shade_lights(p, n, d, &kd, &knh, &fd, &fnh);
    ia_realv ks = IAV_R(0.45) * shade_power48(knh), fs = IAV_R(0.10) * shade_power48(fnh);
    shade_combine(surface, j, height, albedo, kd, fd, ks, fs, rgb);
}

/* The segment path's colours: each lane's material, its highlight weight `specular` on the key light (the fill
 * light's in the first-root path's proportion, 0.10 / 0.45) and its exponent `shininess`. */
IA_FN void shade_lit_materials(const KERNEL_CONSTANT ia_real *p, ia_maskv surface, const ia_realv n[3],
                               const ia_realv d[3], shade_colorv j, int height, const shade_colorv albedo[3],
                               ia_realv specular, ia_realv shininess, shade_colorv rgb[3]) {
    ia_realv kd, knh, fd, fnh;
    shade_lights(p, n, d, &kd, &knh, &fd, &fnh);
    ia_realv ks = select(IAV_R(0), exp2(shininess * log2(knh)), knh > 0);
    ia_realv fs = select(IAV_R(0), exp2(shininess * log2(fnh)), fnh > 0);
    shade_combine(surface, j, height, albedo, kd, fd, specular * ks, specular * (IAV_R(0.10 / 0.45) * fs), rgb);
}

/* The effects' lighting (src/render_effects.c, kernels/effects.cl): any lights (kernels/effects.h), each seen or
 * not from the hit (shadow rays), the material's highlight weight and exponent; the default rig is the plain
 * render's key and fill lights (EFFECTS_LIGHT_CAMERA), so that without shadows a hit gets the plain colour. */

/* The unit direction of each light of the effects' block at infinity (a camera light's from the camera, a dir
 * light's as the host made it; a point light's entry is not set), once a work-item: worked out at each shading of
 * each light, a camera light's scalars were stored and read back at once (a store-forwarding stall: a quarter of
 * effects_centre's CPU samples with the default rig). */
IA_FN void shade_light_units(const KERNEL_CONSTANT ia_real *params, const KERNEL_CONSTANT ia_real *fx,
                             ia_real u[EFFECTS_MAX_LIGHTS][3]) {
    for (int l = 0; l < (int)fx[EFFECTS_NLIGHTS]; l++) {
        const KERNEL_CONSTANT ia_real *L = fx + EFFECTS_LIGHTS + EFFECTS_LIGHT_REALS * l;
        if ((int)L[EFFECTS_LIGHT_KIND] == EFFECTS_LIGHT_CAMERA)
            shade_light_direction(params, L[EFFECTS_LIGHT_XYZ], L[EFFECTS_LIGHT_XYZ + 1], u[l]);
        else
            for (int k = 0; k < 3; k++)
                u[l][k] = L[EFFECTS_LIGHT_XYZ + k];
    }
}

/* The unit directions l from points p towards light L (EFFECTS_LIGHT_REALS reals of the effects' block; `unit` its
 * direction where it is at infinity, shade_light_units), and returns the distances to it (+inf at infinity). */
IA_FN ia_realv shade_towards(const KERNEL_CONSTANT ia_real *L, const ia_real unit[3], const ia_realv p[3],
                             ia_realv l[3]) {
    if ((int)L[EFFECTS_LIGHT_KIND] == EFFECTS_LIGHT_POINT) {
        for (int k = 0; k < 3; k++)
            l[k] = L[EFFECTS_LIGHT_XYZ + k] - p[k];
        ia_realv dist = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        for (int k = 0; k < 3; k++)
            l[k] = l[k] / dist;
        return dist;
    }
    for (int k = 0; k < 3; k++)
        l[k] = IAV_R(unit[k]);
    return IAV_R(IA_INF);
}

/* The lanes of `on` where light L (as shade_towards) is in front of the surface at p, its normal n. */
IA_FN ia_maskv shade_facing(const KERNEL_CONSTANT ia_real *L, const ia_real unit[3], const ia_realv p[3],
                            const ia_realv n[3], ia_maskv on) {
    ia_realv towards[3];
    shade_towards(L, unit, p, towards);
    return on & (n[0] * towards[0] + n[1] * towards[1] + n[2] * towards[2] > 0);
}

/* nh^shininess, 0 where nh is 0: by squaring where every lane's exponent is the first-root path's 48, else by
 * exp2 and log2. */
IA_FN ia_realv shade_highlight(ia_realv nh, ia_realv shininess) {
    if (!iav_any(shininess != 48))
        return shade_power48(nh);
    return select(IAV_R(0), exp2(shininess * log2(nh)), nh > 0);
}

/* The linear colour of a lit hit: albedo times the diffuse sum (the ambient term included) plus specular times
 * the highlight sum. */
IA_FN void shade_lit_linear(const shade_colorv albedo[3], ia_realv specular, ia_realv diffuse, ia_realv highlight,
                            shade_colorv lin[3]) {
    shade_colorv dc = shade_to_color(diffuse), hc = shade_to_color(specular * highlight);
    for (int c = 0; c < 3; c++)
        lin[c] = albedo[c] * dc + hc;
}

/* The effects' colours (linear) of hits at points p, at depths t along view directions d, with unit normals n
 * facing them, by the effects' block fx (kernels/effects.h): the previews (-shade normals, depth, ids: id_rgb,
 * linear), or lit: albedo (-shade gradient: the normal's direction), specular and shininess, under each light l
 * (units: shade_light_units'), of which the fraction vis[l] reaches the hit (shadow rays). */
IA_FN void shade_effects(const KERNEL_CONSTANT ia_real *fx, const ia_real units[EFFECTS_MAX_LIGHTS][3],
                         const ia_realv p[3], ia_realv t, const ia_realv n[3], const ia_realv d[3],
                         const ia_realv vis[EFFECTS_MAX_LIGHTS], const shade_colorv albedo[3], ia_realv specular,
                         ia_realv shininess, const shade_colorv id_rgb[3], shade_colorv lin[3]) {
    int shade = (int)fx[EFFECTS_SHADE];
    if (shade >= EFFECTS_SHADE_NORMALS) {
        ia_real span = fx[EFFECTS_DEPTH_HI] - fx[EFFECTS_DEPTH_LO];
        ia_realv v = span > 0 ? fmin(fmax((t - fx[EFFECTS_DEPTH_LO]) / span, IAV_R(0)), IAV_R(1)) : IAV_R(0);
        for (int c = 0; c < 3; c++) {
            shade_colorv shown = shade_to_color(shade == EFFECTS_SHADE_NORMALS ? (ia_real)0.5 + (ia_real)0.5 * n[c]
                                                                                 : (ia_real)1 - (ia_real)0.85 * v);
            lin[c] = shade == EFFECTS_SHADE_IDS ? id_rgb[c] : shown * shown;
        }
        return;
    }
    ia_realv diffuse = IAV_R(EFFECTS_AMBIENT), highlight = IAV_R(0);
    for (int l = 0; l < (int)fx[EFFECTS_NLIGHTS]; l++) {
        const KERNEL_CONSTANT ia_real *L = fx + EFFECTS_LIGHTS + EFFECTS_LIGHT_REALS * l;
        ia_realv towards[3], nl, nh;
        shade_towards(L, units[l], p, towards);
        shade_light(n, d, towards, &nl, &nh);
        diffuse += select(IAV_R(0), vis[l] * (L[EFFECTS_LIGHT_INTENSITY] * nl), vis[l] > 0);
        highlight += select(IAV_R(0), vis[l] * (L[EFFECTS_LIGHT_HIGHLIGHT] * shade_highlight(nh, shininess)),
                            vis[l] > 0);
    }
    shade_colorv lit[3];
    for (int c = 0; c < 3; c++) { /* -shade gradient: the normal's direction as the colour */
        shade_colorv g = shade_to_color((ia_real)0.5 + (ia_real)0.5 * n[c]);
        lit[c] = shade == EFFECTS_SHADE_GRADIENT ? g * g : albedo[c];
    }
    shade_lit_linear(lit, specular, diffuse, highlight, lin);
}

#endif
#endif
