/* implicits/ast.h -- stage 2: the syntax tree. Nodes live in an array in the order the parser finishes them,
 * so every node's children come before it: later stages walk the array with a loop, never a recursion, and a
 * scene's statements appear in source order. */
#ifndef IACSG_AST_H
#define IACSG_AST_H
#include "lex.h"

typedef enum {
    AST_NUM,  /* tok: the number */
    AST_NAME, /* tok: the name (a variable, constant, binding, parameter or bare primitive) */
    AST_CALL, /* tok: the callee's name; args[first .. first + nargs) */
    AST_NEG,  /* a: the operand; tok: the '-' */
    AST_BIN,  /* a op b, op one of + - * / ^ | & \ ; tok: the operator */
    AST_BIND, /* tok: the name; a: the value ("name = value" in a scene) */
    /* The declarations of multi-material scenes (docs/language.md, "Regions, surfaces and materials"); tok is
     * the declared name, the statement's keyword is the token before it. */
    AST_MATERIAL, /* args[first .. first + nargs): red, green, blue (AST_NUM, or AST_NEG of one), then the
                   * keyword arguments ("specular 0.5": the keyword's token and its number) */
    AST_LIGHT,    /* op 'p' (point(X, Y, Z)) or 'd' (dir(X, Y, Z)); args: X, Y, Z, then keyword arguments */
    AST_SOLID,    /* a: the expression */
    AST_REGION,   /* a: the boolean expression (AST_BOOL over operands); first: the material's token, or -1 */
    AST_SURFACE,  /* a: the expression; b: the condition, or -1; first: the material's token, or -1 */
    AST_BOOL,     /* in a region: a op b, op one of | & \ as set operations over solids; tok: the operator */
    AST_COND,     /* in a condition: a op b, op '&' (and) or '|' (or); tok: the operator */
    AST_NOT,      /* in a condition: ! a; tok: the '!' */
    AST_CMP       /* in a condition: a < 0 or a > 0 (op '<' or '>'); tok: the operator */
} ast_kind;

/* An AST_NAME's op is AST_OPERAND when the name is an operand of a region or a condition: it names a solid,
 * or is an expression written inline (a binding or a bare primitive). */
#define AST_OPERAND 's'

typedef struct {
    ast_kind kind;
    long tok;
    char op;
    int a, b;
    int first, nargs;
} ast_node;

typedef struct {
    int value;    /* ast node */
    long keyword; /* token of "keyword =", or -1 for a positional argument */
} ast_arg;

typedef struct {
    const char *text;
    token *toks;
    long ntoks;
    ast_node *nodes;
    int count, cap;
    ast_arg *args;
    int nargs, capargs;
    int root; /* the final expression, or -1 in a scene with regions or surfaces (which has none) */
} ast;

#define PARSE_MAX_DEPTH 200 /* nesting of parentheses, calls and exponents */

/* Lexes and parses text: a scene (statements separated by line breaks or ';': bindings "name = expression",
 * declarations, and, for the last one only, an expression; parse.c has the grammar). On failure returns the
 * status with err set (line and column of the offending token) and frees everything. */
iacsg_status parse(const char *text, ast *out, iacsg_error *err);
void ast_free(ast *a);

/* The line of a binding or declaration of name after token tok, or 0 if there is none (for "used before its
 * declaration"). */
int ast_declaration_line(const ast *a, const char *name, long tok);

/* The source text of a token, copied into buf (truncated to size). */
const char *ast_token_text(const ast *a, long tok, char *buf, size_t size);

/* One line per node in array order, e.g. "n4 = call sphere(n2, r=n3)". NULL on out of memory. */
char *ast_dump(const ast *a);

#endif
