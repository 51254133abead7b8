/* tests/t_tape_slope_fp.c -- the tape interpreter's derivative along a ray (kernels/tape_eval.h: tape_lists_dt,
 * for interval Newton and the mean value form in kernels/packet.h), float and double, over SIMD lanes:
 *   tape_slope_encloses: for unions of spheres, cubes (max of abs: kinks) and quartics ((x - a)^4: squares of
 *     squares, one instruction each, tape.c's TAPE_THEN_SQR) over the boxes of random segments of rays, a
 *     box's list of parts (tape_tile_parts) gives through tape_lists_dt the value tape_lists gives, bit for bit;
 *     a slope that holds every difference quotient (F(p) - F(q)) / (s_p - s_q) of the union at points p, q of the
 *     segment (MPFR) where both values are <= 0 (where the parts left out are not the min: elsewhere the slope is
 *     that of the min of the parts kept, which has the same roots); and at the segment's midpoint a value that
 *     holds the union's wherever that is <= 0. A part dropped or a derivative too narrow fails it. */
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

/* A query: the segment's box x0, x1, ..., t0, t1, then its direction and its midpoint (exact in float). */
#define SLOPE_IN 14
/* Out: listed (1, or 0 when the list is full), tape_lists_dt's value, tape_lists's, the slope, the midpoint's. */
#define SLOPE_OUT 9

static const char kernel_source[] =
    "__kernel void slope_check(__global const int *which, __global const uint *tapes, __global const uint *at,\n"
    "                          __global const ia_real *in, __global ia_real *out, __global ushort *records) {\n"
    "    size_t g = get_global_id(0);\n"
    "    ia_real v[14][IA_VW];\n"
    "    for (int l = 0; l < IA_VW; l++)\n"
    "        for (int k = 0; k < 14; k++)\n"
    "            v[k][l] = in[14 * (g * IA_VW + l) + k];\n"
    "    iav b[4], d[3], m[3];\n"
    "    for (int c = 0; c < 4; c++)\n"
    "        b[c] = iav_make(IAV_LOAD(v[2 * c]), IAV_LOAD(v[2 * c + 1]));\n"
    "    for (int c = 0; c < 3; c++) {\n"
    "        d[c] = iav_make(IAV_LOAD(v[8 + c]), IAV_LOAD(v[8 + c]));\n"
    "        m[c] = iav_make(IAV_LOAD(v[11 + c]), IAV_LOAD(v[11 + c]));\n"
    "    }\n"
    "    tape_ptr tape = tapes + at[which[g]];\n"
    "    ulong groups[IA_VW];\n"
    "    ushort lists[IA_VW][TAPE_TILE_RECORD];\n"
    "    tape_tile_parts(tape, ~(ulong)0, b[0], b[1], b[2], b[3], groups, lists);\n"
    "    __global ushort *record = records + TAPE_TILE_RECORD * g;\n"
    "    for (int l = 0; l < IA_VW; l++) { /* each lane over its own list, all lanes' boxes skipping */\n"
    "        for (int k = 0; k < TAPE_TILE_RECORD; k++)\n"
    "            record[k] = lists[l][k];\n"
    "        iav r, plain, slope, at_m;\n"
    "        int listed = tape_lists_dt(tape, record, 0, 0, (ia_maskv)-1, b[0], b[1], b[2], b[3], d, m[0], m[1],\n"
    "                                   m[2], &r, &slope, &at_m);\n"
    "        tape_lists(tape, record, 0, 0, 1, (ia_maskv)-1, b[0], b[1], b[2], b[3], &plain);\n"
    "        iav o[4] = {r, plain, slope, at_m};\n"
    "        __global ia_real *lane = out + 9 * (g * IA_VW + l);\n"
    "        lane[0] = listed;\n"
    "        for (int k = 0; k < 4; k++) {\n"
    "            ia_real lo[IA_VW], hi[IA_VW];\n"
    "            IAV_STORE(o[k].lo, lo);\n"
    "            IAV_STORE(o[k].hi, hi);\n"
    "            lane[1 + 2 * k] = lo[l];\n"
    "            lane[2 + 2 * k] = hi[l];\n"
    "        }\n"
    "    }\n"
    "}\n";

