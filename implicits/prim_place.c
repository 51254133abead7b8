/* implicits/prim_place.c -- see prim_place.h. Stages: the matrix as intervals (L, T: x' = L x + T); per type, the
 * world parameters in double interval arithmetic (ia/, rounded outward), a frame's matrix inverted with a
 * verified enclosure; the world box. Choices BRL-CAD makes on floating-point tests (which arb vertices coincide,
 * which make a face) are made here the same way, on the midpoints; what follows from them is enclosed. */
#define IA_FP64 1
#include "prim_place.h"
#include "ia/flush.h"
#include "ia/ia.h"
#include "kernels/prim.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(SCENE_PRIM_HALF == PRIM_HALF && SCENE_PRIM_ARB8 == PRIM_ARB8 && SCENE_PRIM_ELL == PRIM_ELL &&
                   SCENE_PRIM_TGC == PRIM_TGC && SCENE_PRIM_TOR == PRIM_TOR && SCENE_PRIM_EHY == PRIM_EHY &&
                   SCENE_PRIM_PIPE == PRIM_PIPE,
               "kernels/prim.h numbers the types as implicits/scene.h does");

/* BRL-CAD's tolerances (librt): vertices closer than BN_TOL_DIST mm are one; a third face vertex nearer than
 * RT_SLOPPY_DOT_TOL mm to the line of the first two does not make a plane (arb8.c). */
#define BRL_TOL_DIST 0.0005
#define BRL_SLOPPY_DOT_TOL 0.0087
/* Pipes (pipe.c): points nearer than RT_LEN_TOL mm are one; SQRT_SMALL_FASTF decides "in line". */
#define BRL_LEN_TOL 1.0e-8
#define BRL_SQRT_SMALL 1.0e-18

typedef ia_interval iv;

static iv pt(double x) { return ia_point(x); }

static iv dot3(const iv a[3], const iv b[3]) {
    return ia_add(ia_add(ia_mul(a[0], b[0]), ia_mul(a[1], b[1])), ia_mul(a[2], b[2]));
}

static void cross3(const iv a[3], const iv b[3], iv out[3]) {
    iv r[3] = {ia_sub(ia_mul(a[1], b[2]), ia_mul(a[2], b[1])), ia_sub(ia_mul(a[2], b[0]), ia_mul(a[0], b[2])),
               ia_sub(ia_mul(a[0], b[1]), ia_mul(a[1], b[0]))};
    memcpy(out, r, sizeof r);
}

static iv norm3(const iv a[3]) { return ia_sqrt(dot3(a, a)); }

static void sub3(const iv a[3], const iv b[3], iv out[3]) {
    for (int c = 0; c < 3; c++)
        out[c] = ia_sub(a[c], b[c]);
}

static void scale3(const iv a[3], iv k, iv out[3]) {
    for (int c = 0; c < 3; c++)
        out[c] = ia_mul(a[c], k);
}

static void point3(const double *x, iv out[3]) {
    for (int c = 0; c < 3; c++)
        out[c] = pt(x[c]);
}

