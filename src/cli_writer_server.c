/* src/cli_writer_server.c -- see cli_writer_server.h.
 *
 * Stages: the server's name (a hash of what must match between a command and its server), the connection (to a
 * running server, else one started: the command binds the name and listens, then forks the server, which
 * inherits the listening socket, so that commands starting at once agree on one server and none waits for it to
 * come up), the server's start (its own session, stdio on /dev/null and every other inherited descriptor closed,
 * so that it never holds a caller's pipe open), and its loop (poll over the listener and its clients).
 *
 * The name is an abstract unix socket, "iacsg-writer-UID-HASH": HASH covers the protocol's version, the binary
 * and the image library (device, inode, size, times), the user's ids and groups, the mount namespace, the dynamic
 * loader's variables and the idle time, so that another build (a sanitizer build, an installed copy) or another
 * setting never talks to this one's server. Anyone may connect to an abstract socket: both ends check that the
 * other runs as the same user (SO_PEERCRED), and a name taken by another user only makes the command write
 * another way.
 *
 * Protocol (SOCK_SEQPACKET, so a message arrives whole): the command's hello, a writer_hello with the pixels'
 * memfd and a descriptor of its working directory (SCM_RIGHTS); then cli_writer_lib.h's requests, each answered
 * in order. The server serves one request at a time, in the command's directory (fchdir) with its umask, so that
 * files land where and as they would from the command itself, and error messages name the same paths. */
#define _GNU_SOURCE /* memfd, accept4, SO_PEERCRED, MSG_CMSG_CLOEXEC */
#include "cli_writer_server.h"
#include "cli_library.h"
#include "cli_writer_lib.h"
#include "detach.h"
#include "digest.h"
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#define WRITER_PROTOCOL 1u
enum { MAX_CLIENTS = 256, DEFAULT_IDLE = 30 };

typedef struct {
    unsigned version; /* WRITER_PROTOCOL */
    unsigned umask;
} writer_hello;

int cli_writer_server_idle(void) {
    const char *s = getenv("IACSG_WRITER_IDLE");
    if (!s || !*s)
        return DEFAULT_IDLE;
    char *end;
    long v = strtol(s, &end, 10);
    return *end || v <= 0 ? 0 : v > 86400 ? 86400 : (int)v;
}

/* ---- the name ---- */

static void hash_file(digest_ctx *c, const char *path) {
    struct stat st;
    long long v[7] = {0};
    if (stat(path, &st) == 0) {
        long long f[7] = {(long long)st.st_dev, (long long)st.st_ino, (long long)st.st_size, st.st_mtim.tv_sec,
                          st.st_mtim.tv_nsec, st.st_ctim.tv_sec, st.st_ctim.tv_nsec};
        memcpy(v, f, sizeof v);
    }
    digest_update(c, v, sizeof v);
}

static void hash_string(digest_ctx *c, const char *s) { digest_update(c, s ? s : "", s ? strlen(s) + 1 : 1); }

static socklen_t server_address(int idle, struct sockaddr_un *a) {
    digest_ctx c;
    digest_init(&c);
    unsigned version = WRITER_PROTOCOL;
    digest_update(&c, &version, sizeof version);
    hash_file(&c, "/proc/self/exe");
    char path[4096];
    if (cli_library_path("libiacsg_image.so", path) == 0)
        hash_file(&c, path);
    uid_t uid = geteuid();
    gid_t gid = getegid(), groups[256];
    int ngroups = getgroups(256, groups);
    digest_update(&c, &uid, sizeof uid);
    digest_update(&c, &gid, sizeof gid);
    if (ngroups > 0)
        digest_update(&c, groups, (size_t)ngroups * sizeof *groups);
    ssize_t n = readlink("/proc/self/ns/mnt", path, sizeof path - 1);
    path[n > 0 ? n : 0] = '\0';
    hash_string(&c, path);
    hash_string(&c, getenv("LD_LIBRARY_PATH"));
    hash_string(&c, getenv("LD_PRELOAD"));
    digest_update(&c, &idle, sizeof idle);
    char hex[65];
    digest_hex(&c, hex);
    memset(a, 0, sizeof *a);
    a->sun_family = AF_UNIX; /* sun_path[0] == 0: the abstract namespace */
    int len = snprintf(a->sun_path + 1, sizeof a->sun_path - 1, "iacsg-writer-%u-%.32s", (unsigned)uid, hex);
    return (socklen_t)(offsetof(struct sockaddr_un, sun_path) + 1 + (size_t)len);
}

static int peer_is_this_user(int fd) {
    struct ucred cred;
    socklen_t len = sizeof cred;
    return getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0 && cred.uid == geteuid();
}

