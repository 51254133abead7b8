/* src/cli_writer_lib.h -- what every image writer of the command shares (src/cli_writer.c's child and its own
 * process, src/cli_writer_server.c's server): the image library (libiacsg_image.so) loaded at run time, and the
 * requests they serve. A request is one message: a writer_request and then the path's bytes (no NUL); the
 * pixels of a write are in memory shared with the command; the answer is one iacsg_error record (IACSG_OK on
 * success). */
#ifndef IACSG_CLI_WRITER_LIB_H
#define IACSG_CLI_WRITER_LIB_H
#include "error.h"
#include <stddef.h>

enum { REQUEST_CHECK, REQUEST_WRITE_FLOATS, REQUEST_WRITE_BYTES };

typedef struct {
    int op, width, height, channels, as_float;
    size_t path_len;
} writer_request;

/* The longest request message: a request and a path of up to 4095 bytes. */
enum { WRITER_MESSAGE_MAX = sizeof(writer_request) + 4095 };

/* The library's entry points the command uses (src/image.h). */
typedef struct {
    void *handle;
    void **deps; /* the handles of preload_dependencies, ndeps of them */
    size_t ndeps;
    iacsg_status (*check_format)(const char *, iacsg_error *);
    iacsg_status (*write)(const char *, int, int, int, const float *, int, iacsg_error *);
    iacsg_status (*write_bytes)(const char *, int, int, int, const unsigned char *, iacsg_error *);
} image_library;

/* Loads the library (its dependencies first); on failure the error says why (and the next call tries again). */
iacsg_status writer_library_load(image_library *lib, iacsg_error *err);
void writer_library_unload(image_library *lib);

/* Serves the request message `msg` (`size` bytes) with the pixels at `pixels` (`pixels_size` bytes there):
 * loads the library if it is not loaded, then checks or writes. A malformed message, or a write larger than the
 * shared memory, is answered with an error. */
iacsg_status writer_serve_message(image_library *lib, const void *msg, size_t size, const void *pixels,
                                  size_t pixels_size, iacsg_error *err);

#endif
