/* kernels/segments_lanes_frame.h -- a packet's ells, quadric tgcs and ehys solved along its IA_VW rays at once, one
 * SIMD lane per ray, into segments_lanes.h's table (OpenCL C; an orthographic view: the rays share the direction
 * terms G d).
 *
 *   segments_lanes_fill_solid(l, k, type, p, d, dir, known): solid k's slot for every lane, the direction terms
 *     kept in dir (prim_segments_dir) whatever the type (0 where the scalar code solves it):
 *     1. planar types: segments_lanes_fill; frame types, where the pieces' shape is one for every ray (a tgc's
 *        alpha and beta close, its slab's planes not along the rays), on:
 *     2. each lane's range start, its ray's entry into the solid's BVH leaf as bvh_push computes it
 *        (bvh_node_clip: the same products, roundings and maxima; the leaf from the table after the BVH's links),
 *        and on only where SEGMENTS_LANES_FRAME_RAYS lanes at least meet the leaf;
 *     3. prim_segments' frame s = G (x - P) at that point, and prim_segments_frame's pieces from it, each operation
 *        the scalar one in every lane (ia/vec.h's, which round as ia/round.h), the quadric's branches selected per
 *        lane; a lane whose quadric the scalar code would not solve this way (A may be 0, a bound not finite, a
 *        NaN) gets a NaN start, and the scalar code solves its ray.
 *
 * Why: operators' render was its ells and ehys solved ray by ray in scalar interval code (prim_frame,
 * prim_segments_frame, prim_segments_quadric: half of its kernel samples), for the 16 rays of a packet that mostly
 * reach the same solids.
 *
 * Bit for bit the scalar code's: a ray takes its lane only where its range start is the lane's, bit for bit
 * (segments_lanes_changes), and a lane's span is a function of its origin, the shared direction and that start.
 */
#ifndef KERNELS_SEGMENTS_LANES_FRAME_H
#define KERNELS_SEGMENTS_LANES_FRAME_H
#include "bvh.h"
#include "segments_lanes.h"
#ifdef SEGMENTS_LANES

/* The fewest rays of a packet that must meet a frame solid's leaf for the lanes to solve it: a solve in lanes costs
 * a few scalar ones (truck's small tgcs, met by a few rays a packet, were slower in lanes). */
#define SEGMENTS_LANES_FRAME_RAYS 4

/* Each lane's span (prim_segments_span) and the lanes where a bound was NaN. */
typedef struct {
    ia_realv plo, phi, ilo, ihi;
    ia_maskv nan;
} segments_lanes_span;

IA_FN void segments_lanes_keep(segments_lanes_span *s, ia_realv plo, ia_realv phi, ia_realv ilo, ia_realv ihi) {
    s->nan |= isnan(plo) | isnan(phi) | isnan(ilo) | isnan(ihi);
    s->plo = fmax(s->plo, plo);
    s->phi = fmin(s->phi, phi);
    s->ilo = fmax(s->ilo, ilo);
    s->ihi = fmin(s->ihi, ihi);
}

/* ia_div_one_signed(a, b) in each lane. */
IA_FN iav segments_lanes_div_v(iav a, iav b) {
    ia_maskv zero = a.lo == 0 && a.hi == 0, positive = b.lo > 0;
    ia_realv num_lo = select(a.hi, a.lo, positive), num_hi = select(a.lo, a.hi, positive);
    ia_realv lo = num_lo / select(b.lo, b.hi, num_lo >= 0), hi = num_hi / select(b.hi, b.lo, num_hi >= 0);
    return iav_make(select(iav_lo_k(lo, IA_ULP_DIV), IAV_R(0), zero), select(iav_hi_k(hi, IA_ULP_DIV), IAV_R(0), zero));
}

