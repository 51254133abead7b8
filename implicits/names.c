/* implicits/names.c -- see names.h. */
#include "names.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static unsigned long hash_name(const char *s) {
    unsigned long h = 5381;
    while (*s)
        h = h * 33 + (unsigned char)*s++;
    return h;
}

/* The slot holding name, or the empty slot where it would go (the table is never full: see names_add). */
static name_entry *slot_of(const name_table *t, const char *name) {
    unsigned long mask = (unsigned long)t->nslots - 1;
    for (unsigned long i = hash_name(name) & mask;; i = (i + 1) & mask)
        if (t->slots[i].name[0] == '\0' || strcmp(t->slots[i].name, name) == 0)
            return &t->slots[i];
}

const name_entry *names_find(const name_table *t, const char *name) {
    if (t->nslots == 0)
        return NULL;
    const name_entry *e = slot_of(t, name);
    return e->name[0] ? e : NULL;
}

int names_add(name_table *t, const char *name, name_kind kind, int node, int index, int line) {
    if ((t->count + 1) * 2 > t->nslots) {
        int n = t->nslots ? t->nslots * 2 : 64;
        name_table bigger = {calloc((size_t)n, sizeof(name_entry)), n, t->count};
        if (!bigger.slots)
            return 0;
        for (int i = 0; i < t->nslots; i++)
            if (t->slots[i].name[0])
                *slot_of(&bigger, t->slots[i].name) = t->slots[i];
        free(t->slots);
        *t = bigger;
    }
    name_entry *e = slot_of(t, name);
    snprintf(e->name, sizeof e->name, "%s", name);
    e->kind = kind;
    e->node = node;
    e->index = index;
    e->line = line;
    t->count++;
    return 1;
}

void names_free(name_table *t) {
    free(t->slots);
    memset(t, 0, sizeof *t);
}

const char *name_kind_word(name_kind kind) {
    static const char *const words[] = {"binding", "solid", "material", "region", "surface", "light"};
    return words[kind];
}
