/* src/scene_tables.h -- a scene's tables for the segment path's kernels (kernels/scene_data.h), built on the
 * host once per renderer:
 *   boxes     each region solid's proven box (iacsg_expr_bounds), or an infinite one where the solid has none or
 *             its inside reaches beyond it (the sign of f at a point outside the box says which)
 *   BVH       over those boxes, split along the centres' longest axis by the surface area heuristic, flattened
 *             in preorder with skip links
 *   trees     every tree and condition as the scene has them, then the regions' terms (scene_terms.h), each
 *             relinearised so that its evaluation's stack stays within SCENE_TREE_STACK (kernels/classify.h)
 *   lists     per solid the terms it triggers (scene_terms.h); the surfaces; each item's albedo (material, or the
 *             palette)
 */
#ifndef IACSG_SCENE_TABLES_H
#define IACSG_SCENE_TABLES_H
#include "implicits/scene.h"
#include <stdint.h>

typedef struct {
    int nsolids;
    int nbvh;
    double *bvh_box; /* 6 per node: x0 y0 z0 x1 y1 z1 (infinite for unbounded solids) */
    int *bvh_link;   /* 2 per node: SCENE_BVH_SKIP, SCENE_BVH_SOLID; then per solid its leaf (-1: none) */
    uint32_t *nodes;
    int nnodes;
    int *items; /* SCENE_ITEM_INTS per item */
    int nitems;
    int *solid_items_start, *solid_items; /* nsolids + 1 starts, and the terms (SCENE_TERM_INTS ints each) */
    int *surfaces, nsurfaces;
    float *albedo; /* the item's material: SCENE_MATERIAL_FLOATS per item (kernels/scene_data.h) */
    int uses_time; /* some solid depends on t (the boxes hold for t in [0, 1]) */
    int in_cube;   /* some box holds only inside the cube of IACSG_BOUNDS_CUBE */
} scene_tables;

iacsg_status scene_tables_build(const iacsg_scene *s, scene_tables *t, iacsg_error *err);
void scene_tables_free(scene_tables *t);

/* The palette colour (linear) of an item without a material. */
void scene_palette(int id, float rgb[3]);

#endif
