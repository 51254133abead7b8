/* kernels/weave.h -- partitions and their claims. The candidates' walks (segments.h) are stepped in t order;
 * between two consecutive points where some solid's state changes lies a partition where each solid has one
 * state, and each partition is classified (classify.h) once no walk can change a state before its end: against
 * the regions' terms that a solid not OUT there triggers (the per-solid lists of src/scene_terms.h). The first
 * partition that some region may be in is the hit; the region declared first among those that may be in claims
 * it. At the first partition from there on where the winner is certainly in, another region certainly in makes
 * an overlap (weave_ray).
 *
 * A scene with a distance tolerance (SCENE_DIST_TOL, world units: BRL-CAD's 0.0005 mm, librt's rt_tol.dist) fuses
 * the changes of state that lie within it, as librt's weave fuses hit points closer than tol.dist: a change that no
 * zone holds opens one (weave_zone_length long), the partitions inside it are passed unclassified, and the first
 * partition that ends past it is classified and claimed from the zone's start. A region that may be in only inside
 * a zone -- the sliver of no volume between a minuend's face and its subtrahend's on the same plane, whose two
 * enclosures leave it "may be in" -- is left out; a region the ray crosses for longer than the zone is in somewhere
 * past the zone's end in the partition classified there, so it is never missed, and the claim is at most the
 * zone's length before its first point. Without a tolerance every zone is one point: each partition is classified.
 *
 * Why not Domingues' linked list of partitions: the walks give the state changes already in order, so a
 * partition is classified as the weave passes it and never stored; the per-ray buffer is the candidates alone
 * (scene_data.h). What a partition is in is the table of states per solid (bytes, not bits: each ray resets only
 * its candidates' entries when it is done).
 */
#ifndef KERNELS_WEAVE_H
#define KERNELS_WEAVE_H
#include "classify.h"
#include "segments.h"
#include "bvh.h"

/* The scene's tables and one ray's buffers (scene_data.h). */
typedef struct {
    const KERNEL_GLOBAL kernel_u32 *nodes;
    const KERNEL_GLOBAL int *items;             /* SCENE_ITEM_INTS per item */
    const KERNEL_GLOBAL int *solid_items_start; /* solid k's terms: solid_items[start[k] .. start[k + 1]) */
    const KERNEL_GLOBAL int *solid_items;       /* SCENE_TERM_INTS per term (scene_data.h) */
    segments_walks walks; /* the candidates (bvh.h) and their walks */
    int cand_cap, ncand, nstarted; /* the walks started are the first nstarted */
    KERNEL_GLOBAL unsigned char *state; /* per solid of the scene, all OUT between rays */
    kernel_u32 evals, segments, partitions;
    int passing; /* 1 + a region the ray starts in and passes through (src/render_effects.c, transparency): not
                  * claimed until a partition where it is certainly out; 0: none */
    int deep;        /* 1: the walks whose range starts at deep_from start at nodes no wider than deep_eps */
    ia_real deep_from, deep_eps;
} scene_ray;

typedef struct {
    ia_real t;   /* the claimed partition's start */
    int item;    /* the region that claims it */
    int solid;   /* the solid whose state change starts it: its boundary is the hit's surface */
    int overlap; /* another region certainly in there, or -1 */
} weave_hit;

#define WEAVE_NONE 0x7fffffff

/* The value (classify.h) of region `item` over the current partition: the union of its terms triggered by the
 * solids not OUT there (src/scene_terms.h: an untriggered term is certainly out). */
IA_FN int weave_value(const scene_ray *r, int item) {
    int in = 0, out = 1;
    for (int c = 0; c < r->nstarted; c++) {
        int k = r->walks.solid[c];
        if (r->state[k] == SCENE_OUT)
            continue;
        for (int j = r->solid_items_start[k]; j < r->solid_items_start[k + 1]; j += SCENE_TERM_INTS) {
            const KERNEL_GLOBAL int *e = r->solid_items + j;
            if (e[SCENE_TERM_ITEM] > item)
                break;
            if (e[SCENE_TERM_ITEM] < item)
                continue;
            int v = classify_tree(r->nodes, e[SCENE_TERM_ROOT], e[SCENE_TERM_SIZE], r->state);
            in |= v & CLASSIFY_MAY_IN;
            out &= v >> 1;
        }
    }
    return in | out << 1;
}

