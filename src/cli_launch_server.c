/* src/cli_launch_server.c -- see cli_launch_server.h.
 *
 * Stages: the name (beyond src/cli_server.c's: whatever a forked process inherits from the server rather than
 * from the command, so that a command only reaches a server that would run it as it would run itself: resource
 * limits, CPU affinity, nice value, cgroup, pid namespace, and the ICD loader's variables, which choose the
 * libraries loaded), the preload (each OpenCL driver the ICD loader would open, opened now: nothing of OpenCL is
 * called, so the server starts no thread and may fork), and the loop (poll over the listener, the commands'
 * sockets and SIGCHLD; each command to a process forked for it: src/cli_launch_run.c).
 *
 * A command's socket closing while its process runs means the command is gone (killed by SIGKILL, say): its
 * process gets SIGTERM, as it would have from a shell that killed the command.
 *
 * Nothing of OpenCL is opened ahead of a command (a process with platforms, devices and a context ready would save
 * it 6-22 ms): PoCL's device start creates its cache directory and a file in it, so done after a command it would
 * write into a directory that the user may be removing then, and a process prepared before the user removed that
 * directory fails its builds. */
#define _GNU_SOURCE /* accept4, signalfd, close_range, sched_getaffinity */
#include "cli_launch_server.h"
#include "cli_launch_run.h"
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

enum { MAX_COMMANDS = 256, FIRST_WAIT_MS = 200 };

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

/* ---- the loop ---- */

typedef struct {
    int fd; /* the command's socket; -1 once it is gone */
    pid_t pid;
} command;

static int send_answer(int fd, int kind, int value, long long more) {
    launch_answer a = {kind, value, more};
    return send(fd, &a, sizeof a, MSG_NOSIGNAL | MSG_DONTWAIT) == (ssize_t)sizeof a ? 0 : -1;
}

/* Takes a command waiting on the listener and starts its process: 1 when one was taken (or refused). */
static int start_command(int listener, command *cmds, int *n) {
    static char buf[LAUNCH_REQUEST_MAX];
    int fd = accept4(listener, NULL, NULL, SOCK_CLOEXEC);
    if (fd < 0)
        return 0;
    struct timeval limit = {2, 0}; /* a command sends its request with its connect */
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
    int fds[5] = {-1, -1, -1, -1, fd}; /* the command's streams, its directory, and its socket */
    ssize_t got = -1;
    if (*n < MAX_COMMANDS && cli_server_peer_ok(fd))
        got = cli_server_recv_fds(fd, buf, sizeof buf, fds, 4, 0);
    launch_request q;
    char **argv = NULL, **envp = NULL;
    pid_t pid = -1;
    if (got > 0 && fds[3] >= 0 && launch_parse(buf, (size_t)got, &q, &argv, &envp) == 0) {
        pid = fork();
        if (pid == 0)
            launch_run(&q, argv, envp, fds);
    }
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
    while ((pid = wait4(-1, &status, WNOHANG, &ru)) > 0) {
        for (int k = 0; k < *n; k++)
            if (cmds[k].pid == pid) {
                if (cmds[k].fd >= 0) {
                    send_answer(cmds[k].fd, LAUNCH_ENDED, status, launch_cpu_us(&ru));
                    close(cmds[k].fd);
                }
                cmds[k] = cmds[--*n];
                break;
            }
    }
}

/* The started server (detach_process: its own session, stdio on /dev/null, no descriptor but the listener). */
static _Noreturn void serve(int listener, int idle) {
    if (chdir("/") != 0)
        _exit(1);
    prctl(PR_SET_NAME, "iacsg-launch"); /* in ps and top, where it shows the first command's arguments */
    launch_title((char *const[]){"iacsg-launch", NULL});
    fcntl(listener, F_SETFL, O_NONBLOCK);
    signal(SIGPIPE, SIG_IGN);
    sigset_t child;
    sigemptyset(&child);
    sigaddset(&child, SIGCHLD);
    sigprocmask(SIG_SETMASK, &child, NULL);
    int children = signalfd(-1, &child, SFD_CLOEXEC | SFD_NONBLOCK);
    if (children < 0)
        _exit(1);
    static command cmds[MAX_COMMANDS];
    static struct pollfd p[MAX_COMMANDS + 2];
    int n = 0, first = 1, loaded = 0;
    for (;;) {
        /* The first command (it started this server and sends its request at once) is forked for before the
         * preload: its process loads OpenCL on its own thread while it reads its input, as a command that runs
         * itself does, rather than waiting for this process's load. The load waits until no command runs. */
        if (n == 0 && !first && !loaded) {
            preload_opencl();
            loaded = 1;
        }
        int np = 0;
        p[np++] = (struct pollfd){listener, POLLIN, 0};
        p[np++] = (struct pollfd){children, POLLIN, 0};
        for (int k = 0; k < n; k++)
            p[np++] = (struct pollfd){cmds[k].fd, POLLIN, 0}; /* -1: ignored by poll */
        int r = poll(p, (nfds_t)np, first ? FIRST_WAIT_MS : n > 0 ? -1 : idle * 1000);
        int was_first = first;
        first = 0;
        if (r < 0 && errno != EINTR)
            break;
        if (r == 0 && !was_first && !start_command(listener, cmds, &n)) /* idle: one connected just now? */
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
    launch_title_area(argc, argv);
    return (cli_server){"launch", LAUNCH_PROTOCOL, idle, NULL, hash_inherited, serve};
}
