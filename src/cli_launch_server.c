/* src/cli_launch_server.c -- see cli_launch_server.h.
 *
 * Stages: the name (beyond src/cli_server.c's: whatever a forked process inherits from the server rather than
 * from the command, so that a command only reaches a server that would run it as it would run itself: resource
 * limits, CPU affinity, nice value, cgroup, pid namespace, and the ICD loader's variables, which choose the
 * libraries loaded), the preload (each OpenCL driver the ICD loader would open, opened now: nothing of OpenCL is
 * called, so the server starts no thread and may fork), the loop (poll over the listener, the commands'
 * sockets and SIGCHLD), and the forked process (the command's streams, directory, umask and environment, then
 * main's dispatch).
 *
 * A command's socket closing while its process runs means the command is gone (killed by SIGKILL, say): its
 * process gets SIGTERM, as it would have from a shell that killed the command. */
#define _GNU_SOURCE /* accept4, signalfd, close_range, sched_getaffinity */
#include "cli_launch_server.h"
#include "cli.h"
#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/signalfd.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

enum { MAX_COMMANDS = 256 };

/* ---- the name ---- */

static void hash_file_text(digest_ctx *c, const char *path) {
    char text[4096];
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(text, 1, sizeof text, f) : 0;
    if (f)
        fclose(f);
    digest_update(c, text, n);
    digest_update(c, &n, sizeof n);
}

static void hash_inherited(digest_ctx *c) {
    for (int r = 0; r < RLIM_NLIMITS; r++) {
        struct rlimit l = {0, 0};
        getrlimit((__rlimit_resource_t)r, &l);
        digest_update(c, &l, sizeof l);
    }
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    sched_getaffinity(0, sizeof cpus, &cpus);
    digest_update(c, &cpus, sizeof cpus);
    errno = 0;
    int nice = getpriority(PRIO_PROCESS, 0);
    digest_update(c, &nice, sizeof nice);
    hash_file_text(c, "/proc/self/cgroup");
    char ns[256];
    ssize_t n = readlink("/proc/self/ns/pid", ns, sizeof ns - 1);
    ns[n > 0 ? n : 0] = '\0';
    cli_server_hash_string(c, ns);
    cli_server_hash_string(c, getenv("OCL_ICD_VENDORS"));
    cli_server_hash_string(c, getenv("OCL_ICD_FILENAMES"));
    cli_server_hash_string(c, getenv("OPENCL_VENDOR_PATH"));
}

/* ---- the title ---- */

/* The memory of the first command's arguments, which ps and /proc/PID/cmdline show for the server and its forked
 * processes: rewritten with the server's name, then each process's own arguments (cut to fit). */
static char *title;
static size_t title_size;

