/* tests/expr_exercise.h -- runs one input text through every stage of the compiler that needs no device:
 * parse, emit OpenCL C, bounds, host evaluation in float and double. Shared by the libFuzzer target
 * (tests/fuzz/fuzz_expr.c) and the regression test that replays every input in tests/data/fuzz/. */
#ifndef IACSG_EXPR_EXERCISE_H
#define IACSG_EXPR_EXERCISE_H
#include <stddef.h>

/* Returns 1 if the text compiled, 0 if it was rejected with an error that has a message (the only other
 * outcome is a crash, which is what the callers look for). -1 if a rejection came without a message. */
int expr_exercise(const char *data, size_t size);

#endif