/* The first declared region that may be in over the current partition (returns 0 when none may be), among the
 * regions of the terms that its solids not OUT trigger; with `certain`, the first that is certainly in, other
 * than `except`. A region may be in where one of its terms may be, and is certainly in where one is (a union is
 * certainly out only where all its sides are). */
IA_FN int weave_first_region(const scene_ray *r, int certain, int except, int *first) {
    int best = WEAVE_NONE;
    for (int c = 0; c < r->nstarted; c++) {
        int k = r->walks.solid[c];
        if (r->state[k] == SCENE_OUT)
            continue;
        for (int j = r->solid_items_start[k]; j < r->solid_items_start[k + 1]; j += SCENE_TERM_INTS) {
            const KERNEL_GLOBAL int *e = r->solid_items + j;
            int item = e[SCENE_TERM_ITEM];
            if (item >= best) /* the entries are in the regions' order */
                break;
            if (item == except)
                continue;
            int v = classify_tree(r->nodes, e[SCENE_TERM_ROOT], e[SCENE_TERM_SIZE], r->state);
            if (certain ? v == CLASSIFY_MAY_IN : (v & CLASSIFY_MAY_IN) != 0)
                best = item;
        }
    }
    *first = best;
    return best != WEAVE_NONE;
}

/* After a claim: whether the winner is certainly in over the current partition (1, and *other the first other
 * region certainly in there, or -1), may still be in (0), or is certainly out (-1: it claimed on undecided
 * states alone). */
IA_FN int weave_overlap(const scene_ray *r, int winner, int *other) {
    int v = weave_value(r, winner);
    if (v != CLASSIFY_MAY_IN)
        return v & CLASSIFY_MAY_IN ? 0 : -1;
    if (!weave_first_region(r, 1, winner, other))
        *other = -1;
    return 1;
}

/* Without a tolerance, no zone: each partition is claimed for itself. */
#ifndef SCENE_DIST_TOL
#define SCENE_DIST_TOL 0
#endif
/* The zone's length in t from a zone's start t: the tolerance, plus WEAVE_ZONE_ULPS units of rounding of the
 * coordinates there (the enclosures of a face's crossing are a few of them wide: in float about 1e-3 mm at 10 m from
 * the origin, twice librt's tolerance), over dlen = |d|, t's unit along the ray; 0 without a tolerance. */
#define WEAVE_ZONE_ULPS 16
IA_FN ia_real weave_zone_length(const ia_real o[3], ia_real dlen, ia_real t) {
    if (SCENE_DIST_TOL <= 0)
        return 0;
    ia_real reach = fmax(fabs(o[0]), fmax(fabs(o[1]), fabs(o[2]))) + fabs(t) * dlen;
    return ((ia_real)SCENE_DIST_TOL + WEAVE_ZONE_ULPS * IA_REAL_EPS * reach) / dlen;
}

/* The hit's surface for a claim from a zone: the solid whose change starts the zone (at the hit's t) where the
 * claiming region holds it, so that the normal is its own; else the one whose change ends the zone. */
IA_FN int weave_zone_solid(const scene_ray *r, int item, int zone_solid, int solid) {
    const KERNEL_GLOBAL int *it = r->items + SCENE_ITEM_INTS * item;
    return zone_solid >= 0 && classify_tree_holds(r->nodes, it[SCENE_ITEM_ROOT], it[SCENE_ITEM_SIZE], zone_solid)
               ? zone_solid
               : solid;
}

/* Brings the pending entry (bvh.h) with the least range start to position nstarted, expanding the BVH nodes that
 * come first until it is a solid (or none is left). Returns 0 when the pending entries overflow. */
IA_FN int weave_next_entry(scene_ray *r, const bvh_walk *b) {
    segments_walks *w = &r->walks;
    for (;;) {
        int c = r->nstarted, best = c;
        if (c >= r->ncand)
            return 1;
        for (int k = c + 1; k < r->ncand; k++)
            best = w->range[2 * k] < w->range[2 * best] ? k : best;
        int solid = w->solid[c];
        ia_real start = w->range[2 * c], width = w->range[2 * c + 1];
        w->solid[c] = w->solid[best];
        w->range[2 * c] = w->range[2 * best];
        w->range[2 * c + 1] = w->range[2 * best + 1];
        w->solid[best] = solid;
        w->range[2 * best] = start;
        w->range[2 * best + 1] = width;
        if (w->solid[c] >= 0)
            return 1;
        if (!bvh_expand(b, c, w->solid, w->range, &r->ncand, r->cand_cap))
            return 0;
    }
}

