/* src/cli_launch.c -- see cli_launch.h.
 *
 * Stages: whether the command goes to the launcher (refusals), the request (arguments, environment, umask; the
 * standard streams and the working directory as descriptors), and the wait: the launched process's pid, then its
 * wait status (from the process as its command returns, else from the launcher's reap), with the signals a shell
 * or a terminal sends this process relayed to it in between. The launched process is in the launcher's session,
 * not the terminal's foreground group, so Ctrl-C reaches only this process and is relayed; a stop (Ctrl-Z) stops
 * it with SIGSTOP (an orphaned group ignores SIGTSTP) and then this process, and SIGCONT resumes both. */
#define _GNU_SOURCE /* O_PATH */
#include "cli_launch.h"
#include "cli_launch_server.h"
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

static const int relayed[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGWINCH, SIGCONT, SIGTSTP, SIGTTIN,
                              SIGTTOU};

static volatile sig_atomic_t launched_pid;

/* ---- refusals ---- */

static int traced(void) {
    char line[256];
    int tracer = 0;
    FILE *f = fopen("/proc/self/status", "r");
    while (f && fgets(line, sizeof line, f))
        if (strncmp(line, "TracerPid:", 10) == 0)
            tracer = atoi(line + 10) != 0;
    if (f)
        fclose(f);
    return tracer;
}

/* Why this process runs the command itself (NULL: it may go to the launcher); "" for a command that needs no
 * OpenCL (nothing to trace). */
static const char *refusal(int argc, char **argv) {
    static const char *const here[] = {"--help", "-h", "-help", "--version", "eval", "compile", "view", "objects",
                                       "regions"};
    if (argc < 2)
        return "";
    for (size_t k = 0; k < sizeof here / sizeof *here; k++)
        if (strcmp(argv[1], here[k]) == 0)
            return "";
    if (cli_server_idle("IACSG_LAUNCH_IDLE", LAUNCH_DEFAULT_IDLE) == 0)
        return "IACSG_LAUNCH_IDLE=0";
    if (getenv("OMPI_COMM_WORLD_SIZE"))
        return "under mpirun";
    if (getenv("LD_PRELOAD"))
        return "LD_PRELOAD is set";
    for (int fd = 0; fd < 3; fd++) {
        struct termios t;
        if (fcntl(fd, F_GETFD) < 0)
            return "a standard stream is closed";
        if (fd > 0 && isatty(fd) && tcgetattr(fd, &t) == 0 && (t.c_lflag & TOSTOP))
            return "the terminal stops background writes";
    }
    if (traced())
        return "traced";
    return NULL;
}

/* ---- the request ---- */

/* The request's bytes, or NULL when they do not fit a message. */
static char *request(int argc, char **argv, size_t *size) {
    extern char **environ;
    size_t total = sizeof(launch_request);
    unsigned envc = 0;
    for (int k = 0; k < argc; k++)
        total += strlen(argv[k]) + 1;
    for (char **e = environ; e && *e; e++, envc++)
        total += strlen(*e) + 1;
    char *buf = total <= LAUNCH_REQUEST_MAX ? malloc(total) : NULL;
    if (!buf)
        return NULL;
    mode_t mask = umask(0);
    umask(mask);
    launch_request q = {LAUNCH_PROTOCOL, (unsigned)mask, (unsigned)argc, envc, 0, 0};
    sigset_t blocked;
    sigprocmask(SIG_BLOCK, NULL, &blocked);
    for (int sig = 1; sig <= 64; sig++) {
        struct sigaction a;
        if (sigaction(sig, NULL, &a) == 0 && a.sa_handler == SIG_IGN)
            q.ignored |= 1ull << (sig - 1);
        if (sigismember(&blocked, sig) == 1)
            q.blocked |= 1ull << (sig - 1);
    }
    memcpy(buf, &q, sizeof q);
    size_t at = sizeof q;
    for (int k = 0; k < argc; k++)
        at += (size_t)sprintf(buf + at, "%s", argv[k]) + 1;
    for (unsigned k = 0; k < envc; k++)
        at += (size_t)sprintf(buf + at, "%s", environ[k]) + 1;
    *size = total;
    return buf;
}

/* ---- the wait ---- */

static void trace(const char *how) {
    const char *t = getenv("IACSG_LAUNCH_TRACE");
    if (t && *t)
        fprintf(stderr, "iacsg: launcher: %s\n", how);
}

