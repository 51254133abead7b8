/* kernels/scene_lit.h -- the effects that the segment path's camera kernels apply to a packet's hits themselves
 * (kernels/render_scene.cl: scene_packet; src/render_effects.c: render_effects_in_camera), in SIMD lanes:
 *
 *   the hits --> each lit by the effects' lights, as far as its shadow ray lets a light through: seen where it
 *     meets no item, or through the transparent items it meets (scene_lanes_light, scene_lanes_transmitted; the
 *     shadow rays traced as packets with the work-item's buffers, scene_rays.h)
 *   --> where a material reflects (one bounce, every item opaque): the reflected rays traced, their hits lit
 *     (scene_lanes_mirror); where one lets light through (no reflection): the layers behind, each traced, lit
 *     and weighed (scene_lanes_layers)
 *   --> the colours (display-encoded, or in linear light for -aa's samples) and the misses' background.
 * A secondary ray that overflows the buffers lists its pixel to be traced again, as a camera ray does.
 */
#ifndef KERNELS_SCENE_LIT_H
#define KERNELS_SCENE_LIT_H

/* The display colours of the effects' background (f->fx's top and bottom) in rows `row`. */
static void scene_fx_background(const scene_frame *f, shade_colorv row, shade_colorv bg[3]) {
    float top[3], bottom[3];
    for (int c = 0; c < 3; c++) {
        top[c] = (float)f->fx[EFFECTS_BG_TOP + c];
        bottom[c] = (float)f->fx[EFFECTS_BG_BOTTOM + c];
    }
    shade_background(row, f->height / f->aa, top, bottom, bg);
}

/* Traces the packet's secondary rays from o along d over [0, tf] (lanes of `live`, each passing pass_k[k], weave.h;
 * start NULL, or g at o shared with other rays from there: scene_rays_start) with r's buffers (scene_rays_trace;
 * `whether`: every item opaque, a ray may end on a proven crossing), their origins and directions into ok, dk;
 * found, hits as scene_rays_trace's. A lane whose ray overflows the buffers is listed to be traced again (pixel[k]
 * -1), as a camera ray that overflows. rays_k, evals_k: each lane's rays and their evaluations, added. */
static void scene_lanes_trace(__constant ia_real *params, const scene_frame *f, const scene_view *view, scene_ray *r,
                              int whether, scene_rays_start *start, const ia_realv o[3], const ia_realv d[3],
                              ia_realv tf, ia_maskv live, const ia_real pass_k[PACKET_LANES], int pixel[PACKET_LANES],
                              kernel_u32 rays_k[PACKET_LANES], kernel_u32 evals_k[PACKET_LANES],
                              ia_real ok[3][PACKET_LANES], ia_real dk[3][PACKET_LANES], int found[PACKET_LANES],
                              weave_hit hits[PACKET_LANES]) {
    ia_real tn_k[PACKET_LANES], tf_k[PACKET_LANES], meets[PACKET_LANES], cast[PACKET_LANES];
    for (int c = 0; c < 3; c++) {
        IAV_STORE(o[c], ok[c]);
        IAV_STORE(d[c], dk[c]);
    }
    IAV_STORE(IAV_R(0), tn_k);
    IAV_STORE(tf, tf_k);
    IAV_STORE(select(IAV_R(0), IAV_R(1), live), meets);
    IAV_STORE(select(IAV_R(0), IAV_R(1), live), cast);
    kernel_u32 evals[PACKET_LANES];
    scene_rays_trace(view, r, params, whether, start, ok, dk, tn_k, tf_k, meets, pass_k, found, hits, evals);
    for (int k = 0; k < PACKET_LANES; k++) {
        if (found[k] == SCENE_TRACE_OVERFLOW && pixel[k] >= 0) {
            f->overflow[atomic_inc(f->noverflow)] = pixel[k];
            pixel[k] = -1;
        }
        rays_k[k] += cast[k] != 0;
        evals_k[k] += evals[k];
    }
}

/* What the packet's lanes hit: where, what and the material there, in lanes (a secondary ray's, scene_lanes_hits). */
typedef struct {
    ia_maskv on;     /* the lanes that hit */
    ia_realv t, n[3]; /* how far along the ray; the unit normal there, facing the ray */
    int item[PACKET_LANES];
    shade_colorv albedo[3];
    ia_realv specular, shininess;
} scene_lanes_hit;

