/* src/cli_view_scene.c -- see cli_view_scene.h. */
#include "cli_view_scene.h"
#include "cli_effects.h"
#include <stdio.h>
#include <stdlib.h>

iacsg_status view_scene_load(const render_options *o, view_scene **out, const char **name, iacsg_error *err) {
    *out = NULL;
    char *text = read_input(o->input, name);
    if (!text)
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: cannot read the scene file", o->input);
    view_scene *s = calloc(1, sizeof *s);
    iacsg_status st = s ? load_input(o, text, *name, &s->scene, err)
                        : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    free(text);
    if (st != IACSG_OK) {
        view_scene_destroy(s);
        return st;
    }
    render_options chosen = *o; /* choose_bounds writes the options' view */
    const char *phrase = choose_bounds(&chosen, s->scene, s->bounds_phrase, sizeof s->bounds_phrase);
    if (phrase != s->bounds_phrase)
        snprintf(s->bounds_phrase, sizeof s->bounds_phrase, "%s", phrase);
    for (int k = 0; k < 6; k++)
        s->bounds[k] = chosen.view.bounds[k];
    s->effects = o->effects;
    s->has_effects = cli_effects_from_scene(&s->effects, s->scene) || o->view.effects;
    *out = s;
    return IACSG_OK;
}

iacsg_status view_scene_renderer(const view_scene *s, const iacsg_render_config *config, iacsg_renderer **out,
                                 iacsg_error *err) {
    return iacsg_renderer_create_scene(s->scene, config, out, err);
}

void view_scene_destroy(view_scene *s) {
    if (!s)
        return;
    iacsg_scene_destroy(s->scene);
    free(s);
}
