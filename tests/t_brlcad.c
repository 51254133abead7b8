/* tests/t_brlcad.c -- the BRL-CAD reader's semantics (implicits/brlcad.h): region and instance counts of the seven
 * sample databases against the table of tests/data/brlcad/README.md, and small databases written here whose
 * answer is known: GIFT precedence, v5 trees, push-down, matrices, invented regions, air, colours, parameters. */
#include "implicits/brlcad.h"
#include "implicits/scene.h"
#include "t_brlcad_model.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The README's per-scene table: top objects, instances, regions (air regions are left out: m35's 44). */
TEST(brlcad_counts_of_the_seven_scenes) {
    static const struct {
        const char *file, *objects[4];
        int nobjects, instances, regions, air;
    } rows[] = {
        {"boolean-ops.asc", {"all"}, 1, 3, 3, 0},
        {"boolean-ops.asc", {"aUbUc"}, 1, 3, 1, 0},
        {"boolean-ops.asc", {"a-b-c"}, 1, 3, 1, 0},
        {"boolean-ops.asc", {"a-b+c"}, 1, 3, 1, 0},
        {"boolean-ops.asc", {"c-a-b"}, 1, 3, 1, 0},
        {"operators.asc", {"operators"}, 1, 32, 20, 0},
        {"truck.asc", {"g4"}, 1, 178, 142, 0},
        {"m35.asc", {"all.g"}, 1, 1126, 937 - 44, 44},
        {"m35.asc", {"component"}, 1, 1123, 934 - 44, 44},
        {"tank_car.asc", {"tank_car"}, 1, 482, 79, 0},
        {"tank_car.asc", {"tank_car", "track"}, 2, 787, 180, 0},
        {"havoc.asc", {"havoc"}, 1, 2427, 308, 0},
        {"goliath.asc", {"Goliath.c"}, 1, 3310, 1411, 0},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        brlcad_model m = model_of_file(rows[k].file, rows[k].objects, rows[k].nobjects);
        CHECK(m.ninstances == rows[k].instances && m.scene->nitems == rows[k].regions && m.nair == rows[k].air,
              "%s %s: %d instances, %d regions, %d air; expected %d, %d, %d", rows[k].file, rows[k].objects[0],
              m.ninstances, m.scene->nitems, m.nair, rows[k].instances, rows[k].regions, rows[k].air);
        for (int r = 0; r < m.scene->nitems; r++)
            CHECK(m.scene->items[r].kind == SCENE_REGION && m.scene->items[r].name, "%s: item %d", rows[k].file, r);
        brlcad_model_free(&m);
    }
}

/* The value of region r's tree where the solids in `inside` (a bit per solid) are inside. */
static int region_holds(const brlcad_model *m, int r, unsigned inside) {
    signed char sign[32];
    for (int k = 0; k < m->scene->nsolids && k < 32; k++)
        sign[k] = inside >> k & 1 ? -1 : 1;
    return scene_tree_eval(m->scene, m->scene->items[r].tree, sign);
}

/* Region r's truth table over its (at most 5) solids against an expected function of the bits. */
static void check_truth(const brlcad_model *m, int r, int (*expected)(unsigned), const char *what) {
    CHECK(m->scene->nsolids <= 5, "%s: %d solids", what, m->scene->nsolids);
    for (unsigned in = 0; in < 1u << m->scene->nsolids; in++)
        CHECK(region_holds(m, r, in) == expected(in), "%s: region %d at inside-set %#x: %d", what, r, in,
              region_holds(m, r, in));
}

/* Solid indices follow the order in which solids are first met: a b c d below. */
static int gift_expected(unsigned in) { /* a - b u c + d = (a - b) u (c + d) */
    int a = in & 1, b = in >> 1 & 1, c = in >> 2 & 1, d = in >> 3 & 1;
    return (a && !b) || (c && d);
}

#define IDENTITY " 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"
#define V4_SPHERE(name, x) "S 19 " name " 1 " x " 0 0 1 0 0 0 1 0 0 0 1 0 0 0 0 0 0 0 0 0 0 0 0\n"

TEST(brlcad_v4_gift_precedence) {
    const char *db = "I 1 v4\ntitle\n" V4_SPHERE("a", "0") V4_SPHERE("b", "1") V4_SPHERE("c", "2") V4_SPHERE("d", "3")
        "C Y r 7 0 4 0 0 0 0 0 0 0\n"
        "M u a" IDENTITY "\nM - b" IDENTITY "\nM u c" IDENTITY "\nM + d" IDENTITY "\n";
    brlcad_model m = model_of(db, NULL, 0);
    CHECK(m.scene->nitems == 1 && m.ninstances == 4 && m.region_ids[0] == 7, "%d regions, %d solids, id %d",
          m.scene->nitems, m.ninstances, m.region_ids[0]);
    CHECK(strcmp(m.scene->items[0].name, "/r") == 0, "name %s", m.scene->items[0].name);
    check_truth(&m, 0, gift_expected, "u a - b u c + d");
    brlcad_model_free(&m);
}

