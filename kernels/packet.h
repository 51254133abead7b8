/* kernels/packet.h -- the first roots of IA_VW rays at once, by interval bisection (Knoll et al., Hijazi et al.)
 * without a stack (traverse.h) and interval Newton below a few pixel footprints (where Newton stalls, a mean
 * value form instead), one SIMD lane per ray (OpenCL C only; ia/vec.h's intervals and the emitted iacsg_Fv,
 * iacsg_Fdv).
 *
 * Why lanes: PoCL runs a work-group's work-items in a loop that it vectorises only when every work-item takes
 * the same path; the bisection's trip count differs per ray, so a kernel with a ray per work-item ran one ray at
 * a time with no vector instruction at all. Here a work-item carries a packet of PACKET_W x PACKET_H
 * neighbouring rays, which mostly walk the same nodes; the loop runs while any lane is searching, and a lane
 * that is done idles.
 *
 * The walk is over the tree of one root interval [t0, t0 + w] shared by all the rays of a frame (the tile pass,
 * tile.h, walks the same tree), restricted to each ray's part [t_near, t_far] inside the bounds: each node is
 * clipped to it. A ray starts at its tile's first coarse leaf, before which the tile pass proved the tile
 * root-free: a ray whose surface lies after that leaf continues at the leaf's level instead of descending again
 * from the top.
 *
 * Guarantee, lane by lane: every node before the returned leaf was proven root-free on [t_near, t_far] (0 not in
 * F over its box, and the box contains the float ray's points), and the clipped nodes tile [t_near, t_far]
 * without gaps (node ends are traverse.h's formula over the same operations, bit-identical wherever computed);
 * a node that Newton narrows keeps all its roots in the narrowed part, and one whose mean value form misses 0 has
 * none (packet_mean_value). So if the float ray meets the surface
 * there, a leaf is returned, and its start is never after the first root.
 */
#ifndef KERNELS_PACKET_H
#define KERNELS_PACKET_H
#include "packet_camera.h"
#include "traverse.h"
#if IA_DEVICE && defined(IA_VW) && !defined(IACSG_SCALAR_CODE) /* (the segment path: SCENE_REGIONS_UNION) */

/* log2 of powers of two p > 0, lane by lane: the exponent of p converted to a real (exactly). There is no vector
 * popcount or count of trailing zeros before AVX-512 VPOPCNTDQ; PoCL ran them lane by lane. */
IA_FN packet_int packet_log2_of_power(packet_index p) {
    return (packet_as_int(packet_to_real(p)) >> PACKET_MANT_BITS) - PACKET_EXP_BIAS;
}

/* Interval evaluations are counted per lane only in a kernel built with -D KERNEL_STATS: the normal kernel
 * pays nothing. A true lane of a mask is -1. */
#ifdef KERNEL_STATS
#define PACKET_COUNT(counts, lanes) ((counts) -= packet_to_index(lanes))
#else
#define PACKET_COUNT(counts, lanes) ((void)(counts))
#endif

/* node_scale lane by lane: 2^-level from its exponent bits. */
IA_FN ia_realv packet_node_scale(packet_int level) {
    return packet_as_real(packet_to_index(PACKET_EXP_BIAS - level) << PACKET_MANT_BITS);
}

/* node_bound lane by lane: t0 + w * (i * 2^-level). */
IA_FN ia_realv packet_node_bound(ia_real t0, ia_real w, packet_int level, packet_index i) {
    return t0 + w * (packet_to_real(i) * packet_node_scale(level));
}

/* An interpreted expression's tape (kernels/tape_eval.h, a program with IACSG_TAPE) travels as the first argument
 * of the functions that evaluate F, PACKET_TAPE_PARAM; for a compiled one these expand to nothing, so the
 * functions keep the signatures that kernels/effects.cl calls (a tape program leaves effects.cl out). */
#ifdef IACSG_TAPE
#define PACKET_TAPE_PARAM tape_ptr tape,
#define PACKET_TAPE_ARG tape,
#else
#define PACKET_TAPE_PARAM
#define PACKET_TAPE_ARG
#endif

/* F over the groups of a union set in `groups` (bit g for group g), for the lanes of `live` (the others get
 * an interval, of no use): the min of their enclosures, exact (min rounds nothing). The tile pass leaves out of
 * a tile's segment only groups certainly positive (> 0) on every box its rays evaluate there (tile.h), so there
 * the union is < 0, = 0 or > 0 exactly where the min of the groups kept is: the roots, and the walk's
 * decisions, are the same. A group is the compiled iacsg_Fv_group, or the tape's (kernels/tape_eval.h), which
 * also leaves out the parts whose boxes no live lane's box meets, for the same reason. An expression emitted
 * without groups (no IACSG_GROUPS) is iacsg_Fv. */
