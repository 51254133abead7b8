/* kernels/render_scene.cl -- the entry point of the segment path, iacsg_render_scene: one work-item per block of
 * PACKET_W x PACKET_H tiles (SCENE_BLOCK pixels square) of the band of block rows from block_row0 or, when
 * `pixels` is not NULL, per 16 listed pixels 16 (block_row0 + g) + 0..15 (rays traced again with larger buffers).
 * Rows from row_end on (past the view's band of rows, iacsg_view.row_count) are neither traced nor written.
 *
 * Per block: the union's tile pass over its 16 tiles in SIMD lanes (scene_union.h, where the program has the
 * union), then its packets of PACKET_W x PACKET_H pixels. Per packet: the surfaces' block passes (scene_block),
 * which prove where no ray of the packet can meet a surface; the camera rays clipped to the bounds (camera.h, in
 * lanes where the program has packet.h); with the union, its first root in lanes from the tile's leaf, and where
 * the regions are disjoint the claim at that leaf (scene_union_claim). Per pixel: the ray traced one at a time
 * (scene_trace.h) with the work-item's slice of the per-ray buffers; a ray that overflows them is appended to
 * `overflow` and writes nothing. A listed pixel is traced with its own packet and its block's tile pass, so
 * exactly as in the first pass. Then, in SIMD lanes, the normals (the hit solid's gradient, facing the eye) and
 * the colours (light.h, each pixel's item's albedo), or with the effects' block `fx` (every item opaque, at most
 * one bounce: src/render_effects.c) the effects' lights, each light's shadow rays and the reflected rays traced as
 * packets with the same buffers (scene_rays.h; one that overflows lists its pixel as above). Outputs per pixel: rgb,
 * depth (the claimed partition's start, +inf on a miss), normal, ids (the item, -1 on a miss), overlap (another
 * region certainly in the claimed partition, or -1), and with KERNEL_STATS the evaluations, segments and
 * partitions of each ray (and with `fx` its secondary rays and their evaluations, fx_counts).
 *
 * iacsg_render_scene_samples: -aa's sample rays (src/render_effects_samples.c) as the camera rays of an image aa
 * times as wide and high, the listed packets of listed blocks traced as above, each packet's lanes written to an
 * output slot of its own instead of its pixels, with the effects' block their colours in linear light.
 */
#include "packet_camera.h"
#include "scene_trace.h"
#include "light.h"
#include "scene_union.h"
#include "scene_rays.h"

/* The unit normal at o + t d of the solid: its gradient (scene_solid_f_grad). */
static void scene_gradient(scene_prims q, int solid, const ia_real o[3], const ia_real d[3], ia_real t, ia_real time,
                           ia_real g[3]) {
    scene_solid_f_grad(q, solid, o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2], time, &g[0], &g[1], &g[2]);
}

/* The block passes over the rays of the packet of pixels from (i0, j0), one per surface (surface.h): sets where
 * the rays start (starts) and returns the passes' evaluations, shared out over the packet's rays for the
 * statistics. (The same for the regions' solids, a pass proving where none can be other than OUT so that the
 * weaves start there, saved evaluations but no time: Fig. 2 as regions, 1000 spheres; BENCHMARKS.md.) */
static kernel_u32 scene_block(__constant ia_real *params, int flags, int i0, int j0, int width, int height,
                              __global const int *items, __global const uint *nodes, scene_prims prims,
                              ia_interval time, surface_start starts[SURFACE_BLOCK_MAX], scene_view *view) {
    int i1 = min(i0 + PACKET_W, width) - 1, j1 = min(j0 + PACKET_H, height) - 1;
    kernel_u32 evals = 0;
    for (int s = 0; s < min(view->nsurfaces, SURFACE_BLOCK_MAX); s++) {
        __global const int *it = items + SCENE_ITEM_INTS * view->surfaces[s];
        surface_block(params, flags & RENDER_ORTHO, i0, i1, j0, j1, width, height, it[SCENE_ITEM_SOLID],
                      it[SCENE_ITEM_ROOT], nodes, prims, time, &starts[s], &evals);
    }
    view->starts = starts;
    return (evals + PACKET_LANES - 1) / PACKET_LANES;
}

/* What the packets of a work-item share: the frame's parameters, tables and outputs (the kernel's arguments). */
typedef struct {
    int flags, width, height, row_end;
    __global const int *items;
    __global const uint *nodes;
    __global const float *albedo;
    __global float *rgb, *depth, *normal, *ids;
    __global int *overlap;
    __global uint *counts;
    __global int *overflow, *noverflow;
    int out0; /* where a packet's lanes write: -1 their pixels, else out0 + lane (-aa's samples) */
    __constant ia_real *fx; /* the effects' block where the packets apply them (scene_packet_lit), else 0 */
    __global uint *fx_counts; /* with them and KERNEL_STATS: each pixel's secondary rays and their evaluations */
    int linear; /* with them: the colours in linear light, unclamped (-aa's samples, summed by the host), else shown */
    int aa;     /* the image's pixels per view pixel across (-aa's samples: their pixel's row is row / aa) */
    ia_real fx_eps; /* the secondary rays' leaves (the view's eps, also for -aa's samples) */
} scene_frame;

