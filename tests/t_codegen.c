/* tests/t_codegen.c -- golden tests of the emitted OpenCL C: each tests/data/golden/NAME.cl is the exact output
 * of `iacsg compile` for one expression. A change to the emitter shows up here as a diff to review; run with
 * IACSG_GOLDEN_UPDATE=1 to rewrite the files after checking the new output by eye. */
#include "implicits/expr.h"
#include "implicits/scene.h"
#include "implicits/scene_emit.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const struct {
    const char *name, *text;
} goldens[] = {
    {"sphere", "sphere"},                                 /* x^2 -> sqr, r^2 folded to a point, ADD_R */
    {"torus_keywords", "torus(R = 1, r = 0.25)"},         /* keyword arguments, sqrt */
    {"shared_subexpressions", "min(sin(x) * y, sin(x) + 0.1)"}, /* sin(x) computed once; 0.1 as an interval */
    {"powers", "x^3 + y^0.5 + z^-2 + x*x + y^1.5"},     /* pown, sqrt, pown < 0, sqr from x*x, pow */
    {"csg_transform", "move(sphere(0.5), 1, 0, 0) | box \\ rotatez(cylinder(0.25), pi / 4)"},
    {"scene", "# a scene\nball = sphere(0.8)\nhole = cylinder(0.3)\nball \\ hole\n"},
    {"time", "sigmoid_blend(decocube, sphere)"},          /* uses t; exp */
};

TEST(codegen_golden) {
    int update = getenv("IACSG_GOLDEN_UPDATE") != NULL;
    for (size_t i = 0; i < sizeof goldens / sizeof goldens[0]; i++) {
        iacsg_expr *e;
        iacsg_error err = {0};
        char *src = NULL, path[1024];
        CHECK(iacsg_expr_parse(goldens[i].text, "<golden>", &e, &err) == IACSG_OK, "%s: %s", goldens[i].name,
              err.message);
        CHECK(iacsg_expr_emit_cl(e, "iacsg", &src, &err) == IACSG_OK, "%s: %s", goldens[i].name, err.message);
        iacsg_expr_destroy(e);
        snprintf(path, sizeof path, "%s/tests/data/golden/%s.cl", test_source_dir(), goldens[i].name);
        if (update) {
            FILE *f = fopen(path, "wb");
            CHECK(f && fputs(src, f) >= 0 && fclose(f) == 0, "cannot write %s", path);
        }
        char *want = test_read_file(path, NULL);
        CHECK(want != NULL, "missing %s (IACSG_GOLDEN_UPDATE=1 writes it)", path);
        int same = strcmp(want, src) == 0;
        if (!same)
            printf("--- expected %s\n%s--- got\n%s", path, want, src);
        free(want);
        free(src);
        CHECK(same, "%s: the emitted code differs from %s", goldens[i].name, path);
    }
    if (update)
        test_note("golden files rewritten");
}

TEST(codegen_rejects_bad_prefix) {
    iacsg_expr *e;
    char *src = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse("sphere", "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    static const char *const bad[] = {"", "1abc", "a b", "x); evil(", "a-b"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        CHECK(iacsg_expr_emit_cl(e, bad[i], &src, &err) == IACSG_ERR_ARG && src == NULL, "prefix '%s' accepted",
              bad[i]);
    }
    CHECK(iacsg_expr_emit_cl(e, "my_prefix2", &src, &err) == IACSG_OK, "%s", err.message);
    CHECK(strstr(src, "my_prefix2_F(") && strstr(src, "my_prefix2_Fv(") && strstr(src, "my_prefix2_Fdv(") &&
              strstr(src, "my_prefix2_f_grad("),
          "the four functions are not all there");
    free(src);
    iacsg_expr_destroy(e);
}

/* The scene program has each solid's derivative along a ray, for the walks' interval Newton, in scenes of up to
 * 64 solids: past that its build time grew about fourfold for no faster frames (implicits/scene_emit.c). */
