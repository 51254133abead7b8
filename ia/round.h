/* ia/round.h -- outward widening of round-to-nearest results, and the error table it relies on.
 *
 * OpenCL C has no directed rounding, so every bound is computed in round-to-nearest and then moved outward by
 * the documented error of the operation that produced it:
 *
 *   ia_lo_k(r, k) = min(r - (|r| * (k+1) * EPS + (k+1) * TINY), MAX)   for k >= 1    (ia_hi_k symmetric)
 *   ia_lo(r)      = min(r - (|r| * 0.625 * EPS + TINY), MAX)              for k = 0
 *
 * Why this is enough. For a result r of an operation whose error is at most k ulps of the exact value y,
 * |r - y| <= k * ulp(y) <= (k+1) * |r| * EPS once |r| is normal (ulp(y) can exceed ulp(r) only by the factor 2
 * across a binade boundary, which the extra 1 absorbs), and <= k * TRUE_MIN below that. The subtraction
 * r - d is itself rounded to nearest, which is monotone: since d is at least one ulp of r, the rounded
 * difference cannot land above the exact lower bound.
 *
 * k = 0 (correctly rounded: + - * and, when the device says so, / and sqrt) needs one step: the neighbour of
 * r = RN(y) on the outer side is never inside y, so it is enough that the rounded r - d lands at or beyond it,
 * i.e. d > half the gap to it. d = |r| * 0.625 * EPS + TINY is 0.625 m ulps of r (r = m * 2^e, 1 <= m < 2)
 * plus TINY; when the product is subnormal it is off by at most TINY/2, which the added TINY more than repays,
 * so d > ulp(r)/2 always. It is also small enough to stop at the neighbour: 0.625 m ulps is less than 1.5 ulps
 * (or 1.5 half-size ulps below a power of two), so + - * land one ulp outside the correctly rounded outward
 * bound, two within 2^(p+3) smallest subnormals of 0 (p = 24 or 53), where TINY is no longer negligible.
 *
 * TINY is the smallest subnormal, or the smallest normal number when IA_FTZ says the device flushes
 * subnormals to zero (then a bound that would be subnormal is pushed to the nearest normal one instead, and
 * below 2^(p+2) TINY the widening's r + TINY may round a step further out: a tie where TINY is half an ulp).
 * The final min/max with MAX turns the NaN of "+inf - inf" into the largest finite number: a lower bound
 * of +inf only arises from an overflowed finite result, whose exact value is at least MAX.
 * Callers never pass NaN: each operation resolves 0 * inf and inf - inf before widening.
 */
#ifndef IA_ROUND_H
#define IA_ROUND_H
#include "compat.h"

#ifdef IA_FTZ
#define IA_TINY IA_REAL_MIN_NORMAL
#else
#define IA_TINY IA_REAL_TRUE_MIN
#endif

/* Error bounds in ulps, per operation. Device: the OpenCL C 1.2 specification, section 7.4 (full profile).
 * Host: glibc's libm on x86-64, whose documented maxima are 1-2 ulps; tests/t_ia_libm_fp.c measures the real
 * maximum against MPFR (float and double, the figures below are from 20x its default run) and fails if an
 * error ever exceeds the bound used here; tests/t_ia_device_fp.c does the same for the device's table.
 * An error "of k ulps" is |computed - exact| <= k * ulp(exact); k = 0 means correctly rounded. */
#if IA_DEVICE
#ifdef IA_FP64
#define IA_ULP_DIV 0
#define IA_ULP_SQRT 0
#else
#ifdef IA_CR_DIVSQRT /* built with -cl-fp32-correctly-rounded-divide-sqrt */
#define IA_ULP_DIV 0
#define IA_ULP_SQRT 0
#else
#define IA_ULP_DIV 3 /* 2.5 in the spec */
#define IA_ULP_SQRT 3
#endif
#endif
#define IA_ULP_EXP 3
#define IA_ULP_LOG 3
#define IA_ULP_SINCOS 4
#define IA_ULP_TAN 5
#define IA_ULP_ATAN 5
#define IA_ULP_POW 16
#else
#define IA_ULP_DIV 0
#define IA_ULP_SQRT 0
#define IA_ULP_EXP 1 /* measured maxima (glibc 2.36, x86-64), float / double: 0.50 / 0.51 */
#define IA_ULP_LOG 1    /* 0.76 / 0.51 */
#define IA_ULP_SINCOS 1 /* 0.56 / 0.56 */
#define IA_ULP_TAN 2    /* 1.27 / 0.68 */
#define IA_ULP_ATAN 1   /* 0.83 / 0.51 */
#define IA_ULP_POW 1    /* 0.50 / 0.51 */
#endif

#ifdef IA_FAST
#define ia_lo_k(r, k) (r)
#define ia_hi_k(r, k) (r)
#else
/* The widening for an error of k ulps moves r by |r| * C + T: C = 0.625 EPS and T = TINY for k = 0, C = (k+1) EPS
 * and T = (k+1) TINY for k >= 1, as above. It is computed as fma(|r|, -C, r - T): r - T first, which is exact
 * or rounds to r (T is below half an ulp of r once r is normal, and differences of subnormals are exact; with
 * IA_FTZ it may round further out, see TINY above, which only widens), then
 * the exact product |r| * C taken off with one rounding, which is monotone. The argument above holds for this
 * form as it is (its pad is this one up to the rounding of the product, far inside its margins), and it is one
 * fused operation where a multiply, an add and a subtract were. The widening was half the render kernel's time
 * (IA_FAST renders the reference view with the same evaluations at 0.53x its CPU); this form took the kernel
 * from ~5300 to ~4600 CPU samples. fma is correctly rounded in OpenCL C and in C11 alike. */
#define IA_PAD_C(k) ((k) == 0 ? IA_R(0.625) * IA_REAL_EPS : (ia_real)((k) + 1) * IA_REAL_EPS)
#define IA_PAD_T(k) ((k) == 0 ? IA_TINY : (ia_real)((k) + 1) * IA_TINY)
/* min(x, MAX) and max(x, -MAX) that also map NaN to the finite end (as fmin and fmax do, but inline on the
 * host, where glibc's fmin is a call). */
IA_FN ia_real ia__below_max(ia_real x) { return x <= IA_REAL_MAX ? x : IA_REAL_MAX; }
IA_FN ia_real ia__above_min(ia_real x) { return x >= -IA_REAL_MAX ? x : -IA_REAL_MAX; }
#define ia_lo_k(r, k) ia__below_max(fma(fabs(r), -IA_PAD_C(k), (r) - IA_PAD_T(k)))
#define ia_hi_k(r, k) ia__above_min(fma(fabs(r), IA_PAD_C(k), (r) + IA_PAD_T(k)))
#endif

/* One ulp outward: for correctly rounded results (+, -, * and the rounded steps inside other operations). */
IA_FN ia_real ia_lo(ia_real r) { return ia_lo_k(r, 0); }
IA_FN ia_real ia_hi(ia_real r) { return ia_hi_k(r, 0); }

#endif
