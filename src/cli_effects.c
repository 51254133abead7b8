/* src/cli_effects.c -- see cli_effects.h. */
#include "cli_effects.h"
#include "cli_render.h"
#include "implicits/scene.h"
#include <stdio.h>
#include <string.h>

/* The reflection rays a path may take unless -bounces says otherwise (a material's reflect needs some). */
#define CLI_DEFAULT_BOUNCES 2

void cli_effects_init(iacsg_effects *e) {
    memset(e, 0, sizeof *e);
    e->bounces = CLI_DEFAULT_BOUNCES;
    e->aa = 1;
}

static int bad(const char *option, const char *value, const char *expected) {
    cli_print_bad_value(option, value, expected);
    return -1;
}

static int read_light(const char *a, const char *v, iacsg_effects *e) {
    if (e->nlights == IACSG_MAX_LIGHTS) {
        fprintf(stderr, "iacsg: %s %s: at most %d lights\n", a, v, IACSG_MAX_LIGHTS);
        return -1;
    }
    iacsg_light *L = &e->lights[e->nlights];
    const char *comma = strchr(v, ',');
    size_t kind = comma ? (size_t)(comma - v) : strlen(v);
    if (kind == 5 && strncmp(v, "point", 5) == 0)
        L->kind = IACSG_LIGHT_POINT;
    else if (kind == 3 && strncmp(v, "dir", 3) == 0)
        L->kind = IACSG_LIGHT_DIR;
    else {
        fprintf(stderr, "iacsg: %s %s: unknown light kind '%.*s' (point or dir)\n", a, v, (int)kind, v);
        return -1;
    }
    double num[4];
    if (!comma || !cli_parse_numbers(comma + 1, num, 4))
        return bad(a, v, "point,X,Y,Z,I or dir,X,Y,Z,I (I the intensity)");
    if (!(num[3] >= 0))
        return bad(a, v, "an intensity I >= 0 (the last number)");
    if (L->kind == IACSG_LIGHT_DIR && num[0] == 0 && num[1] == 0 && num[2] == 0)
        return bad(a, v, "a direction X,Y,Z that is not 0,0,0");
    memcpy(L->xyz, num, sizeof L->xyz);
    L->intensity = num[3];
    e->nlights++;
    return 1;
}

static int read_background(const char *a, const char *v, iacsg_effects *e) {
    double c[6];
    int n = cli_parse_numbers(v, c, 3) ? 3 : cli_parse_numbers(v, c, 6) ? 6 : 0;
    for (int k = 0; k < n; k++)
        if (!(c[k] >= 0 && c[k] <= 1))
            n = 0;
    if (n == 0)
        return bad(a, v, "R,G,B or R,G,B,R,G,B (top, bottom) in [0, 1]");
    for (int k = 0; k < 3; k++) {
        e->background_top[k] = (float)c[k];
        e->background_bottom[k] = (float)c[n == 6 ? k + 3 : k];
    }
    e->background = 1;
    return 1;
}

int cli_effects_option(int argc, char **argv, int *k, iacsg_effects *e, int *given) {
    const char *a = argv[*k];
    if (strcmp(a, "-shadows") == 0) {
        e->shadows = *given = 1;
        return 1;
    }
    static const char *const options[] = {"-shade", "-background", "-light", "-bounces", "-reflect", "-opacity", "-aa"};
    int which = -1;
    for (int o = 0; o < (int)(sizeof options / sizeof options[0]); o++)
        if (strcmp(a, options[o]) == 0)
            which = o;
    if (which < 0 || *k + 1 >= argc)
        return 0; /* not ours, or a missing value, which parse_options reports */
    const char *v = argv[++*k];
    double x;
    *given = 1;
    switch (which) {
    case 0: {
        static const char *const modes[] = {"lit", "gradient", "normals", "depth", "ids"};
        for (int m = 0; m < 5; m++)
            if (strcmp(v, modes[m]) == 0) {
                e->shade = (iacsg_shade)m;
                return 1;
            }
        return bad(a, v, "lit, gradient, normals, depth or ids");
    }
    case 1: return read_background(a, v, e);
    case 2: return read_light(a, v, e);
    case 3:
        return cli_parse_int(v, 0, IACSG_MAX_BOUNCES, &e->bounces) ? 1 : bad(a, v, "a count of bounces from 0 to 16");
    case 4:
    case 5:
        if (!cli_parse_numbers(v, &x, 1) || !(x >= 0 && x <= 1))
            return bad(a, v, "a number in [0, 1]");
        if (which == 4)
            e->reflect = x;
        else
            e->transparency = 1 - x;
        return 1;
    default: return cli_parse_int(v, 1, IACSG_MAX_AA, &e->aa) ? 1 : bad(a, v, "N from 1 to 16 (N x N rays a pixel)");
    }
}

int cli_effects_from_scene(iacsg_effects *e, const iacsg_scene *s) {
    if (e->nlights == 0)
        e->nlights = iacsg_scene_lights(s, e->lights);
    if (s->nlights > 0)
        return 1;
    for (int m = 0; m < s->nmaterials; m++)
        if (s->materials[m].reflect > 0 || s->materials[m].opacity < 1)
            return 1;
    return 0;
}