/* A union of `parts` spheres, cubes and quartic blobs at random places in [-1.5, 1.5]^3, into buf. */
static void newton_union(test_rng_t *r, int parts, char *buf, size_t size) {
    size_t used = (size_t)snprintf(buf, size, "min(");
    for (int j = 0; j < parts; j++) {
        double a = 3 * test_rand_unit(r) - 1.5, b = 3 * test_rand_unit(r) - 1.5, c = 3 * test_rand_unit(r) - 1.5;
        double s = 0.1 + 0.4 * test_rand_unit(r);
        const char *sep = j ? ", " : "";
        const char *form = j % 3 == 0   ? "%s(x-%.4f)^2+(y-%.4f)^2+(z-%.4f)^2-%.4f"
                           : j % 3 == 1 ? "%smax(abs(x-%.4f),abs(y-%.4f),abs(z-%.4f))-%.4f"
                                        : "%s(x-%.4f)^4+(y-%.4f)^4+(z-%.4f)^4-%.4f";
        used += (size_t)snprintf(buf + used, size - used, form, sep, a, b, c, j % 3 == 1 ? s : s * s);
        CHECK(used < size - 1, "union text too long");
    }
    snprintf(buf + used, size - used, ")");
}

/* A multiple of 2^-8 in [-m, m] (exact in float, and so are its sums and products below). */
static double dyadic(test_rng_t *r, double m) { return round((2 * test_rand_unit(r) - 1) * m * 256) / 256; }

#define UNIONS 8
#define ITEMS 24 /* work-items per union: 24 x 16 segments */
#define PAIRS 6