IAV_INLINE iav packet_F_live(PACKET_TAPE_PARAM ulong groups, ia_maskv live, iav x, iav y, iav z, iav t) {
#ifdef IACSG_TAPE
    ia_real hull[6];
    tape_hull(live, x, y, z, hull);
    iav r = iav_point(IA_INF);
    for (; groups; groups &= groups - 1) /* the set bits, lowest first: g = the trailing zeros */
        r = iav_min(r, tape_group(tape, (int)popcount((groups & (0 - groups)) - 1), hull, live, x, y, z, t));
    return r;
#elif defined(IACSG_GROUPS)
    (void)live;
    iav r = iav_point(IA_INF); /* the identity of min */
    for (int g = 0; g < IACSG_GROUPS; g++)
        if (groups >> g & 1)
            r = iav_min(r, iacsg_Fv_group(g, x, y, z, t));
    return r;
#else
    (void)groups, (void)live;
    return iacsg_Fv(x, y, z, t);
#endif
}

/* packet_F_live for every lane. */
IAV_INLINE iav packet_F(PACKET_TAPE_PARAM ulong groups, iav x, iav y, iav z, iav t) {
    return packet_F_live(PACKET_TAPE_ARG groups, (ia_maskv)-1, x, y, z, t);
}

/* What the shading's point evaluations take (packet_F_points): the groups set in `groups`, or for a tape the
 * tile's lists of segments first..last (records: the tile's first list) unless one is full. */
typedef struct {
    ulong groups;
#ifdef IACSG_TAPE
    const __global ushort *records;
    int first, last;
#endif
} packet_parts;

/* packet_F at points (boxes of one point a lane), for the shading's differences: an interpreted expression
 * skips no part by its box there (kernels/tape_eval.h), the compiled one is packet_F. */
IAV_INLINE iav packet_F_points(PACKET_TAPE_PARAM packet_parts parts, iav x, iav y, iav z, iav t) {
#ifdef IACSG_TAPE
    iav r;
    if (tape_lists(tape, parts.records, parts.first, parts.last, 0, (ia_maskv)-1, x, y, z, t, &r))
        return r;
    r = iav_point(IA_INF);
    for (int g = 0; g < IACSG_GROUPS; g++)
        if (parts.groups >> g & 1)
            r = iav_min(r, tape_group(tape, g, 0, (ia_maskv)-1, x, y, z, t)); /* hull NULL: skip none */
    return r;
#else
    return packet_F(parts.groups, x, y, z, t);
#endif
}

/* The groups that can matter on node (level, i) of the frame's tree: the union of the masks of the segments
 * (the nodes at SEGMENT_LEVEL) it overlaps, exact integer arithmetic on the tree's indices. */
IA_FN ulong packet_node_groups(const __global ulong *segment_groups, int level, bisect_index i) {
    bisect_index first = level >= SEGMENT_LEVEL ? i >> (level - SEGMENT_LEVEL) : i << (SEGMENT_LEVEL - level);
    bisect_index last = level >= SEGMENT_LEVEL ? first : ((i + 1) << (SEGMENT_LEVEL - level)) - 1;
    ulong groups = 0;
    for (bisect_index k = first; k <= last; k++)
        groups |= segment_groups[k];
    return groups;
}

/* The lanes' nodes as arrays: on[k] != 0 where lane k is live, its node (lv[k], index[k]). */
IA_FN void packet_lane_nodes(ia_maskv live, packet_int level, packet_index i, ia_real on[IA_VW],
                             bisect_index index[IA_VW], int lv[IA_VW]) {
    IAV_STORE(select(IAV_R(0), IAV_R(1), live), on);
    IAV_STORE(i, index);
    IAV_CAT(vstore, IA_VW)(IAV_CAT(convert_int, IA_VW)(level), 0, lv); /* packet_int is long in double */
}

/* The groups that can matter on the nodes of the lanes of `live`. */
IA_FN ulong packet_groups(const __global ulong *segment_groups, ia_maskv live, packet_int level, packet_index i) {
#ifdef IACSG_GROUPS
    ia_real on[IA_VW];
    bisect_index index[IA_VW];
    int lv[IA_VW];
    packet_lane_nodes(live, level, i, on, index, lv);
    ulong groups = 0;
    for (int k = 0; k < IA_VW; k++)
        if (on[k] != 0)
            groups |= packet_node_groups(segment_groups, lv[k], index[k]);
    return groups;
#else
    (void)segment_groups, (void)live, (void)level, (void)i;
    return ~(ulong)0;
#endif
}

