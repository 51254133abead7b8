/* tests/t_expr_props_fp.c -- the containment contract for compiled expressions on the host, in float and
 * double intervals: for random expression trees, every primitive and every op, the host enclosure over a random
 * box contains the MPFR value of the expression as written at points of the box. Each test also requires a
 * minimum share of points in the domain, so that an oracle or a generator that leaves everything undefined fails. */
#include "t_expr_oracle.h"
#include <stdio.h>
#include <stdlib.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

/* Checks `boxes` random boxes with `points` points each; returns the number of points checked. */
static long check_expr(const char *text, int boxes, int points) {
    iacsg_expr *e;
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "'%s' does not compile: %s", text, err.message);
    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    long checked = 0;
    for (int b = 0; b < boxes; b++) {
        double v[8], r[2], p[4];
        expr_random_box(test_rng(), v);
        CHECK(iacsg_expr_eval_vars(e, FP64, v, r, &err) == IACSG_OK, "%s", err.message);
        for (int k = 0; k < points; k++) {
            expr_random_point(test_rng(), v, p);
            if (!expr_oracle(e, p, y))
                continue;
            checked++;
            if (mpfr_cmp_d(y, r[0]) < 0 || mpfr_cmp_d(y, r[1]) > 0) {
                char *dump = dag_dump(&e->simple, e->root);
                printf("%s", dump ? dump : "");
                free(dump);
                CHECK(0,
                      "'%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a] gave [%a, %a], but at (%a, %a, %a, %a) "
                      "the value is %.20g",
                      text, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], r[0], r[1], p[0], p[1], p[2], p[3],
                      mpfr_get_d(y, MPFR_RNDN));
            }
        }
    }
    mpfr_clear(y);
    iacsg_expr_destroy(e);
    return checked;
}

TEST_FP(expr_contains_random_trees) {
    long n = test_iters(1500), checked = 0;
    char text[8192];
    for (long i = 0; i < n; i++) {
        expr_random_text(test_rng(), 4, text, sizeof text);
        checked += check_expr(text, 4, 6);
    }
    test_note("%ld random expressions, %ld points in the domain checked", n, checked);
    CHECK(checked >= n * 4 * 6 / 2, "only %ld of %ld points in the domain", checked, n * 4 * 6);
}

TEST_FP(expr_contains_every_primitive) {
    const char *names[64];
    int n = expr_primitive_names(names, 64);
    long checked = 0, boxes = test_iters(40);
    for (int i = 0; i < n; i++) {
        long here = check_expr(names[i], (int)boxes, 6);
        CHECK(here == boxes * 6, "%s: only %ld of %ld points in the domain", names[i], here, boxes * 6);
        checked += here;
    }
    test_note("%d primitives, %ld points checked", n, checked);
}

TEST_FP(expr_contains_every_op) {
    int used[OP_COUNT] = {0};
    long checked = 0;
    for (int i = 0; i < expr_every_op_count; i++) {
        iacsg_expr *e;
        CHECK(iacsg_expr_parse(expr_every_op_texts[i], "<test>", &e, NULL) == IACSG_OK, "%s", expr_every_op_texts[i]);
        for (int k = 0; k < e->count; k++)
            used[e->simple.nodes[e->order[k]].op] = 1;
        iacsg_expr_destroy(e);
        /* every op is defined on at least a quarter of the random boxes' points (log, sqrt, pow: x > 0) */
        long boxes = test_iters(200), here = check_expr(expr_every_op_texts[i], (int)boxes, 4);
        CHECK(4 * here >= boxes * 4, "'%s': only %ld of %ld points in the domain", expr_every_op_texts[i], here,
              boxes * 4);
        checked += here;
    }
    for (int op = OP_NEG; op < OP_COUNT; op++)
        CHECK(used[op], "no test expression exercises %s: add one to expr_every_op_texts", dag_op_id(op));
    test_note("%d ops, %ld points checked", OP_COUNT - OP_NEG, checked);
}
