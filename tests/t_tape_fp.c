/* tests/t_tape_fp.c -- the tape interpreter (implicits/tape.c, kernels/tape_eval.h) on the device, float and
 * double, over SIMD lanes as the kernels run it:
 *   tape_matches_compiled: for the device tests' expressions (every primitive, every op, random texts), the
 *     interpreter's union of all groups, skipping nothing, is bit for bit the compiled iacsg_Fv over random
 *     boxes (so it has every property the compiled code is tested for); and for those and for unions of 24 to
 *     40 parts (spheres, caps undefined off their disc, random texts), the interpreter's value encloses the MPFR
 *     value at points of the boxes, and with the parts skipped by their boxes it still holds every value <= 0
 *     of the expression and is > 0 somewhere wherever the expression is > 0 (what the walk decides from); and
 *     each box's list of parts (tape_tile_parts, the tile pass's) gives the union's lower bound bit for bit on
 *     the box, and on a sub-box, skipping by boxes too, the same guarantee against MPFR.
 *   tape_fallback: a part that needs more registers than the interpreter has is refused with a message, and the
 *     renderer compiles it instead, saying so.
 *   tape_auto_takes_large_unions: -tape auto interprets a union of 128 parts that need fewer operations than its
 *     threshold of operations. */
#include "clrt.h"
#include "implicits/tape.h"
#include "kernels/params.h"
#include "t_expr_oracle.h"
#include "t_lanes_run.h"
#include "t_tape_pack.h"
#include "render.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

extern const char iacsg_cl_ia[], iacsg_cl_tape_kernels[];

#define TAPE_IN 8  /* a query: the box x0, x1, ..., t1 */
/* compiled [lo, hi] (NaN without), interpreted, interpreted skipping parts; the box's own list of parts
 * (tape_tile_parts: its count, -1 when full) and the interpreted value over its parts; over a sub-box (the
 * lower half on every axis), the interpreted value and the value over the box's list */
#define TAPE_OUT 13

static const char kernel_head[] =
    "__kernel void tape_check(__global const int *which, __global const uint *tapes, __global const uint *at,\n"
    "                         __global const ia_real *in, __global ia_real *out, __global ushort *records) {\n"
    "    size_t g = get_global_id(0);\n"
    "    ia_real v[8][IA_VW];\n"
    "    for (int l = 0; l < IA_VW; l++)\n"
    "        for (int k = 0; k < 8; k++)\n"
    "            v[k][l] = in[8 * (g * IA_VW + l) + k];\n"
    "    iav b[4];\n"
    "    for (int c = 0; c < 4; c++)\n"
    "        b[c] = iav_make(IAV_LOAD(v[2 * c]), IAV_LOAD(v[2 * c + 1]));\n"
    "    iav r = iav_point(NAN), s = iav_point(IA_INF), u = iav_point(IA_INF);\n"
    "    tape_ptr tape = tapes + at[which[g]];\n"
    "    ia_real hull[6];\n"
    "    tape_hull((ia_maskv)-1, b[0], b[1], b[2], hull);\n"
    "    iav h[3], sub_s = iav_point(IA_INF);\n"
    "    for (int c = 0; c < 3; c++) { /* the sub-box: the lower half, where the midpoint is finite */\n"
    "        ia_realv m = b[c].lo * (ia_real)0.5 + b[c].hi * (ia_real)0.5;\n"
    "        h[c] = iav_make(b[c].lo, select(b[c].hi, m, isfinite(m) & (m >= b[c].lo) & (m <= b[c].hi)));\n"
    "    }\n"
    "    for (int grp = 0; grp < IACSG_GROUPS; grp++) {\n"
    "        s = iav_min(s, tape_group(tape, grp, 0, (ia_maskv)-1, b[0], b[1], b[2], b[3]));\n"
    "        u = iav_min(u, tape_group(tape, grp, hull, (ia_maskv)-1, b[0], b[1], b[2], b[3]));\n"
    "        sub_s = iav_min(sub_s, tape_group(tape, grp, 0, (ia_maskv)-1, h[0], h[1], h[2], b[3]));\n"
    "    }\n"
    "    ulong groups[IA_VW];\n"
    "    ushort lists[IA_VW][TAPE_TILE_RECORD];\n"
    "    tape_tile_parts(tape, ~(ulong)0, b[0], b[1], b[2], b[3], groups, lists);\n"
    "    ia_real lo[5][IA_VW]; /* each lane over its own list, the list in records[g] */\n"
    "    __global ushort *record = records + TAPE_TILE_RECORD * g;\n"
    "    for (int l = 0; l < IA_VW; l++) {\n"
    "        for (int k = 0; k < TAPE_TILE_RECORD; k++)\n"
    "            record[k] = lists[l][k];\n"
    "        iav on_box, on_sub;\n"
    "        int listed = tape_lists(tape, record, 0, 0, 0, (ia_maskv)-1, b[0], b[1], b[2], b[3], &on_box);\n"
    "        tape_lists(tape, record, 0, 0, 1, (ia_maskv)-1, h[0], h[1], h[2], b[3], &on_sub);\n"
    "        ia_real a[IA_VW];\n"
    "        lo[0][l] = listed ? lists[l][0] : -1;\n"
    "        IAV_STORE(on_box.lo, a); lo[1][l] = listed ? a[l] : NAN;\n"
    "        IAV_STORE(on_box.hi, a); lo[2][l] = listed ? a[l] : NAN;\n"
    "        IAV_STORE(on_sub.lo, a); lo[3][l] = listed ? a[l] : NAN;\n"
    "        IAV_STORE(on_sub.hi, a); lo[4][l] = listed ? a[l] : NAN;\n"
    "    }\n"
    "    switch (which[g]) {\n";
