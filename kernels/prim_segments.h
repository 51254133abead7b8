/* kernels/prim_segments.h -- closed-form segments of the convex primitives along a ray: where librt solves each
 * primitive once per ray, the bisection walk (segments.h) evaluates its implicit some 30 times. The solid's states
 * come out as the walk's accepted nodes would: OUT, BOUNDARY over an enclosure of the entry, IN, BOUNDARY over an
 * enclosure of the exit, OUT; every enclosure outward, so a boundary the ray crosses is never missed nor late.
 *
 *   prim_segments(type, p, o, d, ta, tend, e):
 *     1. the ray's origin o and direction d (exact), its point at ta enclosed (traverse.h's ray_extent);
 *     2. each piece of the solid along the ray: a plane's c + b t from o (c and b each with 2 products of an
 *        interval by a real: as precise as from ta, both a few ulps of t), a quadric's A u^2 + 2 B u + C in
 *        u = t - ta (from the far origin its discriminant would cancel), the coefficients intervals holding the
 *        exact ones (from kernels/prim.h's placed parameters);
 *     3. each piece's t span where it may be in (outside it certainly out) and where it is certainly in
 *        (prim_segments_plane, prim_segments_quadric);
 *     4. the solid, the intersection of its pieces (convex: one span each), clipped to [ta, tend]: its four
 *        changes e[0..3] (OUT before e0, BOUNDARY to e1, IN to e2, BOUNDARY to e3, OUT after).
 *   Returns 0 where a piece cannot be decided (a quadric whose A may be 0, along a ray that meets its surface: a
 *   ray on a cone's side line), and for the other types: the walk then bisects.
 *
 * The pieces. HALF: its plane. ARB8: its six planes (the solid is their intersection, prim.h). ELL: |s|^2 - 1 (s
 * = G (x - P)). TGC where alpha and beta are within PRIM_SEGMENTS_SKEW (rcc, rec, trc, tec): the slab 0 <= w <= 1
 * and u^2 + v^2 - (1 + gamma w)^2, gamma over the hull of alpha and beta. With r = 1 + gamma w >= 0 on the slab
 * (alpha, beta >= -1), the tgc lies between the cones of gamma = min(alpha, beta) and max(alpha, beta)
 * (u^2 / ra^2 + v^2 / rb^2 is between (u^2 + v^2) / max(ra, rb)^2 and that over min(ra, rb)^2), so an enclosure
 * over every gamma of the hull holds the tgc's own boundary, a few ulps wider where alpha and beta differ in their
 * last digits, as a database's rounded trc does. A cone's quadric is negative in both nappes: where A < 0 (the
 * ray crosses both) the slab keeps the one where r grows along the ray, after the later root (before the earlier
 * one where r falls); where r is 0 the quadric is u^2 + v^2 >= 0, so the other nappe holds no point of the slab.
 * EHY: the slab -1 <= z <= 0 and prim.h's k1 (x^2 + y^2 - 1) - (z + k2)^2 + k2^2 = k1 (x^2 + y^2) - (z + k2)^2 + c'^2,
 * negative inside both sheets of a hyperboloid; the slab's (z + k2 >= c') is the one where z + k2 > 0, and where
 * z + k2 = 0 the quadric is positive: so where A < 0, the half-line on the side where z grows, as a cone's.
 *
 * Every root is one interval expression of the coefficients (the stable form: q = -(B + sign(B) sqrt(D)), roots
 * q / A and C / q), which holds the exact root of every quadratic with coefficients in their intervals. Where
 * the discriminant D may be 0 (a grazing ray), the roots, where there are any, lie in (-B +- sqrt(D.hi)) / A: a
 * BOUNDARY over all of it, never IN. Written in the subset of C11 and OpenCL C of ia/ (host tests run it).
 */
#ifndef KERNELS_PRIM_SEGMENTS_H
#define KERNELS_PRIM_SEGMENTS_H
#include "prim.h"
#include "traverse.h"

/* The most reals of parameters a closed-form type has: an arb8's 24 intervals (implicits/scene_emit.c stores
 * each type's padded to a multiple of 8 reals, 48 for an arb8). */
#define PRIM_SEGMENTS_REALS (2 * PRIM_ARB8_N)
/* A tgc is a quadric here where its alpha and beta are this close (their hull's width). */
#define PRIM_SEGMENTS_SKEW ((ia_real)1e-6)

/* A span of the ray: possibly in over [plo, phi] (certainly out elsewhere), certainly in over (ilo, ihi); nan
 * when a bound was NaN (fmax and fmin would drop it). */
typedef struct {
    ia_real plo, phi, ilo, ihi;
    int nan;
} prim_segments_span;

IA_FN void prim_segments_keep(prim_segments_span *s, ia_real plo, ia_real phi, ia_real ilo, ia_real ihi) {
    s->nan |= isnan(plo) || isnan(phi) || isnan(ilo) || isnan(ihi);
    s->plo = fmax(s->plo, plo);
    s->phi = fmin(s->phi, phi);
    s->ilo = fmax(s->ilo, ilo);
    s->ihi = fmin(s->ihi, ihi);
}

