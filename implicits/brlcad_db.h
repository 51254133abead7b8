/* implicits/brlcad_db.h -- a BRL-CAD database as the .asc readers leave it: primitives (parameters in
 * scene.h's layout), combinations (boolean trees of named members with matrices, region flags, colours) and the
 * region-id colour table. Internal to the reader; the outside sees implicits/brlcad.h.
 *
 *   text --brlcad_v4.c | brlcad_v5.c--> brlcad_db (names unresolved) --brlcad_db_finish--> references resolved,
 *   cycles refused, top objects listed --brlcad_tree.c--> iacsg_scene
 */
#ifndef IACSG_BRLCAD_DB_H
#define IACSG_BRLCAD_DB_H
#include "brlcad.h"
#include "scene.h"
#include <stddef.h>

/* Nesting of a v5 combination's tree: deeper ones are refused, so that the recursive parse stays within the
 * stack (brlcad_tree.c bounds its walks the same way). BRL-CAD's own models nest at most a few dozen levels. */
#define BRL_DEPTH_MAX 4096

typedef enum { BRL_LEAF, BRL_UNION, BRL_INTERSECT, BRL_SUBTRACT, BRL_XOR } brl_op;

/* A node of a combination's tree. */
typedef struct {
    brl_op op;
    int left, right; /* binary: node indices */
    char *name;      /* leaf: the member's name */
    int object;      /* leaf: the member's object index, once resolved (brlcad_db_finish) */
    int mat;         /* leaf: index of its 16 numbers in mats, or -1 for the identity */
    int line;        /* leaf: where the member is written */
} brl_node;

typedef struct {
    char *name;
    int line;     /* where it is defined */
    int is_comb;
    /* a primitive */
    scene_prim_type type;
    int nparams, params; /* its numbers: params .. params + nparams - 1 in brlcad_db.params */
    /* a combination */
    int tree; /* root node, or -1 for an empty combination */
    int region, region_id, aircode, inherit, rgb_valid;
    unsigned char rgb[3];
    int referenced; /* a member of some combination */
} brl_object;

typedef struct {
    int low, high;
    unsigned char rgb[3];
} brl_colour;

struct brlcad_db {
    brl_object *objects;
    int nobjects, cap_objects;
    brl_node *nodes;
    int nnodes, cap_nodes;
    double *params;
    int nparams, cap_params;
    double *mats; /* 16 numbers each */
    int nmats, cap_mats;
    brl_colour *colours;
    int ncolours, cap_colours;
    int *hash; /* open addressing over object names: object index + 1, 0 for empty */
    int hash_size;
    int *tops; /* objects no combination references, in order of definition */
    int ntops;
    int version; /* 4 or 5 */
};

brlcad_db *brlcad_db_create(int version);
/* The index of the object named `name`, or -1. */
int brlcad_db_find(const brlcad_db *db, const char *name);
/* A new object (a primitive or an empty combination) named by the n bytes at name; -1 after setting err (out
 * of memory, or the name is already defined). */
int brlcad_db_add_prim(brlcad_db *db, const char *name, size_t n, int line, scene_prim_type type,
                       const double *params, int nparams, iacsg_error *err);
int brlcad_db_add_comb(brlcad_db *db, const char *name, size_t n, int line, iacsg_error *err);
/* Tree nodes: a leaf naming a member (mat NULL: the identity), and a binary node. -1 when out of memory. */
int brlcad_db_leaf(brlcad_db *db, const char *name, size_t n, int line, const double *mat, iacsg_error *err);
int brlcad_db_binary(brlcad_db *db, brl_op op, int left, int right, iacsg_error *err);
int brlcad_db_add_colour(brlcad_db *db, int low, int high, const int rgb[3], iacsg_error *err);
/* Resolves every member name, refuses dangling references and cycles, lists the top objects. */
iacsg_status brlcad_db_finish(brlcad_db *db, iacsg_error *err);

/* The readers of the two formats (text is NUL-terminated at text[len]). */
iacsg_status brlcad_read_v4(const char *text, size_t len, brlcad_db **out, iacsg_error *err);
iacsg_status brlcad_read_v5(const char *text, size_t len, brlcad_db **out, iacsg_error *err);

#endif
