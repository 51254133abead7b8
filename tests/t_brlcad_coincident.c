/* tests/t_brlcad_coincident.c -- BRL-CAD's distance tolerance at coincident faces (kernels/weave.h's zones): a
 * region A - B whose two solids start on the same plane has no volume there, and the region C under that plane
 * must be shown in every pixel, as rt shows it (truck's r150 over r136); where B starts a little more than the
 * tolerance above A's face, A - B is a real slab along each ray and must be shown in every pixel. Both in float and
 * in double: in float the zone is wider by the rounding of the coordinates (README, the segment path). The
 * boxes are placed as truck's bed is, metres from the origin, where float's rounding is coarse; A - B is declared
 * first, so that an unresolved sliver wins its pixels. Then truck's bed itself. */
#include "implicits/brlcad.h"
#include "implicits/scene.h"
#include "render.h"
#include "t_brlcad_model.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SIZE 24 /* pixels a side */

/* An axis-aligned box as a v5 arb8. */
static void put_box(char *out, size_t cap, const char *name, const double lo[3], const double hi[3]) {
    size_t n = (size_t)snprintf(out, cap, "put {%s} arb8", name);
    for (int v = 0; v < 8; v++) {
        int top = v >= 4, x = v % 4 == 1 || v % 4 == 2, y = v % 4 >= 2;
        n += (size_t)snprintf(out + n, cap - n, " V%d {%.17g %.17g %.17g}", v + 1, x ? hi[0] : lo[0],
                              y ? hi[1] : lo[1], top ? hi[2] : lo[2]);
    }
    snprintf(out + n, cap - n, "\n");
}

/* Walls A - B (B cut from A's inside, through its top, from `lift` mm above A's bottom) over a tray C whose top is
 * A's bottom: truck's r150 and r136, in that order. */
static char *bed_database(double lift) {
    static const double a_lo[3] = {0, -1100, 1384.3}, a_hi[3] = {6000, 1100, 1816.1};
    static const double c_lo[3] = {0, -1200, 1295.4}, c_hi[3] = {6000, 1200, 1384.3};
    double b_lo[3] = {2.5, -1097.5, 1384.3 + lift}, b_hi[3] = {5997.5, 1097.5, 1828.8};
    size_t cap = 4096;
    char *text = malloc(cap), box[1024];
    CHECK(text, "out of memory");
    text[0] = '\0';
    put_box(box, sizeof box, "a", a_lo, a_hi);
    strcat(text, box);
    put_box(box, sizeof box, "b", b_lo, b_hi);
    strcat(text, box);
    put_box(box, sizeof box, "c", c_lo, c_hi);
    strcat(text, box);
    strcat(text, "put {walls} comb region yes tree {- {l a} {l b}}\n"
                 "put {tray} comb region yes tree {l c}\n"
                 "put {bed} comb region no tree {u {l walls} {l tray}}\n");
    return text;
}

static int item_named(const brlcad_model *m, const char *name) {
    for (int k = 0; k < m->scene->nitems; k++)
        if (strcmp(m->scene->items[k].name, name) == 0)
            return k;
    CHECK(0, "no region %s", name);
    return -1;
}

/* How many pixels of an orthographic SIZE x SIZE view of the model, `height` mm high, centred on `at` and seen
 * from rt's -a 35 -e 25, show item `item` (ids), in float or double. */
static int pixels_showing(const brlcad_model *m, const double at[3], double height, int fp64, int item) {
    iacsg_view view = {0};
    CHECK(brlcad_scene_bounds(m->scene, view.bounds), "no bounded solid");
    double deg = acos(-1) / 180, az = 35 * deg, el = 25 * deg, far = 20000;
    double dir[3] = {cos(el) * cos(az), cos(el) * sin(az), sin(el)};
    for (int k = 0; k < 3; k++) {
        view.camera.at[k] = at[k];
        view.camera.eye[k] = at[k] + far * dir[k];
    }
    view.camera.up[2] = 1;
    view.camera.ortho_height = height;
    view.width = view.height = SIZE;
    view.eps = 0x1p-16;
    view.no_normals = 1;
    iacsg_render_config config = {0};
    config.fp64 = fp64;
    iacsg_renderer *r = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_renderer_create_scene(m->scene, &config, &r, &err) == IACSG_OK, "renderer: %s", err.message);
    iacsg_frame fr = {0};
    CHECK(iacsg_render(r, &view, &fr, &err) == IACSG_OK, "render: %s", err.message);
    int n = 0;
    for (int p = 0; p < SIZE * SIZE; p++)
        n += fr.ids[p] == item;
    iacsg_frame_free(&fr);
    iacsg_renderer_destroy(r);
    return n;
}

static const double bed_centre[3] = {3000, 0, 1384.3};

TEST(brlcad_coincident_faces_show_what_lies_behind) {
    char *text = bed_database(0);
    brlcad_model m = model_of(text, (const char *const[]){"bed"}, 1);
    for (int fp64 = 0; fp64 < 2; fp64++) {
        int tray = pixels_showing(&m, bed_centre, 400, fp64, item_named(&m, "/bed/tray"));
        CHECK(tray == SIZE * SIZE, "%s: the tray in %d of %d pixels (the walls' sliver of no volume in the others)",
              fp64 ? "double" : "float", tray, SIZE * SIZE);
    }
    brlcad_model_free(&m);
    free(text);
}

/* B's face above A's by a little more than the tolerance, vertically (the ray, at 25 degrees, crosses 2.4 times
 * that): 0.0006 mm in double; in float more than the zone's rounding there (about 0.02 mm along the ray). */
TEST(brlcad_thin_slab_above_the_tolerance_is_shown) {
    for (int fp64 = 0; fp64 < 2; fp64++) {
        char *text = bed_database(fp64 ? 1.2 * BRLCAD_DIST_TOL : 0.05);
        brlcad_model m = model_of(text, (const char *const[]){"bed"}, 1);
        int walls = pixels_showing(&m, bed_centre, 400, fp64, item_named(&m, "/bed/walls"));
        CHECK(walls == SIZE * SIZE, "%s: the walls' slab in %d of %d pixels", fp64 ? "double" : "float", walls,
              SIZE * SIZE);
        brlcad_model_free(&m);
        free(text);
    }
}

/* truck's bed, 400 mm of its middle seen as rt sees it: r136's top plate, where r150's walls (s150 - s151, a common
 * bottom on that plate) have nothing. */
TEST(brlcad_truck_bed_is_whole) {
    brlcad_model m = model_of_file("truck.asc", (const char *const[]){"g4"}, 1);
    static const double centre[3] = {3100, 0, 1384.3};
    int plate = pixels_showing(&m, centre, 400, 0, item_named(&m, "/g4/r136"));
    CHECK(plate == SIZE * SIZE, "r136 in %d of %d pixels", plate, SIZE * SIZE);
    brlcad_model_free(&m);
}