/* The rays of the packet of pixels from (i0, j0) (camera_ray), their directions' reciprocals (ik, for the BVH),
 * and where they meet the bounds (meets[k] 1, over [tn[k], tf[k]]: camera_clip); a pixel outside the image or the
 * band's rows meets nothing. In SIMD lanes (packet_camera.h, bit for bit the scalar functions' results) where the
 * program has them, else one by one. Returns whether any ray meets the bounds (from the lanes' mask: meets[]
 * read back as a vector right after its stores in parts was a store-forwarding stall, 2 % of truck's render). */
static int scene_packet_rays(__constant ia_real *params, const scene_frame *f, int i0, int j0,
                              ia_real ok[3][PACKET_LANES], ia_real dk[3][PACKET_LANES], ia_real ik[3][PACKET_LANES],
                              ia_real tn[PACKET_LANES], ia_real tf[PACKET_LANES], ia_real meets[PACKET_LANES]) {
    int ortho = f->flags & RENDER_ORTHO, width = f->width, height = f->height;
#ifdef PACKET_CAMERA_LANES
    packet_int lanes = packet_lane_numbers();
    packet_int col = i0 + lanes % PACKET_W, row = j0 + lanes / PACKET_W;
    ia_realv o[3], d[3], t_near, t_far;
    packet_rays(params, ortho, min(col, width - 1), min(row, height - 1), width, height, o, d);
    ia_maskv in = (col < width) & (row < f->row_end) & packet_clip(params, o, d, &t_near, &t_far);
    for (int c = 0; c < 3; c++) {
        IAV_STORE(o[c], ok[c]);
        IAV_STORE(d[c], dk[c]);
        IAV_STORE(IAV_R(1) / d[c], ik[c]);
    }
    IAV_STORE(t_near, tn);
    IAV_STORE(t_far, tf);
    IAV_STORE(select(IAV_R(0), IAV_R(1), in), meets);
    return iav_any(in);
#else
    int any = 0;
    for (int k = 0; k < PACKET_LANES; k++) {
        int i = i0 + k % PACKET_W, j = j0 + k / PACKET_W;
        ia_real o[3], d[3];
        camera_ray(params, ortho, min(i, width - 1), min(j, height - 1), width, height, o, d);
        meets[k] = i < width && j < f->row_end && camera_clip(params, o, d, &tn[k], &tf[k]);
        for (int c = 0; c < 3; c++) {
            ok[c][k] = o[c];
            dk[c][k] = d[c];
            ik[c][k] = (ia_real)1 / d[c];
        }
        any |= meets[k] != 0;
    }
    return any;
#endif
}

/* Drops from the packet's cut the solids proven out along every ray of its beam over the beam's range in their
 * boxes (segments_beam_out: each ray's range there is within it, and outside its box a solid is out), so that
 * its rays neither test nor solve them. */
static void scene_beam_drop_out(scene_prims prims, const bvh_beam *beam, scene_view *view, int cut[BVH_CUT_MAX]) {
#ifdef SCENE_SOLID_PRIMS
    ia_interval o[3], d[3];
    for (int c = 0; c < 3; c++) {
        o[c] = ia_make(beam->olo[c], beam->ohi[c]);
        d[c] = ia_make(beam->dlo[c], beam->dhi[c]);
    }
    for (int j = 0; j < view->ncut;) {
        int solid = view->link[2 * cut[j] + SCENE_BVH_SOLID];
        ia_real ta, tend;
        if (solid >= 0 && bvh_beam_range(beam, view->box, cut[j], &ta, &tend) &&
            segments_beam_out(prims, solid, o, d, ta, tend))
            cut[j] = cut[--view->ncut];
        else
            j++;
    }
#else
    (void)prims;
    (void)beam;
    (void)view;
    (void)cut;
#endif
}

/* Where lane k of a packet, pixel (i, j), writes its outputs: that pixel, or slot out0 + k (-aa's samples); -1 for
 * a lane outside the image or the band's rows, or other than `only` (>= 0). */
static int scene_lane_output(const scene_frame *f, int i, int j, int k, int only) {
    if (i >= f->width || j >= f->row_end || (only >= 0 && k != only))
        return -1;
    return f->out0 < 0 ? j * f->width + i : f->out0 + k;
}

/* A traced pixel's outputs but its colour and normal: depth, ids, overlap and (KERNEL_STATS) its ray's counts. */
static void scene_store_hit(const scene_frame *f, int pixel, int found, const weave_hit *hit, kernel_u32 evals,
                            kernel_u32 segments, kernel_u32 partitions) {
    if (f->depth)
        f->depth[pixel] = found ? camera_depth_round_down(hit->t) : INFINITY;
    f->ids[pixel] = found ? (float)hit->item : -1.0f;
    f->overlap[pixel] = found ? hit->overlap : -1;
#ifdef KERNEL_STATS
    f->counts[3 * pixel] = evals;
    f->counts[3 * pixel + 1] = segments;
    f->counts[3 * pixel + 2] = partitions;
#else
    (void)evals;
    (void)segments;
    (void)partitions;
#endif
}

