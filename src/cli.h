/* src/cli.h -- the command-line subcommands. Each takes the arguments after its name (argv[0] is the
 * subcommand), prints its own one-line errors to stderr as "iacsg: ...", and returns the process exit status. */
#ifndef IACSG_CLI_H
#define IACSG_CLI_H

int cli_render(int argc, char **argv);  /* iacsg EXPR|SCENE [options]   (src/cli_render.c) */
int cli_eval(int argc, char **argv);    /* iacsg eval EXPR [options]     (src/cli_eval.c) */
int cli_compile(int argc, char **argv); /* iacsg compile EXPR            (src/cli_eval.c) */
int cli_devices(int argc, char **argv); /* iacsg devices                 (src/cli_render.c) */
int cli_view(int argc, char **argv);    /* iacsg view EXPR|SCENE [options] (src/cli_view.c) */

/* The subcommand argv[1] names, or the render (src/cli_main.c): main, once src/cli_launch.c has not handed the
 * command to the launcher, and the launcher's forked process. */
int cli_dispatch(int argc, char **argv);

#endif
