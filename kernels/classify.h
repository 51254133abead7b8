/* kernels/classify.h -- the value of a region's tree (or a surface's condition) over a partition, in
 * three-valued logic: each solid is IN, OUT or BOUNDARY (may be either) there (scene_data.h), and the tree's
 * value is a pair of bits, "may be in" and "may be out", which propagate exactly: a union may be in where either
 * side may be, and may be out where both may be; an intersection the other way round; a difference is left and
 * not right; NOT swaps them.
 *
 * Without recursion: the nodes are visited from the tree's last to its root (children follow their parent, so
 * each node finds its children's values on a stack, the left one on top). The stack is two words of bits; the
 * host orders each node's children so that the deeper one is evaluated first, which bounds the stack by the
 * tree's Strahler number (at most log2 of its leaves + 1), checked against SCENE_TREE_STACK when the scene is
 * loaded (src/render_scene.c).
 */
#ifndef KERNELS_CLASSIFY_H
#define KERNELS_CLASSIFY_H
#include "csg_node.h"
#include "scene_data.h"

#define CLASSIFY_MAY_IN 1
#define CLASSIFY_MAY_OUT 2

/* The value of a solid's state as a leaf "solid < 0". */
IA_FN int classify_leaf(int state) {
    return (state != SCENE_OUT ? CLASSIFY_MAY_IN : 0) | (state != SCENE_IN ? CLASSIFY_MAY_OUT : 0);
}

/* The value of the tree nodes[root .. root + size) where solid k has state[k]. */
IA_FN int classify_tree(const KERNEL_GLOBAL kernel_u32 *nodes, int root, int size,
                        const KERNEL_GLOBAL unsigned char *state) {
    kernel_u64 may_in = 0, may_out = 0; /* the stack: bit 0 is the top */
    for (int k = root + size - 1; k >= root; k--) {
        kernel_u32 node = nodes[k];
        int op = CSG_NODE_OP(node), value;
        if (op == CSG_INSIDE || op == CSG_OUTSIDE) {
            value = classify_leaf(state[CSG_NODE_ARG(node)]);
            if (op == CSG_OUTSIDE)
                value = (value & 1) << 1 | value >> 1;
        } else {
            int a = (int)(may_in & 1) | (int)(may_out & 1) << 1; /* the left child, or NOT's only one */
            may_in >>= 1;
            may_out >>= 1;
            if (op == CSG_NOT) {
                value = (a & 1) << 1 | a >> 1;
            } else {
                int b = (int)(may_in & 1) | (int)(may_out & 1) << 1;
                may_in >>= 1;
                may_out >>= 1;
                int in_a = a & 1, out_a = a >> 1, in_b = b & 1, out_b = b >> 1, in, out;
                if (op == CSG_UNION) {
                    in = in_a | in_b;
                    out = out_a & out_b;
                } else if (op == CSG_INTERSECT) {
                    in = in_a & in_b;
                    out = out_a | out_b;
                } else { /* CSG_DIFFERENCE */
                    in = in_a & out_b;
                    out = out_a | in_b;
                }
                value = in | out << 1;
            }
        }
        may_in = may_in << 1 | (kernel_u64)(value & 1);
        may_out = may_out << 1 | (kernel_u64)(value >> 1);
    }
    return (int)(may_in & 1) | (int)(may_out & 1) << 1;
}

/* Whether solid k is a leaf of the tree nodes[root .. root + size). */
IA_FN int classify_tree_holds(const KERNEL_GLOBAL kernel_u32 *nodes, int root, int size, int k) {
    for (int j = root; j < root + size; j++) {
        int op = CSG_NODE_OP(nodes[j]);
        if ((op == CSG_INSIDE || op == CSG_OUTSIDE) && (int)CSG_NODE_ARG(nodes[j]) == k)
            return 1;
    }
    return 0;
}

#endif
