/* tests/t_expr_parse.c -- the language: errors (status, line, column, message, suggestions), injection
 * attempts, nesting and size limits, scenes, precedence, and the meaning of primitives and transforms (checked
 * by host evaluation at points). */
#include "implicits/expr_internal.h"
#include "implicits/library.h"
#include "implicits/scene.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <glob.h>
#include <time.h>

static void expect_error(const char *text, iacsg_status status, int line, int column, const char *message) {
    iacsg_expr *e = NULL;
    iacsg_error err = {0};
    iacsg_status st = iacsg_expr_parse(text, "<test>", &e, &err);
    CHECK(st != IACSG_OK && e == NULL, "'%.60s' was accepted", text);
    CHECK(st == status && err.status == status, "'%.60s': status %s, expected %s (%s)", text,
          iacsg_status_name(st), iacsg_status_name(status), err.message);
    CHECK(err.line == line && err.column == column, "'%.60s': at %d:%d, expected %d:%d (%s)", text, err.line,
          err.column, line, column, err.message);
    CHECK(strstr(err.message, message) != NULL, "'%.60s': message \"%s\" lacks \"%s\"", text, err.message, message);
}

TEST(expr_errors) {
    expect_error("tours", IACSG_ERR_NAME, 1, 1, "unknown primitive 'tours', did you mean 'torus'?");
    expect_error("min(sphere, tours(R=2))", IACSG_ERR_NAME, 1, 13, "did you mean 'torus'?");
    expect_error("sqrtt(x)", IACSG_ERR_NAME, 1, 1, "unknown function 'sqrtt', did you mean 'sqrt'?");
    expect_error("smooth_unoin(x, y)", IACSG_ERR_NAME, 1, 1, "did you mean 'smooth_union'?");
    expect_error("zz + 1", IACSG_ERR_NAME, 1, 1, "unknown name 'zz', did you mean 'z'?");
    expect_error("qwertyuiop", IACSG_ERR_NAME, 1, 1, "unknown name 'qwertyuiop'");
    expect_error("sphere(", IACSG_ERR_SYNTAX, 1, 8, "expected a number, a name or '(', found the end of the input");
    expect_error("x + ", IACSG_ERR_SYNTAX, 1, 5, "expected a number, a name or '('");
    expect_error("(x + y", IACSG_ERR_SYNTAX, 1, 7, "expected ')'");
    expect_error("x) + (y", IACSG_ERR_SYNTAX, 1, 2, "unbalanced ')'");
    expect_error("x y", IACSG_ERR_SYNTAX, 1, 3, "expected an operator or the end of the statement");
    expect_error("2e", IACSG_ERR_SYNTAX, 1, 1, "malformed number: '2e'"); /* a letter glued to a number */
    expect_error("0x1p3", IACSG_ERR_SYNTAX, 1, 1, "malformed number: '0x1p3'");
    expect_error("x + 1e999", IACSG_ERR_SYNTAX, 1, 5, "number out of range");
    expect_error("1 @ 2", IACSG_ERR_SYNTAX, 1, 3, "unexpected character '@'");
    expect_error("x + \xff", IACSG_ERR_SYNTAX, 1, 5, "unexpected byte 0xff");
    expect_error("sqrt(x, y)", IACSG_ERR_ARITY, 1, 1, "'sqrt' takes 1 argument, got 2");
    expect_error("min(x)", IACSG_ERR_ARITY, 1, 1, "'min' takes at least 2 arguments, got 1");
    expect_error("sin(x=1)", IACSG_ERR_NAME, 1, 5, "'sin' takes no keyword arguments");
    expect_error("torus(R=1, rr=0.5)", IACSG_ERR_NAME, 1, 12, "'torus' has no parameter 'rr', did you mean 'r'?");
    expect_error("torus(R=1, R=2)", IACSG_ERR_ARITY, 1, 12, "'R' is given twice");
    expect_error("torus(r=1, 2)", IACSG_ERR_SYNTAX, 1, 1, "a positional argument follows a keyword");
    expect_error("sphere(1, 2)", IACSG_ERR_ARITY, 1, 1, "'sphere' takes at most 1 argument");
    expect_error("rotatex(sphere)", IACSG_ERR_ARITY, 1, 1, "'rotatex' needs its argument 'angle'");
    expect_error("move", IACSG_ERR_ARITY, 1, 1, "'move' needs arguments");
    expect_error("x(1)", IACSG_ERR_NAME, 1, 1, "'x' is not a function");
    expect_error("a = 1\na(2)", IACSG_ERR_NAME, 2, 1, "'a' is a binding, not a function");
    expect_error("material", IACSG_ERR_NAME, 1, 1, "reserved");
    /* scenes */
    expect_error("a = sphere\nb = a\nc", IACSG_ERR_NAME, 3, 1, "unknown name 'c'");
    expect_error("a = 1\na = 2\na", IACSG_ERR_NAME, 2, 1, "'a' is already bound (line 1)");
    expect_error("sphere = 1\nsphere", IACSG_ERR_NAME, 1, 1, "cannot bind 'sphere'");
    expect_error("x\ny", IACSG_ERR_SYNTAX, 1, 1, "only the last statement of a scene may be an expression");
    expect_error("a = x", IACSG_ERR_SYNTAX, 1, 6, "expected an expression to render");
    expect_error("# only a comment\n", IACSG_ERR_SYNTAX, 2, 1, "expected an expression to render");
    expect_error("a = a + 1\na", IACSG_ERR_NAME, 1, 5, "unknown name 'a'");
}

