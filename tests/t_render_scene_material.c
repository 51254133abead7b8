/* tests/t_render_scene_material.c -- the segment path shades each region with its material: with the default
 * highlight a sphere as a region looks as the single-expression path draws it, and a material's specular and
 * shininess change its highlight. */
#include "iacsg.h"
#include "test.h"
#include <math.h>
#include <stdlib.h>

#define SIZE 64

/* The colour image of `text` (an expression or a scene) seen from (3, -4, 2); the caller frees it. */
static float *render_rgb(const char *text) {
    iacsg_scene *s = NULL;
    iacsg_renderer *r = NULL;
    iacsg_error err = {0};
    iacsg_render_config config = {0};
    CHECK(iacsg_scene_parse(text, "<test>", &s, &err) == IACSG_OK, "%s", err.message);
    CHECK(iacsg_renderer_create_scene(s, &config, &r, &err) == IACSG_OK, "%s", err.message);
    iacsg_view v = {.width = SIZE, .height = SIZE, .eps = 1e-5, .bounds = {-1.5, -1.5, -1.5, 1.5, 1.5, 1.5},
                    .camera = {.eye = {3, -4, 2}, .up = {0, 0, 1}, .fov = 40}};
    iacsg_frame f = {0};
    CHECK(iacsg_render(r, &v, &f, &err) == IACSG_OK, "%s", err.message);
    float *rgb = f.rgb;
    f.rgb = NULL;
    iacsg_frame_free(&f);
    iacsg_renderer_destroy(r);
    iacsg_scene_destroy(s);
    return rgb;
}

/* The largest channel value of the image, and the mean absolute difference of two images. */
static float brightest(const float *a) {
    float m = 0;
    for (int k = 0; k < 3 * SIZE * SIZE; k++)
        m = fmaxf(m, a[k]);
    return m;
}
static double mean_difference(const float *a, const float *b) {
    double sum = 0;
    for (int k = 0; k < 3 * SIZE * SIZE; k++)
        sum += fabs((double)a[k] - b[k]);
    return sum / (3 * SIZE * SIZE);
}

TEST(render_scene_material_highlight) {
    /* kernels/shade.h's albedo, the default highlight */
    float *plain = render_rgb("sphere");
    float *region = render_rgb("material m = rgb(0.80, 0.52, 0.28)\nsolid b = sphere\nregion r = b : m\n");
    float *matte = render_rgb("material m = rgb(0.80, 0.52, 0.28) specular 0\nsolid b = sphere\nregion r = b : m\n");
    float *broad =
        render_rgb("material m = rgb(0.80, 0.52, 0.28) specular 1 shininess 4\nsolid b = sphere\nregion r = b : m\n");
    double same = mean_difference(plain, region), off = mean_difference(region, broad);
    test_note("mean differences: region against expression %.5f, broad highlight %.4f; brightest: default %.3f, "
              "matte %.3f",
              same, off, brightest(region), brightest(matte));
    CHECK(same < 1.0 / 255, "the default material differs from the expression's shading by %g on average", same);
    CHECK(brightest(matte) < brightest(region) - 0.05, "specular 0 leaves the highlight (%g against %g)",
          brightest(matte), brightest(region));
    CHECK(off > 0.01, "a broad, strong highlight changes little (%g)", off);
    free(plain);
    free(region);
    free(matte);
    free(broad);
}
