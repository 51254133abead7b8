/* src/cli.h -- the command-line subcommands. Each takes the arguments after its name (argv[0] is the
 * subcommand), prints its own one-line errors to stderr as "iacsg: ...", and returns the process exit status. */
#ifndef IACSG_CLI_H
#define IACSG_CLI_H
#include "error.h"

int cli_render(int argc, char **argv);  /* iacsg EXPR|SCENE [options]   (src/cli_render.c) */
int cli_eval(int argc, char **argv);    /* iacsg eval EXPR [options]     (src/cli_eval.c) */
int cli_compile(int argc, char **argv); /* iacsg compile EXPR            (src/cli_eval.c) */
int cli_devices(int argc, char **argv); /* iacsg devices                 (src/cli_render.c) */

/* The functions of src/image.h that the CLI uses, from libiacsg_image.so beside the executable, which is
 * dlopen()ed rather than linked so that only the render command pays for OpenImageIO's libraries
 * (src/cli_image.c). cli_image_load_start starts loading it on a thread; the functions wait for that thread
 * (or load it themselves) and fail with "cannot load the image writer PATH: WHY" if it could not be loaded. */
void cli_image_load_start(void);
iacsg_status cli_image_check_format(const char *path, iacsg_error *err);
iacsg_status cli_image_write(const char *path, int width, int height, int channels, const float *pixels,
                             int as_float, iacsg_error *err);

#endif