/* The segments first..last of the frame's tree that the nodes (level, i) of the lanes of `live` overlap
 * (first > last when no lane is live). */
IA_FN void packet_segments(ia_maskv live, packet_int level, packet_index i, int *first, int *last) {
    ia_real on[IA_VW];
    bisect_index index[IA_VW];
    int lv[IA_VW];
    packet_lane_nodes(live, level, i, on, index, lv);
    *first = SEGMENTS;
    *last = -1;
    for (int k = 0; k < IA_VW; k++)
        if (on[k] != 0) {
            int shift = lv[k] - SEGMENT_LEVEL;
            *first = min(*first, (int)(shift >= 0 ? index[k] >> shift : index[k] << -shift));
            *last = max(*last, (int)(shift >= 0 ? index[k] >> shift : ((index[k] + 1) << -shift) - 1));
        }
}

/* F on the nodes (level, i) of the lanes of `live`, for the walk: packet_F_live over the groups that can matter
 * there (packet_groups); for a tape, over the tile's lists of parts of the segments the nodes overlap (the tile
 * pass's, kernels/tape_eval.h: tape_tile_parts, after the segments' group masks in the tile's words) unless one
 * is full. Inlined at both its calls (the walk's and Newton's leaf test): called, its 16-lane operands and result went
 * through memory. */
IAV_INLINE iav packet_F_nodes(PACKET_TAPE_PARAM const __global ulong *segment_groups, ia_maskv live, packet_int level,
                              packet_index i, iav x, iav y, iav z, iav t) {
#ifdef IACSG_TAPE
    int first, last;
    packet_segments(live, level, i, &first, &last);
    iav r;
    if (tape_lists(tape, (const __global ushort *)(segment_groups + SEGMENTS), first, last, 1, live, x, y, z, t, &r))
        return r;
#endif
    return packet_F_live(PACKET_TAPE_ARG packet_groups(segment_groups, live, level, i), live, x, y, z, t);
}

/* node_at for the t of each lane of `lanes` at its level lv (0 in the other lanes). */
IA_FN packet_index packet_node_at_levels(ia_real t0, ia_real w, packet_int lv, ia_maskv lanes, ia_realv t) {
    packet_index last = (((packet_index)1) << packet_to_index(lv)) - 1;
    ia_realv u = (t - t0) / w / packet_node_scale(lv);
    packet_index j = packet_to_index(fmin(fmax(u, IAV_R(0)), packet_to_real(last))); /* u > 0 ? u : 0, truncated */
    j = select((packet_index)0, j, lanes);
    while (1) {
        ia_maskv back = lanes & (j > 0) & (packet_node_bound(t0, w, lv, j) > t);
        if (!iav_any(back))
            break;
        j = select(j, j - 1, back);
    }
    while (1) {
        ia_maskv forward = lanes & (j < last) & (packet_node_bound(t0, w, lv, j + 1) <= t);
        if (!iav_any(forward))
            return j;
        j = select(j, j + 1, forward);
    }
}

/* node_at for each lane's t, at one level for all. */
IA_FN packet_index packet_node_at(ia_real t0, ia_real w, int level, ia_realv t) {
    return packet_node_at_levels(t0, w, (packet_int)level, (ia_maskv)-1, t);
}

/* ray_extent lane by lane. */
IA_FN iav packet_extent(ia_realv o, ia_realv d, iav t) {
    ia_maskv forward = d >= 0;
    ia_realv first = select(t.hi, t.lo, forward), last = select(t.lo, t.hi, forward);
    return iav_make(iav_lo(fma(d, first, o)), iav_hi(fma(d, last, o)));
}

/* One step of the walk in every lane of `searching`: the lanes of `down` (a subset) descend to the left child,
 * the others move to the next node not inside theirs (node_next: i + 1, then up past its trailing zeros, the
 * levels where it is a left child's position), and leave `searching` when that climbs to the root. */
IA_FN void packet_advance(ia_maskv *searching, ia_maskv down, packet_int *level, packet_index *i) {
    ia_maskv next = *searching & ~down;
    packet_index i1 = *i + 1;
    packet_int up = min(packet_log2_of_power(i1 & (0 - i1)), *level); /* trailing zeros of i1 */
    *i = select(select(*i, *i << 1, down), i1 >> packet_to_index(up), next);
    *level = select(select(*level, *level + 1, down), *level - up, next);
    *searching &= ~(next & (*level == 0));
}

