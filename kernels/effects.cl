/* kernels/effects.cl -- the first-root path's ray-tracing effects (src/render_effects.c,
 * src/render_effects_device.c), 16 paths per work-item in SIMD lanes: in the camera kernel (iacsg_render_effects,
 * its packets' hits shaded by effects_centre), or after the frame (iacsg_effects):
 *
 *   the paths' rays: the centre rays (their hits the camera kernel's, or the frame's depth and normals: nothing
 *   traced), -aa's n x n rays of listed pixels, or the reflected rays a previous launch listed --> their first
 *   hits (effects_trace)
 *   --> per hit: the lights, each seen or not by a shadow ray traced in the lanes --> its colour (light.h:
 *       shade_effects) times the path's weight
 *   --> off an opaque hit: the reflected ray goes on in the lane (weight reflect), traced in the same launch
 *   --> through a transparent hit: the ray goes on from past it, traced in the same launch; a reflected ray off
 *       it is listed for the next launch (kid_slots at most a path)
 *   --> until every lane is out of weight, bounces or layers, or has met the background
 *   --> per path: its colour (a centre ray's into its pixel of the frame), the reflected rays it listed
 *
 * Every secondary ray is traced rigorously (effects_trace: effects_march, then packet.h's bisection) with all
 * groups of a union, so an occluder or a surface a ray crosses inside the bounds is never missed; in the camera
 * kernel a transparent layer's ray, its camera ray's continuation, searches only the runs of its tile's rays where
 * the tile pass found that surface may be (tile.h: tile_runs, over boxes grown by how far the layers' rays may lie
 * off their camera rays; layer rays 9.67 -> 5.34 evaluations on the reference view); a layer's or a shadow ray's
 * way on past a surface it crossed by a proven crossing (march.h: march_crossing) starts along the same line from
 * the end of that crossing's step, F known there (5.34 -> 4.29). The rays of a packet come
 * from neighbouring pixels (a camera packet's, or listed by the host in blocks of 4 x 4), so that they take
 * similar steps. The normals are render.cl's packet_gradients (this file is appended to the first-root path's
 * program after render.cl).
 */

#include "march.h"

/* The first hits of the rays o + t d of the lanes of `on` in [tn, tf] within the bounds, with leaves of width eps
 * and interval Newton from nodes no wider than 32 `newton` (packet.h): the start of the hit leaf in *t (+inf on a
 * miss) and, where `normals`, the unit normal there facing the ray in n. With `whether` (no normals), a hit's *t
 * may be the start of a longer part of the ray that certainly holds the first root (effects_march). A ray that
 * starts next to a surface (`leaving`, its distance from it) first leaves it by effects_march, which searches only
 * the runs of the lanes in `runs` (NULL: none) and starts those of `crossing` (NULL: none; in and out, march.h) past
 * a proven crossing, F known there. The tree is [0, w], w the farthest end of the packet's rays (so no level of it
 * is spent on a node that holds a whole ray). Counts the rays and their evaluations (KERNEL_STATS). */
static ia_maskv effects_trace(__constant ia_real *params, __global const ulong *all_groups, const ia_realv o[3],
                              const ia_realv d[3], ia_realv tn, ia_realv tf, ia_maskv on, ia_realv leaving,
                              ia_real eps, ia_real newton, int whether, ia_realv *t, int normals, ia_realv n[3],
                              const march_runs *runs, march_crossing *crossing, packet_index *rays,
                              packet_index *evals) {
    ia_realv t_near, t_far;
    ia_maskv searching = on & packet_clip(params, o, d, &t_near, &t_far);
    t_near = fmax(t_near, tn);
    t_far = fmin(t_far, tf);
    searching &= t_near <= t_far;
    PACKET_COUNT(*rays, on);
    ia_realv lo = IAV_R(0), hi = IAV_R(0);
    ia_real time = params[PARAM_TIME_LO];
    iav times = iav_const(time, params[PARAM_TIME_HI]);
    ia_real w = march_farthest(t_far, searching);
    ia_maskv hit = (ia_maskv)0, marching = searching & (leaving > 0);
    if (crossing && !iav_any(marching))
        crossing->lanes = (ia_maskv)0; /* else effects_march's in and out */
#ifdef PACKET_NEWTON
    if (iav_any(marching)) {
        ia_maskv walking = marching;
        hit = effects_march(o, d, &t_near, &t_far, &walking, leaving, runs, crossing, eps, whether, times, &lo, &hi,
                            evals);
        searching &= ~marching | walking;
    }
#else
    (void)runs;
#endif
    if (iav_any(searching))
        hit |= packet_first_root(all_groups, o, d, 0, w, (packet_int)0, (packet_index)0, t_near, t_far, searching,
                                 eps, newton, 0, times, &lo, &hi, evals);
    *t = select(IAV_R(IA_INF), lo, hit);
    if (normals) {
        ia_realv g[3] = {IAV_R(0), IAV_R(0), IAV_R(0)};
        if (iav_any(hit))
            packet_gradients(all_groups, 0, w, hit, o, d, lo * (ia_real)0.5 + hi * (ia_real)0.5, time, g);
        shade_normals(g, d, n);
    }
    return hit;
}

