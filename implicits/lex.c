/* implicits/lex.c -- stage 1: the lexer (see lex.h). Comments run from '#' to the end of the line. A line break
 * inside parentheses is plain space, so long expressions may span lines. */
#include "lex.h"
#include "strbuf.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* The length of the number at s: digits [. digits] [e [+-] digits]; an 'e' not followed by an exponent is the
 * constant e, so "2e" is 2 then e. */
static size_t number_length(const char *s) {
    size_t i = 0;
    while (is_digit(s[i]))
        i++;
    if (s[i] == '.')
        for (i++; is_digit(s[i]); i++)
            ;
    if (s[i] == 'e' || s[i] == 'E') {
        size_t j = i + 1;
        if (s[j] == '+' || s[j] == '-')
            j++;
        if (is_digit(s[j])) {
            while (is_digit(s[j]))
                j++;
            i = j;
        }
    }
    return i;
}

/* Why the number of length len at s is not acceptable, or NULL. A letter right after it ("0x", "2e", "3pi")
 * makes it malformed: products are written with '*'. Beyond the largest double it is out of range (a real
 * that no float or double interval of finite numbers can enclose). */
static const char *number_problem(const char *s, size_t len) {
    if (is_alpha(s[len]))
        return "malformed number";
    char buf[LEX_MAX_NUMBER + 1];
    memcpy(buf, s, len);
    buf[len] = '\0';
    return isinf(strtod(buf, NULL)) ? "number out of range (beyond 1.8e308)" : NULL;
}

long lex(const char *text, token **out, iacsg_error *err) {
    size_t size = strlen(text);
    *out = NULL;
    if (size > LEX_MAX_TEXT)
        return iacsg_error_set(err, IACSG_ERR_LIMIT, 0, 0, "input too large: %zu bytes (the limit is %zu)", size,
                               LEX_MAX_TEXT),
               -1;
    token *toks = NULL;
    long count = 0, cap = 0;
    int line = 1, depth = 0;
    size_t line_start = 0, i = 0;
    for (;;) {
        char c = text[i];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            i++;
            continue;
        }
        if (c == '#') {
            while (text[i] && text[i] != '\n')
                i++;
            continue;
        }
        if (count == cap) {
            cap = cap ? cap * 2 : 64;
            token *t = realloc(toks, (size_t)cap * sizeof *t);
            if (!t) {
                free(toks);
                return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory reading the expression"), -1;
            }
            toks = t;
        }
        token *t = &toks[count];
        int column = (int)(i - line_start) + 1;
        t->start = i;
        t->line = line;
        t->column = column;
        t->ch = 0;
        if (c == '\0') {
            t->kind = TOK_END;
            t->len = 0;
            *out = toks;
            return count + 1;
        }
        if (c == '\n') {
            line++;
            line_start = i + 1;
            if (depth > 0) {
                i++;
                continue;
            }
            t->kind = TOK_NEWLINE;
            t->len = 1;
        } else if (is_digit(c) || (c == '.' && is_digit(text[i + 1]))) {
            t->kind = TOK_NUM;
            t->len = number_length(text + i);
            if (t->len > LEX_MAX_NUMBER) {
                free(toks);
                return iacsg_error_set(err, IACSG_ERR_LIMIT, line, column, "number too long (over %d characters)",
                                       LEX_MAX_NUMBER),
                       -1;
            }
            const char *bad = number_problem(text + i, t->len);
            if (bad) {
                size_t shown = t->len;
                while (is_alpha(text[i + shown]) || is_digit(text[i + shown]))
                    shown++;
                free(toks);
                return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, column, "%s: '%.*s'", bad, (int)shown, text + i),
                       -1;
            }
        } else if (is_alpha(c)) {
            t->kind = TOK_NAME;
            size_t n = 0;
            while (is_alpha(text[i + n]) || is_digit(text[i + n]))
                n++;
            t->len = n;
            if (n > LEX_MAX_NAME) {
                free(toks);
                return iacsg_error_set(err, IACSG_ERR_LIMIT, line, column, "name too long (over %d characters)",
                                       LEX_MAX_NAME),
                       -1;
            }
        } else if (c && strchr("+-*/^(),=|&\\;<>!:", c)) {
            t->kind = TOK_PUNCT;
            t->ch = c;
            t->len = 1;
            depth += c == '(' ? 1 : c == ')' && depth > 0 ? -1 : 0;
        } else {
            unsigned char u = (unsigned char)c;
            free(toks);
            if (u >= 0x21 && u < 0x7f)
                return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, column, "unexpected character '%c'", c), -1;
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, column, "unexpected byte 0x%02x", u), -1;
        }
        i += t->len;
        count++;
    }
}

char *lex_dump(const char *text, const token *toks, long count) {
    static const char *const kinds[] = {"NUM", "NAME", "PUNCT", "NEWLINE", "END"};
    strbuf b = {0};
    for (long k = 0; k < count; k++) {
        const token *t = &toks[k];
        strbuf_printf(&b, "%d:%d %s", t->line, t->column, kinds[t->kind]);
        if (t->kind == TOK_NUM || t->kind == TOK_NAME || t->kind == TOK_PUNCT)
            strbuf_printf(&b, " %.*s", (int)t->len, text + t->start);
        strbuf_printf(&b, "\n");
    }
    return strbuf_finish(&b);
}