/* out = A B for 3x3 interval matrices (row-major). */
static void matmul3(const iv a[9], const iv b[9], iv out[9]) {
    iv r[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r[3 * i + j] = ia_add(ia_add(ia_mul(a[3 * i], b[j]), ia_mul(a[3 * i + 1], b[3 + j])),
                                  ia_mul(a[3 * i + 2], b[6 + j]));
    memcpy(out, r, sizeof r);
}

/* out = A v. */
static void matvec3(const iv a[9], const iv v[3], iv out[3]) {
    iv r[3];
    for (int i = 0; i < 3; i++)
        r[i] = dot3(a + 3 * i, v);
    memcpy(out, r, sizeof r);
}

/* An enclosure W of the inverse of every matrix in K: R, an inverse of K's midpoint, and E = I - R K; if
 * ||E|| = delta < 1 (row sums), K^-1 = (I - E)^-1 R and |K^-1 - R| <= delta / (1 - delta) ||R|| entrywise. 0 when K
 * is (numerically) singular. */
static int inverse3(const iv k[9], iv w[9]) {
    double m[9], r[9];
    for (int i = 0; i < 9; i++)
        m[i] = ia_mid(k[i]);
    double c[9] = {m[4] * m[8] - m[5] * m[7], m[2] * m[7] - m[1] * m[8], m[1] * m[5] - m[2] * m[4],
                   m[5] * m[6] - m[3] * m[8], m[0] * m[8] - m[2] * m[6], m[2] * m[3] - m[0] * m[5],
                   m[3] * m[7] - m[4] * m[6], m[1] * m[6] - m[0] * m[7], m[0] * m[4] - m[1] * m[3]};
    double det = m[0] * c[0] + m[1] * c[3] + m[2] * c[6];
    if (!(fabs(det) > 0) || !isfinite(det))
        return 0;
    iv ri[9], e[9];
    for (int i = 0; i < 9; i++) {
        r[i] = c[i] / det;
        ri[i] = pt(r[i]);
    }
    matmul3(ri, k, e);
    iv delta = pt(0), size = pt(0);
    for (int i = 0; i < 3; i++) {
        iv row = pt(0), rrow = pt(0);
        for (int j = 0; j < 3; j++) {
            row = ia_add(row, ia_abs(ia_sub(pt(i == j), e[3 * i + j])));
            rrow = ia_add(rrow, ia_abs(ri[3 * i + j]));
        }
        delta = ia_max(delta, row);
        size = ia_max(size, rrow);
    }
    if (!(delta.hi < 0.5))
        return 0;
    double pad = ia_div(ia_mul(ia_point(delta.hi), ia_point(size.hi)), ia_sub(pt(1), ia_point(delta.hi))).hi;
    for (int i = 0; i < 9; i++)
        w[i] = ia_add(ri[i], ia_make(-pad, pad));
    return 1;
}

/* The parameters being written. */
typedef struct {
    prim_placed *out;
    int cap;
} writer;

static int put(writer *w, iv x) {
    prim_placed *o = w->out;
    if (o->n == w->cap) {
        int cap = w->cap ? 2 * w->cap : 64;
        double *lo = realloc(o->lo, sizeof(double) * (size_t)cap),
               *hi = lo ? realloc(o->hi, sizeof(double) * (size_t)cap) : NULL;
        if (lo)
            o->lo = lo;
        if (!hi)
            return 0;
        o->hi = hi;
        w->cap = cap;
    }
    o->lo[o->n] = x.lo;
    o->hi[o->n] = x.hi;
    o->n++;
    return 1;
}

static int put_n(writer *w, const iv *x, int n) {
    int ok = 1;
    for (int k = 0; k < n; k++)
        ok = ok && put(w, x[k]);
    return ok;
}

/* ---- the matrix */

typedef struct {
    iv l[9], t[3];
    double scale; /* mat[15] */
} placement;

static int placement_of(const double mat[16], placement *m) {
    if (mat[12] != 0 || mat[13] != 0 || mat[14] != 0 || !(mat[15] > 0) || !isfinite(mat[15]))
        return 0;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            m->l[3 * i + j] = ia_div(pt(mat[4 * i + j]), pt(mat[15]));
        m->t[i] = ia_div(pt(mat[4 * i + 3]), pt(mat[15]));
    }
    m->scale = mat[15];
    return 1;
}

static void place_point(const placement *m, const double *x, iv out[3]) {
    iv p[3];
    point3(x, p);
    matvec3(m->l, p, out);
    for (int c = 0; c < 3; c++)
        out[c] = ia_add(out[c], m->t[c]);
}

static void place_vector(const placement *m, const double *x, iv out[3]) {
    iv v[3];
    point3(x, v);
    matvec3(m->l, v, out);
}

/* ---- boxes */

static void box_empty(double box[6]) {
    for (int c = 0; c < 3; c++) {
        box[c] = INFINITY;
        box[c + 3] = -INFINITY;
    }
}

/* Adds centre + [-r, r] per coordinate. */
static void box_add(double box[6], const iv centre[3], const iv r[3]) {
    for (int c = 0; c < 3; c++) {
        box[c] = fmin(box[c], ia_sub(centre[c], r[c]).lo);
        box[c + 3] = fmax(box[c + 3], ia_add(centre[c], r[c]).hi);
    }
}

/* The half-widths of the image of the unit disk (columns a, b of K) or ball (a, b, c) per coordinate. */
static void ellipse_reach(const iv k[9], int ncols, iv scale0, iv scale1, iv r[3]) {
    for (int c = 0; c < 3; c++) {
        iv sum = ia_add(ia_sqr(ia_mul(k[3 * c], scale0)), ia_sqr(ia_mul(k[3 * c + 1], scale1)));
        if (ncols == 3)
            sum = ia_add(sum, ia_sqr(k[3 * c + 2]));
        r[c] = ia_sqrt(sum);
    }
}

