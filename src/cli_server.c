/* src/cli_server.c -- see cli_server.h.
 *
 * Stages: the name, the connection (to a running server, else one started: the command binds the name and
 * listens, then forks the server, which inherits the listening socket, so that commands starting at once agree on
 * one server and none waits for it to come up), and the messages with descriptors both servers exchange.
 *
 * The name is an abstract unix socket, "iacsg-KIND-UID-HASH": HASH covers the kind and its protocol's version,
 * the binary and the given library (device, inode, size, times), the user's ids and groups, the mount
 * namespace, the dynamic loader's variables, the idle time and what the kind adds, so that another build (a
 * sanitizer build, an installed copy) or another setting never talks to this one's server. Anyone may connect to
 * an abstract socket: both ends check that the other runs as the same user (SO_PEERCRED), and a name taken by
 * another user only makes the command do without the server. */
#define _GNU_SOURCE /* SO_PEERCRED, MSG_CMSG_CLOEXEC */
#include "cli_server.h"
#include "cli_library.h"
#include "detach.h"
#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

enum { MAX_IDLE = 86400, MAX_FDS = 8 };

int cli_server_idle(const char *var, int fallback) {
    const char *s = getenv(var);
    if (!s || !*s)
        return fallback;
    char *end;
    long v = strtol(s, &end, 10);
    return *end || v <= 0 ? 0 : v > MAX_IDLE ? MAX_IDLE : (int)v;
}

/* ---- the name ---- */

void cli_server_hash_file(digest_ctx *c, const char *path) {
    struct stat st;
    long long v[7] = {0};
    if (stat(path, &st) == 0) {
        long long f[7] = {(long long)st.st_dev, (long long)st.st_ino, (long long)st.st_size, st.st_mtim.tv_sec,
                          st.st_mtim.tv_nsec, st.st_ctim.tv_sec, st.st_ctim.tv_nsec};
        memcpy(v, f, sizeof v);
    }
    digest_update(c, v, sizeof v);
}

void cli_server_hash_string(digest_ctx *c, const char *s) { digest_update(c, s ? s : "", s ? strlen(s) + 1 : 1); }

static socklen_t server_address(const cli_server *s, struct sockaddr_un *a) {
    digest_ctx c;
    digest_init(&c);
    cli_server_hash_string(&c, s->kind);
    digest_update(&c, &s->protocol, sizeof s->protocol);
    cli_server_hash_file(&c, "/proc/self/exe");
    char path[4096];
    if (s->library && cli_library_path(s->library, path) == 0)
        cli_server_hash_file(&c, path);
    uid_t uid = geteuid();
    gid_t gid = getegid(), groups[256];
    int ngroups = getgroups(256, groups);
    digest_update(&c, &uid, sizeof uid);
    digest_update(&c, &gid, sizeof gid);
    if (ngroups > 0)
        digest_update(&c, groups, (size_t)ngroups * sizeof *groups);
    ssize_t n = readlink("/proc/self/ns/mnt", path, sizeof path - 1);
    path[n > 0 ? n : 0] = '\0';
    cli_server_hash_string(&c, path);
    cli_server_hash_string(&c, getenv("LD_LIBRARY_PATH"));
    cli_server_hash_string(&c, getenv("LD_PRELOAD"));
    digest_update(&c, &s->idle, sizeof s->idle);
    if (s->more)
        s->more(&c);
    char hex[65];
    digest_hex(&c, hex);
    memset(a, 0, sizeof *a);
    a->sun_family = AF_UNIX; /* sun_path[0] == 0: the abstract namespace */
    int len = snprintf(a->sun_path + 1, sizeof a->sun_path - 1, "iacsg-%s-%u-%.32s", s->kind, (unsigned)uid, hex);
    return (socklen_t)(offsetof(struct sockaddr_un, sun_path) + 1 + (size_t)len);
}

int cli_server_peer_ok(int fd) {
    struct ucred cred;
    socklen_t len = sizeof cred;
    return getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0 && cred.uid == geteuid();
}

/* ---- the connection ---- */

/* Binds the name and starts the server on it: 1 started, 0 another command holds the name, -1 failed. */
static int start_server(const cli_server *s, const struct sockaddr_un *a, socklen_t len) {
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
        s->serve(listener, s->idle);
    close(listener);
    return started == 0 ? 1 : -1;
}

int cli_server_connect(const cli_server *s, int *started) {
    struct sockaddr_un a;
    socklen_t len = server_address(s, &a);
    *started = 0;
    for (int tries = 0; tries < 100; tries++) { /* another command may have bound the name and not yet listen */
        int sock = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
        if (sock < 0)
            return -1;
        if (connect(sock, (const struct sockaddr *)&a, len) == 0) {
            if (cli_server_peer_ok(sock))
                return sock;
            close(sock);
            return -1;
        }
        int refused = errno == ECONNREFUSED;
        close(sock);
        if (!refused)
            return -1;
        if (!*started) {
            int r = start_server(s, &a, len);
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

/* ---- messages with descriptors ---- */

int cli_server_send_fds(int sock, const void *data, size_t size, const int *fds, int n) {
    union {
        struct cmsghdr h;
        char buf[CMSG_SPACE(MAX_FDS * sizeof(int))];
    } ctl;
    memset(&ctl, 0, sizeof ctl);
    struct iovec iov = {(void *)data, size};
    struct msghdr m = {.msg_iov = &iov, .msg_iovlen = 1};
    if (n > 0) {
        m.msg_control = ctl.buf;
        m.msg_controllen = CMSG_SPACE((size_t)n * sizeof(int));
        struct cmsghdr *c = CMSG_FIRSTHDR(&m);
        c->cmsg_level = SOL_SOCKET;
        c->cmsg_type = SCM_RIGHTS;
        c->cmsg_len = CMSG_LEN((size_t)n * sizeof(int));
        memcpy(CMSG_DATA(c), fds, (size_t)n * sizeof(int));
    }
    return n <= MAX_FDS && sendmsg(sock, &m, MSG_NOSIGNAL) == (ssize_t)size ? 0 : -1;
}

ssize_t cli_server_recv_fds(int sock, void *data, size_t size, int *fds, int max, int flags) {
    union {
        struct cmsghdr h;
        char buf[CMSG_SPACE(MAX_FDS * sizeof(int))];
    } ctl;
    struct iovec iov = {data, size};
    struct msghdr m = {.msg_iov = &iov, .msg_iovlen = 1, .msg_control = ctl.buf, .msg_controllen = sizeof ctl.buf};
    ssize_t got = recvmsg(sock, &m, flags | MSG_CMSG_CLOEXEC);
    int n = 0;
    for (int k = 0; k < max; k++)
        fds[k] = -1;
    for (struct cmsghdr *h = got >= 0 ? CMSG_FIRSTHDR(&m) : NULL; h; h = CMSG_NXTHDR(&m, h)) {
        if (h->cmsg_level != SOL_SOCKET || h->cmsg_type != SCM_RIGHTS)
            continue;
        size_t count = (h->cmsg_len - CMSG_LEN(0)) / sizeof(int);
        for (size_t k = 0; k < count; k++) {
            int fd;
            memcpy(&fd, CMSG_DATA(h) + k * sizeof(int), sizeof fd);
            if (n < max)
                fds[n++] = fd;
            else
                close(fd);
        }
    }
    if (got > 0 && (m.msg_flags & (MSG_TRUNC | MSG_CTRUNC))) {
        errno = EMSGSIZE;
        return -1;
    }
    return got;
}
