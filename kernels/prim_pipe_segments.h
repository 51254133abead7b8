/* kernels/prim_pipe_segments.h -- a pipe's segments along a ray in closed form (prim_segments' PIPE case, declared
 * there; this file follows prim_segments.h, whose quadrics and quartics it reuses). A pipe is the union of its parts
 * (prim.h):
 *
 *   1. each part whose box the ray meets within [ta, tend] (the t range clipped to the box, rounded outward), over
 *      that range, runs of each piece alone: its cell's start plane, its end plane, its tube and its bore's:
 *        a straight part's frustum, the cone r(w) = R0 + R1 w as a quadric (s0^2 + s1^2) - r^2 on the nappe where r
 *        grows along the ray (within the cell r >= 0, as in a quadric tgc's slab): one run;
 *        a bend's torus (prim_quartic_bounds' and prim_quartic_solve's, from the part's frame, bend radius and
 *        tube radius) walked as a quartic
 *        over the cell's possible span: its first run, and where it may be in again, the point to solve again from;
 *   2. the union swept in ray order into a quartet (prim_segments.h): at each point the greatest (OUT < BOUNDARY <
 *      IN) of each part's state (the least of its planes', its tube's and its bore's negation), and of each joint's:
 *      where a part's start plane is the end plane of the part before it, both tubes less both bores between the
 *      first's start plane and the second's end plane, which
 *      the two closed cells cover (a point is on one side of the shared plane or the other, and in that part's
 *      tube). So a ray through a joint inside the wall stays IN there, as it is, where each part alone would be
 *      BOUNDARY over the shared plane's crossing. Where a part must solve again, the quartet is cut there (the run
 *      ends, and the walk solves again from that point: prim_segments returns 2).
 * 0 (the walk bisects) for a part without a closed form (a bend whose tube reaches its axis, a ray along a cone's
 * side line), or more than PRIM_PIPE_SEGMENTS_PARTS parts met along the range.
 */
#ifndef KERNELS_PRIM_PIPE_SEGMENTS_H
#define KERNELS_PRIM_PIPE_SEGMENTS_H
#include "camera.h"

/* The most parts met along one solve, and in a pipe whose parameters the walk's array holds (kernels/segments.h,
 * in a scene with pipes: SCENE_SOLID_PIPES). */
#define PRIM_PIPE_SEGMENTS_PARTS 16
#define PRIM_PIPE_SEGMENTS_REALS (2 + 2 * PRIM_PIPE_PART_N * PRIM_PIPE_SEGMENTS_PARTS)

/* The t range [*t0, *t1] of the ray in part q's box (intervals 29-31), rounded outward, within [ta, tend]
 * (camera_clip_box); 0 when it misses or the range is a point. */
IA_FN int prim_pipe_box_range(const ia_real *q, const ia_real o[3], const ia_real d[3], ia_real ta, ia_real tend,
                              ia_real *t0, ia_real *t1) {
    ia_real lo[3] = {q[58], q[60], q[62]}, hi[3] = {q[59], q[61], q[63]};
    return camera_clip_box(lo, hi, o, d, ta, tend, t0, t1) && *t0 < *t1;
}

/* A plane of the cell, in where n.(x - a) <= 0 (sign 1) or >= 0 (sign -1): n.o - n.a + t n.d from the ray's origin
 * (n at interval at + 3, a at at). */
IA_FN void prim_pipe_cell_plane(prim_segments_span *s, const ia_real *q, int at, ia_real sign, const ia_real o[3],
                                const ia_real d[3], ia_interval range) {
    ia_interval c = ia_sub(prim_segments_dot(q, at + 3, o), prim_dot3(q, at + 3, prim_iv(q, at), prim_iv(q, at + 1),
                                                                         prim_iv(q, at + 2)));
    ia_interval b = prim_segments_dot(q, at + 3, d);
    prim_segments_plane(s, ia_mul_r(c, sign), ia_mul_r(b, sign), 0, range);
}

/* A span within [lo, hi] as a run's four changes (OUT, BOUNDARY, IN, BOUNDARY, OUT; all lo when it is empty). */
IA_FN void prim_pipe_run_of(const prim_segments_span *s, ia_real lo, ia_real hi, ia_real e[4]) {
    ia_real plo = fmax(s->plo, lo), phi = fmin(s->phi, hi), ilo = fmax(s->ilo, plo), ihi = fmin(s->ihi, phi);
    e[0] = plo < phi ? plo : lo;
    e[1] = plo < phi ? (ilo < ihi ? ilo : phi) : lo;
    e[2] = plo < phi ? (ilo < ihi ? ihi : phi) : lo;
    e[3] = plo < phi ? phi : lo;
}

/* A run's state at t, and its next change after t (or `next`, if earlier) into *next. */
IA_FN int prim_pipe_run_state(const ia_real e[4], ia_real t, ia_real *next) {
    int j = 0;
    while (j < 4 && e[j] <= t)
        j++;
    *next = j < 4 ? fmin(*next, e[j]) : *next;
    return j == 2 ? SCENE_IN : j & 1 ? SCENE_BOUNDARY : SCENE_OUT;
}