/* The packet's colours (linear rgb in lanes) and, where the frame keeps them, normals (NULL: none hit), to its
 * pixels (pixel[k] >= 0). */
static void scene_store_colors(const scene_frame *f, const int pixel[PACKET_LANES], const shade_colorv rgb[3],
                               const ia_realv *n) {
    float color[3][PACKET_LANES];
    ia_real nk[3][PACKET_LANES];
    for (int c = 0; c < 3; c++) {
        IAV_CAT(vstore, IA_VW)(rgb[c], 0, color[c]);
        if (n && f->normal)
            IAV_STORE(n[c], nk[c]);
    }
    for (int k = 0; k < PACKET_LANES; k++) {
        if (pixel[k] < 0)
            continue;
        for (int c = 0; c < 3; c++) {
            f->rgb[3 * pixel[k] + c] = color[c][k];
            if (f->normal)
                f->normal[3 * pixel[k] + c] = n ? (float)nk[c][k] : 0.0f;
        }
    }
}

/* The display colours of the effects' background (f->fx's top and bottom) in rows `row`. */
static void scene_fx_background(const scene_frame *f, shade_colorv row, shade_colorv bg[3]) {
    float top[3], bottom[3];
    for (int c = 0; c < 3; c++) {
        top[c] = (float)f->fx[EFFECTS_BG_TOP + c];
        bottom[c] = (float)f->fx[EFFECTS_BG_BOTTOM + c];
    }
    shade_background(row, f->height / f->aa, top, bottom, bg);
}

/* The linear colours of the hits (lanes of `hit`) at t along rays o + t d, unit normals n facing them, by the
 * effects' block f->fx (units: its lights' directions, shade_light_units): each light seen where it is in front
 * of the surface and, with shadows, where its shadow ray from off the surface (effects_offset) meets no item (every
 * item is opaque: scene_rays_trace's `whether`), traced in lanes with r's buffers. A lane whose shadow ray
 * overflows them is listed to be traced again (pixel[k] -1), as a camera ray that overflows. rays_k, evals_k: each
 * lane's shadow rays and their evaluations, added. */
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
    ia_realv off = effects_offset(view->eps, p, t);
    for (int c = 0; c < 3; c++) /* off the surface, on the side its normal faces (the ray's) */
        so[c] = p[c] + off * n[c];
    for (int l = 0; l < EFFECTS_MAX_LIGHTS; l++) /* shade_effects reads the first nlights */
        vis[l] = IAV_R(l < nlights);
    for (int l = 0; shadows && l < nlights; l++) {
        __constant ia_real *L = fx + EFFECTS_LIGHTS + EFFECTS_LIGHT_REALS * l;
        ia_realv towards[3], sd[3];
        shade_towards(L, units[l], p, towards);
        ia_maskv cast = hit & (n[0] * towards[0] + n[1] * towards[1] + n[2] * towards[2] > 0);
        ia_realv dist = shade_towards(L, units[l], so, sd);
        vis[l] = select(IAV_R(0), IAV_R(1), cast);
        if (!iav_any(cast))
            continue;
        ia_real sk[3][PACKET_LANES], sdk[3][PACKET_LANES], tn[PACKET_LANES], tf[PACKET_LANES];
        ia_real meets[PACKET_LANES], pass[PACKET_LANES], seen[PACKET_LANES];
        for (int c = 0; c < 3; c++) {
            IAV_STORE(so[c], sk[c]);
            IAV_STORE(sd[c], sdk[c]);
        }
        IAV_STORE(IAV_R(0), tn);
        IAV_STORE(dist, tf);
        IAV_STORE(vis[l], meets);
        IAV_STORE(vis[l], seen);
        IAV_STORE(IAV_R(0), pass);
        int found[PACKET_LANES];
        weave_hit hits[PACKET_LANES];
        kernel_u32 evals[PACKET_LANES];
        scene_rays_trace(view, r, params, 1, sk, sdk, tn, tf, meets, pass, found, hits, evals);
        for (int k = 0; k < PACKET_LANES; k++) {
            if (found[k] == SCENE_TRACE_OVERFLOW && pixel[k] >= 0) {
                f->overflow[atomic_inc(f->noverflow)] = pixel[k];
                pixel[k] = -1;
            }
            rays_k[k] += seen[k] != 0;
            evals_k[k] += evals[k];
            seen[k] = found[k] == 0 ? seen[k] : 0;
        }
        vis[l] = IAV_LOAD(seen);
    }
    shade_colorv id_rgb[3];
    for (int c = 0; c < 3; c++)
        id_rgb[c] = (shade_colorv)(0); /* no -shade ids here */
    shade_effects(fx, units, p, t, n, d, vis, albedo, specular, shininess, id_rgb, lin);
}

