/* src/render_effects_edges.h -- -aa's edge test (src/render_effects_edges.c). */
#ifndef IACSG_RENDER_EFFECTS_EDGES_H
#define IACSG_RENDER_EFFECTS_EDGES_H
#include "iacsg.h"

/* Marks in edge[] (a byte per pixel of the whole frame, zeroed by the caller) the pixels of the traced rows row0 ..
 * row1 - 1 that differ from a traced neighbour (left, right, above, below): in id (fr->ids, or without them 0 a
 * hit; -1 a miss, whose depth is +inf), in a channel of their colours (fr->rgb, 3 floats a pixel) by more than
 * `contrast`, or as two hits in depth by more than `near_depth` times the nearer. 0, or -1 out of memory. */
int fx_find_edges(const iacsg_frame *fr, int row0, int row1, float contrast, float near_depth, unsigned char *edge);

#endif