/* prim_segments_plane for a slope b one-signed (the same in every lane), from each lane's start ta. */
IA_FN void segments_lanes_plane(segments_lanes_span *s, iav c, ia_interval b, ia_realv ta) {
    iav u = segments_lanes_div(iav_neg(c), b), t = iav_add(iav_make(ta, ta), u);
    t = iav_make(select(t.lo, u.lo, ta == 0), select(t.hi, u.hi, ta == 0));
    if (b.lo > 0)
        segments_lanes_keep(s, IAV_R(-IA_INF), t.hi, IAV_R(-IA_INF), t.lo);
    else
        segments_lanes_keep(s, t.lo, IAV_R(IA_INF), t.hi, IAV_R(IA_INF));
}

/* prim_segments_quadric's span in each lane, from its start ta, where the quadric's roots decide it (side: the same
 * in every lane); returns the lanes where they do not (the scalar code's other cases, or its 0). */
IA_FN ia_maskv segments_lanes_quadric(segments_lanes_span *s, iav a, iav b, iav c, int side, ia_realv ta) {
    ia_maskv flip = a.hi < 0, scalar = !(a.lo > 0) && (side == 0 ? (ia_maskv)(-1) : !flip);
    a = iav_make(select(a.lo, -a.hi, flip), select(a.hi, -a.lo, flip));
    b = iav_make(select(b.lo, -b.hi, flip), select(b.hi, -b.lo, flip));
    c = iav_make(select(c.lo, -c.hi, flip), select(c.hi, -c.lo, flip));
    iav disc = iav_sub(iav_sqr(b), iav_mul(a, c)), root = iav_sqrt(disc), nb = iav_neg(b);
    scalar = scalar | !(disc.lo <= disc.hi) | !isfinite(disc.lo) | !isfinite(disc.hi);
    ia_maskv miss = disc.hi < 0, graze = !(disc.lo > 0), up = b.lo > 0, down = b.hi < 0;
    scalar = scalar | (miss & flip);
    /* the roots r1 <= r2 as quotients: q / A and C / q (q the stable form, of B's sign), -B -+ sqrt(D) over A where
     * B may be 0, -B + [-h, h] over A where D may be 0 */
    ia_realv h = iav_hi_k(sqrt(disc.hi), IA_ULP_SQRT);
    iav q_up = iav_neg(iav_add(b, root)), q_down = iav_sub(root, b), q = iav__pick(q_down, q_up, up);
    iav either = iav_sub(nb, root), other = iav_add(nb, root), wide = iav_add(nb, iav_make(-h, h));
    iav num1 = iav__pick(iav__pick(either, c, down), q, up), num2 = iav__pick(iav__pick(other, q, down), c, up);
    num1 = iav__pick(num1, wide, graze);
    num2 = iav__pick(num2, wide, graze);
    iav den1 = iav__pick(iav__pick(a, q, down), a, up), den2 = iav__pick(iav__pick(a, a, down), q, up);
    den1 = iav__pick(den1, a, graze);
    den2 = iav__pick(den2, a, graze);
    iav r1 = iav_add(iav_make(ta, ta), segments_lanes_div_v(num1, den1));
    iav r2 = iav_add(iav_make(ta, ta), segments_lanes_div_v(num2, den2));
    ia_maskv decided = !graze & (r1.hi < r2.lo);
    ia_realv plo = r1.lo, phi = r2.hi, ilo = select(IAV_R(IA_INF), r1.hi, decided);
    ia_realv ihi = select(IAV_R(-IA_INF), r2.lo, decided);
    if (side > 0) {
        plo = select(plo, r2.lo, flip);
        phi = select(phi, IAV_R(IA_INF), flip);
        ilo = select(ilo, r2.hi, flip);
        ihi = select(ihi, IAV_R(IA_INF), flip);
    } else if (side < 0) {
        plo = select(plo, IAV_R(-IA_INF), flip);
        phi = select(phi, r1.hi, flip);
        ilo = select(ilo, IAV_R(-IA_INF), flip);
        ihi = select(ihi, r1.lo, flip);
    }
    plo = select(plo, IAV_R(IA_INF), miss); /* no root: out all along */
    phi = select(phi, IAV_R(-IA_INF), miss);
    ilo = select(ilo, IAV_R(IA_INF), miss);
    ihi = select(ihi, IAV_R(-IA_INF), miss);
    segments_lanes_keep(s, plo, phi, ilo, ihi);
    return scalar;
}

