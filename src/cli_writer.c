/* src/cli_writer.c -- see cli_writer.h.
 *
 * Why another process: linked into the command, OpenImageIO's dependency closure (some 260 shared libraries) cost
 * ~180 ms of dynamic linking before main, half of the whole command for a render with a cached kernel. The
 * command is not linked with it; it hands each image, through shared memory, to a writer that loads
 * libiacsg_image.so (src/cli_writer_lib.c). A thread could not overlap the load with OpenCL's start: glibc's
 * dlopen holds one lock, which PoCL's own dlopens wait for.
 *
 * Which writer, in order: the server that outlives the command (src/cli_writer_server.c: after the first command
 * no command waits for the load any more); else, when it is disabled (IACSG_WRITER_IDLE=0) or cannot be had, a
 * child forked here that loads the library while the command starts OpenCL; else (no fork) this process. A server
 * lost in the middle (killed, or ended between a command's connect and its request) is replaced by this process,
 * which asks again the questions it had not answered: the command sees the same answers, only later.
 *
 * Requests and answers: cli_writer_lib.h's, over a SOCK_SEQPACKET socket (MSG_NOSIGNAL: a dead writer is an
 * error, not a SIGPIPE). IACSG_WRITER_TRACE (non-empty) prints on stderr which writer a command got.
 */
#define _GNU_SOURCE /* memfd_create, MAP_ANONYMOUS, MAP_NORESERVE, MSG_NOSIGNAL */
#include "cli_writer.h"
#include "cli_writer_lib.h"
#include "cli_writer_server.h"
#include "image_bytes.h"
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

typedef enum { WRITER_HERE, WRITER_CHILD, WRITER_SERVER } writer_mode;

struct cli_writer {
    writer_mode mode;
    pid_t child;       /* WRITER_CHILD: the child; -1 once reaped */
    int sock;          /* this end of the child's or the server's socket */
    void *shared;      /* the pixels of a write, shared with the child or the server */
    size_t shared_size;
    char **checks;     /* the paths of the checks asked through sock, in order */
    int nchecks, answered;
    iacsg_error check; /* the first failed check */
    image_library lib; /* WRITER_HERE */
    int trace;
};

static void trace(const cli_writer *w, const char *how) {
    if (w->trace)
        fprintf(stderr, "iacsg: image writer: %s\n", how);
}

/* A request served in this process, as the child or the server would serve it. */
static iacsg_status serve_here(cli_writer *w, const writer_request *rq, const char *path, const void *pixels,
                               size_t pixels_size, iacsg_error *err) {
    size_t size = sizeof *rq + rq->path_len;
    char *msg = malloc(size);
    if (!msg)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    memcpy(msg, rq, sizeof *rq);
    memcpy(msg + sizeof *rq, path, rq->path_len);
    iacsg_status st = writer_serve_message(&w->lib, msg, size, pixels, pixels_size, err);
    free(msg);
    return st;
}

static void check_here(cli_writer *w, const char *path) {
    writer_request rq = {.op = REQUEST_CHECK, .path_len = strlen(path)};
    if (w->check.status == IACSG_OK)
        serve_here(w, &rq, path, NULL, 0, &w->check);
}

/* The server is lost: this process writes from now on, and answers the checks the server had not. */
static void fall_back_here(cli_writer *w) {
    close(w->sock);
    w->sock = -1;
    w->mode = WRITER_HERE;
    trace(w, "this process (the server was lost)");
    for (; w->answered < w->nchecks; w->answered++)
        check_here(w, w->checks[w->answered]);
}

static void start_child(cli_writer *w) {
    int pair[2];
    if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, pair) != 0)
        return;
    fflush(NULL); /* or the child's copy of the buffers could be written twice */
    pid_t pid = fork();
    if (pid == 0) {
        close(pair[0]);
        cli_writer_serve_child(pair[1], w->shared, w->shared_size);
    }
    close(pair[1]);
    if (pid > 0) {
        w->mode = WRITER_CHILD;
        w->child = pid;
        w->sock = pair[0];
    } else {
        close(pair[0]);
    }
}

/* The pixels' memory: a memfd, which the server maps from the descriptor it is sent; else an anonymous shared
 * mapping, which a forked child shares. The memfd is mapped only after the server's start, so that a server the
 * command starts does not inherit it. */
