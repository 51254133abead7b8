/* implicits/parse.c -- stage 2: recursive descent from tokens to the AST (ast.h).
 *
 *   scene      := { [statement] (NEWLINE | ';') } ; the last statement is the final expression
 *   statement  := NAME '=' expr | expr
 *   expr       := inter { '|' inter }            union (lowest precedence)
 *   inter      := diff { '&' diff }               intersection
 *   diff       := sum { '\' sum }                 difference
 *   sum        := product { ('+' | '-') product }
 *   product    := unary { ('*' | '/') unary }
 *   unary      := { '-' | '+' } power
 *   power      := primary [ '^' unary ]           right associative: 2^3^2 = 2^9, -x^2 = -(x^2)
 *   primary    := NUM | NAME | NAME '(' [arg { ',' arg }] ')' | '(' expr ')'
 *   arg        := NAME '=' expr | expr
 *
 * Chains of binary operators and signs are loops; only parentheses, calls and exponents recurse, and their
 * depth is limited (PARSE_MAX_DEPTH), so no input can overflow the stack. A line break after a binary operator,
 * '=' or ',' continues the statement. */
#include "ast.h"
#include "strbuf.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    ast *a;
    long pos;
    int depth;
    iacsg_error *err;
    iacsg_status status;
    ast_arg *pending; /* arguments of the calls being parsed, innermost last */
    int npending, cappending;
} parser;

static const token *peek(parser *p) { return &p->a->toks[p->pos]; }
static int at_punct(parser *p, char c) { return peek(p)->kind == TOK_PUNCT && peek(p)->ch == c; }

static void describe(const parser *p, const token *t, char *buf, size_t size) {
    if (t->kind == TOK_END)
        snprintf(buf, size, "the end of the input");
    else if (t->kind == TOK_NEWLINE)
        snprintf(buf, size, "the end of the line");
    else
        snprintf(buf, size, "'%.*s'", (int)(t->len < 40 ? t->len : 40), p->a->text + t->start);
}

static int fail_at(parser *p, const token *t, iacsg_status status, const char *what) {
    char found[64];
    describe(p, t, found, sizeof found);
    if (p->status == IACSG_OK)
        p->status = iacsg_error_set(p->err, status, t->line, t->column, "%s, found %s", what, found);
    return -1;
}

static int add_node(parser *p, ast_kind kind, long tok, char op, int a, int b) {
    ast *t = p->a;
    if (t->count == t->cap) {
        int cap = t->cap ? t->cap * 2 : 256;
        ast_node *n = realloc(t->nodes, (size_t)cap * sizeof *n);
        if (!n) {
            p->status = iacsg_error_set(p->err, IACSG_ERR_NOMEM, 0, 0, "out of memory parsing the expression");
            return -1;
        }
        t->nodes = n;
        t->cap = cap;
    }
    ast_node node = {kind, tok, op, a, b, 0, 0};
    t->nodes[t->count] = node;
    return t->count++;
}

static void skip_newlines(parser *p) {
    while (peek(p)->kind == TOK_NEWLINE)
        p->pos++;
}

static int parse_expr(parser *p);

/* One more level of nesting, opened at token `at`. */
static int enter(parser *p, long at) {
    if (++p->depth <= PARSE_MAX_DEPTH)
        return 1;
    const token *t = &p->a->toks[at];
    if (p->status == IACSG_OK)
        p->status = iacsg_error_set(p->err, IACSG_ERR_LIMIT, t->line, t->column,
                                    "expression nested too deeply (more than %d levels)", PARSE_MAX_DEPTH);
    return 0;
}

static int push_arg(parser *p, int value, long keyword) {
    if (p->npending == p->cappending) {
        int cap = p->cappending ? p->cappending * 2 : 32;
        ast_arg *n = realloc(p->pending, (size_t)cap * sizeof *n);
        if (!n) {
            p->status = iacsg_error_set(p->err, IACSG_ERR_NOMEM, 0, 0, "out of memory parsing the expression");
            return 0;
        }
        p->pending = n;
        p->cappending = cap;
    }
    p->pending[p->npending].value = value;
    p->pending[p->npending].keyword = keyword;
    p->npending++;
    return 1;
}