/* Text that tries to close the generated function and add a kernel never reaches the emitter. */
TEST(expr_rejects_injection) {
    expect_error("x); } __kernel void evil(", IACSG_ERR_SYNTAX, 1, 5, "unexpected character '}'");
    expect_error("x) + 0; } __kernel void evil() { (x", IACSG_ERR_SYNTAX, 1, 9, "unexpected character '}'");
    expect_error("sphere(r = 1)) ; evil(", IACSG_ERR_SYNTAX, 1, 14, "unbalanced ')'");
    expect_error("x /* comment */", IACSG_ERR_SYNTAX, 1, 4, "expected a number");
    expect_error("\"x\"", IACSG_ERR_SYNTAX, 1, 1, "unexpected character '\"'");
    /* '#' starts a comment: a preprocessor line in the input is a comment, never emitted */
    iacsg_expr *e;
    char *src;
    CHECK(iacsg_expr_parse("x\n#define F 1\n", "<test>", &e, NULL) == IACSG_OK, "a comment line was refused");
    CHECK(iacsg_expr_emit_cl(e, "p", &src, NULL) == IACSG_OK && !strstr(src, "define F"), "the comment was emitted");
    free(src);
    iacsg_expr_destroy(e);
    /* names that happen to be OpenCL or C keywords are unknown names, never copied */
    expect_error("__kernel", IACSG_ERR_NAME, 1, 1, "unknown name '__kernel'");
    expect_error("return(x)", IACSG_ERR_NAME, 1, 1, "unknown function 'return'");
}

static char *repeat(const char *head, const char *unit, long n, const char *tail) {
    size_t hu = strlen(head), uu = strlen(unit), tu = strlen(tail);
    char *s = malloc(hu + uu * (size_t)n + tu * (size_t)n + 1), *p = s;
    CHECK(s != NULL, "out of memory");
    memcpy(p, head, hu), p += hu;
    for (long i = 0; i < n; i++)
        memcpy(p, unit, uu), p += uu;
    for (long i = 0; i < n && tu; i++)
        memcpy(p, tail, tu), p += tu;
    *p = '\0';
    return s;
}

