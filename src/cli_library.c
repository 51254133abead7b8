/* src/cli_library.c -- see cli_library.h. */
#include "cli_library.h"
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define INSTALLED_DIR "../lib/iacsg/" /* from bin/ */

int cli_library_path(const char *name, char path[4096]) {
    ssize_t n = readlink("/proc/self/exe", path, 4096 - 256);
    if (n <= 0 || strlen(name) > 128)
        return -1;
    path[n] = '\0';
    char *slash = strrchr(path, '/');
    char *file = slash ? slash + 1 : path;
    strcpy(file, name);
    if (access(path, F_OK) != 0)
        snprintf(file, 256, INSTALLED_DIR "%s", name);
    return 0;
}

void *cli_library_open(const char *name, const char *what, int dlopen_flags, iacsg_error *err) {
    char path[4096];
    if (cli_library_path(name, path) != 0) {
        iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "cannot load %s: cannot find %s: %s", what, name, strerror(errno));
        return NULL;
    }
    void *handle = dlopen(path, dlopen_flags);
    if (!handle)
        iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "cannot load %s: %s", what, dlerror());
    return handle;
}
