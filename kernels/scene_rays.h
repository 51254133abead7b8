/* kernels/scene_rays.h -- a packet of the segment path's secondary rays traced (scene_rays_trace): the camera kernel's
 * shadow rays (kernels/render_scene.cl, where the effects are applied in it) and the effects' trace kernel's
 * (kernels/scene_effects.cl: iacsg_scene_trace_rays) alike.
 *
 *   the rays clipped to the bounds (camera_clip, in lanes: packet_clip)
 *   --> where the program has the regions' union and they are disjoint (scene_union.h), the rays that start outside
 *       every region find the union's first root in SIMD lanes, marching off the surface they leave (march.h), and
 *       claim their region at its leaf, as the camera rays do; a transparent layer's ray, which starts inside the
 *       region it passes through (1 + the region, weave.h), finds where it leaves it in lanes too, and the next
 *       region on (scene_rays_union)
 *   --> the others, and a leaf no region claims, woven one at a time as a camera ray is (scene_trace.h).
 * With `whether` (the scene's items all opaque: shadow rays), a ray whose march proves g crossing 0 ends there
 * without its leaf, item EFFECTS_HIT_BLOCKED, t before the crossing.
 */
#ifndef KERNELS_SCENE_RAYS_H
#define KERNELS_SCENE_RAYS_H

/* g at the point several secondary rays start from (t = 0 along each: a hit's shadow rays, one a light), in the
 * lanes of `valid` (none at first): the first ray's trace evaluates it, the others take it. */
typedef struct {
    iav g;
    ia_maskv valid;
} scene_rays_start;

#if defined(SCENE_REGIONS_DISJOINT) && defined(SCENE_UNION_PREPASS)
#define SCENE_RAYS_MARCH 1
/* g's first root on the lanes of `walking` over [a, b]: with `march`, the march off the surface the ray leaves
 * (march.h: `leaving` is the start's distance from it; g at a, where the caller evaluated it, in ga: the march does
 * not evaluate it again), then for the lanes it hands over (all of them without `march`) bisection with Newton from
 * any node; *lo, *hi its leaf (with `whether`, a part where g crosses 0, wider than a leaf). */
static ia_maskv scene_rays_root(const ia_realv o[3], const ia_realv d[3], ia_realv a, ia_realv b, ia_maskv walking,
                                int march, ia_realv leaving, iav ga, ia_real eps, int whether, iav time, ia_realv *lo,
                                ia_realv *hi, packet_index *counts) {
    ia_maskv hit = (ia_maskv)0;
#ifdef PACKET_FDV
    march_crossing known = {walking, a, ga}; /* march.h takes it where g there is off 0 */
    if (march)
        hit = effects_march(o, d, &a, &b, &walking, leaving, 0, &known, eps, whether, time, lo, hi, counts);
#else
    (void)ga;
    if (march)
        hit = march_enclosure(o, d, &a, b, &walking, leaving, eps, whether, time, lo, hi, counts);
#endif
    ia_real w = march_farthest(b, walking);
    if (iav_any(walking)) /* a tree as long as the farthest ray; Newton from any node */
        hit |= packet_first_root(0, o, d, 0, w, (packet_int)0, (packet_index)0, a, b, walking, eps, IA_INF, 0, time,
                                 lo, hi, counts);
    return hit;
}

/* The lanes of `lanes` whose states (scene_union_states) let a region other than pass_k[k] - 1 be in. */
static ia_maskv scene_rays_other(scene_ray *r, const int states[SCENE_REGIONS_UNION][PACKET_LANES],
                                 const ia_real pass_k[PACKET_LANES], ia_maskv lanes) {
    ia_real on[IA_VW], other[IA_VW];
    IAV_STORE(select(IAV_R(0), IAV_R(1), lanes), on);
    for (int k = 0; k < IA_VW; k++) {
        int item, solid;
        other[k] = on[k] != 0 && scene_union_first(r, states, k, (int)pass_k[k] - 1, &item, &solid) != 0;
    }
    return IAV_LOAD(other) != 0;
}

/* Where the packet's rays (ok, dk over [tn, tf]; start NULL, or g at their shared origin: scene_rays_start) where
 * meets[k] is not 0 meet a region first, in lanes, and which
 * region the claim there may not be (pass_k[k], in: 1 + the region a transparent layer's ray passes through,
 * weave.h, else 0; out: the ray's `passing` from `from` on). evals: each lane's evaluations.
 * - A ray that starts outside every region (g > 0 at t_near, its enclosure at the point): g's first root
 *   (scene_rays_root); no region is in before it (g is continuous, and a region is in only where g <= 0,
 *   scene_union.h).
 * - A transparent layer's ray (not `whether`: some item is transparent) that starts inside the region it passes through
 *   (g < 0 at t_near, and no other region may be in there): g's first root, the leaf where it leaves the region, by
 *   bisection alone (Fig. 2's glass: the march took 26.9 evaluations of g's derivative code a ray to that leaf, closing
 *   in on x^500's wall from inside, each some 2.5 of g's enclosure). g < 0 all the way there: no region's boundary is
 *   crossed (g is 0 on each, the regions being disjoint), so the ray stays in its region. Where another region may be
 *   in over that leaf (a region touching it), the leaf is claimed, not by the region passed through. Else, where g > 0
 *   at the leaf's end (the ray has left every region: the weave would claim again from there), g's first root from
 *   there on (marching), claimed by any region.
 * Out: the leaf [from, leaf_hi] and the solids' states over it (scene_union_states) for scene_union_claim; from
 * +inf where no region is on the ray, from t_near or from a leaf with leaf_hi -inf for the lanes left to the weave
 * from there; with `whether` (the scene's items all opaque), crossed_k 1 where g certainly crosses 0 in [from,
 * leaf_hi]. */