/* -aa's sample rays o + t d of the lanes of `on`, ray k through doubled column x2[k] and row y2[k] of pixel pix[k]
 * (packet_rays_at), with leaves eps wide and Newton's window `newton`. A ray inside the box of its tile's centre
 * rays (doubled columns and rows from its first pixel's centre's to its last's: tile_rays_of's box holds every ray
 * between, its bounds monotone in them, or widened for an inexact /) is traced as the camera rays are (render.cl:
 * trace_packet), from the tile's first coarse leaf in `tiles` (none where the tile pass proved the tile empty); the
 * others, on its outer border, from the root of the frame's tree. The packet searches its tile's groups of a union
 * (tile_groups_of) where all its rays are inside one tile, else all_groups. A ray whose walk an earlier call left
 * at a node goes on from it: from[k] (level, node; level -1: none). With `turns` above 0 the walks stop after that
 * many turns (packet_first_root_turns): *left is then the lanes not done, their nodes in left_from. Out: the start
 * of the hit leaf in *t (+inf on a miss) and the unit normal there facing the ray in n. Counts the rays, where
 * `count_rays`, and their evaluations (KERNEL_STATS). Evaluations a sample at -aa 4 (all from the root before):
 * reference view 33.1 -> 26.7 (its camera rays 4.4), multiple unions 51.7 -> 44.4, gyroid in a ball 39.5 -> 32.3;
 * where a packet holds rays from the root, it waits for them, so its time falls less. */
static ia_maskv effects_trace_samples(__constant ia_real *params, int width, int height,
                                      __global const ia_real *tiles, __global const ulong *tile_groups_of,
                                      __global const ulong *all_groups, const int pix[IA_VW],
                                      const ia_real x2[IA_VW], const ia_real y2[IA_VW],
                                      const ia_real from[2][IA_VW], const ia_realv o[3], const ia_realv d[3],
                                      ia_maskv on, ia_real eps, ia_real newton, int turns, ia_maskv *left,
                                      ia_real left_from[2][IA_VW], ia_realv *t, ia_realv n[3], int count_rays,
                                      packet_index *rays, packet_index *evals) {
    int tiles_x = (width + TILE_SIZE - 1) / TILE_SIZE;
    ia_real level_k[IA_VW], leaf_k[IA_VW];
    size_t tile_k[IA_VW];
    int one_tile = 1;
    for (int k = 0; k < IA_VW; k++) {
        int tx = pix[k] % width / TILE_SIZE, ty = pix[k] / width / TILE_SIZE;
        int i0, i1, j0, j1;
        tile_pixels(tx, ty, width, height, &i0, &i1, &j0, &j1);
        int inside = x2[k] >= (ia_real)(2 * i0 + 1) && x2[k] <= (ia_real)(2 * i1 + 1) &&
                     y2[k] >= (ia_real)(2 * j0 + 1) && y2[k] <= (ia_real)(2 * j1 + 1);
        tile_k[k] = tile_index(tx, ty, tiles_x);
        level_k[k] = inside ? tiles[2 * tile_k[k]] : 0;
        leaf_k[k] = inside ? tiles[2 * tile_k[k] + 1] : 0;
        if (from && from[0][k] >= 0) { /* on from where an earlier walk left it */
            level_k[k] = from[0][k];
            leaf_k[k] = from[1][k];
        }
        one_tile &= inside && tile_k[k] == tile_k[0]; /* (the lanes past the launch's paths repeat its last one) */
    }
    const __global ulong *groups = one_tile ? tile_groups_of + tile_k[0] * TILE_GROUPS_WORDS : all_groups;
    ia_realv level_r = IAV_LOAD(level_k), t_near, t_far, lo = IAV_R(0), hi = IAV_R(0);
    ia_maskv searching = on & (level_r >= 0) & packet_clip(params, o, d, &t_near, &t_far), hit = (ia_maskv)0;
    if (count_rays)
        PACKET_COUNT(*rays, on);
    ia_real t0, w, time = params[PARAM_TIME_LO];
    frame_root(params, &t0, &w);
    packet_int level = select((packet_int)0, packet_to_int(level_r), searching);
    packet_index node = max(packet_to_index(IAV_LOAD(leaf_k)), packet_node_at_levels(t0, w, level, searching, t_near));
    if (iav_any(searching))
        hit = packet_first_root_turns(groups, o, d, t0, w, &level, &node, t_near, t_far, &searching, turns, eps, newton,
                                      0, iav_const(time, params[PARAM_TIME_HI]), &lo, &hi, evals);
    *left = searching;
    IAV_STORE(select((ia_realv)-1, packet_to_real(level), searching), left_from[0]);
    IAV_STORE(packet_to_real(node), left_from[1]);
    *t = select(IAV_R(IA_INF), lo, hit);
    ia_realv g[3] = {IAV_R(0), IAV_R(0), IAV_R(0)};
    if (iav_any(hit))
        packet_gradients(groups, t0, w, hit, o, d, lo * (ia_real)0.5 + hi * (ia_real)0.5, time, g);
    shade_normals(g, d, n);
    return hit;
}

