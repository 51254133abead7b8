/* tests/t_prim_walk.h -- the body of the primitive walk tests (t_prim_segments_fp.c: bisection alone, as scenes of
 * more than 64 solids run; t_prim_newton_fp.c: with interval Newton on prim_Fd, as smaller ones do). Each type
 * (kernels/prim.h, placed by implicits/prim_place.c) goes through the segment path's walk (kernels/segments.h,
 * compiled here as the device runs it) along random rays, against the exact long-double crossings of
 * tests/t_prim_ref.h:
 *
 * - every node the walk accepts as IN or OUT holds no crossing and has the reference's state (so no boundary is
 *   missed and none is late);
 * - every BOUNDARY leaf lies within PRIM_NEAR eps of the boundary: of a crossing along the ray, or, for a ray that
 *   grazes the surface, of a point where a cube of that size around the leaf meets both sides (no phantom leaves,
 *   which the weave could claim as a hit); beside an arb's sharp vertex, within that of every face's plane (the max
 *   of the faces' enclosures can hold 0 up to about PRIM_NEAR eps / sin(angle / 2) from a vertex whose faces meet
 *   at that angle).
 *
 * Random placements: a rotation, a uniform scale in mat[15] and a translation (librt's matrices), and for ell, tgc
 * and arb8 also any affine matrix (librt applies it to their points and vectors); rays aimed at
 * random points of the box and at the features: arb vertices and edges, along the axes of cylinders, cones and
 * tori, through a torus's hole and its plane, along pipes' segments.
 *
 * The including file defines PRIM_WALK_NAME (the tests' prefix) and, for Newton, SCENE_SOLID_FD.
 */
#ifndef T_PRIM_WALK_H
#define T_PRIM_WALK_H
#include "implicits/prim_place.h"
#include "kernels/prim.h"
#include "kernels/scene_prims.h"
#include "t_prim_ref.h"
#include "test.h"
#include <stdio.h>

static int host_type;
static ia_real *host_params, *host_table;

/* The device's dispatchers for one primitive solid (the walks' closed forms read its parameters from the scene's
 * table, host_table, through kernels/scene_prims.h's scene_solid_P, as the device does). */
static ia_interval scene_solid_F(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t) {
    (void)q, (void)k, (void)t;
    return prim_F(host_type, host_params, x, y, z);
}
#ifdef SCENE_SOLID_FD
static ia_interval scene_solid_Fd(scene_prims q, int k, ia_interval x, ia_interval y, ia_interval z, ia_interval t,
                                  ia_interval dx, ia_interval dy, ia_interval dz, ia_interval *dt) {
    (void)q, (void)k, (void)t;
    return prim_Fd(host_type, host_params, x, y, z, dx, dy, dz, dt);
}
#endif

#include "kernels/segments.h"


/* A BOUNDARY leaf must be this many eps from the boundary at most. */
#define PRIM_NEAR 4

/* ---- random primitives */

static double rnd(test_rng_t *rng, double lo, double hi) { return lo + (hi - lo) * test_rand_unit(rng); }

/* A random rotation (rows), from a unit quaternion. */
static void random_rotation(test_rng_t *rng, double r[9]) {
    double q[4], len = 0;
    for (int k = 0; k < 4; k++) {
        q[k] = rnd(rng, -1, 1);
        len += q[k] * q[k];
    }
    len = sqrt(len);
    double w = q[0] / len, x = q[1] / len, y = q[2] / len, z = q[3] / len;
    double m[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                   2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                   2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    memcpy(r, m, sizeof m);
}

/* librt's kind of matrix: rotation, translation, mat[15] = 1 / scale. */
static void random_matrix(test_rng_t *rng, double mat[16], double *scale) {
    double r[9];
    random_rotation(rng, r);
    *scale = rnd(rng, 0.5, 4);
    memset(mat, 0, 16 * sizeof(double));
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            mat[4 * i + j] = r[3 * i + j];
        mat[4 * i + 3] = rnd(rng, -10, 10);
    }
    mat[15] = 1 / *scale;
}

/* Any affine matrix: a rotation times a non-uniform scale times a shear, over mat[15]. librt applies such a matrix
 * to an ell's, a tgc's and an arb's points and vectors as it is (other types take it for a rotation); *scale: the
 * smallest stretch, so that eps stays below the primitive's features. */
