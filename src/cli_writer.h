/* src/cli_writer.h -- the image files of the `iacsg` command, written by a child process that loads the image
 * library (libiacsg_image.so: src/image.h over OpenImageIO) while the command starts OpenCL and renders.
 * Calls follow src/image.h; errors come back as iacsg_error records. */
#ifndef IACSG_CLI_WRITER_H
#define IACSG_CLI_WRITER_H
#include "error.h"
#include <stddef.h>

typedef struct cli_writer cli_writer;

/* Starts the writer for images of up to max_floats floats. Call it before anything starts threads (OpenCL):
 * it forks. Falls back to loading the library in this process when it cannot fork. */
iacsg_status cli_writer_start(size_t max_floats, cli_writer **out, iacsg_error *err);

/* Asks whether `path` names a format the library can write (iacsg_image_check_format); the answer is read by
 * cli_writer_checked, so the question costs nothing while the library loads. */
void cli_writer_check(cli_writer *w, const char *path);

/* The answers to the questions asked so far: the first failure, or IACSG_OK. Waits for them. */
iacsg_status cli_writer_checked(cli_writer *w, iacsg_error *err);

/* Makes the first `bytes` of the shared memory a write copies pixels into resident now (an 8-bit image's are
 * width x height x channels), so that the write does not fault them in. For the slack while OpenCL starts. */
void cli_writer_prefault(cli_writer *w, size_t bytes);

/* iacsg_image_write through the writer; waits until the file is written (or has failed). */
iacsg_status cli_writer_write(cli_writer *w, const char *path, int width, int height, int channels,
                              const float *pixels, int as_float, iacsg_error *err);

/* The same for pixels already 8-bit (channels bytes a pixel), written as they are. */
iacsg_status cli_writer_write_bytes(cli_writer *w, const char *path, int width, int height, int channels,
                                    const unsigned char *pixels, iacsg_error *err);

/* Ends the child (at once: every write has been answered) and frees the writer. NULL is allowed. For the end of a
 * command: the child is not waited for, and this process ignores SIGCHLD from then on (so it leaves no zombie). */
void cli_writer_stop(cli_writer *w);

#endif