/* The background (the effects' block fx: top and bottom colours) of rows `row` of `height`, linear. */
static void effects_background(__constant ia_real *fx, ia_realv row, int height, shade_colorv bg[3]) {
    float top[3], bottom[3];
    for (int c = 0; c < 3; c++) {
        top[c] = (float)fx[EFFECTS_BG_TOP + c];
        bottom[c] = (float)fx[EFFECTS_BG_BOTTOM + c];
    }
    shade_background(IAV_CAT(convert_float, IA_VW)(row), height, top, bottom, bg);
    for (int c = 0; c < 3; c++)
        bg[c] *= bg[c];
}

/* acc += w c in the lanes of `on`. */
static void effects_add(shade_colorv acc[3], ia_maskv on, ia_realv w, const shade_colorv c[3]) {
    IAV_CAT(int, IA_VW) lanes = IAV_CAT(convert_int, IA_VW)(on) != 0;
    shade_colorv wc = shade_to_color(w);
    for (int k = 0; k < 3; k++)
        acc[k] += select((shade_colorv)0, wc * c[k], lanes);
}

/* F at the point so every secondary ray off a hit's outer side starts from (p + off n: each light's shadow ray,
 * the reflected ray), evaluated once for the lanes of `lanes` at the first ray that needs it and handed to the
 * others' marches as known there (march.h: march_crossing at t = 0, where a ray's start is the point itself:
 * packet_extent at t = 0 is so, whatever the direction). With the default rig's two lights, or a light and a
 * reflection, a hit's rays had each evaluated it. Without the march (no derivative code) nothing is shared. */
typedef struct {
    ia_realv so[3];
    ia_maskv lanes, done, counted; /* the hits', those F is known for, those whose rays used it (the statistics) */
    iav f;
} effects_start;

/* The march's hint for rays from s->so in the lanes of `on`: F there, evaluated on first use. */
static march_crossing effects_start_hint(effects_start *s, ia_maskv on, iav time, packet_index *evals) {
#ifdef PACKET_FDV
    if (!iav_any(s->done) && iav_any(on)) {
        iav at = iav_point(0);
        s->f = packet_F(~(ulong)0, packet_extent(s->so[0], IAV_R(0), at), packet_extent(s->so[1], IAV_R(0), at),
                        packet_extent(s->so[2], IAV_R(0), at), time);
        s->done = s->lanes;
    }
    PACKET_COUNT(*evals, on & s->done & ~s->counted); /* one evaluation a lane, however many rays use it */
    s->counted |= on & s->done;
    march_crossing hint = {on & s->done, IAV_R(0), s->f};
#else
    (void)time, (void)evals;
    march_crossing hint = {(ia_maskv)0, IAV_R(0), s->f};
#endif
    return hint;
}

/* The paths of the lanes of `live` from their rays o + t d's first hits (where `hit`: at t, normal n) on, each of
 * weight `through`, its transparent layers and reflections so far `layers` and `bounces`, its pixel in row `row`:
 * each hit lit (its shadow rays traced), the reflected ray off an opaque hit and the ray through a transparent one
 * traced in the lane, a reflected ray off a transparent hit listed in kids (lane k's slots from kid_slots path[k] on,
 * nk[k] of them so far; none where kid_slots is 0), until every lane is out of weight, bounces or layers or has met
 * the background. Adds each lane's linear light to acc; counts the rays it traces and their evaluations. */
