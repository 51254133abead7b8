/* src/render_effects_edges.h -- -aa's edge test (src/render_effects_edges.c). */
#ifndef IACSG_RENDER_EFFECTS_EDGES_H
#define IACSG_RENDER_EFFECTS_EDGES_H
#include "iacsg.h"

/* Lists in out (room for every pixel of the traced rows) the pixels of the traced rows row0 .. row1 - 1 that differ
 * from a traced neighbour (left, right, above, below): in id (fr->ids, or without them 0 a hit; -1 a miss, whose
 * depth is +inf), in a channel of their colours (fr->rgb, 3 floats a pixel) by more than `contrast`, or as two hits
 * in depth by more than `near_depth` times the nearer. In the order of the packets' blocks (PACKET_W x PACKET_H
 * pixels from row row0: rows of blocks top to bottom, blocks left to right, a block's pixels row by row), so that
 * a packet of secondary rays comes from neighbouring pixels. Returns how many, or -1 out of memory. The rows go in
 * bands of whole rows of blocks, one a CPU (at least 64 rows a band). */
long fx_find_edges(const iacsg_frame *fr, int row0, int row1, float contrast, float near_depth, int *out);

/* fx_find_edges in `bands` bands (at most 8, and a row of blocks each), each a thread of its own but the first. */
long fx_find_edges_banded(const iacsg_frame *fr, int row0, int row1, float contrast, float near_depth, int bands,
                          int *out);

#endif