static void random_affine(test_rng_t *rng, double mat[16], double *scale) {
    double r[9], m[9], k[3] = {rnd(rng, 0.5, 2), rnd(rng, 0.5, 2), rnd(rng, 0.5, 2)}, shear = rnd(rng, -0.5, 0.5);
    random_matrix(rng, mat, scale);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r[3 * i + j] = mat[4 * i + j];
    for (int i = 0; i < 3; i++) /* r diag(k) (1 + shear e0 e1^T) */
        for (int j = 0; j < 3; j++)
            m[3 * i + j] = r[3 * i + j] * k[j] + (j == 1 ? r[3 * i] * k[0] * shear : 0);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            mat[4 * i + j] = m[3 * i + j];
    *scale = fmin(fmin(k[0], k[1]), k[2]) * 0.5 / mat[15];
}

/* A dyadic number in [lo, hi] on a grid of 1/8 (arb vertices: their planes are exact). */
static double grid(test_rng_t *rng, double lo, double hi) { return floor(rnd(rng, lo, hi) * 8) / 8; }

/* Fills params with a random primitive of the type (in its own frame); returns the count. `variant` picks a
 * special case (rcc, cone, arb4, ...). */
static int random_prim(test_rng_t *rng, int type, int variant, double *q) {
    double r[9];
    random_rotation(rng, r);
    switch (type) {
    case SCENE_PRIM_HALF: {
        double len = rnd(rng, 0.5, 2);
        for (int c = 0; c < 3; c++)
            q[c] = r[c] * len;
        q[3] = rnd(rng, -1, 1);
        return 4;
    }
    case SCENE_PRIM_ELL:
        for (int c = 0; c < 3; c++)
            q[c] = rnd(rng, -1, 1);
        for (int a = 0; a < 3; a++) {
            double len = variant == 1 ? 1 : rnd(rng, 0.2, 1.5); /* variant 1: a sphere */
            for (int c = 0; c < 3; c++)
                q[3 + 3 * a + c] = r[3 * a + c] * len;
        }
        return 12;
    case SCENE_PRIM_TGC: {
        double la = rnd(rng, 0.2, 1), lb = variant == 1 ? la : rnd(rng, 0.2, 1), h[3], hd = 0;
        static const double tops[][2] = {{1, 1}, {0.5, 0.5}, {0, 0}, {1.5, 0.4}, {0, 1}}; /* rcc, trc, cone, tgc */
        const double *k = tops[variant % 5];
        do { /* a height not too near the base's plane: a sheared cylinder at worst */
            hd = 0;
            for (int c = 0; c < 3; c++) {
                h[c] = variant < 2 ? r[6 + c] * rnd(rng, 0.5, 2) : rnd(rng, -2, 2);
                hd += h[c] * r[6 + c];
            }
        } while (fabs(hd) < 0.5);
        for (int c = 0; c < 3; c++) {
            q[c] = rnd(rng, -1, 1);
            q[3 + c] = h[c];
            q[6 + c] = r[c] * la;
            q[9 + c] = r[3 + c] * lb;
            q[12 + c] = r[c] * la * k[0];
            q[15 + c] = r[3 + c] * lb * k[1];
        }
        return 18;
    }
    case SCENE_PRIM_TOR: {
        double ra = rnd(rng, 0.5, 1.5);
        for (int c = 0; c < 3; c++) {
            q[c] = rnd(rng, -1, 1);
            q[3 + c] = r[c] * rnd(rng, 0.5, 2);
        }
        q[6] = ra;
        q[7] = rnd(rng, 0.1, 0.9) * ra;
        return 8;
    }
    case SCENE_PRIM_EHY: {
        double r1 = rnd(rng, 0.5, 1.5), hl = rnd(rng, 0.5, 2);
        for (int c = 0; c < 3; c++) {
            q[c] = rnd(rng, -1, 1);
            q[3 + c] = r[6 + c] * hl;
            q[6 + c] = r[c];
        }
        q[9] = r1;
        q[10] = rnd(rng, 0.2, 1) * r1;
        q[11] = rnd(rng, 0.1, 1);
        return 12;
    }
    case SCENE_PRIM_ARB8: {
        double x0 = grid(rng, -1, 0), x1 = grid(rng, 0.25, 1), y0 = grid(rng, -1, 0), y1 = grid(rng, 0.25, 1);
        double z0 = grid(rng, -1, 0), z1 = grid(rng, 0.25, 1), cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
        double inset = grid(rng, 0, 0.2);
        double base[4][3] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}};
        double top[4][3] = {{x0 + inset, y0 + inset, z1}, {x1 - inset, y0 + inset, z1}, {x1 - inset, y1 - inset, z1},
                            {x0 + inset, y1 - inset, z1}};
        double apex[3] = {cx, cy, z1}, ridge0[3] = {x0, cy, z1}, ridge1[3] = {x1, cy, z1};
        const double *v[8];
        switch (variant % 4) {
        case 0: /* arb8: a frustum of a box */
            for (int k = 0; k < 4; k++)
                v[k] = base[k], v[4 + k] = top[k];
            break;
        case 1: /* arb5: a pyramid */
            for (int k = 0; k < 4; k++)
                v[k] = base[k], v[4 + k] = apex;
            break;
        case 2: /* arb6: a wedge, the top a ridge (librt: 1 2 3 4 5 5 6 6) */
            for (int k = 0; k < 4; k++)
                v[k] = base[k];
            v[4] = v[5] = ridge0;
            v[6] = v[7] = ridge1;
            break;
        default: /* arb4: a tetrahedron (librt: 1 2 3 3 4 4 4 4) */
            v[0] = base[0], v[1] = base[1], v[2] = v[3] = base[2];
            for (int k = 4; k < 8; k++)
                v[k] = apex;
        }
        for (int k = 0; k < 8; k++)
            memcpy(q + 3 * k, v[k], 3 * sizeof(double));
        return 24;
    }
    default: { /* a pipe: 3 to 5 points turning by 30 to 150 degrees, long enough for their bends */
        int n = 3 + (int)(test_rand_u64(rng) % 3);
        double p[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, od = rnd(rng, 0.3, 0.6);
        for (int i = 0; i < n; i++) {
            double *pt = q + 6 * i;
            memcpy(pt, p, sizeof p);
            pt[3] = od * rnd(rng, 0.8, 1.2);
            pt[4] = variant % 2 ? 0 : pt[3] * rnd(rng, 0.3, 0.7);
            pt[5] = variant % 3 == 2 ? 0 : pt[3] * rnd(rng, 1, 1.5); /* some sharp corners */
            double len = rnd(rng, 3, 5);
            for (int c = 0; c < 3; c++)
                p[c] += dir[c] * len;
            double turn = rnd(rng, 0.5, 2.6), axis[3], rr[9];
            random_rotation(rng, rr);
            double nd = 0;
            for (int c = 0; c < 3; c++)
                nd += rr[c] * dir[c];
            for (int c = 0; c < 3; c++)
                axis[c] = rr[c] - nd * dir[c];
            double al = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
            for (int c = 0; c < 3; c++)
                dir[c] = dir[c] * cos(turn) + axis[c] / al * sin(turn);
        }
        return 6 * n;
    }
    }
}