static const char kernel_tail[] = "    }\n"
                                  "    ia_real o[8][IA_VW];\n"
                                  "    IAV_STORE(sub_s.lo, o[6]);\n"
                                  "    IAV_STORE(sub_s.hi, o[7]);\n"
                                  "    IAV_STORE(r.lo, o[0]);\n"
                                  "    IAV_STORE(r.hi, o[1]);\n"
                                  "    IAV_STORE(s.lo, o[2]);\n"
                                  "    IAV_STORE(s.hi, o[3]);\n"
                                  "    IAV_STORE(u.lo, o[4]);\n"
                                  "    IAV_STORE(u.hi, o[5]);\n"
                                  "    for (int l = 0; l < IA_VW; l++)\n"
                                  "        for (int k = 0; k < 13; k++)\n"
                                  "            out[13 * (g * IA_VW + l) + k] =\n"
                                  "                k < 6 ? o[k][l] : k == 6 ? lo[0][l] : k < 9 ? lo[k - 6][l]\n"
                                  "                : k < 11 ? o[k - 3][l] : lo[k - 8][l];\n"
                                  "}\n";

/* Runs ia/, the interpreter, sources[1 .. n-1] and the check kernel with `cases` over `items` work-items of
 * which[] expressions, whose tapes are at words at[] of tapes; fills out (TAPE_OUT per query) from in (TAPE_IN
 * exact doubles per query, all box bounds, rounded outward to floats without fp64). */
static void run_check(const char **sources, int n, const char *cases, size_t items, const int *which,
                      const unsigned *tapes, size_t tape_words, const unsigned *at, int nexprs, const double *in,
                      double *out) {
    char *kernel = lanes_kernel_source(kernel_head, cases, kernel_tail);
    sources[n] = iacsg_cl_tape_kernels;
    sources[n + 1] = kernel;
    lanes_run(&(lanes_job){.sources = sources, .nsources = (size_t)n + 2, .kernel = "tape_check", .items = items,
                           .which = which,
                           .extra = {{tapes, tape_words * sizeof(unsigned)}, {at, (size_t)nexprs * sizeof(unsigned)}},
                           .nextra = 2, .in = in, .in_per_query = TAPE_IN, .bounds_per_query = TAPE_IN, .out = out,
                           .out_per_query = TAPE_OUT, .scratch_per_item = {TAPE_TILE_RECORD * sizeof(cl_ushort)},
                           .nscratch = 1});
    free(kernel);
}

/* A union of `parts` parts into buf: spheres, caps (sqrt(r^2 - (x-a)^2 - (y-b)^2) - (z-c), undefined off the
 * disc: there the union takes the others) and random texts of depth 2, at random places in [-1.5, 1.5]^3. */
