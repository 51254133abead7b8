/* kernels/prim.h -- BRL-CAD's primitive solids as inclusion functions: for each type the interval enclosure F of an
 * implicit f (f < 0 inside) over a box, f and its gradient at a point (the normal), and Fd, F with the derivative
 * along a ray's direction (the walks' interval Newton). Written in the subset of C11 and OpenCL C of ia/, so the
 * host tests run the device's code. The scene program calls them out of line (prim_F, prim_f_grad, prim_Fd, one
 * copy per program), with a solid's parameters copied from the scene's table of primitives (kernels/scene_prims.h,
 * a device buffer): a primitive costs its scene's program nothing, whatever the model.
 *
 *   implicits/prim_place.c: database parameters and matrix --> world parameters as intervals (outward) -->
 *   implicits/scene_prims.c: the table, reals of the program's precision --> scene_solid_P's copy --> prim_F here
 *
 * Parameters. p holds intervals as lo, hi pairs (prim_iv), each holding the exact real number the placement
 * defines from the database's numbers, so F over a box holds f of the primitive exactly as the database defines
 * it at every point of the box. ELL, TGC, TOR and EHY work in a frame: s = G (x - P), P the primitive's world
 * origin, G a 3x3 matrix (rows), intervals 0-2 and 3-11. For ell and tgc G encloses the exact inverse of the map
 * from the canonical shape to the world (a verified inverse, prim_place.c), so any affine matrix places them as
 * librt does; a torus's G is an orthonormal frame around its placed axis and an ehy's ehy.c's S R times the
 * matrix's inverse (librt takes their matrices for rotations and uniform scales).
 *
 * The implicits, and why each is tight (F's overestimate shrinks with the box, so bisection converges, and no
 * f is 0 except on the surface: a zero elsewhere would be split down to BOUNDARY leaves, which the weave may claim):
 *   HALF  n.x - d (n, d: 4 intervals). Linear: each coordinate occurs once, F is exact up to rounding.
 *   ARB8  max over its faces of n_i.x - d_i, n_i outward, d_i = n_i.a_i for a vertex a_i of face i (6 planes, 24
 *         intervals; a degenerate arb repeats a plane). The faces are BRL-CAD's (rt_arb_info: the first three distinct,
 *         non-collinear vertices in its order; vertices within BRL-CAD's 0.0005 mm merged), so the solid is the
 *         intersection of the faces' half-spaces, within the box of the vertices (the BVH's range clips it
 *         there, which only matters for a non-planar face). Each plane is linear: exact up to rounding.
 *   ELL   |s|^2 - 1, s in the frame of V and the semi-axes (12 intervals): a sum of squares of linear forms.
 *   TGC   max(-w, w - 1, u^2 / ra^2 + v^2 / rb^2 - 1), (u, v, w) = s in the frame of V, A, B, H; ra = 1 + alpha w,
 *         rb = 1 + beta w (alpha = |C| / |A| - 1, beta = |D| / |B| - 1; 14 intervals): the ellipse at height w
 *         scaled to the unit circle. The quotients make f = +inf, never 0, on the plane of a cone's apex (ra or rb
 *         0), where the product form u^2 rb^2 + v^2 ra^2 - ra^2 rb^2 is 0 all over the plane.
 *   TOR   (sqrt(s1^2 + s2^2) - r_a)^2 + s3^2 - r_h^2, s in an orthonormal frame with the axis third (r_a, r_h^2;
 *         14 intervals): the squared distance to the core circle, each part occurring once (the quartic's two
 *         occurrences of s1^2 + s2^2 would double its width).
 *   EHY   max(z, -1 - z, k1 (x^2 + y^2 - 1) - (z + k2)^2 + k2^2), (x, y, z) = s = BRL-CAD's S R (p - V) (z from 0 at
 *         the base to -1 at the tip), k1 = 2 c' + 1, k2 = c' + 1, c' = c / |H| (ehy.c's quadric, rearranged so that
 *         z occurs once; 15 intervals). Over -1 <= z <= 0 it is 0 only on the sheet.
 *   PIPE  librt's parts (pipe.c): straight frusta between the points and torus bends at them, each in its cell
 *         between two planes (PRIM_PIPE_PART_N intervals a part, the last three its box, which prim_pipe_F tests
 *         first: a pipe of many parts costs its walk little away from them). f is the tube of a part whose
 *         cell holds x (a frustum's max(rho - ro(w), ri(w) - rho), a bend's max(d - ro, ri - d), d the distance
 *         from its core circle), +inf where none does. A union of closed parts that abut would be 0 all over the
 *         faces where they meet, inside the wall; here a box across a plane two consecutive parts share is in
 *         their union and gets the hull of both tubes, negative there (prim_pipe_F).
 *
 * Fd: the derivative along the ray from the same parts (a frame type's from s and G d; a max's by ia_dmax, Clarke's
 * derivative, for which the mean value theorem Newton relies on still holds); unbounded where a quotient's
 * denominator may be 0 and for pipes, whose f jumps at the end caps: the walk then bisects.
 */
