/* implicits/parse.c -- stage 2: recursive descent from tokens to the AST (ast.h).
 *
 *   scene      := { [statement] (NEWLINE | ';') } ; the last statement is the final expression, except in a
 *                                                     scene with regions or surfaces, which has none
 *   statement  := NAME '=' expr | declaration | expr
 *   declaration:= 'material' NAME '=' 'rgb' '(' number ',' number ',' number ')' { NAME number }
 *               | 'light' NAME '=' ('point' | 'dir') '(' number ',' number ',' number ')' { NAME number }
 *               | 'solid' NAME '=' expr
 *               | 'region' NAME '=' expr [':' NAME]        the expression's outer | & \ are set operations
 *               | 'surface' NAME '=' expr ['where' cond] [':' NAME]
 *   number     := ['-'] NUM
 *   cond       := cand { '|' cand }
 *   cand       := cnot { '&' cnot }
 *   cnot       := { '!' } cprimary
 *   cprimary   := '(' cond ')' | expr ('<' | '>') NUM      the number is 0; a '(' opens a condition when a
 *                                                          '<', '>' or '!' comes before its matching ')'
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
 * In a region, the operators | & \ that are not inside a call's arguments or an arithmetic operand are set
 * operations over solids (AST_BOOL); every maximal expression under them is an operand (a solid's name or an
 * expression written inline): `sphere(1.2) & box` is two operands, `(a + 1) \ b` too, `move(a | b, 1)` one.
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

/* '(' inner ')' at token `at`, nesting counted: an expression's group, or a condition's. */
static int parse_group(parser *p, long at, int (*inner)(parser *)) {
    if (!enter(p, at))
        return -1;
    p->pos++;
    int r = inner(p);
    p->depth--;
    if (r < 0)
        return -1;
    if (!at_punct(p, ')'))
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, "expected ')'");
    p->pos++;
    return r;
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
    if (at_punct(p, '('))
        return parse_group(p, at, parse_expr);
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

static int at_word(parser *p, long at, const char *word) {
    const token *t = &p->a->toks[at];
    return t->kind == TOK_NAME && t->len == strlen(word) && memcmp(p->a->text + t->start, word, t->len) == 0;
}
static int at_statement_end(parser *p) {
    return peek(p)->kind == TOK_NEWLINE || peek(p)->kind == TOK_END || at_punct(p, ';');
}

/* A failure at token t with a message that says all (no ", found ..."). */
static int fail_here(parser *p, const token *t, const char *message) {
    if (p->status == IACSG_OK)
        p->status = iacsg_error_set(p->err, IACSG_ERR_SYNTAX, t->line, t->column, "%s", message);
    return -1;
}

/* ['-'] NUM, for a material. */
static int parse_number(parser *p, const char *what) {
    long sign = at_punct(p, '-') ? p->pos++ : -1;
    if (peek(p)->kind != TOK_NUM)
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, what);
    int r = add_node(p, AST_NUM, p->pos++, 0, -1, -1);
    return r >= 0 && sign >= 0 ? add_node(p, AST_NEG, sign, 0, r, -1) : r;
}

/* WORD(A, B, C) { KEYWORD number }, after "material NAME =" (WORD: rgb) or "light NAME =" (point or dir); the
 * values become the node's arguments, the word's first letter its op. */
static int parse_valued(parser *p, long name, ast_kind kind) {
    int base = p->npending, light = kind == AST_LIGHT;
    const char *what = light ? "light" : "material", *takes = light ? "a light's position or direction takes 3 numbers"
                                                                    : "rgb takes 3 numbers";
    skip_newlines(p);
    int word_ok = light ? at_word(p, p->pos, "point") || at_word(p, p->pos, "dir") : at_word(p, p->pos, "rgb");
    int call = peek(p)->kind == TOK_NAME && p->a->toks[p->pos + 1].kind == TOK_PUNCT &&
               p->a->toks[p->pos + 1].ch == '(';
    if (light && call && !word_ok) {
        char text[LEX_MAX_NAME + 1], message[LEX_MAX_NAME + 96];
        snprintf(message, sizeof message, "unknown light kind '%s': expected point(X, Y, Z) or dir(X, Y, Z)",
                 ast_token_text(p->a, p->pos, text, sizeof text));
        return fail_here(p, peek(p), message);
    }
    if (!call || !word_ok)
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX,
                       light ? "expected point(X, Y, Z) or dir(X, Y, Z), the light's kind and place"
                             : "expected rgb(R, G, B), the material's colour");
    char op = p->a->text[p->a->toks[p->pos].start];
    p->pos += 2;
    for (int k = 0; k < 3; k++) {
        if (k > 0 && !at_punct(p, ','))
            return fail_at(p, peek(p), IACSG_ERR_SYNTAX, takes);
        p->pos += k > 0;
        int v = parse_number(p, takes);
        if (v < 0 || !push_arg(p, v, -1))
            return -1;
    }
    if (!at_punct(p, ')'))
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, takes);
    p->pos++;
    char expected[96];
    snprintf(expected, sizeof expected, "expected a number after the %s's keyword", what);
    while (peek(p)->kind == TOK_NAME) {
        long keyword = p->pos++;
        int v = parse_number(p, expected);
        if (v < 0 || !push_arg(p, v, keyword))
            return -1;
    }
    snprintf(expected, sizeof expected, "expected a %s keyword and its number, or the end of the statement", what);
    if (!at_statement_end(p))
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, expected);
    int first = commit_args(p, base);
    int m = first < 0 ? -1 : add_node(p, kind, name, 0, -1, -1);
    if (m >= 0) {
        p->a->nodes[m].op = op;
        p->a->nodes[m].first = first;
        p->a->nodes[m].nargs = p->a->nargs - first;
    }
    return m;
}

