/* implicits/library.h -- the built-in primitives, blends and transforms, each written in the language itself:
 * a signature with default values (any expression; a default may use earlier parameters) and a body. The
 * compiler parses these fixed texts like user text (lower.c), so a primitive is an AST builder: calling one
 * substitutes the arguments for its parameters. docs/language.md lists them with their formulas. */
#ifndef IACSG_LIBRARY_H
#define IACSG_LIBRARY_H

typedef enum {
    LIB_PRIMITIVE, /* a solid; usable bare (`sphere`) when every parameter has a default */
    LIB_BLEND,     /* combines solids given as arguments */
    LIB_TRANSFORM  /* acts on the space of its first argument: body = the new x, y and z */
} lib_kind;

typedef struct {
    const char *name;
    lib_kind kind;
    const char *signature; /* "torus(R = 1, r = sqrt(0.125))": a parameter without '=' is required */
    const char *prelude;   /* bindings the bodies may use ("" if none) */
    const char *body[3];   /* the solid, or for a transform the expressions substituted for x, y and z */
} lib_entry;

extern const lib_entry lib_entries[];
extern const int lib_count;

/* The entry called `name`, or NULL. */
const lib_entry *lib_find(const char *name);

#endif