#ifndef KERNELS_PRIM_H
#define KERNELS_PRIM_H
#include "../ia/ia.h"

/* The types, as implicits/scene.h numbers them (SCENE_PRIM_*; prim_place.c checks). */
#define PRIM_HALF 0
#define PRIM_ARB8 1
#define PRIM_ELL 2
#define PRIM_TGC 3
#define PRIM_TOR 4
#define PRIM_EHY 5
#define PRIM_PIPE 6

#define PRIM_ARB_PLANES 6
/* The number of intervals of each type's parameters (a pipe's depend on its parts). */
#define PRIM_HALF_N 4
#define PRIM_ARB8_N (4 * PRIM_ARB_PLANES)
#define PRIM_ELL_N 12
#define PRIM_TGC_N 14
#define PRIM_TOR_N 14
#define PRIM_EHY_N 15
/* A pipe: its number of parts, then per part PRIM_PIPE_PART_N intervals (see prim_pipe_F). */
#define PRIM_PIPE_PART_N 32
#define PRIM_PIPE_LINEAR 0
#define PRIM_PIPE_BEND 1
#define PRIM_PIPE_SHARES_START 2 /* its start plane is the previous part's end plane */
#define PRIM_PIPE_INNER 4        /* it has a bore */

/* The small helpers below are inlined on the device, where LLVM left prim_dot3 a call (its interval result through
 * memory) inside the large prim_F: 14 % of goliath's render went to the call (its pipes' bisection). */
#if IA_DEVICE
#define PRIM_INLINE IA_FN __attribute__((always_inline))
#else
#define PRIM_INLINE IA_FN
#endif

/* The k-th interval of p, and its midpoint (the point code's parameter). */
PRIM_INLINE ia_interval prim_iv(const ia_real *p, int k) { return ia_make(p[2 * k], p[2 * k + 1]); }
IA_FN ia_real prim_mid(const ia_real *p, int k) { return p[2 * k] * (ia_real)0.5 + p[2 * k + 1] * (ia_real)0.5; }

/* a.b + c (three terms of a dot product, the third given). */
PRIM_INLINE ia_interval prim_dot3(const ia_real *p, int k, ia_interval x, ia_interval y, ia_interval z) {
    return ia_add(ia_add(ia_mul(prim_iv(p, k), x), ia_mul(prim_iv(p, k + 1), y)), ia_mul(prim_iv(p, k + 2), z));
}

/* s = G (x - P) over a box: P at interval `at`, G's rows after it. */
IA_FN void prim_frame(const ia_real *p, int at, ia_interval x, ia_interval y, ia_interval z, ia_interval s[3]) {
    ia_interval qx = ia_sub(x, prim_iv(p, at)), qy = ia_sub(y, prim_iv(p, at + 1)), qz = ia_sub(z, prim_iv(p, at + 2));
    for (int r = 0; r < 3; r++)
        s[r] = prim_dot3(p, at + 3 + 3 * r, qx, qy, qz);
}