/* The candidate whose walk is the least advanced (the least position; or the next pending solid at its range's
 * start, which it then starts), or -1 when all are done; -2 when the pending entries overflow. */
IA_FN int weave_next_walk(scene_ray *r, const bvh_walk *b) {
    int best = -1;
    ia_real least = IA_INF;
    for (int c = 0; c < r->nstarted; c++)
        if (r->walks.pos[c] < least) {
            least = r->walks.pos[c];
            best = c;
        }
    if (r->nstarted < r->ncand && r->walks.range[2 * r->nstarted] <= least) {
        best = r->nstarted++;
        ia_real start = r->walks.range[2 * best], width = r->walks.range[2 * best + 1];
        segments_start_at(&r->walks, best,
                          r->deep && start == r->deep_from ? segments_leaf_level(width, r->deep_eps) : 0);
        if (!weave_next_entry(r, b))
            return -2;
    }
    return best;
}

/* Weaves the candidates' walks along the ray over [tn, tf] (b): returns 1 at the first claimed partition
 * (*hit), 0 when no partition starting before tf is claimed, -1 when the ray meets more boxes than r has room
 * for. The claimed partition is mostly a BOUNDARY leaf, where no region is certainly in: for the overlap, the
 * weave goes on to the first partition where the winner is certainly in (at most WEAVE_OVERLAP_PARTITIONS
 * further) and names another region certainly in there. With a tolerance, only the partitions that end past a
 * zone are classified (see the top). */
#define WEAVE_OVERLAP_PARTITIONS 8
IA_FN int weave_ray(scene_ray *r, const bvh_walk *b, ia_real eps, ia_interval time, weave_hit *hit) {
    const ia_real *o = b->o, *d = b->d;
    ia_real tf = b->tf;
    int pending = 0, pending_solid = -1, found = 0, confirming = WEAVE_OVERLAP_PARTITIONS, zone_solid = -1;
    ia_real pending_t = 0, zone_t = 0, zone_end = -IA_INF; /* the open zone, [zone_t, zone_end]: none at first */
    ia_real dlen = SCENE_DIST_TOL > 0 ? sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) : 1;
    r->nstarted = 0;
    r->ncand = 0;
    if (!bvh_roots(b, r->walks.solid, r->walks.range, &r->ncand, r->cand_cap) || !weave_next_entry(r, b))
        return -1;
    for (;;) {
        int c = weave_next_walk(r, b);
        if (c == -2)
            return found ? 1 : -1;
        ia_real at = c >= 0 ? r->walks.pos[c] : IA_INF;
        if (pending && at > pending_t) { /* no walk can change a state before `at` any more */
            pending = 0;
            if (r->passing && !(weave_value(r, r->passing - 1) & CLASSIFY_MAY_IN))
                r->passing = 0; /* out of the region it passed through: it may claim again */
            if (found) { /* confirming the claim for the overlap */
                int other = -1, v = weave_overlap(r, hit->item, &other);
                hit->overlap = v > 0 ? other : -1;
                if (v != 0 || --confirming == 0)
                    return 1;
            } else {
                r->partitions += 1;
                if (zone_end < pending_t) { /* no zone open: this partition's start opens one */
                    zone_t = pending_t;
                    zone_end = pending_t + weave_zone_length(o, dlen, pending_t);
                    zone_solid = pending_solid;
                }
                if (at > zone_end || !(at < tf)) { /* past the zone: classified, and claimed from its start */
                    if (weave_first_region(r, 0, r->passing - 1, &hit->item)) {
                        found = 1;
                        hit->t = zone_t;
                        hit->solid = zone_t < pending_t ? weave_zone_solid(r, hit->item, zone_solid, pending_solid)
                                                        : pending_solid;
                        int other = -1, v = weave_overlap(r, hit->item, &other);
                        hit->overlap = v > 0 ? other : -1;
                        if (v != 0)
                            return 1;
                    }
                    zone_end = -IA_INF;
                }
            }
        }
        if (!(at < tf))
            return found;
        int k = r->walks.solid[c], s = segments_step(&r->walks, c, o, d, eps, time, &r->evals);
        if (s == r->state[k])
            continue;
        r->segments += r->state[k] == SCENE_OUT;
        r->state[k] = (unsigned char)s;
        /* the hit's surface: of the changes at one point, one to a state that may be in */
        pending_solid = !pending || s != SCENE_OUT ? k : pending_solid;
        pending = 1;
        pending_t = at;
    }
}

#endif
