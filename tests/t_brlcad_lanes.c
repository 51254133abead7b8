/* tests/t_brlcad_lanes.c -- a packet's solids solved in SIMD lanes (kernels/segments_lanes.h: halves and arb8s;
 * segments_lanes_frame.h: ells, quadric tgcs, ehys) against the same solids solved ray by ray (the program built with
 * IACSG_SEGMENTS_LANES=0): ids, depth and colour bit for bit, orthographic views of truck's 125 arbs, of
 * operators' ells and ehys, and of random rotated boxes and quadrics cut from each other, from random directions and
 * along the axes (faces parallel to the rays: those solids go to the scalar code; rays along an axis: bvh_node_clip's
 * axes where d is 0). A wrong lane (another ray's origin or range start, a bound rounded the other way, a root's
 * branch taken wrongly) moves a depth by an ulp at least, or a claim. */
#include "implicits/brlcad.h"
#include "implicits/scene.h"
#include "render.h"
#include "t_brlcad_model.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SIZE 64  /* pixels a side */
#define VIEWS 6  /* the first three along the axes, the others random */
#define BOXES 12 /* in the random database */

static double uniform(test_rng_t *r, double lo, double hi) { return lo + (hi - lo) * test_rand_unit(r); }

/* v rotated about the unit axis k by angle (Rodrigues' formula) into out. */
static void rotate(const double k[3], double angle, const double v[3], double out[3]) {
    double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    double cross[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int c = 0; c < 3; c++)
        out[c] = v[c] * cos(angle) + cross[c] * sin(angle) + k[c] * kv * (1 - cos(angle));
}

/* A random rotation (unit axis k, angle) and a centre. */
static void random_placement(test_rng_t *r, double k[3], double *angle, double centre[3]) {
    double len = 0;
    *angle = uniform(r, 0, acos(-1));
    for (int c = 0; c < 3; c++) {
        centre[c] = uniform(r, -400, 400);
        k[c] = uniform(r, -1, 1);
        len += k[c] * k[c];
    }
    for (int c = 0; c < 3; c++)
        k[c] /= sqrt(len);
}

/* " NAME {x y z}": v rotated (k, angle), plus `at` where it is not 0, into text at *n. */
static void put_vector(char *text, size_t cap, size_t *n, const char *name, const double k[3], double angle,
                       const double v[3], const double *at) {
    double p[3];
    rotate(k, angle, v, p);
    for (int c = 0; at && c < 3; c++)
        p[c] += at[c];
    *n += (size_t)snprintf(text + *n, cap - *n, " %s {%.17g %.17g %.17g}", name, p[0], p[1], p[2]);
}

/* Regions r_k = s_k - s_{k+1} of `solids` solids and "all", their union, into text at *n. */
static void put_regions(char *text, size_t cap, size_t *n, int solids) {
    for (int b = 0; b < solids; b++)
        *n += (size_t)snprintf(text + *n, cap - *n, "put {r%d} comb region yes tree {- {l s%d} {l s%d}}\n", b, b,
                               (b + 1) % solids);
    char tree[1024]; /* ((r0 u r1) u r2) u ...: "{u " solids - 1 times, "{l r0}", then " {l rB}}" for each B > 0 */
    size_t t = 0;
    for (int b = 1; b < solids; b++)
        t += (size_t)snprintf(tree + t, sizeof tree - t, "{u ");
    t += (size_t)snprintf(tree + t, sizeof tree - t, "{l r0}");
    for (int b = 1; b < solids; b++)
        t += (size_t)snprintf(tree + t, sizeof tree - t, " {l r%d}}", b);
    CHECK(t < sizeof tree, "the union's tree overflows");
    *n += (size_t)snprintf(text + *n, cap - *n, "put {all} comb region no tree %s\n", tree);
    CHECK(*n < cap, "the database overflows");
}

/* BOXES boxes, each rotated about a random axis, as v5 arb8s; regions box_k - box_{k+1} and their union. */
static char *random_boxes(test_rng_t *r) {
    size_t cap = 64 * 1024, n = 0;
    char *text = malloc(cap);
    CHECK(text, "out of memory");
    for (int b = 0; b < BOXES; b++) {
        double centre[3], half[3], k[3], angle;
        random_placement(r, k, &angle, centre);
        for (int c = 0; c < 3; c++)
            half[c] = uniform(r, 20, 200);
        n += (size_t)snprintf(text + n, cap - n, "put {s%d} arb8", b);
        for (int v = 0; v < 8; v++) {
            int top = v >= 4, x = v % 4 == 1 || v % 4 == 2, y = v % 4 >= 2;
            double q[3] = {x ? half[0] : -half[0], y ? half[1] : -half[1], top ? half[2] : -half[2]};
            char name[16];
            snprintf(name, sizeof name, "V%d", v + 1);
            put_vector(text, cap, &n, name, k, angle, q, centre);
        }
        n += (size_t)snprintf(text + n, cap - n, "\n");
    }
    put_regions(text, cap, &n, BOXES);
    return text;
}