/* ---- rays */

typedef struct {
    ia_real o[3], d[3];
} test_ray;

/* A point of the primitive's box, or of one of its features (local frame, then placed). */
static void feature_point(test_rng_t *rng, const scene_prim *sp, const double box[6], double target[3],
                          double axis[3]) {
    const double *q = sp->params;
    double local[3] = {0, 0, 0};
    int kind = (int)(test_rand_u64(rng) % 3);
    axis[0] = axis[1] = axis[2] = 0;
    if (kind == 0 || sp->type == SCENE_PRIM_HALF) {
        for (int c = 0; c < 3; c++)
            target[c] = rnd(rng, box[c], box[c + 3]);
        return;
    }
    switch (sp->type) {
    case SCENE_PRIM_ARB8: { /* a vertex, or a point of an edge */
        int a = (int)(test_rand_u64(rng) % 8), b = (int)(test_rand_u64(rng) % 8);
        double u = kind == 1 ? 0 : test_rand_unit(rng);
        for (int c = 0; c < 3; c++)
            local[c] = q[3 * a + c] + u * (q[3 * b + c] - q[3 * a + c]);
        break;
    }
    case SCENE_PRIM_TGC:
    case SCENE_PRIM_ELL:
        if (kind == 2) { /* on the surface (a tgc's side), along a tangent: a grazing ray */
            int ell = sp->type == SCENE_PRIM_ELL;
            double phi = rnd(rng, 0, 6.283185307179586), w = ell ? rnd(rng, -0.95, 0.95) : rnd(rng, 0.05, 0.95);
            double len2[4] = {0, 0, 0, 0}; /* a tgc's |A|^2, |B|^2, |C|^2, |D|^2 */
            for (int k = 0; k < 4 && !ell; k++)
                for (int c = 0; c < 3; c++)
                    len2[k] += q[6 + 3 * k + c] * q[6 + 3 * k + c];
            double ca = ell ? sqrt(1 - w * w) : 1 + w * (sqrt(len2[2] / len2[0]) - 1); /* the radii at w */
            double cb = ell ? ca : 1 + w * (sqrt(len2[3] / len2[1]) - 1);
            double s[3] = {ca * cos(phi), cb * sin(phi), w}, t[3] = {-ca * sin(phi), cb * cos(phi), 0};
            const double *e0 = ell ? q + 3 : q + 6, *e1 = ell ? q + 6 : q + 9, *e2 = ell ? q + 9 : q + 3;
            for (int c = 0; c < 3; c++) {
                local[c] = q[c] + s[0] * e0[c] + s[1] * e1[c] + s[2] * e2[c];
                axis[c] = t[0] * e0[c] + t[1] * e1[c];
            }
            break;
        }
        /* fall through */
    case SCENE_PRIM_EHY: /* on the axis, along it */
    case SCENE_PRIM_TOR:
        for (int c = 0; c < 3; c++) {
            local[c] = q[c];
            axis[c] = q[3 + c];
        }
        break;
    default: { /* along a pipe's segment */
        int i = (int)(test_rand_u64(rng) % (uint64_t)(sp->nparams / 6 - 1));
        for (int c = 0; c < 3; c++) {
            local[c] = q[6 * i + c];
            axis[c] = q[6 * (i + 1) + c] - q[6 * i + c];
        }
    }
    }
    const double *m = sp->mat;
    double placed_axis[3];
    for (int r = 0; r < 3; r++) {
        target[r] = (m[4 * r] * local[0] + m[4 * r + 1] * local[1] + m[4 * r + 2] * local[2] + m[4 * r + 3]) / m[15];
        placed_axis[r] = m[4 * r] * axis[0] + m[4 * r + 1] * axis[1] + m[4 * r + 2] * axis[2];
    }
    memcpy(axis, placed_axis, sizeof placed_axis);
    if (kind == 1 && sp->type == SCENE_PRIM_TOR) /* in the torus's plane, through its centre */
        axis[0] = axis[1] = axis[2] = 0;
}