/* a.v for intervals a = p's k..k+2 and a real vector v: interval times real (2 products, not 4). */
IA_FN ia_interval prim_segments_dot(const ia_real *p, int k, const ia_real v[3]) {
    return ia_add(ia_add(ia_mul_r(prim_iv(p, k), v[0]), ia_mul_r(prim_iv(p, k + 1), v[1])),
                  ia_mul_r(prim_iv(p, k + 2), v[2]));
}

/* A plane's piece c + b (t - t0), over the range u = t - t0 in `range`: in before its root where b > 0, after it
 * where b < 0; where b may be 0, in, out or undecided over the whole range by its enclosure there. */
IA_FN void prim_segments_plane(prim_segments_span *s, ia_interval c, ia_interval b, ia_real t0, ia_interval range) {
    if (b.lo > 0 || b.hi < 0) {
        ia_interval u = ia_div(ia_neg(c), b), t = t0 == 0 ? u : ia_add(ia_point(t0), u);
        if (b.lo > 0)
            prim_segments_keep(s, -IA_INF, t.hi, -IA_INF, t.lo);
        else
            prim_segments_keep(s, t.lo, IA_INF, t.hi, IA_INF);
        return;
    }
    ia_interval g = ia_add(c, ia_mul(range, b));
    if (g.lo > 0)
        prim_segments_keep(s, IA_INF, -IA_INF, IA_INF, -IA_INF);
    else if (!(g.hi < 0))
        prim_segments_keep(s, -IA_INF, IA_INF, IA_INF, -IA_INF);
}

/* A quadric's piece A u^2 + 2 B u + C (u = t - ta), in where it is negative; with A < 0 only the half-line
 * after its later root (side > 0) or before its earlier one (side < 0). Where A may be 0 or its sign leaves the
 * nappe open (a ray along a cylinder's axis), in or out all along the range [ta, ta + width] by its enclosure
 * there. 0 where it cannot be decided. */
IA_FN int prim_segments_quadric(prim_segments_span *s, ia_interval a, ia_interval b, ia_interval c, int side,
                                ia_real ta, ia_real width) {
    int flip = a.hi < 0; /* -q has the same roots, and A > 0 */
    if (!(a.lo > 0) && !(flip && side != 0)) {
        ia_interval u = ia_make(0, width), q = ia_add(ia_mul(ia_add(ia_mul(a, u), ia_mul_r(b, 2)), u), c);
        if (q.lo > 0)
            prim_segments_keep(s, IA_INF, -IA_INF, IA_INF, -IA_INF);
        return q.lo > 0 || q.hi < 0;
    }
    if (flip) {
        a = ia_neg(a);
        b = ia_neg(b);
        c = ia_neg(c);
    }
    ia_interval disc = ia_sub(ia_sqr(b), ia_mul(a, c)), r1, r2;
    if (!(disc.lo <= disc.hi) || !isfinite(disc.lo) || !isfinite(disc.hi))
        return 0;
    if (disc.hi < 0) { /* no root: q > 0 everywhere (a cone's line always has one: undecided) */
        if (flip)
            return 0;
        prim_segments_keep(s, IA_INF, -IA_INF, IA_INF, -IA_INF);
        return 1;
    }
    if (disc.lo > 0) {
        ia_interval root = ia_sqrt(disc);
        if (b.lo > 0 || b.hi < 0) {
            ia_interval q = b.lo > 0 ? ia_neg(ia_add(b, root)) : ia_sub(root, b);
            ia_interval big = ia_div(q, a), small = ia_div(c, q); /* q / A is the root of B's other sign */
            r1 = b.lo > 0 ? big : small;
            r2 = b.lo > 0 ? small : big;
        } else {
            r1 = ia_div(ia_sub(ia_neg(b), root), a);
            r2 = ia_div(ia_add(ia_neg(b), root), a);
        }
    } else {
        ia_real h = ia_sqrt(ia_make(0, disc.hi)).hi;
        r1 = r2 = ia_div(ia_add(ia_neg(b), ia_make(-h, h)), a);
    }
    r1 = ia_add(ia_point(ta), r1);
    r2 = ia_add(ia_point(ta), r2);
    int decided = disc.lo > 0 && r1.hi < r2.lo;
    if (!flip)
        prim_segments_keep(s, r1.lo, r2.hi, decided ? r1.hi : IA_INF, decided ? r2.lo : -IA_INF);
    else if (side > 0)
        prim_segments_keep(s, r2.lo, IA_INF, r2.hi, IA_INF);
    else
        prim_segments_keep(s, -IA_INF, r1.hi, -IA_INF, r1.lo);
    return 1;
}

