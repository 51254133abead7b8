/* src/cli_brlcad.c -- BRL-CAD models on the command line: `iacsg objects MODEL.asc`, `iacsg regions MODEL.asc
 * [OBJECT ...]`, and the scene `iacsg MODEL.asc [OBJECT ...]` renders (implicits/brlcad.h reads it). */
#include "cli.h"
#include "cli_brlcad.h"
#include "implicits/brlcad.h"
#include "implicits/scene.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_brlcad_input(const char *input) {
    size_t n = strlen(input);
    return n > 4 && strcmp(input + n - 4, ".asc") == 0;
}

static iacsg_status read_model(const char *text, const char *const *objects, int nobjects, brlcad_model *m,
                               iacsg_error *err) {
    brlcad_db *db = NULL;
    iacsg_status st = brlcad_db_read(text, strlen(text), &db, err);
    if (st == IACSG_OK)
        st = brlcad_model_build(db, objects, nobjects, m, err);
    brlcad_db_destroy(db);
    return st;
}

iacsg_status cli_brlcad_scene(const char *text, const char *const *objects, int nobjects, iacsg_scene **out,
                              iacsg_error *err) {
    brlcad_model m;
    iacsg_status st = read_model(text, objects, nobjects, &m, err);
    *out = NULL;
    if (st == IACSG_OK) {
        *out = m.scene;
        m.scene = NULL;
        brlcad_model_free(&m);
    }
    return st;
}

/* The model file's text, or NULL after a message; for the listing commands. */
static char *read_model_file(int argc, char **argv, const char *usage) {
    if (argc < 2 || argv[1][0] == '-') {
        fprintf(stderr, "iacsg: usage: %s\n", usage);
        return NULL;
    }
    if (!cli_brlcad_input(argv[1])) {
        fprintf(stderr, "iacsg: %s: not a BRL-CAD ASCII database (.asc)\n", argv[1]);
        return NULL;
    }
    const char *name;
    return read_input(argv[1], &name);
}

static int report(iacsg_error *err, const char *file) {
    print_error(err, file);
    return 1;
}

int cli_objects(int argc, char **argv) {
    char *text = read_model_file(argc, argv, "iacsg objects MODEL.asc");
    if (!text)
        return argc < 2 || argv[1][0] == '-' ? 2 : 1;
    if (argc > 2) {
        free(text);
        fprintf(stderr, "iacsg: objects takes one database, not '%s' too\n", argv[2]);
        return 2;
    }
    iacsg_error err = {0};
    brlcad_db *db = NULL;
    iacsg_status st = brlcad_db_read(text, strlen(text), &db, &err);
    free(text);
    if (st != IACSG_OK)
        return report(&err, argv[1]);
    for (int k = 0; k < brlcad_db_top_count(db); k++)
        printf("%s\n", brlcad_db_top_name(db, k));
    brlcad_db_destroy(db);
    return 0;
}

int cli_regions(int argc, char **argv) {
    char *text = read_model_file(argc, argv, "iacsg regions MODEL.asc [OBJECT ...]");
    if (!text)
        return argc < 2 || argv[1][0] == '-' ? 2 : 1;
    iacsg_error err = {0};
    brlcad_model m;
    iacsg_status st = read_model(text, (const char *const *)argv + 2, argc - 2, &m, &err);
    free(text);
    if (st != IACSG_OK)
        return report(&err, argv[1]);
    printf("# index region_id path (%d regions, %d solid instances, %d air regions left out)\n", m.scene->nitems,
           m.ninstances, m.nair);
    double b[6];
    if (brlcad_scene_bounds(m.scene, b))
        printf("# bounds (rt's model box): %.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", b[0], b[1], b[2], b[3], b[4],
               b[5]);
    for (int k = 0; k < m.scene->nitems; k++)
        printf("%d %d %s\n", k, m.region_ids[k], m.scene->items[k].name);
    brlcad_model_free(&m);
    return 0;
}