TEST_FP(tape_slope_encloses) {
    static char texts[UNIONS][EXPR_TEXT_SIZE];
    iacsg_expr *exprs[UNIONS];
    const char *sources[3] = {iacsg_cl_ia};
    char *interpreter = tape_cl();
    CHECK(interpreter != NULL, "out of memory");
    sources[1] = interpreter;
    size_t words = 0;
    unsigned at[UNIONS], *tapes = NULL;
    long squared = 0;
    for (int i = 0; i < UNIONS; i++) {
        newton_union(test_rng(), 3 + 4 * i, texts[i], EXPR_TEXT_SIZE);
        iacsg_error err = {0};
        CHECK(iacsg_expr_parse(texts[i], "<test>", &exprs[i], &err) == IACSG_OK, "'%s': %s", texts[i], err.message);
        iacsg_tape tape;
        CHECK(tape_build(&exprs[i]->simple, exprs[i]->root, FP64, &tape, &err) == IACSG_OK, "'%s': %s", texts[i],
              err.message);
        CHECK(tape.newton, "'%s': no Newton on its tape", texts[i]);
        const unsigned *code = tape.words + tape.words[TAPE_W_CODE];
        for (int k = 0; k < tape.instructions; k++)
            squared += (code[TAPE_INSTR_WORDS * k] >> 8 & TAPE_THEN_SQR) != 0;
        at[i] = tape_pack(&tapes, &words, &tape);
        tape_free(&tape);
    }
    size_t items = (size_t)UNIONS * ITEMS, q = items * PACKET_LANES;
    int *which = malloc(items * sizeof *which);
    double *in = malloc(SLOPE_IN * q * sizeof *in), *out = malloc(SLOPE_OUT * q * sizeof *out);
    double *from = malloc(3 * q * sizeof *from), *length = malloc(q * sizeof *length);
    CHECK(which && in && out && from && length, "out of memory");
    for (size_t g = 0; g < items; g++)
        which[g] = (int)(g / ITEMS);
    for (size_t k = 0; k < q; k++) { /* from + s d, s in [0, length]: a segment of 2^-8 to 1 */
        double *v = in + SLOPE_IN * k;
        length[k] = ldexp(1, -(int)(test_rand_unit(test_rng()) * 9));
        for (int c = 0; c < 3; c++) {
            from[3 * k + c] = dyadic(test_rng(), 1.5);
            double to = from[3 * k + c], d = dyadic(test_rng(), 1);
            to += d * length[k];
            v[2 * c] = fmin(from[3 * k + c], to);
            v[2 * c + 1] = fmax(from[3 * k + c], to);
            v[8 + c] = d;
            v[11 + c] = from[3 * k + c] + d * length[k] * 0.5;
        }
        v[6] = v[7] = 0; /* t */
    }
    char *kernel = lanes_kernel_source(kernel_source, "", "");
    sources[2] = iacsg_cl_tape_kernels;
    const char *all[4] = {sources[0], sources[1], sources[2], kernel};
    lanes_run(&(lanes_job){.sources = all, .nsources = 4, .kernel = "slope_check", .items = items, .which = which,
                           .extra = {{tapes, words * sizeof(unsigned)}, {at, UNIONS * sizeof(unsigned)}},
                           .nextra = 2, .in = in, .in_per_query = SLOPE_IN, .bounds_per_query = 8, .out = out,
                           .out_per_query = SLOPE_OUT, .scratch_per_item = {TAPE_TILE_RECORD * sizeof(cl_ushort)},
                           .nscratch = 1});
    free(kernel);
    free(interpreter);
    free(tapes);

    mpfr_t fp, fq, quotient;
    mpfr_inits2(EXPR_ORACLE_PREC, fp, fq, quotient, (mpfr_ptr)0);
    long listed = 0, quotients = 0, midpoints = 0;
    for (size_t k = 0; k < q; k++) {
        int x = which[k / PACKET_LANES];
        const double *v = in + SLOPE_IN * k, *o = out + SLOPE_OUT * k;
        if (o[0] == 0)
            continue; /* a full list: the walk bisects there */
        listed++;
        CHECK((o[1] == o[3] || (o[1] != o[1] && o[3] != o[3])) && (o[2] == o[4] || (o[2] != o[2] && o[4] != o[4])),
              "'%s' over x [%a, %a] y [%a, %a] z [%a, %a]: tape_lists_dt [%a, %a], tape_lists [%a, %a]", texts[x],
              v[0], v[1], v[2], v[3], v[4], v[5], o[1], o[2], o[3], o[4]);
        for (int pair = 0; pair < PAIRS; pair++) {
            double s[2], p[2][4] = {{0}};
            for (int e = 0; e < 2; e++) {
                s[e] = length[k] * round(test_rand_unit(test_rng()) * 64) / 64;
                for (int c = 0; c < 3; c++)
                    p[e][c] = from[3 * k + c] + v[8 + c] * s[e];
            }
            if (s[0] == s[1] || !expr_oracle(exprs[x], p[0], fp) || !expr_oracle(exprs[x], p[1], fq) ||
                mpfr_sgn(fp) > 0 || mpfr_sgn(fq) > 0)
                continue;
            quotients++;
            mpfr_sub(quotient, fp, fq, MPFR_RNDN);
            mpfr_div_d(quotient, quotient, s[0] - s[1], MPFR_RNDN);
            /* to a double outward: a linear part's quotient is its slope exactly, which the oracle's rounding
             * (far below a double's) may miss */
            CHECK(mpfr_get_d(quotient, MPFR_RNDU) >= o[5] && mpfr_get_d(quotient, MPFR_RNDD) <= o[6],
                  "'%s' along (%a, %a, %a) + s (%a, %a, %a), s in [0, %a]: slope [%a, %a], but from s = %a to %a "
                  "the union's quotient is %.17g",
                  texts[x], from[3 * k], from[3 * k + 1], from[3 * k + 2], v[8], v[9], v[10], length[k], o[5], o[6],
                  s[1], s[0], mpfr_get_d(quotient, MPFR_RNDN));
        }
        double m[4] = {v[11], v[12], v[13], 0};
        if (expr_oracle(exprs[x], m, fp) && mpfr_sgn(fp) <= 0) {
            midpoints++;
            CHECK(mpfr_cmp_d(fp, o[7]) >= 0 && mpfr_cmp_d(fp, o[8]) <= 0,
                  "'%s' at the midpoint (%a, %a, %a): [%a, %a], but the value is %.17g", texts[x], m[0], m[1], m[2],
                  o[7], o[8], mpfr_get_d(fp, MPFR_RNDN));
        }
    }
    mpfr_clears(fp, fq, quotient, (mpfr_ptr)0);
    for (int i = 0; i < UNIONS; i++)
        iacsg_expr_destroy(exprs[i]);
    free(which);
    free(in);
    free(out);
    free(from);
    free(length);
    test_note("%d unions, %zu segments: %ld listed, %ld quotients and %ld midpoint values checked, %ld squares "
              "folded into their operand's instruction",
              UNIONS, q, listed, quotients, midpoints, squared);
    CHECK(listed > 1000 && quotients > 1000 && midpoints > 200 && squared > 0, "too little checked to mean anything");
}