/* The same at a point (midpoints of the parameters), and G^T g: a gradient in s back to the world. */
IA_FN void prim_frame_point(const ia_real *p, int at, ia_real x, ia_real y, ia_real z, ia_real s[3]) {
    ia_real q[3] = {x - prim_mid(p, at), y - prim_mid(p, at + 1), z - prim_mid(p, at + 2)};
    for (int r = 0; r < 3; r++)
        s[r] = prim_mid(p, at + 3 + 3 * r) * q[0] + prim_mid(p, at + 4 + 3 * r) * q[1] +
               prim_mid(p, at + 5 + 3 * r) * q[2];
}
IA_FN void prim_frame_back(const ia_real *p, int at, const ia_real g[3], ia_real *gx, ia_real *gy, ia_real *gz) {
    ia_real out[3];
    for (int c = 0; c < 3; c++)
        out[c] = prim_mid(p, at + 3 + c) * g[0] + prim_mid(p, at + 6 + c) * g[1] + prim_mid(p, at + 9 + c) * g[2];
    *gx = out[0];
    *gy = out[1];
    *gz = out[2];
}

/* num / den for den >= 0 (a square), +inf where den is 0 and num > 0 (a cone's apex plane: outside); where both
 * may be 0 (the apex itself) anything from 0 up. */
IA_FN ia_interval prim_ratio(ia_interval num, ia_interval den) {
    if (den.hi <= 0)
        return ia_make(num.lo > 0 ? IA_REAL_MAX : (ia_real)0, IA_INF);
    return ia_div(num, ia_make(fmax(den.lo, (ia_real)0), den.hi));
}

/* ---- the enclosures over a box */

IA_FN ia_interval prim_half_F(const ia_real *p, ia_interval x, ia_interval y, ia_interval z) {
    return ia_sub(prim_dot3(p, 0, x, y, z), prim_iv(p, 3));
}

IA_FN ia_interval prim_arb8_F(const ia_real *p, ia_interval x, ia_interval y, ia_interval z) {
    ia_interval f = ia_make(-IA_INF, -IA_INF);
    for (int j = 0; j < PRIM_ARB_PLANES; j++)
        f = ia_max(f, prim_half_F(p + 8 * j, x, y, z));
    return f;
}

/* ds = G d: the direction (dx, dy, dz) in the frame at `at`. */
IA_FN void prim_frame_dir(const ia_real *p, int at, ia_interval dx, ia_interval dy, ia_interval dz, ia_interval ds[3]) {
    for (int r = 0; r < 3; r++)
        ds[r] = prim_dot3(p, at + 3 + 3 * r, dx, dy, dz);
}

/* A frame type's f over the box from its s, and when dt is not NULL, in *dt f's derivative along a direction whose
 * frame coordinates are ds (unbounded where a quotient's denominator may be 0: interval Newton then bisects). A max
 * differentiates as Clarke's derivative (ia_dmax), for which the mean value theorem Newton needs still holds. */
