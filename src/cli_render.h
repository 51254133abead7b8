/* src/cli_render.h -- the render command's options and the steps from them to a view, shared by `iacsg EXPR`
 * (src/cli_render.c, which defines them) and `iacsg view` (src/cli_view.c), so that both read the same
 * options the same way. */
#ifndef IACSG_CLI_RENDER_H
#define IACSG_CLI_RENDER_H
#include "iacsg.h"
#include <stddef.h>

#define RENDER_OBJECTS_MAX 256

typedef struct {
    const char *input, *output, *depth_file, *normals_file, *ids_file, *time_text;
    iacsg_view view;
    iacsg_render_config config;
    iacsg_effects effects; /* src/cli_effects.c; view.effects points here when an effects option is given */
    int have_bounds, have_eye, have_at, have_azel, have_time, have_device, frames, resume;
    double az, el;
    /* a BRL-CAD model (input *.asc): the objects named after it, and whether -fov asks for perspective */
    const char *objects[RENDER_OBJECTS_MAX];
    int nobjects, have_fov;
} render_options;

/* Option values, for every option parser (src/cli_render.c, src/cli_effects.c): `count` comma-separated finite
 * numbers, the whole text (0 otherwise); an integer in [lo, hi], the whole text (0 otherwise); and the one line
 * that says an option's value is not what it expects. */
int cli_parse_numbers(const char *text, double *out, int count);
int cli_parse_int(const char *text, long lo, long hi, int *out);
void cli_print_bad_value(const char *option, const char *value, const char *expected);

/* Fills *o from the command line (argv[0] is the command's name); returns 0, or the exit status after
 * printing the problem. */
int parse_options(int argc, char **argv, render_options *o);

/* The text of a scene file when `input` names a file (*name = input), else the input itself as an expression
 * (*name = "<expr>"). The result is malloc'ed; NULL (after a message) when the file cannot be read. */
char *read_input(const char *input, const char **name);

/* Compiles what read_input gave: a scene file may declare regions and surfaces; an expression on the command
 * line (name "<expr>") is one solid, and a region in it is refused where it stands (iacsg_expr_parse's
 * message). */
iacsg_status parse_input(const char *text, const char *name, iacsg_scene **out, iacsg_error *err);

/* The scene of the options' input: a BRL-CAD model's given objects (src/cli_brlcad.c), else parse_input's. */
iacsg_status load_input(const render_options *o, const char *text, const char *name, iacsg_scene **out,
                        iacsg_error *err);

/* Sets o->view.bounds (given, found by the compiler for the times rendered, or the default) and returns a
 * phrase saying which and what was proven (in `phrase`, or a constant). A scene with items: the union of its
 * solids' proven boxes. */
const char *choose_bounds(render_options *o, const iacsg_scene *s, char *phrase, size_t size);

/* -at defaults to the centre of the bounds; without -eye, -az/-el place the eye to see all of the bounds. A
 * BRL-CAD model is seen as rt sees it: orthographic, as wide as the bounds' diagonal, unless -ortho or -fov. */
void place_camera(render_options *o);

/* One line on stderr: "iacsg: NAME:LINE:COL: message", or "iacsg: message" without a place. */
void print_error(const iacsg_error *err, const char *name);

#endif
