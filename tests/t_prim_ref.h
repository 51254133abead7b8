/* tests/t_prim_ref.h -- an exact long-double reference for BRL-CAD's primitives (implicits/scene.h: scene_prim)
 * along a line: the points where the line crosses the primitive's boundary, from the database's own parameters in
 * the primitive's own frame (the line is taken there through the matrix's inverse), independently of
 * implicits/prim_place.c and kernels/prim.h: no interval, no frame of theirs.
 *
 *   prim_ref_crossings  candidate crossings (roots of each surface's polynomial in t, by isolating them between
 *                       the roots of the derivatives, and planes), sorted; prim_ref_inside decides each piece
 *   prim_ref_inside     the primitive's membership of a point of the line (its definition, in long double)
 *   prim_ref_normal     the outward normal at a crossing (for the early-depth bound), in the world
 *
 * The matrices the tests use are librt's kind: a rotation over mat[15] (a uniform scale) and a translation.
 */
#ifndef T_PRIM_REF_H
#define T_PRIM_REF_H
#include "implicits/scene.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef long double ld;

/* A line o + t d in the primitive's frame: the world line through the inverse of the matrix. */
typedef struct {
    ld o[3], d[3];
} ref_line;

static inline ld ref_dot(const ld *a, const ld *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void ref_cross(const ld *a, const ld *b, ld *out) {
    ld r[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(out, r, sizeof r);
}
static inline ld ref_norm(const ld *a) { return sqrtl(ref_dot(a, a)); }

/* The inverse of a 3x3 matrix (cofactors). */
static inline void ref_inverse3(const ld m[9], ld out[9]) {
    ld c[9] = {m[4] * m[8] - m[5] * m[7], m[2] * m[7] - m[1] * m[8], m[1] * m[5] - m[2] * m[4],
               m[5] * m[6] - m[3] * m[8], m[0] * m[8] - m[2] * m[6], m[2] * m[3] - m[0] * m[5],
               m[3] * m[7] - m[4] * m[6], m[1] * m[6] - m[0] * m[7], m[0] * m[4] - m[1] * m[3]};
    ld det = m[0] * c[0] + m[1] * c[3] + m[2] * c[6];
    for (int k = 0; k < 9; k++)
        out[k] = c[k] / det;
}

/* The world line (o, d) in the frame of a primitive placed by mat: x_local = L^-1 (x - T), L = mat3 / mat[15]. */
static inline ref_line ref_local_line(const double mat[16], const ld o[3], const ld d[3]) {
    ld l[9], inv[9], q[3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            l[3 * i + j] = (ld)mat[4 * i + j] / mat[15];
        q[i] = o[i] - (ld)mat[4 * i + 3] / mat[15];
    }
    ref_inverse3(l, inv);
    ref_line r;
    for (int i = 0; i < 3; i++) {
        r.o[i] = ref_dot(inv + 3 * i, q);
        r.d[i] = ref_dot(inv + 3 * i, d);
    }
    return r;
}

static inline void ref_at(const ref_line *r, ld t, ld p[3]) {
    for (int c = 0; c < 3; c++)
        p[c] = r->o[c] + t * r->d[c];
}

/* ---- real roots of polynomials of degree <= 4 in [lo, hi]: between consecutive roots of the derivative the
 * polynomial is monotone, so each piece holds at most one root, found by bisection to the last bit. */
static inline ld ref_poly(const ld *c, int deg, ld t) {
    ld v = c[deg];
    for (int k = deg - 1; k >= 0; k--)
        v = v * t + c[k];
    return v;
}

static inline int ref_poly_roots(const ld *c, int deg, ld lo, ld hi, ld *roots) {
    while (deg > 0 && c[deg] == 0)
        deg--;
    if (deg == 0)
        return 0;
    ld ends[6];
    int n = 0;
    ends[n++] = lo;
    if (deg > 1) {
        ld dc[4];
        for (int k = 1; k <= deg; k++)
            dc[k - 1] = k * c[k];
        n += ref_poly_roots(dc, deg - 1, lo, hi, ends + 1);
    }
    ends[n++] = hi;
    int count = 0;
    for (int k = 0; k + 1 < n; k++) {
        ld a = ends[k], b = ends[k + 1], fa = ref_poly(c, deg, a), fb = ref_poly(c, deg, b);
        if (fa == 0) {
            if (count == 0 || roots[count - 1] != a)
                roots[count++] = a;
            continue;
        }
        if ((fa < 0) == (fb < 0) && fb != 0)
            continue;
        for (int it = 0; it < 200; it++) {
            ld m = a + (b - a) / 2;
            if (m <= a || m >= b)
                break;
            ld fm = ref_poly(c, deg, m);
            if ((fm < 0) == (fa < 0) && fm != 0)
                a = m, fa = fm;
            else
                b = m;
        }
        roots[count++] = b;
    }
    return count;
}

/* Polynomials in t of linear forms along a line: a + b t. */
typedef struct {
    ld a, b;
} ref_lin;

static inline ref_lin ref_lin_of(const ref_line *r, const ld *n, ld offset) {
    return (ref_lin){ref_dot(r->o, n) - offset, ref_dot(r->d, n)};
}

/* c += k * p * q for linear p, q (degree 2). */
static inline void ref_add_prod(ld *c, ld k, ref_lin p, ref_lin q) {
    c[0] += k * p.a * q.a;
    c[1] += k * (p.a * q.b + p.b * q.a);
    c[2] += k * p.b * q.b;
}

/* c = p * q for polynomials of degree <= 2 (degree 4). */
static inline void ref_mul2(const ld *p, const ld *q, ld *c) {
    for (int k = 0; k < 5; k++)
        c[k] = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            c[i + j] += p[i] * q[j];
}

/* The roots of a linear form in [lo, hi]. */
static inline int ref_lin_root(ref_lin p, ld lo, ld hi, ld *out) {
    if (p.b == 0)
        return 0;
    ld t = -p.a / p.b;
    if (t < lo || t > hi)
        return 0;
    *out = t;
    return 1;
}

/* ---- each type: its inside at a point (local frame), and its crossings' candidates along a line. */

/* A tgc's frame: (u, v, w) = K^-1 (p - V), K = [A B H]; alpha, beta as kernels/prim.h's (from |C|/|A|, |D|/|B|). */
static inline void ref_tgc_frame(const double *q, ld inv[9], ld *alpha, ld *beta) {
    ld k[9];
    for (int r = 0; r < 3; r++) {
        k[3 * r] = q[6 + r];
        k[3 * r + 1] = q[9 + r];
        k[3 * r + 2] = q[3 + r];
    }
    ref_inverse3(k, inv);
    ld a[3] = {q[6], q[7], q[8]}, b[3] = {q[9], q[10], q[11]}, c[3] = {q[12], q[13], q[14]}, d[3] = {q[15], q[16], q[17]};
    *alpha = ref_norm(c) / ref_norm(a) - 1;
    *beta = ref_norm(d) / ref_norm(b) - 1;
}

/* The ehy's frame rows (ehy.c's S R): -B/r2, A/r1, -H/|H|, B = A x H/|H|; and c' = c / |H|. */
static inline void ref_ehy_frame(const double *q, ld rows[9], ld *cp) {
    ld h[3] = {q[3], q[4], q[5]}, a[3] = {q[6], q[7], q[8]}, hu[3], b[3], len = ref_norm(h);
    for (int c = 0; c < 3; c++)
        hu[c] = h[c] / len;
    ref_cross(a, hu, b);
    for (int c = 0; c < 3; c++) {
        rows[c] = -b[c] / q[10];
        rows[3 + c] = a[c] / q[9];
        rows[6 + c] = -hu[c] / len;
    }
    *cp = q[11] / len;
}

/* An arb's faces as librt takes them: per face, the first three distinct non-collinear vertices in rt_arb_info's
 * order (the tests' arbs are exact: no tolerance decides), the normal away from the vertices' mean. Returns the
 * number of planes (n, d: n.p <= d inside). */
static inline int ref_arb_planes(const double *q, ld planes[6][4]) {
    static const int faces[6][4] = {{3, 2, 1, 0}, {4, 5, 6, 7}, {4, 7, 3, 0}, {2, 6, 5, 1}, {1, 5, 4, 0}, {7, 6, 2, 3}};
    ld centre[3] = {0, 0, 0};
    for (int i = 0; i < 8; i++)
        for (int c = 0; c < 3; c++)
            centre[c] += (ld)q[3 * i + c] / 8;
    int n = 0;
    for (int f = 0; f < 6; f++) {
        int pts[3], np = 0;
        for (int j = 0; j < 4 && np < 3; j++) {
            const double *v = q + 3 * faces[f][j];
            int dup = 0;
            for (int k = 0; k < np; k++)
                dup |= !memcmp(v, q + 3 * pts[k], 3 * sizeof(double));
            if (dup)
                continue;
            if (np == 2) {
                ld u[3], w[3], x[3];
                for (int c = 0; c < 3; c++) {
                    u[c] = q[3 * pts[1] + c] - q[3 * pts[0] + c];
                    w[c] = v[c] - q[3 * pts[0] + c];
                }
                ref_cross(u, w, x);
                if (ref_norm(x) == 0)
                    continue;
            }
            pts[np++] = faces[f][j];
        }
        if (np < 3)
            continue;
        ld u[3], w[3], nrm[3], a[3], out[3];
        for (int c = 0; c < 3; c++) {
            a[c] = q[3 * pts[0] + c];
            u[c] = q[3 * pts[1] + c] - a[c];
            w[c] = q[3 * pts[2] + c] - a[c];
            out[c] = a[c] - centre[c];
        }
        ref_cross(w, u, nrm);
        ld sign = ref_dot(nrm, out) < 0 ? -1 : 1;
        for (int c = 0; c < 3; c++)
            planes[n][c] = sign * nrm[c];
        planes[n][3] = ref_dot(planes[n], a);
        n++;
    }
    return n;
}

/* A pipe's parts (pipe.c's pipe_elements_calculate, in long double): straight frusta and bends. */
typedef struct {
    int bend;
    ld a[3], t[3], b[3], u[3]; /* cell: (p - a).t >= 0, (p - b).u <= 0 */
    ld c[3], axis[3];          /* straight: start point and unit axis; bend: centre and unit normal */
    ld r[4];                   /* straight: ro0, ro1, ri0, ri1 and length in len; bend: R, ro, ri */
    ld len;
} ref_pipe_part;

static inline void ref_unit(ld *v) {
    ld l = ref_norm(v);
    for (int c = 0; c < 3; c++)
        v[c] /= l;
}

static inline int ref_pipe_parts(const double *q, int npoints, ref_pipe_part *parts) {
    int n = 0, i2 = 1, i3 = npoints > 2 ? 2 : -1;
    ld curr[3] = {q[0], q[1], q[2]}, curr_r[2] = {q[3] / 2, q[4] / 2};
    for (;;) {
        const double *p2 = q + 6 * i2;
        ld n1[3], h[3], start_t[3];
        for (int c = 0; c < 3; c++) {
            n1[c] = curr[c] - p2[c];
            h[c] = -n1[c];
        }
        if (ref_norm(n1) > 0) {
            ref_unit(h);
            /* after a bend, the plane where they meet (its end's direction equals this axis in exact arithmetic;
             * one value for both, as rounding would leave a sliver between two) */
            memcpy(start_t, n > 0 && parts[n - 1].bend ? parts[n - 1].u : h, sizeof h);
            ld n2[3], nrm[3], dist = 0;
            int bend = 0;
            if (i3 >= 0) {
                for (int c = 0; c < 3; c++)
                    n2[c] = q[6 * i3 + c] - p2[c];
                ref_cross(n1, n2, nrm);
                ref_unit(n1);
                ref_unit(n2);
                ld cosine = ref_dot(n1, n2);
                dist = p2[5] * sqrtl((1 + cosine) / (1 - cosine));
                bend = ref_norm(nrm) > 0 && dist > 0;
            }
            ld end[3];
            for (int c = 0; c < 3; c++)
                end[c] = bend ? p2[c] + dist * n1[c] : p2[c];
            ref_pipe_part *lp = &parts[n++];
            lp->bend = 0;
            memcpy(lp->a, curr, sizeof curr);
            memcpy(lp->t, start_t, sizeof start_t);
            memcpy(lp->b, end, sizeof end);
            for (int c = 0; c < 3; c++) /* before a bend, its start plane (the same) */
                lp->u[c] = bend ? -n1[c] : h[c];
            memcpy(lp->c, curr, sizeof curr);
            memcpy(lp->axis, h, sizeof h);
            lp->r[0] = curr_r[0];
            lp->r[1] = p2[3] / 2;
            lp->r[2] = curr_r[1];
            lp->r[3] = p2[4] / 2;
            ld seg[3];
            for (int c = 0; c < 3; c++)
                seg[c] = end[c] - curr[c];
            lp->len = ref_norm(seg);
            if (bend) {
                ref_pipe_part *bp = &parts[n++];
                ld v1[3];
                ref_unit(nrm);
                ref_cross(n1, nrm, v1);
                bp->bend = 1;
                for (int c = 0; c < 3; c++) {
                    bp->a[c] = end[c];
                    bp->t[c] = -n1[c];
                    bp->b[c] = p2[c] + dist * n2[c];
                    bp->u[c] = n2[c];
                    bp->c[c] = end[c] - p2[5] * v1[c];
                    bp->axis[c] = nrm[c];
                    curr[c] = bp->b[c];
                }
                bp->r[0] = p2[5];
                bp->r[1] = p2[3] / 2;
                bp->r[2] = p2[4] / 2;
            } else {
                memcpy(curr, end, sizeof end);
            }
        }
        if (i3 < 0)
            return n;
        curr_r[0] = p2[3] / 2;
        curr_r[1] = p2[4] / 2;
        i2 = i3;
        i3 = i3 + 1 < npoints ? i3 + 1 : -1;
    }
}

#define REF_PIPE_MAX_PARTS 64

static inline int ref_pipe_part_inside(const ref_pipe_part *pp, const ld p[3]) {
    ld qa[3], qb[3], q[3];
    for (int c = 0; c < 3; c++) {
        qa[c] = p[c] - pp->a[c];
        qb[c] = p[c] - pp->b[c];
        q[c] = p[c] - pp->c[c];
    }
    if (ref_dot(qa, pp->t) < 0 || ref_dot(qb, pp->u) > 0)
        return 0;
    ld z = ref_dot(q, pp->axis), rho = sqrtl(fmaxl(ref_dot(q, q) - z * z, 0));
    if (pp->bend) {
        ld d = sqrtl((rho - pp->r[0]) * (rho - pp->r[0]) + z * z);
        return d < pp->r[1] && (pp->r[2] == 0 || d > pp->r[2]);
    }
    ld w = z / pp->len, ro = pp->r[0] + (pp->r[1] - pp->r[0]) * w, ri = pp->r[2] + (pp->r[3] - pp->r[2]) * w;
    return rho < ro && (pp->r[2] == 0 && pp->r[3] == 0 ? 1 : rho > ri); /* no bore: the axis is inside */
}

static inline int ref_pipe_inside(const ref_pipe_part *parts, int n, const ld p[3]) {
    for (int k = 0; k < n; k++)
        if (ref_pipe_part_inside(&parts[k], p))
            return 1;
    return 0;
}

/* Whether the point p (local frame) is inside the primitive. */
static inline int prim_ref_inside_local(const scene_prim *sp, const ld p[3]) {
    const double *q = sp->params;
    switch (sp->type) {
    case SCENE_PRIM_HALF: {
        ld n[3] = {q[0], q[1], q[2]};
        return ref_dot(n, p) < q[3];
    }
    case SCENE_PRIM_ARB8: {
        ld planes[6][4];
        int n = ref_arb_planes(q, planes);
        for (int k = 0; k < n; k++)
            if (ref_dot(planes[k], p) >= planes[k][3])
                return 0;
        return 1;
    }
    case SCENE_PRIM_ELL: {
        ld s = 0, x[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
        for (int a = 0; a < 3; a++) {
            ld ax[3] = {q[3 + 3 * a], q[4 + 3 * a], q[5 + 3 * a]}, u = ref_dot(x, ax) / ref_dot(ax, ax);
            s += u * u;
        }
        return s < 1;
    }
    case SCENE_PRIM_TGC: {
        ld inv[9], alpha, beta, x[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
        ref_tgc_frame(q, inv, &alpha, &beta);
        ld u = ref_dot(inv, x), v = ref_dot(inv + 3, x), w = ref_dot(inv + 6, x);
        ld ra = 1 + alpha * w, rb = 1 + beta * w;
        return w > 0 && w < 1 && u * u * rb * rb + v * v * ra * ra < ra * ra * rb * rb;
    }
    case SCENE_PRIM_TOR: {
        ld x[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]}, n[3] = {q[3], q[4], q[5]};
        ref_unit(n);
        ld z = ref_dot(x, n), rho = sqrtl(fmaxl(ref_dot(x, x) - z * z, 0));
        return (rho - q[6]) * (rho - q[6]) + z * z < (ld)q[7] * q[7];
    }
    case SCENE_PRIM_EHY: {
        ld rows[9], cp, x[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
        ref_ehy_frame(q, rows, &cp);
        ld a = ref_dot(rows, x), b = ref_dot(rows + 3, x), z = ref_dot(rows + 6, x);
        return z < 0 && z > -1 && (2 * cp + 1) * (a * a + b * b - 1) - z * z - 2 * (cp + 1) * z < 0;
    }
    case SCENE_PRIM_PIPE: {
        ref_pipe_part parts[REF_PIPE_MAX_PARTS];
        return ref_pipe_inside(parts, ref_pipe_parts(q, sp->nparams / 6, parts), p);
    }
    default:
        return 0;
    }
}

/* Candidate crossings of the line with the primitive's surfaces in [lo, hi] (a superset of the crossings). */
static inline int prim_ref_candidates(const scene_prim *sp, const ref_line *r, ld lo, ld hi, ld *out) {
    const double *q = sp->params;
    int n = 0;
    ld c[5] = {0, 0, 0, 0, 0};
    switch (sp->type) {
    case SCENE_PRIM_HALF: {
        ld nrm[3] = {q[0], q[1], q[2]};
        return ref_lin_root(ref_lin_of(r, nrm, q[3]), lo, hi, out);
    }
    case SCENE_PRIM_ARB8: {
        ld planes[6][4];
        int np = ref_arb_planes(q, planes);
        for (int k = 0; k < np; k++)
            n += ref_lin_root(ref_lin_of(r, planes[k], planes[k][3]), lo, hi, out + n);
        return n;
    }
    case SCENE_PRIM_ELL: {
        ld v[3] = {q[0], q[1], q[2]};
        c[0] = -1;
        for (int a = 0; a < 3; a++) {
            ld ax[3] = {q[3 + 3 * a], q[4 + 3 * a], q[5 + 3 * a]}, len2 = ref_dot(ax, ax);
            ref_lin u = ref_lin_of(r, ax, ref_dot(ax, v));
            ref_add_prod(c, 1 / (len2 * len2), u, u);
        }
        return ref_poly_roots(c, 2, lo, hi, out);
    }
    case SCENE_PRIM_TGC: {
        ld inv[9], alpha, beta, v[3] = {q[0], q[1], q[2]};
        ref_tgc_frame(q, inv, &alpha, &beta);
        ref_lin u = ref_lin_of(r, inv, ref_dot(inv, v)), w0 = ref_lin_of(r, inv + 3, ref_dot(inv + 3, v));
        ref_lin w = ref_lin_of(r, inv + 6, ref_dot(inv + 6, v));
        ref_lin ra = {1 + alpha * w.a, alpha * w.b}, rb = {1 + beta * w.a, beta * w.b};
        ld uu[3] = {0, 0, 0}, vv[3] = {0, 0, 0}, aa[3] = {0, 0, 0}, bb[3] = {0, 0, 0}, t1[5], t2[5], t3[5];
        ref_add_prod(uu, 1, u, u);
        ref_add_prod(vv, 1, w0, w0);
        ref_add_prod(aa, 1, ra, ra);
        ref_add_prod(bb, 1, rb, rb);
        ref_mul2(uu, bb, t1);
        ref_mul2(vv, aa, t2);
        ref_mul2(aa, bb, t3);
        for (int k = 0; k < 5; k++)
            c[k] = t1[k] + t2[k] - t3[k];
        n = ref_poly_roots(c, 4, lo, hi, out);
        n += ref_lin_root(w, lo, hi, out + n);
        n += ref_lin_root((ref_lin){w.a - 1, w.b}, lo, hi, out + n);
        return n;
    }
    case SCENE_PRIM_TOR: {
        ld x0[3] = {r->o[0] - q[0], r->o[1] - q[1], r->o[2] - q[2]}, nrm[3] = {q[3], q[4], q[5]};
        ref_unit(nrm);
        ref_line rl = {{x0[0], x0[1], x0[2]}, {r->d[0], r->d[1], r->d[2]}};
        ld qq[3] = {0, 0, 0}, zz[3] = {0, 0, 0}, sq[5];
        ref_lin px = {rl.o[0], rl.d[0]}, py = {rl.o[1], rl.d[1]}, pz = {rl.o[2], rl.d[2]};
        ref_add_prod(qq, 1, px, px);
        ref_add_prod(qq, 1, py, py);
        ref_add_prod(qq, 1, pz, pz);
        ref_lin z = ref_lin_of(&rl, nrm, 0);
        ref_add_prod(zz, 1, z, z);
        ld base[3] = {qq[0] + (ld)q[6] * q[6] - (ld)q[7] * q[7], qq[1], qq[2]};
        ref_mul2(base, base, sq);
        for (int k = 0; k < 5; k++)
            c[k] = sq[k] - (k < 3 ? 4 * (ld)q[6] * q[6] * (qq[k] - zz[k]) : 0);
        return ref_poly_roots(c, 4, lo, hi, out);
    }
    case SCENE_PRIM_EHY: {
        ld rows[9], cp, v[3] = {q[0], q[1], q[2]};
        ref_ehy_frame(q, rows, &cp);
        ref_lin a = ref_lin_of(r, rows, ref_dot(rows, v)), b = ref_lin_of(r, rows + 3, ref_dot(rows + 3, v));
        ref_lin z = ref_lin_of(r, rows + 6, ref_dot(rows + 6, v));
        ref_add_prod(c, 2 * cp + 1, a, a);
        ref_add_prod(c, 2 * cp + 1, b, b);
        ref_add_prod(c, -1, z, z);
        c[0] += -(2 * cp + 1) - 2 * (cp + 1) * z.a;
        c[1] += -2 * (cp + 1) * z.b;
        n = ref_poly_roots(c, 2, lo, hi, out);
        n += ref_lin_root(z, lo, hi, out + n);
        n += ref_lin_root((ref_lin){z.a + 1, z.b}, lo, hi, out + n);
        return n;
    }
    case SCENE_PRIM_PIPE: {
        ref_pipe_part parts[REF_PIPE_MAX_PARTS];
        int np = ref_pipe_parts(q, sp->nparams / 6, parts);
        for (int k = 0; k < np; k++) {
            const ref_pipe_part *pp = &parts[k];
            n += ref_lin_root(ref_lin_of(r, pp->t, ref_dot(pp->t, pp->a)), lo, hi, out + n);
            n += ref_lin_root(ref_lin_of(r, pp->u, ref_dot(pp->u, pp->b)), lo, hi, out + n);
            ref_line rl;
            for (int j = 0; j < 3; j++) {
                rl.o[j] = r->o[j] - pp->c[j];
                rl.d[j] = r->d[j];
            }
            ref_lin px = {rl.o[0], rl.d[0]}, py = {rl.o[1], rl.d[1]}, pz = {rl.o[2], rl.d[2]};
            ld qq[3] = {0, 0, 0}, zz[3] = {0, 0, 0};
            ref_add_prod(qq, 1, px, px);
            ref_add_prod(qq, 1, py, py);
            ref_add_prod(qq, 1, pz, pz);
            ref_lin z = ref_lin_of(&rl, pp->axis, 0);
            ref_add_prod(zz, 1, z, z);
            for (int which = 1; which <= 2; which++) {
                ld cc[5] = {0, 0, 0, 0, 0};
                if (pp->bend) { /* the torus of tube radius r[which] */
                    ld base[3] = {qq[0] + pp->r[0] * pp->r[0] - pp->r[which] * pp->r[which], qq[1], qq[2]}, sq[5];
                    ref_mul2(base, base, sq);
                    for (int j = 0; j < 5; j++)
                        cc[j] = sq[j] - (j < 3 ? 4 * pp->r[0] * pp->r[0] * (qq[j] - zz[j]) : 0);
                    n += ref_poly_roots(cc, 4, lo, hi, out + n);
                } else { /* rho^2 = (r0 + (r1 - r0) z / len)^2, outer (r[0], r[1]) or inner (r[2], r[3]) */
                    ld r0 = pp->r[which == 1 ? 0 : 2], r1 = pp->r[which == 1 ? 1 : 3], k = (r1 - r0) / pp->len;
                    ref_lin rad = {r0 + k * z.a, k * z.b};
                    for (int j = 0; j < 3; j++)
                        cc[j] = qq[j] - zz[j];
                    ref_add_prod(cc, -1, rad, rad);
                    n += ref_poly_roots(cc, 2, lo, hi, out + n);
                }
            }
        }
        return n;
    }
    default:
        return 0;
    }
}

static inline int ref_cmp_ld(const void *a, const void *b) {
    ld x = *(const ld *)a, y = *(const ld *)b;
    return (x > y) - (x < y);
}

/* The crossings of the line with the primitive in (lo, hi): the candidates where membership changes (decided at
 * the midpoints of the pieces between candidates), sorted; *inside_at_lo: membership just after lo. The
 * candidates are the roots along the line moved to start at lo: in t from the ray's far origin, a quartic's
 * terms cancel (t^4 ~ 10^7 for roots within 1 of each other), and a root came out 2e-10 away (a cone's). */
#define REF_MAX_CROSSINGS 512
static inline int prim_ref_crossings(const scene_prim *sp, const ref_line *r, ld lo, ld hi, ld *out,
                                     int *inside_at_lo) {
    ld cand[REF_MAX_CROSSINGS + 2];
    ref_line near = *r;
    for (int c = 0; c < 3; c++)
        near.o[c] = r->o[c] + lo * r->d[c];
    int n = prim_ref_candidates(sp, &near, 0, hi - lo, cand + 1);
    for (int k = 1; k <= n; k++)
        cand[k] += lo;
    cand[0] = lo;
    qsort(cand + 1, (size_t)n, sizeof(ld), ref_cmp_ld);
    cand[n + 1] = hi;
    ref_pipe_part parts[REF_PIPE_MAX_PARTS]; /* a pipe's, made once */
    int nparts = sp->type == SCENE_PRIM_PIPE ? ref_pipe_parts(sp->params, sp->nparams / 6, parts) : 0;
    int count = 0, prev = -1;
    for (int k = 0; k <= n; k++) {
        if (!(cand[k] < cand[k + 1]))
            continue;
        ld p[3];
        ref_at(r, cand[k] + (cand[k + 1] - cand[k]) / 2, p);
        int in = sp->type == SCENE_PRIM_PIPE ? ref_pipe_inside(parts, nparts, p) : prim_ref_inside_local(sp, p);
        if (prev < 0)
            *inside_at_lo = in;
        else if (in != prev)
            out[count++] = cand[k];
        prev = in;
    }
    if (prev < 0)
        *inside_at_lo = 0;
    return count;
}

#endif