IA_FN ia_interval prim_frame_value(int type, const ia_real *p, const ia_interval s[3], const ia_interval ds[3],
                                   ia_interval *dt) {
    ia_interval f = ia_entire(), d = ia_entire();
    ia_interval s01 = ia_add(ia_sqr(s[0]), ia_sqr(s[1]));
    ia_interval ds01 = dt ? ia_mul_r(ia_add(ia_mul(s[0], ds[0]), ia_mul(s[1], ds[1])), 2) : d; /* (s0^2 + s1^2)' */
    if (type == PRIM_ELL) {
        f = ia_add_r(ia_add(s01, ia_sqr(s[2])), -1);
        if (dt)
            d = ia_add(ds01, ia_mul_r(ia_mul(s[2], ds[2]), 2));
    } else if (type == PRIM_TGC) {
        ia_interval alpha = prim_iv(p, 12), beta = prim_iv(p, 13);
        ia_interval ra = ia_add_r(ia_mul(alpha, s[2]), 1), rb = ia_add_r(ia_mul(beta, s[2]), 1);
        ia_interval u2 = ia_sqr(s[0]), v2 = ia_sqr(s[1]);
        ia_interval side = ia_add_r(ia_add(prim_ratio(u2, ia_sqr(ra)), prim_ratio(v2, ia_sqr(rb))), -1);
        ia_interval below = ia_neg(s[2]), above = ia_add_r(s[2], -1), cap = ia_max(below, above);
        f = ia_max(cap, side);
        if (dt) { /* (u^2 / ra^2)' = 2 (u u' ra - u^2 alpha w') / ra^3 */
            ia_interval du = ia_div(
                ia_mul_r(ia_sub(ia_mul(ia_mul(s[0], ds[0]), ra), ia_mul(ia_mul(u2, alpha), ds[2])), 2), ia_pown(ra, 3));
            ia_interval dv = ia_div(
                ia_mul_r(ia_sub(ia_mul(ia_mul(s[1], ds[1]), rb), ia_mul(ia_mul(v2, beta), ds[2])), 2), ia_pown(rb, 3));
            d = ia_dmax(cap, side, ia_dmax(below, above, ia_neg(ds[2]), ds[2]), ia_add(du, dv));
        }
    } else if (type == PRIM_TOR) {
        ia_interval rho = ia_sqrt(s01), off = ia_sub(rho, prim_iv(p, 12));
        f = ia_sub(ia_add(ia_sqr(off), ia_sqr(s[2])), prim_iv(p, 13));
        if (dt) /* rho' = (s0^2 + s1^2)' / (2 rho) */
            d = ia_add(ia_div(ia_mul(off, ds01), rho), ia_mul_r(ia_mul(s[2], ds[2]), 2));
    } else if (type == PRIM_EHY) {
        ia_interval k1 = prim_iv(p, 12), k2 = prim_iv(p, 13), zk = ia_add(s[2], k2);
        ia_interval sheet = ia_add(ia_sub(ia_mul(k1, ia_add_r(s01, -1)), ia_sqr(zk)), prim_iv(p, 14));
        ia_interval below = ia_sub(ia_make(-1, -1), s[2]), cap = ia_max(s[2], below);
        f = ia_max(cap, sheet);
        if (dt)
            d = ia_dmax(cap, sheet, ia_dmax(s[2], below, ds[2], ia_neg(ds[2])),
                        ia_sub(ia_mul(k1, ds01), ia_mul_r(ia_mul(zk, ds[2]), 2)));
    }
    if (dt)
        *dt = d;
    return f;
}

/* A pipe part's cell: the start plane (x - a).t >= 0 and the end plane (x - b).u <= 0, and its tube over the box:
 * a frustum's max(rho - ro(w), ri(w) - rho) (rho the distance from the axis, w the length along it), a bend's
 * max(d - ro, ri - d) (d the distance from the bend's core circle, rho as a torus's). */
IA_FN ia_interval prim_pipe_plane(const ia_real *q, int at, ia_interval x, ia_interval y, ia_interval z) {
    return prim_dot3(q, at + 3, ia_sub(x, prim_iv(q, at)), ia_sub(y, prim_iv(q, at + 1)),
                     ia_sub(z, prim_iv(q, at + 2)));
}

IA_FN ia_interval prim_pipe_tube(const ia_real *q, int flags, ia_interval x, ia_interval y, ia_interval z) {
    ia_interval s[3];
    prim_frame(q, 13, x, y, z, s);
    ia_interval rho = ia_sqrt(ia_add(ia_sqr(s[0]), ia_sqr(s[1]))), outer, inner;
    if (flags & PRIM_PIPE_BEND) {
        ia_interval d = ia_sqrt(ia_add(ia_sqr(ia_sub(rho, prim_iv(q, 25))), ia_sqr(s[2])));
        outer = ia_sub(d, prim_iv(q, 26));
        inner = ia_sub(prim_iv(q, 27), d);
    } else {
        outer = ia_sub(rho, ia_add(prim_iv(q, 25), ia_mul(prim_iv(q, 26), s[2])));
        inner = ia_sub(ia_add(prim_iv(q, 27), ia_mul(prim_iv(q, 28), s[2])), rho);
    }
    return flags & PRIM_PIPE_INNER ? ia_max(outer, inner) : outer;
}