/* packet_advance for the lanes of `moving` only (a subset of *searching); the other lanes keep their node. */
IA_FN void packet_advance_some(ia_maskv *searching, ia_maskv moving, ia_maskv down, packet_int *level,
                               packet_index *i) {
    packet_int lv = *level;
    packet_index ix = *i;
    ia_maskv still = moving;
    packet_advance(&still, down & moving, &lv, &ix);
    *level = select(*level, lv, moving);
    *i = select(*i, ix, moving);
    *searching = (*searching & ~moving) | still;
}

/* The lanes of `moving` (Newton's, stalled on their part [t, t + width] of their node) go on by the walk from the
 * node holding t at the deepest level whose nodes are no narrower than the part, one level below theirs at least:
 * the part of their node before t is root-free (Newton's proof), so the halvings down to there are skipped. */
IA_FN void packet_resume_at(ia_real t0, ia_real w, ia_maskv moving, ia_realv t, ia_realv width, packet_int *level,
                            packet_index *i) {
    ia_realv node = w * packet_node_scale(*level);
    /* log2 of node / width, at least 1, kept in range where width is 0 or NaN (lanes not moving) */
    ia_realv halvings = fmin(floor(log2(fmax(node / width, IAV_R(2)))), (ia_real)BISECT_MAX_LEVEL);
    packet_int lv = select(*level, min(*level + packet_to_int(halvings), (packet_int)BISECT_MAX_LEVEL), moving);
    *i = select(*i, packet_node_at_levels(t0, w, lv, moving, t), moving);
    *level = lv;
}

/* Interval Newton along the ray, where the compiler emitted iacsg_Fdv (implicits/emit.c: newton_pays): from a
 * node [a, b] that holds 0, no wider than NEWTON_PIXELS pixel footprints and at least NEWTON_MIN_LEAVES leaves
 * wide, instead of bisecting it down to eps, N = m - F(m) / F'([a, b]) with m the midpoint, and
 * [a, b] := [a, b] n N, where F' = iacsg_Fdv's enclosure of the derivative along the ray over the box of the
 * segment (Clarke's generalized derivative at the kinks of abs, min, max).
 *
 * When a step is valid: only where F' is BOUNDED (both ends finite). Proof sketch. iacsg_Fdv reports
 * [-inf, +inf] wherever an operation of the expression may be undefined on the box (implicits/emit.c: a pole of
 * 1/x, tan or a negative power, the domain edge of sqrt, log or pow), so a bounded F' means every operation is
 * defined on the whole segment; all of them are continuous where defined, so F is continuous there, with its
 * derivative along the ray (Clarke's generalized one at the kinks) in the bounded F' (the inclusion property of
 * the derivative code): F is Lipschitz on [a, b], and Lebourg's mean value theorem gives F(m) - F(r) in
 * F' (m - r) for every point r of [a, b]. At a root r, F(r) = 0, so r is in m - F(m) / F' when 0 is not in
 * F': N keeps every root of [a, b], the first one is neither lost nor passed. Over a node that holds a pole the
 * derivative is unbounded in any case (F is unbounded near it, so F' cannot be bounded by the inclusion
 * property); the old test, "F' holds 0", let through F' = [-inf, -c] over a pole, and the step kept the wrong
 * side of it (tests/t_newton_pole_fp.c).
 *
 * When N misses [a, b] or F([a, b]) misses 0 the node is root-free; when F' holds 0 or is unbounded, or a step does not
 * halve the width, the ray goes back to bisecting (from the node that holds its part's start, as wide as the part:
 * the stretch before is root-free; and every later node by the mean value form: a second try from the next node
 * rarely paid), but where the mean value form's F' over a node keeps one sign, the form's
 * F and F' make a Newton step from its centre without a further evaluation, and Newton's turns go on from there: a ray
 * that grazes a surface bisects down to where its stretch of the ray turns monotone, not to eps (evaluations a ray,
 * 1024x1024 at eps 1e-5: reference view 4.85 -> 4.46, heart 5.65 -> 3.31, decocube 8.56 -> 5.08, a gyroid in a ball
 * 6.23 -> 3.56). A turn whose lanes all test a leaf (a part no wider than eps, where F' is not needed) takes F alone.
 * Near a simple root the width squares at each step: on the reference view at eps 1e-5, 12.27 evaluations per ray
 * became 5.54 (~3 steps per hit) and the frame 49 -> 39 ms. With IA_FAST the same steps run unrounded (not rigorous, as
 * everything in that mode), so that the fast mode differs from the rigorous one only in the rounding. Measured choices:
 * 8, 32, 128 footprints gave 43, 39, 40 ms; below 64 leaves bisection is as cheap. A tape's (1024 spheres of radius
 * 0.08, ~55 footprints across, reference camera): 32 footprints, 32.13 -> 28.28 evaluations per ray and no faster (a
 * node that wide often holds the ray's closest approach to a centre, where the slope holds 0: the ray bisects from
 * there, with the costlier mean value form); 8, 20.38 and ~10 % fewer kernel samples; 4 and 16 no better. */
