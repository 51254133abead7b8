/* ia/ia.h -- rigorous interval arithmetic, one source for host C11 and OpenCL C.
 *
 * THE CONTRACT (it holds for every operation in ia/, and every test in tests/t_ia_*.c checks it):
 *
 *   Inclusion. For intervals A, B and an operation op, ia_op(A, B) contains op(x, y) for every x in A and y in B
 *   at which op is defined (IEEE 1788 set-based semantics, restricted to single intervals: where the true range
 *   is two pieces, as 1/[-1,1], the result is their hull). Points where op is undefined are ignored; if no
 *   point is in the domain the result is empty.
 *
 *   Rounding assumptions. Every float operation is rounded to nearest, once, in its own format (host:
 *   FLT_EVAL_METHOD == 0 and no contraction into FMA, enforced in ia/compat.h; device: OpenCL C with
 *   FP_CONTRACT OFF and never -cl-fast-relaxed-math, -cl-unsafe-math-optimizations or -cl-mad-enable).
 *   + - * are correctly rounded; /, sqrt and the elementary functions are within the ulp bounds of
 *   ia/round.h (the OpenCL C specification's table on the device, measured glibc bounds on the host). Each
 *   bound computed in round-to-nearest is then moved outward past that error (ia/round.h explains why that
 *   is enough). With IA_FTZ the same holds on a device that flushes subnormals to zero.
 *
 *   Tightness. Monotone operations return bounds within a few ulps of the exact range (one ulp for + - *,
 *   k+1 for a function with a k-ulp bound). sin and cos return +-1 exactly when the interval may contain an
 *   extremum; sqr and even pown of an interval straddling 0 start at exactly 0. Nothing returns
 *   [-inf, +inf] unless the true range is unbounded on both sides.
 *
 *   Values. Empty is [+inf, -inf]; every operation maps empty inputs to empty. Infinite bounds mean
 *   "unbounded". No operation makes a NaN bound from non-NaN inputs (ia_mid of empty is NaN by definition).
 *
 *   Fast mode (IA_FAST) drops the widening: the Hijazi seed's arithmetic, for measuring the cost of rigor.
 *
 * Files: compat.h (host/device differences), round.h (widening, error table), interval.h (type, exact ops),
 * arith.h (+ - * / recip sqr pown sqrt), elem.h (exp log sin cos tan atan pow). Host only: decimal.h.
 */
#ifndef IA_IA_H
#define IA_IA_H
#include "elem.h"
#endif
