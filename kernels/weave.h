/* kernels/weave.h -- partitions and their claims: the breaks of every candidate solid (segments.h), sorted by t,
 * are swept in order; between two consecutive break points lies a partition where each solid has one state, and
 * each partition is classified as the sweep passes it (classify.h) against the regions that use a solid which
 * is not OUT there (the per-solid lists of src/render_scene.c). The first partition that some region may be in
 * is the hit; the region declared first among those that may be in claims it. Where another region is
 * certainly in as well as a certainly-in winner, the partition is an overlap.
 *
 * Why a sweep over sorted breaks rather than Domingues' linked list of partitions: the partitions are never
 * stored, only the breaks (and the sweep needs no links), and a partition is final as soon as the sweep has
 * passed the next candidate's box entry (bvh.h sorts candidates by it): before it every solid not yet bisected
 * is certainly OUT. So the sweep advances after each solid, and stops at the first claim without bisecting the
 * solids behind it.
 */
#ifndef KERNELS_WEAVE_H
#define KERNELS_WEAVE_H
#include "classify.h"

/* The scene's tables and one ray's buffers (scene_data.h). */
typedef struct {
    const KERNEL_GLOBAL kernel_u32 *nodes;
    const KERNEL_GLOBAL int *items;             /* SCENE_ITEM_INTS per item */
    const KERNEL_GLOBAL int *solid_items_start; /* solid k's regions: solid_items[start[k] .. start[k + 1]) */
    const KERNEL_GLOBAL int *solid_items;
    KERNEL_GLOBAL int *cand_solid; /* the candidates (bvh.h) */
    KERNEL_GLOBAL ia_real *cand_range;
    int cand_cap, ncand; /* ncand: those bisected so far */
    KERNEL_GLOBAL ia_real *break_t; /* the breaks not yet swept, sorted */
    KERNEL_GLOBAL int *break_info;
    int break_cap, nbreaks;
    KERNEL_GLOBAL unsigned char *state; /* per solid of the scene, all OUT between rays */
    kernel_u32 evals, segments, partitions;
} scene_ray;

typedef struct {
    ia_real t;   /* the claimed partition's start */
    int item;    /* the region that claims it */
    int solid;   /* the solid whose break starts it: its boundary is the hit's surface */
    int overlap; /* another region certainly in there, or -1 */
} weave_hit;

#define WEAVE_NONE 0x7fffffff

/* The region that claims the current partition (returns 0 when none may be in), and an overlapping one. */
IA_FN int weave_claim(const scene_ray *r, int *winner, int *other) {
    int may = WEAVE_NONE, first = WEAVE_NONE, second = WEAVE_NONE; /* first, second: certainly in */
    for (int c = 0; c < r->ncand; c++) {
        int k = r->cand_solid[c];
        if (r->state[k] == SCENE_OUT)
            continue;
        for (int j = r->solid_items_start[k]; j < r->solid_items_start[k + 1]; j++) {
            int item = r->solid_items[j];
            if ((item >= may && item >= second) || item == first)
                continue; /* it can change neither the winner nor the overlap */
            const KERNEL_GLOBAL int *it = r->items + SCENE_ITEM_INTS * item;
            int v = classify_tree(r->nodes, it[SCENE_ITEM_ROOT], it[SCENE_ITEM_SIZE], r->state);
            if (v & CLASSIFY_MAY_IN)
                may = item < may ? item : may;
            if (v == CLASSIFY_MAY_IN && item < first) {
                second = first;
                first = item;
            } else if (v == CLASSIFY_MAY_IN && item < second) {
                second = item;
            }
        }
    }
    if (may == WEAVE_NONE)
        return 0;
    *winner = may;
    *other = first == may && second != WEAVE_NONE ? second : -1;
    return 1;
}

/* Sweeps the breaks before `limit`, applying each to its solid's state and classifying the partition that each
 * group of equal break points starts. Returns 1 at the first claimed partition (*hit), else 0 with the swept
 * breaks removed. */
IA_FN int weave_advance(scene_ray *r, ia_real limit, weave_hit *hit) {
    int n = 0;
    while (n < r->nbreaks && r->break_t[n] < limit) {
        ia_real t = r->break_t[n];
        int solid = -1, solid_in = -1;
        for (; n < r->nbreaks && r->break_t[n] == t; n++) {
            int b = r->break_info[n], k = r->cand_solid[SCENE_BREAK_SLOT(b)];
            r->state[k] = (unsigned char)SCENE_BREAK_STATE(b);
            solid = k;
            solid_in = SCENE_BREAK_STATE(b) != SCENE_OUT ? k : solid_in;
        }
        r->partitions += 1;
        if (weave_claim(r, &hit->item, &hit->overlap)) {
            hit->t = t;
            hit->solid = solid_in >= 0 ? solid_in : solid;
            return 1;
        }
    }
    for (int k = n; k < r->nbreaks; k++) {
        r->break_t[k - n] = r->break_t[k];
        r->break_info[k - n] = r->break_info[k];
    }
    r->nbreaks -= n;
    return 0;
}

#endif