#if defined(IACSG_FDV) || defined(IACSG_TAPE) /* a tape's: tape_lists_dt, where its header allows (TAPE_W_NEWTON) */
#define PACKET_NEWTON 1
#endif
#if (defined(IACSG_FDV) || defined(IACSG_FDV_MARCH)) && !defined(IACSG_TAPE) /* iacsg_Fdv, for march.h at least */
#define PACKET_FDV 1
#endif
#ifdef IACSG_TAPE /* its unions' parts are small: see below */
#define NEWTON_PIXELS 8
#else
#define NEWTON_PIXELS 32
#endif
#define NEWTON_MIN_LEAVES 64

#ifdef PACKET_FDV
/* F over the boxes (x, y, z, t) and in *slope the enclosure of its derivative along the rays, the boxes moving at
 * the rates `rates`: the compiled iacsg_Fdv, or for a union in groups (implicits/emit.c) the min over the groups set
 * in `groups` of iacsg_Fdv_group, with the min's derivative by iav_dmin (Clarke's generalized one at its kinks), as
 * tape_lists_dt's over its parts. Those groups are one function, continuous with its derivative in *slope, with the
 * union's roots wherever the groups left out are > 0: the mean value theorem's, so a caller takes F at its points
 * over the same groups. */
IAV_INLINE iav packet_Fdv(ulong groups, iav x, iav y, iav z, iav t, const iav rates[3], iav *slope) {
#ifdef IACSG_GROUPS
    iav r = iav_point(IA_INF);
    *slope = iav_point(0); /* the identity's: read by iav_dmin only where a group may be +inf */
    for (int g = 0; g < IACSG_GROUPS; g++)
        if (groups >> g & 1) {
            iav s, v = iacsg_Fdv_group(g, x, y, z, t, rates[0], rates[1], rates[2], &s);
            *slope = iav_dmin(r, v, *slope, s);
            r = iav_min(r, v);
        }
    return r;
#else
    (void)groups;
    return iacsg_Fdv(x, y, z, t, rates[0], rates[1], rates[2], slope);
#endif
}
#endif

#ifdef PACKET_NEWTON
/* F over the boxes of the segments [t.lo, t.hi] of the rays of the lanes of `live`, on their nodes (level, i), and
 * in *slope the enclosure of its derivative along the rays there, for Newton and the mean value form: the
 * compiled iacsg_Fdv; for a tape tape_lists_dt over the tile's lists, which also gives *at_m, F at the segments'
 * midpoints over the same parts (the proofs need one function: kernels/tape_eval.h); where a list is full, the
 * walk's F and the slope [-inf, +inf] (those lanes bisect). The compiled code's *at_m is the caller's, over the
 * groups its function was taken over, *groups (packet_groups of `live`: packet_Fdv's; a tape leaves it alone). */
IA_FN iav packet_Fd(PACKET_TAPE_PARAM const __global ulong *segment_groups, const ia_realv o[3], const ia_realv d[3],
                    iav t, ia_maskv live, packet_int level, packet_index i, iav time, iav *slope, iav *at_m,
                    ulong *groups) {
    iav x = packet_extent(o[0], d[0], t), y = packet_extent(o[1], d[1], t), z = packet_extent(o[2], d[2], t);
    iav rates[3] = {iav_make(d[0], d[0]), iav_make(d[1], d[1]), iav_make(d[2], d[2])};
#ifdef IACSG_TAPE
    ia_realv m = t.lo * (ia_real)0.5 + t.hi * (ia_real)0.5; /* as the callers' midpoint */
    iav tm = iav_make(m, m), f;
    (void)groups;
    int first, last;
    packet_segments(live, level, i, &first, &last);
    if (tape_lists_dt(tape, (const __global ushort *)(segment_groups + SEGMENTS), first, last, live, x, y, z, time,
                      rates, packet_extent(o[0], d[0], tm), packet_extent(o[1], d[1], tm),
                      packet_extent(o[2], d[2], tm), &f, slope, at_m))
        return f;
    *slope = iav_entire_where(iav_point(0), (ia_maskv)-1);
    *at_m = f = packet_F_nodes(tape, segment_groups, live, level, i, x, y, z, time);
    return f;
#else
    (void)at_m;
    *groups = packet_groups(segment_groups, live, level, i);
    return packet_Fdv(*groups, x, y, z, time, rates, slope);
#endif
}

