/* src/cli_writer.c -- see cli_writer.h.
 *
 * Why a process: linked into the command, OpenImageIO's dependency closure (some 260 shared libraries) cost
 * ~180 ms of dynamic linking before main, half of the whole command for a render with a cached kernel. The
 * command is not linked with it; a child forked at start loads libiacsg_image.so (see library_load) while
 * the parent starts OpenCL and builds, and the parent hands it each image through shared memory. A
 * thread could not overlap the two: glibc's dlopen holds one lock, which PoCL's own dlopens wait for.
 *
 * Protocol, over a socket pair (MSG_NOSIGNAL: a dead child is an error, not a SIGPIPE): a writer_request and
 * the path; the child answers every request with an iacsg_error record (status IACSG_OK on success), in order.
 * The pixels of a write are in the shared mapping.
 */
#define _GNU_SOURCE /* MAP_ANONYMOUS, MAP_NORESERVE, MSG_NOSIGNAL */
#include "cli_writer.h"
#include "cli_library.h"
#include "image.h"
#include <dlfcn.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#define WRITER_LIBRARY "libiacsg_image.so"

enum { REQUEST_CHECK, REQUEST_WRITE_FLOATS, REQUEST_WRITE_BYTES };

typedef struct {
    int op, width, height, channels, as_float;
    size_t path_len;
} writer_request;

/* The library's shared libraries by soname, deepest first, NULL-terminated (build/image_deps.c, from ldd). */
extern const char *const cli_image_deps[];

/* The library's entry points the command uses (src/image.h). */
typedef struct {
    void *handle;
    void **deps; /* the handles of preload_dependencies, ndeps of them */
    size_t ndeps;
    iacsg_status (*check_format)(const char *, iacsg_error *);
    iacsg_status (*write)(const char *, int, int, int, const float *, int, iacsg_error *);
    iacsg_status (*write_bytes)(const char *, int, int, int, const unsigned char *, iacsg_error *);
} image_library;

struct cli_writer {
    pid_t child;       /* 0: the library runs in this process (fork failed) */
    int sock;          /* this end of the socket pair */
    void *shared;      /* the pixels of a write (up to max_floats floats), shared with the child */
    size_t max_floats;
    int unanswered;    /* checks asked and not yet read */
    iacsg_error check; /* in this process: the first failed check */
    image_library lib; /* in this process */
};

/* Loads the library's dependencies one at a time, deepest first. Loaded by the library's own dlopen, each of
 * OpenImageIO's ~260 libraries binds its symbols by searching them all in one breadth-first list, where its own
 * dependencies come late; loaded on its own, it searches its own dependencies first. The writer's load of the
 * library went from 175 to 118 ms of CPU (perf stat, 10 runs; most of the rest is their constructors). A name that
 * does not load (a library changed since the build) is skipped: the library's own dlopen loads what it needs. */
static void preload_dependencies(image_library *lib) {
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

/* Loads the library (cli_library_open), after its dependencies. RTLD_LAZY: the command calls three functions of it, so binding the rest
 * would be wasted. */
static iacsg_status library_load(image_library *lib, iacsg_error *err) {
    preload_dependencies(lib);
    lib->handle = cli_library_open(WRITER_LIBRARY, "the image library", RTLD_LAZY | RTLD_LOCAL, err);
    if (!lib->handle)
        return err->status;
    *(void **)&lib->check_format = dlsym(lib->handle, "iacsg_image_check_format");
    *(void **)&lib->write = dlsym(lib->handle, "iacsg_image_write");
    *(void **)&lib->write_bytes = dlsym(lib->handle, "iacsg_image_write_bytes");
    if (!lib->check_format || !lib->write || !lib->write_bytes)
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "cannot load the image library: %s", dlerror());
    return IACSG_OK;
}

static iacsg_status library_call(image_library *lib, const writer_request *rq, const char *path,
                                 const void *pixels, iacsg_error *err) {
    if (!lib->handle && library_load(lib, err) != IACSG_OK)
        return err->status;
    if (rq->op == REQUEST_CHECK)
        return lib->check_format(path, err);
    if (rq->op == REQUEST_WRITE_BYTES)
        return lib->write_bytes(path, rq->width, rq->height, rq->channels, pixels, err);
    return lib->write(path, rq->width, rq->height, rq->channels, pixels, rq->as_float, err);
}

/* Floats to 8 bits as OpenImageIO converts them (clamped to [0, 1], rounded to nearest; NaN gives 0): done
 * here, in the copy to shared memory, it costs a few ms; in the child it was ~14 ms of each frame's write. */
static void floats_to_bytes(const float *in, unsigned char *out, size_t n) {
    for (size_t k = 0; k < n; k++) {
        float v = in[k] > 0 ? in[k] : 0.0f;
        out[k] = (unsigned char)((v < 1 ? v : 1.0f) * 255.0f + 0.5f);
    }
}

/* Sends (or receives) all `size` bytes, through interruptions; 0 when the other end is gone. */
static int transfer_all(int fd, char *p, size_t size, int sending) {
    while (size > 0) {
        ssize_t n = sending ? send(fd, p, size, MSG_NOSIGNAL) : recv(fd, p, size, 0);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return 0;
        p += n;
        size -= (size_t)n;
    }
    return 1;
}
static int send_all(int fd, const void *data, size_t size) { return transfer_all(fd, (char *)data, size, 1); }
static int recv_all(int fd, void *data, size_t size) { return transfer_all(fd, data, size, 0); }

