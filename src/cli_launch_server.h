/* src/cli_launch_server.h -- the launcher: a process per user and build that has loaded the OpenCL driver's
 * libraries (PoCL's LLVM and Clang: 75-90 ms of dynamic linking on a paravirtualised AMD EPYC, 15-30 ms on an
 * Intel Xeon) and runs, for each command that asks, a process forked for it (src/cli_launch_run.h) with the
 * command's arguments, environment, working directory, umask and standard streams.
 * The first command starts it; it ends after IACSG_LAUNCH_IDLE seconds (default 30) without a command. The
 * command's side is src/cli_launch.c. */
#ifndef IACSG_CLI_LAUNCH_SERVER_H
#define IACSG_CLI_LAUNCH_SERVER_H
#include "cli_server.h"

#define LAUNCH_PROTOCOL 1u
enum { LAUNCH_REQUEST_MAX = 131072, LAUNCH_DEFAULT_IDLE = 30 };

/* The request: this header, then argc arguments and envc environment strings, each NUL-terminated, with the
 * command's stdin, stdout, stderr and working directory (O_PATH) as SCM_RIGHTS. */
typedef struct {
    unsigned version; /* LAUNCH_PROTOCOL */
    unsigned umask;
    unsigned argc, envc;
    unsigned long long ignored, blocked; /* the command's ignored and blocked signals: bit s-1 for signal s */
} launch_request;

/* The answers: LAUNCH_STARTED with the process's pid, then LAUNCH_ENDED with its wait status (`more`: the CPU
 * time in microseconds, user and system, of its threads and reaped children). The process itself sends
 * LAUNCH_ENDED when its command returns, before it exits; the launcher sends it too when it reaps the process (the
 * command sees only the first: a process ended by a signal reports nothing itself). */
typedef enum { LAUNCH_STARTED = 1, LAUNCH_ENDED = 2 } launch_answer_kind;
typedef struct {
    int kind;
    int value;
    long long more;
} launch_answer;

/* The launcher's identity for cli_server_connect, with `idle` seconds; the server it starts shows its name, and
 * each forked process its command's arguments, in the memory of argv (this command's arguments, as main got
 * them). */
cli_server cli_launch_server(int idle, int argc, char **argv);

#endif
