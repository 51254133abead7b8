/* tests/t_brlcad_model.h -- what the BRL-CAD tests share: the model of a database text (all its top objects when
 * objects is NULL), read and built as the command does, and of a sample database (tests/data/brlcad/); the test
 * fails on an error. */
#ifndef T_BRLCAD_MODEL_H
#define T_BRLCAD_MODEL_H
#include "implicits/brlcad.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static inline brlcad_model model_of(const char *text, const char *const *objects, int nobjects) {
    brlcad_db *db = NULL;
    iacsg_error err = {0};
    brlcad_model m;
    CHECK(brlcad_db_read(text, strlen(text), &db, &err) == IACSG_OK, "read: line %d: %s", err.line, err.message);
    iacsg_status st = brlcad_model_build(db, objects, nobjects, &m, &err);
    brlcad_db_destroy(db);
    CHECK(st == IACSG_OK, "build: %s", err.message);
    return m;
}

static inline brlcad_model model_of_file(const char *file, const char *const *objects, int nobjects) {
    char path[4096];
    snprintf(path, sizeof path, "%s/tests/data/brlcad/%s", test_source_dir(), file);
    char *text = test_read_file(path, NULL);
    CHECK(text, "cannot read %s", path);
    brlcad_model m = model_of(text, objects, nobjects);
    free(text);
    return m;
}

#endif
