/* kernels/segments_lanes.h -- a packet's planar solids (a half, an arb8) solved along its IA_VW rays at once, one
 * SIMD lane per ray (OpenCL C, a program with IA_VW and primitives; an orthographic view, whose rays share their
 * direction and so each plane's n.d, prim_segments.h's direction terms). Its ells, quadric tgcs and ehys:
 * segments_lanes_frame.h, into the same table.
 *
 *   segments_lanes_start(l, o, inv, tn, from, tf, box, link, nodes): at a packet, its rays' origins (lane k: ray
 *     k), reciprocal directions and where their BVH walks start and end (fmax(tn, from) and tf: scene_trace.h's
 *     b.tn, b.tf), the BVH, and an empty table;
 *   segments_lanes_fill(l, k, type, p, d, dir, known): solid k's span (prim_segments_span) along every lane's ray,
 *     into the table's slot of k: each plane's c = n.o - d in lanes, its root -c / n.d and the span's bounds (0
 *     where a plane may be parallel to the rays: its piece then depends on each ray's range, and the scalar code
 *     solves it);
 *   segments_lanes_changes(l, k, ta, tend, e, evals): lane l->lane's changes over [ta, tend] from the table, as
 *     prim_segments gives them (prim_segments_convex), or 0 where a bound was NaN (the walk bisects).
 *
 * Why: a ray of a BRL-CAD model solves each arb its BVH leaves reach, six planes in scalar interval code, and the
 * 16 rays of a packet mostly reach the same ones (truck: 125 arbs, their planes a third of the render). The first
 * ray that reaches a solid solves it for all 16 in the cost of about one; the others read their lane.
 *
 * Bit for bit the scalar code's: each lane runs prim_segments_plane's operations on its ray in the same order
 * (ia_mul_r, ia_add, ia_sub, ia_div_one_signed, then fmax and fmin, which are exact and commute), with ia/vec.h's
 * widening, which is ia/round.h's; so images, depths and counts are the scalar path's (tests/t_brlcad_lanes.c
 * renders with and without the lanes: IACSG_SEGMENTS_LANES=0 builds the program without them).
 */
#ifndef KERNELS_SEGMENTS_LANES_H
#define KERNELS_SEGMENTS_LANES_H
#include "prim_segments.h"
typedef struct segments_lanes segments_lanes; /* (segments.h's walks point to one) */
#if IA_DEVICE && defined(IA_VW) && defined(SCENE_SOLID_PRIMS) && !defined(SEGMENTS_LANES_OFF)
#define SEGMENTS_LANES 1

/* Solids kept per packet, by their number modulo this (a packet's rays reach a few arbs each). */
#define SEGMENTS_LANES_SLOTS 16

/* A lane's span of the solid in a slot: plo, phi, ilo, ihi (plo NaN where a bound was), and for a frame type the
 * range start it was solved from (SEGMENTS_LANES_FROM, the lane's entry into the solid's BVH leaf: NaN where the
 * scalar code solves that lane). */
#define SEGMENTS_LANES_BOUNDS 5
#define SEGMENTS_LANES_FROM 4

/* solved[]: how a slot's solid is solved */
#define SEGMENTS_LANES_SCALAR 0 /* by the scalar code (a plane along the rays, a general tgc) */
#define SEGMENTS_LANES_PLANES 1 /* in lanes, over any range */
#define SEGMENTS_LANES_FRAME 2  /* in lanes from each lane's SEGMENTS_LANES_FROM (a quadric expanded there) */

struct segments_lanes {
    ia_realv o[3], inv[3]; /* the packet's origins and reciprocal directions */
    ia_realv tn, tf;       /* where their BVH walks start and end */
    const KERNEL_GLOBAL ia_real *box; /* the BVH (bvh.h), and after its links each solid's leaf */
    const KERNEL_GLOBAL int *link;
    int nodes;
    int lane; /* the ray being traced */
    int solid[SEGMENTS_LANES_SLOTS]; /* -1: empty */
    int solved[SEGMENTS_LANES_SLOTS];
    ia_real span[SEGMENTS_LANES_SLOTS][SEGMENTS_LANES_BOUNDS][IA_VW];
};

IA_FN void segments_lanes_start(segments_lanes *l, ia_real o[3][IA_VW], ia_real inv[3][IA_VW], ia_real tn[IA_VW],
                                ia_real from[IA_VW], ia_real tf[IA_VW], const KERNEL_GLOBAL ia_real *box,
                                const KERNEL_GLOBAL int *link, int nodes) {
    for (int c = 0; c < 3; c++) {
        l->o[c] = IAV_LOAD(o[c]);
        l->inv[c] = IAV_LOAD(inv[c]);
    }
    l->tn = fmax(IAV_LOAD(tn), IAV_LOAD(from));
    l->tf = IAV_LOAD(tf);
    l->box = box;
    l->link = link;
    l->nodes = nodes;
    for (int s = 0; s < SEGMENTS_LANES_SLOTS; s++)
        l->solid[s] = -1;
}