/* A mean value form's parts (packet_mean_value), for a Newton step from its centre. */
typedef struct {
    ia_maskv use; /* the lanes the form narrowed */
    iav slope;    /* F' over the segment */
    ia_realv c;   /* the form's centre */
    iav fc;       /* F at c */
} packet_form;

/* F over the boxes of the segments [t.lo, t.hi] of the rays, and for the lanes of `tangent` narrowed by the mean
 * value form F(c) + F'(t - c) (c a point of the segment, F' = iacsg_Fdv's derivative along the ray over the box),
 * where F' is bounded: the same theorem as a Newton step's (above), so the true range of F over the segment lies in
 * both, and in their intersection. The centre is Baumann's, the point that makes the form's lower bound the
 * highest (where F's enclosure lies mostly above 0, as along a ray that passes a surface by) or its upper bound
 * the lowest (mostly below): c = (s.hi a - s.lo b) / (s.hi - s.lo) for the lower one, F' = [s.lo, s.hi]; the
 * midpoint where F' is a point, and for a tape (its F at the midpoint comes with F'; reference view at eps 1e-5:
 * the form's steps 0.42 -> 0.39 a ray). For the rays Newton gave up on: they pass near the surface almost
 * tangentially, where F' is small but F's natural enclosure over the box is as wide as |grad F| times the segment
 * (it takes each coordinate's extent on its own); bisection then went down to eps along the whole stretch where
 * the ray grazes the surface (up to ~2200 evaluations a ray at eps 1e-5). An empty intersection is a proof of no
 * root. Counts the point evaluation; the caller counts the box's. The form's parts go to *out. */
IA_FN iav packet_mean_value(PACKET_TAPE_PARAM const __global ulong *segment_groups, const ia_realv o[3],
                            const ia_realv d[3], iav t, ia_maskv live, packet_int level, packet_index i,
                            ia_maskv tangent, iav time, packet_form *out, packet_index *evals) {
    iav slope, fm;
    ulong groups;
    iav f = packet_Fd(PACKET_TAPE_ARG segment_groups, o, d, t, live, level, i, time, &slope, &fm, &groups);
    ia_maskv use = tangent & isfinite(slope.lo) & isfinite(slope.hi); /* NaN is not finite: garbage lanes too */
    ia_realv m = t.lo * (ia_real)0.5 + t.hi * (ia_real)0.5;
#ifndef IACSG_TAPE
    ia_realv span = slope.hi - slope.lo;
    ia_realv c_lo = (slope.hi * t.lo - slope.lo * t.hi) / span, c_hi = (slope.hi * t.hi - slope.lo * t.lo) / span;
    ia_realv c = select(c_hi, c_lo, f.lo + f.hi > 0);
    m = select(m, fmin(fmax(c, t.lo), t.hi), use & (span > 0)); /* in the segment, whatever the rounding */
#endif
    iav at_m = iav_make(m, m);
#ifndef IACSG_TAPE /* over packet_Fd's groups: one function */
    fm = packet_F(groups, packet_extent(o[0], d[0], at_m), packet_extent(o[1], d[1], at_m),
                  packet_extent(o[2], d[2], at_m), time);
#endif
    PACKET_COUNT(*evals, use);
    /* lanes not using it multiply by 0: an infinite slope there would send every lane down iav_mul's slow path */
    iav form = iav_add(fm, iav_mul(iav__pick(iav_point(0), slope, use), iav_sub(t, at_m)));
    out->use = use;
    out->slope = slope;
    out->c = m;
    out->fc = fm;
    return iav_make(select(f.lo, fmax(f.lo, form.lo), use), select(f.hi, fmin(f.hi, form.hi), use));
}

/* Newton's step from c in the lanes of `lanes`, whose slope over [a, b] excludes 0: [a, b] n (c - F(c) / F') into
 * [*lo, *hi]; returns the lanes where that is not empty (the others hold no root). Never narrower than half a leaf:
 * the step after this one is the leaf's test, F over it, and unrounded (IA_FAST) F over a box far below the widths
 * at which its rounding errors show missed the root in a fifth of the reference view's rays. The part grows inside
 * [a, b], so it keeps every root; the leaf's start is still at or before the first one. */
IA_FN ia_maskv packet_newton_step(ia_realv c, iav fc, iav slope, ia_maskv lanes, ia_realv a, ia_realv b, ia_real eps,
                                  ia_realv *lo, ia_realv *hi) {
    /* lanes not stepping divide by 1: a pole there would send every lane down iav_div's slow path */
    iav n = iav_sub(iav_make(c, c), iav_div(fc, iav__pick(iav_point(1), slope, lanes)));
    *lo = fmax(a, n.lo);
    *hi = fmin(b, n.hi);
    ia_maskv kept = lanes & (*lo <= *hi);
    *hi = fmin(b, fmax(*hi, *lo + (ia_real)0.5 * eps));
    return kept;
}
#endif

