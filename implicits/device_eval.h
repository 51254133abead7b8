/* implicits/device_eval.h -- evaluation of compiled expressions on an OpenCL device, with the emitted code:
 * `iacsg eval --device` and the device tests. */
#ifndef IACSG_DEVICE_EVAL_H
#define IACSG_DEVICE_EVAL_H
#include "clrt.h"
#include "expr.h"

/* One program for nexprs expressions, then n queries: query i evaluates expression which[i] with
 * in[8i .. 8i+7] = x0, x1, y0, y1, z0, z1, t0, t1 (exact doubles; rounded outward to floats without fp64, and
 * out of the subnormals, ia/flush.h) and writes out[6i .. 6i+5] = the enclosure lo, hi of F over that box, f and
 * its gradient gx, gy, gz at the corner (x0, y0, z0, t0) as the device holds it (rounded down to float without
 * fp64). */
#define DEVICE_EVAL_IN 8
#define DEVICE_EVAL_OUT 6
iacsg_status device_eval(clrt *rt, const iacsg_expr *const *exprs, int nexprs, int fp64, size_t n,
                         const int *which, const double *in, double *out, iacsg_error *err);

#endif