/* The hits of the packet's secondary rays (lanes of `live`: from o, directions d, over [0, tf], each passing
 * pass_k[k], weave.h), traced in lanes (scene_lanes_trace, not `whether`), with their normals and materials. */
static void scene_lanes_hits(__constant ia_real *params, const scene_frame *f, const scene_view *view, scene_ray *r,
                             const ia_realv o[3], const ia_realv d[3], ia_realv tf, ia_maskv live,
                             const ia_real pass_k[PACKET_LANES], int pixel[PACKET_LANES],
                             kernel_u32 rays_k[PACKET_LANES], kernel_u32 evals_k[PACKET_LANES], scene_lanes_hit *h) {
    ia_real ok[3][PACKET_LANES], dk[3][PACKET_LANES], on[PACKET_LANES], t_k[PACKET_LANES], nk[3][PACKET_LANES];
    ia_real specular_k[PACKET_LANES], shininess_k[PACKET_LANES];
    float albedo_k[3][PACKET_LANES];
    int found[PACKET_LANES];
    weave_hit hits[PACKET_LANES];
    scene_lanes_trace(params, f, view, r, 0, 0, o, d, tf, live, pass_k, pixel, rays_k, evals_k, ok, dk, found, hits);
    IAV_STORE(select(IAV_R(0), IAV_R(1), live), on);
    for (int k = 0; k < PACKET_LANES; k++) {
        int got = found[k] == 1 && on[k] != 0, item = got ? hits[k].item : 0;
        ia_real ro[3] = {ok[0][k], ok[1][k], ok[2][k]}, rd[3] = {dk[0][k], dk[1][k], dk[2][k]}, g[3] = {0, 0, 0};
        if (got)
            scene_gradient(r->walks.prims, hits[k].solid, ro, rd, hits[k].t, params[PARAM_TIME_LO], g);
        ia_real len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        ia_real facing = g[0] * rd[0] + g[1] * rd[1] + g[2] * rd[2];
        int ok_g = len > 0 && isfinite(len);
        for (int c = 0; c < 3; c++) { /* facing the ray; -d where the gradient vanishes (as iacsg_scene_trace_rays) */
            nk[c][k] = !got ? 0 : ok_g ? (facing > 0 ? -g[c] : g[c]) / len : -rd[c];
            albedo_k[c][k] = f->albedo[SCENE_MATERIAL_FLOATS * item + SCENE_MATERIAL_RGB + c];
        }
        on[k] = got;
        t_k[k] = got ? hits[k].t : 0;
        h->item[k] = got ? hits[k].item : -1;
        specular_k[k] = f->albedo[SCENE_MATERIAL_FLOATS * item + SCENE_MATERIAL_SPECULAR];
        shininess_k[k] = got ? f->albedo[SCENE_MATERIAL_FLOATS * item + SCENE_MATERIAL_SHININESS] : 48;
    }
    for (int c = 0; c < 3; c++) {
        h->n[c] = IAV_LOAD(nk[c]);
        h->albedo[c] = IAV_CAT(vload, IA_VW)(0, albedo_k[c]);
    }
    h->on = IAV_LOAD(on) != 0;
    h->t = IAV_LOAD(t_k);
    h->specular = IAV_LOAD(specular_k);
    h->shininess = IAV_LOAD(shininess_k);
}

/* The opacity of the items that the packet's hits met (h->item, -1 for none: item 0's, unread), and what a ray
 * on through each passes (pass_k, weave.h): a region is a volume, entered once and passed from inside; a surface
 * is crossed (0). */
static ia_realv scene_lanes_opacity(const scene_frame *f, const scene_lanes_hit *h, ia_real pass_k[PACKET_LANES]) {
    ia_real opacity_k[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        int item = max(h->item[k], 0);
        opacity_k[k] = f->albedo[SCENE_MATERIAL_FLOATS * item + SCENE_MATERIAL_OPACITY];
        pass_k[k] = f->items[SCENE_ITEM_INTS * item + SCENE_ITEM_KIND] == SCENE_KIND_REGION ? 1 + item : 0;
    }
    return IAV_LOAD(opacity_k);
}

