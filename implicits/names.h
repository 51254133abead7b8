/* implicits/names.h -- a scene's one namespace: every name a scene declares (bindings, solids, materials,
 * regions, surfaces), with its kind and where it was declared. Open addressing; lookups are O(1), so scenes of
 * thousands of solids resolve their names in linear time. */
#ifndef IACSG_NAMES_H
#define IACSG_NAMES_H
#include "lex.h"

typedef enum { NAME_BINDING, NAME_SOLID, NAME_MATERIAL, NAME_REGION, NAME_SURFACE, NAME_LIGHT } name_kind;

typedef struct {
    char name[LEX_MAX_NAME + 1]; /* "" in an empty slot */
    name_kind kind;
    int node;  /* binding, solid: its DAG node; else -1 */
    int index; /* solid, material, region, surface: its index in the scene; else -1 */
    int line;
} name_entry;

typedef struct {
    name_entry *slots;
    int nslots, count;
} name_table;

/* The entry of name, or NULL. */
const name_entry *names_find(const name_table *t, const char *name);
/* Adds a name that is not in the table yet; 0 when out of memory. */
int names_add(name_table *t, const char *name, name_kind kind, int node, int index, int line);
void names_free(name_table *t);

/* "binding", "solid", "material", "region", "surface", "light". */
const char *name_kind_word(name_kind kind);

#endif