/* Marks an operand that is a bare name (it may name a solid). */
static void mark_operand(parser *p, int node) {
    if (p->a->nodes[node].kind == AST_NAME)
        p->a->nodes[node].op = AST_OPERAND;
}

/* Retypes the outer | & \ of a region's expression (nodes first .. root) into set operations, and marks their
 * operands. Children come before parents, so one backward pass reaches every node from the root. */
static int mark_boolean(parser *p, int first, int root) {
    unsigned char *outer = calloc((size_t)(root - first + 1), 1);
    if (!outer) {
        p->status = iacsg_error_set(p->err, IACSG_ERR_NOMEM, 0, 0, "out of memory parsing the expression");
        return -1;
    }
    outer[root - first] = 1;
    for (int i = root; i >= first; i--) {
        ast_node *n = &p->a->nodes[i];
        if (!outer[i - first])
            continue;
        if (n->kind == AST_BIN && (n->op == '|' || n->op == '&' || n->op == '\\')) {
            n->kind = AST_BOOL;
            outer[n->a - first] = outer[n->b - first] = 1;
        } else {
            mark_operand(p, i);
        }
    }
    free(outer);
    return root;
}

/* Whether the '(' at p->pos opens a condition: a '<', '>' or '!' comes before its matching ')' (no expression
 * holds one). */
static int group_is_condition(parser *p) {
    int depth = 0;
    for (long k = p->pos; p->a->toks[k].kind == TOK_PUNCT || p->a->toks[k].kind == TOK_NAME ||
                          p->a->toks[k].kind == TOK_NUM;
         k++) {
        char c = p->a->toks[k].kind == TOK_PUNCT ? p->a->toks[k].ch : 0;
        depth += c == '(' ? 1 : c == ')' ? -1 : 0;
        if (depth == 0 || c == ';')
            return 0;
        if (c == '<' || c == '>' || c == '!')
            return 1;
    }
    return 0;
}

static int parse_cond(parser *p);

/* '(' cond ')' or E ('<' | '>') 0. */
static int parse_comparison(parser *p) {
    long at = p->pos;
    if (at_punct(p, '(') && group_is_condition(p))
        return parse_group(p, at, parse_cond);
    if (at_statement_end(p) || at_punct(p, ':'))
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, "expected a comparison such as 'ball < 0'");
    int e = parse_expr(p);
    if (e < 0)
        return -1;
    mark_operand(p, e);
    if (!at_punct(p, '<') && !at_punct(p, '>'))
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, "expected '< 0' or '> 0' after the expression in the condition");
    long op = p->pos++;
    const token *zero = peek(p);
    char num[LEX_MAX_NUMBER + 1];
    if (zero->kind != TOK_NUM || strtod(ast_token_text(p->a, p->pos, num, sizeof num), NULL) != 0)
        return fail_at(p, zero, IACSG_ERR_SYNTAX,
                       "a condition compares with 0 ('E < 0' or 'E > 0'; write 'E - c < 0')");
    p->pos++;
    return add_node(p, AST_CMP, op, p->a->toks[op].ch, e, -1);
}

/* { '!' } comparison: the '!' tokens are consecutive, the innermost last. */
static int parse_not(parser *p) {
    long first = p->pos;
    while (at_punct(p, '!'))
        p->pos++;
    long last = p->pos;
    int r = parse_comparison(p);
    for (long k = last - 1; r >= 0 && k >= first; k--)
        r = add_node(p, AST_NOT, k, 0, r, -1);
    return r;
}

