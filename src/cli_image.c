/* src/cli_image.c -- the CLI's image writer, loaded at run time. Linking OpenImageIO directly pulls in ~260
 * shared libraries (OpenCV, ffmpeg, GStreamer, ...) whose loading costs every command ~0.13 s before main, and
 * makes every later symbol lookup (PoCL's, LLVM's) search them too. Instead the render command dlopen()s
 * libiacsg_image.so (src/image_oiio.cpp, built beside the executable) on a thread while it parses and starts
 * OpenCL, and the other commands never load it. glibc runs one dlopen at a time, so the thread overlaps only
 * the part of the OpenCL start-up that is not itself loading libraries. */
#include "cli.h"
#include <dlfcn.h>
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define LIBRARY_NAME "libiacsg_image.so"

typedef iacsg_status (*write_fn)(const char *, int, int, int, const float *, int, iacsg_error *);
typedef iacsg_status (*check_fn)(const char *, iacsg_error *);

static struct {
    pthread_t thread;
    int started, done;
    /* Never dlclose()d: OpenImageIO keeps allocations in its globals for the life of the process. */
    void *handle;
    write_fn write;
    check_fn check_format;
    char path[4096];
    char failure[400]; /* why loading failed, "" if it did not (copied: dlerror()'s text is per thread) */
} loader = {.path = LIBRARY_NAME};

/* dlsym's object pointer into a function pointer: ISO C has no cast between the two, POSIX makes them alike. */
_Static_assert(sizeof(write_fn) == sizeof(void *) && sizeof(check_fn) == sizeof(void *), "POSIX pointers");
static int find_symbol(const char *name, void *fn) {
    void *sym = dlsym(loader.handle, name);
    memcpy(fn, &sym, sizeof sym);
    return sym != NULL;
}

/* The library beside the executable: the directory of /proc/self/exe, whatever the current directory. */
static int locate_library(void) {
    char exe[sizeof loader.path];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n < 0) {
        snprintf(loader.failure, sizeof loader.failure, "/proc/self/exe: %s", strerror(errno));
        return 0;
    }
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    int dir_len = slash ? (int)(slash - exe) : 0;
    snprintf(loader.path, sizeof loader.path, "%.*s/" LIBRARY_NAME, dir_len, exe);
    return 1;
}

static void *load(void *unused) {
    (void)unused;
    if (!locate_library())
        return NULL;
    loader.handle = dlopen(loader.path, RTLD_NOW | RTLD_LOCAL);
    if (!loader.handle || !find_symbol("iacsg_image_write", &loader.write) ||
        !find_symbol("iacsg_image_check_format", &loader.check_format)) {
        const char *why = dlerror();
        snprintf(loader.failure, sizeof loader.failure, "%s", why ? why : "unknown error");
    }
    return NULL;
}

void cli_image_load_start(void) {
    loader.started = pthread_create(&loader.thread, NULL, load, NULL) == 0;
}

/* Waits for the loader (or loads here, if no thread could start); IACSG_OK once the functions are there. */
static iacsg_status loaded(iacsg_error *err) {
    if (!loader.done) {
        if (loader.started)
            pthread_join(loader.thread, NULL);
        else
            load(NULL);
        loader.done = 1;
    }
    if (loader.failure[0])
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "cannot load the image writer %s: %s", loader.path,
                               loader.failure);
    return IACSG_OK;
}

iacsg_status cli_image_check_format(const char *path, iacsg_error *err) {
    iacsg_status st = loaded(err);
    return st != IACSG_OK ? st : loader.check_format(path, err);
}

iacsg_status cli_image_write(const char *path, int width, int height, int channels, const float *pixels,
                             int as_float, iacsg_error *err) {
    iacsg_status st = loaded(err);
    return st != IACSG_OK ? st : loader.write(path, width, height, channels, pixels, as_float, err);
}