/* Moves the pending arguments from `base` on into the AST's argument array; returns the first index or -1. */
static int commit_args(parser *p, int base) {
    ast *t = p->a;
    int n = p->npending - base;
    if (t->nargs + n > t->capargs) {
        int cap = t->capargs ? t->capargs : 64;
        while (cap < t->nargs + n)
            cap *= 2;
        ast_arg *a = realloc(t->args, (size_t)cap * sizeof *a);
        if (!a) {
            p->status = iacsg_error_set(p->err, IACSG_ERR_NOMEM, 0, 0, "out of memory parsing the expression");
            return -1;
        }
        t->args = a;
        t->capargs = cap;
    }
    int first = t->nargs;
    if (n > 0)
        memcpy(t->args + first, p->pending + base, (size_t)n * sizeof *t->args);
    t->nargs += n;
    p->npending = base;
    return first;
}

/* NAME '(' args ')', the name already consumed at position `name`. */
static int parse_call(parser *p, long name) {
    int base = p->npending;
    p->pos++; /* '(' */
    skip_newlines(p);
    if (!at_punct(p, ')'))
        for (;;) {
            long keyword = -1;
            if (peek(p)->kind == TOK_NAME && p->a->toks[p->pos + 1].kind == TOK_PUNCT &&
                p->a->toks[p->pos + 1].ch == '=') {
                keyword = p->pos;
                p->pos += 2;
            }
            int v = parse_expr(p);
            if (v < 0 || !push_arg(p, v, keyword))
                return -1;
            if (!at_punct(p, ','))
                break;
            p->pos++;
        }
    if (!at_punct(p, ')'))
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, "expected ',' or ')' in the argument list");
    p->pos++;
    int first = commit_args(p, base);
    if (first < 0)
        return -1;
    int call = add_node(p, AST_CALL, name, 0, -1, -1);
    if (call >= 0) {
        p->a->nodes[call].first = first;
        p->a->nodes[call].nargs = p->a->nargs - first;
    }
    return call;
}

static int parse_primary(parser *p) {
    const token *t = peek(p);
    long at = p->pos;
    if (t->kind == TOK_NUM) {
        p->pos++;
        return add_node(p, AST_NUM, at, 0, -1, -1);
    }
    if (t->kind == TOK_NAME) {
        p->pos++;
        if (at_punct(p, '(')) {
            if (!enter(p, at))
                return -1;
            int r = parse_call(p, at);
            p->depth--;
            return r;
        }
        return add_node(p, AST_NAME, at, 0, -1, -1);
    }
    if (at_punct(p, '(')) {
        if (!enter(p, at))
            return -1;
        p->pos++;
        int r = parse_expr(p);
        p->depth--;
        if (r < 0)
            return -1;
        if (!at_punct(p, ')'))
            return fail_at(p, peek(p), IACSG_ERR_SYNTAX, "expected ')'");
        p->pos++;
        return r;
    }
    return fail_at(p, t, IACSG_ERR_SYNTAX, "expected a number, a name or '('");
}

static int parse_unary(parser *p) {
    long signs[PARSE_MAX_DEPTH];
    int nsigns = 0;
    while (at_punct(p, '-') || at_punct(p, '+')) {
        if (at_punct(p, '-')) {
            if (nsigns == PARSE_MAX_DEPTH)
                return fail_at(p, peek(p), IACSG_ERR_LIMIT, "too many signs in a row");
            signs[nsigns++] = p->pos;
        }
        p->pos++;
    }
    int r = parse_primary(p);
    if (r >= 0 && at_punct(p, '^')) {
        long op = p->pos++;
        skip_newlines(p);
        if (!enter(p, op))
            return -1;
        int e = parse_unary(p);
        p->depth--;
        r = e < 0 ? -1 : add_node(p, AST_BIN, op, '^', r, e);
    }
    while (r >= 0 && nsigns > 0)
        r = add_node(p, AST_NEG, signs[--nsigns], 0, r, -1);
    return r;
}

/* One left-associative level: operand { op operand } for the operator characters in ops. */
typedef int (*level_fn)(parser *);
static int parse_level(parser *p, const char *ops, level_fn operand) {
    int r = operand(p);
    while (r >= 0 && peek(p)->kind == TOK_PUNCT && strchr(ops, peek(p)->ch)) {
        long op = p->pos++;
        skip_newlines(p);
        int b = operand(p);
        r = b < 0 ? -1 : add_node(p, AST_BIN, op, p->a->toks[op].ch, r, b);
    }
    return r;
}
static int parse_product(parser *p) { return parse_level(p, "*/", parse_unary); }
static int parse_sum(parser *p) { return parse_level(p, "+-", parse_product); }
static int parse_diff(parser *p) { return parse_level(p, "\\", parse_sum); }
static int parse_inter(parser *p) { return parse_level(p, "&", parse_diff); }
static int parse_expr(parser *p) {
    skip_newlines(p);
    return parse_level(p, "|", parse_inter);
}

