/* src/detach.c -- a process detached from the one that starts it, for work that outlives a command: the image
 * writer's server (src/cli_writer_server.c) and the program cache's saver (src/clrt_cache.c). */
#ifndef IACSG_DETACH_H
#define IACSG_DETACH_H

/* Forks a process of its own session that is no child of this one (an intermediate process forks it and ends at
 * once; this process waits for that one), with stdio on /dev/null and every other descriptor closed but *keep
 * (keep NULL: none), so that it holds no end of a caller's pipe. Returns 1 in the detached process (*keep then
 * names the kept descriptor, moved above 2), 0 in this process when it was started, -1 when it could not be. */
int detach_process(int *keep);

#endif
