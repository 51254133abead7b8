/* tests/t_scene_parse.c -- the scene language's regions, surfaces and materials (implicits/scene_parse.c): the
 * issue's example scene, how operands are split into solids, conditions, the trees' meaning (scene_tree_eval over
 * every sign combination against the intended boolean function), the 32-bit node encoding, plain scenes, and
 * every error with its message and place. */
#include "implicits/expr_internal.h"
#include "implicits/scene.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static iacsg_scene *parse_ok(const char *text) {
    iacsg_scene *s = NULL;
    iacsg_error err = {0};
    iacsg_status st = iacsg_scene_parse(text, "<test>", &s, &err);
    CHECK(st == IACSG_OK && s, "'%.80s' was refused: %d:%d: %s", text, err.line, err.column, err.message);
    return s;
}

static void expect_error(const char *text, iacsg_status status, int line, int column, const char *message) {
    iacsg_scene *s = NULL;
    iacsg_error err = {0};
    iacsg_status st = iacsg_scene_parse(text, "<test>", &s, &err);
    CHECK(st != IACSG_OK && s == NULL, "'%.80s' was accepted", text);
    CHECK(st == status && err.status == status, "'%.80s': status %s, expected %s (%s)", text,
          iacsg_status_name(st), iacsg_status_name(status), err.message);
    CHECK(err.line == line && err.column == column, "'%.80s': at %d:%d, expected %d:%d (%s)", text, err.line,
          err.column, line, column, err.message);
    CHECK(strcmp(err.message, message) == 0, "'%.80s': message \"%s\", expected \"%s\"", text, err.message,
          message);
}

/* The boolean function a tree should compute, over the signs of the scene's solids. */
typedef int (*intended_fn)(const signed char *sign);

/* scene_tree_eval of the tree at root against intended on every combination of signs (-1, 0, 1) of the
 * scene's solids. Returns the number of combinations. */
static int check_tree(const iacsg_scene *s, int root, intended_fn intended, const char *what) {
    CHECK(s->nsolids <= 10, "%s: too many solids for the truth table (%d)", what, s->nsolids);
    int combos = 1;
    for (int k = 0; k < s->nsolids; k++)
        combos *= 3;
    signed char sign[10];
    for (int c = 0; c < combos; c++) {
        for (int k = 0, r = c; k < s->nsolids; k++, r /= 3)
            sign[k] = (signed char)(r % 3 - 1);
        int got = scene_tree_eval(s, root, sign), want = intended(sign) != 0;
        CHECK(got == want, "%s: combination %d gives %d, expected %d", what, c, got, want);
    }
    return combos;
}

#define IN(k) (sign[k] < 0)
#define OUT(k) (sign[k] > 0)

/* The value of solid k at point p encloses want. */
static void check_solid_value(const iacsg_scene *s, int k, const double p[3], double want) {
    double out[2];
    iacsg_error err = {0};
    CHECK(s->solids[k].expr, "solid %d has no expression", k);
    CHECK(iacsg_expr_eval_box(s->solids[k].expr, 1, p, p, 0, out, &err) == IACSG_OK, "%s", err.message);
    CHECK(out[0] <= want && want <= out[1], "solid %d at (%g, %g, %g): [%.17g, %.17g] misses %.17g", k, p[0], p[1],
          p[2], out[0], out[1], want);
}

static const char issue_scene[] = "material red = rgb(0.8, 0.2, 0.1)          # optional further keywords\n"
                                  "material blue = rgb(0.2, 0.4, 0.9)\n"
                                  "material gold = rgb(0.9, 0.7, 0.2)\n"
                                  "solid ball = sphere(1.2)                   # any expression; f < 0 inside\n"
                                  "solid bar  = box(1.5, 0.4, 0.4)\n"
                                  "region body = ball \\ bar : red\n"
                                  "region plug = ball & bar : blue\n"
                                  "solid inner = sphere(1.0)\n"
                                  "solid outer = sphere(1.5)\n"
                                  "surface shell = gyroid(4) where inner > 0 & outer < 0 : gold\n";

static int body_fn(const signed char *sign) { return IN(0) && !IN(1); }
static int plug_fn(const signed char *sign) { return IN(0) && IN(1); }
static int shell_fn(const signed char *sign) { return OUT(2) && IN(3); }