/* One level of a condition: operand { op operand }. */
static int parse_cond_level(parser *p, char op, level_fn operand) {
    int r = operand(p);
    while (r >= 0 && at_punct(p, op)) {
        long at = p->pos++;
        skip_newlines(p);
        int b = operand(p);
        r = b < 0 ? -1 : add_node(p, AST_COND, at, op, r, b);
    }
    return r;
}
static int parse_cand(parser *p) { return parse_cond_level(p, '&', parse_not); }
static int parse_cond(parser *p) { return parse_cond_level(p, '|', parse_cand); }

/* [':' NAME]: the token of the material's name, -1 without one, -2 on failure. */
static long parse_material_ref(parser *p) {
    if (!at_punct(p, ':'))
        return -1;
    p->pos++;
    if (peek(p)->kind != TOK_NAME)
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, "expected the name of a material after ':'"), -2;
    return p->pos++;
}

static int declaration_at(parser *p);

/* The expression of a region or surface NAME, which must not be missing (it may start on the next line, as
 * after any '='; not with the next declaration). */
static int parse_item_expr(parser *p, const char *kind, long name) {
    const token *equals = &p->a->toks[p->pos - 1];
    skip_newlines(p);
    if (at_statement_end(p) || at_punct(p, ':') || at_word(p, p->pos, "where") || declaration_at(p) >= 0) {
        char text[LEX_MAX_NAME + 1], message[160];
        snprintf(message, sizeof message, "%s '%s' has no expression after '='", kind,
                 ast_token_text(p->a, name, text, sizeof text));
        return fail_here(p, equals, message);
    }
    return parse_expr(p);
}

static int parse_region(parser *p, long name) {
    int first = p->a->count;
    int v = parse_item_expr(p, "region", name);
    if (v < 0 || mark_boolean(p, first, v) < 0)
        return -1;
    long material = parse_material_ref(p);
    int r = material < -1 ? -1 : add_node(p, AST_REGION, name, 0, v, -1);
    if (r >= 0)
        p->a->nodes[r].first = (int)material;
    return r;
}

static int parse_surface(parser *p, long name) {
    int v = parse_item_expr(p, "surface", name), cond = -1;
    if (v < 0)
        return -1;
    mark_operand(p, v);
    if (at_word(p, p->pos, "where")) {
        const token *where = peek(p);
        p->pos++;
        if (at_statement_end(p) || at_punct(p, ':'))
            return fail_here(p, where, "'where' without a condition: write e.g. 'where ball < 0'");
        if ((cond = parse_cond(p)) < 0)
            return -1;
    }
    long material = parse_material_ref(p);
    int r = material < -1 ? -1 : add_node(p, AST_SURFACE, name, 0, v, cond);
    if (r >= 0)
        p->a->nodes[r].first = (int)material;
    return r;
}

/* The declarations: "KEYWORD NAME" starts one. */
static const char *const declaration_words[] = {"material", "solid", "region", "surface", "light"};

/* The declaration at p->pos (its keyword's index in declaration_words), or -1 for another statement. */
static int declaration_at(parser *p) {
    if (peek(p)->kind != TOK_NAME || p->a->toks[p->pos + 1].kind != TOK_NAME)
        return -1;
    for (int k = 0; k < 5; k++)
        if (at_word(p, p->pos, declaration_words[k]))
            return k;
    return -1;
}

static int parse_declaration(parser *p, int which) {
    long name = p->pos + 1;
    p->pos += 2;
    if (!at_punct(p, '=')) {
        char text[LEX_MAX_NAME + 1], what[128];
        snprintf(what, sizeof what, "expected '=' after '%s %s'", declaration_words[which],
                 ast_token_text(p->a, name, text, sizeof text));
        return fail_at(p, peek(p), IACSG_ERR_SYNTAX, what);
    }
    p->pos++;
    switch (which) {
    case 0: return parse_valued(p, name, AST_MATERIAL);
    case 4: return parse_valued(p, name, AST_LIGHT);
    case 1: {
        int v = parse_expr(p);
        return v < 0 ? -1 : add_node(p, AST_SOLID, name, 0, v, -1);
    }
    case 2: return parse_region(p, name);
    default: return parse_surface(p, name);
    }
}

/* Whether a statement's node is an expression (rather than a binding or a declaration). */
static int is_expression(const ast_node *n) {
    return n->kind != AST_BIND && n->kind != AST_MATERIAL && n->kind != AST_LIGHT && n->kind != AST_SOLID &&
           n->kind != AST_REGION && n->kind != AST_SURFACE;
}