/* The first root of each lane of *searching in [t_near, t_far] of its ray o + t*d, from its node (*level, *i) on
 * (no node before it may hold a root): the first clipped node whose enclosure holds 0 and that is no wider than
 * eps, or at the deepest level, or its part Newton narrowed to eps. A pixel's footprint at t is
 * footprint0 + t * footprint_t. Returns the lanes that hit, with their leaves in [*hit_lo, *hit_hi]. With `turns`
 * above 0 the walk stops after that many turns: *searching is then the lanes not done, each at its node in *level,
 * *i (a lane in Newton's steps at the node they narrow), from which a later call goes on (a packet waits for its
 * slowest lane: the lanes left over from many packets go on in full ones, kernels/effects.cl). */
IA_FN ia_maskv packet_first_root_turns(PACKET_TAPE_PARAM const __global ulong *segment_groups, const ia_realv o[3],
                                       const ia_realv d[3], ia_real t0, ia_real w, packet_int *level_io,
                                       packet_index *i_io, ia_realv t_near, ia_realv t_far, ia_maskv *searching_io,
                                       int turns, ia_real eps, ia_real footprint0, ia_real footprint_t, iav time,
                                       ia_realv *hit_lo, ia_realv *hit_hi, packet_index *evals) {
    packet_int level = *level_io;
    packet_index i = *i_io;
    ia_maskv searching = *searching_io;
    ia_maskv hit = (ia_maskv)0, newton = (ia_maskv)0, bisect_only = (ia_maskv)0;
    ia_realv na = IAV_R(0), nb = IAV_R(0);
#ifndef PACKET_NEWTON
    (void)footprint0, (void)footprint_t, (void)na, (void)nb, (void)bisect_only;
#elif defined(IACSG_TAPE)
    int newton_on = tape[TAPE_W_NEWTON]; /* (bisect_only, and so the mean value form, follow Newton's steps) */
#else
    int newton_on = 1;
#endif
    for (int turn = 0; iav_any(searching) && (turns == 0 || turn < turns); turn++) {
        ia_maskv bisecting = searching & ~newton;
#ifdef PACKET_NEWTON
        /* one kind of step at a time, for the lanes that are the majority: a lane waits while the others step */
        int newton_turn = iav_count(searching & newton) >= iav_count(bisecting);
#else
        int newton_turn = 0;
#endif
        if (!newton_turn) {
            ia_realv lo = packet_node_bound(t0, w, level, i), hi = packet_node_bound(t0, w, level, i + 1);
            searching &= ~(bisecting & (lo > t_far)); /* so is every node after it: a miss */
            bisecting &= searching;
            ia_realv a = fmax(lo, t_near), b = fmin(hi, t_far);
            ia_maskv live = bisecting & (a <= b);
            iav t = iav_make(a, b);
            iav f;
#ifdef PACKET_NEWTON
            ia_realv coarse = (ia_real)NEWTON_PIXELS * (footprint0 + a * footprint_t);
            ia_maskv tangent = live & bisect_only & (b - a <= coarse);
            packet_form form = {(ia_maskv)0, iav_point(1), a, iav_point(0)};
            if (iav_any(tangent))
                f = packet_mean_value(PACKET_TAPE_ARG segment_groups, o, d, t, live, level, i, tangent, time, &form,
                                      evals);
            else
#endif
                f = packet_F_nodes(PACKET_TAPE_ARG segment_groups, live, level, i, packet_extent(o[0], d[0], t),
                                   packet_extent(o[1], d[1], t), packet_extent(o[2], d[2], t), time);
            PACKET_COUNT(*evals, live);
            ia_maskv zero = live & iav_contains_zero(f);
            ia_maskv leaf = zero & ((b - a <= eps) | (level == BISECT_MAX_LEVEL));
#ifdef PACKET_NEWTON
            ia_maskv refine = newton_on ? zero & ~leaf & ~bisect_only & (b - a <= coarse) &
                                              (b - a >= (ia_real)NEWTON_MIN_LEAVES * eps)
                                        : (ia_maskv)0;
            na = select(na, a, refine);
            nb = select(nb, b, refine);
            /* a tangent lane whose slope keeps one sign over its node: Newton's step from the form's centre, with
             * the form's F and F' (no evaluation), and Newton's turns from there */
            ia_maskv monotone = form.use & zero & ~leaf & ((form.slope.lo > 0) | (form.slope.hi < 0));
            if (newton_on && iav_any(monotone)) {
                ia_realv n_lo, n_hi;
                ia_maskv kept = packet_newton_step(form.c, form.fc, form.slope, monotone, a, b, eps, &n_lo, &n_hi);
                zero &= ~(monotone & ~kept); /* N misses the node: no root in it */
                monotone = kept;
                na = select(na, n_lo, monotone);
                nb = select(nb, n_hi, monotone);
                refine |= monotone;
            }
            newton |= refine;
#else
            ia_maskv refine = (ia_maskv)0;
#endif
            *hit_lo = select(*hit_lo, a, leaf);
            *hit_hi = select(*hit_hi, b, leaf);
            hit |= leaf;
            searching &= ~leaf;
            packet_advance_some(&searching, bisecting & ~leaf & ~refine, zero, &level, &i);
        }
#ifdef PACKET_NEWTON
        ia_maskv stepping = searching & newton;
        if (newton_turn) {
            iav t = iav_make(na, nb), slope = iav_point(0), fm, f;
            ulong groups; /* as fm: set by packet_Fd, read only after it (without it no lane steps) */
            if (iav_any(stepping & (nb - na > eps)))
                f = packet_Fd(PACKET_TAPE_ARG segment_groups, o, d, t, stepping, level, i, time, &slope, &fm, &groups);
            else
                f = packet_F_nodes(PACKET_TAPE_ARG segment_groups, stepping, level, i, packet_extent(o[0], d[0], t),
                                   packet_extent(o[1], d[1], t), packet_extent(o[2], d[2], t), time);
            PACKET_COUNT(*evals, stepping);
            ia_maskv zero = stepping & iav_contains_zero(f);
            ia_maskv leaf = zero & (nb - na <= eps);
            ia_maskv bounded = isfinite(slope.lo) & isfinite(slope.hi); /* NaN is not: garbage lanes stop too */
            ia_maskv stuck = zero & ~leaf & (iav_contains_zero(slope) | ~bounded);
            ia_maskv step = zero & ~leaf & ~stuck;
            ia_maskv empty = stepping & ~zero;
            if (iav_any(step)) {
                ia_realv m = na * (ia_real)0.5 + nb * (ia_real)0.5;
#ifndef IACSG_TAPE /* a tape's came with f, over the same parts; over packet_Fd's groups here */
                iav at_m = iav_make(m, m);
                fm = packet_F_live(groups, step, packet_extent(o[0], d[0], at_m), packet_extent(o[1], d[1], at_m),
                                   packet_extent(o[2], d[2], at_m), time);
#endif
                PACKET_COUNT(*evals, step);
                ia_realv a, b;
                ia_maskv kept = packet_newton_step(m, fm, slope, step, na, nb, eps, &a, &b);
                empty |= step & ~kept;
                step = kept;
                /* no longer converging: bisect instead (the half leaf's floor never decides it: a step's part is
                 * wider than eps) */
                stuck |= step & (b - a > (ia_real)0.5 * (nb - na));
                na = select(na, a, step);
                nb = select(nb, b, step);
            }
            *hit_lo = select(*hit_lo, na, leaf);
            *hit_hi = select(*hit_hi, nb, leaf);
            hit |= leaf;
            searching &= ~leaf;
            bisect_only |= stuck; /* Newton does not converge on this ray: the walk from its part, and later nodes */
            newton &= ~(leaf | stuck | empty);
            packet_advance_some(&searching, empty, (ia_maskv)0, &level, &i);
            if (iav_any(stuck))
                packet_resume_at(t0, w, stuck, na, nb - na, &level, &i);
        }
#endif
    }
    *level_io = level;
    *i_io = i;
    *searching_io = searching;
    return hit;
}

/* packet_first_root_turns until every lane of `searching` is done. */
IA_FN ia_maskv packet_first_root(PACKET_TAPE_PARAM const __global ulong *segment_groups, const ia_realv o[3],
                                 const ia_realv d[3], ia_real t0, ia_real w, packet_int level, packet_index i,
                                 ia_realv t_near, ia_realv t_far, ia_maskv searching, ia_real eps,
                                 ia_real footprint0, ia_real footprint_t, iav time, ia_realv *hit_lo,
                                 ia_realv *hit_hi, packet_index *evals) {
    return packet_first_root_turns(PACKET_TAPE_ARG segment_groups, o, d, t0, w, &level, &i, t_near, t_far,
                                   &searching, 0, eps, footprint0, footprint_t, time, hit_lo, hit_hi, evals);
}

#endif
#endif