TEST(scene_parse_issue_example) {
    iacsg_scene *s = parse_ok(issue_scene);
    CHECK(s->expr == NULL, "a scene with regions has a final expression");
    CHECK(s->nmaterials == 3, "%d materials", s->nmaterials);
    static const char *const mnames[] = {"red", "blue", "gold"};
    static const float rgb[3][3] = {{0.8f, 0.2f, 0.1f}, {0.2f, 0.4f, 0.9f}, {0.9f, 0.7f, 0.2f}};
    for (int k = 0; k < 3; k++) {
        const scene_material *m = &s->materials[k];
        CHECK(strcmp(m->name, mnames[k]) == 0, "material %d is '%s'", k, m->name);
        CHECK(memcmp(m->rgb, rgb[k], sizeof rgb[k]) == 0, "material %s: rgb %g %g %g", m->name, m->rgb[0], m->rgb[1],
              m->rgb[2]);
        CHECK(m->specular == SCENE_DEFAULT_SPECULAR && m->shininess == SCENE_DEFAULT_SHININESS,
              "material %s: specular %g shininess %g", m->name, m->specular, m->shininess);
    }
    /* ball, bar, inner, outer in declaration order, then the surface's gyroid written inline */
    CHECK(s->nsolids == 5, "%d solids", s->nsolids);
    static const char *const snames[] = {"ball", "bar", "inner", "outer", NULL};
    static const int sline[] = {4, 5, 8, 9, 10}, scol[] = {1, 1, 1, 1, 17};
    for (int k = 0; k < 5; k++) {
        const scene_solid *o = &s->solids[k];
        CHECK(snames[k] ? o->name && strcmp(o->name, snames[k]) == 0 : o->name == NULL, "solid %d is '%s'", k,
              o->name ? o->name : "(inline)");
        CHECK(o->line == sline[k] && o->column == scol[k], "solid %d at %d:%d", k, o->line, o->column);
    }
    const double p[3] = {0.5, 0.25, -0.125};
    double r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    check_solid_value(s, 0, p, r2 - 1.44);
    check_solid_value(s, 1, p, fmax(fabs(p[0]) - 1.5, fmax(fabs(p[1]) - 0.4, fabs(p[2]) - 0.4)));
    check_solid_value(s, 2, p, r2 - 1);
    check_solid_value(s, 3, p, r2 - 2.25);
    check_solid_value(s, 4, p,
                      sin(4 * p[0]) * cos(4 * p[1]) + sin(4 * p[1]) * cos(4 * p[2]) + sin(4 * p[2]) * cos(4 * p[0]));
    double box[6];
    CHECK(iacsg_expr_bounds(s->solids[0].expr, (double[2]){0, 0}, box) && box[3] >= 1.2 && box[3] < 2, "ball's bounds: %g", box[3]);
    /* items: ids in declaration order */
    CHECK(s->nitems == 3, "%d items", s->nitems);
    static const char *const inames[] = {"body", "plug", "shell"};
    static const int iline[] = {6, 7, 10}, imaterial[] = {0, 1, 2};
    for (int k = 0; k < 3; k++) {
        const scene_item *it = &s->items[k];
        CHECK(strcmp(it->name, inames[k]) == 0, "item %d is '%s'", k, it->name);
        CHECK(it->kind == (k < 2 ? SCENE_REGION : SCENE_SURFACE), "item %d has kind %d", k, (int)it->kind);
        CHECK(it->material == imaterial[k], "item %s has material %d", it->name, it->material);
        CHECK(it->line == iline[k] && it->column == 1, "item %s at %d:%d", it->name, it->line, it->column);
    }
    CHECK(s->items[0].solid == -1 && s->items[1].solid == -1 && s->items[2].solid == 4, "the surface's solid: %d",
          s->items[2].solid);
    int combos = check_tree(s, s->items[0].tree, body_fn, "body");
    check_tree(s, s->items[1].tree, plug_fn, "plug");
    check_tree(s, s->items[2].tree, shell_fn, "shell");
    /* the exact encoding of body: DIFFERENCE(INSIDE ball, INSIDE bar), right child two after the root */
    int t = s->items[0].tree;
    CHECK(scene_tree_size(s, t) == 3, "body has %d nodes", scene_tree_size(s, t));
    CHECK(s->nodes[t] == CSG_NODE(CSG_DIFFERENCE, (uint32_t)t + 2) && s->nodes[t + 1] == CSG_NODE(CSG_INSIDE, 0) &&
              s->nodes[t + 2] == CSG_NODE(CSG_INSIDE, 1),
          "body's nodes: %08x %08x %08x", s->nodes[t], s->nodes[t + 1], s->nodes[t + 2]);
    iacsg_scene_destroy(s);
    test_note("3 trees checked on %d sign combinations each", combos);
}

/* Inline operands: each maximal expression under a region's outer | & \ is one solid, numbered left to right;
 * an expression met before (same DAG node: a solid's, a binding's) is the same solid. */
