/* kernels/scene_data.h -- what the host and the device share for the segment path (src/render_scene.c fills it,
 * kernels/render_scene.cl reads it): the per-ray buffer bounds, the states of a solid along a ray, and the
 * layout of the scene's tables.
 *
 * Per-ray buffers. A ray collects the solids whose boxes it meets (candidates: a solid's number and the t range
 * of its box, SCENE_CANDIDATE_BYTES each) and the points where a solid's state changes (breaks: a t and the
 * solid's candidate slot and new state, SCENE_BREAK_BYTES each). A render starts with room for
 * SCENE_RAY_CANDIDATES and SCENE_RAY_BREAKS per ray; a ray that needs more stops, is listed, and is traced
 * again with four times the room, until it fits (never truncated). The partitions are not stored: the weave
 * sweeps the sorted breaks and classifies each partition as it passes it (kernels/weave.h).
 */
#ifndef KERNELS_SCENE_DATA_H
#define KERNELS_SCENE_DATA_H
#include "compat.h"

#define SCENE_RAY_CANDIDATES 32
#define SCENE_RAY_BREAKS 128
#define SCENE_CANDIDATE_BYTES (4 + 2 * (int)sizeof(ia_real))
#define SCENE_BREAK_BYTES (4 + (int)sizeof(ia_real))

/* A solid's state over a part of a ray, decided on the enclosure F of its function over the part's box: OUT
 * where F > 0, IN where F < 0, BOUNDARY where 0 is in F on a leaf of the bisection (width <= eps): the solid
 * may be in or out there. OUT is 0: the per-ray table of states starts, and is left, all OUT. */
#define SCENE_OUT 0
#define SCENE_IN 1
#define SCENE_BOUNDARY 2

/* A break: bits 2.. the candidate slot, bits 0-1 the state from its t on. */
#define SCENE_BREAK(slot, state) ((slot) << 2 | (state))
#define SCENE_BREAK_SLOT(b) ((b) >> 2)
#define SCENE_BREAK_STATE(b) ((b) & 3)

/* The BVH over the solids' boxes, in preorder: node k has a box (6 reals, x0 y0 z0 x1 y1 z1, rounded outward)
 * and two ints: the node that follows its subtree (where a ray that misses the box goes on), and the solid of a
 * leaf (-1 for an inner node). A solid whose inside reaches beyond its box, or that has no proven box, has an
 * infinite one: every ray evaluates it all along. */
#define SCENE_BVH_SKIP 0
#define SCENE_BVH_SOLID 1

/* An item (region or surface): SCENE_ITEM_INTS ints. Its tree (or condition) is nodes[root .. root + size),
 * kernels/csg_node.h, relinearised so that its evaluation needs at most SCENE_TREE_STACK values at once
 * (kernels/classify.h). */
enum { SCENE_ITEM_KIND = 0, SCENE_ITEM_ROOT = 1, SCENE_ITEM_SIZE = 2, SCENE_ITEM_SOLID = 3, SCENE_ITEM_INTS = 4 };
#define SCENE_KIND_REGION 0
#define SCENE_KIND_SURFACE 1
#define SCENE_TREE_STACK 64

#endif
