/* src/cli_launch_run.h -- the process that runs a command for the launcher (src/cli_launch_server.c forks it). */
#ifndef IACSG_CLI_LAUNCH_RUN_H
#define IACSG_CLI_LAUNCH_RUN_H
#include "cli_launch_server.h"
#include <stddef.h>
#include <sys/resource.h>

/* The memory of argv (main's, argc of them), which ps and /proc/PID/cmdline show for the launcher and each process
 * it forks; launch_title writes `words` there (cut to fit). */
void launch_title_area(int argc, char **argv);
void launch_title(char *const *words);

/* Reads a request of `size` bytes at buf (the strings stay there): *q, and argv and envp (NULL-terminated, one
 * allocation at *argv to free). 0 when well formed. */
int launch_parse(char *buf, size_t size, launch_request *q, char ***argv, char ***envp);

/* A process's user and system CPU time in microseconds. */
long long launch_cpu_us(const struct rusage *r);

/* Runs the command in this forked process with fds (stdin, stdout, stderr, working directory, and the command's
 * socket, on which it reports its end; every other descriptor is closed): never returns. */
_Noreturn void launch_run(const launch_request *q, char **argv, char **envp, const int fds[5]);

#endif