static int precedence_fn(const signed char *sign) { return IN(0) || (IN(3) && (IN(4) && !IN(2))); }
static int paren_fn(const signed char *sign) { return (IN(0) || IN(1)) && !IN(2); }
static int call_fn(const signed char *sign) { return IN(5) && IN(6); }
static int cond_fn(const signed char *sign) { return (IN(0) || OUT(1)) && !IN(2) && !!OUT(4); }
static int inline_cond_fn(const signed char *sign) { return OUT(2) && IN(3); }

TEST(scene_parse_operands) {
    iacsg_scene *s = parse_ok("solid ball = sphere(1.2)\n"
                              "region r = sphere(1.2) & box | ball\n");
    /* sphere(1.2) written inline is ball itself; box is the only inline solid */
    CHECK(s->nsolids == 2 && s->solids[1].name == NULL, "%d solids", s->nsolids);
    CHECK(s->solids[1].line == 2 && s->solids[1].column == 26, "box at %d:%d", s->solids[1].line,
          s->solids[1].column);
    iacsg_scene_destroy(s);

    s = parse_ok("c = sphere(0.5)\n"
                 "region r = move(sphere, 1) | (x + y) & c ; region q = c");
    CHECK(s->nsolids == 3, "%d solids", s->nsolids);
    CHECK(s->solids[0].column == 12 && s->solids[1].column == 31 && s->solids[2].column == 40,
          "inline solids at columns %d, %d, %d", s->solids[0].column, s->solids[1].column, s->solids[2].column);
    signed char sign[3] = {1, -1, -1};
    CHECK(scene_tree_eval(s, s->items[0].tree, sign) == 1, "(x + y) & c");
    CHECK(scene_tree_eval(s, s->items[1].tree, sign) == 1 && s->nodes[s->items[1].tree] == CSG_NODE(CSG_INSIDE, 2),
          "the binding c is the inline solid 2");
    const double p[3] = {0.25, -0.5, 0};
    check_solid_value(s, 1, p, -0.25); /* the parenthesised arithmetic is one solid */
    iacsg_scene_destroy(s);

    /* solids no region or surface uses are dropped, the others keep their order */
    s = parse_ok("solid a = sphere\nsolid b = box\nsolid c = a | b\nsolid d = y\nregion r = c & x\nsurface s = d");
    CHECK(s->nsolids == 3 && strcmp(s->solids[0].name, "c") == 0 && strcmp(s->solids[1].name, "d") == 0 &&
              s->solids[2].name == NULL && s->solids[2].line == 5,
          "%d solids after dropping the unused ones", s->nsolids);
    CHECK(s->nodes[1] == CSG_NODE(CSG_INSIDE, 0) && s->nodes[2] == CSG_NODE(CSG_INSIDE, 2) && s->items[1].solid == 1,
          "the trees and the surface name the renumbered solids");
    const double q[3] = {0.5, 0.25, 0};
    check_solid_value(s, 0, q, fmin(0.25 + 0.0625 - 1, fmax(-0.5, -0.75)));
    iacsg_scene_destroy(s);

    s = parse_ok("material m =\n  rgb(1, 1, 1)\nregion r =\n  sphere |\n  box");
    CHECK(s->nsolids == 2 && s->solids[1].line == 5, "a region's expression over three lines");
    iacsg_scene_destroy(s);

    /* | loosest, then &, then \ (as in expressions); parentheses group; calls and arithmetic are operands */
    s = parse_ok("solid a = sphere\nsolid b = box\nsolid c = x\n"
                 "region r = a | sphere(2) & y \\ c\n"
                 "region q = (a | b) \\ c\n"
                 "region n = move(a | b, 1) & -(c & y)");
    CHECK(s->nsolids == 7, "%d solids", s->nsolids);
    check_tree(s, s->items[0].tree, precedence_fn, "a | sphere(2) & y \\ c");
    check_tree(s, s->items[1].tree, paren_fn, "(a | b) \\ c");
    check_tree(s, s->items[2].tree, call_fn, "move(a | b, 1) & -(c & y)");
    iacsg_scene_destroy(s);
}

/* Conditions: < and > leaves, & | ! and parentheses; a parenthesis opens a condition only when it holds a
 * comparison or a '!', else it starts an expression. */