static int boolean_ops_expected(unsigned in) { /* a-b+c: (a - b) + c over solids a b c */
    return (in & 1) && !(in >> 1 & 1) && (in >> 2 & 1);
}

TEST(brlcad_boolean_ops_trees) {
    const char *objects[] = {"a-b+c"};
    brlcad_model m = model_of_file("boolean-ops.asc", objects, 1);
    CHECK(m.scene->nitems == 1 && m.region_ids[0] == 1002, "%d regions, id %d", m.scene->nitems, m.region_ids[0]);
    check_truth(&m, 0, boolean_ops_expected, "a-b+c");
    /* its colour: no override on the combination, so the colour table's 1002 entry, 0 0 255 */
    const scene_material *mat = &m.scene->materials[m.scene->items[0].material];
    float blue = (255 + 0.5f) / 255;
    CHECK(mat->rgb[0] < 1e-4f && mat->rgb[1] < 1e-4f && fabsf(mat->rgb[2] - blue * blue) < 1e-6f,
          "colour %g %g %g", mat->rgb[0], mat->rgb[1], mat->rgb[2]);
    brlcad_model_free(&m);
}

#define V5_SPHERE(name, x) "put {" name "} ell V {" x " 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
#define V5_REGION(name, solid, id) "put {" name "} comb region yes tree {l " solid "}\nattr set {" name "} " \
    "{region_id} {" id "}\n"

/* solids in the order first met: s1 (bit 0), s3 (bit 1, in the first region), s2 (bit 2) */
static int push_first(unsigned in) { return (in & 1) && !(in >> 1 & 1); }       /* s1 - s3 */
static int push_second(unsigned in) { return (in >> 2 & 1) && !(in >> 1 & 1); } /* s2 - s3 */

/* (r1 u r2) - r3 above region level: two regions, r1 - r3 and r2 - r3, named and numbered by r1 and r2. */
TEST(brlcad_v5_push_down) {
    const char *db = V5_SPHERE("s1", "0") V5_SPHERE("s2", "1") V5_SPHERE("s3", "2") V5_REGION("r1", "s1", "1")
        V5_REGION("r2", "s2", "2") V5_REGION("r3", "s3", "3")
        "put {top} comb region no tree {- {u {l r1} {l r2}} {l r3}}\n";
    brlcad_model m = model_of(db, NULL, 0);
    CHECK(m.scene->nitems == 2 && m.ninstances == 3, "%d regions, %d solids", m.scene->nitems, m.ninstances);
    CHECK(strcmp(m.scene->items[0].name, "/top/r1") == 0 && strcmp(m.scene->items[1].name, "/top/r2") == 0,
          "names %s %s", m.scene->items[0].name, m.scene->items[1].name);
    CHECK(m.region_ids[0] == 1 && m.region_ids[1] == 2, "ids %d %d", m.region_ids[0], m.region_ids[1]);
    check_truth(&m, 0, push_first, "r1 - r3");
    check_truth(&m, 1, push_second, "r2 - r3");
    brlcad_model_free(&m);
}

static int intersect_first(unsigned in) { return (in & 1) && (in >> 1 & 1); }    /* s1 + s2 */
static int intersect_second(unsigned in) { return (in & 1) && (in >> 2 & 1); }   /* s1 + s3 */
static int subtract_both(unsigned in) { return (in & 1) && !(in >> 1 & 1) && !(in >> 2 & 1); }

/* C + (A u B) -> (C + A) u (C + B): two regions named by C; C - (A u B) -> (C - A) - B: one. */
TEST(brlcad_v5_push_down_right) {
    const char *db = V5_SPHERE("s1", "0") V5_SPHERE("s2", "1") V5_SPHERE("s3", "2") V5_REGION("r1", "s1", "1")
        V5_REGION("r2", "s2", "2") V5_REGION("r3", "s3", "3")
        "put {i} comb region no tree {n {l r1} {u {l r2} {l r3}}}\n"
        "put {d} comb region no tree {- {l r1} {u {l r2} {l r3}}}\n";
    const char *i[] = {"i"}, *d[] = {"d"};
    brlcad_model m = model_of(db, i, 1);
    CHECK(m.scene->nitems == 2, "%d regions", m.scene->nitems);
    CHECK(strcmp(m.scene->items[0].name, "/i/r1") == 0 && strcmp(m.scene->items[1].name, "/i/r1") == 0, "names");
    check_truth(&m, 0, intersect_first, "r1 + r2");
    check_truth(&m, 1, intersect_second, "r1 + r3");
    brlcad_model_free(&m);
    m = model_of(db, d, 1);
    CHECK(m.scene->nitems == 1, "%d regions", m.scene->nitems);
    check_truth(&m, 0, subtract_both, "r1 - r2 - r3");
    brlcad_model_free(&m);
}

