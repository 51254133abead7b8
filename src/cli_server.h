/* src/cli_server.h -- what the command's two servers share: the image writer (src/cli_writer_server.c) and the
 * launcher (src/cli_launch_server.c) are each a process per user and build, on an abstract unix socket named by a
 * hash of what must match between a command and its server, started by the first command that finds none and
 * ended after some idle seconds. */
#ifndef IACSG_CLI_SERVER_H
#define IACSG_CLI_SERVER_H
#include "digest.h"
#include <sys/socket.h>
#include <sys/un.h>

typedef struct {
    const char *kind;                  /* in the name: "writer", "launch" */
    unsigned protocol;                 /* the protocol's version */
    int idle;                          /* seconds without a client before the server ends */
    const char *library;               /* a library beside the binary whose identity is part of the name, or NULL */
    void (*more)(digest_ctx *c);       /* hashes what else must match, or NULL */
    void (*serve)(int listener, int idle); /* the server's loop, in the started process: never returns */
} cli_server;

/* The idle time the variable `var` asks for, in seconds (a whole number; unset or empty: default); 0 (or a
 * value that is not a number) means no server. */
int cli_server_idle(const char *var, int fallback);

/* Connects to the server `s` names for this user, starting it when none answers. Returns the connected socket
 * (SOCK_SEQPACKET, close-on-exec), or -1 when no server can be had. *started: this call started it. Call it
 * before any thread starts (it forks). */
int cli_server_connect(const cli_server *s, int *started);

/* 1 when the process at the other end of the unix socket `fd` runs as this user. */
int cli_server_peer_ok(int fd);

/* Sends `size` bytes with the descriptors fds[0..n-1] (SCM_RIGHTS). 0 when sent whole, -1 otherwise. */
int cli_server_send_fds(int sock, const void *data, size_t size, const int *fds, int n);

/* Receives a message of at most `size` bytes into `data` and at most `max` descriptors into fds (the rest, -1;
 * those beyond `max` closed). Returns the message's size, 0 at the end, -1 on an error or a truncated message. */
ssize_t cli_server_recv_fds(int sock, void *data, size_t size, int *fds, int max, int flags);

/* Hashes a file's identity (device, inode, size, times) into c; a file that is not there hashes as zeros. */
void cli_server_hash_file(digest_ctx *c, const char *path);

/* Hashes a string (NULL as the empty string). */
void cli_server_hash_string(digest_ctx *c, const char *s);

#endif