TEST(scene_parse_conditions) {
    iacsg_scene *s = parse_ok("solid a = sphere\nsolid b = box\nsolid c = x\n"
                              "surface s = (x + y) where (a < 0 | b > 0) & !(c < 0) & !!((x - 2) * 3 > 0)");
    CHECK(s->nitems == 1 && s->items[0].kind == SCENE_SURFACE, "one surface");
    CHECK(s->nsolids == 5 && s->items[0].solid == 3, "%d solids, the surface's is %d", s->nsolids, s->items[0].solid);
    check_tree(s, s->items[0].tree, cond_fn, "(a < 0 | b > 0) & !(c < 0) & !!((x - 2) * 3 > 0)");
    const double p[3] = {2.5, 0, 0};
    check_solid_value(s, 4, p, 1.5);
    iacsg_scene_destroy(s);
    /* a surface without where keeps all of its zero set; one that is a solid's name is that solid */
    s = parse_ok("solid a = sphere\nsurface s = a\nsurface u = plane where sphere(2) > 0 & (sphere(3)) < 0.0");
    CHECK(s->nsolids == 4 && s->items[0].solid == 0 && s->items[0].tree == -1 && s->items[0].material == -1,
          "surface s = a: solid %d, condition %d", s->items[0].solid, s->items[0].tree);
    CHECK(s->items[1].solid == 1, "surface u's solid: %d", s->items[1].solid);
    check_tree(s, s->items[1].tree, inline_cond_fn, "sphere(2) > 0 & (sphere(3)) < 0.0");
    iacsg_scene_destroy(s);
}

/* The 32-bit nodes: 3 bits of operator and 29 of operand, both read back exactly. */
TEST(scene_node_encoding) {
    static const uint32_t args[] = {0, 1, 2, 12345, 1u << 28, CSG_ARG_MAX - 1, CSG_ARG_MAX};
    int n = 0;
    for (int op = CSG_INSIDE; op <= CSG_NOT; op++)
        for (int k = 0; k < (int)(sizeof args / sizeof args[0]); k++, n++) {
            uint32_t node = CSG_NODE(op, args[k]);
            CHECK(CSG_NODE_OP(node) == op && CSG_NODE_ARG(node) == args[k], "op %d arg %u: read back %d %u", op,
                  args[k], CSG_NODE_OP(node), CSG_NODE_ARG(node));
        }
    CHECK(CSG_ARG_MAX == 0x1fffffffu && CSG_NODE(CSG_NOT, CSG_ARG_MAX) == 0xbfffffffu, "the bit layout");
    /* scene_add_tree rebases a tree's operands to where it lands */
    iacsg_scene *s = parse_ok("region r = sphere | box\nregion q = x & y");
    uint32_t t = (uint32_t)s->items[1].tree;
    CHECK(t == 3 && s->nodes[t] == CSG_NODE(CSG_INTERSECT, t + 2), "q's root at %u: %08x", t, s->nodes[t]);
    iacsg_scene_destroy(s);
    test_note("%d nodes round-tripped", n);
}

/* A scene without regions or surfaces is what iacsg_expr_parse makes of it: its solids are bindings, its
 * materials are listed (unused). */
TEST(scene_parse_plain) {
    static const char *const texts[] = {"sphere", "a = sphere(2)\nb = box\na \\ b",
                                        "material m = rgb(1, 0.5, 0) specular 0.75 shininess 8\n"
                                        "solid ball = sphere\nball | move(ball, 1)"};
    for (int k = 0; k < 3; k++) {
        iacsg_scene *s = parse_ok(texts[k]);
        iacsg_expr *e;
        CHECK(iacsg_expr_parse(texts[k], "<test>", &e, NULL) == IACSG_OK, "iacsg_expr_parse refused '%s'", texts[k]);
        CHECK(s->nitems == 0 && s->nsolids == 0 && s->expr, "'%s': %d items, %d solids", texts[k], s->nitems,
              s->nsolids);
        char *a, *b;
        CHECK(iacsg_expr_emit_cl(s->expr, "p", &a, NULL) == IACSG_OK, "emit");
        CHECK(iacsg_expr_emit_cl(e, "p", &b, NULL) == IACSG_OK, "emit");
        CHECK(strcmp(a, b) == 0, "'%s': the scene's expression differs from iacsg_expr_parse's", texts[k]);
        free(a);
        free(b);
        if (k == 2) {
            const scene_material *m = &s->materials[0];
            CHECK(s->nmaterials == 1 && m->specular == 0.75f && m->shininess == 8 && m->rgb[1] == 0.5f,
                  "material m: specular %g shininess %g", m->specular, m->shininess);
        }
        iacsg_expr_destroy(e);
        iacsg_scene_destroy(s);
    }
}