iacsg_status cli_writer_start(size_t max_floats, cli_writer **out, iacsg_error *err) {
    cli_writer *w = calloc(1, sizeof *w);
    if (!w)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    const char *t = getenv("IACSG_WRITER_TRACE");
    w->trace = t && *t;
    w->sock = -1;
    w->shared_size = max_floats * sizeof(float);
    int memfd = memfd_create("iacsg-pixels", MFD_CLOEXEC);
    if (memfd >= 0 && ftruncate(memfd, (off_t)w->shared_size) != 0) {
        close(memfd);
        memfd = -1;
    }
    int idle = cli_writer_server_idle(), started = 0;
    if (memfd >= 0 && idle > 0 && (w->sock = cli_writer_server_connect(memfd, idle, &started)) >= 0)
        w->mode = WRITER_SERVER;
    void *shared = mmap(NULL, w->shared_size, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_NORESERVE |
                        (memfd >= 0 ? 0 : MAP_ANONYMOUS), memfd, 0);
    if (memfd >= 0)
        close(memfd);
    if (shared != MAP_FAILED)
        w->shared = shared;
    if (!w->shared && w->mode == WRITER_SERVER) {
        close(w->sock);
        w->sock = -1;
        w->mode = WRITER_HERE;
    }
    if (w->mode == WRITER_HERE && w->shared)
        start_child(w);
    trace(w, w->mode == WRITER_SERVER ? (started ? "server (started)" : "server (reused)")
             : w->mode == WRITER_CHILD ? "child process" : "this process");
    *out = w;
    return IACSG_OK;
}

/* The writer's next answer: 0, or -1 when it is gone (a lost child's reason in *err). */
static int receive(cli_writer *w, iacsg_error *err) {
    ssize_t n;
    while ((n = recv(w->sock, err, sizeof *err, 0)) < 0 && errno == EINTR)
        ;
    if (n == (ssize_t)sizeof *err)
        return 0;
    if (w->mode == WRITER_CHILD) {
        int status = 0;
        waitpid(w->child, &status, 0);
        w->child = -1; /* reaped: cli_writer_stop must not kill it */
        if (WIFSIGNALED(status))
            iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer process died (signal %d)", WTERMSIG(status));
        else
            iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "the image writer process ended unexpectedly");
    }
    return -1;
}

static int send_request(cli_writer *w, const writer_request *rq, const char *path) {
    char msg[WRITER_MESSAGE_MAX];
    if (w->sock < 0 || rq->path_len > sizeof msg - sizeof *rq)
        return -1;
    memcpy(msg, rq, sizeof *rq);
    memcpy(msg + sizeof *rq, path, rq->path_len);
    return send(w->sock, msg, sizeof *rq + rq->path_len, MSG_NOSIGNAL) == (ssize_t)(sizeof *rq + rq->path_len) ? 0
                                                                                                              : -1;
}

static const char gone[] = "the image writer process is gone";

void cli_writer_check(cli_writer *w, const char *path) {
    if (w->mode == WRITER_HERE) {
        check_here(w, path);
        return;
    }
    char **grown = realloc(w->checks, (size_t)(w->nchecks + 1) * sizeof *grown);
    char *copy = strdup(path);
    if (grown)
        w->checks = grown;
    if (!grown || !copy) {
        free(copy);
        if (w->check.status == IACSG_OK)
            iacsg_error_set(&w->check, IACSG_ERR_NOMEM, 0, 0, "out of memory");
        return;
    }
    w->checks[w->nchecks++] = copy;
    writer_request rq = {.op = REQUEST_CHECK, .path_len = strlen(path)};
    if (send_request(w, &rq, path) == 0)
        return;
    if (w->mode == WRITER_SERVER) {
        fall_back_here(w);
    } else if (w->check.status == IACSG_OK) {
        iacsg_error_set(&w->check, IACSG_ERR_IO, 0, 0, gone);
        w->answered = w->nchecks;
    }
}

iacsg_status cli_writer_checked(cli_writer *w, iacsg_error *err) {
    while (w->mode != WRITER_HERE && w->answered < w->nchecks) {
        iacsg_error answer = {0};
        if (receive(w, &answer) != 0) {
            if (w->mode == WRITER_SERVER) {
                fall_back_here(w);
                break;
            }
            w->answered = w->nchecks;
        } else {
            w->answered++;
        }
        if (answer.status != IACSG_OK && w->check.status == IACSG_OK)
            w->check = answer;
    }
    if (w->check.status != IACSG_OK) {
        *err = w->check;
        return err->status;
    }
    return IACSG_OK;
}

