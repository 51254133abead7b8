/* src/cli_view_display.h -- what the viewer shows of a frame: its colour, depth, normals or ids, as 3 floats
 * a pixel in [0, 1], averaged over factor x factor blocks when the frame was supersampled (antialiasing). */
#ifndef IACSG_CLI_VIEW_DISPLAY_H
#define IACSG_CLI_VIEW_DISPLAY_H
#include "render.h"
#include <stddef.h>

typedef enum { VIEW_COLOUR, VIEW_DEPTH, VIEW_NORMALS, VIEW_IDS } view_mode;

extern const char *const view_mode_names[4];

/* Fills out (frame->width / factor) x (frame->height / factor) pixels, 3 floats each. The frame has depth and
 * normals. Depth: nearest white to farthest dark grey over the frame's hits; normals: 0.5 + 0.5 n; ids: each
 * hit pixel in its solid's colour (an expression is one solid, id 0); misses black but in colour mode. */
void view_display(const iacsg_frame *frame, view_mode mode, int factor, float *out);

/* Floats in [0, 1] to bytes, as image files store them (rounded to nearest). */
void view_display_bytes(const float *in, size_t count, unsigned char *out);

#endif
