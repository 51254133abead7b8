/* src/image.h -- image files through OpenImageIO (src/image_oiio.cpp, the only C++ file). Pixels are floats,
 * `channels` of them per pixel, rows from the top. */
#ifndef IACSG_IMAGE_H
#define IACSG_IMAGE_H
#include "error.h"

IACSG_API_BEGIN

/* Writes an image; the file format comes from the extension of `path` (png, exr, tif, jpg, ...). With
 * as_float the file stores 32-bit floats where the format can (exr, tif), otherwise 8 bits per channel from
 * values in [0, 1]. The data goes to a temporary file in the same directory, renamed over `path` only once
 * complete: a failure never leaves a partial file nor touches an existing one. */
iacsg_status iacsg_image_write(const char *path, int width, int height, int channels, const float *pixels,
                               int as_float, iacsg_error *err);

/* The same for pixels already in 8 bits (0 to 255). */
iacsg_status iacsg_image_write_bytes(const char *path, int width, int height, int channels,
                                     const unsigned char *pixels, iacsg_error *err);

/* IACSG_OK if `path` names a format OpenImageIO can write (by its extension): to refuse a name early. */
iacsg_status iacsg_image_check_format(const char *path, iacsg_error *err);

/* Reads an image as floats (8-bit files give values in [0, 1]). *pixels is malloc'ed; the caller free()s it. */
iacsg_status iacsg_image_read(const char *path, int *width, int *height, int *channels, float **pixels,
                              iacsg_error *err);

IACSG_API_END
#endif