/* ---- one ray: the walk against the reference */

typedef struct {
    long rays, nodes, boundary_leaves, grazing_leaves, vertex_leaves;
    long closed;         /* rays walked by a closed form (kernels/prim_segments.h) */
    double closed_worst; /* their farthest BOUNDARY from a crossing, in eps: a quadric's enclosures are a few ulps */
    int quartic;         /* the primitive is walked as a quartic: its leaves where it is not monotone are of eps */
    double quartic_worst; /* their farthest BOUNDARY from a crossing, in eps (within PRIM_NEAR as any leaf) */
    unsigned long long evals;
    double worst; /* the farthest BOUNDARY leaf from a crossing along the ray, in eps */
} tally;

/* Whether a cube of half-size h around the line's point at t (local frame) meets both the inside and the outside,
 * on a grid of 9^3 points (fine enough for the thin wedges at a pipe's mitred corner and the cones at an arb's
 * vertices that the tests make: they open by at least 0.5 radians). */
static int meets_both(const scene_prim *sp, const ref_line *r, ld t, ld h) {
    ld p[3];
    ref_at(r, t, p);
    int in = 0, out = 0;
    for (int k = 0; k < 729 && !(in && out); k++) {
        ld x[3] = {p[0] + (k % 9 - 4) * h / 4, p[1] + (k / 9 % 9 - 4) * h / 4, p[2] + (k / 81 - 4) * h / 4};
        *(prim_ref_inside_local(sp, x) ? &in : &out) = 1;
    }
    return in && out;
}