/* sqrt(1 - u_c^2) for a unit vector u, as the other two components' length (no cancellation where u_c is near 1):
 * how far a unit circle across u reaches in coordinate c. */
static iv across(const iv u[3], int c) { return ia_sqrt(ia_add(ia_sqr(u[(c + 1) % 3]), ia_sqr(u[(c + 2) % 3]))); }

/* ---- the types */

/* P and G of a frame: G = W, the verified inverse of K (the canonical shape's axes in the world, columns). */
static int put_frame(writer *w, const iv p[3], const iv k[9], iv g[9]) {
    if (!inverse3(k, g))
        return -1;
    return put_n(w, p, 3) && put_n(w, g, 9);
}

/* K's columns a, b, c. */
static void columns(const iv a[3], const iv b[3], const iv c[3], iv k[9]) {
    for (int r = 0; r < 3; r++) {
        k[3 * r] = a[r];
        k[3 * r + 1] = b[r];
        k[3 * r + 2] = c[r];
    }
}

/* As librt's rt_hlf_mat: the normal turned by L, a point of the plane (N d / |N|^2) placed, d from it. */
static int place_half(const scene_prim *sp, const placement *m, writer *w, const char **why) {
    iv n[3], nw[3], onplane[3], pw[3];
    point3(sp->params, n);
    iv len2 = dot3(n, n);
    if (!(len2.lo > 0))
        return *why = "its normal is zero", -1;
    scale3(n, ia_div(pt(sp->params[3]), len2), onplane);
    matvec3(m->l, n, nw);
    matvec3(m->l, onplane, pw);
    for (int c = 0; c < 3; c++) {
        pw[c] = ia_add(pw[c], m->t[c]);
        w->out->box[c] = -INFINITY;
        w->out->box[c + 3] = INFINITY;
    }
    return put_n(w, nw, 3) && put(w, dot3(nw, pw));
}

/* rt_arb_info: each face's vertices, in the order BRL-CAD takes them. */
static const int arb_faces[6][4] = {{3, 2, 1, 0}, {4, 5, 6, 7}, {4, 7, 3, 0}, {2, 6, 5, 1}, {1, 5, 4, 0}, {7, 6, 2, 3}};

static int place_arb8(const scene_prim *sp, const placement *m, writer *w, const char **why) {
    iv v[8][3];
    double mid[8][3], centre[3] = {0, 0, 0};
    int same[8];
    box_empty(w->out->box);
    for (int i = 0; i < 8; i++) {
        place_point(m, sp->params + 3 * i, v[i]);
        for (int c = 0; c < 3; c++) {
            mid[i][c] = ia_mid(v[i][c]);
            centre[c] += mid[i][c] / 8;
            w->out->box[c] = fmin(w->out->box[c], v[i][c].lo);
            w->out->box[c + 3] = fmax(w->out->box[c + 3], v[i][c].hi);
        }
        same[i] = i;
        for (int j = i - 1; j >= 0; j--) {
            double d2 = 0;
            for (int c = 0; c < 3; c++)
                d2 += (mid[i][c] - mid[j][c]) * (mid[i][c] - mid[j][c]);
            if (d2 < BRL_TOL_DIST * BRL_TOL_DIST) {
                same[i] = same[j];
                break;
            }
        }
    }
    iv planes[PRIM_ARB_PLANES][4];
    int nplanes = 0;
    for (int f = 0; f < 6; f++) {
        int pts[3], npts = 0;
        for (int j = 0; j < 4 && npts < 3; j++) {
            int k = same[arb_faces[f][j]], dup = 0;
            for (int q = 0; q < npts; q++)
                dup |= pts[q] == k;
            if (dup)
                continue;
            if (npts == 2) { /* the third: not (nearly) on the line of the first two */
                double u[3], a[3], len = 0, cr2 = 0;
                for (int c = 0; c < 3; c++) {
                    u[c] = mid[pts[1]][c] - mid[pts[0]][c];
                    a[c] = mid[k][c] - mid[pts[0]][c];
                    len += u[c] * u[c];
                }
                len = sqrt(len);
                for (int c = 0; c < 3; c++) {
                    double x = (a[(c + 1) % 3] * u[(c + 2) % 3] - a[(c + 2) % 3] * u[(c + 1) % 3]) / len;
                    cr2 += x * x;
                }
                if (sqrt(cr2) < BRL_SLOPPY_DOT_TOL)
                    continue;
            }
            pts[npts++] = k;
        }
        if (npts < 3)
            continue;
        iv ab[3], ac[3], n[3], outward[3], c3[3];
        sub3(v[pts[1]], v[pts[0]], ab);
        sub3(v[pts[2]], v[pts[0]], ac);
        cross3(ac, ab, n);
        point3(centre, c3);
        sub3(v[pts[0]], c3, outward);
        iv side = dot3(outward, n);
        if (ia_contains_zero(side))
            return *why = "its centre is on one of its faces", -1;
        if (side.hi < 0)
            for (int c = 0; c < 3; c++)
                n[c] = ia_neg(n[c]);
        for (int c = 0; c < 3; c++)
            planes[nplanes][c] = n[c];
        planes[nplanes][3] = dot3(n, v[pts[0]]);
        nplanes++;
    }
    if (nplanes < 4)
        return *why = "it has fewer than four faces", -1;
    int ok = 1;
    for (int j = 0; j < PRIM_ARB_PLANES; j++)
        ok = ok && put_n(w, planes[j < nplanes ? j : 0], 4);
    return ok;
}

