/* tests/t_tape_pack.h -- what the tape tests share: many tapes in one device buffer, each at its own offset. */
#ifndef T_TAPE_PACK_H
#define T_TAPE_PACK_H
#include "implicits/tape.h"
#include "test.h"
#include <stdlib.h>
#include <string.h>

/* Appends tape's words to *tapes (*words of them used), the next tape starting on an even word so that its
 * doubles are aligned; returns this tape's offset. */
static inline unsigned tape_pack(unsigned **tapes, size_t *words, const iacsg_tape *tape) {
    unsigned at = (unsigned)*words;
    *tapes = realloc(*tapes, (*words + tape->count + 1) * sizeof **tapes);
    CHECK(*tapes != NULL, "out of memory");
    memcpy(*tapes + *words, tape->words, tape->count * sizeof **tapes);
    *words += tape->count + tape->count % 2;
    return at;
}

#endif
