/* implicits/bounds.c -- iacsg_expr_bounds: a box proven (by double interval evaluation) to hold the surface.
 *
 * Plain interval arithmetic cannot prove anything over unbounded boxes for most shapes (x^4 - 5x^2 over
 * [2, inf] is [-inf, inf]), so the search is limited to the cube [-BOUNDS_DOMAIN, BOUNDS_DOMAIN]^3 and to times
 * t in [0, 1] (bisected like the space): the box returned holds every zero of f in that cube at those times. For each side of each axis,
 * a binary search over candidate planes finds the tightest plane beyond which the slab of the cube is proven
 * free of zeros; a slab counts as proven when adaptive bisection (a budget of BOUNDS_BUDGET evaluations)
 * covers it with boxes whose enclosure excludes 0. The total work is capped too (BOUNDS_WORK): for an
 * expression of a million nodes the search gives up rather than take minutes. */
#include "eval.h"
#include "expr_internal.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BOUNDS_DOMAIN IACSG_BOUNDS_DOMAIN
#define BOUNDS_BUDGET 3000
#define BOUNDS_WORK 30000000.0 /* node evaluations in all: about a tenth of a second; huge DAGs give up */

typedef struct {
    const iacsg_expr *e;
    void *scratch;
    double (*stack)[8];
    int uses_time;
    double work_left; /* below 0: out of work, no bounds */
} prover;

/* 1 if f has no zero in the box (x0,x1,y0,y1,z0,z1) for t in [0, 1]. */
static int no_zero_in(prover *p, const double box[6]) {
    double unit = 1 / (2 * BOUNDS_DOMAIN), scale[4] = {unit, unit, unit, p->uses_time};
    int top = 0, evals = 0;
    memcpy(p->stack[top], box, 6 * sizeof(double));
    p->stack[top][6] = 0;
    p->stack[top][7] = 1;
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
        /* the widest side relative to the domain, time included: morph(a, b, t) needs t split to be proven */
        int axis = 0;
        for (int a = 1; a < 4; a++)
            if ((b[2 * a + 1] - b[2 * a]) * scale[a] > (b[2 * axis + 1] - b[2 * axis]) * scale[axis])
                axis = a;
        double mid = b[2 * axis] * 0.5 + b[2 * axis + 1] * 0.5;
        if (!(mid > b[2 * axis] && mid < b[2 * axis + 1]))
            return 0; /* a zero (or something indistinguishable from one) at the resolution of doubles */
        memcpy(p->stack[top], b, sizeof b);
        p->stack[top][2 * axis + 1] = mid;
        memcpy(p->stack[top + 1], b, sizeof b);
        p->stack[top + 1][2 * axis] = mid;
        top += 2;
    }
    return 1;
}

/* The slab of the domain cube where side * coordinate[axis] >= v. */
static int slab_is_empty(prover *p, int axis, int side, double v) {
    double box[6] = {-BOUNDS_DOMAIN, BOUNDS_DOMAIN, -BOUNDS_DOMAIN, BOUNDS_DOMAIN, -BOUNDS_DOMAIN, BOUNDS_DOMAIN};
    if (side > 0)
        box[2 * axis] = v;
    else
        box[2 * axis + 1] = -v;
    return no_zero_in(p, box);
}

/* Candidate plane positions, increasing: 0, +-2^(k/4) for 2^-4 <= |v| <= BOUNDS_DOMAIN. */
#define NCAND (2 * 57 + 1)
static double candidate(int j) {
    int k = j - 57; /* -57 .. 57 */
    if (k == 0)
        return 0;
    double m = pow(2.0, (abs(k) - 17) / 4.0); /* |k| = 1 gives 2^-4, |k| = 57 gives 2^10 */
    return k < 0 ? -m : m;
}

int iacsg_expr_bounds(const iacsg_expr *e, double box[6]) {
    prover p = {e, malloc(eval_scratch_size(e->root)), malloc((BOUNDS_BUDGET + 2) * sizeof(double[8])),
                iacsg_expr_uses_time(e), BOUNDS_WORK};
    int ok = p.scratch && p.stack;
    double result[6];
    for (int axis = 0; ok && axis < 3; axis++)
        for (int side = -1; ok && side <= 1; side += 2) {
            /* the smallest j whose slab is proven empty, with the slab at the domain's face as the fallback */
            int lo = 0, hi = NCAND - 1;
            if (!slab_is_empty(&p, axis, side, candidate(hi)) || slab_is_empty(&p, axis, side, candidate(lo))) {
                ok = 0;
                break;
            }
            while (hi - lo > 1) {
                int mid = (lo + hi) / 2;
                if (slab_is_empty(&p, axis, side, candidate(mid)))
                    hi = mid;
                else
                    lo = mid;
            }
            /* side > 0: zeros have coordinate < candidate(hi); side < 0: > -candidate(hi) */
            result[2 * axis + (side > 0)] = side > 0 ? candidate(hi) : -candidate(hi);
        }
    free(p.scratch);
    free(p.stack);
    if (!ok || p.work_left < 0)
        return 0;
    box[0] = result[0], box[1] = result[2], box[2] = result[4];
    box[3] = result[1], box[4] = result[3], box[5] = result[5];
    return 1;
}
