/* kernels/scene_data.h -- what the host and the device share for the segment path (src/render_scene.c fills it,
 * kernels/render_scene.cl reads it): the per-ray buffer bounds, the states of a solid along a ray, and the
 * layout of the scene's tables.
 *
 * Per-ray buffers. A ray collects its candidates, the solids whose boxes it meets (bvh.h), and keeps per
 * candidate its solid, its box's t range, and where its bisection walk stands (segments.h): 3 ints, 5 reals and a
 * node index (36 bytes in float, 60 in double: src/render_scene.c, candidate_bytes), plus one byte per solid of
 * the scene for the states (kept all OUT between rays). That is all: the walks give the solids' state changes
 * in t order, so partitions are classified as they are passed (weave.h) and neither segments nor partitions
 * are stored. A render starts with room for SCENE_RAY_CANDIDATES; a ray that
 * meets more boxes stops, is listed, and is traced again with four times the room, until it fits (never
 * truncated).
 */
#ifndef KERNELS_SCENE_DATA_H
#define KERNELS_SCENE_DATA_H
#include "params.h"

#define SCENE_RAY_CANDIDATES 32

/* A work-item of the first pass renders a block of PACKET_W x PACKET_H tiles, SCENE_BLOCK_W x SCENE_BLOCK_H pixels:
 * the union's tile pass (kernels/scene_union.h) searches its PACKET_LANES tiles in SIMD lanes, then its packets are
 * traced. Its packets: SCENE_TILE_PACKETS a tile, SCENE_BLOCK_PACKETS in all (64 whatever the packets' width),
 * numbered tile by tile (the tiles in rows of PACKET_W), each tile's in rows of SCENE_TILE_PACKETS_W. The widths
 * are the device's only: the host's layout reads the renderer's (src/render.c: render_block_w). */
#define SCENE_BLOCK_H (PACKET_H * TILE_SIZE)
#define SCENE_BLOCK_PACKETS (TILE_SIZE * TILE_SIZE)
/* The same for packets pw pixels wide, as the host lays them out (src/render_effects_samples.c). */
#define SCENE_BLOCK_W_OF(pw) ((pw) * TILE_SIZE)
#define SCENE_TILE_PACKETS_W_OF(pw) (TILE_SIZE / (pw))
#define SCENE_TILE_PACKETS_OF(pw) (SCENE_TILE_PACKETS_W_OF(pw) * (TILE_SIZE / PACKET_H))
#if IA_DEVICE
#define SCENE_BLOCK_W SCENE_BLOCK_W_OF(PACKET_W)
#define SCENE_TILE_PACKETS_W SCENE_TILE_PACKETS_W_OF(PACKET_W)
#define SCENE_TILE_PACKETS SCENE_TILE_PACKETS_OF(PACKET_W)
#endif

/* -aa's samples on the segment path (iacsg_render_scene_samples, src/render_effects_samples.c) are the pixels of an
 * image aa times as wide and high, of which a work-item traces the packets listed in one block: SCENE_SAMPLES_INTS
 * ints, the block's column and row (in blocks), the mask of its packets to trace (two ints: packets 0-31 and
 * 32-63) and the first of their output slots (PACKET_LANES lanes a slot, a slot a packet, in packet order). */
enum { SCENE_SAMPLES_BX = 0, SCENE_SAMPLES_BY = 1, SCENE_SAMPLES_MASK = 2, SCENE_SAMPLES_SLOT = 4,
       SCENE_SAMPLES_INTS = 5 };

/* A solid's state over a part of a ray, decided on the enclosure F of its function over the part's box: OUT
 * where F > 0, IN where F < 0, BOUNDARY where 0 is in F on a leaf of the bisection (width <= eps): the solid
 * may be in or out there. OUT is 0: the per-ray table of states starts, and is left, all OUT. */
#define SCENE_OUT 0
#define SCENE_IN 1
#define SCENE_BOUNDARY 2

/* The BVH over the solids' boxes, in preorder: node k has a box (6 reals, x0 y0 z0 x1 y1 z1, rounded outward)
 * and two ints: the node that follows its subtree (where a ray that misses the box goes on), and the solid of a
 * leaf (-1 for an inner node). A solid whose inside reaches beyond its box, or that has no proven box, has an
 * infinite one: every ray evaluates it all along. After the nodes' links, one int per solid: its leaf (-1 where
 * none: a solid of no region), for a packet's lanes (segments_lanes_frame.h). */
#define SCENE_BVH_SKIP 0
#define SCENE_BVH_SOLID 1

/* An item (region or surface): SCENE_ITEM_INTS ints. Its tree (or condition) is nodes[root .. root + size),
 * kernels/csg_node.h, as the scene has it; the weave classifies a region by its terms (below), each relinearised so
 * that its evaluation needs at most SCENE_TREE_STACK values at once (kernels/classify.h). */
enum { SCENE_ITEM_KIND = 0, SCENE_ITEM_ROOT = 1, SCENE_ITEM_SIZE = 2, SCENE_ITEM_SOLID = 3, SCENE_ITEM_INTS = 4 };
/* An entry of a solid's list (src/scene_terms.h): a term of a region, one of whose trigger solids it is: the
 * region, and the term's tree nodes[root .. root + size), relinearised like a region's. A solid's entries are in
 * the regions' order. */
enum { SCENE_TERM_ITEM = 0, SCENE_TERM_ROOT = 1, SCENE_TERM_SIZE = 2, SCENE_TERM_INTS = 3 };
/* An item's material: SCENE_MATERIAL_FLOATS floats, its linear albedo, highlight weight and exponent, the
 * fraction of light it reflects and its opacity. */
enum {
    SCENE_MATERIAL_RGB = 0,
    SCENE_MATERIAL_SPECULAR = 3,
    SCENE_MATERIAL_SHININESS = 4,
    SCENE_MATERIAL_REFLECT = 5,
    SCENE_MATERIAL_OPACITY = 6,
    SCENE_MATERIAL_FLOATS = 7
};
#define SCENE_KIND_REGION 0
#define SCENE_KIND_SURFACE 1
#define SCENE_TREE_STACK 64

#endif