static void scene_rays_union(scene_ray *r, __constant ia_real *params, ia_real eps, int whether,
                             scene_rays_start *start, const ia_real ok[3][PACKET_LANES],
                             const ia_real dk[3][PACKET_LANES],
                             const ia_real tn[PACKET_LANES], const ia_real tf[PACKET_LANES],
                             const ia_real meets[PACKET_LANES], ia_real pass_k[PACKET_LANES],
                             ia_real from[PACKET_LANES], ia_real leaf_hi[PACKET_LANES], ia_real crossed_k[PACKET_LANES],
                             int states[SCENE_REGIONS_UNION][PACKET_LANES], kernel_u32 evals[PACKET_LANES]) {
    ia_realv o[3], d[3], t_near = IAV_LOAD(tn), t_far = IAV_LOAD(tf), pass = IAV_LOAD(pass_k);
    for (int c = 0; c < 3; c++) {
        o[c] = IAV_LOAD(ok[c]);
        d[c] = IAV_LOAD(dk[c]);
    }
    iav time = iav_const(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    packet_index counts = (packet_index)0;
    ia_maskv on = IAV_LOAD(meets) != 0, passing = on & (pass > 0), outside = (ia_maskv)0, inside = (ia_maskv)0;
    if (whether)
        on &= ~passing;
    iav g = iav_point(0); /* at t_near, where some lane is on */
    if (start && iav_any(on) && !iav_any(on & ~(start->valid & (t_near == 0)))) {
        g = start->g; /* the rays' shared start, evaluated by an earlier one */
    } else if (iav_any(on)) {
        g = scene_union_g_at(o, d, t_near, time);
        PACKET_COUNT(counts, on);
        if (start) { /* at the start itself where t_near is 0 (packet_extent there is o, whatever d is) */
            start->g = g;
            start->valid = on & (t_near == 0);
        }
    }
    outside = on & ~passing & (g.lo > 0);
    inside = passing & (g.hi < 0);
    if (iav_any(inside)) { /* in no region but its own at t_near */
        scene_union_states(o, d, t_near, t_near, inside, time, states, &counts);
        inside &= ~scene_rays_other(r, states, pass_k, inside);
    }
    ia_realv leaving = effects_offset(eps, o, IAV_R(0)); /* the start's distance off its hit (offset_of) */
    ia_realv lo = IAV_R(0), hi = IAV_R(0), out_from = t_near, out_hi = IAV_R(-IA_INF);
    ia_maskv hit = (ia_maskv)0, crossed = (ia_maskv)0;
    if (iav_any(outside | inside)) {
        hit = scene_rays_root(o, d, t_near, t_far, outside, 1, leaving, g, eps, whether, time, &lo, &hi, &counts);
        if (iav_any(inside)) /* no march (see above) */
            hit |= scene_rays_root(o, d, t_near, t_far, inside, 0, leaving, g, eps, 0, time, &lo, &hi, &counts);
        crossed = hit & (hi - lo > eps); /* `whether`: a part where g crosses 0, not a leaf */
        hit &= ~crossed;
        out_from = select(out_from, select(IAV_R(IA_INF), lo, hit | crossed), outside | inside);
        out_hi = select(out_hi, hi, hit);
    }
    ia_maskv exit = inside & hit, beyond = (ia_maskv)0;
    if (iav_any(exit)) { /* the leaf where the layer's ray leaves its region, claimed by a region touching it */
        scene_union_states(o, d, lo, hi, exit, time, states, &counts);
        ia_maskv left = exit & ~scene_rays_other(r, states, pass_k, exit);
        out_hi = select(out_hi, IAV_R(-IA_INF), left); /* else woven from the leaf on, passing through */
        if (iav_any(left)) {
            PACKET_COUNT(counts, left);
            g = scene_union_g_at(o, d, hi, time);
            beyond = left & (g.lo > 0);
        }
    }
    if (iav_any(beyond)) { /* out of every region: the next root of g (at hi: g), claimed by any region */
        ia_realv lo2 = IAV_R(0), hi2 = IAV_R(0);
        ia_maskv hit2 = scene_rays_root(o, d, hi, t_far, beyond, 1, leaving, g, eps, 0, time, &lo2, &hi2, &counts);
        out_from = select(out_from, select(IAV_R(IA_INF), lo2, hit2), beyond);
        out_hi = select(out_hi, hi2, beyond & hit2);
        pass = select(pass, IAV_R(0), beyond);
        if (iav_any(beyond & hit2))
            scene_union_states(o, d, lo2, hi2, beyond & hit2, time, states, &counts);
    }
    if (iav_any(hit & outside))
        scene_union_states(o, d, fmax(t_near, lo), hi, hit & outside, time, states, &counts);
    IAV_STORE(select(IAV_R(0), IAV_R(1), crossed), crossed_k);
    IAV_STORE(out_from, from);
    IAV_STORE(out_hi, leaf_hi);
    IAV_STORE(pass, pass_k);
    bisect_index count[IA_VW];
    IAV_STORE(counts, count);
    for (int k = 0; k < IA_VW; k++)
        evals[k] = (kernel_u32)count[k];
}
#endif


/* Traces the packet's rays ok, dk over [tn, tf] (clipped to the bounds in place), lane k where meets[k] is not 0
 * (cleared where the ray misses the bounds), pass_in[k] the region it passes through (1 + the region, weave.h, or
 * 0). Out per lane: found[k] 1 with hits[k] (t: the claimed partition's start; item, or EFFECTS_HIT_BLOCKED with
 * `whether`; solid), 0 where nothing is hit in [tn, tf] within the bounds, SCENE_TRACE_OVERFLOW where the ray meets
 * more boxes than r has room for; evals[k] the ray's interval evaluations. r's solids are all OUT after. */
static void scene_rays_trace(const scene_view *view, scene_ray *r, __constant ia_real *params, int whether,
                             scene_rays_start *start, ia_real ok[3][PACKET_LANES], ia_real dk[3][PACKET_LANES],
                             ia_real tn[PACKET_LANES],
                             ia_real tf[PACKET_LANES], ia_real meets[PACKET_LANES],
                             const ia_real pass_in[PACKET_LANES], int found[PACKET_LANES],
                             weave_hit hits[PACKET_LANES], kernel_u32 evals[PACKET_LANES]) {
    ia_real ik[3][PACKET_LANES], pass[PACKET_LANES], from[PACKET_LANES], leaf_hi[PACKET_LANES];
    ia_real crossed[PACKET_LANES];
    kernel_u32 from_evals[PACKET_LANES];
    for (int k = 0; k < PACKET_LANES; k++) {
        pass[k] = pass_in[k];
        from[k] = leaf_hi[k] = -IA_INF;
        crossed[k] = 0;
        from_evals[k] = 0;
    }
    { /* the part in the bounds (camera_clip, in lanes: packet_clip) and the inverse directions */
        ia_realv o[3], d[3], t_near, t_far;
        for (int c = 0; c < 3; c++) {
            o[c] = IAV_LOAD(ok[c]);
            d[c] = IAV_LOAD(dk[c]);
            IAV_STORE((ia_real)1 / d[c], ik[c]);
        }
        ia_maskv in = packet_clip(params, o, d, &t_near, &t_far) & (IAV_LOAD(meets) != 0);
        t_near = fmax(t_near, IAV_LOAD(tn));
        t_far = fmin(t_far, IAV_LOAD(tf));
        IAV_STORE(t_near, tn);
        IAV_STORE(t_far, tf);
        IAV_STORE(select(IAV_R(0), IAV_R(1), in & (t_near <= t_far)), meets);
    }
#ifdef SCENE_RAYS_MARCH
    int states[SCENE_REGIONS_UNION][PACKET_LANES] = {{0}};
    scene_rays_union(r, params, view->eps, whether, start, ok, dk, tn, tf, meets, pass, from, leaf_hi, crossed,
                     states, from_evals);
#else
    (void)whether, (void)start;
#endif
    for (int k = 0; k < PACKET_LANES; k++) {
        ia_real o[3] = {ok[0][k], ok[1][k], ok[2][k]}, d[3] = {dk[0][k], dk[1][k], dk[2][k]};
        bvh_ray br = bvh_ray_lane(dk, ik, k);
        weave_hit hit = {0, -1, -1, -1};
        r->evals = 0;
        r->passing = (int)pass[k]; /* from `from` on */
        int got = 0, claimed = 0;
        if (crossed[k] != 0) { /* certainly blocked (`whether`) */
            got = 1;
            hit.t = from[k];
            hit.item = EFFECTS_HIT_BLOCKED;
        } else if (meets[k] != 0) {
#ifdef SCENE_RAYS_MARCH
            if (leaf_hi[k] >= from[k])
                claimed = scene_union_claim(r, states, k, r->passing - 1, fmax(tn[k], from[k]), &hit);
#endif
            if (claimed < 0) /* more solids in at the leaf than r lists: woven from t_near */
                r->passing = (int)pass_in[k];
            got = claimed > 0 ? scene_trace_surfaces(view, r, o, d, tn[k], tf[k], 1, &hit)
                              : scene_trace_ray_from(view, r, o, d, &br, tn[k],
                                                     claimed < 0 ? tn[k] : fmax(tn[k], from[k]), tf[k], &hit);
        }
        found[k] = got;
        hits[k] = hit;
        evals[k] = r->evals + from_evals[k];
    }
}

#endif
