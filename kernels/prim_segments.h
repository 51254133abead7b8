/* kernels/prim_segments.h -- closed-form segments of the primitives along a ray (the pipe's: prim_pipe_segments.h):
 * where librt solves each primitive once per ray, the bisection walk (segments.h) evaluates its implicit some 30 to 60
 * times. The solid's states come out as the walk's accepted nodes would: OUT, BOUNDARY over an enclosure of the entry,
 * IN, BOUNDARY over an enclosure of the exit, OUT; every enclosure outward, so a boundary the ray crosses is never
 * missed nor late. A torus or a general tgc may have a second run: prim_segments gives the first and the point to solve
 * again from (see "the quartics" below).
 *
 *   prim_segments(type, p, o, d, ta, tend, eps, e, resume, evals, dir, known):
 *     1. the ray's origin o and direction d (exact), its point at ta enclosed (traverse.h's ray_extent); the
 *        direction terms (n.d, G d) from dir where an earlier ray of the same direction left them (prim_dirs);
 *     2. each piece of the solid along the ray: a plane's c + b t from o (c and b each with 2 products of an
 *        interval by a real: as precise as from ta, both a few ulps of t), a quadric's A u^2 + 2 B u + C in
 *        u = t - ta (from the far origin its discriminant would cancel), the coefficients intervals holding the
 *        exact ones (from kernels/prim.h's placed parameters);
 *     3. each piece's t span where it may be in (outside it certainly out) and where it is certainly in
 *        (prim_segments_plane, prim_segments_quadric);
 *     4. the solid, the intersection of its pieces (convex: one span each), clipped to [ta, tend]: its four
 *        changes e[0..3] (OUT before e0, BOUNDARY to e1, IN to e2, BOUNDARY to e3, OUT after); a quartic's first run
 *        by prim_quartic_walk (eps: its leaves where the quartic is not monotone, at a double root), its
 *        coefficients in u = t - tm from the middle tm of the range it solves (prim_quartic_solve).
 *   Returns 0 where a piece cannot be decided (a quadric whose A may be 0, along a ray that meets its surface: a
 *   ray on a cone's side line): the walk then bisects. A pipe, the union of its parts: prim_pipe_segments.h.
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

/* The direction's part of the closed forms, a plane's n.d (an arb's six) or a frame's G d: the same for every ray
 * of an orthographic view, so a work-item keeps each solid's once computed (segments.h: segments_closed_solve),
 * in a table indexed by the solid's number modulo its size (solid[] -1: empty). */
#define PRIM_DIRS_SLOTS 32
#define PRIM_DIRS_INTERVALS PRIM_ARB_PLANES
typedef struct {
    int solid[PRIM_DIRS_SLOTS];
    ia_interval v[PRIM_DIRS_SLOTS][PRIM_DIRS_INTERVALS];
} prim_dirs;

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

/* The j-th direction term, a.d for a = p's k..k+2: dir[j] where `known`, else computed (and kept in dir[j] where
 * dir is not 0). */
IA_FN ia_interval prim_segments_dir(const ia_real *p, int k, const ia_real d[3], ia_interval *dir, int known, int j) {
    if (known)
        return dir[j];
    ia_interval v = prim_segments_dot(p, k, d);
    if (dir)
        dir[j] = v;
    return v;
}

/* A plane's piece c + b (t - t0), over the range u = t - t0 in `range`: in before its root where b > 0, after it
 * where b < 0; where b may be 0, in, out or undecided over the whole range by its enclosure there. */