static int xor_expected(unsigned in) { return (in & 1) != (in >> 1 & 1); }

TEST(brlcad_v5_xor_and_bare_solids) {
    const char *db = V5_SPHERE("s1", "0") V5_SPHERE("s2", "1") V5_SPHERE("s3", "5")
        "put {x} comb region yes tree {^ {l s1} {l s2}}\n"
        "put {g} comb region no tree {u {l x} {l s3 {1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1}}}\n";
    brlcad_model m = model_of(db, NULL, 0);
    CHECK(m.scene->nitems == 2 && m.ninstances == 3, "%d regions, %d solids", m.scene->nitems, m.ninstances);
    check_truth(&m, 0, xor_expected, "s1 ^ s2");
    /* s3, under no region, gets a region of its own, id 0, and its member matrix */
    CHECK(strcmp(m.scene->items[1].name, "/g/s3") == 0 && m.region_ids[1] == 0, "invented region %s id %d",
          m.scene->items[1].name, m.region_ids[1]);
    CHECK(m.scene->solids[2].prim->mat[3] == 10, "s3's matrix: translation %g", m.scene->solids[2].prim->mat[3]);
    brlcad_model_free(&m);
}

/* Matrices compose from the top down (P M), and a solid is one instance per distinct matrix. */
TEST(brlcad_matrices_and_instances) {
    const char *db = V5_SPHERE("s", "0")
        "put {r} comb region yes tree {u {l s {2 0 0 1 0 2 0 0 0 0 2 0 0 0 0 1}} {l s {2 0 0 1 0 2 0 0 0 0 2 0 0 0 0 "
        "1.0000000001}}}\n"
        "put {a} comb region no tree {l r {1 0 0 0 0 1 0 5 0 0 1 0 0 0 0 1}}\n"
        "put {b} comb region no tree {l a {0 -1 0 0 1 0 0 0 0 0 1 7 0 0 0 1}}\n";
    brlcad_model m = model_of(db, NULL, 0);
    /* the two members of r are one instance within rt's tolerance */
    CHECK(m.scene->nitems == 1 && m.ninstances == 1, "%d regions, %d solids", m.scene->nitems, m.ninstances);
    /* B A R: rotate (x, y) -> (-y, x) after translating y by 5, after scaling by 2 and moving x by 1 */
    static const double expected[16] = {0, -2, 0, -5, 2, 0, 0, 1, 0, 0, 2, 7, 0, 0, 0, 1};
    for (int k = 0; k < 16; k++)
        CHECK(m.scene->solids[0].prim->mat[k] == expected[k], "mat[%d] = %g, expected %g", k,
              m.scene->solids[0].prim->mat[k], expected[k]);
    CHECK(strcmp(m.scene->items[0].name, "/b/a/r") == 0, "name %s", m.scene->items[0].name);
    brlcad_model_free(&m);
}

/* Air regions are left out; an empty combination is nothing; the top objects are those nobody references. */
TEST(brlcad_air_and_tops) {
    const char *text = V5_SPHERE("s1", "0") V5_SPHERE("s2", "1") V5_REGION("r1", "s1", "1")
        "put {air} comb region yes tree {l s2}\nattr set {air} {region_id} {2} {aircode} {4}\n"
        "put {empty} comb region no tree {}\n"
        "put {top} comb region no tree {u {- {l r1} {l air}} {l empty}}\n";
    brlcad_db *db = NULL;
    iacsg_error err = {0};
    CHECK(brlcad_db_read(text, strlen(text), &db, &err) == IACSG_OK, "%s", err.message);
    CHECK(brlcad_db_top_count(db) == 1 && strcmp(brlcad_db_top_name(db, 0), "top") == 0, "tops: %d",
          brlcad_db_top_count(db));
    brlcad_db_destroy(db);
    brlcad_model m = model_of(text, NULL, 0);
    CHECK(m.scene->nitems == 1 && m.ninstances == 1 && m.nair == 1, "%d regions, %d solids, %d air",
          m.scene->nitems, m.ninstances, m.nair);
    brlcad_model_free(&m);
}

/* Colours: a combination's colour applies from the top down until one that does not inherit; below region
 * level none counts; with none, the colour table's entry for the region id; with neither, the palette. */
