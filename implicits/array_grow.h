/* implicits/array_grow.h -- room in a growable array: the one helper behind the scene's, the BRL-CAD reader's
 * and the region terms' arrays (a pointer, a count in use, a capacity). */
#ifndef IACSG_ARRAY_GROW_H
#define IACSG_ARRAY_GROW_H
#include <stddef.h>

/* Room for `more` elements of `size` bytes after the `count` in use in *items (a pointer to the array's pointer,
 * *cap allocated), doubling from 16; 0 when out of memory (the array is left as it was). */
int array_grow(void *items, int count, int *cap, size_t size, int more);

#endif
