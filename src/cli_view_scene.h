/* src/cli_view_scene.h -- what `iacsg view` shows: its input (an expression or a scene file) read and compiled
 * the render command's way (src/cli_render.h), with its bounds, and the renderer for it. The one place of the
 * viewer that knows how an input becomes something to render. */
#ifndef IACSG_CLI_VIEW_SCENE_H
#define IACSG_CLI_VIEW_SCENE_H
#include "cli_render.h"

typedef struct {
    iacsg_scene *scene; /* a plain expression, or regions and surfaces */
    double bounds[6];       /* as the render command chooses them for the same options */
    char bounds_phrase[256]; /* which bounds, and what was proven (choose_bounds) */
    /* the effects it is seen with, as the render command's: the options', with the scene's lights where the
     * options give none (cli_effects_from_scene); has_effects: 0 for the plain render */
    iacsg_effects effects;
    int has_effects;
} view_scene;

/* Reads and compiles o->input into a new scene (*out); *name is the input's name for messages. A file that
 * cannot be read has its message printed (read_input) and becomes IACSG_ERR_IO. */
iacsg_status view_scene_load(const render_options *o, view_scene **out, const char **name, iacsg_error *err);

/* A renderer for the scene (built on the device: seconds when the kernel is not in the cache). */
iacsg_status view_scene_renderer(const view_scene *s, const iacsg_render_config *config, iacsg_renderer **out,
                                 iacsg_error *err);

void view_scene_destroy(view_scene *s); /* NULL is allowed */

#endif
