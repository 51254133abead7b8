/* src/detach.c -- see detach.h. */
#define _GNU_SOURCE /* close_range */
#include "detach.h"
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

/* In the detached process: stdio on /dev/null, every descriptor but *keep closed. */
static void detach_descriptors(int *keep) {
    int k = keep ? *keep : -1;
    if (k >= 0 && k < 3) { /* stdio was closed: keep it clear of 0-2 */
        k = fcntl(k, F_DUPFD_CLOEXEC, 3);
        if (k < 0)
            _exit(1);
        *keep = k;
    }
    int null = open("/dev/null", O_RDWR | O_CLOEXEC);
    for (int fd = 0; fd < 3; fd++)
        if (null < 0 || dup2(null, fd) < 0)
            close(fd);
    int failed = k < 0 ? close_range(3, ~0u, 0) != 0
                       : (k > 3 && close_range(3, (unsigned)k - 1, 0) != 0) ||
                             close_range((unsigned)k + 1, ~0u, 0) != 0;
    if (failed)
        for (int fd = 3; fd < 65536; fd++)
            if (fd != k)
                close(fd);
}

int detach_process(int *keep) {
    fflush(NULL); /* or the detached copy of the buffers could be written twice */
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        pid_t detached = setsid() < 0 ? -1 : fork();
        if (detached == 0) {
            detach_descriptors(keep);
            return 1;
        }
        _exit(detached < 0);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}