static void effects_paths(__constant ia_real *params, __constant ia_real *fx, __global const ulong *all_groups,
                          ia_real footprint, ia_realv row, int height, ia_realv o[3], ia_realv d[3], ia_maskv live,
                          ia_maskv hit, ia_realv t, ia_realv n[3], ia_realv through, ia_realv layers,
                          ia_realv bounces, __global ia_real *kids, int kid_slots, const int *path, int nk[IA_VW],
                          const tile_layer_runs *runs, shade_colorv acc[3], packet_index *rays,
                          packet_index *evals) {
    march_runs layer_runs = {runs, IAV_R(0), (ia_maskv)0}; /* tau0: where the layers start on their camera rays */
    march_crossing crossing = {(ia_maskv)0, IAV_R(0), iav_point(0)}; /* the last layer's hits that are proven */
    shade_colorv bg[3];
    effects_background(fx, row, height, bg);
    int shade = (int)fx[EFFECTS_SHADE], nlights = (int)fx[EFFECTS_NLIGHTS], shadows = fx[EFFECTS_SHADOWS] != 0;
    shade_colorv albedo[3], id_rgb[3];
    for (int c = 0; c < 3; c++) {
        albedo[c] = (shade_colorv)(float)fx[EFFECTS_ALBEDO + c];
        id_rgb[c] = (shade_colorv)(float)fx[EFFECTS_ID_RGB + c];
    }
    ia_real a = fx[EFFECTS_OPACITY], max_bounces = fx[EFFECTS_BOUNCES], eps = params[PARAM_EPS];
    iav times = iav_const(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    ia_real units[EFFECTS_MAX_LIGHTS][3];
    shade_light_units(params, fx, units);
    while (1) { /* one transparent layer a turn */
        effects_add(acc, live & ~hit, through, bg);
        live &= hit;
        if (!iav_any(live))
            break;
        ia_realv p[3];
        for (int c = 0; c < 3; c++)
            p[c] = o[c] + t * d[c];
        /* the light each hit gets from each light in front of it: all of it, or where shadows are cast what a
         * shadow ray from off the surface (on the light's side) to the light lets through: each crossing of a
         * transparent surface on the way keeps 1 - A of it (a layer, as the camera rays see it), an opaque one none */
        ia_realv off = effects_offset(eps, p, t), vis[EFFECTS_MAX_LIGHTS];
        effects_start start = {{p[0] + off * n[0], p[1] + off * n[1], p[2] + off * n[2]}, live, (ia_maskv)0,
                               (ia_maskv)0, iav_point(0)};
        for (int l = 0; l < nlights; l++) {
            __constant ia_real *L = fx + EFFECTS_LIGHTS + EFFECTS_LIGHT_REALS * l;
            ia_maskv ray = shade_facing(L, units[l], p, n, live);
            vis[l] = select(IAV_R(0), IAV_R(1), ray);
            ia_realv so[3] = {start.so[0], start.so[1], start.so[2]}, sd[3], sp = off, sn[3] = {n[0], n[1], n[2]}, st;
            /* through transparent surfaces as the layers go: past a proven crossing along the same line (the first
             * from the hit's shared start, F known there) */
            march_crossing past = {(ia_maskv)0, IAV_R(0), iav_point(0)};
            for (int layer = 0; shadows && shade < EFFECTS_SHADE_NORMALS && iav_any(ray); layer++) {
                ia_maskv restart = layer > 0 ? ray & ~past.lanes : (ia_maskv)0;
                for (int c = 0; c < 3; c++) /* off the surface it leaves, on the light's side */
                    so[c] = select(so[c], so[c] + sp * sn[c], restart);
                if (layer == 0)
                    past = effects_start_hint(&start, ray, times, evals);
                ia_realv dist = shade_towards(L, units[l], so, sd);
                ia_maskv blocked = effects_trace(params, all_groups, so, sd, select(IAV_R(0), past.b, past.lanes), dist,
                                                 ray, sp, eps, footprint, a >= 1, &st, a < 1, sn, 0, &past, rays,
                                                 evals);
                vis[l] = select(vis[l], vis[l] * (1 - a), blocked);
                ray = layer + 1 < EFFECTS_MAX_LAYERS ? blocked & (vis[l] >= (ia_real)EFFECTS_MIN_WEIGHT) : (ia_maskv)0;
                for (int c = 0; c < 3; c++) { /* on from past it: its normal faces the shadow ray */
                    ia_realv q = so[c] + st * sd[c];
                    so[c] = select(so[c], q, ray & ~past.lanes);
                    sn[c] = -sn[c];
                }
                sp = effects_offset(eps, so, st);
            }
        }
        shade_colorv lin[3];
        shade_effects(fx, units, p, t, n, d, vis, albedo, IAV_R(fx[EFFECTS_SPECULAR]), IAV_R(fx[EFFECTS_SHININESS]),
                      id_rgb, lin);
        if (shade >= EFFECTS_SHADE_NORMALS) { /* the previews: unlit, opaque */
            effects_add(acc, live, through, lin);
            break;
        }
        /* the fraction of the light reflected: the last bounce is lit only */
        ia_realv k = select(IAV_R(0), IAV_R(fx[EFFECTS_REFLECT]), bounces < max_bounces);
        effects_add(acc, live, through * (a * (1 - k)), lin);
        ia_maskv mirror = live & (k > 0) & (through * (a * k) >= (ia_real)EFFECTS_MIN_WEIGHT);
        ia_realv r[3] = {IAV_R(0), IAV_R(0), IAV_R(0)}; /* the mirror direction, where some lane reflects */
        if (iav_any(mirror)) {
            ia_realv dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            for (int c = 0; c < 3; c++)
                r[c] = d[c] - 2 * dn * n[c];
            ia_realv len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
            for (int c = 0; c < 3; c++)
                r[c] = r[c] / len;
        }
        if (a >= 1) { /* opaque: the reflected ray goes on in this lane, from off the surface */
            through = through * k;
            live = mirror;
            if (!iav_any(live))
                break;
            for (int c = 0; c < 3; c++) {
                o[c] = select(o[c], start.so[c], live);
                d[c] = select(d[c], r[c], live);
            }
            bounces = select(bounces, bounces + 1, live);
            march_crossing from = effects_start_hint(&start, live, times, evals);
            hit = effects_trace(params, all_groups, o, d, IAV_R(0), IAV_R(IA_INF), live, off, eps, footprint, 0, &t,
                                1, n, 0, &from, rays, evals);
            continue;
        }
        if (iav_any(mirror)) { /* transparent: the lane goes on through, the reflected ray is listed */
            ia_realv rec[EFFECTS_PATH_REALS];
            for (int c = 0; c < 3; c++) {
                rec[EFFECTS_PATH_O + c] = p[c] + off * n[c];
                rec[EFFECTS_PATH_D + c] = r[c];
            }
            rec[EFFECTS_PATH_WEIGHT] = through * (a * k);
            rec[EFFECTS_PATH_LAYERS] = layers;
            rec[EFFECTS_PATH_BOUNCES] = bounces + 1;
            ia_real on[IA_VW], fields[EFFECTS_PATH_REALS][IA_VW];
            IAV_STORE(select(IAV_R(0), IAV_R(1), mirror), on);
            for (int f = 0; f < EFFECTS_PATH_REALS; f++)
                IAV_STORE(rec[f], fields[f]);
            for (int q = 0; q < IA_VW; q++) {
                if (on[q] == 0 || nk[q] >= kid_slots)
                    continue;
                __global ia_real *out = kids + EFFECTS_PATH_REALS * ((size_t)path[q] * kid_slots + nk[q]++);
                for (int f = 0; f < EFFECTS_PATH_REALS; f++)
                    out[f] = fields[f][q];
            }
        }
        through *= 1 - a;
        live &= through > 0;
        ia_maskv spent = live & ((through < (ia_real)EFFECTS_MIN_WEIGHT) | (layers + 1 >= EFFECTS_MAX_LAYERS));
        effects_add(acc, spent, through, bg); /* what is left of the path */
        live &= ~spent;
        if (!iav_any(live))
            break;
        /* on through the surface, the same direction: past a proven crossing along the same line from the end of
         * its step (F off 0 since the leaf, and known there), else from just past the hit */
        ia_maskv restart = live & ~crossing.lanes;
        for (int c = 0; c < 3; c++)
            o[c] = select(o[c], p[c] - off * n[c], restart);
        layers = select(layers, layers + 1, live);
        layer_runs.tau0 = select(layer_runs.tau0, layer_runs.tau0 + t, restart);
        layer_runs.lanes = layers <= TILE_RUN_LAYERS;
        hit = effects_trace(params, all_groups, o, d, select(IAV_R(0), crossing.b, crossing.lanes), IAV_R(IA_INF),
                            live, off, eps, footprint, 0, &t, 1, n, runs ? &layer_runs : 0, &crossing, rays, evals);
    }
}

/* The display colours (gamma 2, as light.h encodes) of a camera packet's pixels in `live`, shaded with the effects
 * by the camera kernel itself (render.cl: trace_packet, given an effects block): the centre rays o + t d, their
 * hits (where `hit`: the leaf's start hit_lo, the normal n) lit and their paths followed as iacsg_effects'
 * EFFECTS_MODE_CENTRE follows them from the frame's depth and normals. Those are floats, so t and n are rounded
 * here as they are: a pixel gets the same colour either way. The host gives the camera kernel the block only where
 * no path lists a reflected ray (kid_slots 0). Counts the secondary rays and their evaluations. Not inlined into
 * the camera kernel: there its paths' code crowded the camera rays' (CPU samples of the reference view's kernel
 * with shadows, means of 3-5 runs: 2,600 inlined, 1,760-2,120 not; plain 1,470). */
__attribute__((noinline)) static void effects_centre(__constant ia_real *params, __constant ia_real *fx,
                                                     __global const ulong *all_groups, ia_real footprint,
                                                     packet_int row, int height, ia_maskv live, ia_maskv hit,
                                                     const ia_realv o_ray[3], const ia_realv d_ray[3],
                                                     ia_realv hit_lo, const ia_realv n_hit[3],
                                                     const tile_layer_runs *runs, shade_colorv color[3],
                                                     packet_index *rays, packet_index *evals) {
    if (!iav_any(live & hit)) { /* the background alone, as effects_paths gives it, without reading the rays: a
                                 * packet the tile pass proved empty has them zeroed in halves just before this
                                 * call, and loading them whole waited for those stores (a fifth of this
                                 * function's CPU samples); nor adding it to a zeroed sum, whose load waited on
                                 * the zeroing's stores in halves (a fifth again, with transparency) */
        shade_colorv bg[3];
        effects_background(fx, packet_to_real(row), height, bg);
        IAV_CAT(int, IA_VW) lanes = IAV_CAT(convert_int, IA_VW)(live) != 0;
        for (int c = 0; c < 3; c++)
            color[c] = select((shade_colorv)0, sqrt(fmin(fmax(bg[c], 0.0f), 1.0f)), lanes);
        return;
    }
    shade_colorv acc[3] = {(shade_colorv)0, (shade_colorv)0, (shade_colorv)0};
    ia_realv o[3], d[3], n[3], t = hit_lo;
    for (int c = 0; c < 3; c++) {
        o[c] = o_ray[c];
        d[c] = d_ray[c];
        n[c] = n_hit[c];
    }
#ifdef IA_FP64 /* in float both roundings are the identity: no copy through memory lane by lane (a third of this
                * function's CPU samples, the loads of the copy waiting on the caller's stores) */
    ia_real start[IA_VW], t_k[IA_VW], n_k[3][IA_VW];
    float n_f[3][IA_VW];
    IAV_STORE(hit_lo, start);
    for (int c = 0; c < 3; c++)
        IAV_CAT(vstore, IA_VW)(shade_to_color(n_hit[c]), 0, n_f[c]);
    for (int k = 0; k < IA_VW; k++) {
        t_k[k] = (ia_real)camera_depth_round_down(start[k]);
        for (int c = 0; c < 3; c++)
            n_k[c][k] = (ia_real)n_f[c][k];
    }
    t = IAV_LOAD(t_k);
    for (int c = 0; c < 3; c++)
        n[c] = IAV_LOAD(n_k[c]);
#endif
    int nk[IA_VW];
    for (int q = 0; q < IA_VW; q++)
        nk[q] = 0;
    effects_paths(params, fx, all_groups, footprint, packet_to_real(row), height, o, d, live, live & hit, t, n,
                  IAV_R(1), IAV_R(0), IAV_R(0), 0, 0, 0, nk, runs, acc, rays, evals);
    for (int c = 0; c < 3; c++)
        color[c] = sqrt(fmin(fmax(acc[c], 0.0f), 1.0f));
}

