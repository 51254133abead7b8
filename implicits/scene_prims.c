/* implicits/scene_prims.c -- see scene_prims.h. Two passes over the solids: the entries and the parameters'
 * offsets, then (with room for the table) the bounds. */
#include "scene_prims.h"
#include "ia/flush.h"
#include "kernels/scene_prims.h"
#include "prim_place.h"
#include <stdlib.h>
#include <string.h>

/* A bound as a real of the program's precision: the double moved out of the subnormals (ia/flush.h), or the
 * float rounded outward (down for a lower bound). */
static void put_bound(void *reals, int fp64, size_t at, double x, int upper) {
    if (fp64)
        ((double *)reals)[at] = upper ? ia_flush_hi_d(x) : ia_flush_lo_d(x);
    else
        ((float *)reals)[at] = prim_float_bound(x, upper);
}

/* An integer of the table's header or entries (exact in float: below 2^24). */
static void put_int(void *reals, int fp64, size_t at, double x) {
    if (fp64)
        ((double *)reals)[at] = x;
    else
        ((float *)reals)[at] = (float)x;
}

/* Solid k's entry and, for a primitive, its parameters from *at on (zeros after them up to a multiple of
 * SCENE_PRIMS_ALIGN); *at moves past them. Without reals, only *at and *most. */
static iacsg_status put_solid(const iacsg_scene *s, int k, int fp64, void *reals, size_t *at, int *most,
                              iacsg_error *err) {
    size_t entry = SCENE_PRIMS_HEADER + SCENE_PRIMS_ENTRY * (size_t)k;
    const scene_solid *solid = &s->solids[k];
    if (!solid->prim) {
        if (reals)
            for (int j = 0; j < SCENE_PRIMS_ENTRY; j++)
                put_int(reals, fp64, entry + (size_t)j, j == 0 ? -1 : 0);
        return IACSG_OK;
    }
    prim_placed placed;
    iacsg_status st = prim_place(solid->prim, solid->name, &placed, err);
    if (st != IACSG_OK)
        return st;
    int nreal = 2 * placed.n, padded = (nreal + SCENE_PRIMS_ALIGN - 1) / SCENE_PRIMS_ALIGN * SCENE_PRIMS_ALIGN;
    if (reals) {
        put_int(reals, fp64, entry, placed.type);
        put_int(reals, fp64, entry + 1, (double)*at);
        put_int(reals, fp64, entry + 2, padded);
        for (int i = 0; i < padded; i++)
            if (i < nreal)
                put_bound(reals, fp64, *at + (size_t)i, i % 2 ? placed.hi[i / 2] : placed.lo[i / 2], i % 2);
            else
                put_int(reals, fp64, *at + (size_t)i, 0);
    }
    *at += (size_t)padded;
    *most = padded > *most ? padded : *most;
    prim_placed_free(&placed);
    return IACSG_OK;
}

iacsg_status scene_prims_table(const iacsg_scene *s, int fp64, void **reals, size_t *count, int *most,
                               iacsg_error *err) {
    size_t head = SCENE_PRIMS_HEADER + SCENE_PRIMS_ENTRY * (size_t)s->nsolids, at = head;
    *most = 0;
    if (reals)
        *reals = NULL;
    iacsg_status st = IACSG_OK;
    for (int k = 0; k < s->nsolids && st == IACSG_OK; k++) /* the length first */
        st = put_solid(s, k, fp64, NULL, &at, most, err);
    *count = at;
    if (st != IACSG_OK || !reals)
        return st;
    if (at >= (size_t)1 << 24)
        return iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0, "the scene's primitives take too many parameters");
    void *table = malloc(at * (fp64 ? sizeof(double) : sizeof(float)));
    if (!table)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory for the scene's primitives");
    put_int(table, fp64, 0, s->nsolids);
    at = head;
    for (int k = 0; k < s->nsolids && st == IACSG_OK; k++)
        st = put_solid(s, k, fp64, table, &at, most, err);
    if (st != IACSG_OK) {
        free(table);
        return st;
    }
    *reals = table;
    return IACSG_OK;
}