static void set_title(char *const *argv) {
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

/* ---- the preload ---- */

/* Opens the library an .icd file names (its first line). */
static void open_icd(const char *path) {
    char name[4096];
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    if (fgets(name, sizeof name, f)) {
        name[strcspn(name, "\r\n")] = '\0';
        if (*name)
            dlopen(name, RTLD_NOW | RTLD_LOCAL); /* kept open: the forked processes find it loaded */
    }
    fclose(f);
}

/* What ocl-icd opens: OCL_ICD_FILENAMES's libraries, else the .icd files of OCL_ICD_VENDORS (a directory or one
 * file), else those of /etc/OpenCL/vendors. */
static void preload_opencl(void) {
    const char *names = getenv("OCL_ICD_FILENAMES");
    if (names && *names) {
        char list[4096];
        snprintf(list, sizeof list, "%s", names);
        for (char *save = NULL, *lib = strtok_r(list, ":", &save); lib; lib = strtok_r(NULL, ":", &save))
            dlopen(lib, RTLD_NOW | RTLD_LOCAL);
        return;
    }
    const char *vendors = getenv("OCL_ICD_VENDORS");
    struct stat st;
    if (vendors && *vendors && stat(vendors, &st) == 0 && S_ISREG(st.st_mode)) {
        open_icd(vendors);
        return;
    }
    const char *dir_path = vendors && *vendors ? vendors : "/etc/OpenCL/vendors";
    DIR *dir = opendir(dir_path);
    for (struct dirent *e = dir ? readdir(dir) : NULL; e; e = readdir(dir)) {
        size_t len = strlen(e->d_name);
        char path[4096];
        if (len > 4 && strcmp(e->d_name + len - 4, ".icd") == 0 &&
            snprintf(path, sizeof path, "%s/%s", dir_path, e->d_name) < (int)sizeof path)
            open_icd(path);
    }
    if (dir)
        closedir(dir);
}

/* ---- the forked process ---- */

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

/* Runs the command in this (forked) process: never returns. */
static _Noreturn void run_command(const launch_request *q, char **argv, char **envp, const int fds[4]) {
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
    close_range(3, ~0u, 0); /* the listener, the other commands' sockets, this one's: none is the command's */
    prctl(PR_SET_NAME, "iacsg");
    set_title(argv);
    if (!entered) {
        fputs("iacsg: the launcher cannot enter the command's working directory\n", stderr);
        exit(1);
    }
    extern char **environ;
    environ = envp;
    int argc = 0;
    while (argv[argc])
        argc++;
    exit(cli_dispatch(argc, argv)); /* exit, not _exit: the command's stdio is flushed as it would be */
}

/* ---- the loop ---- */

typedef struct {
    int fd; /* the command's socket; -1 once it is gone */
    pid_t pid;
} command;

static int send_answer(int fd, int kind, int value, long long cpu_us) {
    launch_answer a = {kind, value, cpu_us};
    return send(fd, &a, sizeof a, MSG_NOSIGNAL | MSG_DONTWAIT) == (ssize_t)sizeof a ? 0 : -1;
}

/* Takes a command waiting on the listener and forks its process: 1 when one was taken (or refused). */
static int start_command(int listener, command *cmds, int *n) {
    static char buf[LAUNCH_REQUEST_MAX];
    int fd = accept4(listener, NULL, NULL, SOCK_CLOEXEC);
    if (fd < 0)
        return 0;
    struct timeval limit = {2, 0}; /* a command sends its request with its connect */
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
    int fds[4] = {-1, -1, -1, -1};
    ssize_t got = -1;
    if (*n < MAX_COMMANDS && cli_server_peer_ok(fd))
        got = cli_server_recv_fds(fd, buf, sizeof buf, fds, 4, 0);
    launch_request q;
    char **argv = NULL, **envp = NULL;
    int ok = got >= (ssize_t)sizeof q && fds[3] >= 0;
    if (ok) {
        memcpy(&q, buf, sizeof q);
        ok = q.version == LAUNCH_PROTOCOL &&
             split_strings(buf + sizeof q, (size_t)got - sizeof q, q.argc, q.envc, &argv, &envp) == 0;
    }
    pid_t pid = ok ? fork() : -1;
    if (pid == 0)
        run_command(&q, argv, envp, fds);
    free(argv);
    for (int k = 0; k < 4; k++)
        if (fds[k] >= 0)
            close(fds[k]);
    if (pid > 0 && send_answer(fd, LAUNCH_STARTED, (int)pid, 0) == 0) {
        fcntl(fd, F_SETFL, O_NONBLOCK);
        cmds[(*n)++] = (command){fd, pid};
    } else {
        if (pid > 0)
            kill(pid, SIGTERM); /* its command is gone already; reaped with the others */
        close(fd);
    }
    return 1;
}

/* Reaps the ended processes and tells their commands. */
static void reap(command *cmds, int *n) {
    int status;
    pid_t pid;
    struct rusage ru;
    while ((pid = wait4(-1, &status, WNOHANG, &ru)) > 0)
        for (int k = 0; k < *n; k++)
            if (cmds[k].pid == pid) {
                if (cmds[k].fd >= 0) {
                    long long cpu_us = (ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1000000LL + ru.ru_utime.tv_usec +
                                       ru.ru_stime.tv_usec;
                    send_answer(cmds[k].fd, LAUNCH_ENDED, status, cpu_us);
                    close(cmds[k].fd);
                }
                cmds[k] = cmds[--*n];
                break;
            }
}

/* The started server (detach_process: its own session, stdio on /dev/null, no descriptor but the listener). */
static _Noreturn void serve(int listener, int idle) {
    if (chdir("/") != 0)
        _exit(1);
    prctl(PR_SET_NAME, "iacsg-launch"); /* in ps and top, where it shows the first command's arguments */
    set_title((char *const[]){"iacsg-launch", NULL});
    fcntl(listener, F_SETFL, O_NONBLOCK);
    signal(SIGPIPE, SIG_IGN);
    sigset_t child;
    sigemptyset(&child);
    sigaddset(&child, SIGCHLD);
    sigprocmask(SIG_SETMASK, &child, NULL);
    int children = signalfd(-1, &child, SFD_CLOEXEC | SFD_NONBLOCK);
    if (children < 0)
        _exit(1);
    preload_opencl();
    static command cmds[MAX_COMMANDS];
    static struct pollfd p[MAX_COMMANDS + 2];
    int n = 0;
    for (;;) {
        int np = 0;
        p[np++] = (struct pollfd){listener, POLLIN, 0};
        p[np++] = (struct pollfd){children, POLLIN, 0};
        for (int k = 0; k < n; k++)
            p[np++] = (struct pollfd){cmds[k].fd, POLLIN, 0}; /* -1: ignored by poll */
        int r = poll(p, (nfds_t)np, n > 0 ? -1 : idle * 1000);
        if (r < 0 && errno != EINTR)
            break;
        if (r == 0 && !start_command(listener, cmds, &n)) /* idle: a command that connected just now? */
            break;
        if (r <= 0)
            continue;
        for (int k = 0; k < n; k++) /* a command's socket readable: it is gone (it sends nothing more) */
            if (cmds[k].fd >= 0 && p[k + 2].revents) {
                kill(cmds[k].pid, SIGTERM);
                close(cmds[k].fd);
                cmds[k].fd = -1;
            }
        if (p[1].revents) {
            struct signalfd_siginfo info;
            while (read(children, &info, sizeof info) == (ssize_t)sizeof info)
                ;
            reap(cmds, &n);
        }
        if (p[0].revents & POLLIN)
            start_command(listener, cmds, &n);
    }
    _exit(0);
}

cli_server cli_launch_server(int idle, int argc, char **argv) {
    if (argc > 0) { /* the arguments lie end to end in one block, each after the last one's NUL */
        title = argv[0];
        title_size = (size_t)(argv[argc - 1] + strlen(argv[argc - 1]) - argv[0]);
    }
    return (cli_server){"launch", LAUNCH_PROTOCOL, idle, NULL, hash_inherited, serve};
}