/* Whether the table holds solid k (solved in lanes, or marked for the scalar code). */
IA_FN int segments_lanes_holds(const segments_lanes *l, int k) { return l->solid[k % SEGMENTS_LANES_SLOTS] == k; }

/* ia_mul_r(a, c) in each lane c: [0, 0] where c is 0. */
IA_FN iav segments_lanes_mul_r(ia_interval a, ia_realv c) {
    ia_realv p = a.lo * c, q = a.hi * c;
    return iav_make(select(iav_lo(fmin(p, q)), IAV_R(0), c == 0), select(iav_hi(fmax(p, q)), IAV_R(0), c == 0));
}

/* ia_div_one_signed(a, b) in each lane a, b one-signed and the same in every lane. */
IA_FN iav segments_lanes_div(iav a, ia_interval b) {
    ia_maskv zero = a.lo == 0 && a.hi == 0;
    ia_realv num_lo = b.lo > 0 ? a.lo : a.hi, num_hi = b.lo > 0 ? a.hi : a.lo;
    ia_realv lo = num_lo / select(IAV_R(b.lo), IAV_R(b.hi), num_lo >= 0);
    ia_realv hi = num_hi / select(IAV_R(b.hi), IAV_R(b.lo), num_hi >= 0);
    return iav_make(select(iav_lo_k(lo, IA_ULP_DIV), IAV_R(0), zero), select(iav_hi_k(hi, IA_ULP_DIV), IAV_R(0), zero));
}

/* Solid k's planes (type PRIM_HALF or PRIM_ARB8, parameters p) along every lane's ray into k's slot, their
 * direction terms from dir (prim_segments_dir: kept where `known`, else computed and kept there). 0 where one
 * may be 0: the slot then sends k to the scalar code. */
IA_FN int segments_lanes_fill(segments_lanes *l, int k, int type, const ia_real *p, const ia_real d[3],
                              ia_interval *dir, int known) {
    int slot = k % SEGMENTS_LANES_SLOTS, planes = type == PRIM_HALF ? 1 : PRIM_ARB_PLANES, along = 0;
    ia_interval b[PRIM_ARB_PLANES];
    for (int j = 0; j < planes; j++) {
        b[j] = prim_segments_dir(p + 8 * j, 0, d, dir, known, j);
        along |= !(b[j].lo > 0 || b[j].hi < 0);
    }
    l->solid[slot] = k;
    l->solved[slot] = along ? SEGMENTS_LANES_SCALAR : SEGMENTS_LANES_PLANES;
    if (along)
        return 0;
    ia_realv plo = IAV_R(-IA_INF), phi = IAV_R(IA_INF), ilo = IAV_R(-IA_INF), ihi = IAV_R(IA_INF);
    ia_maskv nan = plo != plo;
    for (int j = 0; j < planes; j++) {
        const ia_real *q = p + 8 * j;
        iav dot = iav_add(segments_lanes_mul_r(prim_iv(q, 0), l->o[0]), segments_lanes_mul_r(prim_iv(q, 1), l->o[1]));
        dot = iav_add(dot, segments_lanes_mul_r(prim_iv(q, 2), l->o[2]));
        iav t = segments_lanes_div(iav_neg(iav_sub(dot, iav_splat(prim_iv(q, 3)))), b[j]);
        nan = nan | isnan(t.lo) | isnan(t.hi);
        if (b[j].lo > 0) {
            phi = fmin(phi, t.hi);
            ihi = fmin(ihi, t.lo);
        } else {
            plo = fmax(plo, t.lo);
            ilo = fmax(ilo, t.hi);
        }
    }
    IAV_STORE(select(plo, IAV_R(NAN), nan), l->span[slot][0]);
    IAV_STORE(phi, l->span[slot][1]);
    IAV_STORE(ilo, l->span[slot][2]);
    IAV_STORE(ihi, l->span[slot][3]);
    return 1;
}

/* Lane l->lane's changes of solid k (held in its slot) over [ta, tend] into e (prim_segments_convex); 0 where a
 * bound was NaN; -1 where the scalar code solves it (the slot says so, or a frame type's lane was solved from
 * another range start than ta: its quadric's expansion point, so the roots' rounding, would differ). */
IA_FN int segments_lanes_changes(const segments_lanes *l, int k, ia_real ta, ia_real tend, ia_real e[4],
                                 kernel_u32 *evals) {
    int slot = k % SEGMENTS_LANES_SLOTS, n = l->lane, solved = l->solved[slot];
    if (solved == SEGMENTS_LANES_SCALAR)
        return -1;
    if (solved == SEGMENTS_LANES_FRAME) {
        ia_real from = l->span[slot][SEGMENTS_LANES_FROM][n]; /* bit for bit ta (not -0 for 0) */
        if (!(from == ta && signbit(from) == signbit(ta)))
            return -1;
    }
    prim_segments_span s = {l->span[slot][0][n], l->span[slot][1][n], l->span[slot][2][n], l->span[slot][3][n], 0};
    if (isnan(s.plo))
        return 0;
    return prim_segments_convex(&s, ta, tend, e, evals);
}

#endif
#endif
