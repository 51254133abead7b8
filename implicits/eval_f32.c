/* implicits/eval_f32.c -- the host evaluator in float intervals (see eval.h, eval_body.h). */
#define EVAL_SUFFIX f32
#include "eval_body.h"
