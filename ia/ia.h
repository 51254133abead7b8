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
 *   is enough). With IA_FTZ the same holds on a device (or an x86 host in FTZ+DAZ mode) that flushes
 *   subnormals to zero, provided no input bound (and no real operand) is subnormal; results then have no
 *   subnormal bound either, so a chain of operations keeps the precondition. The renderer's kernels are built
 *   so (src/clrt.c); what the host hands them as bounds goes through ia/flush.h.
 *
 *   Tightness. Each bound is within a few steps (format numbers) of the exact range rounded outward:
 *   0 for neg, abs, min, max, hull, intersect; 1 for + - * sqr, add_r, mul_r, width and correctly rounded
 *   / and sqrt (2 within 2^(p+3) subnormal steps of 0, p = 24 or 53); 3k+3 for a function with a k-ulp bound
 *   (k+1 from the function and its rounding, 2k+2 from the widening); pown: about 2.25 (|n|-1) + 2 up to
 *   |n| = IA_POWN_CHAIN_MAX (4 on the host, 1024 on the device), that of pow above it, doubled for n < 0;
 *   float pown beyond IA_POWN_FORMAT_MAX = 8 (ia/arith.h), sin and cos on a device with double compute in
 *   double and round once: about 1 step (IA_DEVICE_DOUBLE, ia/compat.h). sin and cos return +-1 exactly when the
 *   interval may contain an extremum, and find out whether it does from the derivative's signs when the
 *   interval is shorter than 2 pi (so huge arguments stay tight); sqr and even pown of an interval holding 0
 *   start at exactly 0. Nothing returns [-inf, +inf] unless the true range is unbounded on both sides.
 *   With IA_FTZ the steps are counted on its grid (the normal numbers and 0), and each rounding or widening
 *   may also add its TINY, the smallest normal number (tests/t_ia_tight_fp.c, ftz_within).
 *   tests/t_ia_tight_fp.c checks all of this against MPFR, on the host and on the device.
 *
 *   Values. Empty is [+inf, -inf]; every operation maps empty inputs to empty (for hull, empty is the
 *   identity). Infinite bounds mean "unbounded". Reals passed to an operation (add_r, mul_r, contains) are
 *   finite. No operation makes a NaN bound from non-NaN inputs (ia_mid of empty is NaN by definition).
 *
 *   Undefined operands (what an expression means where a part of it is undefined: sqrt(x) for x < 0, log(0),
 *   1/0, tan at its poles, pow off its domain). ONE rule, the same in the host evaluator (implicits/eval_body.h),
 *   the interval code F, the vector code Fv (ia/vec.h) and its union groups, and the point code f, f_grad:
 *     - every operation with an undefined operand is undefined (NaN in the point code), except the union:
 *     - min(a, b) is b where a is undefined and a where b is (undefined counts as outside, +inf, in a union),
 *       undefined where both are; max(a, b) is undefined where either is (outside: an intersection with
 *       nothing is nothing);
 *     - where the whole expression is undefined, the point is outside the solid: the solid is where the
 *       expression is defined and < 0, and its boundary is the surface f = 0 and the edge of the domain where
 *       the defined side is inside.
 *   As intervals: an enclosure holds the values at the points of the box where the expression is defined (the
 *   set-based rule above), and the emitted code carries beside each interval that can be undefined a flag,
 *   "may be undefined somewhere on the box", made by the `undefined` column of implicits/ops.def (the vector
 *   code a second one, "undefined on all of it": ia/vec.h). A union with a flagged operand is ia_union, which
 *   takes that operand as [lo, +inf] (ia_or_outside), and so is the value of the whole expression read. (C's
 *   fmin already drops a NaN; the point max is ia_real_max.) Interval Newton needs F defined and continuous on
 *   the whole node, so the derivative code reports an unbounded derivative wherever a flag is raised
 *   (kernels/packet.h).
 *
 *   Fast mode (IA_FAST) drops the widening: the Hijazi seed's arithmetic, for measuring the cost of rigor.
 *
 * Files: compat.h (host/device differences), round.h (widening, error table), interval.h (type, exact ops, the
 * union under the rule for undefined operands), arith.h (+ - * / recip sqr pown sqrt), elem.h (exp log sin cos sin_cos
 * tan atan pow). Host only: decimal.h. Device only: vec.h, the operations over IA_VW lanes (for lanes with
 * nonempty operands, bit-identical to these).
 */
#ifndef IA_IA_H
#define IA_IA_H
#include "elem.h"
#endif