static void random_union(test_rng_t *r, int parts, char *buf, size_t size) {
    size_t used = (size_t)snprintf(buf, size, "min(");
    for (int j = 0; j < parts; j++) {
        double a = 3 * test_rand_unit(r) - 1.5, b = 3 * test_rand_unit(r) - 1.5, c = 3 * test_rand_unit(r) - 1.5;
        double radius = 0.05 + 0.4 * test_rand_unit(r);
        const char *sep = j ? ", " : "";
        if (j % 3 == 0) {
            used += (size_t)snprintf(buf + used, size - used, "%s(x-%.4f)^2+(y-%.4f)^2+(z-%.4f)^2-%.4f", sep, a, b, c,
                                     radius * radius);
        } else if (j % 3 == 1) {
            used += (size_t)snprintf(buf + used, size - used, "%ssqrt(%.4f-(x-%.4f)^2-(y-%.4f)^2)-(z-%.4f)", sep,
                                     radius * radius, a, b, c);
        } else {
            char part[4096];
            expr_random_text(r, 2, part, sizeof part);
            used += (size_t)snprintf(buf + used, size - used, "%s%s", sep, part);
        }
        CHECK(used < size - 1, "union text too long");
    }
    snprintf(buf + used, size - used, ")");
}

/* The check kernel's sub-box of [lo, hi] on one axis (its bounds rounded outward to floats without fp64): from
 * its lower bound to the midpoint, or to hi where that is not finite; the midpoint a unit in the last place lower
 * (whether the device contracts the sum into an fma or not), so that points of sub are in the kernel's. */
static void kernel_sub_box(double lo, double hi, double sub[2]) {
    double l = lo, h = hi, m;
    if (FP64) {
        m = nextafter(lo * 0.5 + hi * 0.5, -INFINITY);
    } else {
        float lf = (float)lo, hf = (float)hi;
        if ((double)lf > lo)
            lf = nextafterf(lf, -INFINITY);
        if ((double)hf < hi)
            hf = nextafterf(hf, INFINITY);
        l = lf;
        h = hf;
        m = nextafterf(lf * 0.5f + hf * 0.5f, -INFINITY);
    }
    sub[0] = l;
    sub[1] = isfinite(l * 0.5 + h * 0.5) ? fmax(l, fmin(h, m)) : h;
}

#define MAX_EXPRS 72
#define UNIONS 6
#define ITEMS 6 /* work-items per expression: 6 x 16 boxes */