/* The arguments of a launch of iacsg_effects (described at effects_packet, below). */
typedef struct {
    __constant ia_real *params, *fx;
    int mode, flags, width, height, aa, kid_slots, aa_set, round, turns;
    __global const int *pixels;
    __global const ia_real *paths, *tiles, *from;
    __global const float *depth, *normal;
    ia_real aa_eps, footprint;
    __global const ulong *all_groups, *tile_groups_of;
    __global float *rgb, *color;
    __global ia_real *kids, *left, *hits;
    __global int *nkids, *counts;
    __global uint *stats;
} effects_launch;

/* Paths first .. first + 15 of the launch. mode (kernels/effects.h): EFFECTS_MODE_CENTRE, path k the centre ray
 * of pixel pixels[k], its hit the frame's (depth, normal); EFFECTS_MODE_AA, path k the ray (k mod m) of the m
 * rays of the aa x aa grid in `aa_set` (effects_aa_cell) in pixel pixels[k / m], weight 1 / aa^2, traced with
 * leaves aa_eps (as camera rays, from the frame's tile pass: `tiles` and `tile_groups_of`, render.cl's);
 * EFFECTS_MODE_PATHS, path k the ray paths[k] (EFFECTS_PATH_REALS) of pixel pixels[k]. Interval Newton's window
 * in the walks (packet.h): 32 `footprint`s, the camera rays'. Out per path: its colour (3 floats: linear light
 * times the weight, in `color`; a centre ray's in its pixel of the frame's `rgb`, display-encoded when it lists no
 * reflected ray), the reflected rays it lists (nkids, in kids from kid_slots k on), and with `stats`
 * (KERNEL_STATS) the rays it traced and their interval evaluations.
 * -aa's walks in rounds (EFFECTS_MODE_AA; a packet waits for its slowest ray): where `left` is not NULL a walk
 * stops after `turns` turns and its path goes on in the next round, listed in `left` (EFFECTS_LEFT_REALS a path:
 * its index, level and node) at counts[round] (counted atomically); where `from` is not NULL, the round's paths
 * are the counts[round - 1] listed there by the last (each on from its node), in full packets. Its outputs come
 * from the round that ends it; or, where `hits` is not NULL, the rounds (round >= 0) only trace, each walk's end
 * its path's hit in `hits` (4 a path: t, +inf on a miss, and the normal), and the launch after them (round -1)
 * shades the paths in their order from those hits: the leftover lists' order is the atomics', and a secondary ray's
 * steps depend on its packet (its tree is as long as its packet's farthest ray), so that shading them in the rounds
 * made images with shadows, reflections or layers differ from run to run. Statistics are summed over the launches. */
