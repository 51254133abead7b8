/* examples/embed.c -- using iacsg as a library: compile scene files, render each, and lay the images out as a
 * contact sheet. `make gallery` runs it on the scenes in examples/ to make docs/gallery.png.
 *
 *   usage: embed OUT.png CELL COLUMNS SCENE.csg...
 *
 * Each scene is rendered CELL x CELL pixels from the default view of the command line (azimuth 35, elevation
 * 25, the whole bounds in view), at t = 1/2 if it depends on time. A scene of one expression is rendered by
 * the first-root path, one of regions and surfaces by the segment path (iacsg_renderer_create_scene chooses).
 * The library never prints: every call returns a status and fills an iacsg_error, and this program decides
 * what to say. */
#include <iacsg/iacsg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = size >= 0 ? malloc((size_t)size + 1) : NULL;
    if (text && fread(text, 1, (size_t)size, f) != (size_t)size) {
        free(text);
        text = NULL;
    }
    if (text)
        text[size] = '\0';
    fclose(f);
    return text;
}

/* Renders one scene into a cell of the sheet (rows of `sheet_width` RGB pixels). */
static iacsg_status render_cell(const char *path, int cell, float *sheet, int sheet_width, int x0, int y0,
                                iacsg_error *err) {
    char *text = read_file(path);
    if (!text)
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: cannot read", path);
    iacsg_scene *s = NULL;
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_scene_parse(text, path, &s, err);
    free(text);
    iacsg_render_config config = {0}; /* device 0, float, rigorous */
    if (st == IACSG_OK)
        st = iacsg_renderer_create_scene(s, &config, &r, err);
    if (st == IACSG_OK) {
        iacsg_view view = {.width = cell, .height = cell, .eps = 0x1p-16, .camera = {.up = {0, 0, 1}, .fov = 40}};
        view.time[0] = view.time[1] = iacsg_scene_uses_time(s) ? 0.5 : 0;
        if (!iacsg_scene_bounds(s, view.time, view.bounds))
            memcpy(view.bounds, (double[6]){-2, -2, -2, 2, 2, 2}, sizeof view.bounds);
        for (int k = 0; k < 3; k++)
            view.camera.at[k] = 0.5 * (view.bounds[k] + view.bounds[k + 3]);
        iacsg_camera_fit_azel(&view.camera, view.bounds, 35, 25);
        iacsg_frame frame;
        st = iacsg_render(r, &view, &frame, err);
        if (st == IACSG_OK) {
            for (int j = 0; j < cell; j++)
                memcpy(sheet + 3 * ((size_t)(y0 + j) * sheet_width + x0), frame.rgb + 3 * (size_t)j * cell,
                       3 * (size_t)cell * sizeof(float));
            iacsg_frame_free(&frame);
        }
    }
    iacsg_renderer_destroy(r);
    iacsg_scene_destroy(s);
    return st;
}

int main(int argc, char **argv) {
    if (argc < 5) {
        fprintf(stderr, "usage: embed OUT.png CELL COLUMNS SCENE...\n");
        return 2;
    }
    int cell = atoi(argv[2]), columns = atoi(argv[3]), count = argc - 4;
    if (cell < 8 || cell > 4096 || columns < 1) {
        fprintf(stderr, "embed: CELL must be 8..4096 and COLUMNS at least 1\n");
        return 2;
    }
    if (columns > count)
        columns = count;
    int rows = (count + columns - 1) / columns, width = columns * cell, height = rows * cell;
    size_t floats = (size_t)width * height * 3;
    float *sheet = malloc(floats * sizeof(float));
    if (!sheet) {
        fprintf(stderr, "embed: out of memory\n");
        return 1;
    }
    for (size_t k = 0; k < floats; k++)
        sheet[k] = 0.37f; /* empty cells: the renders' background at its darkest, display-encoded */
    iacsg_error err = {0};
    iacsg_status st = IACSG_OK;
    for (int k = 0; k < count && st == IACSG_OK; k++) {
        st = render_cell(argv[4 + k], cell, sheet, width, (k % columns) * cell, (k / columns) * cell, &err);
        if (st == IACSG_OK)
            printf("rendered %s\n", argv[4 + k]);
    }
    if (st == IACSG_OK)
        st = iacsg_image_write(argv[1], width, height, 3, sheet, 0, &err);
    free(sheet);
    if (st != IACSG_OK) {
        fprintf(stderr, "embed: %s\n", err.message);
        return 1;
    }
    printf("wrote %s\n", argv[1]);
    return 0;
}