/* What of light L (unit: its direction where it is at infinity) reaches the lanes of `cast` along their shadow
 * rays (from so, directions sd, dist to the light) where some item lets light through, as the host's
 * shadow_fractions: 1 - opacity of each item a ray meets (a region is a volume, entered once: the ray goes on from
 * inside it, passing it; a surface is crossed), none past an opaque one; for at most EFFECTS_MAX_LAYERS items, or
 * until less than EFFECTS_MIN_WEIGHT of the light is left. Each leg traced in lanes (scene_lanes_hits) from just
 * past the last item's surface, aimed at the light again. */
static ia_realv scene_lanes_transmitted(__constant ia_real *params, const scene_frame *f, const scene_view *view,
                                        scene_ray *r, __constant ia_real *L, const ia_real unit[3],
                                        const ia_realv so_in[3], const ia_realv sd_in[3], ia_realv dist,
                                        ia_maskv cast, int pixel[PACKET_LANES], kernel_u32 rays_k[PACKET_LANES],
                                        kernel_u32 evals_k[PACKET_LANES]) {
    ia_realv so[3], sd[3], vis = select(IAV_R(0), IAV_R(1), cast);
    ia_real pass_k[PACKET_LANES];
    IAV_STORE(IAV_R(0), pass_k);
    for (int c = 0; c < 3; c++) {
        so[c] = so_in[c];
        sd[c] = sd_in[c];
    }
    ia_maskv ray = cast;
    for (int layer = 0; layer < EFFECTS_MAX_LAYERS && iav_any(ray); layer++) {
        scene_lanes_hit h;
        scene_lanes_hits(params, f, view, r, so, sd, dist, ray, pass_k, pixel, rays_k, evals_k, &h);
        ia_realv a = scene_lanes_opacity(f, &h, pass_k);
        ia_maskv met = ray & h.on;
        vis = select(vis, vis * (1 - a), met);
        ray = met & (vis >= (ia_real)EFFECTS_MIN_WEIGHT);
        if (!iav_any(ray))
            break;
        ia_realv p[3], next[3], towards[3];
        for (int c = 0; c < 3; c++)
            p[c] = so[c] + h.t * sd[c];
        ia_realv off = effects_offset(view->eps, p, h.t);
        for (int c = 0; c < 3; c++) /* on from just past it: its normal faces the shadow ray */
            next[c] = p[c] - off * h.n[c];
        ia_realv far = shade_towards(L, unit, next, towards);
        for (int c = 0; c < 3; c++) {
            so[c] = select(so[c], next[c], ray);
            sd[c] = select(sd[c], towards[c], ray);
        }
        dist = select(dist, far, ray);
    }
    return vis;
}

/* The linear colours of the hits (lanes of `hit`) at t along rays o + t d, unit normals n facing them, by the
 * effects' block f->fx (units: its lights' directions, shade_light_units): each light seen where it is in front
 * of the surface and, with shadows, as far as its shadow ray from off the surface (effects_offset) lets it through:
 * where every item is opaque, where the ray meets no item (scene_rays_trace's `whether`); else what the items it
 * meets let through (scene_lanes_transmitted; f->fx's opacity is the scene's least); traced in lanes with r's
 * buffers. A lane whose shadow ray overflows them is listed to be traced again (pixel[k] -1), as a camera ray that
 * overflows. rays_k, evals_k: each lane's shadow rays and their evaluations, added. */