TEST_FP(tape_matches_compiled) {
    static char texts[MAX_EXPRS + UNIONS][EXPR_TEXT_SIZE];
    iacsg_expr *exprs[MAX_EXPRS + UNIONS];
    int n = expr_test_texts(test_rng(), texts, MAX_EXPRS);
    for (int u = 0; u < UNIONS; u++)
        random_union(test_rng(), 24 + 3 * u, texts[n + u], EXPR_TEXT_SIZE);
    int total = n + UNIONS;
    const char *sources[MAX_EXPRS + 4] = {iacsg_cl_ia};
    char *interpreter = tape_cl();
    CHECK(interpreter != NULL, "out of memory");
    sources[1] = interpreter;
    static char cases[MAX_EXPRS * 100];
    size_t used = 0, words = 0;
    unsigned at[MAX_EXPRS + UNIONS], *tapes = NULL;
    long skipping = 0;
    for (int i = 0; i < total; i++) {
        iacsg_error err = {0};
        CHECK(iacsg_expr_parse(texts[i], "<test>", &exprs[i], &err) == IACSG_OK, "'%s': %s", texts[i], err.message);
        iacsg_tape tape;
        CHECK(tape_build(&exprs[i]->simple, exprs[i]->root, FP64, &tape, &err) == IACSG_OK, "'%s': %s", texts[i],
              err.message);
        skipping += tape.bounded_parts;
        at[i] = tape_pack(&tapes, &words, &tape);
        tape_free(&tape);
        if (i >= n)
            continue; /* a union in groups: its compiled code would define IACSG_GROUPS */
        char prefix[16];
        snprintf(prefix, sizeof prefix, "e%d", i);
        char *src = NULL;
        CHECK(iacsg_expr_emit_cl(exprs[i], prefix, &src, &err) == IACSG_OK, "%s", err.message);
        CHECK(!strstr(src, "IACSG_GROUPS"), "'%s': a union in groups; the test calls e<k>_Fv", texts[i]);
        sources[2 + i] = src;
        used += (size_t)snprintf(cases + used, sizeof cases - used,
                                 "    case %d: r = e%d_Fv(b[0], b[1], b[2], b[3]); break;\n", i, i);
    }
    size_t items = (size_t)total * ITEMS, q = items * PACKET_LANES;
    int *which = malloc(items * sizeof *which);
    double *in = malloc(TAPE_IN * q * sizeof *in), *out = malloc(TAPE_OUT * q * sizeof *out);
    CHECK(which && in && out, "out of memory");
    for (size_t g = 0; g < items; g++)
        which[g] = (int)(g / ITEMS);
    for (size_t k = 0; k < q; k++) {
        expr_random_box(test_rng(), in + TAPE_IN * k);
        if (which[k / PACKET_LANES] >= n && k % 4 == 0) /* a union over most of its parts: lists too long */
            for (int c = 0; c < 6; c++)
                in[TAPE_IN * k + c] = c % 2 ? 1.6 : -1.6;
    }
    run_check(sources, 2 + n, cases, items, which, tapes, words, at, total, in, out);
    for (int i = 0; i < n; i++)
        free((char *)sources[2 + i]);
    free(interpreter);
    free(tapes);

    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    long same = 0, values = 0, skipped = 0, listed = 0, full = 0, list_parts = 0, shorter = 0, sub_values = 0;
    for (size_t k = 0; k < q; k++) {
        int x = which[k / PACKET_LANES];
        const double *v = in + TAPE_IN * k, *o = out + TAPE_OUT * k;
        if (x < n) { /* bit for bit the compiled code (NaN: the same NaN-ness) */
            for (int c = 0; c < 2; c++)
                CHECK(o[c] == o[2 + c] || (o[c] != o[c] && o[2 + c] != o[2 + c]),
                      "'%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a]: compiled [%a, %a], interpreted [%a, %a]",
                      texts[x], v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], o[0], o[1], o[2], o[3]);
            same++;
        }
        skipped += o[4] != o[2] || o[5] != o[3];
        /* the box's own list (tape_tile_parts): the parts left out are positive on the box or dominated there,
         * so its bounds are the whole union's, bit for bit, except where those are > 0 (then higher) */
        if (o[6] >= 0) {
            listed++;
            list_parts += (long)o[6];
            CHECK((o[7] == o[2] || (o[7] != o[7] && o[2] != o[2]) || (o[2] > 0 && o[7] > o[2])) &&
                      (o[8] == o[3] || (o[8] != o[8] && o[3] != o[3]) || (o[3] > 0 && o[8] > o[3])),
                  "'%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a]: interpreted [%a, %a], over its list of "
                  "%g parts [%a, %a]",
                  texts[x], v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], o[2], o[3], o[6], o[7], o[8]);
            shorter += o[8] != o[3];
        } else {
            full++;
        }
        for (int s = 0; s < 6; s++) {
            double p[4];
            expr_random_point(test_rng(), v, p);
            if (!expr_oracle(exprs[x], p, y))
                continue;
            values++;
            int ok = mpfr_cmp_d(y, o[2]) >= 0 && mpfr_cmp_d(y, o[3]) <= 0;
            /* skipping: every value <= 0 kept; a value > 0 leaves the enclosure > 0 somewhere */
            int ok_skipping = mpfr_sgn(y) <= 0 ? mpfr_cmp_d(y, o[4]) >= 0 && mpfr_cmp_d(y, o[5]) <= 0 : o[5] > 0;
            CHECK(ok && ok_skipping,
                  "'%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a]: interpreted [%a, %a], skipping [%a, %a], "
                  "but at (%a, %a, %a, %a) the value is %.20g",
                  texts[x], v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], o[2], o[3], o[4], o[5], p[0], p[1], p[2],
                  p[3], mpfr_get_d(y, MPFR_RNDN));
        }
        /* the list on a sub-box (the lower ~half on every axis, inside the kernel's), skipping by the parts' boxes:
         * as skipping, every value <= 0 held, and > 0 somewhere wherever the expression is > 0 */
        double sub[TAPE_IN];
        memcpy(sub, v, sizeof sub);
        for (int c = 0; c < 3 && o[6] >= 0; c++)
            kernel_sub_box(v[2 * c], v[2 * c + 1], sub + 2 * c);
        for (int s = 0; s < 6 && o[6] >= 0; s++) {
            double p[4];
            expr_random_point(test_rng(), sub, p);
            if (!expr_oracle(exprs[x], p, y))
                continue;
            sub_values++;
            CHECK(mpfr_sgn(y) <= 0 ? mpfr_cmp_d(y, o[11]) >= 0 && mpfr_cmp_d(y, o[12]) <= 0 : o[12] > 0,
                  "'%s' over x [%a, %a] y [%a, %a] z [%a, %a] t [%a, %a]: on the sub-box, over the box's list "
                  "[%a, %a] (all its parts [%a, %a]), but at (%a, %a, %a, %a) the value is %.20g",
                  texts[x], v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], o[11], o[12], o[9], o[10], p[0], p[1],
                  p[2], p[3],
                  mpfr_get_d(y, MPFR_RNDN));
        }
    }
    mpfr_clear(y);
    for (int i = 0; i < total; i++)
        iacsg_expr_destroy(exprs[i]);
    free(which);
    free(in);
    free(out);
    test_note("%d expressions and %d unions, %zu boxes: %ld bit for bit the compiled code, %ld values checked, "
              "%ld boxes where parts were skipped (%ld parts boxed)",
              n, UNIONS, q, same, values, skipped, skipping);
    test_note("tile lists: %ld boxes listed (%.1f parts a list, %ld with an upper bound raised by a part left out, "
              "%ld sub-box values), %ld full", listed, listed ? (double)list_parts / listed : 0.0, shorter, sub_values,
              full);
    CHECK(same > 5000 && values > 20000 && skipped > 100 && listed > 1000 && full > 10 && shorter > 10 &&
              sub_values > 5000,
          "too little checked to mean anything");
}

