/* src/cli_brlcad.h -- BRL-CAD models on the command line (src/cli_brlcad.c): the listing commands and the scene
 * the render and view commands make of a model. */
#ifndef IACSG_CLI_BRLCAD_H
#define IACSG_CLI_BRLCAD_H
#include "cli_render.h"

/* Whether the input names a BRL-CAD ASCII database (it ends in ".asc"). */
int cli_brlcad_input(const char *input);

/* The scene of the given top objects of the database text (all tops when nobjects is 0). */
iacsg_status cli_brlcad_scene(const char *text, const char *const *objects, int nobjects, iacsg_scene **out,
                              iacsg_error *err);

int cli_objects(int argc, char **argv); /* iacsg objects MODEL.asc */
int cli_regions(int argc, char **argv); /* iacsg regions MODEL.asc [OBJECT ...] */

#endif