/* What the packet's lanes hit: where, what and the material there, in lanes (a secondary ray's, scene_lanes_hits). */
typedef struct {
    ia_maskv on;     /* the lanes that hit */
    ia_realv t, n[3]; /* how far along the ray; the unit normal there, facing the ray */
    int item[PACKET_LANES];
    shade_colorv albedo[3];
    ia_realv specular, shininess;
} scene_lanes_hit;

/* The hits of the packet's secondary rays (lanes of `live`: from o, directions d, each passing pass_k[k], weave.h),
 * traced in lanes with r's buffers and leaves of the view's eps (scene_rays_trace; no item is opaque-only here:
 * not `whether`). A lane whose ray overflows r's buffers is listed to be traced again (pixel[k] -1). rays_k,
 * evals_k: each lane's rays and their evaluations, added. */
static void scene_lanes_hits(__constant ia_real *params, const scene_frame *f, const scene_view *view, scene_ray *r,
                             const ia_realv o[3], const ia_realv d[3], ia_maskv live,
                             const ia_real pass_k[PACKET_LANES], int pixel[PACKET_LANES],
                             kernel_u32 rays_k[PACKET_LANES], kernel_u32 evals_k[PACKET_LANES], scene_lanes_hit *h) {
    ia_real ok[3][PACKET_LANES], dk[3][PACKET_LANES], tn[PACKET_LANES], tf[PACKET_LANES], meets[PACKET_LANES];
    ia_real on[PACKET_LANES], t_k[PACKET_LANES], nk[3][PACKET_LANES];
    ia_real specular_k[PACKET_LANES], shininess_k[PACKET_LANES];
    float albedo_k[3][PACKET_LANES];
    for (int c = 0; c < 3; c++) {
        IAV_STORE(o[c], ok[c]);
        IAV_STORE(d[c], dk[c]);
    }
    IAV_STORE(IAV_R(0), tn);
    IAV_STORE(IAV_R(IA_INF), tf);
    IAV_STORE(select(IAV_R(0), IAV_R(1), live), meets);
    IAV_STORE(select(IAV_R(0), IAV_R(1), live), on);
    int found[PACKET_LANES];
    weave_hit hits[PACKET_LANES];
    kernel_u32 evals[PACKET_LANES];
    scene_rays_trace(view, r, params, 0, ok, dk, tn, tf, meets, pass_k, found, hits, evals);
    for (int k = 0; k < PACKET_LANES; k++) {
        if (found[k] == SCENE_TRACE_OVERFLOW && pixel[k] >= 0) {
            f->overflow[atomic_inc(f->noverflow)] = pixel[k];
            pixel[k] = -1;
        }
        rays_k[k] += on[k] != 0;
        evals_k[k] += evals[k];
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
    scene_lanes_hits(params, f, view, r, so, md, mirror, none, pixel, rays_k, evals_k, &h);
    shade_colorv shown[3];
    scene_lanes_light(params, f, view, r, units, so, md, h.t, h.on, h.n, pixel, h.albedo, h.specular, h.shininess,
                      rays_k, evals_k, shown);
    IAV_CAT(int, IA_VW) at = IAV_CAT(convert_int, IA_VW)(h.on) != 0;
    for (int c = 0; c < 3; c++)
        lin[c] = select(bg[c] * bg[c], shown[c], at);
}

/* The linear colours of the packet's hits through their transparent layers (no reflected ray, no shadows:
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
        ia_real opacity_k[PACKET_LANES], pass_k[PACKET_LANES];
        for (int k = 0; k < PACKET_LANES; k++) {
            int item = max(h->item[k], 0);
            opacity_k[k] = f->albedo[SCENE_MATERIAL_FLOATS * item + SCENE_MATERIAL_OPACITY];
            pass_k[k] = f->items[SCENE_ITEM_INTS * item + SCENE_ITEM_KIND] == SCENE_KIND_REGION ? 1 + item : 0;
        }
        ia_realv a = IAV_LOAD(opacity_k), through = w * (1 - a);
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
        scene_lanes_hits(params, f, view, r, o, d, on_through, pass_k, pixel, rays_k, evals_k, h);
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

/* A packet none of whose rays can hit (none meets the bounds, or its beam meets no solid's box and there is no
 * surface): its pixels get the background of their rows and no hit, as the traced path would give them, without
 * its per-ray scaffolding (an empty frame's packets cost 6x as much through it: the per-lane arrays' stores read
 * back in lanes). */
static void scene_packet_empty(__constant ia_real *params, const scene_frame *f, int i0, int j0, int only,
                               kernel_u32 block_evals) {
    int pixel[PACKET_LANES];
    float rows[PACKET_LANES];
    weave_hit none = {0, -1, -1, -1};
    for (int k = 0; k < PACKET_LANES; k++) {
        int i = i0 + k % PACKET_W, j = j0 + k / PACKET_W;
        pixel[k] = scene_lane_output(f, i, j, k, only);
        rows[k] = (float)(min(j, f->height - 1) / f->aa);
        if (pixel[k] >= 0)
            scene_store_hit(f, pixel[k], 0, &none, block_evals, 0, 0);
    }
    shade_colorv albedo[3], rgb[3];
    for (int c = 0; c < 3; c++)
        albedo[c] = (shade_colorv)(0);
    if (f->fx) {
        scene_fx_background(f, IAV_CAT(vload, IA_VW)(0, rows), rgb);
        for (int c = 0; c < 3 && f->linear; c++)
            rgb[c] *= rgb[c];
    } else
        shade_combine((ia_maskv)0, IAV_CAT(vload, IA_VW)(0, rows), f->height / f->aa, albedo, IAV_R(0), IAV_R(0),
                      IAV_R(0), IAV_R(0), rgb);
    scene_store_colors(f, pixel, rgb, 0);
}

/* Traces the packet of pixels from (i0, j0): all its rays, or (only >= 0) lane `only` alone, a listed ray traced
 * again exactly as in the first pass. The rays and their parts in the bounds come in SIMD lanes (packet.h), then
 * each is woven alone; `tile` is the union's tile pass for the packet's tile (scene_union.h), with its evaluations
 * shared out over the tile's rays. */
static void scene_packet(__constant ia_real *params, const scene_frame *f, scene_view *view, scene_ray *ray, int i0,
                         int j0, int only, const scene_tile *tile) {
    int width = f->width, height = f->height;
    surface_start starts[SURFACE_BLOCK_MAX];
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    kernel_u32 block_evals =
        scene_block(params, f->flags, i0, j0, width, height, f->items, f->nodes, ray->walks.prims, time, starts, view);
    ia_real ok[3][PACKET_LANES], dk[3][PACKET_LANES], ik[3][PACKET_LANES], tn[PACKET_LANES], tf[PACKET_LANES];
    ia_real meets[PACKET_LANES];
    if (!scene_packet_rays(params, f, i0, j0, ok, dk, ik, tn, tf, meets)) {
        scene_packet_empty(params, f, i0, j0, only, block_evals);
        return;
    }
    ia_real from[PACKET_LANES]; /* where each ray's weave starts (scene_union.h), or -inf: its own t_near */
    ia_real leaf_hi[PACKET_LANES]; /* the end of the union's leaf starting at from[k], or -inf */
    kernel_u32 from_evals[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        from[k] = leaf_hi[k] = -IA_INF;
        from_evals[k] = 0;
    }
#ifdef SCENE_UNION_PREPASS
    int states[SCENE_REGIONS_UNION][PACKET_LANES] = {{0}}; /* the solids' states over the leaves (disjoint regions) */
    scene_union_packet(params, f->flags, height, tile, ok, dk, tn, tf, meets, from, leaf_hi, states,
                       from_evals);
#else
    (void)tile;
#endif
    int pixel[PACKET_LANES], cut[BVH_CUT_MAX];
    bvh_beam beam;
    bvh_beam_start(&beam);
    for (int k = 0; k < PACKET_LANES; k++)
        if (i0 + k % PACKET_W < width && j0 + k / PACKET_W < f->row_end && meets[k] != 0)
            bvh_beam_add_lane(&beam, ok, dk, ik, k, tn[k], tf[k]);
#ifdef SEGMENTS_LANES
    if (ray->walks.lanes)
        segments_lanes_start(ray->walks.lanes, ok, ik, tn, from, tf, view->box, view->link, view->nodes);
#endif
    view->ncut = bvh_beam_cut(&beam, view->box, view->link, view->nodes, cut);
    view->cut = view->ncut >= 0 ? cut : 0;
    scene_beam_drop_out(ray->walks.prims, &beam, view, cut);
    bvh_cut_lanes cut_lanes;
    view->cut_lanes = view->ncut > 0 && bvh_cut_lanes_fill(&cut_lanes, view->box, cut, view->ncut, ok, dk, ik,
                                                           fmax(IAV_LOAD(tn), IAV_LOAD(from)), IAV_LOAD(tf))
                          ? &cut_lanes
                          : 0;
#ifndef SCENE_UNION_PREPASS
    if (view->ncut == 0 && view->nsurfaces == 0) { /* no ray meets a solid's box (bvh_beam_cut) */
        scene_packet_empty(params, f, i0, j0, only, block_evals);
        return;
    }
#endif
    ia_real gk[3][PACKET_LANES], on[PACKET_LANES], t_hit[PACKET_LANES];
    int item_hit[PACKET_LANES];
    float color[3][PACKET_LANES], rows[PACKET_LANES];
    ia_real specular[PACKET_LANES], shininess[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        int i = i0 + k % PACKET_W, j = j0 + k / PACKET_W;
        pixel[k] = scene_lane_output(f, i, j, k, only);
        rows[k] = (float)(min(j, height - 1) / f->aa);
        weave_hit hit = {0, -1, -1, -1};
        ray->evals = ray->segments = ray->partitions = 0;
        view->lane = k;
#ifdef SEGMENTS_LANES
        if (ray->walks.lanes)
            ray->walks.lanes->lane = k;
#endif
        ia_real o[3] = {ok[0][k], ok[1][k], ok[2][k]}, d[3] = {dk[0][k], dk[1][k], dk[2][k]};
        bvh_ray br = bvh_ray_lane(dk, ik, k);
        int found = 0, claimed = 0; /* claimed: at the union's leaf (scene_union_claim), or overflowing */
        if (pixel[k] >= 0 && meets[k] != 0 && (from[k] < IA_INF || view->nsurfaces > 0)) { /* else no hit */
#ifdef SCENE_REGIONS_DISJOINT
            if (leaf_hi[k] >= from[k])
                claimed = scene_union_claim(ray, states, k, -1, fmax(tn[k], from[k]), &hit);
#endif
            found = claimed == SCENE_TRACE_OVERFLOW ? claimed
                    : claimed ? scene_trace_surfaces(view, ray, o, d, tn[k], tf[k], 1, &hit)
                              : scene_trace_ray_from(view, ray, o, d, &br, tn[k], fmax(tn[k], from[k]), tf[k], &hit);
        }
        if (found == SCENE_TRACE_OVERFLOW) {
            f->overflow[atomic_inc(f->noverflow)] = pixel[k];
            pixel[k] = -1;
            found = 0;
        }
        on[k] = found;
        t_hit[k] = found ? hit.t : 0;
        item_hit[k] = found ? hit.item : -1;
        ia_real gradient[3] = {0, 0, 0};
        if (found) /* at a point, for shading */
            scene_gradient(ray->walks.prims, hit.solid, o, d, hit.t, params[PARAM_TIME_LO], gradient);
        for (int c = 0; c < 3; c++) {
            gk[c][k] = gradient[c];
            color[c][k] = found ? f->albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_RGB + c] : 0;
        }
        specular[k] = found ? f->albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_SPECULAR] : 0;
        /* a miss: the exponent that lets light.h's shade_highlight square (48) where the hits' do, so that a hit's
         * highlight does not hang on its packet's misses (a traced-again lane's packet is misses but it) */
        shininess[k] = found ? f->albedo[SCENE_MATERIAL_FLOATS * hit.item + SCENE_MATERIAL_SHININESS] : 48;
        if (pixel[k] >= 0)
            scene_store_hit(f, pixel[k], found, &hit, ray->evals + block_evals + from_evals[k], ray->segments,
                            ray->partitions);
    }
    ia_realv g[3], d_v[3], n[3];
    shade_colorv albedo_v[3], rgb_v[3];
    for (int c = 0; c < 3; c++) {
        g[c] = IAV_LOAD(gk[c]);
        d_v[c] = IAV_LOAD(dk[c]);
        albedo_v[c] = IAV_CAT(vload, IA_VW)(0, color[c]);
    }
    ia_maskv hit_v = IAV_LOAD(on) != 0;
    shade_colorv row_v = IAV_CAT(vload, IA_VW)(0, rows);
    if (iav_any(hit_v))
        shade_normals(g, d_v, n);
    for (int c = 0; c < 3 && !iav_any(hit_v); c++)
        n[c] = IAV_R(0);
    if (f->fx)
        scene_packet_lit(params, f, view, ray, ok, dk, t_hit, item_hit, hit_v, n, pixel, row_v, albedo_v,
                         IAV_LOAD(specular), IAV_LOAD(shininess), rgb_v);
    else if (iav_any(hit_v))
        shade_lit_materials(params, hit_v, n, d_v, row_v, height / f->aa, albedo_v, IAV_LOAD(specular),
                            IAV_LOAD(shininess), rgb_v);
    else /* a packet with no hit: its background only, no normals nor lighting */
        shade_combine(hit_v, row_v, height / f->aa, albedo_v, IAV_R(0), IAV_R(0), IAV_R(0), IAV_R(0), rgb_v);
    for (int c = 0; c < 3; c++)
        n[c] = select(IAV_R(0), n[c], hit_v);
    scene_store_colors(f, pixel, rgb_v, n);
}

