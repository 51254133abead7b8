/* src/scene_terms.h -- the regions' trees in the form the weave classifies them (kernels/weave.h), built on the
 * host with the scene's tables (scene_tables.h):
 *   split      each region's tree is a union of terms: cut at its unions, a difference or intersection above a
 *              union distributed over it ((a u b) - x = (a - x) u (b - x), exact in the three-valued logic too,
 *              which is a distributive lattice), unless the copies would grow the tree past a bound
 *   triggers   per term a set of solids one of which is not OUT wherever the term may be in: a leaf's solid,
 *              both sides of a union, the smaller side of an intersection, the left side of a difference
 *   relinearise  each term's tree for the device's stack (kernels/classify.h), at most SCENE_TREE_STACK
 *   lists      per solid, the terms it triggers as (region, root, size), in the regions' order
 * A partition is classified against the terms triggered by its solids that are not OUT, not against whole trees:
 * on havoc a region is a union of up to 70 terms of a few nodes each, and a solid subtracted from most of them
 * triggers none.
 */
#ifndef IACSG_SCENE_TERMS_H
#define IACSG_SCENE_TERMS_H
#include "scene_tables.h"

/* Appends the terms' trees to t->nodes (growing it; t->nnodes nodes in use, room for cap) and builds
 * t->solid_items_start (per solid an index into t->solid_items, SCENE_TERM_INTS ints an entry) and
 * t->solid_items; sets used[k] for every solid that some region's tree holds. */
iacsg_status scene_terms_build(const iacsg_scene *s, scene_tables *t, int *cap, unsigned char *used,
                               iacsg_error *err);

#endif
