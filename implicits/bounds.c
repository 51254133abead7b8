/* implicits/bounds.c -- iacsg_expr_bounds: a box proven (by double interval evaluation) to hold the surface.
 *
 * Stages:
 *   1. Over all of space: for each side of each axis, a binary search over candidate planes finds the tightest
 *      plane beyond which the half-space (unbounded in the other two axes too) is proven free of zeros, for
 *      every t of the time interval. Interval arithmetic takes infinite bounds (ia/ia.h), so a half-space is a
 *      box like any other: sqr([2, inf]) + sqr([-inf, inf]) - 1 is [3, inf].
 *   2. When stage 1 cannot prove a half-space (natural interval arithmetic often fails over unbounded boxes:
 *      x^4 - 5x^2 over [2, inf] is inf - inf, [-inf, inf]), the same search inside the cube [-C, C]^3 only
 *      (C = IACSG_BOUNDS_CUBE), and the result says that nothing was proven outside the cube.
 * A slab counts as proven when adaptive bisection (a budget of BOUNDS_BUDGET evaluations) covers it with
 * boxes whose enclosure excludes 0, or is empty (f is undefined there: no surface). Unbounded sides are split
 * in the compactified coordinate x / (S + |x|), which maps the reals onto (-1, 1): [S, inf] splits at 3 S,
 * then 7 S, ... The time interval is bisected like the space. The total work is capped (BOUNDS_WORK per stage):
 * for an expression of a million nodes the search gives up rather than take minutes. */
#include "eval.h"
#include "expr_internal.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BOUNDS_SCALE 1024.0 /* S above: below it the split is close to the plain midpoint */
#define BOUNDS_BUDGET 10000 /* bretzel4 needs ~10^4 in y (3000 proved it 128 deep) */
#define BOUNDS_WORK 30000000.0 /* node evaluations per stage: about a tenth of a second; huge DAGs give up */
#define BOUNDS_TOP_SPACE 100   /* stage 1 looks for planes up to 2^100 */

typedef struct {
    const iacsg_expr *e;
    void *scratch;
    double (*stack)[8];
    double time[2], time_scale; /* time_scale: 1 / the time interval's width, 0 for a point or no t */
    double half;                /* the domain: [-half, half]^3, half = inf for all of space */
    double work_left;           /* below 0: out of work, no bounds */
} prover;

/* The compactified coordinate, in [-1, 1]. */
static double compact(double x) { return isinf(x) ? copysign(1, x) : x / (BOUNDS_SCALE + fabs(x)); }

/* A point strictly inside (lo, hi) that halves it in the compactified coordinate; NaN when the doubles
 * between them are too few to split. */
static double split_space(double lo, double hi) {
    double m = 0.5 * (compact(lo) + compact(hi)), x = BOUNDS_SCALE * m / (1 - fabs(m));
    if (!(x > lo && x < hi))
        x = lo * 0.5 + hi * 0.5; /* where the compactified coordinate has too few digits */
    return x > lo && x < hi ? x : NAN;
}

/* 1 if f has no zero in the box (x0,x1,y0,y1,z0,z1) for any t in p->time. */
static int no_zero_in(prover *p, const double box[6]) {
    int top = 0, evals = 0;
    memcpy(p->stack[top], box, 6 * sizeof(double));
    p->stack[top][6] = p->time[0];
    p->stack[top][7] = p->time[1];
    top++;
    while (top > 0) {
        double b[8], r[2];
        memcpy(b, p->stack[--top], sizeof b);
        p->work_left -= p->e->count;
        if (++evals > BOUNDS_BUDGET || p->work_left < 0)
            return 0;
        eval_dag_f64(&p->e->simple, p->e->order, p->e->count, b, p->scratch, r);
        if (!(r[0] <= 0 && r[1] >= 0))
            continue;
        /* the widest side, each measured against its whole range: morph(a, b, t) needs t split to be proven */
        int axis = 0;
        double widest = -1;
        for (int a = 0; a < 4; a++) {
            double w = a < 3 ? 0.5 * (compact(b[2 * a + 1]) - compact(b[2 * a])) : (b[7] - b[6]) * p->time_scale;
            if (w > widest)
                axis = a, widest = w;
        }
        double lo = b[2 * axis], hi = b[2 * axis + 1];
        double mid = axis < 3 ? split_space(lo, hi) : lo * 0.5 + hi * 0.5;
        if (!(mid > lo && mid < hi))
            return 0; /* a zero (or something indistinguishable from one) at the resolution of doubles */
        memcpy(p->stack[top], b, sizeof b);
        p->stack[top][2 * axis + 1] = mid;
        memcpy(p->stack[top + 1], b, sizeof b);
        p->stack[top + 1][2 * axis] = mid;
        top += 2;
    }
    return 1;
}