/* The union's tile pass over the block of tiles from (tx0, ty0), where the program has the union (else nothing). */
static void scene_tiles(__constant ia_real *params, const scene_frame *f, int tx0, int ty0,
                        scene_tile tiles[PACKET_LANES]) {
#ifdef SCENE_UNION_PREPASS
    scene_union_tiles(params, f->flags, f->width, f->height, tx0, ty0, tiles);
#else
    (void)params;
    (void)f;
    (void)tx0;
    (void)ty0;
    for (int k = 0; k < PACKET_LANES; k++) {
        tiles[k].start.level = -1;
        tiles[k].above = 0;
        tiles[k].evals = 0;
    }
#endif
}

/* A work-item's table of its packet's planar solids solved in lanes (segments_lanes.h), where the program has them. */
#ifdef SEGMENTS_LANES
#define SCENE_LANES_DECLARE(name) segments_lanes name
#define SCENE_LANES_OF(name) (&(name))
#else
#define SCENE_LANES_DECLARE(name) (void)0
#define SCENE_LANES_OF(name) 0
#endif

/* A work-item's ray state over its slice `slot` of the per-ray buffers; dirs: where an orthographic view's rays,
 * which share their direction, keep the primitives' work on it. */
static scene_ray scene_slot_ray(__global const uint *nodes, __global const int *items,
                                __global const int *solid_items_start, __global const int *solid_items,
                                __global int *cand_solid, __global ia_real *cand_range, __global ia_real *cand_pos,
                                __global int *cand_level, __global bisect_index *cand_index, __global int *cand_newton,
                                __global ia_real *cand_newton_t, int cand_cap, __global uchar *state, int nsolids,
                                size_t slot, int flags, prim_dirs *dirs, segments_lanes *lanes, scene_prims prims) {
    size_t first = slot * (size_t)cand_cap;
    for (int k = 0; k < PRIM_DIRS_SLOTS; k++)
        dirs->solid[k] = -1;
    scene_ray ray = {nodes,
                     items,
                     solid_items_start,
                     solid_items,
                     {cand_solid + first, cand_range + 2 * first, cand_pos + first, cand_level + first,
                      cand_index + first, cand_newton + first, cand_newton_t + 2 * first,
                      flags & RENDER_ORTHO ? dirs : 0,
                      flags & RENDER_ORTHO ? lanes : 0,
                      prims},
                     cand_cap,
                     0,
                     0,
                     state + slot * nsolids,
                     0,
                     0,
                     0};
    return ray;
}