static void effects_packet(const effects_launch *a, int first, int here) {
    int walking = a->hits && a->round >= 0, shading = a->hits && a->round < 0; /* -aa's rounds, then their shading */
    int samples = a->mode == EFFECTS_MODE_AA ? effects_aa_rays(a->aa, a->aa_set) : 1, pix[IA_VW], path[IA_VW];
    ia_real valid_k[IA_VW], w_k[IA_VW], layers_k[IA_VW], bounces_k[IA_VW], row_k[IA_VW], x2_k[IA_VW], y2_k[IA_VW];
    ia_real t_k[IA_VW], from_k[2][IA_VW], left_k[2][IA_VW];
    ia_real o_k[3][IA_VW], d_k[3][IA_VW], n_k[3][IA_VW];
    for (int k = 0; k < IA_VW; k++) {
        int entry = min(first + k, here - 1);
        path[k] = a->from ? (int)a->from[EFFECTS_LEFT_REALS * entry] : entry;
        from_k[0][k] = a->from ? a->from[EFFECTS_LEFT_REALS * entry + 1] : -1;
        from_k[1][k] = a->from ? a->from[EFFECTS_LEFT_REALS * entry + 2] : 0;
        valid_k[k] = first + k < here;
        pix[k] = a->pixels[path[k] / samples];
        int i = pix[k] % a->width, j = pix[k] / a->width, s = path[k] % samples;
        row_k[k] = (ia_real)j;
        w_k[k] = a->mode == EFFECTS_MODE_AA ? (ia_real)1 / (ia_real)(a->aa * a->aa) : 1;
        layers_k[k] = bounces_k[k] = 0;
        x2_k[k] = (ia_real)(2 * i + 1); /* the centre ray's, exactly as the camera kernel's (packet_rays) */
        y2_k[k] = (ia_real)(2 * j + 1);
        if (a->mode == EFFECTS_MODE_AA) {
            int cell = effects_aa_cell(a->aa, a->aa_set, s);
            x2_k[k] = (ia_real)(2 * i) + (ia_real)(2 * (cell % a->aa) + 1) / (ia_real)a->aa;
            y2_k[k] = (ia_real)(2 * j) + (ia_real)(2 * (cell / a->aa) + 1) / (ia_real)a->aa;
        }
        t_k[k] = a->mode == EFFECTS_MODE_CENTRE ? (ia_real)a->depth[pix[k]] : shading ? a->hits[4 * path[k]] : 0;
        for (int c = 0; c < 3; c++)
            n_k[c][k] = a->mode == EFFECTS_MODE_CENTRE ? (ia_real)a->normal[3 * pix[k] + c]
                        : shading                      ? a->hits[4 * path[k] + 1 + c]
                                                       : 0;
        if (a->mode == EFFECTS_MODE_PATHS) {
            __global const ia_real *q = a->paths + EFFECTS_PATH_REALS * (size_t)path[k];
            for (int c = 0; c < 3; c++) {
                o_k[c][k] = q[EFFECTS_PATH_O + c];
                d_k[c][k] = q[EFFECTS_PATH_D + c];
            }
            w_k[k] = q[EFFECTS_PATH_WEIGHT];
            layers_k[k] = q[EFFECTS_PATH_LAYERS];
            bounces_k[k] = q[EFFECTS_PATH_BOUNCES];
        }
    }
    ia_realv o[3], d[3], n[3], t = IAV_LOAD(t_k), through = IAV_LOAD(w_k), layers = IAV_LOAD(layers_k);
    ia_realv bounces = IAV_LOAD(bounces_k);
    ia_maskv live = IAV_LOAD(valid_k) != 0, hit, going_on = (ia_maskv)0;
    packet_index rays = (packet_index)0, evals = (packet_index)0;
    if (a->mode == EFFECTS_MODE_PATHS)
        for (int c = 0; c < 3; c++) {
            o[c] = IAV_LOAD(o_k[c]);
            d[c] = IAV_LOAD(d_k[c]);
        }
    else
        packet_rays_at(a->params, a->flags & RENDER_ORTHO, IAV_LOAD(x2_k), IAV_LOAD(y2_k), a->width, a->height, o, d);
    ia_real eps = a->params[PARAM_EPS];
    if (a->mode == EFFECTS_MODE_CENTRE || shading) { /* the hits known: the frame's, or -aa's rounds' */
        hit = live & isfinite(t);
        for (int c = 0; c < 3; c++)
            n[c] = IAV_LOAD(n_k[c]);
    } else if (a->mode == EFFECTS_MODE_AA) {
        hit = effects_trace_samples(a->params, a->width, a->height, a->tiles, a->tile_groups_of, a->all_groups, pix,
                                    x2_k, y2_k, a->from ? from_k : 0, o, d, live, a->aa_eps, a->footprint,
                                    a->left ? a->turns : 0, &going_on, left_k, &t, n, !a->from, &rays, &evals);
        live &= ~going_on; /* their outputs come from the round that ends them */
    } else {
        hit = effects_trace(a->params, a->all_groups, o, d, IAV_R(0), IAV_R(IA_INF), live,
                            effects_offset(eps, o, IAV_R(0)), eps, a->footprint, 0, &t, 1, n, 0, 0, &rays, &evals);
    }
    shade_colorv acc[3] = {(shade_colorv)0, (shade_colorv)0, (shade_colorv)0};
    int nk[IA_VW];
    for (int q = 0; q < IA_VW; q++)
        nk[q] = 0;
    if (!walking)
        effects_paths(a->params, a->fx, a->all_groups, a->footprint, IAV_LOAD(row_k), a->height, o, d, live, hit, t, n,
                      through, layers, bounces, a->kids, a->kid_slots, path, nk, 0, acc, &rays, &evals);
    float out[3][IA_VW];
    bisect_index ray_count[IA_VW], eval_count[IA_VW];
    ia_real on_k[IA_VW], hit_k[4][IA_VW];
    for (int c = 0; c < 3; c++) {
        IAV_CAT(vstore, IA_VW)(acc[c], 0, out[c]);
        IAV_STORE(n[c], hit_k[1 + c]);
    }
    IAV_STORE(t, hit_k[0]);
    IAV_STORE(rays, ray_count);
    IAV_STORE(evals, eval_count);
    IAV_STORE(select(IAV_R(0), IAV_R(1), going_on), on_k);
    for (int q = 0; q < IA_VW && first + q < here; q++) {
        int p = path[q];
        if (a->stats) { /* with KERNEL_STATS (-stats); else 0 */
            a->stats[2 * p] = (a->from || shading ? a->stats[2 * p] : 0) + (uint)ray_count[q];
            a->stats[2 * p + 1] = (a->from || shading ? a->stats[2 * p + 1] : 0) + (uint)eval_count[q];
        }
        if (on_k[q] != 0) { /* on in the next round */
            int at = atomic_inc(a->counts + a->round);
            a->left[EFFECTS_LEFT_REALS * at] = (ia_real)p;
            a->left[EFFECTS_LEFT_REALS * at + 1] = left_k[0][q];
            a->left[EFFECTS_LEFT_REALS * at + 2] = left_k[1][q];
            continue;
        }
        if (walking) { /* its hit, for the shading after the rounds */
            for (int f = 0; f < 4; f++)
                a->hits[4 * p + f] = hit_k[f][q];
            continue;
        }
        /* a centre ray's pixel is its alone: its display colour where it listed no reflected ray (gamma 2, as
         * light.h encodes), else its linear light, which the reflected rays add to */
        __global float *to = a->mode == EFFECTS_MODE_CENTRE ? a->rgb + 3 * (size_t)pix[q] : a->color + 3 * (size_t)p;
        int final = a->mode == EFFECTS_MODE_CENTRE && nk[q] == 0;
        for (int c = 0; c < 3; c++)
            to[c] = final ? sqrt(fmin(fmax(out[c][q], 0.0f), 1.0f)) : out[c][q];
        if (a->kids)
            a->nkids[p] = nk[q];
    }
}

