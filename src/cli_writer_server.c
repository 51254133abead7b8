/* src/cli_writer_server.c -- see cli_writer_server.h.
 *
 * Stages: the server's identity (src/cli_server.c names, starts and connects it; its name here also covers the image
 * library), the server's loop (poll over the listener and its clients), and the command's hello.
 *
 * Protocol (SOCK_SEQPACKET, so a message arrives whole): the command's hello, a writer_hello with the pixels'
 * memfd and a descriptor of its working directory (SCM_RIGHTS); then cli_writer_lib.h's requests, each answered
 * in order. The server serves one request at a time, in the command's directory (fchdir) with its umask, so that
 * files land where and as they would from the command itself, and error messages name the same paths. */
#define _GNU_SOURCE /* accept4 */
#include "cli_writer_server.h"
#include "cli_server.h"
#include "cli_writer_lib.h"
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#define WRITER_PROTOCOL 1u
enum { MAX_CLIENTS = 256, DEFAULT_IDLE = 30 };

typedef struct {
    unsigned version; /* WRITER_PROTOCOL */
    unsigned umask;
} writer_hello;

int cli_writer_server_idle(void) { return cli_server_idle("IACSG_WRITER_IDLE", DEFAULT_IDLE); }

/* ---- the server ---- */

typedef struct {
    int fd;
    int cwd;            /* the command's working directory (O_PATH); -1: this process's (the child writer) */
    unsigned umask;
    const void *pixels; /* the shared memory, mapped */
    size_t size;
    int greeted;
} client;

static int greet(client *c, const char *msg, ssize_t size, int fds[2]) {
    writer_hello h;
    if (size != (ssize_t)sizeof h || fds[0] < 0 || fds[1] < 0)
        return 0;
    memcpy(&h, msg, sizeof h);
    struct stat st;
    if (h.version != WRITER_PROTOCOL || fstat(fds[0], &st) != 0)
        return 0;
    c->umask = h.umask & 0777;
    c->cwd = fds[1];
    fds[1] = -1;
    if (st.st_size > 0) {
        void *p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_SHARED | MAP_NORESERVE, fds[0], 0);
        if (p == MAP_FAILED)
            return 0;
        c->pixels = p;
        c->size = (size_t)st.st_size;
    }
    c->greeted = 1;
    return 1;
}

/* Serves the client's next message; 0 when it is gone (or broke the protocol) and must be dropped. */
static int serve_client(image_library *lib, client *c, char *msg) {
    int fds[2];
    ssize_t got = cli_server_recv_fds(c->fd, msg, WRITER_MESSAGE_MAX, fds, 2, MSG_DONTWAIT);
    if (got < 0 && (errno == EAGAIN || errno == EINTR))
        return 1;
    int ok = got > 0;
    if (ok && !c->greeted) {
        ok = greet(c, msg, got, fds);
    } else if (ok) {
        iacsg_error answer = {0};
        if (c->cwd >= 0 && fchdir(c->cwd) != 0) {
            iacsg_error_set(&answer, IACSG_ERR_IO, 0, 0, "the image writer cannot enter the working directory");
        } else {
            if (c->cwd >= 0)
                umask(c->umask);
            writer_serve_message(lib, msg, (size_t)got, c->pixels, c->size, &answer);
            if (c->cwd >= 0 && chdir("/") != 0) /* holds no command's directory between requests */
                ok = 0;
        }
        ok = ok && send(c->fd, &answer, sizeof answer, MSG_DONTWAIT | MSG_NOSIGNAL) == (ssize_t)sizeof answer;
    }
    for (int k = 0; k < 2; k++)
        if (fds[k] >= 0)
            close(fds[k]);
    return ok;
}

static void drop_client(client *c) {
    close(c->fd);
    if (c->cwd >= 0)
        close(c->cwd);
    if (c->pixels)
        munmap((void *)c->pixels, c->size);
}

/* A client waiting on the listener, if any: 1 when one was taken (or refused). */
static int accept_client(int listener, client *clients, int *n) {
    int fd = accept4(listener, NULL, NULL, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0)
        return 0;
    if (*n >= MAX_CLIENTS || !cli_server_peer_ok(fd))
        close(fd);
    else
        clients[(*n)++] = (client){.fd = fd, .cwd = -1};
    return 1;
}

/* Loads the library, then serves until it has had no client for `idle` seconds (with no listener: until its
 * clients are gone). */
static void serve(int listener, client *clients, int n, int idle) {
    image_library lib = {0};
    iacsg_error ignored = {0};
    writer_library_load(&lib, &ignored); /* a failure is retried, and reported, by each request */
    static char msg[WRITER_MESSAGE_MAX];
    struct pollfd p[MAX_CLIENTS + 1];
    while (n > 0 || listener >= 0) {
        int np = 0;
        for (int k = 0; k < n; k++)
            p[np++] = (struct pollfd){clients[k].fd, POLLIN, 0};
        if (listener >= 0)
            p[np++] = (struct pollfd){listener, POLLIN, 0};
        int r = poll(p, (nfds_t)np, n > 0 ? -1 : idle * 1000);
        if (r < 0 && errno != EINTR)
            break;
        if (r == 0 && !accept_client(listener, clients, &n)) /* idle: a command that connected just now? */
            break;
        for (int k = n - 1; k >= 0; k--) /* backwards: a dropped client's place takes the last, already served */
            if (r > 0 && p[k].revents && !serve_client(&lib, &clients[k], msg)) {
                drop_client(&clients[k]);
                clients[k] = clients[--n];
            }
        if (r > 0 && listener >= 0 && (p[np - 1].revents & POLLIN))
            accept_client(listener, clients, &n);
    }
}

_Noreturn void cli_writer_serve_child(int sock, const void *shared, size_t size) {
    /* mpirun sends SIGTERM to a rank's whole process group when it stops a job: a write under way still ends in
     * its rename, never as a partial file, and the child ends when the command's end is closed. */
    signal(SIGTERM, SIG_IGN);
    static client one;
    one = (client){.fd = sock, .cwd = -1, .pixels = shared, .size = size, .greeted = 1};
    serve(-1, &one, 1, 0);
    _exit(0); /* no atexit handlers, no flush of the command's stdio buffers */
}

/* The started server (detach_process: its own session, stdio on /dev/null, no descriptor but the listener). */
static _Noreturn void server_main(int listener, int idle) {
    if (chdir("/") != 0)
        _exit(1);
    prctl(PR_SET_NAME, "iacsg-writer"); /* in ps and top, where it shows the first command's arguments */
    fcntl(listener, F_SETFL, O_NONBLOCK);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
    signal(SIGPIPE, SIG_IGN);
    signal(SIGCHLD, SIG_DFL);
    static client clients[MAX_CLIENTS];
    serve(listener, clients, 0, idle);
    _exit(0);
}

static int send_hello(int sock, int memfd) {
    int cwd = open(".", O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (cwd < 0)
        return -1;
    mode_t mask = umask(0);
    umask(mask);
    writer_hello h = {WRITER_PROTOCOL, (unsigned)mask};
    int fds[2] = {memfd, cwd};
    int sent = cli_server_send_fds(sock, &h, sizeof h, fds, 2);
    close(cwd);
    return sent;
}

int cli_writer_server_connect(int memfd, int idle, int *started) {
    const cli_server s = {"writer", WRITER_PROTOCOL, idle, "libiacsg_image.so", NULL, server_main};
    int sock = cli_server_connect(&s, started);
    if (sock >= 0 && send_hello(sock, memfd) != 0) {
        close(sock);
        return -1;
    }
    return sock;
}