TEST(codegen_scene_fd_only_in_small_scenes) {
    for (int n = 64; n <= 65; n++) {
        iacsg_scene *s = scene_create();
        iacsg_error err = {0};
        CHECK(s != NULL, "out of memory");
        for (int k = 0; k < n; k++) {
            iacsg_expr *e = NULL;
            CHECK(iacsg_expr_parse("sphere", "<test>", &e, &err) == IACSG_OK, "%s", err.message);
            CHECK(scene_add_solid(s, NULL, e, &err) == k, "%s", err.message);
        }
        char *src = NULL;
        CHECK(scene_emit_cl(s, &src, &err) == IACSG_OK, "%s", err.message);
        int with_fd = strstr(src, "#define SCENE_SOLID_FD") && strstr(src, "#define IACSG_SCALAR_FD") &&
                      strstr(src, "scene_solid_Fd(");
        int any_fd = strstr(src, "SCENE_SOLID_FD") || strstr(src, "IACSG_SCALAR_FD 1") || strstr(src, "_Fd(int");
        free(src);
        iacsg_scene_destroy(s);
        CHECK(n <= 64 ? with_fd : !any_fd, "%d solids: derivative code %s", n, n <= 64 ? "missing" : "emitted");
    }
}

/* The union of the regions as one expression, for the segment path's pre-pass in lanes (kernels/scene_union.h), is
 * emitted only where its sign argument holds and it pays: some region, at most 8 solids and regions, every solid
 * defined everywhere (no sqrt here, whose domain edge may be met). The regions are taken as disjoint (claimed at the
 * union's leaf) only where no two can be in at one point whatever the solids: a \ b and a & b, a \ b and b \ a,
 * a \ b and b; not a and a & b, nor b \ a and a | b. */
TEST(codegen_scene_regions_union) {
    static const struct {
        const char *text;
        int expected, disjoint;
    } cases[] = {
        {"solid a = sphere(1.2)\nsolid b = box(1.5, 0.4, 0.4)\nregion r = a \\ b\nregion s = a & b", 1, 1},
        {"solid a = sphere(1.2)\nsolid b = box(1.5, 0.4, 0.4)\nregion r = a\nregion s = a & b", 1, 0},
        {"solid a = sphere(1.2)\nsolid b = box(1.5, 0.4, 0.4)\nregion r = a \\ b\nregion s = b \\ a", 1, 1},
        {"solid a = sphere(1.2)\nsolid b = box(1.5, 0.4, 0.4)\nregion r = a \\ b\nregion s = b", 1, 1},
        {"solid a = sphere(1.2)\nsolid b = box(1.5, 0.4, 0.4)\nregion r = b \\ a\nregion s = a | b", 1, 0},
        {"solid a = sphere(1.2)\nsolid b = sqrt(x^2 + y^2) - 0.5\nregion r = a \\ b", 0, 0},
        {"solid a = sphere(1.2)\nsurface s = x where a < 0", 0, 0},
        {"solid a = sphere(1)\nregion r1 = a\nregion r2 = a\nregion r3 = a\nregion r4 = a\nregion r5 = a\n"
         "region r6 = a\nregion r7 = a\nregion r8 = a\nregion r9 = a",
         0, 0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        iacsg_scene *s = NULL;
        iacsg_error err = {0};
        CHECK(iacsg_scene_parse(cases[c].text, "<test>", &s, &err) == IACSG_OK, "case %zu: %s", c, err.message);
        char *src = NULL;
        CHECK(scene_emit_cl(s, &src, &err) == IACSG_OK, "case %zu: %s", c, err.message);
        int with_union = strstr(src, "#define SCENE_REGIONS_UNION") && strstr(src, "iacsg_Fv(");
        int any_union = strstr(src, "SCENE_REGIONS_UNION") != NULL;
        int disjoint = strstr(src, "#define SCENE_REGIONS_DISJOINT") != NULL;
        free(src);
        iacsg_scene_destroy(s);
        CHECK(cases[c].expected ? with_union : !any_union, "case %zu: the regions' union %s", c,
              cases[c].expected ? "missing" : "emitted");
        CHECK(disjoint == cases[c].disjoint, "case %zu: the regions %s as disjoint", c,
              disjoint ? "taken" : "not taken");
    }
}