TEST(scene_parse_errors) {
    /* names */
    expect_error("solid ball = sphere\nregion r = bal \\ box", IACSG_ERR_NAME, 2, 12,
                 "unknown solid 'bal', did you mean 'ball'?");
    expect_error("region r = qwertyuiop", IACSG_ERR_NAME, 1, 12, "unknown solid 'qwertyuiop'");
    expect_error("solid inner = sphere\nsurface s = plane where iner > 0", IACSG_ERR_NAME, 2, 25,
                 "unknown solid 'iner', did you mean 'inner'?");
    expect_error("material red = rgb(1, 0, 0)\nregion r = sphere : rde", IACSG_ERR_NAME, 2, 21,
                 "unknown material 'rde', did you mean 'red'?");
    expect_error("region r = sphere : gold", IACSG_ERR_NAME, 1, 21, "unknown material 'gold'");
    expect_error("region r = sphere : gold\nmaterial gold = rgb(1, 1, 0)", IACSG_ERR_NAME, 1, 21,
                 "'gold' is used before its declaration (line 2)");
    expect_error("region r = ball\nsolid ball = sphere", IACSG_ERR_NAME, 1, 12,
                 "'ball' is used before its declaration (line 2)");
    expect_error("solid ball = sphere\nregion r = sphere : ball", IACSG_ERR_NAME, 2, 21,
                 "'ball' is a solid, not a material");
    expect_error("material red = rgb(1, 0, 0)\nregion r = red", IACSG_ERR_NAME, 2, 12,
                 "'red' is a material, not a solid");
    expect_error("region r = sphere\nregion q = r & box", IACSG_ERR_NAME, 2, 12, "'r' is a region, not a solid");
    /* declared twice: any name, any kind */
    expect_error("material red = rgb(1, 0, 0)\nmaterial red = rgb(0, 1, 0)\nregion r = x", IACSG_ERR_NAME, 2, 10,
                 "'red' is already declared as a material (line 1)");
    expect_error("a = 1\nsolid a = sphere\na", IACSG_ERR_NAME, 2, 7, "'a' is already bound (line 1)");
    expect_error("solid a = sphere\na = 1\na", IACSG_ERR_NAME, 2, 1, "'a' is already declared as a solid (line 1)");
    expect_error("region a = sphere\nsurface a = box", IACSG_ERR_NAME, 2, 9,
                 "'a' is already declared as a region (line 1)");
    expect_error("solid sphere = box\nbox", IACSG_ERR_NAME, 1, 7,
                 "cannot name a solid 'sphere': it is a built-in name");
    /* missing parts */
    expect_error("region body =\n", IACSG_ERR_SYNTAX, 1, 13, "region 'body' has no expression after '='");
    expect_error("region body =\nregion plug = sphere", IACSG_ERR_SYNTAX, 1, 13,
                 "region 'body' has no expression after '='");
    expect_error("material m = rgb(1, 1, 1)\nregion body = : m", IACSG_ERR_SYNTAX, 2, 13,
                 "region 'body' has no expression after '='");
    expect_error("surface s = where x < 0", IACSG_ERR_SYNTAX, 1, 11, "surface 's' has no expression after '='");
    expect_error("surface s = plane where", IACSG_ERR_SYNTAX, 1, 19,
                 "'where' without a condition: write e.g. 'where ball < 0'");
    expect_error("material g = rgb(1, 1, 1)\nsurface s = plane where : g", IACSG_ERR_SYNTAX, 2, 19,
                 "'where' without a condition: write e.g. 'where ball < 0'");
    expect_error("region r = sphere :", IACSG_ERR_SYNTAX, 1, 20,
                 "expected the name of a material after ':', found the end of the input");
    expect_error("region r sphere", IACSG_ERR_SYNTAX, 1, 10, "expected '=' after 'region r', found 'sphere'");
    /* conditions */
    expect_error("surface s = plane where sphere", IACSG_ERR_SYNTAX, 1, 31,
                 "expected '< 0' or '> 0' after the expression in the condition, found the end of the input");
    expect_error("surface s = plane where sphere < 1", IACSG_ERR_SYNTAX, 1, 34,
                 "a condition compares with 0 ('E < 0' or 'E > 0'; write 'E - c < 0'), found '1'");
    expect_error("surface s = plane where sphere < 0 &", IACSG_ERR_SYNTAX, 1, 37,
                 "expected a comparison such as 'ball < 0', found the end of the input");
    expect_error("surface s = plane where (sphere < 0", IACSG_ERR_SYNTAX, 1, 36,
                 "expected ')', found the end of the input");
    /* materials */
    expect_error("material m = rgb(1.5, 0, 0)\nx", IACSG_ERR_ARG, 1, 18, "rgb component 1.5 is outside [0, 1]");
    expect_error("material m = rgb(0, -0.1, 0)\nx", IACSG_ERR_ARG, 1, 21, "rgb component -0.1 is outside [0, 1]");
    expect_error("material m = rgb(0.5, 0.5)", IACSG_ERR_SYNTAX, 1, 26, "rgb takes 3 numbers, found ')'");
    expect_error("material m = rgb(0.5, 0.5, 0.5, 1)", IACSG_ERR_SYNTAX, 1, 31, "rgb takes 3 numbers, found ','");
    expect_error("material m = rgb(0.5, x, 0.5)", IACSG_ERR_SYNTAX, 1, 23, "rgb takes 3 numbers, found 'x'");
    expect_error("material m = 0.5", IACSG_ERR_SYNTAX, 1, 14,
                 "expected rgb(R, G, B), the material's colour, found '0.5'");
    expect_error("material m = rgb(1, 1, 1) shine 3\nx", IACSG_ERR_NAME, 1, 27,
                 "unknown material keyword 'shine' (specular, shininess, reflect, opacity)");
    expect_error("material m = rgb(1, 1, 1) speculr 0.5\nx", IACSG_ERR_NAME, 1, 27,
                 "unknown material keyword 'speculr', did you mean 'specular'?");
    expect_error("material m = rgb(1, 1, 1) specular 0.5 specular 0.1\nx", IACSG_ERR_ARG, 1, 40,
                 "'specular' is given twice for material 'm'");
    expect_error("material m = rgb(1, 1, 1) specular 2\nx", IACSG_ERR_ARG, 1, 36, "specular 2 is outside [0, 1]");
    expect_error("material m = rgb(1, 1, 1) specular", IACSG_ERR_SYNTAX, 1, 35,
                 "expected a number after the material's keyword, found the end of the input");
    expect_error("material m = rgb(1, 1, 1) 0.5", IACSG_ERR_SYNTAX, 1, 27,
                 "expected a material keyword and its number, or the end of the statement, found '0.5'");
    /* a final expression in a scene with regions */
    expect_error("region r = sphere\nbox", IACSG_ERR_SYNTAX, 2, 1,
                 "a scene with regions or surfaces has no final expression (its regions and surfaces are what is "
                 "rendered): declare it as a region, or remove it");
    expect_error("solid a = sphere\nmaterial m = rgb(1, 1, 1)", IACSG_ERR_SYNTAX, 2, 26,
                 "expected an expression to render, found the end of the input");
    /* the new punctuation is no expression operator */
    expect_error("sphere < 0", IACSG_ERR_SYNTAX, 1, 8, "expected an operator or the end of the statement, found '<'");
    expect_error("region r = sphere < 0", IACSG_ERR_SYNTAX, 1, 19,
                 "expected an operator or the end of the statement, found '<'");
}

