/* kernels/csg_node.h -- the 32-bit nodes of region trees and surface conditions (the Domingues seed), shared by
 * the host (implicits/scene.c, the front ends, the tests) and the device (the segment path's classification).
 *
 * A node is 3 bits of operator and 29 bits of operand. A tree is stored depth first: a node's left (or only)
 * child is the next node; a binary node's operand is the index of its right child; a leaf's operand is a solid
 * index. The trees of all regions and surfaces of a scene share one array, so operands are absolute indices
 * into it. Region trees use INSIDE, UNION, INTERSECT and DIFFERENCE; surface conditions (a level set kept where
 * the condition holds) use all six: INSIDE is "solid < 0", OUTSIDE "solid > 0", UNION "or", INTERSECT "and".
 */
#ifndef KERNELS_CSG_NODE_H
#define KERNELS_CSG_NODE_H
#include "compat.h"

#define CSG_ARG_BITS 29
#define CSG_ARG_MAX ((1u << CSG_ARG_BITS) - 1u)

enum {
    CSG_INSIDE = 0,     /* leaf: the solid's f < 0 */
    CSG_OUTSIDE = 1,    /* leaf: the solid's f > 0 (conditions only) */
    CSG_UNION = 2,      /* left | right (or) */
    CSG_INTERSECT = 3,  /* left & right (and) */
    CSG_DIFFERENCE = 4, /* left \ right (and not) */
    CSG_NOT = 5         /* ! child, the child follows (conditions only) */
};

#define CSG_NODE(op, arg) ((kernel_u32)(op) << CSG_ARG_BITS | (kernel_u32)(arg))
#define CSG_NODE_OP(n) ((int)((kernel_u32)(n) >> CSG_ARG_BITS))
#define CSG_NODE_ARG(n) ((kernel_u32)(n) & CSG_ARG_MAX)

#endif