TEST(brlcad_colours) {
    const char *db = V5_SPHERE("s1", "0") V5_SPHERE("s2", "1") V5_SPHERE("s3", "2")
        "put {r1} comb region yes tree {l s1}\nattr set {r1} {region_id} {1} {rgb} {0/255/0}\n"
        "put {r2} comb region yes tree {l s2}\nattr set {r2} {region_id} {2}\n"
        "put {r3} comb region yes tree {l s3}\nattr set {r3} {region_id} {3} {color} {10/20/30}\n"
        "put {g1} comb region no tree {u {l r1} {l r2}}\nattr set {g1} {rgb} {255/0/0} {inherit} {1}\n"
        "put {top} comb region no tree {u {l g1} {l r3}}\n"
        "color 3 3 1 2 3\ncolor 2 2 0 0 255\n";
    brlcad_model m = model_of(db, NULL, 0);
    CHECK(m.scene->nitems == 3, "%d regions", m.scene->nitems);
    /* g1 inherits: red wins over r1's green and r2's table entry; r3 has its own colour over the table */
    static const float expected[3][3] = {{255, 0, 0}, {255, 0, 0}, {10, 20, 30}};
    for (int r = 0; r < 3; r++) {
        const float *rgb = m.scene->materials[m.scene->items[r].material].rgb;
        for (int k = 0; k < 3; k++) {
            float v = expected[r][k] / 255;
            CHECK(fabsf(rgb[k] - v * v) < 1e-6f, "region %d component %d: %g, expected %g", r, k, rgb[k], v * v);
        }
    }
    brlcad_model_free(&m);
}

/* v4 records: arb8's vectors relative to V become vertices; tor's radii are its vectors' lengths. */
TEST(brlcad_v4_parameters) {
    const char *db = "I 1 v4\nt\n"
                     "S 20 box 1 1 2 3 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\n"
                     "S 16 ring 2 0 0 0 0 0 0.5 4 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n"
                     "S 24 floor 3 0 0 1 -2 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n"
                     "C N g 0 0 3 0 0 0 0 0 0 0\nM u box" IDENTITY "\nM u ring" IDENTITY "\nM u floor" IDENTITY "\n";
    brlcad_model m = model_of(db, NULL, 0);
    CHECK(m.ninstances == 3 && m.scene->nitems == 3, "%d solids, %d regions", m.ninstances, m.scene->nitems);
    const scene_prim *box = m.scene->solids[0].prim, *ring = m.scene->solids[1].prim, *floor = m.scene->solids[2].prim;
    CHECK(box->type == SCENE_PRIM_ARB8 && box->nparams == 24, "box type %d", box->type);
    static const double vertices[24] = {1, 2, 3, 2, 2, 3, 2, 3, 3, 1, 3, 3, 1, 2, 4, 2, 2, 4, 2, 3, 4, 1, 3, 4};
    for (int k = 0; k < 24; k++)
        CHECK(box->params[k] == vertices[k], "arb8 parameter %d: %g, expected %g", k, box->params[k], vertices[k]);
    CHECK(ring->type == SCENE_PRIM_TOR && ring->params[6] == 4 && ring->params[7] == 0.5, "tor radii %g %g",
          ring->params[6], ring->params[7]);
    CHECK(floor->type == SCENE_PRIM_HALF && floor->params[2] == 1 && floor->params[3] == -2, "half %g %g",
          floor->params[2], floor->params[3]);
    brlcad_model_free(&m);
}

/* v5 primitives: pipe points in scene.h's order (x y z od id bend), ehy's A made a unit vector. */
TEST(brlcad_v5_parameters) {
    const char *db = "put {p} pipe V0 {0 0 0} O0 4 I0 1 R0 6 V1 {0 0 10} I1 2 O1 5 R1 7\n"
                     "put {h} ehy V {0 0 0} H {0 0 3} A {0 2 0} r_1 2 r_2 1 c 0.5\n";
    brlcad_model m = model_of(db, NULL, 0);
    CHECK(m.ninstances == 2, "%d solids", m.ninstances);
    const scene_prim *p = m.scene->solids[0].prim, *h = m.scene->solids[1].prim;
    static const double pipe[12] = {0, 0, 0, 4, 1, 6, 0, 0, 10, 5, 2, 7};
    CHECK(p->type == SCENE_PRIM_PIPE && p->nparams == 12, "pipe %d %d", p->type, p->nparams);
    for (int k = 0; k < 12; k++)
        CHECK(p->params[k] == pipe[k], "pipe parameter %d: %g, expected %g", k, p->params[k], pipe[k]);
    CHECK(h->type == SCENE_PRIM_EHY && h->params[7] == 1 && h->params[11] == 0.5, "ehy A_y %g c %g", h->params[7],
          h->params[11]);
    brlcad_model_free(&m);
}
