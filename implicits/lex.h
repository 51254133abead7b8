/* implicits/lex.h -- stage 1: text to tokens. Positions are 1-based line and column (bytes). */
#ifndef IACSG_LEX_H
#define IACSG_LEX_H
#include "error.h"
#include <stddef.h>

typedef enum {
    TOK_NUM,     /* 12, 0.5, .5, 1e-3 */
    TOK_NAME,    /* identifiers */
    TOK_PUNCT,   /* one of + - * / ^ ( ) , = | & \ ; and, for scenes, < > ! : (the character is in `ch`) */
    TOK_NEWLINE, /* a line break outside parentheses: ends a scene statement */
    TOK_END
} tok_kind;

typedef struct {
    tok_kind kind;
    char ch;       /* TOK_PUNCT */
    size_t start;  /* byte offset into the text */
    size_t len;
    int line, column;
} token;

#define LEX_MAX_TEXT ((size_t)16 << 20) /* bytes of input */
#define LEX_MAX_NAME 64
#define LEX_MAX_NUMBER 400

/* Splits text into tokens (ending with TOK_END). *out is malloc'ed. Returns the count, or -1 with err set
 * (an unexpected character, a too long name or number, the size limit, out of memory). */
long lex(const char *text, token **out, iacsg_error *err);

/* One line per token, "line:col KIND text", malloc'ed (NULL on out of memory). */
char *lex_dump(const char *text, const token *toks, long count);

#endif
