/* tests/fuzz/fuzz_expr.c -- libFuzzer target for the lexer, parser and compiler, scenes with regions, surfaces
 * and materials included (`make fuzz`). A crash, a sanitizer report, an error without a message, or a scene that
 * breaks its invariants aborts; save the input into tests/data/fuzz/ and the regression test
 * (tests/t_fuzz_regressions.c) replays it in every `make test`. */
#include "../expr_exercise.h"
#include <stdint.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (expr_exercise((const char *)data, size) < 0)
        abort();
    return 0;
}
