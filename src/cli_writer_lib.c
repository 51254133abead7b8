/* src/cli_writer_lib.c -- see cli_writer_lib.h. */
#include "cli_writer_lib.h"
#include "cli_library.h"
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

#define WRITER_LIBRARY "libiacsg_image.so"

/* The library's shared libraries by soname, deepest first, NULL-terminated (build/image_deps.c, from ldd). */
extern const char *const cli_image_deps[];

/* Loads the library's dependencies one at a time, deepest first. Loaded by the library's own dlopen, each of
 * OpenImageIO's ~260 libraries binds its symbols by searching them all in one breadth-first list, where its own
 * dependencies come late; loaded on its own, it searches its own dependencies first. The writer's load of the
 * library went from 175 to 118 ms of CPU (perf stat, 10 runs; most of the rest is their constructors). A name that
 * does not load (a library changed since the build) is skipped: the library's own dlopen loads what it needs. */
static void preload_dependencies(image_library *lib) {
    if (lib->deps) /* loaded by an earlier try */
        return;
    size_t n = 0;
    while (cli_image_deps[n])
        n++;
    lib->deps = malloc((n + 1) * sizeof *lib->deps);
    for (size_t k = 0; lib->deps && k < n; k++) {
        void *h = dlopen(cli_image_deps[k], RTLD_LAZY | RTLD_LOCAL);
        if (h)
            lib->deps[lib->ndeps++] = h;
    }
}

/* RTLD_LAZY: the command calls three functions of it, so binding the rest would be wasted. */
iacsg_status writer_library_load(image_library *lib, iacsg_error *err) {
    preload_dependencies(lib);
    lib->handle = cli_library_open(WRITER_LIBRARY, "the image library", RTLD_LAZY | RTLD_LOCAL, err);
    if (!lib->handle)
        return err->status;
    *(void **)&lib->check_format = dlsym(lib->handle, "iacsg_image_check_format");
    *(void **)&lib->write = dlsym(lib->handle, "iacsg_image_write");
    *(void **)&lib->write_bytes = dlsym(lib->handle, "iacsg_image_write_bytes");
    if (!lib->check_format || !lib->write || !lib->write_bytes) {
        iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "cannot load the image library: %s", dlerror());
        dlclose(lib->handle);
        lib->handle = NULL;
        return err->status;
    }
    return IACSG_OK;
}

void writer_library_unload(image_library *lib) {
    if (lib->handle)
        dlclose(lib->handle);
    for (size_t k = lib->ndeps; k > 0; k--)
        dlclose(lib->deps[k - 1]);
    free(lib->deps);
    memset(lib, 0, sizeof *lib);
}

iacsg_status writer_serve_message(image_library *lib, const void *msg, size_t size, const void *pixels,
                                  size_t pixels_size, iacsg_error *err) {
    writer_request rq;
    char path[WRITER_MESSAGE_MAX - sizeof rq + 1];
    if (size < sizeof rq)
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer got a malformed request");
    memcpy(&rq, msg, sizeof rq);
    if (rq.path_len != size - sizeof rq || rq.path_len >= sizeof path)
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer got a malformed request");
    memcpy(path, (const char *)msg + sizeof rq, rq.path_len);
    path[rq.path_len] = '\0';
    if (!lib->handle && writer_library_load(lib, err) != IACSG_OK)
        return err->status;
    if (rq.op == REQUEST_CHECK)
        return lib->check_format(path, err);
    size_t each = rq.op == REQUEST_WRITE_BYTES ? 1 : sizeof(float);
    if (rq.width <= 0 || rq.height <= 0 || rq.channels <= 0 ||
        (size_t)rq.width * (size_t)rq.height * (size_t)rq.channels > pixels_size / each)
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: the image writer got a malformed request", path);
    if (rq.op == REQUEST_WRITE_BYTES)
        return lib->write_bytes(path, rq.width, rq.height, rq.channels, pixels, err);
    return lib->write(path, rq.width, rq.height, rq.channels, pixels, rq.as_float, err);
}