/* prim_segments_frame in each lane from its frame point a (at its start ta) and the shared direction terms b; 0
 * where the pieces' shape is not one for every lane (the scalar code solves the solid), else the lanes it
 * leaves to the scalar code in *scalar. */
IA_FN int segments_lanes_pieces(segments_lanes_span *s, int type, const ia_real *p, const iav a[3],
                                const ia_interval b[3], ia_realv ta, ia_maskv *scalar) {
    iav aa = iav_add(iav_sqr(a[0]), iav_sqr(a[1]));
    iav ab = iav_add(iav_mul(a[0], iav_splat(b[0])), iav_mul(a[1], iav_splat(b[1])));
    ia_interval bb = ia_add(ia_sqr(b[0]), ia_sqr(b[1]));
    if (type == PRIM_ELL) {
        *scalar = segments_lanes_quadric(s, iav_splat(ia_add(bb, ia_sqr(b[2]))),
                                         iav_add(ab, iav_mul(a[2], iav_splat(b[2]))),
                                         iav_add_r(iav_add(aa, iav_sqr(a[2])), -1), 0, ta);
        return 1;
    }
    if (!(b[2].lo > 0 || b[2].hi < 0)) /* the slab's planes along the rays: their pieces depend on the range */
        return 0;
    if (type == PRIM_EHY) {
        ia_interval k1 = prim_iv(p, 12);
        iav zk = iav_add(a[2], iav_splat(prim_iv(p, 13)));
        segments_lanes_plane(s, a[2], b[2], ta);
        segments_lanes_plane(s, iav_sub(iav_const(-1, -1), a[2]), ia_neg(b[2]), ta);
        iav c = iav_add(iav_sub(iav_mul(iav_splat(k1), iav_add_r(aa, -1)), iav_sqr(zk)), iav_splat(prim_iv(p, 14)));
        *scalar = segments_lanes_quadric(s, iav_splat(ia_sub(ia_mul(k1, bb), ia_sqr(b[2]))),
                                         iav_sub(iav_mul(iav_splat(k1), ab), iav_mul(zk, iav_splat(b[2]))), c,
                                         b[2].lo > 0 ? 1 : -1, ta);
        return 1;
    }
    ia_interval gamma = ia_hull(prim_iv(p, 12), prim_iv(p, 13));
    gamma.lo = fmax(gamma.lo, (ia_real)-1);
    if (!(gamma.hi - gamma.lo <= PRIM_SEGMENTS_SKEW)) /* a general tgc: a quartic */
        return 0;
    ia_interval r1 = ia_mul(gamma, b[2]);
    iav r0 = iav_add_r(iav_mul(iav_splat(gamma), a[2]), 1);
    segments_lanes_plane(s, iav_neg(a[2]), ia_neg(b[2]), ta);
    segments_lanes_plane(s, iav_add_r(a[2], -1), b[2], ta);
    *scalar = segments_lanes_quadric(s, iav_splat(ia_sub(bb, ia_sqr(r1))), iav_sub(ab, iav_mul(r0, iav_splat(r1))),
                                     iav_sub(aa, iav_sqr(r0)), r1.lo > 0 ? 1 : r1.hi < 0 ? -1 : 0, ta);
    return 1;
}

/* Each lane's entry into node k's box as bvh_node_clip gives it from the lane's walk start (garbage in a lane that
 * misses the box, whose ray never solves the solid from there), and how many lanes meet the box; -1 where a ray
 * divides (bvh_ray's `divide`). */
