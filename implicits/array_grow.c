/* implicits/array_grow.c -- see array_grow.h. */
#include "array_grow.h"
#include <stdlib.h>

int array_grow(void *items, int count, int *cap, size_t size, int more) {
    if (count + more <= *cap)
        return 1;
    int n = *cap ? *cap : 16;
    while (n < count + more)
        n *= 2;
    void *p = realloc(*(void **)items, (size_t)n * size);
    if (!p)
        return 0;
    *(void **)items = p;
    *cap = n;
    return 1;
}