/* The AST dump shows the declarations and the set operations, conditions and operands. */
TEST(scene_parse_dump) {
    iacsg_error err = {0};
    char *dump = iacsg_expr_dump("material m = rgb(1, 0.5, 0) specular 0.2\nsolid a = sphere\n"
                                 "region r = a & box \\ (x + 1) : m\nsurface s = a where !(a < 0) | y > 0",
                                 "ast", &err);
    CHECK(dump, "%s", err.message);
    static const char *const lines[] = {"n4 = material m = rgb(n0, n1, n2, specular=n3)\n", "n6 = solid a = n5\n",
                                        "n7 = name a (operand)\n", "n12 = set n8 \\ n11\n", "n13 = set n7 & n12\n",
                                        "n14 = region r = n13 : m\n", "n18 = not n17\n", "n20 = cmp n19 > 0\n",
                                        "n21 = cond n18 | n20\n", "n22 = surface s = n15 where n21\n"};
    for (int k = 0; k < (int)(sizeof lines / sizeof lines[0]); k++)
        CHECK(strstr(dump, lines[k]), "the dump lacks \"%.*s\":\n%s", (int)strlen(lines[k]) - 1, lines[k], dump);
    free(dump);
}

/* iacsg_expr_parse reads one expression (with bindings): a region or surface is refused at its keyword. */
TEST(scene_parse_expr_refuses_items) {
    static const struct {
        const char *text;
        int line, column;
        const char *message;
    } cases[] = {
        {"region a = sphere", 1, 1,
         "a region makes a multi-material scene, not one expression (such scenes are read from files, by "
         "iacsg_scene_parse)"},
        {"solid b = box\n  surface s = b where b < 0", 2, 3,
         "a surface makes a multi-material scene, not one expression (such scenes are read from files, by "
         "iacsg_scene_parse)"},
    };
    for (int k = 0; k < 2; k++) {
        iacsg_expr *e = NULL;
        iacsg_error err = {0};
        CHECK(iacsg_expr_parse(cases[k].text, "<expr>", &e, &err) == IACSG_ERR_SYNTAX && !e, "'%s' was accepted",
              cases[k].text);
        CHECK(err.line == cases[k].line && err.column == cases[k].column && strcmp(err.message, cases[k].message) == 0,
              "'%s': %d:%d: %s", cases[k].text, err.line, err.column, err.message);
    }
}