static int place_ell(const scene_prim *sp, const placement *m, writer *w, const char **why) {
    iv p[3], a[3], b[3], c[3], k[9], g[9], r[3];
    place_point(m, sp->params, p);
    place_vector(m, sp->params + 3, a);
    place_vector(m, sp->params + 6, b);
    place_vector(m, sp->params + 9, c);
    columns(a, b, c, k);
    int ok = put_frame(w, p, k, g);
    if (ok < 0)
        return *why = "its semi-axes are not independent", -1;
    ellipse_reach(k, 3, pt(1), pt(1), r);
    box_empty(w->out->box);
    box_add(w->out->box, p, r);
    return ok;
}

static int place_tgc(const scene_prim *sp, const placement *m, writer *w, const char **why) {
    const double *q = sp->params;
    iv p[3], h[3], a[3], b[3], k[9], g[9], r[3], top[3], da[3], db[3], dc[3], dd[3];
    place_point(m, q, p);
    place_vector(m, q + 3, h);
    place_vector(m, q + 6, a);
    place_vector(m, q + 9, b);
    columns(a, b, h, k);
    int ok = put_frame(w, p, k, g);
    if (ok < 0)
        return *why = "its height and base axes are not independent", -1;
    point3(q + 6, da);
    point3(q + 9, db);
    point3(q + 12, dc);
    point3(q + 15, dd);
    iv ca = ia_div(norm3(dc), norm3(da)), db_ = ia_div(norm3(dd), norm3(db));
    ok = ok && put(w, ia_add_r(ca, -1)) && put(w, ia_add_r(db_, -1));
    box_empty(w->out->box);
    ellipse_reach(k, 2, pt(1), pt(1), r);
    box_add(w->out->box, p, r);
    for (int c = 0; c < 3; c++)
        top[c] = ia_add(p[c], h[c]);
    ellipse_reach(k, 2, ca, db_, r);
    box_add(w->out->box, top, r);
    return ok;
}

/* An orthonormal frame (rows e1, e2, n) around axis n: intervals holding the exact frame these formulas give. */
static int axis_frame(const iv axis[3], iv f[9]) {
    iv n[3], e[3], e1[3], e2[3];
    memcpy(n, axis, sizeof n);
    iv len = norm3(n);
    if (!(len.lo > 0))
        return 0;
    for (int c = 0; c < 3; c++)
        n[c] = ia_div(n[c], len);
    int least = 0; /* the world axis most across n */
    for (int c = 1; c < 3; c++)
        least = fabs(ia_mid(axis[c])) < fabs(ia_mid(axis[least])) ? c : least;
    for (int c = 0; c < 3; c++)
        e[c] = pt(c == least);
    cross3(n, e, e1);
    iv l1 = norm3(e1);
    for (int c = 0; c < 3; c++)
        e1[c] = ia_div(e1[c], l1);
    cross3(n, e1, e2);
    for (int c = 0; c < 3; c++) {
        f[c] = e1[c];
        f[3 + c] = e2[c];
        f[6 + c] = n[c];
    }
    return 1;
}

/* As librt's rt_tor_mat: the centre placed, the axis turned by L, the radii divided by mat[15] (L taken as a
 * rotation: librt ignores any other part of a torus's matrix). */
