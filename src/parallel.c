/* src/parallel.c -- see parallel.h. */
#include "parallel.h"
#include <pthread.h>
#include <stdlib.h>
#include <unistd.h>

void parallel_each(void *(*fn)(void *), void *shares, size_t size, int n) {
    pthread_t *id = n > 1 ? malloc((size_t)n * sizeof *id) : NULL;
    unsigned char *started = n > 1 ? calloc((size_t)n, 1) : NULL;
    for (int k = 1; id && started && k < n; k++)
        started[k] = pthread_create(&id[k], NULL, fn, (char *)shares + (size_t)k * size) == 0;
    for (int k = 0; k < n; k++) /* without room for the threads' ids, every share here */
        if (!started || !started[k])
            fn((char *)shares + (size_t)k * size);
    for (int k = 1; started && k < n; k++)
        if (started[k])
            pthread_join(id[k], NULL);
    free(id);
    free(started);
}

int parallel_cpus(int most) {
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    return cpus < 1 ? 1 : cpus > most ? most : (int)cpus;
}
