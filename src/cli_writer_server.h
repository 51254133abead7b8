/* src/cli_writer_server.h -- the image writer that outlives the command: a process per user and build that has
 * loaded the image library (libiacsg_image.so, ~120 ms of CPU for OpenImageIO's ~260 libraries) and serves the
 * commands that follow, so that they no longer wait for that load. The first command starts it; it ends after
 * IACSG_WRITER_IDLE seconds (default 30) without a client. Also the loop of the command's own child writer, which
 * is that server with one client and no listener. */
#ifndef IACSG_CLI_WRITER_SERVER_H
#define IACSG_CLI_WRITER_SERVER_H
#include <stddef.h>

/* IACSG_WRITER_IDLE in seconds (a whole number; default 30); 0 (or a value that is not a number) means no
 * server: each command forks its own writer. */
int cli_writer_server_idle(void);

/* Connects to this build's server for this user, starting it when none answers, and greets it: the shared memory
 * `memfd` of the images' pixels, this process's working directory (relative paths are resolved in it) and umask.
 * Returns the connected socket, or -1 when no server can be had (the caller writes another way). *started: this
 * call started the server. Call it before any thread starts (it forks). */
int cli_writer_server_connect(int memfd, int idle, int *started);

/* The command's own child writer: serves requests on `sock` with the pixels at `shared` until the command closes
 * its end, then exits. Never returns. */
_Noreturn void cli_writer_serve_child(int sock, const void *shared, size_t size);

#endif
