/* src/parallel.h -- a host pass split among threads: the CPUs the device leaves idle while the host works. */
#ifndef IACSG_PARALLEL_H
#define IACSG_PARALLEL_H
#include <stddef.h>

/* Runs fn on each of the n shares (share k at (char *)shares + k * size): shares 1 .. n - 1 on threads of their
 * own, share 0 and any whose thread did not start on this one; returns once every share is done. */
void parallel_each(void *(*fn)(void *), void *shares, size_t size, int n);

/* The machine's CPUs online, at least 1 and at most `most`. */
int parallel_cpus(int most);

#endif