IA_FN void prim_segments_plane(prim_segments_span *s, ia_interval c, ia_interval b, ia_real t0, ia_interval range) {
    if (b.lo > 0 || b.hi < 0) {
        ia_interval u = ia_div_one_signed(ia_neg(c), b), t = t0 == 0 ? u : ia_add(ia_point(t0), u);
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
            /* q / A is the root of B's other sign */
            ia_interval big = ia_div_one_signed(q, a), small = ia_div_one_signed(c, q);
            r1 = b.lo > 0 ? big : small;
            r2 = b.lo > 0 ? small : big;
        } else {
            r1 = ia_div_one_signed(ia_sub(ia_neg(b), root), a);
            r2 = ia_div_one_signed(ia_add(ia_neg(b), root), a);
        }
    } else {
        ia_real h = ia_sqrt(ia_make(0, disc.hi)).hi;
        r1 = r2 = ia_div_one_signed(ia_add(ia_neg(b), ia_make(-h, h)), a);
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

/* The changes over [ta, tend] of a convex solid whose pieces left the span s (no NaN): OUT all along where it
 * holds nothing of the range. Always 1 (one evaluation). */
IA_FN int prim_segments_convex(const prim_segments_span *s, ia_real ta, ia_real tend, ia_real e[4],
                               kernel_u32 *evals) {
    ia_real plo = fmax(s->plo, ta), phi = fmin(s->phi, tend);
    *evals += 1;
    if (!(plo < phi)) { /* out all along */
        e[0] = e[1] = e[2] = e[3] = ta;
        return 1;
    }
    ia_real ilo = fmax(s->ilo, plo), ihi = fmin(s->ihi, phi);
    e[0] = plo;
    e[1] = ilo < ihi ? ilo : phi;
    e[2] = ilo < ihi ? ihi : phi;
    e[3] = phi;
    return 1;
}

/* ---- the quartics: a torus and a general tgc. Along the ray each is a polynomial of degree 4 in u = t - ta,
 * q(u) = sum c_k u^k, with intervals c_k holding the exact coefficients, negative inside. The solver walks the
 * nodes of [lo, hi] (traverse.h's tree) in ray order: over a node q's Taylor form at its midpoint decides IN or OUT;
 * where it holds 0 and q' excludes 0 (q monotone), interval Newton narrows the one root to a BOUNDARY of a few ulps
 * and the node's parts before and after it get their signs without being split (the mean value theorem: a point
 * before every Newton image N = m - q(m) / D has q's sign before the root, as in segments.h's segments_newton);
 * elsewhere the node is split, down to BOUNDARY leaves of eps (a double root: a grazing ray). The states go into a
 * quartet, the four changes of a convex solid's run (OUT, BOUNDARY, IN, BOUNDARY, OUT); the walk stops at the
 * first state that does not fit it, and the segment walk solves again from there (prim_segments returns 2). */
#define PRIM_QUARTIC_NEWTON 8

typedef struct {
    ia_real e[4];
    int stage; /* the pattern's part that holds the last state: 0 OUT, 1 BOUNDARY, 2 IN, 3 BOUNDARY, 4 OUT after
                * the run, 5 done: the solid may be in again from `resume` on */
    ia_real resume;
    ia_real ilo, ihi; /* where the other pieces (a tgc's slab) are certainly in: IN outside it is BOUNDARY */
} prim_quartet;

IA_FN void prim_quartet_state(prim_quartet *q, ia_real at, int st) {
    int k = q->stage, next = k;
    if (k == 4) {
        q->stage = st == SCENE_OUT ? 4 : 5;
        q->resume = at;
        return;
    }
    while (next < 4 && (next == 0 ? SCENE_OUT : next == 2 ? SCENE_IN : SCENE_BOUNDARY) != st)
        next += 1;
    for (int j = k; j < next; j++)
        q->e[j] = at;
    if (next == 4) { /* OUT after the run, or IN again right after its end's BOUNDARY */
        q->e[3] = at;
        q->resume = at;
        next = st == SCENE_OUT ? 4 : 5;
    }
    q->stage = next;
}

/* The piece [lo, hi) of the quartic's state st; its parts outside the slab's certain span are at most BOUNDARY. */
IA_FN void prim_quartet_add(prim_quartet *q, ia_real lo, ia_real hi, int st) {
    ia_real cut[4] = {lo, fmax(lo, fmin(hi, q->ilo)), fmin(hi, fmax(lo, q->ihi)), hi};
    for (int z = 0; z < 3 && q->stage < 5; z++)
        if (cut[z] < cut[z + 1])
            prim_quartet_state(q, cut[z], z != 1 && st == SCENE_IN ? SCENE_BOUNDARY : st);
}

/* The coefficients of the product of two quadratics x, y (c0 first), or of a square when x == y. */
IA_FN void prim_quartic_mul(const ia_interval x[3], const ia_interval y[3], ia_interval c[5]) {
    c[0] = ia_mul(x[0], y[0]);
    c[1] = ia_add(ia_mul(x[0], y[1]), ia_mul(x[1], y[0]));
    c[2] = ia_add(ia_add(ia_mul(x[0], y[2]), ia_mul(x[1], y[1])), ia_mul(x[2], y[0]));
    c[3] = ia_add(ia_mul(x[1], y[2]), ia_mul(x[2], y[1]));
    c[4] = ia_mul(x[2], y[2]);
}
IA_FN void prim_quartic_sqr(const ia_interval x[3], ia_interval c[5]) {
    c[0] = ia_sqr(x[0]);
    c[1] = ia_mul_r(ia_mul(x[0], x[1]), 2);
    c[2] = ia_add(ia_sqr(x[1]), ia_mul_r(ia_mul(x[0], x[2]), 2));
    c[3] = ia_mul_r(ia_mul(x[1], x[2]), 2);
    c[4] = ia_sqr(x[2]);
}
/* (a + u b)^2 */
IA_FN void prim_quadratic_sqr(ia_interval a, ia_interval b, ia_interval x[3]) {
    x[0] = ia_sqr(a);
    x[1] = ia_mul_r(ia_mul(a, b), 2);
    x[2] = ia_sqr(b);
}

/* The Taylor coefficients of q at the point m: q(m + h) = sum d_k h^k (repeated synthetic division). */
IA_FN void prim_quartic_shift(const ia_interval c[5], ia_real m, ia_interval d[5]) {
    for (int k = 0; k < 5; k++)
        d[k] = c[k];
    for (int k = 0; k < 4; k++)
        for (int j = 3; j >= k; j--)
            d[j] = ia_add(d[j], ia_mul_r(d[j + 1], m));
}
IA_FN ia_interval prim_quartic_at(const ia_interval c[5], ia_real m) {
    ia_interval v = c[4];
    for (int j = 3; j >= 0; j--)
        v = ia_add(c[j], ia_mul_r(v, m));
    return v;
}

/* q's enclosure over m + h (h in [h.lo, h.hi]) from its Taylor coefficients d at m, and in *dq q' there. */
IA_FN ia_interval prim_quartic_taylor(const ia_interval d[5], ia_interval h, ia_interval *dq) {
    ia_interval h2 = ia_sqr(h);
    *dq = ia_add(ia_add(d[1], ia_mul(h2, ia_mul_r(d[3], 3))),
                 ia_mul(h, ia_add(ia_mul_r(d[2], 2), ia_mul(h2, ia_mul_r(d[4], 4)))));
    return ia_add(ia_add(d[0], ia_mul(h2, ia_add(d[2], ia_mul(h2, d[4])))), ia_mul(h, ia_add(d[1], ia_mul(h2, d[3]))));
}

/* The root of q in the u range [r0, r1] over which q' excludes 0 (rising: q' > 0), bracketed around a float
 * Newton's estimate x (the coefficients' midpoints, no rounding control): where q's enclosures at the two points
 * x -+ h have opposite strict signs in q's direction, the exact q has a root between them (it is continuous), the
 * node's only one (it is monotone there), and the exact q has the sign before the root on the node's part before
 * the first point, the other after the second. h starts at 2 ulps of t (ta: where u is 0), or where q's
 * enclosure's width at x over q's float slope there says q's sign shows, and doubles per try. 1 with the bracket
 * in [*a, *b]; 2 with *a = *b = r0 where q has its sign after the root at r0 (so all over the node: no root in
 * it), or = r1 where it has its sign before at r1; 0 where nothing is proven (coefficients too loose there), and
 * interval Newton narrows it. Two point evaluations a try, where a Newton step is a Taylor form's shift and
 * enclosure: truck's tori (11) were a fifth of its render. */
#define PRIM_QUARTIC_FLOAT_STEPS 8
#define PRIM_QUARTIC_BRACKET_TRIES 3
IA_FN int prim_quartic_bracket(const ia_interval c[5], ia_interval dq, ia_real ta, ia_real r0, ia_real r1, ia_real *a,
                               ia_real *b, kernel_u32 *evals) {
    int rising = dq.lo > 0;
    ia_real m[5], x = r0 * (ia_real)0.5 + r1 * (ia_real)0.5, df = 0;
    for (int k = 0; k < 5; k++)
        m[k] = c[k].lo * (ia_real)0.5 + c[k].hi * (ia_real)0.5;
    for (int it = 0; it < PRIM_QUARTIC_FLOAT_STEPS; it++) {
        ia_real f = m[4];
        df = 0;
        for (int j = 3; j >= 0; j--) {
            df = df * x + f;
            f = f * x + m[j];
        }
        ia_real step = f / df;
        if (!isfinite(step))
            break;
        x = fmin(fmax(x - step, r0), r1);
        if (fabs(step) <= (fabs(ta) + fabs(x)) * IA_REAL_EPS)
            break;
    }
    if (x == r0 || x == r1) { /* the root not in the node: all after it where q has that sign at r0, ... */
        ia_interval end = prim_quartic_at(c, x);
        int after = rising ? end.lo > 0 : end.hi < 0, before = rising ? end.hi < 0 : end.lo > 0;
        *evals += 1;
        if (x == r0 ? after : before) {
            *a = *b = x;
            return 2;
        }
    }
    ia_interval at = prim_quartic_at(c, x); /* |q| exceeds its enclosure's width about that far from the root */
    ia_real h = fmax((fabs(ta) + fabs(x)) * 2 * IA_REAL_EPS, (ia_real)0.625 * (at.hi - at.lo) / fabs(df));
    *evals += 1;
    if (!(h * 4 < r1 - r0)) /* no narrower than the node: the coefficients are too loose here */
        return 0;
    for (int tries = 0; tries < PRIM_QUARTIC_BRACKET_TRIES; tries++, h *= 2) {
        ia_real lo = fmax(x - h, r0), hi = fmin(x + h, r1);
        ia_interval before = prim_quartic_at(c, lo), after = prim_quartic_at(c, hi);
        *evals += 1;
        if (rising ? before.hi < 0 && after.lo > 0 : before.lo > 0 && after.hi < 0) {
            *a = lo;
            *b = hi;
            return 1;
        }
    }
    return 0;
}

/* A node [tlo, thi] (u range [r0, r1]) over which q' is dq, excluding 0: the root bracketed (prim_quartic_bracket)
 * or, where that fails, narrowed by Newton, each step with q' over the narrowed range where that excludes 0; the
 * node goes to the quartet as the part before the root, the root's BOUNDARY and the part after it. */
IA_FN void prim_quartic_newton(prim_quartet *q, const ia_interval c[5], ia_interval dq, ia_real ta, ia_real tlo,
                               ia_real thi, ia_real r0, ia_real r1, kernel_u32 *evals) {
    int before = dq.lo > 0 ? SCENE_IN : SCENE_OUT;
    ia_real u0 = r0, u1 = r1;
    int bracketed = prim_quartic_bracket(c, dq, ta, r0, r1, &r0, &r1, evals), none = bracketed == 2;
    for (int it = 0; it < PRIM_QUARTIC_NEWTON && !bracketed; it++) {
        ia_real m = r0 * (ia_real)0.5 + r1 * (ia_real)0.5;
        ia_interval d[5], slope;
        prim_quartic_shift(c, m, d);
        prim_quartic_taylor(d, ia_sub(ia_make(r0, r1), ia_point(m)), &slope);
        if ((slope.lo > 0 || slope.hi < 0) && isfinite(slope.lo) && isfinite(slope.hi))
            dq = slope;
        ia_interval n = ia_sub(ia_point(m), ia_div(d[0], dq));
        *evals += 1;
        ia_real n0 = fmax(r0, n.lo), n1 = fmin(r1, n.hi);
        if (!(n0 <= n1)) { /* none left: [r0, r1] is all before N or all after it */
            r0 = r1 = n.lo > r1 ? r1 : r0;
            none = 1;
            break;
        }
        int slow = n1 - n0 > (r1 - r0) * (ia_real)0.5;
        r0 = n0;
        r1 = n1;
        if (slow)
            break;
    }
    /* the root's BOUNDARY, in t; none where the node is all before or all after (its sign does not change) */
    ia_interval root = ia_add(ia_point(ta), ia_make(r0, r1));
    ia_real a = none && r1 >= u1 ? thi : none && r0 <= u0 ? tlo : fmin(fmax(root.lo, tlo), thi);
    ia_real b = none && r1 >= u1 ? thi : none && r0 <= u0 ? tlo : fmin(fmax(root.hi, tlo), thi);
    prim_quartet_add(q, tlo, a, before);
    prim_quartet_add(q, a, b, SCENE_BOUNDARY);
    prim_quartet_add(q, b, thi, SCENE_IN + SCENE_OUT - before);
}

/* Walks q (coefficients in u = t - ta) over [lo, hi] into the quartet, until its pattern is complete. */
IA_FN void prim_quartic_walk(prim_quartet *q, const ia_interval c[5], ia_real ta, ia_real lo, ia_real hi, ia_real eps,
                             kernel_u32 *evals) {
    ia_real w = ia_hi(hi - lo);
    int level = 0;
    bisect_index i = 0;
    for (;;) {
        ia_real tlo = node_bound(lo, w, level, i), thi = fmin(node_bound(lo, w, level, i + 1), hi);
        if (!(tlo < hi))
            return;
        ia_interval u = ia_sub(ia_make(tlo, thi), ia_point(ta)), d[5];
        ia_real m = u.lo * (ia_real)0.5 + u.hi * (ia_real)0.5;
        prim_quartic_shift(c, m, d);
        ia_interval dq, f = prim_quartic_taylor(d, ia_sub(u, ia_point(m)), &dq);
        *evals += 1;
        if (f.lo > 0 || f.hi < 0) {
            prim_quartet_add(q, tlo, thi, f.lo > 0 ? SCENE_OUT : SCENE_IN);
        } else {
            if ((dq.lo > 0 || dq.hi < 0) && isfinite(dq.lo) && isfinite(dq.hi)) {
                prim_quartic_newton(q, c, dq, ta, tlo, thi, u.lo, u.hi, evals);
            } else if (thi - tlo > eps && level < BISECT_MAX_LEVEL) {
                level += 1;
                i *= 2;
                continue;
            } else {
                prim_quartet_add(q, tlo, thi, SCENE_BOUNDARY);
            }
        }
        if (q->stage == 5 || !node_next(&level, &i))
            return;
    }
}

/* A sphere in the frame around the solid (centre (0, 0, z0), squared radius k), into the span of the solid's
 * bounds: it makes the range to solve finite when the walk solves again from some point to the end (prim_segments
 * with tend +inf). */
IA_FN int prim_quartic_sphere(prim_segments_span *s, const ia_interval a[3], const ia_interval b[3], ia_real z0,
                              ia_interval k, ia_real ta, ia_real width) {
    ia_interval az = ia_add_r(a[2], -z0);
    ia_interval aa = ia_add(ia_add(ia_sqr(a[0]), ia_sqr(a[1])), ia_sqr(az));
    ia_interval ab = ia_add(ia_add(ia_mul(a[0], b[0]), ia_mul(a[1], b[1])), ia_mul(az, b[2]));
    ia_interval bb = ia_add(ia_add(ia_sqr(b[0]), ia_sqr(b[1])), ia_sqr(b[2]));
    return prim_segments_quadric(s, bb, ab, ia_sub(aa, k), 0, ta, width);
}

/* The bounds of a torus or a general tgc from s = a + u b along the ray (a at ta, b = G d): the tgc's slab into s,
 * a sphere around the solid and a torus's slab into `bound` (they clip the range, and nothing is in outside them).
 * 1 where the ray may meet the solid within [ta, ta + width], 2 where the bounds leave nothing to solve, 0 where
 * there is no closed form (a torus whose tube reaches its axis: its quartic is negative in a spindle too). */
IA_FN int prim_quartic_bounds(int type, const ia_real *p, const ia_interval a[3], const ia_interval b[3],
                              prim_segments_span *s, prim_segments_span *bound, ia_real ta, ia_real width) {
    ia_interval range = ia_make(0, width);
    if (type == PRIM_TOR) {
        ia_interval r2 = ia_sqr(prim_iv(p, 12)), rh2 = prim_iv(p, 13);
        if (!(r2.lo > rh2.hi) || !(rh2.lo >= 0))
            return 0;
        ia_interval rh = ia_sqrt(rh2);
        prim_segments_plane(bound, ia_sub(a[2], rh), b[2], ta, range);
        prim_segments_plane(bound, ia_neg(ia_add(a[2], rh)), ia_neg(b[2]), ta, range);
        if (!prim_quartic_sphere(bound, a, b, 0, ia_sqr(ia_add(prim_iv(p, 12), rh)), ta, width))
            return 0;
    } else {
        ia_interval alpha = prim_iv(p, 12), beta = prim_iv(p, 13);
        ia_interval reach = ia_add(ia_sqr(ia_add_r(ia_max(alpha, ia_point(0)), 1)),
                                   ia_sqr(ia_add_r(ia_max(beta, ia_point(0)), 1)));
        prim_segments_plane(s, ia_neg(a[2]), ia_neg(b[2]), ta, range);
        prim_segments_plane(s, ia_add_r(a[2], -1), b[2], ta, range);
        if (!prim_quartic_sphere(bound, a, b, (ia_real)0.5, ia_add_r(reach, (ia_real)0.25), ta, width))
            return 0;
    }
    return fmax(fmax(s->plo, bound->plo), ta) < fmin(fmin(s->phi, bound->phi), ta + width) ? 1 : 2;
}

/* The quartic's coefficients in u = t - tm from s = a + u b (a at tm). The walk takes them from tm in the middle
 * of the range it solves: expanded from the range's start, or farther, the coefficients' rounding, times powers of
 * u, hid the quartic's sign over a long stretch of a ray that passes near the surface (a BOUNDARY 0.1 long in f32
 * where 0.0006 was asked for, on a ray that meets the solid nowhere). */
IA_FN void prim_quartic_coefficients(int type, const ia_real *p, const ia_interval a[3], const ia_interval b[3],
                                     ia_interval c[5]) {
    ia_interval x[3], y[3], z[3];
    if (type == PRIM_TOR) { /* (|s|^2 + R^2 - r^2)^2 - 4 R^2 (s0^2 + s1^2): negative inside where r < R */
        ia_interval r2 = ia_sqr(prim_iv(p, 12)), rh2 = prim_iv(p, 13), sum[3];
        prim_quadratic_sqr(a[0], b[0], x);
        prim_quadratic_sqr(a[1], b[1], y);
        prim_quadratic_sqr(a[2], b[2], z);
        for (int k = 0; k < 3; k++) {
            x[k] = ia_add(x[k], y[k]); /* s0^2 + s1^2 */
            sum[k] = ia_add(x[k], z[k]);
        }
        sum[0] = ia_add(sum[0], ia_sub(r2, rh2));
        prim_quartic_sqr(sum, c);
        for (int k = 0; k < 3; k++)
            c[k] = ia_sub(c[k], ia_mul(ia_mul_r(r2, 4), x[k]));
        return;
    }
    /* u^2 rb^2 + v^2 ra^2 - ra^2 rb^2 (ra = 1 + alpha w, rb = 1 + beta w) on the slab 0 <= w <= 1: negative exactly
     * where u^2 / ra^2 + v^2 / rb^2 < 1 (it depends on ra and rb through their squares) */
    ia_interval alpha = prim_iv(p, 12), beta = prim_iv(p, 13), ra[3], rb[3], t[5];
    prim_quadratic_sqr(ia_add_r(ia_mul(alpha, a[2]), 1), ia_mul(alpha, b[2]), ra);
    prim_quadratic_sqr(ia_add_r(ia_mul(beta, a[2]), 1), ia_mul(beta, b[2]), rb);
    prim_quadratic_sqr(a[0], b[0], x);
    prim_quadratic_sqr(a[1], b[1], y);
    for (int k = 0; k < 3; k++)
        y[k] = ia_sub(y[k], rb[k]);
    prim_quartic_mul(x, rb, c);
    prim_quartic_mul(ra, y, t);
    for (int k = 0; k < 5; k++)
        c[k] = ia_add(c[k], t[k]);
}

/* Walks the quartic of a torus or a general tgc (`type`, its radii or alpha and beta in coef_p) over [lo, hi] into
 * q: its coefficients from the ray o + t d in the frame of frame_p's parameters from `at` (prim_frame), b the
 * direction's part there, taken at the middle of [lo, hi]. 0 where they are not finite (the walk bisects). */
IA_FN int prim_quartic_solve(prim_quartet *q, int type, const ia_real *coef_p, const ia_real *frame_p, int at,
                             const ia_real o[3], const ia_real d[3], const ia_interval b[3], ia_real lo, ia_real hi,
                             ia_real eps, kernel_u32 *evals) {
    ia_real tm = lo * (ia_real)0.5 + hi * (ia_real)0.5;
    ia_interval mid = ia_point(tm), a[3], c[5];
    prim_frame(frame_p, at, ray_extent(o[0], d[0], mid), ray_extent(o[1], d[1], mid), ray_extent(o[2], d[2], mid), a);
    prim_quartic_coefficients(type, coef_p, a, b, c);
    for (int k = 0; k < 5; k++)
        if (!isfinite(c[k].lo) || !isfinite(c[k].hi))
            return 0;
    prim_quartic_walk(q, c, tm, lo, hi, eps, evals);
    return 1;
}

/* A pipe's (prim_pipe_segments.h, after this file: it solves its parts with the forms above). */
IA_FN int prim_pipe_segments(const ia_real *p, const ia_real o[3], const ia_real d[3], ia_real ta, ia_real tend,
                             ia_real eps, ia_real e[4], ia_real *resume, kernel_u32 *evals);

/* The solid's changes along o + t d over [ta, tend] (see the top), adding its evaluations to *evals: 1 with
 * e[0..3] (OUT after e3), 2 with e[0..3] where the solid may be in again after e3 (a torus's or a general tgc's
 * second run: solve again from e3), or 0 where the walk must bisect. dir: the solid's direction terms
 * (prim_dirs), taken from it where `known`, else written there for every type but a pipe; or 0. */
IA_FN int prim_segments(int type, const ia_real *p, const ia_real o[3], const ia_real d[3], ia_real ta, ia_real tend,
                        ia_real eps, ia_real e[4], ia_real *resume, kernel_u32 *evals, ia_interval *dir, int known) {
    prim_segments_span s = {-IA_INF, IA_INF, -IA_INF, IA_INF, 0}, bound = s;
    ia_interval b[3]; /* the direction's part in a frame type's frame */
    int quartic = 0;
    if (type == PRIM_PIPE)
        return prim_pipe_segments(p, o, d, ta, tend, eps, e, resume, evals);
    if (type == PRIM_HALF || type == PRIM_ARB8) { /* n.o - d + t n.d: from the ray's origin, an exact point */
        for (int j = 0; j < (type == PRIM_HALF ? 1 : PRIM_ARB_PLANES); j++)
            prim_segments_plane(&s, ia_sub(prim_segments_dot(p + 8 * j, 0, o), prim_iv(p + 8 * j, 3)),
                                prim_segments_dir(p + 8 * j, 0, d, dir, known, j), 0, ia_make(ta, tend));
    } else if (type == PRIM_ELL || type == PRIM_TGC || type == PRIM_EHY || type == PRIM_TOR) {
        ia_interval at = ia_point(ta), a[3];
        prim_frame(p, 0, ray_extent(o[0], d[0], at), ray_extent(o[1], d[1], at), ray_extent(o[2], d[2], at), a);
        for (int r = 0; r < 3; r++)
            b[r] = prim_segments_dir(p, 3 + 3 * r, d, dir, known, r);
        ia_real width = ia_hi(tend - ta);
        ia_interval gamma = type == PRIM_TGC ? ia_hull(prim_iv(p, 12), prim_iv(p, 13)) : ia_point(0);
        quartic = type == PRIM_TOR || !(gamma.hi - gamma.lo <= PRIM_SEGMENTS_SKEW);
        int of = quartic ? prim_quartic_bounds(type, p, a, b, &s, &bound, ta, width)
                         : prim_segments_frame(type, p, a, b, &s, ta, width);
        if (of == 0)
            return 0;
        if (quartic && of == 2) { /* the bounds say out all along */
            *evals += 1;
            e[0] = e[1] = e[2] = e[3] = ta;
            return 1;
        }
    } else {
        return 0;
    }
    if (s.nan || bound.nan)
        return 0;
    if (!quartic)
        return prim_segments_convex(&s, ta, tend, e, evals);
    ia_real plo = fmax(fmax(s.plo, bound.plo), ta), phi = fmin(fmin(s.phi, bound.phi), tend);
    if (!(plo < phi)) { /* out all along */
        *evals += 1;
        e[0] = e[1] = e[2] = e[3] = ta;
        return 1;
    }
    prim_quartet q = {{phi, phi, phi, phi}, 0, phi, s.ilo, s.ihi};
    if (!prim_quartic_solve(&q, type, p, p, 0, o, d, b, plo, phi, eps, evals))
        return 0;
    for (int k = 0; k < 4; k++)
        e[k] = q.e[k];
    *resume = q.resume;
    return q.stage == 5 ? 2 : 1;
}

/* Whether no ray o + t d with o and d in the boxes `o` and `d` (a packet's beam, bvh.h) meets the solid for t in
 * [ta, tend]: 1 only where that is proven, by the forms above over intervals of rays (every bound they give holds
 * the crossings of every ray of the beam: the same inclusion functions, with o and d intervals instead of points).
 * Ells, the tgcs that are quadrics and ehys; for the others 0 (not proven: an arb's box is mostly tight, so its
 * planes over a beam paid less than they cost, truck's evaluations a ray 0.51 -> 0.50). */
IA_FN int prim_segments_beam_out(int type, const ia_real *p, const ia_interval o[3], const ia_interval d[3], ia_real ta,
                                 ia_real tend) {
    prim_segments_span s = {-IA_INF, IA_INF, -IA_INF, IA_INF, 0};
    if (type == PRIM_ELL || type == PRIM_TGC || type == PRIM_EHY) {
        ia_interval at = ia_point(ta), a[3], b[3], x[3];
        for (int c = 0; c < 3; c++)
            x[c] = ia_add(o[c], ia_mul(d[c], at));
        prim_frame(p, 0, x[0], x[1], x[2], a);
        for (int r = 0; r < 3; r++)
            b[r] = prim_dot3(p, 3 + 3 * r, d[0], d[1], d[2]);
        if (!prim_segments_frame(type, p, a, b, &s, ta, ia_hi(tend - ta)))
            return 0;
    } else {
        return 0;
    }
    return !s.nan && !(fmax(s.plo, ta) < fmin(s.phi, tend));
}

#include "prim_pipe_segments.h"

#endif