/* BOXES quadrics in turn an ell, a tgc whose alpha and beta agree (a truncated elliptic cone) and an ehy, each
 * rotated about a random axis; regions s_k - s_{k+1} and their union. */
static char *random_quadrics(test_rng_t *r) {
    size_t cap = 64 * 1024, n = 0;
    char *text = malloc(cap);
    CHECK(text, "out of memory");
    for (int b = 0; b < BOXES; b++) {
        double centre[3], k[3], angle, a = uniform(r, 40, 200), bl = uniform(r, 40, 200), h = uniform(r, 60, 300);
        random_placement(r, k, &angle, centre);
        double ea[3] = {a, 0, 0}, eb[3] = {0, bl, 0}, eh[3] = {0, 0, h}, base[3] = {0, 0, -h / 2}, v[3];
        rotate(k, angle, base, v);
        for (int c = 0; c < 3; c++)
            v[c] += centre[c];
        if (b % 3 == 0) {
            double ec[3] = {0, 0, uniform(r, 40, 200)};
            n += (size_t)snprintf(text + n, cap - n, "put {s%d} ell", b);
            put_vector(text, cap, &n, "V", k, angle, (double[3]){0, 0, 0}, centre);
            put_vector(text, cap, &n, "A", k, angle, ea, 0);
            put_vector(text, cap, &n, "B", k, angle, eb, 0);
            put_vector(text, cap, &n, "C", k, angle, ec, 0);
        } else if (b % 3 == 1) {
            double s = uniform(r, 0.2, 1.5), ec[3] = {s * a, 0, 0}, ed[3] = {0, s * bl, 0};
            n += (size_t)snprintf(text + n, cap - n, "put {s%d} tgc", b);
            put_vector(text, cap, &n, "V", k, angle, (double[3]){0, 0, 0}, v);
            put_vector(text, cap, &n, "H", k, angle, eh, 0);
            put_vector(text, cap, &n, "A", k, angle, ea, 0);
            put_vector(text, cap, &n, "B", k, angle, eb, 0);
            put_vector(text, cap, &n, "C", k, angle, ec, 0);
            put_vector(text, cap, &n, "D", k, angle, ed, 0);
        } else {
            double unit[3] = {1, 0, 0}, r2 = uniform(r, 30, a);
            n += (size_t)snprintf(text + n, cap - n, "put {s%d} ehy", b);
            put_vector(text, cap, &n, "V", k, angle, (double[3]){0, 0, 0}, v);
            put_vector(text, cap, &n, "H", k, angle, eh, 0);
            put_vector(text, cap, &n, "A", k, angle, unit, 0);
            n += (size_t)snprintf(text + n, cap - n, " r_1 %.17g r_2 %.17g c %.17g", a, r2, uniform(r, 5, 100));
        }
        n += (size_t)snprintf(text + n, cap - n, "\n");
    }
    put_regions(text, cap, &n, BOXES);
    return text;
}

/* Renders views[v] (azimuth, elevation in degrees) of the model into ids, depth and rgb (SIZE x SIZE each, rgb 3
 * floats a pixel), the program built with or without the lanes. Returns the pixels hit over all views. */