/* The child: answers requests until the parent closes its end. Never returns. It ignores SIGTERM, which mpirun
 * sends to a rank's whole process group when it stops a job: a write under way then still ends in its rename,
 * never as a partial file, and the child ends at the next read, when the parent's end is closed. */
static void child_serve(int sock, const void *shared) {
    signal(SIGTERM, SIG_IGN);
    image_library lib = {0};
    writer_request rq;
    char *path = NULL;
    while (recv_all(sock, &rq, sizeof rq)) {
        char *grown = realloc(path, rq.path_len + 1);
        if (!grown || !recv_all(sock, grown, rq.path_len))
            break;
        path = grown;
        path[rq.path_len] = '\0';
        iacsg_error e = {0};
        library_call(&lib, &rq, path, shared, &e);
        if (!send_all(sock, &e, sizeof e))
            break;
    }
    _exit(0); /* no atexit handlers, no flush of the parent's stdio buffers */
}

iacsg_status cli_writer_start(size_t max_floats, cli_writer **out, iacsg_error *err) {
    cli_writer *w = calloc(1, sizeof *w);
    if (!w)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    w->sock = -1;
    w->max_floats = max_floats;
    int pair[2];
    void *shared = mmap(NULL, max_floats * sizeof(float), PROT_READ | PROT_WRITE,
                        MAP_SHARED | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (shared != MAP_FAILED && socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) == 0) {
        fflush(NULL); /* or the child's copy of the buffers could be written twice */
        pid_t pid = fork();
        if (pid == 0) {
            close(pair[0]);
            child_serve(pair[1], shared);
        }
        close(pair[1]);
        if (pid > 0) {
            w->child = pid;
            w->sock = pair[0];
            w->shared = shared;
        } else {
            close(pair[0]);
        }
    }
    if (!w->child && shared != MAP_FAILED)
        munmap(shared, max_floats * sizeof(float));
    *out = w;
    return IACSG_OK;
}

/* The child's answer to the oldest request, or an error when it is gone. */
static iacsg_status child_answer(cli_writer *w, iacsg_error *err) {
    if (w->child < 0)
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer process is gone");
    if (recv_all(w->sock, err, sizeof *err))
        return err->status;
    int status = 0;
    waitpid(w->child, &status, 0);
    w->child = -1; /* reaped: cli_writer_stop must not wait again */
    if (WIFSIGNALED(status))
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer process died (signal %d)",
                               WTERMSIG(status));
    return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer process ended unexpectedly");
}

static iacsg_status child_request(cli_writer *w, const writer_request *rq, const char *path, iacsg_error *err) {
    if (w->child < 0 || !send_all(w->sock, rq, sizeof *rq) || !send_all(w->sock, path, rq->path_len))
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer process is gone");
    return IACSG_OK;
}

void cli_writer_check(cli_writer *w, const char *path) {
    writer_request rq = {.op = REQUEST_CHECK, .path_len = strlen(path)};
    if (w->child == 0) {
        if (w->check.status == IACSG_OK)
            library_call(&w->lib, &rq, path, NULL, &w->check);
        return;
    }
    if (child_request(w, &rq, path, &w->check) == IACSG_OK)
        w->unanswered++;
}

iacsg_status cli_writer_checked(cli_writer *w, iacsg_error *err) {
    while (w->unanswered > 0 && w->check.status == IACSG_OK) {
        w->unanswered--;
        iacsg_error answer = {0};
        if (child_answer(w, &answer) != IACSG_OK)
            w->check = answer;
    }
    if (w->check.status != IACSG_OK) {
        *err = w->check;
        return err->status;
    }
    return IACSG_OK;
}

iacsg_status cli_writer_write(cli_writer *w, const char *path, int width, int height, int channels,
                              const float *pixels, int as_float, iacsg_error *err) {
    writer_request rq = {REQUEST_WRITE_FLOATS, width, height, channels, as_float, strlen(path)};
    if (cli_writer_checked(w, err) != IACSG_OK)
        return err->status;
    if (w->child == 0)
        return library_call(&w->lib, &rq, path, pixels, err);
    size_t count = (size_t)width * (size_t)height * (size_t)channels;
    if (count > w->max_floats)
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "%s: image larger than the writer was started for", path);
    if (as_float) {
        memcpy(w->shared, pixels, count * sizeof(float));
    } else {
        rq.op = REQUEST_WRITE_BYTES;
        floats_to_bytes(pixels, w->shared, count);
    }
    if (child_request(w, &rq, path, err) != IACSG_OK)
        return err->status;
    return child_answer(w, err);
}

void cli_writer_stop(cli_writer *w) {
    if (!w)
        return;
    if (w->child > 0) {
        /* Not waited for: its exit unmaps OpenImageIO's ~120 MB, which took ~14 ms of every command's end. With
         * SIGCHLD ignored the kernel reaps it. Every write was answered: it can only be loading or checking. */
        signal(SIGCHLD, SIG_IGN);
        kill(w->child, SIGKILL);
    }
    if (w->sock >= 0)
        close(w->sock);
    if (w->shared)
        munmap(w->shared, w->max_floats * sizeof(float));
    if (w->lib.handle)
        dlclose(w->lib.handle);
    for (size_t k = w->lib.ndeps; k > 0; k--)
        dlclose(w->lib.deps[k - 1]);
    free(w->lib.deps);
    free(w);
}
