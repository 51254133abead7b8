/* src/cli_launch.h -- the command's side of the launcher (src/cli_launch_server.h): a command that needs OpenCL
 * (a render, `devices`) is run by a process the launcher forks, which has the OpenCL driver's libraries loaded
 * already, while this process relays signals to it and ends as it ends. */
#ifndef IACSG_CLI_LAUNCH_H
#define IACSG_CLI_LAUNCH_H

/* Hands the command to the launcher when it should go there and one can be had (started, if none answers).
 * Returns 1 when the launcher ran it (*status: its exit status; a command that a signal ended ends this process
 * by the same signal), 0 when this process must run it itself. Not when: IACSG_LAUNCH_IDLE=0; the command needs no
 * OpenCL or is the viewer; under mpirun; under a debugger or tracer, or with LD_PRELOAD (valgrind); a standard
 * stream closed, or a terminal that stops background writes (stty tostop). IACSG_LAUNCH_TRACE (non-empty)
 * prints on stderr which way the command went. */
int cli_launch(int argc, char **argv, int *status);

#endif
