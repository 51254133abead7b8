/* tests/expr_exercise.h -- runs one input text through every stage of the compiler that needs no device:
 * parse (as a scene, so regions, surfaces and materials too), emit OpenCL C, bounds, host evaluation in float and
 * double of the final expression or of every solid, and the shape of every region's and surface's tree. Shared
 * by the libFuzzer target (tests/fuzz/fuzz_expr.c) and the regression test that replays every input in
 * tests/data/fuzz/. */
#ifndef IACSG_EXPR_EXERCISE_H
#define IACSG_EXPR_EXERCISE_H
#include <stddef.h>

/* Returns 1 if the text compiled, 0 if it was rejected with an error that has a message (the only other
 * outcome is a crash, which is what the callers look for). -1 if a rejection came without a message, or the
 * scene it made breaks its own invariants (a tree's operand out of range, an item's solid or material unknown). */
int expr_exercise(const char *data, size_t size);

#endif