/* ---- the server ---- */

typedef struct {
    int fd;
    int cwd;            /* the command's working directory (O_PATH); -1: this process's (the child writer) */
    unsigned umask;
    const void *pixels; /* the shared memory, mapped */
    size_t size;
    int greeted;
} client;

/* The descriptors a message carried, into fds[0..1] (others closed); -1 where none. */
static void take_fds(struct msghdr *m, int fds[2]) {
    int n = 0;
    fds[0] = fds[1] = -1;
    for (struct cmsghdr *h = CMSG_FIRSTHDR(m); h; h = CMSG_NXTHDR(m, h)) {
        if (h->cmsg_level != SOL_SOCKET || h->cmsg_type != SCM_RIGHTS)
            continue;
        size_t count = (h->cmsg_len - CMSG_LEN(0)) / sizeof(int);
        for (size_t k = 0; k < count; k++) {
            int fd;
            memcpy(&fd, CMSG_DATA(h) + k * sizeof(int), sizeof fd);
            if (n < 2)
                fds[n++] = fd;
            else
                close(fd);
        }
    }
}

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
    union {
        struct cmsghdr h;
        char buf[CMSG_SPACE(2 * sizeof(int))];
    } ctl;
    struct iovec iov = {msg, WRITER_MESSAGE_MAX};
    struct msghdr m = {.msg_iov = &iov, .msg_iovlen = 1, .msg_control = ctl.buf, .msg_controllen = sizeof ctl.buf};
    ssize_t got = recvmsg(c->fd, &m, MSG_DONTWAIT | MSG_CMSG_CLOEXEC);
    if (got < 0)
        return errno == EAGAIN || errno == EINTR;
    int fds[2];
    take_fds(&m, fds);
    int ok = got > 0 && !(m.msg_flags & (MSG_TRUNC | MSG_CTRUNC));
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
    if (*n >= MAX_CLIENTS || !peer_is_this_user(fd))
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

/* Binds the name and starts the server on it: 1 started, 0 another command holds the name, -1 failed. */
static int start_server(const struct sockaddr_un *a, socklen_t len, int idle) {
    int listener = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
    if (listener < 0)
        return -1;
    if (bind(listener, (const struct sockaddr *)a, len) != 0 || listen(listener, SOMAXCONN) != 0) {
        int taken = errno == EADDRINUSE;
        close(listener);
        return taken ? 0 : -1;
    }
    int started = detach_process(&listener);
    if (started == 1)
        server_main(listener, idle);
    close(listener);
    return started == 0 ? 1 : -1;
}

static int send_hello(int sock, int memfd) {
    int cwd = open(".", O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (cwd < 0)
        return -1;
    mode_t mask = umask(0);
    umask(mask);
    writer_hello h = {WRITER_PROTOCOL, (unsigned)mask};
    int fds[2] = {memfd, cwd};
    union {
        struct cmsghdr h;
        char buf[CMSG_SPACE(sizeof fds)];
    } ctl;
    memset(&ctl, 0, sizeof ctl);
    struct iovec iov = {&h, sizeof h};
    struct msghdr m = {.msg_iov = &iov, .msg_iovlen = 1, .msg_control = ctl.buf, .msg_controllen = sizeof ctl.buf};
    struct cmsghdr *c = CMSG_FIRSTHDR(&m);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SCM_RIGHTS;
    c->cmsg_len = CMSG_LEN(sizeof fds);
    memcpy(CMSG_DATA(c), fds, sizeof fds);
    ssize_t sent = sendmsg(sock, &m, MSG_NOSIGNAL);
    close(cwd);
    return sent == (ssize_t)sizeof h ? 0 : -1;
}

int cli_writer_server_connect(int memfd, int idle, int *started) {
    struct sockaddr_un a;
    socklen_t len = server_address(idle, &a);
    *started = 0;
    for (int tries = 0; tries < 100; tries++) { /* another command may have bound the name and not yet listen */
        int sock = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
        if (sock < 0)
            return -1;
        if (connect(sock, (const struct sockaddr *)&a, len) == 0) {
            if (peer_is_this_user(sock) && send_hello(sock, memfd) == 0)
                return sock;
            close(sock);
            return -1;
        }
        int refused = errno == ECONNREFUSED;
        close(sock);
        if (!refused)
            return -1;
        if (!*started) {
            int r = start_server(&a, len, idle);
            if (r < 0)
                return -1;
            *started = r;
            if (r)
                continue;
        }
        nanosleep(&(struct timespec){0, 1000000}, NULL);
    }
    return -1;
}