/* The lesser and the greater of two states (OUT < BOUNDARY < IN). */
IA_FN int prim_pipe_min(int a, int b) { return a == SCENE_OUT || b == SCENE_OUT ? SCENE_OUT : a == SCENE_IN ? b : a; }
IA_FN int prim_pipe_max(int a, int b) { return a == SCENE_IN || b == SCENE_IN ? SCENE_IN : a == SCENE_OUT ? b : a; }

/* A tube's run over [lo, hi] (the cell's possible span within the part's box range [t0, t0 + width]), a, b the ray
 * in the part's frame at t0: a straight part's cone r(w) = R0 + R1 w (intervals at, at + 1: the outer or the bore's)
 * as the quadric (s0^2 + s1^2) - r^2 where r >= 0 (on the nappe where r grows along the ray, as in a quadric tgc's
 * slab); a bend's torus (radius interval 25, tube radius at `at`) walked as a quartic, its coefficients from the ray
 * o + t d: its first run, and where it may be in again, *resume (else left as it is). 0 where it has no closed form. */
IA_FN int prim_pipe_tube_run(const ia_real *q, int at, const ia_real o[3], const ia_real d[3], const ia_interval a[3],
                             const ia_interval b[3], ia_real t0, ia_real width, ia_real lo, ia_real hi, ia_real eps,
                             ia_real run[4], ia_real *resume, kernel_u32 *evals) {
    prim_segments_span tube = {-IA_INF, IA_INF, -IA_INF, IA_INF, 0}, bound = tube;
    if ((int)q[0] & PRIM_PIPE_BEND) { /* the torus's radii where prim_quartic_bounds reads them (a, b in its frame) */
        ia_real tor[2 * PRIM_TOR_N] = {0};
        ia_interval r2 = ia_sqr(prim_iv(q, at));
        tor[24] = q[50];
        tor[25] = q[51];
        tor[26] = r2.lo;
        tor[27] = r2.hi;
        int of = lo < hi ? prim_quartic_bounds(PRIM_TOR, tor, a, b, &tube, &bound, t0, width) : 2;
        if (of == 0 || bound.nan)
            return 0;
        lo = fmax(lo, bound.plo);
        hi = fmin(hi, bound.phi);
        prim_quartet w = {{hi, hi, hi, hi}, 0, IA_INF, -IA_INF, IA_INF}; /* changes not reached: at its end */
        if (of == 1 && lo < hi && !prim_quartic_solve(&w, PRIM_TOR, tor, q, 13, o, d, b, lo, hi, eps, evals))
            return 0;
        for (int k = 0; k < 4; k++)
            run[k] = w.e[k];
        *resume = w.stage == 5 ? fmin(*resume, w.resume) : *resume;
        return 1;
    }
    /* along the ray (a0 + u b0)^2 + (a1 + u b1)^2 - (r0 + u r1)^2 */
    ia_interval r0 = ia_add(prim_iv(q, at), ia_mul(prim_iv(q, at + 1), a[2])), r1 = ia_mul(prim_iv(q, at + 1), b[2]);
    ia_interval aa = ia_add(ia_sqr(a[0]), ia_sqr(a[1])), ab = ia_add(ia_mul(a[0], b[0]), ia_mul(a[1], b[1]));
    ia_interval bb = ia_add(ia_sqr(b[0]), ia_sqr(b[1]));
    prim_segments_plane(&tube, ia_neg(r0), ia_neg(r1), t0, ia_make(0, width)); /* r >= 0: a mitred cell may reach
                                                                                 * past a steep cone's apex */
    if (!prim_segments_quadric(&tube, ia_sub(bb, ia_sqr(r1)), ia_sub(ab, ia_mul(r0, r1)), ia_sub(aa, ia_sqr(r0)),
                               r1.lo > 0 ? 1 : r1.hi < 0 ? -1 : 0, t0, width) ||
        tube.nan)
        return 0;
    prim_pipe_run_of(&tube, lo, hi, run);
    return 1;
}

/* Part q's runs over [t0, t1] (its box's range), each alone: its start plane's, its end plane's, its tube's and,
 * with a bore, the bore's (the part is in where it is in the planes and the tube and out of the bore), and
 * *resume, where a bend's torus may be in again (else +inf). 0 when a tube has no closed form. */