static double seconds(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

/* Deep nesting is refused with a clear error; long flat input compiles in linear time. */
TEST(expr_limits) {
    char *s = malloc(200002);
    CHECK(s != NULL, "out of memory");
    memset(s, '(', 100000);
    s[100000] = 'x';
    memset(s + 100001, ')', 100000);
    s[200001] = '\0';
    expect_error(s, IACSG_ERR_LIMIT, 1, 201, "nested too deeply (more than 200 levels)");
    free(s);
    s = repeat("", "sin(", 100000, ")");
    expect_error(s, IACSG_ERR_LIMIT, 1, 801, "nested too deeply");
    free(s);
    s = repeat("", "-", 100000, "");
    expect_error(s, IACSG_ERR_LIMIT, 1, 201, "too many signs in a row");
    free(s);
    s = repeat("x", "^x", 100000, "");
    expect_error(s, IACSG_ERR_LIMIT, 1, 402, "nested too deeply"); /* at the 201st ^ */
    free(s);
    s = repeat("", "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa", 1, "");
    expect_error(s, IACSG_ERR_LIMIT, 1, 1, "name too long");
    free(s);

    /* a million characters of x+y*z+...: accepted, linear */
    double t0 = seconds();
    s = repeat("x", "+y*z", 250000, "");
    iacsg_expr *e;
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse(s, "<big>", &e, &err) == IACSG_OK, "%s", err.message);
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, out[2];
    CHECK(iacsg_expr_eval_box(e, 1, lo, hi, 0, out, &err) == IACSG_OK && out[0] <= 0 && out[1] >= 250001,
          "[%g, %g]", out[0], out[1]);
    iacsg_expr_destroy(e);
    free(s);
    double t1 = seconds();
    /* 100000 chained bindings: each refers to the one before */
    size_t size = 100000 * 32 + 64;
    s = malloc(size);
    CHECK(s != NULL, "out of memory");
    size_t len = (size_t)snprintf(s, size, "a0 = x\n");
    for (int i = 1; i < 100000; i++)
        len += (size_t)snprintf(s + len, size - len, "a%d = a%d * 0.5 + y\n", i, i - 1);
    snprintf(s + len, size - len, "a99999 - 1\n");
    CHECK(iacsg_expr_parse(s, "<scene>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_expr_destroy(e);
    free(s);
    double t2 = seconds();
    CHECK(t1 - t0 < 5 && t2 - t1 < 5, "too slow: %.2f s and %.2f s", t1 - t0, t2 - t1);
    test_note("10^6 characters in %.0f ms, 10^5 bindings in %.0f ms", (t1 - t0) * 1e3, (t2 - t1) * 1e3);

    char *huge = malloc(((size_t)17 << 20) + 1);
    CHECK(huge != NULL, "out of memory");
    memset(huge, ' ', (size_t)17 << 20);
    huge[(size_t)17 << 20] = '\0';
    huge[0] = 'x';
    expect_error(huge, IACSG_ERR_LIMIT, 0, 0, "input too large");
    free(huge);
}

/* The enclosure at the point (x, y, z) and time t, in double. */
static void at(const char *text, double x, double y, double z, double t, double out[2]) {
    iacsg_expr *e;
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "'%s': %s", text, err.message);
    double v[8] = {x, x, y, y, z, z, t, t};
    CHECK(iacsg_expr_eval_vars(e, 1, v, out, &err) == IACSG_OK, "%s", err.message);
    iacsg_expr_destroy(e);
}

/* text at (x, y, z) is within tol of want (and its enclosure contains want when tol is 0). */
static void expect_value(const char *text, double x, double y, double z, double want, double tol) {
    double r[2];
    at(text, x, y, z, 0, r);
    CHECK(r[0] - tol <= want && want <= r[1] + tol && r[1] - r[0] <= 1e-9 + 2 * tol,
          "'%s' at (%g, %g, %g) is [%.17g, %.17g], expected %.17g", text, x, y, z, r[0], r[1], want);
}

TEST(expr_semantics) {
    expect_value("-x^2", 3, 0, 0, -9, 0);
    expect_value("2^3^2", 0, 0, 0, 512, 0);
    expect_value("x - y - z", 1, 2, 3, -4, 0);
    expect_value("x / y / z", 1, 2, 4, 0.125, 0);
    expect_value("2 * -x", 3, 0, 0, -6, 0);
    expect_value("x | y & z", 1, 5, 3, 1, 0);  /* | binds loosest: x | (y & z) = min(1, max(5, 3)) */
    expect_value("x & y \\ z", 1, 5, 3, 5, 0); /* x & (y \ z) = max(1, max(5, -3)) */
    expect_value("difference(x, y, z)", 1, 5, 3, 1, 0);
    expect_value("union(x, y, z)", 4, 2, 3, 2, 0);
    expect_value("intersection(x, y, z)", 4, 2, 3, 4, 0);
    expect_value("max(x, y, z, 7)", 4, 2, 3, 7, 0);
    expect_value("2e-1 + .5 + 1.5E1", 0, 0, 0, 15.7, 1e-12);
    expect_value("pi", 0, 0, 0, 3.141592653589793, 1e-15);
    expect_value("# comment\na = x # trailing\nb = a + 1 ; b * 2", 3, 0, 0, 8, 0);
    expect_value("a = x +\n  y\n(a\n * 2)", 1, 2, 0, 6, 0); /* line breaks after an operator and in parentheses */
    /* primitives, defaults and keywords */
    expect_value("sphere", 0, 0, 0, -1, 0);
    expect_value("sphere(0.5)", 0.5, 0, 0, 0, 1e-15);
    expect_value("sphere(r = 2)", 0, 0, 2, 0, 1e-15);
    expect_value("torus(r = 0.25)", 1, 0, 0.25, 0, 1e-15);
    expect_value("torus(2, 0.5)", 0, 2.5, 0, 0, 1e-15);
    expect_value("box(2)", 2, 1.5, -2, 0, 0);
    expect_value("box(1, 2, 3)", 0, 0, 3, 0, 0);
    expect_value("pown(x, 3)", 2, 0, 0, 8, 0);
    /* transforms: a point is in the moved solid where the inverse motion takes it into the original */
    expect_value("move(sphere, 0.5, 0, 0)", 0.5, 0, 0, -1, 0);
    expect_value("move(sphere, dz = 2)", 0, 0, 2, -1, 0);
    expect_value("translate(sphere, 1, 1, 1)", 1, 1, 1, -1, 0);
    expect_value("scale(sphere, 2)", 2, 0, 0, 0, 0);
    expect_value("scale(sphere, 1, 2, 3)", 0, 0, 3, 0, 0);
    expect_value("rotatez(move(sphere, 1), pi / 2)", 0, 1, 0, -1, 1e-12);  /* +x turns to +y */
    expect_value("rotatex(move(sphere, 0, 1, 0), pi / 2)", 0, 0, 1, -1, 1e-12); /* +y turns to +z */
    expect_value("rotatey(move(sphere, 0, 0, 1), pi / 2)", 1, 0, 0, -1, 1e-12); /* +z turns to +x */
    expect_value("rotate(move(sphere, 1), pi / 2, 0, 0, 1)", 0, 1, 0, -1, 1e-12);
    expect_value("rotate(move(sphere, 1), 2 * pi / 3, 1, 1, 1)", 0, 1, 0, -1, 1e-12); /* x -> y about (1,1,1) */
    /* blends */
    expect_value("smooth_union(x, y, 1)", 0, 0, 0, -0.25, 1e-15);
    expect_value("smooth_union(x, y, 1)", 0, 3, 0, 0, 0);
    expect_value("product(x, y)", 2, 3, 0, 6, 0);
    expect_value("morph(x, y, 0.25)", 4, 8, 0, 5, 0);
    double r[2];
    at("sigmoid_blend(x, y)", 1, 3, 0, 0.5, r); /* at t = c the blend is halfway */
    CHECK(r[0] <= 2 && 2 <= r[1] && r[1] - r[0] < 1e-12, "[%g, %g]", r[0], r[1]);
}

static int count_ops(const iacsg_expr *e, int op) {
    int n = 0;
    for (int k = 0; k < e->count; k++)
        n += e->simple.nodes[e->order[k]].op == op;
    return n;
}

TEST(expr_simplify) {
    static const struct {
        const char *text;
        int op, count;
    } cases[] = {
        {"x*x", OP_SQR, 1},          {"x^2", OP_SQR, 1},         {"x^3", OP_POWN, 1},
        {"x^-2", OP_POWN, 1},        {"x^0.5", OP_SQRT, 1},      {"x^0.25", OP_POW, 1},       {"pow(x, 10)", OP_POWN, 1},
        {"x^4 - x^2", OP_SQR, 2} /* x^4 = (x^2)^2 shares x^2 */, {"x^4", OP_POWN, 0},
        {"x^(1+1)", OP_SQR, 1},      {"sin(x) + sin(x)", OP_SIN, 1}, {"sin(x) * sin(x)", OP_SQR, 1},
        {"x + 0", OP_ADD, 0},        {"x * 1", OP_MUL, 0},       {"--x", OP_NEG, 0},
        {"x * 0.5", OP_MUL_R, 1},    {"x / 4", OP_MUL_R, 1},     {"x / 3", OP_DIV, 1},        {"1 / x", OP_RECIP, 1},
        {"x + 0.5", OP_ADD_R, 1},    {"x - 2", OP_ADD_R, 1},     {"x + 0.1", OP_ADD_R, 0},
        {"min(x, x)", OP_MIN, 0},    {"abs(-x)", OP_NEG, 0},     {"(-x)^2", OP_NEG, 0},
        {"sqrt(2) * cos(pi) + 1", OP_CONST, 1}, {"sphere(0.5)", OP_SQR, 3},
        {"min(sphere, move(sphere, 0, 0, 0))", OP_MIN, 0}, /* equal subtrees are one node */
        {"x*y + y*x", OP_MUL, 1},    {"x*y + y*x", OP_MUL_R, 1}, {"max(x, y) - max(y, x)", OP_MAX, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        iacsg_expr *e;
        CHECK(iacsg_expr_parse(cases[i].text, "<test>", &e, NULL) == IACSG_OK, "%s", cases[i].text);
        int n = count_ops(e, cases[i].op);
        char *dump = n == cases[i].count ? NULL : dag_dump(&e->simple, e->root);
        iacsg_expr_destroy(e);
        CHECK(n == cases[i].count, "'%s' has %d %s, expected %d:\n%s", cases[i].text, n, dag_op_id(cases[i].op),
              cases[i].count, dump);
    }
}

/* A sum's pair q u^2 + c u becomes q (u + c/2q)^2 - c^2/4q (implicits/simplify.c), where u occurs once: the
 * enclosure over a box is then the exact range (up to rounding) where the sum as written overestimates it; so do
 * products that come to such a sum. */
TEST(expr_squares_completed) {
    static const struct {
        const char *text;
        double lo[3], hi[3], range[2]; /* the exact range over the box */
    } cases[] = {
        {"x^4 - 5*x^2", {1, 0, 0}, {2, 0, 0}, {-6.25, -4}},        /* as written: [-19, 11] */
        {"x^2 - 3*x", {0, 0, 0}, {3, 0, 0}, {-2.25, 0}},           /* [-9, 9] */
        {"8*x^4 - 8*x^2 + 1", {-1, 0, 0}, {1, 0, 0}, {-1, 1}},     /* [-7, 9] */
        {"2*x^2 + x", {-1, 0, 0}, {1, 0, 0}, {-0.125, 3}},         /* [-1, 3] */
        {"y - x^2 + x", {0, 0, 0}, {1, 0, 0}, {0, 0.25}},          /* [-1, 1] */
        {"x - y + x^2 + 1", {-2, 1, 0}, {1, 1, 0}, {-0.25, 2}},    /* the pair apart: [-2, 4] */
        {"tangle", {1, 0, 0}, {2, 0, 0}, {5.55, 7.8}},             /* [-7.2, 22.8] */
        /* products: u (k u + c) expanded to be completed, equal powers joined, point factors pulled out */
        {"x*(x + 1)", {-1, 0, 0}, {0, 0, 0}, {-0.25, 0}},          /* [-1, 0] */
        {"4*y^3*(1 - y)^3", {0, 0, 0}, {0, 1, 0}, {0, 0.0625}},    /* [0, 4] */
        {"2*y*(3 - 2*y)", {0, 0, 0}, {0, 1.5, 0}, {0, 2.25}},      /* [0, 9] */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        iacsg_expr *e;
        iacsg_error err = {0};
        CHECK(iacsg_expr_parse(cases[i].text, "<test>", &e, &err) == IACSG_OK, "%s: %s", cases[i].text, err.message);
        for (int fp64 = 0; fp64 < 2; fp64++) {
            double r[2], slack = fp64 ? 1e-12 : 1e-5;
            CHECK(iacsg_expr_eval_box(e, fp64, cases[i].lo, cases[i].hi, 0, r, &err) == IACSG_OK, "%s", err.message);
            CHECK(r[0] <= cases[i].range[0] && r[1] >= cases[i].range[1] && r[0] >= cases[i].range[0] - slack &&
                      r[1] <= cases[i].range[1] + slack,
                  "'%s' (%s) over its box: [%.17g, %.17g], its range [%g, %g]", cases[i].text, fp64 ? "fp64" : "float",
                  r[0], r[1], cases[i].range[0], cases[i].range[1]);
        }
        iacsg_expr_destroy(e);
    }
}

TEST(expr_uses_time_and_bounds) {
    static const struct {
        const char *text;
        int uses_time;
        iacsg_bounds_proof bounded;
        double box[6];
    } cases[] = {
        {"sphere", 0, IACSG_BOUNDS_EVERYWHERE, {-1, -1, -1, 1, 1, 1}},
        {"move(sphere(0.5), 3, 0, 0)", 0, IACSG_BOUNDS_EVERYWHERE, {2.5, -0.5, -0.5, 3.5, 0.5, 0.5}},
        /* a + t (b - a): b - a is inf - inf over the unbounded boxes outside the cube */
        {"morph(sphere(0.5), sphere, t)", 1, IACSG_BOUNDS_IN_CUBE, {-1, -1, -1, 1, 1, 1}},
        {"move(sphere, t, 0, 0)", 1, IACSG_BOUNDS_EVERYWHERE, {-1, -1, -1, 2, 1, 1}},
        /* its squares completed (implicits/simplify.c), the tangle's enclosures prove all of space */
        {"tangle", 0, IACSG_BOUNDS_EVERYWHERE, {-2.2663, -2.2663, -2.2663, 2.2663, 2.2663, 2.2663}},
        {"citrus", 0, IACSG_BOUNDS_EVERYWHERE, {-0.25, 0, -0.25, 0.25, 1, 0.25}}, /* was 53.8 deep in z */
        /* its y slabs need some 10^4 boxes (x^2 thrice in its polynomial): it was proven 128 deep in y */
        {"bretzel4", 0, IACSG_BOUNDS_EVERYWHERE, {-2.0689, -1.2310, -0.18257, 2.0689, 1.2310, 0.18257}},
        {"cylinder", 0, IACSG_BOUNDS_NONE, {0, 0, 0, 0, 0, 0}},
        {"gyroid", 0, IACSG_BOUNDS_NONE, {0, 0, 0, 0, 0, 0}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        iacsg_expr *e;
        CHECK(iacsg_expr_parse(cases[i].text, "<test>", &e, NULL) == IACSG_OK, "%s", cases[i].text);
        double box[6];
        int uses = iacsg_expr_uses_time(e);
        iacsg_bounds_proof bounded = iacsg_expr_bounds(e, (double[2]){0, 1}, box);
        iacsg_expr_destroy(e);
        CHECK(uses == cases[i].uses_time, "'%s': uses_time %d", cases[i].text, uses);
        CHECK(bounded == cases[i].bounded, "'%s': bounds %d", cases[i].text, (int)bounded);
        for (int k = 0; bounded && k < 6; k++) /* contains the true box, and not more than 1.5 times wider */
            CHECK(k < 3 ? box[k] <= cases[i].box[k] && box[k] >= cases[i].box[k] - 0.5 * (cases[i].box[k + 3] - cases[i].box[k])
                        : box[k] >= cases[i].box[k] && box[k] <= cases[i].box[k] + 0.5 * (cases[i].box[k] - cases[i].box[k - 3]),
                  "'%s': bound %d is %g, the surface's is %g", cases[i].text, k, box[k], cases[i].box[k]);
    }
}

/* Every scene in examples/ compiles, and a plain one has proven bounds (the gallery renders them). Scenes with
 * regions and surfaces compile every solid (tests/t_scene_parse.c looks into them). */
TEST(expr_examples_compile) {
    char pattern[1024];
    snprintf(pattern, sizeof pattern, "%s/examples/*.csg", test_source_dir());
    glob_t g;
    CHECK(glob(pattern, 0, NULL, &g) == 0 && g.gl_pathc >= 15, "examples/*.csg: fewer than 15 scenes");
    for (size_t i = 0; i < g.gl_pathc; i++) {
        FILE *f = fopen(g.gl_pathv[i], "rb");
        char text[8192];
        size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
        if (f)
            fclose(f);
        text[n] = '\0';
        iacsg_scene *s;
        iacsg_error err = {0};
        double box[6];
        CHECK(n > 0 && iacsg_scene_parse(text, g.gl_pathv[i], &s, &err) == IACSG_OK, "%s:%d:%d: %s", g.gl_pathv[i],
              err.line, err.column, err.message);
        int bounded = !s->expr || iacsg_expr_bounds(s->expr, (double[2]){0, 0.5}, box);
        iacsg_scene_destroy(s);
        CHECK(bounded, "%s: no bounds found", g.gl_pathv[i]);
    }
    test_note("%zu scenes", g.gl_pathc);
    globfree(&g);
}

/* Every library entry compiles when called with its required arguments (its texts parse and lower). */
TEST(expr_library_entries_compile) {
    for (int i = 0; i < lib_count; i++) {
        const lib_entry *l = &lib_entries[i];
        char text[256];
        if (l->kind == LIB_PRIMITIVE)
            snprintf(text, sizeof text, "%s", l->name);
        else if (l->kind == LIB_TRANSFORM)
            snprintf(text, sizeof text, "%s(sphere, 0.3)", l->name);
        else
            snprintf(text, sizeof text, "%s(sphere, box)", l->name);
        iacsg_expr *e;
        iacsg_error err = {0};
        CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "'%s': %s", text, err.message);
        iacsg_expr_destroy(e);
    }
    test_note("%d entries", lib_count);
}
