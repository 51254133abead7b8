/* tests/brlcad_exercise.h -- runs one input through the BRL-CAD reader (implicits/brlcad.h): read, list the top
 * objects, build the regions of all of them, check the scene's shape. Shared by the libFuzzer target
 * (tests/fuzz/fuzz_brlcad.c) and the regression test that replays tests/data/fuzz-brlcad/ and the samples. */
#ifndef IACSG_BRLCAD_EXERCISE_H
#define IACSG_BRLCAD_EXERCISE_H
#include <stddef.h>

/* 1 if the input made a scene, 0 if it was refused with a message; -1 if a refusal came without a message or
 * the scene breaks its invariants (a tree's operand or solid out of range, a primitive's parameters of the
 * wrong count, a region without its id, rt's model box not a box). The input is copied and NUL-terminated
 * inside. */
int brlcad_exercise(const char *data, size_t size);

#endif