/* Scenes of thousands of solids parse in linear time (names are hashed, inline solids found by DAG node). */
TEST(scene_parse_many_regions) {
    enum { N = 3000 };
    size_t size = (size_t)N * 96 + 64;
    char *text = malloc(size);
    CHECK(text, "out of memory");
    size_t len = 0;
    for (int k = 0; k < N; k++)
        len += (size_t)snprintf(text + len, size - len,
                                "solid s%d = move(sphere(0.1), %d, 0, 0)\nregion r%d = s%d & x\n", k, k, k, k);
    clock_t t0 = clock();
    iacsg_scene *s = parse_ok(text);
    double ms = 1e3 * (double)(clock() - t0) / CLOCKS_PER_SEC;
    free(text);
    CHECK(s->nitems == N && s->nsolids == N + 1, "%d items, %d solids", s->nitems, s->nsolids);
    /* x written inline in every region is one solid, the first inline one (after s0) */
    CHECK(s->nodes[s->items[N - 1].tree + 2] == CSG_NODE(CSG_INSIDE, 1), "the shared inline solid");
    const double p[3] = {(double)(N - 1), 0.05, 0};
    check_solid_value(s, N, p, 0.05 * 0.05 - 0.01);
    iacsg_scene_destroy(s);
    test_note("%d regions and %d solids parsed in %.0f ms", N, N + 1, ms);
}

/* The sign of solid k at point p from its enclosure: 0 where the enclosure straddles 0. */
static signed char solid_sign(const iacsg_scene *s, int k, const double p[3]) {
    double out[2];
    CHECK(iacsg_expr_eval_box(s->solids[k].expr, 1, p, p, 0, out, NULL) == IACSG_OK, "evaluation of solid %d", k);
    return (signed char)(out[1] < 0 ? -1 : out[0] > 0 ? 1 : 0);
}

static iacsg_scene *parse_example(const char *file) {
    char path[4096];
    snprintf(path, sizeof path, "%s/examples/%s", test_source_dir(), file);
    char *text = test_read_file(path, NULL);
    CHECK(text, "cannot read %s", path);
    iacsg_scene *s = parse_ok(text);
    free(text);
    return s;
}

/* The multi-material examples: their items, and the regions each point of a grid lies in (the solids' signs at
 * the point through the trees): the machined part's regions never overlap, and named points are where the
 * comments say. */
TEST(scene_parse_examples) {
    iacsg_scene *s = parse_example("fig2_cube_sphere_regions.csg");
    CHECK(s->nitems == 2 && s->nsolids == 2 && s->items[0].material == 0 && s->items[1].material == 1,
          "fig2 regions: %d items", s->nitems);
    iacsg_scene_destroy(s);

    s = parse_example("machined_part.csg");
    static const char *const names[] = {"flange", "bushing", "seal", "bolt_a", "bolt_b", "bolt_c", "bolt_d"};
    CHECK(s->nitems == 7 && s->nsolids == 10 && s->nmaterials == 4, "%d items, %d solids", s->nitems, s->nsolids);
    for (int k = 0; k < 7; k++)
        CHECK(strcmp(s->items[k].name, names[k]) == 0 && s->items[k].kind == SCENE_REGION, "item %d", k);
    static const struct {
        double p[3];
        int region; /* -1: none */
    } points[] = {{{1.0, 0, 0}, 0}, {{0.5, 0.1, 0.4}, 0}, {{0.3, 0, 0}, 1}, {{0, 0, 0}, -1}, {{0.48, 0, 0.5}, 2},
                  {{0, 0.5, 0.47}, 2},  {{0.9, 0.9, 0.23}, 3}, {{-0.9, -0.9, 0.25}, 5}, {{1.1, 1.1, 0.3}, -1}};
    signed char sign[10];
    for (int i = 0; i < (int)(sizeof points / sizeof points[0]); i++) {
        for (int k = 0; k < s->nsolids; k++)
            sign[k] = solid_sign(s, k, points[i].p);
        for (int r = 0; r < s->nitems; r++)
            CHECK(scene_tree_eval(s, s->items[r].tree, sign) == (r == points[i].region),
                  "point (%g, %g, %g): in region %s is %d", points[i].p[0], points[i].p[1], points[i].p[2],
                  s->items[r].name, scene_tree_eval(s, s->items[r].tree, sign));
    }
    int claimed = 0, decided = 0;
    const int n = 24;
    for (int i = 0; i < n * n * n; i++) {
        double p[3] = {-1.3 + 2.6 * (i % n + 0.37) / n, -1.3 + 2.6 * (i / n % n + 0.41) / n,
                       -0.7 + 1.4 * (i / (n * n) + 0.43) / n};
        int undecided = 0, regions = 0;
        for (int k = 0; k < s->nsolids; k++)
            undecided |= (sign[k] = solid_sign(s, k, p)) == 0;
        if (undecided)
            continue;
        decided++;
        for (int r = 0; r < s->nitems; r++)
            regions += scene_tree_eval(s, s->items[r].tree, sign);
        CHECK(regions <= 1, "(%g, %g, %g) is in %d regions", p[0], p[1], p[2], regions);
        claimed += regions;
    }
    CHECK(claimed > decided / 10, "only %d of %d points in a region", claimed, decided);
    iacsg_scene_destroy(s);
    test_note("machined part: %d grid points, %d in one region, none in two", decided, claimed);
}