/* The pieces of an ell, a quadric tgc or an ehy, from s = a + u b along the ray (a at ta, b = G d). */
IA_FN int prim_segments_frame(int type, const ia_real *p, const ia_interval a[3], const ia_interval b[3],
                              prim_segments_span *s, ia_real ta, ia_real width) {
    ia_interval aa = ia_add(ia_sqr(a[0]), ia_sqr(a[1])), ab = ia_add(ia_mul(a[0], b[0]), ia_mul(a[1], b[1]));
    ia_interval bb = ia_add(ia_sqr(b[0]), ia_sqr(b[1]));
    if (type == PRIM_ELL)
        return prim_segments_quadric(s, ia_add(bb, ia_sqr(b[2])), ia_add(ab, ia_mul(a[2], b[2])),
                                     ia_add_r(ia_add(aa, ia_sqr(a[2])), -1), 0, ta, width);
    if (type == PRIM_EHY) { /* k1 (x^2 + y^2 - 1) - (z + k2)^2 + k2^2 on the slab -1 <= z <= 0 */
        ia_interval k1 = prim_iv(p, 12), zk = ia_add(a[2], prim_iv(p, 13));
        prim_segments_plane(s, a[2], b[2], ta, ia_make(0, width));
        prim_segments_plane(s, ia_sub(ia_make(-1, -1), a[2]), ia_neg(b[2]), ta, ia_make(0, width));
        return prim_segments_quadric(s, ia_sub(ia_mul(k1, bb), ia_sqr(b[2])), ia_sub(ia_mul(k1, ab), ia_mul(zk, b[2])),
                                     ia_add(ia_sub(ia_mul(k1, ia_add_r(aa, -1)), ia_sqr(zk)), prim_iv(p, 14)),
                                     b[2].lo > 0 ? 1 : b[2].hi < 0 ? -1 : 0, ta, width);
    }
    ia_interval gamma = ia_hull(prim_iv(p, 12), prim_iv(p, 13));
    gamma.lo = fmax(gamma.lo, (ia_real)-1); /* alpha, beta = |C| / |A| - 1, |D| / |B| - 1 */
    if (!(gamma.hi - gamma.lo <= PRIM_SEGMENTS_SKEW))
        return 0;
    ia_interval r0 = ia_add_r(ia_mul(gamma, a[2]), 1), r1 = ia_mul(gamma, b[2]); /* r = r0 + u r1 */
    prim_segments_plane(s, ia_neg(a[2]), ia_neg(b[2]), ta, ia_make(0, width));
    prim_segments_plane(s, ia_add_r(a[2], -1), b[2], ta, ia_make(0, width));
    return prim_segments_quadric(s, ia_sub(bb, ia_sqr(r1)), ia_sub(ab, ia_mul(r0, r1)), ia_sub(aa, ia_sqr(r0)),
                                 r1.lo > 0 ? 1 : r1.hi < 0 ? -1 : 0, ta, width);
}

/* The solid's changes along o + t d over [ta, tend] (see the top): 1 with e[0..3], or 0 where the walk must
 * bisect. */
IA_FN int prim_segments(int type, const ia_real *p, const ia_real o[3], const ia_real d[3], ia_real ta, ia_real tend,
                        ia_real e[4]) {
    prim_segments_span s = {-IA_INF, IA_INF, -IA_INF, IA_INF, 0};
    if (type == PRIM_HALF || type == PRIM_ARB8) { /* n.o - d + t n.d: from the ray's origin, an exact point */
        for (int j = 0; j < (type == PRIM_HALF ? 1 : PRIM_ARB_PLANES); j++)
            prim_segments_plane(&s, ia_sub(prim_segments_dot(p + 8 * j, 0, o), prim_iv(p + 8 * j, 3)),
                                prim_segments_dot(p + 8 * j, 0, d), 0, ia_make(ta, tend));
    } else if (type == PRIM_ELL || type == PRIM_TGC || type == PRIM_EHY) {
        ia_interval at = ia_point(ta), a[3], b[3];
        prim_frame(p, 0, ray_extent(o[0], d[0], at), ray_extent(o[1], d[1], at), ray_extent(o[2], d[2], at), a);
        for (int r = 0; r < 3; r++)
            b[r] = prim_segments_dot(p, 3 + 3 * r, d);
        if (!prim_segments_frame(type, p, a, b, &s, ta, ia_hi(tend - ta)))
            return 0;
    } else {
        return 0;
    }
    if (s.nan)
        return 0;
    ia_real plo = fmax(s.plo, ta), phi = fmin(s.phi, tend);
    if (!(plo < phi)) { /* out all along */
        e[0] = e[1] = e[2] = e[3] = ta;
        return 1;
    }
    ia_real ilo = fmax(s.ilo, plo), ihi = fmin(s.ihi, phi);
    e[0] = plo;
    e[1] = ilo < ihi ? ilo : phi;
    e[2] = ilo < ihi ? ihi : phi;
    e[3] = phi;
    return 1;
}

#endif
