/* src/cli_effects.h -- the render command's options for the ray-tracing effects (iacsg_effects, src/render.h):
 * -shade, -background, -light, -shadows, -bounces, -reflect, -opacity, -aa. Read by parse_options
 * (src/cli_render.c) for the command and the viewer alike. */
#ifndef IACSG_CLI_EFFECTS_H
#define IACSG_CLI_EFFECTS_H
#include "iacsg.h"

/* The effects before any option: all off, but -bounces' default, which only a material that reflects uses. */
void cli_effects_init(iacsg_effects *e);

/* If argv[*k] is an effects option, reads it (and its value, argv[*k + 1], moving *k past it) into *e and returns
 * 1, or prints the problem and returns -1 (exit status 2); returns 0 for any other option. */
int cli_effects_option(int argc, char **argv, int *k, iacsg_effects *e, int *given);

/* Takes a scene's lights (unless -light gave some); returns whether the scene needs the effects: it declares
 * lights, or its materials reflect or let light through. */
int cli_effects_from_scene(iacsg_effects *e, const iacsg_scene *s);

#endif