/* Whether the line's point at t (local frame) is within h of every face's plane of the arb. */
static int near_every_face(const scene_prim *sp, const ref_line *r, ld t, ld h) {
    ld planes[6][4], p[3];
    int n = ref_arb_planes(sp->params, planes);
    ref_at(r, t, p);
    for (int k = 0; k < n; k++)
        if ((ref_dot(planes[k], p) - planes[k][3]) / ref_norm(planes[k]) > h)
            return 0;
    return 1;
}

static void check_ray(const scene_prim *sp, double scale, const test_ray *ray, ia_real ta, ia_real w, ia_real eps,
                      tally *tl) {
    ld o[3], d[3];
    for (int c = 0; c < 3; c++)
        o[c] = ray->o[c], d[c] = ray->d[c];
    ref_line line = ref_local_line(sp->mat, o, d);
    ia_real range[2] = {ta, w}, pos[1], newton_t[2];
    int solid[1] = {0}, level[1], newton[1];
    bisect_index index[1];
    segments_walks walk = {solid, range, pos, level, index, newton, newton_t, 0, 0, host_table};
    segments_start(&walk, 0);
    ia_real end = node_bound(ta, w, 0, 1);
    ld cross[REF_MAX_CROSSINGS];
    int inside0, ncross = prim_ref_crossings(sp, &line, (ld)ta, (ld)end, cross, &inside0);
    kernel_u32 evals = 0;
    ld len = sqrtl(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    int guard = 0;
    while (pos[0] < IA_INF) {
        ia_real a = pos[0];
        int s = segments_step(&walk, 0, ray->o, ray->d, eps, ia_point(0), &evals);
        tl->closed += guard == 0 && level[0] == SEGMENTS_CLOSED;
        ia_real b = pos[0] < IA_INF ? pos[0] : end;
        if (s == SCENE_OUT && !(b > a)) /* the final OUT at the range's end */
            break;
        CHECK(++guard < 1000000, "the walk does not end");
        tl->nodes++;
        ld tol = 1e-12L * (fabsl((ld)a) + fabsl((ld)b) + 1);
        int near = 0;
        ld nearest = INFINITY;
        for (int k = 0; k < ncross; k++) {
            CHECK(s == SCENE_BOUNDARY || !(cross[k] > a + tol && cross[k] < b - tol),
                  "type %d: a %s node [%.17g, %.17g] holds the crossing at %.20Lg", sp->type,
                  s == SCENE_IN ? "IN" : "OUT",
                  (double)a, (double)b, cross[k]);
            ld gap = cross[k] < a ? a - cross[k] : cross[k] > b ? cross[k] - b : 0;
            nearest = fminl(nearest, gap);
        }
        ld p[3];
        ref_at(&line, (ld)a + ((ld)b - (ld)a) / 2, p);
        int in = prim_ref_inside_local(sp, p);
        if (s != SCENE_BOUNDARY) {
            CHECK((s == SCENE_IN) == in, "type %d: node [%.9g, %.9g] is %s, the reference %s", sp->type, (double)a,
                  (double)b, s == SCENE_IN ? "IN" : "OUT", in ? "inside" : "outside");
            continue;
        }
        tl->boundary_leaves++;
        near = nearest * len <= PRIM_NEAR * eps;
        if (near) {
            tl->worst = fmax(tl->worst, (double)(nearest * len / eps));
            if (level[0] == SEGMENTS_CLOSED) {
                double *worst = tl->quartic ? &tl->quartic_worst : &tl->closed_worst;
                *worst = fmax(*worst, (double)(nearest * len / eps));
            }
            continue;
        }
        /* a graze: the boundary passes within PRIM_NEAR eps of the leaf in space (the cube in the local frame,
         * eps scaled back by the matrix's scale) */
        tl->grazing_leaves++;
        ld mid = (ld)a + ((ld)b - (ld)a) / 2, h = (ld)PRIM_NEAR * eps / scale;
        if (meets_both(sp, &line, mid, h))
            continue;
        /* an arb's enclosure is the max of its faces' (each tight): beside a vertex where faces meet at a small
         * angle it may hold 0 farther out, but never where a face is more than the leaf's reach away */
        tl->vertex_leaves++;
        CHECK(sp->type == SCENE_PRIM_ARB8 && near_every_face(sp, &line, mid, h),
              "type %d: a BOUNDARY leaf [%.9g, %.9g] is %.3Lg eps from the boundary", sp->type, (double)a, (double)b,
              nearest * len / eps);
    }
    tl->rays++;
    tl->evals += evals;
}

/* The primitive's parameters in the working precision, rounded outward. */
static ia_real *params_of(const prim_placed *pl) {
    ia_real *p = malloc(sizeof(ia_real) * 2 * (size_t)pl->n);
    CHECK(p, "out of memory");
    for (int k = 0; k < pl->n; k++) {
#ifdef IA_FP64
        p[2 * k] = pl->lo[k];
        p[2 * k + 1] = pl->hi[k];
#else
        p[2 * k] = prim_float_bound(pl->lo[k], 0);
        p[2 * k + 1] = prim_float_bound(pl->hi[k], 1);
#endif
    }
    return p;
}

/* The scene's table of primitives (kernels/scene_prims.h) holding the one solid, solid 0, as the device reads it. */
static ia_real *table_of(int type, const ia_real *params, int nreal) {
    int at = SCENE_PRIMS_HEADER + SCENE_PRIMS_ENTRY, padded = (nreal + SCENE_PRIMS_ALIGN - 1) / SCENE_PRIMS_ALIGN *
                                                              SCENE_PRIMS_ALIGN;
    ia_real *t = calloc((size_t)(at + padded), sizeof *t);
    CHECK(t, "out of memory");
    t[0] = 1;
    t[SCENE_PRIMS_HEADER] = (ia_real)type;
    t[SCENE_PRIMS_HEADER + 1] = (ia_real)at;
    t[SCENE_PRIMS_HEADER + 2] = (ia_real)padded;
    memcpy(t + at, params, sizeof *t * (size_t)nreal);
    return t;
}

/* The t range of the ray in the box (long double, rounded outward); 0 when it misses. */
static int clip(const double box[6], const test_ray *ray, ia_real *ta, ia_real *w) {
    ld lo = 0, hi = INFINITY;
    for (int c = 0; c < 3; c++) {
        if (ray->d[c] == 0) {
            if (ray->o[c] < box[c] || ray->o[c] > box[c + 3])
                return 0;
            continue;
        }
        ld t1 = (box[c] - (ld)ray->o[c]) / ray->d[c], t2 = (box[c + 3] - (ld)ray->o[c]) / ray->d[c];
        lo = fmaxl(lo, fminl(t1, t2));
        hi = fminl(hi, fmaxl(t1, t2));
    }
    if (!(lo < hi))
        return 0;
    *ta = (ia_real)lo;
    if ((ld)*ta > lo)
        *ta = nextafter(*ta, -IA_INF);
    *w = (ia_real)(hi - (ld)*ta);
    for (ia_real step = *w * IA_REAL_EPS + IA_REAL_MIN_NORMAL; (ld)node_bound(*ta, *w, 0, 1) < hi; step *= 2)
        *w += step;
    return 1;
}

#ifdef SCENE_SOLID_PRIMS
/* A packet's beam around the ray (kernels/prim_segments.h's prim_segments_beam_out): 16 rays on a 4 x 4 grid of
 * spacing h, of one direction and origins apart (an orthographic camera's) or one origin and directions apart (a
 * perspective one's), and 16 more at random within their hulls. Where the beam is proven out over [ta, tend] (the
 * hull of the grid rays' ranges in the box), no ray with its origin and direction in the hulls may cross the
 * primitive there, nor start inside it. Counts the beams tried and proven out. */
static void check_beam(test_rng_t *rng, const scene_prim *sp, const double box[6], double scale, const test_ray *ray,
                       long *beams, long *out) {
    enum { GRID = 16, RAYS = 32 };
    int ortho = test_rand_u64(rng) % 2;
    double h = scale * ldexp(1, -(int)(test_rand_u64(rng) % 12)) * (ortho ? 0.3 : 0.01), u[3], v[3];
    for (int c = 0; c < 3; c++) {
        u[c] = rnd(rng, -h, h);
        v[c] = rnd(rng, -h, h);
    }
    test_ray rays[RAYS];
    ia_interval o[3], d[3];
    ia_real ta = IA_INF, tend = -IA_INF;
    for (int k = 0; k < GRID; k++) {
        double i = k % 4, j = k / 4;
        for (int c = 0; c < 3; c++) {
            rays[k].o[c] = ortho ? (ia_real)(ray->o[c] + i * u[c] + j * v[c]) : ray->o[c];
            rays[k].d[c] = ortho ? ray->d[c] : (ia_real)(ray->d[c] + i * u[c] + j * v[c]);
            o[c] = k ? ia_hull(o[c], ia_point(rays[k].o[c])) : ia_point(rays[k].o[c]);
            d[c] = k ? ia_hull(d[c], ia_point(rays[k].d[c])) : ia_point(rays[k].d[c]);
        }
        ia_real a, w;
        if (clip(box, &rays[k], &a, &w)) {
            ta = fmin(ta, a);
            tend = fmax(tend, node_bound(a, w, 0, 1));
        }
    }
    if (!(ta < tend))
        return;
    for (int k = GRID; k < RAYS; k++)
        for (int c = 0; c < 3; c++) {
            rays[k].o[c] = (ia_real)rnd(rng, o[c].lo, o[c].hi);
            rays[k].d[c] = (ia_real)rnd(rng, d[c].lo, d[c].hi);
        }
    *beams += 1;
    if (!prim_segments_beam_out(host_type, host_params, o, d, ta, tend))
        return;
    *out += 1;
    for (int k = 0; k < RAYS; k++) {
        ld lo[3], ld_[3], cross[REF_MAX_CROSSINGS];
        for (int c = 0; c < 3; c++)
            lo[c] = rays[k].o[c], ld_[c] = rays[k].d[c];
        ref_line line = ref_local_line(sp->mat, lo, ld_);
        int inside0, n = prim_ref_crossings(sp, &line, (ld)ta, (ld)tend, cross, &inside0);
        CHECK(n == 0 && !inside0, "type %d: a beam proven out, but its ray %d %s over [%.9g, %.9g]", sp->type, k,
              n ? "crosses the primitive" : "starts inside", (double)ta, (double)tend);
    }
}
#endif

#ifdef SCENE_SOLID_PRIMS
/* The direction terms kept for later rays (prim_dirs): a solve that fills them and one that takes them give what a
 * solve without them gives, bit for bit. */
static void check_dirs(const test_ray *ray, ia_real ta, ia_real w, ia_real eps) {
    ia_interval dir[PRIM_DIRS_INTERVALS];
    ia_real e[3][4], resume[3] = {0, 0, 0}, end = node_bound(ta, w, 0, 1);
    kernel_u32 evals = 0;
    int r[3];
    for (int k = 0; k < 3; k++)
        r[k] = prim_segments(host_type, host_params, ray->o, ray->d, ta, end, eps, e[k], &resume[k], &evals,
                             k ? dir : 0, k == 2);
    for (int k = 1; k < 3; k++)
        CHECK(r[k] == r[0] && (r[0] == 0 || (memcmp(e[k], e[0], sizeof e[0]) == 0 && resume[k] == resume[0])),
              "type %d: a solve %s the kept direction terms differs from one without them", host_type,
              k == 1 ? "keeping" : "taking");
}
#endif

static void run_type(int type, int variants, const char *name) {
    test_rng_t *rng = test_rng();
    tally tl = {0};
    long prims = test_iters(40), per_prim = 30, closable_rays = 0, closed_of_closable = 0;
#ifdef SCENE_SOLID_PRIMS
    long beams = 0, beams_out = 0;
    test_rng_t beam_rng = *rng; /* a stream of its own: the rays above stay those of the tests before */
    beam_rng.s[0] ^= 0x9e3779b97f4a7c15u;
#endif
    for (long it = 0; it < prims; it++) {
        /* every type has a closed form (a tgc's variants 0-2, rec, rcc or trc and cone, are quadrics, the others
         * and the torus quartics, kernels/prim_segments.h; a pipe's bends too) */
        int closable = 1;
        tl.quartic = type == SCENE_PRIM_TOR || type == SCENE_PRIM_PIPE || (type == SCENE_PRIM_TGC && it % variants >= 3);
        double q[64], mat[16], scale;
        int n = random_prim(rng, type, (int)(it % variants), q);
        int affine = it % 3 == 2 && (type == SCENE_PRIM_ELL || type == SCENE_PRIM_TGC || type == SCENE_PRIM_ARB8);
        if (affine)
            random_affine(rng, mat, &scale);
        else
            random_matrix(rng, mat, &scale);
        scene_prim sp = {type, n, q, {0}, NULL};
        memcpy(sp.mat, mat, sizeof mat);
        prim_placed pl;
        iacsg_error err = {0};
        CHECK(prim_place(&sp, name, &pl, &err) == IACSG_OK, "%s: %s", name, err.message);
        double box[6];
        memcpy(box, pl.box, sizeof box);
        if (type == SCENE_PRIM_HALF) /* unbounded: a box around its placement */
            for (int c = 0; c < 3; c++)
                box[c] = mat[4 * c + 3] - 8 * scale, box[c + 3] = mat[4 * c + 3] + 8 * scale;
        host_type = pl.type;
        host_params = params_of(&pl);
        host_table = table_of(pl.type, host_params, 2 * pl.n);
        ia_real eps = (ia_real)(1e-3 * scale);
        for (long k = 0; k < per_prim; k++) {
            double target[3], axis[3], dir[3], dl = 0;
            feature_point(rng, &sp, box, target, axis);
            int along = axis[0] != 0 || axis[1] != 0 || axis[2] != 0;
            for (int c = 0; c < 3; c++) {
                dir[c] = along && k % 2 ? axis[c] : rnd(rng, -1, 1);
                dl += dir[c] * dir[c];
            }
            dl = sqrt(dl);
            test_ray ray;
            for (int c = 0; c < 3; c++) {
                ray.d[c] = (ia_real)(dir[c] / dl);
                ray.o[c] = (ia_real)(target[c] - 40 * scale * dir[c] / dl);
            }
            ia_real ta, w;
            long closed = tl.closed;
            if (!clip(box, &ray, &ta, &w))
                continue;
            check_ray(&sp, scale, &ray, ta, w, eps, &tl);
#ifdef SCENE_SOLID_PRIMS
            check_beam(&beam_rng, &sp, box, scale, &ray, &beams, &beams_out);
            if (type != SCENE_PRIM_PIPE)
                check_dirs(&ray, ta, w, eps);
#endif
            closable_rays += closable;
            closed_of_closable += closable && tl.closed > closed;
        }
        free(host_params);
        free(host_table);
        prim_placed_free(&pl);
    }
    test_note("%s: %ld rays, %.1f evaluations per ray; %ld boundary leaves, at most %.2f eps from a crossing, %ld "
              "beside a graze (%ld only near every face at a sharp arb vertex)",
              name, tl.rays, (double)tl.evals / (double)(tl.rays ? tl.rays : 1), tl.boundary_leaves, tl.worst,
              tl.grazing_leaves, tl.vertex_leaves);
    CHECK(tl.rays > prims * per_prim / 3, "%s: too few rays met the box (%ld)", name, tl.rays);
#ifdef SCENE_SOLID_PRIMS /* the closed forms take every ray they can decide, and only those types' */
    test_note("%s: %ld of %ld rays walked in closed form (quartics' BOUNDARY at most %.2f eps from a crossing)", name,
              tl.closed, closable_rays, tl.quartic_worst);
    CHECK(tl.closed == closed_of_closable && closed_of_closable >= closable_rays * 97 / 100,
          "%s: %ld rays in closed form, %ld of the %ld that have one", name, tl.closed, closed_of_closable,
          closable_rays);
    CHECK(tl.closed_worst <= 0.05, "%s: a closed form's BOUNDARY %.3g eps from its crossing", name, tl.closed_worst);
    int beam_type = type == SCENE_PRIM_ELL || type == SCENE_PRIM_EHY || type == SCENE_PRIM_TGC;
    test_note("%s: %ld of %ld beams of 16 rays around them proven out", name, beams_out, beams);
    CHECK(beam_type ? beams_out > beams / 50 : beams_out == 0, "%s: %ld of %ld beams proven out", name, beams_out,
          beams);
#else
    CHECK(tl.closed == 0, "%s: %ld rays in closed form without SCENE_SOLID_PRIMS", name, tl.closed);
#endif
}

#endif