IA_FN int prim_pipe_part_runs(const ia_real *q, const ia_real o[3], const ia_real d[3], ia_real t0, ia_real t1,
                              ia_real eps, ia_real run[4][4], ia_real *resume, kernel_u32 *evals) {
    prim_segments_span all = {-IA_INF, IA_INF, -IA_INF, IA_INF, 0}, start = all, end = all;
    ia_interval at = ia_point(t0), a[3], b[3];
    ia_real width = ia_hi(t1 - t0);
    prim_pipe_cell_plane(&start, q, 1, -1, o, d, ia_make(t0, t1)); /* (x - a).t >= 0 */
    prim_pipe_cell_plane(&end, q, 7, 1, o, d, ia_make(t0, t1));    /* (x - b).u <= 0 */
    if (start.nan || end.nan)
        return 0;
    prim_pipe_run_of(&start, t0, t1, run[0]);
    prim_pipe_run_of(&end, t0, t1, run[1]);
    prim_frame(q, 13, ray_extent(o[0], d[0], at), ray_extent(o[1], d[1], at), ray_extent(o[2], d[2], at), a);
    for (int r = 0; r < 3; r++)
        b[r] = prim_segments_dot(q, 16 + 3 * r, d);
    /* the tubes are needed over the cell's possible span only */
    ia_real lo = fmax(fmax(start.plo, end.plo), t0), hi = fmin(fmin(start.phi, end.phi), t1);
    int bend = ((int)q[0] & PRIM_PIPE_BEND) != 0;
    *resume = IA_INF;
    *evals += 1;
    for (int k = 0; k < 4; k++)
        run[3][k] = lo; /* no bore: out of it all along */
    return prim_pipe_tube_run(q, bend ? 26 : 25, o, d, a, b, t0, width, lo, hi, eps, run[2], resume, evals) &&
           (!((int)q[0] & PRIM_PIPE_INNER) ||
            prim_pipe_tube_run(q, 27, o, d, a, b, t0, width, lo, hi, eps, run[3], resume, evals));
}

/* A part's state at t from its runs (*next: the runs' next change, if earlier): the least of its planes' and
 * tube's and the bore's negation; with `joint`, the runs of the part before it (prev) and the part between the
 * previous part's start plane and this one's end plane, in both tubes and out of both bores. */
IA_FN int prim_pipe_state(ia_real run[4][4], ia_real prev[4][4], int joint, ia_real t, ia_real *next) {
    int start = prim_pipe_run_state(run[0], t, next), end = prim_pipe_run_state(run[1], t, next);
    int tube = prim_pipe_min(prim_pipe_run_state(run[2], t, next),
                             SCENE_IN + SCENE_OUT - prim_pipe_run_state(run[3], t, next)); /* BOUNDARY stays */
    int state = prim_pipe_min(prim_pipe_min(start, end), tube);
    if (joint) {
        ia_real unused = *next; /* prev's changes are among its own part's */
        int before = prim_pipe_min(prim_pipe_run_state(prev[0], t, &unused),
                                   prim_pipe_min(prim_pipe_run_state(prev[2], t, &unused),
                                                 SCENE_IN + SCENE_OUT - prim_pipe_run_state(prev[3], t, &unused)));
        state = prim_pipe_max(state, prim_pipe_min(prim_pipe_min(before, end), tube));
    }
    return state;
}

/* The pipe's changes over [ta, tend] (prim_segments' contract). */
IA_FN int prim_pipe_segments(const ia_real *p, const ia_real o[3], const ia_real d[3], ia_real ta, ia_real tend,
                             ia_real eps, ia_real e[4], ia_real *resume, kernel_u32 *evals) {
    ia_real run[PRIM_PIPE_SEGMENTS_PARTS][4][4], cut = IA_INF;
    int parts = (int)p[0], met = 0, joint[PRIM_PIPE_SEGMENTS_PARTS], last = -2;
    for (int k = 0; k < parts; k++) {
        const ia_real *q = p + 2 + 2 * PRIM_PIPE_PART_N * k;
        ia_real t0, t1, again;
        if (!prim_pipe_box_range(q, o, d, ta, tend, &t0, &t1))
            continue;
        if (met == PRIM_PIPE_SEGMENTS_PARTS || !prim_pipe_part_runs(q, o, d, t0, t1, eps, run[met], &again, evals))
            return 0;
        cut = fmin(cut, again);
        joint[met] = last == k - 1 && ((int)q[0] & PRIM_PIPE_SHARES_START); /* with the part met before it */
        last = k;
        met += 1;
    }
    /* the union, from ta: the greatest state of the parts and joints at `at`, up to the next change of any */
    prim_quartet u = {{ta, ta, ta, ta}, 0, IA_INF, -IA_INF, IA_INF};
    for (ia_real at = ta; at < cut && u.stage < 5;) {
        int state = SCENE_OUT;
        ia_real next = cut;
        for (int k = 0; k < met; k++)
            state = prim_pipe_max(state, prim_pipe_state(run[k], run[k > 0 ? k - 1 : 0], joint[k], at, &next));
        prim_quartet_add(&u, at, next, state);
        at = next;
    }
    if (u.stage < 5 && cut < IA_INF) { /* a part solves again from cut: the run ends there */
        for (int j = u.stage; j < 4; j++)
            u.e[j] = cut;
        u.stage = 5;
        u.resume = cut;
    }
    for (int k = 0; k < 4; k++)
        e[k] = u.stage == 0 ? ta : u.e[k];
    *resume = u.resume;
    return u.stage == 5 ? 2 : 1;
}

#endif