static void relay(int sig) {
    int saved = errno;
    pid_t pid = (pid_t)launched_pid;
    if (sig == SIGTSTP || sig == SIGTTIN || sig == SIGTTOU) {
        kill(pid, SIGSTOP);
        raise(SIGSTOP);
    } else {
        kill(pid, sig);
    }
    errno = saved;
}

static void set_relays(const sigset_t *set) {
    struct sigaction a;
    memset(&a, 0, sizeof a);
    a.sa_handler = relay; /* no SA_RESTART: the wait's recv sees EINTR and waits again */
    sigfillset(&a.sa_mask);
    for (size_t k = 0; k < sizeof relayed / sizeof *relayed; k++) {
        struct sigaction was;
        if (sigaction(relayed[k], NULL, &was) == 0 && was.sa_handler != SIG_IGN) /* ignored: by both, as before */
            sigaction(relayed[k], &a, NULL);
    }
    sigprocmask(SIG_SETMASK, set, NULL);
}

/* Ends as the launched process ended. */
static int end_as(int status) {
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    int sig = WIFSIGNALED(status) ? WTERMSIG(status) : SIGKILL;
    struct rlimit none = {0, 0};
    setrlimit(RLIMIT_CORE, &none); /* its core, if any, is dumped already */
    signal(sig, SIG_DFL);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, sig);
    sigprocmask(SIG_UNBLOCK, &set, NULL);
    raise(sig);
    return 128 + sig;
}

/* Sends the request and waits for the launched process: 1 with *status, 0 when none was started. */
static int run_launched(int sock, const char *req, size_t size, int cwd, int started, int *status) {
    char how[96];
    sigset_t blocked, before;
    sigemptyset(&blocked);
    for (size_t k = 0; k < sizeof relayed / sizeof *relayed; k++)
        sigaddset(&blocked, relayed[k]);
    sigprocmask(SIG_BLOCK, &blocked, &before); /* held until the pid is known, then relayed */
    int fds[4] = {0, 1, 2, cwd};
    launch_answer a;
    if (cli_server_send_fds(sock, req, size, fds, 4) != 0 || recv(sock, &a, sizeof a, 0) != (ssize_t)sizeof a ||
        (a.kind != LAUNCH_STARTED && a.kind != LAUNCH_ENDED)) {
        sigprocmask(SIG_SETMASK, &before, NULL);
        return 0;
    }
    ssize_t got = sizeof a;
    trace(started ? "server (started)" : "server (reused)");
    if (a.kind == LAUNCH_ENDED) { /* the process reported its end before the launcher its start */
        sigprocmask(SIG_SETMASK, &before, NULL);
    } else {
        launched_pid = a.value;
        set_relays(&before);
        while ((got = recv(sock, &a, sizeof a, 0)) < 0 && errno == EINTR)
            ;
    }
    if (got != (ssize_t)sizeof a || a.kind != LAUNCH_ENDED) {
        kill((pid_t)launched_pid, SIGTERM);
        fprintf(stderr, "iacsg: the launcher ended before the command it ran (pid %d); its outcome is unknown\n",
                (int)launched_pid);
        *status = 1;
        return 1;
    }
    snprintf(how, sizeof how, "the launched process ended: %.3f s of CPU", (double)a.more * 1e-6);
    trace(how); /* the bench adds it to the command's own */
    *status = end_as(a.value);
    return 1;
}

int cli_launch(int argc, char **argv, int *status) {
    const char *why = refusal(argc, argv);
    char how[128];
    if (why) {
        snprintf(how, sizeof how, "this process (%s)", why);
        if (*why)
            trace(how);
        return 0;
    }
    size_t size;
    char *req = request(argc, argv, &size);
    int cwd = req ? open(".", O_PATH | O_DIRECTORY | O_CLOEXEC) : -1;
    int started = 0, launched = 0;
    const cli_server server = cli_launch_server(cli_server_idle("IACSG_LAUNCH_IDLE", LAUNCH_DEFAULT_IDLE), argc, argv);
    int sock = cwd >= 0 ? cli_server_connect(&server, &started) : -1;
    if (sock >= 0) {
        launched = run_launched(sock, req, size, cwd, started, status);
        close(sock);
    }
    if (!launched)
        trace(!req ? "this process (the arguments and environment are too large)"
                   : "this process (no launcher could be had)");
    if (cwd >= 0)
        close(cwd);
    free(req);
    return launched;
}