/* MADV_POPULATE_WRITE (Linux 5.14) faults the pages in at once, as the first write would one by one (~2 ms for a
 * 1024x1024 frame's 3 MB on the Intel Xeon): called while OpenCL starts on its thread, that time is taken off the
 * frame's write. Advice only: where it fails, the write faults them in as before. */
void cli_writer_prefault(cli_writer *w, size_t bytes) {
#ifdef MADV_POPULATE_WRITE
    if (w && w->shared)
        madvise(w->shared, bytes < w->shared_size ? bytes : w->shared_size, MADV_POPULATE_WRITE);
#else
    (void)w;
    (void)bytes;
#endif
}

/* Sends the write rq of the pixels already in shared memory, and waits for its answer; a server lost meanwhile is
 * replaced by this process. */
static iacsg_status send_write(cli_writer *w, writer_request *rq, const char *path, iacsg_error *err) {
    if (send_request(w, rq, path) == 0 && receive(w, err) == 0)
        return err->status;
    if (w->mode == WRITER_SERVER) {
        fall_back_here(w);
        return serve_here(w, rq, path, w->shared, w->shared_size, err);
    }
    if (err->status == IACSG_OK)
        iacsg_error_set(err, IACSG_ERR_IO, 0, 0, gone);
    return err->status;
}

/* Whether `bytes` of pixels fit the shared memory (else err says so). */
static int fits(cli_writer *w, const char *path, size_t bytes, iacsg_error *err) {
    if (bytes <= w->shared_size)
        return 1;
    iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "%s: image larger than the writer was started for", path);
    return 0;
}

iacsg_status cli_writer_write(cli_writer *w, const char *path, int width, int height, int channels,
                              const float *pixels, int as_float, iacsg_error *err) {
    writer_request rq = {REQUEST_WRITE_FLOATS, width, height, channels, as_float, strlen(path)};
    if (cli_writer_checked(w, err) != IACSG_OK)
        return err->status;
    size_t count = (size_t)width * (size_t)height * (size_t)channels;
    if (w->mode == WRITER_HERE)
        return serve_here(w, &rq, path, pixels, count * sizeof(float), err);
    if (!fits(w, path, count * (as_float ? sizeof(float) : 1), err))
        return err->status;
    if (as_float) {
        memcpy(w->shared, pixels, count * sizeof(float));
    } else {
        rq.op = REQUEST_WRITE_BYTES;
        image_floats_to_bytes(pixels, w->shared, count);
    }
    return send_write(w, &rq, path, err);
}

iacsg_status cli_writer_write_bytes(cli_writer *w, const char *path, int width, int height, int channels,
                                    const unsigned char *pixels, iacsg_error *err) {
    writer_request rq = {REQUEST_WRITE_BYTES, width, height, channels, 0, strlen(path)};
    if (cli_writer_checked(w, err) != IACSG_OK)
        return err->status;
    size_t count = (size_t)width * (size_t)height * (size_t)channels;
    if (w->mode == WRITER_HERE)
        return serve_here(w, &rq, path, pixels, count, err);
    if (!fits(w, path, count, err))
        return err->status;
    memcpy(w->shared, pixels, count);
    return send_write(w, &rq, path, err);
}

void cli_writer_stop(cli_writer *w) {
    if (!w)
        return;
    if (w->mode == WRITER_CHILD && w->child > 0) {
        /* Not waited for: its exit unmaps OpenImageIO's ~120 MB, which took ~14 ms of every command's end. With
         * SIGCHLD ignored the kernel reaps it. Every write was answered: it can only be loading or checking. */
        signal(SIGCHLD, SIG_IGN);
        kill(w->child, SIGKILL);
    }
    if (w->sock >= 0)
        close(w->sock); /* the server drops this client */
    if (w->shared)
        munmap(w->shared, w->shared_size);
    writer_library_unload(&w->lib);
    for (int k = 0; k < w->nchecks; k++)
        free(w->checks[k]);
    free(w->checks);
    free(w);
}
