/* src/cli_library.h -- the command's helper libraries (libiacsg_image.so, libiacsg_mpi.so), which it loads at
 * run time rather than links, so that a plain render does not pay for their dependencies. */
#ifndef IACSG_CLI_LIBRARY_H
#define IACSG_CLI_LIBRARY_H
#include "error.h"

/* dlopen()s `name` from beside the running binary (the build tree), else from ../lib/iacsg/ relative to it (an
 * installed prefix: the Makefile's IMAGE_HELPER_DIR), so that a copied or relocated prefix still finds it.
 * NULL when it cannot, with "cannot load WHAT: why" in *err. */
/* The path cli_library_open loads `name` from: 0, or -1 when the binary's own path cannot be read. */
int cli_library_path(const char *name, char path[4096]);

void *cli_library_open(const char *name, const char *what, int dlopen_flags, iacsg_error *err);

#endif