/* Whether the box (x, y, z) misses the part's box (intervals 29-31). A part whose box it misses is left out of the
 * min: its tube is positive all over the box, so where only its cell holds x, f becomes +inf instead of a positive
 * value (the same sign), and where another part holds x too, the min keeps its sign. */
PRIM_INLINE int prim_pipe_apart(const ia_real *q, ia_interval x, ia_interval y, ia_interval z) {
    return x.hi < q[58] || x.lo > q[59] || y.hi < q[60] || y.lo > q[61] || z.hi < q[62] || z.lo > q[63];
}

/* The pipe: f = min over its parts of the tube where x is in the part's (closed) cell, +inf in none. A box that
 * is partly in a cell gives [F.lo, +inf] (f may be +inf there); one that lies across the plane that two
 * consecutive parts share and is otherwise in both cells is all in their union, where f is within the hull of
 * both tubes: so the joints inside the wall, where f is negative on both sides, are proven inside, not split down
 * to BOUNDARY leaves (a union of closed parts that abut has f = 0 all over the shared face). */
IA_FN ia_interval prim_pipe_F(const ia_real *p, ia_interval x, ia_interval y, ia_interval z) {
    int parts = (int)p[0];
    ia_real lo = IA_INF, hi = IA_INF;
    ia_interval before = ia_empty(); /* the previous part's tube, when the box is in its cell but for its end */
    for (int k = 0; k < parts; k++) {
        const ia_real *q = p + 2 + 2 * PRIM_PIPE_PART_N * k;
        int flags = (int)q[0];
        if (prim_pipe_apart(q, x, y, z)) { /* outside the part's box: outside it, and f > 0 there (see above) */
            before = ia_empty();
            continue;
        }
        ia_interval a = prim_pipe_plane(q, 1, x, y, z), b = prim_pipe_plane(q, 7, x, y, z);
        if (a.hi < 0 || b.lo > 0) {
            before = ia_empty();
            continue;
        }
        ia_interval tube = prim_pipe_tube(q, flags, x, y, z);
        int start_in = a.lo >= 0, end_in = b.hi <= 0;
        ia_interval part = start_in && end_in ? tube : ia_make(tube.lo, IA_INF);
        if (!start_in && end_in && (flags & PRIM_PIPE_SHARES_START) && !ia_is_empty(before))
            part = ia_hull(tube, before);
        lo = fmin(lo, part.lo);
        hi = fmin(hi, part.hi);
        before = start_in && !end_in ? tube : ia_empty();
    }
    return ia_make(lo, hi);
}

/* ---- f and its gradient at a point. Where f is a max, the gradient of the largest part (of a face, of a cap). */

IA_FN ia_real prim_half_grad(const ia_real *p, ia_real x, ia_real y, ia_real z, ia_real g[3]) {
    for (int c = 0; c < 3; c++)
        g[c] = prim_mid(p, c);
    return g[0] * x + g[1] * y + g[2] * z - prim_mid(p, 3);
}

IA_FN ia_real prim_arb8_grad(const ia_real *p, ia_real x, ia_real y, ia_real z, ia_real g[3]) {
    ia_real best = -IA_INF;
    for (int j = 0; j < PRIM_ARB_PLANES; j++) {
        ia_real n[3], f = prim_half_grad(p + 8 * j, x, y, z, n);
        if (f > best) {
            best = f;
            for (int c = 0; c < 3; c++)
                g[c] = n[c];
        }
    }
    return best;
}

/* A pipe at a point: min over the parts of max(tube, the cell's planes) (closed parts; the planes give the end
 * caps' normals), the gradient of the part and term that give it. */