static int render_views(const brlcad_model *m, double views[VIEWS][2], int lanes, float *ids, float *depth,
                        float *rgb) {
    if (lanes)
        unsetenv("IACSG_SEGMENTS_LANES");
    else
        setenv("IACSG_SEGMENTS_LANES", "0", 1);
    iacsg_render_config config = {0};
    iacsg_renderer *r = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_renderer_create_scene(m->scene, &config, &r, &err) == IACSG_OK, "renderer: %s", err.message);
    unsetenv("IACSG_SEGMENTS_LANES");
    double bounds[6], at[3], radius = 0, deg = acos(-1) / 180;
    CHECK(brlcad_scene_bounds(m->scene, bounds), "no bounded solid");
    for (int c = 0; c < 3; c++) {
        at[c] = (bounds[c] + bounds[c + 3]) / 2;
        radius += (bounds[c + 3] - bounds[c]) * (bounds[c + 3] - bounds[c]) / 4;
    }
    radius = sqrt(radius);
    int hits = 0, pixels = SIZE * SIZE;
    for (int v = 0; v < VIEWS; v++) {
        iacsg_view view = {0};
        memcpy(view.bounds, bounds, sizeof bounds);
        double az = views[v][0] * deg, el = views[v][1] * deg;
        double dir[3] = {cos(el) * cos(az), cos(el) * sin(az), sin(el)};
        for (int c = 0; c < 3; c++) {
            view.camera.at[c] = at[c];
            view.camera.eye[c] = at[c] + 4 * radius * dir[c];
        }
        view.camera.up[fabs(dir[2]) > 0.9 ? 1 : 2] = 1;
        view.camera.ortho_height = 2 * radius;
        view.width = view.height = SIZE;
        view.eps = 0x1p-16;
        iacsg_frame fr = {0};
        CHECK(iacsg_render(r, &view, &fr, &err) == IACSG_OK, "render: %s", err.message);
        memcpy(ids + v * pixels, fr.ids, pixels * sizeof *ids);
        memcpy(depth + v * pixels, fr.depth, pixels * sizeof *depth);
        memcpy(rgb + 3 * v * pixels, fr.rgb, 3 * pixels * sizeof *rgb);
        for (int p = 0; p < pixels; p++)
            hits += fr.ids[p] >= 0;
        iacsg_frame_free(&fr);
    }
    iacsg_renderer_destroy(r);
    return hits;
}

/* The model's views with and without the lanes: the same bits in every output. */
static void check_same(const brlcad_model *m, double views[VIEWS][2], const char *what) {
    size_t pixels = (size_t)VIEWS * SIZE * SIZE;
    float *ids[2], *depth[2], *rgb[2];
    int hits[2];
    for (int lanes = 0; lanes < 2; lanes++) {
        ids[lanes] = malloc(pixels * sizeof(float));
        depth[lanes] = malloc(pixels * sizeof(float));
        rgb[lanes] = malloc(3 * pixels * sizeof(float));
        CHECK(ids[lanes] && depth[lanes] && rgb[lanes], "out of memory");
        hits[lanes] = render_views(m, views, lanes, ids[lanes], depth[lanes], rgb[lanes]);
    }
    long differ = 0;
    for (size_t p = 0; p < pixels; p++)
        differ += memcmp(&ids[0][p], &ids[1][p], sizeof(float)) != 0 ||
                  memcmp(&depth[0][p], &depth[1][p], sizeof(float)) != 0 ||
                  memcmp(&rgb[0][3 * p], &rgb[1][3 * p], 3 * sizeof(float)) != 0;
    test_note("%s: %d of %zu pixels hit, %ld differ between the lanes and the scalar solves", what, hits[1], pixels,
              differ);
    CHECK(hits[1] > (int)(pixels / 20), "%s: too few pixels hit (%d) for the comparison to say much", what, hits[1]);
    CHECK(differ == 0 && hits[0] == hits[1], "%s: %ld pixels differ with the lanes", what, differ);
    for (int lanes = 0; lanes < 2; lanes++) {
        free(ids[lanes]);
        free(depth[lanes]);
        free(rgb[lanes]);
    }
}

static void random_views(test_rng_t *r, double views[VIEWS][2]) {
    static const double axes[3][2] = {{0, 0}, {90, 0}, {0, 90}};
    for (int v = 0; v < VIEWS; v++) {
        views[v][0] = v < 3 ? axes[v][0] : uniform(r, 0, 360);
        views[v][1] = v < 3 ? axes[v][1] : uniform(r, -89, 89);
    }
}

/* A sample model's object, and a random model (make's text, every top object), from VIEWS random views. */
static void check_model_file(const char *file, const char *object) {
    brlcad_model m = model_of_file(file, (const char *const[]){object}, 1);
    double views[VIEWS][2];
    random_views(test_rng(), views);
    check_same(&m, views, file);
    brlcad_model_free(&m);
}
static void check_random_model(char *(*make)(test_rng_t *), const char *what) {
    test_rng_t *r = test_rng();
    char *text = make(r);
    brlcad_model m = model_of(text, (const char *const[]){"all"}, 1);
    double views[VIEWS][2];
    random_views(r, views);
    check_same(&m, views, what);
    brlcad_model_free(&m);
    free(text);
}

TEST(brlcad_lanes_truck_match_scalar) { check_model_file("truck.asc", "g4"); }

TEST(brlcad_lanes_rotated_boxes_match_scalar) { check_random_model(random_boxes, "rotated boxes"); }

TEST(brlcad_lanes_operators_match_scalar) { check_model_file("operators.asc", "operators"); }

TEST(brlcad_lanes_rotated_quadrics_match_scalar) { check_random_model(random_quadrics, "rotated quadrics"); }