static void scene_lanes_light(__constant ia_real *params, const scene_frame *f, const scene_view *view, scene_ray *r,
                              const ia_real units[EFFECTS_MAX_LIGHTS][3], const ia_realv o[3], const ia_realv d[3],
                              ia_realv t, ia_maskv hit, const ia_realv n[3], int pixel[PACKET_LANES],
                              const shade_colorv albedo[3], ia_realv specular, ia_realv shininess,
                              kernel_u32 rays_k[PACKET_LANES], kernel_u32 evals_k[PACKET_LANES], shade_colorv lin[3]) {
    __constant ia_real *fx = f->fx;
    int nlights = (int)fx[EFFECTS_NLIGHTS], shadows = fx[EFFECTS_SHADOWS] != 0;
    ia_realv p[3], so[3], vis[EFFECTS_MAX_LIGHTS];
    for (int c = 0; c < 3; c++)
        p[c] = o[c] + t * d[c];
    effects_off_surface(view->eps, p, t, n, so); /* on the side the normal faces (the ray's) */
    scene_rays_start start = {iav_point(0), (ia_maskv)0}; /* g at so, for each light's shadow ray */
    for (int l = 0; l < EFFECTS_MAX_LIGHTS; l++) /* shade_effects reads the first nlights */
        vis[l] = IAV_R(l < nlights);
    for (int l = 0; shadows && l < nlights; l++) {
        __constant ia_real *L = fx + EFFECTS_LIGHTS + EFFECTS_LIGHT_REALS * l;
        ia_realv sd[3];
        ia_maskv cast = shade_facing(L, units[l], p, n, hit);
        ia_realv dist = shade_towards(L, units[l], so, sd);
        vis[l] = select(IAV_R(0), IAV_R(1), cast);
        if (!iav_any(cast))
            continue;
        if (fx[EFFECTS_OPACITY] < 1) { /* some item lets light through */
            vis[l] = scene_lanes_transmitted(params, f, view, r, L, units[l], so, sd, dist, cast, pixel, rays_k,
                                             evals_k);
            continue;
        }
        ia_real sk[3][PACKET_LANES], sdk[3][PACKET_LANES], pass[PACKET_LANES], seen[PACKET_LANES];
        int found[PACKET_LANES];
        weave_hit hits[PACKET_LANES];
        IAV_STORE(IAV_R(0), pass);
        scene_lanes_trace(params, f, view, r, 1, &start, so, sd, dist, cast, pass, pixel, rays_k, evals_k, sk, sdk,
                          found, hits);
        for (int k = 0; k < PACKET_LANES; k++) /* seen where the ray meets nothing */
            seen[k] = found[k] == 0;
        vis[l] = select(IAV_R(0), IAV_LOAD(seen), cast);
    }
    shade_colorv id_rgb[3];
    for (int c = 0; c < 3; c++)
        id_rgb[c] = (shade_colorv)(0); /* no -shade ids here */
    shade_effects(fx, units, p, t, n, d, vis, albedo, specular, shininess, id_rgb, lin);
}

/* The linear colours that the packet's reflected rays (lanes of `mirror`: from so, directions md; no item lets
 * light through, so none passes a region) bring back: their hits lit as their parents (scene_lanes_light, shadows
 * and all); a miss the linear background of its pixel's row (bg, display). */
static void scene_lanes_mirror(__constant ia_real *params, const scene_frame *f, const scene_view *view, scene_ray *r,
                               const ia_real units[EFFECTS_MAX_LIGHTS][3], const ia_realv so[3], const ia_realv md[3],
                               ia_maskv mirror, const shade_colorv bg[3], int pixel[PACKET_LANES],
                               kernel_u32 rays_k[PACKET_LANES], kernel_u32 evals_k[PACKET_LANES],
                               shade_colorv lin[3]) {
    ia_real none[PACKET_LANES];
    IAV_STORE(IAV_R(0), none);
    scene_lanes_hit h;
    scene_lanes_hits(params, f, view, r, so, md, IAV_R(IA_INF), mirror, none, pixel, rays_k, evals_k, &h);
    shade_colorv shown[3];
    scene_lanes_light(params, f, view, r, units, so, md, h.t, h.on, h.n, pixel, h.albedo, h.specular, h.shininess,
                      rays_k, evals_k, shown);
    IAV_CAT(int, IA_VW) at = IAV_CAT(convert_int, IA_VW)(h.on) != 0;
    for (int c = 0; c < 3; c++)
        lin[c] = select(bg[c] * bg[c], shown[c], at);
}

/* The linear colours of the packet's hits through their transparent layers (no reflected ray:
 * src/render_effects.c), as the host's paths and fx_path_weights give them: a hit on an item of opacity a shows
 * a of the weight left (its colour: lit, scene_lanes_light) and lets 1 - a on, from just past its surface in the
 * same direction (into a region: passing through it, weave.h), to the next hit; a ray that meets nothing, or a
 * weight under EFFECTS_MIN_WEIGHT or the EFFECTS_MAX_LAYERS-th layer, ends in the background of the pixel's row
 * (bg, display). In: the camera rays' hits (o, d, h); lin: their colours lit, replaced by the layers' sum. */
