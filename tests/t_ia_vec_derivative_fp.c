/* tests/t_ia_vec_derivative_fp.c -- the two operations of ia/vec.h that only the derivative code along a ray uses
 * (implicits/emit.c: vector_tderiv), on the device over SIMD lanes, float and double:
 *   ia_vec_mul_pv: iav_mul_pv(a, p) is iav_mul(a, [p, p]) (tested against ia/ and MPFR by t_ia_vec_device_fp.c)
 *     in every lane where a is nonempty: the same bounds, for every pair of special bounds (zeros of both signs,
 *     the smallest normal, small and large values, the largest finite, infinities) and every special p, then
 *     random ones.
 *   ia_vec_twice: iav_twice(a) is [2 a.lo, 2 a.hi] exactly where that is finite, and where it overflows rounds
 *     towards the finite range (lower bound REAL_MAX above it, -inf below; upper bound -REAL_MAX, +inf), so it
 *     always contains 2a.
 */
#include "ia/ia.h"
#include "t_lanes_run.h"

extern const char iacsg_cl_ia[];

static const char kernel[] =
    "__kernel void vec_derivative(__global const int *which, __global const ia_real *in, __global ia_real *out) {\n"
    "    size_t g = get_global_id(0);\n"
    "    ia_real v[3][IA_VW], o[4][IA_VW];\n"
    "    for (int l = 0; l < IA_VW; l++)\n"
    "        for (int k = 0; k < 3; k++)\n"
    "            v[k][l] = in[3 * (g * IA_VW + l) + k];\n"
    "    iav a = iav_make(IAV_LOAD(v[0]), IAV_LOAD(v[1]));\n"
    "    ia_realv p = IAV_LOAD(v[2]);\n"
    "    iav r = which[g] == 0 ? iav_mul_pv(a, p) : iav_twice(a);\n"
    "    iav s = which[g] == 0 ? iav_mul(a, iav_make(p, p)) : a; /* a itself: the exact values to check */\n"
    "    IAV_STORE(r.lo, o[0]);\n"
    "    IAV_STORE(r.hi, o[1]);\n"
    "    IAV_STORE(s.lo, o[2]);\n"
    "    IAV_STORE(s.hi, o[3]);\n"
    "    for (int l = 0; l < IA_VW; l++)\n"
    "        for (int k = 0; k < 4; k++)\n"
    "            out[4 * (g * IA_VW + l) + k] = o[k][l];\n"
    "}\n";

#define SPECIALS 13
static const double specials[SPECIALS] = {0.0, -0.0, 1.0, -1.0, 1.5, -3.25, 0.1, IA_REAL_MIN_NORMAL, IA_REAL_MAX / 2,
                                          IA_REAL_MAX, -IA_REAL_MAX, INFINITY, -INFINITY};

/* Runs `count` queries (a.lo, a.hi, p) of one operation (which: 0 mul_pv, 1 twice); out: 4 a query. */
static void run(int which, const double *in, size_t count, double *out) {
    size_t items = count / PACKET_LANES;
    int *w = malloc(items * sizeof *w);
    CHECK(w, "out of memory");
    for (size_t g = 0; g < items; g++)
        w[g] = which;
    const char *sources[] = {iacsg_cl_ia, kernel};
    lanes_run(&(lanes_job){.sources = sources, .nsources = 2, .kernel = "vec_derivative", .items = items, .which = w,
                           .in = in, .in_per_query = 3, .bounds_per_query = 0, .out = out, .out_per_query = 4});
    free(w);
}

/* The cases: every pair of specials as bounds with every special p, then random ones, padded to whole packets;
 * reals of the working precision, so that the device gets them as they are. */
static double *cases(size_t *count) {
    size_t n = SPECIALS * SPECIALS * SPECIALS + 4096;
    n = (n + PACKET_LANES - 1) / PACKET_LANES * PACKET_LANES;
    double *in = malloc(3 * n * sizeof *in);
    CHECK(in, "out of memory");
    test_rng_t *r = test_rng();
    for (size_t k = 0; k < n; k++) {
        double *q = in + 3 * k;
        if (k < SPECIALS * SPECIALS * SPECIALS) {
            q[0] = (ia_real)specials[k % SPECIALS];
            q[1] = (ia_real)specials[k / SPECIALS % SPECIALS];
            q[2] = (ia_real)specials[k / (SPECIALS * SPECIALS)];
        } else {
            for (int c = 0; c < 3; c++)
                q[c] = (ia_real)((2 * test_rand_unit(r) - 1) * ldexp(1, (int)(test_rand_unit(r) * 40) - 20));
        }
    }
    *count = n;
    return in;
}

TEST_FP(ia_vec_mul_pv) {
    size_t n;
    double *in = cases(&n), *out = malloc(4 * n * sizeof *out);
    CHECK(out, "out of memory");
    run(0, in, n, out);
    long checked = 0;
    for (size_t k = 0; k < n; k++) {
        const double *q = in + 3 * k, *o = out + 4 * k;
        if (!(q[0] <= q[1]) || q[0] == INFINITY || q[1] == -INFINITY || isinf(q[2]))
            continue; /* empty, or not a real direction */
        checked++;
        CHECK(o[0] == o[2] && o[1] == o[3] && !isnan(o[0]) && !isnan(o[1]),
              "[%a, %a] * %a: iav_mul_pv gave [%a, %a], iav_mul [%a, %a]", q[0], q[1], q[2], o[0], o[1], o[2], o[3]);
    }
    test_note("%zu cases, %ld with a nonempty interval and a finite point checked", n, checked);
    free(in);
    free(out);
}

TEST_FP(ia_vec_twice) {
    size_t n;
    double *in = cases(&n), *out = malloc(4 * n * sizeof *out);
    CHECK(out, "out of memory");
    run(1, in, n, out);
    long checked = 0, overflows = 0;
    for (size_t k = 0; k < n; k++) {
        const double *o = out + 4 * k, *a = o + 2; /* the device's a, as it holds it */
        if (!(a[0] <= a[1]) || a[0] == INFINITY || a[1] == -INFINITY)
            continue;
        checked++;
        for (int e = 0; e < 2; e++) { /* end e of a: its double 2x is exact in double where it is finite */
            double x = a[e], got = o[e], want = x;
            if (fabs(x) <= IA_REAL_MAX / 2)
                want = 2 * x;
            else if (isfinite(x)) /* 2x overflows: towards the finite range, outward beyond it */
                want = e == 0 ? (x > 0 ? IA_REAL_MAX : -INFINITY) : (x < 0 ? -IA_REAL_MAX : INFINITY), overflows++;
            CHECK(got == want && (want != 0 || signbit(got) == signbit(x)),
                  "iav_twice([%a, %a]): bound %d is %a, not %a", a[0], a[1], e, got, want);
        }
    }
    test_note("%zu cases, %ld nonempty intervals checked, %ld bounds overflowing", n, checked, overflows);
    CHECK(overflows > 0, "no bound overflowed: the cases miss the edge");
    free(in);
    free(out);
}
