/* src/cli_launch_run.c -- see cli_launch_run.h.
 *
 * Stages: the title (what ps shows), the request's strings, the command's run (its signal dispositions and mask,
 * directory, umask, streams and environment, as an exec would have carried them, then main's dispatch). */
#define _GNU_SOURCE /* close_range */
#include "cli_launch_run.h"
#include "cli.h"
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- the title ---- */

/* The memory of the first command's arguments: rewritten with the server's name, then each process's own
 * arguments. */
static char *title;
static size_t title_size;

void launch_title_area(int argc, char **argv) {
    if (argc > 0) { /* the arguments lie end to end in one block, each after the last one's NUL */
        title = argv[0];
        title_size = (size_t)(argv[argc - 1] + strlen(argv[argc - 1]) - argv[0]);
    }
}

void launch_title(char *const *argv) {
    if (!title)
        return;
    size_t at = 0;
    for (int k = 0; argv[k] && at < title_size; k++) {
        size_t len = strlen(argv[k]);
        if (len > title_size - at)
            len = title_size - at;
        memcpy(title + at, argv[k], len);
        at += len;
        if (at < title_size)
            title[at++] = argv[k + 1] ? ' ' : '\0';
    }
    memset(title + at, 0, title_size - at);
}

/* ---- the request ---- */

/* Splits the request's strings into argv and envp (NULL-terminated). 0 when they fill the payload exactly. */
static int split_strings(char *p, size_t size, unsigned argc, unsigned envc, char ***argv, char ***envp) {
    char **v = malloc(((size_t)argc + envc + 2) * sizeof *v);
    if (!v)
        return -1;
    size_t at = 0;
    unsigned k = 0;
    for (; k < argc + envc && at < size; k++) {
        char *end = memchr(p + at, '\0', size - at);
        if (!end)
            break;
        v[k + (k >= argc)] = p + at;
        at = (size_t)(end - p) + 1;
    }
    if (k != argc + envc || at != size || argc == 0) {
        free(v);
        return -1;
    }
    v[argc] = NULL;
    v[argc + envc + 1] = NULL;
    *argv = v;
    *envp = v + argc + 1;
    return 0;
}

int launch_parse(char *buf, size_t size, launch_request *q, char ***argv, char ***envp) {
    if (size < sizeof *q)
        return -1;
    memcpy(q, buf, sizeof *q);
    if (q->version != LAUNCH_PROTOCOL)
        return -1;
    return split_strings(buf + sizeof *q, size - sizeof *q, q->argc, q->envc, argv, envp);
}

/* ---- the run ---- */

long long launch_cpu_us(const struct rusage *r) {
    return (r->ru_utime.tv_sec + r->ru_stime.tv_sec) * 1000000LL + r->ru_utime.tv_usec + r->ru_stime.tv_usec;
}

/* The command's end, told to it at once: its output flushed and its standard streams closed (a `$(...)` reading
 * them sees their end), its status and CPU time sent on `reply`; this process's exit (PoCL's threads and
 * destructors, ~4 ms) and the launcher's reap (~2.5 ms) are then not waited for. */
static void report_end(int reply, int status) {
    fflush(NULL);
    int null = open("/dev/null", O_RDWR | O_CLOEXEC);
    for (int fd = 0; fd < 3; fd++)
        if (null < 0 || dup2(null, fd) < 0)
            close(fd);
    if (null >= 0)
        close(null);
    struct rusage self, children;
    getrusage(RUSAGE_SELF, &self);
    getrusage(RUSAGE_CHILDREN, &children);
    long long us = launch_cpu_us(&self) + launch_cpu_us(&children);
    launch_answer a = {LAUNCH_ENDED, (status & 0xff) << 8, us}; /* a wait status: exited with `status` */
    send(reply, &a, sizeof a, MSG_NOSIGNAL | MSG_DONTWAIT);
    close(reply);
}

_Noreturn void launch_run(const launch_request *q, char **argv, char **envp, const int fds[5]) {
    sigset_t blocked; /* the command's dispositions and mask, as an exec would have carried them */
    sigemptyset(&blocked);
    for (int sig = 1; sig <= 64; sig++) {
        if (sig != SIGKILL && sig != SIGSTOP)
            signal(sig, q->ignored >> (sig - 1) & 1 ? SIG_IGN : SIG_DFL);
        if (q->blocked >> (sig - 1) & 1)
            sigaddset(&blocked, sig);
    }
    sigprocmask(SIG_SETMASK, &blocked, NULL);
    int entered = fchdir(fds[3]) == 0;
    umask((mode_t)(q->umask & 0777));
    for (int k = 0; k < 3; k++)
        if (dup2(fds[k], k) < 0)
            _exit(125);
    const int reply = 3; /* the command's socket; the launcher's other descriptors (the listener, the other
                          * commands' sockets) are closed */
    if ((fds[4] != reply && dup3(fds[4], reply, O_CLOEXEC) < 0) || close_range(reply + 1, ~0u, 0) != 0)
        _exit(125);
    prctl(PR_SET_NAME, "iacsg");
    launch_title(argv);
    if (!entered) {
        fputs("iacsg: the launcher cannot enter the command's working directory\n", stderr);
        exit(1);
    }
    extern char **environ;
    environ = envp;
    int argc = 0;
    while (argv[argc])
        argc++;
    int status = cli_dispatch(argc, argv);
    report_end(reply, status);
    exit(status); /* exit, not _exit: atexit handlers run as they would (the streams are /dev/null by now) */
}