IA_FN int segments_lanes_entry(const segments_lanes *l, int k, const ia_real d[3], ia_realv *te) {
    ia_realv dv[3], tx;
    for (int c = 0; c < 3; c++) {
        if (d[c] != 0 && !isfinite((ia_real)1 / d[c]))
            return -1;
        dv[c] = IAV_R(d[c]);
    }
    ia_maskv miss = bvh_node_clip_lanes(l->box, k, l->o, dv, l->inv, l->tn, l->tf, te, &tx);
    return iav_count(!miss & (*te <= tx)); /* (not a lane whose range is NaN) */
}

/* An ell's, a quadric tgc's or an ehy's slot for every lane (type, parameters p, direction terms as
 * segments_lanes_fill); 0 where the scalar code solves the solid. */
IA_FN int segments_lanes_fill_frame(segments_lanes *l, int k, int type, const ia_real *p, const ia_real d[3],
                                    ia_interval *dir, int known) {
    int slot = k % SEGMENTS_LANES_SLOTS, leaf = l->link[2 * l->nodes + k];
    ia_interval b[3];
    for (int r = 0; r < 3; r++)
        b[r] = prim_segments_dir(p, 3 + 3 * r, d, dir, known, r);
    l->solid[slot] = k;
    l->solved[slot] = SEGMENTS_LANES_SCALAR;
    ia_realv ta;
    if (leaf < 0 || segments_lanes_entry(l, leaf, d, &ta) < SEGMENTS_LANES_FRAME_RAYS)
        return 0;
    iav x[3], q[3], a[3];
    for (int c = 0; c < 3; c++) { /* ray_extent at the point ta, less P */
        ia_realv at = fma(IAV_R(d[c]), ta, l->o[c]);
        x[c] = iav_make(iav_lo(at), iav_hi(at));
        q[c] = iav_sub(x[c], iav_splat(prim_iv(p, c)));
    }
    for (int r = 0; r < 3; r++) /* prim_frame's s = G (x - P) */
        a[r] = iav_add(iav_add(iav_mul(iav_splat(prim_iv(p, 3 + 3 * r)), q[0]),
                               iav_mul(iav_splat(prim_iv(p, 4 + 3 * r)), q[1])),
                       iav_mul(iav_splat(prim_iv(p, 5 + 3 * r)), q[2]));
    segments_lanes_span s = {IAV_R(-IA_INF), IAV_R(IA_INF), IAV_R(-IA_INF), IAV_R(IA_INF), ta != ta};
    ia_maskv scalar;
    if (!segments_lanes_pieces(&s, type, p, a, b, ta, &scalar))
        return 0;
    scalar = scalar | s.nan;
    for (int c = 0; c < 3; c++) /* ... and where a frame bound is not finite, which the scalar code may treat apart */
        scalar = scalar | !isfinite(a[c].lo) | !isfinite(a[c].hi);
    l->solved[slot] = SEGMENTS_LANES_FRAME;
    IAV_STORE(s.plo, l->span[slot][0]);
    IAV_STORE(s.phi, l->span[slot][1]);
    IAV_STORE(s.ilo, l->span[slot][2]);
    IAV_STORE(s.ihi, l->span[slot][3]);
    IAV_STORE(select(ta, IAV_R(NAN), scalar), l->span[slot][SEGMENTS_LANES_FROM]);
    return 1;
}

/* Whether solid type `type` has a lanes' solve here. */
IA_FN int segments_lanes_fits(int type) {
    return type == PRIM_HALF || type == PRIM_ARB8 || type == PRIM_ELL || type == PRIM_TGC || type == PRIM_EHY;
}

/* Solid k's slot for every lane (a type that segments_lanes_fits), its direction terms left in dir. */
IA_FN void segments_lanes_fill_solid(segments_lanes *l, int k, int type, const ia_real *p, const ia_real d[3],
                                     ia_interval *dir, int known) {
    if (type == PRIM_HALF || type == PRIM_ARB8)
        segments_lanes_fill(l, k, type, p, d, dir, known);
    else
        segments_lanes_fill_frame(l, k, type, p, d, dir, known);
}

#endif
#endif