/* The slab of the domain where side * coordinate[axis] >= v. */
static int slab_is_empty(prover *p, int axis, int side, double v) {
    double box[6] = {-p->half, p->half, -p->half, p->half, -p->half, p->half};
    if (side > 0)
        box[2 * axis] = v;
    else
        box[2 * axis + 1] = -v;
    return no_zero_in(p, box);
}

/* Candidate plane positions j = 0 .. 2 top, increasing: 0 at j = top, +-2^(k/4) for 2^-4 <= |v| <= 2^((top - 17)/4). */
static double candidate(int j, int top) {
    int k = j - top;
    if (k == 0)
        return 0;
    double m = pow(2.0, (abs(k) - 17) / 4.0); /* |k| = 1 gives 2^-4 */
    return k < 0 ? -m : m;
}

/* Stage 1 or 2 in the domain p->half: 1 and the box (x0,x1,y0,y1,z0,z1) if every side's search succeeds. */
static int search(prover *p, double result[6]) {
    /* the last candidate: the cube's face (a plane: proven when f has no zero on it, or none at all), or
     * 2^BOUNDS_TOP_SPACE in all of space */
    int top = isinf(p->half) ? 4 * BOUNDS_TOP_SPACE + 17 : (int)(4 * log2(p->half)) + 17;
    for (int axis = 0; axis < 3; axis++)
        for (int side = -1; side <= 1; side += 2) {
            /* the smallest j whose slab is proven empty; the slab beyond the last candidate must be */
            int lo = 0, hi = 2 * top;
            if (!slab_is_empty(p, axis, side, candidate(hi, top)) || slab_is_empty(p, axis, side, candidate(lo, top)))
                return 0;
            while (hi - lo > 1) {
                int mid = (lo + hi) / 2;
                if (slab_is_empty(p, axis, side, candidate(mid, top)))
                    hi = mid;
                else
                    lo = mid;
            }
            /* side > 0: zeros have coordinate < candidate(hi); side < 0: > -candidate(hi) */
            result[2 * axis + (side > 0)] = side > 0 ? candidate(hi, top) : -candidate(hi, top);
        }
    return p->work_left >= 0;
}

iacsg_bounds_proof iacsg_expr_bounds(const iacsg_expr *e, const double time[2], double box[6]) {
    if (!(time[0] <= time[1]) || !isfinite(time[0]) || !isfinite(time[1]))
        return IACSG_BOUNDS_NONE;
    prover p = {e, malloc(eval_scratch_size(e->root)), malloc((BOUNDS_BUDGET + 2) * sizeof(double[8])),
                {time[0], time[1]}, 0, INFINITY, BOUNDS_WORK};
    p.time_scale = iacsg_expr_uses_time(e) && time[1] > time[0] ? 1 / (time[1] - time[0]) : 0;
    double result[6];
    iacsg_bounds_proof proof = IACSG_BOUNDS_NONE;
    if (p.scratch && p.stack) {
        if (search(&p, result))
            proof = IACSG_BOUNDS_EVERYWHERE;
        else {
            p.half = IACSG_BOUNDS_CUBE;
            p.work_left = BOUNDS_WORK;
            proof = search(&p, result) ? IACSG_BOUNDS_IN_CUBE : IACSG_BOUNDS_NONE;
        }
    }
    free(p.scratch);
    free(p.stack);
    if (proof != IACSG_BOUNDS_NONE) {
        box[0] = result[0], box[1] = result[2], box[2] = result[4];
        box[3] = result[1], box[4] = result[3], box[5] = result[5];
    }
    return proof;
}
