/* implicits/eval_f64.c -- the host evaluator in double intervals (see eval.h, eval_body.h). */
#define IA_FP64
#define EVAL_SUFFIX f64
#include "eval_body.h"

/* Shared by both precisions: a double interval is the larger of the two; a flag byte per node after them. */
size_t eval_scratch_size(int max_index) { return ((size_t)max_index + 1) * (sizeof(ia_interval) + 1); }
