/* ia/round.h -- outward widening of round-to-nearest results, and the error table it relies on.
 *
 * OpenCL C has no directed rounding, so every bound is computed in round-to-nearest and then moved outward by
 * the documented error of the operation that produced it:
 *
 *   ia_lo_k(r, k) = min(r - (|r| * (k+1) * EPS + (k+1) * TINY), MAX)      (ia_hi_k symmetric)
 *
 * Why this is enough. For a result r of an operation whose error is at most k ulps of the exact value y,
 * |r - y| <= k * ulp(y) <= (k+1) * |r| * EPS once |r| is normal (ulp(y) can exceed ulp(r) only by the factor 2
 * across a binade boundary, which the extra 1 absorbs), and <= k * TRUE_MIN below that. The subtraction
 * r - d is itself rounded to nearest, which is monotone: since d is at least one ulp of r, the rounded
 * difference cannot land above the exact lower bound. Correctly rounded operations (+ - * and, when the
 * device says so, / and sqrt) use k = 0, widening by one ulp of the result.
 *
 * TINY is the smallest subnormal, or the smallest normal number when IA_FTZ says the device flushes
 * subnormals to zero (then a bound that would be subnormal is pushed to the nearest normal one instead).
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
 * Host: glibc's libm on x86-64, whose documented maxima are 1-2 ulps; tests/t_ia_props.c measures the real
 * maximum against MPFR and fails if a result ever exceeds the bound used here. */
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
#define IA_ULP_EXP 2
#define IA_ULP_LOG 2
#define IA_ULP_SINCOS 2
#define IA_ULP_TAN 2
#define IA_ULP_ATAN 2
#define IA_ULP_POW 2
#endif

#ifdef IA_FAST
#define ia_lo_k(r, k) (r)
#define ia_hi_k(r, k) (r)
#else
/* The widening amount for an error of k ulps. */
#define IA_PAD(r, k) (fabs(r) * ((ia_real)((k) + 1) * IA_REAL_EPS) + (ia_real)((k) + 1) * IA_TINY)
#define ia_lo_k(r, k) fmin((r) - IA_PAD(r, k), IA_REAL_MAX)
#define ia_hi_k(r, k) fmax((r) + IA_PAD(r, k), -IA_REAL_MAX)
#endif

/* One ulp outward: for correctly rounded results (+, -, * and the rounded steps inside other operations). */
IA_FN ia_real ia_lo(ia_real r) { return ia_lo_k(r, 0); }
IA_FN ia_real ia_hi(ia_real r) { return ia_hi_k(r, 0); }

#endif