/* One work-item per block of PACKET_W x PACKET_H tiles (SCENE_BLOCK pixels square) from block row block_row0 on,
 * or, when `pixels` is not NULL, per 16 listed pixels (block_row0 + g) 16 + 0..15, each traced again with its
 * own packet, its block's tile pass included. */
__kernel void iacsg_render_scene(__constant ia_real *params, int flags, int width, int height, int block_row0,
                                 __global const int *pixels, int npixels, __global const ia_real *bvh_box,
                                 __global const int *bvh_link, int nbvh, __global const uint *nodes,
                                 __global const int *items, __global const int *solid_items_start,
                                 __global const int *solid_items, __global const int *surfaces, int nsurfaces,
                                 __global const float *albedo, __global int *cand_solid, __global ia_real *cand_range,
                                 __global ia_real *cand_pos, __global int *cand_level,
                                 __global bisect_index *cand_index, __global int *cand_newton,
                                 __global ia_real *cand_newton_t, int cand_cap, __global uchar *state, int nsolids,
                                 __global float *rgb, __global float *depth, __global float *normal,
                                 __global float *ids, __global int *overlap, __global uint *counts,
                                 __global int *overflow, __global int *noverflow, int row_end,
                                 __global const ia_real *prims, __constant ia_real *fx, __global uint *fx_counts) {
    size_t slot = get_global_id(1) * get_global_size(0) + get_global_id(0);
    int bx = (int)get_global_id(0) * SCENE_BLOCK, by = (block_row0 + (int)get_global_id(1)) * SCENE_BLOCK;
    if (!pixels && (bx >= width || by >= height))
        return;
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    scene_view view = {bvh_box, bvh_link, nbvh, surfaces, nsurfaces, params[PARAM_EPS], time, 0};
    prim_dirs dirs; /* every ray of an orthographic view has the same direction */
    SCENE_LANES_DECLARE(lanes);
    scene_ray ray = scene_slot_ray(nodes, items, solid_items_start, solid_items, cand_solid, cand_range, cand_pos,
                                   cand_level, cand_index, cand_newton, cand_newton_t, cand_cap, state, nsolids, slot,
                                   flags, &dirs, SCENE_LANES_OF(lanes), prims);
    scene_frame f = {flags, width, height, row_end, items, nodes, albedo, rgb, depth, normal, ids,
                     overlap, counts, overflow, noverflow, -1, fx, fx_counts, 0, 1, params[PARAM_EPS]};
    scene_tile tiles[PACKET_LANES];
    if (pixels) {
        for (int k = 0; k < PACKET_LANES; k++) {
            int n = (block_row0 + (int)slot) * PACKET_LANES + k;
            if (n >= npixels)
                return;
            int i = pixels[n] % width, j = pixels[n] / width;
            int tx = i / TILE_SIZE, ty = j / TILE_SIZE, tx0 = tx - tx % PACKET_W, ty0 = ty - ty % PACKET_H;
            int t = (ty - ty0) * PACKET_W + tx - tx0;
            scene_tiles(params, &f, tx0, ty0, tiles);
            scene_packet(params, &f, &view, &ray, i - i % PACKET_W, j - j % PACKET_H,
                         j % PACKET_H * PACKET_W + i % PACKET_W, &tiles[t]);
        }
        return;
    }
    scene_tiles(params, &f, bx / TILE_SIZE, by / TILE_SIZE, tiles);
    for (int t = 0; t < PACKET_LANES; t++)
        for (int j = 0; j < TILE_SIZE; j += PACKET_H)
            for (int i = 0; i < TILE_SIZE; i += PACKET_W) {
                int i0 = bx + t % PACKET_W * TILE_SIZE + i, j0 = by + t / PACKET_W * TILE_SIZE + j;
                if (i0 < width && j0 < min(height, row_end))
                    scene_packet(params, &f, &view, &ray, i0, j0, -1, &tiles[t]);
            }
}