/* The program the renderer takes for `e` under `config` (iacsg_renderer_program's note, also noted); destroys e. */
static void program_of(iacsg_expr *e, const iacsg_render_config *config, char *note, size_t size) {
    iacsg_error err = {0};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s", err.message);
    snprintf(note, size, "%s", iacsg_renderer_program(r));
    iacsg_renderer_destroy(r);
    test_note("%s", note);
}

TEST_FP(tape_fallback) {
    /* (s1 + ... + s40) * (s1 * ... * s40): every s_k is live from its sum to its product, 40 values at once
     * where the interpreter has TAPE_SLOTS registers */
    static char text[16384];
    size_t used = 0;
    for (int half = 0; half < 2; half++) {
        used += (size_t)snprintf(text + used, sizeof text - used, "%s(", half ? "*" : "");
        for (int k = 0; k < 40; k++)
            used += (size_t)snprintf(text + used, sizeof text - used, "%s(x+%d)*(y-%d)", k ? (half ? "*" : "+") : "",
                                     k + 1, k + 2);
        used += (size_t)snprintf(text + used, sizeof text - used, ")");
    }
    CHECK(used < sizeof text, "text too long");
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_tape tape;
    iacsg_status st = tape_build(&e->simple, e->root, FP64, &tape, &err);
    if (st == IACSG_OK)
        tape_free(&tape);
    CHECK(st == IACSG_ERR_LIMIT && strstr(err.message, "registers"), "tape_build: %s",
          st == IACSG_OK ? "the tape fit" : err.message);
    iacsg_render_config config = {.fp64 = FP64, .tape = IACSG_TAPE_ALWAYS};
    iacsg_renderer *r = NULL;
    st = iacsg_renderer_create_expr(e, &config, &r, &err);
    CHECK(st == IACSG_ERR_LIMIT && r == NULL, "with the tape required: %s", st == IACSG_OK ? "built" : err.message);
    config.tape = IACSG_TAPE_AUTO;
    config.tape_min_nodes = e->count; /* this one is over the threshold */
    char note[200];
    program_of(e, &config, note, sizeof note);
    CHECK(strncmp(note, "compiled (", 10) == 0 && strstr(note, "registers"), "the renderer says: %s", note);
}

/* IACSG_TAPE_AUTO interprets a union of IACSG_TAPE_MIN_PARTS parts however few operations its parts need: a grid
 * of 128 spheres shares their (x - c)^2 among the spheres of a plane, 461 operations, under IACSG_TAPE_MIN_NODES. */
TEST_FP(tape_auto_takes_large_unions) {
    static char text[16384];
    size_t used = (size_t)snprintf(text, sizeof text, "min(");
    for (int k = 0; k < IACSG_TAPE_MIN_PARTS; k++)
        used += (size_t)snprintf(text + used, sizeof text - used, "%s(x-%g)^2+(y-%g)^2+(z-%g)^2-0.01", k ? ", " : "",
                                 -1.5 + 0.2 * (k % 16), -1.5 + 0.4 * (k / 16 % 4), -1.5 + 1.0 * (k / 64));
    snprintf(text + used, sizeof text - used, ")");
    CHECK(used < sizeof text - 1, "text too long");
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    CHECK(e->count < IACSG_TAPE_MIN_NODES, "%d operations: the parts' rule is not what is tested", e->count);
    iacsg_render_config config = {.fp64 = FP64, .tape = IACSG_TAPE_AUTO};
    char note[200];
    program_of(e, &config, note, sizeof note);
    CHECK(strncmp(note, "interpreted (tape: 128 parts", 28) == 0, "the renderer says: %s", note);
}