/* A random boolean expression over the solids s0..s4, written fully parenthesised into text, and its value at
 * the signs sign[]: a region's (| & \ over names) or a condition's (& | ! over comparisons < 0, > 0). */
typedef struct {
    char text[4096];
    size_t len;
} text_buf;

static int random_bool(test_rng_t *rng, text_buf *t, int depth, int condition, const signed char *sign) {
    int leaf = depth == 0 || test_rand_u64(rng) % 3 == 0;
    if (leaf) {
        int k = (int)(test_rand_u64(rng) % 5);
        int above = condition && test_rand_u64(rng) % 2;
        t->len += (size_t)snprintf(t->text + t->len, sizeof t->text - t->len, condition ? "s%d %c 0" : "s%d", k,
                                   above ? '>' : '<');
        return above ? sign[k] > 0 : sign[k] < 0;
    }
    if (condition && test_rand_u64(rng) % 4 == 0) {
        t->len += (size_t)snprintf(t->text + t->len, sizeof t->text - t->len, "!(");
        int v = !random_bool(rng, t, depth - 1, condition, sign);
        t->len += (size_t)snprintf(t->text + t->len, sizeof t->text - t->len, ")");
        return v;
    }
    char op = "|&\\"[test_rand_u64(rng) % (condition ? 2 : 3)];
    t->len += (size_t)snprintf(t->text + t->len, sizeof t->text - t->len, "(");
    int l = random_bool(rng, t, depth - 1, condition, sign);
    t->len += (size_t)snprintf(t->text + t->len, sizeof t->text - t->len, " %c ", op);
    int r = random_bool(rng, t, depth - 1, condition, sign);
    t->len += (size_t)snprintf(t->text + t->len, sizeof t->text - t->len, ")");
    return op == '|' ? l || r : op == '&' ? l && r : l && !r;
}

/* Random regions and conditions: their trees compute, on every combination of the solids' signs, what the
 * text says. The text is regenerated from the same random state for each combination. */
TEST(scene_parse_random_trees) {
    test_rng_t *rng = test_rng();
    long n = test_iters(150), combos = 0;
    for (long i = 0; i < n; i++) {
        int condition = (int)(i % 2);
        test_rng_t start = *rng;
        signed char sign[5] = {0};
        text_buf t = {.len = 0};
        t.len = (size_t)snprintf(t.text, sizeof t.text, "solid s0 = x\nsolid s1 = y\nsolid s2 = z\n"
                                                         "solid s3 = x + y\nsolid s4 = sphere\n%s",
                                 condition ? "surface s = s0 + s1 + s2 + s3 + s4 where " : "region r = ");
        size_t prefix = t.len;
        random_bool(rng, &t, 5, condition, sign);
        test_rng_t end = *rng;
        iacsg_scene *s = parse_ok(t.text);
        /* solids keep their declaration order; the surface's own solid comes last */
        for (int c = 0; c < 243; c++, combos++) {
            for (int k = 0, r = c; k < 5; k++, r /= 3)
                sign[k] = (signed char)(r % 3 - 1);
            int used[5] = {0};
            for (int k = 0; k < s->nsolids; k++)
                if (s->solids[k].name)
                    used[s->solids[k].name[1] - '0'] = 1;
            signed char mapped[6] = {0};
            for (int k = 0, m = 0; k < 5; k++)
                if (used[k])
                    mapped[m++] = sign[k];
            *rng = start;
            t.len = prefix;
            int want = random_bool(rng, &t, 5, condition, sign);
            CHECK(scene_tree_eval(s, s->items[0].tree, mapped) == want, "combination %d of\n%s", c, t.text);
        }
        *rng = end;
        iacsg_scene_destroy(s);
    }
    test_note("%ld random trees, %ld sign combinations", n, combos);
}