/* The launch's packets of paths (effects_packet), a work-item's from its own on, as many work-items apart: a round
 * past the first need not have a work-item per packet its paths may fill. */
__kernel void iacsg_effects(__constant ia_real *params, __constant ia_real *fx, int mode, int flags, int width,
                            int height, __global const int *pixels, __global const ia_real *paths, int npaths,
                            int aa, __global const float *depth, __global const float *normal,
                            ia_real aa_eps, ia_real footprint, __global const ulong *all_groups,
                            __global float *rgb, __global float *color, __global ia_real *kids,
                            __global int *nkids, int kid_slots, __global uint *stats, int aa_set,
                            __global const ia_real *tiles, __global const ulong *tile_groups_of,
                            __global const ia_real *from, __global ia_real *left, __global int *counts, int round,
                            int turns, __global ia_real *hits) {
    effects_launch launch = {params, fx,         mode,   flags, width, height, aa,   kid_slots, aa_set, round,
                             turns,  pixels,     paths,  tiles, from,  depth,  normal, aa_eps, footprint,
                             all_groups, tile_groups_of, rgb, color, kids, left, hits, nkids, counts, stats};
    int here = from ? counts[round - 1] : npaths, step = (int)get_global_size(0) * IA_VW;
    for (int first = (int)get_global_id(0) * IA_VW; first < here; first += step)
        effects_packet(&launch, first, here);
}

/* iacsg_render (render.cl) with the effects applied by the camera kernel itself (effects_centre), where no path
 * lists a reflected ray (src/render_effects.c: render_effects_in_camera): fx_block the effects' parameters
 * (kernels/effects.h), all_groups a union's groups all on, footprint the secondary rays' Newton window (as
 * iacsg_effects'), fx_counts (with KERNEL_STATS, else NULL) per packet the secondary rays and their evaluations.
 * Nothing of the frame goes to the host and back between the camera rays and their effects. */
__kernel void iacsg_render_effects(__constant ia_real *params, int flags, int width, int height, int block_row0,
                                   __global ia_real *tiles, __global float *rgb, __global float *depth,
                                   __global float *normal, __global uint *evals, __global uint *tile_evals,
                                   __global ulong *tile_groups_of, __global const uint *tape,
                                   __constant ia_real *fx_block, __global const ulong *all_groups, ia_real footprint,
                                   __global uint *fx_counts) {
    (void)tape; /* the effects are compiled code's */
    render_effects fx = {fx_block, all_groups, footprint, fx_counts};
    render_block(params, flags, width, height, block_row0, tiles, rgb, depth, normal, evals, tile_evals,
                 tile_groups_of, &fx);
}
