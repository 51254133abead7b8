/* ia/flush.h -- host only: interval bounds as a device that flushes subnormals reads them.
 *
 * ia/ runs on the device with subnormals flushed to zero (-cl-denorms-are-zero and IA_FTZ, src/clrt.c: on x86
 * CPUs each subnormal operand or result costs a microcode assist, and the exp of a sigmoid blend made its render
 * 15x slower). Its operations keep the inclusion property there provided no input bound is subnormal, and make
 * none themselves (ia/ia.h). So every bound the host computes for the device (an expression's constant, a
 * reciprocal, a primitive's parameter, a query's box) goes through these first: a subnormal lower bound moves
 * down to 0 or minus the smallest normal number, an upper bound up to 0 or the smallest normal number. Other
 * bounds are returned as they are. */
#ifndef IA_FLUSH_H
#define IA_FLUSH_H
#include <float.h>
#include <math.h>

static inline float ia_flush_lo_f(float lo) { return lo != 0 && fabsf(lo) < FLT_MIN ? (lo > 0 ? 0.0f : -FLT_MIN) : lo; }
static inline float ia_flush_hi_f(float hi) { return hi != 0 && fabsf(hi) < FLT_MIN ? (hi < 0 ? 0.0f : FLT_MIN) : hi; }
static inline double ia_flush_lo_d(double lo) { return lo != 0 && fabs(lo) < DBL_MIN ? (lo > 0 ? 0.0 : -DBL_MIN) : lo; }
static inline double ia_flush_hi_d(double hi) { return hi != 0 && fabs(hi) < DBL_MIN ? (hi < 0 ? 0.0 : DBL_MIN) : hi; }

#endif
