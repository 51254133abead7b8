/* implicits/strbuf.h -- a growable string for the dumps and the emitter. An allocation failure is sticky:
 * later appends do nothing and strbuf_finish returns NULL. */
#ifndef IACSG_STRBUF_H
#define IACSG_STRBUF_H
#include <stddef.h>

typedef struct {
    char *s;
    size_t len, cap;
    int failed;
} strbuf;

void strbuf_printf(strbuf *b, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void strbuf_append(strbuf *b, const char *s, size_t n);
/* The string (the caller free()s it), or NULL if an allocation failed. The buffer is reset either way. */
char *strbuf_finish(strbuf *b);

#endif