static void scene_lanes_layers(__constant ia_real *params, const scene_frame *f, const scene_view *view, scene_ray *r,
                               const ia_real units[EFFECTS_MAX_LIGHTS][3], const ia_realv o_in[3], const ia_realv d[3],
                               scene_lanes_hit *h, const shade_colorv bg[3], int pixel[PACKET_LANES],
                               kernel_u32 rays_k[PACKET_LANES], kernel_u32 evals_k[PACKET_LANES],
                               shade_colorv lin[3]) {
    ia_realv o[3], w = IAV_R(1);
    shade_colorv sum[3], bg2[3];
    for (int c = 0; c < 3; c++) {
        o[c] = o_in[c];
        sum[c] = (shade_colorv)(0);
        bg2[c] = bg[c] * bg[c];
    }
    for (int layer = 0; layer < EFFECTS_MAX_LAYERS; layer++) {
        ia_real pass_k[PACKET_LANES];
        ia_realv a = scene_lanes_opacity(f, h, pass_k), through = w * (1 - a);
        ia_maskv on = h->on, last = layer + 1 >= EFFECTS_MAX_LAYERS ? on : (ia_maskv)0;
        ia_maskv ends = on & (through > 0) & ((through < (ia_real)EFFECTS_MIN_WEIGHT) | last);
        ia_maskv on_through = on & (through > 0) & ~ends;
        if (layer > 0)
            scene_lanes_light(params, f, view, r, units, o, d, h->t, on, h->n, pixel, h->albedo, h->specular,
                              h->shininess, rays_k, evals_k, lin);
        shade_colorv shown = IAV_CAT(convert_float, IA_VW)(select(IAV_R(0), w * a, on));
        shade_colorv left = IAV_CAT(convert_float, IA_VW)(select(IAV_R(0), through, ends));
        for (int c = 0; c < 3; c++)
            sum[c] += shown * lin[c] + left * bg2[c];
        if (!iav_any(on_through))
            break;
        ia_realv p[3];
        for (int c = 0; c < 3; c++)
            p[c] = o[c] + h->t * d[c];
        ia_realv off = effects_offset(view->eps, p, h->t);
        for (int c = 0; c < 3; c++) /* on from just past the surface */
            o[c] = select(o[c], p[c] - off * h->n[c], on_through);
        scene_lanes_hits(params, f, view, r, o, d, IAV_R(IA_INF), on_through, pass_k, pixel, rays_k, evals_k, h);
        shade_colorv missed = IAV_CAT(convert_float, IA_VW)(select(IAV_R(0), through, on_through & ~h->on));
        for (int c = 0; c < 3; c++)
            sum[c] += missed * bg2[c];
        w = select(IAV_R(0), through, on_through);
    }
    for (int c = 0; c < 3; c++)
        lin[c] = sum[c];
}

/* The display colours of a packet's lanes by the effects' block (src/render_effects.c applies it in this kernel
 * where it can: render_effects_in_camera), as kernels/scene_centre.cl, iacsg_scene_shade and the host's paths give
 * them after the frame: each hit (at t_k along its ray; item_k; unit normal n, facing the ray) lit by the block's
 * lights (scene_lanes_light); where the block has bounces (at most one, every item opaque: src/render_effects.c) and
 * the hit's material reflects a fraction k (not under EFFECTS_MIN_WEIGHT), its colour weighs 1 - k and its
 * reflected ray's (scene_lanes_mirror) k, as the host's fx_path_weights; a miss the block's background. With
 * KERNEL_STATS each pixel's secondary rays and their evaluations go to f->fx_counts. */