static int place_tor(const scene_prim *sp, const placement *m, writer *w, const char **why) {
    const double *q = sp->params;
    iv p[3], axis[3], fr[9], r[3];
    if (!(q[6] > 0 && q[7] > 0))
        return *why = "its radii are not positive", -1;
    place_point(m, q, p);
    place_vector(m, q + 3, axis);
    if (!axis_frame(axis, fr))
        return *why = "its axis is zero", -1;
    iv ra = ia_div(pt(q[6]), pt(m->scale)), rh = ia_div(pt(q[7]), pt(m->scale));
    int ok = put_n(w, p, 3) && put_n(w, fr, 9) && put(w, ra) && put(w, ia_sqr(rh));
    /* the core circle's reach in coordinate c is r_a sqrt(1 - n_c^2), the tube's r_h */
    for (int c = 0; c < 3; c++)
        r[c] = ia_add(ia_mul(ra, across(fr + 6, c)), rh);
    box_empty(w->out->box);
    box_add(w->out->box, p, r);
    return ok;
}

static int place_ehy(const scene_prim *sp, const placement *m, writer *w, const char **why) {
    const double *q = sp->params;
    iv p[3], h[3], a[3], hu[3], bu[3], fr[9], winv[9], g[9], back[9], k[9], r[3];
    if (!(q[9] > 0 && q[10] > 0 && q[11] > 0 && q[10] <= q[9]))
        return *why = "its semi-axes and c are not 0 < r_2 <= r_1, c > 0", -1;
    point3(q + 3, h);
    point3(q + 6, a);
    iv hlen = norm3(h);
    if (!(hlen.lo > 0))
        return *why = "its height is zero", -1;
    for (int c = 0; c < 3; c++)
        hu[c] = ia_div(h[c], hlen);
    cross3(a, hu, bu);
    /* ehy.c's S R: rows -B/r2, A/r1, -H/|H| */
    for (int c = 0; c < 3; c++) {
        fr[c] = ia_div(ia_neg(bu[c]), pt(q[10]));
        fr[3 + c] = ia_div(a[c], pt(q[9]));
        fr[6 + c] = ia_neg(ia_div(hu[c], hlen));
    }
    if (!inverse3(m->l, winv) || !inverse3(fr, back))
        return *why = "its axes are not independent", -1;
    place_point(m, q, p);
    matmul3(fr, winv, g);
    iv cp = ia_div(pt(q[11]), hlen), k2 = ia_add_r(cp, 1);
    int ok = put_n(w, p, 3) && put_n(w, g, 9) && put(w, ia_add_r(ia_mul_r(cp, 2), 1)) && put(w, k2) &&
             put(w, ia_sqr(k2));
    /* inside, s1^2 + s2^2 <= 1 and -1 <= s3 <= 0: the world points P + L back s */
    matmul3(m->l, back, k);
    box_empty(w->out->box);
    ellipse_reach(k, 2, pt(1), pt(1), r);
    iv tip[3];
    for (int c = 0; c < 3; c++)
        tip[c] = ia_sub(p[c], k[3 * c + 2]);
    box_add(w->out->box, p, r);
    box_add(w->out->box, tip, r);
    return ok;
}

/* ---- pipes: librt's pipe_elements_calculate, its choices on the midpoints, its geometry in intervals */

/* A plane of a part's cell: a point and the direction of travel there. */
typedef struct {
    iv a[3], t[3];
} pipe_plane;

typedef struct {
    writer *w;
    int parts;
    double *box;
} pipe_builder;

static int near_zero3(const iv v[3], double tol) {
    return fabs(ia_mid(v[0])) < tol && fabs(ia_mid(v[1])) < tol && fabs(ia_mid(v[2])) < tol;
}

static iv distance3(const iv a[3], const iv b[3]) {
    iv d[3];
    sub3(a, b, d);
    return norm3(d);
}

/* One part: its flags, cell planes, frame (origin and the rows of axis_frame(axis)), radii and box (added to the
 * pipe's). */