static int parse_scene(parser *p) {
    int last = -1, items = 0;
    long last_tok = 0;
    for (;;) {
        while (peek(p)->kind == TOK_NEWLINE || at_punct(p, ';'))
            p->pos++;
        if (peek(p)->kind == TOK_END)
            break;
        if (last >= 0 && is_expression(&p->a->nodes[last]))
            return fail_at(p, &p->a->toks[last_tok], IACSG_ERR_SYNTAX,
                           "only the last statement of a scene may be an expression; expected 'name = ...'");
        last_tok = p->pos;
        int which = declaration_at(p);
        if (which >= 0) {
            last = parse_declaration(p, which);
            items += which == 2 || which == 3; /* region, surface */
        } else if (peek(p)->kind == TOK_NAME && p->a->toks[p->pos + 1].kind == TOK_PUNCT &&
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
        if (!at_statement_end(p))
            return fail_at(p, peek(p), IACSG_ERR_SYNTAX,
                           at_punct(p, ')') ? "unbalanced ')'" : "expected an operator or the end of the statement");
    }
    if (items > 0 && last >= 0 && is_expression(&p->a->nodes[last]))
        return fail_here(p, &p->a->toks[last_tok],
                         "a scene with regions or surfaces has no final expression (its regions and surfaces are "
                         "what is rendered): declare it as a region, or remove it");
    if (items > 0)
        return -1; /* no final expression; p->status stays OK */
    if (last < 0 || !is_expression(&p->a->nodes[last]))
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
    if (p.status != IACSG_OK) {
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

int ast_declaration_line(const ast *a, const char *name, long tok) {
    char text[LEX_MAX_NAME + 1];
    for (int i = 0; i < a->count; i++) {
        const ast_node *n = &a->nodes[i];
        if ((n->kind == AST_BIND || (n->kind >= AST_MATERIAL && n->kind <= AST_SURFACE)) && n->tok > tok &&
            strcmp(ast_token_text(a, n->tok, text, sizeof text), name) == 0)
            return a->toks[n->tok].line;
    }
    return 0;
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
        case AST_NAME:
            strbuf_printf(&b, "name %s%s", ast_token_text(a, n->tok, name, sizeof name),
                          n->op == AST_OPERAND ? " (operand)" : "");
            break;
        case AST_NEG: strbuf_printf(&b, "neg n%d", n->a); break;
        case AST_BIN: strbuf_printf(&b, "n%d %c n%d", n->a, n->op, n->b); break;
        case AST_BIND: strbuf_printf(&b, "bind %s = n%d", ast_token_text(a, n->tok, name, sizeof name), n->a); break;
        case AST_CALL:
        case AST_MATERIAL:
        case AST_LIGHT:
            strbuf_printf(&b, n->kind == AST_CALL ? "call %s(" : n->kind == AST_MATERIAL ? "material %s = rgb("
                              : n->op == 'p' ? "light %s = point(" : "light %s = dir(",
                          ast_token_text(a, n->tok, name, sizeof name));
            for (int k = 0; k < n->nargs; k++) {
                const ast_arg *g = &a->args[n->first + k];
                strbuf_printf(&b, "%s%s%sn%d", k ? ", " : "",
                              g->keyword >= 0 ? ast_token_text(a, g->keyword, name, sizeof name) : "",
                              g->keyword >= 0 ? "=" : "", g->value);
            }
            strbuf_printf(&b, ")");
            break;
        case AST_SOLID: strbuf_printf(&b, "solid %s = n%d", ast_token_text(a, n->tok, name, sizeof name), n->a); break;
        case AST_REGION:
        case AST_SURFACE:
            strbuf_printf(&b, "%s %s = n%d", n->kind == AST_REGION ? "region" : "surface",
                          ast_token_text(a, n->tok, name, sizeof name), n->a);
            if (n->kind == AST_SURFACE && n->b >= 0)
                strbuf_printf(&b, " where n%d", n->b);
            if (n->first >= 0)
                strbuf_printf(&b, " : %s", ast_token_text(a, n->first, name, sizeof name));
            break;
        case AST_BOOL: strbuf_printf(&b, "set n%d %c n%d", n->a, n->op, n->b); break;
        case AST_COND: strbuf_printf(&b, "cond n%d %c n%d", n->a, n->op, n->b); break;
        case AST_NOT: strbuf_printf(&b, "not n%d", n->a); break;
        case AST_CMP: strbuf_printf(&b, "cmp n%d %c 0", n->a, n->op); break;
        }
        strbuf_printf(&b, "%s\n", i == a->root ? "   <- root" : "");
    }
    return strbuf_finish(&b);
}