IA_FN ia_real prim_pipe_grad(const ia_real *p, ia_real x, ia_real y, ia_real z, ia_real g[3]) {
    int parts = (int)prim_mid(p, 0);
    ia_real best = IA_INF;
    for (int k = 0; k < parts; k++) {
        const ia_real *q = p + 2 + 2 * PRIM_PIPE_PART_N * k;
        int flags = (int)q[0];
        ia_real s[3], gs[3] = {0, 0, 0}, pos[3] = {x, y, z}, a = 0, b = 0, f;
        for (int c = 0; c < 3; c++) {
            a -= (pos[c] - prim_mid(q, 1 + c)) * prim_mid(q, 4 + c);
            b += (pos[c] - prim_mid(q, 7 + c)) * prim_mid(q, 10 + c);
        }
        prim_frame_point(q, 13, x, y, z, s);
        ia_real rho = sqrt(s[0] * s[0] + s[1] * s[1]);
        if (flags & PRIM_PIPE_BEND) {
            ia_real d = sqrt((rho - prim_mid(q, 25)) * (rho - prim_mid(q, 25)) + s[2] * s[2]);
            ia_real k_rho = d > 0 && rho > 0 ? (rho - prim_mid(q, 25)) / (d * rho) : 0;
            gs[0] = k_rho * s[0];
            gs[1] = k_rho * s[1];
            gs[2] = d > 0 ? s[2] / d : 0;
            f = d - prim_mid(q, 26);
            if ((flags & PRIM_PIPE_INNER) && prim_mid(q, 27) - d > f) {
                f = prim_mid(q, 27) - d;
                for (int c = 0; c < 3; c++)
                    gs[c] = -gs[c];
            }
        } else {
            ia_real out_w = prim_mid(q, 26), in_w = prim_mid(q, 28);
            gs[0] = rho > 0 ? s[0] / rho : 0;
            gs[1] = rho > 0 ? s[1] / rho : 0;
            gs[2] = -out_w;
            f = rho - prim_mid(q, 25) - out_w * s[2];
            ia_real inner = prim_mid(q, 27) + in_w * s[2] - rho;
            if ((flags & PRIM_PIPE_INNER) && inner > f) {
                f = inner;
                gs[0] = -gs[0];
                gs[1] = -gs[1];
                gs[2] = in_w;
            }
        }
        ia_real gw[3];
        prim_frame_back(q, 13, gs, &gw[0], &gw[1], &gw[2]);
        if (a > f || b > f) { /* beyond an end cap */
            int end = b > a;
            f = end ? b : a;
            for (int c = 0; c < 3; c++)
                gw[c] = end ? prim_mid(q, 10 + c) : -prim_mid(q, 4 + c);
        }
        if (f < best) {
            best = f;
            for (int c = 0; c < 3; c++)
                g[c] = gw[c];
        }
    }
    return best;
}

/* A frame type's f and gradient in s, given s. */
IA_FN ia_real prim_ell_grad_s(const ia_real *p, const ia_real s[3], ia_real g[3]) {
    (void)p;
    for (int c = 0; c < 3; c++)
        g[c] = 2 * s[c];
    return s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - 1;
}

IA_FN ia_real prim_tgc_grad_s(const ia_real *p, const ia_real s[3], ia_real g[3]) {
    ia_real alpha = prim_mid(p, 12), beta = prim_mid(p, 13);
    ia_real ra = 1 + alpha * s[2], rb = 1 + beta * s[2];
    ia_real u = s[0] / ra, v = s[1] / rb, side = u * u + v * v - 1;
    g[0] = g[1] = 0;
    g[2] = s[2] < (ia_real)0.5 ? -1 : 1;
    ia_real cap = fmax(-s[2], s[2] - 1);
    if (side >= cap) {
        g[0] = 2 * u / ra;
        g[1] = 2 * v / rb;
        g[2] = -2 * (u * u * alpha / ra + v * v * beta / rb);
        return side;
    }
    return cap;
}

IA_FN ia_real prim_tor_grad_s(const ia_real *p, const ia_real s[3], ia_real g[3]) {
    ia_real rho = sqrt(s[0] * s[0] + s[1] * s[1]), ra = prim_mid(p, 12);
    ia_real k = rho > 0 ? 2 * (rho - ra) / rho : 0;
    g[0] = k * s[0];
    g[1] = k * s[1];
    g[2] = 2 * s[2];
    return (rho - ra) * (rho - ra) + s[2] * s[2] - prim_mid(p, 13);
}