static int pipe_part(pipe_builder *pb, int flags, const pipe_plane *start, const pipe_plane *end, const iv origin[3],
                     const iv axis[3], const iv radii[4], const double box[6]) {
    iv frame[9];
    if (!axis_frame(axis, frame))
        return -1;
    writer *w = pb->w;
    pb->parts++;
    for (int c = 0; c < 3; c++) {
        pb->box[c] = fmin(pb->box[c], box[c]);
        pb->box[c + 3] = fmax(pb->box[c + 3], box[c + 3]);
    }
    return put(w, pt(flags)) && put_n(w, start->a, 3) && put_n(w, start->t, 3) && put_n(w, end->a, 3) &&
           put_n(w, end->t, 3) && put_n(w, origin, 3) && put_n(w, frame, 9) && put_n(w, radii, 4) &&
           put(w, ia_make(box[0], box[3])) && put(w, ia_make(box[1], box[4])) && put(w, ia_make(box[2], box[5]));
}

/* A straight part from a to b, radii (outer, inner) going from r0 to r1, in the cell between the planes. */
static int pipe_linear(pipe_builder *pb, const pipe_plane *start, int shares, const pipe_plane *end, const iv r0[2],
                       const iv r1[2]) {
    iv h[3], len = distance3(end->a, start->a);
    sub3(end->a, start->a, h);
    if (!(len.lo > 0))
        return -1;
    iv radii[4] = {r0[0], ia_div(ia_sub(r1[0], r0[0]), len), r0[1], ia_div(ia_sub(r1[1], r0[1]), len)};
    for (int c = 0; c < 3; c++)
        h[c] = ia_div(h[c], len);
    int flags = PRIM_PIPE_LINEAR | (shares ? PRIM_PIPE_SHARES_START : 0) |
                (r0[1].hi > 0 || r1[1].hi > 0 ? PRIM_PIPE_INNER : 0);
    iv reach[3];
    for (int c = 0; c < 3; c++) /* a disk of radius r across h reaches r sqrt(1 - h_c^2) */
        reach[c] = across(h, c);
    iv r[3];
    double box[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    scale3(reach, r0[0], r);
    box_add(box, start->a, r);
    scale3(reach, r1[0], r);
    box_add(box, end->a, r);
    return pipe_part(pb, flags, start, end, start->a, h, radii, box);
}

/* A bend: the torus of centre c, axis n, radius bend, tube radii r (outer, inner), between the planes. */
static int pipe_bend(pipe_builder *pb, const pipe_plane *start, int shares, const pipe_plane *end, const iv c[3],
                     const iv n[3], iv bend, const iv r[2]) {
    iv radii[4] = {bend, r[0], r[1], pt(0)}, reach[3];
    for (int k = 0; k < 3; k++)
        reach[k] = ia_add(ia_mul(bend, across(n, k)), r[0]);
    double box[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    box_add(box, c, reach);
    int flags = PRIM_PIPE_BEND | (shares ? PRIM_PIPE_SHARES_START : 0) | (r[1].hi > 0 ? PRIM_PIPE_INNER : 0);
    return pipe_part(pb, flags, start, end, c, n, radii, box);
}

static void unit3(const iv v[3], iv out[3]) {
    iv len = norm3(v);
    for (int c = 0; c < 3; c++)
        out[c] = ia_div(v[c], len);
}

/* The parts of a pipe through the placed points (librt's pipe_elements_calculate), written after the count. */
static int pipe_build(writer *w, const iv (*pts)[3], const iv (*radii)[2], const iv *bends, int n, const char **why) {
    int ok = 1;
    pipe_builder pb = {w, 0, w->out->box};
    box_empty(pb.box);
    pipe_plane start, shared;
    int have_shared = 0, i2 = 1, i3 = n > 2 ? 2 : -1;
    iv curr[3], curr_r[2];
    memcpy(curr, pts[0], sizeof curr);
    memcpy(curr_r, radii[0], sizeof curr_r);
    while (ok > 0) {
        iv n1[3], n2[3], norm[3], n1u[3], n2u[3], h[3];
        sub3(curr, pts[i2], n1);
        if (!near_zero3(n1, BRL_LEN_TOL)) {
            /* the straight part's start: the plane shared with the part before, or across its own axis */
            sub3(pts[i2], curr, h);
            unit3(h, h);
            memcpy(start.a, curr, sizeof start.a);
            memcpy(start.t, have_shared ? shared.t : h, sizeof start.t);
            int shares = have_shared;
            have_shared = 0;
            double dist = NAN;
            if (i3 >= 0) {
                sub3(pts[i3], pts[i2], n2);
                cross3(n1, n2, norm);
                unit3(n1, n1u);
                unit3(n2, n2u);
                double cosine = ia_mid(dot3(n1u, n2u));
                dist = ia_mid(bends[i2]) * tan((3.14159265358979323846 - acos(cosine)) / 2); /* as pipe.c */
            }
            if (i3 < 0 || isnan(dist) || near_zero3(norm, BRL_SQRT_SMALL) || fabs(dist) < BRL_SQRT_SMALL) {
                /* the last part, or collinear: straight to the point */
                pipe_plane end;
                memcpy(end.a, pts[i2], sizeof end.a);
                memcpy(end.t, h, sizeof end.t);
                ok = pipe_linear(&pb, &start, shares, &end, curr_r, radii[i2]);
                memcpy(curr, pts[i2], sizeof curr);
                /* exactly in line (not a sharp corner of bend radius 0): the next part starts on this plane */
                have_shared = i3 >= 0 && !isnan(dist) && near_zero3(norm, BRL_SQRT_SMALL);
                shared = end;
            } else {
                /* the bend's ends at bend * cot(theta / 2) from the corner (theta between the segments) */
                iv cosine = dot3(n1u, n2u), bs[3], be[3], normu[3], v1[3], centre[3], diff[3];
                iv along = ia_mul(bends[i2], ia_sqrt(ia_div(ia_add_r(cosine, 1), ia_sub(pt(1), cosine))));
                for (int c = 0; c < 3; c++) {
                    bs[c] = ia_add(pts[i2][c], ia_mul(along, n1u[c]));
                    be[c] = ia_add(pts[i2][c], ia_mul(along, n2u[c]));
                }
                unit3(norm, normu);
                pipe_plane bend_start, bend_end;
                for (int c = 0; c < 3; c++) {
                    bend_start.t[c] = ia_neg(n1u[c]);
                    bend_end.t[c] = n2u[c];
                }
                memcpy(bend_end.a, be, sizeof be);
                sub3(curr, bs, diff);
                if (ia_mid(norm3(diff)) <= BRL_LEN_TOL) { /* too short to trace: the bend starts here */
                    memcpy(bs, curr, sizeof bs);
                    memcpy(bend_start.a, bs, sizeof bs);
                    if (shares)
                        memcpy(bend_start.t, start.t, sizeof bend_start.t);
                } else {
                    memcpy(bend_start.a, bs, sizeof bs);
                    ok = pipe_linear(&pb, &start, shares, &bend_start, curr_r, radii[i2]);
                    shares = 1;
                }
                cross3(n1u, normu, v1);
                for (int c = 0; c < 3; c++)
                    centre[c] = ia_sub(bs[c], ia_mul(bends[i2], v1[c]));
                if (ok > 0)
                    ok = pipe_bend(&pb, &bend_start, shares, &bend_end, centre, normu, bends[i2], radii[i2]);
                memcpy(curr, be, sizeof curr);
                have_shared = 1;
                shared = bend_end;
            }
        }
        if (i3 < 0)
            break;
        memcpy(curr_r, radii[i2], sizeof curr_r);
        i2 = i3;
        i3 = i3 + 1 < n ? i3 + 1 : -1;
    }
    if (ok > 0 && pb.parts == 0)
        ok = (*why = "all its points coincide", -1);
    if (ok > 0)
        w->out->lo[0] = w->out->hi[0] = pb.parts;
    return ok;
}

/* Points x y z od id bend: placed, the lengths divided by mat[15] (librt's rt_pipe_mat). */
static int place_pipe(const scene_prim *sp, const placement *m, writer *w, const char **why) {
    int n = sp->nparams / 6;
    if (sp->nparams % 6 != 0 || n < 2)
        return *why = "a pipe needs whole points (x y z od id bend), at least two", -1;
    iv(*pts)[3] = malloc(sizeof *pts * (size_t)n), (*radii)[2] = malloc(sizeof *radii * (size_t)n);
    iv *bends = malloc(sizeof *bends * (size_t)n);
    int ok = pts && radii && bends && put(w, pt(0));
    *why = "a part of it is degenerate";
    for (int i = 0; ok > 0 && i < n; i++) {
        const double *q = sp->params + 6 * i;
        if (!(q[3] > 0 && q[4] >= 0 && q[4] < q[3] && q[5] >= 0))
            ok = (*why = "a point's diameters and bend radius are not 0 <= id < od, bend >= 0", -1);
        place_point(m, q, pts[i]);
        radii[i][0] = ia_div(pt(q[3] / 2), pt(m->scale));
        radii[i][1] = ia_div(pt(q[4] / 2), pt(m->scale));
        bends[i] = ia_div(pt(q[5]), pt(m->scale));
    }
    if (ok > 0)
        ok = pipe_build(w, (const iv(*)[3])pts, (const iv(*)[2])radii, bends, n, why);
    free(pts);
    free(radii);
    free(bends);
    return ok;
}

static const struct {
    const char *name;
    int nparams; /* 0: variable */
    int (*place)(const scene_prim *, const placement *, writer *, const char **);
} types[] = {
    [PRIM_HALF] = {"half", 4, place_half}, [PRIM_ARB8] = {"arb8", 24, place_arb8}, [PRIM_ELL] = {"ell", 12, place_ell},
    [PRIM_TGC] = {"tgc", 18, place_tgc},   [PRIM_TOR] = {"tor", 8, place_tor},     [PRIM_EHY] = {"ehy", 12, place_ehy},
    [PRIM_PIPE] = {"pipe", 0, place_pipe},
};

static int all_finite(const double *x, int n) {
    for (int k = 0; k < n; k++)
        if (!isfinite(x[k]))
            return 0;
    return 1;
}

/* A copy of a kept placement: 0 when memory runs out. */
static int copy_placed(const prim_placed *from, prim_placed *out) {
    *out = *from;
    out->lo = malloc((size_t)from->n * sizeof *out->lo);
    out->hi = malloc((size_t)from->n * sizeof *out->hi);
    if (!out->lo || !out->hi) {
        prim_placed_free(out);
        return 0;
    }
    memcpy(out->lo, from->lo, (size_t)from->n * sizeof *out->lo);
    memcpy(out->hi, from->hi, (size_t)from->n * sizeof *out->hi);
    return 1;
}

iacsg_status prim_place(const scene_prim *sp, const char *name, prim_placed *out, iacsg_error *err) {
    memset(out, 0, sizeof *out);
    if (sp->placed)
        return copy_placed(sp->placed, out)
                   ? IACSG_OK
                   : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory placing solid '%s'", name ? name : "");
    out->type = sp->type;
    const char *why = "it is not a supported primitive type";
    int ok = -1;
    placement m;
    if ((int)sp->type < 0 || sp->type >= SCENE_PRIM_TYPES || !types[sp->type].place)
        ok = -1;
    else if (types[sp->type].nparams && sp->nparams != types[sp->type].nparams)
        why = "it has the wrong number of parameters";
    else if (!placement_of(sp->mat, &m))
        why = "its matrix is not affine and invertible";
    else if (!all_finite(sp->params, sp->nparams))
        why = "a parameter is not a finite number";
    else {
        writer w = {out, 0};
        ok = types[sp->type].place(sp, &m, &w, &why);
    }
    if (ok == 1)
        return IACSG_OK;
    prim_placed_free(out);
    if (ok == 0)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory placing solid '%s'", name ? name : "");
    return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "solid '%s' (%s) is not a valid primitive: %s", name ? name : "",
                           (int)sp->type >= 0 && sp->type < SCENE_PRIM_TYPES ? types[sp->type].name : "?", why);
}

void prim_placed_free(prim_placed *out) {
    free(out->lo);
    free(out->hi);
    out->lo = out->hi = NULL;
    out->n = 0;
}

void prim_keep(scene_prim *p) {
    prim_placed *placed = p->placed ? NULL : malloc(sizeof *placed);
    iacsg_error err = {0};
    if (placed && prim_place(p, NULL, placed, &err) == IACSG_OK)
        p->placed = placed;
    else
        free(placed);
}

void prim_unkeep(scene_prim *p) {
    if (p->placed)
        prim_placed_free(p->placed);
    free(p->placed);
    p->placed = NULL;
}

int prim_world_box(const scene_prim *p, double box[6]) {
    prim_placed placed = {0};
    iacsg_error err = {0};
    int ok = p->placed || prim_place(p, NULL, &placed, &err) == IACSG_OK;
    const double *b = p->placed ? p->placed->box : placed.box;
    int bounded = ok && isfinite(b[0]) && isfinite(b[3]);
    for (int c = 0; c < 6; c++)
        box[c] = bounded ? b[c] : c < 3 ? -INFINITY : INFINITY;
    prim_placed_free(&placed);
    return bounded;
}

float prim_float_bound(double x, int upper) {
    float f = (float)x;
    if (upper ? (double)f < x : (double)f > x)
        f = nextafterf(f, upper ? INFINITY : -INFINITY);
    return upper ? ia_flush_hi_f(f) : ia_flush_lo_f(f);
}