static int parse_scene(parser *p) {
    int last = -1;
    long last_tok = 0;
    for (;;) {
        while (peek(p)->kind == TOK_NEWLINE || at_punct(p, ';'))
            p->pos++;
        if (peek(p)->kind == TOK_END)
            break;
        if (last >= 0 && p->a->nodes[last].kind != AST_BIND)
            return fail_at(p, &p->a->toks[last_tok], IACSG_ERR_SYNTAX,
                           "only the last statement of a scene may be an expression; expected 'name = ...'");
        last_tok = p->pos;
        if (peek(p)->kind == TOK_NAME && p->a->toks[p->pos + 1].kind == TOK_PUNCT &&
            p->a->toks[p->pos + 1].ch == '=') {
            long name = p->pos;
            p->pos += 2;
            int v = parse_expr(p);
            last = v < 0 ? -1 : add_node(p, AST_BIND, name, 0, v, -1);
        } else {
            last = parse_expr(p);
        }
        if (last < 0)
            return -1;
        if (peek(p)->kind != TOK_NEWLINE && peek(p)->kind != TOK_END && !at_punct(p, ';'))
            return fail_at(p, peek(p), IACSG_ERR_SYNTAX,
                           at_punct(p, ')') ? "unbalanced ')'" : "expected an operator or the end of the statement");
    }
    if (last < 0 || p->a->nodes[last].kind == AST_BIND)
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, "expected an expression to render");
    return last;
}

iacsg_status parse(const char *text, ast *out, iacsg_error *err) {
    memset(out, 0, sizeof *out);
    out->text = text;
    out->ntoks = lex(text, &out->toks, err);
    if (out->ntoks < 0)
        return err ? err->status : IACSG_ERR_SYNTAX;
    parser p = {out, 0, 0, err, IACSG_OK, NULL, 0, 0};
    out->root = parse_scene(&p);
    free(p.pending);
    if (out->root < 0) {
        ast_free(out);
        return p.status;
    }
    return IACSG_OK;
}

void ast_free(ast *a) {
    free(a->toks);
    free(a->nodes);
    free(a->args);
    memset(a, 0, sizeof *a);
}

const char *ast_token_text(const ast *a, long tok, char *buf, size_t size) {
    const token *t = &a->toks[tok];
    size_t n = t->len < size - 1 ? t->len : size - 1;
    memcpy(buf, a->text + t->start, n);
    buf[n] = '\0';
    return buf;
}

char *ast_dump(const ast *a) {
    strbuf b = {0};
    char name[LEX_MAX_NUMBER + 1];
    for (int i = 0; i < a->count; i++) {
        const ast_node *n = &a->nodes[i];
        strbuf_printf(&b, "n%d = ", i);
        switch (n->kind) {
        case AST_NUM: strbuf_printf(&b, "num %s", ast_token_text(a, n->tok, name, sizeof name)); break;
        case AST_NAME: strbuf_printf(&b, "name %s", ast_token_text(a, n->tok, name, sizeof name)); break;
        case AST_NEG: strbuf_printf(&b, "neg n%d", n->a); break;
        case AST_BIN: strbuf_printf(&b, "n%d %c n%d", n->a, n->op, n->b); break;
        case AST_BIND: strbuf_printf(&b, "bind %s = n%d", ast_token_text(a, n->tok, name, sizeof name), n->a); break;
        case AST_CALL:
            strbuf_printf(&b, "call %s(", ast_token_text(a, n->tok, name, sizeof name));
            for (int k = 0; k < n->nargs; k++) {
                const ast_arg *g = &a->args[n->first + k];
                strbuf_printf(&b, "%s%s%sn%d", k ? ", " : "",
                              g->keyword >= 0 ? ast_token_text(a, g->keyword, name, sizeof name) : "",
                              g->keyword >= 0 ? "=" : "", g->value);
            }
            strbuf_printf(&b, ")");
            break;
        }
        strbuf_printf(&b, "%s\n", i == a->root ? "   <- root" : "");
    }
    return strbuf_finish(&b);
}