/* -aa's sample rays (src/render_effects_samples.c): sample (a, b) of pixel (i, j) is pixel (aa i + a, aa j + b) of
 * an image aa times as wide and high (width, height; params is that image's camera, with -aa's eps), whose centre
 * is the sample's point. One work-item per listed block (SCENE_SAMPLES_INTS ints each, kernels/scene_data.h) from
 * first_block on: the block's tile pass, then each listed packet traced as the camera rays are, its lanes written
 * to slot s, outputs PACKET_LANES s + lane (rgb, depth, normal, ids, overlap, counts as iacsg_render_scene's). A
 * sample's pixel of 4x4 samples is one packet, a coherent beam: the BVH cut, the union's leaf and the claim at it
 * serve all 16 rays. The per-ray buffers hold every solid (src/render_scene.c: render_scene_trace_args), so no ray
 * overflows; `overflow` lists any that would. With the effects' block fx, each sample's colour is lit by it
 * (scene_packet_lit, shadow and reflected rays and all, with leaves of fx_eps, the view's, as the host's paths;
 * the background of its pixel's row) in linear light, with KERNEL_STATS its secondary rays and their evaluations
 * to fx_counts (2 a slot's lane). */
__kernel void iacsg_render_scene_samples(__constant ia_real *params, int flags, int width, int height,
                                         __global const int *blocks, int nblocks, int first_block,
                                         __global const float *albedo, __global float *rgb, __global float *depth,
                                         __global float *normal, __global float *ids, __global int *overlap,
                                         __global uint *counts, __global int *overflow, __global int *noverflow,
                                         __global const ia_real *bvh_box, __global const int *bvh_link, int nbvh,
                                         __global const uint *nodes, __global const int *items,
                                         __global const int *solid_items_start, __global const int *solid_items,
                                         __global const int *surfaces, int nsurfaces, __global int *cand_solid,
                                         __global ia_real *cand_range, __global ia_real *cand_pos,
                                         __global int *cand_level, __global bisect_index *cand_index,
                                         __global int *cand_newton, __global ia_real *cand_newton_t, int cand_cap,
                                         __global uchar *state, int nsolids, __global const ia_real *prims,
                                         __constant ia_real *fx, __global uint *fx_counts, int aa,
                                         ia_real fx_eps) {
    size_t slot = get_global_id(0);
    int listed = first_block + (int)slot;
    if (listed >= nblocks)
        return;
    __global const int *block = blocks + SCENE_SAMPLES_INTS * (size_t)listed;
    ia_interval time = ia_make(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    scene_view view = {bvh_box, bvh_link, nbvh, surfaces, nsurfaces, params[PARAM_EPS], time, 0};
    prim_dirs dirs;
    SCENE_LANES_DECLARE(lanes);
    scene_ray ray = scene_slot_ray(nodes, items, solid_items_start, solid_items, cand_solid, cand_range, cand_pos,
                                   cand_level, cand_index, cand_newton, cand_newton_t, cand_cap, state, nsolids, slot,
                                   flags, &dirs, SCENE_LANES_OF(lanes), prims);
    scene_frame f = {flags, width, height, height, items, nodes, albedo, rgb, depth, normal, ids,
                     overlap, counts, overflow, noverflow, 0, fx, fx_counts, fx != 0, aa, fx_eps};
    int bx = block[SCENE_SAMPLES_BX] * SCENE_BLOCK, by = block[SCENE_SAMPLES_BY] * SCENE_BLOCK;
    int out = block[SCENE_SAMPLES_SLOT];
    scene_tile tiles[PACKET_LANES];
    scene_tiles(params, &f, bx / TILE_SIZE, by / TILE_SIZE, tiles);
    for (int p = 0; p < SCENE_BLOCK_PACKETS; p++) {
        if (!(((uint)block[SCENE_SAMPLES_MASK + p / 32] >> (p % 32)) & 1))
            continue;
        int t = p / SCENE_TILE_PACKETS, q = p % SCENE_TILE_PACKETS;
        int i0 = bx + t % PACKET_W * TILE_SIZE + q % SCENE_TILE_PACKETS_W * PACKET_W;
        int j0 = by + t / PACKET_W * TILE_SIZE + q / SCENE_TILE_PACKETS_W * PACKET_H;
        f.out0 = PACKET_LANES * out++;
        scene_packet(params, &f, &view, &ray, i0, j0, -1, &tiles[t]);
    }
}
