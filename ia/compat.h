/* ia/compat.h -- the only place where host C11 and OpenCL C differ for ia/.
 *
 * Selects the real type (float, or double with IA_FP64), the function qualifier, the math built-ins and the
 * constants the rounding code needs. Everything after this header is written in the common subset of C11 and
 * OpenCL C 1.2: no pointers, no library calls other than the overloaded math built-ins, values passed by value.
 *
 * Build flags (the same names on host and device):
 *   IA_FP64  intervals of double instead of float.
 *   IA_FAST  no outward widening (the unrigorous mode of the Hijazi seed), to measure what rigor costs.
 *   IA_FTZ   the device flushes subnormals to zero: widen by at least the smallest normal number.
 *   IA_HOST_ULPS / device: which error table applies is chosen here, see ia/round.h.
 */
#ifndef IA_COMPAT_H
#define IA_COMPAT_H

#ifdef __OPENCL_C_VERSION__
/* ---------------------------------------------------------------- OpenCL C */
#define IA_DEVICE 1
#pragma OPENCL FP_CONTRACT OFF
#ifdef IA_FP64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#elif defined(cl_khr_fp64)
/* float intervals on a device that has double: some functions compute in double and round outward to float
 * (ia/arith.h's pown, ia/elem.h's sin and cos) */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define IA_DEVICE_DOUBLE 1
#endif
#define IA_FN static inline
#define IA_BOOL int

#else
/* ---------------------------------------------------------------- host C11 */
#define IA_DEVICE 0
#include <float.h>
#include <math.h>
#include <tgmath.h> /* type-generic sqrt, exp, ... like OpenCL's overloaded built-ins */
#define IA_FN static inline
#define IA_BOOL int
/* The widening arguments assume every float operation is rounded once to its own format, to nearest. */
_Static_assert(FLT_EVAL_METHOD == 0, "ia/ needs FLT_EVAL_METHOD == 0 (SSE2 or similar, no x87 excess precision)");
#ifdef __GNUC__
/* GCC only honours -ffp-contract; ISO C mode (-std=c11) turns contraction off. Clang honours the pragma. */
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif
#endif
#endif

#ifdef IA_FP64
typedef double ia_real;
#define IA_REAL_MAX DBL_MAX
#define IA_REAL_EPS 0x1p-52       /* ulp(1) */
#define IA_REAL_TRUE_MIN 0x1p-1074 /* smallest subnormal */
#define IA_REAL_MIN_NORMAL DBL_MIN
#define IA_R(c) (c)
#else
typedef float ia_real;
#define IA_REAL_MAX FLT_MAX
#define IA_REAL_EPS 0x1p-23f
#define IA_REAL_TRUE_MIN 0x1p-149f
#define IA_REAL_MIN_NORMAL FLT_MIN
#define IA_R(c) (c##f)
#endif

#define IA_INF ((ia_real)INFINITY)

#endif