static void scene_packet_lit(__constant ia_real *params, const scene_frame *f, const scene_view *camera,
                             const scene_ray *ray, ia_real ok[3][PACKET_LANES], ia_real dk[3][PACKET_LANES],
                             const ia_real t_k[PACKET_LANES], const int item_k[PACKET_LANES], ia_maskv hit,
                             const ia_realv n[3], int pixel[PACKET_LANES], shade_colorv row,
                             const shade_colorv albedo[3], ia_realv specular, ia_realv shininess, shade_colorv rgb[3]) {
    __constant ia_real *fx = f->fx;
    scene_view view = {camera->box, camera->link, camera->nodes, camera->surfaces, camera->nsurfaces, f->fx_eps,
                       camera->time, 0};
    scene_ray r = *ray; /* its buffers, not the camera rays' shared direction */
    r.walks.dirs = 0;
    r.walks.lanes = 0;
    ia_realv o[3], d[3], t = IAV_LOAD(t_k);
    for (int c = 0; c < 3; c++) {
        o[c] = IAV_LOAD(ok[c]);
        d[c] = IAV_LOAD(dk[c]);
    }
    ia_real units[EFFECTS_MAX_LIGHTS][3];
    shade_light_units(params, fx, units);
    kernel_u32 rays_k[PACKET_LANES], evals_k[PACKET_LANES];
    ia_real reflect_k[PACKET_LANES];
    int layers = 0; /* a hit lets light through */
    for (int k = 0; k < PACKET_LANES; k++) {
        __global const float *m = f->albedo + SCENE_MATERIAL_FLOATS * max(item_k[k], 0);
        rays_k[k] = evals_k[k] = 0;
        reflect_k[k] = item_k[k] >= 0 ? m[SCENE_MATERIAL_REFLECT] : 0;
        layers |= item_k[k] >= 0 && m[SCENE_MATERIAL_OPACITY] < 1;
    }
    shade_colorv lin[3], bg[3];
    scene_lanes_light(params, f, &view, &r, units, o, d, t, hit, n, pixel, albedo, specular, shininess, rays_k,
                      evals_k, lin);
    scene_fx_background(f, row, bg);
    ia_realv k = IAV_LOAD(reflect_k);
    ia_maskv mirror = hit & (k >= (ia_real)EFFECTS_MIN_WEIGHT);
    int lit = (int)fx[EFFECTS_SHADE] == EFFECTS_SHADE_LIT || (int)fx[EFFECTS_SHADE] == EFFECTS_SHADE_GRADIENT;
    if (fx[EFFECTS_BOUNCES] > 0 && lit && iav_any(hit & (k > 0))) {
        ia_realv p[3], so[3], md[3], dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        for (int c = 0; c < 3; c++)
            p[c] = o[c] + t * d[c];
        ia_realv off = effects_offset(view.eps, p, t);
        for (int c = 0; c < 3; c++) { /* the mirror direction d - 2 (d.n) n, from off the surface */
            so[c] = p[c] + off * n[c];
            md[c] = d[c] - 2 * dn * n[c];
        }
        ia_realv len = sqrt(md[0] * md[0] + md[1] * md[1] + md[2] * md[2]);
        for (int c = 0; c < 3; c++)
            md[c] = md[c] / len;
        shade_colorv seen[3];
        if (iav_any(mirror))
            scene_lanes_mirror(params, f, &view, &r, units, so, md, mirror, bg, pixel, rays_k, evals_k, seen);
        shade_colorv kc = IAV_CAT(convert_float, IA_VW)(k);
        IAV_CAT(int, IA_VW) mirrored = IAV_CAT(convert_int, IA_VW)(mirror) != 0;
        for (int c = 0; c < 3; c++)
            lin[c] = lin[c] * (1 - kc) + select((shade_colorv)(0), kc * seen[c], mirrored);
    }
    if (lit && layers) { /* no reflected ray then (src/render_effects.c) */
        scene_lanes_hit h = {hit, t, {n[0], n[1], n[2]}, {0}, {albedo[0], albedo[1], albedo[2]}, specular, shininess};
        for (int k = 0; k < PACKET_LANES; k++)
            h.item[k] = item_k[k];
        scene_lanes_layers(params, f, &view, &r, units, o, d, &h, bg, pixel, rays_k, evals_k, lin);
    }
    IAV_CAT(int, IA_VW) on = IAV_CAT(convert_int, IA_VW)(hit) != 0;
    for (int c = 0; c < 3; c++) /* display-encoded as fx_encode (fmax takes 0 over NaN) */
        rgb[c] = f->linear ? select(bg[c] * bg[c], lin[c], on)
                           : select(bg[c], sqrt(fmin(fmax(lin[c], 0.0f), 1.0f)), on);
#ifdef KERNEL_STATS
    for (int k = 0; k < PACKET_LANES && f->fx_counts; k++)
        if (pixel[k] >= 0) {
            f->fx_counts[2 * pixel[k]] = rays_k[k];
            f->fx_counts[2 * pixel[k] + 1] = evals_k[k];
        }
#endif
}

#endif
