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

/* The index of the last node of the tree at `root`: the leaf at the end of its rightmost path. */
IA_FN int csg_tree_last(const KERNEL_GLOBAL kernel_u32 *nodes, int root) {
    int k = root;
    for (;;) {
        int op = CSG_NODE_OP(nodes[k]);
        if (op == CSG_INSIDE || op == CSG_OUTSIDE)
            return k;
        k = op == CSG_NOT ? k + 1 : (int)CSG_NODE_ARG(nodes[k]);
    }
}

/* A condition is evaluated over a box from its last node back to its root (kernels/surface.h), keeping the
 * values of finished subtrees on a stack of CSG_STACK_MAX entries of 2 bits, one 64-bit word: no recursion and
 * bounded private memory. csg_stack_need is the depth that evaluation reaches for the tree at `root` (a chain
 * a & b & c & ... needs one entry per operand); the scene rejects a condition that needs more. */
#define CSG_STACK_MAX 32
IA_FN int csg_stack_need(const KERNEL_GLOBAL kernel_u32 *nodes, int root) {
    int depth = 0, need = 0;
    for (int k = csg_tree_last(nodes, root); k >= root; k--) {
        int op = CSG_NODE_OP(nodes[k]);
        depth += op == CSG_INSIDE || op == CSG_OUTSIDE ? 1 : op == CSG_NOT ? 0 : -1;
        need = depth > need ? depth : need;
    }
    return need;
}

#endif
