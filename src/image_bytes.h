/* src/image_bytes.h -- a frame's display-encoded colours (floats in [0, 1]) to the 8 bits an image file stores, as
 * OpenImageIO converts them: clamped to [0, 1] (NaN gives 0), then v * 255 rounded half up. The command does it
 * while it copies a frame into the writer's shared memory (src/cli_writer.c). */
#ifndef IACSG_IMAGE_BYTES_H
#define IACSG_IMAGE_BYTES_H
#include <stddef.h>

void image_floats_to_bytes(const float *in, unsigned char *out, size_t n);

#endif