IA_FN ia_real prim_ehy_grad_s(const ia_real *p, const ia_real s[3], ia_real g[3]) {
    ia_real k1 = prim_mid(p, 12), k2 = prim_mid(p, 13);
    ia_real sheet = k1 * (s[0] * s[0] + s[1] * s[1] - 1) - (s[2] + k2) * (s[2] + k2) + k2 * k2;
    ia_real cap = fmax(s[2], -1 - s[2]);
    g[0] = g[1] = 0;
    g[2] = s[2] > (ia_real)-0.5 ? 1 : -1;
    if (sheet >= cap) {
        g[0] = 2 * k1 * s[0];
        g[1] = 2 * k1 * s[1];
        g[2] = -2 * (s[2] + k2);
        return sheet;
    }
    return cap;
}

/* ---- the entry points, out of line: one copy per program, which each solid calls with its parameters. */

#if IA_DEVICE
#define PRIM_FN __attribute__((noinline))
#else
#define PRIM_FN IA_FN
#endif

PRIM_FN ia_interval prim_F(int type, const ia_real *p, ia_interval x, ia_interval y, ia_interval z) {
    switch (type) {
    case PRIM_HALF:
        return prim_half_F(p, x, y, z);
    case PRIM_ARB8:
        return prim_arb8_F(p, x, y, z);
    case PRIM_PIPE:
        return prim_pipe_F(p, x, y, z);
    }
    ia_interval s[3];
    prim_frame(p, 0, x, y, z, s);
    return prim_frame_value(type, p, s, s, 0);
}

PRIM_FN ia_real prim_f_grad(int type, const ia_real *p, ia_real x, ia_real y, ia_real z, ia_real *gx, ia_real *gy,
                            ia_real *gz) {
    ia_real g[3] = {0, 0, 0}, s[3], f = 0;
    if (type == PRIM_HALF || type == PRIM_ARB8 || type == PRIM_PIPE) {
        f = type == PRIM_HALF   ? prim_half_grad(p, x, y, z, g)
            : type == PRIM_ARB8 ? prim_arb8_grad(p, x, y, z, g)
                                : prim_pipe_grad(p, x, y, z, g);
        *gx = g[0];
        *gy = g[1];
        *gz = g[2];
        return f;
    }
    prim_frame_point(p, 0, x, y, z, s);
    switch (type) {
    case PRIM_ELL:
        f = prim_ell_grad_s(p, s, g);
        break;
    case PRIM_TGC:
        f = prim_tgc_grad_s(p, s, g);
        break;
    case PRIM_TOR:
        f = prim_tor_grad_s(p, s, g);
        break;
    case PRIM_EHY:
        f = prim_ehy_grad_s(p, s, g);
        break;
    }
    prim_frame_back(p, 0, g, gx, gy, gz);
    return f;
}

/* F, and in *dt its derivative along (dx, dy, dz), for interval Newton. A pipe's f jumps at its end caps (it is +inf
 * outside every part), so its derivative is unbounded: the walk bisects there. */
PRIM_FN ia_interval prim_Fd(int type, const ia_real *p, ia_interval x, ia_interval y, ia_interval z, ia_interval dx,
                            ia_interval dy, ia_interval dz, ia_interval *dt) {
    if (type == PRIM_HALF || type == PRIM_ARB8 || type == PRIM_PIPE) {
        ia_interval f = ia_make(-IA_INF, -IA_INF), d = ia_make(-IA_INF, -IA_INF);
        for (int j = 0; type != PRIM_PIPE && j < (type == PRIM_HALF ? 1 : PRIM_ARB_PLANES); j++) {
            ia_interval fj = prim_half_F(p + 8 * j, x, y, z), dj = prim_dot3(p + 8 * j, 0, dx, dy, dz);
            d = j == 0 ? dj : ia_dmax(f, fj, d, dj);
            f = ia_max(f, fj);
        }
        *dt = type == PRIM_PIPE ? ia_entire() : d;
        return type == PRIM_PIPE ? prim_pipe_F(p, x, y, z) : f;
    }
    ia_interval s[3], ds[3];
    prim_frame(p, 0, x, y, z, s);
    prim_frame_dir(p, 0, dx, dy, dz, ds);
    return prim_frame_value(type, p, s, ds, dt);
}

#endif
